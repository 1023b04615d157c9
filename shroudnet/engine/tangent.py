"""Tangent dynamics: the variational flow of the loop's state, and saltation at switches.

Between switches the modes are fixed and the flow of y = (x, ẋ) is smooth, so a small
change δy of the state moves by δẏ = J δy, with J = ∂f/∂y the Jacobian of that mode set's
vector field f = (ẋ, ẍ) (DESIGN §6):

    δẍ_i = Σ_{j in i's cluster} δR_j / M_c  (0 in a grounded or driven cluster),
    δR_i = −k_i δx_i − c_i δẋ_i − Σ_e B_ei (∂F_e/∂u δu_e + ∂F_e/∂u̇ δu̇_e)

over the interfaces that are closed and not stuck, with u_e = x_left − x_right (paper
eq. 7; ``dynamics``). The slopes ∂F/∂u and ∂F/∂u̇ come from the laws' derivatives and are
worked out by ``template.linearise``; everything here is law-independent.

The tangent is carried through each Dormand–Prince step by differentiating the step
itself (internal differentiation): stage j's tangent is K_j = J_j (Φ + h Σ_l a_jl K_l),
and Φ ← Φ + h Σ_j b_j K_j, with J_j at the stage's state. Φ is then the exact derivative
of the computed trajectory, to rounding. The tangent's own local error, from the embedded
pair as the state's, takes part in accepting a step: where the state stands still (a
blade at rest, a stick phase) its error alone would let the steps grow past what the
tangent's accuracy allows.

At a switch on the guard surface g(y, t) = 0 with gradient n = ∂g/∂y, where the state is
mapped by y⁺ = P y⁻ (the velocities projected onto the new stick clusters, ``regroup``)
and the vector field changes from f⁻ to f⁺, the tangent is multiplied by the saltation
matrix (Leine & Nijmeijer 2004, ch. 7; Müller 1995):

    S = P + (f⁺ − P f⁻) nᵀ / (nᵀ f⁻ + ∂g/∂t).

Entering stick, f⁺ has no relative acceleration across the stuck interface and P removes
the relative velocity, so S kills that direction: a stick phase gives a zero Floquet
multiplier. Where nᵀ f⁻ + ∂g/∂t vanishes (a grazing switch, the flow tangent to the
surface) S is unbounded; such a switch, and one where several guards cross at once (where
the trajectory does not depend differentiably on its start), are counted as singular,
never silently multiplied in. Several guards that are one surface on the stick clusters
(two interfaces joining the same two clusters reverse together) make one switch, with one
saltation matrix.
"""

import math

from .codes import OPEN
from .compiled import njit_inlined, njit_step, njit_step_exact
from .dynamics import cluster_accelerations, excitation_rate, prescribed_acceleration
from .tableau import DP_A, DP_B, DP_E, DP_STAGES

#: A switch is grazing when its saltation's correction (f⁺ − P f⁻) nᵀ / ġ would stretch
#: a tangent by more than this: |Δẍ| (|∂g/∂x| τ + |∂g/∂ẋ|) / |ġ|, with ġ = nᵀ f⁻ + ∂g/∂t,
#: Δẍ the jump of the accelerations and τ = 1/(l Ω) the excitation's time scale (1 s
#: without excitation). Where the vector field is continuous (a contact law with
#: N(0) = 0) the jump vanishes with ġ, and grazing is harmless.
GRAZING_GAIN = 1e6


@njit_inlined
def linearised_acceleration(direction, s, modes, topology, g):
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


@njit_inlined
def project_rates(values, s, topology, rows):
    """Project the velocity half of ``values`` (δx then δẋ) onto the stick clusters of
    ``topology`` as ``regroup.project_velocities`` projects velocities: the momentum-
    weighted mean of each cluster, 0 in a grounded one, and the prescribed node's in a
    driven one (0 in a tangent, where that node has no variation, but its acceleration in
    P f⁻)."""
    n = len(s.mass)
    for c in range(len(topology.grounded)):
        rows[c] = 0.0
    for i in range(n):
        rows[topology.labels[i]] += s.mass[i] * values[n + i]
    for c in range(len(topology.grounded)):
        if topology.driver[c] >= 0:
            rows[c] = values[n + topology.driver[c]]
    for i in range(n):
        c = topology.labels[i]
        values[n + i] = rows[c] if topology.driver[c] >= 0 else (
            0.0 if topology.grounded[c] else rows[c] / topology.masses[c])


