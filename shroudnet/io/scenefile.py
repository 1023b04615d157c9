"""Scene files: a blade group, its excitation and how to run it, in TOML, and back.

A scene file holds one document (SI units; speeds in rev/min)::

    speed_rpm = 6000.0

    [excitation]
    engine_order = 2
    amplitudes = [0.0, 50.0]          # q0, q1, … [N]
    phases = "anti-phase"             # or "engine-order" (ND = l mod N), or
                                      # {travelling_wave = 3}, or [φ1, φ2, …] [rad]
    # blades_on_disc = 36             # with "engine-order": the group is a packet on a
                                      # disc of 36 blades (φ_i = 2π l i / 36)
    # frequency = 210.0               # f [Hz]: forced at f whatever the speed (which
                                      # still sets the stiffening); l Ω/2π without

    [[blades]]                        # one table per blade, in order
    name = "blade1"
    mass = 0.082                      # [kg]
    damping = 4.0                     # [N·s/m]
    frequency = 210.0                 # f_d1 [Hz]; or {f0 = …, coefficient = …} (Southwell);
                                      # or {speeds_rpm = […], frequencies = […]}; or
                                      # stiffness = … [N/m] instead of a frequency
                                      # (0: a node held by couplings or interfaces)
    excitation_scale = 1.0            # s_i, its signed share of Q(t); optional (0: unforced)

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
    method = "adaptive"               # or "fixed" or "exponential" (steps_per_period), or
                                      # "accuracy" (target)
    periods = 400
    transient = 300                   # periods left out of summaries and figures
    blade = "blade2"                  # the blade they are about (with substructures,
                                      # a point's component: see below)

A node may be a linear structure of many degrees of freedom instead (a ``Substructure``,
with named points r_p = Φ_p q): a ``[[blades]]`` table with ``file``, ``modal`` or ``beam``,
or with its matrices inline::

    [[blades]]
    name = "blade1"
    file = "blade.npz"                # M and K from a .npz or .mat file (fe_files); a
                                      # relative path is read from this file's folder
    names = {mass = "M", stiffness = "K"}   # their names in the file (these by default);
                                      # also damping = "C", stiffness_speed = "K1" (K₁ of
                                      # K(Ω) = K₀ + Ω² K₁); optional
    points = {shroud = [[0.0, …], [0.0, …]], load = [0.0, …]}   # Φ_p: d × n, d ≤ 3 [m]
    load = "load"                     # where Q(t) acts: a point of one component, or
                                      # {point = "shroud", direction = [0.0, 1.0]}, or b
                                      # (n numbers); optional (see Substructure.load)
    damping_ratios = 0.002            # modal damping ζ: one, or one per mode; optional
    excitation_scale = 1.0            # s, signed; optional
    reduce = {method = "craig_bampton", boundary = [0, 1], modes = 8}   # optional; or
                                      # {method = "modal_truncation", modes = 8}

    [[blades]]                        # modal data, as an FE modal analysis prints it
    name = "blade2"
    modal = {frequencies = [180.0, {f0 = 420.0, coefficient = 2.0}], masses = [0.05, 0.04]}
                                      # f_k as a blade's frequency above; m_k [kg]
    damping_ratios = 0.005            # required here (0: undamped)
    points = {shroud = [[1.0, 0.3], [0.2, 1.0]], load = [0.8, 0.5]}   # shapes: d × modes

    [[blades]]                        # a clamped beam (beam.cantilever_beam: its keywords);
    name = "blade3"                   # points "shroud" (d = 2, the tip) and "load"
    beam = {length = 0.1, youngs_modulus = 2e11, density = 7800.0, width = 0.02, thickness = 0.004}
    damping_ratios = 0.002            # excitation_scale and reduce as above; optional

    [[interfaces]]                    # an end is then [node, point]; between points of d
    left = ["blade1", "shroud"]       # components, unit directions in the points' frame
    right = ["blade3", "shroud"]      # replace the angle (Interface)
    gap = -2e-6
    normal_direction = [0.8, 0.6]
    tangent_direction = [-0.6, 0.8]
    normal = {law = "LinearSpring", stiffness = 2e5}
                                      # points of d = 3 may slide in the face's plane:
                                      # tangent_directions = [[…], […]] (t₁, t₂) with
                                      # tangential_stiffness = 5e5 (elastic stick, k_t N/m)

An end ``[node, [point, …]]`` joins several points at once, a patch: the other end names as
many (``left = ["blade1", ["R0", "R1"]]``, ``right = ["blade2", ["L0", "L1"]]``), and each
pair is a contact of its own with the interface's laws (``BladeGroup.connect``). Two nodes
may be joined by several interfaces and couplings.

A node's matrices may also be written inline: ``mass = [[…], …]``, ``stiffness``, and
optionally ``damping``, ``stiffness_speed`` (rows of numbers, or ``{shape = [n, n],
rows = […], columns = […], values = […]}`` for a sparse one, indices from 0), with
``points``; that is how ``document`` writes a substructure built in Python. A node read from a
file, built as a beam or reduced is written back as it was given, its file by absolute
path (or relative to ``document``'s ``folder``: ``save`` writes a scene file so). With
substructures, ``[run] blade`` is a component of a point, ``["blade1", "shroud", 0]``, or
a node of one point of one component, or a position in ``Scene.responses`` (0, the
first, by default).

Identical blades may be given once instead, as ``[group]`` with ``shape = "ring"`` or
``"chain"``, ``count``, ``blade = {…}`` and ``interface = {…}``; a bladed disc of
identical sectors (``BladeGroup.bladed_disc``) as ``shape = "bladed_disc"``, ``count``
(sectors), ``disc = {…}`` (a blade table), ``disc_coupling = {stiffness, damping}``,
``blade = [{…}, …]`` (its nodes, root to tip), ``blade_couplings = [{…}, …]`` (one per
blade node) and, optionally, ``interface = {…}`` between neighbouring tips. With
``points = ["L", "R"]`` (or lists of names, patches) a ring's or chain's blades, or a disc's
tips, meet face to face, each turned into a sector frame of its own (``BladeGroup.ring``;
a chain's with ``blades_on_disc``). A blade table's ``frame = [[…], …]`` is its node's
rotation into the group's frame (``BladeGroup.add_blade``), and a top-level
``sectors = N`` declares a group built blade by blade a ring of N sectors
(``BladeGroup.declare_sectors``). A law is named by its
class in ``contact_laws``; its other keys are the law's fields, a law it wraps as that
law's table. ``Regularised`` takes ``exact = {law = "Coulomb", mu = 0.3}`` (its field
``law``, spelled so because ``law`` names the class) and ``velocity``.

A law of one's own is named ``"module:Class"``. Reading a file never imports a module nor
runs any code of its own choosing: the class must come from a module that is already
imported, or be passed in ``laws``::

    import my_laws                                   # the user chooses to run this code
    scenefile.load("group.toml")                     # finds "my_laws:CubicSpring"
    scenefile.load("group.toml", laws=[CubicSpring])  # or allow the classes explicitly

(on the command line: ``shroudnet run group.toml --laws my_laws``).

``[excitation]`` may be left out: no force Q(t) acts (a block driven by a belt alone), and
the period the run counts in is 60/``speed_rpm`` s.

Every key is checked before anything runs: each table declares its keys and what each
holds (a number, an integer, text, a table, a list of numbers, ...), and a bad file raises
``SceneFileError`` naming the file, the key and what is allowed there.
"""

