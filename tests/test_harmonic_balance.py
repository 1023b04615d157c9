"""Harmonic balance against what it approximates: the closed-form response of linear
structures, exact orbits by shooting (their amplitudes, energies and Floquet
multipliers), central differences of its own contact forces, and the refusals of what
it does not carry.

The exact orbits are found by ``periodic_orbit`` on kernels the suite compiles anyway
(blades with their tangent flow, as ``test_orbits``; elastic contacts on coordinates
with their tangent flow, as ``test_elastic_tangent``); harmonic balance itself compiles
only its slider march (a few seconds, once)."""

import math

import numpy as np
import pytest
import scipy.linalg

import shroudnet as sn
from contact_laws import (
    Coulomb,
    Hertz,
    KelvinVoigt,
    LinearSpring,
    Regularised,
    Stribeck,
)
from shroudnet.steady.harmonic.aft import contact_forces
from shroudnet.steady.harmonic.balance import balance_of
from shroudnet.steady.harmonic.fourier import samples_for
from shroudnet.studies.harmonic_precision import harmonic_precision
from tests.differences import central_columns
from tests.laws import CubicSpring, RationalWeakening

EXACT = sn.Adaptive(rtol=1e-12)


# -- linear structures: the closed form at any number of harmonics ------------------------

def open_pair(harmonics=(3.0, 60.0, 10.0, 4.0)):
    """The blade pair with a gap no motion closes, forced by a constant and three
    harmonics."""
    group = sn.BladeGroup().add_blade("a", sn.Blade(mass=0.1, damping=2.0, stiffness=1e5))
    group.add_blade("b", sn.Blade(mass=0.3, damping=3.0, stiffness=2e5)).add_fixed("disc")
    group.connect("b", "disc", sn.Coupling(stiffness=5e4, damping=0.5))
    group.connect("a", "b", sn.Interface(gap=1.0, angle=0.6, normal=LinearSpring(stiffness=3e5)))
    return sn.Scene(group=group, speed_rpm=6000.0, excitation=sn.Excitation(
        engine_order=1, amplitudes=harmonics, phases=sn.ExplicitPhases((0.3, 2.0))))


def closed_form(scene, times, harmonics):
    """x(t) = K⁻¹ s q₀ + Σ_{n ≤ H} Im(X_n e^{inωt}), (K − n²ω²M + inωC) X_n = s q_n e^{inφ}."""
    a = scene.arrays
    mass, damping, stiffness = np.diag(a.mass), a.damping_matrix(), a.stiffness_matrix()
    omega = a.excitation_frequency
    x = np.tile(np.linalg.solve(stiffness, a.harmonic_amplitudes[0]), (len(times), 1))
    for n in range(1, min(harmonics, a.harmonic_amplitudes.shape[0] - 1) + 1):
        load = a.harmonic_amplitudes[n] * np.exp(1j * a.harmonic_phases[n])
        amplitude = np.linalg.solve(stiffness - (n * omega) ** 2 * mass
                                    + 1j * n * omega * damping, load)
        x = x + np.imag(np.outer(np.exp(1j * n * omega * times), amplitude))
    return x


@pytest.mark.parametrize("harmonics", [1, 2, 3, 8])
def test_a_linear_structure_is_its_closed_form_response_at_any_number_of_harmonics(
        harmonics):
    scene = open_pair()
    orbit = sn.harmonic_balance(scene, harmonics)
    times = np.linspace(0.0, scene.excitation_period, 17)
    expected = closed_form(scene, times, harmonics)
    assert orbit.converged
    # Measured: 1.1e-16 of the motion at every H.
    assert np.abs(orbit.at(times) - expected).max() <= 1e-13 * np.abs(expected).max()
    velocity = np.gradient(closed_form(scene, times, harmonics), times, axis=0)
    assert np.sign(orbit.at(times, 1)[5, 0]) == np.sign(velocity[5, 0])
    energy = orbit.energy_per_cycle
    assert energy.excitation == pytest.approx(energy.damping, rel=1e-12)
    assert energy.friction == energy.contact == 0.0


