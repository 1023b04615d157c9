"""``simulate``: the one entry point that turns a scene into a trajectory."""

from __future__ import annotations

import os
from dataclasses import dataclass, replace
from pathlib import Path

import numpy as np

from contact_laws import check_array, check_instance, check_int, check_real

from ..engine.codes import EventKind, Mode, Status, WorkColumn
from ..engine.controller import SMALLEST_STEP, first_step, smallest_step
from ..engine.dynamics import interface_kinematics
from ..engine.generate import compiled, kernel_scene, load_kernel
from ..engine.records import Controls, Run, allocate, finish, new_propagation
from ..model.lowering import from_dofs, to_dofs
from ..model.motion import motion_span
from ..model.scene import Scene, edge_matrix
from .footprint import check_footprint
from .methods import (
    EVENT_TOLERANCE,
    Accuracy,
    Adaptive,
    Exponential,
    FixedStep,
    SimulationSettings,
    ZenoGuard,
    check_event_tolerance,
)
from .scales import check_scales
from .simulation import EnergyLedger, EventLog, Simulation, SimulationError


def simulate(scene: Scene, periods: int, *,
             method: FixedStep | Adaptive | Exponential | Accuracy = Adaptive(),
             samples_per_period: int = 100,
             event_tolerance: float = EVENT_TOLERANCE,
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
    method : FixedStep, Adaptive, Exponential or Accuracy
        The integrator and its accuracy knobs, or the accuracy asked for. The default,
        ``Adaptive()`` (rtol = 1e-8), keeps Poincaré points and E_ρ of the paper's group
        to about 1e-7 at a quarter of the cost of ``FixedStep(steps_per_period=1000)``,
        which reaches 1e-9 (docs/guide/simulating.md, "What accuracy costs").
        ``Exponential()`` carries the motion between switches exactly, for scenes whose
        phases are linear.
    samples_per_period : int
        Output samples per period; with ``FixedStep`` or ``Exponential`` it must divide the
        steps per period.
    event_tolerance : float
        Width of the time bracket of each located switch, in excitation periods. Its
        error on the results is 0.3–6 times this; the default ``EVENT_TOLERANCE``
        (1e-10) stays below the integrators' own.
    zeno : ZenoGuard
        When to stop a run whose switches pile up.
    initial : (x0, v0) or (x0, v0, u0), optional
        Initial displacements [m] and velocities [m/s] by blade position: with
        substructures, every node's own degrees of freedom q (of
        ``Substructure.matrices_at``, in its units) and their rates, stacked in
        ``Scene.blades`` order (``Simulation.x`` and ``Simulation.state`` give them so);
        default at rest. With elastic contacts, u0 gives their springs' stretches [m] (two
        each, as ``Simulation.stretches``; relaxed where not given): a closed face whose
        stretch holds its force at the friction limit or beyond starts slipping, its
        stretch put on the limit; an open face's is relaxed.
    event_capacity : int
        Most events kept in the log, ≥ 0 (counts stay exact beyond it).

    Raises
    ------
    TypeError
        Before any work, on an argument of the wrong type, naming it.
    ValueError
        Before any work, on a bad argument, or when the record of the run (``output_bytes``)
        would need more than ``MEMORY_FRACTION`` (half) of the memory available as the run
        starts (``available_memory``; 8 GiB where it cannot be read).
    SimulationError
        Before any work, when the scene's numbers cannot be run (``scales.check_scales``: a
        natural frequency or damping rate whose stable step is below the smallest step, an
        energy beyond a float's range), naming the quantity.
        On Zeno or chattering behaviour, a mode set with no consistent choice, a step size
        that collapses, or a non-finite state; the message names the time and the interface.
        A run never returns a non-finite value: one found in the record or the energy ledger
        at the end raises this, naming the quantity.
    """
    check_instance("simulate", "scene", scene, Scene, expected="a shroudnet.Scene")
    done = integrate(scene, periods, method=method, samples_per_period=samples_per_period,
                     event_tolerance=event_tolerance, zeno=zeno,
                     initial=start_coordinates(scene, initial), event_capacity=event_capacity)
    run, method = done.run, done.method
    out = run.output
    events = EventLog(time=run.events.time, interface=run.events.interface,
                      kind=run.events.kind,
                      counts={k.name.lower(): int(run.events.counts[k]) for k in EventKind})
    settings = SimulationSettings(method=method, periods=periods,
                                  samples_per_period=samples_per_period,
                                  event_tolerance=done.event_tolerance,
                                  zeno=replace(zeno, window=done.zeno_window))
    with np.errstate(over="ignore", invalid="ignore"):
        ledger = _ledger(scene, out.t, out.x, out.v, out.modes, out.energy, done.stretches)
    check_finished(out, ledger)
    layout = scene.arrays.layout
    return Simulation(scene=scene, settings=settings, t=out.t, x=to_dofs(layout, out.x),
                      v=to_dofs(layout, out.v),
                      normal_force=out.normal, friction_force=out.friction, modes=out.modes,
                      events=events, energy=EnergyLedger(**ledger), work=out.energy,
                      samples_per_period=samples_per_period, steps=int(run.steps),
                      compile_seconds=done.compile_seconds,
                      friction_force_second=_second_friction(scene, done.stretches))


def _second_friction(scene, stretches) -> np.ndarray | None:
    """f₂ = k_t u₂ [N] of each elastic contact at every sample (n_t × n_interfaces, 0 on
    the others: u₂ stays 0 on a face of one direction, u on an open contact), from the
    springs' ``stretches`` (``Integration.stretches``); None without elastic contacts."""
    stiffness = scene.arrays.tangential_stiffness
    elastic = scene.arrays.elastic_interfaces
    if len(elastic) == 0:
        return None
    force = np.zeros((len(stretches), len(stiffness)))
    force[:, elastic] = stiffness[elastic] * stretches[:, 1::2]
    return force


