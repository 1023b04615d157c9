"""Kernel generation: the loop template specialised for the law classes of a scene.

A kernel is ``template.py`` behind a generated header that dispatches to law classes and
switches off the effects those classes rule out (contact events, stick, friction,
regularisation). Scenes whose laws are all built into ``contact_laws`` share one kernel
that dispatches over every built-in class with every effect kept, so no combination of
them compiles twice; a scene with a law of the user's own gets a kernel specialised for
its law classes. A kernel never depends on the number of blades or on a parameter value,
so a sweep compiles at most once.
Kernels are written to the cache folder (``cache.cache_folder``) and compiled by numba
with its on-disk cache, so a second process does not compile again. The cache key covers
every source a kernel is made of: the template, the engine's modules, and the modules of
each law class and of the functions its law calls.
"""

from __future__ import annotations

import dataclasses
import functools
import hashlib
import importlib.util
import inspect
import os
import sys
import tempfile
import time
from collections.abc import Callable
from pathlib import Path
from types import ModuleType

import numba
import numpy as np

from contact_laws import (ConstantLoad, Coulomb, ExponentialFriction, Hertz, HuntCrossley,
                          KelvinVoigt, LinearSpring, Stribeck)
from contact_laws import base as law_base
from contact_laws.base import PENETRATION_SCALE, RATE_SCALE, SPEED_SCALE

from ..scene import Scene
from .cache import cache_folder
from .records import KernelScene
from .regroup import fill_groups

_ENGINE = Path(__file__).parent
_TEMPLATE = _ENGINE / "template.py"

#: About how long compiling one driver of a kernel takes on a 2-core machine [s], with
#: the engine's own compiled code in the cache, and without (the very first run); and
#: the driver with its tangent flow.
COMPILE_ESTIMATE = 30
FIRST_COMPILE_ESTIMATE = 35
TANGENT_COMPILE_ESTIMATE = 60


def announce(message: str) -> None:
    """Tell the user about a compile before it starts (replaceable, e.g. by a GUI)."""
    print(message, file=sys.stderr, flush=True)


def _law_function(law_class, kind: str):
    return law_class.normal_force if kind == "normal" else law_class.coefficient


def _classes(laws) -> list[type]:
    unique = {type(law): None for law in laws}
    return sorted(unique, key=lambda c: (c.__module__, c.__qualname__))


#: The law classes of the shared kernel, in its index order.
BUILT_IN_NORMAL = (LinearSpring, Hertz, KelvinVoigt, HuntCrossley, ConstantLoad)
BUILT_IN_FRICTION = (Coulomb, ExponentialFriction, Stribeck)


def _law_classes(arrays) -> tuple[list[type], list[type]]:
    """The kernel's normal and (exact) friction law classes, in its index order: every
    built-in class where the scene has no other, else the scene's own."""
    frictions = [f.exact for f in arrays.friction_laws if f is not None]
    normal, friction = _classes(arrays.normal_laws), _classes(frictions)
    if built_in(normal, friction):
        return list(BUILT_IN_NORMAL), list(BUILT_IN_FRICTION)
    return normal, friction


def built_in(normal_classes, friction_classes) -> bool:
    """Whether these law classes are all built into ``contact_laws`` (the shared kernel)."""
    return (set(normal_classes) <= set(BUILT_IN_NORMAL)
            and set(friction_classes) <= set(BUILT_IN_FRICTION))


def flags(arrays, tangent: bool = False) -> dict[str, bool]:
    """The effects a scene calls for, from the law classes alone (never from their values),
    whether the scene has couplings or prescribed-motion nodes, and whether it integrates the
    tangent flow. A specialised kernel keeps these; the shared one keeps every effect.

    Contact events need a normal law that opens; stick needs an exact friction law;
    regularisation a smoothed one.
    """
    frictions = [f for f in arrays.friction_laws if f is not None]
    return {
        "HAS_CONTACT_EVENTS": any(type(law).opens for law in arrays.normal_laws),
        "HAS_STICK": any(f.exact is f for f in frictions),
        "HAS_FRICTION": bool(frictions),
        "HAS_REGULARISED": any(f.exact is not f for f in frictions),
        "HAS_COUPLINGS": arrays.n_couplings > 0,
        "HAS_PRESCRIBED": arrays.n_prescribed > 0,
        "HAS_TANGENT": tangent,
    }


