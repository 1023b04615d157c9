"""The paper's three-blade group: its parameters, resonance, and forces in each contact state.

Run: python examples/paper_scene.py
"""

import math

from shroudnet import Mode, assemble
from shroudnet.scenes import paper_frequency_model, three_blade_paper


def compute(gamma1=2.2, speed_rpm=6000.0, q1=50.0):
    """The paper scene and its assembled forces with both shrouds pressed and stuck."""
    scene = three_blade_paper(gamma1=gamma1, speed_rpm=speed_rpm, q1=q1)
    gap = scene.arrays.gap[0]
    x = [2.0 * gap, 0.0, -2.0 * gap]  # both contacts closed by one gap
    stuck = assemble(scene, 0.25 * scene.excitation_period, x, [0.0, 0.0, 0.0],
                     [Mode.STICK, Mode.STICK])
    return scene, stuck


def main():
    """Print the scene's parameters and forces; returns what ``compute`` gives."""
    scene, stuck = compute()
    model = paper_frequency_model()
    print(f"f_d1(Ω) = sqrt({model.f0:.2f}² + {model.coefficient} (Ω/60)²) Hz")
    for rpm in (5030.0, 6000.0, 6487.5):
        print(f"  {rpm:7.1f} rpm: f_d1 = {model.at(rpm):7.2f} Hz, "
              f"f_e = {scene.excitation.frequency_at(rpm):7.2f} Hz")
    a = scene.arrays
    print(f"k = {a.stiffness[0]:.4g} N/m, k_c = γ1 k = {a.normal_laws[0].stiffness:.4g} N/m, "
          f"T_e = {scene.excitation_period * 1e3:.4f} ms")
    print("both interfaces stuck, x = (2Δ, 0, −2Δ):")
    for e in range(2):
        limit = a.static_mu[e] * stuck.normal_force[e]
        print(f"  interface {e}: N = {stuck.normal_force[e]:.3f} N, static f = "
              f"{stuck.friction_force[e]:.3f} N, limit μ_s N = {limit:.3f} N "
              f"({'holds' if abs(stuck.friction_force[e]) <= limit else 'breaks away'})")
    print(f"  cluster acceleration = {stuck.acceleration[0]:.4g} m/s² "
          f"(angle α = {math.degrees(math.asin(a.sin_angle[0])):.0f}°)")
    return scene, stuck


if __name__ == "__main__":
    main()
