"""The forces kept at each stage of a step for the tangent's slopes there: law-free
storage of the kinematics and forces each ``derivative`` of the state's own step found
(``kernel.tangent.stage_slopes`` reads them), so that the tangent does not evaluate them
again (``tangent``'s module docstring).

A stage's forces are those of the step just taken; the step's start takes the forces kept
at the step before's end, and only where that step ended at this very state: time, x, ẋ
and modes the same to the last bit (``start_kept``). After a switch, a rejected trial, or
a state read off a dense output, they are evaluated again.
"""

from .compiled import njit_inlined
from .records import START

__all__ = ["START", "keep_end", "keep_stage", "keep_start", "start_kept"]


@njit_inlined
def keep_stage(j, g, w):
    """The interfaces' kinematics and forces that stage j's ``derivative`` just left in
    w, into g.stage_forces[j] (``records.STAGE_FORCES``): the slopes of the tangent at
    that stage are read from them (``stage_slopes``) rather than from the forces
    evaluated again."""
    kept = g.stage_forces[j]
    for e in range(kept.shape[1]):
        kept[0, e] = w.penetration[e]
        kept[1, e] = w.rate[e]
        kept[2, e] = w.slip[e]
        kept[3, e] = w.normal[e]
        kept[4, e] = w.friction[e]
        kept[5, e] = w.friction_second[e]
        kept[6, e] = w.slider_speed[e]


@njit_inlined
def keep_end(t, g, w, modes):
    """The key of the forces kept at the end of the step just taken (``keep_stage``): its
    time t, state and modes, into g.stage_keys[0]."""
    key = g.stage_keys[0]
    n = len(w.x_new)
    key[0] = t
    for i in range(n):
        key[1 + i] = w.x_new[i]
        key[1 + n + i] = w.v_new[i]
    for e in range(len(modes)):
        key[1 + 2 * n + e] = modes[e]


@njit_inlined
def keep_start(g):
    """Before a step: the forces kept at the end of the step before, with their key, become
    the start's (slot ``records.START``, g.stage_keys[1])."""
    for r in range(g.stage_forces.shape[1]):
        for e in range(g.stage_forces.shape[2]):
            g.stage_forces[START, r, e] = g.stage_forces[START - 1, r, e]
    for c in range(g.stage_keys.shape[1]):
        g.stage_keys[1, c] = g.stage_keys[0, c]


@njit_inlined
def start_kept(t, state, g):
    """Whether the forces in the start's slot were found at this very state: time, x, ẋ
    and modes the same to the last bit (after a switch, a rejected step or a state read
    off a dense output, they are not)."""
    key = g.stage_keys[1]
    n = len(state.x)
    if key[0] != t:
        return False
    for i in range(n):
        if key[1 + i] != state.x[i] or key[1 + n + i] != state.v[i]:
            return False
    for e in range(len(state.modes)):
        if key[1 + 2 * n + e] != state.modes[e]:
            return False
    return True
