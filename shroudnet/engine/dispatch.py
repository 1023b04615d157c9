"""Dispatch by scene: one name, compiled for one-mass blades or for substructures.

A scene of one-mass blades reaches the loop as a ``records.KernelScene``, one with
substructures (nodes of many degrees of freedom, interfaces between their points) as a
``records.StructureScene``. The few law-free functions whose mathematics differ between
the two (the interfaces' kinematics, stick as clusters or as constraints, the tangent's
accelerations and the guards' gradients) are written twice, and ``by_scene`` joins each
pair under one name: numba picks the version by the type of the scene argument while it
compiles, and LLVM inlines the call through the join, so a scene of blades compiles and
runs its own version alone, as before, and pays nothing for the other. ``by_record``
joins a pair the same way on any argument and record type (``advance.record``: a run's
samples kept as rows, or reduced as they are taken).
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
    return is_record(StructureScene, scene_type)


def is_record(record, value_type) -> bool:
    """Whether a numba type (or a Python value) is that of the namedtuple class ``record``."""
    return (getattr(value_type, "instance_class", None) is record
            or isinstance(value_type, record))


def by_scene(name, blades, structures):
    """A function called ``name`` that runs ``blades`` (compiled) for a ``KernelScene``
    argument named ``s``, and ``structures`` for a ``StructureScene``; both take the same
    arguments.

    Called from compiled code, the choice is made while compiling; called as plain
    Python (with numba's JIT disabled, for debugging), at run time."""
    return by_record(name, "s", StructureScene, blades, structures)


def by_record(name, argument, record, usual, other):
    """A function called ``name`` that runs ``other`` (compiled) where its argument named
    ``argument`` is a ``record`` (a namedtuple class), else ``usual``; both take the same
    arguments. The choice is made as ``by_scene`` makes it."""
    names = list(inspect.signature(getattr(usual, "py_func", usual)).parameters)
    where = names.index(argument)
    listed = ", ".join(names)
    namespace = {"_choose": lambda *args: other if is_record(record, args[where]) else usual}
    exec(f"def {name}({listed}):\n"  # noqa: S102 - a signature, built once
         f"    return _choose({listed})({listed})\n", namespace)
    stub = namespace[name]
    stub.__doc__ = getattr(usual, "__doc__", None)

    def implementation(*types):
        chosen = other if is_record(record, types[where]) else usual
        local = {"_chosen": chosen}
        exec(f"def implementation({listed}):\n"  # noqa: S102
             f"    return _chosen({listed})\n", local)
        return local["implementation"]

    typing = {"_implementation": implementation}  # numba wants the stub's very signature
    exec(f"def typing({listed}):\n"  # noqa: S102
         f"    return _implementation({listed})\n", typing)
    overload(stub, jit_options=JOIN)(typing["typing"])
    return stub
