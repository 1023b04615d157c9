"""The ``shroudnet`` command: run a scene file, sweep one of its numbers, redraw, benchmark.

    shroudnet run SCENE.toml                       simulate; summary, results and figure
    shroudnet sweep SCENE.toml --param PATH --values ...   a bifurcation diagram
    shroudnet continue SCENE.toml --param PATH --from A --to B   a forced-response curve
    shroudnet modes SCENE.toml                     linear modes, open and stuck, by ND
    shroudnet mistuning SCENE.toml --spread S --samples K --speeds ...   mistuning
    shroudnet plot RESULTS                         redraw a saved run or sweep
    shroudnet bench [--quick]                      the benchmark

``shroudnet COMMAND --help`` explains each. Scene files are described in
``shroudnet.scenefile``; examples are in ``examples/scenes/``.

Whatever goes wrong is told in one line, ``shroudnet COMMAND: error: …``, with exit status
2 (bad input: a file, a folder, an option), 1 (a fault of shroudnet itself; set
``SHROUDNET_TRACEBACK=1`` to see where) or 130 (interrupted with Ctrl-C). Options, files and
output folders are checked before any work: a folder to write in is made and a file written
and removed there first.
"""

from __future__ import annotations

import argparse
import importlib
import os
import re
import sys
import tempfile
import time
import traceback
import zipfile
from collections.abc import Iterator
from contextlib import contextmanager
from dataclasses import replace
from pathlib import Path
from types import ModuleType

import numpy as np

import contact_laws

from ..analysis.readings import classify
from ..engine.cache import cache_folder, cache_size, checked_cache_folder, clear_cache
from ..io import results, scenefile
from ..linear.modes import linear_modes
from ..model.group import BLADE_POINT
from ..model.substructure import Substructure
from ..run.methods import TRANSIENT
from ..run.simulate import simulate
from ..run.simulation import SimulationError, steady_rows
from ..steady.continuation import LARGEST_STEP, Branch, continuation
from ..steady.parametric import same_scene
from ..studies.sweep import default_workers, sweep
from .options import whole
from .progress import ProgressReporter, TerminalProgress
from .studies import mistuning_study

#: Exit statuses.
BAD_INPUT, FAULT, INTERRUPTED = 2, 1, 130

#: Errors that mean bad input (a file, a folder, an option, a parameter value), told in a
#: line: ``SceneFileError`` and ``ResultsError`` are ``ValueError``s. A ``TypeError`` is bad
#: input too when one of shroudnet's checks raised it (``_refused``).
_INPUT_ERRORS = (ValueError, OSError, EOFError, zipfile.BadZipFile, SimulationError)

#: The folders of the packages whose ``raise TypeError(...)`` is a check of an argument.
_CHECKING_CODE = (Path(__file__).resolve().parents[1],  # shroudnet
                  Path(contact_laws.__file__).resolve().parent)


class UsageError(ValueError):
    """An option that cannot work (checked before any simulation runs)."""


class Interrupted(Exception):
    """Ctrl-C, with what was kept and how to go on."""


def main(argv: list[str] | None = None) -> int:
    """Run the ``shroudnet`` command with ``argv`` (default: the process's); the exit status."""
    argv = sys.argv[1:] if argv is None else list(argv)
    if argv[:1] == ["bench"]:  # its options, --help included, are the benchmark's own
        return _guarded("bench", lambda: _bench(argv[1:]))
    args = _parser().parse_args(argv)
    return _guarded(args.name, lambda: args.command(args))


def _bench(options: list[str]) -> int:
    from . import bench
    # a bad option is told now, in one line, not after minutes of benchmark
    bench.options_parser("shroudnet bench", OneLineParser).parse_args(options)
    bench.main(options)
    return 0


def _guarded(name: str, command) -> int:
    """Call ``command()``; tell any failure in one line and give its exit status."""
    try:
        return command()
    except (Interrupted, KeyboardInterrupt) as stop:
        _say(name, str(stop) or "interrupted; nothing was saved")
        return INTERRUPTED
    except MemoryError:
        _say(name, "error: not enough memory for this run; ask for fewer periods or fewer "
                   "samples_per_period in [run]")
        return BAD_INPUT
    except _INPUT_ERRORS as error:
        _say(name, f"error: {_describe(error)}")
        return BAD_INPUT
    except Exception as error:
        if isinstance(error, TypeError) and _refused(error):
            _say(name, f"error: {_describe(error)}")
            return BAD_INPUT
        if os.environ.get("SHROUDNET_TRACEBACK"):
            raise
        _say(name, f"error: unexpected {type(error).__name__}: {_describe(error)} (a fault of "
                   "shroudnet; set SHROUDNET_TRACEBACK=1 to see where)")
        return FAULT


def _refused(error: TypeError) -> bool:
    """Whether ``error`` is a check's verdict on the input: raised by a ``raise`` statement
    of shroudnet or contact_laws (a value of the wrong type, named, as DESIGN §4 asks),
    not by Python on an operation that met the wrong type, which is a fault."""
    raised = _raised_at(error)
    if raised is None:
        return False
    where, line = Path(raised[0]).resolve(), raised[1]
    return (any(where.is_relative_to(folder) for folder in _CHECKING_CODE)
            and line.startswith("raise "))


def _raised_at(error: BaseException) -> tuple[str, str] | None:
    """(file, source line) of the statement that raised ``error``; for an error raised in
    a worker process of a sweep, that statement in the worker (whose traceback comes as
    the error's cause, in words)."""
    remote = getattr(error.__cause__, "tb", None)
    if isinstance(remote, str):
        frames = re.findall(r'^  File "(.+)", line \d+, in .+\n    (.*)$', remote, re.M)
        return frames[-1] if frames else None
    frames = traceback.extract_tb(error.__traceback__)
    return (frames[-1].filename, frames[-1].line or "") if frames else None


