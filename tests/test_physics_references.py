"""The physics through ``simulate``, each result against a reference derived here by hand.

Every scene is a set of independent blades, each facing its own fixed pad across one
interface (u = x, the blade's own displacement), so that eq. (7) reduces to

    m ẍ + c ẋ + k x = Q(t) − N sin α − f cos α,       δ = (x − Δ) sin α,  v = ẋ cos α,

and the expected values follow in closed form. Tolerances follow from the run's settings:
a switch is located to within the event tolerance, in a time bracket whose end, just past
the switch, is where the run restarts and what the log holds; each adaptive step holds its
local error to rtol·|y| + atol, so n steps carry an error of at most n times that.

A scene's law classes decide which compiled kernel it runs on. So that this file compiles
one kernel, not one per combination, every scene here also holds idle blades carrying the
built-in laws a test does not drive: unforced (excitation scale 0) and at rest, far from
their pads or held by a large friction limit, they stay at rest exactly and add nothing
to any result.
"""

import math

import numpy as np
import pytest
from scipy.optimize import brentq

from contact_laws import (ConstantLoad, Coulomb, ExponentialFriction, Hertz, HuntCrossley,
                          KelvinVoigt, LinearSpring, Regularised, Stribeck)
from shroudnet import (Adaptive, Blade, BladeGroup, EventKind, Excitation, Interface, Mode,
                       Scene, simulate)
from tests.laws import static_limit

SPEED_RPM = 6000.0   # with engine order 1: f_e = 100 Hz
PERIOD = 60.0 / SPEED_RPM          # T_e [s]
OMEGA = 2.0 * math.pi / PERIOD     # excitation frequency lΩ [rad/s]
EVENT_TOLERANCE = 1e-10            # periods: simulate's default
PRECISE = Adaptive(rtol=1e-10, atol=1e-15)
BLADE = Blade(mass=0.1, damping=2.0, stiffness=1e5)
FAR = 1.0  # m: a gap no blade here comes near

#: Idle blades, unforced, and one interface for every built-in exact law. The
#: ConstantLoad pad holds its blade by a friction limit of 1 kN; the others are never
#: reached.
IDLE_BLADE = Blade(mass=0.1, damping=2.0, stiffness=1e5, excitation_scale=0.0)
IDLE = (
    Interface(gap=0.0, angle=0.0, normal=ConstantLoad(force=1e3), friction=Coulomb(mu=1.0)),
    Interface(gap=FAR, angle=1.0, normal=LinearSpring(stiffness=1e6),
              friction=ExponentialFriction(mu_static=0.5, mu_kinetic=0.3, beta=5.0)),
    Interface(gap=FAR, angle=1.0, normal=Hertz(stiffness=1e9),
              friction=Stribeck(mu_static=0.6, mu_kinetic=0.2, stribeck_velocity=0.01)),
    Interface(gap=FAR, angle=1.0, normal=KelvinVoigt(stiffness=1e6, damping=10.0)),
    Interface(gap=FAR, angle=1.0, normal=HuntCrossley(stiffness=1e9, damping=0.1)),
)


def facing_pads(pairs, amplitudes=(0.0,)):
    """Blades "blade1", "blade2", … (positions 0, 1, …) each facing its own fixed pad
    "pad1", "pad2", … across its interface, then the ``IDLE`` blades.

    ``pairs`` holds (Blade, Interface). Every driven blade feels Q(t) = q0 + q1 sin(ωt), with
    ``amplitudes`` = (q0, q1) or (q0,), and ω = 2π/T_e.
    """
    group = BladeGroup()
    named = [(f"blade{k}", f"pad{k}", blade, interface)
             for k, (blade, interface) in enumerate(pairs, start=1)]
    named += [(f"idle{k}", f"idle_pad{k}", IDLE_BLADE, interface)
              for k, interface in enumerate(IDLE, start=1)]
    for name, pad, blade, interface in named:
        group.add_blade(name, blade).add_fixed(pad).connect(name, pad, interface)
    excitation = Excitation(engine_order=1, amplitudes=amplitudes, phases=[0.0] * len(named))
    return Scene(group=group, excitation=excitation, speed_rpm=SPEED_RPM)


