"""The event-driven integration loops, compiled once per combination of laws and effects.

This file is not imported as it stands. ``shroudnet.kernel`` writes a module made of a
generated header followed by this source, so that numba can cache it on disk. The header
defines, for the laws present in a scene:

- ``normal_force(kind, params, penetration, rate)`` and
  ``friction_coefficient(kind, params, slip_speed)``, which dispatch on the law's index;
- the effect flags ``HAS_CONTACT_EVENTS``, ``HAS_STICK``, ``HAS_FRICTION`` and
  ``HAS_REGULARISED``, compile-time constants that remove the code of absent effects.

A step reads as five phases: advance (one Runge–Kutta step with fixed modes), detect (a
guard of ``event_guards`` changed sign), locate (bisection to within the event tolerance,
keeping the end just past the switch), resolve (the new consistent set of modes) and
regroup (stick clusters, the static friction operator, and one velocity for each cluster).
Two drivers share everything but the advance and the state inside a step:
``run_fixed_step`` (classical RK4 on a grid; a state inside a step is integrated anew) and
``run_adaptive`` (Dormand–Prince 5(4) with error control; a state inside a step comes from
its dense output).

The state carries, beside x and ẋ, the work done so far: excitation, damping, friction and
contact work from the powers ``derivative`` returns (integrated by the same Runge–Kutta
weights), and the kinetic energy removed when velocities are projected onto stick clusters.
"""

import math

import numpy as np
from numba import njit

from shroudnet.clusters import cluster_labels
from shroudnet.compiled import njit_inlined, njit_without_refcounts
from shroudnet.dynamics import (breakaway_margin, cluster_accelerations, cluster_mass,
                                event_guards, excitation_forces, interface_kinematics,
                                relative_motion, resultant_forces, static_friction,
                                static_friction_operator)
from shroudnet.kernel_types import Events, Output, Topology, Work

OPEN, STICK, SLIP_POSITIVE, SLIP_NEGATIVE = 0, 1, 2, 3
CLOSING, SEPARATION, STICKING, REVERSAL, BREAKAWAY = 0, 1, 2, 3, 4
FINISHED, ZENO, INCONSISTENT, NOT_FINITE, STEP_TOO_SMALL, NO_PROGRESS = 0, 1, 2, 3, 4, 5

#: Relative slack on |f| ≤ μ_s N for an interface whose slip velocity has just reached zero,
#: so that rounding in its static friction does not release it at once. An interface
#: already stuck is released as soon as |f| > μ_s N, where its breakaway guard fires.
FRICTION_SLACK = 1e-9

#: Located switches in a row that change no mode before a run is stopped (NO_PROGRESS).
#: A guard that crosses while the mode rule keeps every mode is legitimate once (a slip
#: velocity that touches zero and goes on the same way); a long series means the guards
#: and the mode rule disagree, and the run would creep on by one event tolerance a switch.
MAX_IDLE_SWITCHES = 1000
#: Work columns of the state: excitation, damping, friction, contact; then projection loss.
N_POWERS = 4
N_WORK = 5

# Dormand–Prince 5(4) (Dormand & Prince 1980) with Shampine's dense output of order 4,
# as in Hairer, Nørsett & Wanner, Solving ODEs I, §II.5–6.
DP_C = np.array([0.0, 1 / 5, 3 / 10, 4 / 5, 8 / 9, 1.0])
DP_A = np.array([
    [0.0, 0.0, 0.0, 0.0, 0.0],
    [1 / 5, 0.0, 0.0, 0.0, 0.0],
    [3 / 40, 9 / 40, 0.0, 0.0, 0.0],
    [44 / 45, -56 / 15, 32 / 9, 0.0, 0.0],
    [19372 / 6561, -25360 / 2187, 64448 / 6561, -212 / 729, 0.0],
    [9017 / 3168, -355 / 33, 46732 / 5247, 49 / 176, -5103 / 18656],
])
DP_B = np.array([35 / 384, 0.0, 500 / 1113, 125 / 192, -2187 / 6784, 11 / 84, 0.0])
#: Fifth- minus fourth-order weights: the local error estimate is h Σ DP_E_j k_j.
DP_E = np.array([-71 / 57600, 0.0, 71 / 16695, -71 / 1920, 17253 / 339200, -22 / 525,
                 1 / 40])
#: Dense output: y(t + θh) = y + h Σ_j k_j Σ_p DP_P[j, p] θ^(p+1).
DP_P = np.array([
    [1.0, -8048581381 / 2820520608, 8663915743 / 2820520608, -12715105075 / 11282082432],
    [0.0, 0.0, 0.0, 0.0],
    [0.0, 131558114200 / 32700410799, -68118460800 / 10900136933,
     87487479700 / 32700410799],
    [0.0, -1754552775 / 470086768, 14199869525 / 1410260304, -10690763975 / 1880347072],
    [0.0, 127303824393 / 49829197408, -318862633887 / 49829197408,
     701980252875 / 199316789632],
    [0.0, -282668133 / 205662961, 2019193451 / 616988883, -1453857185 / 822651844],
    [0.0, 40617522 / 29380423, -110615467 / 29380423, 69997945 / 29380423],
])
#: Points inside an adaptive step where the kinematic guards, and the breakaway margins of
#: stuck interfaces, are checked, so that a contact that closes and opens again within one
#: step, or a static friction that passes μ_s N and falls back, is not missed.
DIP_POINTS = np.array([0.25, 0.5, 0.75])


