"""Figs. 21–23: the reference blade's energy density E_ρ at resonance against γ1, Δ1 and α.

Run: python examples/fig21_23_energy_density.py [OUTPUT_FOLDER]
The scene is the paper's §3.2 setting: q1 = 25 N, Δ1 = Δ2 (K = 1), at the speed where f_d1
crosses f_e = 216.25 Hz (6487.5 rpm with l = 2; the paper prints 6847.5). E_ρ is
normalised by the response of the same blades with the shrouds never touching, so 1 means
no vibration reduction. Saves three figures in OUTPUT_FOLDER (default examples/output/)
and prints the curves.
"""

import math
import sys
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from shroudnet import Adaptive, sweep
from shroudnet.scenes import three_blade_paper

OUTPUT = Path(__file__).resolve().parent / "output"
RESONANCE_RPM = 6487.5
METHOD = Adaptive(rtol=1e-8, atol=1e-12)
#: The initial gaps of Fig. 21's curves [m].
FIG21_GAPS = (5e-6, 2e-5, 1e-4, 1e-3)
#: A gap the blades never close [m]: the normalisation's contact-free response.
NO_CONTACT = 1.0


@dataclass(frozen=True)
class EnergyDensities:
    """E_ρ / E_ρ(no contact) of the reference blade along each figure's parameter."""

    free: float                     # E_ρ without contact [m²]
    gammas: np.ndarray              # Fig. 21's stiffness ratios γ1
    by_gap: dict[str, np.ndarray]   # Fig. 21: one curve over ``gammas`` per initial gap
    gaps: np.ndarray                # Fig. 22's initial gaps Δ1 [m]
    by_size: np.ndarray             # Fig. 22: over ``gaps``
    angles: np.ndarray              # Fig. 23's contact angles α [rad]
    by_angle: np.ndarray            # Fig. 23: over ``angles``


def energy_densities(scene_at, values, transient, record):
    result = sweep(scene_at, values, transient=transient, record=record, method=METHOD)
    return np.array([point.energy_density for point in result.points])


def scene(gamma1=2.2, gap=2e-5, alpha=math.pi / 3):
    return three_blade_paper(gamma1=gamma1, gap=gap, alpha=alpha, speed_rpm=RESONANCE_RPM,
                             q1=25.0)


def compute(points=16, transient=200, record=50) -> EnergyDensities:
    """E_ρ ratios at ``points`` values of γ1 (per gap of Fig. 21), of Δ1 and of α."""
    free = energy_densities(lambda _: scene(gap=NO_CONTACT), [0.0], transient, record)[0]
    gammas = np.linspace(0.2, 10.0, points)
    by_gap = {f"Δ1 = {gap * 1e3:g} mm": energy_densities(
        lambda g, gap=gap: scene(gamma1=g, gap=gap), gammas, transient, record) / free
        for gap in FIG21_GAPS}
    gaps = np.geomspace(1e-6, 2e-2, points)
    by_size = energy_densities(lambda d: scene(gap=d), gaps, transient, record) / free
    angles = np.linspace(0.1, 1.45, points)
    by_angle = energy_densities(lambda a: scene(alpha=a), angles, transient, record) / free
    return EnergyDensities(free=free, gammas=gammas, by_gap=by_gap, gaps=gaps,
                           by_size=by_size, angles=angles, by_angle=by_angle)


def save_figures(result: EnergyDensities, output: Path) -> None:
    """Figs. 21, 22 and 23, saved in ``output``."""
    from shroudnet.front.figures import curves
    output = Path(output)
    output.mkdir(parents=True, exist_ok=True)
    curves(result.gammas, result.by_gap, xlabel="stiffness ratio γ1",
           ylabel="E_ρ / E_ρ(no contact)", title="Fig. 21: E_ρ against γ1 (α = π/3)").savefig(
        output / "fig21_energy_density_gamma1.png", dpi=110)
    figure = curves(result.gaps * 1e3, {"γ1 = 2.2": result.by_size},
                    xlabel="initial gap Δ1 [mm]", ylabel="E_ρ / E_ρ(no contact)",
                    title="Fig. 22: E_ρ against Δ1 (α = π/3)")
    figure.axes[0].set_xscale("log")
    figure.savefig(output / "fig22_energy_density_gap.png", dpi=110)
    curves(result.angles, {"Δ1 = 0.02 mm": result.by_angle}, xlabel="contact angle α [rad]",
           ylabel="E_ρ / E_ρ(no contact)", title="Fig. 23: E_ρ against α").savefig(
        output / "fig23_energy_density_angle.png", dpi=110)


def print_curves(result: EnergyDensities) -> None:
    gammas, angles = result.gammas, result.angles
    print(f"E_rho without contact: {result.free:.4e} m^2 (the normalisation)")
    for label, values in result.by_gap.items():
        print(f"Fig. 21, {label}: E_rho ratio from {values[0]:.3f} (γ1 = {gammas[0]:g}) "
              f"to {values[-1]:.3f} (γ1 = {gammas[-1]:g}), smallest {values.min():.3f}")
    print("Fig. 22, gap [mm] -> ratio: " + ", ".join(
        f"{d * 1e3:.3g}: {r:.3f}" for d, r in zip(result.gaps, result.by_size)))
    print("Fig. 23, α [rad] -> ratio: " + ", ".join(
        f"{a:.2f}: {r:.3f}" for a, r in zip(angles, result.by_angle)))
    print(f"smallest E_rho at α = {angles[np.argmin(result.by_angle)]:.2f} rad")


def main(points=16, transient=200, record=50, output=OUTPUT):
    """Compute, save the figures in ``output`` and print the curves; returns the result."""
    result = compute(points, transient, record)
    save_figures(result, output)
    print_curves(result)
    print(f"saved the figures in {output}")
    return result


if __name__ == "__main__":
    main(output=Path(sys.argv[1]) if len(sys.argv) > 1 else OUTPUT)
