"""Saltation: the tangent across a switch (DESIGN §6; the flow between switches: ``tangent``).

At a switch on the guard surface g(y, t) = 0 with gradient n = ∂g/∂y, where the state is
mapped by y⁺ = P y⁻ (the velocities projected onto the new stick clusters, ``regroup``)
and the vector field changes from f⁻ to f⁺, the tangent is multiplied by the saltation
matrix (Leine & Nijmeijer 2004, ch. 7; Müller 1995):

    S = P + (f⁺ − P f⁻) nᵀ / (nᵀ f⁻ + ∂g/∂t).

The guards' gradients are ``contact_normal``, ``slip_normal`` and ``breakaway_normal``;
``apply_saltation`` multiplies one switch in, ``apply_saltations`` several at one instant
where their saltations commute. A grazing switch (``grazing``) and one of several guards
that do not commute are counted as singular, never silently multiplied in.
"""

from .compiled import njit_inlined, njit_step, njit_step_exact
from .constraints import reduce_to_constraints
from .dispatch import by_scene
from .dynamics import cluster_accelerations, excitation_rate, prescribed_acceleration
from .regroup import project_velocities
from .structures import (structure_breakaway_normal, structure_contact_normal,
                         structure_saltations, structure_slip_normal, stuck_position,
                         unit_direction)
from .tangent import linearised_acceleration, time_scale

#: A switch is grazing when its saltation's correction (f⁺ − P f⁻) nᵀ / ġ would stretch
#: a tangent by more than this: |Δẍ| (|∂g/∂x| τ + |∂g/∂ẋ|) / |ġ|, with ġ = nᵀ f⁻ + ∂g/∂t,
#: Δẍ the jump of the accelerations and τ = 1/(l Ω) the excitation's time scale (1 s
#: without excitation). Where the vector field is continuous (a contact law with
#: N(0) = 0) the jump vanishes with ġ, and grazing is harmless.
GRAZING_GAIN = 1e6


@njit_inlined
def correction_stretch(jump_size, normal, s):
    """How far a saltation's correction stretches a tangent per unit of the guard's rate ġ,
    for accelerations that jump by at most ``jump_size`` across a guard with gradient
    ``normal`` (∂g/∂y, 2n): ``jump_size`` (|∂g/∂x| τ + |∂g/∂ẋ|) (``GRAZING_GAIN``)."""
    n = len(s.mass)
    by_position = 0.0
    by_velocity = 0.0
    for i in range(n):
        by_position = max(by_position, abs(normal[i]))
        by_velocity = max(by_velocity, abs(normal[n + i]))
    return jump_size * (by_position * time_scale(s) + by_velocity)


@njit_inlined
def grazing(jump_size, normal, s, rate):
    """Whether a switch with guard gradient ``normal`` (∂g/∂y, 2n) and rate ġ = ``rate``
    grazes: its saltation's correction, with accelerations that jump by at most
    ``jump_size``, would stretch a tangent by more than ``GRAZING_GAIN``."""
    return correction_stretch(jump_size, normal, s) > GRAZING_GAIN * abs(rate)


@njit_inlined
def count_singular(t, e, g):
    """Count a switch at t on interface e whose saltation matrix is singular (grazing, or
    several guards at once); the first one's time and interface are kept."""
    if g.singular[0] == 0:
        g.singular_time[0] = t
        g.singular_interface[0] = e
    g.singular[0] += 1


@njit_step
def reduce_on_clusters(normal, s, topology, rows):
    """n ← Pᵀ n: a guard's gradient as it acts on tangents of the stick clusters of
    ``topology`` (P as ``regroup.project_velocities``): each velocity component becomes
    its cluster's sum times the blade's share of the cluster's mass, 0 in a grounded
    cluster; in a driven one the sum goes to the prescribed node's component."""
    n = len(s.mass)
    for c in range(len(topology.grounded)):
        rows[c] = 0.0
    for i in range(n):
        rows[topology.labels[i]] += normal[n + i]
    for i in range(n):
        c = topology.labels[i]
        if topology.driver[c] >= 0:
            normal[n + i] = rows[c] if i == topology.driver[c] else 0.0
        else:
            normal[n + i] = 0.0 if topology.grounded[c] else \
                rows[c] * s.mass[i] / topology.masses[c]


#: Two guards are one surface when their gradients (with ∂/∂t) are parallel to this
#: relative tolerance.
SAME_SURFACE = 1e-9


