"""An independent reference for the elastic dry-friction (Jenkins) contact element.

The element joins a point of relative tangential displacement r_t ∈ ℝᵈ (d = 1, 2 or 3)
to a slider at w ∈ ℝᵈ through a tangential spring k_t, under a normal load N ≥ 0 with a
circular Coulomb limit of one coefficient μ (static = kinetic)::

    f = k_t (r_t − w)                                  friction force [N]

    stuck:     |f| < μN,   ẇ = 0
    slipping:  |f| = μN,   ẇ = f̂ λ,  λ ≥ 0,   f̂ = f/|f|
    open:      N = 0,      w = r_t,  f = 0

Slipping, d|f|/dt = d(μN)/dt gives the consistency condition (with r_t − w = |f| f̂/k_t
and f̂·df̂/dt = 0)::

    λ = f̂·ṙ_t − (d(μN)/dt) / k_t                          [m/s]

A stuck element breaks away where |f|² − (μN)² rises to 0; a slipping one sticks where λ
falls to 0. The power taken out by the slider is f·ẇ = μN λ ≥ 0 [W].

Two references are built on these equations with numpy and scipy only; they share no
code with the compiled engine (``shroudnet.engine``) nor with the other baselines
(``shroudnet.references.blades``, ``shroudnet.references.structures``), so that the tests can use
them as a check of all three.

1. ``return_mapping``: the classical backward-Euler (radial) return over a sampled path
   (r_t,k, N_k), k = 0 … n − 1, from w_{−1} = w0::

       f_trial = k_t (r_t,k − w_{k−1});   |f_trial| ≤ μN_k:  f_k = f_trial, w_k = w_{k−1}
                                          else:  f_k = μN_k f_trial/|f_trial|,
                                                 w_k = r_t,k − f_k/k_t
       dissipated energy  D_k = Σ_{j≤k} f_j·(w_j − w_{j−1})   [J]  (each term ≥ 0)

   In 1-D at constant N it is exact at the samples for the path interpolated linearly
   between them (the play operator of a monotone stretch depends on its ends only); a
   smooth path's reversal between two samples is cut short by O(h²) of its amplitude, so
   the loop's area converges at second order in the step h. In 2-D the slip direction is
   taken at the end of the step (backward Euler): first order. On a circle of radius r,
   Δθ a step, the return's steady slider radius ρ solves ρ² + 2aρ sin(Δθ/2) + a² = r²,
   a = μN/k_t (the slider, the one before it and the driver lie on one line, a apart),
   against ρ² + a² = r² of the continuous law.

2. ``slide_path`` and ``run_oscillator``: the continuous law integrated with plain
   ``scipy.integrate.solve_ivp`` (DOP853), per mode a right-hand side, a terminal event for
   every guard, and a restart at every switch. ``slide_path`` drives the element along a
   prescribed r_t(t) at a normal load N(t) > 0; ``run_oscillator`` carries it on a point
   mass pressed onto a rigid ground (``JenkinsOscillator``)::

       m ẍ + C ẋ + K x = F(t) − (f, N),      x = (x_t, z) ∈ ℝᵈ⁺¹,  r_t = x_t
       F(t) = F_0 + F_c cos ωt + F_s sin ωt
       δ = z − Δ (penetration, z towards the ground),   N = k_n max(δ, 0)

   Modes and guards (each a terminal event falling through 0):

   ======== ========================= ==================================================
   mode     right-hand side of w      guards
   ======== ========================= ==================================================
   open     ẇ = ẋ_t (w stays = x_t)   closing: −δ
   stick    ẇ = 0                     separation: δ;  breakaway: μN − |f|
   slip     ẇ = f̂ λ                   separation: δ;  sticking: λ
   ======== ========================= ==================================================

   Closed modes use N = k_n δ, Ṅ = k_n ż, the smooth continuation of the normal law
   across δ = 0, so that a step straddling a guard sees one smooth system. The breakaway
   guard is not squared: (μN)² − |f|² would rise again as the continued N turns
   negative, and a stuck element that breaks away just before it separates would be seen
   to separate only. A guard that
   starts a segment at or below 0 (a rounding error on the far side of the switch just
   made) is raised by that much to start just above 0.

   The switches: closing sticks if k_t|ẋ_t| ≤ μ k_n ż (the friction limit grows faster
   than the force the stuck spring would take), else slips along ẋ_t (f̂ taken from ẋ_t
   while f = 0); separation opens; breakaway slips; sticking sticks. Closing and
   separation set w = x_t, the element's stored energy ½ k_t |x_t − w|² (zero in exact
   arithmetic: w follows x_t while open, and |f| = μN → 0 at separation) booked as
   friction loss.

   The energy ledger rides along with the motion (excluded from the step control)::

       excitation  ∫ F·ẋ dt,   damping  ∫ ẋᵀCẋ dt,   friction  ∫ f·ẇ dt    [J]
       stored      ½ m|ẋ|² + ½ xᵀKx + ½ k_n max(δ, 0)² + ½ k_t |x_t − w|²  [J]
       residual    excitation − damping − friction − (stored − stored(0))  [J]

All quantities in SI units: m, N, N/m, kg, s, rad/s, J.
"""