# ---- allocation (once per run or per mode change) -------------------------------------

@njit(cache=True)
def new_work(n_blades, n_interfaces):
    b, m = n_blades, n_interfaces
    return Work(np.empty(b), np.empty(b), np.empty(b), np.empty(b), np.empty(b),
                np.empty(b), np.empty(b), np.empty(b), np.empty(b), np.empty(b), np.empty(b),
                np.empty(m), np.empty(m), np.empty(m), np.empty(m), np.empty(m), np.empty(m),
                np.empty(m), np.empty(m),
                np.empty(m), np.empty(m),
                np.zeros((7, b)), np.zeros((7, b)), np.zeros((7, N_POWERS)), np.zeros(7),
                np.zeros(N_WORK), np.zeros(N_WORK))


@njit(cache=True)
def new_events(capacity, zeno_events):
    return Events(np.empty(capacity), np.empty(capacity, dtype=np.int64),
                  np.empty(capacity, dtype=np.int8), np.zeros(5, dtype=np.int64),
                  np.full(max(zeno_events, 1), -np.inf), np.zeros(1, dtype=np.int64),
                  np.zeros(1, dtype=np.int64))


@njit(cache=True)
def new_output(n_samples, n_blades, n_interfaces):
    return Output(np.empty(n_samples), np.empty((n_samples, n_blades)),
                  np.empty((n_samples, n_blades)), np.empty((n_samples, n_interfaces)),
                  np.empty((n_samples, n_interfaces)),
                  np.empty((n_samples, n_interfaces), dtype=np.int8),
                  np.empty((n_samples, N_WORK)))


@njit(cache=True)
def regroup(s, modes):
    """Stick clusters and the static friction operator of a set of modes."""
    stuck = modes == STICK
    labels, grounded = cluster_labels(len(s.mass), s.left, s.right, stuck)
    operator, stuck_interfaces = static_friction_operator(len(s.mass), s.left, s.right,
                                                          s.cos_angle, stuck)
    return Topology(stuck, labels, grounded, cluster_mass(s.mass, labels, len(grounded)),
                    operator, stuck_interfaces)


# ---- the right-hand side and the guards (every stage of every step) -------------------

@njit_without_refcounts
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


@njit_inlined
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
    excitation_forces(t, s.amplitudes, s.cos_phase, s.sin_phase, s.excitation_frequency,
                      w.q)
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


@njit_without_refcounts
def evaluate_guards(t, x, v, modes, topology, s, w, acceleration):
    """``derivative``, then static friction and guards into w (w.friction includes static).

    Returns the powers, as ``derivative``.
    """
    powers = derivative(t, x, v, modes, topology, s, w, acceleration)
    if HAS_STICK and len(topology.stuck_interfaces) > 0:
        static_friction(topology.operator, topology.stuck_interfaces, s.mass, w.resultant,
                        acceleration, w.normal, s.sin_angle, s.left, s.right, w.imbalance,
                        w.friction)
    event_guards(modes, w.penetration, w.slip, w.normal, w.friction, s.static_mu, s.opens,
                 s.can_stick, w.contact, w.motion)
    return powers


@njit_inlined
def set_powers(row, powers):
    for k in range(N_POWERS):
        row[k] = powers[k]


@njit_inlined
def crossed(before, after):
    """A guard changed sign: it is negative now and was not, or it fell further below zero."""
    return after < 0.0 and (before >= 0.0 or after < before)


@njit_inlined
def first_crossed(contact_before, motion_before, w):
    """The first interface whose guard in w crossed since the reference, or −1."""
    for e in range(len(contact_before)):
        if crossed(contact_before[e], w.contact[e]) or crossed(motion_before[e], w.motion[e]):
            return e
    return -1


@njit_inlined
def any_crossed(contact_before, motion_before, w):
    return first_crossed(contact_before, motion_before, w) >= 0


# ---- fixed step: classical Runge–Kutta --------------------------------------------------

@njit_without_refcounts
def rk4_step(t, x, v, energy, h, modes, topology, s, w, x_out, v_out, energy_out):
    """One classical Runge–Kutta step of size h with fixed modes, into the ``_out`` arrays.

    The first stage is the acceleration and powers at (t, x, v) held in w.a_start and
    w.stage_p[0], so a step costs three evaluations of ``derivative`` (plus the guards at
    its end).
    """
    a1, a2, a3, a4 = w.a_start, w.stage_a[1], w.stage_a[2], w.stage_a[3]
    xt, vt, p = w.xt, w.vt, w.stage_p
    for i in range(len(x)):
        xt[i] = x[i] + 0.5 * h * v[i]
        vt[i] = v[i] + 0.5 * h * a1[i]
    set_powers(p[1], derivative(t + 0.5 * h, xt, vt, modes, topology, s, w, a2))
    for i in range(len(x)):
        xt[i] = x[i] + 0.5 * h * (v[i] + 0.5 * h * a1[i])
        vt[i] = v[i] + 0.5 * h * a2[i]
    set_powers(p[2], derivative(t + 0.5 * h, xt, vt, modes, topology, s, w, a3))
    for i in range(len(x)):
        xt[i] = x[i] + h * (v[i] + 0.5 * h * a2[i])
        vt[i] = v[i] + h * a3[i]
    set_powers(p[3], derivative(t + h, xt, vt, modes, topology, s, w, a4))
    for i in range(len(x)):
        v2 = v[i] + 0.5 * h * a1[i]
        v3 = v[i] + 0.5 * h * a2[i]
        v4 = v[i] + h * a3[i]
        x_out[i] = x[i] + h / 6.0 * (v[i] + 2.0 * v2 + 2.0 * v3 + v4)
        v_out[i] = v[i] + h / 6.0 * (a1[i] + 2.0 * a2[i] + 2.0 * a3[i] + a4[i])
    for k in range(N_POWERS):
        energy_out[k] = energy[k] + h / 6.0 * (p[0, k] + 2.0 * p[1, k] + 2.0 * p[2, k]
                                               + p[3, k])
    energy_out[N_POWERS] = energy[N_POWERS]


