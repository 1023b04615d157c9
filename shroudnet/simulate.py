"""``simulate``: the one entry point that turns a scene into a trajectory."""

from __future__ import annotations

import os
from dataclasses import asdict, dataclass
from pathlib import Path

import numpy as np

from contact_laws import check_int, check_real

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
        object.__setattr__(self, "steps_per_period",
                           check_int("FixedStep", "steps_per_period", self.steps_per_period,
                                     low=8))


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
        deflection = scene.arrays.static_deflection
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
        object.__setattr__(self, "events", check_int("ZenoGuard", "events", self.events, low=2))
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
        Most events kept in the log, ≥ 0 (counts stay exact beyond it).

    Raises
    ------
    ValueError
        Before any work, on a bad argument, or when the record of the run (``output_bytes``)
        would need more than ``MEMORY_FRACTION`` (half) of the memory available as the run
        starts (``available_memory``; 8 GiB where it cannot be read).
    SimulationError
        On Zeno or chattering behaviour, a mode set with no consistent choice, a step size
        that collapses, or a non-finite state; the message names the time and the interface.
    """
    if not isinstance(scene, Scene):
        raise TypeError(f"simulate needs a shroudnet.Scene, got {scene!r}")
    periods = check_int("simulate", "periods", periods, low=1)
    if not isinstance(method, FixedStep | Adaptive | Accuracy):
        raise TypeError("method must be FixedStep(...), Adaptive(...) or Accuracy(...), "
                        f"got {method!r}")
    check_real("simulate", "event_tolerance", event_tolerance, low=0.0, low_open=True,
               high=1e-3, unit="periods")
    if isinstance(method, Accuracy):
        method, event_tolerance = method.settings(scene, event_tolerance)
    samples_per_period = check_int("simulate", "samples_per_period", samples_per_period, low=1)
    event_capacity = check_int("simulate", "event_capacity", event_capacity, low=0)
    if isinstance(method, FixedStep) and method.steps_per_period % samples_per_period:
        raise ValueError(f"samples_per_period must divide FixedStep.steps_per_period = "
                         f"{method.steps_per_period}, got {samples_per_period}")
    n = len(scene.blades)
    x0, v0 = (np.zeros(n), np.zeros(n)) if initial is None else (
        _initial(initial[0], n, "x0"), _initial(initial[1], n, "v0"))
    _check_memory(scene, periods, samples_per_period, event_capacity)

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

#: A run may claim at most this fraction of the memory available when it starts.
MEMORY_FRACTION = 0.5
#: The bound [bytes] where the available memory cannot be read: 8 GiB.
MEMORY_FALLBACK = 8 * 2**30
#: Columns of ``Simulation.work``: excitation, damping, friction, contact, lock.
_WORK_COLUMNS = 5


def available_memory() -> int | None:
    """Bytes the machine can still give this process, or None where that cannot be read.

    ``MemAvailable`` of ``/proc/meminfo`` (Linux), else the free physical pages
    (``os.sysconf``), lowered to the room left under a cgroup v2 memory limit.
    """
    found = []
    try:
        for line in Path("/proc/meminfo").read_text().splitlines():
            if line.startswith("MemAvailable:"):
                found.append(int(line.split()[1]) * 1024)
    except (OSError, ValueError, IndexError):
        pass
    if not found:
        try:
            found.append(os.sysconf("SC_AVPHYS_PAGES") * os.sysconf("SC_PAGE_SIZE"))
        except (AttributeError, OSError, ValueError):
            pass
    try:
        cgroup = Path("/sys/fs/cgroup")
        limit = (cgroup / "memory.max").read_text().strip()
        if limit != "max":
            found.append(int(limit) - int((cgroup / "memory.current").read_text()))
    except (OSError, ValueError):
        pass
    return max(min(found), 0) if found else None


def output_bytes(scene: Scene, periods: int, samples_per_period: int,
                 event_capacity: int) -> int:
    """Bytes a run allocates for its record: per sample t, x, v (float64 per blade), normal
    and friction forces (float64) and modes (int8) per interface and the work columns;
    and the event log (time, interface, kind) at its capacity."""
    n_samples = periods * samples_per_period + 1
    blades, interfaces = len(scene.blades), len(scene.group.interfaces)
    per_sample = 8 * (1 + 2 * blades + 2 * interfaces + _WORK_COLUMNS) + interfaces
    return n_samples * per_sample + event_capacity * (8 + 8 + 1)


def _check_memory(scene, periods, samples_per_period, event_capacity):
    """Refuse, before any work, a run whose record would not fit in memory."""
    needed = output_bytes(scene, periods, samples_per_period, event_capacity)
    available = available_memory()
    bound = MEMORY_FALLBACK if available is None else int(MEMORY_FRACTION * available)
    if needed > bound:
        what = (f"half the {available / 2**30:.3g} GiB available" if available is not None
                else f"the {MEMORY_FALLBACK / 2**30:g} GiB allowed where the available memory "
                     "cannot be read")
        raise ValueError(f"periods = {periods} with samples_per_period = {samples_per_period} "
                         f"would record {periods * samples_per_period + 1:,} samples and need "
                         f"{needed / 2**30:.3g} GiB, more than {what}. Run fewer periods, "
                         "take fewer samples per period, or run in pieces, each starting from "
                         "the last state of the one before (initial=).")


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
        return (f"no consistent set of stick and slip modes {when}{where}: the interface "
                "needs more static friction than μ_s N to stick, yet slipping either way "
                "would reverse at once. Its friction law's kinetic coefficient near zero "
                "slip, μ(0⁺), must not exceed μ_s.")
    if status == kernel.NO_PROGRESS:
        return (f"no progress {when}{where}: {kernel.MAX_IDLE_SWITCHES} switches in a row "
                "changed no mode, so the event guards and the stick and slip rule disagree "
                "there. The laws cannot cause this (both read the same μ_s N): it is a "
                "defect of the mode rule; please report it with the scene file.")
    if status == kernel.STEP_TOO_SMALL:
        return (f"the adaptive step fell below {_SMALLEST_STEP:g} periods {when}{where}: "
                "the forces change too abruptly there for the tolerances (a jump in a "
                "contact law, or a very stiff contact); smooth the law, or loosen rtol/atol.")
    return (f"the state or the forces became non-finite {when}{where}: a contact or "
            "friction law returned inf or NaN there, or the fixed step is too large for the "
            "stiffest contact (use Adaptive, or more steps per period).")


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
