"""Files are checked when read. A results file whose array is missing, of the wrong kind
of number, NaN, of a shape that does not fit the others, out of time order, or holding a
code that means nothing is refused with ``ResultsError`` naming the file and the array; a
scene file whose key holds the wrong type is refused with ``SceneFileError`` naming the
file and the key; and every contact law, ``Regularised`` around each exact one included,
reads back equal from both kinds of file."""

import dataclasses
import math
import re
import time
import tomllib
from pathlib import Path

import numpy as np
import pytest

import contact_laws as cl
from shroudnet import AntiPhase, Blade, BladeGroup, Excitation, Interface, Scene, simulate
from shroudnet.io import results, scenefile
from shroudnet.io.results import ResultsError
from shroudnet.run import footprint
from shroudnet.run.classification import Classification
from shroudnet.run.simulation import EventLog, SweepPoint
from shroudnet.scenes import beam_pair, modal_packet, three_blade_paper
from shroudnet.steady.continuation import Bifurcation, Branch
from shroudnet.steady.cycle import EnergyPerCycle
from shroudnet.steady.orbits import PeriodicOrbit

from .laws import CubicSpring, RationalWeakening

# ---- three files of each kind, the scene of three blades and two interfaces ----------------

def paper_scene() -> Scene:
    return three_blade_paper(gamma1=2.0)


@pytest.fixture(scope="module")
def simulation(tmp_path_factory) -> Path:
    """A short run of the paper's group, with events (4 periods × 10 samples)."""
    sim = simulate(paper_scene(), 4, samples_per_period=10)
    assert len(sim.events) >= 2
    return results.save_simulation(tmp_path_factory.mktemp("run") / "run.npz", sim)


def orbit(scene: Scene, shift: float) -> PeriodicOrbit:
    """A made-up orbit of ``scene`` (three blades: a state of 6), with two events."""
    width = len(scene.responses)
    return PeriodicOrbit(
        scene=scene, initial=(np.full(3, shift), np.zeros(3)), periods=1,
        multipliers=np.array([0.5, 0.4j, -0.4j, 0.3, 0.2, 0.1]), monodromy=np.eye(6) * shift,
        residual=1e-12, scale=1e-3, iterations=3,
        events=EventLog(time=np.array([0.1, 0.2]) * shift, interface=np.array([0, 1]),
                        kind=np.array([0, 1]), counts={"closing": 1, "separation": 1}),
        peak=np.full(width, 2.0), mean_square=np.full(width, 1.0),
        maximum=np.full(width, 2.0), minimum=np.full(width, -1.0), mean=np.full(width, 0.5),
        energy_per_cycle=EnergyPerCycle(1.0, 0.5, 0.3, 0.2), kinetic_peak=1.0, singular=0)


@pytest.fixture(scope="module")
def branch(tmp_path_factory) -> Path:
    """A branch of two orbits and a fold between them, made up (nothing integrated)."""
    scene = paper_scene()
    orbits = (orbit(scene, 1.0), orbit(scene, 2.0))
    fold = Bifurcation(kind="fold", parameter=1.5, orbit=orbit(scene, 1.5),
                       multiplier=complex(1.0), index=0, bracket=(1.0, 2.0))
    made = Branch(parameter=np.array([1.0, 2.0]), orbits=orbits, bifurcations=(fold,),
                  periods=1, name="q1", ended="stop reached")
    return results.save_branch(tmp_path_factory.mktemp("branch") / "branch.npz", made)


@pytest.fixture(scope="module")
def sweep(tmp_path_factory) -> Path:
    """A sweep folder of one made-up point."""
    folder = tmp_path_factory.mktemp("sweep")
    store = results.SweepStore(folder, {"parameter": "q1", "values": [1.0], "settings": {},
                                        "blade": 1})
    label = Classification(label="p1", period=1, n_points=4, tolerance=1e-6, mismatch=0.0,
                           zero_one=0.0, broadband=0.0)
    store.save(0, SweepPoint(value=1.0, poincare=np.ones((4, 2)), energy_density=1e-8,
                             friction_loss_per_cycle=1e-3, classification=label,
                             final_state=(np.ones(3), np.zeros(3)), peak=np.ones(3)))
    return folder


def point_of(folder: Path) -> Path:
    return folder / "points" / "00000.npz"


