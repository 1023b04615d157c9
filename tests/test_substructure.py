"""Substructures, their reductions, the FE readers and the beam blade, against closed forms.

Every reference number here is computed independently of the code under test: the
Euler–Bernoulli cantilever's βₙL, the exact Timoshenko and tip-mass frequency equations
solved with brentq, the static tip deflection PL³/3EI, the first-order Southwell
coefficient ∫ T φ'² dx / ∫ ρA φ² dx from the exact mode shape by quadrature, and the damping
ratio of a complex eigenvalue.
"""

import dataclasses
import math

import numpy as np
import pytest
import scipy.io
import scipy.linalg
import scipy.sparse
from scipy.integrate import quad
from scipy.optimize import brentq

import shroudnet.model.reduction as reduction
from shroudnet import (
    FrequencyTable,
    Southwell,
    Substructure,
    cantilever_beam,
    craig_bampton,
    modal_truncation,
    read_matrices,
)
from shroudnet.model.matrix_files import substructure_from_file

#: A steel strip 100 × 20 × 4 mm: flapwise (along the 4 mm thickness) is the weak plane.
STEEL = dict(youngs_modulus=2.0e11, density=7800.0)
LENGTH, WIDTH, THICKNESS = 0.1, 0.02, 0.004
AREA = WIDTH * THICKNESS
I_FLAP, I_EDGE = WIDTH * THICKNESS**3 / 12.0, THICKNESS * WIDTH**3 / 12.0
SHEAR_MODULUS = STEEL["youngs_modulus"] / (2.0 * 1.3)   # ν = 0.3
#: βₙL of the clamped–free Euler–Bernoulli beam: the roots of 1 + cos βL cosh βL = 0.
BETA_L = (1.875104068711961, 4.694091132974175, 7.854757438237613)


def strip(**options):
    return cantilever_beam(length=LENGTH, width=WIDTH, thickness=THICKNESS, **STEEL, **options)


def euler_bernoulli_hz(beta_l, inertia, area=AREA, length=LENGTH):
    """ωₙ = (βₙL)² √(EI / ρAL⁴), in Hz."""
    return beta_l**2 * math.sqrt(STEEL["youngs_modulus"] * inertia
                                 / (STEEL["density"] * area * length**4)) / (2.0 * math.pi)


def split_by_plane(substructure):
    """The frequencies [Hz] of the flapwise and of the edgewise modes of a beam."""
    frequencies, shapes = substructure.modes_at(0.0)
    flapwise = (shapes[0::4] ** 2).sum(0) + (shapes[1::4] ** 2).sum(0)
    edgewise = (shapes[2::4] ** 2).sum(0) + (shapes[3::4] ** 2).sum(0)
    return frequencies[flapwise > edgewise], frequencies[edgewise > flapwise]


# ---- the beam against closed forms -----------------------------------------------------------

def test_euler_bernoulli_beam_has_the_closed_form_frequencies_in_both_planes():
    flapwise, edgewise = split_by_plane(strip(elements=30))
    for plane, inertia in ((flapwise, I_FLAP), (edgewise, I_EDGE)):
        expected = [euler_bernoulli_hz(beta_l, inertia) for beta_l in BETA_L]
        np.testing.assert_allclose(plane[:3], expected, rtol=1e-5)   # measured 3.3e-6


def timoshenko_first_frequency(thickness):
    """ω₁ [rad/s] of the clamped–free Timoshenko strip, from the exact frequency equation.

    W, Ψ ∝ e^{sx} solve κGA(W'' − Ψ') + ρAω²W = 0, EIΨ'' + κGA(W' − Ψ) + ρIω²Ψ = 0 when
    (κGA s² + ρAω²)(EI s² − κGA + ρIω²) + (κGA s)² = 0; below the cut-off frequency s² has a
    positive root α² and a negative one −β². With W = (cosh αx, sinh αx, cos βx, sin βx) the
    rotations are Ψ = (g sinh, g cosh, h sin, −h cos), g = (κGAα² + ρAω²)/(κGAα),
    h = (ρAω² − κGAβ²)/(κGAβ). The clamp (W = Ψ = 0 at 0) and the free end (Ψ' = 0,
    W' − Ψ = 0 at L) make a 4 × 4 determinant whose first root is ω₁.
    """
    area, inertia = WIDTH * thickness, WIDTH * thickness**3 / 12.0
    k_ga = 5.0 / 6.0 * SHEAR_MODULUS * area
    ei, rho_a, rho_i = STEEL["youngs_modulus"] * inertia, STEEL["density"] * area, \
        STEEL["density"] * inertia

    def determinant(omega):
        w2 = omega**2
        roots = np.roots([k_ga * ei, k_ga * (rho_i * w2 - k_ga) + rho_a * w2 * ei + k_ga**2,
                          rho_a * w2 * (rho_i * w2 - k_ga)]).real
        alpha, beta = math.sqrt(roots.max()), math.sqrt(-roots.min())
        g = (k_ga * alpha**2 + rho_a * w2) / (k_ga * alpha)
        h = (rho_a * w2 - k_ga * beta**2) / (k_ga * beta)
        ch, sh = math.cosh(alpha * LENGTH), math.sinh(alpha * LENGTH)
        c, s = math.cos(beta * LENGTH), math.sin(beta * LENGTH)
        return np.linalg.det([
            [1.0, 0.0, 1.0, 0.0],                                           # W(0)
            [0.0, g, 0.0, -h],                                              # Ψ(0)
            [g * alpha * ch, g * alpha * sh, h * beta * c, h * beta * s],   # Ψ'(L)
            [(alpha - g) * sh, (alpha - g) * ch, -(beta + h) * s, (beta + h) * c]])  # W' − Ψ

    euler = 2.0 * math.pi * euler_bernoulli_hz(BETA_L[0], inertia, area)
    assert euler < math.sqrt(k_ga / rho_i)   # below the cut-off frequency
    grid = np.linspace(0.5 * euler, 1.0 * euler, 201)
    values = [determinant(omega) for omega in grid]
    first = next(k for k in range(200) if values[k] * values[k + 1] < 0.0)
    return brentq(determinant, grid[first], grid[first + 1], xtol=1e-12, rtol=1e-14)