def run(pairs, periods, x0, v0, amplitudes=(0.0,), samples_per_period=100):
    """``simulate`` the ``facing_pads`` scene from x0, v0 (the driven blades; idle ones at
    rest) with ``PRECISE`` settings."""
    idle = [0.0] * len(IDLE)
    return simulate(facing_pads(pairs, amplitudes), periods, method=PRECISE,
                    samples_per_period=samples_per_period,
                    initial=(list(x0) + idle, list(v0) + idle))


def state_bound(sim, x_scale, v_scale):
    """How far the run's n adaptive steps may carry the state, (δx [m], δv [m/s]) for
    displacements up to ``x_scale`` and velocities up to ``v_scale``: each step holds its
    local error to rtol·|x| + atol and rtol·|ẋ| + atol·lΩ, so n (rtol·scale + atol)."""
    n, rtol, atol = sim.steps, sim.settings["rtol"], sim.settings["atol"]
    return n * (rtol * x_scale + atol), n * (rtol * v_scale + atol * OMEGA)


def energy_bound(sim, x_scale, v_scale, force, mass):
    """How far an energy [J] may be off after the run: an error δx in a displacement moves
    it by at most ``force`` δx (the largest force doing work there), and δv by at most
    m v δv."""
    dx, dv = state_bound(sim, x_scale, v_scale)
    return force * dx + mass * v_scale * dv


def first_event(sim, interface, kind):
    """Time [s] of the first event of ``kind`` on ``interface``, or None."""
    log = sim.events
    times = log.time[(log.interface == interface) & (log.kind == kind)]
    return float(times[0]) if len(times) else None


def assert_located(logged, expected, slack=0.0):
    """Each logged switch lies in [t* − slack, t* + tol·T_e + slack] of its expected time
    t* [s]: the bracket of the event tolerance, widened by ``slack`` [s] where the motion
    that leads to the switch carries an integration error (and by the rounding of t*)."""
    logged, expected = np.array(logged, dtype=float), np.array(expected, dtype=float)
    late = logged - expected
    early = slack + 4e-16 * expected
    assert ((late >= -early) & (late <= EVENT_TOLERANCE * PERIOD + slack)).all(), \
        f"logged − expected, in event tolerances: {late / (EVENT_TOLERANCE * PERIOD)}"


# ---- 1. the stick limit: breakaway when the static friction reaches μ_s N ---------------

Q1 = 10.0  # N


def exponential(mu_s):
    return ExponentialFriction(mu_static=mu_s, mu_kinetic=0.5 * mu_s, beta=5.0)


def stribeck(mu_s):
    return Stribeck(mu_static=mu_s, mu_kinetic=0.25 * mu_s, stribeck_velocity=0.01)


def friction_coefficient(law, speed):
    """μ(|v|) of the built-in exact laws, written out from their definitions."""
    if isinstance(law, Coulomb):
        return law.mu
    if isinstance(law, ExponentialFriction):  # the paper's eq. (4)
        return law.mu_kinetic + (law.mu_static - law.mu_kinetic) * math.exp(-law.beta * speed)
    if isinstance(law, Stribeck):
        return law.mu_kinetic + (law.mu_static - law.mu_kinetic) * math.exp(
            -(speed / law.stribeck_velocity) ** law.exponent)
    raise TypeError(law)


def held_friction(t, x0, load, alpha, amplitudes):
    """Static friction [N] that holds a blade at rest at x0 against its pad.

    With ẋ = ẍ = 0, eq. (7) leaves 0 = Q(t) − k x0 − N sin α − f cos α, so
    f = (Q(t) − k x0 − N sin α) / cos α.
    """
    q = amplitudes[0] + amplitudes[1] * np.sin(OMEGA * np.asarray(t))
    return (q - BLADE.stiffness * x0 - load * math.sin(alpha)) / math.cos(alpha)


