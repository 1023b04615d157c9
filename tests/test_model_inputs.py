"""Bad inputs fail early and clearly; the forcing model is the travelling pattern it claims.

What a user types wrong (a number for a sequence, a word for a phase pattern, a numpy
integer, a run that cannot fit in memory, a law that breaks its contract) is refused before
any work with a message that names the field and what is allowed. The excitation is checked
against its closed form: harmonic n carries n φ_i, engine-order forcing of a ring excites
ND = l mod N, and each blade's force is scaled by its ``excitation_scale``.
"""

import math
import re
import sys
from dataclasses import dataclass
from pathlib import Path

import numpy as np
import pytest

import contact_laws as cl
from shroudnet import (
    AntiPhase,
    Blade,
    BladeGroup,
    Excitation,
    ExplicitPhases,
    FixedStep,
    Interface,
    Mode,
    Scene,
    TravellingWave,
    ZenoGuard,
    assemble,
    classify,
    friction_loss_per_cycle,
    simulate,
    spectrum,
)
from shroudnet.io.scenefile import load
from shroudnet.model.excitation import ENGINE_ORDER_MAX, EngineOrderWave
from shroudnet.references.blades import solve_ivp_baseline
from shroudnet.scenes import three_blade_paper
from tests.laws import CubicSpring, PreloadedStop, RationalWeakening

ROOT = Path(__file__).resolve().parents[1]
BLADE = Blade(mass=0.1, damping=2.0, stiffness=1e5)
SHROUD = Interface(gap=1e-5, angle=0.5, normal=cl.LinearSpring(stiffness=1e5),
                   friction=cl.Coulomb(mu=0.3))
EXCITATION = Excitation(engine_order=2, amplitudes=(0.0, 10.0), phases=AntiPhase())
#: The module (``shroudnet.simulate`` the attribute is the function of the same name).
simulate_module = sys.modules["shroudnet.run.simulate"]


# ---- check_int ------------------------------------------------------------------------------

@pytest.mark.parametrize("value", [3, np.int64(3), np.int32(3), np.uint8(3)])
def test_check_int_takes_python_and_numpy_integers(value):
    number = cl.check_int("Owner", "count", value, low=1, high=5)
    assert number == 3 and type(number) is int


@pytest.mark.parametrize("value, error, message", [
    (True, TypeError, r"Owner\.count must be an int, got bool True"),
    (np.bool_(True), TypeError, r"Owner\.count must be an int, got bool"),
    (2.0, TypeError, r"Owner\.count must be an int, got float 2\.0"),
    ("3", TypeError, r"Owner\.count must be an int, got str '3'"),
    (None, TypeError, r"Owner\.count must be an int, got NoneType"),
    (0, ValueError, r"Owner\.count must be an int >= 1 and <= 5, got 0"),
    (np.int64(6), ValueError, r"Owner\.count must be an int >= 1 and <= 5, got 6"),
])
def test_check_int_names_the_field_and_the_range(value, error, message):
    with pytest.raises(error, match=message):
        cl.check_int("Owner", "count", value, low=1, high=5)


def test_check_int_takes_whole_floats_only_when_asked():
    assert cl.check_int("O", "skip", np.float64(4.0), whole_floats=True) == 4
    assert cl.check_int("O", "skip", 4.0, whole_floats=True) == 4
    for value in (4.5, math.nan, math.inf, True):
        with pytest.raises(TypeError, match=r"O\.skip must be an int \(or a whole float\)"):
            cl.check_int("O", "skip", value, whole_floats=True)
    with pytest.raises(ValueError, match=r"must be an int <= N − 1 = 2, got 3"):
        cl.check_int("O", "nd", 3, high=2, high_label="N − 1")


@pytest.mark.parametrize("make, field", [
    (lambda n: Excitation(engine_order=n, amplitudes=(0.0, 1.0), phases=AntiPhase()),
     "engine_order"),
    (lambda n: TravellingWave(n), "nodal_diameter"),
    (lambda n: FixedStep(steps_per_period=n * 8), "steps_per_period"),
    (lambda n: ZenoGuard(events=n * 2), "events"),
])
def test_numpy_integers_are_taken_and_stored_as_int(make, field):
    made = make(np.int64(2))
    assert type(getattr(made, field)) is int


