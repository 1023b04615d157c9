"""Benchmark: ``python -m shroudnet.front.bench`` prints what the paper's scene costs to simulate.

0. Compiling: the first run of the paper's scene on an empty cache, and then the first run
   of another combination of built-in law classes, each in a fresh process.
1. Steps per second of each integrator on one core.
2. Effects: the same blades with no contact, frictionless and frictional contact, each
   paying for the effects it has (all of them run the kernel shared by the built-in laws).
3. The ratio against a plain ``solve_ivp`` event-driven implementation of the same scene
   (``shroudnet.references.blades``) at equal accuracy, both measured against a converged reference.
4. Sweeps: seconds per bifurcation point, the speed-up with the number of workers, and the
   wall time (median of three runs, each in a process of its own) and peak memory of a
   Fig. 6-class diagram (γ1 over [0.5, 10], 300 transient + 100 recorded periods per
   value) on every core.
5. The tangent flow: the cost of a period with one tangent vector (``lyapunov``) and with
   all 2N (``monodromy``) against the plain run, for the paper's group and the 24-blade
   ring of ``examples/scenes``; and the time ``lyapunov`` takes to give the paper's
   chaotic exponent (γ1 = 8.8) to two digits.
6. Steady states: milliseconds per periodic orbit (``periodic_orbit``) for the paper's
   group and the 24-blade ring; the seconds a forced-response curve of about 300 orbits
   across the paper's l = 2 resonance takes (``continuation``), against transient sweeps
   up and down the same speeds.
7. Substructures: periods per second and milliseconds per periodic orbit (with all its
   multipliers) of a packet of six three-mode blades (``scenes.modal_packet``), with its
   1-D rigid-stick contacts and with 3-D elastic ones, and the
   seconds a forced-response curve of 300 of its orbits takes; two
   unreduced beams with a shroud contact (``scenes.beam_pair``), by the adaptive and the
   exponential methods, against the plain ``solve_ivp`` reference of
   ``baseline_structures``, every run measured against a converged one, and each plain
   run's time against the fastest of ours at least as accurate.
8. Tuned rings at the cost of one sector: milliseconds per period-1 orbit with all its
   multipliers, shooting whole periods against the travelling wave's reduced map
   (``cyclic``), for the 24-blade ring and the 24-sector disc at an engine order coprime
   with 24 and at engine order 6; and a forced-response curve of 100 orbits of the ring
   both ways.
9. Harmonic balance (``bench_harmonic``): a point of the packet with 3-D elastic faces
   at H = 7, its certificate by exact shooting, its forced-response curve, and the error
   against H and time.
10. GPU batches (``--gpu`` runs this section alone, in under five minutes on one H200):
    the paper's group at 512 fixed steps a period, one thread per trajectory, in periods
    per second at 1,024 / 8,192 / 65,536 / 262,144 trajectories (γ1 over the Fig. 6 range)
    against the CPU fixed-step engine at the same steps on one core and on every core; the
    agreement of the first 50 periods of each of the 1,024 trajectories with the CPU's
    (to 1e-9 of the motion's size; the chaotic ones diverge after a while and are counted
    as such); and the 256 × 256 map of stiffness ratio × speed (300 + 100 periods a cell),
    whose figure goes to docs/gallery. Without a GPU it says what is missing and, with
    ``--gpu`` where numba-cuda's toolkit is installed, the kernel's registers and
    occupancy from its compile report for an H200 (sm_90).
11. Steady states at the scale of FE models: where a packet orbit's time goes. For a pair
    and a packet of eight-mode blades with 3-D elastic faces (``fe_packet``: 34 and 106
    state variables) and the three-mode packet of ``examples/fe_packet_elastic.py``: a
    period's steps (the state alone, with one tangent column, with all; the stiffest
    mode's bound), its switches and the share of it in linear phases; then one orbit from
    a settled guess by dense and by Krylov shooting, with and without its stability, each
    broken down by kind of run (``ShootingWork``: state, products, dense, outputs), with
    the GMRES and Arnoldi products; the pair of four-mode blades whose faces are 9-point
    patches (``scenes.faced_group``, 34 state variables) alike; and the six eight-mode
    blades with rigid stick (96 state variables, every phase linear) by those and by the
    exponential method, dense and Krylov. The 24-blade ring's full orbit at default
    settings;
    with ``--fe-curve``, the six blades' forced response over 2400–3800 rpm.

Figures are medians of several runs after one warm-up run (which also compiles or loads
the kernel); nothing here is asserted, because timings depend on the machine.
"""

from __future__ import annotations

import argparse
import dataclasses
import functools
import json
import os
import resource
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path

import numpy as np

from ..analysis.stability import TANGENT_METHOD, lyapunov, state_size
from ..engine.codes import Mode
from ..io import scenefile
from ..model.blade import Southwell
from ..model.excitation import EngineOrderWave, Excitation
from ..model.group import BladeGroup
from ..model.lowering import from_dofs
from ..model.scene import Scene
from ..model.substructure import Substructure
from ..references import structures as baseline_structures
from ..references.blades import solve_ivp_baseline
from ..run.methods import EVENT_TOLERANCE, TRANSIENT, Adaptive, Exponential, FixedStep
from ..run.simulate import integrate, simulate, start_coordinates
from ..run.simulation import SimulationError
from ..scenes import (beam_pair, bladed_disc_24, faced_group, modal_packet,
                      three_blade_paper)
from ..steady.continuation import continuation
from ..steady.orbits import periodic_orbit, state_weights
from ..steady.stroboscopic import StroboscopicMap
from ..studies.sweep import default_workers, sweep
from . import bench_harmonic
from .options import whole
from .progress import progress_callback

#: The benchmark's operating point: p3 motion with stick, slip and impacts on both shrouds.
POINT = {"gamma1": 2.2, "speed_rpm": 6000.0, "q1": 50.0}


_FIRST_RUN = (
    "import sys, time\n"
    "began = time.perf_counter()\n"
    "from contact_laws import Coulomb, Hertz\n"
    "from shroudnet import simulate\n"
    "from shroudnet.scenes import three_blade_paper\n"
    "laws = {} if sys.argv[1] == 'paper' else "
    "{'normal': Hertz(stiffness=3e7), 'friction': Coulomb(mu=0.3)}\n"
    "sim = simulate(three_blade_paper(**laws), 1)\n"
    "print(time.perf_counter() - began, sim.compile_seconds)\n")


def first_runs() -> dict[str, tuple[float, float]]:
    """(wall seconds of a fresh process's first run, of them compiling) on an empty cache:
    the paper's scene, then a scene with other law classes (the engine's own code now
    cached, the kernel new)."""
    with tempfile.TemporaryDirectory() as folder:
        env = {**os.environ, "SHROUDNET_CACHE": f"{folder}/kernels",
               "NUMBA_CACHE_DIR": f"{folder}/numba"}
        runs = {}
        for which in ("paper", "other laws"):
            done = subprocess.run([sys.executable, "-c", _FIRST_RUN, which.split()[0]],
                                  env=env, capture_output=True, text=True, check=True)
            wall, compiling = map(float, done.stdout.split())
            runs[which] = (wall, compiling)
        return runs


def median_time(function, repeats: int) -> tuple[float, object]:
    """Median wall time [s] of ``function()`` over ``repeats`` runs, and its last result."""
    times = []
    for _ in range(repeats):
        start = time.perf_counter()
        result = function()
        times.append(time.perf_counter() - start)
    return statistics.median(times), result


def steps_per_second(method, *, scene=None, periods: int = 200, repeats: int = 5
                     ) -> tuple[float, object]:
    """Median Runge–Kutta steps per second on one core, and the last simulation.

    A step is one grid step for ``FixedStep``, one accepted step for ``Adaptive``; the time
    includes locating and resolving every switch and recording 100 samples per period.
    """
    scene = three_blade_paper(**POINT) if scene is None else scene
    simulate(scene, 2, method=method)
    seconds, sim = median_time(lambda: simulate(scene, periods, method=method), repeats)
    return sim.steps / seconds, sim