@njit_step
def reduce_to_clusters(normal, s, topology, rows):
    """n ← Pᵀ n: a guard's gradient as it acts on tangents of the stick clusters of
    ``topology`` (P as ``project_rates``): each velocity component becomes its cluster's
    sum times the blade's share of the cluster's mass, 0 in a grounded cluster; in a
    driven one the sum goes to the prescribed node's component."""
    n = len(s.mass)
    for c in range(len(topology.grounded)):
        rows[c] = 0.0
    for i in range(n):
        rows[topology.labels[i]] += normal[n + i]
    for i in range(n):
        c = topology.labels[i]
        if topology.driver[c] >= 0:
            normal[n + i] = rows[c] if i == topology.driver[c] else 0.0
        else:
            normal[n + i] = 0.0 if topology.grounded[c] else \
                rows[c] * s.mass[i] / topology.masses[c]


#: Two guards are one surface when their gradients (with ∂/∂t) are parallel to this
#: relative tolerance.
SAME_SURFACE = 1e-9


@njit_step
def same_surface(first, first_rate, second, second_rate):
    """Whether (second, second_rate) = c (first, first_rate) for some c ≠ 0, to
    ``SAME_SURFACE``: two guards that vanish together on one surface of (y, t)."""
    dot = first_rate * second_rate
    first_size = first_rate * first_rate
    second_size = second_rate * second_rate
    for r in range(len(first)):
        dot += first[r] * second[r]
        first_size += first[r] * first[r]
        second_size += second[r] * second[r]
    if first_size == 0.0 or second_size == 0.0:
        return False
    return dot * dot >= (1.0 - SAME_SURFACE) * first_size * second_size


@njit_step
def contact_normal(e, s, g):
    """∂g/∂y of interface e's contact guard (±δ, δ = (u − Δ) sin α) into g.guard_normal."""
    for r in range(len(g.guard_normal)):
        g.guard_normal[r] = 0.0
    if s.left[e] >= 0:
        g.guard_normal[s.left[e]] += s.sin_angle[e]
    if s.right[e] >= 0:
        g.guard_normal[s.right[e]] -= s.sin_angle[e]


@njit_step
def slip_normal(e, s, g):
    """∂g/∂y of interface e's slip guard (± u̇ cos α) into g.guard_normal."""
    n = len(s.mass)
    for r in range(len(g.guard_normal)):
        g.guard_normal[r] = 0.0
    if s.left[e] >= 0:
        g.guard_normal[n + s.left[e]] += s.cos_angle[e]
    if s.right[e] >= 0:
        g.guard_normal[n + s.right[e]] -= s.cos_angle[e]


@njit_inlined
def _static_friction_change(k, sign, s, topology, g):
    """−sgn(f) δf_e of stuck interface e = stuck_interfaces[k], from δR and δẍ in g and the
    normal-force changes already subtracted in g.imbalance (``static_friction``)."""
    change = 0.0
    for i in range(len(s.mass)):
        change += topology.operator[k, i] * g.imbalance[i]
    return -sign * change


