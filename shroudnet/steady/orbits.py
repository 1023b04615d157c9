"""Periodic orbits by shooting: Newton on the stroboscopic map with its exact Jacobian.

A forced orbit of period k T_e is a fixed point of the k-period stroboscopic map φ:
F(y) = φ(y) − y = 0 with y = (x, ẋ) at t = 0 mod T_e (DESIGN §6). Newton's step solves
(M − I) Δy = −F, with M = ∂φ/∂y the monodromy matrix that the tangent flow gives through
every switch (``stability``); the Floquet multipliers are M's eigenvalues at the orbit.

The map is a ``stroboscopic.StroboscopicMap``, and Newton's linear systems are solved in
one of two ways (``periodic_orbit``'s ``jacobian``): "dense" forms M, one tangent column
per state variable carried through the period; "krylov" solves (M − I) Δy = −F by GMRES
on Jacobian–vector products, each one tangent column through the period (``krylov``), and
finds the leading multipliers by Arnoldi on the same products (DESIGN §8: Newton–Krylov
shooting, Lust, Roose, Spence & Champneys 1998). A contact stuck through the whole orbit
leaves its offset free (``neutral``): the offset is pinned, and its multiplier 1 left
out of the stability test.
"""

from __future__ import annotations

import dataclasses
from collections.abc import Iterator
from dataclasses import dataclass

import numpy as np

from contact_laws import check_choice, check_instance, check_int, check_real

from ..analysis.readings import hysteresis_loop
from ..analysis.stability import TANGENT_METHOD, jacobian_in_dofs, state_parts, state_size
from ..checked_records import check_record
from ..engine.codes import EventKind
from ..linear.modes import nodal_diameters
from ..model.lowering import from_dofs, to_dofs
from ..model.scene import Scene
from ..run.methods import (EVENT_TOLERANCE, SMALLEST_EVENT_TOLERANCE, Accuracy, Adaptive,
                           Exponential, check_event_tolerance)
from ..run.simulate import MAX_PERIODS, simulate, start_coordinates
from ..run.simulation import EventLog, Simulation, SimulationError
from .cycle import (
    EnergyPerCycle,
    Harmonics,
    OrbitReadings,
    energy_per_cycle,
    harmonics,
    kinetic_peak,
)
from .cyclic import first_sector, symmetry_of
from .extremes import orbit_extremes
from .krylov import gmres, leading_eigenvalues
from .neutral import pin_rows, tested
from .stroboscopic import MapValue, StroboscopicMap


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
#: A Newton whose step no longer lowers a residual within this many times the tolerance
#: has met the map's own integration noise (the map amplifies its error by up to
#: 1/|1 − μ|): it tightens the integration once (``TIGHTENING``), and where it stalls
#: again, the orbit is returned with the residual it reached.
NOISE_FLOOR = 10.0
#: The factor the tolerances of a map at its noise floor are tightened by, once.
TIGHTENING = 0.01
#: How many multipliers Arnoldi finds (``jacobian="krylov"``), beyond the neutral ones:
#: the largest in modulus, those that decide stability and that the continuation's
#: bifurcation tests follow.
LEADING = 10
#: The Ritz residual (over ‖M‖, in the scaled coordinates of ``state_weights``) below
#: which Arnoldi's multipliers count as found: their error is about this times their
#: condition number, 1–10 on the orbits measured.
ARNOLDI_TOLERANCE = 1e-11
#: The jacobian= choices, and the state size from which "krylov" is the default on a
#: scene of substructures whose phases are not all linear (``front.bench``, section 11,
#: one core, an orbit with its stability from a settled guess). On the six eight-mode
#: blades with 3-D elastic faces (106 state variables) a run of all 106 columns took 71
#: times one column's, GMRES 17 products and Arnoldi 45: 3.6 s by Krylov against 9.1 s
#: dense. On the six three-mode blades with those faces (46), all columns took 21 times
#: one: 0.91 s by Krylov against 0.73 s dense; on a pair of eight-mode blades (34), 0.58 s
#: against 0.69 s. Where every phase is linear the tangent rides each phase's exponential
#: and a column costs next to nothing (96 columns 0.06 s against one 0.04 s): dense is 6
#: times faster there (0.41 s against 2.6 s), and the default.
JACOBIANS = ("dense", "krylov")
KRYLOV_SIZE = 80


