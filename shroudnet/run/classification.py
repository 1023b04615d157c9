"""The kind of a steady motion: the ``Classification`` record and its labels.

A plain record, kept apart from the analysis that computes it (``analysis.classify``), so
that the records runs return (a sweep point holds one) need no study to be read, built or
loaded.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

from ..checked_records import check_record

#: Labels besides "p1" … "pN".
QUASI_PERIODIC = "quasi-periodic"
CHAOTIC = "chaotic"
UNDETERMINED = "undetermined"
#: The label of a failed sweep point's classification.
FAILED = "failed"

#: The default tolerance of a repeat (``classify``, ``classify_section``, ``sweep``):
#: Poincaré points N periods apart closer than this, relative to the steady response's
#: largest |x| and |ẋ|, make the motion pN.
REPEAT_TOLERANCE = 1e-5


@dataclass(frozen=True)
class Classification:
    """The kind of a steady motion, with the evidence for it.

    ``label`` is "p1", "p2", … "pN" (the response repeats after N excitation periods),
    "quasi-periodic", "chaotic", or "undetermined" when the record cannot tell (``reason``
    says why). ``period`` is N, or None. ``mismatch`` is the largest distance between
    Poincaré points N periods apart relative to the attractor's size (for the best N tried
    when none repeats). ``lyapunov`` is the largest Lyapunov exponent λ_max per period and
    ``lyapunov_error`` its standard error (``stability.lyapunov``; NaN where it was not
    computed): the main evidence between chaos and quasi-periodicity. ``zero_one`` is the
    0–1 test's K on the Poincaré displacements (near 1: chaos; near 0: regular), NaN with
    too few points; ``broadband`` is the fraction of the spectrum's power outside its 20
    strongest lines: both secondary evidence.
    """

    label: str
    period: int | None
    n_points: int
    tolerance: float
    mismatch: float
    zero_one: float
    broadband: float
    lyapunov: float = math.nan
    lyapunov_error: float = math.nan
    reason: str = ""

    #: Fields that may hold NaN or ±inf (see ``checked_records``).
    NON_FINITE = ("tolerance", "mismatch", "zero_one", "broadband", "lyapunov", "lyapunov_error")

    def __post_init__(self):
        check_record(self)

    def __str__(self) -> str:
        exponent = "" if math.isnan(self.lyapunov) else (
            f"λ_max = {self.lyapunov:+.3g} ± {self.lyapunov_error:.1g} per period, ")
        why = f" ({self.reason})" if self.reason else ""
        return (f"{self.label}{why}: {self.n_points} Poincaré points, repeat mismatch "
                f"{self.mismatch:.1e} (tolerance {self.tolerance:g}), {exponent}0-1 test K = "
                f"{self.zero_one:.2f}, broadband fraction {self.broadband:.1e}")

    @classmethod
    def failed(cls, tolerance: float = math.nan) -> Classification:
        """The classification of a point whose simulation stopped: label "failed", no
        points, NaN evidence; ``tolerance`` is the one the point would have used."""
        return cls(label=FAILED, period=None, n_points=0, tolerance=tolerance,
                   mismatch=math.nan, zero_one=math.nan, broadband=math.nan)
