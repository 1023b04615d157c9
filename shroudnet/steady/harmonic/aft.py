"""The contacts' forces in time (alternating frequency–time) and their Jacobian.

From the contact coordinates' coefficients z ((2H+1) × m) the samples r(t_n) and
ṙ(t_n) of every contact follow (``fourier``); at each sample each contact gives

- its penetration δ = ν·r − g and rate δ̇ = ν·ṙ, and its normal force N from its normal
  law, N(δ, δ̇) where the contact is closed (δ > 0, or always for a law that never
  opens) and 0 where it is open, as the engine has it;
- its friction force: for an elastic contact the Jenkins slider marched over the
  period (``hysteresis``) with the limit μ_s N; for a regularised law
  f = μ(|v|) N tanh(v/v_ε) with the slip velocity v = τ₁·ṙ;

and λ = N ν + f₁ τ₁ + f₂ τ₂ (``model``), whose discrete Fourier transform is λ̂.

Only the laws' own functions are called (``normal_force``, its gradient, the friction
coefficient and its slope, by ``contact_laws``' interface): a law of one's own needs no
code here. The Jacobian ∂λ̂/∂z is exact for what is computed: a memoryless force at t_n
depends on r(t_n) and ṙ(t_n) alone, so ∂λ̂_j/∂z_l = Σ_n F_jn (∂λ/∂r)_n E_nl +
(∂λ/∂ṙ)_n Ė_nl (E the synthesis, Ė its rate, F the analysis), and a slider's force
carries its derivatives through the march. The derivatives in ṙ alone are kept apart
too (``velocity_jacobian``): Hill's method needs them (``hill``).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from .fourier import FourierBasis
from .hysteresis import periodic_hysteresis
from .model import ELASTIC, REGULARISED, Contact, HarmonicModel


@dataclass(frozen=True, eq=False)
class ContactForces:
    """The contacts' forces over one period at the samples t_n (N of them):
    ``normal`` N (N × interfaces) [N], ``friction`` f along τ₁ and τ₂ (N × interfaces ×
    2) [N], ``generalised`` λ (N × m), and its coefficients ``coefficients`` λ̂
    ((2H+1) × m). With the Jacobian: ``jacobian`` ∂λ̂/∂z and ``velocity_jacobian``, the
    part of it through ṙ (both m(2H+1) square, harmonic-major: index j·m + a). For the
    elastic contacts, ``stretches`` u = f/k_t at t = 0 (2 each, in interface order: the
    third member of a run's ``initial``), the ``hysteresis_periods`` their sliders took
    to repeat (the most of any) and whether all did (``repeated``)."""

    normal: np.ndarray
    friction: np.ndarray
    generalised: np.ndarray
    coefficients: np.ndarray
    stretches: np.ndarray
    hysteresis_periods: int
    repeated: bool
    jacobian: np.ndarray | None = None
    velocity_jacobian: np.ndarray | None = None


def normal_samples(contact: Contact, penetration, rate, gradient: bool):
    """(N, ∂N/∂δ, ∂N/∂δ̇) at each sample from the normal law's own functions; 0 where the
    contact is open (the gradients None without ``gradient``)."""
    law = contact.normal_law
    function, parameters = type(law).normal_force, contact.normal_parameters
    closed = np.flatnonzero((penetration > 0.0) | (not contact.opens))
    force = np.zeros(len(penetration))
    depths, speeds = penetration[closed], rate[closed]
    force[closed] = at_samples(function, depths, speeds, parameters)
    if not gradient:
        return force, None, None
    slope, damping = np.zeros(len(penetration)), np.zeros(len(penetration))
    if type(law).has_analytic_gradient():
        derivative = type(law).normal_force_gradient
        values = at_samples(derivative, depths, speeds, parameters, 2)
    else:
        values = np.array([law.gradient(d, v) for d, v in zip(depths.tolist(),
                                                              speeds.tolist())]).T
    if len(closed):
        slope[closed], damping[closed] = values
    return force, slope, damping


#: The law functions found to branch on their arguments (``at_samples``): called sample
#: by sample from then on, without trying the arrays again.
SCALAR_ONLY: set = set()


def at_samples(function, depths: np.ndarray, speeds: np.ndarray, parameters,
               outputs: int = 1) -> np.ndarray:
    """A law's scalar function of (δ, δ̇, *parameters) at every sample: called once on
    the arrays where its code is numpy's arithmetic (a linear spring, Hertz's power: its
    ``outputs`` results broadcast to the samples), else sample by sample (a law whose
    code branches on its penetration cannot take arrays, and says so by raising)."""
    shape = (outputs, len(depths)) if outputs > 1 else (len(depths),)
    if function not in SCALAR_ONLY:
        try:
            values = np.asarray(function(depths, speeds, *parameters), dtype=float)
            return values if values.shape == shape else np.broadcast_to(values, shape)
        except Exception:  # noqa: BLE001 - whatever a scalar code raises on arrays
            SCALAR_ONLY.add(function)
    return np.array([function(d, v, *parameters) for d, v in zip(depths.tolist(),
                                                                  speeds.tolist())],
                    dtype=float).reshape(len(depths), *shape[:-1]).T


def regularised_samples(contact: Contact, speed):
    """(μ(|v|) tanh(v/v_ε), its derivative in v [s/m]) at each slip velocity ``speed``
    [m/s] from the exact law's coefficient and slope."""
    exact = contact.friction_law.exact
    function, parameters = type(exact).coefficient, contact.friction_parameters
    magnitudes = np.abs(speed).tolist()
    mu = np.array([function(v, *parameters) for v in magnitudes])
    slope = np.array([exact.slope(v) for v in magnitudes])
    smooth = np.tanh(speed / contact.regularisation)
    value = mu * smooth
    rate = slope * np.sign(speed) * smooth + mu * (1.0 - smooth * smooth) / \
        contact.regularisation
    return value, rate


