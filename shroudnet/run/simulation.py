"""What runs return: a simulation's trajectories, interface forces and modes, events and
energy; a sweep's points, failed ones included."""

from __future__ import annotations

import math
from collections.abc import Hashable
from dataclasses import dataclass, field

import numpy as np

from contact_laws import check_int

from ..checked_records import check_record
from ..model.lowering import from_dofs
from ..model.scene import Scene
from .classification import Classification
from .methods import SimulationSettings


class SimulationError(RuntimeError):
    """A simulation that cannot go on: the message names the time and the interface."""


@dataclass(frozen=True)
class EventLog:
    """Every located switch, in time order."""

    time: np.ndarray        # [s]
    interface: np.ndarray   # contact index (order of ``Scene.contacts``: of the interfaces)
    kind: np.ndarray        # ``EventKind`` values
    counts: dict            # events of each kind by name, complete even if the log is not

    def __post_init__(self):
        check_record(self)

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
    ``excitation_work`` is the work of the forces Q(t) and of the prescribed-motion nodes
    (the force each motion exerts on the group times its velocity). ``friction_loss``
    includes the kinetic energy lost when slipping blades lock together at stick onset (of
    the order of the event tolerance). ``contact_loss`` is what damped
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

    def __post_init__(self):
        check_record(self)