def test_group_presets_take_numpy_counts_and_refuse_others():
    assert len(BladeGroup.chain(np.int64(4), BLADE, SHROUD).blades) == 4
    assert len(BladeGroup.ring(np.int32(5), BLADE, SHROUD).interfaces) == 5
    with pytest.raises(TypeError, match=r"BladeGroup\.chain\.n must be an int, got float"):
        BladeGroup.chain(3.0, BLADE, SHROUD)
    with pytest.raises(TypeError, match=r"BladeGroup\.ring\.n must be an int, got bool"):
        BladeGroup.ring(True, BLADE, SHROUD)
    with pytest.raises(ValueError, match=r"BladeGroup\.chain\.n must be an int >= 1, got 0"):
        BladeGroup.chain(0, BLADE, SHROUD)


@pytest.mark.parametrize("make, error, message", [
    (lambda: FixedStep(steps_per_period=True), TypeError,
     r"FixedStep\.steps_per_period must be an int, got bool"),
    (lambda: FixedStep(steps_per_period=4), ValueError,
     r"FixedStep\.steps_per_period must be an int >= 8 and <= 1000000, got 4"),
    (lambda: ZenoGuard(events=2.5), TypeError, r"ZenoGuard\.events must be an int, got float"),
    (lambda: Excitation(engine_order=2.0, amplitudes=(0.0,), phases=AntiPhase()), TypeError,
     r"Excitation\.engine_order must be an int, got float 2\.0"),
])
def test_integer_knobs_refuse_other_types_clearly(make, error, message):
    with pytest.raises(error, match=message):
        make()


@pytest.mark.parametrize("kwargs, error, message", [
    (dict(periods=2.0), TypeError, r"simulate\.periods must be an int, got float"),
    (dict(periods=np.int64(0)), ValueError, r"simulate\.periods must be an int >= 1, got 0"),
    (dict(periods=2, samples_per_period="10"), TypeError,
     r"simulate\.samples_per_period must be an int, got str"),
    (dict(periods=2, event_capacity=-1), ValueError,
     r"simulate\.event_capacity must be an int >= 0"),
])
def test_simulate_checks_its_integers_before_any_work(kwargs, error, message):
    with pytest.raises(error, match=message):
        simulate(three_blade_paper(), **kwargs)


# ---- the excitation's own inputs ----------------------------------------------------------

@pytest.mark.parametrize("amplitudes", [50.0, 50, "50", None])
def test_amplitudes_must_be_a_sequence(amplitudes):
    with pytest.raises(TypeError, match=r"Excitation\.amplitudes must be a sequence "
                                        r"\(q0, q1, …\) \[N\].*\(0\.0, 50\.0\)"):
        Excitation(engine_order=2, amplitudes=amplitudes, phases=AntiPhase())


def test_amplitudes_take_a_numpy_array():
    excitation = Excitation(engine_order=2, amplitudes=np.array([1.0, 2.0]), phases=AntiPhase())
    assert excitation.amplitudes == (1.0, 2.0) and excitation.n_harmonics == 1


@pytest.mark.parametrize("phases", ["anti-phase", b"anti-phase", 3.0, None])
def test_a_phase_pattern_that_is_no_pattern_lists_the_accepted_ones(phases):
    with pytest.raises(TypeError) as raised:
        Excitation(engine_order=2, amplitudes=(0.0, 1.0), phases=phases)
    message = str(raised.value)
    assert message.startswith("Excitation.phases must be ")
    for pattern in ("AntiPhase()", "TravellingWave(nd)", "EngineOrderWave()",
                    "ExplicitPhases(values)"):
        assert pattern in message


