"""Scales a run can represent: refuse, before any work, a scene whose numbers cannot be run.

A float holds magnitudes up to about 1.8e308, and the integrators take at least
``SMALLEST_STEP`` of an excitation period a step. A scene can be valid field by field and
still not be runnable: a coupling of 1e300 N/m makes a natural frequency whose stable step
is far below the smallest step, and so does a tangential stiffness of 1e300 N/m; a speed of
1e-300 rpm makes an excitation period of 1e301 s in which no blade motion can be followed,
and one of 1e300 rpm a period whose smallest step is no normal float; an initial velocity
of 1e300 m/s has a kinetic energy no float holds. ``check_scales`` finds these from the
scene's arrays and names the quantity, where the run would otherwise stop much later with
an unrelated message (a non-finite state blamed on a contact law) or finish with a NaN in
its energy ledger.
"""

from __future__ import annotations

import math

import numpy as np

from ..engine.controller import SMALLEST_STEP
from .simulation import SimulationError

#: The largest step, in units of 1/ω, that an explicit Runge–Kutta step stays stable at
#: on an undamped oscillator of angular frequency ω (classical RK4: 2√2; Dormand–Prince
#: reaches a little more on the real axis, a little less on the imaginary one).
STABLE_STEP = 2.8

#: The largest energy [J] a run may carry: the integrators square the state in their error
#: norms and the energy ledger sums products of forces and displacements, so quantities
#: whose energy exceeds the square root of the largest float (1.3e154) overflow. Any real
#: blade group is below 1e10 J by far.
LARGEST_ENERGY = 1e150

#: The smallest normal float: below it a float loses digits (subnormal numbers), and a
#: step or a time of that size cannot be told from its neighbours.
SMALLEST_NORMAL = float(np.finfo(float).tiny)

#: The most blades for which the fixed step is checked against the exact largest natural
#: frequency (one symmetric eigenvalue problem of that size); a larger scene, or one with
#: substructures (whose mass matrix is not diagonal), is checked with the adaptive bound.
EXACT_LIMIT = 2000


def fastest_rate(matrix: np.ndarray, mass: np.ndarray) -> tuple[float, int]:
    """An upper bound of the largest eigenvalue of M⁻¹ A for a non-negative-definite A
    (a stiffness or damping matrix) and the diagonal mass M, with the row that sets it:
    Gershgorin's bound max_i Σ_j |A_ij| / m_i (no work beyond a pass over the matrix)."""
    with np.errstate(over="ignore", invalid="ignore"):
        rows = np.abs(matrix).sum(axis=1) / mass
    if rows.size == 0:
        return 0.0, -1
    row = int(np.nanargmax(rows)) if not np.isnan(rows).all() else 0
    return float(rows[row]), row


def check_scales(scene, periods: int, method, initial) -> None:
    """Refuse, before any work, a run whose numbers a float cannot carry (see
    ``scale_limits``); the ``SimulationError`` says the run cannot start at t = 0 s."""
    try:
        scale_limits(scene, periods, method, initial)
    except SimulationError as error:
        raise SimulationError(f"the run cannot start (t = 0 s): {error}") from None


