"""Hard cases where nonsmooth solvers usually break. Each states what it expects.

Every run must stay finite, close its energy ledger (to 1e-6 of the excitation work, which
covers the integrator's tolerance over the run) and report a finite number of switches.
Beyond that, each case is held to what its physics allows, derived here: forces within
their laws at every sample, an event log that the sampled motion bears out, responses
within a limit case (the group without contact, or the passivity of its interfaces), and
counts and accumulation times from closed forms.
The slowest are marked ``slow``: ``pytest -m "not slow"`` skips them locally; CI runs all.
"""

import math
import re

import numpy as np
import pytest

from contact_laws import Coulomb, ExponentialFriction, LinearSpring
from shroudnet import (Adaptive, Blade, BladeGroup, EventKind, Excitation, FixedStep, Interface,
                       Mode, Scene, SimulationError, ZenoGuard, simulate)
from shroudnet.scenes import three_blade_paper
from tests.groups import external_forces, incidence
from tests.laws import PreloadedStop, static_limit


def assert_sound(sim, energy=None):
    """No NaN, the ledger closes to 1e-6 of ``energy`` [J] (default: the excitation work),
    the switches are counted; returns the switch count."""
    assert np.isfinite(sim.x).all() and np.isfinite(sim.v).all()
    assert np.isfinite(sim.normal_force).all() and np.isfinite(sim.friction_force).all()
    ledger = sim.energy
    assert abs(ledger.residual) < 1e-6 * abs(ledger.excitation_work if energy is None
                                              else energy)
    switches = sum(sim.events.counts.values())
    assert len(sim.events.time) == switches  # every switch logged (far below capacity)
    return switches


def relative(sim, values):
    """x_i − x_j (or ẋ_i − ẋ_j) of every interface at every sample; a fixed node has 0."""
    a = sim.scene.arrays
    return (np.where(a.left >= 0, values[:, a.left], 0.0)
            - np.where(a.right >= 0, values[:, a.right], 0.0))


def friction_coefficient(law, speed):
    """μ(|v|) of the laws used here, written out: Coulomb, and the paper's eq. (4)."""
    if isinstance(law, Coulomb):
        return np.full_like(speed, law.mu)
    return law.mu_kinetic + (law.mu_static - law.mu_kinetic) * np.exp(-law.beta * speed)


def assert_forces_follow_the_laws(sim):
    """At every sample, for linear contact springs and exact friction: N = k_c δ ≥ 0 with
    δ = (x_i − x_j − Δ) sin α computed here while closed, N = 0 while open; |f| ≤ μ_s N
    (μ_s as the test gave it; the stick test accepts 1e-9 of slack); f = μ(|v|) N sgn(v)
    while slipping, v = (ẋ_i − ẋ_j) cos α, with μ written out here."""
    a = sim.scene.arrays
    normal, friction = sim.normal_force, sim.friction_force
    penetration = (relative(sim, sim.x) - a.gap) * a.sin_angle
    slip = relative(sim, sim.v) * a.cos_angle
    closed = sim.modes != Mode.OPEN
    for e, (_, _, interface) in enumerate(sim.scene.group.interfaces):
        on = closed[:, e]
        np.testing.assert_allclose(normal[on, e],
                                   interface.normal.stiffness * penetration[on, e],
                                   rtol=1e-12, atol=1e-12 * np.abs(normal[:, e]).max())
        assert (normal[~on, e] == 0.0).all() and (normal[:, e] >= 0.0).all()
        if interface.friction is None:
            continue
        assert (np.abs(friction[:, e])
                <= static_limit(interface.friction) * normal[:, e] * (1 + 1e-9)).all()
        for mode, sign in ((Mode.SLIP_POSITIVE, 1.0), (Mode.SLIP_NEGATIVE, -1.0)):
            rows = sim.modes[:, e] == mode
            mu = friction_coefficient(interface.friction, np.abs(slip[rows, e]))
            np.testing.assert_allclose(friction[rows, e], sign * mu * normal[rows, e],
                                       rtol=1e-12, atol=1e-15)


#: The modes each kind of switch leads from, and to.
SWITCHES = {
    EventKind.CLOSING: ({Mode.OPEN}, {Mode.SLIP_POSITIVE, Mode.SLIP_NEGATIVE, Mode.STICK}),
    EventKind.SEPARATION: ({Mode.SLIP_POSITIVE, Mode.SLIP_NEGATIVE, Mode.STICK}, {Mode.OPEN}),
    EventKind.STICKING: ({Mode.SLIP_POSITIVE, Mode.SLIP_NEGATIVE}, {Mode.STICK}),
    EventKind.BREAKAWAY: ({Mode.STICK}, {Mode.SLIP_POSITIVE, Mode.SLIP_NEGATIVE}),
}


