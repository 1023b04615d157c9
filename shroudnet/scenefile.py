"""Scene files: a blade group, its excitation and how to run it, in TOML, and back.

A scene file holds one document (SI units; speeds in rev/min)::

    speed_rpm = 6000.0

    [excitation]
    engine_order = 2
    amplitudes = [0.0, 50.0]          # q0, q1, … [N]
    phases = "anti-phase"             # or "engine-order" (ND = l mod N), or
                                      # {travelling_wave = 3}, or [φ1, φ2, …] [rad]

    [[blades]]                        # one table per blade, in order
    name = "blade1"
    mass = 0.082                      # [kg]
    damping = 4.0                     # [N·s/m]
    frequency = 210.0                 # f_d1 [Hz]; or {f0 = …, coefficient = …} (Southwell);
                                      # or {speeds_rpm = […], frequencies = […]}; or
                                      # stiffness = … [N/m] instead of a frequency
                                      # (0: a node held by couplings or interfaces)
    excitation_scale = 1.0            # s_i ≥ 0, its share of Q(t); optional (0: unforced)

    fixed = ["disc"]                  # fixed nodes (x ≡ 0), optional

    [[prescribed]]                    # nodes moving on a given path, optional
    name = "belt"
    motion = {kind = "constant_velocity", velocity = 0.1}   # V [m/s], position x_0 [m]
    # or {kind = "harmonic", amplitude = 1e-4, frequency = 100.0, phase = 0.0}  [m, Hz, rad]
    # or {kind = "table", times = [0.0, …], displacements = [0.0, …]}           [s, m]

    [[interfaces]]
    left = "blade1"
    right = "blade2"
    gap = 2e-5                        # Δ [m]
    angle = 1.0471975511965976        # α [rad]
    normal = {law = "LinearSpring", stiffness = 3.3e5}
    friction = {law = "ExponentialFriction", mu_static = 0.5, mu_kinetic = 0.3, beta = 5.0}

    [[couplings]]                     # springs and dampers between nodes, optional
    left = "disc"
    right = "blade1"
    stiffness = 2e5                   # k_c ≥ 0 [N/m]
    damping = 1.0                     # c_c ≥ 0 [N·s/m], optional

    sectors = 24                      # optional: a ring of identical sectors, nodes given
                                      # sector by sector (``linear_modes``)

    [run]                             # optional: how ``shroudnet run`` integrates it
    method = "adaptive"               # or "fixed" (steps_per_period) or "accuracy" (target)
    periods = 400
    transient = 300                   # periods left out of summaries and figures
    blade = "blade2"                  # the blade they are about

Identical blades may be given once instead, as ``[group]`` with ``shape = "ring"`` or
``"chain"``, ``count``, ``blade = {…}`` and ``interface = {…}``; a bladed disc of
identical sectors (``BladeGroup.bladed_disc``) as ``shape = "bladed_disc"``, ``count``
(sectors), ``disc = {…}`` (a blade table), ``disc_coupling = {stiffness, damping}``,
``blade = [{…}, …]`` (its nodes, root to tip), ``blade_couplings = [{…}, …]`` (one per
blade node) and, optionally, ``interface = {…}`` between neighbouring tips. A law is named by its
class in ``contact_laws``; its other keys are the law's fields. ``Regularised`` takes
``law = {…}`` and ``velocity``.

A law of one's own is named ``"module:Class"``. Reading a file never imports a module nor
runs any code of its own choosing: the class must come from a module that is already
imported, or be passed in ``laws``::

    import my_laws                                   # the user chooses to run this code
    scenefile.load("group.toml")                     # finds "my_laws:CubicSpring"
    scenefile.load("group.toml", laws=[CubicSpring])  # or allow the classes explicitly

(on the command line: ``shroudnet run group.toml --laws my_laws``).

``[excitation]`` may be left out: no force Q(t) acts (a block driven by a belt alone), and
the period the run counts in is 60/``speed_rpm`` s.

Every key is checked before anything runs: a bad file raises ``SceneFileError`` naming
the file, the key and what is allowed there.
"""

from __future__ import annotations

