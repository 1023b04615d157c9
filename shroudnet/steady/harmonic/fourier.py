"""Truncated Fourier series of a periodic motion and the time samples they are read at.

A coordinate of an orbit of period T = 2π/ω is held by its 2H + 1 real coefficients,
in the order c = (c₀, a₁, b₁, …, a_H, b_H)::

    x(t) = c₀ + Σ_{k=1..H} (a_k cos kωt + b_k sin kωt)

so that harmonic k is the complex amplitude X_k = a_k − i b_k of x = Re(X_k e^{ikωt}).
The forces of the contacts are computed in time, at N evenly spaced samples
t_n = n T/N over one period (alternating frequency–time, AFT), and transformed back by
the discrete Fourier transform, which returns a series of degree H exactly where
N > 2H and where the sampled function has no harmonic above N − H − 1; beyond, higher
harmonics fold onto the kept ones (aliasing). A contact force with a kink (stick–slip,
a contact closing)
has harmonics decaying as 1/k², so its aliasing error decays as 1/N², while the error of
the truncated series itself, on the friction problems of the tests, falls about as
H⁻³ (the motion's harmonics decay as 1/k⁴ where the force has kinks): the samples grow
as H^{3/2} (``samples_for``), so that aliasing keeps pace with the truncation and never
caps the accuracy as H grows (at N = 16 H, the 2-DOF Jenkins chain's amplitude stalled
at 1e-5 from H = 15 to 35; at 8 H^{3/2} it is 2e-6 at H = 25 and 1e-6 at H = 35).
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from functools import cached_property

import numpy as np

#: N = ``SAMPLES_FACTOR`` · H^{3/2} time samples per period (``samples_for``; the
#: module's docstring says why the power, the tests measure the factor).
SAMPLES_FACTOR = 8.0
#: The fewest samples a period is evaluated at.
FEWEST_SAMPLES = 32


def samples_for(harmonics: int) -> int:
    """N = max(``FEWEST_SAMPLES``, ⌈``SAMPLES_FACTOR`` · H^{3/2}⌉): the time samples per
    period for a series of H harmonics (always > 2H): 32 up to H = 4, 149 at H = 7,
    1000 at H = 25."""
    return max(FEWEST_SAMPLES, math.ceil(SAMPLES_FACTOR * harmonics ** 1.5))


def coefficient_count(harmonics: int) -> int:
    """2H + 1."""
    return 2 * harmonics + 1


@dataclass(frozen=True, eq=False)
class FourierBasis:
    """The series of ``harmonics`` H harmonics of the fundamental ``frequency`` ω [rad/s]
    and its ``samples`` N time samples per period.

    ``synthesis`` (N × (2H+1)) gives the samples x(t_n) from the coefficients,
    ``rate`` the samples of ẋ(t_n), ``analysis`` ((2H+1) × N) the coefficients from
    samples (the discrete Fourier transform, exact on series of degree ≤ N − H − 1), and
    ``derivative`` ((2H+1) × (2H+1)) the coefficients of ẋ from those of x:
    a_k' = kω b_k, b_k' = −kω a_k.
    """

    harmonics: int
    frequency: float
    samples: int

    def __post_init__(self):
        if self.samples <= 2 * self.harmonics:
            raise ValueError(f"FourierBasis.samples must exceed 2 harmonics = "
                             f"{2 * self.harmonics}, got {self.samples}")

    @property
    def size(self) -> int:
        """2H + 1."""
        return coefficient_count(self.harmonics)

    @property
    def period(self) -> float:
        """T = 2π/ω [s]."""
        return 2.0 * math.pi / self.frequency

    @cached_property
    def times(self) -> np.ndarray:
        """t_n = n T/N [s], n = 0 … N − 1."""
        return np.arange(self.samples) * (self.period / self.samples)

    @cached_property
    def synthesis(self) -> np.ndarray:
        return series_matrix(self.harmonics, self.frequency, self.times)

    @cached_property
    def derivative(self) -> np.ndarray:
        return derivative_matrix(self.harmonics, self.frequency)

    @cached_property
    def rate(self) -> np.ndarray:
        return self.synthesis @ self.derivative

    @cached_property
    def analysis(self) -> np.ndarray:
        angles = np.outer(np.arange(1, self.harmonics + 1), 2.0 * math.pi
                          * np.arange(self.samples) / self.samples)
        matrix = np.empty((self.size, self.samples))
        matrix[0] = 1.0 / self.samples
        matrix[1::2] = 2.0 / self.samples * np.cos(angles)
        matrix[2::2] = 2.0 / self.samples * np.sin(angles)
        return matrix


def series_matrix(harmonics: int, frequency: float, times, order: int = 0) -> np.ndarray:
    """(len(times) × (2H+1)): the ``order``-th time derivative of each basis function
    (1, cos kωt, sin kωt) at ``times`` [s], so that ``series_matrix(...) @ c`` is
    x⁽ᵒʳᵈᵉʳ⁾(t)."""
    times = np.asarray(times, dtype=float)
    k = np.arange(1, harmonics + 1)
    angles = np.multiply.outer(times, k * frequency)
    matrix = np.empty(times.shape + (coefficient_count(harmonics),))
    matrix[..., 0] = 1.0 if order == 0 else 0.0
    # d^p/dt^p cos θ = (kω)^p cos(θ + pπ/2), and likewise for sin
    scale = (k * frequency) ** order
    shift = order * math.pi / 2.0
    matrix[..., 1::2] = scale * np.cos(angles + shift)
    matrix[..., 2::2] = scale * np.sin(angles + shift)
    return matrix


def derivative_matrix(harmonics: int, frequency: float) -> np.ndarray:
    """D ((2H+1) × (2H+1)) with D c the coefficients of ẋ (module docstring)."""
    size = coefficient_count(harmonics)
    matrix = np.zeros((size, size))
    for k in range(1, harmonics + 1):
        matrix[2 * k - 1, 2 * k] = k * frequency
        matrix[2 * k, 2 * k - 1] = -k * frequency
    return matrix


def complex_amplitudes(coefficients: np.ndarray) -> np.ndarray:
    """X_k = a_k − i b_k for k = 0 … H (row k; X_0 = c₀) from real coefficients
    ((2H+1) × m)."""
    amplitudes = np.empty(((coefficients.shape[0] + 1) // 2,) + coefficients.shape[1:],
                          dtype=complex)
    amplitudes[0] = coefficients[0]
    amplitudes[1:] = coefficients[1::2] - 1j * coefficients[2::2]
    return amplitudes


def real_coefficients(amplitudes: np.ndarray) -> np.ndarray:
    """The inverse of ``complex_amplitudes`` (the imaginary part of X_0 dropped)."""
    coefficients = np.empty((2 * amplitudes.shape[0] - 1,) + amplitudes.shape[1:])
    coefficients[0] = amplitudes[0].real
    coefficients[1::2] = amplitudes[1:].real
    coefficients[2::2] = -amplitudes[1:].imag
    return coefficients


def mean_product(first: np.ndarray, second: np.ndarray) -> np.ndarray:
    """(1/T)∫₀ᵀ x y dt of series x and y given by coefficients ((2H+1) × …, summed over
    the first axis): c₀c₀' + ½ Σ_k (a_k a_k' + b_k b_k') (Parseval)."""
    weights = np.full(first.shape[0], 0.5)
    weights[0] = 1.0
    return np.tensordot(weights, first * second, axes=(0, 0))


