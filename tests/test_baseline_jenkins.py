"""The Jenkins element reference (``shroudnet.references.jenkins``) against what it does not
compute itself: the closed-form hysteresis loop of the 1-D element under a harmonic
displacement, the closed-form steady sliding of the 2-D element driven round a circle (and
the closed-form steady state of the discrete return on it), the convergence of the
return mapping onto the event-driven integration of the continuous law along an ellipse
and along an oscillator's own motion, and the oscillator's energy balance through stick,
slip and separation."""

import math
from collections import Counter

import numpy as np
import pytest

from shroudnet.references.jenkins import (
    LEDGER_COLUMNS,
    MODES,
    OPEN,
    SLIP,
    STICK,
    JenkinsOscillator,
    return_mapping,
    run_oscillator,
    slide_path,
)

# The element of the closed-form checks: a = μN/k_t = 5 mm.
K_T, MU, N = 1000.0, 0.5, 10.0
A = MU * N / K_T
OMEGA = 2.0 * math.pi  # 1 s a cycle


def loop_area(u0):
    """The closed-form energy a cycle of the 1-D element under r_t = u0 sin ωt, u0 > a:
    a parallelogram of height 2μN and width 2(u0 − a)."""
    return 4.0 * MU * N * (u0 - A)


# ----------------------------------------------------------------------------------- 1-D


def test_the_1d_return_mapping_dissipates_the_closed_form_loop_area_at_second_order():
    u0 = 2.0 * A
    errors = {}
    for steps in (1000, 2000):
        h = 1.0 / steps
        # Samples at the midpoints t = (k + ½) h: each extreme of r_t falls half a step
        # between two samples, so the cut-off reversal is the same fraction of a step at
        # both sizes (on the extremes themselves the return would be exact).
        t = (np.arange(3 * steps) + 0.5) * h
        run = return_mapping(u0 * np.sin(OMEGA * t), N, K_T, MU, w0=0.0)
        assert run.dimension == 1 and run.slipping.any() and not run.slipping.all()
        cycle = slice(steps - 1, 2 * steps)  # the second cycle, after the first loading
        dissipated = run.dissipation[2 * steps - 1] - run.dissipation[steps - 1]
        errors[steps] = dissipated / loop_area(u0) - 1.0
        # The bound of a reversal cut short by half a step: u0 (1 − cos(ωh/2)).
        bound = u0 * (1.0 - math.cos(OMEGA * h / 2.0)) / (u0 - A)
        assert -1.0001 * bound <= errors[steps] <= 0.0
        # The loop's corners: ±μN at the turning points, where slip sets in again
        # 2a before the turning point.
        force, r = run.forces[cycle, 0], run.displacements[cycle, 0]
        assert force.max() == pytest.approx(MU * N, rel=1e-13)
        assert force.min() == pytest.approx(-MU * N, rel=1e-13)
        top = int(np.argmax(r))
        assert force[top] == pytest.approx(MU * N, rel=1e-13)
        onset = top + int(np.argmax(run.slipping[cycle][top + 1:])) + 1
        assert force[onset] == pytest.approx(-MU * N, rel=1e-13)
        assert r[onset] <= r[top] - 2.0 * A < r[onset - 1]
        assert not run.slipping[cycle][top + 1:onset].any()
    # Measured: −9.87e-6 at 1000 steps a cycle, −2.47e-6 at 2000: a ratio of 4.000.
    assert errors[1000] / errors[2000] == pytest.approx(4.0, rel=1e-3)
    assert abs(errors[2000]) < 2.5e-6


def test_the_1d_continuous_element_dissipates_the_closed_form_loop_area():
    u0 = 2.0 * A
    run = slide_path(lambda t: (u0 * math.sin(OMEGA * t), u0 * OMEGA * math.cos(OMEGA * t)),
                     N, K_T, MU, 3.0, t_eval=[1.0, 2.0, 3.0])
    # Measured: 8.9e-13.
    assert (run.dissipation[1] - run.dissipation[0]) / loop_area(u0) == pytest.approx(
        1.0, abs=1e-10)
    assert run.mode_counts[STICK] >= 6 and run.mode_counts[SLIP] >= 6
    assert set(run.switch_kinds) == {"breakaway", "sticking"}


# ------------------------------------------------------------------------- 2-D, a circle


