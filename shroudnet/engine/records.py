"""The named records the compiled loop passes around, and their allocation.

Records are ``namedtuple`` classes defined at module level, so numba can cache code that
takes them. Arrays inside a record are mutable; the records themselves are not, so
scalars that change during a run (the time, the step size) travel as plain values.
"""

from collections import namedtuple

import numpy as np

from .codes import N_EVENT_KINDS, N_POWERS, N_WORK
from .compiled import njit_inlined, njit_internal
from .exponential import SLOTS
from .propagation import WORK_SLOTS, augmented_size, levels_for, slots_for
from .tableau import DP_STAGES

#: A scene as the compiled loop sees it: the ``SceneArrays`` fields that are numbers, plus
#: each interface's law index (into the kernel's list of law classes, −1 for none) and its
#: parameters, padded into one row per interface; the excitation as tables with one row per
#: harmonic n and one column per blade: amplitudes s_i q_n, and cos n φ_i and sin n φ_i;
#: and the couplings' nodes, stiffnesses and dampers. The prescribed-motion nodes follow
#: the blades in the node arrays (no mass, spring, damper or excitation of their own), and
#: each one's acceleration −A ω² sin(ω t + φ) + a(t) (``motion.MotionTerms``) is given by
#: ``motion_amplitude`` A [m], ``motion_frequency`` ω [rad/s], ``motion_phase`` φ [rad]
#: and the first ``motion_knots`` entries of its row of ``motion_times`` [s] and
#: ``motion_accelerations`` [m/s²], between which a(t) is linear.
KernelScene = namedtuple("KernelScene", [
    "mass", "damping", "stiffness", "left", "right", "gap", "sin_angle", "cos_angle",
    "opens", "can_stick", "static_mu", "regularisation", "normal_kind", "normal_params",
    "friction_kind", "friction_params", "amplitudes", "cos_phase", "sin_phase",
    "excitation_frequency", "coupling_left", "coupling_right", "coupling_stiffness",
    "coupling_damping", "motion_amplitude", "motion_frequency", "motion_phase",
    "motion_times", "motion_accelerations", "motion_knots",
])

#: A scene with substructures as the compiled loop sees it: the ``KernelScene`` fields,
#: with one entry per degree of freedom (coordinate) where a ``KernelScene`` has one per
#: blade, and the structure that those cannot express. A substructure's coordinates are
#: its modal coordinates, mass-normalised (``mass`` 1), so the mass stays diagonal; its
#: stiffness K and damping C, with the couplings', are n × n matrices stored by rows
#: (compressed: row i's entries are ``matrix_start[i]`` … ``matrix_start[i + 1]`` − 1 of
#: ``matrix_column``, ``stiffness_entry`` and ``damping_entry``; a substructure's own are
#: diagonal). Interface e sees the penetration δ_e = n_e·x − ``normal_gap[e]`` and the
#: slip velocity t_e·ẋ, with n_e and t_e the rows of ``normal_rows`` and ``tangent_rows``,
#: nonzero only at its coordinates ``support_index[support_start[e]:support_start[e +
#: 1]]``, and pushes the coordinates by −(N_e n_e + f_e t_e). The per-blade ``damping``,
#: ``stiffness``, the couplings' and the angles' fields are unused.
#:
#: An elastic contact (a Jenkins element: ``sliders``) has its slider's position w in the
#: tangent plane as coordinates of the state, between the structure's free coordinates
#: and the prescribed ones: ``slider_index[e]`` is its first (−1 where stick is rigid),
#: one per tangent direction (the second's row in ``second_tangent_rows``, all zero for
#: an interface of one direction); ``tangential_stiffness`` is k_t [N/m] (inf where
#: rigid). A slider coordinate has mass 1 and no stiffness, damping, load or contact row.
StructureScene = namedtuple("StructureScene", KernelScene._fields + (
    "normal_rows", "tangent_rows", "normal_gap", "support_start", "support_index",
    "matrix_start", "matrix_column", "stiffness_entry", "damping_entry",
    "second_tangent_rows", "tangential_stiffness", "slider_index",
))