from __future__ import annotations

import dataclasses
import inspect
import json
import math
import os
import re
import sys
import tomllib
import typing
import weakref
from collections.abc import Callable, Iterable
from dataclasses import dataclass
from pathlib import Path
from types import ModuleType
from typing import Any

import numpy as np
import scipy.sparse

import contact_laws
from contact_laws import check_instance, check_int, check_real

from .. import atomic
from ..model import matrix_files as fe_files
from ..model.beam import cantilever_beam
from ..model.blade import Blade, ConstantFrequency, FrequencyTable, Southwell
from ..model.coupling import Coupling
from ..model.excitation import (
    NO_EXCITATION,
    AntiPhase,
    EngineOrderWave,
    Excitation,
    ExplicitPhases,
    TravellingWave,
)
from ..model.group import BladeGroup
from ..model.interface import Interface
from ..model.motion import ConstantVelocity, HarmonicMotion, MotionTable
from ..model.reduction import craig_bampton, modal_truncation
from ..model.scene import Scene
from ..model.substructure import Substructure
from ..run.footprint import check_group_size
from ..run.methods import EVENT_TOLERANCE, TRANSIENT, Accuracy, Adaptive, Exponential, FixedStep


class SceneFileError(ValueError):
    """A scene file that cannot be read: the message names the file, the key and the fix."""


@dataclass(frozen=True, kw_only=True)
class RunSettings:
    """How to run a scene: the ``[run]`` table of a scene file."""

    method: FixedStep | Adaptive | Exponential | Accuracy = Adaptive()
    periods: int = 400
    transient: int = TRANSIENT
    samples_per_period: int = 100
    event_tolerance: float = EVENT_TOLERANCE
    blade: str | int | tuple = 1

    def __post_init__(self):
        if not isinstance(self.method, FixedStep | Adaptive | Exponential | Accuracy):
            raise TypeError(f"run.method must be FixedStep(...), Adaptive(...), "
                            f"Exponential(...) or Accuracy(...), got {self.method!r}")
        for name in ("periods", "samples_per_period"):
            check_int("run", name, getattr(self, name), low=1)
        if isinstance(self.transient, bool) or not isinstance(self.transient, int) \
                or not 0 <= self.transient < self.periods:
            raise ValueError(f"run.transient must be an int in [0, periods = {self.periods}), "
                             f"got {self.transient!r}")
        check_real("run", "event_tolerance", self.event_tolerance, low=0.0, low_open=True,
                   unit="periods")
        blade = self.blade
        if not (_is_name(blade) or isinstance(blade, tuple) and blade
                and all(_is_name(part) for part in blade)):
            raise TypeError(f"run.blade must be a blade's name or position, or (node, point, "
                            f"component), got {blade!r}")


#: What ``laws`` may hold: law classes, or modules whose law classes are allowed.
Laws = Iterable[type | ModuleType]


@dataclass(frozen=True)
class SceneFile:
    """A scene file read: the scene, its run settings and the document they came from
    (with the paths of the matrix files it names made absolute, so that it reads the same
    from any folder)."""

    scene: Scene
    run: RunSettings
    document: dict


def load(path: str | Path, *, laws: Laws = ()) -> SceneFile:
    """Read a scene file; raises ``SceneFileError`` naming the key at fault.

    ``laws``: law classes of one's own (or modules holding them) that the file may name as
    ``"module:Class"``, besides those of modules already imported. Nothing is imported.
    A group too large for any run on this machine is refused before it is built
    (``read``'s ``check_memory``).
    """
    path = Path(path)
    document = _parse(path, _text(path))
    return read(document, source=str(path), laws=laws, folder=path.parent, check_memory=True)


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


def read(document: dict, *, source: str = "scene", laws: Laws = (),
         folder: str | Path | None = None, check_memory: bool = False) -> SceneFile:
    """Build the scene and run settings of a document (a parsed scene file).

    ``laws`` as for ``load``. ``folder``: where the relative paths of matrix files are
    read from (default: the current folder). With ``check_memory``, a group whose counts of
    nodes and interfaces alone make a run too large for this machine's memory
    (``footprint.check_group_size``) is refused, naming the key that gives them, before it
    is built: a scene on its way to a run. Without it (a saved run's scene, read again on
    another machine) the group is built whatever its size.
    """
    own = _own_laws(laws)
    try:
        if not isinstance(document, dict):
            raise _KeyError("the file", "must be a table of keys, got "
                                        f"{type(document).__name__}")
        document = _absolute_files(document, folder)
        scene, run = _scene(document, own, check_memory), _run(document.get("run", {}))
        structure = scene.group.has_substructures
        if "blade" not in document.get("run", {}) and (len(scene.blades) == 1 or structure):
            run = dataclasses.replace(run, blade=0)  # the default, position 1, is not there
        position = scene.response_position if structure else scene.blade_position
        _build("run.blade", lambda: position(run.blade))
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


# ---- what each key holds: one check for every table ----------------------------------------

@dataclass(frozen=True)
class _Kind:
    """What a key of a scene file holds: ``test(value)`` says whether a value is one,
    ``words`` what it must be. ``a | b`` is either."""

    words: str
    test: Callable[[object], bool]

    def __or__(self, other: _Kind) -> _Kind:
        return _Kind(f"{self.words} or {other.words}",
                     lambda value: self.test(value) or other.test(value))


def _is_number(value) -> bool:
    return isinstance(value, int | float) and not isinstance(value, bool)


def _is_name(value) -> bool:
    return isinstance(value, str | int) and not isinstance(value, bool)


def _list_of(test: Callable[[object], bool], empty: bool = True) -> Callable[[object], bool]:
    return lambda value: isinstance(value, list) and (empty or bool(value)) \
        and all(test(item) for item in value)


_NUMBER = _Kind("a number", _is_number)
_INTEGER = _Kind("an integer", lambda value: isinstance(value, int)
                 and not isinstance(value, bool))
_TEXT = _Kind("text", lambda value: isinstance(value, str))
_TABLE = _Kind("a table", lambda value: isinstance(value, dict))
_TABLES = _Kind("a list of tables", _list_of(lambda item: isinstance(item, dict)))
_NUMBERS = _Kind("a list of numbers", _list_of(_is_number))
_MATRIX = _Kind("rows of numbers [[…], …]", _list_of(_list_of(_is_number)))
_INDICES = _Kind("a list of integers", _list_of(_INTEGER.test))
_NAME = _Kind("a node name (text or integer)", _is_name)
_NAMES = _Kind("a list of node names", _list_of(_is_name))
_END = _Kind("a node name (text or integer), [node, point name] or [node, [point name, "
             "…]] (a patch)", lambda value: _is_name(value) or (
                 isinstance(value, list) and len(value) == 2 and _is_name(value[0])
                 and (isinstance(value[1], str) and bool(value[1])
                      or _list_of(lambda name: isinstance(name, str) and bool(name),
                                  empty=False)(value[1]))))
_FACES = _Kind("[left face, right face], each a point's name or a list of names",
               lambda value: isinstance(value, list) and len(value) == 2 and all(
                   isinstance(face, str) and bool(face)
                   or _list_of(lambda name: isinstance(name, str), empty=False)(face)
                   for face in value))
_RESPONSE = _Kind("a blade name or position, or [node, point, component]", lambda value:
                  _is_name(value) or _list_of(_is_name, empty=False)(value))
