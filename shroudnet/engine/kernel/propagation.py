"""Propagation: the exact step of a linear phase, and the phase's matrices from the vector
field (law-aware; the levels and their use: ``shroudnet.engine.propagation``).

In an exponential kernel (``EXPONENTIAL``) every phase starts with ``prepare_phase``,
which puts in use the propagation of its modes, built once per run: its augmented matrix A
and the powers' quadratic forms Q_c from ``derivative`` itself (``linear_field``), then
its levels. ``exact_step`` and ``step.motion_inside`` read the state off them.
"""

import math
from typing import TYPE_CHECKING

from shroudnet.engine.advance import set_powers
from shroudnet.engine.codes import N_POWERS, N_WORK
from shroudnet.engine.compiled import njit_inlined, njit_step
from shroudnet.engine.propagation import (fill_levels, load_state, modes_key, propagate,
                                          select_phase, store_state)
from shroudnet.engine.tableau import DP_STAGES

if TYPE_CHECKING:
    from .forces import derivative, evaluate_guards


@njit_step
def exact_step(t, h, state, topology, s, w):
    """The exact step of size h from t through the phase in use (``propagation``): the new
    state and work columns into w.x_new, w.v_new, w.e_new, with the forces and guards at
    its end (w.a_end, w.contact, w.motion)."""
    p = state.propagation
    load_state(t, state.x, state.v, s.excitation_frequency, p)
    for c in range(N_WORK):
        w.e_new[c] = state.energy[c]
    propagate(p, h, w.e_new, True)
    store_state(p, w.x_new, w.v_new)
    set_powers(w.stage_p[DP_STAGES - 1], evaluate_guards(t + h, w.x_new, w.v_new, state.modes,
                                                         topology, s, w, w.a_end))


@njit_step
def prepare_phase(state, topology, s):
    """Put in use the propagation of the phase of the state's modes: kept from an earlier
    phase of the same modes, or built (``linear_field``, then ``propagation.fill_levels``)."""
    p = state.propagation
    if select_phase(p, modes_key(state.modes)):
        return
    slot = p.slot[0]
    linear_field(state.modes, topology, s, p, slot)
    fill_levels(p, slot, p.step[0], len(state.x))


