"""Families of periodic orbits in one parameter: pseudo-arclength continuation.

The unknowns are u = (y, p): the orbit's start y = (x, ẋ) at t = 0 mod T_e (with
elastic contacts, their springs' stretches too: ``stability.state_parts``; with
substructures, by the engine's coordinates, while the orbits of the ``Branch`` hold their
nodes' own degrees of freedom) and the parameter p. Each step predicts along the branch's
tangent τ (the kernel of [M − I, ∂φ/∂p], DESIGN §6) and corrects by Newton on

    φ(y, p) − y = 0,    τ · (u − u_predicted) = 0,

in scaled coordinates (displacements over the first orbit's state scale, velocities over
that times l Ω, p over |stop − start|), so that a step of the arclength weighs the
orbit's change and the parameter's alike. The corrector keeps the last point's monodromy
while its steps converge fast (a chord: runs of the state alone), and forms the
monodromy once at the new point, for its tangent and its multipliers; with
``jacobian="krylov"`` it solves by GMRES on the products instead (``orbits``). A contact
stuck through the whole orbit leaves its offset free (``neutral``): it is pinned at the
last point's value, which keeps the tangent a single direction where the orbits form a
family, and its multiplier 1 is left out of the tests.

Along the branch the Floquet multipliers are watched: a real one through +1 (where the
parameter turns back) is a fold, one through −1 a period doubling, a complex pair through
the unit circle a torus (Neimark–Sacker) bifurcation; each is located on the branch by
the secant method on its test function, |μ| − 1 of the multiplier that crosses.

A change of the orbit's switch sequence is a kink of the branch, a nonsmooth bifurcation
("grazing" for contact closing or opening, "stick-slip" for stick phases): located by
bisection on the parameter to ``KINK_WIDTH`` of the range (``Solver.locate_kink``) and
reported there. At a kink ∂φ/∂y jumps, and the corrector's linear model, taken on one
side, may not reach the branch on the other however short the step. Where the steps
have shrunk to ``KINK_STEP`` (they shrink no further while a crossing may succeed) the
branch is crossed at a fixed parameter instead, a step of ``KINK_JUMPS`` of
|stop − start| on, by Newton from the secant through the last two points extrapolated
there; failing that, from a transient there (said in ``Branch.notes``). The arclength
steps go on from there, in the parameter's direction: the orbit's jump across the kink
may point back along the branch. Bifurcations found at one parameter (to ``SAME`` of
the range) are one.
"""

from __future__ import annotations

import cmath
import dataclasses
import math
from collections.abc import Callable
from dataclasses import dataclass, field

import numpy as np

from contact_laws import (check_callable, check_calls_with, check_choice, check_instance,
                          check_int, check_real)

from ..analysis.stability import TANGENT_METHOD, state_parts
from ..checked_records import check_record
from ..engine.codes import EventKind
from ..linear.response import frequency_response
from ..model.lowering import from_dofs
from ..model.scene import Scene
from ..run.methods import EVENT_TOLERANCE, Accuracy, Adaptive, Exponential, check_event_tolerance
from ..run.simulate import MAX_PERIODS, integrate
from ..run.simulation import SimulationError
from .cyclic import CyclicSymmetry, cyclic_symmetry, symmetry_of
from .harmonic.orbit import HarmonicOrbit
from .krylov import gmres
from .neutral import tested
from .orbits import (
    EDGE,
    JACOBIANS,
    ORBIT_TOLERANCE,
    SMALLEST_TOLERANCE,
    UNIT_CIRCLE,
    ConvergenceError,
    PeriodicOrbit,
    forcing,
    jacobian_kind,
    least_squares,
    orbit_at,
    periodic_orbit,
    pins,
    stability_of,
    state_weights,
)
from .parametric import checked_scene_at, same_scene
from .stroboscopic import EVENT_LOG, MapValue, MapWork, StroboscopicMap
from .vertex import parabola_vertex

#: Bifurcation kinds; the last two are kinks of the branch (``Bifurcation.kink``).
KINDS = ("fold", "period-doubling", "torus", "symmetry-breaking", "grazing", "stick-slip")

