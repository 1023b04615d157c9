"""The doors of the command line and of ``sweep``: every bad input told in one line with exit
status 2, or as a ValueError/TypeError naming the argument, before any work; output folders
made and proven writable first; a true fault still told as one, with exit status 1.

Nothing here simulates: where a command would reach a simulation, ``simulate`` or the
sweep's ``steady_point`` is replaced by a stand-in that fails the test or answers at once.
"""

import errno
import importlib
import math
import os
from pathlib import Path

import numpy as np
import pytest

import shroudnet.front.bench as bench_module
from contact_laws import check_real
from shroudnet import continuation, sweep
from shroudnet.front import cli
from shroudnet.io import scenefile
from shroudnet.scenes import three_blade_paper
from tests.test_cli_errors import stand_in_point

sweep_module = importlib.import_module("shroudnet.studies.sweep")
ROOT = Path(__file__).resolve().parents[1]
PAPER = ROOT / "examples" / "scenes" / "paper_three_blade.toml"


def scene_file(folder: Path, text: str | None = None) -> Path:
    path = folder / "scene.toml"
    path.write_text(PAPER.read_text() if text is None else text)
    return path


def one_error_line(err: str, command: str) -> str:
    """The message of the single ``shroudnet COMMAND: error: …`` line of ``err``."""
    lines = err.strip().splitlines()
    assert len(lines) == 1, err
    assert "Traceback" not in err
    prefix = f"shroudnet {command}: error: "
    assert lines[0].startswith(prefix), lines[0]
    return lines[0][len(prefix):]


def refuse(*args, **kwargs):
    raise AssertionError("work began before the input was checked")


@pytest.fixture
def no_work(monkeypatch):
    """Fail the test if a command gets as far as simulating, sweeping or benchmarking."""
    for name in ("simulate", "sweep", "continuation", "linear_modes", "mistuning_study"):
        monkeypatch.setattr(cli, name, refuse)
    monkeypatch.setattr(bench_module, "first_runs", refuse)
    monkeypatch.delenv("SHROUDNET_TRACEBACK", raising=False)


# ---- the benchmark's options -------------------------------------------------------------

@pytest.mark.parametrize("option, value, message", [
    ("--points", "-5", "argument --points: must be a whole number >= 1, got -5"),
    ("--points", "many", "argument --points: must be a whole number >= 1, got 'many'"),
    ("--record", "2", "argument --record: must be a whole number >= 3, got 2"),
    ("--transient", "-1", "argument --transient: must be a whole number >= 0, got -1"),
    ("--scaling-points", "0", "argument --scaling-points: must be a whole number >= 1"),
    ("--baseline-periods", "0", "argument --baseline-periods: must be a whole number >= 1"),
    ("--workers", "0", "argument --workers: must be a whole number >= 1, got 0"),
    ("--sections", "12", "argument --sections: must be section numbers 0–11 separated by "
                         "commas, got '12'"),
    ("--sections", "1,,2", "argument --sections: must be section numbers 0–11"),
    ("--sections", "-1", "argument --sections: must be section numbers 0–11"),
])
def test_a_bad_benchmark_option_is_one_line_before_any_work(capsys, no_work, option, value,
                                                            message):
    with pytest.raises(SystemExit) as stopped:
        cli.main(["bench", option, value])
    assert stopped.value.code == 2
    assert one_error_line(capsys.readouterr().err, "bench").startswith(message)


# ---- options argparse refuses are one line too -------------------------------------------

@pytest.mark.parametrize("argv, message", [
    (["run"], "the following arguments are required: scene"),
    (["sweep", "scene.toml", "--param"], "argument --param: expected one argument"),
    (["run", "scene.toml", "--periods", "0"], "argument --periods: must be a whole number"),
])
def test_an_option_argparse_refuses_is_one_line(capsys, argv, message):
    with pytest.raises(SystemExit) as stopped:
        cli.main(argv)
    assert stopped.value.code == 2
    assert one_error_line(capsys.readouterr().err, argv[0]).startswith(message)


# ---- a parameter the scene does not have -------------------------------------------------

