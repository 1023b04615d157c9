"""The event-driven integration loop: the functions that must see the scene's laws.

This file is not imported as it stands. ``shroudnet.engine.generate`` writes a module
made of a generated header followed by this source, so that numba can cache it on disk.
The header defines, for the law classes of a scene:

- ``normal_force(kind, params, penetration, rate)`` and
  ``friction_coefficient(kind, params, slip_speed)``, which dispatch on the law's index;
- ``normal_force_gradient(kind, params, penetration, rate)`` (∂N/∂δ, ∂N/∂δ̇) and
  ``friction_slope(kind, params, slip_speed)`` (dμ/d|v|): the laws' own derivatives, or
  central differences of the law where it gives none;
- the effect flags ``HAS_CONTACT_EVENTS``, ``HAS_STICK``, ``HAS_FRICTION`` and
  ``HAS_REGULARISED``, compile-time constants that remove the code of effects the laws
  rule out, ``HAS_COUPLINGS`` and ``HAS_PRESCRIBED``, set only for scenes with couplings
  and with prescribed-motion nodes (all of these are set in the kernel shared by the
  built-in laws, whose code then checks each effect at run time), and ``HAS_TANGENT``,
  set only in the kernels of runs that integrate the tangent flow (``tangent``), so that
  other runs carry none of its code. Their state holds a ``records.NoTangent``, which has
  none of the tangent's fields: code that reads them sits behind ``if HAS_TANGENT and
  ...`` at each branch, since numba removes a branch on the flag itself, not on a
  variable computed from it.

A step reads as five phases, each with a module of its own for what does not need the
laws: advance (one Runge–Kutta step with fixed modes; ``advance``), detect (a guard
changed sign; ``detect``), locate (the switch inside the step, to within the event
tolerance, by the Illinois method; ``locate``), resolve (the new consistent set of modes;
``resolve``) and regroup (stick clusters, the static friction operator, and one velocity
for each cluster; ``regroup``). Two drivers share everything but the advance and the
state inside a step: ``run_fixed_step`` (classical RK4 on a grid; a state inside a step is
integrated anew) and ``run_adaptive`` (Dormand–Prince 5(4) with error control; a switch is
located on the step's dense output, and the state there integrated anew). A driver works
in records its caller allocates (``records.allocate``) and allocates nothing itself, at a
switch included (regrouping refills ``records.Switching``), so that all of it compiles
without reference counting.

The state carries, beside x and ẋ, the work done so far: excitation, damping, friction and
contact work from the powers ``derivative`` returns (integrated by the same Runge–Kutta
weights), and the kinetic energy removed when velocities are projected onto stick clusters.
In a tangent kernel it carries the tangent vectors too: each adaptive step differentiates
itself (``tangent_step``), and each switch multiplies them by its saltation matrix
(``saltation``).
"""

import math

import numpy as np

from contact_laws.base import ZERO_PLUS_SPEED
from shroudnet.engine.advance import (dense_motion, dense_state, is_finite, keep_guards,
                                      move_state, next_step, record, retry_step, set_powers,
                                      stage_sum, take_step)
from shroudnet.engine.codes import (FINISHED, INCONSISTENT, MAX_IDLE_SWITCHES, N_POWERS,
                                    NO_PROGRESS, NOT_FINITE, OPEN, OVERCONSTRAINED,
                                    PROJECTION,
                                    SLIP_NEGATIVE, SLIP_POSITIVE, STALL_SIZE, STALL_STEPS,
                                    STALLED, STEP_TOO_SMALL, STICK, ZENO)
from shroudnet.engine.clusters import TWO_DRIVERS
from shroudnet.engine.compiled import (njit_entry, njit_inlined, njit_step,
                                       njit_step_callable, njit_step_exact, njit_step_merged)
from shroudnet.engine.detect import (any_crossed, breakaway_margin, contact_guard,
                                     count_crossed, crossed, event_guards, first_crossed,
                                     graze_dense, kinematic_dip, kinematic_guards,
                                     mark_grazing, predicted_low, stuck_crossed)
from shroudnet.engine.dynamics import (cluster_accelerations, coupling_forces,
                                       driven_accelerations, excitation_forces,
                                       interface_kinematics, prescribed_acceleration,
                                       resultant_forces, static_friction)
from shroudnet.engine.locate import bracket_after, bracket_start, next_trial
from shroudnet.engine.records import last_sample, new_switching, new_tangent, new_work
from shroudnet.engine.regroup import project_velocities, regroup, same_stuck
from shroudnet.engine.resolve import (direction_bit, initial_modes, log_switches, piling_up,
                                      relative_acceleration)
from shroudnet.engine.tableau import DIP_POINTS, DP_A, DP_B, DP_C, DP_E, DP_STAGES
from shroudnet.engine.tangent import (apply_saltation, apply_saltations, breakaway_normal,
                                      candidate_tangent, commit_tangent, contact_normal,
                                      last_stage_tangent, linearised_acceleration,
                                      project_tangent, reduce_to_clusters, same_surface,
                                      slip_normal, stage_tangent, tangent_error)

#: Relative slack on |f| ≤ μ_s N for an interface whose slip velocity has just reached zero,
#: so that rounding in its static friction does not release it at once. An interface
#: already stuck is released as soon as |f| > μ_s N, where its breakaway guard fires.
FRICTION_SLACK = 1e-9


