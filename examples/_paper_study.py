"""Shared by the figure scripts of the paper's §3.1: a bifurcation diagram, response panels
at the paper's chosen values, and a table of the paper's claims beside what shroudnet finds.
"""

from pathlib import Path

import numpy as np

from shroudnet import Adaptive, classify, simulate, sweep
from shroudnet.figures import bifurcation_diagram, response_panel

#: Where the examples save their figures.
OUTPUT = Path(__file__).resolve().parent / "output"
#: Tolerances that keep Poincaré points to about 1e-7 of the response.
METHOD = Adaptive(rtol=1e-8, atol=1e-12)


def study(*, scene_at, parameter, label, unit, claims, first_figure, diagram_figure,
          values, transient, record, steady):
    """Response panels at each claimed value, then the bifurcation diagram over ``values``.

    ``claims`` maps a parameter value to the paper's label. Returns the table rows
    (value, paper's label, shroudnet's classification).
    """
    OUTPUT.mkdir(exist_ok=True)
    rows = []
    for number, (value, claim) in enumerate(claims.items(), start=first_figure):
        sim = simulate(scene_at(value), transient + steady, method=METHOD)
        kind = classify(sim, "blade2", skip=transient)
        rows.append((value, claim, kind))
        title = f"Fig. {number}: {label} = {value:g} {unit}".rstrip()
        panel = response_panel(sim, "blade2", skip=transient, title=title)
        panel.savefig(OUTPUT / f"fig{number:02d}_{parameter}_{value:g}.png", dpi=110)
    print(f"{label:>8} {'paper':>15} {'shroudnet':>15}  evidence")
    for value, claim, kind in rows:
        print(f"{value:8g} {claim:>15} {kind.label:>15}  {kind}")
    result = sweep(scene_at, np.asarray(values), parameter=parameter, transient=transient,
                   record=record, method=METHOD)
    diagram = bifurcation_diagram(result, xlabel=f"{label} [{unit}]" if unit else label,
                                  title=f"Fig. {diagram_figure}: reference blade")
    diagram.savefig(OUTPUT / f"fig{diagram_figure:02d}_bifurcation_{parameter}.png", dpi=110)
    print(f"saved the figures in {OUTPUT}")
    return rows
