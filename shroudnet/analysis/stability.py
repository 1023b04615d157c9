"""Stability from the tangent flow: monodromy matrices and Lyapunov exponents.

Both integrate the variational equations with the state, through every switch by its
saltation matrix (``engine.tangent``, DESIGN §6), in a kernel compiled for it on first use.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from contact_laws import check_instance, check_int

from ..checked_records import check_record
from ..model.lowering import from_dofs, to_dofs
from ..model.scene import Scene
from ..run.methods import EVENT_TOLERANCE, TRANSIENT, Accuracy, Adaptive, Exponential
from ..run.simulate import MAX_PERIODS, integrate, start_coordinates
from ..run.simulation import SimulationError

#: The default accuracy of the tangent flow: the trajectory to rtol 1e-10, so that the
#: monodromy matrix and the orbits found with it are good to about that.
TANGENT_METHOD = Adaptive(rtol=1e-10)

#: Blocks the record of ``lyapunov`` is cut into for the error of its exponents.
LYAPUNOV_BLOCKS = 10


def monodromy(scene: Scene, periods: int = 1, initial=None, *,
              method: Adaptive | Accuracy | Exponential = TANGENT_METHOD,
              event_tolerance: float = EVENT_TOLERANCE) -> np.ndarray:
    """The Jacobian of the ``periods``-period stroboscopic map at the start ``initial``.

    The map takes the state (x, ẋ) at t = 0 to the state at t = periods·T_e. Its Jacobian
    M is integrated with the state (the tangent flow), multiplied by the saltation matrix
    of every switch on the way (contact closing and opening, stick, slip reversal,
    breakaway, and the velocity projection onto stick clusters). The Floquet multipliers
    of a periodic orbit are its eigenvalues; a stick phase gives zero multipliers.

    Parameters
    ----------
    scene : Scene
    periods : int
        Excitation periods of the map, ≥ 1.
    initial : (x0, v0) or (x0, v0, u0), optional
        The start: displacements [m] and velocities [m/s] by blade position (with
        substructures, the nodes' own degrees of freedom, as ``simulate`` takes them);
        default at rest. A start with stuck interfaces has its velocities projected onto
        the stick clusters first, and M includes that projection. With elastic contacts,
        (x0, v0, u0) gives their springs' stretches too (``Simulation.stretches``; relaxed
        by default); a contact that starts at its friction limit, or beyond, slips, its
        stretch on the limit.
    method : Adaptive, Accuracy or Exponential
        The accuracy of the trajectory; M is the exact derivative of the computed map.
        ``Exponential()`` (scenes whose phases are linear) carries it exactly: each
        phase's e^{JΔt}, and the saltations at its switches.
    event_tolerance : float
        As ``simulate``.

    Returns
    -------
    float array (``state_size``, ``state_size``): (2 n_blades, 2 n_blades), and two more
        per elastic contact
        Rows and columns: displacements by blade position (with substructures, the nodes'
        own degrees of freedom), then velocities; with elastic contacts, then their
        stretches.

    Raises
    ------
    SimulationError
        As ``simulate``; and where a switch on the way is grazing (the flow tangent to the
        switching surface) or several interfaces switch at the same instant: the map is
        not differentiable there.
    """
    check_instance("monodromy", "scene", scene, Scene, expected="a shroudnet.Scene")
    periods = check_int("monodromy", "periods", periods, low=1, most=MAX_PERIODS)
    step = stroboscopic_step(scene, periods,
                             start_coordinates(scene, initial, "monodromy"),
                             method=method, event_tolerance=event_tolerance)
    if step.singular:
        raise SimulationError(step.singular_reason("the monodromy matrix"))
    return jacobian_in_dofs(scene, step.jacobian)


def jacobian_in_dofs(scene: Scene, jacobian: np.ndarray) -> np.ndarray:
    """A Jacobian of the stroboscopic map by the engine's coordinates (a
    ``StroboscopicStep``'s) taken to the nodes' own degrees of freedom, T M T⁻¹ with
    T = ``to_dofs`` on a state: its eigenvalues stay, its eigenvectors are states as a
    user reads them. A scene of ``Blade``s gets it back as it is."""
    layout = scene.arrays.layout
    if layout is None or layout.identity:
        return jacobian
    return to_dofs(layout, jacobian @ from_dofs(layout, np.eye(len(jacobian)), axis=0),
                   axis=0)


def state_size(scene: Scene) -> int:
    """The size of the state the stroboscopic map acts on: y = (x, ẋ), and with elastic
    contacts their springs' stretches u too (two each: ``Simulation.stretches``)."""
    return 2 * scene.arrays.n_blades + scene.arrays.n_stretches


