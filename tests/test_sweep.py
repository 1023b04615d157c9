"""Sweeps: serial, on a process pool and on a dask cluster, with the same points bit for bit;
against direct runs and closed forms; failed points; the workers when the sweep stops."""

import ast
import io
import math
import os
import signal
import subprocess
import sys
import threading
import time
from concurrent.futures import ProcessPoolExecutor
from dataclasses import asdict
from pathlib import Path

import numpy as np
import pytest

from shroudnet import Sweep, simulate, sweep
from shroudnet.front.progress import NoticeLines, ProgressReporter, SweepWarning, TerminalProgress
from shroudnet.io import results
from shroudnet.run.simulation import SweepFailure
from shroudnet.scenes import three_blade_paper
from tests.test_layers import imports_of, module_names

ROOT = Path(__file__).resolve().parents[1]

#: Short enough for a test, long enough to leave the transient: p1 at 1.0, p3 at 3.5.
SETTINGS = {"transient": 20, "record": 6, "samples_per_period": 20}
GAMMAS = [1.0, 2.2, 3.5, 5.0]


def paper_scene_at(gamma1):
    """Module-level, so that worker processes can unpickle it."""
    return three_blade_paper(gamma1=gamma1)


def failing_scene_at(gamma1):
    if gamma1 > 2.0:
        raise ValueError("no scene here")
    return three_blade_paper(gamma1=gamma1)


def assert_same_points(sweep_a, sweep_b):
    assert len(sweep_a.points) == len(sweep_b.points)
    for a, b in zip(sweep_a.points, sweep_b.points):
        assert a.value == b.value
        np.testing.assert_array_equal(a.poincare, b.poincare)
        assert a.energy_density == b.energy_density
        assert a.friction_loss_per_cycle == b.friction_loss_per_cycle
        # NaN-aware: the 0–1 test gives NaN on so short a record
        np.testing.assert_equal(asdict(a.classification), asdict(b.classification))
        for state_a, state_b in zip(a.final_state, b.final_state):
            np.testing.assert_array_equal(state_a, state_b)
        np.testing.assert_array_equal(a.peak, b.peak)


@pytest.fixture(scope="module")
def serial():
    return sweep(paper_scene_at, GAMMAS, workers=1, **SETTINGS)


def test_a_sweep_equals_its_points_run_one_by_one(serial):
    apart = [sweep(paper_scene_at, [value], **SETTINGS).points[0] for value in (1.0, 3.5)]
    for a, b in zip([serial.points[0], serial.points[2]], apart):
        np.testing.assert_array_equal(a.poincare, b.poincare)
        assert a.energy_density == b.energy_density
    assert serial.labels == [p.classification.label for p in serial.points]


def test_each_point_is_the_steady_part_of_one_direct_run(serial):
    """A point equals one ``simulate`` over transient + record periods, read after the
    transient (the sweep restarts at the transient's end, so they agree to the
    integrator's tolerance, not bit for bit), and the diagram lists exactly those
    Poincaré points against their value."""
    transient, record = SETTINGS["transient"], SETTINGS["record"]
    values, section = serial.diagram()
    rows = 0
    for gamma1, point in zip(GAMMAS, serial.points):
        run = simulate(paper_scene_at(gamma1), transient + record,
                       samples_per_period=SETTINGS["samples_per_period"])
        direct = run.poincare("blade2", skip=transient)
        scale = np.abs(direct).max(axis=0)
        assert point.value == gamma1 and point.poincare.shape == (record + 1, 2)
        np.testing.assert_allclose(point.poincare / scale, direct / scale, rtol=0, atol=1e-6)
        assert point.energy_density == pytest.approx(run.energy_density("blade2",
                                                                        skip=transient),
                                                     rel=1e-6)
        np.testing.assert_allclose(point.final_state[0], run.x[-1],
                                   atol=1e-6 * np.abs(run.x).max())
        np.testing.assert_array_equal(values[rows:rows + record + 1], gamma1)
        np.testing.assert_array_equal(section[rows:rows + record + 1], point.poincare[:, 0])
        rows += record + 1
    assert rows == len(values) == len(section)


