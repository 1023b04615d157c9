"""Families of periodic orbits in one parameter: pseudo-arclength continuation.

The unknowns are u = (y, p): the orbit's start y = (x, ẋ) at t = 0 mod T_e (with
elastic contacts, their springs' stretches too: ``stability.state_parts``; with
substructures, by the engine's coordinates, while the orbits of the ``Branch`` hold their
nodes' own degrees of freedom) and the parameter p. Each step predicts along the branch's
tangent τ (the kernel of [M − I, ∂φ/∂p], DESIGN §6) and corrects by Newton on

    φ(y, p) − y = 0,    τ · (u − u_predicted) = 0,

in scaled coordinates (displacements over the first orbit's state scale, velocities over
that times l Ω, p over |stop − start|), so that a step of the arclength weighs the
orbit's change and the parameter's alike. Along the branch the Floquet multipliers are
watched: a real one through +1 (where the parameter turns back) is a fold, one through −1
a period doubling, a complex pair through the unit circle a torus (Neimark–Sacker)
bifurcation; each is located on the branch by the secant method on its test function,
|μ| − 1 of the multiplier that crosses. A
change of the orbit's switch sequence is a nonsmooth bifurcation ("grazing" for contact
closing or opening, "stick-slip" for stick phases), reported at the first orbit beyond it.

At such a change the branch has a kink: ∂φ/∂y jumps, and the corrector's linear model,
taken on one side, may not reach the branch on the other however short the step. Where
the steps have shrunk to ``KINK_STEP`` the branch is crossed at a fixed parameter
instead, by Newton on the orbit alone from the last point's orbit, a step of
``KINK_JUMPS`` of |stop − start| on; the arclength steps go on from there, in the
parameter's direction: the orbit's jump across the kink may point back along the branch.
"""

from __future__ import annotations

import cmath
import math
from collections.abc import Callable
from dataclasses import dataclass

import numpy as np

from contact_laws import check_callable, check_calls_with, check_instance, check_int, check_real

from ..analysis.stability import TANGENT_METHOD, state_parts, stroboscopic_step
from ..checked_records import check_record
from ..linear.response import frequency_response
from ..model.lowering import from_dofs
from ..model.scene import Scene
from ..run.methods import EVENT_TOLERANCE, Accuracy, Adaptive, check_event_tolerance
from ..run.simulate import MAX_PERIODS, integrate
from ..run.simulation import SimulationError
from .cyclic import CyclicSymmetry, cyclic_symmetry, reduced_step, whole_period
from .harmonic.orbit import HarmonicOrbit
from .orbits import (
    ORBIT_TOLERANCE,
    SMALLEST_TOLERANCE,
    UNIT_CIRCLE,
    ConvergenceError,
    PeriodicOrbit,
    least_squares,
    orbit_at,
    periodic_orbit,
    state_weights,
    symmetry_of,
)
from .parametric import checked_scene_at, same_scene
from .vertex import parabola_vertex

#: Bifurcation kinds.
KINDS = ("fold", "period-doubling", "torus", "symmetry-breaking", "grazing", "stick-slip")

#: Arclength steps (scaled units, see the module's docstring): the largest by default,
#: the first as a fraction of the largest, and the smallest before the branch is given up.
LARGEST_STEP = 1.0
FIRST_STEP = 0.1
SMALLEST_STEP = 1e-7
#: The arclength step below which a failing step is taken for a kink of the branch, and
#: the parameter steps (fractions of |stop − start|, shortest first) tried across it.
KINK_STEP = 1e-3
KINK_JUMPS = (1e-5, 1e-4, 1e-3)
#: A corrector whose residual stops falling (by less than half an iteration) within
#: this many times the tolerance has met the map's own integration noise: it has converged.
NOISE_FLOOR = 10.0
#: How far from a period doubling (or a symmetry-breaking point) the new branch is first
#: sought (scaled units).
DOUBLED_OFFSET = 1e-3
#: Corrector iterations before a step is halved; a step that converged in at most
#: ``EASY_ITERATIONS`` grows by ``GROWTH``.
CORRECTOR_ITERATIONS = 7
EASY_ITERATIONS = 3
GROWTH = 1.5
#: How much larger than the state scale an orbit grows before the scale follows it.
RESCALE = 2.0
#: The least cosine between consecutive tangents; a sharper turn halves the step.
TURN = 0.95
#: Relative step of the forward difference ∂φ/∂p (of max(|p|, |stop − start|)).
PARAMETER_DIFFERENCE = 1e-6
#: Steps locating a bifurcation, and the bracket (of the arclength between the two
#: points around it) that is close enough.
LOCATING_STEPS = 16
LOCATED = 1e-6
#: |Im μ| / |μ| below which a multiplier is taken as real.
REAL = 1e-8
#: How far |μ| − 1 may stay from 0 where the bracket has closed on a sign change of a
#: multiplier's test function: beyond it the change is a jump (two real multipliers that
#: meet and leave the axis together), not a crossing of the unit circle.
JUMP = 1e-3


