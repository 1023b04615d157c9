"""Detect: the event guards, and whether one of them crossed zero.

Every interface has two guards, values that stay ≥ 0 while its mode holds and cross 0 at
a switch (``event_guards``). A step is checked against the guards where the last one
ended (the state's ``contact_before`` / ``motion_before``). Between the step's ends, a
contact can close and open again, and a stuck interface's friction can pass μ_s N and
fall back; ``kinematic_dip``, ``may_graze`` and ``predicted_low`` look for those (with
``kernel.detect``). None of this depends on the contact or friction laws.
"""

import numpy as np

from .advance import dense_motion
from .codes import OPEN, SLIP_NEGATIVE, SLIP_POSITIVE, STICK
from .compiled import njit_inlined, njit_inlined_callable
from .dispatch import by_scene
from .dynamics import relative_motion
from .structures import kinematics, structure_contact_guard
from .tableau import DIP_POINTS


@njit_inlined_callable
def breakaway_margin(static_mu, normal_force, friction_force):
    """μ_s N − |f| [N]: how much more friction a stuck interface can hold."""
    return static_mu * normal_force - abs(friction_force)


@njit_inlined_callable
def event_guards(modes, penetration, slip_velocity, normal_force, friction_force, static_mu,
                 opens, can_stick, contact, motion):
    """Guards: per interface, values that stay ≥ 0 while its mode holds and cross 0 at a switch.

    contact: −δ while open (crosses 0 as the contact closes), δ while closed (as it opens);
    +inf for a contact that never opens. motion: ±v while slipping with exact friction
    (crosses 0 as the slip velocity reaches zero); μ_s N − |f| while stuck (the breakaway
    margin); +inf otherwise. Written into ``contact`` and ``motion``.
    """
    for e in range(len(modes)):
        mode = modes[e]
        contact[e] = np.inf
        motion[e] = np.inf
        if opens[e]:
            contact[e] = -penetration[e] if mode == OPEN else penetration[e]
        if mode == STICK:
            motion[e] = breakaway_margin(static_mu[e], normal_force[e], friction_force[e])
        elif can_stick[e] and mode == SLIP_POSITIVE:
            motion[e] = slip_velocity[e]
        elif can_stick[e] and mode == SLIP_NEGATIVE:
            motion[e] = -slip_velocity[e]


@njit_inlined_callable
def crossed(before, after):
    """A guard changed sign: it is negative now and was not, or it fell further below zero."""
    return after < 0.0 and (before >= 0.0 or after < before)


@njit_inlined_callable
def depth(before, after):
    """How far a guard is past its crossing: < 0 exactly when ``crossed(before, after)``.

    The guard itself where it started ≥ 0; where it started below 0 (a restart just past a
    switch), its fall below that start. Continuous in ``after``: the function the
    switch is located on.
    """
    return after if before >= 0.0 else after - before


@njit_inlined
def guard_crossed(state, w, e):
    """Whether interface e's contact or motion guard in w crossed since the state's
    reference."""
    return crossed(state.contact_before[e], w.contact[e]) or crossed(state.motion_before[e],
                                                                      w.motion[e])


@njit_inlined
def first_crossed(state, w):
    """The first interface whose guard in w crossed since the state's reference, or −1."""
    for e in range(len(state.contact_before)):
        if guard_crossed(state, w, e):
            return e
    return -1


@njit_inlined
def count_crossed(state, w):
    """How many interfaces' guards in w crossed since the state's reference."""
    count = 0
    for e in range(len(state.contact_before)):
        if guard_crossed(state, w, e):
            count += 1
    return count


@njit_inlined
def any_crossed(state, w):
    return first_crossed(state, w) >= 0


@njit_inlined
def stuck_crossed(topology, state, s, w):
    """Whether a stuck interface's breakaway margin, from the forces in w, has crossed."""
    for e in topology.stuck_interfaces:
        if crossed(state.motion_before[e], breakaway_margin(s.static_mu[e], w.normal[e],
                                                            w.friction[e])):
            return True
    return False


@njit_inlined
def blade_contact_guard(e, x, v, modes, s):
    """Interface e's contact guard g (−δ while open, δ while closed) [m] and ġ [m/s]."""
    u, du = relative_motion(x, v, s.left, s.right, e)
    side = -s.sin_angle[e] if modes[e] == OPEN else s.sin_angle[e]
    return side * (u - s.gap[e]), side * du


