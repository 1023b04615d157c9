"""Kernel generation: the loop's phase modules specialised for the law classes of a scene.

A kernel is a module that starts with a generated header, which dispatches to law classes
and switches off the effects those classes rule out (contact events, stick, friction,
regularisation), and then runs the phase modules of ``kernel`` (``kernel.PHASES``) in its
namespace, each compiled from its own file, so that an error or a traceback names the
phase module and its line. Scenes whose laws are all built into ``contact_laws``
(``contact_laws.BUILT_IN_NORMAL``, ``BUILT_IN_FRICTION``) share one kernel per method
that dispatches over every built-in class with every effect kept, so no combination of
them compiles twice; a scene with a law of the user's own gets a kernel specialised for
its law classes. A kernel never depends on the number of blades or on a parameter value,
so a sweep compiles at most once per method.

The header is written to the cache folder (``cache.cache_folder``) and every function is
compiled by numba with its on-disk cache, so a second process does not compile again.
numba keys that cache by a function's file, name and line, and a phase module runs in
many kernels, so each phase function's name carries a key of everything its code is made
of (``compiled``): the phase modules, the engine's modules, the header, the method, and
the modules of each law class and of the functions its law calls. The phases that are the
same for every method (``METHOD_FREE``) run once for the laws, in a module of their own
that each method's kernel calls into, so another method compiles only its own phases.
"""

from __future__ import annotations

import functools
import hashlib
import importlib.util
import inspect
import sys
import time
import weakref
from collections.abc import Callable
from pathlib import Path
from types import ModuleType

import numba
import numpy as np

from contact_laws import BUILT_IN_FRICTION, BUILT_IN_NORMAL, Coulomb
from contact_laws import base as law_base

from ..model.scene import Scene
from .cache import cache_folder, keep
from .compiled import compile_seconds
from .header import derivative_function, has_derivative, header, law_function
from .kernel import PHASES
from .records import KernelScene, StructureScene

_ENGINE = Path(__file__).parent
_PHASES = [_ENGINE / "kernel" / f"{phase}.py" for phase in PHASES]

#: The phase modules whose code is the same for every method: they never read ``ADAPTIVE``
#: or ``EXPONENTIAL``, nor call a function of another phase (which their module lacks).
METHOD_FREE = ("forces", "tangent", "resolve")

def announce(message: str) -> None:
    """Tell the user about a compile before it starts (replaceable, e.g. by a GUI)."""
    print(message, file=sys.stderr, flush=True)


def _classes(laws) -> list[type]:
    unique = {type(law): None for law in laws}
    return sorted(unique, key=lambda c: (c.__module__, c.__qualname__))


def _law_classes(arrays, shared: bool = True) -> tuple[list[type], list[type]]:
    """The kernel's normal and (exact) friction law classes, in its index order: every
    built-in class where the scene has no other (and the kernel is ``shared``), else the
    scene's own."""
    frictions = [f.exact for f in arrays.friction_laws if f is not None]
    normal, friction = _classes(arrays.normal_laws), _classes(frictions)
    if shared and built_in(normal, friction):
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
        "HAS_STRUCTURES": arrays.is_structure,
        "HAS_SLIDERS": has_sliders(arrays),
        "HAS_TANGENT": tangent,
    }


def has_sliders(arrays) -> bool:
    """Whether a scene has elastic contacts (finite k_t), whose sliders the state carries."""
    return arrays.n_stretches > 0


@functools.cache
def phase_sources() -> tuple[tuple[str, ...], str]:
    """The phase modules' sources (in ``PHASES`` order), and the sources of the modules
    they are built on: the engine's, and ``contact_laws.base``, whose constants they take
    (read once per process)."""
    paths = sorted(_ENGINE.glob("*.py")) + [Path(law_base.__file__)]
    engine = "\n".join(path.read_text() for path in paths)
    return tuple(path.read_text() for path in _PHASES), engine


def law_sources(law_class, kind: str) -> str:
    """Every source a law's compiled function depends on: the module of its class, and the
    modules of the functions (plain or compiled) it reaches through module globals."""
    sources: dict[str, str] = {}
    visited = set()
    pending = [law_function(law_class, kind)]
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


def load_kernel(scene: Scene, tangent: bool = False, method: str = "adaptive",
                shared: bool = True) -> ModuleType:
    """The kernel module for the law classes of ``scene`` and a method ("adaptive",
    "fixed_step" or "exponential"); with ``tangent``, the one that integrates the tangent
    flow too (not "fixed_step"). Without ``shared``, a scene of built-in laws gets a
    kernel of its own law classes and effects too, as one with a law of the user's own
    does (the CUDA flavour, ``batch``, compiles each kernel anew for the device, where
    code never run costs compile time and registers)."""
    if tangent and method == "fixed_step":
        raise ValueError("the tangent flow is integrated by adaptive or exponential steps")
    arrays = scene.arrays
    if tangent:
        _check_slider_laws(scene)
    normal_classes, friction_classes = _law_classes(arrays, shared)
    effects = flags(arrays, tangent)
    if shared and built_in(normal_classes, friction_classes):
        effects = {flag: True for flag in effects} | {
            "HAS_TANGENT": tangent, "HAS_STRUCTURES": arrays.is_structure,
            "HAS_SLIDERS": has_sliders(arrays)}
    return _kernel(tuple(normal_classes), tuple(friction_classes), tuple(effects.items()),
                   method)


