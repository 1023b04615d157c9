"""A blade group: blades are nodes, shroud interfaces and couplings are edges of a networkx
multigraph (two nodes may be joined by several edges: an interface and a coupling, or two
interfaces).

Every node carries the attribute ``blade`` (a ``Blade`` or a ``Substructure``, a node of
many degrees of freedom, or None for a fixed node: the disc,
the casing, a damper platform, whose displacement is x ≡ 0, and for a prescribed-motion
node) and ``motion`` (the ``Motion`` of a prescribed-motion node, else None: a belt, a
shaker, whose displacement is a given function of time). Every edge carries either
``interface`` (an ``Interface``: a contact that opens, slips and sticks) or ``coupling`` (a
``Coupling``: a linear spring and damper that never does), ``left`` (the name of its left
node i, so that u = x_left − x_right; see ``model.interface``) and ``index`` (its
position in the interface or the coupling arrays: the order of its kind's ``connect``
calls). An edge between points of nodes (``connect`` with (node, point) ends) also
carries ``left_point`` and ``right_point``, the point names at its left and right ends
(None at a fixed or prescribed node, or where the node's only point is meant). An edge
that joins several pairs of points, a **patch** (``connect`` with (node, [point, …])
ends), carries a tuple of k names at each end (or None at a fixed or prescribed node):
its pairs (``point_pairs``) are k contacts, each with the edge's laws.

A group's graph is a ``GroupGraph``: a ``networkx.MultiGraph`` whose ``edges[a, b]`` also
reads the one edge between two nodes, as a ``networkx.Graph``'s does. A graph built with
networkx itself (a ``Graph`` or a ``MultiGraph``) and assigned (``group.graph = graph``)
is read the same way, and counted once by the next ``connect``; its edges must carry
``left`` and an ``index`` of their own, distinct within each kind. An edge added through
networkx to a group's graph after that is not counted: two edges that share an index are
refused when read.

Building is linear in the size of the group: ``connect`` numbers an edge from a count it
keeps, and ``chain`` and ``ring`` check each distinct blade once and add their nodes and
edges in bulk (a ring of 100,000 blades in 0.6 s of CPU, where counting every edge on each
``connect`` took 53 s for 10,000).
"""

from __future__ import annotations

import math
from collections.abc import Hashable, Iterable, Sequence
from functools import cached_property
from itertools import islice
from typing import NamedTuple

import networkx as nx
from networkx.classes.reportviews import MultiEdgeView

import numpy as np

from contact_laws import check_array, check_int, check_real

from .blade import Blade
from .coupling import Coupling
from .interface import Interface
from .motion import ConstantVelocity, HarmonicMotion, Motion, MotionTable
from .substructure import Substructure

#: An end of an edge: a node's name, (node name, point name), or (node name, [point
#: name, …]), the k points of a patch.
End = Hashable | tuple[Hashable, str] | tuple[Hashable, Sequence[str]]
#: The one point of a ``Blade``: its displacement x.
BLADE_POINT = "x"
#: The kinds of edge, each named by the attribute that holds its law.
KINDS = ("interface", "coupling")
#: How many names a message lists before it gives only their number.
SHOWN = 5


class Contact(NamedTuple):
    """One contact of a group: the point pair ``contact`` (0-based) of the ``interface``-th
    interface (``BladeGroup.interfaces``), which has ``pairs`` of them (1 but for a patch),
    between ``left_point`` of node ``left`` and ``right_point`` of node ``right`` (None at
    a fixed or prescribed node, or at a node's only point). Its ``str`` names it in
    messages: "interface 2 ('a', 'b')", or "interface 2, contact 5 ('a', 'b')" in a
    patch."""

    interface: int
    contact: int
    pairs: int
    left: Hashable
    right: Hashable
    left_point: str | None
    right_point: str | None

    def __str__(self) -> str:
        which = f"interface {self.interface}"
        if self.pairs > 1:
            which += f", contact {self.contact}"
        return f"{which} ({self.left!r}, {self.right!r})"


class _EdgeView(MultiEdgeView):
    """A multigraph's edges, which also reads ``edges[a, b]``: the data of the one edge
    between a and b (a ValueError where there are several: name one as ``edges[a, b,
    key]``)."""

    def __getitem__(self, edge):
        if isinstance(edge, tuple) and len(edge) == 2:
            a, b = edge
            try:
                keys = self._graph._adj[a][b]
            except KeyError:
                raise KeyError(f"the edge {a!r}–{b!r} is not in the graph") from None
            if len(keys) != 1:
                raise ValueError(f"nodes {a!r} and {b!r} are joined by {len(keys)} edges; "
                                 f"name one as edges[{a!r}, {b!r}, key], key in "
                                 f"{list(keys)}")
            return next(iter(keys.values()))
        return super().__getitem__(edge)


class GroupGraph(nx.MultiGraph):
    """The graph of a ``BladeGroup``: a ``networkx.MultiGraph`` (two nodes may be joined by
    several edges) whose ``edges[a, b]`` reads the one edge between a and b, as a
    ``networkx.Graph``'s does."""

    @cached_property
    def edges(self):
        return _EdgeView(self)