from __future__ import annotations

import math
from collections.abc import Callable, Sequence
from dataclasses import dataclass

import numpy as np
from scipy.integrate import solve_ivp

#: The element's modes.
OPEN, STICK, SLIP = "open", "stick", "slip"
MODES = (OPEN, STICK, SLIP)

#: What a located switch did: closed the contact, opened it, broke a stuck element away,
#: or stuck a slipping one.
SWITCH_KINDS = ("closing", "separation", "breakaway", "sticking")

#: Columns of ``OscillatorRun.ledger`` [J], cumulative from t = 0: the work of F(t), and
#: the viscous and the friction losses.
LEDGER_COLUMNS = ("excitation", "damping", "friction")

#: The most tangential dimensions d.
MAX_DIMENSION = 3

#: Added to every guard: the smallest positive normal double. It moves a guard that is
#: exactly 0 only (it is lost beside anything above about 1e-290).
_ABOVE_ZERO = float(np.finfo(float).tiny)

#: More switches than this at one instant in a row: no progress (a mode rule that cannot
#: settle), the run stops.
_STALLED = 20


# --------------------------------------------------------------------------- validation


def _number(owner: str, name: str, value, *, positive: bool, unit: str) -> float:
    try:
        number = float(value)
    except (TypeError, ValueError):
        raise ValueError(f"{owner}.{name} must be a number [{unit}], got {value!r}") from None
    if not math.isfinite(number) or number < 0.0 or (positive and number == 0.0):
        bound = "> 0" if positive else ">= 0"
        raise ValueError(f"{owner}.{name} must be finite and {bound} [{unit}], got {value!r}")
    return number


def _finite_array(owner: str, name: str, value, shape: tuple[int, ...] | None = None,
                  unit: str = "") -> np.ndarray:
    try:
        array = np.array(value, dtype=float)
    except (TypeError, ValueError):
        raise ValueError(f"{owner}.{name} must be numeric, got {value!r}") from None
    if shape is not None and array.shape != shape:
        raise ValueError(f"{owner}.{name} must have shape {shape}, got {array.shape}")
    if not np.all(np.isfinite(array)):
        raise ValueError(f"{owner}.{name} must be finite [{unit}]")
    return array


def _frozen(array: np.ndarray) -> np.ndarray:
    array.setflags(write=False)
    return array


# ------------------------------------------------------------------------ return mapping


@dataclass(frozen=True, eq=False)
class ReturnMapping:
    """The element along a sampled path, by ``return_mapping``.

    Attributes
    ----------
    displacements : (n, d) array
        r_t,k [m], as given (a 1-D path as one column).
    normal_loads : (n,) array
        N_k [N].
    forces : (n, d) array
        f_k = k_t (r_t,k − w_k) [N], |f_k| ≤ μN_k.
    slider : (n, d) array
        w_k [m].
    slipping : (n,) bool array
        Whether step k returned the trial force onto the circle |f| = μN_k.
    dissipation : (n,) array
        D_k = Σ_{j≤k} f_j·(w_j − w_{j−1}) [J], cumulative from w_{−1} = w0.
    stiffness, mu : float
        k_t [N/m] and μ [-].
    """

    displacements: np.ndarray
    normal_loads: np.ndarray
    forces: np.ndarray
    slider: np.ndarray
    slipping: np.ndarray
    dissipation: np.ndarray
    stiffness: float
    mu: float

    @property
    def dimension(self) -> int:
        """d, the tangential dimensions."""
        return self.displacements.shape[1]


def _path_array(owner: str, displacements) -> np.ndarray:
    path = _finite_array(owner, "displacements", displacements, unit="m")
    if path.ndim == 1:
        path = path[:, None]
    if path.ndim != 2 or path.shape[0] == 0 or not 1 <= path.shape[1] <= MAX_DIMENSION:
        raise ValueError(f"{owner}.displacements must be n values or an n × d array with "
                         f"n >= 1 and 1 <= d <= {MAX_DIMENSION}, got shape {path.shape}")
    return path