#: Arclength steps (scaled units, see the module's docstring): the largest by default,
#: the first as a fraction of the largest, and the smallest before the branch is given up.
LARGEST_STEP = 1.0
FIRST_STEP = 0.1
SMALLEST_STEP = 1e-5
#: The arclength step below which a failing step is taken for a kink of the branch, and
#: the parameter steps (fractions of |stop − start|, longest first: the kink itself is
#: then located by ``locate_kink``) tried across it.
KINK_STEP = 1e-3
KINK_JUMPS = (1e-3, 1e-4)
#: A kink is located by bisection on the parameter to this fraction of the range, in at
#: most ``KINK_HALVINGS`` halvings of the step it lies in.
KINK_WIDTH = 1e-6
KINK_HALVINGS = 8
#: Bifurcations this close (a fraction of the range) are one.
SAME = 1e-6
#: A corrector whose residual stops falling (by less than half an iteration) within
#: this many times the tolerance has met the map's own integration noise: it has converged.
NOISE_FLOOR = 10.0
#: How far from a period doubling (or a symmetry-breaking point) the new branch is first
#: sought (scaled units).
DOUBLED_OFFSET = 1e-3
#: Corrector iterations before a step is halved; a step that converged in at most
#: ``EASY_ITERATIONS`` grows by ``GROWTH``.
CORRECTOR_ITERATIONS = 10
EASY_ITERATIONS = 5
GROWTH = 1.5
#: A corrector keeps its chord matrix while each step lowers the residual this many
#: times; a slower one forms the matrix at the iterate.
CHORD_DROP = 8.0
#: The relative residual GMRES solves the branch's tangent to (``jacobian="krylov"``).
KRYLOV_TANGENT = 1e-10
#: How much larger than the state scale an orbit grows before the scale follows it.
RESCALE = 2.0
#: The least cosine between consecutive tangents; a sharper turn halves the step, unless
#: the orbits' switches changed between the two points (a kink).
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
    the orbits for "fold", "period-doubling" and "torus"; for the kinks "grazing" and
    "stick-slip", the middle of ``bracket``, the parameters on either side of the change
    after its bisection, the ``orbit`` the one on the far side).
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

    @property
    def kink(self) -> bool:
        """Whether it is a kink of the branch (a change of the orbits' switches, where the
        branch is not smooth): "grazing" or "stick-slip"."""
        return self.kind in ("grazing", "stick-slip")


@dataclass(frozen=True)
class Branch:
    """A family of periodic orbits of ``periods`` excitation periods along a parameter.

    ``parameter[i]`` and ``orbits[i]`` are its points, in the order continued (the
    parameter turns back at a fold); ``bifurcations`` the changes met between them;
    ``name`` the parameter's name; ``ended`` why the continuation stopped; ``notes`` what
    it did beyond its steps (an orbit found from a transient where Newton from a
    neighbour failed).
    """

    parameter: np.ndarray
    orbits: tuple[PeriodicOrbit, ...]
    bifurcations: tuple[Bifurcation, ...]
    periods: int
    name: str
    ended: str
    notes: tuple[str, ...] = ()

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
        """Per point, the Floquet multipliers by descending modulus (complex); where the
        orbits hold only their leading ones (``jacobian="krylov"``), as many columns as
        the most any holds, NaN beyond an orbit's own."""
        width = max(len(orbit.multipliers) for orbit in self.orbits)
        table = np.full((len(self.orbits), width), complex(math.nan))
        for row, orbit in zip(table, self.orbits):
            row[:len(orbit.multipliers)] = orbit.multipliers
        return table