@njit_step
def linear_field(modes, topology, s, p, slot):
    """A and Q_c of the phase of ``modes`` (``propagation``) into p.matrix[slot] and
    p.quadratic[slot], from the vector field and powers of ``derivative``, which are affine
    and quadratic in the state for fixed modes and laws of constant slopes, wherever the
    state: central differences at ±σ e_r give A's columns and the powers' linear terms
    exactly (σ = 1 on x, ω on ẋ), the quadratic terms come by polarisation at the sums of
    two, and the forcing and the linear terms' harmonics by the discrete Fourier transform
    of their values at 2H + 1 times of a period."""
    n = len(s.mass)
    a, quadratic = p.matrix[slot], p.quadratic[slot]
    m = a.shape[0]
    one = 2 * n
    count = m - 2 * n  # 2H + 1
    frequency = s.excitation_frequency
    period = 2.0 * math.pi / frequency if frequency > 0.0 else 0.0
    x, v, acceleration, w = p.x, p.v, p.acceleration, p.field
    for i in range(m):
        for j in range(m):
            a[i, j] = 0.0
            for c in range(N_POWERS):
                quadratic[c, i, j] = 0.0
    for i in range(n):
        a[i, n + i] = 1.0
    for h in range(1, (count - 1) // 2 + 1):
        a[one + 2 * h - 1, one + 2 * h] = -h * frequency
        a[one + 2 * h, one + 2 * h - 1] = h * frequency
    for j in range(count):
        time = j * period / count
        _set_basis(x, v, -1, 0.0, -1, 0.0)
        powers = derivative(time, x, v, modes, topology, s, w, acceleration)
        for i in range(n):
            _add_harmonics(a[n + i], one, acceleration[i], j, count, 1.0)
        for c in range(N_POWERS):
            _add_harmonics(quadratic[c, one], one, powers[c], j, count, 0.5)
            _add_harmonics(quadratic[c, :, one], one, powers[c], j, count, 0.5)
        for r in range(2 * n):
            size = _basis_size(r, n, frequency)
            _set_basis(x, v, r, size, -1, 0.0)
            plus = derivative(time, x, v, modes, topology, s, w, acceleration)
            if j == 0:
                for i in range(n):
                    a[n + i, r] = acceleration[i]
            _set_basis(x, v, r, -size, -1, 0.0)
            minus = derivative(time, x, v, modes, topology, s, w, acceleration)
            if j == 0:
                for i in range(n):
                    a[n + i, r] = (a[n + i, r] - acceleration[i]) / (2.0 * size)
            for c in range(N_POWERS):
                linear = (plus[c] - minus[c]) / (2.0 * size)
                _add_harmonics(quadratic[c, r], one, linear, j, count, 0.5)
                _add_harmonics(quadratic[c, :, r], one, linear, j, count, 0.5)
                if j == 0:
                    quadratic[c, r, r] = (plus[c] + minus[c] - 2.0 * powers[c]) \
                        / (2.0 * size * size)
    _set_basis(x, v, -1, 0.0, -1, 0.0)
    zero = derivative(0.0, x, v, modes, topology, s, w, acceleration)
    for r in range(2 * n):
        for q in range(r + 1, 2 * n):
            size_r, size_q = _basis_size(r, n, frequency), _basis_size(q, n, frequency)
            _set_basis(x, v, r, size_r, q, size_q)
            both = derivative(0.0, x, v, modes, topology, s, w, acceleration)
            for c in range(N_POWERS):
                # p(σ_r e_r + σ_q e_q) − p(0) less the diagonal and linear terms
                rest = both[c] - zero[c] - size_r * size_r * quadratic[c, r, r] \
                    - size_q * size_q * quadratic[c, q, q] \
                    - size_r * _linear_at_zero(quadratic[c, r], one) \
                    - size_q * _linear_at_zero(quadratic[c, q], one)
                value = rest / (2.0 * size_r * size_q)
                quadratic[c, r, q] = value
                quadratic[c, q, r] = value


@njit_inlined
def _basis_size(r, n, frequency):
    """σ of coordinate r of (x, ẋ): 1 on x, ω on ẋ (1 without excitation)."""
    return 1.0 if r < n or frequency <= 0.0 else frequency


@njit_inlined
def _set_basis(x, v, r, size_r, q, size_q):
    """(x, ẋ) ← σ_r e_r + σ_q e_q (r or q −1 for none)."""
    n = len(x)
    for i in range(n):
        x[i] = 0.0
        v[i] = 0.0
    for index, size in ((r, size_r), (q, size_q)):
        if index >= n:
            v[index - n] = size
        elif index >= 0:
            x[index] = size


@njit_inlined
def _add_harmonics(row, one, value, j, count, factor):
    """Add ``factor`` times the discrete Fourier coefficients of a sample ``value`` at
    time j of ``count`` over a period into row[one:]: the mean, then cos and sin of each
    harmonic h (2/count · value · cos or sin 2πhj/count)."""
    row[one] += factor * value / count
    for h in range(1, (count - 1) // 2 + 1):
        angle = 2.0 * math.pi * h * j / count
        row[one + 2 * h - 1] += factor * 2.0 / count * value * math.cos(angle)
        row[one + 2 * h] += factor * 2.0 / count * value * math.sin(angle)


@njit_inlined
def _linear_at_zero(row, one):
    """b_r(0) of a power's linear term b_r(t) y_r from its quadratic form's row r, whose
    forcing entries hold b_r's coefficients halved: 2 (row[1] + Σ_h row[cos h])."""
    total = row[one]
    for h in range(1, (len(row) - one - 1) // 2 + 1):
        total += row[one + 2 * h - 1]
    return 2.0 * total