def test_the_2d_return_mapping_slides_round_a_circle_as_the_closed_form_at_first_order():
    r = 2.0 * A
    lag = math.sqrt(r * r - A * A)  # r_w: the slider's radius, (r_t − w) ⊥ w
    turns = 12
    radius_errors, energy_errors = {}, {}
    for steps in (1000, 2000):
        angle = np.arange(turns * steps + 1) * (2.0 * math.pi / steps)
        path = r * np.column_stack([np.cos(angle), np.sin(angle)])
        run = return_mapping(path, N, K_T, MU, w0=[0.0, 0.0])
        last = slice((turns - 1) * steps, turns * steps + 1)
        force = np.linalg.norm(run.forces[last], axis=1)
        spring = np.linalg.norm(run.displacements[last] - run.slider[last], axis=1)
        radius = np.linalg.norm(run.slider[last], axis=1)
        assert run.slipping[last].all()
        assert np.abs(force / (MU * N) - 1.0).max() < 1e-13     # |f| = μN
        assert np.abs(spring / A - 1.0).max() < 1e-12            # a behind the driver
        # The discrete return's own steady state (module docstring): the radius ρ of
        # ρ² + 2aρ sin(Δθ/2) + a² = r², and μN·2ρ sin(Δθ/2) a step.
        s = math.sin(math.pi / steps)
        discrete = -A * s + math.sqrt(A * A * s * s + r * r - A * A)
        assert np.abs(radius / discrete - 1.0).max() < 1e-11
        dissipated = run.dissipation[turns * steps] - run.dissipation[(turns - 1) * steps]
        assert dissipated / (steps * MU * N * 2.0 * discrete * s) == pytest.approx(1.0,
                                                                                 abs=1e-11)
        radius_errors[steps] = radius.mean() / lag - 1.0
        energy_errors[steps] = dissipated / (2.0 * math.pi * lag * MU * N) - 1.0
        # The first-order bound: ρ − r_w ≈ −a sin(Δθ/2).
        assert abs(radius_errors[steps]) <= 1.01 * A * s / lag
    # Measured: radius −1.81e-3 and −9.07e-4, energy a turn −1.81e-3 and −9.07e-4.
    assert radius_errors[1000] / radius_errors[2000] == pytest.approx(2.0, rel=1e-2)
    assert energy_errors[1000] / energy_errors[2000] == pytest.approx(2.0, rel=1e-2)
    assert abs(energy_errors[2000]) < 1e-3


def test_the_2d_continuous_element_slides_round_a_circle_as_the_closed_form():
    r = 2.0 * A
    lag = math.sqrt(r * r - A * A)

    def circle(t):
        c, s = math.cos(OMEGA * t), math.sin(OMEGA * t)
        return r * np.array([c, s]), r * OMEGA * np.array([-s, c])
    run = slide_path(circle, N, K_T, MU, 12.0, w0=[0.0, 0.0],
                     t_eval=np.linspace(11.0, 12.0, 101))
    radius = np.linalg.norm(run.slider, axis=1)
    force = np.linalg.norm(run.forces, axis=1)
    spring = np.linalg.norm(run.displacements - run.slider, axis=1)
    # Measured: 3.5e-10 (what is left of the start after 11 turns), 1.0e-9, 1.0e-9, 6.2e-10.
    assert np.abs(radius / lag - 1.0).max() < 1e-8
    assert np.abs(force / (MU * N) - 1.0).max() < 1e-8
    assert np.abs(spring / A - 1.0).max() < 1e-8
    assert np.abs(np.einsum("ij,ij->i", run.slider, run.displacements - run.slider)).max() \
        < 1e-8 * lag * A                                          # (r_t − w) ⊥ w
    dissipated = run.dissipation[-1] - run.dissipation[0]
    assert dissipated / (2.0 * math.pi * lag * MU * N) == pytest.approx(1.0, abs=1e-8)
    assert set(run.modes) == {SLIP}


# ----------------------------------------------------------------------- 2-D, an ellipse


def test_the_return_mapping_converges_onto_the_continuous_element_along_an_ellipse():
    """A flat ellipse, 3a by 0.8a: the element sticks at either end of it and slips along
    its flanks; the return's slider converges on the event-driven one at first order."""
    major, minor = 3.0 * A, 0.8 * A

    def ellipse(t):
        c, s = math.cos(OMEGA * t), math.sin(OMEGA * t)
        return (np.array([major * c, minor * s]),
                np.array([-major * OMEGA * s, minor * OMEGA * c]))
    errors, energy = {}, {}
    for steps in (1000, 2000):
        t = np.arange(2 * steps + 1) / steps
        reference = slide_path(ellipse, N, K_T, MU, 2.0, t_eval=t)
        path = np.column_stack([major * np.cos(OMEGA * t), minor * np.sin(OMEGA * t)])
        assert np.abs(reference.displacements - path).max() < 1e-9 * A
        run = return_mapping(path, N, K_T, MU)
        errors[steps] = np.abs(run.slider - reference.slider).max() / A
        energy[steps] = run.dissipation[-1] / reference.dissipation[-1] - 1.0
    counts = Counter(reference.switch_kinds)
    assert counts["breakaway"] == 4 and counts["sticking"] == 3
    assert reference.mode_counts == {OPEN: 0, STICK: 4, SLIP: 4}
    # Measured: slider 3.34e-3 a and 1.68e-3 a; energy −9.9e-4 and −4.9e-4.
    assert errors[1000] / errors[2000] == pytest.approx(2.0, rel=0.05)
    assert energy[1000] / energy[2000] == pytest.approx(2.0, rel=0.05)
    assert errors[2000] < 2e-3 and abs(energy[2000]) < 1e-3


