"""Harmonic balance of contact patches: a face of many points on blades of few modes has
more contact coordinates than directions, and the balance is solved on the directions
(z = y Eᵀ) — checked against the same balance solved on every coordinate, and its
Jacobian in y against central differences of its own residual.

No kernel is compiled here (harmonic balance's slider march only, which the
harmonic-balance tests compile anyway)."""

import numpy as np
import pytest

from shroudnet import harmonic_balance, scenes
from shroudnet.steady.harmonic.balance import Balance, balance_of, orbit_from, solve
from shroudnet.steady.harmonic.condensation import condense
from shroudnet.steady.harmonic.fourier import samples_for
from tests.differences import central_columns

HARMONICS = 5


def patch_packet(**options):
    """Three four-mode blades face to face, faces of four 3-D points: 24 contact
    coordinates, 12 modal coordinates."""
    return scenes.faced_group(blades=3, face_points=4, **options)


def test_a_patch_is_solved_on_its_directions_and_is_the_balance_on_every_coordinate():
    scene = patch_packet()
    balance = balance_of(scene, HARMONICS, 1, samples_for(HARMONICS))
    m, n = balance.model.n_contact_coordinates, balance.model.n_coordinates
    assert balance.reading is not None and balance.shape[1] <= n < m
    assert np.allclose(balance.reading.T @ balance.reading, np.eye(balance.shape[1]),
                       atol=1e-13)
    reduced = harmonic_balance(scene, HARMONICS, stability=False)
    every = Balance(balance.model, balance.basis, condense(balance.model, HARMONICS))
    plain = orbit_from(every, solve(every, None, 1e-12), False)
    assert reduced.converged and plain.converged
    assert reduced.contact_coefficients.shape == plain.contact_coefficients.shape
    scale = np.abs(plain.coefficients).max()
    assert np.abs(reduced.coefficients - plain.coefficients).max() <= 1e-9 * scale
    assert reduced.energy_per_cycle.friction == pytest.approx(
        plain.energy_per_cycle.friction, rel=1e-8)
    # the reduced orbit solves the balance on every coordinate
    residual, _, _ = every.evaluate(reduced.contact_coefficients, False)
    assert np.abs(residual).max() <= 1e-9 * every.scale(reduced.contact_coefficients)


def test_the_jacobian_on_the_directions_is_the_residuals_derivative():
    """At a point off the orbit (every coefficient moved by up to 5 % of the largest),
    ∂R/∂y = I + W (I ⊗ Eᵀ) ∂λ̂/∂z (I ⊗ E) against central differences of R(y), column
    by column."""
    scene = patch_packet()
    balance = balance_of(scene, HARMONICS, 1, samples_for(HARMONICS))
    orbit = harmonic_balance(scene, HARMONICS, stability=False)
    y = balance.unknowns_of(orbit.contact_coefficients)
    y = y + 0.05 * np.abs(y).max() * np.random.default_rng(0).normal(size=y.shape)
    jacobian = balance.evaluate(y, True)[1]
    differences = central_columns(lambda moved: balance.evaluate(moved, False)[0], y,
                                  1e-7 * np.abs(y).max())
    assert np.abs(jacobian - differences).max() <= 1e-6 * np.abs(differences).max()


def test_a_guess_by_every_coordinate_starts_the_solve_on_the_directions():
    scene = patch_packet()
    orbit = harmonic_balance(scene, HARMONICS, stability=False)
    again = harmonic_balance(patch_packet(speed_rpm=2905.0), HARMONICS,
                             guess=orbit.contact_coefficients, stability=False)
    assert again.converged and again.iterations <= 4
    directions = balance_of(scene, HARMONICS, 1, samples_for(HARMONICS)).shape[1]
    with pytest.raises(ValueError, match=r"harmonic_balance\.guess must be .* × 24 finite"):
        harmonic_balance(scene, HARMONICS, guess=np.zeros((3, directions)))