def test_timoshenko_beam_matches_the_exact_timoshenko_frequency_of_a_stubby_strip():
    thickness = LENGTH / 5.0
    exact = timoshenko_first_frequency(thickness) / (2.0 * math.pi)
    beam = cantilever_beam(length=LENGTH, width=WIDTH, thickness=thickness, **STEEL,
                           elements=40, shear_modulus=SHEAR_MODULUS)
    flapwise, _ = split_by_plane(beam)
    euler = euler_bernoulli_hz(BETA_L[0], WIDTH * thickness**3 / 12.0, WIDTH * thickness)
    assert exact / euler == pytest.approx(0.96979, abs=1e-5)   # shear and rotary inertia
    assert flapwise[0] / exact - 1.0 == pytest.approx(0.0, abs=1e-5)   # measured 3.1e-6


def test_timoshenko_beam_tends_to_euler_bernoulli_as_it_grows_slender():
    ratios = []
    for slenderness in (5.0, 10.0, 20.0, 100.0):
        section = dict(length=LENGTH, width=WIDTH, thickness=LENGTH / slenderness, **STEEL,
                       elements=40)
        timoshenko = cantilever_beam(**section, shear_modulus=SHEAR_MODULUS)
        ratios.append(timoshenko.frequencies_at(0.0)[0]
                      / cantilever_beam(**section).frequencies_at(0.0)[0])
    assert all(ratio < 1.0 for ratio in ratios)
    assert ratios == sorted(ratios)
    assert 1.0 - ratios[-1] < 1e-4   # L/h = 100: measured 8.0e-5


def test_a_tip_mass_lowers_the_first_frequency_as_the_frequency_equation_says():
    tip_mass = 0.3 * STEEL["density"] * AREA * LENGTH
    rho_a = STEEL["density"] * AREA

    def equation(beta_l):
        beta = beta_l / LENGTH
        return (1.0 + math.cos(beta_l) * math.cosh(beta_l) + tip_mass * beta / rho_a
                * (math.cos(beta_l) * math.sinh(beta_l) - math.sin(beta_l) * math.cosh(beta_l)))

    beta_l = brentq(equation, 0.5, BETA_L[0], xtol=1e-14)
    flapwise, edgewise = split_by_plane(strip(elements=20, tip_mass=tip_mass))
    assert beta_l < BETA_L[0]
    assert flapwise[0] == pytest.approx(euler_bernoulli_hz(beta_l, I_FLAP), rel=1e-6)
    assert edgewise[0] == pytest.approx(euler_bernoulli_hz(beta_l, I_EDGE), rel=1e-6)


def test_the_load_point_interpolates_the_flapwise_displacement():
    """Statically, v(x) = P x² (3L − x) / 6EI under a tip load P: the element's cubic is the
    exact solution, so the point between nodes reads it exactly."""
    beam = strip(elements=4, load_position=0.3)   # 0.3 L lies inside the second element
    force = beam.point("shroud").T @ np.array([1.0, 0.0])
    q = np.linalg.solve(beam.matrices_at(0.0).stiffness, force)
    x = 0.3 * LENGTH
    expected = x**2 * (3.0 * LENGTH - x) / (6.0 * STEEL["youngs_modulus"] * I_FLAP)
    assert (beam.point("load") @ q)[0] == pytest.approx(expected, rel=1e-12)
    np.testing.assert_array_equal(beam.load_vector, beam.point("load")[0])


