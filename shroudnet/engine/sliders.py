"""Elastic contacts: the Jenkins element of an interface with a tangential stiffness k_t.

Interface e's points move apart by r_t = (t₁·x, t₂·x) in its tangent plane (the rows
``tangent_rows`` and ``second_tangent_rows`` of a ``records.StructureScene``; t₂ = 0 for
one direction). A slider at w ties them through a spring of stiffness k_t. The state
carries the spring's stretch u = r_t − w [m], coordinates ``slider_index[e]`` and the
next (the second stays 0 for one direction), and not w itself: the friction force

    f = k_t u                                                          [N]

is then read off the state, never the difference of two nearly equal positions (a
contact that closes straight into slip starts with u at the size of the integrator's
error, far below r_t). It pushes the coordinates by −(f₁ t₁ + f₂ t₂). By the interface's
mode (DESIGN §7):

    open      u = 0,          u̇ = 0                 (w follows r_t: f = 0 as it closes)
    stuck     |f| ≤ μ N,      u̇ = ṙ_t               (w frozen)
    slipping  |f| = μ N,      u̇ = ṙ_t − û λ,  λ = û·ṙ_t − μ Ṅ / k_t ≥ 0

with ẇ = û λ the slider's velocity while slipping; λ keeps |f| = μN
(d|f|/dt = k_t û·u̇ = μṄ); Coulomb's one μ = μ_s. The guards are smooth: μN − |f| while
stuck (breakaway), λ while slipping (sticking: the slider's loading stops outrunning the
limit), and the contact's ±δ. The stretch is integrated as first-order coordinates: a
Runge–Kutta stage takes u̇ as their velocity (``kernel.step.dp5_step``), which
``derivative`` leaves in their acceleration slots.

The power the sliders take out is Σ f·ẇ = Σ μ N λ ≥ 0 [W] (the friction column of the
ledger); the contact stores ½ k_t |u|² [J]. Nothing here depends on the laws: the
kernel's forces give N and Ṅ (``kernel.forces.slider_rates``).
"""

import math

from .codes import OPEN, SLIP_NEGATIVE, SLIP_POSITIVE, STICK
from .compiled import njit_inlined
from .support import row_dot


@njit_inlined
def tangential_motion(s, e, values, first):
    """(t₁·y, t₂·y) of interface e over ``values[first:]`` (displacements or velocities)."""
    return (row_dot(s, s.tangent_rows, e, values, first),
            row_dot(s, s.second_tangent_rows, e, values, first))


@njit_inlined
def slider_forces(x, modes, s, w):
    """f = k_t u of every closed elastic contact into w.friction (t₁) and
    w.friction_second (t₂); 0 where open."""
    for e in range(len(modes)):
        k = s.slider_index[e]
        if k < 0:
            continue
        w.friction[e] = 0.0
        w.friction_second[e] = 0.0
        if modes[e] == OPEN:
            continue
        w.friction[e] = s.tangential_stiffness[e] * x[k]
        w.friction_second[e] = s.tangential_stiffness[e] * x[k + 1]


@njit_inlined
def push_second_friction(s, w):
    """R ← R − f₂ t₂ over every elastic contact's support (f₁ t₁ is pushed with N)."""
    for e in range(len(s.slider_index)):
        friction = w.friction_second[e]
        if s.slider_index[e] < 0 or friction == 0.0:
            continue
        for k in range(s.support_start[e], s.support_start[e + 1]):
            i = s.support_index[k]
            w.resultant[i] -= friction * s.second_tangent_rows[e, i]


@njit_inlined
def friction_size(w, e):
    """|f| [N] of elastic contact e."""
    return math.hypot(w.friction[e], w.friction_second[e])


@njit_inlined
def slider_guards(modes, s, w, motion):
    """The motion guards of the elastic contacts into ``motion``: μN − |f| while stuck,
    λ (w.slider_speed) while slipping, +inf while open."""
    for e in range(len(modes)):
        if s.slider_index[e] < 0:
            continue
        if modes[e] == OPEN:
            motion[e] = math.inf
        elif modes[e] == STICK:
            motion[e] = s.static_mu[e] * w.normal[e] - friction_size(w, e)
        else:
            motion[e] = w.slider_speed[e]


