"""Periodic orbits by shooting: Newton on the stroboscopic map with its exact Jacobian.

A forced orbit of period k T_e is a fixed point of the k-period stroboscopic map φ:
F(y) = φ(y) − y = 0 with y = (x, ẋ) at t = 0 mod T_e (DESIGN §6). Newton's step solves
(M − I) Δy = −F, with M = ∂φ/∂y the monodromy matrix that the tangent flow gives through
every switch (``stability``); the Floquet multipliers are M's eigenvalues at the orbit.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from contact_laws import check_choice, check_instance, check_int, check_real

from ..analysis.readings import hysteresis_loop
from ..analysis.stability import (
    TANGENT_METHOD,
    StroboscopicStep,
    jacobian_in_dofs,
    state_parts,
    state_size,
    stroboscopic_step,
)
from ..checked_records import check_record
from ..engine.codes import EventKind
from ..linear.modes import nodal_diameters
from ..model.lowering import from_dofs, to_dofs
from ..model.scene import Scene
from ..run.methods import EVENT_TOLERANCE, Accuracy, Adaptive, check_event_tolerance
from ..run.simulate import MAX_PERIODS, simulate, start_coordinates
from ..run.simulation import EventLog, Simulation, SimulationError
from .cycle import (
    EnergyPerCycle,
    Harmonics,
    energy_per_cycle,
    equivalent_damping,
    harmonics,
    kinetic_peak,
)
from .cyclic import (
    CyclicSymmetry,
    cyclic_symmetry,
    first_sector,
    reduced_step,
    state_on_orbit,
    whole_period,
)
from .extremes import orbit_extremes, state_at


class ConvergenceError(SimulationError):
    """Newton's iteration for a periodic orbit (or a continuation step) did not converge."""


#: The residual a periodic orbit is solved to: max |φ(y) − y| over the state scale.
ORBIT_TOLERANCE = 1e-10
#: Newton steps before giving up, and the halvings of one step while it does not lower
#: the residual.
NEWTON_ITERATIONS = 30
HALVINGS = 12
#: Switches this close to an orbit's start or end [periods] do not count in its
#: ``switches``.
EDGE = 1e-8
#: Modulus above which a multiplier makes an orbit unstable: 1 beyond the accuracy of M.
UNIT_CIRCLE = 1.0 + 1e-7