def test_explicit_phases_refuse_a_single_number():
    with pytest.raises(TypeError, match=r"ExplicitPhases\.values must be a sequence"):
        ExplicitPhases(1.0)
    assert ExplicitPhases(np.array([0.0, 1.0])).values == (0.0, 1.0)


def test_engine_order_is_bounded():
    Excitation(engine_order=ENGINE_ORDER_MAX, amplitudes=(0.0, 1.0), phases=AntiPhase())
    with pytest.raises(ValueError, match=r"Excitation\.engine_order must be an int >= 1 and "
                                         r"<= 1000, got 1000000"):
        Excitation(engine_order=10**6, amplitudes=(0.0, 1.0), phases=AntiPhase())


def test_nodal_diameter_lies_in_0_to_n_minus_1():
    excitation = Excitation(engine_order=2, amplitudes=(0.0, 1.0), phases=TravellingWave(100))
    with pytest.raises(ValueError, match=r"TravellingWave\.nodal_diameter must be in "
                                         r"\[0, N − 1\] = \[0, 2\] for N = 3 blades, got 100"):
        Scene(group=BladeGroup.chain(3, BLADE, SHROUD), excitation=excitation, speed_rpm=1e3)
    with pytest.raises(ValueError, match=r"TravellingWave\.nodal_diameter must be an int >= 0"):
        TravellingWave(-1)
    # ND = N − 1 is the backward wave of one nodal diameter: the conjugate phases.
    np.testing.assert_allclose(np.exp(1j * TravellingWave(7).phases(8)),
                               np.conj(np.exp(1j * TravellingWave(1).phases(8))), atol=1e-12)


# ---- engine-order forcing of a ring ---------------------------------------------------------

@pytest.mark.parametrize("engine_order, n_blades", [(2, 24), (7, 5), (24, 24), (30, 12)])
def test_engine_order_wave_has_engine_order_mod_n_nodal_diameters(engine_order, n_blades):
    scene = Scene(group=BladeGroup.ring(n_blades, BLADE, SHROUD), speed_rpm=3000.0,
                  excitation=Excitation(engine_order=engine_order, amplitudes=(0.0, 1.0),
                                        phases=EngineOrderWave()))
    assert scene.excitation.phases == TravellingWave(engine_order % n_blades)
    # A blade at angle 2π i/N meets l lobes with the phase l · 2π i/N.
    expected = np.exp(2j * math.pi * engine_order * np.arange(n_blades) / n_blades)
    np.testing.assert_allclose(np.exp(1j * scene.arrays.phases), expected, atol=1e-12)


def packet_scene(phases, n_blades=6, engine_order=4):
    return Scene(group=BladeGroup.chain(n_blades, BLADE, SHROUD), speed_rpm=3000.0,
                 excitation=Excitation(engine_order=engine_order, amplitudes=(0.0, 1.0),
                                       phases=phases))


def test_a_packet_on_a_disc_meets_the_disc_s_phase_steps():
    """6 blades of a 36-blade disc at l = 4: 2π·4/36 = 40° between neighbours (not the
    240° of a disc of 6); l = 40 ≡ 4 on 36 blades gives the same phases."""
    for order in (4, 40):
        scene = packet_scene(EngineOrderWave(blades_on_disc=36), engine_order=order)
        steps = np.angle(np.exp(1j * np.diff(scene.arrays.phases)), deg=True)
        np.testing.assert_allclose(steps, 40.0, atol=1e-12)
    whole = packet_scene(EngineOrderWave(blades_on_disc=6))
    np.testing.assert_allclose(np.exp(1j * whole.arrays.phases),
                               np.exp(1j * TravellingWave(4).phases(6)), atol=1e-12)


def test_an_open_packet_taken_for_a_whole_disc_is_said_once():
    import warnings
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("default")
        for _ in range(3):
            packet_scene(EngineOrderWave())
    said = [w for w in caught if "blades_on_disc" in str(w.message)]
    assert len(said) == 1
    assert "takes this packet's 6 blades for a whole disc of 6" in str(said[0].message)
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        packet_scene(EngineOrderWave(blades_on_disc=36))
        Scene(group=BladeGroup.ring(6, BLADE, SHROUD), speed_rpm=3000.0,
              excitation=Excitation(engine_order=4, amplitudes=(0.0, 1.0),
                                    phases=EngineOrderWave()))


