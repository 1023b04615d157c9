"""Work–precision: what each digit of accuracy costs, in the results users look at.

A run is judged by what a user reads from it, against a reference computed at the
tightest settings (``REFERENCE``):

- in a periodic regime, the Poincaré points of the reference blade and its E_ρ (§3.2);
- in a chaotic regime, where no single trajectory converges, E_ρ and the bounds of the
  attractor (the least and greatest displacement over the record).

Errors are relative: Poincaré points and bounds to the response amplitude (max |x| and
max |ẋ| of the reference over the record), E_ρ to the reference E_ρ. In chaos the
reference itself is one sample of the attractor: ``sampling_floor`` estimates how far
two equally exact records of the same length differ, below which no setting can be
judged. Cost is the process's CPU time per excitation period, the median of ``repeats``.
"""

from __future__ import annotations

import math
import statistics
import time
from collections.abc import Callable, Iterable, Sequence
from dataclasses import dataclass, replace

import numpy as np

from contact_laws import Regularised

from ..model.group import BladeGroup
from ..model.scene import Scene
from ..run.methods import EVENT_TOLERANCE, TRANSIENT, Accuracy, Adaptive, FixedStep
from ..run.simulate import simulate
from ..run.simulation import Simulation
from ..scenes import three_blade_paper

#: The reference blade whose results are judged.
BLADE = "blade2"


@dataclass(frozen=True, kw_only=True)
class Regime:
    """A scene in a known regime, and the periods to skip and to record there."""

    name: str
    scene: Scene
    transient: int
    record: int
    chaotic: bool


def paper_regimes(*, transient: int = TRANSIENT, record: int = 100,
                  chaotic_record: int = 2000) -> list[Regime]:
    """The paper's group at γ1 = 1 (p1), 3.5 (p3) and 8.8 (chaotic), 6000 rpm, q1 = 50 N."""
    return [
        Regime(name="p1 (γ1 = 1)", scene=three_blade_paper(gamma1=1.0),
               transient=transient, record=record, chaotic=False),
        Regime(name="p3 (γ1 = 3.5)", scene=three_blade_paper(gamma1=3.5),
               transient=transient, record=record, chaotic=False),
        Regime(name="chaotic (γ1 = 8.8)", scene=three_blade_paper(gamma1=8.8),
               transient=transient, record=chaotic_record, chaotic=True),
    ]


@dataclass(frozen=True, kw_only=True)
class Setting:
    """One way to run a scene: an integrator with its knobs, the event tolerance, and
    optionally every friction law regularised with the velocity v_ε [m/s]."""

    family: str
    label: str
    method: FixedStep | Adaptive | Accuracy
    event_tolerance: float = EVENT_TOLERANCE
    regularisation: float | None = None


#: The tightest settings: the reference every other run is judged against.
REFERENCE = Setting(family="reference", label="rtol = 1e-13",
                    method=Adaptive(rtol=1e-13, atol=1e-17), event_tolerance=1e-12)


def default_settings() -> list[Setting]:
    """Each integrator over its knob, the event tolerance alone, regularised friction, and
    ``Accuracy`` at the targets it promises."""
    fixed = [Setting(family="FixedStep", label=f"{n} steps/period",
                     method=FixedStep(steps_per_period=n))
             for n in (100, 200, 500, 1000, 2000, 5000)]
    adaptive = [Setting(family="Adaptive", label=f"rtol = {rtol:g}",
                        method=Adaptive(rtol=rtol, atol=rtol * 1e-4))
                for rtol in (1e-4, 1e-6, 1e-8, 1e-10, 1e-12)]
    events = [Setting(family="event tolerance", label=f"event_tolerance = {tol:g}",
                      method=Adaptive(rtol=1e-12, atol=1e-16), event_tolerance=tol)
              for tol in (1e-4, 1e-6, 1e-8)]
    smoothed = [Setting(family="Regularised", label=f"v_ε = {velocity:g} m/s",
                        method=Adaptive(rtol=1e-10, atol=1e-14), regularisation=velocity)
                for velocity in (1e-2, 1e-3, 1e-4)]
    asked = [Setting(family="Accuracy", label=f"Accuracy({target:g})",
                     method=Accuracy(target=target))
             for target in (1e-2, 1e-4, 1e-6, 1e-8)]
    return fixed + adaptive + events + smoothed + asked


def regularised(scene: Scene, velocity: float) -> Scene:
    """The scene with every exact friction law replaced by ``Regularised(law, velocity)``."""
    group = BladeGroup()
    for name in scene.group.blades:
        group.add_blade(name, scene.group.blade(name))
    for name in scene.group.fixed:
        group.add_fixed(name)
    for left, right, interface in scene.group.interfaces:
        law = interface.friction
        if law is not None and not isinstance(law, Regularised):
            interface = replace(interface, friction=Regularised(law=law, velocity=velocity))
        group.connect(left, right, interface)
    return replace(scene, group=group)


@dataclass(frozen=True)
class Outcome:
    """What a user reads from a run of a regime (units: m, m/s, m²)."""

    poincare: np.ndarray          # (x, ẋ) at t = k T_e over the record
    energy_density: float         # E_ρ
    bounds: tuple[float, float]   # least and greatest x over the record
    amplitude: tuple[float, float]  # max |x| and max |ẋ| over the record


