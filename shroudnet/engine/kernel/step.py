"""Step: one step with fixed modes, and what the method decides.

Fixed steps are classical RK4 (``rk4_step``), adaptive ones Dormand–Prince 5(4)
(``dp5_step``), exponential ones the exact propagation of a linear phase
(``exact_step``). Everything else in the loop is the same for every method (``ADAPTIVE``
and ``EXPONENTIAL``, constants of each kernel): a step is taken and sized here
(``trial_step``), and the state inside a step just taken is read off the dense output of
an adaptive one, integrated anew from the start of a fixed one, or propagated exactly
(``motion_inside``).
"""

from typing import TYPE_CHECKING

from shroudnet.engine.advance import dense_motion, set_powers
from shroudnet.engine.codes import N_POWERS, PROJECTION
from shroudnet.engine.compiled import njit_step, njit_step_merged
from shroudnet.engine.controller import accepted, scaled_error
from shroudnet.engine.propagation import load_state, propagate, store_state
from shroudnet.engine.sliders import first_order_rk4_end, first_order_rk4_stage, first_order_stage
from shroudnet.engine.stage_forces import keep_end, keep_stage, keep_start
from shroudnet.engine.tableau import DP_A, DP_B, DP_C, DP_STAGES, stage_sum

if TYPE_CHECKING:
    from .forces import derivative, evaluate_guards
    from .generated import ADAPTIVE, EXPONENTIAL, HAS_SLIDERS, HAS_TANGENT
    from .propagation import exact_step
    from .tangent import stepwise, tangent_step


@njit_step_merged
def rk4_step(t, h, state, topology, s, w):
    """One classical Runge–Kutta step of size h with fixed modes, into w.x_new, w.v_new and
    w.e_new.

    The first stage is the acceleration and powers at the state, held in w.a_start and
    w.stage_p[0], so a step costs three evaluations of ``derivative`` (plus the guards at
    its end). The sliders' stretches are first-order coordinates, whose rates
    ``derivative`` leaves in their acceleration slots (``sliders.first_order_rk4_stage``).
    """
    x, v, energy, modes = state.x, state.v, state.energy, state.modes
    a1, a2, a3, a4 = w.a_start, w.stage_a[1], w.stage_a[2], w.stage_a[3]
    xt, vt, p = w.xt, w.vt, w.stage_p
    for i in range(len(x)):
        xt[i] = x[i] + 0.5 * h * v[i]
        vt[i] = v[i] + 0.5 * h * a1[i]
    if HAS_SLIDERS:
        first_order_rk4_stage(s, x, 0.5 * h, a1, xt, vt)
    set_powers(p[1], derivative(t + 0.5 * h, xt, vt, modes, topology, s, w, a2))
    for i in range(len(x)):
        xt[i] = x[i] + 0.5 * h * (v[i] + 0.5 * h * a1[i])
        vt[i] = v[i] + 0.5 * h * a2[i]
    if HAS_SLIDERS:
        first_order_rk4_stage(s, x, 0.5 * h, a2, xt, vt)
    set_powers(p[2], derivative(t + 0.5 * h, xt, vt, modes, topology, s, w, a3))
    for i in range(len(x)):
        xt[i] = x[i] + h * (v[i] + 0.5 * h * a2[i])
        vt[i] = v[i] + h * a3[i]
    if HAS_SLIDERS:
        first_order_rk4_stage(s, x, h, a3, xt, vt)
    set_powers(p[3], derivative(t + h, xt, vt, modes, topology, s, w, a4))
    for i in range(len(x)):
        v2 = v[i] + 0.5 * h * a1[i]
        v3 = v[i] + 0.5 * h * a2[i]
        v4 = v[i] + h * a3[i]
        w.x_new[i] = x[i] + h / 6.0 * (v[i] + 2.0 * v2 + 2.0 * v3 + v4)
        w.v_new[i] = v[i] + h / 6.0 * (a1[i] + 2.0 * a2[i] + 2.0 * a3[i] + a4[i])
    if HAS_SLIDERS:
        first_order_rk4_end(s, x, h, a1, a2, a3, a4, w.x_new, w.v_new)
    for k in range(N_POWERS):
        w.e_new[k] = energy[k] + h / 6.0 * (p[0, k] + 2.0 * p[1, k] + 2.0 * p[2, k] + p[3, k])
    w.e_new[PROJECTION] = energy[PROJECTION]

@njit_step_merged
def rk4_guarded(t, h, state, topology, s, w):
    """``rk4_step``, then the forces and guards at its end (w.a_end, w.stage_p[-1])."""
    rk4_step(t, h, state, topology, s, w)
    set_powers(w.stage_p[DP_STAGES - 1], evaluate_guards(t + h, w.x_new, w.v_new, state.modes,
                                                         topology, s, w, w.a_end))

