"""A blade group: blades are nodes, shroud interfaces are edges of a networkx graph.

Every node carries the attribute ``blade`` (a ``Blade``, or None for a fixed node: the disc,
the casing, a damper platform, whose displacement is x ≡ 0). Every edge carries
``interface`` (an ``Interface``), ``left`` (the name of its left blade i, so that
u = x_left − x_right; see ``shroudnet.interface``) and ``index`` (its position in the
interface arrays: the order of ``connect`` calls).
"""

from __future__ import annotations

from collections.abc import Hashable, Sequence

import networkx as nx

from contact_laws import check_int

from .blade import Blade
from .interface import Interface


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

    def connect(self, left: Hashable, right: Hashable, interface: Interface) -> BladeGroup:
        """Add the interface between ``left`` (blade i) and ``right`` (blade j)."""
        if not isinstance(interface, Interface):
            raise TypeError(f"connect({left!r}, {right!r}, ...) needs a shroudnet.Interface, "
                            f"got {interface!r}")
        for end in (left, right):
            if end not in self.graph:
                raise ValueError(f"connect({left!r}, {right!r}): unknown node {end!r}; "
                                 f"add it first (nodes: {list(self.graph)})")
        if left == right:
            raise ValueError(f"connect({left!r}, {right!r}): an interface needs two nodes")
        if self.graph.has_edge(left, right):
            raise ValueError(f"connect({left!r}, {right!r}): these nodes are already connected")
        if self.graph.nodes[left]["blade"] is None and self.graph.nodes[right]["blade"] is None:
            raise ValueError(f"connect({left!r}, {right!r}): both nodes are fixed")
        self.graph.add_edge(left, right, interface=interface, left=left,
                            index=self.graph.number_of_edges())
        return self

    def _add_node(self, name: Hashable, blade: Blade | None) -> None:
        if name in self.graph:
            raise ValueError(f"node {name!r} is already in the group")
        self.graph.add_node(name, blade=blade)

    # -- presets ----------------------------------------------------------------------------

    @classmethod
    def chain(cls, n: int, blade: Blade | Sequence[Blade], interface: Interface,
              names: Sequence[Hashable] | None = None) -> BladeGroup:
        """A packet of ``n ≥ 1`` blades in a row, each joined to the next by ``interface``.

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
    def ring(cls, n: int, blade: Blade | Sequence[Blade], interface: Interface,
             names: Sequence[Hashable] | None = None) -> BladeGroup:
        """A full shrouded disc of ``n ≥ 3`` blades: a ``chain`` whose last blade is joined
        to its first."""
        if check_int("BladeGroup.ring", "n", n) < 3:
            raise ValueError(f"ring needs n >= 3 blades, got {n!r}")
        group = cls.chain(n, blade, interface, names)
        group.connect(group.blades[-1], group.blades[0], interface)
        return group

    # -- reading ----------------------------------------------------------------------------

    @property
    def blades(self) -> list[Hashable]:
        """Names of the moving blades, in the order they were added (their positions)."""
        return [n for n, blade in self.graph.nodes(data="blade") if blade is not None]

    @property
    def fixed(self) -> list[Hashable]:
        """Names of the fixed nodes."""
        return [n for n, blade in self.graph.nodes(data="blade") if blade is None]

    @property
    def interfaces(self) -> list[tuple[Hashable, Hashable, Interface]]:
        """(left, right, interface) for every edge, in the order they were connected."""
        edges = sorted(self.graph.edges(data=True), key=lambda edge: edge[2]["index"])
        return [(data["left"], b if data["left"] == a else a, data["interface"])
                for a, b, data in edges]

    def blade(self, name: Hashable) -> Blade:
        """The ``Blade`` at node ``name``."""
        blade = self.graph.nodes[name]["blade"]
        if blade is None:
            raise ValueError(f"node {name!r} is fixed, not a blade")
        return blade

    def __repr__(self) -> str:
        return (f"BladeGroup({len(self.blades)} blades, {len(self.fixed)} fixed nodes, "
                f"{self.graph.number_of_edges()} interfaces)")


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
