"""Shared by the figure scripts of the paper's §3.1: a bifurcation diagram, response panels
at the paper's chosen values, and a table of the paper's claims beside what shroudnet finds.

Each script calls ``compute`` (the numbers), then ``save_figures`` and ``print_table``;
``output_folder`` reads the folder to save in from the command line.
"""

import sys
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from shroudnet import Adaptive, classify, simulate, sweep
from shroudnet.analysis.readings import Classification
from shroudnet.run.simulation import Simulation
from shroudnet.studies.sweep import Sweep

#: Where the examples save their figures unless told otherwise.
OUTPUT = Path(__file__).resolve().parent / "output"
#: Tolerances that keep Poincaré points to about 1e-7 of the response.
METHOD = Adaptive(rtol=1e-8, atol=1e-12)
#: The reference blade of the paper's figures.
BLADE = "blade2"


@dataclass(frozen=True)
class Claim:
    """The response at one of the paper's chosen values, beside the paper's label."""

    value: float
    paper: str                      # the paper's label: "p1", "p3", "quasi-periodic", ...
    found: Classification           # shroudnet's, over the steady periods
    simulation: Simulation          # transient + steady periods


@dataclass(frozen=True)
class PaperStudy:
    """What a figure script computes: the claims checked and the bifurcation diagram."""

    parameter: str
    transient: int                  # periods left out of each claim's classification
    claims: tuple[Claim, ...]
    diagram: Sweep


def compute(*, scene_at, parameter, claims, values, transient, record, steady) -> PaperStudy:
    """The response at each claimed value, then the bifurcation diagram over ``values``,
    with the largest Lyapunov exponent of every point that does not repeat.

    ``claims`` maps a parameter value to the paper's label; ``transient`` periods are run
    before ``steady`` (a claim) or ``record`` (a diagram point) periods are analysed.
    """
    checked = []
    for value, label in claims.items():
        sim = simulate(scene_at(value), transient + steady, method=METHOD)
        checked.append(Claim(value=value, paper=label,
                             found=classify(sim, BLADE, skip=transient), simulation=sim))
    diagram = sweep(scene_at, np.asarray(values), parameter=parameter, blade=BLADE,
                    transient=transient, record=record, method=METHOD, lyapunov=True)
    return PaperStudy(parameter=parameter, transient=transient, claims=tuple(checked),
                      diagram=diagram)


def save_figures(result: PaperStudy, output: Path, *, label, unit, first_figure,
                 diagram_figure) -> list[Path]:
    """A response panel per claim and the bifurcation diagram, saved in ``output``."""
    from shroudnet.front.figures import bifurcation_diagram, response_panel
    output = Path(output)
    output.mkdir(parents=True, exist_ok=True)
    saved = []
    for number, claim in enumerate(result.claims, start=first_figure):
        title = f"Fig. {number}: {label} = {claim.value:g} {unit}".rstrip()
        panel = response_panel(claim.simulation, BLADE, skip=result.transient, title=title)
        saved.append(output / f"fig{number:02d}_{result.parameter}_{claim.value:g}.png")
        panel.savefig(saved[-1], dpi=110)
    diagram = bifurcation_diagram(result.diagram,
                                  xlabel=f"{label} [{unit}]" if unit else label,
                                  title=f"Fig. {diagram_figure}: reference blade")
    saved.append(output / f"fig{diagram_figure:02d}_bifurcation_{result.parameter}.png")
    diagram.savefig(saved[-1], dpi=110)
    return saved


def print_table(result: PaperStudy, label: str) -> None:
    """The paper's label beside shroudnet's at each claimed value, with the evidence."""
    print(f"{label:>8} {'paper':>15} {'shroudnet':>15}  evidence")
    for claim in result.claims:
        print(f"{claim.value:8g} {claim.paper:>15} {claim.found.label:>15}  {claim.found}")


def output_folder() -> Path:
    """The folder named on the command line (``python SCRIPT [FOLDER]``), else ``OUTPUT``."""
    return Path(sys.argv[1]) if len(sys.argv) > 1 else OUTPUT