# ------------------------------------------------------------------------- the oscillator

STIFFNESS = np.array([[100.0, 20.0, 5.0], [20.0, 150.0, 10.0], [5.0, 10.0, 80.0]])


def oscillator(dimension):
    """A 1 kg mass, pressed onto the ground by 20 N and lifted off it for part of each
    cycle by 22 N at 7 rad/s, while 8 N drive it along the ground."""
    keep = [0, 2] if dimension == 1 else [0, 1, 2]
    stiffness = STIFFNESS[np.ix_(keep, keep)]
    return JenkinsOscillator(
        mass=1.0, stiffness=stiffness, normal_stiffness=1000.0, tangential_stiffness=500.0,
        mu=0.4, force_static=np.array([0.0, 0.0, 20.0])[keep],
        force_cos=np.array([8.0, 1.0, 22.0])[keep], force_sin=np.array([2.0, 5.6, -6.0])[keep],
        frequency=7.0, damping=0.5 * np.eye(dimension + 1) + 1e-3 * stiffness)


@pytest.fixture(scope="module", params=[1, 2], ids=["1-D", "2-D"])
def oscillator_run(request):
    system = oscillator(request.param)
    period = 2.0 * math.pi / system.frequency
    x0 = np.zeros(system.dimension + 1)
    x0[-1] = 20.0 / 1080.0  # pressed in by the preload
    return run_oscillator(system, x0, np.zeros_like(x0), 4.0 * period, rtol=1e-12,
                          atol=1e-14, t_eval=np.linspace(0.0, 4.0 * period, 8001))


def test_the_oscillator_ledger_closes_through_stick_slip_and_separation(oscillator_run):
    run = oscillator_run
    assert LEDGER_COLUMNS == ("excitation", "damping", "friction")
    excitation, damping, friction = run.ledger[-1]
    assert excitation > 5.0 and damping > 1.0 and friction > 1.0
    assert np.all(np.diff(run.ledger[:, 1:], axis=0) >= -1e-12)  # losses only grow
    # Measured: 3.0e-12 (1-D) and 1.9e-12 (2-D) of the excitation's work.
    assert np.abs(run.residual).max() <= 1e-8 * excitation
    # Every mode and every switch, several times over four periods.
    modes = [segment[2] for segment in run.segments]
    transitions = Counter(zip(modes[:-1], modes[1:]))
    assert transitions[(OPEN, STICK)] >= 5 and transitions[(OPEN, SLIP)] >= 3
    assert transitions[(STICK, SLIP)] >= 10 and transitions[(SLIP, STICK)] >= 5
    assert transitions[(SLIP, OPEN)] >= 10
    assert all(run.mode_counts[mode] >= 10 for mode in MODES)
    kinds = Counter(run.switch_kinds)
    assert kinds["closing"] == kinds["separation"] >= 10
    # The samples keep to the modes' laws.
    open_ = np.array([mode == OPEN for mode in run.modes])
    assert np.all(run.normal_loads[open_] == 0.0) and np.all(run.forces[open_] == 0.0)
    force = np.linalg.norm(run.forces, axis=1)
    assert np.all(force <= 0.4 * run.normal_loads * (1.0 + 1e-8) + 1e-12)


def test_the_oscillator_element_is_the_return_mapping_of_its_own_motion(oscillator_run):
    """The oscillator's tangential motion and normal load fed to ``return_mapping``: its
    friction loss converges on the integrated one at first order, through separations,
    and its forces stay within a first-order bound. (The force error is not monotone in
    the step: a closing between two samples costs up to k_t|ẋ_t| h, by where it falls.)"""
    run = oscillator_run
    system = run.oscillator
    d = system.dimension
    speed = np.linalg.norm(run.v[:, :d], axis=1).max()
    errors = {}
    for stride in (4, 2, 1):
        sampled = slice(None, None, stride)
        step = run.times[stride] - run.times[0]
        mapped = return_mapping(run.x[sampled, :d], run.normal_loads[sampled],
                                system.tangential_stiffness, system.mu)
        force = np.linalg.norm(mapped.forces - run.forces[sampled], axis=1)
        # Measured: at most 0.18 (1-D) and 0.21 (2-D) of k_t max|ẋ_t| h.
        assert force.max() <= 0.3 * system.tangential_stiffness * speed * step
        errors[stride] = mapped.dissipation[-1] / run.ledger[-1, 2] - 1.0
    # Measured: −4.4e-2, −2.2e-2, −1.1e-2 (1-D); −4.1e-2, −2.1e-2, −1.1e-2 (2-D).
    assert errors[4] / errors[2] == pytest.approx(2.0, rel=0.1)
    assert errors[2] / errors[1] == pytest.approx(2.0, rel=0.1)
    assert abs(errors[1]) < 1.5e-2