@dataclass(frozen=True)
class ShootingWork:
    """How an orbit was solved, and what its runs cost (``stroboscopic.MapWork``):
    ``jacobian`` ("dense" or "krylov"), ``newton_steps``, ``krylov_iterations`` (the
    Jacobian–vector products GMRES took, over all Newton steps) and
    ``arnoldi_products`` (those the leading multipliers took); ``runs``, ``columns`` and
    ``seconds`` by kind of run: "state" (φ alone), "products" (tangent columns),
    "dense" (the whole monodromy), "outputs" (the orbit's run and its extremes)."""

    jacobian: str
    newton_steps: int
    krylov_iterations: int
    arnoldi_products: int
    runs: dict
    columns: dict
    seconds: dict

    @property
    def total_seconds(self) -> float:
        return float(sum(self.seconds.values()))


@dataclass(frozen=True)
class PeriodicOrbit(OrbitReadings):
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

    Solved with ``jacobian="krylov"``, ``multipliers`` holds the leading ones Arnoldi
    found (``LEADING`` beyond the neutral ones), ``monodromy`` is None and
    ``monodromy_matrix()`` forms it on request; solved with ``stability=False``, both
    are empty (``multipliers`` of length 0, ``monodromy`` None). ``neutral``: the
    interfaces stuck through the whole orbit, whose frozen offsets (``neutral``: their
    ``neutral_directions`` in all) were pinned at the start's values: the orbit is one of
    a family, and the multipliers 1 of the family's directions are left out of
    ``stable`` (``tested_multipliers``). ``notes``: what the solver did beyond Newton
    from the start (a fallback to a transient, an integration tightened at the map's
    noise floor). ``work``: how it was solved and what that cost (``ShootingWork``).
    """

    scene: Scene
    initial: tuple[np.ndarray, ...]
    periods: int
    multipliers: np.ndarray
    monodromy: np.ndarray | None
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
    neutral: tuple[int, ...] = ()
    neutral_directions: int = 0
    notes: tuple[str, ...] = ()
    work: ShootingWork | None = None
    stroboscopic: StroboscopicMap | None = None

    def __post_init__(self):
        check_record(self)

    @property
    def tested_multipliers(self) -> np.ndarray:
        """``multipliers`` less those of the neutral family's directions (``neutral``):
        the ones stability and the bifurcation tests look at."""
        return tested(self.multipliers, self.neutral_directions)

    @property
    def stable(self) -> bool:
        """Whether every multiplier lies inside the unit circle (see ``singular``; the
        neutral directions' left out). A ValueError for an orbit solved without its
        stability."""
        multipliers = self.tested_multipliers
        if len(multipliers) == 0 and len(self.multipliers) == 0:
            raise ValueError("PeriodicOrbit.stable: the orbit was solved with "
                             "stability=False, without its multipliers")
        return bool(len(multipliers) == 0 or np.abs(multipliers[0]) < UNIT_CIRCLE)

    def monodromy_matrix(self) -> np.ndarray:
        """The monodromy matrix over the whole orbit: ``monodromy`` where it was formed,
        else formed now from the orbit's start (one run of every tangent column). A
        ValueError for an orbit read from a file without it."""
        if self.monodromy is not None:
            return self.monodromy
        if self.stroboscopic is None:
            raise ValueError("PeriodicOrbit.monodromy_matrix: this orbit keeps neither its "
                             "monodromy matrix nor the map to form it")
        found = self.stroboscopic
        if found.repeating:
            found = found.whole_ring()
        y = from_dofs(self.scene.arrays.layout, self.state)
        return jacobian_in_dofs(self.scene, found.whole(found.dense(y)).jacobian)

    @property
    def state(self) -> np.ndarray:
        """y = (x0, ẋ0[, u0]) as one array."""
        return np.concatenate(self.initial)

    def completed(self) -> PeriodicOrbit:
        """This orbit with its whole monodromy matrix and all its multipliers: itself
        where it holds them, else with them formed now (``monodromy_matrix``)."""
        if self.monodromy is not None and len(self.multipliers) == len(self.monodromy):
            return self
        matrix = self.monodromy_matrix()
        values = np.linalg.eigvals(matrix).astype(complex)
        return dataclasses.replace(self, monodromy=matrix, multipliers=values[
            np.argsort(-np.abs(values), kind="stable")])

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
        values, vectors = np.linalg.eig(self.monodromy_matrix())
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

    def simulation(self, samples_per_period: int = 100) -> Simulation:
        """One orbit's ``Simulation`` (the contact forces' histories with the motion): the
        kept ``history`` if it has ``samples_per_period``, else the orbit run again."""
        if self.history is not None and self.history.samples_per_period == samples_per_period:
            return self.history
        if self.stroboscopic is not None:
            return self.stroboscopic.sampled(
                from_dofs(self.scene.arrays.layout, self.state), samples_per_period)
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
                   method: Adaptive | Accuracy | Exponential = TANGENT_METHOD,
                   transient: int = 100, tolerance: float = ORBIT_TOLERANCE,
                   event_tolerance: float = EVENT_TOLERANCE,
                   samples_per_period: int = 100, history: bool = False,
                   symmetry: str | None = None, jacobian: str | None = None,
                   stability: bool = True) -> PeriodicOrbit:
    """The periodic orbit of ``periods`` excitation periods nearest ``guess``, by Newton.

    Each Newton step solves (M − I) Δy = −(φ(y) − y) at the iterate, M the monodromy
    (``jacobian``); a step that does not lower the residual is halved. The orbit may be
    unstable: Newton finds it all the same. Where Newton from ``guess`` fails, it is
    tried again from a transient (``transient`` periods from rest), and the orbit says so
    (``PeriodicOrbit.notes``). Where its steps stall within ``NOISE_FLOOR`` times the
    tolerance (the map's own integration noise), the integration is tightened once
    (``TIGHTENING``), and where they stall again, the orbit is returned with the residual
    it reached (``residual``, ``notes``).

    A contact stuck through the whole orbit leaves its offset free (``neutral``): the
    offset keeps its value in the start, and its multiplier 1 is left out of ``stable``.

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
    method : Adaptive, Accuracy or Exponential
        The accuracy of the map; the orbit is as good as the map. ``Exponential()``
        propagates each phase exactly, with its tangent e^{JΔt} (scenes whose phases are
        linear: ``simulate``).
    transient : int
        Periods run from rest for the default guess (and where Newton from ``guess``
        fails), ≥ 0.
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
    jacobian : None, "dense" or "krylov"
        How Newton's linear systems are solved: "dense" forms M (a run of every tangent
        column); "krylov" solves them by GMRES on Jacobian–vector products (a run of one
        tangent column each) and finds the ``LEADING`` multipliers by Arnoldi on the same
        products. None (default): "krylov" from ``KRYLOV_SIZE`` state variables on for
        substructures whose phases are not all linear, else "dense" (``KRYLOV_SIZE``'s
        measurements).
    stability : bool
        Compute the multipliers (True, default), or skip them (the orbit's
        ``multipliers`` empty, ``stable`` a ValueError).

    Raises
    ------
    ConvergenceError
        Newton did not reach ``tolerance`` from any start: the message gives the residual
        and the last step.
    SimulationError
        As ``simulate``.
    """
    check_instance("periodic_orbit", "scene", scene, Scene, expected="a shroudnet.Scene")
    periods = check_int("periodic_orbit", "periods", periods, low=1, most=MAX_PERIODS)
    transient = check_int("periodic_orbit", "transient", transient, low=0, most=MAX_PERIODS)
    check_real("periodic_orbit", "tolerance", tolerance, low=SMALLEST_TOLERANCE, high=1e-3)
    check_instance("periodic_orbit", "method", method, (Adaptive, Accuracy, Exponential),
                   expected="Adaptive(...), Accuracy(...) or Exponential(...)")
    check_event_tolerance("periodic_orbit", event_tolerance)
    samples_per_period = check_int("periodic_orbit", "samples_per_period", samples_per_period,
                                   low=1)
    check_instance("periodic_orbit", "history", history, bool, expected="True or False")
    check_instance("periodic_orbit", "stability", stability, bool, expected="True or False")
    cyclic = symmetry_of(scene, periods, symmetry)
    # Where the forcing comes round in fewer sectors than the ring has (g > 1), Newton
    # solves on the states that repeat every N/g sectors, its tangent flow of 2mN/g
    # columns; one run at the orbit then gives every multiplier, its first N/g sectors'
    # tangent columns moved round the ring (``cyclic.whole_tangent``).
    repeating = cyclic is not None and cyclic.share > 1
    stroboscopic = StroboscopicMap(scene=scene, periods=periods, method=method,
                                   event_tolerance=event_tolerance, cyclic=cyclic,
                                   repeating=repeating)
    kind = jacobian_kind("periodic_orbit", jacobian, stroboscopic)
    failures = []
    for origin, y in start_states(scene, periods, guess, transient, method, event_tolerance):
        weights = state_weights(scene, y)
        if repeating:
            y, weights = cyclic.restricted(y), cyclic.restricted(weights)
        try:
            solve = newton(stroboscopic, y, weights, tolerance, kind)
        except ConvergenceError as error:
            failures.append((origin, error))
            continue
        notes = [f"Newton from the {failures[0][0]} did not converge ({failures[0][1]}); "
                 f"the orbit was solved from {origin}"] if failures else []
        y, found = solve.state, solve.map
        if repeating:
            y, found = cyclic.tiled(y), found.whole_ring()
        return orbit_at(scene, periods, y, solve.value, solve.residual, 1.0 / weights[0],
                        solve.iterations, found, samples_per_period, history,
                        stability=stability, jacobian=kind, weights=_whole(cyclic, weights),
                        krylov_iterations=solve.krylov_iterations,
                        notes=tuple(notes) + solve.notes)
    raise failures[-1][1]


def jacobian_kind(owner: str, jacobian: str | None, stroboscopic: StroboscopicMap) -> str:
    """``jacobian`` checked, or the default for ``stroboscopic``: "krylov" from
    ``KRYLOV_SIZE`` state variables on for a scene of substructures whose phases are not
    all linear (as measured there), else "dense" (scenes of ``Blade``s keep it: their
    tangent is not measured to pay for products)."""
    if jacobian is None:
        arrays = stroboscopic.scene.arrays
        krylov = stroboscopic.size >= KRYLOV_SIZE and arrays.is_structure \
            and not arrays.linear_phases
        return "krylov" if krylov else "dense"
    check_choice(owner, "jacobian", jacobian, JACOBIANS)
    return jacobian


def _whole(cyclic, weights):
    """The weights of the whole ring's states, from those of its repeating ones."""
    if cyclic is None or len(weights) == 2 * cyclic.sectors * cyclic.per_sector:
        return weights
    return cyclic.tiled(weights)


