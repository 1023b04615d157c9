"""Cyclic symmetry: a tuned ring of N identical sectors forced in engine order l.

The group's nodes are added sector by sector (``BladeGroup.ring``, ``bladed_disc``):
node p = s m + j is slot j of sector s, and its image one sector on is
P(p) = ((s + 1) mod N) m + j. The shift (S y)_p = y_{P(p)} maps the structure, every
interface and coupling onto itself, and the engine-order forcing, φ_{P(p)} = φ_p + 2πl/N,
onto itself one sector-passing time Δ = 2π/(NΩ) later: S Q(t) = Q(t + Δ). A tuned disc's
steady state shares that symmetry, y(t + Δ) = S y(t), and, reduced modulo T_e, the
smallest shift is

    y(t + τ) = Sᵏ y(t),   τ = g T_e / N,   g = gcd(l, N),   k l ≡ g (mod N),

so the orbit is a fixed point of the reduced map G(y) = S⁻ᵏ φ_τ(y), integrated over τ
only. Its Jacobian A = S⁻ᵏ Φ_τ gives the whole monodromy: the tangent over each τ is
Φ_τ moved round by the symmetry, so that

    M = Φ_{T_e} = S^{kN/g} A^{N/g},

whose eigenvalues are the multipliers of every perturbation, those that break the
symmetry included (Wagg's and Vakakis's spatio-temporal symmetry; DESIGN §7).
"""

from __future__ import annotations

import dataclasses
import math
from dataclasses import dataclass

import numpy as np

from ..analysis.stability import StroboscopicStep
from ..model.scene import Scene
from ..run.simulate import integrate
from .extremes import state_at


@dataclass(frozen=True)
class CyclicSymmetry:
    """The symmetry of a tuned ring forced in engine order (module docstring):
    ``sectors`` N of ``per_sector`` nodes each, ``engine_order`` l."""

    sectors: int
    per_sector: int
    engine_order: int

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

    def positions(self, steps: int) -> np.ndarray:
        """Pᵐ (m = ``steps``) as an index array, (Sᵐ y)_p = y[Pᵐ(p)]: node p's image m
        sectors on, p + m·``per_sector`` round the ring."""
        n = self.sectors * self.per_sector
        return (np.arange(n) + steps * self.per_sector) % n

    def shifted(self, y: np.ndarray, steps: int) -> np.ndarray:
        """Sᵐ y for a state y = (x, ẋ) (or a matrix whose rows are), m = ``steps``."""
        index = self.positions(steps)
        n = len(index)
        return np.asarray(y)[np.concatenate([index, n + index])]

    @property
    def repeating(self) -> int:
        """The nodes of the N/g sectors over which a symmetric orbit's state repeats round
        the ring: the forcing's phase, 2πl/N a sector, comes round every N/g sectors."""
        return self.repeats * self.per_sector

    def tiled(self, z: np.ndarray) -> np.ndarray:
        """The ring's state y = B z (or matrix, by rows) that repeats z = (x, ẋ) of the
        first N/g sectors all round the ring."""
        m = self.repeating
        index = np.arange(self.sectors * self.per_sector) % m
        return np.asarray(z)[np.concatenate([index, m + index])]

    def restricted(self, y: np.ndarray) -> np.ndarray:
        """The first N/g sectors' part z of a ring's state y (or matrix, by rows): the
        inverse of ``tiled`` on the states it makes."""
        m, n = self.repeating, self.sectors * self.per_sector
        return np.asarray(y)[np.r_[0:m, n:n + m]]

    def monodromy(self, reduced: np.ndarray) -> np.ndarray:
        """M = S^{kN/g} A^{N/g} from the reduced map's Jacobian A = ``reduced``."""
        power = np.linalg.matrix_power(reduced, self.repeats)
        return self.shifted(power, self.steps * self.repeats)


def cyclic_symmetry(scene: Scene) -> CyclicSymmetry:
    """The ``CyclicSymmetry`` of ``scene``; a ValueError saying what breaks it where the
    scene is not a tuned ring of one-mass nodes forced by an engine-order wave."""
    a = scene.arrays
    sectors = scene.group.graph.graph.get("sectors")
    if sectors is None:
        raise ValueError("cyclic symmetry needs a ring or a disc of sectors "
                         "(BladeGroup.ring, BladeGroup.bladed_disc); this group has none")
    if a.is_structure:
        raise ValueError("cyclic symmetry is solved for groups of Blades; this group has "
                         "substructures or elastic contacts")
    if a.n_prescribed:
        raise ValueError("cyclic symmetry needs every node to move with its sector; this "
                         "group has prescribed-motion nodes")
    n = a.n_blades
    if n % sectors:
        raise ValueError(f"cyclic symmetry needs the {n} nodes to be {sectors} sectors of "
                         "as many nodes each")
    symmetry = CyclicSymmetry(sectors=sectors, per_sector=n // sectors,
                              engine_order=scene.excitation.engine_order)
    image = symmetry.positions(1)
    _check_nodes(a, image)
    _check_edges("interface", (a.left, a.right), image, _interface_rows(a))
    _check_edges("coupling", (a.coupling_left, a.coupling_right), image,
                 list(zip(a.coupling_stiffness, a.coupling_damping)))
    _check_forcing(a, image, symmetry.engine_order, sectors)
    return symmetry


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
    """The positions of the first sector's responses (its nodes: ``cyclic_symmetry`` takes
    groups of ``Blade``s only): on a symmetric orbit the others repeat them, sector by
    sector."""
    return np.arange(symmetry.per_sector)


