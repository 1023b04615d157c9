"""Where compiled kernels are kept, how much room they take, and clearing them.

Generated kernel headers and numba's compiled code for every kernel (its phase modules,
``kernel``, compiled for its laws and method) live in one folder: ``$SHROUDNET_CACHE``,
else ``~/.cache/shroudnet``. numba keeps the compiled code of the engine's own modules
beside them, in the package's ``__pycache__`` folders.

A folder that cannot take a new kernel (a file at its path or on its way, or a folder that
cannot be written) is refused when a kernel must be written there, before it is built, with a
``ValueError`` naming ``SHROUDNET_CACHE`` and the path, never an ``OSError`` from inside the
build; ``cache_size`` and ``clear_cache`` refuse it too. A folder that holds a kernel already
serves it even if it cannot be written (numba then keeps that kernel's compiled code in its
own cache: ``compiled._KernelCacheLocator``).
"""

from __future__ import annotations

import os
import shutil
from pathlib import Path

from .. import atomic

_ENGINE = Path(__file__).parent
_NUMBA_SUFFIXES = (".nbi", ".nbc")


def cache_folder() -> Path:
    """Where generated kernels and numba's compiled code for them are kept."""
    folder = os.environ.get("SHROUDNET_CACHE") or Path.home() / ".cache" / "shroudnet"
    return Path(folder)


def checked_cache_folder() -> Path:
    """``cache_folder()``, refused (``ValueError``) if it cannot hold kernels: a file at its
    path or on its way there, or a folder, the nearest that exists, that cannot be written.
    Makes nothing."""
    folder = cache_folder()
    existing = folder
    while not existing.exists():  # a path under a file does not exist either
        existing = existing.parent
    if not existing.is_dir():
        raise _unusable(folder, "is a file, not a folder" if existing == folder else
                        f"{existing} is a file, not a folder")
    if not os.access(existing, os.W_OK | os.X_OK):
        raise _unusable(folder, f"cannot write in {existing} (permission denied)")
    return folder


def keep(name: str, text: str) -> Path:
    """The file ``name`` of the cache folder, written with ``text`` first unless it is
    there (atomically: concurrent processes never see half a file). A folder that holds it
    already serves even if it cannot be written. What the system refuses only to a write (a
    read-only file system, a full disc) is refused as ``checked_cache_folder`` refuses."""
    path = cache_folder() / name
    if path.exists():  # a folder that holds the kernel already need not be writable
        return path
    folder = checked_cache_folder()
    try:
        return atomic.write_text(path, text)
    except atomic.WriteError as error:
        raise _unusable(folder, f"cannot write there ({error.strerror})") from None


def _unusable(folder: Path, why: str) -> ValueError:
    named = f"SHROUDNET_CACHE={folder}" if os.environ.get("SHROUDNET_CACHE") else \
        f"the kernel cache {folder} (SHROUDNET_CACHE is not set)"
    return ValueError(f"{named}: {why}; set SHROUDNET_CACHE to a folder that can be written")


def _engine_files() -> list[Path]:
    return [p for p in _ENGINE.rglob("__pycache__/*") if p.suffix in _NUMBA_SUFFIXES]


def cache_size() -> tuple[int, int]:
    """(bytes, files) held by the kernel folder and the engine's compiled code; the folder is
    checked as ``checked_cache_folder`` checks it."""
    folder = checked_cache_folder()
    files = [p for p in folder.rglob("*") if p.is_file()] if folder.exists() else []
    files += _engine_files()
    return sum(p.stat().st_size for p in files), len(files)


def clear_cache() -> int:
    """Delete every compiled kernel and the engine's compiled code; returns bytes freed.

    The next run compiles again (announced, once per combination of law classes).
    """
    freed, _ = cache_size()
    folder = cache_folder()
    if folder.exists():
        shutil.rmtree(folder)
    for path in _engine_files():
        path.unlink(missing_ok=True)
    return freed