def without_interfaces(scene: Scene) -> Scene:
    """The same blades and excitation with no shroud interfaces at all."""
    group = BladeGroup()
    for name in scene.group.blades:
        group.add_blade(name, scene.group.blade(name))
    return Scene(group=group, excitation=scene.excitation, speed_rpm=scene.speed_rpm)


def effect_scenes() -> dict[str, Scene]:
    frictional = three_blade_paper(**POINT)
    return {
        "no interfaces": without_interfaces(frictional),
        "contact that never closes (gap 1 m)": three_blade_paper(**POINT, gap=1.0),
        "frictionless contact": three_blade_paper(**POINT, friction=None),
        "frictional contact (the paper's)": frictional,
    }


def gamma_scene(gamma1):
    """The benchmark's scene at stiffness ratio ``gamma1`` (module-level: it is pickled)."""
    return three_blade_paper(**{**POINT, "gamma1": gamma1})


def baseline_comparison(gammas=(1.0, 2.2, 3.5), periods: int = 50, repeats: int = 3):
    """Per γ1: (seconds ours, seconds solve_ivp, error ours, error solve_ivp, switches).

    Both run Dormand–Prince 5(4) at rtol = 1e-8, atol = 1e-12 m; errors are the largest
    deviation of the displacements at t = k T_e from a reference at rtol = 1e-12, relative
    to the largest displacement.
    """
    rows = []
    for gamma1 in gammas:
        scene = gamma_scene(gamma1)
        reference = simulate(scene, periods, method=Adaptive(rtol=1e-12, atol=1e-16),
                             samples_per_period=1, event_tolerance=1e-13).x
        run = functools.partial(simulate, scene, periods, method=Adaptive(atol=1e-12),
                                samples_per_period=1)
        run()
        ours_seconds, ours = median_time(run, repeats)
        start = time.perf_counter()
        plain = solve_ivp_baseline(scene, periods, rtol=1e-8, atol=1e-12)
        plain_seconds = time.perf_counter() - start
        scale = np.abs(reference).max()
        rows.append((gamma1, ours_seconds, plain_seconds,
                     np.abs(ours.x - reference).max() / scale,
                     np.abs(plain.x - reference).max() / scale, plain.switches))
    return rows


def diagram(values, *, workers, transient=TRANSIENT, record=100, progress=False):
    """A Fig. 6-class sweep of γ1; returns (wall time [s], the sweep)."""
    start = time.perf_counter()
    result = sweep(gamma_scene, values, parameter="gamma1", transient=transient,
                   record=record, method=Adaptive(), workers=workers, progress=progress)
    return time.perf_counter() - start, result


#: Runs of the Fig. 6-class diagram, each in a process of its own, whose median is quoted.
DIAGRAM_REPEATS = 3


def diagram_in_fresh_process(points, transient, record, workers) -> dict:
    """Run the diagram in a new Python process, so that its peak memory is its own.

    Returns wall seconds, peak resident memory [MB] of that process and of its largest
    worker, and the size of the results the sweep keeps [MB]. Progress goes to stderr.
    """
    command = [sys.executable, "-m", "shroudnet.front.bench", "--diagram-only", "--points",
               str(points), "--transient", str(transient), "--record", str(record),
               "--workers", str(workers)]
    done = subprocess.run(command, stdout=subprocess.PIPE, text=True, check=True)
    return json.loads(done.stdout.strip().splitlines()[-1])


def _diagram_only(points, transient, record, workers) -> None:
    seconds, result = diagram(np.linspace(0.5, 10.0, points), workers=workers,
                              transient=transient, record=record,
                              progress=progress_callback("auto"))
    kept = sum(p.poincare.nbytes + sum(s.nbytes for s in p.final_state)
               for p in result.points)
    print(json.dumps({
        "seconds": seconds, "kept_mb": kept / 1e6,
        "own_mb": resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024,
        "worker_mb": resource.getrusage(resource.RUSAGE_CHILDREN).ru_maxrss / 1024}))


RING = Path(__file__).resolve().parents[2] / "examples" / "scenes" / "ring_24_travelling_wave.toml"


def tangent_costs(scene, periods: int, repeats: int) -> tuple[float, float, float]:
    """Seconds per period of the plain run, of ``lyapunov`` with one exponent and of
    ``monodromy`` (2N tangent vectors), each from the same settled start (medians)."""
    settled = simulate(scene, 100, samples_per_period=1)
    start = (settled.x[-1], settled.v[-1])
    n = len(start[0])
    plain, _ = median_time(lambda: simulate(scene, periods, samples_per_period=1,
                                            initial=start, event_capacity=0), repeats)
    one, _ = median_time(lambda: lyapunov(scene, periods, transient=0, initial=start),
                         repeats)
    every, _ = median_time(lambda: lyapunov(scene, periods, transient=0, initial=start,
                                            exponents=2 * n), repeats)
    return plain / periods, one / periods, every / periods


def chaotic_exponent(periods: int, repeats: int) -> tuple[float, object]:
    """Seconds for λ_max of the paper's γ1 = 8.8 case (300 transient periods), and the result."""
    return median_time(lambda: lyapunov(three_blade_paper(gamma1=8.8), periods,
                                        transient=300), repeats)


def orbit_cost(scene, periods: int, repeats: int, **options) -> tuple[float, object]:
    """Seconds for ``periodic_orbit`` from the state after 100 periods (median), and the
    orbit."""
    settled = simulate(scene, 100, samples_per_period=1, event_capacity=0)
    guess = (settled.x[-1], settled.v[-1])
    return median_time(lambda: periodic_orbit(scene, periods, guess=guess, **options),
                       repeats)


def symmetric_costs(scene, repeats: int) -> dict[str, tuple[float, object]]:
    """(seconds, orbit) of ``periodic_orbit`` to 1e-8 from the state after 100 periods
    (median), by solver: "full" shoots whole periods, "symmetric" the travelling wave's
    reduced map (``cyclic``)."""
    return {name: orbit_cost(scene, 1, repeats, symmetry=symmetry, tolerance=1e-8)
            for name, symmetry in (("full", "none"), ("symmetric", "cyclic"))}


def paper_ring(engine_order: int, speed_rpm: float = 6000.0) -> Scene:
    """24 of the paper's blades round a ring, each joined to the next by the paper's
    shroud (γ1 = 2.2), forced by its q1 in engine order ``engine_order``."""
    paper = three_blade_paper(speed_rpm=speed_rpm)
    group = BladeGroup.ring(24, paper.group.blade("blade1"), paper.group.interfaces[0][2])
    return Scene(group=group, speed_rpm=speed_rpm, excitation=Excitation(
        engine_order=engine_order, amplitudes=paper.excitation.amplitudes,
        phases=EngineOrderWave()))


def in_engine_order(scene, engine_order: int):
    """``scene`` forced in ``engine_order`` (the same amplitudes, an engine-order wave)."""
    return Scene(group=scene.group, speed_rpm=scene.speed_rpm, excitation=Excitation(
        engine_order=engine_order, amplitudes=scene.excitation.amplitudes,
        phases=EngineOrderWave()))


def symmetric_curve(scene, start: float, stop: float, points: int,
                    symmetry: str) -> tuple[float, object]:
    """(seconds, branch) of ``scene``'s forced response over ``start``–``stop`` rpm, at
    most ``points`` orbits, with ``symmetry`` as ``continuation`` takes it."""
    def scene_at(speed_rpm):
        return Scene(group=scene.group, excitation=scene.excitation, speed_rpm=speed_rpm)

    clock = time.perf_counter()
    branch = continuation(scene_at, start, stop, max_points=points, symmetry=symmetry,
                          max_step=0.012)
    return time.perf_counter() - clock, branch


