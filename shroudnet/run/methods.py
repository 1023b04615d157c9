"""Method settings of ``simulate``: the integrator, the accuracy asked for, the Zeno guard.

``FixedStep`` and ``Adaptive`` choose the integrator and its knobs; ``Accuracy`` asks for a
relative error and becomes the ``Adaptive`` settings that deliver it on a scene;
``ZenoGuard`` says when a run whose switches pile up stops. ``SimulationSettings`` records
what a run used, every knob resolved.
"""

from __future__ import annotations

from collections.abc import Iterator, Mapping
from dataclasses import asdict, dataclass, fields

from contact_laws import check_int, check_real

from ..model.scene import Scene

#: The default width of the time bracket of each located switch, in excitation periods,
#: of every entry point that locates switches (``simulate``, ``monodromy``, ``lyapunov``,
#: ``periodic_orbit``, ``continuation``, a scene file's ``[run]``). Its error on the
#: results is 0.3–6 times this (docs/guide/simulating.md, "What accuracy costs"): below
#: the integrators' own at their default tolerances.
EVENT_TOLERANCE = 1e-10
#: The smallest event tolerance [periods]: ten times the resolution of a float, below which
#: a switch's time bracket cannot shrink, and its location would never end.
SMALLEST_EVENT_TOLERANCE = 1e-15


def check_event_tolerance(owner: str, value: object) -> float:
    """``value`` as an event tolerance [periods] in [``SMALLEST_EVENT_TOLERANCE``, 1e-3], or
    raise naming ``owner.event_tolerance``."""
    value = check_real(owner, "event_tolerance", value, low=0.0, low_open=True, high=1e-3,
                       unit="periods")
    if value < SMALLEST_EVENT_TOLERANCE:
        raise ValueError(f"{owner}.event_tolerance must be at least "
                         f"{SMALLEST_EVENT_TOLERANCE:g} periods, got {value:g}: a switch's time "
                         "bracket cannot shrink below the resolution of a float")
    return value

#: The default number of excitation periods run and left out before a steady response is
#: read (``sweep``, ``lyapunov``, ``mistuning_study``, the work-precision regimes, a scene
#: file's ``[run]``, the command line): the transient of the paper's §3.1 figures.
TRANSIENT = 300


def transient_for(periods: int) -> int:
    """The transient [periods] to leave out of a run of ``periods`` periods that was given
    none (a run saved without its settings): ``TRANSIENT`` where the run is longer, else
    half of it, so that the steady response read after it has periods in it."""
    return TRANSIENT if periods > TRANSIENT else periods // 2


#: The most steps per excitation period of a method on a grid: a step of 10⁻⁶ periods.
#: Finer steps buy nothing: the classical Runge–Kutta step's truncation error (h⁴, 10⁻²⁴
#: of a period's motion) is then far below the rounding its steps add up, and the
#: exponential step is exact at any size. They only cost time: at a microsecond a step, a
#: second a period (10¹² steps a period would take 220 days for one).
MOST_STEPS_PER_PERIOD = 10**6


@dataclass(frozen=True, kw_only=True)
class _OnGrid:
    """A method whose steps lie on the grid t0 + k T_e / ``steps_per_period`` (in [8,
    ``MOST_STEPS_PER_PERIOD``])."""

    steps_per_period: int

    def __post_init__(self):
        object.__setattr__(self, "steps_per_period",
                           check_int(type(self).__name__, "steps_per_period",
                                     self.steps_per_period, low=8,
                                     high=MOST_STEPS_PER_PERIOD))


@dataclass(frozen=True, kw_only=True)
class FixedStep(_OnGrid):
    """Classical fourth-order Runge–Kutta on a fixed grid, switches located by bisection.

    This is the paper's scheme. The global error falls as h⁴ between switches.

    Parameters
    ----------
    steps_per_period : int
        Steps per excitation period T_e, in [8, ``MOST_STEPS_PER_PERIOD`` = 10⁶].
    """

    steps_per_period: int = 1000