#: Starts taken from a transient: its closest returns after ``periods`` periods.
STARTS = 4


def start_states(scene, periods, guess, transient, method, event_tolerance
                 ) -> Iterator[tuple[str, np.ndarray]]:
    """Where Newton starts, by the engine's coordinates, each with where it comes from:
    ``guess`` (checked), and then (or without a guess, only) the ``STARTS`` stroboscopic
    states of the second half of a ``transient`` from rest that come closest to
    themselves after ``periods`` periods (near-returns lie near an orbit), closest first;
    the transient is run only when Newton needs it."""
    n = scene.arrays.n_blades
    sliders = state_size(scene) - 2 * n
    if guess is not None:
        start = start_coordinates(scene, guess, "periodic_orbit", "guess")
        yield "guess", np.concatenate(start if len(start) == 3
                                      else start + (np.zeros(sliders),))
    if transient == 0:
        if guess is None:
            yield "rest", np.zeros(2 * n + sliders)
        return
    run = simulate(scene, transient + periods, method=method, samples_per_period=1,
                   event_tolerance=event_tolerance, event_capacity=0)
    states = from_dofs(scene.arrays.layout, np.hstack([run.x, run.v, run.stretches]))
    weights = state_weights(scene, states[-1])
    half = transient // 2
    returns = np.abs(weights * (states[half + periods:] - states[half:-periods])).max(axis=1)
    for j in np.argsort(returns, kind="stable")[:STARTS]:
        yield f"a transient of {transient} periods", states[half + j]


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
    """Where Newton stopped: the ``state``, the map's ``value`` there (its Jacobian where
    it was formed there), the ``residual`` reached, the Newton steps and the GMRES
    products they took, the map it converged on (``map``: tightened at the noise floor,
    or the one it was given), and ``notes`` on what it did beyond Newton."""

    state: np.ndarray
    value: MapValue
    residual: float
    iterations: int
    krylov_iterations: int
    map: StroboscopicMap
    notes: tuple[str, ...]


