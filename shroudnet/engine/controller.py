"""The step-size controller of the adaptive method, in one place.

Hairer, Nørsett & Wanner, *Solving ODEs I*, §II.4. A Dormand–Prince step of size h is
accepted when its scaled local error

    err = sqrt( Σ_i [(h Σ_j e_j k^x_ij / s^x_i)² + (h Σ_j e_j k^v_ij / s^v_i)²] / (2n) ),
    s^x_i = atol_x + rtol · max(|x_i|, |x_i⁺|),  s^v_i likewise for ẋ,

is at most 1 (``scaled_error``, ``accepted``). After an accepted step the next is
h · clip(SAFETY · err^(−1/5), ·, GROW_LIMIT), at most h_max (``next_step``); a rejected one
is retried with h · max(SHRINK_LIMIT, SAFETY · err^(−1/5)) (``retry_step``), never larger.
A run starts with ``INITIAL_STEP`` periods (``first_step``), stops with STEP_TOO_SMALL
when a step shrinks below ``SMALLEST_STEP`` periods (``too_small``), and with STALLED when
``STALL_STEPS`` accepted steps in a row are shorter than ``STALL_SIZE`` times that
(``stalling``).
"""

import math

from .compiled import njit_inlined
from .tableau import DP_E, DP_STAGES, stage_sum

SAFETY = 0.9
ERROR_EXPONENT = -0.2
SHRINK_LIMIT = 0.2
GROW_LIMIT = 5.0

#: The first trial step of an adaptive run, in excitation periods.
INITIAL_STEP = 1e-3
#: An adaptive step below this many excitation periods stops the run.
SMALLEST_STEP = 1e-14
#: Accepted adaptive steps in a row, each shorter than ``STALL_SIZE`` times the smallest
#: step, before a run is stopped (STALLED). A force that jumps where no guard looks (a law
#: discontinuous inside the contact) can make the motion chatter across the jump: each
#: step then crosses it and comes back, accepted, at some 1e-16 s a step, and the run
#: would take years. Switches never need this: they are located, not stepped to.
STALL_STEPS = 10_000
STALL_SIZE = 1e5


def first_step(period: float) -> float:
    """The first trial step [s] of an adaptive run with excitation period ``period`` [s]."""
    return INITIAL_STEP * period


def smallest_step(period: float) -> float:
    """The smallest step [s] an adaptive run may take (``SMALLEST_STEP`` periods)."""
    return SMALLEST_STEP * period


@njit_inlined
def scaled_error(h, x, v, x_new, v_new, stage_v, stage_a, controls):
    """The scaled local error of the Dormand–Prince step of size h from (x, v) to
    (x_new, v_new) whose stages are ``stage_v`` (ẋ) and ``stage_a`` (ẍ): the embedded
    pair's difference h Σ_j e_j k_j, as an RMS over x and ẋ with each component scaled
    by atol + rtol·max(|y|, |y⁺|). At most 1 accepts the step."""
    total = 0.0
    for i in range(len(x)):
        scale_x = controls.atol_x + controls.rtol * max(abs(x[i]), abs(x_new[i]))
        scale_v = controls.atol_v + controls.rtol * max(abs(v[i]), abs(v_new[i]))
        total += (h * stage_sum(DP_E, stage_v, DP_STAGES, i) / scale_x) ** 2 \
            + (h * stage_sum(DP_E, stage_a, DP_STAGES, i) / scale_v) ** 2
    return math.sqrt(total / (2 * len(x)))


@njit_inlined
def accepted(error):
    """Whether a step with scaled error ``error`` is accepted (inf and NaN are not)."""
    return error <= 1.0


@njit_inlined
def next_step(h, error, h_max):
    """The step after an accepted one of size h with scaled error ``error`` ≤ 1."""
    factor = min(GROW_LIMIT, SAFETY * error ** ERROR_EXPONENT) if error > 0.0 else GROW_LIMIT
    return min(h * factor, h_max)


@njit_inlined
def retry_step(h, error):
    """The step to try after one of size h was rejected with scaled error ``error`` > 1
    (inf or NaN: a law gave a non-finite force ahead)."""
    if not math.isfinite(error):
        return h * SHRINK_LIMIT
    return h * max(SHRINK_LIMIT, SAFETY * error ** ERROR_EXPONENT)


@njit_inlined
def too_small(h, last, controls):
    """Whether a step of size h is below h_min, unless it is the short last step of the
    run: the run stops (STEP_TOO_SMALL, or NOT_FINITE where the last trial's error was
    inf or NaN, a law having given a non-finite force ahead)."""
    return h < controls.h_min and not (last and h > 0.0)


@njit_inlined
def stalling(h, tiny, controls):
    """The count of accepted steps in a row below ``STALL_SIZE``·h_min after one of size
    h, and whether it has passed ``STALL_STEPS``: the run stops (STALLED)."""
    tiny = tiny + 1 if h < STALL_SIZE * controls.h_min else 0
    return tiny, tiny > STALL_STEPS
