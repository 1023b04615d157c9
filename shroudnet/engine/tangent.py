"""Tangent dynamics: the variational flow of the loop's state, and saltation at switches.

Between switches the modes are fixed and the flow of y = (x, ẋ) is smooth, so a small
change δy of the state moves by δẏ = J δy, with J = ∂f/∂y the Jacobian of that mode set's
vector field f = (ẋ, ẍ) (DESIGN §6):

    δẍ_i = Σ_{j in i's cluster} δR_j / M_c  (0 in a grounded or driven cluster),
    δR_i = −k_i δx_i − c_i δẋ_i − Σ_e B_ei (∂F_e/∂u δu_e + ∂F_e/∂u̇ δu̇_e)

over the interfaces that are closed and not stuck, with u_e = x_left − x_right (paper
eq. 7; ``dynamics``). The slopes ∂F/∂u and ∂F/∂u̇ come from the laws' derivatives and are
worked out by ``kernel.tangent.linearise``; everything here is law-independent.

The tangent is carried through each Dormand–Prince step by differentiating the step
itself (internal differentiation): stage j's tangent is K_j = J_j (Φ + h Σ_l a_jl K_l),
and Φ ← Φ + h Σ_j b_j K_j, with J_j at the stage's state. Φ is then the exact derivative
of the computed trajectory, to rounding. J_j's slopes are read from the forces the
state's own step found at that stage (``stage_forces``; at the step's start,
those of the step before's end where it ended at this very state), rather than from the
forces evaluated again: the same Φ to the last bit, and on the six eight-mode blades with
3-D elastic faces a period with one tangent column in 0.066 s instead of 0.106 s
(``front.bench``, section 11).

The tangent's own local error, from the embedded pair as the state's, takes part in
accepting a step: where the state stands still (a blade at rest, a stick phase) its error
alone would let the steps grow past what the tangent's accuracy allows. The rows of a
slipping elastic contact's stretch too short for the run to resolve its direction take no
part (``slider_tangent``).

Where the vector field is linear in the state between switches (substructures whose laws
all have ``constant_slopes``: ``SceneArrays.linear_phases``), J is the same all through a
phase, and a run that keeps no orthonormal basis, or that propagates its phases exactly
(``methods.Exponential``, which then orthonormalises at switches and samples), carries the
tangent through the whole phase at its end instead, Φ ← e^{J Δt} Φ
(``kernel.tangent.carry_phase``, ``exponential``):
exact where the steps' tangent is good to the tolerance, its cost one exponential a phase
and not 2n columns a step, and the steps sized by the state alone. On the six-blade
three-mode packet a period with its 36-column tangent took 121 ms by steps and 9 ms by
phases, against 5.8 ms for the state alone.

At a switch the tangent is multiplied by the switch's saltation matrix (``saltation``).
"""

import math

from .codes import OPEN
from .compiled import njit_inlined, njit_step
from .dispatch import by_scene
from .dynamics import cluster_accelerations
from .structures import structure_linearised_acceleration
from .tableau import DP_A, DP_B, DP_E, DP_STAGES


@njit_inlined
def blade_linearised_acceleration(direction, s, modes, topology, g):
    """δR (into g.resultant_change) and δẍ (into g.acceleration_change) along the state
    change ``direction`` (δx then δẋ, 2 n_blades), from the slopes in g."""
    n = len(s.mass)
    change = g.resultant_change
    for i in range(n):
        change[i] = -s.stiffness[i] * direction[i] - s.damping[i] * direction[n + i]
    for c in range(len(s.coupling_left)):
        left, right = s.coupling_left[c], s.coupling_right[c]
        force = 0.0
        if left >= 0:
            force += s.coupling_stiffness[c] * direction[left] \
                + s.coupling_damping[c] * direction[n + left]
        if right >= 0:
            force -= s.coupling_stiffness[c] * direction[right] \
                + s.coupling_damping[c] * direction[n + right]
        if left >= 0:
            change[left] -= force
        if right >= 0:
            change[right] += force
    for e in range(len(modes)):
        if modes[e] == OPEN or topology.stuck[e]:
            continue
        left, right = s.left[e], s.right[e]
        du = 0.0
        ddu = 0.0
        if left >= 0:
            du += direction[left]
            ddu += direction[n + left]
        if right >= 0:
            du -= direction[right]
            ddu -= direction[n + right]
        force = g.force_u[e] * du + g.force_du[e] * ddu
        if left >= 0:
            change[left] -= force
        if right >= 0:
            change[right] += force
    cluster_accelerations(change, topology.labels, topology.grounded, topology.masses,
                          g.rows, g.acceleration_change)


#: δR and δẍ along a state change, for a scene of blades or of substructures.
linearised_acceleration = by_scene("linearised_acceleration", blade_linearised_acceleration,
                                   structure_linearised_acceleration)


