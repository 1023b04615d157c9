"""A map of the paper's three-blade group over the stiffness ratio γ1 and the rotating
speed Ω (q1 = 50 N): the reference blade's steady motion classified in every cell, as the
paper's Figs. 6 and 12 classify it along one line of each.

Run: python examples/paper_map.py [OUTPUT_FOLDER]
Saves paper_map.png in OUTPUT_FOLDER (default examples/output/): the map coloured by the
classification (period-k, quasi-periodic, chaotic), γ1 along x and Ω along y. Prints how
many cells fall in each class, the cells at the paper's γ1 values at 6000 rpm beside the
paper's label (Figs. 7–11), and the wall time.

The grid is 39 values of γ1 over [0.5, 10] (steps of 0.25) by 41 speeds over
[5000, 7000] rpm (steps of 50 rpm), the ranges of the paper's Figs. 6 and 12: its row at
6000 rpm is Fig. 6's line, and it holds the paper's γ1 = 1, 3.5 and 6. Every cell runs
the paper's 300 transient and 100 recorded periods, from rest, on every core
(``sweep_map``'s default executor), and a cell that does not repeat is told chaotic or
quasi-periodic by its largest Lyapunov exponent (without it, the 0–1 test over 100
points calls the paper's quasi-periodic γ1 = 2.2 at 6000 rpm chaotic). The integrator is
``Adaptive(rtol=1e-7)``: on 20 values of γ1 at 6000 rpm and 15 speeds at γ1 = 2.2 it
labels every point as rtol = 1e-8 does, its periodic points repeat to 1e-7 of the motion
or better (the classification's tolerance is 1e-5), and it runs 1.6–1.9 times as fast;
fixed RK4 steps need 250 a period for Poincaré points as close and then run no faster
than rtol = 1e-8, while rtol = 1e-6 turns γ1 = 0.5's period-1 into quasi-periodic. The
1,599 cells × 400 periods took 155 s on two cores that other work shared. The few
undetermined cells lie on the boundaries between regions: their λ_max is negative but
their points do not yet repeat (at γ1 = 2.75, 6400 rpm, λ_max = −0.036 per period and a
mismatch of 1.8e-4 after 300 periods), transients that settle slowly near a bifurcation.
"""

import sys
import time
from collections import Counter
from dataclasses import dataclass
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parent))
from _paper_study import BLADE, OUTPUT, output_folder  # noqa: E402
from fig06_11_stiffness_ratio import CLAIMS  # noqa: E402

from shroudnet import Adaptive, SweepMap, sweep_map  # noqa: E402
from shroudnet.scenes import three_blade_paper  # noqa: E402

#: The grid: γ1 as in Fig. 6, Ω [rpm] as in Fig. 12.
GAMMAS = np.linspace(0.5, 10.0, 39)
SPEEDS = np.linspace(5000.0, 7000.0, 41)
#: The speed of Fig. 6 [rpm], at which ``CLAIMS`` are the paper's labels over γ1.
PAPER_SPEED = 6000.0
#: Poincaré points to about 1e-7 of the motion: the labels of rtol = 1e-8, at less cost.
METHOD = Adaptive(rtol=1e-7)


def scene_at(gamma1, speed_rpm):
    return three_blade_paper(gamma1=gamma1, speed_rpm=speed_rpm, q1=50.0)


@dataclass(frozen=True)
class PaperMap:
    """The map and the wall time it took [s]."""

    map: SweepMap
    seconds: float

    def counts(self) -> dict[str, int]:
        """Cells of each class, the commonest first."""
        return dict(Counter(self.map.labels.ravel().tolist()).most_common())

    def label_at(self, gamma1: float, speed_rpm: float) -> str:
        """The class of the cell at (γ1, Ω), which must be on the grid."""
        row = np.flatnonzero(np.isclose(self.map.first, gamma1))
        column = np.flatnonzero(np.isclose(self.map.second, speed_rpm))
        if not (row.size and column.size):
            raise ValueError(f"PaperMap.label_at: (γ1, Ω) = ({gamma1}, {speed_rpm}) is not a "
                             "cell of the grid")
        return self.map.labels[row[0], column[0]]


def compute(gammas=GAMMAS, speeds=SPEEDS, transient=300, record=100):
    """The map over ``gammas`` × ``speeds`` [rpm], ``transient`` + ``record`` periods a
    cell, with its wall time."""
    began = time.perf_counter()
    result = sweep_map(scene_at, gammas, speeds, parameters=("gamma1", "speed_rpm"),
                       blade=BLADE, transient=transient, record=record, method=METHOD,
                       lyapunov=True)
    return PaperMap(map=result, seconds=time.perf_counter() - began)


def main(gammas=GAMMAS, speeds=SPEEDS, transient=300, record=100, output=OUTPUT):
    """Compute, save the map in ``output`` and print its classes; returns the result."""
    from shroudnet.front.figures import save_figure, sweep_map_figure

    result = compute(gammas, speeds, transient, record)
    cells = result.map.labels.size
    print(f"{len(result.map.first)} γ1 × {len(result.map.second)} speeds = {cells} cells, "
          f"{transient} + {record} periods each: {result.seconds:.1f} s")
    for label, count in result.counts().items():
        print(f"  {label:>15} {count:5d} cells ({count / cells:.1%})")
    if np.isclose(result.map.second, PAPER_SPEED).any():
        print(f"at {PAPER_SPEED:g} rpm (Fig. 6): γ1, paper, map")
        for gamma1, paper in CLAIMS.items():
            if np.isclose(result.map.first, gamma1).any():
                print(f"  {gamma1:5g} {paper:>8} {result.label_at(gamma1, PAPER_SPEED):>15}")
    figure = sweep_map_figure(result.map, xlabel="stiffness ratio γ1",
                              ylabel="speed Ω [rpm]",
                              title="The paper's group, q1 = 50 N: reference blade's motion")
    output = Path(output)
    output.mkdir(parents=True, exist_ok=True)
    saved = save_figure(figure, output / "paper_map.png", dpi=110)
    print(f"saved {saved}")
    return result


if __name__ == "__main__":
    main(output=output_folder())
