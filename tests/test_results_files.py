"""Saved results that are damaged, inconsistent, misplaced or made elsewhere: every failure
is a ``ResultsError`` naming the file and what is wrong, and a sweep folder repairs what it
can on resuming."""

import json
import math
import subprocess
import sys
import textwrap
from pathlib import Path

import numpy as np
import pytest

from contact_laws import ExponentialFriction, LinearSpring
from shroudnet import Blade, BladeGroup, Excitation, Interface, Scene, Sweep, simulate, sweep
from shroudnet.front.progress import ProgressReporter, SweepWarning
from shroudnet.io import results
from shroudnet.io.results import ResultsError
from shroudnet.scenes import three_blade_paper

ROOT = Path(__file__).resolve().parents[1]
SETTINGS = {"transient": 20, "record": 6, "samples_per_period": 20}


@pytest.fixture(scope="module")
def saved(tmp_path_factory):
    """A simulation of the paper's group, saved: (path, the simulation)."""
    sim = simulate(three_blade_paper(gamma1=2.0), 4, samples_per_period=10)
    return results.save_simulation(tmp_path_factory.mktemp("run") / "run.npz", sim), sim


def copy_of(saved, folder: Path) -> Path:
    path = folder / "copy.npz"
    path.write_bytes(saved[0].read_bytes())
    return path


def rewritten(path: Path, *, meta=None, header=None, **arrays) -> Path:
    """``path`` written again with ``meta`` changed by ``meta(meta)`` (or the raw header
    bytes ``header``) and the given arrays replaced (None: removed)."""
    with np.load(path) as data:
        content = {name: data[name] for name in data.files}
    if header is None:
        decoded = json.loads(content["meta"].tobytes())
        header = json.dumps(decoded if meta is None else meta(decoded)).encode()
    content["meta"] = np.frombuffer(header, dtype=np.uint8)
    for name, array in arrays.items():
        if array is None:
            del content[name]
        else:
            content[name] = array
    np.savez(path, **content)
    return path


def assert_refused(path: Path, message: str, load=results.load):
    with pytest.raises(ResultsError, match=message) as caught:
        load(path)
    assert str(path) in str(caught.value)


# ---- damaged files ------------------------------------------------------------------------

