"""The framework's assembled dynamics against the paper's own case equations (8)–(22).

The paper's dimensionless equations are transcribed here independently of the library, in
the paper's notation: X = x/Δ1, τ = ω t, X' = dX/dτ, Q̄ = Q/(m Δ1 ω²), N̄ = γ1 X_r sin α,
X_r1 = X1 − X2 − 1, X_r2 = X2 − X3 − K. Eq. (22) is used as corrected in DESIGN §5 (the
printed signs of its Q and C terms are inverted); μ(v_r) takes the physical slip velocity.
The scene is given the paper's friction law with μ_s = 0.5 here, so that the stick limit
μ_s N̄ is the paper's number, not one read back from the scene.
"""

import math

import numpy as np
import pytest
from hypothesis import given
from hypothesis import strategies as st

from contact_laws import ExponentialFriction
from shroudnet import Mode, assemble
from shroudnet.scenes import three_blade_paper

MU_S, MU_M, BETA = 0.5, 0.3, 5.0
#: The paper's eq. (4) law with its §3 numbers, given to the scene by the test.
PAPER_FRICTION = ExponentialFriction(mu_static=MU_S, mu_kinetic=MU_M, beta=BETA)

# The paper's cases: (contact 1, contact 2) with "open", "slip" or "stick" on each side.
CASES = {
    "1": ("open", "open"),
    "2a": ("slip", "open"), "2b": ("stick", "open"),
    "3a": ("open", "slip"), "3b": ("open", "stick"),
    "4a": ("slip", "slip"), "4b": ("slip", "stick"), "4c": ("stick", "slip"),
    "4d": ("stick", "stick"),
}


def mu(v_r):
    """Paper eq. (4)."""
    return MU_M + (MU_S - MU_M) * math.exp(-BETA * abs(v_r))


def paper_case(case, X, dX, Qb, eps, gamma1, alpha, K, v_r):
    """X'' of the three blades and the static friction forces f̄τ by the paper's case equations."""
    sa, ca = math.sin(alpha), math.cos(alpha)
    Xr1, Xr2 = X[0] - X[1] - 1.0, X[1] - X[2] - K
    N1 = gamma1 * Xr1 * sa if Xr1 > 0 else 0.0
    N2 = gamma1 * Xr2 * sa if Xr2 > 0 else 0.0
    C1, C2 = X[0] - X[1], X[1] - X[2]
    S1 = N1 * (sa + mu(v_r[0]) * ca * np.sign(v_r[0]))
    S2 = N2 * (sa + mu(v_r[1]) * ca * np.sign(v_r[1]))
    Q1, Q2, Q3 = Qb
    f1 = f2 = None
    if case == "1":                                                     # eq. (8)
        rhs = [Q1, Q2, Q3]
    elif case == "2a":                                                  # eq. (9)
        rhs = [Q1 - S1, Q2 + S1, Q3]
    elif case == "2b":                                                  # eqs. (10), (11)
        rhs = [(Q1 + Q2 + C1) / 2, (Q1 + Q2 - C1) / 2, Q3]
        f1 = -1 / (2 * ca) * (Q2 - Q1 + 2 * N1 * sa + C1)
    elif case == "3a":                                                  # eq. (12)
        rhs = [Q1, Q2 - S2, Q3 + S2]
    elif case == "3b":                                                  # eqs. (13), (14)
        rhs = [Q1, (Q2 + Q3 + C2) / 2, (Q2 + Q3 - C2) / 2]
        f2 = -1 / (2 * ca) * (Q3 - Q2 + 2 * N2 * sa + C2)
    elif case == "4a":                                                  # eq. (15)
        rhs = [Q1 - S1, Q2 + S1 - S2, Q3 + S2]
    elif case == "4b":                                                  # eqs. (16), (17)
        rhs = [Q1 - S1, (Q2 + S1 + Q3 + C2) / 2, (Q2 + S1 + Q3 - C2) / 2]
        f2 = -1 / (2 * ca) * (Q3 - Q2 - S1 + 2 * N2 * sa + C2)
    elif case == "4c":                                                  # eqs. (18), (19)
        rhs = [(Q1 + Q2 - S2 + C1) / 2, (Q1 + Q2 - S2 - C1) / 2, Q3 + S2]
        f1 = -1 / (2 * ca) * (Q2 - S2 - Q1 + 2 * N1 * sa + C1)
    elif case == "4d":                                                  # eqs. (20)–(22)
        total = Q1 + Q2 + Q3
        rhs = [(total + 2 * C1 + C2) / 3, (total - C1 + C2) / 3, (total - C1 - 2 * C2) / 3]
        f1 = -1 / (3 * ca) * (Q2 + Q3 - 2 * Q1 + 3 * N1 * sa + 2 * C1 + C2)
        f2 = -1 / (3 * ca) * (2 * Q3 - Q1 - Q2 + 3 * N2 * sa + C1 + 2 * C2)  # DESIGN §5
    ddX = np.array(rhs) - 2 * eps * np.asarray(dX) - np.asarray(X)
    return ddX, (N1, N2), (f1, f2)


