"""The event-driven integration loop, compiled once per combination of laws and effects.

This file is not imported as it stands. ``shroudnet.kernel`` writes a module made of a
generated header followed by this source, so that numba can cache it on disk. The header
defines, for the laws present in a scene:

- ``normal_force(kind, params, penetration, rate)`` and
  ``friction_coefficient(kind, params, slip_speed)``, which dispatch on the law's index;
- the effect flags ``HAS_CONTACT_EVENTS``, ``HAS_STICK``, ``HAS_FRICTION`` and
  ``HAS_REGULARISED``, compile-time constants that remove the code of absent effects.

A step reads as five phases: advance (one Runge–Kutta step with fixed modes), detect (a
guard of ``event_guards`` changed sign), locate (bisection on the step size to within the
event tolerance, keeping the end just past the switch), resolve (the new consistent set of
modes) and regroup (stick clusters, the static friction operator, and one velocity for each
cluster).
"""

import math

import numpy as np
from numba import njit

from shroudnet.clusters import cluster_labels
from shroudnet.dynamics import (cluster_accelerations, cluster_mass, event_guards,
                                excitation_forces, interface_kinematics, resultant_forces,
                                static_friction, static_friction_operator)
from shroudnet.kernel_types import Topology, Work

OPEN, STICK, SLIP_POSITIVE, SLIP_NEGATIVE = 0, 1, 2, 3
CLOSING, SEPARATION, STICKING, REVERSAL, BREAKAWAY = 0, 1, 2, 3, 4
FINISHED, ZENO, INCONSISTENT, NOT_FINITE = 0, 1, 2, 3

#: Relative slack on |f| ≤ μ_s N when a mode set is settled.
FRICTION_SLACK = 1e-9


@njit(cache=True)
def new_work(n_blades, n_interfaces):
    b, m = n_blades, n_interfaces
    return Work(np.empty(b), np.empty(m), np.empty(m), np.empty(m), np.empty(m), np.empty(m),
                np.empty(m), np.empty(b), np.empty(b), np.empty(m), np.empty(m),
                np.empty(b), np.empty(b), np.empty(b), np.empty(b), np.empty(b), np.empty(b))


@njit(cache=True)
def regroup(s, modes):
    """Stick clusters and the static friction operator of a set of modes."""
    stuck = modes == STICK
    labels, grounded = cluster_labels(len(s.mass), s.left, s.right, stuck)
    operator, stuck_interfaces = static_friction_operator(len(s.mass), s.left, s.right,
                                                          s.cos_angle, stuck)
    return Topology(stuck, labels, grounded, cluster_mass(s.mass, labels, len(grounded)),
                    operator, stuck_interfaces)


@njit(cache=True)
def law_forces(s, modes, w):
    """N and sliding f on every interface from its laws, into w.normal and w.friction."""
    for e in range(len(modes)):
        w.normal[e] = 0.0
        w.friction[e] = 0.0
        if modes[e] == OPEN:
            continue
        normal = normal_force(s.normal_kind[e], s.normal_params[e], w.penetration[e],
                              w.rate[e])
        w.normal[e] = normal
        if not HAS_FRICTION or s.friction_kind[e] < 0 or modes[e] == STICK:
            continue
        sliding = normal * friction_coefficient(s.friction_kind[e], s.friction_params[e],
                                                abs(w.slip[e]))
        if HAS_REGULARISED and s.regularisation[e] > 0.0:
            w.friction[e] = sliding * math.tanh(w.slip[e] / s.regularisation[e])
        elif modes[e] == SLIP_POSITIVE:
            w.friction[e] = sliding
        else:
            w.friction[e] = -sliding


@njit(cache=True)
def derivative(t, x, v, modes, topology, s, w, acceleration):
    """ẍ into ``acceleration``; returns the powers (excitation, damping, friction, contact) [W].

    Contact power is Σ N δ̇, friction power Σ f v over sliding interfaces: with stuck
    interfaces carrying no relative motion, d(kinetic + spring energy)/dt is
    excitation − damping − friction − contact.
    """
    interface_kinematics(x, v, s.left, s.right, s.gap, s.sin_angle, s.cos_angle,
                         w.penetration, w.rate, w.slip)
    law_forces(s, modes, w)
    for e in range(len(modes)):
        w.force[e] = w.normal[e] * s.sin_angle[e] + w.friction[e] * s.cos_angle[e]
    excitation_forces(t, s.amplitudes, s.phases, s.excitation_frequency, w.q)
    resultant_forces(x, v, w.q, s.damping, s.stiffness, s.left, s.right, w.force,
                     topology.stuck, w.resultant)
    cluster_accelerations(w.resultant, topology.labels, topology.grounded, topology.masses,
                          w.scratch, acceleration)
    excitation = 0.0
    damping = 0.0
    for i in range(len(x)):
        excitation += w.q[i] * v[i]
        damping += s.damping[i] * v[i] * v[i]
    friction = 0.0
    contact = 0.0
    for e in range(len(modes)):
        friction += w.friction[e] * w.slip[e]
        contact += w.normal[e] * w.rate[e]
    return excitation, damping, friction, contact