def newton(stroboscopic: StroboscopicMap, y, weights, tolerance, jacobian="dense"
           ) -> NewtonResult:
    """Safeguarded Newton on F(y) = φ(y) − y (``stroboscopic``), the offsets of the
    contacts stuck through the whole orbit pinned at their values in the start
    (``neutral``).

    Residuals are max |w ⊙ F|. Newton's matrix M − I is formed (``jacobian`` "dense")
    or known by its products (``newton_step``); a dense one is formed at each accepted
    iterate that has not converged (so that the last step is a full Newton step, and
    lands far below the tolerance). A step that does not lower the residual is halved up
    to ``HALVINGS`` times, its trials runs of the state alone; one that still does not,
    within ``NOISE_FLOOR`` times the tolerance, tightens the map once (``TIGHTENING``),
    and past that returns what it reached.
    """
    start = y
    notes = []
    dense = jacobian == "dense"
    # The residuals are all the state's runs': a run that carries tangent columns takes
    # other adaptive steps, and its φ differs at the integrator's error (1e-9 at rtol
    # 1e-10), beyond the tolerance: its Jacobian is Newton's matrix, not its φ.
    value = stroboscopic.value(y)
    linear = stroboscopic.dense(y) if dense else value
    residual = np.abs(weights * (value.end - y)).max()
    last, krylov, tightened = 0.0, 0, False
    for iteration in range(NEWTON_ITERATIONS + 1):
        if residual <= tolerance:
            return NewtonResult(y, value, float(residual), iteration, krylov, stroboscopic,
                                tuple(notes))
        if iteration == NEWTON_ITERATIONS:
            break
        rows = pins(stroboscopic, value)
        change, products = newton_step(stroboscopic, linear, value, weights, rows, start,
                                       residual, tolerance)
        krylov += products
        trial, trial_value, trial_residual = line_search(stroboscopic, y, change, weights,
                                                         residual)
        if trial is None:
            if residual <= NOISE_FLOOR * tolerance:
                if tightened:
                    notes.append(f"Newton stalled at the map's noise floor again: the "
                                 f"residual reached is {residual:.3g} of the state scale "
                                 f"(asked: {tolerance:.3g})")
                    return NewtonResult(y, value, float(residual), iteration, krylov,
                                        stroboscopic, tuple(notes))
                stroboscopic = stroboscopic.with_method(tighter(stroboscopic.method))
                stroboscopic = dataclasses.replace(
                    stroboscopic, event_tolerance=max(TIGHTENING * stroboscopic.event_tolerance,
                                                      SMALLEST_EVENT_TOLERANCE))
                tightened = True
                notes.append(f"Newton stalled at the map's noise floor (residual "
                             f"{residual:.3g} of the state scale, asked {tolerance:.3g}): the "
                             f"integration was tightened to {describe(stroboscopic)}")
                value = stroboscopic.value(y)
                linear = stroboscopic.dense(y) if dense else value
                residual = np.abs(weights * (value.end - y)).max()
                continue
            raise stall_error(residual, tolerance, np.abs(weights * change).max(), linear,
                              weights)
        last = np.abs(weights * (trial - y)).max()
        y, residual, value = trial, trial_residual, trial_value
        linear = stroboscopic.dense(y) if dense and residual > tolerance else value
    raise ConvergenceError(
        f"periodic orbit: Newton did not converge in {NEWTON_ITERATIONS} steps: the "
        f"residual is {residual:.3g} of the state scale (asked: {tolerance:.3g}), the last "
        f"step {last:.3g}. Start nearer the orbit (guess=), or loosen the tolerance.")