@pytest.mark.parametrize("command", [
    ["sweep", "--param", "run.periods", "--values", "3", "4"],
    ["sweep", "--param", "run.rtol", "--values", "1e-8"],
    ["continue", "--param", "run.rtol", "--from", "1e-8", "--to", "1e-6"],
])
def test_a_run_setting_cannot_be_swept_and_the_scenes_numbers_are_named(tmp_path, capsys,
                                                                        no_work, command):
    argv = [command[0], str(scene_file(tmp_path)), *command[1:], "-o", str(tmp_path / "o")]
    assert cli.main(argv) == 2
    error = one_error_line(capsys.readouterr().err, command[0])
    assert error.startswith(f"--param {command[2]}: the [run] table says how the scene is run")
    for number in ("speed_rpm", "excitation.amplitudes.N", "interfaces.N.gap",
                   "interfaces.N.normal.stiffness"):
        assert number in error
    assert "run." not in error.split("vary a number of the scene:")[1]
    assert not (tmp_path / "o").exists()


def test_a_number_that_leaves_the_scene_as_it_is_cannot_be_swept(tmp_path, capsys, no_work,
                                                                 monkeypatch):
    monkeypatch.setattr(cli, "same_scene", lambda a, b: True)
    assert cli.main(["sweep", str(scene_file(tmp_path)), "--param", "speed_rpm",
                     "--values", "5000", "6000"]) == 2
    error = one_error_line(capsys.readouterr().err, "sweep")
    assert error.startswith("--param speed_rpm: the scene is the same at every value")
    assert "vary a number of the scene: speed_rpm, " in error


# ---- output folders: made and proven writable before any work ----------------------------

@pytest.mark.skipif(not Path("/proc/self").is_dir(), reason="needs /proc")
def test_run_into_proc_fails_at_once_naming_the_folder(tmp_path, capsys, no_work):
    assert cli.main(["run", str(scene_file(tmp_path)), "-o", "/proc/foo"]) == 2
    assert one_error_line(capsys.readouterr().err, "run").startswith(
        "--output /proc/foo: cannot write there")


def writing_commands(folder: Path) -> dict[str, list[str]]:
    """Each command that writes, with ``-o`` in ``folder / 'out'``."""
    scene, out = str(scene_file(folder)), str(folder / "out")
    return {
        "run": ["run", scene, "-o", out],
        "sweep": ["sweep", scene, "--param", "speed_rpm", "--values", "5000", "6000",
                  "-o", out],
        "continue": ["continue", scene, "--param", "speed_rpm", "--from", "5000",
                     "--to", "6000", "-o", out],
        "modes": ["modes", scene, "-o", out],
        "mistuning": ["mistuning", scene, "--spread", "0.01", "--samples", "2",
                      "--speeds", "6000", "-o", out],
        "plot": ["plot", str(folder / "saved.npz"), "-o", str(folder / "out" / "f.png")],
    }


@pytest.mark.parametrize("command", ["run", "sweep", "continue", "modes", "mistuning",
                                     "plot"])
def test_every_command_that_writes_proves_its_folder_before_any_work(tmp_path, capsys,
                                                                     no_work, monkeypatch,
                                                                     command):
    """A file system that refuses writes only when one is tried (read-only, full, a
    pseudo file system) is found by the probe file, before any work."""
    def full(*args, **kwargs):
        raise OSError(errno.ENOSPC, "No space left on device")
    monkeypatch.setattr(cli.tempfile, "mkstemp", full)
    argv = writing_commands(tmp_path)[command]
    assert cli.main(argv) == 2
    assert one_error_line(capsys.readouterr().err, command) == (
        f"--output {argv[-1]}: cannot write there (No space left on device)")


def test_the_probe_makes_the_folder_and_leaves_nothing_in_it(tmp_path):
    folder = tmp_path / "a" / "b"
    cli._prove_writable(folder, "--output")
    assert folder.is_dir() and list(folder.iterdir()) == []


def test_a_run_makes_its_folder_before_it_simulates(tmp_path, monkeypatch):
    folder = tmp_path / "new" / "out"

    def simulate(*args, **kwargs):
        assert folder.is_dir() and list(folder.iterdir()) == []
        raise KeyboardInterrupt
    monkeypatch.setattr(cli, "simulate", simulate)
    assert cli.main(["run", str(scene_file(tmp_path)), "-o", str(folder)]) == 130


