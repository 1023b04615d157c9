"""The largest and smallest values of each response over a periodic orbit, where its
velocity crosses zero, to the integrator's accuracy rather than at samples.

A response r(t) = c·x(t) (a blade's x, or a component of a point) is sampled with its rate
ṙ = c·ẋ. Its maximum lies where ṙ falls through zero (or, where a switch makes ṙ jump, at
the switch). Between two samples t_k < t_{k+1} the cubic Hermite interpolant of (r, ṙ)
at both ends places that zero at t_c, within O(h⁴) of it; the orbit is run again from its
start to t_c, and from its r, ṙ there and the interpolant's curvature r̈ the extremum is

    r* = r(t_c) − ṙ(t_c)² / (2 r̈)

(the vertex of the parabola through the state at t_c): its error is of third order in
t_c − t*, far below the orbit's tolerance. Where a switch lies in the interval, the zero
of ṙ is searched for on states of the orbit run again to each trial instant. Of the
candidate intervals the two with the largest interpolated extremum are refined; a sampled
value larger than both is kept (an extremum at a switch, where ṙ jumps). The minimum is
the maximum of −r.

Every refinement of an orbit advances together: the instants they wait on are read from
one run of the orbit, sampled there from the dense output of the step that holds each
(``stroboscopic.StroboscopicMap.states_at``; a run to one instant otherwise, its last
step cut there). On the six eight-mode blades with 3-D elastic faces the extremes of 24
responses took 81 runs one instant at a time, 0.74 s, and take 6 runs in all this way.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ..run.simulate import integrate

#: Candidate intervals refined for each extremum of each response, and how far below the
#: best interpolated extremum (a fraction of the response's sampled spread) another may
#: lie and still be refined.
CANDIDATES = 2
MARGIN = 1e-3


@dataclass(frozen=True)
class Extremes:
    """Per response (``Scene.responses``): the largest and smallest value over the orbit
    [m] and the times they are reached [s] (from the orbit's start)."""

    maximum: np.ndarray
    minimum: np.ndarray
    time_of_maximum: np.ndarray
    time_of_minimum: np.ndarray


def orbit_extremes(scene, t, x, v, switches, state, *, responses=None,
                   states=None) -> Extremes:
    """The ``Extremes`` of an orbit from its samples ``t``, ``x``, ``ẋ`` over one whole
    orbit (first and last samples one orbit apart) and the times of its ``switches`` [s],
    each extremum refined on the orbit's exact states: ``state`` (time [s] → (x, ẋ) as
    ``x`` and ``v`` hold them: the orbit run again to that time; module docstring) or,
    where given, ``states`` (increasing times [s] → their states, from one run), which
    reads every refinement's next instant at once (``_in_lockstep``); of the responses
    whose positions ``responses`` lists (default: all of them)."""
    rows = scene.response_matrix
    if responses is not None:
        rows = rows[responses]
    r, rate = x @ rows.T, v @ rows.T
    searches, owners = [], []
    best = {1.0: [], -1.0: []}  # per sign, (sign · extremum, time) of each response
    for j in range(r.shape[1]):
        for sign in best:
            k = int(np.argmax(sign * r[:-1, j]))
            best[sign].append((sign * r[k, j], t[k]))
            for time, _ in _crossings(t, sign * r[:, j], sign * rate[:, j]):
                searches.append(_refinement(scene, time, rows[j], sign, t, r[:, j],
                                            rate[:, j], switches))
                owners.append((sign, j))
    for (sign, j), found in zip(owners, _in_lockstep(searches, state, states)):
        best[sign][j] = max(best[sign][j], found, key=lambda pair: pair[0])
    return Extremes(
        maximum=np.array([value for value, _ in best[1.0]]),
        minimum=np.array([-value for value, _ in best[-1.0]]),
        time_of_maximum=np.array([time for _, time in best[1.0]]),
        time_of_minimum=np.array([time for _, time in best[-1.0]]))


def _has_switch(t, k, switches) -> bool:
    """Whether a switch lies in the sample interval [t_k, t_k+1]."""
    return bool(np.any((switches >= t[k]) & (switches <= t[k + 1])))


def _interval(t, time) -> int:
    """The index k of the sample interval [t_k, t_k+1] that holds ``time``."""
    return min(max(int(np.searchsorted(t, time)) - 1, 0), len(t) - 2)


def sampled_peaks(t, x, v, rows) -> np.ndarray:
    """max |r| [m] of each response r = ``rows`` · x over a sampled run that need not be
    periodic (a transient's record): the largest sample of ±r, or, larger, the maximum of
    the cubic Hermite interpolant of (r, ṙ) in an interval where ṙ changes sign (within
    O(h⁴) of the motion's there, h the samples' spacing, where it is smooth)."""
    r, rate = x @ rows.T, v @ rows.T
    peaks = np.abs(r).max(axis=0)
    for j in range(r.shape[1]):
        for sign in (1.0, -1.0):
            found = _crossings(t, sign * r[:, j], sign * rate[:, j])
            if found:
                peaks[j] = max(peaks[j], found[0][1])
    return peaks


def _crossings(t, r, rate) -> list[tuple[float, float]]:
    """(t_c, interpolated maximum) of the ``CANDIDATES`` intervals where the rate falls
    through zero with the largest cubic Hermite maximum, best first; one whose maximum
    is below the best by more than ``MARGIN`` of the samples' spread is left out (the
    interpolant is far closer than that)."""
    found = []
    for k in np.flatnonzero((rate[:-1] > 0.0) & (rate[1:] <= 0.0)):
        h = t[k + 1] - t[k]
        root = _falling_root(r[k], r[k + 1], h * rate[k], h * rate[k + 1])
        if root is not None:
            found.append((t[k] + root * h, _hermite(r[k], r[k + 1], h * rate[k],
                                                    h * rate[k + 1], root)))
    found.sort(key=lambda pair: -pair[1])
    spread = float(np.ptp(r))
    return [pair for pair in found[:CANDIDATES] if pair[1] >= found[0][1] - MARGIN * spread]


def _hermite(p0, p1, m0, m1, s):
    """The cubic Hermite interpolant of values p0, p1 and slopes m0, m1 (per unit s) at
    s ∈ [0, 1]."""
    s2, s3 = s * s, s * s * s
    return ((2 * s3 - 3 * s2 + 1) * p0 + (s3 - 2 * s2 + s) * m0
            + (-2 * s3 + 3 * s2) * p1 + (s3 - s2) * m1)


def _hermite_slopes(p0, p1, m0, m1, s):
    """(first, second) derivatives in s of ``_hermite``."""
    first = ((6 * s * s - 6 * s) * p0 + (3 * s * s - 4 * s + 1) * m0
             + (-6 * s * s + 6 * s) * p1 + (3 * s * s - 2 * s) * m1)
    second = (12 * s - 6) * p0 + (6 * s - 4) * m0 + (-12 * s + 6) * p1 + (6 * s - 2) * m1
    return first, second


def _falling_root(p0, p1, m0, m1) -> float | None:
    """The s ∈ [0, 1] where the interpolant's slope falls through zero (m0 > 0 ≥ m1)."""
    a = 3 * (2 * p0 + m0 - 2 * p1 + m1)
    b = -6 * p0 - 4 * m0 + 6 * p1 - 2 * m1
    c = m0
    if abs(a) < 1e-14 * (abs(b) + abs(c)):
        roots = [-c / b] if b != 0.0 else []
    else:
        discriminant = b * b - 4 * a * c
        if discriminant < 0.0:
            return None
        root = np.sqrt(discriminant)
        q = -0.5 * (b + np.copysign(root, b))
        roots = [q / a, c / q] if q != 0.0 else [0.0]
    inside = [s for s in roots if -1e-12 <= s <= 1.0 + 1e-12
              and _hermite_slopes(p0, p1, m0, m1, s)[1] <= 0.0]
    return float(np.clip(min(inside), 0.0, 1.0)) if inside else None


def _refinement(scene, time, row, sign, t, r, rate, switches):
    """The search for the extremum in the sample interval holding the candidate time
    ``time`` (module docstring), as a generator: it yields each instant [s] whose exact
    state (x, ẋ) it is to be sent, and returns (sign · r*, t*). Where no switch lies in the
    interval the motion is smooth there: the state at ``time`` and the vertex of the
    parabola through it, with the interpolant's curvature. Else the zero of sign · ṙ, by
    the Illinois method on the states at its trial times, from the Hermite estimate
    ``time``."""
    k = _interval(t, time)
    if not _has_switch(t, k, switches):
        h = t[k + 1] - t[k]
        curvature = sign * _hermite_slopes(r[k], r[k + 1], h * rate[k], h * rate[k + 1],
                                           (time - t[k]) / h)[1] / (h * h)
        x, v = yield time
        value, slope = sign * float(row @ x), sign * float(row @ v)
        if curvature < 0.0:
            value -= slope * slope / (2.0 * curvature)
        return value, float(time)
    low, high = (t[k], sign * rate[k]), (t[k + 1], sign * rate[k + 1])
    best, trial, stale = (-np.inf, time), time, 0
    width = ROOT_WIDTH * scene.excitation_period
    for _ in range(ROOT_STEPS):
        x, v = yield trial
        value, slope = sign * float(row @ x), sign * float(row @ v)
        best = max(best, (value, trial))
        if slope > 0.0:
            low, stale = (trial, slope), stale + 1 if stale >= 0 else 1
        else:
            high, stale = (trial, slope), stale - 1 if stale <= 0 else -1
        if high[0] - low[0] < width or slope == 0.0:
            break
        weight_low = 0.5 if stale <= -2 else 1.0  # Illinois: halve the end kept twice
        weight_high = 0.5 if stale >= 2 else 1.0
        trial = (low[0] * weight_high * (-high[1]) + high[0] * weight_low * low[1]) / (
            weight_high * (-high[1]) + weight_low * low[1])
    return best


def _in_lockstep(searches, state, states) -> list:
    """What each of ``searches`` (``_refinement``) returns, all of them run together:
    each round the instants they wait on are read at once, by ``states`` (increasing
    times [s] → their states, one run) where given and the instants are past the start,
    else one by one by ``state``."""
    found = [None] * len(searches)
    waiting = {}
    for index, search in enumerate(searches):
        waiting[index] = next(search)
    while waiting:
        instants = sorted(set(waiting.values()))
        if states is not None and instants[0] > 0.0:
            read = dict(zip(instants, states(np.array(instants))))
        else:
            read = {instant: state(instant) for instant in instants}
        for index in list(waiting):
            try:
                waiting[index] = searches[index].send(read[waiting[index]])
            except StopIteration as stop:
                found[index] = stop.value
                del waiting[index]
    return found


#: The zero of the rate is bracketed to this fraction of the excitation period (the
#: extremum's value is then exact to ½ r̈ (width·T_e)², 10⁻¹³ of it), within ROOT_STEPS
#: runs.
ROOT_WIDTH = 1e-7
ROOT_STEPS = 40


def state_at(scene, initial, time, method, event_tolerance):
    """(x, ẋ) of the orbit at ``time`` [s], by running it again from its start ``initial``:
    both by the engine's coordinates (``integrate``'s)."""
    if time <= 0.0:
        return initial[:2]
    periods = max(1, int(np.ceil(time / scene.excitation_period - 1e-12)))
    run = integrate(scene, periods, method=method, event_tolerance=event_tolerance,
                    initial=initial, until=min(time, periods * scene.excitation_period),
                    event_capacity=0).run
    return run.output.x[-1], run.output.v[-1]