_DIRECTION_LIST = _Kind("a list of one or two directions [[…], …]",
                        _list_of(_NUMBERS.test, empty=False))
_FREQUENCY = _NUMBER | _TABLE
_LAW = _Kind("a law's table {law = …, …}", _TABLE.test)


def _only(table: dict, allowed: dict[str, _Kind], key: str, what: str = "keys") -> None:
    """Check that every key of ``table`` is one ``allowed`` names and holds what it says
    (those required are read with ``_required``)."""
    for name, value in table.items():
        where = f"{key}.{name}" if key != "the file" else name
        if name not in allowed:
            raise _KeyError(where, f"unknown key; allowed {what}: {', '.join(sorted(allowed))}")
        _expect(value, allowed[name], where)


def _choice(value, choices: dict, key: str) -> str:
    """``value`` if it is one of the names ``choices`` holds, else the key's error."""
    if not isinstance(value, str) or value not in choices:
        raise _KeyError(key, f"must be one of {', '.join(map(repr, choices))}, got "
                             f"{_short(value)}")
    return value


def _expect(value, kind: _Kind, key: str):
    """``value`` if it is of ``kind``, else the key's error saying what it must be."""
    if not kind.test(value):
        raise _KeyError(key, f"must be {kind.words}, got {_short(value)}")
    return value


_TOP = {"speed_rpm": _NUMBER, "excitation": _TABLE, "blades": _TABLES, "fixed": _NAMES,
        "prescribed": _TABLES, "interfaces": _TABLES, "couplings": _TABLES,
        "sectors": _INTEGER, "group": _TABLE, "run": _TABLE}


def _scene(document: dict, own: dict[str, type], fits: bool) -> Scene:
    _only(document, _TOP, "the file")
    if "group" in document and ("blades" in document or "interfaces" in document):
        raise _KeyError("group", "give either [group] or [[blades]] and [[interfaces]], "
                                 "not both")
    for key in ("couplings", "prescribed"):
        if "group" in document and key in document:
            raise _KeyError(key, f"give {key} with [[blades]], not with [group]")
    group = _shorthand(document["group"], own, fits) if "group" in document \
        else _explicit(document, own, fits)
    if "sectors" in document:
        sectors = document["sectors"]
        if isinstance(sectors, bool) or not isinstance(sectors, int) or sectors < 1 \
                or len(group.blades) % sectors:
            raise _KeyError("sectors", f"must be a whole number >= 1 that divides the "
                                       f"{len(group.blades)} blades, got {sectors!r}")
        group.declare_sectors(sectors)
    excitation = _excitation(_table(document, "excitation", "excitation")) \
        if "excitation" in document else NO_EXCITATION
    speed = _number(document, "speed_rpm", "speed_rpm", low=0.0)
    return _build("the scene", lambda: Scene(group=group, excitation=excitation,
                                             speed_rpm=speed))


def _explicit(document: dict, own: dict[str, type], fits: bool) -> BladeGroup:
    group = BladeGroup()
    blades = _list(document, "blades", "blades")
    if not blades:
        raise _KeyError("blades", "a group needs at least one blade")
    if fits:
        _fits("blades", len(blades) + len(_list(document, "prescribed", "prescribed")),
              sum(contact_count(entry) if isinstance(entry, dict) else 1
                  for entry in _list(document, "interfaces", "interfaces")))
    for i, entry in enumerate(blades):
        key = f"blades[{i}]"
        entry = _as_table(entry, key)
        name = _name(entry, key)
        frame = _expect(entry["frame"], _MATRIX, f"{key}.frame") if "frame" in entry else None
        blade = _body({k: v for k, v in entry.items() if k not in ("name", "frame")}, key)
        _build(key, lambda: group.add_blade(name, blade, frame))
    for i, name in enumerate(document.get("fixed", [])):
        _build(f"fixed[{i}]", lambda: group.add_fixed(name))
    for i, entry in enumerate(_list(document, "prescribed", "prescribed")):
        key = f"prescribed[{i}]"
        entry = _as_table(entry, key)
        _only(entry, {"name": _NAME, "motion": _TABLE}, key)
        name = _name(entry, key)
        motion = _motion(_table(entry, "motion", f"{key}.motion"), f"{key}.motion")
        _build(key, lambda: group.add_prescribed(name, motion))
    for i, entry in enumerate(document.get("interfaces", [])):
        key = f"interfaces[{i}]"
        entry = _as_table(entry, key)
        _only(entry, _ENDS | _INTERFACE_KEYS, key)
        left, right = (_end(entry, end, f"{key}.{end}") for end in ("left", "right"))
        interface = _interface({k: v for k, v in entry.items() if k not in ("left", "right")},
                               key, own)
        _build(key, lambda: group.connect(left, right, interface))
    for i, entry in enumerate(_list(document, "couplings", "couplings")):
        key = f"couplings[{i}]"
        entry = _as_table(entry, key)
        _only(entry, _ENDS | _COUPLING_KEYS, key)
        left, right = (_end(entry, end, f"{key}.{end}") for end in ("left", "right"))
        coupling = _coupling({k: v for k, v in entry.items() if k not in ("left", "right")},
                             key)
        _build(key, lambda: group.connect(left, right, coupling))
    return group


def _shorthand(table, own: dict[str, type], fits: bool) -> BladeGroup:
    table = _as_table(table, "group")
    shape = _choice(table.get("shape"), dict.fromkeys(("ring", "chain", "bladed_disc")),
                    "group.shape")
    if shape == "bladed_disc":
        return _bladed_disc(table, own, fits)
    _only(table, {"shape": _TEXT, "count": _INTEGER, "blade": _TABLE, "interface": _TABLE,
                  "points": _FACES, "blades_on_disc": _INTEGER}, "group")
    if "blades_on_disc" in table and (shape != "chain" or "points" not in table):
        raise _KeyError("group.blades_on_disc", "turns the blades of a chain given its "
                                                "points; give it with shape = \"chain\" and "
                                                "points")
    count = table.get("count")
    if isinstance(count, bool) or not isinstance(count, int) or count < (3 if shape == "ring"
                                                                          else 1):
        raise _KeyError("group.count", f"must be an integer >= {3 if shape == 'ring' else 1} "
                                       f"for a {shape}, got {count!r}")
    if fits:
        _fits("group.count", count, count if shape == "ring" else count - 1)
    blade = _body(_table(table, "blade", "group.blade"), "group.blade")
    interface = _interface(_table(table, "interface", "group.interface"), "group.interface",
                           own)
    faces = _faces(table)
    if shape == "ring":
        return _build("group", lambda: BladeGroup.ring(count, blade, interface, points=faces))
    return _build("group", lambda: BladeGroup.chain(
        count, blade, interface, points=faces, blades_on_disc=table.get("blades_on_disc")))


def _faces(table: dict):
    """``[group]``'s points: (left face, right face), each a name or a tuple of names."""
    if "points" not in table:
        return None
    return tuple(tuple(face) if isinstance(face, list) else face for face in table["points"])