@dataclass(frozen=True, kw_only=True)
class Adaptive:
    """Dormand–Prince 5(4) with error control and dense output; switches found on it.

    A step is accepted when the RMS over blades of its local error estimate, each component
    divided by atol + rtol·|value|, is at most 1. Displacements are held to ``atol`` [m] and
    velocities to ``atol``·lΩ [m/s], the same scale for harmonic motion at the excitation
    frequency. By default atol = rtol·x_s, with x_s = Σ|q_n| / min k_i the static
    deflection under the whole excitation (``DISPLACEMENT_SCALE`` when nothing excites the
    group), so that rtol alone sets the accuracy: halve it and every component, the energy
    ledger's residual included, follows. A fixed atol instead stops the error falling once
    rtol·|x| drops below it, at small excitation first. Samples and switches are taken from
    the step's 4th-order dense output, so they do not shorten the steps.

    Parameters
    ----------
    rtol : float
        Relative tolerance per step, in [1e-14, 0.1].
    atol : float, optional
        Absolute tolerance on displacements per step [m], > 0; by default rtol·x_s.
    max_step : float
        Largest step, in excitation periods, in (0, 1].
    """

    rtol: float = 1e-8
    atol: float | None = None
    max_step: float = 0.05

    def __post_init__(self):
        check_real("Adaptive", "rtol", self.rtol, low=1e-14, high=0.1)
        if self.atol is not None:
            check_real("Adaptive", "atol", self.atol, low=0.0, low_open=True, unit="m")
        check_real("Adaptive", "max_step", self.max_step, low=0.0, low_open=True, high=1.0,
                   unit="periods")

    def absolute_tolerance(self, scene: Scene) -> float:
        """The displacement tolerance [m] on ``scene``: ``atol``, or by default rtol·x_s."""
        if self.atol is not None:
            return self.atol
        deflection = scene.arrays.static_deflection
        return self.rtol * (deflection if deflection > 0.0 else DISPLACEMENT_SCALE)


@dataclass(frozen=True, kw_only=True)
class Exponential(_OnGrid):
    """The exact motion between switches, on a fixed grid; switches located as by the
    other methods.

    For scenes whose vector field is linear between switches (substructures whose laws
    are ``LinearSpring`` or ``ConstantLoad`` and ``Coulomb``, rigid stick, no prescribed
    motion: ``SceneArrays.linear_phases``), each phase is ż = A z in the state augmented by
    the excitation's harmonics, z = (x, ẋ, 1, cos lΩt, sin lΩt, …), and a step of size τ
    is e^{Aτ}, exact; the work of each power over it is the quadratic form of
    ∫₀^τ e^{Aᵀs} Q e^{As} ds (``engine.propagation``). The motion between switches then has
    no error of its own, whatever the step, and the results' error is the event
    location's: the steps only have to be short enough that no switch is missed between
    two of them (a contact that closes and opens again inside one, unseen at its ends),
    and no frequency of the structure limits them.

    Each set of modes met is built once per run (its matrix exponentials, from the
    vector field itself), so the method pays where phases are long and the structure
    stiff: unreduced finite-element blades whose high modes ring after every impact.

    Parameters
    ----------
    steps_per_period : int
        Steps per excitation period T_e, in [8, ``MOST_STEPS_PER_PERIOD`` = 10⁶]; each
        step is checked for switches at its ends and quarters. The default, 400, finds a
        stick of 11 µs in a period of 4 ms that 128 step over
        (``tests/test_exponential.py``).
    """

    steps_per_period: int = 400


#: The displacement scale [m] of the default atol when nothing excites the group.
DISPLACEMENT_SCALE = 1e-4


