"""Every public door refuses bad input by name: a property over the whole public surface.

The doors are the callables of ``shroudnet.__all__`` and ``contact_laws.__all__`` (classes'
constructors and functions; a module listed there, ``scenes``, adds its own public
functions), so a new export is walked the day it is added. Each door has one valid call in
``VALID``; a door without one fails ``test_every_door_has_a_valid_call``, so none is skipped
silently. The property substitutes one bad value (a wrong type, NaN, ±inf, a negative, zero,
an empty sequence, a 0-d or wrong-shaped array, a huge or tiny magnitude, a string, None)
into one argument of that call at a time, and asserts that the call either succeeds with
finite results or raises ``ValueError``, ``TypeError`` or a documented project error whose
message names the argument.
"""

from __future__ import annotations

import dataclasses
import enum
import functools
import inspect
import math
import types

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

import contact_laws
import shroudnet
from contact_laws import Coulomb, LinearSpring
from shroudnet import AntiPhase, Blade, BladeGroup, Excitation, Interface, Scene, scenes

pytestmark = pytest.mark.timeout(900)


@pytest.fixture(autouse=True)
def _in_a_scratch_folder(tmp_path, monkeypatch):
    """A door handed a random string as a folder (``sweep(save_to="Å")``) writes there:
    relative to a scratch folder, never to the checkout."""
    monkeypatch.chdir(tmp_path)


def _project_errors() -> tuple[type[Exception], ...]:
    from shroudnet.io.results import ResultsError
    from shroudnet.io.scenefile import SceneFileError
    return (ValueError, TypeError, shroudnet.SimulationError, shroudnet.ConvergenceError,
            SceneFileError, ResultsError)


# -- the doors ------------------------------------------------------------------------------

def _doors() -> dict[str, object]:
    doors = {}
    for package in (shroudnet, contact_laws):
        for name in package.__all__:
            value = getattr(package, name)
            if isinstance(value, types.ModuleType):
                for inner, member in vars(value).items():
                    if not inner.startswith("_") and inspect.isfunction(member) \
                            and member.__module__ == value.__name__:
                        doors[f"{name}.{inner}"] = member
            elif callable(value):
                doors[name if package is shroudnet else f"contact_laws.{name}"] = value
    return doors


DOORS = _doors()


# -- small, fast inputs that every valid call shares ----------------------------------------

@functools.cache
def paper() -> Scene:
    """The paper's three-blade group (its kernel is the one most tests compile)."""
    return scenes.three_blade_paper()


@functools.cache
def open_paper() -> Scene:
    """The paper's group with gaps no motion closes: linear, so orbits converge at once."""
    return scenes.three_blade_paper(gap=1.0)


@functools.cache
def run():
    return shroudnet.simulate(paper(), 2, samples_per_period=20)


@functools.cache
def orbit():
    return shroudnet.periodic_orbit(open_paper(), transient=2)


def scene_at(speed: float) -> Scene:
    return scenes.three_blade_paper(gap=1.0, speed_rpm=speed)


@functools.cache
def branch():
    return shroudnet.continuation(scene_at, 6000.0, 6010.0, step=0.5, max_points=2,
                                  transient=2)


@functools.cache
def swept():
    return shroudnet.sweep(scene_at, [6000.0], transient=1, record=3, workers=1,
                           progress=None)


def map_at(speed: float, q1: float) -> Scene:
    return scenes.three_blade_paper(gap=1.0, speed_rpm=speed, q1=q1)


@functools.cache
def mapped():
    return shroudnet.sweep_map(map_at, [6000.0], [40.0], transient=1, record=3, workers=1,
                               progress=None)


@functools.cache
def harmonic_orbit():
    """The Jenkins chain's orbit by harmonic balance, three harmonics (no kernel)."""
    return shroudnet.harmonic_balance(scenes.jenkins_chain(), 3)


def chain_at(frequency: float) -> Scene:
    return scenes.jenkins_chain(frequency=frequency)


@functools.cache
def fe_file(folder=None) -> str:
    import tempfile
    path = f"{tempfile.mkdtemp()}/blade.npz"
    np.savez(path, M=np.eye(2), K=np.array([[2.0, -1.0], [-1.0, 1.0]]))
    return path


def record(make):
    """The valid call of a result record: its own fields, taken from one the library made."""
    def call():
        made = make()
        if isinstance(made, tuple):  # a NamedTuple
            return (), made._asdict()
        return (), {f.name: getattr(made, f.name) for f in dataclasses.fields(made) if f.init}
    return call


