"""An independent event-driven reference for structures of many degrees of freedom.

A linear structure of n degrees of freedom q with contacts, DESIGN §7::

    M q̈ + C q̇ + K q = F(t) − Σ_e (N_e n_e + f_e t_e),        q ∈ ℝⁿ

    F(t) = F_0 + Σ_h (F_h^c cos(h ω t) + F_h^s sin(h ω t)),   h = 1 … H

integrated with plain ``scipy.integrate.solve_ivp`` and numpy: per set of contact modes a
numpy right-hand side, an event function for every guard, and a restart at every switch.
It shares no code with the compiled engine (``shroudnet.engine``; only the ``Mode`` codes
are read from it) nor with ``shroudnet.references.blades`` (the one-mass-blade reference), so the
tests use it as a check of both and of the general structures built on them.

Contact e has a normal row n_e and a tangent row t_e (any vectors of ℝⁿ: neither parallel
nor orthogonal is assumed), a gap Δ_e, a normal law and a friction law (``contact_laws``)::

    penetration  δ_e = n_e·q − Δ_e   (> 0: closed),   its rate  δ̇_e = n_e·q̇
    slip velocity  s_e = t_e·q̇

    force on q from contact e:   − N_e n_e − f_e t_e

        slipping with s_e > 0:   q̇·t_e > 0  ──▶
        friction on q:                ◀──  −f_e t_e,   f_e = +μ(|s_e|) N_e > 0
        power taken out:  f_e s_e ≥ 0

Modes per contact (``Mode``): OPEN (δ ≤ 0: N = 0, f = 0); SLIP_POSITIVE / SLIP_NEGATIVE
(N = N(δ, δ̇), f = ±μ(|s|) N); STICK (t_e·q̇ = 0 held rigidly while the contact is closed;
N = N(δ, δ̇) still acts along n_e, since the normal relative motion stays free unless n_e
is parallel to t_e). A frictionless contact, a regularised one (f = μ(|s|) N tanh(s/v_ε))
and one whose tangent row is zero never stick: closed, they are SLIP_POSITIVE, the sign
unused. A contact whose normal law does not open (``ConstantLoad``) is never OPEN.

Stick. The stuck tangent rows stacked in G hold G q̇ = 0 with M q̈ = R − Gᵀλ, where
R = F − C q̇ − K q − Σ_closed N n − Σ_slipping f t; so

    λ = (G M⁻¹ Gᵀ)⁺ G M⁻¹ R,       q̈ = M⁻¹ (R − Gᵀ λ),

the pseudo-inverse giving the least-norm λ where stuck rows are redundant. λ_e takes the
place of f_e: the force on q is −λ_e t_e, so λ_e > 0 holds back a motion towards s_e > 0,
and a contact that breaks away (|λ_e| reaching μ_s N_e) slips with s_e of the sign of λ_e
(SLIP_POSITIVE when λ_e > 0), its friction f_e = ±μ(0⁺) N_e then of the sign λ_e had. At
stick onset the velocity is projected M-orthogonally onto the constraints,
q̇ ← q̇ − M⁻¹Gᵀ(G M⁻¹ Gᵀ)⁺ G q̇: the momentum M q̇ along every motion the constraints allow
is kept, the kinetic energy of the rest (booked as ``projection`` work) is lost.

Guards (terminal ``solve_ivp`` events, each with direction −1, a guard g falling to 0):
a closed contact that can open, g = δ (separation); an open one, g = −δ (closing); a
slipping contact that can stick, g = ±s (slip velocity reaching 0); a stuck one,
g = μ_s N − |λ| (breakaway). solve_ivp sees a crossing only as a change of sign between
step ends, and takes a guard at 0 at a step's start for the root. So a guard that starts
a segment at or below 0 (a rounding error on the far side of a switch just made) is
shifted by that much to start just above 0: a crossing back within the first step is then
found where it lies. A guard that dips below 0 and comes back within one step (a contact
that barely grazes) is missed, as by any reference built on solve_ivp's events.

The mode rule at a switch (terminating: every contact sticks at most once and is released
at most once in it):

1. The located guard fires, and so does every other guard below 0 at the switch state
   (two guards crossing in one step), falling to 0 within 1e-12·max(t, 2π/ω) seconds
   (``_TOGETHER``; ω the excitation's frequency, else the highest natural one), or, for a
   breakaway margin, within 1e-12·μ_s N of 0: crossings that are one in exact arithmetic,
   as in a symmetric group, switch together. Per contact a contact guard comes first:
   closing gives SLIP± by the sign of s (STICK if s = 0 and the contact can stick),
   separation OPEN; a slip velocity at 0 gives STICK; breakaway gives SLIP± by the sign
   of λ (the contact is *released*).
2. Repeat: project the velocity before the switch onto the stuck set; if a slipping
   contact that can stick, and was not released, now has s against its slip sign, it
   sticks; else if a stuck contact needs |λ| > μ_s N, release the one with the largest
   |λ|/(μ_s N), to SLIP± by the sign of its λ; else stop. A slip velocity that reached 0
   where stick is not admissible so reverses (or, with λ of the old sign, slips on).

A run whose switches make no progress in time (more than ``4 m + 10`` in a row at one
instant, m contacts) or exceed ``max_switches`` stops with a ``RuntimeError``.
"""

from __future__ import annotations

import math
from collections.abc import Callable, Sequence
from dataclasses import dataclass
from typing import Any

import numpy as np
import scipy.linalg
from scipy.integrate import solve_ivp

from contact_laws.base import ZERO_PLUS_SPEED

from ..engine.codes import Mode

OPEN, STICK, SLIP_POSITIVE, SLIP_NEGATIVE = (int(Mode.OPEN), int(Mode.STICK),
                                             int(Mode.SLIP_POSITIVE), int(Mode.SLIP_NEGATIVE))

