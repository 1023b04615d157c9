"""Fig. 20: the Campbell diagram of the rotating shrouded blade.

Run: python examples/fig20_campbell.py [OUTPUT_FOLDER]
Saves fig20_campbell.png in OUTPUT_FOLDER (default examples/output/) and prints the
resonance crossings of f_d1(Ω) (``paper_frequency_model``) with the engine-order lines.
"""

import sys
from pathlib import Path

import numpy as np

from shroudnet import campbell
from shroudnet.scenes import paper_frequency_model

OUTPUT = Path(__file__).resolve().parent / "output"


def compute(speeds=np.linspace(0.0, 12000.0, 241), engine_orders=(1, 2, 3, 4)):
    """The Campbell diagram of the paper's f_d1(Ω) over ``speeds`` [rpm]."""
    return campbell(paper_frequency_model(), speeds, engine_orders)


def main(speeds=np.linspace(0.0, 12000.0, 241), engine_orders=(1, 2, 3, 4), output=OUTPUT):
    """Compute, print the crossings and save the figure in ``output``; returns the diagram."""
    from shroudnet.front.figures import campbell_diagram
    diagram = compute(speeds, engine_orders)
    print("engine order   speed [rpm]   f_d1 = f_e [Hz]")
    for order, speed, frequency in diagram.crossings:
        print(f"{order:12d} {speed:13.1f} {frequency:17.2f}")
    output = Path(output)
    output.mkdir(parents=True, exist_ok=True)
    campbell_diagram(diagram, title="Fig. 20: Campbell diagram").savefig(
        output / "fig20_campbell.png", dpi=110)
    print(f"saved the figure in {output}")
    return diagram


if __name__ == "__main__":
    main(output=Path(sys.argv[1]) if len(sys.argv) > 1 else OUTPUT)