def test_a_sweep_without_contact_gives_the_linear_steady_response():
    """With gaps no motion closes, each blade is a forced linear oscillator: after the
    transient its Poincaré points are A (sin(φ − θ), ω cos(φ − θ)) with
    A = q1 / |k − m ω² + i c ω|, θ = arg(k − m ω² + i c ω), and E_ρ = A²/2, through the
    resonance (6487.5 rpm) and off it."""
    speeds = [5000.0, 6487.5, 7000.0]

    def free_scene_at(speed_rpm):
        return three_blade_paper(speed_rpm=speed_rpm, gap=1.0)

    result = sweep(free_scene_at, speeds, parameter="speed_rpm", blade="blade2",
                   transient=160, record=4, samples_per_period=20, workers=1)
    for speed, point in zip(speeds, result.points):
        a = free_scene_at(speed).arrays
        w = a.excitation_frequency
        impedance = a.stiffness[1] - a.mass[1] * w * w + 1j * a.damping[1] * w
        amplitude, lag = 50.0 / abs(impedance), np.angle(impedance)
        expected = amplitude * np.array([np.sin(a.phases[1] - lag),
                                         w * np.cos(a.phases[1] - lag)])
        scale = amplitude * np.array([1.0, w])
        np.testing.assert_allclose(point.poincare / scale, np.tile(expected / scale, (5, 1)),
                                   rtol=0, atol=1e-6)
        assert point.energy_density == pytest.approx(amplitude ** 2 / 2, rel=1e-6)
        assert point.friction_loss_per_cycle == 0.0
        assert point.classification.label == "p1"
    assert not result.failures


def test_continuation_starts_each_point_from_the_last(serial):
    chained = sweep(paper_scene_at, [1.0, 3.5], continuation=True, **SETTINGS)
    first = sweep(paper_scene_at, [1.0], **SETTINGS)
    second = sweep(paper_scene_at, [3.5], initial=first.points[0].final_state, **SETTINGS)
    np.testing.assert_array_equal(chained.points[1].poincare, second.points[0].poincare)
    assert not np.array_equal(chained.points[1].poincare, serial.points[2].poincare)


def test_a_process_pool_gives_the_serial_points_bit_for_bit(serial):
    assert_same_points(sweep(paper_scene_at, GAMMAS, workers=2, **SETTINGS), serial)
    with ProcessPoolExecutor(max_workers=2) as pool:
        assert_same_points(sweep(paper_scene_at, GAMMAS, executor=pool, **SETTINGS), serial)


@pytest.mark.slow  # starting a local dask cluster of two processes takes seconds
def test_a_dask_cluster_gives_the_serial_points_bit_for_bit(serial):
    from distributed import Client, LocalCluster

    with LocalCluster(n_workers=2, threads_per_worker=1, processes=True, host="127.0.0.1",
                      dashboard_address=None) as cluster, Client(cluster) as client:
        assert len(client.scheduler_info()["workers"]) == 2
        assert_same_points(sweep(paper_scene_at, GAMMAS, executor=client, **SETTINGS), serial)
        assert_same_points(sweep(paper_scene_at, GAMMAS, executor=client.get_executor(),
                                 **SETTINGS), serial)


def test_a_failing_point_names_its_value():
    for workers in (1, 2):
        with pytest.raises(ValueError, match="no scene here") as caught:
            sweep(failing_scene_at, [1.0, 3.0], parameter="gamma1", workers=workers,
                  **SETTINGS)
        assert "in the sweep point gamma1 = 3" in "".join(caught.value.__notes__)


def test_progress_counts_every_point_and_can_be_silenced(serial, capsys):
    calls = []
    sweep(paper_scene_at, [1.0, 2.2], workers=1, progress=lambda *a: calls.append(a),
          **SETTINGS)
    assert calls == [(0, 2), (1, 2), (2, 2)]
    sweep(paper_scene_at, [1.0], progress=False, **SETTINGS)
    sweep(paper_scene_at, [1.0], progress="auto", **SETTINGS)  # stderr is no terminal here
    assert capsys.readouterr().err == ""

    stream = io.StringIO()
    show = TerminalProgress("sweep", stream=stream)
    for done in range(4):
        show(done, 3)
    lines = stream.getvalue().split("\r")
    assert lines[1].startswith("  sweep 0/3 points")
    assert "left" in lines[2] and "points/s" in lines[2]
    assert lines[-1].startswith("  sweep 3/3 points") and lines[-1].rstrip().endswith("in all")
    assert lines[-1].endswith("\n")


