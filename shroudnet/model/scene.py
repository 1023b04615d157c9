"""A scene: a blade group, its excitation and its rotating speed, validated at construction.

``Scene.arrays`` lowers the scene to the flat arrays the dynamics work on.
"""

from __future__ import annotations

import dataclasses
import math
import warnings
from collections.abc import Hashable
from dataclasses import dataclass
from functools import cached_property

import networkx as nx
import numpy as np

from contact_laws import FrictionLaw, NormalLaw, check_int, check_real

from ..checked_records import check_record
from .excitation import EngineOrderWave, Excitation, ExplicitPhases
from .group import BLADE_POINT, BladeGroup, Contact
from .lowering import NO_TANGENTIAL, Layout, law_arrays, lower
from .motion import Motion
from .substructure import Substructure


@dataclass(frozen=True, eq=False)
class SceneArrays:
    """A scene as flat arrays: blades by position, interfaces by edge order.

    Blade arrays have length n_blades, interface arrays length n_interfaces: one entry per
    contact (``Scene.contacts``: an interface's, or each point pair's of a patch). ``left`` and
    ``right`` hold node positions: a blade's (0 … n_blades − 1), n_blades + p for the
    prescribed-motion node ``motions[p]``, −1 for a fixed node (x ≡ 0). With substructures
    (or elastic contacts) they are by the engine's coordinates (``model.lowering``), which
    never reach a user: states are given and returned in the nodes' own degrees of
    freedom (``model.lowering.to_dofs``).
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
    tangential_stiffness: np.ndarray  # k_t [N/m] of an elastic contact; inf where rigid
    amplitudes: np.ndarray     # (q0, q1, …, qn) [N]
    phases: np.ndarray         # φ_i [rad], the phases of the fundamental
    excitation_frequency: float  # ω = l Ω, or 2π f at a frequency of its own [rad/s]
    excitation_scale: np.ndarray   # s_i [-], the factor on Q(t) of each blade
    harmonic_amplitudes: np.ndarray  # s_i q_n [N]: row n (0 … n_harmonics), column i
    harmonic_phases: np.ndarray      # n φ_i [rad]: row n, column i (paper §2, see excitation)
    coupling_left: np.ndarray       # node i of each coupling (int64, −1 = fixed)
    coupling_right: np.ndarray      # node j of each coupling (int64, −1 = fixed)
    coupling_stiffness: np.ndarray  # k_c [N/m]
    coupling_damping: np.ndarray    # c_c [N·s/m]
    motions: tuple[Motion, ...] = ()  # the prescribed-motion nodes, by position − n_blades
    # A scene with substructures (``model.lowering``): its "blades" are coordinates, and these
    # hold what per-blade arrays cannot (None for a scene of blades):
    normal_rows: np.ndarray | None = None   # n_e over all coordinates (prescribed last)
    tangent_rows: np.ndarray | None = None  # t_e (t₁ of a face with two directions)
    second_tangent_rows: np.ndarray | None = None  # t₂ of a face's plane, else zeros
    normal_gap: np.ndarray | None = None    # δ_e = n_e·x − normal_gap_e [m]
    structure_stiffness: np.ndarray | None = None  # K̃, couplings included, all coordinates
    structure_damping: np.ndarray | None = None    # C̃
    layout: Layout | None = None            # where each node's coordinates and points are

    #: Fields that may hold NaN or ±inf (see ``checked_records``).
    NON_FINITE = ("tangential_stiffness",)

    def __post_init__(self):
        check_record(self)

    @property
    def is_structure(self) -> bool:
        """Whether the scene has substructures (its arrays are by coordinate)."""
        return self.layout is not None

    def slip_rows(self, direction: int = 1) -> np.ndarray:
        """T (interfaces × (coordinates + prescribed nodes)): each interface's tangential
        relative displacement u_t = T_e [x, x_p] [m], whose rate is its slip velocity:
        t_e·(r_a − r_b), or (x_i − x_j) cos α for blades (a fixed node has no column);
        along t₂ of the face's plane with ``direction`` 2 (zero rows where a face has one
        direction)."""
        if direction == 2:
            if self.second_tangent_rows is None:
                return np.zeros((self.n_interfaces, self.n_blades + self.n_prescribed))
            return self.second_tangent_rows.copy()
        if self.is_structure:
            return self.tangent_rows.copy()
        return self._blade_rows(self.cos_angle)

    def normal_rows_over_coordinates(self) -> np.ndarray:
        """N (interfaces × (coordinates + prescribed nodes)): each interface's penetration
        per unit coordinate, n_e over the coordinates with substructures, else sin α at
        its left blade and −sin α at its right one (a fixed node has no column)."""
        if self.is_structure:
            return self.normal_rows
        return self._blade_rows(self.sin_angle)

    def _blade_rows(self, weight: np.ndarray) -> np.ndarray:
        """Rows (interfaces × (blades + prescribed nodes)) of ``weight[e]`` at interface
        e's left blade and −``weight[e]`` at its right one (a fixed node has no column)."""
        rows = np.zeros((self.n_interfaces, self.n_blades + self.n_prescribed))
        for e, (i, j) in enumerate(zip(self.left, self.right)):
            if i >= 0:
                rows[e, i] += weight[e]
            if j >= 0:
                rows[e, j] -= weight[e]
        return rows

    @property
    def linear_phases(self) -> bool:
        """Whether the vector field is linear in the state between switches: substructures
        whose every law has ``constant_slopes`` (the stiffness, damping, stick
        constraints and excitation are so already), so that the tangent flow of a phase
        is the matrix exponential of its Jacobian. An elastic contact's slip turns its
        slider with the stretch's direction, which is not linear."""
        return self.is_structure and not self.n_stretches and all(
            type(law).constant_slopes for law in self.normal_laws) and all(
            law is None or type(law).constant_slopes for law in self.friction_laws)

    @property
    def elastic_interfaces(self) -> np.ndarray:
        """The positions of the elastic contacts (finite k_t), in interface order."""
        return np.flatnonzero(np.isfinite(self.tangential_stiffness))

    @property
    def n_stretches(self) -> int:
        """The elastic contacts' springs' stretches a state carries: two each, along t₁
        and t₂ (``Simulation.stretches``)."""
        return 2 * len(self.elastic_interfaces)

    @property
    def n_blades(self) -> int:
        return len(self.mass)

    @property
    def n_prescribed(self) -> int:
        return len(self.motions)

    def prescribed_state(self, t) -> tuple[np.ndarray, np.ndarray]:
        """(x_p, ẋ_p) of the prescribed-motion nodes at time ``t`` [s] (a scalar, or an
        array: one row per time)."""
        t = np.asarray(t, dtype=float)
        if not self.motions:
            return np.zeros(t.shape + (0,)), np.zeros(t.shape + (0,))
        return (np.stack([m.displacement_at(t) for m in self.motions], axis=-1),
                np.stack([m.velocity_at(t) for m in self.motions], axis=-1))

    @property
    def n_interfaces(self) -> int:
        return len(self.gap)

    @property
    def n_couplings(self) -> int:
        return len(self.coupling_stiffness)

    def stiffness_matrix(self) -> np.ndarray:
        """K [N/m] of M ẍ + C ẋ + K x: the blades' own springs k_i on the diagonal, plus
        each coupling's k_c on the rows and columns of its two nodes (a coupling to a fixed
        node adds to the diagonal only). Interfaces are not in it. With substructures, K̃
        of the free coordinates."""
        if self.is_structure:
            return self.structure_stiffness[:self.n_blades, :self.n_blades].copy()
        return edge_matrix(self.stiffness, self.coupling_left, self.coupling_right,
                              self.coupling_stiffness)

    def damping_matrix(self) -> np.ndarray:
        """C [N·s/m]: the blades' c_i and the couplings' c_c, as ``stiffness_matrix``."""
        if self.is_structure:
            return self.structure_damping[:self.n_blades, :self.n_blades].copy()
        return edge_matrix(self.damping, self.coupling_left, self.coupling_right,
                              self.coupling_damping)

    @property
    def static_deflection(self) -> float:
        """x_s = max_i |x_i| with K x = s Σ|q_n| [m]: the largest blade deflection under the
        whole excitation applied statically, interfaces open (the least-squares solution
        where a node is held by interfaces alone). Without couplings x_i = s_i Σ|q_n| / k_i."""
        load = np.abs(self.harmonic_amplitudes).sum(axis=0)
        if self.n_couplings == 0 and np.all(self.stiffness > 0.0):
            return float((load / self.stiffness).max())
        stiffness = self.stiffness_matrix()
        return float(np.abs(np.linalg.lstsq(stiffness, load, rcond=None)[0]).max())