@dataclass(frozen=True)
class FrequencyShift:
    """A branch's resonance against the linear limits it lies between [Hz]: ``peak``, the
    excitation frequency where its amplitude is largest; ``open``, ``stuck`` and
    ``closed``, where the linear responses with the interfaces in those limits peak
    (``linear_modes``' docstring): open is the lower bound, closed (every interface
    closed, and stuck where it can stick) the upper one, and stuck the group at rest with
    its friction locked, the normal springs of interfaces open at rest left out. Friction
    and contact move the resonance by ``peak − open`` from the open blades', a fraction
    ``stiffening`` of the way to the closed one.

    ``at_end`` is True where the largest amplitude is at the first or the last point of
    the branch: the branch has no maximum inside it, so ``peak`` is where the branch was
    started or stopped, not a resonance (which lies beyond it, or nowhere); ``str`` says
    so.
    """

    peak: float
    open: float
    stuck: float
    closed: float
    at_end: bool

    @property
    def stiffening(self) -> float:
        """(peak − open)/(closed − open): 0 at the open resonance, 1 at the closed one;
        NaN where the two coincide (nothing the interfaces do moves the resonance)."""
        if self.closed == self.open:
            return math.nan
        return (self.peak - self.open) / (self.closed - self.open)

    def __str__(self) -> str:
        text = (f"resonance at {self.peak:.2f} Hz; the linear limits' at {self.open:.2f} Hz "
                f"(open), {self.stuck:.2f} Hz (stuck) and {self.closed:.2f} Hz (closed)")
        if self.closed != self.open:
            text += f": {self.stiffening:.0%} of the way from open to closed"
        if self.at_end:
            text += ("; the branch's largest amplitude is at its end, not a maximum inside "
                     "it: the resonance lies beyond the branch, if anywhere")
        return text


#: Frequencies at which ``Branch.frequency_shift`` evaluates each linear limit.
SHIFT_POINTS = 3001


def _parabola_top(grid, values) -> float:
    """The abscissa of the largest of ``values`` on the even ``grid``, refined by the
    parabola through it and its neighbours (``vertex``)."""
    k = int(np.argmax(values))
    if k == 0 or k == len(values) - 1:
        return float(grid[k])
    shift, _ = parabola_vertex(values[k - 1], values[k], values[k + 1])
    return float(grid[k] + shift * (grid[1] - grid[0]))


@dataclass(frozen=True)
class Bifurcation:
    """A point of a branch where the orbit changes its kind or its stability.

    ``kind``: one of ``KINDS``. ``parameter``: where it is (located to the accuracy of
    the orbits for "fold", "period-doubling" and "torus"; the first orbit past the
    change for "grazing" and "stick-slip", with the change inside ``bracket``).
    ``orbit``: the orbit there; ``multiplier``: the critical Floquet multiplier (nan for
    a nonsmooth one); ``index``: the change lies between branch points ``index`` and
    ``index + 1``. On a branch of travelling waves (``continuation``'s ``symmetry``), a
    real multiplier that leaves the unit circle through +1 without a fold of the
    symmetric branch is a "symmetry-breaking" bifurcation: its eigenvector is a wave of
    another diameter (``wave_number``), the motion a standing or localised one beyond.
    On a branch of harmonic-balance orbits (``harmonic_continuation``) the orbit is a
    ``HarmonicOrbit`` and the multiplier one of Hill's.
    """

    kind: str
    parameter: float
    orbit: PeriodicOrbit | HarmonicOrbit
    multiplier: complex
    index: int
    bracket: tuple[float, float]

    #: Fields that may hold NaN or ±inf (see ``checked_records``).
    NON_FINITE = ("multiplier",)

    def __post_init__(self):
        check_record(self)

    @property
    def wave_number(self) -> int:
        """The nodal diameter of the critical multiplier's eigenvector
        (``PeriodicOrbit.wave_numbers``); a ValueError for a nonsmooth bifurcation or a
        group without sectors."""
        if cmath.isnan(self.multiplier):
            raise ValueError(f"Bifurcation.wave_number: a {self.kind} bifurcation has no "
                             "critical multiplier")
        k = int(np.argmin(np.abs(self.orbit.multipliers - self.multiplier)))
        return int(self.orbit.wave_numbers[k])