def outer(values, first, second) -> np.ndarray:
    """values_n first_a second_b (N × ρ × ρ)."""
    return values[:, None, None] * np.multiply.outer(first, second)[None]


def contact_forces(model: HarmonicModel, basis: FourierBasis, z: np.ndarray,
                   jacobian: bool = True, reading: np.ndarray | None = None
                   ) -> ContactForces:
    """The ``ContactForces`` at the coefficients z ((2H+1) × m), with the Jacobian if
    asked (module docstring). Where the contact coordinates are read from fewer ones,
    z = y Eᵀ with ``reading`` E (m × r, ``balance``), the Jacobians are those in y,
    (I ⊗ Eᵀ) ∂λ̂/∂z (I ⊗ E), assembled contact by contact."""
    synthesis, rate_synthesis, analysis = basis.synthesis, basis.rate, basis.analysis
    count, size = basis.samples, basis.size
    m = model.n_contact_coordinates
    r, rdot = synthesis @ z, rate_synthesis @ z
    interfaces = model.scene.arrays.n_interfaces
    normal_force = np.zeros((count, interfaces))
    friction = np.zeros((count, interfaces, 2))
    generalised = np.zeros((count, m))
    blocks, rate_blocks = [], []  # (J × ρ × J × ρ block, its contact's columns)
    stretches, periods, repeated = [], 0, True
    for contact in model.contacts:
        columns, rho = contact.columns, contact.size
        local_r, local_rate = r[:, columns], rdot[:, columns]
        penetration = local_r @ contact.normal - contact.gap
        force, slope, damping = normal_samples(contact, penetration,
                                               local_rate @ contact.normal, jacobian)
        normal_force[:, contact.index] = force
        local = force[:, None] * contact.normal[None, :]
        if jacobian:  # ∂λ/∂r and ∂λ/∂ṙ at each sample, of the memoryless forces
            by_r = outer(slope, contact.normal, contact.normal)
            by_rate = outer(damping, contact.normal, contact.normal)
        hysteretic = None
        if contact.friction_kind == REGULARISED:
            tangent = contact.tangents[0]
            value, value_rate = regularised_samples(contact, local_rate @ tangent)
            along = force * value
            friction[:, contact.index, 0] = along
            local = local + along[:, None] * tangent[None, :]
            if jacobian:
                by_r += outer(slope * value, tangent, contact.normal)
                by_rate += outer(damping * value, tangent, contact.normal) \
                    + outer(force * value_rate, tangent, tangent)
        elif contact.friction_kind == ELASTIC:
            slider = elastic_forces(contact, basis, local_r, penetration, force, slope,
                                    damping, jacobian)
            friction[:, contact.index] = slider.force
            local = local + slider.force @ contact.tangents
            stretches.append(slider.force[0] / contact.tangential_stiffness)
            periods = max(periods, slider.periods)
            repeated = repeated and slider.repeated
            if jacobian:  # ∂λ/∂z through the slider: τᵀ ∂f/∂z (N × ρ × J ρ)
                hysteretic = slider.jacobian
        generalised[:, columns] = local
        if jacobian:
            # Σ_n F_jn (A_n E_nl + B_n Ė_nl) as one product over the samples; the terms in
            # ṙ only where a force depends on it (a damped law, regularised friction)
            rate_dependent = bool(np.any(by_rate))
            samples = by_r[..., None] * synthesis[:, None, None, :]
            if rate_dependent:
                samples = samples + by_rate[..., None] * rate_synthesis[:, None, None, :]
            block = (analysis @ samples.reshape(count, -1)).reshape(size, rho, rho, size)
            block = block.transpose(0, 1, 3, 2)
            if hysteretic is not None:
                block = block + (analysis @ hysteretic.reshape(count, -1)).reshape(
                    size, rho, size, rho)
            blocks.append((block, columns))
            if rate_dependent:
                rate_samples = by_rate[..., None] * synthesis[:, None, None, :]
                rate_blocks.append(((analysis @ rate_samples.reshape(count, -1)).reshape(
                    size, rho, rho, size).transpose(0, 1, 3, 2), columns))
    stretch_array = np.concatenate(stretches) if stretches else np.zeros(0)
    if jacobian:
        total = assembled(blocks, size, m, reading)
        through_rate = assembled(rate_blocks, size, m, reading)
    else:
        total = through_rate = None
    return ContactForces(normal=normal_force, friction=friction, generalised=generalised,
                         coefficients=analysis @ generalised, stretches=stretch_array,
                         hysteresis_periods=periods, repeated=repeated, jacobian=total,
                         velocity_jacobian=through_rate)