def _say(name: str, message: str) -> None:
    print(f"shroudnet {name}: {message}", file=sys.stderr)


def _describe(error: BaseException) -> str:
    """An error's message on one line, its notes (which sweep point, ...) included."""
    if isinstance(error, OSError) and error.strerror:
        where = error.filename if error.filename is not None else ""
        text = f"{where}: {error.strerror}" if where else error.strerror
    else:
        text = str(error) or type(error).__name__
    notes = getattr(error, "__notes__", [])
    return " ".join(" ".join([text, *(f"({note})" for note in notes)]).split())


class OneLineParser(argparse.ArgumentParser):
    """argparse's parser, telling a bad option in one line, ``PROG: error: …``, with exit
    status 2, as every other bad input is told (the usage is in ``--help``)."""

    def error(self, message: str):
        self.exit(BAD_INPUT, f"{self.prog}: error: {message}\n")


def _parser() -> argparse.ArgumentParser:
    parser = OneLineParser(
        prog="shroudnet", description="Nonlinear forced vibration of shrouded blade groups "
        "that rub, impact and stick: simulate scene files, sweep their parameters, redraw "
        "saved results, benchmark.",
        epilog="Run 'shroudnet COMMAND --help' for the options of each command.")
    commands = parser.add_subparsers(metavar="COMMAND", required=True)

    run = commands.add_parser(
        "run", help="simulate a scene file: summary, results file and response figure",
        description="Simulate SCENE.toml with the settings of its [run] table. Prints the "
        "motion's classification, E_rho, the events, the energy ledger and the time taken; "
        "writes the results (.npz, loads back with shroudnet.results.load) and the response "
        "figure (.png) of the [run] blade.")
    run.add_argument("scene", type=Path, help="scene file (TOML)")
    run.add_argument("--periods", type=whole(1),
                     help="excitation periods (default: [run] periods)")
    run.add_argument("--output", "-o", type=Path, default=Path("."),
                     help="folder for SCENE.npz and SCENE.png (default: here)")
    run.add_argument("--no-figure", action="store_true", help="write the results only")
    _blade_option(run)
    _laws_option(run)
    run.set_defaults(command=_run, name="run")

    sweep_ = commands.add_parser(
        "sweep", help="sweep one number of a scene file: bifurcation data and diagram",
        description="Run the steady response of SCENE.toml for each value of one of its "
        "numbers, on every core. Each point is saved in the output folder as it finishes; "
        "run the same command again to resume an interrupted sweep. A point whose "
        "simulation fails is told (its value and why) and left out of the diagram; the "
        "others go on. Writes the diagram bifurcation.png there.")
    sweep_.add_argument("scene", type=Path, help="scene file (TOML)")
    sweep_.add_argument("--param", required=True, metavar="PATH",
                        help="the number to sweep, as a dotted path into the file: "
                        "speed_rpm, excitation.amplitudes.1, interfaces.0.normal.stiffness, "
                        "group.interface.gap, excitation.frequency (a frequency sweep at "
                        "the file's speed: give [excitation] frequency = f), ...")
    sweep_.add_argument("--values", required=True, nargs="+", metavar="VALUE",
                        help="the values: numbers, or START:STOP:COUNT for COUNT evenly "
                        "spaced ones; negative ones too (--values -1e-5:2e-5:4)")
    sweep_.add_argument("--transient", type=whole(0),
                        help="periods before recording (default: [run] transient)")
    sweep_.add_argument("--record", type=whole(3), default=100,
                        help="periods recorded per value, at least 3 (default 100)")
    sweep_.add_argument("--workers", type=whole(1),
                        help="worker processes (default: every core)")
    sweep_.add_argument("--output", "-o", type=Path,
                        help="folder for the points and the diagram "
                        "(default: SCENE-sweep-PATH, here)")
    sweep_.add_argument("--lyapunov", action="store_true",
                        help="classify each point by its largest Lyapunov exponent, and "
                        "keep it (integrates the tangent flow: about twice the time)")
    sweep_.add_argument("--retry-failed", action="store_true",
                        help="on resuming, run again the points whose simulation failed "
                        "(by default they are kept: the same code fails the same way)")
    _blade_option(sweep_)
    _laws_option(sweep_)
    _negative_numbers_are_values(sweep_)
    sweep_.set_defaults(command=_sweep, name="sweep")

    follow = commands.add_parser(
        "continue", help="follow the periodic orbits of a scene file along one of its "
        "numbers: forced-response curve with stability and bifurcations",
        description="Continue the branch of periodic orbits of SCENE.toml in one of its "
        "numbers from A to B (pseudo-arclength, through folds), with each orbit's Floquet "
        "multipliers. Prints the bifurcations met (fold, period-doubling, torus, "
        "symmetry-breaking, grazing, stick-slip; on a ring, each smooth one with the nodal "
        "diameter of its eigenvector); writes the branch (.npz, loads back with "
        "shroudnet.results.load) and its forced-response figure (.png) of the [run] blade.")
    follow.add_argument("scene", type=Path, help="scene file (TOML)")
    follow.add_argument("--param", required=True, metavar="PATH",
                        help="the number to follow, as a dotted path into the file (as for "
                        "'sweep')")
    follow.add_argument("--from", dest="start", required=True, type=float, metavar="A",
                        help="where the branch starts")
    follow.add_argument("--to", dest="stop", required=True, type=float, metavar="B",
                        help="where it ends")
    follow.add_argument("--periods", type=whole(1), default=1,
                        help="orbits of this many excitation periods (default 1)")
    follow.add_argument("--max-step", type=float, default=LARGEST_STEP, metavar="S",
                        help="the largest arclength step, as a fraction of the range and "
                        f"of the orbit's size (default {LARGEST_STEP:g}); smaller draws "
                        "more points")
    follow.add_argument("--max-points", type=whole(2), default=1000,
                        help="the most orbits (default 1000)")
    follow.add_argument("--symmetry", choices=("cyclic", "none"), default=None,
                        help="'cyclic': follow the travelling waves of a tuned ring forced "
                        "in engine order on the reduced map of one sector-passing time; "
                        "'none': shoot whole periods (default: 'cyclic' where the ring has "
                        "the symmetry)")
    follow.add_argument("--output", "-o", type=Path, default=Path("."),
                        help="folder for SCENE-continue-PATH.npz and .png (default: here)")
    _blade_option(follow)
    _laws_option(follow)
    _negative_numbers_are_values(follow)
    follow.set_defaults(command=_continue, name="continue")

    modes = commands.add_parser(
        "modes", help="the group's linear modes with its interfaces open, stuck and "
        "closed, by nodal diameter for a ring",
        description="Natural frequencies of SCENE.toml's group at its speed, with every "
        "interface open, with every interface that can stick stuck (the group at rest, "
        "its friction locked), and closed (every contact closed and stuck, normal springs "
        "included: the upper bound). For a ring of "
        "sectors (a [group] ring, or 'sectors' in the file) the table is by nodal diameter, "
        "and the frequency-nodal-diameter (ZZENF) figure SCENE-modes.png is written with "
        "the engine orders at the scene's speed.")
    modes.add_argument("scene", type=Path, help="scene file (TOML)")
    modes.add_argument("--families", type=whole(1), default=3,
                       help="mode families per nodal diameter shown (default 3)")
    modes.add_argument("--output", "-o", type=Path, default=Path("."),
                       help="folder for SCENE-modes.png (default: here)")
    _laws_option(modes)
    modes.set_defaults(command=_modes, name="modes")

    mistuning = commands.add_parser(
        "mistuning", help="Monte Carlo of the forced response over random blade frequency "
        "patterns: amplification factors",
        description="Run SCENE.toml's group, tuned and with SAMPLES random patterns of "
        "blade frequency deviations (standard deviation SPREAD), at every speed of "
        "--speeds, on every core. Prints the distribution of the amplification factor "
        "(worst blade's peak over the tuned peak) against Whitehead's bound, and writes "
        "its histogram SCENE-mistuning.png.")
    mistuning.add_argument("scene", type=Path, help="scene file (TOML)")
    mistuning.add_argument("--spread", required=True, type=float,
                           help="standard deviation of the frequency deviations, e.g. 0.01")
    mistuning.add_argument("--samples", required=True, type=whole(1),
                           help="number of random patterns")
    mistuning.add_argument("--speeds", required=True, nargs="+", metavar="RPM",
                           help="the speeds [rev/min] the peak is sought over: numbers, or "
                           "START:STOP:COUNT")
    mistuning.add_argument("--seed", type=whole(0), default=0,
                           help="of the random patterns (default 0)")
    mistuning.add_argument("--transient", type=whole(0), default=TRANSIENT,
                           help=f"periods before the peak is read (default {TRANSIENT})")
    mistuning.add_argument("--workers", type=whole(1),
                           help="worker processes (default: every core)")
    mistuning.add_argument("--output", "-o", type=Path, default=Path("."),
                           help="folder for SCENE-mistuning.png (default: here)")
    _laws_option(mistuning)
    mistuning.set_defaults(command=_mistuning, name="mistuning")

    plot = commands.add_parser(
        "plot", help="redraw a saved run (.npz), branch (.npz) or sweep (folder)",
        description="Redraw RESULTS: the response figure of a saved run, the "
        "forced-response figure of a branch, or the bifurcation diagram of a sweep folder.")
    plot.add_argument("results", type=Path,
                      help="a .npz file of 'run' or 'continue', or a folder of 'sweep'")
    plot.add_argument("--output", "-o", type=Path,
                      help="figure to write (default: beside RESULTS, .png)")
    _blade_option(plot)
    _laws_option(plot)
    plot.set_defaults(command=_plot, name="plot")

    cache = commands.add_parser(
        "cache", help="show where compiled integrators are kept and their size; --clear",
        description="Show the folder that keeps the compiled integrators (one shared by "
        "the built-in laws, and one per combination of law classes of your own) and how "
        "much room they take: $SHROUDNET_CACHE, else ~/.cache/shroudnet; a file there, "
        "or a folder that cannot be written, is refused. "
        "With --clear, delete them: the next run compiles again, once. With --warm, "
        "compile every integrator the built-in laws call for now, on every core, so that "
        "no first run waits for one.")
    action = cache.add_mutually_exclusive_group()
    action.add_argument("--clear", action="store_true", help="delete the compiled integrators")
    action.add_argument("--warm", action="store_true",
                        help="compile every built-in integrator now (minutes, once)")
    cache.add_argument("--workers", type=whole(1), default=None,
                       help="integrators compiled at once with --warm (default: every core)")
    cache.set_defaults(command=_cache, name="cache")

    bench = commands.add_parser(
        "bench", help="run the benchmark (speed, effects, baseline, sweeps)",
        description="Run the benchmark; the options after 'bench' go to it "
        "(python -m shroudnet.front.bench --help lists them).", add_help=False)
    bench.add_argument("options", nargs=argparse.REMAINDER)
    return parser




