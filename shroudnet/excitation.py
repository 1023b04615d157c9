"""Excitation: the aerodynamic force on each blade (paper §2).

Q_i(t) = q0 + Σ_{n≥1} q_n sin(n l Ω t + φ_i), with engine order l, rotating speed Ω [rad/s]
and a phase φ_i per blade from a phase pattern.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass

import numpy as np

from contact_laws import check_real


@dataclass(frozen=True)
class AntiPhase:
    """φ_{i+1} − φ_i = π: neighbouring blades pushed in opposition (the paper's choice)."""

    def phases(self, n_blades: int) -> np.ndarray:
        return math.pi * np.arange(n_blades, dtype=float)


@dataclass(frozen=True)
class TravellingWave:
    """φ_i = 2π ND i / N: a wave travelling round a ring of N blades with ND nodal diameters."""

    nodal_diameter: int

    def __post_init__(self):
        if isinstance(self.nodal_diameter, bool) or not isinstance(self.nodal_diameter, int):
            raise TypeError(f"TravellingWave.nodal_diameter must be an int, "
                            f"got {self.nodal_diameter!r}")

    def phases(self, n_blades: int) -> np.ndarray:
        return 2.0 * math.pi * self.nodal_diameter * np.arange(n_blades) / n_blades


@dataclass(frozen=True)
class ExplicitPhases:
    """φ_i given one per blade [rad]."""

    values: tuple[float, ...]

    def __post_init__(self):
        values = tuple(check_real("ExplicitPhases", "values", v, unit="rad") for v in self.values)
        object.__setattr__(self, "values", values)

    def phases(self, n_blades: int) -> np.ndarray:
        if len(self.values) != n_blades:
            raise ValueError(f"ExplicitPhases has {len(self.values)} phases for "
                             f"{n_blades} blades")
        return np.array(self.values)


PhasePattern = AntiPhase | TravellingWave | ExplicitPhases


@dataclass(frozen=True, kw_only=True)
class Excitation:
    """The harmonic force on every blade, locked to the rotation by the engine order.

    Parameters
    ----------
    engine_order : int
        l ≥ 1: excitation frequency f_e = l Ω/2π (the paper's l = 2).
    amplitudes : sequence of float
        (q0, q1, …, qn) [N]: the mean force q0 and the amplitude q_n of the n-th harmonic.
    phases : AntiPhase, TravellingWave, ExplicitPhases or a sequence of float
        The phase pattern φ_i; a sequence is taken as explicit phases [rad].
    """

    engine_order: int
    amplitudes: tuple[float, ...]
    phases: PhasePattern

    def __post_init__(self):
        if (isinstance(self.engine_order, bool) or not isinstance(self.engine_order, int)
                or self.engine_order < 1):
            raise ValueError(f"Excitation.engine_order must be an int >= 1, "
                             f"got {self.engine_order!r}")
        amplitudes = tuple(check_real("Excitation", "amplitudes", q, unit="N")
                           for q in self.amplitudes)
        if not amplitudes:
            raise ValueError("Excitation.amplitudes needs at least q0 (the mean force)")
        object.__setattr__(self, "amplitudes", amplitudes)
        if not isinstance(self.phases, AntiPhase | TravellingWave | ExplicitPhases):
            if not isinstance(self.phases, Sequence | np.ndarray):
                raise TypeError("Excitation.phases must be AntiPhase(), TravellingWave(nd), "
                                f"ExplicitPhases(...) or a sequence of floats, got {self.phases!r}")
            object.__setattr__(self, "phases", ExplicitPhases(tuple(self.phases)))

    def frequency(self, speed_rpm: float) -> float:
        """f_e = l Ω/60 [Hz] at ``speed_rpm`` [rev/min]."""
        return self.engine_order * speed_rpm / 60.0
