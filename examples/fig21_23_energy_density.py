"""Figs. 21–23: the reference blade's energy density E_ρ at resonance against γ1, Δ1 and α.

Run: python examples/fig21_23_energy_density.py
The scene is the paper's §3.2 setting: q1 = 25 N, Δ1 = Δ2 (K = 1), at the speed where f_d1
crosses f_e = 216.25 Hz (6487.5 rpm with l = 2; the paper prints 6847.5). E_ρ is
normalised by the response of the same blades with the shrouds never touching, so 1 means
no vibration reduction. Saves three figures in examples/output/ and prints the curves.
"""

import math
from pathlib import Path

import numpy as np

from shroudnet import Adaptive, sweep
from shroudnet.figures import curves
from shroudnet.scenes import three_blade_paper

OUTPUT = Path(__file__).resolve().parent / "output"
RESONANCE_RPM = 6487.5
METHOD = Adaptive(rtol=1e-8, atol=1e-12)


def energy_densities(scene_at, values, transient, record):
    result = sweep(scene_at, values, transient=transient, record=record, method=METHOD)
    return np.array([point.energy_density for point in result.points])


def scene(gamma1=2.2, gap=2e-5, alpha=math.pi / 3):
    return three_blade_paper(gamma1=gamma1, gap=gap, alpha=alpha, speed_rpm=RESONANCE_RPM,
                             q1=25.0)


def main(points=16, transient=200, record=50):
    OUTPUT.mkdir(exist_ok=True)
    free = energy_densities(lambda _: scene(gap=1.0), [0.0], transient, record)[0]
    gammas = np.linspace(0.2, 10.0, points)
    by_gap = {f"Δ1 = {gap * 1e3:g} mm": energy_densities(
        lambda g, gap=gap: scene(gamma1=g, gap=gap), gammas, transient, record) / free
        for gap in (5e-6, 2e-5, 1e-4, 1e-3)}
    gaps = np.geomspace(1e-6, 2e-2, points)
    by_size = energy_densities(lambda d: scene(gap=d), gaps, transient, record) / free
    angles = np.linspace(0.1, 1.45, points)
    by_angle = energy_densities(lambda a: scene(alpha=a), angles, transient, record) / free

    curves(gammas, by_gap, xlabel="stiffness ratio γ1", ylabel="E_ρ / E_ρ(no contact)",
           title="Fig. 21: E_ρ against γ1 (α = π/3)").savefig(
        OUTPUT / "fig21_energy_density_gamma1.png", dpi=110)
    figure = curves(gaps * 1e3, {"γ1 = 2.2": by_size}, xlabel="initial gap Δ1 [mm]",
                    ylabel="E_ρ / E_ρ(no contact)", title="Fig. 22: E_ρ against Δ1 (α = π/3)")
    figure.axes[0].set_xscale("log")
    figure.savefig(OUTPUT / "fig22_energy_density_gap.png", dpi=110)
    curves(angles, {"Δ1 = 0.02 mm": by_angle}, xlabel="contact angle α [rad]",
           ylabel="E_ρ / E_ρ(no contact)", title="Fig. 23: E_ρ against α").savefig(
        OUTPUT / "fig23_energy_density_angle.png", dpi=110)

    print(f"E_rho without contact: {free:.4e} m^2 (the normalisation)")
    for label, values in by_gap.items():
        print(f"Fig. 21, {label}: E_rho ratio from {values[0]:.3f} (γ1 = {gammas[0]:g}) "
              f"to {values[-1]:.3f} (γ1 = {gammas[-1]:g}), smallest {values.min():.3f}")
    print("Fig. 22, gap [mm] -> ratio: " + ", ".join(
        f"{d * 1e3:.3g}: {r:.3f}" for d, r in zip(gaps, by_size)))
    best = angles[np.argmin(by_angle)]
    print("Fig. 23, α [rad] -> ratio: " + ", ".join(
        f"{a:.2f}: {r:.3f}" for a, r in zip(angles, by_angle)))
    print(f"smallest E_rho at α = {best:.2f} rad")
    print(f"saved the figures in {OUTPUT}")
    return by_gap, by_size, by_angle


if __name__ == "__main__":
    main()
