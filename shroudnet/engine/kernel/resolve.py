"""Resolve: the new consistent set of modes at a switch, the switch itself, and the start.

``resolve`` turns the guards that crossed into tentative modes and ``settle`` releases
stuck interfaces until every one holds (a terminating rule). ``switch`` logs it, restarts
the loop there, and multiplies the tangent by the switch's saltation matrix; ``begin``
starts a run. Everything here is the same for both methods. Law-free parts:
``shroudnet.engine.resolve`` and ``shroudnet.engine.regroup``.
"""

from typing import TYPE_CHECKING

import numpy as np

from shroudnet.engine.advance import is_finite, keep_guards, record, set_powers
from shroudnet.engine.clusters import TWO_DRIVERS
from shroudnet.engine.codes import (FINISHED, INCONSISTENT, MAX_IDLE_SWITCHES, NO_PROGRESS,
                                    NOT_FINITE, OPEN, OVERCONSTRAINED, PROJECTION,
                                    SLIP_NEGATIVE, SLIP_POSITIVE, STICK, ZENO)
from shroudnet.engine.compiled import (njit_inlined, njit_step, njit_step_exact,
                                       njit_step_merged)
from shroudnet.engine.detect import count_crossed, crossed, first_crossed
from shroudnet.engine.regroup import project_velocities, regroup, same_stuck
from shroudnet.engine.resolve import (direction_bit, initial_modes, log_switches, piling_up,
                                      relative_acceleration)
from shroudnet.engine.saltation import apply_saltation, apply_saltations, project_tangent
from shroudnet.engine.slider_tangent import (first_order_field, release_open_stretches,
                                             slipping_start)
from shroudnet.engine.sliders import initial_slider_modes, switch_slider

if TYPE_CHECKING:
    from .forces import evaluate_guards_apart, law_forces
    from .generated import (HAS_PRESCRIBED, HAS_SLIDERS, HAS_STRUCTURES, HAS_TANGENT,
                            normal_force_gradient)
    from .tangent import crossed_gradients, crossings_coincide, guard_gradient


#: Relative slack on |f| ≤ μ_s N for an interface whose slip velocity has just reached zero,
#: so that rounding in its static friction does not release it at once. An interface
#: already stuck is released as soon as |f| > μ_s N, where its breakaway guard fires.
FRICTION_SLACK = 1e-9


@njit_inlined
def overconstrained(topology, candidates, modes, s):
    """A candidate for stick in a cluster that ties two prescribed motions (or one and a
    fixed node) together, else −1 (``clusters.cluster_labels``)."""
    for e in range(len(modes)):
        if candidates[e] and modes[e] == STICK:
            end = s.left[e] if s.left[e] >= 0 else s.right[e]
            if topology.driver[topology.labels[end]] == TWO_DRIVERS:
                return e
    return -1


