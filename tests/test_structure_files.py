"""Scene files, results files and the command line with substructures (DESIGN §7): nodes
of many degrees of freedom read from FE files (.npz, .mat), modal data and the beam
builder, interfaces between their points; each reads, writes back and runs."""

import json
from pathlib import Path

import numpy as np
import pytest
import scipy.io
import scipy.sparse

from contact_laws import Coulomb, LinearSpring
from shroudnet import (
    Blade,
    BladeGroup,
    Coupling,
    Excitation,
    Interface,
    Scene,
    TravellingWave,
    simulate,
)
from shroudnet.front.cli import main
from shroudnet.io import results, scenefile
from shroudnet.model.beam import cantilever_beam
from shroudnet.model.blade import Southwell
from shroudnet.model.reduction import craig_bampton
from shroudnet.model.substructure import Substructure

#: Three DOFs of a small FE model, exported as an FE tool would (SI units).
MASS = np.diag([0.03, 0.02, 0.01])
STIFFNESS = 1e5 * np.array([[2.0, -1.0, 0.0], [-1.0, 2.0, -1.0], [0.0, -1.0, 1.0]])
STIFFNESS_SPEED = 1e-3 * np.eye(3)
SHROUD = [[0.0, 0.0, 1.0], [0.0, 1.0, 0.0]]

#: The module docstring's syntax: a node from a .npz, a reduced one from a .mat, one of
#: modal data; interfaces between two-component points.
SCENE = """\
speed_rpm = 5000.0

[excitation]
engine_order = 2
amplitudes = [0.0, 20.0]

[[blades]]
name = "blade1"
file = "../fe/blade.npz"
names = {stiffness_speed = "K1"}
points = {shroud = [[0.0, 0.0, 1.0], [0.0, 1.0, 0.0]], load = [0.0, 0.5, 1.0]}
load = "load"
damping_ratios = 0.005

[[blades]]
name = "blade2"
file = "../fe/blade.mat"
names = {mass = "Mb", stiffness = "Kb"}
points = {shroud = [[0.0, 0.0, 1.0], [0.0, 1.0, 0.0]]}
load = {point = "shroud", direction = [0.6, 0.8]}
damping_ratios = [0.005, 0.004, 0.003]
excitation_scale = -1.0
reduce = {method = "craig_bampton", boundary = [1, 2], modes = 1}

[[blades]]
name = "blade3"
modal = {frequencies = [180.0, {f0 = 420.0, coefficient = 2.0}], masses = [0.05, 0.04]}
damping_ratios = 0.006
points = {shroud = [[1.0, 0.3], [0.2, 1.0]], load = [0.8, 0.5]}

[[interfaces]]
left = ["blade1", "shroud"]
right = ["blade2", "shroud"]
gap = -2e-6
normal_direction = [0.8, 0.6]
tangent_direction = [-0.6, 0.8]
normal = {law = "LinearSpring", stiffness = 2e5}
friction = {law = "Coulomb", mu = 0.5}

[[interfaces]]
left = ["blade2", "shroud"]
right = ["blade3", "shroud"]
gap = 1e-5
normal_direction = [1.0, 0.0]
tangent_direction = [0.0, 1.0]
normal = {law = "LinearSpring", stiffness = 2e5}

[run]
periods = 6
transient = 2
blade = ["blade2", "shroud", 0]
"""

#: What two scenes must share to be the same to the engine.
ARRAYS = ("mass", "normal_rows", "tangent_rows", "normal_gap", "structure_stiffness",
          "structure_damping", "harmonic_amplitudes", "phases", "excitation_scale")


def scene_file(folder: Path, text: str = SCENE) -> Path:
    """``text`` as scenes/scene.toml in ``folder``, beside fe/ with the matrix files."""
    fe = folder / "fe"
    if not fe.exists():
        fe.mkdir()
        np.savez(fe / "blade.npz", M=MASS, K=STIFFNESS, K1=STIFFNESS_SPEED)
        scipy.io.savemat(fe / "blade.mat", {"Mb": scipy.sparse.csc_matrix(MASS),
                                            "Kb": scipy.sparse.csc_matrix(STIFFNESS)})
    (folder / "scenes").mkdir(exist_ok=True)
    path = folder / "scenes" / "scene.toml"
    path.write_text(text)
    return path


