"""Trajectories: closed-form limits, convergence, energy balance, stick admissibility."""

import math

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from contact_laws import Coulomb, ExponentialFriction, KelvinVoigt, LinearSpring, Regularised
from shroudnet import (
    Accuracy,
    Adaptive,
    Blade,
    BladeGroup,
    EventKind,
    Excitation,
    FixedStep,
    Interface,
    Mode,
    Scene,
    SimulationError,
    Southwell,
    ZenoGuard,
    simulate,
)
from shroudnet.run.methods import SimulationSettings
from shroudnet.scenes import three_blade_paper


def linear_response(scene, t):
    """Steady state of m ẍ + c ẋ + k x = q0 + q1 sin(ω t + φ) for every blade, in closed form."""
    a = scene.arrays
    w = a.excitation_frequency
    q0, q1 = a.amplitudes[0], a.amplitudes[1]
    amplitude = q1 / np.hypot(a.stiffness - a.mass * w**2, a.damping * w)
    lag = np.arctan2(a.damping * w, a.stiffness - a.mass * w**2)
    angle = w * np.asarray(t)[:, None] + a.phases - lag
    return q0 / a.stiffness + amplitude * np.sin(angle), amplitude * w * np.cos(angle)


@pytest.mark.parametrize("method", [FixedStep(steps_per_period=400), Adaptive()])
def test_without_contact_each_blade_is_the_closed_form_linear_oscillator(method):
    scene = three_blade_paper(gap=1.0, q1=50.0, speed_rpm=6000.0, q0=3.0)
    x0, v0 = linear_response(scene, [0.0])
    sim = simulate(scene, 20, method=method, initial=(x0[0], v0[0]))
    x, v = linear_response(scene, sim.t)
    scale = np.abs(x).max()
    assert np.abs(sim.x - x).max() < 1e-6 * scale
    assert np.abs(sim.v - v).max() < 1e-6 * np.abs(v).max()
    assert sum(sim.events.counts.values()) == 0


def test_adaptive_error_follows_its_tolerance():
    """On the smooth case the error against the closed form falls in step with rtol."""
    scene = three_blade_paper(gap=1.0, q1=50.0, speed_rpm=6000.0)
    x0, v0 = linear_response(scene, [0.0])
    errors = []
    for rtol in [1e-6, 1e-8, 1e-10]:
        sim = simulate(scene, 10, method=Adaptive(rtol=rtol, atol=rtol * 1e-4),
                       samples_per_period=20, initial=(x0[0], v0[0]))
        x = linear_response(scene, sim.t)[0]
        errors.append(np.abs(sim.x - x).max() / np.abs(x).max())
        assert errors[-1] < 10 * rtol
    assert errors[0] > 30 * errors[1] > 900 * errors[2], errors


def test_fixed_step_scheme_converges_with_fourth_order():
    """Largest error over every sample against the closed form: it falls as h⁴."""
    scene = three_blade_paper(gap=1.0, q1=50.0, speed_rpm=5000.0)
    x0, v0 = linear_response(scene, [0.0])
    errors = []
    for n in [16, 32, 64, 128]:
        sim = simulate(scene, 3, method=FixedStep(steps_per_period=n), samples_per_period=16,
                       initial=(x0[0], v0[0]))
        errors.append(np.abs(sim.x - linear_response(scene, sim.t)[0]).max())
    orders = np.log2(np.array(errors[:-1]) / np.array(errors[1:]))
    assert np.all((orders > 3.6) & (orders < 4.4)), orders


def test_paper_run_logs_its_events_and_closes_the_energy_ledger():
    scene = three_blade_paper(gamma1=2.2, speed_rpm=6000.0, q1=50.0)
    sim = simulate(scene, 30)
    counts = sim.events.counts
    assert counts["closing"] > 0 and counts["separation"] > 0 and counts["reversal"] > 0
    assert len(sim.events) == sum(counts.values())
    assert np.all(np.diff(sim.events.time) >= 0)
    ledger = sim.energy
    assert all(math.isfinite(value) for value in vars(ledger).values())
    assert ledger.friction_loss > 0 and ledger.damping_loss > 0
    assert abs(ledger.residual) < 1e-6 * ledger.friction_loss
    assert np.isfinite(sim.x).all() and np.isfinite(sim.friction_force).all()


