r"""Prescribed motions: nodes whose displacement is a given function of time.

A prescribed-motion node (``BladeGroup.add_prescribed``) stands wherever a fixed node may: a
moving belt under a block, a shaker under a blade, a casing that wobbles. Its displacement
x_p(t) [m] along the blades' direction is one of

- ``ConstantVelocity``:  x_p = x_0 + V t;
- ``HarmonicMotion``:    x_p = A sin(2π f t + φ);
- ``MotionTable``:       the C² cubic spline through measured points (t_k, x_k).

Interfaces and couplings see the relative motion u = x_i − x_j, so friction against a
prescribed node acts on the relative slip velocity, and a block stuck to a belt moves with
it. The integrator carries each prescribed node as a state driven by its acceleration
ẍ_p(t), which every motion gives in closed form (a spline's is piecewise linear); the
work the motion does on the group is counted as input work (``EnergyLedger``).
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass, field
from functools import cached_property

import numpy as np
from scipy.interpolate import CubicSpline

from contact_laws import check_real


@dataclass(frozen=True, kw_only=True)
class ConstantVelocity:
    """x_p(t) = x_0 + V t: a belt or a slider moving at constant speed.

    Parameters
    ----------
    velocity : float
        V [m/s], any sign.
    position : float
        x_0 [m] at t = 0.
    """

    velocity: float
    position: float = 0.0

    def __post_init__(self):
        check_real("ConstantVelocity", "velocity", self.velocity, unit="m/s")
        check_real("ConstantVelocity", "position", self.position, unit="m")

    def displacement_at(self, t):
        """x_p(t) [m]."""
        return self.position + self.velocity * np.asarray(t, dtype=float)

    def velocity_at(self, t):
        """ẋ_p(t) [m/s]."""
        return np.full_like(np.asarray(t, dtype=float), self.velocity)

    def acceleration_at(self, t):
        """ẍ_p(t) = 0 [m/s²]."""
        return np.zeros_like(np.asarray(t, dtype=float))

    def terms(self) -> MotionTerms:
        """ẍ_p = 0."""
        return MotionTerms()


@dataclass(frozen=True, kw_only=True)
class HarmonicMotion:
    """x_p(t) = A sin(2π f t + φ): a shaker, or a casing that wobbles.

    Parameters
    ----------
    amplitude : float
        A ≥ 0 [m].
    frequency : float
        f > 0 [Hz].
    phase : float
        φ [rad].
    """

    amplitude: float
    frequency: float
    phase: float = 0.0

    def __post_init__(self):
        check_real("HarmonicMotion", "amplitude", self.amplitude, low=0.0, unit="m")
        check_real("HarmonicMotion", "frequency", self.frequency, low=0.0, low_open=True,
                   unit="Hz")
        check_real("HarmonicMotion", "phase", self.phase, unit="rad")

    @property
    def angular_frequency(self) -> float:
        """ω = 2π f [rad/s]."""
        return 2.0 * math.pi * self.frequency

    def displacement_at(self, t):
        """x_p(t) [m]."""
        return self.amplitude * np.sin(self.angular_frequency * np.asarray(t, dtype=float)
                                       + self.phase)

    def velocity_at(self, t):
        """ẋ_p(t) [m/s]."""
        omega = self.angular_frequency
        return self.amplitude * omega * np.cos(omega * np.asarray(t, dtype=float) + self.phase)

    def acceleration_at(self, t):
        """ẍ_p(t) [m/s²]."""
        omega = self.angular_frequency
        return -self.amplitude * omega**2 * np.sin(omega * np.asarray(t, dtype=float)
                                                   + self.phase)

    def terms(self) -> MotionTerms:
        """ẍ_p = −A ω² sin(ω t + φ)."""
        return MotionTerms(amplitude=self.amplitude, angular_frequency=self.angular_frequency,
                           phase=self.phase)


@dataclass(frozen=True, kw_only=True)
class MotionTable:
    """x_p(t): the C² cubic spline (not-a-knot ends) through the points (t_k, x_k).

    A run must stay inside the table, t_0 ≤ t ≤ t_last: ``simulate`` refuses one that
    would leave it. Two points give a straight line, three a parabola.

    Parameters
    ----------
    times : sequence of float
        t_k [s], at least 2, finite and strictly increasing.
    displacements : sequence of float
        x_k [m], finite, one per time.
    """

    times: tuple[float, ...]
    displacements: tuple[float, ...]

    def __post_init__(self):
        times = _finite_sequence(self.times, "times", "s")
        displacements = _finite_sequence(self.displacements, "displacements", "m")
        if len(times) < 2:
            raise ValueError(f"MotionTable.times needs at least 2 points, got {len(times)}")
        if len(displacements) != len(times):
            raise ValueError(f"MotionTable.displacements needs one value per time: "
                             f"{len(displacements)} displacements for {len(times)} times")
        steps = np.diff(times)
        if np.any(steps <= 0.0):
            k = int(np.argmax(steps <= 0.0)) + 1
            raise ValueError(f"MotionTable.times must increase strictly: times[{k}] = "
                             f"{times[k]:g} s follows times[{k - 1}] = {times[k - 1]:g} s")
        object.__setattr__(self, "times", tuple(map(float, times)))
        object.__setattr__(self, "displacements", tuple(map(float, displacements)))

    @cached_property
    def spline(self) -> CubicSpline:
        """The spline x_p(t) through the points."""
        return CubicSpline(self.times, self.displacements)

    @property
    def span(self) -> tuple[float, float]:
        """(t_0, t_last) [s]: where the table defines the motion."""
        return self.times[0], self.times[-1]

    def displacement_at(self, t):
        """x_p(t) [m]."""
        return self.spline(np.asarray(t, dtype=float))

    def velocity_at(self, t):
        """ẋ_p(t) [m/s]."""
        return self.spline(np.asarray(t, dtype=float), 1)

    def acceleration_at(self, t):
        """ẍ_p(t) [m/s²], linear between the knots."""
        return self.spline(np.asarray(t, dtype=float), 2)

    def terms(self) -> MotionTerms:
        """ẍ_p linear between the knots, where the spline's second derivative is given."""
        times = np.asarray(self.times)
        return MotionTerms(knot_times=times, knot_accelerations=self.spline(times, 2))