def _dispatch(name, prefix, classes, arguments):
    lines = ["@njit_step", f"def {name}(kind, params, {arguments}):"]
    for index, law_class in enumerate(classes):
        arity = len(dataclasses.fields(law_class))
        params = ", ".join(f"params[{p}]" for p in range(arity))
        lines.append(f"    if kind == {index}:")
        lines.append(f"        return {prefix}{index}({arguments}, {params})")
    lines.append("    return 0.0")
    return "\n".join(lines)


def _difference(law, names, position, params, scale, one_sided=False):
    """Generated lines: the derivative of ``law`` in its argument ``names[position]`` by a
    central difference (one-sided near 0 where ``one_sided``), as ``NormalLaw.gradient``
    and ``FrictionLaw.slope`` take it."""
    argument = names[position]

    def call(shift):
        moved = [f"{name} {shift} step" if i == position and shift else name
                 for i, name in enumerate(names)]
        return f"{law}({', '.join(moved)}, {params})"

    lines = [f"        step = DIFFERENCE_STEP * max(abs({argument}), {scale!r})"]
    if one_sided:
        lines.append(f"        if {argument} < step:")
        lines.append(f"            return ({call('+')} - {call('')}) / step")
    lines.append(f"        d_{argument} = ({call('+')} - {call('-')}) / (2.0 * step)")
    return lines


def _derivative_dispatch(classes, kind):
    """Generated ``normal_force_gradient`` or ``friction_slope``: each law's own derivative,
    or central differences of the law where it gives none."""
    if kind == "normal":
        name, names, zero = "normal_force_gradient", ["penetration", "rate"], "0.0, 0.0"
    else:
        name, names, zero = "friction_slope", ["slip_speed"], "0.0"
    arguments = ", ".join(names)
    lines = ["@njit_step", f"def {name}(kind, params, {arguments}):"]
    for index, law_class in enumerate(classes):
        arity = len(dataclasses.fields(law_class))
        params = ", ".join(f"params[{p}]" for p in range(arity))
        lines.append(f"    if kind == {index}:")
        if _has_derivative(law_class, kind):
            lines.append(f"        return _{kind}_derivative_{index}({arguments}, {params})")
        elif kind == "normal":
            lines += _difference(f"_normal_{index}", names, 0, params, PENETRATION_SCALE)
            lines += _difference(f"_normal_{index}", names, 1, params, RATE_SCALE)
            lines.append("        return d_penetration, d_rate")
        else:
            lines += _difference(f"_friction_{index}", names, 0, params, SPEED_SCALE,
                                 one_sided=True)
            lines.append("        return d_slip_speed")
    lines.append(f"    return {zero}")
    return "\n".join(lines)


def _has_derivative(law_class, kind: str) -> bool:
    return (law_class.has_analytic_gradient() if kind == "normal"
            else law_class.has_analytic_slope())


def _derivative_function(law_class, kind: str):
    return law_class.normal_force_gradient if kind == "normal" else law_class.coefficient_slope


def header(normal_classes, friction_classes, effect_flags) -> str:
    """The generated lines a kernel starts with: effect flags and law dispatch."""
    placeholders = [f"_normal_{i} = None" for i in range(len(normal_classes))]
    placeholders += [f"_friction_{i} = None" for i in range(len(friction_classes))]
    placeholders += [f"_{kind}_derivative_{i} = None"
                     for kind, classes in (("normal", normal_classes),
                                           ("friction", friction_classes))
                     for i, law_class in enumerate(classes) if _has_derivative(law_class, kind)]
    names = ", ".join(c.__qualname__ for c in normal_classes + friction_classes) or "none"
    return "\n".join([
        f"# Generated by shroudnet.engine.generate for the laws: {names}. Do not edit.",
        "from contact_laws.base import DIFFERENCE_STEP",
        "from shroudnet.engine.compiled import njit_step",
        *(f"{flag} = {value}" for flag, value in effect_flags.items()),
        "# Compiled law functions, set by shroudnet.engine.generate before the first call:",
        *placeholders,
        "",
        _dispatch("normal_force", "_normal_", normal_classes, "penetration, rate"),
        "",
        _dispatch("friction_coefficient", "_friction_", friction_classes, "slip_speed"),
        "",
        _derivative_dispatch(normal_classes, "normal"),
        "",
        _derivative_dispatch(friction_classes, "friction"),
        "",
        "",
    ])