def test_a_scene_without_contacts_is_its_closed_form_and_its_branch_runs():
    """No contact coordinates at all: the balance has no unknowns, the orbit is the
    linear response |X| = q/|k − ω²m + iωc|, and a branch follows it."""
    group = sn.BladeGroup().add_blade("a", sn.Blade(mass=0.1, damping=2.0, stiffness=1e5))

    def scene_at(rpm):
        return sn.Scene(group=group, speed_rpm=rpm, excitation=sn.Excitation(
            engine_order=1, amplitudes=(0.0, 10.0), phases=sn.ExplicitPhases((0.0,))))

    orbit = sn.harmonic_balance(scene_at(6000.0), 3)
    omega = scene_at(6000.0).excitation_circular_frequency
    assert orbit.converged and orbit.contact_coefficients.shape == (7, 0)
    assert orbit.amplitude("a") == pytest.approx(
        10.0 / abs(1e5 - 0.1 * omega ** 2 + 2j * omega), rel=1e-12)
    branch = sn.harmonic_continuation(scene_at, 5000.0, 6000.0, 3, stability=False)
    assert branch.parameter[-1] == pytest.approx(6000.0)


def test_an_orbit_of_two_periods_of_a_linear_structure_is_its_one_period_orbit():
    """periods=2: the series of ω/2, whose odd harmonics a linear structure leaves at 0."""
    scene = open_pair()
    twice = sn.harmonic_balance(scene, 6, periods=2)
    once = sn.harmonic_balance(scene, 3)
    times = np.linspace(0.0, 2.0 * scene.excitation_period, 23)
    assert twice.period == pytest.approx(2.0 * once.period)
    assert np.abs(twice.at(times) - once.at(times)).max() <= 1e-13 * np.abs(once.at(times)).max()
    assert np.abs(twice.coefficients[1::4]).max() <= 1e-15 * np.abs(once.coefficients).max()
    assert twice.energy_per_cycle.damping == pytest.approx(once.energy_per_cycle.damping)


def test_a_linear_structures_hill_multipliers_are_its_closed_form_floquet_multipliers():
    """Without contact the orbit's multipliers are e^{λT} of the free structure's
    eigenvalues λ (the state matrix [[0, I], [−M⁻¹K, −M⁻¹C]]), at any H."""
    scene = open_pair()
    a = scene.arrays
    inverse = np.diag(1.0 / a.mass)
    state = np.block([[np.zeros((2, 2)), np.eye(2)],
                      [-inverse @ a.stiffness_matrix(), -inverse @ a.damping_matrix()]])
    expected = np.exp(np.linalg.eigvals(state) * scene.excitation_period)
    for harmonics in (1, 4):
        found = sn.harmonic_balance(scene, harmonics).multipliers
        assert len(found) == 4
        # Measured: 3e-15.
        assert max(np.abs(expected - mu).min() for mu in found) <= 1e-12


def steady_response_in_dofs(scene):
    """X of q = Im(X e^{iωt}), by every blade's own degrees of freedom q, for a
    substructure packet whose contacts never close: (K − ω²M + iωC) X = s q₁ e^{iφ} b with
    its own M, C, K(Ω) and load vector b (``Substructure.matrices_at``)."""
    omega = scene.arrays.excitation_frequency
    q1 = scene.excitation.amplitudes[1]
    blocks = []
    for name, phase in zip(scene.blades, scene.excitation.blade_phases(len(scene.blades))):
        blade = scene.group.blade(name)
        own = blade.matrices_at(scene.speed_rpm)
        load = blade.excitation_scale * q1 * np.exp(1j * phase) * blade.load_vector
        blocks.append(np.linalg.solve(own.stiffness - omega**2 * own.mass
                                      + 1j * omega * own.damping, load))
    return np.concatenate(blocks)


