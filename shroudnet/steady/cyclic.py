"""Cyclic symmetry: a tuned ring of N identical sectors forced in engine order l.

The group's nodes are added sector by sector (``BladeGroup.ring``, ``bladed_disc``,
``declare_sectors``): coordinate p = s m + j is slot j of sector s (a one-mass blade's x,
or a substructure's modal coordinates), and its image one sector on is
P(p) = ((s + 1) mod N) m + j. The shift (S y)_p = y_{P(p)} — each elastic contact's
stretches taken from its twin's one sector on — maps the structure, every contact and
coupling onto itself, and the engine-order forcing, φ_{P(p)} = φ_p + 2πl/N, onto itself
one sector-passing time Δ = l T_e/N later: S Q(t) = Q(t + Δ). Substructures in frames of
their own (sector s turned by 2πs/N, ``BladeGroup.add_blade``) have identical matrices
and points, so S moves each sector's coordinates to the next one's unchanged: a contact's
rows, in its left node's frame, are its twin's one sector on (DESIGN §8). Their one Φ
(q_i = Φ η_i, ``model.lowering.to_dofs``) commutes with S, so S is the same permutation
of the nodes' own degrees of freedom q, in which every state a user gives or gets is. A tuned disc's
steady state shares that symmetry, y(t + Δ) = S y(t), and, reduced modulo T_e, the
smallest shift is

    y(t + τ) = Sᵏ y(t),   τ = g T_e / N,   g = gcd(l, N),   k l ≡ g (mod N),

so the orbit is a fixed point of the reduced map G(y) = S⁻ᵏ φ_τ(y), integrated over τ
only. Its Jacobian A = S⁻ᵏ Φ_τ gives the whole monodromy: the tangent over each τ is
Φ_τ moved round by the symmetry, so that

    M = Φ_{T_e} = S^{kN/g} A^{N/g},

whose eigenvalues are the multipliers of every perturbation, those that break the
symmetry included (Wagg's and Vakakis's spatio-temporal symmetry; DESIGN §7).

Where g > 1, sectors N/g apart switch at the same instant on a symmetric orbit. Between
substructures the tangent flow does not tell such independent switches apart (it does
between one-mass blades, by their stick clusters), so the orbit is ``singular`` to the
symmetric and the full solver alike: its multipliers are not to be trusted, the orbit is.
"""

from __future__ import annotations

import dataclasses
import math
from dataclasses import dataclass, field

import numpy as np

from contact_laws import check_choice

from ..analysis.stability import StroboscopicStep, state_parts
from ..model.scene import Scene
from ..run.simulate import integrate
from .extremes import state_at