# ---- which errors are bad input, which a fault -------------------------------------------

def raising(error_or_call):
    """A stand-in for ``simulate`` that raises, or calls something that raises."""
    def stand_in(*args, **kwargs):
        if isinstance(error_or_call, BaseException):
            raise error_or_call
        error_or_call()
    return stand_in


@pytest.mark.parametrize("stand_in, status, message", [
    # a check of shroudnet or contact_laws that refuses a type: bad input
    (raising(lambda: check_real("simulate", "event_tolerance", "x")), 2,
     "simulate.event_tolerance must be a real number, got str 'x'"),
    (raising(lambda: sweep(three_blade_paper, 5)), 2,
     "sweep.values must be a sequence of numbers"),
    # Python meeting a wrong type or a missing attribute inside shroudnet: a fault
    (raising(lambda: len(5)), 1, "unexpected TypeError: object of type 'int' has no len()"),
    (raising(AttributeError("'NoneType' object has no attribute 'x'")), 1,
     "unexpected AttributeError"),
    (raising(KeyError("blade9")), 1, "unexpected KeyError"),
])
def test_a_checks_type_error_is_bad_input_and_a_bug_is_a_fault(tmp_path, capsys, monkeypatch,
                                                             stand_in, status, message):
    monkeypatch.setattr(cli, "simulate", stand_in)
    monkeypatch.delenv("SHROUDNET_TRACEBACK", raising=False)
    assert cli.main(["run", str(scene_file(tmp_path)), "-o", str(tmp_path)]) == status
    error = one_error_line(capsys.readouterr().err, "run")
    assert message in error
    assert ("a fault of shroudnet" in error) == (status == 1)


def test_a_checks_type_error_in_a_worker_process_is_bad_input_too():
    """A sweep's point raises in a worker: the worker's traceback decides."""
    from concurrent.futures import ProcessPoolExecutor

    with ProcessPoolExecutor(max_workers=1) as pool:
        for call, arguments, verdict in ((check_real, ("simulate", "rtol", "x"), True),
                                         (len, (5,), False)):
            with pytest.raises(TypeError) as caught:
                pool.submit(call, *arguments).result()
            assert cli._refused(caught.value) is verdict


def test_a_bug_still_shows_its_traceback_when_asked(tmp_path, monkeypatch):
    monkeypatch.setattr(cli, "simulate", raising(lambda: len(5)))
    monkeypatch.setenv("SHROUDNET_TRACEBACK", "1")
    with pytest.raises(TypeError, match="has no len"):
        cli.main(["run", str(scene_file(tmp_path)), "-o", str(tmp_path)])


@pytest.mark.parametrize("text, named", [
    ("interfaces = 5\n", "the file"),
    ('[run]\nevent_tolerance = "x"\n', "event_tolerance"),
])
def test_a_scene_file_of_the_wrong_shape_is_bad_input(tmp_path, capsys, monkeypatch, text,
                                                      named):
    """Told by the scene file's reader, naming its key, or else by the check of the
    function it reaches first (``simulate`` checks ``event_tolerance`` before any work)."""
    monkeypatch.delenv("SHROUDNET_TRACEBACK", raising=False)
    paper = PAPER.read_text()
    if text.startswith("[run]"):
        body = paper.replace("[run]\n", text)
    else:
        body = text + paper[:paper.index("[[interfaces]]")].split("\n", 1)[1] + \
            paper[paper.index("[run]"):]
    path = scene_file(tmp_path, body)
    assert cli.main(["run", str(path), "-o", str(tmp_path)]) == 2
    error = one_error_line(capsys.readouterr().err, "run")
    assert (str(path) if named == "the file" else named) in error


def test_what_a_scene_file_reader_meets_unnamed_is_told_as_the_files(tmp_path, capsys,
                                                                     no_work, monkeypatch):
    def load(path, laws=()):
        return {}["interfaces"]
    monkeypatch.setattr(scenefile, "load", load)
    path = scene_file(tmp_path)
    assert cli.main(["run", str(path)]) == 2
    assert one_error_line(capsys.readouterr().err, "run") == (
        f"{path}: not a scene file shroudnet can read (KeyError: 'interfaces')")


