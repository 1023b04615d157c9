"""Where Hill's method can be trusted: Hill's multipliers against the exact Floquet
multipliers as the harmonics grow, on a smooth orbit, an impacting one and a stick–slip
one.

Smooth: a mass pressed on a Hertz stop that never opens (``scenes.mass_on_stop`` with a
2 mm interference, 2 N at 31 Hz), its contact force smooth over the orbit: Hill's
multipliers converge to the exact ones exponentially, down to the exact orbit's own
accuracy (shot at rtol 1e-12, a residual of 1e-12). Impacting: the same mass hitting a
linear stop once a cycle (``scenes.mass_on_stop()``): the force has a kink at each
closing and opening, and the saltations there are in no series; Hill's multipliers
approach the exact ones slowly and not monotonically, about as 1/H from H = 4.
Stick–slip: the 2-DOF Jenkins chain (``scenes.jenkins_chain``), its slider sticking and
slipping twice a cycle: a slipping slider forgets a constant offset, so Hill's problem
is solved by the open structure's motions, and Hill's multipliers are the open
structure's at every H, as far from the exact ones at H = 16 as at H = 1
(``steady.harmonic.hill``).

Run: python examples/hill_against_floquet.py [OUTPUT_FOLDER]
Saves in OUTPUT_FOLDER (default examples/output/):
- hill_against_floquet.png: for each case, the multipliers in the complex plane (Hill's
  at each H over the exact ones, with the unit circle) and the error of the exact
  multipliers against H.
Prints, per case and H, whether the orbit is smooth, Hill's largest modulus and the
error of the leading multiplier.
"""

import sys
from pathlib import Path

from contact_laws import Hertz
from shroudnet import Adaptive
from shroudnet.front.figures import hill_floquet_diagram, save_figure
from shroudnet.scenes import jenkins_chain, mass_on_stop
from shroudnet.studies.hill_floquet import HARMONICS, HillFloquet, hill_against_floquet

OUTPUT = Path(__file__).resolve().parent / "output"

#: The cases: a scene, and the accuracy its exact orbit is shot to (the smooth one's
#: tight enough for Hill's error to fall to 1e-12 before it levels off).
CASES = {
    "Hertz stop, closed throughout": (
        lambda: mass_on_stop(gap=-2e-3, normal=Hertz(stiffness=1e6), q1=2.0, frequency=31.0),
        dict(method=Adaptive(rtol=1e-12), tolerance=1e-12)),
    "mass hitting a stop": (mass_on_stop, {}),
    "Jenkins chain, stick–slip": (jenkins_chain, {}),
}


def compute(harmonics=HARMONICS) -> dict[str, HillFloquet]:
    """The study of each case at ``harmonics``."""
    return {name: hill_against_floquet(scene(), harmonics, **accuracy)
            for name, (scene, accuracy) in CASES.items()}


def report(studies: dict[str, HillFloquet]) -> None:
    for name, study in studies.items():
        print(f"{name}: H, smooth, Hill's largest |μ|, error of the leading multiplier")
        for h, smooth, modulus, error in study.rows():
            print(f"  {h:>5} {smooth!s:>5} {modulus:.6f} {error:.1e}")


def plot(studies: dict[str, HillFloquet]):
    """A figure of one row per case: ``hill_floquet_diagram``'s two panels."""
    from matplotlib.figure import Figure
    figure = Figure(figsize=(10, 4.2 * len(studies)), layout="constrained")
    rows = figure.subplots(len(studies), 2, squeeze=False)
    for row, (name, study) in zip(rows, studies.items()):
        hill_floquet_diagram(study, label=name, axes=list(row))
    figure.suptitle("Hill's multipliers against the exact Floquet multipliers")
    return figure


def main(harmonics=HARMONICS, output=OUTPUT) -> dict[str, HillFloquet]:
    """Compute, print, save the figure in ``output``; returns the studies."""
    studies = compute(harmonics)
    report(studies)
    output = Path(output)
    output.mkdir(parents=True, exist_ok=True)
    save_figure(plot(studies), output / "hill_against_floquet.png")
    print(f"saved the figure in {output}")
    return studies


if __name__ == "__main__":
    main(output=Path(sys.argv[1]) if len(sys.argv) > 1 else OUTPUT)