import dataclasses
import math
import sys
import tomllib
from collections.abc import Iterable
from dataclasses import dataclass
from pathlib import Path
from types import ModuleType
from typing import Any

import contact_laws

from .blade import Blade, ConstantFrequency, FrequencyTable, Southwell
from .coupling import Coupling
from .excitation import (NO_EXCITATION, AntiPhase, EngineOrderWave, Excitation,
                         ExplicitPhases, TravellingWave)
from .group import BladeGroup
from .interface import Interface
from .methods import EVENT_TOLERANCE, TRANSIENT, Accuracy, Adaptive, FixedStep
from .motion import ConstantVelocity, HarmonicMotion, MotionTable
from .scene import Scene


class SceneFileError(ValueError):
    """A scene file that cannot be read: the message names the file, the key and the fix."""


@dataclass(frozen=True, kw_only=True)
class RunSettings:
    """How to run a scene: the ``[run]`` table of a scene file."""

    method: FixedStep | Adaptive | Accuracy = Adaptive()
    periods: int = 400
    transient: int = TRANSIENT
    samples_per_period: int = 100
    event_tolerance: float = EVENT_TOLERANCE
    blade: str | int = 1

    def __post_init__(self):
        for name in ("periods", "samples_per_period"):
            number = getattr(self, name)
            if isinstance(number, bool) or not isinstance(number, int) or number < 1:
                raise ValueError(f"run.{name} must be an int >= 1, got {number!r}")
        if isinstance(self.transient, bool) or not isinstance(self.transient, int) \
                or not 0 <= self.transient < self.periods:
            raise ValueError(f"run.transient must be an int in [0, periods = {self.periods}), "
                             f"got {self.transient!r}")


#: What ``laws`` may hold: law classes, or modules whose law classes are allowed.
Laws = Iterable[type | ModuleType]


@dataclass(frozen=True)
class SceneFile:
    """A scene file read: the scene, its run settings and the document they came from."""

    scene: Scene
    run: RunSettings
    document: dict


def load(path: str | Path, *, laws: Laws = ()) -> SceneFile:
    """Read a scene file; raises ``SceneFileError`` naming the key at fault.

    ``laws``: law classes of one's own (or modules holding them) that the file may name as
    ``"module:Class"``, besides those of modules already imported. Nothing is imported.
    """
    path = Path(path)
    document = _parse(path, _text(path))
    return read(document, source=str(path), laws=laws)


def _text(path: Path) -> str:
    """The text of a scene file, or a ``SceneFileError`` saying why it cannot be read."""
    if path.is_dir():
        raise SceneFileError(f"{path}: is a folder; give a scene file (.toml)")
    if path.exists() and not path.is_file():
        raise SceneFileError(f"{path}: is not a regular file; give a scene file (.toml)")
    try:
        return path.read_text(encoding="utf-8")
    except FileNotFoundError:
        raise SceneFileError(f"{path}: no such scene file") from None
    except UnicodeDecodeError as error:
        raise SceneFileError(f"{path}: not a text file (UTF-8 TOML): byte {error.start} "
                             f"cannot be decoded") from None
    except OSError as error:
        raise SceneFileError(f"{path}: cannot be read: {error.strerror or error}") from None


def _parse(path: Path, text: str) -> dict:
    if not text.strip():
        raise SceneFileError(f"{path}: the file is empty; a scene file needs speed_rpm, "
                             "[excitation], [[blades]] and [[interfaces]] (or [group]); "
                             "see examples/scenes/")
    try:
        return tomllib.loads(text)
    except tomllib.TOMLDecodeError as error:
        raise SceneFileError(f"{path}: not valid TOML: {error}") from None
    except RecursionError:
        raise SceneFileError(f"{path}: not a scene file: its tables or lists are nested too "
                             "deeply to read") from None


def read(document: dict, *, source: str = "scene", laws: Laws = ()) -> SceneFile:
    """Build the scene and run settings of a document (a parsed scene file).

    ``laws`` as for ``load``.
    """
    own = _own_laws(laws)
    try:
        if not isinstance(document, dict):
            raise _KeyError("the file", "must be a table of keys, got "
                                        f"{type(document).__name__}")
        scene, run = _scene(document, own), _run(document.get("run", {}))
        if "blade" not in document.get("run", {}) and len(scene.blades) == 1:
            run = dataclasses.replace(run, blade=0)  # the default, position 1, is not there
        _build("run.blade", lambda: scene.blade_position(run.blade))
        return SceneFile(scene=scene, run=run, document=document)
    except _KeyError as error:
        raise SceneFileError(f"{source}: {error.key}: {error.message}") from None


