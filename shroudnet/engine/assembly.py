"""The dynamics of a scene in one state and set of modes, assembled in plain Python.

``assemble`` evaluates, for a ``Scene``, what the compiled loop evaluates at every stage
of a step (``dynamics``, ``regroup``, ``detect``), calling the scene's law objects
themselves: it is how users and tests look at forces, accelerations and guards.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from contact_laws import check_array, check_instance, check_real
from contact_laws.base import ZERO_PLUS_SPEED

from ..checked_records import check_record
from ..model.scene import Scene, SceneArrays
from .clusters import TWO_DRIVERS, cluster_labels
from .codes import OPEN, SLIP_POSITIVE, STICK, Mode
from .detect import event_guards
from .dynamics import (
    cluster_accelerations,
    continued_mu,
    coupling_forces,
    driven_accelerations,
    excitation_forces,
    interface_kinematics,
    resultant_forces,
    static_friction,
)
from .regroup import cluster_mass, static_friction_operator


def law_forces(arrays: SceneArrays, penetration, rate, slip_velocity, modes):
    """Normal force N_e and sliding friction f_e [N] from each interface's laws.

    Open interfaces carry nothing; stuck ones carry N and no sliding friction (their static
    friction comes from ``static_friction``). Exact laws slip with f = σ μ(σv) N, σ = ±1 by
    the sign of the mode (paper eqs. 5–6), with μ(0⁺) at v = 0, continued past the mode's
    end (σv < 0) by μ(|v|) + 2 μ'(|v|) σv, as the compiled loop does
    (``sliding_coefficient``);
    regularised ones with f = μ(|v|) N tanh(v/v_ε).
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
        if arrays.regularisation[e] > 0.0:
            friction[e] = friction_law(slip_velocity[e]) * normal[e] \
                * math.tanh(slip_velocity[e] / arrays.regularisation[e])
            continue
        sign = 1.0 if modes[e] == SLIP_POSITIVE else -1.0
        speed = sign * slip_velocity[e] if slip_velocity[e] != 0.0 else ZERO_PLUS_SPEED
        mu = continued_mu(friction_law(speed), friction_law.slope(speed), speed)
        friction[e] = sign * mu * normal[e]
    return normal, friction


@dataclass(frozen=True)
class Assembly:
    """The forces and accelerations of a scene in a given state and set of modes.

    Each field is checked (``check_record``): an array, finite except the guards, which are
    +inf where no event can come (``event_guards``).
    """

    acceleration: np.ndarray     # ẍ_i [m/s²], by blade position
    normal_force: np.ndarray     # N_e [N], by interface
    friction_force: np.ndarray   # f_e [N]: sliding, or static on stuck interfaces
    interface_force: np.ndarray  # F_e = N_e sin α_e + f_e cos α_e [N], −F_e on i, +F_e on j
    cluster: np.ndarray          # stick-cluster label of each blade
    grounded: np.ndarray         # per cluster: joined to a fixed or prescribed-motion node
    contact_guard: np.ndarray    # see event_guards
    motion_guard: np.ndarray     # see event_guards

    NON_FINITE = ("contact_guard", "motion_guard")

    def __post_init__(self):
        check_record(self)


def assemble(scene: Scene, t: float, x, v, modes) -> Assembly:
    """Assemble the dynamics of ``scene`` at time ``t`` [s] in state (x [m], ẋ [m/s]).

    ``modes`` gives each interface's ``Mode``. A stuck interface must have zero slip
    velocity (its nodes move together; a prescribed-motion node moves as its motion says
    at t); the result's ``motion_guard`` tells whether each static friction force is
    admissible (|f| ≤ μ_s N). Every argument is checked first, by name.
    """
    check_instance("assemble", "scene", scene, Scene, expected="a shroudnet.Scene")
    t = check_real("assemble", "t", t, unit="s")
    a = scene.arrays
    x = check_array("assemble", "x", x, shape=(a.n_blades,), unit="m")
    v = check_array("assemble", "v", v, shape=(a.n_blades,), unit="m/s")
    modes = _modes(modes, a.n_interfaces)
    stuck = modes == STICK
    if np.any(stuck & ~a.can_stick):
        raise ValueError("assemble.modes: STICK on an interface that cannot stick (no exact "
                         f"friction law, or α = π/2): {np.flatnonzero(stuck & ~a.can_stick)}")
    n, m, p = a.n_blades, a.n_interfaces, a.n_prescribed
    x_p, v_p = a.prescribed_state(t)
    x, v = np.concatenate([x, x_p]), np.concatenate([v, v_p])
    drive = np.array([motion.acceleration_at(t) for motion in a.motions], dtype=float)
    none = np.zeros(p)
    mass = np.concatenate([a.mass, none])
    penetration, rate, slip_velocity = np.empty(m), np.empty(m), np.empty(m)
    interface_kinematics(x, v, a.left, a.right, a.gap, a.sin_angle, a.cos_angle,
                         penetration, rate, slip_velocity)
    normal, friction = law_forces(a, penetration, rate, slip_velocity, modes)
    interface_force = normal * a.sin_angle + friction * a.cos_angle
    q = np.zeros(n + p)
    excitation_forces(t, a.harmonic_amplitudes, np.cos(a.harmonic_phases),
                      np.sin(a.harmonic_phases), a.excitation_frequency, q[:n])
    labels, grounded, driver = cluster_labels(n + p, n, a.left, a.right, stuck)
    if np.any(driver == TWO_DRIVERS):
        raise ValueError("assemble.modes: the stuck interfaces tie two prescribed motions "
                         "together, or a prescribed motion to a fixed node")
    resultant = np.empty(n + p)
    resultant_forces(x, v, q, np.concatenate([a.damping, none]),
                     np.concatenate([a.stiffness, none]), a.left, a.right, interface_force,
                     stuck, resultant)
    coupling_forces(x, v, a.coupling_left, a.coupling_right, a.coupling_stiffness,
                    a.coupling_damping, resultant)
    acceleration = np.empty(n + p)
    masses = cluster_mass(mass, labels, len(grounded))
    cluster_force = np.empty(n + p)
    cluster_accelerations(resultant, labels, grounded, masses, cluster_force, acceleration)
    driven_accelerations(labels, driver, masses, cluster_force, v, drive, n, acceleration)
    operator, stuck_interfaces = static_friction_operator(n + p, n, a.left, a.right,
                                                          a.cos_angle, stuck, labels, grounded)
    static_friction(operator, stuck_interfaces, mass, resultant, acceleration, normal,
                    a.sin_angle, a.left, a.right, np.empty(n + p), friction)
    interface_force = normal * a.sin_angle + friction * a.cos_angle
    contact, motion = np.empty(m), np.empty(m)
    event_guards(modes, penetration, slip_velocity, normal, friction, a.static_mu, a.opens,
                 a.can_stick, contact, motion)
    return Assembly(acceleration[:n], normal, friction, interface_force, labels[:n], grounded,
                    contact, motion)


def _modes(modes, n_interfaces: int) -> np.ndarray:
    """``modes`` as int64 codes, one ``Mode`` per interface, or raise naming
    ``assemble.modes``."""
    codes = check_array("assemble", "modes", modes, shape=(n_interfaces,))
    if not np.isin(codes, [int(mode) for mode in Mode]).all():
        names = ", ".join(f"{mode.name} = {int(mode)}" for mode in Mode)
        raise ValueError(f"assemble.modes must hold {n_interfaces} values of shroudnet.Mode "
                         f"({names}), got {modes!r:.80}")
    return codes.astype(np.int64)
