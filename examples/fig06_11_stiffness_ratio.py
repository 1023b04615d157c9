"""Figs. 6–11: the reference blade against the stiffness ratio γ1 (Ω = 6000 rpm, q1 = 50 N).

Run: python examples/fig06_11_stiffness_ratio.py [OUTPUT_FOLDER]
Saves the response panels at the paper's γ1 values and the bifurcation diagram in
OUTPUT_FOLDER (default examples/output/), and prints the paper's classification
beside shroudnet's.
"""

import sys
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parent))
from _paper_study import OUTPUT, output_folder, print_table, save_figures  # noqa: E402
from _paper_study import compute as compute_study  # noqa: E402

from shroudnet.scenes import three_blade_paper  # noqa: E402

#: The motions the paper reports (§3.1.1).
CLAIMS = {1.0: "p1", 3.5: "p3", 5.31: "p9", 6.0: "chaotic", 8.8: "p5"}


def scene_at(gamma1):
    return three_blade_paper(gamma1=gamma1, speed_rpm=6000.0, q1=50.0)


def compute(values=400, transient=300, record=100, steady=500):
    """The paper's claims checked, and the bifurcation diagram over ``values`` γ1 in [0.5, 10]."""
    return compute_study(scene_at=scene_at, parameter="gamma1", claims=CLAIMS,
                         values=np.linspace(0.5, 10.0, values), transient=transient,
                         record=record, steady=steady)


def main(values=400, transient=300, record=100, steady=500, output=OUTPUT):
    """Compute, save the figures in ``output`` and print the claims; returns the result."""
    result = compute(values, transient, record, steady)
    save_figures(result, output, label="γ1", unit="", first_figure=7,
                 diagram_figure=6)
    print_table(result, "γ1")
    print(f"saved the figures in {output}")
    return result


if __name__ == "__main__":
    main(output=output_folder())