def _own_laws(laws: Laws) -> dict[str, type]:
    """The allowed laws of one's own by the ``"module:Class"`` names a file may give them."""
    if isinstance(laws, type | ModuleType | str):
        raise TypeError(f"laws must be a list of law classes or modules, got {laws!r}")
    own = {}
    for item in laws:
        if isinstance(item, ModuleType):
            for attribute, value in vars(item).items():
                if _is_law(value):
                    own[f"{item.__name__}:{attribute}"] = value
                    own[f"{value.__module__}:{value.__qualname__}"] = value
        elif _is_law(item):
            own[f"{item.__module__}:{item.__qualname__}"] = item
        else:
            raise TypeError(f"laws must hold NormalLaw or FrictionLaw classes, or modules, "
                            f"got {item!r}")
    return own


def _is_law(value) -> bool:
    bases = (contact_laws.NormalLaw, contact_laws.FrictionLaw)
    return isinstance(value, type) and issubclass(value, bases) and value not in bases


# ---- reading ------------------------------------------------------------------------------

class _KeyError(Exception):
    def __init__(self, key: str, message: str):
        super().__init__(f"{key}: {message}")
        self.key, self.message = key, message


_TOP = {"speed_rpm", "excitation", "blades", "fixed", "prescribed", "interfaces",
        "couplings", "sectors", "group", "run"}


def _scene(document: dict, own: dict[str, type]) -> Scene:
    _only(document, _TOP, "the file")
    if "group" in document and ("blades" in document or "interfaces" in document):
        raise _KeyError("group", "give either [group] or [[blades]] and [[interfaces]], "
                                 "not both")
    for key in ("couplings", "prescribed"):
        if "group" in document and key in document:
            raise _KeyError(key, f"give {key} with [[blades]], not with [group]")
    group = _shorthand(document["group"], own) if "group" in document \
        else _explicit(document, own)
    if "sectors" in document:
        sectors = document["sectors"]
        if isinstance(sectors, bool) or not isinstance(sectors, int) or sectors < 1 \
                or len(group.blades) % sectors:
            raise _KeyError("sectors", f"must be a whole number >= 1 that divides the "
                                       f"{len(group.blades)} blades, got {sectors!r}")
        group.graph.graph["sectors"] = sectors
    excitation = _excitation(_table(document, "excitation", "excitation")) \
        if "excitation" in document else NO_EXCITATION
    speed = _number(document, "speed_rpm", "speed_rpm", low=0.0)
    return _build("the scene", lambda: Scene(group=group, excitation=excitation,
                                             speed_rpm=speed))


def _explicit(document: dict, own: dict[str, type]) -> BladeGroup:
    group = BladeGroup()
    blades = _list(document, "blades", "blades")
    if not blades:
        raise _KeyError("blades", "a group needs at least one blade")
    for i, entry in enumerate(blades):
        key = f"blades[{i}]"
        entry = _as_table(entry, key)
        _only(entry, {"name"} | _BLADE_KEYS, key)
        name = _name(entry, key)
        blade = _blade({k: v for k, v in entry.items() if k != "name"}, key)
        _build(key, lambda: group.add_blade(name, blade))
    fixed = document.get("fixed", [])
    if not isinstance(fixed, list):
        raise _KeyError("fixed", f"must be a list of node names, got {fixed!r}")
    for i, name in enumerate(fixed):
        if not isinstance(name, str | int) or isinstance(name, bool):
            raise _KeyError(f"fixed[{i}]", f"must be a name (text or integer), got {name!r}")
        _build(f"fixed[{i}]", lambda: group.add_fixed(name))
    for i, entry in enumerate(_list(document, "prescribed", "prescribed")):
        key = f"prescribed[{i}]"
        entry = _as_table(entry, key)
        _only(entry, {"name", "motion"}, key)
        name = _name(entry, key)
        motion = _motion(_table(entry, "motion", f"{key}.motion"), f"{key}.motion")
        _build(key, lambda: group.add_prescribed(name, motion))
    for i, entry in enumerate(document.get("interfaces", [])):
        key = f"interfaces[{i}]"
        entry = _as_table(entry, key)
        _only(entry, {"left", "right"} | _INTERFACE_KEYS, key)
        left, right = (_node(entry, end, f"{key}.{end}") for end in ("left", "right"))
        interface = _interface({k: v for k, v in entry.items() if k not in ("left", "right")},
                               key, own)
        _build(key, lambda: group.connect(left, right, interface))
    for i, entry in enumerate(_list(document, "couplings", "couplings")):
        key = f"couplings[{i}]"
        entry = _as_table(entry, key)
        _only(entry, {"left", "right", "stiffness", "damping"}, key)
        left, right = (_node(entry, end, f"{key}.{end}") for end in ("left", "right"))
        coupling = _coupling({k: v for k, v in entry.items() if k not in ("left", "right")},
                             key)
        _build(key, lambda: group.connect(left, right, coupling))
    return group


