"""Substructures: the interfaces' kinematics, forces, tangent and guard gradients of a
scene whose nodes have many degrees of freedom (``records.StructureScene``).

Interface e sees its points' relative motion through two rows of the coordinates: the
penetration δ_e = n_e·x − Δ_e and the slip velocity v_e = t_e·ẋ; it pushes the
coordinates by −(N_e n_e + f_e t_e) (DESIGN §7). The structure's own forces are
−K x − C ẋ with the full K and C (couplings included), and the excitation Q(t) comes
by coordinate as for blades. Stick is the constraint t_e·ẋ = 0 (``constraints``).
These are the versions of the blades' functions that ``dispatch.by_scene`` picks for a
``StructureScene``; none of them depends on the laws.
"""

from .codes import OPEN, STICK
from .compiled import njit_inlined, njit_step
from .dispatch import by_scene
from .dynamics import blade_kinematics, excitation_rate, prescribed_acceleration
from .slider_tangent import slider_force_change, slider_rate_change
from .support import row_dot


@njit_inlined
def structure_kinematics(x, v, s, penetration, rate, slip_velocity):
    """δ_e = n_e·x − Δ_e [m], δ̇_e = n_e·ẋ and the slip velocity t_e·ẋ [m/s] of every
    interface, into the last three arrays."""
    for e in range(len(penetration)):
        penetration[e] = row_dot(s, s.normal_rows, e, x, 0) - s.normal_gap[e]
        rate[e] = row_dot(s, s.normal_rows, e, v, 0)
        slip_velocity[e] = row_dot(s, s.tangent_rows, e, v, 0)


#: (δ, δ̇, slip velocity) of every interface of a scene of blades or of substructures.
kinematics = by_scene("kinematics", blade_kinematics, structure_kinematics)


@njit_inlined
def structure_contact_guard(e, x, v, modes, s):
    """Interface e's contact guard g (−δ while open, δ while closed) [m] and ġ [m/s]."""
    side = -1.0 if modes[e] == OPEN else 1.0
    return (side * (row_dot(s, s.normal_rows, e, x, 0) - s.normal_gap[e]),
            side * row_dot(s, s.normal_rows, e, v, 0))


@njit_inlined
def structure_slip_acceleration(s, e, acceleration):
    """t_e·ẍ: the rate of change of interface e's slip velocity."""
    return row_dot(s, s.tangent_rows, e, acceleration, 0)


@njit_inlined
def structure_resultant(x, v, s, w):
    """R = Q − K x − C ẋ − Σ_e (N_e n_e + f_e t_e) [N] into w.resultant, from the
    excitation in w.q and the laws' forces in w.normal and w.friction (no friction on a
    stuck interface yet: its static friction is the multiplier); returns the power the
    damping dissipates, ẋᵀ C ẋ [W]."""
    n = len(x)
    damping = 0.0
    for i in range(n):
        value = w.q[i]
        for k in range(s.matrix_start[i], s.matrix_start[i + 1]):
            j = s.matrix_column[k]
            value -= s.stiffness_entry[k] * x[j]
            force = s.damping_entry[k] * v[j]
            value -= force
            damping += v[i] * force
        w.resultant[i] = value
    for e in range(len(w.normal)):
        normal, friction = w.normal[e], w.friction[e]
        if normal == 0.0 and friction == 0.0:
            continue
        for k in range(s.support_start[e], s.support_start[e + 1]):
            i = s.support_index[k]
            w.resultant[i] -= normal * s.normal_rows[e, i] + friction * s.tangent_rows[e, i]
    return damping