def _check_label(label, what: str) -> None:
    """A blade or response is named by a hashable label or a position: refuse an array, a
    list or a float NaN, which no label equals, naming what was asked for."""
    if not isinstance(label, Hashable) or isinstance(label, bool) or (
            isinstance(label, float) and label != label):
        raise TypeError(f"{what} must be a name or a 0-based position (an int), got "
                        f"{type(label).__name__} {label!r:.80}")


def edge_matrix(own, left, right, values) -> np.ndarray:
    """diag(own) plus, for each edge (i, j) of value k (a spring [N/m] or a damper
    [N·s/m]), k on the diagonal at i and j and −k at (i, j) and (j, i); an end outside
    0 … len(own) − 1 (a fixed node, −1, or a prescribed one beyond the blades) has no row:
    its motion is no unknown of the matrix."""
    n = len(own)
    matrix = np.diag(np.asarray(own, dtype=float))
    for i, j, value in zip(left, right, values):
        for a, b in ((i, j), (j, i)):
            if 0 <= a < n:
                matrix[a, a] += value
                if 0 <= b < n:
                    matrix[a, b] -= value
    return matrix


@dataclass(frozen=True, kw_only=True, eq=False)
class Scene:
    """Everything a simulation needs: the group, its excitation and the rotating speed.

    The group is copied and frozen, so editing the original later does not change the scene.
    An ``EngineOrderWave`` phase pattern is replaced by the ``TravellingWave`` it stands for
    on this group (ND = l mod N), or, on a group of N sectors of several nodes each
    (``BladeGroup.bladed_disc``), by the phases 2π (l mod N) s/N of each node's sector s.
    Laws that are not built into ``contact_laws`` are probed at construction
    (``check_user_laws``): a sampled check of their contract, not a proof.

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
        n_blades = len(frozen.blades)
        pattern = self.excitation.phases
        # the pattern given, or the one a scene made these phases from for its own group
        pattern = getattr(pattern, "engine_order_wave", None) or pattern
        if isinstance(pattern, EngineOrderWave):
            sectors = frozen.graph.graph.get("sectors", n_blades)
            if pattern.blades_on_disc is None and _open_packet(frozen):
                warnings.warn(
                    f"EngineOrderWave() takes this packet's {n_blades} blades for a whole "
                    f"disc of {n_blades} (ND = l mod {n_blades}); a packet on a disc of N "
                    "blades needs EngineOrderWave(blades_on_disc=N)", stacklevel=3)
            wave = pattern.wave(sectors, self.excitation.engine_order)
            if sectors != n_blades:  # every node of a sector meets the pattern together
                wave = ExplicitPhases(tuple(np.repeat(wave.phases(sectors),
                                                      n_blades // sectors)),
                                      engine_order_wave=pattern)
            object.__setattr__(self, "excitation",
                               dataclasses.replace(self.excitation, phases=wave))
        self.excitation.blade_phases(n_blades)  # raises if the count or the ND is wrong
        for name in frozen.blades:  # raises outside a table's range
            body = frozen.blade(name)
            if isinstance(body, Substructure):
                body.matrices_at(self.speed_rpm)
            else:
                body.stiffness_at(self.speed_rpm)
        check_held(frozen, self.speed_rpm, self.excitation.amplitudes[0])
        check_user_laws(self)

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
        """T_e = 2π/(l Ω) [s], or 1/f at the excitation's own ``frequency`` f."""
        if self.excitation.frequency is not None:
            return 1.0 / self.excitation.frequency
        return 2.0 * math.pi / (self.excitation.engine_order * self.omega)

    @property
    def excitation_circular_frequency(self) -> float:
        """ω = l Ω, or 2π f at the excitation's own ``frequency`` f [rad/s]."""
        if self.excitation.frequency is not None:
            return 2.0 * math.pi * self.excitation.frequency
        return self.excitation.engine_order * self.omega

    def blade_position(self, blade: Hashable | int) -> int:
        """The 0-based position of a blade given by name or by position."""
        _check_label(blade, "blade")
        names = self.blades
        if blade in names:
            return names.index(blade)
        if isinstance(blade, int | np.integer) and not isinstance(blade, bool) \
                and 0 <= blade < len(names):
            return int(blade)
        raise ValueError(f"unknown blade {blade!r}: give a name in {names} or a position "
                         f"0..{len(names) - 1}")

    @cached_property
    def contacts(self) -> tuple[Contact, ...]:
        """Every contact, in the order of the interface arrays (``Scene.arrays``, the
        columns of ``Simulation.normal_force``, ``friction_force`` and ``modes``, the
        interfaces of events): an interface's one point pair, or each pair of a patch in
        turn (``BladeGroup.contacts``)."""
        return tuple(self.group.contacts)

    def contact_position(self, contact, owner: str = "Scene.contact_position") -> int:
        """The column of a contact among ``contacts``: ``contact`` an interface's position
        (0-based, in the order of ``BladeGroup.interfaces``) where the interface is one
        point pair, or (interface, k), the k-th pair (0-based) of its patch. Messages name
        ``owner``."""
        contacts = self.contacts
        count = len(self.group.interfaces)
        if count == 0:
            raise ValueError(f"{owner}: the scene has no interfaces")
        if isinstance(contact, tuple) and len(contact) == 2:
            interface, k = contact
        else:
            interface, k = contact, None
        interface = check_int(owner, "interface", interface, low=0, high=count - 1)
        first = self._first_contacts[interface]
        pairs = contacts[first].pairs
        if k is None:
            if pairs > 1:
                raise ValueError(f"{owner}: interface {interface} is a patch of {pairs} "
                                 f"contacts; name one as ({interface}, k), k in 0..{pairs - 1}")
            return first
        return first + check_int(owner, "contact", k, low=0, high=pairs - 1)

    @cached_property
    def _first_contacts(self) -> np.ndarray:
        """The column of each interface's first contact."""
        return np.array([c for c, contact in enumerate(self.contacts) if contact.contact == 0],
                        dtype=int)

    @cached_property
    def responses(self) -> tuple:
        """The scalar responses a scene reports peaks, Poincaré points and spectra of: its
        blades' displacements by name; with substructures, every component of every
        point of every node, as (node, point, component)."""
        a = self.arrays
        if not a.is_structure:
            return tuple(self.blades)
        return tuple((node, point, k) for node, points in zip(a.layout.nodes, a.layout.points)
                     for point, rows in points.items() for k in range(rows.shape[0]))

    @cached_property
    def response_matrix(self) -> np.ndarray:
        """R (n_responses × n_dofs): the ``responses`` are R q, q the nodes' own degrees
        of freedom stacked in ``blades`` order (a state's displacements, ``dof_matrix``)."""
        a = self.arrays
        if not a.is_structure:
            return np.eye(a.n_blades)
        return np.vstack([self.point_rows(node, point)[k] for node, point, k in self.responses])

    def response_position(self, target) -> int:
        """The position in ``responses`` of ``target``: a blade's name or position; with
        substructures a node (of one point of one component), (node, point) (a point of one
        component), (node, point, component), or a position."""
        _check_label(target, "blade (a response)")
        if not self.arrays.is_structure:
            return self.blade_position(target)
        labels = self.responses
        if isinstance(target, int | np.integer) and not isinstance(target, bool):
            if 0 <= target < len(labels):
                return int(target)
        else:
            found = [i for i, (node, point, k) in enumerate(labels)
                     if target in (node, (node, point), (node, point, k))]
            if len(found) == 1:
                return found[0]
            if found:
                raise ValueError(f"{target!r} has {len(found)} components; name one as "
                                 "(node, point, component)")
        raise ValueError(f"unknown response {target!r}: give (node, point, component) "
                         f"from {list(labels)[:6]}{' …' if len(labels) > 6 else ''}, "
                         f"or a position 0..{len(labels) - 1}")

    def response_of(self, values: np.ndarray, target) -> np.ndarray:
        """``target``'s response (``response_position``) from state rows ``values`` (the
        nodes' own degrees of freedom, or their velocities): a column of them for blades,
        R_target · values else."""
        i = self.response_position(target)
        if not self.arrays.is_structure:
            return values[..., i]
        return values @ self.response_matrix[i]

    def responses_of(self, values: np.ndarray) -> np.ndarray:
        """Every response from state rows ``values``: ``values`` itself for blades."""
        return values if not self.arrays.is_structure else values @ self.response_matrix.T

    def point_rows(self, node: Hashable, point: str | None = None) -> np.ndarray:
        """R (d × n_dofs): the displacement r = R q [m] of ``node``'s ``point`` from the
        state's displacements q (the nodes' own degrees of freedom stacked in ``blades``
        order: R holds the point's Φ_p in ``node``'s columns). A ``Blade``'s one point is
        its displacement (R = e_i); a substructure's point needs its name unless it has
        one point only."""
        a = self.arrays
        if not a.is_structure:
            rows = np.zeros((1, a.n_blades))
            if point not in (None, BLADE_POINT):
                raise ValueError(f"blade {node!r} has the one point {BLADE_POINT!r}, not "
                                 f"{point!r}")
            rows[0, self.blade_position(node)] = 1.0
            return rows
        local = a.layout.point(node, point)
        rows = np.zeros((local.shape[0], a.n_blades))
        rows[:, a.layout.coordinates(node)] = local
        return rows

    def dof_rows(self, node: Hashable) -> np.ndarray:
        """T (n_i × n_dofs): ``node``'s own degrees of freedom q_i = T q from the state's
        displacements q, which stack every node's in ``blades`` order (T picks ``node``'s;
        for a ``Blade``, its x)."""
        a = self.arrays
        if not a.is_structure:
            return self.point_rows(node)
        rows = np.zeros((a.layout.sizes[a.layout.position(node)], a.n_blades))
        rows[:, a.layout.coordinates(node)] = np.eye(rows.shape[0])
        return rows

    def dof_matrix(self) -> np.ndarray:
        """D: every node's own degrees of freedom, stacked in ``blades`` order, from the
        state's displacements (``dof_rows`` of each node): the identity, as every state a
        run takes and gives holds them already."""
        return np.vstack([self.dof_rows(name) for name in self.blades])

    @cached_property
    def arrays(self) -> SceneArrays:
        """The scene lowered to flat arrays (computed once): by blade, or with
        substructures or elastic contacts by coordinate (``model.lowering``)."""
        if self.group.has_substructures or any(
                interface.elastic for _, _, interface in self.group.interfaces):
            return SceneArrays(**lower(self))
        names = self.blades
        position = {name: i for i, name in enumerate(names)}
        prescribed = self.group.prescribed
        position.update((name, len(names) + p) for p, (name, _) in enumerate(prescribed))
        blades = [self.group.blade(name) for name in names]
        edges = self.group.interfaces
        couplings = self.group.couplings
        interfaces = [interface for _, _, interface in edges]
        angle = np.array([i.angle for i in interfaces], dtype=float)
        cos_angle = np.where(angle == math.pi / 2, 0.0, np.cos(angle))
        laws = law_arrays(interfaces)
        exact = laws.pop("exact")
        scale = np.array([b.excitation_scale for b in blades], dtype=float)
        return SceneArrays(
            mass=np.array([b.mass for b in blades], dtype=float),
            damping=np.array([b.damping for b in blades], dtype=float),
            stiffness=np.array([b.stiffness_at(self.speed_rpm) for b in blades], dtype=float),
            left=np.array([position.get(a, -1) for a, _, _ in edges], dtype=np.int64),
            right=np.array([position.get(b, -1) for _, b, _ in edges], dtype=np.int64),
            gap=np.array([i.gap for i in interfaces], dtype=float),
            sin_angle=np.sin(angle),
            cos_angle=cos_angle,
            **laws,
            can_stick=exact & (np.abs(cos_angle) > NO_TANGENTIAL),
            amplitudes=np.array(self.excitation.amplitudes, dtype=float),
            phases=self.excitation.blade_phases(len(names)).astype(float),
            excitation_frequency=self.excitation_circular_frequency,
            excitation_scale=scale,
            harmonic_amplitudes=np.array(self.excitation.amplitudes, dtype=float)[:, None]
            * scale[None, :],
            harmonic_phases=self.excitation.harmonic_phases(len(names)).astype(float),
            coupling_left=np.array([position.get(a, -1) for a, _, _ in couplings],
                                   dtype=np.int64),
            coupling_right=np.array([position.get(b, -1) for _, b, _ in couplings],
                                    dtype=np.int64),
            coupling_stiffness=np.array([c.stiffness for *_, c in couplings], dtype=float),
            coupling_damping=np.array([c.damping for *_, c in couplings], dtype=float),
            motions=tuple(motion for _, motion in prescribed),
        )