@njit(cache=True)
def evaluate_guards(t, x, v, modes, topology, s, w):
    """Forces, static friction and guards at a point, into w (friction includes static)."""
    derivative(t, x, v, modes, topology, s, w, w.a1)
    if HAS_STICK and len(topology.stuck_interfaces) > 0:
        static = static_friction(topology.operator, topology.stuck_interfaces, s.mass,
                                 w.resultant, w.a1, w.normal, s.sin_angle, s.left, s.right)
        for e in topology.stuck_interfaces:
            w.friction[e] = static[e]
    event_guards(modes, w.penetration, w.slip, w.normal, w.friction, s.static_mu, s.opens,
                 s.can_stick, w.contact, w.motion)


@njit(cache=True)
def crossed(before, after):
    """A guard changed sign: it is negative now and was not, or it fell further below zero."""
    return after < 0.0 and (before >= 0.0 or after < before)


@njit(cache=True)
def any_crossed(contact_before, motion_before, w):
    for e in range(len(contact_before)):
        if crossed(contact_before[e], w.contact[e]) or crossed(motion_before[e], w.motion[e]):
            return True
    return False


@njit(cache=True)
def rk4_step(t, x, v, h, modes, topology, s, w, x_out, v_out, energy):
    """One classical Runge–Kutta step of size h with fixed modes; adds work done to energy."""
    a1, a2, a3, a4, xt, vt = w.a1, w.a2, w.a3, w.a4, w.xt, w.vt
    p1 = derivative(t, x, v, modes, topology, s, w, a1)
    for i in range(len(x)):
        xt[i] = x[i] + 0.5 * h * v[i]
        vt[i] = v[i] + 0.5 * h * a1[i]
    p2 = derivative(t + 0.5 * h, xt, vt, modes, topology, s, w, a2)
    for i in range(len(x)):
        xt[i] = x[i] + 0.5 * h * (v[i] + 0.5 * h * a1[i])
        vt[i] = v[i] + 0.5 * h * a2[i]
    p3 = derivative(t + 0.5 * h, xt, vt, modes, topology, s, w, a3)
    for i in range(len(x)):
        xt[i] = x[i] + h * (v[i] + 0.5 * h * a2[i])
        vt[i] = v[i] + h * a3[i]
    p4 = derivative(t + h, xt, vt, modes, topology, s, w, a4)
    for i in range(len(x)):
        v2 = v[i] + 0.5 * h * a1[i]
        v3 = v[i] + 0.5 * h * a2[i]
        v4 = v[i] + h * a3[i]
        x_out[i] = x[i] + h / 6.0 * (v[i] + 2.0 * v2 + 2.0 * v3 + v4)
        v_out[i] = v[i] + h / 6.0 * (a1[i] + 2.0 * a2[i] + 2.0 * a3[i] + a4[i])
    for k in range(4):
        energy[k] += h / 6.0 * (p1[k] + 2.0 * p2[k] + 2.0 * p3[k] + p4[k])


@njit(cache=True)
def project_velocities(s, topology, v):
    """One velocity per stick cluster, conserving its momentum; 0 in a grounded cluster.

    Returns the kinetic energy removed [J] (of the order of the event tolerance).
    """
    n_clusters = len(topology.grounded)
    momentum = np.zeros(n_clusters)
    for i in range(len(v)):
        momentum[topology.labels[i]] += s.mass[i] * v[i]
    lost = 0.0
    for i in range(len(v)):
        c = topology.labels[i]
        new = 0.0 if topology.grounded[c] else momentum[c] / topology.masses[c]
        lost += 0.5 * s.mass[i] * (v[i] * v[i] - new * new)
        v[i] = new
    return lost


@njit(cache=True)
def relative_acceleration(s, e, acceleration):
    """(ẍ_i − ẍ_j) cos α of interface e: the rate of change of its slip velocity."""
    value = 0.0
    if s.left[e] >= 0:
        value += acceleration[s.left[e]]
    if s.right[e] >= 0:
        value -= acceleration[s.right[e]]
    return value * s.cos_angle[e]