class BladeGroup:
    """A group of blades and the interfaces between them, built up node by node.

    Examples
    --------
    >>> from contact_laws import LinearSpring, Coulomb
    >>> blade = Blade(mass=0.08, damping=4.0, stiffness=1.5e5)
    >>> shroud = Interface(gap=2e-5, angle=1.0, normal=LinearSpring(stiffness=3e5),
    ...                    friction=Coulomb(mu=0.3))
    >>> group = BladeGroup.chain(3, blade, shroud)
    >>> group.blades
    ['blade1', 'blade2', 'blade3']
    """

    def __init__(self) -> None:
        self.graph = GroupGraph()
        # The edges of each kind on ``graph`` (the graph they were counted on): the next
        # ``index`` in O(1). A graph assigned to ``graph`` is counted on its first connect.
        self._counted = (self.graph, dict.fromkeys(KINDS, 0))

    # -- building ---------------------------------------------------------------------------

    def add_blade(self, name: Hashable, blade: Blade | Substructure,
                  frame=None) -> BladeGroup:
        """Add a blade node called ``name``: a ``Blade`` (one mass) or a ``Substructure``
        (a structure of many degrees of freedom with named points); returns the group so
        calls can be chained.

        ``frame`` (a substructure's, optional) is the rotation Q (d × d, d = 2 or 3, QᵀQ
        = I, det Q = 1) of its points' components into the group's frame: r = Q Φ_p q for
        its points of d components (those of one component are left as they are). Nodes
        whose models are given in frames of their own, the sectors of a disc each turned
        by 2πs/N, then have identical matrices; an interface's directions are in its left
        node's frame (see ``model.interface``), and so are a node's own readings
        (``Scene.point_rows``). Without a frame, a node's components are the group's.
        """
        if not isinstance(blade, Blade | Substructure):
            raise TypeError(f"add_blade({name!r}, ...) needs a shroudnet.Blade or "
                            f"shroudnet.Substructure, got {_shown(blade)}")
        frame = _frame(f"add_blade({name!r}, ...)", frame, blade)
        self._add_node("add_blade", name, blade)
        if frame is not None:
            self.graph.nodes[name]["frame"] = frame
        return self

    def frame(self, name: Hashable) -> np.ndarray | None:
        """The rotation Q of node ``name``'s points' components into the group's frame
        (``add_blade``), or None for a node in the group's frame."""
        if name not in self.graph:
            _check_name("BladeGroup.frame", "name", name)
            raise ValueError(f"BladeGroup.frame: no node {name!r} in the group; its nodes "
                             f"are {_some(self.graph)}")
        frame = self.graph.nodes[name].get("frame")  # optional: None for the group's
        return None if frame is None else np.array(frame, dtype=float)

    @property
    def sectors(self) -> int | None:
        """The number of identical sectors the group's moving nodes make round a disc,
        whose nodes come sector by sector (``ring``, ``bladed_disc``,
        ``declare_sectors``), or None."""
        return self.graph.graph.get("sectors")

    def declare_sectors(self, sectors: int) -> BladeGroup:
        """Declare the group a ring of ``sectors`` identical sectors, as ``ring`` and
        ``bladed_disc`` do: its moving nodes were added sector by sector, as many to each
        (slot j of sector s is the moving node s·m + j), and one sector on, every node,
        edge and load meets its twin (what ``periodic_orbit(symmetry="cyclic")`` checks
        and uses; ``linear_modes`` reads the nodal diameters by it). Returns the group."""
        sectors = check_int("BladeGroup.declare_sectors", "sectors", sectors, low=1)
        blades = len(self.blades)
        if blades % sectors:
            raise ValueError(f"BladeGroup.declare_sectors: {sectors} sectors must share the "
                             f"group's {blades} moving nodes evenly, as many to each")
        self.graph.graph["sectors"] = sectors
        return self

    def add_fixed(self, name: Hashable) -> BladeGroup:
        """Add a fixed node (x ≡ 0) called ``name``: the disc, the casing, a damper platform."""
        self._add_node("add_fixed", name, None)
        return self

    def add_prescribed(self, name: Hashable, motion: Motion) -> BladeGroup:
        """Add a node called ``name`` whose displacement follows ``motion`` (a
        ``ConstantVelocity``, ``HarmonicMotion`` or ``MotionTable``), whatever the forces on
        it: a moving belt, a shaker. It stands wherever a fixed node may."""
        if not isinstance(motion, ConstantVelocity | HarmonicMotion | MotionTable):
            raise TypeError(f"add_prescribed({name!r}, ...) needs a ConstantVelocity, "
                            f"HarmonicMotion or MotionTable, got {_shown(motion)}")
        self._add_node("add_prescribed", name, None, motion)
        return self

    def connect(self, left: End, right: End, interface: Interface | Coupling) -> BladeGroup:
        """Join ``left`` (node i) and ``right`` (node j) by ``interface``: an ``Interface``
        (a contact) or a ``Coupling`` (a spring and damper); returns the group.

        An end is a node's name, or a (node name, point name) tuple that joins a point of
        a ``Substructure``: ``connect(("blade1", "shroud"), ("blade2", "shroud"), shroud)``.
        A substructure's end names its point unless the substructure has only one; a
        ``Blade`` has the one point ``"x"``, its displacement.

        An end (node name, [point name, …]) joins k points at once, a **patch**: the other
        end names as many (or is a fixed or prescribed node), and each pair, k-th point to
        k-th point, is a contact of its own with the interface's laws (its own normal load,
        stick or slip, slider), as a face meshed with k node pairs is:
        ``connect(("blade1", ["R0", "R1"]), ("blade2", ["L0", "L1"]), shroud)``. A point
        may come more than once (coincident pairs). A coupling's patch is a spring and
        damper per pair.

        Two nodes may be joined by several edges (an interface and a coupling, or two
        interfaces), each connected by a call of its own.
        """
        kind = _kind(interface, f"connect({left!r}, {right!r}, ...) needs")
        where = f"connect({left!r}, {right!r})"
        (left, left_point), (right, right_point) = (self._end(left, interface, where),
                                                    self._end(right, interface, where))
        if left == right:
            raise ValueError(f"{where}: an interface needs two nodes")
        if not self.graph.is_multigraph() and self.graph.has_edge(left, right):
            raise ValueError(f"{where}: these nodes are already connected, and this group's "
                             "graph is a networkx.Graph, which holds one edge between two "
                             "nodes; assign it as a networkx.MultiGraph (group.graph = "
                             "networkx.MultiGraph(group.graph)) to join them again")
        nodes = self.graph.nodes
        if nodes[left]["blade"] is None and nodes[right]["blade"] is None:
            raise ValueError(f"{where}: neither node is a blade (both are "
                             "fixed or prescribed), so nothing between them can move")
        _check_patch(left_point, right_point, nodes[left]["blade"] is None
                     or nodes[right]["blade"] is None, where)
        self._add_edges([(left, right)], interface, kind, (left_point, right_point))
        return self

    def _add_edges(self, pairs: list[tuple[Hashable, Hashable]], interface, kind: str,
                   points: tuple | list[tuple]) -> None:
        """Add an edge of ``kind`` holding ``interface`` for each (left, right) of ``pairs``,
        checked already, indexed on from the edges of that kind so far; ``points`` is the
        (left point, right point) of every edge (each a name, None, or a patch's tuple of
        names), or a list of one per edge."""
        graph, counts = getattr(self, "_counted", (None, None))
        if graph is not self.graph:  # assigned, or built by networkx: count once
            counts = {k: sum(1 for *_, data in self.graph.edges(data=True) if k in data)
                      for k in KINDS}
            self._counted = (self.graph, counts)
        first = counts[kind]
        if points == (None, None):  # no edge joins named points
            edges = ((a, b, {"left": a, "index": index, kind: interface})
                     for index, (a, b) in enumerate(pairs, first))
        else:
            ends = [points] * len(pairs) if isinstance(points, tuple) else points
            edges = ((a, b, {"left": a, "index": index, kind: interface} | (
                {} if lp is None and rp is None else {"left_point": lp, "right_point": rp}))
                     for index, ((a, b), (lp, rp)) in enumerate(zip(pairs, ends), first))
        self.graph.add_edges_from(edges)
        counts[kind] = first + len(pairs)

    def _end(self, end, interface, where) -> tuple[Hashable, str | tuple | None]:
        """(node, point) of an edge's end, checked against the node and the interface:
        the point a name (or None), or the tuple of a patch's names."""
        node, point = (end if isinstance(end, tuple) and len(end) == 2
                       and (isinstance(end[1], str) or _is_patch(end[1])) else (end, None))
        if node not in self.graph:  # False for an unhashable name, too
            _check_name(where, "an end", node)
            raise ValueError(f"{where}: unknown node {node!r}; add it first (nodes: "
                             f"{_some(self.graph)})")
        body = self._body(node)
        if _is_patch(point):
            if not point:
                raise ValueError(f"{where}: the patch at node {node!r} names no points; give "
                                 "one or more")
            names = tuple(_point(node, body, name, interface, where) for name in point)
            return node, names if len(names) > 1 else names[0]
        return node, _point(node, body, point, interface, where)

    def _add_node(self, owner: str, name: Hashable, blade: Blade | None,
                  motion: Motion | None = None) -> None:
        _check_name(owner, "name", name)
        if name in self.graph:
            raise ValueError(f"node {name!r} is already in the group")
        self.graph.add_node(name, blade=blade, motion=motion)

    def _body(self, node: Hashable) -> Blade | Substructure | None:
        """The ``blade`` attribute of ``node`` (in the graph), which every node must carry."""
        try:
            return self.graph.nodes[node]["blade"]
        except KeyError:
            raise _no_body(node) from None

    # -- presets ----------------------------------------------------------------------------

    @classmethod
    def chain(cls, n: int, blade: Blade | Sequence[Blade], interface: Interface | Coupling,
              names: Sequence[Hashable] | None = None, *,
              points: tuple | None = None, blades_on_disc: int | None = None) -> BladeGroup:
        """A packet of ``n ≥ 1`` blades in a row, each joined to the next by ``interface``
        (or a ``Coupling``).

        The blades are named ``"blade1"`` … ``"bladen"`` as in the paper, unless ``names``
        gives n names; their positions are 0 … n−1 in that order. ``blade`` is one blade
        (or ``Substructure``) for all or a sequence of n (a mistuned packet). Time and
        memory are linear in n.

        ``points`` = (left face, right face) names the points of each blade where its
        neighbours touch it, each a point's name or a list of them (a patch): blade s's
        right face meets blade s + 1's left face, k-th point to k-th point
        (``connect``). Without, each blade's one point (or its named only point) is
        joined on both sides. With ``points`` and ``blades_on_disc`` N, blade s (from 0)
        is turned by 2πs/N into the group's frame, as ``ring`` turns its blades.
        """
        n = check_int("BladeGroup.chain", "n", n, low=1)
        if blades_on_disc is not None:
            blades_on_disc = check_int("BladeGroup.chain", "blades_on_disc", blades_on_disc,
                                       low=n)
        group = cls()
        group._add_row("BladeGroup.chain", n, blade, interface, names, closed=False,
                       points=points, turns=blades_on_disc)
        return group

    @classmethod
    def ring(cls, n: int, blade: Blade | Sequence[Blade], interface: Interface | Coupling,
             names: Sequence[Hashable] | None = None, *,
             points: tuple | None = None) -> BladeGroup:
        """A full shrouded disc of ``n ≥ 3`` blades: a ``chain`` whose last blade is joined
        to its first. Its ``sectors`` is n.

        ``points`` = (left face, right face), as for ``chain``: blade s's right face
        meets blade s + 1's left face (the last blade's, the first's). With it, blade s
        (from 0) is a sector in a frame of its own, turned by 2πs/n into the group's
        (``add_blade``): its face points' components, if they are two, lie in the disc's
        plane; if three, the third is along the disc's axis (``sector_frame``). Identical
        blades then have identical matrices, and the interface's directions are those of
        each blade's right face, in that blade's own frame.
        """
        n = check_int("BladeGroup.ring", "n", n)
        if n < 3:
            raise ValueError(f"BladeGroup.ring needs n >= 3 blades, got {n}")
        group = cls()
        group._add_row("BladeGroup.ring", n, blade, interface, names, closed=True,
                       points=points, turns=n)
        group.graph.graph["sectors"] = n
        return group

    def _add_row(self, owner, n, blade, interface, names, closed, points=None,
                 turns=None) -> None:
        """``chain``'s and ``ring``'s n blades, each joined to the next (the last to the
        first when ``closed``): each distinct blade is checked once, then the nodes and the
        edges are added in bulk. With ``points`` (left face, right face), blade s's right
        face meets blade s + 1's left face, and with ``turns`` N blade s is turned by
        2πs/N (``sector_frame``)."""
        kind = _kind(interface, f"{owner} needs interface to be")
        bodies = _bodies(owner, n, blade)
        names = _names(owner, n, names)
        pairs = list(zip(names, names[1:]))
        if closed:
            pairs.append((names[-1], names[0]))
        if points is not None:
            self._add_faced_row(owner, names, [blade] * n if bodies is None else bodies,
                                interface, kind, pairs, points, turns)
            return
        if bodies is None:  # one blade for all
            point = _point(names[0], blade, None, interface, f"{owner}: blade {names[0]!r}")
            self.graph.add_nodes_from(names, blade=blade, motion=None)
            points = (point, point)
        else:
            ends = {}  # id(body) → its point for this interface
            for name, body in zip(names, bodies):
                if id(body) not in ends:
                    ends[id(body)] = _point(name, body, None, interface,
                                            f"{owner}: blade {name!r}")
                self.graph.add_node(name, blade=body, motion=None)
            at = [ends[id(body)] for body in bodies]
            points = list(zip(at, at[1:] + at[:1]))[:len(pairs)]
        self._add_edges(pairs, interface, kind, points)

    def _add_faced_row(self, owner, names, bodies, interface, kind, pairs, points,
                       turns) -> None:
        """``_add_row``'s blades joined face to face: blade s's right face to blade
        s + 1's left face, each blade turned by 2πs/``turns`` where its faces' points have
        two or three components (and ``turns`` is given)."""
        faces = _face_names(owner, points)
        ends = {}  # id(body) → (its left face, its right face) for this interface
        for name, body in zip(names, bodies):
            if id(body) not in ends:
                where = f"{owner}: blade {name!r}"
                ends[id(body)] = tuple(_face(name, body, face, interface, where)
                                       for face in faces)
        at = [ends[id(body)] for body in bodies]
        edges = [(at[s][1], at[(s + 1) % len(at)][0]) for s in range(len(pairs))]
        for (left, right), (a, b) in zip(pairs, edges):
            _check_patch(a, b, False, f"{owner}: blades {left!r} and {right!r}")
        for s, (name, body) in enumerate(zip(names, bodies)):
            self.graph.add_node(name, blade=body, motion=None)
            components = _face_components(body, at[s])
            if turns is not None and components in (2, 3):
                self.graph.nodes[name]["frame"] = _frame(
                    f"{owner}: blade {name!r}",
                    sector_frame(2.0 * math.pi * s / turns, components), body)
        self._add_edges(pairs, interface, kind, edges)

    @classmethod
    def bladed_disc(cls, sectors: int, disc: Blade, disc_coupling: Coupling,
                    blade: Sequence[Blade], blade_couplings: Sequence[Coupling],
                    shroud: Interface | None = None, *,
                    points: tuple | None = None) -> BladeGroup:
        """A bladed disc of ``sectors ≥ 3`` identical sectors, each a disc node and a blade
        of one or more nodes, root to tip::

            ── disc_s ── disc_coupling ── disc_s+1 ──        (round the ring)
                 │ blade_couplings[0]
               blade_s_1 ── blade_couplings[1] ── blade_s_2 … (the tip: the last node)
                 tip_s ═══ shroud ═══ tip_s+1                 (interfaces, if given)

        ``blade`` gives the blade's nodes root to tip, typically with no spring to ground
        (stiffness 0: they are held by the couplings), ``blade_couplings`` the couplings
        disc–root and node to node (one per blade node); a single node and a single
        coupling may be given as such. Nodes are named
        ``disc{s}`` and ``blade{s}_{k}`` (s from 1, k root = 1) and added sector by
        sector, so that ``sectors`` reads the positions (``linear_modes``).

        ``points`` = (left face, right face) of the tip, as ``ring`` takes it: tip s's
        right face meets tip s + 1's left face by ``shroud``, and sector s (from 0) is
        turned by 2πs/N into the group's frame (``sector_frame``): each of its
        substructures whose points have as many components as the faces'. A coupling
        joins a node of several points at its point "root" (the node's end nearer the
        disc) or "tip" (its outer end).
        """
        owner = "BladeGroup.bladed_disc"
        sectors = check_int(owner, "sectors", sectors, low=3)
        if not isinstance(disc, Blade | Substructure):
            raise TypeError(f"{owner}.disc must be a shroudnet.Blade or Substructure, got "
                            f"{_shown(disc)}")
        _kind(disc_coupling, f"{owner} needs disc_coupling to be")
        blade = _sequence(f"{owner}.blade", blade, Blade | Substructure,
                          "a Blade or Substructure")
        blade_couplings = _sequence(f"{owner}.blade_couplings", blade_couplings,
                                    Interface | Coupling, "a Coupling or an Interface")
        if shroud is not None:
            _kind(shroud, f"{owner} needs shroud to be None or")
        if not blade or len(blade_couplings) != len(blade):
            raise ValueError(f"bladed_disc needs one coupling per blade node (disc–root, "
                             f"then node to node): got {len(blade)} nodes and "
                             f"{len(blade_couplings)} couplings")
        faces = components = None
        if points is not None:
            if shroud is None:
                raise ValueError(f"{owner}.points names the tips' faces, which the shroud "
                                 "joins: give shroud= too")
            where = f"{owner}: the tip"
            faces = tuple(_face("tip", blade[-1], face, shroud, where)
                          for face in _face_names(owner, points))
            _check_patch(faces[1], faces[0], False, where)
            components = _face_components(blade[-1], faces)
        group = cls()
        tips = []
        for s in range(1, sectors + 1):
            chain = [f"disc{s}"] + [f"blade{s}_{k}" for k in range(1, len(blade) + 1)]
            frame = sector_frame(2.0 * math.pi * (s - 1) / sectors, components) \
                if components in (2, 3) else None
            for name, node in zip(chain, [disc, *blade]):
                turned = frame is not None and isinstance(node, Substructure) and any(
                    matrix.shape[0] == components for matrix in node.points.values())
                group.add_blade(name, node, frame if turned else None)
            bodies = [disc, *blade]
            for (inner, outer), (body, next_body), coupling in zip(
                    zip(chain, chain[1:]), zip(bodies, bodies[1:]), blade_couplings):
                group.connect(_joint(inner, body, "tip"), _joint(outer, next_body, "root"),
                              coupling)
            tips.append(chain[-1])
        for s in range(sectors):
            group.connect(f"disc{s + 1}", f"disc{(s + 1) % sectors + 1}", disc_coupling)
            if shroud is not None:
                right, left = ((tips[s], faces[1]), (tips[(s + 1) % sectors], faces[0])) \
                    if faces is not None else (tips[s], tips[(s + 1) % sectors])
                group.connect(right, left, shroud)
        group.graph.graph["sectors"] = sectors
        return group

    # -- reading ----------------------------------------------------------------------------

    @property
    def blades(self) -> list[Hashable]:
        """Names of the moving blades, in the order they were added (their positions)."""
        try:
            return [n for n, data in self.graph.nodes(data=True) if data["blade"] is not None]
        except KeyError:
            raise self._no_body() from None

    @property
    def fixed(self) -> list[Hashable]:
        """Names of the fixed nodes."""
        try:
            return [n for n, data in self.graph.nodes(data=True)
                    if data["blade"] is None and data.get("motion") is None]
        except KeyError:
            raise self._no_body() from None

    def _no_body(self) -> ValueError:
        return _no_body(next(n for n, data in self.graph.nodes(data=True)
                             if "blade" not in data))

    @property
    def prescribed(self) -> list[tuple[Hashable, Motion]]:
        """(name, motion) of the prescribed-motion nodes, in the order they were added."""
        return [(n, motion) for n, motion in self.graph.nodes(data="motion")
                if motion is not None]

    @property
    def has_substructures(self) -> bool:
        """Whether a node is a ``Substructure``, or an edge joins named points."""
        return any(isinstance(blade, Substructure) for _, blade in
                   self.graph.nodes(data="blade")) or any(
            "left_point" in data or getattr(data.get("interface"), "components", None)
            for *_, data in self.graph.edges(data=True))

    def edge_points(self, kind: str) -> list[tuple[str | tuple | None, str | tuple | None]]:
        """(left point, right point) of every interface (``kind`` "interface") or coupling
        ("coupling"), in the order of ``interfaces`` or ``couplings``: each a point's name,
        None (a node's only point, or a fixed or prescribed node), or a patch's tuple of
        names (``point_pairs`` pairs them)."""
        if not isinstance(kind, str):
            raise TypeError(f"BladeGroup.edge_points: kind must be 'interface' or "
                            f"'coupling', got {_shown(kind)}")
        if kind not in KINDS:
            raise ValueError(f"BladeGroup.edge_points: kind must be 'interface' or "
                             f"'coupling', got {kind!r}")
        return [(data.get("left_point"), data.get("right_point"))
                for *_, data in self._ordered(kind)]

    def point_pairs(self, kind: str) -> list[tuple[tuple[str | None, str | None], ...]]:
        """The (left point, right point) pairs of every interface (``kind`` "interface")
        or coupling ("coupling"), in the order of ``interfaces`` or ``couplings``: one pair
        for an edge between two points (or nodes), k for a patch of k (``connect``)."""
        return [_pairs(left, right) for left, right in self.edge_points(kind)]

    @property
    def contacts(self) -> list[Contact]:
        """Every contact: each interface's point pairs in turn, in the order of
        ``interfaces`` (one per interface but for patches, k for a patch of k)."""
        return [Contact(e, c, len(pairs), left, right, *pair)
                for e, ((left, right, _), pairs) in enumerate(zip(self.interfaces,
                                                                  self.point_pairs("interface")))
                for c, pair in enumerate(pairs)]

    @property
    def interfaces(self) -> list[tuple[Hashable, Hashable, Interface]]:
        """(left, right, interface) for every interface, in the order they were connected."""
        return self._edges("interface")

    @property
    def couplings(self) -> list[tuple[Hashable, Hashable, Coupling]]:
        """(left, right, coupling) for every coupling, in the order they were connected."""
        return self._edges("coupling")

    def _edges(self, kind):
        edges = []
        for a, b, data in self._ordered(kind):
            left = data.get("left")  # None where missing: never a node's name
            if left != a and left != b:
                raise ValueError(f"the {kind} between {a!r} and {b!r} needs the edge "
                                 f"attribute 'left', one of its two nodes; got "
                                 f"{_or_none(data, 'left')}")
            edges.append((left, b if left == a else a, data[kind]))
        return edges

    def _ordered(self, kind: str) -> list[tuple[Hashable, Hashable, dict]]:
        """(a, b, data) of the edges of ``kind``, by their ``index``, which must be
        present, comparable and distinct."""
        edges = [edge for edge in self.graph.edges(data=True) if kind in edge[2]]
        try:
            edges.sort(key=lambda edge: edge[2]["index"])
        except (KeyError, TypeError):
            bad = next((edge for edge in edges if "index" not in edge[2]), edges[0])
            raise ValueError(f"the {kind} between {bad[0]!r} and {bad[1]!r} needs an "
                             f"edge attribute 'index', a whole number that orders the "
                             f"{kind}s; got {_or_none(bad[2], 'index')}") from None
        for (a, b, one), (c, d, other) in zip(edges, edges[1:]):
            if one["index"] == other["index"]:
                raise ValueError(f"the {kind}s between {a!r} and {b!r} and between {c!r} "
                                 f"and {d!r} share the index {one['index']!r}; each "
                                 f"{kind} needs its own")
        return edges

    def blade(self, name: Hashable) -> Blade | Substructure:
        """The ``Blade`` or ``Substructure`` at node ``name``."""
        try:
            data = self.graph.nodes[name]
        except (KeyError, TypeError, nx.NetworkXError):
            _check_name("BladeGroup.blade", "name", name)
            raise ValueError(f"BladeGroup.blade: no node {name!r} in the group; its nodes "
                             f"are {_some(self.graph)}") from None
        if "blade" not in data:
            raise _no_body(name)
        blade = data["blade"]
        if blade is None:
            kind = "prescribed" if data.get("motion") else "fixed"
            raise ValueError(f"node {name!r} is {kind}, not a blade")
        return blade

    def __repr__(self) -> str:
        couplings = f", {len(self.couplings)} couplings" if self.couplings else ""
        prescribed = f", {len(self.prescribed)} prescribed" if self.prescribed else ""
        return (f"BladeGroup({len(self.blades)} blades, {len(self.fixed)} fixed nodes"
                f"{prescribed}, {len(self.interfaces)} interfaces{couplings})")


