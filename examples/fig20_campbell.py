"""Fig. 20: the Campbell diagram of the rotating shrouded blade.

Run: python examples/fig20_campbell.py
Saves examples/output/fig20_campbell.png and prints the resonance crossings of f_d1(Ω)
(``paper_frequency_model``) with the engine-order lines.
"""

from pathlib import Path

import numpy as np

from shroudnet import campbell
from shroudnet.figures import campbell_diagram
from shroudnet.scenes import paper_frequency_model

OUTPUT = Path(__file__).resolve().parent / "output"


def main(speeds=np.linspace(0.0, 12000.0, 241), engine_orders=(1, 2, 3, 4)):
    diagram = campbell(paper_frequency_model(), speeds, engine_orders)
    print("engine order   speed [rpm]   f_d1 = f_e [Hz]")
    for order, speed, frequency in diagram.crossings:
        print(f"{order:12d} {speed:13.1f} {frequency:17.2f}")
    OUTPUT.mkdir(exist_ok=True)
    campbell_diagram(diagram, title="Fig. 20: Campbell diagram").savefig(
        OUTPUT / "fig20_campbell.png", dpi=110)
    print(f"saved the figure in {OUTPUT}")
    return diagram


if __name__ == "__main__":
    main()