def _check_slider_laws(scene: Scene) -> None:
    """Refuse the tangent flow of an elastic contact whose normal law's slopes vary: the
    variation of its slipping stretch's rate takes δṄ from constant slopes
    (``slider_tangent``)."""
    a = scene.arrays
    for e in a.elastic_interfaces:
        law = a.normal_laws[e]
        if not type(law).constant_slopes:
            raise ValueError(
                f"{scene.contacts[e]}: the tangent flow (periodic orbits, "
                "monodromy, Lyapunov exponents) of an elastic contact takes a normal law of "
                f"constant slopes, LinearSpring or ConstantLoad, not {type(law).__name__}")


def _digest(*parts: str) -> str:
    return hashlib.sha256("\n".join(parts).encode()).hexdigest()[:20]


@functools.cache
def _kernel(normal_classes, friction_classes, effect_flags, method) -> ModuleType:
    """The kernel of one combination of law classes, effect flags and method (once per
    process): the method's phases, run in a namespace that holds the method-free kernel
    of the same laws (``_method_free``), ``ADAPTIVE`` and ``EXPONENTIAL``."""
    laws = _method_free(normal_classes, friction_classes, effect_flags)
    phases, _ = phase_sources()
    adaptive, exponential = method == "adaptive", method == "exponential"
    key = _digest(laws.CACHE_KEY, "EXPONENTIAL = True" if exponential else f"ADAPTIVE = {adaptive}")
    module = ModuleType(f"shroudnet_kernel_{key}")
    module.__dict__.update({name: value for name, value in vars(laws).items()
                            if not name.startswith("__")})
    module.__file__ = laws.__file__
    module.ADAPTIVE, module.EXPONENTIAL, module.METHOD = adaptive, exponential, method
    _run_phases(module, key, [phase for phase in PHASES if phase not in METHOD_FREE], phases)
    return module


@functools.cache
def _method_free(normal_classes, friction_classes, effect_flags) -> ModuleType:
    """The header and the method-free phases (``METHOD_FREE``) of a kernel, for both
    methods: a phase here that read ``ADAPTIVE``, or called a function of another phase,
    would find no such name."""
    phases, engine = phase_sources()
    source = header(list(normal_classes), list(friction_classes), dict(effect_flags))
    key = _digest(source, *phases, engine,
                  *[law_sources(c, "normal") for c in normal_classes],
                  *[law_sources(c, "friction") for c in friction_classes])
    path = keep(f"kernel_{key}.py", source)
    spec = importlib.util.spec_from_file_location(f"shroudnet_kernel_{key}", path)
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    _run_phases(module, key, METHOD_FREE, phases)
    for kind, classes in (("normal", normal_classes), ("friction", friction_classes)):
        for index, law_class in enumerate(classes):
            setattr(module, f"_{kind}_{index}", numba.njit(law_function(law_class, kind)))
            if has_derivative(law_class, kind):
                setattr(module, f"_{kind}_derivative_{index}",
                        numba.njit(derivative_function(law_class, kind)))
    module.LAWS = tuple(c.__qualname__ for c in normal_classes + friction_classes)
    module.TANGENT = dict(effect_flags)["HAS_TANGENT"]
    module.SHARED = built_in(normal_classes, friction_classes)
    return module


def forget_kernels() -> None:
    """Forget the kernels built in this process, so that the next ``load_kernel`` builds
    them again from the phase sources (for tests that plant a change in them)."""
    _kernel.cache_clear()
    _method_free.cache_clear()


def _run_phases(module: ModuleType, key: str, names, phases) -> None:
    """Run the phase modules ``names`` in ``module``, each compiled from its own file (so
    that errors name it), their functions cached under ``key`` in the kernel cache folder
    (``compiled``). The module is registered under its name, as numba's cache looks it
    up there."""
    sys.modules[module.__name__] = module
    module.CACHE_KEY = key
    module.CACHE_FOLDER = str(cache_folder() / "compiled")
    for phase, path, source in zip(PHASES, _PHASES, phases):
        if phase in names:
            exec(compile(source, str(path), "exec"), module.__dict__)


