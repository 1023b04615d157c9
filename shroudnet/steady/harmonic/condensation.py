"""The linear structure condensed onto the contact coordinates, harmonic by harmonic.

At harmonic k of ω the structure answers a force of complex amplitude F by
X = H_k F with its dynamic compliance H_k = (K − (kω)² M + ikω C)⁻¹. With the
excitation Q_k and the contacts' forces Λ_k (``model``: the structure feels Q − Gᵀλ),

    X_k = H_k Q_k − H_k Gᵀ Λ_k,       Z_k = G X_k = Z_k^lin − W_k Λ_k,

with W_k = G H_k Gᵀ (m × m) the compliance at the contacts and Z_k^lin = G H_k Q_k their
motion with the contacts open. Harmonic balance solves the m (2H + 1) real equations

    R(z) = z − z^lin + W λ̂(z) = 0                                             (1)

for the contact coordinates' coefficients z, λ̂(z) the coefficients of the contacts'
forces computed in time (``aft``); every coordinate's response follows from (1)'s
first line (``recover``). Per harmonic this costs one factorisation of an n × n complex
matrix, once per scene and frequency, not per Newton step.

In the real coefficients (a_k, b_k) of ``fourier`` (X = a − ib), the complex product
W X with W = P + iQ is the real block [[P, Q], [−Q, P]] on (a, b); it is applied as the
complex product, harmonic by harmonic, to the residual and to each column of the
Jacobian alike.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
import scipy.linalg

from .fourier import complex_amplitudes, real_coefficients
from .model import HarmonicModel


@dataclass(frozen=True, eq=False)
class Condensed:
    """The structure at the contacts for H harmonics: ``compliance`` W_k ((H+1) × m × m,
    complex), ``linear`` z^lin ((2H+1) × m, real coefficients), and for ``recover`` the
    responses to unit contact forces H_k Gᵀ ((H+1) × n × m) and to the excitation
    H_k Q_k ((H+1) × n)."""

    harmonics: int
    compliance: np.ndarray
    linear: np.ndarray
    to_contacts: np.ndarray
    to_load: np.ndarray

    def truncated(self, harmonics: int) -> "Condensed":
        """The same structure for fewer harmonics (the first H' + 1 of each table)."""
        return Condensed(harmonics=harmonics, compliance=self.compliance[:harmonics + 1],
                         linear=self.linear[:2 * harmonics + 1],
                         to_contacts=self.to_contacts[:harmonics + 1],
                         to_load=self.to_load[:harmonics + 1])

    def apply(self, forces: np.ndarray) -> np.ndarray:
        """W λ̂ in real coefficients ((2H+1) × m) from the forces' ((2H+1) × m)."""
        product = np.einsum("kab,kb->ka", self.compliance, complex_amplitudes(forces))
        return real_coefficients(product)

    def residual(self, z: np.ndarray, forces: np.ndarray) -> np.ndarray:
        """R = z − z^lin + W λ̂ of equation (1) ((2H+1) × m)."""
        return z - self.linear + self.apply(forces)

    def apply_columns(self, matrix: np.ndarray) -> np.ndarray:
        """W applied to each column of ``matrix`` (m(2H+1) × c, rows harmonic-major: index
        j·m + a), harmonic by harmonic: the Jacobian W ∂λ̂/∂z without W as a dense
        matrix (its blocks off the harmonics' diagonal are zero)."""
        size, m = self.linear.shape
        if m == 0:  # no contacts: nothing to apply
            return np.zeros((0, matrix.shape[1]))
        columns = matrix.reshape(size, m, -1)
        # a batched matrix product (BLAS), not einsum's loops: 17× faster on 135 contact
        # coordinates of 15 coefficients
        product = np.matmul(self.compliance, complex_amplitudes(columns))
        return real_coefficients(product).reshape(size * m, -1)

    def recover(self, forces: np.ndarray) -> np.ndarray:
        """Every coordinate's coefficients ((2H+1) × n): X_k = H_k Q_k − H_k Gᵀ Λ_k."""
        response = self.to_load - np.einsum("kna,ka->kn", self.to_contacts,
                                            complex_amplitudes(forces))
        return real_coefficients(response)


def dynamic_matrix(model: HarmonicModel, k: int) -> np.ndarray:
    """K − (kω)² M + ikω C (n × n)."""
    rate = k * model.frequency
    return model.stiffness - rate * rate * model.mass + 1j * rate * model.damping


def condense(model: HarmonicModel, harmonics: int, rows: np.ndarray | None = None
             ) -> Condensed:
    """The ``Condensed`` structure of ``model`` for ``harmonics`` H: one LU factorisation
    of K − (kω)²M + ikωC per harmonic k = 0 … H, solved for Gᵀ and Q_k; G the model's
    rows, or ``rows`` (fewer coordinates the contacts' are read from, ``balance``)."""
    rows = model.rows if rows is None else rows
    load = model.load_coefficients(harmonics)
    n, m = model.n_coordinates, rows.shape[0]
    to_contacts = np.empty((harmonics + 1, n, m), dtype=complex)
    to_load = np.empty((harmonics + 1, n), dtype=complex)
    for k in range(harmonics + 1):
        factor = scipy.linalg.lu_factor(dynamic_matrix(model, k), check_finite=False)
        solved = scipy.linalg.lu_solve(factor, np.column_stack([rows.T, load[k]]),
                                       check_finite=False)
        to_contacts[k], to_load[k] = solved[:, :m], solved[:, m]
    compliance = np.matmul(rows, to_contacts)
    linear = real_coefficients(to_load @ rows.T)
    return Condensed(harmonics=harmonics, compliance=compliance, linear=linear,
                     to_contacts=to_contacts, to_load=to_load)
