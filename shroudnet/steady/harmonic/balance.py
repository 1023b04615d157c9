"""Harmonic balance: a periodic orbit as a truncated Fourier series, solved on the
contact coordinates alone.

The linear structure is condensed onto the contacts harmonic by harmonic
(``condensation``), the contacts' forces are computed in time from the series of their
coordinates and transformed back (``aft``), and Newton's method with a line search
(``newton``) solves the balance R(z) = z − z^lin + W λ̂(z) = 0 for the contact
coordinates' 2H + 1 coefficients each, its Jacobian I + W ∂λ̂/∂z exact. Every
coordinate's series follows from the solution, in the engine's coordinates η, and
crosses to the nodes' own degrees of freedom q through ``model.lowering.to_dofs``; from
it every output (``orbit``). Hill's method gives the stability (``hill``).

The unknowns are m (2H + 1), m the contacts' coordinates (two or three a contact, one
for a blade pair), whatever the structure's size: the cost of a Newton step is the
contacts' forces at N samples and a dense solve of that size, the structure's
factorisations being done once per frequency.
"""

from __future__ import annotations

import dataclasses
from dataclasses import dataclass
from functools import cached_property

import numpy as np

from contact_laws import check_instance, check_int, check_real

from ...model.lowering import to_dofs
from ...model.scene import Scene
from ...run.simulate import MAX_PERIODS
from ..cyclic import symmetry_of
from .aft import ContactForces, contact_forces
from .condensation import Condensed, condense
from .fourier import FourierBasis, extremes, mean_product, samples_for
from .hill import hill_exponents, multipliers_of
from .model import ELASTIC, HarmonicModel, harmonic_model, independent_directions
from .newton import ITERATIONS, NewtonOutcome, newton
from .orbit import HarmonicOrbit, energy_per_cycle, kinetic_peak
from .sectors import condense_sector, first_sector_model, kept_columns, lag_samples, whole_ring

#: The residual max |R| / scale a balance is solved to by default.
BALANCE_TOLERANCE = 1e-10
#: The residual the levels of the ``ladder`` below the last are solved to: they are
#: starts, nearer the orbit than their own truncation error is.
LADDER_TOLERANCE = 1e-4
#: The most harmonics a series may hold, and the most time samples a period.
MOST_HARMONICS = 1000
MOST_SAMPLES = 100_000


