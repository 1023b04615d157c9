"""Branches of harmonic-balance orbits in one parameter: pseudo-arclength continuation.

The unknowns are u = (z / s, p / span): the contact coordinates' coefficients (z = B q
over the nodes' own degrees of freedom, ``model``: the same coordinates at every p,
however the engine's modal basis turns with the speed) over their scale s at the
branch's first orbit, and the parameter over |stop − start|
(``steady.continuation`` does the same with the exact orbits' states). Each step
predicts along the tangent τ, the kernel of [∂R/∂z, ∂R/∂p] (∂R/∂p by a forward
difference: the scene at p + h condensed again), and corrects by Newton on

    R(z, p) = 0,        τ · (u − u_predicted) = 0,

a step that converges in few iterations growing the next, one that does not halving
it. The balance is piecewise smooth (a contact's samples change from stick to slip, or
from open to closed, one at a time), so the branch has small kinks where its tangent
jumps: a turn sharper than ``TURN`` is refused (the corrector may have left for another
branch) down to steps of ``KINK_STEP``, and taken below it. A fold is where τ's
parameter component changes sign; it is located on the branch by the secant method on
that component. Hill's multipliers (``hill``) are watched as
``steady.continuation`` watches the exact ones: a real one through −1 (period
doubling), a complex pair through the unit circle (torus), each located by the secant
method on |μ| − 1 of the multiplier that crosses — between orbits whose contact forces
are smooth only (``HarmonicOrbit.smooth``), where Hill's method is to be trusted
(``hill``): where contacts stick and slip, or open and close, the orbits keep Hill's
multipliers but no bifurcation is read from them.

The branch is a ``Branch`` whose orbits are ``HarmonicOrbit``s (their series by the
nodes' own degrees of freedom), read as a branch of exact orbits is (amplitudes,
energies, multipliers, the frequency shift).
"""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass

import numpy as np
import scipy.linalg

from contact_laws import check_callable, check_calls_with, check_instance, check_int, \
    check_real

from ...run.simulate import MAX_PERIODS
from ..continuation import (
    FIRST_STEP,
    KINK_STEP,
    LARGEST_STEP,
    SMALLEST_STEP,
    TURN,
    Bifurcation,
    Branch,
    bracketed_zero,
    critical,
    smooth_changes,
)
from ..orbits import ConvergenceError
from ..parametric import checked_scene_at
from .balance import (
    BALANCE_TOLERANCE,
    MOST_HARMONICS,
    MOST_SAMPLES,
    Balance,
    balance_of,
    first_guess,
    orbit_from,
    solve,
)
from .fourier import samples_for
from .newton import NewtonOutcome
from .orbit import HarmonicOrbit

#: Corrector iterations before a step is halved; a step that converged in at most
#: ``EASY_ITERATIONS`` grows by ``GROWTH``; the corrector's first ``FRESH_JACOBIANS``
#: iterations compute the Jacobian, the rest keep the last (``Follower.correct``).
CORRECTOR_ITERATIONS = 10
EASY_ITERATIONS = 4
FRESH_JACOBIANS = 2
GROWTH = 1.5
#: Relative step of the forward difference ∂R/∂p (of max(|p|, |stop − start|)).
PARAMETER_DIFFERENCE = 1e-7


@dataclass(frozen=True, eq=False)
class Point:
    """A converged point: u, its parameter, its balance, the map's value there (R's
    Jacobian in z and ∂R/∂p, the contact forces) and its unit tangent."""

    u: np.ndarray
    parameter: float
    balance: Balance
    outcome: NewtonOutcome
    jacobian: np.ndarray      # [∂R/∂z ∂R/∂p] in the scaled unknowns
    tangent: np.ndarray | None = None

    def with_tangent(self, tangent):
        return Point(self.u, self.parameter, self.balance, self.outcome, self.jacobian,
                     tangent)