#: Columns of ``StructureRun.work`` [J], cumulative from t = 0: the excitation's work ∫F·q̇
#: (in); the viscous loss ∫q̇ᵀCq̇, the friction loss ∫Σ f s over slipping contacts, the
#: contact work ∫Σ N δ̇ over closed contacts and the kinetic energy removed by the
#: projections at stick onset (out). Stored energy ½q̇ᵀMq̇ + ½qᵀKq changes by in − out.
WORK_COLUMNS = ("excitation", "damping", "friction", "contact", "projection")

#: What a located switch did to the contact whose guard was located: closed, opened, stuck,
#: slipped the other way, broke away, or nothing ("touch": a slip velocity that touched 0
#: and slipped on the same way).
SWITCH_KINDS = ("closing", "separation", "sticking", "reversal", "breakaway", "touch")

#: Relative asymmetry allowed in M and K (the stored energy needs symmetric matrices).
_SYMMETRY = 1e-12
#: A guard that falls to 0 within this fraction of max(t, 2π/ω) seconds of a located
#: switch switches with it: the rounding of the location, and of guards that are one in
#: exact arithmetic (a symmetric group), is far below it.
_TOGETHER = 1e-12
#: Added to every guard: the smallest positive normal double, lost beside any value above
#: about 1e-290, so it moves a guard that is exactly 0 only.
_START = float(np.finfo(float).tiny)
#: Relative size of the penetration on the wrong side of 0 that ``modes0`` may be given
#: with: a state taken at a located switch lies a rounding error from δ = 0.
_MODES_SLACK = 1e-9


def _matrix(name: str, value, n: int | None) -> np.ndarray:
    array = np.array(value, dtype=float)
    if array.ndim != 2 or array.shape[0] != array.shape[1] or (n is not None
                                                              and array.shape[0] != n):
        size = "n × n" if n is None else f"{n} × {n}"
        raise ValueError(f"StructureProblem.{name} must be a square {size} matrix, "
                         f"got shape {array.shape}")
    if not np.all(np.isfinite(array)):
        raise ValueError(f"StructureProblem.{name} must be finite")
    array.setflags(write=False)
    return array


def _vector(owner: str, name: str, value, n: int) -> np.ndarray:
    array = np.array(value, dtype=float)
    if array.shape != (n,):
        raise ValueError(f"{owner}.{name} must have shape ({n},), got {array.shape}")
    if not np.all(np.isfinite(array)):
        raise ValueError(f"{owner}.{name} must be finite")
    array.setflags(write=False)
    return array


def _symmetric(name: str, matrix: np.ndarray) -> None:
    if np.abs(matrix - matrix.T).max(initial=0.0) > _SYMMETRY * np.abs(matrix).max(initial=0.0):
        raise ValueError(f"StructureProblem.{name} must be symmetric")


@dataclass(frozen=True, eq=False)
class Contact:
    """One contact of a ``StructureProblem``: δ = n·q − Δ, δ̇ = n·q̇, s = t·q̇.

    Parameters
    ----------
    normal_row : (n,) array
        n_e [-]: the penetration's row (zero for a contact whose normal force is given,
        e.g. a ``ConstantLoad``).
    tangent_row : (n,) array
        t_e [-]: the slip velocity's row; zero for a contact that carries no friction.
    gap : float
        Δ_e [m] (negative: preload).
    normal_law
        Called as ``normal_law(δ, δ̇)`` → N [N]; its ``opens`` says whether the contact can
        open (``contact_laws.NormalLaw``).
    friction_law
        None (frictionless) or called as ``friction_law(|s|)`` → μ, with
        ``static_coefficient`` μ_s and ``regularisation_velocity`` v_ε (0 for an exact
        law), as ``contact_laws.FrictionLaw``.
    """

    normal_row: np.ndarray
    tangent_row: np.ndarray
    gap: float
    normal_law: Any
    friction_law: Any = None

    def __post_init__(self):
        for name in ("normal_row", "tangent_row"):
            array = np.array(getattr(self, name), dtype=float)
            if array.ndim != 1 or not np.all(np.isfinite(array)):
                raise ValueError(f"Contact.{name} must be a finite vector, got {array!r}")
            array.setflags(write=False)
            object.__setattr__(self, name, array)
        if self.normal_row.shape != self.tangent_row.shape:
            raise ValueError("Contact.normal_row and Contact.tangent_row must have one length,"
                             f" got {self.normal_row.shape} and {self.tangent_row.shape}")
        gap = float(self.gap)
        if not math.isfinite(gap):
            raise ValueError(f"Contact.gap must be finite [m], got {self.gap!r}")
        object.__setattr__(self, "gap", gap)
        if not callable(self.normal_law) or not hasattr(self.normal_law, "opens"):
            raise TypeError("Contact.normal_law must be callable as law(penetration, rate) "
                            f"and say whether it opens (.opens), got {self.normal_law!r}")
        if self.friction_law is not None and not (
                callable(self.friction_law)
                and hasattr(self.friction_law, "static_coefficient")
                and hasattr(self.friction_law, "regularisation_velocity")):
            raise TypeError("Contact.friction_law must be None or callable as law(speed) with "
                            ".static_coefficient and .regularisation_velocity, got "
                            f"{self.friction_law!r}")

    @property
    def opens(self) -> bool:
        """Whether the contact can open (its normal law's ``opens``)."""
        return bool(self.normal_law.opens)

    @property
    def can_stick(self) -> bool:
        """Exact (unregularised) friction along a tangent row that is not zero."""
        return (self.friction_law is not None
                and self.friction_law.regularisation_velocity == 0.0
                and bool(np.any(self.tangent_row != 0.0)))

    @property
    def static_mu(self) -> float:
        """μ_s, 0 without friction."""
        return 0.0 if self.friction_law is None else float(self.friction_law.static_coefficient)


