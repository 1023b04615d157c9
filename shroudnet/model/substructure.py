"""Substructures: nodes of a group that are linear structures with many degrees of freedom.

A substructure has n degrees of freedom q ∈ ℝⁿ and obeys

    M q̈ + C q̇ + K(Ω) q = s b Q(t) + Σ_p Φ_pᵀ f_p,        K(Ω) = K₀ + Ω² K₁,

with M symmetric positive definite, K₀ and C symmetric positive semi-definite, K₁ symmetric
(centrifugal stiffening and spin softening), b the load vector on which the excitation Q(t)
acts with the scale s, and f_p the force an interface puts on the **point** p, whose
displacement is r_p = Φ_p q (Φ_p of shape d × n, d ≤ 3). A ``Blade`` is the case n = d = 1.

The matrices come dense or as ``scipy.sparse`` matrices (a reader of FE files, a beam model)
or as modal data (``Substructure.modal``: what an FE modal analysis prints). Reductions of
large models (``reduction.craig_bampton``, ``reduction.modal_truncation``) return a small
substructure that keeps the basis T of q_full = T q.
"""

from __future__ import annotations

import math
from collections.abc import Mapping, Sequence
from dataclasses import KW_ONLY, dataclass
from numbers import Real
from types import MappingProxyType
from typing import NamedTuple

import numpy as np
import scipy.linalg
import scipy.sparse

from contact_laws import check_array, check_real

from .blade import ConstantFrequency, FrequencyTable, Southwell, frequency_of

#: Largest n for which ``matrices_at`` and ``modes_at`` build dense matrices.
DENSE_LIMIT = 5000
#: Largest n whose definiteness is checked on all eigenvalues at construction; a larger model
#: is checked on its diagonal only (a necessary condition), and the reductions, which
#: factorise it, report the rest.
DEFINITENESS_CHECK_LIMIT = 2000
#: A matrix is symmetric when max |A − Aᵀ| ≤ SYMMETRY_TOLERANCE · max |A|.
SYMMETRY_TOLERANCE = 1e-9
#: A matrix is positive semi-definite when λ_min ≥ −DEFINITENESS_TOLERANCE · max |λ|.
DEFINITENESS_TOLERANCE = 1e-9
#: A direction is a unit vector when | |n| − 1 | ≤ DIRECTION_TOLERANCE.
DIRECTION_TOLERANCE = 1e-9
#: The largest number of components of a point's displacement.
POINT_DIMENSIONS = 3

FREQUENCY_MODELS = (ConstantFrequency, Southwell, FrequencyTable)


class Matrices(NamedTuple):
    """M, C, K(Ω) of a substructure at one speed, dense, each n × n (SI units)."""

    mass: np.ndarray
    damping: np.ndarray
    stiffness: np.ndarray


class Modes(NamedTuple):
    """The undamped natural frequencies [Hz], ascending, and the mass-normalised mode shapes
    (column k of ``shapes`` is mode k, Φᵀ M Φ = I)."""

    frequencies: np.ndarray
    shapes: np.ndarray


# ---- checks shared by the modules that build substructures ---------------------------------

def square_matrix(name: str, value: object, n: int | None = None):
    """``value`` as a float n × n matrix: a read-only ndarray, or a ``csr_array`` if sparse.

    Raises ``TypeError`` for what is not a real matrix and ``ValueError`` naming ``name``
    for a wrong shape or a value that is not finite.
    """
    if scipy.sparse.issparse(value):
        if not np.issubdtype(value.dtype, np.number) or np.iscomplexobj(value):
            raise TypeError(f"{name} must hold real numbers, got dtype {value.dtype}")
        matrix = scipy.sparse.csr_array(value, dtype=float, copy=True)
        matrix.sum_duplicates()
        finite = bool(np.isfinite(matrix.data).all())
    else:
        matrix = _real_array(name, value)
        finite = bool(np.isfinite(matrix).all())
    if matrix.ndim != 2 or matrix.shape[0] != matrix.shape[1] or matrix.shape[0] == 0:
        raise ValueError(f"{name} must be a square matrix with at least one row, "
                         f"got shape {matrix.shape}")
    if n is not None and matrix.shape[0] != n:
        raise ValueError(f"{name} must be {n} × {n} like the mass, got {matrix.shape}")
    if not finite:
        raise ValueError(f"{name} must be finite, got NaN or inf entries")
    if not scipy.sparse.issparse(matrix):
        matrix.flags.writeable = False
    return matrix