def outcome(sim: Simulation, regime: Regime) -> Outcome:
    """The results of ``regime`` read from ``sim``, after its transient."""
    i = sim.scene.blade_position(BLADE)
    rows = slice(regime.transient * sim.samples_per_period, None)
    x, v = sim.x[rows, i], sim.v[rows, i]
    return Outcome(poincare=sim.poincare(BLADE, skip=regime.transient),
                   energy_density=sim.energy_density(BLADE, skip=regime.transient),
                   bounds=(float(x.min()), float(x.max())),
                   amplitude=(float(np.abs(x).max()), float(np.abs(v).max())))


def run(regime: Regime, setting: Setting, *, initial=None) -> Simulation:
    """Simulate ``regime`` with ``setting``."""
    scene = regime.scene if setting.regularisation is None else regularised(
        regime.scene, setting.regularisation)
    return simulate(scene, regime.transient + regime.record, method=setting.method,
                    samples_per_period=_SAMPLES_PER_PERIOD,
                    event_tolerance=setting.event_tolerance, initial=initial)


#: Samples per period: enough for E_ρ and the bounds to 1e-6 of a smooth response.
_SAMPLES_PER_PERIOD = 100


def errors(result: Outcome, reference: Outcome, chaotic: bool) -> dict[str, float]:
    """Relative errors of ``result``: Poincaré points and E_ρ, or in chaos E_ρ and bounds."""
    x_scale, v_scale = reference.amplitude
    energy = abs(result.energy_density - reference.energy_density) / reference.energy_density
    if chaotic:
        bounds = max(abs(a - b) for a, b in zip(result.bounds, reference.bounds)) / x_scale
        return {"E_rho": energy, "bounds": bounds}
    difference = np.abs(result.poincare - reference.poincare)
    points = max(difference[:, 0].max() / x_scale, difference[:, 1].max() / v_scale)
    return {"Poincaré": float(points), "E_rho": energy}


def sampling_floor(regime: Regime, reference: Outcome) -> float:
    """In chaos, the error between the reference and an equally exact record that starts
    1e-9 of the amplitude away: the sampling error of a record of this length. Zero for
    periodic regimes, whose reference converges."""
    if not regime.chaotic:
        return 0.0
    n = len(regime.scene.blades)
    nudge = np.full(n, 1e-9 * reference.amplitude[0])
    other = outcome(run(regime, REFERENCE, initial=(nudge, np.zeros(n))), regime)
    return max(errors(other, reference, chaotic=True).values())


@dataclass(frozen=True)
class Measurement:
    """One setting in one regime: its cost and its errors."""

    regime: str
    setting: Setting
    seconds_per_period: float   # CPU time, median of the repeats
    errors: dict[str, float]

    @property
    def error(self) -> float:
        """The largest of the relative errors."""
        return max(self.errors.values())


def measure(regime: Regime, setting: Setting, reference: Outcome, *,
            repeats: int = 3) -> Measurement:
    """Time ``setting`` on ``regime`` (after one untimed run that loads its kernel)."""
    run(replace(regime, transient=0, record=1), setting)
    seconds = []
    for _ in range(repeats):
        start = time.process_time()
        sim = run(regime, setting)
        seconds.append(time.process_time() - start)
    periods = regime.transient + regime.record
    return Measurement(regime=regime.name, setting=setting,
                       seconds_per_period=statistics.median(seconds) / periods,
                       errors=errors(outcome(sim, regime), reference, regime.chaotic))


@dataclass(frozen=True)
class Study:
    """The measurements of every setting in every regime, with each regime's floor."""

    measurements: list[Measurement]
    floors: dict[str, float]

    def cheapest(self, regime: str, target: float, family: str | None = None
                 ) -> Measurement | None:
        """The cheapest setting (of ``family``, if given) within ``target`` in ``regime``."""
        fits = [m for m in self.measurements if m.regime == regime and m.error <= target
                and (family is None or m.setting.family == family)]
        return min(fits, key=lambda m: m.seconds_per_period, default=None)


def study(regimes: Sequence[Regime], settings: Iterable[Setting], *, repeats: int = 3,
          progress: Callable[[str], None] | None = None) -> Study:
    """Measure every setting in every regime against the regime's reference."""
    settings = list(settings)
    measurements, floors = [], {}
    for regime in regimes:
        reference = outcome(run(regime, REFERENCE), regime)
        floors[regime.name] = sampling_floor(regime, reference)
        for setting in settings:
            measurements.append(measure(regime, setting, reference, repeats=repeats))
            if progress is not None:
                m = measurements[-1]
                progress(f"{regime.name:>20}  {setting.label:<26} "
                         f"{m.seconds_per_period * 1e3:9.4f} ms/period  error {m.error:.1e}")
    return Study(measurements=measurements, floors=floors)


#: The accuracies the summary table is drawn for.
TARGETS = (1e-2, 1e-4, 1e-6)


def summary(result: Study, targets: Sequence[float] = TARGETS) -> list[tuple]:
    """Rows (regime, target, family, setting, ms per period, error): the cheapest setting of
    each family that reaches each target, cheapest first; a family that never does is left
    out, and a target that no setting reaches gets one row with family "none"."""
    rows = []
    for regime in result.floors:
        for target in targets:
            found = [m for family in SUMMARY_FAMILIES
                     if (m := result.cheapest(regime, target, family)) is not None]
            found.sort(key=lambda m: m.seconds_per_period)
            rows.extend((regime, target, m.setting.family, m.setting.label,
                         m.seconds_per_period * 1e3, m.error) for m in found)
            if not found:
                rows.append((regime, target, "none", "", math.nan, math.nan))
    return rows


#: The families a user picks a setting from (the event tolerance family shows one knob).
SUMMARY_FAMILIES = ("FixedStep", "Adaptive", "Regularised", "Accuracy")