@njit_step
def breakaway_normal(e, sign, t, s, modes, topology, g):
    """∂g/∂y into g.guard_normal, and ∂g/∂t returned, of the breakaway guard
    g = μ_s N_e − |f_e| of stuck interface e, whose static friction f_e has the sign
    ``sign``, from the slopes in g (linearised at the switch, in the modes before it).

    f = P b (``dynamics.static_friction``) with b_i = R_i − m_i ẍ_i − Σ_e' B_e'i N_e' sin α_e'
    over the stuck interfaces, so δf = P δb, differentiated along each unit direction.
    """
    n = len(s.mass)
    k = 0
    for index in range(len(topology.stuck_interfaces)):
        if topology.stuck_interfaces[index] == e:
            k = index
    for r in range(2 * n):
        for q in range(2 * n):
            g.direction[q] = 0.0
        g.direction[r] = 1.0
        linearised_acceleration(g.direction, s, modes, topology, g)
        for i in range(n):
            g.imbalance[i] = g.resultant_change[i] - s.mass[i] * g.acceleration_change[i]
        normal_change = 0.0
        for stuck in topology.stuck_interfaces:
            left, right = s.left[stuck], s.right[stuck]
            du = (g.direction[left] if left >= 0 else 0.0) \
                - (g.direction[right] if right >= 0 else 0.0)
            ddu = (g.direction[n + left] if left >= 0 else 0.0) \
                - (g.direction[n + right] if right >= 0 else 0.0)
            change = g.normal_u[stuck] * du + g.normal_du[stuck] * ddu
            if stuck == e:
                normal_change = change
            if left >= 0:
                g.imbalance[left] -= change * s.sin_angle[stuck]
            if right >= 0:
                g.imbalance[right] += change * s.sin_angle[stuck]
        g.guard_normal[r] = s.static_mu[e] * normal_change \
            + _static_friction_change(k, sign, s, topology, g)
    excitation_rate(t, s.amplitudes, s.cos_phase, s.sin_phase, s.excitation_frequency,
                    g.q_rate)
    cluster_accelerations(g.q_rate, topology.labels, topology.grounded, topology.masses,
                          g.rows, g.acceleration_change)
    n_blades = n - len(s.motion_amplitude)
    for i in range(n):
        driver = topology.driver[topology.labels[i]]
        if driver >= 0:  # a driven cluster: ∂ẍ/∂t is its prescribed motion's jerk
            g.acceleration_change[i] = prescribed_acceleration(t, s, driver - n_blades)[1]
        g.imbalance[i] = g.q_rate[i] - s.mass[i] * g.acceleration_change[i]
    return _static_friction_change(k, sign, s, topology, g)


@njit_step
def apply_saltation(t, e, time_rate, several, s, topology, g):
    """Φ ← S Φ with S = P + (f⁺ − P f⁻) nᵀ / (nᵀ f⁻ + ∂g/∂t), from g.f_minus, g.f_plus and
    g.guard_normal (n) and ``time_rate`` (∂g/∂t); P projects onto the clusters of
    ``topology``, those after the switch at t on interface e.

    A grazing switch (``GRAZING_GAIN``) or ``several`` guards crossing at once is counted
    in g.singular (the first one's time and interface kept) and S is applied as it stands
    (without its jump term where ġ is exactly 0).
    """
    n = len(s.mass)
    normal, jump = g.guard_normal, g.direction
    rate = time_rate
    for r in range(2 * n):
        rate += normal[r] * g.f_minus[r]
        jump[r] = g.f_minus[r]
    project_rates(jump, s, topology, g.rows)
    size = 0.0
    for r in range(2 * n):
        jump[r] = g.f_plus[r] - jump[r]
        if r >= n:
            size = max(size, abs(jump[r]))
    by_position = 0.0
    by_velocity = 0.0
    for i in range(n):
        by_position = max(by_position, abs(normal[i]))
        by_velocity = max(by_velocity, abs(normal[n + i]))
    stretch = size * (by_position * time_scale(s) + by_velocity)
    grazing = stretch > GRAZING_GAIN * abs(rate)
    along_scale = 1.0 / rate if rate != 0.0 else 0.0  # no jump term where ġ is exactly 0
    if grazing or several:
        if g.singular[0] == 0:
            g.singular_time[0] = t
            g.singular_interface[0] = e
        g.singular[0] += 1
    matrix = g.matrix
    for column in range(matrix.shape[1]):
        along = 0.0
        for r in range(2 * n):
            along += normal[r] * matrix[r, column]
            g.f_minus[r] = matrix[r, column]  # f⁻ is no longer needed: column scratch
        project_rates(g.f_minus, s, topology, g.rows)
        for r in range(2 * n):
            matrix[r, column] = g.f_minus[r] + jump[r] * along * along_scale


#: Relative size of n_jᵀ Δf_k against n_jᵀ f⁻ below which the saltations of two
#: interfaces that switch at the same instant commute (``apply_saltations``).
COMMUTING = 1e-9