def _open_packet(group: BladeGroup) -> bool:
    """Whether the group is blades in a row that no edge closes into a ring: two or more
    blades whose edges among themselves form no cycle, and no ``sectors`` of its own."""
    blades = group.blades
    if len(blades) < 2 or "sectors" in group.graph.graph:
        return False
    return nx.is_forest(nx.Graph(group.graph.subgraph(blades)))


def check_held(group: BladeGroup, speed_rpm: float, mean_force: float = 0.0) -> None:
    """Raise unless every blade is held against rigid-body drift.

    A set of blades joined by interfaces and couplings is held when one of them has a
    spring to ground (k > 0 at ``speed_rpm``) or one of its edges reaches a fixed or a
    prescribed-motion node.
    Blades with k = 0 are allowed where something holds them; a set that nothing holds
    would drift away under a mean force, and has no static equilibrium.

    An interface whose contact opens holds one way only: it stops its left blade moving
    +x and its right one moving −x (``check_one_sided``), and ``mean_force`` [N], the
    excitation's q0, may press blades onto it.
    """
    moving = group.graph.subgraph(group.blades)
    for part in nx.connected_components(moving):
        held = any(_grounded(group.blade(name), speed_rpm) for name in part) or any(
            group.graph.nodes[other]["blade"] is None
            for name in part for other in group.graph.neighbors(name))
        if not held:
            names = sorted(map(str, part))
            raise ValueError(
                f"blades {names} float free: none has a spring to ground (stiffness > 0) and "
                "none is joined to a fixed node, so they can drift away together as a rigid "
                "body. Give one of them a stiffness, or connect one to a fixed node "
                "(add_fixed) by a Coupling or an Interface.")
    check_one_sided(group, speed_rpm, mean_force)


