"""A block on a moving belt: the stick–slip limit cycle of velocity-weakening friction.

Run: python examples/belt_stick_slip.py [OUTPUT_FOLDER]
Saves in OUTPUT_FOLDER (default examples/output/):
- belt_stick_slip.png: the block's displacement with its stuck phases shaded, its phase
  portrait, and the friction it carried against the slip velocity over the Stribeck law.

The scene is ``shroudnet.scenes.block_on_belt``: a block on a spring, pressed on a belt
that moves at constant speed (a prescribed-motion node), with no excitation at all. The
belt's work feeds the cycle. While stuck the block rides with the belt, x = x_0 + V t, so
every breakaway happens where the spring pulls with μ_s N: at x = μ_s N / k. The script
prints where the breakaways happened against that value, the cycle's period and its stick
fraction, and the energy balance.
"""

import sys
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from shroudnet import Mode, Simulation, simulate
from shroudnet.engine.codes import EventKind
from shroudnet.scenes import block_on_belt

OUTPUT = Path(__file__).resolve().parent / "output"


@dataclass(frozen=True)
class Cycle:
    """The settled stick–slip cycle of a run."""

    sim: Simulation
    skip: int                     # transient periods left out
    period: float                 # [s], between the last breakaways
    stick_fraction: float         # of the samples after the transient
    breakaway_x: np.ndarray       # [m], the block's x at each breakaway after the transient,
                                  # carried from the last stuck sample at the belt's speed
    static_limit: float           # μ_s N / k [m]


def compute(periods=60, transient=30, samples_per_period=400):
    """Run the block from rest and read its cycle."""
    scene = block_on_belt()
    sim = simulate(scene, periods, samples_per_period=samples_per_period)
    law = scene.group.interfaces[0][2]
    start = transient * scene.excitation_period
    times = sim.events.time[(sim.events.kind == EventKind.BREAKAWAY)
                            & (sim.events.time >= start)]
    a = scene.arrays
    limit = a.static_mu[0] * law.normal.force / a.stiffness[0]
    rows = slice(transient * samples_per_period, None)
    belt_speed = scene.group.prescribed[0][1].velocity
    before = np.searchsorted(sim.t, times) - 1  # the last sample before, still stuck
    x_at = sim.x[before, 0] + belt_speed * (times - sim.t[before])
    return Cycle(sim=sim, skip=transient, period=float(np.diff(times)[-1]),
                 stick_fraction=float(np.mean(sim.modes[rows, 0] == Mode.STICK)),
                 breakaway_x=x_at, static_limit=float(limit))


def report(cycle: Cycle) -> None:
    ledger = cycle.sim.energy
    print(f"stick–slip cycle: period {cycle.period * 1e3:.3f} ms, stuck "
          f"{cycle.stick_fraction:.1%} of the time")
    print(f"breakaway at x = {cycle.breakaway_x.min() * 1e3:.6f} … "
          f"{cycle.breakaway_x.max() * 1e3:.6f} mm; μ_s N / k = "
          f"{cycle.static_limit * 1e3:.6f} mm")
    print(f"energy: the belt put in {ledger.excitation_work:.4f} J, friction took "
          f"{ledger.friction_loss:.4f} J, {ledger.stored_change:+.2e} J stored, residual "
          f"{ledger.residual:.1e} J")


def main(periods=60, transient=30, samples_per_period=400, output=OUTPUT):
    """Compute, print, save the figure in ``output``; returns the ``Cycle``."""
    from shroudnet.front.figures import stick_slip_cycle
    cycle = compute(periods, transient, samples_per_period)
    report(cycle)
    output = Path(output)
    output.mkdir(parents=True, exist_ok=True)
    stick_slip_cycle(cycle.sim, 0, cycle.skip, shown_periods=5,
                     title="A block on a moving belt: the stick–slip limit cycle").savefig(
        output / "belt_stick_slip.png", dpi=110)
    print(f"saved the figure in {output}")
    return cycle


if __name__ == "__main__":
    main(output=Path(sys.argv[1]) if len(sys.argv) > 1 else OUTPUT)
