"""Every way a run can stop, reached on purpose: each ``SimulationError`` names the time,
the interface and what to do, and a run that makes no progress stops instead of hanging.

(The Zeno stop is reached in ``test_hard_cases``.)
"""

from dataclasses import dataclass

import numpy as np
import pytest

import contact_laws as cl
import shroudnet.engine.generate as generate
import shroudnet.model.scene as scene_module
from shroudnet import Adaptive, FixedStep, SimulationError, simulate
from shroudnet.scenes import three_blade_paper
from tests.laws import PreloadedStop


def sticking_scene(**laws):
    """The paper's group with μ_s above tan α, so that its interfaces stick and break away."""
    friction = laws.pop("friction", cl.ExponentialFriction(mu_static=0.8, mu_kinetic=0.3,
                                                           beta=5.0))
    return three_blade_paper(alpha=0.4, friction=friction, **laws)


@pytest.fixture
def unchecked_laws(monkeypatch):
    """Scenes built without the sampled check of user laws, to reach the loop's own guards."""
    monkeypatch.setattr(scene_module, "check_user_laws", lambda scene: None)


@dataclass(frozen=True, kw_only=True)
class GrippingOnceSliding(cl.FrictionLaw):
    """A law whose coefficient jumps up as soon as it slips: μ(0) = μ_s < μ(0⁺) = μ_slip."""

    mu_static: float
    mu_slip: float

    @staticmethod
    def coefficient(slip_speed, mu_static, mu_slip):
        return mu_slip if slip_speed > 0.0 else mu_static


def faulty_scene(**fault):
    """The paper's group with a contact spring N = k δ (k = 3e5 N/m) that has ``fault``:
    ``reach`` (NaN beyond it) or ``step`` and ``jump`` (``PreloadedStop`` without preload),
    and Coulomb friction, so that its kernel is the one of test_hard_cases' stop."""
    return three_blade_paper(normal=PreloadedStop(preload=0.0, stiffness=3e5, **fault),
                             friction=cl.Coulomb(mu=0.3))


@pytest.fixture
def planted_friction_slack(monkeypatch, tmp_path):
    """Kernels whose stick rule keeps |f| up to 1.05 μ_s N, while their breakaway guard
    fires at μ_s N: guards and mode rule disagree."""
    phases, engine = generate.phase_sources()
    planted = tuple(source.replace("if candidates[e] else limit):",
                                   "if candidates[e] else 1.05 * limit):") for source in phases)
    assert planted != phases, "the stick rule's threshold moved: plant it where it is now"
    monkeypatch.setattr(generate, "phase_sources", lambda: (planted, engine))
    monkeypatch.setenv("SHROUDNET_CACHE", str(tmp_path))
    generate.forget_kernels()
    yield
    generate.forget_kernels()


@pytest.mark.slow  # compiles a kernel with the planted rule
def test_guards_and_stick_rule_that_disagree_stop_the_run_instead_of_hanging(
        planted_friction_slack):
    """Each located breakaway leaves the interface stuck, its guard falls further, and the
    next switch is one event tolerance later: without a guard the run would creep on for
    hours. It stops after MAX_IDLE_SWITCHES switches that change no mode."""
    with pytest.raises(SimulationError,
                       match=r"no progress at t = .* on interface [01] \('blade\d', 'blade\d'\): "
                             r"1000 switches in a row changed no mode"):
        simulate(sticking_scene(), 20)


def test_the_same_scene_with_a_consistent_rule_sticks_and_breaks_away():
    """The scene above, with the real kernel, runs through its stick phases."""
    sim = simulate(sticking_scene(), 20)
    assert sim.events.counts["sticking"] > 0
    assert sim.events.counts["breakaway"] > 0


