"""What harmonic balance needs of a scene: the linear structure, its excitation as a
Fourier series, and each contact in coordinates of its own.

The structure is M η̈ + C η̇ + K η = Q(t) − Gᵀ λ over the engine's coordinates η
(blades' displacements, or the scaled modal coordinates of substructures, couplings
included: ``SceneArrays``, ``model.lowering``), where it is solved. Each interface e
moves with the rows its laws read: its normal n_e·r, its tangent t₁·r and, on a face's
plane, t₂·r of the relative displacement r of its points (for blades, sin α (x_i − x_j)
and cos α (x_i − x_j)). Over the nodes' own degrees of freedom q (``model.lowering``:
q = Φ η node by node, Φ = 1 for blades) those rows span ρ_e ≤ 3 directions; an
orthonormal basis B_e of them (ρ_e × n, over q) gives the contact's **contact
coordinates** z_e = B_e q, and each row is then a vector of ℝ^ρ: n_e·r = ν·z_e,
t·r = τ·z_e. All contacts' coordinates stacked give z = B q = G η, G = B Φ (m = Σρ_e
rows), the unknowns of the condensed problem, and the contact pushes the structure by
−Gᵀλ with

    λ_e = N ν + f₁ τ₁ + f₂ τ₂                                              [N]

(the normal force along its normal, the friction force along its tangents:
``model.interface``'s −(N n + f t)). The basis is taken over q, not over η, so that z
means the same at every speed (Φ changes with K(Ω); B does not) and whatever scaling the
engine's coordinates have: an orbit's contact coefficients are a guess for another
scene of the same contacts. The rows cross between η and q through ``to_dofs`` and
``from_dofs`` alone (of the identity: Φ and Φ⁻¹).

What harmonic balance refuses, by name, before any work: prescribed-motion nodes
(their motion is an excitation of another kind), rigid stick (an exact friction law
without ``tangential_stiffness``: its force is a constraint, set-valued at zero slip,
which a Fourier series of the force cannot carry; give it an elastic stick or a
``Regularised`` law), and a structure that drifts without its contacts (K singular: no
static compliance at the contacts).
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from functools import cached_property

import numpy as np

from contact_laws import FrictionLaw, NormalLaw

from ...model.lowering import from_dofs, to_dofs
from ...model.scene import Scene

#: Singular values of an interface's rows below this fraction of its largest are
#: rounding: the rows span fewer directions.
RANK = 1e-12

#: How a contact's friction force is computed in time (``aft``).
NO_FRICTION, ELASTIC, REGULARISED = "none", "elastic", "regularised"


@dataclass(frozen=True, eq=False)
class Contact:
    """Interface ``index`` in contact coordinates: its ``columns`` of z, its normal ν
    (ρ), its tangents τ (2 × ρ; the second zero on a face of one direction), the normal
    gap g [m] (δ = ν·r − g), its laws, and how its friction acts (``friction_kind``):
    ``ELASTIC`` (a Jenkins element of stiffness ``tangential_stiffness`` k_t [N/m] and
    limit μ_s N), ``REGULARISED`` (f = μ(|v|) N tanh(v/v_ε) along τ₁), or none."""

    index: int
    columns: slice
    normal: np.ndarray
    tangents: np.ndarray
    gap: float
    normal_law: NormalLaw
    opens: bool
    friction_law: FrictionLaw | None
    friction_kind: str
    tangential_stiffness: float
    static_mu: float
    regularisation: float

    @property
    def size(self) -> int:
        """ρ_e, the contact's coordinates."""
        return self.columns.stop - self.columns.start

    @cached_property
    def normal_parameters(self) -> tuple[float, ...]:
        """The normal law's parameters, as its ``normal_force`` takes them."""
        return self.normal_law.parameters()

    @cached_property
    def friction_parameters(self) -> tuple[float, ...]:
        """The exact friction law's parameters, as its ``coefficient`` takes them."""
        return self.friction_law.exact.parameters()


@dataclass(frozen=True, eq=False)
class HarmonicModel:
    """A scene as harmonic balance sees it (module docstring), for orbits of ``periods``
    excitation periods, whose fundamental is ``frequency`` ω = l Ω / periods [rad/s].

    ``mass``, ``damping``, ``stiffness``: M, C, K (n × n) over the engine's coordinates
    η; ``rows``: G = B Φ (m × n), the contact coordinates z = G η = B q; the
    excitation as ``load_harmonics`` (the harmonic of ω each excitation harmonic is) with
    its complex amplitudes ``load`` (one row each, n columns: Q_k = a − i b, the
    constant for harmonic 0)."""

    scene: Scene
    periods: int
    frequency: float
    mass: np.ndarray
    damping: np.ndarray
    stiffness: np.ndarray
    rows: np.ndarray
    contacts: tuple[Contact, ...]
    load_harmonics: np.ndarray
    load: np.ndarray

    @property
    def n_coordinates(self) -> int:
        return self.mass.shape[0]

    @property
    def n_contact_coordinates(self) -> int:
        return self.rows.shape[0]

    @property
    def elastic(self) -> tuple[Contact, ...]:
        """The elastic contacts, in interface order (their stretches in that order)."""
        return tuple(c for c in self.contacts if c.friction_kind == ELASTIC)

    def load_coefficients(self, harmonics: int) -> np.ndarray:
        """Q as complex amplitudes by harmonic 0 … H of ω ((H+1) × n): the excitation's
        harmonics beyond H are left out."""
        amplitudes = np.zeros((harmonics + 1, self.n_coordinates), dtype=complex)
        for k, row in zip(self.load_harmonics, self.load):
            if k <= harmonics:
                amplitudes[k] += row
        return amplitudes


