"""The law-aware half of the loop, one module per phase.

Each module holds the functions of one phase that must see a scene's laws; the law-free
half of the same phase is the engine module of the same name (``shroudnet.engine.detect``
beside ``kernel.detect``, and so on). ``shroudnet.engine.generate`` writes a header for
the law classes of a scene and the method (``generated`` declares what it defines), then
runs these modules, in the order of ``PHASES``, in the header's module: their functions
see the header's names, and each other's, as module globals. Each module can also be
imported on its own, to be read and linted; its functions are compiled only in a kernel.

A step reads as: ``forces`` (the right-hand side and the guards), ``step`` (one step, and
what the method decides), ``propagation`` (the exact step of a linear phase, in kernels
that propagate them), ``tangent`` (the tangent flow, in kernels that carry it),
``detect`` (switches hidden inside a step), ``locate`` (the switch inside a step),
``resolve`` (the new modes, the switch and the start) and ``drive`` (the loop).
"""

#: The phase modules in the order a kernel runs them. ``forces``, ``tangent`` and
#: ``resolve`` are the same for every method: their compiled code is cached once for
#: all (``generate.METHOD_FREE``).
PHASES = ("forces", "step", "propagation", "tangent", "detect", "locate", "resolve",
          "drive")