@dataclass(frozen=True)
class Branch:
    """A family of periodic orbits of ``periods`` excitation periods along a parameter.

    ``parameter[i]`` and ``orbits[i]`` are its points, in the order continued (the
    parameter turns back at a fold); ``bifurcations`` the changes met between them;
    ``name`` the parameter's name; ``ended`` why the continuation stopped.
    """

    parameter: np.ndarray
    orbits: tuple[PeriodicOrbit, ...]
    bifurcations: tuple[Bifurcation, ...]
    periods: int
    name: str
    ended: str

    def __post_init__(self):
        check_record(self)

    def __len__(self) -> int:
        return len(self.orbits)

    @property
    def stable(self) -> np.ndarray:
        """Whether each orbit is stable (every multiplier inside the unit circle)."""
        return np.array([orbit.stable for orbit in self.orbits])

    @property
    def peak(self) -> np.ndarray:
        """max |x| [m] over each orbit, by point of the branch and response
        (``Scene.responses``: blades by position, or every component of every point of
        substructures)."""
        return np.array([orbit.peak for orbit in self.orbits])

    def amplitude(self, blade) -> np.ndarray:
        """The amplitude [m] of ``blade`` (a name or a position; with substructures a point
        component, ``Scene.response_position``) over each orbit: half its peak-to-peak
        (``PeriodicOrbit.amplitude``; ``peak`` holds max |x|)."""
        return np.array([orbit.amplitude(blade) for orbit in self.orbits])

    def energy_density(self, blade) -> np.ndarray:
        """E_ρ = ∫x² dt / (k T_e) [m²] of ``blade`` over each orbit (paper §3.2)."""
        return np.array([orbit.energy_density(blade) for orbit in self.orbits])

    @property
    def equivalent_damping(self) -> np.ndarray:
        """ζ_eq = W_d / (4π T_max) [-] of each orbit (``PeriodicOrbit.equivalent_damping``)."""
        return np.array([orbit.equivalent_damping for orbit in self.orbits])

    @property
    def energy_per_cycle(self) -> np.ndarray:
        """Per orbit, the energy per excitation period [J]: columns excitation, damping,
        friction, contact (``cycle.EnergyPerCycle``)."""
        return np.array([orbit.energy_per_cycle.as_array() for orbit in self.orbits])

    def frequency_shift(self, blade) -> FrequencyShift:
        """Where the branch peaks against the linear limits (``FrequencyShift``): the
        excitation frequency 1/T_e of the orbit of largest ``amplitude(blade)`` (flagged
        ``at_end`` where that orbit is the branch's first or last), and those at which
        ``frequency_response`` of that orbit's scene (at its speed) peaks for ``blade``
        with the interfaces open, stuck and closed, each sought over a half to twice the
        branch's (a grid of ``SHIFT_POINTS``, refined by a parabola). A ValueError where
        the closed limit is not linear (a Hertz contact open at rest: ``linear``)."""
        amplitude = self.amplitude(blade)
        top = int(np.argmax(amplitude))
        scene = self.orbits[top].scene
        peak = float(1.0 / scene.excitation_period)
        grid = np.linspace(0.5 * peak, 2.0 * peak, SHIFT_POINTS)
        limits = {}
        for contacts in ("open", "stuck", "closed"):
            found = frequency_response(scene, grid, contacts)
            limits[contacts] = _parabola_top(grid, np.abs(scene.response_of(found.response,
                                                                             blade)))
        return FrequencyShift(peak=peak, **limits, at_end=top in (0, len(amplitude) - 1))

    def harmonics(self, blade, order: int = 5) -> tuple[np.ndarray, np.ndarray]:
        """(amplitudes A_n [m], phases φ_n [rad]) of ``blade`` along the branch, one row
        per orbit and one column per harmonic n = 0 … ``order``
        (``PeriodicOrbit.harmonics``; each orbit is run again)."""
        found = [orbit.harmonics(blade, order) for orbit in self.orbits]
        return (np.array([h.amplitudes for h in found]), np.array([h.phases for h in found]))

    def worst_blade(self) -> np.ndarray:
        """Per point, the position of the blade (the response) with the largest peak."""
        return np.argmax(self.peak, axis=1)

    def amplification(self, tuned: Branch | float) -> np.ndarray:
        """Per point, the worst blade's peak over the tuned group's peak [m] (``tuned``: a
        number, or the tuned group's branch, whose largest peak is taken): the
        amplification factor of a mistuned group."""
        reference = tuned.peak.max() if isinstance(tuned, Branch) else float(tuned)
        return self.peak.max(axis=1) / reference

    def multipliers(self) -> np.ndarray:
        """Per point, the Floquet multipliers by descending modulus (complex)."""
        return np.array([orbit.multipliers for orbit in self.orbits])


