"""The group's linear modes, in three limits of its interfaces, and by nodal diameter.

Before any nonlinear run a designer reads the natural frequencies of the group with its
interfaces in the limits the friction and contact move between:

- ``contacts="open"``: every interface carries nothing; the blades' own springs and the
  couplings hold the group (``SceneArrays.stiffness_matrix``). The lower bound.
- ``contacts="stuck"``: every interface that can stick (an exact friction law and a face
  with a component along x, α < π/2) is stuck, as the loop's stick clusters are: its two
  nodes move as one body, and a node stuck to a fixed node does not move. The normal
  springs are those of the group at rest: an interface closed at rest (penetration
  −Δ sin α > 0, or a law that never opens) pushes by its normal law, a spring of its
  contact stiffness ∂N/∂δ sin²α along x (the law's gradient at the rest penetration)
  where it cannot stick and slides; an interface open at rest (a gap, Δ > 0) adds no
  normal spring, stuck or not. An elastic contact (``Interface.tangential_stiffness``
  k_t) is not a constraint: stuck, it is the spring k_t cos²α along x beside its normal
  spring (if closed at rest); rigid stick is only where k_t is None. So "stuck" is the
  group at rest with its friction locked, not an upper bound: with gaps it leaves the
  normal springs out.
- ``contacts="closed"``: every interface closed, and stuck where it can stick: "stuck"
  with the normal spring of every interface, open at rest or not. The upper bound of the
  frequencies: the k-th closed frequency is at least the k-th stuck one, and that at least
  the k-th open one (a spring ∂N/∂δ ≥ 0 or a constraint added never lowers the k-th
  eigenvalue: Courant–Fischer).
  An interface closed at rest is linearised at its rest penetration, as in "stuck"; one
  open at rest at first touch, δ → 0⁺, read as the law's gradient at ``FIRST_TOUCH``,
  which must agree with that at ``DEEPER`` to ``TOUCH_AGREEMENT``: a law linear where it
  closes (``LinearSpring``, ``KelvinVoigt`` with its dashpot, ``Hertz`` and
  ``HuntCrossley`` of exponent 1) gives its stiffness k; ``Hertz`` and ``HuntCrossley``
  of exponent n > 1, whose ∂N/∂δ = k n δ^(n−1) is 0 at first touch and grows without
  bound, have no linear closed limit there and are refused (preload the contact, Δ < 0,
  to linearise it at its rest penetration). ``ConstantLoad`` never opens and its force
  does not depend on δ: it adds no normal spring, its closed limit is its stuck one.
  Between one-mass blades a rigidly stuck interface's nodes move as one body, so its
  normal spring would change nothing and is not read (nor its law refused).

The modes solve K φ = ω² M φ (``scipy.linalg.eigh``), mass-normalised (φᵀ M φ = 1). A
prescribed-motion node is held where it is, as a fixed node: these are the modes about
its path.

A ring of N identical sectors (``BladeGroup.ring``, ``BladeGroup.bladed_disc``, or
``sectors=N`` for a group whose nodes were added sector by sector) has modes that are
travelling or standing waves round the ring: mode φ has nodal diameter ND when its
sectors' amplitudes vary round the ring as cos(2π ND s/N + θ), that is when it lies in
the cyclic subspace of the harmonics k = ND and N − ND of the discrete Fourier transform
over the sectors. Each eigenspace (eigenvalues ω² equal to ``EIGENSPACE``, relative) is
projected onto these subspaces and its basis turned so that each mode lies in one of
them (``cyclic_eigenspaces``): a tuned ring's eigenspace is invariant under the sector
shift, so a degenerate family (N uncoupled blades: N modes at one frequency) gets every
diameter exactly once, ND = 0 and N/2 one mode, the others two. A mode is labelled by
the diameter holding most of its square, so that a mistuned ring's modes are labelled by
their dominant diameter. An engine order l excites the diameter
ND = min(l mod N, N − l mod N) only (``excited_diameter``).

A group with substructures (DESIGN §7) is solved in the engine's coordinates
(``SceneArrays.layout``: each node's modal coordinates, mass diag(m̃)), with the same
limits written in the rows of its interfaces (n_e, t_e; δ_e = n_e·x − Δ_e, v_e = t_e·ẋ):

- ``"open"``: K̃ x = ω² M̃ x, K̃ the nodes' stiffness with the couplings
  (``SceneArrays.stiffness_matrix``), the interfaces carrying nothing;
- ``"stuck"``: every interface that can stick (an exact friction law, t_e ≠ 0) holds
  t_e·x = 0, a constraint, while its normal force still acts along n_e; so every interface
  closed at rest (−Δ_e > 0, or a law that never opens), stuck or sliding, adds the spring
  ∂N/∂δ n_e n_eᵀ, and one open at rest adds nothing: stuck with a gap, its two points are
  held along the face and free across it. The constraints G x = 0 (one row t_e per stuck
  interface) are eliminated by an orthonormal basis T of the null space of G (redundant
  rows, as round an all-stuck ring, are dropped by its rank), and Tᵀ K T z = ω² Tᵀ M T z
  is solved. For one-mass blades (t_e ∥ n_e) this is the stick clusters above. An elastic
  contact adds, in place of its constraint, the spring k_t (t₁t₁ᵀ + t₂t₂ᵀ) over its
  tangent directions;
- ``"closed"``: as "stuck", with the spring ∂N/∂δ n_e n_eᵀ of every interface (its law
  read as above).

``shapes`` are then taken to the nodes' own degrees of freedom q (``model.lowering.to_dofs``;
mass-normalised with the nodes' mass matrices, the kinetic energy being the physical one);
``LinearModes.node_shapes`` and ``point_shapes`` read them node by node or as a point's
displacement r_p. The nodal diameter of a ring of substructures
is read, as for blades, from the DFT over the sectors of each node's own degrees of freedom
q_i (so that sectors whose coordinates differ, as mistuned ones do, are compared in the same
physical terms).
"""