def _shorthand(table, own: dict[str, type]) -> BladeGroup:
    table = _as_table(table, "group")
    shape = table.get("shape")
    if shape == "bladed_disc":
        return _bladed_disc(table, own)
    _only(table, {"shape", "count", "blade", "interface"}, "group")
    if shape not in ("ring", "chain"):
        raise _KeyError("group.shape", f'must be "ring", "chain" or "bladed_disc", got '
                                       f'{shape!r}')
    count = table.get("count")
    if isinstance(count, bool) or not isinstance(count, int) or count < (3 if shape == "ring"
                                                                          else 1):
        raise _KeyError("group.count", f"must be an integer >= {3 if shape == 'ring' else 1} "
                                       f"for a {shape}, got {count!r}")
    blade = _blade(_table(table, "blade", "group.blade"), "group.blade")
    interface = _interface(_table(table, "interface", "group.interface"), "group.interface",
                           own)
    build = BladeGroup.ring if shape == "ring" else BladeGroup.chain
    return _build("group", lambda: build(count, blade, interface))


def _bladed_disc(table, own: dict[str, type]) -> BladeGroup:
    """``BladeGroup.bladed_disc`` from [group] with shape = "bladed_disc"."""
    _only(table, {"shape", "count", "disc", "disc_coupling", "blade", "blade_couplings",
                  "interface"}, "group")
    count = table.get("count")
    if isinstance(count, bool) or not isinstance(count, int) or count < 3:
        raise _KeyError("group.count", f"must be an integer >= 3 sectors, got {count!r}")
    disc = _blade(_table(table, "disc", "group.disc"), "group.disc")
    blade = [_blade(_as_table(entry, f"group.blade[{k}]"), f"group.blade[{k}]")
             for k, entry in enumerate(_list(table, "blade", "group.blade"))]
    couplings = [_coupling(_as_table(entry, f"group.blade_couplings[{k}]"),
                           f"group.blade_couplings[{k}]")
                 for k, entry in enumerate(_list(table, "blade_couplings",
                                                 "group.blade_couplings"))]
    disc_coupling = _coupling(_table(table, "disc_coupling", "group.disc_coupling"),
                              "group.disc_coupling")
    shroud = None
    if "interface" in table:
        shroud = _interface(_table(table, "interface", "group.interface"), "group.interface",
                            own)
    return _build("group", lambda: BladeGroup.bladed_disc(count, disc, disc_coupling, blade,
                                                         couplings, shroud))


#: The ``kind`` of a prescribed motion in a file, its class and its keys.
_MOTIONS = {"constant_velocity": (ConstantVelocity, {"velocity", "position"}),
            "harmonic": (HarmonicMotion, {"amplitude", "frequency", "phase"}),
            "table": (MotionTable, {"times", "displacements"})}