def _laws_option(parser: argparse.ArgumentParser) -> None:
    parser.add_argument(
        "--laws", action="append", default=[], metavar="MODULE",
        help="allow the scene file to name contact laws of one's own from MODULE (a Python "
        "module on the path or in this folder) as 'MODULE:Class'. This imports MODULE, "
        "which RUNS ITS CODE: give only modules you trust. Without it a scene file names "
        "only the laws of contact_laws, and reading it runs no code. May be repeated.")


def _negative_numbers_are_values(parser: argparse.ArgumentParser) -> None:
    """Let ``-1e-5`` and ``-1e-5:2e-5:4`` be values, not options (argparse reads only plain
    negative numbers such as ``-1`` or ``-0.5`` so; the parser has no option that starts
    with a digit, so none is shadowed)."""
    parser._negative_number_matcher = re.compile(r"^-\.?\d")


#: A compile or a cache load shorter than this [s] is not worth a word in ``run``'s output.
COMPILE_WORTH_SAYING = 0.5


def _cache(args) -> int:
    if args.clear:
        freed = clear_cache()
        print(f"cleared  {cache_folder()} ({freed / 2**20:.1f} MiB)")
        return 0
    if args.warm:
        return _warm(args.workers)
    size, files = cache_size()
    print(f"cache    {cache_folder()}: {size / 2**20:.1f} MiB in {files} files "
          "(clear with 'shroudnet cache --clear')")
    return 0