def test_a_linear_substructure_packet_is_its_closed_form_response():
    """Modal blades (three modes each), contacts that never close: the series is, by
    every blade's own degrees of freedom q, its steady response written from its own
    matrices (``steady_response_in_dofs``): q = Im(X e^{iωt}) = Im X cos ωt + Re X sin ωt;
    and the frequency response's (an independent solve) at the first harmonic."""
    scene = sn.scenes.modal_packet(blades=3, gap=1.0, friction=None)
    orbit = sn.harmonic_balance(scene, 2)
    omega = scene.arrays.excitation_frequency
    expected = steady_response_in_dofs(scene)
    scale = np.abs(expected).max()
    # Measured: 2e-16 of the motion.
    assert np.abs(orbit.coefficients[1] - expected.imag).max() <= 1e-13 * scale
    assert np.abs(orbit.coefficients[2] - expected.real).max() <= 1e-13 * scale
    assert np.abs(orbit.coefficients[[0, 3, 4]]).max() <= 1e-15 * scale
    response = sn.frequency_response(scene, [1.0 / scene.excitation_period]).response[0]
    assert np.abs(response - expected).max() <= 1e-13 * scale
    # its state at t = 0, q(0) = Im X and q̇(0) = ω Re X, is what periodic_orbit takes
    displacement, velocity = orbit.initial
    assert np.abs(displacement - expected.imag).max() <= 1e-13 * scale
    assert np.abs(velocity - omega * expected.real).max() <= 1e-13 * omega * scale
    # the contact coordinates z_e = B_e q, B_e orthonormal over q on the rows each face's
    # laws read (n·r and t·r of its points' relative displacement r): |z_e| of every
    # coefficient is that of q's projection on those rows
    for e, ((left, right, face), (point_a, point_b)) in enumerate(
            zip(scene.group.interfaces, scene.group.edge_points("interface"))):
        relative = scene.point_rows(left, point_a) - scene.point_rows(right, point_b)
        rows = np.vstack([face.normal_direction, face.tangent_directions]) @ relative
        projector = rows.T @ np.linalg.solve(rows @ rows.T, rows)
        z = orbit.contact_coefficients[:, 2 * e:2 * e + 2]
        np.testing.assert_allclose(np.linalg.norm(z, axis=1),
                                   np.linalg.norm(orbit.coefficients @ projector, axis=1),
                                   rtol=0.0, atol=1e-13 * scale)


def test_a_branch_of_the_linear_substructure_packet_is_its_closed_form_at_every_speed():
    """Over the speed the engine's modal coordinates change with K(Ω); the branch's
    orbits are by the blades' own q all the same, each its closed form."""
    branch = sn.harmonic_continuation(
        lambda rpm: sn.scenes.modal_packet(blades=3, gap=1.0, friction=None,
                                           speed_rpm=rpm), 2950.0, 3050.0, 1,
        max_step=0.5, stability=False)
    assert branch.ended == "reached p = 3050" and branch.parameter[0] == 2950.0
    for orbit in branch.orbits:
        expected = steady_response_in_dofs(orbit.scene)
        # Measured: 6e-15 of the motion (0.76 when the series was of η).
        assert np.abs(orbit.coefficients[1] - expected.imag).max() <= 1e-12 * np.abs(
            expected).max()
        assert np.abs(orbit.coefficients[2] - expected.real).max() <= 1e-12 * np.abs(
            expected).max()


# -- convergence to the exact orbit as H grows ---------------------------------------------

PROBLEMS = {
    "2-DOF Jenkins chain": sn.scenes.jenkins_chain,
    "modal blade pair, 2-D Jenkins shroud": sn.scenes.modal_pair,
    "mass against a unilateral stop": sn.scenes.mass_on_stop,
}


@pytest.fixture(scope="module", params=list(PROBLEMS))
def study(request):
    return request.param, harmonic_precision(PROBLEMS[request.param](), (1, 3, 5, 9, 15, 25),
                                             repeats=1)