def _motion(table: dict, key: str):
    kind = table.get("kind")
    if kind not in _MOTIONS:
        raise _KeyError(f"{key}.kind", f"must be one of {', '.join(map(repr, _MOTIONS))}, "
                                       f"got {kind!r}")
    cls, keys = _MOTIONS[kind]
    _only(table, {"kind"} | keys, key)
    fields = {k: tuple(v) if isinstance(v, list) else v for k, v in table.items()
              if k != "kind"}
    return _build(key, lambda: cls(**fields))


def _motion_document(motion) -> dict:
    kind = next(k for k, (cls, _) in _MOTIONS.items() if isinstance(motion, cls))
    return {"kind": kind, **{f.name: list(getattr(motion, f.name))
                             if isinstance(getattr(motion, f.name), tuple)
                             else float(getattr(motion, f.name))
                             for f in dataclasses.fields(motion)}}


def _coupling(table: dict, key: str) -> Coupling:
    _only(table, {"stiffness", "damping"}, key)
    stiffness = _number(table, "stiffness", f"{key}.stiffness")
    damping = _number(table, "damping", f"{key}.damping") if "damping" in table else 0.0
    return _build(key, lambda: Coupling(stiffness=stiffness, damping=damping))


_BLADE_KEYS = {"mass", "damping", "frequency", "stiffness", "excitation_scale"}


def _blade(table: dict, key: str) -> Blade:
    _only(table, _BLADE_KEYS, key)
    if ("frequency" in table) == ("stiffness" in table):
        raise _KeyError(key, "give a blade either frequency [Hz] or stiffness [N/m]")
    arguments = {"mass": _number(table, "mass", f"{key}.mass"),
                 "damping": _number(table, "damping", f"{key}.damping")}
    if "excitation_scale" in table:
        arguments["excitation_scale"] = _number(table, "excitation_scale",
                                                f"{key}.excitation_scale", low=0.0)
    if "stiffness" in table:
        arguments["stiffness"] = _number(table, "stiffness", f"{key}.stiffness")
    else:
        arguments["frequency"] = _frequency(table["frequency"], f"{key}.frequency")
    return _build(key, lambda: Blade(**arguments))


def _frequency(value, key):
    if isinstance(value, int | float) and not isinstance(value, bool):
        return _build(key, lambda: ConstantFrequency(hz=float(value)))
    value = _as_table(value, key, "a number [Hz] or a table")
    if set(value) == {"f0", "coefficient"}:
        return _build(key, lambda: Southwell(**value))
    if set(value) == {"speeds_rpm", "frequencies"}:
        return _build(key, lambda: FrequencyTable(**value))
    raise _KeyError(key, "must be a number [Hz], {f0, coefficient} (Southwell's law) or "
                         f"{{speeds_rpm, frequencies}} (a table), got keys {sorted(value)}")


_INTERFACE_KEYS = {"gap", "angle", "normal", "friction"}


def _interface(table: dict, key: str, own: dict[str, type]) -> Interface:
    _only(table, _INTERFACE_KEYS, key)
    normal = _law(_table(table, "normal", f"{key}.normal"), f"{key}.normal",
                  contact_laws.NormalLaw, own)
    friction = None
    if "friction" in table:
        friction = _law(_table(table, "friction", f"{key}.friction"), f"{key}.friction",
                        contact_laws.FrictionLaw, own)
    return _build(key, lambda: Interface(gap=_number(table, "gap", f"{key}.gap"),
                                         angle=_number(table, "angle", f"{key}.angle"),
                                         normal=normal, friction=friction))


def _law(table: dict, key: str, kind: type, own: dict[str, type]):
    name = table.get("law")
    if not isinstance(name, str):
        raise _KeyError(f"{key}.law", f"must name a {kind.__name__} ({_law_names(kind)}), "
                                      f"got {name!r}")
    law_class = _law_class(name, kind, f"{key}.law", own)
    fields = {f.name for f in dataclasses.fields(law_class) if f.init}
    arguments = {k: v for k, v in table.items() if k != "law"}
    _only(arguments, fields, key, what=f"fields of {name}")
    missing = sorted(f.name for f in dataclasses.fields(law_class) if f.init
                     and f.default is dataclasses.MISSING and f.name not in arguments)
    if missing:
        raise _KeyError(key, f"{name} needs {', '.join(missing)}")
    if "law" in fields:  # a law wrapping another (Regularised)
        arguments["law"] = _law(_table(arguments, "law", f"{key}.law"), f"{key}.law", kind,
                                own)
    return _build(key, lambda: law_class(**arguments))