def check_symmetric(name: str, matrix) -> None:
    """Raise ``ValueError`` unless max |A − Aᵀ| ≤ SYMMETRY_TOLERANCE · max |A|."""
    largest = _abs_max(matrix)
    asymmetry = _abs_max(matrix - matrix.T)
    if asymmetry > SYMMETRY_TOLERANCE * largest:
        raise ValueError(f"{name} must be symmetric: max |A − Aᵀ| = {asymmetry:.3g} exceeds "
                         f"{SYMMETRY_TOLERANCE:g} × max |A| = {largest:.3g}")


def check_definite(name: str, matrix, *, strict: bool) -> None:
    """Raise ``ValueError`` unless the symmetric ``matrix`` is positive definite (``strict``)
    or positive semi-definite to DEFINITENESS_TOLERANCE relative to its largest eigenvalue.

    All eigenvalues are checked up to DEFINITENESS_CHECK_LIMIT rows; a larger matrix is
    checked on its diagonal only, which a definite matrix must pass.
    """
    kind = "positive definite" if strict else "positive semi-definite"
    n = matrix.shape[0]
    if n > DEFINITENESS_CHECK_LIMIT:
        diagonal = matrix.diagonal()
        bad = diagonal <= 0.0 if strict else diagonal < 0.0
        if bad.any():
            index = int(np.flatnonzero(bad)[0])
            raise ValueError(f"{name} must be {kind}, but its diagonal entry {index} is "
                             f"{diagonal[index]:g}")
        return
    eigenvalues = scipy.linalg.eigvalsh(_dense(matrix))
    scale = max(abs(eigenvalues[0]), abs(eigenvalues[-1]))
    lowest = eigenvalues[0]
    if (strict and lowest <= 0.0) or lowest < -DEFINITENESS_TOLERANCE * scale:
        raise ValueError(f"{name} must be {kind}, but its lowest eigenvalue is {lowest:.6g} "
                         f"(largest magnitude {scale:.6g})")


def point_matrix(name: str, value: object, n: int) -> np.ndarray:
    """``value`` as a read-only d × n matrix Φ_p, 1 ≤ d ≤ 3 (a length-n vector is d = 1)."""
    if scipy.sparse.issparse(value):
        value = value.toarray()
    matrix = _real_array(name, value)
    if matrix.ndim == 1:
        matrix = matrix.reshape(1, -1)
    if matrix.ndim != 2 or matrix.shape[1] != n:
        raise ValueError(f"{name} must be a d × {n} matrix (or a vector of length {n}), one "
                         f"column per degree of freedom, got shape {matrix.shape}")
    if not 1 <= matrix.shape[0] <= POINT_DIMENSIONS:
        raise ValueError(f"{name} must have d = 1, 2 or 3 rows (components of the point's "
                         f"displacement), got d = {matrix.shape[0]}")
    if not np.isfinite(matrix).all():
        raise ValueError(f"{name} must be finite, got NaN or inf entries")
    matrix = matrix.copy()
    matrix.flags.writeable = False
    return matrix


def point_matrices(name: str, points: object, n: int) -> Mapping[str, np.ndarray]:
    """``points`` (a mapping name → Φ_p) as a read-only mapping of ``point_matrix`` values."""
    if not isinstance(points, Mapping):
        raise TypeError(f"{name} must be a mapping point name → d × n matrix, "
                        f"got {type(points).__name__}")
    checked = {}
    for key, value in points.items():
        if not isinstance(key, str) or not key:
            raise TypeError(f"{name} must be keyed by non-empty strings, got {key!r}")
        checked[key] = point_matrix(f"{name}[{key!r}]", value, n)
    return MappingProxyType(checked)