@njit_step_merged
def settle(t, state, topology, s, w, sw):
    """Release stuck interfaces until every one holds: a terminating mode-selection rule.

    ``state.modes`` holds the tentative set, with every candidate for stick
    (``sw.candidates``) and every held interface in STICK. Each round projects the velocities
    onto the clusters, computes the static friction, and releases the stuck interface that
    exceeds μ_s N by the largest ratio, to slip in the direction its friction pushed
    (|f| > μ_s N with f > 0 means the relative motion starts positive). A released
    candidate whose slip would reverse at once (its relative acceleration opposes its
    direction) is held again, and that direction is marked as tried for it. Releasing
    other interfaces can turn the friction it needs round, so it may later be released the
    other way; but when it needs more than μ_s N towards a direction already tried,
    neither stick nor slip is consistent for it (its friction law's μ(0⁺) exceeds μ_s, or
    the coupled limits conflict) and INCONSISTENT is returned with that interface. A
    candidate whose stick would tie two prescribed motions together (``overconstrained``)
    slips instead, the same way tried first, and OVERCONSTRAINED is returned when both
    ways reverse. A held
    interface is released at most once, and a candidate at most once each way, so the rule
    ends within 4 n_interfaces + 1 rounds. A held interface is released as soon as
    |f| > μ_s N, as its breakaway guard says; a candidate only beyond
    μ_s N (1 + ``FRICTION_SLACK``).

    With nothing stuck and no candidate the set holds as it is, and no force is evaluated.

    ``topology`` is that of the modes before the switch, kept while the set of stuck
    interfaces stays the same. Returns (status, kinetic energy lost to the projection,
    topology, the interface that made the set inconsistent or −1); state.v is projected.
    Regroups into ``sw``, and takes its scratch from there.
    """
    modes, x, v, candidates = state.modes, state.x, state.v, sw.candidates
    n = len(modes)
    tried = sw.tried  # per interface: bit 1 slip +, bit 2 slip − tried
    for e in range(n):
        tried[e] = 0
    v_trial = sw.v_trial
    any_candidate = candidates.any()
    for _ in range(4 * n + 2):
        if not same_stuck(topology, modes):
            topology = regroup(s, modes, sw)
        if HAS_PRESCRIBED and not HAS_STRUCTURES:
            tie = overconstrained(topology, candidates, modes, s)
            if tie >= 0:  # a candidate would tie motions that differ: it slips, a way untried
                direction = SLIP_NEGATIVE if tried[tie] & direction_bit(SLIP_POSITIVE) \
                    else SLIP_POSITIVE
                if tried[tie] & direction_bit(direction):
                    return OVERCONSTRAINED, 0.0, topology, tie
                modes[tie] = direction
                continue
        for i in range(len(v)):
            v_trial[i] = v[i]
        lost = project_velocities(s, topology, v_trial, 0, w.scratch)
        if len(topology.stuck_interfaces) > 0 or any_candidate:  # else forces decide nothing
            evaluate_guards_apart(t, x, v_trial, modes, topology, s, w, w.a_end)
        worst = -1
        worst_ratio = 0.0
        for e in topology.stuck_interfaces:
            limit = s.static_mu[e] * w.normal[e]
            need = abs(w.friction[e])
            if need > (limit * (1.0 + FRICTION_SLACK) if candidates[e] else limit):
                ratio = need / limit if limit > 0.0 else np.inf
                if ratio >= worst_ratio:
                    worst = e
                    worst_ratio = ratio
        if worst >= 0:
            direction = SLIP_POSITIVE if w.friction[worst] > 0.0 else SLIP_NEGATIVE
            if tried[worst] & direction_bit(direction):
                return INCONSISTENT, 0.0, topology, worst
            modes[worst] = direction
            continue
        restick = -1
        for e in range(n):
            if candidates[e] and modes[e] != STICK:
                sign = 1.0 if modes[e] == SLIP_POSITIVE else -1.0
                if sign * relative_acceleration(s, e, w.a_end) < 0.0:
                    restick = e
                    break
        if restick < 0:
            for i in range(len(v)):
                v[i] = v_trial[i]
            return FINISHED, lost, topology, -1
        tried[restick] |= direction_bit(modes[restick])
        modes[restick] = STICK
    return INCONSISTENT, 0.0, regroup(s, modes, sw), -1


@njit_step_merged
def resolve(t, state, topology, s, w, sw):
    """The new modes after the guards in w crossed, from those of ``topology``; returns what
    ``settle`` returns."""
    modes = state.modes
    candidates = sw.candidates
    for e in range(len(modes)):
        candidates[e] = False
    for e in range(len(modes)):
        if HAS_SLIDERS:
            if s.slider_index[e] >= 0:
                switch_slider(state.x, modes, s, e,
                              crossed(state.contact_before[e], w.contact[e]),
                              crossed(state.motion_before[e], w.motion[e]), w.friction[e])
                continue
        if crossed(state.contact_before[e], w.contact[e]):
            if modes[e] == OPEN:
                modes[e] = SLIP_POSITIVE if w.slip[e] >= 0.0 else SLIP_NEGATIVE
            else:
                modes[e] = OPEN
        elif crossed(state.motion_before[e], w.motion[e]) and modes[e] != STICK:
            modes[e] = STICK  # slip velocity reached zero: try to stick
            candidates[e] = True
    return settle(t, state, topology, s, w, sw)