@dataclass(frozen=True, eq=False)
class Balance:
    """A scene's balance for H harmonics: its model, time samples and condensed
    structure, and the map y ↦ (R, ∂R/∂y) Newton solves.

    The unknowns y are the contact coordinates z themselves, or, where the contacts'
    rows are fewer directions than their coordinates (a patch of many points on a
    blade of few modes), the coordinates of those directions: z = y Eᵀ with ``reading``
    E (m × r, orthonormal columns, ``contact_span``), the structure condensed onto them
    and the forces' Jacobian taken in them (``aft``). On a tuned ring solved on one
    sector (``sectors``), ``model`` holds sector 0's contacts, which are the unknowns,
    and ``ring`` the whole ring, on which the orbit's outputs are read; else ``ring`` is
    None."""

    model: HarmonicModel
    basis: FourierBasis
    condensed: Condensed
    ring: HarmonicModel | None = None
    reading: np.ndarray | None = None

    @property
    def shape(self) -> tuple[int, int]:
        """(2H + 1, r): the unknowns' shape."""
        return self.basis.size, self.condensed.linear.shape[1]

    def contact_coordinates(self, y: np.ndarray) -> np.ndarray:
        """z = y Eᵀ: the contact coordinates' coefficients of the unknowns'."""
        return y if self.reading is None else y @ self.reading.T

    def read_back(self, coefficients: np.ndarray) -> np.ndarray:
        """Coefficients over the contact coordinates (forces λ̂, or z) taken to the
        unknowns: λ̂ E (z E = y for z = y Eᵀ)."""
        return coefficients if self.reading is None else coefficients @ self.reading

    def evaluate(self, y: np.ndarray, jacobian: bool):
        """(R flat, ∂R/∂y or None, the ``ContactForces``) at y ((2H+1) × r)."""
        forces = contact_forces(self.model, self.basis, self.contact_coordinates(y),
                                jacobian, self.reading)
        residual = self.condensed.residual(y, self.read_back(forces.coefficients)).ravel()
        if not jacobian:
            return residual, None, forces
        return residual, np.eye(len(residual)) + self.condensed.apply_columns(
            forces.jacobian), forces

    def scale(self, y: np.ndarray) -> float:
        """The contacts' motion [m]: the largest coefficient of y or of y^lin."""
        return motion_scale(y, self.condensed.linear)

    @cached_property
    def kept(self) -> np.ndarray | None:
        """On a ring solved on one sector, the columns of the ring's contact coordinates
        that are the unknowns (sector 0's contacts'); else None."""
        return None if self.ring is None else kept_columns(self.ring, self.model)

    def unknowns_of(self, coefficients: np.ndarray) -> np.ndarray:
        """The unknowns of the coefficients of the scene's contact coordinates: all of
        them read back (``read_back``), or on a ring solved on one sector those of
        sector 0's contacts (given either way)."""
        if self.kept is not None and coefficients.shape[1] == self.ring.n_contact_coordinates:
            return coefficients[:, self.kept]
        if self.reading is not None and coefficients.shape[1] == self.reading.shape[0]:
            return self.read_back(coefficients)
        return coefficients

    def whole(self, found: NewtonOutcome, jacobian: bool
              ) -> tuple[HarmonicModel, NewtonOutcome, np.ndarray, float]:
        """(the model the orbit is read on, Newton's outcome on its contact coordinates
        with the contacts' forces, their Jacobian in z where ``jacobian``, every
        coordinate's coefficients over the engine's η, the contacts' motion [m]) where
        Newton stopped: the scene's own, or on a ring solved on one sector the whole
        ring's (``sectors.whole_ring``)."""
        if self.ring is not None:
            outcome, modal, opened = whole_ring(self.ring, self.condensed, self.basis,
                                                found, jacobian)
            return self.ring, outcome, modal, motion_scale(outcome.z, opened)
        forces = found.value  # computed on z = y Eᵀ; its Jacobian, if any, in y
        if jacobian and (self.reading is not None or forces.jacobian is None):
            forces = contact_forces(self.model, self.basis,
                                    self.contact_coordinates(found.z), jacobian)
        modal = self.condensed.recover(self.read_back(forces.coefficients))
        z = self.contact_coordinates(found.z)
        outcome = dataclasses.replace(found, z=z, value=forces)
        return self.model, outcome, modal, motion_scale(
            z, self.contact_coordinates(self.condensed.linear))


def contact_span(rows: np.ndarray) -> tuple[np.ndarray, np.ndarray | None]:
    """(the rows the structure is condensed onto, the reading E or None): the contact
    coordinates' rows G (m × n) themselves where they are independent, else G = E B
    by the singular value decomposition G = U S Vᵀ, E = U_r (orthonormal columns) and
    B = S_r V_rᵀ over the r = rank G directions (a patch of nine 3-D points between
    blades of four modes each: 27 coordinates, at most 8 directions)."""
    if rows.shape[0] <= 1:
        return rows, None
    left, values, right = independent_directions(rows)
    if len(values) == rows.shape[0]:
        return rows, None
    return values[:, None] * right, left


def motion_scale(z: np.ndarray, linear: np.ndarray) -> float:
    """The contacts' motion [m]: the largest coefficient of z or of z^lin (1e-300 at
    rest)."""
    return max(float(np.abs(z).max(initial=0.0)), float(np.abs(linear).max(initial=0.0)),
               1e-300)


def balance_of(scene: Scene, harmonics: int, periods: int, samples: int,
               owner: str = "harmonic_balance", symmetry: str | None = None) -> Balance:
    """The ``Balance`` of ``scene`` (refusals named after ``owner``), on one sector of a
    tuned ring where ``symmetry`` (as ``harmonic_balance`` takes it) says so."""
    model = harmonic_model(scene, periods, owner)
    cyclic = symmetry_of(scene, periods, symmetry, owner)
    ring = reading = None
    if cyclic is None:
        rows, reading = contact_span(model.rows)
        condensed = condense(model, harmonics, rows)
    else:
        ring, model = model, first_sector_model(model, cyclic)
        condensed = condense_sector(ring, model, cyclic, harmonics)
        samples = lag_samples(samples, cyclic)
    basis = FourierBasis(harmonics, model.frequency, samples)
    if not np.all(np.isfinite(condensed.to_contacts)) or not np.all(
            np.isfinite(condensed.to_load)):
        raise ValueError(f"{owner}: the structure is at a resonance nothing damps at one of "
                         f"its harmonics (K − (kω)²M + ikωC is singular): give it damping")
    return Balance(model, basis, condensed, ring, reading)