@pytest.mark.parametrize("arguments, message", [
    ({"workers": 0}, "sweep.workers must be an int >= 1"),
    ({"workers": 2, "executor": ProcessPoolExecutor}, "not both"),
    ({"workers": 2, "continuation": True}, "continuation chains"),
    ({"executor": object()}, "sweep.executor must be"),
    ({"progress": "loud"}, "progress must be"),
    ({"save_to": "unused", "store": lambda manifest, notice: None},
     r"give save_to \(a folder\) or store"),
    ({"store": object()}, "sweep.store must be a callable"),
])
def test_bad_sweep_arguments_are_named(arguments, message):
    with pytest.raises((ValueError, TypeError), match=message):
        sweep(paper_scene_at, [1.0, 2.0], **SETTINGS, **arguments)


class MemoryStore:
    """A store of one's own (``sweep.StoreOpener`` and ``sweep.PointStore`` at once): the
    points in a dict, kept from one sweep to the next."""

    def __init__(self):
        self.manifests, self.points = [], {}

    def __call__(self, manifest, *, notice):
        self.manifests.append(manifest)
        return self

    def finished(self):
        return dict(self.points)

    def save(self, index, point):
        self.points[index] = point


def test_a_store_of_ones_own_keeps_the_points_and_a_sweep_resumes_from_it(serial):
    store = MemoryStore()
    first = sweep(paper_scene_at, GAMMAS[:2], parameter="gamma1", workers=1, store=store,
                  progress=False, **SETTINGS)
    assert_same_points(first, Sweep("gamma1", 1, serial.points[:2], {}))
    assert sorted(store.points) == [0, 1]
    manifest, = store.manifests
    assert (manifest["parameter"], manifest["blade"], manifest["values"]) == ("gamma1", 1,
                                                                              GAMMAS[:2])
    assert manifest["settings"] == first.settings

    counts = []
    again = sweep(paper_scene_at, GAMMAS[:2], parameter="gamma1", workers=1, store=store,
                  progress=lambda done, total: counts.append((done, total)), **SETTINGS)
    assert counts == [(2, 2)]  # nothing run: every point was kept
    assert_same_points(again, first)


def test_progress_true_draws_the_terminal_display_the_package_supplies(capsys):
    sweep(paper_scene_at, [1.0], workers=1, progress=True, **SETTINGS)
    err = capsys.readouterr().err
    assert "  sweep 0/1 points" in err and "  sweep 1/1 points" in err and err.endswith("\n")


def test_a_lambda_runs_on_worker_processes(serial):
    assert_same_points(sweep(lambda g: three_blade_paper(gamma1=g), GAMMAS, workers=2,
                             **SETTINGS), serial)


def test_a_scene_function_that_cannot_be_pickled_gets_a_clear_error():
    lock = threading.Lock()

    def scene_at(gamma1):
        with lock:
            return three_blade_paper(gamma1=gamma1)

    with pytest.raises(TypeError, match="cannot be sent to worker processes.*workers=1"):
        sweep(scene_at, [1.0, 2.0], workers=2, **SETTINGS)
    assert len(sweep(scene_at, [1.0, 2.0], workers=1, **SETTINGS).points) == 2


# ---- points that fail ---------------------------------------------------------------------

#: gamma1 values whose scene is driven so hard (q1 = 1e308 N) that the state overflows in
#: the first period: ``simulate`` stops with a ``SimulationError`` (a non-finite state).
OVERFLOWING = {3.5}


def overflowing_scene_at(gamma1):
    """The paper's group, but at the values of ``OVERFLOWING`` one whose run fails."""
    return three_blade_paper(gamma1=gamma1, q1=1e308 if gamma1 in OVERFLOWING else 50.0)


class Recorder(ProgressReporter):
    """Keeps every count and notice it is given."""

    def __init__(self):
        self.counts, self.notices = [], []

    def __call__(self, done, total):
        self.counts.append((done, total))

    def notice(self, message):
        self.notices.append(message)


def assert_failed_at(result, index, value, parameter="gamma1"):
    """The point ``index`` of ``result`` failed on a non-finite state, and only it."""
    assert result.failures == (SweepFailure(parameter, index, value,
                                            result.points[index].error),)
    failure = result.failures[0]
    assert "non-finite" in failure.message and "t = " in failure.message
    assert str(failure).startswith(f"{parameter} = {value:g} (point {index}) failed: ")
    point = result.points[index]
    assert point.failed and point.value == value and point.poincare.shape == (0, 2)
    assert np.isnan(point.energy_density) and np.isnan(point.friction_loss_per_cycle)
    assert result.labels[index] == "failed"


