"""Contract tests, run over every law: built-in ones and a user's own; and every built-in
law against values computed by hand from the closed form its docstring states."""

import dataclasses
import math

import numba
import pytest
from hypothesis import assume, given
from hypothesis import strategies as st
from scipy.integrate import solve_ivp

import contact_laws as cl
from tests.laws import (EVERY_FRICTION_LAW, EVERY_NORMAL_LAW, CubicSpring, PreloadedStop,
                        RationalWeakening, static_limit)

NORMAL_IDS = [type(law).__name__ for law in EVERY_NORMAL_LAW]
FRICTION_IDS = [repr(law) for law in EVERY_FRICTION_LAW]

# Values of e^(−z) from tables (16 digits), so that no expected value below goes through
# the same math.exp as the law it checks.
EXP_M025 = 0.77880078307140487    # e^(−1/4)
EXP_M05 = 0.60653065971263342     # e^(−1/2)
EXP_M1 = 0.36787944117144233      # e^(−1)
EXP_M2 = 0.13533528323661270      # e^(−2)
EXP_M4 = 0.018315638888734180     # e^(−4)
EXP_M5 = 0.0067379469990854671    # e^(−5)

# (law, penetration δ [m], rate δ̇ [m/s], N [N] by hand from the docstring's formula).
NORMAL_VALUES = [
    # LinearSpring, N = k_c δ (paper eqs. 2–3): linear in δ, blind to δ̇.
    (cl.LinearSpring(stiffness=1e5), 2e-6, 0.0, 1e5 * 2e-6),
    (cl.LinearSpring(stiffness=1e5), 2e-6, 5.0, 1e5 * 2e-6),
    (cl.LinearSpring(stiffness=1e5), 1e-3, -3.0, 100.0),
    (cl.LinearSpring(stiffness=1e5), 0.0, 1.0, 0.0),
    # Hertz, N = k δ^n: (4 µm)^1.5 = 8e-9, (100 µm)^1.5 = 1e-6, (2 µm)^1.5 = 2√2 · 1e-9.
    (cl.Hertz(stiffness=1e9), 4e-6, 0.0, 1e9 * 8e-9),
    (cl.Hertz(stiffness=1e9), 1e-4, 0.7, 1e9 * 1e-6),
    (cl.Hertz(stiffness=1e9), 2e-6, -0.7, 1e9 * 2 * 1.4142135623730950 * 1e-9),
    (cl.Hertz(stiffness=1e6, exponent=1.0), 3e-6, 0.0, 1e6 * 3e-6),
    (cl.Hertz(stiffness=2e12, exponent=2.0), 1e-5, 0.0, 2e12 * 1e-10),
    (cl.Hertz(stiffness=1e9), 0.0, 0.0, 0.0),
    (cl.Hertz(stiffness=1e9), -1e-6, 0.0, 0.0),     # just past separation: 0, not NaN
    (cl.Hertz(stiffness=1e9), -1e-6, 2.0, 0.0),
    # KelvinVoigt, N = max(0, k δ + c δ̇): a separating contact never pulls.
    (cl.KelvinVoigt(stiffness=1e5, damping=20.0), 2e-6, 0.3, 1e5 * 2e-6 + 20.0 * 0.3),
    (cl.KelvinVoigt(stiffness=1e5, damping=20.0), 2e-6, -0.005, 0.2 - 20.0 * 0.005),
    (cl.KelvinVoigt(stiffness=1e5, damping=20.0), 2e-6, -0.3, 0.0),
    (cl.KelvinVoigt(stiffness=1e5, damping=20.0), 0.0, 0.0, 0.0),
    (cl.KelvinVoigt(stiffness=1e5, damping=20.0), 0.0, 0.1, 20.0 * 0.1),  # jumps at touch
    (cl.KelvinVoigt(stiffness=1e5, damping=20.0), -1e-6, -0.1, 0.0),
    # HuntCrossley, N = max(0, k δ^n (1 + d δ̇)).
    (cl.HuntCrossley(stiffness=1e8, damping=0.5), 4e-6, 0.2, 1e8 * 8e-9 * (1 + 0.5 * 0.2)),
    (cl.HuntCrossley(stiffness=1e8, damping=0.5), 4e-6, 0.0, 1e8 * 8e-9),
    (cl.HuntCrossley(stiffness=1e8, damping=0.5), 4e-6, -1.0, 1e8 * 8e-9 * (1 - 0.5)),
    (cl.HuntCrossley(stiffness=1e8, damping=0.5), 4e-6, -3.0, 0.0),
    (cl.HuntCrossley(stiffness=1e6, damping=2.0, exponent=1.0), 5e-6, 0.25,
     1e6 * 5e-6 * (1 + 2.0 * 0.25)),
    (cl.HuntCrossley(stiffness=1e8, damping=0.5), 0.0, 5.0, 0.0),  # continuous at touch
    (cl.HuntCrossley(stiffness=1e8, damping=0.5), -1e-6, 5.0, 0.0),
    # ConstantLoad, N = F whatever δ and δ̇.
    (cl.ConstantLoad(force=10.0), 2e-6, 0.3, 10.0),
    (cl.ConstantLoad(force=10.0), -1e-6, -2.0, 10.0),
    (cl.ConstantLoad(force=0.0), 1e-3, 0.0, 0.0),
    # The test suite's own laws, N = k1 δ + k3 δ³ and N = F0 + k δ.
    (CubicSpring(linear=1e5, cubic=1e13), 1e-4, 0.0, 1e5 * 1e-4 + 1e13 * 1e-12),
    (PreloadedStop(preload=2.0, stiffness=1e5), 1e-5, 0.0, 2.0 + 1e5 * 1e-5),
]

