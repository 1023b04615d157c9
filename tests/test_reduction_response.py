"""Reduced blades against the full one in forced response through stick, slip and impact.

The scene is ``scenes.beam_pair``'s: two clamped steel beams (80 × 20 × 3 mm, a 20 g
shroud mass at the tip, ζ = 1 % in every mode of every model) whose tip shrouds meet on a
face inclined at 0.5 rad, preloaded (Δ = −2 µm, k_c = 1e5 N/m, Coulomb μ = 0.4), forced in
anti-phase at engine order 2 with q1 = 2 N at the tip, 5 % above the first flap resonance
of the full blade (every model is run at that speed). Here each
blade has 6 Euler–Bernoulli elements (24 degrees of freedom), and the same pair is built
from that blade unreduced (the reference), reduced by Craig–Bampton (boundary: the tip's
v and w, the DOFs the points "shroud" and "load" read) and by modal truncation.

Each reduction is a Ritz basis T, q_full = T q: its forced response with contact is the
full model's up to the flexibility the basis leaves out. The claim checked: the periodic
orbit of the reduced pair reproduces the full pair's, measured as the shroud point's
displacement along the contact normal over one period,

    e = max_t |n · (r_reduced(t) − r_full(t))| / max_t |n · r_full(t)|,

and e falls as modes are added. Both orbits are solved to a residual of 1e-10 of the
state scale, and sampled at the same instants of the excitation period.
"""

import math
from dataclasses import dataclass

import numpy as np
import pytest
import scipy.linalg

import shroudnet as sn
from shroudnet import craig_bampton, modal_truncation, periodic_orbit, scenes
from shroudnet.steady.orbits import ORBIT_TOLERANCE

ELEMENTS = 6
FULL = scenes.beam_pair(elements=ELEMENTS).group.blade("blade1")
#: The full model's DOFs that the points read, beyond the rounding of the load point's
#: shape functions (1e-16): the tip's v and w, as the load sits at the tip.
BOUNDARY = np.flatnonzero((np.abs(np.vstack(list(FULL.points.values()))) > 1e-12).any(axis=0))
FACE = 0.5
NORMAL = np.array([math.cos(FACE), math.sin(FACE)])
#: One speed for every model: 5 % above the full blade's first flap frequency (l = 2).
SPEED_RPM = 1.05 * FULL.frequencies_at(0.0)[0] * 60.0 / 2.0
SAMPLES = 200
#: The switches of one period of every orbit here, in order, on the one interface.
SWITCHES = ((0, "closing"), (0, "sticking"), (0, "breakaway"), (0, "separation"))
CB_MODES = (1, 2, 4)
MT_MODES = (2, 4, 8)


def pair(blade) -> sn.Scene:
    """``scenes.beam_pair`` built from ``blade``, at the full blade's ``SPEED_RPM``."""
    return scenes.beam_pair(blade=blade, speed_rpm=SPEED_RPM)


def state_maps(full_scene, reduced_scene, reduced):
    """E, P on states y = (x, ẋ): E expands the reduced pair's state into the full pair's
    (q_full = T q per blade), P projects back by the mass-weighted least squares
    q = (Tᵀ M T)⁻¹ Tᵀ M q_full, so that P E = I."""
    basis = reduced.basis
    mass = FULL.mass.toarray()
    projection = np.linalg.solve(basis.T @ mass @ basis, basis.T @ mass)
    full_dofs, reduced_dofs = full_scene.dof_matrix(), reduced_scene.dof_matrix()
    expand = np.linalg.solve(full_dofs, scipy.linalg.block_diag(basis, basis) @ reduced_dofs)
    project = np.linalg.solve(reduced_dofs,
                              scipy.linalg.block_diag(projection, projection) @ full_dofs)
    return scipy.linalg.block_diag(expand, expand), scipy.linalg.block_diag(project, project)


def normal_displacement(scene, run) -> np.ndarray:
    """n · r(t) [m] of blade1's shroud at the run's samples."""
    return run.x @ scene.point_rows("blade1", "shroud").T @ NORMAL


@dataclass(frozen=True)
class Reference:
    """The full pair's orbit, sampled ``SAMPLES`` times a period, and n · r(t) [m]."""

    scene: sn.Scene
    orbit: sn.PeriodicOrbit
    response: np.ndarray


def full_orbit(start: sn.PeriodicOrbit, reduced) -> Reference:
    """The full pair's periodic orbit, by Newton (``periodic_orbit``) from the reduced
    pair's orbit ``start`` expanded onto the full model (q_full = T q per blade). Its
    tangent flow (2 × 24 coordinates and their velocities, 96 columns) is carried by one
    exponential a phase, as its laws are linear (``kernel.tangent.carry_phase``)."""
    scene = pair(FULL)
    expand, _ = state_maps(scene, start.scene, reduced)
    orbit = periodic_orbit(scene, guess=np.split(expand @ start.state, 2), history=True,
                           samples_per_period=SAMPLES)
    return Reference(scene, orbit, normal_displacement(scene, orbit.history))


