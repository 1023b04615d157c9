"""Newton's method with a backtracking line search, on the condensed equations.

Each step solves J Δ = −R and takes z + α Δ with the largest α of 1, ½, ¼, … that
lowers ‖R‖₂ by the fraction ``DESCENT`` α of it (Armijo's rule on ½‖R‖²); where no α
down to 2⁻``HALVINGS`` does, the iteration stops there and says so. The residual is
measured as max |R| over a scale (the contacts' motion), so that a tolerance means a
fraction of it.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass

import numpy as np

#: Newton steps at most, halvings of one step at most, and the sufficient decrease.
ITERATIONS = 50
HALVINGS = 30
DESCENT = 1e-4


@dataclass(frozen=True, eq=False)
class NewtonOutcome:
    """Where Newton stopped: the unknowns ``z``, what the function gave there
    (``value``), the ``residual`` max |R| / scale reached, the ``iterations`` taken,
    whether the residual meets ``tolerance`` (``converged``), and why it stopped
    (``message``)."""

    z: np.ndarray
    value: object
    residual: float
    iterations: int
    tolerance: float
    message: str

    @property
    def converged(self) -> bool:
        return self.residual <= self.tolerance


def newton(evaluate: Callable, z: np.ndarray, scale: Callable[[np.ndarray], float],
           tolerance: float, iterations: int = ITERATIONS) -> NewtonOutcome:
    """Newton with a line search from ``z`` on ``evaluate(z, jacobian)`` → (R, J or
    None, value), R flat, J its square Jacobian; the residual max |R| / ``scale(z)``."""
    residual_vector, jacobian, value = evaluate(z, True)
    size = float(np.abs(residual_vector).max()) / scale(z)
    for iteration in range(iterations + 1):
        if size <= tolerance:
            return NewtonOutcome(z, value, size, iteration, tolerance,
                                 f"converged: residual {size:.3g} of the contacts' motion")
        if iteration == iterations:
            break
        try:
            change = -np.linalg.solve(jacobian, residual_vector)
        except np.linalg.LinAlgError:
            change = -np.linalg.lstsq(jacobian, residual_vector, rcond=None)[0]
        norm = np.linalg.norm(residual_vector)
        fraction = 1.0
        for _ in range(HALVINGS + 1):
            trial = z + fraction * change.reshape(z.shape)
            trial_vector, _, _ = evaluate(trial, False)
            if np.linalg.norm(trial_vector) <= (1.0 - DESCENT * fraction) * norm:
                break
            fraction /= 2.0
        else:
            return NewtonOutcome(z, value, size, iteration, tolerance,
                                 f"stopped: no step along Newton's direction lowers the "
                                 f"residual {size:.3g} (the equations are not smooth "
                                 f"enough there, or the start is too far from an orbit: "
                                 f"give a guess, or continue from a nearby orbit)")
        z = trial
        residual_vector, jacobian, value = evaluate(z, True)
        size = float(np.abs(residual_vector).max()) / scale(z)
    return NewtonOutcome(z, value, size, iterations, tolerance,
                         f"stopped after {iterations} Newton steps at the residual "
                         f"{size:.3g} (asked {tolerance:.3g})")