# ---- sweep: as strict as continuation, every argument checked first ----------------------

@pytest.fixture
def stand_in_points(monkeypatch):
    """``steady_point`` answering at once; the options each point got, by value."""
    seen = {}

    def steady_point(scene, value, **options):
        seen[value] = options
        return stand_in_point(value)
    monkeypatch.setattr(sweep_module, "steady_point", steady_point)
    return seen


def paper_at(gamma1):
    return three_blade_paper(gamma1=gamma1)


def test_a_sweep_refuses_a_scene_at_that_ignores_its_value_as_continuation_does(
        stand_in_points):
    def ignores(value):
        return three_blade_paper()
    with pytest.raises(ValueError, match="sweep: scene_at returns the same scene for "
                                         r"different values \(1 and 3\)"):
        sweep(ignores, [1.0, 2.0, 3.0], workers=1, progress=False)
    with pytest.raises(ValueError, match="continuation: scene_at returns the same scene for "
                                         "different values"):
        continuation(ignores, 1.0, 2.0)
    assert stand_in_points == {}


def test_a_scene_at_that_fails_while_checked_names_its_value(stand_in_points):
    def fails_far(gamma1):
        if gamma1 > 2.0:
            raise ValueError("no scene here")
        return three_blade_paper(gamma1=gamma1)
    with pytest.raises(ValueError, match="no scene here") as caught:
        sweep(fails_far, [1.0, 2.0, 3.0], parameter="gamma1", workers=1, progress=False)
    assert caught.value.__notes__ == ["in the sweep point gamma1 = 3"]
    with pytest.raises(TypeError, match=r"sweep\.scene_at must return a shroudnet\.Scene"):
        sweep(lambda value: "scene", [1.0], workers=1, progress=False)


@pytest.mark.parametrize("values, error, message", [
    (5, TypeError, r"sweep\.values must be a sequence of numbers .*got int 5"),
    (np.array(5.0), TypeError, r"sweep\.values must be a sequence of numbers .*got ndarray"),
    (np.ones((2, 2)), TypeError, r"sweep\.values must be a sequence of numbers"),
    ("1, 2", TypeError, r"sweep\.values must be a sequence of numbers .*got str"),
    ({1.0, 2.0}, TypeError, r"sweep\.values must be a sequence of numbers .*got set"),
    ([], ValueError, r"sweep\.values must be a sequence of at least one number .*got an "
                     r"empty list \[\]"),
    (np.array([]), ValueError, r"sweep\.values must be a sequence of at least one number"),
    ([1.0, "2"], TypeError, r"sweep\.values\[1\] must be a real number, got str"),
    ([1.0, math.nan], ValueError, r"sweep\.values\[1\] must be a number in .*got NaN"),
    ([math.inf], ValueError, r"sweep\.values\[0\] must be in .*got inf"),
    ([True], TypeError, r"sweep\.values\[0\] must be a real number, got bool"),
])
def test_values_must_be_a_sequence_of_finite_numbers(stand_in_points, values, error, message):
    with pytest.raises(error, match=message):
        sweep(paper_at, values, workers=1, progress=False)
    assert stand_in_points == {}