def _law_class(name: str, kind: type, key: str, own: dict[str, type]) -> type:
    """The class a law's name gives: built in, allowed in ``own``, or of an imported module."""
    if ":" in name:
        law_class = own.get(name) or _imported(name, key)
    else:
        law_class = getattr(contact_laws, name, None)
    if not (isinstance(law_class, type) and issubclass(law_class, kind)
            and law_class is not kind):
        raise _KeyError(key, f"{name!r} is not a {kind.__name__}; built in: "
                             f"{_law_names(kind)}; or 'module:Class' for a law of one's own")
    if not dataclasses.is_dataclass(law_class):
        raise _KeyError(key, f"{name!r} is not a dataclass; a law is a frozen dataclass "
                             "(see contact_laws.base)")
    return law_class


def _imported(name: str, key: str):
    """What ``"module:Class"`` names in a module already imported; never imports one.

    Attributes are read from the namespaces themselves (``vars``), so that no module or
    class hook runs either.
    """
    module_name, _, qualname = name.partition(":")
    module = sys.modules.get(module_name)
    if module is None:
        raise _KeyError(key, f"{name!r}: module {module_name!r} is not imported, and reading "
                             "a scene file never imports one (that would run its code). "
                             f"To allow it: import {module_name} before reading, or pass "
                             "the class in laws=[...] to scenefile.load or read, or on the "
                             f"command line add --laws {module_name}")
    value: Any = module
    for part in qualname.split("."):
        namespace = getattr(value, "__dict__", None)
        if part not in (namespace or {}):
            raise _KeyError(key, f"{name!r}: module {module_name!r} has no {qualname!r}")
        value = namespace[part]
    return value


def _law_names(kind: type) -> str:
    return ", ".join(sorted(name for name in dir(contact_laws)
                            if isinstance(c := getattr(contact_laws, name), type)
                            and issubclass(c, kind) and c is not kind))


def _excitation(table: dict) -> Excitation:
    _only(table, {"engine_order", "amplitudes", "phases"}, "excitation")
    for name in ("engine_order", "amplitudes"):
        if name not in table:
            raise _KeyError(f"excitation.{name}", "is required")
    phases = table.get("phases", "anti-phase")
    if phases == "anti-phase":
        pattern = AntiPhase()
    elif phases == "engine-order":
        pattern = EngineOrderWave()
    elif isinstance(phases, dict) and set(phases) == {"travelling_wave"}:
        pattern = _build("excitation.phases",
                         lambda: TravellingWave(phases["travelling_wave"]))
    elif isinstance(phases, list):
        pattern = _build("excitation.phases", lambda: ExplicitPhases(tuple(phases)))
    else:
        raise _KeyError("excitation.phases", 'must be "anti-phase", "engine-order", '
                                             "{travelling_wave = nd} or a list of phases "
                                             f"[rad], got {phases!r}")
    amplitudes = table["amplitudes"]
    if not isinstance(amplitudes, list):
        raise _KeyError("excitation.amplitudes", f"must be a list [q0, q1, …] [N], "
                                                 f"got {amplitudes!r}")
    return _build("excitation", lambda: Excitation(engine_order=table["engine_order"],
                                                   amplitudes=tuple(amplitudes),
                                                   phases=pattern))


_METHODS = {"adaptive": (Adaptive, {"rtol", "atol", "max_step"}),
            "fixed": (FixedStep, {"steps_per_period"}),
            "accuracy": (Accuracy, {"target"})}


def _run(table) -> RunSettings:
    table = dict(_as_table(table, "run"))
    method_keys = set().union(*(keys for _, keys in _METHODS.values()))
    _only(table, {"method", "periods", "transient", "samples_per_period", "event_tolerance",
                  "blade"} | method_keys, "run")
    name = table.pop("method", "adaptive")
    if name not in _METHODS:
        raise _KeyError("run.method", f"must be one of {', '.join(map(repr, _METHODS))}, "
                                      f"got {name!r}")
    method_class, keys = _METHODS[name]
    knobs = {k: table.pop(k) for k in list(table) if k in method_keys}
    stray = sorted(set(knobs) - keys)
    if stray:
        raise _KeyError(f"run.{stray[0]}", f"does not apply to method = {name!r}; it takes "
                                           f"{', '.join(sorted(keys))}")
    method = _build("run", lambda: method_class(**knobs))
    return _build("run", lambda: RunSettings(method=method, **table))


