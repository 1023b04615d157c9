"""Saved results: self-describing files that load back without loss, written atomically.

A simulation is one ``.npz`` file: its arrays, and a JSON header ``meta`` holding the
format, the scene as a scene-file document (``scenefile.document``), the settings, the
event counts and the energy ledger. ``load_simulation`` rebuilds the same ``Simulation``,
scene included; ``load_arrays`` reads everything but the scene, which it leaves as its
document, so that a run whose laws are not importable here still loads.

A sweep is a folder: ``sweep.json`` (parameter, values, settings, and what the scenes
came from) and ``points/00012.npz``, one file per finished point, written as it finishes;
a failed point's file holds the message of what stopped it. ``SweepStore`` reopens the
folder of an interrupted sweep, so that it runs only the points still missing
(``sweep(store=open_sweep_store(folder))``, or ``save_to=folder``); ``load_sweep`` reads a
finished one. Each point file carries the fingerprint of the sweep it belongs to (a hash
of ``sweep.json``'s content).

Every file is written to a temporary name in its folder and renamed into place
(``atomic.write``), so a run killed at any moment leaves either the whole file or none, and
a full disc leaves the file that was there as it was. A file damaged anyway (cut
short by a full disk, a flipped bit, edited by hand) raises ``ResultsError`` naming the
file and what is wrong with it, never a bare zip, JSON or numpy error. Resuming a sweep
computes a damaged point again, with a notice; a damaged ``sweep.json`` is written again
from the sweep's arguments when every readable point carries their fingerprint, and is
otherwise refused with ``ResultsError`` saying what to do.
"""

from __future__ import annotations

import dataclasses
import functools
import hashlib
import json
import math
import re
import warnings
from collections.abc import Callable, Iterable
from dataclasses import asdict, dataclass
from enum import IntEnum
from pathlib import Path

import numpy as np

from contact_laws import check_instance

from .. import atomic
from ..analysis.stability import state_parts, state_size
from ..engine.codes import EventKind, Mode
from ..run.classification import Classification
from ..run.methods import SimulationSettings, transient_for
from ..run.reporting import SweepWarning
from ..run.simulation import EnergyLedger, EventLog, Simulation, Sweep, SweepPoint
from ..steady.continuation import Bifurcation, Branch
from ..steady.cycle import EnergyPerCycle
from ..steady.orbits import PeriodicOrbit
from . import scenefile

#: Version of the file layout, stored in every file: 2 since every state a file holds
#: (a run's x and v, a branch's initial states and monodromy matrices, a sweep point's
#: final state) is by the nodes' own degrees of freedom, as the runs give them.
FORMAT = 2
#: The formats read. Format 1 held the states of scenes with substructures by the
#: engine's modal coordinates, which nothing in such a file allows to convert (the
#: modes are not in it, and an eigensolver may give them other signs, or other bases of
#: equal frequencies): those files are refused by name; the others read as they are.
READABLE = (1, 2)


class ResultsError(ValueError):
    """A results file or folder that cannot be read or written, or a sweep folder that
    holds another sweep. The message names the file."""


# ---- writing and reading one file ---------------------------------------------------------

def atomic_write(path: str | Path, write: Callable[[object], None]) -> Path:
    """Call ``write(file)`` on a temporary file beside ``path``, then rename it to ``path``
    (``atomic.write``).

    Raises ``ResultsError`` naming ``path`` when it is a folder, when a part of its folder
    is a file, or when the system refuses the write (a folder that cannot be written, a
    full disc); the file that was there before is then left as it was.
    """
    path = Path(path)
    _make_folder(path.parent, f"cannot save {path}")
    if path.is_dir():
        raise ResultsError(f"{path}: is a folder; give the name of a file to save to")
    try:
        return atomic.write(path, write)
    except atomic.WriteError as error:
        raise ResultsError(f"cannot save {path}: {error.strerror}; nothing was changed "
                           "there") from None


def _make_folder(folder: Path, doing: str) -> None:
    """Make ``folder`` (and its parents), or raise ``ResultsError`` saying why not."""
    try:
        folder.mkdir(parents=True, exist_ok=True)
    except (FileExistsError, NotADirectoryError):
        blocking = next((part for part in (folder, *folder.parents)
                         if part.exists() and not part.is_dir()), folder)
        raise ResultsError(f"{doing}: {blocking} is a file, not a folder") from None
    except OSError as error:
        raise ResultsError(f"{doing}: cannot make the folder {folder}: "
                           f"{error.strerror or error}") from None


def _save_npz(path, meta: dict, arrays: dict) -> Path:
    header = np.frombuffer(json.dumps(meta).encode(), dtype=np.uint8)
    return atomic_write(path, lambda file: np.savez(file, meta=header, **arrays))


def _load_npz(path, kind: str | None = None) -> tuple[dict, dict]:
    """The header (a dict, format checked) and the arrays of a results file; ``kind``, if
    given, is the kind of file it must be."""
    path = Path(path)
    arrays = _read_archive(path)
    meta = _header(path, arrays.pop("meta", None))
    if meta.get("format") not in READABLE:
        raise ResultsError(f"{path}: results format {meta.get('format')!r}; this shroudnet "
                           f"reads formats {' and '.join(map(str, READABLE))}")
    if kind is not None and meta.get("kind") != kind:
        raise ResultsError(f"{path}: holds a {meta.get('kind')!r}, not a {kind}")
    return meta, arrays


def _check_states(path: Path, meta: dict, documents: list | None, states: str) -> None:
    """Refuse a file of format 1 whose ``states`` (what it holds of them, in words) may be
    by the engine's modal coordinates: where a scene document of ``documents`` has a
    substructure, or where there are none to tell (None)."""
    if meta.get("format") != 1:
        return
    if documents is not None and not any(
            scenefile.is_substructure(entry) for document in documents
            for entry in (document.get("blades") or [] if isinstance(document, dict) else [])):
        return  # blades only: their coordinates are their displacements
    why = ("its scenes have substructures" if documents is not None else
           "nothing in it says whether its scenes have substructures")
    raise ResultsError(
        f"{path}: written in results format 1, which kept the {states} of a scene with "
        f"substructures by the engine's modal coordinates, not by the nodes' own degrees of "
        f"freedom, and {why}; the file does not hold the modes that would convert them (an "
        f"eigensolver may give them other signs, or other bases of equal frequencies), so "
        f"they cannot be read correctly. Compute it again to write it in format {FORMAT}.")


