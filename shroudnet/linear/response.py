"""The group's linear forced response in the limits of its interfaces.

Every friction-damping plot is drawn between two linear curves: the response with the
interfaces open (they carry nothing) and with them closed, normal springs included, and
stuck where they can stick (``linear.interface_limit``, the limits ``linear_modes``
takes). Between them the nonlinear response moves as the contacts slip, close and open.
The third limit, "stuck", is the group at rest with its friction locked: an interface
open at rest adds no normal spring there, so with gaps it is not the upper bound.

The excitation's first harmonic drives the group: node coordinate i feels
Q_i(t) = A_i sin(ω t + φ_i) (``SceneArrays.harmonic_amplitudes``, ``harmonic_phases``, row
1), here at any angular frequency ω = 2π f instead of l Ω. With F_i = A_i e^{iφ_i}, the
steady response x(t) = Im(X e^{iωt}) solves

    Tᵀ (K − ω² M + iω C) T Z = Tᵀ F,   X = T Z,

in the basis T of the limit (the identity when open; ``linear.Limit``). The stiffness is
K(Ω) at the scene's speed; stuck, K and C include the spring ∂N/∂δ and dashpot ∂N/∂δ̇
of each interface closed at rest, and closed, those of every interface (one open at rest
taken at first touch; ``linear``'s docstring says which laws have none). The constant
load q_0 and the harmonics n ≥ 2 are not part of it (each harmonic n would add its own
response at n ω), and a scene with prescribed-motion nodes, whose motion is an
excitation of its own, is refused.
"""

from __future__ import annotations

import math
from collections.abc import Hashable, Sequence
from dataclasses import dataclass

import numpy as np

from ..checked_records import check_record
from ..model.lowering import to_dofs
from ..model.scene import Scene
from .modes import CONTACTS, interface_limit

#: Where the smallest singular value of K − ω²M + iωC is below this share (√ε of double
#: precision) of ‖K‖ or ω²‖M‖, the response is rounding: a resonance nothing damps (a
#: damping ratio below 1e-8 or so, or a frequency within 1e-8 of an undamped mode's).
RESONANCE = math.sqrt(np.finfo(float).eps)


@dataclass(frozen=True, eq=False)
class FrequencyResponse:
    """The complex steady response of a scene's group to its excitation's first harmonic.

    ``frequencies`` [Hz] are the excitation frequencies f; ``response[k]`` is X at
    ``frequencies[k]`` by blade (with substructures, by every node's own degree of freedom,
    stacked in ``Scene.blades`` order as a state's displacements are) [m]: degree of
    freedom i moves as Im(X_i e^{i 2π f t}), so |X_i| is its amplitude and arg X_i its
    phase against the excitation's sine. Read it by node with ``dofs`` and by point with
    ``displacement`` and ``amplitude``.
    """

    frequencies: np.ndarray
    response: np.ndarray
    contacts: str
    scene: Scene

    def __post_init__(self):
        check_record(self)

    def dofs(self, node: Hashable) -> np.ndarray:
        """``node``'s own degrees of freedom q_i (frequencies × n_i, complex) [m]."""
        return self.response @ self.scene.dof_rows(node).T

    def displacement(self, node: Hashable, point: str | None = None) -> np.ndarray:
        """The complex displacement R of ``node``'s ``point`` (frequencies × d) [m]: the
        point moves as r(t) = Im(R e^{i 2π f t}). A ``Blade``'s one point is its x; a
        substructure with one point needs no name."""
        return self.response @ self.scene.point_rows(node, point).T

    def amplitude(self, node: Hashable, point: str | None = None) -> np.ndarray:
        """The largest distance [m] ``node``'s ``point`` moves from rest over a cycle, at
        each frequency: |R| for a point of one component; for more, the semi-major axis
        of the ellipse r(t) traces, √(½(|a|² + |b|²) + √(¼(|a|² − |b|²)² + (a·b)²)) with
        R = a + i b."""
        return ellipse_semi_major_axis(self.displacement(node, point))

    def peak(self, node: Hashable, point: str | None = None) -> tuple[float, float]:
        """(frequency [Hz], amplitude [m]) of the largest ``amplitude`` among the
        frequencies given (the grid's, not interpolated)."""
        amplitude = self.amplitude(node, point)
        k = int(np.argmax(amplitude))
        return float(self.frequencies[k]), float(amplitude[k])