#: What a run is asked for, in seconds: the first sample time, the sample spacing and the
#: number of samples (the last at ``last_sample``); the fixed step, or the first trial step
#: of an adaptive run, and the number of fixed steps per sample; the adaptive tolerances
#: (rtol, atol on x [m] and on ẋ [m/s]) and step limits; the event tolerance; the Zeno
#: guard (switches within a window [s]); how many events the log keeps; and whether the
#: tangent's columns are orthonormalised after every step (``tangent.orthonormalise``,
#: for Lyapunov exponents), or, with ``exponentials``, carried through each phase between
#: switches by one matrix exponential (``kernel.tangent.carry_phase``) rather than with
#: every step.
Controls = namedtuple("Controls", [
    "t0", "sample_step", "n_samples", "step", "steps_per_sample",
    "rtol", "atol_x", "atol_v", "h_max", "h_min",
    "event_tolerance", "zeno_events", "zeno_window", "event_capacity", "orthonormalise",
    "exponentials",
])

#: The integrator's state between steps: displacements x [m] and velocities ẋ [m/s] by
#: blade, the cumulative work columns [J] (``codes.WorkColumn``), each interface's mode,
#: and its contact and motion guards where the last step ended (``detect.event_guards``),
#: the reference a switch is detected against; its ``Tangent`` (a ``NoTangent`` unless a
#: run asks for the tangent flow); and its ``Propagation`` (a ``NoPropagation`` unless it
#: propagates its phases exactly: ``methods.Exponential``).
State = namedtuple("State", ["x", "v", "energy", "modes", "contact_before", "motion_before",
                             "tangent", "propagation"])

#: The exact propagation of the phases of a run (``propagation``), for the ``slots`` phases
#: it keeps, each in the slot its modes' key (``keys``) names: its augmented matrix A
#: (``matrix``, m × m, m = 2n + 1 + 2H) and its powers' quadratic forms Q_c
#: (``quadratic``), then e^{A h 2^-k} (``levels``) and the works W_c of a step of
#: h 2^-k (``forms``) at k = 0 … L − 1, h the fixed step (``step[0]``, [s]). ``slot[0]``
#: is the phase in use, ``slot[1]`` the next slot to fill. Scratch: the exponential's
#: storage (``work``), vectors of the augmented state's size (``z``, ``z_next``, ``term``,
#: ``spare``), and a ``Work`` (``field``) with the state ``x``, ``v`` and
#: ``acceleration`` at which the vector field is evaluated.
Propagation = namedtuple("Propagation", [
    "matrix", "quadratic", "levels", "forms", "keys", "slot", "step", "work", "z", "z_next",
    "term", "spare", "field", "x", "v", "acceleration",
])

#: The propagation of a run that takes Runge–Kutta steps: nothing to carry, and nothing
#: to pass (an array would add its machine words to every call that takes the state).
NoPropagation = namedtuple("NoPropagation", [])

#: The tangent (variational) state of a run and its scratch (``tangent``). ``matrix``
#: (2 n_blades × k) holds k tangent vectors, displacement rows then velocity rows;
#: ``log_growth`` the log of each column's growth removed by orthonormalisation, and
#: ``history`` its value at every sample. Per interface, from the laws where the flow was
#: last linearised (``kernel.tangent.linearise``): ∂N/∂u, ∂N/∂u̇, and ∂F/∂u, ∂F/∂u̇ of its force
#: F = N sin α + f cos α on the blades (u = x_left − x_right). ``stages``: the tangent of
#: each Runge–Kutta stage, and ``candidate`` the tangent at the end of a step until the
#: step's tangent error accepts it. Scratch: ``direction`` (one tangent vector), the changes of the
#: resultants and accelerations along it, per-cluster ``rows``, ``imbalance`` and
#: ``q_rate`` (dQ/dt) per blade; ``guard_normal`` the gradient of the guard that crossed,
#: ``f_minus`` and ``f_plus`` the vector field (ẋ, ẍ) before and after the switch.
#: ``singular`` counts the switches whose saltation matrix was singular (a grazing
#: switch, or several guards at once), the first at ``singular_time[0]`` on interface
#: ``singular_interface[0]``. ``work`` and ``acceleration``: the forces at a stage.
#: ``phase_work``: storage for the exponential of a phase's Jacobian
#: (``exponential``; its first slot the Jacobian). ``resolution`` [s]: the time the run
#: resolves, its event tolerance (0 for the exact Jacobian): a slipping elastic contact's
#: stretch direction that relaxes faster is followed at that pace (``slider_tangent``).
#: ``since[0]``: the time [s] up to which a run that carries its tangent by phase has
#: carried it (``kernel.tangent.carry_tangent``). ``stage_forces`` and ``stage_keys``: the
#: forces each stage of the step just taken found, and at its start (``START``) those of
#: the step before's end, with the states they were found at (``stage_forces``).
Tangent = namedtuple("Tangent", [
    "matrix", "log_growth", "history", "normal_u", "normal_du", "force_u", "force_du",
    "stages", "candidate", "direction", "resultant_change", "acceleration_change", "rows",
    "imbalance", "q_rate", "guard_normal", "f_minus", "f_plus", "singular", "singular_time",
    "singular_interface", "work", "acceleration", "phase_work", "resolution", "since",
    "stage_forces", "stage_keys",
])
#: The rows of ``Tangent.stage_forces``: penetration, its rate, slip velocity, normal
#: force, friction, friction along the second tangent, slider speed (``Work``'s fields).
STAGE_FORCES = 7
#: The slot of ``Tangent.stage_forces`` that holds the forces at a step's start.
START = DP_STAGES

