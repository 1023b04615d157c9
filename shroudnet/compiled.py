"""How shroudnet compiles its inner loop.

``njit_without_refcounts`` compiles a function without numba's reference counting. Such a
function cannot create arrays (numba refuses to compile one that tries); in exchange, passing
arrays to it and reading them out of tuples costs nothing. With counting, each step of the
integrator spent most of its time incrementing and decrementing the counts of the few dozen
arrays it touches: a three-blade derivative took 700 ns instead of 60 ns. Everything on the
path of a step is compiled this way; code that allocates (regrouping after an event, the
driver loops) keeps the default.
"""

from numba import njit

njit_without_refcounts = njit(cache=True, _nrt=False, error_model="numpy")
