"""Scene files, saved results and the ``shroudnet`` command, end to end."""

import json
import math
import os
import signal
import subprocess
import sys
from dataclasses import asdict
from pathlib import Path

import numpy as np
import pytest

from shroudnet import (
    BladeGroup,
    Coupling,
    HarmonicMotion,
    MotionTable,
    Scene,
    continuation,
    simulate,
    sweep,
)
from shroudnet import scenes as sn_scenes
from shroudnet.front.cli import main
from shroudnet.io import results, scenefile
from shroudnet.scenes import block_on_belt, three_blade_paper

ROOT = Path(__file__).resolve().parents[1]
SCENES = ROOT / "examples" / "scenes"
PAPER = SCENES / "paper_three_blade.toml"


def small_paper_scene(folder: Path, periods=30, transient=20) -> Path:
    """The shipped paper scene file, with a short run."""
    text = PAPER.read_text().replace("periods = 400", f"periods = {periods}")
    path = folder / "paper.toml"
    path.write_text(text.replace("transient = 300", f"transient = {transient}"))
    return path


def test_the_paper_scene_file_is_the_paper_scene():
    loaded = scenefile.load(PAPER)
    built, paper = loaded.scene.arrays, three_blade_paper().arrays
    for field in ("mass", "damping", "stiffness", "gap", "sin_angle", "cos_angle",
                  "static_mu", "amplitudes", "phases", "excitation_frequency"):
        np.testing.assert_allclose(getattr(built, field), getattr(paper, field), rtol=1e-15)
    assert built.normal_laws == paper.normal_laws and built.friction_laws == paper.friction_laws
    assert loaded.run.blade == "blade2" and loaded.run.transient == 300


@pytest.mark.parametrize("name", ["paper_three_blade", "ring_24_travelling_wave",
                                  "mistuned_packet", "bladed_disc_24", "belt_stick_slip"])
def test_every_shipped_scene_reads_and_writes_back_to_the_same_scene(name):
    loaded = scenefile.load(SCENES / f"{name}.toml")
    again = scenefile.read(json.loads(json.dumps(scenefile.document(loaded.scene, loaded.run))))
    assert scenefile.document(again.scene, again.run) == scenefile.document(loaded.scene,
                                                                            loaded.run)
    assert again.run == loaded.run
    np.testing.assert_array_equal(again.scene.arrays.stiffness, loaded.scene.arrays.stiffness)
    np.testing.assert_array_equal(again.scene.arrays.phases, loaded.scene.arrays.phases)


@pytest.mark.parametrize("preset", ["three_blade_paper", "bladed_disc_24", "block_on_belt",
                                    "modal_packet", "beam_pair"])
def test_every_shipped_scene_saves_from_python_and_loads_back_equal(preset, tmp_path):
    """``save(scene, path)`` (either order) writes a TOML file that ``load`` reads back into
    the same scene: the same document, and the same arrays the dynamics work on."""
    from shroudnet import scenes
    scene = getattr(scenes, preset)()
    path = scenefile.save(scene, tmp_path / f"{preset}.toml")
    again = scenefile.load(path).scene
    assert scenefile.document(again) == scenefile.document(scene)
    built, original = again.arrays, scene.arrays
    for field in ("mass", "damping", "stiffness", "gap", "harmonic_amplitudes",
                  "harmonic_phases", "static_mu", "tangential_stiffness"):
        np.testing.assert_array_equal(getattr(built, field), getattr(original, field))
    assert scenefile.load(scenefile.save(tmp_path / "swapped.toml", scene)).scene.blades \
        == scene.blades
    with pytest.raises(TypeError, match=r"scenefile\.save\.scene must be a shroudnet\.Scene"):
        scenefile.save(tmp_path / "x.toml", "scene")
    with pytest.raises(TypeError, match=r"scenefile\.save\.path must be a path"):
        scenefile.save(scene, 5)