def _bladed_disc(table, own: dict[str, type], fits: bool) -> BladeGroup:
    """``BladeGroup.bladed_disc`` from [group] with shape = "bladed_disc"."""
    _only(table, {"shape": _TEXT, "count": _INTEGER, "disc": _TABLE, "disc_coupling": _TABLE,
                  "blade": _TABLES, "blade_couplings": _TABLES, "interface": _TABLE,
                  "points": _FACES}, "group")
    count = table.get("count")
    if isinstance(count, bool) or not isinstance(count, int) or count < 3:
        raise _KeyError("group.count", f"must be an integer >= 3 sectors, got {count!r}")
    if fits:
        _fits("group.count", count * (1 + len(_list(table, "blade", "group.blade"))),
              count if "interface" in table else 0)
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
                                                         couplings, shroud,
                                                         points=_faces(table)))


#: The ``kind`` of a prescribed motion in a file, its class and its keys.
_MOTIONS = {"constant_velocity": (ConstantVelocity, dict.fromkeys(("velocity", "position"),
                                                                   _NUMBER)),
            "harmonic": (HarmonicMotion, dict.fromkeys(("amplitude", "frequency", "phase"),
                                                       _NUMBER)),
            "table": (MotionTable, dict.fromkeys(("times", "displacements"), _NUMBERS))}


def _motion(table: dict, key: str):
    kind = _choice(table.get("kind"), _MOTIONS, f"{key}.kind")
    cls, keys = _MOTIONS[kind]
    _only(table, {"kind": _TEXT} | keys, key)
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
    _only(table, _COUPLING_KEYS, key)
    stiffness = _number(table, "stiffness", f"{key}.stiffness")
    damping = _number(table, "damping", f"{key}.damping") if "damping" in table else 0.0
    return _build(key, lambda: Coupling(stiffness=stiffness, damping=damping))


_BLADE_KEYS = {"mass": _NUMBER, "damping": _NUMBER, "frequency": _FREQUENCY,
               "stiffness": _NUMBER, "excitation_scale": _NUMBER}
_COUPLING_KEYS = {"stiffness": _NUMBER, "damping": _NUMBER}
_ENDS = {"left": _END, "right": _END}


def _blade(table: dict, key: str) -> Blade:
    _only(table, _BLADE_KEYS, key)
    if ("frequency" in table) == ("stiffness" in table):
        raise _KeyError(key, "give a blade either frequency [Hz] or stiffness [N/m]")
    arguments = {"mass": _number(table, "mass", f"{key}.mass"),
                 "damping": _number(table, "damping", f"{key}.damping")}
    if "excitation_scale" in table:
        arguments["excitation_scale"] = _number(table, "excitation_scale",
                                                f"{key}.excitation_scale")
    if "stiffness" in table:
        arguments["stiffness"] = _number(table, "stiffness", f"{key}.stiffness")
    else:
        arguments["frequency"] = _frequency(table["frequency"], f"{key}.frequency")
    return _build(key, lambda: Blade(**arguments))


#: A speed-dependent frequency by the keys of its table: its model and what each key holds.
_FREQUENCY_MODELS = {frozenset({"f0", "coefficient"}): (Southwell, _NUMBER),
                     frozenset({"speeds_rpm", "frequencies"}): (FrequencyTable, _NUMBERS)}


def _frequency(value, key):
    if isinstance(value, int | float) and not isinstance(value, bool):
        return _build(key, lambda: ConstantFrequency(hz=float(value)))
    value = _as_table(value, key, "a number [Hz] or a table")
    if frozenset(value) not in _FREQUENCY_MODELS:
        raise _KeyError(key, "must be a number [Hz], {f0, coefficient} (Southwell's law) or "
                             f"{{speeds_rpm, frequencies}} (a table), got keys {sorted(value)}")
    model, what = _FREQUENCY_MODELS[frozenset(value)]
    _only(value, dict.fromkeys(value, what), key)
    return _build(key, lambda: model(**{k: tuple(v) if isinstance(v, list) else v
                                        for k, v in value.items()}))


# ---- substructures: nodes of many degrees of freedom ---------------------------------------

#: How a node of many degrees of freedom is given: its key, and the keys each way takes.
_STRUCTURE_COMMON = {"points": _TABLE, "load": _TEXT | _TABLE | _NUMBERS,
                     "damping_ratios": _NUMBER | _NUMBERS, "excitation_scale": _NUMBER}
_MATRICES = ("mass", "stiffness", "damping", "stiffness_speed")
_STRUCTURE_KEYS = {
    "file": {"file": _TEXT, "names": _TABLE, "reduce": _TABLE} | _STRUCTURE_COMMON,
    "matrices": dict.fromkeys(_MATRICES, _MATRIX | _TABLE) | {"reduce": _TABLE}
    | _STRUCTURE_COMMON,
    "modal": {"modal": _TABLE} | _STRUCTURE_COMMON,
    "beam": {"beam": _TABLE, "damping_ratios": _NUMBER | _NUMBERS,
             "excitation_scale": _NUMBER, "reduce": _TABLE},
}
#: The keywords of ``cantilever_beam`` that a ``beam`` table holds (the rest are the node's):
#: numbers, but for the count of elements and the two second moments of area.
_BEAM_KEYS = {name: {"elements": _INTEGER, "second_moments": _NUMBERS}.get(name, _NUMBER)
              for name in inspect.signature(cantilever_beam).parameters
              if name not in ("damping_ratios", "excitation_scale")}
_REDUCTIONS = {"craig_bampton": {"method": _TEXT, "boundary": _INDICES, "modes": _INTEGER},
               "modal_truncation": {"method": _TEXT, "modes": _INTEGER}}

#: What a substructure read from a file was given as (its table, the file's path made
#: absolute), so that ``document`` writes it back so: by the substructure, which is frozen
#: and compared by identity, for as long as it lives.
_GIVEN_AS: weakref.WeakKeyDictionary = weakref.WeakKeyDictionary()


def is_substructure(entry) -> bool:
    """Whether a ``[[blades]]`` table of a document gives a ``Substructure`` (a node of
    many degrees of freedom) rather than a ``Blade``."""
    return isinstance(entry, dict) and (any(key in entry for key in (
        "file", "modal", "beam", "points")) or isinstance(entry.get("mass"), list | dict))


def _body(table: dict, key: str) -> Blade | Substructure:
    """The ``Blade`` or ``Substructure`` a node's table (its name left out) gives."""
    return _substructure(table, key) if is_substructure(table) else _blade(table, key)


def _structure_kind(table: dict, key: str) -> str:
    given = [name for name in ("file", "modal", "beam") if name in table]
    if isinstance(table.get("mass"), list | dict):
        given.append("mass")
    if len(given) > 1:
        raise _KeyError(key, "give a node one of file, modal, beam or its matrices inline "
                             f"(mass = [[…], …]), not {' and '.join(given)}")
    return "matrices" if given in ([], ["mass"]) else given[0]


def _substructure(table: dict, key: str) -> Substructure:
    kind = _structure_kind(table, key)
    _only(table, _STRUCTURE_KEYS[kind], key, what=f"keys of a node given by {kind}")
    options = {}
    if "damping_ratios" in table:
        options["damping_ratios"] = _one_or_list(table["damping_ratios"],
                                                 f"{key}.damping_ratios")
    if "excitation_scale" in table:
        options["excitation_scale"] = _number(table, "excitation_scale",
                                              f"{key}.excitation_scale")
    if kind == "beam":
        body = _beam(_table(table, "beam", f"{key}.beam"), f"{key}.beam", options)
    else:
        points = _points(table, key)
        load = _load(table, key, points)
        if kind == "modal":
            return _modal(table, key, points, load, options)
        matrices = _file_matrices(table, key) if kind == "file" else {
            name: _matrix(table, name, f"{key}.{name}") for name in _MATRICES
            if name in table or name in ("mass", "stiffness")}
        body = _build(key, lambda: Substructure(**matrices, points=points, load=load,
                                                **options))
    if "reduce" in table:
        body = _reduce(body, _as_table(table["reduce"], f"{key}.reduce"), f"{key}.reduce")
    if kind != "matrices" or "reduce" in table:
        _GIVEN_AS[body] = _deep_copy(table)
    return body


