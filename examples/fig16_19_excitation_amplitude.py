"""Figs. 16–19: the reference blade against the excitation amplitude q1 (γ1 = 2.2, 6000 rpm).

Run: python examples/fig16_19_excitation_amplitude.py [OUTPUT_FOLDER]
Saves the response panels at the paper's amplitudes and the bifurcation diagram in
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

#: The motions the paper reports (§3.1.3).
CLAIMS = {5.0: "p1", 20.0: "p3", 50.0: "quasi-periodic"}


def scene_at(q1):
    return three_blade_paper(gamma1=2.2, speed_rpm=6000.0, q1=q1)


def compute(values=400, transient=300, record=100, steady=500):
    """The paper's claims checked, and the bifurcation diagram over ``values`` q1 in [1, 60] N."""
    return compute_study(scene_at=scene_at, parameter="q1", claims=CLAIMS,
                         values=np.linspace(1.0, 60.0, values), transient=transient,
                         record=record, steady=steady)


def main(values=400, transient=300, record=100, steady=500, output=OUTPUT):
    """Compute, save the figures in ``output`` and print the claims; returns the result."""
    result = compute(values, transient, record, steady)
    save_figures(result, output, label="q1", unit="N", first_figure=17,
                 diagram_figure=16)
    print_table(result, "q1")
    print(f"saved the figures in {output}")
    return result


if __name__ == "__main__":
    main(output=output_folder())