def line_search(stroboscopic, y, change, weights, residual):
    """The first of y + change, y + change/2, … (``HALVINGS`` halvings) whose residual
    is below ``residual``: (trial, its map value, its residual), or (None, None, None)."""
    fraction = 1.0
    for _ in range(HALVINGS + 1):
        trial = y + fraction * change
        trial_value = stroboscopic.value(trial)
        trial_residual = np.abs(weights * (trial_value.end - trial)).max()
        if trial_residual < residual:
            return trial, trial_value, trial_residual
        fraction /= 2.0
    return None, None, None


def stall_error(residual, tolerance, last, value, weights) -> ConvergenceError:
    """The error of a Newton whose halved steps no longer lower the residual."""
    if residual < 1e3 * tolerance and value.columns is not None \
            and value.columns.shape[1] == len(weights):
        largest = np.abs(np.linalg.eigvals(value.columns)).max()
        advice = (f"The largest multiplier there is {largest:.3g}: the map amplifies its "
                  f"own integration error by that much, so a residual this small asks for "
                  f"a tighter method (a smaller rtol) or a looser tolerance.")
    elif residual < 1e3 * tolerance:
        advice = ("The map amplifies its own integration error: a residual this small "
                  "asks for a tighter method (a smaller rtol) or a looser tolerance.")
    else:
        advice = "Start nearer the orbit (guess=), or from a longer transient."
    return ConvergenceError(
        f"periodic orbit: Newton's step does not lower the residual {residual:.3g} (of the "
        f"state scale) even when halved {HALVINGS} times; the last full step was "
        f"{last:.3g} of the state scale. {advice}")