def state_on_orbit(symmetry: CyclicSymmetry, scene: Scene, initial, *, method,
                   event_tolerance: float):
    """time [s] → (x, ẋ) of the symmetric orbit from ``initial``, run again from its start
    over less than τ: with t = iτ + s, 0 ≤ s < τ, y(t) = S^{ik} y(s) — a run to s rather
    than to t (``extremes.state_at``)."""
    tau = symmetry.fraction * scene.excitation_period

    def state(time):
        turns = max(int(np.floor(time / tau)), 0)
        x, v = state_at(scene, initial, time - turns * tau, method, event_tolerance)
        return np.split(symmetry.shifted(np.concatenate([x, v]), turns * symmetry.steps), 2)
    return state


def reduced_step(scene: Scene, symmetry: CyclicSymmetry, initial, *, method,
                 event_tolerance: float, repeating: bool = False) -> StroboscopicStep:
    """G(y) = S⁻ᵏ φ_τ(y) and its Jacobian A = S⁻ᵏ Φ_τ from ``initial`` = (x0, v0), in one
    run over τ with its tangent flow (``stability.stroboscopic_step`` over τ);
    ``singular`` counts the switches of the run over τ.

    With ``repeating``, ``initial`` is z, the first N/g sectors' state, of a ring state
    y = B z that repeats it round the ring (``CyclicSymmetry.tiled``), which G maps onto
    such a state again (the forcing comes round every N/g sectors): the step is
    z ↦ B⁺ G(B z) with its Jacobian B⁺ A B, whose tangent flow carries 2mN/g columns, not
    2mN — the map Newton solves on, the symmetric orbit lying among those states.
    Without, from a start that repeats every N/g sectors, the tangent flow carries the
    first N/g sectors' 2mN/g columns too, and ``whole_tangent`` moves them round the
    ring; from any other start, all 2mN."""
    x0, v0 = initial
    if repeating:
        x0, v0 = np.split(symmetry.tiled(np.concatenate([x0, v0])), 2)
    n = scene.arrays.n_blades
    y = np.concatenate([x0, v0])
    # The first N/g sectors' columns stand for all where the state repeats every N/g
    # sectors exactly (``whole_tangent``); a start that does not carries every column.
    block = repeating or np.array_equal(symmetry.tiled(symmetry.restricted(y)), y)
    first = symmetry.restricted(np.arange(2 * n)) if block else np.arange(2 * n)
    start = symmetry.tiled(np.eye(len(first))) if repeating else np.eye(2 * n)[:, first]
    run = integrate(scene, 1, method=method, samples_per_period=1,
                    event_tolerance=event_tolerance, initial=(x0, v0), event_capacity=0,
                    tangent=start, until=symmetry.fraction * scene.excitation_period).run
    tangent = run.tangent
    end = symmetry.shifted(np.concatenate([run.output.x[-1], run.output.v[-1]]),
                           -symmetry.steps)
    matrix = whole_tangent(symmetry, tangent.matrix) if block and not repeating \
        else tangent.matrix
    jacobian = symmetry.shifted(matrix, -symmetry.steps)
    if repeating:
        end, jacobian = symmetry.restricted(end), symmetry.restricted(jacobian)
    return StroboscopicStep(scene=scene, end=end, jacobian=jacobian,
                            singular=int(tangent.singular[0]),
                            singular_time=float(tangent.singular_time[0]),
                            singular_interface=int(tangent.singular_interface[0]))


def whole_tangent(symmetry: CyclicSymmetry, block: np.ndarray) -> np.ndarray:
    """Φ_τ of the whole ring from ``block``, its columns along the first N/g sectors'
    coordinates. On a symmetric orbit the ring's state repeats every N/g sectors over
    all of τ, and so do its forces: the tangent flow commutes with that shift, R = S^{N/g},
    and its columns along the c-th group of N/g sectors are R⁻ᶜ Φ_τ's along the first —
    a tangent flow of 2mN/g columns gives all 2mN (m coordinates a sector)."""
    m = symmetry.repeating
    n = symmetry.sectors * symmetry.per_sector
    whole = np.empty((2 * n, 2 * n))
    for c in range(symmetry.share):
        moved = symmetry.shifted(block, -c * symmetry.repeats)
        whole[:, c * m:(c + 1) * m] = moved[:, :m]
        whole[:, n + c * m:n + (c + 1) * m] = moved[:, m:]
    return whole


def whole_period(symmetry: CyclicSymmetry, reduced: StroboscopicStep) -> StroboscopicStep:
    """The step over one excitation period that the reduced one at a symmetric orbit
    stands for: the monodromy M = S^{kN/g} A^{N/g}, and N/g times its singular switches."""
    return dataclasses.replace(reduced, jacobian=symmetry.monodromy(reduced.jacobian),
                               singular=reduced.singular * symmetry.repeats)