def assert_same_scene(a: Scene, b: Scene):
    for name in ARRAYS:
        np.testing.assert_array_equal(getattr(b.arrays, name), getattr(a.arrays, name),
                                      err_msg=name)
    assert scenefile.document(a) == scenefile.document(b)


def test_matrices_are_read_from_npz_and_mat_files_beside_the_scene_file(tmp_path,
                                                                        monkeypatch):
    path = scene_file(tmp_path)
    monkeypatch.chdir(tmp_path / "fe")  # relative paths are the scene file's, not here
    loaded = scenefile.load(path)
    group = loaded.scene.group
    first = group.blade("blade1")
    np.testing.assert_array_equal(first.mass, MASS)
    np.testing.assert_array_equal(first.stiffness, STIFFNESS)
    np.testing.assert_array_equal(first.stiffness_speed, STIFFNESS_SPEED)
    reduced = craig_bampton(MASS, STIFFNESS, [1, 2], 1, points={"shroud": SHROUD},
                            load=("shroud", (0.6, 0.8)), damping_ratios=(0.005, 0.004, 0.003),
                            excitation_scale=-1.0)
    second = group.blade("blade2")
    for name in ("mass", "stiffness", "basis", "load_vector"):
        np.testing.assert_allclose(getattr(second, name), getattr(reduced, name), rtol=1e-12)
    np.testing.assert_allclose(second.point("shroud"), reduced.point("shroud"), rtol=1e-12)
    modal = group.blade("blade3")
    assert modal.modal_frequencies[1] == Southwell(f0=420.0, coefficient=2.0)
    assert loaded.run.blade == ("blade2", "shroud", 0)
    assert loaded.scene.arrays.n_blades == 3 + 3 + 2  # coordinates
    # the document read holds the files by absolute path, so it reads from anywhere
    assert loaded.document["blades"][1]["file"] == str(tmp_path / "fe" / "blade.mat")
    assert_same_scene(scenefile.read(loaded.document).scene, loaded.scene)


def test_a_scene_of_files_writes_back_by_path_and_reads_back_equal(tmp_path):
    loaded = scenefile.load(scene_file(tmp_path))
    written = scenefile.document(loaded.scene, loaded.run)
    assert written["blades"][0]["file"] == str(tmp_path / "fe" / "blade.npz")
    assert written["blades"][1]["reduce"] == {"method": "craig_bampton", "boundary": [1, 2],
                                              "modes": 1}
    beside = scenefile.document(loaded.scene, folder=tmp_path / "scenes")
    assert [b.get("file") for b in beside["blades"]] == ["../fe/blade.npz",
                                                         "../fe/blade.mat", None]
    copy = scenefile.save(tmp_path / "elsewhere" / "deeper" / "copy.toml", loaded.scene,
                          loaded.run)
    assert 'file = "../../fe/blade.npz"' in copy.read_text()
    again = scenefile.load(copy)
    assert_same_scene(again.scene, loaded.scene)
    assert again.run == loaded.run
    through_json = scenefile.read(json.loads(json.dumps(written)))
    assert_same_scene(through_json.scene, loaded.scene)
    assert scenefile.document(through_json.scene, through_json.run) == written


