"""Stability of a harmonic-balance orbit by Hill's method.

A perturbation of the orbit x(t) is sought as e^{λt} p(t) with p periodic, of the same H
harmonics. Linearised about the orbit, M ẍ + C ẋ + K x + Gᵀ λ_c(G x, G ẋ) = Q becomes
the quadratic eigenvalue problem (Krack & Gross 2019, §5.3; Lazarus & Thomas 2010)

    (A₀ + λ A₁ + λ² A₂) P = 0,        A₀ = ∂R/∂X,
    A₁ = I ⊗ C + 2 D ⊗ M + Gᵀ ∂λ̂/∂ż G,   A₂ = I ⊗ M,

over the coefficients P of p (n(2H+1) of them, harmonic-major): A₀ the Jacobian of the
balance in every coordinate (K, C and M through the derivative matrix D, and the
contacts' forces' Jacobian, ``aft``), A₁ what a factor e^{λt} adds through ṗ → ṗ + λp
(the contacts' part only for forces that depend on ṙ: damped normal laws and
regularised friction). Its 2n(2H+1) eigenvalues come in families λ + ikω that all stand
for one Floquet exponent; of each family the one whose eigenvector is most centred on
harmonic 0 (the smallest |Σ_k k |p_k|²| / Σ_k |p_k|² over the complex harmonics
k = −H … H) is kept, 2n in all, and the Floquet multipliers are μ = e^{λT}.

Where Hill's method is not to be trusted: it linearises the forces as the Fourier
series sees them. For smooth laws (a contact that stays closed, a regularised law) the
kept exponents converge to the exact Floquet exponents as H grows. At a contact that
closes and opens, or sticks and slips, the exact linearisation has saltations at the
switches that no series of H harmonics carries, and an elastic contact's slider is a
state of its own (its multipliers, 0 where it slips, are not among Hill's): there the
multipliers converge slowly or not at all, and stability near the unit circle is a
guess. Worse, a slider that slips forgets a constant offset, so the periodic Jacobian of
its force has no column for the mean, and e^{λt} φ with (K + λC + λ²M) φ = 0 solves
Hill's problem exactly: on the 2-DOF Jenkins chain Hill's multipliers are the open
structure's at every H (0.35 from the exact ones), and on the six-blade packet with
elastic faces Hill's largest has modulus 2.3 where the exact orbit's is 0.88.
``HarmonicOrbit.smooth`` says which orbits Hill's method is to be trusted on; ``certify``
gives the exact multipliers.
"""

from __future__ import annotations

import math

import numpy as np

from .fourier import FourierBasis
from .model import HarmonicModel


def hill_matrices(model: HarmonicModel, basis: FourierBasis, contact_jacobian: np.ndarray,
                  velocity_jacobian: np.ndarray):
    """(A₀, A₁, A₂) of the module's equation, each n(2H+1) square."""
    size = basis.size
    identity = np.eye(size)
    derivative = basis.derivative
    rows = np.kron(identity, model.rows)
    first = (np.kron(identity, model.stiffness) + np.kron(derivative, model.damping)
             + np.kron(derivative @ derivative, model.mass)
             + rows.T @ contact_jacobian @ rows)
    second = (np.kron(identity, model.damping) + 2.0 * np.kron(derivative, model.mass)
              + rows.T @ velocity_jacobian @ rows)
    return first, second, np.kron(identity, model.mass)


def centring(vectors: np.ndarray, harmonics: int, n: int) -> np.ndarray:
    """|Σ_k k |p_k|²| / Σ_k |p_k|² of each eigenvector (columns of ``vectors``, n(2H+1)
    long: the real coefficients of p, complex) over its complex harmonics p_{±k} =
    (a_k ∓ i b_k)/2."""
    coefficients = vectors.reshape(2 * harmonics + 1, n, -1)
    a, b = coefficients[1::2], coefficients[2::2]
    positive = (np.abs(a - 1j * b) ** 2).sum(axis=1) / 4.0
    negative = (np.abs(a + 1j * b) ** 2).sum(axis=1) / 4.0
    total = (np.abs(coefficients[0]) ** 2).sum(axis=0) + positive.sum(axis=0) \
        + negative.sum(axis=0)
    k = np.arange(1, harmonics + 1)[:, None]
    return np.abs((k * (positive - negative)).sum(axis=0)) / total


def hill_exponents(model: HarmonicModel, basis: FourierBasis, contact_jacobian: np.ndarray,
                   velocity_jacobian: np.ndarray) -> np.ndarray:
    """The 2n Floquet exponents [1/s] Hill's method keeps (module docstring), by
    descending real part."""
    first, second, third = hill_matrices(model, basis, contact_jacobian, velocity_jacobian)
    size = first.shape[0]
    inverse_mass = 1.0 / np.diag(third)
    companion = np.zeros((2 * size, 2 * size))
    companion[:size, size:] = np.eye(size)
    companion[size:, :size] = -inverse_mass[:, None] * first
    companion[size:, size:] = -inverse_mass[:, None] * second
    values, vectors = np.linalg.eig(companion)
    n = model.n_coordinates
    score = centring(vectors[:size], basis.harmonics, n)
    # most centred first; among equals, the smaller |Im λ| (the family's central member)
    order = np.lexsort((np.abs(values.imag), np.round(score, 9)))
    kept = values[order[:2 * n]]
    return kept[np.argsort(-kept.real, kind="stable")]


def multipliers_of(exponents: np.ndarray, period: float) -> np.ndarray:
    """μ = e^{λT} by descending modulus."""
    values = np.exp(exponents.astype(complex) * period)
    return values[np.argsort(-np.abs(values), kind="stable")]


def orbit_period(basis: FourierBasis) -> float:
    """T = 2π/ω [s]."""
    return 2.0 * math.pi / basis.frequency
