"""The studies as the package offers them: a sweep and a mistuning study that show their
progress on the terminal and keep their points in a folder when asked.

The computations (``studies.sweep``, ``studies.mistuning``) take a progress callback and a
store as objects, and never print or touch a file; these build the display from
``progress="auto"`` (or True) and the store from ``save_to=FOLDER``, then run them.
"""

from __future__ import annotations

import os
from collections.abc import Callable, Hashable, Sequence

from ..model.scene import Scene
from ..run.classification import REPEAT_TOLERANCE
from ..run.methods import TRANSIENT, Adaptive
from ..run.simulation import Sweep, SweepMap
from ..studies import maps as maps_module
from ..studies import mistuning as mistuning_module
from ..studies import sweep as sweep_module
from ..studies.mistuning import MistuningStudy
from ..studies.sweep import StoreOpener


def sweep(scene_at: Callable[[float], Scene], values: Sequence[float], *,
          parameter: str = "value", blade: Hashable | int = 1, transient: int = TRANSIENT,
          record: int = 100, method=Adaptive(), samples_per_period: int = 50,
          continuation: bool = False, initial=None, tolerance: float = REPEAT_TOLERANCE,
          lyapunov: bool = False, workers: int | None = None, executor=None, progress="auto",
          save_to: str | os.PathLike | None = None, store: StoreOpener | None = None,
          retry_failed: bool = False) -> Sweep:
    """The steady response of ``scene_at(value)`` for each value, in the order given.

    Each point runs ``transient`` periods, then records ``record`` periods of which it keeps
    the Poincaré points of ``blade``, E_ρ, the friction loss per cycle and the
    classification. Every point starts from ``initial`` (default rest; (x0, v0) as
    ``simulate`` takes it: with substructures, the nodes' own degrees of freedom) and is
    independent of the others, so the points run in parallel and the result is the same,
    bit for bit, however they are spread.

    A point whose simulation stops with a ``SimulationError`` is kept as a failed point
    (``SweepPoint.failed``, listed in ``Sweep.failures``) and reported as a notice (see
    ``progress``); the sweep goes on. Any other exception stops the sweep, with a note
    naming the point. Ctrl-C (``KeyboardInterrupt``) stops the sweep's own worker
    processes at once and is raised again; the points saved so far are kept.

    Parameters
    ----------
    scene_at : callable
        value ↦ Scene; a lambda or a function defined in a notebook will do (it travels to
        the workers by cloudpickle).
    method : FixedStep, Adaptive, Exponential or Accuracy
        As for ``simulate``; the default ``Adaptive()`` keeps each point's Poincaré points
        and E_ρ to about 1e-7 in periodic regimes.
    workers : int, optional
        Worker processes of the pool the sweep makes for itself; default every core of the
        machine. 1 runs the points one after the other in this process. The workers ignore
        Ctrl-C (this process stops them) and exit when this process dies.
    executor : concurrent.futures.Executor, dask.distributed.Client or "cuda", optional
        Run the points there instead (a thread pool gains nothing: the loop holds the GIL).
        A dask client runs them on its cluster (``pip install 'shroudnet[dask]'``).
        "cuda" runs every point at once on the GPU, one thread each, by the fixed-step
        method (``method`` a ``FixedStep``; ``pip install 'shroudnet[gpu]'``); the points
        equal the CPU's to rounding (chaos amplifies it), their classification decided
        by the repeat test and the 0–1 test (``lyapunov`` is refused), with a NaN
        broadband fraction and no peaks, since the GPU keeps no time history. ``workers``
        then make the points' scenes. Where no GPU can run it, a ``run.batch.NoDevice``
        says in one line what is missing.
    continuation : bool
        Chain the points in order: each starts from the final state of the last point
        before it that did not fail (the first from ``initial``), so a forward and a
        backward sweep can land on different coexisting attractors. Inherently serial: not
        allowed with ``workers`` > 1 or an ``executor``.
    lyapunov : bool
        Classify each point with its largest Lyapunov exponent (``classify``): kept as
        ``classification.lyapunov`` ± ``lyapunov_error``, at the cost of integrating the
        tangent flow over the recorded periods of every point that does not repeat.
        Without it the 0–1 test tells chaos from quasi-periodicity.
    progress : "auto", bool, None or callable
        ``progress(done, total)`` after each point (failed points count as done); "auto"
        shows points done, rate and time left on standard error when it is a terminal
        (True: always; the display is ``front.progress.TerminalProgress``); False or None
        is silent.
        Notices (a failed point, a saved file that is damaged and computed again) go to
        ``progress.notice(message)`` when ``progress`` is a
        ``run.reporting.ProgressReporter`` (as the terminal display is), else they are
        issued as ``SweepWarning`` warnings.
    save_to : path of a folder, optional
        Save each point there as it finishes (``shroudnet.results``). If the folder holds
        this same sweep, interrupted, only its missing points run: none is lost or
        repeated, and the result is the same as an uninterrupted sweep's. A saved point
        file that cannot be read is reported and computed again. Failed points are saved
        too, and kept on resuming. Short for ``store=results.open_sweep_store(save_to)``.
    store : StoreOpener, optional
        Keep each point in the store that ``store(manifest, notice=...)`` makes or reopens
        (a ``PointStore``), and resume from the points it already holds, as ``save_to``
        does with a folder. Give ``save_to`` or ``store``, not both.
    retry_failed : bool
        On resuming from ``save_to`` or ``store``, run the failed points again instead of
        keeping them (worth it after changing what made them fail, e.g. the code or the
        machine; the simulation is deterministic, so the same code fails the same way).

    Raises
    ------
    ValueError, TypeError
        Bad arguments, named, before any point runs: among them a ``scene_at`` that
        returns the same scene for the first value and the one farthest from it (its value
        changes nothing, as ``continuation`` refuses too), a ``blade`` or an ``initial``
        state that the first value's scene does not have.
    shroudnet.results.ResultsError
        ``save_to`` holds another sweep, is a file, or its ``sweep.json`` is damaged and
        its points cannot be matched to this sweep. A ``store`` raises its own errors.
    """
    if save_to is not None and not isinstance(save_to, str | os.PathLike):
        raise TypeError(f"sweep.save_to must be the path of a folder (str or os.PathLike), "
                        f"got {type(save_to).__name__} {save_to!r}")
    if save_to is not None and store is not None:
        raise ValueError("sweep: give save_to (a folder) or store (where to keep the "
                         "points), not both")
    if save_to is not None:
        from ..io.results import open_sweep_store

        store = open_sweep_store(save_to)
    return sweep_module.sweep(
        scene_at, values, parameter=parameter, blade=blade, transient=transient,
        record=record, method=method, samples_per_period=samples_per_period,
        continuation=continuation, initial=initial, tolerance=tolerance, lyapunov=lyapunov,
        workers=workers, executor=executor, progress=display("sweep", progress),
        store=store, retry_failed=retry_failed)


