"""Dynamics assembly for a fixed set of interface modes (DESIGN §2, paper eqs. 1–7).

With blade displacements x, the incidence matrix B (row e: +1 at the left blade i, −1 at the
right blade j) and the interface forces F_e = N_e sin α_e + f_e cos α_e,

    M ẍ + C ẋ + K x = Q(t) − Bᵀ F.                                   (paper eq. 7)

Open interfaces carry no force. A slipping interface carries its normal law's N and
f = μ(|v|) N sgn(v) (eqs. 2–6). Stuck interfaces join their blades into stick clusters that
move as one body: a cluster's acceleration is the sum of the forces on its blades (stuck
interfaces cancel inside) over its total mass, and the static friction forces follow from
each blade's equilibrium. For the paper's chain these are eqs. (10)–(22). A cluster holding a
cycle (an all-stuck ring) is statically indeterminate: we take the friction forces of
minimum Euclidean norm, which leave no force circulating round the cycle.

The array functions here are compiled with numba and take no Python objects, so the
integrator's loop calls them directly; ``assemble`` wraps them for a ``Scene``.
"""

from __future__ import annotations

import math
from typing import NamedTuple

import numpy as np
from numba import njit

from .clusters import cluster_labels
from .compiled import njit_inlined, njit_without_refcounts
from .modes import Mode
from .scene import Scene, SceneArrays

OPEN, STICK, SLIP_POSITIVE, SLIP_NEGATIVE = (int(m) for m in Mode)


@njit_without_refcounts
def excitation_forces(t, amplitudes, cos_phase, sin_phase, excitation_frequency, out):
    """Q_i(t) = s_i [q0 + Σ_n q_n sin(n (l Ω t + φ_i))] [N] (paper §2), written into ``out``.

    The tables have one row per harmonic n = 0 … n_harmonics and one column per blade
    (``SceneArrays.harmonic_amplitudes`` and ``harmonic_phases``): ``amplitudes[n, i]`` is
    s_i q_n, ``cos_phase[n, i]`` and ``sin_phase[n, i]`` are cos n φ_i and sin n φ_i. By
    sin(a + φ) = sin a cos φ + cos a sin φ, a harmonic costs one sine and one cosine
    whatever the number of blades.
    """
    for i in range(len(out)):
        out[i] = amplitudes[0, i]
    for n in range(1, amplitudes.shape[0]):
        angle = n * excitation_frequency * t
        sine = math.sin(angle)
        cosine = math.cos(angle)
        for i in range(len(out)):
            out[i] += amplitudes[n, i] * (sine * cos_phase[n, i] + cosine * sin_phase[n, i])


@njit_inlined
def relative_motion(x, v, left, right, e):
    """(u, u̇) of interface e: u = x_i − x_j of its left and right blades [m], and its rate
    [m/s]; a fixed node has x = 0."""
    u = 0.0
    du = 0.0
    if left[e] >= 0:
        u += x[left[e]]
        du += v[left[e]]
    if right[e] >= 0:
        u -= x[right[e]]
        du -= v[right[e]]
    return u, du


@njit_inlined
def interface_kinematics(x, v, left, right, gap, sin_angle, cos_angle,
                         penetration, rate, slip_velocity):
    """Penetration δ = (u − Δ) sin α [m], its rate δ̇ [m/s] and slip velocity u̇ cos α [m/s].

    u = x_i − x_j is the relative displacement of the left and right blades
    (``relative_motion``). Written into the last three arrays.
    """
    for e in range(len(left)):
        u, du = relative_motion(x, v, left, right, e)
        penetration[e] = (u - gap[e]) * sin_angle[e]
        rate[e] = du * sin_angle[e]
        slip_velocity[e] = du * cos_angle[e]


@njit_without_refcounts
def resultant_forces(x, v, q, damping, stiffness, left, right, interface_force, stuck,
                     resultant):
    """R_i = Q_i − c_i ẋ_i − k_i x_i − (Bᵀ F)_i over the interfaces that are not stuck [N].

    Written into ``resultant``.
    """
    for i in range(len(x)):
        resultant[i] = q[i] - damping[i] * v[i] - stiffness[i] * x[i]
    for e in range(len(left)):
        if stuck[e]:
            continue
        if left[e] >= 0:
            resultant[left[e]] -= interface_force[e]
        if right[e] >= 0:
            resultant[right[e]] += interface_force[e]


@njit(cache=True)
def cluster_mass(mass, labels, n_clusters):
    """Σ m [kg] of each stick cluster."""
    total = np.zeros(n_clusters)
    for i in range(len(mass)):
        total[labels[i]] += mass[i]
    return total