@dataclass(frozen=True, eq=False)
class StructureProblem:
    """M q̈ + C q̇ + K q = F(t) − Σ_e (N_e n_e + f_e t_e), as plain arrays (module docstring).

    Parameters
    ----------
    mass, damping, stiffness : (n, n) arrays
        M [kg] (symmetric positive definite), C [N·s/m], K [N/m] (symmetric).
    force_static : (n,) array
        F_0 [N].
    force_cos, force_sin : (H, n) arrays
        Row h − 1 holds F_h^c and F_h^s [N], the amplitudes of cos(h ω t) and sin(h ω t).
    frequency : float
        ω ≥ 0 [rad/s], the fundamental of the excitation; its period 2π/ω is the one the
        stroboscopic points are taken at.
    contacts : sequence of Contact
    """

    mass: np.ndarray
    damping: np.ndarray
    stiffness: np.ndarray
    force_static: np.ndarray
    force_cos: np.ndarray
    force_sin: np.ndarray
    frequency: float
    contacts: tuple[Contact, ...] = ()

    def __post_init__(self):
        mass = _matrix("mass", self.mass, None)
        n = mass.shape[0]
        if n == 0:
            raise ValueError("StructureProblem.mass must have at least one degree of freedom")
        _symmetric("mass", mass)
        if np.linalg.eigvalsh(mass).min() <= 0.0:
            raise ValueError("StructureProblem.mass must be positive definite")
        stiffness = _matrix("stiffness", self.stiffness, n)
        _symmetric("stiffness", stiffness)
        object.__setattr__(self, "mass", mass)
        object.__setattr__(self, "stiffness", stiffness)
        object.__setattr__(self, "damping", _matrix("damping", self.damping, n))
        object.__setattr__(self, "force_static",
                           _vector("StructureProblem", "force_static", self.force_static, n))
        for name in ("force_cos", "force_sin"):
            array = np.array(getattr(self, name), dtype=float)
            if array.size == 0:
                array = np.zeros((0, n))
            if array.ndim != 2 or array.shape[1] != n or not np.all(np.isfinite(array)):
                raise ValueError(f"StructureProblem.{name} must be a finite (H, {n}) array")
            array.setflags(write=False)
            object.__setattr__(self, name, array)
        if self.force_cos.shape != self.force_sin.shape:
            raise ValueError("StructureProblem.force_cos and force_sin must have one shape "
                             f"(H, n), got {self.force_cos.shape} and {self.force_sin.shape}")
        frequency = float(self.frequency)
        if not (math.isfinite(frequency) and frequency >= 0.0):
            raise ValueError(f"StructureProblem.frequency must be >= 0 [rad/s], got "
                             f"{self.frequency!r}")
        object.__setattr__(self, "frequency", frequency)
        contacts = tuple(self.contacts)
        for e, contact in enumerate(contacts):
            if not isinstance(contact, Contact):
                raise TypeError(f"StructureProblem.contacts[{e}] must be a Contact, got "
                                f"{contact!r}")
            if contact.normal_row.shape != (n,):
                raise ValueError(f"StructureProblem.contacts[{e}] has rows of length "
                                 f"{contact.normal_row.shape[0]}, the structure {n}")
        object.__setattr__(self, "contacts", contacts)

    @property
    def n_dof(self) -> int:
        return self.mass.shape[0]

    @property
    def n_contacts(self) -> int:
        return len(self.contacts)

    @property
    def period(self) -> float:
        """2π/ω [s]."""
        if self.frequency <= 0.0:
            raise ValueError("StructureProblem.period needs frequency > 0")
        return 2.0 * math.pi / self.frequency

    def force(self, t: float) -> np.ndarray:
        """F(t) [N]."""
        angle = np.arange(1, len(self.force_cos) + 1) * (self.frequency * t)
        return self.force_static + np.cos(angle) @ self.force_cos + np.sin(angle) @ self.force_sin


def shroud_contact(n_dof: int, left: int | None, right: int | None, *, gap: float,
                   angle: float, normal_law, friction_law) -> Contact:
    """The one-coordinate shroud contact of DESIGN §2 between coordinates ``left`` (i) and
    ``right`` (j) (None: a fixed node): n = sin α (e_i − e_j), t = cos α (e_i − e_j),
    Δ_e = gap·sin α, so that δ = (x_i − x_j − gap) sin α and s = (ẋ_i − ẋ_j) cos α.
    At α = π/2, cos α is taken as exactly 0 (no friction along the coordinates)."""
    direction = np.zeros(n_dof)
    if left is not None:
        direction[left] += 1.0
    if right is not None:
        direction[right] -= 1.0
    cos_angle = 0.0 if angle == math.pi / 2 else math.cos(angle)
    return Contact(normal_row=math.sin(angle) * direction, tangent_row=cos_angle * direction,
                   gap=gap * math.sin(angle), normal_law=normal_law, friction_law=friction_law)


def structure_from_scene(scene) -> StructureProblem:
    """The ``StructureProblem`` of a ``Scene`` of one-coordinate blades (no prescribed-
    motion nodes): M = diag(m), C and K with the couplings, the excitation
    Q_i = s_i [q_0 + Σ_n q_n sin(n (lΩ t + φ_i))] written as cosines and sines of n lΩ t,
    and one ``shroud_contact`` per interface."""
    if any(interface.tangential_stiffness is not None
           for _, _, interface in scene.group.interfaces):
        raise ValueError("structure_from_scene takes rigid stick only, not an elastic "
                         "contact (Interface.tangential_stiffness)")
    a = scene.arrays
    n = a.n_blades
    if a.n_prescribed:
        raise ValueError("structure_from_scene: a scene with prescribed-motion nodes has no "
                         "StructureProblem (its motion is not an unknown)")
    # a sin(θ + nφ) = a sin(nφ) cos θ + a cos(nφ) sin θ, θ = n lΩ t.
    amplitudes, phases = a.harmonic_amplitudes, a.harmonic_phases
    contacts = []
    for e in range(a.n_interfaces):
        direction = np.zeros(n)
        if a.left[e] >= 0:
            direction[a.left[e]] += 1.0
        if a.right[e] >= 0:
            direction[a.right[e]] -= 1.0
        contacts.append(Contact(normal_row=a.sin_angle[e] * direction,
                                tangent_row=a.cos_angle[e] * direction,
                                gap=a.gap[e] * a.sin_angle[e], normal_law=a.normal_laws[e],
                                friction_law=a.friction_laws[e]))
    return StructureProblem(
        mass=np.diag(a.mass), damping=a.damping_matrix(), stiffness=a.stiffness_matrix(),
        force_static=amplitudes[0], force_cos=amplitudes[1:] * np.sin(phases[1:]),
        force_sin=amplitudes[1:] * np.cos(phases[1:]), frequency=a.excitation_frequency,
        contacts=tuple(contacts))


