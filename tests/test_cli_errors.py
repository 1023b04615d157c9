"""Bad input to scene files and to the ``shroudnet`` command: one clear line, never a
traceback, and no simulation before the input has been checked.

Nothing here runs a simulation: where a command would reach one, ``simulate`` or the sweep's
``steady_point`` is replaced by a stand-in.
"""

import functools
import importlib
import math
import os
import re
import struct
import sys
import types
import zipfile
from dataclasses import dataclass, replace
from pathlib import Path

import numpy as np
import pytest

import contact_laws as cl
from shroudnet.analysis.readings import Classification
from shroudnet.front import cli
from shroudnet.io import results, scenefile
from shroudnet.run.simulation import SimulationError, SweepPoint

sweep_module = importlib.import_module("shroudnet.studies.sweep")
ROOT = Path(__file__).resolve().parents[1]
PAPER = ROOT / "examples" / "scenes" / "paper_three_blade.toml"


def scene_file(folder: Path, text: str | None = None, name: str = "scene.toml") -> Path:
    path = folder / name
    path.write_text(PAPER.read_text() if text is None else text)
    return path


def with_law(folder: Path, law: str) -> Path:
    """The paper's scene file with its first normal law named ``law``."""
    text = PAPER.read_text().replace('law = "LinearSpring"', f'law = "{law}"', 1)
    return scene_file(folder, text, "own_law.toml")


def one_error_line(err: str, command: str) -> str:
    """The message of the single ``shroudnet COMMAND: error: …`` line of ``err``."""
    lines = err.strip().splitlines()
    assert len(lines) == 1, err
    assert "Traceback" not in err
    prefix = f"shroudnet {command}: error: "
    assert lines[0].startswith(prefix), lines[0]
    return lines[0][len(prefix):]


@pytest.fixture
def no_simulation(monkeypatch):
    """Fail the test if the command gets as far as simulating."""
    def refuse(*args, **kwargs):
        raise AssertionError("a simulation ran before the input was checked")
    monkeypatch.setattr(cli, "simulate", refuse)
    monkeypatch.setattr(cli, "sweep", refuse)


# ---- a scene file never runs code ------------------------------------------------------

def test_reading_a_scene_file_never_imports_the_module_it_names(tmp_path, capsys,
                                                                  monkeypatch):
    monkeypatch.delitem(sys.modules, "this", raising=False)
    path = with_law(tmp_path, "this:Zen")
    with pytest.raises(scenefile.SceneFileError,
                       match=r"interfaces\[0\]\.normal\.law: 'this:Zen': module 'this' is "
                             r"not imported.*--laws this"):
        scenefile.load(path)
    assert "this" not in sys.modules
    assert capsys.readouterr() == ("", "")


def test_the_command_never_imports_the_module_a_scene_file_names(tmp_path, capsys,
                                                                   monkeypatch, no_simulation):
    monkeypatch.delitem(sys.modules, "this", raising=False)
    assert cli.main(["run", str(with_law(tmp_path, "this:Zen"))]) == 2
    captured = capsys.readouterr()
    assert captured.out == "" and "this" not in sys.modules
    assert "module 'this' is not imported" in one_error_line(captured.err, "run")


def test_a_law_of_an_already_imported_module_is_found():
    from tests.laws import CubicSpring
    document = scenefile.document(scenefile.load(PAPER).scene)
    document["interfaces"][0]["normal"] = {"law": "tests.laws:CubicSpring",
                                           "linear": 3e5, "cubic": 1e12}
    law = scenefile.read(document).scene.group.interfaces[0][2].normal
    assert law == CubicSpring(linear=3e5, cubic=1e12)


@dataclass(frozen=True, kw_only=True)
class SoftSpring(cl.NormalLaw):
    """A law whose module is not imported anywhere: it must be passed in ``laws``."""

    stiffness: float

    @staticmethod
    def normal_force(penetration, rate, stiffness):
        return stiffness * penetration