#: Each kind of file: its arrays (every one it holds), by the kind of number they hold.
REAL = {"simulation": ("t", "x", "v", "normal_force", "friction_force", "work", "event_time"),
        "branch": ("parameter", "initial", "multipliers", "monodromy", "residual", "scale",
                   "peak", "mean_square", "maximum", "minimum", "mean", "energy_per_cycle",
                   "kinetic_peak", "event_time", "bifurcation_multiplier",
                   "bifurcation_bracket"),
        "sweep": ("poincare", "final_x", "final_v", "peak")}
INTEGER = {"simulation": ("modes", "event_interface", "event_kind"),
           "branch": ("iterations", "singular", "event_offsets", "event_interface",
                      "event_kind", "bifurcation_index"),
           "sweep": ()}
#: May hold NaN: the critical multiplier of a nonsmooth bifurcation has none.
MAY_BE_NAN = {"bifurcation_multiplier"}
#: May be missing: a sweep point written before peaks were kept.
OPTIONAL = {("sweep", "peak")}


def every_array(kind: str) -> set[str]:
    return set(REAL[kind]) | set(INTEGER[kind])


@pytest.fixture
def damaged(request, simulation, branch, sweep, tmp_path):
    """``damaged(kind, name, change)``: a copy of the file of ``kind`` with the array
    ``name`` replaced by ``change(array)`` (None: removed); (its path, how to load it)."""
    def make(kind, name, change):
        if kind == "sweep":
            folder = tmp_path / "sweep"
            (folder / "points").mkdir(parents=True)
            (folder / "sweep.json").write_bytes((sweep / "sweep.json").read_bytes())
            source, path, load = point_of(sweep), point_of(folder), results.load_sweep
            target = folder
        else:
            source = simulation if kind == "simulation" else branch
            path = target = tmp_path / source.name
            load = results.load
        with np.load(source) as data:
            content = {key: data[key] for key in data.files}
        new = change(content[name].copy())
        if new is None:
            del content[name]
        else:
            content[name] = new
        np.savez(path, **content)
        return path, lambda: load(target)
    return make


def refused(made, message: str) -> str:
    path, load = made
    with pytest.raises(ResultsError, match=message) as caught:
        load()
    assert str(path) in str(caught.value)
    return str(caught.value)


def with_nan(array):
    array = array.astype(np.result_type(array.dtype, float))
    array.reshape(-1)[-1] = math.nan
    return array


def test_the_damage_cases_cover_every_array_each_file_holds(simulation, branch, sweep):
    for kind, path in (("simulation", simulation), ("branch", branch),
                       ("sweep", point_of(sweep))):
        with np.load(path) as data:
            assert set(data.files) - {"meta"} == every_array(kind)
            for name in data.files:
                if name != "meta":
                    assert data[name].size, f"{kind}: {name} is empty, so nothing is damaged"


# ---- a damaged array: refused, naming the file and the array -------------------------------

DAMAGES = {
    "missing": (lambda a: None, "has no array '{name}'"),
    "text": (lambda a: a.astype(str), r"array '{name}' holds <U\d+, not numbers"),
    "extra axis": (lambda a: a[..., None], r"array '{name}' has shape \(.*\); it must be "),
}
REAL_DAMAGES = {"NaN": (with_nan, r"array '{name}' holds NaN at \w[\w ]* \d+")}
INTEGER_DAMAGES = {"fraction": (lambda a: a + 0.5, r"array '{name}' holds float64, not "
                                                   r"integers")}

CASES = [(kind, name, damage)
         for kind in REAL for name in REAL[kind]
         for damage in (*DAMAGES, *(() if name in MAY_BE_NAN else REAL_DAMAGES))
         if not (damage == "missing" and (kind, name) in OPTIONAL)]
CASES += [(kind, name, damage) for kind in INTEGER for name in INTEGER[kind]
          for damage in (*DAMAGES, *INTEGER_DAMAGES)]


@pytest.mark.parametrize("kind, name, damage", CASES, ids=["-".join(c) for c in CASES])
def test_a_damaged_array_is_refused_naming_the_file_and_the_array(damaged, kind, name,
                                                                  damage):
    change, message = {**DAMAGES, **REAL_DAMAGES, **INTEGER_DAMAGES}[damage]
    refused(damaged(kind, name, change), message.format(name=re.escape(name)))


def swapped(first: int, second: int):
    def change(array):
        array[[first, second]] = array[[second, first]]
        return array
    return change


def setting(index, value):
    def change(array):
        array[index] = value
        return array
    return change


