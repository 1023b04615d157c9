"""From your FE model to a forced response: a packet of six blades given by modal data.

Each blade is three modes as an FE modal analysis prints them (``scenes.modal_blade``:
first flap 180 Hz, edgewise 450 Hz and second flap 1050 Hz at rest, stiffening with
speed by Southwell's law; modal masses; shapes at the shroud, flapwise and edgewise, and
at the load point; 2 % damping in every mode). Neighbouring shrouds meet on faces
inclined at 0.6 rad to the flapwise direction, each a 1e5 N/m contact spring with
Coulomb friction μ = 0.3 (``scenes.modal_packet``); engine order 4 forces the packet
with 1 N at the load points, at its first flap resonance near 3000 rpm. Two shroud
designs are compared: a gap (the shrouds close only when the blades swing far enough)
and a preload.

Run: python examples/fe_packet.py [OUTPUT_FOLDER]
Saves in OUTPUT_FOLDER (default examples/output/):
- fe_packet_campbell_open.png and fe_packet_campbell_stuck.png: the packet's natural
  frequencies against speed with the shrouds open (the blades alone: the first flap
  family meets engine order 4 at 2995.4 rpm) and stuck, with the engine-order lines;
- fe_packet_response.png: the forced response over speed across the first flap
  resonance, for the gap and the preload, each followed up from 2600 rpm and down from
  3400 rpm: the flapwise amplitude (half the peak-to-peak) of blade 1's shroud and its
  E_ρ, stable orbits solid, unstable ones dashed, bifurcations marked, between the linear
  responses with the shrouds open and stuck (``frequency_response``; stuck, the preloaded shrouds
  also push by their contact springs, so the two designs have stuck limits of their own);
- fe_packet_content.png: along the same branches, the amplitude, the phase of its first
  harmonic and the orbit's equivalent damping ratio ζ_eq;
- fe_packet_hysteresis.png: the friction force of the shroud interface between blades 1
  and 2 against its tangential relative displacement over one period of the preloaded
  design's orbit, at three speeds: below, at and above its peak. Stick is rigid, so
  each loop's stuck stretches are vertical.
Prints, for each branch, its orbits and how long they took, how many are stable, where
it ended, its smooth bifurcations, the response peak, the share of the dissipated
energy that friction takes there and the equivalent damping ratio, and the resonance's
frequency against the linear limits' (``Branch.frequency_shift``).
"""

import sys
import time
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from shroudnet import (
    Branch,
    GroupCampbell,
    HysteresisLoop,
    continuation,
    frequency_response,
    group_campbell,
    hysteresis_loop,
    simulate,
)
from shroudnet.scenes import modal_packet

OUTPUT = Path(__file__).resolve().parent / "output"
#: The shroud designs: the gap Δ [m] of every interface (negative: a preload).
DESIGNS = {"gap 2 µm": 2e-6, "preload 2 µm": -2e-6}
SPEEDS = (2600.0, 3400.0)
#: The response plotted: the flapwise component (0) of blade 1's shroud point.
RESPONSE = ("blade1", "shroud", 0)
#: The hysteresis loops: of this design's branch, at these speeds [rpm] ("peak": where
#: the branch peaks), of its first interface (blade 1 to blade 2).
LOOP_BRANCH = "preload 2 µm, up"
LOOP_SPEEDS = {"below the peak": 2800.0, "at the peak": "peak", "above the peak": 3300.0}


def scene_at(gap):
    def at(speed_rpm):
        return modal_packet(gap=gap, speed_rpm=speed_rpm)
    return at


@dataclass(frozen=True)
class Packet:
    """The Campbell diagrams (shrouds open and stuck), each design's branches up and down
    in speed, the seconds each took, and the linear limits: by label, (speeds [rpm],
    amplitude [m] of ``RESPONSE``), and the hysteresis loops by speed."""

    open: GroupCampbell
    stuck: GroupCampbell
    branches: dict[str, Branch]
    seconds: dict[str, float]
    limits: dict[str, tuple[np.ndarray, np.ndarray]]
    loops: dict[str, HysteresisLoop]


def linear_limit(scene_at, speeds, contacts):
    """|X| of ``RESPONSE`` [m] at each speed [rpm]: the linear response with the shrouds
    ``contacts`` to the engine order at that speed (its frequency l Ω/60)."""
    node, point, component = RESPONSE
    amplitude = []
    for speed in speeds:
        scene = scene_at(speed)
        frequency = scene.excitation.engine_order * speed / 60.0
        response = frequency_response(scene, [frequency], contacts)
        amplitude.append(abs(response.displacement(node, point)[0, component]))
    return speeds, np.array(amplitude)


def compute(speeds=41, max_points=600, max_step=0.05) -> Packet:
    """The Campbell diagrams at ``speeds`` speeds up to 4000 rpm, and for each design the
    branch of period-1 orbits from each end of ``SPEEDS``: where the response bends into
    a fold, or ends at a nonsmooth one, the two ends find what coexists."""
    grid = np.linspace(100.0, 4000.0, speeds)
    scene = scene_at(DESIGNS["preload 2 µm"])(SPEEDS[0])
    diagrams = [group_campbell(scene, grid, engine_orders=(2, 4, 6), contacts=contacts)
                for contacts in ("open", "stuck")]
    branches, seconds = {}, {}
    for label, gap in DESIGNS.items():
        for way, (start, stop) in (("up", SPEEDS), ("down", SPEEDS[::-1])):
            clock = time.perf_counter()
            branches[f"{label}, {way}"] = continuation(
                scene_at(gap), start, stop, parameter="Ω [rpm]", max_step=max_step,
                max_points=max_points)
            seconds[f"{label}, {way}"] = time.perf_counter() - clock
    fine = np.linspace(*SPEEDS, 321)
    limits = {"linear, open": linear_limit(scene_at(DESIGNS["gap 2 µm"]), fine, "open")}
    for label, gap in DESIGNS.items():
        limits[f"linear, stuck ({label})"] = linear_limit(scene_at(gap), fine, "stuck")
    return Packet(*diagrams, branches, seconds, limits, loops(branches[LOOP_BRANCH]))