def test_a_point_whose_simulation_fails_leaves_a_gap_and_the_sweep_goes_on(serial):
    """3.5 fails; 1.0 and 2.2 are the serial sweep's points, bit for bit, however the
    points are spread. The failure is told as a notice; the diagram skips its value."""
    for workers in (1, 2):
        recorder = Recorder()
        result = sweep(overflowing_scene_at, [1.0, 3.5, 2.2], parameter="gamma1",
                       workers=workers, progress=recorder, **SETTINGS)
        assert_failed_at(result, 1, 3.5)
        assert_same_points(Sweep("gamma1", 1, (result.points[0], result.points[2]), {}),
                           Sweep("gamma1", 1, serial.points[:2], {}))
        assert result.values.tolist() == [1.0, 3.5, 2.2]
        values, section = result.diagram()
        assert 3.5 not in values and len(values) == len(section) == 2 * 7
        assert recorder.counts[0] == (0, 3) and recorder.counts[-1] == (3, 3)
        assert recorder.notices == [str(result.failures[0])]


def test_a_failed_point_is_a_warning_when_progress_is_a_plain_callable():
    with pytest.warns(SweepWarning, match=r"gamma1 = 3\.5 \(point 0\) failed: .*non-finite"):
        result = sweep(overflowing_scene_at, [3.5], parameter="gamma1", workers=1,
                       progress=lambda done, total: None, **SETTINGS)
    assert_failed_at(result, 0, 3.5)


def test_the_bifurcation_figure_leaves_a_failed_point_out():
    from shroudnet.front.figures import bifurcation_diagram

    result = sweep(overflowing_scene_at, [1.0, 3.5], parameter="gamma1", workers=1,
                   progress=Recorder(), **SETTINGS)
    lines = bifurcation_diagram(result).axes[0].get_lines()
    plotted = np.concatenate([line.get_xdata() for line in lines])
    assert set(plotted.tolist()) == {1.0}


def test_continuation_goes_on_from_the_last_point_that_did_not_fail():
    chained = sweep(overflowing_scene_at, [1.0, 3.5, 2.2], continuation=True,
                    parameter="gamma1", progress=Recorder(), **SETTINGS)
    assert_failed_at(chained, 1, 3.5)
    after = sweep(paper_scene_at, [2.2], initial=chained.points[0].final_state, **SETTINGS)
    np.testing.assert_array_equal(chained.points[2].poincare, after.points[0].poincare)


def test_failed_points_are_saved_kept_on_resuming_and_run_again_when_asked(tmp_path, serial,
                                                                           monkeypatch):
    folder = tmp_path / "sweep"
    options = dict(parameter="gamma1", workers=1, save_to=folder, **SETTINGS)
    first = sweep(overflowing_scene_at, [1.0, 3.5], progress=Recorder(), **options)
    assert_failed_at(first, 1, 3.5)
    saved = results.load(folder)
    assert saved.failures == first.failures and saved.labels == first.labels
    assert first.labels[1] == "failed" and first.labels[0] != "failed"
    files = sorted((folder / "points").iterdir())
    stamps = [file.stat().st_mtime_ns for file in files]

    recorder = Recorder()
    again = sweep(overflowing_scene_at, [1.0, 3.5], progress=recorder, **options)
    assert recorder.counts == [(2, 2)]  # nothing run: the failure is kept
    assert recorder.notices == ["kept 1 failed point(s) of the saved sweep (gamma1 = 3.5); "
                                "pass retry_failed=True to run them again"]
    assert again.failures == first.failures
    assert [file.stat().st_mtime_ns for file in files] == stamps

    monkeypatch.setattr(sys.modules[__name__], "OVERFLOWING", set())  # what failed is fixed
    recorder = Recorder()
    retried = sweep(overflowing_scene_at, [1.0, 3.5], progress=recorder, retry_failed=True,
                    **options)
    assert recorder.counts == [(1, 2), (2, 2)] and not recorder.notices
    assert not retried.failures
    assert_same_points(retried, Sweep("gamma1", 1, (serial.points[0], serial.points[2]), {}))
    assert files[0].stat().st_mtime_ns == stamps[0]  # the good point is not run again
    assert not results.load(folder).failures


