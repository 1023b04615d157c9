"""Drive: the loop of a run, the same for every method.

``advance`` takes steps until a guard crosses; ``run`` alternates it with ``switch``.
The method (``ADAPTIVE`` and ``EXPONENTIAL``, constants of each kernel) decides only how
a step is taken and sized (``step.trial_step``, ``controller``), how the state inside it
is obtained (``step.motion_inside``), and where samples are taken: on the fixed grid
t0 + k·step every ``steps_per_sample`` steps, or on an adaptive step's dense output. An
exponential run puts each phase's propagation in use as it starts
(``propagation.prepare_phase``).
"""

import math
from typing import TYPE_CHECKING

import numpy as np

from shroudnet.engine.advance import (is_finite, keep_guards, record, sample_time,
                                      take_step)
from shroudnet.engine.codes import FINISHED, NOT_FINITE, STALLED, STEP_TOO_SMALL
from shroudnet.engine.compiled import njit_inlined, njit_step_callable, njit_step_merged
from shroudnet.engine.controller import (accepted, next_step, retry_step, stalling,
                                         too_small)
from shroudnet.engine.records import last_sample
from shroudnet.engine.tangent import commit_tangent

if TYPE_CHECKING:
    from .detect import first_inside
    from .generated import ADAPTIVE, EXPONENTIAL, HAS_CONTACT_EVENTS, HAS_STICK, HAS_TANGENT
    from .locate import locate, record_dense
    from .propagation import prepare_phase
    from .resolve import begin, switch
    from .step import trial_step
    from .tangent import by_phase, carry_tangent, stepwise


@njit_step_merged
def advance(t, h, k, sample, steps, state, topology, s, w, controls, out):
    """Steps from t, recording samples, until a guard crosses or the run ends.

    Fixed steps follow the grid t0 + k·step from time t inside step k (t is on the grid
    unless a switch was just resolved). Adaptive steps start with the trial step h and
    are accepted by the controller; one that shrinks below h_min stops the run:
    NOT_FINITE if the last trial's error was inf or NaN (a law gave a non-finite force
    ahead), else STEP_TOO_SMALL; ``STALL_STEPS`` accepted steps in a row below
    ``STALL_SIZE``·h_min stop it as STALLED.

    Returns (t, h, k, sample, steps, status, switched): with ``switched``, t is the first
    switch found, located (``locate``) and the state moved there; otherwise the run
    reached its last sample or stopped with the status.
    """
    error = 0.0
    tiny = 0
    t_final = sample_time(out, controls.n_samples - 1, controls)
    while sample < controls.n_samples:
        if ADAPTIVE:
            last = h >= t_final - t
            if last:
                h = t_final - t
            if too_small(h, last, controls):
                status = STEP_TOO_SMALL if math.isfinite(error) else NOT_FINITE
                return t, h, k, sample, steps, status, False
            t_end = t_final if last else t + h
        else:
            t_end = min(grid_time(k + 1, controls), t_final)
            h = t_end - t
        error = trial_step(t, h, state, topology, s, w, controls)
        if not accepted(error):
            h = retry_step(h, error)
            continue
        steps += 1
        if ADAPTIVE:
            tiny, stalled = stalling(h, tiny, controls)
            if stalled:
                return t, h, k, sample, steps, STALLED, False
        if HAS_CONTACT_EVENTS or HAS_STICK:
            theta = first_inside(t, h, state, topology, s, w, controls)
            if theta <= 1.0:
                t, sample = locate(t, h, t_end, theta, sample, state, topology, s, w,
                                   controls, out)
                return t, h, k, sample, steps, FINISHED, True
        if HAS_TANGENT and stepwise(state, controls):
            commit_tangent(state.tangent, s, controls.orthonormalise)
        keep_guards(state, w)
        if ADAPTIVE:
            sample = record_dense(sample, t, t_end, h, state, topology, s, w, controls, out)
        take_step(state, w)
        if not is_finite(state):
            return t, h, k, sample, steps, NOT_FINITE, False
        t = t_end
        if ADAPTIVE:
            h = next_step(h, error, controls.h_max)
        else:
            k, sample = next_on_grid(k, t, state, topology, s, w, controls, out, sample)
    return t, h, k, sample, steps, FINISHED, False


@njit_inlined
def grid_time(k, controls):
    """t0 + k·step, the end of fixed step k − 1."""
    return controls.t0 + k * controls.step


@njit_step_merged
def next_on_grid(k, t, state, topology, s, w, controls, out, sample):
    """After fixed step k ended at t: the next step's index, and the sample taken at t
    every ``steps_per_sample`` steps (or at the run's last sample, which a run to a given
    time reaches by a shorter last step). A run that carries its tangent by phase for
    Lyapunov exponents carries it to the sample and orthonormalises it there, and records
    its growth. Returns (k, the next sample)."""
    k += 1
    if k % controls.steps_per_sample == 0 or t == last_sample(controls):
        if HAS_TANGENT and controls.orthonormalise and by_phase(state, controls):
            carry_tangent(t, state, topology, s, controls)
            for c in range(len(state.tangent.log_growth)):
                state.tangent.history[sample, c] = state.tangent.log_growth[c]
        record(out, sample, t, state.x, state.v, state.modes, state.energy, w)
        sample += 1
    return k, sample


@njit_step_callable
def run(state, s, w, sw, events, controls, out):
    """Integrate from the state at t0 to the last sample, locating every switch, in the
    records ``records.allocate`` made; returns (status, the time it stopped at, the
    interface that stopped it or −1, steps, samples), for ``records.finish``.

    Fixed RK4 steps of ``controls.step`` stay on the grid t0 + k·step: after a switch
    inside a step, the rest of the step is integrated in the new modes, and the step
    counts once. Adaptive Dormand–Prince 5(4) steps start from ``controls.step`` (at most
    h_max). Zeno guard: ``zeno_events`` switches within ``zeno_window`` seconds stop the
    run.
    """
    status, topology = begin(state, s, w, sw, controls, out)
    if EXPONENTIAL:
        prepare_phase(state, topology, s)
    if HAS_TANGENT:
        state.tangent.since[0] = controls.t0
    # np.int64, not literals: a literal argument would compile the callee twice
    t, h = controls.t0, min(controls.step, controls.h_max)
    k, sample, steps = np.int64(0), np.int64(1), np.int64(0)
    stop_interface = -1
    while status == FINISHED and sample < controls.n_samples:
        t, h, k, sample, steps, status, switched = advance(t, h, k, sample, steps, state,
                                                           topology, s, w, controls, out)
        if not switched or status != FINISHED:
            break
        if HAS_TANGENT and by_phase(state, controls):
            carry_tangent(t, state, topology, s, controls)
        status, stop_interface, topology = switch(t, state, topology, s, w, sw, events,
                                                  controls)
        if EXPONENTIAL:
            prepare_phase(state, topology, s)
        if not ADAPTIVE and t == min(grid_time(k + 1, controls), last_sample(controls)):
            k, sample = next_on_grid(k, t, state, topology, s, w, controls, out, sample)
    if HAS_TANGENT and by_phase(state, controls) and status == FINISHED:
        carry_tangent(t, state, topology, s, controls)
    return status, t, stop_interface, steps if ADAPTIVE else k, sample
