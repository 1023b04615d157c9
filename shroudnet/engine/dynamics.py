"""Dynamics assembly for a fixed set of interface modes (DESIGN §2, paper eqs. 1–7).

With blade displacements x, the incidence matrix B (row e: +1 at the left blade i, −1 at the
right blade j) and the interface forces F_e = N_e sin α_e + f_e cos α_e,

    M ẍ + C ẋ + K x = Q(t) − Bᵀ F.                                   (paper eq. 7)

K and C hold the blades' own springs and dampers (diagonal) and the couplings' (between
nodes; ``coupling_forces``); a coupling inside a stick cluster cancels in its sum, as a stuck
interface does, and loads the static friction like any other force on a blade.

Open interfaces carry no force. A slipping interface carries its normal law's N and
f = μ(|v|) N sgn(v) (eqs. 2–6). Stuck interfaces join their blades into stick clusters that
move as one body: a cluster's acceleration is the sum of the forces on its blades (stuck
interfaces cancel inside) over its total mass, and the static friction forces follow from
each blade's equilibrium. For the paper's chain these are eqs. (10)–(22). A cluster holding a
cycle (an all-stuck ring) is statically indeterminate: we take the friction forces of
minimum Euclidean norm, which leave no force circulating round the cycle.

A prescribed-motion node is a node of the state whose acceleration is given,
ẍ_p = a_p(t) (``prescribed_acceleration``); a cluster that holds one moves with it, and
the force its motion must exert does work on the group (``driven_accelerations``).

The array functions here are compiled with numba and take no Python objects, so the
integrator's loop calls them directly; ``assembly.assemble`` wraps them for a ``Scene``.
"""

from __future__ import annotations

import math

from .compiled import njit_inlined, njit_inlined_callable, njit_step_callable


@njit_inlined_callable
def continued_mu(mu, slope, speed):
    """μ of an exact friction law at the slip speed s signed by the slip mode, from μ = μ(|s|)
    and its slope μ'(|s|): μ for s ≥ 0, and μ + 2 μ' s for s < 0, a state just past the
    end of its mode, so that the mode's vector field leaves s = 0 with the slope μ'(0⁺)
    the slip side arrives with, where μ(|s|) would have a kink."""
    if speed >= 0.0:
        return mu
    return mu + 2.0 * slope * speed


@njit_inlined
def prescribed_acceleration(t, s, p):
    """(ẍ_p [m/s²], its rate [m/s³]) of prescribed-motion node p at time t [s]: the sum
    −A ω² sin(ω t + φ) + a(t) of its ``KernelScene`` terms (``motion.MotionTerms``), a(t)
    linear between its knots (and continued by the end pieces outside them)."""
    omega = s.motion_frequency[p]
    amplitude = s.motion_amplitude[p]
    angle = omega * t + s.motion_phase[p]
    acceleration = -amplitude * omega * omega * math.sin(angle)
    rate = -amplitude * omega * omega * omega * math.cos(angle)
    knots = s.motion_knots[p]
    if knots > 1:
        times, values = s.motion_times[p], s.motion_accelerations[p]
        j = 0
        while j < knots - 2 and times[j + 1] <= t:
            j += 1
        slope = (values[j + 1] - values[j]) / (times[j + 1] - times[j])
        acceleration += values[j] + slope * (t - times[j])
        rate += slope
    return acceleration, rate


@njit_inlined_callable
def driven_accelerations(labels, driver, masses, cluster_force, v, drive, n_blades,
                         acceleration):
    """ẍ = a_d of every node of a cluster driven by prescribed-motion node d (``drive``
    holds a_d by d − n_blades) into ``acceleration``; returns the power the prescribed
    motions put into the group [W]: Σ_c (M_c a_d − Σ_c R) ẋ_d, the force the motion exerts
    on its cluster beyond the cluster's resultant (``cluster_force``, from
    ``cluster_accelerations``), times its velocity."""
    power = 0.0
    for c in range(len(driver)):
        d = driver[c]
        if d >= 0:
            power += (masses[c] * drive[d - n_blades] - cluster_force[c]) * v[d]
    for i in range(len(labels)):
        d = driver[labels[i]]
        if d >= 0:
            acceleration[i] = drive[d - n_blades]
    return power


@njit_inlined_callable
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


@njit_step_callable
def excitation_rate(t, amplitudes, cos_phase, sin_phase, excitation_frequency, out):
    """dQ_i/dt [N/s] of ``excitation_forces`` (same tables), written into ``out``."""
    for i in range(len(out)):
        out[i] = 0.0
    for n in range(1, amplitudes.shape[0]):
        rate = n * excitation_frequency
        angle = rate * t
        sine = math.sin(angle)
        cosine = math.cos(angle)
        for i in range(len(out)):
            out[i] += rate * amplitudes[n, i] * (cosine * cos_phase[n, i]
                                                 - sine * sin_phase[n, i])


@njit_inlined
def relative_motion(x, v, left, right, e):
    """(u, u̇) of interface e: u = x_i − x_j of its left and right nodes [m], and its rate
    [m/s]; a fixed node has x = 0, a prescribed-motion node is in x."""
    u = 0.0
    du = 0.0
    if left[e] >= 0:
        u += x[left[e]]
        du += v[left[e]]
    if right[e] >= 0:
        u -= x[right[e]]
        du -= v[right[e]]
    return u, du


@njit_inlined_callable
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


@njit_inlined
def blade_kinematics(x, v, s, penetration, rate, slip_velocity):
    """``interface_kinematics`` of the scene ``s``'s interfaces (``structures.kinematics``
    joins it with the substructures' version)."""
    interface_kinematics(x, v, s.left, s.right, s.gap, s.sin_angle, s.cos_angle,
                         penetration, rate, slip_velocity)


@njit_inlined_callable
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


@njit_inlined_callable
def coupling_forces(x, v, left, right, stiffness, damping, resultant):
    """Subtract each coupling's F = k_c (x_i − x_j) + c_c (ẋ_i − ẋ_j) from node i's resultant
    and add it to node j's [N]; returns the power its dampers dissipate, Σ c_c (ẋ_i − ẋ_j)²
    [W]. A fixed node (−1) has x = 0."""
    power = 0.0
    for c in range(len(left)):
        u, du = relative_motion(x, v, left, right, c)
        force = stiffness[c] * u + damping[c] * du
        power += damping[c] * du * du
        if left[c] >= 0:
            resultant[left[c]] -= force
        if right[c] >= 0:
            resultant[right[c]] += force
    return power


@njit_inlined_callable
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


@njit_inlined_callable
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