def assert_log_explains_samples(sim):
    """The event log and the sampled motion tell the same story, interface by interface.

    1. Each sampled mode matches the sampled kinematics, computed here: open where δ ≤ 0,
       closed where δ ≥ 0, slipping in the direction of v, stuck with v = 0. A switch is
       logged at the end of its bracket, up to tol·T_e after the true one, so a sample in
       between may keep the old mode by |δ̇| tol·T_e (resp. |v̇| tol·T_e, with v̇ from
       eq. (7) and the sampled forces).
    2. Replaying the logged switches between two samples leads from the earlier sample's
       mode to the later one's: nothing happened unlogged, nothing was logged that did
       not happen.
    Returns the number of closings seen in the samples (open, then closed) per interface.
    """
    a = sim.scene.arrays
    bracket = sim.settings["event_tolerance"] * sim.scene.excitation_period
    u, du = relative(sim, sim.x), relative(sim, sim.v)
    penetration, rate, slip = (u - a.gap) * a.sin_angle, du * a.sin_angle, du * a.cos_angle
    force = sim.normal_force * a.sin_angle + sim.friction_force * a.cos_angle
    acceleration = (external_forces(sim.scene, sim.t[:, None], sim.x, sim.v)
                    - force @ incidence(sim.scene)) / a.mass
    slip_rate = relative(sim, acceleration) * a.cos_angle
    reach = 1e-15 * (np.abs(u) + np.abs(a.gap))
    closings = []
    for e in range(a.n_interfaces):
        modes = sim.modes[:, e]
        lag = np.abs(rate[:, e]) * bracket * (1 + 1e-6) + reach[:, e]
        assert (penetration[modes == Mode.OPEN, e] <= lag[modes == Mode.OPEN]).all()
        assert (penetration[modes != Mode.OPEN, e] >= -lag[modes != Mode.OPEN]).all()
        drift = 2 * np.abs(slip_rate[:, e]).max() * bracket
        assert (slip[modes == Mode.SLIP_POSITIVE, e] >= -drift).all()
        assert (slip[modes == Mode.SLIP_NEGATIVE, e] <= drift).all()
        assert (np.abs(slip[modes == Mode.STICK, e]) <= 1e-12 * np.abs(slip[:, e]).max()).all()
        mine = sim.events.interface == e
        times, kinds = sim.events.time[mine], sim.events.kind[mine]
        interval = np.searchsorted(sim.t, times, side="right") - 1
        quiet = np.ones(len(sim.t) - 1, dtype=bool)
        quiet[interval[interval < len(quiet)]] = False
        assert (modes[1:][quiet] == modes[:-1][quiet]).all()
        for k in np.unique(interval[interval < len(quiet)]):
            possible = {Mode(modes[k])}
            for kind in kinds[interval == k]:
                if kind == EventKind.REVERSAL:
                    before = {Mode.SLIP_POSITIVE, Mode.SLIP_NEGATIVE}
                    after = {m for m in (Mode.SLIP_POSITIVE, Mode.SLIP_NEGATIVE)
                             if {m} != possible}
                else:
                    before, after = SWITCHES[EventKind(kind)]
                assert possible & before, f"{EventKind(kind).name} from {possible} at {k}"
                possible = set(after)
            assert Mode(modes[k + 1]) in possible
        closings.append(int(((modes[:-1] == Mode.OPEN) & (modes[1:] != Mode.OPEN)).sum()))
    return closings


def assert_damping_limited(sim):
    """Passivity. From rest at x = 0 with no preload, the stored energy only grows from 0,
    and friction and the contact springs never give energy back, so the ledger's damping
    loss D = c ∫ Σ ẋ² dt is at most the excitation work W = ∫ Σ Q ẋ dt, which by
    Cauchy–Schwarz is at most √(∫ Σ Q² dt · D/c). Hence D ≤ ∫ Σ Q² dt / c: with
    Q_i = q1 sin(ωt + φ_i) over whole periods, ∫ Σ Q² = n q1² t/2, and the mean-square
    velocity of the blades is at most q1²/2c² each, what a linear blade reaches at
    resonance with no contact. The ledger closes to 1e-6 of W, hence that slack."""
    a = sim.scene.arrays
    assert len(set(a.damping)) == 1 and a.amplitudes[0] == 0.0
    c = a.damping[0]
    forcing = a.n_blades * a.amplitudes[1] ** 2 * sim.t[-1] / 2
    ledger = sim.energy
    assert ledger.damping_loss <= ledger.excitation_work * (1 + 1e-6)
    assert ledger.excitation_work <= math.sqrt(forcing * ledger.damping_loss / c) * (1 + 1e-6)
    assert ledger.damping_loss <= forcing / c * (1 + 2e-6)


