"""Regroup: the stick clusters of a set of modes and what follows from them.

Stuck interfaces join their blades into stick clusters that move as one body
(``clusters.cluster_labels``). A mode change regroups once: cluster masses, the linear
operator that turns force imbalances into static friction, and the projection of the
velocities onto the clusters. Regrouping refills storage allocated once per run
(``records.Switching``) and the projection works in the caller's scratch, so a switch
allocates nothing. Sums here stay as written (``njit_step_exact``). None of it depends on
the contact or friction laws.
"""

import math

import numpy as np

from .clusters import label_clusters
from .codes import STICK
from .compiled import njit_entry, njit_inlined, njit_step_exact, njit_step_merged
from .constraints import project_onto_constraints, regroup_constraints
from .dispatch import by_scene
from .records import Topology, new_switching


@njit_entry
def cluster_mass(mass, labels, n_clusters):
    """Σ m [kg] of each stick cluster."""
    total = np.empty(n_clusters)
    fill_cluster_mass(mass, labels, n_clusters, total)
    return total


@njit_step_exact
def fill_cluster_mass(mass, labels, n_clusters, total):
    """``cluster_mass`` into the first ``n_clusters`` entries of ``total``."""
    for c in range(n_clusters):
        total[c] = 0.0
    for i in range(len(mass)):
        total[labels[i]] += mass[i]


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
    g = new_switching(n_nodes, len(stuck), n_nodes)
    for e in range(len(stuck)):
        g.stuck[e] = stuck[e]
    for i in range(n_nodes):
        g.labels[i] = labels[i]
    for c in range(len(grounded)):
        g.grounded[c] = grounded[c]
    n_stuck = fill_operator(n_blades, left, right, cos_angle, g, len(grounded))
    return g.operator[:n_stuck].copy(), g.stuck_interfaces[:n_stuck].copy()


@njit_step_exact
def fill_operator(n_blades, left, right, cos_angle, g, n_clusters):
    """``static_friction_operator`` of g.stuck, g.labels and g.grounded (the first
    ``n_clusters``) into g.operator and g.stuck_interfaces, with g's gram, lower, inverse,
    ends, entries and size as scratch (g: ``records.Switching``); returns the number of
    stuck interfaces. Allocates nothing."""
    n_nodes = len(g.labels)
    n_stuck = 0
    for e in range(len(g.stuck)):
        if g.stuck[e]:
            g.stuck_interfaces[n_stuck] = e
            n_stuck += 1
    if n_stuck == 0:
        return 0
    # G's column k: cos α at interface k's left blade, −cos α at its right (none at a
    # fixed or prescribed end)
    ends, entries, labels = g.ends, g.entries, g.labels
    for k in range(n_stuck):
        e = g.stuck_interfaces[k]
        ends[k, 0], entries[k, 0] = -1, 0.0
        ends[k, 1], entries[k, 1] = -1, 0.0
        if 0 <= left[e] < n_blades:
            ends[k, 0], entries[k, 0] = left[e], cos_angle[e]
        if 0 <= right[e] < n_blades:
            ends[k, 1], entries[k, 1] = right[e], -cos_angle[e]
    matrix = g.gram
    for i in range(n_nodes):
        for j in range(n_nodes):
            matrix[i, j] = 0.0
    for k in range(n_stuck):
        for a in range(2):
            for b in range(2):
                if ends[k, a] >= 0 and ends[k, b] >= 0:
                    matrix[ends[k, a], ends[k, b]] += entries[k, a] * entries[k, b]
    size = g.size
    for c in range(n_clusters):
        size[c] = 0.0
    for i in range(n_nodes):
        size[labels[i]] += 1.0
    for i in range(n_nodes):
        for j in range(n_nodes):
            if labels[i] == labels[j] and not g.grounded[labels[i]]:
                matrix[i, j] += 1.0 / size[labels[i]]
        if i >= n_blades:
            matrix[i, i] = 1.0
    _spd_inverse(matrix, labels, g.lower, g.inverse)
    operator = g.operator
    for k in range(n_stuck):
        for j in range(n_nodes):
            operator[k, j] = 0.0
        for a in range(2):
            i = ends[k, a]
            if i >= 0:
                for j in range(n_nodes):
                    operator[k, j] += entries[k, a] * g.inverse[i, j]
    return n_stuck