def sweep_map(scene_at: Callable[[float, float], Scene], first: Sequence[float],
              second: Sequence[float], *, parameters: tuple[str, str] = ("first", "second"),
              blade: Hashable | int = 1, transient: int = TRANSIENT, record: int = 100,
              method=Adaptive(), samples_per_period: int = 50, initial=None,
              tolerance: float = REPEAT_TOLERANCE, workers: int | None = None,
              executor=None, progress="auto") -> SweepMap:
    """The steady response of ``scene_at(a, b)`` at every a of ``first`` and b of
    ``second``: each cell a sweep point (Poincaré points of ``blade``, E_ρ, friction loss
    per cycle, classification), every cell from ``initial``. ``executor="cuda"`` runs
    every cell at once on the GPU; ``front.figures.sweep_map_figure`` draws the map
    coloured by the classification.

    Parameters
    ----------
    scene_at : callable
        (a, b) ↦ Scene.
    first, second : sequences of numbers
        The grid's values of each parameter.
    parameters : (str, str)
        The parameters' names.
    executor : None, concurrent.futures.Executor, dask client or "cuda"
        Where the cells run, as for ``sweep``; "cuda" runs them all at once on the GPU, one
        thread each, neighbouring cells in a warp (``method`` a ``FixedStep``;
        ``pip install 'shroudnet[gpu]'``).
    progress : "auto", bool, None or callable
        As for ``sweep``.

    The other arguments are ``sweep``'s, for every cell.

    Returns
    -------
    SweepMap

    Raises
    ------
    ValueError, TypeError
        A bad argument, named, before any cell runs.
    run.batch.NoDevice
        ``executor="cuda"`` where no GPU can run it, saying what is missing.
    """
    return maps_module.sweep_map(
        scene_at, first, second, parameters=parameters, blade=blade, transient=transient,
        record=record, method=method, samples_per_period=samples_per_period,
        initial=initial, tolerance=tolerance, workers=workers, executor=executor,
        progress=display("sweep_map", progress))