def continuation(scene_at: Callable[[float], Scene], start: float, stop: float, *,
                 periods: int = 1, guess=None, step: float | None = None,
                 max_step: float = LARGEST_STEP, max_points: int = 1000,
                 method: Adaptive | Accuracy = TANGENT_METHOD,
                 tolerance: float = ORBIT_TOLERANCE,
                 event_tolerance: float = EVENT_TOLERANCE,
                 transient: int = 100, from_bifurcation: Bifurcation | None = None,
                 parameter: str = "value", progress: Callable | None = None,
                 symmetry: str | None = None) -> Branch:
    """The branch of periodic orbits of ``scene_at(p)`` from p = ``start`` towards ``stop``.

    Pseudo-arclength continuation (see the module's docstring): it follows the branch
    through folds, where the parameter turns back, and ends where the parameter leaves
    [start, stop] (the last point on ``stop`` exactly when it gets there), after
    ``max_points`` points, or where no step as small as ``SMALLEST_STEP`` converges.

    Parameters
    ----------
    scene_at : callable
        p ↦ Scene, as for ``sweep``; any number of a scene may be the parameter.
    start, stop : float
        The parameter range; the branch starts at ``start`` (or at ``from_bifurcation``).
    periods : int
        k ≥ 1: orbits of period k T_e.
    guess : (x0, v0) or (x0, v0, u0), optional
        Near the orbit at ``start``, as ``periodic_orbit`` takes it (with substructures,
        the nodes' own degrees of freedom); default the state after ``transient`` periods.
    step, max_step : float, optional
        The first and the largest arclength step, in the scaled units: about the
        fraction of [start, stop] a step crosses where the orbit changes little. Default
        ``LARGEST_STEP``, and ``FIRST_STEP`` times it for the first.
    max_points : int
        The most points of the branch.
    method, tolerance, event_tolerance, transient
        As ``periodic_orbit``.
    from_bifurcation : Bifurcation, optional
        A "period-doubling" point of another branch: continue the doubled branch (period
        2k T_e) born there, away from it, within [start, stop]; or a "symmetry-breaking"
        one: continue the branch of non-symmetric orbits born there, with the full
        solver.
    parameter : str
        The parameter's name, for the record and for plots.
    progress : callable, optional
        ``progress(points, p)`` after each point.
    symmetry : None, "cyclic" or "none"
        As ``periodic_orbit``: "cyclic" follows the travelling waves of a tuned ring
        forced in engine order at the cost of the reduced map (a ValueError where the
        scene at ``start``, or at any point, lacks the symmetry), and locates
        "symmetry-breaking" bifurcations; None (default) does so where the scene at
        ``start`` has the symmetry, ``periods`` is 1 and there is no
        ``from_bifurcation``.

    Raises
    ------
    ValueError
        Bad arguments: ``start`` equal to ``stop``, a ``scene_at`` whose scene does not
        change with p, a guess of the wrong shape, a ``from_bifurcation`` that is not a
        period doubling.
    ConvergenceError
        No periodic orbit converges at the branch's start.
    """
    start = check_real("continuation", "start", start)
    stop = check_real("continuation", "stop", stop)
    if start == stop:
        raise ValueError(f"continuation: start and stop are both {start}: give a range")
    check_callable("continuation", "scene_at", scene_at, expected="a callable value -> Scene")
    periods = check_int("continuation", "periods", periods, low=1, most=MAX_PERIODS)
    transient = check_int("continuation", "transient", transient, low=0, most=MAX_PERIODS)
    check_instance("continuation", "method", method, (Adaptive, Accuracy),
                   expected="Adaptive(...) or Accuracy(...)")
    check_real("continuation", "tolerance", tolerance, low=SMALLEST_TOLERANCE, high=1e-3)
    check_event_tolerance("continuation", event_tolerance)
    check_instance("continuation", "parameter", parameter, str, expected="a name (str)")
    if progress is not None:
        check_calls_with("continuation", "progress", progress, 2,
                         expected="None or a callable progress(points, p)")
    max_points = check_int("continuation", "max_points", max_points, low=2)
    max_step = check_real("continuation", "max_step", max_step, low=SMALLEST_STEP,
                          high=1.0)
    step = FIRST_STEP * max_step if step is None else check_real(
        "continuation", "step", step, low=SMALLEST_STEP, high=max_step)
    if from_bifurcation is not None and (
            not isinstance(from_bifurcation, Bifurcation)
            or from_bifurcation.kind not in ("period-doubling", "symmetry-breaking")):
        raise ValueError(f"continuation.from_bifurcation must be a 'period-doubling' or a "
                         f"'symmetry-breaking' Bifurcation of a branch, got "
                         f"{from_bifurcation!r}")
    span = abs(stop - start)
    try:
        checked_scene_at("continuation", scene_at, start, start + 1e-3 * span)
    except (ValueError, TypeError) as error:
        if "scene_at" in str(error):
            raise
        raise type(error)(f"continuation: scene_at refused the range start = {start:g} … "
                          f"stop = {stop:g}: {error}") from error
    if from_bifurcation is not None:
        _check_born_here(from_bifurcation, scene_at, start, stop)
    cyclic = None if from_bifurcation is not None and symmetry is None else symmetry_of(
        scene_at(start), periods, symmetry, "continuation")
    if cyclic is not None and from_bifurcation is not None:
        raise ValueError("continuation: a branch from a bifurcation is followed with the "
                         "full solver: leave symmetry=None or give 'none'")
    if cyclic is not None and symmetry is None and symmetry_of(
            scene_at(start + 1e-3 * (stop - start)), periods, None) is None:
        cyclic = None  # the parameter itself breaks the symmetry (a mistuning, say)
    solver = Solver(scene_at=scene_at, span=span,
                    low=min(start, stop), high=max(start, stop), method=method,
                    tolerance=tolerance, event_tolerance=event_tolerance, cyclic=cyclic)
    if from_bifurcation is None:
        first = periodic_orbit(solver.scene_at(start), periods, guess, method=method,
                               transient=transient, tolerance=tolerance,
                               event_tolerance=event_tolerance,
                               symmetry="none" if cyclic is None else "cyclic")
        y = from_dofs(first.scene.arrays.layout, first.state)
        solver.weights = state_weights(first.scene, y)
        point = solver.point(y, start, periods)
        direction = np.zeros(len(point.u))
        direction[-1] = math.copysign(1.0, stop - start)
    elif from_bifurcation.kind == "period-doubling":
        point, direction = solver.doubled(from_bifurcation)
        periods = point.periods
    else:
        point, direction = solver.broken(from_bifurcation)
        periods = point.periods
    point = point.with_tangent(solver.tangent(point, direction))
    return solver.follow(point, step, max_step, max_points, parameter, progress)