# ---- adaptive step: Dormand–Prince 5(4) -------------------------------------------------

@njit_inlined
def stage_sum(weights, stages, n_stages, column):
    """Σ_k weights[k] · stages[k, column] over the first ``n_stages`` Runge–Kutta stages."""
    total = 0.0
    for k in range(n_stages):
        total += weights[k] * stages[k, column]
    return total


@njit_without_refcounts
def dp5_step(t, x, v, energy, h, modes, topology, s, w, rtol, atol_x, atol_v):
    """One Dormand–Prince step of size h: the new state into w.x_new, w.v_new, w.e_new.

    Stage 1 is w.a_start / w.stage_p[0] (first same as last); stage 7 is evaluated with
    the guards at the step's end, into w.a_end. Returns the RMS of the local error over
    x and ẋ scaled by atol + rtol·|y| (≤ 1 accepts the step).
    """
    n = len(x)
    sv, sa, sp = w.stage_v, w.stage_a, w.stage_p
    for i in range(n):
        sv[0, i] = v[i]
        sa[0, i] = w.a_start[i]
    for j in range(1, 6):
        for i in range(n):
            w.xt[i] = x[i] + h * stage_sum(DP_A[j], sv, j, i)
            w.vt[i] = v[i] + h * stage_sum(DP_A[j], sa, j, i)
            sv[j, i] = w.vt[i]
        set_powers(sp[j], derivative(t + DP_C[j] * h, w.xt, w.vt, modes, topology, s, w,
                                     sa[j]))
    for i in range(n):
        w.x_new[i] = x[i] + h * stage_sum(DP_B, sv, 6, i)
        w.v_new[i] = v[i] + h * stage_sum(DP_B, sa, 6, i)
        sv[6, i] = w.v_new[i]
    for c in range(N_POWERS):
        w.e_new[c] = energy[c] + h * stage_sum(DP_B, sp, 6, c)
    w.e_new[N_POWERS] = energy[N_POWERS]
    set_powers(sp[6], evaluate_guards(t + h, w.x_new, w.v_new, modes, topology, s, w,
                                      w.a_end))
    for i in range(n):
        sa[6, i] = w.a_end[i]
    error = 0.0
    for i in range(n):
        scale_x = atol_x + rtol * max(abs(x[i]), abs(w.x_new[i]))
        scale_v = atol_v + rtol * max(abs(v[i]), abs(w.v_new[i]))
        error += (h * stage_sum(DP_E, sv, 7, i) / scale_x) ** 2 \
            + (h * stage_sum(DP_E, sa, 7, i) / scale_v) ** 2
    return math.sqrt(error / (2 * n))


@njit_inlined
def dense_state(theta, h, x, v, energy, w, x_out, v_out, energy_out):
    """The state at t + θh from the dense output of the last ``dp5_step``."""
    b0 = theta
    b1 = theta * theta
    b2 = b1 * theta
    b3 = b2 * theta
    weights = w.dense_weights
    for k in range(7):
        weights[k] = DP_P[k, 0] * b0 + DP_P[k, 1] * b1 + DP_P[k, 2] * b2 + DP_P[k, 3] * b3
    for i in range(len(x)):
        x_out[i] = x[i] + h * stage_sum(weights, w.stage_v, 7, i)
        v_out[i] = v[i] + h * stage_sum(weights, w.stage_a, 7, i)
    for c in range(N_POWERS):
        energy_out[c] = energy[c] + h * stage_sum(weights, w.stage_p, 7, c)
    energy_out[N_POWERS] = energy[N_POWERS]


@njit_inlined
def kinematic_dip(h, x, v, energy, modes, contact_before, motion_before, s, w):
    """The first of ``DIP_POINTS`` at which a contact or slip guard has crossed, else 2.

    Contact closing and opening, and the slip velocity of a sliding interface, are
    functions of the state alone, so they are checked on the dense output without
    evaluating forces: the guards go into w.contact_trial / w.motion_trial, and the
    breakaway margins of stuck interfaces, which would need the forces, are not read.
    """
    for theta in DIP_POINTS:
        dense_state(theta, h, x, v, energy, w, w.xt, w.vt, w.e_sample)
        interface_kinematics(w.xt, w.vt, s.left, s.right, s.gap, s.sin_angle, s.cos_angle,
                             w.penetration, w.rate, w.slip)
        event_guards(modes, w.penetration, w.slip, w.normal, w.friction, s.static_mu,
                     s.opens, s.can_stick, w.contact_trial, w.motion_trial)
        for e in range(len(modes)):
            if crossed(contact_before[e], w.contact_trial[e]) or (
                    modes[e] != STICK and crossed(motion_before[e], w.motion_trial[e])):
                return theta
    return 2.0


