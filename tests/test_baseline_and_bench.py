"""The plain solve_ivp implementation agrees with the compiled loop; the benchmark runs;
compiled kernels are cached for the next process."""

import math
import re
import subprocess
import sys

import numpy as np
import pytest

from shroudnet import Adaptive, FixedStep, simulate
from shroudnet.front.bench import POINT
from shroudnet.front.bench import main as bench_main
from shroudnet.references.blades import solve_ivp_baseline
from shroudnet.scenes import three_blade_paper


@pytest.mark.parametrize("scene", [
    three_blade_paper(gamma1=3.5),                 # impacts, slip, stick and breakaway
    three_blade_paper(gamma1=1.0, friction=None),  # frictionless impacts
], ids=["paper gamma1=3.5", "frictionless"])
def test_plain_solve_ivp_and_the_compiled_loop_follow_the_same_trajectory(scene):
    periods = 10
    compiled = simulate(scene, periods, method=Adaptive(rtol=1e-10, atol=1e-14),
                        samples_per_period=1, event_tolerance=1e-12)
    plain = solve_ivp_baseline(scene, periods, rtol=1e-10, atol=1e-14)
    scale = np.abs(compiled.x).max()
    # Measured: 1.8e-9 with stick (each located switch adds its tolerance), 1.8e-11 without.
    assert np.abs(plain.x - compiled.x).max() < 1e-7 * scale
    assert np.abs(plain.v - compiled.v).max() < 1e-7 * np.abs(compiled.v).max()
    assert plain.switches == sum(compiled.events.counts.values()) > 10


#: A figure as the benchmark prints it: 1,234.5, 0.97, 6.542e-08, -4.2e-10.
N = r"(-?[\d,]*\.?\d+(?:e[-+]?\d+)?)"


def figures(pattern, text, count=None):
    """Each match of ``pattern`` in ``text``, its groups as numbers (``N``) or strings
    (other groups); checks there are ``count`` of them (else at least one), each finite."""
    found = []
    for match in re.finditer(pattern, text, flags=re.MULTILINE):
        row = []
        for group in match.groups():
            try:
                row.append(float(group.replace(",", "")))
            except ValueError:
                row.append(group)
        found.append(row)
    assert len(found) == count if count is not None else found, (pattern, found)
    assert all(math.isfinite(x) for row in found for x in row if isinstance(x, float))
    return found


def event_total(scene, periods, method, **options):
    return sum(simulate(scene, periods, method=method, **options).events.counts.values())


def quick_bench(capsys, sections: str, *headings: str) -> str:
    """What ``bench --quick --sections sections`` prints, each of ``headings`` in it.

    The benchmark's sections are run by separate tests, so that the test workers share
    them out; each section's figures are checked against what they claim to be."""
    bench_main(["--quick", "--sections", sections])
    out = capsys.readouterr().out
    for heading in (*headings, "wall time of the benchmark"):
        assert heading in out
    return out


@pytest.mark.slow  # compiles in fresh processes, on an empty cache
def test_the_benchmarks_first_run_is_timed_with_its_compiling_apart(capsys):
    out = quick_bench(capsys, "0", "0. First run")
    for wall, compiling in figures(rf"\): {N} s, of which {N} s compiling$", out, 2):
        assert 0.0 <= compiling <= wall