# ---- speed ------------------------------------------------------------------------------------

def test_matrices_at_adds_the_speed_stiffness_times_omega_squared():
    mass, stiffness = np.diag([1.0, 2.0]), np.array([[3.0, -1.0], [-1.0, 2.0]])
    speed = np.array([[0.5, 0.1], [0.1, 0.2]])
    substructure = Substructure(mass, stiffness, stiffness_speed=speed, points={})
    omega = 2.0 * math.pi * 3000.0 / 60.0
    np.testing.assert_allclose(substructure.matrices_at(3000.0).stiffness,
                               stiffness + omega**2 * speed, rtol=1e-15)
    np.testing.assert_array_equal(substructure.matrices_at(0.0).stiffness, stiffness)


def southwell_coefficient(hub_ratio):
    """dω²/dΩ² at rest of the first flapwise mode: ∫ T φ'² / ∫ ρA φ² with the exact mode
    φ = cosh βx − cos βx − σ (sinh βx − sin βx), T/(ρAΩ²) = ((R + L)² − (R + x)²)/2 (L = 1)."""
    beta = BETA_L[0]
    sigma = (math.cosh(beta) + math.cos(beta)) / (math.sinh(beta) + math.sin(beta))
    shape = lambda x: (math.cosh(beta * x) - math.cos(beta * x)  # noqa: E731
                       - sigma * (math.sinh(beta * x) - math.sin(beta * x)))
    slope = lambda x: beta * (math.sinh(beta * x) + math.sin(beta * x)  # noqa: E731
                              - sigma * (math.cosh(beta * x) - math.cos(beta * x)))
    tension = lambda x: ((1.0 + hub_ratio) ** 2 - (hub_ratio + x) ** 2) / 2.0  # noqa: E731
    return (quad(lambda x: tension(x) * slope(x) ** 2, 0.0, 1.0, epsabs=1e-13)[0]
            / quad(lambda x: shape(x) ** 2, 0.0, 1.0, epsabs=1e-13)[0])


@pytest.mark.parametrize("hub_ratio, literature", [(0.0, 1.1933), (0.5, None)])
def test_centrifugal_stiffening_gives_the_rotating_cantilevers_southwell_coefficient(
        hub_ratio, literature):
    """f² = f₀² + B (Ω/2π)² to first order, B = φᵀ K₁ φ for the mass-normalised mode φ.
    B = 1.1933 at R = 0 is the value usually quoted for the uniform cantilever; over a wide
    range of speeds the secant is lower (f² grows slower than linearly in Ω²)."""
    beam = strip(elements=30, hub_radius=hub_ratio * LENGTH)
    rest, shapes = beam.modes_at(0.0)
    first = shapes[:, 0]
    coefficient = first @ beam.stiffness_speed @ first
    expected = southwell_coefficient(hub_ratio)
    if literature is not None:
        assert expected == pytest.approx(literature, abs=1e-4)
    assert coefficient == pytest.approx(expected, rel=1e-4)   # measured 1.2e-5
    speeds = [0.0, 6000.0, 30000.0]
    frequencies = [beam.frequencies_at(speed)[0] for speed in speeds]
    assert frequencies == sorted(frequencies) and frequencies[0] == rest[0]
    secant = (frequencies[1] ** 2 - rest[0] ** 2) / (speeds[1] / 60.0) ** 2
    assert 0.95 * coefficient < secant <= coefficient


# ---- reductions -------------------------------------------------------------------------------

BEAM_40 = strip(elements=40)
TIP = list(range(BEAM_40.n_dofs - 4, BEAM_40.n_dofs))   # v, θ_z, w, θ_y of the tip node


def relative_errors(reduced, full, count=4):
    return np.abs(reduced.frequencies_at(0.0)[:count] / full.frequencies_at(0.0)[:count] - 1.0)


def test_craig_bampton_frequencies_converge_as_modes_are_added():
    errors = [relative_errors(craig_bampton(BEAM_40.mass, BEAM_40.stiffness, TIP, modes),
                              BEAM_40).max() for modes in (2, 4, 8, 16)]
    assert all(later < earlier for earlier, later in zip(errors, errors[1:]))
    assert errors[-1] < 5e-5   # measured 4.8e-3, 1.6e-3, 1.9e-4, 1.7e-5
    reduced = craig_bampton(BEAM_40.mass, BEAM_40.stiffness, TIP, 16)
    assert np.all(reduced.frequencies_at(0.0)[:4] >= BEAM_40.frequencies_at(0.0)[:4]
                  * (1 - 1e-12))   # a Rayleigh–Ritz basis bounds from above


