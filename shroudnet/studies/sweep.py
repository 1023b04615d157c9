"""Parameter sweeps and bifurcation diagrams: one steady response per value of a scalar.

A sweep keeps, per value, only what a diagram needs (Poincaré points, E_ρ, the
classification and the final state), never the time histories. Its points run on every core
by default, on any ``concurrent.futures.Executor``, or on a dask cluster.

A point whose simulation stops with a ``SimulationError`` (the Zeno guard, a collapsing
step, a non-finite state) does not stop the sweep: it is kept as a *failed point*, a gap in
the diagram, with its message (``Sweep.failures``). Every other exception is a bug or bad
input and stops the sweep.

Where the points are kept, to resume an interrupted sweep, comes from the caller as a
``store`` (``StoreOpener``; the folders of ``shroudnet.results`` are one), and so does the
progress display (``ProgressCallback``; those of ``front.progress`` draw on a terminal; the
sweep knows only the protocol of ``run.reporting``). The sweep the package offers,
``shroudnet.sweep`` (``front.studies``), builds both from ``save_to=FOLDER`` and
``progress="auto"``; the computation here imports no file or terminal code.
"""

from __future__ import annotations

import ctypes
import os
import pickle
import reprlib
import signal
import sys
import threading
import time
import warnings
from collections.abc import Callable, Hashable, Iterable, Mapping, Sequence, Set
from concurrent.futures import Executor, ProcessPoolExecutor, as_completed
from contextlib import contextmanager
from typing import Protocol

import cloudpickle
import numpy as np

from contact_laws import check_int, check_real

from ..analysis.readings import classify, friction_loss_per_cycle
from ..analysis.stability import LYAPUNOV_BLOCKS, lyapunov
from ..model.scene import Scene
from ..run.classification import REPEAT_TOLERANCE
from ..run.methods import TRANSIENT, Accuracy, Adaptive, Exponential, FixedStep
from ..run.reporting import ProgressReporter, SweepWarning
from ..run.simulate import simulate
from ..run.batch import check_batch_scene, check_device
from ..run.simulation import SimulationError, Sweep, SweepFailure, SweepPoint
from ..steady.extremes import sampled_peaks
from ..steady.parametric import checked_scene_at
from .gpu import points_on_gpu


class PointStore(Protocol):
    """Where a sweep keeps its points as they finish (``results.SweepStore`` is one)."""

    def finished(self) -> Mapping[int, SweepPoint]:
        """The points already kept (failed ones included), by index in the values."""

    def save(self, index: int, point: SweepPoint) -> None:
        """Keep the point (or failed point) of index ``index``."""


class StoreOpener(Protocol):
    """What ``sweep(store=...)`` takes: makes, or reopens, the store of the sweep that
    ``manifest`` describes (a dict of its ``parameter``, ``blade``, ``values`` and
    ``settings``, all plain JSON). ``notice(message)`` hears what the store repaired or will
    have computed again. ``shroudnet.results.open_sweep_store(folder)`` gives one."""

    def __call__(self, manifest: dict, *, notice: Callable[[str], None]) -> PointStore: ...


class ProgressCallback(Protocol):
    """What ``sweep(progress=...)`` takes: called with the points done so far out of
    ``total``, once before the first point and after each. A
    ``run.reporting.ProgressReporter`` also hears the notices (``notice(message)``)."""

    def __call__(self, done: int, total: int) -> None: ...


def steady_point(scene: Scene, value: float, *, blade: Hashable | int, transient: int,
                 record: int, method=Adaptive(), samples_per_period: int = 50,
                 initial=None, tolerance: float = REPEAT_TOLERANCE,
                 exponent: bool = False) -> SweepPoint:
    """Run ``transient`` periods unrecorded, then ``record`` periods, and reduce them
    (``classify``, with λ_max when ``exponent``)."""
    start = initial
    if transient > 0:
        run = simulate(scene, transient, method=method, samples_per_period=1, initial=initial)
        start = (run.x[-1], run.v[-1])
    sim = simulate(scene, record, method=method, samples_per_period=samples_per_period,
                   initial=start)
    return SweepPoint(value=float(value), poincare=sim.poincare(blade, skip=0),
                      energy_density=sim.energy_density(blade, skip=0),
                      friction_loss_per_cycle=friction_loss_per_cycle(sim, skip=0),
                      classification=classify(sim, blade, skip=0, tolerance=tolerance,
                                              exponent=exponent),
                      final_state=(sim.x[-1].copy(), sim.v[-1].copy()),
                      peak=sampled_peaks(sim.t, sim.x, sim.v, sim.scene.response_matrix))