def assert_held_then_slipping(sim, b, x0, load, alpha, law, breakaway):
    """Before ``breakaway`` [s] (None: never) blade b rests at x0 holding the closed-form
    static friction; every slipping sample carries f = μ(|v|) N sgn(v), μ written out here;
    N is the constant load at every sample, and |f| ≤ μ_s N at every sample."""
    amplitudes = sim.scene.arrays.amplitudes
    held = sim.t < (np.inf if breakaway is None else breakaway)
    assert (sim.modes[held, b] == Mode.STICK).all()
    assert (sim.x[held, b] == x0).all() and (sim.v[held, b] == 0.0).all()
    np.testing.assert_allclose(sim.friction_force[held, b],
                               held_friction(sim.t[held], x0, load, alpha, amplitudes),
                               rtol=1e-12, atol=1e-12 * load)
    assert (sim.normal_force[:, b] == load).all()  # ConstantLoad: always closed, N = F
    slipping = np.isin(sim.modes[:, b], [Mode.SLIP_POSITIVE, Mode.SLIP_NEGATIVE])
    slip = sim.v[slipping, b] * math.cos(alpha)
    sign = np.where(sim.modes[slipping, b] == Mode.SLIP_POSITIVE, 1.0, -1.0)
    mu = np.array([friction_coefficient(law, abs(s)) for s in slip])
    np.testing.assert_allclose(sim.friction_force[slipping, b], sign * mu * load, rtol=1e-12)
    assert (np.abs(sim.friction_force[:, b])
            <= static_limit(law) * load * (1.0 + 1e-9)).all()


def test_breakaway_comes_when_the_static_friction_reaches_mu_s_times_the_load():
    """A blade held at rest at x0 against a pad pressed with a constant load N
    (ConstantLoad) sticks while the static friction of ``held_friction``,
    f = (Q − k x0 − N sin α)/cos α, stays within ±μ_s N. Under Q = q1 sin ωt, rising from
    0, it breaks away when Q(t*) = k x0 + N sin α + μ_s N cos α, at
    t* = arcsin((k x0 + N sin α + μ_s N cos α)/q1)/ω, provided the held friction starts
    within the limit (k x0 + N sin α − μ_s N cos α < 0 < k x0 + N sin α + μ_s N cos α).
    Three blades, each with its own law, load, angle and rest position, break away at
    three times; the laws' kinetic coefficients (below μ_s) must not enter.

    The stuck blade does not move, so the static friction is exact and the only error in
    the logged time is the bracket of the event tolerance (the rounding of Q near t*, with
    a slope of ~10³ N/s, is far below it).
    """
    cases = [  # (law, N [N], α [rad], x0 [m])
        (Coulomb(mu=0.4), 8.0, 0.3, 0.0),
        (exponential(0.6), 5.0, 0.6, -3e-5),
        (stribeck(0.8), 6.0, 0.2, 2e-5),
    ]
    pairs = [(BLADE, Interface(gap=0.0, angle=alpha, normal=ConstantLoad(force=load),
                               friction=law)) for law, load, alpha, _ in cases]
    sim = run(pairs, 1, [x0 for *_, x0 in cases], [0.0] * len(cases), (0.0, Q1),
              samples_per_period=200)
    expected, logged = [], []
    for b, (law, load, alpha, x0) in enumerate(cases):
        mu_s = static_limit(law)
        rest = BLADE.stiffness * x0 + load * math.sin(alpha)
        assert rest - mu_s * load * math.cos(alpha) < 0.0 < rest + mu_s * load * math.cos(alpha)
        expected.append(math.asin((rest + mu_s * load * math.cos(alpha)) / Q1) / OMEGA)
        logged.append(first_event(sim, b, EventKind.BREAKAWAY))
        assert logged[-1] is not None
        assert sim.events.time[sim.events.interface == b][0] == logged[-1]  # its first switch
        assert_held_then_slipping(sim, b, x0, load, alpha, law, logged[-1])
    assert min(np.diff(sorted(expected))) > 0.05 * PERIOD
    assert_located(logged, expected)


