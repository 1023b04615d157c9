"""Benchmark: ``python -m shroudnet.bench`` prints integration speed on the paper's scene.

Figures are medians of several runs after one warm-up run (which also compiles or loads
the kernel); nothing here is asserted, because timings depend on the machine.
"""

from __future__ import annotations

import statistics
import time

from .scenes import three_blade_paper
from .simulate import Adaptive, FixedStep, simulate


def steps_per_second(method, *, periods: int = 200, repeats: int = 5) -> tuple[float, object]:
    """Median Runge–Kutta steps per second on one core, and the last simulation.

    A step is one grid step for ``FixedStep``, one accepted step for ``Adaptive``; the time
    includes locating and resolving every switch and recording 100 samples per period.
    """
    scene = three_blade_paper(gamma1=2.2, speed_rpm=6000.0, q1=50.0)
    simulate(scene, 2, method=method)
    rates = []
    for _ in range(repeats):
        start = time.perf_counter()
        sim = simulate(scene, periods, method=method)
        rates.append(sim.steps / (time.perf_counter() - start))
    return statistics.median(rates), sim


def main() -> None:
    start = time.perf_counter()
    three_blade_paper()  # imports done
    print("paper three-blade scene, gamma1 = 2.2, 6000 rpm, q1 = 50 N, 200 periods, one core")
    for label, method in [("fixed-step RK4, 1000 steps/period", FixedStep()),
                          ("adaptive DP5(4), default tolerances", Adaptive())]:
        rate, sim = steps_per_second(method)
        counts = sim.events.counts
        per_period = sim.steps / sim.periods
        print(f"  {label}: {rate:,.0f} steps/s, {per_period:,.0f} steps/period, "
              f"{rate / per_period:,.0f} periods/s (median of 5)")
        print(f"    events: {sum(counts.values())} "
              f"({', '.join(f'{k} {v}' for k, v in counts.items())})")
        print(f"    energy ledger residual: {sim.energy.residual:.3e} J "
              f"against friction loss {sim.energy.friction_loss:.4f} J")
    print(f"  wall time including warm-up: {time.perf_counter() - start:.1f} s")


if __name__ == "__main__":
    main()