@dataclass(frozen=True)
class PeriodicOrbit:
    """A periodic orbit of a forced scene, of ``periods`` excitation periods.

    ``initial``: (x0 [m], ẋ0 [m/s]) at t = 0 mod T_e, by blade position (with
    substructures, every node's own degrees of freedom q and their rates, stacked in
    ``Scene.blades`` order: the orbit's first sample, ``Simulation.state(0)``), and with
    elastic contacts their springs' stretches u0 [m] (``Simulation.stretches``).
    ``monodromy``: ∂φ/∂y at ``state``, rows and columns as ``state``'s (``monodromy``).
    ``multipliers``: the Floquet multipliers (eigenvalues of ``monodromy``), complex, by
    descending modulus; a stick phase gives zeros. ``residual``: max |φ(y) − y| over
    ``scale``, the state scale Newton weighs by (velocities count divided by l Ω): [m] for
    blades; with substructures, of their modal coordinates (``model.lowering``), each of
    which a static load moves alike. ``events``: the switches over one orbit, in
    order. Per response (``Scene.responses``: a blade's x, or a component of a point):
    ``maximum`` and ``minimum`` [m], its extremes over the orbit, located where its
    velocity crosses zero to the integrator's accuracy (``extremes``), not at samples;
    ``peak`` = max |x| [m], the larger of |maximum| and |minimum| (a preload's static
    deflection included); ``mean`` [m], its average over the orbit; ``mean_square``:
    E_ρ = ∫x² dt / (k T_e) [m²] (paper §3.2). ``amplitude`` is half the peak-to-peak.
    ``energy_per_cycle``: the work of the excitation and the losses per excitation period
    (``cycle.EnergyPerCycle``); ``kinetic_peak``: the largest kinetic energy T_max [J]
    over the orbit; ``equivalent_damping``: ζ_eq = W_d / (4π T_max) (``cycle``).
    ``singular``: switches on the orbit where the map is not differentiable (grazing, or
    several independent interfaces at once); where there are any, the monodromy matrix and
    the multipliers are not to be trusted, and neither is ``stable``. ``history``: one
    orbit's ``Simulation``, when asked for.
    """

    scene: Scene
    initial: tuple[np.ndarray, ...]
    periods: int
    multipliers: np.ndarray
    monodromy: np.ndarray
    residual: float
    scale: float
    iterations: int
    events: EventLog
    peak: np.ndarray
    mean_square: np.ndarray
    maximum: np.ndarray
    minimum: np.ndarray
    mean: np.ndarray
    energy_per_cycle: EnergyPerCycle
    kinetic_peak: float
    singular: int
    history: Simulation | None = None

    def __post_init__(self):
        check_record(self)

    @property
    def stable(self) -> bool:
        """Whether every multiplier lies inside the unit circle (see ``singular``)."""
        return bool(np.abs(self.multipliers[0]) < UNIT_CIRCLE)

    @property
    def state(self) -> np.ndarray:
        """y = (x0, ẋ0[, u0]) as one array."""
        return np.concatenate(self.initial)

    @property
    def wave_numbers(self) -> np.ndarray:
        """The nodal diameter of each multiplier's eigenvector (``multipliers``' order), on
        a ring or disc of sectors: the harmonic of the sector-to-sector DFT of its
        displacements and velocities (the latter over l Ω) holding most of its square
        (``linear.nodal_diameters``). A ValueError for a group without sectors."""
        sectors = self.scene.group.graph.graph.get("sectors")
        if sectors is None:
            raise ValueError("PeriodicOrbit.wave_numbers: the group has no sectors (a ring "
                             "or a disc of sectors has)")
        values, vectors = np.linalg.eig(self.monodromy)
        order = np.argsort(-np.abs(values), kind="stable")
        vectors = vectors[:, order]
        n = self.scene.arrays.n_blades  # the coordinates, the stretches left out
        per_sector = n // sectors
        shapes = np.concatenate(
            [vectors[:n].reshape(sectors, per_sector, -1),
             vectors[n:2 * n].reshape(sectors, per_sector, -1)
             / self.scene.arrays.excitation_frequency], axis=1)
        return nodal_diameters(shapes.reshape(2 * n, -1), sectors)

    @property
    def event_sequence(self) -> tuple[tuple[int, str], ...]:
        """(interface, kind) of each switch over one orbit, in order."""
        return event_sequence(self.events)

    @property
    def switches(self) -> dict[tuple[int, str], int]:
        """How many switches of each (interface, kind) one orbit makes; a switch within
        ``EDGE`` periods of the orbit's start or end (where rounding of the start may put
        it on either side) is left out."""
        period = self.scene.excitation_period
        edge = EDGE * period
        end = self.periods * period
        counts: dict[tuple[int, str], int] = {}
        for t, switch in zip(self.events.time, self.event_sequence):
            if edge < t < end - edge:
                counts[switch] = counts.get(switch, 0) + 1
        return counts

    def amplitude(self, blade) -> float:
        """The vibration amplitude [m] of ``blade`` (a name or a position; with
        substructures a point component, ``Scene.response_position``): half its
        peak-to-peak, (max x − min x)/2, without the static deflection that ``peak``
        includes."""
        j = self.scene.response_position(blade)
        return float(0.5 * (self.maximum[j] - self.minimum[j]))

    def energy_density(self, blade) -> float:
        """E_ρ [m²] of ``blade`` (as ``amplitude``) over the orbit."""
        return float(self.mean_square[self.scene.response_position(blade)])

    @property
    def equivalent_damping(self) -> float:
        """ζ_eq = W_d / (4π T_max) [-]: the damping ratio a linear oscillator would need to
        dissipate as much per cycle at this frequency and kinetic energy (``cycle``)."""
        return equivalent_damping(self.energy_per_cycle, self.kinetic_peak)

    def simulation(self, samples_per_period: int = 100) -> Simulation:
        """One orbit's ``Simulation`` (the contact forces' histories with the motion): the
        kept ``history`` if it has ``samples_per_period``, else the orbit run again."""
        if self.history is not None and self.history.samples_per_period == samples_per_period:
            return self.history
        return simulate(self.scene, self.periods, method=TANGENT_METHOD,
                        samples_per_period=samples_per_period, initial=self.initial)

    def harmonics(self, blade, order: int = 5, samples_per_period: int = 100) -> Harmonics:
        """The harmonics of ``blade`` (as ``amplitude``) up to ``order`` (``cycle``):
        r = A_0 + Σ_n A_n sin(n ω_0 t + φ_n), ω_0 = 2π/(periods T_e)."""
        run = self.simulation(samples_per_period)
        response = self.scene.response_of(run.x, blade)
        return harmonics(response, self.periods * self.scene.excitation_period, order)

    def slip_harmonics(self, interface: int, order: int = 5,
                       samples_per_period: int = 100) -> Harmonics:
        """The harmonics up to ``order`` of interface ``interface``'s tangential relative
        displacement (``Simulation.slip_displacement``: the motion of its pair of points
        along the face), as ``harmonics``."""
        run = self.simulation(samples_per_period)
        run.checked_interface(interface, "slip_harmonics")
        slip = run.slip_displacement(interface)
        return harmonics(slip, self.periods * self.scene.excitation_period, order)

    def friction_losses(self, samples_per_period: int = 100) -> np.ndarray:
        """The energy [J] each contact's friction takes per excitation period (one per
        interface, or per point pair of a patch: ``Scene.contacts``): the sum of the areas
        of its hysteresis loops (``analysis.hysteresis_loop``) over the orbit along every
        tangent direction it slides in (t₁, and t₂ of a face that slides in its plane),
        from the samples (0 where a contact has no friction). Summed over the contacts, it
        is the friction loss per cycle of ``energy_per_cycle`` to the samples' trapezoidal
        error (falling as their spacing squared), less the kinetic energy lost where a
        slipping contact sticks rigidly, which loops do not hold."""
        run = self.simulation(samples_per_period)
        planar = np.any(self.scene.arrays.slip_rows(2) != 0.0, axis=1)
        return np.array([sum(hysteresis_loop(run, (contact.interface, contact.contact), 0,
                                             direction).area_per_cycle()
                             for direction in ((1, 2) if planar[e] else (1,)))
                         if law is not None else 0.0
                         for e, (contact, law) in enumerate(zip(
                             self.scene.contacts, self.scene.arrays.friction_laws))])