def _check_born_here(bifurcation: Bifurcation, scene_at, start: float, stop: float) -> None:
    """Refuse a ``from_bifurcation`` whose branch cannot start here: its parameter outside
    [start, stop], or its orbit an orbit of another scene than ``scene_at`` gives there."""
    where = bifurcation.parameter
    if not min(start, stop) <= where <= max(start, stop):
        raise ValueError(f"continuation.from_bifurcation lies at {where:g}, outside the "
                         f"range start = {start:g} … stop = {stop:g}: the branch born there "
                         "starts at its parameter, so the range must hold it")
    if not same_scene(bifurcation.orbit.scene,
                      checked_scene_at("continuation", scene_at, where, where)):
        raise ValueError(f"continuation.from_bifurcation is a bifurcation of another scene: "
                         f"its orbit's scene is not scene_at({where:g}); give a bifurcation of "
                         "a branch of this scene_at")


@dataclass(frozen=True)
class Point:
    """A converged point of the branch: u = (W y, p / span), its map and ∂φ/∂p, and its
    unit tangent (scaled)."""

    u: np.ndarray
    parameter: float
    periods: int
    step: object          # the StroboscopicStep at the point
    rate: np.ndarray      # ∂φ/∂p
    tangent: np.ndarray | None = None

    def with_tangent(self, tangent):
        return Point(self.u, self.parameter, self.periods, self.step, self.rate, tangent)


