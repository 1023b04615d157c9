"""The plain way: an event-driven run with scipy's ``solve_ivp`` and a Python right-hand side.

This is what one writes without shroudnet, and what the benchmark compares against: per set
of interface modes a numpy right-hand side of the same model (DESIGN §2, paper eqs. 1–7),
``solve_ivp`` event functions for every guard (contact closing or opening, slip velocity
reaching zero, breakaway), and a restart at each switch. It shares no code with the compiled
loop beyond the scene's arrays and its laws' ``__call__``, so it also serves the tests as an
independent check of that loop. Stuck interfaces join their blades into clusters with one
acceleration; the static friction is the minimum-norm solution of each blade's equilibrium,
as in ``shroudnet.dynamics``. After a switch the release rule is the simple one: a stuck
interface whose friction exceeds μ_s N slips the way its friction pushed. A prescribed-
motion node is evaluated from its motion at each time (the loop carries it as a state), and
a cluster that holds one moves with it.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from scipy.integrate import solve_ivp
from scipy.sparse import coo_matrix
from scipy.sparse.csgraph import connected_components

from ..engine.codes import Mode
from ..model.scene import Scene, edge_matrix

OPEN, STICK, SLIP_POSITIVE, SLIP_NEGATIVE = (int(m) for m in Mode)


@dataclass(frozen=True)
class BaselineRun:
    """Displacements and velocities at t = k T_e (k = 0 … periods), and the switches made."""

    x: np.ndarray   # (periods + 1, n_blades) [m]
    v: np.ndarray   # (periods + 1, n_blades) [m/s]
    switches: int


class _Model:
    """The scene's equations in plain numpy, for one set of modes at a time.

    A prescribed-motion node is no unknown here: its displacement, velocity and
    acceleration are its motion's, evaluated at the time asked for."""

    def __init__(self, scene: Scene):
        a = scene.arrays
        self.a = a
        n, m, p = a.n_blades, a.n_interfaces, a.n_prescribed
        self.incidence = np.zeros((m, n + p))  # B: +1 at the left node, −1 at the right one
        for e in range(m):
            if a.left[e] >= 0:
                self.incidence[e, a.left[e]] = 1.0
            if a.right[e] >= 0:
                self.incidence[e, a.right[e]] = -1.0
        self.harmonics = np.arange(1, len(a.amplitudes))
        none = np.zeros(p)
        # blades' springs and couplings, by blade row and node column
        self.stiffness = edge_matrix(np.concatenate([a.stiffness, none]), a.coupling_left,
                                     a.coupling_right, a.coupling_stiffness)[:n]
        self.damping = edge_matrix(np.concatenate([a.damping, none]), a.coupling_left,
                                   a.coupling_right, a.coupling_damping)[:n]
        self.set_modes(np.zeros(m, dtype=np.int64))

    def motion(self, t):
        """(x_p, ẋ_p, ẍ_p) of the prescribed-motion nodes at time t."""
        motions = self.a.motions
        return (np.array([m.displacement_at(t) for m in motions], dtype=float),
                np.array([m.velocity_at(t) for m in motions], dtype=float),
                np.array([m.acceleration_at(t) for m in motions], dtype=float))

    def set_modes(self, modes):
        """Clusters, their masses and the static-friction pseudo-inverse for ``modes``."""
        a = self.a
        n, nodes = a.n_blades, a.n_blades + a.n_prescribed
        self.modes = modes.copy()
        self.stuck = np.flatnonzero(modes == STICK)
        # Cluster labels over the nodes plus one ground node (index nodes) for fixed ones.
        ends = [(a.left[e] if a.left[e] >= 0 else nodes,
                 a.right[e] if a.right[e] >= 0 else nodes) for e in self.stuck]
        rows = [i for i, _ in ends]
        cols = [j for _, j in ends]
        graph = coo_matrix((np.ones(len(rows)), (rows, cols)), shape=(nodes + 1, nodes + 1))
        _, labels = connected_components(graph, directed=False)
        self.labels = labels[:n]
        grounded = labels[:n] == labels[nodes]
        # each blade's prescribed node, where its cluster holds one (−1 where none)
        self.driven_by = np.full(n, -1)
        for node in range(n, nodes):
            self.driven_by[labels[:n] == labels[node]] = node - n
        self.sums = (self.labels[None, :] == np.unique(self.labels)[:, None]).astype(float)
        self.sums[:, grounded | (self.driven_by >= 0)] = 0.0  # given motion: no momentum
        masses = self.sums @ a.mass
        self.share = np.divide(self.sums, masses[:, None], out=np.zeros_like(self.sums),
                               where=masses[:, None] > 0)
        balance = (self.incidence[self.stuck][:, :n] * a.cos_angle[self.stuck, None]).T
        self.pinv = np.linalg.pinv(balance) if len(self.stuck) else np.zeros((0, n))

    def kinematics(self, t, x, v):
        x_p, v_p, _ = self.motion(t)
        u = self.incidence @ np.concatenate([x, x_p])
        du = self.incidence @ np.concatenate([v, v_p])
        a = self.a
        return (u - a.gap) * a.sin_angle, du * a.sin_angle, du * a.cos_angle

    def forces(self, t, x, v):
        """(ẍ, N, f): accelerations, normal forces, friction (sliding or static)."""
        a = self.a
        n = a.n_blades
        penetration, rate, slip = self.kinematics(t, x, v)
        closed = self.modes != OPEN
        normal = np.zeros(a.n_interfaces)
        friction = np.zeros(a.n_interfaces)
        for e in np.flatnonzero(closed):
            normal[e] = a.normal_laws[e](penetration[e], rate[e])
            law = a.friction_laws[e]
            if law is None or self.modes[e] == STICK:
                continue
            sliding = law(slip[e]) * normal[e]
            if a.regularisation[e] > 0.0:
                friction[e] = sliding * np.tanh(slip[e] / a.regularisation[e])
            else:
                friction[e] = sliding if self.modes[e] == SLIP_POSITIVE else -sliding
        load = normal * a.sin_angle + friction * a.cos_angle
        load[self.stuck] = 0.0
        # Q_i = s_i [q0 + Σ_n q_n sin(n (lΩ t + φ_i))]: harmonic n carries n φ_i.
        angle = self.harmonics[:, None] * (a.excitation_frequency * t + a.phases[None, :])
        q = a.excitation_scale * (a.amplitudes[0] + a.amplitudes[1:] @ np.sin(angle))
        x_p, v_p, a_p = self.motion(t)
        resultant = (q - self.damping @ np.concatenate([v, v_p])
                     - self.stiffness @ np.concatenate([x, x_p])
                     - self.incidence[:, :n].T @ load)
        acceleration = self.share.T @ (self.sums @ resultant)
        driven = self.driven_by >= 0
        acceleration[driven] = a_p[self.driven_by[driven]]
        if len(self.stuck):
            imbalance = (resultant - a.mass * acceleration
                         - self.incidence[self.stuck][:, :n].T
                         @ (normal * a.sin_angle)[self.stuck])
            friction[self.stuck] = self.pinv @ imbalance
        return acceleration, normal, friction

    def rhs(self, t, y):
        n = self.a.n_blades
        return np.concatenate([y[n:], self.forces(t, y[:n], y[n:])[0]])

    def project(self, t, v):
        """Velocities of the current clusters: each one's momentum over its mass (0 if
        grounded, the prescribed node's if it holds one)."""
        projected = self.share.T @ (self.sums @ (self.a.mass * v))
        driven = self.driven_by >= 0
        projected[driven] = self.motion(t)[1][self.driven_by[driven]]
        return projected

    def events(self):
        """(interface, is a contact guard, solve_ivp event function) for every guard that
        can cross under the current modes."""
        a = self.a
        n = a.n_blades
        found = []
        for e in range(a.n_interfaces):
            mode = self.modes[e]
            if a.opens[e]:
                sign = -1.0 if mode == OPEN else 1.0
                found.append((e, True, _event(lambda t, y, e=e, s=sign:
                                              s * self.kinematics(t, y[:n], y[n:])[0][e])))
            if mode == STICK:
                def margin(t, y, e=e):
                    _, normal, friction = self.forces(t, y[:n], y[n:])
                    return a.static_mu[e] * normal[e] - abs(friction[e])
                found.append((e, False, _event(margin)))
            elif a.can_stick[e] and mode != OPEN:
                sign = 1.0 if mode == SLIP_POSITIVE else -1.0
                found.append((e, False, _event(lambda t, y, e=e, s=sign:
                                               s * self.kinematics(t, y[:n], y[n:])[2][e])))
        return found