def sweep(scene_at: Callable[[float], Scene], values: Sequence[float], *,
          parameter: str = "value", blade: Hashable | int = 1, transient: int = TRANSIENT,
          record: int = 100, method=Adaptive(), samples_per_period: int = 50,
          continuation: bool = False, initial=None, tolerance: float = REPEAT_TOLERANCE,
          lyapunov: bool = False, workers: int | None = None, executor=None,
          progress: ProgressCallback | None = None, store: StoreOpener | None = None,
          retry_failed: bool = False, order_by=None) -> Sweep:
    """The steady response of ``scene_at(value)`` for each value, in the order given: the
    computation behind ``shroudnet.sweep`` (``front.studies.sweep``, where every argument
    is documented), with its display and its store given as objects.

    Parameters
    ----------
    progress : ProgressCallback or None
        ``progress(done, total)`` once before the first point and after each; a
        ``run.reporting.ProgressReporter`` also hears the notices, which otherwise are
        issued as ``SweepWarning`` warnings. None (or False) reports nothing.
    store : StoreOpener or None
        Keep each point in the store that ``store(manifest, notice=...)`` opens, and resume
        from the points it holds; None keeps nothing.
    order_by : array (values × parameters), optional
        With ``executor="cuda"``, the parameters each value stands for, by which the runs
        are ordered on the GPU (``gpu.warp_order``; default the values themselves): a
        map sweeps an index into its grid, whose two parameters are what neighbours in a
        warp should share.

    The other arguments are ``shroudnet.sweep``'s.
    """
    values = checked_values(values)
    transient = check_int("sweep", "transient", transient, low=0, unit="periods")
    record = check_int("sweep", "record", record, low=3, unit="periods")
    samples_per_period = check_int("sweep", "samples_per_period", samples_per_period, low=1)
    tolerance = check_real("sweep", "tolerance", tolerance, low=0.0, low_open=True)
    workers = None if workers is None else check_int("sweep", "workers", workers, low=1)
    _check_arguments(scene_at, parameter, method, samples_per_period, workers, executor,
                     store, continuation=continuation, lyapunov=lyapunov,
                     retry_failed=retry_failed)
    on_gpu = _on_gpu_asked(executor, method, lyapunov)
    executor = None if executor is None or on_gpu else _as_executor(executor)
    report = _reporter(progress)
    first = checked_scene_at("sweep", _named(scene_at, parameter), values[0],
                             max(values, key=lambda value: abs(value - values[0])))
    _check_for(first, blade, initial)
    if on_gpu:
        check_batch_scene("sweep", first)
    blade = int(blade) if isinstance(blade, np.integer) else blade  # kept as JSON
    if executor is None and not continuation:
        workers = min(default_workers() if workers is None else workers, len(values))
    serial = continuation or (executor is None and workers == 1)
    pickled = None if serial else _pickled(scene_at)
    notice = _notifier(report)
    options = {"blade": blade, "transient": transient, "record": record, "method": method,
               "samples_per_period": samples_per_period, "tolerance": tolerance,
               "exponent": lyapunov}
    settings = {"transient": transient, "record": record, "method": repr(method),
                "samples_per_period": samples_per_period, "continuation": continuation,
                "tolerance": tolerance, **({"lyapunov": True} if lyapunov else {}),
                "initial": _listed(initial),
                "scenes": _source(scene_at), **({"executor": "cuda"} if on_gpu else {})}
    points: list[SweepPoint | None] = [None] * len(values)
    kept = None
    if store is not None:
        kept = store({"parameter": parameter, "blade": blade, "values": values,
                      "settings": settings}, notice=notice)
        _resume(points, kept.finished(), parameter, retry_failed, notice)
    todo = [index for index, point in enumerate(points) if point is None]

    def finished(index, point):
        points[index] = point
        if kept is not None:
            kept.save(index, point)
        if point.failed:
            notice(str(SweepFailure(parameter, index, point.value, point.error)))
        if report is not None:
            report(sum(p is not None for p in points), len(values))

    if report is not None:
        report(len(values) - len(todo), len(values))
    if todo and on_gpu:
        where = np.asarray(values if order_by is None else order_by, dtype=float)
        _on_gpu(scene_at, [(values[index],) for index in todo],
                [values[index] for index in todo], where.reshape(len(values), -1)[todo],
                first, todo, initial, options, workers, pickled, finished)
    elif todo and serial:
        _one_by_one(scene_at, values, todo, points, initial, options, parameter, finished,
                    chain=continuation)
    elif todo and executor is not None:
        _spread(executor, pickled, values, todo, initial, options, parameter, finished)
    elif todo:
        with _naming(parameter, values[todo[0]]):
            _warm_kernel(scene_at(values[todo[0]]), method, lyapunov)
        with _own_pool(min(workers, len(todo))) as pool:
            _spread(pool, pickled, values, todo, initial, options, parameter, finished)
    return Sweep(parameter=parameter, blade=blade, points=tuple(points), settings=settings)


