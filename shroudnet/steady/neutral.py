"""Neutral directions: a contact stuck through a whole orbit leaves its offset free.

While an interface stays stuck, the quantity its stick freezes does not move: with rigid
stick, its tangential relative displacement r_t = T x (``SceneArrays.slip_rows``); with
elastic stick (a Jenkins element), its slider's position w = r_t − u, u the spring's
stretch (two of them, along t₁ and t₂ of the face; on a face of one direction
t₂ = 0, and w₂ = −u₂). Nothing else in the orbit's equations fixes that offset: any value
within the friction limit gives an orbit, so the orbits form a family, and the
stroboscopic map has a multiplier exactly 1 along it — not a fold, not a loss of
stability, and a Newton matrix Φ − I that is singular.

The condition that picks one orbit of the family, stated here once: **each frozen
offset keeps its value in the start** — the guess's, the transient's end, or the last
point's of a branch (``pin_rows``: one row c per offset, c · y = c · y_start). Newton
solves with those rows appended; the multipliers of the family's directions (the one
nearest +1 per pinned offset: ``tested``) are left out of the stability and bifurcation
tests, and the orbit names its neutral interfaces (``PeriodicOrbit.neutral``).
"""

from __future__ import annotations

import numpy as np

from ..model.scene import Scene

#: A pin row whose part independent of the rows before it is this small (relative) adds
#: nothing (a closed loop of stuck interfaces freezes one offset fewer than it has).
DEPENDENT = 1e-10


def pin_rows(scene: Scene, stuck: np.ndarray) -> tuple[tuple[int, ...], np.ndarray]:
    """(the interfaces stuck through the whole orbit, per ``stuck``, that leave an offset
    free; their rows c, one per offset, on the state y = (x, ẋ[, u])): r_t = T_e x for a
    rigid stick, w_d = T_{e,d} x − u_{e,d} (d = 1, 2) for an elastic one, linearly
    independent rows only."""
    a = scene.arrays
    n = a.n_blades
    size = 2 * n + a.n_stretches
    elastic = list(a.elastic_interfaces)
    first, second = a.slip_rows(1)[:, :n], a.slip_rows(2)[:, :n]
    rows, owners = [], []
    for e in np.flatnonzero(stuck):
        candidates = []
        if e in elastic:
            k = 2 * n + 2 * elastic.index(e)
            for d, slip in enumerate((first, second)):
                row = np.zeros(size)
                row[:n] = slip[e]
                row[k + d] = -1.0
                candidates.append(row)
        else:
            row = np.zeros(size)
            row[:n] = first[e]
            candidates.append(row)
        for row in candidates:
            if _independent(rows, row):
                rows.append(row)
                if int(e) not in owners:
                    owners.append(int(e))
    return tuple(owners), np.array(rows).reshape(len(rows), size)


def _independent(rows: list, row: np.ndarray) -> bool:
    """Whether ``row`` adds a direction to ``rows`` (its residual after projecting them out
    is above ``DEPENDENT`` of its length)."""
    size = np.linalg.norm(row)
    if size == 0.0:
        return False
    if not rows:
        return True
    basis = np.linalg.qr(np.array(rows).T)[0]
    rest = row - basis @ (basis.T @ row)
    return np.linalg.norm(rest) > DEPENDENT * size


#: How near +1 a multiplier must lie to be a family's direction (``tested``): it is 1 to
#: the accuracy of the monodromy.
NEUTRAL = 1e-6


def tested(multipliers: np.ndarray, neutral: int) -> np.ndarray:
    """``multipliers`` less those of a family's directions: the ``neutral`` nearest +1,
    of those within ``NEUTRAL`` of it (Arnoldi finds one of a repeated multiplier 1
    only), in their order."""
    if neutral == 0 or len(multipliers) == 0:
        return multipliers
    distance = np.abs(multipliers - 1.0)
    drop = [k for k in np.argsort(distance, kind="stable")[:neutral]
            if distance[k] <= NEUTRAL]
    keep = np.ones(len(multipliers), dtype=bool)
    keep[drop] = False
    return multipliers[keep]