def structure_from_substructures(scene) -> StructureProblem:
    """The ``StructureProblem`` of a ``Scene`` whose nodes are substructures (``Blade``s
    not, nor prescribed-motion nodes), built from each substructure's own matrices and
    points in its physical degrees of freedom, side by side in the order of the scene's
    nodes (not from the coordinates the engine lowers the scene to): M, C, K block by
    block; per interface between points a and b (per pair of points of a patch: a contact
    each), in the group's frame (nodes' frames Q turn their points and the left one's
    the interface's directions), n = (Q_a n̂)·(Q_a Φ_a − Q_b Φ_b) and
    t = (Q_a t̂)·(Q_a Φ_a − Q_b Φ_b), Δ = the gap; node i's load s_i b_i, forced as
    Q_i = q_0 + Σ_h q_h sin(h (lΩ t + φ_i))."""
    group = scene.group
    bodies = [group.blade(name) for name in scene.blades]
    if any(interface.tangential_stiffness is not None or interface.tangent_direction is None
           and interface.normal_direction is not None for _, _, interface in group.interfaces):
        raise ValueError("structure_from_substructures takes rigid contacts of one tangent "
                         "direction only, not elastic ones (Interface.tangential_stiffness)")
    if group.prescribed or any(not hasattr(body, "matrices_at") for body in bodies):
        raise ValueError("structure_from_substructures takes scenes of substructures only, "
                         "with no prescribed-motion nodes")
    blocks = [body.matrices_at(scene.speed_rpm) for body in bodies]
    mass, damping, stiffness = (scipy.linalg.block_diag(*(block[k] for block in blocks))
                                for k in range(3))
    offsets = np.cumsum([0] + [body.n_dofs for body in bodies])
    n = int(offsets[-1])

    def turned(node, vectors):
        """``vectors`` (rows of a point's components) of ``node``'s frame in the group's:
        Q v, for points of as many components as its frame has."""
        frame = group.frame(node) if node in scene.blades else None
        if frame is None or vectors.shape[0] != frame.shape[0]:
            return vectors
        return frame @ vectors

    def point(node, name):
        """A point's displacement in the group's frame, Q Φ_p, over all the dofs."""
        if node not in scene.blades:  # a fixed node
            return 0.0
        i = scene.blades.index(node)
        rows = np.zeros((bodies[i].point(name).shape[0], n))
        rows[:, offsets[i]:offsets[i + 1]] = bodies[i].point(name)
        return turned(node, rows)

    contacts = []
    for (left, right, interface), pairs in zip(group.interfaces,
                                               group.point_pairs("interface")):
        normal, tangent = (turned(left, np.asarray(direction, dtype=float)[:, None])[:, 0]
                           for direction in (interface.normal_direction,
                                             interface.tangent_direction))
        for a, b in pairs:  # a patch: a contact per pair of points
            relative = point(left, a) - point(right, b)
            contacts.append(Contact(normal @ relative, tangent @ relative, interface.gap,
                                    interface.normal, interface.friction))
    excitation = scene.excitation
    phases = excitation.blade_phases(len(bodies))
    loads = []
    for i, body in enumerate(bodies):
        load = np.zeros(n)
        load[offsets[i]:offsets[i + 1]] = body.excitation_scale * body.load_vector
        loads.append(load)
    harmonics = len(excitation.amplitudes) - 1
    force_cos, force_sin = np.zeros((harmonics, n)), np.zeros((harmonics, n))
    for h in range(1, harmonics + 1):  # q_h sin(hθ + hφ) = q_h (sin hθ cos hφ + cos hθ sin hφ)
        for phase, load in zip(phases, loads):
            force_sin[h - 1] += excitation.amplitudes[h] * math.cos(h * phase) * load
            force_cos[h - 1] += excitation.amplitudes[h] * math.sin(h * phase) * load
    return StructureProblem(mass, damping, stiffness, excitation.amplitudes[0] * sum(loads),
                            force_cos, force_sin, scene.arrays.excitation_frequency,
                            tuple(contacts))


def stored_energy(problem: StructureProblem, q, v) -> np.ndarray:
    """½ q̇ᵀ M q̇ + ½ qᵀ K q [J], of one state or of rows of states."""
    q, v = np.asarray(q, dtype=float), np.asarray(v, dtype=float)
    return 0.5 * (np.einsum("...i,ij,...j->...", v, problem.mass, v)
                  + np.einsum("...i,ij,...j->...", q, problem.stiffness, q))


@dataclass(frozen=True, eq=False)
class ContactForces:
    """The dynamics of one set of modes at one (t, q, q̇)."""

    acceleration: np.ndarray  # q̈ (n,) [m/s²]
    normal: np.ndarray        # N_e (m,) [N], 0 where open
    friction: np.ndarray      # f_e (m,) [N] where slipping, λ_e (static friction) where stuck
    penetration: np.ndarray   # δ_e (m,) [m]
    rate: np.ndarray          # δ̇_e (m,) [m/s]
    slip: np.ndarray          # s_e (m,) [m/s]
    power: np.ndarray         # (4,) [W]: F·q̇, q̇ᵀCq̇, Σ f s slipping, Σ N δ̇ closed