from __future__ import annotations

from collections.abc import Hashable, Sequence
from dataclasses import dataclass, replace

import numpy as np
import scipy.linalg
from scipy.optimize import brentq

from contact_laws import check_array, check_instance, check_int, check_sequence

from ..checked_records import check_record
from ..engine.clusters import cluster_labels
from ..model.lowering import to_dofs
from ..model.scene import Scene, edge_matrix

CONTACTS = ("open", "stuck", "closed")

#: Where the "closed" limit reads a contact open at rest (module docstring): the law's
#: gradient at a penetration of ``FIRST_TOUCH`` [m], which must agree with that at
#: ``DEEPER`` [m] to ``TOUCH_AGREEMENT`` (relative) for the law to be linear where it
#: closes. A nanometre is below any gap or amplitude of a shroud and above the central
#: differences' step (6e-12 m) of a law without an analytic gradient, so that they do
#: not straddle δ = 0.
FIRST_TOUCH = 1e-9
DEEPER = 1e-8
TOUCH_AGREEMENT = 1e-3

#: Eigenvalues ω² that belong to one eigenspace: consecutive ones within ``EIGENSPACE`` of
#: the larger (relative), or within ``EIGENSPACE_ROUNDING`` of the largest |ω²| (the
#: rounding of a generalised symmetric eigensolver, which also gathers the rigid-body
#: modes, ω² = 0 to within it).
EIGENSPACE = 1e-8
EIGENSPACE_ROUNDING = 1e3 * np.finfo(float).eps


