"""Figs. 12–15: the reference blade against the rotating speed Ω (γ1 = 2.2, q1 = 50 N).

Run: python examples/fig12_15_rotating_speed.py [OUTPUT_FOLDER]
Saves the response panels at the paper's speeds and the bifurcation diagram in
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

#: The motions the paper reports (§3.1.2).
CLAIMS = {5030.0: "p1", 5790.0: "p3", 5990.0: "quasi-periodic"}


def scene_at(speed_rpm):
    return three_blade_paper(gamma1=2.2, speed_rpm=speed_rpm, q1=50.0)


def compute(values=400, transient=300, record=100, steady=500):
    """The paper's claims checked, and the bifurcation diagram over ``values`` speeds in
    [5000, 7000] rpm."""
    return compute_study(scene_at=scene_at, parameter="speed", claims=CLAIMS,
                         values=np.linspace(5000.0, 7000.0, values), transient=transient,
                         record=record, steady=steady)


def main(values=400, transient=300, record=100, steady=500, output=OUTPUT):
    """Compute, save the figures in ``output`` and print the claims; returns the result."""
    result = compute(values, transient, record, steady)
    save_figures(result, output, label="Ω", unit="rpm", first_figure=13,
                 diagram_figure=12)
    print_table(result, "Ω")
    print(f"saved the figures in {output}")
    return result


if __name__ == "__main__":
    main(output=output_folder())