# ---- small checks ---------------------------------------------------------------------------

def _only(table: dict, allowed: set, key: str, what: str = "keys") -> None:
    for name in table:
        if name not in allowed:
            where = f"{key}.{name}" if key != "the file" else name
            raise _KeyError(where, f"unknown key; allowed {what}: {', '.join(sorted(allowed))}")


def _as_table(value, key: str, expected: str = "a table") -> dict:
    if not isinstance(value, dict):
        raise _KeyError(key, f"must be {expected}, got {value!r}")
    return value


def _table(table: dict, name: str, key: str) -> dict:
    if name not in table:
        raise _KeyError(key, "is required")
    return _as_table(table[name], key)


def _list(table: dict, name: str, key: str) -> list:
    value = table.get(name, [])
    if not isinstance(value, list):
        raise _KeyError(key, f"must be a list of tables ([[{name}]]), got {value!r}")
    return value


def _number(table: dict, name: str, key: str, low: float = -math.inf) -> float:
    if name not in table:
        raise _KeyError(key, "is required")
    value = table[name]
    if isinstance(value, bool) or not isinstance(value, int | float) or not value >= low:
        raise _KeyError(key, f"must be a number >= {low:g}, got {value!r}" if low > -math.inf
                        else f"must be a number, got {value!r}")
    return float(value)


def _name(entry: dict, key: str):
    if "name" not in entry:
        raise _KeyError(f"{key}.name", "is required")
    return _node(entry, "name", f"{key}.name")


def _node(entry: dict, name: str, key: str):
    value = entry.get(name)
    if isinstance(value, bool) or not isinstance(value, str | int):
        raise _KeyError(key, f"must be a node name (text or integer), got {value!r}")
    return value


def _build(key: str, make):
    """Call ``make``; turn the errors of the objects' own checks into the key's error."""
    try:
        return make()
    except (TypeError, ValueError) as error:
        raise _KeyError(key, str(error)) from None


# ---- writing ------------------------------------------------------------------------------

def document(scene: Scene, run: RunSettings | None = None) -> dict:
    """The document of ``scene`` (and ``run``), which ``read`` turns back into an equal scene.

    It is plain data (TOML- and JSON-compatible): every blade and interface written out.
    """
    group = scene.group
    result: dict[str, Any] = {"speed_rpm": float(scene.speed_rpm),
                              "excitation": _excitation_document(scene.excitation)}
    result["blades"] = [{"name": name, **_blade_document(group.blade(name))}
                        for name in group.blades]
    if group.fixed:
        result["fixed"] = list(group.fixed)
    if group.prescribed:
        result["prescribed"] = [{"name": name, "motion": _motion_document(motion)}
                                for name, motion in group.prescribed]
    result["interfaces"] = [{"left": left, "right": right, "gap": float(i.gap),
                             "angle": float(i.angle), "normal": _law_document(i.normal),
                             **({"friction": _law_document(i.friction)}
                                if i.friction is not None else {})}
                            for left, right, i in group.interfaces]
    if group.couplings:
        result["couplings"] = [{"left": left, "right": right, "stiffness": float(c.stiffness),
                                "damping": float(c.damping)}
                               for left, right, c in group.couplings]
    if "sectors" in group.graph.graph:
        result["sectors"] = int(group.graph.graph["sectors"])
    if run is not None:
        result["run"] = _run_document(run)
    return result


def _blade_document(blade: Blade) -> dict:
    out = {"mass": float(blade.mass), "damping": float(blade.damping)}
    if blade.excitation_scale != 1.0:
        out["excitation_scale"] = float(blade.excitation_scale)
    if blade.frequency is None:
        out["stiffness"] = float(blade.stiffness)
        return out
    model = blade.frequency
    if isinstance(model, ConstantFrequency):
        out["frequency"] = float(model.hz)
    else:
        out["frequency"] = {k: list(v) if isinstance(v, tuple) else float(v)
                            for k, v in dataclasses.asdict(model).items()}
    return out