def with_tip_spring(substructure, stiffness=1e6):
    """The frequencies [Hz] with a flapwise spring k from the tip to ground: the stiffness a
    stuck contact adds at a point, which the reduction must carry."""
    mass, _, k = substructure.matrices_at(0.0)
    row = substructure.point("shroud")[0]
    return np.sqrt(scipy.linalg.eigh(k + stiffness * np.outer(row, row), mass,
                                     eigvals_only=True)[:3]) / (2.0 * math.pi)


def test_modal_truncation_keeps_the_frequencies_and_converges_under_a_contact_spring():
    for modes in (4, 8):
        reduced = modal_truncation(BEAM_40.mass, BEAM_40.stiffness, modes)
        assert relative_errors(reduced, BEAM_40).max() < 1e-8   # the full eigensolve's own
    exact = with_tip_spring(BEAM_40)
    errors = [np.abs(with_tip_spring(modal_truncation(BEAM_40.mass, BEAM_40.stiffness, modes,
                                                      points=BEAM_40.points)) / exact - 1).max()
              for modes in (4, 8, 16, 32)]
    assert all(later < earlier for earlier, later in zip(errors, errors[1:]))
    assert errors[-1] < 3e-5   # measured 5.8e-3, 7.5e-4, 1.2e-4, 1.5e-5
    cb_errors = [np.abs(with_tip_spring(craig_bampton(BEAM_40.mass, BEAM_40.stiffness, TIP,
                                                      modes, points=BEAM_40.points))
                        / exact - 1).max() for modes in (2, 4, 8)]
    assert all(later < earlier for earlier, later in zip(cb_errors, cb_errors[1:]))
    assert cb_errors[-1] < 1e-4   # measured 3.3e-3, 8.9e-4, 7.1e-5: fewer coordinates


@pytest.mark.parametrize("modes", [0, 5])
def test_craig_bampton_reproduces_the_static_tip_deflection_exactly(modes):
    """Constraint modes span every static response to boundary loads: P L³/3EI in each
    plane, and the expanded field v(x) = P x²(3L − x)/6EI at every node."""
    reduced = craig_bampton(BEAM_40.mass, BEAM_40.stiffness, TIP, modes,
                            points=BEAM_40.points, load=("shroud", [1.0, 0.0]))
    stiffness = reduced.matrices_at(0.0).stiffness
    flexibility = np.linalg.solve(stiffness, reduced.point("shroud").T)
    tip = reduced.point("shroud") @ flexibility
    modulus = STEEL["youngs_modulus"]
    assert tip[0, 0] == pytest.approx(LENGTH**3 / (3 * modulus * I_FLAP), rel=1e-10)
    assert tip[1, 1] == pytest.approx(LENGTH**3 / (3 * modulus * I_EDGE), rel=1e-10)
    assert abs(tip[0, 1]) < 1e-12 * tip[0, 0]
    field = reduced.expand(np.linalg.solve(stiffness, reduced.load_vector))
    x = LENGTH * np.arange(1, 41) / 40
    np.testing.assert_allclose(field[0::4], x**2 * (3 * LENGTH - x) / (6 * modulus * I_FLAP),
                               rtol=1e-9)
    assert reduced.basis.shape == (BEAM_40.n_dofs, 4 + modes)
    np.testing.assert_array_equal(reduced.basis[TIP], np.eye(4, 4 + modes))


def test_the_sparse_solvers_agree_with_the_dense_ones(monkeypatch):
    dense_cb = craig_bampton(BEAM_40.mass, BEAM_40.stiffness, TIP, 6, points=BEAM_40.points)
    dense_modes = modal_truncation(BEAM_40.mass, BEAM_40.stiffness, 6)
    monkeypatch.setattr(reduction, "DENSE_SOLVE_LIMIT", 10)
    sparse_cb = craig_bampton(BEAM_40.mass, BEAM_40.stiffness, TIP, 6, points=BEAM_40.points)
    sparse_modes = modal_truncation(BEAM_40.mass, BEAM_40.stiffness, 6)
    np.testing.assert_allclose(sparse_cb.frequencies_at(0.0), dense_cb.frequencies_at(0.0),
                               rtol=1e-9)
    np.testing.assert_allclose(sparse_modes.frequencies_at(0.0),
                               dense_modes.frequencies_at(0.0), rtol=1e-9)
    with pytest.raises(ValueError, match=r"modal_truncation\.modes must be an int >= 1 and "
                                         r"<= N − 1 .* = 159"):
        modal_truncation(BEAM_40.mass, BEAM_40.stiffness, 160)


