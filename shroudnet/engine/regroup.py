"""Regroup: the stick clusters of a set of modes and what follows from them.

Stuck interfaces join their blades into stick clusters that move as one body
(``clusters.cluster_labels``). A mode change regroups once: cluster masses, the linear
operator that turns force imbalances into static friction, and the projection of the
velocities onto the clusters. Regrouping allocates; the projection, done at every
switch, works in the caller's scratch. None of it depends on the contact or friction laws.
"""

import numpy as np

from .clusters import cluster_labels
from .codes import STICK
from .compiled import njit_entry, njit_inlined, njit_internal, njit_step_exact
from .records import Topology


@njit_entry
def cluster_mass(mass, labels, n_clusters):
    """Σ m [kg] of each stick cluster."""
    total = np.zeros(n_clusters)
    for i in range(len(mass)):
        total[labels[i]] += mass[i]
    return total


@njit_entry
def static_friction_operator(n_nodes, n_blades, left, right, cos_angle, stuck, labels,
                             grounded):
    """The linear map P from node force imbalances to static friction on stuck interfaces.

    Every blade i of a cluster obeys Σ_e B_ei (N_e sin α_e + f_e cos α_e) = R_i − m_i ẍ_i
    over its stuck interfaces e, i.e. G f = b with G_ie = B_ei cos α_e. For a tree cluster
    the solution is unique; a cycle (an all-stuck ring) makes it indeterminate, and we take
    the solution of minimum Euclidean norm, which leaves no force circulating round the
    cycle. Both are f = Gᵀ y with G Gᵀ y = b. G Gᵀ is singular only along the rigid motion
    of each free (ungrounded) cluster, y = const on the cluster, which b never excites (its
    sum over a free cluster is 0: the cluster's acceleration balances its forces). Adding
    J_c / n_c (all entries 1/n_c on the cluster's blades) for each free cluster c makes the
    matrix positive definite without changing y on that b, so

        P = Gᵀ (G Gᵀ + Σ_c J_c / n_c)⁻¹,

    inverted by a Cholesky factorisation written out here (no LAPACK call, and the same
    P as the pseudo-inverse of G). P is block-diagonal by cluster and depends only on the
    set of stuck interfaces, so it is computed once per mode change, and each block on
    its own: entries between two clusters are exact zeros, so skipping them changes no
    bit, and a ring of 24 blades costs the work of its small clusters, not of a dense
    24 × 24 inverse.

    A prescribed-motion node (positions n_blades … n_nodes − 1) takes whatever force its
    motion needs, as a fixed node does: it has no equation, so no row of G (a 1 on the
    diagonal keeps the matrix definite and its column of P zero).

    Returns
    -------
    operator : float array (n_stuck, n_nodes)
    stuck_interfaces : int64 array (n_stuck,)
    """
    count = 0
    for e in range(len(stuck)):
        count += 1 if stuck[e] else 0
    stuck_interfaces = np.empty(count, dtype=np.int64)
    k = 0
    for e in range(len(stuck)):
        if stuck[e]:
            stuck_interfaces[k] = e
            k += 1
    n_stuck = len(stuck_interfaces)
    if n_stuck == 0:
        return np.zeros((0, n_nodes)), stuck_interfaces
    # G's column k: cos α at interface k's left blade, −cos α at its right (none at a
    # fixed or prescribed end)
    ends = np.full((n_stuck, 2), -1, dtype=np.int64)
    entries = np.zeros((n_stuck, 2))
    for k in range(n_stuck):
        e = stuck_interfaces[k]
        if 0 <= left[e] < n_blades:
            ends[k, 0], entries[k, 0] = left[e], cos_angle[e]
        if 0 <= right[e] < n_blades:
            ends[k, 1], entries[k, 1] = right[e], -cos_angle[e]
    matrix = np.zeros((n_nodes, n_nodes))
    for k in range(n_stuck):
        for a in range(2):
            for b in range(2):
                if ends[k, a] >= 0 and ends[k, b] >= 0:
                    matrix[ends[k, a], ends[k, b]] += entries[k, a] * entries[k, b]
    size = np.zeros(len(grounded))
    for i in range(n_nodes):
        size[labels[i]] += 1.0
    for i in range(n_nodes):
        for j in range(n_nodes):
            if labels[i] == labels[j] and not grounded[labels[i]]:
                matrix[i, j] += 1.0 / size[labels[i]]
        if i >= n_blades:
            matrix[i, i] = 1.0
    inverse = _spd_inverse(matrix, labels)
    operator = np.zeros((n_stuck, n_nodes))
    for k in range(n_stuck):
        for a in range(2):
            i = ends[k, a]
            if i >= 0:
                for j in range(n_nodes):
                    operator[k, j] += entries[k, a] * inverse[i, j]
    return operator, stuck_interfaces


