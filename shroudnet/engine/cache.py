"""Where compiled kernels are kept, how much room they take, and clearing them.

Generated kernel headers and numba's compiled code for every kernel (its phase modules,
``kernel``, compiled for its laws and method) live in one folder: ``$SHROUDNET_CACHE``,
else ``~/.cache/shroudnet``. numba keeps the compiled code of the engine's own modules
beside them, in the package's ``__pycache__`` folders.
"""

from __future__ import annotations

import os
import shutil
from pathlib import Path

_ENGINE = Path(__file__).parent
_NUMBA_SUFFIXES = (".nbi", ".nbc")


def cache_folder() -> Path:
    """Where generated kernels and numba's compiled code for them are kept."""
    folder = os.environ.get("SHROUDNET_CACHE") or Path.home() / ".cache" / "shroudnet"
    return Path(folder)


def _engine_files() -> list[Path]:
    return [p for p in _ENGINE.rglob("__pycache__/*") if p.suffix in _NUMBA_SUFFIXES]


def cache_size() -> tuple[int, int]:
    """(bytes, files) held by the kernel folder and the engine's compiled code."""
    files = [p for p in cache_folder().rglob("*") if p.is_file()] if cache_folder().exists() \
        else []
    files += _engine_files()
    return sum(p.stat().st_size for p in files), len(files)


def clear_cache() -> int:
    """Delete every compiled kernel and the engine's compiled code; returns bytes freed.

    The next run compiles again (announced, once per combination of law classes).
    """
    freed, _ = cache_size()
    if cache_folder().exists():
        shutil.rmtree(cache_folder())
    for path in _engine_files():
        path.unlink(missing_ok=True)
    return freed