@njit_step_exact
def switch(t, state, topology, s, w, sw, events, controls):
    """Resolve the switch located at t (the state there, its guards in w; ``topology`` that
    of the modes before it), log it and restart there.

    On return the guards at the restart are the state's reference and its acceleration
    and powers are in w.a_start / w.stage_p[0]. Returns (status, the interface that stopped
    the run or −1, topology). A switch that changes no mode is counted in ``events.idle``;
    ``MAX_IDLE_SWITCHES`` of them in a row stop the run (NO_PROGRESS).
    """
    old = sw.modes_before
    for e in range(len(old)):
        old[e] = state.modes[e]
    crossing = first_crossed(state, w)
    tangent = HAS_TANGENT and state.tangent.matrix.shape[1] > 0 and crossing >= 0
    time_rate = 0.0
    several = False
    n_crossed = 0
    if HAS_TANGENT and tangent:
        time_rate = guard_gradient(t, crossing, state, topology, s, w)
        several = count_crossed(state, w) > 1 and not crossings_coincide(
            t, crossing, time_rate, state, topology, s, w)
        if several:
            n_crossed = crossed_gradients(t, state, topology, s, w, sw)
            guard_gradient(t, crossing, state, topology, s, w)
    status, lost, topology, culprit = resolve(t, state, topology, s, w, sw)
    state.energy[PROJECTION] += lost
    last = log_switches(t, old, state.modes, events)
    events.idle[0] = events.idle[0] + 1 if last < 0 else 0
    stop_interface = -1
    if status != FINISHED:
        stop_interface = culprit if culprit >= 0 else last
    elif events.idle[0] >= MAX_IDLE_SWITCHES:
        status = NO_PROGRESS
        stop_interface = crossing
    elif piling_up(t, events, controls):
        status = ZENO
        stop_interface = last
    start(t, state, topology, s, w)
    if HAS_TANGENT and tangent:
        g = state.tangent
        for i in range(len(state.x)):
            g.f_plus[i] = state.v[i]
            g.f_plus[len(state.x) + i] = w.a_start[i]
        if HAS_SLIDERS:
            first_order_field(s, g.f_plus)
        if not (several and apply_saltations(t, n_crossed, state.modes, s, topology, g,
                                             sw)):
            apply_saltation(t, crossing, time_rate, several, s, topology, g)
        if HAS_SLIDERS:
            release_open_stretches(state.modes, s, g.matrix)
    if status == FINISHED and not is_finite(state):
        status = NOT_FINITE
    return status, stop_interface, topology


@njit_step
def start(t, state, topology, s, w):
    """Evaluate the first stage and the guards at a (re)start point; they become the
    state's reference."""
    set_powers(w.stage_p[0], evaluate_guards_apart(t, state.x, state.v, state.modes, topology,
                                                   s, w, w.a_start))
    keep_guards(state, w)


@njit_step
def start_sliders(state, s, w):
    """The elastic contacts' modes at the start (``sliders.initial_slider_modes``): an open
    one's stretch relaxed, with its tangent, and a slipping one's put on its friction
    limit with its tangent (``slider_tangent.slipping_start``)."""
    law_forces(s, state.modes, w)
    initial_slider_modes(state.x, state.modes, s, w)
    release_open_stretches(state.modes, s, state.tangent.matrix)
    for e in range(len(state.modes)):
        if s.slider_index[e] < 0 or state.modes[e] == OPEN or state.modes[e] == STICK:
            continue
        slope, rate_slope = normal_force_gradient(s.normal_kind[e], s.normal_params[e],
                                                  w.penetration[e], w.rate[e])
        slipping_start(state.x, s, e, w.normal[e], slope, rate_slope, state.tangent.matrix)


@njit_step_exact
def begin(state, s, w, sw, controls, out):
    """The start at t0: consistent modes, velocities projected onto their clusters, the
    first sample. Returns (status, topology).

    The tangent's velocity rows are projected as the state's are (the derivative of the
    start's projection)."""
    initial_modes(state, s, w, sw.candidates)
    if HAS_SLIDERS:
        start_sliders(state, s, w)
    status, lost, topology, _ = settle(controls.t0, state, regroup(s, state.modes, sw), s, w,
                                       sw)
    state.energy[PROJECTION] += lost
    if HAS_TANGENT:
        project_tangent(s, topology, state.tangent)
    start(controls.t0, state, topology, s, w)
    record(out, np.int64(0), controls.t0, state.x, state.v, state.modes, state.energy, w)
    return status, topology
