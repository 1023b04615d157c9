"""Parameter sweeps and bifurcation diagrams: one steady response per value of a scalar.

A sweep keeps, per value, only what a diagram needs (Poincaré points, E_ρ, the
classification and the final state), never the time histories. Its points run on every core
by default, on any ``concurrent.futures.Executor``, or on a dask cluster.

A point whose simulation stops with a ``SimulationError`` (the Zeno guard, a collapsing
step, a non-finite state) does not stop the sweep: it is kept as a *failed point*, a gap in
the diagram, with its message (``Sweep.failures``). Every other exception is a bug or bad
input and stops the sweep.
"""

from __future__ import annotations

import ctypes
import math
import os
import pickle
import signal
import sys
import threading
import time
import warnings
from collections.abc import Callable, Hashable, Sequence
from concurrent.futures import Executor, ProcessPoolExecutor, as_completed
from contextlib import contextmanager
from dataclasses import dataclass

import cloudpickle
import numpy as np

from .analysis import Classification, classify, friction_loss_per_cycle
from .progress import ProgressReporter, SweepWarning, progress_callback
from .scene import Scene
from .simulate import Accuracy, Adaptive, FixedStep, simulate
from .simulation import SimulationError

#: The label of a failed point's classification.
FAILED = "failed"


@dataclass(frozen=True)
class SweepPoint:
    """The steady response at one value of the swept parameter.

    A *failed* point (``error`` set: the message of the ``SimulationError`` that stopped
    its simulation) has no Poincaré points (shape (0, 2)), NaN for E_ρ and the friction
    loss, the classification label "failed" and an empty final state.
    """

    value: float
    poincare: np.ndarray                 # (record × 2): (x [m], ẋ [m/s]) at t = k T_e
    energy_density: float                # E_ρ [m²] over the recorded periods
    friction_loss_per_cycle: float       # [J]
    classification: Classification
    final_state: tuple[np.ndarray, np.ndarray]  # (x, ẋ) at the end, to continue from
    error: str | None = None             # why the point failed; None for a computed point

    @property
    def failed(self) -> bool:
        """Whether the simulation of this point stopped with a ``SimulationError``."""
        return self.error is not None

    @classmethod
    def failure(cls, value: float, message: str, tolerance: float = math.nan) -> SweepPoint:
        """The failed point at ``value``, with the message of what stopped it."""
        nothing = np.empty(0)
        return cls(value=float(value), poincare=np.empty((0, 2)), energy_density=math.nan,
                   friction_loss_per_cycle=math.nan,
                   classification=Classification(label=FAILED, period=None, n_points=0,
                                                 tolerance=tolerance, mismatch=math.nan,
                                                 zero_one=math.nan, broadband=math.nan),
                   final_state=(nothing, nothing.copy()), error=str(message))


@dataclass(frozen=True)
class SweepFailure:
    """A point of a sweep whose simulation stopped: where, and why."""

    parameter: str
    index: int          # position of the value in the sweep's values (0-based)
    value: float
    message: str        # the ``SimulationError``'s message (time and interface)

    def __str__(self) -> str:
        return f"{self.parameter} = {self.value:g} (point {self.index}) failed: {self.message}"


@dataclass(frozen=True)
class Sweep:
    """A bifurcation diagram's data: the points of a sweep, in the order of its values.

    Failed points keep their place (``values`` lists every value); ``diagram`` leaves them
    out, and ``failures`` lists them.
    """

    parameter: str
    blade: Hashable | int
    points: tuple[SweepPoint, ...]
    settings: dict

    @property
    def values(self) -> np.ndarray:
        return np.array([p.value for p in self.points])

    @property
    def labels(self) -> list[str]:
        """Each point's classification label ("failed" for a failed point)."""
        return [p.classification.label for p in self.points]

    @property
    def failures(self) -> tuple[SweepFailure, ...]:
        """The failed points, in order, each with its index, value and message."""
        return tuple(SweepFailure(parameter=self.parameter, index=index, value=point.value,
                                  message=point.error)
                     for index, point in enumerate(self.points) if point.failed)

    def diagram(self, coordinate: int = 0) -> tuple[np.ndarray, np.ndarray]:
        """(parameter values, Poincaré coordinates) flattened for a scatter plot.

        ``coordinate`` 0 is the displacement, 1 the velocity. Failed points have no
        Poincaré points, so they leave a gap.
        """
        values = np.concatenate([np.full(len(p.poincare), p.value) for p in self.points])
        section = np.concatenate([p.poincare[:, coordinate] for p in self.points])
        return values, section