def _file_matrices(table: dict, key: str) -> dict:
    """M, K (and C, K₁ where named) read from the node's ``file``."""
    path = table["file"]
    if not isinstance(path, str) or not path:
        raise _KeyError(f"{key}.file", f"must be the path of a .npz or .mat file, got "
                                       f"{_short(path)}")
    names = table.get("names", {})
    _only(names, dict.fromkeys(_MATRICES, _Kind("the name of a matrix in the file",
                                                _TEXT.test)), f"{key}.names", what="matrices")
    try:
        read = fe_files.read_matrices(path, **names)
    except FileNotFoundError:
        raise _KeyError(f"{key}.file", f"no such file: {path} (a relative path is read "
                                       "from the scene file's folder)") from None
    except (TypeError, ValueError) as error:
        raise _KeyError(f"{key}.file", str(error)) from None
    except OSError as error:
        raise _KeyError(f"{key}.file", f"{path}: cannot be read: "
                                       f"{error.strerror or error}") from None
    return {name: getattr(read, name) for name in _MATRICES if getattr(read, name) is not None}


def _matrix(table: dict, name: str, key: str):
    """A matrix written inline: rows of numbers, or a sparse one as index triplets."""
    if name not in table:
        raise _KeyError(key, "is required: a matrix [[…], …] (or give the node file, modal or "
                             "beam)")
    value = table[name]
    if not isinstance(value, dict):
        return _numbers(value, key, "rows of numbers [[…], …]")
    _only(value, dict.fromkeys(("shape", "rows", "columns", "values"), _NUMBERS), key)
    parts = {part: _numbers(_required(value, part, f"{key}.{part}"), f"{key}.{part}",
                            "a list of numbers") for part in ("shape", "rows", "columns", "values")}
    indices = [parts[part] for part in ("shape", "rows", "columns")]
    if any(p.ndim != 1 or np.any(p != np.round(p)) or np.any(p < 0) for p in indices) \
            or len(parts["shape"]) != 2 or not len(parts["rows"]) == len(parts["columns"]) \
            == len(parts["values"]):
        raise _KeyError(key, "a sparse matrix is {shape = [n, n], rows = […], columns = […], "
                             "values = […]}: whole numbers from 0, one row, column and value "
                             "per entry")
    shape, rows, columns = (p.astype(np.int64) for p in indices)
    return _build(key, lambda: scipy.sparse.coo_array(
        (parts["values"], (rows, columns)), shape=tuple(shape)).tocsr())


def _points(table: dict, key: str) -> dict[str, np.ndarray]:
    points = _table(table, "points", f"{key}.points")
    return {name: _numbers(value, f"{key}.points.{name}", "a d × n matrix [[…], …] or a "
                                                          "vector [m]")
            for name, value in points.items()}


def _load(table: dict, key: str, points: dict):
    """The ``load`` of a substructure: a point's name, (point, direction) or the vector b."""
    if "load" not in table:
        return None
    value, where = table["load"], f"{key}.load"
    if isinstance(value, list):
        return _vector(value, where)
    if isinstance(value, dict):
        _only(value, {"point": _TEXT, "direction": _NUMBERS}, where)
        point = value.get("point")
        direction = tuple(_vector(_required(value, "direction", f"{where}.direction"),
                                  f"{where}.direction"))
    elif isinstance(value, str):
        point, direction = value, None
    else:
        raise _KeyError(where, "must be a point's name, {point = …, direction = […]} or the "
                               f"load vector [b_1, …, b_n], got {_short(value)}")
    if point not in points:
        raise _KeyError(where, f"names the unknown point {point!r}; the points are "
                               f"{sorted(points)}")
    return point if direction is None else (point, direction)


def _modal(table: dict, key: str, points: dict, load, options: dict) -> Substructure:
    modal = _table(table, "modal", f"{key}.modal")
    _only(modal, {"frequencies": _Kind("a list, one frequency per mode [Hz]",
                                       _list_of(_FREQUENCY.test)),
                  "masses": _NUMBER | _NUMBERS}, f"{key}.modal")
    frequencies = _required(modal, "frequencies", f"{key}.modal.frequencies")
    models = [_frequency(value, f"{key}.modal.frequencies[{k}]")
              for k, value in enumerate(frequencies)]
    masses = _required(modal, "masses", f"{key}.modal.masses")
    masses = _one_or_list(masses, f"{key}.modal.masses")
    if "damping_ratios" not in options:
        raise _KeyError(f"{key}.damping_ratios", "is required with modal data (0: undamped)")
    return _build(key, lambda: Substructure.modal(
        models, options["damping_ratios"], masses, points, load=load,
        excitation_scale=options.get("excitation_scale", 1.0)))


def _beam(table: dict, key: str, options: dict) -> Substructure:
    _only(table, _BEAM_KEYS, key, what="keywords of beam.cantilever_beam")
    needed = sorted(name for name, parameter in
                    inspect.signature(cantilever_beam).parameters.items()
                    if parameter.default is inspect.Parameter.empty and name not in table)
    if needed:
        raise _KeyError(key, f"cantilever_beam needs {', '.join(needed)}")
    arguments = {name: tuple(value) if isinstance(value, list) else value
                 for name, value in table.items()}
    return _build(key, lambda: cantilever_beam(**arguments, **options))


def _reduce(body: Substructure, table: dict, key: str) -> Substructure:
    """``body`` reduced as ``table`` says: Craig–Bampton or modal truncation."""
    method = _choice(table.get("method"), _REDUCTIONS, f"{key}.method")
    _only(table, _REDUCTIONS[method], key, what=f"keys of {method}")
    if body.damping is not None:
        raise _KeyError(key, "a reduction takes modal damping (damping_ratios), not a "
                             "damping matrix")
    modes = _required(table, "modes", f"{key}.modes")
    options = dict(damping_ratios=body.damping_ratios, points=dict(body.points),
                   load=body.load, excitation_scale=body.excitation_scale,
                   stiffness_speed=body.stiffness_speed)
    if method == "modal_truncation":
        return _build(key, lambda: modal_truncation(body.mass, body.stiffness, modes,
                                                    **options))
    boundary = _required(table, "boundary", f"{key}.boundary")
    return _build(key, lambda: craig_bampton(body.mass, body.stiffness, boundary, modes,
                                             **options))


def _one_or_list(value, key: str) -> float | tuple[float, ...]:
    """One number (for every mode), or a list of numbers (one per mode)."""
    if isinstance(value, list):
        return tuple(float(v) for v in _vector(value, key))
    return _number({"value": value}, "value", key)


def _vector(value, key: str) -> np.ndarray:
    array = _numbers(value, key, "a list of numbers")
    if array.ndim != 1:
        raise _KeyError(key, f"must be a list of numbers, got {_short(value)}")
    return array