def return_mapping(displacements, normal_loads, stiffness: float, mu: float,
                   w0=None) -> ReturnMapping:
    """The backward-Euler return of the Jenkins element along a sampled path (module
    docstring, item 1).

    Parameters
    ----------
    displacements : (n,) or (n, d) array_like
        r_t,k [m], d ≤ 3 (n values: d = 1).
    normal_loads : float or (n,) array_like
        N_k ≥ 0 [N]; N_k = 0 is a separated contact (f_k = 0, w_k = r_t,k).
    stiffness : float
        k_t > 0 [N/m].
    mu : float
        μ ≥ 0 [-].
    w0 : (d,) array_like or float, optional
        The slider before the first sample [m]; by default r_t,0 (the spring relaxed).
    """
    owner = "return_mapping"
    path = _path_array(owner, displacements)
    n, d = path.shape
    loads = _finite_array(owner, "normal_loads", normal_loads, unit="N")
    if loads.ndim == 0:
        loads = np.full(n, float(loads))
    if loads.shape != (n,):
        raise ValueError(f"{owner}.normal_loads must be a number or {n} values (one per "
                         f"sample), got shape {loads.shape}")
    if np.any(loads < 0.0):
        raise ValueError(f"{owner}.normal_loads must be >= 0 [N], got a minimum of "
                         f"{loads.min()!r}")
    k_t = _number(owner, "stiffness", stiffness, positive=True, unit="N/m")
    mu = _number(owner, "mu", mu, positive=False, unit="-")
    if w0 is None:
        w = path[0].copy()
    else:
        w = _finite_array(owner, "w0", w0, unit="m").reshape(-1)
        if w.shape != (d,):
            raise ValueError(f"{owner}.w0 must have {d} components (one per column of "
                             f"displacements), got {np.shape(w0)}")
    forces = np.empty((n, d))
    slider = np.empty((n, d))
    slipping = np.zeros(n, dtype=bool)
    dissipation = np.empty(n)
    total = 0.0
    for k in range(n):
        trial = k_t * (path[k] - w)
        size = math.sqrt(float(trial @ trial))
        limit = mu * loads[k]
        if size > limit:
            force = trial * (limit / size)
            moved = path[k] - force / k_t
            total += float(force @ (moved - w))
            w = moved
            slipping[k] = True
        else:
            force = trial
        forces[k], slider[k], dissipation[k] = force, w, total
    return ReturnMapping(displacements=_frozen(path), normal_loads=_frozen(loads),
                         forces=_frozen(forces), slider=_frozen(slider),
                         slipping=_frozen(slipping), dissipation=_frozen(dissipation),
                         stiffness=k_t, mu=mu)


# ----------------------------------------------------------------- the continuous element


def _direction(u: np.ndarray, hint: np.ndarray) -> np.ndarray:
    """f̂ = u/|u|, u = r_t − w; the direction ``hint`` where u is exactly 0 (the instant
    a contact closes into slip)."""
    size = math.sqrt(float(u @ u))
    return u / size if size > 0.0 else hint


def _unit(vector: np.ndarray) -> np.ndarray:
    size = math.sqrt(float(vector @ vector))
    if size > 0.0:
        return vector / size
    unit = np.zeros_like(vector)
    unit[0] = 1.0
    return unit


def _slip_rate(u, rate, limit_rate, k_t, hint) -> tuple[float, np.ndarray]:
    """(λ, f̂): λ = f̂·ṙ_t − (d(μN)/dt)/k_t [m/s]."""
    direction = _direction(u, hint)
    return float(direction @ rate) - limit_rate / k_t, direction


def _guard_event(guard: Callable, t0: float, y0: np.ndarray) -> Callable:
    """``guard`` − min(guard(t0, y0), 0) + ``_ABOVE_ZERO`` as a terminal solve_ivp event
    falling through 0: a guard starting a rounding error at or below 0 starts just above
    it, and a crossing within the first step is found where it lies."""
    offset = min(guard(t0, y0), 0.0)

    def event(t, y):
        return guard(t, y) - offset + _ABOVE_ZERO
    event.terminal = True
    event.direction = -1.0
    return event


@dataclass
class _Segment:
    start: float
    end: float
    mode: str


def _event_driven(system, y: np.ndarray, mode: str, hint: np.ndarray, t_end: float,
                  samples: np.ndarray, rtol: float, atol: np.ndarray, max_switches: int):
    """Integrate ``system`` mode by mode from t = 0 to ``t_end``: its ``rhs(mode, hint)``,
    ``guards(mode, hint)`` → [(kind, g)], ``switch(kind, t, y)`` → (mode, y, hint). Returns
    (samples' states, samples' modes, segments, switch times, switch kinds, final y)."""
    t, taken, stalled = 0.0, 0, 0
    out_y: list[np.ndarray] = []
    out_modes: list[str] = []
    segments: list[_Segment] = []
    switch_times: list[float] = []
    switch_kinds: list[str] = []
    while True:
        guards = system.guards(mode, hint)
        events = [_guard_event(g, t, y) for _, g in guards]
        solution = solve_ivp(system.rhs(mode, hint), (t, t_end), y, method="DOP853",
                             rtol=rtol, atol=atol, dense_output=True, events=events or None)
        if solution.status < 0:
            raise RuntimeError(f"solve_ivp failed after t = {t:.12g} s: {solution.message}")
        reached = float(solution.t[-1])
        upto = int(np.searchsorted(samples, reached, side="right"))
        if upto > taken:
            points = samples[taken:upto]
            out_y.extend(np.reshape(solution.sol(points), (len(y), -1)).T)
            out_modes.extend([mode] * len(points))
            taken = upto
        segments.append(_Segment(t, reached, mode))
        if solution.status == 0:
            return out_y, out_modes, segments, switch_times, switch_kinds, solution.y[:, -1]
        located = next(k for k, times in enumerate(solution.t_events) if len(times))
        t_switch = float(solution.t_events[located][0])
        kind = guards[located][0]
        mode, y, hint = system.switch(kind, t_switch, solution.y_events[located][0].copy())
        switch_times.append(t_switch)
        switch_kinds.append(kind)
        stalled = stalled + 1 if t_switch <= t else 0
        if stalled > _STALLED:
            raise RuntimeError(f"switches make no progress at t = {t_switch:.12g} s")
        if len(switch_times) > max_switches:
            raise RuntimeError(f"more than {max_switches} switches by t = {t_switch:.12g} s")
        t = t_switch