def test_an_unforced_node_and_an_engine_order_wave_read_and_write_back():
    """``excitation_scale`` survives the round trip; ``"engine-order"`` becomes the
    travelling wave with ND = l mod N, here 2 mod 3 = 2."""
    document = scenefile.document(three_blade_paper())
    document["blades"][0]["excitation_scale"] = 0.0
    document["blades"][2]["excitation_scale"] = -0.24
    document["excitation"]["phases"] = "engine-order"
    with pytest.warns(UserWarning, match="takes this packet's 3 blades for a whole disc"):
        scene = scenefile.read(document).scene
    np.testing.assert_array_equal(scene.arrays.excitation_scale, [0.0, 1.0, -0.24])
    np.testing.assert_allclose(scene.arrays.phases, [0.0, 4 * math.pi / 3, 8 * math.pi / 3])
    again = scenefile.document(scene)
    assert again["blades"][0]["excitation_scale"] == 0.0
    assert again["blades"][2]["excitation_scale"] == -0.24
    assert "excitation_scale" not in again["blades"][1]
    assert again["excitation"]["phases"] == {"travelling_wave": 2}


def test_the_belt_file_is_the_shipped_belt_scene_and_every_motion_writes_back():
    loaded = scenefile.load(SCENES / "belt_stick_slip.toml").scene
    built = block_on_belt()
    assert loaded.group.prescribed == built.group.prescribed
    assert loaded.excitation_period == built.excitation_period
    assert not any(loaded.excitation.amplitudes)
    group = BladeGroup()
    group.graph = built.group.graph.copy()  # the scene's own is frozen
    group.add_prescribed("shaker", HarmonicMotion(amplitude=1e-4, frequency=80.0, phase=0.5))
    group.add_prescribed("path", MotionTable(times=(0.0, 1.0, 2.0),
                                             displacements=(0.0, 1e-3, 0.0)))
    group.connect("block", "shaker", Coupling(stiffness=1e3))
    group.connect("block", "path", Coupling(stiffness=1e3))
    scene = Scene(group=group, excitation=built.excitation, speed_rpm=built.speed_rpm)
    again = scenefile.read(json.loads(json.dumps(scenefile.document(scene)))).scene
    assert again.group.prescribed == scene.group.prescribed


@pytest.mark.parametrize("motion, message", [
    ('{kind = "table", times = [0.0, 0.2, 0.1], displacements = [0.0, 1e-3, 0.0]}',
     r"prescribed\[0\]\.motion: MotionTable\.times must increase strictly: times\[2\] = "
     r"0\.1 s follows times\[1\] = 0\.2 s"),
    ('{kind = "table", times = [0.0, 0.1], displacements = [0.0]}',
     r"prescribed\[0\]\.motion: MotionTable\.displacements needs one value per time"),
    ('{kind = "belt", velocity = 0.1}',
     r"prescribed\[0\]\.motion\.kind: must be one of 'constant_velocity', 'harmonic', "
     r"'table', got 'belt'"),
    ('{kind = "harmonic", amplitude = 1e-4}',
     r"prescribed\[0\]\.motion: .*frequency"),
])
def test_a_bad_prescribed_motion_is_one_line_naming_its_key(tmp_path, motion, message):
    text = (SCENES / "belt_stick_slip.toml").read_text().replace(
        'motion = {kind = "constant_velocity", velocity = 0.1}', f"motion = {motion}")
    path = tmp_path / "belt.toml"
    path.write_text(text)
    with pytest.raises(scenefile.SceneFileError, match=message) as error:
        scenefile.load(path)
    assert "\n" not in str(error.value)


def test_a_user_law_is_named_by_its_module():
    from tests.laws import CubicSpring
    scene = three_blade_paper(normal=CubicSpring(linear=3e5, cubic=1e12))
    document = scenefile.document(scene)
    assert document["interfaces"][0]["normal"]["law"] == "tests.laws:CubicSpring"
    assert scenefile.read(document).scene.group.interfaces[0][2].normal == scene.group \
        .interfaces[0][2].normal