def _event(function):
    function.terminal = True
    function.direction = -1.0
    return function


def _switch(model: _Model, t, x, v, interface, guard_is_contact):
    """New modes after ``interface``'s guard crossed; returns the projected velocities."""
    a = model.a
    modes = model.modes.copy()
    _, _, slip = model.kinematics(t, x, v)
    if guard_is_contact:
        slipping = SLIP_POSITIVE if slip[interface] >= 0.0 else SLIP_NEGATIVE
        modes[interface] = slipping if modes[interface] == OPEN else OPEN
    elif modes[interface] != STICK:
        modes[interface] = STICK  # slip velocity reached zero: try to stick
    else:  # breakaway: slip the way the friction pushed (the event lies at |f| = μ_s N)
        _, _, friction = model.forces(t, x, v)
        modes[interface] = SLIP_POSITIVE if friction[interface] > 0.0 else SLIP_NEGATIVE
    for _ in range(2 * a.n_interfaces + 1):  # release the worst stuck interface until all hold
        model.set_modes(modes)
        trial = model.project(t, v)
        _, normal, friction = model.forces(t, x, trial)
        ratio = np.zeros(a.n_interfaces)
        held = model.stuck
        ratio[held] = np.abs(friction[held]) / np.maximum(a.static_mu[held] * normal[held],
                                                          1e-300)
        worst = int(np.argmax(ratio))
        if ratio[worst] <= 1.0:
            return trial
        modes[worst] = SLIP_POSITIVE if friction[worst] > 0.0 else SLIP_NEGATIVE
    raise RuntimeError(f"no consistent stick/slip modes at t = {t:.9g} s")