#: The smallest residual Newton is asked for, relative to the state scale: a few times the
#: resolution of a float, below which the residual is rounding.
SMALLEST_TOLERANCE = 1e-14


def periodic_orbit(scene: Scene, periods: int = 1, guess=None, *,
                   method: Adaptive | Accuracy = TANGENT_METHOD, transient: int = 100,
                   tolerance: float = ORBIT_TOLERANCE,
                   event_tolerance: float = EVENT_TOLERANCE,
                   samples_per_period: int = 100, history: bool = False,
                   symmetry: str | None = None) -> PeriodicOrbit:
    """The periodic orbit of ``periods`` excitation periods nearest ``guess``, by Newton.

    Each Newton step integrates the state with its tangent flow over ``periods`` periods
    (``stroboscopic_step``) and solves (M − I) Δy = −(φ(y) − y); a step that does not
    lower the residual is halved. The orbit may be unstable: Newton finds it all the same.

    On a tuned ring forced in engine order l (``cyclic``), a period-1 orbit is solved as
    the travelling wave it is, y(t + τ) = Sᵏ y(t) with τ = gcd(l, N) T_e / N: Newton on
    the reduced map S⁻ᵏ φ_τ integrates τ, not T_e, and the monodromy M = S^{kN/g} A^{N/g}
    still holds every perturbation's multiplier, those that break the symmetry included
    (``PeriodicOrbit.wave_numbers`` names each one's nodal diameter).

    Parameters
    ----------
    scene : Scene
    periods : int
        k ≥ 1: the orbit's period is k T_e.
    guess : (x0, v0) or (x0, v0, u0), optional
        A start near the orbit [m, m/s] by blade position (with substructures, the nodes'
        own degrees of freedom, as ``simulate`` takes them), with elastic contacts'
        stretches u0 [m] (relaxed where not given). Default: the state after
        ``transient`` periods from rest. With elastic contacts the state Newton solves for
        holds their stretches too.
    method : Adaptive or Accuracy
        The accuracy of the map; the orbit is as good as the map.
    transient : int
        Periods run from rest for the default guess, ≥ 0.
    tolerance : float
        The residual max |φ(y) − y| / scale to reach, in [1e-14, 1e-3]. The scale is the
        largest of the guess's max |x|, its max |ẋ| / (l Ω) and the static deflection
        (with substructures, in their modal coordinates: ``PeriodicOrbit.scale``).
    event_tolerance : float
        As ``simulate``.
    samples_per_period : int
        Samples of the orbit for ``peak``, ``mean_square`` and ``history``.
    history : bool
        Keep the orbit's ``Simulation`` (``PeriodicOrbit.history``).
    symmetry : None, "cyclic" or "none"
        "cyclic": solve the symmetric orbit of a tuned ring forced in engine order (a
        ValueError says what breaks the symmetry where the scene has none, or where
        ``periods`` > 1); "none": shoot over whole periods; None (default): "cyclic"
        where the scene has the symmetry and ``periods`` is 1, else "none".

    Raises
    ------
    ConvergenceError
        Newton did not reach ``tolerance``: the message gives the residual and the last
        step.
    SimulationError
        As ``simulate``.
    """
    check_instance("periodic_orbit", "scene", scene, Scene, expected="a shroudnet.Scene")
    periods = check_int("periodic_orbit", "periods", periods, low=1, most=MAX_PERIODS)
    transient = check_int("periodic_orbit", "transient", transient, low=0, most=MAX_PERIODS)
    check_real("periodic_orbit", "tolerance", tolerance, low=SMALLEST_TOLERANCE, high=1e-3)
    check_instance("periodic_orbit", "method", method, (Adaptive, Accuracy),
                   expected="Adaptive(...) or Accuracy(...)")
    check_event_tolerance("periodic_orbit", event_tolerance)
    samples_per_period = check_int("periodic_orbit", "samples_per_period", samples_per_period,
                                   low=1)
    check_instance("periodic_orbit", "history", history, bool, expected="True or False")
    cyclic = symmetry_of(scene, periods, symmetry)
    starts = start_states(scene, periods, guess, transient, method, event_tolerance)

    # Where the forcing comes round in fewer sectors than the ring has (g > 1), Newton
    # solves on the states that repeat every N/g sectors, its tangent flow of 2mN/g
    # columns; one run at the orbit then gives every multiplier, its first N/g sectors'
    # tangent columns moved round the ring (``cyclic.whole_tangent``).
    repeating = cyclic is not None and cyclic.share > 1

    def step_at(z):
        if cyclic is None:
            return stroboscopic_step(scene, periods, state_parts(scene, z), method=method,
                                     event_tolerance=event_tolerance)
        return reduced_step(scene, cyclic, z, method=method,
                            event_tolerance=event_tolerance, repeating=repeating)

    for attempt, y in enumerate(starts):
        weights = state_weights(scene, y)
        if repeating:
            y, weights = cyclic.restricted(y), cyclic.restricted(weights)
        try:
            solve = newton(step_at, y, weights, tolerance)
        except ConvergenceError:
            if attempt == len(starts) - 1:
                raise
            continue
        y, step = solve.state, solve.step
        if repeating:
            y = cyclic.tiled(y)
            step = reduced_step(scene, cyclic, y, method=method,
                                event_tolerance=event_tolerance)
        if cyclic is not None:
            step = whole_period(cyclic, step)
        return orbit_at(scene, periods, y, step, solve.residual,
                        1.0 / weights[0], solve.iterations, method, event_tolerance,
                        samples_per_period, history, cyclic)