def _samples(owner: str, t_eval, t_end: float) -> np.ndarray:
    if t_eval is None:
        return np.array([0.0, t_end])
    samples = _finite_array(owner, "t_eval", t_eval, unit="s").reshape(-1)
    if len(samples) and (samples[0] < 0.0 or samples[-1] > t_end
                         or np.any(np.diff(samples) < 0.0)):
        raise ValueError(f"{owner}.t_eval must increase within [0, t_end]")
    return samples


def _controls(owner: str, t_end, rtol, max_switches) -> tuple[float, float]:
    t_end = _number(owner, "t_end", t_end, positive=True, unit="s")
    rtol = _number(owner, "rtol", rtol, positive=True, unit="-")
    if not isinstance(max_switches, int | np.integer) or isinstance(max_switches, bool):
        raise TypeError(f"{owner}.max_switches must be an integer >= 0, got "
                        f"{max_switches!r}")
    if max_switches < 0:
        raise ValueError(f"{owner}.max_switches must be an integer >= 0, got "
                         f"{max_switches!r}")
    return t_end, rtol


def _atol(motion: np.ndarray, ledger: int) -> np.ndarray:
    """The motion's absolute tolerances, scaled by √(k/(k + ledger)) to undo the larger
    count in solve_ivp's RMS error norm, and ∞ for the ledger's integrals (they ride along
    with the steps, outside the error control)."""
    shrink = math.sqrt(len(motion) / (len(motion) + ledger))
    return np.concatenate([motion * shrink, np.full(ledger, np.inf)])


def _count(segments: Sequence[_Segment]) -> dict[str, int]:
    return {mode: sum(1 for s in segments if s.mode == mode and s.end > s.start)
            for mode in MODES}


# ------------------------------------------------------------------- a prescribed path


@dataclass(frozen=True, eq=False)
class PathRun:
    """The element along a prescribed path, by ``slide_path``.

    Attributes
    ----------
    times : (k,) array
        The samples [s].
    displacements, slider, forces : (k, d) arrays
        r_t [m], w [m] and f = k_t (r_t − w) [N] there.
    normal_loads : (k,) array
        N [N] there.
    dissipation : (k,) array
        ∫ f·ẇ dt [J] from t = 0.
    modes : tuple of str
        The mode at each sample (at a switch: the one before it).
    switch_times, switch_kinds
        Each located switch [s] and what it did (``SWITCH_KINDS``).
    segments : tuple of (start [s], end [s], mode)
        The stretches between switches.
    """

    times: np.ndarray
    displacements: np.ndarray
    slider: np.ndarray
    forces: np.ndarray
    normal_loads: np.ndarray
    dissipation: np.ndarray
    modes: tuple[str, ...]
    switch_times: np.ndarray
    switch_kinds: tuple[str, ...]
    segments: tuple[tuple[float, float, str], ...]

    @property
    def mode_counts(self) -> dict[str, int]:
        """Stretches of nonzero length spent in each mode."""
        return _count([_Segment(*s) for s in self.segments])


class _Path:
    """y = (r_t, w, ∫ f·ẇ dt) along a prescribed path at N(t) > 0 (stick and slip only).
    r_t is integrated from ṙ_t alongside, so that the steps resolve the path even where
    the slider stands still."""

    def __init__(self, rate, load, k_t, mu, d):
        self.rate, self.load, self.k_t, self.mu, self.d = rate, load, k_t, mu, d

    def rhs(self, mode, hint):
        k_t, mu, d = self.k_t, self.mu, self.d

        def rhs(t, y):
            rate = self.rate(t)
            if mode == STICK:
                return np.concatenate([rate, np.zeros(d + 1)])
            u = y[:d] - y[d:2 * d]
            lam, direction = _slip_rate(u, rate, mu * self.load(t)[1], k_t, hint)
            return np.concatenate([rate, direction * lam,
                                   [k_t * float(u @ direction) * lam]])
        return rhs

    def guards(self, mode, hint):
        k_t, mu, d = self.k_t, self.mu, self.d
        if mode == STICK:
            def breakaway(t, y):
                f = k_t * (y[:d] - y[d:2 * d])
                return (mu * self.load(t)[0]) ** 2 - float(f @ f)
            return [("breakaway", breakaway)]

        def sticking(t, y):
            return _slip_rate(y[:d] - y[d:2 * d], self.rate(t), mu * self.load(t)[1], k_t,
                              hint)[0]
        return [("sticking", sticking)]

    def switch(self, kind, t, y):
        d = self.d
        return (SLIP if kind == "breakaway" else STICK), y, _unit(y[:d] - y[d:2 * d])