def ellipse_semi_major_axis(phasors: np.ndarray) -> np.ndarray:
    """max_θ |Re(R e^{iθ})| for each row R of ``phasors`` (rows × d, complex); each row is
    scaled to its largest component first, so that squares neither overflow nor vanish."""
    scale = np.abs(phasors).max(axis=-1, initial=0.0)
    safe = np.where(scale > 0.0, scale, 1.0)
    a, b = phasors.real / safe[..., None], phasors.imag / safe[..., None]
    mean = 0.5 * ((a * a).sum(axis=-1) + (b * b).sum(axis=-1))
    half_difference = 0.5 * ((a * a).sum(axis=-1) - (b * b).sum(axis=-1))
    cross = (a * b).sum(axis=-1)
    return scale * np.sqrt(mean + np.sqrt(half_difference ** 2 + cross ** 2))


def frequency_response(scene: Scene, frequencies: Sequence[float],
                       contacts: str = "open") -> FrequencyResponse:
    """The linear steady response of ``scene``'s group to its excitation's first harmonic,
    at each excitation frequency in ``frequencies`` [Hz], with the interfaces ``contacts``
    ("open", "stuck" or "closed"; module docstring).

    Examples
    --------
    >>> from shroudnet import frequency_response, scenes
    >>> scene = scenes.three_blade_paper(gamma1=2.2)
    >>> open_, stuck = (frequency_response(scene, [150.0, 200.0, 250.0], contacts)
    ...                 for contacts in ("open", "stuck"))
    >>> open_.amplitude("blade1").shape
    (3,)
    """
    if not isinstance(scene, Scene):
        raise TypeError(f"frequency_response needs a shroudnet.Scene (scene=), got "
                        f"{scene!r:.80}")
    if not isinstance(contacts, str) or contacts not in CONTACTS:
        raise (ValueError if isinstance(contacts, str) else TypeError)(
            f"frequency_response: contacts must be one of {CONTACTS}, got "
                         f"{contacts!r}")
    frequencies = _checked_frequencies(frequencies)
    a = scene.arrays
    if a.n_prescribed:
        raise ValueError("frequency_response: the scene has prescribed-motion nodes, whose "
                         "motion is an excitation this linear response leaves out; "
                         "simulate it instead")
    n = a.n_blades
    if a.harmonic_amplitudes.shape[0] < 2 or not np.any(a.harmonic_amplitudes[1, :n]):
        raise ValueError("frequency_response: the excitation has no first harmonic "
                         "(Excitation.amplitudes[1] is 0 or absent): nothing drives the "
                         "response")
    limit = interface_limit(scene, contacts, "frequency_response")
    basis = limit.basis
    forcing = a.harmonic_amplitudes[1, :n] * np.exp(1j * a.harmonic_phases[1, :n])
    mass = basis.T @ np.diag(a.mass) @ basis
    damping = basis.T @ limit.damping @ basis
    stiffness = basis.T @ limit.stiffness @ basis
    load = basis.T @ forcing
    response = np.empty((len(frequencies), n), dtype=complex)
    for k, f in enumerate(frequencies):
        omega = 2.0 * math.pi * f
        dynamic = stiffness - omega * omega * mass + 1j * omega * damping
        scale = max(np.linalg.norm(stiffness, 2), omega * omega * np.linalg.norm(mass, 2))
        if np.linalg.svd(dynamic, compute_uv=False)[-1] <= RESONANCE * scale:
            raise ValueError(f"frequency_response: at {f} Hz the group is at a resonance "
                             "that nothing damps (K − ω²M + iωC is singular to within rounding); "
                             "give damping or leave this frequency out")
        response[k] = basis @ np.linalg.solve(dynamic, load)
    return FrequencyResponse(frequencies=frequencies, response=to_dofs(a.layout, response),
                             contacts=contacts, scene=scene)


#: The largest frequency [Hz] a response is computed at: (2π f)² times a mass stays far
#: inside a float's range (1.8e308).
LARGEST_FREQUENCY = 1e150


def _checked_frequencies(frequencies) -> np.ndarray:
    try:
        values = np.array(frequencies, dtype=float)  # a copy: the record keeps it
    except (TypeError, ValueError):
        raise ValueError("frequency_response: frequencies must be numbers [Hz], got "
                         f"{frequencies!r}") from None
    if values.ndim != 1 or len(values) == 0:
        raise ValueError("frequency_response: frequencies must be a non-empty list of "
                         f"frequencies [Hz], got shape {values.shape}")
    if not np.all(np.isfinite(values)) or np.any(values <= 0.0) \
            or np.any(values > LARGEST_FREQUENCY):
        raise ValueError("frequency_response: frequencies must be finite and > 0 [Hz], at "
                         f"most {LARGEST_FREQUENCY:g} (ω² must stay within a float)")
    return values
