"""``simulate``: the one entry point that turns a scene into a trajectory."""

from __future__ import annotations

from dataclasses import asdict, dataclass

import numpy as np

from contact_laws import check_real

from .dynamics import interface_kinematics
from .kernel import kernel_scene, load_kernel
from .modes import Mode
from .scene import Scene
from .simulation import EnergyLedger, EventKind, EventLog, Simulation, SimulationError


@dataclass(frozen=True, kw_only=True)
class FixedStep:
    """Classical fourth-order Runge–Kutta on a fixed grid, switches located by bisection.

    This is the paper's scheme. The global error falls as h⁴ between switches.

    Parameters
    ----------
    steps_per_period : int
        Steps per excitation period T_e, ≥ 8.
    """

    steps_per_period: int = 1000

    def __post_init__(self):
        if isinstance(self.steps_per_period, bool) or not isinstance(self.steps_per_period, int) \
                or self.steps_per_period < 8:
            raise ValueError(f"FixedStep.steps_per_period must be an int >= 8, "
                             f"got {self.steps_per_period!r}")


@dataclass(frozen=True, kw_only=True)
class Adaptive:
    """Dormand–Prince 5(4) with error control and dense output; switches found on it.

    A step is accepted when the RMS over blades of its local error estimate, each component
    divided by atol + rtol·|value|, is at most 1. Displacements are held to ``atol`` [m] and
    velocities to ``atol``·lΩ [m/s], the same scale for harmonic motion at the excitation
    frequency. Samples and switches are taken from the step's 4th-order dense output, so
    they do not shorten the steps.

    Parameters
    ----------
    rtol : float
        Relative tolerance per step, in [1e-14, 0.1].
    atol : float
        Absolute tolerance on displacements per step [m], > 0.
    max_step : float
        Largest step, in excitation periods, in (0, 1].
    """

    rtol: float = 1e-8
    atol: float = 1e-12
    max_step: float = 0.05

    def __post_init__(self):
        check_real("Adaptive", "rtol", self.rtol, low=1e-14, high=0.1)
        check_real("Adaptive", "atol", self.atol, low=0.0, low_open=True, unit="m")
        check_real("Adaptive", "max_step", self.max_step, low=0.0, low_open=True, high=1.0,
                   unit="periods")


@dataclass(frozen=True, kw_only=True)
class Accuracy:
    """Ask for a relative error; get the adaptive settings that deliver it.

    ``target`` bounds the relative error of what a periodic response is read for: its
    Poincaré points (relative to the response amplitude) and E_ρ. For each scene it
    becomes ``Adaptive(rtol=target/100, atol=rtol·x_s)`` with x_s = Σ|q_n| / min k_i, the
    static deflection under the whole excitation, and an event tolerance of at most
    target/100 periods. The factor 100 comes from the work–precision study
    (``shroudnet.precision``, README "What accuracy costs"): on the paper's group the
    error of the adaptive integrator is 7–16 times its rtol, and that of the event
    location 0.3–6 times its tolerance. In chaos no single trajectory converges; E_ρ and
    the attractor's bounds then converge to the sampling error of the record instead.

    Parameters
    ----------
    target : float
        The relative error asked for, in [1e-8, 0.1].
    """

    target: float

    def __post_init__(self):
        check_real("Accuracy", "target", self.target, low=1e-8, high=0.1)

    def settings(self, scene: Scene, event_tolerance: float) -> tuple[Adaptive, float]:
        """The integrator and event tolerance [periods] that deliver ``target`` on ``scene``."""
        a = scene.arrays
        deflection = np.abs(a.amplitudes).sum() / a.stiffness.min()
        rtol = self.target / ACCURACY_MARGIN
        method = Adaptive(rtol=rtol, atol=rtol * (deflection if deflection > 0.0 else 1e-6))
        return method, min(event_tolerance, rtol)


#: How much tighter than the asked accuracy the step and event tolerances are set.
ACCURACY_MARGIN = 100.0