#: The tangent of a run that integrates none, in a kernel compiled without the tangent
#: flow: a matrix with no columns, and nothing else to carry through every call.
NoTangent = namedtuple("NoTangent", ["matrix"])

#: Stick clusters of a set of modes (``regroup``): which interfaces are stuck, each node's
#: cluster, whether each cluster's motion is given (``clusters.cluster_labels``: grounded)
#: and by which prescribed-motion node (``driver``), its mass, and the static friction
#: operator with the stuck interfaces it gives the friction of. Its arrays are views of a
#: run's ``Switching`` storage, refilled at each mode change.
Topology = namedtuple("Topology", [
    "stuck", "labels", "grounded", "driver", "masses", "operator", "stuck_interfaces",
])

#: What the switches of one run work in, allocated once, so that a switch allocates
#: nothing. The stick clusters (``regroup``): the ``Topology`` fields at their largest
#: sizes (one cluster per node, every interface stuck), refilled at each mode change, and
#: their scratch: the union–find's ``parent`` (n_nodes + 1: the ground is a node), each
#: stuck interface's two blade ``ends`` and G entries, the n_nodes × n_nodes G Gᵀ
#: (``gram``), its Cholesky factor and its inverse, and each cluster's ``size``. The mode
#: rule (``settle``): per interface the modes before the switch (``modes_before``), the
#: ``candidates`` for stick and the slip directions ``tried``, and per node ``v_trial``,
#: the velocities projected onto trial clusters. Switches of several interfaces at once
#: (``tangent.apply_saltations``): the interfaces that switch (``crossings``), each one's
#: guard gradient (a row of ``crossing_normals``) and rate, each node's switching
#: interface (``owner``) and each switching interface's component of a tangent vector
#: (``along``).
Switching = namedtuple("Switching", [
    "stuck", "labels", "grounded", "driver", "masses", "operator", "stuck_interfaces",
    "parent", "ends", "entries", "gram", "lower", "inverse", "size",
    "modes_before", "candidates", "tried", "v_trial",
    "crossings", "crossing_normals", "crossing_rates", "owner", "along",
])

#: Scratch arrays of one run, allocated once. Per blade: q … a_sample, x_new, v_new; per
#: interface: penetration … motion_trial; Runge–Kutta stages (7 rows): stage_v, stage_a
#: (per blade) and stage_p (the four powers), and the dense output's weight of each stage;
#: the state's energy columns: e_new, e_sample; per prescribed-motion node: ``drive``, its
#: acceleration at the stage being evaluated; per interface, an elastic contact's friction
#: along its second tangent direction (``friction_second``) and its slider's speed λ
#: (``slider_speed``, ``sliders``).
Work = namedtuple("Work", [
    "q", "resultant", "scratch", "imbalance", "a_start", "a_end", "a_sample", "xt", "vt",
    "x_new", "v_new",
    "penetration", "rate", "slip", "normal", "friction", "force", "contact", "motion",
    "contact_trial", "motion_trial",
    "stage_v", "stage_a", "stage_p", "dense_weights", "e_new", "e_sample", "drive",
    "friction_second", "slider_speed",
])