@pytest.mark.parametrize("ratio", [0.99, 1.01])
def test_a_force_peak_at_0_99_of_the_limit_holds_and_at_1_01_breaks_away(ratio):
    """Centre each blade's stick window on Q = 0 (x0 = −N sin α / k, so that the held
    friction is f = Q/cos α) and size it by the load: μ_s N cos α = q1 / ``ratio``. With
    the force peak q1 at 0.99 of the limit no blade ever breaks away and the held friction
    follows Q(t)/cos α for three periods; at 1.01 of it, each breaks away at
    sin ωt* = 1/1.01, in the first period, within a window of 2 arccos(1/1.01)/ω (4.5 %
    of a period) where the needed friction exceeds the limit."""
    laws = [Coulomb(mu=0.4), exponential(0.6), stribeck(0.8)]
    alpha = 0.4
    loads = [Q1 / (ratio * static_limit(law) * math.cos(alpha)) for law in laws]
    rests = [-load * math.sin(alpha) / BLADE.stiffness for load in loads]
    pairs = [(BLADE, Interface(gap=0.0, angle=alpha, normal=ConstantLoad(force=load),
                               friction=law)) for law, load in zip(laws, loads)]
    sim = run(pairs, 3, rests, [0.0] * len(laws), (0.0, Q1))
    logged = [first_event(sim, b, EventKind.BREAKAWAY) for b in range(len(laws))]
    if ratio < 1.0:
        assert logged == [None] * len(laws) and sum(sim.events.counts.values()) == 0
    else:
        assert None not in logged, "a breakaway was missed"
    for b, (law, load, x0) in enumerate(zip(laws, loads, rests)):
        assert_held_then_slipping(sim, b, x0, load, alpha, law, logged[b])
    if ratio > 1.0:
        assert_located(logged, [math.asin(1.0 / ratio) / OMEGA] * len(laws))


# ---- 2. the energy ledger against closed forms -------------------------------------------

def test_a_block_sliding_under_a_constant_load_loses_mu_n_cos_alpha_per_metre():
    """An undamped blade slides from x0 = 0 at v0 > 0 against a pad pressed with N
    (ConstantLoad, Coulomb μ). While ẋ > 0, eq. (7) is m ẍ + k x = −F0 with
    F0 = N (sin α + μ cos α): a harmonic motion about x_e = −F0/k,
    x(t) = x_e + A cos ωt + (v0/ω) sin ωt, A = x0 − x_e, ω = √(k/m). It stops at
    t1 = atan2(v0/ω, A)/ω, at x1 = x_e + R, R = √(A² + (v0/ω)²), and sticks there if the
    held friction (−k x1 − N sin α)/cos α is within ±μ N. The friction force μN does work
    μ N cos α per metre of x (the slip velocity is ẋ cos α), so the friction loss is
    μ N cos α (x1 − x0); the stored energy changes by ½ k x1² − ½ m v0² plus the constant
    load's contact energy ∫₀^δ N ds = N δ, which grows by N sin α (x1 − x0).
    """
    mass, stiffness, load, alpha, mu = 0.1, 100.0, 1.0, 0.2, 0.4
    v0 = 0.1
    blade = Blade(mass=mass, damping=0.0, stiffness=stiffness)
    pair = (blade, Interface(gap=0.0, angle=alpha, normal=ConstantLoad(force=load),
                             friction=Coulomb(mu=mu)))
    sim = run([pair], 3, [0.0], [v0])
    w = math.sqrt(stiffness / mass)
    push = load * (math.sin(alpha) + mu * math.cos(alpha))
    x_e = -push / stiffness
    amplitude = math.hypot(-x_e, v0 / w)
    t1 = math.atan2(v0 / w, -x_e) / w
    x1 = x_e + amplitude
    held = (-stiffness * x1 - load * math.sin(alpha)) / math.cos(alpha)
    assert abs(held) <= mu * load and t1 < 2 * PERIOD
    reach = amplitude - x_e  # the largest |x|
    dx, dv = state_bound(sim, reach, v0)
    slack = dv / (w * w * amplitude)  # the velocity error over the deceleration ω² R
    assert sim.events.counts == {"closing": 0, "separation": 0, "sticking": 1, "reversal": 0,
                                 "breakaway": 0}
    assert_located([first_event(sim, 0, EventKind.STICKING)], [t1], slack)
    sliding = sim.t < t1
    expected = np.where(sliding, x_e - x_e * np.cos(w * sim.t) + v0 / w * np.sin(w * sim.t),
                        x1)
    assert np.abs(sim.x[:, 0] - expected).max() <= dx + v0 * slack
    assert (sim.friction_force[sliding, 0] == mu * load).all()
    np.testing.assert_allclose(sim.friction_force[~sliding, 0], held, rtol=1e-9)
    energy = 0.5 * mass * v0**2
    tolerance = energy_bound(sim, reach, v0, push + stiffness * reach, mass)
    ledger = sim.energy
    assert ledger.friction_loss == pytest.approx(mu * load * math.cos(alpha) * x1,
                                                 abs=tolerance)
    stored = 0.5 * stiffness * x1**2 + load * math.sin(alpha) * x1 - energy
    assert ledger.stored_change == pytest.approx(stored, abs=tolerance)
    assert ledger.excitation_work == ledger.damping_loss == 0.0
    assert ledger.contact_loss == pytest.approx(0.0, abs=tolerance)  # N δ̇ integrates to N Δδ