@njit_without_refcounts
def cluster_accelerations(resultant, labels, grounded, masses, cluster_force, acceleration):
    """ẍ_i = Σ_cluster R / Σ_cluster m for every blade of a cluster; 0 in a grounded one.

    ``masses`` are the clusters' masses (``cluster_mass``); ``cluster_force`` is scratch
    space of at least n_clusters; the result is written into ``acceleration``.
    """
    n_clusters = len(grounded)
    cluster_force[:n_clusters] = 0.0
    for i in range(len(resultant)):
        cluster_force[labels[i]] += resultant[i]
    for i in range(len(resultant)):
        c = labels[i]
        acceleration[i] = 0.0 if grounded[c] else cluster_force[c] / masses[c]


@njit(cache=True)
def static_friction_operator(n_blades, left, right, cos_angle, stuck):
    """The linear map P from blade force imbalances to static friction on stuck interfaces.

    Every blade i of a cluster obeys Σ_e B_ei (N_e sin α_e + f_e cos α_e) = R_i − m_i ẍ_i
    over its stuck interfaces e, i.e. G f = b with G_ie = B_ei cos α_e. P is the
    pseudo-inverse of G, so f = P b: exact for a tree cluster, the least-squares solution of
    minimum norm where a cycle makes the cluster indeterminate. G is block-diagonal by
    cluster, so P treats clusters independently. It depends only on the set of stuck
    interfaces and is computed once per mode change.

    Returns
    -------
    operator : float array (n_stuck, n_blades)
    stuck_interfaces : int64 array (n_stuck,)
    """
    stuck_interfaces = np.flatnonzero(stuck)
    matrix = np.zeros((n_blades, len(stuck_interfaces)))
    for k in range(len(stuck_interfaces)):
        e = stuck_interfaces[k]
        if left[e] >= 0:
            matrix[left[e], k] += cos_angle[e]
        if right[e] >= 0:
            matrix[right[e], k] -= cos_angle[e]
    if len(stuck_interfaces) == 0 or n_blades == 0:
        return np.zeros((len(stuck_interfaces), n_blades)), stuck_interfaces
    return np.ascontiguousarray(np.linalg.pinv(matrix)), stuck_interfaces


@njit_without_refcounts
def static_friction(operator, stuck_interfaces, mass, resultant, acceleration, normal_force,
                    sin_angle, left, right, imbalance, friction):
    """Static friction f_e [N] on each stuck interface, written into ``friction[e]``.

    f = P b with b_i = R_i − m_i ẍ_i − Σ_e B_ei N_e sin α_e over the stuck interfaces
    (see ``static_friction_operator``). Other entries of ``friction`` are left as they are;
    ``imbalance`` is scratch space of n_blades.
    """
    for i in range(len(mass)):
        imbalance[i] = resultant[i] - mass[i] * acceleration[i]
    for e in stuck_interfaces:
        push = normal_force[e] * sin_angle[e]
        if left[e] >= 0:
            imbalance[left[e]] -= push
        if right[e] >= 0:
            imbalance[right[e]] += push
    for k in range(len(stuck_interfaces)):
        value = 0.0
        for i in range(len(mass)):
            value += operator[k, i] * imbalance[i]
        friction[stuck_interfaces[k]] = value


@njit_inlined
def breakaway_margin(static_mu, normal_force, friction_force):
    """μ_s N − |f| [N]: how much more friction a stuck interface can hold."""
    return static_mu * normal_force - abs(friction_force)


@njit_inlined
def event_guards(modes, penetration, slip_velocity, normal_force, friction_force, static_mu,
                 opens, can_stick, contact, motion):
    """Guards: per interface, values that stay ≥ 0 while its mode holds and cross 0 at a switch.

    contact: −δ while open (crosses 0 as the contact closes), δ while closed (as it opens);
    +inf for a contact that never opens. motion: ±v while slipping with exact friction
    (crosses 0 as the slip velocity reaches zero); μ_s N − |f| while stuck (the breakaway
    margin); +inf otherwise. Written into ``contact`` and ``motion``.
    """
    for e in range(len(modes)):
        mode = modes[e]
        contact[e] = np.inf
        motion[e] = np.inf
        if opens[e]:
            contact[e] = -penetration[e] if mode == OPEN else penetration[e]
        if mode == STICK:
            motion[e] = breakaway_margin(static_mu[e], normal_force[e], friction_force[e])
        elif can_stick[e] and mode == SLIP_POSITIVE:
            motion[e] = slip_velocity[e]
        elif can_stick[e] and mode == SLIP_NEGATIVE:
            motion[e] = -slip_velocity[e]


