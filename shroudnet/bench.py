"""Benchmark: ``python -m shroudnet.bench`` prints integration speed on the paper's scene.

Figures are medians of several runs after one warm-up run (which also compiles or loads
the kernel); nothing here is asserted, because timings depend on the machine.
"""

from __future__ import annotations

import statistics
import time

from .scenes import three_blade_paper
from .simulate import FixedStep, simulate


def steps_per_second(*, periods: int = 200, steps_per_period: int = 1000,
                     repeats: int = 5) -> tuple[float, object]:
    """Median fixed steps per second on one core, and the last simulation."""
    scene = three_blade_paper(gamma1=2.2, speed_rpm=6000.0, q1=50.0)
    method = FixedStep(steps_per_period=steps_per_period)
    simulate(scene, 2, method=method)
    rates = []
    for _ in range(repeats):
        start = time.perf_counter()
        sim = simulate(scene, periods, method=method)
        rates.append(periods * steps_per_period / (time.perf_counter() - start))
    return statistics.median(rates), sim


def main() -> None:
    start = time.perf_counter()
    three_blade_paper()  # imports done
    rate, sim = steps_per_second()
    counts = sim.events.counts
    print("paper three-blade scene, gamma1 = 2.2, 6000 rpm, q1 = 50 N, 200 periods")
    print(f"  fixed-step RK4, 1000 steps/period: {rate:,.0f} steps/s (median of 5, one core)")
    print(f"  events: {sum(counts.values())} ({', '.join(f'{k} {v}' for k, v in counts.items())})")
    print(f"  energy ledger residual: {sim.energy.residual:.3e} J "
          f"against friction loss {sim.energy.friction_loss:.4f} J")
    print(f"  wall time including warm-up: {time.perf_counter() - start:.1f} s")


if __name__ == "__main__":
    main()