def continuation(scene_at: Callable[[float], Scene], start: float, stop: float, *,
                 periods: int = 1, guess=None, step: float | None = None,
                 max_step: float = LARGEST_STEP, max_points: int = 1000,
                 method: Adaptive | Accuracy | Exponential = TANGENT_METHOD,
                 tolerance: float = ORBIT_TOLERANCE,
                 event_tolerance: float = EVENT_TOLERANCE,
                 transient: int = 100, from_bifurcation: Bifurcation | None = None,
                 parameter: str = "value", progress: Callable | None = None,
                 symmetry: str | None = None, jacobian: str | None = None,
                 stability: bool = True) -> Branch:
    """The branch of periodic orbits of ``scene_at(p)`` from p = ``start`` towards ``stop``.

    Pseudo-arclength continuation (see the module's docstring): it follows the branch
    through folds, where the parameter turns back, and across kinks, where the orbits'
    switches change, and ends where the parameter leaves [start, stop] (the last point
    on ``stop`` exactly when it gets there), after ``max_points`` points, or where no
    step as small as ``SMALLEST_STEP`` converges and no jump across succeeds.

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
    method, tolerance, event_tolerance, transient, jacobian
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
    stability : bool
        Compute each orbit's multipliers and look for the smooth bifurcations (True,
        default); with False, the orbits have none (``PeriodicOrbit.stable`` a
        ValueError), and only folds (the parameter turning back) and kinks are found.

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
    check_instance("continuation", "method", method, (Adaptive, Accuracy, Exponential),
                   expected="Adaptive(...), Accuracy(...) or Exponential(...)")
    check_real("continuation", "tolerance", tolerance, low=SMALLEST_TOLERANCE, high=1e-3)
    check_event_tolerance("continuation", event_tolerance)
    check_instance("continuation", "parameter", parameter, str, expected="a name (str)")
    check_instance("continuation", "stability", stability, bool, expected="True or False")
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
    if jacobian is not None:
        check_choice("continuation", "jacobian", jacobian, JACOBIANS)
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
    first_map = StroboscopicMap(scene=scene_at(start), cyclic=cyclic)
    solver = Solver(scene_at=scene_at, span=span,
                    low=min(start, stop), high=max(start, stop), method=method,
                    tolerance=tolerance, event_tolerance=event_tolerance, cyclic=cyclic,
                    jacobian=jacobian_kind("continuation", jacobian, first_map),
                    stability=stability)
    if from_bifurcation is None:
        first = periodic_orbit(solver.scene_at(start), periods, guess, method=method,
                               transient=transient, tolerance=tolerance,
                               event_tolerance=event_tolerance,
                               symmetry="none" if cyclic is None else "cyclic",
                               jacobian=solver.jacobian, stability=False)
        solver.notes.extend(first.notes)
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
    """A converged point of the branch: u = (W y, p / span), the map's value there (with
    its Jacobian where it was formed there: ``stroboscopic.MapValue``) and ∂φ/∂p, its
    unit tangent (scaled), and the map it was evaluated on."""

    u: np.ndarray
    parameter: float
    periods: int
    value: MapValue
    rate: np.ndarray      # ∂φ/∂p
    map: StroboscopicMap
    tangent: np.ndarray | None = None

    def with_tangent(self, tangent):
        return dataclasses.replace(self, tangent=tangent)

    def with_value(self, value):
        return dataclasses.replace(self, value=value)

    @property
    def dense(self) -> bool:
        """Whether its value holds the map's whole Jacobian."""
        return self.value.columns is not None and self.value.columns.shape[1] == len(
            self.u) - 1


