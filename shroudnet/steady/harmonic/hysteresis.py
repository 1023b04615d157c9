"""Elastic contacts in time: Jenkins sliders marched over the samples of a period.

A contact of tangential stiffness k_t ties its tangential relative displacement r_t
(two components in its face's plane; the second 0 on a face of one direction) to a
slider at w: the friction force is f = k_t (r_t − w) while |f| ≤ μ_s N, and the slider
moves to keep |f| = μ_s N beyond (the engine's law, ``engine.sliders``: the circular
Coulomb limit with the static coefficient). At the samples n = 0 … N − 1 of a period
the slider is marched by the return mapping (backward Euler, radial return)::

    f_trial = k_t (r_t,n − w_{n−1})
    μ_s N_n = 0:              f_n = 0,                      w_n = r_t,n   (open)
    |f_trial| ≤ μ_s N_n:      f_n = f_trial,                w_n = w_{n−1} (stuck)
    else:                     f_n = μ_s N_n f_trial/|f_trial|, w_n = r_t,n − f_n/k_t

which tends to the continuous law as the samples' spacing h → 0. Where a slip stops
or the contact closes between two samples, the plain mapping is O(h²) and O(h) of the
motion off; there the slider is put where the continuous law has it, interpolated to
O(h⁴) (``slider_pass``). A period's forces depend on where the slider starts; the
periodic hysteresis is the start that the period returns to, w_N = P(w_0) = w_0. From
the stated start — the slider at the mean of r_t over the period, so that a contact
that never slips carries no mean friction force — the period is marched until it
repeats (``HYSTERESIS_STEPS`` at most): once a 1-D slider slips it forgets its start,
and a 2-D one forgets it geometrically; past ``NEWTON_AFTER`` periods the fixed point is
sought by Newton's method on w_0 ↦ P(w_0) − w_0 with the 2 × 2 Jacobian the pass
carries.

Every pass carries the derivatives of f_n with respect to the unknowns z (through
r_t,n and N_n) and to the start w_0, so that the forces' Jacobian is exact for what is
computed: at a periodic start that slips, dw_0/dz = (I − A)⁻¹ ∂P/∂z with A = ∂P/∂w_0
(whose eigenvalues lie inside the unit circle when the slider slips); at one that never
slips, dw_0/dz is carried from the stated start through every pass.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numba
import numpy as np

#: The most periods the sliders are marched for their hysteresis to repeat, and the
#: pass after which Newton's method takes over from plain marching.
HYSTERESIS_STEPS = 64
NEWTON_AFTER = 4
#: A period repeats where its slider returns to within this fraction of the contact's
#: scale (its tangential travel and its largest elastic stretch μ_s N / k_t).
REPEATS = 1e-13


@numba.njit(cache=True)
def cubic_peak(values):
    """(s*, P(s*), ℓ(s*)) of the cubic P through ``values`` at s = −1, 0, 1, 2: where it
    is largest on [0, 1], its value there, and the four Lagrange weights at s*, with
    which P(s*) = Σ ℓ_i values_i (its derivative in the values at an interior peak,
    P'(s*) being 0 there)."""
    a, b, c, d = values[0], values[1], values[2], values[3]
    c1 = -a / 3.0 - b / 2.0 + c - d / 6.0
    c2 = a / 2.0 - b + c / 2.0
    c3 = -a / 6.0 + b / 2.0 - c / 2.0 + d / 6.0
    best_s, best = 0.0, b
    if c + 0.0 > best:
        best_s, best = 1.0, c
    # P'(s) = c1 + 2 c2 s + 3 c3 s² = 0
    roots = np.empty(2)
    count = 0
    if abs(c3) > 1e-300 * (abs(c1) + abs(c2) + 1e-300):
        disc = 4.0 * c2 * c2 - 12.0 * c3 * c1
        if disc >= 0.0:
            root = math.sqrt(disc)
            roots[0] = (-2.0 * c2 + root) / (6.0 * c3)
            roots[1] = (-2.0 * c2 - root) / (6.0 * c3)
            count = 2
    elif c2 != 0.0:
        roots[0] = -c1 / (2.0 * c2)
        count = 1
    for k in range(count):
        s = roots[k]
        if 0.0 < s < 1.0:
            value = ((c3 * s + c2) * s + c1) * s + b
            if value > best:
                best_s, best = s, value
    weights, _ = lagrange(best_s)
    return best_s, best, weights


@numba.njit(cache=True)
def lagrange(s):
    """The weights ℓ_i(s) of the cubic through the nodes −1, 0, 1, 2 at s, and their
    derivatives ℓ_i'(s)."""
    weights, slopes = np.empty(4), np.empty(4)
    weights[0] = -s * (s - 1.0) * (s - 2.0) / 6.0
    weights[1] = (s + 1.0) * (s - 1.0) * (s - 2.0) / 2.0
    weights[2] = -(s + 1.0) * s * (s - 2.0) / 2.0
    weights[3] = (s + 1.0) * s * (s - 1.0) / 6.0
    slopes[0] = -(3.0 * s * s - 6.0 * s + 2.0) / 6.0
    slopes[1] = (3.0 * s * s - 4.0 * s - 1.0) / 2.0
    slopes[2] = -(3.0 * s * s - 2.0 * s - 2.0) / 2.0
    slopes[3] = (3.0 * s * s - 1.0) / 6.0
    return weights, slopes


@numba.njit(cache=True)
def cubic_root(values):
    """The s in [0, 1] where the cubic through ``values`` at −1, 0, 1, 2 crosses 0, given
    values[1] ≤ 0 < values[2]: Newton's method kept inside a shrinking bracket."""
    low, high = 0.0, 1.0
    s = values[1] / (values[1] - values[2])
    for _ in range(60):
        weights, slopes = lagrange(s)
        value = weights @ values
        if value > 0.0:
            high = s
        else:
            low = s
        slope = slopes @ values
        step = s - value / slope if slope > 0.0 else 0.5 * (low + high)
        if not low < step < high:
            step = 0.5 * (low + high)
        if abs(step - s) <= 1e-15:
            return step
        s = step
    return s


@numba.njit(cache=True)
def slider_pass(rt, limit, depth, drt, dlimit, ddepth, kt, w, f, df, dfw):
    """One period of the return mapping from the slider at ``w`` (2), the tangential
    displacements ``rt`` (N × 2), friction limits μ_s N ``limit`` (N) and penetrations
    ``depth`` (N) with their derivatives ``drt`` (N × 2 × P), ``dlimit`` and ``ddepth``
    (N × P) in the unknowns: the forces
    into ``f`` (N × 2), ∂f/∂z at a fixed start into ``df`` (N × 2 × P) and ∂f/∂w_0 into
    ``dfw`` (N × 2 × 2). Returns (w_N, ∂w_N/∂z at a fixed start (2 × P), ∂w_N/∂w_0
    (2 × 2), whether the slider moved: slipped or was released by an open contact).

    Where a slip ends between samples n − 1 and n (slipping at n − 1, its slider's
    position along the slip direction û, g(t) = û·r_t(t) − μ_s N(t)/k_t — the 1-D
    slider's position while it slips — peaking inside the interval), the slider moves on
    to the peak before sample n is taken, g interpolated by the cubic through samples
    n − 2 … n + 1: w ← w_{n−1} + û (max g − g_{n−1}), exact to O(h⁴) where the plain
    return mapping stops the slider at sample n − 1, O(h²) short of the reversal. As the
    peak crosses a sample the forces change continuously (the cubic interpolates the
    samples), so the balance stays continuous in its unknowns. Where the contact
    closes between samples n − 1 and n (δ crossing 0), the slider starts relaxed at the
    closing instant, where the cubic through δ crosses 0, not at sample n − 1, O(h) of
    the motion away."""
    count, unknowns = drt.shape[0], drt.shape[2]
    w = w.copy()
    dw = np.zeros((2, unknowns))
    dww = np.eye(2)
    trial = np.empty((2, unknowns))
    trial_w = np.empty((2, 2))
    moved = False
    slipped = False  # whether sample n − 1 slipped, with its direction and derivatives
    direction = np.zeros(2)
    d_direction = np.zeros((2, unknowns))
    d_direction_w = np.zeros((2, 2))
    values = np.empty(4)
    was_open = limit[count - 1] <= 0.0
    for n in range(count):
        bound = limit[n]
        if was_open and bound > 0.0 and depth[n - 1] <= 0.0 < depth[n]:
            relax_at_closing(n, rt, depth, drt, ddepth, w, dw, dww, values)
        was_open = bound <= 0.0
        if slipped and bound > 0.0:
            refine_stop(n, rt, limit, drt, dlimit, kt, w, dw, dww, direction,
                        d_direction, d_direction_w, values)
        f0 = kt * (rt[n, 0] - w[0])
        f1 = kt * (rt[n, 1] - w[1])
        for c in range(2):
            for p in range(unknowns):
                trial[c, p] = kt * (drt[n, c, p] - dw[c, p])
            for q in range(2):
                trial_w[c, q] = -kt * dww[c, q]
        size = math.hypot(f0, f1)
        slipped = False
        if bound <= 0.0:  # open, or pressed by no force: the slider follows
            moved = True
            f[n, 0] = 0.0
            f[n, 1] = 0.0
            w[0] = rt[n, 0]
            w[1] = rt[n, 1]
            for c in range(2):
                for p in range(unknowns):
                    df[n, c, p] = 0.0
                    dw[c, p] = drt[n, c, p]
                for q in range(2):
                    dfw[n, c, q] = 0.0
                    dww[c, q] = 0.0
        elif size <= bound:  # stuck: the slider stays
            f[n, 0] = f0
            f[n, 1] = f1
            for c in range(2):
                for p in range(unknowns):
                    df[n, c, p] = trial[c, p]
                for q in range(2):
                    dfw[n, c, q] = trial_w[c, q]
        else:  # slipping: the force is put back on the limit, along the trial
            moved = True
            slipped = True
            u0, u1 = f0 / size, f1 / size
            direction[0], direction[1] = u0, u1
            f[n, 0] = bound * u0
            f[n, 1] = bound * u1
            w[0] = rt[n, 0] - f[n, 0] / kt
            w[1] = rt[n, 1] - f[n, 1] / kt
            # dû = (I − û ûᵀ) df_trial / |f_trial|;  df = û dμN + μN dû
            for p in range(unknowns):
                along = u0 * trial[0, p] + u1 * trial[1, p]
                d_direction[0, p] = (trial[0, p] - u0 * along) / size
                d_direction[1, p] = (trial[1, p] - u1 * along) / size
                df[n, 0, p] = u0 * dlimit[n, p] + bound * d_direction[0, p]
                df[n, 1, p] = u1 * dlimit[n, p] + bound * d_direction[1, p]
                dw[0, p] = drt[n, 0, p] - df[n, 0, p] / kt
                dw[1, p] = drt[n, 1, p] - df[n, 1, p] / kt
            for q in range(2):
                along = u0 * trial_w[0, q] + u1 * trial_w[1, q]
                d_direction_w[0, q] = (trial_w[0, q] - u0 * along) / size
                d_direction_w[1, q] = (trial_w[1, q] - u1 * along) / size
                dfw[n, 0, q] = bound * d_direction_w[0, q]
                dfw[n, 1, q] = bound * d_direction_w[1, q]
                dww[0, q] = -dfw[n, 0, q] / kt
                dww[1, q] = -dfw[n, 1, q] / kt
    return w, dw, dww, moved


@numba.njit(cache=True)
def relax_at_closing(n, rt, depth, drt, ddepth, w, dw, dww, values):
    """The slider of a contact that closed between samples n − 1 and n put where the
    points were at the closing instant s_c (the cubic through δ at n − 2 … n + 1 crossing
    0): w = Σ ℓ_k(s_c) r_t,k, dw = Σ ℓ_k dr_t,k + (Σ ℓ_k' r_t,k) ds_c with
    ds_c = −Σ ℓ_k dδ_k / Σ ℓ_k' δ_k; it no longer depends on where the period started."""
    count, unknowns = drt.shape[0], drt.shape[2]
    for k in range(4):
        values[k] = depth[(n - 2 + k) % count]
    s = cubic_root(values)
    weights, slopes = lagrange(s)
    crossing = slopes @ values
    for c in range(2):
        w[c] = 0.0
        rate = 0.0
        for k in range(4):
            i = (n - 2 + k) % count
            w[c] += weights[k] * rt[i, c]
            rate += slopes[k] * rt[i, c]
        for p in range(unknowns):
            shift = 0.0
            value = 0.0
            for k in range(4):
                i = (n - 2 + k) % count
                shift += weights[k] * ddepth[i, p]
                value += weights[k] * drt[i, c, p]
            dw[c, p] = value - rate * shift / crossing
        dww[c, 0] = 0.0
        dww[c, 1] = 0.0


@numba.njit(cache=True)
def refine_stop(n, rt, limit, drt, dlimit, kt, w, dw, dww, direction, d_direction,
                d_direction_w, values):
    """The slider of a slip at sample n − 1 moved on to where g = û·r_t − μ_s N/k_t
    peaks between samples n − 1 and n (``slider_pass``), where it peaks inside the
    interval: w, dw (∂/∂z) and dww (∂/∂w_0) in place; û and its derivatives are sample
    n − 1's."""
    count, unknowns = drt.shape[0], drt.shape[2]
    u0, u1 = direction[0], direction[1]
    for k in range(4):
        i = (n - 2 + k) % count
        values[k] = u0 * rt[i, 0] + u1 * rt[i, 1] - limit[i] / kt
    s, peak, weights = cubic_peak(values)
    if s == 0.0 or s == 1.0:  # g turned back at t_{n−1}, or still rises at t_n
        return
    rise = peak - values[1]
    w[0] += u0 * rise
    w[1] += u1 * rise
    # d rise = Σ_k ℓ_k dg_k − dg_{n−1},  dg_i = dû·r_t,i + û·dr_t,i − dμN_i/k_t
    for k in range(4):
        i = (n - 2 + k) % count
        weight = weights[k] - (1.0 if k == 1 else 0.0)
        if weight == 0.0:
            continue
        for p in range(unknowns):
            change = weight * (d_direction[0, p] * rt[i, 0] + d_direction[1, p] * rt[i, 1]
                               + u0 * drt[i, 0, p] + u1 * drt[i, 1, p] - dlimit[i, p] / kt)
            dw[0, p] += u0 * change
            dw[1, p] += u1 * change
        for q in range(2):
            change = weight * (d_direction_w[0, q] * rt[i, 0]
                               + d_direction_w[1, q] * rt[i, 1])
            dww[0, q] += u0 * change
            dww[1, q] += u1 * change
    for p in range(unknowns):
        dw[0, p] += d_direction[0, p] * rise
        dw[1, p] += d_direction[1, p] * rise
    for q in range(2):
        dww[0, q] += d_direction_w[0, q] * rise
        dww[1, q] += d_direction_w[1, q] * rise


@dataclass(frozen=True, eq=False)
class Hysteresis:
    """A slider's periodic forces: ``force`` f (N × 2) [N], ``jacobian`` d(τᵀf)/dz
    (N × ρ × P, the force in the contact's coordinates), where its period starts
    (``start`` w_0 [m]), the ``periods`` marched, whether they repeated (``repeated``)
    and by how much the last one missed (``miss``, [m])."""

    force: np.ndarray
    jacobian: np.ndarray
    start: np.ndarray
    periods: int
    repeated: bool
    miss: float


@numba.njit(cache=True)
def inverse_2x2(matrix):
    """The inverse of a 2 × 2 ``matrix``, by its adjugate."""
    a, b, c, d = matrix[0, 0], matrix[0, 1], matrix[1, 0], matrix[1, 1]
    inverse = np.empty((2, 2))
    determinant = a * d - b * c
    inverse[0, 0], inverse[0, 1] = d / determinant, -b / determinant
    inverse[1, 0], inverse[1, 1] = -c / determinant, a / determinant
    return inverse


@numba.njit(cache=True)
def periodic_march(rt, limit, depth, drt, dlimit, ddepth, kt, tangents, steps, newton_after,
                   repeats):
    """The march of ``periodic_hysteresis`` compiled whole: (forces, ∂(τᵀf)/∂z, the start,
    the periods, whether they repeated, the last miss [m])."""
    count, unknowns = drt.shape[0], drt.shape[2]
    span = 0.0
    for c in range(2):
        span = max(span, rt[:, c].max() - rt[:, c].min())
    tolerance = repeats * max(span, limit.max() / kt, 1e-300)
    w = np.empty(2)
    carried = np.empty((2, unknowns))  # dw/dz of the stated start: the mean of r_t's
    for c in range(2):
        w[c] = rt[:, c].mean()
        for p in range(unknowns):
            carried[c, p] = drt[:, c, p].mean()
    force = np.empty((count, 2))
    partial = np.empty((count, 2, unknowns))
    by_start = np.empty((count, 2, 2))
    identity = np.eye(2)
    miss, periods, repeated = np.inf, 0, False
    moved_by, turned, moved = np.zeros((2, unknowns)), np.eye(2), False
    for periods in range(1, steps + 1):
        end, moved_by, turned, moved = slider_pass(rt, limit, depth, drt, dlimit, ddepth, kt,
                                                   w, force, partial, by_start)
        miss = max(abs(end[0] - w[0]), abs(end[1] - w[1]))
        if miss <= tolerance:
            repeated = True
            break
        if moved and periods >= newton_after:
            # Newton on P(w₀) − w₀ = 0: (I − A) Δ = P(w₀) − w₀
            w = w + np.dot(inverse_2x2(identity - turned), end - w)
        else:
            carried = moved_by + np.dot(turned, carried)
            w = end
    start_rate = np.dot(inverse_2x2(identity - turned), moved_by) if moved else carried
    rho = tangents.shape[1]
    jacobian = np.zeros((count, rho, unknowns))
    for n in range(count):
        total = partial[n] + np.dot(by_start[n], start_rate)
        for a in range(rho):
            for p in range(unknowns):
                jacobian[n, a, p] = (tangents[0, a] * total[0, p]
                                     + tangents[1, a] * total[1, p])
    return force, jacobian, w, periods, repeated, miss


def periodic_hysteresis(rt, limit, depth, drt, dlimit, ddepth, kt: float,
                        tangents: np.ndarray) -> Hysteresis:
    """The ``Hysteresis`` of a slider of stiffness ``kt`` [N/m] driven by ``rt`` (N × 2)
    under the limits ``limit`` (N) [N] at the penetrations ``depth`` (N) [m], with their
    derivatives ``drt`` (N × 2 × P), ``dlimit`` and ``ddepth`` (N × P) (module
    docstring), its Jacobian that of the force along the contact's coordinates, τᵀ f
    (``tangents`` τ: 2 × ρ): marched from the slider at the mean of r_t until a period
    repeats to ``REPEATS`` of the contact's scale, by Newton on the period's start past
    ``NEWTON_AFTER`` periods, ``HYSTERESIS_STEPS`` at most."""
    force, jacobian, start, periods, repeated, miss = periodic_march(
        rt, limit, depth, drt, dlimit, ddepth, float(kt), tangents, HYSTERESIS_STEPS,
        NEWTON_AFTER, REPEATS)
    return Hysteresis(force=force, jacobian=jacobian, start=start, periods=int(periods),
                      repeated=bool(repeated), miss=float(miss))
