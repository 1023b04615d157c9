"""What accuracy costs: the six-blade packet's forced response by harmonic balance at
H = 1, 3 and 7, against its exact orbits.

The packet of ``examples/fe_packet_elastic.py`` (six three-mode blades, 3-D shroud faces
with elastic stick, k_t = 3e5 N/m, a circular Coulomb limit μ = 0.3) across its first
flap resonance (2650–3200 rpm: beyond, the exact tangent flow's adaptive step collapses
within a period from the series' state, and shooting fails). Harmonic balance solves
each speed on the contacts' coordinates alone (5 faces × 3 coordinates × (2H + 1)
unknowns), each speed from the last one's orbit;
the exact orbit at each speed is shot from the H = 7 series (``certify``), every switch
located. The figure draws the four curves, each labelled with its largest relative
amplitude error over the speeds and the CPU time of the whole curve.

Run: python examples/harmonic_balance_packet.py [OUTPUT_FOLDER]
Saves in OUTPUT_FOLDER (default examples/output/):
- harmonic_balance_packet.png: the flapwise amplitude (half the peak-to-peak) of blade 1's
  shroud against the speed, by harmonic balance at H = 1, 3, 7 and exact.
Prints, per H, the largest error and the time, and the exact orbits' time.
"""

import sys
import time
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from shroudnet import certify, harmonic_balance
from shroudnet.scenes import modal_packet

OUTPUT = Path(__file__).resolve().parent / "output"
#: The response drawn: blade 1's shroud, flapwise; the speeds [rpm]; the faces' k_t [N/m].
RESPONSE = ("blade1", "shroud", 0)
SPEEDS = (2650.0, 3200.0)
TANGENTIAL_STIFFNESS = 3e5
HARMONICS = (1, 3, 7)


def scene_at(speed_rpm):
    return modal_packet(speed_rpm=speed_rpm, tangential_stiffness=TANGENTIAL_STIFFNESS)


@dataclass(frozen=True)
class Curves:
    """The amplitudes [m] at ``speeds`` [rpm] by H and exact, whether every series
    converged, and the CPU seconds of each curve."""

    speeds: np.ndarray
    amplitude: dict[int, np.ndarray]
    exact: np.ndarray
    converged: dict[int, bool]
    seconds: dict[int, float]
    exact_seconds: float

    def error(self, harmonics: int) -> float:
        """The largest relative amplitude error of the curve of ``harmonics`` H."""
        return float(np.abs(self.amplitude[harmonics] - self.exact).max()
                     / self.exact.max())


#: The residual the exact orbits are solved to: 1e-8 of the state, far below the series'
#: errors, and above the integration noise the packet's map has at some speeds.
EXACT_TOLERANCE = 1e-8


def compute(speeds=12, harmonics=HARMONICS) -> Curves:
    """Harmonic balance at each H over ``speeds`` speeds, each from the last one's orbit,
    and the exact orbits shot from the largest H's series."""
    grid = np.linspace(*SPEEDS, speeds)
    amplitude, converged, seconds, finest = {}, {}, {}, []
    for h in harmonics:
        began, orbit, values, ok = time.process_time(), None, [], True
        orbits = []
        for speed in grid:
            orbit = harmonic_balance(scene_at(speed), h, guess=orbit, stability=False)
            values.append(orbit.amplitude(RESPONSE))
            ok = ok and orbit.converged
            orbits.append(orbit)
        seconds[h] = time.process_time() - began
        amplitude[h], converged[h], finest = np.array(values), ok, orbits
    began = time.process_time()
    exact = np.array([certify(orbit, tolerance=EXACT_TOLERANCE).exact.amplitude(RESPONSE)
                      for orbit in finest])
    return Curves(grid, amplitude, exact, converged, seconds, time.process_time() - began)


def report(curves: Curves) -> None:
    for h in curves.amplitude:
        print(f"H = {h}: largest amplitude error {curves.error(h):.1e}, "
              f"{curves.seconds[h]:.2f} s CPU for {len(curves.speeds)} speeds"
              + ("" if curves.converged[h] else " (not every series converged)"))
    print(f"exact orbits (shooting from the H = {max(curves.amplitude)} series): "
          f"{curves.exact_seconds:.2f} s CPU")


def plot(curves: Curves, ax=None):
    """The curves on ``ax`` (a new figure's axes by default), returned."""
    from matplotlib.figure import Figure
    if ax is None:
        ax = Figure(figsize=(7, 4.8), layout="constrained").add_subplot()
    for h, values in curves.amplitude.items():
        ax.plot(curves.speeds, values * 1e6, "-", lw=1.2,
                label=f"harmonic balance, H = {h}: error {curves.error(h):.0e}, "
                      f"{curves.seconds[h]:.2f} s")
    ax.plot(curves.speeds, curves.exact * 1e6, "ko", ms=3,
            label=f"exact orbits (shooting): {curves.exact_seconds:.1f} s")
    ax.set(xlabel="Ω [rpm]", ylabel="amplitude of blade 1's shroud, flapwise [µm]",
           title="Six-blade packet, 3-D elastic shroud faces: what accuracy costs")
    ax.legend(fontsize="small")
    return ax


def main(speeds=12, output=OUTPUT) -> Curves:
    """Compute, print, save the figure in ``output``; returns the ``Curves``."""
    curves = compute(speeds)
    report(curves)
    output = Path(output)
    output.mkdir(parents=True, exist_ok=True)
    plot(curves).figure.savefig(output / "harmonic_balance_packet.png", dpi=110)
    print(f"saved the figure in {output}")
    return curves


if __name__ == "__main__":
    main(output=Path(sys.argv[1]) if len(sys.argv) > 1 else OUTPUT)