def scale_limits(scene, periods: int, method, initial) -> None:
    """Refuse, before any work, a run whose numbers a float cannot carry.

    Checks, in this order: the smallest step of the excitation period is a normal float
    (``SMALLEST_NORMAL``); the stiffness and damping matrices are finite; the largest
    natural frequency ω_max = √(max eig M⁻¹K) and the fastest damping rate max eig M⁻¹C
    allow a stable step no shorter than the smallest step (``SMALLEST_STEP`` excitation
    periods; with ``FixedStep``, the fixed step), and so does each contact's stiffness
    (``_check_contacts``); the initial state's energy, the energy
    the excitation can put into the blades (q²/k) and the prescribed motions' (m v²) stay
    below ``LARGEST_ENERGY``. ``initial`` is (x0, v0) by blade position, already checked
    finite. Raises ``SimulationError`` naming the quantity and its value: the scene is
    valid, but no run of it can be carried out (so a sweep takes it for a failed point).
    """
    from .methods import FixedStep

    a = scene.arrays
    period = scene.excitation_period
    mass = np.asarray(a.mass, dtype=float)
    stiffness, damping = a.stiffness_matrix(), a.damping_matrix()
    where = (f"at speed_rpm = {scene.speed_rpm:g} (excitation period T_e = {period:g} s, "
             f"engine order {scene.excitation.engine_order})")
    if SMALLEST_STEP * period < SMALLEST_NORMAL:
        raise SimulationError(
            f"Scene.speed_rpm = {scene.speed_rpm:g} rpm makes an excitation period T_e = "
            f"{period:.3g} s (engine order {scene.excitation.engine_order}), whose smallest "
            f"step, {SMALLEST_STEP:g} T_e = {SMALLEST_STEP * period:.3g} s, is below the "
            f"smallest normal float, {SMALLEST_NORMAL:.3g}: no step of a run could be told "
            "from the next. Check the units of the speed (rev/min).")
    for name, matrix, unit in (("stiffness", stiffness, "N/m"),
                               ("damping", damping, "N·s/m")):
        if not np.isfinite(matrix).all():
            raise SimulationError(f"the scene's {name} matrix overflows (an entry is inf): its "
                             f"entries add up beyond the largest float, 1.8e308 {unit}")
    if isinstance(method, FixedStep):
        smallest, which = period / method.steps_per_period, (
            f"the fixed step T_e/{method.steps_per_period} (FixedStep.steps_per_period)")
    else:
        smallest, which = SMALLEST_STEP * period, (
            f"the smallest step, {SMALLEST_STEP:g} excitation periods")
    omega_squared, row = fastest_rate(stiffness, mass)
    if isinstance(method, FixedStep) and np.isfinite(omega_squared):
        # A bound is not enough where the step itself is at stake: the exact largest
        # eigenvalue of M⁻¹K, for blades (diagonal M), small enough to take it.
        if a.is_structure or len(mass) > EXACT_LIMIT:
            omega_squared = 0.0
        elif len(mass):
            scaled = stiffness / np.sqrt(np.outer(mass, mass))
            omega_squared = float(np.linalg.eigvalsh(scaled)[-1])
    omega = math.sqrt(max(omega_squared, 0.0))
    if omega * smallest > STABLE_STEP:
        raise SimulationError(
            f"{_stiffest(scene, row)} makes a natural frequency √(k/m) of up to {omega:.3g} "
            f"rad/s, whose stable step ({STABLE_STEP:g}/ω = {STABLE_STEP / omega:.3g} s) is "
            f"below {which} = {smallest:.3g} s {where}: the run cannot follow the motion. "
            "Check the units of the stiffness, mass and speed.")
    rate, row = fastest_rate(damping, mass)
    if isinstance(method, FixedStep) and np.isfinite(rate):
        if a.is_structure or len(mass) > EXACT_LIMIT:
            rate = 0.0
        elif len(mass):
            rate = float(np.linalg.eigvalsh(damping / np.sqrt(np.outer(mass, mass)))[-1])
    if rate * smallest > STABLE_STEP:
        raise SimulationError(
            f"{_most_damped(scene, row)} makes a damping rate c/m of up to {rate:.3g} 1/s, "
            f"whose stable step ({STABLE_STEP / rate:.3g} s) is below {which} = "
            f"{smallest:.3g} s {where}: the run cannot follow the motion. Check the units "
            "of the damping, mass and speed.")
    _check_contacts(scene, mass, where)
    x0, v0 = initial
    with np.errstate(over="ignore", invalid="ignore"):
        kinetic = 0.5 * np.sum(mass * v0 * v0)
        strain = 0.5 * abs(x0 @ stiffness @ x0)
    for name, energy in (("initial velocities v0", kinetic),
                         ("initial displacements x0", strain)):
        if not energy <= LARGEST_ENERGY:
            raise SimulationError(f"initial: the {name} carry an energy of {energy:.3g} J, more "
                             f"than the {LARGEST_ENERGY:g} J a run can represent: its "
                             "state would become non-finite")
    _check_forcing(scene, mass, stiffness)
    _check_motions(scene, mass, stiffness, periods * period)


