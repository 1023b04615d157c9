"""Shroud faces as FE engineers mesh them: a packet whose contact faces are patches of points.

Six blades of four modes (``scenes.faced_blade``: first flap, edgewise, shroud twist and
second flap), each in its own sector frame of a disc of 36 (``BladeGroup.chain`` with
``points`` and ``blades_on_disc``): blade s's right shroud face meets blade s + 1's left
face at a grid of k point pairs, each a 3-D contact of its own (``scenes.faced_group``):
a 2 µm preload shared by the pairs, the face's normal and tangential stiffnesses split
among them, Coulomb friction μ = 0.3 with elastic stick in the face's plane. The shroud
twists in its third mode, so the pairs at the two ends of a face load and slip
differently: one pair in the middle of the face cannot tell.

Run: python examples/fe_packet_patches.py [OUTPUT_FOLDER]
Saves in OUTPUT_FOLDER (default examples/output/):
- fe_packet_patches_map.png: the contact-state map (open, stuck, slipping) and the
  normal-load distribution of the nine pairs of the face between blades 1 and 2 over one
  period near the resonance (``patch_history``, ``figures.patch_map``);
- fe_packet_patches_response.png: the amplitude of blade 1's load point over the first
  flap resonance, in speed (its excitation frequency l Ω/60) and, beside it, in frequency
  at a fixed speed (``Excitation(frequency=f)``: the stiffening fixed), nine pairs a face;
- fe_packet_patches_convergence.png: the response in speed with 1, 4 and 9 pairs a face,
  and its peak against the pairs: how the answer converges as the patch is refined.
Prints the peaks, their change from one patch to the next, the stuck and slipping shares
of the face's pairs at the map's speed, and the seconds each part took.
"""

import sys
import time
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from shroudnet import PatchHistory, patch_history, simulate
from shroudnet.scenes import faced_group

OUTPUT = Path(__file__).resolve().parent / "output"
#: The response: blade 1's load point (one component), the same whatever the patch.
RESPONSE = ("blade1", "load", 0)
#: Speeds [rpm] across the first flap resonance (l = 4: f_e = 4 Ω/60 ≈ 200 Hz), and the
#: fixed speed [rpm] and frequencies [Hz] of the response in frequency.
SPEEDS = (2800.0, 3200.0)
FIXED_SPEED = 3000.0
FREQUENCIES = (186.0, 214.0)
#: The engine order of ``scenes.faced_group``'s forcing.
ENGINE_ORDER = 4


def scene_at(face_points, speed_rpm, frequency=None):
    """The packet with ``face_points`` pairs a face at ``speed_rpm``, forced at l Ω/60, or
    at ``frequency`` [Hz] where given."""
    return faced_group(blades=6, face_points=face_points, speed_rpm=speed_rpm,
                       engine_order=ENGINE_ORDER, frequency=frequency)


@dataclass(frozen=True)
class Patches:
    """Per pairs a face: the speeds [rpm] and the settled amplitude [m] of ``RESPONSE``
    there; the frequencies [Hz] and amplitudes at ``FIXED_SPEED`` (nine pairs); the
    patch's history over one period near the peak; the seconds each part took."""

    speeds: np.ndarray
    in_speed: dict[int, np.ndarray]
    frequencies: np.ndarray
    in_frequency: np.ndarray
    patch: PatchHistory
    map_speed: float
    seconds: dict[str, float]


def settled_amplitudes(scenes, transient, record):
    """Half the peak-to-peak of ``RESPONSE`` over ``record`` periods after ``transient``
    at each scene in turn, each run started from the last one's end (a stepped sine)."""
    amplitude, start = [], None
    for scene in scenes:
        run = simulate(scene, transient + record, samples_per_period=64, initial=start)
        response = scene.response_of(run.x[transient * 64:], RESPONSE)
        amplitude.append(0.5 * (response.max() - response.min()))
        start = run.state()
    return np.array(amplitude)


def compute(points=(1, 4, 9), speeds=21, frequencies=21, transient=60, record=4,
            samples=400) -> Patches:
    """The response in speed for each of ``points`` pairs a face, the response in
    frequency at ``FIXED_SPEED`` with the finest patch, and that patch's history over one
    period at the speed of its peak."""
    grid = np.linspace(*SPEEDS, speeds)
    seconds, in_speed = {}, {}
    for k in points:
        clock = time.perf_counter()
        in_speed[k] = settled_amplitudes([scene_at(k, speed) for speed in grid], transient,
                                         record)
        seconds[f"{k} pairs a face, in speed"] = time.perf_counter() - clock
    finest = max(points)
    band = np.linspace(*FREQUENCIES, frequencies)
    clock = time.perf_counter()
    in_frequency = settled_amplitudes([scene_at(finest, FIXED_SPEED, f) for f in band],
                                      transient, record)
    seconds["in frequency"] = time.perf_counter() - clock
    map_speed = float(grid[int(np.argmax(in_speed[finest]))])
    scene = scene_at(finest, map_speed)
    clock = time.perf_counter()
    settled = simulate(scene, transient, samples_per_period=1)
    run = simulate(scene, 1, samples_per_period=samples, initial=settled.state())
    seconds["map"] = time.perf_counter() - clock
    return Patches(grid, in_speed, band, in_frequency, patch_history(run, 0), map_speed,
                   seconds)


