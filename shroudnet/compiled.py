"""How shroudnet compiles its inner loop.

``njit_without_refcounts`` compiles a function without numba's reference counting. Such a
function cannot create arrays (numba refuses to compile one that tries); in exchange, passing
arrays to it and reading them out of tuples costs nothing. With counting, each step of the
integrator spent most of its time incrementing and decrementing the counts of the few dozen
arrays it touches: summing the forces on three blades took 125 ns instead of 14 ns, and
the paper scene ran at 170,000 instead of 1,150,000 steps per second. Everything on the
path of a step is compiled this way; code that allocates (regrouping after an event, the
driver loops) keeps the default.

numpy's error model makes a division by zero give inf or NaN instead of raising inside
compiled code; the loop then stops with a non-finite state, which it reports.
"""

from numba import njit

njit_without_refcounts = njit(cache=True, _nrt=False, error_model="numpy")

#: The same, inlined into its callers by numba: for the small helpers called many times
#: per step with the loop's tuples of arrays, whose passing would otherwise cost more than
#: their work.
njit_inlined = njit(cache=True, _nrt=False, error_model="numpy", inline="always")
