"""Sweeps and maps on a GPU, tested without one.

numba's CUDA simulator (``NUMBA_ENABLE_CUDASIM=1``) runs the batch kernel's generated
entry on the CPU, each thread calling the CPU kernel it compiles for the device: the
records the entry builds in each thread's local arrays, the scene rows it reads, the two
runs it makes (transient, recorded) and the samples it reduces are those of a GPU run,
and must give, point for point, what the CPU engine's fixed-step sweep gives. The
simulator must be chosen before ``numba.cuda`` is first imported, so it runs in a process
of its own; the rest of the suite never sees it. ``tests.gpu_scenes.every_law`` carries
every built-in law (and a user's own normal and friction law) in one scene, so that one
kernel covers them all: its CPU kernel is compiled once for the reference and the
simulated batch (a new flavour: these tests are slow).
"""

from __future__ import annotations

import importlib.util
import os
import pickle
import subprocess
import sys
import textwrap
from pathlib import Path

import numpy as np
import pytest

import shroudnet
from shroudnet import FixedStep
from shroudnet.run.batch import NoDevice
from shroudnet.studies.gpu import warp_order
from tests.gpu_scenes import RUNS, SPEEDS, STEPS_PER_PERIOD, every_law

ROOT = Path(__file__).resolve().parents[1]
METHOD = FixedStep(steps_per_period=STEPS_PER_PERIOD)
AMPLITUDES = (20.0, 30.0)
HAS_NUMBA_CUDA = importlib.util.find_spec("numba_cuda") is not None

_SIMULATED = textwrap.dedent("""
    import pickle, sys
    from shroudnet import FixedStep, sweep, sweep_map
    from tests.gpu_scenes import RUNS, SPEEDS, STEPS_PER_PERIOD, every_law
    method = FixedStep(steps_per_period=STEPS_PER_PERIOD)
    swept = sweep(every_law, SPEEDS, parameter="speed_rpm", blade="b2", method=method,
                  executor="cuda", workers=1, progress=False, **RUNS)
    mapped = sweep_map(every_law, SPEEDS[:2], {amplitudes!r}, parameters=("speed_rpm", "q1"),
                       blade="b2", method=method, executor="cuda", workers=1, **RUNS)
    recorded = dict(RUNS, transient=0)
    at_once = sweep(every_law, SPEEDS[:2], blade="b2", method=method, executor="cuda",
                    workers=1, progress=False, **recorded)
    with open(sys.argv[1], "wb") as file:
        pickle.dump((swept, mapped, at_once), file)
""")


@pytest.fixture(scope="module")
def simulated(tmp_path_factory):
    """The sweep and the map of ``every_law`` run by the batch kernel under the simulator."""
    if not HAS_NUMBA_CUDA:
        pytest.skip("numba-cuda is not installed (pip install 'shroudnet[test]')")
    path = tmp_path_factory.mktemp("gpu") / "simulated.pkl"
    env = {**os.environ, "NUMBA_ENABLE_CUDASIM": "1"}
    env["PYTHONPATH"] = os.pathsep.join([str(ROOT), env.get("PYTHONPATH", "")])
    done = subprocess.run([sys.executable, "-c", _SIMULATED.format(amplitudes=AMPLITUDES),
                           str(path)], cwd=ROOT, env=env, capture_output=True, text=True,
                          timeout=1500)
    assert done.returncode == 0, done.stderr[-3000:]
    with open(path, "rb") as file:
        return pickle.load(file)


@pytest.fixture(scope="module")
def on_cpu():
    """The same sweep by the CPU engine's fixed-step method, point by point."""
    return shroudnet.sweep(every_law, SPEEDS, parameter="speed_rpm", blade="b2",
                           method=METHOD, workers=1, progress=False, **RUNS)


