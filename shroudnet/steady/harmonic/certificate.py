"""The certificate of a harmonic-balance orbit: the exact orbit it stands for, and its
error.

Shooting (``periodic_orbit``) from the series' state at t = 0 — every one of the nodes'
own degrees of freedom and its velocity, and the elastic contacts' stretches —
converges to the exact periodic orbit near it, with every switch located and its
Floquet multipliers from the monodromy matrix. Against it the harmonic-balance orbit
is measured in what a user reads: its state at t = 0, the amplitude of every response,
the energy per cycle and the multipliers. A series whose exact orbit is not there
(Newton's shooting does not converge from it) has no certificate: ``ConvergenceError``
says so.
"""

from __future__ import annotations

import time
from dataclasses import dataclass

import numpy as np

from contact_laws import check_instance, check_real

from ...analysis.stability import TANGENT_METHOD
from ...checked_records import check_record
from ...run.methods import EVENT_TOLERANCE, Accuracy, Adaptive, check_event_tolerance
from ..orbits import SMALLEST_TOLERANCE, PeriodicOrbit, periodic_orbit, state_weights
from .orbit import HarmonicOrbit

#: The accuracy of the exact orbits certificates are made with by default:
#: ``periodic_orbit``'s own method (rtol 1e-10), solved to a residual of 1e-9 of the
#: state: far below the errors of the series they judge but for the smoothest, and above
#: the integration noise of the map (the six-blade packet with elastic faces stalls near
#: 1.5e-10 at some speeds, where 1e-10 is asked).
CERTIFYING_METHOD = TANGENT_METHOD
CERTIFYING_TOLERANCE = 1e-9


@dataclass(frozen=True)
class Certificate:
    """A harmonic-balance orbit (``harmonic``) against the exact orbit shooting finds
    from it (``exact``).

    ``state_error``: max |y_HB − y| of the state at t = 0 by the nodes' own degrees of
    freedom (``HarmonicOrbit.state``, ``PeriodicOrbit.state``) over the exact orbit's
    state scale (velocities over l Ω, as ``periodic_orbit`` weighs them), or the exact orbit's
    residual where that is larger (a series whose state meets the shooting's tolerance is
    its own start: its error is below that residual, not 0); ``amplitude_error``:
    max over the responses of |A_HB − A| over the largest exact amplitude A;
    ``energy_error``: |W_HB − W| / W of the energy dissipated per excitation period;
    ``multiplier_errors``: for each of Hill's multipliers, the distance to the nearest
    exact one (empty where the orbit has none: ``stability=False``). ``seconds``: the
    time the exact orbit took [s].
    """

    harmonic: HarmonicOrbit
    exact: PeriodicOrbit
    state_error: float
    amplitude_error: float
    energy_error: float
    multiplier_errors: np.ndarray
    seconds: float

    def __post_init__(self):
        check_record(self)

    @property
    def multiplier_error(self) -> float:
        """The largest of ``multiplier_errors`` (NaN where there are none)."""
        return float(self.multiplier_errors.max()) if len(self.multiplier_errors) else \
            float("nan")


def certify(orbit: HarmonicOrbit, *, method: Adaptive | Accuracy = CERTIFYING_METHOD,
            tolerance: float = CERTIFYING_TOLERANCE,
            event_tolerance: float = EVENT_TOLERANCE) -> Certificate:
    """The ``Certificate`` of a harmonic-balance ``orbit``: the exact orbit by shooting
    from its state at t = 0 (``HarmonicOrbit.initial``, by the nodes' own degrees of
    freedom: ``periodic_orbit``'s ``guess``), and the series' errors against it (module
    docstring). A branch of orbits is certified at chosen points by certifying its
    orbits (``Branch.orbits[i]``).

    Parameters
    ----------
    orbit : HarmonicOrbit
    method, tolerance, event_tolerance
        As ``periodic_orbit``: the exact orbit's accuracy (by default ``CERTIFYING_METHOD``
        and ``CERTIFYING_TOLERANCE``, far tighter than a series' but for the smoothest;
        the state error reads no less than the residual reached).

    Raises
    ------
    ConvergenceError
        Shooting does not converge from the series' state: no exact orbit is near it.
    """
    check_instance("certify", "orbit", orbit, HarmonicOrbit, expected="a HarmonicOrbit")
    check_instance("certify", "method", method, (Adaptive, Accuracy),
                   expected="Adaptive(...) or Accuracy(...)")
    check_real("certify", "tolerance", tolerance, low=SMALLEST_TOLERANCE, high=1e-3)
    check_event_tolerance("certify", event_tolerance)
    began = time.perf_counter()
    exact = periodic_orbit(orbit.scene, orbit.periods, guess=orbit.initial, method=method,
                           tolerance=tolerance, event_tolerance=event_tolerance,
                           symmetry="none")
    seconds = time.perf_counter() - began
    weights = state_weights(exact.scene, exact.state)
    amplitudes = 0.5 * (exact.maximum - exact.minimum)
    series = 0.5 * (orbit.maximum - orbit.minimum)
    dissipated = exact.energy_per_cycle.dissipated
    errors = np.array([np.abs(exact.multipliers - m).min() for m in orbit.multipliers])
    return Certificate(
        harmonic=orbit, exact=exact,
        state_error=max(float(np.abs(weights * (orbit.state - exact.state)).max()),
                        exact.residual),
        amplitude_error=float(np.abs(series - amplitudes).max() / amplitudes.max()),
        energy_error=float(abs(orbit.energy_per_cycle.dissipated - dissipated)
                           / abs(dissipated)),
        multiplier_errors=errors, seconds=seconds)
