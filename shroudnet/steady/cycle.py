"""What one cycle of a periodic orbit holds, in an engineer's terms: the energy each force
puts in or takes out per excitation period, the equivalent damping ratio, and the
harmonics of each response.

With a periodic orbit of k excitation periods T_e, sampled by one run over it
(``Simulation``, its first and last samples one orbit apart):

- **Energy per cycle** [J per T_e]: the ledger's integrals over the orbit (the work of
  the excitation; the losses to damping, friction and damped contacts), over k. At a
  periodic orbit the stored energy returns, so excitation = damping + friction + contact
  to the integrator's accuracy.
- **Equivalent damping ratio** ζ_eq = W_d / (4π T_max): W_d the energy dissipated per
  cycle, T_max the largest kinetic energy ½ ẋᵀ M ẋ over it (near the samples' largest,
  the vertex of the parabola through its exact values at three close instants). For a linear viscous
  oscillator m ẍ + c ẋ + k x = q sin ωt, W_d = π c ω X² and T_max = ½ m ω² X², so
  ζ_eq = c/(2mω) at every forcing frequency ω: the ratio of critical damping that a
  linear oscillator would need to dissipate as much at that frequency and amplitude.
- **Harmonics** of a response r(t) = A_0 + Σ_n A_n sin(n ω_0 t + φ_n), with ω_0 = 2π/(k T_e)
  (the excitation's frequency for a period-1 orbit; its k-th subharmonic otherwise): from
  the discrete Fourier transform of the samples over the orbit, the trapezoidal rule,
  exact for a response with no harmonic beyond half the samples and spectrally accurate
  where the motion is smooth (at a contact switch, where r̈ jumps, it converges as the
  samples' spacing squared). The phases are those of sines, as the excitation's are.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from contact_laws import check_int

from ..model.lowering import from_dofs
from .vertex import parabola_vertex


@dataclass(frozen=True)
class EnergyPerCycle:
    """Energy per excitation period [J] over a periodic orbit: the work of the excitation
    (prescribed motions included), and the losses to viscous damping, to friction and to
    damped contacts."""

    excitation: float
    damping: float
    friction: float
    contact: float

    @property
    def dissipated(self) -> float:
        """W_d = damping + friction + contact [J]."""
        return self.damping + self.friction + self.contact

    def as_array(self) -> np.ndarray:
        return np.array([self.excitation, self.damping, self.friction, self.contact])


@dataclass(frozen=True)
class Harmonics:
    """A response's harmonics r(t) = A_0 + Σ_n A_n sin(n ω_0 t + φ_n): ``order`` n = 0 …,
    ``frequencies`` n ω_0/2π [Hz], ``amplitudes`` A_n [m] (A_0 the mean, signed) and
    ``phases`` φ_n [rad] in (−π, π] (0 for n = 0)."""

    order: np.ndarray
    frequencies: np.ndarray
    amplitudes: np.ndarray
    phases: np.ndarray


def energy_per_cycle(run, periods: int) -> EnergyPerCycle:
    """The ``EnergyPerCycle`` of a run over a whole orbit of ``periods`` periods."""
    ledger = run.energy
    return EnergyPerCycle(excitation=ledger.excitation_work / periods,
                          damping=ledger.damping_loss / periods,
                          friction=ledger.friction_loss / periods,
                          contact=ledger.contact_loss / periods)


def kinetic_peak(scene, run, state_at=None) -> float:
    """T_max = max ½ ẋᵀ M ẋ [J] over the run's samples of a whole orbit (the last one, the
    first again, left out): the largest sample's time refined by the parabola through it
    and its neighbours (wrapping round); with ``state_at`` (time [s] → the orbit's exact
    (x, ẋ) there, as ``run`` holds them), the vertex of the parabola through the exact
    kinetic energies at that time and a tenth of a sample spacing either side (exact to
    third order in the time's error), else the sampled parabola's. M is diagonal in the
    engine's coordinates, which ``from_dofs`` takes the velocities to."""
    mass = scene.arrays.mass[:run.v.shape[1]]

    def energies(v):
        v = from_dofs(scene.arrays.layout, v)
        return 0.5 * np.einsum("...j,j,...j->...", v, mass, v)

    kinetic = energies(run.v[:-1])
    k = int(np.argmax(kinetic))
    shift, top = parabola_vertex(kinetic[k - 1], kinetic[k], kinetic[(k + 1) % len(kinetic)])
    if state_at is None:
        return float(top)
    spacing = run.t[1] - run.t[0]
    time, width = run.t[k] + shift * spacing, 0.1 * spacing
    if time - width <= 0.0:
        time += run.t[-1] - run.t[0]  # the same instant one orbit on
    near = [float(energies(v)) for _, v in
            (state_at(time + offset) for offset in (-width, 0.0, width))]
    if near[0] - 2.0 * near[1] + near[2] >= 0.0:
        return max(near)
    return float(parabola_vertex(*near)[1])


def equivalent_damping(energy: EnergyPerCycle, kinetic: float) -> float:
    """ζ_eq = W_d / (4π T_max) (module docstring); 0 for an orbit at rest."""
    return energy.dissipated / (4.0 * math.pi * kinetic) if kinetic > 0.0 else 0.0


def harmonics(response: np.ndarray, duration: float, order: int) -> Harmonics:
    """The ``Harmonics`` up to ``order`` of one response sampled evenly over a whole orbit
    of ``duration`` [s] (first and last samples one orbit apart)."""
    order = check_int("harmonics", "order", order, low=0)
    samples = np.asarray(response[:-1], dtype=float)
    count = len(samples)
    if order > (count - 1) // 2:
        raise ValueError(f"harmonics: order must be at most {(count - 1) // 2} with "
                         f"{count} samples an orbit (half of them, less one), got {order}; "
                         "take more samples_per_period")
    spectrum = np.fft.rfft(samples)[:order + 1] / count
    # r = A_0 + Σ A_n sin(n ω_0 t + φ_n) gives the DFT coefficient c_n = (A_n/2i) e^{iφ_n}.
    amplitudes = np.concatenate([[spectrum[0].real], 2.0 * np.abs(spectrum[1:])])
    phases = np.concatenate([[0.0], np.angle(2j * spectrum[1:])])
    n = np.arange(order + 1)
    return Harmonics(order=n, frequencies=n / duration, amplitudes=amplitudes,
                     phases=phases)