def _point(node, body, point, interface, where) -> str | None:
    """The point of ``body`` (at ``node``) that an end joins, checked against the interface:
    ``point``, or a substructure's only one; None for a blade's x or a node with none."""
    if isinstance(body, Substructure):
        names = list(body.points)
        if point is None:
            if len(names) != 1:
                raise ValueError(f"{where}: node {node!r} is a Substructure with points "
                                 f"{names}; name one, as ({node!r}, point)")
            point = names[0]
        elif point not in body.points:
            raise ValueError(f"{where}: node {node!r} has no point {point!r}; its "
                             f"points are {names}")
        size = body.point(point).shape[0]
    elif point is not None and not (isinstance(body, Blade) and point == BLADE_POINT):
        kind = "a Blade, whose one point is 'x'" if body is not None \
            else "fixed or prescribed, with no points"
        raise ValueError(f"{where}: node {node!r} is {kind}; got the point {point!r}")
    else:
        size = 1
    wanted = getattr(interface, "components", None)
    if body is not None and wanted is not None and size != wanted:
        raise ValueError(f"{where}: point {point!r} of node {node!r} has {size} "
                         f"component(s), but the interface's directions have {wanted}")
    if body is not None and wanted is None and size != 1 and isinstance(interface,
                                                                       Interface):
        raise ValueError(f"{where}: point {point!r} of node {node!r} has {size} "
                         "components: give the Interface normal_direction= and "
                         "tangent_direction= (the angle form joins points of one "
                         "component)")
    return point