SoftSpring.__module__ = "unimported_laws"


def test_a_law_of_a_module_not_imported_needs_to_be_passed():
    document = scenefile.document(scenefile.load(PAPER).scene)
    document["interfaces"][0]["normal"] = {"law": "unimported_laws:SoftSpring",
                                           "stiffness": 1e5}
    with pytest.raises(scenefile.SceneFileError, match="pass the class in laws="):
        scenefile.read(document)
    read = scenefile.read(document, laws=[SoftSpring])
    assert read.scene.group.interfaces[0][2].normal == SoftSpring(stiffness=1e5)
    module = types.ModuleType("unimported_laws")
    module.SoftSpring = SoftSpring
    by_module = scenefile.read(document, laws=[module])
    assert by_module.scene.group.interfaces[0][2].normal == SoftSpring(stiffness=1e5)
    at = scenefile.SceneAt(document, "interfaces.0.normal.stiffness", laws=(SoftSpring,))
    assert at(2e5).group.interfaces[0][2].normal == SoftSpring(stiffness=2e5)


@pytest.mark.parametrize("law, message", [
    ("os:system", "'os:system' is not a NormalLaw"),
    ("contact_laws:NormalLaw", "is not a NormalLaw"),
    ("NormalLaw", "is not a NormalLaw"),
    ("tests.laws:NoSuchLaw", "module 'tests.laws' has no 'NoSuchLaw'"),
])
def test_a_law_name_that_is_no_law_is_refused(tmp_path, law, message):
    import tests.laws  # noqa: F401  (imported, so that only the class is missing)
    with pytest.raises(scenefile.SceneFileError, match=message):
        scenefile.load(with_law(tmp_path, law))


@pytest.mark.parametrize("laws", [SoftSpring, ["not a law"], "unimported_laws"])
def test_laws_must_be_a_list_of_law_classes_or_modules(laws):
    with pytest.raises(TypeError, match="laws must"):
        scenefile.read({}, laws=laws)


@pytest.fixture
def own_law_module(tmp_path, monkeypatch):
    """A module ``my_shroud_laws`` in the current folder, not imported; removed after."""
    (tmp_path / "my_shroud_laws.py").write_text(
        "from dataclasses import dataclass\n"
        "import contact_laws as cl\n\n"
        "@dataclass(frozen=True, kw_only=True)\n"
        "class Stiff(cl.NormalLaw):\n"
        "    stiffness: float\n\n"
        "    @staticmethod\n"
        "    def normal_force(penetration, rate, stiffness):\n"
        "        return stiffness * penetration\n")
    monkeypatch.chdir(tmp_path)
    monkeypatch.setattr(sys, "path", list(sys.path))
    yield "my_shroud_laws"
    sys.modules.pop("my_shroud_laws", None)


def test_the_laws_option_allows_a_module_of_ones_own(tmp_path, own_law_module, capsys):
    scene = with_law(tmp_path, f"{own_law_module}:Stiff")
    sweep = ["sweep", str(scene), "--param", "no_such_key", "--values", "1"]
    assert cli.main(sweep) == 2
    assert f"--laws {own_law_module}" in one_error_line(capsys.readouterr().err, "sweep")
    assert own_law_module not in sys.modules
    # Allowed, the file reads; the sweep then stops at its --param, before any work.
    assert cli.main(sweep + ["--laws", own_law_module]) == 2
    assert "no_such_key: nothing at no_such_key" in one_error_line(capsys.readouterr().err,
                                                                  "sweep")


def test_the_laws_option_says_it_runs_the_modules_code(capsys):
    for command in ("run", "sweep", "plot"):
        with pytest.raises(SystemExit):
            cli.main([command, "--help"])
        assert "RUNS ITS CODE" in " ".join(capsys.readouterr().out.split())


