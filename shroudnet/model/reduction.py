"""Reductions of full finite-element matrices to small substructures.

Both reductions choose a basis T (N × n, n ≪ N) of the full model's degrees of freedom,
q_full = T q, and project: M_r = Tᵀ M T, K_r = Tᵀ K T, Φ_p,r = Φ_p T, b_r = Tᵀ b. The
returned ``Substructure`` keeps T as its ``basis``, so that ``expand`` maps its motion back
onto the full model.

- ``modal_truncation``: T = the lowest mass-normalised modes. The kept frequencies are the
  full model's; what it misses is the static flexibility of the modes left out, which a
  contact force at a point excites.
- ``craig_bampton`` (fixed-interface): T = [constraint modes | fixed-interface modes]. The
  boundary (retained) degrees of freedom stay physical, and any static load on them is
  reproduced exactly; the right basis where contacts act on a few known degrees of freedom.

Small models (N ≤ DENSE_SOLVE_LIMIT) are solved densely (``scipy.linalg.eigh``); larger
sparse ones by sparse LU and shift-invert Lanczos (``scipy.sparse.linalg.eigsh``), in
O(nnz of the factor) memory.
"""

from __future__ import annotations

import numpy as np
import scipy.linalg
import scipy.sparse
import scipy.sparse.linalg

from contact_laws import check_array, check_int, check_real, check_sequence

from .substructure import (Substructure, check_definite, check_symmetric, damping_ratios,
                           is_point_load, point_matrices, square_matrix)

#: Largest N solved with dense factorisations; a larger sparse model is solved sparse.
DENSE_SOLVE_LIMIT = 2000
#: The shift of ``modal_truncation``'s sparse eigensolver, relative to the mean K_jj / M_jj.
SHIFT_FRACTION = 1e-12


def craig_bampton(mass, stiffness, boundary, modes, *, damping_ratios=None, points=None,
                  load=None, excitation_scale=1.0, stiffness_speed=None) -> Substructure:
    """Fixed-interface Craig–Bampton reduction of M, K to the boundary DOFs and ``modes``
    fixed-interface normal modes.

    With the degrees of freedom split into boundary b and interior i,

        T = ⎡ I     0  ⎤     Ψ = −K_ii⁻¹ K_ib   (constraint modes: the static shape of the
            ⎣ Ψ    Φ_i ⎦                         interior when one boundary DOF moves by 1),
                                                 K_ii Φ_i = M_ii Φ_i diag(ω²)  (lowest ``modes``,
                                                 mass-normalised, boundary fixed),

    and q = (u_b, η): the first len(boundary) coordinates are the boundary DOFs themselves,
    in the order given, the rest the amplitudes of the fixed-interface modes. Any static load
    on the boundary is reproduced exactly; the frequencies converge from above as modes are
    added.

    Parameters
    ----------
    mass, stiffness : (N, N) array or scipy.sparse matrix
        M (symmetric positive definite) and K (symmetric positive semi-definite) of the full
        model. The boundary must hold K's rigid-body motion (K_ii nonsingular).
    boundary : sequence of int
        Indices (0 … N − 1, no repeats) of the retained physical DOFs.
    modes : int
        The number of fixed-interface normal modes kept, 0 … N − len(boundary).
    damping_ratios : float or sequence of float, optional
        Modal damping of the reduced model (``Substructure.damping_ratios``).
    points : mapping str → (d, N) array, optional
        Points in full-model DOFs, r_p = Φ_p q_full; reduced to Φ_p T.
    load : (N,) array, str or (str, direction), optional
        A load vector in full-model DOFs (reduced to Tᵀ b), or a point (see ``Substructure``).
    excitation_scale : float
        As for ``Substructure``.
    stiffness_speed : (N, N) array or scipy.sparse matrix, optional
        K₁ of the full model, reduced to Tᵀ K₁ T. The basis is computed at rest, so K(Ω) of
        the reduction is the full one's projected on the modes at rest.

    Returns
    -------
    Substructure
        n = len(boundary) + modes, with ``basis`` = T (N × n).

    Examples
    --------
    >>> from shroudnet.model.beam import cantilever_beam
    >>> beam = cantilever_beam(length=0.2, width=0.02, thickness=0.005,
    ...                        youngs_modulus=2.1e11, density=7850.0, elements=20)
    >>> tip = list(range(beam.n_dofs - 4, beam.n_dofs))
    >>> reduced = craig_bampton(beam.mass, beam.stiffness, tip, 6, points=beam.points)
    >>> reduced
    Substructure(n_dofs=10, points=['shroud', 'load'], reduced from 80)
    """
    owner = "craig_bampton"
    mass, stiffness, stiffness_speed = _full_model(owner, mass, stiffness, stiffness_speed)
    total = mass.shape[0]
    boundary = _indices(owner, boundary, total)
    interior = np.setdiff1d(np.arange(total), boundary)
    sparse = _solve_sparse(mass, stiffness)
    most = interior.size - 1 if sparse and interior.size else interior.size
    modes = check_int(owner, "modes", modes, low=0, high=most,
                      high_label=("N − len(boundary) − 1 (sparse eigensolver)" if sparse
                                  else "N − len(boundary)"))
    if boundary.size + modes == 0:
        raise ValueError(f"{owner} needs a boundary or at least one mode, got neither")
    if interior.size:
        k_ii = _block(stiffness, interior, interior)
        m_ii = _block(mass, interior, interior)
        k_ib = _block(stiffness, interior, boundary)
        solve = _factor(owner, k_ii, sparse)
        constraint = -solve(_dense(k_ib)) if boundary.size else np.zeros((interior.size, 0))
        if not np.isfinite(constraint).all():
            raise ValueError(f"{owner}: K with the boundary fixed is singular; the boundary "
                             "must hold the structure's rigid-body motion")
        normal = _lowest_modes(k_ii, m_ii, modes, sparse, solve)
    basis = np.zeros((total, boundary.size + modes))
    basis[boundary, np.arange(boundary.size)] = 1.0
    if interior.size:
        basis[np.ix_(interior, np.arange(boundary.size))] = constraint
        basis[np.ix_(interior, boundary.size + np.arange(modes))] = normal
    return _project(owner, basis, mass, stiffness, stiffness_speed, damping_ratios, points,
                    load, excitation_scale)