def linear_response_from_rest(scene, t):
    """Each blade alone, m ẍ + c ẋ + k x = q1 sin(ωt + φ), from rest at x = 0 [m].

    Steady state x_s = A sin(ωt + φ − θ), A = q1/√((k − mω²)² + (cω)²),
    θ = atan2(cω, k − mω²), plus the free motion that cancels x_s and ẋ_s at t = 0:
    e^{−σt} (B cos ω_d t + (Ḃ + σB)/ω_d sin ω_d t), B = −x_s(0), Ḃ = −ẋ_s(0), σ = c/2m.
    Returns (x, a bound on |x| over all t).
    """
    a = scene.arrays
    m, c, k, w = a.mass, a.damping, a.stiffness, a.excitation_frequency
    amplitude = a.amplitudes[1] / np.hypot(k - m * w * w, c * w)
    lag = np.arctan2(c * w, k - m * w * w)
    sigma = c / (2 * m)
    wd = np.sqrt(k / m - sigma**2)
    start, start_rate = -amplitude * np.sin(a.phases - lag), -amplitude * w * np.cos(a.phases - lag)
    sine = (start_rate + sigma * start) / wd
    t = np.asarray(t)[:, None]
    steady = amplitude * np.sin(w * t + a.phases - lag)
    free = np.exp(-sigma * t) * (start * np.cos(wd * t) + sine * np.sin(wd * t))
    return steady + free, amplitude + np.hypot(start, sine)


def test_very_stiff_contact_stays_stable():
    """γ1 up to 1e5: the adaptive step shrinks inside each impact; nothing blows up. An
    impact's kinetic energy goes into the contact spring, so the deepest penetration falls
    as 1/√γ1: a factor of about 10 from γ1 = 1e3 to 1e5."""
    deepest = []
    for gamma1 in (1e3, 1e5):
        sim = simulate(three_blade_paper(gamma1=gamma1), 50, method=Adaptive())
        assert assert_sound(sim) > 100
        a = sim.scene.arrays
        deepest.append(((sim.x[:, 0] - sim.x[:, 1] - a.gap[0]) * a.sin_angle[0]).max())
    assert 5.0 < deepest[0] / deepest[1] < 20.0


def test_contact_angle_near_zero_keeps_friction_finite():
    """α → 0: the normal force barely acts along x and friction dominates; no division.

    The limit is the group without contact: each interface pushes its blades with
    |F| = |N sin α + f cos α| ≤ N (sin α + μ_s cos α), N = k_c (u − Δ) sin α, at most
    k_c U sin α (sin α + μ_s) for |u − Δ| ≤ U. A blade with two interfaces then feels at
    most F = 2 k_c U sin α (sin α + μ_s), and its motion leaves the contact-free one (the
    closed form from rest) by at most ∫₀^∞ |h| F = 2F/(c ω_d), h the blade's impulse
    response e^{−σt} sin(ω_d t)/(m ω_d). With U ≤ Δ + 2 (X + e) for blades within X + e
    of zero, e ≤ β (Δ + 2X + 2e) solves to e ≤ β (Δ + 2X)/(1 − 2β), β = 4 k_c sin α
    (sin α + μ_s)/(c ω_d): here about 3e-4 of the amplitude."""
    scene = three_blade_paper(alpha=1e-6)
    sim = simulate(scene, 50, method=Adaptive())
    assert_sound(sim)
    assert_forces_follow_the_laws(sim)
    assert_log_explains_samples(sim)
    assert_damping_limited(sim)
    a = scene.arrays
    interface = scene.group.interfaces[0][2]
    free, reach = linear_response_from_rest(scene, sim.t)
    c, m, k = a.damping[0], a.mass[0], a.stiffness[0]
    wd = math.sqrt(k / m - (c / (2 * m)) ** 2)
    beta = (4 * interface.normal.stiffness * a.sin_angle[0]
            * (a.sin_angle[0] + static_limit(interface.friction)) / (c * wd))
    deviation = beta * (abs(a.gap[0]) + 2 * reach.max()) / (1 - 2 * beta)
    integration = sim.steps * (sim.settings["rtol"] * reach.max() + sim.settings["atol"])
    assert deviation < 1e-3 * reach.max()
    assert np.abs(sim.x - free).max() <= deviation + integration