@dataclass(frozen=True)
class _Constraints:
    """The stick operators of one set of modes."""

    stuck: np.ndarray          # indices of the stuck contacts
    rows: np.ndarray           # G (k, n)
    inverse_rows: np.ndarray   # M⁻¹ Gᵀ (n, k)
    pseudo_inverse: np.ndarray  # (G M⁻¹ Gᵀ)⁺ (k, k)


@dataclass(frozen=True)
class _Guard:
    contact: int
    kind: str                  # "contact", "slip" or "stick"
    sign: float                # ±1: g = sign·δ ("contact"), g = sign·s ("slip"); 1 ("stick")
    function: Callable


class _Equations:
    """The problem's equations in numpy, for any set of modes."""

    def __init__(self, problem: StructureProblem):
        self.problem = problem
        n, m = problem.n_dof, problem.n_contacts
        self.n, self.m = n, m
        self.normal_rows = np.array([c.normal_row for c in problem.contacts]).reshape(m, n)
        self.tangent_rows = np.array([c.tangent_row for c in problem.contacts]).reshape(m, n)
        self.gaps = np.array([c.gap for c in problem.contacts], dtype=float)
        self.opens = np.array([c.opens for c in problem.contacts], dtype=bool)
        self.can_stick = np.array([c.can_stick for c in problem.contacts], dtype=bool)
        self.static_mu = np.array([c.static_mu for c in problem.contacts], dtype=float)
        self.inverse_mass = np.linalg.inv(problem.mass)
        self.time_scale = 2.0 * math.pi / _reference_frequency(problem)
        self._constraints: dict[bytes, _Constraints] = {}

    def kinematics(self, q, v):
        """(δ, δ̇, s) of every contact."""
        return self.normal_rows @ q - self.gaps, self.normal_rows @ v, self.tangent_rows @ v

    def constraints(self, modes) -> _Constraints:
        key = np.asarray(modes, dtype=np.int64).tobytes()
        if key not in self._constraints:
            stuck = np.flatnonzero(np.asarray(modes) == STICK)
            rows = self.tangent_rows[stuck]
            inverse_rows = self.inverse_mass @ rows.T
            self._constraints[key] = _Constraints(
                stuck=stuck, rows=rows, inverse_rows=inverse_rows,
                pseudo_inverse=np.linalg.pinv(rows @ inverse_rows) if len(stuck)
                else np.zeros((0, 0)))
        return self._constraints[key]

    def evaluate(self, modes, t, q, v) -> ContactForces:
        problem = self.problem
        penetration, rate, slip = self.kinematics(q, v)
        normal = np.zeros(self.m)
        friction = np.zeros(self.m)
        for e in np.flatnonzero(np.asarray(modes) != OPEN):
            contact = problem.contacts[e]
            normal[e] = contact.normal_law(penetration[e], rate[e])
            law = contact.friction_law
            if law is None or modes[e] == STICK:
                continue
            regularisation = law.regularisation_velocity
            if regularisation > 0.0:
                friction[e] = law(abs(slip[e])) * normal[e] * math.tanh(slip[e] / regularisation)
            else:  # a slip mode at |s| = 0 (just broken away) takes μ(0⁺)
                sliding = law(max(abs(slip[e]), ZERO_PLUS_SPEED)) * normal[e]
                friction[e] = sliding if modes[e] == SLIP_POSITIVE else -sliding
        force = problem.force(t)
        damping = problem.damping @ v
        resultant = (force - damping - problem.stiffness @ q - self.normal_rows.T @ normal
                     - self.tangent_rows.T @ friction)
        acceleration = self.inverse_mass @ resultant
        constraints = self.constraints(modes)
        if len(constraints.stuck):
            static = constraints.pseudo_inverse @ (constraints.rows @ acceleration)
            acceleration = acceleration - constraints.inverse_rows @ static
            friction[constraints.stuck] = static
        slipping = (np.asarray(modes) == SLIP_POSITIVE) | (np.asarray(modes) == SLIP_NEGATIVE)
        power = np.array([force @ v, v @ damping, friction[slipping] @ slip[slipping],
                          normal @ rate])
        return ContactForces(acceleration=acceleration, normal=normal, friction=friction,
                             penetration=penetration, rate=rate, slip=slip, power=power)

    def project(self, modes, v) -> np.ndarray:
        """q̇ − M⁻¹Gᵀ(G M⁻¹ Gᵀ)⁺ G q̇: M-orthogonally onto the stuck rows' null space."""
        constraints = self.constraints(modes)
        if not len(constraints.stuck):
            return np.array(v, dtype=float)
        return v - constraints.inverse_rows @ (constraints.pseudo_inverse
                                               @ (constraints.rows @ v))

    def right_hand_side(self, modes) -> Callable:
        n = self.n

        def rhs(t, y):
            forces = self.evaluate(modes, t, y[:n], y[n:2 * n])
            return np.concatenate([y[n:2 * n], forces.acceleration, forces.power])
        return rhs

    def guards(self, modes, t0, y0) -> list[_Guard]:
        """Every guard that can fall to 0 under ``modes`` (module docstring), each shifted
        to start at or above 0 at (t0, y0)."""
        n = self.n
        found = []
        for e in range(self.m):
            mode = modes[e]
            if self.opens[e]:
                sign = -1.0 if mode == OPEN else 1.0
                row, gap = self.normal_rows[e], self.gaps[e]
                found.append(_Guard(e, "contact", sign, _terminal(
                    lambda t, y, s=sign, row=row, gap=gap: s * (row @ y[:n] - gap), t0, y0)))
            if mode == STICK:
                def margin(t, y, e=e):
                    forces = self.evaluate(modes, t, y[:n], y[n:2 * n])
                    return self.static_mu[e] * forces.normal[e] - abs(forces.friction[e])
                found.append(_Guard(e, "stick", 1.0, _terminal(margin, t0, y0)))
            elif mode != OPEN and self.can_stick[e]:
                sign = 1.0 if mode == SLIP_POSITIVE else -1.0
                row = self.tangent_rows[e]
                found.append(_Guard(e, "slip", sign, _terminal(
                    lambda t, y, s=sign, row=row: s * (row @ y[n:2 * n]), t0, y0)))
        return found


