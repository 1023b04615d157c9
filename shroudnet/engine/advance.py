"""Advance: the parts of a Runge–Kutta step that do not evaluate forces.

The Dormand–Prince dense output, moving the state to the end of a step, and recording a
sample: as a row of the run's ``records.Output``, or reduced into its
``records.Reduction`` (``record`` picks by the output's type while compiling). The steps
themselves (``kernel.step``) evaluate the scene's laws; the step-size
controller is ``controller``.
"""

import math

from .codes import N_POWERS, N_WORK
from .compiled import njit_inlined
from .dispatch import by_record
from .records import Reduction
from .tableau import DP_P, DP_STAGES, stage_sum


@njit_inlined
def set_powers(row, powers):
    for k in range(N_POWERS):
        row[k] = powers[k]


@njit_inlined
def dense_motion(theta, h, state, w, x_out, v_out):
    """x and ẋ at t + θh from the dense output of the last ``dp5_step`` of size h; the
    stages' dense weights at θ are left in w.dense_weights."""
    b0 = theta
    b1 = theta * theta
    b2 = b1 * theta
    b3 = b2 * theta
    weights = w.dense_weights
    for k in range(DP_STAGES):
        weights[k] = DP_P[k, 0] * b0 + DP_P[k, 1] * b1 + DP_P[k, 2] * b2 + DP_P[k, 3] * b3
    for i in range(len(state.x)):
        x_out[i] = state.x[i] + h * stage_sum(weights, w.stage_v, DP_STAGES, i)
        v_out[i] = state.v[i] + h * stage_sum(weights, w.stage_a, DP_STAGES, i)


@njit_inlined
def dense_state(theta, h, state, w, x_out, v_out, energy_out):
    """The state at t + θh from the dense output of the last ``dp5_step`` of size h: its
    motion (``dense_motion``) and its work columns."""
    dense_motion(theta, h, state, w, x_out, v_out)
    for c in range(N_POWERS):
        energy_out[c] = state.energy[c] + h * stage_sum(w.dense_weights, w.stage_p,
                                                        DP_STAGES, c)
    for c in range(N_POWERS, N_WORK):
        energy_out[c] = state.energy[c]


@njit_inlined
def keep_guards(state, w):
    """The guards in w become the reference for detecting the next switch."""
    for e in range(len(state.contact_before)):
        state.contact_before[e] = w.contact[e]
        state.motion_before[e] = w.motion[e]


@njit_inlined
def move_state(state, w):
    """The state becomes w.x_new, w.v_new, w.e_new."""
    for i in range(len(state.x)):
        state.x[i] = w.x_new[i]
        state.v[i] = w.v_new[i]
    for c in range(N_WORK):
        state.energy[c] = w.e_new[c]


@njit_inlined
def take_step(state, w):
    """Move to the end of the step just taken: its state, and its last stage as the first."""
    move_state(state, w)
    for i in range(len(state.x)):
        w.a_start[i] = w.a_end[i]
    for c in range(N_POWERS):
        w.stage_p[0, c] = w.stage_p[DP_STAGES - 1, c]


@njit_inlined
def is_finite(state):
    for i in range(len(state.x)):
        if not (math.isfinite(state.x[i]) and math.isfinite(state.v[i])):
            return False
    return True


@njit_inlined
def record_row(out, k, t, x, v, modes, energy, w):
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


@njit_inlined
def reduce_sample(out, k, t, x, v, modes, energy, w):
    """Sample k reduced into the ``records.Reduction`` ``out``: a Poincaré point every
    ``out.every`` samples, the extent of the response, its ∫ x² dt by the trapezoidal rule
    (Δt (x_k² + x_{k−1}²) / 2 a sample, as ``numpy.trapezoid`` takes it) and the work
    columns at the first and the latest sample."""
    r = out.response
    position, rate = x[r], v[r]
    square = position * position
    if k % out.every == 0:
        row = k // out.every
        out.poincare[row, 0] = position
        out.poincare[row, 1] = rate
    if k == 0:
        out.extent[0] = abs(position)
        out.extent[1] = abs(rate)
        out.square[0] = 0.0
        for c in range(N_WORK):
            out.work[0, c] = energy[c]
    else:
        out.extent[0] = max(out.extent[0], abs(position))
        out.extent[1] = max(out.extent[1], abs(rate))
        out.square[0] += (t - out.square[1]) * (square + out.square[2]) / 2.0
    out.square[1] = t
    out.square[2] = square
    for c in range(N_WORK):
        out.work[1, c] = energy[c]


#: Sample k of a run: a row of its ``records.Output``, or reduced into its
#: ``records.Reduction``.
record = by_record("record", "out", Reduction, record_row, reduce_sample)


@njit_inlined
def listed_time(out, k, controls):
    """Sample k's time [s], as the run's ``records.Output`` lists it (``records.allocate``:
    the grid t0 + k·sample_step, or times of the caller's own)."""
    return out.t[k]


@njit_inlined
def grid_sample_time(out, k, controls):
    """Sample k's time [s] on the grid t0 + k·sample_step (a reduced run lists none)."""
    return controls.t0 + k * controls.sample_step


#: Sample k's time [s]: listed in the run's ``records.Output``, or on the grid of a run
#: reduced into a ``records.Reduction``.
sample_time = by_record("sample_time", "out", Reduction, listed_time,
                        grid_sample_time)