def call(*args, **kwargs):
    return lambda: (args, kwargs)


def lazy(make):
    """A valid call whose arguments take work to build: ``make`` returns (args, kwargs)."""
    return make


BLADE = Blade(mass=0.1, damping=1.0, stiffness=1e5)
SPRING = LinearSpring(stiffness=1e5)
SHROUD = Interface(gap=1e-5, angle=math.pi / 3, normal=SPRING, friction=Coulomb(mu=0.3))
MATRIX_M, MATRIX_K = np.eye(2), np.array([[2e4, -1e4], [-1e4, 1e4]])
SHAPES = {"tip": np.array([[0.0, 1.0]])}


def _group():
    return BladeGroup.chain(2, BLADE, SHROUD)


#: One valid call per door: name → () → (args, kwargs).
VALID = {
    "scenes.cantilever_frequency": call(young_modulus=2e11, density=7800.0, length=0.1,
                                        width=0.02, thickness=0.003, tip_mass=0.01),
    "scenes.paper_frequency_model": call(),
    "scenes.three_blade_paper": call(),
    "scenes.bladed_disc_24": call(),
    "scenes.block_on_belt": call(),
    "scenes.blade_pair": call(tangential_stiffness=1e7),
    "scenes.modal_blade": call(),
    "scenes.modal_packet": call(blades=2),
    "scenes.beam_pair": call(),
    "scenes.faced_blade": call(face_points=4),
    "scenes.faced_group": call(blades=2, face_points=1),
    "scenes.face_point_names": call("L", 4),
    "scenes.jenkins_chain": call(),
    "scenes.modal_pair": call(),
    "scenes.mass_on_stop": call(),
    "harmonic_balance": lazy(lambda: ((scenes.jenkins_chain(), 3), {})),
    "harmonic_continuation": lazy(lambda: ((chain_at, 11.0, 11.2, 3),
                                           dict(max_points=2, stability=False))),
    "HarmonicOrbit": record(harmonic_orbit),
    "certify": lazy(lambda: ((harmonic_orbit(),), {})),
    "Certificate": record(lambda: shroudnet.certify(harmonic_orbit())),
    "Campbell": record(lambda: shroudnet.campbell(scenes.paper_frequency_model(),
                                                  [0.0, 6000.0])),
    "Spectrum": record(lambda: shroudnet.amplitude_spectrum(np.sin(np.arange(64.0)), 8)),
    "amplitude_spectrum": call(np.sin(np.arange(64.0)), 8),
    "campbell": call(scenes.paper_frequency_model(), [0.0, 6000.0], (1, 2)),
    "classify": lazy(lambda: ((run(), 0, 1), {})),
    "classify_section": call(np.array([[1.0, 2.0], [1.0, 2.0], [1.0, 2.0], [1.0, 2.0]])),
    "HysteresisLoop": record(lambda: shroudnet.hysteresis_loop(run(), 0, 1)),
    "friction_loss_per_cycle": lazy(lambda: ((run(), 1), {})),
    "hysteresis_loop": lazy(lambda: ((run(), 0, 1), {})),
    "PatchHistory": record(lambda: shroudnet.patch_history(run(), 0, 1)),
    "patch_history": lazy(lambda: ((run(), 0, 1), {})),
    "spectrum": lazy(lambda: ((run(), 0, 1), {})),
    "zero_one_test": call(np.sin(np.arange(200.0))),
    "cantilever_beam": call(length=0.1, youngs_modulus=2e11, density=7800.0, width=0.02,
                            thickness=0.003, elements=2),
    "Blade": call(mass=0.1, damping=1.0, stiffness=1e5),
    "ConstantFrequency": call(hz=200.0),
    "FrequencyTable": call(speeds_rpm=(0.0, 6000.0), frequencies=(190.0, 210.0)),
    "Southwell": call(f0=190.0, coefficient=0.8),
    "Classification": record(lambda: shroudnet.classify(run(), 0, 1)),
    "Bifurcation": lazy(lambda: ((), dict(kind="fold", parameter=6000.0, orbit=orbit(),
                                          multiplier=1.0 + 0.0j, index=0,
                                          bracket=(5990.0, 6010.0)))),
    "Branch": record(branch),
    "continuation": lazy(lambda: ((scene_at, 6000.0, 6010.0),
                                  dict(step=0.5, max_points=2, transient=2,
                                       jacobian="dense", stability=True))),
    "Coupling": call(stiffness=1e5, damping=1.0),
    "stick_clusters": lazy(lambda: ((_group().graph, [(0, 1)]), {})),
    "Assembly": record(lambda: shroudnet.assemble(paper(), 0.0, np.zeros(3), np.zeros(3),
                                                  np.zeros(2, dtype=np.int8))),
    "assemble": lazy(lambda: ((paper(), 0.0, np.zeros(3), np.zeros(3),
                               np.zeros(2, dtype=np.int8)), {})),
    "AntiPhase": call(),
    "EngineOrderWave": call(blades_on_disc=24),
    "Excitation": call(engine_order=2, amplitudes=(0.0, 50.0), phases=AntiPhase()),
    "ExplicitPhases": call((0.0, 1.0)),
    "TravellingWave": call(1),
    "read_matrices": lazy(lambda: ((fe_file(),), {})),
    "BladeGroup": call(),
    "Interface": call(gap=1e-5, angle=0.5, normal=SPRING, friction=Coulomb(mu=0.3)),
    "GroupCampbell": record(lambda: shroudnet.group_campbell(paper(), [3000.0, 6000.0])),
    "LinearModes": record(lambda: shroudnet.linear_modes(paper())),
    "group_campbell": lazy(lambda: ((paper(), [3000.0, 6000.0], (1, 2)), {})),
    "linear_modes": lazy(lambda: ((paper(), "open"), {})),
    "FrequencyResponse": record(lambda: shroudnet.frequency_response(paper(), [150.0, 200.0])),
    "frequency_response": lazy(lambda: ((paper(), [150.0, 200.0], "open"), {})),
    "Accuracy": call(target=1e-6),
    "MistuningStudy": record(lambda: shroudnet.mistuning_study(
        open_paper(), spread=0.01, samples=1, speeds_rpm=[6000.0], transient=1, record=3,
        samples_per_period=20, workers=1, progress=None)),
    "mistuning_study": lazy(lambda: ((open_paper(),), dict(
        spread=0.01, samples=1, speeds_rpm=[6000.0], transient=1, record=3,
        samples_per_period=20, workers=1, progress=None))),
    "ConstantVelocity": call(velocity=0.1),
    "HarmonicMotion": call(amplitude=1e-3, frequency=50.0),
    "MotionTable": call(times=(0.0, 1.0), displacements=(0.0, 1e-3)),
    "Adaptive": call(rtol=1e-8),
    "FixedStep": call(steps_per_period=100),
    "Exponential": call(steps_per_period=100),
    "ZenoGuard": call(events=200),
    "Mode": call(0),
    "ConvergenceError": call("no orbit"),
    "PeriodicOrbit": record(orbit),
    "periodic_orbit": lazy(lambda: ((open_paper(), 1), dict(transient=2, jacobian="dense",
                                                            stability=True))),
    "craig_bampton": call(MATRIX_M, MATRIX_K, [1], 1, points=SHAPES),
    "modal_truncation": call(MATRIX_M, MATRIX_K, 1, points=SHAPES),
    "Scene": lazy(lambda: ((), dict(group=_group(), speed_rpm=3000.0, excitation=Excitation(
        engine_order=1, amplitudes=(0.0, 1.0), phases=AntiPhase())))),
    "SceneArrays": record(lambda: paper().arrays),
    "simulate": lazy(lambda: ((paper(), 1), dict(samples_per_period=20))),
    "LyapunovExponents": record(lambda: shroudnet.lyapunov(open_paper(), 10, transient=1)),
    "lyapunov": lazy(lambda: ((open_paper(), 10), dict(transient=1))),
    "monodromy": lazy(lambda: ((open_paper(), 1), {})),
    "Substructure": call(MATRIX_M, MATRIX_K, points=SHAPES, damping_ratios=0.01),
    "EnergyLedger": record(lambda: run().energy),
    "EventKind": call(0),
    "EventLog": record(lambda: run().events),
    "Simulation": record(run),
    "SimulationError": call("stopped"),
    "Sweep": record(swept),
    "SweepFailure": call(parameter="speed", index=0, value=6000.0, message="stopped"),
    "SweepPoint": record(lambda: swept().points[0]),
    "sweep": lazy(lambda: ((scene_at, [6000.0]), dict(transient=1, record=3, workers=1,
                                                     progress=None))),
    "SweepMap": record(mapped),
    "sweep_map": lazy(lambda: ((map_at, [6000.0], [40.0]), dict(transient=1, record=3,
                                                               workers=1, progress=None))),
    "contact_laws.check_array": call("Owner", "value", [1.0], shape=(None,)),
    "contact_laws.check_callable": call("Owner", "value", print),
    "contact_laws.check_calls_with": call("Owner", "value", max, 2, expected="max(a, b)"),
    "contact_laws.check_choice": call("Owner", "value", "a", ("a", "b")),
    "contact_laws.check_instance": call("Owner", "value", 1.0, float),
    "contact_laws.check_int": call("Owner", "value", 1),
    "contact_laws.check_real": call("Owner", "value", 1.0),
    "contact_laws.check_sequence": call("Owner", "value", [1.0]),
    "contact_laws.FrictionLaw": None,   # abstract: built through its subclasses below
    "contact_laws.NormalLaw": None,
    "contact_laws.Coulomb": call(mu=0.3),
    "contact_laws.ExponentialFriction": call(mu_static=0.5, mu_kinetic=0.3, beta=5.0),
    "contact_laws.Regularised": call(law=Coulomb(mu=0.3), velocity=1e-3),
    "contact_laws.Stribeck": call(mu_static=0.4, mu_kinetic=0.25, stribeck_velocity=0.05),
    "contact_laws.ConstantLoad": call(force=10.0),
    "contact_laws.Hertz": call(stiffness=1e9),
    "contact_laws.HuntCrossley": call(stiffness=1e9, damping=0.1),
    "contact_laws.KelvinVoigt": call(stiffness=1e5, damping=1.0),
    "contact_laws.LinearSpring": call(stiffness=1e5),
}