def _numbers(value, key: str, expected: str) -> np.ndarray:
    """``value`` (numbers, or nested lists of them, rectangular) as a float array."""
    def numbers(item) -> bool:
        if isinstance(item, list):
            return all(numbers(v) for v in item)
        return isinstance(item, int | float) and not isinstance(item, bool)
    if not isinstance(value, list) or not numbers(value):
        raise _KeyError(key, f"must be {expected}, got {_short(value)}")
    try:
        return np.array(value, dtype=float)
    except ValueError:
        raise _KeyError(key, f"must be {expected}, with rows of one length") from None


def _required(table: dict, name: str, key: str):
    if name not in table:
        raise _KeyError(key, "is required")
    return table[name]


def _short(value) -> str:
    text = repr(value)
    return text if len(text) <= 80 else text[:77] + "..."


def _absolute_files(document: dict, folder) -> dict:
    """``document``, its nodes' ``file`` paths made absolute (relative ones are in
    ``folder``); the document itself if it names no file."""
    blades = document.get("blades")
    if not isinstance(blades, list) or not any(
            isinstance(entry, dict) and isinstance(entry.get("file"), str) and entry["file"]
            for entry in blades):
        return document
    base = Path(folder) if folder is not None else Path()
    copy = dict(document)
    copy["blades"] = [{**entry, "file": os.path.abspath(base / entry["file"])}
                      if isinstance(entry, dict) and isinstance(entry.get("file"), str)
                      and entry["file"] else entry for entry in blades]
    return copy


_DIRECTIONS = ("normal_direction", "tangent_direction")
_INTERFACE_KEYS = {"gap": _NUMBER, "angle": _NUMBER, "normal": _TABLE, "friction": _TABLE,
                   "tangent_directions": _DIRECTION_LIST, "tangential_stiffness": _NUMBER,
                   **dict.fromkeys(_DIRECTIONS, _NUMBERS)}


def _interface(table: dict, key: str, own: dict[str, type]) -> Interface:
    _only(table, _INTERFACE_KEYS, key)
    normal = _law(_table(table, "normal", f"{key}.normal"), f"{key}.normal",
                  contact_laws.NormalLaw, own)
    friction = None
    if "friction" in table:
        friction = _law(_table(table, "friction", f"{key}.friction"), f"{key}.friction",
                        contact_laws.FrictionLaw, own)
    gap = _number(table, "gap", f"{key}.gap")
    elastic = {}
    if "tangential_stiffness" in table:
        elastic["tangential_stiffness"] = _number(table, "tangential_stiffness",
                                                  f"{key}.tangential_stiffness")
    if not any(name in table for name in (*_DIRECTIONS, "tangent_directions")):
        angle = _number(table, "angle", f"{key}.angle")
        return _build(key, lambda: Interface(gap=gap, angle=angle, normal=normal,
                                             friction=friction, **elastic))
    directions = {}
    if "normal_direction" not in table:
        raise _KeyError(f"{key}.normal_direction", "is required with the tangent "
                                                   "direction(s) (or give angle instead)")
    directions["normal_direction"] = tuple(_vector(table["normal_direction"],
                                                   f"{key}.normal_direction"))
    if "tangent_directions" in table:
        planes = table["tangent_directions"]
        directions["tangent_directions"] = tuple(
            tuple(_vector(t, f"{key}.tangent_directions[{k}]")) for k, t in enumerate(planes))
    if "tangent_direction" in table or "tangent_directions" not in table:
        if "tangent_direction" not in table:
            raise _KeyError(f"{key}.tangent_direction", "is required with the other "
                                                        "direction (or give angle instead "
                                                        "of both)")
        directions["tangent_direction"] = tuple(_vector(table["tangent_direction"],
                                                        f"{key}.tangent_direction"))
    angle = _number(table, "angle", f"{key}.angle") if "angle" in table else None
    return _build(key, lambda: Interface(gap=gap, angle=angle, normal=normal,
                                         friction=friction, **directions, **elastic))


#: A law's fields a file spells otherwise: ``law`` names the law's class there, so the law
#: that ``Regularised`` (or a law of one's own) wraps in its field ``law`` is ``exact``.
_FIELD_KEYS = {"law": "exact"}


def _law(table: dict, key: str, kind: type, own: dict[str, type]):
    name = table.get("law")
    if not isinstance(name, str):
        raise _KeyError(f"{key}.law", f"must name a {kind.__name__} ({_law_names(kind)}), "
                                      f"got {_short(name)}")
    law_class = _law_class(name, kind, f"{key}.law", own)
    fields = _law_fields(law_class, kind)
    given = {k: v for k, v in table.items() if k != "law"}
    _only(given, {file_key: what for file_key, (_, what, _) in fields.items()}, key,
          what=f"fields of {name}")
    missing = sorted(file_key for file_key, (field, _, _) in fields.items()
                     if file_key not in given and _required_field(law_class, field))
    if missing:
        raise _KeyError(key, f"{name} needs {', '.join(missing)}")
    arguments = {}
    for file_key, value in given.items():
        field, _, contract = fields[file_key]
        arguments[field] = _law(value, f"{key}.{file_key}", contract, own) \
            if isinstance(value, dict) else value
    return _build(key, lambda: law_class(**arguments))


def _law_fields(law_class: type, kind: type) -> dict[str, tuple[str, _Kind, type]]:
    """A law's fields by the keys a file gives them: (field, what the key holds, the
    contract of the law it holds if a table). A field is a number, or where it is
    annotated as a law (``Regularised.law``), the table of that law; where annotations
    cannot be resolved here, either (a table read as a law of ``kind``)."""
    try:
        hints = typing.get_type_hints(law_class)
    except (NameError, TypeError, AttributeError):  # a law of one's own, annotated so
        hints = {}
    fields = {}
    for field in dataclasses.fields(law_class):
        if not field.init:
            continue
        hint = hints.get(field.name)
        contract = next((c for c in (contact_laws.NormalLaw, contact_laws.FrictionLaw)
                         if isinstance(hint, type) and issubclass(hint, c)), None)
        what = _LAW if contract else _NUMBER if hint is not None else _NUMBER | _LAW
        fields[_FIELD_KEYS.get(field.name, field.name)] = (field.name, what, contract or kind)
    return fields


def _required_field(law_class: type, name: str) -> bool:
    field = next(f for f in dataclasses.fields(law_class) if f.name == name)
    return field.default is dataclasses.MISSING and field.default_factory is dataclasses.MISSING


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
    _only(table, {"engine_order": _INTEGER, "amplitudes": _NUMBERS,
                  "phases": _TEXT | _TABLE | _NUMBERS, "blades_on_disc": _INTEGER,
                  "frequency": _NUMBER}, "excitation")
    for name in ("engine_order", "amplitudes"):
        if name not in table:
            raise _KeyError(f"excitation.{name}", "is required")
    phases = table.get("phases", "anti-phase")
    if "blades_on_disc" in table and phases != "engine-order":
        raise _KeyError("excitation.blades_on_disc", 'goes with phases = "engine-order" '
                                                     f"only, got phases = {phases!r}")
    if phases == "anti-phase":
        pattern = AntiPhase()
    elif phases == "engine-order":
        pattern = _build("excitation.blades_on_disc",
                         lambda: EngineOrderWave(table.get("blades_on_disc")))
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
    return _build("excitation", lambda: Excitation(engine_order=table["engine_order"],
                                                   amplitudes=tuple(amplitudes),
                                                   phases=pattern,
                                                   frequency=table.get("frequency")))