#: The event log of one run: located switches (time, interface, kind) up to its capacity,
#: exact counts by kind, the times of the latest switches (for the Zeno guard), and
#: ``n_events[0]``, the number of switches so far, and ``idle[0]``, the located switches in
#: a row that changed no mode.
Events = namedtuple("Events", ["time", "interface", "kind", "counts", "recent", "n_events",
                               "idle"])

#: Sampled output of one run: one row per sample time.
Output = namedtuple("Output", ["t", "x", "v", "normal", "friction", "modes", "energy"])

#: What a run keeps of its samples where it keeps no record of them (a batch of runs, one
#: per GPU thread: ``batch``), reduced as they are taken (``advance.reduce_sample``): the
#: Poincaré points (x, ẋ) of coordinate ``response`` at every ``every``-th sample, one row
#: each (``poincare``, as ``Simulation.poincare`` takes them); the largest |x| and |ẋ| of
#: that coordinate over the samples (``extent``); ∫ x² dt by the trapezoidal rule over the
#: samples (``square[0]``, [m² s]) with the last sample's t and x² (``square[1]``,
#: ``square[2]``); and the work columns [J] at the first and at the last sample (``work``,
#: 2 × N_WORK). ``response`` and ``every`` are numbers, the rest arrays.
Reduction = namedtuple("Reduction", ["response", "every", "poincare", "extent", "square",
                                     "work"])

#: What a driver returns: its ``codes.Status``, the time it stopped at [s], the interface
#: that stopped it (−1 for none), the Runge–Kutta steps taken (accepted ones, for the
#: adaptive driver), the samples taken, the events logged, and the tangent state.
Run = namedtuple("Run", ["status", "time", "interface", "steps", "output", "events",
                         "tangent"])


@njit_inlined
def last_sample(controls):
    """The time of the last sample [s], computed as every sample time is, so that a run
    ends exactly on it."""
    return controls.t0 + (controls.n_samples - 1) * controls.sample_step


@njit_internal
def new_work(n_blades, n_interfaces, n_prescribed):
    b, m = n_blades, n_interfaces
    return Work(np.empty(b), np.empty(b), np.empty(b), np.empty(b), np.empty(b),
                np.empty(b), np.empty(b), np.empty(b), np.empty(b), np.empty(b), np.empty(b),
                np.empty(m), np.empty(m), np.empty(m), np.empty(m), np.empty(m), np.empty(m),
                np.empty(m), np.empty(m), np.empty(m), np.empty(m),
                np.zeros((DP_STAGES, b)), np.zeros((DP_STAGES, b)),
                np.zeros((DP_STAGES, N_POWERS)), np.zeros(DP_STAGES),
                np.zeros(N_WORK), np.zeros(N_WORK), np.zeros(n_prescribed), np.zeros(m),
                np.zeros(m))


@njit_internal
def new_switching(n_nodes, n_interfaces, square):
    """A ``Switching`` for n_nodes nodes and n_interfaces interfaces, with G Gᵀ, its factor
    and its inverse ``square`` × ``square``: n_nodes for stick clusters; for stick as
    constraints (``constraints``), at least n_interfaces."""
    n, m, q = n_nodes, n_interfaces, square
    return Switching(np.zeros(m, dtype=np.bool_), np.zeros(n, dtype=np.int64),
                     np.zeros(n, dtype=np.bool_), np.zeros(n, dtype=np.int64), np.zeros(n),
                     np.zeros((m, n)), np.zeros(m, dtype=np.int64),
                     np.zeros(n + 1, dtype=np.int64), np.zeros((m, 2), dtype=np.int64),
                     np.zeros((m, 2)), np.zeros((q, q)), np.zeros((q, q)), np.zeros((q, q)),
                     np.zeros(q),
                     np.zeros(m, dtype=np.int64), np.zeros(m, dtype=np.bool_),
                     np.zeros(m, dtype=np.int64), np.zeros(n),
                     np.zeros(m, dtype=np.int64), np.zeros((m, 2 * n)), np.zeros(m),
                     np.zeros(n, dtype=np.int64), np.zeros(m))


