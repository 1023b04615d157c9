"""A blade group: blades are nodes, shroud interfaces and couplings are edges of a networkx
graph.

Every node carries the attribute ``blade`` (a ``Blade`` or a ``Substructure``, a node of
many degrees of freedom, or None for a fixed node: the disc,
the casing, a damper platform, whose displacement is x ≡ 0, and for a prescribed-motion
node) and ``motion`` (the ``Motion`` of a prescribed-motion node, else None: a belt, a
shaker, whose displacement is a given function of time). Every edge carries either
``interface`` (an ``Interface``: a contact that opens, slips and sticks) or ``coupling`` (a
``Coupling``: a linear spring and damper that never does), ``left`` (the name of its left
node i, so that u = x_left − x_right; see ``shroudnet.interface``) and ``index`` (its
position in the interface or the coupling arrays: the order of its kind's ``connect``
calls). An edge between points of nodes (``connect`` with (node, point) ends) also
carries ``left_point`` and ``right_point``, the point names at its left and right ends
(None at a fixed or prescribed node, or where the node's only point is meant).
"""

from __future__ import annotations

from collections.abc import Hashable, Sequence

import networkx as nx

from contact_laws import check_int

from .blade import Blade
from .coupling import Coupling
from .interface import Interface
from .motion import ConstantVelocity, HarmonicMotion, Motion, MotionTable
from .substructure import Substructure