contact_guard = by_scene("contact_guard", blade_contact_guard, structure_contact_guard)


@njit_inlined
def may_graze(e, h, x, v, x_end, v_end, modes, s):
    """Interface e's contact guard, positive at both ends of the step of size h from (x, v)
    to (x_end, v_end), may still dip below 0 inside it: a grazing contact.

    That needs a minimum inside the step (ġ < 0 at its start, > 0 at its end) and the
    tangents at both ends, which bound a convex guard from below, meeting below 0. Far
    from grazing the bound stays positive and nothing more is evaluated.
    """
    if not s.opens[e]:
        return False
    g0, rate0 = contact_guard(e, x, v, modes, s)
    g1, rate1 = contact_guard(e, x_end, v_end, modes, s)
    if not (g0 > 0.0 and g1 > 0.0 and rate0 < 0.0 and rate1 > 0.0):
        return False
    meet = (g1 - g0 - rate1 * h) / (rate0 - rate1)
    return g0 + rate0 * meet <= 0.0


@njit_inlined
def mark_grazing(h, state, s, w):
    """Mark in w.contact_trial (1 or 0) the contacts that ``may_graze`` in the step of size h
    from the state to w.x_new, w.v_new; returns whether any may."""
    any_marked = False
    for e in range(len(state.modes)):
        marked = may_graze(e, h, state.x, state.v, w.x_new, w.v_new, state.modes, s)
        w.contact_trial[e] = 1.0 if marked else 0.0
        any_marked = any_marked or marked
    return any_marked


@njit_inlined_callable
def parabola_low(a, b, c):
    """(s, p(s)) at the lowest point for s in [−1, 1] of the parabola p through (−1, a),
    (0, b) and (1, c)."""
    curvature = a - 2.0 * b + c
    if curvature > 0.0:
        offset = min(1.0, max(-1.0, 0.5 * (a - c) / curvature))
    else:
        offset = 1.0 if c < a else -1.0
    return offset, b + 0.5 * (c - a) * offset + 0.5 * curvature * offset * offset


@njit_inlined_callable
def predicted_low(samples):
    """(θ, value) at the lowest point of the parabola through the lowest of ``samples``
    (values at equally spaced fractions 0 … 1 of a step) and its two neighbours."""
    last = len(samples) - 1
    lowest = 0
    for k in range(1, last + 1):
        if samples[k] < samples[lowest]:
            lowest = k
    centre = min(max(lowest, 1), last - 1)
    offset, value = parabola_low(samples[centre - 1], samples[centre], samples[centre + 1])
    return (centre + offset) / last, value


@njit_inlined
def kinematic_guards(x, v, modes, s, w, contact, motion):
    """The contact and slip guards at (x, v) into ``contact`` and ``motion``, from the
    kinematics alone (left in w.penetration, w.rate, w.slip): no force is evaluated, so
    a stuck interface's breakaway margin there is not to be read."""
    kinematics(x, v, s, w.penetration, w.rate, w.slip)
    event_guards(modes, w.penetration, w.slip, w.normal, w.friction, s.static_mu, s.opens,
                 s.can_stick, contact, motion)


@njit_inlined
def kinematic_dip(h, state, s, w):
    """The first of ``DIP_POINTS`` inside the adaptive step of size h at which a contact or
    slip guard has crossed, else 2.

    Contact closing and opening, and the slip velocity of a sliding interface, are
    functions of the state alone, so they are checked on the dense output without
    evaluating forces: the guards go into w.contact_trial / w.motion_trial, and the
    breakaway margins of stuck interfaces, which would need the forces, are not read.
    """
    for theta in DIP_POINTS:
        dense_motion(theta, h, state, w, w.xt, w.vt)
        if kinematic_crossing(state, s, w):
            return theta
    return 2.0


@njit_inlined
def kinematic_crossing(state, s, w):
    """Whether a contact or slip guard has crossed at the state in w.xt, w.vt, whose
    guards are left in w.contact_trial / w.motion_trial (``kinematic_guards``: no force
    is evaluated, and stuck interfaces' breakaway margins are not read)."""
    modes = state.modes
    kinematic_guards(w.xt, w.vt, modes, s, w, w.contact_trial, w.motion_trial)
    for e in range(len(modes)):
        if crossed(state.contact_before[e], w.contact_trial[e]) or (
                modes[e] != STICK and crossed(state.motion_before[e], w.motion_trial[e])):
            return True
    return False