def test_the_laws_option_names_a_module_that_cannot_be_imported(tmp_path, capsys,
                                                                 no_simulation):
    assert cli.main(["run", str(scene_file(tmp_path)), "--laws", "no_such_module_here"]) == 2
    assert "--laws no_such_module_here: cannot import it" in one_error_line(
        capsys.readouterr().err, "run")


# ---- files that are not scene files -----------------------------------------------------

def bad_scene(folder: Path, kind: str) -> tuple[Path, str]:
    """(path, expected message) of a scene file that cannot be read."""
    if kind == "empty":
        return scene_file(folder, ""), "the file is empty"
    if kind == "blank":
        return scene_file(folder, "\n  \n"), "the file is empty"
    if kind == "binary":
        path = folder / "garbage.toml"
        path.write_bytes(bytes(range(256)) * 4)
        return path, "not a text file (UTF-8 TOML)"
    if kind == "folder":
        return folder, "is a folder; give a scene file"
    if kind == "device":
        return Path("/dev/null"), "is not a regular file"
    if kind == "nested":
        return scene_file(folder, "a = " + "[" * 100_000 + "]" * 100_000), "nested too deeply"
    if kind == "missing":
        return folder / "missing.toml", "no such scene file"
    raise ValueError(kind)


@pytest.mark.parametrize("kind", ["empty", "blank", "binary", "folder", "missing",
                                  pytest.param("device", marks=pytest.mark.skipif(
                                      not Path("/dev/null").exists(), reason="no /dev/null")),
                                  "nested"])
def test_a_file_that_is_no_scene_file_is_one_error_line(tmp_path, capsys, kind,
                                                        no_simulation):
    path, message = bad_scene(tmp_path, kind)
    with pytest.raises(scenefile.SceneFileError, match=re.escape(message)):
        scenefile.load(path)
    for command in (["run", str(path)], ["sweep", str(path), "--param", "speed_rpm",
                                         "--values", "1"]):
        assert cli.main(command) == 2
        assert message in one_error_line(capsys.readouterr().err, command[0])


# ---- options checked by argparse, before anything is read ---------------------------------

@pytest.mark.parametrize("option, value, message", [
    ("--workers", "0", "argument --workers: must be a whole number >= 1, got 0"),
    ("--record", "0", "argument --record: must be a whole number >= 3, got 0"),
    ("--record", "2", "argument --record: must be a whole number >= 3, got 2"),
    ("--transient", "-5", "argument --transient: must be a whole number >= 0, got -5"),
    ("--workers", "two", "argument --workers: must be a whole number >= 1, got 'two'"),
])
def test_sweep_counts_are_checked_before_anything_is_read(tmp_path, capsys, option, value,
                                                          message, no_simulation):
    with pytest.raises(SystemExit) as stopped:
        cli.main(["sweep", str(tmp_path / "missing.toml"), "--param", "speed_rpm",
                  "--values", "1", f"{option}={value}"])
    assert stopped.value.code == 2
    assert capsys.readouterr().err.strip().splitlines()[-1] == f"shroudnet sweep: error: " \
                                                               f"{message}"


@pytest.mark.parametrize("value", ["0", "-3"])
def test_run_periods_must_be_a_positive_whole_number(tmp_path, capsys, value, no_simulation):
    with pytest.raises(SystemExit) as stopped:
        cli.main(["run", str(scene_file(tmp_path)), f"--periods={value}"])
    assert stopped.value.code == 2
    assert "argument --periods: must be a whole number >= 1" in capsys.readouterr().err


# ---- output locations, checked before any simulation -------------------------------------

@pytest.fixture
def a_file(tmp_path) -> Path:
    path = tmp_path / "a_file"
    path.write_text("not a folder")
    return path