def check_one_sided(group: BladeGroup, speed_rpm: float, mean_force: float) -> None:
    """Raise where blades are held along x by contacts that open alone, all stopping them
    the same way, and their mean force does not press them onto those contacts: after the
    first impact they would drift away the other way for good.

    Blades joined by couplings, or by contacts that never open (``ConstantLoad``), move
    together as one part, held both ways if one of them has a spring to ground or one of
    those edges reaches a fixed or prescribed node. A contact that opens, at a contact
    angle α > 0, joining part P (its left end) to a node Q, stops P moving +x if Q cannot
    move +x (a fixed or prescribed node, or a part held that way); as its right end, −x.
    The directions spread from part to part until none is added. A part held one way
    only is allowed where its mean force s q0 (summed over its blades) presses it that
    way: a mass pressed onto a stop by a constant force, as a ball bounces on a table.
    Parts with substructures, and interfaces given by directions, are taken as held, as
    ``check_held`` takes them.
    """
    both, one_sided = _edges_by_hold(group)
    parts = _parts(group, both)
    held = {part: {1, -1} if _anchored(group, part, both, speed_rpm) else set()
            for part in dict.fromkeys(parts[name] for name in group.blades)}  # in order
    changed = True
    while changed:
        changed = False
        for left, right in one_sided:
            for end, other, direction in ((left, right, 1), (right, left, -1)):
                part = parts.get(end)
                if part is None or direction in held[part] or other in part:
                    continue
                if other not in parts or direction in held[parts[other]]:
                    held[part].add(direction)
                    changed = True
    for part, directions in held.items():
        bodies = [group.blade(name) for name in part]
        pressing = mean_force * sum(body.excitation_scale for body in bodies)
        if len(directions) == 2 or any(isinstance(b, Substructure) for b in bodies) or (
                directions and pressing * next(iter(directions)) > 0.0):
            continue
        names = sorted(map(str, part))
        crossing = [(left, right) for left, right in one_sided
                    if (left in part) != (right in part)]
        if directions:
            way = "+x" if 1 in directions else "−x"
            contacts = [(left, right) for left, right in crossing
                        if (left in part) == (1 in directions)]  # those that stop it
            raise ValueError(
                f"Scene.group: blades {names} are held only by contacts that open, "
                f"{contacts}, which stop them moving {way}: nothing holds them the other way "
                "(no spring to ground, no Coupling, no contact on their other side) and "
                f"their mean force, {pressing:g} N, does not press them onto those contacts, "
                "so they would drift away after the first impact. Give one of them a "
                "stiffness or a Coupling, a contact on its other side, or a mean force "
                "(Excitation.amplitudes q0) that presses it onto the contact.")
        raise ValueError(
            f"Scene.group: blades {names} are held along x by no spring, no Coupling and "
            f"no contact that can stop them (their contacts {crossing} are at a contact "
            "angle of 0, or push on blades that nothing holds either): they can drift "
            "away together. Give one of them a stiffness, or connect one to a fixed node "
            "by a Coupling or an Interface at an angle above 0.")