@njit_inlined
def stuck_forces(time, xt, vt, modes, topology, s, w):
    """The forces, static friction included, at the state (xt, vt) inside a step, into w's
    scratch (the step's end guards in w.contact / w.motion are kept)."""
    derivative(time, xt, vt, modes, topology, s, w, w.a_sample)
    static_friction(topology.operator, topology.stuck_interfaces, s.mass, w.resultant,
                    w.a_sample, w.normal, s.sin_angle, s.left, s.right, w.imbalance, w.friction)


@njit_inlined
def parabola_low(a, b, c):
    """(s, p(s)) at the lowest point for s in [−1, 1] of the parabola p through (−1, a),
    (0, b) and (1, c)."""
    curvature = a - 2.0 * b + c
    if curvature > 0.0:
        offset = min(1.0, max(-1.0, 0.5 * (a - c) / curvature))
    else:
        offset = 1.0 if c < a else -1.0
    return offset, b + 0.5 * (c - a) * offset + 0.5 * curvature * offset * offset


@njit_inlined
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
def stuck_crossed(topology, motion_before, s, w):
    """Whether a stuck interface's breakaway margin, from the forces in w, has crossed."""
    for e in topology.stuck_interfaces:
        if crossed(motion_before[e], breakaway_margin(s.static_mu[e], w.normal[e],
                                                      w.friction[e])):
            return True
    return False


@njit_inlined
def breakaway_dense(t, h, x, v, energy, modes, topology, motion_before, s, w):
    """The first fraction of the adaptive step from t where a stuck interface's breakaway
    margin has crossed, else 2.

    A stuck phase has no integration error to shorten the steps, so one step can span a
    whole excursion of the static friction beyond μ_s N. The margins are sampled at
    ``DIP_POINTS`` on the dense output (the first two kept in w.contact_trial and
    w.motion_trial), then checked where a parabola through the samples and the step's ends
    puts them lowest.
    """
    kept = (w.contact_trial, w.motion_trial)
    for k in range(len(DIP_POINTS)):
        theta = DIP_POINTS[k]
        dense_state(theta, h, x, v, energy, w, w.xt, w.vt, w.e_sample)
        stuck_forces(t + theta * h, w.xt, w.vt, modes, topology, s, w)
        for e in topology.stuck_interfaces:
            margin = breakaway_margin(s.static_mu[e], w.normal[e], w.friction[e])
            if crossed(motion_before[e], margin):
                return theta
            if k < len(kept):
                kept[k][e] = margin
    first = 2.0
    for e in topology.stuck_interfaces:
        theta, value = predicted_low((motion_before[e], w.contact_trial[e], w.motion_trial[e],
                                      breakaway_margin(s.static_mu[e], w.normal[e],
                                                       w.friction[e]), w.motion[e]))
        if value < 0.0 and 0.0 < theta < first:
            first = theta
    if first < 1.0:
        dense_state(first, h, x, v, energy, w, w.xt, w.vt, w.e_sample)
        stuck_forces(t + first * h, w.xt, w.vt, modes, topology, s, w)
        if stuck_crossed(topology, motion_before, s, w):
            return first
    return 2.0


@njit_inlined
def breakaway_fixed(t, h, x, v, energy, modes, topology, motion_before, s, w):
    """``breakaway_dense`` for the fixed-step RK4 step of size h from t: the margins are
    sampled at its middle and checked where a parabola through them and the step's ends
    puts them lowest, each state integrated anew from the step's start. Returns θ ≤ 1, or
    2 with the step's end state and guards restored in w."""
    rk4_step(t, x, v, energy, 0.5 * h, modes, topology, s, w, w.x_new, w.v_new, w.e_new)
    stuck_forces(t + 0.5 * h, w.x_new, w.v_new, modes, topology, s, w)
    if stuck_crossed(topology, motion_before, s, w):
        return 0.5
    first = 2.0
    for e in topology.stuck_interfaces:
        theta, value = predicted_low((motion_before[e],
                                      breakaway_margin(s.static_mu[e], w.normal[e],
                                                       w.friction[e]), w.motion[e]))
        if value < 0.0 and 0.0 < theta < first:
            first = theta
    if first < 1.0:
        rk4_step(t, x, v, energy, first * h, modes, topology, s, w, w.x_new, w.v_new,
                 w.e_new)
        stuck_forces(t + first * h, w.x_new, w.v_new, modes, topology, s, w)
        if stuck_crossed(topology, motion_before, s, w):
            return first
    rk4_step(t, x, v, energy, h, modes, topology, s, w, w.x_new, w.v_new, w.e_new)
    set_powers(w.stage_p[6], evaluate_guards(t + h, w.x_new, w.v_new, modes, topology, s, w,
                                             w.a_end))
    return 2.0


@njit_inlined
def contact_guard(e, x, v, modes, s):
    """Interface e's contact guard g (−δ while open, δ while closed) [m] and ġ [m/s]."""
    u, du = relative_motion(x, v, s.left, s.right, e)
    side = -s.sin_angle[e] if modes[e] == OPEN else s.sin_angle[e]
    return side * (u - s.gap[e]), side * du


