"""Central differences of a map, column by column: what analytic Jacobians are checked
against."""

import numpy as np


def central_columns(function, x: np.ndarray, step: float) -> np.ndarray:
    """(f(x + h e_j) − f(x − h e_j)) / 2h for every entry j of ``x`` (any shape), as the
    columns of a matrix; ``function`` returns an array, taken flat."""
    columns = []
    for j in range(x.size):
        moved = np.zeros(x.size)
        moved[j] = step
        up, down = (np.ravel(function(x + sign * moved.reshape(x.shape)))
                    for sign in (1.0, -1.0))
        columns.append((up - down) / (2.0 * step))
    return np.column_stack(columns)