def _warm(workers: int | None) -> int:
    """Compile every shipped flavour, printing each as it is done and the whole."""
    from .warm import FLAVOURS, warm

    checked_cache_folder()
    workers = min(workers or default_workers(), len(FLAVOURS))
    print(f"warming  {len(FLAVOURS)} integrators in {cache_folder()}, {workers} at once",
          flush=True)
    began = time.perf_counter()
    seconds = warm(FLAVOURS, workers,
                   lambda flavour, took: print(f"  {flavour.name:<42} {took:6.1f} s",
                                               flush=True))
    print(f"warmed   {len(FLAVOURS)} integrators in {time.perf_counter() - began:.0f} s "
          f"(their compiles: {sum(seconds.values()):.0f} s of processor time)")
    return 0


def _run(args) -> int:
    loaded = _load_scene(args.scene, _import_laws(args.laws))
    settings = loaded.run
    periods = settings.periods if args.periods is None else args.periods
    if periods <= settings.transient:
        raise UsageError(f"--periods must exceed the transient of {settings.transient} "
                         f"periods, got {periods}")
    settings = _reference(loaded.scene, replace(settings, periods=periods), args)
    scene = loaded.scene
    stem = args.output / args.scene.stem
    _check_folder(args.output, "--output")
    for suffix in (".npz", ".png"):
        _check_file(_beside(stem, suffix), "--output")
    _prove_writable(args.output, "--output")
    start = time.perf_counter()
    sim = simulate(scene, periods, method=settings.method,
                   samples_per_period=settings.samples_per_period,
                   event_tolerance=settings.event_tolerance)
    took = time.perf_counter() - start
    blade, skip = settings.blade, settings.transient
    kind = classify(sim, blade, skip=skip)
    ledger = sim.energy
    counts = sim.events.counts
    group = scene.group
    prescribed = f", {len(group.prescribed)} prescribed" if group.prescribed else ""
    forced = (f"f_e = {1.0 / scene.excitation_period:g} Hz"
              if any(scene.excitation.amplitudes) else
              f"no excitation (periods of {scene.excitation_period:g} s)")
    print(f"scene    {args.scene}: {_nodes(scene)}, {len(group.fixed)} fixed nodes"
          f"{prescribed}, {_interfaces(scene)}; {scene.speed_rpm:g} rpm, "
          f"{forced}")
    print(f"method   {settings.method}, {periods} periods, event tolerance "
          f"{settings.event_tolerance:g} periods")
    compiling = (f" + {sim.compile_seconds:.2f} s compiling the integrator, once"
                 if sim.compile_seconds >= COMPILE_WORTH_SAYING else "")
    print(f"took     {took - sim.compile_seconds:.2f} s ({sim.steps:,} steps){compiling}")
    print(f"motion   {kind}")
    print(f"E_rho    {sim.energy_density(blade, skip=skip):.6e} m^2 ({_about(scene, blade)} "
          f"after {skip} periods)")
    if scene.arrays.is_structure:
        print(f"peaks    max |r| [m] of each point after {skip} periods: " + ", ".join(
            f"{node}.{point} {peak:.4g}" for node, point, peak in _point_peaks(sim, skip)))
    print(f"events   {sum(counts.values())}: "
          + ", ".join(f"{name} {count}" for name, count in counts.items()))
    print(f"energy   excitation {ledger.excitation_work:.6g} J = damping "
          f"{ledger.damping_loss:.6g} + friction {ledger.friction_loss:.6g} + contact "
          f"{ledger.contact_loss:.3g} + stored {ledger.stored_change:.3g} + residual "
          f"{ledger.residual:.2e} ({_share(ledger.residual, ledger.excitation_work)})")
    saved = [results.save_simulation(_beside(stem, ".npz"), sim, settings)]
    if not args.no_figure:
        saved.append(_save_response(sim, settings, _beside(stem, ".png")))
    print("saved    " + ", ".join(map(str, saved)))
    return 0