@dataclass(frozen=True)
class Integration:
    """What ``integrate`` did: the kernel's ``records.Run``, the method with every knob as
    used (``Accuracy`` resolved, the default atol filled in), the event tolerance
    [periods] and the Zeno window [periods] it used, and the seconds spent compiling; the
    stretches u = r_t − w [m] of the elastic contacts' springs at every sample (two columns
    each, in interface order; none without elastic contacts), which the record by blade
    leaves out."""

    run: Run
    method: FixedStep | Adaptive | Exponential
    event_tolerance: float
    zeno_window: float
    compile_seconds: float
    stretches: np.ndarray


def integrate(scene: Scene, periods: int, *,
              method: FixedStep | Adaptive | Exponential | Accuracy = Adaptive(),
              samples_per_period: int = 100, event_tolerance: float = EVENT_TOLERANCE,
              zeno: ZenoGuard = ZenoGuard(), initial=None, event_capacity: int = 1_000_000,
              tangent: np.ndarray | None = None,
              orthonormalise: bool = False, until: float | None = None,
              times: np.ndarray | None = None) -> Integration:
    """``simulate``'s checks and run, returning the kernel's raw record: the engine's own,
    whose ``initial``, record and tangent are by its coordinates (``model.lowering``), not the
    nodes' degrees of freedom that ``simulate`` takes and gives.

    With ``tangent`` (2 n_blades × k; with elastic contacts, its rows δx and δẋ may be
    followed by the stretches' δu, 0 where they are not), the run integrates those k
    tangent vectors of the start with the state (``engine.tangent``), in a kernel compiled
    for it, by the adaptive method, or by the exponential one, which carries them through
    each phase by the phase's own e^{JΔt} (``kernel.tangent.carry_phase``); the run's
    tangent has rows δx, δẋ and, with elastic contacts, δu. ``orthonormalise``
    re-orthonormalises them after every step (by phases: at every switch and sample). With
    ``until`` [s] in (0, periods T_e], the run stops there instead, with two samples: the
    start and the state at ``until`` (the steps before it are those of the whole run; a
    fixed-grid method's last step ends at ``until``). With ``times`` [s] (increasing, in
    (0, periods T_e]; adaptive steps), it samples at 0 and at those times instead of the
    grid, each from the dense output of the step that holds it, and stops at the last.
    Arguments as ``simulate``; raises what it raises.
    """
    check_instance("simulate", "scene", scene, Scene, expected="a shroudnet.Scene")
    periods = check_int("simulate", "periods", periods, low=1, most=MAX_PERIODS)
    check_instance("simulate", "method", method, (FixedStep, Adaptive, Exponential, Accuracy),
                   expected="FixedStep(...), Adaptive(...), Exponential(...) or Accuracy(...)")
    check_instance("simulate", "zeno", zeno, ZenoGuard, expected="a ZenoGuard(...)")
    check_event_tolerance("simulate", event_tolerance)
    if isinstance(method, Accuracy):
        method, event_tolerance = method.settings(scene, event_tolerance)
    samples_per_period = check_int("simulate", "samples_per_period", samples_per_period, low=1)
    event_capacity = check_int("simulate", "event_capacity", event_capacity, low=0)
    on_grid = isinstance(method, FixedStep | Exponential)
    if on_grid and method.steps_per_period % samples_per_period:
        raise ValueError(f"samples_per_period must divide {type(method).__name__}."
                         f"steps_per_period = {method.steps_per_period}, got "
                         f"{samples_per_period}")
    if isinstance(method, Exponential):
        check_linear_phases(scene)
    n = scene.arrays.n_blades  # coordinates, with substructures
    initial, stretches = split_stretches(scene, initial)
    x0, v0 = initial_state(initial, n)
    check_footprint(scene, periods * samples_per_period + 1, event_capacity,
                    tangent_columns=None if tangent is None else np.shape(tangent)[1])
    _check_memory(scene, periods, samples_per_period, event_capacity)
    check_scales(scene, periods, method, (x0, v0))
    period = scene.excitation_period
    _check_motions(scene, periods * period)

    n_columns = 0 if tangent is None else tangent.shape[1]
    if tangent is not None and isinstance(method, FixedStep):
        raise ValueError("the tangent flow is integrated by the adaptive and the exponential "
                         "methods: use method=Adaptive(...), Accuracy(...) or Exponential(), "
                         "not FixedStep")
    tangent0 = np.zeros((2 * n, n_columns)) if tangent is None else np.array(
        tangent, dtype=float)
    tangent0, stretch_rows = tangent0[:2 * n], tangent0[2 * n:]  # rows δx, δẋ[, δu]
    x_p, v_p = scene.arrays.prescribed_state(0.0)
    x0, v0 = np.concatenate([x0, x_p]), np.concatenate([v0, v_p])
    tangent0 = _with_prescribed(tangent0, n, len(x_p))
    arrays = kernel_scene(scene)
    x0, v0, tangent0 = _with_sliders(scene.arrays.n_stretches, x0, v0, tangent0, n, stretches,
                                     stretch_rows if len(stretch_rows) else None)

    kernel = load_kernel(scene, tangent=tangent is not None, method=_KERNEL_METHODS[type(method)])
    controls, method, zeno_window = run_controls(
        scene, periods, method, samples_per_period, event_tolerance, zeno, event_capacity,
        orthonormalise=orthonormalise, until=until)
    listed = None
    if times is not None:
        listed = _listed_times(times, method, until, periods * period)
        controls = controls._replace(n_samples=len(listed),
                                     sample_step=listed[-1] / (len(listed) - 1))
    propagation = new_propagation(arrays, scene.arrays, controls.step) \
        if isinstance(method, Exponential) else None
    state, work, switching, events, output = allocate(arrays, x0, v0, tangent0, controls,
                                                      flow=tangent is not None,
                                                      propagation=propagation, times=listed)
    arguments = (state, arrays, work, switching, events, controls, output)
    driver, compile_seconds = compiled(kernel.run, arguments)
    run = finish(driver(*arguments), output, events, state.tangent)
    stretches = run.output.x[:, n:len(x0) - len(x_p)]
    run = _blades_only(run, n, scene.arrays.n_stretches)
    status = Status(run.status)
    if status != Status.FINISHED:
        raise SimulationError(_stop_message(scene, status, run.time, run.interface, period,
                                            zeno.events, zeno_window,
                                            isinstance(method, FixedStep)))
    return Integration(run=run, method=method, event_tolerance=event_tolerance,
                       zeno_window=zeno_window, compile_seconds=compile_seconds,
                       stretches=stretches)