_METHODS = {"adaptive": (Adaptive, dict.fromkeys(("rtol", "atol", "max_step"), _NUMBER)),
            "fixed": (FixedStep, {"steps_per_period": _INTEGER}),
            "exponential": (Exponential, {"steps_per_period": _INTEGER}),
            "accuracy": (Accuracy, {"target": _NUMBER})}
_RUN_KEYS = {"method": _TEXT, "periods": _INTEGER, "transient": _INTEGER,
             "samples_per_period": _INTEGER, "event_tolerance": _NUMBER, "blade": _RESPONSE}


def _run(table) -> RunSettings:
    table = dict(_as_table(table, "run"))
    method_keys = {k: what for _, keys in _METHODS.values() for k, what in keys.items()}
    _only(table, _RUN_KEYS | method_keys, "run")
    name = _choice(table.pop("method", "adaptive"), _METHODS, "run.method")
    method_class, keys = _METHODS[name]
    knobs = {k: table.pop(k) for k in list(table) if k in method_keys}
    stray = sorted(set(knobs) - set(keys))
    if stray:
        raise _KeyError(f"run.{stray[0]}", f"does not apply to method = {name!r}; it takes "
                                           f"{', '.join(sorted(keys))}")
    method = _build("run", lambda: method_class(**knobs))
    if isinstance(table.get("blade"), list):  # a point's component: [node, point, k]
        table["blade"] = tuple(table["blade"])
    return _build("run", lambda: RunSettings(method=method, **table))


def _as_table(value, key: str, expected: str = "a table") -> dict:
    return _expect(value, _TABLE if expected == "a table" else _Kind(expected, _TABLE.test), key)


def _table(table: dict, name: str, key: str) -> dict:
    return _expect(_required(table, name, key), _TABLE, key)


def _list(table: dict, name: str, key: str) -> list:
    return _expect(table.get(name, []), _TABLES, key)


def _number(table: dict, name: str, key: str, low: float = -math.inf) -> float:
    value = _expect(_required(table, name, key), _NUMBER, key)
    if not value >= low:
        raise _KeyError(key, f"must be a number >= {low:g}, got {value!r}")
    return float(value)


def _name(entry: dict, key: str):
    return _expect(_required(entry, "name", f"{key}.name"), _NAME, f"{key}.name")


def _end(entry: dict, name: str, key: str):
    """An edge's end: a node's name, ``[node, point]`` (a point of a substructure), or
    ``[node, [point, …]]`` (a patch's points)."""
    value = _expect(entry.get(name), _END, key)
    if not isinstance(value, list):
        return value
    node, point = value
    return node, tuple(point) if isinstance(point, list) else point


def contact_count(entry) -> int:
    """The contacts an ``[[interfaces]]`` entry makes: the points of its patch, else 1."""
    sizes = [len(end[1]) for end in (entry.get("left"), entry.get("right"))
             if isinstance(end, list) and len(end) == 2 and isinstance(end[1], list)]
    return max(sizes, default=1)


def _fits(key: str, nodes: int, interfaces: int) -> None:
    """Refuse, naming ``key``, a group whose counts of nodes (a lower bound with
    substructures: each holds one coordinate at least) and interfaces alone make a run too
    large for this machine's memory (``footprint.check_group_size``): told now, before a
    minute and gigabytes are spent building a group that no run could take."""
    try:
        check_group_size(nodes, interfaces)
    except ValueError as error:
        raise _KeyError(key, f"{error}; give fewer blades") from None


def _build(key: str, make):
    """Call ``make``; turn the errors of the objects' own checks into the key's error."""
    try:
        return make()
    except (TypeError, ValueError) as error:
        raise _KeyError(key, str(error)) from None
    except OverflowError as error:  # a number too large for what is made of it
        raise _KeyError(key, f"a number there is too large to compute with ({error})") \
            from None


# ---- writing ------------------------------------------------------------------------------

def document(scene: Scene, run: RunSettings | None = None, *,
             folder: str | Path | None = None) -> dict:
    """The document of ``scene`` (and ``run``), which ``read`` turns back into an equal scene.

    It is plain data (TOML- and JSON-compatible): every blade and interface written out. A
    substructure read from a scene file's ``file``, ``beam`` or ``reduce`` is written as it
    was given, its file by its absolute path, or relative to ``folder`` if given (where the
    document will be saved); any other substructure with its matrices, or its modal data,
    inline (a reduction's basis is not kept).
    """
    check_instance("scenefile.document", "scene", scene, Scene, expected="a shroudnet.Scene")
    check_instance("scenefile.document", "run", run, RunSettings, optional=True,
                   expected="scenefile.RunSettings(...) or None")
    check_instance("scenefile.document", "folder", folder, (str, os.PathLike), optional=True,
                   expected="a folder (str or pathlib.Path) or None")
    group = scene.group
    result: dict[str, Any] = {"speed_rpm": float(scene.speed_rpm),
                              "excitation": _excitation_document(scene.excitation)}
    result["blades"] = [{"name": name, **_body_document(group.blade(name), folder)}
                        | _frame_document(group.frame(name)) for name in group.blades]
    if group.fixed:
        result["fixed"] = list(group.fixed)
    if group.prescribed:
        result["prescribed"] = [{"name": name, "motion": _motion_document(motion)}
                                for name, motion in group.prescribed]
    result["interfaces"] = [
        {"left": _end_document(left, ends[0]), "right": _end_document(right, ends[1]),
         **_interface_document(i)}
        for (left, right, i), ends in zip(group.interfaces, group.edge_points("interface"))]
    if group.couplings:
        result["couplings"] = [
            {"left": _end_document(left, ends[0]), "right": _end_document(right, ends[1]),
             "stiffness": float(c.stiffness), "damping": float(c.damping)}
            for (left, right, c), ends in zip(group.couplings, group.edge_points("coupling"))]
    if "sectors" in group.graph.graph:
        result["sectors"] = int(group.graph.graph["sectors"])
    if run is not None:
        result["run"] = _run_document(run)
    return result


def _frame_document(frame) -> dict:
    return {} if frame is None else {"frame": np.asarray(frame, dtype=float).tolist()}


def _blade_document(blade: Blade) -> dict:
    out = {"mass": float(blade.mass), "damping": float(blade.damping)}
    if blade.excitation_scale != 1.0:
        out["excitation_scale"] = float(blade.excitation_scale)
    if blade.frequency is None:
        out["stiffness"] = float(blade.stiffness)
        return out
    out["frequency"] = _frequency_document(blade.frequency)
    return out


def _frequency_document(model):
    if isinstance(model, ConstantFrequency):
        return float(model.hz)
    return {k: list(v) if isinstance(v, tuple) else float(v)
            for k, v in dataclasses.asdict(model).items()}


def _body_document(body: Blade | Substructure, folder) -> dict:
    if isinstance(body, Blade):
        return _blade_document(body)
    given = _GIVEN_AS.get(body)
    if given is None:
        return _substructure_document(body)
    out = _deep_copy(given)
    if "file" in out and folder is not None:
        try:
            out["file"] = os.path.relpath(out["file"], folder)
        except ValueError:  # on another drive: it stays absolute
            pass
    return out