# (law, slip speed v [m/s], μ by hand from the docstring's formula).
PAPER_EQ4 = cl.ExponentialFriction(mu_static=0.5, mu_kinetic=0.3, beta=5.0)
FRICTION_VALUES = [
    # Coulomb, μ(v) = μ at every speed.
    (cl.Coulomb(mu=0.3), 0.0, 0.3),
    (cl.Coulomb(mu=0.3), 1e-9, 0.3),
    (cl.Coulomb(mu=0.3), 100.0, 0.3),
    # The paper's eq. (4) at its numbers: μ = μ_m + (μ_s − μ_m) e^(−β|v|), μ_s = 0.5,
    # μ_m = 0.3, β = 5 s/m.
    (PAPER_EQ4, 0.0, 0.5),
    (PAPER_EQ4, 0.1, 0.3 + 0.2 * EXP_M05),
    (PAPER_EQ4, 0.2, 0.3 + 0.2 * EXP_M1),
    (PAPER_EQ4, 1.0, 0.3 + 0.2 * EXP_M5),
    (PAPER_EQ4, math.inf, 0.3),
    (cl.ExponentialFriction(mu_static=0.5, mu_kinetic=0.3, beta=0.0), 7.0, 0.5),
    # Stribeck, μ = μ_k + (μ_s − μ_k) exp(−(v/v_s)^δ).
    (cl.Stribeck(mu_static=0.6, mu_kinetic=0.2, stribeck_velocity=0.01), 0.0, 0.6),
    (cl.Stribeck(mu_static=0.6, mu_kinetic=0.2, stribeck_velocity=0.01), 0.005,
     0.2 + 0.4 * EXP_M025),
    (cl.Stribeck(mu_static=0.6, mu_kinetic=0.2, stribeck_velocity=0.01), 0.01,
     0.2 + 0.4 * EXP_M1),
    (cl.Stribeck(mu_static=0.6, mu_kinetic=0.2, stribeck_velocity=0.01), 0.02,
     0.2 + 0.4 * EXP_M4),
    (cl.Stribeck(mu_static=0.6, mu_kinetic=0.2, stribeck_velocity=0.01), math.inf, 0.2),
    (cl.Stribeck(mu_static=0.6, mu_kinetic=0.2, stribeck_velocity=0.01, exponent=1.0), 0.02,
     0.2 + 0.4 * EXP_M2),
    # Regularised keeps the exact law's coefficient (the tanh shapes the force, see
    # test_dynamics_properties).
    (cl.Regularised(law=cl.Coulomb(mu=0.3), velocity=1e-3), 0.0, 0.3),
    (cl.Regularised(law=PAPER_EQ4, velocity=1e-3), 0.1, 0.3 + 0.2 * EXP_M05),
    # The test suite's own law, μ = μ_k + (μ_s − μ_k)/(1 + v/v_c).
    (RationalWeakening(mu_static=0.5, mu_kinetic=0.25, speed=0.05), 0.05, 0.25 + 0.25 / 2),
]


def _name(row):
    law, *point = row
    return f"{type(law).__name__}{tuple(point[:-1])}"


