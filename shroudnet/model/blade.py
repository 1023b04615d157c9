"""Blades: the nodes of a group, each a lumped mass on a spring in the tangential direction x.

A blade's stiffness either is given or follows from its first dynamic frequency f_d1(Ω),
which centrifugal stiffening raises with the rotating speed: k(Ω) = m (2π f_d1(Ω))².
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from contact_laws import check_array, check_real


@dataclass(frozen=True, kw_only=True)
class ConstantFrequency:
    """f_d1(Ω) = f: a frequency that does not depend on speed.

    Parameters
    ----------
    hz : float
        f > 0 [Hz].
    """

    hz: float

    def __post_init__(self):
        check_real("ConstantFrequency", "hz", self.hz, low=0.0, low_open=True, unit="Hz")

    def at(self, speed_rpm: float) -> float:
        """f_d1 [Hz] at the rotating speed ``speed_rpm`` [rev/min]."""
        return float(self.hz)


@dataclass(frozen=True, kw_only=True)
class Southwell:
    """f_d1² = f0² + B (Ω/60)²: Southwell's law of centrifugal stiffening.

    Parameters
    ----------
    f0 : float
        The frequency at rest, f0 > 0 [Hz].
    coefficient : float
        The Southwell coefficient B ≥ 0 [-], with Ω/60 the rotating frequency in Hz.
    """

    f0: float
    coefficient: float

    def __post_init__(self):
        check_real("Southwell", "f0", self.f0, low=0.0, low_open=True, unit="Hz")
        check_real("Southwell", "coefficient", self.coefficient, low=0.0)

    def at(self, speed_rpm: float) -> float:
        """f_d1 [Hz] at the rotating speed ``speed_rpm`` [rev/min]."""
        return math.sqrt(self.f0**2 + self.coefficient * (speed_rpm / 60.0) ** 2)


@dataclass(frozen=True, kw_only=True)
class FrequencyTable:
    """f_d1(Ω) interpolated linearly in a table, e.g. from a finite-element run.

    Parameters
    ----------
    speeds_rpm : sequence of float
        Strictly increasing rotating speeds [rev/min], at least two.
    frequencies : sequence of float
        f_d1 > 0 at those speeds [Hz].

    A speed outside the table is an error, not an extrapolation.
    """

    speeds_rpm: tuple[float, ...]
    frequencies: tuple[float, ...]

    def __post_init__(self):
        speeds = tuple(float(s) for s in check_array(
            "FrequencyTable", "speeds_rpm", self.speeds_rpm, shape=(None,), low=0.0,
            unit="rpm"))
        freqs = tuple(float(f) for f in check_array(
            "FrequencyTable", "frequencies", self.frequencies, shape=(None,), low=0.0,
            low_open=True, unit="Hz"))
        if len(speeds) < 2 or len(speeds) != len(freqs):
            raise ValueError("FrequencyTable needs at least two speeds_rpm and as many "
                             f"frequencies, got {len(speeds)} and {len(freqs)}")
        if any(b <= a for a, b in zip(speeds, speeds[1:])):
            raise ValueError(f"FrequencyTable.speeds_rpm must increase strictly, got {speeds}")
        object.__setattr__(self, "speeds_rpm", speeds)
        object.__setattr__(self, "frequencies", freqs)

    def at(self, speed_rpm: float) -> float:
        """f_d1 [Hz] at the rotating speed ``speed_rpm`` [rev/min]."""
        low, high = self.speeds_rpm[0], self.speeds_rpm[-1]
        if not low <= speed_rpm <= high:
            raise ValueError(f"speed {speed_rpm:g} rpm is outside the FrequencyTable range "
                             f"[{low:g}, {high:g}] rpm")
        return float(np.interp(speed_rpm, self.speeds_rpm, self.frequencies))


FrequencyModel = ConstantFrequency | Southwell | FrequencyTable


def frequency_of(model: FrequencyModel, speed_rpm: float) -> float:
    """f_d1 [Hz] of the frequency ``model`` at ``speed_rpm`` [rev/min]; inf where its
    arithmetic overflows a float (Southwell's law squares the speed: beyond about 1e155
    rpm), so that the caller refuses it by name."""
    try:
        return model.at(speed_rpm)
    except OverflowError:
        return math.inf


@dataclass(frozen=True, kw_only=True)
class Blade:
    """A blade reduced to its shroud: m ẍ + c ẋ + k(Ω) x = s Q(t) + interface forces.

    Give exactly one of ``stiffness`` and ``frequency``.

    Parameters
    ----------
    mass : float
        m > 0 [kg].
    damping : float
        Viscous damping c ≥ 0 [N·s/m].
    stiffness : float, optional
        k ≥ 0 [N/m], independent of speed. k = 0 is a node with no spring to ground (an
        under-platform damper, a blade held by a disc through couplings): the scene then
        needs couplings or interfaces that hold it (``Scene`` refuses a group that could
        drift away as a rigid body).
    frequency : float or frequency model, optional
        f_d1 [Hz] (a float is a constant frequency) or a model of f_d1(Ω):
        ``ConstantFrequency``, ``Southwell`` or ``FrequencyTable``; then k = m (2π f_d1)².
    excitation_scale : float
        s [-], the signed factor on the excitation force Q(t) this node receives: 1 for
        a blade of the row, 0 for a node the flow does not load (a damper or a platform
        modelled as a node), another value for a blade of different aerodynamic load or a
        mode's participation factor, whose sign is the direction it is pushed in.
    """

    mass: float
    damping: float
    stiffness: float | None = None
    frequency: FrequencyModel | float | None = None
    excitation_scale: float = 1.0

    def __post_init__(self):
        check_real("Blade", "mass", self.mass, low=0.0, low_open=True, unit="kg")
        check_real("Blade", "damping", self.damping, low=0.0, unit="N·s/m")
        check_real("Blade", "excitation_scale", self.excitation_scale)
        if (self.stiffness is None) == (self.frequency is None):
            raise ValueError("Blade needs exactly one of stiffness= [N/m] and frequency= "
                             "[Hz or a frequency model]")
        if self.stiffness is not None:
            check_real("Blade", "stiffness", self.stiffness, low=0.0, unit="N/m")
        elif not isinstance(self.frequency, ConstantFrequency | Southwell | FrequencyTable):
            check_real("Blade", "frequency", self.frequency, low=0.0, low_open=True, unit="Hz")
            object.__setattr__(self, "frequency", ConstantFrequency(hz=self.frequency))

    def stiffness_at(self, speed_rpm: float) -> float:
        """k(Ω) [N/m] at the rotating speed ``speed_rpm`` [rev/min]."""
        if self.stiffness is not None:
            return float(self.stiffness)
        try:
            stiffness = self.mass * (2.0 * math.pi
                                     * frequency_of(self.frequency, speed_rpm)) ** 2
        except OverflowError:
            stiffness = math.inf
        if not math.isfinite(stiffness):
            raise ValueError(f"Blade.stiffness_at: k(Ω) = m (2π f_d1(Ω))² overflows a float "
                             f"at speed_rpm = {speed_rpm:g} ({self.frequency!r}); check the "
                             "units of the speed (rev/min)")
        return stiffness

    def frequency_at(self, speed_rpm: float) -> float:
        """The blade's own natural frequency sqrt(k/m)/2π [Hz] at ``speed_rpm``."""
        return math.sqrt(self.stiffness_at(speed_rpm) / self.mass) / (2.0 * math.pi)