def symmetry_of(scene: Scene, periods: int, symmetry: str | None,
                owner: str = "periodic_orbit") -> CyclicSymmetry | None:
    """The ``CyclicSymmetry`` ``owner`` solves with (``symmetry`` as ``periodic_orbit``
    takes it), or None for whole periods."""
    if symmetry is not None:
        check_choice(owner, "symmetry", symmetry, ("cyclic", "none"))
    if symmetry == "none":
        return None
    if periods != 1:
        if symmetry == "cyclic":
            raise ValueError(f"{owner}: symmetry='cyclic' solves period-1 orbits (a "
                             f"travelling wave), got periods = {periods}")
        return None
    try:
        return cyclic_symmetry(scene)
    except ValueError as reason:
        if symmetry == "cyclic":
            raise ValueError(f"{owner}: symmetry='cyclic' does not hold: {reason}") from None
        return None


#: Starts taken from a transient: its closest returns after ``periods`` periods.
STARTS = 4


def start_states(scene, periods, guess, transient, method, event_tolerance) -> list:
    """Where Newton starts, by the engine's coordinates: ``guess`` (checked); or the
    ``STARTS`` stroboscopic states of the second half of a ``transient`` from rest that
    come closest to themselves after ``periods`` periods (near-returns lie near an orbit),
    closest first."""
    n = scene.arrays.n_blades
    sliders = state_size(scene) - 2 * n
    if guess is not None:
        start = start_coordinates(scene, guess, "periodic_orbit", "guess")
        return [np.concatenate(start if len(start) == 3 else start + (np.zeros(sliders),))]
    if transient == 0:
        return [np.zeros(2 * n + sliders)]
    run = simulate(scene, transient + periods, method=method, samples_per_period=1,
                   event_tolerance=event_tolerance, event_capacity=0)
    states = from_dofs(scene.arrays.layout, np.hstack([run.x, run.v, run.stretches]))
    weights = state_weights(scene, states[-1])
    half = transient // 2
    returns = np.abs(weights * (states[half + periods:] - states[half:-periods])).max(axis=1)
    return [states[half + j] for j in np.argsort(returns, kind="stable")[:STARTS]]