def new_events(capacity, zeno_events):
    return Events(np.empty(capacity), np.empty(capacity, dtype=np.int64),
                  np.empty(capacity, dtype=np.int8), np.zeros(N_EVENT_KINDS, dtype=np.int64),
                  np.full(max(zeno_events, 1), -np.inf), np.zeros(1, dtype=np.int64),
                  np.zeros(1, dtype=np.int64))


def new_reduction(response, every, n_points):
    """A ``Reduction`` of coordinate ``response`` keeping ``n_points`` Poincaré points, one
    every ``every`` samples."""
    return Reduction(int(response), int(every), np.zeros((n_points, 2)), np.zeros(2),
                     np.zeros(3), np.zeros((2, N_WORK)))


def new_output(n_samples, n_blades, n_interfaces):
    return Output(np.empty(n_samples), np.empty((n_samples, n_blades)),
                  np.empty((n_samples, n_blades)), np.empty((n_samples, n_interfaces)),
                  np.empty((n_samples, n_interfaces)),
                  np.empty((n_samples, n_interfaces), dtype=np.int8),
                  np.empty((n_samples, N_WORK)))


@njit_internal
def new_tangent(tangent0, n_interfaces, n_samples, work, resolution=0.0):
    """A ``Tangent`` starting from the columns of ``tangent0`` (2 n_nodes × k, k ≥ 0), with
    ``work`` (``new_work``) for the forces at its stages, resolving time to ``resolution``
    [s] (0: the exact Jacobian)."""
    b, m = tangent0.shape[0] // 2, n_interfaces
    k = tangent0.shape[1]
    return Tangent(tangent0.copy(), np.zeros(k), np.zeros((n_samples, k)), np.zeros(m),
                   np.zeros(m), np.zeros(m), np.zeros(m), np.zeros((DP_STAGES, 2 * b, k)),
                   np.zeros((2 * b, k)), np.zeros(2 * b), np.zeros(b), np.zeros(b),
                   np.zeros(b), np.zeros(b), np.zeros(b), np.zeros(2 * b), np.zeros(2 * b),
                   np.zeros(2 * b),
                   np.zeros(1, dtype=np.int64), np.full(1, np.nan),
                   np.full(1, -1, dtype=np.int64), work, np.zeros(b),
                   np.zeros((SLOTS, 2 * b, 2 * b)), float(resolution), np.zeros(1),
                   np.zeros((DP_STAGES + 1, STAGE_FORCES, m)),
                   np.full((2, 1 + 2 * b + m), np.nan))


def new_state(x0, v0, tangent, n_interfaces, propagation):
    return State(np.array(x0, dtype=float), np.array(v0, dtype=float), np.zeros(N_WORK),
                 np.zeros(n_interfaces, np.int64), np.empty(n_interfaces),
                 np.empty(n_interfaces), tangent, propagation)


#: The most memory one phase's propagation may take [bytes].
LARGEST_PHASE_BYTES = 2**30