def test_the_amplitude_and_energy_converge_to_the_exact_orbits_as_harmonics_grow(study):
    """Measured (relative amplitude / energy per cycle errors at H = 5, 25; fitted rate):
    the chain 3.2e-4 / 8.0e-4 and 1.8e-6 / 2.2e-6, H^-3.3; the modal pair (read by its
    blades' own q) 5.3e-5 / 2.4e-5 and 1.7e-7 / 1.2e-6, H^-3.4 and H^-1.8; the stop,
    whose contact force has a kink every cycle, 2.9e-3 / 4.3e-2 and 7.5e-8 / 4.3e-4."""
    name, found = study
    final = {h: k for k, h in enumerate(found.harmonics)}
    amplitude, energy = found.amplitude_error, found.energy_error
    assert amplitude[final[25]] <= amplitude[final[5]] / 10
    assert energy[final[25]] <= energy[final[5]] / 10
    if "stop" in name:
        assert amplitude[final[25]] <= 1e-4 and energy[final[25]] <= 1e-3
    else:  # friction: no floor from aliasing, 1e-5 at H = 25
        assert amplitude[final[25]] <= 1e-5 and energy[final[25]] <= 1e-5
        assert found.rate() <= -2.0


def test_the_samples_grow_faster_than_the_harmonics():
    """The aliasing of a kinked force falls as 1/N², the series' error as H⁻³: N grows
    as H^{3/2}, so that sampling never caps the accuracy."""
    assert samples_for(7) == 149 and samples_for(25) == 1000
    assert all(samples_for(h) > 2 * h for h in range(0, 200))


# -- Hill's multipliers against the exact Floquet multipliers ------------------------------

def test_hill_multipliers_converge_to_the_exact_ones_where_the_orbit_is_smooth():
    """A mass pressed on a Hertz stop that never opens: the force is smooth, and Hill's
    multipliers converge to the exact orbit's exponentially (measured: 8.6e-4 at H = 1,
    6.4e-9 at H = 3, 1.2e-11 at H = 5)."""
    scene = sn.scenes.mass_on_stop(gap=-2e-3, normal=Hertz(stiffness=1e6), q1=2.0,
                                   frequency=31.0)
    errors = []
    for harmonics in (1, 3, 5):
        certificate = sn.certify(sn.harmonic_balance(scene, harmonics), method=EXACT,
                                 tolerance=1e-12)
        assert not certificate.exact.switches  # closed throughout
        assert certificate.harmonic.smooth
        errors.append(certificate.multiplier_error)
    assert errors[0] > 1e-5 and errors[1] <= 1e-7 and errors[2] <= 1e-9


def test_hill_multipliers_of_a_slipping_jenkins_contact_are_the_open_structures():
    """Where Hill's method fails: a slipping slider forgets a constant offset, so the
    periodic Jacobian of its force has no column for the mean, and e^{λt} φ with (K + λC
    + λ²M) φ = 0 solves Hill's problem exactly: it returns the open structure's
    multipliers at every H, while the exact orbit's differ (by 0.35 here)."""
    scene = sn.scenes.jenkins_chain()
    a = scene.arrays
    inverse = np.diag(1.0 / a.mass)
    free = np.block([[np.zeros((2, 2)), np.eye(2)],
                     [-inverse @ a.stiffness_matrix(), -inverse @ a.damping_matrix()]])
    open_multipliers = np.exp(np.linalg.eigvals(free) * scene.excitation_period)
    certificate = sn.certify(sn.harmonic_balance(scene, 9))
    assert not certificate.harmonic.smooth  # it sticks and slips: the orbit says so
    hill = certificate.harmonic.multipliers
    assert max(np.abs(open_multipliers - mu).min() for mu in hill) <= 1e-9
    assert certificate.multiplier_error > 0.1


# -- the certificate ---------------------------------------------------------------------

def test_a_certificate_is_the_exact_orbit_and_the_series_errors():
    orbit = sn.harmonic_balance(sn.scenes.jenkins_chain(), 9)
    certificate = sn.certify(orbit, method=EXACT, tolerance=1e-11)
    exact = sn.periodic_orbit(orbit.scene, guess=orbit.initial, method=EXACT,
                              tolerance=1e-11)
    assert np.abs(certificate.exact.state - exact.state).max() <= 1e-9 * np.abs(
        exact.state).max()
    amplitudes = [(exact.amplitude(r), orbit.amplitude(r)) for r in ("a", "b")]
    largest = max(a for a, _ in amplitudes)
    assert certificate.amplitude_error == pytest.approx(
        max(abs(a - b) for a, b in amplitudes) / largest, rel=1e-6)
    assert certificate.energy_error == pytest.approx(
        abs(orbit.energy_per_cycle.dissipated - exact.energy_per_cycle.dissipated)
        / exact.energy_per_cycle.dissipated, rel=1e-5)
    assert 1e-6 < certificate.amplitude_error < 1e-3