#: Doors whose refusal of a bad value is another module's work, now under way: name →
#: (argument, why). Only these substitutions may break the property, and only as xfail.
KNOWN: dict[tuple[str, str], str] = {}

#: Doors the property does not call with bad values, each with its reason.
NOT_INPUT = {
    "contact_laws.FrictionLaw": "an abstract base: its subclasses are walked",
    "contact_laws.NormalLaw": "an abstract base: its subclasses are walked",
    "ConvergenceError": "an exception: it carries any message, as every exception does",
    "SimulationError": "an exception: it carries any message, as every exception does",
}

#: Doors walked on some of their arguments only: the others are the caller's constants
#: (the check family's owner, field and bounds) or Python's own machinery (an enum's
#: functional API).
ONLY_ARGUMENTS = {
    "Mode": ("value",), "EventKind": ("value",),
    **{f"contact_laws.check_{kind}": ("value",)
       for kind in ("array", "callable", "calls_with", "choice", "instance", "int", "real",
                    "sequence")},
}

#: Doors whose result may hold NaN by their documented contract.
DOCUMENTED_NAN = {
    **{f"contact_laws.check_{kind}": "returns the value it checks as given: its type, "
                                     "callability or membership is all it checks"
       for kind in ("callable", "calls_with", "choice", "instance", "sequence")},
}