def reduced_response(reduced, reference: Reference):
    """The reduced pair's orbit (from the reference's state projected on the basis) and
    its error e against the reference."""
    scene = pair(reduced)
    _, project = state_maps(reference.scene, scene, reduced)
    guess = project @ reference.orbit.state
    orbit = periodic_orbit(scene, guess=np.split(guess, 2), history=True,
                           samples_per_period=SAMPLES)
    response = normal_displacement(scene, orbit.history)
    error = np.abs(response - reference.response).max() / np.abs(reference.response).max()
    return orbit, float(error)


def craig_bampton_blade(modes):
    return craig_bampton(FULL.mass, FULL.stiffness, BOUNDARY, modes, points=FULL.points,
                         damping_ratios=0.01)


def truncated_blade(modes):
    return modal_truncation(FULL.mass, FULL.stiffness, modes, points=FULL.points,
                            damping_ratios=0.01)


@pytest.fixture(scope="module")
def reference() -> Reference:
    blade = craig_bampton_blade(max(CB_MODES))
    return full_orbit(periodic_orbit(pair(blade)), blade)


def convergence(make, modes, reference):
    """Per basis size, the reduced orbit and its error e; each orbit switches as the full
    one does, and the switch instants of each are returned too, as the largest
    |t_reduced − t_full| over the period's four switches [periods]."""
    errors, timings = [], []
    period = reference.scene.excitation_period
    for count in modes:
        orbit, error = reduced_response(make(count), reference)
        assert orbit.event_sequence == SWITCHES, (count, orbit.event_sequence)
        errors.append(error)
        timings.append(np.abs(orbit.events.time - reference.orbit.events.time).max() / period)
    return errors, timings


def test_the_full_pair_is_a_periodic_orbit_that_closes_sticks_slips_and_separates(reference):
    """The reference: the full pair's orbit, to the residual ``periodic_orbit`` solves to
    (measured 8.0e-11 of the state scale after 2 Newton steps, in 6.5 s on 2 cores),
    closing, sticking, breaking away and separating once a period. The contact makes the
    motion lopsided: the shroud moves 3.5e-5 m along n one way and 6.0e-5 m the other (a
    linear orbit moves as far each way)."""
    assert reference.orbit.residual <= ORBIT_TOLERANCE
    assert reference.orbit.event_sequence == SWITCHES
    assert reference.response.max() < 0.75 * -reference.response.min()   # measured 0.58


def test_craig_bampton_matches_the_full_forced_response_better_with_every_mode(reference):
    """Craig–Bampton with the tip's v, w as boundary and 1, 2, 4 fixed-interface modes
    (3, 4, 6 coordinates a blade, of 24): e measured 2.72e-3, 2.19e-3, 1.62e-4, falling
    with each mode, by 16.8 from 1 to 4 modes. Bounds: e(4) ≤ 5e-4 (3 × measured) and the
    fall ≥ 5. The switch instants of 4 modes lie within 1.8e-4 periods of the full
    model's (bound 6e-4); with 1 and 2 modes 2.4e-3 and 2.7e-3, not monotone."""
    errors, timings = convergence(craig_bampton_blade, CB_MODES, reference)
    assert all(later < earlier for earlier, later in zip(errors, errors[1:])), errors
    assert errors[0] / errors[-1] >= 5.0, errors
    assert errors[-1] <= 5e-4, errors
    assert timings[-1] <= 6e-4, timings


def test_modal_truncation_matches_the_full_forced_response_better_with_every_mode(reference):
    """Modal truncation to the lowest 2, 4, 8 modes (of 24): e measured 5.04e-3, 9.87e-4,
    1.49e-4, falling with each doubling, by 34 from 2 to 8 modes: the modes left out are
    the static flexibility the contact force at the tip feels. Bounds: e(8) ≤ 4.5e-4
    (3 × measured) and the fall ≥ 10. The switch instants of 8 modes lie within 1.7e-4
    periods of the full model's (bound 6e-4); with 2 and 4 modes 1.8e-3 and 3.0e-3, not
    monotone."""
    errors, timings = convergence(truncated_blade, MT_MODES, reference)
    assert all(later < earlier for earlier, later in zip(errors, errors[1:])), errors
    assert errors[0] / errors[-1] >= 10.0, errors
    assert errors[-1] <= 4.5e-4, errors
    assert timings[-1] <= 6e-4, timings