def _read_archive(path: Path) -> dict[str, np.ndarray]:
    """Every array of the .npz file ``path``, or ``ResultsError`` saying why not."""
    if not path.exists():
        raise ResultsError(f"{path}: no such results file")
    if path.is_dir():
        raise ResultsError(f"{path}: is a folder, not a results file (.npz)")
    if path.stat().st_size == 0:
        raise ResultsError(f"{path}: the file is empty (a write cut short?); delete it "
                           "and compute it again")
    try:
        data = np.load(path, allow_pickle=False)
    except Exception as error:  # whatever the bytes are, say so
        raise ResultsError(f"{path}: not a shroudnet results file, or damaged "
                           f"({_reason(error)})") from None
    if not isinstance(data, np.lib.npyio.NpzFile):
        raise ResultsError(f"{path}: holds a single array (.npy), not a shroudnet results "
                           "file (.npz)")
    try:
        with data:
            return {name: data[name] for name in data.files}
    except Exception as error:  # a damaged archive fails in many ways
        raise ResultsError(f"{path}: damaged: cut short, or altered since it was written "
                           f"({_reason(error)})") from None


def _reason(error: BaseException) -> str:
    return f"{type(error).__name__}: {error}" if str(error) else type(error).__name__


def _header(path: Path, raw) -> dict:
    """The JSON header ``meta`` of a results file, decoded and checked to be an object."""
    if raw is None:
        raise ResultsError(f"{path}: not a shroudnet results file (no meta header)")
    if raw.dtype != np.uint8 or raw.ndim != 1:
        raise ResultsError(f"{path}: its meta header is not text (an array of "
                           f"{raw.dtype} of shape {raw.shape})")
    try:
        meta = json.loads(raw.tobytes().decode("utf-8"))
    except (UnicodeDecodeError, json.JSONDecodeError) as error:
        raise ResultsError(f"{path}: its meta header is not JSON ({error})") from None
    if not isinstance(meta, dict):
        raise ResultsError(f"{path}: its meta header must be a JSON object, got a "
                           f"{type(meta).__name__}")
    return meta


# ---- checking what a file holds -----------------------------------------------------------

@dataclass(frozen=True)
class _Field:
    """What a header field must be, for ``_checked``: ``test(value)`` holds; ``allowed``
    says so in words."""

    name: str
    allowed: str
    test: Callable[[object], bool]


def _is_number(value) -> bool:
    return isinstance(value, int | float) and not isinstance(value, bool)


def _is_count(value) -> bool:
    return isinstance(value, int) and not isinstance(value, bool) and value >= 0


def _checked(path: Path, meta: dict, fields: Iterable[_Field], where: str = "meta") -> dict:
    """``meta`` if every field is there and as allowed, else ``ResultsError`` naming it."""
    for field in fields:
        if field.name not in meta:
            raise ResultsError(f"{path}: its {where} header has no {field.name!r}")
        value = meta[field.name]
        if not field.test(value):
            raise ResultsError(f"{path}: {where}.{field.name} must be {field.allowed}, got "
                               f"{_short(value)}")
    return meta


def _short(value) -> str:
    text = repr(value)
    return text if len(text) <= 60 else text[:57] + "..."


def _number_table(names: Iterable[str]) -> Callable[[object], bool]:
    names = set(names)
    return lambda value: isinstance(value, dict) and set(value) == names \
        and all(_is_number(v) for v in value.values())


# ---- checking what a file holds: arrays ---------------------------------------------------

#: The kinds of number an array may hold: numpy dtype kinds, and what they are in words.
_REAL, _INTEGER, _COMPLEX = ("fiu", "real numbers"), ("iu", "integers"), ("fciu", "numbers")


@dataclass(frozen=True)
class _Array:
    """What an array of a results file must be, for ``_checked_arrays``.

    ``dims`` names its sizes (keys of the sizes the check is given, or found on the way:
    the first array with a size unknown so far sets it, each later one must agree);
    ``numbers`` its kind (``_REAL``, ``_INTEGER``, ``_COMPLEX``); ``finite``: no NaN or
    inf; ``rising``: along its first axis it must ``"increase"`` (strictly) or ``"not
    decrease"``; ``codes``: every value a member of this ``IntEnum``; ``indexes``: every
    value an index into the size of that name (0 to size − 1); ``optional``: it may be
    missing.
    """

    name: str
    dims: tuple[str, ...]
    numbers: tuple[str, str] = _REAL
    finite: bool = True
    rising: str = ""
    codes: type[IntEnum] | None = None
    indexes: str = ""
    optional: bool = False


def _checked_arrays(path: Path, arrays: dict, fields: Iterable[_Array], sizes: dict,
                    words: dict | None = None) -> dict[str, np.ndarray]:
    """The arrays ``fields`` name, each checked as its record says; ``ResultsError`` naming
    the file and the array at the first fault.

    ``sizes``: the sizes known (None: set by the first array that has it), updated as
    arrays set them; ``words``: how a size is said, where not by its own name.
    """
    words = words or {}
    checked = {}
    for field in fields:
        if field.name not in arrays:
            if field.optional:
                continue
            raise ResultsError(f"{path}: has no array {field.name!r}")
        checked[field.name] = _checked_array(path, arrays[field.name], field, sizes, words)
    return checked


def _checked_array(path: Path, array: np.ndarray, field: _Array, sizes: dict,
                   words: dict) -> np.ndarray:
    """``array``, checked in turn for each fault ``_ARRAY_FAULTS`` names; the sizes it has
    that were unknown are then known."""
    for fault in _ARRAY_FAULTS:
        found = fault(array, field, sizes, words)
        if found:
            raise ResultsError(f"{path}: {found}")
    sizes.update(zip(field.dims, array.shape))
    return array


def _kind_fault(array, field: _Array, sizes: dict, words: dict) -> str:
    kinds, numbers = field.numbers
    if array.dtype.kind not in kinds:
        return f"array {field.name!r} holds {array.dtype}, not " + (
            numbers if array.dtype.kind in "biufc" else "numbers")
    return ""


def _shape_fault(array, field: _Array, sizes: dict, words: dict) -> str:
    wanted = tuple(sizes.get(dim) for dim in field.dims)
    if array.ndim == len(wanted) and all(want is None or have == want
                                         for have, want in zip(array.shape, wanted)):
        return ""
    shape = " × ".join("any" if n is None else str(n) for n in wanted) or "a scalar"
    meaning = " × ".join(_count(n, words.get(dim, dim)) for n, dim in zip(wanted, field.dims))
    return f"array {field.name!r} has shape {array.shape}; it must be {shape} ({meaning})"


def _finite_fault(array, field: _Array, sizes: dict, words: dict) -> str:
    if not field.finite or array.dtype.kind not in "fc" or np.isfinite(array).all():
        return ""
    at = np.unravel_index(np.argmax(~np.isfinite(array)), array.shape)
    value = "NaN" if np.isnan(array[at]) else "inf"
    return f"array {field.name!r} holds {value} at {_along(field, words)} {at[0]}"