def _terminal(guard, t0, y0):
    """``guard`` − min(guard(t0, y0), 0) + ``_START`` as a terminal solve_ivp event falling
    through 0.

    A guard just switched, or one that crossed with another, can start a rounding error
    below 0, or at 0 itself; solve_ivp sees a crossing only as a change of sign between
    two step ends, and takes a guard at 0 at a step's start for the root. So shifted, the
    guard starts just above 0 (``_START`` vanishes beside any value it is added to but 0),
    and a crossing back within the first step (a contact that separates and closes again
    within it) is found where it lies, not at the step's start."""
    offset = min(guard(t0, y0), 0.0)

    def event(t, y):
        return guard(t, y) - offset + _START
    # solve_ivp reads these two attributes; they are set here only, where guards are made.
    event.terminal = True
    event.direction = -1.0
    return event


def _closed_mode(equations: _Equations, e: int, slip: float) -> int:
    """The mode of contact e closing (or found closed) with slip velocity ``slip``."""
    if not equations.can_stick[e]:
        return SLIP_POSITIVE
    if slip > 0.0:
        return SLIP_POSITIVE
    return SLIP_NEGATIVE if slip < 0.0 else STICK


def _slip_mode(static: float) -> int:
    """The slip mode of a contact released with static friction λ: slip the way λ held."""
    return SLIP_POSITIVE if static > 0.0 else SLIP_NEGATIVE


def _consistent(equations: _Equations, modes, released, t, q, v):
    """Step 2 of the mode rule: (modes, projected velocity) with every stuck contact within
    its friction limit and every slipping one on its own side of s = 0."""
    modes = np.array(modes, dtype=np.int64)
    released = np.array(released, dtype=bool)
    for _ in range(2 * equations.m + 1):
        projected = equations.project(modes, v)
        forces = equations.evaluate(modes, t, q, projected)
        sign = np.where(modes == SLIP_POSITIVE, 1.0, np.where(modes == SLIP_NEGATIVE, -1.0, 0.0))
        crossed = equations.can_stick & ~released & (sign * forces.slip < 0.0)
        if crossed.any():
            modes[crossed] = STICK
            continue
        stuck = modes == STICK
        limit = equations.static_mu * np.maximum(forces.normal, 0.0)
        held = np.abs(forces.friction)
        ratio = np.zeros(equations.m)
        ratio[stuck] = np.divide(held[stuck], limit[stuck], out=np.full(stuck.sum(), np.inf),
                                 where=limit[stuck] > 0.0)
        ratio[stuck & (held == 0.0)] = 0.0
        worst = int(np.argmax(ratio)) if equations.m else 0
        if not equations.m or ratio[worst] <= 1.0:
            return modes, projected
        modes[worst] = _slip_mode(forces.friction[worst])
        released[worst] = True
    raise RuntimeError(f"no consistent contact modes at t = {t:.12g} s")


def _fired(equations: _Equations, guards: list[_Guard], located: int, before: ContactForces,
           t, y) -> set[int]:
    """Step 1 of the mode rule: the guards that switch at ``t``, the located one and those
    below 0 or falling to 0 within ``_TOGETHER`` time scales (a breakaway margin: within
    ``_TOGETHER`` μ_s N of 0)."""
    window = _TOGETHER * max(abs(t), equations.time_scale)
    fired = {located}
    for k, guard in enumerate(guards):
        e = guard.contact
        value = guard.function(t, y) - _START
        if guard.kind == "stick":  # its rate would need λ̇: the margin's size decides
            together = value <= _TOGETHER * equations.static_mu[e] * before.normal[e]
        else:
            rate = guard.sign * (before.rate[e] if guard.kind == "contact"
                                 else equations.tangent_rows[e] @ before.acceleration)
            together = value < 0.0 or (rate < 0.0 and value <= -rate * window)
        if together:
            fired.add(k)
    return fired


def _switch(equations: _Equations, modes, guards: list[_Guard], located: int, t, q, v):
    """Step 1 and 2 of the mode rule at a located switch: (modes, projected velocity)."""
    before = equations.evaluate(modes, t, q, v)
    fired = _fired(equations, guards, located, before, t, np.concatenate([q, v]))
    order = {"contact": 0, "slip": 1, "stick": 1}
    by_contact: dict[int, str] = {}
    for k in sorted(fired, key=lambda k: order[guards[k].kind]):
        by_contact.setdefault(guards[k].contact, guards[k].kind)
    new = np.array(modes, dtype=np.int64)
    released = np.zeros(equations.m, dtype=bool)
    for e, kind in by_contact.items():
        if kind == "contact":
            new[e] = (OPEN if modes[e] != OPEN
                      else _closed_mode(equations, e, before.slip[e]))
        elif kind == "slip":
            new[e] = STICK
        else:
            new[e] = _slip_mode(before.friction[e])
            released[e] = True
    return _consistent(equations, new, released, t, q, v)


def _kind(old: int, new: int) -> str:
    if old == OPEN and new != OPEN:
        return "closing"
    if old != OPEN and new == OPEN:
        return "separation"
    if new == STICK and old != STICK:
        return "sticking"
    if old == STICK and new != STICK:
        return "breakaway"
    if old != new:
        return "reversal"
    return "touch"


