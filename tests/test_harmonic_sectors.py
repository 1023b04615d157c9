"""Harmonic balance of tuned rings on one sector, the neighbours' harmonics lagging by
2πkl/N, against what shares none of the reduction: the whole ring's own balance
(condensed over every coordinate and every contact) evaluated at the sector's orbit and
solved from scratch, and a linear ring's travelling-wave closed form.

No kernel is compiled here (harmonic balance's slider march only, which the
harmonic-balance tests compile anyway)."""

import dataclasses
import math

import numpy as np
import pytest

import shroudnet as sn
from shroudnet import scenes
from shroudnet.steady.harmonic.balance import balance_of

PAPER = scenes.three_blade_paper()
BLADE = PAPER.group.blade("blade1")
#: The paper's shroud with an elastic stick (harmonic balance refuses rigid stick).
SHROUD = dataclasses.replace(PAPER.group.interfaces[0][2], tangential_stiffness=2e5)


def blade_ring(n, engine_order, gap=SHROUD.gap, speed_rpm=6000.0):
    """The paper's blade and elastic shroud round a ring of ``n``, in ``engine_order``."""
    group = sn.BladeGroup.ring(n, BLADE, dataclasses.replace(SHROUD, gap=gap))
    return sn.Scene(group=group, speed_rpm=speed_rpm, excitation=sn.Excitation(
        engine_order=engine_order, amplitudes=(0.0, PAPER.excitation.amplitudes[1]),
        phases=sn.EngineOrderWave()))


def whole_residual(orbit):
    """max |R| / scale of the whole ring's balance (every contact, condensed over every
    coordinate) at the orbit's contact coefficients, at its samples."""
    whole = balance_of(orbit.scene, orbit.harmonic_count, 1, orbit.samples, symmetry="none")
    z = orbit.contact_coefficients
    residual, _, _ = whole.evaluate(whole.unknowns_of(z), False)
    return float(np.abs(residual).max()) / whole.scale(whole.unknowns_of(z))


#: Rings, and whether their Hill multipliers are compared (an eigenvalue problem of the
#: whole ring: 2 × 24 × 8 × 11 unknowns for the 24 FE sectors, a minute).
RINGS = {
    "6 blades, l = 1, impacts and stick-slip": (lambda: blade_ring(6, 1), True),
    "7 blades, l = 3, impacts and stick-slip": (lambda: blade_ring(7, 3), True),
    "6 FE sectors, l = 2, 3-D elastic faces": (lambda: scenes.faced_group(
        shape="ring", blades=6, face_points=1, engine_order=2), False),
    "24 FE sectors, l = 5, 3-D elastic faces": (lambda: scenes.faced_group(
        shape="ring", blades=24, face_points=1, engine_order=5), False),
}


@pytest.mark.parametrize("name", RINGS)
def test_a_sector_orbit_is_the_whole_rings_orbit(name):
    """The sector's orbit, spread round the ring by the lag, solves the whole ring's
    balance to the tolerance, and is what the whole ring's solve finds at the same samples
    (contacts that stick and slip, open and close: the forces' kinks sampled where the
    whole ring samples them); its energy balances and its Hill multipliers (the whole
    ring's, symmetry-breaking perturbations included) are the whole solve's."""
    build, stability = RINGS[name]
    scene = build()
    sector = sn.harmonic_balance(scene, 5, symmetry="cyclic", stability=stability)
    assert sector.converged and sector.sectors == scene.group.sectors
    assert sector.samples % scene.group.sectors == 0
    assert whole_residual(sector) <= 1e-9
    whole = sn.harmonic_balance(scene, 5, symmetry="none", samples=sector.samples,
                                guess=sector, stability=stability)
    assert whole.converged and whole.sectors == 1
    scale = np.abs(whole.coefficients).max()
    assert np.abs(sector.coefficients - whole.coefficients).max() <= 1e-8 * scale
    energy = sector.energy_per_cycle
    assert abs(energy.excitation - energy.damping - energy.friction - energy.contact) <= \
        1e-8 * energy.excitation
    assert energy.friction == pytest.approx(whole.energy_per_cycle.friction, rel=1e-7)
    if not stability:
        return
    assert len(sector.multipliers) == len(whole.multipliers) == 2 * scene.arrays.n_blades
    assert np.abs(np.sort_complex(sector.multipliers)
                  - np.sort_complex(whole.multipliers)).max() <= 1e-7