FAULTS = [
    ("simulation", "x", setting((12, 1), math.nan), r"array 'x' holds NaN at sample 12\b"),
    ("simulation", "work", setting((30, 0), math.inf), r"array 'work' holds inf at sample 30\b"),
    ("simulation", "t", swapped(6, 7), r"array 't' must increase, it falls at sample 7\b"),
    ("simulation", "t", setting(5, 0.0), r"array 't' must increase, it falls at sample 5\b"),
    ("simulation", "event_time", lambda a: a[::-1].copy(),
     r"array 'event_time' must not decrease, it falls at event 1\b"),
    ("simulation", "event_kind", setting(0, 9),
     r"array 'event_kind' holds the unknown event kind 9 at event 0; the event kinds are 0 "
     r"\(closing\), 1 \(separation\)"),
    ("simulation", "modes", setting((3, 1), 7),
     r"array 'modes' holds the unknown mode 7 at sample 3; the modes are 0 \(open\), "
     r"1 \(stick\)"),
    ("simulation", "event_interface", setting(0, 2),
     r"event_interface holds 0 to 2; the scene has interfaces 0 to 1"),
    ("branch", "monodromy", lambda a: a[:, :5, :5].copy(),
     r"array 'monodromy' has shape \(3, 5, 5\); it must be 3 × 6 × 6 \(3 orbits × 6 state "
     r"variables × 6 state variables\)"),
    ("branch", "multipliers", lambda a: a[:, :4].copy(),
     r"array 'multipliers' has shape \(3, 4\); it must be 3 × 6"),
    ("branch", "initial", lambda a: a[:2].copy(),
     r"array 'initial' has shape \(2, 6\); it must be 3 × 6 \(3 orbits × 6 state variables\)"),
    ("branch", "parameter", setting(1, math.nan), r"array 'parameter' holds NaN at orbit 1\b"),
    ("branch", "event_time", setting(1, 0.05),
     r"array 'event_time' must not decrease within an orbit, it falls at event 1\b"),
    ("branch", "event_offsets", lambda a: np.array([0, 4, 2, 6]),
     r"array 'event_offsets' must not decrease, it falls at orbit start 2\b"),
    ("branch", "event_offsets", lambda a: np.array([0, 2, 4, 5]),
     r"array 'event_offsets' runs from 0 to 5; it must run from 0 to 6"),
    ("branch", "event_kind", setting(3, -1), r"holds the unknown event kind -1 at event 3\b"),
    ("branch", "event_interface", setting(3, 5), r"event_interface holds 0 to 5; the scene "
                                                 r"has interfaces 0 to 1"),
    ("branch", "bifurcation_index", setting(0, 2),
     r"bifurcation_index holds 2 to 2; the branch has points 0 to 1"),
    ("branch", "energy_per_cycle", lambda a: a[:, :3].copy(),
     r"array 'energy_per_cycle' has shape \(3, 3\); it must be 3 × 4 \(3 orbits × 4 energy "
     r"terms\)"),
    ("sweep", "poincare", lambda a: a[:, :1].copy(),
     r"array 'poincare' has shape \(4, 1\); it must be any × 2"),
    ("sweep", "final_v", lambda a: a[:2].copy(),
     r"array 'final_v' has shape \(2,\); it must be 3 \(3 coordinates\)"),
    ("sweep", "final_x", setting(2, -math.inf), r"array 'final_x' holds inf at coordinate 2\b"),
]


@pytest.mark.parametrize("kind, name, change, message", FAULTS,
                         ids=[f"{kind}-{name}-{k}" for k, (kind, name, *_) in enumerate(FAULTS)])
def test_each_fault_is_said_as_it_is(damaged, kind, name, change, message):
    refused(damaged(kind, name, change), message)


def test_an_undamaged_file_of_each_kind_loads(simulation, branch, sweep, damaged):
    assert len(results.load(simulation).events) >= 2
    loaded = results.load(branch)
    assert len(loaded) == 2 and loaded.bifurcations[0].kind == "fold"
    assert loaded.orbits[1].monodromy.shape == (6, 6)
    assert results.load_sweep(sweep).points[0].peak.shape == (3,)
    path, load = damaged("sweep", "peak", lambda a: None)  # written before peaks were kept
    assert load().points[0].peak.shape == (0,)
    path, load = damaged("branch", "bifurcation_multiplier", lambda a: a * math.nan)
    assert math.isnan(load().bifurcations[0].multiplier.real)


def test_a_branch_file_without_its_event_counts_is_refused(branch, tmp_path):
    import json
    with np.load(branch) as data:
        content = {key: data[key] for key in data.files}
    meta = json.loads(content["meta"].tobytes())
    del meta["event_counts"]
    content["meta"] = np.frombuffer(json.dumps(meta).encode(), dtype=np.uint8)
    path = tmp_path / "branch.npz"
    np.savez(path, **content)
    with pytest.raises(ResultsError, match=r"its meta header has no 'event_counts'"):
        results.load(path)


