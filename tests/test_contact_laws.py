"""Contract tests, run over every law: built-in ones and a user's own."""

import dataclasses
import math

import numba
import pytest
from hypothesis import given
from hypothesis import strategies as st

import contact_laws as cl
from tests.laws import EVERY_FRICTION_LAW, EVERY_NORMAL_LAW, CubicSpring

NORMAL_IDS = [type(law).__name__ for law in EVERY_NORMAL_LAW]
FRICTION_IDS = [repr(law) for law in EVERY_FRICTION_LAW]


@pytest.mark.parametrize("law", EVERY_NORMAL_LAW, ids=NORMAL_IDS)
@given(penetration=st.floats(1e-9, 1e-3), rate=st.floats(-10.0, 10.0))
def test_normal_force_is_finite_and_never_pulls(law, penetration, rate):
    force = law(penetration, rate)
    assert math.isfinite(force) and force >= 0.0


@pytest.mark.parametrize("law", EVERY_NORMAL_LAW, ids=NORMAL_IDS)
@given(penetration=st.floats(-1e-6, 0.0), rate=st.floats(-10.0, 10.0))
def test_normal_force_is_finite_just_past_separation(law, penetration, rate):
    """A trial state inside a step that separates holds δ slightly below 0 (a Hertz law
    once gave NaN there and stalled the adaptive step)."""
    assert math.isfinite(law(penetration, rate))


@pytest.mark.parametrize("law", [law for law in EVERY_NORMAL_LAW if law.opens], ids=str)
def test_normal_force_grows_from_zero_with_penetration_at_rest(law):
    assert law(1e-12) < law(1e-6) < law(1e-5)


@pytest.mark.parametrize("law", EVERY_FRICTION_LAW, ids=FRICTION_IDS)
@given(speed=st.floats(0.0, 100.0))
def test_friction_coefficient_is_bounded_by_the_static_one(law, speed):
    mu = law(speed)
    assert 0.0 <= mu <= law.static_coefficient + 1e-15
    assert law(-speed) == mu


@pytest.mark.parametrize("law", EVERY_NORMAL_LAW + EVERY_FRICTION_LAW,
                         ids=NORMAL_IDS + FRICTION_IDS)
def test_laws_are_immutable(law):
    field = dataclasses.fields(law)[0].name
    with pytest.raises(dataclasses.FrozenInstanceError):
        setattr(law, field, 1.0)


@pytest.mark.parametrize("law", EVERY_NORMAL_LAW, ids=NORMAL_IDS)
def test_normal_laws_compile_with_numba_and_agree(law):
    compiled = numba.njit(type(law).normal_force)
    assert compiled(2e-6, 0.3, *law.parameters()) == pytest.approx(law(2e-6, 0.3), rel=1e-14)


@pytest.mark.parametrize("law", EVERY_FRICTION_LAW, ids=FRICTION_IDS)
def test_friction_laws_compile_with_numba_and_agree(law):
    compiled = numba.njit(type(law.exact).coefficient)
    assert compiled(0.02, *law.parameters()) == pytest.approx(law(0.02), rel=1e-14)


def test_paper_friction_law_is_eq4():
    law = cl.ExponentialFriction(mu_static=0.5, mu_kinetic=0.3, beta=5.0)
    assert law(0.0) == 0.5
    assert law(0.1) == pytest.approx(0.3 + 0.2 * math.exp(-0.5), rel=1e-15)
    assert law(1e3) == pytest.approx(0.3)


def test_regularised_law_keeps_the_exact_coefficient_and_never_sticks():
    exact = cl.Stribeck(mu_static=0.6, mu_kinetic=0.2, stribeck_velocity=0.01)
    smooth = cl.Regularised(law=exact, velocity=1e-4)
    assert smooth(0.005) == exact(0.005)
    assert smooth.exact is exact and exact.exact is exact
    assert smooth.regularisation_velocity == 1e-4 and exact.regularisation_velocity == 0.0


def test_user_law_in_a_few_lines():
    law = CubicSpring(linear=1e5, cubic=1e13)
    assert law(1e-4) == pytest.approx(1e5 * 1e-4 + 1e13 * 1e-12)
    with pytest.raises(ValueError, match=r"CubicSpring\.cubic must be in \[0, inf\) N/m³"):
        CubicSpring(linear=1.0, cubic=-1.0)


@pytest.mark.parametrize("make, message", [
    (lambda: cl.LinearSpring(stiffness=-1.0), r"LinearSpring\.stiffness must be in \(0, inf\)"),
    (lambda: cl.LinearSpring(stiffness=float("nan")), r"LinearSpring\.stiffness .*NaN"),
    (lambda: cl.Hertz(stiffness=1.0, exponent=5.0), r"Hertz\.exponent must be in \[1, 3\]"),
    (lambda: cl.ExponentialFriction(mu_static=0.3, mu_kinetic=0.5, beta=1.0),
     r"mu_kinetic must be in \[0, mu_static = 0.3\]"),
    (lambda: cl.Coulomb(mu=-0.1), r"Coulomb\.mu must be in \[0, inf\)"),
    (lambda: cl.Stribeck(mu_static=0.5, mu_kinetic=0.1, stribeck_velocity=0.0),
     r"stribeck_velocity must be in \(0, inf\) m/s"),
    (lambda: cl.ConstantLoad(force=math.inf), r"ConstantLoad\.force"),
    (lambda: cl.Regularised(law=cl.Coulomb(mu=0.1), velocity=0.0), r"Regularised\.velocity"),
])
def test_bad_parameters_name_the_field_and_range(make, message):
    with pytest.raises(ValueError, match=message):
        make()


@pytest.mark.parametrize("make, message", [
    (lambda: cl.LinearSpring(), r"missing 1 required keyword-only argument: 'stiffness'"),
    (lambda: cl.ExponentialFriction(mu_static=0.5, mu_kinetic=0.3),
     r"missing 1 required keyword-only argument: 'beta'"),
    (lambda: cl.LinearSpring(stiffness="1e5"), r"LinearSpring\.stiffness must be a real number"),
    (lambda: cl.Regularised(law=cl.LinearSpring(stiffness=1.0), velocity=1.0),
     r"Regularised\.law must be an exact FrictionLaw"),
])
def test_missing_or_mistyped_parameters_are_type_errors(make, message):
    with pytest.raises(TypeError, match=message):
        make()


def test_contact_laws_do_not_import_shroudnet():
    import subprocess
    import sys
    code = "import sys, contact_laws; assert 'shroudnet' not in sys.modules"
    subprocess.run([sys.executable, "-c", code], check=True)