def test_every_sector_repeats_the_first_one_its_harmonics_turned_by_the_lag():
    """x_s = Re(X_0,k e^{i(kωt + s θ_k)}), θ_k = 2πkl/N, coordinate by coordinate."""
    n, order = 7, 3
    orbit = sn.harmonic_balance(blade_ring(n, order), 5, stability=False)
    assert orbit.sectors == n  # the default where the ring has the symmetry
    x = orbit.coefficients
    amplitudes = x[1::2] - 1j * x[2::2]  # harmonics 1 … H
    k = np.arange(1, amplitudes.shape[0] + 1)[:, None]
    turned = amplitudes[:, :1] * np.exp(2j * math.pi * k * order * np.arange(n) / n)
    assert np.abs(amplitudes - turned).max() <= 1e-12 * np.abs(amplitudes).max()
    assert np.allclose(x[0], x[0, 0], rtol=0.0, atol=1e-14 * np.abs(x).max())


@pytest.mark.parametrize("order", [1, 2, 3])
def test_a_linear_ring_is_its_travelling_waves_closed_form(order):
    """Contacts preloaded and stuck all through are springs k_c = k_n sin²α + k_t cos²α
    between neighbours: sector 0 answers the wave of engine order l as one mass on
    k + 2 k_c (1 − cos 2πl/N), |X| = q / |k_eff − ω² m + iωc|."""
    n = 6
    scene = blade_ring(n, order, gap=-1e-3)
    orbit = sn.harmonic_balance(scene, 3, stability=False)
    assert orbit.sectors == n and orbit.smooth
    a = scene.arrays
    m, c, k = a.mass[0], a.damping_matrix()[0, 0], a.stiffness_matrix()[0, 0]
    coupling = SHROUD.normal.stiffness * math.sin(SHROUD.angle) ** 2 \
        + SHROUD.tangential_stiffness * math.cos(SHROUD.angle) ** 2
    omega = scene.excitation_circular_frequency
    stiffness = k + 2.0 * coupling * (1.0 - math.cos(2.0 * math.pi * order / n))
    expected = PAPER.excitation.amplitudes[1] / abs(stiffness - omega ** 2 * m + 1j * omega * c)
    assert orbit.amplitude(scene.blades[0]) == pytest.approx(expected, rel=1e-10)


def test_a_guess_from_the_whole_ring_starts_the_sector_and_back():
    """An orbit's contact coefficients are the whole ring's either way: each solve takes
    the other's as its guess and converges at once."""
    scene = blade_ring(6, 1)
    sector = sn.harmonic_balance(scene, 5, stability=False)
    whole = sn.harmonic_balance(scene, 5, symmetry="none", guess=sector,
                                samples=sector.samples, stability=False)
    again = sn.harmonic_balance(scene, 5, guess=whole, stability=False)
    assert whole.converged and again.converged and again.iterations <= 1
    assert np.abs(again.coefficients - sector.coefficients).max() <= \
        1e-9 * np.abs(sector.coefficients).max()


def test_a_branch_of_a_tuned_ring_is_solved_on_one_sector():
    """harmonic_continuation takes the symmetry too: every orbit of the branch is a
    sector's and solves the whole ring's balance."""
    branch = sn.harmonic_continuation(lambda rpm: blade_ring(6, 1, speed_rpm=rpm), 5900.0,
                                      6000.0, 3, max_step=0.3, stability=False,
                                      symmetry="cyclic")
    assert branch.parameter[-1] == pytest.approx(6000.0)
    for orbit in branch.orbits:
        assert orbit.sectors == 6 and whole_residual(orbit) <= 1e-8


def test_what_breaks_the_symmetry_is_refused_by_name():
    packet = scenes.jenkins_chain()
    with pytest.raises(ValueError, match="harmonic_balance: symmetry='cyclic' does not hold"):
        sn.harmonic_balance(packet, 3, symmetry="cyclic")
    with pytest.raises(ValueError, match="solves period-1 orbits"):
        sn.harmonic_balance(blade_ring(6, 1), 3, periods=2, symmetry="cyclic")
    with pytest.raises(ValueError, match="harmonic_balance.symmetry"):
        sn.harmonic_balance(blade_ring(6, 1), 3, symmetry="sectors")
