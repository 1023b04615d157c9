r"""Couplings: bilateral linear springs with viscous dampers between two nodes of a group.

A coupling is structure, not contact: the disc between two blade roots, a blade between
its root and its tip, a lacing wire. With its left node i and right node j::

        node i      k, c       node j
      ┌────────┐ /\/\/\/\/\ ┌────────┐      x →
      └────────┘ ──[====]── └────────┘

it pushes node i by −F and node j by +F with F = k (x_i − x_j) + c (ẋ_i − ẋ_j), whatever
the sign of x_i − x_j: it never opens, slips or sticks, so it makes no events.
"""

from __future__ import annotations

from dataclasses import dataclass

from contact_laws import check_real


@dataclass(frozen=True, kw_only=True)
class Coupling:
    """A spring of stiffness k and a damper c in parallel between two nodes.

    Parameters
    ----------
    stiffness : float
        k ≥ 0 [N/m].
    damping : float
        c ≥ 0 [N·s/m].

    Examples
    --------
    >>> Coupling(stiffness=2e5, damping=1.0)
    Coupling(stiffness=200000.0, damping=1.0)
    """

    stiffness: float
    damping: float = 0.0

    def __post_init__(self):
        check_real("Coupling", "stiffness", self.stiffness, low=0.0, unit="N/m")
        check_real("Coupling", "damping", self.damping, low=0.0, unit="N·s/m")
        if self.stiffness == 0.0 and self.damping == 0.0:
            raise ValueError("Coupling needs stiffness > 0 [N/m] or damping > 0 [N·s/m]; "
                             "with neither it joins nothing")