def elastic_forces(contact: Contact, basis: FourierBasis, local_r, penetration, force, slope,
                   damping, jacobian: bool):
    """The ``hysteresis.Hysteresis`` of an elastic contact: its slider driven by
    r_t = τ r under the limit μ_s N, with the derivatives of both in the contact's
    coefficients z_(l,b) (index l ρ + b): ∂r_t,n = E_nl τ_cb and
    ∂(μ_s N)_n = μ_s (N'_δ E_nl + N'_δ̇ Ė_nl) ν_b, ∂δ_n = E_nl ν_b."""
    count = basis.samples
    tangential = local_r @ contact.tangents.T
    limit = contact.static_mu * force
    if jacobian:
        unknowns = basis.size * contact.size
        drt = (basis.synthesis[:, None, :, None] * contact.tangents[None, :, None, :]
               ).reshape(count, 2, unknowns)
        dlimit = (contact.static_mu * (slope[:, None] * basis.synthesis
                                       + damping[:, None] * basis.rate)[:, :, None]
                  * contact.normal[None, None, :]).reshape(count, unknowns)
        ddepth = (basis.synthesis[:, :, None] * contact.normal[None, None, :]).reshape(
            count, unknowns)
    else:
        drt, dlimit, ddepth = np.zeros((count, 2, 0)), np.zeros((count, 0)), \
            np.zeros((count, 0))
    return periodic_hysteresis(tangential, limit, penetration, drt, dlimit, ddepth,
                               contact.tangential_stiffness,
                               np.ascontiguousarray(contact.tangents))


def assembled(blocks, size: int, m: int, reading: np.ndarray | None) -> np.ndarray:
    """The harmonic-major matrix (index j·m + a) of the contacts' blocks (each J × ρ × J
    × ρ at its contact's columns); with ``reading`` E, the matrix in y (index j·r + s),
    Σ_c E_cᵀ block_c E_c (E_c the contact's rows of E), contacts of one ρ in one
    product."""
    unknowns = size * (m if reading is None else reading.shape[1])
    matrix = np.zeros((unknowns, unknowns))
    for rho in sorted({block.shape[1] for block, _ in blocks}):
        group = [(block, columns) for block, columns in blocks if block.shape[1] == rho]
        stack = np.stack([block for block, _ in group])  # C × J × ρ × J × ρ
        if reading is None:
            for block, columns in zip(stack, (columns for _, columns in group)):
                index = (np.arange(size)[:, None] * m
                         + np.arange(columns.start, columns.stop)).ravel()
                matrix[np.ix_(index, index)] += block.reshape(len(index), len(index))
            continue
        local = np.stack([reading[columns] for _, columns in group])  # C × ρ × r
        count, r = len(group), reading.shape[1]
        right = np.matmul(stack.reshape(count, -1, rho), local)  # C × (J ρ J) × r
        right = right.reshape(count, size, rho, size * r).transpose(0, 2, 1, 3)
        left = local.reshape(count * rho, r).T @ right.reshape(count * rho, -1)
        matrix += left.reshape(r, size, size, r).transpose(1, 0, 2, 3).reshape(
            unknowns, unknowns)
    return matrix
