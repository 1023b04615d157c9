"""Propagation: the exact motion through a phase whose vector field is linear
(``methods.Exponential``).

Between switches the modes are fixed, and with laws of constant slopes (``SceneArrays.
linear_phases``) the vector field is affine in the state, its time dependence the
excitation's harmonics. In the augmented state

    z = (x, ẋ, 1, cos ωt, sin ωt, …, cos Hωt, sin Hωt),   ω = lΩ,

it is linear, ż = A z, and a step of any size τ is z(τ) = e^{Aτ} z(0), exact. Each power
of the ledger (excitation, damping, friction, contact) is a quadratic form zᵀ Q_c z in
the phase, so the work of a step is z(0)ᵀ W_c(τ) z(0), W_c(τ) = ∫₀^τ e^{Aᵀs} Q_c e^{As} ds.

A phase keeps P_k = e^{A h 2⁻ᵏ} and W_c(h 2⁻ᵏ) for its ``levels`` k = 0 … L − 1, h the
fixed step. The P_k come from the scaled Padé exponential (``exponential``) at every
``SQUARINGS``-th level from the finest and by squaring in between: squared up from the
finest alone, their rounding doubles with each squaring (4e-9 after 28 on the two beams),
against 1e-14 with an anchor every 7. The W_c come by doubling, W(2τ) = W(τ) +
P(τ)ᵀ W(τ) P(τ), from the finest level's Taylor series. A step of size τ ≤ h applies the
levels of the binary digits of τ/h, and the remainder below the finest by the Taylor
series of e^{Ar} (its work by two-point Gauss quadrature).

The scaling is D = diag(1, 1/ω_b, 1) on (x, ẋ, forcing), ω_b² the largest row sum of
|∂ẍ/∂x|: the scaled matrix D A D⁻¹ then has blocks of one size, and its norm follows the
fastest frequency, where the excitation's time scale (``tangent.time_scale``) would let
ω_max²/ω dominate it.
"""

import math

import numpy as np

from .codes import N_POWERS
from .compiled import njit_inlined, njit_step
from .exponential import SLOTS, exponential, product

#: Levels squared up from each one the exponential computes.
SQUARINGS = 7
#: The finest level's scaled norm ‖D A D⁻¹‖₁ h 2^{1−L} that ``levels_for`` aims at.
FINEST_NORM = 1.0 / 64.0
#: The most levels a run keeps, whatever its stiffness.
MOST_LEVELS = 40
#: The most terms of a Taylor series (the finest level's works, a remainder's motion).
MOST_TERMS = 40
#: A span this close to the fixed step (relatively) is a whole step: t0 + (k + 1) h − t
#: differs from h by rounding; and a remainder this small (against h) is none: a binary
#: fraction of a step less its levels leaves rounding.
WHOLE = 1e-12
#: The phases a run keeps at most, and the bytes they may take together.
MOST_SLOTS = 8
SLOT_BYTES = 64 * 2**20
#: More interfaces than this have no key of their own (base 4 in an int64): their phases
#: are built again at every switch.
MOST_KEYED_INTERFACES = 30


def augmented_size(n_coordinates: int, harmonics: int) -> int:
    """m = 2n + 1 + 2H: the size of the augmented state."""
    return 2 * n_coordinates + 1 + 2 * harmonics


def levels_for(step: float, norm: float) -> int:
    """L such that the finest level's scaled norm ‖D A D⁻¹‖₁ h 2^{1−L} is at most
    ``FINEST_NORM`` (for a bound ``norm`` of ‖D A D⁻¹‖₁), within [2, ``MOST_LEVELS``]."""
    if not norm * step > FINEST_NORM:
        return 2
    return int(min(MOST_LEVELS, max(2, math.ceil(math.log2(norm * step / FINEST_NORM)) + 1)))