def _order_fault(array, field: _Array, sizes: dict, words: dict) -> str:
    if not field.rising or len(array) < 2:
        return ""
    step = np.diff(array, axis=0).reshape(len(array) - 1, -1)
    bad = (step <= 0 if field.rising == "increase" else step < 0).any(axis=1)
    if not bad.any():
        return ""
    at = int(np.argmax(bad))
    how = "falls" if (step[at] < 0).any() else "repeats a value"
    return (f"array {field.name!r} must {field.rising}, it {how} at "
            f"{_along(field, words)} {at + 1}")


def _code_fault(array, field: _Array, sizes: dict, words: dict) -> str:
    if field.codes is None:
        return ""
    unknown = ~np.isin(array, [member.value for member in field.codes])
    if not unknown.any():
        return ""
    at = np.unravel_index(np.argmax(unknown), array.shape)
    what = re.sub(r"(?<!^)(?=[A-Z])", " ", field.codes.__name__).lower()  # EventKind
    known = ", ".join(f"{member.value} ({member.name.lower()})" for member in field.codes)
    return (f"array {field.name!r} holds the unknown {what} {array[at]} at "
            f"{_along(field, words)} {at[0]}; the {what}s are {known}")


def _index_fault(array, field: _Array, sizes: dict, words: dict) -> str:
    if not field.indexes or not array.size:
        return ""
    count, low, high = sizes[field.indexes], array.min(), array.max()
    if 0 <= low and high < count:
        return ""
    things = words.get(field.indexes, field.indexes) + "s"
    return f"{field.name} holds {low} to {high}; the scene has " + (
        f"{things} 0 to {count - 1}" if count else f"no {things}")


#: The faults an array is checked for, in this order (each check may take the ones
#: before it as passed).
_ARRAY_FAULTS = (_kind_fault, _shape_fault, _finite_fault, _order_fault, _code_fault,
                 _index_fault)


def _along(field: _Array, words: dict) -> str:
    """What the first axis of an array counts, in words (``sample``, ``orbit``)."""
    return words.get(field.dims[0], field.dims[0])


def _count(n: int | None, word: str) -> str:
    return word + "s" if n is None else f"{n} {word}" + ("s" if n != 1 else "")


#: The names an event count may be kept under: the event kinds, as ``EventLog.counts``
#: names them.
_EVENT_KINDS = tuple(kind.name.lower() for kind in EventKind)


def _is_event_counts(value) -> bool:
    """Whether ``value`` is a table of counts by name (``_check_event_kinds`` checks the
    names)."""
    return isinstance(value, dict) and all(isinstance(k, str) and _is_count(n)
                                           for k, n in value.items())


def _check_event_kinds(path: Path, counts: dict, where: str = "meta.event_counts") -> None:
    """Refuse a table of event counts that counts a kind of event there is not."""
    unknown = [kind for kind in counts if kind not in _EVENT_KINDS]
    if unknown:
        raise ResultsError(f"{path}: {where} counts the unknown event kind "
                           f"{', '.join(map(repr, unknown))}; the kinds are "
                           f"{', '.join(_EVENT_KINDS)}")


# ---- a simulation -------------------------------------------------------------------------

_SIMULATION_HEADER = (
    _Field("scene", "a scene document (a JSON object)", lambda v: isinstance(v, dict)),
    _Field("settings", "a JSON object", lambda v: isinstance(v, dict)),
    _Field("energy", "the energy ledger: " + ", ".join(f.name for f in dataclasses.fields(
        EnergyLedger)) + " [J]", _number_table(f.name for f in dataclasses.fields(EnergyLedger))),
    _Field("event_counts", "a table of event counts by kind", _is_event_counts),
    _Field("samples_per_period", "an int >= 1", lambda v: _is_count(v) and v >= 1),
    _Field("steps", "an int >= 0", _is_count),
)


#: The arrays of a simulation file, in the order checked: a column is a blade (with
#: substructures, a degree of freedom of a node); the events are in time order.
_EVENT_ARRAYS = (
    _Array("event_time", ("event",), rising="not decrease"),
    _Array("event_interface", ("event",), _INTEGER, indexes="interface"),
    _Array("event_kind", ("event",), _INTEGER, codes=EventKind),
)
_SIMULATION_ARRAYS = (
    _Array("t", ("sample",), rising="increase"),
    _Array("x", ("sample", "column")),
    _Array("v", ("sample", "column")),
    _Array("normal_force", ("sample", "interface")),
    _Array("friction_force", ("sample", "interface")),
    _Array("friction_force_second", ("sample", "interface"), optional=True),  # elastic
    _Array("modes", ("sample", "interface"), _INTEGER, codes=Mode),
    _Array("work", ("sample", "work column")),
    *_EVENT_ARRAYS,
)


@dataclass(frozen=True, eq=False)
class SimulationArrays:
    """Everything a simulation file holds, the scene left as its scene-file document.

    ``load_simulation`` builds the ``Simulation`` from it; on its own it needs no law
    class of the scene to be importable. Arrays as in ``Simulation``.
    """

    path: Path
    document: dict           # the scene (and run settings), as ``scenefile.read`` takes it
    settings: SimulationSettings
    t: np.ndarray            # (n_t,) [s]
    x: np.ndarray            # (n_t × n_blades) [m]; with substructures, by dof
    v: np.ndarray            # (n_t × n_blades) [m/s]
    normal_force: np.ndarray     # (n_t × n_interfaces) [N]
    friction_force: np.ndarray   # (n_t × n_interfaces) [N]
    modes: np.ndarray            # (n_t × n_interfaces) ``Mode`` values
    work: np.ndarray             # (n_t × columns) cumulative [J]
    events: EventLog
    energy: EnergyLedger
    samples_per_period: int
    steps: int
    friction_force_second: np.ndarray | None = None  # (n_t × n_interfaces) [N], or None

    @property
    def periods(self) -> int:
        """Number of excitation periods simulated."""
        return (len(self.t) - 1) // self.samples_per_period


