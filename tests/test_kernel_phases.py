"""The engine's files by phase: each importable on its own, named in errors, the built-in
laws registered once, and the method deciding only what it should."""

import importlib
import inspect
import sys
from pathlib import Path

import numba
import numpy as np
import pytest

import contact_laws
from contact_laws import BUILT_IN_FRICTION, BUILT_IN_NORMAL, FrictionLaw, NormalLaw
from shroudnet.engine import generate
from shroudnet.engine.kernel import PHASES
from shroudnet.engine.records import new_work
from shroudnet.scenes import three_blade_paper

from .laws import EVERY_FRICTION_LAW, EVERY_NORMAL_LAW

ENGINE = Path(generate.__file__).parent


def test_every_phase_module_imports_on_its_own():
    for phase in PHASES:
        module = importlib.import_module(f"shroudnet.engine.kernel.{phase}")
        assert module.__doc__, phase


def test_no_engine_file_is_over_400_lines():
    long = {path.relative_to(ENGINE).as_posix(): n for path in ENGINE.rglob("*.py")
            if (n := len(path.read_text().splitlines())) > 400}
    assert not long


def _law_classes_of(module, base):
    return {value for value in vars(module).values()
            if inspect.isclass(value) and issubclass(value, base) and value is not base
            and value.__module__ == module.__name__}


def test_every_built_in_law_class_is_registered_and_tested():
    """A law class added to ``contact_laws`` but not to its registry would compile a
    kernel of its own; one missing from the tests' list would escape the law contracts."""
    normal = _law_classes_of(contact_laws.normal, NormalLaw)
    friction = _law_classes_of(contact_laws.friction, FrictionLaw) - {contact_laws.Regularised}
    assert normal == set(BUILT_IN_NORMAL) and friction == set(BUILT_IN_FRICTION)
    tested = {type(law) for law in EVERY_NORMAL_LAW + EVERY_FRICTION_LAW}
    assert set(BUILT_IN_NORMAL + BUILT_IN_FRICTION) <= tested


@pytest.mark.parametrize("law", [law for law in EVERY_NORMAL_LAW + EVERY_FRICTION_LAW
                                 if type(law) in BUILT_IN_NORMAL + BUILT_IN_FRICTION],
                         ids=lambda law: type(law).__name__)
def test_no_built_in_law_compiles_a_kernel_of_its_own(law):
    shared = generate.load_kernel(three_blade_paper())
    option = "normal" if isinstance(law, NormalLaw) else "friction"
    kernel = generate.load_kernel(three_blade_paper(**{option: law}))
    assert kernel is shared and kernel.SHARED


def test_each_method_has_its_kernel_and_shares_the_method_free_phases():
    scene = three_blade_paper()
    adaptive = generate.load_kernel(scene)
    fixed = generate.load_kernel(scene, method="fixed_step")
    assert adaptive.ADAPTIVE and not fixed.ADAPTIVE and adaptive is not fixed
    assert adaptive.switch is fixed.switch and adaptive.advance is not fixed.advance
    method_free = sys.modules[fixed.switch.py_func.__module__]
    assert not {"ADAPTIVE", "advance", "locate", "motion_inside"} & set(vars(method_free))
    with pytest.raises(ValueError, match="adaptive or exponential steps"):
        generate.load_kernel(scene, tangent=True, method="fixed_step")


def test_a_kernel_function_is_named_by_its_phase_module_and_line(monkeypatch):
    """Tracebacks and numba's errors point into the phase module, not into the generated
    header in the cache."""
    kernel = generate.load_kernel(three_blade_paper())
    function = kernel.law_forces.py_func
    path = ENGINE / "kernel" / "forces.py"
    assert Path(function.__code__.co_filename) == path
    lines = path.read_text().splitlines()
    first = function.__code__.co_firstlineno  # the decorator's line, as Python counts it
    assert lines[first - 1:first + 1] == ["@njit_step", "def law_forces(s, modes, w):"]
    phases, engine = generate.phase_sources()
    forces = PHASES.index("forces")
    planted = list(phases)
    call = "    law_forces(s, modes, w)\n"
    planted[forces] = phases[forces].replace(call, call + "    w.mistyped[0] = 0.0\n", 1)
    line = planted[forces].splitlines().index("    w.mistyped[0] = 0.0") + 1
    monkeypatch.setattr(generate, "phase_sources", lambda: (tuple(planted), engine))
    generate.forget_kernels()
    try:
        broken = generate.load_kernel(three_blade_paper(gamma1=2.0))
        with pytest.raises(numba.TypingError) as error:
            broken.forces_at(generate.kernel_scene(three_blade_paper()),
                             np.zeros(2, dtype=np.int64), new_work.py_func(3, 2, 0))
    finally:
        generate.forget_kernels()
    assert "mistyped" in str(error.value)
    assert f'kernel/forces.py", line {line}' in str(error.value)


def test_an_engine_functions_cache_goes_stale_with_any_engine_module(tmp_path, monkeypatch):
    """numba stamps a cached function by its own file, but the helpers it inlines from
    other modules are cached inside it: the engine's functions are stamped by all of the
    engine's sources, so that a change to one helper recompiles every function using it."""
    from shroudnet.engine import compiled
    from shroudnet.engine.tangent import stage_tangent

    locator = stage_tangent._cache._impl.locator
    assert isinstance(locator, compiled._EngineCacheLocator)
    stamp = locator.get_source_stamp()
    for path in ENGINE.glob("*.py"):
        (tmp_path / path.name).write_bytes(path.read_bytes())
    helper = tmp_path / "structures.py"  # not stage_tangent's own module
    monkeypatch.setattr(compiled, "_ENGINE", tmp_path)
    compiled._engine_stamp.cache_clear()
    try:
        assert locator.get_source_stamp() == stamp  # the same sources
        compiled._engine_stamp.cache_clear()
        helper.write_text(helper.read_text() + "\n# changed\n")
        assert locator.get_source_stamp() != stamp
    finally:
        compiled._engine_stamp.cache_clear()