@njit_inlined
def structure_linearised_acceleration(direction, s, modes, topology, g):
    """δR (into g.resultant_change) and δẍ (into g.acceleration_change) along the state
    change ``direction`` (δx then δẋ), from the slopes in g (``kernel.tangent.linearise``
    for substructures: g.normal_u = ∂N/∂δ, g.normal_du = ∂N/∂δ̇, g.force_u = ∂f/∂N and
    g.force_du = ∂f/∂v, 0 where stuck):

        δR = −K δx − C δẋ − Σ_e [n_e δN_e + t_e (∂f/∂N δN_e + ∂f/∂v t_e·δẋ)],
        δN_e = ∂N/∂δ n_e·δx + ∂N/∂δ̇ n_e·δẋ,

    and δẍ_f = (δR_f − G_fᵀ δλ)/m with δλ = W_f δR_f (the prescribed motions do not
    depend on the state: δẍ_p = 0). An elastic contact's friction is its spring's,
    δf = k_t δu, and its stretch's rate δu̇ lands in the direction's velocity slot
    (``slider_tangent``)."""
    n = len(s.mass)
    free = n - len(s.motion_amplitude)
    change = g.resultant_change
    for i in range(n):
        value = 0.0
        for k in range(s.matrix_start[i], s.matrix_start[i + 1]):
            j = s.matrix_column[k]
            value -= s.stiffness_entry[k] * direction[j] + s.damping_entry[k] * direction[n + j]
        change[i] = value
    for e in range(len(modes)):
        if modes[e] == OPEN:
            continue
        normal = g.normal_u[e] * row_dot(s, s.normal_rows, e, direction, 0) \
            + g.normal_du[e] * row_dot(s, s.normal_rows, e, direction, n)
        friction = 0.0
        if modes[e] != STICK:
            friction = g.force_u[e] * normal \
                + g.force_du[e] * row_dot(s, s.tangent_rows, e, direction, n)
        for k in range(s.support_start[e], s.support_start[e + 1]):
            i = s.support_index[k]
            change[i] -= normal * s.normal_rows[e, i] + friction * s.tangent_rows[e, i]
    slider_force_change(direction, s, modes, change)
    acceleration = g.acceleration_change
    for i in range(free):
        acceleration[i] = change[i]
    for i in range(free, n):
        acceleration[i] = 0.0
    for k in range(len(topology.stuck_interfaces)):
        value = 0.0
        for i in range(free):
            value += topology.operator[k, i] * change[i]
        e = topology.stuck_interfaces[k]
        for i in range(free):
            acceleration[i] -= s.tangent_rows[e, i] * value
    for i in range(free):
        acceleration[i] /= s.mass[i]
    slider_rate_change(direction, s, modes, g)


@njit_inlined
def _row_as_gradient(rows, e, first, g):
    """g.guard_normal ← row e of ``rows`` on the state's displacements (``first`` 0) or
    velocities (``first`` n), 0 elsewhere."""
    for r in range(len(g.guard_normal)):
        g.guard_normal[r] = 0.0
    for i in range(rows.shape[1]):
        g.guard_normal[first + i] = rows[e, i]


@njit_step
def structure_contact_normal(e, s, g):
    """∂g/∂y of interface e's contact guard (±δ, δ = n_e·x − Δ_e) into g.guard_normal."""
    _row_as_gradient(s.normal_rows, e, 0, g)


@njit_step
def structure_slip_normal(e, s, g):
    """∂g/∂y of interface e's slip guard (± t_e·ẋ) into g.guard_normal."""
    _row_as_gradient(s.tangent_rows, e, len(s.mass), g)


@njit_inlined
def stuck_position(topology, e):
    """The position of stuck interface e among ``topology.stuck_interfaces``."""
    k = 0
    for index in range(len(topology.stuck_interfaces)):
        if topology.stuck_interfaces[index] == e:
            k = index
    return k


@njit_inlined
def unit_direction(direction, r):
    """``direction`` ← the r-th unit vector."""
    for q in range(len(direction)):
        direction[q] = 0.0
    direction[r] = 1.0


@njit_step
def structure_breakaway_normal(e, sign, t, s, modes, topology, g):
    """∂g/∂y into g.guard_normal, and ∂g/∂t returned, of the breakaway guard
    g = μ_s N_e − |λ_e| of stuck interface e, whose static friction λ_e has the sign
    ``sign``, from the slopes in g: λ = W z (``constraints``), so δλ_e = W_e,f δR_f along
    each unit direction (``structure_linearised_acceleration``), and ∂λ_e/∂t =
    W_e,f Q̇_f + W_e,p ȧ_p."""
    n = len(s.mass)
    free = n - len(s.motion_amplitude)
    k = stuck_position(topology, e)
    for r in range(2 * n):
        unit_direction(g.direction, r)
        structure_linearised_acceleration(g.direction, s, modes, topology, g)
        change = 0.0
        for i in range(free):
            change += topology.operator[k, i] * g.resultant_change[i]
        normal_change = g.normal_u[e] * s.normal_rows[e, r] if r < n \
            else g.normal_du[e] * s.normal_rows[e, r - n]
        g.guard_normal[r] = s.static_mu[e] * normal_change - sign * change
    excitation_rate(t, s.amplitudes, s.cos_phase, s.sin_phase, s.excitation_frequency,
                    g.q_rate)
    rate = 0.0
    for i in range(free):
        rate += topology.operator[k, i] * g.q_rate[i]
    for p in range(n - free):
        rate += topology.operator[k, free + p] * prescribed_acceleration(t, s, p)[1]
    return -sign * rate


@njit_step
def structure_saltations(t, count, modes, s, topology, g, sw):
    """``apply_saltations`` for substructures: switches of several interfaces at one
    instant are not split by support (a substructure's coordinates are shared by all its
    interfaces), so none is applied here and the caller counts the switch as singular."""
    return False
