"""Excitation: the aerodynamic force on each blade (paper §2).

Q_i(t) = s_i [q0 + Σ_{n≥1} q_n sin(n (l Ω t + φ_i))], with engine order l, rotating speed
Ω [rad/s], a phase φ_i per blade from a phase pattern and the blade's excitation scale s_i
(``Blade.excitation_scale``, 1 for a blade, 0 for an unforced node such as a damper).
Forced at a frequency f of its own (``Excitation.frequency``: a shaker, or a sweep in
frequency at a fixed speed), l Ω is 2π f instead, the speed setting only the stiffening
and the pattern φ_i keeping its engine order.

The force on a blade is a periodic function of the angle l Ω t + φ_i as a whole: the
pattern the blade meets one excitation period later is the same pattern shifted by φ_i.
Its n-th harmonic therefore carries the phase n φ_i. The paper (§2) writes φ_i on every
harmonic but keeps only q1, where the two readings agree; with the anti-phase pattern
(φ = 0, π, 2π, …) the even harmonics reach every blade in phase.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass, field

import numpy as np

from contact_laws import check_array, check_instance, check_int, check_real

#: Largest engine order accepted: l counts the vanes, struts or burners a blade passes per
#: revolution, a few hundred at most in any turbomachine; beyond 1000 the excitation
#: frequency l Ω/2π is taken for a mistake (10⁶ at 6000 rpm would be 10⁸ Hz).
ENGINE_ORDER_MAX = 1000


def _count(owner: str, n_blades: object) -> int:
    """The number of blades a pattern is asked for: an int ≥ 1."""
    return check_int(owner, "n_blades", n_blades, low=1)


@dataclass(frozen=True)
class AntiPhase:
    """φ_{i+1} − φ_i = π: neighbouring blades pushed in opposition (the paper's choice)."""

    def phases(self, n_blades: int) -> np.ndarray:
        """φ_i = π i [rad] for the blades by position."""
        n_blades = _count("AntiPhase.phases", n_blades)
        return math.pi * np.arange(n_blades, dtype=float)


@dataclass(frozen=True)
class TravellingWave:
    """φ_i = 2π ND i / N: a wave travelling round a ring of N blades with ND nodal diameters.

    ``nodal_diameter`` ND must lie in [0, N − 1]: ND and N − ND are the same number of
    nodal diameters travelling in opposite directions (N − ND is the backward wave), and
    ND ≥ N repeats the phases of ND mod N, so it is refused as a mistake. The range is
    checked when the number of blades is known (``phases``, or building a ``Scene``).
    For engine-order forcing of a tuned disc ND = l mod N: use ``EngineOrderWave()``.
    ``engine_order_wave`` is the ``EngineOrderWave`` a ``Scene`` made this wave from (None
    for a wave given as such): another group given the excitation takes that pattern again.
    """

    nodal_diameter: int
    engine_order_wave: EngineOrderWave | None = field(default=None, compare=False,
                                                      repr=False, kw_only=True)

    def __post_init__(self):
        object.__setattr__(self, "nodal_diameter",
                           check_int("TravellingWave", "nodal_diameter", self.nodal_diameter,
                                     low=0))
        _check_source("TravellingWave", self.engine_order_wave)

    def phases(self, n_blades: int) -> np.ndarray:
        """φ_i = 2π ND i / N [rad] for the N = ``n_blades`` blades by position."""
        n_blades = _count("TravellingWave.phases", n_blades)
        nd = self.nodal_diameter
        if nd >= n_blades:
            raise ValueError(f"TravellingWave.nodal_diameter must be in [0, N − 1] = "
                             f"[0, {n_blades - 1}] for N = {n_blades} blades, got {nd}: ND ≥ N "
                             f"repeats the phases of ND mod N = {nd % n_blades} (and N − ND is "
                             "ND travelling backwards)")
        return 2.0 * math.pi * self.nodal_diameter * np.arange(n_blades) / n_blades


@dataclass(frozen=True)
class EngineOrderWave:
    """The pattern engine order l makes on the blades of a disc of N blades.

    A blade at angular position 2π i/N meets a stationary pattern of l lobes with the phase
    φ_i = 2π l i / N. On a tuned disc whose N blades are the group's, this is
    ``TravellingWave(l mod N)`` (ND = l mod N). A packet of n < N blades that sits on a disc
    of N (``blades_on_disc``) takes the same phases for its n blades: a packet of 6 on a
    disc of 36 at l = 4 has 2π·4/36 = 40° between neighbours, not the 240° of a disc of 6.
    Without ``blades_on_disc`` the group is taken for the whole disc (N = its number of
    blades, or of sectors); a ``Scene`` whose group is an open packet then says so once, as
    a warning. A ``Scene`` replaces this pattern by the phases it stands for, since only
    then are l and the group both known; those phases remember this pattern
    (``engine_order_wave``), so that the scene's excitation given to another group (a ring
    grown by a blade) is the engine-order wave there too, not the phases of the first.
    """

    blades_on_disc: int | None = None

    def __post_init__(self):
        if self.blades_on_disc is not None:
            object.__setattr__(self, "blades_on_disc", check_int(
                "EngineOrderWave", "blades_on_disc", self.blades_on_disc, low=1))

    @staticmethod
    def nodal_diameter(n_blades: int, engine_order: int) -> int:
        """ND = l mod N."""
        n_blades = _count("EngineOrderWave.nodal_diameter", n_blades)
        return check_int("EngineOrderWave.nodal_diameter", "engine_order", engine_order,
                         low=1) % n_blades

    def wave(self, n_blades: int, engine_order: int) -> TravellingWave | ExplicitPhases:
        """The pattern this stands for on ``n_blades`` blades (or sectors) in a row: the
        ``TravellingWave`` of ND = l mod N where they are the whole disc, else the
        ``ExplicitPhases`` 2π l i / N (reduced to [0, 2π))."""
        n_blades = _count("EngineOrderWave.wave", n_blades)
        engine_order = check_int("EngineOrderWave.wave", "engine_order", engine_order, low=1)
        disc = n_blades if self.blades_on_disc is None else self.blades_on_disc
        if disc == n_blades:
            return TravellingWave(self.nodal_diameter(n_blades, engine_order),
                                  engine_order_wave=self)
        if n_blades > disc:
            raise ValueError(f"EngineOrderWave.blades_on_disc = {disc} is fewer than the "
                             f"group's {n_blades} blades (or sectors): a packet must fit on "
                             "its disc")
        steps = (engine_order * np.arange(n_blades)) % disc
        return ExplicitPhases(tuple(2.0 * math.pi * steps / disc), engine_order_wave=self)

    def phases(self, n_blades: int, engine_order: int) -> np.ndarray:
        """φ_i = 2π l i / N [rad] for the blades by position (reduced by whole turns)."""
        return self.wave(n_blades, engine_order).phases(n_blades)


@dataclass(frozen=True)
class ExplicitPhases:
    """φ_i given one per blade [rad]; ``engine_order_wave`` as for ``TravellingWave``."""

    values: tuple[float, ...]
    engine_order_wave: EngineOrderWave | None = field(default=None, compare=False,
                                                      repr=False, kw_only=True)

    def __post_init__(self):
        if isinstance(self.values, str) or getattr(self.values, "ndim", 1) == 0 \
                or not isinstance(self.values, Sequence | np.ndarray):
            raise TypeError("ExplicitPhases.values must be a sequence of phases (φ1, φ2, …) "
                            f"[rad], one per blade, got {type(self.values).__name__} "
                            f"{self.values!r}")
        values = tuple(check_real("ExplicitPhases", "values", v, unit="rad")
                       for v in self.values)
        object.__setattr__(self, "values", values)
        _check_source("ExplicitPhases", self.engine_order_wave)

    def phases(self, n_blades: int) -> np.ndarray:
        """The given φ_i [rad]; raises unless there is one per blade."""
        n_blades = _count("ExplicitPhases.phases", n_blades)
        if len(self.values) != n_blades:
            raise ValueError(f"ExplicitPhases has {len(self.values)} phases for "
                             f"{n_blades} blades")
        return np.array(self.values)


def _check_source(owner: str, pattern: object) -> None:
    """Refuse an ``engine_order_wave`` that is neither None nor an ``EngineOrderWave``."""
    check_instance(owner, "engine_order_wave", pattern, EngineOrderWave, optional=True,
                   expected="None or the EngineOrderWave(...) these phases stand for")


PhasePattern = AntiPhase | TravellingWave | EngineOrderWave | ExplicitPhases

_PATTERNS = ("AntiPhase(), TravellingWave(nd), EngineOrderWave() or ExplicitPhases(values) "
             "(a sequence of phases [rad] is taken as ExplicitPhases)")


@dataclass(frozen=True, kw_only=True)
class Excitation:
    """The harmonic force on every blade, locked to the rotation by the engine order, or
    at a frequency of its own.

    Q_i(t) = s_i [q0 + Σ_{n≥1} q_n sin(n (ω t + φ_i))] (paper §2; harmonic n carries
    n φ_i, see the module's docstring), with s_i the blade's ``excitation_scale`` and
    ω = l Ω, or 2π f where ``frequency`` f is given.

    Parameters
    ----------
    engine_order : int
        l in [1, ``ENGINE_ORDER_MAX`` = 1000]: excitation frequency f_e = l Ω/2π (the
        paper's l = 2).
    amplitudes : sequence of float
        (q0, q1, …, qn) [N]: the mean force q0 and the amplitude q_n of the n-th harmonic.
    phases : AntiPhase, TravellingWave, EngineOrderWave, ExplicitPhases or a sequence
        The phase pattern φ_i; a sequence of floats is taken as explicit phases [rad].
    frequency : float or None
        f > 0 [Hz]: the excitation's frequency, whatever the speed (the speed still sets
        the blades' stiffening, and the engine order the phase pattern's nodal
        diameters); None (the default): f_e = l Ω/2π, locked to the speed. Read the
        frequency at a speed with ``frequency_at``.
    """

    engine_order: int
    amplitudes: tuple[float, ...]
    phases: PhasePattern
    frequency: float | None = None

    def __post_init__(self):
        object.__setattr__(self, "engine_order",
                           check_int("Excitation", "engine_order", self.engine_order, low=1,
                                     high=ENGINE_ORDER_MAX))
        if isinstance(self.amplitudes, str | bytes) or getattr(self.amplitudes, "ndim", 1) == 0 \
                or not isinstance(self.amplitudes, Sequence | np.ndarray):
            raise TypeError("Excitation.amplitudes must be a sequence (q0, q1, …) [N]: the "
                            "mean force q0, then the amplitude of each harmonic (one "
                            "harmonic of 50 N without mean force is (0.0, 50.0)); got "
                            f"{type(self.amplitudes).__name__} {self.amplitudes!r}")
        amplitudes = tuple(float(q) for q in check_array(
            "Excitation", "amplitudes", self.amplitudes, shape=(None,), unit="N"))
        if not amplitudes:
            raise ValueError("Excitation.amplitudes needs at least q0 (the mean force)")
        object.__setattr__(self, "amplitudes", amplitudes)
        if not isinstance(self.phases, PhasePattern):
            if isinstance(self.phases, str | bytes) or getattr(self.phases, "ndim", 1) == 0 \
                    or not isinstance(self.phases, Sequence | np.ndarray):
                hint = (" (the paper's pattern, φ_{i+1} − φ_i = π, is AntiPhase())"
                        if isinstance(self.phases, str) else "")
                raise TypeError(f"Excitation.phases must be {_PATTERNS}, got "
                                f"{type(self.phases).__name__} {self.phases!r}{hint}")
            try:
                object.__setattr__(self, "phases", ExplicitPhases(tuple(self.phases)))
            except (TypeError, ValueError) as error:
                raise type(error)(f"Excitation.phases: {error}") from None
        if self.frequency is not None:
            object.__setattr__(self, "frequency", check_real(
                "Excitation", "frequency", self.frequency, low=0.0, low_open=True, unit="Hz"))

    @property
    def n_harmonics(self) -> int:
        """The number of harmonics n ≥ 1 (amplitudes beyond q0)."""
        return len(self.amplitudes) - 1

    def blade_phases(self, n_blades: int) -> np.ndarray:
        """φ_i [rad] of the fundamental for ``n_blades`` blades by position."""
        n_blades = _count("Excitation.blade_phases", n_blades)
        if isinstance(self.phases, EngineOrderWave):
            return self.phases.phases(n_blades, self.engine_order)
        return self.phases.phases(n_blades)

    def harmonic_phases(self, n_blades: int) -> np.ndarray:
        """n φ_i [rad]: row n (0 … number of harmonics) holds the phases of harmonic n."""
        return np.arange(len(self.amplitudes))[:, None] * self.blade_phases(n_blades)[None, :]

    def frequency_at(self, speed_rpm: float) -> float:
        """The excitation frequency f_e [Hz] at ``speed_rpm`` [rev/min]: ``frequency``
        where given, else l Ω/60."""
        speed_rpm = check_real("Excitation.frequency_at", "speed_rpm", speed_rpm, low=0.0,
                               unit="rpm")
        if self.frequency is not None:
            return self.frequency
        return self.engine_order * speed_rpm / 60.0


#: No force on any blade: a group driven by prescribed motions alone (a block on a belt).
#: Its engine order 1 makes the period a run counts in 60/speed_rpm s.
NO_EXCITATION = Excitation(engine_order=1, amplitudes=(0.0,), phases=AntiPhase())