def checked_values(values, owner: str = "sweep", field: str = "values") -> list[float]:
    """``values`` as a list of floats: a sequence of finite real numbers (a list, a tuple,
    a range, a 1-d array; numpy's numbers as Python's), at least one; errors name
    ``owner.field``."""
    if (isinstance(values, str | bytes | Mapping | Set) or not isinstance(values, Iterable)
            or (isinstance(values, np.ndarray) and values.ndim != 1)):
        raise TypeError(f"{owner}.{field} must be a sequence of numbers (a list, a tuple or a "
                        f"1-d array), got {type(values).__name__} {reprlib.repr(values)}")
    checked = [check_real(owner, f"{field}[{index}]", value)
               for index, value in enumerate(values)]
    if not checked:
        raise ValueError(f"{owner}.{field} must be a sequence of at least one number (a list, a "
                         f"tuple or a 1-d array), got an empty {type(values).__name__} "
                         f"{reprlib.repr(values)}")
    return checked


def _check_arguments(scene_at, parameter, method, samples_per_period, workers, executor,
                     store, **flags) -> None:
    """Raise ``ValueError``/``TypeError`` naming the first bad argument of ``sweep`` (the
    numbers are checked already; ``flags`` are those that must be True or False)."""
    if not callable(scene_at):
        raise TypeError(f"sweep.scene_at must be a callable value -> Scene, got {scene_at!r}")
    if not isinstance(parameter, str):
        raise TypeError(f"sweep.parameter must be a str (the parameter's name), got "
                        f"{type(parameter).__name__} {parameter!r}")
    for name, flag in flags.items():
        if not isinstance(flag, bool):
            raise TypeError(f"sweep.{name} must be True or False, got {flag!r}")
    if not isinstance(method, FixedStep | Adaptive | Exponential | Accuracy):
        raise TypeError("sweep.method must be FixedStep(...), Adaptive(...), Exponential(...) "
                        f"or Accuracy(...), got {method!r}")
    if isinstance(method, FixedStep | Exponential) \
            and method.steps_per_period % samples_per_period:
        raise ValueError(f"sweep.samples_per_period must divide {type(method).__name__}."
                         f"steps_per_period = {method.steps_per_period}, got "
                         f"{samples_per_period}")
    if executor is not None and not _is_cuda(executor) and workers is not None:
        raise ValueError("sweep: give workers (a pool of our own) or executor, not both")
    if flags["continuation"] and (executor is not None or (workers or 1) > 1):
        raise ValueError("sweep: continuation chains each point from the previous one and "
                         "runs serially; leave out workers and executor")
    if store is not None and not callable(store):
        raise TypeError(f"sweep.store must be a callable store(manifest, notice=...) that "
                        f"opens a store, such as results.open_sweep_store(folder); got "
                        f"{store!r}")


def _named(scene_at, parameter):
    """``scene_at``, with the value named in any error it raises."""
    def scene(value):
        with _naming(parameter, value):
            return scene_at(value)
    return scene