@dataclass
class Follower:
    """The continuation's maps and steps, the unknowns scaled by ``scale`` and ``span``."""

    scene_at: Callable
    harmonics: int
    periods: int
    samples: int
    span: float
    low: float
    high: float
    tolerance: float
    stability: bool
    symmetry: str | None = None
    scale: float = 1.0

    def balance(self, p: float) -> Balance:
        return balance_of(self.scene_at(p), self.harmonics, self.periods, self.samples,
                          "harmonic_continuation", self.symmetry)

    def split(self, u):
        """(z, p) of the scaled unknowns."""
        shape = (2 * self.harmonics + 1, -1)
        return u[:-1].reshape(shape) * self.scale, u[-1] * self.span

    def evaluate(self, u, rate=None):
        """(R / scale, [∂R/∂z ∂R/∂p] scaled, the balance at p, the contact forces), with
        the scaled ∂R/∂p given as ``rate`` or by a forward difference."""
        z, p = self.split(u)
        balance = self.balance(p)
        residual, jacobian, forces = balance.evaluate(z, True)
        if rate is None:
            h = PARAMETER_DIFFERENCE * max(abs(p), self.span)
            shifted, _, _ = self.balance(p + h).evaluate(z, False)
            rate = (shifted - residual) / h * self.span / self.scale
        matrix = np.column_stack([jacobian, rate])
        return residual / self.scale, matrix, balance, forces

    def point(self, u, outcome_z=None) -> Point:
        residual, matrix, balance, forces = self.evaluate(u)
        z, p = self.split(u)
        size = float(np.abs(residual).max(initial=0.0)) * self.scale / balance.scale(z)
        outcome = NewtonOutcome(z, forces, size, 0, self.tolerance,
                                f"converged: residual {size:.3g} of the contacts' motion")
        return Point(u, p, balance, outcome, matrix)

    def tangent(self, point: Point, reference: np.ndarray) -> np.ndarray:
        """The unit kernel vector of ``point``'s Jacobian, oriented along ``reference``."""
        bordered = np.vstack([point.jacobian, reference])
        right = np.zeros(len(reference))
        right[-1] = 1.0
        try:
            tangent = np.linalg.solve(bordered, right)
        except np.linalg.LinAlgError:  # a singular border: the least-squares kernel
            tangent = np.linalg.lstsq(bordered, right, rcond=None)[0]
        tangent /= np.linalg.norm(tangent)
        return tangent if tangent @ reference >= 0.0 else -tangent

    def correct(self, predicted, normal, offset) -> tuple[Point, int]:
        """Newton on R(z, p) = 0, normal · u = offset from ``predicted``: the point and
        the iterations, or ``ConvergenceError``. Past ``FRESH_JACOBIANS`` iterations the
        last Jacobian is kept (chord steps, each a balance without the forces' Jacobian,
        a fifth of the cost on a patch of 45 contacts) for as long as a step at least
        halves the residual; the point keeps the last Jacobian computed, a step or two
        from it, for its tangent."""
        u = predicted.copy()
        rate = factor = matrix = None
        last = math.inf
        for iteration in range(CORRECTOR_ITERATIONS):
            fresh = factor is None or iteration < FRESH_JACOBIANS
            try:
                if fresh:
                    # ∂R/∂p from the prediction on (a chord in the parameter alone: over
                    # one step it changes by the step, and its difference is a second
                    # balance)
                    residual, matrix, balance, forces = self.evaluate(u, rate)
                    rate = matrix[:, -1]
                else:
                    residual, balance, forces = self.residual(u)
            except ValueError as error:  # scene_at refuses p: the corrector went astray
                raise ConvergenceError(f"the corrector reached p = {u[-1] * self.span:.9g}, "
                                       f"where scene_at says: {error}") from error
            z, p = self.split(u)
            size = float(np.abs(residual).max(initial=0.0)) * self.scale / balance.scale(z)
            constraint = normal @ u - offset
            if size <= self.tolerance and abs(constraint) <= 1e-12:
                outcome = NewtonOutcome(z, forces, size, iteration, self.tolerance,
                                        f"converged: residual {size:.3g} of the contacts' "
                                        "motion")
                return Point(u, p, balance, outcome, matrix), iteration
            if not fresh and size > 0.5 * last:  # the chord stalls: a fresh Jacobian
                factor = None
                continue
            last = size
            if fresh:
                factor = scipy.linalg.lu_factor(np.vstack([matrix, normal]),
                                                check_finite=False)
            u = u - scipy.linalg.lu_solve(factor, np.append(residual, constraint),
                                          check_finite=False)
        raise ConvergenceError(f"no convergence in {CORRECTOR_ITERATIONS} corrector steps "
                               f"(residual {size:.3g})")

    def residual(self, u):
        """(R / scale, the balance at p, the contact forces) without Jacobians."""
        z, p = self.split(u)
        balance = self.balance(p)
        residual, _, forces = balance.evaluate(z, False)
        return residual / self.scale, balance, forces

    def advance(self, point: Point, sigma: float) -> tuple[Point, int]:
        predicted = point.u + sigma * point.tangent
        return self.correct(predicted, point.tangent, point.tangent @ predicted)

    def at_parameter(self, point: Point, target: float, sigma: float) -> Point:
        predicted = point.u + sigma * point.tangent
        predicted[-1] = target / self.span
        normal = np.zeros(len(predicted))
        normal[-1] = 1.0
        return self.correct(predicted, normal, target / self.span)[0]

    def orbit(self, point: Point) -> HarmonicOrbit:
        return orbit_from(point.balance, point.outcome, self.stability)

    # ---- the branch ------------------------------------------------------------------

    def follow(self, point, step, max_step, max_points, name, progress) -> Branch:
        points, orbits, bifurcations = [point], [self.orbit(point)], []
        ended = f"reached max_points = {max_points}"
        sigma = step
        while len(points) < max_points:
            try:
                new, iterations = self.advance(point, sigma)
                new = new.with_tangent(self.tangent(new, point.tangent))
                if new.tangent @ point.tangent < TURN and sigma >= KINK_STEP:
                    raise ConvergenceError("the branch turns too sharply")
            except (ConvergenceError, np.linalg.LinAlgError) as error:
                sigma /= 2.0
                if sigma < SMALLEST_STEP:
                    ended = (f"no step converged at p = {point.parameter:.9g} (the last "
                             f"try: {error})")
                    break
                continue
            if not self.low <= new.parameter <= self.high:
                target = self.high if new.parameter > self.high else self.low
                if target != point.parameter:
                    fraction = (target - point.parameter) / (new.parameter - point.parameter)
                    try:
                        end = self.at_parameter(point, target, fraction * sigma)
                    except (ConvergenceError, np.linalg.LinAlgError):
                        sigma /= 2.0
                        continue
                    end = end.with_tangent(self.tangent(end, point.tangent))
                    self.record(points, orbits, bifurcations, end)
                ended = f"reached p = {target:.9g}"
                break
            self.record(points, orbits, bifurcations, new)
            point = new
            if progress is not None:
                progress(len(points), point.parameter)
            if iterations <= EASY_ITERATIONS:
                sigma = min(sigma * GROWTH, max_step)
        return Branch(parameter=np.array([p.parameter for p in points]), orbits=tuple(orbits),
                      bifurcations=tuple(bifurcations), periods=self.periods, name=name,
                      ended=ended)

    def record(self, points, orbits, bifurcations, new: Point) -> None:
        """Append ``new`` with the bifurcations between the last point and it: those
        ``steady.continuation.smooth_changes`` finds, Hill's multipliers standing for the
        monodromy's eigenvalues; the changes of Hill's multipliers only between orbits
        whose contact forces are smooth (``HarmonicOrbit.smooth``), where they are to be
        trusted, folds everywhere."""
        last, before = points[-1], orbits[-1]
        orbit = self.orbit(new)
        index = len(points) - 1
        changes = smooth_changes(last, before, new, orbit, self.multipliers)
        if not (self.stability and before.smooth and orbit.smooth):
            changes = [(kind, test) for kind, test in changes if kind == "fold"]
        for kind, test in changes:
            found = self.locate(kind, test, last, new, index)
            if found is not None:
                bifurcations.append(found)
        points.append(new)
        orbits.append(orbit)

    def multipliers(self, point: Point) -> np.ndarray:
        """Hill's multipliers of ``point``'s orbit: those ``smooth_changes``' test
        functions read."""
        return self.orbit(point).multipliers

    def locate(self, kind, test, a: Point, b: Point, index: int) -> Bifurcation | None:
        """The zero of ``test`` between a and b (``bracketed_zero`` on the arclength from
        a, as ``steady.continuation``); None where the signs agree."""
        located = bracketed_zero(test, a, b, self.trial,
                                 (ConvergenceError, np.linalg.LinAlgError))
        if located is None:
            return None
        orbit = self.orbit(located[0])
        multiplier = critical(kind, orbit.multipliers) if len(orbit.multipliers) else \
            complex(math.nan)
        return Bifurcation(kind, located[0].parameter, orbit, multiplier, index,
                           (a.parameter, b.parameter))

    def trial(self, a: Point, sigma: float) -> Point:
        """The point at arclength ``sigma`` from ``a``, with its tangent."""
        trial = self.advance(a, sigma)[0]
        return trial.with_tangent(self.tangent(trial, a.tangent))