@st.composite
def paper_states(draw):
    case = draw(st.sampled_from(sorted(CASES)))
    sides = CASES[case]
    params = dict(
        gamma1=draw(st.floats(0.1, 10.0)),
        speed_rpm=draw(st.floats(3000.0, 8000.0)),
        q1=draw(st.floats(0.0, 100.0)),
        alpha=draw(st.floats(0.1, math.pi / 2 - 0.1)),
    )
    delta1 = draw(st.floats(1e-6, 1e-4))
    K = draw(st.floats(0.2, 5.0))
    # Relative displacements and velocities in the paper's dimensionless units.
    Xr = [draw(st.floats(0.01, 5.0)) * (-1.0 if s == "open" else 1.0) for s in sides]
    dXr = [0.0 if s == "stick" else draw(st.floats(0.05, 3.0)) * draw(st.sampled_from([-1, 1]))
           for s in sides]
    X2, dX2 = draw(st.floats(-10.0, 10.0)), draw(st.floats(-3.0, 3.0))
    X = [X2 + 1.0 + Xr[0], X2, X2 - K - Xr[1]]
    dX = [dX2 + dXr[0], dX2, dX2 - dXr[1]]
    phase = draw(st.floats(0.0, 1.0))
    return case, params, delta1, K, X, dX, phase


def _mode(side, relative_velocity):
    if side == "open":
        return Mode.OPEN
    if side == "stick":
        return Mode.STICK
    return Mode.SLIP_POSITIVE if relative_velocity > 0 else Mode.SLIP_NEGATIVE


@given(paper_states())
def test_assembled_dynamics_match_the_papers_case_equations(sample):
    case, params, delta1, K, X, dX, phase = sample
    scene = three_blade_paper(gap=(delta1, K * delta1), friction=PAPER_FRICTION, **params)
    arrays = scene.arrays
    m, c, k = arrays.mass[0], arrays.damping[0], arrays.stiffness[0]
    omega = math.sqrt(k / m)
    eps = c / (2 * m * omega)
    force_unit = m * delta1 * omega**2
    t = phase * scene.excitation_period
    x = np.array(X) * delta1
    v = np.array(dX) * delta1 * omega
    modes = [_mode(side, dX[e] - dX[e + 1]) for e, side in enumerate(CASES[case])]

    result = assemble(scene, t, x, v, modes)

    q = np.array([params["q1"] * math.sin(2 * scene.omega * t + i * math.pi) for i in range(3)])
    v_r = [(v[0] - v[1]) * math.cos(params["alpha"]), (v[1] - v[2]) * math.cos(params["alpha"])]
    ddX, N, f = paper_case(case, X, dX, q / force_unit, eps, params["gamma1"], params["alpha"],
                           K, v_r)
    scale = max(1.0, np.abs(ddX).max())
    np.testing.assert_allclose(result.acceleration / (delta1 * omega**2), ddX,
                               rtol=1e-9, atol=1e-9 * scale)
    np.testing.assert_allclose(result.normal_force / force_unit, N, rtol=1e-9, atol=1e-12)
    for e, expected in enumerate(f):
        if expected is not None:
            assert result.friction_force[e] / force_unit == pytest.approx(
                expected, rel=1e-9, abs=1e-9 * scale)
            # A stuck contact holds while |f̄τ| ≤ μ_s N̄ (eq. 6 with μ(0) = μ_s = 0.5): the
            # breakaway margin is measured against that limit.
            assert result.motion_guard[e] / force_unit == pytest.approx(
                MU_S * N[e] - abs(expected), rel=1e-9, abs=1e-9 * scale)


def test_printed_eq22_violates_eq7_and_the_corrected_one_does_not():
    """DESIGN §5: the printed eq. (22) has the signs of its Q and C terms inverted."""
    scene = three_blade_paper(gamma1=2.0, q1=30.0)
    arrays = scene.arrays
    m, k, delta1 = arrays.mass[0], arrays.stiffness[0], arrays.gap[0]
    omega = math.sqrt(k / m)
    unit = m * delta1 * omega**2
    x = np.array([2.5, 0.7, -1.1]) * delta1
    t = 0.3 * scene.excitation_period
    result = assemble(scene, t, x, np.full(3, 0.01), [Mode.STICK, Mode.STICK])
    Qb = np.array([30.0 * math.sin(2 * scene.omega * t + i * math.pi) for i in range(3)]) / unit
    X = x / delta1
    C1, C2 = X[0] - X[1], X[1] - X[2]
    N2 = 2.0 * (C2 - 1.0) * math.sin(math.pi / 3)
    ca, sa = math.cos(math.pi / 3), math.sin(math.pi / 3)
    printed = -1 / (3 * ca) * (Qb[0] + Qb[1] - 2 * Qb[2] + 3 * N2 * sa - C1 - 2 * C2)
    corrected = -1 / (3 * ca) * (2 * Qb[2] - Qb[0] - Qb[1] + 3 * N2 * sa + C1 + 2 * C2)
    assert result.friction_force[1] / unit == pytest.approx(corrected, rel=1e-10)
    assert abs(result.friction_force[1] / unit - printed) > 0.1