def law_forces(arrays: SceneArrays, penetration, rate, slip_velocity, modes):
    """Normal force N_e and sliding friction f_e [N] from each interface's laws.

    Open interfaces carry nothing; stuck ones carry N and no sliding friction (their static
    friction comes from ``static_friction``). Exact laws slip with f = ±μ(|v|) N by the sign
    of the mode (paper eqs. 5–6); regularised ones with f = μ(|v|) N tanh(v/v_ε).
    This is the plain-Python evaluation of the laws; it calls each law object.
    """
    normal = np.zeros(arrays.n_interfaces)
    friction = np.zeros(arrays.n_interfaces)
    for e, law in enumerate(arrays.normal_laws):
        if modes[e] == OPEN:
            continue
        normal[e] = law(penetration[e], rate[e])
        friction_law = arrays.friction_laws[e]
        if friction_law is None or modes[e] == STICK:
            continue
        sliding = friction_law(slip_velocity[e]) * normal[e]
        if arrays.regularisation[e] > 0.0:
            friction[e] = sliding * math.tanh(slip_velocity[e] / arrays.regularisation[e])
        else:
            friction[e] = sliding if modes[e] == SLIP_POSITIVE else -sliding
    return normal, friction


class Assembly(NamedTuple):
    """The forces and accelerations of a scene in a given state and set of modes."""

    acceleration: np.ndarray     # ẍ_i [m/s²], by blade position
    normal_force: np.ndarray     # N_e [N], by interface
    friction_force: np.ndarray   # f_e [N]: sliding, or static on stuck interfaces
    interface_force: np.ndarray  # F_e = N_e sin α_e + f_e cos α_e [N], −F_e on i, +F_e on j
    cluster: np.ndarray          # stick-cluster label of each blade
    grounded: np.ndarray         # per cluster: joined to a fixed node
    contact_guard: np.ndarray    # see event_guards
    motion_guard: np.ndarray     # see event_guards


def assemble(scene: Scene, t: float, x, v, modes) -> Assembly:
    """Assemble the dynamics of ``scene`` at time ``t`` [s] in state (x [m], ẋ [m/s]).

    ``modes`` gives each interface's ``Mode``. A stuck interface must have zero slip
    velocity (its blades move together); the result's ``motion_guard`` tells whether each
    static friction force is admissible (|f| ≤ μ_s N).
    """
    a = scene.arrays
    x, v = _state(x, a.n_blades, "x"), _state(v, a.n_blades, "v")
    modes = np.asarray(modes, dtype=np.int64)
    if modes.shape != (a.n_interfaces,) or not np.isin(modes, list(Mode)).all():
        raise ValueError(f"modes must hold {a.n_interfaces} values of shroudnet.Mode, "
                         f"got {modes}")
    stuck = modes == STICK
    if np.any(stuck & ~a.can_stick):
        raise ValueError("modes: STICK on an interface that cannot stick (no exact friction "
                         f"law, or α = π/2): {np.flatnonzero(stuck & ~a.can_stick)}")
    n, m = a.n_blades, a.n_interfaces
    penetration, rate, slip_velocity = np.empty(m), np.empty(m), np.empty(m)
    interface_kinematics(x, v, a.left, a.right, a.gap, a.sin_angle, a.cos_angle,
                         penetration, rate, slip_velocity)
    normal, friction = law_forces(a, penetration, rate, slip_velocity, modes)
    interface_force = normal * a.sin_angle + friction * a.cos_angle
    q = np.empty(n)
    excitation_forces(float(t), a.harmonic_amplitudes, np.cos(a.harmonic_phases),
                      np.sin(a.harmonic_phases), a.excitation_frequency, q)
    labels, grounded = cluster_labels(n, a.left, a.right, stuck)
    resultant = np.empty(n)
    resultant_forces(x, v, q, a.damping, a.stiffness, a.left, a.right, interface_force, stuck,
                     resultant)
    acceleration = np.empty(n)
    cluster_accelerations(resultant, labels, grounded,
                          cluster_mass(a.mass, labels, len(grounded)), np.empty(n), acceleration)
    operator, stuck_interfaces = static_friction_operator(a.n_blades, a.left, a.right,
                                                          a.cos_angle, stuck)
    static_friction(operator, stuck_interfaces, a.mass, resultant, acceleration, normal,
                    a.sin_angle, a.left, a.right, np.empty(n), friction)
    interface_force = normal * a.sin_angle + friction * a.cos_angle
    contact, motion = np.empty(m), np.empty(m)
    event_guards(modes, penetration, slip_velocity, normal, friction, a.static_mu, a.opens,
                 a.can_stick, contact, motion)
    return Assembly(acceleration, normal, friction, interface_force, labels, grounded,
                    contact, motion)


def _state(values, n, name):
    array = np.asarray(values, dtype=float)
    if array.shape != (n,) or not np.isfinite(array).all():
        raise ValueError(f"{name} must hold {n} finite numbers (one per blade), got {values}")
    return np.ascontiguousarray(array)