@pytest.mark.parametrize("q1", [0.2, 50.0])
def test_energy_ledger_residual_falls_with_rtol_at_small_and_large_excitation(q1):
    """The residual follows rtol alone, however small the motion: the default atol scales
    with it (a fixed atol stopped the q1 = 0.2 N residual at 1.5e-6 of the work)."""
    scene = three_blade_paper(q1=q1, gamma1=2.2, frequency=Southwell(f0=194.6, coefficient=0.76))
    share = []
    for rtol in (1e-8, 1e-10):
        ledger = simulate(scene, 100, method=Adaptive(rtol=rtol)).energy
        share.append(abs(ledger.residual) / ledger.excitation_work)
    assert share[1] < 1e-9
    assert share[1] < share[0] / 20


def _sticky_scene(alpha=0.3, mu=0.8, q1=20.0, n=3, regularisation=0.0):
    """μ_s above tan α, so that interfaces stick (DESIGN §5); optionally regularised [m/s]."""
    blade = Blade(mass=0.082, damping=4.0, stiffness=1.5e5)
    friction = Coulomb(mu=mu)
    if regularisation:
        friction = Regularised(law=friction, velocity=regularisation)
    shroud = Interface(gap=-5e-6, angle=alpha, normal=LinearSpring(stiffness=3e5),
                       friction=friction)
    excitation = Excitation(engine_order=2, amplitudes=(0.0, q1), phases=[0.0, 2.0, 4.0][:n])
    return Scene(group=BladeGroup.chain(n, blade, shroud), excitation=excitation,
                 speed_rpm=6000.0)


# Adaptive samples come from the dense output between steps, with their own forces: the
# laws alone while nothing sticks, static friction as well while something does.
@pytest.mark.parametrize("method", [FixedStep(steps_per_period=1000), Adaptive()])
def test_stuck_interfaces_respect_the_friction_limit_and_slip_follows_its_mode(method):
    sim = simulate(_sticky_scene(), 30, method=method, samples_per_period=1000)
    counts = sim.events.counts
    assert counts["sticking"] > 0 and counts["breakaway"] > 0
    # By hand from _sticky_scene's numbers: u = x_i − x_(i+1), δ = (u + 5 µm) sin 0.3,
    # N = 3e5 δ while closed, and the limit μ_s N with the μ_s = 0.8 it gave Coulomb.
    u = sim.x[:, :-1] - sim.x[:, 1:]
    closed = sim.modes != Mode.OPEN
    normal = np.where(closed, 3e5 * (u + 5e-6) * math.sin(0.3), 0.0)
    np.testing.assert_allclose(sim.normal_force, normal, rtol=1e-9, atol=1e-15)
    stuck = sim.modes == Mode.STICK
    sliding = closed & ~stuck
    assert stuck.any() and sliding.any()
    limit = 0.8 * normal
    assert np.all(np.abs(sim.friction_force[stuck]) <= limit[stuck] * (1 + 1e-6) + 1e-12)
    np.testing.assert_allclose(np.abs(sim.friction_force[sliding]), limit[sliding], rtol=1e-9)
    slip = (sim.v[:, :-1] - sim.v[:, 1:]) * math.cos(0.3)
    vscale = np.abs(slip).max()
    assert np.all(slip[sim.modes == Mode.SLIP_POSITIVE] >= -1e-6 * vscale)
    assert np.all(slip[sim.modes == Mode.SLIP_NEGATIVE] <= 1e-6 * vscale)
    assert np.all(np.abs(slip[stuck]) <= 1e-12 * vscale)
    assert abs(sim.energy.residual) < 1e-6 * sim.energy.friction_loss


