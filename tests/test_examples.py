"""Examples and the README's code run as they are shown."""

import importlib.util
import re
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]


def test_readme_python_blocks_run():
    blocks = re.findall(r"```python\n(.*?)```", (ROOT / "README.md").read_text(), re.S)
    assert blocks
    for block in blocks:
        exec(compile(block, "README.md", "exec"), {})


#: Each example with arguments small enough for a test, and the figures it must save.
EXAMPLES = {
    "paper_scene": ({}, []),
    "paper_three_blade": ({"periods": 20, "skip": 10}, []),
    "fig06_11_stiffness_ratio": ({"values": 4, "transient": 20, "record": 5, "steady": 10},
                                 ["fig06_bifurcation_gamma1.png", "fig11_gamma1_8.8.png"]),
    "fig12_15_rotating_speed": ({"values": 3, "transient": 20, "record": 5, "steady": 10},
                                ["fig12_bifurcation_speed.png", "fig15_speed_5990.png"]),
    "fig16_19_excitation_amplitude": ({"values": 3, "transient": 20, "record": 5,
                                       "steady": 10},
                                      ["fig16_bifurcation_q1.png", "fig19_q1_50.png"]),
    "fig20_campbell": ({}, ["fig20_campbell.png"]),
    "work_precision": ({"transient": 10, "record": 5, "chaotic_record": 10, "repeats": 1},
                       ["work_precision.png"]),
    "fig21_23_energy_density": ({"points": 3, "transient": 20, "record": 5},
                                ["fig21_energy_density_gamma1.png",
                                 "fig22_energy_density_gap.png",
                                 "fig23_energy_density_angle.png"]),
}


@pytest.mark.parametrize("name", sorted(EXAMPLES))
def test_example_runs_and_saves_its_figures(name, capsys):
    # Imported as a module of its own name, so that its functions pickle for the sweep's
    # worker processes as they do when the script runs as __main__.
    path = ROOT / "examples" / f"{name}.py"
    spec = importlib.util.spec_from_file_location(name, path)
    example = importlib.util.module_from_spec(spec)
    sys.modules[name] = example
    spec.loader.exec_module(example)
    arguments, figures = EXAMPLES[name]
    for figure in figures:
        (ROOT / "examples" / "output" / figure).unlink(missing_ok=True)
    example.main(**arguments)
    assert capsys.readouterr().out
    for figure in figures:
        assert (ROOT / "examples" / "output" / figure).stat().st_size > 10_000
