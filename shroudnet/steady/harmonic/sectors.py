"""A tuned ring's harmonic balance on one sector: the harmonics' inter-sector phase lag.

A tuned ring of N identical sectors forced by an engine-order wave of order l has a
symmetric steady state, y(t + Δ) = S y(t) with Δ = l T_e / N (``steady.cyclic``: S moves
each sector's coordinates to the next one's, the sectors' frames included). Harmonic k
of ω = 2π/T_e turns that into a phase: sector s's complex amplitudes are sector 0's
turned by s θ_k,

    X_s,k = e^{i s θ_k} X_0,k,        θ_k = 2π k l / N,

and so are its contacts' coordinates and forces (a contact one sector on is its twin's
motion Δ later, under the same laws). Over the engine's coordinates η, sector by sector
(p = s m + j), sector 0's equations under that lag are those of the sector alone with
its neighbours folded in,

    D_θ X_0 = Q_0 − R_θᴴ Λ_0,        D_θ = Σ_j D[0, j] e^{i j θ},
    Z_0 = R_θ X_0,                    R_θ = Σ_j G_0[:, j] e^{i j θ},

with D = K − (kω)² M + ikω C, its blocks D[0, j] between sectors 0 and j, G_0 the rows of
sector 0's contacts (``model``) and D[0, j], G_0[:, j] their blocks over sector j (a
contact of sector 0 may read the next sector's coordinates; the forces of the other
sectors' contacts on sector 0 are R_θᴴ's: a contact s sectors on reads sector 0 through
the block −s of its twin, turned by s θ). The balance keeps only sector 0's contacts,

    W_k = R_θ D_θ⁻¹ R_θᴴ,     Z_k^lin = R_θ D_θ⁻¹ Q_0,k,

m/N contact coordinates and a factorisation of the sector's size per harmonic: the
cost of one sector, the ring's contacts N times fewer unknowns. The whole ring's series
follows by the lag (``SectorCondensed.recover``), and from it the orbit's outputs on
the whole ring: its contacts' forces computed once on every contact, the energy per
cycle, and Hill's stability (on the whole ring, its perturbations breaking the symmetry
included: an eigenvalue problem of the whole ring's size). The time samples are a
multiple of N/g (``lag_samples``), so that the lag maps samples onto samples and the
sector's orbit solves the whole ring's balance, not an approximation of it.
"""

from __future__ import annotations

import dataclasses
from dataclasses import dataclass

import numpy as np
import scipy.linalg

from ..cyclic import CyclicSymmetry, contact_sectors
from .aft import contact_forces
from .condensation import Condensed
from .fourier import complex_amplitudes, real_coefficients
from .model import HarmonicModel
from .newton import NewtonOutcome


@dataclass(frozen=True, eq=False)
class SectorCondensed(Condensed):
    """``Condensed`` for sector 0's contacts under the phase lag (module docstring):
    ``compliance`` and ``linear`` are the sector's W_k and Z^lin; ``to_contacts``
    ((H+1) × m_s × m₀) and ``to_load`` ((H+1) × m_s) give sector 0's response,
    ``lags`` θ_k (H+1) turn it round the ``sectors`` N."""

    sectors: int
    lags: np.ndarray

    def truncated(self, harmonics: int) -> "SectorCondensed":
        """The same sector for fewer harmonics."""
        cut = Condensed.truncated(self, harmonics)
        return SectorCondensed(**{f.name: getattr(cut, f.name)
                                  for f in dataclasses.fields(Condensed)},
                               sectors=self.sectors, lags=self.lags[:harmonics + 1])

    def recover(self, forces: np.ndarray) -> np.ndarray:
        """The whole ring's coefficients ((2H+1) × N m_s) from sector 0's contacts' forces:
        X_s,k = e^{i s θ_k} (D_θ⁻¹ Q_0,k − D_θ⁻¹ R_θᴴ Λ_0,k)."""
        first = self.to_load - np.einsum("kna,ka->kn", self.to_contacts,
                                         complex_amplitudes(forces))
        turns = np.exp(1j * np.outer(self.lags, np.arange(self.sectors)))  # (H+1) × N
        whole = turns[:, :, None] * first[:, None, :]
        return real_coefficients(whole.reshape(len(self.lags), -1))