def interface_rows(arrays) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
    """(n_e, t₁, t₂ rows over the engine's free coordinates η, normal gap g_e) of every
    interface: a scene with substructures holds them; for blades, sin α (e_i − e_j),
    cos α (e_i − e_j), 0 and Δ sin α."""
    n = arrays.n_blades
    if arrays.is_structure:
        return (arrays.normal_rows[:, :n], arrays.tangent_rows[:, :n],
                arrays.second_tangent_rows[:, :n], arrays.normal_gap.copy())
    difference = np.zeros((arrays.n_interfaces, n))
    for e, (i, j) in enumerate(zip(arrays.left, arrays.right)):
        if 0 <= i < n:
            difference[e, i] += 1.0
        if 0 <= j < n:
            difference[e, j] -= 1.0
    return (arrays.sin_angle[:, None] * difference, arrays.cos_angle[:, None] * difference,
            np.zeros_like(difference), arrays.gap * arrays.sin_angle)


def friction_kind(arrays, e: int, owner: str, scene: Scene) -> str:
    """How interface e's friction acts (``Contact``); a ValueError naming ``owner`` for
    rigid stick."""
    law = arrays.friction_laws[e]
    if law is None:
        return NO_FRICTION
    if math.isfinite(arrays.tangential_stiffness[e]):
        return ELASTIC
    if arrays.regularisation[e] > 0.0:
        return REGULARISED
    if not arrays.can_stick[e]:
        return NO_FRICTION  # a face with no tangential motion carries no friction
    left, right, _ = scene.group.interfaces[e]
    raise ValueError(
        f"{owner}: interface {e} ({left!r}, {right!r}) sticks rigidly (the exact friction "
        f"law {law!r} without tangential_stiffness): its stuck force is a constraint, "
        "set-valued at zero slip, which harmonic balance does not carry (a dynamic "
        "Lagrangian formulation would). Give the interface tangential_stiffness= k_t "
        "(elastic stick, a Jenkins element) or a contact_laws.Regularised friction law, or "
        "solve the exact orbit with periodic_orbit")


def independent_directions(rows: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """(U_r, s_r, V_rᵀ): the singular value decomposition rows = U_r diag(s_r) V_rᵀ kept
    to the r singular values above ``RANK`` of the largest, the directions the rows
    span."""
    left, values, right = np.linalg.svd(rows, full_matrices=False)
    rank = int(np.sum(values > RANK * values.max(initial=0.0)))
    return left[:, :rank], values[:rank], right[:rank]


def harmonic_model(scene: Scene, periods: int, owner: str = "harmonic_balance"
                   ) -> HarmonicModel:
    """The ``HarmonicModel`` of ``scene`` for orbits of ``periods`` periods, or a
    ValueError naming ``owner`` for what harmonic balance refuses (module docstring)."""
    a = scene.arrays
    if a.n_prescribed:
        raise ValueError(f"{owner}: the scene has prescribed-motion nodes "
                         f"({', '.join(map(repr, (name for name, _ in scene.group.prescribed)))}); "
                         "harmonic balance condenses a structure forced by its excitation "
                         "alone: simulate the scene, or solve its orbit with periodic_orbit")
    n = a.n_blades
    stiffness = a.stiffness_matrix()
    if np.linalg.svd(stiffness, compute_uv=False)[-1] <= 1e-12 * np.abs(stiffness).max(
            initial=0.0):
        raise ValueError(f"{owner}: the structure without its contacts can drift (its "
                         "stiffness K is singular: a node held by its interfaces alone), so "
                         "it has no static compliance at the contacts to condense onto; "
                         "hold every node by a spring or a coupling")
    normal_rows, tangent_rows, second_rows, gaps = interface_rows(a)
    # η = Φ⁻¹ q, so rows r_η over η read q as r_η Φ⁻¹ (from_dofs of the identity is Φ⁻¹,
    # to_dofs's Φ)
    to_coordinates = from_dofs(a.layout, np.eye(n), axis=0)
    contacts, blocks, start = [], [], 0
    for e in range(a.n_interfaces):
        kind = friction_kind(a, e, owner, scene)
        rows = np.vstack([normal_rows[e], tangent_rows[e], second_rows[e]]) @ to_coordinates
        left, values, basis = independent_directions(rows)  # basis: B_e, over q
        rank = len(values)
        if rank == 0:
            continue  # an interface between fixed nodes: nothing moves it
        coordinates = left * values  # rows = coordinates @ basis
        friction = a.friction_laws[e]
        contacts.append(Contact(
            index=e, columns=slice(start, start + rank), normal=coordinates[0],
            tangents=coordinates[1:], gap=float(gaps[e]), normal_law=a.normal_laws[e],
            opens=bool(a.opens[e]), friction_law=friction, friction_kind=kind,
            tangential_stiffness=float(a.tangential_stiffness[e]),
            static_mu=float(a.static_mu[e]), regularisation=float(a.regularisation[e])))
        blocks.append(basis)
        start += rank
    rows = (np.vstack(blocks) if blocks else np.zeros((0, n))) @ to_dofs(
        a.layout, np.eye(n), axis=0)
    harmonics = np.arange(a.harmonic_amplitudes.shape[0]) * periods
    amplitudes = a.harmonic_amplitudes[:, :n]
    phases = a.harmonic_phases[:, :n]
    # A sin(nωt + φ) = A sin φ cos nωt + A cos φ sin nωt: X = A sin φ − i A cos φ
    load = amplitudes * (np.sin(phases) - 1j * np.cos(phases))
    load[0] = amplitudes[0]
    return HarmonicModel(
        scene=scene, periods=periods, frequency=a.excitation_frequency / periods,
        mass=np.diag(a.mass), damping=a.damping_matrix(), stiffness=stiffness, rows=rows,
        contacts=tuple(contacts), load_harmonics=harmonics, load=load)