def _import_laws(names: list[str]) -> tuple[ModuleType, ...]:
    """Import the modules of ``--laws`` (running their code, as the option says)."""
    modules = []
    for name in names:
        if os.getcwd() not in sys.path:
            sys.path.append(os.getcwd())
        try:
            modules.append(importlib.import_module(name))
        except ImportError as error:
            raise UsageError(f"--laws {name}: cannot import it: {error}") from None
        except Exception as error:
            raise UsageError(f"--laws {name}: importing it failed: {type(error).__name__}: "
                             f"{_describe(error)}") from None
    return tuple(modules)


def _check_folder(folder: Path, option: str, requested: Path | None = None) -> None:
    """Fail now, before any work, if files cannot be written in ``folder`` (made if
    missing); the message names ``requested`` (default ``folder``), what the user gave."""
    requested = folder if requested is None else requested
    existing = folder
    while not existing.exists():  # a path under a file does not exist either
        existing = existing.parent
    if not existing.is_dir():
        raise UsageError(f"{option} {requested}: {existing} is a file, not a folder")
    if not os.access(existing, os.W_OK | os.X_OK):
        raise UsageError(f"{option} {requested}: cannot write in {existing} "
                         "(permission denied)")


def _check_file(path: Path, option: str) -> None:
    """Fail now if the file ``path`` cannot be written: a folder of that name is in the way,
    a part of its folder is a file, or its folder is not writable."""
    if path.is_dir():
        raise UsageError(f"{option} {path}: is a folder, so the file cannot be written")
    _check_folder(path.parent, option, requested=path)


def _writable_file(path: Path, option: str) -> None:
    """``_check_file``, and its folder made and proven writable (``_prove_writable``)."""
    _check_file(path, option)
    _prove_writable(path.parent, option, requested=path)


def _prove_writable(folder: Path, option: str, requested: Path | None = None) -> None:
    """Make ``folder`` (and its parents) and write and remove a file there, now, before any
    work: what the system refuses only to a write (a read-only or pseudo file system such
    as /proc, a full disc, rights that ``os.access`` does not see) fails here, not after
    the run. The message names ``requested`` (default ``folder``), what the user gave."""
    requested = folder if requested is None else requested
    try:
        folder.mkdir(parents=True, exist_ok=True)
        handle, probe = tempfile.mkstemp(prefix=".shroudnet-probe-", dir=folder)
        try:
            os.write(handle, b"shroudnet")
        finally:
            os.close(handle)
            os.unlink(probe)
    except OSError as error:
        raise UsageError(f"{option} {requested}: cannot write there "
                         f"({error.strerror or _describe(error)})") from None


def _load_scene(path: Path, laws: tuple[ModuleType, ...]):
    """``scenefile.load``, with what its reader met unnamed told as the file's."""
    with _reading(path):
        return scenefile.load(path, laws=laws)


@contextmanager
def _reading(path: Path) -> Iterator[None]:
    """Tell an error that no check named while a scene file is read or built (a number
    where a table was expected, ...) as a ``SceneFileError`` of the file: it is bad input,
    like the errors its checks name. A ``TypeError`` a check raised passes as it is."""
    try:
        yield
    except (TypeError, KeyError, IndexError, AttributeError) as error:
        if isinstance(error, TypeError) and _refused(error):
            raise
        raise scenefile.SceneFileError(
            f"{path}: not a scene file shroudnet can read ({type(error).__name__}: "
            f"{_describe(error)})") from error


def _scenes_of(path: Path, scene_at: scenefile.SceneAt, values, document: dict) -> None:
    """Build the scene at each value, before any work: a bad path or value fails now; and
    refuse a ``--param`` that does not change the scene, naming those that do."""
    param = scene_at.path
    if param.split(".")[0] == "run":
        raise UsageError(f"--param {param}: the [run] table says how the scene is run, "
                         "not what it is, so its values would all give the same scene; vary "
                         f"a number of the scene: {_scene_numbers(document)}")
    first, changes = None, False
    with _reading(path):
        for value in values:
            scene = scene_at(value)
            first = scene if first is None else first
            changes = changes or not same_scene(first, scene)
    if len(set(values)) > 1 and not changes:
        raise UsageError(f"--param {param}: the scene is the same at every value, so the "
                         "value would change nothing; vary a number of the scene: "
                         f"{_scene_numbers(document)}")


#: The most paths ``_scene_numbers`` lists.
LISTED_NUMBERS = 24


def _scene_numbers(document: dict) -> str:
    """The dotted paths of a scene file's numbers outside [run], a list's index shown as
    N: what ``--param`` may vary."""
    found: dict[str, None] = {}

    def walk(node, path):
        if isinstance(node, dict):
            for key, item in node.items():
                if path or key != "run":
                    walk(item, [*path, str(key)])
        elif isinstance(node, list):
            for item in node:
                walk(item, [*path, "N"])
        elif isinstance(node, int | float) and not isinstance(node, bool):
            found[".".join(path)] = None

    walk(document, [])
    listed = list(found)
    more = f", … ({len(listed) - LISTED_NUMBERS} more)" if len(listed) > LISTED_NUMBERS else ""
    return ", ".join(listed[:LISTED_NUMBERS]) + more + " (N: an index from 0)"


def _share(part: float, whole: float) -> str:
    return f"{abs(part) / abs(whole):.1e} of the excitation work" if whole else "no excitation"


def _interfaces(scene) -> str:
    """"n interfaces", and their contacts where patches make more."""
    interfaces, contacts = len(scene.group.interfaces), len(scene.contacts)
    return f"{interfaces} interfaces" + (f" ({contacts} contacts)" if contacts > interfaces
                                         else "")