@njit_step_exact
def _spd_inverse(matrix, labels, lower, inverse):
    """The inverse of a symmetric positive definite matrix into ``inverse``, by Cholesky
    factorisation (into ``lower``), block-diagonal by ``labels``: an entry between two
    labels is zero in the matrix, and so in its factor and its inverse; those are left
    out. Only the first len(labels) rows and columns are read and written."""
    n = len(labels)
    for i in range(n):
        for j in range(n):
            lower[i, j] = 0.0
            inverse[i, j] = 0.0
    for j in range(n):
        for i in range(j, n):
            if labels[i] != labels[j]:
                continue
            value = matrix[i, j]
            for k in range(j):
                if labels[k] == labels[j]:
                    value -= lower[i, k] * lower[j, k]
            lower[i, j] = math.sqrt(value) if i == j else value / lower[j, j]
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


@njit_inlined
def same_stuck(topology, modes):
    """Whether ``modes`` stick the interfaces ``topology`` was built for, and no other."""
    for e in range(len(modes)):
        if topology.stuck[e] != (modes[e] == STICK):
            return False
    return True


@njit_step_exact
def fill_groups(s, modes, g):
    """The stick clusters of ``modes`` into ``g`` (``records.Switching``): stuck
    interfaces, labels, grounded, drivers, masses and the static friction operator.
    Returns (n_clusters, n_stuck). Allocates nothing."""
    for e in range(len(modes)):
        g.stuck[e] = modes[e] == STICK
    n_blades = len(s.mass) - len(s.motion_amplitude)
    n_clusters = label_clusters(n_blades, s.left, s.right, g.stuck, g.parent, g.labels,
                                g.grounded, g.driver)
    fill_cluster_mass(s.mass, g.labels, n_clusters, g.masses)
    n_stuck = fill_operator(n_blades, s.left, s.right, s.cos_angle, g, n_clusters)
    return n_clusters, n_stuck


@njit_step_merged
def regroup_clusters(s, modes, g):
    """Stick clusters and the static friction operator of a set of modes, refilled into
    ``g`` (``records.Switching``): a ``Topology`` of views of it, valid until g is refilled.

    Merged into each caller, so that the views are counted as the caller counts arrays
    (code compiled without reference counting must not hand arrays to code with it)."""
    n_clusters, n_stuck = fill_groups(s, modes, g)
    return Topology(g.stuck, g.labels, g.grounded[:n_clusters], g.driver[:n_clusters],
                    g.masses[:n_clusters], g.operator[:n_stuck], g.stuck_interfaces[:n_stuck])


@njit_step_exact
def project_onto_clusters(s, topology, values, first, momentum):
    """One velocity per stick cluster in values[first:first + n_nodes], conserving its
    momentum; 0 in a grounded cluster, the prescribed node's in a driven one. ``momentum``
    is scratch, one entry per node. With ``first`` = 0 these are the state's velocities;
    with n_nodes, the velocity rows of a tangent vector (δx then δẋ), P δy.

    Returns the kinetic energy removed [J] (of the order of the event tolerance for the
    state's velocities).
    """
    n_clusters = len(topology.grounded)
    for c in range(n_clusters):
        momentum[c] = 0.0
    n = len(s.mass)
    for i in range(n):
        momentum[topology.labels[i]] += s.mass[i] * values[first + i]
    for c in range(n_clusters):
        if topology.driver[c] >= 0:
            momentum[c] = values[first + topology.driver[c]]
    lost = 0.0
    for i in range(n):
        c = topology.labels[i]
        new = momentum[c] if topology.driver[c] >= 0 else (
            0.0 if topology.grounded[c] else momentum[c] / topology.masses[c])
        lost += 0.5 * s.mass[i] * (values[first + i] * values[first + i] - new * new)
        values[first + i] = new
    return lost


#: The stick clusters (one-mass blades) or constraints (substructures) of a set of modes.
regroup = by_scene("regroup", regroup_clusters, regroup_constraints)
#: The velocities projected onto the stuck interfaces' clusters or constraints.
project_velocities = by_scene("project_velocities", project_onto_clusters,
                              project_onto_constraints)