def steady_point(scene: Scene, value: float, *, blade: Hashable | int, transient: int,
                 record: int, method=Adaptive(), samples_per_period: int = 50,
                 initial=None, tolerance: float = 1e-5) -> SweepPoint:
    """Run ``transient`` periods unrecorded, then ``record`` periods, and reduce them."""
    start = initial
    if transient > 0:
        run = simulate(scene, transient, method=method, samples_per_period=1, initial=initial)
        start = (run.x[-1], run.v[-1])
    sim = simulate(scene, record, method=method, samples_per_period=samples_per_period,
                   initial=start)
    return SweepPoint(value=float(value), poincare=sim.poincare(blade, skip=0),
                      energy_density=sim.energy_density(blade, skip=0),
                      friction_loss_per_cycle=friction_loss_per_cycle(sim, skip=0),
                      classification=classify(sim, blade, skip=0, tolerance=tolerance),
                      final_state=(sim.x[-1].copy(), sim.v[-1].copy()))


def sweep(scene_at: Callable[[float], Scene], values: Sequence[float], *,
          parameter: str = "value", blade: Hashable | int = 1, transient: int = 300,
          record: int = 100, method=Adaptive(), samples_per_period: int = 50,
          continuation: bool = False, initial=None, tolerance: float = 1e-5,
          workers: int | None = None, executor=None, progress="auto",
          save_to: str | os.PathLike | None = None, retry_failed: bool = False) -> Sweep:
    """The steady response of ``scene_at(value)`` for each value, in the order given.

    Each point runs ``transient`` periods, then records ``record`` periods of which it keeps
    the Poincaré points of ``blade``, E_ρ, the friction loss per cycle and the
    classification. Every point starts from ``initial`` (default rest) and is independent
    of the others, so the points run in parallel and the result is the same, bit for bit,
    however they are spread.

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
    method : FixedStep, Adaptive or Accuracy
        As for ``simulate``; the default ``Adaptive()`` keeps each point's Poincaré points
        and E_ρ to about 1e-7 in periodic regimes.
    workers : int, optional
        Worker processes of the pool the sweep makes for itself; default every core of the
        machine. 1 runs the points one after the other in this process. The workers ignore
        Ctrl-C (this process stops them) and exit when this process dies.
    executor : concurrent.futures.Executor or dask.distributed.Client, optional
        Run the points there instead (a thread pool gains nothing: the loop holds the GIL).
        A dask client runs them on its cluster (``pip install 'shroudnet[dask]'``).
    continuation : bool
        Chain the points in order: each starts from the final state of the last point
        before it that did not fail (the first from ``initial``), so a forward and a
        backward sweep can land on different coexisting attractors. Inherently serial: not
        allowed with ``workers`` > 1 or an ``executor``.
    progress : "auto", bool, None or callable
        ``progress(done, total)`` after each point (failed points count as done); "auto"
        shows points done, rate and time left on standard error when it is a terminal;
        False or None is silent. Notices (a failed point, a saved file that is damaged and
        computed again) go to ``progress.notice(message)`` when ``progress`` is a
        ``shroudnet.progress.ProgressReporter`` (as the terminal display is), else they are
        issued as ``SweepWarning`` warnings.
    save_to : path of a folder, optional
        Save each point there as it finishes (``shroudnet.results``). If the folder holds
        this same sweep, interrupted, only its missing points run: none is lost or
        repeated, and the result is the same as an uninterrupted sweep's. A saved point
        file that cannot be read is reported and computed again. Failed points are saved
        too, and kept on resuming.
    retry_failed : bool
        On resuming from ``save_to``, run the failed points again instead of keeping them
        (worth it after changing what made them fail, e.g. the code or the machine; the
        simulation is deterministic, so the same code fails the same way).

    Raises
    ------
    ValueError, TypeError
        Bad arguments, named.
    shroudnet.results.ResultsError
        ``save_to`` holds another sweep, is a file, or its ``sweep.json`` is damaged and
        its points cannot be matched to this sweep.
    """
    values = [float(v) for v in values]
    _check_arguments(values, transient, record, method, workers, executor, continuation,
                     scene_at, retry_failed)
    executor = None if executor is None else _as_executor(executor)
    if executor is None and not continuation:
        workers = min(default_workers() if workers is None else workers, len(values))
    serial = continuation or (executor is None and workers == 1)
    pickled = None if serial else _pickled(scene_at)
    report = progress_callback(progress)
    notice = _notifier(report)
    options = {"blade": blade, "transient": transient, "record": record, "method": method,
               "samples_per_period": samples_per_period, "tolerance": tolerance}
    settings = {"transient": transient, "record": record, "method": repr(method),
                "samples_per_period": samples_per_period, "continuation": continuation,
                "tolerance": tolerance, "initial": _listed(initial),
                "scenes": _source(scene_at)}
    points: list[SweepPoint | None] = [None] * len(values)
    store = None
    if save_to is not None:
        store = _open_store(save_to, parameter, blade, values, settings, notice)
        _resume(points, store.finished(), parameter, retry_failed, notice)
    todo = [index for index, point in enumerate(points) if point is None]

    def finished(index, point):
        points[index] = point
        if store is not None:
            store.save(index, point)
        if point.failed:
            notice(str(SweepFailure(parameter, index, point.value, point.error)))
        if report is not None:
            report(sum(p is not None for p in points), len(values))

    if report is not None:
        report(len(values) - len(todo), len(values))
    if todo and serial:
        _one_by_one(scene_at, values, todo, points, initial, options, parameter, finished,
                    chain=continuation)
    elif todo and executor is not None:
        _spread(executor, pickled, values, todo, initial, options, parameter, finished)
    elif todo:
        with _naming(parameter, values[todo[0]]):
            _warm_kernel(scene_at(values[todo[0]]), method)
        with _own_pool(min(workers, len(todo))) as pool:
            _spread(pool, pickled, values, todo, initial, options, parameter, finished)
    return Sweep(parameter=parameter, blade=blade, points=tuple(points), settings=settings)