@dataclass(frozen=True, eq=False)
class LinearModes:
    """Natural frequencies and mode shapes of a scene's linearised group.

    ``frequencies`` [Hz] ascending; ``shapes`` one mass-normalised column per mode, rows
    by blade position [1/√kg] (with substructures, by every node's own degrees of freedom
    q, stacked in ``Scene.blades`` order as a state's displacements are: read them by
    node with ``node_shapes`` or ``point_shapes``); ``nodal_diameters`` the ND of each
    mode for a group of ``sectors`` identical sectors, else None; ``scene`` the scene they
    are of.
    """

    frequencies: np.ndarray
    shapes: np.ndarray
    nodal_diameters: np.ndarray | None
    contacts: str
    sectors: int | None
    speed_rpm: float
    scene: Scene | None = None

    def __post_init__(self):
        check_record(self)

    def node_shapes(self, node: Hashable) -> np.ndarray:
        """The mode shapes in ``node``'s own degrees of freedom q_i (n_i × modes; column k
        is mode k, mass-normalised with the whole group) [1/√kg for displacements]: for a
        ``Blade``, its displacement x (1 × modes); for a substructure, its q (of
        ``Substructure.matrices_at``), so that ``Substructure.expand`` takes a reduction's
        shape back to its full model."""
        return self._scene("node_shapes").dof_rows(node) @ self.shapes

    def point_shapes(self, node: Hashable, point: str | None = None) -> np.ndarray:
        """The displacement r_p = Φ_p q_i of ``node``'s ``point`` in each mode (d × modes)
        [m per √kg]; a ``Blade``'s one point is its x, and a substructure with one point
        needs no name."""
        return self._scene("point_shapes").point_rows(node, point) @ self.shapes

    def _scene(self, method: str) -> Scene:
        if self.scene is None:
            raise ValueError(f"LinearModes.{method} needs the scene: these modes were made "
                             "without one (linear_modes gives it)")
        return self.scene

    def of_diameter(self, nodal_diameter: int) -> np.ndarray:
        """The frequencies [Hz] of the modes of one nodal diameter, ascending."""
        if self.nodal_diameters is None:
            raise ValueError("these modes are not sorted by nodal diameter: the group has "
                             "no sectors (give linear_modes(..., sectors=N))")
        nodal_diameter = check_int("LinearModes.of_diameter", "nodal_diameter", nodal_diameter,
                                   low=0, high=self.sectors // 2, high_label="N // 2")
        return self.frequencies[self.nodal_diameters == nodal_diameter]

    def families(self) -> np.ndarray:
        """Frequencies [Hz] as a table: row = nodal diameter 0 … N//2, column = family
        (the k-th lowest mode of that diameter); NaN where a diameter has fewer modes.

        A diameter 0 < ND < N/2 has its modes in pairs (two standing waves, or a forward
        and a backward travelling one, of one frequency when tuned): each pair is one
        entry, at its mean frequency.
        """
        if not self.sectors:
            raise ValueError("these modes are not sorted by nodal diameter: the group has "
                             "no sectors (give linear_modes(..., sectors=N))")
        rows = []
        for nd in range(self.sectors // 2 + 1):
            row = self.of_diameter(nd)
            if 0 < nd < self.sectors / 2:
                row = row[: len(row) // 2 * 2].reshape(-1, 2).mean(axis=1)
            rows.append(row)
        width = max((len(r) for r in rows), default=0)
        table = np.full((len(rows), width), np.nan)
        for nd, row in enumerate(rows):
            table[nd, :len(row)] = row
        return table


def linear_modes(scene: Scene, contacts: str = "open", *,
                 sectors: int | None = None) -> LinearModes:
    """The natural frequencies and mode shapes of ``scene``'s group at its speed.

    Parameters
    ----------
    scene : Scene
    contacts : "open", "stuck" or "closed"
        The limit of the interfaces (module docstring): "closed" is the upper bound,
        "stuck" the group at rest with its friction locked.
    sectors : int, optional
        N, for a ring of N identical sectors whose nodes are numbered sector by sector
        (the node at position p in sector p // (nodes/N)); taken from the group where it
        was built as a ring or a bladed disc. With substructures, every sector must have
        as many degrees of freedom. The modes of each eigenspace are then turned so that
        each lies in one nodal diameter's cyclic subspace (module docstring).

    Raises
    ------
    ValueError
        Bad arguments; "stuck" or "closed" where nothing can move; "closed" where an
        interface open at rest has a law without a linear closed limit (module
        docstring).

    Examples
    --------
    >>> from shroudnet import (AntiPhase, Blade, BladeGroup, Coupling, Excitation, Scene,
    ...                        linear_modes)
    >>> ring = BladeGroup.ring(6, Blade(mass=0.1, damping=0.0, stiffness=1e5),
    ...                        Coupling(stiffness=2e4))
    >>> scene = Scene(group=ring, excitation=Excitation(engine_order=1,
    ...               amplitudes=(0.0, 1.0), phases=AntiPhase()), speed_rpm=6000.0)
    >>> modes = linear_modes(scene)
    >>> [int(nd) for nd in modes.nodal_diameters]
    [0, 1, 1, 2, 2, 3]
    """
    check_instance("linear_modes", "scene", scene, Scene, expected="a shroudnet.Scene")
    if not isinstance(contacts, str) or contacts not in CONTACTS:
        kind = ValueError if isinstance(contacts, str) else TypeError
        raise kind(f"linear_modes: contacts must be one of {CONTACTS}, got {contacts!r}")
    a = scene.arrays
    if sectors is None:
        sectors = scene.group.graph.graph.get("sectors")
    if sectors is not None:
        sectors = check_int("linear_modes", "sectors", sectors, low=1)
        if len(scene.blades) % sectors:
            raise ValueError(f"linear_modes: sectors = {sectors} does not divide the "
                             f"{len(scene.blades)} blades into equal sectors")
    limit = interface_limit(scene, contacts, "linear_modes")
    basis, stiffness = limit.basis, limit.stiffness
    mass = basis.T @ np.diag(a.mass) @ basis
    eigenvalues, vectors = scipy.linalg.eigh(basis.T @ stiffness @ basis, mass)
    shapes = basis @ vectors
    diameters = None
    if sectors is not None:
        eigenvalues, shapes, diameters = cyclic_eigenspaces(
            eigenvalues, shapes, stiffness, _dof_matrix(scene, sectors), sectors)
    shapes = to_dofs(a.layout, shapes, axis=0)
    frequencies = np.sqrt(np.clip(eigenvalues, 0.0, None)) / (2.0 * np.pi)
    return LinearModes(frequencies=frequencies, shapes=shapes, nodal_diameters=diameters,
                       contacts=contacts, sectors=sectors, speed_rpm=scene.speed_rpm,
                       scene=scene)


@dataclass(frozen=True, eq=False)
class Limit:
    """The group linearised with its interfaces in one limit: the state's displacements
    x = T z move as the stuck interfaces allow (``basis`` T), under the stiffness K [N/m]
    and damping C [N·s/m] of the blades, couplings and interfaces the limit closes (each a
    spring ∂N/∂δ and a dashpot ∂N/∂δ̇ along its normal: "stuck" those closed at rest, at
    their rest penetration; "closed" every one, those open at rest at first touch)."""

    basis: np.ndarray
    stiffness: np.ndarray
    damping: np.ndarray


def interface_limit(scene: Scene, contacts: str, caller: str) -> Limit:
    """The ``Limit`` of ``scene``'s group with its interfaces ``contacts`` (module
    docstring). Open, the interfaces add nothing. Raises a ValueError, naming ``caller``,
    where nothing can move, or where "closed" meets a law with no linear closed limit."""
    a = scene.arrays
    stiffness, damping = a.stiffness_matrix(), a.damping_matrix()
    closing = _NormalSprings(scene, closed=contacts == "closed", caller=caller)
    if a.is_structure:
        basis = np.eye(a.n_blades)
        if contacts != "open":
            basis, springs, dashpots = _structure_limit(a, closing)
            stiffness, damping = stiffness + springs, damping + dashpots
    else:
        stuck = np.zeros(a.n_interfaces, dtype=bool)
        if contacts != "open":
            elastic = np.isfinite(a.tangential_stiffness)
            stuck = a.can_stick & ~elastic
            springs, dashpots = _sliding_contacts(a, ~stuck, closing)
            tangential = np.where(elastic, a.tangential_stiffness, 0.0) * a.cos_angle ** 2
            springs = springs + edge_matrix(np.zeros(a.n_blades), a.left, a.right, tangential)
            stiffness, damping = stiffness + springs, damping + dashpots
        basis = _cluster_basis(a, stuck)
    if basis.shape[1] == 0:
        raise ValueError(f"{caller}: with every interface stuck nothing moves: every "
                         "blade is stuck to a fixed node")
    return Limit(basis=basis, stiffness=stiffness, damping=damping)


@dataclass(frozen=True)
class _NormalSprings:
    """The normal spring of each interface in a limit (module docstring): "stuck" closes
    those closed at rest, "closed" (``closed``) every one; a refusal names ``caller``."""

    scene: Scene
    closed: bool
    caller: str

    def gradient(self, e: int, penetration: float) -> tuple[float, float]:
        """(∂N/∂δ [N/m], ∂N/∂δ̇ [N·s/m]) of interface e at rest at ``penetration`` [m]:
        at it where the contact is closed there (or its law never opens); at first touch
        where it is open at rest and the limit is "closed"; else (0, 0)."""
        a = self.scene.arrays
        law = a.normal_laws[e]
        if penetration > 0.0 or not a.opens[e]:
            return law.gradient(max(penetration, 0.0), 0.0)
        if not self.closed:
            return 0.0, 0.0
        touch, deeper = law.gradient(FIRST_TOUCH, 0.0), law.gradient(DEEPER, 0.0)
        if not abs(deeper[0] - touch[0]) <= TOUCH_AGREEMENT * abs(deeper[0]):
            left, right, _ = self.scene.group.interfaces[e]
            raise ValueError(
                f"{self.caller}: contacts='closed' closes interface {e} ({left!r}, "
                f"{right!r}), open at rest, at first touch, where the stiffness of its "
                f"{type(law).__name__} law depends on the penetration (∂N/∂δ = "
                f"{touch[0]:.6g} N/m at {FIRST_TOUCH:g} m, {deeper[0]:.6g} N/m at "
                f"{DEEPER:g} m): a law that stiffens as it presses (Hertz or HuntCrossley "
                "of exponent > 1) has no linear closed limit there; preload the contact "
                "(gap < 0) to linearise it at its rest penetration, or take "
                "contacts='stuck'")
        return touch


def _structure_limit(a, closing: _NormalSprings) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """(T, springs, dashpots) of a scene with substructures, its interfaces stuck (module
    docstring): x = T z spans the motions the stuck interfaces allow (T orthonormal); each
    interface ``closing`` closes adds ∂N/∂δ n nᵀ and ∂N/∂δ̇ n nᵀ, and each elastic contact
    k_t (t₁t₁ᵀ + t₂t₂ᵀ) in place of its constraint. A prescribed-motion coordinate is held
    (its columns of the rows dropped)."""
    n = a.n_blades
    springs, dashpots = np.zeros((n, n)), np.zeros((n, n))
    elastic = np.isfinite(a.tangential_stiffness)
    for e in range(a.n_interfaces):
        spring, dashpot = closing.gradient(e, -a.normal_gap[e])
        normal = a.normal_rows[e, :n]
        springs += spring * np.outer(normal, normal)
        dashpots += dashpot * np.outer(normal, normal)
        if elastic[e]:
            for rows in (a.tangent_rows, a.second_tangent_rows):
                springs += a.tangential_stiffness[e] * np.outer(rows[e, :n], rows[e, :n])
    constraints = a.tangent_rows[a.can_stick & ~elastic, :n]
    basis = scipy.linalg.null_space(constraints) if len(constraints) else np.eye(n)
    return basis, springs, dashpots


def _dof_matrix(scene: Scene, sectors: int) -> np.ndarray:
    """D: the nodes' own degrees of freedom q = D x of the engine's coordinates x, nodes by
    position (a scene of blades: the identity), checked to give every sector as many
    rows."""
    a = scene.arrays
    if not a.is_structure:
        return np.eye(a.n_blades)
    per_sector = len(a.layout.sizes) // sectors
    sizes = {sum(a.layout.sizes[s * per_sector:(s + 1) * per_sector]) for s in range(sectors)}
    if len(sizes) != 1:
        raise ValueError(f"linear_modes: the {sectors} sectors have different numbers of "
                         f"degrees of freedom ({sorted(sizes)}): they are not identical")
    return to_dofs(a.layout, np.eye(a.n_blades), axis=0)


def _sliding_contacts(a, candidates, closing: _NormalSprings) -> tuple[np.ndarray, np.ndarray]:
    """The spring ∂N/∂δ sin²α [N/m] and dashpot ∂N/∂δ̇ sin²α [N·s/m] along x of each
    interface in ``candidates`` that ``closing`` closes, on the rows and columns of its
    nodes."""
    springs, dashpots = np.zeros(a.n_interfaces), np.zeros(a.n_interfaces)
    for e in np.flatnonzero(candidates):
        spring, dashpot = closing.gradient(e, -a.gap[e] * a.sin_angle[e])
        springs[e], dashpots[e] = (value * a.sin_angle[e] ** 2 for value in (spring, dashpot))
    own = np.zeros(a.n_blades)
    return (edge_matrix(own, a.left, a.right, springs),
            edge_matrix(own, a.left, a.right, dashpots))


def _cluster_basis(a, stuck) -> np.ndarray:
    """T (n_blades × free clusters): x = T z moves each stick cluster as one body; clusters
    stuck to a fixed or a prescribed-motion node have no column."""
    n = a.n_blades
    labels, grounded, _ = cluster_labels(n + a.n_prescribed, n, a.left, a.right, stuck)
    free = np.flatnonzero(~grounded)
    return (labels[:n, None] == free[None, :]).astype(float)


def nodal_diameters(shapes, sectors: int) -> np.ndarray:
    """The nodal diameter of each column of ``shapes`` (rows by position, sector-major):
    the harmonic k of the sector-to-sector DFT holding most of the shape's square, with k
    and N − k one diameter min(k, N − k)."""
    n, count = shapes.shape
    per_sector = n // sectors
    grid = shapes.reshape(sectors, per_sector, count)
    power = (np.abs(np.fft.fft(grid, axis=0)) ** 2).sum(axis=1)  # (harmonic, mode)
    folded = np.zeros((sectors // 2 + 1, count))
    for k in range(sectors):
        folded[min(k, sectors - k)] += power[k]
    return np.argmax(folded, axis=0)


def cyclic_eigenspaces(eigenvalues: np.ndarray, shapes: np.ndarray, stiffness: np.ndarray,
                       dofs: np.ndarray, sectors: int
                       ) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """(eigenvalues, shapes, nodal diameters) of the modes ``shapes`` (columns,
    mass-normalised, of the ascending ``eigenvalues`` ω² [rad²/s²] of the stiffness
    ``stiffness`` [N/m]), each eigenspace's basis turned so that each mode lies in one
    diameter's cyclic subspace where the eigenspace allows it (module docstring).

    ``dofs`` D (rows by position, sector-major, as many per sector) takes a shape to the
    nodes' own degrees of freedom q = D φ, where the DFT over the sectors is taken. For an
    eigenspace of several modes, Φ = shapes[:, cluster] and Q = D Φ: the operator
    Σ_ND ND Qᵀ P_ND Q, P_ND the orthogonal projector on the harmonics ND and N − ND of
    q, is diagonalised against Qᵀ Q (``scipy.linalg.eigh``); its eigenvectors R are the
    combinations of Φ whose q are orthonormal, each of one diameter, where the eigenspace
    is invariant under the sector shift (a tuned ring: P_ND Q = Q C_ND there, and the
    eigenvalues are the diameters). Φ R is made mass-normalised again by the orthogonal
    polar factor of R (Φ is), which keeps each diameter's columns within it, in
    ascending diameter. An eigenspace gathered to the tolerance may join the exact
    eigenspaces of neighbouring diameters, each of which its turned modes then are: where
    their Rayleigh quotients φᵀ K φ spread beyond rounding (``EIGENSPACE_ROUNDING``),
    they become the modes' eigenvalues and order them. Each mode is labelled by
    ``nodal_diameters``. A single mode is left as it is.
    """
    eigenvalues, shapes = eigenvalues.copy(), shapes.copy()
    rounding = EIGENSPACE_ROUNDING * np.abs(eigenvalues).max(initial=0.0)
    if sectors > 1:
        for cluster in _eigenspaces(eigenvalues):
            if len(cluster) > 1:
                q = dofs @ shapes[:, cluster]
                _, turn = scipy.linalg.eigh(_diameter_operator(q, sectors), q.T @ q)
                turned = shapes[:, cluster] @ scipy.linalg.polar(turn)[0]
                rayleigh = np.einsum("ij,ij->j", turned, stiffness @ turned)
                if np.ptp(rayleigh) > rounding:
                    order = np.argsort(rayleigh, kind="stable")
                    eigenvalues[cluster], turned = rayleigh[order], turned[:, order]
                shapes[:, cluster] = turned
    return eigenvalues, shapes, nodal_diameters(dofs @ shapes, sectors)


def _eigenspaces(eigenvalues: np.ndarray) -> list[np.ndarray]:
    """The indices of each run of ascending ``eigenvalues`` equal to ``EIGENSPACE``
    (relative) or ``EIGENSPACE_ROUNDING`` of the largest."""
    floor = EIGENSPACE_ROUNDING * np.abs(eigenvalues).max(initial=0.0)
    gaps = np.diff(eigenvalues)
    tolerance = EIGENSPACE * np.abs(eigenvalues[1:]) + floor
    return np.split(np.arange(len(eigenvalues)), np.flatnonzero(gaps > tolerance) + 1)


def _diameter_operator(q: np.ndarray, sectors: int) -> np.ndarray:
    """Σ_ND ND Qᵀ P_ND Q for the columns Q of ``q`` (rows sector-major): with the unitary
    DFT F_k = Σ_s Q_s e^{−2πi k s/N}/√N over the sectors s, Σ_k min(k, N − k) Re(F_kᴴ F_k)."""
    grid = q.reshape(sectors, -1, q.shape[1])
    harmonics = np.fft.fft(grid, axis=0) / np.sqrt(sectors)
    k = np.arange(sectors)
    weights = np.minimum(k, sectors - k).astype(float)
    return np.einsum("k,kpi,kpj->ij", weights, harmonics.conj(), harmonics).real


def excited_diameter(engine_order: int, sectors: int) -> int:
    """The one nodal diameter an engine order l excites on N sectors: l mod N, folded to
    min(r, N − r)."""
    remainder = engine_order % sectors
    return min(remainder, sectors - remainder)


@dataclass(frozen=True, eq=False)
class GroupCampbell:
    """The group's natural frequencies over speed and the engine orders that cross them.

    ``frequencies[k, m]`` [Hz] is mode m (ascending) at ``speeds_rpm[k]``, and
    ``nodal_diameters[k, m]`` its ND (None without sectors). ``crossings`` lists
    (engine order, mode number, speed [rpm], frequency [Hz]) where f_m = l Ω/60 on a mode
    the engine order excites (its ND, for a ring).
    """

    speeds_rpm: np.ndarray
    frequencies: np.ndarray
    nodal_diameters: np.ndarray | None
    engine_orders: tuple[int, ...]
    crossings: tuple[tuple[int, int, float, float], ...]
    contacts: str

    #: Fields that may hold NaN or ±inf (see ``checked_records``).
    NON_FINITE = ("frequencies",)

    def __post_init__(self):
        check_record(self)

    def line(self, engine_order: int) -> np.ndarray:
        """The excitation frequency l Ω/60 [Hz] of an engine order at each speed."""
        return engine_order * self.speeds_rpm / 60.0


def group_campbell(scene: Scene, speeds_rpm: Sequence[float],
                   engine_orders: Sequence[int] = (1, 2, 3, 4), *, contacts: str = "open",
                   sectors: int | None = None) -> GroupCampbell:
    """The Campbell diagram of the group: ``linear_modes`` at each of the increasing
    ``speeds_rpm``, with the crossings of the engine-order lines located by Brent's method
    on the modes each order excites."""
    check_instance("group_campbell", "scene", scene, Scene, expected="a shroudnet.Scene")
    speeds = check_array("group_campbell", "speeds_rpm", speeds_rpm, shape=(None,), low=0.0,
                         low_open=True, unit="rpm")
    if len(speeds) < 2 or np.any(np.diff(speeds) <= 0):
        raise ValueError("group_campbell needs at least two increasing speeds_rpm")
    orders = tuple(check_int("group_campbell", "engine_orders", order, low=1)
                   for order in check_sequence("group_campbell", "engine_orders",
                                               engine_orders, expected="a sequence of ints",
                                               min_length=1))

    def modes_at(speed):
        return linear_modes(replace(scene, speed_rpm=float(speed)), contacts,
                            sectors=sectors)

    table = [modes_at(speed) for speed in speeds]
    frequencies = np.array([m.frequencies for m in table])
    ring = table[0].sectors
    diameters = None if ring is None else np.array([m.nodal_diameters for m in table])
    crossings = []
    for order in orders:
        for mode in range(frequencies.shape[1]):
            if ring is not None and excited_diameter(order, ring) not in diameters[:, mode]:
                continue
            gap = frequencies[:, mode] - order * speeds / 60.0
            for k in range(len(speeds) - 1):
                if gap[k] * gap[k + 1] > 0.0 or gap[k + 1] == 0.0:
                    continue

                def detuning(speed, mode=mode, order=order):
                    return modes_at(speed).frequencies[mode] - order * speed / 60.0

                speed = speeds[k] if gap[k] == 0.0 else brentq(
                    detuning, speeds[k], speeds[k + 1], xtol=1e-6)
                if ring is not None and modes_at(speed).nodal_diameters[mode] \
                        != excited_diameter(order, ring):
                    continue
                crossings.append((order, mode, float(speed), float(order * speed / 60.0)))
    return GroupCampbell(speeds, frequencies, diameters, orders, tuple(crossings), contacts)