@pytest.mark.slow  # compiles a kernel for its law
def test_friction_that_grips_harder_once_sliding_has_no_consistent_mode(unchecked_laws):
    """μ(0⁺) > μ_s: past μ_s N the interface cannot stick, and slipping either way is
    opposed by more friction than the force that drives it (the Painlevé situation).
    The mode rule reports it, naming the interface, instead of holding a stick beyond its
    limit."""
    scene = sticking_scene(friction=GrippingOnceSliding(mu_static=0.3, mu_slip=0.8))
    with pytest.raises(SimulationError, match=r"no consistent set of stick and slip modes at "
                                              r"t = .* on interface [01] .*μ\(0⁺\)"):
        simulate(scene, 20)


@pytest.mark.slow  # compiles a kernel for its law (the one of test_hard_cases' stop)
def test_a_law_that_gives_nan_stops_the_adaptive_run_as_not_finite(unchecked_laws):
    """A table law read past its end gives NaN: the adaptive step shrinks in front of it
    until it collapses, and the run says a law gave a non-finite force, not that the
    tolerances are too tight."""
    scene = faulty_scene(reach=1e-6)
    with pytest.raises(SimulationError, match=r"non-finite at t = .*law returned inf or NaN"):
        simulate(scene, 5, method=Adaptive())


@pytest.mark.slow  # compiles a kernel for its law (the one of test_hard_cases' stop)
def test_a_law_that_gives_nan_stops_the_fixed_step_run_as_not_finite(unchecked_laws):
    scene = faulty_scene(reach=1e-6)
    with pytest.raises(SimulationError, match=r"non-finite at t = .*law returned inf or NaN"):
        simulate(scene, 5, method=FixedStep(steps_per_period=200))


@pytest.mark.slow  # compiles a kernel for its law (the one of test_hard_cases' stop)
def test_a_force_jump_the_tolerances_cannot_follow_collapses_the_step():
    """A jump J in the normal force at δ = δ1: a step of h across it errs by about
    h J / m in velocity, against atol·lΩ ≈ 1.3e-9 m/s at atol = 1e-12 m. With J = 1e9 N
    that is still 500 times too much at the smallest step (1e-14 periods = 5e-17 s), so
    the step collapses as it closes in on δ1."""
    scene = faulty_scene(step=1e-6, jump=1e9)
    with pytest.raises(SimulationError, match=r"adaptive step fell below 1e-14 periods at "
                                              r"t = .*jump in a contact law"):
        simulate(scene, 5, method=Adaptive(atol=1e-12))


@pytest.mark.slow  # compiles a kernel for its law (the one of test_hard_cases' stop)
def test_motion_chattering_across_a_force_jump_stops_the_run_instead_of_hanging():
    """With a looser atol the same jump does not collapse the step: the 1e9 N throws the
    blades back each time δ passes δ1, and the steps, some 1e-16 s each, cross it and come
    back, accepted, without end (the run used to hang here). No guard sees the jump, so
    no event is located; the run stops once the steps stay that small."""
    scene = faulty_scene(step=1e-6, jump=1e9)
    with pytest.raises(SimulationError, match=r"adaptive steps stayed below 1e-09 periods for "
                                              r"10000 steps in a row at t = .*"
                                              r"chatter across it"):
        simulate(scene, 5, method=Adaptive(atol=3.4e-12))


def test_a_full_event_log_keeps_the_first_switches_and_exact_counts():
    """A log of capacity 10 holds the first ten switches of the full log, says it is
    truncated, and still counts every switch."""
    scene = sticking_scene()
    full = simulate(scene, 10)
    short = simulate(scene, 10, event_capacity=10)
    assert len(full.events) == sum(full.events.counts.values()) > 10
    assert not full.events.truncated
    assert len(short.events) == 10 and short.events.truncated
    assert short.events.counts == full.events.counts
    np.testing.assert_array_equal(short.events.time, full.events.time[:10])
    np.testing.assert_array_equal(short.events.kind, full.events.kind[:10])
    np.testing.assert_array_equal(short.x, full.x)