def loops(branch: Branch, samples=2000) -> dict[str, HysteresisLoop]:
    """The hysteresis loop of the first interface over one period of the branch's orbit
    nearest each of ``LOOP_SPEEDS``, labelled with its name and speed."""
    top = int(np.argmax(branch.amplitude(RESPONSE)))
    found = {}
    for name, speed in LOOP_SPEEDS.items():
        k = top if speed == "peak" else int(np.argmin(np.abs(branch.parameter - speed)))
        orbit = branch.orbits[k]
        sim = simulate(orbit.scene, 1, initial=orbit.initial, samples_per_period=samples)
        found[f"{name}, {branch.parameter[k]:.0f} rpm"] = hysteresis_loop(sim, 0, 0)
    return found


def friction_share(branch: Branch, point: int) -> float:
    """Friction loss over all dissipation per cycle of the branch's orbit ``point``."""
    energy = branch.orbits[point].energy_per_cycle
    return energy.friction / energy.dissipated


def report(packet: Packet):
    for contacts, diagram in (("open", packet.open), ("stuck", packet.stuck)):
        speeds = [speed for order, mode, speed, _ in diagram.crossings
                  if order == 4 and mode == 0]
        print(f"shrouds {contacts}: engine order 4 meets the lowest mode at "
              + (f"{speeds[0]:.1f} rpm" if speeds else "no speed of the diagram"))
    for label, (speeds, amplitude) in packet.limits.items():
        top = int(np.argmax(amplitude))
        print(f"{label}: peak {amplitude[top] * 1e6:.2f} µm at {speeds[top]:.1f} rpm")
    for label, loop in packet.loops.items():
        print(f"hysteresis loop {label}: friction takes {loop.area_per_cycle() * 1e6:.3f} "
              "µJ a cycle at the first interface")
    for label, branch in packet.branches.items():
        peak = branch.amplitude(RESPONSE)
        top = int(np.argmax(peak))
        print(f"{label}: {len(branch)} orbits in {packet.seconds[label]:.1f} s, "
              f"{int(branch.stable.sum())} stable, {branch.ended}; peak "
              f"{peak[top] * 1e6:.2f} µm at {branch.parameter[top]:.1f} rpm, friction "
              f"{friction_share(branch, top):.0%} of the loss there, ζ_eq "
              f"{branch.equivalent_damping[top]:.4f}")
        print(f"  {branch.frequency_shift(RESPONSE)}")
        switches = sum(b.kind in ("grazing", "stick-slip") for b in branch.bifurcations)
        print(f"  {switches} changes of the switch sequence (grazing, stick-slip)")
        for b in branch.bifurcations:
            if b.kind in ("period-doubling", "torus"):
                print(f"  {b.kind:16s} at {b.parameter:9.2f} rpm, |μ| = "
                      f"{abs(b.multiplier):.4f}")
            elif b.kind == "fold":
                print(f"  fold             at {b.parameter:9.2f} rpm")


def main(speeds=41, max_points=600, max_step=0.05, output=OUTPUT):
    """Compute, print and save the figures in ``output``; returns the ``Packet``."""
    from shroudnet.front.figures import (
        branch_content,
        forced_response,
        group_campbell_diagram,
        hysteresis_loops,
    )
    packet = compute(speeds, max_points, max_step)
    report(packet)
    output = Path(output)
    output.mkdir(parents=True, exist_ok=True)
    for contacts, diagram in (("open", packet.open), ("stuck", packet.stuck)):
        group_campbell_diagram(diagram, modes=18, title=f"Campbell diagram of the packet, "
                               f"shrouds {contacts}").savefig(
            output / f"fe_packet_campbell_{contacts}.png", dpi=110)
    forced_response(packet.branches, RESPONSE, limits=packet.limits, xlabel="Ω [rpm]",
                    scale=1e6, unit="µm",
                    title="Blade 1's shroud, flapwise: period-1 orbits").savefig(
        output / "fe_packet_response.png", dpi=110)
    branch_content(packet.branches, RESPONSE, xlabel="Ω [rpm]", scale=1e6, unit="µm",
                   title="Blade 1's shroud, flapwise: amplitude, phase and equivalent "
                   "damping").savefig(output / "fe_packet_content.png", dpi=110)
    hysteresis_loops(packet.loops, title=f"Shroud interface blade 1–blade 2, "
                     f"{LOOP_BRANCH.rsplit(',', 1)[0]}: one period").savefig(
        output / "fe_packet_hysteresis.png", dpi=110)
    print(f"saved the figures in {output}")
    return packet


if __name__ == "__main__":
    main(output=Path(sys.argv[1]) if len(sys.argv) > 1 else OUTPUT)