def test_every_door_has_a_valid_call():
    """A new export without a valid call here fails, so that it cannot go unwalked."""
    missing = sorted(set(DOORS) - set(VALID))
    assert not missing, f"public doors without a valid call in VALID: {missing}"
    stale = sorted(set(VALID) - set(DOORS))
    assert not stale, f"VALID names doors that are not public: {stale}"


# -- bad values -----------------------------------------------------------------------------

BAD_VALUES = (
    None, "x", "", b"x", True, [], (), {}, {1, 2}, object(), 1 + 2j,
    math.nan, math.inf, -math.inf, -1, -1.0, 0, 0.0, 1e300, -1e300, 1e-300, -1e-300, 2**70,
    np.array(50.0), np.array([]), np.zeros((2, 2, 2)), np.array([math.nan]),
    np.array([1.0, math.inf]), [math.nan], ["a", "b"], [[1.0], [1.0, 2.0]], lambda: None,
    np.float64("nan"), np.int64(-3),
)

bad_values = st.one_of(
    st.sampled_from(BAD_VALUES),
    st.floats(allow_nan=True, allow_infinity=True),
    st.text(max_size=3),
    st.lists(st.floats(), min_size=0, max_size=3),
)


def _bound(door, args, kwargs) -> inspect.BoundArguments:
    signature = inspect.signature(door)
    bound = signature.bind(*args, **kwargs)
    bound.apply_defaults()
    for name, parameter in signature.parameters.items():
        if parameter.kind in (parameter.VAR_POSITIONAL, parameter.VAR_KEYWORD):
            bound.arguments.pop(name, None)
    return bound


