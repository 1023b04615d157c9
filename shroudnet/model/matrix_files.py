"""Reading finite-element matrices from files: numpy ``.npz`` and MATLAB ``.mat``.

An FE tool exports its mass and stiffness matrices (ANSYS, Abaqus, NASTRAN through a small
script; MATLAB with ``save('blade.mat', 'M', 'K', '-v7')``). The matrices are found by name:

- ``.npz`` (``numpy.savez``): a dense array under the name, or a sparse matrix as
  coordinate triplets under ``<name>_rows``, ``<name>_cols``, ``<name>_values`` (0-based) and
  ``<name>_shape``. Pickled objects are refused.
- ``.mat`` (``scipy.io.savemat``, MATLAB up to v7): dense or sparse variables. MATLAB's
  v7.3 files are HDF5, which ``scipy.io.loadmat`` does not read: save with ``-v7``.

Units are the file's: give SI (kg, N/m) or know what the frequencies mean.
"""

from __future__ import annotations

import os
import zipfile
from dataclasses import dataclass
from pathlib import Path

import numpy as np
import scipy.io
import scipy.sparse

from contact_laws import check_array

from ..machine import machine_memory
from .substructure import Substructure, square_matrix

#: The file kinds read, by extension.
EXTENSIONS = (".npz", ".mat")
#: The arrays of a sparse matrix stored as coordinate triplets in an ``.npz``.
TRIPLET_SUFFIXES = ("_rows", "_cols", "_values", "_shape")


@dataclass(frozen=True, eq=False)
class FEMatrices:
    """The matrices read from one file: each an (N, N) float ndarray or ``csr_array``.

    ``damping`` and ``stiffness_speed`` are None where they were not asked for.
    """

    path: Path
    mass: object
    stiffness: object
    damping: object = None
    stiffness_speed: object = None

    @property
    def n_dofs(self) -> int:
        """N, the number of degrees of freedom of the file's model."""
        return self.mass.shape[0]


def read_matrices(path, mass: str = "M", stiffness: str = "K", damping: str | None = None,
                  stiffness_speed: str | None = None) -> FEMatrices:
    """Read M and K (and C, K₁ where ``damping``, ``stiffness_speed`` name them) from an
    ``.npz`` or ``.mat`` file.

    Parameters
    ----------
    path : str or Path
        The file; its extension, ``.npz`` or ``.mat``, says how to read it.
    mass, stiffness, damping, stiffness_speed : str
        The names of the matrices in the file (K₁ of K(Ω) = K₀ + Ω² K₁: see
        ``Substructure.stiffness_speed``).

    Returns
    -------
    FEMatrices
        Square float matrices of one size, dense or sparse as stored; their symmetry and
        definiteness are checked where they are used (``Substructure``, the reductions).

    Examples
    --------
    >>> import numpy as np, tempfile, pathlib
    >>> file = pathlib.Path(tempfile.mkdtemp()) / "blade.npz"
    >>> np.savez(file, M=np.eye(2), K=np.array([[2.0, -1.0], [-1.0, 1.0]]))
    >>> read_matrices(file).stiffness
    array([[ 2., -1.],
           [-1.,  1.]])
    """
    if not isinstance(path, str | os.PathLike):
        raise TypeError(f"read_matrices.path must be a file name (str or Path), got "
                        f"{type(path).__name__} {path!r:.80}")
    path = Path(path)
    if path.suffix.lower() not in EXTENSIONS:
        raise ValueError(f"read_matrices.path: read_matrices reads {' and '.join(EXTENSIONS)} "
                         f"files, got {path.name!r}")
    if not path.is_file():
        raise FileNotFoundError(f"read_matrices: no file {str(path)!r}")
    arrays = _read_npz(path) if path.suffix.lower() == ".npz" else _read_mat(path)
    names = {"mass": mass, "stiffness": stiffness, "damping": damping,
             "stiffness_speed": stiffness_speed}
    matrices = {}
    for field, name in names.items():
        if name is None and field in ("mass", "stiffness"):
            raise TypeError(f"read_matrices.{field} must be the name of a matrix in the file, "
                            "got None")
        if name is None:
            continue
        if not isinstance(name, str):
            raise TypeError(f"read_matrices.{field} must be the name of a matrix in the file, "
                            f"got {type(name).__name__}")
        if name not in arrays:
            found = ", ".join(sorted(arrays)) or "nothing"
            raise ValueError(f"{path.name!r} has no matrix {name!r} ({field}=); it holds: "
                             f"{found}")
        matrices[field] = square_matrix(f"{path.name}[{name!r}] ({field})", arrays[name])
    size = matrices["mass"].shape[0]
    for field, matrix in matrices.items():
        if matrix.shape[0] != size:
            raise ValueError(f"{path.name!r}: the {field} matrix {names[field]!r} is "
                             f"{matrix.shape[0]} × {matrix.shape[0]}, the mass {size} × {size}")
    return FEMatrices(path=path, **matrices)