@dataclass(frozen=True, eq=False)
class Simulation:
    """A trajectory of a scene, sampled uniformly with a sample at every t = k T_e.

    Arrays have one row per sample: ``x`` [m], ``v`` [m/s] by blade position (n_t ×
    n_blades); with substructures, every node's own degrees of freedom q (of
    ``Substructure.matrices_at``, in its units) and their rates, stacked in
    ``Scene.blades`` order (n_t × n_dofs; ``dofs`` picks a node's); ``normal_force``,
    ``friction_force`` and ``modes`` by interface (n_t × n_interfaces);
    ``friction_force`` is along the tangent t (t₁ of a face's plane), and
    ``friction_force_second`` along t₂ where the scene has elastic contacts (0 on
    interfaces with one direction; None without elastic contacts).
    ``settings`` says how the run was made; a table in its saved layout
    (``SimulationSettings.as_dict``) is taken too.
    """

    scene: Scene
    settings: SimulationSettings
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
    compile_seconds: float = 0.0  # spent compiling the integrator, or loading it, first
    friction_force_second: np.ndarray | None = None  # (n_t × n_interfaces) along t₂ [N]

    def __post_init__(self):
        if not isinstance(self.settings, SimulationSettings):
            object.__setattr__(self, "settings", SimulationSettings.from_dict(self.settings))
        check_record(self)

    @property
    def periods(self) -> int:
        """Number of excitation periods simulated."""
        return (len(self.t) - 1) // self.samples_per_period

    def poincare(self, blade: Hashable | int, skip: int = 0) -> np.ndarray:
        """Stroboscopic points (x [m], ẋ [m/s]) of a blade at t = k T_e, k ≥ skip.

        ``blade`` is a name or a 0-based position; ``skip`` as ``steady_rows`` takes it.
        Returns an array (n_points × 2), periods − skip + 1 points.
        """
        rows = slice(steady_rows(self, skip, "Simulation.poincare").start, None,
                     self.samples_per_period)
        return np.column_stack([self.scene.response_of(self.x[rows], blade),
                                self.scene.response_of(self.v[rows], blade)])

    def energy_density(self, blade: Hashable | int, skip: int) -> float:
        """E_ρ = ∫ x² dt / (t2 − t1) [m²] of a blade after ``skip`` periods (the paper's §3.2).

        ``skip``, the transient periods left out, is required: a mean square that includes
        the transient is not the steady response's. It is taken as ``steady_rows`` takes it;
        give 0 for a run that starts on the steady state.
        """
        rows = steady_rows(self, skip, "Simulation.energy_density")
        t, x = self.t[rows], self.scene.response_of(self.x[rows], blade)
        return float(np.trapezoid(x * x, t) / (t[-1] - t[0]))

    def displacement(self, node: Hashable, point: str | None = None) -> np.ndarray:
        """The displacement r [m] of ``node``'s ``point`` at every sample (n_t × d); a
        ``Blade``'s one point is its x (``Scene.point_rows``)."""
        return self.x @ self.scene.point_rows(node, point).T

    def velocity(self, node: Hashable, point: str | None = None) -> np.ndarray:
        """The velocity ṙ [m/s] of ``node``'s ``point`` at every sample (n_t × d)."""
        return self.v @ self.scene.point_rows(node, point).T

    def dofs(self, node: Hashable) -> np.ndarray:
        """``node``'s own degrees of freedom q at every sample (n_t × n_i), in its
        substructure's units; expand a reduced one with ``Substructure.expand``."""
        return self.x @ self.scene.dof_rows(node).T

    def slip_displacement(self, interface, direction: int = 1) -> np.ndarray:
        """The tangential relative displacement u_t [m] of the interface at position
        ``interface`` (0-based, or (interface, k) for a patch's k-th contact:
        ``Scene.contact_position``; its column of ``friction_force``) at every sample: the
        integral of its slip velocity, t·(r_a − r_b) (blades: (x_i − x_j) cos α); with
        ``direction`` 2, t₂·(r_a − r_b) in a face's plane. Against its column of
        ``friction_force`` (or ``friction_force_second``) it draws the contact's
        hysteresis loop in that direction, whose area is the energy friction takes along
        it (``analysis.hysteresis_loop``)."""
        row = self._slip_row(interface, "Simulation.slip_displacement", direction)
        return np.concatenate([from_dofs(self.scene.arrays.layout, self.x),
                               self.scene.arrays.prescribed_state(self.t)[0]], axis=1) @ row

    def slip_velocity(self, interface) -> np.ndarray:
        """The slip velocity u̇_t [m/s] of the interface (or contact) ``interface`` at every
        sample: t·(ṙ_a − ṙ_b) (blades: (ẋ_i − ẋ_j) cos α), prescribed nodes moving as
        they do."""
        row = self._slip_row(interface, "Simulation.slip_velocity")
        return np.concatenate([from_dofs(self.scene.arrays.layout, self.v),
                               self.scene.arrays.prescribed_state(self.t)[1]], axis=1) @ row

    def checked_interface(self, interface, caller: str) -> int:
        """``interface`` as a contact's column (``Scene.contact_position``: an interface's
        position, or (interface, k) for the k-th pair of a patch), or an error naming
        ``caller`` where there is no such contact."""
        return self.scene.contact_position(interface, caller)

    def _slip_row(self, interface, caller: str, direction: int = 1) -> np.ndarray:
        """The interface's row of ``SceneArrays.slip_rows``: by the engine's coordinates
        (then the prescribed nodes), which ``from_dofs`` gives the samples in."""
        direction = check_int(caller, "direction", direction, low=1, most=2)
        return self.scene.arrays.slip_rows(direction)[self.checked_interface(interface,
                                                                             caller)]

    @property
    def stretches(self) -> np.ndarray:
        """The elastic contacts' springs' stretches u = r_t − w [m] at every sample (n_t ×
        2 per elastic contact, in the order of the interfaces: along t₁, then t₂), read
        back from their forces f = k_t u; with the last row as the third member of
        ``initial``, a run takes up the sliders where this one left them."""
        stiffness = self.scene.arrays.tangential_stiffness
        elastic = self.scene.arrays.elastic_interfaces
        values = np.empty((len(self.t), 2 * len(elastic)))
        values[:, 0::2] = self.friction_force[:, elastic] / stiffness[elastic]
        values[:, 1::2] = (0.0 if self.friction_force_second is None else
                           self.friction_force_second[:, elastic] / stiffness[elastic])
        return values

    def state(self, sample: int = -1) -> tuple[np.ndarray, ...]:
        """The whole state at sample ``sample`` (a row index; −1, the default, is the
        last), as ``initial`` takes it: (x, ẋ) [m, m/s], and with elastic contacts their
        springs' stretches u [m] (``stretches``). A run from the state at a sample
        t = k T_e (every ``samples_per_period``-th) goes on as this one went on from
        there: the excitation is the same at t = 0."""
        sample = check_int("Simulation.state", "sample", sample, low=-len(self.t),
                           high=len(self.t) - 1)
        stretches = (self.stretches[sample],) if self.scene.arrays.n_stretches else ()
        return (self.x[sample].copy(), self.v[sample].copy()) + stretches

    def friction_along(self, interface, direction: int = 1) -> np.ndarray:
        """The friction force [N] of the interface (or contact) ``interface`` along its
        tangent t₁ (``direction`` 1: ``friction_force``) or t₂ (2: 0 where the interface
        has one direction) at every sample."""
        interface = self.checked_interface(interface, "Simulation.friction_along")
        direction = check_int("Simulation.friction_along", "direction", direction, low=1,
                              most=2)
        if direction == 1:
            return self.friction_force[:, interface]
        if self.friction_force_second is None:
            return np.zeros(len(self.t))
        return self.friction_force_second[:, interface]


def steady_rows(sim: Simulation, skip: int, owner: str) -> slice:
    """The rows of ``sim`` from t = skip·T_e on: what is left after ``skip`` transient periods
    (``skip`` checked by ``steady_skip``). Every reading of a steady response takes ``skip``
    through here."""
    return slice(steady_skip(sim, skip, owner) * sim.samples_per_period, None)