Motion = ConstantVelocity | HarmonicMotion | MotionTable


@dataclass(frozen=True)
class MotionTerms:
    """A motion's acceleration as the integrator evaluates it:

        ẍ_p(t) = −A ω² sin(ω t + φ) + a(t),

    a(t) the linear interpolation of ``knot_accelerations`` [m/s²] at ``knot_times`` [s]
    (none: a = 0). Every ``Motion`` is one such sum."""

    amplitude: float = 0.0
    angular_frequency: float = 0.0
    phase: float = 0.0
    knot_times: np.ndarray = field(default_factory=lambda: np.zeros(0))
    knot_accelerations: np.ndarray = field(default_factory=lambda: np.zeros(0))


def motion_span(motion: Motion) -> tuple[float, float]:
    """(earliest, latest) time [s] at which ``motion`` is defined."""
    return motion.span if isinstance(motion, MotionTable) else (-math.inf, math.inf)


def _finite_sequence(values, field, unit) -> np.ndarray:
    if isinstance(values, str | bytes) or not isinstance(values, Sequence | np.ndarray):
        raise TypeError(f"MotionTable.{field} must be a sequence of numbers [{unit}], got "
                        f"{type(values).__name__} {values!r}")
    try:
        array = np.asarray(values, dtype=float)
    except (TypeError, ValueError) as error:
        raise TypeError(f"MotionTable.{field} must hold numbers [{unit}]: {error}") from error
    if array.ndim != 1:
        raise ValueError(f"MotionTable.{field} must be a flat sequence, got shape "
                         f"{array.shape}")
    bad = np.flatnonzero(~np.isfinite(array))
    if len(bad):
        raise ValueError(f"MotionTable.{field}[{bad[0]}] must be finite, got {array[bad[0]]}")
    return array