@njit_entry
def _spd_inverse(matrix, labels):
    """The inverse of a symmetric positive definite matrix, by Cholesky factorisation,
    block-diagonal by ``labels``: an entry between two labels is zero in the matrix, and
    so in its factor and its inverse; those are left out."""
    n = len(matrix)
    lower = np.zeros((n, n))
    for j in range(n):
        for i in range(j, n):
            if labels[i] != labels[j]:
                continue
            value = matrix[i, j]
            for k in range(j):
                if labels[k] == labels[j]:
                    value -= lower[i, k] * lower[j, k]
            lower[i, j] = np.sqrt(value) if i == j else value / lower[j, j]
    inverse = np.zeros((n, n))
    for c in range(n):
        for i in range(n):  # L z = e_c
            if labels[i] != labels[c]:
                continue
            value = 1.0 if i == c else 0.0
            for k in range(i):
                if labels[k] == labels[c]:
                    value -= lower[i, k] * inverse[k, c]
            inverse[i, c] = value / lower[i, i]
        for i in range(n - 1, -1, -1):  # Lᵀ y = z
            if labels[i] != labels[c]:
                continue
            value = inverse[i, c]
            for k in range(i + 1, n):
                if labels[k] == labels[c]:
                    value -= lower[k, i] * inverse[k, c]
            inverse[i, c] = value / lower[i, i]
    return inverse


@njit_inlined
def same_stuck(topology, modes):
    """Whether ``modes`` stick the interfaces ``topology`` was built for, and no other."""
    for e in range(len(modes)):
        if topology.stuck[e] != (modes[e] == STICK):
            return False
    return True


@njit_internal
def regroup(s, modes):
    """Stick clusters and the static friction operator of a set of modes."""
    stuck = np.empty(len(modes), dtype=np.bool_)
    for e in range(len(modes)):
        stuck[e] = modes[e] == STICK
    n_nodes = len(s.mass)
    n_blades = n_nodes - len(s.motion_amplitude)
    labels, grounded, driver = cluster_labels(n_nodes, n_blades, s.left, s.right, stuck)
    operator, stuck_interfaces = static_friction_operator(n_nodes, n_blades, s.left, s.right,
                                                          s.cos_angle, stuck, labels, grounded)
    return Topology(stuck, labels, grounded, driver,
                    cluster_mass(s.mass, labels, len(grounded)), operator, stuck_interfaces)


@njit_step_exact
def project_velocities(s, topology, v, momentum):
    """One velocity per stick cluster, conserving its momentum; 0 in a grounded cluster,
    the prescribed node's in a driven one. ``momentum`` is scratch, one entry per node.

    Returns the kinetic energy removed [J] (of the order of the event tolerance).
    """
    n_clusters = len(topology.grounded)
    for c in range(n_clusters):
        momentum[c] = 0.0
    for i in range(len(v)):
        momentum[topology.labels[i]] += s.mass[i] * v[i]
    for c in range(n_clusters):
        if topology.driver[c] >= 0:
            momentum[c] = v[topology.driver[c]]
    lost = 0.0
    for i in range(len(v)):
        c = topology.labels[i]
        new = momentum[c] if topology.driver[c] >= 0 else (
            0.0 if topology.grounded[c] else momentum[c] / topology.masses[c])
        lost += 0.5 * s.mass[i] * (v[i] * v[i] - new * new)
        v[i] = new
    return lost