def test_contact_angle_of_a_right_angle_holds_no_friction():
    """α = π/2: cos α = 0, so friction has no component along x and cannot stick."""
    sim = simulate(three_blade_paper(alpha=math.pi / 2), 50, method=Adaptive())
    assert assert_sound(sim) > 0
    assert sim.events.counts["sticking"] == 0
    assert abs(sim.energy.friction_loss) < 1e-12
    assert not (sim.modes == Mode.STICK).any()


def test_static_and_kinetic_friction_equal():
    """μ_s = μ_k (Coulomb): stick and slip share one limit; the run still settles each switch."""
    sim = simulate(three_blade_paper(friction=Coulomb(mu=0.3)), 50, method=Adaptive())
    assert assert_sound(sim) > 0
    stuck = sim.modes == Mode.STICK
    limit = 0.3 * sim.normal_force[stuck]
    assert (np.abs(sim.friction_force[stuck]) <= limit * (1 + 1e-6) + 1e-12).all()


def test_very_large_beta():
    """β = 1e4 s/m: μ falls from μ_s to μ_k within 0.1 mm/s of slip; still well-behaved.
    The friction follows eq. (4) at every slipping sample and stays within μ_s N, the log
    matches the sampled motion, and the response stays within the passivity limit."""
    law = ExponentialFriction(mu_static=0.5, mu_kinetic=0.3, beta=1e4)
    sim = simulate(three_blade_paper(friction=law), 50, method=Adaptive())
    assert assert_sound(sim) > 0
    assert_forces_follow_the_laws(sim)
    assert_log_explains_samples(sim)
    assert_damping_limited(sim)
    slipping = np.isin(sim.modes, [Mode.SLIP_POSITIVE, Mode.SLIP_NEGATIVE])
    fast = slipping & (np.abs(relative(sim, sim.v)) * 0.5 > 1e-3)  # β|v| > 10
    assert fast.sum() > 0.5 * slipping.sum()
    ratio = np.abs(sim.friction_force[fast]) / sim.normal_force[fast]
    assert (np.abs(ratio - 0.3) <= 0.2 * math.exp(-10.0)).all()  # μ_k to within e^{-10}


def test_zero_and_negative_gaps():
    """Δ = 0 touches at rest. Δ < 0 is preloaded from the start: the preload N pushes the
    blades apart by N sin α, which friction can hold only if μ_s ≥ tan α. At the paper's
    α = π/3 (tan α = 1.73 > 0.5) the interfaces slip at once; at α = 0.3 they stick."""
    touching = simulate(three_blade_paper(gap=0.0), 50, method=Adaptive())
    assert_sound(touching)
    assert_forces_follow_the_laws(touching)
    assert_log_explains_samples(touching)
    assert_damping_limited(touching)
    for alpha, start in ((math.pi / 3, {Mode.SLIP_POSITIVE, Mode.SLIP_NEGATIVE}),
                         (0.3, {Mode.STICK})):
        sim = simulate(three_blade_paper(gap=-1e-5, alpha=alpha), 50, method=Adaptive())
        assert_sound(sim)
        assert set(sim.modes[0]) <= start
        a = sim.scene.arrays
        preload = a.normal_laws[0](1e-5 * a.sin_angle[0], 0.0)
        np.testing.assert_allclose(sim.normal_force[0], preload, rtol=1e-12)


def test_almost_no_damping():
    """c = 1e-6 N·s/m: friction is nearly the only loss, and the ledger still closes."""
    sim = simulate(three_blade_paper(damping=1e-6), 100, method=Adaptive())
    assert_sound(sim)
    assert sim.energy.damping_loss < 1e-4 * sim.energy.friction_loss