def test_a_free_damped_oscillation_stores_and_loses_what_the_closed_form_says():
    """No contact (the pad is 1 m away): m ẍ + c ẋ + k x = 0 from x0 at rest gives, with
    σ = c/2m, ω_d = √(k/m − σ²),
    x(t) = x0 e^{−σt} (cos ω_d t + (σ/ω_d) sin ω_d t),  ẋ(t) = −x0 (k/m ω_d) e^{−σt} sin ω_d t.
    The stored energy E = ½ m ẋ² + ½ k x² falls from E0 = ½ k x0², and dE/dt = −c ẋ², so
    the damping loss up to t is E0 − E(t), sample by sample."""
    blade = Blade(mass=0.1, damping=10.0, stiffness=1e5)
    x0 = 1e-4
    pair = (blade, Interface(gap=FAR, angle=1.0, normal=LinearSpring(stiffness=1e6)))
    sim = run([pair], 3, [x0], [0.0])
    m, c, k = blade.mass, blade.damping, blade.stiffness
    sigma = c / (2 * m)
    wd = math.sqrt(k / m - sigma**2)
    decay = np.exp(-sigma * sim.t)
    x = x0 * decay * (np.cos(wd * sim.t) + sigma / wd * np.sin(wd * sim.t))
    v = -x0 * k / (m * wd) * decay * np.sin(wd * sim.t)
    stored = 0.5 * m * v**2 + 0.5 * k * x**2
    e0 = 0.5 * k * x0**2
    dx, dv = state_bound(sim, x0, x0 * math.sqrt(k / m))
    assert np.abs(sim.x[:, 0] - x).max() <= dx
    assert np.abs(sim.v[:, 0] - v).max() <= dv
    tolerance = energy_bound(sim, x0, x0 * math.sqrt(k / m), k * x0, m)
    assert np.abs(sim.work[:, 1] - (e0 - stored)).max() <= tolerance
    ledger = sim.energy
    assert ledger.stored_change == pytest.approx(stored[-1] - e0, abs=tolerance)
    assert ledger.damping_loss == pytest.approx(e0 - stored[-1], abs=tolerance)
    assert ledger.excitation_work == ledger.friction_loss == ledger.contact_loss == 0.0
    assert sum(sim.events.counts.values()) == 0