def speed_at(speed_rpm):
    return three_blade_paper(speed_rpm=speed_rpm)


def response_curve(max_step: float, max_points: int, repeats: int) -> tuple[float, object]:
    """Seconds for the paper's forced response over 5800–7200 rpm (median), and the branch."""
    return median_time(lambda: continuation(speed_at, 5800.0, 7200.0, max_step=max_step,
                                            max_points=max_points), repeats)


def transient_sweeps(values, transient: int, record: int) -> float:
    """Seconds for sweeps of transients up and down ``values`` on one core, each point
    starting from the last."""
    options = {"transient": transient, "record": record, "continuation": True,
               "workers": 1, "progress": False}
    start = time.perf_counter()
    sweep(speed_at, values, **options)
    sweep(speed_at, values[::-1], **options)
    return time.perf_counter() - start


def worker_counts(cores: int) -> list[int]:
    counts = [1]
    while counts[-1] * 2 <= cores:
        counts.append(counts[-1] * 2)
    return counts + ([cores] if counts[-1] != cores else [])


def packet_costs(scene, periods: int, repeats: int) -> tuple[float, float, object]:
    """(periods per second, seconds per periodic orbit from a settled guess, the orbit) of
    a ``scenes.modal_packet``."""
    rate = periods_per_second(scene, periods, repeats)
    orbit = periodic_orbit(scene)
    orbit_seconds, orbit = median_time(lambda: periodic_orbit(scene, guess=orbit.initial),
                                       repeats)
    return rate, orbit_seconds, orbit


def periods_per_second(scene, periods: int, repeats: int) -> float:
    """Periods per second of ``scene`` sampled 20 times a period (median), its kernel
    compiled or loaded first."""
    simulate(scene, 5)
    seconds, _ = median_time(lambda: simulate(scene, periods, samples_per_period=20), repeats)
    return periods / seconds


#: ``scenes.modal_packet`` with 3-D shroud points whose faces slide in their plane with
#: elastic stick (k_t three times the normal contact stiffness; 2-D Coulomb friction
#: with a circular limit, the sliders in the state), against its 1-D rigid-stick faces.
ELASTIC_PACKET = {"tangential_stiffness": 3e5}


def packet_curve(points: int) -> tuple[float, object]:
    """(seconds, the branch) of a forced-response curve of ``scenes.modal_packet`` up in
    speed from 2600 rpm across its first flap resonance, of at most ``points`` orbits
    (steps of at most 5 % of the range, as ``examples/fe_packet.py`` takes them), from
    the orbit at 2600 rpm."""
    def scene_at(speed_rpm):
        return modal_packet(speed_rpm=speed_rpm)

    start = periodic_orbit(scene_at(2600.0))
    clock = time.perf_counter()
    branch = continuation(scene_at, 2600.0, 3400.0, guess=start.initial, max_step=0.05,
                          max_points=points)
    return time.perf_counter() - clock, branch


def beams_against_plain(periods: int, repeats: int) -> dict[str, tuple[float, float]]:
    """(seconds, error) on ``scenes.beam_pair`` from rest, by run: shroudnet's adaptive
    method at rtol 1e-6 and its exponential one (``Exponential()``, the motion between
    switches exact, its error the switches' location: at the default event tolerance and
    at 1e-12 periods), and the plain ``baseline_structures`` run with RK45 at rtol 1e-9 and
    DOP853 at rtol 1e-9 and 1e-10 (atol rtol times the displacement scale); each error the
    largest deviation of the physical degrees of freedom at t = k T_e from a run at rtol
    1e-12 with switches located to 1e-13 periods, relative to their largest value. Each
    impact sets the beams' high modes ringing, which Runge–Kutta steps follow: at rtol
    1e-6, 17,377 steps in 10 periods without the contact, 45,714 with it, and 175,749 at
    rtol 1e-9; the exponential method carries them exactly, 400 steps a period."""
    scene = beam_pair()
    dofs = scene.dof_matrix()
    reference = simulate(scene, periods, method=Adaptive(rtol=1e-12), samples_per_period=1,
                         event_tolerance=1e-13).x @ dofs.T
    scale = np.abs(reference).max()
    rows = {}
    for label, method, tolerance in (
            ("shroudnet Adaptive(rtol=1e-6)", Adaptive(rtol=1e-6), EVENT_TOLERANCE),
            ("shroudnet Exponential()", Exponential(), EVENT_TOLERANCE),
            ("shroudnet Exponential(), event_tolerance 1e-12", Exponential(), 1e-12)):
        run = functools.partial(simulate, scene, periods, method=method, samples_per_period=1,
                                event_tolerance=tolerance)
        run()
        seconds, ours = median_time(run, repeats)
        rows[label] = seconds, np.abs(ours.x @ dofs.T - reference).max() / scale
    problem = baseline_structures.structure_from_substructures(scene)
    zero = np.zeros(problem.n_dof)
    for method, rtol in (("RK45", 1e-9), ("DOP853", 1e-9), ("DOP853", 1e-10)):
        start = time.perf_counter()
        plain = baseline_structures.strobe_structure(problem, zero, zero, periods, rtol=rtol,
                                                     atol=rtol * scale, method=method)
        rows[f"solve_ivp {method}, rtol {rtol:g}"] = (time.perf_counter() - start,
                                                      np.abs(plain.q - reference).max() / scale)
    return rows


def against_ours(rows: dict[str, tuple[float, float]]) -> dict[str, tuple[str, float]]:
    """For each plain run of ``beams_against_plain``'s rows, the fastest shroudnet run at
    least as accurate, and how many times faster it is: {plain label: (ours, ratio)}."""
    ours = {label: row for label, row in rows.items() if label.startswith("shroudnet")}
    ratios = {}
    for label, (seconds, error) in rows.items():
        if label in ours:
            continue
        matched = [(time_, name) for name, (time_, ours_error) in ours.items()
                   if ours_error <= error]
        if matched:
            time_, name = min(matched)
            ratios[label] = name, seconds / time_
    return ratios


#: The GPU section's method: the issue's 512 RK4 steps a period.
GPU_METHOD = FixedStep(steps_per_period=512)
#: Trajectories per batch, and the periods each runs, for the throughput.
GPU_BATCHES = (1024, 8192, 65536, 262144)
GPU_PERIODS = 20
#: The agreement: periods compared against the CPU engine, and to what (of the motion).
AGREEMENT_PERIODS = 50
AGREEMENT = 1e-9
AGREEMENT_RUNS = 1024
#: The map: stiffness ratio γ1 × speed [rpm], cells per side, transient + recorded periods.
MAP_GAMMA = (0.5, 10.0)
MAP_SPEED = (5500.0, 7500.0)
MAP_CELLS = 256
MAP_PERIODS = (300, 100)
MAP_FIGURE = Path(__file__).resolve().parents[2] / "docs" / "gallery" / "gpu_map_gamma_speed.png"