# ---- the right-hand side and the guards (every stage of every step) -------------------

@njit_inlined
def sliding_mu(kind, params, speed):
    """μ of an exact law at the slip speed s = ±u̇ cos α signed by the slip mode: μ(s) for
    s ≥ 0; for s < 0, a state past the end of its mode (within the event tolerance past a
    located switch, or a Runge–Kutta stage just beyond it), μ(|s|) + 2 μ'(|s|) s, which
    leaves s = 0 with the slope μ'(0⁺) that the slip side arrives with. The mode's vector
    field thus continues across the switching surface with a continuous slope, where
    μ(|s|) would have a kink: stages beyond the kink made the tangent flow converge at
    first order only. A law whose μ jumps at 0 (μ(0⁺) ≠ μ_s) slips with μ(0⁺), the value
    the slip side has, at s = 0 too (``ZERO_PLUS_SPEED``): an interface just broken away
    from stick, whose slip is exactly 0. The slope is evaluated only for s < 0."""
    size = max(abs(speed), ZERO_PLUS_SPEED)
    mu = friction_coefficient(kind, params, size)
    if speed >= 0.0:
        return mu
    return mu + 2.0 * friction_slope(kind, params, size) * speed


@njit_step
def sliding_coefficient(kind, params, speed):
    """``sliding_mu`` and dμ/ds: μ'(|s|) (for s < 0 the slope of the continuation,
    μ'(|s|) − 2 μ''(|s|) s, is taken as μ'(|s|): s is within a tolerance of 0)."""
    return sliding_mu(kind, params, speed), friction_slope(kind, params,
                                                          max(abs(speed), ZERO_PLUS_SPEED))


@njit_step
def law_forces(s, modes, w):
    """N and sliding f on every interface from its laws, into w.normal and w.friction.

    Exact laws slip with f = σ μ(σ u̇ cos α) N, σ = ±1 by the mode (``sliding_mu``),
    regularised ones with f = μ(|u̇ cos α|) N tanh(u̇ cos α / v_ε) (paper eqs. 2–6).
    """
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
        if HAS_REGULARISED and s.regularisation[e] > 0.0:
            w.friction[e] = normal * friction_coefficient(
                s.friction_kind[e], s.friction_params[e], abs(w.slip[e])) \
                * math.tanh(w.slip[e] / s.regularisation[e])
        else:
            sign = 1.0 if modes[e] == SLIP_POSITIVE else -1.0
            w.friction[e] = sign * normal * sliding_mu(s.friction_kind[e],
                                                       s.friction_params[e], sign * w.slip[e])


@njit_entry
def forces_at(s, modes, w):
    """``law_forces``, callable from Python: the kernel's law dispatch, for tests."""
    law_forces(s, modes, w)