def save_simulation(path: str | Path, sim: Simulation,
                    run: scenefile.RunSettings | None = None) -> Path:
    """Write ``sim`` to ``path`` (.npz), scene and settings included, and the scene file's
    run settings (the blade and transient its summaries are about) when given.

    Raises ``ResultsError`` when ``path`` cannot be written (a folder, or under a file).
    """
    check_instance("results.save_simulation", "sim", sim, Simulation,
                   expected="a shroudnet.Simulation (what simulate returns)")
    check_instance("results.save_simulation", "run", run, scenefile.RunSettings,
                   optional=True, expected="scenefile.RunSettings(...) or None")
    meta = {"format": FORMAT, "kind": "simulation",
            "scene": scenefile.document(sim.scene, run), "settings": sim.settings.as_dict(),
            "energy": asdict(sim.energy), "event_counts": sim.events.counts,
            "samples_per_period": sim.samples_per_period, "steps": sim.steps}
    arrays = {"t": sim.t, "x": sim.x, "v": sim.v, "normal_force": sim.normal_force,
              "friction_force": sim.friction_force, "modes": sim.modes, "work": sim.work,
              "event_time": sim.events.time, "event_interface": sim.events.interface,
              "event_kind": sim.events.kind}
    if sim.friction_force_second is not None:
        arrays["friction_force_second"] = sim.friction_force_second
    return _save_npz(path, meta, arrays)


def load_arrays(path: str | Path) -> SimulationArrays:
    """Read a simulation file without rebuilding its scene.

    Every array is checked as ``_SIMULATION_ARRAYS`` says: there, numbers of its kind,
    finite, its shape consistent with the others and with the numbers of blades and
    interfaces of the scene document (with substructures, whose degrees of freedom the
    document does not count, x and v with each other), its times in order, its modes and event
    kinds known; raises ``ResultsError`` naming the file, the array and what is wrong.
    """
    path = Path(path)
    meta, arrays = _load_npz(path, kind="simulation")
    _checked(path, meta, _SIMULATION_HEADER)
    blades, interfaces = _document_counts(path, meta["scene"])
    _check_event_kinds(path, meta["event_counts"])
    _check_second_friction(path, meta["scene"], "friction_force_second" in arrays)
    _check_states(path, meta, [meta["scene"]], "displacements and velocities x and v")
    # with substructures, whose degrees of freedom the document does not count, x sets them
    sizes = {"sample": None, "column": blades, "interface": interfaces}
    words = {"column": "dof" if blades is None else "blade"}
    checked = _checked_arrays(path, arrays, _SIMULATION_ARRAYS[:1], sizes, words)
    n = len(checked["t"])
    if n < 1 or (n - 1) % meta["samples_per_period"]:
        raise ResultsError(f"{path}: {n} samples are not a whole number of periods of "
                           f"{meta['samples_per_period']} samples, plus one")
    checked.update(_checked_arrays(path, arrays, _SIMULATION_ARRAYS[1:], sizes, words))
    try:
        settings = SimulationSettings.from_dict(meta["settings"])
    except (TypeError, ValueError) as error:
        raise ResultsError(f"{path}: meta.settings is damaged ({error})") from None
    events = EventLog(time=checked.pop("event_time"), interface=checked.pop("event_interface"),
                      kind=checked.pop("event_kind"), counts=meta["event_counts"])
    return SimulationArrays(path=path, document=meta["scene"], settings=settings,
                            events=events, energy=EnergyLedger(**meta["energy"]),
                            samples_per_period=meta["samples_per_period"],
                            steps=meta["steps"], **checked)


def _document_counts(path: Path, document: dict) -> tuple[int | None, int]:
    """(blades, contacts) listed in a saved scene document (an interface's contacts are
    one, or the points of its patch); blades is None where a node is a substructure (the
    state is then by degree of freedom, which the scene counts)."""
    counts = []
    for key in ("blades", "interfaces"):
        entries = document.get(key)
        if not isinstance(entries, list):
            raise ResultsError(f"{path}: its scene document has no list of {key}")
        counts.append(len(entries) if key == "blades" else sum(
            scenefile.contact_count(entry) if isinstance(entry, dict) else 1
            for entry in entries))
    if any(scenefile.is_substructure(entry) for entry in document["blades"]):
        return None, counts[1]
    return counts[0], counts[1]


def _check_second_friction(path: Path, document: dict, held: bool) -> None:
    """Refuse a file that holds ``friction_force_second`` where its scene has no elastic
    contact (an interface with a ``tangential_stiffness``), or lacks it where it has one:
    the friction along t₂ would read as 0 N or as whatever the array holds."""
    elastic = any(isinstance(entry, dict) and "tangential_stiffness" in entry
                  for entry in document["interfaces"])
    if elastic and not held:
        raise ResultsError(f"{path}: has no array 'friction_force_second', which a run of a "
                           "scene with elastic contacts (tangential_stiffness) records")
    if held and not elastic:
        raise ResultsError(f"{path}: holds an array 'friction_force_second', which only a "
                           "run of a scene with elastic contacts (tangential_stiffness) "
                           "records, and its scene has none")


def load_simulation(path: str | Path, *, laws: scenefile.Laws = ()) -> Simulation:
    """Read a file written by ``save_simulation`` back into an equal ``Simulation``.

    ``laws``: law classes of one's own (or modules holding them) that the scene names, as
    for ``scenefile.load``. A law defined in a script run as a program lives in that
    program's ``__main__`` only; elsewhere the scene cannot be rebuilt and this raises
    ``ResultsError`` naming the law, while ``load_arrays`` still reads the rest.
    """
    data = load_arrays(path)
    scene = _scene(data.path, data.document, laws).scene
    columns = scene.arrays.n_blades  # blades, or with substructures degrees of freedom
    if columns != data.x.shape[1] or len(scene.contacts) != data.normal_force.shape[1]:
        what = "degrees of freedom" if scene.arrays.is_structure else "blades"
        raise ResultsError(f"{path}: its arrays are for {data.x.shape[1]} {what} and "
                           f"{data.normal_force.shape[1]} interfaces; its scene has "
                           f"{columns} and {len(scene.contacts)}")
    return Simulation(scene=scene, settings=data.settings, t=data.t, x=data.x, v=data.v,
                      normal_force=data.normal_force, friction_force=data.friction_force,
                      modes=data.modes, events=data.events, energy=data.energy,
                      work=data.work, samples_per_period=data.samples_per_period,
                      steps=data.steps, friction_force_second=data.friction_force_second)


def _scene(path: Path, document: dict, laws: scenefile.Laws) -> scenefile.SceneFile:
    """The scene file read from a saved document, or ``ResultsError`` saying why not."""
    extra = {"laws": laws} if laws else {}
    try:
        return scenefile.read(document, source=f"{path} (its scene)", **extra)
    except scenefile.SceneFileError as error:
        own = _own_law_names(document)
        if not own:
            raise ResultsError(str(error)) from None
        in_script = [name for name in own if name.startswith("__main__:")]
        advice = ("it was defined in the script that made the run (module __main__), so "
                  "only that script can rebuild it: move the law to a module of its own "
                  "and import it from there" if in_script else
                  "import the module that defines it before loading, or pass laws=[...]")
        raise ResultsError(f"{path}: its scene cannot be rebuilt here, it uses the law "
                           f"{', '.join(own)}: {advice}. results.load_arrays reads its "
                           f"arrays and settings without the scene. ({error})") from None
    except Exception as error:  # a document of the wrong shape
        raise ResultsError(f"{path}: its scene document is damaged ({_reason(error)})") \
            from None