@pytest.mark.parametrize("law, penetration, rate, expected", NORMAL_VALUES,
                         ids=list(map(_name, NORMAL_VALUES)))
def test_normal_laws_give_their_closed_form_by_hand(law, penetration, rate, expected):
    """The law object, and its ``normal_force`` as numba compiles it into the integrator's
    loop (shroudnet.engine.generate), both give the hand-computed N."""
    compiled = numba.njit(type(law).normal_force)
    for force in (law(penetration, rate), compiled(penetration, rate, *law.parameters())):
        assert force == pytest.approx(expected, rel=1e-14, abs=0.0)


@pytest.mark.parametrize("law, speed, expected", FRICTION_VALUES,
                         ids=list(map(_name, FRICTION_VALUES)))
def test_friction_laws_give_their_closed_form_by_hand(law, speed, expected):
    """μ(v) and μ(−v) of the law object, and its compiled ``coefficient``, equal the hand
    value: friction is symmetric in the slip velocity."""
    compiled = numba.njit(type(law.exact).coefficient)
    for mu in (law(speed), law(-speed), compiled(speed, *law.parameters())):
        assert mu == pytest.approx(expected, rel=1e-14, abs=0.0)


@pytest.mark.parametrize("law", EVERY_FRICTION_LAW, ids=FRICTION_IDS)
def test_static_coefficient_is_the_given_mu_s_and_the_limit_at_zero_speed(law):
    """μ(0) = μ_s = static_coefficient, with μ_s the parameter the law was given."""
    assert law(0.0) == law.static_coefficient == static_limit(law)


@pytest.mark.parametrize("make, mu_s, mu_k", [
    (lambda s, k: cl.ExponentialFriction(mu_static=s, mu_kinetic=k, beta=5.0), 0.5, 0.3),
    (lambda s, k: cl.Stribeck(mu_static=s, mu_kinetic=k, stribeck_velocity=0.01), 0.6, 0.2),
    (lambda s, k: cl.Stribeck(mu_static=s, mu_kinetic=k, stribeck_velocity=0.01,
                              exponent=0.5), 0.6, 0.2),
])
def test_velocity_weakening_falls_from_mu_s_to_mu_k(make, mu_s, mu_k):
    """μ(0) = μ_s, μ decreases strictly with speed until it reaches μ_k in floating
    point, and μ(v) → μ_k as v → ∞."""
    law = make(mu_s, mu_k)
    speeds = [0.0, 1e-4, 1e-3, 1e-2, 0.1, 1.0]
    values = [law(v) for v in speeds]
    assert values[0] == mu_s
    assert all(a > b or a == b == mu_k for a, b in zip(values, values[1:]))
    assert law(1e6) == pytest.approx(mu_k, abs=1e-12) and law(math.inf) == mu_k


@pytest.mark.parametrize("restitution", [0.99, 0.95])
def test_hunt_crossley_damping_of_lankarani_nikravesh_gives_the_restitution(restitution):
    """Docstring claim: d = 3(1 − e²)/(4 v₀) makes an impact at v₀ rebound with e.

    Lankarani & Nikravesh, J. Mech. Des. 112 (1990) 369, derive d to first order in
    1 − e, so the rebound ratio of the exact impact m δ̈ = −N(δ, δ̇) (integrated here
    with scipy, not shroudnet) may differ from e by O((1 − e)²): at most 2 (1 − e)².
    """
    mass, speed = 0.1, 0.5
    law = cl.HuntCrossley(stiffness=1e9, damping=3 * (1 - restitution**2) / (4 * speed))

    def motion(t, y):
        return [y[1], -law(y[0], y[1]) / mass]

    def separation(t, y):
        return y[0]
    separation.terminal, separation.direction = True, -1
    impact = solve_ivp(motion, (0.0, 1.0), [0.0, speed], events=separation, method="DOP853",
                       rtol=1e-12, atol=1e-16, first_step=1e-9)
    rebound = -impact.y_events[0][-1][1] / speed
    assert abs(rebound - restitution) <= 2 * (1 - restitution) ** 2


@pytest.mark.parametrize("law", EVERY_NORMAL_LAW, ids=NORMAL_IDS)
@given(penetration=st.floats(1e-9, 1e-3), rate=st.floats(-10.0, 10.0))
def test_normal_force_is_finite_and_never_pulls(law, penetration, rate):
    force = law(penetration, rate)
    assert math.isfinite(force) and force >= 0.0


