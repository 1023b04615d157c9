"""The benchmark's harmonic-balance section (``bench``, section 9), one core.

- A point of the six-blade packet with 3-D elastic shroud faces
  (``scenes.modal_packet(tangential_stiffness=3e5)``) at H = 7: CPU milliseconds of
  ``harmonic_balance`` from the linear response, and from the orbit of a speed 10 rpm
  away (as a forced-response curve takes its points), without and with Hill's
  multipliers.
- Its certificate: the exact orbit shot from that series (``certify``), and the
  series' errors.
- A forced-response curve of the packet up in speed by ``harmonic_continuation`` at
  H = 7, of about ``points`` points, with and without Hill's multipliers, and one of
  the packet of four-mode blades whose faces are 9-point patches
  (``scenes.faced_group``: 135 contact coordinates, solved on their 24 directions)
  from 2400 to 3800 rpm.
- A tuned ring of FE sectors with 4-point faces, solved on one sector and whole.
- The error against H and time at one of its speeds (``studies.harmonic_precision``).

CPU times (``time.process_time``), medians of ``repeats`` after a run that loads the
slider march's compiled code; BLAS should run on one thread (OMP_NUM_THREADS=1,
OPENBLAS_NUM_THREADS=1), as the bench's other sections run on one core.
"""

from __future__ import annotations

import statistics
import time

from ..scenes import faced_group, modal_packet
from ..steady.harmonic.balance import harmonic_balance
from ..steady.harmonic.certificate import certify
from ..steady.harmonic.continuation import harmonic_continuation
from ..studies.harmonic_precision import harmonic_precision

#: The packet's faces' tangential stiffness [N/m], the speed of the point [rpm], H.
TANGENTIAL_STIFFNESS = 3e5
SPEED = 2900.0
HARMONICS = 7


def packet(speed_rpm: float = SPEED):
    return modal_packet(speed_rpm=speed_rpm, tangential_stiffness=TANGENTIAL_STIFFNESS)


def cpu_median(function, repeats: int):
    """(median CPU seconds of ``function()`` over ``repeats`` runs, its last result)."""
    times, result = [], None
    for _ in range(repeats):
        began = time.process_time()
        result = function()
        times.append(time.process_time() - began)
    return statistics.median(times), result


def point_costs(repeats: int) -> dict[str, tuple[float, object]]:
    """CPU seconds of one point at H = 7, by how it starts and whether Hill runs."""
    scene = packet()
    neighbour = harmonic_balance(packet(SPEED - 10.0), HARMONICS, stability=False)
    harmonic_balance(scene, HARMONICS)  # load the compiled march
    return {
        "from the linear response": cpu_median(
            lambda: harmonic_balance(scene, HARMONICS, stability=False), repeats),
        "from the orbit 10 rpm away": cpu_median(
            lambda: harmonic_balance(scene, HARMONICS, guess=neighbour, stability=False),
            repeats),
        "from the orbit 10 rpm away, with Hill's multipliers": cpu_median(
            lambda: harmonic_balance(scene, HARMONICS, guess=neighbour), repeats),
    }


def curve_cost(points: int, stability: bool) -> tuple[float, object]:
    """(CPU seconds, branch) of the packet's curve up from 2600 to 3400 rpm at H = 7, its
    largest step sized for about ``points`` points."""
    began = time.process_time()
    branch = harmonic_continuation(packet, 2600.0, 3400.0, HARMONICS,
                                   max_step=min(1.0, 7.0 / points), max_points=2 * points,
                                   stability=stability, parameter="speed [rpm]")
    return time.process_time() - began, branch


def patch_curve_cost(points: int) -> tuple[float, object]:
    """(CPU seconds, branch) of the 9-point-patch packet's curve up from 2400 to 3800 rpm
    at H = 7, its largest step sized for about ``points`` points."""
    def scene_at(rpm):
        return faced_group(blades=6, face_points=9, speed_rpm=rpm)

    harmonic_balance(scene_at(2400.0), HARMONICS, stability=False)  # load the march
    began = time.process_time()
    branch = harmonic_continuation(scene_at, 2400.0, 3800.0, HARMONICS,
                                   max_step=min(1.0, 28.0 / points), max_points=2 * points,
                                   stability=False, parameter="speed [rpm]")
    return time.process_time() - began, branch


