"""The layers of DESIGN §3 as imports: no module of shroudnet imports itself round a circle,
and a run (what ``simulate`` returns, and the records of a sweep) knows no study.

Imports are read from the source, every one of them: at the top, inside functions (the
lazy ones) and under ``TYPE_CHECKING``, because each is a dependency all the same.
"""

import ast
from pathlib import Path

import pytest

PACKAGE = Path(__file__).resolve().parents[1] / "shroudnet"

#: The run layer: what integrates a scene and the records runs return.
RUN = ("simulate", "simulation", "methods", "baseline", "classification", "extremes")
#: The studies and steady states, which run simulations and read them.
STUDIES = ("analysis", "stability", "sweep", "precision", "mistuning", "linear",
           "linear_response", "orbits",
           "continuation")


def module_names(package: Path = PACKAGE) -> dict[str, Path]:
    """Every module of the package by its dotted name relative to it ("" for the package,
    "engine.codes", ...)."""
    names = {}
    for path in sorted(package.rglob("*.py")):
        parts = path.relative_to(package).with_suffix("").parts
        if parts[-1] == "__init__":
            parts = parts[:-1]
        names[".".join(parts)] = path
    return names


def imports_of(name: str, path: Path, modules: dict[str, Path]) -> set[str]:
    """The modules of the package that the module ``name`` (source at ``path``) imports
    anywhere in its source, by their names in ``module_names``."""
    package = name if path.name == "__init__.py" else name.rpartition(".")[0]
    found = set()
    for node in ast.walk(ast.parse(path.read_text(), filename=str(path))):
        if isinstance(node, ast.ImportFrom):
            if node.level:
                base = package.split(".") if package else []
                base = base[:len(base) - (node.level - 1)]
                target = ".".join(base + ([node.module] if node.module else []))
            elif node.module == "shroudnet" or (node.module or "").startswith("shroudnet."):
                target = node.module.removeprefix("shroudnet").removeprefix(".")
            else:
                continue
            # ``from . import results`` imports the module results; ``from .scene import
            # Scene`` imports the module scene.
            for alias in node.names:
                submodule = f"{target}.{alias.name}" if target else alias.name
                found.add(submodule if submodule in modules else target)
        elif isinstance(node, ast.Import):
            for alias in node.names:
                if alias.name == "shroudnet" or alias.name.startswith("shroudnet."):
                    found.add(alias.name.removeprefix("shroudnet").removeprefix("."))
    return {module for module in found if module in modules} - {name}


def import_graph() -> dict[str, set[str]]:
    """Module → the modules it imports, over the whole package."""
    modules = module_names()
    return {name: imports_of(name, path, modules) for name, path in modules.items()}


def cycles(graph: dict[str, set[str]]) -> list[list[str]]:
    """The import circles of ``graph``: its strongly connected components of more than one
    module (Tarjan's algorithm, O(modules + imports)), each sorted."""
    index: dict[str, int] = {}
    low: dict[str, int] = {}
    stack: list[str] = []
    found = []

    def visit(module):
        index[module] = low[module] = len(index)
        stack.append(module)
        for imported in sorted(graph[module]):
            if imported not in index:
                visit(imported)
                low[module] = min(low[module], low[imported])
            elif imported in stack:
                low[module] = min(low[module], index[imported])
        if low[module] == index[module]:
            component = []
            while not component or component[-1] != module:
                component.append(stack.pop())
            if len(component) > 1:
                found.append(sorted(component))

    for module in sorted(graph):
        if module not in index:
            visit(module)
    return found


def reachable(graph: dict[str, set[str]], start: str) -> set[str]:
    """The modules ``start`` imports, directly or through others."""
    seen, todo = set(), [start]
    while todo:
        for imported in graph[todo.pop()]:
            if imported not in seen:
                seen.add(imported)
                todo.append(imported)
    return seen


def test_the_graph_reads_every_kind_of_import(tmp_path):
    package = tmp_path / "pkg"
    (package / "engine").mkdir(parents=True)
    for name in ("__init__", "a", "b", "c", "d", "engine/__init__", "engine/e"):
        (package / f"{name}.py").write_text("")
    (package / "a.py").write_text(
        "from typing import TYPE_CHECKING\n"
        "from . import b\n"
        "if TYPE_CHECKING:\n    from .c import C\n"
        "def lazy():\n    from shroudnet.d import D\n")
    (package / "engine" / "e.py").write_text("from ..a import thing\nimport shroudnet.b\n")
    modules = module_names(package)
    assert imports_of("a", package / "a.py", modules) == {"b", "c", "d"}
    assert imports_of("engine.e", package / "engine" / "e.py", modules) == {"a", "b"}


def test_cycles_finds_a_circle_and_only_circles():
    assert cycles({"a": {"b"}, "b": {"c"}, "c": {"a"}, "d": {"a"}}) == [["a", "b", "c"]]
    assert cycles({"a": {"b"}, "b": set(), "c": {"a", "b"}}) == []


def test_no_module_of_shroudnet_imports_itself_round_a_circle():
    graph = import_graph()
    assert {"simulation", "simulate", "analysis", "stability", "sweep"} <= set(graph)
    assert cycles(graph) == []


@pytest.mark.parametrize("module", RUN)
def test_a_run_imports_no_study(module):
    """Not directly and not through another module: a run record is read, saved and loaded
    without any study, and the studies are free to read runs."""
    assert reachable(import_graph(), module).isdisjoint(STUDIES)


def test_importing_the_package_only_imports():
    """``shroudnet/__init__.py`` names the public API and does nothing else: no module's
    attributes are set from outside it, nothing runs (STYLE §6); its one assignment is
    ``__all__``, a list of the names it imports."""
    tree = ast.parse((PACKAGE / "__init__.py").read_text())
    docstring, *statements = tree.body
    assert isinstance(docstring, ast.Expr) and isinstance(docstring.value, ast.Constant)
    others = [s for s in statements if not isinstance(s, ast.Import | ast.ImportFrom)]
    assert len(others) <= 1
    for statement in others:
        assert isinstance(statement, ast.Assign | ast.AnnAssign)
        targets = statement.targets if isinstance(statement, ast.Assign) else [statement.target]
        assert [getattr(t, "id", None) for t in targets] == ["__all__"]
        assert isinstance(statement.value, ast.List | ast.Tuple)
        assert all(isinstance(item, ast.Constant) and isinstance(item.value, str)
                   for item in statement.value.elts)
