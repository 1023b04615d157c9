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

from numba import njit

_STEP = {"cache": True, "_nrt": False, "error_model": "numpy", "no_cfunc_wrapper": True,
         "fastmath": {"contract", "reassoc"}}
_NOT_FROM_PYTHON = {"no_cpython_wrapper": True}

#: Allocating code callable from Python: arrays-only helpers.
njit_entry = njit(cache=True, no_cfunc_wrapper=True)
#: Allocating code called from compiled code only: the records' allocators.
njit_internal = njit(cache=True, no_cfunc_wrapper=True, **_NOT_FROM_PYTHON)
#: Step-path code called from compiled code only.
njit_step = njit(**_STEP, **_NOT_FROM_PYTHON)
#: Step-path code whose sums must stay as written, with no fused or reordered terms: the
#: projection onto stick clusters, whose removed energy is a difference of near equals.
njit_step_exact = njit(**{**_STEP, "fastmath": False}, **_NOT_FROM_PYTHON)
#: Step-path functions that Python calls too: the drivers, and array functions.
njit_step_callable = njit(**_STEP)
#: Small step-path helpers, inlined into their callers.
njit_inlined = njit(**_STEP, forceinline=True, **_NOT_FROM_PYTHON)
#: Small step-path helpers, inlined, that Python calls too.
njit_inlined_callable = njit(**_STEP, forceinline=True)

# Merged flavours: parts of a larger function, called from one or two places, whose code
# numba merges into each caller (``inline="always"``) instead of compiling it on its own.
# A function compiled on its own is linked, with everything it calls, into every caller,
# and compiled again there; merging the loop's middle layers cut the compile time by
# a third (left to LLVM's forceinline, they compile in 95 s against 57 s).
#: Step-path code merged into its caller.
njit_step_merged = njit(**_STEP, inline="always", **_NOT_FROM_PYTHON)