def load_vector(name: str, load: object, points: Mapping[str, np.ndarray], n: int) -> np.ndarray:
    """The load vector b ∈ ℝⁿ that ``load`` names (see ``Substructure``), read-only."""
    if load is None:
        if "load" not in points:
            vector = np.zeros(n)
        elif points["load"].shape[0] == 1:
            vector = points["load"][0].copy()
        else:
            raise ValueError(f"{name} is None and the point 'load' has d = "
                             f"{points['load'].shape[0]}: give load=('load', direction)")
    elif isinstance(load, str):
        matrix = _named_point(name, load, points)
        if matrix.shape[0] != 1:
            raise ValueError(f"{name} = {load!r} names a point with d = {matrix.shape[0]}: "
                             f"give load=({load!r}, direction) with a unit direction")
        vector = matrix[0].copy()
    elif is_point_load(load):
        matrix = _named_point(name, load[0], points)
        direction = unit_direction(f"{name} direction", load[1], matrix.shape[0])
        vector = matrix.T @ direction
    else:
        vector = _real_array(name, load)
        if vector.shape != (n,):
            raise ValueError(f"{name} must be a vector of {n} generalised forces, a point "
                             f"name or (point name, direction), got shape {vector.shape}")
        if not np.isfinite(vector).all():
            raise ValueError(f"{name} must be finite, got NaN or inf entries")
        vector = vector.copy()
    vector.flags.writeable = False
    return vector


def unit_direction(name: str, value: object, d: int) -> np.ndarray:
    """``value`` as a unit d-vector (| |n| − 1 | ≤ DIRECTION_TOLERANCE)."""
    direction = _real_array(name, value).reshape(-1)
    if direction.shape != (d,):
        raise ValueError(f"{name} must have {d} components like its point, "
                         f"got {direction.shape[0]}")
    norm = float(np.linalg.norm(direction))
    if not math.isfinite(norm) or abs(norm - 1.0) > DIRECTION_TOLERANCE:
        raise ValueError(f"{name} must be a unit vector (|n| = 1 within "
                         f"{DIRECTION_TOLERANCE:g}), got |n| = {norm:.12g}")
    return direction


def damping_ratios(owner: str, value: object, n: int) -> float | tuple[float, ...]:
    """ζ ≥ 0, one for all n modes (a float) or one per mode (a sequence of n), checked as
    ``owner.damping_ratios``."""
    if isinstance(value, Real) and not isinstance(value, bool):
        return check_real(owner, "damping_ratios", value, low=0.0)
    if isinstance(value, str) or not isinstance(value, Sequence | np.ndarray):
        raise TypeError(f"{owner}.damping_ratios must be a float or a sequence of floats, "
                        f"got {type(value).__name__}")
    ratios = tuple(check_real(owner, "damping_ratios", v, low=0.0)
                   for v in np.ravel(np.asarray(value, dtype=object)))
    if len(ratios) != n:
        raise ValueError(f"{owner}.damping_ratios must hold one ratio for all modes or one "
                         f"per mode ({n}), got {len(ratios)}")
    return ratios


def is_point_load(load: object) -> bool:
    """Whether ``load`` names a point (a name, or a (name, direction) pair) rather than
    giving the load vector itself."""
    return isinstance(load, str) or (isinstance(load, tuple) and len(load) == 2
                                     and isinstance(load[0], str))


def _real_array(name: str, value: object) -> np.ndarray:
    try:
        array = np.asarray(value)
    except (TypeError, ValueError) as error:
        raise TypeError(f"{name} must be an array of real numbers: {error}") from None
    if array.dtype == bool or not (np.issubdtype(array.dtype, np.integer)
                                   or np.issubdtype(array.dtype, np.floating)):
        raise TypeError(f"{name} must be an array of real numbers, got dtype {array.dtype}")
    return np.array(array, dtype=float)


def _named_point(name: str, point: str, points: Mapping[str, np.ndarray]) -> np.ndarray:
    if point not in points:
        raise ValueError(f"{name} names the unknown point {point!r}; the points are "
                         f"{sorted(points)}")
    return points[point]


def _abs_max(matrix) -> float:
    if scipy.sparse.issparse(matrix):
        return float(abs(matrix).max()) if matrix.nnz else 0.0
    return float(np.abs(matrix).max())


def _dense(matrix) -> np.ndarray:
    return matrix.toarray() if scipy.sparse.issparse(matrix) else np.array(matrix)


