"""Saved results: self-describing files that load back without loss, written atomically.

A simulation is one ``.npz`` file: its arrays, and a JSON header ``meta`` holding the
format, the scene as a scene-file document (``scenefile.document``), the settings, the
event counts and the energy ledger. ``load_simulation`` rebuilds the same ``Simulation``,
scene included.

A sweep is a folder: ``sweep.json`` (parameter, values, settings, and what the scenes
came from) and ``points/00012.npz``, one file per finished point, written as it finishes.
``SweepStore`` reopens the folder of an interrupted sweep, so that it runs only the points
still missing; ``load_sweep`` reads a finished one.

Every file is written to a temporary name in its folder and renamed into place, so a run
killed at any moment leaves either the whole file or none.
"""

from __future__ import annotations

import json
import os
import tempfile
from collections.abc import Callable
from dataclasses import asdict
from pathlib import Path

import numpy as np

from . import scenefile
from .analysis import Classification
from .simulation import EnergyLedger, EventLog, Simulation
from .sweep import Sweep, SweepPoint

#: Version of the file layout, stored in every file.
FORMAT = 1


class ResultsError(ValueError):
    """A results file or folder that cannot be read, or a sweep folder that holds another
    sweep."""


def atomic_write(path: str | Path, write: Callable[[object], None]) -> Path:
    """Call ``write(file)`` on a temporary file beside ``path``, then rename it to ``path``."""
    path = Path(path)
    path.parent.mkdir(parents=True, exist_ok=True)
    handle, temporary = tempfile.mkstemp(dir=path.parent, prefix=f".{path.name}.",
                                         suffix=".part")
    try:
        with os.fdopen(handle, "wb") as file:
            write(file)
            file.flush()
            os.fsync(file.fileno())
        os.replace(temporary, path)
    except BaseException:
        Path(temporary).unlink(missing_ok=True)
        raise
    return path


def _save_npz(path, meta: dict, arrays: dict) -> Path:
    header = np.frombuffer(json.dumps(meta).encode(), dtype=np.uint8)
    return atomic_write(path, lambda file: np.savez(file, meta=header, **arrays))


def _load_npz(path) -> tuple[dict, dict]:
    try:
        with np.load(Path(path), allow_pickle=False) as data:
            arrays = {name: data[name] for name in data.files}
    except (OSError, ValueError) as error:
        raise ResultsError(f"{path}: not a shroudnet results file ({error})") from None
    if "meta" not in arrays:
        raise ResultsError(f"{path}: not a shroudnet results file (no meta header)")
    meta = json.loads(arrays.pop("meta").tobytes().decode())
    if meta.get("format") != FORMAT:
        raise ResultsError(f"{path}: results format {meta.get('format')!r}; this shroudnet "
                           f"reads format {FORMAT}")
    return meta, arrays


# ---- a simulation -------------------------------------------------------------------------

def save_simulation(path: str | Path, sim: Simulation,
                    run: scenefile.RunSettings | None = None) -> Path:
    """Write ``sim`` to ``path`` (.npz), scene and settings included, and the scene file's
    run settings (the blade and transient its summaries are about) when given."""
    meta = {"format": FORMAT, "kind": "simulation",
            "scene": scenefile.document(sim.scene, run), "settings": sim.settings,
            "energy": asdict(sim.energy), "event_counts": sim.events.counts,
            "samples_per_period": sim.samples_per_period, "steps": sim.steps}
    arrays = {"t": sim.t, "x": sim.x, "v": sim.v, "normal_force": sim.normal_force,
              "friction_force": sim.friction_force, "modes": sim.modes, "work": sim.work,
              "event_time": sim.events.time, "event_interface": sim.events.interface,
              "event_kind": sim.events.kind}
    return _save_npz(path, meta, arrays)


def load_simulation(path: str | Path) -> Simulation:
    """Read a file written by ``save_simulation`` back into an equal ``Simulation``."""
    meta, arrays = _load_npz(path)
    if meta.get("kind") != "simulation":
        raise ResultsError(f"{path}: holds a {meta.get('kind')}, not a simulation")
    scene = scenefile.read(meta["scene"], source=f"{path} (its scene)").scene
    events = EventLog(time=arrays["event_time"], interface=arrays["event_interface"],
                      kind=arrays["event_kind"], counts=meta["event_counts"])
    return Simulation(scene=scene, settings=meta["settings"], t=arrays["t"], x=arrays["x"],
                      v=arrays["v"], normal_force=arrays["normal_force"],
                      friction_force=arrays["friction_force"], modes=arrays["modes"],
                      events=events, energy=EnergyLedger(**meta["energy"]),
                      work=arrays["work"], samples_per_period=meta["samples_per_period"],
                      steps=meta["steps"])