def _edges_by_hold(group: BladeGroup) -> tuple[list, list]:
    """(the edges that hold both ways: couplings, contacts that never open, and interfaces
    whose direction along x is not told here (given by directions, or at a substructure);
    the contacts that hold one way: those that open, at a contact angle α > 0). A contact
    that opens at α = 0 has no normal force along x and is in neither list."""
    both = [(left, right) for left, right, _ in group.couplings]
    one_sided = []
    for left, right, interface in group.interfaces:
        ends = [group.graph.nodes[node]["blade"] for node in (left, right)]
        if interface.angle is None or any(isinstance(b, Substructure) for b in ends) \
                or not type(interface.normal).opens:
            both.append((left, right))
        elif interface.angle > 0.0:
            one_sided.append((left, right))
    return both, one_sided


def _parts(group: BladeGroup, both: list) -> dict:
    """The part of each blade: the blades joined to it by edges that hold both ways."""
    joined = nx.Graph()
    joined.add_nodes_from(group.blades)
    joined.add_edges_from(both)
    parts = {}
    for part in nx.connected_components(joined.subgraph(group.blades)):
        parts.update(dict.fromkeys(part, frozenset(part)))
    return parts


def _anchored(group: BladeGroup, part: frozenset, both: list, speed_rpm: float) -> bool:
    """Whether a part is held both ways: by a spring to ground, or by an edge that holds
    both ways to a fixed or prescribed node."""
    return any(_grounded(group.blade(name), speed_rpm) for name in part) or any(
        group.graph.nodes[right if left in part else left]["blade"] is None
        for left, right in both if (left in part) != (right in part))