def _substructure_document(body: Substructure) -> dict:
    """A substructure built in Python, inline: its modal data, or its matrices."""
    out: dict[str, Any] = {}
    ratios = body.damping_ratios
    if body.modal_frequencies is not None:
        out["modal"] = {"frequencies": [_frequency_document(m) for m in body.modal_frequencies],
                        "masses": [float(m) for m in _dense(body.mass).diagonal()]}
        ratios = 0.0 if ratios is None else ratios
    else:
        out.update((name, _matrix_document(getattr(body, name))) for name in _MATRICES
                   if getattr(body, name) is not None)
    if ratios is not None:
        out["damping_ratios"] = list(ratios) if isinstance(ratios, tuple) else float(ratios)
    out["points"] = {name: matrix.tolist() for name, matrix in body.points.items()}
    load = body.load
    if isinstance(load, str):
        out["load"] = load
    elif isinstance(load, tuple):
        out["load"] = {"point": load[0], "direction": np.ravel(load[1]).astype(float).tolist()}
    elif load is not None:
        out["load"] = np.asarray(load, dtype=float).tolist()
    if body.excitation_scale != 1.0:
        out["excitation_scale"] = float(body.excitation_scale)
    return out


def _matrix_document(matrix):
    if not scipy.sparse.issparse(matrix):
        return np.asarray(matrix, dtype=float).tolist()
    entries = scipy.sparse.coo_array(matrix)
    return {"shape": list(entries.shape), "rows": entries.row.tolist(),
            "columns": entries.col.tolist(), "values": entries.data.astype(float).tolist()}


def _dense(matrix) -> np.ndarray:
    return matrix.toarray() if scipy.sparse.issparse(matrix) else np.asarray(matrix)


def _end_document(node, point):
    if isinstance(point, tuple):  # a patch's points
        return [node, list(point)]
    return node if point is None else [node, point]


def _interface_document(interface: Interface) -> dict:
    out: dict[str, Any] = {"gap": float(interface.gap)}
    if interface.normal_direction is None:
        out["angle"] = float(interface.angle)
    else:
        out["normal_direction"] = [float(c) for c in interface.normal_direction]
        if interface.tangent_direction is not None:
            out["tangent_direction"] = [float(c) for c in interface.tangent_direction]
        else:
            out["tangent_directions"] = [[float(c) for c in t]
                                         for t in interface.tangent_directions]
    if interface.tangential_stiffness is not None:
        out["tangential_stiffness"] = float(interface.tangential_stiffness)
    out["normal"] = _law_document(interface.normal)
    if interface.friction is not None:
        out["friction"] = _law_document(interface.friction)
    return out


def _law_document(law) -> dict:
    cls = type(law)
    name = cls.__name__ if getattr(contact_laws, cls.__name__, None) is cls \
        else f"{cls.__module__}:{cls.__qualname__}"
    out: dict[str, Any] = {"law": name}
    for field in dataclasses.fields(law):
        if field.init:
            value = getattr(law, field.name)
            out[_FIELD_KEYS.get(field.name, field.name)] = _law_document(value) \
                if dataclasses.is_dataclass(value) else float(value)
    return out


def _excitation_document(excitation: Excitation) -> dict:
    phases = excitation.phases
    if isinstance(phases, AntiPhase):
        pattern: Any = "anti-phase"
    elif isinstance(phases, TravellingWave):
        pattern = {"travelling_wave": phases.nodal_diameter}
    else:
        pattern = [float(p) for p in phases.values]
    frequency = {} if excitation.frequency is None else {
        "frequency": float(excitation.frequency)}
    return {"engine_order": excitation.engine_order,
            "amplitudes": [float(q) for q in excitation.amplitudes], "phases": pattern,
            **frequency}


def _run_document(run: RunSettings) -> dict:
    name = next(n for n, (cls, _) in _METHODS.items() if isinstance(run.method, cls))
    knobs = {k: v for k, v in dataclasses.asdict(run.method).items() if v is not None}
    return {"method": name, **knobs, "periods": run.periods,
            "transient": run.transient, "samples_per_period": run.samples_per_period,
            "event_tolerance": run.event_tolerance,
            "blade": list(run.blade) if isinstance(run.blade, tuple) else run.blade}


def save(path: str | Path | Scene | SceneFile, scene: Scene | SceneFile | str | Path,
         run: RunSettings | None = None) -> Path:
    """Write ``scene`` (and ``run``) as the scene file ``path`` (TOML), which ``load`` reads
    back into an equal scene; the matrix files it names are written relative to its folder
    (made if missing). The scene and the path may come in either order:
    ``save(scene, "group.toml")`` is ``save("group.toml", scene)``.

    ``scene`` may also be what ``load`` returned (a ``SceneFile``): its scene is written,
    with its run settings where its file had a ``[run]`` table (``run``, if given, takes
    their place). The file is written whole or not at all (``atomic.write``): on a full
    disc the file that was there is left as it was, and ``atomic.WriteError`` names it.
    """
    if isinstance(path, Scene | SceneFile):
        path, scene = scene, path
    check_instance("scenefile.save", "scene", scene, (Scene, SceneFile),
                   expected="a shroudnet.Scene (or the SceneFile that scenefile.load returns)")
    check_instance("scenefile.save", "path", path, (str, os.PathLike),
                   expected="a path (str or pathlib.Path)")
    check_instance("scenefile.save", "run", run, RunSettings, optional=True,
                   expected="scenefile.RunSettings(...) or None")
    if isinstance(scene, SceneFile):
        run = scene.run if run is None and "run" in scene.document else run
        scene = scene.scene
    path = Path(path)
    return atomic.write_text(path, dumps(document(scene, run, folder=path.parent)))


def dumps(document: dict) -> str:
    """The TOML text of a scene document: its tables as ``[name]``, its lists of tables as
    ``[[name]]``, whatever is inside them inline."""
    def is_tables(value) -> bool:
        return isinstance(value, dict) or (isinstance(value, list) and bool(value)
                                           and all(isinstance(v, dict) for v in value))

    lines = [f"{_toml_key(k)} = {_toml(v)}" for k, v in document.items() if not is_tables(v)]
    for name, value in document.items():
        if is_tables(value):
            for table in [value] if isinstance(value, dict) else value:
                lines += ["", f"[{_toml_key(name)}]" if isinstance(value, dict)
                          else f"[[{_toml_key(name)}]]"]
                lines += [f"{_toml_key(k)} = {_toml(v)}" for k, v in table.items()]
    return "\n".join(lines) + "\n"


def _toml(value) -> str:
    if isinstance(value, bool):
        return "true" if value else "false"
    if isinstance(value, int):
        return str(value)
    if isinstance(value, float):
        return repr(value) if math.isfinite(value) else \
            ("nan" if math.isnan(value) else "inf" if value > 0 else "-inf")
    if isinstance(value, str):
        return _toml_string(value)
    if isinstance(value, list | tuple):
        return "[" + ", ".join(_toml(v) for v in value) + "]"
    if isinstance(value, dict):
        return "{" + ", ".join(f"{_toml_key(k)} = {_toml(v)}" for k, v in value.items()) + "}"
    raise TypeError(f"a scene document holds numbers, text, lists and tables, got "
                    f"{type(value).__name__}")


def _toml_key(key) -> str:
    key = str(key)
    return key if re.fullmatch(r"[A-Za-z0-9_-]+", key) else _toml_string(key)


def _toml_string(text: str) -> str:
    """A TOML basic string: JSON's escapes, which TOML shares, and DEL escaped too."""
    return json.dumps(text, ensure_ascii=False).replace("\x7f", "\\u007f")


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
                    source=f"{self.path} = {value:g}", laws=self.laws, check_memory=True).scene