def state_parts(scene: Scene, y: np.ndarray) -> tuple:
    """y = (x, ẋ[, u]) as the ``initial`` of a run: (x0, v0), and u0 with elastic
    contacts."""
    n = scene.arrays.n_blades
    return (y[:n], y[n:2 * n]) + ((y[2 * n:],) if len(y) > 2 * n else ())


@dataclass(frozen=True)
class StroboscopicStep:
    """One application of the ``periods``-period stroboscopic map y ↦ φ(y), y = (x, ẋ)
    (with elastic contacts (x, ẋ, u)):
    ``end`` = φ(start), its Jacobian ``jacobian`` (the monodromy matrix; see
    ``monodromy``), and ``singular``, the switches on the way where φ is not
    differentiable (grazing, or several interfaces at once), with the first one's
    ``singular_time`` [s] and ``singular_interface``."""

    scene: Scene
    end: np.ndarray
    jacobian: np.ndarray
    singular: int
    singular_time: float
    singular_interface: int

    def singular_reason(self, what: str) -> str:
        """Why ``what`` is not defined at this start."""
        t = self.singular_time
        return (f"{what} is not defined: at t = {t:.9g} s (period "
                f"{t / self.scene.excitation_period:.6f}) "
                f"{self.scene.contacts[self.singular_interface]} switches grazing its "
                f"switching surface, or together with another interface, and the "
                f"trajectory does not depend differentiably on its start there "
                f"({self.singular} such switches). Move the start or the parameter "
                f"slightly.")


def stroboscopic_step(scene: Scene, periods: int, initial=None, *,
                      method: Adaptive | Accuracy | Exponential = TANGENT_METHOD,
                      event_tolerance: float = EVENT_TOLERANCE) -> StroboscopicStep:
    """φ and its Jacobian from ``initial`` = (x0, v0) or, with elastic contacts,
    (x0, v0, u0) (default at rest), in one run of the state with its square tangent flow,
    all by the engine's coordinates (``integrate``). Arguments as ``monodromy``."""
    size = state_size(scene)
    done = integrate(scene, periods, method=method, samples_per_period=1,
                     event_tolerance=event_tolerance, initial=initial, event_capacity=0,
                     tangent=np.eye(size))
    run = done.run
    tangent = run.tangent
    return StroboscopicStep(scene=scene,
                            end=np.concatenate([run.output.x[-1], run.output.v[-1],
                                                done.stretches[-1]]),
                            jacobian=tangent.matrix.copy(), singular=int(tangent.singular[0]),
                            singular_time=float(tangent.singular_time[0]),
                            singular_interface=int(tangent.singular_interface[0]))


@dataclass(frozen=True)
class LyapunovExponents:
    """The largest Lyapunov exponents of a run, descending.

    ``per_period``: natural log of the growth per excitation period; ``per_second``: the
    same per second; ``error``: each one's standard error, from the spread of the
    exponents over ``LYAPUNOV_BLOCKS`` equal blocks of the record (nan for an exponent of
    −inf: a direction that a stick phase removed). ``periods`` and ``transient``: the
    periods measured and skipped before; ``singular_switches``: grazing switches met.
    """

    per_period: np.ndarray
    per_second: np.ndarray
    error: np.ndarray
    periods: int
    transient: int
    singular_switches: int

    #: Fields that may hold NaN or ±inf (see ``checked_records``).
    NON_FINITE = ("per_period", "per_second", "error")

    def __post_init__(self):
        check_record(self)

    @property
    def largest(self) -> float:
        """λ_max per period."""
        return float(self.per_period[0])

    def is_positive(self) -> bool:
        """Whether λ_max is positive beyond its error (chaos) — by two standard errors."""
        return bool(self.per_period[0] > 2.0 * self.error[0])


