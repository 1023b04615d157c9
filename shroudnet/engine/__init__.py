"""The engine: the compiled event-driven loop and everything it is made of.

A step of the loop reads as five phases, each with a module for what does not depend on
the contact and friction laws:

- ``advance``: one Runge–Kutta step with fixed modes (``tableau``: its coefficients);
- ``detect``: the event guards, and whether one crossed inside the step;
- ``locate``: the switch inside the step, by the Illinois method;
- ``resolve``: the new consistent set of modes, and the event log;
- ``regroup``: stick clusters (``clusters``), the static friction operator, and one
  velocity for each cluster.

``tangent`` carries the variational (tangent) state through the steps and multiplies it
by the saltation matrix of each switch, in the kernels compiled for it.

``dynamics`` assembles the forces and accelerations of a set of modes (``assembly``
does the same in plain Python for a ``Scene``). ``template`` holds the functions that
must see the laws; ``generate`` writes it behind a header that dispatches to a scene's law
classes, into the folder of ``cache``. ``records`` names what the loop passes around, and
``codes`` defines each integer code once.
"""