@pytest.mark.parametrize("reach, method", [
    (0.2, Adaptive()), (0.2, FixedStep(steps_per_period=1000)),
    # The excitation's peak passes the limit by 1 %: |f| > μ_s N for 4.5 % of a period.
    (0.99, Adaptive()), (0.99, FixedStep(steps_per_period=1000)),
    # |f| crosses μ_s N at the excitation's peak, rising through it very slowly.
    (0.999999, FixedStep(steps_per_period=1000)),
], ids=lambda value: type(value).__name__ if not isinstance(value, float) else f"{value:g}")
def test_a_held_blade_breaks_away_when_its_static_friction_reaches_mu_s_n(reach, method):
    """One blade pressed against the disc and started at rest at x = 0, where it sticks.

    By hand, with k_c = 3e5 N/m, gap −5 µm, α = 0.3 rad, μ_s = 0.8 and
    Q = q1 sin(ω t): N = 3e5 · 5e-6 · sin 0.3. Held (ẍ = 0 at x = 0) the blade's equation
    m ẍ = Q − k x + F gives F = N sin α + f cos α = −Q, so f = −(Q + N sin α)/cos α. It
    reaches −μ_s N, and the blade breaks away slipping negatively, first when
    sin(ω t*) = N (μ_s cos α − sin α)/q1 = ``reach`` (q1 is chosen for that): a μ_s misread
    by a part in a million would move t* by more than the event tolerance.
    """
    alpha, mu = 0.3, 0.8
    normal = 3e5 * 5e-6 * math.sin(alpha)
    q1 = normal * (mu * math.cos(alpha) - math.sin(alpha)) / reach
    blade = Blade(mass=0.082, damping=4.0, stiffness=1.5e5)
    shroud = Interface(gap=-5e-6, angle=alpha, normal=LinearSpring(stiffness=3e5),
                       friction=Coulomb(mu=mu))
    group = BladeGroup().add_fixed("disc").add_blade("held", blade)
    group.connect("disc", "held", shroud)
    scene = Scene(group=group, excitation=Excitation(engine_order=2, amplitudes=(0.0, q1),
                                                     phases=[0.0]), speed_rpm=6000.0)
    omega = 2 * 6000.0 * 2 * math.pi / 60.0
    t_star = math.asin(reach) / omega
    sim = simulate(scene, 1, method=method, samples_per_period=1000, event_tolerance=1e-10)
    assert sim.events.counts["breakaway"] >= 1
    assert sim.events.kind[0] == EventKind.BREAKAWAY and sim.events.interface[0] == 0
    # Located within the event tolerance after the time |f| passes μ_s N by the mode
    # rule's relative slack of 1e-9, which |f| rising at q1 ω cos(ω t*)/cos α takes to do.
    rate = q1 * omega * math.cos(omega * t_star) / math.cos(alpha)
    late = 1e-10 * scene.excitation_period + 1e-9 * mu * normal / rate
    assert 0.0 <= sim.events.time[0] - t_star <= 1.01 * late
    held = sim.t < t_star
    assert np.all(sim.modes[held, 0] == Mode.STICK) and np.all(sim.x[held] == 0.0)
    expected = -(q1 * np.sin(omega * sim.t[held]) + normal * math.sin(alpha)) / math.cos(alpha)
    np.testing.assert_allclose(sim.friction_force[held, 0], expected, rtol=1e-9)
    if reach < 0.5:  # well past the limit: still slipping at the next sample
        after = np.flatnonzero(~held)[0]
        assert sim.modes[after, 0] == Mode.SLIP_NEGATIVE
        assert sim.friction_force[after, 0] == pytest.approx(-mu * sim.normal_force[after, 0])


def _nonsmooth_errors(scene, methods, reference):
    """Largest displacement error of each method against the reference, relative."""
    scale = np.abs(reference.x).max()
    periods = reference.periods
    return [np.abs(simulate(scene, periods, method=m, samples_per_period=10).x
                   - reference.x).max() / scale for m in methods]


def test_both_integrators_agree_on_a_nonsmooth_case_as_their_knobs_tighten():
    """Contact closing and opening, stick, breakaway and reversal within ten periods."""
    scene = _sticky_scene()
    reference = simulate(scene, 10, method=Adaptive(rtol=1e-12, atol=1e-16),
                         samples_per_period=10)
    assert all(count > 0 for count in reference.events.counts.values())
    fixed = _nonsmooth_errors(scene, [FixedStep(steps_per_period=n) for n in (250, 500, 1000)],
                              reference)
    adaptive = _nonsmooth_errors(scene, [Adaptive(rtol=r, atol=r * 1e-4)
                                         for r in (1e-6, 1e-8, 1e-10)], reference)
    assert fixed[0] > 8 * fixed[1] > 8 * fixed[2] and fixed[2] < 1e-8, fixed
    assert adaptive[0] > 30 * adaptive[1] > 30 * adaptive[2] and adaptive[2] < 1e-8, adaptive
    ledger = reference.energy
    dissipated = ledger.damping_loss + ledger.friction_loss + ledger.contact_loss
    assert abs(ledger.residual) < 1e-6 * dissipated