# ---- a scene file with a key of the wrong type: refused, naming the key --------------------

def paper_document() -> dict:
    return scenefile.document(paper_scene(), scenefile.RunSettings(periods=10, transient=2))


def substructure_document() -> dict:
    return scenefile.document(modal_packet(blades=2))


def matrices_document() -> dict:
    return scenefile.document(beam_pair())


def group_document() -> dict:
    document = paper_document()
    blade, interface = document["blades"][0], document["interfaces"][0]
    del document["blades"], document["interfaces"]
    document["group"] = {"shape": "ring", "count": 4,
                         "blade": {k: v for k, v in blade.items() if k != "name"},
                         "interface": {k: v for k, v in interface.items()
                                       if k not in ("left", "right")}}
    return document


def belt_document() -> dict:
    document = paper_document()
    document["prescribed"] = [{"name": "belt", "motion": {"kind": "constant_velocity",
                                                          "velocity": 0.1}}]
    document["couplings"] = [{"left": "belt", "right": "blade1", "stiffness": 1e4}]
    return document


BASES = {"paper": paper_document, "substructure": substructure_document,
         "matrices": matrices_document,
         "group": group_document, "belt": belt_document}

REGULARISED = {"law": "Regularised", "exact": {"law": "Coulomb", "mu": 0.3}, "velocity": 1e-3}