@njit_step
def same_surface(first, first_rate, second, second_rate):
    """Whether (second, second_rate) = c (first, first_rate) for some c ≠ 0, to
    ``SAME_SURFACE``: two guards that vanish together on one surface of (y, t)."""
    dot = first_rate * second_rate
    first_size = first_rate * first_rate
    second_size = second_rate * second_rate
    for r in range(len(first)):
        dot += first[r] * second[r]
        first_size += first[r] * first[r]
        second_size += second[r] * second[r]
    if first_size == 0.0 or second_size == 0.0:
        return False
    return dot * dot >= (1.0 - SAME_SURFACE) * first_size * second_size


@njit_step
def blade_contact_normal(e, s, g):
    """∂g/∂y of interface e's contact guard (±δ, δ = (u − Δ) sin α) into g.guard_normal."""
    for r in range(len(g.guard_normal)):
        g.guard_normal[r] = 0.0
    if s.left[e] >= 0:
        g.guard_normal[s.left[e]] += s.sin_angle[e]
    if s.right[e] >= 0:
        g.guard_normal[s.right[e]] -= s.sin_angle[e]


@njit_step
def blade_slip_normal(e, s, g):
    """∂g/∂y of interface e's slip guard (± u̇ cos α) into g.guard_normal."""
    n = len(s.mass)
    for r in range(len(g.guard_normal)):
        g.guard_normal[r] = 0.0
    if s.left[e] >= 0:
        g.guard_normal[n + s.left[e]] += s.cos_angle[e]
    if s.right[e] >= 0:
        g.guard_normal[n + s.right[e]] -= s.cos_angle[e]


@njit_inlined
def _static_friction_change(k, sign, s, topology, g):
    """−sgn(f) δf_e of stuck interface e = stuck_interfaces[k], from δR and δẍ in g and the
    normal-force changes already subtracted in g.imbalance (``static_friction``)."""
    change = 0.0
    for i in range(len(s.mass)):
        change += topology.operator[k, i] * g.imbalance[i]
    return -sign * change


@njit_step
def blade_breakaway_normal(e, sign, t, s, modes, topology, g):
    """∂g/∂y into g.guard_normal, and ∂g/∂t returned, of the breakaway guard
    g = μ_s N_e − |f_e| of stuck interface e, whose static friction f_e has the sign
    ``sign``, from the slopes in g (linearised at the switch, in the modes before it).

    f = P b (``dynamics.static_friction``) with b_i = R_i − m_i ẍ_i − Σ_e' B_e'i N_e' sin α_e'
    over the stuck interfaces, so δf = P δb, differentiated along each unit direction.
    """
    n = len(s.mass)
    k = stuck_position(topology, e)
    for r in range(2 * n):
        unit_direction(g.direction, r)
        linearised_acceleration(g.direction, s, modes, topology, g)
        for i in range(n):
            g.imbalance[i] = g.resultant_change[i] - s.mass[i] * g.acceleration_change[i]
        normal_change = 0.0
        for stuck in topology.stuck_interfaces:
            left, right = s.left[stuck], s.right[stuck]
            du = (g.direction[left] if left >= 0 else 0.0) \
                - (g.direction[right] if right >= 0 else 0.0)
            ddu = (g.direction[n + left] if left >= 0 else 0.0) \
                - (g.direction[n + right] if right >= 0 else 0.0)
            change = g.normal_u[stuck] * du + g.normal_du[stuck] * ddu
            if stuck == e:
                normal_change = change
            if left >= 0:
                g.imbalance[left] -= change * s.sin_angle[stuck]
            if right >= 0:
                g.imbalance[right] += change * s.sin_angle[stuck]
        g.guard_normal[r] = s.static_mu[e] * normal_change \
            + _static_friction_change(k, sign, s, topology, g)
    excitation_rate(t, s.amplitudes, s.cos_phase, s.sin_phase, s.excitation_frequency,
                    g.q_rate)
    cluster_accelerations(g.q_rate, topology.labels, topology.grounded, topology.masses,
                          g.rows, g.acceleration_change)
    n_blades = n - len(s.motion_amplitude)
    for i in range(n):
        driver = topology.driver[topology.labels[i]]
        if driver >= 0:  # a driven cluster: ∂ẍ/∂t is its prescribed motion's jerk
            g.acceleration_change[i] = prescribed_acceleration(t, s, driver - n_blades)[1]
        g.imbalance[i] = g.q_rate[i] - s.mass[i] * g.acceleration_change[i]
    return _static_friction_change(k, sign, s, topology, g)