#: How far QᵀQ may be from I, and det Q from 1, for a frame.
FRAME_TOLERANCE = 1e-9


def sector_frame(angle: float, components: int) -> np.ndarray:
    """The rotation by ``angle`` [rad] about a disc's axis of a point's ``components``
    (2: both in the disc's plane; 3: the third along the axis), the frame of a sector
    turned by that angle (``BladeGroup.ring``)::

        2:  [[cos, −sin], [sin, cos]]      3:  [[cos, −sin, 0], [sin, cos, 0], [0, 0, 1]]
    """
    angle = check_real("sector_frame", "angle", angle, unit="rad")
    components = check_int("sector_frame", "components", components, low=2, high=3)
    cos, sin = math.cos(angle), math.sin(angle)
    frame = np.eye(components)
    frame[:2, :2] = [[cos, -sin], [sin, cos]]
    return frame


def _frame(owner: str, frame, body) -> tuple | None:
    """``frame`` checked (``add_blade``), as rows of floats; None stays None."""
    if frame is None:
        return None
    if not isinstance(body, Substructure):
        raise ValueError(f"{owner}: frame= turns a Substructure's points; a Blade's one "
                         "point has one component, which no frame turns")
    matrix = check_array(owner, "frame", frame, shape=(None, None))
    d = matrix.shape[0]
    if matrix.shape != (d, d) or d not in (2, 3):
        raise ValueError(f"{owner}: frame must be a 2 × 2 or 3 × 3 rotation, got shape "
                         f"{matrix.shape}")
    if np.abs(matrix.T @ matrix - np.eye(d)).max() > FRAME_TOLERANCE \
            or abs(np.linalg.det(matrix) - 1.0) > FRAME_TOLERANCE:
        raise ValueError(f"{owner}: frame must be a rotation (QᵀQ = I and det Q = 1 to "
                         f"{FRAME_TOLERANCE:g}), got {matrix.tolist()}")
    odd = sorted({p.shape[0] for p in body.points.values()} - {1, d})
    if odd:
        raise ValueError(f"{owner}: a frame of {d} × {d} turns points of {d} components "
                         f"(and leaves those of one); this substructure has points of {odd[0]}")
    return _rows(matrix)