def broken_files(folder: Path):
    """(file, expected message): each breaks one thing in the paper's scene file."""
    paper = PAPER.read_text()
    cases = {
        "unknown top-level key": (paper.replace("speed_rpm = 6000.0", "speed_rpm = 6000.0\n"
                                                "sped = 1"),
                                  r"sped: unknown key; allowed keys: blades, couplings, "
                                  r"excitation"),
        "missing speed": (paper.replace("speed_rpm = 6000.0", ""), r"speed_rpm: is required"),
        "negative mass": (paper.replace("mass = 0.082", "mass = -0.082", 1),
                          r"blades\[0\]: Blade\.mass must be in \(0, inf\) kg, got -0\.082"),
        "unknown law": (paper.replace('law = "LinearSpring"', 'law = "Linear"', 1),
                        r"interfaces\[0\]\.normal\.law: 'Linear' is not a NormalLaw; built in: "
                        r"ConstantLoad, Hertz, HuntCrossley, KelvinVoigt, LinearSpring"),
        "wrong law field": (paper.replace("mu_kinetic = 0.3", "mu_dynamic = 0.3", 1),
                            r"interfaces\[0\]\.friction\.mu_dynamic: unknown key; allowed "
                            r"fields of ExponentialFriction: beta, mu_kinetic, mu_static"),
        "friction out of range": (paper.replace("mu_kinetic = 0.3", "mu_kinetic = 0.7", 1),
                                  r"ExponentialFriction\.mu_kinetic must be in \[0, "
                                  r"mu_static = 0\.5\]"),
        "unknown blade": (paper.replace('right = "blade3"', 'right = "blade4"'),
                          r"interfaces\[1\]: connect\('blade2', 'blade4'\): unknown node "
                          r"'blade4'"),
        "text for a number": (paper.replace("gap = 2e-5", 'gap = "small"', 1),
                              r"interfaces\[0\]\.gap: must be a number, got 'small'"),
        "no frequency": (paper.replace("frequency = { f0 = 194.55636166861493, coefficient "
                                       "= 0.76 }", "", 1),
                         r"blades\[0\]: give a blade either frequency \[Hz\] or stiffness"),
        "bad phases": (paper.replace('phases = "anti-phase"', 'phases = "wave"'),
                       r'excitation\.phases: must be "anti-phase", "engine-order", '
                       r'\{travelling_wave = nd\}'),
        "bad method": (paper.replace('method = "adaptive"', 'method = "rk45"'),
                       r"run\.method: must be one of 'adaptive', 'fixed', 'exponential', "
                       r"'accuracy'"),
        "knob of another method": (paper.replace("rtol = 1e-8", "steps_per_period = 500"),
                                   r"run\.steps_per_period: does not apply to method = "
                                   r"'adaptive'; it takes atol, max_step, rtol"),
        "transient too long": (paper.replace("transient = 300", "transient = 500"),
                               r"run\.transient must be an int in \[0, periods = 400\)"),
        "unknown run blade": (paper.replace('blade = "blade2"', 'blade = "blade9"'),
                              r"run\.blade: unknown blade 'blade9': give a name in "
                              r"\['blade1', 'blade2', 'blade3'\]"),
        "not TOML": ("speed_rpm = = 1", r"not valid TOML"),
    }
    for number, (name, (text, message)) in enumerate(cases.items()):
        path = folder / f"broken{number}.toml"
        path.write_text(text)
        yield name, path, message


def test_each_broken_scene_file_names_its_key_before_any_work(tmp_path):
    for name, path, message in broken_files(tmp_path):
        with pytest.raises(scenefile.SceneFileError, match=message):
            scenefile.load(path)
        assert str(path) in str(pytest.raises(scenefile.SceneFileError, scenefile.load,
                                              path).value), name
    with pytest.raises(scenefile.SceneFileError, match="no such scene file"):
        scenefile.load(tmp_path / "missing.toml")


def test_a_result_file_loads_back_without_loss(tmp_path):
    loaded = scenefile.load(small_paper_scene(tmp_path))
    sim = simulate(loaded.scene, 12)
    path = results.save_simulation(tmp_path / "run.npz", sim, loaded.run)
    back = results.load_simulation(path)
    for field in ("t", "x", "v", "normal_force", "friction_force", "modes", "work"):
        np.testing.assert_array_equal(getattr(back, field), getattr(sim, field))
        assert getattr(back, field).dtype == getattr(sim, field).dtype
    for field in ("time", "interface", "kind"):
        np.testing.assert_array_equal(getattr(back.events, field), getattr(sim.events, field))
    assert back.events.counts == sim.events.counts and back.energy == sim.energy
    assert back.settings == sim.settings and back.steps == sim.steps
    assert scenefile.document(back.scene) == scenefile.document(sim.scene)
    assert back.energy_density("blade2", 4) == sim.energy_density("blade2", 4)
    assert results.load_run_settings(path) == loaded.run
    assert not list(tmp_path.glob(".*part"))  # nothing left from the atomic write


