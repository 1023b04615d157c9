"""Stick clusters: blades joined by stuck interfaces move as one rigid body.

A stick cluster is a connected component of the subgraph of stuck interfaces. A cluster that
reaches a fixed node is grounded: all its blades are at rest. A cluster that holds a
prescribed-motion node is driven by it: all its blades move with that node.
"""

from __future__ import annotations

from collections.abc import Hashable, Iterable

import networkx as nx
import numpy as np

from contact_laws import check_instance

from .compiled import njit_entry, njit_inlined, njit_step_callable

#: ``cluster_labels``' driver of a cluster whose stuck interfaces join motions that differ.
TWO_DRIVERS = -2


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

    Both arguments are checked first, by name (``TypeError`` for a wrong type, ``ValueError``
    for a pair that is no edge of ``graph``).
    """
    check_instance("stick_clusters", "graph", graph, nx.Graph,
                   expected="a networkx.Graph (BladeGroup.graph)")
    stuck = _edges(graph, stuck)
    sub = nx.Graph()
    sub.add_nodes_from(graph)
    sub.add_edges_from(stuck)
    return [set(c) for c in nx.connected_components(sub)]


def _edges(graph: nx.Graph, stuck) -> list[tuple[Hashable, Hashable]]:
    """``stuck`` as a list of edges of ``graph``, or raise naming ``stick_clusters.stuck``."""
    what = "an iterable of (node, node) pairs, each an edge of the group"
    try:
        edges = None if isinstance(stuck, str | bytes) else list(stuck)
    except TypeError:  # not iterable (a number, a 0-d array)
        edges = None
    if edges is None:
        raise TypeError(f"stick_clusters.stuck must be {what}, got {type(stuck).__name__} "
                        f"{stuck!r:.80}")
    for i, pair in enumerate(edges):
        if not _pair(pair):
            raise TypeError(f"stick_clusters.stuck[{i}] must be a (node, node) pair, got "
                            f"{type(pair).__name__} {pair!r:.80}")
        if not graph.has_edge(*pair):
            raise ValueError(f"stick_clusters.stuck[{i}]: ({pair[0]!r}, {pair[1]!r}) is not "
                             "an edge of the group")
    return [tuple(pair) for pair in edges]


def _pair(value) -> bool:
    """Whether ``value`` is two things that could be nodes of a graph (hashable ones)."""
    if not isinstance(value, tuple | list) or len(value) != 2:
        return False
    try:
        hash(tuple(value))
    except TypeError:
        return False
    return True


@njit_inlined
def _root(parent, node):
    while parent[node] != node:
        parent[node] = parent[parent[node]]  # path halving
        node = parent[node]
    return node


@njit_entry
def cluster_labels(n_nodes, n_blades, left, right, stuck):
    """Stick clusters of node positions, by union–find over the stuck interfaces.

    Parameters
    ----------
    n_nodes : int
        Positions 0 … n_blades − 1 are blades; n_blades … n_nodes − 1 prescribed-motion
        nodes, each a cluster's driver.
    n_blades : int
    left, right : int64 arrays (n_interfaces,)
        Node positions of each interface, −1 for a fixed node.
    stuck : bool array (n_interfaces,)

    Returns
    -------
    labels : int64 array (n_nodes,)
        Cluster number 0..n_clusters−1 of each node, numbered by first node.
    grounded : bool array (n_clusters,)
        Whether the cluster's motion is given: joined to a fixed node (all fixed nodes are
        one ground) or holding a prescribed-motion node.
    driver : int64 array (n_clusters,)
        The position of the prescribed-motion node a cluster holds, −1 for none, and
        ``TWO_DRIVERS`` (−2) where it holds two of them, or one and a fixed node:
        motions no stick can join.

    O((n_nodes + n_interfaces) α(n)).
    """
    labels = np.empty(n_nodes, dtype=np.int64)
    grounded = np.empty(n_nodes, dtype=np.bool_)
    driver = np.empty(n_nodes, dtype=np.int64)
    parent = np.empty(n_nodes + 1, dtype=np.int64)
    count = label_clusters(n_blades, left, right, stuck, parent, labels, grounded, driver)
    return labels, grounded[:count].copy(), driver[:count].copy()


@njit_step_callable
def label_clusters(n_blades, left, right, stuck, parent, labels, grounded, driver):
    """``cluster_labels`` into the caller's arrays (n_nodes = len(labels); ``parent`` is
    scratch of n_nodes + 1 entries): fills labels, and grounded and driver up to the number
    of clusters, which it returns. Allocates nothing."""
    n_nodes = len(labels)
    ground = n_nodes
    for i in range(n_nodes + 1):
        parent[i] = i
    for e in range(len(left)):
        if stuck[e]:
            a = _root(parent, left[e] if left[e] >= 0 else ground)
            b = _root(parent, right[e] if right[e] >= 0 else ground)
            if a != b:
                parent[max(a, b)] = min(a, b)
    # A union keeps the smaller root, so each cluster's root is its first node (the ground,
    # last, is a root only while no node joins it): numbering roots as they come numbers
    # the clusters by first node.
    count = 0
    for i in range(n_nodes):
        r = _root(parent, i)
        if r == i:
            labels[i] = count
            count += 1
        else:
            labels[i] = labels[r]
    ground_root = _root(parent, ground)
    for c in range(count):
        grounded[c] = False
        driver[c] = -1
    for i in range(n_nodes):
        c = labels[i]
        if _root(parent, i) == ground_root:
            grounded[c] = True
            if i >= n_blades:
                driver[c] = TWO_DRIVERS
        elif i >= n_blades:
            driver[c] = TWO_DRIVERS if grounded[c] else i
            grounded[c] = True
    return count