def harmonic_continuation(scene_at: Callable[[float], object], start: float, stop: float,
                          harmonics: int, *, periods: int = 1, guess=None,
                          samples: int | None = None, step: float | None = None,
                          max_step: float = LARGEST_STEP, max_points: int = 1000,
                          tolerance: float = BALANCE_TOLERANCE, stability: bool = True,
                          parameter: str = "value", symmetry: str | None = None,
                          progress: Callable | None = None) -> Branch:
    """The branch of harmonic-balance orbits of ``scene_at(p)`` from p = ``start``
    towards ``stop`` (module docstring): through folds, to where p leaves [start, stop]
    (the last point on ``stop`` exactly), after ``max_points`` points, or where no step as
    small as ``SMALLEST_STEP`` converges.

    Parameters
    ----------
    scene_at : callable
        p ↦ Scene, as for ``continuation``: the speed, an amplitude, a gap, …, or the
        excitation frequency f [Hz] at a fixed speed: a scene forced at a frequency of
        its own (``Excitation(frequency=f)``), whose speed sets the blades' stiffening
        and f the series' fundamental ω = 2π f / ``periods``.
    start, stop : float
        The parameter's range.
    harmonics, periods, samples, tolerance, stability
        As ``harmonic_balance`` (``stability``: Hill's multipliers at every point, and
        the period doublings and tori they show between smooth orbits; an eigenvalue
        problem of 2n(2H+1) a point, most of a point's cost on a large structure).
    guess : HarmonicOrbit or array, optional
        As ``harmonic_balance``'s, at ``start``.
    step, max_step, max_points, parameter, progress
        As ``continuation``: the first and largest arclength steps in the scaled
        unknowns, the most points, the parameter's name, ``progress(points, p)``.
    symmetry : None, "cyclic" or "none"
        As ``harmonic_balance``: a tuned ring forced in engine order is solved on one
        sector by default.

    Raises
    ------
    ConvergenceError
        The balance at ``start`` does not converge.

    Examples
    --------
    The Jenkins chain at its speed of 720 rpm, forced from 9.5 to 10.5 Hz::

        chain = scenes.jenkins_chain()
        def forced_at(f):
            return dataclasses.replace(chain, excitation=dataclasses.replace(
                chain.excitation, frequency=f))
        branch = harmonic_continuation(forced_at, 9.5, 10.5, 5, parameter="f [Hz]")
    """
    owner = "harmonic_continuation"
    check_callable(owner, "scene_at", scene_at, expected="a callable value -> Scene")
    start = check_real(owner, "start", start)
    stop = check_real(owner, "stop", stop)
    if start == stop:
        raise ValueError(f"{owner}: start and stop are both {stop}: give a range")
    harmonics = check_int(owner, "harmonics", harmonics, low=0, most=MOST_HARMONICS)
    periods = check_int(owner, "periods", periods, low=1, most=MAX_PERIODS)
    samples = samples_for(harmonics) if samples is None else check_int(
        owner, "samples", samples, low=2 * harmonics + 1, most=MOST_SAMPLES)
    check_real(owner, "tolerance", tolerance, low=1e-14, high=1e-2)
    check_instance(owner, "stability", stability, bool, expected="True or False")
    check_instance(owner, "parameter", parameter, str, expected="a name (str)")
    if progress is not None:
        check_calls_with(owner, "progress", progress, 2,
                         expected="None or a callable progress(points, p)")
    max_points = check_int(owner, "max_points", max_points, low=2)
    max_step = check_real(owner, "max_step", max_step, low=SMALLEST_STEP, high=1.0)
    step = FIRST_STEP * max_step if step is None else check_real(
        owner, "step", step, low=SMALLEST_STEP, high=max_step)
    span = abs(stop - start)
    try:
        checked_scene_at(owner, scene_at, start, start + 1e-3 * (stop - start))
    except (ValueError, TypeError) as error:
        if "scene_at" in str(error):
            raise
        raise type(error)(f"{owner}: scene_at refused the range start = {start:g} … "
                          f"stop = {stop:g}: {error}") from error
    follower = Follower(scene_at=scene_at, harmonics=harmonics, periods=periods,
                        samples=samples, span=span, low=min(start, stop),
                        high=max(start, stop), tolerance=tolerance, stability=stability,
                        symmetry=symmetry)
    first = follower.balance(start)
    found = solve(first, first_guess(first, guess, owner), tolerance)
    if not found.converged:
        raise ConvergenceError(f"{owner}: no orbit at p = {start:g}: {found.message}")
    follower.scale = first.scale(found.z)
    point = follower.point(np.append(found.z.ravel() / follower.scale,
                                     start / span))
    direction = np.zeros(len(point.u))
    direction[-1] = math.copysign(1.0, stop - start)
    point = point.with_tangent(follower.tangent(point, direction))
    return follower.follow(point, step, max_step, max_points, parameter, progress)