@pytest.mark.parametrize("where, message", [
    (lambda f: f / "x", "a_file is a file, not a folder"),
    (lambda f: f / "x" / "y", "a_file is a file, not a folder"),
    (lambda f: f, "a_file is a file, not a folder"),
])
def test_run_and_sweep_refuse_an_output_under_a_file_before_simulating(
        tmp_path, capsys, a_file, where, message, no_simulation):
    scene = str(scene_file(tmp_path))
    for command in (["run", scene], ["sweep", scene, "--param", "speed_rpm", "--values",
                                     "5000", "6000"]):
        assert cli.main(command + ["-o", str(where(a_file))]) == 2
        error = one_error_line(capsys.readouterr().err, command[0])
        assert error.startswith("--output ") and message in error


def test_run_refuses_a_results_name_taken_by_a_folder(tmp_path, capsys, no_simulation):
    scene = scene_file(tmp_path)
    (tmp_path / "out" / "scene.npz").mkdir(parents=True)
    assert cli.main(["run", str(scene), "-o", str(tmp_path / "out")]) == 2
    assert "scene.npz: is a folder" in one_error_line(capsys.readouterr().err, "run")


@pytest.mark.skipif(os.name != "posix" or os.geteuid() == 0,
                    reason="needs POSIX permissions that bind (root writes anywhere)")
def test_run_refuses_a_folder_it_cannot_write(tmp_path, capsys, no_simulation):
    locked = tmp_path / "locked"
    locked.mkdir()
    locked.chmod(0o500)
    try:
        assert cli.main(["run", str(scene_file(tmp_path)), "-o", str(locked / "out")]) == 2
        assert "cannot write in" in one_error_line(capsys.readouterr().err, "run")
    finally:
        locked.chmod(0o700)


def test_the_writable_check_asks_the_system(tmp_path, monkeypatch):
    """As root the test above cannot run; the check itself asks ``os.access``."""
    monkeypatch.setattr(os, "access", lambda path, mode: False)
    with pytest.raises(cli.UsageError, match="cannot write in"):
        cli._check_folder(tmp_path / "new", "--output")


# ---- the kernel cache folder (SHROUDNET_CACHE) --------------------------------------------

@pytest.mark.parametrize("where, why", [
    (lambda f: f, "is a file, not a folder"),
    (lambda f: f / "kernels", "a_file is a file, not a folder"),
])
@pytest.mark.parametrize("clear", [[], ["--clear"]])
def test_the_cache_command_refuses_a_cache_at_a_file(capsys, monkeypatch, a_file, where, why,
                                                     clear):
    monkeypatch.setenv("SHROUDNET_CACHE", str(where(a_file)))
    assert cli.main(["cache", *clear]) == 2
    error = one_error_line(capsys.readouterr().err, "cache")
    assert error.startswith(f"SHROUDNET_CACHE={where(a_file)}: ") and why in error
    assert a_file.read_text() == "not a folder"


def test_the_cache_command_refuses_a_folder_it_cannot_write(tmp_path, capsys, monkeypatch):
    """(``os.access`` answers as for a user without the right: root writes anywhere.)"""
    monkeypatch.setenv("SHROUDNET_CACHE", str(tmp_path))
    monkeypatch.setattr(os, "access", lambda path, mode: False)
    assert cli.main(["cache"]) == 2
    assert one_error_line(capsys.readouterr().err, "cache") == (
        f"SHROUDNET_CACHE={tmp_path}: cannot write in {tmp_path} (permission denied); set "
        "SHROUDNET_CACHE to a folder that can be written")


def test_the_cache_command_reports_a_folder_still_to_be_made(tmp_path, capsys, monkeypatch):
    monkeypatch.setenv("SHROUDNET_CACHE", str(tmp_path / "new" / "kernels"))
    monkeypatch.setattr("shroudnet.engine.cache._engine_files", lambda: [])
    assert cli.main(["cache"]) == 0
    assert capsys.readouterr().out.startswith(f"cache    {tmp_path / 'new' / 'kernels'}: 0.0 MiB")