def _own_law_names(document) -> list[str]:
    """The ``"module:Class"`` law names in a scene document, in order, once each."""
    names: dict[str, None] = {}

    def visit(node):
        if isinstance(node, dict):
            law = node.get("law")
            if isinstance(law, str) and ":" in law:
                names[law] = None
            for value in node.values():
                visit(value)
        elif isinstance(node, list):
            for value in node:
                visit(value)

    visit(document)
    return list(names)


def load_run_settings(path: str | Path, *, laws: scenefile.Laws = ()) -> scenefile.RunSettings:
    """The run settings saved with a simulation or a branch (the defaults if none were).

    A simulation saved without them gets the defaults fitted to it: its own periods, and
    the transient ``transient_for`` them (``TRANSIENT``, or half a shorter run), so that
    what reads its steady response after the transient has periods left to read.
    """
    path = Path(path)
    meta = _load_npz(path)[0]
    if meta.get("kind") == "branch":
        _checked(path, meta, _BRANCH_HEADER)
        scenes = meta["scenes"]
        return _scene(path, scenes if isinstance(scenes, dict) else scenes[0], laws).run
    data = load_arrays(path)
    run = _scene(data.path, data.document, laws).run
    if "run" in data.document:
        return run
    return dataclasses.replace(run, periods=data.periods, transient=transient_for(data.periods))


# ---- a sweep, point by point --------------------------------------------------------------

#: The fields a saved classification must hold (later ones have defaults: files written
#: before λ_max was kept lack them).
_CLASSIFICATION_NEEDS = {f.name for f in dataclasses.fields(Classification)
                         if f.default is dataclasses.MISSING}
_POINT_HEADER = (
    _Field("value", "a number", _is_number),
    _Field("energy_density", "a number [m^2]", _is_number),
    _Field("friction_loss_per_cycle", "a number [J]", _is_number),
    _Field("classification", "a table of " + ", ".join(
        f.name for f in dataclasses.fields(Classification)),
        lambda v: isinstance(v, dict) and _CLASSIFICATION_NEEDS <= set(v) <= {
            f.name for f in dataclasses.fields(Classification)}),
)
_FAILURE_HEADER = (
    _Field("value", "a number", _is_number),
    _Field("message", "text", lambda v: isinstance(v, str)),
)
_POINT, _FAILED_POINT = "sweep point", "failed sweep point"
#: The arrays of a sweep point: its Poincaré points (x, v), its final state (by blade, or
#: by degree of freedom of a node), and its peak per response (which the file does not
#: count; files written before peaks were kept have none).
_POINT_ARRAYS = (
    _Array("poincare", ("recorded period", "phase coordinate")),
    _Array("final_x", ("coordinate",)),
    _Array("final_v", ("coordinate",)),
    _Array("peak", ("response",), optional=True),
)


def _save_point(path: Path, point: SweepPoint, fingerprint: str | None = None) -> Path:
    """Write a point (or a failed point) to ``path``, with its sweep's ``fingerprint``."""
    tag = {} if fingerprint is None else {"sweep": fingerprint}
    if point.failed:
        meta = {"format": FORMAT, "kind": _FAILED_POINT, "value": point.value,
                "message": point.error, "tolerance": point.classification.tolerance, **tag}
        return _save_npz(path, meta, {})
    meta = {"format": FORMAT, "kind": _POINT, "value": point.value,
            "energy_density": point.energy_density,
            "friction_loss_per_cycle": point.friction_loss_per_cycle,
            "classification": asdict(point.classification), **tag}
    arrays = {"poincare": point.poincare, "final_x": point.final_state[0],
              "final_v": point.final_state[1], "peak": point.peak}
    return _save_npz(path, meta, arrays)


def _load_point(path: Path) -> SweepPoint:
    """The point (or failed point) in ``path``; ``ResultsError`` if it cannot be read."""
    return _read_point(path)[0]


def _read_point(path: Path) -> tuple[SweepPoint, str | None]:
    """(the point in ``path``, the fingerprint of its sweep or None if it has none)."""
    path = Path(path)
    meta, arrays = _load_npz(path)
    fingerprint = meta.get("sweep")
    if meta.get("kind") == _FAILED_POINT:
        _checked(path, meta, _FAILURE_HEADER)
        tolerance = meta.get("tolerance", math.nan)
        return SweepPoint.failure(meta["value"], meta["message"],
                                  tolerance if _is_number(tolerance) else math.nan), fingerprint
    if meta.get("kind") != _POINT:
        raise ResultsError(f"{path}: holds a {meta.get('kind')!r}, not a sweep point")
    _checked(path, meta, _POINT_HEADER)
    checked = _checked_arrays(path, arrays, _POINT_ARRAYS, {"phase coordinate": 2})
    poincare, final_x, final_v = (checked[name] for name in ("poincare", "final_x", "final_v"))
    # none kept, or a file written before peaks were kept: empty
    peak = checked.get("peak", np.empty(0))
    try:
        classification = Classification(**meta["classification"])
    except (TypeError, ValueError) as error:
        raise ResultsError(f"{path}: meta.classification is damaged ({error})") from None
    return SweepPoint(value=meta["value"], poincare=poincare,
                      energy_density=float(meta["energy_density"]),
                      friction_loss_per_cycle=float(meta["friction_loss_per_cycle"]),
                      classification=classification,
                      final_state=(final_x, final_v), peak=peak), fingerprint


_MANIFEST_FIELDS = (
    _Field("format", " or ".join(map(str, READABLE)), lambda v: v in READABLE),
    _Field("kind", "'sweep'", lambda v: v == "sweep"),
    _Field("parameter", "text", lambda v: isinstance(v, str)),
    _Field("values", "a list of numbers",
           lambda v: isinstance(v, list) and all(_is_number(x) for x in v)),
    _Field("settings", "a JSON object", lambda v: isinstance(v, dict)),
    _Field("blade", "a blade name or position", lambda v: True),
)


def _read_manifest(path: Path) -> dict:
    """The manifest ``sweep.json`` of a sweep folder, checked; ``ResultsError`` if it is
    missing or damaged (the message says which)."""
    try:
        text = path.read_text(encoding="utf-8")
    except FileNotFoundError:
        raise ResultsError(f"{path.parent}: not a sweep folder (no {path.name})") from None
    except (OSError, UnicodeDecodeError) as error:
        raise ResultsError(f"{path}: cannot be read ({_reason(error)})") from None
    try:
        manifest = json.loads(text)
    except json.JSONDecodeError as error:
        raise ResultsError(f"{path}: damaged: not JSON ({error})") from None
    if not isinstance(manifest, dict):
        raise ResultsError(f"{path}: damaged: not a JSON object")
    return _checked(path, manifest, _MANIFEST_FIELDS, where="sweep.json")