def paper_runs(gammas, *, record: int, transient: int = 0):
    """The prepared runs (``run.batch.prepare_run``) of the paper's group at each γ1 of
    ``gammas`` and 6000 rpm, made from one: γ1 sets the contact springs k_c = γ1 k(Ω) and
    nothing else, so each run is the first with its normal law's row replaced (preparing
    262,144 scenes one by one would take the host longer than the GPU takes to run them).
    Checked against scenes made one by one at three values."""
    from dataclasses import replace

    from ..engine.records import KernelScene
    from ..run.batch import prepare_run

    options = dict(transient=transient, record=record, method=GPU_METHOD,
                   samples_per_period=1)
    base = prepare_run(three_blade_paper(gamma1=1.0), **options)
    where = KernelScene._fields.index("normal_params")
    stiffness = base.fields[KernelScene._fields.index("stiffness")][0]

    def run_at(gamma):
        fields = list(base.fields)
        fields[where] = np.full_like(base.fields[where], float(gamma) * stiffness)
        return replace(base, fields=tuple(fields))

    for gamma in (gammas[0], gammas[len(gammas) // 2], gammas[-1]):
        made = prepare_run(three_blade_paper(gamma1=float(gamma)), **options)
        assert all(np.array_equal(a, b) for a, b in zip(made.fields, run_at(gamma).fields))
    return [run_at(gamma) for gamma in gammas]


def gpu_throughput(runs: int) -> tuple[float, float]:
    """(periods per second, seconds) of one batch of ``runs`` trajectories of
    ``GPU_PERIODS`` periods each, γ1 over [0.5, 10] in order."""
    from ..run.batch import run_batch

    gammas = np.linspace(0.5, 10.0, runs)
    prepared = paper_runs(gammas, record=GPU_PERIODS)
    done = run_batch(three_blade_paper(), prepared, response=1, transient=0,
                     record=GPU_PERIODS, samples_per_period=1)
    return runs * GPU_PERIODS / done.seconds, done.seconds


def cpu_rates(cores: int) -> tuple[float, float]:
    """Periods per second of the CPU fixed-step engine at ``GPU_METHOD``'s steps on the
    same trajectories: one core (``simulate`` of 32 of them in turn) and every core (a
    sweep of 64 a core on a pool whose workers have loaded the kernel)."""
    from concurrent.futures import ProcessPoolExecutor

    gammas = np.linspace(0.5, 10.0, 32)
    simulate(three_blade_paper(gamma1=1.0), 1, method=GPU_METHOD, samples_per_period=1)
    began = time.perf_counter()
    for gamma in gammas:
        simulate(three_blade_paper(gamma1=gamma), GPU_PERIODS, method=GPU_METHOD,
                 samples_per_period=1)
    one = len(gammas) * GPU_PERIODS / (time.perf_counter() - began)
    values = np.linspace(0.5, 10.0, 64 * cores)
    with ProcessPoolExecutor(cores) as pool:
        # two samples a period: the classification's spectrum needs four samples at least
        sweep(gamma_scene, values[:2 * cores], transient=0, record=3, method=GPU_METHOD,
              samples_per_period=2, executor=pool)  # each worker loads the kernel
        began = time.perf_counter()
        sweep(gamma_scene, values, transient=GPU_PERIODS - 3, record=3, method=GPU_METHOD,
              samples_per_period=2, executor=pool)
        every = len(values) * GPU_PERIODS / (time.perf_counter() - began)
    return one, every


def gpu_agreement(cores: int) -> dict:
    """The first ``AGREEMENT_PERIODS`` periods of ``AGREEMENT_RUNS`` trajectories on the GPU
    against the CPU engine's: the largest difference of the blade's Poincaré points
    relative to its motion's extent, per trajectory, and the CPU's classification of
    those beyond ``AGREEMENT``."""
    from ..run.batch import run_batch

    gammas = np.linspace(0.5, 10.0, AGREEMENT_RUNS)
    done = run_batch(three_blade_paper(), paper_runs(gammas, record=AGREEMENT_PERIODS),
                     response=1, transient=0, record=AGREEMENT_PERIODS,
                     samples_per_period=1)
    cpu = sweep(gamma_scene, gammas, transient=0, record=AGREEMENT_PERIODS,
                method=GPU_METHOD, samples_per_period=1, workers=cores)
    gaps, labels = [], []
    for k, point in enumerate(cpu.points):
        scale = np.abs(point.poincare).max(axis=0)
        gaps.append(float(np.abs((done.poincare[k] - point.poincare) / scale).max()))
        labels.append(point.classification.label)
    return {"gaps": np.array(gaps), "labels": labels}


def gpu_map(progress=False):
    """The 256 × 256 map of γ1 × speed on the GPU (``MAP_PERIODS``), its wall time [s]."""
    from ..studies.maps import sweep_map

    def scene_at(gamma1, speed_rpm):
        return three_blade_paper(gamma1=gamma1, speed_rpm=speed_rpm)

    began = time.perf_counter()
    result = sweep_map(scene_at, np.linspace(*MAP_GAMMA, MAP_CELLS),
                       np.linspace(*MAP_SPEED, MAP_CELLS), parameters=("gamma1", "speed_rpm"),
                       transient=MAP_PERIODS[0], record=MAP_PERIODS[1], method=GPU_METHOD,
                       samples_per_period=64, executor="cuda", progress=progress)
    return time.perf_counter() - began, result


def kernel_resources():
    """The paper kernel's compile report for an H200 (``engine.batch_report.kernel_report``)."""
    from ..engine.batch import kernel_for, kernel_key, layout_of
    from ..engine.batch_report import kernel_report
    from ..run.batch import batch_input

    scene = three_blade_paper()
    prepared = paper_runs([1.0, 2.0], record=3)
    numbers = batch_input(prepared, [0, 1], kernel_key(scene), response=1, transient=0,
                          record=3, samples_per_period=1)
    return kernel_report(kernel_for(scene), layout_of(scene, prepared[0].controls[1]),
                         numbers)


def gpu_section(cores: int, report: bool = True) -> None:
    """Section 9 of the benchmark (see the module's docstring); without a GPU, the
    kernel's compile report where ``report`` (it takes minutes)."""
    from ..engine.batch import cuda_missing

    print(f"\n10. GPU batches: the paper's group, fixed-step RK4 at "
          f"{GPU_METHOD.steps_per_period} steps a period, switches located to "
          f"{EVENT_TOLERANCE:g} of the period")
    missing = cuda_missing()
    if missing is not None:
        print(f"   no GPU here: {missing}")
        if not report:
            return
        try:
            report = kernel_resources()
        except Exception as error:  # noqa: BLE001 - no toolkit either: say so and stop
            print(f"   no compile report either: {error}")
            return
        print(f"   compile report for sm_{''.join(map(str, report.compute_capability))} "
              f"(no device): {report.registers} registers a thread, {report.stack} bytes "
              f"of stack, spills {report.spill_stores} bytes stored and "
              f"{report.spill_loads} loaded; occupancy {report.occupancy:.1%} at 64 "
              f"threads a block; PTX {report.ptx_bytes / 1e6:.1f} MB in "
              f"{report.ptx_seconds:.0f} s, assembled in {report.assembly_seconds:.0f} s")
        return
    began = time.perf_counter()
    gpu_throughput(64)  # compiles (or loads) the kernel
    print(f"   compiling (or loading) the kernel: {time.perf_counter() - began:.0f} s")
    one, every = cpu_rates(cores)
    print(f"   CPU fixed-step engine: {one:,.0f} periods/s on one core, {every:,.0f} on "
          f"{cores} cores")
    for runs in GPU_BATCHES:
        rate, seconds = gpu_throughput(runs)
        print(f"   {runs:>7,} trajectories × {GPU_PERIODS} periods: {rate:,.0f} periods/s "
              f"({seconds:.2f} s), {rate / one:,.0f}x one core, {rate / every:,.1f}x "
              f"{cores} cores")
    found = gpu_agreement(cores)
    gaps, labels = found["gaps"], found["labels"]
    beyond = gaps > AGREEMENT
    chaotic = sum(1 for k in np.flatnonzero(beyond) if labels[k] == "chaotic")
    print(f"   agreement over the first {AGREEMENT_PERIODS} periods, {AGREEMENT_RUNS:,} "
          "trajectories: "
          f"{int((~beyond).sum())} within {AGREEMENT:g} of the motion (largest "
          f"{gaps[~beyond].max(initial=0.0):.1e}); {int(beyond.sum())} beyond, of them "
          f"{chaotic} chaotic by the CPU's classification"
          + (f" (the others: {sorted({labels[k] for k in np.flatnonzero(beyond)} - {'chaotic'})})"
             if int(beyond.sum()) > chaotic else ""))
    seconds, result = gpu_map()
    counts = {label: int((result.labels == label).sum())
              for label in np.unique(result.labels)}
    print(f"   {MAP_CELLS} × {MAP_CELLS} map of γ1 × speed ({MAP_PERIODS[0]} + "
          f"{MAP_PERIODS[1]} periods a cell): {seconds:.1f} s; "
          + ", ".join(f"{label} {n}" for label, n in sorted(counts.items())))
    from .figures import save_figure, sweep_map_figure

    figure = sweep_map_figure(result, xlabel="stiffness ratio γ1", ylabel="speed [rpm]",
                              title="The paper's group: classification of the steady response")
    MAP_FIGURE.parent.mkdir(parents=True, exist_ok=True)
    save_figure(figure, MAP_FIGURE, dpi=120)
    print(f"   figure: {MAP_FIGURE}")


# ---- 11. steady states at the scale of FE models ------------------------------------------------

#: The modes of the bench's FE blade: ``scenes.modal_blade``'s three (first flap, edgewise,
#: second flap, stiffening with speed) and five higher ones up to 4.9 kHz, as a finer FE
#: model keeps them: 25 times the excitation frequency at the first flap resonance. Modal
#: masses [kg], and the shapes at the shroud (flapwise, edgewise, radial rows) and at the
#: load point, per mode.
FE_FREQUENCIES = (Southwell(f0=180.0, coefficient=3.0), Southwell(f0=450.0, coefficient=1.5),
                  Southwell(f0=1050.0, coefficient=2.0), 1900.0, 2600.0, 3300.0, 4100.0,
                  4900.0)
FE_MASSES = (0.06, 0.05, 0.04, 0.035, 0.03, 0.03, 0.025, 0.025)
FE_SHROUD = ((1.0, 0.25, -0.5, 0.3, -0.2, 0.15, -0.1, 0.08),
             (0.15, 1.0, 0.35, -0.25, 0.3, -0.15, 0.12, -0.1),
             (0.08, -0.12, 0.3, 0.2, 0.15, -0.2, 0.1, 0.05))
FE_LOAD = ((0.7, 0.4, 0.2, 0.1, -0.1, 0.05, 0.05, -0.03),)


def fe_packet(speed_rpm: float = 3000.0, blades: int = 6, elastic: bool = True) -> Scene:
    """The packet of ``examples/fe_packet_elastic.py`` (``scenes.modal_packet`` with 3-D
    elastic faces, k_t = 3e5 N/m) whose blades keep eight modes (``FE_FREQUENCIES``):
    six blades have 106 state variables (48 modal coordinates, their velocities, and two
    stretches for each of the five faces); two, 34. Without ``elastic``, the faces of
    ``scenes.modal_packet`` (sliding along one direction, their stick rigid: every phase
    linear, so that ``Exponential`` runs it): 96 and 32."""
    shroud_rows = FE_SHROUD if elastic else FE_SHROUD[:2]
    blade = Substructure.modal(frequencies=list(FE_FREQUENCIES), damping_ratios=0.02,
                               masses=list(FE_MASSES),
                               shapes={"shroud": [list(row) for row in shroud_rows],
                                       "load": [list(row) for row in FE_LOAD]}, load="load")
    packet = modal_packet(blades=blades, speed_rpm=speed_rpm,
                          **(ELASTIC_PACKET if elastic else {}))
    group = BladeGroup()
    names = [f"blade{k}" for k in range(1, blades + 1)]
    for name in names:
        group.add_blade(name, blade)
    shroud = packet.group.interfaces[0][2]
    for left, right in zip(names, names[1:]):
        group.connect((left, "shroud"), (right, "shroud"), shroud)
    return Scene(group=group, speed_rpm=speed_rpm, excitation=packet.excitation)


def settled_guess(scene, periods: int) -> tuple:
    """(x, ẋ, u) after ``periods`` periods from rest: a guess near the orbit."""
    run = simulate(scene, periods, samples_per_period=1, event_capacity=0)
    return (run.x[-1], run.v[-1], run.stretches[-1]) if run.stretches.size \
        else (run.x[-1], run.v[-1])


def period_steps(scene, guess) -> dict:
    """Where a period's steps come from, from ``guess``: the adaptive steps of the state
    alone at rtol 1e-10 and at the map's (``StroboscopicMap.state_method``), with one
    tangent column and with all; the steps the stiffest mode alone would need (the
    Dormand–Prince stability bound, |λh| ≤ 3.3); the switches by kind; the share of the
    period in phases linear in the state (no elastic face slipping in 2-D)."""
    size = state_size(scene)
    start = start_coordinates(scene, guess)  # integrate's, by the engine's coordinates
    integrate(scene, 1, method=TANGENT_METHOD, samples_per_period=1, initial=start,
              event_capacity=0, tangent=np.eye(size)[:, :1])  # its kernel loaded
    found = {}
    for label, method, columns in (("state", TANGENT_METHOD, 0),
                                   ("map", StroboscopicMap(scene=scene).state_method, 0),
                                   ("one column", TANGENT_METHOD, 1),
                                   ("all columns", TANGENT_METHOD, size)):
        clock = time.perf_counter()
        done = integrate(scene, 1, method=method, samples_per_period=1, initial=start,
                         event_capacity=0, tangent=np.eye(size)[:, :columns] if columns
                         else None)
        found[label] = (done.run.steps, time.perf_counter() - clock)
    run = simulate(scene, 1, method=TANGENT_METHOD, samples_per_period=2000, initial=guess)
    slipping = np.isin(run.modes[:-1][:, scene.arrays.elastic_interfaces],
                       (Mode.SLIP_POSITIVE, Mode.SLIP_NEGATIVE)).any(axis=1)
    stiffest = max(float(np.max(scene.group.blade(name).frequencies_at(scene.speed_rpm)))
                   for name in scene.group.blades)
    return {"steps": found, "stiffest_hz": stiffest,
            "stability_steps": 2.0 * np.pi * stiffest * scene.excitation_period / 3.3,
            "events": {k: v for k, v in run.events.counts.items() if v},
            "linear_share": float(1.0 - slipping.mean()) if scene.arrays.n_stretches
            else float(scene.arrays.linear_phases)}


#: The solvers an orbit's breakdown compares: (label, periodic_orbit's options); those
#: of ``EXPONENTIAL_SOLVERS`` too on a scene whose phases are linear.
SOLVERS = (("dense", {"jacobian": "dense"}),
           ("krylov", {"jacobian": "krylov"}),
           ("dense, no stability", {"jacobian": "dense", "stability": False}),
           ("krylov, no stability", {"jacobian": "krylov", "stability": False}))
EXPONENTIAL_SOLVERS = (
    ("exponential, dense", {"jacobian": "dense", "method": Exponential()}),
    ("exponential, krylov", {"jacobian": "krylov", "method": Exponential()}))
#: Runs of each solver an orbit's time is the median of (after one that loads the
#: kernels).
ORBIT_RUNS = 3


def orbit_breakdown(scene, guess, runs: int = ORBIT_RUNS) -> dict:
    """(median seconds of ``runs``, orbit) of ``periodic_orbit`` from ``guess`` by each of
    ``SOLVERS`` (the orbit's ``work`` breaks its time down by kind of run), and the
    largest gap between their orbits' states over the scale and between their leading
    multipliers."""
    found = {}
    solvers = SOLVERS + (EXPONENTIAL_SOLVERS if scene.arrays.linear_phases else ())
    for label, options in solvers:
        periodic_orbit(scene, guess=guess, **options)  # its kernels loaded
        found[label] = median_time(lambda: periodic_orbit(scene, guess=guess, **options),
                                   runs)
    layout = scene.arrays.layout  # the scale Newton weighs by, of the engine's coordinates
    dense = from_dofs(layout, found["dense"][1].state)
    weights = state_weights(scene, dense)
    state_gap = max(np.abs(weights * (from_dofs(layout, orbit.state) - dense)).max()
                    for _, orbit in found.values())
    reference = found["dense"][1].multipliers
    multiplier_gap = max(np.abs(reference - value).min() for _, orbit in found.values()
                         for value in orbit.multipliers)
    return {"solvers": found, "state_gap": state_gap, "multiplier_gap": multiplier_gap}


def describe_work(seconds: float, orbit) -> str:
    """An orbit's solve in words: its time, Newton steps, products, and runs by kind."""
    work = orbit.work
    kinds = ", ".join(f"{kind} {work.runs[kind]} run(s) ({work.columns[kind]} columns) "
                      f"{work.seconds[kind]:.2f} s" for kind in work.runs if work.runs[kind])
    return (f"{seconds:.2f} s, {work.newton_steps} Newton step(s), "
            f"{work.krylov_iterations} GMRES and {work.arnoldi_products} Arnoldi "
            f"products; {kinds}")


def fe_curve(start: float, stop: float, max_points: int, scene_at=fe_packet
             ) -> tuple[float, object]:
    """(seconds, branch) of the forced response of ``scene_at`` over ``start``–``stop``
    rpm, with its stability, from a settled guess at ``start``."""
    guess = settled_guess(scene_at(start), 150)
    clock = time.perf_counter()
    branch = continuation(scene_at, start, stop, guess=guess, max_points=max_points,
                          max_step=0.05, parameter="speed_rpm")
    return time.perf_counter() - clock, branch


def full_ring_orbit() -> tuple[float, object]:
    """(seconds, orbit) of the 24-blade ring's full orbit (``symmetry="none"``, as a
    mistuned ring must be solved) at default settings, from a settled guess."""
    scene = scenefile.load(RING).scene
    guess = settled_guess(scene, 100)
    clock = time.perf_counter()
    orbit = periodic_orbit(scene, guess=guess, symmetry="none")
    return time.perf_counter() - clock, orbit


def print_breakdown(label: str, scene, transient: int, runs: int = ORBIT_RUNS) -> dict:
    """Section 11's lines for one scene: a period's steps, then each solver's orbit (the
    median time of ``runs``)."""
    guess = settled_guess(scene, transient)
    steps = period_steps(scene, guess)
    counts = steps["steps"]
    print(f"   {label} ({state_size(scene)} state variables), {scene.speed_rpm:g} rpm, from "
          f"the state after {transient} periods:")
    print(f"     a period: {counts['state'][0]} steps for the state alone at rtol 1e-10 "
          f"({counts['state'][1]:.3f} s), {counts['map'][0]} at the map's rtol 1e-12 "
          f"({counts['map'][1]:.3f} s), {counts['one column'][0]} with one tangent column "
          f"({counts['one column'][1]:.3f} s), {counts['all columns'][0]} with all "
          f"{state_size(scene)} ({counts['all columns'][1]:.2f} s); the stiffest mode "
          f"({steps['stiffest_hz']:.0f} Hz) alone would allow "
          f"{steps['stability_steps']:.0f}; switches "
          + ", ".join(f"{k} {v}" for k, v in steps["events"].items())
          + f"; {100 * steps['linear_share']:.0f} % of the period in linear phases")
    found = orbit_breakdown(scene, guess, runs)
    for name, (seconds, orbit) in found["solvers"].items():
        print(f"     orbit, {name}: {describe_work(seconds, orbit)}")
    print(f"     the solvers' orbits agree to {found['state_gap']:.1e} of the scale, "
          f"their multipliers (Arnoldi's {len(found['solvers']['krylov'][1].multipliers)} "
          f"leading ones) the dense ones to {found['multiplier_gap']:.1e}")
    return found


#: The benchmark's sections, by number (see the module's docstring).
SECTION_NUMBERS = tuple(range(12))


def section_list(text: str) -> tuple[int, ...]:
    """An argparse type: section numbers separated by commas (``"0,5,7"``), each one of
    ``SECTION_NUMBERS``, in the order the benchmark prints them."""
    try:
        numbers = {int(part) for part in text.split(",")}
    except ValueError:
        numbers = None
    if not numbers or not numbers <= set(SECTION_NUMBERS):
        raise argparse.ArgumentTypeError(
            f"must be section numbers {SECTION_NUMBERS[0]}–{SECTION_NUMBERS[-1]} separated "
            f"by commas, got {text!r}")
    return tuple(sorted(numbers))


section_list.__name__ = "section numbers"


def options_parser(prog: str = "python -m shroudnet.front.bench",
                   parser_class: type[argparse.ArgumentParser] = argparse.ArgumentParser
                   ) -> argparse.ArgumentParser:
    """The benchmark's options, every one checked as it is read; ``prog`` and
    ``parser_class`` those of the command that runs it (``shroudnet bench``)."""
    parser = parser_class(prog=prog, description=__doc__.split("\n\n")[0])
    parser.add_argument("--points", type=whole(1), default=400,
                        help="values of γ1 in the diagram (default 400)")
    parser.add_argument("--transient", type=whole(0), default=TRANSIENT,
                        help=f"periods before recording, per value (default {TRANSIENT})")
    parser.add_argument("--record", type=whole(3), default=100,
                        help="periods recorded per value, at least 3 (default 100)")
    parser.add_argument("--scaling-points", type=whole(1), default=None,
                        help="values per run of the worker scaling (default 8 per core)")
    parser.add_argument("--baseline-periods", type=whole(1), default=50,
                        help="periods of the comparison with solve_ivp (default 50)")
    parser.add_argument("--quick", action="store_true",
                        help="small sizes everywhere, to check that the benchmark runs")
    parser.add_argument("--sections", type=section_list, default=SECTION_NUMBERS,
                        help="the sections to run, numbers separated by commas, e.g. 0,5,7 "
                             "(default all of them, 0–11)")
    parser.add_argument("--gpu", action="store_true",
                        help="run section 10 alone: batches of trajectories on a GPU")
    parser.add_argument("--fe-curve", action="store_true",
                        help="add the forced response of the six eight-mode blades "
                             "across their first flap resonance (2400–3800 rpm): long")
    parser.add_argument("--diagram-only", action="store_true", help=argparse.SUPPRESS)
    parser.add_argument("--workers", type=whole(1), default=None, help=argparse.SUPPRESS)
    return parser


@dataclasses.dataclass(frozen=True)
class Sizes:
    """How much each section runs: the options' sizes, or ``--quick``'s small ones (enough
    for every figure to be what it says, nothing representative of the machine).

    Parameters
    ----------
    quick : bool
        Whether these are ``--quick``'s sizes.
    cores : int
        This machine's cores (``default_workers``).
    points, transient, record : int
        Values of γ1 in the Fig. 6-class diagram; periods before recording and recorded,
        per value.
    scaling_points : int
        Values per run of the worker scaling.
    baseline_periods : int
        Periods of the comparison with solve_ivp.
    repeats : int
        Runs each time is the median of.
    periods : int
        Periods of each rate's run.
    fe_curve : bool
        Whether section 11 adds the six eight-mode blades' forced response.
    """

    quick: bool
    cores: int
    points: int
    transient: int
    record: int
    scaling_points: int
    baseline_periods: int
    repeats: int
    periods: int
    fe_curve: bool

    @classmethod
    def from_options(cls, args: argparse.Namespace) -> Sizes:
        """The sizes ``options_parser``'s ``args`` ask for."""
        cores = default_workers()
        quick = args.quick
        return cls(quick=quick, cores=cores,
                   points=8 if quick else args.points,
                   transient=20 if quick else args.transient,
                   record=10 if quick else args.record,
                   scaling_points=args.scaling_points or (4 if quick else 8 * cores),
                   baseline_periods=5 if quick else args.baseline_periods,
                   repeats=1 if quick else 5, periods=20 if quick else 200,
                   fe_curve=args.fe_curve)


def first_run_section(sizes: Sizes) -> None:
    runs = first_runs()
    print("0. First run in a fresh process on an empty cache (import, compile, 1 period)")
    for which, (wall, compiling) in runs.items():
        laws = "LinearSpring + ExponentialFriction" if which == "paper" else "Hertz + Coulomb"
        print(f"   {which} ({laws}): {wall:.1f} s, of which {compiling:.1f} s compiling")


def integration_section(sizes: Sizes) -> None:
    repeats, periods = sizes.repeats, sizes.periods
    print(f"\n1. Integration speed, one core: paper scene γ1 = {POINT['gamma1']}, "
          f"{POINT['speed_rpm']:g} rpm, q1 = {POINT['q1']:g} N, {periods} periods")
    for label, method in [("fixed-step RK4, 1000 steps/period", FixedStep()),
                          ("adaptive DP5(4), default tolerances", Adaptive())]:
        rate, sim = steps_per_second(method, periods=periods, repeats=repeats)
        counts = sim.events.counts
        per_period = sim.steps / sim.periods
        print(f"   {label}: {rate:,.0f} steps/s, {per_period:,.0f} steps/period, "
              f"{rate / per_period:,.0f} periods/s (median of {repeats})")
        print(f"     events: {sum(counts.values())} "
              f"({', '.join(f'{k} {v}' for k, v in counts.items())}); energy ledger "
              f"residual {sim.energy.residual:.3e} J against friction loss "
              f"{sim.energy.friction_loss:.4f} J")


def effects_section(sizes: Sizes) -> None:
    print("\n2. Effects: the same blades, one core, steps/s with fixed-step RK4 and adaptive "
          "DP5(4)")
    for label, scene in effect_scenes().items():
        fixed, sim = steps_per_second(FixedStep(), scene=scene, periods=sizes.periods,
                                      repeats=sizes.repeats)
        adaptive, _ = steps_per_second(Adaptive(), scene=scene, periods=sizes.periods,
                                       repeats=sizes.repeats)
        print(f"   {label}: {fixed:,.0f} fixed, {adaptive:,.0f} adaptive steps/s, "
              f"{sum(sim.events.counts.values())} events")


def baseline_section(sizes: Sizes) -> None:
    print(f"\n3. Against plain solve_ivp (RK45, Python right-hand side, event functions), "
          f"{sizes.baseline_periods} periods, both at rtol 1e-8, atol 1e-12 m")
    ratios = []
    for gamma1, ours, plain, error_ours, error_plain, switches in baseline_comparison(
            gammas=(2.2,) if sizes.quick else (1.0, 2.2, 3.5),
            periods=sizes.baseline_periods, repeats=sizes.repeats):
        ratios.append(plain / ours)
        print(f"   γ1 = {gamma1:g}: shroudnet {ours * 1e3:.1f} ms (error {error_ours:.1e}), "
              f"solve_ivp {plain:.2f} s (error {error_plain:.1e}), {switches} switches: "
              f"{plain / ours:,.0f}x")
    print(f"   median ratio: {statistics.median(ratios):,.0f}x per trajectory")


def sweeps_section(sizes: Sizes) -> None:
    cores, scaling_points = sizes.cores, sizes.scaling_points
    print(f"\n4. Sweeps of γ1 ({sizes.transient} transient + {sizes.record} recorded periods "
          f"per value, adaptive DP5(4)); this machine has {cores} cores")
    subset = np.linspace(0.5, 10.0, scaling_points)
    diagram(subset[:2], workers=1, transient=2, record=3)  # compile or load the kernel
    serial = None
    for workers in worker_counts(cores):
        seconds, _ = diagram(subset, workers=workers, transient=sizes.transient,
                             record=sizes.record)
        serial = serial or seconds
        print(f"   {workers:>3} worker(s), {scaling_points} values: {seconds:6.2f} s, "
              f"{seconds / scaling_points:.3f} s per point, speed-up "
              f"{serial / seconds:.2f} (efficiency {serial / seconds / workers:.0%})")
    runs = [diagram_in_fresh_process(sizes.points, sizes.transient, sizes.record, cores)
            for _ in range(1 if sizes.quick else DIAGRAM_REPEATS)]
    times = sorted(run["seconds"] for run in runs)
    seconds = statistics.median(times)
    figures = runs[0]
    print(f"   Fig. 6-class diagram, {sizes.points} values on {cores} workers: {seconds:.1f} s "
          f"wall (median of {len(times)}, {times[0]:.1f}–{times[-1]:.1f} s), "
          f"{seconds / sizes.points:.3f} s per point")
    print(f"   peak resident memory of the first run: {figures['own_mb']:.0f} MB in its main "
          f"process, {figures['worker_mb']:.0f} MB in its largest worker; the sweep keeps "
          f"{figures['kept_mb']:.2f} MB of results")


def tangent_section(sizes: Sizes) -> None:
    print("\n5. The tangent flow, one core, ms per period: plain run, with one tangent vector "
          "(lyapunov), with all 2N (monodromy)")
    scenes = {"paper group, 3 blades": three_blade_paper(**POINT)}
    if RING.exists() and not sizes.quick:
        scenes["ring of 24 blades"] = scenefile.load(RING).scene
    for label, scene in scenes.items():
        lyapunov(scene, 10, transient=0)  # compile or load the kernel
        plain, one, every = tangent_costs(scene, 20 if sizes.quick else 100, sizes.repeats)
        # five significant figures: the ratios, to 0.1, are then the printed times' quotients
        print(f"   {label}: {plain * 1e3:.5g}, {one * 1e3:.5g} ({one / plain:.1f}x), "
              f"{every * 1e3:.5g} ({every / plain:.1f}x)")
    for periods in (100,) if sizes.quick else (1000, 2000):
        seconds, result = chaotic_exponent(periods, sizes.repeats)
        print(f"   γ1 = 8.8: λ_max = {result.largest:.3f} ± {result.error[0]:.3f} per period "
              f"from {periods} periods, {seconds:.2f} s")


def steady_section(sizes: Sizes) -> None:
    print("\n6. Steady states, one core: ms per periodic orbit from a settled guess "
          "(Newton steps)")
    cases = {"paper group, γ1 = 1, period 1": (three_blade_paper(gamma1=1.0), 1, {}),
             "paper group, γ1 = 3.5, period 3": (three_blade_paper(gamma1=3.5), 3, {})}
    if RING.exists() and not sizes.quick:
        cases["ring of 24 blades, period 1 (its travelling wave), to 1e-8"] = (
            scenefile.load(RING).scene, 1, {"tolerance": 1e-8})
    for label, (scene, orbit_periods, options) in cases.items():
        try:
            seconds, orbit = orbit_cost(scene, orbit_periods, sizes.repeats, **options)
        except SimulationError as error:
            print(f"   {label}: no orbit ({error})")
            continue
        print(f"   {label}: {seconds * 1e3:.1f} ms ({orbit.iterations} steps), "
              f"|μ|max = {abs(orbit.multipliers[0]):.4f}"
              + (f", {orbit.singular} switches where the map is not differentiable"
                 if orbit.singular else ""))
    target = 30 if sizes.quick else 300
    max_step = 0.0185 * 453 / target  # about ``target`` orbits over the range
    response_curve(0.3, 20, 1)  # compile or load the kernels
    seconds, branch = response_curve(max_step, 2 * target, sizes.repeats)
    print(f"   forced response of the paper's group, 5800–7200 rpm: {len(branch)} orbits in "
          f"{seconds:.2f} s ({seconds / len(branch) * 1e3:.1f} ms per orbit), "
          f"bifurcations: " + ", ".join(f"{b.kind} at {b.parameter:.1f} rpm"
                                        for b in branch.bifurcations))
    values = np.linspace(5800.0, 7200.0, len(branch))
    swept = transient_sweeps(values, sizes.transient, 50)
    print(f"   transient sweeps up and down the same {len(values)} speeds ({sizes.transient} + "
          f"50 periods a point): {swept:.2f} s, {swept / seconds:.1f}x the continuation's "
          "time, for the stable orbits only")


def substructures_section(sizes: Sizes) -> None:
    print("\n7. Substructures, one core")
    repeats, periods = sizes.repeats, sizes.periods
    rate, orbit_seconds, orbit = packet_costs(modal_packet(), periods, repeats)
    print(f"   packet of 6 blades of 3 modes (18 coordinates, 5 interfaces): {rate:,.0f} "
          f"periods/s; a periodic orbit with its {len(orbit.multipliers)} multipliers from a "
          f"settled guess {orbit_seconds * 1e3:.0f} ms ({orbit.iterations} Newton steps)")
    elastic, elastic_seconds, elastic_orbit = packet_costs(modal_packet(**ELASTIC_PACKET),
                                                           periods, repeats)
    print(f"   the packet's contacts: 1-D contacts, rigid stick {rate:,.0f} periods/s; 3-D "
          f"contacts, elastic stick, 2-D friction {elastic:,.0f} periods/s")
    print(f"   with the 3-D elastic contacts (their stretches in the state), a periodic orbit "
          f"with its {len(elastic_orbit.multipliers)} multipliers from a settled guess "
          f"{elastic_seconds * 1e3:.0f} ms ({elastic_orbit.iterations} Newton steps)")
    seconds, branch = packet_curve(5 if sizes.quick else 300)
    print(f"   its forced-response curve up from 2600 rpm: {len(branch)} orbits with their "
          f"multipliers in {seconds:.1f} s ({branch.ended} at "
          f"{branch.parameter[-1]:.1f} rpm)")
    beam_periods = 2 if sizes.quick else 10
    rows = beams_against_plain(beam_periods, repeats)
    print("   two unreduced beams (2 × 8 degrees of freedom) with a tip shroud contact, "
          f"{beam_periods} periods from rest:")
    for label, (seconds, error) in rows.items():
        print(f"     {label}: {seconds:.3f} s, error {error:.1e}")
    for label, (ours, ratio) in against_ours(rows).items():
        print(f"     {label} takes {ratio:,.0f}x the time of {ours}, as accurate or more")


def rings_section(sizes: Sizes) -> None:
    print("\n8. Tuned rings at the cost of one sector, one core: ms per period-1 orbit with "
          "all its multipliers, to 1e-8 from a settled guess")
    disc = bladed_disc_24()
    cases = {"ring of 24 paper blades, l = 5 (τ = T/24)": paper_ring(5),
             "ring of 24 paper blades, l = 6 (τ = T/4)": paper_ring(6),
             "24-sector disc, l = 5 (τ = T/24)": in_engine_order(disc, 5),
             # where the wave of l = 6 is stable, so that both solvers find it
             "24-sector disc, l = 6 at 3300 rpm (τ = T/4)": bladed_disc_24(speed_rpm=3300.0)}
    if sizes.quick:
        cases = dict(list(cases.items())[:1])
    for label, scene in cases.items():
        try:
            found = symmetric_costs(scene, sizes.repeats)
        except SimulationError as error:
            print(f"   {label}: no orbit ({error})")
            continue
        (full, full_orbit), (symmetric, orbit) = found["full"], found["symmetric"]
        gap = np.abs(full_orbit.state - orbit.state).max() / np.abs(orbit.state).max()
        print(f"   {label}: full {full * 1e3:.5g} ms, symmetric {symmetric * 1e3:.5g} ms "
              f"({full / symmetric:.1f}x); |μ|max {abs(orbit.multipliers[0]):.4f} of ND "
              f"{orbit.wave_numbers[0]}"
              + ("" if gap < 1e-6 else f"; the full solver found another orbit ({gap:.2g} "
                 "apart): the travelling wave is unstable there"))
    points = 10 if sizes.quick else 100
    times = {symmetry: symmetric_curve(paper_ring(5), 5500.0, 6500.0, points, symmetry)
             for symmetry in ("none", "cyclic")}
    (full, branch), (symmetric, reduced) = times["none"], times["cyclic"]
    print(f"   forced response of the ring of 24 paper blades in l = 5, 5500–6500 rpm: full "
          f"{len(branch)} orbits in {full:.1f} s, symmetric {len(reduced)} in "
          f"{symmetric:.1f} s ({full / len(branch) / (symmetric / len(reduced)):.1f}x per "
          "orbit)")


def harmonic_section(sizes: Sizes) -> None:
    bench_harmonic.section(sizes.quick)


def gpu_batches_section(sizes: Sizes) -> None:
    gpu_section(sizes.cores, report=False)


def fe_section(sizes: Sizes) -> None:
    print("\n11. Steady states at the scale of FE models, one core: where an orbit's time "
          "goes")
    cases = [("pair of eight-mode blades, one 3-D elastic face", fe_packet(blades=2))]
    if not sizes.quick:
        cases += [("packet of examples/fe_packet_elastic.py, three-mode blades",
                   modal_packet(speed_rpm=3000.0, **ELASTIC_PACKET)),
                  ("packet of six eight-mode blades, 3-D elastic faces", fe_packet()),
                  ("pair of four-mode blades, faces of 9-point patches",
                   faced_group(blades=2, face_points=9, speed_rpm=3000.0)),
                  ("packet of six eight-mode blades, rigid stick (linear phases)",
                   fe_packet(elastic=False))]
    for label, scene in cases:
        print_breakdown(label, scene, 20 if sizes.quick else 150, 1 if sizes.quick else 3)
    if not sizes.quick:
        seconds, orbit = full_ring_orbit()
        print(f"   the 24-blade ring's full orbit (symmetry='none') at default settings: "
              f"residual {orbit.residual:.1e} in {seconds:.1f} s ({orbit.iterations} Newton "
              f"steps){'; ' + '; '.join(orbit.notes) if orbit.notes else ''}")
    if sizes.fe_curve:
        seconds, branch = fe_curve(2400.0, 3800.0, 400)
        print(f"   forced response of the six eight-mode blades, 2400–3800 rpm: "
              f"{len(branch)} orbits with their stability in {seconds:.0f} s "
              f"({branch.ended}); bifurcations: "
              + ", ".join(f"{b.kind} at {b.parameter:.2f} rpm" for b in branch.bifurcations))


#: Each section's printer, by number, in the order the benchmark runs them.
SECTIONS = dict(zip(SECTION_NUMBERS, (
    first_run_section, integration_section, effects_section, baseline_section,
    sweeps_section, tangent_section, steady_section, substructures_section, rings_section,
    harmonic_section, gpu_batches_section, fe_section)))


def main(argv=None) -> None:
    """Run the benchmark with the options ``argv`` (default: the process's)."""
    args = options_parser().parse_args(argv)
    if args.diagram_only:
        return _diagram_only(args.points, args.transient, args.record, args.workers)
    if args.gpu:
        return gpu_section(default_workers())
    sizes = Sizes.from_options(args)
    start = time.perf_counter()
    for number in args.sections:
        SECTIONS[number](sizes)
    print(f"\nwall time of the benchmark: {time.perf_counter() - start:.0f} s")


if __name__ == "__main__":
    main()