def mistuning_study(scene: Scene, *, spread: float, samples: int,
                    speeds_rpm: Sequence[float], blades: Sequence[Hashable] | None = None,
                    patterns=None, seed: int = 0, transient: int = TRANSIENT, record: int = 10,
                    samples_per_period: int = 100, method=Adaptive(),
                    workers: int | None = None, executor=None,
                    progress="auto") -> MistuningStudy:
    """A Monte Carlo of the forced response over random mistuning patterns.

    Every sample, and the tuned group, runs at every speed of ``speeds_rpm`` (one
    ``sweep``, on every core or on ``executor``, a dask cluster included); a point keeps
    the peak |x| of each node (of a substructure, the largest over its points' components)
    over ``record`` periods after ``transient`` ones, sampled ``samples_per_period`` times a
    period.

    Parameters
    ----------
    scene : Scene
        The tuned group; its speed is replaced by each of ``speeds_rpm``.
    spread : float
        The standard deviation of the blade frequency deviation ε, 0 ≤ spread < 0.3 [-].
    samples : int
        Number of random patterns, ≥ 1.
    speeds_rpm : sequence of float
        The speeds [rev/min] the peak is sought over: the resonance to study.
    blades : sequence of node names, optional
        The nodes that are mistuned and whose amplitudes count; default every node, or
        every node whose name starts with "blade" in a group built by
        ``BladeGroup.bladed_disc``.
    patterns : array (samples × sectors), optional
        Given deviations ε instead of random ones (then ``spread`` is only reported).
    seed : int
        Of the random generator: the same seed gives the same patterns.
    transient, record : int
        Periods run before a point is read, and periods read.
    samples_per_period : int
        Samples a period the peaks are read from.
    method : FixedStep, Adaptive, Exponential or Accuracy
        As for ``simulate``.
    workers, executor
        Where the runs go, as for ``sweep``.
    progress : "auto", bool, None or callable
        As for ``sweep``: "auto" shows runs done, rate and time left on standard error
        when it is a terminal, True always; False or None is silent; a callable
        ``progress(done, total)`` (a ``ProgressReporter`` hears the notices too).

    Returns
    -------
    MistuningStudy
    """
    return mistuning_module.mistuning_study(
        scene, spread=spread, samples=samples, speeds_rpm=speeds_rpm, blades=blades,
        patterns=patterns, seed=seed, transient=transient, record=record,
        samples_per_period=samples_per_period, method=method, workers=workers,
        executor=executor, progress=display("mistuning_study", progress))


def display(owner: str, progress):
    """The progress callback ``progress`` asks for (``front.progress.progress_callback``):
    the terminal code is imported only when a display is asked for, so that importing the
    package loads none of it."""
    if isinstance(progress, str) and progress == "auto" or progress is True:
        from .progress import progress_callback

        return progress_callback(progress)
    if progress is None or progress is False or callable(progress):
        return progress
    wrong = ValueError if isinstance(progress, str) else TypeError
    raise wrong(f"{owner}.progress must be 'auto', True, False, None or a callable "
                f"progress(done, total), got {progress!r}")
