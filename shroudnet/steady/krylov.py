"""Krylov methods on a matrix known only by its products: GMRES for Newton's linear
systems and Arnoldi for the leading eigenvalues (matrix-free shooting, DESIGN §8).

Both build an orthonormal basis Q_m of the Krylov space span{b, A b, …, A^{m−1} b} one
product at a time, the Arnoldi relation A Q_m = Q_{m+1} H̄_m holding with H̄_m upper
Hessenberg ((m + 1) × m), by ``arnoldi_step``: the new product orthogonalised against
the basis by modified Gram–Schmidt, twice (Kahan's "twice is enough", so that the basis
stays orthonormal to rounding however many steps it grows).

- ``gmres``: x_m = x_0 + Q_m z, z minimising ‖β e_1 − H̄_m z‖ (Saad & Schultz 1986); the
  residual of the linear system is that small least-squares problem's, read without a
  product more. A right preconditioner P (A P⁻¹ u = b, x = P⁻¹ u) makes the products
  A P⁻¹ v.
- ``leading_eigenvalues``: the Ritz values of H_m (the square part) approximate A's
  eigenvalues of largest modulus first; a Ritz pair (θ, Q_m s) has the residual
  ‖A Q_m s − θ Q_m s‖ = |h_{m+1,m}| |e_mᵀ s| (the Arnoldi relation), so convergence is
  read without a product more. The basis grows, without restarts, until the wanted
  pairs' residuals are small or it spans the space (then H_m is similar to A and its
  eigenvalues are A's to rounding).

A product is one run of a tangent column through the period (``stroboscopic``): the cost
these methods count.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass

import numpy as np
import scipy.linalg


@dataclass(frozen=True)
class KrylovSolution:
    """x of A x = b by ``gmres``: ``residual`` = ‖b − A x‖/‖b‖ (relative, 0 for b = 0),
    ``iterations`` the products of A it took."""

    x: np.ndarray
    residual: float
    iterations: int


@dataclass(frozen=True)
class Eigenpairs:
    """The eigenvalues of largest modulus that ``leading_eigenvalues`` found, by
    descending modulus, their unit eigenvectors (columns of ``vectors``), each pair's
    ``residuals`` ‖A v − μ v‖ over ‖A‖'s estimate (the largest |H| entry), and the
    products of A it took."""

    values: np.ndarray
    vectors: np.ndarray
    residuals: np.ndarray
    products: int


def arnoldi_step(basis: np.ndarray, product: np.ndarray, m: int) -> tuple[np.ndarray, float]:
    """Orthogonalise ``product`` (A q_m) against the first m + 1 columns of ``basis`` by
    modified Gram–Schmidt, twice; returns (the column m of H̄: its first m + 1 entries,
    then the new vector's norm h_{m+1,m} last, all m + 2 of them) and leaves the
    normalised vector in ``basis``'s column m + 1 (zeros where it vanished: the Krylov
    space is invariant)."""
    w = product.astype(complex if np.iscomplexobj(basis) else float)
    column = np.zeros(m + 2, dtype=w.dtype)
    for _ in range(2):
        for j in range(m + 1):
            overlap = np.vdot(basis[:, j], w)
            column[j] += overlap
            w = w - overlap * basis[:, j]
    norm = float(np.linalg.norm(w))
    column[m + 1] = norm
    scale = max(float(np.linalg.norm(product)), np.finfo(float).tiny)
    basis[:, m + 1] = w / norm if norm > BREAKDOWN * scale else 0.0
    return column, norm


#: A new vector this much smaller than the product it came from (relative) has vanished:
#: the Krylov space is invariant (a lucky breakdown).
BREAKDOWN = 1e-13


def gmres(product: Callable[[np.ndarray], np.ndarray], b: np.ndarray, *,
          tolerance: float, most: int, preconditioner: Callable | None = None,
          ) -> KrylovSolution:
    """x ≈ A⁻¹ b with ‖b − A x‖ ≤ ``tolerance`` ‖b‖, by GMRES from x_0 = 0 on the products
    ``product(v)`` = A v, at most ``most`` of them (the best x found is returned either
    way: read ``residual``). With ``preconditioner`` (v ↦ P⁻¹ v), right preconditioned."""
    size = len(b)
    beta = float(np.linalg.norm(b))
    if beta == 0.0:
        return KrylovSolution(np.zeros(size), 0.0, 0)
    most = max(1, min(most, size + 1))
    basis = np.zeros((size, most + 1))
    basis[:, 0] = b / beta
    hessenberg = np.zeros((most + 1, most))
    apply = (lambda v: v) if preconditioner is None else preconditioner
    z, residual, m = np.zeros(0), 1.0, 0
    for m in range(most):
        column, norm = arnoldi_step(basis, product(apply(basis[:, m])), m)
        hessenberg[:m + 2, m] = column
        z, residual = _least_squares(hessenberg[:m + 2, :m + 1], beta)
        if residual <= tolerance or norm == 0.0 or not basis[:, m + 1].any():
            break
    x = apply(basis[:, :len(z)] @ z)
    return KrylovSolution(x, residual, m + 1)


def _least_squares(hessenberg: np.ndarray, beta: float) -> tuple[np.ndarray, float]:
    """z minimising ‖β e_1 − H̄ z‖, and that minimum over β."""
    right = np.zeros(hessenberg.shape[0])
    right[0] = beta
    z = np.linalg.lstsq(hessenberg, right, rcond=None)[0]
    return z, float(np.linalg.norm(right - hessenberg @ z)) / beta


def leading_eigenvalues(product: Callable[[np.ndarray], np.ndarray], start: np.ndarray, *,
                        count: int, tolerance: float, most: int | None = None) -> Eigenpairs:
    """The ``count`` eigenvalues of A of largest modulus (complex, by descending
    modulus) with their eigenvectors, by Arnoldi from ``start`` on ``product(v)`` = A v:
    the basis grows until each of them has a Ritz residual ≤ ``tolerance`` ‖A‖ (``most``
    products at most, default the size: then they are exact to rounding). A pair split
    by the count (a complex pair whose second member would come next) is completed."""
    size = len(start)
    count = max(1, min(count, size))
    most = size if most is None else max(count, min(most, size))
    basis = np.zeros((size, most + 1))
    basis[:, 0] = start / np.linalg.norm(start)
    hessenberg = np.zeros((most + 1, most))
    found = None
    for m in range(most):
        column, _ = arnoldi_step(basis, product(basis[:, m]), m)
        hessenberg[:m + 2, m] = column
        dimension = m + 1
        if dimension < count and basis[:, m + 1].any():
            continue
        found = _ritz(hessenberg, basis, dimension, count)
        invariant = not basis[:, m + 1].any()
        if invariant or np.all(found.residuals <= tolerance):
            break
    return Eigenpairs(found.values, found.vectors, found.residuals, dimension)


def _ritz(hessenberg, basis, dimension, count) -> Eigenpairs:
    """The ``count`` Ritz pairs of largest modulus of the Arnoldi basis of ``dimension``
    vectors (completing a split complex pair), with their residuals (module docstring)."""
    square = hessenberg[:dimension, :dimension]
    values, vectors = scipy.linalg.eig(square)
    order = np.argsort(-np.abs(values), kind="stable")
    values, vectors = values[order], vectors[:, order]
    keep = min(count, dimension)
    if keep < dimension and abs(values[keep - 1].imag) > 0.0 \
            and np.isclose(values[keep], np.conj(values[keep - 1]), rtol=1e-12, atol=0.0):
        keep += 1
    values, vectors = values[:keep], vectors[:, :keep]
    scale = max(float(np.abs(hessenberg[:dimension + 1, :dimension]).max()),
                np.finfo(float).tiny)
    residuals = np.abs(hessenberg[dimension, dimension - 1] * vectors[-1, :]) / scale
    shapes = basis[:, :dimension] @ vectors
    shapes /= np.linalg.norm(shapes, axis=0)
    return Eigenpairs(values, shapes, residuals, dimension)