def new_propagation(s, arrays, step: float) -> Propagation:
    """The ``Propagation`` of a run of the kernel scene ``s`` (``arrays`` its
    ``SceneArrays``) with the fixed ``step`` [s]: its levels from a bound of the scaled
    matrix's norm, 2ω_b + max Σ|M⁻¹C| + Hω, ω_b² bounding the rows of M⁻¹K with every
    linear contact closed (``propagation.levels_for``: the kernel scales by each phase's own ω_b,
    and a remainder coarser than aimed at costs only Taylor terms), as many phases kept as
    ``propagation.slots_for`` allows."""
    n, n_interfaces = len(s.mass), len(s.gap)
    stiffness, damping = np.zeros(n), np.zeros(n)
    mass = np.asarray(s.mass, dtype=float)
    for i in range(n):
        entries = slice(s.matrix_start[i], s.matrix_start[i + 1])
        stiffness[i] = np.abs(s.stiffness_entry[entries]).sum() / mass[i]
        damping[i] = np.abs(s.damping_entry[entries]).sum() / mass[i]
    for e, law in enumerate(arrays.normal_laws):
        row = np.abs(s.normal_rows[e])
        stiffness += getattr(law, "stiffness", 0.0) * row * row.sum() / mass
    harmonics = s.amplitudes.shape[0] - 1
    norm = 2.0 * np.sqrt(stiffness.max(initial=0.0)) + damping.max(initial=0.0) \
        + harmonics * s.excitation_frequency
    levels = levels_for(step, norm)
    m = augmented_size(n, harmonics)
    slot_bytes = 8 * m * m * (1 + N_POWERS) * (levels + 1)
    if slot_bytes > LARGEST_PHASE_BYTES:
        raise ValueError(f"method=Exponential(): a phase of {n} coordinates and {harmonics} "
                         f"harmonics keeps {levels} levels of {m} × {m} matrices, "
                         f"{slot_bytes / 2**30:.1f} GiB, above {LARGEST_PHASE_BYTES / 2**30:g} "
                         "GiB: reduce the model (craig_bampton, modal_truncation) or use "
                         "Adaptive")
    slots = slots_for(m, levels)
    return Propagation(np.zeros((slots, m, m)), np.zeros((slots, N_POWERS, m, m)),
                       np.zeros((slots, levels, m, m)),
                       np.zeros((slots, levels, N_POWERS, m, m)),
                       np.full(slots, -1, dtype=np.int64), np.zeros(2, dtype=np.int64),
                       np.full(1, step), np.zeros((WORK_SLOTS, m, m)), np.zeros(m),
                       np.zeros(m), np.zeros(m), np.zeros(m),
                       plain(new_work)(n, n_interfaces, len(s.motion_amplitude)),
                       np.zeros(n), np.zeros(n), np.zeros(n))


def allocate(s, x0, v0, tangent0, controls, flow, propagation=None, times=None):
    """Every record a driver works in, allocated once, here in Python, so that the
    compiled loop allocates nothing and runs without reference counting: (state, work
    arrays, the switches' storage, event log, output), with the tangent from ``tangent0``
    (2 n_nodes × k) for a kernel with the tangent ``flow``, else a ``NoTangent``, and the
    ``propagation`` of a run that propagates its phases exactly (else a
    ``NoPropagation``). The output lists its sample times (``advance.sample_time``):
    ``times`` (``controls.n_samples`` of them, the first t0), else the grid
    t0 + k·sample_step, computed as the loop computed it."""
    n_nodes, n_interfaces, n_prescribed = len(s.mass), len(s.gap), len(s.motion_amplitude)
    tangent = plain(new_tangent)(
        tangent0, n_interfaces, controls.n_samples,
        plain(new_work)(n_nodes, n_interfaces, n_prescribed),
        controls.event_tolerance) if flow \
        else NoTangent(tangent0.copy())
    if propagation is None:
        propagation = NoPropagation()
    output = new_output(controls.n_samples, n_nodes, n_interfaces)
    output.t[:] = controls.t0 + np.arange(controls.n_samples) * controls.sample_step \
        if times is None else times
    return (new_state(x0, v0, tangent, n_interfaces, propagation),
            plain(new_work)(n_nodes, n_interfaces, n_prescribed),
            plain(new_switching)(n_nodes, n_interfaces, square_size(s)),
            new_events(controls.event_capacity, controls.zeno_events), output)


def square_size(s) -> int:
    """The side of a run's ``Switching.gram``: one row per node for stick clusters, per
    interface too for stick as constraints (``constraints``)."""
    n_nodes = len(s.mass)
    return max(n_nodes, len(s.gap)) if isinstance(s, StructureScene) else n_nodes


def plain(allocator):
    """The allocator as plain Python (numpy): compiled, it is callable from compiled code
    only."""
    return getattr(allocator, "py_func", allocator)


def finish(returned, out, events, tangent) -> Run:
    """The driver's ``Run``: what it ``returned`` (status, time, interface, steps, samples
    taken), the samples taken and the events logged, trimmed."""
    status, time, interface, steps, n_samples = returned
    n = min(int(events.n_events[0]), len(events.time))
    output = Output(*(column[:n_samples] for column in out))
    logged = events._replace(time=events.time[:n], interface=events.interface[:n],
                             kind=events.kind[:n])
    if isinstance(tangent, Tangent):
        tangent = tangent._replace(history=tangent.history[:n_samples])
    return Run(int(status), float(time), int(interface), int(steps), output, logged, tangent)