@functools.cache
def template_sources() -> tuple[str, str]:
    """The template's source, and the sources of the modules it is built on: the engine's,
    and ``contact_laws.base``, whose constants it takes (read once per process)."""
    paths = [path for path in sorted(_ENGINE.glob("*.py")) if path != _TEMPLATE]
    engine = "\n".join(path.read_text() for path in paths + [Path(law_base.__file__)])
    return _TEMPLATE.read_text(), engine


def law_sources(law_class, kind: str) -> str:
    """Every source a law's compiled function depends on: the module of its class, and the
    modules of the functions (plain or compiled) it reaches through module globals."""
    sources: dict[str, str] = {}
    visited = set()
    pending = [_law_function(law_class, kind)]
    while pending:
        item = pending.pop()
        function = getattr(item, "py_func", item)
        if not hasattr(function, "__code__") or function in visited:
            continue
        visited.add(function)
        module = inspect.getmodule(function)
        name = module.__name__ if module is not None else function.__qualname__
        if name not in sources:
            try:
                sources[name] = inspect.getsource(module if module is not None else function)
            except (OSError, TypeError):
                sources[name] = repr(function.__code__.co_code)
        for global_name in function.__code__.co_names:
            value = function.__globals__.get(global_name)
            if hasattr(getattr(value, "py_func", value), "__code__"):
                pending.append(value)
    return "\n".join(f"# {name}\n{source}" for name, source in sorted(sources.items()))


def load_kernel(scene: Scene, tangent: bool = False) -> ModuleType:
    """The kernel module for the law classes of ``scene``; with ``tangent``, the one that
    integrates the tangent flow too."""
    arrays = scene.arrays
    normal_classes, friction_classes = _law_classes(arrays)
    effects = flags(arrays, tangent)
    if built_in(normal_classes, friction_classes):
        effects = {flag: True for flag in effects} | {"HAS_TANGENT": tangent}
    return _kernel(tuple(normal_classes), tuple(friction_classes), tuple(effects.items()))


@functools.cache
def _kernel(normal_classes, friction_classes, effect_flags) -> ModuleType:
    """The kernel of one combination of law classes and effect flags (once per process)."""
    template, engine = template_sources()
    source = header(list(normal_classes), list(friction_classes), dict(effect_flags)) \
        + template
    identity = "\n".join([source, engine]
                         + [law_sources(c, "normal") for c in normal_classes]
                         + [law_sources(c, "friction") for c in friction_classes])
    key = hashlib.sha256(identity.encode()).hexdigest()[:20]
    folder = cache_folder()
    folder.mkdir(parents=True, exist_ok=True)
    path = folder / f"kernel_{key}.py"
    if not path.exists():
        with tempfile.NamedTemporaryFile("w", dir=folder, suffix=".tmp", delete=False) as f:
            f.write(source)
        os.replace(f.name, path)  # atomic: concurrent processes never see half a file
    name = f"shroudnet_kernel_{key}"
    spec = importlib.util.spec_from_file_location(name, path)
    module = importlib.util.module_from_spec(spec)
    sys.modules[name] = module
    spec.loader.exec_module(module)
    for kind, classes in (("normal", normal_classes), ("friction", friction_classes)):
        for index, law_class in enumerate(classes):
            setattr(module, f"_{kind}_{index}", numba.njit(_law_function(law_class, kind)))
            if _has_derivative(law_class, kind):
                setattr(module, f"_{kind}_derivative_{index}",
                        numba.njit(_derivative_function(law_class, kind)))
    module.LAWS = tuple(c.__qualname__ for c in normal_classes + friction_classes)
    module.TANGENT = dict(effect_flags)["HAS_TANGENT"]
    module.SHARED = built_in(normal_classes, friction_classes)
    return module