#: (base document, the key set, its new value, the key the message names, what it says)
BAD_KEYS = [
    ("paper", "interfaces", 5, "interfaces", r"must be a list of tables, got 5"),
    ("paper", "interfaces", {"left": "blade1"}, "interfaces", r"must be a list of tables"),
    ("paper", "interfaces", [5], "interfaces", r"must be a list of tables, got \[5\]"),
    ("paper", "blades", "blade1", "blades", r"must be a list of tables"),
    ("paper", "speed_rpm", "fast", "speed_rpm", r"must be a number, got 'fast'"),
    ("paper", "speed_rpm", True, "speed_rpm", r"must be a number, got True"),
    ("paper", "sectors", "3", "sectors", r"must be an integer, got '3'"),
    ("paper", "fixed", "disc", "fixed", r"must be a list of node names, got 'disc'"),
    ("paper", "fixed", [1.5], "fixed", r"must be a list of node names"),
    ("paper", "run", 5, "run", r"must be a table, got 5"),
    ("paper", "run", [1, 2], "run", r"must be a table"),
    ("paper", "run.event_tolerance", "x", "run.event_tolerance", r"must be a number, got 'x'"),
    ("paper", "run.event_tolerance", -1e-9, "run",
     r"run\.event_tolerance must be in \(0, inf\) periods"),
    ("paper", "run.event_tolerance", math.nan, "run", r"run\.event_tolerance must be a number"),
    ("paper", "run.periods", 2.5, "run.periods", r"must be an integer, got 2\.5"),
    ("paper", "run.periods", "10", "run.periods", r"must be an integer"),
    ("paper", "run.transient", [1], "run.transient", r"must be an integer"),
    ("paper", "run.samples_per_period", 0, "run", r"run\.samples_per_period must be an int "
                                                  r">= 1"),
    ("paper", "run.blade", 1.5, "run.blade", r"must be a blade name or position"),
    ("paper", "run.blade", {"name": "blade1"}, "run.blade", r"must be a blade name"),
    ("paper", "run.method", ["adaptive"], "run.method", r"must be text"),
    ("paper", "run.rtol", "tight", "run.rtol", r"must be a number"),
    ("paper", "excitation", [0.0, 50.0], "excitation", r"must be a table"),
    ("paper", "excitation.engine_order", 2.5, "excitation.engine_order",
     r"must be an integer"),
    ("paper", "excitation.amplitudes", 50.0, "excitation.amplitudes",
     r"must be a list of numbers, got 50\.0"),
    ("paper", "excitation.amplitudes", ["fifty"], "excitation.amplitudes",
     r"must be a list of numbers"),
    ("paper", "excitation.phases", 5, "excitation.phases",
     r"must be text or a table or a list of numbers"),
    ("paper", "blades.0", 5, "blades", r"must be a list of tables"),
    ("paper", "blades.0.mass", "heavy", "blades[0].mass", r"must be a number"),
    ("paper", "blades.0.damping", [4.0], "blades[0].damping", r"must be a number"),
    ("paper", "blades.0.frequency", [200.0], "blades[0].frequency",
     r"must be a number or a table"),
    ("paper", "blades.0.frequency", {"f0": "a", "coefficient": 1.0}, "blades[0].frequency.f0",
     r"must be a number"),
    ("paper", "blades.0.frequency", {"speeds_rpm": 5, "frequencies": 6},
     "blades[0].frequency.speeds_rpm", r"must be a list of numbers"),
    ("paper", "blades.0.name", 1.5, "blades[0].name", r"must be a node name"),
    ("paper", "blades.0.name", [1], "blades[0].name", r"must be a node name"),
    ("paper", "interfaces.0", "blade1-blade2", "interfaces", r"must be a list of tables"),
    ("paper", "interfaces.0.left", 1.5, "interfaces[0].left",
     r"must be a node name \(text or integer\), \[node, point name\] or \[node, \[point "
     r"name, …\]\] \(a patch\)"),
    ("paper", "interfaces.0.gap", [2e-5], "interfaces[0].gap", r"must be a number"),
    ("paper", "interfaces.0.angle", "steep", "interfaces[0].angle", r"must be a number"),
    ("paper", "interfaces.0.normal", 5, "interfaces[0].normal", r"must be a table"),
    ("paper", "interfaces.0.normal", [{"law": "LinearSpring"}], "interfaces[0].normal",
     r"must be a table"),
    ("paper", "interfaces.0.normal", {"law": 5}, "interfaces[0].normal.law",
     r"must name a NormalLaw"),
    ("paper", "interfaces.0.normal", {"law": "Linear", "stiffness": 1e5},
     "interfaces[0].normal.law", r"'Linear' is not a NormalLaw"),
    ("paper", "interfaces.0.normal", {"law": "Coulomb", "mu": 0.3},
     "interfaces[0].normal.law", r"'Coulomb' is not a NormalLaw"),
    ("paper", "interfaces.0.normal", {"law": "nowhere:Spring"}, "interfaces[0].normal.law",
     r"module 'nowhere' is not imported"),
    ("paper", "interfaces.0.normal.stiffness", "stiff", "interfaces[0].normal.stiffness",
     r"must be a number, got 'stiff'"),
    ("paper", "interfaces.0.normal.stiffness", {"law": "Hertz"},
     "interfaces[0].normal.stiffness", r"must be a number"),
    ("paper", "interfaces.0.friction", "Coulomb", "interfaces[0].friction", r"must be a table"),
    ("paper", "interfaces.0.friction", {"law": "LinearSpring", "stiffness": 1e5},
     "interfaces[0].friction.law", r"'LinearSpring' is not a FrictionLaw"),
    ("paper", "interfaces.0.friction", {**REGULARISED, "exact": 0.3},
     "interfaces[0].friction.exact", r"must be a law's table"),
    ("paper", "interfaces.0.friction", {**REGULARISED, "exact": {"law": 5}},
     "interfaces[0].friction.exact.law", r"must name a FrictionLaw"),
    ("paper", "interfaces.0.friction", {**REGULARISED, "exact": {"law": "Hertz",
                                                                 "stiffness": 1.0}},
     "interfaces[0].friction.exact.law", r"'Hertz' is not a FrictionLaw"),
    ("paper", "interfaces.0.friction", {**REGULARISED, "exact": REGULARISED},
     "interfaces[0].friction", r"Regularised\.law must be an exact FrictionLaw"),
    ("paper", "interfaces.0.friction", {"law": "Regularised", "velocity": 1e-3},
     "interfaces[0].friction", r"Regularised needs exact"),
    ("paper", "interfaces.0.friction", {**REGULARISED, "velocity": "slow"},
     "interfaces[0].friction.velocity", r"must be a number"),
    ("paper", "interfaces.0.friction.mu_static", [0.5], "interfaces[0].friction.mu_static",
     r"must be a number"),
    ("paper", "interfaces.0.tangential_stiffness", "stiff",
     "interfaces[0].tangential_stiffness", r"must be a number"),
    ("paper", "interfaces.0.normal_direction", 1.0, "interfaces[0].normal_direction",
     r"must be a list of numbers"),
    ("paper", "interfaces.0.tangent_directions", [1.0, 0.0],
     "interfaces[0].tangent_directions", r"must be a list of one or two directions"),
    ("belt", "prescribed", 5, "prescribed", r"must be a list of tables"),
    ("belt", "prescribed.0.motion", "belt", "prescribed[0].motion", r"must be a table"),
    ("belt", "prescribed.0.motion.kind", ["constant_velocity"], "prescribed[0].motion.kind",
     r"must be one of 'constant_velocity', 'harmonic', 'table'"),
    ("belt", "prescribed.0.motion.velocity", "fast", "prescribed[0].motion.velocity",
     r"must be a number"),
    ("belt", "couplings", {"left": "belt"}, "couplings", r"must be a list of tables"),
    ("belt", "couplings.0.stiffness", "stiff", "couplings[0].stiffness", r"must be a number"),
    ("belt", "couplings.0.right", None, "couplings[0].right", r"must be a node name"),
    ("group", "group", 5, "group", r"must be a table, got 5"),
    ("group", "group.shape", 5, "group.shape",
     r"must be one of 'ring', 'chain', 'bladed_disc', got 5"),
    ("group", "group.count", "4", "group.count", r"must be an integer"),
    ("group", "group.blade", [1], "group.blade", r"must be a table"),
    ("group", "group.interface", 5, "group.interface", r"must be a table"),
    ("group", "group.interface.normal", {"law": "Nope"}, "group.interface.normal.law",
     r"'Nope' is not a NormalLaw"),
    ("matrices", "blades.0.mass", [[1.0, "a"]], "blades[0].mass",
     r"must be rows of numbers \[\[…\], …\] or a table"),
    ("matrices", "blades.0.stiffness.rows", 5, "blades[0].stiffness.rows",
     r"must be a list of numbers"),
    ("matrices", "blades.0.reduce", 5, "blades[0].reduce", r"must be a table"),
    ("matrices", "blades.0.reduce", {"method": ["modal_truncation"], "modes": 2},
     "blades[0].reduce.method", r"must be one of 'craig_bampton', 'modal_truncation'"),
    ("matrices", "blades.0.reduce", {"method": "craig_bampton", "boundary": "root",
                                     "modes": 2},
     "blades[0].reduce.boundary", r"must be a list of integers"),
    ("matrices", "blades.0.points.shroud", "tip", "blades[0].points.shroud",
     r"must be a d × n matrix"),
    ("substructure", "blades.0.points", 5, "blades[0].points", r"must be a table"),
    ("substructure", "blades.0.damping_ratios", "light", "blades[0].damping_ratios",
     r"must be a number or a list of numbers"),
    ("substructure", "blades.0.load", 5, "blades[0].load",
     r"must be text or a table or a list of numbers"),
    ("substructure", "blades.0.modal", 5, "blades[0].modal", r"must be a table"),
    ("substructure", "blades.0.modal.frequencies", 180.0, "blades[0].modal.frequencies",
     r"must be a list, one frequency per mode"),
    ("substructure", "blades.0.modal.masses", "x", "blades[0].modal.masses",
     r"must be a number or a list of numbers"),
    ("substructure", "blades.0.excitation_scale", [1.0], "blades[0].excitation_scale",
     r"must be a number"),
]