# -- the contact forces' Jacobian against central differences ------------------------------

def pair_with(normal, friction, tangential_stiffness=None, gap=-1e-6):
    """Two modal blades whose shrouds meet at a 0.6 rad face with the given laws (a face's
    plane with elastic stick, one direction otherwise)."""
    blade = sn.scenes.modal_blade(dimensions=3 if tangential_stiffness else 2)
    n = (math.cos(0.6), math.sin(0.6))
    if tangential_stiffness:
        face = dict(normal_direction=(*n, 0.0),
                    tangent_directions=((-n[1], n[0], 0.0), (0.0, 0.0, 1.0)),
                    tangential_stiffness=tangential_stiffness)
    else:
        face = dict(normal_direction=n, tangent_direction=(-n[1], n[0]))
    group = sn.BladeGroup().add_blade("blade1", blade).add_blade("blade2", blade)
    group.connect(("blade1", "shroud"), ("blade2", "shroud"),
                  sn.Interface(gap=gap, normal=normal, friction=friction, **face))
    return sn.Scene(group=group, speed_rpm=3100.0, excitation=sn.Excitation(
        engine_order=4, amplitudes=(0.0, 3.0), phases=sn.AntiPhase()))


JACOBIAN_CASES = {
    "1-D Jenkins, constant load": lambda: sn.scenes.jenkins_chain(),
    "2-D Jenkins, constant load": lambda: sn.scenes.modal_pair(),
    "2-D Jenkins, spring load, opening and closing": lambda: sn.scenes.modal_packet(
        blades=2, tangential_stiffness=3e4, gap=-1e-6, q1=3.0, speed_rpm=3100.0,
        blades_on_disc=8),
    "Hertz, regularised Stribeck": lambda: pair_with(
        Hertz(stiffness=3e8), Regularised(law=Stribeck(mu_static=0.4, mu_kinetic=0.25,
                                                       stribeck_velocity=0.05),
                                          velocity=1e-3)),
    "Kelvin-Voigt, 2-D Jenkins": lambda: pair_with(KelvinVoigt(stiffness=1e5, damping=2.0),
                                                   Coulomb(mu=0.3), tangential_stiffness=3e4),
    "user laws, differenced gradients": lambda: pair_with(
        CubicSpring(linear=1e5, cubic=1e15),
        Regularised(law=RationalWeakening(mu_static=0.4, mu_kinetic=0.2, speed=0.01),
                    velocity=1e-3)),
}


@pytest.mark.parametrize("case", list(JACOBIAN_CASES))
def test_the_contact_forces_jacobian_agrees_with_central_differences(case):
    """At a point off the orbit (every coefficient moved by up to 5 % of the largest),
    where contacts stick, slip, open and close: ∂λ̂/∂z against central differences of the
    forces the same code computes (measured: 1e-10 to 1e-9 of the largest entry)."""
    scene = JACOBIAN_CASES[case]()
    orbit = sn.harmonic_balance(scene, 5, stability=False)
    assert orbit.converged
    balance = balance_of(scene, 5, 1, orbit.samples)
    rng = np.random.default_rng(0)
    z = orbit.contact_coefficients
    z = z + 0.05 * np.abs(z).max() * rng.normal(size=z.shape)
    jacobian = contact_forces(balance.model, balance.basis, z, True).jacobian
    step = 1e-7 * np.abs(z).max()
    differences = central_columns(lambda moved: contact_forces(
        balance.model, balance.basis, moved, False).coefficients, z, step)
    assert np.abs(jacobian - differences).max() <= 1e-6 * np.abs(differences).max()
    # and the balance's, I + W ∂λ̂/∂z, against differences of R(z) = z − z_lin + W λ̂(z)
    balance_jacobian = balance.evaluate(z, True)[1]
    residuals = central_columns(lambda moved: balance.evaluate(moved, False)[0], z, step)
    assert np.abs(balance_jacobian - residuals).max() <= 1e-6 * np.abs(residuals).max()