@njit_inlined
def derivative(t, x, v, modes, topology, s, w, acceleration):
    """ẍ into ``acceleration``; returns the powers (excitation, damping, friction, contact) [W].

    Excitation power is the forces Q's and the prescribed motions'
    (``dynamics.driven_accelerations``); damping power is the blades' dampers' and the
    couplings'.

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
    damping = 0.0
    if HAS_COUPLINGS:
        damping = coupling_forces(x, v, s.coupling_left, s.coupling_right,
                                  s.coupling_stiffness, s.coupling_damping, w.resultant)
    cluster_accelerations(w.resultant, topology.labels, topology.grounded, topology.masses,
                          w.scratch, acceleration)
    excitation = 0.0
    if HAS_PRESCRIBED and len(w.drive) > 0:
        for p in range(len(w.drive)):
            w.drive[p] = prescribed_acceleration(t, s, p)[0]
        excitation = driven_accelerations(topology.labels, topology.driver, topology.masses,
                                          w.scratch, v, w.drive, len(x) - len(w.drive),
                                          acceleration)
    for i in range(len(x)):
        excitation += w.q[i] * v[i]
        damping += s.damping[i] * v[i] * v[i]
    friction = 0.0
    contact = 0.0
    for e in range(len(modes)):
        friction += w.friction[e] * w.slip[e]
        contact += w.normal[e] * w.rate[e]
    return excitation, damping, friction, contact


@njit_step_merged
def evaluate_guards(t, x, v, modes, topology, s, w, acceleration):
    """``derivative``, then static friction and guards into w (w.friction includes static).

    Returns the powers, as ``derivative``. Merged into the step loops; the paths taken
    once per switch call ``evaluate_guards_apart``.
    """
    powers = derivative(t, x, v, modes, topology, s, w, acceleration)
    if HAS_STICK and len(topology.stuck_interfaces) > 0:
        static_friction(topology.operator, topology.stuck_interfaces, s.mass, w.resultant,
                        acceleration, w.normal, s.sin_angle, s.left, s.right, w.imbalance,
                        w.friction)
    event_guards(modes, w.penetration, w.slip, w.normal, w.friction, s.static_mu, s.opens,
                 s.can_stick, w.contact, w.motion)
    return powers


@njit_step
def evaluate_guards_apart(t, x, v, modes, topology, s, w, acceleration):
    """``evaluate_guards`` compiled on its own, for the paths taken once per switch."""
    return evaluate_guards(t, x, v, modes, topology, s, w, acceleration)


@njit_step_merged
def sample_forces(time, xt, vt, modes, topology, s, w):
    """The interface forces that a sample records, static friction included, at the state
    (xt, vt) into w.normal / w.friction: with nothing stuck, the laws alone."""
    if HAS_STICK and len(topology.stuck_interfaces) > 0:
        stuck_forces(time, xt, vt, modes, topology, s, w)
        return
    interface_kinematics(xt, vt, s.left, s.right, s.gap, s.sin_angle, s.cos_angle,
                         w.penetration, w.rate, w.slip)
    law_forces(s, modes, w)


@njit_step_merged
def stuck_forces(time, xt, vt, modes, topology, s, w):
    """The forces, static friction included, at the state (xt, vt) inside a step, into w's
    scratch (the step's end guards in w.contact / w.motion are kept)."""
    derivative(time, xt, vt, modes, topology, s, w, w.a_sample)
    static_friction(topology.operator, topology.stuck_interfaces, s.mass, w.resultant,
                    w.a_sample, w.normal, s.sin_angle, s.left, s.right, w.imbalance, w.friction)


# ---- advance: one step with fixed modes --------------------------------------------------

@njit_step_merged
def rk4_step(t, h, state, topology, s, w):
    """One classical Runge–Kutta step of size h with fixed modes, into w.x_new, w.v_new and
    w.e_new.

    The first stage is the acceleration and powers at the state, held in w.a_start and
    w.stage_p[0], so a step costs three evaluations of ``derivative`` (plus the guards at
    its end).
    """
    x, v, energy, modes = state.x, state.v, state.energy, state.modes
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
        w.x_new[i] = x[i] + h / 6.0 * (v[i] + 2.0 * v2 + 2.0 * v3 + v4)
        w.v_new[i] = v[i] + h / 6.0 * (a1[i] + 2.0 * a2[i] + 2.0 * a3[i] + a4[i])
    for k in range(N_POWERS):
        w.e_new[k] = energy[k] + h / 6.0 * (p[0, k] + 2.0 * p[1, k] + 2.0 * p[2, k] + p[3, k])
    w.e_new[PROJECTION] = energy[PROJECTION]


@njit_step_merged
def rk4_guarded(t, h, state, topology, s, w):
    """``rk4_step``, then the forces and guards at its end (w.a_end, w.stage_p[-1])."""
    rk4_step(t, h, state, topology, s, w)
    set_powers(w.stage_p[DP_STAGES - 1], evaluate_guards(t + h, w.x_new, w.v_new, state.modes,
                                                         topology, s, w, w.a_end))


# The step loops merge the steps they take every step (a function compiled on its own takes
# the records as hundreds of machine words of arguments, and passing them cost more than
# the three blades' forces); the paths taken once per switch call these, compiled once each.

@njit_step
def rk4_step_apart(t, h, state, topology, s, w):
    """``rk4_step`` compiled on its own."""
    rk4_step(t, h, state, topology, s, w)


@njit_step
def rk4_guarded_apart(t, h, state, topology, s, w):
    """``rk4_guarded`` compiled on its own."""
    rk4_guarded(t, h, state, topology, s, w)


@njit_step_merged
def dp5_step(t, h, state, topology, s, w, controls):
    """One Dormand–Prince step of size h: the new state into w.x_new, w.v_new, w.e_new.

    Stage 1 is w.a_start / w.stage_p[0] (first same as last); the last stage is evaluated
    with the guards at the step's end, into w.a_end. Returns the RMS of the local error
    over x and ẋ scaled by atol + rtol·|y| (≤ 1 accepts the step).
    """
    x, v, energy, modes = state.x, state.v, state.energy, state.modes
    n = len(x)
    last = DP_STAGES - 1
    sv, sa, sp = w.stage_v, w.stage_a, w.stage_p
    for i in range(n):
        sv[0, i] = v[i]
        sa[0, i] = w.a_start[i]
    for j in range(1, last):
        for i in range(n):
            w.xt[i] = x[i] + h * stage_sum(DP_A[j], sv, j, i)
            w.vt[i] = v[i] + h * stage_sum(DP_A[j], sa, j, i)
            sv[j, i] = w.vt[i]
        set_powers(sp[j], derivative(t + DP_C[j] * h, w.xt, w.vt, modes, topology, s, w,
                                     sa[j]))
    for i in range(n):
        w.x_new[i] = x[i] + h * stage_sum(DP_B, sv, last, i)
        w.v_new[i] = v[i] + h * stage_sum(DP_B, sa, last, i)
        sv[last, i] = w.v_new[i]
    for c in range(N_POWERS):
        w.e_new[c] = energy[c] + h * stage_sum(DP_B, sp, last, c)
    w.e_new[PROJECTION] = energy[PROJECTION]
    set_powers(sp[last], evaluate_guards(t + h, w.x_new, w.v_new, modes, topology, s, w,
                                         w.a_end))
    for i in range(n):
        sa[last, i] = w.a_end[i]
    error = 0.0
    for i in range(n):
        scale_x = controls.atol_x + controls.rtol * max(abs(x[i]), abs(w.x_new[i]))
        scale_v = controls.atol_v + controls.rtol * max(abs(v[i]), abs(w.v_new[i]))
        error += (h * stage_sum(DP_E, sv, DP_STAGES, i) / scale_x) ** 2 \
            + (h * stage_sum(DP_E, sa, DP_STAGES, i) / scale_v) ** 2
    return math.sqrt(error / (2 * n))


@njit_step
def dp5_step_apart(t, h, state, topology, s, w, controls):
    """``dp5_step`` compiled on its own."""
    return dp5_step(t, h, state, topology, s, w, controls)


# ---- the tangent flow (tangent kernels only) ---------------------------------------------

@njit_step
def linearise(t, x, v, modes, topology, s, g):
    """The forces at (t, x, v) into g.work, and each closed interface's slopes into g:
    ∂N/∂u = ∂N/∂δ sin α and ∂N/∂u̇ = ∂N/∂δ̇ sin α, and, unless it is stuck, ∂F/∂u and ∂F/∂u̇ of
    F = N sin α + f cos α, with f = μ(|w|) N σ, w = u̇ cos α, σ = ±1 by the slip mode
    and μ at σw (``sliding_coefficient``): ∂f/∂u = μ σ ∂N/∂u, ∂f/∂u̇ = μ σ ∂N/∂u̇ +
    N μ'(σw) cos α; for a regularised law σ = tanh(w/ε) and μ at |w|, so the last term is
    N (μ'(|w|) sgn(w) σ + μ σ') cos α (paper eqs. 2–6)."""
    derivative(t, x, v, modes, topology, s, g.work, g.acceleration)
    w = g.work
    for e in range(len(modes)):
        g.normal_u[e] = 0.0
        g.normal_du[e] = 0.0
        g.force_u[e] = 0.0
        g.force_du[e] = 0.0
        if modes[e] == OPEN:
            continue
        sine, cosine = s.sin_angle[e], s.cos_angle[e]
        d_penetration, d_rate = normal_force_gradient(s.normal_kind[e], s.normal_params[e],
                                                      w.penetration[e], w.rate[e])
        g.normal_u[e] = d_penetration * sine
        g.normal_du[e] = d_rate * sine
        if modes[e] == STICK:
            continue
        force_u = sine * g.normal_u[e]
        force_du = sine * g.normal_du[e]
        if HAS_FRICTION and s.friction_kind[e] >= 0:
            kind, params, slip = s.friction_kind[e], s.friction_params[e], w.slip[e]
            if HAS_REGULARISED and s.regularisation[e] > 0.0:
                mu = friction_coefficient(kind, params, abs(slip))
                sigma = math.tanh(slip / s.regularisation[e])
                d_sigma = (1.0 - sigma * sigma) / s.regularisation[e]
                sign = 1.0 if slip >= 0.0 else -1.0
                d_slip = w.normal[e] * (friction_slope(kind, params, abs(slip)) * sign * sigma
                                        + mu * d_sigma)
            else:
                sigma = 1.0 if modes[e] == SLIP_POSITIVE else -1.0
                mu, slope = sliding_coefficient(kind, params, sigma * slip)
                d_slip = w.normal[e] * slope
            force_u += cosine * mu * sigma * g.normal_u[e]
            force_du += cosine * (mu * sigma * g.normal_du[e] + d_slip * cosine)
        g.force_u[e] = force_u
        g.force_du[e] = force_du


@njit_entry
def linearise_at(t, x, v, modes, s, tangent0):
    """``linearise`` and the vector field's Jacobian at (t, x, v) in ``modes``, callable
    from Python for tests: returns (J, ẍ), J = ∂(ẋ, ẍ)/∂(x, ẋ) (2 n_blades square)."""
    n = len(x)
    g = new_tangent(tangent0, len(modes), 1, new_work(n, len(modes), len(s.motion_amplitude)))
    topology = regroup(s, modes, new_switching(n, len(modes)))
    linearise(t, x, v, modes, topology, s, g)
    jacobian = np.zeros((2 * n, 2 * n))
    for r in range(2 * n):
        for q in range(2 * n):
            g.direction[q] = 1.0 if q == r else 0.0
        linearised_acceleration(g.direction, s, modes, topology, g)
        for i in range(n):
            jacobian[i, r] = g.direction[n + i]
            jacobian[n + i, r] = g.acceleration_change[i]
    return jacobian, g.acceleration.copy()


@njit_step
def tangent_step(t, h, state, topology, s, w, controls):
    """The tangent through the Dormand–Prince step of size h from t just taken (its stages
    in w), the exact derivative of the step (``tangent``), into state.tangent.candidate;
    returns its scaled local error (``tangent.tangent_error``). ``commit_tangent`` makes
    it the tangent."""
    g = state.tangent
    x = g.work.xt
    v = g.work.vt
    for j in range(DP_STAGES - 1):
        for i in range(len(x)):
            x[i] = state.x[i] + h * stage_sum(DP_A[j], w.stage_v, j, i)
            v[i] = w.stage_v[j, i]
        linearise(t + DP_C[j] * h, x, v, state.modes, topology, s, g)
        stage_tangent(j, h, s, state.modes, topology, g)
    candidate_tangent(h, g)
    linearise(t + h, w.x_new, w.v_new, state.modes, topology, s, g)
    last_stage_tangent(s, state.modes, topology, g)
    return tangent_error(h, controls.rtol, s, g)


@njit_step
def guard_gradient(t, e, state, topology, s, w):
    """Before a switch at t found on interface e: f⁻ = (ẋ, ẍ) of the modes before it into
    g.f_minus, and the gradient of the guard that crossed into g.guard_normal; returns
    its ∂g/∂t (nonzero for a breakaway only, through the excitation)."""
    g = state.tangent
    n = len(state.x)
    for i in range(n):
        g.f_minus[i] = state.v[i]
        g.f_minus[n + i] = w.a_end[i]
    if crossed(state.contact_before[e], w.contact[e]):
        contact_normal(e, s, g)
        return 0.0
    if state.modes[e] != STICK:
        slip_normal(e, s, g)
        return 0.0
    linearise(t, state.x, state.v, state.modes, topology, s, g)
    gw = g.work
    static_friction(topology.operator, topology.stuck_interfaces, s.mass, gw.resultant,
                    g.acceleration, gw.normal, s.sin_angle, s.left, s.right, gw.imbalance,
                    gw.friction)
    sign = 1.0 if gw.friction[e] >= 0.0 else -1.0
    return breakaway_normal(e, sign, t, s, state.modes, topology, g)


@njit_step_merged
def crossings_coincide(t, crossing, time_rate, state, topology, s, w):
    """Whether every guard crossed together with ``crossing``'s (gradient in
    g.guard_normal, ∂/∂t ``time_rate``) is the same surface on the stick clusters, as for
    two interfaces that join the same two clusters: then the switch is one. g.f_plus
    holds the first gradient meanwhile (it is free until the switch is resolved);
    g.guard_normal and g.f_minus are left as ``guard_gradient`` of ``crossing`` made them."""
    g = state.tangent
    first = g.f_plus
    for r in range(len(first)):
        first[r] = g.guard_normal[r]
    reduce_to_clusters(first, s, topology, g.rows)
    coincide = True
    for e in range(len(state.modes)):
        if e == crossing or not (crossed(state.contact_before[e], w.contact[e])
                                 or crossed(state.motion_before[e], w.motion[e])):
            continue
        rate = guard_gradient(t, e, state, topology, s, w)
        reduce_to_clusters(g.guard_normal, s, topology, g.rows)
        if not same_surface(first, time_rate, g.guard_normal, rate):
            coincide = False
            break
    guard_gradient(t, crossing, state, topology, s, w)
    return coincide


@njit_step_exact
def crossed_gradients(t, state, topology, s, w, sw):
    """Every interface whose guard crossed at t, the gradient n of its guard (one row
    each) and its rate nᵀ f⁻ + ∂g/∂t (``guard_gradient``), into sw.crossings,
    sw.crossing_normals and sw.crossing_rates, for ``apply_saltations``; returns their
    number."""
    g = state.tangent
    crossings, normals, rates = sw.crossings, sw.crossing_normals, sw.crossing_rates
    k = 0
    for e in range(len(state.modes)):
        if not (crossed(state.contact_before[e], w.contact[e])
                or crossed(state.motion_before[e], w.motion[e])):
            continue
        rate = guard_gradient(t, e, state, topology, s, w)
        for r in range(len(g.guard_normal)):
            normals[k, r] = g.guard_normal[r]
            rate += g.guard_normal[r] * g.f_minus[r]
        crossings[k] = e
        rates[k] = rate
        k += 1
    return k


# ---- detect: switches hidden inside a step ------------------------------------------------

@njit_step_merged
def breakaway_dense(t, h, state, topology, s, w):
    """The first fraction of the adaptive step from t where a stuck interface's breakaway
    margin has crossed, else 2.

    A stuck phase has no integration error to shorten the steps, so one step can span a
    whole excursion of the static friction beyond μ_s N. The margins are sampled at
    ``DIP_POINTS`` on the dense output (the first two kept in w.contact_trial and
    w.motion_trial), then checked where a parabola through the samples and the step's ends
    puts them lowest.
    """
    modes, before = state.modes, state.motion_before
    kept = (w.contact_trial, w.motion_trial)
    for k in range(len(DIP_POINTS)):
        theta = DIP_POINTS[k]
        dense_motion(theta, h, state, w, w.xt, w.vt)
        stuck_forces(t + theta * h, w.xt, w.vt, modes, topology, s, w)
        for e in topology.stuck_interfaces:
            margin = breakaway_margin(s.static_mu[e], w.normal[e], w.friction[e])
            if crossed(before[e], margin):
                return theta
            if k < len(kept):
                kept[k][e] = margin
    first = 2.0
    for e in topology.stuck_interfaces:
        theta, value = predicted_low((before[e], w.contact_trial[e], w.motion_trial[e],
                                      breakaway_margin(s.static_mu[e], w.normal[e],
                                                       w.friction[e]), w.motion[e]))
        if value < 0.0 and 0.0 < theta < first:
            first = theta
    if first < 1.0:
        dense_motion(first, h, state, w, w.xt, w.vt)
        stuck_forces(t + first * h, w.xt, w.vt, modes, topology, s, w)
        if stuck_crossed(topology, state, s, w):
            return first
    return 2.0


@njit_step
def breakaway_fixed(t, h, state, topology, s, w):
    """``breakaway_dense`` for the fixed-step RK4 step of size h from t: the margins are
    sampled at its middle and checked where a parabola through them and the step's ends
    puts them lowest, each state integrated anew from the step's start. Returns θ ≤ 1, or
    2 with the step's end state and guards restored in w."""
    modes = state.modes
    rk4_step_apart(t, 0.5 * h, state, topology, s, w)
    stuck_forces(t + 0.5 * h, w.x_new, w.v_new, modes, topology, s, w)
    if stuck_crossed(topology, state, s, w):
        return 0.5
    first = 2.0
    for e in topology.stuck_interfaces:
        theta, value = predicted_low((state.motion_before[e],
                                      breakaway_margin(s.static_mu[e], w.normal[e],
                                                       w.friction[e]), w.motion[e]))
        if value < 0.0 and 0.0 < theta < first:
            first = theta
    if first < 1.0:
        rk4_step_apart(t, first * h, state, topology, s, w)
        stuck_forces(t + first * h, w.x_new, w.v_new, modes, topology, s, w)
        if stuck_crossed(topology, state, s, w):
            return first
    rk4_guarded_apart(t, h, state, topology, s, w)
    return 2.0


@njit_step
def graze_fixed(t, h, state, topology, s, w, tolerance):
    """``detect.graze_dense`` for the fixed-step RK4 step of size h from t, on the contacts
    ``detect.mark_grazing`` marked, each trial state integrated anew from the step's start.
    Returns θ ≤ 1, or 2 with the step's end state and guards restored in w when no contact
    guard dips below 0."""
    modes = state.modes
    candidates = w.contact_trial
    first = 2.0
    for e in range(len(modes)):
        if candidates[e] == 0.0:
            continue
        lo, hi = 0.0, 1.0
        while (hi - lo) * h > tolerance:
            mid = 0.5 * (lo + hi)
            rk4_step_apart(t, mid * h, state, topology, s, w)
            if contact_guard(e, w.x_new, w.v_new, modes, s)[1] < 0.0:
                lo = mid
            else:
                hi = mid
        rk4_step_apart(t, hi * h, state, topology, s, w)
        if contact_guard(e, w.x_new, w.v_new, modes, s)[0] < 0.0:
            first = min(first, hi)
    if first > 1.0:
        rk4_guarded_apart(t, h, state, topology, s, w)
    return first


# ---- resolve and regroup: a switch, in storage allocated once per run ------------------

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
        if HAS_PRESCRIBED:
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
        lost = project_velocities(s, topology, v_trial, w.scratch)
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
        if not (several and apply_saltations(t, n_crossed, s, topology, g, sw)):
            apply_saltation(t, crossing, time_rate, several, s, topology, g)
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


@njit_step_exact
def begin(state, s, w, sw, controls, out):
    """The start at t0: consistent modes, velocities projected onto their clusters, the
    first sample. Returns (status, topology).

    The tangent's velocity rows are projected as the state's are (the derivative of the
    start's projection)."""
    initial_modes(state, s, w, sw.candidates)
    status, lost, topology, _ = settle(controls.t0, state, regroup(s, state.modes, sw), s, w,
                                       sw)
    state.energy[PROJECTION] += lost
    if HAS_TANGENT:
        project_tangent(s, topology, state.tangent)
    start(controls.t0, state, topology, s, w)
    record(out, np.int64(0), controls.t0, state.x, state.v, state.modes, state.energy, w)
    return status, topology


# ---- locate: the switch inside a step ----------------------------------------------------

@njit_step_merged
def locate_fixed(t, h, theta, state, topology, s, w, controls):
    """The earliest switch in (0, θh] of the RK4 step from t of size h; moves the state
    there.

    The switch lies in (lo, hi] of the step; each trial state is integrated anew from the
    step's start. Returns hi, the step taken, with the guards at its end in w.
    """
    width = controls.event_tolerance
    rk4_guarded_apart(t, theta * h, state, topology, s, w)
    lo, f_lo, hi, f_hi, side, g = bracket_start(theta * h, state, w)
    previous, slow = hi, np.int64(0)
    while hi - lo > width:
        trial, slow = next_trial(lo, f_lo, hi, f_hi, width, previous, slow)
        previous = hi - lo
        rk4_guarded_apart(t, trial, state, topology, s, w)
        lo, f_lo, hi, f_hi, side, g = bracket_after(lo, f_lo, hi, f_hi, side, g, trial, state,
                                                    w)
    rk4_guarded_apart(t, hi, state, topology, s, w)
    move_state(state, w)
    return hi


@njit_step_merged
def dense_guards(t, h, theta, state, topology, s, w):
    """The guards at t + θh on the dense output of the adaptive step of size h from t, into
    w.contact / w.motion (the state there in w.xt, w.vt).

    Contact and slip guards are functions of the state alone: without stuck interfaces
    no force is evaluated (``detect.kinematic_guards``). A
    breakaway margin needs the static friction, so with stuck interfaces the forces are
    evaluated too.
    """
    dense_motion(theta, h, state, w, w.xt, w.vt)
    if len(topology.stuck_interfaces) > 0:
        evaluate_guards_apart(t + theta * h, w.xt, w.vt, state.modes, topology, s, w,
                              w.a_sample)
        return
    kinematic_guards(w.xt, w.vt, state.modes, s, w, w.contact, w.motion)


@njit_step_merged
def locate_dense(t, h, theta, sample, state, topology, s, w, controls, out):
    """The earliest switch in (0, θ] of the adaptive step from t of size h; moves the state
    there.

    The switch is located on the step's dense output to half the event tolerance, the
    samples up to it are recorded, and the state half a tolerance past it is integrated
    anew by a Dormand–Prince step from t, so that the state and its work columns keep the
    order of the steps rather than the dense output's. Should that state not have
    crossed yet (the two differ by the dense output's error), the dense output's state
    is taken. Leaves the guards there in w. Returns (the switch time, the next sample).
    """
    width = 0.5 * controls.event_tolerance / h
    dense_guards(t, h, theta, state, topology, s, w)
    lo, f_lo, hi, f_hi, side, g = bracket_start(theta, state, w)
    previous, slow = hi, np.int64(0)
    while hi - lo > width:
        trial, slow = next_trial(lo, f_lo, hi, f_hi, width, previous, slow)
        previous = hi - lo
        dense_guards(t, h, trial, state, topology, s, w)
        lo, f_lo, hi, f_hi, side, g = bracket_after(lo, f_lo, hi, f_hi, side, g, trial, state,
                                                    w)
    past = min(1.0, hi + width)
    t_final = last_sample(controls)
    t_event = t_final if past == 1.0 and t + h >= t_final else t + past * h
    sample = record_dense(sample, t, t_event, h, state, topology, s, w, controls, out)
    dp5_step_apart(t, t_event - t, state, topology, s, w, controls)
    tangent = HAS_TANGENT and state.tangent.matrix.shape[1] > 0
    if any_crossed(state, w):
        if HAS_TANGENT and tangent:
            tangent_step(t, t_event - t, state, topology, s, w, controls)
            commit_tangent(state.tangent, s, controls.orthonormalise)
    else:  # the whole step again, for its dense output at hi
        t_event = t + hi * h
        # the tangent of a step to hi, which the dense state matches to its error
        if HAS_TANGENT and tangent:
            dp5_step_apart(t, hi * h, state, topology, s, w, controls)
            tangent_step(t, hi * h, state, topology, s, w, controls)
            commit_tangent(state.tangent, s, controls.orthonormalise)
        dp5_step_apart(t, h, state, topology, s, w, controls)
        dense_state(hi, h, state, w, w.x_new, w.v_new, w.e_new)
        evaluate_guards_apart(t_event, w.x_new, w.v_new, state.modes, topology, s, w, w.a_end)
    move_state(state, w)
    return t_event, sample


@njit_step_merged
def record_dense(sample, t, t_to, h, state, topology, s, w, controls, out):
    """Record the samples in (t, t_to] from the dense output of the step of size h from t.

    Returns the index of the next sample. Overwrites the forces in w (``sample_forces``).
    """
    while sample < controls.n_samples:
        time = controls.t0 + sample * controls.sample_step
        if time > t_to:
            break
        dense_state((time - t) / h, h, state, w, w.xt, w.vt, w.e_sample)
        sample_forces(time, w.xt, w.vt, state.modes, topology, s, w)
        record(out, sample, time, w.xt, w.vt, state.modes, w.e_sample, w)
        if HAS_TANGENT:  # the growth to within a step of the sample: enough for its spread
            for c in range(len(state.tangent.log_growth)):
                state.tangent.history[sample, c] = state.tangent.log_growth[c]
        sample += 1
    return sample


# ---- the drivers --------------------------------------------------------------------------

@njit_step_merged
def advance_fixed(k, t, state, topology, s, w, controls, out, sample):
    """RK4 steps along the grid t0 + k·step, recording samples, until a guard crosses.

    Starts at time t inside step k (t = t0 + k·step unless a switch was just resolved).
    Returns (k, t, sample, status, switched): with ``switched``, t is the first switch
    found in step k, located (``locate_fixed``) and the state moved there; otherwise the
    run took its last sample or stopped with the status.
    """
    n_steps = (controls.n_samples - 1) * controls.steps_per_sample
    while k < n_steps:
        t_end = controls.t0 + (k + 1) * controls.step
        h = t_end - t
        rk4_guarded(t, h, state, topology, s, w)
        theta = 2.0
        if (HAS_CONTACT_EVENTS or HAS_STICK) and any_crossed(state, w):
            theta = 1.0
        else:
            if HAS_CONTACT_EVENTS and mark_grazing(h, state, s, w):
                theta = graze_fixed(t, h, state, topology, s, w, controls.event_tolerance)
            if HAS_STICK and len(topology.stuck_interfaces) > 0:
                theta = min(theta, breakaway_fixed(t, h, state, topology, s, w))
        if theta <= 1.0:
            hi = locate_fixed(t, h, theta, state, topology, s, w, controls)
            return k, t_end if hi == h else t + hi, sample, FINISHED, True
        keep_guards(state, w)
        take_step(state, w)
        if not is_finite(state):
            return k, t, sample, NOT_FINITE, False
        t = t_end
        k += 1
        if k % controls.steps_per_sample == 0:
            record(out, sample, t, state.x, state.v, state.modes, state.energy, w)
            sample += 1
    return k, t, sample, FINISHED, False


@njit_step_callable
def run_fixed_step(state, s, w, sw, events, controls, out):
    """Integrate fixed RK4 steps of ``controls.step`` from the state at t0 to the last
    sample, locating every switch, in the records ``records.allocate`` made; returns
    (status, the time it stopped at, the interface that stopped it or −1, steps, samples),
    for ``records.finish``.

    Steps stay on the grid t0 + k·step: after a switch inside a step, the rest of the step
    is integrated in the new modes. Samples are taken every ``steps_per_sample`` steps.
    Zeno guard: ``zeno_events`` switches within ``zeno_window`` seconds stop the run.
    """
    status, topology = begin(state, s, w, sw, controls, out)
    k, t, sample = np.int64(0), controls.t0, np.int64(1)
    stop_interface = -1
    while status == FINISHED:
        k, t, sample, status, switched = advance_fixed(k, t, state, topology, s, w, controls,
                                                       out, sample)
        if not switched or status != FINISHED:
            break
        t_end = controls.t0 + (k + 1) * controls.step
        status, stop_interface, topology = switch(t, state, topology, s, w, sw, events,
                                                  controls)
        if t == t_end:
            k += 1
            if k % controls.steps_per_sample == 0:
                record(out, sample, t, state.x, state.v, state.modes, state.energy, w)
                sample += 1
    return status, t, stop_interface, k, sample


@njit_step_merged
def advance_adaptive(t, h, sample, steps, state, topology, s, w, controls, out):
    """Dormand–Prince steps from t, recording samples, until a guard crosses or the end.

    Returns (t, h, sample, steps, status, switched): with ``switched``, t is the first
    switch found, located (``locate_dense``) and the state moved there; otherwise the run
    reached its last sample or stopped with the status. A step that shrinks below
    h_min stops the run: NOT_FINITE if the last trial's error was inf or NaN (a law gave a
    non-finite force ahead), else STEP_TOO_SMALL; ``STALL_STEPS`` accepted steps in a row
    below ``STALL_SIZE``·h_min stop it as STALLED.
    """
    error = 0.0
    tiny = 0
    t_final = last_sample(controls)
    while sample < controls.n_samples:
        last = h >= t_final - t
        if last:
            h = t_final - t
        if h < controls.h_min and not (last and h > 0.0):
            status = STEP_TOO_SMALL if math.isfinite(error) else NOT_FINITE
            return t, h, sample, steps, status, False
        error = dp5_step(t, h, state, topology, s, w, controls)
        tangent = HAS_TANGENT and state.tangent.matrix.shape[1] > 0
        if HAS_TANGENT and tangent and error <= 1.0:
            error = max(error, tangent_step(t, h, state, topology, s, w, controls))
        if not error <= 1.0:
            h = retry_step(h, error)
            continue
        steps += 1
        tiny = tiny + 1 if h < STALL_SIZE * controls.h_min else 0
        if tiny > STALL_STEPS:
            return t, h, sample, steps, STALLED, False
        if HAS_CONTACT_EVENTS or HAS_STICK:
            theta = 1.0 if any_crossed(state, w) else 2.0
            theta = min(theta, kinematic_dip(h, state, s, w))
            if HAS_STICK and len(topology.stuck_interfaces) > 0:
                theta = min(theta, breakaway_dense(t, h, state, topology, s, w))
            if HAS_CONTACT_EVENTS:
                theta = min(theta, graze_dense(h, controls.event_tolerance, state, s, w))
            if theta <= 1.0:
                t, sample = locate_dense(t, h, theta, sample, state, topology, s, w, controls,
                                         out)
                return t, h, sample, steps, FINISHED, True
        t_new = t_final if last else t + h
        if HAS_TANGENT and tangent:
            commit_tangent(state.tangent, s, controls.orthonormalise)
        keep_guards(state, w)
        sample = record_dense(sample, t, t_new, h, state, topology, s, w, controls, out)
        take_step(state, w)
        if not is_finite(state):
            return t, h, sample, steps, NOT_FINITE, False
        t = t_new
        h = next_step(h, error, controls.h_max)
    return t, h, sample, steps, FINISHED, False


@njit_step_callable
def run_adaptive(state, s, w, sw, events, controls, out):
    """Integrate by Dormand–Prince 5(4) from the state at t0 to the last sample, in the
    records ``records.allocate`` made; returns what ``run_fixed_step`` returns.

    Steps are accepted when the scaled local error (``dp5_step``) is at most 1, and the next
    step follows from the controller (``advance.next_step``), capped at h_max. Samples at
    t0 + k·sample_step and the guards inside a step come from the step's dense output, so
    steps never shorten to meet them. A step below h_min stops the run (STEP_TOO_SMALL).
    """
    status, topology = begin(state, s, w, sw, controls, out)
    # np.int64, not literals: a literal argument would compile the callee twice
    t, h, sample, steps = controls.t0, min(controls.step, controls.h_max), np.int64(1), \
        np.int64(0)
    stop_interface = -1
    while status == FINISHED and sample < controls.n_samples:
        t, h, sample, steps, status, switched = advance_adaptive(t, h, sample, steps, state,
                                                                 topology, s, w, controls, out)
        if not switched or status != FINISHED:
            break
        status, stop_interface, topology = switch(t, state, topology, s, w, sw, events,
                                                  controls)
    return status, t, stop_interface, steps, sample