@dataclass
class Solver:
    """The continuation's maps and steps; ``weights`` W scale the state (set at the
    branch's first orbit), ``jacobian`` says how its linear systems are solved
    (``orbits.JACOBIANS``), ``stability`` whether the orbits' multipliers are found,
    ``notes`` what the branch did beyond its steps (``Branch.notes``)."""

    scene_at: Callable
    span: float
    low: float
    high: float
    method: object
    tolerance: float
    event_tolerance: float
    cyclic: CyclicSymmetry | None = None
    jacobian: str = "dense"
    stability: bool = True
    weights: np.ndarray | None = None
    work: MapWork = field(default_factory=MapWork)
    notes: list = field(default_factory=list)

    # ---- the map and its derivatives -------------------------------------------------------

    def state(self, u):
        return u[:-1] / self.weights

    def map_at(self, p, periods) -> StroboscopicMap:
        """The stroboscopic map of the scene at p (the branch's symmetry checked to hold
        there), its work counted with the branch's."""
        scene = self.scene_at(p)
        cyclic = None if self.cyclic is None else self.symmetric(scene, p)
        return StroboscopicMap(scene=scene, periods=periods, method=self.method,
                               event_tolerance=self.event_tolerance, cyclic=cyclic,
                               work=self.work)

    def evaluate(self, y, p, periods, rate=None):
        """The map's value at (y, p) (the state's run), its map, and ∂φ/∂p (by a
        forward difference unless ``rate`` is given)."""
        found = self.map_at(p, periods)
        value = found.value(y)
        if rate is None:
            h = PARAMETER_DIFFERENCE * max(abs(p), self.span)
            rate = (self.map_at(p + h, periods)(y) - value.end) / h
        return value, found, rate

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

    def pins(self, point_map, value) -> np.ndarray:
        """The rows of the offsets ``value``'s run kept stuck all through (``neutral``),
        scaled: c W⁻¹ (none on a symmetric ring's reduced map)."""
        return pins(point_map, value) / self.weights[None, :]

    def product(self, point_map, y):
        """z ↦ W (M − I) W⁻¹ z at y, by one run of a tangent column."""
        w = self.weights

        def apply(z):
            return w * point_map.products(y, z / w).columns[:, 0] - z
        return apply

    def linear_system(self, point, rows, relative=None):
        """The scaled Jacobian of the branch's equations at ``point``: (A, b) with
        A = W (M − I) W⁻¹ (a matrix where the point holds M, else its product: for a
        solve to the ``relative`` residual, as loose as that allows,
        ``StroboscopicMap.for_solve``) and b = W ∂φ/∂p span, and the pins' ``rows``."""
        w = self.weights
        rate = w * point.rate * self.span
        if point.dense:
            return w[:, None] * (point.value.columns - np.eye(len(w))) / w[None, :], rate
        point_map = point.map if relative is None else point.map.for_solve(relative)
        return self.product(point_map, point.value.start), rate

    def solve(self, system, rate, rows, border, right, tolerance=None):
        """Δu of [A, b] Δu = right[:N], ``border`` · Δu = right[N], rows (on the state
        part) · Δu = right[N + 1:] — least squares where A is a matrix, else GMRES on
        the system bordered by the rows' transposes (``orbits.newton_step``)."""
        size = len(rate)
        m = len(rows)
        if isinstance(system, np.ndarray):
            matrix = np.vstack([np.column_stack([system, rate]), border,
                                np.column_stack([rows, np.zeros(m)])])
            return least_squares(matrix, right), 0

        def product(v):
            du, pin = v[:size + 1], v[size + 1:]
            top = system(du[:size]) + rate * du[size] + rows.T @ pin
            return np.concatenate([top, [border @ du], rows @ du[:size]])

        solved = gmres(product, right,
                       tolerance=KRYLOV_TANGENT if tolerance is None else tolerance,
                       most=size + 1 + m)
        return solved.x[:size + 1], solved.iterations

    def point(self, y, p, periods):
        value, found, rate = self.evaluate(y, p, periods)
        if self.jacobian == "dense":
            value = value.with_tangent_of(found.dense(y))
        return Point(np.append(self.weights * y, p / self.span), p, periods, value, rate,
                     found)

    def tangent(self, point, reference):
        """The unit kernel vector of the scaled Jacobian (the pinned offsets held),
        oriented along ``reference``."""
        rows = self.pins(point.map, point.value)
        system, rate = self.linear_system(point, rows)
        right = np.zeros(len(point.u) + len(rows))
        right[len(point.u) - 1] = 1.0
        tangent, _ = self.solve(system, rate, rows, reference, right)
        tangent /= np.linalg.norm(tangent)
        return tangent if tangent @ reference >= 0.0 else -tangent

    # ---- corrector -------------------------------------------------------------------------

    def correct(self, predicted, normal, offset, periods, reach, fixed=None, linear=None,
                pinned=None, formed=True):
        """Newton on W(φ(y, p) − y) = 0, normal · u = offset, from u = ``predicted``, the
        offsets of the contacts stuck all through pinned at their values in ``pinned``
        (a state; default the prediction's).

        A dense Jacobian is taken from ``linear`` (a ``Point`` near the prediction: a
        chord) while each step lowers the residual ``CHORD_DROP`` times, and formed anew
        at the iterate where not; with ``jacobian="krylov"`` each step solves by GMRES on
        the iterate's products. Returns the converged ``Point`` (its Jacobian formed at
        it where dense and ``formed``) and the iterations it took, or raises
        ``ConvergenceError``, also when an update is longer than ``reach`` (the corrector
        is leaving for another branch).
        """
        u = predicted.copy()
        rate = None  # ∂φ/∂p at the prediction serves every iteration (a chord method)
        last = math.inf
        target = self.state(predicted) if pinned is None else pinned
        dense = self.jacobian == "dense"
        for iteration in range(CORRECTOR_ITERATIONS):
            p = u[-1] * self.span if fixed is None else fixed
            y = self.state(u)
            try:
                value, found, rate = self.evaluate(y, p, periods, rate)
            except ValueError as error:  # scene_at refuses p: the corrector went astray
                raise ConvergenceError(f"the corrector reached p = {p:.9g}, where "
                                       f"scene_at says: {error}") from error
            residual = self.weights * (value.end - y)
            constraint = normal @ u - offset
            size = np.abs(residual).max()
            stalled = NOISE_FLOOR * self.tolerance >= size > last / 2.0
            if (size <= self.tolerance or stalled) and abs(constraint) <= 1e-12:
                point = Point(u, p, periods, value, rate, found)
                if dense and formed:
                    point = point.with_value(value.with_tangent_of(found.dense(y)))
                return point, iteration
            if linear is None or not dense or size * CHORD_DROP > last:
                linear = Point(u, p, periods, found.dense(y) if dense else value, rate,
                               found)
            last = size
            rows = self.pins(found, value)
            relative = forcing(size, self.tolerance)
            system, slope = self.linear_system(linear, rows, relative)
            right = np.concatenate([residual, [constraint], rows @ (u[:-1] - self.weights
                                                                  * target)])
            change, _ = self.solve(system, slope, rows, normal, right, tolerance=relative)
            if np.linalg.norm(change) > reach:
                raise ConvergenceError(f"a corrector step of {np.linalg.norm(change):.3g} "
                                       f"leaves the prediction's reach {reach:.3g}")
            u = u - change
        raise ConvergenceError(f"no convergence in {CORRECTOR_ITERATIONS} corrector steps "
                               f"(residual {last:.3g})")

    def advance(self, point, sigma):
        """The point at arclength ``sigma`` along ``point``'s tangent."""
        predicted = point.u + sigma * point.tangent
        return self.correct(predicted, point.tangent, point.tangent @ predicted,
                            point.periods, reach=abs(sigma), linear=point,
                            pinned=self.state(point.u))

    def at_parameter(self, point, target, predicted, reach, linear=None, formed=True):
        """The point of the branch at p = ``target`` from the prediction ``predicted`` (a
        scaled u), its corrector's updates no longer than ``reach``, the offsets stuck
        all through pinned at ``point``'s (``correct``)."""
        predicted = predicted.copy()
        predicted[-1] = target / self.span
        normal = np.zeros(len(predicted))
        normal[-1] = 1.0
        return self.correct(predicted, normal, target / self.span, point.periods,
                            reach=reach, fixed=target, linear=linear,
                            pinned=self.state(point.u), formed=formed)[0]

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
                if new.tangent @ point.tangent < TURN and not self.kinked(point, new):
                    raise ConvergenceError("the branch turns too sharply")
            except SimulationError as error:
                sigma /= 2.0
                new = None
                if sigma < KINK_STEP and crossing:
                    crossing = False
                    new = self.across(points)
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
                        end = self.at_parameter(
                            point, target, point.u + fraction * (new.u - point.u),
                            reach=abs(fraction) * float(np.linalg.norm(new.u - point.u))
                            + abs(sigma), linear=point)
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
                      ended=ended, notes=tuple(self.notes))

    def kinked(self, a, b) -> bool:
        """Whether the orbits' switches differ between points a and b: the branch has a
        kink between them, where its tangent may turn as sharply as it likes."""
        return switch_counts(a) != switch_counts(b)

    def across(self, points) -> Point | None:
        """The branch a fixed parameter step beyond its last point, for each step of
        ``KINK_JUMPS`` of the range in turn (the parameter moving as the last point's
        tangent does): Newton on the orbit alone at that parameter, from the secant
        through the last two points extrapolated there (from the last point's orbit
        where it has no predecessor); failing that, from a transient at that parameter
        (said in ``Branch.notes``). None where none converges."""
        point = points[-1]
        direction = math.copysign(1.0, point.tangent[-1])
        before = points[-2] if len(points) > 1 else None
        for jump in KINK_JUMPS:
            p = point.parameter + direction * jump * self.span
            if not self.low <= p <= self.high:
                return None
            predicted = point.u.copy()
            if before is not None and before.parameter != point.parameter:
                slope = (point.u - before.u) / (point.parameter - before.parameter)
                predicted = point.u + slope * (p - point.parameter)
            try:
                new = self.at_parameter(point, p, predicted, reach=math.inf, linear=point)
            except SimulationError:
                continue
            return self.oriented(new, point, direction)
        return self.restarted(point, direction)

    def oriented(self, new, point, direction):
        """``new`` with its tangent, oriented in the parameter's ``direction``: the
        secant across a kink, mostly the orbit's change, need not point along the
        branch beyond it."""
        tangent = self.tangent(new, new.u - point.u)
        return new.with_tangent(tangent if tangent[-1] * direction >= 0.0 else -tangent)

    def restarted(self, point, direction) -> Point | None:
        """The orbit a ``KINK_JUMPS[-1]`` step of the range beyond ``point``, from a
        transient there (``periodic_orbit``); None where it too fails."""
        p = point.parameter + direction * KINK_JUMPS[-1] * self.span
        if not self.low <= p <= self.high:
            return None
        try:
            orbit = periodic_orbit(self.scene_at(p), point.periods, method=self.method,
                                   tolerance=self.tolerance,
                                   event_tolerance=self.event_tolerance,
                                   symmetry="none" if self.cyclic is None else "cyclic",
                                   jacobian=self.jacobian, stability=False)
        except SimulationError:
            return None
        self.notes.append(f"no step from p = {point.parameter:.9g} converged; the branch "
                          f"was taken up again at p = {p:.9g} from a transient")
        y = from_dofs(orbit.scene.arrays.layout, orbit.state)
        return self.oriented(self.point(y, p, point.periods), point, direction)

    def rescaled(self, point):
        """``point`` in coordinates whose state scale has grown to its orbit's, once the
        orbit is ``RESCALE`` times larger than the scale: steps stay a fraction of the
        orbit, however far from the first one the branch has grown."""
        weights = state_weights(point.map.scene, self.state(point.u))
        if weights[0] * RESCALE > self.weights[0]:
            return point
        change = np.append(weights / self.weights, 1.0)
        self.weights = weights
        tangent = change * point.tangent
        return dataclasses.replace(point, u=change * point.u,
                                   tangent=tangent / np.linalg.norm(tangent))

    def orbit(self, point, iterations):
        y = self.state(point.u)
        residual = np.abs(self.weights * (point.value.end - y)).max()
        value = point.value
        return orbit_at(point.map.scene, point.periods, y, value, residual,
                        1.0 / self.weights[0], iterations, point.map, 100, False,
                        stability=self.stability, jacobian=self.jacobian,
                        weights=self.weights)

    def record(self, points, orbits, bifurcations, new):
        """Append ``new`` and what changed since the last point: the smooth bifurcations
        located between them, and a kink where the orbits' switches changed
        (``locate_kink``); a change at the parameter of one already found is that one."""
        last, before = points[-1], orbits[-1]
        orbit = self.orbit(new, 0)
        index = len(points) - 1
        found = []
        if self.stability:
            for kind, test in smooth_changes(last, before, new, orbit, self.multipliers,
                                             symmetric=self.cyclic is not None):
                located = self.locate(kind, test, last, new, index)
                if located is not None:
                    found.append(located)
        elif last.tangent[-1] * new.tangent[-1] < 0.0:
            found.append(self.locate("fold", lambda point: point.tangent[-1], last, new,
                                     index))
        if orbit.switches != before.switches:
            found.append(self.locate_kink(last, before, new, orbit, index))
        bifurcations[:] = merged(bifurcations, found, self.span)
        points.append(new)
        orbits.append(orbit)

    def locate_kink(self, a, orbit_a, b, orbit_b, index) -> Bifurcation:
        """The kink between points a and b, whose orbits' switches differ: bisection on
        the parameter, each middle solved at a fixed parameter from the chord between
        them, to ``KINK_WIDTH`` of the range or ``KINK_HALVINGS`` halvings (where several
        changes lie between a and b, the one nearest b); reported with the orbit on b's
        side of the final bracket and its parameter at that bracket's middle (the
        bracket itself in ``Bifurcation.bracket``)."""
        kind = "stick-slip" if _stick_phases(orbit_a) != _stick_phases(orbit_b) else "grazing"
        low, high = (a, orbit_a), (b, orbit_b)
        for _ in range(KINK_HALVINGS):
            if abs(high[0].parameter - low[0].parameter) <= KINK_WIDTH * self.span:
                break
            middle = self.middle(low[0], high[0], a, b)
            if middle is None:
                break
            if switch_counts(middle) == orbit_b.switches:
                high = (middle, None)
            else:  # a's switches, or a third sequence: the change nearest b lies beyond
                low = (middle, None)
        near = high[0]
        orbit = orbit_b if near is b else self.orbit(near.with_tangent(b.tangent), 0)
        return Bifurcation(kind, 0.5 * (low[0].parameter + near.parameter), orbit,
                           complex(math.nan), index,
                           (float(low[0].parameter), float(near.parameter)))

    def middle(self, low, high, a, b) -> Point | None:
        """The point of the branch at the parameter midway between ``low`` and ``high``,
        from the chord between them, its offsets stuck all through pinned at ``low``'s
        (``a``'s monodromy its chord), else at ``high``'s (``b``'s); None where neither
        converges (a pinned offset the contact's friction no longer holds there)."""
        p = 0.5 * (low.parameter + high.parameter)
        guess = 0.5 * (low.u + high.u)
        reach = float(np.linalg.norm(high.u - low.u))
        for side, chord in ((low, a), (high, b)):
            try:
                return self.at_parameter(side, p, guess, reach, linear=chord, formed=False)
            except SimulationError:
                continue
        return None

    def multipliers(self, point) -> np.ndarray:
        """The multipliers of ``point``'s orbit, the neutral directions' left out: of its
        whole monodromy where formed (dense), else Arnoldi's leading ones."""
        rows = pins(point.map, point.value)
        y = self.state(point.u)
        found = stability_of(point.map, y, point.value, self.weights, self.jacobian,
                             len(rows))
        return tested(found.multipliers, len(rows))

    def locate(self, kind, test, a, b, index) -> Bifurcation | None:
        """The zero of ``test`` between points a and b (``bracketed_zero`` on the
        arclength from a); None where ``test`` has the same sign at both, or, for a
        multiplier's test, where it jumps through 0 rather than crossing it (multipliers
        that changed their count without crossing the circle: two real ones that meet and
        leave the real axis together, say)."""
        located = bracketed_zero(test, a, b, self.trial, (SimulationError,))
        if located is None:
            return None
        best, best_value, bracketed = located
        if bracketed and kind != "fold" and best_value > JUMP:
            return None  # |μ| jumps there: two multipliers met, none crossed the circle
        orbit = self.orbit(best, 0)
        multiplier = critical(kind, orbit.tested_multipliers) if len(orbit.multipliers) \
            else complex(math.nan)
        return Bifurcation(kind, best.parameter, orbit, multiplier,
                           index, (a.parameter, b.parameter))

    def trial(self, a, sigma):
        """The point at arclength ``sigma`` from ``a``, with its tangent."""
        trial = self.advance(a, sigma)[0]
        return trial.with_tangent(self.tangent(trial, a.tangent))

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
        values, vectors = np.linalg.eig(orbit.monodromy_matrix())
        k = np.argmin(np.abs(values - multiplier))
        w = self.weights
        away = np.append(w * from_dofs(layout, np.real(vectors[:, k])), 0.0)
        away /= np.linalg.norm(away)
        base = np.append(w * state, bifurcation.parameter / self.span)
        size = DOUBLED_OFFSET
        point, _ = self.correct(base + size * away, away, away @ base + size, periods,
                                reach=1.0)
        return point, point.u - base