@dataclass(frozen=True, eq=False)
class StructureRun:
    """A run of ``run_structure``: samples, switches and the final state.

    ``q`` and ``v`` at a sample that falls on a switch are the left limits (before any
    velocity projection). ``work`` columns are ``WORK_COLUMNS`` [J], cumulative from t = 0;
    ``stored`` is ½q̇ᵀMq̇ + ½qᵀKq [J]. Switch k was located at ``switch_times[k]`` on
    contact ``switch_contacts[k]``, which it made ``switch_kinds[k]`` (``SWITCH_KINDS``); it
    left the modes ``switch_modes[k]`` and turned the velocity ``velocity_before[k]`` into
    ``velocity_after[k]``.
    """

    problem: StructureProblem
    times: np.ndarray            # (k,) [s]
    q: np.ndarray                # (k, n) [m]
    v: np.ndarray                # (k, n) [m/s]
    work: np.ndarray             # (k, 5) [J]
    stored: np.ndarray           # (k,) [J]
    switch_times: np.ndarray     # (s,) [s]
    switch_contacts: np.ndarray  # (s,) contact index
    switch_kinds: tuple[str, ...]
    switch_modes: np.ndarray     # (s, m) ``Mode`` codes after the switch
    velocity_before: np.ndarray  # (s, n) [m/s]
    velocity_after: np.ndarray   # (s, n) [m/s]
    initial_modes: np.ndarray    # (m,) the modes the run started in
    t_end: float
    q_end: np.ndarray
    v_end: np.ndarray
    modes_end: np.ndarray
    work_end: np.ndarray         # (5,) [J]


def contact_forces(problem: StructureProblem, modes, t: float, q, v) -> ContactForces:
    """The accelerations, normal forces and friction (λ where stuck) under ``modes`` at
    (t, q, q̇)."""
    return _Equations(problem).evaluate(np.asarray(modes, dtype=np.int64), float(t),
                                        np.asarray(q, dtype=float), np.asarray(v, dtype=float))


def project_velocity(problem: StructureProblem, modes, v) -> np.ndarray:
    """q̇ − M⁻¹Gᵀ(G M⁻¹ Gᵀ)⁺ G q̇ for the contacts stuck in ``modes``."""
    return _Equations(problem).project(np.asarray(modes, dtype=np.int64),
                                       np.asarray(v, dtype=float))


def initial_modes(problem: StructureProblem, q0, v0, t0: float = 0.0):
    """(modes, projected velocity) from the state: closed where δ > 0 (or the contact cannot
    open), slipping by the sign of s, stuck where s = 0 and the static friction holds; by
    step 2 of the mode rule."""
    equations = _Equations(problem)
    q0, v0 = np.asarray(q0, dtype=float), np.asarray(v0, dtype=float)
    penetration, _, slip = equations.kinematics(q0, v0)
    modes = np.array([OPEN if equations.opens[e] and penetration[e] <= 0.0
                      else _closed_mode(equations, e, slip[e]) for e in range(equations.m)],
                     dtype=np.int64)
    return _consistent(equations, modes, np.zeros(equations.m, dtype=bool), t0, q0, v0)


def _check_modes(equations: _Equations, modes, q) -> np.ndarray:
    modes = np.array(modes, dtype=np.int64)
    if modes.shape != (equations.m,) or not np.isin(modes, [int(m) for m in Mode]).all():
        raise ValueError(f"modes0 must hold {equations.m} Mode codes, got {modes!r}")
    penetration = equations.normal_rows @ q - equations.gaps
    # A state from a switch may lie a rounding error on the far side of δ = 0.
    slack = _MODES_SLACK * (np.abs(equations.normal_rows) @ np.abs(q) + np.abs(equations.gaps))
    for e, mode in enumerate(modes):
        if mode == OPEN and (not equations.opens[e] or penetration[e] > slack[e]):
            raise ValueError(f"modes0[{e}] is OPEN where the contact is closed")
        if mode != OPEN and equations.opens[e] and penetration[e] < -slack[e]:
            raise ValueError(f"modes0[{e}] is closed where the contact is open (δ < 0)")
        if mode == STICK and not equations.can_stick[e]:
            raise ValueError(f"modes0[{e}] is STICK where the contact cannot stick")
    return modes


def _reference_frequency(problem: StructureProblem) -> float:
    """ω [rad/s] of the excitation, else the highest undamped natural frequency, else 1."""
    if problem.frequency > 0.0:
        return problem.frequency
    highest = np.linalg.eigvals(np.linalg.solve(problem.mass, problem.stiffness)).real.max()
    return math.sqrt(highest) if highest > 0.0 else 1.0


def _tolerances(problem: StructureProblem, rtol: float, atol) -> tuple[float, np.ndarray]:
    """(rtol, atol) of the state [q, q̇, work]. The work integrals ride along with the steps
    but take no part in their error control (atol = ∞); the motion's tolerances are scaled
    by √(2n/(2n + 4)) to undo the larger count in solve_ivp's RMS error norm, so the steps
    are the motion's own."""
    n = problem.n_dof
    atol = np.asarray(atol, dtype=float)
    if atol.ndim == 0:
        scale = _reference_frequency(problem)
        atol = np.concatenate([np.full(n, float(atol)), np.full(n, float(atol) * scale)])
    if atol.shape != (2 * n,) or np.any(atol <= 0.0) or not np.all(np.isfinite(atol)):
        raise ValueError(f"atol must be > 0: a number or {2 * n} values (q then q̇)")
    if not (math.isfinite(rtol) and rtol > 0.0):
        raise ValueError(f"rtol must be > 0, got {rtol!r}")
    shrink = math.sqrt(2 * n / (2 * n + 4))
    return rtol * shrink, np.concatenate([atol * shrink, np.full(4, np.inf)])