def _listed_times(times, method, until, span: float) -> np.ndarray:
    """0 and ``times`` [s], checked (``integrate``): increasing, in (0, ``span``], and
    sampled by adaptive steps' dense output."""
    if not isinstance(method, Adaptive) or until is not None:
        raise ValueError("integrate.times: sample times of the caller's own are taken by "
                         "adaptive steps (method=Adaptive(...) or Accuracy(...)), without "
                         "until")
    try:
        listed = np.asarray(times, dtype=float)
    except (TypeError, ValueError):
        listed = np.zeros((0, 0))
    if listed.ndim != 1 or not len(listed) or not np.all(np.isfinite(listed)) \
            or listed[0] <= 0.0 or listed[-1] > span or np.any(np.diff(listed) <= 0.0):
        raise ValueError(f"integrate.times must be a 1-D array of increasing times in "
                         f"(0, {span:.9g}] s (the run's periods), got {times!r}")
    return np.concatenate([[0.0], listed])


def run_controls(scene: Scene, periods: int, method: FixedStep | Adaptive | Exponential,
                 samples_per_period: int, event_tolerance: float, zeno: ZenoGuard,
                 event_capacity: int, *, orthonormalise: bool = False,
                 until: float | None = None) -> tuple[Controls, object, float]:
    """The ``records.Controls`` of a run of ``scene`` over ``periods`` (arguments checked
    as ``integrate`` checks them), the method as recorded (the default atol filled in) and
    the Zeno window [periods]."""
    period = scene.excitation_period
    on_grid = isinstance(method, FixedStep | Exponential)
    zeno_window = zeno.window_at(event_tolerance)
    n_samples = periods * samples_per_period + 1
    sample_step = period / samples_per_period
    if until is not None:
        sample_step = check_real("simulate", "until", until, low=0.0, low_open=True,
                                 high=periods * period, unit="s")
        n_samples = 2
    if on_grid:
        step, rtol, atol = period / method.steps_per_period, 0.0, 0.0
        # a run to a given time samples its end only, after a shorter last step
        steps_per_sample = method.steps_per_period // samples_per_period if until is None \
            else periods * method.steps_per_period + 1
    else:
        method = replace(method, atol=method.absolute_tolerance(scene))  # as recorded
        step, rtol, atol = first_step(period), method.rtol, method.atol
        steps_per_sample = 0
    controls = Controls(
        t0=0.0, sample_step=sample_step,
        n_samples=n_samples, step=step, steps_per_sample=steps_per_sample, rtol=rtol,
        atol_x=atol, atol_v=atol * scene.arrays.excitation_frequency,
        h_max=getattr(method, "max_step", 1.0) * period, h_min=smallest_step(period),
        event_tolerance=event_tolerance * period, zeno_events=zeno.events,
        zeno_window=zeno_window * period, event_capacity=event_capacity,
        orthonormalise=orthonormalise,
        exponentials=scene.arrays.linear_phases and (
            not orthonormalise or isinstance(method, Exponential)))
    return controls, method, zeno_window


