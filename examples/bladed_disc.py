"""A 24-sector shrouded bladed disc: its modes by nodal diameter, its forced response through
the shroud contacts, and how mistuning amplifies it.

Run: python examples/bladed_disc.py [OUTPUT_FOLDER]
Saves in OUTPUT_FOLDER (default examples/output/):
- bladed_disc_zzenf.png: the first three families' frequencies against the nodal diameter
  with the shrouds open and stuck, and the engine-order zig-zag at 3000 rpm;
- bladed_disc_response.png: a tip's amplitude (half its peak-to-peak) and E_ρ along the
  period-1 travelling waves (``continuation``, on the reduced map of one sector-passing
  quarter period) across the engine-order-6 resonance, 2900–3300 rpm, where the
  preloaded shrouds open, slip and stick every period; stable waves solid, unstable ones
  dashed, and the bifurcations marked, each with the nodal diameter of its eigenvector:
  those that break the wave's symmetry lead to standing or localised motion;
- bladed_disc_localised.png: each sector's tip amplitude at 3000 rpm, for the travelling
  wave (unstable there) and for the orbit a transient settles on instead, whose sectors
  no longer repeat one another;
- bladed_disc_mistuning.png: the distribution of the amplification factor over random
  blade frequency patterns (``mistuning_study``), with Whitehead's bound.
The scene is ``shroudnet.scenes.bladed_disc_24``: a disc node and a two-node blade per
sector, joined by couplings, with the paper's shroud contacts between neighbouring tips.
"""

import sys
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from shroudnet import (
    Branch,
    LinearModes,
    MistuningStudy,
    PeriodicOrbit,
    continuation,
    linear_modes,
    mistuning_study,
    periodic_orbit,
)
from shroudnet.scenes import bladed_disc_24

OUTPUT = Path(__file__).resolve().parent / "output"
ENGINE_ORDER = 6
TIP = "blade1_2"  # the tip of sector 1


def at_speed(speed_rpm):
    return bladed_disc_24(speed_rpm=speed_rpm)


@dataclass(frozen=True)
class Result:
    open: LinearModes
    stuck: LinearModes
    branch: Branch
    mistuning: MistuningStudy
    wave: PeriodicOrbit
    settled: PeriodicOrbit


#: The speeds [rpm] of the forced-response curve and of the mistuning study: across the
#: resonance of the ND-6 mode with the shrouds closed, near 3100 rpm.
CURVE = (2900.0, 3300.0)
PEAK = (2950.0, 3250.0)


def compute(max_points=150, samples=40, speeds=9, transient=200, record=10):
    scene = at_speed(3000.0)
    open_, stuck = linear_modes(scene, "open"), linear_modes(scene, "stuck")
    # 72 nodes and some 30 switches a period: Newton's residual stalls near 1e-10 of the
    # state at the default rtol, so the orbits are asked for to 1e-8.
    branch = continuation(at_speed, *CURVE, max_points=max_points, max_step=0.3,
                          transient=transient, tolerance=1e-8, parameter="speed [rpm]")
    study = mistuning_study(scene, spread=0.01, samples=samples,
                            speeds_rpm=np.linspace(*PEAK, speeds), transient=transient,
                            record=record, progress=False)
    # At 3000 rpm: the travelling wave, and the orbit shooting whole periods finds from a
    # transient, which need not share the wave's symmetry.
    wave = periodic_orbit(scene, symmetry="cyclic", tolerance=1e-8)
    settled = periodic_orbit(scene, symmetry="none", transient=transient, tolerance=1e-8)
    return Result(open_, stuck, branch, study, wave, settled)


def tip_amplitudes(orbit: PeriodicOrbit) -> np.ndarray:
    """Each sector's tip amplitude [m] (half its peak-to-peak), sector by sector."""
    half = 0.5 * (orbit.maximum - orbit.minimum)
    return half.reshape(24, -1)[:, -1]


def report(result: Result):
    print("Nodal diameter | first three families, shrouds open [Hz] | shrouds stuck [Hz]")
    for nd, (free, held) in enumerate(zip(result.open.families()[:, :3],
                                          result.stuck.families()[:, :3])):
        print(f"{nd:14d} | {'  '.join(f'{f:7.1f}' for f in free)} | "
              f"{'  '.join(f'{f:7.1f}' for f in held if np.isfinite(f))}")
    branch = result.branch
    print(f"forced response: {len(branch)} period-1 orbits from {branch.parameter[0]:.1f} to "
          f"{branch.parameter[-1]:.1f} rpm, {branch.stable.sum()} stable; the tip's largest "
          f"amplitude {branch.amplitude(TIP).max() * 1e3:.4f} mm")
    for b in branch.bifurcations:
        smooth = np.isfinite(b.multiplier)
        print(f"  {b.kind} at {b.parameter:.2f} rpm"
              + (f", |μ| = {abs(b.multiplier):.6f} along ND {b.wave_number}" if smooth
                 else ""))
    for label, orbit in (("travelling wave", result.wave), ("after a transient", result.settled)):
        tips = tip_amplitudes(orbit)
        print(f"3000 rpm, {label}: {'stable' if orbit.stable else 'unstable'}, |μ|max "
              f"{abs(orbit.multipliers[0]):.4f} along ND {orbit.wave_numbers[0]}; tip "
              f"amplitudes {tips.min() * 1e3:.4f}–{tips.max() * 1e3:.4f} mm over the sectors")
    study = result.mistuning
    factors = study.amplification
    print(f"mistuning, spread {study.spread:g}, {len(factors)} patterns: amplification "
          f"median {np.median(factors):.3f}, 95th percentile "
          f"{np.percentile(factors, 95):.3f}, largest {factors.max():.3f} (pattern "
          f"{study.worst}); Whitehead's bound {study.whitehead_bound:.3f}")


def main(max_points=150, samples=40, speeds=9, transient=200, record=10, output=OUTPUT):
    """Compute, print the tables, save the figures in ``output``; returns the ``Result``."""
    from shroudnet.front.figures import (
        forced_response,
        mistuning_histogram,
        sector_amplitudes,
        zzenf_diagram,
    )
    result = compute(max_points, samples, speeds, transient, record)
    report(result)
    output = Path(output)
    output.mkdir(parents=True, exist_ok=True)
    zzenf_diagram({"shrouds open": result.open, "shrouds stuck": result.stuck},
                  speed_rpm=result.open.speed_rpm, engine_orders=range(1, 13)).savefig(
        output / "bladed_disc_zzenf.png", dpi=110)
    forced_response({"engine order 6": result.branch}, TIP, xlabel="Ω [rpm]",
                     title="Bladed disc: forced response of a tip, period-1 orbits").savefig(
        output / "bladed_disc_response.png", dpi=110)
    mistuning_histogram(result.mistuning).savefig(output / "bladed_disc_mistuning.png",
                                                  dpi=110)
    sector_amplitudes({"travelling wave (unstable)": result.wave,
                       "the orbit a transient settles on": result.settled},
                      title="Bladed disc at 3000 rpm, engine order 6: tip amplitude by "
                            "sector").savefig(output / "bladed_disc_localised.png", dpi=110)
    print(f"saved the figures in {output}")
    return result


if __name__ == "__main__":
    main(output=Path(sys.argv[1]) if len(sys.argv) > 1 else OUTPUT)