def test_a_run_with_a_cache_at_a_file_is_one_error_line_before_any_compile(
        tmp_path, capsys, monkeypatch, a_file):
    generate = importlib.import_module("shroudnet.engine.generate")
    monkeypatch.setattr(generate, "_kernel", functools.cache(generate._kernel.__wrapped__))
    monkeypatch.setattr(generate, "_method_free",
                        functools.cache(generate._method_free.__wrapped__))

    def no_compile(*args, **kwargs):
        raise AssertionError("a kernel was built in a cache folder that cannot hold it")
    monkeypatch.setattr(generate, "_run_phases", no_compile)
    monkeypatch.setenv("SHROUDNET_CACHE", str(a_file))
    assert cli.main(["run", str(scene_file(tmp_path)), "-o", str(tmp_path / "out")]) == 2
    assert one_error_line(capsys.readouterr().err, "run") == (
        f"SHROUDNET_CACHE={a_file}: is a file, not a folder; set SHROUDNET_CACHE to a folder "
        "that can be written")


# ---- what simulate raises reaches the terminal as a line ---------------------------------

@pytest.mark.parametrize("error, status, message", [
    (MemoryError(), 2, "not enough memory"),
    (ValueError("simulate: 1e9 periods of 100 samples need 2.4 TB"), 2, "need 2.4 TB"),
    (SimulationError("Zeno: 10000 events in 1e-12 s"), 2, "Zeno"),
    (OSError(28, "No space left on device", "out/scene.npz"),
     2, "out/scene.npz: No space left on device"),
    (FileExistsError(17, "File exists", "out"), 2, "out: File exists"),
    (NotADirectoryError(20, "Not a directory", "out/x"), 2, "out/x: Not a directory"),
    (RuntimeError("a fault"), 1, "unexpected RuntimeError: a fault"),
])
def test_what_a_run_raises_is_one_error_line(tmp_path, capsys, monkeypatch, error, status,
                                             message):
    def fail(*args, **kwargs):
        raise error
    monkeypatch.setattr(cli, "simulate", fail)
    monkeypatch.delenv("SHROUDNET_TRACEBACK", raising=False)
    assert cli.main(["run", str(scene_file(tmp_path)), "--periods", "1000000000",
                     "-o", str(tmp_path / "out")]) == status
    assert message in one_error_line(capsys.readouterr().err, "run")


def test_ctrl_c_during_a_run_is_one_line_and_status_130(tmp_path, capsys, monkeypatch):
    def interrupted(*args, **kwargs):
        raise KeyboardInterrupt
    monkeypatch.setattr(cli, "simulate", interrupted)
    assert cli.main(["run", str(scene_file(tmp_path)), "-o", str(tmp_path)]) == 130
    err = capsys.readouterr().err
    assert err.strip() == "shroudnet run: interrupted; nothing was saved"


# ---- damaged results files ---------------------------------------------------------------

@pytest.fixture(scope="module")
def results_file(tmp_path_factory) -> Path:
    """A small, valid results file (no simulation: arrays of the right shapes)."""
    from shroudnet.run.simulation import EnergyLedger, EventLog, Simulation
    loaded = scenefile.load(PAPER)
    run = replace(loaded.run, periods=4, transient=1)
    n, m, samples = 3, 2, 21
    events = EventLog(time=np.zeros(0), interface=np.zeros(0, dtype=np.int64),
                      kind=np.zeros(0, dtype=np.int64), counts={})
    settings = {"method": "FixedStep", "steps_per_period": 10, "periods": 4,  # as saved
                "samples_per_period": 5, "event_tolerance": 1e-10,
                "zeno": {"events": 200, "window": 1e-4}}
    sim = Simulation(scene=loaded.scene, settings=settings,
                     t=np.linspace(0.0, 4 * loaded.scene.excitation_period, samples),
                     x=np.zeros((samples, n)), v=np.zeros((samples, n)),
                     normal_force=np.zeros((samples, m)), friction_force=np.zeros((samples, m)),
                     modes=np.zeros((samples, m), dtype=np.int8), events=events,
                     energy=EnergyLedger(0.0, 0.0, 0.0, 0.0, 0.0, 0.0),
                     work=np.zeros((samples, 5)), samples_per_period=5, steps=10)
    folder = tmp_path_factory.mktemp("results")
    return results.save_simulation(folder / "run.npz", sim, run)