@dataclass(frozen=True, eq=False)
class CyclicSymmetry:
    """The symmetry of a tuned ring forced in engine order (module docstring):
    ``sectors`` N of ``per_sector`` coordinates each (nodes of one-mass blades), in
    engine order ``engine_order`` l. ``stretch_image`` gives, for each stretch of an
    elastic contact (two a contact: ``Simulation.stretches``), the position of its twin's
    one sector on, and ``stretch_sector`` its contact's sector (that of its first moving
    node); ``responses`` counts the responses of a sector (``Scene.responses``)."""

    sectors: int
    per_sector: int
    engine_order: int
    stretch_image: np.ndarray = field(default_factory=lambda: np.zeros(0, dtype=int))
    stretch_sector: np.ndarray = field(default_factory=lambda: np.zeros(0, dtype=int))
    responses: int | None = None

    @property
    def share(self) -> int:
        """g = gcd(l, N)."""
        return math.gcd(self.engine_order, self.sectors)

    @property
    def fraction(self) -> float:
        """τ / T_e = g/N."""
        return self.share / self.sectors

    @property
    def repeats(self) -> int:
        """N/g: the reduced maps in one excitation period."""
        return self.sectors // self.share

    @property
    def steps(self) -> int:
        """k, the sectors the orbit moves on over τ: k (l/g) ≡ 1 (mod N/g); 0 where
        N/g = 1."""
        return pow(self.engine_order // self.share, -1, self.repeats) if self.repeats > 1 \
            else 0

    @property
    def size(self) -> int:
        """The length of a state y = (x, ẋ[, u])."""
        return 2 * self.sectors * self.per_sector + len(self.stretch_image)

    def positions(self, steps: int) -> np.ndarray:
        """Pᵐ (m = ``steps``) as an index array, (Sᵐ x)_p = x[Pᵐ(p)]: coordinate p's
        image m sectors on, p + m·``per_sector`` round the ring."""
        n = self.sectors * self.per_sector
        return (np.arange(n) + steps * self.per_sector) % n

    def permutation(self, steps: int) -> np.ndarray:
        """Sᵐ on a whole state y = (x, ẋ[, u]) as an index array, (Sᵐ y)_i = y[π(i)]: the
        coordinates as ``positions``, each stretch its twin's m sectors on."""
        index = self.positions(steps)
        n = len(index)
        stretches = np.arange(len(self.stretch_image))
        for _ in range(steps % self.sectors):
            stretches = self.stretch_image[stretches]
        return np.concatenate([index, n + index, 2 * n + stretches])

    def shifted(self, y: np.ndarray, steps: int) -> np.ndarray:
        """Sᵐ y for a state y = (x, ẋ[, u]) (or a matrix whose rows are), m = ``steps``."""
        return np.asarray(y)[self.permutation(steps)]

    @property
    def repeating(self) -> int:
        """The coordinates of the N/g sectors over which a symmetric orbit's state repeats
        round the ring: the forcing's phase, 2πl/N a sector, comes round every N/g
        sectors."""
        return self.repeats * self.per_sector

    @property
    def _representatives(self) -> np.ndarray:
        """For each entry of a whole state, the entry of the first N/g sectors it repeats
        on a state that repeats every N/g sectors: coordinate p's is p mod (N/g)m, a
        stretch's its twin's i N/g sectors back (i = its sector // (N/g))."""
        m, n = self.repeating, self.sectors * self.per_sector
        index = np.arange(n) % m
        stretches = np.arange(len(self.stretch_image))
        back = -(self.stretch_sector // self.repeats) * self.repeats % self.sectors
        for turn in range(1, self.sectors):  # back: each stretch's own count of turns
            moved = back >= turn
            stretches[moved] = self.stretch_image[stretches[moved]]
        return np.concatenate([index, n + index, 2 * n + stretches])

    @property
    def _kept(self) -> np.ndarray:
        """The entries of a whole state that a repeating one keeps: the first N/g
        sectors' coordinates, velocities and stretches, in the state's order."""
        m, n = self.repeating, self.sectors * self.per_sector
        stretches = np.flatnonzero(self.stretch_sector < self.repeats)
        return np.concatenate([np.arange(m), n + np.arange(m), 2 * n + stretches])

    def tiled(self, z: np.ndarray) -> np.ndarray:
        """The ring's state y = B z (or matrix, by rows) that repeats z, the state of the
        first N/g sectors (``restricted``), all round the ring."""
        kept = self._kept
        place = np.empty(self.size, dtype=int)
        place[kept] = np.arange(len(kept))
        return np.asarray(z)[place[self._representatives]]

    def restricted(self, y: np.ndarray) -> np.ndarray:
        """The first N/g sectors' part z of a ring's state y (or matrix, by rows): the
        inverse of ``tiled`` on the states it makes."""
        return np.asarray(y)[self._kept]

    def monodromy(self, reduced: np.ndarray) -> np.ndarray:
        """M = S^{kN/g} A^{N/g} from the reduced map's Jacobian A = ``reduced``."""
        power = np.linalg.matrix_power(reduced, self.repeats)
        return self.shifted(power, self.steps * self.repeats)


def cyclic_symmetry(scene: Scene) -> CyclicSymmetry:
    """The ``CyclicSymmetry`` of ``scene``; a ValueError saying what breaks it where the
    scene is not a tuned ring forced by an engine-order wave: its sectors' nodes, edges
    (contacts and couplings, in the sectors' frames) and loads must be each other's,
    one sector on."""
    a = scene.arrays
    sectors = scene.group.sectors
    if sectors is None:
        raise ValueError("cyclic symmetry needs a ring or a disc of sectors "
                         "(BladeGroup.ring, BladeGroup.bladed_disc, or declare_sectors); "
                         "this group has none")
    if a.n_prescribed:
        raise ValueError("cyclic symmetry needs every node to move with its sector; this "
                         "group has prescribed-motion nodes")
    nodes = len(scene.blades)
    if nodes % sectors:
        raise ValueError(f"cyclic symmetry needs the {nodes} nodes to be {sectors} sectors of "
                         "as many nodes each")
    n = a.n_blades
    if a.is_structure:
        sizes = np.array(a.layout.sizes).reshape(sectors, -1)
        if np.any(sizes != sizes[0]):
            raise ValueError("the ring is mistuned: its sectors' nodes have different "
                             "numbers of coordinates; cyclic symmetry needs identical sectors")
    symmetry = CyclicSymmetry(sectors=sectors, per_sector=n // sectors,
                              engine_order=scene.excitation.engine_order)
    image = symmetry.positions(1)
    _check_nodes(a, image)
    if a.is_structure:
        twins = _contact_twins(scene, nodes // sectors)
        _check_structure(a, image, twins)
        elastic = a.elastic_interfaces
        where = {int(e): k for k, e in enumerate(elastic)}
        slot = np.array([where[int(twins[e])] for e in elastic], dtype=int)
        contact_sector = contact_sectors(scene, nodes // sectors)[elastic]
        symmetry = dataclasses.replace(
            symmetry, stretch_image=np.stack([2 * slot, 2 * slot + 1], axis=1).ravel(),
            stretch_sector=np.repeat(contact_sector, 2),
            responses=len(scene.responses) // sectors)
    else:
        _check_edges("interface", (a.left, a.right), image, _interface_rows(a))
        _check_edges("coupling", (a.coupling_left, a.coupling_right), image,
                     list(zip(a.coupling_stiffness, a.coupling_damping)))
        symmetry = dataclasses.replace(symmetry, responses=symmetry.per_sector)
    _check_forcing(a, image, symmetry.engine_order, sectors)
    return symmetry


def symmetry_of(scene: Scene, periods: int, symmetry: str | None,
                owner: str = "periodic_orbit") -> CyclicSymmetry | None:
    """The ``CyclicSymmetry`` ``owner`` solves with (``symmetry`` as ``periodic_orbit``
    takes it), or None for whole periods."""
    if symmetry is not None:
        check_choice(owner, "symmetry", symmetry, ("cyclic", "none"))
    if symmetry == "none":
        return None
    if periods != 1:
        if symmetry == "cyclic":
            raise ValueError(f"{owner}: symmetry='cyclic' solves period-1 orbits (a "
                             f"travelling wave), got periods = {periods}")
        return None
    try:
        return cyclic_symmetry(scene)
    except ValueError as reason:
        if symmetry == "cyclic":
            raise ValueError(f"{owner}: symmetry='cyclic' does not hold: {reason}") from None
        return None


#: Entries of a sector's rows and matrices may differ from their twins' one sector on by
#: this fraction of the largest: the sectors' frames turned by 2πs/N round differently.
FRAME_ROUNDING = 1e-12


def _node_image(scene: Scene, per_sector: int) -> dict:
    """Each node's image one sector on (moving nodes: the same slot of the next sector;
    fixed nodes: themselves)."""
    names = scene.blades
    image = {name: names[(i + per_sector) % len(names)] for i, name in enumerate(names)}
    image.update((name, name) for name in scene.group.fixed)
    return image


def _contact_twins(scene: Scene, per_sector: int) -> np.ndarray:
    """Each contact's twin one sector on: the contact of the same place in its patch
    between the images of its nodes and at the same points (the first such one for the
    first such contact, and so on, where edges are parallel)."""
    image = _node_image(scene, per_sector)
    free: dict = {}
    for c, contact in enumerate(scene.contacts):
        key = (contact.left, contact.right, contact.left_point, contact.right_point,
               contact.contact)
        free.setdefault(key, []).append(c)
    twins = np.empty(len(scene.contacts), dtype=int)
    for c, contact in enumerate(scene.contacts):
        key = (image[contact.left], image[contact.right], contact.left_point,
               contact.right_point, contact.contact)
        if not free.get(key):
            raise ValueError(f"the ring is not tuned: {contact} has no twin between "
                             f"{key[0]!r} and {key[1]!r}, one sector on")
        twins[c] = free[key].pop(0)
    return twins


def contact_sectors(scene: Scene, per_sector: int) -> np.ndarray:
    """The sector of each contact: its left node's, or its right node's at a fixed one."""
    position = {name: i for i, name in enumerate(scene.blades)}
    return np.array([position.get(contact.left, position.get(contact.right)) // per_sector
                     for contact in scene.contacts], dtype=int)


def _close(one: np.ndarray, other: np.ndarray, scale: float) -> bool:
    return bool(np.all(np.abs(one - other) <= FRAME_ROUNDING * scale))


def _check_structure(a, image, twins) -> None:
    """Every contact's rows are its twin's read one sector on, with its laws; the
    stiffness and damping (couplings in) are their own one sector on."""
    for name in ("structure_stiffness", "structure_damping"):
        matrix = getattr(a, name)
        if not _close(matrix[np.ix_(image, image)], matrix, np.abs(matrix).max()):
            raise ValueError(f"the ring is not tuned: its {name.split('_')[1]} (couplings "
                             "in) differs from sector to sector; cyclic symmetry needs "
                             "identical sectors")
    rows = [a.normal_rows, a.tangent_rows, a.second_tangent_rows]
    laws = _interface_rows(a)
    for c, twin in enumerate(twins):
        same = laws[twin] == laws[c] and a.normal_gap[twin] == a.normal_gap[c]
        for row in rows:
            same = same and _close(row[twin, image], row[c], np.abs(row[c]).max())
        if not same:
            raise ValueError(f"the ring is not tuned: contact {c} differs from its twin "
                             f"{int(twin)} one sector on (its laws, gap or rows in the "
                             "sectors' frames); cyclic symmetry needs identical sectors")


def _check_nodes(a, image) -> None:
    """Every node is its image's twin: mass, damping, stiffness and forcing scale."""
    for name in ("mass", "damping", "stiffness", "excitation_scale"):
        values = getattr(a, name)
        differs = np.flatnonzero(values[image] != values)
        if len(differs):
            p = int(differs[0])
            raise ValueError(f"the ring is mistuned: node {p}'s {name} {values[p]:.6g} differs "
                             f"from node {int(image[p])}'s {values[image[p]]:.6g}, one sector "
                             "on; cyclic symmetry needs identical sectors")


def _interface_rows(a) -> list[tuple]:
    """Per interface, everything its forces depend on, to compare with its image."""
    return list(zip(a.gap, a.sin_angle, a.cos_angle, a.normal_laws, a.friction_laws,
                    a.opens, a.can_stick, a.regularisation, a.tangential_stiffness))


def _check_edges(kind, ends, image, rows) -> None:
    """Every edge (left, right) has an edge (P left, P right) with the same ``rows`` entry
    (fixed ends, −1, stay fixed)."""
    left, right = ends
    moved = {(int(i), int(j)): e for e, (i, j) in enumerate(zip(left, right))}
    for e, (i, j) in enumerate(zip(left, right)):
        target = tuple(int(image[k]) if k >= 0 else -1 for k in (i, j))
        twin = moved.get(target)
        if twin is None or rows[twin] != rows[e]:
            raise ValueError(f"the ring is not tuned: {kind} {e} between nodes {int(i)} and "
                             f"{int(j)} has no identical {kind} between nodes {target[0]} and "
                             f"{target[1]}, one sector on")


def _check_forcing(a, image, engine_order, sectors) -> None:
    """Each harmonic n is the same on a node and its image, its phase n·2πl/N later."""
    step = 2.0 * math.pi * engine_order / sectors
    for harmonic in range(1, a.harmonic_amplitudes.shape[0]):
        amplitudes = a.harmonic_amplitudes[harmonic]
        if np.any(amplitudes[image] != amplitudes):
            raise ValueError("the forcing is not an engine-order wave: its amplitudes differ "
                             "from sector to sector")
        lag = a.harmonic_phases[harmonic, image] - a.harmonic_phases[harmonic] \
            - harmonic * step
        loaded = amplitudes != 0.0
        if np.any(np.abs(np.angle(np.exp(1j * lag[loaded]))) > 1e-9):
            raise ValueError(f"the forcing is not an engine-order wave of l = {engine_order} "
                             f"on {sectors} sectors: neighbouring sectors' phases do not differ "
                             f"by 2πl/N")
    if np.any(a.harmonic_amplitudes[0][image] != a.harmonic_amplitudes[0]):
        raise ValueError("the forcing is not an engine-order wave: its static part differs "
                         "from sector to sector")


def first_sector(symmetry: CyclicSymmetry) -> np.ndarray:
    """The positions of the first sector's responses (``Scene.responses``, which come
    sector by sector, each node's in its own frame): on a symmetric orbit the others
    repeat them, sector by sector."""
    return np.arange(symmetry.responses)


def state_on_orbit(symmetry: CyclicSymmetry, scene: Scene, initial, *, method,
                   event_tolerance: float):
    """time [s] → (x, ẋ) of the symmetric orbit from ``initial``, run again from its start
    over less than τ: with t = iτ + s, 0 ≤ s < τ, y(t) = S^{ik} y(s) — a run to s rather
    than to t (``extremes.state_at``)."""
    tau = symmetry.fraction * scene.excitation_period

    def state(time):
        turns = max(int(np.floor(time / tau)), 0)
        x, v = state_at(scene, initial, time - turns * tau, method, event_tolerance)
        index = symmetry.positions(turns * symmetry.steps)
        return x[index], v[index]
    return state


def reduced_step(scene: Scene, symmetry: CyclicSymmetry, initial, *, method,
                 event_tolerance: float, repeating: bool = False) -> StroboscopicStep:
    """G(y) = S⁻ᵏ φ_τ(y) and its Jacobian A = S⁻ᵏ Φ_τ from ``initial``, the state
    y = (x0, v0[, u0]) (one array, or its parts), in one run over τ with its tangent flow
    (``stability.stroboscopic_step`` over τ); ``singular`` counts the switches of the run
    over τ.

    With ``repeating``, ``initial`` is z, the first N/g sectors' state, of a ring state
    y = B z that repeats it round the ring (``CyclicSymmetry.tiled``), which G maps onto
    such a state again (the forcing comes round every N/g sectors): the step is
    z ↦ B⁺ G(B z) with its Jacobian B⁺ A B, whose tangent flow carries as many columns as
    z has entries (2mN/g and the first N/g sectors' stretches), not all of y's — the map
    Newton solves on, the symmetric orbit lying among those states. Without, from a start
    that repeats every N/g sectors, the tangent flow carries the first N/g sectors'
    columns too, and ``whole_tangent`` moves them round the ring; from any other start,
    all of them."""
    y = np.concatenate(initial) if isinstance(initial, tuple | list) else np.asarray(initial)
    if repeating:
        y = symmetry.tiled(y)
    size = len(y)
    # The first N/g sectors' columns stand for all where the state repeats every N/g
    # sectors exactly (``whole_tangent``); a start that does not carries every column.
    block = repeating or np.array_equal(symmetry.tiled(symmetry.restricted(y)), y)
    first = symmetry.restricted(np.arange(size)) if block else np.arange(size)
    start = symmetry.tiled(np.eye(len(first))) if repeating else np.eye(size)[:, first]
    done = integrate(scene, 1, method=method, samples_per_period=1,
                     event_tolerance=event_tolerance, initial=state_parts(scene, y),
                     event_capacity=0, tangent=start,
                     until=symmetry.fraction * scene.excitation_period)
    run = done.run
    tangent = run.tangent
    end = shifted_end(symmetry, done)
    matrix = whole_tangent(symmetry, tangent.matrix) if block and not repeating \
        else tangent.matrix
    jacobian = symmetry.shifted(matrix, -symmetry.steps)
    if repeating:
        end, jacobian = symmetry.restricted(end), symmetry.restricted(jacobian)
    return StroboscopicStep(scene=scene, end=end, jacobian=jacobian,
                            singular=int(tangent.singular[0]),
                            singular_time=float(tangent.singular_time[0]),
                            singular_interface=int(tangent.singular_interface[0]))


def shifted_end(symmetry: CyclicSymmetry, done) -> np.ndarray:
    """S⁻ᵏ φ_τ(y): the state (x, ẋ, u) at the end of ``done``, a run over τ (what
    ``integrate`` returns), moved back by the k sectors the forcing moved on."""
    run = done.run
    return symmetry.shifted(np.concatenate([run.output.x[-1], run.output.v[-1],
                                            done.stretches[-1]]), -symmetry.steps)


def whole_tangent(symmetry: CyclicSymmetry, block: np.ndarray) -> np.ndarray:
    """Φ_τ of the whole ring from ``block``, its columns along the first N/g sectors'
    entries (``CyclicSymmetry.restricted``). On a symmetric orbit the ring's state
    repeats every N/g sectors over all of τ, and so do its forces: the tangent flow
    commutes with that shift, R = S^{N/g}, and its column along the entry π_Rᶜ(j) (j's
    twin c N/g sectors on) is R⁻ᶜ Φ_τ's along j — a tangent flow of the first N/g
    sectors' columns gives them all."""
    first = symmetry.restricted(np.arange(symmetry.size))
    whole = np.empty((symmetry.size, symmetry.size))
    for c in range(symmetry.share):
        moved = symmetry.shifted(block, -c * symmetry.repeats)
        whole[:, symmetry.permutation(c * symmetry.repeats)[first]] = moved
    return whole


def whole_period(symmetry: CyclicSymmetry, reduced: StroboscopicStep) -> StroboscopicStep:
    """The step over one excitation period that the reduced one at a symmetric orbit
    stands for: the monodromy M = S^{kN/g} A^{N/g}, and N/g times its singular switches."""
    return dataclasses.replace(reduced, jacobian=symmetry.monodromy(reduced.jacobian),
                               singular=reduced.singular * symmetry.repeats)