def test_command_line_runs_the_belt_and_its_result_loads_back(tmp_path, capsys):
    assert main(["run", str(SCENES / "belt_stick_slip.toml"), "-o", str(tmp_path)]) == 0
    out = capsys.readouterr().out
    assert "1 prescribed" in out and "no excitation (periods of 0.1 s)" in out
    back = results.load(tmp_path / "belt_stick_slip.npz")
    assert back.scene.group.prescribed == block_on_belt().group.prescribed
    assert back.events.counts["sticking"] > 20


def test_command_line_run_sweep_and_plot(tmp_path, capsys):
    scene = small_paper_scene(tmp_path)
    assert main(["run", str(scene), "-o", str(tmp_path / "out")]) == 0
    out = capsys.readouterr().out
    for line in ("scene ", "method ", "took ", "motion ", "E_rho ", "events ", "energy ",
                 "saved "):
        assert line in out
    assert "residual" in out and "of the excitation work" in out
    run = results.load(tmp_path / "out" / "paper.npz")
    assert run.periods == 30 and (tmp_path / "out" / "paper.png").stat().st_size > 10_000

    folder = tmp_path / "sweep"
    assert main(["sweep", str(scene), "--param", "interfaces.0.normal.stiffness",
                 "--values", "1.5e5:3e5:3", "4e5", "--record", "5", "--transient", "10",
                 "--workers", "1", "-o", str(folder)]) == 0
    assert "motions " in capsys.readouterr().out
    diagram = results.load(folder)
    assert diagram.values.tolist() == [1.5e5, 2.25e5, 3e5, 4e5]
    assert (folder / "bifurcation.png").stat().st_size > 10_000

    (folder / "bifurcation.png").unlink()
    (tmp_path / "out" / "paper.png").unlink()
    assert main(["plot", str(folder)]) == 0
    assert main(["plot", str(tmp_path / "out" / "paper.npz")]) == 0
    assert (folder / "bifurcation.png").exists() and (tmp_path / "out" / "paper.png").exists()


def test_command_line_continue_saves_a_branch_that_loads_back_equal_and_redraws(tmp_path,
                                                                               capsys):
    """The forced response of the paper's scene file over 6000–6300 rpm, through the
    torus bifurcation where period 1 becomes stable; the saved branch loads back with
    every orbit, multiplier and switch it had, and its scene at each value."""
    assert main(["continue", str(PAPER), "--param", "speed_rpm", "--from", "6000",
                 "--to", "6300", "-o", str(tmp_path)]) == 0
    out = capsys.readouterr().out
    assert "followed speed_rpm from 6000 to 6300" in out and "torus" in out
    assert "amplitude (half peak-to-peak) of blade2 =" in out  # the [run] blade, by name
    saved = tmp_path / "paper_three_blade-continue-speed_rpm.npz"
    figure = saved.with_suffix(".png")
    assert figure.stat().st_size > 10_000
    branch = results.load(saved)
    document = scenefile.load(PAPER).document
    expected = continuation(scenefile.SceneAt(document, "speed_rpm"), 6000.0, 6300.0,
                            parameter="speed_rpm")
    assert branch.parameter.tolist() == expected.parameter.tolist()
    assert [b.kind for b in branch.bifurcations] == ["torus"]
    for a, b in zip([*branch.orbits, *(x.orbit for x in branch.bifurcations)],
                    [*expected.orbits, *(x.orbit for x in expected.bifurcations)]):
        assert scenefile.document(a.scene) == scenefile.document(b.scene)
        for name in ("multipliers", "monodromy", "peak", "mean_square", "state", "maximum",
                     "minimum", "mean"):
            np.testing.assert_array_equal(getattr(a, name), getattr(b, name))
        assert a.event_sequence == b.event_sequence and a.events.counts == b.events.counts
        assert (a.residual, a.scale, a.periods, a.singular) == \
            (b.residual, b.scale, b.periods, b.singular)
    assert (branch.name, branch.ended, branch.periods) == \
        (expected.name, expected.ended, expected.periods)
    assert branch.bifurcations[0].multiplier == expected.bifurcations[0].multiplier
    figure.unlink()
    assert main(["plot", str(saved)]) == 0
    assert figure.stat().st_size > 10_000


