"""The stroboscopic map: all that the steady-state solvers ask of the run layer.

A periodic orbit of k excitation periods is a fixed point of y ↦ φ(y), the state
y = (x, ẋ[, u]) at t = 0 mod T_e carried k periods on (DESIGN §6). Newton, GMRES,
Arnoldi and continuation see only this object:

- ``map(y)``: φ(y), one run of the state alone;
- ``map.products(y, V)``: φ(y) and Φ V, the tangent columns V carried through the period
  with the state, multiplied by the saltation matrix of every switch (``engine.tangent``):
  one column is one Jacobian–vector product, the currency of matrix-free shooting;
- ``map.dense(y)``: φ(y) and the whole Φ (the monodromy matrix), on request;
- ``map.sampled(y, samples_per_period)``, ``map.state_function(y)`` and
  ``map.states_at(y)``: the one run of an orbit its outputs are read from, and its exact
  state at any instant, or at many from one run.

The state's own runs (φ, and the orbit's run) take a hundredth of the method's rtol and
of its event tolerance (``STATE_ACCURACY``): a run that carries tangent columns accepts a
step only where their
error is within rtol too (the largest column's), and comes out more accurate than the
state's run alone at the same rtol, whose error is an RMS over all the coordinates (a
contact's few may err √N times more) and whose φ is a discontinuous function of y at the
level of its error (its steps move with y), and of the switches' brackets (a located
switch moves within its bracket as y moves: 0.3–6 times the event tolerance on the
state, ``methods.EVENT_TOLERANCE``). On the paper's group at rtol 1e-10 the state's run
alone misses the orbit by 1.6e-9 of its scale; on the six-blade packet of 106 state
variables Newton on it stalls near 9e-10 at rtol 1e-11; on the three-mode packet with 28
switches a period, near 1.3e-10 at rtol 1e-12 while its switches are located to 1e-10
periods. The tangent's runs keep the method's tolerances: Newton's matrix needs no more,
and a state run at rtol 1e-12 costs a tenth of one with a single column at 1e-10.
Newton–Krylov's products need less still (``for_solve``): GMRES solves Newton's system
only to a relative residual r (``orbits.forcing``: 0.1 tolerance / residual), and a
product whose relative error is ε perturbs the solution by about ε/(1 − |μ|_max), so
products at rtol 1e-3 r (their error measured at about 10 rtol) leave the step as good as
exact ones. On the six eight-mode blades with 3-D elastic faces a product at rtol 1e-8
took 0.050 s against 0.106 s at 1e-10, its error 1.0e-7 of its scale against 1.4e-9;
from a settled guess (residual 1.6e-7, GMRES asked for 6.4e-5) its 17 products at rtol
6.4e-8 took 0.44 s against 0.61 s at 1e-8, and Newton's one step landed on the same
orbit (to 1.5e-15) at a residual of 8.7e-12.
An orbit's extremes are refined on the state's runs, each sampled at every instant the
refinements wait on (``states_at``).

On a tuned ring solved as its travelling wave (``cyclic``), the map is the reduced one,
G(y) = S⁻ᵏ φ_τ(y) over τ = g T_e / N, and ``whole`` turns its Jacobian into the monodromy
over T_e. Each value also says which interfaces stayed stuck through the whole run: a
contact that never slips leaves its slider's offset free (``orbits``' neutral directions).

Its states y, products and Jacobians are all by the engine's coordinates (``integrate``'s:
with substructures, modal coordinates η, ``model.lowering``); what an orbit shows a user
(``sampled``, ``state_function``) is by the nodes' own degrees of freedom q.

Every run is counted in the map's ``MapWork`` (runs, tangent columns and seconds by kind):
the breakdown of where an orbit's time goes.
"""

from __future__ import annotations

import dataclasses
import time
from dataclasses import dataclass, field

import numpy as np

from ..analysis.stability import TANGENT_METHOD, state_parts, state_size
from ..engine.codes import Mode
from ..model.lowering import to_dofs
from ..model.scene import Scene
from ..run.methods import EVENT_TOLERANCE, SMALLEST_EVENT_TOLERANCE, Accuracy, Adaptive, Exponential
from ..run.simulate import integrate, simulate
from ..run.simulation import Simulation
from .cyclic import CyclicSymmetry, reduced_step, shifted_end, state_on_orbit
from .extremes import state_at

#: The smallest rtol an adaptive run takes (``Adaptive``).
SMALLEST_RTOL = 1e-14
#: The switches a map's run logs to tell which interfaces stayed stuck; a run with more
#: (its log full) is taken to have switched them all.
EVENT_LOG = 10_000
#: The kinds of run a ``MapWork`` counts.
KINDS = ("state", "products", "dense", "outputs")
#: The state's runs take the adaptive method's tolerances times this (module docstring).
STATE_ACCURACY = 0.01
#: A linear solve to a relative residual r takes its products at rtol ``SOLVE_SHARE`` r,
#: at most ``LOOSEST_SOLVE_RTOL`` (``StroboscopicMap.for_solve``; module docstring).
SOLVE_SHARE = 1e-3
LOOSEST_SOLVE_RTOL = 1e-7


