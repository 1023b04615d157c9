"""What a simulation means: spectra, periodicity and chaos, energy measures, the Campbell diagram.

Functions here compute; they never plot (``front.figures`` draws their results). Each
works on a ``Simulation`` and, where that is useful beyond shroudnet, on plain arrays.
"""

from __future__ import annotations

import math
from collections.abc import Hashable, Sequence
from dataclasses import dataclass, replace

import numpy as np
from scipy.optimize import brentq

from contact_laws import (
    check_array,
    check_choice,
    check_instance,
    check_int,
    check_real,
    check_sequence,
)

from ..checked_records import check_record
from ..engine.codes import Mode
from ..run.classification import (
    CHAOTIC,
    QUASI_PERIODIC,
    REPEAT_TOLERANCE,
    UNDETERMINED,
    Classification,
)
from ..run.methods import Adaptive
from ..run.simulation import Simulation, steady_rows, steady_skip
from .stability import LYAPUNOV_BLOCKS, LyapunovExponents, lyapunov


@dataclass(frozen=True)
class Spectrum:
    """One-sided amplitude spectrum of a steady response.

    ``frequency_ratio`` is f/f_e; ``amplitude`` is the amplitude of each component [m for
    displacements], corrected for the window's coherent gain so that a pure sine of
    amplitude A on a bin shows A. ``resolution`` is the bin width in f/f_e: 1/(number of
    periods analysed).
    """

    frequency_ratio: np.ndarray
    amplitude: np.ndarray
    resolution: float
    window: str

    def __post_init__(self):
        check_record(self)

    def peak(self) -> float:
        """f/f_e of the largest component other than the mean."""
        return float(self.frequency_ratio[1:][np.argmax(self.amplitude[1:])])

    def amplitude_at(self, ratio: float) -> float:
        """Largest amplitude within one bin of f/f_e = ``ratio``."""
        near = np.abs(self.frequency_ratio - ratio) <= self.resolution
        return float(self.amplitude[near].max()) if near.any() else 0.0


#: The windows ``amplitude_spectrum`` takes.
WINDOWS = ("hann", "rectangular")
#: The largest relative distance at which two Poincaré points count as the same: beyond
#: it every bounded motion would repeat (a tolerance of 10 labels any motion "p1").
LARGEST_TOLERANCE = 0.1


def amplitude_spectrum(signal, samples_per_period: int, *, window: str = "hann") -> Spectrum:
    """The spectrum of ``signal`` sampled ``samples_per_period`` times per excitation period.

    The mean is removed before windowing and kept as the amplitude at f = 0. ``window`` is
    "hann" (low leakage, for finding subharmonics) or "rectangular" (exact on whole
    periods of a periodic signal).
    """
    x = check_array("amplitude_spectrum", "signal", signal, shape=(None,), min_length=4)
    samples_per_period = check_int("amplitude_spectrum", "samples_per_period",
                                   samples_per_period, low=1)
    check_choice("amplitude_spectrum", "window", window, WINDOWS)
    mean = x.mean()
    weights = np.hanning(len(x) + 1)[:-1] if window == "hann" else np.ones(len(x))
    amplitude = 2.0 * np.abs(np.fft.rfft((x - mean) * weights)) / weights.sum()
    amplitude[0] = abs(mean)
    ratio = np.fft.rfftfreq(len(x), d=1.0 / samples_per_period)
    return Spectrum(frequency_ratio=ratio, amplitude=amplitude,
                    resolution=samples_per_period / len(x), window=window)


def spectrum(sim: Simulation, blade: Hashable | int, skip: int, *,
             window: str = "hann") -> Spectrum:
    """Amplitude spectrum of a blade's displacement over whole periods after ``skip``."""
    check_instance("spectrum", "sim", sim, Simulation, expected="a shroudnet.Simulation")
    check_choice("spectrum", "window", window, WINDOWS)
    x = sim.scene.response_of(sim.x[steady_rows(sim, skip, "spectrum")], blade)[:-1]  # whole
    # periods: the last sample is dropped
    return amplitude_spectrum(x, sim.samples_per_period, window=window)