def _assert_same_point(gpu, cpu):
    """A point of the batch equals the CPU's to rounding: its Poincaré points and final
    state relative to the motion's size, E_ρ and the friction loss relative to their own,
    and its classification (but the broadband fraction, which needs the time history)."""
    assert gpu.error is None and cpu.error is None
    scale = np.abs(cpu.poincare).max(axis=0)
    np.testing.assert_allclose(gpu.poincare / scale, cpu.poincare / scale, rtol=0, atol=1e-12)
    np.testing.assert_allclose(gpu.energy_density, cpu.energy_density, rtol=1e-12)
    np.testing.assert_allclose(gpu.friction_loss_per_cycle, cpu.friction_loss_per_cycle,
                               rtol=1e-11)
    for mine, theirs in zip(gpu.final_state, cpu.final_state):
        size = np.abs(theirs).max()
        np.testing.assert_allclose(mine / size, theirs / size, rtol=0, atol=1e-12)
    assert gpu.classification.label == cpu.classification.label
    assert gpu.classification.mismatch == pytest.approx(cpu.classification.mismatch,
                                                        rel=1e-9, abs=1e-12)
    assert np.isnan(gpu.classification.broadband)


@pytest.mark.slow
def test_the_every_law_scene_exercises_every_law():
    """What makes the equality below cover every law: in the CPU runs of the scene, each
    interface closes (its normal law acts) and slips (its friction law acts), and two of
    them stick and break away again."""
    from shroudnet import simulate
    from shroudnet.engine.codes import Mode

    for speed in (SPEEDS[0], SPEEDS[-1]):
        sim = simulate(every_law(speed), RUNS["transient"] + RUNS["record"], method=METHOD,
                       samples_per_period=RUNS["samples_per_period"])
        modes = sim.modes
        slipping = (modes == Mode.SLIP_POSITIVE) | (modes == Mode.SLIP_NEGATIVE)
        assert slipping.any(axis=0).all()
        assert sim.events.counts["breakaway"] > 0
    assert (modes == Mode.STICK).any(axis=0).sum() >= 1
    first = simulate(every_law(SPEEDS[0]), RUNS["transient"] + RUNS["record"], method=METHOD,
                     samples_per_period=RUNS["samples_per_period"])
    assert (first.modes == Mode.STICK).any(axis=0).sum() >= 2


@pytest.mark.slow
@pytest.mark.timeout(1800)
def test_a_sweep_on_the_gpu_equals_the_cpu_fixed_step_sweep(simulated, on_cpu):
    swept, _, _ = simulated
    assert swept.parameter == "speed_rpm" and swept.settings["executor"] == "cuda"
    np.testing.assert_array_equal(swept.values, on_cpu.values)
    for gpu, cpu in zip(swept.points, on_cpu.points):
        _assert_same_point(gpu, cpu)


@pytest.mark.slow
@pytest.mark.timeout(1800)
def test_a_map_on_the_gpu_holds_each_cells_sweep_point(simulated, on_cpu):
    """Each cell of the map at q1 = 30 N (the scene's default) is the sweep's point at its
    speed; the cells at 20 N are those of the CPU's own sweep at that amplitude."""
    _, mapped, _ = simulated
    assert mapped.parameters == ("speed_rpm", "q1")
    np.testing.assert_array_equal(mapped.first, SPEEDS[:2])
    np.testing.assert_array_equal(mapped.second, AMPLITUDES)
    at_20 = shroudnet.sweep(lambda speed: every_law(speed, q1=20.0), SPEEDS[:2],
                            blade="b2", method=METHOD, workers=1, progress=False, **RUNS)
    for row, speed in enumerate(SPEEDS[:2]):
        cells = mapped.rows[row].points
        assert [cell.value for cell in cells] == list(AMPLITUDES)
        _assert_same_point(cells[1], on_cpu.points[row])
        _assert_same_point(cells[0], at_20.points[row])
    assert mapped.labels.shape == (2, 2)
    assert np.isfinite(mapped.grid("energy_density")).all()