def _check_contacts(scene, mass, where) -> None:
    """The stiffest contact: each interface's tangential stiffness k_t (an elastic
    contact), and its normal law's ∂N/∂δ where that is one number (a law of constant
    slopes), on the masses the contact joins. A contact of stiffness k along the row g of
    the free coordinates (its normal, or a tangent) adds k g gᵀ to the stiffness: the
    natural frequency of that rank-one term, ω² = k gᵀ M⁻¹ g, must allow a stable step no
    shorter than the smallest step any method takes (a contact is closed only at times, so
    a fixed step is not held to it here: the run tells if it is too long)."""
    a = scene.arrays
    n = a.n_blades
    smallest = SMALLEST_STEP * scene.excitation_period
    normal = a.normal_rows_over_coordinates()[:, :n]
    tangents = [a.slip_rows(direction)[:, :n] for direction in (1, 2)]
    for e, (left, right, interface) in enumerate(scene.group.interfaces):
        law = a.normal_laws[e]
        stiffnesses = []
        if type(law).opens and type(law).constant_slopes:
            stiffnesses.append((f"its normal law's stiffness ∂N/∂δ ({type(law).__name__})",
                                abs(float(law.gradient(1.0, 0.0)[0])), [normal[e]]))
        if interface.elastic:
            stiffnesses.append(("its tangential_stiffness", interface.tangential_stiffness,
                                [rows[e] for rows in tangents]))
        for what, value, rows in stiffnesses:
            with np.errstate(over="ignore", invalid="ignore"):
                squared = max(value * float(np.sum(row * row / mass)) for row in rows)
            omega = math.sqrt(squared) if squared < math.inf else math.inf
            if omega * smallest > STABLE_STEP:
                raise SimulationError(
                    f"interface {e} ({left!r}, {right!r}): {what}, {value:g} N/m, on the "
                    f"masses it joins makes a natural frequency of up to {omega:.3g} rad/s, "
                    f"whose stable step ({STABLE_STEP / omega:.3g} s) is below the smallest "
                    f"step of any method, {SMALLEST_STEP:g} excitation periods = "
                    f"{smallest:.3g} s {where}: no run can follow the contact. Check the "
                    "units of the stiffness and the masses.")


def _check_forcing(scene, mass, stiffness) -> None:
    """The energy the excitation's amplitudes put into a blade, q² / (k + m ω_e²)."""
    a = scene.arrays
    load = np.abs(a.harmonic_amplitudes).sum(axis=0)
    if load.size == 0 or not load.any():
        return
    with np.errstate(over="ignore", invalid="ignore"):
        resistance = np.diag(stiffness) + mass * np.float64(a.excitation_frequency) ** 2
        energy = load * load / resistance
    worst = int(np.nanargmax(np.where(np.isnan(energy), np.inf, energy)))
    if not energy[worst] <= LARGEST_ENERGY:
        raise SimulationError(
            f"Excitation.amplitudes: a force of {load[worst]:.3g} N on "
            f"{scene.blades[worst] if worst < len(scene.blades) else worst!r} puts an "
            f"energy of order {energy[worst]:.3g} J into it (q²/(k + m ω_e²)), more than the "
            f"{LARGEST_ENERGY:g} J a run can represent: its state would become non-finite")


def _check_motions(scene, mass, stiffness, duration) -> None:
    """The prescribed motions' displacements and velocities over the run, against the
    largest mass and stiffness they can push."""
    a = scene.arrays
    if not a.motions:
        return
    times = np.linspace(0.0, duration, 5)
    with np.errstate(over="ignore", invalid="ignore"):
        x, v = a.prescribed_state(times)
        energy = (0.5 * mass.max() * np.abs(v).max() ** 2
                  + 0.5 * np.abs(np.diag(stiffness)).max() * np.abs(x).max() ** 2)
    if not energy <= LARGEST_ENERGY:
        names = [name for name, _ in scene.group.prescribed]
        raise SimulationError(
            f"prescribed node {names[0] if len(names) == 1 else names!r}: its motion (up to "
            f"{np.abs(x).max():.3g} m, {np.abs(v).max():.3g} m/s) carries an energy of order "
            f"{energy:.3g} J against the blades it drives, more than the {LARGEST_ENERGY:g} "
            "J a run can represent: its state would become non-finite")


def _stiffest(scene, row) -> str:
    """Words for what sets the stiffest row: the blade's own stiffness or a coupling's."""
    return _culprit(scene, row, "stiffness", "N/m")


def _most_damped(scene, row) -> str:
    return _culprit(scene, row, "damping", "N·s/m")


def _culprit(scene, row, what, unit) -> str:
    a = scene.arrays
    if a.is_structure or row < 0:
        return f"the scene's {what} (row {row} of its matrix, mass {a.mass[row]:.3g})"
    own = float((a.stiffness if what == "stiffness" else a.damping)[row])
    values = a.coupling_stiffness if what == "stiffness" else a.coupling_damping
    couplings = [(abs(float(c)), e) for e, (c, i, j) in enumerate(
        zip(values, a.coupling_left, a.coupling_right)) if row in (i, j)]
    blade = scene.blades[row] if row < len(scene.blades) else row
    if couplings and max(couplings)[0] > abs(own):
        value, e = max(couplings)
        left, right, _ = scene.group.couplings[e]
        return (f"the coupling {what} {value:g} {unit} between {left!r} and {right!r} "
                f"(on blade {blade!r} of mass {a.mass[row]:g} kg)")
    return f"blade {blade!r}: its {what} {own:g} {unit} on a mass of {a.mass[row]:g} kg"
