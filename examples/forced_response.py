"""Forced-response curves of the paper's group, with their unstable branches.

Run: python examples/forced_response.py [OUTPUT_FOLDER]
Saves in OUTPUT_FOLDER (default examples/output/):
- forced_response_speed.png: blade 2's amplitude (half its peak-to-peak) and E_ρ against
  the speed across the l = 2 resonance, at the paper's gap and at a 10 times larger one;
- forced_response_q1.png: the same against the excitation amplitude q1 (Fig. 16's
  parameter) at 6000 rpm.
Each branch of period-1 orbits comes from ``continuation``; stable orbits are drawn
solid, unstable ones dashed, bifurcations marked. Over them, the E_ρ of transient sweeps
up and down the parameter: wherever a branch is stable and alone they must agree, and the
script prints how well they do.
"""

import sys
from collections.abc import Callable
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from shroudnet import Branch, Sweep, continuation, periodic_orbit, sweep
from shroudnet.scenes import three_blade_paper

OUTPUT = Path(__file__).resolve().parent / "output"
PAPER_GAP = 2e-5  # m


def at_speed(gap):
    def scene_at(speed_rpm):
        return three_blade_paper(speed_rpm=speed_rpm, gap=gap)
    return scene_at


def at_q1(q1):
    return three_blade_paper(q1=q1)


@dataclass(frozen=True)
class Curve:
    """One parameter's branch and its transient sweeps up and down."""

    scene_at: Callable
    branch: Branch
    up: Sweep
    down: Sweep

    def agreement(self, blade="blade2") -> float:
        """max |E_ρ(sweep) / E_ρ(orbit) − 1| over the sweep points that repeat with
        period 1 where the branch has exactly one orbit, and it is stable: the orbit at
        the point's value solved by ``periodic_orbit`` from the branch on both sides."""
        worst = 0.0
        for result in (self.up, self.down):
            for point in result.points:
                if point.failed or point.classification.period != 1:
                    continue
                orbit = self.orbit_at(point.value)
                if orbit is not None:
                    worst = max(worst, abs(point.energy_density
                                           / orbit.energy_density(blade) - 1.0))
        return worst

    def orbit_at(self, value):
        """The branch's orbit at ``value``, if the branch passes there once, stably."""
        p, stable = self.branch.parameter, self.branch.stable
        inside = [i for i in range(len(p) - 1)
                  if min(p[i], p[i + 1]) <= value <= max(p[i], p[i + 1]) and p[i] != p[i + 1]]
        if len(inside) != 1 or not (stable[inside[0]] and stable[inside[0] + 1]):
            return None
        i = inside[0]
        a, b = self.branch.orbits[i].state, self.branch.orbits[i + 1].state
        guess = a + (value - p[i]) / (p[i + 1] - p[i]) * (b - a)
        return periodic_orbit(self.scene_at(value), 1, guess=np.split(guess, 2))


def curve(scene_at, start, stop, *, name, max_step, values, transient, record):
    branch = continuation(scene_at, start, stop, parameter=name, max_step=max_step)
    grid = np.linspace(start, stop, values)
    options = {"parameter": name, "transient": transient, "record": record,
               "continuation": True, "workers": 1, "progress": False}
    return Curve(scene_at, branch, sweep(scene_at, grid, **options),
                 sweep(scene_at, grid[::-1], **options))


def compute(values=29, transient=300, record=50, max_step=0.3):
    """The speed curves at the paper's gap and at 10× it, and the q1 curve."""
    speed = {f"Δ = {gap * 1e3:g} mm": curve(at_speed(gap), 5800.0, 7200.0, name="speed [rpm]",
                                             max_step=max_step, values=values,
                                             transient=transient, record=record)
             for gap in (PAPER_GAP, 10 * PAPER_GAP)}
    q1 = {"Ω = 6000 rpm": curve(at_q1, 1.0, 60.0, name="q1 [N]", max_step=max_step,
                                values=values, transient=transient, record=record)}
    return speed, q1


def report(curves):
    for label, result in curves.items():
        branch = result.branch
        print(f"{label}: {len(branch)} orbits, {branch.stable.sum()} stable; "
              f"transient sweeps agree with the stable branch to "
              f"{result.agreement():.1e} in E_ρ")
        for b in branch.bifurcations:
            print(f"  {b.kind:16s} at {branch.name} = {b.parameter:10.4f}"
                  + (f"   |μ| = {abs(b.multiplier):.6f}, arg μ = "
                     f"{np.angle(b.multiplier):+.4f}" if np.isfinite(b.multiplier) else ""))


def main(values=29, transient=300, record=50, max_step=0.3, output=OUTPUT):
    """Compute, print the bifurcations and the agreement, save the figures in ``output``;
    returns (speed curves, q1 curves)."""
    from shroudnet.front.figures import forced_response
    speed, q1 = compute(values, transient, record, max_step)
    report(speed)
    report(q1)
    output = Path(output)
    output.mkdir(parents=True, exist_ok=True)
    for curves, name, xlabel in ((speed, "forced_response_speed.png", "Ω [rpm]"),
                                 (q1, "forced_response_q1.png", "q1 [N]")):
        sweeps = {f"{label}, sweep {way}": getattr(result, way)
                  for label, result in curves.items() for way in ("up", "down")}
        figure = forced_response({label: result.branch for label, result in curves.items()},
                                 "blade2", sweeps=sweeps, xlabel=xlabel,
                                 title="Forced response of blade 2, period-1 orbits")
        figure.savefig(output / name, dpi=110)
    print(f"saved the figures in {output}")
    return speed, q1


if __name__ == "__main__":
    main(output=Path(sys.argv[1]) if len(sys.argv) > 1 else OUTPUT)