def load_run_settings(path: str | Path) -> scenefile.RunSettings:
    """The run settings saved with a simulation (the defaults if none were)."""
    meta, _ = _load_npz(path)
    return scenefile.read(meta["scene"], source=f"{path} (its scene)").run


# ---- a sweep, point by point --------------------------------------------------------------

def _save_point(path: Path, point: SweepPoint) -> Path:
    meta = {"format": FORMAT, "kind": "sweep point", "value": point.value,
            "energy_density": point.energy_density,
            "friction_loss_per_cycle": point.friction_loss_per_cycle,
            "classification": asdict(point.classification)}
    arrays = {"poincare": point.poincare, "final_x": point.final_state[0],
              "final_v": point.final_state[1]}
    return _save_npz(path, meta, arrays)


def _load_point(path: Path) -> SweepPoint:
    meta, arrays = _load_npz(path)
    return SweepPoint(value=meta["value"], poincare=arrays["poincare"],
                      energy_density=meta["energy_density"],
                      friction_loss_per_cycle=meta["friction_loss_per_cycle"],
                      classification=Classification(**meta["classification"]),
                      final_state=(arrays["final_x"], arrays["final_v"]))


class SweepStore:
    """The folder of one sweep: its manifest and a file per finished point.

    Opening a folder that already holds the same sweep (same manifest) resumes it;
    one that holds another sweep is refused.
    """

    MANIFEST = "sweep.json"

    def __init__(self, folder: str | Path, manifest: dict):
        self.folder = Path(folder)
        manifest = json.loads(json.dumps({"format": FORMAT, "kind": "sweep", **manifest}))
        existing = self.folder / self.MANIFEST
        if existing.exists():
            found = json.loads(existing.read_text())
            if found != manifest:
                changed = sorted(k for k in set(found) | set(manifest)
                                 if found.get(k) != manifest.get(k))
                raise ResultsError(
                    f"{self.folder} holds another sweep (its {', '.join(changed)} differ); "
                    "resume it with the same arguments, or choose another folder")
        else:
            text = json.dumps(manifest, indent=2).encode()
            atomic_write(existing, lambda file: file.write(text))
        for stale in self.folder.glob("points/.*.part"):  # a write cut short by a kill
            stale.unlink(missing_ok=True)
        self.manifest = manifest

    def finished(self) -> dict[int, SweepPoint]:
        """The points already saved, by index."""
        return _saved_points(self.folder, len(self.manifest["values"]))

    def save(self, index: int, point: SweepPoint) -> None:
        _save_point(_point_path(self.folder, index), point)


def _point_path(folder: Path, index: int) -> Path:
    return folder / "points" / f"{index:05d}.npz"


def _saved_points(folder: Path, count: int) -> dict[int, SweepPoint]:
    return {i: _load_point(_point_path(folder, i)) for i in range(count)
            if _point_path(folder, i).exists()}


def load_sweep(folder: str | Path) -> Sweep:
    """Read a sweep folder; raises ``ResultsError`` if points are missing."""
    folder = Path(folder)
    try:
        manifest = json.loads((folder / SweepStore.MANIFEST).read_text())
    except FileNotFoundError:
        raise ResultsError(f"{folder}: not a sweep folder (no {SweepStore.MANIFEST})") from None
    if manifest.get("format") != FORMAT or manifest.get("kind") != "sweep":
        raise ResultsError(f"{folder}: not a sweep folder of results format {FORMAT}")
    points = _saved_points(folder, len(manifest["values"]))
    missing = [i for i in range(len(manifest["values"])) if i not in points]
    if missing:
        raise ResultsError(f"{folder}: {len(missing)} of {len(manifest['values'])} points are "
                           "missing; run the same sweep again to finish it")
    return Sweep(parameter=manifest["parameter"], blade=manifest["blade"],
                 points=tuple(points[i] for i in range(len(points))),
                 settings=manifest["settings"])


def load(path: str | Path) -> Simulation | Sweep:
    """A simulation file or a sweep folder, whichever ``path`` is."""
    path = Path(path)
    return load_sweep(path) if path.is_dir() else load_simulation(path)
