"""Named tuples passed through the compiled loop (module-level so numba can cache them)."""

from collections import namedtuple

#: A scene as the compiled loop sees it: the ``SceneArrays`` fields that are numbers, plus
#: each interface's law index (into the kernel's list of law classes, −1 for none) and its
#: parameters, padded into one row per interface.
KernelScene = namedtuple("KernelScene", [
    "mass", "damping", "stiffness", "left", "right", "gap", "sin_angle", "cos_angle",
    "opens", "can_stick", "static_mu", "regularisation", "normal_kind", "normal_params",
    "friction_kind", "friction_params", "amplitudes", "phases", "excitation_frequency",
])

#: Stick clusters of a mode set and its static friction operator.
Topology = namedtuple("Topology", [
    "stuck", "labels", "grounded", "masses", "operator", "stuck_interfaces",
])

#: Scratch arrays of one run, allocated once.
Work = namedtuple("Work", [
    "q", "penetration", "rate", "slip", "normal", "friction", "force", "resultant",
    "scratch", "contact", "motion", "a1", "a2", "a3", "a4", "xt", "vt",
])