#: Points per harmonic period at which ``extremes`` looks for a series' largest and
#: least values before refining them by Newton's method.
SEARCH_POINTS = 16
#: Newton steps refining an extremum.
REFINE_STEPS = 6


def extremes(coefficients: np.ndarray, frequency: float) -> tuple[np.ndarray, np.ndarray]:
    """(max, min) over a period of each series (columns of ``coefficients``, (2H+1) × r):
    the largest and least of ``SEARCH_POINTS`` samples per period of the highest
    harmonic, each refined by Newton's method on x'(t) = 0 (the series' own derivatives,
    so exact to rounding where the sampled extremum lies in the basin of the true one)."""
    harmonics = (coefficients.shape[0] - 1) // 2
    count = SEARCH_POINTS * max(harmonics, 1)
    times = np.arange(count) * (2.0 * math.pi / frequency / count)
    values = series_matrix(harmonics, frequency, times) @ coefficients
    found = []
    for pick, sign in ((np.argmax, 1.0), (np.argmin, -1.0)):
        at = times[pick(values, axis=0)]
        columns = np.arange(coefficients.shape[1])
        best = values[pick(values, axis=0), columns]
        for _ in range(REFINE_STEPS):
            slope = np.einsum("rj,jr->r", series_matrix(harmonics, frequency, at, 1),
                              coefficients)
            curvature = np.einsum("rj,jr->r", series_matrix(harmonics, frequency, at, 2),
                                  coefficients)
            # a Newton step only where it heads for the extremum sought (curvature of
            # the right sign), within one search spacing
            step = np.where(sign * curvature < 0.0, -slope / np.where(
                curvature != 0.0, curvature, 1.0), 0.0)
            at = at + np.clip(step, -times[1], times[1])
        refined = np.einsum("rj,jr->r", series_matrix(harmonics, frequency, at), coefficients)
        found.append(np.maximum(best, refined) if sign > 0 else np.minimum(best, refined))
    return found[0], found[1]