@pytest.mark.slow
def test_the_benchmarks_rates_are_their_quotients_and_its_events_a_plain_runs(capsys):
    """Sections 1-4: each integrator's rate, and the events of a plain run of the same
    scene; the effects (no contact, no events); the ratio against solve_ivp; sweeps."""
    out = quick_bench(capsys, "1,2,3,4", "1. Integration speed", "2. Effects",
                      "3. Against plain", "4. Sweeps", "Fig. 6-class diagram",
                      "peak resident memory")

    # 1. each integrator's rate, and the events of a plain run of the same scene
    scene, periods = three_blade_paper(**POINT), 20
    rates = figures(rf": {N} steps/s, {N} steps/period, {N} periods/s", out, 2)
    ledgers = figures(rf"events: {N} \(([^)]*)\); energy ledger residual {N} J against "
                      rf"friction loss {N} J$", out, 2)
    for (rate, per_period, per_second), (total, counts, residual, loss), method in zip(
            rates, ledgers, (FixedStep(), Adaptive())):
        assert rate > 0.0 and per_second == pytest.approx(rate / per_period, rel=0.01)
        plain = simulate(scene, periods, method=method).events.counts
        assert {kind: int(n) for kind, n in (c.split() for c in counts.split(", "))} == plain
        assert total == sum(plain.values()) > 0
        assert loss > 0.0 and abs(residual) <= 1e-6 * loss
    assert figures(r"fixed-step RK4, 1000 steps/period: [\d,]+ steps/s, 1,000 steps/period",
                   out, 1)

    # 2. effects: no contact, no events; the paper's scene as in section 1
    events = {label: total for label, total in figures(
        r"^   ([^:]+): [\d,]+ fixed, [\d,]+ adaptive steps/s, (\d+) events$", out, 4)}
    assert events["no interfaces"] == events["contact that never closes (gap 1 m)"] == 0.0
    assert events["frictional contact (the paper's)"] == ledgers[0][0]
    assert events["frictionless contact"] == event_total(
        three_blade_paper(**POINT, friction=None), periods, FixedStep())

    # 3. against solve_ivp: both accurate, the ratio the quotient of the times
    for ours, error, plain, plain_error, switches, ratio in figures(
            rf"shroudnet {N} ms \(error {N}\), solve_ivp {N} s \(error {N}\), {N} "
            rf"switches: {N}x$", out, 1):
        assert max(error, plain_error) < 1e-5 and switches > 0
        # the printed times are rounded to 0.1 ms and 0.01 s: the ratio lies in what
        # they allow, and the ratio itself is rounded to 1
        low = (plain - 0.005) / ((ours + 0.05) * 1e-3)
        high = (plain + 0.005) / ((ours - 0.05) * 1e-3)
        assert low - 0.5 <= ratio <= high + 0.5

    # 4. sweeps
    scaling = figures(rf"worker\(s\), {N} values: +{N} s, {N} s per point, speed-up {N} "
                      rf"\(efficiency {N}%\)$", out, 2)
    assert scaling[0][3] == 1.0
    for values, seconds, per_point, _, _ in scaling:
        assert per_point == pytest.approx(seconds / values, abs=0.005 / values + 5e-4)
    ((points, seconds, per_point),) = figures(
        rf"diagram, {N} values on \d+ workers: {N} s wall .*, {N} s per point$", out, 1)
    assert per_point == pytest.approx(seconds / points, abs=0.05 / points + 5e-4)
    assert all(mb > 0.0 for mb in figures(rf"memory of the first run: {N} MB in its main "
                                          rf"process, {N} MB", out, 1)[0])


@pytest.mark.slow
def test_the_benchmarks_tangent_flow_and_steady_states_hold_together(capsys):
    """Sections 5 and 6: the ratios are the quotients; the linear multiplier every orbit
    of three identical blades has (all three moving alike, their contacts never see it:
    |μ| = e^(−c kT/2m)), a positive exponent for the paper's chaotic case and its torus
    bifurcation near 6120 rpm."""
    out = quick_bench(capsys, "5,6", "5. The tangent flow", "6. Steady states")

    # 5. the tangent flow: the ratios are the quotients; γ1 = 8.8 is chaotic
    ((plain, one, one_ratio, every, every_ratio),) = figures(
        rf"paper group, 3 blades: {N}, {N} \({N}x\), {N} \({N}x\)$", out, 1)
    assert plain > 0.0
    assert one_ratio == pytest.approx(one / plain, abs=0.06)
    assert every_ratio == pytest.approx(every / plain, abs=0.06)
    ((exponent, error),) = figures(rf"λ_max = {N} ± {N} per period", out, 1)
    assert exponent > 0.0 <= error

    # 6. steady states: stable orbits, each with the blades' common multiplier
    scene = three_blade_paper(**POINT)
    a = scene.arrays
    for k, _, _, largest in figures(
            rf"period {N}: {N} ms \({N} steps\), \|μ\|max = {N}(?:, .*)?$", out, 2):
        common = math.exp(-a.damping[0] / (2 * a.mass[0]) * k * scene.excitation_period)
        assert common * (1 - 1e-3) <= largest < 1.0
    ((orbits, seconds, per_orbit),) = figures(
        rf"5800–7200 rpm: {N} orbits in {N} s \({N} ms per orbit\)", out, 1)
    assert per_orbit == pytest.approx(seconds / orbits * 1e3, rel=0.01)
    (torus,) = figures(rf"torus at {N} rpm", out, 1)[0]
    assert 6100.0 < torus < 6150.0
    ((swept, ratio),) = figures(rf"speeds \(.*\): {N} s, {N}x the continuation's time",
                                out, 1)
    assert ratio == pytest.approx(swept / seconds, abs=0.06)