def slide_path(path: Callable, normal_load, stiffness: float, mu: float, t_end: float, *,
               w0=None, t_eval=None, rtol: float = 1e-11, atol: float = 1e-14,
               max_switches: int = 100_000) -> PathRun:
    """The Jenkins element driven along a prescribed path, integrated event by event
    (module docstring, item 2).

    Parameters
    ----------
    path : callable
        ``path(t)`` → (r_t, ṙ_t), two arrays of d ≤ 3 values [m], [m/s], smooth in t.
        r_t is read at t = 0 only, then integrated from ṙ_t alongside w (so that the
        steps follow the path where the slider stands still); ``PathRun.displacements``
        are the integrated values.
    normal_load : float or callable
        N > 0 [N], or ``normal_load(t)`` → (N, Ṅ) [N], [N/s] with N staying > 0.
    stiffness, mu : float
        k_t > 0 [N/m], μ > 0 [-].
    t_end : float
        The run's end [s] (it starts at t = 0).
    w0 : (d,) array_like, optional
        The slider at t = 0 [m]; by default r_t(0). Beyond the friction limit it is
        returned onto it first, as one step of ``return_mapping``.
    t_eval : array_like, optional
        Sample times within [0, t_end], increasing; by default 0 and t_end.
    rtol, atol
        solve_ivp's tolerances; ``atol`` [m] is that of r_t and w.
    max_switches : int
        The most switches before a ``RuntimeError``.
    """
    owner = "slide_path"
    if not callable(path):
        raise TypeError(f"{owner}.path must be callable as path(t) -> (r_t, ṙ_t)")
    k_t = _number(owner, "stiffness", stiffness, positive=True, unit="N/m")
    mu = _number(owner, "mu", mu, positive=True, unit="-")
    t_end, rtol = _controls(owner, t_end, rtol, max_switches)
    atol = _number(owner, "atol", atol, positive=True, unit="m")
    if callable(normal_load):
        load = normal_load
    else:
        constant = _number(owner, "normal_load", normal_load, positive=True, unit="N")

        def load(t):
            return constant, 0.0
    r0 = np.atleast_1d(np.asarray(path(0.0)[0], dtype=float))
    d = r0.shape[0]
    if r0.ndim != 1 or not 1 <= d <= MAX_DIMENSION or not np.all(np.isfinite(r0)):
        raise ValueError(f"{owner}.path must give r_t of 1 to {MAX_DIMENSION} finite values, "
                         f"got {r0!r}")

    def rate(t):
        return np.atleast_1d(np.asarray(path(t)[1], dtype=float))
    n0, n0_rate = (float(value) for value in load(0.0))
    if not n0 > 0.0:
        raise ValueError(f"{owner}.normal_load must be > 0 [N], got {n0!r} at t = 0")
    if w0 is not None:
        w0 = _finite_array(owner, "w0", w0, unit="m").reshape(-1)
        if w0.shape != (d,):
            raise ValueError(f"{owner}.w0 must have {d} components, got {w0.shape}")
    start = return_mapping(r0[None, :], [n0], k_t, mu, w0=w0)
    system = _Path(rate, load, k_t, mu, d)
    y = np.concatenate([r0, start.slider[0], [start.dissipation[0]]])
    u = r0 - start.slider[0]
    hint = _unit(u) if np.any(u != 0.0) else _unit(rate(0.0))
    mode = STICK
    if k_t * math.sqrt(float(u @ u)) >= mu * n0 * (1.0 - 1e-12) and \
            _slip_rate(u, rate(0.0), mu * n0_rate, k_t, hint)[0] > 0.0:
        mode = SLIP
    samples = _samples(owner, t_eval, t_end)
    out, modes, segments, times, kinds, _ = _event_driven(
        system, y, mode, hint, t_end, samples, rtol, _atol(np.full(2 * d, atol), 1),
        max_switches)
    states = np.array(out).reshape(-1, 2 * d + 1)
    displacements, slider = states[:, :d], states[:, d:2 * d]
    loads = np.array([float(load(t)[0]) for t in samples])
    return PathRun(
        times=_frozen(samples), displacements=_frozen(displacements.copy()),
        slider=_frozen(slider.copy()), forces=_frozen(k_t * (displacements - slider)),
        normal_loads=_frozen(loads), dissipation=_frozen(states[:, 2 * d].copy()),
        modes=tuple(modes), switch_times=_frozen(np.array(times)),
        switch_kinds=tuple(kinds), segments=tuple((s.start, s.end, s.mode) for s in segments))