def lag_samples(samples: int, symmetry: CyclicSymmetry) -> int:
    """``samples`` rounded up to a multiple of N/g (g = gcd(l, N)): then the lag of one
    sector, Δ = l T/N, moves the time samples onto samples, and the contacts' forces
    computed on sector 0's contacts are those the whole ring's samples give (a force
    with kinks sampled at other instants aliases differently: at 90 samples a period on
    24 sectors in engine order 5, the orbits of the sector and of the whole ring
    differed by 8e-4 of the motion; at 96 they are one)."""
    step = symmetry.repeats
    return -(-samples // step) * step


def sector_blocks(matrix: np.ndarray, sectors: int) -> np.ndarray:
    """Sector 0's rows of ``matrix`` (… × N m_s) split by the sector of its columns:
    (… × N × m_s)."""
    return matrix.reshape(matrix.shape[:-1] + (sectors, matrix.shape[-1] // sectors))


def first_sector_model(ring: HarmonicModel, symmetry: CyclicSymmetry) -> HarmonicModel:
    """``ring`` with sector 0's contacts alone (their coordinates renumbered from 0): what
    the contacts' forces are computed on while the balance is solved."""
    sector = contact_sectors(ring.scene, len(ring.scene.blades) // symmetry.sectors)
    kept, rows, start = [], [], 0
    for contact in ring.contacts:
        if sector[contact.index] != 0:
            continue
        kept.append(dataclasses.replace(
            contact, columns=slice(start, start + contact.size)))
        rows.append(ring.rows[contact.columns])
        start += contact.size
    return dataclasses.replace(
        ring, contacts=tuple(kept),
        rows=np.vstack(rows) if rows else np.zeros((0, ring.n_coordinates)))


def kept_columns(ring: HarmonicModel, sector: HarmonicModel) -> np.ndarray:
    """The columns of the ring's contact coordinates that sector 0's contacts are."""
    where = {c.index: c.columns for c in ring.contacts}
    return np.concatenate([np.arange(where[c.index].start, where[c.index].stop)
                           for c in sector.contacts]).astype(int)


def condense_sector(ring: HarmonicModel, sector: HarmonicModel, symmetry: CyclicSymmetry,
                    harmonics: int) -> SectorCondensed:
    """The ``SectorCondensed`` of sector 0 for H harmonics (module docstring): per
    harmonic one factorisation of D_θ (m_s square)."""
    n_sectors, m_s = symmetry.sectors, symmetry.per_sector
    lags = 2.0 * np.pi * symmetry.engine_order * np.arange(harmonics + 1) / n_sectors
    load = ring.load_coefficients(harmonics)[:, :m_s]
    first_rows = slice(0, m_s)
    stiffness, damping, mass = (sector_blocks(matrix[first_rows], n_sectors)
                                for matrix in (ring.stiffness, ring.damping, ring.mass))
    rows = sector_blocks(sector.rows, n_sectors)
    m0 = sector.n_contact_coordinates
    compliance = np.empty((harmonics + 1, m0, m0), dtype=complex)
    linear = np.empty((harmonics + 1, m0), dtype=complex)
    to_contacts = np.empty((harmonics + 1, m_s, m0), dtype=complex)
    to_load = np.empty((harmonics + 1, m_s), dtype=complex)
    for k, lag in enumerate(lags):
        turns = np.exp(1j * lag * np.arange(n_sectors))
        rate = k * ring.frequency
        dynamic = np.einsum("ajb,j->ab", stiffness - rate * rate * mass
                            + 1j * rate * damping, turns)
        reading = np.einsum("ajb,j->ab", rows, turns)  # R_θ (m₀ × m_s)
        factor = scipy.linalg.lu_factor(dynamic, check_finite=False)
        solved = scipy.linalg.lu_solve(
            factor, np.column_stack([reading.conj().T, load[k]]), check_finite=False)
        to_contacts[k], to_load[k] = solved[:, :m0], solved[:, m0]
        compliance[k] = reading @ to_contacts[k]
        linear[k] = reading @ to_load[k]
    return SectorCondensed(harmonics=harmonics, compliance=compliance,
                           linear=real_coefficients(linear), to_contacts=to_contacts,
                           to_load=to_load, sectors=n_sectors, lags=lags)


def whole_ring(ring: HarmonicModel, condensed: SectorCondensed, basis, found: NewtonOutcome,
               jacobian: bool) -> tuple[NewtonOutcome, np.ndarray, np.ndarray]:
    """(Newton's outcome on the whole ring, its coefficients over η, the contacts'
    coordinates with every contact open) from sector 0's: every contact's coordinates
    read from the ring's series, their forces computed once on the whole ring."""
    modal = condensed.recover(found.value.coefficients)
    z = modal @ ring.rows.T
    forces = contact_forces(ring, basis, z, jacobian)
    opened = condensed.recover(np.zeros_like(found.value.coefficients)) @ ring.rows.T
    outcome = NewtonOutcome(z, forces, found.residual, found.iterations, found.tolerance,
                            found.message)
    return outcome, modal, opened