@pytest.mark.parametrize("law", EVERY_NORMAL_LAW, ids=NORMAL_IDS)
@given(penetration=st.floats(-1e-6, 0.0), rate=st.floats(-10.0, 10.0))
def test_normal_force_is_finite_just_past_separation(law, penetration, rate):
    """A trial state inside a step that separates holds δ slightly below 0 (a Hertz law
    once gave NaN there and stalled the adaptive step); the force there is finite and
    small: no more than the law gives at |δ|."""
    force = law(penetration, rate)
    assert math.isfinite(force)
    if law.opens:
        assert abs(force) <= law(-penetration, max(rate, 0.0)) * (1 + 1e-12) + 1e-300


@pytest.mark.parametrize("law", [law for law in EVERY_NORMAL_LAW if law.opens], ids=str)
def test_normal_force_grows_from_zero_with_penetration_at_rest(law):
    assert law(0.0) == 0.0
    assert law(1e-12) < law(1e-6) < law(1e-5)


@pytest.mark.parametrize("law", EVERY_FRICTION_LAW, ids=FRICTION_IDS)
@given(speed=st.floats(0.0, 100.0))
def test_friction_coefficient_is_bounded_by_the_static_one(law, speed):
    mu = law(speed)
    assert 0.0 <= mu <= static_limit(law)
    assert law(-speed) == mu


@pytest.mark.parametrize("law", EVERY_NORMAL_LAW + EVERY_FRICTION_LAW,
                         ids=NORMAL_IDS + FRICTION_IDS)
def test_laws_are_immutable(law):
    field = dataclasses.fields(law)[0].name
    with pytest.raises(dataclasses.FrozenInstanceError):
        setattr(law, field, 1.0)


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


# ---- derivatives, for tangent dynamics -----------------------------------------------------

def _richardson(function, at, step):
    """f'(at) by Richardson-extrapolated central differences: error O(step⁴), written here
    so that no derivative below is checked against the code it checks."""
    def central(h):
        return (function(at + h) - function(at - h)) / (2.0 * h)
    return (4.0 * central(step / 2.0) - central(step)) / 3.0


BUILT_IN_NORMAL = [law for law in EVERY_NORMAL_LAW if type(law).__module__.startswith("contact")]
BUILT_IN_FRICTION = [law for law in EVERY_FRICTION_LAW
                     if type(law).__module__.startswith("contact")]


@pytest.mark.parametrize("law", BUILT_IN_NORMAL, ids=str)
def test_every_built_in_normal_law_gives_its_gradient(law):
    assert law.has_analytic_gradient()


@pytest.mark.parametrize("law", BUILT_IN_FRICTION, ids=str)
def test_every_built_in_friction_law_gives_its_slope(law):
    assert (law.exact if isinstance(law, cl.Regularised) else law).has_analytic_slope()


@st.composite
def _smooth_normal_points(draw):
    """A built-in normal law with random parameters, and (δ, δ̇) at least 1 % of the way from
    any kink (touch, or the clipping of a damped force at zero)."""
    stiffness = draw(st.floats(1e4, 1e9))
    law = draw(st.sampled_from([
        cl.LinearSpring(stiffness=stiffness),
        cl.Hertz(stiffness=stiffness, exponent=draw(st.floats(1.0, 3.0))),
        cl.Hertz(stiffness=stiffness),  # n = 3/2 has a path of its own
        cl.KelvinVoigt(stiffness=stiffness, damping=draw(st.floats(0.0, 100.0))),
        cl.HuntCrossley(stiffness=stiffness, damping=draw(st.floats(0.0, 5.0)),
                        exponent=draw(st.floats(1.0, 3.0))),
        cl.ConstantLoad(force=draw(st.floats(0.0, 100.0))),
    ]))
    penetration = draw(st.floats(1e-7, 1e-3))
    rate = draw(st.floats(-10.0, 10.0))
    room = math.inf  # how far δ̇ may move before the force is clipped [m/s]
    if isinstance(law, cl.KelvinVoigt):
        clip = law.stiffness * penetration + law.damping * rate
        assume(abs(clip) > 0.01 * (law.stiffness * penetration + law.damping * abs(rate)))
        room = abs(clip) / law.damping if law.damping else math.inf
    if isinstance(law, cl.HuntCrossley):
        assume(abs(1.0 + law.damping * rate) > 0.01)
        room = abs(1.0 + law.damping * rate) / law.damping if law.damping else math.inf
    return law, penetration, rate, room