def substructure_from_file(path, *, points, load=None, mass: str = "M", stiffness: str = "K",
                           damping: str | None = None, damping_ratios=None,
                           excitation_scale: float = 1.0) -> Substructure:
    """A ``Substructure`` of the matrices in ``path`` (see ``read_matrices``) with the given
    ``points``, ``load``, ``damping_ratios`` and ``excitation_scale`` (as for
    ``Substructure``). For a model too large to use as it is, read the matrices and reduce
    them (``craig_bampton``, ``modal_truncation``) instead."""
    matrices = read_matrices(path, mass=mass, stiffness=stiffness, damping=damping)
    return Substructure(matrices.mass, matrices.stiffness, matrices.damping,
                        damping_ratios=damping_ratios, points=points, load=load,
                        excitation_scale=excitation_scale)


def _read_npz(path: Path) -> dict[str, object]:
    _check_not_empty(path)
    if not zipfile.is_zipfile(path):  # what numpy.savez writes; else np.load guesses pickle
        raise ValueError(f"{path.name!r} is not a .npz archive (numpy.savez writes a zip "
                         f"archive of arrays): {path} holds something else")
    try:
        with np.load(path, allow_pickle=False) as archive:
            arrays = {name: archive[name] for name in archive.files}
    except (ValueError, OSError, EOFError, zipfile.BadZipFile) as error:
        raise ValueError(f"{path.name!r} is not a readable .npz of numeric arrays ({error})") \
            from None
    for name in [key[:-len("_rows")] for key in arrays if key.endswith("_rows")]:
        parts = [f"{name}{suffix}" for suffix in TRIPLET_SUFFIXES]
        if name in arrays or not all(part in arrays for part in parts):
            continue
        arrays[name] = _triplet_matrix(path, name, *(arrays.pop(part) for part in parts))
    return arrays


def _triplet_matrix(path: Path, name: str, rows, cols, values, shape) -> scipy.sparse.csr_array:
    """The sparse matrix ``name`` of the coordinate triplets ``rows``, ``cols``, ``values``
    and its ``shape``, each array checked and named as ``FILE.name_rows``: the shape two
    whole sizes ≥ 1 whose row index fits in this machine's memory; the indices whole
    numbers (0-based) within it, one of each per value; the values finite real numbers.
    """
    owner = path.name
    size = _whole(owner, f"{name}_shape", shape, 1, np.inf, "sizes")
    if size.shape != (2,):
        raise ValueError(f"{owner}.{name}_shape must hold two sizes (rows, columns), got "
                         f"{np.ravel(shape).tolist()}")
    memory, index = machine_memory(), 8 * (int(size[0]) + 1)
    if memory is not None and index > memory:
        raise ValueError(f"{owner}.{name}_shape = {size.tolist()}: a sparse matrix of "
                         f"{size[0]:,} rows needs {index / 2**30:,.0f} GiB for its row index "
                         f"alone, more than the {memory / 2**30:.3g} GiB of memory this "
                         "machine has")
    row = _whole(owner, f"{name}_rows", rows, 0, size[0] - 1, "0-based indices")
    col = _whole(owner, f"{name}_cols", cols, 0, size[1] - 1, "0-based indices")
    value = check_array(owner, f"{name}_values", values, shape=(None,))
    for field, count in ((f"{name}_cols", len(col)), (f"{name}_values", len(value))):
        if count != len(row):
            raise ValueError(f"{owner}.{field} must hold one entry per row index of "
                             f"{name}_rows ({len(row)}), got {count}")
    return scipy.sparse.coo_array((value, (row, col)), shape=tuple(size)).tocsr()


def _whole(owner: str, field: str, value, low: float, high: float, what: str) -> np.ndarray:
    """``value`` as a 1-d int64 array of whole numbers in [``low``, ``high``] (an index
    stored as a float is taken if it is whole), or ``check_array``'s error naming
    ``owner.field``; a ValueError for a number with a fraction, which would be cut."""
    array = check_array(owner, field, np.ravel(value) if np.ndim(value) == 0 else value,
                        shape=(None,), low=low, high=high)
    fraction = array != np.floor(array)
    if fraction.any():
        raise ValueError(f"{owner}.{field} must hold whole numbers ({what}), got "
                         f"{array[fraction][0]:g} at position {int(np.argmax(fraction))}")
    return array.astype(np.int64)


def _read_mat(path: Path) -> dict[str, object]:
    _check_not_empty(path)
    try:
        contents = scipy.io.loadmat(str(path))
    except NotImplementedError:
        raise ValueError(f"{path.name!r} is a MATLAB v7.3 (HDF5) file, which this reader "
                         "does not read: save it with save(..., '-v7')") from None
    except (ValueError, OSError, EOFError, scipy.io.matlab.MatReadError) as error:
        raise ValueError(f"{path.name!r} is not a readable .mat file ({error})") from None
    return {name: value for name, value in contents.items() if not name.startswith("__")}


def _check_not_empty(path: Path) -> None:
    if path.stat().st_size == 0:
        raise ValueError(f"{path.name!r} is empty (0 bytes): {path} holds no matrices")