def _check_for(scene: Scene, blade, initial) -> None:
    """Raise naming ``blade`` or ``initial`` if ``scene`` (the first value's) has no such
    response or no state of that size: found now, not in every point."""
    try:
        scene.response_position(blade)
    except ValueError as error:
        raise ValueError(f"sweep.blade: {error}") from None
    if initial is None:
        return
    n = scene.arrays.n_blades  # coordinates, with substructures
    if isinstance(initial, str | bytes) or not isinstance(initial, Sequence | np.ndarray) \
            or len(initial) != 2:
        raise TypeError(f"sweep.initial must be None or (x0, v0), two arrays of {n} "
                        f"numbers, got {reprlib.repr(initial)}")
    for name, part in zip(("x0", "v0"), initial):
        try:
            array = np.asarray(part, dtype=float)
        except (TypeError, ValueError):
            array = None
        if array is None or array.shape != (n,) or not np.isfinite(array).all():
            raise ValueError(f"sweep.initial {name} must hold {n} finite numbers, got "
                             f"{reprlib.repr(part)}")


def _reporter(progress) -> ProgressCallback | None:
    """The callback ``progress`` is: none for False or None, else ``progress`` itself."""
    if progress is None or progress is False:
        return None
    if callable(progress):
        return progress
    raise TypeError(f"sweep.progress must be None, False or a callable progress(done, "
                    f"total) (a display such as shroudnet.sweep's progress='auto' builds), "
                    f"got {progress!r}")


def _notifier(report) -> Callable[[str], None]:
    """Where notices go: the reporter's ``notice`` if it has the interface, else warnings."""
    if isinstance(report, ProgressReporter):
        return report.notice
    return _warn


def _warn(message: str) -> None:
    warnings.warn(message, SweepWarning, stacklevel=3)


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


#: The executor that runs a sweep's points on a GPU, one thread each.
CUDA = "cuda"


def _is_cuda(executor) -> bool:
    return isinstance(executor, str) and executor == CUDA


def _on_gpu_asked(executor, method, lyapunov) -> bool:
    """Whether ``executor`` asks for the GPU; then the method must be a ``FixedStep``, no
    Lyapunov exponent is asked for and a GPU must be there (``run.batch.NoDevice`` says
    what is missing, in one line, before any work)."""
    if not _is_cuda(executor):
        if isinstance(executor, str):
            raise ValueError(f"sweep.executor must be a concurrent.futures.Executor, a "
                             f"dask.distributed.Client or 'cuda', got {executor!r}")
        return False
    if not isinstance(method, FixedStep):
        raise ValueError(f"sweep: executor='cuda' runs the fixed-step method; give "
                         f"method=FixedStep(...), not {method!r}")
    if lyapunov:
        raise ValueError("sweep: executor='cuda' classifies by the Poincaré points and the "
                         "0–1 test; λ_max (lyapunov=True) is computed on the CPU only")
    check_device("sweep")
    return True


def _on_gpu(scene_at, values, labels, coordinates, first, todo, initial, options, workers,
            pickled, finished) -> None:
    """The points ``todo`` (parameters ``values``, ``SweepPoint.value`` ``labels``,
    ordered by ``coordinates``) in one batch on the GPU, their scenes prepared and their
    points classified on ``workers`` processes where there are many; each goes to
    ``finished(index, point)``."""
    arguments = dict(first=first, response=first.response_position(options["blade"]),
                     transient=options["transient"], record=options["record"],
                     method=options["method"],
                     samples_per_period=options["samples_per_period"],
                     tolerance=options["tolerance"], initial=initial)
    if workers > 1 and len(todo) > GPU_SERIAL_POINTS:
        with _own_pool(workers) as pool:
            points = points_on_gpu(scene_at, values, labels, coordinates, pool=pool,
                                   pickled=pickled, **arguments)
    else:
        points = points_on_gpu(scene_at, values, labels, coordinates, **arguments)
    for index, point in zip(todo, points):
        finished(index, point)


#: The most points of a GPU sweep whose scenes are made in this process (more go to a
#: pool of worker processes: a scene costs about 2 ms of Python to make).
GPU_SERIAL_POINTS = 1024


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


def _warm_kernel(scene, method, tangent):
    """Compile (or load) the kernel here once, so the workers find it in the disk cache;
    and the one with the tangent flow, for ``tangent``.

    A ``SimulationError`` here is left to the point itself to report."""
    try:
        simulate(scene, 1, method=method, samples_per_period=1)
        if tangent:
            lyapunov(scene, LYAPUNOV_BLOCKS, transient=0)
    except SimulationError:
        pass
