"""What a simulation returns: trajectories, interface forces and modes, events, energy."""

from __future__ import annotations

from collections.abc import Hashable
from dataclasses import dataclass
from enum import IntEnum

import numpy as np

from contact_laws import check_int

from .scene import Scene


class EventKind(IntEnum):
    """What switched at an event."""

    CLOSING = 0      # contact closed (δ rose through 0)
    SEPARATION = 1   # contact opened (δ fell through 0)
    STICKING = 2     # slip velocity reached 0 and the static friction holds
    REVERSAL = 3     # slip velocity reached 0 and the interface slips the other way
    BREAKAWAY = 4    # a stuck interface's friction reached μ_s N


class SimulationError(RuntimeError):
    """A simulation that cannot go on: the message names the time and the interface."""


@dataclass(frozen=True)
class EventLog:
    """Every located switch, in time order."""

    time: np.ndarray        # [s]
    interface: np.ndarray   # interface index (order of ``BladeGroup.interfaces``)
    kind: np.ndarray        # ``EventKind`` values
    counts: dict            # events of each kind by name, complete even if the log is not

    @property
    def truncated(self) -> bool:
        """More events happened than the log could keep (their counts are still exact)."""
        return sum(self.counts.values()) > len(self.time)

    def __len__(self) -> int:
        return len(self.time)


@dataclass(frozen=True)
class EnergyLedger:
    """Energy balance over the run [J]: what the excitation put in went somewhere.

    excitation_work = damping_loss + friction_loss + contact_loss + stored_change + residual.
    ``friction_loss`` includes the kinetic energy lost when slipping blades lock together at
    stick onset (of the order of the event tolerance). ``contact_loss`` is what damped
    normal laws dissipate; ``stored_change`` is the change of kinetic energy, blade strain
    energy and contact strain energy ∫₀^δ N(s, 0) ds. The residual measures the integration
    error.
    """

    excitation_work: float
    damping_loss: float
    friction_loss: float
    contact_loss: float
    stored_change: float
    residual: float


@dataclass(frozen=True, eq=False)
class Simulation:
    """A trajectory of a scene, sampled uniformly with a sample at every t = k T_e.

    Arrays have one row per sample: ``x``, ``v`` by blade position (n_t × n_blades),
    ``normal_force``, ``friction_force`` and ``modes`` by interface (n_t × n_interfaces).
    """

    scene: Scene
    settings: dict
    t: np.ndarray
    x: np.ndarray
    v: np.ndarray
    normal_force: np.ndarray
    friction_force: np.ndarray
    modes: np.ndarray
    events: EventLog
    energy: EnergyLedger
    work: np.ndarray         # cumulative (excitation, damping, friction, contact, lock) [J]
    samples_per_period: int
    steps: int               # Runge–Kutta steps taken (accepted ones, for Adaptive)

    def _steady(self, skip: int, owner: str) -> slice:
        """The rows from t = skip T_e on; ``skip`` is a whole number of periods (an int, a
        numpy integer or a float of integral value) in [0, periods]."""
        skip = check_int(owner, "skip", skip, whole_floats=True)
        if not 0 <= skip <= self.periods:
            raise ValueError(f"skip must be in [0, {self.periods}] periods, got {skip}")
        return slice(skip * self.samples_per_period, None)

    @property
    def periods(self) -> int:
        """Number of excitation periods simulated."""
        return (len(self.t) - 1) // self.samples_per_period

    def poincare(self, blade: Hashable | int, skip: int = 0) -> np.ndarray:
        """Stroboscopic points (x [m], ẋ [m/s]) of a blade at t = k T_e, k ≥ skip.

        ``blade`` is a name or a 0-based position; ``skip`` a whole number of periods in
        [0, periods]. Returns an array (n_points × 2).
        """
        i = self.scene.blade_position(blade)
        rows = slice(self._steady(skip, "Simulation.poincare").start, None,
                     self.samples_per_period)
        return np.column_stack([self.x[rows, i], self.v[rows, i]])

    def energy_density(self, blade: Hashable | int, skip: int) -> float:
        """E_ρ = ∫ x² dt / (t2 − t1) [m²] of a blade after ``skip`` periods (the paper's §3.2).

        ``skip``, the transient periods left out, is required: a mean square that includes
        the transient is not the steady response's. It is a whole number of periods in
        [0, periods − 1] (an int, a numpy integer or a float of integral value); give 0 for a
        run that starts on the steady state.
        """
        i = self.scene.blade_position(blade)
        rows = self._steady(skip, "Simulation.energy_density")
        t, x = self.t[rows], self.x[rows, i]
        if len(t) < 2:
            raise ValueError("energy_density needs at least two samples after skip")
        return float(np.trapezoid(x * x, t) / (t[-1] - t[0]))