@pytest.mark.parametrize("disc, error, message", [
    (0, ValueError, r"EngineOrderWave.blades_on_disc must be"),
    (2.5, TypeError, r"EngineOrderWave.blades_on_disc must be"),
    (5, ValueError, r"blades_on_disc = 5 is fewer than the group's 6 blades"),
])
def test_blades_on_disc_is_checked(disc, error, message):
    with pytest.raises(error, match=message):
        packet_scene(EngineOrderWave(blades_on_disc=disc))


def test_scene_files_place_a_packet_on_its_disc():
    from shroudnet.io import scenefile
    document = scenefile.document(packet_scene(EngineOrderWave(blades_on_disc=36)))
    document["excitation"]["phases"] = "engine-order"
    document["excitation"]["blades_on_disc"] = 36
    scene = scenefile.read(document).scene
    steps = np.angle(np.exp(1j * np.diff(scene.arrays.phases)), deg=True)
    np.testing.assert_allclose(steps, 40.0, atol=1e-12)
    document["excitation"]["phases"] = "anti-phase"
    with pytest.raises(ValueError, match='blades_on_disc: goes with phases = "engine-order"'):
        scenefile.read(document)
    document["excitation"]["phases"] = "engine-order"
    document["excitation"]["blades_on_disc"] = -1
    with pytest.raises(ValueError, match="blades_on_disc must be"):
        scenefile.read(document)


def test_shipped_ring_scene_is_engine_order_forcing():
    scene = load(ROOT / "examples" / "scenes" / "ring_24_travelling_wave.toml").scene
    n = len(scene.blades)
    assert scene.excitation.phases == TravellingWave(scene.excitation.engine_order % n)


# ---- the forcing model: harmonic n carries n φ_i, blade i is scaled by s_i ------------------

def closed_form_forces(scene, t):
    """Q_i(t) = s_i [q0 + Σ_n q_n sin(n (lΩ t + φ_i))], from the scene's parts."""
    ex = scene.excitation
    scale = np.array([scene.group.blade(name).excitation_scale for name in scene.blades])
    phase = scene.arrays.excitation_frequency * t + ex.blade_phases(len(scene.blades))
    q = ex.amplitudes[0] + sum(ex.amplitudes[n] * np.sin(n * phase)
                               for n in range(1, len(ex.amplitudes)))
    return scale * q


def free_scene(phases, amplitudes=(1.0, 30.0, 12.0, 5.0), scales=(1.0, 1.0, 1.0, 1.0),
               engine_order=2):
    """Four blades in a ring whose contacts never close (gap 1 m): each a linear oscillator."""
    group = BladeGroup()
    names = [f"blade{i}" for i in range(1, 5)]
    for name, scale, k in zip(names, scales, (1.5e5, 1.6e5, 1.4e5, 1.55e5)):
        group.add_blade(name, Blade(mass=0.082, damping=4.0, stiffness=k,
                                    excitation_scale=scale))
    shroud = Interface(gap=1.0, angle=1.0, normal=cl.LinearSpring(stiffness=3e5),
                       friction=cl.ExponentialFriction(mu_static=0.5, mu_kinetic=0.3,
                                                       beta=5.0))
    for left, right in zip(names, names[1:] + names[:1]):
        group.connect(left, right, shroud)
    return Scene(group=group, speed_rpm=6000.0, excitation=Excitation(
        engine_order=engine_order, amplitudes=amplitudes, phases=phases))


