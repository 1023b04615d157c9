"""Lowering a scene with substructures to the arrays the engine works on.

Every moving node contributes coordinates: a ``Blade`` its displacement x (mass m); a
``Substructure`` its modal coordinates η at the scene's speed, q = Φ η with Φ the
mass-normalised modes of K(Ω) φ = ω² M φ, each scaled by its ``static_scale``, so that the
mass stays diagonal (``records.StructureScene``). Prescribed-motion nodes follow, one
coordinate each. Each point of a node becomes a row block of the coordinates
(r_p = Φ_p Φ η), and each edge the difference D = P_a − P_b of its two points' blocks:

- an interface gives the rows n·D and t·D (with its unit directions), or sin α D and
  cos α D with the gap Δ sin α (the angle form, between points of one component);
- a coupling adds k DᵀD to the stiffness and c DᵀD to the damping (isotropic in its
  points' components).

An edge that joins a patch of k point pairs gives k such differences, one per pair: an
interface's patch is k contacts (k rows of each kind, each with the interface's laws, its
own normal load, stick or slip and slider), a coupling's k springs. The engine sees
contacts, one row each (``BladeGroup.contacts``), never edges.

A node may carry a frame Q_i (``BladeGroup.add_blade``), the rotation of its points'
components into the group's frame; an edge's difference is taken in its left node's frame,
D = P_a − Q_aᵀ Q_b P_b, where the interface's directions are given. Identical sectors of a
disc, each turned by its own Q_s, thus give identical rows, their sector's coordinates
shifted.

The excitation Q_i(t) of node i acts on its coordinates along Φᵀ b_i (its load vector),
scaled by its signed ``excitation_scale``.

These coordinates are the engine's: every state that leaves it, or enters it, is in the
nodes' own degrees of freedom q (a ``Blade``'s x, a substructure's q of
``Substructure.matrices_at``; their velocities likewise), stacked node by node in
``Scene.blades`` order, and crosses through ``to_dofs`` and ``from_dofs`` alone. A scene of
``Blade``s has Φ = 1 everywhere: its coordinates are its dofs, and they cross unchanged.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from functools import cached_property

import numpy as np
import scipy.linalg

from .blade import Blade
from .group import BLADE_POINT

#: Below this |cos α| of a blade's interface, or max |t_e| of a substructure's, friction
#: has no tangential component: the interface never sticks.
NO_TANGENTIAL = 1e-12
#: Entries of a substructure's modal stiffness or damping below this fraction of its
#: largest are rounding (ΦᵀKΦ is diagonal in exact arithmetic), and are dropped.
ROUNDING = 1e-12


@dataclass(frozen=True, eq=False)
class Layout:
    """Where each moving node's coordinates sit in the state, and how its degrees of
    freedom and points follow from them.

    ``nodes`` by position; ``offsets[i]`` the first coordinate of node i and
    ``sizes[i]`` their number (as many as its degrees of freedom: q_i sits at the same
    place of the stacked dofs); ``bases[i]`` the n_i × n_i matrix Φ with q_i = Φ η_i (the
    node's own degrees of freedom from its coordinates) and ``inverses[i]`` Φ⁻¹;
    ``points[i]`` maps each point name to its d × n_i matrix Φ_p in the node's own degrees
    of freedom (r_p = Φ_p q_i; in the coordinates, Φ_p Φ)."""

    nodes: tuple
    offsets: tuple[int, ...]
    sizes: tuple[int, ...]
    bases: tuple[np.ndarray, ...]
    inverses: tuple[np.ndarray, ...]
    points: tuple[dict, ...]

    @property
    def n_coordinates(self) -> int:
        return int(sum(self.sizes))

    @cached_property
    def identity(self) -> bool:
        """Whether every node's coordinates are its degrees of freedom (Φ = 1: ``Blade``s),
        so that states cross ``to_dofs`` and ``from_dofs`` unchanged."""
        return all(basis.shape == (1, 1) and basis[0, 0] == 1.0 for basis in self.bases)

    def position(self, node) -> int:
        if node not in self.nodes:
            raise ValueError(f"unknown node {node!r}: give one of {list(self.nodes)}")
        return self.nodes.index(node)

    def coordinates(self, node) -> slice:
        """The state's columns of ``node``'s coordinates."""
        i = self.position(node)
        return slice(self.offsets[i], self.offsets[i] + self.sizes[i])

    def point(self, node, point: str | None = None) -> np.ndarray:
        """The d × n_i matrix Φ_p of ``node``'s point (its only one when None) in its own
        degrees of freedom."""
        points = self.points[self.position(node)]
        if point is None:
            if len(points) != 1:
                raise ValueError(f"node {node!r} has points {list(points)}: name one")
            return next(iter(points.values()))
        if point not in points:
            raise ValueError(f"node {node!r} has no point {point!r}; its points are "
                             f"{list(points)}")
        return points[point]


def law_arrays(interfaces) -> dict:
    """The ``SceneArrays`` fields of the interfaces' laws: ``normal_laws``,
    ``friction_laws``, ``opens``, ``static_mu`` (μ_s, 0 without friction) and
    ``regularisation`` (v_ε of a regularised law, else 0), ``tangential_stiffness`` (k_t
    of an elastic contact, inf where stick is rigid), and ``exact``: whether each has an
    exact friction law, which may stick."""
    frictions = tuple(i.friction for i in interfaces)
    return dict(
        tangential_stiffness=np.array([math.inf if i.tangential_stiffness is None
                                       else i.tangential_stiffness for i in interfaces]),
        normal_laws=tuple(i.normal for i in interfaces), friction_laws=frictions,
        opens=np.array([i.normal.opens for i in interfaces], dtype=bool),
        static_mu=np.array([0.0 if f is None else f.static_coefficient for f in frictions]),
        regularisation=np.array([0.0 if f is None else f.regularisation_velocity
                                 for f in frictions]),
        exact=np.array([f is not None and f.regularisation_velocity == 0.0
                        for f in frictions], dtype=bool))


def relative_frame(left, right, components: int) -> np.ndarray:
    """Q_aᵀ Q_b: a point of ``components`` of the right node's frame in the left node's
    (``left`` and ``right`` the nodes' frames, None for the group's; points of one
    component are not turned)."""
    identity = np.eye(components)
    turn = [identity if frame is None or frame.shape[0] != components else frame
            for frame in (left, right)]
    return turn[0].T @ turn[1]


def static_scale(squared) -> np.ndarray:
    """s_k = (ω_1/ω_k)² of each mode, ω_1 the lowest nonzero natural frequency (1 for a
    rigid-body mode): the coordinates ξ_k = η_k/s_k respond to a static load alike,
    whatever their frequency, so one absolute tolerance means the same for all of them."""
    squared = np.clip(np.asarray(squared, dtype=float), 0.0, None)
    moving = squared[squared > 0.0]
    if not len(moving):
        return np.ones(len(squared))
    return np.where(squared > 0.0, moving.min() / np.where(squared > 0.0, squared, 1.0), 1.0)


def _node_model(body, speed_rpm):
    """(mass vector, K̃, C̃, Φ, Φ⁻¹, points in its degrees of freedom, load in
    coordinates) of a node."""
    if isinstance(body, Blade):
        return (np.array([float(body.mass)]), np.array([[body.stiffness_at(speed_rpm)]]),
                np.array([[float(body.damping)]]), np.eye(1), np.eye(1),
                {BLADE_POINT: np.eye(1)}, np.ones(1))
    matrices = body.matrices_at(speed_rpm)
    squared, shapes = scipy.linalg.eigh(matrices.stiffness, matrices.mass)
    scale = static_scale(squared)
    # The modes are M-orthonormal, φᵀ M φ = I, so Φ⁻¹ = S⁻¹ φᵀ M: no solve with Φ, whose
    # columns' scales S may span many decades.
    inverse = (shapes.T @ matrices.mass) / scale[:, None]
    shapes = shapes * scale[None, :]

    def projected(matrix):
        """ΦᵀAΦ, symmetric, with the rounding left off the diagonal of a matrix the modes
        diagonalise set to 0 (below ``ROUNDING`` of its largest entry), so that the
        engine's products skip it."""
        value = shapes.T @ matrix @ shapes
        value = 0.5 * (value + value.T)
        value[np.abs(value) <= ROUNDING * np.abs(value).max(initial=0.0)] = 0.0
        return value

    points = {name: np.atleast_2d(body.point(name)) for name in body.points}
    return (scale**2, projected(matrices.stiffness), projected(matrices.damping),
            shapes, inverse, points, shapes.T @ body.load_vector)


def to_dofs(layout: Layout | None, values, axis: int = -1):
    """The nodes' own degrees of freedom q_i = Φ η_i of the engine's coordinates η in
    ``values``, along ``axis``: n entries (displacements, or velocities), or a whole state
    (x, ẋ, then the elastic contacts' stretches u [m], which are alike in both and pass
    as they are). With ``from_dofs``, the only door between the two: every state, tangent
    or record that leaves the engine goes out through it. A scene without a ``layout``, or
    whose every Φ is 1 (``Blade``s), gets ``values`` back as they are, at no cost."""
    return _by_node(layout, values, axis, "bases")


def from_dofs(layout: Layout | None, values, axis: int = -1):
    """The engine's coordinates η_i = Φ⁻¹ q_i of the nodes' degrees of freedom in
    ``values``: ``to_dofs`` the other way, for whatever enters the engine."""
    return _by_node(layout, values, axis, "inverses")


def _by_node(layout, values, axis, matrices):
    """``values`` with each node's block of the displacements (and of the velocities of a
    whole state) along ``axis`` multiplied by its matrix of ``layout.<matrices>``."""
    if layout is None or layout.identity:
        return values
    moved = np.moveaxis(np.asarray(values), axis, -1)
    n, length = layout.n_coordinates, moved.shape[-1]
    if length != n and length < 2 * n:
        raise ValueError(f"{length} values are neither the {n} coordinates nor a state "
                         f"of 2 × {n} and more")
    changed = moved.astype(np.result_type(moved, float), copy=True)
    for start in ((0,) if length == n else (0, n)):
        for offset, size, matrix in zip(layout.offsets, layout.sizes,
                                        getattr(layout, matrices)):
            block = slice(start + offset, start + offset + size)
            changed[..., block] = moved[..., block] @ matrix.T
    return np.moveaxis(changed, -1, axis)


def lower(scene) -> dict:
    """The ``SceneArrays`` fields of a scene with substructures (see the module)."""
    group = scene.group
    names = group.blades
    prescribed = group.prescribed
    models = [_node_model(group.blade(name), scene.speed_rpm) for name in names]
    sizes = [len(model[0]) for model in models]
    offsets = np.concatenate([[0], np.cumsum(sizes)]).astype(int)
    n_free = int(offsets[-1])
    n = n_free + len(prescribed)
    layout = Layout(tuple(names), tuple(int(o) for o in offsets[:-1]), tuple(sizes),
                    tuple(model[3] for model in models), tuple(model[4] for model in models),
                    tuple(model[5] for model in models))
    position = {name: i for i, name in enumerate(names)}
    prescribed_column = {name: n_free + p for p, (name, _) in enumerate(prescribed)}

    def block(node, point):
        """The rows of a point in all the coordinates (d × n); None at a fixed node."""
        if node in position:
            i = position[node]
            local = layout.point(node, point) @ layout.bases[i]
            rows = np.zeros((local.shape[0], n))
            rows[:, offsets[i]:offsets[i] + sizes[i]] = local
            return rows
        if node in prescribed_column:
            rows = np.zeros((1, n))
            rows[0, prescribed_column[node]] = 1.0
            return rows
        return None

    frames = {name: group.frame(name) for name in group.graph.nodes}

    def difference(left, right, points, what):
        """D = P_a − Q_aᵀ Q_b P_b: the relative displacement of the edge's points in its
        left node's frame (Q the nodes' frames, I where none, and for points of one
        component)."""
        a, b = block(left, points[0]), block(right, points[1])
        if a is not None and b is not None and a.shape[0] != b.shape[0]:
            raise ValueError(f"{what} ({left!r}, {right!r}) joins points of {a.shape[0]} and "
                             f"{b.shape[0]} components")
        if b is not None:
            b = relative_frame(frames[left], frames[right], b.shape[0]) @ b
        if a is None:
            return -b
        return a if b is None else a - b

    stiffness = np.zeros((n, n))
    damping = np.zeros((n, n))
    for i, model in enumerate(models):
        where = slice(offsets[i], offsets[i] + sizes[i])
        stiffness[where, where] = model[1]
        damping[where, where] = model[2]
    for (left, right, coupling), pairs in zip(group.couplings, group.point_pairs("coupling")):
        for points in pairs:
            d = difference(left, right, points, "coupling")
            stiffness += coupling.stiffness * d.T @ d
            damping += coupling.damping * d.T @ d

    interfaces = group.interfaces
    contacts = group.contacts
    m = len(contacts)
    normal_rows, tangent_rows = np.zeros((m, n)), np.zeros((m, n))
    second_tangent_rows = np.zeros((m, n))
    normal_gap, sin_angle, cos_angle = np.zeros(m), np.ones(m), np.ones(m)
    laws_of = [interfaces[contact.interface][2] for contact in contacts]
    for c, (contact, interface) in enumerate(zip(contacts, laws_of)):
        d = difference(contact.left, contact.right, (contact.left_point, contact.right_point),
                       "interface")
        if interface.normal_direction is None:
            angle = interface.angle
            sin_angle[c] = math.sin(angle)
            cos_angle[c] = 0.0 if angle == math.pi / 2 else math.cos(angle)
            normal_rows[c] = sin_angle[c] * d[0]
            tangent_rows[c] = cos_angle[c] * d[0]
            normal_gap[c] = interface.gap * sin_angle[c]
        else:
            normal_rows[c] = np.asarray(interface.normal_direction) @ d
            tangents = interface.tangent_directions
            tangent_rows[c] = np.asarray(tangents[0]) @ d
            if len(tangents) == 2:
                second_tangent_rows[c] = np.asarray(tangents[1]) @ d
            normal_gap[c] = interface.gap

    bodies = [group.blade(name) for name in names]
    load = np.concatenate([float(body.excitation_scale) * model[6]
                           for body, model in zip(bodies, models)])
    node_phases = scene.excitation.blade_phases(len(names)).astype(float)
    node_harmonics = scene.excitation.harmonic_phases(len(names)).astype(float)
    amplitudes = np.array(scene.excitation.amplitudes, dtype=float)
    laws = law_arrays(laws_of)
    exact = laws.pop("exact")
    tangential = np.abs(tangent_rows).max(axis=1, initial=0.0) > NO_TANGENTIAL
    none = np.zeros(0, dtype=np.int64)
    mass = np.concatenate([model[0] for model in models])
    return dict(
        mass=mass, damping=np.diag(damping)[:n_free].copy(),
        stiffness=np.diag(stiffness)[:n_free].copy(),
        left=np.full(m, -1, dtype=np.int64), right=np.full(m, -1, dtype=np.int64),
        gap=np.array([i.gap for i in laws_of], dtype=float),
        sin_angle=sin_angle, cos_angle=cos_angle, **laws, can_stick=exact & tangential,
        amplitudes=amplitudes,
        phases=np.repeat(node_phases, sizes),
        excitation_frequency=scene.excitation_circular_frequency,
        excitation_scale=load,
        harmonic_amplitudes=amplitudes[:, None] * load[None, :],
        harmonic_phases=np.repeat(node_harmonics, sizes, axis=1),
        coupling_left=none, coupling_right=none,
        coupling_stiffness=np.zeros(0), coupling_damping=np.zeros(0),
        motions=tuple(motion for _, motion in prescribed),
        normal_rows=normal_rows, tangent_rows=tangent_rows,
        second_tangent_rows=second_tangent_rows, normal_gap=normal_gap,
        structure_stiffness=stiffness, structure_damping=damping, layout=layout,
    )