@dataclass
class Solver:
    """The continuation's maps and steps; ``weights`` W scale the state (set at the
    branch's first orbit)."""

    scene_at: Callable
    span: float
    low: float
    high: float
    method: object
    tolerance: float
    event_tolerance: float
    cyclic: CyclicSymmetry | None = None
    weights: np.ndarray | None = None

    # ---- the map and its derivatives -------------------------------------------------------

    def state(self, u):
        return u[:-1] / self.weights

    def evaluate(self, y, p, periods, rate=None):
        """The map with its Jacobian at (y, p), and ∂φ/∂p (by a forward difference unless
        ``rate`` is given)."""
        scene = self.scene_at(p)
        if self.cyclic is None:
            step = stroboscopic_step(scene, periods, state_parts(scene, y),
                                     method=self.method, event_tolerance=self.event_tolerance)
        else:
            step = reduced_step(scene, self.symmetric(scene, p), y,
                                method=self.method, event_tolerance=self.event_tolerance)
        if rate is None:
            h = PARAMETER_DIFFERENCE * max(abs(p), self.span)
            shifted = self.scene_at(p + h)
            until = None if self.cyclic is None else \
                self.cyclic.fraction * shifted.excitation_period
            done = integrate(shifted, periods, method=self.method,
                             samples_per_period=1, event_tolerance=self.event_tolerance,
                             initial=state_parts(shifted, y), event_capacity=0, until=until)
            end = np.concatenate([done.run.output.x[-1], done.run.output.v[-1],
                                  done.stretches[-1]])
            if self.cyclic is not None:
                end = self.cyclic.shifted(end, -self.cyclic.steps)
            rate = (end - step.end) / h
        return step, rate

    def symmetric(self, scene, p) -> CyclicSymmetry:
        """The branch's symmetry, checked to hold at p."""
        try:
            found = cyclic_symmetry(scene)
        except ValueError as reason:
            raise ValueError(f"the scene at p = {p:.9g} lacks the branch's cyclic "
                             f"symmetry: {reason}") from None
        if (found.sectors, found.engine_order) != (self.cyclic.sectors,
                                                  self.cyclic.engine_order):
            raise ValueError(f"the scene at p = {p:.9g} is a ring of {found.sectors} "
                             f"forced in engine order {found.engine_order}, not the branch's "
                             f"{self.cyclic.sectors} in {self.cyclic.engine_order}")
        return found

    def monodromy(self, point) -> np.ndarray:
        """The monodromy of ``point``'s orbit over its whole period."""
        if self.cyclic is None:
            return point.step.jacobian
        return self.cyclic.monodromy(point.step.jacobian)

    def jacobian(self, step, rate):
        """∂(W(φ − y))/∂u in the scaled coordinates: 2N × (2N + 1)."""
        w = self.weights
        square = w[:, None] * (step.jacobian - np.eye(len(w))) / w[None, :]
        return np.column_stack([square, w * rate * self.span])

    def point(self, y, p, periods):
        step, rate = self.evaluate(y, p, periods)
        return Point(np.append(self.weights * y, p / self.span), p, periods, step, rate)

    def tangent(self, point, reference):
        """The unit kernel vector of the scaled Jacobian, oriented along ``reference``."""
        bordered = np.vstack([self.jacobian(point.step, point.rate), reference])
        right = np.zeros(len(reference))
        right[-1] = 1.0
        tangent = least_squares(bordered, right)
        tangent /= np.linalg.norm(tangent)
        return tangent if tangent @ reference >= 0.0 else -tangent

    # ---- corrector -------------------------------------------------------------------------

    def correct(self, predicted, normal, offset, periods, reach, fixed=None):
        """Newton on W(φ(y, p) − y) = 0, normal · u = offset, from u = ``predicted``.

        Returns the converged ``Point`` and the iterations it took, or raises
        ``ConvergenceError``, also when an update is longer than ``reach`` (the
        corrector is leaving for another branch).
        """
        u = predicted.copy()
        rate = None  # ∂φ/∂p at the prediction serves every iteration (a chord method)
        last = math.inf
        for iteration in range(CORRECTOR_ITERATIONS):
            p = u[-1] * self.span if fixed is None else fixed
            y = self.state(u)
            try:
                step, rate = self.evaluate(y, p, periods, rate)
            except ValueError as error:  # scene_at refuses p: the corrector went astray
                raise ConvergenceError(f"the corrector reached p = {p:.9g}, where "
                                       f"scene_at says: {error}") from error
            residual = self.weights * (step.end - y)
            constraint = normal @ u - offset
            size = np.abs(residual).max()
            stalled = NOISE_FLOOR * self.tolerance >= size > last / 2.0
            if (size <= self.tolerance or stalled) and abs(constraint) <= 1e-12:
                return Point(u, p, periods, step, rate), iteration
            last = size
            system = np.vstack([self.jacobian(step, rate), normal])
            change = least_squares(system, np.append(residual, constraint))
            if np.linalg.norm(change) > reach:
                raise ConvergenceError(f"a corrector step of {np.linalg.norm(change):.3g} "
                                       f"leaves the prediction's reach {reach:.3g}")
            u = u - change
        raise ConvergenceError(f"no convergence in {CORRECTOR_ITERATIONS} corrector steps "
                               f"(residual {np.abs(residual).max():.3g})")

    def advance(self, point, sigma):
        """The point at arclength ``sigma`` along ``point``'s tangent."""
        predicted = point.u + sigma * point.tangent
        return self.correct(predicted, point.tangent, point.tangent @ predicted,
                            point.periods, reach=abs(sigma))

    def at_parameter(self, point, target, sigma, reach=None):
        """The point of the branch at p = ``target``, from a prediction ``sigma`` along,
        its corrector's updates no longer than ``reach`` (default |sigma|)."""
        predicted = point.u + sigma * point.tangent
        predicted[-1] = target / self.span
        normal = np.zeros(len(predicted))
        normal[-1] = 1.0
        return self.correct(predicted, normal, target / self.span, point.periods,
                            reach=abs(sigma) if reach is None else reach, fixed=target)[0]

    # ---- the branch --------------------------------------------------------------------------

    def follow(self, point, step, max_step, max_points, name, progress) -> Branch:
        points = [point]
        orbits = [self.orbit(point, 0)]
        bifurcations = []
        ended = f"reached max_points = {max_points}"
        sigma = step
        crossing = True  # whether a kink may still be crossed from ``point``
        while len(points) < max_points:
            try:
                new, iterations = self.advance(point, sigma)
                new = new.with_tangent(self.tangent(new, point.tangent))
                if new.tangent @ point.tangent < TURN:
                    raise ConvergenceError("the branch turns too sharply")
            except SimulationError as error:
                sigma /= 2.0
                new = None
                if sigma < KINK_STEP and crossing:
                    crossing = False
                    new = self.across(point)
                if new is None:
                    if sigma < SMALLEST_STEP:
                        ended = (f"no step converged at p = {point.parameter:.9g} (the "
                                 f"last try: {error})")
                        break
                    continue
                iterations = CORRECTOR_ITERATIONS  # the step grows again from here
                sigma = max(float(np.linalg.norm(new.u - point.u)), KINK_STEP)
            if not self.low <= new.parameter <= self.high:
                target = self.high if new.parameter > self.high else self.low
                if target != point.parameter:
                    fraction = (target - point.parameter) / (new.parameter - point.parameter)
                    try:
                        end = self.at_parameter(point, target, fraction * sigma)
                    except SimulationError:
                        sigma /= 2.0  # land on the end from nearer
                        continue
                    new = end.with_tangent(self.tangent(end, point.tangent))
                    self.record(points, orbits, bifurcations, new)
                ended = f"reached p = {target:.9g}"
                break
            self.record(points, orbits, bifurcations, new)
            point = points[-1] = self.rescaled(new)
            crossing = crossing or sigma >= KINK_STEP
            if progress is not None:
                progress(len(points), point.parameter)
            if iterations <= EASY_ITERATIONS:
                sigma = min(sigma * GROWTH, max_step)
        return Branch(parameter=np.array([p.parameter for p in points]), orbits=tuple(orbits),
                      bifurcations=tuple(bifurcations), periods=points[0].periods, name=name,
                      ended=ended)

    def across(self, point) -> Point | None:
        """The branch a fixed parameter step beyond ``point``, by Newton on the orbit
        alone from ``point``'s orbit, for each step of ``KINK_JUMPS`` in turn (the
        parameter moving as ``point``'s tangent does, and on beyond it); None where none
        converges."""
        direction = math.copysign(1.0, point.tangent[-1])
        for jump in KINK_JUMPS:
            p = point.parameter + direction * jump * self.span
            if not self.low <= p <= self.high:
                return None
            try:
                new = self.at_parameter(point, p, 0.0, reach=math.inf)
            except SimulationError:
                continue
            # on in the parameter's direction: the secant, mostly the orbit's change
            # across the kink, need not point along the branch beyond it
            tangent = self.tangent(new, new.u - point.u)
            return new.with_tangent(tangent if tangent[-1] * direction >= 0.0 else -tangent)
        return None

    def rescaled(self, point):
        """``point`` in coordinates whose state scale has grown to its orbit's, once the
        orbit is ``RESCALE`` times larger than the scale: steps stay a fraction of the
        orbit, however far from the first one the branch has grown."""
        weights = state_weights(point.step.scene, self.state(point.u))
        if weights[0] * RESCALE > self.weights[0]:
            return point
        change = np.append(weights / self.weights, 1.0)
        self.weights = weights
        tangent = change * point.tangent
        return Point(change * point.u, point.parameter, point.periods, point.step,
                     point.rate, tangent / np.linalg.norm(tangent))

    def orbit(self, point, iterations):
        y = self.state(point.u)
        residual = np.abs(self.weights * (point.step.end - y)).max()
        step = point.step if self.cyclic is None else whole_period(self.cyclic, point.step)
        return orbit_at(point.step.scene, point.periods, y, step, residual,
                        1.0 / self.weights[0], iterations, self.method,
                        self.event_tolerance, 100, False, self.cyclic)

    def record(self, points, orbits, bifurcations, new):
        """Append ``new`` and what changed since the last point."""
        last, before = points[-1], orbits[-1]
        orbit = self.orbit(new, 0)
        index = len(points) - 1
        for kind, test in smooth_changes(last, before, new, orbit, self.monodromy,
                                         symmetric=self.cyclic is not None):
            found = self.locate(kind, test, last, new, index)
            if found is not None:
                bifurcations.append(found)
        if orbit.switches != before.switches:
            kind = "stick-slip" if _stick_phases(orbit) != _stick_phases(before) else "grazing"
            bifurcations.append(Bifurcation(kind, new.parameter, orbit, complex(math.nan), index,
                                            (last.parameter, new.parameter)))
        points.append(new)
        orbits.append(orbit)

    def locate(self, kind, test, a, b, index) -> Bifurcation | None:
        """The zero of ``test`` between points a and b: the Illinois (modified regula
        falsi) method on the arclength from a, to ``LOCATED`` of the arclength from a to
        b; None where ``test`` has the same sign at both, or, for a multiplier's test, where it
        jumps through 0 rather than crossing it (multipliers that changed their count
        without crossing the circle: two real ones that meet and leave the real axis
        together, say)."""
        width = float(a.tangent @ (b.u - a.u))
        low, high = (0.0, test(a)), (width, test(b))
        if low[1] * high[1] > 0.0:
            return None
        best, best_value, kept, bracketed = b, abs(high[1]), None, False
        for _ in range(LOCATING_STEPS):
            if high[1] == low[1]:
                break
            sigma = low[0] - low[1] * (high[0] - low[0]) / (high[1] - low[1])
            try:
                trial = self.advance(a, sigma)[0]
                trial = trial.with_tangent(self.tangent(trial, a.tangent))
            except SimulationError:
                break
            value = test(trial)
            if abs(value) < best_value:
                best, best_value = trial, abs(value)
            bracketed = abs(high[0] - low[0]) <= LOCATED * abs(width)
            if value == 0.0 or bracketed:
                break
            if math.copysign(1.0, value) == math.copysign(1.0, low[1]):
                low = (sigma, value)
                if kept == "low":
                    high = (high[0], high[1] / 2.0)
                kept = "low"
            else:
                high = (sigma, value)
                if kept == "high":
                    low = (low[0], low[1] / 2.0)
                kept = "high"
        if bracketed and kind != "fold" and best_value > JUMP:
            return None  # |μ| jumps there: two multipliers met, none crossed the circle
        orbit = self.orbit(best, 0)
        return Bifurcation(kind, best.parameter, orbit, critical(kind, orbit.multipliers),
                           index, (a.parameter, b.parameter))

    # ---- from a period doubling --------------------------------------------------------------

    def doubled(self, bifurcation):
        """The first point of the period-2k branch born at a period doubling, and the
        direction away from it (``branching``)."""
        return self.branching(bifurcation, -1.0, 2 * bifurcation.orbit.periods)

    def broken(self, bifurcation):
        """The first point of the branch of non-symmetric orbits born at a
        symmetry-breaking bifurcation (followed with the full solver), and the direction
        away from it (``branching``)."""
        return self.branching(bifurcation, bifurcation.multiplier, bifurcation.orbit.periods)

    def branching(self, bifurcation, multiplier, periods):
        """The first point of the branch of orbits of ``periods`` born at ``bifurcation``,
        ``DOUBLED_OFFSET`` along the eigenvector of its orbit's multiplier nearest
        ``multiplier``, and the direction away from it."""
        orbit = bifurcation.orbit
        layout = orbit.scene.arrays.layout  # the orbit's state and monodromy are by dofs
        state = from_dofs(layout, orbit.state)
        self.weights = state_weights(orbit.scene, state)
        values, vectors = np.linalg.eig(orbit.monodromy)
        k = np.argmin(np.abs(values - multiplier))
        w = self.weights
        away = np.append(w * from_dofs(layout, np.real(vectors[:, k])), 0.0)
        away /= np.linalg.norm(away)
        base = np.append(w * state, bifurcation.parameter / self.span)
        size = DOUBLED_OFFSET
        point, _ = self.correct(base + size * away, away, away @ base + size, periods,
                                reach=1.0)
        return point, point.u - base


