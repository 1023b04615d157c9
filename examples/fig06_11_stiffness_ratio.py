"""Figs. 6–11: the reference blade against the stiffness ratio γ1 (Ω = 6000 rpm, q1 = 50 N).

Run: python examples/fig06_11_stiffness_ratio.py
Saves the response panels at the paper's γ1 values and the bifurcation diagram in
examples/output/, and prints the paper's classification beside shroudnet's.
"""

import sys
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parent))
from _paper_study import study  # noqa: E402

from shroudnet.scenes import three_blade_paper  # noqa: E402

#: The motions the paper reports (§3.1.1).
CLAIMS = {1.0: "p1", 3.5: "p3", 5.31: "p9", 6.0: "chaotic", 8.8: "p5"}


def scene_at(gamma1):
    return three_blade_paper(gamma1=gamma1, speed_rpm=6000.0, q1=50.0)


def main(values=400, transient=300, record=100, steady=500):
    return study(scene_at=scene_at, parameter="gamma1", label="γ1", unit="", claims=CLAIMS,
                 first_figure=7, diagram_figure=6, values=np.linspace(0.5, 10.0, values),
                 transient=transient, record=record, steady=steady)


if __name__ == "__main__":
    main()
