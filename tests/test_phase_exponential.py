"""The tangent flow carried by phases: one matrix exponential from switch to switch.

Between switches, a scene of substructures whose laws all have ``constant_slopes``
(``LinearSpring``, ``ConstantLoad``, ``Coulomb``) has a vector field linear in the state,
so the tangent of a phase is e^{J Δt} (``kernel.tangent.carry_phase``). Checked here:
the exponential against scipy's (an implementation it shares nothing with), and the
monodromy carried by phases against the one integrated with every step, which the same
physics gets from a law without ``constant_slopes`` (``KelvinVoigt`` with no damping is
``LinearSpring``'s force, by other code).
"""

import dataclasses

import numpy as np
import pytest
import scipy.linalg

import shroudnet as sn
from shroudnet import scenes
from contact_laws import Coulomb, Hertz, KelvinVoigt, Regularised
from shroudnet.engine.exponential import SLOTS, exponential
from tests.test_structures import modal_pair
from tests.test_tangent import settled_state


def expm(matrix):
    """e^A by ``exponential``."""
    n = len(matrix)
    work = np.zeros((SLOTS, n, n))
    work[0] = matrix
    exponential(work)
    return work[0]


def oscillators(n, rng, frequency):
    """J = [[0, I], [−K, −C]] of n coupled oscillators with frequencies near
    ``frequency`` [rad/s] and 1 % damping: the Jacobians the kernel exponentiates."""
    stiffness = np.diag((frequency * rng.uniform(0.5, 2.0, n)) ** 2)
    coupling = rng.normal(size=(n, n)) * 0.1 * frequency**2
    stiffness = stiffness + coupling @ coupling.T / n
    damping = 0.02 * np.sqrt(np.diag(stiffness)).mean() * np.eye(n)
    return np.block([[np.zeros((n, n)), np.eye(n)], [-stiffness, -damping]])


@pytest.mark.parametrize("norm", [1e-6, 0.5, 5.0, 80.0, 3000.0])
def test_the_exponential_matches_scipys_at_every_scale(norm):
    """Random matrices of a lightly damped system's spectrum (skew-symmetric, less 1 %
    of the identity), scaled to ‖A‖₁ from below θ₁₃ (no squaring) to 3000 (10
    squarings): e^A within 1e-13 ‖A‖₁ of scipy.linalg.expm, relative to ‖e^A‖ (the
    rounding the squarings let grow, for both)."""
    rng = np.random.default_rng(7)
    for size in (2, 7, 20):
        skew = rng.normal(size=(size, size))
        matrix = skew - skew.T - 0.01 * np.eye(size)
        matrix *= norm / np.abs(matrix).sum(axis=0).max()
        reference = scipy.linalg.expm(matrix)
        error = np.abs(expm(matrix) - reference).max() / np.abs(reference).max()
        assert error <= 1e-13 * max(1.0, norm), (size, error)


def test_the_exponential_of_an_oscillators_jacobian_over_a_period():
    """J Δt of 12 coupled damped oscillators (200–800 Hz) over a period of 200 Hz,
    balanced as ``carry_phase`` balances it (D J D⁻¹, D = diag(I, τ I), τ = 1/ω):
    within 1e-11 of scipy's, relative to its largest entry (measured 3.6e-12; ‖J Δt‖₁
    is 7.5e5, and the growth of its powers saves 8 of the 18 squarings it asks)."""
    rng = np.random.default_rng(3)
    omega = 2 * np.pi * 200.0
    jacobian = oscillators(12, rng, omega)
    balance = np.diag(np.r_[np.ones(12), np.full(12, 1.0 / omega)])
    matrix = balance @ jacobian @ np.linalg.inv(balance) * (2 * np.pi / omega)
    reference = scipy.linalg.expm(matrix)
    assert np.abs(expm(matrix) - reference).max() <= 1e-11 * np.abs(reference).max()


def same_with(scene, normal):
    """``scene`` with every interface's normal law replaced by ``normal``."""
    group = sn.BladeGroup()
    for name in scene.blades:
        group.add_blade(name, scene.group.blade(name))
    for (left, right, interface), (left_point, right_point) in zip(
            scene.group.interfaces, scene.group.edge_points("interface")):
        group.connect((left, left_point), (right, right_point),
                      dataclasses.replace(interface, normal=normal))
    return dataclasses.replace(scene, group=group)


def test_which_scenes_are_linear_between_switches():
    pair = modal_pair()
    assert pair.arrays.linear_phases
    assert not same_with(pair, Hertz(stiffness=2e5)).arrays.linear_phases
    assert not same_with(pair, KelvinVoigt(stiffness=2e5, damping=0.0)).arrays.linear_phases
    assert not modal_pair(friction=Regularised(law=Coulomb(mu=0.5),
                                               velocity=1e-3)).arrays.linear_phases
    blades = scenes.three_blade_paper()
    assert not blades.arrays.linear_phases   # blades keep their own tangent code


@pytest.mark.parametrize("gap", [-2e-6, 2e-6])
def test_the_monodromy_carried_by_phases_matches_the_one_integrated_by_steps(gap):
    """The three-mode pair, preloaded and with a gap, through impacts, stick, breakaway
    and slip: the monodromy from one exponential a phase agrees with the one integrated
    with every step (at rtol 1e-10, to the latter's own error: measured 2e-9 and 6e-9
    on the six-blade packet) within 1e-7 of its largest entry, and so do the
    multipliers."""
    scene = modal_pair(gap=gap)
    stepwise = same_with(scene, KelvinVoigt(stiffness=2e5, damping=0.0))
    y = settled_state(scene, 30)
    counts = sn.simulate(scene, 1, samples_per_period=1, initial=np.split(y, 2)).events.counts
    assert counts["closing"] > 0 and counts["sticking"] > 0, counts
    by_phase = sn.monodromy(scene, 1, initial=np.split(y, 2))
    by_step = sn.monodromy(stepwise, 1, initial=np.split(y, 2))
    assert np.abs(by_phase - by_step).max() <= 1e-7 * np.abs(by_step).max()
    multipliers = np.sort_complex(np.linalg.eigvals(by_phase))
    reference = np.sort_complex(np.linalg.eigvals(by_step))
    assert np.abs(multipliers - reference).max() <= 1e-6 * np.abs(reference).max()