def test_harmonic_tables_carry_n_phi_and_the_blade_scale():
    scene = free_scene(TravellingWave(1), scales=(1.0, 0.0, 0.5, -2.0))
    a = scene.arrays
    n = np.arange(4)[:, None]
    np.testing.assert_allclose(a.harmonic_phases, n * a.phases[None, :])
    np.testing.assert_allclose(a.harmonic_amplitudes,
                               np.array([1.0, 30.0, 12.0, 5.0])[:, None] * [1.0, 0.0, 0.5, -2.0])
    np.testing.assert_array_equal(a.excitation_scale, [1.0, 0.0, 0.5, -2.0])
    assert a.static_deflection == pytest.approx(2.0 * 48.0 / 1.55e5)


@pytest.mark.parametrize("phases", [TravellingWave(1), AntiPhase(), EngineOrderWave(),
                                    ExplicitPhases((0.3, -1.0, 2.0, 0.5))])
@pytest.mark.parametrize("t", [0.0, 1.3e-4, 2.71e-3])
def test_assembled_forces_are_the_closed_form_with_n_phi(phases, t):
    scene = free_scene(phases, scales=(1.0, 0.0, 0.5, 2.0))
    zero = np.zeros(4)
    r = assemble(scene, t, zero, zero, [Mode.OPEN] * 4)
    np.testing.assert_allclose(r.acceleration * scene.arrays.mass,
                               closed_form_forces(scene, t), rtol=1e-12, atol=1e-12)


def test_a_travelling_wave_reaches_each_blade_as_the_first_one_delayed():
    """Every harmonic of Q_i is Q_0 shifted by φ_i/(lΩ): the force travels as one pattern."""
    scene = free_scene(TravellingWave(1))
    a = scene.arrays
    zero = np.zeros(4)
    for t in np.linspace(0.0, scene.excitation_period, 7):
        q = assemble(scene, t, zero, zero, [Mode.OPEN] * 4).acceleration * a.mass
        for i in range(4):
            later = t + a.phases[i] / a.excitation_frequency
            q0 = assemble(scene, later, zero, zero, [Mode.OPEN] * 4).acceleration[0] * a.mass[0]
            assert q[i] == pytest.approx(q0, rel=1e-10, abs=1e-10)


def test_the_paper_scene_keeps_its_forces():
    """With q0 and q1 only, n φ_i and φ_i coincide: the paper's anti-phase forcing is
    q1 sin(lΩt + φ_i) as before."""
    scene = three_blade_paper()
    a = scene.arrays
    np.testing.assert_array_equal(a.harmonic_phases[1], a.phases)
    zero = np.zeros(3)
    for t in (0.0, 1e-3, 3.3e-3):
        q = assemble(scene, t, zero, zero, [Mode.OPEN] * 2).acceleration * a.mass
        np.testing.assert_allclose(q, 50.0 * np.sin(a.excitation_frequency * t + a.phases),
                                   rtol=1e-13, atol=1e-12)


def linear_steady_state(scene, t):
    """x_i(t), ẋ_i(t) of the free blades' steady response, harmonic by harmonic."""
    a, ex = scene.arrays, scene.excitation
    t = np.asarray(t)[:, None]
    x = a.harmonic_amplitudes[0] / a.stiffness + 0.0 * t
    v = 0.0 * t
    for n in range(1, len(ex.amplitudes)):
        w = n * a.excitation_frequency
        response = a.harmonic_amplitudes[n] / np.hypot(a.stiffness - a.mass * w**2,
                                                       a.damping * w)
        lag = np.arctan2(a.damping * w, a.stiffness - a.mass * w**2)
        angle = w * t + a.harmonic_phases[n] - lag
        x = x + response * np.sin(angle)
        v = v + response * w * np.cos(angle)
    return x, v


@pytest.fixture(scope="module")
def free_run():
    """A run of the free ring under three harmonics of a travelling wave, one blade unforced
    (a damper modelled as a node) and one pushed the other way (a negative participation
    factor), started on its closed-form steady state."""
    scene = free_scene(TravellingWave(1), scales=(1.0, 0.0, -0.24, 1.0))
    x0, v0 = linear_steady_state(scene, [0.0])
    return simulate(scene, 6, method=FixedStep(steps_per_period=1000), samples_per_period=40,
                    initial=(x0[0], v0[0]))