def slots_for(m: int, levels: int) -> int:
    """How many phases a run keeps: at most ``MOST_SLOTS``, within ``SLOT_BYTES``."""
    per_slot = 8 * m * m * (1 + N_POWERS) * (levels + 1)
    return int(max(1, min(MOST_SLOTS, SLOT_BYTES // per_slot)))


@njit_inlined
def modes_key(modes):
    """The key of a set of modes (base 4), or −1 for more than ``MOST_KEYED_INTERFACES``."""
    if len(modes) > MOST_KEYED_INTERFACES:
        return np.int64(-1)
    key = np.int64(0)
    for e in range(len(modes)):
        key = key * 4 + modes[e]
    return key


@njit_inlined
def select_phase(p, key):
    """Make the phase of ``key`` the one in use; returns whether it was kept, else claims
    a slot for it (the oldest) that the caller fills."""
    for slot in range(len(p.keys)):
        if key >= 0 and p.keys[slot] == key:
            p.slot[0] = slot
            return True
    slot = p.slot[1]
    p.slot[1] = (slot + 1) % len(p.keys)
    p.keys[slot] = key
    p.slot[0] = slot
    return False


@njit_inlined
def set_forcing(t, frequency, z, first):
    """The forcing coordinates of z from index ``first``: 1, cos nωt, sin nωt."""
    z[first] = 1.0
    for n in range(1, (len(z) - first - 1) // 2 + 1):
        angle = n * frequency * t
        z[first + 2 * n - 1] = math.cos(angle)
        z[first + 2 * n] = math.sin(angle)


@njit_inlined
def load_state(t, x, v, frequency, p):
    """p.z ← (x, ẋ, forcing at t)."""
    n = len(x)
    for i in range(n):
        p.z[i] = x[i]
        p.z[n + i] = v[i]
    set_forcing(t, frequency, p.z, 2 * n)


@njit_inlined
def store_state(p, x, v):
    """(x, ẋ) ← the motion part of p.z."""
    n = len(x)
    for i in range(n):
        x[i] = p.z[i]
        v[i] = p.z[n + i]


@njit_inlined
def _matrix_vector(a, z, out):
    for i in range(len(z)):
        total = 0.0
        for j in range(len(z)):
            total += a[i, j] * z[j]
        out[i] = total


@njit_inlined
def _quadratic(a, z):
    """zᵀ a z."""
    total = 0.0
    for i in range(len(z)):
        row = 0.0
        for j in range(len(z)):
            row += a[i, j] * z[j]
        total += z[i] * row
    return total


@njit_inlined
def _apply_level(p, slot, k, energy, with_energy):
    """p.z ← P_k p.z, and energy[c] += zᵀ W_{k,c} z."""
    if with_energy:
        for c in range(N_POWERS):
            energy[c] += _quadratic(p.forms[slot, k, c], p.z)
    _matrix_vector(p.levels[slot, k], p.z, p.z_next)
    for i in range(len(p.z)):
        p.z[i] = p.z_next[i]


@njit_inlined
def series(a, span, z, out, term, spare):
    """out ← e^{a span} z by its Taylor series, to the last term that changes it (span
    small against a: below the finest level)."""
    m = len(z)
    for i in range(m):
        out[i] = z[i]
        term[i] = z[i]
    for j in range(1, MOST_TERMS):
        _matrix_vector(a, term, spare)
        size = 0.0
        largest = 0.0
        for i in range(m):
            term[i] = spare[i] * span / j
            out[i] += term[i]
            size = max(size, abs(out[i]))
            largest = max(largest, abs(term[i]))
        if largest <= 1e-17 * size:
            break


@njit_step
def propagate(p, span, energy, with_energy):
    """p.z ← z(span), span ∈ [0, h] (h the fixed step), through the phase in use: the
    levels of span/h's binary digits, then the remainder by Taylor series; with
    ``with_energy``, the works of the powers over it are added to energy[0 … N_POWERS − 1].
    A span within ``WHOLE`` of h is a whole step (a grid step's end minus its start)."""
    slot = p.slot[0]
    step = p.step[0]
    if span >= step * (1.0 - WHOLE):
        _apply_level(p, slot, 0, energy, with_energy)
        return
    remaining = span
    piece = step
    for k in range(1, p.levels.shape[1]):
        if remaining <= step * WHOLE:  # a binary fraction of the step, to rounding
            return
        piece *= 0.5
        if remaining >= piece - step * WHOLE:
            _apply_level(p, slot, k, energy, with_energy)
            remaining -= piece
    if remaining <= step * WHOLE:
        return
    a = p.matrix[slot]
    if with_energy:  # two-point Gauss over the remainder
        offset = 0.5 / math.sqrt(3.0)
        for node in (0.5 - offset, 0.5 + offset):
            series(a, node * remaining, p.z, p.z_next, p.term, p.spare)
            for c in range(N_POWERS):
                energy[c] += 0.5 * remaining * _quadratic(p.quadratic[slot, c], p.z_next)
    series(a, remaining, p.z, p.z_next, p.term, p.spare)
    for i in range(len(p.z)):
        p.z[i] = p.z_next[i]


@njit_inlined
def scaling(a, n, scale):
    """D's diagonal into ``scale``: 1 on x and the forcing, 1/ω_b on ẋ, ω_b² the largest
    row sum of |∂ẍ/∂x| (1 where there is none)."""
    largest = 0.0
    for i in range(n, 2 * n):
        total = 0.0
        for j in range(n):
            total += abs(a[i, j])
        largest = max(largest, total)
    rate = math.sqrt(largest) if largest > 0.0 else 1.0
    for i in range(len(scale)):
        scale[i] = 1.0 / rate if n <= i < 2 * n else 1.0


#: The slots of a ``Propagation``'s ``work`` beyond the exponential's: the scaled matrix,
#: and two for products.
SCALED, FIRST, SECOND = SLOTS, SLOTS + 1, SLOTS + 2
WORK_SLOTS = SLOTS + 3


@njit_step
def fill_levels(p, slot, step, n):
    """The levels of the phase in ``slot`` from its A and Q_c (``matrix``, ``quadratic``):
    P_k = e^{A h 2⁻ᵏ} and W_c(h 2⁻ᵏ), h = ``step``, n the coordinates (module docstring).
    Works in the scaled coordinates D z and brings the results back."""
    a, quadratic = p.matrix[slot], p.quadratic[slot]
    levels, forms, work, scale = p.levels[slot], p.forms[slot], p.work, p.spare
    m = a.shape[0]
    finest = levels.shape[0] - 1
    scaling(a, n, scale)
    scaled, first, second = work[SCALED], work[FIRST], work[SECOND]
    for i in range(m):
        for j in range(m):
            scaled[i, j] = scale[i] * a[i, j] / scale[j]
    for k in range(finest, -1, -1):
        if (finest - k) % SQUARINGS == 0:
            span = step * 0.5**k
            for i in range(m):
                for j in range(m):
                    work[0, i, j] = scaled[i, j] * span
            exponential(work[:SLOTS])
            for i in range(m):
                for j in range(m):
                    levels[k, i, j] = work[0, i, j]
        else:
            product(levels[k + 1], levels[k + 1], levels[k])
    span = step * 0.5**finest
    for c in range(N_POWERS):
        finest_work(quadratic[c], scaled, scale, span, forms[finest, c], first, second,
                    work[0])
        for k in range(finest, 0, -1):  # W(2τ) = W(τ) + P(τ)ᵀ W(τ) P(τ)
            product(forms[k, c], levels[k], first)
            product(levels[k].T, first, second)
            for i in range(m):
                for j in range(m):
                    forms[k - 1, c, i, j] = forms[k, c, i, j] + second[i, j]
    for k in range(finest + 1):  # back from D z: P = D⁻¹ P̃ D, W = D W̃ D
        for i in range(m):
            for j in range(m):
                levels[k, i, j] *= scale[j] / scale[i]
                for c in range(N_POWERS):
                    forms[k, c, i, j] *= scale[i] * scale[j]


@njit_inlined
def finest_work(quadratic, scaled, scale, span, out, term, following, spare):
    """W̃(τ) = Σ_j τ^{j+1}/(j+1)! T_j, T_0 = D⁻¹ Q D⁻¹, T_{j+1} = Ãᵀ T_j + T_j Ã, into
    ``out`` (Ã = ``scaled``, τ = ``span`` below the finest level's norm)."""
    m = out.shape[0]
    for i in range(m):
        for j in range(m):
            term[i, j] = quadratic[i, j] / (scale[i] * scale[j])
            out[i, j] = span * term[i, j]
    factor = span
    for power in range(1, MOST_TERMS):
        product(term, scaled, following)
        product(scaled.T, term, spare)
        factor *= span / (power + 1)
        size = 0.0
        largest = 0.0
        for i in range(m):
            for j in range(m):
                term[i, j] = following[i, j] + spare[i, j]
                change = factor * term[i, j]
                out[i, j] += change
                size = max(size, abs(out[i, j]))
                largest = max(largest, abs(change))
        if largest <= 1e-17 * size:
            break