@njit_inlined
def may_graze(e, h, x, v, modes, s, w):
    """Interface e's contact guard, positive at both ends of the step of size h from (x, v)
    to (w.x_new, w.v_new), may still dip below 0 inside it: a grazing contact.

    That needs a minimum inside the step (ġ < 0 at its start, > 0 at its end) and the
    tangents at both ends, which bound a convex guard from below, meeting below 0. Far
    from grazing the bound stays positive and nothing more is evaluated.
    """
    if not s.opens[e]:
        return False
    g0, rate0 = contact_guard(e, x, v, modes, s)
    g1, rate1 = contact_guard(e, w.x_new, w.v_new, modes, s)
    if not (g0 > 0.0 and g1 > 0.0 and rate0 < 0.0 and rate1 > 0.0):
        return False
    meet = (g1 - g0 - rate1 * h) / (rate0 - rate1)
    return g0 + rate0 * meet <= 0.0


@njit_inlined
def graze_dense(h, tolerance, x, v, energy, modes, s, w):
    """θ just past the minimum of a contact guard that dips below 0 inside the adaptive step
    of size h, else 2. The minimum is bisected on the sign of ġ along the dense output to
    within ``tolerance`` seconds; a switch then lies in (0, θ], where the guard falls."""
    first = 2.0
    for e in range(len(modes)):
        if not may_graze(e, h, x, v, modes, s, w):
            continue
        lo, hi = 0.0, 1.0
        while (hi - lo) * h > tolerance:
            mid = 0.5 * (lo + hi)
            dense_state(mid, h, x, v, energy, w, w.xt, w.vt, w.e_sample)
            if contact_guard(e, w.xt, w.vt, modes, s)[1] < 0.0:
                lo = mid
            else:
                hi = mid
        dense_state(hi, h, x, v, energy, w, w.xt, w.vt, w.e_sample)
        if contact_guard(e, w.xt, w.vt, modes, s)[0] < 0.0:
            first = min(first, hi)
    return first


@njit_inlined
def graze_fixed(t, h, tolerance, x, v, energy, modes, topology, s, w):
    """``graze_dense`` for the fixed-step RK4 step of size h from t, each trial state
    integrated anew from the step's start. Returns θ ≤ 1, or 2 with the step's end state
    and guards restored in w when no contact guard dips below 0."""
    candidates = w.contact_trial
    searched = False
    for e in range(len(modes)):
        candidates[e] = 1.0 if may_graze(e, h, x, v, modes, s, w) else 0.0
        searched = searched or candidates[e] > 0.0
    if not searched:
        return 2.0
    first = 2.0
    for e in range(len(modes)):
        if candidates[e] == 0.0:
            continue
        lo, hi = 0.0, 1.0
        while (hi - lo) * h > tolerance:
            mid = 0.5 * (lo + hi)
            rk4_step(t, x, v, energy, mid * h, modes, topology, s, w, w.x_new, w.v_new,
                     w.e_new)
            if contact_guard(e, w.x_new, w.v_new, modes, s)[1] < 0.0:
                lo = mid
            else:
                hi = mid
        rk4_step(t, x, v, energy, hi * h, modes, topology, s, w, w.x_new, w.v_new, w.e_new)
        if contact_guard(e, w.x_new, w.v_new, modes, s)[0] < 0.0:
            first = min(first, hi)
    if first > 1.0:
        rk4_step(t, x, v, energy, h, modes, topology, s, w, w.x_new, w.v_new, w.e_new)
        set_powers(w.stage_p[6], evaluate_guards(t + h, w.x_new, w.v_new, modes, topology,
                                                 s, w, w.a_end))
    return first


