"""An interface's support: the coordinates its rows reach, in a ``records.StructureScene``.

Interface e's rows (normal, tangents) are dense over the coordinates but nonzero on its
support only, listed as ``support_index[support_start[e]:support_start[e + 1]]``.
"""

from .compiled import njit_inlined


@njit_inlined
def row_dot(s, rows, e, values, first):
    """Σ_i rows[e, i] values[first + i] over interface e's coordinates (its support)."""
    total = 0.0
    for k in range(s.support_start[e], s.support_start[e + 1]):
        i = s.support_index[k]
        total += rows[e, i] * values[first + i]
    return total
