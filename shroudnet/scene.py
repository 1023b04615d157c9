"""A scene: a blade group, its excitation and its rotating speed, validated at construction.

``Scene.arrays`` lowers the scene to the flat arrays the dynamics work on.
"""

from __future__ import annotations

import math
from collections.abc import Hashable
from dataclasses import dataclass
from functools import cached_property

import networkx as nx
import numpy as np

from contact_laws import FrictionLaw, NormalLaw, check_real

from .excitation import Excitation
from .group import BladeGroup

#: Below this |cos α| friction has no component along x: such an interface never sticks.
_NO_TANGENTIAL = 1e-12


@dataclass(frozen=True, eq=False)
class SceneArrays:
    """A scene as flat arrays: blades by position, interfaces by edge order.

    Blade arrays have length n_blades, interface arrays length n_interfaces. ``left`` and
    ``right`` hold blade positions, −1 for a fixed node (x ≡ 0).
    """

    mass: np.ndarray           # m_i [kg]
    damping: np.ndarray        # c_i [N·s/m]
    stiffness: np.ndarray      # k_i(Ω) [N/m]
    left: np.ndarray           # blade i of each interface (int64, −1 = fixed)
    right: np.ndarray          # blade j of each interface (int64, −1 = fixed)
    gap: np.ndarray            # Δ_e [m]
    sin_angle: np.ndarray      # sin α_e
    cos_angle: np.ndarray      # cos α_e (exactly 0 at α = π/2)
    normal_laws: tuple[NormalLaw, ...]
    friction_laws: tuple[FrictionLaw | None, ...]
    opens: np.ndarray          # False where the normal law holds the contact closed
    can_stick: np.ndarray      # exact friction with a component along x
    static_mu: np.ndarray      # μ_s = μ(0), 0 without friction
    regularisation: np.ndarray  # v_ε [m/s] of a regularised law, else 0
    amplitudes: np.ndarray     # (q0, q1, …, qn) [N]
    phases: np.ndarray         # φ_i [rad]
    excitation_frequency: float  # l Ω [rad/s]

    @property
    def n_blades(self) -> int:
        return len(self.mass)

    @property
    def n_interfaces(self) -> int:
        return len(self.gap)


@dataclass(frozen=True, kw_only=True, eq=False)
class Scene:
    """Everything a simulation needs: the group, its excitation and the rotating speed.

    The group is copied and frozen, so editing the original later does not change the scene.

    Parameters
    ----------
    group : BladeGroup
        At least one blade.
    excitation : Excitation
    speed_rpm : float
        Rotating speed Ω > 0 [rev/min].
    """

    group: BladeGroup
    excitation: Excitation
    speed_rpm: float

    def __post_init__(self):
        if not isinstance(self.group, BladeGroup):
            raise TypeError(f"Scene.group must be a BladeGroup, got {self.group!r}")
        if not isinstance(self.excitation, Excitation):
            raise TypeError(f"Scene.excitation must be an Excitation, got {self.excitation!r}")
        check_real("Scene", "speed_rpm", self.speed_rpm, low=0.0, low_open=True, unit="rpm")
        if not self.group.blades:
            raise ValueError("Scene.group has no blades: add at least one with add_blade")
        frozen = BladeGroup()
        frozen.graph = nx.freeze(self.group.graph.copy())
        object.__setattr__(self, "group", frozen)
        self.excitation.phases.phases(len(frozen.blades))  # raises if the count is wrong
        for name in frozen.blades:
            frozen.blade(name).stiffness_at(self.speed_rpm)  # raises outside a table's range

    @property
    def blades(self) -> list[Hashable]:
        """Blade names by position."""
        return self.group.blades

    @property
    def omega(self) -> float:
        """Ω [rad/s]."""
        return self.speed_rpm * 2.0 * math.pi / 60.0

    @property
    def excitation_period(self) -> float:
        """T_e = 2π/(l Ω) [s]."""
        return 2.0 * math.pi / (self.excitation.engine_order * self.omega)

    def blade_position(self, blade: Hashable | int) -> int:
        """The 0-based position of a blade given by name or by position."""
        names = self.blades
        if blade in names:
            return names.index(blade)
        if isinstance(blade, int | np.integer) and not isinstance(blade, bool) \
                and 0 <= blade < len(names):
            return int(blade)
        raise ValueError(f"unknown blade {blade!r}: give a name in {names} or a position "
                         f"0..{len(names) - 1}")

    @cached_property
    def arrays(self) -> SceneArrays:
        """The scene lowered to flat arrays (computed once)."""
        names = self.blades
        position = {name: i for i, name in enumerate(names)}
        blades = [self.group.blade(name) for name in names]
        edges = self.group.interfaces
        interfaces = [interface for _, _, interface in edges]
        angle = np.array([i.angle for i in interfaces], dtype=float)
        cos_angle = np.where(angle == math.pi / 2, 0.0, np.cos(angle))
        frictions = tuple(i.friction for i in interfaces)
        exact = np.array([f is not None and f.regularisation_velocity == 0.0 for f in frictions],
                         dtype=bool)
        return SceneArrays(
            mass=np.array([b.mass for b in blades], dtype=float),
            damping=np.array([b.damping for b in blades], dtype=float),
            stiffness=np.array([b.stiffness_at(self.speed_rpm) for b in blades], dtype=float),
            left=np.array([position.get(a, -1) for a, _, _ in edges], dtype=np.int64),
            right=np.array([position.get(b, -1) for _, b, _ in edges], dtype=np.int64),
            gap=np.array([i.gap for i in interfaces], dtype=float),
            sin_angle=np.sin(angle),
            cos_angle=cos_angle,
            normal_laws=tuple(i.normal for i in interfaces),
            friction_laws=frictions,
            opens=np.array([i.normal.opens for i in interfaces], dtype=bool),
            can_stick=exact & (np.abs(cos_angle) > _NO_TANGENTIAL),
            static_mu=np.array([0.0 if f is None else f.static_coefficient for f in frictions]),
            regularisation=np.array([0.0 if f is None else f.regularisation_velocity
                                     for f in frictions]),
            amplitudes=np.array(self.excitation.amplitudes, dtype=float),
            phases=self.excitation.phases.phases(len(names)).astype(float),
            excitation_frequency=self.excitation.engine_order * self.omega,
        )
