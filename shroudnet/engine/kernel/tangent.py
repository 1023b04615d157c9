"""Tangent: the law-aware half of the tangent flow (law-free: ``shroudnet.engine.tangent``).

The laws' slopes at a state (``linearise``), the tangent through a Dormand–Prince step
(``tangent_step``), and the gradients of the guards that cross at a switch, which the
saltation matrices (``shroudnet.engine.saltation``) are built from. Compiled into the
kernels of runs that integrate the tangent flow; others never call it.
"""

import math
from typing import TYPE_CHECKING

import numpy as np

from shroudnet.engine.codes import OPEN, SLIP_POSITIVE, STICK
from shroudnet.engine.compiled import (njit_inlined, njit_step, njit_step_callable,
                                       njit_step_exact, njit_step_merged)
from shroudnet.engine.detect import crossed, guard_crossed
from shroudnet.engine.dynamics import static_friction
from shroudnet.engine.exponential import exponential
from shroudnet.engine.records import new_switching, new_tangent, new_work, plain, square_size
from shroudnet.engine.regroup import regroup
from shroudnet.engine.saltation import (breakaway_normal, contact_normal, reduce_to_clusters,
                                        same_surface, slip_normal)
from shroudnet.engine.slider_tangent import (first_order_field, leave_out_unresolved,
                                             slider_breakaway_normal)
from shroudnet.engine.stage_forces import START, start_kept
from shroudnet.engine.tableau import DP_STAGES
from shroudnet.engine.tangent import (candidate_tangent, last_stage_tangent,
                                      linearised_acceleration, orthonormalise, stage_tangent,
                                      tangent_error, time_scale)

if TYPE_CHECKING:
    from .forces import derivative, sliding_coefficient
    from .generated import (HAS_FRICTION, HAS_REGULARISED, HAS_SLIDERS, HAS_STRUCTURES,
                            friction_coefficient, friction_slope, normal_force_gradient)


@njit_inlined
def friction_slopes(s, e, mode, w):
    """(μ, σ, ∂f/∂w) of the sliding friction f = μ σ N of interface e in ``mode``, at the
    slip velocity w in w.slip: σ = ±1 by the slip mode and μ at σw
    (``sliding_coefficient``), so ∂f/∂w = N μ'(σw); for a regularised law σ = tanh(w/ε)
    and μ at |w|, so ∂f/∂w = N (μ'(|w|) sgn(w) σ + μ σ')."""
    kind, params, slip = s.friction_kind[e], s.friction_params[e], w.slip[e]
    if HAS_REGULARISED and s.regularisation[e] > 0.0:
        mu = friction_coefficient(kind, params, abs(slip))
        sigma = math.tanh(slip / s.regularisation[e])
        d_sigma = (1.0 - sigma * sigma) / s.regularisation[e]
        sign = 1.0 if slip >= 0.0 else -1.0
        return mu, sigma, w.normal[e] * (friction_slope(kind, params, abs(slip)) * sign
                                         * sigma + mu * d_sigma)
    sigma = 1.0 if mode == SLIP_POSITIVE else -1.0
    mu, slope = sliding_coefficient(kind, params, sigma * slip)
    return mu, sigma, w.normal[e] * slope


@njit_step
def linearise(t, x, v, modes, topology, s, g):
    """The forces at (t, x, v) into g.work, and each closed interface's slopes into g:
    ∂N/∂u = ∂N/∂δ sin α and ∂N/∂u̇ = ∂N/∂δ̇ sin α, and, unless it is stuck, ∂F/∂u and ∂F/∂u̇ of
    F = N sin α + f cos α, with f = μ(|w|) N σ, w = u̇ cos α, σ = ±1 by the slip mode
    and μ at σw (``sliding_coefficient``): ∂f/∂u = μ σ ∂N/∂u, ∂f/∂u̇ = μ σ ∂N/∂u̇ +
    N μ'(σw) cos α; for a regularised law σ = tanh(w/ε) and μ at |w|, so the last term is
    N (μ'(|w|) sgn(w) σ + μ σ') cos α (paper eqs. 2–6).

    With substructures (``HAS_STRUCTURES``) the normal and slip directions are rows of
    their own (``structures``), so the slopes are kept apart: ∂N/∂δ and ∂N/∂δ̇, then
    ∂f/∂N = μσ and ∂f/∂w (w the slip velocity), the last two in force_u and force_du."""
    derivative(t, x, v, modes, topology, s, g.work, g.acceleration)
    slopes(modes, s, g)