def test_an_all_stuck_ring_of_64_blades_moves_as_one_body():
    """A preloaded ring of 64 mistuned blades with every interface stuck is one cluster
    holding a cycle: statically indeterminate. It must move as the single oscillator
    (Σm, Σc, Σk) under Σ Q, each static friction within μ_s N, never releasing."""
    n = 64
    rng = np.random.default_rng(7)
    masses = 0.082 * (1.0 + 0.02 * rng.uniform(-1.0, 1.0, n))
    blades = [Blade(mass=m, damping=4.0, frequency=210.0) for m in masses]
    shroud = Interface(gap=-1e-4, angle=math.pi / 3, normal=LinearSpring(stiffness=1e6),
                       friction=Coulomb(mu=0.5))
    group = BladeGroup.ring(n, blades, shroud)
    scene = Scene(group=group, excitation=Excitation(engine_order=2, amplitudes=(0.0, 5.0),
                                                     phases=[0.0] * n), speed_rpm=6000.0)
    a = scene.arrays
    mass, damping, stiffness = a.mass.sum(), a.damping.sum(), a.stiffness.sum()
    w = a.excitation_frequency
    force = 5.0 * n
    amplitude = force / math.hypot(stiffness - mass * w * w, damping * w)
    lag = math.atan2(damping * w, stiffness - mass * w * w)

    def steady(t):
        return amplitude * np.sin(w * t - lag), amplitude * w * np.cos(w * t - lag)

    x0, v0 = steady(0.0)
    sim = simulate(scene, 20, method=Adaptive(rtol=1e-10, atol=1e-15),
                   initial=(np.full(n, x0), np.full(n, v0)))
    assert_sound(sim)
    assert (sim.modes == Mode.STICK).all()
    assert sum(sim.events.counts.values()) == 0
    x, _ = steady(sim.t)
    np.testing.assert_allclose(sim.x, np.repeat(x[:, None], n, axis=1),
                               atol=1e-7 * amplitude)
    assert np.abs(sim.friction_force).max() > 0.0  # mistuning loads the friction
    assert (np.abs(sim.friction_force) <= 0.5 * sim.normal_force).all()


def blade_against_a_stop(interface, mean_force=0.0):
    """One undamped 200 Hz blade facing a fixed stop across ``interface``, under q0 only."""
    group = BladeGroup().add_blade("blade", Blade(mass=0.082, damping=0.0, frequency=200.0))
    group.add_fixed("stop").connect("blade", "stop", interface)
    return Scene(group=group, speed_rpm=6000.0,
                 excitation=Excitation(engine_order=2, amplitudes=(mean_force, 0.0),
                                       phases=[0.0]))


@pytest.mark.parametrize("method", [Adaptive(rtol=1e-10, atol=1e-15), FixedStep()])
def test_grazing_contact_is_found_at_every_tangency(method):
    """A free oscillation x = A sin ωt whose crests just reach the gap: the contact closes
    with zero relative velocity. A gap 1e-6 A below the crest is touched for 4e-4 periods,
    well inside one step, at each of the 20 crests: every touch is found (the contact guard
    is searched for a minimum inside each step), with its reversal at the deepest point.
    1e-6 A above the crest, nothing is touched. Exactly at it, whatever the rounding
    decides, the motion stays the free oscillation."""
    amplitude = 1e-4
    law = ExponentialFriction(mu_static=0.5, mu_kinetic=0.3, beta=5.0)
    for offset, touches in ((-1e-6, 20), (0.0, None), (1e-6, 0)):
        scene = blade_against_a_stop(Interface(
            gap=amplitude * (1.0 + offset), angle=math.pi / 3,
            normal=LinearSpring(stiffness=1e6), friction=law))
        a = scene.arrays
        w = math.sqrt(a.stiffness[0] / a.mass[0])
        sim = simulate(scene, 20, method=method, initial=([0.0], [amplitude * w]))
        switches = assert_sound(sim, energy=0.5 * a.mass[0] * (amplitude * w) ** 2)
        counts = sim.events.counts
        if touches is not None:
            assert counts["closing"] == counts["separation"] == counts["reversal"] == touches
        assert switches <= 60
        free = amplitude * np.sin(w * sim.t)
        assert np.abs(sim.x[:, 0] - free).max() < 1e-6 * amplitude