@dataclass(frozen=True, kw_only=True)
class ZenoGuard:
    """Stop a run when switches pile up: ``events`` of them within ``window`` periods.

    Chattering and Zeno behaviour (infinitely many switches in finite time) otherwise make
    an event-driven integrator crawl. Past an accumulation point of switches, a located
    switch leaves the state within the event tolerance of the next one, so the pile-up
    goes on at a spacing of some tens of event tolerances. The default window, 10⁶ event
    tolerances (10⁻⁴ periods at the default tolerance) but at most 10⁻³ periods, is wide
    enough to see that, and 200 switches in it would mean at least 2·10⁵ per period, far
    beyond any motion the integrator resolves. (With a loose event tolerance such a
    pile-up moves on by many tolerances per switch, so it ends without the guard.) The
    run stops with a ``SimulationError`` naming the time and the interface.

    Parameters
    ----------
    events : int
        Switches that make a pile-up, ≥ 2.
    window : float, optional
        Their time span, in excitation periods, > 0; by default
        min(10⁶ × ``event_tolerance``, 10⁻³).
    """

    events: int = 200
    window: float | None = None

    def __post_init__(self):
        if isinstance(self.events, bool) or not isinstance(self.events, int) or self.events < 2:
            raise ValueError(f"ZenoGuard.events must be an int >= 2, got {self.events!r}")
        if self.window is not None:
            check_real("ZenoGuard", "window", self.window, low=0.0, low_open=True,
                       unit="periods")

    def window_at(self, event_tolerance: float) -> float:
        """The window in periods for a run that locates switches to ``event_tolerance``."""
        if self.window is not None:
            return self.window
        return min(ZENO_WINDOW_TOLERANCES * event_tolerance, ZENO_WINDOW_LIMIT)


#: The default Zeno window, in event tolerances, and its upper limit in periods.
ZENO_WINDOW_TOLERANCES = 1e6
ZENO_WINDOW_LIMIT = 1e-3


