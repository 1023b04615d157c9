"""The matrix exponential, in storage given by the caller (compiled code that allocates
nothing: ``compiled``).

Scaling and squaring with the [13/13] Padé approximant (Higham, "The scaling and
squaring method for the matrix exponential revisited", SIAM J. Matrix Anal. Appl. 26,
2005): A is halved s times until ‖A/2ˢ‖₁ ≤ θ₁₃ = 5.37, where r₁₃ matches e^A to the unit
roundoff in exact arithmetic (or fewer, by the growth of its powers: Al-Mohy and Higham
2009); e^{A/2ˢ} ≈ (V − U)⁻¹ (V + U) with U and V the odd and even
parts of the approximant's numerator; then squared s times. The kernel uses it for the
tangent flow of a phase whose vector field is linear (``kernel.tangent.carry_phase``).
"""

import math

import numpy as np

from .compiled import njit_inlined, njit_step_callable

#: b_0 … b_13 of the [13/13] Padé approximant of e^x (Higham 2005, Table 10.4).
PADE = np.array([64764752532480000.0, 32382376266240000.0, 7771770303897600.0,
                 1187353796428800.0, 129060195264000.0, 10559470521600.0, 670442572800.0,
                 33522128640.0, 1323241920.0, 40840800.0, 960960.0, 16380.0, 182.0, 1.0])
#: The largest ‖A‖₁ for which r₁₃(A) meets e^A to the unit roundoff (Higham 2005).
THETA = 5.371920351148152
#: The slots of ``exponential``'s storage (a stack of n × n matrices).
SLOTS = 7


@njit_inlined
def product(a, b, out):
    """out ← a b (square matrices, out distinct from both)."""
    n = a.shape[0]
    for i in range(n):
        for j in range(n):
            out[i, j] = 0.0
        for k in range(n):
            factor = a[i, k]
            if factor != 0.0:
                for j in range(n):
                    out[i, j] += factor * b[k, j]


@njit_inlined
def _norm(a):
    """‖a‖₁, the largest column sum of |a|."""
    norm = 0.0
    for j in range(a.shape[1]):
        column = 0.0
        for i in range(a.shape[0]):
            column += abs(a[i, j])
        norm = max(norm, column)
    return norm


@njit_inlined
def _combine(out, c6, a6, c4, a4, c2, a2, c0):
    """out ← c6 A⁶ + c4 A⁴ + c2 A² + c0 I."""
    n = out.shape[0]
    for i in range(n):
        for j in range(n):
            out[i, j] = c6 * a6[i, j] + c4 * a4[i, j] + c2 * a2[i, j]
        out[i, i] += c0


@njit_inlined
def _solve(lhs, rhs):
    """rhs ← lhs⁻¹ rhs, by Gaussian elimination with partial pivoting (lhs is overwritten
    by its factors)."""
    n = lhs.shape[0]
    for k in range(n):
        pivot = k
        for i in range(k + 1, n):
            if abs(lhs[i, k]) > abs(lhs[pivot, k]):
                pivot = i
        if pivot != k:
            for j in range(n):
                lhs[k, j], lhs[pivot, j] = lhs[pivot, j], lhs[k, j]
                rhs[k, j], rhs[pivot, j] = rhs[pivot, j], rhs[k, j]
        for i in range(k + 1, n):
            factor = lhs[i, k] / lhs[k, k]
            if factor != 0.0:
                for j in range(k + 1, n):
                    lhs[i, j] -= factor * lhs[k, j]
                for j in range(n):
                    rhs[i, j] -= factor * rhs[k, j]
    for k in range(n - 1, -1, -1):
        for j in range(n):
            value = rhs[k, j]
            for i in range(k + 1, n):
                value -= lhs[k, i] * rhs[i, j]
            rhs[k, j] = value / lhs[k, k]


@njit_step_callable
def exponential(work):
    """e^A of A = work[0], into work[0]; ``work`` is ``SLOTS`` n × n matrices of storage.
    Callable from Python (for its tests)."""
    a, a2, a4, a6, u, v, t = work[0], work[1], work[2], work[3], work[4], work[5], work[6]
    n = a.shape[0]
    norm = _norm(a)
    squarings = max(0, int(math.ceil(math.log2(norm / THETA)))) if norm > THETA else 0
    scale = 0.5 ** squarings
    for i in range(n):
        for j in range(n):
            a[i, j] *= scale
    product(a, a, a2)
    product(a2, a2, a4)
    product(a4, a2, a6)
    # ‖A‖₁ overstates the growth of a non-normal A's powers, which the approximant's
    # error follows: with η = max(‖A⁵‖^{1/5}, ‖A⁶‖^{1/6}) ≤ ‖A‖₁ (Al-Mohy and Higham,
    # SIAM J. Matrix Anal. Appl. 31, 2009) fewer squarings do, and each one saved
    # halves the rounding they amplify
    product(a4, a, t)
    growth = max(_norm(t) ** 0.2, _norm(a6) ** (1.0 / 6.0))
    saved = 0
    while saved < squarings and growth * 2.0 ** (saved + 1) <= THETA:
        saved += 1
    if saved:
        squarings -= saved
        factor = 2.0 ** saved
        for i in range(n):
            for j in range(n):
                a[i, j] *= factor
                a2[i, j] *= factor**2
                a4[i, j] *= factor**4
                a6[i, j] *= factor**6
    b = PADE
    _combine(t, b[13], a6, b[11], a4, b[9], a2, 0.0)
    product(a6, t, v)
    for i in range(n):
        for j in range(n):
            v[i, j] += b[7] * a6[i, j] + b[5] * a4[i, j] + b[3] * a2[i, j]
        v[i, i] += b[1]
    product(a, v, u)                                   # U, the odd part
    _combine(t, b[12], a6, b[10], a4, b[8], a2, 0.0)
    product(a6, t, v)
    for i in range(n):
        for j in range(n):
            v[i, j] += b[6] * a6[i, j] + b[4] * a4[i, j] + b[2] * a2[i, j]
        v[i, i] += b[0]                                 # V, the even part
    for i in range(n):
        for j in range(n):
            t[i, j] = v[i, j] - u[i, j]
            a[i, j] = v[i, j] + u[i, j]
    _solve(t, a)                                        # a ← (V − U)⁻¹ (V + U)
    for _ in range(squarings):
        product(a, a, t)
        for i in range(n):
            for j in range(n):
                a[i, j] = t[i, j]