def _grounded(body, speed_rpm) -> bool:
    """Whether a node has a spring to ground: k > 0, or a substructure's K(Ω) with no
    rigid-body mode."""
    if isinstance(body, Substructure):
        return bool(body.frequencies_at(speed_rpm)[0] > 0.0)
    return body.stiffness_at(speed_rpm) > 0.0


# ---- the contract of user laws, probed --------------------------------------------------

#: Penetrations probed, as multiples of the scene's length scale (see ``check_user_laws``).
PROBE_PENETRATIONS = tuple(10.0**k for k in range(-6, 2))
#: Slip speeds probed [m/s], besides 0: one per decade.
PROBE_SLIP_SPEEDS = tuple(10.0**k for k in range(-6, 3))
#: Length scale [m] when the scene has neither gaps nor excitation to give one.
PROBE_FALLBACK_LENGTH = 1e-6
#: Relative slack on μ(v) ≤ μ_s, for a law that computes μ(0) by a different rounding.
PROBE_MU_SLACK = 1e-12


def _builtin(law) -> bool:
    return type(law).__module__.split(".")[0] == "contact_laws"


def check_user_laws(scene: Scene) -> None:
    """Probe every law not built into ``contact_laws`` at sample points; raise on a breach.

    Built-in laws hold their contract by their parameters' ranges; a law of one's own is
    only called, so its contract (``contact_laws.NormalLaw``, ``FrictionLaw``) is checked
    here by sampling, not proved. With the length scale L = max(|Δ_e|, x_s) (the largest
    gap, or the static deflection x_s under the whole excitation; 1 µm without either) and
    the rate scale r = L ω (ω = l Ω, or 2π f):

    - a normal law must return a finite N ≥ 0 at penetrations δ = L·10⁻⁶ … 10 L (one per
      decade) and rates δ̇ = 0, ±r, and a finite N at δ = −10⁻³ L (a trial state of a step
      that separates) if the contact can open;
    - a friction law must return a finite μ with 0 ≤ μ(v) ≤ μ_s at v = 0 and 10⁻⁶ … 10²
      m/s (one per decade), μ_s being its ``static_coefficient``, the stick limit the scene
      uses. A regularised law is probed through the exact law it smooths.

    Raises ``ValueError`` naming the interface, the law, the point and the value.
    """
    group = scene.group
    deflection = scene.arrays.static_deflection
    length = max([abs(interface.gap) for _, _, interface in group.interfaces] + [deflection])
    if not length > 0.0:
        length = PROBE_FALLBACK_LENGTH
    rate = length * scene.excitation_circular_frequency
    for e, (left, right, interface) in enumerate(group.interfaces):
        where = f"interface {e} ({left!r}, {right!r})"
        if not _builtin(interface.normal):
            _probe_normal(interface.normal, where, length, rate)
        if interface.friction is not None and not _builtin(interface.friction.exact):
            _probe_friction(interface.friction.exact, where)