def tighter(method):
    """``method`` with its tolerances ``TIGHTENING`` times smaller (an ``Accuracy``
    resolved to its ``Adaptive`` settings first; ``Exponential`` has none but its event
    tolerance's)."""
    if isinstance(method, Exponential):
        return method
    if isinstance(method, Accuracy):
        method = Adaptive(rtol=method.target / 100.0)
    rtol = max(TIGHTENING * method.rtol, 1e-14)
    atol = None if method.atol is None else TIGHTENING * method.atol
    return dataclasses.replace(method, rtol=rtol, atol=atol)


def describe(stroboscopic) -> str:
    """The accuracy of a map, in words."""
    method = stroboscopic.method
    what = f"rtol {method.rtol:.3g}, " if isinstance(method, Adaptive) else ""
    return f"{what}event tolerance {stroboscopic.event_tolerance:.3g} periods"


def pins(stroboscopic, value) -> np.ndarray:
    """The rows c of the offsets of the contacts that ``value``'s run kept stuck all
    through (``neutral.pin_rows``), in the map's coordinates: none on a symmetric ring's
    reduced map, whose contacts' offsets repeat round it."""
    if stroboscopic.cyclic is not None:
        return np.zeros((0, stroboscopic.size))
    return pin_rows(stroboscopic.scene, value.stuck)[1]