def _rows(matrix) -> tuple[tuple[float, ...], ...]:
    """A matrix as a tuple of rows of floats: immutable, and compared by value."""
    return tuple(tuple(float(value) for value in row) for row in np.asarray(matrix))


def _face_names(owner: str, points) -> tuple:
    """``points`` of a builder: (left face, right face), each a name or names."""
    if not (isinstance(points, tuple | list) and len(points) == 2 and all(
            isinstance(face, str) or _is_patch(face) for face in points)):
        raise TypeError(f"{owner}.points must be (left face, right face), each a point's "
                        f"name or a list of names, got {_shown(points)}")
    return tuple(face if isinstance(face, str) else tuple(face) for face in points)


def _face(node, body, face, interface, where) -> str | tuple | None:
    """A blade's face (a point's name, or a patch's names) checked as ``connect``'s end."""
    if isinstance(face, str):
        return _point(node, body, face, interface, where)
    if not face:
        raise ValueError(f"{where}: a face names no points; give one or more")
    names = tuple(_point(node, body, name, interface, where) for name in face)
    return names if len(names) > 1 else names[0]


def _face_components(body, faces) -> int:
    """The components of the points of a blade's faces (1 for a Blade)."""
    if not isinstance(body, Substructure):
        return 1
    name = next(iter(faces[0] if isinstance(faces[0], tuple) else (faces[0],)))
    return body.point(name).shape[0]