def bracketed_zero(test, a, b, trial, failures):
    """Where ``test`` crosses zero between two points of a branch, a and b (each with
    ``u`` and a unit ``tangent``): the Illinois (modified regula falsi) method on the
    arclength σ from a, ``trial(a, σ)`` giving the branch's point there, until the bracket
    is ``LOCATED`` of the arclength from a to b, at most ``LOCATING_STEPS`` trials, or
    until a trial raises one of ``failures``. Returns None where ``test`` has the same
    sign at a and b, else (the point of least |test| among b and the trials, that
    |test|, whether the bracket closed)."""
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
            point = trial(a, sigma)
        except failures:
            break
        value = test(point)
        if abs(value) < best_value:
            best, best_value = point, abs(value)
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
    return best, best_value, bracketed


def merged(bifurcations, found, span: float) -> list:
    """``bifurcations`` and then each of ``found`` (None for none) whose parameter is not
    within ``SAME`` of ``span`` of one kept already: a bifurcation located twice (a fold
    approached from both sides), or two at one parameter (a fold at a kink), is one."""
    kept = list(bifurcations)
    for bifurcation in found:
        if bifurcation is not None and not any(
                abs(bifurcation.parameter - other.parameter) <= SAME * span for other in kept):
            kept.append(bifurcation)
    return kept


