"""Named tuples passed through the compiled loop (module-level so numba can cache them)."""

from collections import namedtuple

#: A scene as the compiled loop sees it: the ``SceneArrays`` fields that are numbers, plus
#: each interface's law index (into the kernel's list of law classes, −1 for none) and its
#: parameters, padded into one row per interface; the excitation as tables with one row per
#: harmonic n and one column per blade: amplitudes s_i q_n, and cos n φ_i and sin n φ_i.
KernelScene = namedtuple("KernelScene", [
    "mass", "damping", "stiffness", "left", "right", "gap", "sin_angle", "cos_angle",
    "opens", "can_stick", "static_mu", "regularisation", "normal_kind", "normal_params",
    "friction_kind", "friction_params", "amplitudes", "cos_phase", "sin_phase",
    "excitation_frequency",
])

#: Stick clusters of a mode set and its static friction operator.
Topology = namedtuple("Topology", [
    "stuck", "labels", "grounded", "masses", "operator", "stuck_interfaces",
])

#: Scratch arrays of one run, allocated once. Per blade: q … a_sample, x_new, v_new; per
#: interface: penetration … motion_trial; Runge–Kutta stages (7 rows): stage_v, stage_a
#: (per blade) and stage_p (the four powers), and the dense output's weight of each stage;
#: the state's energy columns: e_new, e_sample.
Work = namedtuple("Work", [
    "q", "resultant", "scratch", "imbalance", "a_start", "a_end", "a_sample", "xt", "vt",
    "x_new", "v_new",
    "penetration", "rate", "slip", "normal", "friction", "force", "contact", "motion",
    "contact_trial", "motion_trial",
    "stage_v", "stage_a", "stage_p", "dense_weights", "e_new", "e_sample",
])

#: The event log of one run: located switches (time, interface, kind) up to its capacity,
#: exact counts by kind, the times of the latest switches (for the Zeno guard), and
#: ``n_events[0]``, the number of switches so far, and ``idle[0]``, the located switches in
#: a row that changed no mode.
Events = namedtuple("Events", ["time", "interface", "kind", "counts", "recent", "n_events",
                               "idle"])

#: Sampled output of one run: one row per sample time.
Output = namedtuple("Output", ["t", "x", "v", "normal", "friction", "modes", "energy"])