@pytest.mark.slow
@pytest.mark.timeout(1800)
def test_a_sweep_on_the_gpu_without_transient_equals_the_cpus(simulated):
    """With no transient periods each thread makes the recorded run alone, from the start."""
    _, _, at_once = simulated
    cpu = shroudnet.sweep(every_law, SPEEDS[:2], blade="b2", method=METHOD, workers=1,
                          progress=False, **dict(RUNS, transient=0))
    for gpu, point in zip(at_once.points, cpu.points):
        _assert_same_point(gpu, point)


def test_without_a_gpu_the_cuda_executor_is_refused_in_one_line():
    """No GPU here (and no simulator in this process): the sweep says what is missing,
    in one line, before any point runs."""
    if os.environ.get("NUMBA_ENABLE_CUDASIM", "0") not in ("", "0"):
        pytest.skip("the simulator stands in for a GPU in this process")
    with pytest.raises(NoDevice) as refused:
        shroudnet.sweep(every_law, SPEEDS, method=METHOD, executor="cuda", progress=False,
                        **RUNS)
    message = str(refused.value)
    assert "\n" not in message and "executor='cuda'" in message
    assert ("no CUDA GPU" in message or "not installed" in message
            or "cannot reach" in message)


def test_without_numba_cuda_the_cuda_executor_says_what_to_install(monkeypatch):
    real = importlib.util.find_spec
    monkeypatch.setattr(importlib.util, "find_spec",
                        lambda name, *args: None if name == "numba_cuda" else real(name, *args))
    with pytest.raises(NoDevice, match=r"numba-cuda is not installed \(pip install "
                                       r"'shroudnet\[gpu\]'\)$"):
        shroudnet.sweep(every_law, SPEEDS, method=METHOD, executor="cuda", progress=False,
                        **RUNS)


def test_the_cuda_executor_takes_the_fixed_step_method_and_no_exponent():
    with pytest.raises(ValueError, match="method=FixedStep"):
        shroudnet.sweep(every_law, SPEEDS, executor="cuda", progress=False, **RUNS)
    with pytest.raises(ValueError, match="lyapunov"):
        shroudnet.sweep(every_law, SPEEDS, method=METHOD, executor="cuda", lyapunov=True,
                        progress=False, **RUNS)
    with pytest.raises(ValueError, match="sweep.executor"):
        shroudnet.sweep(every_law, SPEEDS, method=METHOD, executor="gpu", progress=False,
                        **RUNS)


def test_warps_run_neighbours_in_parameter():
    """Along one parameter the runs go in its sorted order; on a 64 × 64 grid every 32 in a
    row (a warp) cover a patch of 8 × 4 cells, whatever order the cells were given in."""
    values = np.random.default_rng(1).permutation(np.linspace(0.0, 1.0, 100))
    np.testing.assert_array_equal(values[warp_order(values[:, None])], np.sort(values))
    a, b = np.meshgrid(np.arange(64.0), np.arange(64.0) * 10.0, indexing="ij")
    cells = np.random.default_rng(2).permutation(np.column_stack([a.ravel(), b.ravel()]))
    ordered = cells[warp_order(cells)]
    for warp in ordered.reshape(-1, 32, 2):
        spans = np.ptp(warp, axis=0)
        assert sorted([spans[0] + 1, spans[1] / 10 + 1]) == [4, 8]
    assert len(np.unique(ordered, axis=0)) == 64 * 64