#: The kernel of each method (``engine.generate.METHODS``).
_KERNEL_METHODS = {Adaptive: "adaptive", FixedStep: "fixed_step", Exponential: "exponential"}


def check_linear_phases(scene: Scene) -> None:
    """Refuse ``Exponential`` on a scene whose vector field is not linear between switches,
    naming what makes it so."""
    a = scene.arrays
    why = None
    if not a.is_structure:
        why = "a scene of blades alone (add a Substructure, or use Adaptive)"
    elif a.n_prescribed:
        why = "prescribed motions, whose accelerations are not harmonics of the excitation"
    elif a.n_stretches:
        why = "elastic contacts, whose sliders turn with the stretch's direction"
    else:
        for contact, normal, friction in zip(scene.contacts, a.normal_laws, a.friction_laws):
            for law in (normal, friction):
                if law is not None and not type(law).constant_slopes:
                    why = (f"{contact} has a {type(law).__name__}, "
                           "not a law of constant slopes (LinearSpring, ConstantLoad, "
                           "Coulomb)")
                    break
            if why:
                break
    if why:
        raise ValueError("method=Exponential() takes scenes whose motion is linear between "
                         f"switches, but this one has {why}")


def _check_motions(scene, duration):
    """Refuse, before any work, a run that would leave a motion table's time span."""
    for name, motion in scene.group.prescribed:
        first, last = motion_span(motion)
        if first > 0.0 or last < duration:
            raise ValueError(f"prescribed node {name!r}: its MotionTable covers t = "
                             f"{first:g} … {last:g} s, but the run spans 0 … {duration:g} s; "
                             "extend the table's times, or run fewer periods")