@njit_step
def apply_saltation(t, e, time_rate, several, s, topology, g):
    """Φ ← S Φ with S = P + (f⁺ − P f⁻) nᵀ / (nᵀ f⁻ + ∂g/∂t), from g.f_minus, g.f_plus and
    g.guard_normal (n) and ``time_rate`` (∂g/∂t); P projects onto the clusters of
    ``topology``, those after the switch at t on interface e.

    A grazing switch (``GRAZING_GAIN``) or ``several`` guards crossing at once is counted
    in g.singular (the first one's time and interface kept) and S is applied as it stands
    (without its jump term where ġ is exactly 0).
    """
    n = len(s.mass)
    normal, jump = g.guard_normal, g.direction
    rate = time_rate
    for r in range(2 * n):
        rate += normal[r] * g.f_minus[r]
        jump[r] = g.f_minus[r]
    project_velocities(s, topology, jump, n, g.rows)
    size = 0.0
    for r in range(2 * n):
        jump[r] = g.f_plus[r] - jump[r]
        if r >= n:
            size = max(size, abs(jump[r]))
    along_scale = 1.0 / rate if rate != 0.0 else 0.0  # no jump term where ġ is exactly 0
    if several or grazing(size, normal, s, rate):
        count_singular(t, e, g)
    matrix = g.matrix
    for column in range(matrix.shape[1]):
        along = 0.0
        for r in range(2 * n):
            along += normal[r] * matrix[r, column]
            g.f_minus[r] = matrix[r, column]  # f⁻ is no longer needed: column scratch
        project_velocities(s, topology, g.f_minus, n, g.rows)
        for r in range(2 * n):
            matrix[r, column] = g.f_minus[r] + jump[r] * along * along_scale


#: Relative size of n_jᵀ Δf_k against n_jᵀ f⁻ below which the saltations of two
#: interfaces that switch at the same instant commute (``apply_saltations``).
COMMUTING = 1e-9

#: The stretch (as ``GRAZING_GAIN`` measures it) below which a jump of the vector field
#: outside every switching interface's support is the switch's location error, not a
#: force that changed there (``apply_saltations``). Where the vector field is continuous
#: across a switch (stick onset on one-mass nodes, breakaway with μ(0⁺) = μ_s, a contact
#: law with N(0) = 0), f⁺ − P f⁻ is that error alone, of the order of the event tolerance
#: times the slope of the forces.
LOCATION_STRETCH = 1e-6


@njit_inlined
def _claim(e, k, s, topology, owner):
    """Give the nodes of the clusters of interface e's two ends to switch k; returns how
    many were not its own before, or −1 where one belonged to another switch."""
    added = 0
    for i in range(len(owner)):
        label = topology.labels[i]
        if (s.left[e] >= 0 and topology.labels[s.left[e]] == label) or (
                s.right[e] >= 0 and topology.labels[s.right[e]] == label):
            if owner[i] >= 0 and owner[i] != k:
                return -1
            if owner[i] != k:
                owner[i] = k
                added += 1
    return added


@njit_inlined
def _end_owner(e, s, topology, owner):
    """The switch that owns a node of the clusters of interface e's ends: −1 for none,
    −2 for nodes of two different switches."""
    found = -1
    for i in range(len(owner)):
        label = topology.labels[i]
        if owner[i] >= 0 and ((s.left[e] >= 0 and topology.labels[s.left[e]] == label) or (
                s.right[e] >= 0 and topology.labels[s.right[e]] == label)):
            if found >= 0 and owner[i] != found:
                return -2
            found = owner[i]
    return found


