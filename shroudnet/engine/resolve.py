"""Resolve: the parts of choosing the new modes at a switch that do not evaluate forces.

The mode rule itself (``kernel.resolve.settle``) computes static friction, which
needs the laws; here are the initial modes, the kinds of events, the event log and the
Zeno guard.
"""

from .codes import (BREAKAWAY, CLOSING, OPEN, REVERSAL, SEPARATION, SLIP_NEGATIVE,
                    SLIP_POSITIVE, STICK, STICKING)
from .compiled import njit_inlined, njit_step
from .dispatch import by_scene
from .structures import kinematics, structure_slip_acceleration


@njit_step
def initial_modes(state, s, w, candidates):
    """Modes at the start, into state.modes: closed where δ > 0 (or the law never opens),
    stuck where possible; which interfaces are candidates for stick, into ``candidates``."""
    modes = state.modes
    kinematics(state.x, state.v, s, w.penetration, w.rate, w.slip)
    for e in range(len(modes)):
        candidates[e] = False
        if s.opens[e] and w.penetration[e] <= 0.0:
            modes[e] = OPEN
        elif s.can_stick[e] and w.slip[e] == 0.0:
            modes[e] = STICK
            candidates[e] = True
        else:
            modes[e] = SLIP_POSITIVE if w.slip[e] >= 0.0 else SLIP_NEGATIVE


@njit_inlined
def blade_slip_acceleration(s, e, acceleration):
    """(ẍ_i − ẍ_j) cos α of interface e: the rate of change of its slip velocity."""
    value = 0.0
    if s.left[e] >= 0:
        value += acceleration[s.left[e]]
    if s.right[e] >= 0:
        value -= acceleration[s.right[e]]
    return value * s.cos_angle[e]


relative_acceleration = by_scene("relative_acceleration", blade_slip_acceleration,
                                 structure_slip_acceleration)


@njit_inlined
def direction_bit(mode):
    """1 for SLIP_POSITIVE, 2 for SLIP_NEGATIVE: the flags of ``settle``'s tried directions."""
    return 1 if mode == SLIP_POSITIVE else 2


@njit_inlined
def event_kind(before, after):
    if before == OPEN:
        return CLOSING
    if after == OPEN:
        return SEPARATION
    if after == STICK:
        return STICKING
    if before == STICK:
        return BREAKAWAY
    return REVERSAL


@njit_step
def log_switches(t, old, modes, events):
    """Record every interface whose mode changed; returns the last one's index (or −1)."""
    last = -1
    for e in range(len(modes)):
        if modes[e] != old[e]:
            kind = event_kind(old[e], modes[e])
            events.counts[kind] += 1
            n = events.n_events[0]
            if n < len(events.time):
                events.time[n] = t
                events.interface[n] = e
                events.kind[n] = kind
            events.n_events[0] = n + 1
            events.recent[(n + 1) % len(events.recent)] = t
            last = e
    return last


@njit_inlined
def piling_up(t, events, controls):
    """The Zeno guard: the last ``zeno_events`` switches all fell within ``zeno_window``."""
    oldest = events.recent[(events.n_events[0] + 1) % len(events.recent)]
    return controls.zeno_events > 0 and t - oldest < controls.zeno_window