@njit(cache=True)
def settle(t, x, v, modes, candidates, s, w):
    """Release stuck interfaces until every one holds: a terminating mode-selection rule.

    ``modes`` holds the tentative set, with every candidate for stick (``candidates``) and
    every held interface in STICK. Each round projects the velocities onto the clusters,
    computes the static friction, and releases the stuck interface that exceeds μ_s N by the
    largest ratio, to slip in the direction its friction pushed (|f| > μ_s N with f > 0 means
    the relative motion starts positive). A released candidate whose slip would reverse at
    once (its relative acceleration opposes the chosen direction) is held again and marked
    so that it is not released twice. At most 2 n_interfaces + 1 rounds: beyond that no
    consistent set exists and INCONSISTENT is returned.

    Returns (status, kinetic energy lost to the projection, topology); v is projected.
    """
    n = len(modes)
    tried = np.zeros(n, dtype=np.bool_)
    v_trial = v.copy()
    for _ in range(2 * n + 2):
        topology = regroup(s, modes)
        v_trial[:] = v
        lost = project_velocities(s, topology, v_trial)
        evaluate_guards(t, x, v_trial, modes, topology, s, w)
        worst = -1
        worst_ratio = 1.0 + FRICTION_SLACK
        for e in topology.stuck_interfaces:
            limit = s.static_mu[e] * w.normal[e]
            need = abs(w.friction[e])
            ratio = need / limit if limit > 0.0 else (np.inf if need > 0.0 else 0.0)
            if ratio > worst_ratio and not (tried[e] and candidates[e]):
                worst = e
                worst_ratio = ratio
        if worst >= 0:
            modes[worst] = SLIP_POSITIVE if w.friction[worst] > 0.0 else SLIP_NEGATIVE
            continue
        restick = -1
        for e in range(n):
            if candidates[e] and modes[e] != STICK and not tried[e]:
                direction = 1.0 if modes[e] == SLIP_POSITIVE else -1.0
                if direction * relative_acceleration(s, e, w.a1) < 0.0:
                    restick = e
                    break
        if restick < 0:
            v[:] = v_trial
            return FINISHED, lost, topology
        tried[restick] = True
        modes[restick] = STICK
    return INCONSISTENT, 0.0, regroup(s, modes)


@njit(cache=True)
def resolve(t, x, v, modes, contact_before, motion_before, s, w):
    """The new modes after the guards in w crossed; returns (status, lost energy, topology)."""
    candidates = np.zeros(len(modes), dtype=np.bool_)
    for e in range(len(modes)):
        if crossed(contact_before[e], w.contact[e]):
            if modes[e] == OPEN:
                modes[e] = SLIP_POSITIVE if w.slip[e] >= 0.0 else SLIP_NEGATIVE
            else:
                modes[e] = OPEN
        elif crossed(motion_before[e], w.motion[e]) and modes[e] != STICK:
            modes[e] = STICK  # slip velocity reached zero: try to stick
            candidates[e] = True
    return settle(t, x, v, modes, candidates, s, w)


@njit(cache=True)
def initial_modes(x, v, s, w):
    """Modes at the start: closed where δ > 0 (or the law never opens), stuck where possible."""
    modes = np.zeros(len(s.gap), dtype=np.int64)
    interface_kinematics(x, v, s.left, s.right, s.gap, s.sin_angle, s.cos_angle,
                         w.penetration, w.rate, w.slip)
    candidates = np.zeros(len(modes), dtype=np.bool_)
    for e in range(len(modes)):
        if s.opens[e] and w.penetration[e] <= 0.0:
            modes[e] = OPEN
        elif s.can_stick[e] and w.slip[e] == 0.0:
            modes[e] = STICK
            candidates[e] = True
        else:
            modes[e] = SLIP_POSITIVE if w.slip[e] >= 0.0 else SLIP_NEGATIVE
    return modes, candidates


@njit(cache=True)
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


@njit(cache=True)
def log_switches(t, old, modes, log, counts, recent, n_events):
    """Record every interface whose mode changed; returns (n_events, the last one's index)."""
    last = -1
    for e in range(len(modes)):
        if modes[e] != old[e]:
            kind = event_kind(old[e], modes[e])
            counts[kind] += 1
            if n_events < len(log[0]):
                log[0][n_events] = t
                log[1][n_events] = e
                log[2][n_events] = kind
            n_events += 1
            recent[n_events % len(recent)] = t
            last = e
    return n_events, last