# ---- the substructure --------------------------------------------------------------------------

@dataclass(frozen=True, eq=False, repr=False)
class Substructure:
    """A linear structure with n degrees of freedom q and named points r_p = Φ_p q.

        M q̈ + C q̇ + (K₀ + Ω² K₁) q = s b Q(t) + Σ_p Φ_pᵀ f_p

    Parameters
    ----------
    mass : (n, n) array or scipy.sparse matrix
        M, symmetric positive definite [kg, or the units that make M q̈ a generalised force].
    stiffness : (n, n) array or scipy.sparse matrix
        K₀, the stiffness at rest, symmetric positive semi-definite [N/m]. ``None`` only for a
        modal substructure (``modal_frequencies`` given), whose stiffness follows from them.
    damping : (n, n) array or scipy.sparse matrix, optional
        C, symmetric positive semi-definite [N·s/m].
    damping_ratios : float or sequence of float, optional
        Modal damping instead of ``damping``: ζ ≥ 0 for every mode, or one per mode (mode k
        the k-th lowest at the speed asked for). C = M Φ diag(2 ζ_k ω_k) Φᵀ M, with Φ and
        ω_k the mass-normalised modes and natural frequencies [rad/s] of K(Ω), so that mode k
        decays with the damping ratio ζ_k. Neither this nor ``damping``: undamped.
    stiffness_speed : (n, n) array or scipy.sparse matrix, optional
        K₁, symmetric, so that K(Ω) = K₀ + Ω² K₁ with Ω the rotating speed [rad/s]
        (centrifugal stiffening, spin softening) [N·s²/m].
    points : mapping str → (d, n) array
        The points interfaces may join: r_p = Φ_p q [m], 1 ≤ d ≤ 3 (a vector of length n is
        d = 1). Required; may be empty.
    load : (n,) array, str or (str, (d,) array), optional
        Where the excitation Q(t) [N] acts: b, the generalised forces per unit Q; or the name
        of a point with d = 1 (b = Φ_pᵀ); or (name, unit direction e) (b = Φ_pᵀ e). None: the
        point named "load" if there is one with d = 1, else b = 0 (an unloaded node).
    excitation_scale : float
        s, a signed participation factor on Q(t) [-]; 0 is an unforced node.
    modal_frequencies : tuple of frequency models, optional
        Set by ``Substructure.modal``: q are modal amplitudes, M = diag(m_k) and
        K(Ω) = diag(m_k (2π f_k(Ω))²), C = diag(2 ζ_k m_k 2π f_k(Ω)) (mode k in the given
        order, whatever the speed).
    basis : (N, n) array, optional
        Set by the reductions: q_full = T q, the full model's degrees of freedom (see
        ``expand``).

    Matrices are validated at construction (shape, finite, symmetric to SYMMETRY_TOLERANCE,
    definite to DEFINITENESS_TOLERANCE). Speeds are given to the methods in rev/min
    (``speed_rpm``), Ω = 2π speed_rpm / 60.

    Examples
    --------
    >>> import numpy as np
    >>> two_masses = Substructure(np.eye(2), np.array([[2.0, -1.0], [-1.0, 1.0]]),
    ...                           points={"tip": [0.0, 1.0]}, load="tip")
    >>> two_masses
    Substructure(n_dofs=2, points=['tip'])
    >>> np.round(two_masses.frequencies_at(0.0) * 2 * np.pi, 4)
    array([0.618, 1.618])
    """

    mass: object
    stiffness: object
    damping: object = None
    _: KW_ONLY
    damping_ratios: float | tuple[float, ...] | None = None
    stiffness_speed: object = None
    points: Mapping[str, np.ndarray]
    load: object = None
    excitation_scale: float = 1.0
    modal_frequencies: tuple | None = None
    basis: np.ndarray | None = None

    def __post_init__(self):
        owner = "Substructure"
        mass = square_matrix(f"{owner}.mass", self.mass)
        n = mass.shape[0]
        check_symmetric(f"{owner}.mass", mass)
        check_definite(f"{owner}.mass", mass, strict=True)
        object.__setattr__(self, "mass", mass)
        modal = self.modal_frequencies is not None
        if modal:
            self._check_modal(mass)
        elif self.stiffness is None:
            raise ValueError(f"{owner}.stiffness is required (None only for a modal "
                             "substructure, see Substructure.modal)")
        for field, strict in (("stiffness", False), ("damping", False),
                              ("stiffness_speed", None)):
            value = getattr(self, field)
            if value is None:
                continue
            matrix = square_matrix(f"{owner}.{field}", value, n)
            check_symmetric(f"{owner}.{field}", matrix)
            if strict is not None:
                check_definite(f"{owner}.{field}", matrix, strict=strict)
            object.__setattr__(self, field, matrix)
        if self.damping is not None and self.damping_ratios is not None:
            raise ValueError(f"{owner} takes damping= (a matrix C) or damping_ratios= (modal "
                             "damping), not both")
        if self.damping_ratios is not None:
            object.__setattr__(self, "damping_ratios",
                               damping_ratios(owner, self.damping_ratios, n))
        points = point_matrices(f"{owner}.points", self.points, n)
        object.__setattr__(self, "points", points)
        object.__setattr__(self, "_load_vector",
                           load_vector(f"{owner}.load", self.load, points, n))
        if self.load is not None and not is_point_load(self.load):
            object.__setattr__(self, "load", self._load_vector)
        object.__setattr__(self, "excitation_scale",
                           check_real(owner, "excitation_scale", self.excitation_scale))
        if self.basis is not None:
            basis = _real_array(f"{owner}.basis", self.basis)
            if basis.ndim != 2 or basis.shape[1] != n or not np.isfinite(basis).all():
                raise ValueError(f"{owner}.basis must be a finite N × {n} matrix "
                                 f"(q_full = T q), got shape {basis.shape}")
            basis.flags.writeable = False
            object.__setattr__(self, "basis", basis)

    def _check_modal(self, mass) -> None:
        owner = "Substructure"
        if isinstance(self.modal_frequencies, str | bytes | np.ndarray) \
                or not isinstance(self.modal_frequencies, tuple | list):
            raise TypeError(f"{owner}.modal_frequencies must be a sequence of frequency models, "
                            f"got {type(self.modal_frequencies).__name__}")
        models = tuple(self.modal_frequencies)
        n = mass.shape[0]
        if len(models) != n:
            raise ValueError(f"{owner}.modal_frequencies must hold one frequency per mode "
                             f"({n}), got {len(models)}")
        for model in models:
            if not isinstance(model, FREQUENCY_MODELS):
                raise TypeError(f"{owner}.modal_frequencies must hold frequency models "
                                "(ConstantFrequency, Southwell, FrequencyTable), got "
                                f"{type(model).__name__}")
        dense = _dense(mass)
        if np.any(dense != np.diag(np.diag(dense))):
            raise ValueError(f"{owner}.mass of a modal substructure must be diagonal "
                             "(the modal masses)")
        for field in ("stiffness", "damping", "stiffness_speed"):
            if getattr(self, field) is not None:
                raise ValueError(f"{owner}.{field} must be None for a modal substructure: "
                                 "its matrices follow from modal_frequencies")
        object.__setattr__(self, "modal_frequencies", models)

    @classmethod
    def modal(cls, frequencies, damping_ratios, masses, shapes, load=None,
              excitation_scale=1.0) -> Substructure:
        """A substructure in modal coordinates, from what an FE modal analysis prints.

        The coordinates are the modal amplitudes η_k, k = 1 … n:

            m_k η̈_k + 2 ζ_k m_k ω_k(Ω) η̇_k + m_k ω_k(Ω)² η_k = s b_k Q(t) + Σ_p (Φ_pᵀ f_p)_k,

        with ω_k = 2π f_k(Ω): M = diag(m_k), K(Ω) = diag(m_k ω_k²), C = diag(2 ζ_k m_k ω_k).

        Parameters
        ----------
        frequencies : sequence of float or frequency model
            f_k [Hz], one per mode: a float (constant) or a ``ConstantFrequency``,
            ``Southwell`` or ``FrequencyTable`` so that f_k depends on the speed.
        damping_ratios : float or sequence of float
            ζ_k ≥ 0, one for all modes or one per mode.
        masses : float or sequence of float
            m_k > 0, the modal masses [kg] (1 for mass-normalised shapes).
        shapes : mapping str → (d, n) array
            Each point's displacement per unit η_k [m] (column k), d ≤ 3; a vector of length
            n is d = 1.
        load, excitation_scale
            As for ``Substructure``.

        Examples
        --------
        >>> blade = Substructure.modal([Southwell(f0=500.0, coefficient=4.0), 1800.0], 0.002,
        ...                            0.05, {"shroud": [1.0, -0.4]})
        >>> blade.frequencies_at(0.0)
        array([ 500., 1800.])
        """
        if isinstance(frequencies, str) or not isinstance(frequencies, Sequence | np.ndarray):
            raise TypeError("Substructure.modal frequencies must be a sequence, one per mode, "
                            f"got {type(frequencies).__name__}")
        models = []
        for frequency in frequencies:
            if not isinstance(frequency, FREQUENCY_MODELS):
                check_real("Substructure.modal", "frequencies", frequency, low=0.0,
                           low_open=True, unit="Hz")
                frequency = ConstantFrequency(hz=float(frequency))
            models.append(frequency)
        n = len(models)
        if n == 0:
            raise ValueError("Substructure.modal frequencies must hold at least one mode")
        if isinstance(masses, Real) and not isinstance(masses, bool):
            masses = [masses] * n
        masses = [check_real("Substructure.modal", "masses", m, low=0.0, low_open=True,
                             unit="kg") for m in np.ravel(np.asarray(masses, dtype=object))]
        if len(masses) != n:
            raise ValueError(f"Substructure.modal masses must hold one mass for all modes or "
                             f"one per mode ({n}), got {len(masses)}")
        return cls(np.diag(masses), None, damping_ratios=damping_ratios, points=shapes,
                   load=load, excitation_scale=excitation_scale, modal_frequencies=tuple(models))

    # ---- reading ---------------------------------------------------------------------------

    @property
    def n_dofs(self) -> int:
        """n, the number of degrees of freedom."""
        return self.mass.shape[0]

    @property
    def load_vector(self) -> np.ndarray:
        """b ∈ ℝⁿ, the generalised forces per unit excitation Q (without the scale s)."""
        return self._load_vector

    def point(self, name: str) -> np.ndarray:
        """Φ_p, the d × n matrix of r_p = Φ_p q for the point ``name``."""
        return _named_point(f"Substructure.point({name!r})", name, self.points)

    def expand(self, q: np.ndarray) -> np.ndarray:
        """q_full = T q: the full model's degrees of freedom from those of a reduction.

        ``q`` has n rows (a state of n, or n × k: one column per instant); another length
        is refused naming ``Substructure.expand.q``.
        """
        if self.basis is None:
            raise ValueError("Substructure.expand needs a basis: this substructure is not a "
                             "reduction (craig_bampton, modal_truncation)")
        try:
            columns = np.ndim(q) == 2
        except ValueError:  # a ragged nesting, which check_array refuses
            columns = False
        q = check_array("Substructure.expand", "q", q,
                        shape=(self.n_dofs, None) if columns else (self.n_dofs,))
        return self.basis @ q

    def __repr__(self) -> str:
        extras = []
        if self.modal_frequencies is not None:
            extras.append("modal")
        if self.stiffness_speed is not None:
            extras.append("speed-dependent")
        if self.basis is not None:
            extras.append(f"reduced from {self.basis.shape[0]}")
        extra = "".join(f", {text}" for text in extras)
        return f"Substructure(n_dofs={self.n_dofs}, points={list(self.points)}{extra})"

    # ---- matrices at a speed -------------------------------------------------------------------

    def matrices_at(self, speed_rpm: float) -> Matrices:
        """M, C, K(Ω) as dense n × n arrays at the rotating speed ``speed_rpm`` [rev/min]."""
        omega = self._omega(speed_rpm, "matrices_at")
        mass = _dense(self.mass)
        if self.modal_frequencies is not None:
            masses = np.diag(mass)
            circular = self._modal_circular(speed_rpm)
            ratios = np.broadcast_to(np.asarray(self.damping_ratios or 0.0, dtype=float),
                                     (self.n_dofs,))
            with np.errstate(over="ignore"):
                stiffness = np.diag(masses * circular**2)
            _check_finite(stiffness, "m ω(Ω)² of its modes", speed_rpm)
            return Matrices(mass, np.diag(2.0 * ratios * masses * circular), stiffness)
        stiffness = _dense(self.stiffness)
        if self.stiffness_speed is not None:
            with np.errstate(over="ignore", invalid="ignore"):
                stiffness = stiffness + np.float64(omega) ** 2 * _dense(self.stiffness_speed)
            _check_finite(stiffness, "K₀ + Ω² K₁", speed_rpm)
        if self.damping is not None:
            damping = _dense(self.damping)
        elif self.damping_ratios is None or not np.any(self.damping_ratios):
            damping = np.zeros_like(mass)
        else:
            circular, shapes = _eigen(mass, stiffness)
            ratios = np.broadcast_to(np.asarray(self.damping_ratios, dtype=float), circular.shape)
            weighted = mass @ shapes
            damping = (weighted * (2.0 * ratios * circular)) @ weighted.T
            damping = 0.5 * (damping + damping.T)
        return Matrices(mass, damping, stiffness)

    def modes_at(self, speed_rpm: float) -> Modes:
        """The undamped natural frequencies [Hz], ascending, and mass-normalised mode shapes
        (n × n, Φᵀ M Φ = I) at ``speed_rpm`` [rev/min], with nothing attached to the points.
        """
        self._omega(speed_rpm, "modes_at")
        if self.modal_frequencies is not None:
            circular = self._modal_circular(speed_rpm)
            order = np.argsort(circular, kind="stable")
            shapes = np.diag(1.0 / np.sqrt(np.diag(_dense(self.mass))))[:, order]
            return Modes(circular[order] / (2.0 * math.pi), shapes)
        matrices = self.matrices_at(speed_rpm)
        circular, shapes = _eigen(matrices.mass, matrices.stiffness)
        return Modes(circular / (2.0 * math.pi), shapes)

    def frequencies_at(self, speed_rpm: float) -> np.ndarray:
        """The undamped natural frequencies [Hz], ascending, at ``speed_rpm`` [rev/min]."""
        return self.modes_at(speed_rpm).frequencies

    def _omega(self, speed_rpm: float, method: str) -> float:
        speed = check_real(f"Substructure.{method}", "speed_rpm", speed_rpm, low=0.0,
                           unit="rpm")
        if self.n_dofs > DENSE_LIMIT:
            raise ValueError(f"Substructure.{method} builds dense matrices and this "
                             f"substructure has n = {self.n_dofs} > {DENSE_LIMIT} degrees of "
                             "freedom: reduce the model first with craig_bampton or "
                             "modal_truncation")
        return 2.0 * math.pi * speed / 60.0

    def _modal_circular(self, speed_rpm: float) -> np.ndarray:
        """ω [rad/s] of each mode at ``speed_rpm``; inf where its model overflows."""
        return np.array([2.0 * math.pi * frequency_of(model, speed_rpm)
                         for model in self.modal_frequencies])


def _check_finite(stiffness: np.ndarray, what: str, speed_rpm: float) -> None:
    """Refuse a stiffness matrix K(Ω) that overflows a float at ``speed_rpm``."""
    if not np.isfinite(stiffness).all():
        raise ValueError(f"Substructure.matrices_at: K(Ω) = {what} overflows a float at "
                         f"speed_rpm = {speed_rpm:g}; check the units of the speed (rev/min)")


def _eigen(mass: np.ndarray, stiffness: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """ω [rad/s], ascending, and mass-normalised shapes of K φ = ω² M φ (dense)."""
    eigenvalues, shapes = scipy.linalg.eigh(stiffness, mass)
    scale = max(abs(eigenvalues[0]), abs(eigenvalues[-1]))
    if eigenvalues[0] < -DEFINITENESS_TOLERANCE * scale:
        raise ValueError(f"K(Ω) is not positive semi-definite at this speed (lowest "
                         f"eigenvalue ω² = {eigenvalues[0]:.6g} rad²/s²): the structure "
                         "diverges statically")
    return np.sqrt(np.clip(eigenvalues, 0.0, None)), shapes