def modal_truncation(mass, stiffness, modes, *, damping_ratios=None, points=None, load=None,
                     excitation_scale=1.0, stiffness_speed=None) -> Substructure:
    """Keep the lowest ``modes`` mass-normalised modes of K φ = ω² M φ: T = [φ_1 … φ_m].

    The reduced M is the identity and K = diag(ω_k²) (to rounding); q are the modal
    amplitudes, mode 1 the lowest.

    Parameters
    ----------
    mass, stiffness : (N, N) array or scipy.sparse matrix
        M (symmetric positive definite) and K (symmetric positive semi-definite).
    modes : int
        1 … N modes (N − 1 for a sparse solve).
    damping_ratios, points, load, excitation_scale, stiffness_speed
        As for ``craig_bampton``.

    Returns
    -------
    Substructure
        n = ``modes``, with ``basis`` = T (N × n).
    """
    owner = "modal_truncation"
    mass, stiffness, stiffness_speed = _full_model(owner, mass, stiffness, stiffness_speed)
    total = mass.shape[0]
    sparse = _solve_sparse(mass, stiffness)
    modes = check_int(owner, "modes", modes, low=1, high=total - 1 if sparse else total,
                      high_label="N − 1 (sparse eigensolver)" if sparse else "N")
    if sparse:
        # K may be singular (a free structure): factor K + σ M, σ a shift at the level of K's
        # rounding (SHIFT_FRACTION of the mean K_jj / M_jj), far below any mode a model in
        # double precision resolves, so the modes nearest −σ are the lowest.
        shift = SHIFT_FRACTION * abs(stiffness.diagonal().sum() / mass.diagonal().sum()) or 1.0
        solve = _factor(owner, (stiffness + shift * mass).tocsc(), True)
        basis = _lowest_modes(stiffness, mass, modes, True, solve, shift=-shift)
    else:
        basis = _lowest_modes(stiffness, mass, modes, False, None)
    return _project(owner, basis, mass, stiffness, stiffness_speed, damping_ratios, points,
                    load, excitation_scale)


# ---- the steps ---------------------------------------------------------------------------------

def _full_model(owner, mass, stiffness, stiffness_speed):
    """The full model's matrices, validated as ``Substructure`` validates its own."""
    mass = square_matrix(f"{owner}.mass", mass)
    total = mass.shape[0]
    stiffness = square_matrix(f"{owner}.stiffness", stiffness, total)
    check_symmetric(f"{owner}.mass", mass)
    check_symmetric(f"{owner}.stiffness", stiffness)
    check_definite(f"{owner}.mass", mass, strict=True)
    check_definite(f"{owner}.stiffness", stiffness, strict=False)
    if stiffness_speed is not None:
        stiffness_speed = square_matrix(f"{owner}.stiffness_speed", stiffness_speed, total)
        check_symmetric(f"{owner}.stiffness_speed", stiffness_speed)
    return mass, stiffness, stiffness_speed