def test_regularised_friction_converges_to_event_driven_friction():
    """tanh(v/v_ε) friction approaches exact stick–slip as v_ε shrinks, error ∝ v_ε."""
    exact = _sticky_scene()
    reference = simulate(exact, 10, method=Adaptive(rtol=1e-10, atol=1e-14),
                         samples_per_period=10)
    scale = np.abs(reference.x).max()
    errors = []
    for velocity in [1e-2, 1e-3, 1e-4]:
        regularised = _sticky_scene(regularisation=velocity)
        sim = simulate(regularised, 10, method=Adaptive(rtol=1e-10, atol=1e-14),
                       samples_per_period=10)
        assert sim.events.counts["sticking"] == 0  # a regularised law never sticks
        errors.append(np.abs(sim.x - reference.x).max() / scale)
    assert errors[0] > 5 * errors[1] > 25 * errors[2] and errors[2] < 1e-3, errors


@settings(max_examples=6, deadline=None)
@given(n=st.integers(2, 4), ring=st.booleans(), alpha=st.floats(0.1, 1.4),
       mu=st.floats(0.1, 1.5), q1=st.floats(5.0, 60.0), gap=st.floats(-5e-6, 2e-5),
       damped=st.booleans(), exponential=st.booleans())
def test_energy_ledger_closes_for_random_groups(n, ring, alpha, mu, q1, gap, damped,
                                                exponential):
    blade = Blade(mass=0.08, damping=3.0, stiffness=1.5e5)
    normal = KelvinVoigt(stiffness=4e5, damping=30.0) if damped else LinearSpring(stiffness=4e5)
    friction = (ExponentialFriction(mu_static=mu, mu_kinetic=0.6 * mu, beta=5.0)
                if exponential else Coulomb(mu=mu))
    shroud = Interface(gap=gap, angle=alpha, normal=normal, friction=friction)
    n = max(n, 3) if ring else n
    group = (BladeGroup.ring if ring else BladeGroup.chain)(n, blade, shroud)
    excitation = Excitation(engine_order=2, amplitudes=(0.0, q1),
                            phases=list(np.linspace(0.0, 5.0, n)))
    sim = simulate(Scene(group=group, excitation=excitation, speed_rpm=6000.0), 10,
                   method=FixedStep(steps_per_period=1000))
    ledger = sim.energy
    dissipated = ledger.damping_loss + ledger.friction_loss + ledger.contact_loss
    assert abs(ledger.residual) < 1e-6 * dissipated
    if damped and sum(sim.events.counts.values()):
        assert ledger.contact_loss >= -1e-9


def test_poincare_and_energy_density_of_a_linear_response():
    scene = three_blade_paper(gap=1.0, q1=50.0)
    x0, v0 = linear_response(scene, [0.0])
    sim = simulate(scene, 12, initial=(x0[0], v0[0]), samples_per_period=50,
                   method=FixedStep(steps_per_period=500))
    points = sim.poincare("blade2", skip=2)
    assert points.shape == (11, 2)
    for column in (0, 1):
        spread = np.ptp(points[:, column])
        assert spread < 1e-6 * np.abs(points[:, column]).max()
    amplitude = np.hypot(x0[0][1], v0[0][1] / scene.arrays.excitation_frequency)
    # The mean square of a sinusoid over whole periods is half its amplitude squared.
    assert sim.energy_density(1, skip=2) == pytest.approx(amplitude**2 / 2, rel=1e-6)
    with pytest.raises(ValueError, match=r"Simulation\.poincare\.skip must be a whole "
                                         r"number of periods in \[0, 12\)"):
        sim.poincare(1, skip=12)
    assert sim.poincare(1, skip=11).shape == (2, 2)