def simulate(scene: Scene, periods: int, *,
             method: FixedStep | Adaptive | Accuracy = Adaptive(),
             samples_per_period: int = 100, event_tolerance: float = 1e-10,
             zeno: ZenoGuard = ZenoGuard(), initial=None,
             event_capacity: int = 1_000_000) -> Simulation:
    """Integrate ``scene`` over ``periods`` excitation periods T_e = 2π/(l Ω).

    Every switch of an interface (contact closing or opening, slip velocity reaching zero,
    breakaway) is located to within ``event_tolerance`` and the integration restarts there
    in a consistent set of modes.

    Parameters
    ----------
    scene : Scene
    periods : int
        Number of excitation periods, ≥ 1.
    method : FixedStep, Adaptive or Accuracy
        The integrator and its accuracy knobs, or the accuracy asked for. The default,
        ``Adaptive()`` (rtol = 1e-8), keeps Poincaré points and E_ρ of the paper's group
        to about 1e-7 at a quarter of the cost of ``FixedStep(steps_per_period=1000)``,
        which reaches 1e-9 (README, "What accuracy costs").
    samples_per_period : int
        Output samples per period; with ``FixedStep`` it must divide the steps per period.
    event_tolerance : float
        Width of the time bracket of each located switch, in excitation periods. Its
        error on the results is 0.3–6 times this; the default 1e-10 stays below the
        integrators' own.
    zeno : ZenoGuard
        When to stop a run whose switches pile up.
    initial : (x0, v0), optional
        Initial displacements [m] and velocities [m/s] by blade position; default at rest.
    event_capacity : int
        Most events kept in the log (counts stay exact beyond it).

    Raises
    ------
    SimulationError
        On Zeno or chattering behaviour, a mode set with no consistent choice, a step size
        that collapses, or a non-finite state; the message names the time and the interface.
    """
    if not isinstance(scene, Scene):
        raise TypeError(f"simulate needs a shroudnet.Scene, got {scene!r}")
    if isinstance(periods, bool) or not isinstance(periods, int) or periods < 1:
        raise ValueError(f"periods must be an int >= 1, got {periods!r}")
    if not isinstance(method, FixedStep | Adaptive | Accuracy):
        raise TypeError("method must be FixedStep(...), Adaptive(...) or Accuracy(...), "
                        f"got {method!r}")
    check_real("simulate", "event_tolerance", event_tolerance, low=0.0, low_open=True,
               high=1e-3, unit="periods")
    if isinstance(method, Accuracy):
        method, event_tolerance = method.settings(scene, event_tolerance)
    if isinstance(samples_per_period, bool) or not isinstance(samples_per_period, int) \
            or samples_per_period < 1:
        raise ValueError(f"samples_per_period must be an int >= 1, got {samples_per_period!r}")
    if isinstance(method, FixedStep) and method.steps_per_period % samples_per_period:
        raise ValueError(f"samples_per_period must divide FixedStep.steps_per_period = "
                         f"{method.steps_per_period}, got {samples_per_period}")
    n = len(scene.blades)
    x0, v0 = (np.zeros(n), np.zeros(n)) if initial is None else (
        _initial(initial[0], n, "x0"), _initial(initial[1], n, "v0"))

    period = scene.excitation_period
    kernel = load_kernel(scene)
    ks = kernel_scene(scene)
    zeno_window = zeno.window_at(event_tolerance)
    common = (event_tolerance * period, zeno.events, zeno_window * period, event_capacity)
    if isinstance(method, FixedStep):
        steps = method.steps_per_period
        result = kernel.run_fixed_step(ks, x0, v0, 0.0, period / steps, periods * steps,
                                       steps // samples_per_period, *common)
    else:
        omega = scene.arrays.excitation_frequency
        result = kernel.run_adaptive(
            ks, x0, v0, 0.0, period / samples_per_period, periods * samples_per_period + 1,
            method.rtol, method.atol, method.atol * omega, 1e-3 * period,
            method.max_step * period, _SMALLEST_STEP * period, *common)
    (status, t_stop, interface, n_steps, t, x, v, normal, friction, modes, work, log_t, log_e,
     log_k, counts) = result
    if status != kernel.FINISHED:
        raise SimulationError(_stop_message(kernel, scene, status, t_stop, interface, period,
                                            zeno.events, zeno_window))

    events = EventLog(time=log_t, interface=log_e, kind=log_k,
                      counts={k.name.lower(): int(counts[k]) for k in EventKind})
    ledger = _ledger(scene, x, v, modes, work)
    settings = {"method": type(method).__name__, **asdict(method), "periods": periods,
                "samples_per_period": samples_per_period, "event_tolerance": event_tolerance,
                "zeno": {"events": zeno.events, "window": zeno_window}}
    return Simulation(scene=scene, settings=settings, t=t, x=x, v=v, normal_force=normal,
                      friction_force=friction, modes=modes, events=events, energy=ledger,
                      work=work, samples_per_period=samples_per_period, steps=int(n_steps))


#: An adaptive step below this many excitation periods stops the run.
_SMALLEST_STEP = 1e-14


def _initial(values, n, name):
    array = np.asarray(values, dtype=float)
    if array.shape != (n,) or not np.isfinite(array).all():
        raise ValueError(f"initial {name} must hold {n} finite numbers, got {values!r}")
    return array


def _stop_message(kernel, scene, status, t, interface, period, zeno_events, zeno_window):
    where = ""
    if interface >= 0:
        left, right, _ = scene.group.interfaces[interface]
        where = f" on interface {interface} ({left!r}, {right!r})"
    when = f"at t = {t:.9g} s (period {t / period:.6f})"
    if status == kernel.ZENO:
        return (f"Zeno or chattering behaviour {when}{where}: {zeno_events} switches within "
                f"{zeno_window:g} periods. The switches accumulate there, and past that "
                "point the laws define no motion the integrator can follow. Make the "
                "contact force continuous at closing, soften or damp the contact, use a "
                "Regularised friction law, or widen ZenoGuard if this is expected.")
    if status == kernel.INCONSISTENT:
        return (f"no consistent set of stick and slip modes {when}{where}: the friction "
                "limits of coupled stuck interfaces conflict.")
    if status == kernel.STEP_TOO_SMALL:
        return (f"the adaptive step fell below {_SMALLEST_STEP:g} periods {when}{where}: "
                "the tolerances cannot be met there; loosen rtol/atol or stiffen less.")
    return f"the state became non-finite {when}{where}; reduce the step or the stiffness."


def _contact_energy(law, penetration):
    """∫₀^δ N(s, 0) ds [J] by 16-point Gauss–Legendre quadrature."""
    nodes, weights = np.polynomial.legendre.leggauss(16)
    s = 0.5 * penetration * (nodes + 1.0)
    return 0.5 * penetration * sum(w * law(si, 0.0) for si, w in zip(s, weights))


def _stored(scene, x, v, modes):
    a = scene.arrays
    kinetic = 0.5 * np.sum(a.mass * v * v)
    strain = 0.5 * np.sum(a.stiffness * x * x)
    penetration, rate, slip = (np.empty(a.n_interfaces) for _ in range(3))
    interface_kinematics(x, v, a.left, a.right, a.gap, a.sin_angle, a.cos_angle,
                         penetration, rate, slip)
    contact = sum(_contact_energy(law, penetration[e])
                  for e, law in enumerate(a.normal_laws) if modes[e] != Mode.OPEN)
    return kinetic + strain, contact


def _ledger(scene, x, v, modes, work) -> EnergyLedger:
    mechanical_0, contact_0 = _stored(scene, x[0], v[0], modes[0])
    mechanical_1, contact_1 = _stored(scene, x[-1], v[-1], modes[-1])
    excitation, damping, friction, contact_work, lock = work[-1] - work[0]
    contact_stored = contact_1 - contact_0
    stored = mechanical_1 - mechanical_0 + contact_stored
    contact_loss = contact_work - contact_stored
    friction_loss = friction + lock
    residual = excitation - damping - friction_loss - contact_loss - stored
    return EnergyLedger(excitation_work=float(excitation), damping_loss=float(damping),
                        friction_loss=float(friction_loss), contact_loss=float(contact_loss),
                        stored_change=float(stored), residual=float(residual))