def switch_counts(point) -> dict:
    """How many switches of each (interface, kind) the orbit of ``point`` makes, from a
    run of its map (``PeriodicOrbit.switches``, without the outputs)."""
    found = point.map
    y = point.value.start
    run = integrate(found.scene, found.periods, method=found.method, samples_per_period=1,
                    event_tolerance=found.event_tolerance, initial=state_parts(found.scene, y),
                    event_capacity=EVENT_LOG).run
    period = found.scene.excitation_period
    edge, end = EDGE * period, found.periods * period
    counts: dict[tuple[int, str], int] = {}
    for t, e, k in zip(run.events.time, run.events.interface, run.events.kind):
        if edge < t < end - edge:
            switch = (int(e), EventKind(k).name.lower())
            counts[switch] = counts.get(switch, 0) + 1
    return counts


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


def smooth_changes(a, orbit_a, b, orbit_b, multipliers, symmetric=False):
    """(kind, test function of a point) of each smooth bifurcation between a and b, from
    their orbits' multipliers (the neutral directions' left out:
    ``PeriodicOrbit.tested_multipliers``) and ``multipliers(point)``, those of any point
    between. The test functions are continuous along the branch and change sign at the
    bifurcation: the tangent's parameter component (fold); and |μ| − 1 of the multiplier
    that crosses the unit circle (``_modulus_crossing``): among the real negative ones
    (period doubling), the complex pairs (torus), or, on a ``symmetric`` branch where no
    fold explains it, the real positive ones (symmetry breaking)."""
    changes = []
    fold = a.tangent[-1] * b.tangent[-1] < 0.0
    if fold:
        changes.append(("fold", lambda point: point.tangent[-1]))
    (doubling_a, torus_a, rising_a), (doubling_b, torus_b, rising_b) = (
        _counts(_tested(orbit_a)), _counts(_tested(orbit_b)))
    if doubling_a != doubling_b:
        changes.append(("period-doubling", _modulus_crossing(
            multipliers, lambda mu: _real(mu) & (mu.real < 0.0), min(doubling_a, doubling_b))))
    if torus_a != torus_b:
        changes.append(("torus", _modulus_crossing(
            multipliers, lambda mu: ~_real(mu) & (mu.imag > 0.0), min(torus_a, torus_b) // 2)))
    if symmetric and not fold and rising_a != rising_b:
        changes.append(("symmetry-breaking", _modulus_crossing(
            multipliers, lambda mu: _real(mu) & (mu.real > 0.0), min(rising_a, rising_b))))
    return changes


def _tested(orbit) -> np.ndarray:
    """The multipliers the bifurcation tests read: a ``PeriodicOrbit``'s less its neutral
    directions' (``tested_multipliers``); a ``HarmonicOrbit``'s (Hill's) as they are."""
    return orbit.tested_multipliers if isinstance(orbit, PeriodicOrbit) else orbit.multipliers


def _modulus_crossing(multipliers, kept, rank):
    """The test function |μ| − 1 of the multiplier, of those that ``kept`` keeps (one of
    each complex pair), ``rank`` from the largest in modulus (0: the largest): where
    ``rank`` of them lie outside the unit circle at one end of the interval and one more
    at the other, it is the one that crossed, and the function changes sign exactly
    there. It varies as that multiplier does, as a product over all of them (det(M + I),
    the bialternate product, of some 10⁴ factors on a ring of many sectors) does not: its
    size changes by orders of magnitude over an interval, which the secant method follows
    only in as many halvings. −1 where fewer than rank + 1 are kept."""
    def test(point):
        found = multipliers(point)
        moduli = np.sort(np.abs(found[kept(found)]))[::-1]
        return float(moduli[rank]) - 1.0 if rank < len(moduli) else -1.0
    return test