# --------------------------------------------------------------------- the oscillator


@dataclass(frozen=True, eq=False)
class JenkinsOscillator:
    """A point mass on springs, pressed onto a rigid ground through a normal spring, with
    a Jenkins element in the tangent plane (module docstring, item 2)::

        m ẍ + C ẋ + K x = F_0 + F_c cos ωt + F_s sin ωt − (f, N),   x = (x_t, z)

    The last coordinate z points into the ground: δ = z − Δ, N = k_n max(δ, 0), and the
    contact pushes the mass back by −N along z and −f along x_t (r_t = x_t).

    Parameters
    ----------
    mass : float
        m > 0 [kg].
    stiffness : (d + 1, d + 1) array
        K [N/m], symmetric, d = 1 … 3 tangential coordinates then z.
    normal_stiffness : float
        k_n > 0 [N/m].
    tangential_stiffness : float
        k_t > 0 [N/m].
    mu : float
        μ > 0 [-].
    force_static, force_cos, force_sin : (d + 1,) arrays
        F_0, F_c, F_s [N] (a preload: F_0 along +z, or a gap Δ < 0).
    frequency : float
        ω ≥ 0 [rad/s].
    gap : float
        Δ [m].
    damping : (d + 1, d + 1) array, optional
        C [N·s/m], symmetric positive semi-definite; by default none.
    """

    mass: float
    stiffness: np.ndarray
    normal_stiffness: float
    tangential_stiffness: float
    mu: float
    force_static: np.ndarray
    force_cos: np.ndarray
    force_sin: np.ndarray
    frequency: float
    gap: float = 0.0
    damping: np.ndarray | None = None

    def __post_init__(self):
        owner = "JenkinsOscillator"
        for name, unit, positive in (("mass", "kg", True), ("normal_stiffness", "N/m", True),
                                     ("tangential_stiffness", "N/m", True),
                                     ("mu", "-", True), ("frequency", "rad/s", False)):
            object.__setattr__(self, name, _number(owner, name, getattr(self, name),
                                                   positive=positive, unit=unit))
        stiffness = _finite_array(owner, "stiffness", self.stiffness, unit="N/m")
        if (stiffness.ndim != 2 or stiffness.shape[0] != stiffness.shape[1]
                or not 2 <= stiffness.shape[0] <= MAX_DIMENSION + 1):
            raise ValueError(f"{owner}.stiffness must be a square (d + 1) × (d + 1) matrix, "
                             f"1 <= d <= {MAX_DIMENSION}, got shape {stiffness.shape}")
        scale = np.abs(stiffness).max(initial=0.0)
        if np.abs(stiffness - stiffness.T).max(initial=0.0) > 1e-12 * scale:
            raise ValueError(f"{owner}.stiffness must be symmetric")
        object.__setattr__(self, "stiffness", _frozen(stiffness))
        n = stiffness.shape[0]
        damping = np.zeros((n, n)) if self.damping is None else _finite_array(
            owner, "damping", self.damping, (n, n), "N·s/m")
        if np.abs(damping - damping.T).max(initial=0.0) > 1e-12 * np.abs(damping).max(
                initial=0.0) or np.linalg.eigvalsh(0.5 * (damping + damping.T)).min() < (
                -1e-12 * np.abs(damping).max(initial=0.0)):
            raise ValueError(f"{owner}.damping must be symmetric positive semi-definite")
        object.__setattr__(self, "damping", _frozen(damping))
        for name in ("force_static", "force_cos", "force_sin"):
            object.__setattr__(self, name, _frozen(_finite_array(
                owner, name, getattr(self, name), (n,), "N")))
        gap = _finite_array(owner, "gap", self.gap, (), "m")
        object.__setattr__(self, "gap", float(gap))

    @property
    def dimension(self) -> int:
        """d, the tangential coordinates."""
        return self.stiffness.shape[0] - 1

    def force(self, t: float) -> np.ndarray:
        """F(t) [N]."""
        angle = self.frequency * t
        return self.force_static + math.cos(angle) * self.force_cos + math.sin(
            angle) * self.force_sin

    def stored_energy(self, x, v, w) -> np.ndarray:
        """½ m|ẋ|² + ½ xᵀKx + ½ k_n max(δ, 0)² + ½ k_t |x_t − w|² [J], of one state or of
        rows of states."""
        x, v, w = (np.asarray(a, dtype=float) for a in (x, v, w))
        d = self.dimension
        penetration = np.maximum(x[..., d] - self.gap, 0.0)
        spring = x[..., :d] - w
        return 0.5 * (self.mass * np.sum(v * v, axis=-1)
                      + np.einsum("...i,ij,...j->...", x, self.stiffness, x)
                      + self.normal_stiffness * penetration ** 2
                      + self.tangential_stiffness * np.sum(spring * spring, axis=-1))


