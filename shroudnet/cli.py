"""The ``shroudnet`` command: run a scene file, sweep one of its numbers, redraw, benchmark.

    shroudnet run SCENE.toml                       simulate; summary, results and figure
    shroudnet sweep SCENE.toml --param PATH --values ...   a bifurcation diagram
    shroudnet plot RESULTS                         redraw a saved run or sweep
    shroudnet bench [--quick]                      the benchmark

``shroudnet COMMAND --help`` explains each. Scene files are described in
``shroudnet.scenefile``; examples are in ``examples/scenes/``.
"""

from __future__ import annotations

import argparse
import sys
import time
from dataclasses import replace
from pathlib import Path

import numpy as np

from . import results, scenefile
from .analysis import classify
from .simulate import simulate
from .simulation import SimulationError
from .sweep import sweep


def main(argv: list[str] | None = None) -> int:
    argv = sys.argv[1:] if argv is None else list(argv)
    if argv[:1] == ["bench"]:  # its options, --help included, are the benchmark's own
        from .bench import main as bench_main
        bench_main(argv[1:])
        return 0
    args = _parser().parse_args(argv)
    try:
        return args.command(args)
    except (scenefile.SceneFileError, results.ResultsError, SimulationError) as error:
        print(f"shroudnet {args.name}: error: {error}", file=sys.stderr)
        return 2