def _with_prescribed(tangent, n, n_prescribed):
    """Tangent columns by blade (x rows, then ẋ rows) with zero rows for the prescribed-
    motion nodes, which follow the blades in the integrator's state: their motion is given,
    so it has no variation."""
    if n_prescribed == 0:
        return tangent
    rows = np.zeros((2 * (n + n_prescribed), tangent.shape[1]))
    rows[:n], rows[n + n_prescribed:2 * n + n_prescribed] = tangent[:n], tangent[n:]
    return rows


def _with_sliders(sliders, x0, v0, tangent0, n, stretches=None, stretch_rows=None):
    """The start (x0, v0, tangent columns) in the integrator's coordinates: the elastic
    contacts' ``sliders`` stretches u (``engine.sliders``, ``SceneArrays.n_stretches``)
    after the n free coordinates, each relaxed
    (u = 0: no friction force) or as ``stretches`` give them, and their tangent rows
    ``stretch_rows`` (0 where None); their velocity slots at rest and without variation."""
    if sliders == 0:
        return x0, v0, tangent0
    nodes = len(x0)
    x0 = np.insert(x0, [n] * sliders, 0.0 if stretches is None else stretches)
    v0 = np.insert(v0, [n] * sliders, 0.0)
    tangent0 = np.insert(tangent0, [n] * sliders,
                         0.0 if stretch_rows is None else stretch_rows, axis=0)
    tangent0 = np.insert(tangent0, [nodes + sliders + n] * sliders, 0.0, axis=0)
    return x0, v0, tangent0


def _blades_only(run: Run, n: int, sliders: int) -> Run:
    """The run's record with the blades' rows only, and its tangent's rows (δx, δẋ, δu):
    the prescribed-motion nodes that follow the blades in the integrator's state are known
    functions of time, and the ``sliders`` stretches' velocity slots are no state."""
    out, g = run.output, run.tangent
    nodes = out.x.shape[1]
    if nodes == n:
        return run
    rows = np.r_[0:n, nodes:nodes + n, n:n + sliders]
    return run._replace(output=out._replace(x=out.x[:, :n], v=out.v[:, :n]),
                        tangent=g._replace(matrix=g.matrix[rows]))


#: The most excitation periods one run may span: beyond it the time t = periods·T_e is so
#: large that a step of 1e-6 periods falls near the resolution of a float (1e-16 of t).
MAX_PERIODS = 10**9

#: A run may claim at most this fraction of the memory available when it starts.
MEMORY_FRACTION = 0.5
#: A record this small [bytes] is not checked against the available memory: 1 MiB.
SMALL_RECORD = 2**20
#: The bound [bytes] where the available memory cannot be read: 8 GiB.
MEMORY_FALLBACK = 8 * 2**30


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
    blades, interfaces = scene.arrays.n_blades, len(scene.group.interfaces)
    per_sample = 8 * (1 + 2 * blades + 2 * interfaces + len(WorkColumn)) + interfaces
    return n_samples * per_sample + event_capacity * (8 + 8 + 1)


def _check_memory(scene, periods, samples_per_period, event_capacity):
    """Refuse, before any work, a run whose record would not fit in memory."""
    needed = output_bytes(scene, periods, samples_per_period, event_capacity)
    if needed <= SMALL_RECORD:
        return
    available = available_memory()
    bound = MEMORY_FALLBACK if available is None else int(MEMORY_FRACTION * available)
    if needed > bound:
        what = (f"half the {available / 2**30:.3g} GiB available" if available is not None
                else f"the {MEMORY_FALLBACK / 2**30:g} GiB allowed where the available memory "
                     "cannot be read")
        raise ValueError(f"periods = {periods} with samples_per_period = {samples_per_period} "
                         f"would record {periods * samples_per_period + 1:,} samples and need "
                         f"{needed / 2**30:.3g} GiB with event_capacity = {event_capacity:,} "
                         f"events, more than {what}. Run fewer periods, "
                         "take fewer samples per period, or run in pieces, each starting from "
                         "the last state of the one before (initial=).")