def _numbers(value, depth=0):
    """The float arrays and numbers a result holds, a few levels down."""
    if depth > 3 or value is None or isinstance(value, str | bytes | enum.Enum | type):
        return
    if isinstance(value, float | complex | np.floating | np.complexfloating):
        yield np.asarray(value)
    elif isinstance(value, np.ndarray):
        if value.dtype.kind in "fc":
            yield value
    elif isinstance(value, tuple | list):
        for item in value[:50]:
            yield from _numbers(item, depth + 1)
    elif isinstance(value, dict):
        for item in list(value.values())[:50]:
            yield from _numbers(item, depth + 1)
    elif dataclasses.is_dataclass(value) and not isinstance(value, type):
        # A record names the fields that may hold NaN or ±inf by design (NON_FINITE).
        allowed = getattr(type(value), "NON_FINITE", ())
        for field in dataclasses.fields(value):
            if field.name not in allowed:
                yield from _numbers(getattr(value, field.name), depth + 1)


def _substitutions(name):
    """The (argument, valid call) pairs of one door."""
    args, kwargs = VALID[name]()
    bound = _bound(DOORS[name], args, kwargs)
    return bound, list(ONLY_ARGUMENTS.get(name, bound.arguments))


WALKED = sorted(name for name in DOORS if name in VALID and name not in NOT_INPUT)

#: Doors that run the dynamics are walked with fewer examples: each example is a short run.
SLOW = {"simulate", "periodic_orbit", "continuation", "lyapunov", "monodromy",
        "mistuning_study", "sweep", "Branch", "MistuningStudy", "Sweep", "SweepPoint",
        "sweep_map", "SweepMap",
        "LyapunovExponents", "PeriodicOrbit", "Simulation", "classify", "spectrum",
        "hysteresis_loop", "friction_loss_per_cycle", "Bifurcation", "Scene",
        "scenes.bladed_disc_24", "scenes.beam_pair", "scenes.modal_packet",
        "harmonic_continuation", "certify", "Certificate", "scenes.modal_pair"}

CASES = {"generated": 0}


@pytest.mark.parametrize("name", WALKED)
def test_a_bad_value_in_any_argument_is_refused_by_name(name):
    door = DOORS[name]
    bound, arguments = _substitutions(name)
    if not arguments:
        return  # nothing to substitute: the valid call is the whole door

    @settings(max_examples=6 if name in SLOW else 25, report_multiple_bugs=False)
    @given(argument=st.sampled_from(arguments), value=bad_values)
    def prop(argument, value):
        CASES["generated"] += 1
        call = dict(bound.arguments)
        call[argument] = value
        positional = [p.name for p in inspect.signature(door).parameters.values()
                      if p.kind == p.POSITIONAL_ONLY]
        args = [call.pop(p) for p in positional if p in call]
        try:
            _refused_by_name_or_finite(door, name, argument, arguments, value, args, call)
        except AssertionError:
            reason = KNOWN.get((name, argument)) or KNOWN.get((name, "*"))
            if reason:
                pytest.xfail(reason)
            raise

    prop()


def _refused_by_name_or_finite(door, name, argument, arguments, value, args, call):
    """The property for one call: finite results, or a documented error naming
    ``argument`` (or the door, where it has one argument only)."""
    try:
        result = door(*args, **call)
    except _project_errors() as error:
        message = str(error)
        owner = name.rsplit(".", 1)[-1]
        assert argument in message or (len(arguments) == 1 and owner in message), (
            f"{name}({argument}={value!r}) raised {type(error).__name__} "
            f"without naming {argument!r}: {message}")
        return
    except Exception as error:  # anything else is a fault of the door
        raise AssertionError(f"{name}({argument}={value!r}) raised "
                             f"{type(error).__name__}: {error}") from error
    if name in DOCUMENTED_NAN:
        return
    for array in _numbers(result):
        assert np.isfinite(array).all(), (
            f"{name}({argument}={value!r}) returned non-finite values")


def test_report_cases():
    """Prints how many doors the property walked and how many calls it generated."""
    print(f"\n{len(WALKED)} public doors walked, {CASES['generated']} bad-value calls made")


# -- the cases that were seen to fail, each with the words it now gives ---------------------

def _coupled(stiffness=1e5, coupling=1e300):
    group = BladeGroup.chain(3, Blade(mass=0.1, damping=1.0, stiffness=stiffness),
                             shroudnet.Coupling(stiffness=coupling))
    return Scene(group=group, speed_rpm=6000.0, excitation=Excitation(
        engine_order=2, amplitudes=(0.0, 50.0), phases=AntiPhase()))