def edited(document: dict, dotted: str, value) -> dict:
    """``document`` with the value at ``dotted`` (tables by key, lists by index) set, or
    the key left out where ``value`` is None (TOML has no null)."""
    *parents, last = dotted.split(".")
    node = document
    for part in parents:
        node = node[int(part)] if isinstance(node, list) else node[part]
    if value is None:
        del node[last]
    elif isinstance(node, list):
        node[int(last)] = value
    else:
        node[last] = value
    return document


@pytest.mark.parametrize("base, dotted, value, key, message", BAD_KEYS,
                         ids=[f"{case[0]}-{case[1]}={case[2]!r}"[:60] for case in BAD_KEYS])
def test_a_key_of_the_wrong_type_is_refused_naming_it(tmp_path, base, dotted, value, key,
                                                      message):
    document = edited(BASES[base](), dotted, value)
    path = tmp_path / "scene.toml"
    path.write_text(scenefile.dumps(document))
    with pytest.raises(scenefile.SceneFileError) as caught:
        scenefile.load(path)
    text = str(caught.value)
    assert text.startswith(f"{path}: {key}: "), text
    assert re.search(message, text), text
    assert "\n" not in text


def test_every_base_document_loads_as_it_is(tmp_path):
    for name, make in BASES.items():
        path = tmp_path / f"{name}.toml"
        path.write_text(scenefile.dumps(make()))
        assert scenefile.load(path).scene is not None


def wrong_values():
    return [5, -1.0, math.nan, True, "x", [], [1, "a"], [[1.0]], {}, {"law": "Nope"},
            [{"a": 1}]]