def steady_skip(sim: Simulation, skip: int, owner: str) -> int:
    """``skip`` as an int: a whole number of periods (an int, a numpy integer or a float of
    integral value) in [0, periods), so that at least one whole period is left for each
    reading of it (Poincaré points, E_ρ, the spectrum, the friction loss per cycle, the
    classification) to read.

    Raises
    ------
    TypeError
        ``skip`` is not a whole number.
    ValueError
        ``skip`` is outside [0, periods).

    Both messages name ``owner.skip`` (``owner``: the reading that was given it) and what
    it allows.
    """
    skip = check_int(owner, "skip", skip, whole_floats=True)
    if not 0 <= skip < sim.periods:
        raise ValueError(f"{owner}.skip must be a whole number of periods in "
                         f"[0, {sim.periods}) (the run's {sim.periods} periods, at least one "
                         f"left to read), got {skip}")
    return skip


@dataclass(frozen=True)
class SweepPoint:
    """The steady response at one value of the swept parameter.

    A *failed* point (``error`` set: the message of the ``SimulationError`` that stopped
    its simulation) has no Poincaré points (shape (0, 2)), NaN for E_ρ and the friction
    loss, the classification label "failed" and an empty final state. The final state is
    in the coordinates of ``Simulation.x`` (with substructures, the nodes' own degrees of
    freedom), as ``sweep``'s ``initial`` takes it.
    """

    value: float
    poincare: np.ndarray                 # (record × 2): (x [m], ẋ [m/s]) at t = k T_e
    energy_density: float                # E_ρ [m²] over the recorded periods
    friction_loss_per_cycle: float       # [J]
    classification: Classification
    final_state: tuple[np.ndarray, np.ndarray]  # (x, ẋ) at the end, to continue from
    error: str | None = None             # why the point failed; None for a computed point
    #: max |x| [m] of each blade over the recorded periods, between samples where the
    #: velocity crosses zero (``extremes.sampled_peaks``; empty: failed, or not kept)
    peak: np.ndarray = field(default_factory=lambda: np.empty(0))

    #: Fields that may hold NaN or ±inf (see ``checked_records``).
    NON_FINITE = ("poincare", "energy_density", "friction_loss_per_cycle", "peak",
                  "final_state")

    def __post_init__(self):
        check_record(self)

    @property
    def worst_blade(self) -> int | None:
        """The position of the blade with the largest peak (None where none is kept)."""
        return int(np.argmax(self.peak)) if len(self.peak) else None

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
                   classification=Classification.failed(tolerance),
                   final_state=(nothing, nothing.copy()), error=str(message))


@dataclass(frozen=True)
class SweepFailure:
    """A point of a sweep whose simulation stopped: where, and why."""

    parameter: str
    index: int          # position of the value in the sweep's values (0-based)
    value: float
    message: str        # the ``SimulationError``'s message (time and interface)

    def __post_init__(self):
        check_record(self)

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

    def __post_init__(self):
        check_record(self)

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

    def peaks(self) -> np.ndarray:
        """max |x| [m] of every blade at every point (points × blades; NaN where a point
        failed or kept none)."""
        width = max((len(p.peak) for p in self.points), default=0)
        return np.array([p.peak if len(p.peak) == width else np.full(width, np.nan)
                         for p in self.points]).reshape(len(self.points), width)

    def amplification(self, tuned: float) -> np.ndarray:
        """Per point, the worst blade's peak over ``tuned`` [m], the tuned group's peak:
        the amplification factor of a mistuned group."""
        return np.nanmax(self.peaks(), axis=1) / tuned

    def diagram(self, coordinate: int = 0) -> tuple[np.ndarray, np.ndarray]:
        """(parameter values, Poincaré coordinates) flattened for a scatter plot.

        ``coordinate`` 0 is the displacement, 1 the velocity. Failed points have no
        Poincaré points, so they leave a gap.
        """
        values = np.concatenate([np.full(len(p.poincare), p.value) for p in self.points])
        section = np.concatenate([p.poincare[:, coordinate] for p in self.points])
        return values, section


@dataclass(frozen=True)
class SweepMap:
    """A two-parameter map: at each value of the first parameter (``first``), a sweep of
    the second (``second``), one ``Sweep`` of ``rows`` each, whose points' ``value`` is
    the second parameter's. ``parameters`` names the two; a failed point keeps its place
    as a gap."""

    parameters: tuple[str, str]
    first: np.ndarray
    second: np.ndarray
    rows: tuple[Sweep, ...]

    def __post_init__(self):
        check_record(self)

    @property
    def labels(self) -> np.ndarray:
        """Each point's classification label (first × second; "failed" where it failed)."""
        return np.array([row.labels for row in self.rows], dtype=object).reshape(
            len(self.first), len(self.second))

    def grid(self, reading: str) -> np.ndarray:
        """A number of every point (first × second) by the name of its ``SweepPoint``
        field: "energy_density" or "friction_loss_per_cycle" (NaN where a point failed)."""
        if reading not in ("energy_density", "friction_loss_per_cycle"):
            raise ValueError(f"SweepMap.grid.reading must be 'energy_density' or "
                             f"'friction_loss_per_cycle', got {reading!r}")
        return np.array([[getattr(point, reading) for point in row.points]
                         for row in self.rows], dtype=float).reshape(
            len(self.first), len(self.second))