# ---------------------------------------------------------------------------- bad input


@pytest.mark.parametrize("arguments, field", [
    (dict(stiffness=0.0), "stiffness"),
    (dict(mu=-0.1), "mu"),
    (dict(normal_loads=[10.0, -1.0, 10.0]), "normal_loads"),
    (dict(normal_loads=[10.0, 10.0]), "normal_loads"),
    (dict(displacements=np.zeros((3, 4))), "displacements"),
    (dict(displacements=[0.0, np.nan, 1.0]), "displacements"),
    (dict(w0=[0.0, 0.0]), "w0"),
])
def test_return_mapping_names_the_bad_field(arguments, field):
    call = dict(displacements=[0.0, 1e-3, 2e-3], normal_loads=10.0, stiffness=K_T, mu=MU)
    call.update(arguments)
    with pytest.raises(ValueError, match=rf"return_mapping\.{field} "):
        return_mapping(**call)


def test_slide_path_names_the_bad_field():
    def line(t):
        return np.array([t]), np.array([1.0])
    for arguments, field in [((line, 0.0, K_T, MU, 1.0), "normal_load"),
                             ((line, N, K_T, 0.0, 1.0), "mu"),
                             ((line, N, K_T, MU, -1.0), "t_end")]:
        with pytest.raises(ValueError, match=rf"slide_path\.{field} "):
            slide_path(*arguments)
    with pytest.raises(TypeError, match=r"slide_path\.path "):
        slide_path(None, N, K_T, MU, 1.0)
    with pytest.raises(TypeError, match=r"slide_path\.max_switches "):
        slide_path(line, N, K_T, MU, 1.0, max_switches=1.5)
    with pytest.raises(ValueError, match=r"slide_path\.t_eval "):
        slide_path(line, N, K_T, MU, 1.0, t_eval=[0.5, 0.2])
    with pytest.raises(ValueError, match=r"slide_path\.w0 "):
        slide_path(line, N, K_T, MU, 1.0, w0=[0.0, 0.0])


@pytest.mark.parametrize("change, field", [
    (dict(mass=0.0), "mass"),
    (dict(stiffness=np.zeros((2, 3))), "stiffness"),
    (dict(stiffness=np.array([[1.0, 2.0], [0.0, 1.0]])), "stiffness"),
    (dict(normal_stiffness=-1.0), "normal_stiffness"),
    (dict(tangential_stiffness=float("inf")), "tangential_stiffness"),
    (dict(mu=0.0), "mu"),
    (dict(force_cos=[1.0, 2.0, 3.0]), "force_cos"),
    (dict(damping=-np.eye(2)), "damping"),
    (dict(gap=float("nan")), "gap"),
])
def test_the_oscillator_names_the_bad_field(change, field):
    fields = dict(mass=1.0, stiffness=np.eye(2), normal_stiffness=1.0,
                  tangential_stiffness=1.0, mu=0.3, force_static=[0.0, 1.0],
                  force_cos=[1.0, 0.0], force_sin=[0.0, 0.0], frequency=1.0)
    fields.update(change)
    with pytest.raises(ValueError, match=rf"JenkinsOscillator\.{field} "):
        JenkinsOscillator(**fields)


def test_run_oscillator_names_the_bad_field():
    system = oscillator(1)
    pressed = np.array([0.0, 0.02])
    for arguments, options, field in [((np.zeros(3), np.zeros(2), 1.0), {}, "x0"),
                                      ((pressed, np.zeros(2), 0.0), {}, "t_end"),
                                      ((pressed, np.zeros(2), 1.0), dict(w0=[1.0]), "w0"),
                                      ((pressed, np.zeros(2), 1.0), dict(rtol=0.0), "rtol")]:
        with pytest.raises(ValueError, match=rf"run_oscillator\.{field} "):
            run_oscillator(system, *arguments, **options)
    with pytest.raises(TypeError, match=r"run_oscillator\.oscillator "):
        run_oscillator("system", pressed, np.zeros(2), 1.0)
