"""Two-parameter maps: the steady response over a grid of two parameters.

A map is a sweep over the cells of its grid (``sweep.sweep`` runs them, on any executor,
and on a GPU with ``executor="cuda"``: a 256 × 256 map is 65,536 runs), read back as one
``Sweep`` of the second parameter at each value of the first (``SweepMap``), whose
classification labels colour the map as a bifurcation diagram colours its points.
"""

from __future__ import annotations

from collections.abc import Callable, Hashable, Sequence
from dataclasses import replace

import numpy as np

from contact_laws import check_int

from ..model.scene import Scene
from ..run.classification import REPEAT_TOLERANCE
from ..run.methods import TRANSIENT, Adaptive
from ..run.simulation import Sweep, SweepMap
from . import sweep as sweep_module


def _axis(field: str, values) -> np.ndarray:
    """A map axis: a 1-d sequence of at least one finite number (as ``sweep`` checks
    its values)."""
    return np.array(sweep_module.checked_values(values, "sweep_map", field), dtype=float)


def sweep_map(scene_at: Callable[[float, float], Scene], first: Sequence[float],
              second: Sequence[float], *, parameters: tuple[str, str] = ("first", "second"),
              blade: Hashable | int = 1, transient: int = TRANSIENT, record: int = 100,
              method=Adaptive(), samples_per_period: int = 50, initial=None,
              tolerance: float = REPEAT_TOLERANCE, workers: int | None = None,
              executor=None, progress=None) -> SweepMap:
    """The steady response of ``scene_at(a, b)`` at every a of ``first`` and b of
    ``second``: the computation behind ``shroudnet.sweep_map`` (``front.studies``, where
    every argument is documented), with ``progress`` a callable ``progress(done, total)``
    or None."""
    if not callable(scene_at):
        raise TypeError(f"sweep_map.scene_at must be a callable (a, b) -> Scene, got "
                        f"{scene_at!r}")
    first, second = _axis("first", first), _axis("second", second)
    if (not isinstance(parameters, tuple | list) or len(parameters) != 2
            or not all(isinstance(name, str) for name in parameters)):
        raise TypeError(f"sweep_map.parameters must be two names (str, str), got "
                        f"{parameters!r}")
    check_int("sweep_map", "cells", len(first) * len(second), most=16_777_216)
    rows, columns = np.meshgrid(first, second, indexing="ij")
    pairs = np.column_stack([rows.ravel(), columns.ravel()])
    done = sweep_module.sweep(
        _Cell(scene_at, pairs), range(len(pairs)), parameter=f"{parameters[0]}, "
        f"{parameters[1]} (cell)", blade=blade, transient=transient, record=record,
        method=method, samples_per_period=samples_per_period, initial=initial,
        tolerance=tolerance, workers=workers, executor=executor, progress=progress,
        order_by=pairs)
    points = [_relabelled(point, value) for point, value in zip(done.points, pairs[:, 1])]
    width = len(second)
    sweeps = tuple(Sweep(parameter=parameters[1], blade=done.blade,
                         points=tuple(points[row * width:(row + 1) * width]),
                         settings={**done.settings, parameters[0]: float(value)})
                   for row, value in enumerate(first))
    return SweepMap(parameters=tuple(parameters), first=first, second=second, rows=sweeps)


class _Cell:
    """The scene of a map's cell by its index in the grid (picklable, for the workers)."""

    def __init__(self, scene_at, pairs):
        self.scene_at, self.pairs = scene_at, pairs

    def __call__(self, index):
        a, b = self.pairs[int(index)]
        return self.scene_at(float(a), float(b))


def _relabelled(point, value):
    """The cell's point with the second parameter's value as its own."""
    return replace(point, value=float(value))