def _fingerprint(manifest: dict) -> str:
    """A short hash of a sweep's manifest, carried by each of its point files."""
    text = json.dumps(manifest, sort_keys=True, separators=(",", ":"))
    return hashlib.sha256(text.encode()).hexdigest()[:16]


def _warn(message: str) -> None:
    warnings.warn(message, SweepWarning, stacklevel=3)


class SweepStore:
    """The folder of one sweep: its manifest and a file per finished (or failed) point.

    Opening a folder that already holds the same sweep (same manifest) resumes it;
    one that holds another sweep is refused. If ``sweep.json`` is missing or damaged
    while points are saved, it is written again from ``manifest`` when every readable
    point carries this sweep's fingerprint; otherwise ``ResultsError`` says what to do.
    ``notice(message)`` hears of what was repaired or will be computed again (default:
    a ``SweepWarning``).
    """

    MANIFEST = "sweep.json"

    def __init__(self, folder: str | Path, manifest: dict, *,
                 notice: Callable[[str], None] | None = None):
        self.folder = Path(folder)
        self.notice = _warn if notice is None else notice
        if self.folder.exists() and not self.folder.is_dir():
            raise ResultsError(f"{self.folder}: is a file; a sweep is saved to a folder (new, "
                               "or holding this same sweep)")
        self.manifest = json.loads(json.dumps({"format": FORMAT, "kind": "sweep", **manifest}))
        self.fingerprint = _fingerprint(self.manifest)
        self._open_manifest(self.folder / self.MANIFEST)
        for stale in self.folder.glob("points/.*.part"):  # a write cut short by a kill
            stale.unlink(missing_ok=True)

    def _open_manifest(self, path: Path) -> None:
        try:
            found = _read_manifest(path)
        except ResultsError as error:
            if path.exists() or self._point_files():
                self._rewrite_manifest(path, error)
            else:
                self._write_manifest(path)
            return
        if found["format"] != FORMAT:
            raise ResultsError(
                f"{self.folder} holds a sweep written in results format {found['format']}; "
                f"this shroudnet writes format {FORMAT} (states by the nodes' own degrees of "
                "freedom) and adds no points to an older one: read it with "
                "results.load_sweep, or save this sweep to another folder")
        if found != self.manifest:
            changed = sorted(k for k in set(found) | set(self.manifest)
                             if found.get(k) != self.manifest.get(k))
            raise ResultsError(
                f"{self.folder} holds another sweep (its {', '.join(changed)} differ); "
                "resume it with the same arguments, or choose another folder")

    def _rewrite_manifest(self, path: Path, error: ResultsError) -> None:
        """Write the manifest again if the saved points are this sweep's, else refuse."""
        foreign = []
        for file in self._point_files():
            try:
                _, fingerprint = _read_point(file)
            except ResultsError:
                continue  # computed again anyway
            if fingerprint != self.fingerprint:
                foreign.append(file.name)
        if foreign:
            raise ResultsError(
                f"{error}. Its {len(foreign)} saved point(s) ({', '.join(foreign[:3])}"
                f"{', ...' if len(foreign) > 3 else ''}) cannot be matched to this sweep "
                f"without it: delete {self.folder} (or its points/ folder) to start again, "
                "or save to another folder") from None
        self._write_manifest(path)
        self.notice(f"{error}; written again from this sweep's arguments (the saved points "
                    "carry their fingerprint)")

    def _write_manifest(self, path: Path) -> None:
        text = json.dumps(self.manifest, indent=2).encode()
        atomic_write(path, lambda file: file.write(text))

    def _point_files(self) -> list[Path]:
        return sorted(self.folder.glob("points/[0-9]*.npz"))

    def finished(self) -> dict[int, SweepPoint]:
        """The points already saved (failed ones included), by index.

        A file that cannot be read, or that holds another sweep's point, is left out (so
        that the point is computed again) with a notice naming it.
        """
        values = self.manifest["values"]
        points = {}
        for index in range(len(values)):
            path = _point_path(self.folder, index)
            if not path.exists():
                continue
            try:
                point, fingerprint = _read_point(path)
            except ResultsError as error:
                self.notice(f"{error}; computing this point again")
                continue
            if fingerprint not in (None, self.fingerprint) or point.value != values[index]:
                self.notice(f"{path}: holds the point of another sweep; computing this "
                            "point again")
                continue
            points[index] = point
        return points

    def save(self, index: int, point: SweepPoint) -> None:
        """Write the point (or failed point) of index ``index``."""
        _save_point(_point_path(self.folder, index), point, self.fingerprint)


def open_sweep_store(folder: str | Path) -> Callable[..., SweepStore]:
    """The ``store`` of ``sweep`` that keeps each point in the sweep folder ``folder``.

    The sweep calls it with its manifest (and ``notice``) as it starts, which makes the
    folder or reopens it (``SweepStore``); ``sweep(save_to=folder)`` is short for it.
    """
    return functools.partial(SweepStore, folder)


def _point_path(folder: Path, index: int) -> Path:
    return folder / "points" / f"{index:05d}.npz"


def load_sweep(folder: str | Path) -> Sweep:
    """Read a sweep folder, failed points included (``Sweep.failures``).

    Raises ``ResultsError`` if points are missing or a file is damaged, naming it; running
    the same sweep again with ``save_to=folder`` computes what is missing or damaged.
    """
    folder = Path(folder)
    if not folder.is_dir():
        raise ResultsError(f"{folder}: not a sweep folder" + (
            " (it is a file)" if folder.exists() else " (no such folder)"))
    path = folder / SweepStore.MANIFEST
    try:
        manifest = _read_manifest(path)
    except ResultsError as error:
        if not path.exists():
            raise
        raise ResultsError(f"{error}; run the same sweep again with save_to={folder} to "
                           "write it again") from None
    source = manifest["settings"].get("scenes")
    document = source.get("document") if isinstance(source, dict) else None
    _check_states(path, manifest, None if document is None else [document],
                  "points' final states")
    count = len(manifest["values"])
    points = {}
    for index in range(count):
        file = _point_path(folder, index)
        if file.exists():
            try:
                points[index] = _load_point(file)
            except ResultsError as error:
                raise ResultsError(f"{error}; run the same sweep again to compute this "
                                   "point again") from None
    missing = [i for i in range(count) if i not in points]
    if missing:
        raise ResultsError(f"{folder}: {len(missing)} of {count} points are missing; run "
                           "the same sweep again to finish it")
    blade = manifest["blade"]  # a point's component was a tuple, and JSON made it a list
    return Sweep(parameter=manifest["parameter"],
                 blade=tuple(blade) if isinstance(blade, list) else blade,
                 points=tuple(points[i] for i in range(count)), settings=manifest["settings"])