def _stick_phases(orbit):
    return {switch: count for switch, count in orbit.switches.items()
            if switch[1] in ("sticking", "breakaway")}


def _real(multipliers):
    """Which multipliers are real (to ``REAL`` of their modulus)."""
    return np.abs(multipliers.imag) <= REAL * np.maximum(np.abs(multipliers), 1e-300)


def critical(kind, multipliers):
    """The multiplier that crosses the unit circle at a bifurcation of ``kind``: the real
    one nearest +1 (fold, symmetry breaking) or −1 (period doubling), or the complex one
    nearest the circle."""
    real = _real(multipliers)
    if kind == "torus":
        pool = multipliers[~real]
        return complex(pool[np.argmin(np.abs(np.abs(pool) - 1.0))])
    target = -1.0 if kind == "period-doubling" else 1.0
    pool = multipliers[real]
    return complex(pool[np.argmin(np.abs(pool - target))]) if len(pool) else complex(target)


def _counts(multipliers):
    """(real multipliers below −1, complex ones outside the unit circle, real ones above
    +1)."""
    real = _real(multipliers)
    outside = np.abs(multipliers) > UNIT_CIRCLE
    return (int(np.sum(real & outside & (multipliers.real < 0))),
            int(np.sum(~real & outside)),
            int(np.sum(real & outside & (multipliers.real > 0))))