@pytest.mark.parametrize("method", [Adaptive(), FixedStep(steps_per_period=50)])
def test_a_breakaway_window_shorter_than_a_step_is_found(method):
    """A blade held at rest against a preloaded stop (linear spring, Coulomb μ) under
    Q = q1 sin ωt. At rest with δ0 = (x0 − Δ) sin α, eq. (7) leaves the held friction
    f = (Q − k x0 − N sin α)/cos α with N = k_c δ0; x0 = k_c Δ sin²α/(k + k_c sin²α)
    makes k x0 + N sin α = 0, so f = Q/cos α. With q1 = 1.0001 μ N cos α, the friction
    needed exceeds μN only while sin ωt > 1/1.0001: 2 arccos(1/1.0001)/2π = 0.45 % of a
    period around each peak, a tenth of a step of either integrator (the adaptive one
    takes its largest, 5 % of a period, while nothing moves; the fixed one 2 %). Like a
    grazing contact, the breakaway must still be found inside the step, at
    sin ωt* = 1/1.0001, to the event tolerance."""
    mass, stiffness, kc, gap, alpha, mu = 0.082, 1.5e5, 3e5, -5e-5, 0.3, 0.8
    s = math.sin(alpha)
    x0 = kc * gap * s * s / (stiffness + kc * s * s)
    normal = kc * (x0 - gap) * s
    q1 = 1.0001 * mu * normal * math.cos(alpha)
    group = BladeGroup().add_blade("blade", Blade(mass=mass, damping=4.0, stiffness=stiffness))
    group.add_fixed("stop").connect("blade", "stop", Interface(
        gap=gap, angle=alpha, normal=LinearSpring(stiffness=kc), friction=Coulomb(mu=mu)))
    scene = Scene(group=group, speed_rpm=6000.0, excitation=Excitation(
        engine_order=2, amplitudes=(0.0, q1), phases=[0.0]))
    sim = simulate(scene, 1, method=method, samples_per_period=10, initial=([x0], [0.0]))
    assert sim.modes[0, 0] == Mode.STICK
    held = sim.t < sim.scene.excitation_period / 4
    np.testing.assert_allclose(sim.friction_force[held, 0],
                               q1 * np.sin(scene.arrays.excitation_frequency * sim.t[held])
                               / math.cos(alpha), rtol=1e-9, atol=1e-12)
    assert (np.abs(sim.friction_force[:, 0]) <= mu * sim.normal_force[:, 0] * (1 + 1e-9)).all()
    breakaway = sim.events.time[sim.events.kind == EventKind.BREAKAWAY]
    assert len(breakaway) > 0, "the breakaway was missed"
    expected = math.asin(1 / 1.0001) / scene.arrays.excitation_frequency
    late = (breakaway[0] - expected) / (1e-10 * scene.excitation_period)
    assert -1e-3 <= late <= 1.0, f"breakaway {late} event tolerances after t*"


class Bounces:
    """The blade of the Zeno test, bounce by bounce, in closed form.

    Undamped, under q0, against a stop whose force jumps to N = P + k_s δ at contact, with
    Coulomb friction μ < tan α. Every phase is linear, so with z = x − Δ each is a harmonic
    motion about its own equilibrium (eq. (7), the friction's sign set by that of ẋ):

    - flight (z < 0): m z̈ = F_f − k z, F_f = q0 − kΔ > 0 pulls the blade back to the stop;
    - compression (z > 0, ẋ > 0): m z̈ = −F_c − K_c z, F_c = s₊P + kΔ − q0,
      K_c = k + s₊ k_s sin α, s₊ = sin α + μ cos α;
    - restitution (z > 0, ẋ < 0): the same with s₋ = sin α − μ cos α, F_r, K_r.

    Hitting at speed v: the compression stops after t_c = atan2(v, F_c/(m ω_c))/ω_c at the
    depth z_m = (v/ω_c)²/(a + √(a² + (v/ω_c)²)), a = F_c/K_c; at the turning point the
    friction needed to stick, (q0 − kx − N sin α)/cos α, exceeds μN (checked), so it
    slips back, leaving after t_r = 2 arcsin√(z_m/2(z_m + b))/ω_r, b = F_r/K_r, at the speed
    v' = ω_r √(z_m (z_m + 2b)); the flight returns it to the stop after
    t_f = 2 atan2(v', F_f/(m ω))/ω at v' again. (These forms keep their precision as v → 0.)
    For small v, v'/v → r = √(F_r/F_c) < 1 and the bounce time is linear in v: the bounces
    form a geometric series that ends at t∞ = t_N + τ_N r/(1 − r) once τ_N is negligible.
    """

    def __init__(self, scene, q0, preload, stiffness, mu):
        a = scene.arrays
        self.m, self.k, self.gap = a.mass[0], a.stiffness[0], a.gap[0]
        s, c = a.sin_angle[0], a.cos_angle[0]
        self.q0, self.preload, self.stiffness, self.mu, self.s, self.c = \
            q0, preload, stiffness, mu, s, c
        self.w = math.sqrt(self.k / self.m)
        self.pull = q0 - self.k * self.gap
        self.phases = []
        for side in (s + mu * c, s - mu * c):
            force = side * preload + self.k * self.gap - q0
            spring = self.k + side * stiffness * s
            self.phases.append((force, spring, math.sqrt(spring / self.m)))

    def first_impact(self):
        """From rest at x = 0: x = (q0/k)(1 − cos ωt) reaches Δ; returns (t, speed)."""
        t = math.acos(1.0 - self.gap * self.k / self.q0) / self.w
        return t, self.q0 / self.k * self.w * math.sin(self.w * t)

    def compression(self, v):
        """(t_c, z_m) of an impact at speed v."""
        force, spring, w = self.phases[0]
        reach = v / w
        return (math.atan2(v, force / (self.m * w)) / w,
                reach**2 / (force / spring + math.hypot(force / spring, reach)))

    def bounce(self, v):
        """(duration from this impact to the next, the next impact's speed)."""
        t_c, depth = self.compression(v)
        normal = self.preload + self.stiffness * self.s * depth
        needed = (self.q0 - self.k * (self.gap + depth) - normal * self.s) / self.c
        assert abs(needed) > self.mu * normal  # no stick at the turning point
        force, spring, w = self.phases[1]
        rest = force / spring
        t_r = 2 * math.asin(math.sqrt(depth / (2 * (depth + rest)))) / w
        v_out = w * math.sqrt(depth * (depth + 2 * rest))
        t_f = 2 * math.atan2(v_out, self.pull / (self.m * self.w)) / self.w
        return t_c + t_r + t_f, v_out

    def impacts(self):
        """Impact times [s] until the bounce time is 1e-20 of the elapsed time, and t∞."""
        t, v = self.first_impact()
        times = [t]
        while True:
            duration, v_next = self.bounce(v)
            ratio, v = v_next / v, v_next
            t += duration
            times.append(t)
            if duration < 1e-20 * t:
                return np.array(times), t + duration * ratio / (1 - ratio)