def python_scene() -> Scene:
    """Substructures built in Python, of every kind ``document`` writes inline: a beam
    (sparse, stiffened with speed), dense matrices with a damping matrix and a load vector,
    modal data, beside a Blade and a fixed node."""
    beam = cantilever_beam(length=0.1, youngs_modulus=2e11, density=7800.0, width=0.02,
                           thickness=0.004, elements=2, hub_radius=0.2, damping_ratios=0.002)
    rig = Substructure(MASS, STIFFNESS, 1e-4 * STIFFNESS, points={"tip": [[0.0, 0.0, 1.0]]},
                       load=np.array([0.0, 1.0, 0.5]), excitation_scale=0.5)
    modal = Substructure.modal([Southwell(f0=300.0, coefficient=3.0), 900.0], [0.01, 0.02],
                               [0.05, 0.03], {"shroud": [[1.0, 0.4]]},
                               load=("shroud", [-1.0]))
    group = (BladeGroup().add_blade("beam", beam).add_blade("rig", rig)
             .add_blade("modal", modal).add_blade("blade", Blade(mass=0.05, damping=1.0,
                                                                  stiffness=1e5))
             .add_fixed("disc"))
    contact = Interface(gap=1e-5, angle=0.5, normal=LinearSpring(stiffness=1e5),
                        friction=Coulomb(mu=0.3))
    group.connect(("beam", "load"), ("rig", "tip"), contact)
    group.connect(("rig", "tip"), ("modal", "shroud"), contact)
    group.connect(("modal", "shroud"), ("blade", "x"), contact)
    group.connect(("rig", "tip"), "disc", Coupling(stiffness=1e4, damping=0.5))
    return Scene(group=group, excitation=Excitation(engine_order=1, amplitudes=(0.0, 5.0),
                                                    phases=TravellingWave(1)),
                 speed_rpm=4000.0)


def test_a_substructure_built_in_python_is_written_inline_and_reads_back_equal(tmp_path):
    scene = python_scene()
    written = scenefile.document(scene)
    beam, rig, modal = written["blades"][:3]
    assert set(beam["mass"]) == {"shape", "rows", "columns", "values"}  # sparse, as triplets
    assert "stiffness_speed" in beam and rig["load"] == [0.0, 1.0, 0.5]
    assert modal["modal"]["frequencies"][1] == 900.0
    assert modal["load"] == {"point": "shroud", "direction": [-1.0]}
    assert written["interfaces"][2]["right"] == ["blade", "x"]
    assert written["couplings"][0]["right"] == "disc"
    again = scenefile.load(scenefile.save(tmp_path / "python.toml", scene)).scene
    assert_same_scene(again, scene)
    assert again.group.edge_points("coupling") == [("tip", None)]


def test_a_beam_node_takes_the_builders_keywords_and_its_numbers_can_be_swept(tmp_path):
    text = SCENE.replace('''modal = {frequencies = [180.0, {f0 = 420.0, coefficient = 2.0}], \
masses = [0.05, 0.04]}
damping_ratios = 0.006
points = {shroud = [[1.0, 0.3], [0.2, 1.0]], load = [0.8, 0.5]}''', '''beam = {length = 0.1, \
youngs_modulus = 2e11, density = 7800.0, width = 0.02, thickness = 0.004, elements = 4}
damping_ratios = 0.002
reduce = {method = "modal_truncation", modes = 3}''')
    loaded = scenefile.load(scene_file(tmp_path, text))
    beam = loaded.scene.group.blade("blade3")
    full = cantilever_beam(length=0.1, youngs_modulus=2e11, density=7800.0, width=0.02,
                           thickness=0.004, elements=4)
    np.testing.assert_allclose(beam.frequencies_at(0.0), full.frequencies_at(0.0)[:3],
                               rtol=1e-9)  # the full model's lowest modes, to rounding
    assert scenefile.document(loaded.scene)["blades"][2]["beam"]["elements"] == 4
    longer = scenefile.SceneAt(loaded.document, "blades.2.beam.length")(0.2)
    assert longer.group.blade("blade3").frequencies_at(0.0)[0] == pytest.approx(
        beam.frequencies_at(0.0)[0] / 4, rel=1e-3)  # f ∝ 1/L²
    with pytest.raises(scenefile.SceneFileError,
                       match=r"blades\[2\]\.beam: cantilever_beam needs density, length"):
        scenefile.load(scene_file(tmp_path, text.replace("length = 0.1, ", "").replace(
            "density = 7800.0, ", "")))