def ring_costs(quick: bool) -> tuple[str, float, float, float]:
    """(the ring, CPU seconds of its orbit on one sector, of the whole ring's, the
    largest difference of their series over its largest coefficient) at H = 5."""
    blades, points = (6, 1) if quick else (12, 4)
    scene = faced_group(shape="ring", blades=blades, face_points=points, engine_order=3)
    sector = harmonic_balance(scene, 5, stability=False)
    one, _ = cpu_median(lambda: harmonic_balance(scene, 5, stability=False), 1)
    whole_seconds, whole = cpu_median(lambda: harmonic_balance(
        scene, 5, symmetry="none", samples=sector.samples, stability=False), 1)
    gap = abs(sector.coefficients - whole.coefficients).max() / abs(
        whole.coefficients).max()
    return (f"{blades} FE sectors with {points}-point 3-D elastic faces, l = 3", one,
            whole_seconds, gap)


def section(quick: bool = False) -> None:
    """Print the section."""
    repeats = 1 if quick else 5
    print("\n9. Harmonic balance, one core (CPU time): the packet of 6 three-mode blades "
          "with 3-D elastic faces (5 faces × 3 contact coordinates)")
    orbit = None
    for label, (seconds, orbit) in point_costs(repeats).items():
        print(f"   a point at H = {HARMONICS} ({orbit.samples} samples, "
              f"{orbit.contact_coefficients.size} unknowns), {label}: {seconds * 1e3:.1f} ms "
              f"({orbit.iterations} Newton steps, residual {orbit.residual:.1e})")
    began = time.process_time()
    certificate = certify(orbit)
    print(f"   its certificate (exact shooting from the series, rtol 1e-10, residual 1e-9): "
          f"{(time.process_time() - began) * 1e3:.0f} ms; errors: amplitude "
          f"{certificate.amplitude_error:.1e}, energy per cycle "
          f"{certificate.energy_error:.1e}, state {certificate.state_error:.1e}, Hill's "
          f"multipliers {certificate.multiplier_error:.1e}")
    points = 3 if quick else 200
    for stability in (False, True):
        seconds, branch = curve_cost(points, stability)
        print(f"   forced-response curve 2600–3400 rpm at H = {HARMONICS}"
              f"{', with Hill' if stability else ''}: {len(branch)} points in {seconds:.1f} s "
              f"({seconds / len(branch) * 1e3:.0f} ms a point; {branch.ended}); faces of "
              "one point pair")
    seconds, branch = patch_curve_cost(3 if quick else 200)
    print(f"   the packet of 6 four-mode blades with 9-point faces (135 contact coordinates "
          f"on 24 directions), 2400–3800 rpm at H = {HARMONICS}: {len(branch)} points in "
          f"{seconds:.1f} s ({seconds / len(branch) * 1e3:.0f} ms a point; {branch.ended})")
    ring, one, whole, gap = ring_costs(quick)
    print(f"   a tuned ring of {ring} at H = 5: one sector {one * 1e3:.0f} ms, the whole "
          f"ring {whole * 1e3:.0f} ms ({whole / one:.1f}x), their series agree to "
          f"{gap:.1e}")
    study = harmonic_precision(packet(), (1, 3, 5, 7) if quick else (1, 3, 5, 7, 9, 15),
                               repeats=1 if quick else 3)
    print(f"   error against H at {SPEED:g} rpm (H, samples, ms, amplitude, energy per "
          "cycle, state at t = 0):")
    for row in study.rows():
        h, n, ms, amplitude, energy, state = row
        print(f"     {h!s:>5} {n!s:>5} {ms:8.1f} ms  {amplitude:.1e}  {energy:.1e}  "
              f"{state:.1e}")


if __name__ == "__main__":
    section()