@pytest.mark.slow  # compiles a kernel for the stop's own law
def test_chattering_at_zero_relative_velocity_meets_the_zeno_guard():
    """A blade pushed by q0 = 30 N against a preloaded stop (N = 50 N + k δ) bounces: each
    impact loses energy to friction (μ = 0.3 < tan α, so it slips back out), and since the
    stop's force jumps to 50 N on contact, bounce and flight times shrink with the speed.
    The bounces accumulate at t∞ (``Bounces``, in closed form), where the relative velocity
    chatters about zero and the laws define no continuation.

    The logged impacts follow the closed form (to n·rtol of the elapsed time, n steps).
    The guard must stop the run at t∞, with the time and the interface, for both
    integrators: the bounce times shrink by r ≈ 0.75 per bounce, so the 200 switches that
    trip it (67 bounces) span r^{−66} ≈ 10⁸ times the last bounce; they fit in its window
    (10⁻⁴ periods) only where the bounces have shrunk to the scale of the event tolerance,
    at t∞, and past it each located switch leaves the next within a few tolerances. So
    the stop lies within one window of t∞. With μ ≥ tan α the first impact ends in stick
    at the end of its compression, and the run finishes."""
    def stop(alpha):
        return blade_against_a_stop(Interface(
            gap=1e-4, angle=alpha, normal=PreloadedStop(preload=50.0, stiffness=1e6),
            friction=Coulomb(mu=0.3)), mean_force=30.0)

    scene = stop(math.pi / 3)
    period = scene.excitation_period
    bounces = Bounces(scene, 30.0, 50.0, 1e6, 0.3)
    impacts, t_end = bounces.impacts()
    ratio = math.sqrt(bounces.phases[1][0] / bounces.phases[0][0])  # √(F_r/F_c)
    assert bounces.bounce(1e-12)[1] / 1e-12 == pytest.approx(ratio, rel=1e-6)
    bouncing = simulate(scene, 2, method=Adaptive())
    assert assert_sound(bouncing) > 20
    closings = bouncing.events.time[bouncing.events.kind == EventKind.CLOSING]
    drift = bouncing.steps * bouncing.settings["rtol"] * closings \
        + bouncing.settings["event_tolerance"] * period
    assert (np.abs(closings - impacts[:len(closings)]) <= drift).all()
    window = ZenoGuard().window_at(1e-10)
    for method in (Adaptive(), FixedStep()):
        with pytest.raises(SimulationError, match=r"Zeno or chattering behaviour .* on "
                                                  r"interface 0 \('blade', 'stop'\)") as stop_:
            simulate(scene, 20, method=method)
        when = float(re.search(r"at t = ([\d.e+-]+) s", str(stop_.value))[1])
        assert abs(when - t_end) <= window * period + 1e-9 * t_end  # printed to 9 digits
    sticky = Bounces(stop(0.2), 30.0, 50.0, 1e6, 0.3)
    t_hit, speed = sticky.first_impact()
    t_stick = t_hit + sticky.compression(speed)[0]
    depth = sticky.compression(speed)[1]
    normal = 50.0 + 1e6 * sticky.s * depth
    assert abs(30.0 - sticky.k * (sticky.gap + depth) - normal * sticky.s) / sticky.c \
        <= 0.3 * normal  # the friction holds at the turning point
    for method in (Adaptive(), FixedStep()):
        sticking = simulate(stop(0.2), 5, method=method)
        assert assert_sound(sticking) == 2
        assert sticking.events.counts["sticking"] == 1
        assert (sticking.modes[-1] == Mode.STICK).all()
        if isinstance(method, Adaptive):
            drift = sticking.steps * method.rtol * t_stick + 1e-10 * period
            assert np.abs(sticking.events.time - [t_hit, t_stick]).max() <= drift