def _beside(stem: Path, suffix: str) -> Path:
    """``stem`` with ``suffix`` added: a stem may hold dots (``…-continue-interfaces.0.gap``),
    which ``with_suffix`` would cut."""
    return stem.with_name(stem.name + suffix)


def _nodes(scene) -> str:
    """The moving nodes of a scene in words: its blades, or how many of its nodes are
    substructures and how many coordinates they have."""
    group = scene.group
    if not scene.arrays.is_structure:
        return f"{len(group.blades)} blades"
    structures = sum(isinstance(group.blade(name), Substructure) for name in group.blades)
    return (f"{len(group.blades)} nodes ({structures} substructures, "
            f"{scene.arrays.n_blades} coordinates)")


def _about(scene, target) -> str:
    """What a summary or a figure is about, by name: a blade's name (a position given
    for it is named), or with substructures the component of a point it reads,
    ``node.point[k]``."""
    position = scene.response_position(target)
    if not scene.arrays.is_structure:
        return str(scene.blades[position])
    node, point, component = scene.responses[position]
    return f"{node}.{point}[{component}]"


def _blade_option(command) -> None:
    command.add_argument("--blade", metavar="NAME", type=_blade_name,
                         help="the blade to report and draw, by name (with substructures "
                         "NODE, or a point's component NODE.POINT[K]); default: [run] "
                         "blade")


def _blade_name(text: str):
    """A ``--blade`` value: a name, or ``node.point[k]`` as (node, point, k)."""
    match = re.fullmatch(r"(.+)\.([^.\[\]]+)\[(\d+)\]", text)
    return (match[1], match[2], int(match[3])) if match else text


def _reference(scene, settings, args):
    """The run settings with the blade to report: ``--blade`` if given, else the [run]
    blade, checked against the scene (a UsageError naming --blade if unknown)."""
    blade = settings.blade if getattr(args, "blade", None) is None else args.blade
    try:
        scene.response_position(blade)
    except ValueError as error:
        raise UsageError(f"--blade: {error}") from None
    return replace(settings, blade=blade)


def _point_peaks(sim, skip: int) -> list[tuple]:
    """(node, point, max |r| [m]) of every point of every moving node after ``skip``
    periods (a ``Blade``'s one point is its x)."""
    scene = sim.scene
    x = sim.x[steady_rows(sim, skip, "peaks")]
    found = []
    for node in scene.blades:
        body = scene.group.blade(node)
        for point in body.points if isinstance(body, Substructure) else [BLADE_POINT]:
            r = x @ scene.point_rows(node, point).T
            found.append((node, point, float(np.linalg.norm(r, axis=1).max())))
    return found


def _save_response(sim, settings, path: Path) -> Path:
    from .figures import response_panel, save_figure  # matplotlib only when one is drawn
    figure = response_panel(sim, settings.blade, skip=settings.transient,
                            title=f"{path.stem}: {_about(sim.scene, settings.blade)}")
    return save_figure(figure, path)


def _sweep(args) -> int:
    laws = _import_laws(args.laws)
    loaded = _load_scene(args.scene, laws)
    values = _values(args.values)
    scene_at = scenefile.SceneAt(loaded.document, args.param, laws=laws)
    _scenes_of(args.scene, scene_at, values, loaded.document)
    settings = _reference(loaded.scene, loaded.run, args)
    position = loaded.scene.response_position(settings.blade)
    blade = loaded.scene.responses[position] if loaded.scene.arrays.is_structure \
        else loaded.scene.blades[position]  # kept by its name, (node, point, component)
    transient = settings.transient if args.transient is None else args.transient
    folder = args.output or Path(f"{args.scene.stem}-sweep-{args.param}")
    _check_folder(folder, "--output")
    _check_file(folder / "bifurcation.png", "--output")
    _prove_writable(folder, "--output")
    start = time.perf_counter()
    try:
        result = sweep(scene_at, values, parameter=args.param, blade=blade,
                       transient=transient, record=args.record, method=settings.method,
                       workers=args.workers, store=results.open_sweep_store(folder),
                       progress=_sweep_progress(), retry_failed=args.retry_failed,
                       lyapunov=args.lyapunov)
    except KeyboardInterrupt:
        raise Interrupted(_kept(folder, len(values))) from None
    took = time.perf_counter() - start
    labels, counts = np.unique(result.labels, return_counts=True)
    print(f"swept    {args.param} over {len(values)} values from {values[0]:g} to "
          f"{values[-1]:g} in {took:.1f} s")
    print("motions  " + ", ".join(f"{label} ×{count}" for label, count in zip(labels, counts)))
    exponents = [(p.value, p.classification.lyapunov) for p in result.points
                 if not p.failed and np.isfinite(p.classification.lyapunov)]
    if exponents:
        low, high = min(exponents, key=lambda e: e[1]), max(exponents, key=lambda e: e[1])
        print(f"λ_max    from {low[1]:+.3g} ({args.param} = {low[0]:g}) to {high[1]:+.3g} "
              f"({args.param} = {high[0]:g}) per period, over the {len(exponents)} points "
              "that do not repeat")
    failures = result.failures
    if failures:
        print(f"failed   {len(failures)} of {len(values)} points, left out of the diagram: "
              + ", ".join(f"{args.param} = {failure.value:g}" for failure in failures))
        print("         (why: above, and in each point's file; run again with "
              "--retry-failed after changing what made them fail)")
    if len(failures) == len(values):
        raise UsageError(f"every point failed, so there is no diagram; the first: "
                         f"{failures[0]}")
    figure = _save_diagram(result, folder / "bifurcation.png")
    print(f"saved    {folder}/ (one file per point), {figure}")
    return 0