@njit_step_exact
def apply_saltations(t, count, s, topology, g, sw):
    """Φ ← S Φ for switches of several interfaces at one instant, where that is well
    defined; returns whether it was (else nothing is changed).

    Interface k's switch changes the vector field on its support only: the blades of the
    clusters (those after the switch) its two ends belong to. Where the supports are
    disjoint, the jump f⁺ − P f⁻ vanishes outside them, and no guard sees another's jump
    (|n_jᵀ Δf_k| ≤ ``COMMUTING`` |n_jᵀ f⁻ + ∂g_j/∂t| for j ≠ k), the saltation matrices
    S_k = P + Δf_k n_kᵀ / ġ_k commute: in whichever order a perturbation makes the
    interfaces switch, S Φ = P Φ + Σ_k Δf_k (n_kᵀ Φ) / ġ_k. Such are interfaces far apart
    on a ring, which its symmetry makes switch together. The first ``count`` rows of
    sw.crossing_normals and entries of sw.crossing_rates are n_k and ġ_k of sw.crossings[k]
    (``records.Switching``); g.f_minus and g.f_plus hold f⁻ and f⁺. A grazing one
    (``GRAZING_GAIN``) is counted in g.singular, as ``apply_saltation`` counts it.
    """
    n = len(s.mass)
    crossings, normals, rates = sw.crossings, sw.crossing_normals, sw.crossing_rates
    jump = g.direction
    for r in range(2 * n):
        jump[r] = g.f_minus[r]
    project_rates(jump, s, topology, g.rows)
    largest = 0.0
    for r in range(2 * n):
        jump[r] = g.f_plus[r] - jump[r]
        largest = max(largest, abs(jump[r]))
    owner = sw.owner
    for i in range(n):
        owner[i] = -1
    for k in range(count):
        e = crossings[k]
        for i in range(n):
            label = topology.labels[i]
            if (s.left[e] >= 0 and topology.labels[s.left[e]] == label) or (
                    s.right[e] >= 0 and topology.labels[s.right[e]] == label):
                if owner[i] >= 0 and owner[i] != k:
                    return False
                owner[i] = k
    for i in range(n):
        if owner[i] < 0 and max(abs(jump[i]), abs(jump[n + i])) > 1e-12 * largest:
            return False
    for j in range(count):
        for k in range(count):
            if j == k:
                continue
            cross = 0.0
            for i in range(n):
                if owner[i] == k:
                    cross += normals[j, i] * jump[i] + normals[j, n + i] * jump[n + i]
            if abs(cross) > COMMUTING * abs(rates[j]):
                return False
    for k in range(count):
        size = 0.0
        by_position = 0.0
        by_velocity = 0.0
        for i in range(n):
            if owner[i] == k:
                size = max(size, abs(jump[n + i]))
            by_position = max(by_position, abs(normals[k, i]))
            by_velocity = max(by_velocity, abs(normals[k, n + i]))
        if size * (by_position * time_scale(s) + by_velocity) > GRAZING_GAIN * abs(rates[k]):
            if g.singular[0] == 0:
                g.singular_time[0] = t
                g.singular_interface[0] = crossings[k]
            g.singular[0] += 1
    along = sw.along
    matrix = g.matrix
    for column in range(matrix.shape[1]):
        for k in range(count):
            value = 0.0
            for r in range(2 * n):
                value += normals[k, r] * matrix[r, column]
            along[k] = value / rates[k] if rates[k] != 0.0 else 0.0
        for r in range(2 * n):
            g.f_minus[r] = matrix[r, column]  # f⁻ is no longer needed: column scratch
        project_rates(g.f_minus, s, topology, g.rows)
        for r in range(2 * n):
            k = owner[r % n]
            matrix[r, column] = g.f_minus[r] + (jump[r] * along[k] if k >= 0 else 0.0)
    return True


@njit_step
def project_tangent(s, topology, g):
    """Φ ← P Φ: the tangent of a start whose velocities are projected onto the clusters."""
    matrix = g.matrix
    for column in range(matrix.shape[1]):
        for r in range(matrix.shape[0]):
            g.direction[r] = matrix[r, column]
        project_rates(g.direction, s, topology, g.rows)
        for r in range(matrix.shape[0]):
            matrix[r, column] = g.direction[r]
