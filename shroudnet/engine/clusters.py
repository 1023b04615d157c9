"""Stick clusters: blades joined by stuck interfaces move as one rigid body.

A stick cluster is a connected component of the subgraph of stuck interfaces. A cluster that
reaches a fixed node is grounded: all its blades are at rest.
"""

from __future__ import annotations

from collections.abc import Hashable, Iterable

import networkx as nx
import numpy as np
from numba import njit


def stick_clusters(graph: nx.Graph, stuck: Iterable[tuple[Hashable, Hashable]]
                   ) -> list[set[Hashable]]:
    """The stick clusters of a group graph: connected components of its stuck edges.

    Every node of ``graph`` appears in exactly one cluster; a node with no stuck edge is a
    cluster of its own. O(V + E).

    Parameters
    ----------
    graph : networkx.Graph
        The group graph (``BladeGroup.graph``).
    stuck : iterable of (node, node)
        The stuck interfaces, each an edge of ``graph``.
    """
    stuck = list(stuck)
    for a, b in stuck:
        if not graph.has_edge(a, b):
            raise ValueError(f"stuck interface ({a!r}, {b!r}) is not an edge of the group")
    sub = nx.Graph()
    sub.add_nodes_from(graph)
    sub.add_edges_from(stuck)
    return [set(c) for c in nx.connected_components(sub)]


@njit(cache=True)
def _root(parent, node):
    while parent[node] != node:
        parent[node] = parent[parent[node]]  # path halving
        node = parent[node]
    return node


@njit(cache=True)
def cluster_labels(n_blades, left, right, stuck):
    """Stick clusters of blade positions, by union–find over the stuck interfaces.

    Parameters
    ----------
    n_blades : int
    left, right : int64 arrays (n_interfaces,)
        Blade positions of each interface, −1 for a fixed node.
    stuck : bool array (n_interfaces,)

    Returns
    -------
    labels : int64 array (n_blades,)
        Cluster number 0..n_clusters−1 of each blade, numbered by first blade.
    grounded : bool array (n_clusters,)
        Whether the cluster is joined to a fixed node (all fixed nodes are one ground).

    O((n_blades + n_interfaces) α(n)).
    """
    ground = n_blades
    parent = np.arange(n_blades + 1)
    for e in range(len(left)):
        if stuck[e]:
            a = _root(parent, left[e] if left[e] >= 0 else ground)
            b = _root(parent, right[e] if right[e] >= 0 else ground)
            if a != b:
                parent[max(a, b)] = min(a, b)
    index = np.full(n_blades + 1, -1)
    labels = np.empty(n_blades, dtype=np.int64)
    count = 0
    for i in range(n_blades):
        r = _root(parent, i)
        if index[r] < 0:
            index[r] = count
            count += 1
        labels[i] = index[r]
    grounded = np.zeros(count, dtype=np.bool_)
    ground_root = _root(parent, ground)
    for i in range(n_blades):
        if _root(parent, i) == ground_root:
            grounded[labels[i]] = True
    return labels, grounded
