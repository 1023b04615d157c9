"""The plain solve_ivp implementation agrees with the compiled loop; the benchmark runs;
compiled kernels are cached for the next process."""

import subprocess
import sys

import numpy as np
import pytest

from shroudnet import Adaptive, simulate
from shroudnet.baseline import solve_ivp_baseline
from shroudnet.bench import main as bench_main
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


@pytest.mark.timeout(1500)  # compiles in fresh processes, then every kind of kernel
def test_the_benchmark_runs_and_prints_every_section(capsys):
    bench_main(["--quick"])
    out = capsys.readouterr().out
    for heading in ("1. Integration speed", "2. Effects", "3. Against plain",
                    "4. Sweeps", "Fig. 6-class diagram", "peak resident memory",
                    "5. The tangent flow"):
        assert heading in out
    assert "steps/s" in out and "x per trajectory" in out and "speed-up" in out
    assert "λ_max =" in out


def test_a_second_process_loads_the_compiled_kernel_instead_of_compiling():
    simulate(three_blade_paper(), 1)  # compiled, or loaded, into the cache folder
    probe = (
        "from shroudnet import simulate\n"
        "from shroudnet.engine.generate import load_kernel\n"
        "from shroudnet.scenes import three_blade_paper\n"
        "scene = three_blade_paper()\n"
        "simulate(scene, 1)\n"
        "stats = load_kernel(scene).run_adaptive.stats\n"
        "print(sum(stats.cache_hits.values()), sum(stats.cache_misses.values()))\n")
    done = subprocess.run([sys.executable, "-c", probe], capture_output=True, text=True,
                          check=True)
    hits, misses = map(int, done.stdout.split())
    assert (hits, misses) == (1, 0)