def newton_step(stroboscopic, linear, value, weights, rows, start, residual, tolerance):
    """Newton's change Δy at ``value``'s start y: (M − I) Δy = −(φ(y) − y) with the pins
    c · (y + Δy) = c · y_start (``rows`` c, ``start``), in the scaled coordinates
    z = w ⊙ y; M the Jacobian of ``linear`` (dense) or M's products at y (``linear`` is
    None or carries no Jacobian): GMRES on the bordered system [[M − I, Cᵀ], [C, 0]],
    to a residual ``forcing`` ‖F‖, its products as loose as that allows
    (``StroboscopicMap.for_solve``). Returns (Δy, the products GMRES took)."""
    y = value.start
    size = len(y)
    right = np.concatenate([-weights * (value.end - y), rows @ (start - y)])
    scaled = rows / weights[None, :]
    if linear.columns is not None and linear.columns.shape[1] == size:
        matrix = weights[:, None] * (linear.columns - np.eye(size)) / weights[None, :]
        change = least_squares(np.vstack([matrix, scaled]), right)
        return change / weights, 0
    m = len(rows)
    relative = forcing(residual, tolerance)
    loose = stroboscopic.for_solve(relative)

    def product(u):
        z, pin = u[:size], u[size:]
        tangent = loose.products(y, z / weights).columns[:, 0]
        return np.concatenate([weights * tangent - z + scaled.T @ pin, scaled @ z])

    solved = gmres(product, right, tolerance=relative, most=size + m)
    return solved.x[:size] / weights, solved.iterations


#: The relative residual GMRES is asked for, between these bounds: small enough that the
#: step lands within a tenth of the tolerance where the map is nearly linear.
LOOSEST_FORCING, TIGHTEST_FORCING = 0.1, 1e-8


def forcing(residual: float, tolerance: float) -> float:
    """The relative residual of Newton's linear solve by GMRES at a Newton ``residual``:
    0.1 tolerance/residual, within [``TIGHTEST_FORCING``, ``LOOSEST_FORCING``] (an
    inexact Newton that stops solving before the linear model is better than the map)."""
    return min(LOOSEST_FORCING, max(TIGHTEST_FORCING, 0.1 * tolerance / residual))


def least_squares(matrix, right):
    """The least-norm solution of ``matrix`` z = ``right``: where the orbit is one of a
    family not pinned (``neutral``), Newton moves across the family as little as it
    can."""
    return np.linalg.lstsq(matrix, right, rcond=None)[0]


@dataclass(frozen=True)
class Stability:
    """The multipliers of an orbit, by descending modulus (all of them, or the leading
    ones), the monodromy matrix where it was formed, the singular switches met, and the
    products Arnoldi took."""

    multipliers: np.ndarray
    monodromy: np.ndarray | None
    singular: int
    products: int


