"""The layers of DESIGN §3 as imports: each folder of shroudnet imports only the folders
below it, and no module imports itself round a circle.

Imports are read from the source, every one of them: at the top, inside functions (the
lazy ones) and under ``TYPE_CHECKING``, because each is a dependency all the same.
"""

import ast
from pathlib import Path

import pytest

PACKAGE = Path(__file__).resolve().parents[1] / "shroudnet"

_COMPUTATION = ("checked_records", "machine", "model", "engine", "run", "linear", "analysis",
                "steady", "studies")
#: What each part of the package may import (besides itself): its layer and the layers
#: below it, by the first part of a module's dotted name ("" is the package itself).
ALLOWED = {
    "checked_records": set(),
    "atomic": set(),
    "machine": set(),
    "model": {"checked_records", "machine"},
    "engine": {"checked_records", "atomic", "model"},
    "run": {"checked_records", "machine", "model", "engine"},
    "linear": {"checked_records", "model", "engine"},
    "analysis": {"checked_records", "model", "engine", "run"},
    "steady": {"checked_records", "model", "engine", "run", "linear", "analysis"},
    "studies": {"checked_records", "model", "scenes", "engine", "run", "linear", "analysis",
                "steady"},
    "io": {*_COMPUTATION, "atomic"},
    "scenes": {"checked_records", "model"},
    # The independent references share no code with the engine: its enums at most.
    "references": {"model", "engine.codes"},
    "front": {*_COMPUTATION, "atomic", "io", "scenes", "references"},
    "results": {"io"},
    "scenefile": {"io"},
    "__main__": {"front"},
    "": {*_COMPUTATION, "io", "scenes", "front"},
}
#: The layers that compute: none of them prints, touches a file or draws but through what
#: its caller hands it (the engine's compiled-kernel cache and its first-compile notice
#: aside, in ``engine.cache`` and ``engine.generate``).
COMPUTATION = ("model", "run", "linear", "analysis", "steady", "studies")


def part(module: str) -> str:
    """The part of the package ``module`` belongs to: its folder, or itself at the top."""
    return module.split(".")[0]


def allowed(importer: str, imported: str) -> bool:
    """Whether ``importer`` may import ``imported`` by ``ALLOWED``."""
    if part(importer) == part(imported):
        return True
    rule = ALLOWED[part(importer)]
    return part(imported) in rule or any(imported == r or imported.startswith(r + ".")
                                         for r in rule)


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


def imports_of(name: str, path: Path, modules: dict[str, Path],
               tree: ast.AST | None = None) -> set[str]:
    """The modules of the package that the module ``name`` (source at ``path``) imports
    anywhere in its source, or in the part ``tree`` of it, by their names in
    ``module_names``."""
    package = name if path.name == "__init__.py" else name.rpartition(".")[0]
    found = set()
    if tree is None:
        tree = ast.parse(path.read_text(), filename=str(path))
    for node in ast.walk(tree):
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
    assert {"run.simulation", "run.simulate", "analysis.readings", "studies.sweep"} <= set(graph)
    assert cycles(graph) == []


def test_every_part_of_the_package_has_a_rule():
    assert {part(module) for module in import_graph()} == set(ALLOWED)


@pytest.mark.parametrize("folder", sorted(ALLOWED))
def test_each_folder_imports_only_the_layers_below_it(folder):
    """Directly, and so through any chain of imports: a run record is read, saved and
    loaded without any study; a study never reaches files or the terminal."""
    graph = import_graph()
    wrong = {(module, imported) for module, imports in graph.items() if part(module) == folder
             for imported in imports if not allowed(module, imported)}
    assert wrong == set()


def test_the_rules_find_an_import_up_a_layer():
    assert not allowed("run.simulate", "steady.orbits")
    assert not allowed("studies.sweep", "io.results")
    assert not allowed("studies.sweep", "front.progress")
    assert not allowed("references.blades", "engine.dynamics")
    assert allowed("references.blades", "engine.codes")
    assert allowed("steady.orbits", "run.simulate")


@pytest.mark.parametrize("folder", COMPUTATION)
def test_computation_neither_prints_nor_opens_files(folder):
    """No ``print``, ``open``, ``sys.stdout``/``sys.stderr`` or matplotlib in the layers that
    compute: what a computation shows or keeps goes through what its caller hands it."""
    found = []
    for path in sorted((PACKAGE / folder).rglob("*.py")):
        for node in ast.walk(ast.parse(path.read_text())):
            if isinstance(node, ast.Call) and isinstance(node.func, ast.Name) \
                    and node.func.id in ("print", "open"):
                found.append(f"{path.name}:{node.lineno} {node.func.id}()")
            elif isinstance(node, ast.Attribute) and node.attr in ("stdout", "stderr") \
                    and isinstance(node.value, ast.Name) and node.value.id == "sys":
                found.append(f"{path.name}:{node.lineno} sys.{node.attr}")
            elif isinstance(node, ast.Import | ast.ImportFrom):
                names = [node.module or ""] if isinstance(node, ast.ImportFrom) \
                    else [a.name for a in node.names]
                found += [f"{path.name}:{node.lineno} {n}" for n in names
                          if n.split(".")[0] == "matplotlib"]
    assert found == []


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