def _check_arguments(values, transient, record, method, workers, executor, continuation,
                     scene_at, retry_failed) -> None:
    """Raise ``ValueError``/``TypeError`` naming the first bad argument of ``sweep``."""
    if not values:
        raise ValueError("sweep needs at least one value")
    for name, number in (("transient", transient), ("record", record)):
        if isinstance(number, bool) or not isinstance(number, int) or number < 0:
            raise ValueError(f"sweep.{name} must be an int >= 0, got {number!r}")
    if record < 3:
        raise ValueError(f"sweep.record must be at least 3 periods, got {record}")
    if not isinstance(method, FixedStep | Adaptive | Accuracy):
        raise TypeError("sweep.method must be FixedStep(...), Adaptive(...) or Accuracy(...), "
                        f"got {method!r}")
    if workers is not None and (isinstance(workers, bool) or not isinstance(workers, int)
                                or workers < 1):
        raise ValueError(f"sweep.workers must be an int >= 1 or None (every core), "
                         f"got {workers!r}")
    if executor is not None and workers is not None:
        raise ValueError("sweep: give workers (a pool of our own) or executor, not both")
    if continuation and (executor is not None or (workers or 1) > 1):
        raise ValueError("sweep: continuation chains each point from the previous one and "
                         "runs serially; leave out workers and executor")
    if not callable(scene_at):
        raise TypeError(f"sweep.scene_at must be a callable value -> Scene, got {scene_at!r}")
    if not isinstance(retry_failed, bool):
        raise TypeError(f"sweep.retry_failed must be True or False, got {retry_failed!r}")