def report(result: Patches) -> None:
    """Print the peaks, their change from one patch to the next, the map's shares and the
    seconds each part took."""
    previous = None
    for k, amplitude in result.in_speed.items():
        top = int(np.argmax(amplitude))
        change = "" if previous is None else \
            f", {abs(amplitude[top] - previous) / amplitude[top]:.2%} from the coarser patch"
        print(f"{k:2d} pairs a face: peak {amplitude[top] * 1e6:.3f} µm at "
              f"{result.speeds[top]:.0f} rpm{change}")
        previous = amplitude[top]
    top = int(np.argmax(result.in_frequency))
    print(f"at {FIXED_SPEED:.0f} rpm in frequency: peak {result.in_frequency[top] * 1e6:.3f} "
          f"µm at {result.frequencies[top]:.2f} Hz")
    shares = result.patch.fractions()
    print(f"face between blades 1 and 2 at {result.map_speed:.0f} rpm, per pair: stuck "
          + ", ".join(f"{s:.0%}" for s in shares["stuck"]) + "; slipping "
          + ", ".join(f"{s:.0%}" for s in shares["slipping"]) + "; normal load shares "
          + ", ".join(f"{s:.0%}" for s in result.patch.load_shares()))
    for part, seconds in result.seconds.items():
        print(f"{part}: {seconds:.1f} s")


def draw(result: Patches, output: Path) -> None:
    """Save the three figures of the module docstring in ``output``."""
    from matplotlib.figure import Figure

    from shroudnet.front.figures import patch_map

    figure = Figure(figsize=(9, 7), layout="constrained")
    states, loads = figure.subplots(2, 1, sharex=True)
    patch_map(result.patch, ax=states, title=f"face blade 1–blade 2 at "
              f"{result.map_speed:.0f} rpm: contact states")
    patch_map(result.patch, quantity="normal", ax=loads, title="normal load")
    figure.savefig(output / "fe_packet_patches_map.png", dpi=110)

    finest = max(result.in_speed)
    figure = Figure(figsize=(11, 4.5), layout="constrained")
    left, right = figure.subplots(1, 2, sharey=True)
    left.plot(ENGINE_ORDER * result.speeds / 60.0, result.in_speed[finest] * 1e6, "o-", ms=3)
    left.set(xlabel="f_e = l Ω/60 [Hz]", ylabel="amplitude [µm]",
             title=f"in speed, {SPEEDS[0]:.0f}–{SPEEDS[1]:.0f} rpm")
    right.plot(result.frequencies, result.in_frequency * 1e6, "o-", ms=3, color="C1")
    right.set(xlabel="f [Hz]", title=f"in frequency at {FIXED_SPEED:.0f} rpm")
    figure.suptitle(f"blade 1's load point, {finest} pairs a face")
    figure.savefig(output / "fe_packet_patches_response.png", dpi=110)

    figure = Figure(figsize=(11, 4.5), layout="constrained")
    curves, peaks = figure.subplots(1, 2)
    for k, amplitude in result.in_speed.items():
        curves.plot(result.speeds, amplitude * 1e6, lw=1.2, label=f"{k} pairs a face")
    curves.set(xlabel="Ω [rpm]", ylabel="amplitude [µm]", title="response in speed")
    curves.legend(fontsize="small")
    pairs = list(result.in_speed)
    peaks.plot(pairs, [result.in_speed[k].max() * 1e6 for k in pairs], "o-")
    peaks.set(xlabel="pairs a face", ylabel="peak amplitude [µm]", xticks=pairs,
              title="convergence as the patch is refined")
    figure.savefig(output / "fe_packet_patches_convergence.png", dpi=110)


def main(points=(1, 4, 9), speeds=21, frequencies=21, transient=60, record=4, samples=400,
         output=OUTPUT) -> Patches:
    """Compute, print and save the figures in ``output``; returns the ``Patches``."""
    result = compute(points, speeds, frequencies, transient, record, samples)
    report(result)
    output = Path(output)
    output.mkdir(parents=True, exist_ok=True)
    draw(result, output)
    print(f"saved the figures in {output}")
    return result


if __name__ == "__main__":
    main(output=Path(sys.argv[1]) if len(sys.argv) > 1 else OUTPUT)
