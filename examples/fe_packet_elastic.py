"""Contacts as engineers model them: the six-blade packet with 3-D shroud contacts.

The packet of ``examples/fe_packet.py`` (six blades of three modes, ``scenes.modal_blade``),
its shroud points now moving in three directions (flapwise, edgewise and radial;
``modal_blade(dimensions=3)``). Each shroud face, inclined at 0.6 rad, presses with a
1e5 N/m contact spring under a 2 µm preload and slides in its plane, spanned by its
in-plane flap–edge direction and the radial one: stick is elastic, a Jenkins element of
tangential stiffness k_t = 3e5 N/m with a circular Coulomb limit μ = 0.3
(``scenes.modal_packet(tangential_stiffness=)``); the sliders are part of the state.

Run: python examples/fe_packet_elastic.py [OUTPUT_FOLDER]
Saves in OUTPUT_FOLDER (default examples/output/):
- fe_packet_elastic_response.png: the flapwise amplitude (half the peak-to-peak) of
  blade 1's shroud (``fe_packet.RESPONSE``) over speed across the first flap resonance,
  from runs that settle at each speed (each started from the last one's end), and the
  stuck limit's resonance beyond it, between the linear responses with
  the shrouds open and stuck (``frequency_response``; stuck, the faces are the springs
  k_t in their plane and the contact spring along their normal);
- fe_packet_elastic_loops.png: the friction force of the interface between blades 1 and 2
  against its tangential relative displacement, along each direction of its face, over
  one period after 200 at three speeds: stick is elastic, so the stuck stretches lean
  with slope k_t, and the areas of the two directions' loops add up to what the slider
  dissipates.
Prints the peak against the linear limits and, at the three speeds, each direction's
energy per cycle.
"""

import sys
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from shroudnet import HysteresisLoop, hysteresis_loop, simulate
from shroudnet.scenes import modal_packet

sys.path.insert(0, str(Path(__file__).resolve().parent))
from fe_packet import RESPONSE, linear_limit  # noqa: E402

OUTPUT = Path(__file__).resolve().parent / "output"
#: The tangential stiffness of every shroud face [N/m] and its preload [m].
TANGENTIAL_STIFFNESS = 3e5
GAP = -2e-6
SPEEDS = (2600.0, 4000.0)
#: The speeds [rpm] of the hysteresis loops.
LOOP_SPEEDS = (2800.0, 3000.0, 3200.0)


def scene_at(speed_rpm):
    return modal_packet(gap=GAP, speed_rpm=speed_rpm,
                        tangential_stiffness=TANGENTIAL_STIFFNESS)


@dataclass(frozen=True)
class Packet:
    """The settled amplitude [m] of ``RESPONSE`` at each speed [rpm], the linear limits'
    at the same speeds by label, and the loops by label (speed and direction)."""

    speeds: np.ndarray
    amplitude: np.ndarray
    limits: dict[str, np.ndarray]
    loops: dict[str, HysteresisLoop]


def settled(speeds, transient, record, samples=100):
    """The amplitude of ``RESPONSE`` over the last ``record`` periods of a run of
    ``transient + record`` periods at each speed, each run started from the last one's
    end, and those runs by speed."""
    node, point, component = RESPONSE
    amplitude, runs, start = [], {}, None
    for speed in speeds:
        sim = simulate(scene_at(speed), transient + record, samples_per_period=samples,
                       initial=start)
        tail = sim.displacement(node, point)[transient * samples:, component]
        amplitude.append(0.5 * float(np.ptp(tail)))
        runs[float(speed)] = sim
        start = (sim.x[-1], sim.v[-1])
    return np.array(amplitude), runs


def compute(speeds=36, transient=60, record=10, loop_transient=200) -> Packet:
    """The settled response at ``speeds`` speeds over ``SPEEDS``, the linear limits, and
    the loops at ``LOOP_SPEEDS`` in both directions of the first face, over the last
    period of runs of ``loop_transient`` + 1 periods."""
    grid = np.linspace(*SPEEDS, speeds)
    amplitude, _ = settled(grid, transient, record)
    limits = {f"linear, {contacts}": linear_limit(scene_at, grid, contacts)[1]
              for contacts in ("open", "stuck")}
    _, runs = settled(np.array(LOOP_SPEEDS), loop_transient, 1, samples=1000)
    loops = {f"{speed:.0f} rpm, t{direction}": hysteresis_loop(sim, 0, loop_transient,
                                                               direction)
             for speed, sim in runs.items() for direction in (1, 2)}
    return Packet(grid, amplitude, limits, loops)


def report(packet: Packet) -> None:
    top = int(np.argmax(packet.amplitude))
    print(f"settled response: peak {packet.amplitude[top] * 1e6:.3f} µm at "
          f"{packet.speeds[top]:.0f} rpm")
    for label, limit in packet.limits.items():
        k = int(np.argmax(limit))
        print(f"  {label}: peak {limit[k] * 1e6:.3f} µm at {packet.speeds[k]:.0f} rpm")
    for label, loop in packet.loops.items():
        print(f"loop {label}: {loop.area_per_cycle() * 1e6:.4f} µJ per cycle")


def main(speeds=36, transient=60, record=10, loop_transient=200, output=OUTPUT) -> Packet:
    """Compute, print, save the figures in ``output``; returns the ``Packet``."""
    from shroudnet.front.figures import curves, hysteresis_loops
    packet = compute(speeds, transient, record, loop_transient)
    report(packet)
    output = Path(output)
    output.mkdir(parents=True, exist_ok=True)
    series = {"elastic 3-D contacts, settled": packet.amplitude * 1e6,
              **{label: limit * 1e6 for label, limit in packet.limits.items()}}
    curves(packet.speeds, series, xlabel="Ω [rpm]", ylabel="amplitude of blade 1's shroud, "
           "flapwise [µm]", title=f"Elastic shroud faces, k_t = {TANGENTIAL_STIFFNESS:.0e} "
           "N/m, between the linear limits").savefig(
        output / "fe_packet_elastic_response.png", dpi=110)
    hysteresis_loops(packet.loops, title="Shroud face blade 1–blade 2, along t1 and "
                     "t2 of its plane").savefig(
        output / "fe_packet_elastic_loops.png", dpi=110)
    print(f"saved the figures in {output}")
    return packet


if __name__ == "__main__":
    main(output=Path(sys.argv[1]) if len(sys.argv) > 1 else OUTPUT)
