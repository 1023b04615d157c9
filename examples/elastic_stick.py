"""Elastic stick tends to rigid stick: a pressed pair of blades as the tangential stiffness grows.

Two blades pressed together at a face inclined at 0.6 rad, forced apart in phase
opposition so that the face slips for part of each cycle and sticks for the rest
(``scenes.blade_pair``). With a tangential stiffness k_t the stick is a Jenkins element:
each stick starts with the relative velocity the slider leaves and rings on the stuck
spring at ω_t ∝ √k_t, so the motion differs from rigid stick's by about v/ω_t ∝ 1/√k_t.

Run: python examples/elastic_stick.py [OUTPUT_FOLDER]
Saves in OUTPUT_FOLDER (default examples/output/):
- elastic_stick_convergence.png: the largest difference of the blades' motion from rigid
  stick's over three periods, relative to its largest value, against k_t (log–log),
  beside the slope −1/2;
- elastic_stick_loops.png: the face's hysteresis loops over the third period for some
  k_t and for rigid stick: the stuck stretches lean with slope k_t and stand up as it
  grows.
Prints each k_t's difference and the ratio from one decade to the next (√10 = 3.16).
"""

import sys
from dataclasses import dataclass
from pathlib import Path

import numpy as np
from matplotlib.figure import Figure

from shroudnet import Adaptive, HysteresisLoop, hysteresis_loop, simulate
from shroudnet.scenes import blade_pair

OUTPUT = Path(__file__).resolve().parent / "output"
#: The tangential stiffnesses [N/m] of the loops drawn (None: rigid stick).
LOOPS = (1e6, 1e7, None)
PERIODS = 3


@dataclass(frozen=True)
class Convergence:
    """The tangential stiffnesses [N/m], each motion's largest difference from rigid
    stick's relative to its largest value, and the loops by label."""

    stiffness: np.ndarray
    difference: np.ndarray
    loops: dict[str, HysteresisLoop]


def run(tangential_stiffness):
    return simulate(blade_pair(tangential_stiffness=tangential_stiffness), PERIODS,
                    samples_per_period=200, method=Adaptive(rtol=1e-10))


def compute(decades=(6, 9), per_decade=2) -> Convergence:
    """The differences at ``per_decade`` stiffnesses a decade over 10^``decades``, and the
    loops of ``LOOPS``."""
    stiffness = np.logspace(*decades, per_decade * (decades[1] - decades[0]) + 1)
    rigid = run(None)
    scale = np.abs(rigid.x).max()
    difference = np.array([np.abs(run(k).x - rigid.x).max() / scale for k in stiffness])
    loops = {("rigid stick" if k is None else f"k_t = {k:.0e} N/m"):
             hysteresis_loop(rigid if k is None else run(k), 0, PERIODS - 1) for k in LOOPS}
    return Convergence(stiffness, difference, loops)


def report(result: Convergence) -> None:
    for k, gap in zip(result.stiffness, result.difference):
        print(f"k_t = {k:9.3g} N/m: the motion differs from rigid stick's by {gap:.3e}")
    decade = np.isclose(result.stiffness[:, None] * 10.0, result.stiffness[None, :])
    for i, j in zip(*np.nonzero(decade)):
        print(f"  from {result.stiffness[i]:.0e} to {result.stiffness[j]:.0e} N/m: "
              f"{result.difference[i] / result.difference[j]:.2f} times smaller")


def main(decades=(6, 9), per_decade=2, output=OUTPUT) -> Convergence:
    """Compute, print, save the figures in ``output``; returns the ``Convergence``."""
    from shroudnet.front.figures import hysteresis_loops
    result = compute(decades, per_decade)
    report(result)
    output = Path(output)
    output.mkdir(parents=True, exist_ok=True)
    figure = Figure(figsize=(6.5, 4.5), layout="constrained")
    axes = figure.subplots()
    axes.loglog(result.stiffness, result.difference, "o-", label="elastic against rigid stick")
    axes.loglog(result.stiffness, result.difference[0] * np.sqrt(result.stiffness[0]
                                                                 / result.stiffness),
                "--", color="0.5", label="slope −1/2")
    axes.set(xlabel="tangential stiffness k_t [N/m]",
             ylabel="largest difference of the motion / its largest value",
             title="Elastic stick tends to rigid stick as 1/√k_t")
    axes.legend()
    figure.savefig(output / "elastic_stick_convergence.png", dpi=110)
    hysteresis_loops(result.loops, title="The pair's face over one period",
                     ).savefig(output / "elastic_stick_loops.png", dpi=110)
    print(f"saved the figures in {output}")
    return result


if __name__ == "__main__":
    main(output=Path(sys.argv[1]) if len(sys.argv) > 1 else OUTPUT)