def test_the_command_line_names_its_blade_and_takes_another_by_name(tmp_path, capsys):
    from shroudnet.front.cli import _about
    scene = small_paper_scene(tmp_path, periods=22, transient=20)
    assert main(["run", str(scene), "-o", str(tmp_path), "--no-figure", "--blade",
                 "blade3"]) == 0
    out = capsys.readouterr().out
    assert "E_rho" in out and "(blade3 " in out.split("E_rho")[1].splitlines()[0]
    assert main(["run", str(scene), "-o", str(tmp_path / "x"), "--blade", "blade9"]) == 2
    assert "--blade: " in capsys.readouterr().err
    paper = three_blade_paper()
    assert [_about(paper, target) for target in (1, "blade1")] == ["blade2", "blade1"]
    packet = sn_scenes.modal_packet()
    assert _about(packet, ("blade2", "shroud", 1)) == "blade2.shroud[1]"
    from shroudnet.front.cli import _blade_name
    assert _blade_name("blade2.shroud[1]") == ("blade2", "shroud", 1)
    assert _blade_name("tip_blade") == "tip_blade"


def test_a_branch_of_a_scene_made_in_python_saves_its_scenes_one_by_one(tmp_path):
    branch = continuation(lambda q1: three_blade_paper(q1=q1, gap=1.0), 10.0, 20.0,
                          max_points=4)
    loaded = results.load(results.save_branch(tmp_path / "b.npz", branch))
    assert [scenefile.document(o.scene) for o in loaded.orbits] == \
        [scenefile.document(o.scene) for o in branch.orbits]
    np.testing.assert_array_equal(loaded.amplitude("blade2"), branch.amplitude("blade2"))


def test_command_line_errors_are_one_clear_line(tmp_path, capsys):
    name, path, message = next(broken_files(tmp_path))
    assert main(["run", str(path)]) == 2
    assert capsys.readouterr().err.startswith(f"shroudnet run: error: {path}: sped: ")
    scene = small_paper_scene(tmp_path)
    assert main(["sweep", str(scene), "--param", "interfaces.5.gap", "--values", "1"]) == 2
    assert "nothing at interfaces.5; keys there: indices 0 to 1" in capsys.readouterr().err
    assert main(["sweep", str(scene), "--param", "speed_rpm", "--values", "fast"]) == 2
    assert "'fast' is neither a number nor START:STOP:COUNT" in capsys.readouterr().err
    assert main(["continue", str(scene), "--param", "speed_rpm", "--from", "6000",
                 "--to", "-1"]) == 2
    assert "speed_rpm" in capsys.readouterr().err
    for command in ("run", "sweep", "continue", "modes", "mistuning", "plot", "bench"):
        with pytest.raises(SystemExit) as done:
            main([command, "--help"])
        assert done.value.code == 0
        assert "usage: " in capsys.readouterr().out


def test_an_interrupted_sweep_resumes_without_losing_or_repeating_a_point(tmp_path):
    """Stopped after two of five points, the sweep runs only the three missing ones and
    ends equal to an uninterrupted sweep, bit for bit."""
    def scene_at(gamma1):
        return three_blade_paper(gamma1=gamma1)

    values = [1.0, 2.0, 3.0, 3.5, 4.0]
    options = dict(parameter="gamma1", transient=20, record=6, workers=1)

    class Interrupted(Exception):
        pass

    def stop_after_two(done, total):
        if done == 2:
            raise Interrupted

    folder = tmp_path / "sweep"
    with pytest.raises(Interrupted):
        sweep(scene_at, values, save_to=folder, progress=stop_after_two, **options)
    first = sorted((folder / "points").iterdir())
    assert [p.name for p in first] == ["00000.npz", "00001.npz"]
    stamps = [p.stat().st_mtime_ns for p in first]

    seen = []
    resumed = sweep(scene_at, values, save_to=folder, progress=lambda d, t: seen.append(d),
                    **options)
    assert seen == [2, 3, 4, 5]  # starts with two done; three computed
    assert [p.stat().st_mtime_ns for p in first] == stamps  # not written again
    whole = sweep(scene_at, values, progress=False, **options)
    for a, b in zip(resumed.points, whole.points):
        np.testing.assert_array_equal(a.poincare, b.poincare)
        assert a.energy_density == b.energy_density
        np.testing.assert_equal(asdict(a.classification), asdict(b.classification))
    assert results.load(folder).points[4].energy_density == whole.points[4].energy_density
    with pytest.raises(results.ResultsError, match=r"holds another sweep \(its values differ"):
        sweep(scene_at, values[:3], save_to=folder, **options)