# ---- a branch of periodic orbits ----------------------------------------------------------

_BRANCH_HEADER = (
    _Field("scenes", "a scene document, or one per orbit",
           lambda v: isinstance(v, dict) or (isinstance(v, list)
                                             and all(isinstance(d, dict) for d in v))),
    _Field("parameter_path", "null or a dotted path", lambda v: v is None or isinstance(v, str)),
    _Field("name", "a string", lambda v: isinstance(v, str)),
    _Field("ended", "a string", lambda v: isinstance(v, str)),
    _Field("periods", "an int >= 1", lambda v: _is_count(v) and v >= 1),
    _Field("points", "an int >= 1", lambda v: _is_count(v) and v >= 1),
    _Field("kinds", "a list of bifurcation kinds",
           lambda v: isinstance(v, list) and all(isinstance(k, str) for k in v)),
    _Field("event_counts", "a list of tables of event counts by kind, one per orbit",
           lambda v: isinstance(v, list) and all(_is_event_counts(c) for c in v)),
)


#: The measures a branch file keeps per orbit and response.
_PER_RESPONSE = ("peak", "mean_square", "maximum", "minimum", "mean")
#: The arrays of a branch file, in the order checked: per orbit (its branch points, then
#: the orbits of its bifurcations) its parameter value, state y = (x, ẋ), Floquet
#: multipliers and monodromy matrix, ...; the events of every orbit, one after another
#: (orbit k's from event_offsets[k]); then per bifurcation. The critical multiplier of a
#: nonsmooth bifurcation is NaN.
_BRANCH_ARRAYS = (
    _Array("parameter", ("orbit",)),
    _Array("initial", ("orbit", "state variable")),
    _Array("multipliers", ("orbit", "state variable"), _COMPLEX),
    _Array("monodromy", ("orbit", "state variable", "state variable")),
    _Array("residual", ("orbit",)),
    _Array("scale", ("orbit",)),
    _Array("iterations", ("orbit",), _INTEGER),
    _Array("singular", ("orbit",), _INTEGER),
    *(_Array(name, ("orbit", "response")) for name in _PER_RESPONSE),
    _Array("energy_per_cycle", ("orbit", "energy term")),
    _Array("kinetic_peak", ("orbit",)),
    _Array("event_offsets", ("orbit start",), _INTEGER, rising="not decrease"),
    _Array("event_time", ("event",)),
    *_EVENT_ARRAYS[1:],
    _Array("bifurcation_multiplier", ("bifurcation",), _COMPLEX, finite=False),
    _Array("bifurcation_index", ("bifurcation",), _INTEGER),
    _Array("bifurcation_bracket", ("bifurcation", "bracket end")),
)


def save_branch(path: str | Path, branch: Branch, scene_at=None) -> Path:
    """Write ``branch`` to ``path`` (.npz): every orbit (its branch points, then the
    orbits of its bifurcations) with its multipliers, monodromy matrix and switches (both
    formed now for an orbit that holds only its leading multipliers, or none:
    ``PeriodicOrbit.completed``).

    Each orbit's scene is kept as the scene document of ``scene_at`` (a
    ``scenefile.SceneAt``) with the parameter's path, or else as one document per orbit.
    """
    check_instance("results.save_branch", "branch", branch, Branch,
                   expected="a shroudnet.Branch (what continuation returns)")
    check_instance("results.save_branch", "scene_at", scene_at, scenefile.SceneAt,
                   optional=True, expected="a scenefile.SceneAt or None")
    orbits = [o.completed() for o in (*branch.orbits, *(b.orbit for b in branch.bifurcations))]
    values = [*branch.parameter, *(b.parameter for b in branch.bifurcations)]
    if isinstance(scene_at, scenefile.SceneAt):
        scenes, parameter_path = scene_at.document, scene_at.path
    else:
        scenes, parameter_path = [scenefile.document(o.scene) for o in orbits], None
    counts = np.array([len(o.events.time) for o in orbits])
    meta = {"format": FORMAT, "kind": "branch", "scenes": scenes,
            "parameter_path": parameter_path, "name": branch.name, "ended": branch.ended,
            "periods": branch.periods, "points": len(branch), "kinds":
                [b.kind for b in branch.bifurcations],
            "event_counts": [o.events.counts for o in orbits],
            "notes": list(branch.notes),
            "orbit_notes": [list(o.notes) for o in orbits],
            "neutral": [[int(e) for e in o.neutral] for o in orbits],
            "neutral_directions": [int(o.neutral_directions) for o in orbits]}
    arrays = {"parameter": np.array(values, dtype=float),
              "initial": np.array([o.state for o in orbits]),
              "multipliers": np.array([o.multipliers for o in orbits]),
              "monodromy": np.array([o.monodromy for o in orbits]),
              "residual": np.array([o.residual for o in orbits]),
              "scale": np.array([o.scale for o in orbits]),
              "iterations": np.array([o.iterations for o in orbits]),
              "singular": np.array([o.singular for o in orbits]),
              "peak": np.array([o.peak for o in orbits]),
              "mean_square": np.array([o.mean_square for o in orbits]),
              "maximum": np.array([o.maximum for o in orbits]),
              "minimum": np.array([o.minimum for o in orbits]),
              "mean": np.array([o.mean for o in orbits]),
              "energy_per_cycle": np.array([o.energy_per_cycle.as_array() for o in orbits]),
              "kinetic_peak": np.array([o.kinetic_peak for o in orbits]),
              "event_offsets": np.concatenate([[0], np.cumsum(counts)]),
              "event_time": np.concatenate([o.events.time for o in orbits]),
              "event_interface": np.concatenate([o.events.interface for o in orbits]),
              "event_kind": np.concatenate([o.events.kind for o in orbits]),
              "bifurcation_multiplier": np.array([b.multiplier for b in branch.bifurcations],
                                                 dtype=complex),
              "bifurcation_index": np.array([b.index for b in branch.bifurcations], dtype=int),
              "bifurcation_bracket": np.array([b.bracket for b in branch.bifurcations],
                                              dtype=float).reshape(-1, 2)}
    return _save_npz(path, meta, arrays)


