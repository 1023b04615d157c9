"""Dispatch by scene: one name, compiled for one-mass blades or for substructures.

A scene of one-mass blades reaches the loop as a ``records.KernelScene``, one with
substructures (nodes of many degrees of freedom, interfaces between their points) as a
``records.StructureScene``. The few law-free functions whose mathematics differ between
the two (the interfaces' kinematics, stick as clusters or as constraints, the tangent's
accelerations and the guards' gradients) are written twice, and ``by_scene`` joins each
pair under one name: numba picks the version by the type of the scene argument while it
compiles, and LLVM inlines the call through the join, so a scene of blades compiles and
runs its own version alone, as before, and pays nothing for the other.
"""

import inspect

from numba.extending import overload

from .compiled import STEP_OPTIONS
from .records import StructureScene

#: How the join itself compiles: as step-path code (no reference counting, as both its
#: versions), inlined by LLVM into its caller, so that a call through it costs what a
#: direct call costs. (numba's own inlining, ``inline="always"``, loses the writes of a
#: version through its arguments when the caller counts references.)
JOIN = {**STEP_OPTIONS, "forceinline": True, "no_cpython_wrapper": True}


def is_structure(scene_type) -> bool:
    """Whether a numba type (or a Python value) is that of a ``StructureScene``."""
    return (getattr(scene_type, "instance_class", None) is StructureScene
            or isinstance(scene_type, StructureScene))


def by_scene(name, blades, structures):
    """A function called ``name`` that runs ``blades`` (compiled) for a ``KernelScene``
    argument named ``s``, and ``structures`` for a ``StructureScene``; both take the same
    arguments.

    Called from compiled code, the choice is made while compiling; called as plain
    Python (with numba's JIT disabled, for debugging), at run time."""
    names = list(inspect.signature(getattr(blades, "py_func", blades)).parameters)
    where = names.index("s")
    listed = ", ".join(names)
    namespace = {"_choose": lambda *args: structures if is_structure(args[where]) else blades}
    exec(f"def {name}({listed}):\n"  # noqa: S102 - a signature, built once
         f"    return _choose({listed})({listed})\n", namespace)
    stub = namespace[name]
    stub.__doc__ = getattr(blades, "__doc__", None)

    def implementation(*types):
        chosen = structures if is_structure(types[where]) else blades
        local = {"_chosen": chosen}
        exec(f"def implementation({listed}):\n"  # noqa: S102
             f"    return _chosen({listed})\n", local)
        return local["implementation"]

    typing = {"_implementation": implementation}  # numba wants the stub's very signature
    exec(f"def typing({listed}):\n"  # noqa: S102
         f"    return _implementation({listed})\n", typing)
    overload(stub, jit_options=JOIN)(typing["typing"])
    return stub
