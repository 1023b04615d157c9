"""Newton's method with a backtracking line search, on the condensed equations.

Each step solves J Δ = −R and takes z + α Δ with the largest α of 1, ½, ¼, … that
lowers ‖R‖₂ by the fraction ``DESCENT`` α of it (Armijo's rule on ½‖R‖²). The balance
is only piecewise smooth (a contact's samples switch between stick and slip, open and
closed), and where Newton's direction, taken from one piece, lowers ‖R‖ by no step
(an impact's contact changing pieces at every step, say), Levenberg–Marquardt steps
(JᵀJ + μ I) Δ = −JᵀR are tried, μ growing tenfold from ``DAMPING_START`` of JᵀJ's
largest diagonal entry until one lowers ‖R‖: they turn towards steepest descent, which
lowers it wherever R is differentiable. Where none does, the iteration stops there and
says so. The residual is measured as max |R| over a scale (the contacts' motion), so
that a tolerance means a fraction of it.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass

import numpy as np

#: Newton steps at most, halvings of one step at most, and the sufficient decrease.
ITERATIONS = 50
HALVINGS = 30
DESCENT = 1e-4
#: The first Levenberg–Marquardt damping, as a fraction of JᵀJ's largest diagonal entry,
#: and the tenfold increases tried.
DAMPING_START = 1e-6
DAMPINGS = 8


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
    size = float(np.abs(residual_vector).max(initial=0.0)) / scale(z)
    hopeful = True
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
        # after a full step, the next full step is tried with its Jacobian: where it is
        # taken, as it mostly is near an orbit, its evaluation is the next iteration's
        evaluated = evaluate(z + change.reshape(z.shape), True) if hopeful else None
        if evaluated is not None and np.linalg.norm(evaluated[0]) <= (1.0 - DESCENT) * norm:
            z = z + change.reshape(z.shape)
        else:
            trial, fraction = line_search(evaluate, z, change, norm,
                                          first=0.5 if hopeful else 1.0)
            hopeful = fraction == 1.0
            if trial is None:
                trial = damped_step(evaluate, z, jacobian, residual_vector, norm)
            if trial is None:
                return NewtonOutcome(z, value, size, iteration, tolerance,
                                     f"stopped: no step along Newton's direction lowers "
                                     f"the residual {size:.3g} (the equations are not "
                                     f"smooth enough there, or the start is too far from "
                                     f"an orbit: give a guess, or continue from a nearby "
                                     f"orbit)")
            z = trial
            evaluated = evaluate(z, True)
        residual_vector, jacobian, value = evaluated
        size = float(np.abs(residual_vector).max(initial=0.0)) / scale(z)
    return NewtonOutcome(z, value, size, iterations, tolerance,
                         f"stopped after {iterations} Newton steps at the residual "
                         f"{size:.3g} (asked {tolerance:.3g})")


def line_search(evaluate, z, change, norm, first: float = 1.0):
    """(z + α Δ, α) with the largest α = ``first`` 2⁻ᵏ, k ≤ ``HALVINGS``, that meets
    Armijo's rule; (None, 0) where none does."""
    fraction = first
    for _ in range(HALVINGS + 1):
        trial = z + fraction * change.reshape(z.shape)
        if np.linalg.norm(evaluate(trial, False)[0]) <= (1.0 - DESCENT * fraction) * norm:
            return trial, fraction
        fraction /= 2.0
    return None, 0.0


def damped_step(evaluate, z, jacobian, residual_vector, norm):
    """z + Δ with (JᵀJ + μI) Δ = −JᵀR for the least μ tried that lowers ‖R‖; None where
    none does."""
    normal = jacobian.T @ jacobian
    gradient = jacobian.T @ residual_vector
    damping = DAMPING_START * float(np.diag(normal).max())
    for _ in range(DAMPINGS):
        change = -np.linalg.solve(normal + damping * np.eye(len(gradient)), gradient)
        trial = z + change.reshape(z.shape)
        if np.linalg.norm(evaluate(trial, False)[0]) < norm:
            return trial
        damping *= 10.0
    return None
