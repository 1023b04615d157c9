"""Parameter sweeps and bifurcation diagrams: one steady response per value of a scalar.

A sweep keeps, per value, only what a diagram needs (Poincaré points, E_ρ, the
classification and the final state), never the time histories.
"""

from __future__ import annotations

from collections.abc import Callable, Hashable, Sequence
from dataclasses import dataclass

import numpy as np

from .analysis import Classification, classify, friction_loss_per_cycle
from .scene import Scene
from .simulate import FixedStep, simulate


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
                 record: int, method=FixedStep(), samples_per_period: int = 50,
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
          record: int = 100, method=FixedStep(), samples_per_period: int = 50,
          continuation: bool = False, initial=None, tolerance: float = 1e-5,
          progress: Callable[[int, int], None] | None = None) -> Sweep:
    """The steady response of ``scene_at(value)`` for each value, in the order given.

    Each point runs ``transient`` periods, then records ``record`` periods of which it keeps
    the Poincaré points of ``blade``, E_ρ, the friction loss per cycle and the
    classification. With ``continuation``, each point starts from the previous point's
    final state (the first from ``initial``, default rest), so a forward and a backward
    sweep can land on different coexisting attractors; otherwise every point starts from
    ``initial``. ``progress(done, total)`` is called after each point.
    """
    values = [float(v) for v in values]
    if not values:
        raise ValueError("sweep needs at least one value")
    for name, number in (("transient", transient), ("record", record)):
        if isinstance(number, bool) or not isinstance(number, int) or number < 0:
            raise ValueError(f"sweep.{name} must be an int >= 0, got {number!r}")
    if record < 3:
        raise ValueError(f"sweep.record must be at least 3 periods, got {record}")
    points = []
    state = initial
    for done, value in enumerate(values, start=1):
        point = steady_point(scene_at(value), value, blade=blade, transient=transient,
                             record=record, method=method,
                             samples_per_period=samples_per_period, initial=state,
                             tolerance=tolerance)
        points.append(point)
        if continuation:
            state = point.final_state
        if progress is not None:
            progress(done, len(values))
    settings = {"transient": transient, "record": record, "method": repr(method),
                "samples_per_period": samples_per_period, "continuation": continuation,
                "tolerance": tolerance}
    return Sweep(parameter=parameter, blade=blade, points=tuple(points), settings=settings)