def compiled(driver, arguments) -> tuple[Callable, float]:
    """``driver`` (a kernel's ``run``) ready to call with ``arguments``, and the seconds
    spent compiling it or loading it from the cache.

    A compile is announced before it starts, once per kernel.
    """
    if not hasattr(driver, "overloads"):  # NUMBA_DISABLE_JIT=1: plain Python, for debugging
        return driver, 0.0
    if not driver.overloads:
        if not _cached(driver):
            module = sys.modules[driver.py_func.__module__]
            seconds = compile_seconds(module)
            flow = " with its tangent flow" if module.TANGENT else ""
            laws = "every built-in contact law (once" if module.SHARED else \
                f"{' + '.join(module.LAWS)} (once for these law classes"
            announce(f"shroudnet: compiling the {module.METHOD} integrator{flow} for {laws}; "
                     f"about {seconds} s)")
        began = time.perf_counter()
        driver.compile(tuple(numba.typeof(a) for a in arguments))
        return driver, time.perf_counter() - began
    return driver, 0.0


def _cached(driver) -> bool:
    try:
        return Path(driver._cache._cache_file._index_path).exists()
    except AttributeError:  # another numba's internals: say nothing is cached
        return False


#: Each scene's kernel arrays, made once: a Newton step, a refinement of an extreme and
#: every run of a study integrate the same scene again and again (the kernel only reads them).
_KERNEL_SCENES: weakref.WeakKeyDictionary = weakref.WeakKeyDictionary()


def kernel_scene(scene: Scene, shared: bool = True) -> KernelScene | StructureScene:
    """The scene's arrays with each law given as (index of its class, parameter row), and
    its prescribed-motion nodes after the blades (``KernelScene``); with substructures or
    elastic contacts, a ``StructureScene``, with the elastic contacts' sliders as
    coordinates between the free and the prescribed ones. Made once per scene; without
    ``shared``, made afresh for the kernel of the scene's own law classes
    (``load_kernel(..., shared=False)``)."""
    if not shared:
        return _lowered(scene, shared=False)
    found = _KERNEL_SCENES.get(scene)
    if found is None:
        found = _KERNEL_SCENES[scene] = _lowered(scene)
    return found


def _lowered(scene: Scene, shared: bool = True) -> KernelScene | StructureScene:
    """``kernel_scene``, made afresh."""
    a = scene.arrays
    for e in a.elastic_interfaces:
        if type(a.friction_laws[e]) is not Coulomb:
            raise ValueError(
                f"{scene.contacts[e]}: an elastic contact "
                "(Interface.tangential_stiffness) slips at the one coefficient of Coulomb "
                f"friction; give friction=Coulomb(mu=...), not {a.friction_laws[e]!r}")
    normal_classes, friction_classes = _law_classes(a, shared)
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
    fields = dict(
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
    if not a.is_structure:
        return KernelScene(**fields)
    free = len(a.mass)
    elastic = np.isfinite(a.tangential_stiffness)
    sliders = 2 * int(elastic.sum())
    slider_index = np.full(len(elastic), -1, dtype=np.int64)
    slider_index[elastic] = free + 2 * np.arange(sliders // 2)

    def with_sliders(values, fill=0.0, axis=-1):
        """``values`` with the sliders' entries inserted after the free coordinates."""
        return np.insert(values, [free] * sliders, fill, axis=axis)

    fields.update(can_stick=a.can_stick & ~elastic,  # a slider's guards are its own
                  mass=with_sliders(fields["mass"], 1.0),
                  damping=with_sliders(fields["damping"]),
                  stiffness=with_sliders(fields["stiffness"]),
                  amplitudes=with_sliders(fields["amplitudes"]),
                  cos_phase=with_sliders(fields["cos_phase"], 1.0),
                  sin_phase=with_sliders(fields["sin_phase"]))
    normal_rows, tangent_rows, second_rows = (
        with_sliders(rows) for rows in (a.normal_rows, a.tangent_rows, a.second_tangent_rows))
    stiffness, damping = (with_sliders(with_sliders(matrix), axis=0)
                          for matrix in (a.structure_stiffness, a.structure_damping))
    support = (normal_rows != 0.0) | (tangent_rows != 0.0) | (second_rows != 0.0)
    pattern = (stiffness != 0.0) | (damping != 0.0)
    rows, columns = np.nonzero(pattern)
    return StructureScene(
        **fields, normal_rows=normal_rows, tangent_rows=tangent_rows,
        normal_gap=a.normal_gap, support_start=_starts(support.sum(axis=1)),
        support_index=np.nonzero(support)[1].astype(np.int64),
        matrix_start=_starts(pattern.sum(axis=1)), matrix_column=columns.astype(np.int64),
        stiffness_entry=stiffness[rows, columns], damping_entry=damping[rows, columns],
        second_tangent_rows=second_rows,
        tangential_stiffness=np.where(elastic, a.tangential_stiffness, np.inf),
        slider_index=slider_index)


def _starts(counts) -> np.ndarray:
    """Where each row's entries start in a compressed store, and the end (len + 1)."""
    return np.concatenate([[0], np.cumsum(counts)]).astype(np.int64)


def _rows(laws) -> np.ndarray:
    rows = [() if law is None else law.parameters() for law in laws]
    width = max([len(r) for r in rows] + [1])
    table = np.zeros((len(rows), width))
    for i, row in enumerate(rows):
        table[i, :len(row)] = row
    return table