def zero_one_test(series, *, n_frequencies: int = 100, seed: int = 0) -> float:
    """The 0–1 test for chaos (Gottwald & Melbourne 2009, correlation method): K ∈ [−1, 1].

    ``series`` is an observable sampled once per forcing period (a Poincaré coordinate).
    K is near 1 for chaotic dynamics and near 0 for periodic or quasi-periodic ones. It needs
    a few hundred points; fewer than ``MIN_ZERO_ONE_POINTS`` (50), from which it could not
    tell, are refused (a ValueError naming ``zero_one_test.series``). The random
    frequencies c ∈ (π/5, 4π/5) come from ``seed``, so the result is reproducible.
    """
    phi = check_array("zero_one_test", "series", series, shape=(None,),
                      min_length=MIN_ZERO_ONE_POINTS)
    n_frequencies = check_int("zero_one_test", "n_frequencies", n_frequencies, low=1,
                              most=100_000)
    seed = check_int("zero_one_test", "seed", seed, low=0)
    n = len(phi)
    spread = np.ptp(phi)
    if spread == 0.0:
        return 0.0
    phi = phi / spread
    lags = np.arange(1, n // 10 + 1)
    c = np.random.default_rng(seed).uniform(math.pi / 5, 4 * math.pi / 5, n_frequencies)
    angles = np.outer(c, np.arange(1, n + 1))  # one row per frequency
    p = np.cumsum(phi * np.cos(angles), axis=1)
    q = np.cumsum(phi * np.sin(angles), axis=1)
    mean_square = np.stack([np.mean((p[:, lag:] - p[:, :-lag]) ** 2
                                    + (q[:, lag:] - q[:, :-lag]) ** 2, axis=1)
                            for lag in lags], axis=1)
    oscillating = phi.mean() ** 2 * (1 - np.cos(np.outer(c, lags))) \
        / (1 - np.cos(c))[:, None]
    displacement = mean_square - oscillating
    # K = the correlation coefficient of each row with the lags; 0 for a flat row
    lag_dev = lags - lags.mean()
    dev = displacement - displacement.mean(axis=1, keepdims=True)
    scale = np.sqrt((lag_dev @ lag_dev) * np.einsum("ij,ij->i", dev, dev))
    flat = np.ptp(displacement, axis=1) == 0.0
    k_values = np.where(flat, 0.0, np.clip(dev @ lag_dev / np.where(flat, 1.0, scale),
                                           -1.0, 1.0))
    return float(np.median(k_values))


def classify_section(points, *, scale=None, tolerance: float = REPEAT_TOLERANCE,
                     max_period: int = 64, chaos_threshold: float = 0.5,
                     broadband: float = math.nan, exponent=None) -> Classification:
    """Classify a motion from its Poincaré points (rows (x, ẋ), one per forcing period).

    The motion is pN for the smallest N ≤ ``max_period`` with every point within
    ``tolerance`` of the point N periods later, distances taken per coordinate relative to
    ``scale`` (default: the largest |value| of each coordinate). Otherwise, given the
    motion's ``exponent`` (``stability.LyapunovExponents``), λ_max decides
    (``exponent_label``); without it the 0–1 test does: K > ``chaos_threshold`` is
    chaotic, else quasi-periodic, and fewer than ``MIN_ZERO_ONE_POINTS`` points are
    undetermined.
    """
    points = check_array("classify_section", "points", points, shape=(None, None))
    if scale is not None:
        scale = check_array("classify_section", "scale", scale, shape=(points.shape[1],),
                            low=0.0)
    tolerance, max_period = _repeat_settings("classify_section", tolerance, max_period)
    check_real("classify_section", "chaos_threshold", chaos_threshold, low=0.0, high=1.0)
    if not (isinstance(broadband, float) and math.isnan(broadband)):
        check_real("classify_section", "broadband", broadband, low=0.0, high=1.0)
    check_instance("classify_section", "exponent", exponent, LyapunovExponents, optional=True)
    period, mismatch = repeat_period(points, scale, tolerance, max_period)
    if period is not None:
        return Classification(f"p{period}", period, len(points), tolerance, mismatch, 0.0,
                              broadband)
    k = zero_one_test(points[:, 0]) if len(points) >= MIN_ZERO_ONE_POINTS else math.nan
    if exponent is not None:
        label, reason = exponent_label(exponent)
        return Classification(label, None, len(points), tolerance, mismatch, k, broadband,
                              exponent.largest, float(exponent.error[0]), reason)
    if not math.isfinite(k) or len(points) < MIN_ZERO_ONE_POINTS:
        return Classification(UNDETERMINED, None, len(points), tolerance, mismatch, k,
                              broadband, reason=f"{len(points)} Poincaré points are too few "
                              f"for the 0–1 test (it needs {MIN_ZERO_ONE_POINTS})")
    label = CHAOTIC if k > chaos_threshold else QUASI_PERIODIC
    return Classification(label, None, len(points), tolerance, mismatch, k, broadband)


def repeat_period(points, scale, tolerance, max_period) -> tuple[int | None, float]:
    """(N, mismatch): the smallest N ≤ ``max_period`` whose points repeat to ``tolerance``
    (None if none) and the relative distance of the closest repeat (``classify_section``)."""
    if points.ndim != 2 or points.shape[1] != 2 or len(points) < 2:
        raise ValueError("classify needs at least two Poincaré points (x, v) as rows")
    if not np.isfinite(points).all():
        raise ValueError("classify: the Poincaré points are not finite")
    scale = np.abs(points).max(axis=0) if scale is None else np.asarray(scale, dtype=float)
    relative = points / np.where(scale > 0.0, scale, 1.0)
    mismatch = math.inf
    for period in range(1, min(max_period, len(points) - 1) + 1):
        gap = float(np.abs(relative[period:] - relative[:-period]).max())
        mismatch = min(mismatch, gap)
        if gap <= tolerance:
            return period, gap
    return None, mismatch


#: The fewest Poincaré points the 0–1 test decides on.
MIN_ZERO_ONE_POINTS = 50
#: λ_max is taken as zero (quasi-periodic) when within this many standard errors of 0.
EXPONENT_ERRORS = 2.0


def exponent_label(exponent) -> tuple[str, str]:
    """(label, reason) of a motion whose Poincaré points repeat with no period, from its
    largest Lyapunov exponent λ ± σ (``stability.LyapunovExponents``): chaotic when
    λ > 2σ; quasi-periodic when |λ| ≤ 2σ; undetermined when λ < −2σ (the motion is
    attracted to an orbit whose period exceeds those tried, or has not settled on it)."""
    largest, error = exponent.largest, float(exponent.error[0])
    if largest > EXPONENT_ERRORS * error:
        return CHAOTIC, ""
    if abs(largest) <= EXPONENT_ERRORS * error:
        return QUASI_PERIODIC, ""
    return UNDETERMINED, (f"λ_max = {largest:.3g} ± {error:.1g} < 0 with no period "
                          "repeating: a longer period, or a transient not yet settled")


def classify(sim: Simulation, blade: Hashable | int, skip: int, *,
             tolerance: float = REPEAT_TOLERANCE, max_period: int = 64,
             exponent: bool = True) -> Classification:
    """Classify the motion of a blade after ``skip`` transient periods.

    See ``classify_section``. Distances are relative to the largest |x| and |ẋ| of the
    steady response; 2N + 1 recorded periods recognise pN. When no period repeats, the
    largest Lyapunov exponent over the recorded periods decides (``exponent_label``): it
    is computed by ``stability.lyapunov`` from the whole state at ``skip`` periods
    (``Simulation.state``: with elastic contacts, their stretches too), with the run's
    rtol (the first time, that compiles the integrator with its tangent flow).
    Fewer than ``stability.LYAPUNOV_BLOCKS`` recorded periods give "undetermined". With
    ``exponent=False`` the 0–1 test decides instead, as ``classify_section`` does without
    an exponent.
    """
    check_instance("classify", "sim", sim, Simulation, expected="a shroudnet.Simulation")
    tolerance, max_period = _repeat_settings("classify", tolerance, max_period)
    check_instance("classify", "exponent", exponent, bool, expected="True or False")
    rows = steady_rows(sim, skip, "classify")
    scale = (np.abs(sim.scene.response_of(sim.x[rows], blade)).max(),
             np.abs(sim.scene.response_of(sim.v[rows], blade)).max())
    points = sim.poincare(blade, skip=skip)
    broadband = broadband_fraction(spectrum(sim, blade, skip))
    recorded = sim.periods - rows.start // sim.samples_per_period  # skip as a checked int
    result = None
    if exponent and repeat_period(points, scale, tolerance, max_period)[0] is None:
        if recorded < LYAPUNOV_BLOCKS:
            kind = classify_section(points, scale=scale, tolerance=tolerance,
                                    max_period=max_period, broadband=broadband)
            return replace(kind, label=UNDETERMINED, reason=(
                f"no period repeats in {recorded} recorded periods, and λ_max needs at "
                f"least {LYAPUNOV_BLOCKS}"))
        start = rows.start
        # The tangent flow to the run's rtol; after a fixed-step run, to the default one.
        run = sim.settings.method
        rtol = run.rtol if isinstance(run, Adaptive) else Adaptive().rtol
        result = lyapunov(sim.scene, recorded, transient=0, initial=sim.state(start),
                          method=Adaptive(rtol=rtol))
    return classify_section(points, scale=scale, tolerance=tolerance, max_period=max_period,
                            broadband=broadband, exponent=result)


def _repeat_settings(owner: str, tolerance, max_period) -> tuple[float, int]:
    """The repeat test's ``tolerance`` (relative distance, in (0, ``LARGEST_TOLERANCE``])
    and ``max_period`` (≥ 1), checked."""
    tolerance = check_real(owner, "tolerance", tolerance, low=0.0, low_open=True,
                           high=LARGEST_TOLERANCE)
    return tolerance, check_int(owner, "max_period", max_period, low=1, most=100_000)


def broadband_fraction(spectrum: Spectrum, lines: int = 20) -> float:
    """Fraction of the power (mean removed) outside the ``lines`` strongest spectral lines.

    A line is a local maximum with the bins beside it (the Hann window's main lobe).
    """
    power = spectrum.amplitude[1:] ** 2
    total = power.sum()
    if total == 0.0:
        return 0.0
    inside = np.zeros(len(power), dtype=bool)
    rises = np.ones(len(power), dtype=bool)   # power[k] >= power[k - 1]
    rises[1:] = power[1:] >= power[:-1]
    falls = np.ones(len(power), dtype=bool)   # power[k] >= power[k + 1]
    falls[:-1] = power[:-1] >= power[1:]
    peaks = np.flatnonzero(rises & falls)
    strongest = peaks[np.argsort(-power[peaks], kind="stable")[:lines]]
    for k in strongest:
        inside[max(k - 2, 0):k + 3] = True
    return float(power[~inside].sum() / total)


def friction_loss_per_cycle(sim: Simulation, skip: int) -> float:
    """Energy dissipated by friction per excitation period after ``skip`` [J/cycle].

    Sliding friction work plus the kinetic energy lost as slipping blades lock together.
    """
    check_instance("friction_loss_per_cycle", "sim", sim, Simulation,
                   expected="a shroudnet.Simulation")
    skip = steady_skip(sim, skip, "friction_loss_per_cycle")
    work = sim.work[steady_rows(sim, skip, "friction_loss_per_cycle")]
    return float((work[-1, 2] + work[-1, 4] - work[0, 2] - work[0, 4])
                 / (sim.periods - skip))


@dataclass(frozen=True, eq=False)
class HysteresisLoop:
    """An interface's friction force against its slip displacement.

    ``slip`` [m] is u_t (``Simulation.slip_displacement``), ``force`` [N] the friction
    force f, positive where it holds back a positive slip (while stuck, the static
    friction), at the samples from ``skip`` periods on; ``cycles`` is how many periods
    they span, ``interface`` the contact's column (``Scene.contacts``: the interface's
    position where no interface is a patch). Friction takes the power f u̇_t, so
    the loop's area ∮ f du_t is the energy it dissipates.
    """

    slip: np.ndarray
    force: np.ndarray
    cycles: int
    interface: int

    def __post_init__(self):
        check_record(self)

    def area_per_cycle(self) -> float:
        """∮ f du_t per period [J/cycle], by the trapezoidal rule over the samples: the
        friction loss per cycle of a steady response, to the sampling's second order
        (without the kinetic energy lost where a slipping interface sticks, which
        ``friction_loss_per_cycle`` also counts)."""
        du = np.diff(self.slip)
        return float(np.sum(0.5 * (self.force[1:] + self.force[:-1]) * du) / self.cycles)


def hysteresis_loop(sim: Simulation, interface, skip: int,
                    direction: int = 1) -> HysteresisLoop:
    """The hysteresis loop of interface ``interface`` (its position, 0-based, or
    (interface, k) for a patch's k-th contact: ``Scene.contact_position``) over the
    periods of ``sim`` after ``skip`` (as ``steady_rows`` takes it): its friction force
    against its tangential relative displacement along t₁ (``direction`` 1) or, on a face
    that slides in its plane, t₂ (2). Over steady cycles of an elastic contact the two
    loops' areas add up to the energy its slider dissipates: ∮ f·dr_t = ∮ f·dw, the
    spring's ½k_t|u|² coming back to itself."""
    check_instance("hysteresis_loop", "sim", sim, Simulation,
                   expected="a shroudnet.Simulation")
    column = sim.checked_interface(interface, "hysteresis_loop")
    direction = check_int("hysteresis_loop", "direction", direction, low=1, most=2)
    if direction == 2 and not np.any(sim.scene.arrays.slip_rows(2)[column]):
        raise ValueError(f"hysteresis_loop.direction = 2: {sim.scene.contacts[column]} "
                         "slides along one direction; a face that slides in its plane "
                         "takes Interface(tangent_directions=(t1, t2), ...)")
    skip = steady_skip(sim, skip, "hysteresis_loop")
    rows = steady_rows(sim, skip, "hysteresis_loop")
    slip = sim.slip_displacement(interface, direction)[rows]
    return HysteresisLoop(slip=slip, force=sim.friction_along(interface, direction)[rows],
                          cycles=sim.periods - skip, interface=column)


@dataclass(frozen=True, eq=False)
class PatchHistory:
    """The contacts of one interface over time: a patch's contact-state map and its
    normal-load distribution.

    ``time`` [s] (n_t samples, from ``skip`` periods on); per contact of the interface
    (columns, in the order of its point pairs): ``modes`` (``Mode`` values: open, stuck,
    slipping either way), ``normal`` [N] its normal force N_k and ``friction`` [N] its
    friction force along t₁; ``interface`` the interface's position, ``period`` T_e [s].
    """

    interface: int
    time: np.ndarray
    modes: np.ndarray
    normal: np.ndarray
    friction: np.ndarray
    period: float

    def __post_init__(self):
        check_record(self)

    @property
    def contacts(self) -> int:
        """k, the point pairs of the interface."""
        return self.modes.shape[1]

    def fractions(self) -> dict[str, np.ndarray]:
        """Per contact, the share of the samples it spends "open", "stuck" and
        "slipping" (either way): three arrays of k values that add up to 1."""
        open_ = self.modes == Mode.OPEN
        stuck = self.modes == Mode.STICK
        return {"open": open_.mean(axis=0), "stuck": stuck.mean(axis=0),
                "slipping": (~open_ & ~stuck).mean(axis=0)}

    def load_shares(self) -> np.ndarray:
        """Per contact, its share of the interface's normal load over the samples:
        ∫ N_k dt / Σ_j ∫ N_j dt (k values adding up to 1; zeros where the interface never
        closes)."""
        loads = np.trapezoid(self.normal, self.time, axis=0) if len(self.time) > 1 \
            else self.normal.sum(axis=0)
        total = loads.sum()
        return loads / total if total > 0.0 else np.zeros_like(loads)


def patch_history(sim: Simulation, interface: int, skip: int = 0) -> PatchHistory:
    """The ``PatchHistory`` of interface ``interface`` (its position, 0-based; a patch of
    k point pairs, or an interface of one) over the samples of ``sim`` from ``skip``
    periods on (as ``steady_rows`` takes it)."""
    check_instance("patch_history", "sim", sim, Simulation,
                   expected="a shroudnet.Simulation")
    first = sim.scene.contact_position((interface, 0), "patch_history")
    columns = slice(first, first + sim.scene.contacts[first].pairs)
    rows = steady_rows(sim, skip, "patch_history")
    return PatchHistory(interface=sim.scene.contacts[first].interface, time=sim.t[rows],
                        modes=sim.modes[rows, columns], normal=sim.normal_force[rows, columns],
                        friction=sim.friction_force[rows, columns],
                        period=sim.scene.excitation_period)


@dataclass(frozen=True)
class Campbell:
    """A Campbell diagram: f_d1 [Hz] against speed [rpm], and the engine-order lines.

    ``crossings`` lists (engine order l, speed [rpm], frequency [Hz]) where f_d1 = l Ω/60:
    the speeds at which the excitation is resonant.
    """

    speeds_rpm: np.ndarray
    frequency: np.ndarray
    engine_orders: tuple[int, ...]
    crossings: tuple[tuple[int, float, float], ...]

    def __post_init__(self):
        check_record(self)

    def line(self, engine_order: int) -> np.ndarray:
        """The excitation frequency l Ω/60 [Hz] of an engine order at each speed."""
        return engine_order * self.speeds_rpm / 60.0


def campbell(frequency_model, speeds_rpm: Sequence[float],
             engine_orders: Sequence[int] = (1, 2, 3, 4)) -> Campbell:
    """Campbell diagram of a blade frequency model (anything with ``at(speed_rpm)`` in Hz:
    ``ConstantFrequency``, ``Southwell``, ``FrequencyTable``) over increasing speeds [rpm]."""
    if not callable(getattr(frequency_model, "at", None)):
        raise TypeError("campbell.frequency_model must be a frequency model with at(speed_rpm) "
                        "in Hz (ConstantFrequency, Southwell, FrequencyTable), got "
                        f"{type(frequency_model).__name__} {frequency_model!r:.80}")
    speeds = check_array("campbell", "speeds_rpm", speeds_rpm, shape=(None,), low=0.0,
                         unit="rpm")
    if len(speeds) < 2 or np.any(np.diff(speeds) <= 0):
        raise ValueError("campbell needs at least two increasing speeds_rpm")
    engine_orders = [check_int("campbell", "engine_orders", order, low=1)
                     for order in check_sequence("campbell", "engine_orders", engine_orders,
                                                 expected="a sequence of ints", min_length=1)]
    frequency = np.array([frequency_model.at(s) for s in speeds])
    crossings = []
    for order in engine_orders:
        def detuning(speed, order=order):
            return frequency_model.at(speed) - order * speed / 60.0
        gap = frequency - order * speeds / 60.0
        for k in range(len(speeds)):
            if gap[k] == 0.0:
                speed = speeds[k]
            elif k + 1 < len(speeds) and gap[k] * gap[k + 1] < 0.0:
                speed = brentq(detuning, speeds[k], speeds[k + 1], xtol=1e-9)
            else:
                continue
            crossings.append((int(order), float(speed), float(order * speed / 60.0)))
    return Campbell(speeds, frequency, tuple(int(o) for o in engine_orders), tuple(crossings))