@njit_step
def slopes(modes, s, g):
    """``linearise``'s slopes, from the forces already in g.work."""
    w = g.work
    for e in range(len(modes)):
        g.normal_u[e] = 0.0
        g.normal_du[e] = 0.0
        g.force_u[e] = 0.0
        g.force_du[e] = 0.0
        if modes[e] == OPEN:
            continue
        d_penetration, d_rate = normal_force_gradient(s.normal_kind[e], s.normal_params[e],
                                                      w.penetration[e], w.rate[e])
        if HAS_STRUCTURES:
            g.normal_u[e] = d_penetration
            g.normal_du[e] = d_rate
            if HAS_SLIDERS:
                if s.slider_index[e] >= 0:  # its friction is its spring's: ``slider_tangent``
                    continue
            if modes[e] != STICK and HAS_FRICTION and s.friction_kind[e] >= 0:
                mu, sigma, d_slip = friction_slopes(s, e, modes[e], w)
                g.force_u[e] = mu * sigma
                g.force_du[e] = d_slip
            continue
        sine, cosine = s.sin_angle[e], s.cos_angle[e]
        g.normal_u[e] = d_penetration * sine
        g.normal_du[e] = d_rate * sine
        if modes[e] == STICK:
            continue
        force_u = sine * g.normal_u[e]
        force_du = sine * g.normal_du[e]
        if HAS_FRICTION and s.friction_kind[e] >= 0:
            mu, sigma, d_slip = friction_slopes(s, e, modes[e], w)
            force_u += cosine * mu * sigma * g.normal_u[e]
            force_du += cosine * (mu * sigma * g.normal_du[e] + d_slip * cosine)
        g.force_u[e] = force_u
        g.force_du[e] = force_du


def linearise_at(t, x, v, modes, s, tangent0):
    """``linearise`` and the vector field's Jacobian at (t, x, v) in ``modes``, callable
    from Python for tests: returns (J, ẍ), J = ∂(ẋ, ẍ)/∂(x, ẋ) (2 n_blades square)."""
    n = len(x)
    g = plain(new_tangent)(tangent0, len(modes), 1,
                           plain(new_work)(n, len(modes), len(s.motion_amplitude)))
    jacobian = np.zeros((2 * n, 2 * n))
    fill_jacobian(t, x, v, modes, s, g, plain(new_switching)(n, len(modes), square_size(s)),
                  jacobian)
    return jacobian, g.acceleration.copy()


@njit_step_callable
def fill_jacobian(t, x, v, modes, s, g, sw, jacobian):
    """``linearise_at``'s Jacobian into ``jacobian``, in storage allocated by the caller
    (g: ``records.Tangent``, sw: ``records.Switching``)."""
    topology = regroup(s, modes, sw)
    linearise(t, x, v, modes, topology, s, g)
    jacobian_into(s, modes, topology, g, jacobian)


@njit_step
def jacobian_into(s, modes, topology, g, jacobian):
    """J = ∂(ẋ, ẍ)/∂(x, ẋ) into ``jacobian``, column by column, from the slopes in g
    (``linearise``)."""
    n = jacobian.shape[0] // 2
    for r in range(2 * n):
        for q in range(2 * n):
            g.direction[q] = 1.0 if q == r else 0.0
        linearised_acceleration(g.direction, s, modes, topology, g)
        for i in range(n):
            jacobian[i, r] = g.direction[n + i]
            jacobian[n + i, r] = g.acceleration_change[i]


@njit_inlined
def by_phase(state, controls):
    """Whether this run carries its tangent by phase (``carry_phase``) rather than with
    every step: substructures whose vector field is linear between switches, in a run
    that keeps no orthonormal basis or that propagates its phases exactly
    (``records.Controls.exponentials``)."""
    return HAS_STRUCTURES and controls.exponentials and state.tangent.matrix.shape[1] > 0


@njit_inlined
def stepwise(state, controls):
    """Whether this run carries its tangent with every step (``tangent_step``)."""
    return state.tangent.matrix.shape[1] > 0 and not by_phase(state, controls)


@njit_step
def carry_phase(t_from, t_to, state, topology, s):
    """Φ ← e^{J (t_to − t_from)} Φ: the tangent carried through a phase between switches
    over which the vector field is linear in the state (``SceneArrays.linear_phases``), so
    that J, here from the slopes at the state at t_to in the phase's modes, is the same
    all through it. The exponential is taken of D J D⁻¹ (t_to − t_from) with
    D = diag(I, τ I) (τ: ``time_scale``), whose displacement and velocity blocks are of
    one size, and brought back by D⁻¹ · D."""
    if t_to <= t_from:
        return
    g = state.tangent
    linearise(t_to, state.x, state.v, state.modes, topology, s, g)
    work = g.phase_work
    jacobian = work[0]
    jacobian_into(s, state.modes, topology, g, jacobian)
    size = jacobian.shape[0]
    n = size // 2
    weight = time_scale(s)
    span = t_to - t_from
    for r in range(size):
        for c in range(size):
            jacobian[r, c] *= span * (weight if r >= n else 1.0) / (weight if c >= n else 1.0)
    exponential(work)
    for r in range(size):
        for c in range(size):
            jacobian[r, c] *= (weight if c >= n else 1.0) / (weight if r >= n else 1.0)
    for r in range(size):
        for column in range(g.matrix.shape[1]):
            total = 0.0
            for q in range(size):
                total += jacobian[r, q] * g.matrix[q, column]
            g.candidate[r, column] = total
    for r in range(size):
        for column in range(g.matrix.shape[1]):
            g.matrix[r, column] = g.candidate[r, column]