def _indices(owner: str, boundary, total: int) -> np.ndarray:
    boundary = check_sequence(owner, "boundary", boundary,
                              expected="a sequence of DOF indices")
    indices = np.array([check_int(owner, "boundary", index, low=0, high=total - 1,
                                  high_label="N − 1") for index in boundary], dtype=int)
    values, counts = np.unique(indices, return_counts=True)
    if (counts > 1).any():
        raise ValueError(f"{owner}.boundary repeats the DOF indices "
                         f"{values[counts > 1].tolist()}")
    return indices


def _solve_sparse(mass, stiffness) -> bool:
    return mass.shape[0] > DENSE_SOLVE_LIMIT and (scipy.sparse.issparse(mass)
                                                  or scipy.sparse.issparse(stiffness))


def _factor(owner: str, matrix, sparse: bool):
    """A solver x = A⁻¹ y for the symmetric positive definite ``matrix``."""
    message = (f"{owner}: K with the boundary fixed is not positive definite; the boundary "
               "must hold the structure's rigid-body motion")
    if sparse:
        try:
            lu = scipy.sparse.linalg.splu(scipy.sparse.csc_matrix(matrix))
        except RuntimeError:
            raise ValueError(message) from None
        return lu.solve
    try:
        factor = scipy.linalg.cho_factor(_dense(matrix))
    except np.linalg.LinAlgError:
        raise ValueError(message) from None
    return lambda right: scipy.linalg.cho_solve(factor, right)


def _lowest_modes(stiffness, mass, modes: int, sparse: bool, solve, shift: float = 0.0):
    """The lowest ``modes`` mass-normalised modes of K φ = ω² M φ, as columns.

    Sparse: shift-invert Lanczos about ``shift`` with ``solve`` = (K − shift M)⁻¹.
    """
    size = mass.shape[0]
    if modes == 0:
        return np.zeros((size, 0))
    if not sparse:
        _, shapes = scipy.linalg.eigh(_dense(stiffness), _dense(mass),
                                      subset_by_index=[0, modes - 1])
        return shapes
    inverse = scipy.sparse.linalg.LinearOperator((size, size), matvec=solve, dtype=float)
    eigenvalues, shapes = scipy.sparse.linalg.eigsh(
        scipy.sparse.csc_matrix(stiffness), k=modes, M=scipy.sparse.csc_matrix(mass),
        sigma=shift, which="LM", OPinv=inverse)
    shapes = shapes[:, np.argsort(eigenvalues)]
    return shapes / np.sqrt(np.einsum("ik,ik->k", shapes, mass @ shapes))


def _project(owner, basis, mass, stiffness, stiffness_speed, ratios, points, load, scale):
    """The ``Substructure`` of Tᵀ M T, Tᵀ K T, Tᵀ K₁ T, Φ_p T and Tᵀ b, with basis T."""
    total = basis.shape[0]
    points = point_matrices(f"{owner}.points", {} if points is None else points, total)
    if load is not None and not is_point_load(load):
        try:
            load = check_array(owner, "load", load, shape=(None,))
        except ValueError:
            load = np.full(np.shape(load), np.nan)  # said below, with the size expected
        if np.shape(load) != (total,) or not np.isfinite(load).all():
            raise ValueError(f"{owner}.load must be a finite vector of {total} generalised "
                             "forces, a point name or (point name, direction), got shape "
                             f"{np.shape(load)}")
        load = basis.T @ load
    if ratios is not None:
        ratios = damping_ratios(owner, ratios, basis.shape[1])
    check_real(owner, "excitation_scale", scale)
    reduced = [None if matrix is None else _symmetric(basis.T @ (matrix @ basis))
               for matrix in (mass, stiffness, stiffness_speed)]
    return Substructure(reduced[0], reduced[1], damping_ratios=ratios,
                        stiffness_speed=reduced[2],
                        points={name: matrix @ basis for name, matrix in points.items()},
                        load=load, excitation_scale=scale, basis=basis)


def _block(matrix, rows, columns):
    if scipy.sparse.issparse(matrix):
        return scipy.sparse.csr_array(matrix)[rows][:, columns]
    return matrix[np.ix_(rows, columns)]


def _dense(matrix) -> np.ndarray:
    return matrix.toarray() if scipy.sparse.issparse(matrix) else np.asarray(matrix)


def _symmetric(matrix) -> np.ndarray:
    matrix = np.asarray(matrix)
    return 0.5 * (matrix + matrix.T)