def state_weights(scene: Scene, y: np.ndarray) -> np.ndarray:
    """Per component of y = (x, ẋ[, u]), 1/scale: displacements (and the elastic
    contacts' stretches) over the state scale x̂ [m], velocities over x̂ l Ω; x̂ is the
    largest of max |x|, max |ẋ| / (l Ω) and the static deflection."""
    n = scene.arrays.n_blades
    frequency = scene.arrays.excitation_frequency
    scale = max(np.abs(y[:n]).max(), np.abs(y[n:2 * n]).max() / frequency,
                scene.arrays.static_deflection, 1e-12)
    return np.concatenate([np.full(n, 1.0 / scale), np.full(n, 1.0 / (scale * frequency)),
                           np.full(len(y) - 2 * n, 1.0 / scale)])


@dataclass(frozen=True)
class NewtonResult:
    state: np.ndarray
    step: StroboscopicStep
    residual: float
    iterations: int


def newton(step_at, y, weights, tolerance) -> NewtonResult:
    """Safeguarded Newton on F(y) = φ(y) − y, with ``step_at(y)`` a ``StroboscopicStep``.

    Residuals are max |w ⊙ F|. A full step that does not lower the residual is halved up
    to ``HALVINGS`` times.
    """
    step = step_at(y)
    residual = np.abs(weights * (step.end - y)).max()
    last = 0.0
    for iteration in range(NEWTON_ITERATIONS + 1):
        if residual <= tolerance:
            return NewtonResult(y, step, float(residual), iteration)
        if iteration == NEWTON_ITERATIONS:
            break
        change = least_squares(step.jacobian - np.eye(len(y)), y - step.end)
        fraction = 1.0
        for _ in range(HALVINGS + 1):
            trial = y + fraction * change
            trial_step = step_at(trial)
            trial_residual = np.abs(weights * (trial_step.end - trial)).max()
            if trial_residual < residual:
                break
            fraction /= 2.0
        else:
            last = np.abs(weights * change).max()
            largest = np.abs(np.linalg.eigvals(step.jacobian)).max()
            advice = (f"The largest multiplier there is {largest:.3g}: the map amplifies "
                      f"its own integration error by that much, so a residual this small "
                      f"asks for a tighter method (a smaller rtol) or a looser tolerance."
                      if residual < 1e3 * tolerance else
                      "Start nearer the orbit (guess=), or from a longer transient.")
            raise ConvergenceError(
                f"periodic orbit: Newton's step does not lower the residual "
                f"{residual:.3g} (of the state scale) even when halved {HALVINGS} times; "
                f"the last full step was {last:.3g} of the state scale. {advice}")
        last = fraction * np.abs(weights * change).max()
        y, step, residual = trial, trial_step, trial_residual
    raise ConvergenceError(
        f"periodic orbit: Newton did not converge in {NEWTON_ITERATIONS} steps: the "
        f"residual is {residual:.3g} of the state scale (asked: {tolerance:.3g}), the last "
        f"step {last:.3g}. Start nearer the orbit (guess=), or loosen the tolerance.")