def _parser() -> argparse.ArgumentParser:
    parser = argparse.ArgumentParser(
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
    run.add_argument("--periods", type=int, help="excitation periods (default: [run] periods)")
    run.add_argument("--output", "-o", type=Path, default=Path("."),
                     help="folder for SCENE.npz and SCENE.png (default: here)")
    run.add_argument("--no-figure", action="store_true", help="write the results only")
    run.set_defaults(command=_run, name="run")

    sweep_ = commands.add_parser(
        "sweep", help="sweep one number of a scene file: bifurcation data and diagram",
        description="Run the steady response of SCENE.toml for each value of one of its "
        "numbers, on every core. Each point is saved in the output folder as it finishes; "
        "run the same command again to resume an interrupted sweep. Writes the diagram "
        "bifurcation.png there.")
    sweep_.add_argument("scene", type=Path, help="scene file (TOML)")
    sweep_.add_argument("--param", required=True, metavar="PATH",
                        help="the number to sweep, as a dotted path into the file: "
                        "speed_rpm, excitation.amplitudes.1, interfaces.0.normal.stiffness, "
                        "group.interface.gap, ...")
    sweep_.add_argument("--values", required=True, nargs="+", metavar="VALUE",
                        help="the values: numbers, or START:STOP:COUNT for COUNT evenly "
                        "spaced ones")
    sweep_.add_argument("--transient", type=int,
                        help="periods before recording (default: [run] transient)")
    sweep_.add_argument("--record", type=int, default=100,
                        help="periods recorded per value (default 100)")
    sweep_.add_argument("--workers", type=int, help="worker processes (default: every core)")
    sweep_.add_argument("--output", "-o", type=Path,
                        help="folder for the points and the diagram "
                        "(default: SCENE-sweep-PATH, here)")
    sweep_.set_defaults(command=_sweep, name="sweep")

    plot = commands.add_parser(
        "plot", help="redraw a saved run (.npz) or sweep (folder)",
        description="Redraw RESULTS: the response figure of a saved run, or the bifurcation "
        "diagram of a sweep folder.")
    plot.add_argument("results", type=Path, help="a .npz file of 'run' or a folder of 'sweep'")
    plot.add_argument("--output", "-o", type=Path,
                      help="figure to write (default: beside RESULTS, .png)")
    plot.set_defaults(command=_plot, name="plot")

    bench = commands.add_parser(
        "bench", help="run the benchmark (speed, specialisation, baseline, sweeps)",
        description="Run the benchmark; the options after 'bench' go to it "
        "(python -m shroudnet.bench --help lists them).", add_help=False)
    bench.add_argument("options", nargs=argparse.REMAINDER)
    return parser


def _run(args) -> int:
    loaded = scenefile.load(args.scene)
    settings = loaded.run
    periods = settings.periods if args.periods is None else args.periods
    if periods <= settings.transient:
        raise scenefile.SceneFileError(f"--periods must exceed the transient of "
                                       f"{settings.transient} periods, got {periods}")
    settings = replace(settings, periods=periods)
    scene = loaded.scene
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
    print(f"scene    {args.scene}: {len(group.blades)} blades, {len(group.fixed)} fixed nodes, "
          f"{len(group.interfaces)} interfaces; {scene.speed_rpm:g} rpm, "
          f"f_e = {1.0 / scene.excitation_period:g} Hz")
    print(f"method   {settings.method}, {periods} periods, event tolerance "
          f"{settings.event_tolerance:g} periods")
    print(f"took     {took:.2f} s ({sim.steps:,} steps)")
    print(f"motion   {kind}")
    print(f"E_rho    {sim.energy_density(blade, skip=skip):.6e} m^2 ({blade!r} after "
          f"{skip} periods)")
    print(f"events   {sum(counts.values())}: "
          + ", ".join(f"{name} {count}" for name, count in counts.items()))
    print(f"energy   excitation {ledger.excitation_work:.6g} J = damping "
          f"{ledger.damping_loss:.6g} + friction {ledger.friction_loss:.6g} + contact "
          f"{ledger.contact_loss:.3g} + stored {ledger.stored_change:.3g} + residual "
          f"{ledger.residual:.2e} ({_share(ledger.residual, ledger.excitation_work)})")
    stem = args.output / args.scene.stem
    saved = [results.save_simulation(stem.with_suffix(".npz"), sim, settings)]
    if not args.no_figure:
        saved.append(_save_response(sim, settings, stem.with_suffix(".png")))
    print("saved    " + ", ".join(map(str, saved)))
    return 0


def _share(part: float, whole: float) -> str:
    return f"{abs(part) / abs(whole):.1e} of the excitation work" if whole else "no excitation"


def _save_response(sim, settings, path: Path) -> Path:
    from .figures import response_panel  # matplotlib only when a figure is drawn
    figure = response_panel(sim, settings.blade, skip=settings.transient,
                            title=f"{path.stem}: {settings.blade}")
    path.parent.mkdir(parents=True, exist_ok=True)
    figure.savefig(path, dpi=110)
    return path


def _sweep(args) -> int:
    loaded = scenefile.load(args.scene)
    values = _values(args.values)
    scene_at = scenefile.SceneAt(loaded.document, args.param)
    for value in (values[0], values[-1]):  # a bad path or value fails before any work
        scene_at(value)
    settings = loaded.run
    transient = settings.transient if args.transient is None else args.transient
    folder = args.output or Path(f"{args.scene.stem}-sweep-{args.param}")
    start = time.perf_counter()
    result = sweep(scene_at, values, parameter=args.param, blade=settings.blade,
                   transient=transient, record=args.record, method=settings.method,
                   workers=args.workers, save_to=folder)
    took = time.perf_counter() - start
    labels, counts = np.unique(result.labels, return_counts=True)
    print(f"swept    {args.param} over {len(values)} values from {values[0]:g} to "
          f"{values[-1]:g} in {took:.1f} s")
    print("motions  " + ", ".join(f"{label} ×{count}" for label, count in zip(labels, counts)))
    figure = _save_diagram(result, folder / "bifurcation.png")
    print(f"saved    {folder}/ (one file per point), {figure}")
    return 0


def _values(tokens: list[str]) -> list[float]:
    values = []
    for token in tokens:
        try:
            if ":" in token:
                start, stop, count = token.split(":")
                values.extend(np.linspace(float(start), float(stop), int(count)).tolist())
            else:
                values.append(float(token))
        except ValueError:
            raise scenefile.SceneFileError(f"--values: {token!r} is neither a number nor "
                                           "START:STOP:COUNT") from None
    if not values:
        raise scenefile.SceneFileError("--values: give at least one value")
    return values


def _save_diagram(result, path: Path) -> Path:
    from .figures import bifurcation_diagram
    bifurcation_diagram(result, title=f"{result.parameter}: blade {result.blade}"
                        ).savefig(path, dpi=110)
    return path


def _plot(args) -> int:
    saved = results.load(args.results)
    if args.results.is_dir():
        path = args.output or args.results / "bifurcation.png"
        _save_diagram(saved, path)
    else:
        path = args.output or args.results.with_suffix(".png")
        _save_response(saved, results.load_run_settings(args.results), path)
    print(f"saved    {path}")
    return 0