def resized(coefficients: np.ndarray, harmonics: int) -> np.ndarray:
    """Coefficients of another series length cut or padded with zeros to H harmonics."""
    size = 2 * harmonics + 1
    out = np.zeros((size,) + coefficients.shape[1:])
    kept = min(size, coefficients.shape[0])
    out[:kept] = coefficients[:kept]
    return out


def first_guess(balance: Balance, guess, owner: str) -> np.ndarray | None:
    """Where Newton starts: ``guess`` (a ``HarmonicOrbit`` of the same scene's contacts, or
    the coefficients of any H of their contact coordinates z = B q, ``model``), checked;
    None without one (``solve``)."""
    size = balance.shape[0]
    if guess is None:
        return None
    if isinstance(guess, HarmonicOrbit):
        guess = guess.contact_coefficients
    try:
        values = None if isinstance(guess, str | bytes) else np.asarray(guess, dtype=float)
    except (TypeError, ValueError):
        values = None
    # the scene's contact coordinates (a ring's, or its first sector's)
    whole = (balance.ring or balance.model).n_contact_coordinates
    accepted = {whole, balance.model.n_contact_coordinates}
    if values is None or values.ndim != 2 or values.shape[1] not in accepted or \
            values.shape[0] % 2 != 1 or not np.all(np.isfinite(values)):
        raise ValueError(f"{owner}.guess must be a HarmonicOrbit of the scene or its "
                         f"contact coefficients ((2H'+1) × {whole} finite numbers), got "
                         f"{guess!r:.120}")
    return resized(balance.unknowns_of(values), (size - 1) // 2)


def truncated(balance: Balance, harmonics: int) -> Balance:
    """The balance of the same scene with fewer harmonics, its samples ``samples_for``
    them."""
    condensed = balance.condensed.truncated(harmonics)
    basis = FourierBasis(harmonics, balance.basis.frequency, samples_for(harmonics))
    return dataclasses.replace(balance, basis=basis, condensed=condensed)


def ladder(balance: Balance, tolerance: float, iterations: int,
           factor: int = 2) -> NewtonOutcome:
    """Newton on the balances of 1, ``factor``, ``factor``², … harmonics in turn, each
    from the last one's orbit, up to the balance's own: a hard nonlinearity (an impact,
    say) whose full series Newton cannot reach from the linear response is reached
    harmonic by harmonic (a level that does not converge hands on where its Newton
    stopped). The levels below the last are starts only, solved to
    ``LADDER_TOLERANCE``."""
    z = balance.condensed.linear[:3].copy()
    level = 1
    while level < balance.basis.harmonics:
        step = truncated(balance, level)
        z = newton(step.evaluate, resized(z, level), step.scale,
                   max(tolerance, LADDER_TOLERANCE), iterations).z
        level = factor * level
    return newton(balance.evaluate, resized(z, balance.basis.harmonics), balance.scale,
                  tolerance, iterations)


#: The quick ladder's levels grow by ``QUICK_FACTOR`` and its Newton takes at most
#: ``QUICK_ITERATIONS`` steps a level (``solve``).
QUICK_FACTOR = 3
QUICK_ITERATIONS = 12


def solve(balance: Balance, z0: np.ndarray | None, tolerance: float,
          iterations: int = ITERATIONS) -> NewtonOutcome:
    """Newton on the balance from z0, or without one up the ``ladder`` of harmonics (it
    reaches orbits of impacts that Newton from the linear response does not): first a
    quick ladder, its levels tripling and its Newton cut at ``QUICK_ITERATIONS`` steps,
    then the ladder whose levels double; where both fail, from the open contacts' linear
    response too; after a guess that fails, the same. The first that converges is
    returned, else the one of least residual. (On the six-blade packet at H = 7 the
    quick ladder converges in 38 ms, the doubling one in 59: 13 of its 27 Newton steps
    at H = 2; a Hertz contact with regularised Stribeck friction needs the doubling one
    at H = 5.)"""
    tries = []
    if z0 is not None:
        tries.append(lambda: newton(balance.evaluate, z0, balance.scale, tolerance,
                                    iterations))
    tries.append(lambda: ladder(balance, tolerance, min(iterations, QUICK_ITERATIONS),
                                QUICK_FACTOR))
    tries.append(lambda: ladder(balance, tolerance, iterations))
    tries.append(lambda: newton(balance.evaluate, balance.condensed.linear.copy(),
                                balance.scale, tolerance, iterations))
    best = None
    for attempt in tries:
        found = attempt()
        if found.converged:
            return found
        if best is None or found.residual < best.residual:
            best = found
    return best


def orbit_from(balance: Balance, found: NewtonOutcome, stability: bool) -> HarmonicOrbit:
    """The ``HarmonicOrbit`` where Newton stopped, read on the whole scene."""
    basis = balance.basis
    model, found, modal, scale = balance.whole(found, stability)
    forces: ContactForces = found.value
    scene = model.scene
    coefficients = to_dofs(scene.arrays.layout, modal)  # over the nodes' own q
    responses = scene.responses_of(coefficients)
    maximum, minimum = extremes(responses, basis.frequency)
    exponents = multipliers = np.zeros(0, dtype=complex)
    if stability:
        exponents = hill_exponents(model, basis, forces.jacobian, forces.velocity_jacobian)
        multipliers = multipliers_of(exponents, basis.period)
    return HarmonicOrbit(
        scene=scene, harmonic_count=basis.harmonics, periods=model.periods,
        samples=basis.samples, coefficients=coefficients,
        contact_coefficients=found.z.copy(), force_coefficients=forces.coefficients,
        stretches=stretches_by_interface(model, forces), residual=found.residual,
        tolerance=found.tolerance, iterations=found.iterations, scale=scale,
        message=found.message + ("" if forces.repeated else
                                 "; an elastic contact's hysteresis did not repeat"),
        exponents=exponents.astype(complex), multipliers=multipliers.astype(complex),
        maximum=maximum, minimum=minimum, mean=responses[0].copy(),
        mean_square=mean_product(responses, responses),
        peak=np.maximum(np.abs(maximum), np.abs(minimum)),
        energy_per_cycle=energy_per_cycle(model, basis, modal, found.z, forces),
        kinetic_peak=kinetic_peak(modal, model.mass, basis.frequency, basis.harmonics),
        hysteresis_periods=forces.hysteresis_periods, smooth=smooth_forces(model, forces),
        sectors=1 if balance.ring is None else balance.condensed.sectors)


#: A slider's force within this fraction of its limit μ_s N counts as slipping.
ON_THE_LIMIT = 1e-9


def smooth_forces(model: HarmonicModel, forces: ContactForces) -> bool:
    """Whether no contact both opens and closes over the period (an opening law's force 0
    at some samples and not at others), and no elastic contact both sticks and slips (its
    force on the limit μ_s N at some samples and inside it at others)."""
    for contact in model.contacts:
        normal = forces.normal[:, contact.index]
        closed = normal > 0.0
        if contact.opens and closed.any() and not closed.all():
            return False
        if contact.friction_kind == ELASTIC:
            size = np.hypot(*forces.friction[:, contact.index].T)
            slipping = closed & (size >= (1.0 - ON_THE_LIMIT) * contact.static_mu * normal)
            if slipping.any() and not slipping.all():
                return False
    return True


def stretches_by_interface(model: HarmonicModel, forces: ContactForces) -> np.ndarray:
    """The stretches at t = 0 in the order of the scene's elastic interfaces (2 each)."""
    elastic = model.scene.arrays.elastic_interfaces
    values = np.zeros(2 * len(elastic))
    found = {c.index: k for k, c in enumerate(model.elastic)}
    for slot, e in enumerate(elastic):
        if e in found:
            values[2 * slot:2 * slot + 2] = forces.stretches[2 * found[e]:2 * found[e] + 2]
    return values


def harmonic_balance(scene: Scene, harmonics: int, *, periods: int = 1, guess=None,
                     samples: int | None = None, tolerance: float = BALANCE_TOLERANCE,
                     iterations: int = ITERATIONS, stability: bool = True,
                     symmetry: str | None = None) -> HarmonicOrbit:
    """The periodic orbit of ``scene`` as a series of ``harmonics`` harmonics, by harmonic
    balance condensed onto the contacts (alternating frequency–time for their forces).

    Parameters
    ----------
    scene : Scene
        Its contacts may be any normal law (gaps that open, Hertz, a constant load, laws
        of one's own), elastic friction (``tangential_stiffness``, 1-D or a face's
        plane) or regularised friction; rigid stick and prescribed motion are refused
        (``model``).
    harmonics : int
        H ≥ 0: the series keeps the harmonics 0 … H of ω = l Ω / periods.
    periods : int
        k ≥ 1: the orbit's period is k T_e (a subharmonic orbit for k > 1).
    guess : HarmonicOrbit or array, optional
        Where Newton starts: an orbit of the same contacts (of any H: cut or padded; at
        another speed, say), or the coefficients of the contact coordinates z = B q
        ((2H'+1) × m, as ``HarmonicOrbit.contact_coefficients``: B an orthonormal basis,
        over the nodes' own degrees of freedom q, of the rows each contact's laws read,
        ``model``). Default: the orbits of 1, 2, 4, … harmonics
        in turn, each from the last (``ladder``), then the open contacts' linear response;
        both are tried where a guess fails.
    samples : int, optional
        N > 2H time samples per period for the contacts' forces; default
        ``fourier.samples_for(H)`` (8 H^{3/2}, at least 32), so that aliasing does not
        cap the accuracy as H grows.
    tolerance : float
        The residual max |R| / scale to reach, in [1e-14, 1e-2] (``HarmonicOrbit``).
    iterations : int
        Newton steps at most.
    stability : bool
        Compute Hill's exponents and multipliers (``hill``): an eigenvalue problem of
        2n(2H+1) unknowns, the costliest part for large H.
    symmetry : None, "cyclic" or "none"
        "cyclic": solve a tuned ring forced in engine order on one sector, the harmonics
        of its neighbours lagging by 2πkl/N (``sectors``; a ValueError says what breaks
        the symmetry where the scene has none, or where ``periods`` > 1); "none": the
        whole group; None (default): "cyclic" where the scene has the symmetry and
        ``periods`` is 1, as ``periodic_orbit``. The orbit is read on the whole ring
        either way (``HarmonicOrbit.sectors`` says which was solved), and Hill's
        stability is the whole ring's, symmetry-breaking perturbations included.

    Returns
    -------
    HarmonicOrbit
        Its series by the nodes' own degrees of freedom q, stacked in ``Scene.blades``
        order (the engine's modal coordinates stay inside the solve), whether it
        converged or not (``HarmonicOrbit.converged``, ``message``): a
        residual above ``tolerance`` is never called converged.

    Examples
    --------
    >>> import shroudnet as sn
    >>> orbit = sn.harmonic_balance(sn.scenes.jenkins_chain(), 7)
    >>> orbit.converged, round(orbit.amplitude("a") * 1e3, 3)
    (True, 5.116)
    """
    owner = "harmonic_balance"
    check_instance(owner, "scene", scene, Scene, expected="a shroudnet.Scene")
    harmonics = check_int(owner, "harmonics", harmonics, low=0, most=MOST_HARMONICS)
    periods = check_int(owner, "periods", periods, low=1, most=MAX_PERIODS)
    samples = samples_for(harmonics) if samples is None else check_int(
        owner, "samples", samples, low=2 * harmonics + 1, most=MOST_SAMPLES)
    check_real(owner, "tolerance", tolerance, low=1e-14, high=1e-2)
    iterations = check_int(owner, "iterations", iterations, low=0, most=10_000)
    check_instance(owner, "stability", stability, bool, expected="True or False")
    balance = balance_of(scene, harmonics, periods, samples, owner, symmetry)
    z0 = first_guess(balance, guess, owner)
    found = solve(balance, z0, tolerance, iterations)
    return orbit_from(balance, found, stability)