def least_squares(matrix, right):
    """The least-norm solution of ``matrix`` z = ``right``: where the orbit is one of a
    family (a blade stuck to a fixed node may stick anywhere within its friction limit, a
    multiplier +1), Newton moves across the family as little as it can."""
    return np.linalg.lstsq(matrix, right, rcond=None)[0]


def orbit_at(scene, periods, y, step, residual, scale, iterations, method, event_tolerance,
             samples_per_period, history, cyclic=None) -> PeriodicOrbit:
    """The ``PeriodicOrbit`` through y, whose map was ``step`` (both by the engine's
    coordinates; the orbit's ``initial`` and ``monodromy`` by the nodes' degrees of
    freedom): its multipliers, and what one sampled run of the orbit shows. On a
    symmetric orbit (``cyclic``), every sector repeats the first one's motion a
    sector-passing time later: the first sector's extremes are every sector's."""
    multipliers = np.linalg.eigvals(step.jacobian).astype(complex)
    multipliers = multipliers[np.argsort(-np.abs(multipliers), kind="stable")]
    layout = scene.arrays.layout
    start = state_parts(scene, y)
    initial = tuple(np.array(part) for part in state_parts(scene, to_dofs(layout, y)))
    run = simulate(scene, periods, method=method, samples_per_period=samples_per_period,
                   event_tolerance=event_tolerance, initial=initial)
    if cyclic is None:
        def exact(time):
            return state_at(scene, start, time, run.settings.method, event_tolerance)
    else:
        exact = state_on_orbit(cyclic, scene, start, method=run.settings.method,
                               event_tolerance=event_tolerance)

    def state(time):
        """(x, ẋ) of the orbit at ``time`` [s], as ``run`` holds them."""
        return tuple(to_dofs(layout, part) for part in exact(time))

    found = orbit_extremes(scene, run.t, run.x, run.v, run.events.time, state,
                           responses=None if cyclic is None else first_sector(cyclic))
    maximum, minimum = found.maximum, found.minimum
    if cyclic is not None:
        maximum, minimum = np.tile(maximum, cyclic.sectors), np.tile(minimum, cyclic.sectors)
    responses = scene.responses_of(run.x[:-1])
    return PeriodicOrbit(scene=scene, initial=initial, periods=periods,
                         multipliers=multipliers,
                         monodromy=jacobian_in_dofs(scene, step.jacobian),
                         residual=float(residual), scale=float(scale),
                         iterations=iterations, events=run.events,
                         peak=np.maximum(np.abs(maximum), np.abs(minimum)),
                         mean_square=np.mean(responses ** 2, axis=0),
                         maximum=maximum, minimum=minimum,
                         mean=np.mean(responses, axis=0),
                         energy_per_cycle=energy_per_cycle(run, periods),
                         kinetic_peak=kinetic_peak(scene, run, state),
                         singular=step.singular, history=run if history else None)


def event_sequence(events: EventLog) -> tuple[tuple[int, str], ...]:
    """(interface, kind) of each logged switch, in order."""
    return tuple((int(e), EventKind(k).name.lower())
                 for e, k in zip(events.interface, events.kind))