def stability_of(stroboscopic: StroboscopicMap, y, value: MapValue, weights, jacobian: str,
                 neutral: int) -> Stability:
    """The multipliers of the orbit through y: the eigenvalues of the monodromy M over the
    whole orbit (``jacobian`` "dense", or on a symmetric ring: formed from its reduced
    map), or the ``LEADING`` + ``neutral`` of largest modulus by Arnoldi on the products
    w ⊙ M (v / w) (``krylov.leading_eigenvalues``)."""
    if jacobian == "dense" or stroboscopic.cyclic is not None:
        if value.columns is None or value.columns.shape[1] != len(y):
            value = stroboscopic.dense(y)
        whole = stroboscopic.whole(value)
        multipliers = np.linalg.eigvals(whole.jacobian).astype(complex)
        order = np.argsort(-np.abs(multipliers), kind="stable")
        return Stability(multipliers[order], whole.jacobian, whole.singular, 0)
    singular = []

    def product(u):
        found = stroboscopic.products(y, u / weights)
        singular.append(found.singular)
        return weights * found.columns[:, 0]

    start = np.random.default_rng(len(y)).standard_normal(len(y))
    pairs = leading_eigenvalues(product, start, count=LEADING + neutral,
                                tolerance=ARNOLDI_TOLERANCE)
    return Stability(pairs.values.astype(complex), None, max(singular, default=0),
                     pairs.products)


def orbit_at(scene, periods, y, value, residual, scale, iterations, stroboscopic,
             samples_per_period, history, *, stability=True, jacobian="dense",
             weights=None, krylov_iterations=0, notes=()) -> PeriodicOrbit:
    """The ``PeriodicOrbit`` through y, whose map value there was ``value``
    (``stroboscopic``'s): its multipliers (``stability_of``, unless not asked for), and
    what one sampled run of the orbit shows. On a symmetric orbit (the map's
    ``cyclic``), every sector repeats the first one's motion a sector-passing time later:
    the first sector's extremes are every sector's."""
    cyclic = stroboscopic.cyclic
    if weights is None:
        weights = state_weights(scene, y)
    neutral, rows = ((), np.zeros((0, len(y)))) if cyclic is not None else pin_rows(
        scene, value.stuck)
    if stability:
        found = stability_of(stroboscopic, y, value, weights, jacobian, len(rows))
    else:
        found = Stability(np.zeros(0, dtype=complex), None, value.singular, 0)
    initial = tuple(np.array(part) for part in state_parts(scene, to_dofs(scene.arrays.layout,
                                                                          y)))
    run = stroboscopic.sampled(y, samples_per_period)
    state = stroboscopic.state_function(y)
    extremes = orbit_extremes(scene, run.t, run.x, run.v, run.events.time, state,
                              responses=None if cyclic is None else first_sector(cyclic),
                              states=stroboscopic.states_at(y))
    maximum, minimum = extremes.maximum, extremes.minimum
    if cyclic is not None:
        maximum, minimum = np.tile(maximum, cyclic.sectors), np.tile(minimum, cyclic.sectors)
    responses = scene.responses_of(run.x[:-1])
    kinetic = kinetic_peak(scene, run, state)
    work = stroboscopic.work
    return PeriodicOrbit(scene=scene, initial=initial, periods=periods,
                         multipliers=found.multipliers,
                         monodromy=None if found.monodromy is None
                         else jacobian_in_dofs(scene, found.monodromy),
                         residual=float(residual), scale=float(scale),
                         iterations=iterations, events=run.events,
                         peak=np.maximum(np.abs(maximum), np.abs(minimum)),
                         mean_square=np.mean(responses ** 2, axis=0),
                         maximum=maximum, minimum=minimum,
                         mean=np.mean(responses, axis=0),
                         energy_per_cycle=energy_per_cycle(run, periods),
                         kinetic_peak=kinetic, singular=found.singular,
                         history=run if history else None, neutral=neutral,
                         neutral_directions=len(rows), notes=tuple(notes),
                         work=ShootingWork(jacobian=jacobian, newton_steps=iterations,
                                           krylov_iterations=krylov_iterations,
                                           arnoldi_products=found.products,
                                           runs=dict(work.runs), columns=dict(work.columns),
                                           seconds=dict(work.seconds)),
                         stroboscopic=stroboscopic)


def event_sequence(events: EventLog) -> tuple[tuple[int, str], ...]:
    """(interface, kind) of each logged switch, in order."""
    return tuple((int(e), EventKind(k).name.lower())
                 for e, k in zip(events.interface, events.kind))