@pytest.mark.slow  # compiles a kernel for the stop's own law
def test_a_point_that_meets_the_zeno_guard_is_a_failed_point():
    """The bouncing blade of test_hard_cases meets the Zeno guard at α = π/3 and sticks at
    α = 0.2: the sweep over α keeps the one and fails the other, on a pool too."""
    for workers in (1, 2):
        recorder = Recorder()
        result = sweep(_stop_at, [0.2, math.pi / 3], parameter="angle", blade="blade",
                       transient=0, record=4, samples_per_period=20, workers=workers,
                       progress=recorder)
        assert [point.failed for point in result.points] == [False, True]
        failure, = result.failures
        assert failure.index == 1 and failure.value == math.pi / 3
        assert "Zeno or chattering behaviour" in failure.message
        assert recorder.notices == [str(failure)]
        assert np.isfinite(result.points[0].energy_density)


def _stop_at(angle):
    """The bouncing blade of test_hard_cases at contact angle ``angle`` [rad]."""
    from contact_laws import Coulomb
    from shroudnet import Interface
    from tests.laws import PreloadedStop
    from tests.test_hard_cases import blade_against_a_stop

    return blade_against_a_stop(Interface(gap=1e-4, angle=angle,
                                          normal=PreloadedStop(preload=50.0, stiffness=1e6),
                                          friction=Coulomb(mu=0.3)), mean_force=30.0)


def test_terminal_progress_writes_a_notice_on_its_own_line():
    stream = io.StringIO()
    show = TerminalProgress("sweep", stream=stream)
    show(0, 3)
    show(1, 3)
    show.notice("gamma1 = 3.5 (point 1) failed: non-finite")
    text = stream.getvalue()
    before, notice, after = text.rsplit("\r", 2)
    assert notice.startswith("  gamma1 = 3.5 (point 1) failed: non-finite") and \
        notice.endswith("\n")
    assert after.startswith("  sweep 1/3 points") and not after.endswith("\n")


# ---- the worker processes when the sweep's process stops ----------------------------------

CHILD = '''
import os, signal, sys
from pathlib import Path
from shroudnet import sweep
from shroudnet.scenes import three_blade_paper

FOLDER = Path(sys.argv[1])
# A command in a terminal takes Ctrl-C; one started in the background inherits it ignored.
signal.signal(signal.SIGINT, signal.default_int_handler)


def scene_at(gamma1):
    (FOLDER / f"pid-{os.getpid()}").touch()  # the process that runs this point
    return three_blade_paper(gamma1=gamma1)


if __name__ == "__main__":
    try:
        sweep(scene_at, [1.0, 2.0, 3.0, 4.0, 5.0, 6.0], transient=int(sys.argv[2]), record=3,
              samples_per_period=4, workers=2, progress=False, save_to=FOLDER / "sweep")
    except KeyboardInterrupt:
        print("interrupted", flush=True)
        sys.exit(130)
'''


def start_sweep_process(folder, transient):
    """A sweep on two workers in a process of its own session (as a terminal's command)."""
    script = folder / "child.py"
    script.write_text(CHILD)
    return subprocess.Popen([sys.executable, str(script), str(folder), str(transient)],
                            cwd=ROOT, stdout=subprocess.PIPE, stderr=subprocess.PIPE,
                            text=True, start_new_session=True)


def wait_for(condition, seconds, what):
    deadline = time.monotonic() + seconds
    while not condition():
        if time.monotonic() > deadline:
            raise AssertionError(f"no {what} within {seconds} s")
        time.sleep(0.05)


def worker_pids(folder, process) -> set[int]:
    pids = {int(path.name[4:]) for path in folder.glob("pid-*")}
    return pids - {process.pid}


def running(pid) -> bool:
    psutil = pytest.importorskip("psutil")
    try:
        return psutil.Process(pid).status() != psutil.STATUS_ZOMBIE
    except psutil.NoSuchProcess:
        return False


def kill_left(pids):
    for pid in pids:
        if running(pid):
            os.kill(pid, signal.SIGKILL)


@pytest.mark.slow
def test_the_workers_exit_when_the_sweep_process_is_killed(tmp_path):
    """SIGKILL of the sweep's process, while both workers are deep in points of minutes:
    both are gone within 20 s (not orphans computing on)."""
    process = start_sweep_process(tmp_path, transient=2_000_000)
    workers = set()
    try:
        wait_for(lambda: len(worker_pids(tmp_path, process)) == 2, 120, "two workers")
        workers = worker_pids(tmp_path, process)
        time.sleep(0.5)  # inside the compiled loop now
        assert all(running(pid) for pid in workers)
        os.kill(process.pid, signal.SIGKILL)
        process.communicate()
        wait_for(lambda: not any(running(pid) for pid in workers), 20, "end of the workers")
    finally:
        process.kill()
        kill_left(workers)


