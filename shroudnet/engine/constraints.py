"""Stick as constraints: the stuck interfaces of a scene with substructures.

With substructures a stuck interface e is the linear constraint t_e·ẋ = 0 on the slip
velocity (DESIGN §7), not two nodes moving as one. Stacking the stuck rows t_e in G
(split into the free coordinates' columns G_f and the prescribed ones' G_p), the motion
with the diagonal mass M (``records.StructureScene``) is

    M ẍ_f = R_f − G_fᵀ λ,     G_f ẍ_f + G_p a_p = 0,

so λ = A⁺ (G_f M⁻¹ R_f + G_p a_p) with A = G_f M⁻¹ G_fᵀ: the static friction forces,
the least-norm solution where the constraints are redundant (a stuck ring), as the stick
clusters take it. A mode change computes the operator W = [A⁺ G_f M⁻¹, A⁺ G_p] once,
so that λ = W z with z = (R_f, a_p); the same W projects the velocities M-orthogonally
onto the constraints at stick onset (``project_onto_constraints``). For nodes of one
degree of freedom this is exactly the stick clusters of ``regroup``.

Sums here stay as written (``njit_step_exact``), as the clusters' do.
"""

import math

from .codes import STICK
from .compiled import njit_inlined, njit_step_exact, njit_step_merged
from .records import Topology

#: Eigenvalues of A = G M⁻¹ Gᵀ below this fraction of its largest are redundancy (a
#: constraint that others imply), which the pseudo-inverse leaves out.
REDUNDANT = 1e-10

#: Jacobi sweeps of ``pseudo_inverse`` at most; a symmetric matrix of a few dozen rows
#: converges in well under ten.
JACOBI_SWEEPS = 60


@njit_step_exact
def pseudo_inverse(matrix, size, vectors, inverse):
    """The Moore–Penrose inverse of the symmetric positive semi-definite leading
    ``size`` × ``size`` block of ``matrix`` into ``inverse``, by cyclic Jacobi rotations
    (``matrix`` is overwritten by its eigenvalues on the diagonal; ``vectors`` by its
    eigenvectors). Eigenvalues within ``REDUNDANT`` of the largest count as zero."""
    for i in range(size):
        for j in range(size):
            vectors[i, j] = 1.0 if i == j else 0.0
    for _ in range(JACOBI_SWEEPS):
        off = 0.0
        total = 0.0
        for i in range(size):
            for j in range(size):
                total += matrix[i, j] * matrix[i, j]
                if i != j:
                    off += matrix[i, j] * matrix[i, j]
        if off <= 1e-32 * total:
            break
        for p in range(size - 1):
            for q in range(p + 1, size):
                apq = matrix[p, q]
                if apq == 0.0:
                    continue
                theta = (matrix[q, q] - matrix[p, p]) / (2.0 * apq)
                t = 1.0 / (abs(theta) + math.sqrt(theta * theta + 1.0))
                if theta < 0.0:
                    t = -t
                c = 1.0 / math.sqrt(t * t + 1.0)
                s = t * c
                for k in range(size):
                    kp, kq = matrix[k, p], matrix[k, q]
                    matrix[k, p] = c * kp - s * kq
                    matrix[k, q] = s * kp + c * kq
                for k in range(size):
                    pk, qk = matrix[p, k], matrix[q, k]
                    matrix[p, k] = c * pk - s * qk
                    matrix[q, k] = s * pk + c * qk
                for k in range(size):
                    kp, kq = vectors[k, p], vectors[k, q]
                    vectors[k, p] = c * kp - s * kq
                    vectors[k, q] = s * kp + c * kq
    largest = 0.0
    for k in range(size):
        largest = max(largest, matrix[k, k])
    for i in range(size):
        for j in range(size):
            value = 0.0
            for k in range(size):
                if matrix[k, k] > REDUNDANT * largest:
                    value += vectors[i, k] * vectors[j, k] / matrix[k, k]
            inverse[i, j] = value


@njit_step_exact
def fill_constraints(s, modes, g):
    """The stuck interfaces of ``modes`` and the operator W (``constraints``) into ``g``
    (``records.Switching``, its gram at least n_interfaces square); returns their number.
    Allocates nothing."""
    n = len(s.mass)
    free = n - len(s.motion_amplitude)
    n_stuck = 0
    for e in range(len(modes)):
        g.stuck[e] = modes[e] == STICK
        if g.stuck[e] and s.slider_index[e] < 0:  # an elastic contact sticks by its spring
            g.stuck_interfaces[n_stuck] = e
            n_stuck += 1
    for i in range(n):
        g.labels[i] = 0
    g.grounded[0] = False
    g.driver[0] = -1
    if n_stuck == 0:
        return 0
    rows = s.tangent_rows
    for a in range(n_stuck):
        for b in range(a, n_stuck):
            ea, eb = g.stuck_interfaces[a], g.stuck_interfaces[b]
            value = 0.0
            for i in range(free):
                value += rows[ea, i] * rows[eb, i] / s.mass[i]
            g.gram[a, b] = value
            g.gram[b, a] = value
    pseudo_inverse(g.gram, n_stuck, g.lower, g.inverse)
    for k in range(n_stuck):
        for i in range(n):
            value = 0.0
            for j in range(n_stuck):
                value += g.inverse[k, j] * rows[g.stuck_interfaces[j], i]
            g.operator[k, i] = value / s.mass[i] if i < free else value
    return n_stuck


