"""Forces: the laws' forces on every interface, the accelerations and powers of a mode set,
and the guards at the end of each step (law-aware; ``dynamics`` assembles the rest).

``derivative`` is the right-hand side every Runge–Kutta stage evaluates; ``evaluate_guards``
adds the static friction of stuck interfaces and the event guards (``detect``).
"""

import math
from typing import TYPE_CHECKING

from contact_laws.base import ZERO_PLUS_SPEED
from shroudnet.engine.codes import OPEN, SLIP_POSITIVE, STICK
from shroudnet.engine.compiled import (njit_entry, njit_inlined, njit_step,
                                       njit_step_merged)
from shroudnet.engine.constraints import constrained_accelerations, prescribed_power
from shroudnet.engine.detect import event_guards
from shroudnet.engine.dynamics import (cluster_accelerations, continued_mu, coupling_forces,
                                       driven_accelerations, excitation_forces,
                                       interface_kinematics, prescribed_acceleration,
                                       resultant_forces, static_friction)
from shroudnet.engine.sliders import (push_second_friction, slider_forces, slider_guards,
                                     slider_rate)
from shroudnet.engine.structures import kinematics, structure_resultant
from shroudnet.engine.support import row_dot

if TYPE_CHECKING:
    from .generated import (HAS_COUPLINGS, HAS_FRICTION, HAS_PRESCRIBED, HAS_REGULARISED,
                            HAS_SLIDERS, HAS_STICK, HAS_STRUCTURES, friction_coefficient,
                            friction_slope, normal_force, normal_force_gradient)


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
    return continued_mu(mu, friction_slope(kind, params, size), speed)


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
        if HAS_SLIDERS:
            if s.slider_index[e] >= 0:  # an elastic contact's: ``sliders``
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

    With substructures (``HAS_STRUCTURES``) the stuck interfaces' static friction is part
    of the accelerations (``constraints``) and lands in w.friction here.
    """
    if HAS_STRUCTURES:
        return structure_derivative(t, x, v, modes, topology, s, w, acceleration)
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


@njit_inlined
def structure_derivative(t, x, v, modes, topology, s, w, acceleration):
    """``derivative`` of a scene with substructures: R from the laws and the structure
    (``structures.structure_resultant``), ẍ and the static friction from the constraints
    (``constraints.constrained_accelerations``)."""
    kinematics(x, v, s, w.penetration, w.rate, w.slip)
    law_forces(s, modes, w)
    if HAS_SLIDERS:
        slider_forces(x, modes, s, w)
    excitation_forces(t, s.amplitudes, s.cos_phase, s.sin_phase, s.excitation_frequency,
                      w.q)
    damping = structure_resultant(x, v, s, w)
    if HAS_SLIDERS:
        push_second_friction(s, w)
    friction = 0.0
    contact = 0.0
    for e in range(len(modes)):
        if not (HAS_SLIDERS and s.slider_index[e] >= 0):  # a slider's is f·ẇ, below
            friction += w.friction[e] * w.slip[e]
        contact += w.normal[e] * w.rate[e]
    if HAS_PRESCRIBED:
        for p in range(len(w.drive)):
            w.drive[p] = prescribed_acceleration(t, s, p)[0]
    constrained_accelerations(s, topology, w.resultant, w.drive, acceleration, w.friction)
    if HAS_SLIDERS:
        friction += slider_rates(s, modes, v, w, acceleration)
    excitation = 0.0
    if HAS_PRESCRIBED:
        excitation = prescribed_power(s, topology, w.resultant, v, w.friction, len(w.drive))
    for i in range(len(x)):
        excitation += w.q[i] * v[i]
    return excitation, damping, friction, contact


@njit_inlined
def slider_rates(s, modes, v, w, acceleration):
    """u̇ of every elastic contact's stretch (``sliders``) into its acceleration slots,
    from the accelerations of the structure: Ṅ = ∂N/∂δ δ̇ + ∂N/∂δ̇ δ̈ with δ̈ = n·ẍ.
    Returns the power the sliders take out, Σ f·ẇ [W]."""
    power = 0.0
    for e in range(len(modes)):
        k = s.slider_index[e]
        if k < 0:
            continue
        normal_rate = 0.0
        if modes[e] != OPEN:
            slope, rate_slope = normal_force_gradient(s.normal_kind[e], s.normal_params[e],
                                                      w.penetration[e], w.rate[e])
            normal_rate = slope * w.rate[e] \
                + rate_slope * row_dot(s, s.normal_rows, e, acceleration, 0)
        first, second, loss = slider_rate(s, e, v, w, modes[e], normal_rate)
        acceleration[k] = first
        acceleration[k + 1] = second
        power += loss
    return power


@njit_step_merged
def evaluate_guards(t, x, v, modes, topology, s, w, acceleration):
    """``derivative``, then static friction and guards into w (w.friction includes static).

    Returns the powers, as ``derivative``. Merged into the step loops; the paths taken
    once per switch call ``evaluate_guards_apart``.
    """
    powers = derivative(t, x, v, modes, topology, s, w, acceleration)
    if HAS_STICK and not HAS_STRUCTURES and len(topology.stuck_interfaces) > 0:
        static_friction(topology.operator, topology.stuck_interfaces, s.mass, w.resultant,
                        acceleration, w.normal, s.sin_angle, s.left, s.right, w.imbalance,
                        w.friction)
    event_guards(modes, w.penetration, w.slip, w.normal, w.friction, s.static_mu, s.opens,
                 s.can_stick, w.contact, w.motion)
    if HAS_SLIDERS:
        slider_guards(modes, s, w, w.motion)
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
    kinematics(xt, vt, s, w.penetration, w.rate, w.slip)
    law_forces(s, modes, w)
    if HAS_SLIDERS:
        slider_forces(xt, modes, s, w)


@njit_step_merged
def stuck_forces(time, xt, vt, modes, topology, s, w):
    """The forces, static friction included, at the state (xt, vt) inside a step, into w's
    scratch (the step's end guards in w.contact / w.motion are kept)."""
    derivative(time, xt, vt, modes, topology, s, w, w.a_sample)
    if HAS_STRUCTURES:
        return
    static_friction(topology.operator, topology.stuck_interfaces, s.mass, w.resultant,
                    w.a_sample, w.normal, s.sin_angle, s.left, s.right, w.imbalance, w.friction)
