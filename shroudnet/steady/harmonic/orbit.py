"""A periodic orbit found by harmonic balance, read as an exact orbit is read.

Every degree of freedom is the truncated series q(t) = c₀ + Σ_k (a_k cos kωt + b_k sin
kωt) (``fourier``), by the nodes' own degrees of freedom q (a ``Blade``'s x, a
substructure's q of ``Substructure.matrices_at``) stacked in ``Scene.blades`` order, as
every state a run or ``PeriodicOrbit`` gives; so what ``PeriodicOrbit`` gives from a
run, this gives from the series:
the extremes of each response (its maximum and minimum over the period, found on the
series and refined by Newton's method: exact for the series), the amplitude as half
the peak-to-peak, the mean and the mean square (Parseval), the harmonics and their
phases, the energy per cycle (each integral exact for the series, the contacts' work
from the samples their forces were computed at), the kinetic energy's peak and ζ_eq.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from ...checked_records import check_record
from ...model.lowering import from_dofs
from ...model.scene import Scene
from ..cycle import EnergyPerCycle, Harmonics, OrbitReadings
from ..orbits import UNIT_CIRCLE
from .aft import contact_forces as forces_in_time
from .fourier import FourierBasis, derivative_matrix, series_matrix
from .model import harmonic_model


@dataclass(frozen=True)
class HarmonicOrbit(OrbitReadings):
    """A periodic orbit of ``periods`` excitation periods by harmonic balance with
    ``harmonic_count`` H harmonics of ω = l Ω / periods (2π f / periods at an
    excitation frequency f of its own), its contact forces evaluated at
    ``samples`` N times per period.

    ``coefficients`` ((2H+1) × n): the real Fourier coefficients (c₀, a₁, b₁, …) of
    every one of the nodes' own degrees of freedom q [their units: m for blades], stacked
    in ``Scene.blades`` order (a ``Blade``'s x, a substructure's q: the columns of
    ``Simulation.x``, which ``Scene.responses`` and ``Scene.dof_rows`` read);
    ``contact_coefficients`` ((2H+1) × m): those of the contact coordinates z = B q
    (``model``: B an orthonormal basis over q of the rows each contact's laws read), the
    unknowns solved for; ``force_coefficients``: the contacts' generalised forces λ̂ [N]
    conjugate to z. ``stretches``: the elastic contacts' stretches u = f/k_t at t = 0
    [m] (two each, as ``Simulation.stretches``).

    ``residual``: max |R| of the balance over ``scale`` (the contacts' motion [m]),
    reached in ``iterations`` Newton steps; ``converged`` says whether it meets
    ``tolerance``, and ``message`` how the solve ended. An orbit that did not converge
    is returned all the same, its outputs those of where Newton stopped.

    Per response (``Scene.responses``): ``maximum``, ``minimum`` [m] over the period (on
    the series), ``peak`` = max |x|, ``mean``, ``mean_square`` (E_ρ). ``energy_per_cycle``
    per excitation period (``cycle.EnergyPerCycle``), ``kinetic_peak`` T_max [J].
    ``exponents`` [1/s] and ``multipliers``: Hill's (``hill``; empty where stability was
    not asked for), by descending modulus of the multiplier. ``hysteresis_periods``: the
    periods the elastic contacts' sliders were marched for their hysteresis to repeat.
    ``smooth``: whether the contacts' forces are smooth over the orbit — no contact
    opens and closes, no elastic contact both sticks and slips —, the orbits on which
    Hill's multipliers converge to the exact ones; where not, they are not to be
    trusted (``hill``), nor ``stable``: ``certify`` gives the exact multipliers.
    ``sectors``: N where a tuned ring of N sectors was solved on one (``sectors``), the
    rest of it by the harmonics' phase lag; 1 where the whole group was solved. Every
    output is the whole group's either way.
    """

    scene: Scene
    harmonic_count: int
    periods: int
    samples: int
    coefficients: np.ndarray
    contact_coefficients: np.ndarray
    force_coefficients: np.ndarray
    stretches: np.ndarray
    residual: float
    tolerance: float
    iterations: int
    scale: float
    message: str
    exponents: np.ndarray
    multipliers: np.ndarray
    maximum: np.ndarray
    minimum: np.ndarray
    mean: np.ndarray
    mean_square: np.ndarray
    peak: np.ndarray
    energy_per_cycle: EnergyPerCycle
    kinetic_peak: float
    hysteresis_periods: int
    smooth: bool
    sectors: int = 1

    def __post_init__(self):
        check_record(self)

    @property
    def converged(self) -> bool:
        """Whether the residual meets the tolerance."""
        return bool(self.residual <= self.tolerance)

    @property
    def frequency(self) -> float:
        """ω = l Ω / periods [rad/s] (2π f / periods at an excitation frequency f of
        its own, ``Excitation.frequency``), the series' fundamental."""
        return self.scene.arrays.excitation_frequency / self.periods

    @property
    def period(self) -> float:
        """The orbit's period, periods · T_e [s]."""
        return self.periods * self.scene.excitation_period

    @property
    def stable(self) -> bool:
        """Whether every one of Hill's multipliers lies inside the unit circle: to be
        trusted on ``smooth`` orbits only (``hill``); a ValueError where they were not
        computed."""
        if not len(self.multipliers):
            raise ValueError("HarmonicOrbit.stable: the multipliers were not computed "
                             "(harmonic_balance(..., stability=True) computes them)")
        return bool(np.abs(self.multipliers[0]) < UNIT_CIRCLE)

    @property
    def state(self) -> np.ndarray:
        """y = (q(0), q̇(0)[, u(0)]): the state at t = 0 mod T by the nodes' own degrees of
        freedom, as ``PeriodicOrbit.state``."""
        return np.concatenate(self.initial)

    @property
    def initial(self) -> tuple[np.ndarray, ...]:
        """(q0, q̇0[, u0 [m]]) at t = 0, by the nodes' own degrees of freedom as
        ``simulate``'s ``initial`` and ``periodic_orbit``'s ``guess`` take them (for blades
        x0 [m], ẋ0 [m/s])."""
        x = self.at(np.zeros(1))[0]
        v = self.at(np.zeros(1), order=1)[0]
        return (x, v) + ((self.stretches.copy(),) if len(self.stretches) else ())

    @property
    def times(self) -> np.ndarray:
        """t_n = n T / N [s]: the samples the contact forces are computed at."""
        return np.arange(self.samples) * (self.period / self.samples)

    def contact_forces(self):
        """The contacts' forces over the period at ``times`` (``aft.ContactForces``):
        ``normal`` N (samples × interfaces) [N], ``friction`` along each interface's
        tangents t₁, t₂ (samples × interfaces × 2) [N], as the balance computed them."""
        model = harmonic_model(self.scene, self.periods, "HarmonicOrbit.contact_forces")
        basis = FourierBasis(self.harmonic_count, self.frequency, self.samples)
        return forces_in_time(model, basis, self.contact_coefficients, False)

    def at(self, times, order: int = 0) -> np.ndarray:
        """The ``order``-th time derivative of the nodes' own degrees of freedom q at
        ``times`` [s] (len(times) × n, the columns of ``coefficients``)."""
        return series_matrix(self.harmonic_count, self.frequency, np.atleast_1d(times),
                             order) @ self.coefficients

    def response(self, blade, times) -> np.ndarray:
        """``blade``'s response (``Scene.response_position``) at ``times`` [s]."""
        return self.scene.response_of(self.at(times), blade)

    def harmonics_of(self, coefficients: np.ndarray, order: int) -> Harmonics:
        """The ``Harmonics`` up to ``order`` of a series given by its coefficients
        (orders above H have none: amplitude 0)."""
        amplitudes, phases = np.zeros(order + 1), np.zeros(order + 1)
        kept = min(order, self.harmonic_count)
        amplitudes[0] = coefficients[0]
        a, b = coefficients[1:2 * kept:2], coefficients[2:2 * kept + 1:2]
        # a cos θ + b sin θ = A sin(θ + φ): A = √(a² + b²), φ = atan2(a, b)
        amplitudes[1:kept + 1] = np.hypot(a, b)
        phases[1:kept + 1] = np.arctan2(a, b)
        n = np.arange(order + 1)
        return Harmonics(order=n, frequencies=n * self.frequency / (2.0 * math.pi),
                         amplitudes=amplitudes, phases=phases)

    def harmonics(self, blade, order: int = 5) -> Harmonics:
        """``blade``'s harmonics up to ``order`` (as ``PeriodicOrbit.harmonics``:
        r = A_0 + Σ_n A_n sin(n ω t + φ_n)), read off the series."""
        row = self.scene.response_matrix[self.scene.response_position(blade)]
        return self.harmonics_of(self.coefficients @ row, _order(order))

    def slip_harmonics(self, interface: int, order: int = 5) -> Harmonics:
        """The harmonics of interface ``interface``'s tangential relative displacement
        along t₁ (as ``PeriodicOrbit.slip_harmonics``)."""
        arrays = self.scene.arrays
        rows = arrays.slip_rows(1)  # over the engine's coordinates, which from_dofs gives
        count = len(rows)
        if isinstance(interface, bool) or not isinstance(interface, int | np.integer) \
                or not 0 <= interface < count:
            raise ValueError(f"HarmonicOrbit.slip_harmonics: interface must be a position "
                             f"0 … {count - 1}, got {interface!r}")
        row = rows[interface, :arrays.n_blades]
        return self.harmonics_of(from_dofs(arrays.layout, self.coefficients) @ row,
                                 _order(order))


def _order(order) -> int:
    if isinstance(order, bool) or not isinstance(order, int | np.integer) or order < 0:
        raise ValueError(f"HarmonicOrbit.harmonics: order must be an int ≥ 0, got {order!r}")
    return int(order)


def kinetic_peak(coefficients: np.ndarray, mass: np.ndarray, frequency: float,
                 harmonics: int) -> float:
    """max_t ½ ẋᵀ M ẋ [J] of the series of ``coefficients`` by the coordinates whose mass
    matrix is ``mass`` (the engine's, where it is diagonal): the largest of 32 samples
    per period of the highest harmonic, refined by Newton's method on d/dt(½ẋᵀMẋ) =
    ẋᵀMẍ = 0."""
    count = 32 * max(harmonics, 1)
    step = 2.0 * math.pi / frequency / count
    times = np.arange(count) * step
    velocity = series_matrix(harmonics, frequency, times, 1) @ coefficients
    energy = 0.5 * np.einsum("ti,ij,tj->t", velocity, mass, velocity)
    best_time, best = times[int(np.argmax(energy))], float(energy.max())
    at = best_time
    for _ in range(8):
        v, a, jerk = (series_matrix(harmonics, frequency, [at], order)[0] @ coefficients
                      for order in (1, 2, 3))
        slope = v @ mass @ a
        curvature = a @ mass @ a + v @ mass @ jerk
        if curvature >= 0.0:
            break
        at = at - float(np.clip(slope / curvature, -step, step))
    v = series_matrix(harmonics, frequency, [at], 1)[0] @ coefficients
    return max(best, 0.5 * float(v @ mass @ v))


def energy_per_cycle(model, basis: FourierBasis, coefficients: np.ndarray,
                     contact_coefficients: np.ndarray, forces) -> EnergyPerCycle:
    """The ``EnergyPerCycle`` per excitation period of the series of ``coefficients``, by
    the engine's coordinates as ``model`` holds them: the excitation's work
    ∫Q·ẋ and the damping's ∫ẋᵀCẋ from the coefficients (Parseval: exact for the
    series), the friction's ∫f·ṙ_t and the contacts' ∫N δ̇ from the samples the
    forces were computed at (exact for their series of degree H, ṙ having no higher
    harmonics)."""
    from .fourier import mean_product, real_coefficients
    period = basis.period
    rate = derivative_matrix(basis.harmonics, basis.frequency) @ coefficients
    load = real_coefficients(model.load_coefficients(basis.harmonics))
    excitation = period * float(mean_product(load, rate).sum())
    damping = period * float(mean_product(rate, rate @ model.damping.T).sum())
    contact_rate = basis.rate @ contact_coefficients
    friction = contact = 0.0
    step = period / basis.samples
    for c in model.contacts:
        local = contact_rate[:, c.columns]
        friction += step * float(np.sum(forces.friction[:, c.index]
                                        * (local @ c.tangents.T)))
        contact += step * float(forces.normal[:, c.index] @ (local @ c.normal))
    periods = model.periods
    return EnergyPerCycle(excitation=excitation / periods, damping=damping / periods,
                          friction=friction / periods, contact=contact / periods)