@njit_step_merged
def regroup_constraints(s, modes, g):
    """``regroup`` for stick as constraints: a ``Topology`` whose operator is W, valid until
    g is refilled. Its labels are all 0 and its one cluster neither grounded nor driven
    (the clusters' fields mean nothing here); its ``masses`` is scratch of at least
    max(n_coordinates, n_interfaces) entries, for the multipliers."""
    n_stuck = fill_constraints(s, modes, g)
    return Topology(g.stuck, g.labels, g.grounded[:1], g.driver[:1], g.size,
                    g.operator[:n_stuck], g.stuck_interfaces[:n_stuck])


@njit_step_exact
def project_onto_constraints(s, topology, values, first, momentum):
    """``project_velocities`` for stick as constraints: the velocities in
    values[first:first + n] projected M-orthogonally onto G ẋ = 0 (prescribed coordinates
    keep theirs): ẋ_f ← ẋ_f − M⁻¹ G_fᵀ A⁺ (G_f ẋ_f + G_p ẋ_p). Returns the kinetic energy
    removed [J]. ``momentum`` is unused (the multipliers go into topology.masses)."""
    n = len(s.mass)
    free = n - len(s.motion_amplitude)
    n_stuck = len(topology.stuck_interfaces)
    if n_stuck == 0:
        return 0.0
    y = topology.masses
    for k in range(n_stuck):
        value = 0.0
        for i in range(n):
            weight = s.mass[i] if i < free else 1.0
            value += topology.operator[k, i] * weight * values[first + i]
        y[k] = value
    lost = 0.0
    rows = s.tangent_rows
    for i in range(free):
        change = 0.0
        for k in range(n_stuck):
            change += rows[topology.stuck_interfaces[k], i] * y[k]
        old = values[first + i]
        new = old - change / s.mass[i]
        lost += 0.5 * s.mass[i] * (old * old - new * new)
        values[first + i] = new
    return lost


@njit_inlined
def constrained_accelerations(s, topology, resultant, drive, acceleration, friction):
    """ẍ of a mode set with stick as constraints into ``acceleration``, and the static
    friction λ into ``friction`` at the stuck interfaces, from the resultants R.

    λ = W z with z = (R_f, a_p) (``constraints``); ẍ_f = (R_f − G_fᵀ λ)/m; a prescribed
    coordinate's ẍ is its motion's, ``drive``."""
    n = len(s.mass)
    free = n - len(drive)
    rows = s.tangent_rows
    for i in range(free):
        acceleration[i] = resultant[i]
    for p in range(len(drive)):
        acceleration[free + p] = drive[p]
    for k in range(len(topology.stuck_interfaces)):
        value = 0.0
        for i in range(free):
            value += topology.operator[k, i] * resultant[i]
        for p in range(len(drive)):
            value += topology.operator[k, free + p] * drive[p]
        e = topology.stuck_interfaces[k]
        friction[e] = value
        for i in range(free):
            acceleration[i] -= rows[e, i] * value
    for i in range(free):
        acceleration[i] /= s.mass[i]


@njit_inlined
def prescribed_power(s, topology, resultant, v, friction, n_prescribed):
    """The power the prescribed motions put into the structure [W]: each massless
    prescribed coordinate p needs the force −(R_p − Σ_e G_ep λ_e) to move as it does."""
    n = len(s.mass)
    free = n - n_prescribed
    power = 0.0
    for p in range(free, n):
        force = -resultant[p]
        for k in range(len(topology.stuck_interfaces)):
            e = topology.stuck_interfaces[k]
            force += s.tangent_rows[e, p] * friction[e]
        power += force * v[p]
    return power


@njit_step_exact
def reduce_to_constraints(normal, s, topology, rows):
    """``reduce_to_clusters`` for stick as constraints: n ← Pᵀ n on the velocity half of a
    guard's gradient, P the projection of ``project_onto_constraints``:
    c = W_f n_f, then n_f ← n_f − G_fᵀ c and n_p ← n_p − G_pᵀ c. ``rows`` is unused."""
    n = len(s.mass)
    free = n - len(s.motion_amplitude)
    n_stuck = len(topology.stuck_interfaces)
    y = topology.masses
    for k in range(n_stuck):
        value = 0.0
        for i in range(free):
            value += topology.operator[k, i] * normal[n + i]
        y[k] = value
    for i in range(n):
        change = 0.0
        for k in range(n_stuck):
            change += s.tangent_rows[topology.stuck_interfaces[k], i] * y[k]
        normal[n + i] -= change