@njit(cache=True)
def run_fixed_step(s, x0, v0, t0, step, n_steps, steps_per_sample, event_tolerance,
                   zeno_events, zeno_window, event_capacity):
    """Integrate n_steps fixed RK4 steps from (t0, x0, v0), locating every switch.

    Steps stay on the grid t0 + k·step: after a switch inside a step, the rest of the step
    is integrated in the new modes. Samples are taken every ``steps_per_sample`` steps.
    Zeno guard: ``zeno_events`` switches within ``zeno_window`` seconds stop the run.
    """
    n_blades, n_interfaces = len(s.mass), len(s.gap)
    w = new_work(n_blades, n_interfaces)
    n_samples = n_steps // steps_per_sample + 1
    out_t = np.empty(n_samples)
    out_x = np.empty((n_samples, n_blades))
    out_v = np.empty((n_samples, n_blades))
    out_normal = np.empty((n_samples, n_interfaces))
    out_friction = np.empty((n_samples, n_interfaces))
    out_modes = np.empty((n_samples, n_interfaces), dtype=np.int8)
    out_energy = np.empty((n_samples, 5))
    log = (np.empty(event_capacity), np.empty(event_capacity, dtype=np.int64),
           np.empty(event_capacity, dtype=np.int8))
    counts = np.zeros(5, dtype=np.int64)
    recent = np.full(max(zeno_events, 1), -np.inf)
    n_events = 0

    x = x0.copy()
    v = v0.copy()
    x_new = np.empty(n_blades)
    v_new = np.empty(n_blades)
    energy = np.zeros(5)  # excitation, damping, friction, contact work; projection loss [J]
    step_energy = np.zeros(4)
    modes, candidates = initial_modes(x, v, s, w)
    status, lost, topology = settle(t0, x, v, modes, candidates, s, w)
    energy[4] += lost
    evaluate_guards(t0, x, v, modes, topology, s, w)
    contact_before = w.contact.copy()
    motion_before = w.motion.copy()
    t = t0
    sample = 0
    stop_interface = -1

    for k in range(n_steps + 1):
        if k % steps_per_sample == 0:
            out_t[sample] = t
            out_x[sample] = x
            out_v[sample] = v
            out_normal[sample] = w.normal
            out_friction[sample] = w.friction
            out_modes[sample] = modes
            out_energy[sample] = energy
            sample += 1
        if k == n_steps or status != FINISHED:
            break
        t_end = t0 + (k + 1) * step
        while status == FINISHED:
            # advance
            h = t_end - t
            step_energy[:] = 0.0
            rk4_step(t, x, v, h, modes, topology, s, w, x_new, v_new, step_energy)
            evaluate_guards(t_end, x_new, v_new, modes, topology, s, w)
            # detect
            if not (HAS_CONTACT_EVENTS or HAS_STICK) or not any_crossed(
                    contact_before, motion_before, w):
                energy[:4] += step_energy
                t = t_end
                x[:] = x_new
                v[:] = v_new
                break
            # locate: the earliest switch lies in (lo, hi]; the state is taken at hi
            lo, hi = 0.0, h
            while hi - lo > event_tolerance:
                mid = 0.5 * (lo + hi)
                rk4_step(t, x, v, mid, modes, topology, s, w, x_new, v_new, step_energy)
                evaluate_guards(t + mid, x_new, v_new, modes, topology, s, w)
                if any_crossed(contact_before, motion_before, w):
                    hi = mid
                else:
                    lo = mid
            step_energy[:] = 0.0
            rk4_step(t, x, v, hi, modes, topology, s, w, x_new, v_new, step_energy)
            evaluate_guards(t + hi, x_new, v_new, modes, topology, s, w)
            energy[:4] += step_energy
            t = t_end if hi == h else t + hi
            x[:] = x_new
            v[:] = v_new
            # resolve and regroup
            old = modes.copy()
            status, lost, topology = resolve(t, x, v, modes, contact_before, motion_before,
                                             s, w)
            energy[4] += lost
            n_events, last = log_switches(t, old, modes, log, counts, recent, n_events)
            if status != FINISHED:
                stop_interface = last
            elif zeno_events > 0 and t - recent[(n_events + 1) % len(recent)] < zeno_window:
                status = ZENO
                stop_interface = last
            evaluate_guards(t, x, v, modes, topology, s, w)
            contact_before[:] = w.contact
            motion_before[:] = w.motion
            if t >= t_end:
                break
        contact_before[:] = w.contact
        motion_before[:] = w.motion
        for i in range(n_blades):
            if not (math.isfinite(x[i]) and math.isfinite(v[i])):
                status = NOT_FINITE
    n_logged = min(n_events, event_capacity)
    return (status, t, stop_interface, out_t[:sample], out_x[:sample], out_v[:sample],
            out_normal[:sample], out_friction[:sample], out_modes[:sample],
            out_energy[:sample], log[0][:n_logged], log[1][:n_logged], log[2][:n_logged],
            counts)
