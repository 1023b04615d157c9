"""Elastic contacts' tangent: the variations of their forces and stretch rates, and the
gradients of their guards (their motion: ``sliders``; DESIGN §6–7).

A change d = (δx, δẋ) of the state changes an elastic contact's friction force by
δf = k_t δu (the stretch u is a coordinate), and its stretch rate, by its mode, by

    open      δu̇ = 0
    stuck     δu̇ = δṙ_t,                                     δṙ_t = (t₁·δẋ, t₂·δẋ)
    slipping  δu̇ = P δṙ_t − λ δû − û (δû·u̇) + û μ δṄ / k_t,

from u̇ = ṙ_t − û λ, λ = û·ṙ_t − μṄ/k_t, with û = u/|u|, P = I − û ûᵀ,
δû = P δu / |u| (so δû·ṙ_t = δû·u̇) and δṄ = ∂N/∂δ n·δẋ + ∂N/∂δ̇ n·δẍ: the normal law's
slopes are taken as constant (``generate.load_kernel`` refuses the tangent flow of an
elastic contact whose law's are not, whose δṄ would need its curvature).

The stretch is a first-order coordinate: its δu̇ is the x-row of J d, left in the
direction's velocity slot (which no force reads, as the state's own velocity slot of a
stretch), and its δẍ is 0, so that every caller reads J d from (d[n:], δẍ) alike.

A slipping stretch's direction relaxes at the rate λ/|u| (J's eigenvalue −λ/|u| along
P δu). Where a face unloads to its separation while it slips, |u| = μN/k_t falls to 0
with N, linearly in the time d left, and the rate grows as κ/d (κ = λ k_t/(μ|Ṅ|): 13 on
the three-blade packet at 2800 rpm). Explicit steps follow such a mode only while
h λ/|u| stays below a few, so the tangent's error held the steps at a fixed fraction of
d (0.11 d with one column, 0.007 d with 22) and they never reached the separation.
Worse, the integrated |u| drifts from μN/k_t by the integration error (the flow keeps
|u| − μN/k_t, it does not restore it): drifted inwards, by 1.9e-16 m there, the stretch
collapses 1.2e-13 s before the face opens, and its direction, the state's u/|u| at
lengths of 1e-18 m, is not resolved at all (it turned by 1.8e-3 rad). Drifted outwards,
the face opened first, at a finite rate: which of the two happened decided whether a
tangent run passed, not its columns or its rtol. The run resolves time to its event
tolerance ε (``records.Tangent.resolution``), so the tangent resolves a stretch's
direction down to the length |λ| ε its slider moves in that time, no further: it turns
a shorter stretch by that length (``turning_length``: a rate of at most 1/ε), and its
error leaves out the rows of such a stretch (``leave_out_unresolved``), whose force
k_t δu acts for a time of order ε before the separation resets it (u ← 0), or after a
slip starts from a stretch that closing relaxed. The exact Jacobian (``linearise_at``)
has ε = 0.
"""

import math

from .codes import OPEN, STICK
from .compiled import njit_inlined
from .support import row_dot


@njit_inlined
def slider_force_change(direction, s, modes, change):
    """δR ← δR − k_t (δu₁ t₁ + δu₂ t₂) over every closed elastic contact (``change``:
    the resultant's change along ``direction``)."""
    for e in range(len(modes)):
        k = s.slider_index[e]
        if k < 0 or modes[e] == OPEN:
            continue
        first = s.tangential_stiffness[e] * direction[k]
        second = s.tangential_stiffness[e] * direction[k + 1]
        for index in range(s.support_start[e], s.support_start[e + 1]):
            i = s.support_index[index]
            change[i] -= first * s.tangent_rows[e, i] + second * s.second_tangent_rows[e, i]