def test_modal_truncation_of_a_free_chain_finds_its_rigid_mode_sparse(monkeypatch):
    """n unit masses joined by springs k, free at both ends: ω_j = 2 √k sin(jπ / 2n)."""
    size, spring = 60, 1e4
    stiffness = scipy.sparse.diags([-np.ones(size - 1), 2.0 * np.ones(size), -np.ones(size - 1)],
                                   [-1, 0, 1]).tolil()
    stiffness[0, 0] = stiffness[-1, -1] = 1.0
    monkeypatch.setattr(reduction, "DENSE_SOLVE_LIMIT", 10)
    chain = modal_truncation(scipy.sparse.identity(size), spring * stiffness.tocsr(), 5)
    expected = [2.0 * math.sqrt(spring) * math.sin(j * math.pi / (2 * size)) for j in range(5)]
    np.testing.assert_allclose(chain.frequencies_at(0.0) * 2 * math.pi, expected, rtol=1e-9,
                               atol=1e-6)


def test_reductions_carry_loads_damping_and_speed():
    beam = strip(elements=10, hub_radius=0.05)
    force = np.zeros(beam.n_dofs)
    force[-4] = 2.0
    reduced = craig_bampton(beam.mass, beam.stiffness, [beam.n_dofs - 4], 3, load=force,
                            damping_ratios=0.01, stiffness_speed=beam.stiffness_speed,
                            excitation_scale=-0.5)
    np.testing.assert_allclose(reduced.load_vector, reduced.basis.T @ force)
    assert reduced.excitation_scale == -0.5 and reduced.damping_ratios == 0.01
    assert reduced.frequencies_at(20000.0)[0] > reduced.frequencies_at(0.0)[0]
    truncated = modal_truncation(beam.mass, beam.stiffness, 3, points=beam.points)
    np.testing.assert_allclose(truncated.load_vector, truncated.point("load")[0])
    free = modal_truncation(np.eye(2), np.array([[1.0, -1.0], [-1.0, 1.0]]), 2)
    np.testing.assert_allclose(free.frequencies_at(0.0), [0.0, math.sqrt(2) / (2 * math.pi)],
                               atol=1e-12)


@pytest.mark.parametrize("call, message", [
    (lambda: craig_bampton(BEAM_40.mass, BEAM_40.stiffness, [0, 160], 2),
     r"craig_bampton\.boundary must be an int >= 0 and <= N − 1 = 159, got 160"),
    (lambda: craig_bampton(BEAM_40.mass, BEAM_40.stiffness, [3, 5, 3], 2),
     r"craig_bampton\.boundary repeats the DOF indices \[3\]"),
    (lambda: craig_bampton(BEAM_40.mass, BEAM_40.stiffness, TIP, -1),
     r"craig_bampton\.modes must be an int >= 0"),
    (lambda: craig_bampton(BEAM_40.mass, BEAM_40.stiffness, TIP, 157),
     r"craig_bampton\.modes must be an int >= 0 and <= N − len\(boundary\) = 156, got 157"),
    (lambda: modal_truncation(BEAM_40.mass, BEAM_40.stiffness, 0),
     r"modal_truncation\.modes must be an int >= 1"),
    (lambda: craig_bampton(np.eye(3), np.array([[1.0, -1, 0], [-1, 2, -1], [0, -1, 1]]), [], 1),
     r"craig_bampton: K with the boundary fixed is not positive definite"),
    (lambda: craig_bampton(BEAM_40.mass, BEAM_40.stiffness, TIP, 2, points={"p": np.ones(3)}),
     r"craig_bampton\.points\['p'\] must be a d × 160 matrix"),
    (lambda: modal_truncation(BEAM_40.mass, BEAM_40.stiffness, 2, load=np.ones(5)),
     r"modal_truncation\.load must be a finite vector of 160"),
    (lambda: modal_truncation(np.eye(2), np.eye(3), 1),
     r"modal_truncation\.stiffness must be 2 × 2 like the mass"),
])
def test_reductions_refuse_bad_input_naming_the_field(call, message):
    with pytest.raises((ValueError, TypeError), match=message):
        call()


# ---- modal substructures and damping ------------------------------------------------------------

def test_a_modal_substructure_has_diagonal_matrices_with_the_given_frequencies():
    modal = Substructure.modal([120.0, 450.0], [0.01, 0.02], [0.2, 0.05],
                               {"shroud": [[1.0, -0.5], [0.2, 0.8]], "load": [1.0, 1.0]})
    mass, damping, stiffness = modal.matrices_at(0.0)
    omega = 2 * math.pi * np.array([120.0, 450.0])
    np.testing.assert_array_equal(mass, np.diag([0.2, 0.05]))
    np.testing.assert_allclose(stiffness, np.diag([0.2, 0.05] * omega**2), rtol=1e-15)
    np.testing.assert_allclose(damping, np.diag(2 * np.array([0.01, 0.02]) * [0.2, 0.05]
                                                * omega), rtol=1e-15)
    np.testing.assert_allclose(modal.frequencies_at(0.0), [120.0, 450.0], rtol=1e-15)
    np.testing.assert_array_equal(modal.load_vector, [1.0, 1.0])
    shapes = modal.modes_at(0.0).shapes
    np.testing.assert_allclose(shapes.T @ mass @ shapes, np.eye(2), atol=1e-15)


