"""Hard cases where nonsmooth solvers usually break. Each states what it expects.

Every run must stay finite, close its energy ledger (to 1e-6 of the excitation work, which
covers the integrator's tolerance over the run) and report a finite number of switches.
The slowest are marked ``slow``: ``pytest -m "not slow"`` skips them locally; CI runs all.
"""

import math
import re

import numpy as np
import pytest

from contact_laws import Coulomb, ExponentialFriction, LinearSpring
from shroudnet import (Adaptive, Blade, BladeGroup, EventKind, Excitation, FixedStep, Interface,
                       Mode, Scene, SimulationError, simulate)
from shroudnet.scenes import three_blade_paper
from tests.laws import PreloadedStop


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
    """α → 0: the normal force barely acts along x and friction dominates; no division."""
    sim = simulate(three_blade_paper(alpha=1e-6), 50, method=Adaptive())
    assert_sound(sim)


@pytest.mark.slow  # compiles a kernel without stick
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
    """β = 1e4 s/m: μ falls from μ_s to μ_k within 0.1 mm/s of slip; still well-behaved."""
    law = ExponentialFriction(mu_static=0.5, mu_kinetic=0.3, beta=1e4)
    assert assert_sound(simulate(three_blade_paper(friction=law), 50, method=Adaptive())) > 0


def test_zero_and_negative_gaps():
    """Δ = 0 touches at rest. Δ < 0 is preloaded from the start: the preload N pushes the
    blades apart by N sin α, which friction can hold only if μ_s ≥ tan α. At the paper's
    α = π/3 (tan α = 1.73 > 0.5) the interfaces slip at once; at α = 0.3 they stick."""
    assert_sound(simulate(three_blade_paper(gap=0.0), 50, method=Adaptive()))
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


@pytest.mark.slow  # compiles a kernel for the stop's own law
def test_chattering_at_zero_relative_velocity_meets_the_zeno_guard():
    """A blade pushed by q0 = 30 N against a preloaded stop (N = 50 N + k δ) bounces: each
    impact loses energy to friction (μ = 0.3 < tan α, so it slips back out), and since the
    stop's force jumps to 50 N on contact, bounce and flight times shrink with the speed.
    The bounces accumulate at a finite time, where the relative velocity chatters about
    zero and the laws define no continuation. The guard must stop the run there, with the
    time and the interface, the same point for both integrators. With μ ≥ tan α the first
    impact ends in stick instead, and the run finishes."""
    def stop(alpha):
        return blade_against_a_stop(Interface(
            gap=1e-4, angle=alpha, normal=PreloadedStop(preload=50.0, stiffness=1e6),
            friction=Coulomb(mu=0.3)), mean_force=30.0)

    bouncing = simulate(stop(math.pi / 3), 2, method=Adaptive())
    assert assert_sound(bouncing) > 20
    closings = bouncing.events.time[bouncing.events.kind == EventKind.CLOSING]
    assert (np.diff(np.diff(closings)) < 0.0).all()  # the bounces keep shortening
    accumulation = []
    for method in (Adaptive(), FixedStep()):
        with pytest.raises(SimulationError, match=r"Zeno or chattering behaviour .* on "
                                                  r"interface 0 \('blade', 'stop'\)") as stop_:
            simulate(stop(math.pi / 3), 20, method=method)
        accumulation.append(float(re.search(r"\(period ([\d.]+)\)", str(stop_.value))[1]))
    assert 2.0 < accumulation[0] < 3.0
    assert accumulation[0] == pytest.approx(accumulation[1], abs=1e-5)
    for method in (Adaptive(), FixedStep()):
        sticking = simulate(stop(0.2), 5, method=method)
        assert assert_sound(sticking) == 2
        assert sticking.events.counts["sticking"] == 1
        assert (sticking.modes[-1] == Mode.STICK).all()


@pytest.mark.slow
def test_ten_thousand_periods():
    """A long run keeps its ledger and its switches: 6 per period at γ1 = 2.2."""
    sim = simulate(three_blade_paper(), 10_000, method=Adaptive(), samples_per_period=1)
    assert assert_sound(sim) == 60_000