def lyapunov(scene: Scene, periods: int, *, transient: int = TRANSIENT, exponents: int = 1,
             initial=None, method: Adaptive | Accuracy | Exponential = Adaptive(),
             event_tolerance: float = EVENT_TOLERANCE, seed: int = 0) -> LyapunovExponents:
    """The ``exponents`` largest Lyapunov exponents, by the QR (Benettin) method.

    After ``transient`` periods from ``initial`` (default at rest), ``exponents`` random
    orthonormal tangent vectors are integrated with the state over ``periods`` periods,
    through every switch by its saltation matrix (Müller 1995), and re-orthonormalised
    after every step; the exponents are the mean logarithmic growth rates. Without
    contact, each is −c/(2m) per second.

    Parameters
    ----------
    scene : Scene
    periods : int
        Periods measured, ≥ ``LYAPUNOV_BLOCKS``.
    transient : int
        Periods run first and discarded, ≥ 0.
    exponents : int
        How many, from the largest: 1 … ``state_size`` (2 n_blades, and two per elastic
        contact).
    initial : (x0, v0) or (x0, v0, u0), optional
        The start of the transient, as ``monodromy`` takes it (with substructures, the
        nodes' own degrees of freedom).
    method : Adaptive, Accuracy or Exponential
        With ``Exponential()``, the vectors are carried through each phase by its
        e^{JΔt} and re-orthonormalised at every switch and sample.
    event_tolerance : float
        As ``simulate``.
    seed : int
        Seed of the random initial tangent vectors.
    """
    check_instance("lyapunov", "scene", scene, Scene, expected="a shroudnet.Scene")
    n = scene.arrays.n_blades
    periods = check_int("lyapunov", "periods", periods, low=LYAPUNOV_BLOCKS, most=MAX_PERIODS)
    transient = check_int("lyapunov", "transient", transient, low=0, most=MAX_PERIODS)
    seed = check_int("lyapunov", "seed", seed, low=0)
    size = state_size(scene)
    exponents = check_int("lyapunov", "exponents", exponents, low=1, high=size)
    initial = start_coordinates(scene, initial, "lyapunov")
    if transient > 0:
        before = integrate(scene, transient, method=method, samples_per_period=1,
                           event_tolerance=event_tolerance, initial=initial,
                           event_capacity=0)
        # the elastic contacts' sliders go on as the transient left them
        end = before.run.output
        initial = (end.x[-1], end.v[-1]) + ((before.stretches[-1],)
                                            if before.stretches.size else ())
    rng = np.random.default_rng(seed)
    start, _ = np.linalg.qr(rng.standard_normal((size, exponents)))
    frequency = scene.arrays.excitation_frequency  # orthonormal in |δx|² + |δẋ / lΩ|² + |δu|²
    start[n:2 * n] *= frequency if frequency > 0.0 else 1.0
    done = integrate(scene, periods, method=method, samples_per_period=1,
                     event_tolerance=event_tolerance, initial=initial, event_capacity=0,
                     tangent=start, orthonormalise=True)
    tangent = done.run.tangent
    growth = tangent.log_growth.copy()
    per_period = growth / periods
    increments = np.diff(np.vstack([np.zeros(exponents), tangent.history[1:periods], growth]),
                         axis=0)
    with np.errstate(invalid="ignore"):
        blocks = np.array([block.mean(axis=0)
                           for block in np.array_split(increments, LYAPUNOV_BLOCKS)])
        error = blocks.std(axis=0, ddof=1) / np.sqrt(LYAPUNOV_BLOCKS)
    error[~np.isfinite(per_period)] = np.nan
    order = np.argsort(-per_period, kind="stable")
    period = scene.excitation_period
    return LyapunovExponents(per_period=per_period[order],
                             per_second=per_period[order] / period, error=error[order],
                             periods=periods, transient=transient,
                             singular_switches=int(tangent.singular[0]))