def start_coordinates(scene: Scene, initial, owner: str = "simulate",
                      field: str = "initial") -> tuple | None:
    """``initial`` as a user gives it (None, (q0, q̇0) or (q0, q̇0, u0): the nodes' own
    degrees of freedom, ``simulate``), checked as ``owner.field``, and as the engine takes
    it: (η0, η̇0[, u0]) by its coordinates (``model.lowering.from_dofs``); None for rest."""
    if initial is None:
        return None
    initial, stretches = split_stretches(scene, initial, owner, field)
    x0, v0 = initial_state(initial, scene.arrays.n_blades, owner, field)
    layout = scene.arrays.layout
    return (from_dofs(layout, x0), from_dofs(layout, v0)) + (
        () if stretches is None else (stretches,))


def split_stretches(scene: Scene, initial, owner: str = "simulate",
                    field: str = "initial") -> tuple[object, np.ndarray | None]:
    """(x0, v0) of ``initial`` and the stretches u0 its third member gives the sliders of a
    scene with elastic contacts (2 per elastic contact [m], as ``Simulation.stretches``),
    or None where it has none: relaxed sliders."""
    count = scene.arrays.n_stretches
    if count == 0 or not isinstance(initial, tuple | list | np.ndarray) \
            or getattr(initial, "ndim", 1) == 0 or len(initial) != 3:
        return initial, None
    try:
        stretches = check_array(owner, f"{field} u0", initial[2], shape=(count,))
    except ValueError:
        raise ValueError(f"{owner}.{field} must be (x0, v0) or (x0, v0, u0): u0 must hold "
                         f"the {count} finite stretches [m] of the elastic contacts' springs "
                         f"(two each), got {initial[2]!r:.200}") from None
    return tuple(initial[:2]), stretches


def initial_state(initial, n: int, owner: str = "simulate",
                  field: str = "initial") -> tuple[np.ndarray, np.ndarray]:
    """(x0, v0) from ``initial``: None (rest) or a pair of sequences of ``n`` finite numbers
    [m, m/s] (a 2 × n array as the same nested list); anything else raises naming
    ``owner.field``."""
    if initial is None:
        return np.zeros(n), np.zeros(n)
    pair = (f"{owner}.{field} must be (x0, v0), a pair of {n} displacements [m] and {n} "
            "velocities [m/s], or None for rest")
    if not isinstance(initial, tuple | list | np.ndarray) or getattr(initial, "ndim", 1) == 0:
        raise TypeError(f"{pair}; got {type(initial).__name__} {initial!r:.200}")
    if len(initial) != 2:
        raise ValueError(f"{pair}; got {type(initial).__name__} {initial!r:.200}")
    state = []
    for name, values in zip(("x0", "v0"), initial):
        try:
            state.append(check_array(owner, f"{field} {name}", values, shape=(n,)))
        except ValueError:
            raise ValueError(f"{owner}.{field} must be (x0, v0): {field} {name} must hold {n} "
                             f"finite numbers, got {values!r:.200}") from None
    return tuple(state)


def check_finished(out, ledger: dict) -> None:
    """Raise ``SimulationError`` naming the first quantity of a finished run's record
    ``out`` (``records.Output``) or of its energy ``ledger`` (the ``EnergyLedger`` fields)
    that is not finite, and the time it first is, for a history: a run never returns one."""
    histories = (("time t", out.t), ("displacement x", out.x), ("velocity v", out.v),
                 ("normal force", out.normal), ("friction force", out.friction),
                 ("cumulative work", out.energy))
    for name, values in histories:
        bad = ~np.isfinite(values)
        if bad.any():
            first = int(np.argmax(bad.reshape(len(values), -1).any(axis=1)))
            raise SimulationError(
                f"the run ended with a non-finite {name} (first at t = {out.t[first]:.9g} s, "
                f"sample {first}): the scene's numbers overflow there; check the units of "
                "its masses, stiffnesses, forces and initial state")
    for name, value in ledger.items():
        if not np.isfinite(value):
            raise SimulationError(
                f"the run ended with a non-finite energy ledger entry {name} = "
                f"{value}: the energies of the scene overflow; check the units of its "
                "masses, stiffnesses, forces and initial state")


