"""Detect: switches hidden inside a step (law-aware; the guards themselves: ``detect``).

A guard that has crossed by the end of a step is seen there. One that crosses and comes
back within the step is not: a contact that closes and opens again, a static friction that
passes μ_s N and falls back. ``first_inside`` looks for them, on states inside the step
that the method provides (``step.motion_inside``): the dense output of an adaptive step,
cheap enough to check the kinematic guards at ``DIP_POINTS`` every step; the exact states
of an exponential step, checked there too (``exact_dip``); a fixed step's states
integrated anew, checked where a contact may graze or a stuck interface's margin may dip
(``graze``, ``breakaway``).
"""

from typing import TYPE_CHECKING

import numpy as np

from shroudnet.engine.compiled import njit_step, njit_step_merged
from shroudnet.engine.detect import (any_crossed, breakaway_margin, contact_guard, crossed,
                                     kinematic_crossing, kinematic_dip, mark_grazing,
                                     predicted_low, stuck_crossed)
from shroudnet.engine.tableau import DIP_POINTS

if TYPE_CHECKING:
    from .forces import stuck_forces
    from .generated import ADAPTIVE, EXPONENTIAL, HAS_CONTACT_EVENTS, HAS_STICK
    from .step import motion_inside, step_apart

#: Where a fixed step's breakaway margins are sampled: its middle (each state inside a
#: fixed step is integrated anew, and fixed steps are short).
MIDDLE = np.array([0.5])


@njit_step_merged
def first_inside(t, h, state, topology, s, w, controls):
    """The first fraction θ ≤ 1 of the step of size h just taken from t by which a guard
    has crossed, or 2 where none has: crossed at its end (θ = 1), on the dense output of
    an adaptive step (``detect.kinematic_dip``), at a grazing contact (``graze``) or a
    breakaway inside it (``breakaway``). A switch then lies in (0, θ]. The step's end
    state and guards are left in w where θ = 2."""
    theta = 1.0 if any_crossed(state, w) else 2.0
    if ADAPTIVE:
        theta = min(theta, kinematic_dip(h, state, s, w))
    if EXPONENTIAL:
        theta = min(theta, exact_dip(t, h, state, topology, s, w))
    if HAS_CONTACT_EVENTS and mark_grazing(h, state, s, w):
        theta = min(theta, graze(t, h, state, topology, s, w, controls))
    if HAS_STICK and len(topology.stuck_interfaces) > 0:
        theta = min(theta, breakaway(t, h, state, topology, s, w, controls))
    return theta


@njit_step
def exact_dip(t, h, state, topology, s, w):
    """``detect.kinematic_dip`` of an exponential step: the contact and slip guards at
    ``DIP_POINTS`` of the step of size h from t, on its exact states (each a level or two
    of the phase's propagation, the points being binary fractions), else 2."""
    for theta in DIP_POINTS:
        motion_inside(t, h, theta, state, topology, s, w)
        if kinematic_crossing(state, s, w):
            return theta
    return 2.0


@njit_step
def breakaway(t, h, state, topology, s, w, controls):
    """The first fraction of the step of size h from t where a stuck interface's breakaway
    margin has crossed, else 2.

    A stuck phase has no integration error to shorten the steps, so one step can span a
    whole excursion of the static friction beyond μ_s N. The margins are sampled inside
    the step (at ``DIP_POINTS`` of an adaptive step, the first two kept in
    w.contact_trial and w.motion_trial; at the ``MIDDLE`` of a fixed one), then checked
    where a parabola through the samples and the step's ends puts them lowest. Compiled
    on its own: it runs only while something is stuck, and costs force evaluations then.
    """
    modes, before = state.modes, state.motion_before
    points = DIP_POINTS if ADAPTIVE or EXPONENTIAL else MIDDLE
    kept = (w.contact_trial, w.motion_trial)
    for k in range(len(points)):
        theta = points[k]
        motion_inside(t, h, theta, state, topology, s, w)
        stuck_forces(t + theta * h, w.xt, w.vt, modes, topology, s, w)
        for e in topology.stuck_interfaces:
            margin = breakaway_margin(s.static_mu[e], w.normal[e], w.friction[e])
            if crossed(before[e], margin):
                return theta
            if k < len(points) - 1:
                kept[k][e] = margin
    first = 2.0
    for e in topology.stuck_interfaces:
        last = breakaway_margin(s.static_mu[e], w.normal[e], w.friction[e])
        if ADAPTIVE or EXPONENTIAL:
            theta, value = predicted_low((before[e], w.contact_trial[e], w.motion_trial[e],
                                          last, w.motion[e]))
        else:
            theta, value = predicted_low((before[e], last, w.motion[e]))
        if value < 0.0 and 0.0 < theta < first:
            first = theta
    if first < 1.0:
        motion_inside(t, h, first, state, topology, s, w)
        stuck_forces(t + first * h, w.xt, w.vt, modes, topology, s, w)
        if stuck_crossed(topology, state, s, w):
            return first
    if not ADAPTIVE and not EXPONENTIAL:  # the states inside overwrote the step's end
        step_apart(t, h, state, topology, s, w, controls)
    return 2.0


@njit_step
def graze(t, h, state, topology, s, w, controls):
    """θ just past the minimum of a contact guard that dips below 0 inside the step of size
    h from t, else 2, for the contacts ``detect.mark_grazing`` marked in w.contact_trial.

    The minimum is bisected on the sign of ġ to within the event tolerance [s]; a switch
    then lies in (0, θ], where the guard falls. Where none dips, the step's end state
    and guards are left in w.
    """
    modes = state.modes
    first = 2.0
    for e in range(len(modes)):
        if w.contact_trial[e] == 0.0:
            continue
        lo, hi = 0.0, 1.0
        while (hi - lo) * h > controls.event_tolerance:
            mid = 0.5 * (lo + hi)
            motion_inside(t, h, mid, state, topology, s, w)
            if contact_guard(e, w.xt, w.vt, modes, s)[1] < 0.0:
                lo = mid
            else:
                hi = mid
        motion_inside(t, h, hi, state, topology, s, w)
        if contact_guard(e, w.xt, w.vt, modes, s)[0] < 0.0:
            first = min(first, hi)
    if not ADAPTIVE and not EXPONENTIAL and first > 1.0:  # the states inside overwrote
        # the step's end
        step_apart(t, h, state, topology, s, w, controls)
    return first
