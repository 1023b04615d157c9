"""How the engine is compiled: flavours of ``numba.njit``, all cached on disk.

Compile time is spent per function, and for a function that takes the loop's records a
large share goes into the wrapper that lets Python call it. So only the drivers, the
array functions that ``assembly`` calls from Python and the scalar helpers that tests
call keep that wrapper; everything else is called from compiled code only (calling it
from Python crashes the interpreter).

Step-path flavours compile without numba's reference counting. Such a function cannot
create arrays (numba refuses to compile one that tries); in exchange, passing arrays to
it and reading them out of tuples costs nothing. With counting, each step of the
integrator spent most of its time incrementing and decrementing the counts of the few
dozen arrays it touches: summing the forces on three blades took 125 ns instead of
14 ns, and the paper scene ran at 170,000 instead of 1,150,000 steps per second.

Inlined flavours are for the small helpers called many times per step with the loop's
records, whose passing would otherwise cost more than their work. LLVM inlines them
(``forceinline``), the force assembly of every stage (``dynamics``: excitation,
resultants, couplings, cluster accelerations, static friction) included: called apart,
its ten-odd array arguments cost more than its work, and inlining it took the paper
scene from 0.21 to 0.15 ms per period (adaptive, loaded from the cache) and fixed steps
from 0.57 to 0.40 ms per period. numba's own inlining (``inline="always"``) does the
same at the level of its typed code, but it copies the callee's code into every caller
and types it again there: for the helpers it cost half the compile time (the shared
kernel's adaptive driver compiled in 105–124 s, against 52–59 s with LLVM's), for the same
speed. The merged flavours below are the exception. Measure both, on code loaded back
from the cache, before changing this.

The drivers compile this way too: they work in records allocated by their caller
(``records.allocate``, in Python) and refill storage allocated once at every switch, so
nothing in the loop allocates. Switches that allocated, and counted the references of the
records they rebound, had cost the paper scene 0.102 ms a period against 0.088 ms
without; and compiled as one function, with no allocating driver around it to compile it
again, the adaptive driver compiles in 45 s instead of 55 s.

What the records hold costs too: each array is some seven machine words of arguments to
every function compiled on its own that takes its record, and stays live across the loop.
Runs without the tangent flow carry a ``records.NoTangent`` (one array in place of 51):
0.087 to 0.083 ms a period, and the first compile 45 to 39 s.

numpy's error model makes a division by zero give inf or NaN instead of raising inside
compiled code; the loop then stops with a non-finite state, which it reports.

Step-path code may contract a·b + c into one fused multiply-add and reorder sums (the
``contract`` and ``reassoc`` fast-math flags, no others: infinities, NaN and signed zeros
keep their meaning, so the checks for a non-finite state still hold). Results move by
rounding only: on the paper's period-1 and period-3 orbits the Poincaré points moved by
5e-11 of the amplitude at most, with the same events; fixed steps ran 2.2–2.8 times
faster, from the fused stage sums of the four stages.
"""

import functools
import hashlib
import os
from pathlib import Path
from types import ModuleType

from numba import njit
from numba.core import caching

_STEP = {"cache": True, "_nrt": False, "error_model": "numpy", "no_cfunc_wrapper": True,
         "fastmath": {"contract", "reassoc"}}
#: The step path's options without caching (for code compiled inside its callers).
STEP_OPTIONS = {key: value for key, value in _STEP.items() if key != "cache"}
_NOT_FROM_PYTHON = {"no_cpython_wrapper": True}


def _flavour(**options):
    """``numba.njit(**options)`` as a decorator that keys a kernel's phase functions.

    numba keys its on-disk cache by a function's file, name and line, but a phase module
    of ``kernel`` runs in many kernels (one per law classes, effects and method), each
    compiling it differently. A function compiled in a kernel's namespace, which holds
    the key of what its code is made of (``CACHE_KEY``, set by ``generate``), takes that
    key into its name, so that each kernel has its own cache entries, kept in the kernel
    cache folder (``_KernelCacheLocator``).
    """
    jit = njit(**options)

    def compile_(function):
        key = function.__globals__.get("CACHE_KEY")
        if key:
            function.__qualname__ = f"{function.__qualname__}__{key}"
            _locate_kernels_in_their_folder()
        return jit(function)

    return compile_


class _KernelCacheLocator(caching._CacheLocator):
    """Where numba caches a kernel's phase functions: the folder a kernel's namespace names
    (``CACHE_FOLDER``, set by ``generate`` inside the kernel cache folder), so that the
    kernel folder holds all a kernel is and clearing it clears them, wherever numba keeps
    the rest of its cache."""

    def __init__(self, py_func, py_file, folder):
        self._py_file = py_file
        self._lineno = py_func.__code__.co_firstlineno
        self._folder = folder

    def get_cache_path(self):
        return self._folder

    def get_source_stamp(self):
        status = os.stat(self._py_file)
        return status.st_mtime, status.st_size

    def get_disambiguator(self):
        return str(self._lineno)

    @classmethod
    def from_function(cls, py_func, py_file):
        folder = py_func.__globals__.get("CACHE_FOLDER")
        if not folder:
            return None
        locator = cls(py_func, py_file, folder)
        try:
            locator.ensure_cache_path()
        except OSError:  # not writable: numba's own locators take it
            return None
        return locator