def test_the_map_figure_colours_each_cell_by_its_class():
    """The figure of a map draws one cell per grid point, coloured by its class, with one
    legend entry per class present, on the axes given."""
    from matplotlib.figure import Figure

    from shroudnet import Classification, Sweep, SweepMap, SweepPoint
    from shroudnet.front.figures import map_classes, sweep_map_figure

    def point(value, label, period):
        kind = Classification(label=label, period=period, n_points=4, tolerance=1e-5,
                              mismatch=0.0, zero_one=0.0, broadband=0.0)
        return SweepPoint(value=value, poincare=np.zeros((4, 2)), energy_density=1.0,
                          friction_loss_per_cycle=0.0, classification=kind,
                          final_state=(np.zeros(1), np.zeros(1)))

    labels = [["p1", "p3"], ["chaotic", "p1"], ["quasi-periodic", "p10"]]
    rows = tuple(Sweep(parameter="b", blade=0, points=tuple(
        point(float(j), label, int(label[1:]) if label[0] == "p" else None)
        for j, label in enumerate(row)), settings={}) for row in labels)
    result = SweepMap(parameters=("a", "b"), first=np.array([0.0, 1.0, 2.0]),
                      second=np.array([0.0, 1.0]), rows=rows)
    assert map_classes(result.labels) == ["p1", "p3", "p10", "quasi-periodic", "chaotic"]
    ax = Figure().add_subplot()
    assert sweep_map_figure(result, ax=ax) is ax
    mesh = ax.collections[0]
    colours = mesh.cmap(mesh.norm(mesh.get_array())).reshape(2, 3, 4)  # second × first
    legend = {text.get_text(): patch.get_facecolor() for text, patch in
              zip(ax.get_legend().get_texts(), ax.get_legend().get_patches())}
    for i, row in enumerate(labels):
        for j, label in enumerate(row):
            np.testing.assert_allclose(colours[j, i], legend[label])
    assert ax.get_xlabel() == "a" and ax.get_ylabel() == "b"


def test_a_map_on_the_cpu_is_its_cells_sweeps():
    """A map run on the CPU holds, in each row, the sweep of the second parameter at the
    row's value of the first (the paper's kernel, as the suite compiles it)."""
    from shroudnet import scenes

    def scene_at(speed, q1):
        return scenes.three_blade_paper(gap=1.0, speed_rpm=speed, q1=q1)

    mapped = shroudnet.sweep_map(scene_at, [6000.0, 6100.0], [40.0, 50.0],
                                 parameters=("speed_rpm", "q1"), transient=1, record=3,
                                 workers=1, progress=False)
    for row, speed in enumerate((6000.0, 6100.0)):
        alone = shroudnet.sweep(lambda q1, speed=speed: scene_at(speed, q1), [40.0, 50.0],
                                transient=1, record=3, workers=1, progress=False)
        for cell, point in zip(mapped.rows[row].points, alone.points):
            assert cell.value == point.value
            np.testing.assert_array_equal(cell.poincare, point.poincare)
    with pytest.raises(TypeError, match="sweep_map.first"):
        shroudnet.sweep_map(scene_at, "abc", [40.0])



@pytest.mark.parametrize("registers, occupancy", [(255, 0.125), (128, 0.25), (96, 0.3125),
                                                  (64, 0.5), (32, 1.0)])
def test_occupancy_follows_the_registers_as_the_cuda_calculator_has_it(registers, occupancy):
    """Warps resident on a multiprocessor of compute capability 9.0 at 64 threads a block
    (NVIDIA's occupancy calculator): 65,536 registers allotted 256 at a time per warp."""
    from shroudnet.engine.batch_report import KernelReport

    report = KernelReport(compute_capability=(9, 0), ptx_bytes=1, registers=registers,
                          stack=0, spill_stores=0, spill_loads=0, ptx_seconds=0.0,
                          assembly_seconds=0.0)
    assert report.occupancy == occupancy


def test_a_batch_refuses_scenes_of_other_laws_by_the_value(monkeypatch):
    """One batch compiles one kernel: a value whose scene has other law classes is named
    before anything runs (the device check is passed over here, as the simulator would)."""
    import contact_laws as cl
    from shroudnet import scenes
    from shroudnet.studies import sweep as sweep_module

    monkeypatch.setattr(sweep_module, "check_device", lambda owner: None)

    def scene_at(gamma):
        if gamma < 2.0:
            return scenes.three_blade_paper(gamma1=gamma)
        return scenes.three_blade_paper(normal=cl.Hertz(stiffness=1e9))

    with pytest.raises(ValueError, match="the scene at 3 has other law classes"):
        shroudnet.sweep(scene_at, [1.0, 3.0], method=METHOD, executor="cuda", workers=1,
                        progress=False, transient=1, record=3, samples_per_period=8)