def _notifier(report) -> Callable[[str], None]:
    """Where notices go: the reporter's ``notice`` if it has the interface, else warnings."""
    if isinstance(report, ProgressReporter):
        return report.notice
    return _warn


def _warn(message: str) -> None:
    warnings.warn(message, SweepWarning, stacklevel=3)


def _open_store(save_to, parameter, blade, values, settings, notice):
    """The sweep's folder (``results.SweepStore``), made or reopened."""
    from .results import SweepStore  # results reads Sweep and SweepPoint from here
    return SweepStore(save_to, {"parameter": parameter, "blade": blade, "values": values,
                                "settings": settings}, notice=notice)


def _resume(points: list, saved: dict, parameter: str, retry_failed: bool, notice) -> None:
    """Put the saved points in place; failed ones only unless ``retry_failed``."""
    kept = []
    for index, point in saved.items():
        if point.failed and retry_failed:
            continue
        points[index] = point
        if point.failed:
            kept.append(f"{point.value:g}")
    if kept:
        notice(f"kept {len(kept)} failed point(s) of the saved sweep ({parameter} = "
               f"{', '.join(kept)}); pass retry_failed=True to run them again")


def _listed(initial):
    """``initial`` as plain lists (for the settings and a saved sweep's manifest)."""
    return None if initial is None else [np.asarray(part, dtype=float).tolist()
                                         for part in initial]


def _source(scene_at) -> dict:
    """What the scenes of a sweep came from: a scene file's document and the swept path
    when ``scene_at`` is a ``scenefile.SceneAt``, else the callable's name."""
    if hasattr(scene_at, "document") and hasattr(scene_at, "path"):
        return {"document": scene_at.document, "path": scene_at.path}
    return {"callable": getattr(scene_at, "__qualname__", type(scene_at).__name__)}


def default_workers() -> int:
    """The cores this process may run on."""
    if hasattr(os, "process_cpu_count"):  # Python ≥ 3.13
        return os.process_cpu_count() or 1
    if hasattr(os, "sched_getaffinity"):
        return len(os.sched_getaffinity(0))
    return os.cpu_count() or 1


def _point(scene_at, value, initial, options) -> SweepPoint:
    """One point; a ``SimulationError`` makes it a failed point, anything else is raised."""
    scene = scene_at(value)
    try:
        return steady_point(scene, value, initial=initial, **options)
    except SimulationError as error:
        return SweepPoint.failure(value, str(error), tolerance=options["tolerance"])


def _remote_point(pickled_scene_at: bytes, value, initial, options) -> SweepPoint:
    """One point on a worker; ``scene_at`` comes pickled by cloudpickle, lambdas included."""
    return _point(pickle.loads(pickled_scene_at), value, initial, options)


def _one_by_one(scene_at, values, todo, points, initial, options, parameter, finished,
                chain):
    """The points ``todo`` in order, in this process; each goes to ``finished(index, point)``.

    With ``chain``, each starts from the last point before it that did not fail.
    """
    for index in todo:
        start = _chain_start(points, index, initial) if chain else initial
        with _naming(parameter, values[index]):
            point = _point(scene_at, values[index], start, options)
        finished(index, point)


def _chain_start(points, index, initial):
    """The final state of the last point before ``index`` that did not fail, else
    ``initial``."""
    for point in reversed(points[:index]):
        if point is not None and not point.failed:
            return point.final_state
    return initial


def _spread(executor: Executor, pickled, values, todo, initial, options, parameter, finished):
    """The points ``todo`` on ``executor``; each goes to ``finished`` as it completes.

    Whatever stops this early (an error, Ctrl-C) cancels the points not yet started.
    """
    futures = {executor.submit(_remote_point, pickled, values[index], initial, options): index
               for index in todo}
    try:
        for future in as_completed(futures):
            index = futures[future]
            with _naming(parameter, values[index]):
                point = future.result()
            finished(index, point)
    finally:
        for future in futures:
            future.cancel()