@dataclass(frozen=True, kw_only=True)
class Accuracy:
    """Ask for a relative error; get the adaptive settings that deliver it.

    ``target`` bounds the relative error of what a periodic response is read for: its
    Poincaré points (relative to the response amplitude) and E_ρ. For each scene it
    becomes ``Adaptive(rtol=target/100)`` (whose atol is rtol·x_s, x_s the static
    deflection under the whole excitation) and an event tolerance of at most
    target/100 periods. The factor 100 comes from the work–precision study
    (``studies.precision``, docs/guide/simulating.md): on the paper's group the
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
        rtol = self.target / ACCURACY_MARGIN
        return Adaptive(rtol=rtol), min(event_tolerance, rtol)


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


#: The integrators a run may record, by the name its settings table gives them.
RECORDED_METHODS = {"FixedStep": FixedStep, "Adaptive": Adaptive, "Exponential": Exponential}


@dataclass(frozen=True, kw_only=True, eq=False)
class SimulationSettings(Mapping):
    """How a simulation was run, every knob as used (``Simulation.settings``).

    It also reads as the flat table it is saved as (``as_dict``), so
    ``settings["rtol"]`` and ``settings["event_tolerance"]`` work as they did when it
    was a dict; two settings, or settings and such a table, are equal when their tables
    are.

    Parameters
    ----------
    method : FixedStep, Adaptive or Exponential
        The integrator: ``Accuracy`` resolved, and ``Adaptive``'s default atol filled in.
    periods : int
        Excitation periods simulated, ≥ 1.
    samples_per_period : int
        Output samples per period, ≥ 1.
    event_tolerance : float
        Width of the time bracket of each located switch, in excitation periods, > 0.
    zeno : ZenoGuard
        The Zeno guard, its window [periods] as used.
    """

    method: FixedStep | Adaptive | Exponential
    periods: int
    samples_per_period: int
    event_tolerance: float
    zeno: ZenoGuard

    def __post_init__(self):
        if not isinstance(self.method, FixedStep | Adaptive | Exponential):
            raise TypeError(f"SimulationSettings.method must be FixedStep(...), "
                            f"Adaptive(...) or Exponential(...), got {self.method!r}")
        if not isinstance(self.zeno, ZenoGuard):
            raise TypeError(f"SimulationSettings.zeno must be a ZenoGuard, got {self.zeno!r}")
        for name in ("periods", "samples_per_period"):
            object.__setattr__(self, name,
                               check_int("SimulationSettings", name, getattr(self, name), low=1))
        object.__setattr__(self, "event_tolerance",
                           check_real("SimulationSettings", "event_tolerance",
                                      self.event_tolerance, low=0.0, low_open=True,
                                      unit="periods"))

    def as_dict(self) -> dict:
        """The table a results file keeps: the method's name and knobs, flat, beside the
        periods, samples per period and event tolerance, and the Zeno guard's table."""
        return {"method": type(self.method).__name__, **asdict(self.method),
                "periods": self.periods, "samples_per_period": self.samples_per_period,
                "event_tolerance": self.event_tolerance,
                "zeno": {"events": self.zeno.events, "window": self.zeno.window}}

    @classmethod
    def from_dict(cls, table: Mapping) -> SimulationSettings:
        """The settings of a table written by ``as_dict`` (a results file's).

        Raises ``ValueError`` naming a key that is missing or not known, and what the
        records raise on a bad value.
        """
        if not isinstance(table, Mapping):
            raise TypeError(f"settings must be a table (a dict), got {table!r}")
        name = table.get("method")
        if name not in RECORDED_METHODS:
            raise ValueError(f"settings.method must be one of {sorted(RECORDED_METHODS)}, "
                             f"got {name!r}")
        method = RECORDED_METHODS[name]
        knobs = [field.name for field in fields(method)]
        wanted = ["method", *knobs, "periods", "samples_per_period", "event_tolerance", "zeno"]
        missing = [key for key in wanted if key not in table]
        unknown = [key for key in table if key not in wanted]
        if missing or unknown:
            raise ValueError(f"settings of a {name} run need the keys {wanted}; "
                             + (f"missing {missing}" if missing else f"unknown {unknown}"))
        zeno = table["zeno"]
        if not isinstance(zeno, Mapping) or set(zeno) != {"events", "window"}:
            raise ValueError(f"settings.zeno must be a table of events and window, got {zeno!r}")
        return cls(method=method(**{knob: table[knob] for knob in knobs}),
                   periods=table["periods"], samples_per_period=table["samples_per_period"],
                   event_tolerance=table["event_tolerance"], zeno=ZenoGuard(**zeno))

    def __getitem__(self, key: str):
        return self.as_dict()[key]

    def __iter__(self) -> Iterator[str]:
        return iter(self.as_dict())

    def __len__(self) -> int:
        return len(self.as_dict())

    def __eq__(self, other) -> bool:
        if not isinstance(other, Mapping):
            return NotImplemented
        return self.as_dict() == dict(other)

    __hash__ = None  # equal to a dict, so unhashable as a dict is