def _joint(node, body, point: str):
    """A coupling's end at ``node`` in ``bladed_disc``: the node itself, or, for a
    substructure of several points, (node, ``point``)."""
    if isinstance(body, Substructure) and len(body.points) > 1:
        return node, point
    return node


def _is_patch(value) -> bool:
    """Whether an end's ``value`` names a patch's points: a list or tuple of names."""
    return isinstance(value, list | tuple) and all(isinstance(name, str) for name in value)


def _check_patch(left, right, grounded: bool, where) -> None:
    """Raise unless an edge's (left point, right point) pair up: two patches of one size,
    or a patch against a fixed or prescribed node (``grounded``), or no patch."""
    sizes = [len(point) for point in (left, right) if isinstance(point, tuple)]
    if sizes and not (len(sizes) == 2 and sizes[0] == sizes[1]) and not (
            len(sizes) == 1 and grounded):
        shown = [len(p) if isinstance(p, tuple) else 1 for p in (left, right)]
        raise ValueError(f"{where}: a patch pairs its points k-th to k-th, so both ends "
                         f"name as many points (or one end is a fixed or prescribed node); "
                         f"got {shown[0]} and {shown[1]}")


def _pairs(left, right) -> tuple[tuple[str | None, str | None], ...]:
    """An edge's point pairs from its (left point, right point) (``point_pairs``)."""
    size = next((len(point) for point in (left, right) if isinstance(point, tuple)), None)
    if size is None:
        return ((left, right),)
    return tuple(zip(*(point if isinstance(point, tuple) else (point,) * size
                       for point in (left, right))))