# -- what every orbit satisfies ---------------------------------------------------------------

def own_matrices(scene):
    """The nodes' own M and C over their degrees of freedom q, stacked in ``blades``
    order (block-diagonal: the scene has no couplings)."""
    own = [scene.group.blade(name).matrices_at(scene.speed_rpm) for name in scene.blades]
    return (scipy.linalg.block_diag(*(m.mass for m in own)),
            scipy.linalg.block_diag(*(m.damping for m in own)))


def test_the_energy_per_cycle_balances_and_the_outputs_read_the_series():
    """The modal pair's orbit read by its nodes' own degrees of freedom q: the energies
    and the kinetic peak from their own M, C and load vectors, the friction's work from
    the face's geometry (its points' rows over q)."""
    orbit = sn.harmonic_balance(sn.scenes.modal_pair(), 9)
    scene = orbit.scene
    energy = orbit.energy_per_cycle
    # the balance holds in every harmonic kept: ∫ẋ·(excitation − damping − contacts) = 0
    assert energy.excitation == pytest.approx(energy.damping + energy.friction
                                              + energy.contact, rel=1e-9)
    times = np.linspace(0.0, orbit.period, 20001)
    response = orbit.response(("blade1", "shroud", 0), times)
    assert orbit.amplitude(("blade1", "shroud", 0)) == pytest.approx(0.5 * np.ptp(response),
                                                                     rel=1e-7)
    harmonic = orbit.harmonics(("blade1", "shroud", 0), 3)
    samples = response[:-1]
    first = 2.0 * np.abs(np.fft.rfft(samples)[1]) / len(samples)
    assert harmonic.amplitudes[1] == pytest.approx(first, rel=1e-9)
    mass, damping = own_matrices(scene)
    velocity = orbit.at(times, 1)
    kinetic = 0.5 * np.einsum("ti,ij,tj->t", velocity, mass, velocity)
    assert orbit.kinetic_peak == pytest.approx(kinetic.max(), rel=1e-7)
    assert orbit.kinetic_peak >= kinetic.max()
    assert orbit.equivalent_damping == pytest.approx(
        energy.dissipated / (4.0 * math.pi * orbit.kinetic_peak))
    # the damping's and the excitation's work, ∫q̇ᵀCq̇ and ∫Σ Q_i b_i·q̇_i over the period
    # (the rectangle rule on a periodic series of degree 9 is exact)
    step = orbit.period / 400
    at = np.arange(400) * step
    velocity = orbit.at(at, 1)
    assert step * np.einsum("ti,ij,tj->", velocity, damping, velocity) == pytest.approx(
        energy.damping, rel=1e-9)
    omega, q1 = orbit.frequency, scene.excitation.amplitudes[1]
    work = 0.0
    for name, phase in zip(scene.blades, scene.excitation.blade_phases(2)):
        blade = scene.group.blade(name)
        load = blade.excitation_scale * q1 * np.sin(omega * at + phase)
        work += step * load @ (velocity @ scene.dof_rows(name).T @ blade.load_vector)
    assert work == pytest.approx(energy.excitation, rel=1e-9)
    # the contact's force in time: pressed by its constant load, within its friction limit
    forces = orbit.contact_forces()
    assert forces.normal.shape == (orbit.samples, 1)
    np.testing.assert_allclose(forces.normal, 2.0)
    assert np.hypot(*forces.friction[:, 0].T).max() <= 0.3 * 2.0 * (1.0 + 1e-12)
    # its work over the period, f·ṙ_t summed over the samples, is the friction's energy:
    # ṙ = (R_a − R_b) q̇ of its two points, along its tangents
    face = scene.group.interfaces[0][2]
    relative = scene.point_rows("blade1", "shroud") - scene.point_rows("blade2", "shroud")
    tangents = np.asarray(face.tangent_directions) @ relative
    rate = orbit.at(orbit.times, 1) @ tangents.T
    work = np.sum(forces.friction[:, 0] * rate) * orbit.period / orbit.samples
    assert work == pytest.approx(energy.friction, rel=1e-9)
    # and its slip along t₁, t₁·r, has the harmonics slip_harmonics reads off the series
    slip = np.fft.rfft(orbit.at(at) @ tangents[0]) / len(at)
    found = orbit.slip_harmonics(0, 3)
    np.testing.assert_allclose(found.amplitudes, [slip[0].real, *(2.0 * np.abs(slip[1:4]))],
                               rtol=1e-9, atol=1e-12 * np.abs(slip).max())