@njit_step
def carry_tangent(t, state, topology, s, controls):
    """The tangent carried by phase from where it was last carried (``Tangent.since``) to
    t (``carry_phase``), and, for Lyapunov exponents (``controls.orthonormalise``), its
    columns orthonormalised there (``tangent.orthonormalise``)."""
    g = state.tangent
    carry_phase(g.since[0], t, state, topology, s)
    g.since[0] = t
    if controls.orthonormalise:
        orthonormalise(g, s)


@njit_inlined
def stage_slopes(slot, j, modes, s, g, w):
    """``linearise`` at stage j of the Dormand–Prince step just taken, from the forces
    its ``derivative`` found there (kept in g.stage_forces[slot]: ``stage_forces``) and the
    stage's accelerations in w: the same slopes, without evaluating the forces again. An
    elastic contact's stretch rate, which ``derivative`` leaves in its acceleration slots,
    is in the stage's velocities (``sliders.first_order_stage``)."""
    kept, forces = g.stage_forces[slot], g.work
    for e in range(kept.shape[1]):
        forces.penetration[e] = kept[0, e]
        forces.rate[e] = kept[1, e]
        forces.slip[e] = kept[2, e]
        forces.normal[e] = kept[3, e]
        forces.friction[e] = kept[4, e]
        forces.friction_second[e] = kept[5, e]
        forces.slider_speed[e] = kept[6, e]
    for i in range(len(g.acceleration)):
        g.acceleration[i] = w.stage_a[j, i]
    if HAS_SLIDERS:
        for e in range(len(s.slider_index)):
            k = s.slider_index[e]
            if k >= 0:
                g.acceleration[k] = w.stage_v[j, k]
                g.acceleration[k + 1] = w.stage_v[j, k + 1]
    slopes(modes, s, g)


@njit_step
def tangent_step(t, h, state, topology, s, w, controls):
    """The tangent through the Dormand–Prince step of size h from t just taken (its stages
    in w, the forces at each kept: ``stage_forces``), the exact derivative of the step
    (``tangent``), into state.tangent.candidate; returns its scaled local error
    (``tangent.tangent_error``). ``commit_tangent`` makes it the tangent."""
    g = state.tangent
    if start_kept(t, state, g):
        stage_slopes(START, 0, state.modes, s, g, w)
    else:
        x = g.work.xt
        v = g.work.vt
        for i in range(len(x)):
            x[i] = state.x[i]
            v[i] = w.stage_v[0, i]
        linearise(t, x, v, state.modes, topology, s, g)
    stage_tangent(0, h, s, state.modes, topology, g)
    for j in range(1, DP_STAGES - 1):
        stage_slopes(j, j, state.modes, s, g, w)
        stage_tangent(j, h, s, state.modes, topology, g)
    candidate_tangent(h, g)
    stage_slopes(DP_STAGES - 1, DP_STAGES - 1, state.modes, s, g, w)
    last_stage_tangent(s, state.modes, topology, g)
    if HAS_SLIDERS:
        leave_out_unresolved(state.modes, s, g)
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
    if HAS_SLIDERS:
        first_order_field(s, g.f_minus)
    if crossed(state.contact_before[e], w.contact[e]):
        contact_normal(e, s, g)
        return 0.0
    if HAS_SLIDERS:
        if s.slider_index[e] >= 0:
            return slider_guard_gradient(t, e, state, topology, s, g)
    if state.modes[e] != STICK:
        slip_normal(e, s, g)
        return 0.0
    linearise(t, state.x, state.v, state.modes, topology, s, g)
    gw = g.work
    if not HAS_STRUCTURES:  # substructures: the static friction came with the accelerations
        static_friction(topology.operator, topology.stuck_interfaces, s.mass, gw.resultant,
                        g.acceleration, gw.normal, s.sin_angle, s.left, s.right,
                        gw.imbalance, gw.friction)
    sign = 1.0 if gw.friction[e] >= 0.0 else -1.0
    return breakaway_normal(e, sign, t, s, state.modes, topology, g)


@njit_step
def slider_guard_gradient(t, e, state, topology, s, g):
    """``guard_gradient`` of elastic contact e's motion guard: breakaway's
    (``slider_tangent.slider_breakaway_normal``) from stick; from slip, none (0): the
    vector field is continuous where λ falls to 0 (u̇ jumps by û λ = 0), so the saltation
    of sticking is P whatever the gradient. ∂g/∂t is 0 for both."""
    g = state.tangent
    if state.modes[e] == STICK:
        linearise(t, state.x, state.v, state.modes, topology, s, g)
        slider_breakaway_normal(e, s, g)
    else:
        for r in range(len(g.guard_normal)):
            g.guard_normal[r] = 0.0
    return 0.0


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
        if e == crossing or not guard_crossed(state, w, e):
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
        if not guard_crossed(state, w, e):
            continue
        rate = guard_gradient(t, e, state, topology, s, w)
        for r in range(len(g.guard_normal)):
            normals[k, r] = g.guard_normal[r]
            rate += g.guard_normal[r] * g.f_minus[r]
        crossings[k] = e
        rates[k] = rate
        k += 1
    return k