def _or_none(data: dict, key: str) -> str:
    """The repr of ``data[key]`` for a message, or "none" where it is missing."""
    return repr(data[key]) if key in data else "none"


def _kind(interface, needs: str) -> str:
    """The kind of edge ``interface`` makes ("interface" or "coupling"), or a TypeError
    that starts with ``needs``."""
    if isinstance(interface, Interface):
        return "interface"
    if isinstance(interface, Coupling):
        return "coupling"
    raise TypeError(f"{needs} a shroudnet.Interface or a shroudnet.Coupling, got "
                    f"{_shown(interface)}")


def _check_name(owner: str, field: str, name) -> None:
    """Raise TypeError unless ``name`` can name a node: hashable, and not None."""
    try:
        hash(name)
    except TypeError:
        pass
    else:
        if name is not None:
            return
    raise TypeError(f"{owner}: {field} must be a node's name (text, an integer or a tuple "
                    f"of them), got {_shown(name)}")


def _no_body(node) -> ValueError:
    return ValueError(f"node {node!r} has no attribute 'blade': every node needs one, a "
                      "Blade, a Substructure or None (fixed or prescribed); add nodes with "
                      "add_blade, add_fixed or add_prescribed")


def _names(owner: str, n: int, names) -> list[Hashable]:
    """n distinct node names: ``names``, or "blade1" … "bladen"."""
    if names is None:
        return [f"blade{i}" for i in range(1, n + 1)]
    if isinstance(names, str | bytes) or not isinstance(names, Iterable):
        raise TypeError(f"{owner}.names must be a sequence of {n} node names, got "
                        f"{_shown(names)}")
    names = list(names)
    if len(names) != n:
        raise ValueError(f"{owner} got {len(names)} names for {n} blades")
    try:
        distinct = set(names)
    except TypeError:
        distinct = None
    if distinct is None or None in distinct:
        for i, name in enumerate(names):
            _check_name(owner, f"names[{i}]", name)
    if len(distinct) != n:
        seen = set()
        twice = next(name for name in names if name in seen or seen.add(name))
        raise ValueError(f"{owner}.names must be distinct, got {twice!r} more than once")
    return names