def test_zeno_guard_stops_with_the_time_and_the_interface():
    scene = three_blade_paper(gamma1=2.2, speed_rpm=6000.0, q1=50.0)
    with pytest.raises(SimulationError, match=r"Zeno or chattering behaviour at t = .* "
                                              r"on interface \d \('blade\d', 'blade\d'\)"):
        simulate(scene, 20, zeno=ZenoGuard(events=3, window=0.9))


@pytest.mark.parametrize("kwargs, message", [
    (dict(periods=0), r"periods must be an int >= 1"),
    (dict(periods=2, method=FixedStep(), samples_per_period=7),
     r"samples_per_period must divide FixedStep"),
    (dict(periods=2, samples_per_period=0), r"samples_per_period must be an int >= 1"),
    (dict(periods=2, event_tolerance=0.0), r"simulate\.event_tolerance must be in \(0"),
    (dict(periods=2, initial=([0.0], [0.0])), r"initial x0 must hold 3 finite numbers"),
])
def test_bad_arguments_fail_before_any_work(kwargs, message):
    with pytest.raises(ValueError, match=message):
        simulate(three_blade_paper(), **kwargs)


def test_a_count_that_is_not_whole_is_refused_by_type():
    with pytest.raises(TypeError, match=r"samples_per_period must be an int, got float 1\.5"):
        simulate(three_blade_paper(), 2, method=Adaptive(), samples_per_period=1.5)


def test_method_knobs_are_checked():
    with pytest.raises(ValueError, match=r"FixedStep\.steps_per_period must be an int >= 8"):
        FixedStep(steps_per_period=4)
    with pytest.raises(ValueError, match=r"ZenoGuard\.events must be an int >= 2"):
        ZenoGuard(events=1)


def test_the_settings_of_a_run_are_a_record_every_knob_resolved_that_reads_as_its_table():
    scene = three_blade_paper()
    sim = simulate(scene, 2, method=Accuracy(target=1e-4), samples_per_period=10)
    settings = sim.settings
    assert isinstance(settings, SimulationSettings)
    assert settings.method == Adaptive(rtol=1e-6, atol=1e-6 * scene.arrays.static_deflection)
    assert (settings.periods, settings.samples_per_period) == (2, 10)
    assert settings.event_tolerance == 1e-10 and settings.zeno.window == 1e-4
    table = settings.as_dict()
    assert table == {"method": "Adaptive", "rtol": 1e-6, "atol": settings.method.atol,
                     "max_step": 0.05, "periods": 2, "samples_per_period": 10,
                     "event_tolerance": 1e-10, "zeno": {"events": 200, "window": 1e-4}}
    # as a mapping, as it was when it was a dict; its table gives it back
    assert settings["rtol"] == 1e-6 and dict(settings) == table and settings == table
    assert SimulationSettings.from_dict(table) == settings
    fixed = SimulationSettings(method=FixedStep(), periods=1, samples_per_period=1,
                               event_tolerance=1e-8, zeno=ZenoGuard(window=1e-3))
    assert SimulationSettings.from_dict(fixed.as_dict()) == fixed != settings


@pytest.mark.parametrize("change, error, message", [
    (lambda t: {**t, "method": "Euler"}, ValueError,
     r"settings\.method must be one of \['Adaptive', 'Exponential', 'FixedStep'\], got 'Euler'"),
    (lambda t: {k: v for k, v in t.items() if k != "rtol"}, ValueError, r"missing \['rtol'\]"),
    (lambda t: {**t, "steps_per_period": 100}, ValueError, r"unknown \['steps_per_period'\]"),
    (lambda t: {**t, "zeno": 200}, ValueError, r"settings\.zeno must be a table"),
    (lambda t: {**t, "periods": 0}, ValueError, r"SimulationSettings\.periods must be an int"),
    (lambda t: [1, 2], TypeError, r"settings must be a table"),
])
def test_a_settings_table_that_describes_no_run_is_refused_by_name(change, error, message):
    table = SimulationSettings(method=Adaptive(atol=1e-12), periods=2, samples_per_period=4,
                               event_tolerance=1e-10, zeno=ZenoGuard(window=1e-4)).as_dict()
    with pytest.raises(error, match=message):
        SimulationSettings.from_dict(change(table))