def solve_ivp_baseline(scene: Scene, periods: int, *, rtol: float = 1e-8,
                       atol: float = 1e-12, method: str = "RK45", initial=None,
                       max_switches: int = 1_000_000) -> BaselineRun:
    """Integrate ``scene`` over ``periods`` excitation periods with ``solve_ivp``, restarting
    at every switch located by its event functions.

    ``atol`` [m] holds the displacements and ``atol``·lΩ the velocities, as in
    ``Adaptive``; ``method`` is any of solve_ivp's explicit methods ("RK45" is the same
    Dormand–Prince 5(4) pair as ``Adaptive``).
    """
    if any(interface.tangential_stiffness is not None
           for _, _, interface in scene.group.interfaces):
        raise ValueError("solve_ivp_baseline takes rigid stick only, not an elastic contact "
                         "(Interface.tangential_stiffness)")
    model = _Model(scene)
    a = scene.arrays
    n = a.n_blades
    period = scene.excitation_period
    x, v = (np.zeros(n), np.zeros(n)) if initial is None else map(np.array, initial)
    penetration, _, slip = model.kinematics(0.0, x, v)
    model.set_modes(np.where(a.opens & (penetration <= 0.0), OPEN,
                             np.where(slip >= 0.0, SLIP_POSITIVE, SLIP_NEGATIVE)))
    tolerance = np.concatenate([np.full(n, atol), np.full(n, atol * a.excitation_frequency)])
    samples = period * np.arange(periods + 1)
    out_x, out_v = [x.copy()], [v.copy()]
    t, t_end, switches = 0.0, samples[-1], 0
    while t < t_end:
        found = model.events()
        after = samples[(samples > t) & (samples <= t_end)]
        solution = solve_ivp(model.rhs, (t, t_end), np.concatenate([x, v]), method=method,
                             rtol=rtol, atol=tolerance, t_eval=after,
                             events=[event for _, _, event in found])
        if solution.status < 0:
            raise RuntimeError(f"solve_ivp failed at t = {t:.9g} s: {solution.message}")
        sampled = np.reshape(solution.y, (2 * n, -1))
        out_x.extend(sampled[:n].T)
        out_v.extend(sampled[n:].T)
        if solution.status == 0:
            break
        which = next(k for k, times in enumerate(solution.t_events) if len(times))
        t = float(solution.t_events[which][0])
        y = solution.y_events[which][0]
        x, v = y[:n].copy(), y[n:].copy()
        interface, is_contact, _ = found[which]
        v = _switch(model, t, x, v, interface, is_contact)
        switches += 1
        if switches > max_switches:
            raise RuntimeError(f"more than {max_switches} switches by t = {t:.9g} s")
    return BaselineRun(x=np.array(out_x), v=np.array(out_v), switches=switches)