def test_an_orbit_that_does_not_converge_says_so():
    orbit = sn.harmonic_balance(sn.scenes.mass_on_stop(), 15, iterations=1)
    assert not orbit.converged and orbit.residual > orbit.tolerance
    assert "stopped" in orbit.message


# -- continuation -------------------------------------------------------------------------

def test_a_branch_follows_the_chain_across_its_resonance_and_its_orbits_are_the_points():
    branch = sn.harmonic_continuation(lambda hz: sn.scenes.jenkins_chain(frequency=hz), 9.0,
                                      11.0, 5, max_step=0.1, stability=False)
    assert branch.ended == "reached p = 11" and len(branch) > 10
    assert np.all(np.diff(branch.parameter) > 0.0)
    k = len(branch) // 2
    alone = sn.harmonic_balance(sn.scenes.jenkins_chain(frequency=branch.parameter[k]), 5,
                                guess=branch.orbits[k])
    assert alone.amplitude("a") == pytest.approx(branch.amplitude("a")[k], rel=1e-9)
    assert all(orbit.converged for orbit in branch.orbits)


def test_a_softening_contact_folds_the_branch_and_the_fold_is_the_exact_orbits_fold():
    """A mass pressed on a Hertz stop (closed throughout: a smooth, softening contact)
    across its resonance: the branch turns back, the fold is located where Hill's
    multiplier is +1, and the exact orbit there (shooting from the fold's series) has a
    real multiplier at +1 too (measured: 1 − 2e-6), its contact closed throughout."""
    branch = sn.harmonic_continuation(
        lambda hz: sn.scenes.mass_on_stop(frequency=hz, q1=0.7, gap=-2e-3,
                                          normal=Hertz(stiffness=1e6)), 30.0, 40.0, 7,
        max_step=0.2)
    folds = [b for b in branch.bifurcations if b.kind == "fold"]
    assert len(folds) == 1 and branch.ended == "reached p = 30"
    fold = folds[0]
    assert fold.parameter >= branch.parameter.max() - 1e-9
    assert abs(fold.multiplier - 1.0) <= 1e-6
    exact = sn.certify(fold.orbit).exact
    assert not exact.switches
    real = exact.multipliers[np.abs(exact.multipliers.imag) <= 1e-9].real
    assert np.abs(real - 1.0).min() <= 1e-3
    stable = branch.stable
    assert stable[0] and not stable[fold.index + 1]


# -- refusals ------------------------------------------------------------------------------

@pytest.mark.parametrize("call, error, message", [
    (lambda: sn.harmonic_balance(sn.scenes.blade_pair(), 3), ValueError,
     r"interface 0 \('a', 'b'\) sticks rigidly .* tangential_stiffness= k_t"),
    (lambda: sn.harmonic_balance(sn.scenes.block_on_belt(), 3), ValueError,
     r"prescribed-motion nodes \('belt'\)"),
    (lambda: sn.harmonic_balance(sn.scenes.jenkins_chain(), -1), ValueError,
     r"harmonic_balance\.harmonics"),
    (lambda: sn.harmonic_balance("scene", 3), TypeError, r"harmonic_balance\.scene"),
    (lambda: sn.harmonic_balance(sn.scenes.jenkins_chain(), 3, samples=6), ValueError,
     r"harmonic_balance\.samples"),
    (lambda: sn.harmonic_balance(sn.scenes.jenkins_chain(), 3, guess=np.zeros((4, 1))),
     ValueError, r"harmonic_balance\.guess must be a HarmonicOrbit"),
    (lambda: sn.certify("orbit"), TypeError, r"certify\.orbit must be a HarmonicOrbit"),
])
def test_what_harmonic_balance_cannot_carry_is_refused_by_name(call, error, message):
    with pytest.raises(error, match=message):
        call()