def truncated(path):
    data = path.read_bytes()
    path.write_bytes(data[:len(data) // 2])


def bit_flipped(path):
    data = bytearray(path.read_bytes())
    data[len(data) // 2] ^= 0x10
    path.write_bytes(bytes(data))


def emptied(path):
    path.write_bytes(b"")


def text(path):
    path.write_text("speed_rpm = 6000\n")


def single_array(path):
    with path.open("wb") as file:
        np.save(file, np.zeros(3))


@pytest.mark.parametrize("damage, message", [
    (truncated, r"not a shroudnet results file, or damaged \(BadZipFile"),
    (bit_flipped, r"damaged: cut short, or altered since it was written \(BadZipFile: "
                  r"Bad CRC-32"),
    (emptied, r"the file is empty"),
    (text, r"not a shroudnet results file, or damaged"),
    (single_array, r"holds a single array \(\.npy\)"),
])
def test_a_damaged_file_is_named_with_what_is_wrong(saved, tmp_path, damage, message):
    path = copy_of(saved, tmp_path)
    damage(path)
    for load in (results.load, results.load_simulation, results.load_arrays,
                 results.load_run_settings, results._load_point):
        assert_refused(path, message, load)


def test_a_bit_flipped_anywhere_is_caught(saved, tmp_path):
    """Every 97th byte flipped in turn: each gives ResultsError (the archive's CRC-32
    covers every array and the header), never another exception."""
    original = saved[0].read_bytes()
    path = tmp_path / "flipped.npz"
    for position in range(0, len(original), 97):
        data = bytearray(original)
        data[position] ^= 0x01
        path.write_bytes(bytes(data))
        try:
            results.load_simulation(path)
        except ResultsError as error:
            assert str(path) in str(error)


@pytest.mark.parametrize("header, message", [
    (b"{not json", r"its meta header is not JSON"),
    (b"\xff\xfe", r"its meta header is not JSON"),
    (b"[1, 2]", r"its meta header must be a JSON object, got a list"),
])
def test_a_header_that_is_not_a_json_object_is_named(saved, tmp_path, header, message):
    path = rewritten(copy_of(saved, tmp_path), header=header)
    assert_refused(path, message)


def without(name):
    return lambda meta: {key: value for key, value in meta.items() if key != name}


def replacing(name, value):
    return lambda meta: {**meta, name: value}


@pytest.mark.parametrize("change, message", [
    (replacing("format", 99), r"results format 99; this shroudnet reads formats 1 and 2"),
    (replacing("kind", "sweep point"), r"holds a 'sweep point', not a simulation"),
    (without("energy"), r"its meta header has no 'energy'"),
    (replacing("energy", {"excitation_work": 1.0}),
     r"meta\.energy must be the energy ledger: excitation_work, damping_loss"),
    (replacing("energy", [1, 2]), r"meta\.energy must be the energy ledger"),
    (replacing("samples_per_period", "ten"), r"meta\.samples_per_period must be an int >= 1, "
                                             r"got 'ten'"),
    (replacing("steps", -1), r"meta\.steps must be an int >= 0"),
    (replacing("event_counts", {"closing": "many"}), r"meta\.event_counts must be a table"),
    (replacing("scene", "paper"), r"meta\.scene must be a scene document"),
    (replacing("settings", None), r"meta\.settings must be a JSON object"),
    (replacing("settings", {"method": "test"}),
     r"meta\.settings is damaged \(settings\.method must be one of"),
    (lambda meta: {**meta, "settings": {k: v for k, v in meta["settings"].items()
                                        if k != "event_tolerance"}},
     r"meta\.settings is damaged \(settings of a \w+ run need the keys .*; missing "
     r"\['event_tolerance'\]\)"),
    (replacing("scene", {"blades": 3}), r"its scene document has no list of blades"),
])
def test_a_header_of_the_wrong_shape_is_named(saved, tmp_path, change, message):
    path = rewritten(copy_of(saved, tmp_path), meta=change)
    assert_refused(path, message)


def test_a_scene_document_that_cannot_be_rebuilt_is_named(saved, tmp_path):
    def bad_mass(meta):
        meta["scene"]["blades"][0]["mass"] = -1.0
        return meta

    path = rewritten(copy_of(saved, tmp_path), meta=bad_mass)
    assert_refused(path, r"\(its scene\): blades\[0\]: Blade\.mass must be in \(0, inf\)")
    assert results.load_arrays(path).x.shape == saved[1].x.shape  # the arrays still load


# ---- arrays that do not fit together ------------------------------------------------------

@pytest.mark.parametrize("name, change, message", [
    ("x", lambda a: a[:-1], r"array 'x' has shape \(40, 3\); it must be 41 × 3 \(41 samples "
                            r"× 3 blades\)"),
    ("v", lambda a: a[:, :2], r"array 'v' has shape \(41, 2\); it must be 41 × 3"),
    ("normal_force", lambda a: a[:, :1], r"array 'normal_force' has shape \(41, 1\); it must "
                                         r"be 41 × 2 \(41 samples × 2 interfaces\)"),
    ("friction_force", lambda a: a[::2], r"array 'friction_force' has shape \(21, 2\)"),
    ("modes", lambda a: a.ravel(), r"array 'modes' has shape \(82,\); it must be 41 × 2"),
    ("work", lambda a: a[:-3], r"array 'work' has shape \(38, 5\); it must be 41 × any"),
    ("t", lambda a: a[:-1], r"40 samples are not a whole number of periods of 10 samples"),
    ("event_kind", lambda a: a[:-1], r"array 'event_kind' has shape"),
    ("event_interface", lambda a: a + 7, r"event_interface holds 7 to 8; the scene has "
                                         r"interfaces 0 to 1"),
    ("x", lambda a: a.astype(str), r"array 'x' holds <U\d+, not numbers"),
    ("work", lambda a: None, r"has no array 'work'"),
])
def test_arrays_of_inconsistent_shapes_are_refused_on_loading(saved, tmp_path, name, change,
                                                              message):
    path = copy_of(saved, tmp_path)
    with np.load(path) as data:
        array = data[name]
    assert len(saved[1].events) > 0  # so that the event checks check something
    rewritten(path, **{name: change(array)})
    for load in (results.load_simulation, results.load_arrays):
        assert_refused(path, message, load)


def test_a_scene_with_fixed_nodes_loads_back_with_its_shapes_checked(tmp_path):
    """Fixed nodes have no column in x: the check counts moving blades only."""
    blade = Blade(mass=0.082, damping=4.0, frequency=200.0)
    interface = Interface(gap=2e-5, angle=math.pi / 3, normal=LinearSpring(stiffness=3e5),
                          friction=ExponentialFriction(mu_static=0.5, mu_kinetic=0.3,
                                                       beta=5.0))
    group = BladeGroup().add_blade("a", blade).add_blade("b", blade).add_fixed("disc")
    group.connect("disc", "a", interface).connect("a", "b", interface)
    scene = Scene(group=group, speed_rpm=6000.0,
                  excitation=Excitation(engine_order=2, amplitudes=(0.0, 50.0),
                                        phases=[0.0, math.pi]))
    sim = simulate(scene, 3, samples_per_period=10)
    back = results.load(results.save_simulation(tmp_path / "fixed.npz", sim))
    np.testing.assert_array_equal(back.x, sim.x)
    assert back.x.shape == (31, 2) and back.normal_force.shape == (31, 2)


# ---- where a result cannot be saved -------------------------------------------------------

def test_saving_under_a_file_or_onto_a_folder_is_refused_by_name(saved, tmp_path):
    sim = saved[1]
    blocker = tmp_path / "results"
    blocker.write_text("not a folder")
    with pytest.raises(ResultsError, match=f"cannot save {blocker}/run.npz: {blocker} is a "
                                           "file, not a folder"):
        results.save_simulation(blocker / "run.npz", sim)
    with pytest.raises(ResultsError, match=f"{blocker} is a file, not a folder"):
        results.save_simulation(blocker / "deeper" / "run.npz", sim)
    folder = tmp_path / "folder.npz"
    folder.mkdir()
    with pytest.raises(ResultsError, match=f"{folder}: is a folder; give the name of a file"):
        results.save_simulation(folder, sim)
    with pytest.raises(ResultsError, match=f"{blocker}: is a file; a sweep is saved to a "
                                           "folder"):
        sweep(lambda g: three_blade_paper(gamma1=g), [1.0], save_to=blocker, workers=1,
              **SETTINGS)
    with pytest.raises(ResultsError, match=f"{blocker} is a file, not a folder"):
        sweep(lambda g: three_blade_paper(gamma1=g), [1.0], save_to=blocker / "sweep",
              workers=1, **SETTINGS)
    assert not list(tmp_path.glob("**/.*part"))


# ---- a run whose law was defined in a script ----------------------------------------------

SCRIPT = '''
"""The guide's own law (docs/guide/scenes-and-laws.md), defined in the script that runs
it."""
import sys
from dataclasses import dataclass

import numpy as np

import contact_laws as cl
from shroudnet import results, simulate
from shroudnet.scenes import three_blade_paper


@dataclass(frozen=True, kw_only=True)
class CubicSpring(cl.NormalLaw):
    linear: float   # N/m
    cubic: float    # N/m³

    def __post_init__(self):
        cl.check_real("CubicSpring", "linear", self.linear, low=0.0, unit="N/m")
        cl.check_real("CubicSpring", "cubic", self.cubic, low=0.0, unit="N/m³")

    @staticmethod
    def normal_force(penetration, rate, linear, cubic):
        return linear * penetration + cubic * penetration**3


sim = simulate(three_blade_paper(normal=CubicSpring(linear=3e5, cubic=1e12)), 3,
               samples_per_period=10)
results.save_simulation(sys.argv[1], sim)
np.save(sys.argv[2], sim.x)
'''


@pytest.mark.slow  # compiles a kernel for the script's law
def test_a_run_with_a_law_of_a_script_loads_elsewhere_all_but_its_scene(tmp_path):
    """Saved by a script that defines its own law, the file is read here, another process:
    ``load_simulation`` names the law and says how to make it loadable; ``load_arrays``
    returns every array and the settings, equal to the script's."""
    script = tmp_path / "own_law.py"
    script.write_text(SCRIPT)
    path, x = tmp_path / "run.npz", tmp_path / "x.npy"
    subprocess.run([sys.executable, str(script), str(path), str(x)], cwd=tmp_path,
                   check=True, capture_output=True)
    with pytest.raises(ResultsError) as caught:
        results.load_simulation(path)
    message = str(caught.value)
    for part in (str(path), "uses the law __main__:CubicSpring",
                 "move the law to a module of its own", "results.load_arrays"):
        assert part in message
    data = results.load_arrays(path)
    np.testing.assert_array_equal(data.x, np.load(x))
    assert data.periods == 3 and data.x.shape == (31, 3) and data.normal_force.shape == (31, 2)
    assert data.document["interfaces"][0]["normal"] == {"law": "__main__:CubicSpring",
                                                        "linear": 3e5, "cubic": 1e12}
    assert data.settings["periods"] == 3 and data.energy.excitation_work != 0.0


def test_the_arrays_of_a_simulation_equal_the_simulation(saved):
    path, sim = saved
    data = results.load_arrays(path)
    for field in ("t", "x", "v", "normal_force", "friction_force", "modes", "work"):
        np.testing.assert_array_equal(getattr(data, field), getattr(sim, field))
    np.testing.assert_array_equal(data.events.time, sim.events.time)
    assert data.energy == sim.energy and data.steps == sim.steps
    assert data.periods == sim.periods


# ---- a sweep folder with damaged files ----------------------------------------------------

def paper_scene_at(gamma1):
    return three_blade_paper(gamma1=gamma1)


class Notices(ProgressReporter):
    def __init__(self):
        self.notices = []

    def notice(self, message):
        self.notices.append(message)


VALUES = [1.0, 2.2, 3.5]


@pytest.fixture(scope="module")
def whole():
    return sweep(paper_scene_at, VALUES, workers=1, progress=False, **SETTINGS)


def saved_sweep(folder: Path) -> Path:
    sweep(paper_scene_at, VALUES, workers=1, progress=False, save_to=folder, **SETTINGS)
    return folder


def assert_same(a: Sweep, b: Sweep):
    for p, q in zip(a.points, b.points, strict=True):
        np.testing.assert_array_equal(p.poincare, q.poincare)
        assert p.energy_density == q.energy_density


@pytest.mark.parametrize("damage", [truncated, bit_flipped, emptied])
def test_resuming_computes_a_damaged_point_again_and_names_its_file(tmp_path, whole, damage):
    folder = saved_sweep(tmp_path / "sweep")
    broken = folder / "points" / "00001.npz"
    damage(broken)
    with pytest.raises(ResultsError, match=f"{broken}: .*; run the same sweep again to "
                                           "compute this point again"):
        results.load(folder)
    stamps = {p.name: p.stat().st_mtime_ns for p in (folder / "points").iterdir()}
    notices = Notices()
    resumed = sweep(paper_scene_at, VALUES, workers=1, progress=notices, save_to=folder,
                    **SETTINGS)
    assert len(notices.notices) == 1
    assert notices.notices[0].startswith(f"{broken}: ")
    assert notices.notices[0].endswith("; computing this point again")
    assert_same(resumed, whole)
    assert_same(results.load(folder), whole)
    after = {p.name: p.stat().st_mtime_ns for p in (folder / "points").iterdir()}
    assert after["00000.npz"] == stamps["00000.npz"] and after["00002.npz"] == \
        stamps["00002.npz"] and after["00001.npz"] != stamps["00001.npz"]


def test_a_point_file_with_another_sweeps_value_is_computed_again(tmp_path, whole):
    folder = saved_sweep(tmp_path / "sweep")
    moved = folder / "points" / "00002.npz"
    moved.write_bytes((folder / "points" / "00000.npz").read_bytes())
    notices = Notices()
    resumed = sweep(paper_scene_at, VALUES, workers=1, progress=notices, save_to=folder,
                    **SETTINGS)
    assert notices.notices == [f"{moved}: holds the point of another sweep; computing this "
                               "point again"]
    assert_same(resumed, whole)


@pytest.mark.parametrize("content", ["", "{\"format\": 1, \"kind\"", "[]",
                                     "{\"format\": 1, \"kind\": \"sweep\"}"])
def test_a_damaged_sweep_json_is_written_again_when_the_points_are_this_sweeps(tmp_path,
                                                                              whole, content):
    folder = saved_sweep(tmp_path / "sweep")
    manifest = folder / "sweep.json"
    good = manifest.read_text()
    manifest.write_text(content)
    with pytest.raises(ResultsError, match=f"{manifest}: .*; run the same sweep again with "
                                           f"save_to={folder} to write it again"):
        results.load(folder)
    stamps = [p.stat().st_mtime_ns for p in sorted((folder / "points").iterdir())]
    notices = Notices()
    resumed = sweep(paper_scene_at, VALUES, workers=1, progress=notices, save_to=folder,
                    **SETTINGS)
    assert len(notices.notices) == 1 and notices.notices[0].startswith(f"{manifest}: ")
    assert "written again from this sweep's arguments" in notices.notices[0]
    assert [p.stat().st_mtime_ns for p in sorted((folder / "points").iterdir())] == stamps
    assert manifest.read_text() == good
    assert_same(resumed, whole)
    assert_same(results.load(folder), whole)


def test_a_damaged_sweep_json_is_refused_when_the_points_cannot_be_matched(tmp_path):
    """Points without this sweep's fingerprint (another sweep's, or written before points
    carried one) are not trusted without the manifest: the error says what to do."""
    folder = saved_sweep(tmp_path / "sweep")
    rewritten(folder / "points" / "00001.npz", meta=without("sweep"))
    (folder / "sweep.json").write_text("{")
    with pytest.raises(ResultsError, match=r"sweep\.json: damaged: not JSON .*Its 1 saved "
                                           r"point\(s\) \(00001\.npz\) cannot be matched to "
                                           r"this sweep without it: delete "):
        sweep(paper_scene_at, VALUES, workers=1, progress=False, save_to=folder, **SETTINGS)
    with pytest.raises(ResultsError, match="cannot be matched"):
        sweep(paper_scene_at, [1.0, 2.0], workers=1, progress=False, save_to=folder,
              **SETTINGS)


def test_a_sweep_folder_that_is_not_one_is_named(tmp_path):
    assert_refused(tmp_path, r"not a sweep folder \(no sweep\.json\)")
    (tmp_path / "sweep.json").write_text(json.dumps({"format": 1, "kind": "sweep"}))
    assert_refused(tmp_path, r"sweep\.json: its sweep\.json header has no 'parameter'")
    assert_refused(tmp_path / "nothing", r"no such results file")


def test_points_from_before_fingerprints_still_resume(tmp_path, whole):
    """A folder whose sweep.json is intact keeps its points even if they carry no
    fingerprint (written by an earlier shroudnet)."""
    folder = saved_sweep(tmp_path / "sweep")
    for path in (folder / "points").iterdir():
        rewritten(path, meta=without("sweep"))
    notices = Notices()
    resumed = sweep(paper_scene_at, VALUES, workers=1, progress=notices, save_to=folder,
                    **SETTINGS)
    assert not notices.notices
    assert_same(resumed, whole)


def test_the_script_in_this_file_is_what_the_guide_shows():
    guide = (ROOT / "docs" / "guide" / "scenes-and-laws.md").read_text()
    law = SCRIPT[SCRIPT.index("@dataclass"):SCRIPT.index("\n\n\nsim = ")]
    assert textwrap.dedent(law) in guide


def test_without_a_reporter_a_damaged_point_is_a_warning(tmp_path, whole):
    folder = saved_sweep(tmp_path / "sweep")
    broken = folder / "points" / "00000.npz"
    truncated(broken)
    with pytest.warns(SweepWarning, match=f"{broken}: .*; computing this point again"):
        resumed = sweep(paper_scene_at, VALUES, workers=1, progress=False, save_to=folder,
                        **SETTINGS)
    assert_same(resumed, whole)


def test_a_branch_keeps_its_notes_and_its_orbits_neutral_directions(tmp_path):
    """What the solver said beyond Newton, and which contacts stuck all through (their
    offsets pinned), come back from the file; a file without them loads with none."""
    import dataclasses

    from shroudnet import continuation

    branch = continuation(lambda q1: three_blade_paper(q1=q1, gap=1.0), 10.0, 20.0,
                          max_points=3)
    marked = dataclasses.replace(
        branch, notes=("a step from a transient",),
        orbits=(dataclasses.replace(branch.orbits[0], neutral=(0, 1), neutral_directions=2,
                                    notes=("Newton from the guess did not converge",)),
                *branch.orbits[1:]))
    loaded = results.load(results.save_branch(tmp_path / "branch.npz", marked))
    assert loaded.notes == marked.notes
    first = loaded.orbits[0]
    assert (first.neutral, first.neutral_directions, first.notes) == \
        ((0, 1), 2, ("Newton from the guess did not converge",))
    assert all(o.neutral == () and o.notes == () for o in loaded.orbits[1:])
    older = rewritten(results.save_branch(tmp_path / "older.npz", branch), meta=lambda m: {
        k: v for k, v in m.items()
        if k not in ("notes", "orbit_notes", "neutral", "neutral_directions")})
    assert results.load(older).notes == ()
    damaged = rewritten(results.save_branch(tmp_path / "damaged.npz", branch),
                        meta=lambda m: {**m, "neutral": [["one"]] * len(m["neutral"])})
    with pytest.raises(results.ResultsError,
                       match=r"meta\.neutral must be a list of lists of interface indices"):
        results.load(damaged)