def u_star(scene):
    """The relative displacement u* [m] beyond which no interface of the paper's group can
    stick at its turning point while the other one is open.

    Stuck, blades i and j share one acceleration, so eq. (7) gives the interface force
    F = N sin α + f cos α = (R_i − R_j)/2 with R = Q − c ẋ − k x; at the turning point
    ẋ_i = ẋ_j, so R_i − R_j = Q_i − Q_j − k u ≤ 2 q1 − k u (anti-phase forcing). Stick
    needs f ≥ −μ_s N, i.e. (R_i − R_j)/2 ≥ N (sin α − μ_s cos α), with N = k_c (u − Δ) sin α.
    For μ_s < tan α that fails once 2 q1 − k u < 2 k_c (u − Δ) sin α (sin α − μ_s cos α):
    u* = (2 q1 + 2 k_c Δ s sin α) / (k + 2 k_c s sin α), s = sin α − μ_s cos α.
    """
    a = scene.arrays
    interface = scene.group.interfaces[0][2]
    s = a.sin_angle[0] - static_limit(interface.friction) * a.cos_angle[0]
    push = 2 * interface.normal.stiffness * s * a.sin_angle[0]
    return (2 * a.amplitudes[1] + push * a.gap[0]) / (a.stiffness[0] + push)


@pytest.mark.slow
def test_ten_thousand_periods():
    """A long run keeps its ledger and its switches: 6 per period at γ1 = 2.2.

    The count comes from the physics. Under anti-phase forcing Q_i − Q_j = ±2 q1 sin ωt,
    each interface's relative displacement swings once per period, far beyond the 20 μm
    gap: one contact per interface per period, seen in the samples (20 per period resolve
    contacts of about half a period). In a contact, u turns once (its slip velocity crosses
    zero once); every sampled turning point lies beyond ``u_star``, where stick cannot
    hold, so the slip reverses. With the two contacts never overlapping, that makes a
    closing, a reversal and a separation per interface and period: 6 × 10,000 switches.
    """
    scene = three_blade_paper()
    sim = simulate(scene, 10_000, method=Adaptive(), samples_per_period=20)
    switches = assert_sound(sim)
    closings = assert_log_explains_samples(sim)
    assert closings == [10_000, 10_000]
    closed = sim.modes != Mode.OPEN
    assert not (closed[:, 0] & closed[:, 1]).any()
    u = relative(sim, sim.x)
    slip = relative(sim, sim.v)
    for e in (0, 1):
        starts = np.flatnonzero(~closed[:-1, e] & closed[1:, e]) + 1
        ends = np.flatnonzero(closed[:-1, e] & ~closed[1:, e]) + 1
        ends = ends[ends > starts[0]]
        for first, last in zip(starts, ends):
            assert u[first:last, e].max() > u_star(scene)
            turns = np.count_nonzero(np.diff(np.sign(slip[first:last, e])))
            assert turns <= 1
    counts = sim.events.counts
    assert counts["closing"] == counts["separation"] == counts["reversal"] == 2 * 10_000
    assert counts["sticking"] == counts["breakaway"] == 0
    assert switches == 6 * 10_000
