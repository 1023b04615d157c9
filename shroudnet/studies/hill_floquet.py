"""Hill's multipliers against the exact Floquet multipliers, as H grows.

For a scene, the harmonic-balance orbit of H harmonics is solved with Hill's
multipliers (``steady.harmonic.hill``) at each H, and the exact periodic orbit is shot
once, from the series of most harmonics (``certify``), with every Floquet multiplier
of its monodromy matrix. Each exact multiplier μ_j, by descending modulus, is then
measured against the nearest of Hill's at each H,

    e_j(H) = min_i |μ_j − μ̂_i(H)|,

so that the leading ones' errors show whether Hill's method converges on the orbit: it
does, quickly, where the contact forces are smooth (``HarmonicOrbit.smooth``), and
where contacts stick and slip or open and close it need not at all (``hill``'s
docstring says why). ``front.figures.hill_floquet_diagram`` draws it.
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass

import numpy as np

from contact_laws import check_instance, check_int, check_real, check_sequence

from ..model.scene import Scene
from ..run.methods import Accuracy, Adaptive
from ..steady.harmonic.balance import MOST_HARMONICS, harmonic_balance
from ..steady.harmonic.certificate import CERTIFYING_METHOD, CERTIFYING_TOLERANCE, certify
from ..steady.harmonic.orbit import HarmonicOrbit
from ..steady.orbits import SMALLEST_TOLERANCE, PeriodicOrbit

#: The harmonics a study runs by default: doubling, as Hill's error falls (or does not).
HARMONICS = (1, 2, 4, 8, 16)


@dataclass(frozen=True, eq=False)
class HillFloquet:
    """Per number of harmonics (``harmonics``, ascending): the harmonic-balance orbit
    with Hill's multipliers (``orbits``; ``HarmonicOrbit.multipliers`` by descending
    modulus, ``HarmonicOrbit.smooth`` whether Hill's method is to be trusted on it);
    the ``exact`` orbit with its Floquet multipliers (``PeriodicOrbit.multipliers``, by
    descending modulus); and ``errors`` (harmonics × exact multipliers): e_j(H), the
    distance of exact multiplier j to the nearest of Hill's at H (module docstring)."""

    scene: Scene
    harmonics: np.ndarray
    orbits: tuple[HarmonicOrbit, ...]
    exact: PeriodicOrbit
    errors: np.ndarray

    def leading_error(self, count: int = 1) -> np.ndarray:
        """max_{j < count} e_j(H) at each H: the error of the ``count`` exact multipliers
        of largest modulus (a complex pair has one error: count 1 reads it)."""
        count = check_int("HillFloquet.leading_error", "count", count, low=1,
                          most=self.errors.shape[1])
        return self.errors[:, :count].max(axis=1)

    def rows(self) -> list[tuple]:
        """(H, smooth, |μ̂₁|, e₀) by H, then the exact orbit's ("exact", "", |μ₁|, 0):
        Hill's largest modulus against the exact one, and the leading error."""
        rows = [(int(h), bool(o.smooth), float(abs(o.multipliers[0])), float(e))
                for h, o, e in zip(self.harmonics, self.orbits, self.leading_error())]
        return rows + [("exact", "", float(abs(self.exact.multipliers[0])), 0.0)]


def hill_against_floquet(scene: Scene, harmonics: Sequence[int] = HARMONICS, *,
                         method: Adaptive | Accuracy = CERTIFYING_METHOD,
                         tolerance: float = CERTIFYING_TOLERANCE) -> HillFloquet:
    """The ``HillFloquet`` of ``scene`` at each of ``harmonics`` (module docstring).

    Parameters
    ----------
    scene : Scene
        A scene harmonic balance carries (``harmonic_balance``).
    harmonics : sequence of int
        The numbers of harmonics H ≥ 1, at least one (sorted; the exact orbit is shot
        from the largest's series).
    method, tolerance
        The exact orbit's accuracy, as ``certify``'s: the errors read no less than the
        multipliers' own error at that accuracy (about 1e-12 at ``Adaptive(rtol=1e-12)``
        and a residual of 1e-12).

    Raises
    ------
    ConvergenceError
        Shooting does not converge from the series of most harmonics.
    """
    owner = "hill_against_floquet"
    check_instance(owner, "scene", scene, Scene, expected="a Scene")
    harmonics = check_sequence(owner, "harmonics", harmonics,
                               expected="a sequence of ints ≥ 1", min_length=1)
    harmonics = np.array(sorted({check_int(owner, "harmonics", h, low=1, most=MOST_HARMONICS)
                                 for h in harmonics}))
    check_instance(owner, "method", method, (Adaptive, Accuracy),
                   expected="Adaptive(...) or Accuracy(...)")
    check_real(owner, "tolerance", tolerance, low=SMALLEST_TOLERANCE, high=1e-3)
    orbits = tuple(harmonic_balance(scene, int(h), stability=True) for h in harmonics)
    exact = certify(orbits[-1], method=method, tolerance=tolerance).exact
    errors = np.array([[float(np.abs(orbit.multipliers - mu).min())
                        for mu in exact.multipliers] for orbit in orbits])
    return HillFloquet(scene=scene, harmonics=harmonics, orbits=orbits, exact=exact,
                       errors=errors)
