"""Hill's multipliers against the exact Floquet multipliers (``studies.hill_floquet``):
on a linear structure both are the closed form e^{λT} of the structure's eigenvalues;
on a smooth orbit Hill's converge to the exact ones; on the stick–slip Jenkins chain
they are the open structure's at every H and do not.

Kernels: the blades' and the elastic contacts' tangent flows, which
``test_harmonic_balance`` compiles anyway; harmonic balance compiles only its slider
march.
"""

import numpy as np
import pytest
from matplotlib.axes import Axes
from matplotlib.figure import Figure

import shroudnet as sn
from contact_laws import Hertz
from shroudnet.front.figures import hill_floquet_diagram
from shroudnet.studies.hill_floquet import hill_against_floquet
from tests.test_harmonic_balance import open_pair

EXACT = dict(method=sn.Adaptive(rtol=1e-12), tolerance=1e-12)


def free_multipliers(scene):
    """e^{λT} of the eigenvalues λ of the structure without its contacts (the state
    matrix [[0, I], [−M⁻¹K, −M⁻¹C]]), T the excitation period: its orbits' Floquet
    multipliers in closed form."""
    a = scene.arrays
    n = len(a.mass)
    inverse = np.diag(1.0 / a.mass)
    state = np.block([[np.zeros((n, n)), np.eye(n)],
                      [-inverse @ a.stiffness_matrix(), -inverse @ a.damping_matrix()]])
    return np.exp(np.linalg.eigvals(state) * scene.excitation_period)


def farthest(found, expected) -> float:
    """The largest distance of one of ``found`` to the nearest of ``expected``."""
    return max(float(np.abs(expected - mu).min()) for mu in found)


@pytest.fixture(scope="module")
def linear():
    return hill_against_floquet(open_pair(), (1, 2), **EXACT)


def test_on_a_linear_structure_hill_and_floquet_are_the_closed_form(linear):
    """The exact orbit's multipliers (shooting) and Hill's at each H against e^{λT}
    (measured: 1.4e-12 and 3e-15), so the study's errors are rounding."""
    expected = free_multipliers(linear.scene)
    assert len(linear.exact.multipliers) == len(expected) == 4
    assert farthest(linear.exact.multipliers, expected) <= 1e-10
    for orbit in linear.orbits:
        assert farthest(orbit.multipliers, expected) <= 1e-12
    assert linear.errors.shape == (2, 4) and linear.errors.max() <= 1e-10


def test_where_the_orbit_is_smooth_hill_converges_to_the_exact_multipliers():
    """A mass pressed on a Hertz stop that never opens: every orbit smooth, the exact one
    without a switch, and the leading multiplier's error falling by orders of magnitude
    as H doubles (measured: 8.6e-4, 2.7e-5, 1.8e-10, 1.2e-12 at H = 1, 2, 4, 8, the last
    the exact orbit's own accuracy)."""
    scene = sn.scenes.mass_on_stop(gap=-2e-3, normal=Hertz(stiffness=1e6), q1=2.0,
                                   frequency=31.0)
    study = hill_against_floquet(scene, (1, 2, 4, 8), **EXACT)
    assert all(orbit.smooth for orbit in study.orbits) and not study.exact.switches
    error = study.leading_error()
    assert error[0] > 1e-4 and error[1] <= error[0] / 10
    assert error[2] <= 1e-8 and error[3] <= 1e-10
    assert study.leading_error(2).max() == pytest.approx(error.max())  # a conjugate pair


def test_where_the_chain_sticks_and_slips_hill_stays_the_open_structures():
    """The Jenkins chain: Hill's multipliers are the open structure's e^{λT} at every H
    (a slipping slider forgets its offset), so the exact ones' errors do not fall
    (measured: 0.17 for the leading pair, 0.35 for the next, at every H)."""
    scene = sn.scenes.jenkins_chain()
    study = hill_against_floquet(scene, (1, 4, 16))
    expected = free_multipliers(scene)
    assert not any(orbit.smooth for orbit in study.orbits)
    for orbit in study.orbits:
        assert farthest(orbit.multipliers, expected) <= 1e-9
    error = study.leading_error()
    assert error.min() > 0.1 and error[-1] >= 0.9 * error[0]
    rows = study.rows()
    assert rows[-1][0] == "exact" and rows[-1][2] == pytest.approx(
        abs(study.exact.multipliers[0]))
    assert [row[0] for row in rows[:-1]] == [1, 4, 16]


@pytest.mark.parametrize("arguments, error, message", [
    (("scene",), TypeError, r"hill_against_floquet\.scene must be a Scene"),
    ((open_pair(), []), ValueError, r"hill_against_floquet\.harmonics needs at least 1"),
    ((open_pair(), [1, 0]), ValueError, r"hill_against_floquet\.harmonics must be"),
    ((open_pair(), 3), TypeError, r"hill_against_floquet\.harmonics must be a sequence"),
])
def test_bad_input_is_refused_by_name(arguments, error, message):
    with pytest.raises(error, match=message):
        hill_against_floquet(*arguments)


def test_bad_accuracy_and_count_are_refused_by_name(linear):
    with pytest.raises(TypeError, match=r"hill_against_floquet\.method must be"):
        hill_against_floquet(open_pair(), (1,), method="tight")
    with pytest.raises(ValueError, match=r"hill_against_floquet\.tolerance must be"):
        hill_against_floquet(open_pair(), (1,), tolerance=0.5)
    with pytest.raises(ValueError, match=r"HillFloquet\.leading_error\.count must be"):
        linear.leading_error(5)


def test_the_diagram_draws_on_the_axes_given_or_on_a_new_figure(linear):
    figure = Figure(layout="constrained")
    given = list(figure.subplots(1, 2))
    assert hill_floquet_diagram(linear, label="pair", axes=given) is given
    assert all(panel.lines for panel in given) and figure.axes == given
    plane = given[0]
    assert plane.get_title() == "(a) pair" and plane.get_aspect() == 1.0
    drawn = hill_floquet_diagram(linear)
    assert isinstance(drawn, Figure) and len(drawn.axes) == 2
    assert all(isinstance(ax, Axes) and ax.lines for ax in drawn.axes)
    with pytest.raises(ValueError, match=r"hill_floquet_diagram\.axes needs 2 Axes"):
        hill_floquet_diagram(linear, axes=given[:1])