@pytest.mark.parametrize("law, strain_energy, stiffness_at", [
    (LinearSpring(stiffness=1e6),
     lambda d: 0.5 * 1e6 * d**2, lambda d: 1e6),
    (Hertz(stiffness=1e8),
     lambda d: 0.4 * 1e8 * d**2.5, lambda d: 1.5 * 1e8 * d**0.5),
], ids=["LinearSpring", "Hertz"])
def test_contact_strain_energy_at_a_known_penetration(law, strain_energy, stiffness_at):
    """A preloaded contact (gap Δ < 0) settles, heavily damped, at the static penetration
    δ_eq = 10 μm: there k x_eq + N(δ_eq) sin α = 0, so x_eq = −N(δ_eq) sin α / k and
    Δ = x_eq − δ_eq / sin α. Starting at rest at x = 0 (δ0 = −Δ sin α), the stored energy
    changes by ½ k x_eq² + E(δ_eq) − E(δ0), with the contact strain energy
    E(δ) = ∫₀^δ N ds: ½ k_c δ² for the linear spring, (2/5) k δ^{5/2} for Hertz; all of it
    goes to damping. N = k_c δ or k δ^{3/2} at every sample.

    The motion is overdamped all along (c² > 4 m (k + N'(δ) sin² α) for δ in [δ_eq, δ0]),
    so from rest it creeps to x_eq without overshoot and the contact never opens. Near
    x_eq it decays as e^{−λt}, λ = (c − √(c² − 4 m K))/2m with K = k + N'(δ_eq) sin² α: after
    five periods (λ ≥ 890/s) nothing of the start is left (e^{−44}). The ledger takes E(δ)
    by 16-point Gauss–Legendre quadrature, exact for the linear spring; for δ^{3/2} its
    error is of order 16^{−5} (the rule's error on s^a over [0, 1] falls as n^{−2a−2}).
    """
    blade = Blade(mass=0.1, damping=600.0, stiffness=1e5)
    m, c, k = blade.mass, blade.damping, blade.stiffness
    alpha = math.pi / 3
    s = math.sin(alpha)
    depth = 1e-5
    x_eq = -law(depth) * s / k
    gap = x_eq - depth / s
    start = -gap * s
    assert all(c * c > 4 * m * (k + stiffness_at(d) * s * s) for d in np.linspace(depth, start))
    pair = (blade, Interface(gap=gap, angle=alpha, normal=law))
    sim = run([pair], 5, [0.0], [0.0])
    assert sum(sim.events.counts.values()) == 0 and (sim.modes[:, 0] != Mode.OPEN).all()
    penetration = (sim.x[:, 0] - gap) * s
    forces = np.array([law(d) for d in penetration])  # closed form through the law's own
    np.testing.assert_allclose(sim.normal_force[:, 0], forces, rtol=1e-12)
    np.testing.assert_allclose(
        sim.normal_force[:, 0],
        law.stiffness * penetration ** (1.0 if isinstance(law, LinearSpring) else 1.5),
        rtol=1e-12)
    stiffness = k + stiffness_at(depth) * s * s
    rate = (c - math.sqrt(c * c - 4 * m * stiffness)) / (2 * m)
    assert rate * sim.t[-1] > 40.0
    assert sim.x[-1, 0] == pytest.approx(x_eq, rel=1e-9)
    expected = 0.5 * k * x_eq**2 + strain_energy(depth) - strain_energy(start)
    quadrature = 0.0 if isinstance(law, LinearSpring) else 16.0**-5
    # From rest, an overdamped creep never outruns the largest force over c.
    force = law(start) * s
    tolerance = quadrature * (strain_energy(start) + strain_energy(depth)) \
        + energy_bound(sim, abs(gap), force / c, force, m)
    ledger = sim.energy
    assert ledger.stored_change == pytest.approx(expected, abs=tolerance)
    assert ledger.damping_loss == pytest.approx(-expected, abs=tolerance)
    assert ledger.excitation_work == ledger.friction_loss == 0.0
    assert ledger.contact_loss == pytest.approx(0.0, abs=tolerance)  # an elastic contact


#: A nearly free blade (its spring 1 N/m) flying at a pad across Δ = 0.1 mm, face normal
#: to x (α = π/2).
FREE_BLADE = Blade(mass=0.1, damping=0.0, stiffness=1.0)
IMPACT_GAP = 1e-4
IMPACT_SPEED = 0.5


def approach(blade, gap, speed):
    """Flight from x = 0 at ``speed`` to the pad: x = (v0/ω) sin ωt reaches Δ at
    t_c = arcsin(Δ ω / v0)/ω with speed v_in = √(v0² − ω² Δ²). Returns (t_c, v_in)."""
    w = math.sqrt(blade.stiffness / blade.mass)
    return math.asin(gap * w / speed) / w, math.sqrt(speed**2 - (w * gap) ** 2)


