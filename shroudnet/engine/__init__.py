"""The engine: the compiled event-driven loop and everything it is made of.

A step of the loop reads as phases, each with a module for what does not depend on the
contact and friction laws, and one of the same name in ``kernel`` for what does:

- ``dynamics`` / ``kernel.forces``: forces, accelerations and powers of a set of modes;
- ``advance``, ``tableau`` and ``controller`` / ``kernel.step``: one Runge–Kutta step with
  fixed modes, its dense output, and the adaptive step-size controller;
- ``detect`` / ``kernel.detect``: the event guards, and switches hidden inside a step;
- ``locate`` / ``kernel.locate``: the switch inside a step, by the Illinois method;
- ``resolve``, ``regroup`` and ``clusters`` / ``kernel.resolve``: the new consistent set
  of modes, stick clusters, the static friction operator, and one velocity for each
  cluster;
- ``tangent`` and ``saltation`` / ``kernel.tangent``: the variational (tangent) state
  through the steps, and the saltation matrix of each switch, in the kernels compiled
  for it;
- ``kernel.drive``: the loop, the same for fixed and adaptive steps.

``generate`` runs the ``kernel`` modules behind a header that dispatches to a scene's law
classes and sets its method, with numba's compiled code cached (``cache``, ``compiled``).
``assembly`` evaluates the same dynamics in plain Python for a ``Scene``. ``records``
names what the loop passes around, and ``codes`` defines each integer code once.
"""
