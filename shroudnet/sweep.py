"""Parameter sweeps and bifurcation diagrams: one steady response per value of a scalar.

A sweep keeps, per value, only what a diagram needs (Poincaré points, E_ρ, the
classification and the final state), never the time histories. Its points run on every core
by default, on any ``concurrent.futures.Executor``, or on a dask cluster.
"""

from __future__ import annotations

import os
import pickle
from collections.abc import Callable, Hashable, Sequence
from concurrent.futures import Executor, ProcessPoolExecutor, as_completed
from contextlib import contextmanager
from dataclasses import dataclass

import cloudpickle
import numpy as np

from .analysis import Classification, classify, friction_loss_per_cycle
from .progress import progress_callback
from .scene import Scene
from .simulate import Accuracy, Adaptive, FixedStep, simulate


@dataclass(frozen=True)
class SweepPoint:
    """The steady response at one value of the swept parameter."""

    value: float
    poincare: np.ndarray                 # (record × 2): (x [m], ẋ [m/s]) at t = k T_e
    energy_density: float                # E_ρ [m²] over the recorded periods
    friction_loss_per_cycle: float       # [J]
    classification: Classification
    final_state: tuple[np.ndarray, np.ndarray]  # (x, ẋ) at the end, to continue from


@dataclass(frozen=True)
class Sweep:
    """A bifurcation diagram's data: the points of a sweep, in the order they were run."""

    parameter: str
    blade: Hashable | int
    points: tuple[SweepPoint, ...]
    settings: dict

    @property
    def values(self) -> np.ndarray:
        return np.array([p.value for p in self.points])

    @property
    def labels(self) -> list[str]:
        return [p.classification.label for p in self.points]

    def diagram(self, coordinate: int = 0) -> tuple[np.ndarray, np.ndarray]:
        """(parameter values, Poincaré coordinates) flattened for a scatter plot.

        ``coordinate`` 0 is the displacement, 1 the velocity.
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
                      energy_density=sim.energy_density(blade),
                      friction_loss_per_cycle=friction_loss_per_cycle(sim, skip=0),
                      classification=classify(sim, blade, skip=0, tolerance=tolerance),
                      final_state=(sim.x[-1].copy(), sim.v[-1].copy()))


def sweep(scene_at: Callable[[float], Scene], values: Sequence[float], *,
          parameter: str = "value", blade: Hashable | int = 1, transient: int = 300,
          record: int = 100, method=Adaptive(), samples_per_period: int = 50,
          continuation: bool = False, initial=None, tolerance: float = 1e-5,
          workers: int | None = None, executor=None, progress="auto",
          save_to: str | os.PathLike | None = None) -> Sweep:
    """The steady response of ``scene_at(value)`` for each value, in the order given.

    Each point runs ``transient`` periods, then records ``record`` periods of which it keeps
    the Poincaré points of ``blade``, E_ρ, the friction loss per cycle and the
    classification. Every point starts from ``initial`` (default rest) and is independent
    of the others, so the points run in parallel and the result is the same, bit for bit,
    however they are spread.

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
        machine. 1 runs the points one after the other in this process.
    executor : concurrent.futures.Executor or dask.distributed.Client, optional
        Run the points there instead (a thread pool gains nothing: the loop holds the GIL).
        A dask client runs them on its cluster (``pip install 'shroudnet[dask]'``).
    continuation : bool
        Chain the points in order: each starts from the previous point's final state (the
        first from ``initial``), so a forward and a backward sweep can land on different
        coexisting attractors. Inherently serial: not allowed with ``workers`` > 1 or an
        ``executor``.
    progress : "auto", bool, None or callable
        ``progress(done, total)`` after each point; "auto" shows points done, rate and time
        left on standard error when it is a terminal; False or None is silent.
    save_to : path of a folder, optional
        Save each point there as it finishes (``shroudnet.results``). If the folder holds
        this same sweep, interrupted, only its missing points run: none is lost or
        repeated, and the result is the same as an uninterrupted sweep's.
    """
    values = [float(v) for v in values]
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
    executor = None if executor is None else _as_executor(executor)
    if executor is None and not continuation:
        workers = min(default_workers() if workers is None else workers, len(values))
    serial = continuation or (executor is None and workers == 1)
    pickled = None if serial else _pickled(scene_at)
    report = progress_callback(progress)
    options = {"blade": blade, "transient": transient, "record": record, "method": method,
               "samples_per_period": samples_per_period, "tolerance": tolerance}
    settings = {"transient": transient, "record": record, "method": repr(method),
                "samples_per_period": samples_per_period, "continuation": continuation,
                "tolerance": tolerance, "initial": _listed(initial),
                "scenes": _source(scene_at)}
    points: list[SweepPoint | None] = [None] * len(values)
    store = None
    if save_to is not None:
        from .results import SweepStore  # results reads Sweep and SweepPoint from here
        store = SweepStore(save_to, {"parameter": parameter, "blade": blade,
                                     "values": values, "settings": settings})
        for index, point in store.finished().items():
            points[index] = point
    todo = [index for index, point in enumerate(points) if point is None]

    def finished(index, point):
        points[index] = point
        if store is not None:
            store.save(index, point)
        if report is not None:
            report(sum(p is not None for p in points), len(values))

    if report is not None:
        report(len(values) - len(todo), len(values))
    if todo and serial:
        if continuation and todo[0] > 0:
            initial = points[todo[0] - 1].final_state
        _one_by_one(scene_at, values, todo, initial, options, parameter, finished,
                    chain=continuation)
    elif todo and executor is not None:
        _spread(executor, pickled, values, todo, initial, options, parameter, finished)
    elif todo:
        with _naming(parameter, values[todo[0]]):
            _warm_kernel(scene_at(values[todo[0]]), method)
        with ProcessPoolExecutor(max_workers=min(workers, len(todo))) as pool:
            _spread(pool, pickled, values, todo, initial, options, parameter, finished)
    return Sweep(parameter=parameter, blade=blade, points=tuple(points), settings=settings)


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
    return steady_point(scene_at(value), value, initial=initial, **options)


def _remote_point(pickled_scene_at: bytes, value, initial, options) -> SweepPoint:
    """One point on a worker; ``scene_at`` comes pickled by cloudpickle, lambdas included."""
    return _point(pickle.loads(pickled_scene_at), value, initial, options)


def _one_by_one(scene_at, values, todo, initial, options, parameter, finished, chain):
    """The points ``todo`` in order, in this process; each goes to ``finished(index, point)``."""
    state = initial
    for index in todo:
        with _naming(parameter, values[index]):
            point = _point(scene_at, values[index], state, options)
        finished(index, point)
        if chain:
            state = point.final_state


def _spread(executor: Executor, pickled, values, todo, initial, options, parameter, finished):
    """The points ``todo`` on ``executor``; each goes to ``finished`` as it completes."""
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
    """Compile (or load) the kernel here once, so the workers find it in the disk cache."""
    simulate(scene, 1, method=method, samples_per_period=1)
