"""Locate: the bracketing root finder that places a switch inside a step.

A switch lies where a guard's depth (``detect.depth``), ≥ 0 at the bracket's low end and
< 0 at its high end, crosses zero. The search follows one guard, one that has crossed at
the high end, by the Illinois variant of regula falsi (Dahlquist & Björck, *Numerical
Methods*, §6.2.4), which converges superlinearly where bisection gains one bit per
evaluation: a switch inside a step of 10⁻² periods, located to 10⁻¹⁰ periods, takes some
5–10 evaluations of the guards instead of 27. Should another guard cross first, the search
follows that one from there. The kernel's ``locate_*`` functions evaluate the guards
(into w.contact / w.motion); the bracket's arithmetic is here. The guards at the low end
are kept in w.contact_trial / w.motion_trial.
"""

import numpy as np

from .compiled import njit_inlined, njit_inlined_callable
from .detect import depth

#: Evaluations that may fail to halve the bracket before the search halves it from then on:
#: a secant that crawls (a kink, a flat guard) costs at most this many evaluations more
#: than bisection.
SLOW_NARROWING = 8


@njit_inlined
def guard_depth(state, contact, motion, g):
    """The depth of guard g (contact guard of interface g < m, else the motion guard of
    interface g − m) in the guard arrays given, against the state's reference."""
    m = len(state.contact_before)
    if g < m:
        return depth(state.contact_before[g], contact[g])
    return depth(state.motion_before[g - m], motion[g - m])


@njit_inlined
def deepest_guard(state, contact, motion):
    """(g, depth) of the guard of least depth in the guard arrays given."""
    best, lowest = -1, np.inf
    for g in range(2 * len(state.contact_before)):
        value = guard_depth(state, contact, motion, g)
        if value < lowest:
            best, lowest = g, value
    return best, lowest


@njit_inlined
def keep_low_end(w):
    for e in range(len(w.contact)):
        w.contact_trial[e] = w.contact[e]
        w.motion_trial[e] = w.motion[e]


@njit_inlined
def bracket_start(hi, state, w):
    """The bracket (0, hi] with the guards at hi in w: (lo, f_lo, hi, f_hi, side, guard)."""
    for e in range(len(w.contact)):
        w.contact_trial[e] = state.contact_before[e]
        w.motion_trial[e] = state.motion_before[e]
    g, f_hi = deepest_guard(state, w.contact, w.motion)
    return (0.0, guard_depth(state, w.contact_trial, w.motion_trial, g), hi, f_hi,
            np.int64(0), g)


@njit_inlined_callable
def next_trial(lo, f_lo, hi, f_hi, width, previous, slow):
    """Where to evaluate next inside the bracket (lo, hi) with depths f_lo ≥ 0 > f_hi, and
    the count of slow evaluations: (trial, slow).

    The regula falsi point, kept at least ``width``/2 inside the bracket, so that a root
    near one end closes the bracket to within ``width`` at the next evaluation. The
    midpoint when the depths give no usable secant, and once ``SLOW_NARROWING``
    evaluations have failed to halve the bracket (``previous`` is its width before the
    last evaluation; ``slow`` counts them).
    """
    slow = slow + 1 if hi - lo > 0.5 * previous else slow
    if slow >= SLOW_NARROWING or not f_lo > f_hi:
        return 0.5 * (lo + hi), slow
    margin = 0.5 * width
    trial = hi - f_hi * (hi - lo) / (f_hi - f_lo)
    return min(max(trial, lo + margin), hi - margin), slow


@njit_inlined_callable
def narrow(lo, f_lo, hi, f_hi, trial, f_trial, side):
    """The bracket after the depth ``f_trial`` at ``trial``, Illinois style.

    ``side`` is +1 when the previous evaluation replaced hi, −1 when it replaced lo, 0 at
    first. An end kept twice running has its depth halved, which moves the next secant
    point towards it and keeps convergence superlinear. Returns (lo, f_lo, hi, f_hi, side).
    """
    if f_trial < 0.0:
        if side == 1:
            f_lo *= 0.5
        return lo, f_lo, trial, f_trial, 1
    if side == -1:
        f_hi *= 0.5
    return trial, f_trial, hi, f_hi, -1


@njit_inlined
def bracket_after(lo, f_lo, hi, f_hi, side, g, trial, state, w):
    """The bracket after the guards at ``trial`` were evaluated into w; the same tuple as
    ``bracket_start``."""
    f = guard_depth(state, w.contact, w.motion, g)
    if f >= 0.0:
        other, f_other = deepest_guard(state, w.contact, w.motion)
        if f_other < 0.0:  # another guard crossed before the one followed: follow it
            return (lo, guard_depth(state, w.contact_trial, w.motion_trial, other), trial,
                    f_other, np.int64(0), other)
        keep_low_end(w)
    lo, f_lo, hi, f_hi, side = narrow(lo, f_lo, hi, f_hi, trial, f, side)
    return lo, f_lo, hi, f_hi, side, g