def test_the_integrator_follows_the_closed_form_of_every_harmonic(free_run):
    x, v = linear_steady_state(free_run.scene, free_run.t)
    assert np.abs(free_run.x - x).max() < 1e-6 * np.abs(x).max()
    assert np.abs(free_run.v - v).max() < 1e-6 * np.abs(v).max()
    ledger = free_run.energy  # the work of the scaled, phased forces balances the losses
    assert abs(ledger.residual) < 1e-6 * ledger.damping_loss


def test_an_unforced_node_stays_at_rest(free_run):
    assert np.all(free_run.x[:, 1] == 0.0) and np.all(free_run.v[:, 1] == 0.0)
    assert np.abs(free_run.x[:, 0]).max() > 0.0


def test_the_plain_baseline_uses_the_same_forcing():
    scene = free_scene(TravellingWave(3), scales=(0.0, 1.0, 2.0, 1.0))
    x0, v0 = linear_steady_state(scene, [0.0])
    run = solve_ivp_baseline(scene, 2, rtol=1e-10, atol=1e-14, initial=(x0[0], v0[0]))
    x, _ = linear_steady_state(scene, scene.excitation_period * np.arange(3))
    assert np.abs(run.x - x).max() < 1e-7 * np.abs(x).max()


@pytest.mark.parametrize("scale, error", [(math.inf, ValueError), (math.nan, ValueError),
                                          ("1", TypeError)])
def test_excitation_scale_is_checked(scale, error):
    with pytest.raises(error, match=r"Blade\.excitation_scale"):
        Blade(mass=1.0, damping=0.0, stiffness=1.0, excitation_scale=scale)
    assert Blade(mass=1.0, damping=0.0, stiffness=1.0).excitation_scale == 1.0
    assert Blade(mass=1.0, damping=0.0, stiffness=1.0, excitation_scale=-0.24
                 ).excitation_scale == -0.24  # a participation factor has a sign


def test_a_negative_excitation_scale_mirrors_the_response():
    """A linear blade forced with −s moves as the one forced with s, mirrored: x → −x."""
    pushed, pulled = (free_scene(TravellingWave(1), scales=(s, 1.0, 1.0, 1.0))
                      for s in (0.24, -0.24))
    runs = [simulate(scene, 2, samples_per_period=20) for scene in (pushed, pulled)]
    np.testing.assert_allclose(runs[1].x[:, 0], -runs[0].x[:, 0], rtol=1e-9,
                               atol=1e-9 * np.abs(runs[0].x[:, 0]).max())
    np.testing.assert_allclose(runs[1].x[:, 1:], runs[0].x[:, 1:], rtol=1e-12, atol=0.0)


# ---- a run that cannot fit in memory --------------------------------------------------------

def test_a_run_too_large_for_memory_is_refused_before_any_work():
    with pytest.raises(ValueError, match=r"periods = 1000000000 with samples_per_period = 100 "
                                         r"would record .* samples and need .* GiB"):
        simulate(three_blade_paper(), 10**9)


def test_the_memory_bound_is_half_the_available_memory(monkeypatch):
    scene = three_blade_paper()
    needed = simulate_module.output_bytes(scene, 1000, 100, 0)
    # t, x, v, N, f, modes and 5 work columns per sample, for 3 blades and 2 interfaces.
    assert needed == (1000 * 100 + 1) * (8 * (1 + 6 + 4 + 5) + 2)
    monkeypatch.setattr(simulate_module, "available_memory", lambda: 2 * needed - 2)
    with pytest.raises(ValueError, match=r"more than half the .* GiB available"):
        simulate(scene, 1000, event_capacity=0)
    monkeypatch.setattr(simulate_module, "available_memory", lambda: None)
    with pytest.raises(ValueError, match=r"the 8 GiB allowed where the available memory"):
        simulate(scene, 10**7, event_capacity=0)


