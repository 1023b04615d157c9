"""What harmonics cost and buy: harmonic balance against the exact orbit, as H grows.

For a scene, the exact periodic orbit is found once by shooting (started from the
series of most harmonics, ``certify``); each harmonic-balance orbit of H harmonics is
then judged as a certificate judges it (the amplitude of every response over the
largest, the energy dissipated per cycle, the state at t = 0), and timed: the CPU time
of ``harmonic_balance`` from the linear response, the median of ``repeats``, against the
exact orbit's. The table shows what each digit of accuracy costs, as
``studies.precision`` shows it for the time integrators.
"""

from __future__ import annotations

import statistics
import time
from collections.abc import Sequence
from dataclasses import dataclass

import numpy as np

from contact_laws import check_int

from ..model.scene import Scene
from ..steady.harmonic.balance import harmonic_balance
from ..steady.harmonic.certificate import certify
from ..steady.orbits import PeriodicOrbit, state_weights

#: The harmonics a study runs by default.
HARMONICS = (1, 3, 5, 7, 9, 15, 25)


@dataclass(frozen=True, eq=False)
class HarmonicPrecision:
    """Per number of harmonics (``harmonics``): the time samples, the CPU seconds of one
    solve, and the relative errors of the amplitudes, the energy dissipated per cycle
    and the state at t = 0 against ``exact``, found in ``exact_seconds``."""

    scene: Scene
    harmonics: np.ndarray
    samples: np.ndarray
    seconds: np.ndarray
    amplitude_error: np.ndarray
    energy_error: np.ndarray
    state_error: np.ndarray
    exact: PeriodicOrbit
    exact_seconds: float

    def rate(self, errors: str = "amplitude_error", fewest: int = 5) -> float:
        """The slope of log(error) against log(H) fitted over H ≥ ``fewest``: the order
        at which ``errors`` fall."""
        keep = self.harmonics >= fewest
        values = getattr(self, errors)[keep]
        return float(np.polyfit(np.log(self.harmonics[keep]), np.log(values), 1)[0])

    def rows(self) -> list[tuple]:
        """(H, N, ms, amplitude error, energy error, state error) by H, then the exact
        orbit's ("exact", "", ms, 0, 0, 0)."""
        rows = [(int(h), int(n), 1e3 * s, a, e, y) for h, n, s, a, e, y in zip(
            self.harmonics, self.samples, self.seconds, self.amplitude_error,
            self.energy_error, self.state_error)]
        return rows + [("exact", "", 1e3 * self.exact_seconds, 0.0, 0.0, 0.0)]


def harmonic_precision(scene: Scene, harmonics: Sequence[int] = HARMONICS, *,
                       repeats: int = 3) -> HarmonicPrecision:
    """The ``HarmonicPrecision`` of ``scene`` at each of ``harmonics`` (module
    docstring)."""
    harmonics = np.array(sorted(check_int("harmonic_precision", "harmonics", h, low=0)
                                for h in harmonics))
    repeats = check_int("harmonic_precision", "repeats", repeats, low=1)
    orbits, seconds = [], []
    for h in harmonics:
        times = []
        for _ in range(repeats):
            began = time.process_time()
            orbit = harmonic_balance(scene, int(h), stability=False)
            times.append(time.process_time() - began)
        orbits.append(orbit)
        seconds.append(statistics.median(times))
    began = time.process_time()
    exact = certify(orbits[-1]).exact
    exact_seconds = time.process_time() - began
    weights = state_weights(scene, exact.state)
    amplitudes = 0.5 * (exact.maximum - exact.minimum)
    dissipated = exact.energy_per_cycle.dissipated
    return HarmonicPrecision(
        scene=scene, harmonics=harmonics, samples=np.array([o.samples for o in orbits]),
        seconds=np.array(seconds),
        amplitude_error=np.array([np.abs(0.5 * (o.maximum - o.minimum) - amplitudes).max()
                                  / amplitudes.max() for o in orbits]),
        energy_error=np.array([abs(o.energy_per_cycle.dissipated - dissipated) / dissipated
                               for o in orbits]),
        state_error=np.array([np.abs(weights * (o.state - exact.state)).max()
                              for o in orbits]),
        exact=exact, exact_seconds=exact_seconds)
