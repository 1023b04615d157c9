"""Every file shroudnet writes is written whole or not at all (``shroudnet.atomic``).

A full disc is simulated by a file that takes the first bytes of a write and then raises
ENOSPC, as a file system does when it runs out of room: the file that was there before
must be left byte for byte, the error must name the file, and nothing of the cut write may
remain. A write cut by Ctrl-C leaves nothing either; one cut by a process killed outright
leaves its temporary file, which the next write of the same file removes.
"""

from __future__ import annotations

import errno
import io
import os
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest

from shroudnet import atomic, simulate
from shroudnet.engine import cache
from shroudnet.io import results, scenefile
from shroudnet.run.classification import Classification
from shroudnet.run.simulation import SweepPoint
from shroudnet.scenes import three_blade_paper
from shroudnet.steady.continuation import Branch

from .test_file_validation import orbit

#: Bytes the full disc takes of a write before it refuses the rest.
ROOM = 100


class FullDisc(io.FileIO):
    """A file on a disc with ``ROOM`` bytes left."""

    def write(self, data) -> int:
        if self.tell() + len(data) > ROOM:
            room = max(ROOM - self.tell(), 0)
            super().write(bytes(data)[:room])
            raise OSError(errno.ENOSPC, os.strerror(errno.ENOSPC))
        return super().write(data)


@pytest.fixture
def full_disc(monkeypatch):
    """From now on every file ``atomic.write`` opens is on a full disc."""
    monkeypatch.setattr(atomic.os, "fdopen", lambda handle, mode: FullDisc(handle, "wb"))


def others(folder: Path, *keep: Path) -> list[str]:
    """The names of what ``folder`` holds besides ``keep``."""
    return sorted(p.name for p in folder.iterdir() if p not in keep)


# ---- the helper ----------------------------------------------------------------------------

def test_a_write_replaces_the_file_whole(tmp_path):
    path = tmp_path / "deeper" / "file.bin"
    assert atomic.write(path, lambda file: file.write(b"old")) == path
    atomic.write(path, lambda file: file.write(b"new content"))
    assert path.read_bytes() == b"new content"
    assert others(path.parent, path) == []


def test_a_full_disc_leaves_the_old_file_and_names_it(tmp_path, full_disc):
    path = tmp_path / "file.bin"
    path.write_bytes(b"old")
    with pytest.raises(atomic.WriteError) as caught:
        atomic.write(path, lambda file: file.write(b"x" * (10 * ROOM)))
    assert caught.value.errno == errno.ENOSPC and caught.value.filename == str(path)
    assert str(caught.value) == (f"cannot write {path}: No space left on device; nothing was "
                                 "changed there")
    assert path.read_bytes() == b"old"
    assert others(tmp_path, path) == []


@pytest.mark.parametrize("stop", [KeyboardInterrupt(), ValueError("the writer's own")])
def test_a_write_stopped_by_anything_leaves_the_old_file_and_nothing_else(tmp_path, stop):
    path = tmp_path / "file.bin"
    path.write_bytes(b"old")

    def interrupted(file):
        file.write(b"half")
        raise stop
    with pytest.raises(type(stop)):
        atomic.write(path, interrupted)
    assert path.read_bytes() == b"old"
    assert others(tmp_path, path) == []


def finished_process() -> int:
    """The id of a process that has ended."""
    child = subprocess.Popen([sys.executable, "-c", "pass"])
    child.wait()
    return child.pid


@pytest.mark.skipif(os.name != "posix", reason="whether a process runs is told on POSIX")
def test_the_next_write_removes_what_killed_writes_of_that_file_left(tmp_path):
    path = tmp_path / "run.npz"
    dead = tmp_path / f".run.npz.{finished_process()}-abcd_123.part"
    older = tmp_path / ".run.npz.k2j4_x9q.part"  # the layout without the process's id
    running = tmp_path / f".run.npz.{os.getppid()}-efgh_456.part"  # a write under way
    another = tmp_path / f".run.npz.b.{finished_process()}-abcd_123.part"  # of run.npz.b
    for leftover in (dead, older, running, another):
        leftover.write_bytes(b"cut short")
    assert set(atomic.leftovers(path)) == {dead, older, running}
    atomic.write(path, lambda file: file.write(b"whole"))
    assert others(tmp_path, path) == sorted([running.name, another.name])


# ---- every writer of the project, on a full disc -------------------------------------------

def made_branch() -> Branch:
    scene = three_blade_paper(gamma1=2.0)
    return Branch(parameter=np.array([1.0, 2.0]), orbits=(orbit(scene, 1.0), orbit(scene, 2.0)),
                  bifurcations=(), periods=1, name="q1", ended="stop reached")