@njit_step
def stage_tangent(j, h, s, modes, topology, g):
    """Stage j's tangent K_j = J_j (Φ + h Σ_{l<j} a_jl K_l) into g.stages[j], with the
    slopes of J_j in g."""
    n = len(s.mass)
    for column in range(g.matrix.shape[1]):
        for r in range(2 * n):
            value = g.matrix[r, column]
            for earlier in range(j):
                value += h * DP_A[j, earlier] * g.stages[earlier, r, column]
            g.direction[r] = value
        linearised_acceleration(g.direction, s, modes, topology, g)
        for i in range(n):
            g.stages[j, i, column] = g.direction[n + i]
            g.stages[j, n + i, column] = g.acceleration_change[i]


@njit_step
def candidate_tangent(h, g):
    """Φ + h Σ_j b_j K_j, the tangent at the end of the step, into g.candidate."""
    matrix = g.matrix
    for r in range(matrix.shape[0]):
        for column in range(matrix.shape[1]):
            total = 0.0
            for j in range(DP_STAGES - 1):
                total += DP_B[j] * g.stages[j, r, column]
            g.candidate[r, column] = matrix[r, column] + h * total


@njit_step
def last_stage_tangent(s, modes, topology, g):
    """The last stage's tangent, J (Φ + h Σ_j b_j K_j), from the candidate and the slopes
    at the step's end in g: the first-same-as-last stage the error estimate needs."""
    n = len(s.mass)
    last = DP_STAGES - 1
    for column in range(g.matrix.shape[1]):
        for r in range(2 * n):
            g.direction[r] = g.candidate[r, column]
        linearised_acceleration(g.direction, s, modes, topology, g)
        for i in range(n):
            g.stages[last, i, column] = g.direction[n + i]
            g.stages[last, n + i, column] = g.acceleration_change[i]


@njit_step
def tangent_error(h, rtol, s, g):
    """The tangent's local error, as the step's: per column, |h Σ_j e_j K_j| over
    rtol·max(|Φ|, |candidate|) in the norm of ``orthonormalise``, the largest of the
    columns (≤ 1 accepts the step). A column that is 0 (a stick phase removed it) has
    none."""
    matrix = g.matrix
    rows, columns = matrix.shape
    n = rows // 2
    weight = time_scale(s)
    worst = 0.0
    for column in range(columns):
        error = 0.0
        for r in range(rows):
            total = 0.0
            for j in range(DP_STAGES):
                total += DP_E[j] * g.stages[j, r, column]
            g.direction[r] = h * total
            error += (g.direction[r] * (weight if r >= n else 1.0)) ** 2
        size = max(_dot(matrix, column, column, n, weight),
                   _dot(g.candidate, column, column, n, weight))
        if error > 0.0:
            worst = max(worst, math.sqrt(error / size) / rtol if size > 0.0 else math.inf)
    return worst


@njit_step
def commit_tangent(g, s, orthonormal):
    """Φ ← the candidate; then ``orthonormalise`` it when ``orthonormal``."""
    for r in range(g.matrix.shape[0]):
        for column in range(g.matrix.shape[1]):
            g.matrix[r, column] = g.candidate[r, column]
    if orthonormal:
        orthonormalise(g, s)


@njit_inlined
def time_scale(s):
    """τ = 1/(l Ω) [s], the excitation's time scale (1 s without excitation): the tangent
    compares a velocity change δẋ with a displacement change as τ δẋ."""
    return 1.0 / s.excitation_frequency if s.excitation_frequency > 0.0 else 1.0


@njit_inlined
def _dot(matrix, a, b, n, weight):
    """Σ_x M_ra M_rb + weight² Σ_ẋ M_ra M_rb: the inner product of two tangent columns."""
    position = 0.0
    velocity = 0.0
    for r in range(n):
        position += matrix[r, a] * matrix[r, b]
        velocity += matrix[n + r, a] * matrix[n + r, b]
    return position + weight * weight * velocity


@njit_step
def orthonormalise(g, s):
    """Modified Gram–Schmidt on the tangent's columns, in the norm |δx|² + τ²|δẋ|²
    (``time_scale``), in which a blade oscillating near the excitation frequency keeps its
    tangent's length over a cycle; the log of each column's length before it is
    normalised is added to g.log_growth (a column that has collapsed to 0, in a stick
    phase, adds −inf and stays 0)."""
    matrix = g.matrix
    rows, columns = matrix.shape
    n = rows // 2
    weight = time_scale(s)
    for c in range(columns):
        for p in range(c):
            dot = _dot(matrix, p, c, n, weight)
            for r in range(rows):
                matrix[r, c] -= dot * matrix[r, p]
        norm = math.sqrt(_dot(matrix, c, c, n, weight))
        if norm > 0.0:
            g.log_growth[c] += math.log(norm)
            for r in range(rows):
                matrix[r, c] /= norm
        else:
            g.log_growth[c] = -math.inf