def _evaluate(law, point, where, kind):
    """The law's value at ``point`` as a float, or a ValueError saying why it has none."""
    try:
        value = law(*point)
    except (ArithmeticError, TypeError, ValueError) as error:
        raise ValueError(f"{where}: {kind} {law!r} raised {type(error).__name__} "
                         f"({error}) at {_point(point)}") from error
    if isinstance(value, bool) or not isinstance(value, int | float | np.floating | np.integer):
        raise ValueError(f"{where}: {kind} {law!r} returned {type(value).__name__} "
                         f"{value!r} at {_point(point)}, not a real number (write max(δ, 0) "
                         "before a fractional power)")
    value = float(value)
    if not math.isfinite(value):
        raise ValueError(f"{where}: {kind} {law!r} returned {value} at {_point(point)}; it "
                         "must stay finite")
    return value


def _point(point) -> str:
    if len(point) == 2:
        return f"penetration δ = {point[0]:.3g} m, rate δ̇ = {point[1]:.3g} m/s"
    return f"slip speed |v| = {point[0]:.3g} m/s"


def _probe_normal(law, where, length, rate):
    kind = "normal law"
    for factor in PROBE_PENETRATIONS:
        for speed in (0.0, rate, -rate):
            point = (factor * length, speed)
            force = _evaluate(law, point, where, kind)
            if force < 0.0:
                raise ValueError(
                    f"{where}: {kind} {law!r} gives N = {force:.6g} N < 0 at {_point(point)}; "
                    "a closed contact only pushes, so N(δ, δ̇) must be ≥ 0 for δ > 0 (clamp "
                    "it, e.g. max(…, 0.0)). Checked by sampling δ over L·1e-6 … 10 L with "
                    f"L = {length:.3g} m and δ̇ = 0, ±{rate:.3g} m/s.")
    if type(law).opens:
        for speed in (0.0, rate, -rate):
            _evaluate(law, (-1e-3 * length, speed), where, kind)