#: A ``shroudnet`` process killed (SIGKILL) half-way through writing its point file number
#: $KILL_AT (0-based, in the order written): the kill lands in the middle of a write,
#: always at the same point, whatever the speed of the machine.
KILLED_WHILE_WRITING = """
import os, signal, sys
from pathlib import Path

replace, written = os.replace, 0

def replace_or_die(source, target):
    global written
    if Path(target).parent.name == "points":
        if written == int(os.environ["KILL_AT"]):
            os.truncate(source, os.path.getsize(source) // 2)
            os.kill(os.getpid(), signal.SIGKILL)
        written += 1
    replace(source, target)

os.replace = replace_or_die
from shroudnet.cli import main
sys.exit(main(sys.argv[1:]))
"""


@pytest.mark.slow
def test_a_command_line_sweep_killed_while_writing_a_point_resumes(tmp_path, capsys):
    """SIGKILL in the middle of writing the fourth point file: the three before it are
    whole, the fourth is only a temporary file, and the same command finishes the rest
    without computing the three again."""
    scene = small_paper_scene(tmp_path)
    folder = tmp_path / "sweep"
    arguments = ["sweep", str(scene), "--param", "interfaces.0.normal.stiffness",
                 "--values", "1.5e5:1.2e6:6", "--transient", "5", "--record", "3",
                 "--workers", "1", "-o", str(folder)]
    killed = subprocess.run([sys.executable, "-c", KILLED_WHILE_WRITING, *arguments],
                            env={**os.environ, "KILL_AT": "3"}, capture_output=True)
    assert killed.returncode == -signal.SIGKILL, killed.stderr.decode()
    kept = sorted(folder.glob("points/*.npz"))
    assert [p.name for p in kept] == ["00000.npz", "00001.npz", "00002.npz"]
    assert len(list(folder.glob("points/.00003.npz.*.part"))) == 1  # the write cut short
    for point in kept:  # whole: every array reads back, its checksum intact
        with np.load(point) as data:
            for name in data.files:
                data[name]
    stamps = [p.stat().st_mtime_ns for p in kept]

    assert main(arguments) == 0
    assert "motions " in capsys.readouterr().out
    assert [p.stat().st_mtime_ns for p in kept] == stamps  # not computed again
    assert len(results.load(folder).points) == 6
    assert not list(folder.glob("points/.*"))  # no temporary file left


DISC = SCENES / "bladed_disc_24.toml"


def test_command_line_modes_prints_the_zzenf_table_of_the_disc(tmp_path, capsys):
    from shroudnet import linear_modes
    from shroudnet.scenes import bladed_disc_24
    assert main(["modes", str(DISC), "-o", str(tmp_path)]) == 0
    out = capsys.readouterr().out
    assert "24 sectors at 3000 rpm" in out
    expected = linear_modes(bladed_disc_24(), "open").families()
    row = next(line for line in out.splitlines() if line.startswith("ND   6"))
    assert f"{expected[6, 0]:9.2f}" in row and f"{expected[6, 1]:9.2f}" in row
    assert (tmp_path / "bladed_disc_24-modes.png").stat().st_size > 10_000


def test_command_line_mistuning_reports_the_distribution_and_the_bound(tmp_path, capsys):
    small = tmp_path / "disc3.toml"
    small.write_text(DISC.read_text().replace("count = 24", "count = 3"))
    assert main(["mistuning", str(small), "--spread", "0.02", "--samples", "3", "--speeds",
                 "2900:3100:2", "--transient", "30", "--workers", "1", "-o",
                 str(tmp_path)]) == 0
    out = capsys.readouterr().out
    assert "3 patterns of spread 0.02 at 2 speeds" in out
    assert "Whitehead's bound ½(1 + √3) = 1.3660" in out
    assert (tmp_path / "disc3-mistuning.png").stat().st_size > 10_000
    assert main(["mistuning", str(small), "--spread", "-1", "--samples", "3", "--speeds",
                 "3000"]) == 2
    assert "mistuning_study.spread must be in [0, 0.3]" in capsys.readouterr().err