#: An end of an edge: a node's name, or (node name, point name).
End = Hashable | tuple[Hashable, str]
#: The one point of a ``Blade``: its displacement x.
BLADE_POINT = "x"


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
        self.graph = nx.Graph()

    # -- building ---------------------------------------------------------------------------

    def add_blade(self, name: Hashable, blade: Blade | Substructure) -> BladeGroup:
        """Add a blade node called ``name``: a ``Blade`` (one mass) or a ``Substructure``
        (a structure of many degrees of freedom with named points); returns the group so
        calls can be chained."""
        if not isinstance(blade, Blade | Substructure):
            raise TypeError(f"add_blade({name!r}, ...) needs a shroudnet.Blade or "
                            f"shroudnet.Substructure, got {blade!r}")
        self._add_node(name, blade)
        return self

    def add_fixed(self, name: Hashable) -> BladeGroup:
        """Add a fixed node (x ≡ 0) called ``name``: the disc, the casing, a damper platform."""
        self._add_node(name, None)
        return self

    def add_prescribed(self, name: Hashable, motion: Motion) -> BladeGroup:
        """Add a node called ``name`` whose displacement follows ``motion`` (a
        ``ConstantVelocity``, ``HarmonicMotion`` or ``MotionTable``), whatever the forces on
        it: a moving belt, a shaker. It stands wherever a fixed node may."""
        if not isinstance(motion, ConstantVelocity | HarmonicMotion | MotionTable):
            raise TypeError(f"add_prescribed({name!r}, ...) needs a ConstantVelocity, "
                            f"HarmonicMotion or MotionTable, got {motion!r}")
        self._add_node(name, None, motion)
        return self

    def connect(self, left: End, right: End, interface: Interface | Coupling) -> BladeGroup:
        """Join ``left`` (node i) and ``right`` (node j) by ``interface``: an ``Interface``
        (a contact) or a ``Coupling`` (a spring and damper); returns the group.

        An end is a node's name, or a (node name, point name) tuple that joins a point of
        a ``Substructure``: ``connect(("blade1", "shroud"), ("blade2", "shroud"), shroud)``.
        A substructure's end names its point unless the substructure has only one; a
        ``Blade`` has the one point ``"x"``, its displacement.
        """
        if not isinstance(interface, Interface | Coupling):
            raise TypeError(f"connect({left!r}, {right!r}, ...) needs a shroudnet.Interface "
                            f"or a shroudnet.Coupling, got {interface!r}")
        where = f"connect({left!r}, {right!r})"
        (left, left_point), (right, right_point) = (self._end(left, interface, where),
                                                    self._end(right, interface, where))
        for end in (left, right):
            if end not in self.graph:
                raise ValueError(f"connect({left!r}, {right!r}): unknown node {end!r}; "
                                 f"add it first (nodes: {list(self.graph)})")
        if left == right:
            raise ValueError(f"connect({left!r}, {right!r}): an interface needs two nodes")
        if self.graph.has_edge(left, right):
            raise ValueError(f"connect({left!r}, {right!r}): these nodes are already connected")
        if self.graph.nodes[left]["blade"] is None and self.graph.nodes[right]["blade"] is None:
            raise ValueError(f"connect({left!r}, {right!r}): neither node is a blade (both are "
                             "fixed or prescribed), so nothing between them can move")
        kind = "interface" if isinstance(interface, Interface) else "coupling"
        index = sum(1 for *_, data in self.graph.edges(data=True) if kind in data)
        points = {} if left_point is None and right_point is None else {
            "left_point": left_point, "right_point": right_point}
        self.graph.add_edge(left, right, left=left, index=index, **{kind: interface},
                            **points)
        return self

    def _end(self, end, interface, where) -> tuple[Hashable, str | None]:
        """(node, point) of an edge's end, checked against the node and the interface."""
        node, point = (end if isinstance(end, tuple) and len(end) == 2
                       and isinstance(end[1], str) else (end, None))
        if node not in self.graph:
            raise ValueError(f"{where}: unknown node {node!r}; add it first (nodes: "
                             f"{list(self.graph)})")
        body = self.graph.nodes[node]["blade"]
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
        return node, point

    def _add_node(self, name: Hashable, blade: Blade | None, motion: Motion | None = None
                  ) -> None:
        if name in self.graph:
            raise ValueError(f"node {name!r} is already in the group")
        self.graph.add_node(name, blade=blade, motion=motion)

    # -- presets ----------------------------------------------------------------------------

    @classmethod
    def chain(cls, n: int, blade: Blade | Sequence[Blade], interface: Interface | Coupling,
              names: Sequence[Hashable] | None = None) -> BladeGroup:
        """A packet of ``n ≥ 1`` blades in a row, each joined to the next by ``interface``
        (or a ``Coupling``).

        The blades are named ``"blade1"`` … ``"bladen"`` as in the paper, unless ``names``
        gives n names; their positions are 0 … n−1 in that order. ``blade`` is one blade
        for all or a sequence of n (a mistuned packet).
        """
        group = cls()
        names = _names(n, names, "chain")
        for name, one in zip(names, _blades(len(names), blade, "chain")):
            group.add_blade(name, one)
        for left, right in zip(group.blades, group.blades[1:]):
            group.connect(left, right, interface)
        return group

    @classmethod
    def ring(cls, n: int, blade: Blade | Sequence[Blade], interface: Interface | Coupling,
             names: Sequence[Hashable] | None = None) -> BladeGroup:
        """A full shrouded disc of ``n ≥ 3`` blades: a ``chain`` whose last blade is joined
        to its first. Its ``sectors`` is n."""
        if check_int("BladeGroup.ring", "n", n) < 3:
            raise ValueError(f"ring needs n >= 3 blades, got {n!r}")
        group = cls.chain(n, blade, interface, names)
        group.connect(group.blades[-1], group.blades[0], interface)
        group.graph.graph["sectors"] = n
        return group

    @classmethod
    def bladed_disc(cls, sectors: int, disc: Blade, disc_coupling: Coupling,
                    blade: Sequence[Blade], blade_couplings: Sequence[Coupling],
                    shroud: Interface | None = None) -> BladeGroup:
        """A bladed disc of ``sectors ≥ 3`` identical sectors, each a disc node and a blade
        of one or more nodes, root to tip::

            ── disc_s ── disc_coupling ── disc_s+1 ──        (round the ring)
                 │ blade_couplings[0]
               blade_s_1 ── blade_couplings[1] ── blade_s_2 … (the tip: the last node)
                 tip_s ═══ shroud ═══ tip_s+1                 (interfaces, if given)

        ``blade`` gives the blade's nodes root to tip, typically with no spring to ground
        (stiffness 0: they are held by the couplings), ``blade_couplings`` the couplings
        disc–root and node to node (one per blade node). Nodes are named
        ``disc{s}`` and ``blade{s}_{k}`` (s from 1, k root = 1) and added sector by
        sector, so that ``sectors`` reads the positions (``linear_modes``).
        """
        sectors = check_int("BladeGroup.bladed_disc", "sectors", sectors, low=3)
        blade, blade_couplings = list(blade), list(blade_couplings)
        if not blade or len(blade_couplings) != len(blade):
            raise ValueError(f"bladed_disc needs one coupling per blade node (disc–root, "
                             f"then node to node): got {len(blade)} nodes and "
                             f"{len(blade_couplings)} couplings")
        group = cls()
        tips = []
        for s in range(1, sectors + 1):
            chain = [f"disc{s}"] + [f"blade{s}_{k}" for k in range(1, len(blade) + 1)]
            group.add_blade(chain[0], disc)
            for name, node in zip(chain[1:], blade):
                group.add_blade(name, node)
            for (inner, outer), coupling in zip(zip(chain, chain[1:]), blade_couplings):
                group.connect(inner, outer, coupling)
            tips.append(chain[-1])
        for s in range(sectors):
            group.connect(f"disc{s + 1}", f"disc{(s + 1) % sectors + 1}", disc_coupling)
            if shroud is not None:
                group.connect(tips[s], tips[(s + 1) % sectors], shroud)
        group.graph.graph["sectors"] = sectors
        return group

    # -- reading ----------------------------------------------------------------------------

    @property
    def blades(self) -> list[Hashable]:
        """Names of the moving blades, in the order they were added (their positions)."""
        return [n for n, blade in self.graph.nodes(data="blade") if blade is not None]

    @property
    def fixed(self) -> list[Hashable]:
        """Names of the fixed nodes."""
        return [n for n, data in self.graph.nodes(data=True)
                if data["blade"] is None and data.get("motion") is None]

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

    def edge_points(self, kind: str) -> list[tuple[str | None, str | None]]:
        """(left point, right point) of every interface (``kind`` "interface") or coupling
        ("coupling"), in the order of ``interfaces`` or ``couplings``."""
        edges = sorted((data for *_, data in self.graph.edges(data=True) if kind in data),
                       key=lambda data: data["index"])
        return [(data.get("left_point"), data.get("right_point")) for data in edges]

    @property
    def interfaces(self) -> list[tuple[Hashable, Hashable, Interface]]:
        """(left, right, interface) for every interface, in the order they were connected."""
        return self._edges("interface")

    @property
    def couplings(self) -> list[tuple[Hashable, Hashable, Coupling]]:
        """(left, right, coupling) for every coupling, in the order they were connected."""
        return self._edges("coupling")

    def _edges(self, kind):
        edges = sorted((edge for edge in self.graph.edges(data=True) if kind in edge[2]),
                       key=lambda edge: edge[2]["index"])
        return [(data["left"], b if data["left"] == a else a, data[kind])
                for a, b, data in edges]

    def blade(self, name: Hashable) -> Blade | Substructure:
        """The ``Blade`` or ``Substructure`` at node ``name``."""
        blade = self.graph.nodes[name]["blade"]
        if blade is None:
            kind = "prescribed" if self.graph.nodes[name].get("motion") else "fixed"
            raise ValueError(f"node {name!r} is {kind}, not a blade")
        return blade

    def __repr__(self) -> str:
        couplings = f", {len(self.couplings)} couplings" if self.couplings else ""
        prescribed = f", {len(self.prescribed)} prescribed" if self.prescribed else ""
        return (f"BladeGroup({len(self.blades)} blades, {len(self.fixed)} fixed nodes"
                f"{prescribed}, {len(self.interfaces)} interfaces{couplings})")


def _names(n, names, preset):
    n = check_int(f"BladeGroup.{preset}", "n", n, low=1)
    names = [f"blade{i}" for i in range(1, n + 1)] if names is None else list(names)
    if len(names) != n:
        raise ValueError(f"{preset} got {len(names)} names for {n} blades")
    return names


def _blades(n, blade, preset):
    blades = [blade] * n if isinstance(blade, Blade) else list(blade)
    if len(blades) != n:
        raise ValueError(f"{preset} got {len(blades)} blades for n = {n}")
    return blades