#: (what is wrong, the text of SCENE replaced, its replacement, the message).
BROKEN = [
    ("missing file", 'file = "../fe/blade.npz"', 'file = "../fe/missing.npz"',
     r"blades\[0\]\.file: no such file: .*missing\.npz \(a relative path is read from the "
     r"scene file's folder\)"),
    ("matrix not in the file", 'stiffness = "Kb"', 'stiffness = "Kx"',
     r"blades\[1\]\.file: 'blade\.mat' has no matrix 'Kx' \(stiffness=\); it holds: Kb, Mb"),
    ("unknown point at an end", 'right = ["blade2", "shroud"]', 'right = ["blade2", "tip"]',
     r"interfaces\[0\]: connect\(.*\): node 'blade2' has no point 'tip'; its points are "
     r"\['shroud'\]"),
    ("unknown load point", 'load = "load"', 'load = "root"',
     r"blades\[0\]\.load: names the unknown point 'root'; the points are \['load', 'shroud'\]"),
    ("normal not a unit vector", "normal_direction = [0.8, 0.6]",
     "normal_direction = [0.8, 0.8]", r"interfaces\[0\]: Interface\.normal_direction must be "
                                      r"a unit vector"),
    ("tangent not orthogonal", "tangent_direction = [-0.6, 0.8]",
     "tangent_direction = [0.6, 0.8]",
     r"interfaces\[0\]: Interface\.tangent_direction must be orthogonal to normal_direction"),
    ("one direction only", "tangent_direction = [0.0, 1.0]\n", "",
     r"interfaces\[1\]\.tangent_direction: is required with the other direction"),
    ("load direction not a unit vector", "direction = [0.6, 0.8]", "direction = [0.6, 0.6]",
     r"blades\[1\]: Substructure\.load direction must be a unit vector"),
    ("unknown reduction", 'method = "craig_bampton"', 'method = "guyan"',
     r"blades\[1\]\.reduce\.method: must be one of 'craig_bampton', 'modal_truncation', got "
     r"'guyan'"),
    ("modal data without damping", "damping_ratios = 0.006\n", "",
     r"blades\[2\]\.damping_ratios: is required with modal data"),
    ("two ways of giving a node", 'names = {stiffness_speed = "K1"}',
     'names = {stiffness_speed = "K1"}\nmodal = {frequencies = [1.0], masses = 1.0}',
     r"blades\[0\]: give a node one of file, modal, beam or its matrices inline .*, not file "
     r"and modal"),
    ("a key of another kind of node", "excitation_scale = -1.0", "frequency = 200.0",
     r"blades\[1\]\.frequency: unknown key; allowed keys of a node given by file: "
     r"damping_ratios, excitation_scale, file, load, names, points, reduce"),
    ("an end without its point", 'left = ["blade1", "shroud"]', 'left = ["blade1"]',
     r"interfaces\[0\]\.left: must be a node name \(text or integer\), \[node, point "
     r"name\] or \[node, \[point name, …\]\] \(a patch\), got \['blade1'\]"),
    ("text in a point", "load = [0.0, 0.5, 1.0]", 'load = [0.0, "half", 1.0]',
     r"blades\[0\]\.points\.load: must be a d × n matrix \[\[…\], …\] or a vector \[m\], "
     r"got \[0\.0, 'half', 1\.0\]"),
    ("a point of the wrong size", "load = [0.0, 0.5, 1.0]", "load = [0.5, 1.0]",
     r"blades\[0\]: Substructure\.points\['load'\] must be a d × 3 matrix"),
    ("unknown run response", 'blade = ["blade2", "shroud", 0]',
     'blade = ["blade2", "shroud", 5]', r"run\.blade: unknown response"),
]


@pytest.mark.parametrize("old, new, message", [case[1:] for case in BROKEN],
                         ids=[case[0] for case in BROKEN])
