"""A blade group: blades are nodes, shroud interfaces and couplings are edges of a networkx
graph.

Every node carries the attribute ``blade`` (a ``Blade``, or None for a fixed node: the disc,
the casing, a damper platform, whose displacement is x ≡ 0, and for a prescribed-motion
node) and ``motion`` (the ``Motion`` of a prescribed-motion node, else None: a belt, a
shaker, whose displacement is a given function of time). Every edge carries either
``interface`` (an ``Interface``: a contact that opens, slips and sticks) or ``coupling`` (a
``Coupling``: a linear spring and damper that never does), ``left`` (the name of its left
node i, so that u = x_left − x_right; see ``shroudnet.interface``) and ``index`` (its
position in the interface or the coupling arrays: the order of its kind's ``connect``
calls).
"""

from __future__ import annotations

from collections.abc import Hashable, Sequence

import networkx as nx

from contact_laws import check_int

from .blade import Blade
from .coupling import Coupling
from .interface import Interface
from .motion import ConstantVelocity, HarmonicMotion, Motion, MotionTable


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

    def add_blade(self, name: Hashable, blade: Blade) -> BladeGroup:
        """Add a blade node called ``name``; returns the group so calls can be chained."""
        if not isinstance(blade, Blade):
            raise TypeError(f"add_blade({name!r}, ...) needs a shroudnet.Blade, got {blade!r}")
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

    def connect(self, left: Hashable, right: Hashable,
                interface: Interface | Coupling) -> BladeGroup:
        """Join ``left`` (node i) and ``right`` (node j) by ``interface``: an ``Interface``
        (a contact) or a ``Coupling`` (a spring and damper); returns the group."""
        if not isinstance(interface, Interface | Coupling):
            raise TypeError(f"connect({left!r}, {right!r}, ...) needs a shroudnet.Interface "
                            f"or a shroudnet.Coupling, got {interface!r}")
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
        self.graph.add_edge(left, right, left=left, index=index, **{kind: interface})
        return self

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

    def blade(self, name: Hashable) -> Blade:
        """The ``Blade`` at node ``name``."""
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
