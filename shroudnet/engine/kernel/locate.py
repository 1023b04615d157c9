"""Locate: the switch inside a step, and the samples recorded up to it (law-aware; the
root finder itself: ``locate``).

The guards are evaluated on states inside the step that the method provides
(``step.motion_inside``), the switch is bracketed by the Illinois method, and the state
there is integrated anew from the step's start, for both methods.
"""

from typing import TYPE_CHECKING

import numpy as np

from shroudnet.engine.advance import dense_state, move_state, record, sample_time
from shroudnet.engine.compiled import njit_step_merged
from shroudnet.engine.detect import any_crossed, kinematic_guards
from shroudnet.engine.locate import bracket_after, bracket_start, next_trial
from shroudnet.engine.tangent import commit_tangent

if TYPE_CHECKING:
    from .forces import evaluate_guards_apart, sample_forces
    from .generated import ADAPTIVE, HAS_SLIDERS, HAS_TANGENT
    from .step import motion_inside, step_apart
    from .tangent import stepwise, tangent_step


@njit_step_merged
def guards_inside(t, h, theta, state, topology, s, w):
    """The guards at t + θh inside the step of size h just taken from t, into w.contact /
    w.motion (the state there in w.xt, w.vt).

    Contact and slip guards are functions of the state alone: without stuck interfaces
    no force is evaluated (``detect.kinematic_guards``). A breakaway margin needs the
    static friction, and an elastic contact's guards its spring's force, so with stuck
    interfaces or elastic contacts the forces are evaluated too.
    """
    motion_inside(t, h, theta, state, topology, s, w)
    if HAS_SLIDERS or len(topology.stuck_interfaces) > 0:
        evaluate_guards_apart(t + theta * h, w.xt, w.vt, state.modes, topology, s, w,
                              w.a_sample)
        return
    kinematic_guards(w.xt, w.vt, state.modes, s, w, w.contact, w.motion)


@njit_step_merged
def locate(t, h, t_end, theta, sample, state, topology, s, w, controls, out):
    """The earliest switch in (0, θ] of the step of size h from t, which ends at t_end;
    moves the state there. Returns (the switch time, the next sample).

    The switch is bracketed to within the event tolerance, and the state at the bracket's
    high end integrated anew from t. On a fixed step that state is the one the guards
    were evaluated on. On an adaptive step the guards were read off the dense output,
    which differs from a step to the same time by its error: half the tolerance then goes
    to locating the switch, the state half a tolerance past it is integrated anew (so that
    the state and its work columns keep the order of the steps), and should it not have
    crossed yet, the dense output's state is taken. The adaptive samples up to the switch
    are recorded from the dense output. Leaves the guards at the switch in w.
    """
    width = (0.5 if ADAPTIVE else 1.0) * controls.event_tolerance / h
    guards_inside(t, h, theta, state, topology, s, w)
    lo, f_lo, hi, f_hi, side, g = bracket_start(theta, state, w)
    previous, slow = hi, np.int64(0)
    while hi - lo > width:
        trial, slow = next_trial(lo, f_lo, hi, f_hi, width, previous, slow)
        previous = hi - lo
        guards_inside(t, h, trial, state, topology, s, w)
        lo, f_lo, hi, f_hi, side, g = bracket_after(lo, f_lo, hi, f_hi, side, g, trial, state,
                                                    w)
    past = min(1.0, hi + width) if ADAPTIVE else hi
    t_event = t_end if past == 1.0 else t + past * h
    if ADAPTIVE:
        sample = record_dense(sample, t, t_event, h, state, topology, s, w, controls, out)
    step_apart(t, t_event - t, state, topology, s, w, controls)
    tangent = HAS_TANGENT and stepwise(state, controls)
    if any_crossed(state, w):
        if HAS_TANGENT and tangent:
            tangent_step(t, t_event - t, state, topology, s, w, controls)
            commit_tangent(state.tangent, s, controls.orthonormalise)
    elif ADAPTIVE:  # the whole step again, for its dense output at hi
        t_event = t + hi * h
        # the tangent of a step to hi, which the dense state matches to its error
        if HAS_TANGENT and tangent:
            step_apart(t, hi * h, state, topology, s, w, controls)
            tangent_step(t, hi * h, state, topology, s, w, controls)
            commit_tangent(state.tangent, s, controls.orthonormalise)
        step_apart(t, h, state, topology, s, w, controls)
        dense_state(hi, h, state, w, w.x_new, w.v_new, w.e_new)
        evaluate_guards_apart(t_event, w.x_new, w.v_new, state.modes, topology, s, w, w.a_end)
    move_state(state, w)
    return t_event, sample


@njit_step_merged
def record_dense(sample, t, t_to, h, state, topology, s, w, controls, out):
    """Record the samples in (t, t_to] from the dense output of the adaptive step of size
    h from t.

    Returns the index of the next sample. Overwrites the forces in w (``sample_forces``).
    """
    while sample < controls.n_samples:
        time = sample_time(out, sample, controls)
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