def test_available_memory_is_a_byte_count_or_unknown():
    available = simulate_module.available_memory()
    assert available is None or (isinstance(available, int) and available >= 0)


# ---- user laws probed at scene construction -------------------------------------------------

@dataclass(frozen=True, kw_only=True)
class OffsetSpring(cl.NormalLaw):
    """N = k (δ − δ0): negative for δ < δ0, against the contract."""

    stiffness: float
    offset: float

    @staticmethod
    def normal_force(penetration, rate, stiffness, offset):
        return stiffness * (penetration - offset)


@dataclass(frozen=True, kw_only=True)
class PlainKelvinVoigt(cl.NormalLaw):
    """N = k δ + c δ̇ without the clamp: it pulls while the contact opens fast."""

    stiffness: float
    damping: float

    @staticmethod
    def normal_force(penetration, rate, stiffness, damping):
        return stiffness * penetration + damping * rate


@dataclass(frozen=True, kw_only=True)
class UnguardedHertz(cl.NormalLaw):
    """N = k δ^1.5 without max(δ, 0): complex (Python) or NaN (numba) for δ < 0."""

    stiffness: float

    @staticmethod
    def normal_force(penetration, rate, stiffness):
        return stiffness * penetration**1.5


@dataclass(frozen=True, kw_only=True)
class LogSpring(cl.NormalLaw):
    """N = k exp(10⁶ δ/m): finite at small penetrations, overflowing at large ones."""

    stiffness: float

    @staticmethod
    def normal_force(penetration, rate, stiffness):
        return stiffness * math.exp(max(penetration, 0.0) * 1e6)


@dataclass(frozen=True, kw_only=True)
class StrengtheningFriction(cl.FrictionLaw):
    """μ rising with the slip speed from μ0: μ(v) > μ(0), against the contract."""

    mu: float

    @staticmethod
    def coefficient(slip_speed, mu):
        return mu * (1.0 + slip_speed)


@dataclass(frozen=True, kw_only=True)
class NegativeFriction(cl.FrictionLaw):
    """μ = μ0 − v: negative past v = μ0."""

    mu: float

    @staticmethod
    def coefficient(slip_speed, mu):
        return mu - slip_speed


def _scene_with(normal=cl.LinearSpring(stiffness=3e5), friction=None):
    shroud = Interface(gap=2e-5, angle=1.0, normal=normal, friction=friction)
    return Scene(group=BladeGroup.chain(3, BLADE, shroud), excitation=EXCITATION,
                 speed_rpm=6000.0)


@pytest.mark.parametrize("normal, message", [
    (OffsetSpring(stiffness=1e5, offset=1e-6),
     r"interface 0 \('blade1', 'blade2'\): normal law OffsetSpring\(.*\) gives N = .* < 0 "
     r"at penetration δ = .* m.*must be ≥ 0 for δ > 0.*sampling"),
    (PlainKelvinVoigt(stiffness=1e5, damping=50.0),
     r"interface 0 .*PlainKelvinVoigt.* < 0 at penetration .* rate δ̇ = -"),
    (UnguardedHertz(stiffness=1e9),
     r"interface 0 .*UnguardedHertz.* returned complex .* not a real number"),
    (LogSpring(stiffness=1.0),
     r"interface 0 .*LogSpring.* (returned inf|raised OverflowError)"),
])
def test_a_user_normal_law_breaking_its_contract_is_refused(normal, message):
    with pytest.raises(ValueError, match=message):
        _scene_with(normal=normal)


@pytest.mark.parametrize("friction, message", [
    (StrengtheningFriction(mu=0.3),
     r"interface 0 \('blade1', 'blade2'\): friction law StrengtheningFriction\(mu=0\.3\) "
     r"gives μ = .* at slip speed .* above its static coefficient μ_s = μ\(0\) = 0\.3"),
    (NegativeFriction(mu=0.3), r"NegativeFriction.* gives μ = .* < 0 at slip speed"),
    (cl.Regularised(law=StrengtheningFriction(mu=0.3), velocity=1e-3),
     r"StrengtheningFriction.*above its static coefficient"),
])
def test_a_user_friction_law_breaking_its_contract_is_refused(friction, message):
    with pytest.raises(ValueError, match=message):
        _scene_with(friction=friction)