def _probe_friction(law, where):
    kind = "friction law"
    try:
        static = float(law.static_coefficient)
    except (ArithmeticError, TypeError, ValueError) as error:
        raise ValueError(f"{where}: {kind} {law!r} has no static coefficient μ_s: "
                         f"{type(error).__name__} ({error})") from error
    if not (math.isfinite(static) and static >= 0.0):
        raise ValueError(f"{where}: {kind} {law!r} has a static coefficient μ_s = {static:g}; "
                         "it must be finite and ≥ 0")
    speeds = (0.0,) + PROBE_SLIP_SPEEDS
    values = [_evaluate(law, (speed,), where, kind) for speed in speeds]
    for speed, mu in zip(speeds, values):
        if mu < 0.0:
            raise ValueError(f"{where}: {kind} {law!r} gives μ = {mu:.10g} < 0 at "
                             f"{_point((speed,))}; μ(v) must be ≥ 0")
    highest = int(np.argmax(values))
    if values[highest] > static * (1.0 + PROBE_MU_SLACK):
        raise ValueError(
            f"{where}: {kind} {law!r} gives μ = {values[highest]:.10g} at "
            f"{_point((speeds[highest],))}, above its static coefficient μ_s = μ(0) = "
            f"{static:.10g}, the stick limit: a slipping interface would carry more friction "
            "than a stuck one can hold. μ(v) must stay within [0, μ_s]; checked by sampling "
            "v = 0 and 1e-6 … 1e2 m/s.")