@contextmanager
def _own_pool(workers: int):
    """A process pool whose workers ignore Ctrl-C and exit with this process.

    If the body stops early (an error, ``KeyboardInterrupt``), the workers are stopped at
    once rather than left to finish the points they are running.
    """
    pool = ProcessPoolExecutor(max_workers=workers, initializer=_worker_started,
                               initargs=(os.getpid(),))
    try:
        yield pool
    except BaseException:
        _stop_workers(pool)
        raise
    pool.shutdown(wait=True)


def _stop_workers(pool: ProcessPoolExecutor) -> None:
    """Terminate the pool's worker processes and shut it down without waiting for points.

    ``ProcessPoolExecutor`` has no public way to stop a running task; its ``_processes``
    (pid → Process) is the one handle on the workers.
    """
    for process in list((getattr(pool, "_processes", None) or {}).values()):
        process.terminate()
    pool.shutdown(wait=True, cancel_futures=True)


#: Seconds between two looks of a worker at whether its parent still lives.
PARENT_POLL_INTERVAL = 0.5

_PR_SET_PDEATHSIG = 1  # from <linux/prctl.h>


def _worker_started(owner: int) -> None:
    """Initializer of the sweep's worker processes.

    Ctrl-C goes to the whole process group of a terminal: the workers ignore it and the
    sweep's process stops them. A worker must also not outlive that process when it is
    killed (SIGKILL leaves it no chance to stop them): on Linux the kernel sends the worker
    SIGKILL when its parent dies (prctl PR_SET_PDEATHSIG), which works even while the
    compiled loop holds the GIL; everywhere, a daemon thread exits the worker when its
    parent changes (checked between the loop's runs, since that thread needs the GIL).
    ``owner`` is the pid of the sweep's process, for the case where it died before this
    ran.
    """
    signal.signal(signal.SIGINT, signal.SIG_IGN)
    parent = os.getppid()
    if sys.platform.startswith("linux"):
        _ask_kernel_for_death_signal()
    if parent != owner and not _alive(owner):
        os._exit(1)
    threading.Thread(target=_exit_with_parent, args=(parent,), daemon=True,
                     name="shroudnet-parent-watch").start()


def _ask_kernel_for_death_signal() -> None:
    try:
        libc = ctypes.CDLL(None, use_errno=True)
        libc.prctl(_PR_SET_PDEATHSIG, int(signal.SIGKILL), 0, 0, 0)
    except (OSError, AttributeError):  # no prctl here: the watching thread still works
        pass


def _alive(pid: int) -> bool:
    try:
        os.kill(pid, 0)  # signal 0: only asks whether the process exists
    except ProcessLookupError:
        return False
    except PermissionError:  # it exists, under another user
        pass
    return True


def _exit_with_parent(parent: int) -> None:
    """Exit this process as soon as its parent is no longer ``parent``."""
    while os.getppid() == parent:
        time.sleep(PARENT_POLL_INTERVAL)
    os._exit(1)


@contextmanager
def _naming(parameter, value):
    """Add the sweep point to the message of an error raised while computing it."""
    try:
        yield
    except Exception as error:
        error.add_note(f"in the sweep point {parameter} = {value:g}")
        raise


def _as_executor(executor) -> Executor:
    if isinstance(executor, Executor):
        return executor
    if hasattr(executor, "get_executor"):  # a dask.distributed.Client
        return executor.get_executor()
    raise TypeError(f"sweep.executor must be a concurrent.futures.Executor or a "
                    f"dask.distributed.Client, got {executor!r}")


def _pickled(scene_at) -> bytes:
    try:
        return cloudpickle.dumps(scene_at)
    except Exception as error:
        raise TypeError(f"sweep: scene_at ({scene_at!r}) cannot be sent to worker processes: "
                        f"{error}. Pass workers=1 to run the sweep in this process.") from None


def _warm_kernel(scene, method):
    """Compile (or load) the kernel here once, so the workers find it in the disk cache.

    A ``SimulationError`` in this one period is left to the point itself to report."""
    try:
        simulate(scene, 1, method=method, samples_per_period=1)
    except SimulationError:
        pass
