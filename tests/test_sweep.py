"""Sweeps: serial, on a process pool and on a dask cluster, with the same points bit for bit."""

import io
import threading
from concurrent.futures import ProcessPoolExecutor
from dataclasses import asdict

import numpy as np
import pytest

from shroudnet import sweep
from shroudnet.progress import TerminalProgress
from shroudnet.scenes import three_blade_paper

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


@pytest.fixture(scope="module")
def serial():
    return sweep(paper_scene_at, GAMMAS, workers=1, **SETTINGS)


def test_a_sweep_equals_its_points_run_one_by_one(serial):
    apart = [sweep(paper_scene_at, [value], **SETTINGS).points[0] for value in (1.0, 3.5)]
    for a, b in zip([serial.points[0], serial.points[2]], apart):
        np.testing.assert_array_equal(a.poincare, b.poincare)
        assert a.energy_density == b.energy_density
    assert serial.labels == [p.classification.label for p in serial.points]
    values, section = serial.diagram()
    assert values.shape == section.shape == (4 * 7,)


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
])
def test_bad_sweep_arguments_are_named(arguments, message):
    with pytest.raises((ValueError, TypeError), match=message):
        sweep(paper_scene_at, [1.0, 2.0], **SETTINGS, **arguments)


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