#: numba's locator of a module's own ``__pycache__`` (named with an underscore before 0.60).
_IN_TREE = getattr(caching, "InTreeCacheLocator", None) or caching._InTreeCacheLocator


class _EngineCacheLocator(_IN_TREE):
    """Where numba caches the engine's own functions (those outside a kernel): beside
    their module, as numba does, but stamped with the sources of the whole engine, not of
    their one file. A function carries inlined into its cached code the helpers it calls
    from other modules; stamped by its own file, it would come back from the cache with
    their old code after they changed (a stage of the tangent flow kept calling the
    accelerations of before the elastic contacts' variations were added)."""

    def get_source_stamp(self):
        return _engine_stamp()

    @classmethod
    def from_function(cls, py_func, py_file):
        if Path(py_file).resolve().parent != _ENGINE:
            return None
        return super().from_function(py_func, py_file)


_ENGINE = Path(__file__).resolve().parent


@functools.cache
def _engine_stamp() -> str:
    """A digest of every module of the engine (read once per process)."""
    digest = hashlib.sha256()
    for path in sorted(_ENGINE.glob("*.py")):
        digest.update(path.read_bytes())
    return digest.hexdigest()


def _locate_engine_functions() -> None:
    """Put ``_EngineCacheLocator`` before numba's own locators, before any engine function
    is decorated (numba picks a function's locator as it decorates it)."""
    locators = _numba_locators()
    if isinstance(locators, list) and _EngineCacheLocator not in locators:
        locators.insert(0, _EngineCacheLocator)


def _numba_locators():
    implementation = getattr(caching, "CacheImpl", None) or getattr(caching, "_CacheImpl",
                                                                    None)
    return getattr(implementation, "_locator_classes", None)


_locate_engine_functions()


@functools.cache
def _locate_kernels_in_their_folder() -> None:
    """Put ``_KernelCacheLocator`` before numba's own locators (once, at the first kernel).
    With another numba, whose internals differ, numba's own locators keep the kernels."""
    locators = _numba_locators()
    if isinstance(locators, list) and _KernelCacheLocator not in locators:
        locators.insert(0, _KernelCacheLocator)


#: Allocating code callable from Python: arrays-only helpers.
njit_entry = _flavour(cache=True, no_cfunc_wrapper=True)
#: Allocating code called from compiled code only: the records' allocators.
njit_internal = _flavour(cache=True, no_cfunc_wrapper=True, **_NOT_FROM_PYTHON)
#: Step-path code called from compiled code only.
njit_step = _flavour(**_STEP, **_NOT_FROM_PYTHON)
#: Step-path code whose sums must stay as written, with no fused or reordered terms: the
#: projection onto stick clusters, whose removed energy is a difference of near equals.
njit_step_exact = _flavour(**{**_STEP, "fastmath": False}, **_NOT_FROM_PYTHON)
#: Step-path functions that Python calls too: the drivers, and array functions.
njit_step_callable = _flavour(**_STEP)
#: Small step-path helpers, inlined into their callers.
njit_inlined = _flavour(**_STEP, forceinline=True, **_NOT_FROM_PYTHON)
#: Small step-path helpers, inlined, that Python calls too.
njit_inlined_callable = _flavour(**_STEP, forceinline=True)

# Merged flavours: parts of a larger function, called from one or two places, whose code
# numba merges into each caller (``inline="always"``) instead of compiling it on its own.
# A function compiled on its own is linked, with everything it calls, into every caller,
# and compiled again there; merging the loop's middle layers cut the compile time by
# a third (left to LLVM's forceinline, they compile in 95 s against 57 s).
#: Step-path code merged into its caller.
njit_step_merged = _flavour(**_STEP, inline="always", **_NOT_FROM_PYTHON)


#: How long compiling each flavour of kernel takes [s of processor time], by (method,
#: substructures, elastic contacts, tangent flow): measured from an empty cache, each in a
#: fresh process, on a 2-core machine (``shroudnet cache --warm`` compiles them all). A
#: kernel of laws of one's own compiles fewer effects, so a little faster.
COMPILE_SECONDS = {
    ("adaptive", False, False, False): 32,
    ("adaptive", False, False, True): 79,
    ("fixed_step", False, False, False): 40,
    ("adaptive", True, False, False): 41,
    ("adaptive", True, False, True): 92,
    ("fixed_step", True, False, False): 54,
    ("exponential", True, False, False): 70,
    ("adaptive", True, True, False): 45,
    ("adaptive", True, True, True): 94,
    ("fixed_step", True, True, False): 63,
}


def compile_seconds(kernel: ModuleType) -> int:
    """About how long compiling ``kernel``'s driver takes (``COMPILE_SECONDS``; the
    longest of its method's where a flavour is not listed)."""
    key = (kernel.METHOD, kernel.HAS_STRUCTURES, kernel.HAS_SLIDERS, kernel.TANGENT)
    return COMPILE_SECONDS.get(key) or max(
        seconds for flavour, seconds in COMPILE_SECONDS.items() if flavour[0] == kernel.METHOD)
