"""The points of a sweep or a map on a GPU: every point a thread (``run.batch``).

``points_on_gpu`` turns each point's scene into numbers (on the caller's pool of worker
processes, where there are many: building a scene costs milliseconds of Python, and a map
has tens of thousands), orders the runs so that neighbours in a warp are neighbours in
parameter (``warp_order``), runs them in one batch and reads each run's steady response
into a ``SweepPoint`` as ``steady_point`` does: the Poincaré points, E_ρ and the friction
loss per cycle over the recorded periods, and the classification from the Poincaré points
(``classify_section``: a repeat of period N, else the 0–1 test). A GPU run keeps no time
history, so the classification's broadband fraction (from the spectrum) is NaN and the
points keep no peaks; the largest Lyapunov exponent is not computed there.
"""

from __future__ import annotations

import math
import pickle
from collections.abc import Callable, Sequence
from concurrent.futures import Executor

import numpy as np

from ..analysis.readings import classify_section
from ..model.scene import Scene
from ..run.batch import PreparedRun, prepare_run, run_batch
from ..run.classification import Classification
from ..run.methods import FixedStep
from ..run.simulation import SweepPoint

#: Points a worker process prepares or classifies at a time.
CHUNK = 512


def warp_order(coordinates) -> np.ndarray:
    """The order to run points in (a permutation), from their parameters ``coordinates``
    (points × d): the Morton (Z) order of the points' ranks along each parameter, so that
    every 32 points in a row, a warp, are a compact patch of the grid (8 × 4 of a
    two-parameter grid), as near each other in parameter as a block of 32 can be; along
    one parameter, its sorted order. Ties keep their given order."""
    coordinates = np.asarray(coordinates, dtype=float).reshape(len(coordinates), -1)
    ranks = np.column_stack([np.unique(column, return_inverse=True)[1].ravel()
                             for column in coordinates.T]).astype(np.uint64)
    code = np.zeros(len(ranks), dtype=np.uint64)
    bits = max(int(ranks.max(initial=0)).bit_length(), 1)
    d = ranks.shape[1]
    for bit in range(bits):
        for axis in range(d):
            code |= ((ranks[:, axis] >> np.uint64(bit)) & np.uint64(1)) \
                << np.uint64(bit * d + (d - 1 - axis))
    return np.argsort(code, kind="stable")


def _prepare_chunk(scene_at, values, options) -> list[PreparedRun]:
    """``prepare_run`` of the scenes at ``values`` (each a tuple of parameters)."""
    return [prepare_run(scene_at(*value), owner="sweep", **options) for value in values]


def _prepare_remote(pickled_scene_at: bytes, values, options) -> list[PreparedRun]:
    """``_prepare_chunk`` on a worker; ``scene_at`` comes pickled by cloudpickle."""
    return _prepare_chunk(pickle.loads(pickled_scene_at), values, options)


def _classify_chunk(poincare, extent, tolerance) -> list[Classification | None]:
    """The classification of each run's Poincaré points (None where the run failed)."""
    return [None if not np.isfinite(points).all() else
            classify_section(points, scale=scale, tolerance=tolerance, broadband=math.nan)
            for points, scale in zip(poincare, extent)]


def _chunks(items, size: int):
    return [items[start:start + size] for start in range(0, len(items), size)]


def points_on_gpu(scene_at: Callable[..., Scene], values: Sequence[tuple], labels,
                  coordinates, *, first: Scene, response: int, transient: int,
                  record: int, method: FixedStep, samples_per_period: int,
                  tolerance: float, initial=None, pool: Executor | None = None,
                  pickled: bytes | None = None) -> list[SweepPoint]:
    """The ``SweepPoint`` of each point, in the order of ``values``.

    ``scene_at(*value)`` is the scene of each value (a tuple of parameters); ``labels``
    each point's ``SweepPoint.value``; ``coordinates`` (points × parameters) what the runs
    are ordered by (``warp_order``); ``first`` one of the scenes (the kernel is compiled
    for its law classes and effects); ``response`` the position of the blade whose
    response is kept. ``pool`` prepares and classifies the points in chunks when given
    (``scene_at`` travels to it as ``pickled``, by cloudpickle), else they are prepared
    here. Raises what ``run.batch`` raises.
    """
    options = {"transient": transient, "record": record, "method": method,
               "samples_per_period": samples_per_period, "initial": initial}
    values = [tuple(value) for value in values]
    if pool is None:
        prepared = _prepare_chunk(scene_at, values, options)
    else:
        futures = [pool.submit(_prepare_remote, pickled, chunk, options)
                   for chunk in _chunks(values, CHUNK)]
        prepared = [run for future in futures for run in future.result()]
    for value, run in zip(labels, prepared):
        if run.kernel != prepared[0].kernel:
            raise ValueError(
                f"sweep: executor='cuda' runs scenes that differ in their numbers only, but "
                f"the scene at {value:g} has other law classes or effects than the first "
                f"one's ({run.kernel[:2]} against {prepared[0].kernel[:2]})")
    order = warp_order(coordinates)
    done = run_batch(first, [prepared[k] for k in order], response=response,
                     transient=transient, record=record,
                     samples_per_period=samples_per_period,
                     scene_of=lambda j: scene_at(*values[order[j]]))
    back = np.argsort(order)
    poincare, extent = done.poincare[back], done.extent[back]
    if pool is None:
        kinds = _classify_chunk(poincare, extent, tolerance)
    else:
        futures = [pool.submit(_classify_chunk, points, scale, tolerance) for points, scale
                   in zip(_chunks(poincare, CHUNK), _chunks(extent, CHUNK))]
        kinds = [kind for future in futures for kind in future.result()]
    points = []
    for k, label in enumerate(labels):
        error = done.errors[back[k]]
        if error is None and kinds[k] is None:
            error = "the run's Poincaré points are not finite"
        if error is not None:
            points.append(SweepPoint.failure(label, error, tolerance=tolerance))
            continue
        j = back[k]
        points.append(SweepPoint(
            value=float(label), poincare=poincare[k].copy(),
            energy_density=float(done.energy_density[j]),
            friction_loss_per_cycle=float(done.friction_loss[j]), classification=kinds[k],
            final_state=(done.final_x[j].copy(), done.final_v[j].copy())))
    return points
