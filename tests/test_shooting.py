"""Shooting at the scale of FE models: the Krylov methods on matrix-free products.

References computed here without the code under test: matrices of a chosen spectrum and
numpy's solvers for GMRES and Arnoldi.
"""

import numpy as np

from shroudnet.steady.krylov import arnoldi_step, gmres, leading_eigenvalues

# ---- the Krylov methods on matrices of known spectrum ---------------------------------------

def known_matrix(values, seed=0):
    """A non-normal matrix V diag(values) V⁻¹ (real: ``values`` holds conjugate pairs)."""
    rng = np.random.default_rng(seed)
    n = len(values)
    blocks = np.zeros((n, n))
    k = 0
    while k < n:
        value = values[k]
        if abs(value.imag) > 0.0:
            blocks[k:k + 2, k:k + 2] = [[value.real, value.imag], [-value.imag, value.real]]
            k += 2
        else:
            blocks[k, k] = value.real
            k += 1
    shape = np.eye(n) + 0.3 * rng.standard_normal((n, n))
    return shape @ blocks @ np.linalg.inv(shape)


SPECTRUM = np.array([0.95 + 0.2j, 0.95 - 0.2j, -0.9, 0.8, 0.5 + 0.5j, 0.5 - 0.5j, 0.3, 0.2,
                     0.1, 0.05, 0.02, 0.01, 0.0, 0.0])


def test_arnoldi_finds_the_leading_eigenvalues_of_a_matrix_of_known_spectrum():
    """The four of largest modulus (a complex pair, a real negative and a real positive),
    to 1e-10, from products alone; each found vector is an eigenvector (residual 1e-9)."""
    matrix = known_matrix(SPECTRUM)
    found = leading_eigenvalues(lambda v: matrix @ v, np.ones(len(SPECTRUM)), count=4,
                                tolerance=1e-12)
    expected = SPECTRUM[np.argsort(-np.abs(SPECTRUM), kind="stable")][:4]
    assert len(found.values) == 4
    for value in expected:
        assert np.abs(found.values - value).min() <= 1e-10
    residual = matrix @ found.vectors - found.vectors * found.values
    assert np.abs(residual).max() <= 1e-9


def test_the_arnoldi_step_keeps_the_basis_orthonormal_and_the_relation_exact():
    """A Q_m = Q_{m+1} H̄_m, to rounding, with QᵀQ = I, after 12 steps on a non-normal
    matrix."""
    matrix = known_matrix(SPECTRUM, seed=3)
    n, steps = len(SPECTRUM), 12
    basis = np.zeros((n, steps + 1))
    basis[:, 0] = np.arange(1.0, n + 1.0) / np.linalg.norm(np.arange(1.0, n + 1.0))
    hessenberg = np.zeros((steps + 1, steps))
    for m in range(steps):
        column, _ = arnoldi_step(basis, matrix @ basis[:, m], m)
        hessenberg[:m + 2, m] = column
    assert np.abs(basis.T @ basis - np.eye(steps + 1)).max() <= 1e-13
    assert np.abs(matrix @ basis[:, :steps] - basis @ hessenberg).max() <= 1e-13


def test_gmres_solves_to_its_tolerance_and_a_right_preconditioner_is_undone():
    """x of (A − I) x = b against numpy's solve: to the tolerance asked; with the exact
    inverse as right preconditioner, allowed a single product."""
    shifted = known_matrix(SPECTRUM, seed=5) - np.eye(len(SPECTRUM))
    b = np.linspace(-1.0, 2.0, len(SPECTRUM))
    exact = np.linalg.solve(shifted, b)
    solved = gmres(lambda v: shifted @ v, b, tolerance=1e-11, most=40)
    assert solved.residual <= 1e-11
    assert np.linalg.norm(shifted @ solved.x - b) <= 1.001e-11 * np.linalg.norm(b)
    assert np.abs(solved.x - exact).max() <= 1e-9 * np.abs(exact).max()
    inverse = np.linalg.inv(shifted)
    once = gmres(lambda v: shifted @ v, b, tolerance=1e-12, most=1,
                 preconditioner=lambda v: inverse @ v)
    assert once.residual <= 1e-12
    assert np.abs(once.x - exact).max() <= 1e-12 * np.abs(exact).max()