def test_modal_frequencies_follow_their_speed_models():
    southwell = Southwell(f0=100.0, coefficient=2.0)
    table = FrequencyTable(speeds_rpm=(0.0, 6000.0), frequencies=(300.0, 360.0))
    modal = Substructure.modal([southwell, table], 0.0, 1.0, {"tip": [1.0, 1.0]})
    np.testing.assert_allclose(modal.frequencies_at(6000.0),
                               [math.sqrt(100.0**2 + 2.0 * 100.0**2), 360.0], rtol=1e-14)
    np.testing.assert_allclose(modal.frequencies_at(3000.0),
                               [math.sqrt(100.0**2 + 2.0 * 50.0**2), 330.0], rtol=1e-14)
    with pytest.raises(ValueError, match="outside the FrequencyTable range"):
        modal.frequencies_at(7000.0)


@pytest.mark.parametrize("ratios", [0.03, (0.01, 0.05, 0.2)])
def test_modal_damping_ratios_are_those_of_the_complex_eigenvalues(ratios):
    """For each pair λ = −ζω ± iω√(1 − ζ²) of the first-order system, ζ = −Re λ / |λ|."""
    mass = np.diag([1.0, 2.0, 0.5])
    stiffness = np.array([[400.0, -100.0, 0.0], [-100.0, 300.0, -150.0], [0.0, -150.0, 250.0]])
    damped = Substructure(mass, stiffness, damping_ratios=ratios, points={})
    m, c, k = damped.matrices_at(0.0)
    eigenvalues = scipy.linalg.eigvals(np.block([[np.zeros((3, 3)), np.eye(3)],
                                                 [-np.linalg.solve(m, k), -np.linalg.solve(m, c)]]))
    upper = eigenvalues[eigenvalues.imag > 0]
    upper = upper[np.argsort(np.abs(upper))]
    np.testing.assert_allclose(-upper.real / np.abs(upper),
                               np.broadcast_to(ratios, (3,)), rtol=1e-10)
    np.testing.assert_allclose(np.abs(upper) / (2 * math.pi), damped.frequencies_at(0.0),
                               rtol=1e-10)


# ---- points, loads, repr -------------------------------------------------------------------------

def test_points_and_loads_resolve_as_documented():
    mass, stiffness = np.eye(3), np.diag([1.0, 2.0, 3.0])
    points = {"shroud": [[1.0, 0.0, 0.0], [0.0, 1.0, 1.0]], "load": [0.0, 0.0, 2.0]}
    substructure = Substructure(mass, stiffness, points=points)
    np.testing.assert_array_equal(substructure.load_vector, [0.0, 0.0, 2.0])
    np.testing.assert_array_equal(substructure.point("load"), [[0.0, 0.0, 2.0]])
    along = Substructure(mass, stiffness, points=points, load=("shroud", [0.6, 0.8]))
    np.testing.assert_allclose(along.load_vector, [0.6, 0.8, 0.8])
    assert not Substructure(mass, stiffness, points={}).load_vector.any()
    assert repr(substructure) == "Substructure(n_dofs=3, points=['shroud', 'load'])"
    with pytest.raises(ValueError, match=r"point\('tip'\) names the unknown point 'tip'; the "
                                         r"points are \['load', 'shroud'\]"):
        substructure.point("tip")


def test_a_substructure_is_immutable_and_replaces_like_a_dataclass():
    beam = strip(elements=3)
    with pytest.raises(dataclasses.FrozenInstanceError):
        beam.excitation_scale = 2.0
    with pytest.raises(ValueError, match="read-only"):
        beam.point("shroud")[0, 0] = 5.0
    scaled = dataclasses.replace(beam, excitation_scale=-2.0)
    assert scaled.excitation_scale == -2.0
    np.testing.assert_array_equal(scaled.load_vector, beam.load_vector)
    np.testing.assert_array_equal(scaled.frequencies_at(0.0), beam.frequencies_at(0.0))


def test_matrices_of_a_large_model_are_refused_with_the_remedy():
    size = 5001
    large = Substructure(scipy.sparse.identity(size, format="csr"),
                         scipy.sparse.identity(size, format="csr"), points={})
    with pytest.raises(ValueError, match=r"n = 5001 > 5000 .* craig_bampton or "
                                         r"modal_truncation"):
        large.matrices_at(0.0)


TWO = np.eye(2)
SPRING = np.array([[2.0, -1.0], [-1.0, 1.0]])