@dataclass
class MapWork:
    """What a map's runs cost, by kind (``KINDS``): how many runs, the tangent columns they
    carried in all, and their seconds. Mutable: the map adds to it as it runs."""

    runs: dict = field(default_factory=lambda: dict.fromkeys(KINDS, 0))
    columns: dict = field(default_factory=lambda: dict.fromkeys(KINDS, 0))
    seconds: dict = field(default_factory=lambda: dict.fromkeys(KINDS, 0.0))

    def add(self, kind: str, columns: int, seconds: float) -> None:
        self.runs[kind] += 1
        self.columns[kind] += columns
        self.seconds[kind] += seconds

    def copy(self) -> MapWork:
        return MapWork(dict(self.runs), dict(self.columns), dict(self.seconds))


@dataclass(frozen=True)
class MapValue:
    """φ(y) from ``start`` (``end``), and the tangent columns Φ V of the run (``columns``,
    size × k, None for a run of the state alone); ``singular``: the switches on the way
    where φ is not differentiable (grazing, or several interfaces at once), the first
    one's ``singular_time`` [s] and ``singular_interface``; ``stuck``: per interface,
    whether it was stuck all through the run (stuck at its start, and no switch of it)."""

    scene: Scene
    start: np.ndarray
    end: np.ndarray
    columns: np.ndarray | None
    singular: int
    singular_time: float
    singular_interface: int
    stuck: np.ndarray

    @property
    def jacobian(self) -> np.ndarray:
        """Φ, where ``columns`` are the whole of it (``StroboscopicMap.dense``)."""
        return self.columns

    def with_tangent_of(self, other: MapValue) -> MapValue:
        """This value (its φ, from the state's run) with the tangent columns, and the
        singular switches, of ``other``, a run from the same start that carried them."""
        return dataclasses.replace(self, columns=other.columns, singular=other.singular,
                                   singular_time=other.singular_time,
                                   singular_interface=other.singular_interface)

    def singular_reason(self, what: str) -> str:
        """Why ``what`` is not defined at this start."""
        left, right, _ = self.scene.group.interfaces[self.singular_interface]
        t = self.singular_time
        return (f"{what} is not defined: at t = {t:.9g} s (period "
                f"{t / self.scene.excitation_period:.6f}) interface "
                f"{self.singular_interface} ({left!r}, {right!r}) switches grazing its "
                f"switching surface, or together with another interface, and the "
                f"trajectory does not depend differentiably on its start there "
                f"({self.singular} such switches). Move the start or the parameter "
                f"slightly.")