@pytest.mark.slow
@pytest.mark.timeout(900)  # on an empty cache it compiles five kernels of substructures
def test_the_benchmarks_packets_contacts_both_run(capsys):
    """Section 7: both kinds of the packet's contacts run, the elastic 3-D ones carrying
    sliders."""
    out = quick_bench(capsys, "7", "7. Substructures")
    ((rigid, elastic),) = figures(rf"rigid stick {N} periods/s; 3-D contacts, elastic "
                                  rf"stick, 2-D friction {N} periods/s", out, 1)
    assert rigid > 0.0 and elastic > 0.0
    ((multipliers, milliseconds, steps),) = figures(
        rf"their stretches in the state\), a periodic orbit with its {N} multipliers from a "
        rf"settled guess {N} ms \({N} Newton steps\)", out, 1)
    assert multipliers == 2 * 18 + 2 * 5 and milliseconds > 0.0 and steps <= 2


@pytest.mark.slow
def test_the_benchmarks_tuned_rings_speed_ups_are_the_quotients_of_the_times(capsys):
    """Section 8."""
    out = quick_bench(capsys, "8", "8. Tuned rings")
    for full, symmetric, ratio in figures(
            rf"full {N} ms, symmetric {N} ms \({N}x\)", out, 1):
        assert ratio == pytest.approx(full / symmetric, abs=0.05 + 0.1 * ratio / symmetric)


@pytest.mark.slow
def test_the_benchmarks_harmonic_balance_times_are_per_point_and_its_errors_fall(capsys):
    """Section 9: a curve's time per point is its time over its points; the series'
    errors against the exact orbit fall from H = 1 to H = 7 (measured 7.8e-2, 5.1e-1 and
    1.7e-1 at H = 1; 3.6e-4, 1.7e-3 and 1.4e-3 at H = 7), the exact orbit's own nought."""
    out = quick_bench(capsys, "9", "9. Harmonic balance")
    figures(rf"certificate .*: {N} ms; errors: amplitude {N}, energy per cycle {N}, state "
            rf"{N}, Hill's multipliers {N}$", out, 1)
    for points, seconds, per_point in figures(
            rf"at H = 7(?:, with Hill)?: {N} points in {N} s \({N} ms a point", out, 3):
        # the time is printed to 0.1 s, the time a point to 1 ms
        assert per_point == pytest.approx(seconds / points * 1e3, abs=50.0 / points + 0.5)
    ((one, whole, ratio, gap),) = figures(
        rf"one sector {N} ms, the whole ring {N} ms \({N}x\), their series agree to {N}$",
        out, 1)
    assert ratio == pytest.approx(whole / one, abs=0.05 + 0.5 * ratio / one) and gap <= 1e-8
    rows = {h: errors for h, _, *errors in figures(
        rf"^ +(\d+|exact) +(?:\d+)? +{N} ms  {N}  {N}  {N}$", out, 5)}
    assert all(low < high for low, high in zip(rows[7.0], rows[1.0]))
    assert rows["exact"] == [0.0, 0.0, 0.0]


@pytest.mark.slow
def test_the_benchmarks_gpu_and_fe_sections_run_and_their_solvers_agree(capsys):
    """Sections 10 (without a GPU, it says what is missing) and 11: the dense and Krylov
    solvers, with and without stability, find the same orbit (measured: 1.7e-11 of the
    scale) and the same leading multipliers (5.1e-12)."""
    out = quick_bench(capsys, "10,11", "10. GPU batches", "11. Steady states at the scale")
    ((state_gap, _, multiplier_gap),) = figures(
        rf"orbits agree to {N} of the scale, their multipliers \(Arnoldi's {N} leading "
        rf"ones\) the dense ones to {N}$", out, 1)
    assert state_gap <= 1e-8 and multiplier_gap <= 1e-8


def test_a_second_process_loads_the_compiled_kernel_instead_of_compiling():
    simulate(three_blade_paper(), 1)  # compiled, or loaded, into the cache folder
    probe = (
        "from shroudnet import simulate\n"
        "from shroudnet.engine.generate import load_kernel\n"
        "from shroudnet.scenes import three_blade_paper\n"
        "scene = three_blade_paper()\n"
        "simulate(scene, 1)\n"
        "stats = load_kernel(scene).run.stats\n"
        "print(sum(stats.cache_hits.values()), sum(stats.cache_misses.values()))\n")
    done = subprocess.run([sys.executable, "-c", probe], capture_output=True, text=True,
                          check=True)
    hits, misses = map(int, done.stdout.split())
    assert (hits, misses) == (1, 0)