@dataclass(frozen=True, eq=False)
class OscillatorRun:
    """A run of ``run_oscillator``.

    Attributes
    ----------
    times : (k,) array
        The samples [s].
    x, v : (k, d + 1) arrays
        Position [m] and velocity [m/s] (at a switch: the left limits).
    slider : (k, d) array
        w [m].
    normal_loads : (k,) array
        N = k_n max(δ, 0) [N].
    forces : (k, d) array
        f = k_t (x_t − w) [N].
    modes : tuple of str
        The mode at each sample (at a switch: the one before it).
    ledger : (k, 3) array
        ``LEDGER_COLUMNS`` [J], cumulative from t = 0.
    stored : (k,) array
        The stored energy [J]; ``stored_start`` that at t = 0.
    switch_times, switch_kinds, segments
        As in ``PathRun``.
    """

    oscillator: JenkinsOscillator
    times: np.ndarray
    x: np.ndarray
    v: np.ndarray
    slider: np.ndarray
    normal_loads: np.ndarray
    forces: np.ndarray
    modes: tuple[str, ...]
    ledger: np.ndarray
    stored: np.ndarray
    stored_start: float
    switch_times: np.ndarray
    switch_kinds: tuple[str, ...]
    segments: tuple[tuple[float, float, str], ...]

    @property
    def residual(self) -> np.ndarray:
        """excitation − damping − friction − (stored − stored(0)) [J] at each sample."""
        return (self.ledger[:, 0] - self.ledger[:, 1] - self.ledger[:, 2]
                - (self.stored - self.stored_start))

    @property
    def mode_counts(self) -> dict[str, int]:
        """Stretches of nonzero length spent in each mode."""
        return _count([_Segment(*s) for s in self.segments])


class _Oscillator:
    """y = (x, ẋ, w, ledger) of a ``JenkinsOscillator``."""

    def __init__(self, oscillator: JenkinsOscillator):
        self.o = oscillator
        self.d = oscillator.dimension
        self.n = self.d + 1

    def split(self, y):
        n, d = self.n, self.d
        return y[:n], y[n:2 * n], y[2 * n:2 * n + d]

    def slip(self, x, v, w, hint):
        """(λ, f̂) of a closed contact."""
        o, d = self.o, self.d
        return _slip_rate(x[:d] - w, v[:d], o.mu * o.normal_stiffness * v[d],
                          o.tangential_stiffness, hint)

    def rhs(self, mode, hint):
        o, n, d = self.o, self.n, self.d
        inverse_mass = 1.0 / o.mass

        def rhs(t, y):
            x, v, w = self.split(y)
            contact = np.zeros(n)
            if mode == OPEN:
                slider_rate = v[:d]
                friction_power = 0.0
            else:
                contact[d] = o.normal_stiffness * (x[d] - o.gap)
                contact[:d] = o.tangential_stiffness * (x[:d] - w)
                if mode == STICK:
                    slider_rate = np.zeros(d)
                    friction_power = 0.0
                else:
                    lam, direction = self.slip(x, v, w, hint)
                    slider_rate = direction * lam
                    friction_power = float(contact[:d] @ slider_rate)
            force = o.force(t)
            viscous = o.damping @ v
            acceleration = (force - viscous - o.stiffness @ x - contact) * inverse_mass
            return np.concatenate([v, acceleration, slider_rate,
                                   [force @ v, v @ viscous, friction_power]])
        return rhs

    def guards(self, mode, hint):
        o, d = self.o, self.d

        def penetration(t, y):
            return y[d] - o.gap
        if mode == OPEN:
            return [("closing", lambda t, y: -penetration(t, y))]
        if mode == STICK:
            def breakaway(t, y):
                x, _, w = self.split(y)
                f = o.tangential_stiffness * (x[:d] - w)
                limit = o.mu * o.normal_stiffness * (x[d] - o.gap)
                return limit - math.sqrt(float(f @ f))
            return [("separation", penetration), ("breakaway", breakaway)]

        def sticking(t, y):
            return self.slip(*self.split(y), hint)[0]
        return [("separation", penetration), ("sticking", sticking)]

    def switch(self, kind, t, y):
        o, n, d = self.o, self.n, self.d
        x, v, w = self.split(y)
        y = y.copy()
        if kind in ("closing", "separation"):
            spring = x[:d] - w
            y[-1] += 0.5 * o.tangential_stiffness * float(spring @ spring)
            y[2 * n:2 * n + d] = x[:d]
        if kind == "separation":
            return OPEN, y, _unit(v[:d])
        if kind == "closing":
            return self.closed_mode(v), y, _unit(v[:d])
        if kind == "breakaway":
            return SLIP, y, _unit(x[:d] - w)
        return STICK, y, _unit(x[:d] - w)

    def closed_mode(self, v):
        """At δ = 0, f = 0: stick if k_t|ẋ_t| ≤ μ k_n ż, else slip along ẋ_t."""
        o, d = self.o, self.d
        speed = math.sqrt(float(v[:d] @ v[:d]))
        return STICK if o.tangential_stiffness * speed <= o.mu * o.normal_stiffness * v[d] \
            else SLIP