def run_structure(problem: StructureProblem, q0, v0, t_end: float, *, rtol: float = 1e-10,
                  atol=1e-13, t_eval: Sequence[float] | None = None, modes0=None,
                  method: str = "DOP853", max_switches: int = 100_000) -> StructureRun:
    """Integrate ``problem`` from (q0, q̇0) at t = 0 to ``t_end`` [s], event by event.

    Parameters
    ----------
    rtol, atol
        solve_ivp's tolerances. ``atol`` [m] is that of q; a number sets q̇'s to atol·ω
        [m/s] (ω the excitation's frequency, else the highest undamped natural frequency),
        or give 2n values (q then q̇).
    t_eval
        Sample times in [0, t_end], increasing; None samples 0 and t_end. Each is taken
        from the dense output of the segment it falls in.
    modes0
        The initial ``Mode`` codes; by default ``initial_modes``. Either way the initial
        velocity is projected onto the stuck contacts and the set made consistent by the
        mode rule (a stuck contact beyond its friction limit is released).
    method
        An explicit Runge–Kutta method of solve_ivp ("DOP853", "RK45", "RK23").
    max_switches
        The most switches before the run stops with a ``RuntimeError``.
    """
    if method not in ("DOP853", "RK45", "RK23"):
        raise ValueError(f"method must be 'DOP853', 'RK45' or 'RK23', got {method!r}")
    t_end = float(t_end)
    if not (math.isfinite(t_end) and t_end > 0.0):
        raise ValueError(f"t_end must be > 0 [s], got {t_end!r}")
    equations = _Equations(problem)
    n, m = equations.n, equations.m
    q = _vector("run_structure", "q0", q0, n).copy()
    v = _vector("run_structure", "v0", v0, n).copy()
    samples = np.array([0.0, t_end] if t_eval is None else t_eval, dtype=float).reshape(-1)
    if len(samples) and (samples[0] < 0.0 or samples[-1] > t_end
                         or np.any(np.diff(samples) < 0.0)):
        raise ValueError("t_eval must increase within [0, t_end]")
    rtol, atol = _tolerances(problem, float(rtol), atol)
    if modes0 is None:
        modes, v_start = initial_modes(problem, q, v)
    else:
        modes, v_start = _consistent(equations, _check_modes(equations, modes0, q),
                                     np.zeros(m, dtype=bool), 0.0, q, v)
    start_modes = modes.copy()
    projection = 0.5 * (v @ problem.mass @ v - v_start @ problem.mass @ v_start)
    v = v_start
    work = np.zeros(4)
    out_t, out_y, out_projection = [], [], []
    switches: dict[str, list] = {key: [] for key in ("t", "contact", "kind", "modes",
                                                       "before", "after")}
    t, idle, taken = 0.0, 0, 0
    while True:
        start = np.concatenate([q, v, work])
        guards = equations.guards(modes, t, start)
        solution = solve_ivp(equations.right_hand_side(modes), (t, t_end), start,
                             method=method, rtol=rtol, atol=atol,
                             dense_output=True, events=[g.function for g in guards] or None)
        if solution.status < 0:
            raise RuntimeError(f"solve_ivp failed after t = {t:.12g} s: {solution.message}")
        reached = float(solution.t[-1])  # t_end, or the switch
        upto = int(np.searchsorted(samples, reached, side="right"))
        points, taken = samples[taken:upto], max(taken, upto)
        if len(points):
            out_t.extend(points)
            out_y.extend(np.reshape(solution.sol(points), (2 * n + 4, -1)).T)
            out_projection.extend([projection] * len(points))
        final = solution.y[:, -1]
        if solution.status == 0:
            break
        located = next(k for k, times in enumerate(solution.t_events) if len(times))
        t_switch = float(solution.t_events[located][0])
        y = solution.y_events[located][0]
        q, v_before, work = y[:n].copy(), y[n:2 * n].copy(), y[2 * n:].copy()
        new, v = _switch(equations, modes, guards, located, t_switch, q, v_before)
        projection += 0.5 * (v_before @ problem.mass @ v_before - v @ problem.mass @ v)
        contact = guards[located].contact
        switches["t"].append(t_switch)
        switches["contact"].append(contact)
        switches["kind"].append(_kind(modes[contact], new[contact]))
        switches["modes"].append(new.copy())
        switches["before"].append(v_before)
        switches["after"].append(v.copy())
        idle = idle + 1 if t_switch <= t else 0
        if idle > 4 * m + 10:
            raise RuntimeError(f"switches make no progress at t = {t_switch:.12g} s "
                               "(a Zeno point or a mode rule that cannot settle)")
        if len(switches["t"]) > max_switches:
            raise RuntimeError(f"more than {max_switches} switches by t = {t_switch:.12g} s")
        modes, t = new, t_switch
    y_out = np.array(out_y).reshape(-1, 2 * n + 4)
    work_out = np.column_stack([y_out[:, 2 * n:], np.array(out_projection)])
    return StructureRun(
        problem=problem, times=np.array(out_t), q=y_out[:, :n], v=y_out[:, n:2 * n],
        work=work_out, stored=stored_energy(problem, y_out[:, :n], y_out[:, n:2 * n]),
        switch_times=np.array(switches["t"]),
        switch_contacts=np.array(switches["contact"], dtype=np.int64),
        switch_kinds=tuple(switches["kind"]),
        switch_modes=np.array(switches["modes"], dtype=np.int64).reshape(len(switches["t"]), m),
        velocity_before=np.array(switches["before"]).reshape(len(switches["t"]), n),
        velocity_after=np.array(switches["after"]).reshape(len(switches["t"]), n),
        initial_modes=start_modes, t_end=t_end, q_end=final[:n], v_end=final[n:2 * n],
        modes_end=modes, work_end=np.concatenate([final[2 * n:], [projection]]))


def strobe_structure(problem: StructureProblem, q0, v0, periods: int,
                     **options) -> StructureRun:
    """``run_structure`` over ``periods`` excitation periods T = 2π/ω, sampled at t = k T
    (k = 0 … periods): the stroboscopic (Poincaré) points are ``run.q`` and ``run.v``.
    ``options`` are those of ``run_structure`` but ``t_eval``."""
    if not isinstance(periods, int | np.integer) or periods < 1:
        raise ValueError(f"periods must be an integer >= 1, got {periods!r}")
    period = problem.period
    return run_structure(problem, q0, v0, periods * period,
                         t_eval=period * np.arange(periods + 1), **options)