def test_user_laws_that_keep_their_contract_are_accepted():
    _scene_with(normal=CubicSpring(linear=1e5, cubic=1e13),
                friction=RationalWeakening(mu_static=0.5, mu_kinetic=0.2, speed=0.05))
    _scene_with(normal=PreloadedStop(preload=2.0, stiffness=1e5),
                friction=cl.Regularised(law=RationalWeakening(mu_static=0.5, mu_kinetic=0.2,
                                                              speed=0.05), velocity=1e-3))


# ---- blade names and whole periods ----------------------------------------------------------

def test_presets_name_blades_from_one_as_the_paper_does():
    chain = BladeGroup.chain(3, BLADE, SHROUD)
    assert chain.blades == ["blade1", "blade2", "blade3"]
    ring = BladeGroup.ring(4, BLADE, SHROUD)
    assert [(a, b) for a, b, _ in ring.interfaces][-1] == ("blade4", "blade1")
    scene = Scene(group=chain, excitation=EXCITATION, speed_rpm=1e3)
    # Positions stay 0-based: "blade2" is position 1, as in the paper's scene.
    assert scene.blade_position("blade2") == 1 == three_blade_paper().blade_position("blade2")
    assert scene.blade_position(0) == 0


def test_energy_density_needs_skip(free_run):
    with pytest.raises(TypeError, match="skip"):
        free_run.energy_density("blade1")


@pytest.mark.parametrize("skip", [2, np.int64(2), 2.0, np.float64(2.0)])
def test_poincare_energy_density_and_spectra_take_the_same_whole_periods(free_run, skip):
    assert free_run.poincare("blade1", skip=skip).shape == (5, 2)
    reference = free_run.energy_density("blade1", skip=2)
    assert free_run.energy_density("blade1", skip=skip) == reference
    assert spectrum(free_run, "blade1", skip).resolution == 0.25
    assert friction_loss_per_cycle(free_run, skip) == 0.0


READINGS = {
    "Simulation.poincare": lambda sim, skip: sim.poincare("blade1", skip=skip),
    "Simulation.energy_density": lambda sim, skip: sim.energy_density("blade1", skip=skip),
    "spectrum": lambda sim, skip: spectrum(sim, "blade1", skip),
    "friction_loss_per_cycle": lambda sim, skip: friction_loss_per_cycle(sim, skip),
    "classify": lambda sim, skip: classify(sim, "blade1", skip, exponent=False),
}


@pytest.mark.parametrize("owner", READINGS)
def test_every_reading_of_a_steady_response_takes_skip_from_0_to_the_last_period(free_run,
                                                                               owner):
    """One range for all: the 6 periods of the run leave 0 … 5 to skip, the last one
    leaving one whole period to read; 6 and −1 are refused, naming the reading, the field
    and the range."""
    read = READINGS[owner]
    for skip in (0, 5, np.int64(5), 5.0):
        read(free_run, skip)
    assert free_run.poincare("blade1", skip=5).shape == (2, 2)
    for skip in (6, -1, 6.0):
        message = (rf"{re.escape(owner)}\.skip must be a whole number of periods in "
                   rf"\[0, 6\) \(the run's 6 periods, at least one left to read\), "
                   rf"got {int(skip)}")
        with pytest.raises(ValueError, match=message):
            read(free_run, skip)


@pytest.mark.parametrize("skip", [2.5, "2", True, None])
def test_fractional_or_other_skips_are_refused(free_run, skip):
    for call in (lambda: free_run.poincare("blade1", skip=skip),
                 lambda: free_run.energy_density("blade1", skip=skip),
                 lambda: spectrum(free_run, "blade1", skip)):
        with pytest.raises(TypeError, match=r"skip must be an int \(or a whole float\)"):
            call()