def compiled(driver, arguments) -> tuple[Callable, float]:
    """``driver`` (a kernel's ``run_fixed_step`` or ``run_adaptive``) ready to call with
    ``arguments``, and the seconds spent compiling it or loading it from the cache.

    A compile is announced before it starts, once per kernel and driver.
    """
    if not hasattr(driver, "overloads"):  # NUMBA_DISABLE_JIT=1: plain Python, for debugging
        return driver, 0.0
    if not driver.overloads:
        if not _cached(driver):
            module = sys.modules[driver.py_func.__module__]
            seconds = TANGENT_COMPILE_ESTIMATE if module.TANGENT else \
                COMPILE_ESTIMATE if _cached(fill_groups) else FIRST_COMPILE_ESTIMATE
            flow = " with its tangent flow" if module.TANGENT else ""
            laws = "every built-in contact law (once" if module.SHARED else \
                f"{' + '.join(module.LAWS)} (once for these law classes"
            announce(f"shroudnet: compiling the {driver.__name__.removeprefix('run_')} "
                     f"integrator{flow} for {laws}; about {seconds} s)")
        began = time.perf_counter()
        driver.compile(tuple(numba.typeof(a) for a in arguments))
        return driver, time.perf_counter() - began
    return driver, 0.0


def _cached(driver) -> bool:
    try:
        return Path(driver._cache._cache_file._index_path).exists()
    except AttributeError:  # another numba's internals: say nothing is cached
        return False


def kernel_scene(scene: Scene) -> KernelScene:
    """The scene's arrays with each law given as (index of its class, parameter row), and
    its prescribed-motion nodes after the blades (``KernelScene``)."""
    a = scene.arrays
    normal_classes, friction_classes = _law_classes(a)
    normal_kind = np.array([normal_classes.index(type(law)) for law in a.normal_laws],
                           dtype=np.int64)
    friction_kind = np.array([-1 if f is None else friction_classes.index(type(f.exact))
                              for f in a.friction_laws], dtype=np.int64)
    terms = [motion.terms() for motion in a.motions]
    knots = max([len(t.knot_times) for t in terms] + [1])
    times, accelerations = np.zeros((len(terms), knots)), np.zeros((len(terms), knots))
    for p, t in enumerate(terms):
        times[p, :len(t.knot_times)] = t.knot_times
        accelerations[p, :len(t.knot_times)] = t.knot_accelerations
    none = np.zeros(len(terms))

    def nodes(values):
        return np.concatenate([values, none])

    amplitudes = a.harmonic_amplitudes
    phases = np.concatenate([a.harmonic_phases, np.zeros((len(amplitudes), len(terms)))],
                            axis=1)
    return KernelScene(
        mass=nodes(a.mass), damping=nodes(a.damping), stiffness=nodes(a.stiffness),
        left=a.left, right=a.right,
        gap=a.gap, sin_angle=a.sin_angle, cos_angle=a.cos_angle, opens=a.opens,
        can_stick=a.can_stick, static_mu=a.static_mu, regularisation=a.regularisation,
        normal_kind=normal_kind, normal_params=_rows(a.normal_laws),
        friction_kind=friction_kind,
        friction_params=_rows(a.friction_laws),
        amplitudes=np.concatenate([amplitudes, np.zeros((len(amplitudes), len(terms)))],
                                  axis=1),
        cos_phase=np.cos(phases), sin_phase=np.sin(phases),
        excitation_frequency=float(a.excitation_frequency),
        coupling_left=a.coupling_left, coupling_right=a.coupling_right,
        coupling_stiffness=a.coupling_stiffness, coupling_damping=a.coupling_damping,
        motion_amplitude=np.array([t.amplitude for t in terms], dtype=float),
        motion_frequency=np.array([t.angular_frequency for t in terms], dtype=float),
        motion_phase=np.array([t.phase for t in terms], dtype=float),
        motion_times=times, motion_accelerations=accelerations,
        motion_knots=np.array([len(t.knot_times) for t in terms], dtype=np.int64))


def _rows(laws) -> np.ndarray:
    rows = [() if law is None else law.parameters() for law in laws]
    width = max([len(r) for r in rows] + [1])
    table = np.zeros((len(rows), width))
    for i, row in enumerate(rows):
        table[i, :len(row)] = row
    return table