@njit_inlined
def slider_rate_change(direction, s, modes, g):
    """δu̇ of every elastic contact along ``direction`` into its velocity slots, its δẍ
    slots 0, from the state's forces and rates in g (``kernel.tangent.linearise``: g.work,
    the stretch rates in g.acceleration) and δẍ in g.acceleration_change."""
    n = len(s.mass)
    for e in range(len(modes)):
        k = s.slider_index[e]
        if k < 0:
            continue
        first, second = 0.0, 0.0
        if modes[e] != OPEN:
            first = row_dot(s, s.tangent_rows, e, direction, n)
            second = row_dot(s, s.second_tangent_rows, e, direction, n)
        if modes[e] != OPEN and modes[e] != STICK:
            first, second = _slipping_rate_change(direction, s, e, k, first, second, g)
        direction[n + k] = first
        direction[n + k + 1] = second
        g.acceleration_change[k] = 0.0
        g.acceleration_change[k + 1] = 0.0


@njit_inlined
def _slipping_rate_change(direction, s, e, k, first, second, g):
    """(δu̇₁, δu̇₂) of slipping elastic contact e (stretch at k), from δṙ_t = (``first``,
    ``second``): P δṙ_t − λ δû − û (δû·u̇) + û μ δṄ / k_t, with δû = P δu / ℓ and ℓ
    the ``turning_length`` (|u| where the run resolves the stretch's direction)."""
    w = g.work
    n = len(s.mass)
    stiffness = s.tangential_stiffness[e]
    size = math.hypot(w.friction[e], w.friction_second[e])
    if size == 0.0:
        return first, second
    d1, d2 = w.friction[e] / size, w.friction_second[e] / size
    speed = w.slider_speed[e]
    length = turning_length(size / stiffness, speed, g.resolution)
    along = d1 * first + d2 * second
    first, second = first - d1 * along, second - d2 * along
    along_u = d1 * direction[k] + d2 * direction[k + 1]
    turn1 = (direction[k] - d1 * along_u) / length
    turn2 = (direction[k + 1] - d2 * along_u) / length
    turn_rate = turn1 * g.acceleration[k] + turn2 * g.acceleration[k + 1]
    normal_change = g.normal_u[e] * row_dot(s, s.normal_rows, e, direction, n) \
        + g.normal_du[e] * row_dot(s, s.normal_rows, e, g.acceleration_change, 0)
    loading = s.static_mu[e] * normal_change / stiffness - turn_rate
    return (first - speed * turn1 + d1 * loading,
            second - speed * turn2 + d2 * loading)


@njit_inlined
def turning_length(stretch, speed, resolution):
    """The length [m] a slipping stretch turns by in the tangent, δû = P δu / ℓ: its own,
    |u| = ``stretch``, but no less than the length |λ| ε its slider moves in the time
    ε = ``resolution`` [s] the run resolves, λ = ``speed`` [m/s] (module docstring)."""
    return max(stretch, abs(speed) * resolution)


@njit_inlined
def leave_out_unresolved(modes, s, g):
    """Zero the stages' rows (g.stages) of every slipping stretch shorter than the length
    its slider moves in the run's resolution, |u| < |λ| ε at the step's end (the forces
    in g.work), so that they take no part in the tangent's error: the run does not
    resolve that stretch's direction (module docstring). Once the candidate is formed,
    only the error reads the stages."""
    w = g.work
    for e in range(len(modes)):
        k = s.slider_index[e]
        if k < 0 or modes[e] == OPEN or modes[e] == STICK:
            continue
        stretch = math.hypot(w.friction[e], w.friction_second[e]) / s.tangential_stiffness[e]
        if turning_length(stretch, w.slider_speed[e], g.resolution) > stretch:
            for j in range(g.stages.shape[0]):
                for column in range(g.stages.shape[2]):
                    g.stages[j, k, column] = 0.0
                    g.stages[j, k + 1, column] = 0.0