@pytest.mark.slow
def test_ctrl_c_stops_the_workers_at_once_without_noise_and_keeps_the_saved_points(tmp_path):
    """Ctrl-C (SIGINT to the process group) after the first points are saved: the sweep
    raises KeyboardInterrupt alone, prints nothing, stops the workers without waiting for
    their points, and every saved point loads."""
    process = start_sweep_process(tmp_path, transient=30_000)
    workers = set()
    points = tmp_path / "sweep" / "points"
    try:
        wait_for(lambda: list(points.glob("*.npz")), 120, "saved point")
        time.sleep(0.5)
        saved = sorted(points.glob("*.npz"))
        workers = worker_pids(tmp_path, process)
        assert 1 <= len(saved) < 6 and all(running(pid) for pid in workers)
        os.killpg(process.pid, signal.SIGINT)
        out, err = process.communicate(timeout=60)
        assert (process.returncode, out, err) == (130, "interrupted\n", "")
        wait_for(lambda: not any(running(pid) for pid in workers), 20, "end of the workers")
        assert sorted(points.glob("*")) == saved  # the running points were not finished
        for path in saved:
            results._load_point(path)
    finally:
        process.kill()
        kill_left(workers)


def test_notice_lines_write_only_the_notices():
    stream = io.StringIO()
    lines = NoticeLines(stream)
    lines(0, 3)
    lines.notice("first")
    lines(1, 3)
    lines.notice("second")
    assert stream.getvalue() == "  first\n  second\n"


# ---- module boundaries --------------------------------------------------------------------

def imported_modules(path: Path, tree: ast.AST | None = None) -> set[str]:
    """The shroudnet modules the module at ``path`` (or the part ``tree`` of it) imports
    anywhere (functions included), by their name in the package ("io.results",
    "engine.codes", ...)."""
    modules = module_names()
    name = next(name for name, found in modules.items() if found == path.resolve())
    return imports_of(name, path.resolve(), modules, tree)


def test_the_sweep_computation_imports_no_file_terminal_or_figure_code():
    """Importing shroudnet, or the sweep, loads neither results nor the terminal displays
    nor the command line nor the figures (in a fresh process). The sweep computation names
    none of them at all (``tests/test_layers.py`` holds every folder to its layer); the
    sweep the package offers (``front.studies``) imports results and the terminal display
    only inside itself, when a sweep asks for ``save_to=FOLDER`` or ``progress="auto"``.
    The records that runs return live beside ``Simulation``, so results does not import
    the sweep."""
    front = ("io.results", "front.progress", "front.cli", "front.figures")
    code = ("import shroudnet, shroudnet.studies.sweep, sys; print([m for m in sys.modules "
            f"if m in {tuple('shroudnet.' + name for name in front)}])")
    done = subprocess.run([sys.executable, "-c", code], cwd=ROOT, capture_output=True,
                          text=True, check=True)
    assert done.stdout.strip() == "[]"
    package = ROOT / "shroudnet"
    assert not imported_modules(package / "studies" / "sweep.py") & set(front)
    tree = ast.parse((package / "front" / "studies.py").read_text())
    outside_functions = ast.Module([node for node in tree.body
                                    if not isinstance(node, ast.FunctionDef)], [])
    assert not imported_modules(package / "front" / "studies.py", outside_functions) \
        & set(front)
    assert "studies.sweep" not in imported_modules(package / "io" / "results.py")
    assert ProgressReporter.__module__ == SweepWarning.__module__ == "shroudnet.run.reporting"
    assert not imported_modules(package / "run" / "reporting.py")
    from shroudnet import SweepFailure, SweepPoint
    assert {Sweep.__module__, SweepPoint.__module__, SweepFailure.__module__} == {
        "shroudnet.run.simulation"}


def test_the_method_settings_have_a_module_the_scene_files_read_them_from():
    import shroudnet
    from shroudnet.run import methods

    for name in ("FixedStep", "Adaptive", "Accuracy", "ZenoGuard"):
        settings = getattr(methods, name)
        assert settings.__module__ == "shroudnet.run.methods"
        assert getattr(shroudnet, name) is settings
    assert (methods.ACCURACY_MARGIN, methods.ZENO_WINDOW_TOLERANCES,
            methods.ZENO_WINDOW_LIMIT) == (100.0, 1e6, 1e-3)
    scenefile = imported_modules(ROOT / "shroudnet" / "io" / "scenefile.py")
    assert "run.methods" in scenefile and "run.simulate" not in scenefile