#: What a scene whose numbers no run can carry raises, before any work.
CANNOT_RUN = shroudnet.SimulationError

SEEN = [
    (lambda: shroudnet.FrequencyTable(speeds_rpm=5, frequencies=6), TypeError,
     r"FrequencyTable\.speeds_rpm must be a sequence of numbers, got int 5"),
    (lambda: Excitation(engine_order=2, amplitudes=np.array(50.0), phases=AntiPhase()),
     TypeError, r"Excitation\.amplitudes must be a sequence"),
    (lambda: shroudnet.simulate(paper(), 5, zeno=None), TypeError,
     r"simulate\.zeno must be a ZenoGuard"),
    (lambda: shroudnet.simulate(paper(), 5, initial=(np.zeros(3),)), ValueError,
     r"simulate\.initial must be \(x0, v0\), a pair of 3 displacements"),
    (lambda: shroudnet.simulate(paper(), 5, initial=(np.zeros(3),) * 3), ValueError,
     r"simulate\.initial must be \(x0, v0\), a pair of 3 displacements"),
    (lambda: shroudnet.periodic_orbit("scene"), TypeError,
     r"periodic_orbit\.scene must be a shroudnet\.Scene, got str 'scene'"),
    (lambda: shroudnet.linear_modes("scene"), TypeError,
     r"linear_modes\.scene must be a shroudnet\.Scene, got str 'scene'"),
    (lambda: shroudnet.TravellingWave(1).phases(0), ValueError,
     r"TravellingWave\.phases\.n_blades must be an int >= 1, got 0"),
    (lambda: shroudnet.continuation(scene_at, 6000.0, 6010.0, progress=5), TypeError,
     r"continuation\.progress must be None or a callable"),
    (lambda: shroudnet.classify(run(), 0, 1, tolerance=math.nan), ValueError,
     r"classify\.tolerance must be a number in \(0, 0\.1\], got NaN"),
    (lambda: shroudnet.classify(run(), 0, 1, tolerance=-1), ValueError,
     r"classify\.tolerance must be in \(0, 0\.1\], got -1"),
    (lambda: shroudnet.classify(run(), 0, 1, tolerance=10), ValueError,
     r"classify\.tolerance must be in \(0, 0\.1\], got 10"),
    (lambda: shroudnet.classify(run(), 0, 1, max_period=0), ValueError,
     r"classify\.max_period must be an int >= 1"),
    (lambda: shroudnet.linear_modes(scenes.bladed_disc_24()).of_diameter(99), ValueError,
     r"of_diameter\.nodal_diameter must be an int >= 0 and <= N // 2 = 12, got 99"),
    (lambda: shroudnet.simulate(_coupled(), 1), CANNOT_RUN,
     r"the coupling stiffness 1e\+300 N/m between 'blade\d' and 'blade\d'.* below the "
     r"smallest step"),
    (lambda: shroudnet.simulate(scenes.three_blade_paper(damping=1e300), 1), CANNOT_RUN,
     r"its damping 1e\+300 N·s/m .* below the smallest step"),
    (lambda: shroudnet.simulate(scenes.three_blade_paper(speed_rpm=1e-300), 1), CANNOT_RUN,
     r"below the smallest step.* at speed_rpm = 1e-300"),
    (lambda: shroudnet.simulate(scenes.three_blade_paper(
        mass=1e-300, frequency=shroudnet.ConstantFrequency(hz=1e150)), 1), CANNOT_RUN,
     r"on a mass of 1e-300 kg makes a natural frequency"),
    (lambda: shroudnet.simulate(paper(), 1, initial=(np.full(3, 1e300), np.zeros(3))),
     CANNOT_RUN, r"initial: the initial displacements x0 carry an energy of inf J"),
    (lambda: shroudnet.simulate(scenes.block_on_belt(belt_speed=1e300), 1), CANNOT_RUN,
     r"prescribed node 'belt': its motion .* 1e\+300 m/s"),
    (lambda: shroudnet.simulate(scenes.three_blade_paper(q1=1e300), 1), CANNOT_RUN,
     r"Excitation\.amplitudes: a force of 1e\+300 N"),
]


@pytest.mark.parametrize("call, error, words", SEEN)
def test_each_case_seen_is_refused_by_name(call, error, words):
    with pytest.raises(error, match=words):
        call()