class _Notices(ProgressReporter):
    """Tells a sweep's notices (a failed point and why, a damaged file computed again) on
    standard error, one line each, and nothing of its progress."""

    def notice(self, message: str) -> None:
        _say("sweep", message)


def _sweep_progress() -> ProgressReporter:
    """The terminal's progress line, with notices above it; on a pipe, the notices only."""
    return TerminalProgress("sweep") if sys.stderr.isatty() else _Notices()


def _kept(folder: Path, total: int) -> str:
    """What Ctrl-C left of a sweep, and how to finish it."""
    saved = len(list(folder.glob("points/*.npz")))
    return (f"interrupted; the {saved} of {total} points saved in {folder}/ are kept: run "
            "the same command again to compute only the missing ones")


def _values(tokens: list[str], option: str = "--values") -> list[float]:
    """The numbers of ``option``: each token a number or START:STOP:COUNT."""
    values = []
    for token in tokens:
        values.extend(_range(token, option) if ":" in token
                      else [_number(token, token, option)])
    if not values:
        raise UsageError(f"{option}: give at least one value")
    return values


def _range(token: str, option: str) -> list[float]:
    """COUNT evenly spaced values from START to STOP, both included."""
    parts = token.split(":")
    if len(parts) != 3:
        raise UsageError(f"{option}: {token!r} is neither a number nor START:STOP:COUNT")
    start, stop = (_number(part, token, option) for part in parts[:2])
    try:
        count = int(parts[2])
    except ValueError:
        count = 0
    if count < 1:
        raise UsageError(f"{option}: in {token!r}, COUNT must be a whole number >= 1, got "
                         f"{parts[2]!r}")
    return np.linspace(start, stop, count).tolist()


def _number(text: str, token: str, option: str) -> float:
    try:
        value = float(text)
    except ValueError:
        raise UsageError(f"{option}: {token!r} is neither a number nor "
                         "START:STOP:COUNT") from None
    if not np.isfinite(value):
        raise UsageError(f"{option}: every value must be finite, got {text!r} in {token!r}")
    return value


def _save_diagram(result, path: Path) -> Path:
    from .figures import bifurcation_diagram, save_figure
    target = result.blade
    about = f"{target[0]}.{target[1]}[{target[2]}]" if isinstance(target, tuple) \
        else f"blade {target}"  # a point's component, as ``_sweep`` names it
    return save_figure(bifurcation_diagram(result, title=f"{result.parameter}: {about}"), path)


def _continue(args) -> int:
    laws = _import_laws(args.laws)
    loaded = _load_scene(args.scene, laws)
    scene_at = scenefile.SceneAt(loaded.document, args.param, laws=laws)
    for value in (args.start, args.stop):
        if not np.isfinite(value):
            raise UsageError(f"--from and --to must be finite, got {value}")
    _scenes_of(args.scene, scene_at, [args.start, args.stop], loaded.document)
    _check_folder(args.output, "--output")
    stem = args.output / f"{args.scene.stem}-continue-{args.param}"
    for suffix in (".npz", ".png"):
        _check_file(_beside(stem, suffix), "--output")
    _prove_writable(args.output, "--output")
    blade = _reference(loaded.scene, loaded.run, args).blade
    start = time.perf_counter()
    try:
        branch = continuation(scene_at, args.start, args.stop, periods=args.periods,
                              max_step=args.max_step, max_points=args.max_points,
                              parameter=args.param, progress=_branch_progress(args.param),
                              symmetry=args.symmetry)
    except KeyboardInterrupt:
        raise Interrupted("interrupted; nothing was saved") from None
    finally:
        if sys.stderr.isatty():
            print(file=sys.stderr)
    took = time.perf_counter() - start
    amplitude = branch.amplitude(blade)
    top = int(np.argmax(amplitude))
    about = _about(branch.orbits[0].scene, blade)
    peak = branch.peak[top, branch.orbits[0].scene.response_position(blade)]
    print(f"followed {args.param} from {args.start:g} to {branch.parameter[-1]:g}: "
          f"{len(branch)} orbits of period {branch.periods}, {int(branch.stable.sum())} "
          f"stable, in {took:.1f} s ({branch.ended})")
    print(f"peak     amplitude (half peak-to-peak) of {about} = {amplitude[top]:.4g} m "
          f"at {args.param} = {branch.parameter[top]:.6g} (max |x| {peak:.4g} m)")
    for b in branch.bifurcations:
        critical = (f", multiplier {b.multiplier.real:+.6f}{b.multiplier.imag:+.6f}j"
                    + _diameter(b) if np.isfinite(b.multiplier) else "")
        print(f"{b.kind:17s}at {args.param} = {b.parameter:.8g}{critical}")
    saved = results.save_branch(_beside(stem, ".npz"), branch, scene_at)
    figure = _save_branch_figure(branch, blade, _beside(stem, ".png"))
    print(f"saved    {saved}, {figure}")
    return 0


def _diameter(bifurcation) -> str:
    """", along ND k" for a bifurcation of a ring (the diameter of its eigenvector), else
    nothing."""
    if bifurcation.orbit.scene.group.graph.graph.get("sectors") is None:
        return ""
    return f", along ND {bifurcation.wave_number}"


#: The limits of the interfaces ``shroudnet modes`` tabulates side by side
#: (``linear_modes``): open and closed bound the group's frequencies; stuck is the group at
#: rest with its friction locked (a gap design's open interfaces stay open).
TABULATED = ("open", "stuck", "closed")