@pytest.mark.parametrize("make, error, message", [
    (lambda: Substructure(np.array([[1.0, 0.1], [0.0, 1.0]]), SPRING, points={}), ValueError,
     r"Substructure\.mass must be symmetric"),
    (lambda: Substructure(np.diag([1.0, -1.0]), SPRING, points={}), ValueError,
     r"Substructure\.mass must be positive definite"),
    (lambda: Substructure(TWO, np.array([[1.0, 2.0], [2.0, 1.0]]), points={}), ValueError,
     r"Substructure\.stiffness must be positive semi-definite, but its lowest eigenvalue is -1"),
    (lambda: Substructure(TWO, SPRING, -TWO, points={}), ValueError,
     r"Substructure\.damping must be positive semi-definite"),
    (lambda: Substructure(TWO, np.eye(3), points={}), ValueError,
     r"Substructure\.stiffness must be 2 × 2 like the mass"),
    (lambda: Substructure(TWO, np.array([[np.nan, 0], [0, 1]]), points={}), ValueError,
     r"Substructure\.stiffness must be finite"),
    (lambda: Substructure("M", SPRING, points={}), TypeError,
     r"Substructure\.mass must be an array of real numbers"),
    (lambda: Substructure(TWO, SPRING, points={"tip": np.ones((2, 3))}), ValueError,
     r"Substructure\.points\['tip'\] must be a d × 2 matrix"),
    (lambda: Substructure(TWO, SPRING, points={"tip": np.ones((4, 2))}), ValueError,
     r"Substructure\.points\['tip'\] must have d = 1, 2 or 3 rows .* got d = 4"),
    (lambda: Substructure(TWO, SPRING, points={"tip": TWO}, load=("tip", [1.0, 1.0])),
     ValueError, r"Substructure\.load direction must be a unit vector .* got \|n\| = 1\.414"),
    (lambda: Substructure(TWO, SPRING, points={"tip": TWO}, load=("tip", [1.0])), ValueError,
     r"Substructure\.load direction must have 2 components"),
    (lambda: Substructure(TWO, SPRING, points={"tip": TWO}, load="tip"), ValueError,
     r"Substructure\.load = 'tip' names a point with d = 2"),
    (lambda: Substructure(TWO, SPRING, points={"load": TWO}), ValueError,
     r"Substructure\.load is None and the point 'load' has d = 2"),
    (lambda: Substructure(TWO, SPRING, points={}, load="tip"), ValueError,
     r"Substructure\.load names the unknown point 'tip'"),
    (lambda: Substructure(TWO, SPRING, points={}, load=[1.0, 2.0, 3.0]), ValueError,
     r"Substructure\.load must be a vector of 2 generalised forces"),
    (lambda: Substructure(TWO, SPRING, damping_ratios=-0.1, points={}), ValueError,
     r"Substructure\.damping_ratios must be in \[0, inf\), got -0\.1"),
    (lambda: Substructure(TWO, SPRING, damping_ratios=[0.1, 0.1, 0.1], points={}), ValueError,
     r"Substructure\.damping_ratios must hold one ratio for all modes or one per mode \(2\)"),
    (lambda: Substructure(TWO, SPRING, TWO, damping_ratios=0.1, points={}), ValueError,
     r"Substructure takes damping= .* or damping_ratios= .*, not both"),
    (lambda: Substructure(TWO, SPRING, stiffness_speed=np.array([[0, 1], [0, 0]]), points={}),
     ValueError, r"Substructure\.stiffness_speed must be symmetric"),
    (lambda: Substructure(TWO, SPRING, points={}, excitation_scale=math.inf), ValueError,
     r"Substructure\.excitation_scale must be in \(-inf, inf\)"),
    (lambda: Substructure(TWO, SPRING, points=[TWO]), TypeError,
     r"Substructure\.points must be a mapping"),
    (lambda: Substructure(TWO, None, points={}), ValueError,
     r"Substructure\.stiffness is required"),
    (lambda: Substructure.modal([100.0, -5.0], 0.0, 1.0, {}), ValueError,
     r"Substructure\.modal\.frequencies must be in \(0, inf\) Hz, got -5"),
    (lambda: Substructure.modal([100.0], 0.0, [1.0, 2.0], {}), ValueError,
     r"Substructure\.modal masses must hold one mass for all modes or one per mode \(1\)"),
    (lambda: Substructure.modal([100.0], 0.0, 0.0, {}), ValueError,
     r"Substructure\.modal\.masses must be in \(0, inf\) kg"),
    (lambda: Substructure(TWO, SPRING, points={}).matrices_at(-1.0), ValueError,
     r"Substructure\.matrices_at\.speed_rpm must be in \[0, inf\) rpm"),
    (lambda: cantilever_beam(length=0.1, width=0.01, **STEEL), ValueError,
     r"cantilever_beam needs both width= and thickness="),
    (lambda: cantilever_beam(length=0.1, width=0.01, thickness=0.01, area=1e-4, **STEEL),
     ValueError, r"cantilever_beam needs exactly one section"),
    (lambda: strip(load_position=0.0), ValueError,
     r"cantilever_beam\.load_position must be in \(0, 1\]"),
    (lambda: strip(elements=0), ValueError, r"cantilever_beam\.elements must be an int >= 1"),
    (lambda: cantilever_beam(length=8e8, width=0.02, thickness=0.003, elements=2, **STEEL),
     ValueError, r"cantilever_beam: length = 8e\+08 m over 2 elements makes elements of "
                 r"4e\+08 m.*check the length's units"),
    (lambda: strip(shear_modulus=-1.0), ValueError, r"cantilever_beam\.shear_modulus"),
])
def test_bad_input_fails_early_naming_the_field(make, error, message):
    with pytest.raises(error, match=message):
        make()