@njit_inlined
def slider_breakaway_normal(e, s, g):
    """∂g/∂y into g.guard_normal of elastic contact e's breakaway guard g = μN − k_t|u|,
    from the slopes in g: μ ∂N/∂δ n on δx, μ ∂N/∂δ̇ n on δẋ, −k_t û on δu."""
    n = len(s.mass)
    normal = g.guard_normal
    for r in range(len(normal)):
        normal[r] = 0.0
    mu = s.static_mu[e]
    for index in range(s.support_start[e], s.support_start[e + 1]):
        i = s.support_index[index]
        normal[i] = mu * g.normal_u[e] * s.normal_rows[e, i]
        normal[n + i] = mu * g.normal_du[e] * s.normal_rows[e, i]
    w = g.work
    size = math.hypot(w.friction[e], w.friction_second[e])
    if size > 0.0:
        k = s.slider_index[e]
        normal[k] = -s.tangential_stiffness[e] * w.friction[e] / size
        normal[k + 1] = -s.tangential_stiffness[e] * w.friction_second[e] / size


@njit_inlined
def first_order_field(s, field):
    """The vector field (ẋ, ẍ) as the tangent sees it: a stretch's rate u̇, which
    ``derivative`` leaves in its acceleration slot, moved to its x-row, and 0 below."""
    n = len(s.mass)
    for e in range(len(s.slider_index)):
        k = s.slider_index[e]
        if k < 0:
            continue
        for i in range(k, k + 2):
            field[i] = field[n + i]
            field[n + i] = 0.0


@njit_inlined
def release_open_stretches(modes, s, matrix):
    """Φ's rows of an open elastic contact's stretch ← 0: its slider follows (u = 0), so no
    change of the state changes it (the reset u ← 0 of opening, in the saltation)."""
    for e in range(len(modes)):
        k = s.slider_index[e]
        if k < 0 or modes[e] != OPEN:
            continue
        for column in range(matrix.shape[1]):
            matrix[k, column] = 0.0
            matrix[k + 1, column] = 0.0


@njit_inlined
def slipping_start(x, s, e, normal, slope, rate_slope, matrix):
    """Elastic contact e starts slipping, at its normal force ``normal`` N with slopes
    ∂N/∂δ = ``slope`` and ∂N/∂δ̇ = ``rate_slope``: its stretch is put on the friction limit,
    u ← r û with r = μN/k_t, and the tangent's rows of it are that projection's
    derivative, δu ← (μ δN/k_t) û + (r/|u|) P δu with δN = ∂N/∂δ n·δx + ∂N/∂δ̇ n·δẋ (a
    start just inside the limit sticks and breaks away at once, with the same
    derivative)."""
    k = s.slider_index[e]
    n = len(s.mass)
    stretch = math.hypot(x[k], x[k + 1])
    d1, d2 = x[k] / stretch, x[k + 1] / stretch
    mu_over_k = s.static_mu[e] / s.tangential_stiffness[e]
    scale = mu_over_k * normal / stretch
    for column in range(matrix.shape[1]):
        radial = d1 * matrix[k, column] + d2 * matrix[k + 1, column]
        change = slope * row_dot_column(s, e, matrix, column, 0) \
            + rate_slope * row_dot_column(s, e, matrix, column, n)
        matrix[k, column] = mu_over_k * change * d1 + scale * (matrix[k, column] - d1 * radial)
        matrix[k + 1, column] = mu_over_k * change * d2 \
            + scale * (matrix[k + 1, column] - d2 * radial)
    x[k] *= scale
    x[k + 1] *= scale


@njit_inlined
def row_dot_column(s, e, matrix, column, first):
    """n_e · (rows ``first`` … of Φ's ``column``): the change of interface e's penetration
    (``first`` 0) or its rate (``first`` n) along that tangent vector."""
    total = 0.0
    for index in range(s.support_start[e], s.support_start[e + 1]):
        i = s.support_index[index]
        total += s.normal_rows[e, i] * matrix[first + i, column]
    return total