def smooth_changes(a, orbit_a, b, orbit_b, monodromy, symmetric=False):
    """(kind, test function of a point) of each smooth bifurcation between a and b, their
    orbits' monodromy matrices M = ``monodromy(point)``. The test functions are
    continuous along the branch and change sign at the bifurcation: the tangent's
    parameter component (fold); and |μ| − 1 of the multiplier that crosses the unit
    circle (``_modulus_crossing``): among the real negative ones (period doubling), the
    complex pairs (torus), or, on a ``symmetric`` branch where no fold explains it, the
    real positive ones (symmetry breaking)."""
    changes = []
    fold = a.tangent[-1] * b.tangent[-1] < 0.0
    if fold:
        changes.append(("fold", lambda point: point.tangent[-1]))
    (doubling_a, torus_a, rising_a), (doubling_b, torus_b, rising_b) = (
        _counts(orbit_a.multipliers), _counts(orbit_b.multipliers))
    if doubling_a != doubling_b:
        changes.append(("period-doubling", _modulus_crossing(
            monodromy, lambda mu: _real(mu) & (mu.real < 0.0), min(doubling_a, doubling_b))))
    if torus_a != torus_b:
        changes.append(("torus", _modulus_crossing(
            monodromy, lambda mu: ~_real(mu) & (mu.imag > 0.0), min(torus_a, torus_b) // 2)))
    if symmetric and not fold and rising_a != rising_b:
        changes.append(("symmetry-breaking", _modulus_crossing(
            monodromy, lambda mu: _real(mu) & (mu.real > 0.0), min(rising_a, rising_b))))
    return changes


def _modulus_crossing(monodromy, kept, rank):
    """The test function |μ| − 1 of the multiplier, of those that ``kept`` keeps (one of
    each complex pair), ``rank`` from the largest in modulus (0: the largest): where
    ``rank`` of them lie outside the unit circle at one end of the interval and one more
    at the other, it is the one that crossed, and the function changes sign exactly
    there. It varies as that multiplier does, as a product over all of them (det(M + I),
    the bialternate product, of some 10⁴ factors on a ring of many sectors) does not: its
    size changes by orders of magnitude over an interval, which the secant method follows
    only in as many halvings. −1 where fewer than rank + 1 are kept."""
    def test(point):
        multipliers = np.linalg.eigvals(monodromy(point))
        moduli = np.sort(np.abs(multipliers[kept(multipliers)]))[::-1]
        return float(moduli[rank]) - 1.0 if rank < len(moduli) else -1.0
    return test