@given(point=_smooth_normal_points())
def test_normal_force_gradient_matches_finite_differences(point):
    law, penetration, rate, room = point
    d_penetration, d_rate = law.gradient(penetration, rate)
    expected_penetration = _richardson(lambda d: law(d, rate), penetration, 1e-3 * penetration)
    rate_step = min(1e-3 * max(abs(rate), 0.1), 0.1 * room)
    expected_rate = _richardson(lambda r: law(penetration, r), rate, rate_step)
    force_scale = law(penetration, abs(rate)) + 1e-300
    assert d_penetration == pytest.approx(expected_penetration, rel=1e-6,
                                          abs=1e-9 * force_scale / penetration)
    assert d_rate == pytest.approx(expected_rate, rel=1e-6, abs=1e-9 * force_scale)


def test_normal_force_gradient_is_zero_where_the_force_is_clipped():
    assert cl.Hertz(stiffness=1e9).gradient(-1e-6, 0.3) == (0.0, 0.0)
    assert cl.KelvinVoigt(stiffness=1e5, damping=20.0).gradient(2e-6, -0.3) == (0.0, 0.0)
    assert cl.HuntCrossley(stiffness=1e8, damping=0.5).gradient(4e-6, -3.0) == (0.0, 0.0)
    # where it is not: (k, c), and Hertz's k n δ^(n−1) at n = 3/2, δ = 4 µm
    assert cl.KelvinVoigt(stiffness=1e5, damping=20.0).gradient(2e-6, 0.3) == (1e5, 20.0)
    assert cl.Hertz(stiffness=1e9).gradient(4e-6)[0] == pytest.approx(1e9 * 1.5 * 2e-3)


@st.composite
def _friction_points(draw):
    mu_s = draw(st.floats(0.01, 2.0))
    mu_k = draw(st.floats(0.0, 1.0)) * mu_s
    law = draw(st.sampled_from([
        cl.Coulomb(mu=mu_s),
        cl.ExponentialFriction(mu_static=mu_s, mu_kinetic=mu_k, beta=draw(st.floats(0.0, 50.0))),
        cl.Stribeck(mu_static=mu_s, mu_kinetic=mu_k,
                    stribeck_velocity=draw(st.floats(1e-4, 1.0)),
                    exponent=draw(st.floats(0.2, 4.0))),
        cl.Stribeck(mu_static=mu_s, mu_kinetic=mu_k,  # δ = 2 has a path of its own
                    stribeck_velocity=draw(st.floats(1e-4, 1.0))),
    ]))
    return law, draw(st.floats(1e-5, 10.0))


@given(point=_friction_points())
def test_friction_slope_matches_finite_differences(point):
    law, speed = point
    expected = _richardson(law, speed, 1e-3 * speed)
    assert law.slope(speed) == pytest.approx(expected, rel=1e-6, abs=1e-9 * law(0.0) / speed)
    assert law.slope(-speed) == law.slope(speed)


def test_friction_slope_at_zero_speed_follows_the_stribeck_exponent():
    def stribeck(exponent):
        return cl.Stribeck(mu_static=0.6, mu_kinetic=0.2, stribeck_velocity=0.01,
                           exponent=exponent)
    assert stribeck(2.0).slope(0.0) == 0.0
    assert stribeck(1.0).slope(0.0) == pytest.approx(-0.4 / 0.01)
    assert stribeck(0.5).slope(0.0) == -math.inf
    assert cl.Regularised(law=PAPER_EQ4, velocity=1e-3).slope(0.1) == PAPER_EQ4.slope(0.1)
    assert PAPER_EQ4.slope(0.1) == pytest.approx(-5.0 * 0.2 * EXP_M05)


def test_a_user_law_without_derivatives_is_differentiated_by_central_differences():
    spring = CubicSpring(linear=1e5, cubic=1e13)
    assert not spring.has_analytic_gradient()
    stiffness, damping = spring.gradient(1e-4, 0.2)
    assert stiffness == pytest.approx(1e5 + 3 * 1e13 * 1e-8, rel=1e-8)
    assert damping == 0.0
    weakening = RationalWeakening(mu_static=0.5, mu_kinetic=0.25, speed=0.05)
    assert not weakening.has_analytic_slope()
    for speed in (0.0, 1e-4, 0.05, 3.0):
        exact = -0.25 / 0.05 / (1.0 + speed / 0.05) ** 2
        assert weakening.slope(speed) == pytest.approx(exact, rel=1e-4)