@njit_step_exact
def commuting_saltations(t, count, modes, s, topology, g, sw):
    """Φ ← S Φ for switches of several interfaces at one instant, where that is well
    defined; returns whether it was (else nothing is changed).

    Interface k's switch changes the vector field on its support only: the nodes of the
    clusters (those after the switch) of its two ends, and of the ends of every interface
    whose mode changed with it (``modes`` against sw.modes_before) and that reaches its
    support: a stuck interface released, or a candidate held, because of it. Where the
    supports are disjoint, the jump f⁺ − P f⁻ outside them is below ``LOCATION_STRETCH``,
    and no guard sees another's jump (|n_jᵀ Δf_k| ≤ ``COMMUTING`` |n_jᵀ f⁻ + ∂g_j/∂t| for
    j ≠ k), the saltation matrices S_k = P + Δf_k n_kᵀ / ġ_k commute: in whichever order a
    perturbation makes the interfaces switch, S Φ = P Φ + Σ_k Δf_k (n_kᵀ Φ) / ġ_k. Such
    are interfaces far apart on a ring, which its symmetry makes switch together. The
    first ``count`` rows of sw.crossing_normals and entries of sw.crossing_rates are n_k
    and ġ_k of sw.crossings[k] (``records.Switching``); g.f_minus and g.f_plus hold f⁻
    and f⁺. A grazing one (``GRAZING_GAIN``) is counted in g.singular, as
    ``apply_saltation`` counts it.
    """
    n = len(s.mass)
    crossings, normals, rates = sw.crossings, sw.crossing_normals, sw.crossing_rates
    jump = g.direction
    for r in range(2 * n):
        jump[r] = g.f_minus[r]
    project_velocities(s, topology, jump, n, g.rows)
    for r in range(2 * n):
        jump[r] = g.f_plus[r] - jump[r]
    owner = sw.owner
    for i in range(n):
        owner[i] = -1
    for k in range(count):
        if _claim(crossings[k], k, s, topology, owner) < 0:
            return False
    grown = True
    while grown:  # the interfaces that changed mode with a switch join its support
        grown = False
        for e in range(len(modes)):
            if modes[e] == sw.modes_before[e]:
                continue
            k = _end_owner(e, s, topology, owner)
            if k == -2:
                return False
            if k >= 0 and _claim(e, k, s, topology, owner) > 0:
                grown = True
    for e in range(len(modes)):  # a mode change that no switch reaches: not split
        if modes[e] != sw.modes_before[e] and _end_owner(e, s, topology, owner) < 0:
            return False
    scale = time_scale(s)
    for i in range(n):
        if owner[i] >= 0:
            continue
        size = max(abs(jump[i]) / scale, abs(jump[n + i]))
        for k in range(count):
            if size > 0.0 and correction_stretch(size, normals[k], s) \
                    > LOCATION_STRETCH * abs(rates[k]):
                return False
    for j in range(count):
        for k in range(count):
            if j == k:
                continue
            cross = 0.0
            for i in range(n):
                if owner[i] == k:
                    cross += normals[j, i] * jump[i] + normals[j, n + i] * jump[n + i]
            if abs(cross) > COMMUTING * abs(rates[j]):
                return False
    for k in range(count):
        size = 0.0
        for i in range(n):
            if owner[i] == k:
                size = max(size, abs(jump[n + i]))
        if grazing(size, normals[k], s, rates[k]):
            count_singular(t, crossings[k], g)
    along = sw.along
    matrix = g.matrix
    for column in range(matrix.shape[1]):
        for k in range(count):
            value = 0.0
            for r in range(2 * n):
                value += normals[k, r] * matrix[r, column]
            along[k] = value / rates[k] if rates[k] != 0.0 else 0.0
        for r in range(2 * n):
            g.f_minus[r] = matrix[r, column]  # f⁻ is no longer needed: column scratch
        project_velocities(s, topology, g.f_minus, n, g.rows)
        for r in range(2 * n):
            k = owner[r % n]
            matrix[r, column] = g.f_minus[r] + (jump[r] * along[k] if k >= 0 else 0.0)
    return True


@njit_step
def project_tangent(s, topology, g):
    """Φ ← P Φ: the tangent of a start whose velocities are projected onto the clusters."""
    matrix = g.matrix
    for column in range(matrix.shape[1]):
        for r in range(matrix.shape[0]):
            g.direction[r] = matrix[r, column]
        project_velocities(s, topology, g.direction, len(s.mass), g.rows)
        for r in range(matrix.shape[0]):
            matrix[r, column] = g.direction[r]


# Each joined with its substructures' version (``structures``, ``constraints``):
#: n ← Pᵀ n, a guard's gradient on the tangents of the stuck interfaces' motion.
reduce_to_clusters = by_scene("reduce_to_clusters", reduce_on_clusters, reduce_to_constraints)
#: The gradients of the contact, slip and breakaway guards.
contact_normal = by_scene("contact_normal", blade_contact_normal, structure_contact_normal)
slip_normal = by_scene("slip_normal", blade_slip_normal, structure_slip_normal)
breakaway_normal = by_scene("breakaway_normal", blade_breakaway_normal,
                            structure_breakaway_normal)
#: Several switches at one instant, where their saltations commute.
apply_saltations = by_scene("apply_saltations", commuting_saltations, structure_saltations)