# ---- files ---------------------------------------------------------------------------------------

MASS_3 = np.array([[2.0, 0.5, 0.0], [0.5, 2.0, 0.5], [0.0, 0.5, 2.0]])
STIFFNESS_3 = np.array([[200.0, -100.0, 0.0], [-100.0, 200.0, -100.0], [0.0, -100.0, 100.0]])
DAMPING_3 = 1e-3 * STIFFNESS_3


def assert_same(matrix, expected):
    dense = matrix.toarray() if scipy.sparse.issparse(matrix) else matrix
    np.testing.assert_array_equal(dense, expected)


def test_npz_round_trip_dense_and_as_triplets(tmp_path):
    np.savez(tmp_path / "dense.npz", M=MASS_3, K=STIFFNESS_3, C=DAMPING_3)
    read = read_matrices(tmp_path / "dense.npz", damping="C")
    for matrix, expected in ((read.mass, MASS_3), (read.stiffness, STIFFNESS_3),
                             (read.damping, DAMPING_3)):
        assert_same(matrix, expected)
    coo = scipy.sparse.coo_array(STIFFNESS_3)
    np.savez(tmp_path / "triplets.npz", mass=MASS_3, stiff_rows=coo.row, stiff_cols=coo.col,
             stiff_values=coo.data, stiff_shape=np.array(coo.shape))
    read = read_matrices(tmp_path / "triplets.npz", mass="mass", stiffness="stiff")
    assert scipy.sparse.issparse(read.stiffness) and read.damping is None
    assert_same(read.stiffness, STIFFNESS_3)
    assert read.n_dofs == 3


@pytest.mark.parametrize("sparse", [False, True])
def test_mat_round_trip_dense_and_sparse(tmp_path, sparse):
    wrap = scipy.sparse.csc_matrix if sparse else np.asarray
    scipy.io.savemat(tmp_path / "blade.mat", {"Mff": wrap(MASS_3), "Kff": wrap(STIFFNESS_3)})
    read = read_matrices(tmp_path / "blade.mat", mass="Mff", stiffness="Kff")
    assert scipy.sparse.issparse(read.stiffness) == sparse
    assert_same(read.mass, MASS_3)
    assert_same(read.stiffness, STIFFNESS_3)
    substructure = substructure_from_file(tmp_path / "blade.mat", mass="Mff", stiffness="Kff",
                                          points={"tip": [0.0, 0.0, 1.0]}, load="tip",
                                          damping_ratios=0.01)
    expected = np.sqrt(scipy.linalg.eigh(STIFFNESS_3, MASS_3, eigvals_only=True)) / (2 * math.pi)
    np.testing.assert_allclose(substructure.frequencies_at(0.0), expected, rtol=1e-12)


def test_readers_refuse_bad_files_naming_what_is_wrong(tmp_path):
    with pytest.raises(FileNotFoundError, match=r"no file .*absent\.npz"):
        read_matrices(tmp_path / "absent.npz")
    (tmp_path / "blade.txt").write_text("1 2 3")
    with pytest.raises(ValueError, match=r"reads \.npz and \.mat files, got 'blade\.txt'"):
        read_matrices(tmp_path / "blade.txt")
    np.savez(tmp_path / "blade.npz", Mass=MASS_3, K=STIFFNESS_3)
    with pytest.raises(ValueError, match=r"has no matrix 'M' \(mass=\); it holds: K, Mass"):
        read_matrices(tmp_path / "blade.npz")
    np.savez(tmp_path / "oblong.npz", M=MASS_3, K=np.ones((3, 2)))
    with pytest.raises(ValueError, match=r"oblong\.npz\['K'\] \(stiffness\) must be a square"):
        read_matrices(tmp_path / "oblong.npz")
    np.savez(tmp_path / "sizes.npz", M=MASS_3, K=np.eye(2))
    with pytest.raises(ValueError, match=r"the stiffness matrix 'K' is 2 × 2, the mass 3 × 3"):
        read_matrices(tmp_path / "sizes.npz")