def _limits(scene) -> dict:
    """``linear_modes`` of ``scene`` in each of ``TABULATED``'s limits it has: a stuck or
    closed limit is left out, with a line saying why, where nothing moves in it or an
    interface's law has no linear closed limit."""
    found = {"open": linear_modes(scene, "open")}
    for contacts in TABULATED[1:]:
        try:
            found[contacts] = linear_modes(scene, contacts)
        except ValueError as error:
            print(f"{contacts} limit left out: {error}")
    return found


def _modes(args) -> int:
    from .figures import save_figure, zzenf_diagram
    loaded = _load_scene(args.scene, _import_laws(args.laws))
    scene = loaded.scene
    _check_folder(args.output, "--output")
    path = args.output / f"{args.scene.stem}-modes.png"
    _check_file(path, "--output")
    _prove_writable(args.output, "--output")
    both = _limits(scene)
    if both["open"].sectors is None:
        for contacts, found in both.items():
            listed = ", ".join(f"{f:.2f}" for f in found.frequencies)
            print(f"{contacts:7s}{len(found.frequencies)} modes [Hz]: {listed}")
        return 0
    families = args.families
    print(f"{both['open'].sectors} sectors at {scene.speed_rpm:g} rpm; the first {families} "
          f"families [Hz], interfaces {' | '.join(both)}")
    tables = {contacts: found.families()[:, :families] for contacts, found in both.items()}
    for nd in range(tables["open"].shape[0]):
        cells = ["  ".join(f"{f:9.2f}" for f in table[nd] if np.isfinite(f))
                 for table in tables.values()]
        print(f"ND {nd:3d}  " + "  |  ".join(cells))
    sectors = both["open"].sectors
    save_figure(zzenf_diagram({f"interfaces {c}": found for c, found in both.items()},
                              speed_rpm=scene.speed_rpm,
                              engine_orders=range(1, sectors // 2 + 1), families=families,
                              title=f"{args.scene.stem}: frequency against nodal diameter"),
                path)
    print(f"saved    {path}")
    return 0


def _mistuning(args) -> int:
    from .figures import mistuning_histogram, save_figure
    loaded = _load_scene(args.scene, _import_laws(args.laws))
    speeds = _values(args.speeds, "--speeds")
    _check_folder(args.output, "--output")
    path = args.output / f"{args.scene.stem}-mistuning.png"
    _check_file(path, "--output")
    _prove_writable(args.output, "--output")
    start = time.perf_counter()
    study = mistuning_study(loaded.scene, spread=args.spread, samples=args.samples,
                            speeds_rpm=speeds, seed=args.seed, transient=args.transient,
                            workers=args.workers, progress="auto")
    factors = study.amplification
    print(f"{args.samples} patterns of spread {args.spread:g} at {len(speeds)} speeds in "
          f"{time.perf_counter() - start:.1f} s; tuned peak {study.tuned_peak:.4g} m")
    print(f"amplification  median {np.median(factors):.4f}, 95th percentile "
          f"{np.percentile(factors, 95):.4f}, largest {factors.max():.4f} (pattern "
          f"{study.worst}); Whitehead's bound ½(1 + √{study.sectors}) = "
          f"{study.whitehead_bound:.4f}")
    save_figure(mistuning_histogram(study, title=f"{args.scene.stem}: mistuning"), path)
    print(f"saved    {path}")
    return 0


def _branch_progress(name: str):
    """``progress(points, p)`` on the terminal's standard error, else nothing."""
    if not sys.stderr.isatty():
        return None

    def progress(points, value):
        print(f"\rcontinue: {points} orbits, {name} = {value:.6g}   ", end="",
              file=sys.stderr, flush=True)
    return progress


def _save_branch_figure(branch, blade, path: Path) -> Path:
    from .figures import forced_response, save_figure
    return save_figure(forced_response(
        {f"period {branch.periods}": branch}, blade,
        title=f"{branch.name}: {_about(branch.orbits[0].scene, blade)}"), path)


def _plot(args) -> int:
    laws = _import_laws(args.laws)  # a saved scene names its laws as its scene file did
    if args.output is not None:  # before reading what may be a sweep of many points
        _writable_file(args.output, "--output")
    saved = _load_results(args.results, laws)
    if isinstance(saved, Branch):
        path = args.output or args.results.with_suffix(".png")
        _writable_file(path, "--output")
        settings = results.load_run_settings(args.results, laws=laws)
        blade = _reference(saved.orbits[0].scene, settings, args).blade
        _save_branch_figure(saved, blade, path)
        print(f"saved    {path}")
        return 0
    if args.results.is_dir():
        if args.blade is not None:
            raise UsageError(f"--blade: a sweep records one blade ({saved.blade!r}); sweep "
                             "again with --blade to see another")
        path = args.output or args.results / "bifurcation.png"
        _writable_file(path, "--output")
        _save_diagram(saved, path)
    else:
        path = args.output or args.results.with_suffix(".png")
        _writable_file(path, "--output")
        _save_response(saved, _reference(
            saved.scene, results.load_run_settings(args.results, laws=laws), args), path)
    print(f"saved    {path}")
    return 0


def _load_results(path: Path, laws: tuple[ModuleType, ...]):
    """``results.load``, with any failure to read told as the file's."""
    try:
        return results.load(path, laws=laws)
    except results.ResultsError:
        raise
    except (ValueError, TypeError, KeyError, AttributeError, IndexError, EOFError,
            zipfile.BadZipFile) as error:
        raise results.ResultsError(f"{path}: not a shroudnet results file or folder "
                                   f"({type(error).__name__}: {_describe(error)})") from None