@dataclass(frozen=True)
class StroboscopicMap:
    """y ↦ φ(y) over ``periods`` excitation periods of ``scene``, to the accuracy of
    ``method`` and ``event_tolerance`` (module docstring; an ``Accuracy`` is resolved to
    the settings it asks for on the scene). With ``cyclic``, the reduced map of a tuned
    ring's travelling wave; with ``repeating`` too, on the states that repeat every N/g
    sectors (``cyclic.reduced_step``)."""

    scene: Scene
    periods: int = 1
    method: Adaptive | Accuracy | Exponential = TANGENT_METHOD
    event_tolerance: float = EVENT_TOLERANCE
    cyclic: CyclicSymmetry | None = None
    repeating: bool = False
    work: MapWork = field(default_factory=MapWork, compare=False, repr=False)

    def __post_init__(self):
        if isinstance(self.method, Accuracy):
            method, event_tolerance = self.method.settings(self.scene, self.event_tolerance)
            object.__setattr__(self, "method", method)
            object.__setattr__(self, "event_tolerance", event_tolerance)

    @property
    def state_method(self) -> Adaptive | Exponential:
        """The method of the state's own runs: an adaptive one's tolerances times
        ``STATE_ACCURACY`` (module docstring)."""
        method = self.method
        if not isinstance(method, Adaptive):
            return method
        return dataclasses.replace(
            method, rtol=max(STATE_ACCURACY * method.rtol, SMALLEST_RTOL),
            atol=None if method.atol is None else STATE_ACCURACY * method.atol)

    @property
    def state_event_tolerance(self) -> float:
        """The event tolerance [periods] of the state's own runs: the map's times
        ``STATE_ACCURACY`` (module docstring)."""
        return max(STATE_ACCURACY * self.event_tolerance, SMALLEST_EVENT_TOLERANCE)

    @property
    def size(self) -> int:
        """The length of the states the map acts on."""
        if self.repeating:
            return 2 * self.cyclic.repeating
        return state_size(self.scene)

    def at(self, scene: Scene) -> StroboscopicMap:
        """The same map of another ``scene`` (a parameter's other value), its work counted
        with this one's."""
        return dataclasses.replace(self, scene=scene)

    def with_method(self, method) -> StroboscopicMap:
        """The same map to the accuracy of another ``method``, its work counted with this
        one's."""
        return dataclasses.replace(self, method=method)

    def for_solve(self, relative: float) -> StroboscopicMap:
        """The map whose products serve a linear solve to the ``relative`` residual
        (Newton–Krylov's GMRES, an inexact Newton's): an adaptive method's rtol loosened
        to ``SOLVE_SHARE`` times it, at most ``LOOSEST_SOLVE_RTOL`` and never tighter
        than the map's own (module docstring); the map itself otherwise."""
        method = self.method
        if not isinstance(method, Adaptive):
            return self
        rtol = min(LOOSEST_SOLVE_RTOL, SOLVE_SHARE * relative)
        if rtol <= method.rtol:
            return self
        atol = None if method.atol is None else method.atol * rtol / method.rtol
        return self.with_method(dataclasses.replace(method, rtol=rtol, atol=atol))

    def whole_ring(self) -> StroboscopicMap:
        """The map over the whole ring's states (not only the repeating ones)."""
        return dataclasses.replace(self, repeating=False)

    # ---- values -------------------------------------------------------------------------

    def __call__(self, y: np.ndarray) -> np.ndarray:
        """φ(y)."""
        return self.value(y).end

    def value(self, y: np.ndarray) -> MapValue:
        """φ(y), from one run of the state alone."""
        return self._run(y, None, "state")

    def products(self, y: np.ndarray, vectors: np.ndarray) -> MapValue:
        """φ(y) and Φ V, V = ``vectors`` (size × k, or one vector), in one run."""
        vectors = np.asarray(vectors, dtype=float)
        if vectors.ndim == 1:
            vectors = vectors[:, None]
        return self._run(y, vectors, "products")

    def dense(self, y: np.ndarray) -> MapValue:
        """φ(y) and the whole Φ (``MapValue.jacobian``), in one run of ``size`` columns
        (fewer on a symmetric orbit of a ring: ``cyclic.reduced_step``)."""
        if self.cyclic is None:
            return self._run(y, np.eye(self.size), "dense")
        clock = time.perf_counter()
        step = reduced_step(self.scene, self.cyclic, y, method=self.method,
                            event_tolerance=self.event_tolerance, repeating=self.repeating)
        self.work.add("dense", self.size, time.perf_counter() - clock)
        return MapValue(scene=self.scene, start=np.asarray(y, dtype=float), end=step.end,
                        columns=step.jacobian, singular=step.singular,
                        singular_time=step.singular_time,
                        singular_interface=step.singular_interface,
                        stuck=np.zeros(self.scene.arrays.n_interfaces, dtype=bool))

    def whole(self, value: MapValue) -> MapValue:
        """The value over one whole excitation period that a reduced map's dense value at a
        symmetric orbit stands for (``cyclic.whole_period``); ``value`` itself without
        symmetry."""
        if self.cyclic is None:
            return value
        return dataclasses.replace(value, columns=self.cyclic.monodromy(value.columns),
                                   singular=value.singular * self.cyclic.repeats)

    def _run(self, y, vectors, kind) -> MapValue:
        """One run from y over the map's time, with the tangent ``vectors`` (or none)."""
        y = np.asarray(y, dtype=float)
        clock = time.perf_counter()
        if self.cyclic is None:
            value = self._plain_run(y, vectors)
        else:
            value = self._reduced_run(y, vectors)
        self.work.add(kind, 0 if vectors is None else vectors.shape[1],
                      time.perf_counter() - clock)
        return value

    def _plain_run(self, y, vectors) -> MapValue:
        done = integrate(self.scene, self.periods, samples_per_period=1,
                         method=self.state_method if vectors is None else self.method,
                         event_tolerance=self.state_event_tolerance if vectors is None
                         else self.event_tolerance,
                         initial=state_parts(self.scene, y), event_capacity=EVENT_LOG,
                         tangent=vectors)
        run = done.run
        end = np.concatenate([run.output.x[-1], run.output.v[-1], done.stretches[-1]])
        return MapValue(scene=self.scene, start=y, end=end,
                        columns=None if vectors is None else run.tangent.matrix.copy(),
                        stuck=_stuck_through(run, self.scene.arrays.n_interfaces),
                        **_singular(run, vectors))

    def _reduced_run(self, y, vectors) -> MapValue:
        symmetry = self.cyclic
        whole = symmetry.tiled(y) if self.repeating else y
        columns = None
        if vectors is not None and self.repeating:
            vectors = symmetry.tiled(vectors)
        done = integrate(self.scene, 1, samples_per_period=1,
                         method=self.state_method if vectors is None else self.method,
                         event_tolerance=self.state_event_tolerance if vectors is None
                         else self.event_tolerance, initial=state_parts(self.scene, whole),
                         event_capacity=EVENT_LOG, tangent=vectors,
                         until=symmetry.fraction * self.scene.excitation_period)
        run = done.run
        end = shifted_end(symmetry, done)
        if vectors is not None:
            columns = symmetry.shifted(run.tangent.matrix, -symmetry.steps)
        if self.repeating:
            end = symmetry.restricted(end)
            columns = None if columns is None else symmetry.restricted(columns)
        return MapValue(scene=self.scene, start=y, end=end, columns=columns,
                        stuck=np.zeros(self.scene.arrays.n_interfaces, dtype=bool),
                        **_singular(run, vectors))

    # ---- an orbit's run --------------------------------------------------------------------

    def sampled(self, y: np.ndarray, samples_per_period: int) -> Simulation:
        """One orbit from y (whole periods, whatever the symmetry), ``samples_per_period``
        samples a period: the run its outputs are read from, by the nodes' own degrees of
        freedom as ``simulate`` gives every run."""
        clock = time.perf_counter()
        run = simulate(self.scene, self.periods, method=self.state_method,
                       samples_per_period=samples_per_period,
                       event_tolerance=self.state_event_tolerance,
                       initial=state_parts(self.scene, to_dofs(self.scene.arrays.layout, y)))
        self.work.add("outputs", 0, time.perf_counter() - clock)
        return run

    def states_at(self, y: np.ndarray):
        """Increasing times [s] within the orbit → [(x, ẋ) at each], the orbit from y run
        once at the state's accuracy and sampled at them from the dense output of the step
        that holds each (``integrate``'s ``times``); None on a symmetric orbit, whose runs
        span less than τ, and on the exponential method, which samples on its grid
        (``state_function`` then). Its run is counted as an output; its states, as
        ``state_function``'s, are by the nodes' own degrees of freedom."""
        if self.cyclic is not None or not isinstance(self.state_method, Adaptive):
            return None
        initial = state_parts(self.scene, y)
        layout = self.scene.arrays.layout

        def states(times):
            clock = time.perf_counter()
            run = integrate(self.scene, self.periods, method=self.state_method,
                            event_tolerance=self.state_event_tolerance, initial=initial,
                            event_capacity=0, times=times).run
            found = [(to_dofs(layout, x), to_dofs(layout, v))
                     for x, v in zip(run.output.x[1:], run.output.v[1:])]
            self.work.add("outputs", 0, time.perf_counter() - clock)
            return found
        return states

    def state_function(self, y: np.ndarray):
        """time [s] → (x, ẋ) of the orbit from y, run again from its start (on a symmetric
        orbit, over less than τ: ``cyclic.state_on_orbit``) at the method's own accuracy
        (its error, some 1e-9 of the scale at rtol 1e-10, is the extremes'). Its runs are
        counted as outputs. Its states, as ``sampled``'s, are by the nodes' own degrees of
        freedom."""
        initial = state_parts(self.scene, y)
        method = self.method
        if self.cyclic is None:
            def state(moment):
                return state_at(self.scene, initial, moment, method, self.event_tolerance)
        else:
            state = state_on_orbit(self.cyclic, self.scene, initial, method=method,
                                   event_tolerance=self.event_tolerance)

        layout = self.scene.arrays.layout

        def counted(moment):
            clock = time.perf_counter()
            found = tuple(to_dofs(layout, part) for part in state(moment))
            self.work.add("outputs", 0, time.perf_counter() - clock)
            return found
        return counted


def _singular(run, vectors) -> dict:
    """The singular switches a run with ``vectors`` met (none without a tangent)."""
    if vectors is None:
        return {"singular": 0, "singular_time": float("nan"), "singular_interface": -1}
    tangent = run.tangent
    return {"singular": int(tangent.singular[0]),
            "singular_time": float(tangent.singular_time[0]),
            "singular_interface": int(tangent.singular_interface[0])}


def _stuck_through(run, n_interfaces: int) -> np.ndarray:
    """Per interface, whether a run kept it stuck from its start to its end: stuck at the
    first sample, and no switch of it logged (none at all where the log is full)."""
    stuck = run.output.modes[0, :n_interfaces] == Mode.STICK
    logged = run.events.interface
    if int(run.events.n_events[0]) > len(logged):
        return np.zeros(n_interfaces, dtype=bool)
    stuck[np.unique(logged[logged >= 0])] = False
    return stuck