def keys_of(node, prefix=""):
    """Every dotted key of a document, lists by their first two entries."""
    if isinstance(node, dict):
        for key, value in node.items():
            yield f"{prefix}{key}"
            yield from keys_of(value, f"{prefix}{key}.")
    elif isinstance(node, list):
        for index, value in enumerate(node[:2]):
            yield f"{prefix}{index}"
            yield from keys_of(value, f"{prefix}{index}.")


@pytest.mark.parametrize("base", ["paper", "belt", "group", "substructure"])
def test_any_value_anywhere_is_read_or_refused_as_bad_input(base):
    """Every key of each document given each wrong value: read, or SceneFileError; never
    an error from inside (a KeyError, a TypeError, ...). (The bladed beams' matrices are
    left out: each of their scenes takes long to build.)"""
    document = BASES[base]()
    count = 0
    for dotted in keys_of(document):
        for value in wrong_values():
            try:
                scenefile.read(edited(BASES[base](), dotted, value))
            except scenefile.SceneFileError:
                pass
            count += 1
    assert count > 300


# ---- a group no run could hold: refused from its counts, before it is built --------------

EXAMPLES = Path(__file__).resolve().parents[1] / "examples" / "scenes"


def chain_document() -> dict:
    document = group_document()
    document["group"]["shape"] = "chain"
    return document


#: Documents of each way a file gives a group, and the key that gives its size.
SIZED = {"ring": (group_document, "group.count"), "chain": (chain_document, "group.count"),
         "bladed_disc": (lambda: tomllib.loads((EXAMPLES / "bladed_disc_24.toml").read_text()),
                         "group.count"),
         "blades": (paper_document, "blades"), "blades and prescribed": (belt_document, "blades")}


@pytest.fixture
def memory(monkeypatch):
    """Set the machine's memory [bytes] that the checks see."""
    def set_to(size):
        monkeypatch.setattr(footprint, "machine_memory", lambda: size)
    return set_to


@pytest.mark.parametrize("form", SIZED)
def test_the_counts_of_a_file_give_the_footprint_of_the_scene_it_builds(tmp_path, memory,
                                                                         form):
    """What the counts set (the stick-cluster matrices and the vectors) is what the built
    scene's footprint says: a machine of exactly that memory loads the file, one byte
    less refuses it, naming the key that gives the size."""
    make, key = SIZED[form]
    path = tmp_path / "scene.toml"
    path.write_text(scenefile.dumps(make()))
    need = footprint.scene_footprint(scenefile.read(make()).scene, 0, 0).total
    memory(need)
    assert scenefile.load(path).scene is not None
    memory(need - 1)
    with pytest.raises(scenefile.SceneFileError,
                       match=rf"^{re.escape(str(path))}: {key}: a run of \d+ nodes and \d+ "
                             r"interfaces would need at least .* GiB .*more than the .* GiB "
                             r"of memory this machine has; give fewer blades$"):
        scenefile.load(path)


def test_a_scene_file_of_a_million_blades_is_refused_before_its_group_is_built(
        tmp_path, memory, monkeypatch):
    """Building a ring of a million blades took a minute and 1.8 GB before ``simulate``
    refused it; its count alone says what the run would need."""
    document = group_document()
    document["group"]["count"] = 1_000_000
    path = tmp_path / "million.toml"
    path.write_text(scenefile.dumps(document))
    memory(24 * 2**30)
    for shape in ("ring", "chain", "bladed_disc"):
        monkeypatch.setattr(BladeGroup, shape, _not_built)
    start = time.perf_counter()
    with pytest.raises(scenefile.SceneFileError) as refused:
        scenefile.load(path)
    print(f"\na million blades refused in {time.perf_counter() - start:.3f} s")
    assert str(refused.value) == (
        f"{path}: group.count: a run of 1,000,000 nodes and 1,000,000 interfaces would need "
        "at least 44,704 GiB (44,703 GiB of it the stick-cluster matrices, whatever the "
        "periods), more than the 24 GiB of memory this machine has; give fewer blades")


def _not_built(*args, **kwargs):
    raise AssertionError("the group was built before its size was checked")


def test_a_sweep_point_is_checked_as_a_file_and_a_saved_run_loads_whatever_its_size(
        simulation, memory):
    """A sweep's scene is on its way to a run; a saved run's scene, read again on a
    machine with less memory than the one that made it, is not, and loads."""
    memory(1000)
    with pytest.raises(scenefile.SceneFileError, match=r"speed_rpm = 5000: blades: a run of "
                                                       r"3 nodes"):
        scenefile.SceneAt(paper_document(), "speed_rpm")(5000.0)
    assert results.load(simulation).scene.group.blades == paper_scene().group.blades
    assert scenefile.read(paper_document()).scene is not None


