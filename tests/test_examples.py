"""Examples and the README's code run as they are shown."""

import re
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]


def test_readme_python_blocks_run():
    blocks = re.findall(r"```python\n(.*?)```", (ROOT / "README.md").read_text(), re.S)
    assert blocks
    for block in blocks:
        exec(compile(block, "README.md", "exec"), {})


@pytest.mark.parametrize("name", ["paper_scene", "paper_three_blade"])
def test_example_runs(name, capsys):
    namespace = {"__name__": "example"}
    exec(compile((ROOT / "examples" / f"{name}.py").read_text(), name, "exec"), namespace)
    main = namespace["main"]
    main(periods=20, skip=10) if name == "paper_three_blade" else main()
    assert capsys.readouterr().out