def test_a_bad_substructure_file_is_one_line_naming_its_key(tmp_path, old, new, message):
    assert SCENE.count(old) == 1
    path = scene_file(tmp_path, SCENE.replace(old, new))
    with pytest.raises(scenefile.SceneFileError, match=message) as error:
        scenefile.load(path)
    assert str(error.value).startswith(f"{path}: ") and "\n" not in str(error.value)


def test_a_run_of_a_substructure_scene_saves_and_loads_back_without_loss(tmp_path):
    loaded = scenefile.load(scene_file(tmp_path))
    sim = simulate(loaded.scene, 3, samples_per_period=20)
    path = results.save_simulation(tmp_path / "run.npz", sim, loaded.run)
    back = results.load_simulation(path)
    for name in ("t", "x", "v", "normal_force", "friction_force", "modes", "work"):
        np.testing.assert_array_equal(getattr(back, name), getattr(sim, name))
    assert back.x.shape[1] == 8 and back.events.counts == sim.events.counts
    assert_same_scene(back.scene, sim.scene)
    target = loaded.run.blade
    assert back.energy_density(target, 1) == sim.energy_density(target, 1)
    np.testing.assert_array_equal(back.displacement("blade1", "shroud"),
                                  sim.displacement("blade1", "shroud"))
    assert results.load_run_settings(path) == loaded.run
    damaged = tmp_path / "damaged.npz"
    damaged.write_bytes(path.read_bytes())
    with np.load(damaged) as data:
        content = {name: data[name] for name in data.files}
    content["v"] = content["v"][:, :-1]
    np.savez(damaged, **content)
    with pytest.raises(results.ResultsError, match=r"array 'v' has shape \(61, 7\); it must "
                                                   r"be 61 × 8 \(61 samples × 8 dofs"):
        results.load(damaged)


def test_the_command_line_runs_sweeps_continues_and_mistunes_a_substructure_scene(tmp_path,
                                                                                  capsys):
    scene = scene_file(tmp_path)
    out = tmp_path / "out"
    assert main(["run", str(scene), "-o", str(out)]) == 0
    printed = capsys.readouterr().out
    assert "3 nodes (3 substructures, 8 coordinates), 0 fixed nodes, 2 interfaces" in printed
    assert "(blade2.shroud[0] after 2 periods)" in printed
    peaks = next(line for line in printed.splitlines() if line.startswith("peaks "))
    for point in ("blade1.shroud", "blade1.load", "blade2.shroud", "blade3.shroud",
                  "blade3.load"):
        assert point in peaks
    run = results.load(out / "scene.npz")
    assert run.periods == 6 and scenefile.document(run.scene) == scenefile.document(
        scenefile.load(scene).scene)
    (out / "scene.png").unlink()
    assert main(["plot", str(out / "scene.npz")]) == 0
    assert (out / "scene.png").stat().st_size > 10_000

    folder = tmp_path / "sweep"
    assert main(["sweep", str(scene), "--param", "blades.2.damping_ratios", "--values",
                 "0.004", "0.008", "--record", "3", "--transient", "2", "--workers", "1",
                 "-o", str(folder)]) == 0
    assert results.load(folder).blade == ("blade2", "shroud", 0)

    assert main(["continue", str(scene), "--param", "excitation.amplitudes.1", "--from",
                 "20", "--to", "25", "--max-points", "3", "-o", str(tmp_path)]) == 0
    assert "amplitude (half peak-to-peak) of blade2.shroud[0]" in capsys.readouterr().out
    branch = results.load(tmp_path / "scene-continue-excitation.amplitudes.1.npz")
    assert 2 <= len(branch) <= 3 and branch.orbits[0].state.shape == (16,)

    assert main(["mistuning", str(scene), "--spread", "0.01", "--samples", "2", "--speeds",
                 "5000", "--transient", "3", "--workers", "1", "-o",
                 str(tmp_path / "new")]) == 0
    assert "2 patterns of spread 0.01 at 1 speeds" in capsys.readouterr().out
    assert (tmp_path / "new" / "scene-mistuning.png").stat().st_size > 10_000