def middle_of_largest_member(archive: Path) -> int:
    """The offset of the middle byte of the largest array stored in an .npz file: one its
    CRC covers, wherever the lengths of the file's header and of the zip's fields put it
    (the middle of the whole file may fall in a zip field no reader checks)."""
    with zipfile.ZipFile(archive) as opened:
        member = max(opened.infolist(), key=lambda info: info.compress_size)
    data = archive.read_bytes()
    start = member.header_offset  # the local header: 30 bytes, the name, an extra field
    name, extra = struct.unpack("<HH", data[start + 26:start + 30])
    return start + 30 + name + extra + member.compress_size // 2


def damaged(original: Path, folder: Path, how: str) -> Path:
    data = original.read_bytes()
    path = folder / f"{how}.npz"
    if how == "empty":
        path.write_bytes(b"")
    elif how == "truncated":
        path.write_bytes(data[: len(data) // 2])
    elif how == "bit-flipped":
        middle = middle_of_largest_member(original)
        path.write_bytes(data[:middle] + bytes([data[middle] ^ 0x10]) + data[middle + 1:])
    elif how == "garbage":
        path.write_bytes(b"PK\x03\x04" + bytes(200))
    elif how == "header not JSON":
        np.savez(path, meta=np.frombuffer(b"{not json", dtype=np.uint8))
    elif how == "header a list":
        np.savez(path, meta=np.frombuffer(b"[1, 2]", dtype=np.uint8))
    elif how == "header without scene":
        np.savez(path, meta=np.frombuffer(b'{"format": 1, "kind": "simulation"}',
                                          dtype=np.uint8))
    elif how == "no header":
        np.savez(path, x=np.zeros(3))
    elif how == "text":
        path.write_text("speed_rpm = 1\n")
    else:
        raise ValueError(how)
    return path


@pytest.mark.parametrize("how", ["empty", "truncated", "bit-flipped", "garbage",
                                 "header not JSON", "header a list", "header without scene",
                                 "no header", "text"])
def test_plot_of_a_damaged_results_file_is_one_error_line(tmp_path, capsys, results_file,
                                                          how):
    path = damaged(results_file, tmp_path, how)
    assert cli.main(["plot", str(path)]) == 2
    assert str(path) in one_error_line(capsys.readouterr().err, "plot")
    assert not path.with_suffix(".png").exists()


def test_plot_refuses_a_figure_under_a_file(tmp_path, capsys, results_file, a_file):
    assert cli.main(["plot", str(results_file), "-o", str(a_file / "figure.png")]) == 2
    assert "figure.png: " in (error := one_error_line(capsys.readouterr().err, "plot"))
    assert "a_file is a file, not a folder" in error


def test_plot_of_a_folder_that_is_no_sweep_is_one_error_line(tmp_path, capsys):
    assert cli.main(["plot", str(tmp_path)]) == 2
    assert str(tmp_path) in one_error_line(capsys.readouterr().err, "plot")


# ---- swept values ------------------------------------------------------------------------

def parsed_values(arguments: list[str]) -> list[float]:
    args = cli._parser().parse_args(["sweep", "scene.toml", "--param", "interfaces.0.gap",
                                     *arguments])
    return cli._values(args.values)


@pytest.mark.parametrize("arguments", [["--values", "-1e-5:2e-5:4"],
                                       ["--values=-1e-5:2e-5:4"]])
def test_negative_ranges_are_values_with_or_without_the_equals_sign(arguments):
    assert parsed_values(arguments) == pytest.approx([-1e-5, 0.0, 1e-5, 2e-5])


def test_negative_numbers_are_values_among_others():
    assert parsed_values(["--values", "-1e-5", "-.5", "-3", "2e-5", "-o", "out"]) \
        == [-1e-5, -0.5, -3.0, 2e-5]
    assert parsed_values(["--values", "-1e-5", "--record", "5"]) == [-1e-5]


@pytest.mark.parametrize("token, message", [("fast", "'fast' is neither a number"),
                                            ("1:2", "'1:2' is neither a number"),
                                            ("1:2:0", "COUNT must be a whole number >= 1"),
                                            ("1:2:-4", "COUNT must be a whole number >= 1"),
                                            ("1:2:x", "COUNT must be a whole number >= 1"),
                                            ("a:2:3", "'a:2:3' is neither a number"),
                                            ("nan", "every value must be finite"),
                                            ("1:inf:3", "every value must be finite")])
def test_a_value_that_is_no_number_is_named(token, message):
    with pytest.raises(cli.UsageError, match=message):
        parsed_values(["--values", token])


def test_an_integer_field_stays_an_integer():
    document = scenefile.load(PAPER).document
    changed = scenefile.with_value(document, "excitation.engine_order", 3.0)
    assert changed["excitation"]["engine_order"] == 3
    assert type(changed["excitation"]["engine_order"]) is int
    assert scenefile.read(changed).scene.excitation.engine_order == 3
    assert type(scenefile.with_value(document, "speed_rpm", 5000)["speed_rpm"]) is float
    at = scenefile.SceneAt(document, "excitation.engine_order")
    assert at(4.0).excitation.engine_order == 4


@pytest.mark.parametrize("value", [2.5, math.inf, math.nan])
def test_a_fraction_for_an_integer_field_is_refused(value):
    document = scenefile.load(PAPER).document
    with pytest.raises(scenefile.SceneFileError,
                       match=r"--param excitation\.engine_order: holds an integer \(2\), so "
                             r"each value must be a whole number"):
        scenefile.with_value(document, "excitation.engine_order", value)


def test_a_fraction_for_an_integer_field_fails_the_sweep_before_any_work(tmp_path, capsys,
                                                                         no_simulation):
    assert cli.main(["sweep", str(scene_file(tmp_path)), "--param",
                     "excitation.engine_order", "--values", "1", "2.5", "3"]) == 2
    assert "must be a whole number, got 2.5" in one_error_line(capsys.readouterr().err,
                                                               "sweep")


def test_a_bad_value_in_the_middle_of_a_range_fails_before_any_work(tmp_path, capsys,
                                                                    no_simulation):
    assert cli.main(["sweep", str(scene_file(tmp_path)), "--param", "blades.1.mass",
                     "--values", "0.1:-0.1:3"]) == 2
    assert "blades.1.mass = 0" in one_error_line(capsys.readouterr().err, "sweep")


# ---- sweeps: failed points, Ctrl-C --------------------------------------------------------

def stand_in_point(value) -> SweepPoint:
    """A computed point without a simulation (a period-1 motion at x = value)."""
    return SweepPoint(value=float(value), poincare=np.full((3, 2), float(value)),
                      energy_density=1.0, friction_loss_per_cycle=0.0,
                      classification=Classification(label="p1", period=1, n_points=3,
                                                    tolerance=1e-5, mismatch=0.0,
                                                    zero_one=math.nan, broadband=0.0),
                      final_state=(np.zeros(3), np.zeros(3)))


@pytest.fixture
def stand_in_points(monkeypatch):
    """``steady_point`` replaced: each value in ``fail`` raises a ``SimulationError``, the
    value ``stop`` raises ``KeyboardInterrupt``; the others are computed at once. Returns
    the settings and the values computed."""
    setting = types.SimpleNamespace(fail=set(), stop=None, computed=[])

    def steady_point(scene, value, **options):
        if value == setting.stop:
            raise KeyboardInterrupt
        setting.computed.append(value)
        if value in setting.fail:
            raise SimulationError(f"Zeno behaviour at t = 0.01 s on interface 0 ({value:g})")
        return stand_in_point(value)

    monkeypatch.setattr(sweep_module, "steady_point", steady_point)
    return setting


def sweep_command(tmp_path) -> list[str]:
    return ["sweep", str(scene_file(tmp_path)), "--param", "speed_rpm", "--values",
            "5000", "5500", "6000", "6500", "--workers", "1", "-o", str(tmp_path / "sweep")]


def test_a_failed_point_is_told_and_the_sweep_goes_on(tmp_path, capsys, stand_in_points):
    stand_in_points.fail = {5500.0, 6500.0}
    assert cli.main(sweep_command(tmp_path)) == 0
    captured = capsys.readouterr()
    told = [line for line in captured.err.splitlines() if "failed" in line]
    assert len(told) == 2 and "Traceback" not in captured.err
    assert "speed_rpm = 5500 (point 1) failed: Zeno behaviour" in told[0]
    assert "speed_rpm = 6500 (point 3) failed" in told[1]
    assert "failed   2 of 4 points, left out of the diagram: speed_rpm = 5500, " \
           "speed_rpm = 6500" in captured.out
    assert "--retry-failed" in captured.out
    assert (tmp_path / "sweep" / "bifurcation.png").exists()
    assert stand_in_points.computed == [5000.0, 5500.0, 6000.0, 6500.0]

    # Resumed, the failed points are kept unless asked to retry them.
    stand_in_points.computed.clear()
    assert cli.main(sweep_command(tmp_path)) == 0
    assert stand_in_points.computed == []
    assert "kept 2 failed point(s)" in capsys.readouterr().err
    stand_in_points.fail = set()
    assert cli.main(sweep_command(tmp_path) + ["--retry-failed"]) == 0
    assert stand_in_points.computed == [5500.0, 6500.0]
    assert "failed " not in capsys.readouterr().out


def test_a_sweep_whose_every_point_fails_says_so(tmp_path, capsys, stand_in_points):
    stand_in_points.fail = {5000.0, 5500.0, 6000.0, 6500.0}
    assert cli.main(sweep_command(tmp_path)) == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert err[-1].startswith("shroudnet sweep: error: every point failed")
    assert not (tmp_path / "sweep" / "bifurcation.png").exists()


def test_ctrl_c_keeps_the_points_saved_and_says_how_to_resume(tmp_path, capsys,
                                                              stand_in_points):
    stand_in_points.stop = 6000.0
    assert cli.main(sweep_command(tmp_path)) == 130
    err = capsys.readouterr().err
    folder = tmp_path / "sweep"
    assert err.strip() == (f"shroudnet sweep: interrupted; the 2 of 4 points saved in "
                           f"{folder}/ are kept: run the same command again to compute "
                           "only the missing ones")
    stand_in_points.stop, stand_in_points.computed = None, []
    assert cli.main(sweep_command(tmp_path)) == 0
    assert stand_in_points.computed == [6000.0, 6500.0]
    assert results.load(folder).values.tolist() == [5000.0, 5500.0, 6000.0, 6500.0]


def test_ctrl_c_in_the_benchmark_is_one_line(capsys, monkeypatch):
    import shroudnet.front.bench as bench

    def interrupted(options):
        raise KeyboardInterrupt
    monkeypatch.setattr(bench, "main", interrupted)
    assert cli.main(["bench", "--quick"]) == 130
    assert capsys.readouterr().err.strip() == "shroudnet bench: interrupted; nothing was saved"


def test_an_error_that_stops_a_sweep_names_its_point(tmp_path, capsys, monkeypatch):
    def steady_point(scene, value, **options):
        if value == 5500.0:
            raise ValueError("a law rejected its state")
        return stand_in_point(value)
    monkeypatch.setattr(sweep_module, "steady_point", steady_point)
    assert cli.main(sweep_command(tmp_path)) == 2
    assert one_error_line(capsys.readouterr().err, "sweep") == (
        "a law rejected its state (in the sweep point speed_rpm = 5500)")