def test_kelvin_voigt_impact_loses_the_energy_of_its_damped_half_cycle():
    """KelvinVoigt N = max(0, k_c δ + c_c δ̇), δ = x − Δ. While N > 0 the blade is the
    linear oscillator m ẍ + c_c ẋ + (k + k_c) x = k_c Δ, about x_c = k_c Δ/(k + k_c):
    with y = x − x_c, σ = c_c/2m, ω² = (k + k_c)/m, ω_d = √(ω² − σ²), from y0 = Δ − x_c and
    ẏ0 = v_in,
        y = e^{−σt} (y0 cos ω_d t + (ẏ0 + σ y0)/ω_d sin ω_d t),
        ẏ = e^{−σt} (ẏ0 cos ω_d t − (ω² y0 + σ ẏ0)/ω_d sin ω_d t).
    The force reaches zero (k_c δ + c_c δ̇ = 0) at τ1, while the shrouds still overlap;
    the law clips it there (it never pulls), so the blade flies free over the last of the
    overlap: its spring energy conserves ½ m ẋ² + ½ k x², and it leaves δ = 0 with
    v_out² = ẋ(τ1)² + (k/m)(x(τ1)² − Δ²). The contact loss is ½ m (v_in² − v_out²): the
    damper's work and the spring energy k_c δ(τ1)²/2 the clip discards. (Unclipped, the
    rebound would be e = exp(−ζπ/√(1 − ζ²)); the clip ends the push earlier and loses more.)
    """
    kc, cc = 1e6, 40.0
    law = KelvinVoigt(stiffness=kc, damping=cc)
    pair = (FREE_BLADE, Interface(gap=IMPACT_GAP, angle=math.pi / 2, normal=law))
    sim = run([pair], 1, [0.0], [IMPACT_SPEED])
    m, k = FREE_BLADE.mass, FREE_BLADE.stiffness
    t_in, v_in = approach(FREE_BLADE, IMPACT_GAP, IMPACT_SPEED)
    x_c = kc * IMPACT_GAP / (k + kc)
    y0 = IMPACT_GAP - x_c
    sigma, w2 = cc / (2 * m), (k + kc) / m
    wd = math.sqrt(w2 - sigma**2)

    def state(t):
        decay, cos, sin = math.exp(-sigma * t), math.cos(wd * t), math.sin(wd * t)
        y = decay * (y0 * cos + (v_in + sigma * y0) / wd * sin)
        return x_c + y, decay * (v_in * cos - (w2 * y0 + sigma * v_in) / wd * sin)

    def push(t):
        x, v = state(t)
        return kc * (x - IMPACT_GAP) + cc * v

    grid = np.linspace(0.0, 2 * math.pi / wd, 20001)
    first = next(i for i, t in enumerate(grid) if i and push(t) <= 0.0)
    tau1 = brentq(push, grid[first - 1], grid[first], xtol=1e-18, rtol=1e-15)
    x1, v1 = state(tau1)
    assert x1 > IMPACT_GAP and v1 < 0.0
    wb = math.sqrt(k / m)
    v_out = math.sqrt(v1**2 + wb**2 * (x1**2 - IMPACT_GAP**2))
    radius = math.hypot(x1, v1 / wb)
    tau2 = (math.acos(IMPACT_GAP / radius) - math.atan2(-v1 / wb, x1)) / wb
    assert sim.events.counts == {"closing": 1, "separation": 1, "sticking": 0, "reversal": 0,
                                 "breakaway": 0}
    deepest = v_in / math.sqrt(w2)  # undamped, an upper bound
    dx, dv = state_bound(sim, IMPACT_GAP + deepest, IMPACT_SPEED)
    slack = dx / v_out
    assert_located([first_event(sim, 0, EventKind.CLOSING)], [t_in], slack)
    assert_located([first_event(sim, 0, EventKind.SEPARATION)], [t_in + tau1 + tau2],
                   2 * slack)
    energy = 0.5 * m * IMPACT_SPEED**2
    loss = 0.5 * m * (v_in**2 - v_out**2)
    assert 0.1 * energy < loss < energy
    peak = kc * deepest + cc * v_in
    tolerance = energy_bound(sim, IMPACT_GAP + deepest, IMPACT_SPEED, peak, m)
    assert sim.energy.contact_loss == pytest.approx(loss, abs=tolerance)
    closed = sim.modes[:, 0] != Mode.OPEN
    penetration = sim.x[closed, 0] - IMPACT_GAP
    np.testing.assert_allclose(sim.normal_force[closed, 0],
                               np.maximum(0.0, kc * penetration + cc * sim.v[closed, 0]),
                               rtol=1e-12, atol=1e-9)
    assert (sim.normal_force[~closed, 0] == 0.0).all()