# ---- resolving a switch (allocates: once per event) -------------------------------------

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
    once (its relative acceleration opposes its direction) is held again, and that
    direction is marked as tried for it. Releasing other interfaces can turn the friction
    it needs round, so it may later be released the other way; but when it needs more than
    μ_s N towards a direction already tried, neither stick nor slip is consistent for it
    (its friction law's μ(0⁺) exceeds μ_s, or the coupled limits conflict) and
    INCONSISTENT is returned with that interface. A held interface is released at most
    once, and a candidate at most once each way, so the rule ends within
    4 n_interfaces + 1 rounds. A held interface is released as soon as |f| > μ_s N, as its
    breakaway guard says; a candidate only beyond μ_s N (1 + ``FRICTION_SLACK``).

    Returns (status, kinetic energy lost to the projection, topology, the interface that
    made the set inconsistent or −1); v is projected.
    """
    n = len(modes)
    tried = np.zeros(n, dtype=np.int64)  # per interface: bit 1 slip +, bit 2 slip − tried
    v_trial = v.copy()
    for _ in range(4 * n + 2):
        topology = regroup(s, modes)
        v_trial[:] = v
        lost = project_velocities(s, topology, v_trial)
        evaluate_guards(t, x, v_trial, modes, topology, s, w, w.a_end)
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
            v[:] = v_trial
            return FINISHED, lost, topology, -1
        tried[restick] |= direction_bit(modes[restick])
        modes[restick] = STICK
    return INCONSISTENT, 0.0, regroup(s, modes), -1


@njit_inlined
def direction_bit(mode):
    """1 for SLIP_POSITIVE, 2 for SLIP_NEGATIVE: the flags of ``settle``'s tried directions."""
    return 1 if mode == SLIP_POSITIVE else 2


@njit(cache=True)
def resolve(t, x, v, modes, contact_before, motion_before, s, w):
    """The new modes after the guards in w crossed; returns what ``settle`` returns."""
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


@njit(cache=True)
def switch(t, x, v, energy, modes, contact_before, motion_before, s, w, events, zeno_events,
           zeno_window):
    """Resolve the switch located at (t, x, v), log it and restart there.

    On return the guards at the restart are in contact_before / motion_before and its
    acceleration and powers in w.a_start / w.stage_p[0]. Returns (status, the interface
    that stopped the run or −1, topology). A switch that changes no mode is counted in
    ``events.idle``; ``MAX_IDLE_SWITCHES`` of them in a row stop the run (NO_PROGRESS).
    """
    old = modes.copy()
    crossing = first_crossed(contact_before, motion_before, w)
    status, lost, topology, culprit = resolve(t, x, v, modes, contact_before,
                                              motion_before, s, w)
    energy[N_POWERS] += lost
    last = log_switches(t, old, modes, events)
    events.idle[0] = events.idle[0] + 1 if last < 0 else 0
    stop_interface = -1
    if status != FINISHED:
        stop_interface = culprit if culprit >= 0 else last
    elif events.idle[0] >= MAX_IDLE_SWITCHES:
        status = NO_PROGRESS
        stop_interface = crossing
    elif zeno_events > 0 and t - events.recent[(events.n_events[0] + 1)
                                               % len(events.recent)] < zeno_window:
        status = ZENO
        stop_interface = last
    start(t, x, v, modes, topology, s, w, contact_before, motion_before)
    return status, stop_interface, topology


@njit_without_refcounts
def start(t, x, v, modes, topology, s, w, contact_before, motion_before):
    """Evaluate the first stage and the guards at a (re)start point."""
    set_powers(w.stage_p[0], evaluate_guards(t, x, v, modes, topology, s, w, w.a_start))
    for e in range(len(modes)):
        contact_before[e] = w.contact[e]
        motion_before[e] = w.motion[e]


@njit_without_refcounts
def record(out, k, t, x, v, modes, energy, w):
    """Sample k of the output: the state and the forces last evaluated into w."""
    out.t[k] = t
    for i in range(len(x)):
        out.x[k, i] = x[i]
        out.v[k, i] = v[i]
    for e in range(len(modes)):
        out.normal[k, e] = w.normal[e]
        out.friction[k, e] = w.friction[e]
        out.modes[k, e] = modes[e]
    for c in range(N_WORK):
        out.energy[k, c] = energy[c]


@njit_without_refcounts
def is_finite(x, v):
    for i in range(len(x)):
        if not (math.isfinite(x[i]) and math.isfinite(v[i])):
            return False
    return True


@njit(cache=True)
def begin(s, x0, v0, t0, n_samples, event_capacity, zeno_events):
    """Everything a driver needs at t0: work arrays, output, log, modes, state, energy."""
    n_blades, n_interfaces = len(s.mass), len(s.gap)
    w = new_work(n_blades, n_interfaces)
    out = new_output(n_samples, n_blades, n_interfaces)
    events = new_events(event_capacity, zeno_events)
    x = x0.copy()
    v = v0.copy()
    energy = np.zeros(N_WORK)
    modes, candidates = initial_modes(x, v, s, w)
    status, lost, topology, _ = settle(t0, x, v, modes, candidates, s, w)
    energy[N_POWERS] += lost
    contact_before = np.empty(n_interfaces)
    motion_before = np.empty(n_interfaces)
    start(t0, x, v, modes, topology, s, w, contact_before, motion_before)
    return w, out, events, x, v, energy, modes, status, topology, contact_before, motion_before


# ---- the drivers --------------------------------------------------------------------------

@njit_without_refcounts
def keep_guards(w, contact_before, motion_before):
    """The guards in w become the reference for detecting the next switch."""
    for e in range(len(contact_before)):
        contact_before[e] = w.contact[e]
        motion_before[e] = w.motion[e]


@njit_without_refcounts
def move_state(x, v, energy, w):
    """The state becomes w.x_new, w.v_new, w.e_new."""
    for i in range(len(x)):
        x[i] = w.x_new[i]
        v[i] = w.v_new[i]
    for c in range(N_WORK):
        energy[c] = w.e_new[c]


@njit_without_refcounts
def take_step(x, v, energy, w):
    """Move to the end of the step just taken: its state, and its last stage as the first."""
    move_state(x, v, energy, w)
    for i in range(len(x)):
        w.a_start[i] = w.a_end[i]
    for c in range(N_POWERS):
        w.stage_p[0, c] = w.stage_p[6, c]


@njit(cache=True)
def finish(status, t, stop_interface, steps, out, n_samples, events):
    n_logged = min(events.n_events[0], len(events.time))
    return (status, t, stop_interface, steps, out.t[:n_samples], out.x[:n_samples],
            out.v[:n_samples], out.normal[:n_samples], out.friction[:n_samples],
            out.modes[:n_samples], out.energy[:n_samples], events.time[:n_logged],
            events.interface[:n_logged], events.kind[:n_logged], events.counts)


@njit_without_refcounts
def advance_fixed(k, t, t0, step, n_steps, steps_per_sample, tolerance, x, v, energy, modes,
                  topology, s, w, contact_before, motion_before, out, sample):
    """RK4 steps along the grid t0 + k·step, recording samples, until a guard crosses.

    Starts at time t inside step k (t = t0 + k·step unless a switch was just resolved).
    Returns (k, t, sample, status, theta): the step in which a guard crossed, with the state
    still at its start (k < n_steps) and the switch in (0, θ] of the step; or
    k = n_steps at the end of the run.
    """
    while k < n_steps:
        t_end = t0 + (k + 1) * step
        rk4_step(t, x, v, energy, t_end - t, modes, topology, s, w, w.x_new, w.v_new,
                 w.e_new)
        set_powers(w.stage_p[6], evaluate_guards(t_end, w.x_new, w.v_new, modes, topology,
                                                 s, w, w.a_end))
        if (HAS_CONTACT_EVENTS or HAS_STICK) and any_crossed(contact_before, motion_before, w):
            return k, t, sample, FINISHED, 1.0
        theta = 2.0
        if HAS_CONTACT_EVENTS:
            theta = graze_fixed(t, t_end - t, tolerance, x, v, energy, modes, topology, s, w)
        if HAS_STICK and len(topology.stuck_interfaces) > 0:
            theta = min(theta, breakaway_fixed(t, t_end - t, x, v, energy, modes, topology,
                                               motion_before, s, w))
        if theta <= 1.0:
            return k, t, sample, FINISHED, theta
        keep_guards(w, contact_before, motion_before)
        take_step(x, v, energy, w)
        if not is_finite(x, v):
            return k, t, sample, NOT_FINITE, 2.0
        t = t_end
        k += 1
        if k % steps_per_sample == 0:
            record(out, sample, t, x, v, modes, energy, w)
            sample += 1
    return k, t, sample, FINISHED, 2.0


@njit_without_refcounts
def locate_fixed(t, h, theta, tolerance, x, v, energy, modes, topology, s, w, contact_before,
                 motion_before):
    """Bisect (0, θh] of the step from t of size h for its earliest switch; move the state
    there.

    The switch lies in (lo, hi] of the step; each trial state is integrated anew from the
    step's start. Returns hi, the step taken, with the guards at its end in w.
    """
    lo, hi = 0.0, theta * h
    while hi - lo > tolerance:
        mid = 0.5 * (lo + hi)
        rk4_step(t, x, v, energy, mid, modes, topology, s, w, w.x_new, w.v_new, w.e_new)
        evaluate_guards(t + mid, w.x_new, w.v_new, modes, topology, s, w, w.a_end)
        if any_crossed(contact_before, motion_before, w):
            hi = mid
        else:
            lo = mid
    rk4_step(t, x, v, energy, hi, modes, topology, s, w, w.x_new, w.v_new, w.e_new)
    move_state(x, v, energy, w)
    evaluate_guards(t + hi, x, v, modes, topology, s, w, w.a_end)
    return hi


@njit(cache=True)
def run_fixed_step(s, x0, v0, t0, step, n_steps, steps_per_sample, event_tolerance,
                   zeno_events, zeno_window, event_capacity):
    """Integrate n_steps fixed RK4 steps from (t0, x0, v0), locating every switch.

    Steps stay on the grid t0 + k·step: after a switch inside a step, the rest of the step
    is integrated in the new modes. Samples are taken every ``steps_per_sample`` steps.
    Zeno guard: ``zeno_events`` switches within ``zeno_window`` seconds stop the run.
    """
    (w, out, events, x, v, energy, modes, status, topology, contact_before,
     motion_before) = begin(s, x0, v0, t0, n_steps // steps_per_sample + 1, event_capacity,
                            zeno_events)
    record(out, 0, t0, x, v, modes, energy, w)
    k, t, sample = 0, t0, 1
    stop_interface = -1
    while status == FINISHED:
        k, t, sample, status, theta = advance_fixed(
            k, t, t0, step, n_steps, steps_per_sample, event_tolerance, x, v, energy, modes,
            topology, s, w, contact_before, motion_before, out, sample)
        if k == n_steps or status != FINISHED:
            break
        t_end = t0 + (k + 1) * step
        h = t_end - t
        hi = locate_fixed(t, h, theta, event_tolerance, x, v, energy, modes, topology, s, w,
                          contact_before, motion_before)
        t = t_end if hi == h else t + hi
        status, stop_interface, topology = switch(t, x, v, energy, modes, contact_before,
                                                  motion_before, s, w, events, zeno_events,
                                                  zeno_window)
        if t == t_end:
            k += 1
            if k % steps_per_sample == 0:
                record(out, sample, t, x, v, modes, energy, w)
                sample += 1
        if not is_finite(x, v):
            status = NOT_FINITE
    return finish(status, t, stop_interface, n_steps, out, sample, events)


@njit_without_refcounts
def advance_adaptive(t, h, t_final, sample_step, t0, n_samples, rtol, atol_x, atol_v, h_max,
                     h_min, tolerance, x, v, energy, modes, topology, s, w, contact_before,
                     motion_before, out, sample, steps):
    """Dormand–Prince steps from t, recording samples, until a guard crosses or the end.

    Returns (t, h, sample, steps, status, theta): theta ≤ 1 locates the first crossing
    found inside the step of size h from t (the state still at its start); theta = 2 when
    the run reached its last sample or stopped with the status. A step that shrinks below
    h_min stops the run: NOT_FINITE if the last trial's error was inf or NaN (a law gave a
    non-finite force ahead), else STEP_TOO_SMALL.
    """
    error = 0.0
    while sample < n_samples:
        last = h >= t_final - t
        if last:
            h = t_final - t
        elif h < h_min:
            status = STEP_TOO_SMALL if math.isfinite(error) else NOT_FINITE
            return t, h, sample, steps, status, 2.0
        error = dp5_step(t, x, v, energy, h, modes, topology, s, w, rtol, atol_x, atol_v)
        if not error <= 1.0:
            h *= max(0.2, 0.9 * error ** -0.2) if math.isfinite(error) else 0.2
            continue
        steps += 1
        if HAS_CONTACT_EVENTS or HAS_STICK:
            theta = 1.0 if any_crossed(contact_before, motion_before, w) else 2.0
            theta = min(theta, kinematic_dip(h, x, v, energy, modes, contact_before,
                                             motion_before, s, w))
            if HAS_STICK and len(topology.stuck_interfaces) > 0:
                theta = min(theta, breakaway_dense(t, h, x, v, energy, modes, topology,
                                                   motion_before, s, w))
            if HAS_CONTACT_EVENTS:
                theta = min(theta, graze_dense(h, tolerance, x, v, energy, modes, s, w))
            if theta <= 1.0:
                return t, h, sample, steps, FINISHED, theta
        t_new = t_final if last else t + h
        keep_guards(w, contact_before, motion_before)
        sample = record_dense(out, sample, n_samples, t0, sample_step, t, t_new, h, x, v,
                              energy, modes, topology, s, w)
        take_step(x, v, energy, w)
        if not is_finite(x, v):
            return t, h, sample, steps, NOT_FINITE, 2.0
        t = t_new
        h = min(h * (min(5.0, 0.9 * error ** -0.2) if error > 0.0 else 5.0), h_max)
    return t, h, sample, steps, FINISHED, 2.0


@njit_without_refcounts
def locate_dense(t, h, theta, t_final, tolerance, sample_step, t0, n_samples, x, v, energy,
                 modes, topology, s, w, contact_before, motion_before, out, sample):
    """Bisect the dense output of the step from t on (0, θ] for its earliest switch.

    Records the samples up to the switch, moves the state there and leaves its guards in
    w. Returns (the switch time, the next sample).
    """
    lo, hi = 0.0, theta
    while (hi - lo) * h > tolerance:
        mid = 0.5 * (lo + hi)
        dense_state(mid, h, x, v, energy, w, w.xt, w.vt, w.e_sample)
        evaluate_guards(t + mid * h, w.xt, w.vt, modes, topology, s, w, w.a_sample)
        if any_crossed(contact_before, motion_before, w):
            hi = mid
        else:
            lo = mid
    t_event = t_final if hi == 1.0 and t + h >= t_final else t + hi * h
    sample = record_dense(out, sample, n_samples, t0, sample_step, t, t_event, h, x, v,
                          energy, modes, topology, s, w)
    dense_state(hi, h, x, v, energy, w, w.x_new, w.v_new, w.e_new)
    move_state(x, v, energy, w)
    evaluate_guards(t_event, x, v, modes, topology, s, w, w.a_end)
    return t_event, sample


@njit(cache=True)
def run_adaptive(s, x0, v0, t0, sample_step, n_samples, rtol, atol_x, atol_v, h_initial,
                 h_max, h_min, event_tolerance, zeno_events, zeno_window, event_capacity):
    """Integrate by Dormand–Prince 5(4) from (t0, x0, v0) to the last of n_samples samples.

    Steps are accepted when the scaled local error (``dp5_step``) is at most 1, and the next
    step is scaled by 0.9·error^(−1/5) within [0.2, 5], capped at h_max. Samples at
    t0 + k·sample_step, switches (to within event_tolerance seconds) and the kinematic
    guards inside a step all come from the step's dense output, so steps never shorten to
    meet them. A step below h_min stops the run (STEP_TOO_SMALL).
    """
    (w, out, events, x, v, energy, modes, status, topology, contact_before,
     motion_before) = begin(s, x0, v0, t0, n_samples, event_capacity, zeno_events)
    record(out, 0, t0, x, v, modes, energy, w)
    t_final = t0 + (n_samples - 1) * sample_step
    t, h, sample, steps = t0, min(h_initial, h_max), 1, 0
    stop_interface = -1
    while status == FINISHED and sample < n_samples:
        t, h, sample, steps, status, theta = advance_adaptive(
            t, h, t_final, sample_step, t0, n_samples, rtol, atol_x, atol_v, h_max, h_min,
            event_tolerance, x, v, energy, modes, topology, s, w, contact_before, motion_before,
            out, sample, steps)
        if theta > 1.0 or status != FINISHED:
            break
        t, sample = locate_dense(t, h, theta, t_final, event_tolerance, sample_step, t0,
                                 n_samples, x, v, energy, modes, topology, s, w,
                                 contact_before, motion_before, out, sample)
        status, stop_interface, topology = switch(t, x, v, energy, modes, contact_before,
                                                  motion_before, s, w, events, zeno_events,
                                                  zeno_window)
        if not is_finite(x, v):
            status = NOT_FINITE
    return finish(status, t, stop_interface, steps, out, sample, events)


@njit_without_refcounts
def record_dense(out, sample, n_samples, t0, sample_step, t, t_to, h, x, v, energy, modes,
                 topology, s, w):
    """Record the samples in (t, t_to] from the dense output of the step of size h from t.

    Returns the index of the next sample. Overwrites the forces and guards in w.
    """
    while sample < n_samples:
        time = t0 + sample * sample_step
        if time > t_to:
            break
        dense_state((time - t) / h, h, x, v, energy, w, w.xt, w.vt, w.e_sample)
        evaluate_guards(time, w.xt, w.vt, modes, topology, s, w, w.a_sample)
        record(out, sample, time, w.xt, w.vt, modes, w.e_sample, w)
        sample += 1
    return sample