def _bodies(owner: str, n: int, blade) -> list[Blade | Substructure] | None:
    """The n blades of a sequence ``blade``, or None where ``blade`` is one for all."""
    if isinstance(blade, Blade | Substructure):
        return None
    what = f"a Blade, a Substructure or a sequence of n = {n} of them"
    if isinstance(blade, str | bytes) or not isinstance(blade, Iterable):
        raise TypeError(f"{owner}.blade must be {what}, got {_shown(blade)}")
    blades = list(blade)
    if len(blades) != n:
        raise ValueError(f"{owner} got {len(blades)} blades for n = {n}")
    for i, one in enumerate(blades):
        if not isinstance(one, Blade | Substructure):
            raise TypeError(f"{owner}.blade[{i}] must be a Blade or a Substructure, got "
                            f"{_shown(one)}")
    return blades


def _sequence(name: str, value, kind, what: str) -> list:
    """``value`` as a list of ``kind``: one of them alone, or a sequence of them."""
    if isinstance(value, kind):
        return [value]
    if isinstance(value, str | bytes) or not isinstance(value, Iterable):
        raise TypeError(f"{name} must be {what} or a sequence of them, got {_shown(value)}")
    items = list(value)
    for i, item in enumerate(items):
        if not isinstance(item, kind):
            raise TypeError(f"{name}[{i}] must be {what}, got {_shown(item)}")
    return items


def _some(names) -> str:
    """The first ``SHOWN`` of ``names`` for a message, and how many there are in all."""
    shown = ", ".join(repr(name) for name in islice(names, SHOWN))
    return (f"{shown}, … ({len(names):,} in all)" if len(names) > SHOWN
            else shown or "none yet")


def _shown(value) -> str:
    """``value`` as a message shows it: its type and a repr cut to 80 characters."""
    text = repr(value)
    return f"{type(value).__name__} {text if len(text) <= 80 else text[:77] + '...'}"