@njit_step_merged
def dp5_step(t, h, state, topology, s, w, controls):
    """One Dormand–Prince step of size h: the new state into w.x_new, w.v_new, w.e_new.

    Stage 1 is w.a_start / w.stage_p[0] (first same as last); the last stage is evaluated
    with the guards at the step's end, into w.a_end. Returns its scaled local error
    (``controller.scaled_error``; at most 1 accepts the step).
    """
    x, v, energy, modes = state.x, state.v, state.energy, state.modes
    n = len(x)
    last = DP_STAGES - 1
    sv, sa, sp = w.stage_v, w.stage_a, w.stage_p
    if HAS_TANGENT and stepwise(state, controls):
        keep_start(state.tangent)
    for i in range(n):
        sv[0, i] = v[i]
        sa[0, i] = w.a_start[i]
    if HAS_SLIDERS:
        first_order_stage(s, sv, sa, 0)
    for j in range(1, last):
        for i in range(n):
            w.xt[i] = x[i] + h * stage_sum(DP_A[j], sv, j, i)
            w.vt[i] = v[i] + h * stage_sum(DP_A[j], sa, j, i)
            sv[j, i] = w.vt[i]
        set_powers(sp[j], derivative(t + DP_C[j] * h, w.xt, w.vt, modes, topology, s, w,
                                     sa[j]))
        if HAS_TANGENT and stepwise(state, controls):
            keep_stage(j, state.tangent, w)
        if HAS_SLIDERS:
            first_order_stage(s, sv, sa, j)
    for i in range(n):
        w.x_new[i] = x[i] + h * stage_sum(DP_B, sv, last, i)
        w.v_new[i] = v[i] + h * stage_sum(DP_B, sa, last, i)
        sv[last, i] = w.v_new[i]
    for c in range(N_POWERS):
        w.e_new[c] = energy[c] + h * stage_sum(DP_B, sp, last, c)
    w.e_new[PROJECTION] = energy[PROJECTION]
    set_powers(sp[last], evaluate_guards(t + h, w.x_new, w.v_new, modes, topology, s, w,
                                         w.a_end))
    if HAS_TANGENT and stepwise(state, controls):
        keep_stage(last, state.tangent, w)
        keep_end(t + h, state.tangent, w, modes)
    for i in range(n):
        sa[last, i] = w.a_end[i]
    if HAS_SLIDERS:
        first_order_stage(s, sv, sa, last)
    return scaled_error(h, x, v, w.x_new, w.v_new, sv, sa, controls)


# The step loops merge the steps they take every step (a function compiled on its own takes
# the records as hundreds of machine words of arguments, and passing them cost more than
# the three blades' forces); the paths taken once per switch or inside a step call steps
# compiled once each: this one, and ``step_apart``.

@njit_step
def rk4_step_apart(t, h, state, topology, s, w):
    """``rk4_step`` compiled on its own."""
    rk4_step(t, h, state, topology, s, w)


# ---- what the method decides --------------------------------------------------------------

@njit_step_merged
def trial_step(t, h, state, topology, s, w, controls):
    """A step of size h from t with fixed modes, into w.x_new, w.v_new, w.e_new, with the
    forces and guards at its end (w.a_end, w.contact, w.motion). Returns its scaled error
    (``controller.scaled_error``, the tangent's included where one is carried; always 0
    for a fixed step, which is never rejected)."""
    if EXPONENTIAL:
        exact_step(t, h, state, topology, s, w)
        return 0.0
    if not ADAPTIVE:
        rk4_guarded(t, h, state, topology, s, w)
        return 0.0
    error = dp5_step(t, h, state, topology, s, w, controls)
    if HAS_TANGENT and stepwise(state, controls) and accepted(error):
        error = max(error, tangent_step(t, h, state, topology, s, w, controls))
    return error


@njit_step
def step_apart(t, h, state, topology, s, w, controls):
    """``trial_step`` without the tangent, compiled on its own: the step to a located
    switch, or again to the end of a step whose inside a fixed step overwrote."""
    if EXPONENTIAL:
        exact_step(t, h, state, topology, s, w)
    elif ADAPTIVE:
        dp5_step(t, h, state, topology, s, w, controls)
    else:
        rk4_guarded(t, h, state, topology, s, w)


@njit_step_merged
def motion_inside(t, h, theta, state, topology, s, w):
    """x and ẋ at t + θh, inside the step of size h just taken from t, into w.xt, w.vt: on
    the dense output of an adaptive step; propagated exactly from the start of an
    exponential one; integrated anew from the start of a fixed one (which overwrites the
    step's end state in w: ``step_apart`` takes it again)."""
    if EXPONENTIAL:
        p = state.propagation
        load_state(t, state.x, state.v, s.excitation_frequency, p)
        propagate(p, theta * h, w.e_sample, False)
        store_state(p, w.xt, w.vt)
        return
    if ADAPTIVE:
        dense_motion(theta, h, state, w, w.xt, w.vt)
        return
    rk4_step_apart(t, theta * h, state, topology, s, w)
    for i in range(len(state.x)):
        w.xt[i] = w.x_new[i]
        w.vt[i] = w.v_new[i]