@njit_inlined
def slider_rate(s, e, v, w, mode, normal_rate):
    """(u̇₁, u̇₂, f·ẇ) of elastic contact e in ``mode``, with Ṅ = ``normal_rate``: the
    stretch's rate and the power the slider takes out [W]; λ into w.slider_speed[e] (the
    rate the slider would move at, were it slipping)."""
    if mode == OPEN:
        w.slider_speed[e] = 0.0
        return 0.0, 0.0, 0.0
    r1, r2 = tangential_motion(s, e, v, 0)
    size = friction_size(w, e)
    if size == 0.0:
        w.slider_speed[e] = 0.0
        return r1, r2, 0.0
    d1, d2 = w.friction[e] / size, w.friction_second[e] / size
    speed = d1 * r1 + d2 * r2 - s.static_mu[e] * normal_rate / s.tangential_stiffness[e]
    w.slider_speed[e] = speed
    if mode == STICK:
        return r1, r2, 0.0
    return r1 - d1 * speed, r2 - d2 * speed, size * speed


@njit_inlined
def release_slider(x, s, e):
    """u ← 0: the slider of elastic contact e relaxed (w = r_t, f = 0), as it opens or
    closes."""
    k = s.slider_index[e]
    x[k] = 0.0
    x[k + 1] = 0.0


@njit_inlined
def first_order_stage(s, velocities, accelerations, j):
    """Runge–Kutta stage j of the sliders, integrated as first-order coordinates: their
    stretch's rate u̇, which ``derivative`` left in the stage's accelerations, becomes the stage's
    velocity, and their acceleration 0 (their velocity slots stay 0)."""
    for e in range(len(s.slider_index)):
        k = s.slider_index[e]
        if k < 0:
            continue
        for i in range(k, k + 2):
            velocities[j, i] = accelerations[j, i]
            accelerations[j, i] = 0.0


@njit_inlined
def first_order_rk4_stage(s, x, h, rate, xt, vt):
    """A classical Runge–Kutta stage of the sliders, integrated as first-order coordinates
    (``kernel.step.rk4_step``): u + h u̇ into ``xt``, with u̇ the rate ``derivative`` left
    in ``rate``'s slots, and their velocity slots 0 in ``vt``."""
    for e in range(len(s.slider_index)):
        k = s.slider_index[e]
        if k < 0:
            continue
        for i in range(k, k + 2):
            xt[i] = x[i] + h * rate[i]
            vt[i] = 0.0


@njit_inlined
def first_order_rk4_end(s, x, h, a1, a2, a3, a4, x_new, v_new):
    """The end of a classical Runge–Kutta step of the sliders:
    u + h (u̇₁ + 2 u̇₂ + 2 u̇₃ + u̇₄)/6 into ``x_new``, their velocity slots 0 in ``v_new``."""
    for e in range(len(s.slider_index)):
        k = s.slider_index[e]
        if k < 0:
            continue
        for i in range(k, k + 2):
            x_new[i] = x[i] + h / 6.0 * (a1[i] + 2.0 * a2[i] + 2.0 * a3[i] + a4[i])
            v_new[i] = 0.0


@njit_inlined
def switch_slider(x, modes, s, e, contact_crossed, motion_crossed, friction):
    """The mode of elastic contact e after its guards crossed (as the flags say), its
    friction f₁ = ``friction`` [N]: closing sticks it and opening opens it, with the
    slider relaxed (``release_slider``); breakaway slips it (the mode's sign that of f₁),
    and λ falling to 0 sticks it."""
    if contact_crossed:
        modes[e] = STICK if modes[e] == OPEN else OPEN
        release_slider(x, s, e)
    elif motion_crossed and modes[e] == STICK:
        modes[e] = SLIP_POSITIVE if friction >= 0.0 else SLIP_NEGATIVE
    elif motion_crossed and modes[e] != OPEN:
        modes[e] = STICK


@njit_inlined
def initial_slider_modes(x, modes, s, w):
    """The elastic contacts' modes at the start, from their normal forces in w.normal: open
    ones relaxed (u = 0); closed ones stuck, or slipping where the stretch the start
    gives them holds its force at the limit or beyond, |f| ≥ μN (a run that takes up
    another's end)."""
    for e in range(len(modes)):
        k = s.slider_index[e]
        if k < 0:
            continue
        if modes[e] == OPEN:
            release_slider(x, s, e)
            continue
        stretch = math.hypot(x[k], x[k + 1])
        if stretch > 0.0 and s.tangential_stiffness[e] * stretch >= s.static_mu[e] * w.normal[e]:
            modes[e] = SLIP_POSITIVE if x[k] >= 0.0 else SLIP_NEGATIVE
        else:
            modes[e] = STICK
