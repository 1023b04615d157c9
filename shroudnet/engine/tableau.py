"""Runge–Kutta coefficients, and their weighted sums over a step's stages.

The Dormand–Prince 5(4) pair (Dormand & Prince 1980) with Shampine's dense output of
order 4, as in Hairer, Nørsett & Wanner, *Solving ODEs I*, §II.5–6. ``Tableau`` checks its
own consistency when built; the compiled code reads the module constants ``DP_*``.
"""

from __future__ import annotations

from typing import NamedTuple

import numpy as np

from .compiled import njit_inlined


class Tableau(NamedTuple):
    """An explicit Runge–Kutta pair with an embedded error estimate and dense output.

    c : nodes (s,);  a : stage coefficients (s, s − 1), strictly lower triangular;
    b : weights of the propagated order (s + 1,), the last for the first-same-as-last
    stage at the step's end; e : propagated minus embedded weights (s + 1,), so the
    local error estimate is h Σ_j e_j k_j; p : dense output, y(t + θh) =
    y + h Σ_j k_j Σ_k p[j, k] θ^(k+1), (s + 1, order).
    """

    c: np.ndarray
    a: np.ndarray
    b: np.ndarray
    e: np.ndarray
    p: np.ndarray

    def check(self, tolerance: float = 1e-14) -> Tableau:
        """The tableau itself, after checking the conditions every such pair meets.

        Raises ``ValueError`` naming the first that fails: each node is its row sum of
        a (Σ_k a_jk = c_j), the weights and the embedded weights are consistent
        (Σ b = 1, Σ e = 0), the dense output meets y and the step's end (at θ = 1 it
        gives b), and the pair is first-same-as-last (the last node is 1, and b leaves
        out the stage at the step's end, which becomes the next step's first).
        """
        conditions = {
            "row sums of a equal c": np.abs(self.a.sum(axis=1) - self.c).max(),
            "sum of b is 1": abs(self.b.sum() - 1.0),
            "sum of e is 0": abs(self.e.sum()),
            "dense output at theta = 1 gives b": np.abs(self.p.sum(axis=1) - self.b).max(),
            "last node is 1 (first same as last)": abs(self.c[-1] - 1.0),
            "b gives no weight to the stage at the step's end": abs(self.b[-1]),
        }
        for condition, error in conditions.items():
            if not error <= tolerance:
                raise ValueError(f"Runge–Kutta tableau: {condition} fails by {error:.3g}")
        return self


DORMAND_PRINCE = Tableau(
    c=np.array([0.0, 1 / 5, 3 / 10, 4 / 5, 8 / 9, 1.0]),
    a=np.array([
        [0.0, 0.0, 0.0, 0.0, 0.0],
        [1 / 5, 0.0, 0.0, 0.0, 0.0],
        [3 / 40, 9 / 40, 0.0, 0.0, 0.0],
        [44 / 45, -56 / 15, 32 / 9, 0.0, 0.0],
        [19372 / 6561, -25360 / 2187, 64448 / 6561, -212 / 729, 0.0],
        [9017 / 3168, -355 / 33, 46732 / 5247, 49 / 176, -5103 / 18656],
    ]),
    b=np.array([35 / 384, 0.0, 500 / 1113, 125 / 192, -2187 / 6784, 11 / 84, 0.0]),
    e=np.array([-71 / 57600, 0.0, 71 / 16695, -71 / 1920, 17253 / 339200, -22 / 525,
                1 / 40]),
    p=np.array([
        [1.0, -8048581381 / 2820520608, 8663915743 / 2820520608,
         -12715105075 / 11282082432],
        [0.0, 0.0, 0.0, 0.0],
        [0.0, 131558114200 / 32700410799, -68118460800 / 10900136933,
         87487479700 / 32700410799],
        [0.0, -1754552775 / 470086768, 14199869525 / 1410260304,
         -10690763975 / 1880347072],
        [0.0, 127303824393 / 49829197408, -318862633887 / 49829197408,
         701980252875 / 199316789632],
        [0.0, -282668133 / 205662961, 2019193451 / 616988883, -1453857185 / 822651844],
        [0.0, 40617522 / 29380423, -110615467 / 29380423, 69997945 / 29380423],
    ]),
).check()

DP_C, DP_A, DP_B, DP_E, DP_P = DORMAND_PRINCE
#: Stages of a Dormand–Prince step, the first-same-as-last stage at its end included.
DP_STAGES = len(DP_B)


#: Fractions of an adaptive step where the kinematic guards, and the breakaway margins of
#: stuck interfaces, are checked on the dense output, so that a contact that closes and
#: opens again within one step, or a static friction that passes μ_s N and falls back, is
#: not missed.
DIP_POINTS = np.array([0.25, 0.5, 0.75])


@njit_inlined
def stage_sum(weights, stages, n_stages, column):
    """Σ_k weights[k] · stages[k, column] over the first ``n_stages`` Runge–Kutta stages."""
    total = 0.0
    for k in range(n_stages):
        total += weights[k] * stages[k, column]
    return total