# ---- every law reads back equal from a scene file and a results file -----------------------

NORMAL_EXAMPLES = {
    cl.LinearSpring: cl.LinearSpring(stiffness=2e5),
    cl.Hertz: cl.Hertz(stiffness=1e8, exponent=1.3),
    cl.KelvinVoigt: cl.KelvinVoigt(stiffness=1e5, damping=20.0),
    cl.HuntCrossley: cl.HuntCrossley(stiffness=1e8, damping=0.5, exponent=1.2),
    cl.ConstantLoad: cl.ConstantLoad(force=10.0),
}
FRICTION_EXAMPLES = {
    cl.Coulomb: cl.Coulomb(mu=0.3),
    cl.ExponentialFriction: cl.ExponentialFriction(mu_static=0.5, mu_kinetic=0.3, beta=5.0),
    cl.Stribeck: cl.Stribeck(mu_static=0.6, mu_kinetic=0.2, stribeck_velocity=0.01,
                             exponent=1.5),
}
OWN_NORMAL = CubicSpring(linear=1e5, cubic=1e13)
OWN_FRICTION = RationalWeakening(mu_static=0.5, mu_kinetic=0.25, speed=0.05)
EXACT = [*FRICTION_EXAMPLES.values(), OWN_FRICTION]
LAW_PAIRS = ([(normal, FRICTION_EXAMPLES[cl.Coulomb]) for normal in NORMAL_EXAMPLES.values()]
             + [(OWN_NORMAL, None)]
             + [(NORMAL_EXAMPLES[cl.LinearSpring], friction) for friction in EXACT]
             + [(NORMAL_EXAMPLES[cl.LinearSpring], cl.Regularised(law=exact, velocity=2e-3))
                for exact in EXACT])


def test_there_is_an_example_of_every_built_in_law():
    assert set(NORMAL_EXAMPLES) == set(cl.BUILT_IN_NORMAL)
    assert set(FRICTION_EXAMPLES) == set(cl.BUILT_IN_FRICTION)


def scene_with(normal, friction) -> Scene:
    """Three blades in a row joined by interfaces of these laws."""
    blade = Blade(mass=0.08, damping=4.0, frequency=200.0)
    interface = Interface(gap=2e-5, angle=1.0, normal=normal, friction=friction)
    return Scene(group=BladeGroup.chain(3, blade, interface),
                 excitation=Excitation(engine_order=2, amplitudes=(0.0, 50.0), phases=AntiPhase()),
                 speed_rpm=6000.0)


def law_id(pair) -> str:
    return "+".join(type(law).__name__ + (f"({type(law.law).__name__})"
                                          if isinstance(law, cl.Regularised) else "")
                    for law in pair if law is not None)


@pytest.mark.parametrize("normal, friction", LAW_PAIRS, ids=map(law_id, LAW_PAIRS))
def test_every_law_reads_back_equal_from_a_scene_file(tmp_path, normal, friction):
    scene = scene_with(normal, friction)
    path = scenefile.save(tmp_path / "scene.toml", scene)
    back = scenefile.load(path).scene
    for (_, _, saved), (_, _, read) in zip(scene.group.interfaces, back.group.interfaces):
        assert read == saved
        assert read.normal == normal and read.friction == friction
    assert scenefile.document(back) == scenefile.document(scene)


@pytest.mark.parametrize("normal, friction", LAW_PAIRS, ids=map(law_id, LAW_PAIRS))
def test_every_law_reads_back_equal_from_a_results_file(simulation, tmp_path, normal,
                                                        friction):
    """The arrays of the paper's run, its scene's laws replaced: three blades, two
    interfaces, as the arrays are."""
    run = results.load_simulation(simulation)
    made = dataclasses.replace(run, scene=scene_with(normal, friction))
    back = results.load(results.save_simulation(tmp_path / "run.npz", made))
    for _, _, read in back.scene.group.interfaces:
        assert read.normal == normal and read.friction == friction
    np.testing.assert_array_equal(back.x, run.x)


def test_regularised_is_written_with_its_exact_law_under_exact():
    law = cl.Regularised(law=cl.Coulomb(mu=0.3), velocity=1e-3)
    interface = scenefile.document(scene_with(NORMAL_EXAMPLES[cl.LinearSpring],
                                              law))["interfaces"][0]
    assert interface["friction"] == {"law": "Regularised",
                                     "exact": {"law": "Coulomb", "mu": 0.3},
                                     "velocity": 1e-3}