@pytest.mark.parametrize("arguments, error, message", [
    ({"transient": -1}, ValueError, r"sweep\.transient must be an int >= 0"),
    ({"transient": 2.5}, TypeError, r"sweep\.transient must be an int, got float"),
    ({"record": 2}, ValueError, r"sweep\.record must be an int >= 3"),
    ({"record": "100"}, TypeError, r"sweep\.record must be an int, got str"),
    ({"samples_per_period": 0}, ValueError, r"sweep\.samples_per_period must be an int >= 1"),
    ({"samples_per_period": 7, "method": sweep_module.FixedStep()}, ValueError,
     r"sweep\.samples_per_period must divide FixedStep\.steps_per_period"),
    ({"tolerance": 0.0}, ValueError, r"sweep\.tolerance must be in \(0, inf\)"),
    ({"tolerance": math.nan}, ValueError, r"sweep\.tolerance must be a number"),
    ({"tolerance": "tight"}, TypeError, r"sweep\.tolerance must be a real number"),
    ({"workers": 0}, ValueError, r"sweep\.workers must be an int >= 1"),
    ({"workers": 2.0}, TypeError, r"sweep\.workers must be an int, got float"),
    ({"workers": True}, TypeError, r"sweep\.workers must be an int, got bool"),
    ({"progress": 5}, TypeError, r"sweep\.progress must be 'auto', True, False, None or a "
                                 "callable"),
    ({"progress": "loud"}, ValueError, r"sweep\.progress must be"),
    ({"lyapunov": "yes"}, TypeError, r"sweep\.lyapunov must be True or False"),
    ({"continuation": 1}, TypeError, r"sweep\.continuation must be True or False"),
    ({"retry_failed": None}, TypeError, r"sweep\.retry_failed must be True or False"),
    ({"parameter": 5}, TypeError, r"sweep\.parameter must be a str"),
    ({"save_to": 5}, TypeError, r"sweep\.save_to must be the path of a folder"),
    ({"store": "memory"}, TypeError, r"sweep\.store must be a callable"),
    ({"executor": 4}, TypeError, r"sweep\.executor must be"),
    ({"method": "rk4"}, TypeError, r"sweep\.method must be FixedStep"),
    ({"blade": "blade9"}, ValueError, r"sweep\.blade: unknown blade 'blade9'"),
    ({"blade": 3}, ValueError, r"sweep\.blade: unknown blade 3"),
    ({"initial": 5}, TypeError, r"sweep\.initial must be None or \(x0, v0\)"),
    ({"initial": (np.zeros(3),)}, TypeError, r"sweep\.initial must be None or \(x0, v0\)"),
    ({"initial": (np.zeros(3), np.zeros(3), np.zeros(3))}, TypeError,
     r"sweep\.initial must be None or \(x0, v0\)"),
    ({"initial": (np.zeros(2), np.zeros(3))}, ValueError,
     r"sweep\.initial x0 must hold 3 finite numbers"),
    ({"initial": (np.zeros(3), [0.0, math.nan, 0.0])}, ValueError,
     r"sweep\.initial v0 must hold 3 finite numbers"),
    ({"initial": (np.zeros(3), "abc")}, ValueError,
     r"sweep\.initial v0 must hold 3 finite numbers"),
])
def test_every_argument_of_sweep_is_checked_and_named_before_any_point(
        stand_in_points, arguments, error, message):
    options = {"workers": 1, "progress": False, **arguments}
    if "executor" in arguments or "continuation" in arguments:
        del options["workers"]
    with pytest.raises(error, match=message):
        sweep(paper_at, [1.0, 2.0], **options)
    assert stand_in_points == {}


def test_numpy_numbers_are_taken_as_pythons(stand_in_points):
    result = sweep(paper_at, np.array([1.0, 2.0], dtype=np.float32),
                   transient=np.int64(2), record=np.int32(3),
                   samples_per_period=np.int16(5), workers=np.int64(1), blade=np.int64(1),
                   tolerance=np.float32(1e-5), progress=False)
    assert result.values.tolist() == [1.0, 2.0]
    assert result.blade == 1 and type(result.blade) is int
    options = stand_in_points[1.0]
    assert (options["transient"], options["record"], options["samples_per_period"]) == \
        (2, 3, 5)
    assert all(type(options[key]) is int for key in ("transient", "record",
                                                     "samples_per_period"))
    assert type(result.settings["tolerance"]) is float
    assert sweep(paper_at, range(1, 3), workers=1, progress=False).values.tolist() == \
        [1.0, 2.0]


def test_the_command_line_sweep_reaches_no_point_with_an_unchanging_parameter(
        tmp_path, capsys, stand_in_points):
    assert cli.main(["sweep", str(scene_file(tmp_path)), "--param", "run.periods",
                     "--values", "3", "4", "--workers", "1", "-o",
                     str(tmp_path / "out")]) == 2
    assert "run.periods" in one_error_line(capsys.readouterr().err, "sweep")
    assert stand_in_points == {}
    assert os.listdir(tmp_path) == ["scene.toml"]