def run_oscillator(oscillator: JenkinsOscillator, x0, v0, t_end: float, *, w0=None,
                   t_eval=None, rtol: float = 1e-11, atol: float = 1e-13,
                   max_switches: int = 100_000) -> OscillatorRun:
    """Integrate a ``JenkinsOscillator`` from (x0, ẋ0) at t = 0 to ``t_end`` [s], event by
    event, with its energy ledger (module docstring, item 2).

    Parameters
    ----------
    x0, v0 : (d + 1,) array_like
        The initial position [m] and velocity [m/s].
    w0 : (d,) array_like, optional
        The initial slider [m] of a closed contact; by default x0_t (f = 0). One beyond
        the friction limit is an error. An open contact takes w = x_t.
    t_eval : array_like, optional
        Sample times within [0, t_end], increasing; by default 0 and t_end.
    rtol, atol
        solve_ivp's tolerances; ``atol`` [m] is that of x and w, atol·max(ω, ω_0) [m/s]
        that of ẋ (ω_0 = √(λ_max(K + k_n e_z e_zᵀ)/m)).
    max_switches : int
        The most switches before a ``RuntimeError``.
    """
    owner = "run_oscillator"
    if not isinstance(oscillator, JenkinsOscillator):
        raise TypeError(f"{owner}.oscillator must be a JenkinsOscillator, got "
                        f"{oscillator!r}")
    system = _Oscillator(oscillator)
    n, d = system.n, system.d
    x = _finite_array(owner, "x0", x0, (n,), "m")
    v = _finite_array(owner, "v0", v0, (n,), "m/s")
    t_end, rtol = _controls(owner, t_end, rtol, max_switches)
    atol = _number(owner, "atol", atol, positive=True, unit="m")
    samples = _samples(owner, t_eval, t_end)
    o = oscillator
    closed = o.stiffness.copy()
    closed[d, d] += o.normal_stiffness
    natural = math.sqrt(max(np.linalg.eigvalsh(closed).max(), 0.0) / o.mass)
    scale = max(o.frequency, natural, 1e-300)
    penetration = x[d] - o.gap
    if penetration <= 0.0:
        w = x[:d].copy()
        mode, hint = OPEN, _unit(v[:d])
    else:
        w = x[:d].copy() if w0 is None else _finite_array(owner, "w0", w0, (d,), "m")
        spring = x[:d] - w
        force = o.tangential_stiffness * math.sqrt(float(spring @ spring))
        limit = o.mu * o.normal_stiffness * penetration
        if force > limit * (1.0 + 1e-12):
            raise ValueError(f"{owner}.w0 puts the friction force {force:.6g} N beyond "
                             f"the limit μN = {limit:.6g} N")
        hint = _unit(spring) if force > 0.0 else _unit(v[:d])
        mode = STICK
        if force >= limit * (1.0 - 1e-12) and system.slip(x, v, w, hint)[0] > 0.0:
            mode = SLIP
    y = np.concatenate([x, v, w, np.zeros(3)])
    stored_start = float(o.stored_energy(x, v, w))
    motion = np.concatenate([np.full(n, atol), np.full(n, atol * scale), np.full(d, atol)])
    out, modes, segments, times, kinds, _ = _event_driven(
        system, y, mode, hint, t_end, samples, rtol, _atol(motion, 3), max_switches)
    states = np.array(out).reshape(-1, 2 * n + d + 3)
    xs, vs, ws = states[:, :n], states[:, n:2 * n], states[:, 2 * n:2 * n + d]
    return OscillatorRun(
        oscillator=o, times=_frozen(samples), x=_frozen(xs.copy()), v=_frozen(vs.copy()),
        slider=_frozen(ws.copy()),
        normal_loads=_frozen(o.normal_stiffness * np.maximum(xs[:, d] - o.gap, 0.0)),
        forces=_frozen(o.tangential_stiffness * (xs[:, :d] - ws)), modes=tuple(modes),
        ledger=_frozen(states[:, 2 * n + d:].copy()),
        stored=_frozen(o.stored_energy(xs, vs, ws)), stored_start=stored_start,
        switch_times=_frozen(np.array(times)), switch_kinds=tuple(kinds),
        segments=tuple((s.start, s.end, s.mode) for s in segments))