def _stop_message(scene, status, t, interface, period, zeno_events, zeno_window,
                  fixed_step=False):
    where = ""
    if interface >= 0:
        where = f" on {scene.contacts[interface]}"
    when = f"at t = {t:.9g} s (period {t / period:.6f})"
    return status.message(when, where, zeno_events=zeno_events, zeno_window=zeno_window,
                          smallest_step=SMALLEST_STEP, fixed_step=fixed_step)


#: Nodes and weights of 16-point Gauss–Legendre quadrature on [−1, 1] (computing them
#: takes longer than a short run's whole energy ledger).
_GAUSS_LEGENDRE = np.polynomial.legendre.leggauss(16)


def _contact_energy(law, penetration):
    """∫₀^δ N(s, 0) ds [J] by 16-point Gauss–Legendre quadrature."""
    nodes, weights = _GAUSS_LEGENDRE
    s = 0.5 * penetration * (nodes + 1.0)
    return 0.5 * penetration * sum(w * law(si, 0.0) for si, w in zip(s, weights))


def _stored(scene, t, x, v, modes):
    """Kinetic and strain energy of the blades and couplings [J], and the contacts' strain
    energy, at time t in state (x, ẋ) by blade; a prescribed-motion node moves as its motion
    says, and carries no energy of its own."""
    a = scene.arrays
    kinetic = 0.5 * np.sum(a.mass * v * v)
    x_p, v_p = a.prescribed_state(t)
    x, v = np.concatenate([x, x_p]), np.concatenate([v, v_p])
    if a.is_structure:
        strain = 0.5 * x @ a.structure_stiffness @ x
        penetration = a.normal_rows @ x - a.normal_gap
    else:
        strain = 0.5 * x @ edge_matrix(np.concatenate([a.stiffness, np.zeros(len(x_p))]),
                                       a.coupling_left, a.coupling_right,
                                       a.coupling_stiffness) @ x
        penetration, rate, slip = (np.empty(a.n_interfaces) for _ in range(3))
        interface_kinematics(x, v, a.left, a.right, a.gap, a.sin_angle, a.cos_angle,
                             penetration, rate, slip)
    contact = sum(_contact_energy(law, penetration[e])
                  for e, law in enumerate(a.normal_laws) if modes[e] != Mode.OPEN)
    return kinetic + strain, contact


def _elastic_energy(scene, stretches, modes):
    """½ k_t |u|² [J] summed over the closed elastic contacts, their springs' stretches
    ``stretches`` (u₁, u₂ of each, in interface order)."""
    stiffness = scene.arrays.tangential_stiffness
    energy = 0.0
    for k, e in enumerate(scene.arrays.elastic_interfaces):
        if modes[e] != Mode.OPEN:
            stretch = stretches[2 * k:2 * k + 2]
            energy += 0.5 * stiffness[e] * float(stretch @ stretch)
    return energy


def _ledger(scene, t, x, v, modes, work, stretches) -> dict[str, float]:
    """The ``EnergyLedger`` fields of a run, by name; ``stretches`` as
    ``Integration.stretches``."""
    mechanical_0, contact_0 = _stored(scene, t[0], x[0], v[0], modes[0])
    mechanical_1, contact_1 = _stored(scene, t[-1], x[-1], v[-1], modes[-1])
    if stretches.shape[1]:
        mechanical_0 += _elastic_energy(scene, stretches[0], modes[0])
        mechanical_1 += _elastic_energy(scene, stretches[-1], modes[-1])
    excitation, damping, friction, contact_work, lock = work[-1] - work[0]
    contact_stored = contact_1 - contact_0
    stored = mechanical_1 - mechanical_0 + contact_stored
    contact_loss = contact_work - contact_stored
    friction_loss = friction + lock
    residual = excitation - damping - friction_loss - contact_loss - stored
    return dict(excitation_work=float(excitation), damping_loss=float(damping),
                friction_loss=float(friction_loss), contact_loss=float(contact_loss),
                stored_change=float(stored), residual=float(residual))