def point(value: float) -> SweepPoint:
    label = Classification(label="p1", period=1, n_points=4, tolerance=1e-6, mismatch=0.0,
                           zero_one=0.0, broadband=0.0)
    return SweepPoint(value=value, poincare=np.ones((4, 2)), energy_density=1e-8,
                      friction_loss_per_cycle=1e-3, classification=label,
                      final_state=(np.ones(3), np.zeros(3)), peak=np.ones(3))


def save_scene(folder: Path, attempt: int) -> Path:
    return scenefile.save(folder / "group.toml", three_blade_paper(speed_rpm=5000.0 + attempt))


def save_branch(folder: Path, attempt: int) -> Path:
    branch = made_branch()
    return results.save_branch(folder / "branch.npz", Branch(
        parameter=branch.parameter + attempt, orbits=branch.orbits, bifurcations=(),
        periods=1, name="q1", ended="stop reached"))


def save_sweep_point(folder: Path, attempt: int) -> Path:
    manifest = {"parameter": "q1", "values": [1.0], "settings": {}, "blade": 1}
    results.SweepStore(folder / "sweep", manifest).save(0, point(1.0 + attempt))
    return folder / "sweep" / "points" / "00000.npz"


def save_a_figure(folder: Path, attempt: int) -> Path:
    from matplotlib.figure import Figure

    from shroudnet.front.figures import save_figure
    figure = Figure()
    figure.add_subplot().plot([0, 1], [attempt, 1])
    return save_figure(figure, folder / "figure.png")


def keep_kernel(folder: Path, attempt: int) -> Path:
    name = "kernel_test.py"
    (folder / name).unlink(missing_ok=True)  # a kernel is written once, if missing
    return cache.keep(name, f"# kernel {attempt}\n" + "x = 1\n" * 50)


#: Each writer, and what it raises on a full disc: the error names the file.
WRITERS = {
    "scene file": (save_scene, atomic.WriteError),
    "branch": (save_branch, results.ResultsError),
    "sweep point": (save_sweep_point, results.ResultsError),
    "figure": (save_a_figure, atomic.WriteError),
}


@pytest.mark.parametrize("kind", WRITERS)
def test_every_file_written_on_a_full_disc_leaves_the_old_one(tmp_path, monkeypatch, kind):
    save, error = WRITERS[kind]
    path = save(tmp_path, 0)
    old = path.read_bytes()
    monkeypatch.setattr(atomic.os, "fdopen", lambda handle, mode: FullDisc(handle, "wb"))
    with pytest.raises(error, match=f"cannot (write|save) {path}: No space left on device"):
        save(tmp_path, 1)
    assert path.read_bytes() == old
    assert not atomic.leftovers(path)


def test_a_sweep_manifest_on_a_full_disc_is_refused_by_name(tmp_path, full_disc):
    manifest = {"parameter": "q1", "values": [1.0], "settings": {}, "blade": 1}
    with pytest.raises(results.ResultsError,
                       match=f"cannot save {tmp_path / 'sweep.json'}: No space left"):
        results.SweepStore(tmp_path, manifest)
    assert not (tmp_path / "sweep.json").exists() and others(tmp_path) == []


def test_a_kernel_on_a_full_disc_is_refused_naming_the_cache(tmp_path, monkeypatch,
                                                             full_disc):
    monkeypatch.setenv("SHROUDNET_CACHE", str(tmp_path))
    with pytest.raises(ValueError, match=f"SHROUDNET_CACHE={tmp_path}: cannot write there "
                                         r"\(No space left on device\)"):
        keep_kernel(tmp_path, 0)
    assert others(tmp_path) == []


def test_a_simulation_file_on_a_full_disc_leaves_the_old_one(tmp_path, monkeypatch):
    sim = simulate(three_blade_paper(), 2, samples_per_period=10)
    path = results.save_simulation(tmp_path / "run.npz", sim)
    old = path.read_bytes()
    monkeypatch.setattr(atomic.os, "fdopen", lambda handle, mode: FullDisc(handle, "wb"))
    with pytest.raises(results.ResultsError, match=f"cannot save {path}: No space left"):
        results.save_simulation(path, sim)
    assert path.read_bytes() == old and others(tmp_path, path) == []


def test_a_leftover_that_cannot_be_deleted_does_not_stop_the_write(tmp_path, monkeypatch):
    path = tmp_path / "run.npz"
    leftover = tmp_path / ".run.npz.k2j4_x9q.part"
    leftover.write_bytes(b"cut short")
    unlink = Path.unlink

    def refuse(self, missing_ok=False):
        if self == leftover:
            raise PermissionError(errno.EACCES, "Permission denied")
        unlink(self, missing_ok=missing_ok)
    monkeypatch.setattr(Path, "unlink", refuse)
    atomic.write(path, lambda file: file.write(b"whole"))
    assert path.read_bytes() == b"whole" and leftover.exists()