def load_branch(path: str | Path, *, laws: scenefile.Laws = ()) -> Branch:
    """Read a file written by ``save_branch`` back into an equal ``Branch``; ``laws`` as
    for ``load_simulation``."""
    path = Path(path)
    meta, arrays = _load_npz(path, kind="branch")
    _checked(path, meta, _BRANCH_HEADER)
    points, kinds = meta["points"], meta["kinds"]
    total = points + len(kinds)
    if len(meta["event_counts"]) != total:
        raise ResultsError(f"{path}: meta.event_counts has {len(meta['event_counts'])} "
                           f"tables for {total} orbits")
    for k, counts in enumerate(meta["event_counts"]):
        _check_event_kinds(path, counts, f"meta.event_counts[{k}]")
    sizes = {"orbit": total, "bifurcation": len(kinds), "bracket end": 2,
             "energy term": len(dataclasses.fields(EnergyPerCycle))}
    values = _checked_arrays(path, arrays, _BRANCH_ARRAYS[:1], sizes)["parameter"]
    scenes = meta["scenes"]
    _check_states(path, meta, [scenes] if isinstance(scenes, dict) else scenes,
                  "orbits' initial states and monodromy matrices")
    if meta["parameter_path"] is not None:
        document = _scene(path, meta["scenes"], laws).document
        scene_at = scenefile.SceneAt(document, meta["parameter_path"], laws=laws)
        try:
            scenes = [scene_at(value) for value in values]
        except ValueError as error:
            raise ResultsError(f"{path}: its scene at a saved parameter value cannot be "
                               f"rebuilt ({_reason(error)})") from None
    else:
        if len(meta["scenes"]) != total:
            raise ResultsError(f"{path}: {len(meta['scenes'])} scene documents for {total} "
                               "orbits")
        scenes = [_scene(path, document, laws).scene for document in meta["scenes"]]
    sizes.update({"state variable": state_size(scenes[0]),  # (x, ẋ[, u])
                  "response": len(scenes[0].responses),
                  "orbit start": total + 1, "interface": len(scenes[0].contacts)})
    columns = _checked_arrays(path, arrays, _BRANCH_ARRAYS[1:], sizes)
    offsets = columns["event_offsets"]
    if offsets[0] != 0 or offsets[-1] != sizes["event"]:
        raise ResultsError(f"{path}: array 'event_offsets' runs from {offsets[0]} to "
                           f"{offsets[-1]}; it must run from 0 to {sizes['event']}, the "
                           "number of events")
    time = columns["event_time"]
    falls = np.setdiff1d(np.flatnonzero(np.diff(time) < 0) + 1, offsets)
    if len(falls):
        raise ResultsError(f"{path}: array 'event_time' must not decrease within an orbit, "
                           f"it falls at event {falls[0]}")
    index = columns["bifurcation_index"]
    if len(index) and (index.min() < 0 or index.max() >= points):
        raise ResultsError(f"{path}: bifurcation_index holds {index.min()} to "
                           f"{index.max()}; the branch has points 0 to {points - 1}")
    extra = _orbit_notes(path, meta, total)
    orbits = []
    for k, scene in enumerate(scenes):
        run = slice(int(offsets[k]), int(offsets[k + 1]))
        events = EventLog(time=time[run], interface=columns["event_interface"][run],
                          kind=columns["event_kind"][run], counts=meta["event_counts"][k])
        initial = columns["initial"][k]
        orbits.append(PeriodicOrbit(
            scene=scene, initial=tuple(part.copy() for part in state_parts(scene, initial)),
            periods=meta["periods"], multipliers=columns["multipliers"][k],
            monodromy=columns["monodromy"][k], residual=float(columns["residual"][k]),
            scale=float(columns["scale"][k]), iterations=int(columns["iterations"][k]),
            events=events, **{name: columns[name][k] for name in _PER_RESPONSE},
            energy_per_cycle=EnergyPerCycle(*(float(e) for e in columns["energy_per_cycle"][k])),
            kinetic_peak=float(columns["kinetic_peak"][k]),
            singular=int(columns["singular"][k]), neutral=tuple(extra["neutral"][k]),
            neutral_directions=extra["neutral_directions"][k],
            notes=tuple(extra["orbit_notes"][k])))
    bifurcations = tuple(
        Bifurcation(kind=kind, parameter=float(values[points + j]), orbit=orbits[points + j],
                    multiplier=complex(columns["bifurcation_multiplier"][j]),
                    index=int(index[j]),
                    bracket=tuple(float(b) for b in columns["bifurcation_bracket"][j]))
        for j, kind in enumerate(kinds))
    return Branch(parameter=values[:points].copy(), orbits=tuple(orbits[:points]),
                  bifurcations=bifurcations, periods=meta["periods"], name=meta["name"],
                  ended=meta["ended"], notes=tuple(extra["notes"]))


def _is_strings(value) -> bool:
    return isinstance(value, list) and all(isinstance(v, str) for v in value)


#: What a branch file may say beyond its arrays, per orbit and of the branch (files
#: written before it was kept have none of it: empty).
_NOTES = (
    _Field("notes", "a list of strings", _is_strings),
    _Field("orbit_notes", "a list of lists of strings, one per orbit",
           lambda v: isinstance(v, list) and all(_is_strings(n) for n in v)),
    _Field("neutral", "a list of lists of interface indices, one per orbit",
           lambda v: isinstance(v, list) and all(
               isinstance(n, list) and all(_is_count(e) for e in n) for n in v)),
    _Field("neutral_directions", "a list of counts, one per orbit",
           lambda v: isinstance(v, list) and all(_is_count(n) for n in v)),
)


def _orbit_notes(path: Path, meta: dict, total: int) -> dict:
    """The branch's notes and each orbit's notes and neutral interfaces, checked; empty
    where the file has none."""
    present = {field.name: meta[field.name] for field in _NOTES if field.name in meta}
    _checked(path, present, [f for f in _NOTES if f.name in present])
    extra = {"notes": [], "orbit_notes": [[]] * total, "neutral": [[]] * total,
             "neutral_directions": [0] * total}
    extra.update(present)
    for name in ("orbit_notes", "neutral", "neutral_directions"):
        if len(extra[name]) != total:
            raise ResultsError(f"{path}: meta.{name} has {len(extra[name])} entries for "
                               f"{total} orbits")
    return extra


def load(path: str | Path, *, laws: scenefile.Laws = ()) -> Simulation | Sweep | Branch:
    """A simulation file, a branch file or a sweep folder, whichever ``path`` is (``laws``
    as for ``load_simulation``)."""
    path = Path(path)
    if path.is_dir():
        return load_sweep(path)
    if _load_npz(path)[0].get("kind") == "branch":
        return load_branch(path, laws=laws)
    return load_simulation(path, laws=laws)