def _law_document(law) -> dict:
    cls = type(law)
    name = cls.__name__ if getattr(contact_laws, cls.__name__, None) is cls \
        else f"{cls.__module__}:{cls.__qualname__}"
    out: dict[str, Any] = {"law": name}
    for field in dataclasses.fields(law):
        if field.init:
            value = getattr(law, field.name)
            out[field.name] = _law_document(value) if dataclasses.is_dataclass(value) \
                else float(value)
    return out


def _excitation_document(excitation: Excitation) -> dict:
    phases = excitation.phases
    if isinstance(phases, AntiPhase):
        pattern: Any = "anti-phase"
    elif isinstance(phases, TravellingWave):
        pattern = {"travelling_wave": phases.nodal_diameter}
    else:
        pattern = [float(p) for p in phases.values]
    return {"engine_order": excitation.engine_order,
            "amplitudes": [float(q) for q in excitation.amplitudes], "phases": pattern}


def _run_document(run: RunSettings) -> dict:
    name = next(n for n, (cls, _) in _METHODS.items() if isinstance(run.method, cls))
    knobs = {k: v for k, v in dataclasses.asdict(run.method).items() if v is not None}
    return {"method": name, **knobs, "periods": run.periods,
            "transient": run.transient, "samples_per_period": run.samples_per_period,
            "event_tolerance": run.event_tolerance, "blade": run.blade}


def with_value(document: dict, path: str, value: float) -> dict:
    """A copy of ``document`` with the number at the dotted ``path`` set to ``value``.

    ``path`` walks tables by key and lists by index: ``speed_rpm``,
    ``interfaces.0.normal.stiffness``, ``excitation.amplitudes.1``,
    ``group.interface.gap``. An integer stays an integer (``excitation.engine_order``,
    ``run.periods``): ``value`` must then be a whole number. Raises ``SceneFileError`` if
    no number is there, or a fraction is given for an integer.
    """
    copy = _deep_copy(document)
    *parents, last = path.split(".")
    node: Any = copy
    walked = []
    for part in parents + [last]:
        container = node
        try:
            node = node[int(part)] if isinstance(node, list) else node[part]
        except (KeyError, IndexError, ValueError, TypeError):
            raise SceneFileError(f"--param {path}: nothing at {'.'.join(walked + [part])}; "
                                 f"keys there: {_keys(container)}") from None
        walked.append(part)
    if isinstance(node, bool) or not isinstance(node, int | float):
        raise SceneFileError(f"--param {path}: holds {node!r}, not a number")
    new = _like(node, value, path)
    if isinstance(container, list):
        container[int(last)] = new
    else:
        container[last] = new
    return copy


def _like(old: int | float, value: float, path: str) -> int | float:
    """``value`` as the kind of number ``old`` is: an int for an int, else a float."""
    value = float(value)
    if not isinstance(old, int):
        return value
    if not (math.isfinite(value) and value == round(value)):
        raise SceneFileError(f"--param {path}: holds an integer ({old}), so each value must "
                             f"be a whole number, got {value:g}")
    return int(value)


def _keys(container) -> str:
    if isinstance(container, dict):
        return ", ".join(map(str, container))
    if isinstance(container, list):
        return f"indices 0 to {len(container) - 1}"
    return "none (a value, not a table)"


def _deep_copy(value):
    if isinstance(value, dict):
        return {k: _deep_copy(v) for k, v in value.items()}
    if isinstance(value, list):
        return [_deep_copy(v) for v in value]
    return value


@dataclass(frozen=True)
class SceneAt:
    """value ↦ the scene of ``document`` with ``path`` set to value (picklable, for sweeps).

    ``laws`` as for ``load``: the laws of one's own the document may name.
    """

    document: dict
    path: str
    laws: tuple = ()

    def __call__(self, value: float) -> Scene:
        return read(with_value(self.document, self.path, value),
                    source=f"{self.path} = {value:g}", laws=self.laws).scene