def test_hunt_crossley_impact_loses_what_its_exact_restitution_says():
    """HuntCrossley N = k δ^n (1 + d δ̇) on a free mass: m δ̈ = −k δ^n (1 + d δ̇). With
    w = δ̇ as a function of δ, m w dw/dδ = −k δ^n (1 + d w) separates:
    m G(w) + k δ^{n+1}/(n+1) is constant, G(w) = ∫ w/(1 + d w) dw = (d w − ln(1 + d w))/d².
    At both ends of the impact δ = 0, so the rebound speed v_out solves
    G(−v_out) = G(v_in), and the contact loss is ½ m (v_in² − v_out²). (To first order
    that is (2/3) d m v_in³, Lankarani–Nikravesh's 1 − e² = (4/3) d v_in.)

    The blade's own spring (1 N/m) pushes with at most k (Δ + δ_max) over the impact of
    duration τ ≲ 4 δ_max/v_in: that changes the speeds by a fraction
    ε = k (Δ + δ_max) τ/(m v_in) ≈ 2e-6, and the loss, quadratic in them, by 2ε at most.
    """
    kh, d = 1e9, 0.1
    law = HuntCrossley(stiffness=kh, damping=d)
    pair = (FREE_BLADE, Interface(gap=IMPACT_GAP, angle=math.pi / 2, normal=law))
    sim = run([pair], 1, [0.0], [IMPACT_SPEED])
    m, k = FREE_BLADE.mass, FREE_BLADE.stiffness
    _, v_in = approach(FREE_BLADE, IMPACT_GAP, IMPACT_SPEED)

    def g(w):
        return (d * w - math.log1p(d * w)) / d**2

    v_out = brentq(lambda v: g(-v) - g(v_in), 0.0, v_in, xtol=1e-16, rtol=1e-15)
    loss = 0.5 * m * (v_in**2 - v_out**2)
    assert loss == pytest.approx(2 / 3 * d * m * v_in**3, rel=2 * d * v_in)
    deepest = (2.5 * 0.5 * m * v_in**2 / kh) ** 0.4  # (2/5) k δ^{5/2} = ½ m v_in²
    spring = k * (IMPACT_GAP + deepest) * 4 * deepest / v_in / (m * v_in)
    assert sim.events.counts == {"closing": 1, "separation": 1, "sticking": 0, "reversal": 0,
                                 "breakaway": 0}
    tolerance = 2 * spring * loss + energy_bound(sim, IMPACT_GAP + deepest, IMPACT_SPEED,
                                                 law(deepest, v_in), m)
    assert sim.energy.contact_loss == pytest.approx(loss, abs=tolerance)
    closed = sim.modes[:, 0] != Mode.OPEN
    penetration = sim.x[closed, 0] - IMPACT_GAP
    expected = kh * np.maximum(penetration, 0.0) ** 1.5 * (1 + d * sim.v[closed, 0])
    np.testing.assert_allclose(sim.normal_force[closed, 0], expected, rtol=1e-12, atol=1e-12)
    assert (sim.normal_force >= 0.0).all()


# ---- 3. the regularised law ----------------------------------------------------------------

def test_regularised_friction_follows_tanh_and_never_sticks():
    """Regularised(Coulomb μ, v_ε): f = μ N tanh(v/v_ε) at every sample, N = k_c δ of the
    preloaded linear contact, computed here from the sampled state; it never sticks, and
    since f has the sign of v it only ever dissipates.

    (A scene of its own: a regularised law compiles a kernel with the regularised branch.)
    """
    mu, velocity, kc, alpha = 0.5, 1e-3, 3e5, 0.3
    law = Regularised(law=Coulomb(mu=mu), velocity=velocity)
    group = BladeGroup().add_blade("blade1", BLADE).add_fixed("pad1")
    group.connect("blade1", "pad1", Interface(gap=-2e-5, angle=alpha,
                                              normal=LinearSpring(stiffness=kc), friction=law))
    scene = Scene(group=group, speed_rpm=SPEED_RPM,
                  excitation=Excitation(engine_order=1, amplitudes=(0.0, Q1), phases=[0.0]))
    sim = simulate(scene, 3, method=PRECISE)
    closed = sim.modes[:, 0] != Mode.OPEN
    assert closed.any() and not (sim.modes == Mode.STICK).any()
    assert sim.events.counts["sticking"] == sim.events.counts["breakaway"] == 0
    normal = kc * (sim.x[:, 0] + 2e-5) * math.sin(alpha)
    np.testing.assert_allclose(sim.normal_force[closed, 0], normal[closed], rtol=1e-12)
    slip = sim.v[:, 0] * math.cos(alpha)
    np.testing.assert_allclose(sim.friction_force[closed, 0],
                               mu * normal[closed] * np.tanh(slip[closed] / velocity),
                               rtol=1e-12, atol=1e-15)
    assert sim.energy.friction_loss > 0.0
