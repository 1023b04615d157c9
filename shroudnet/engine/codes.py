"""The codes the engine stores as small integers, each defined once.

Interface modes, event kinds, run statuses and the columns of the work record are
``IntEnum`` classes; the compiled code reads the module constants below, derived from
them, so the two can never disagree.
"""

from __future__ import annotations

from enum import IntEnum

from .controller import STALL_SIZE, STALL_STEPS


class Mode(IntEnum):
    """Interface modes, stored as small integers in the modes arrays.

    OPEN: no contact (δ ≤ 0), no force. STICK: closed, slip velocity held at zero, friction a
    constraint force. SLIP_POSITIVE / SLIP_NEGATIVE: closed and slipping with v > 0 / v < 0,
    friction ±μ(|v|) N. A closed interface without exact friction (frictionless or
    regularised) is in a slip mode whose sign is not used.
    """

    OPEN = 0
    STICK = 1
    SLIP_POSITIVE = 2
    SLIP_NEGATIVE = 3


class EventKind(IntEnum):
    """What switched at an event."""

    CLOSING = 0      # contact closed (δ rose through 0)
    SEPARATION = 1   # contact opened (δ fell through 0)
    STICKING = 2     # slip velocity reached 0 and the static friction holds
    REVERSAL = 3     # slip velocity reached 0 and the interface slips the other way
    BREAKAWAY = 4    # a stuck interface's friction reached μ_s N


class Status(IntEnum):
    """How a run ended. Every status but FINISHED stops it with a ``SimulationError``
    whose message is ``Status.message``."""

    FINISHED = 0
    ZENO = 1
    INCONSISTENT = 2
    NOT_FINITE = 3
    STEP_TOO_SMALL = 4
    NO_PROGRESS = 5
    STALLED = 6
    OVERCONSTRAINED = 7

    def message(self, when: str, where: str, **details) -> str:
        """What stopped the run ``when`` (a time) ``where`` (an interface), and what to do.

        ``details`` fill the message's numbers: ``zeno_events`` and ``zeno_window``
        [periods] for ZENO, ``smallest_step`` [periods] for STEP_TOO_SMALL and STALLED;
        ``fixed_step``, true for a run of the classical Runge–Kutta on a fixed grid, adds
        its step to the suspects of NOT_FINITE (an adaptive step shrinks instead).
        """
        suspects = _FIXED_STEP_SUSPECT if details.get("fixed_step") else ""
        return _MESSAGES[self].format(when=when, where=where, max_idle=MAX_IDLE_SWITCHES,
                                      stall_steps=STALL_STEPS,
                                      stall_step=STALL_SIZE * details.get("smallest_step", 0.0),
                                      fixed_step_suspect=suspects, **details)


class WorkColumn(IntEnum):
    """Columns of the cumulative work record [J]: the integrated powers (excitation in;
    damping, friction and contact out), then the kinetic energy removed when velocities
    are projected onto stick clusters."""

    EXCITATION = 0
    DAMPING = 1
    FRICTION = 2
    CONTACT = 3
    PROJECTION = 4


#: Located switches in a row that change no mode before a run is stopped (NO_PROGRESS).
#: A guard that crosses while the mode rule keeps every mode is legitimate once (a slip
#: velocity that touches zero and goes on the same way); a long series means the guards
#: and the mode rule disagree, and the run would creep on by one event tolerance a switch.
MAX_IDLE_SWITCHES = 1000


_MESSAGES = {
    Status.ZENO: (
        "Zeno or chattering behaviour {when}{where}: {zeno_events} switches within "
        "{zeno_window:g} periods. The switches accumulate there, and past that point the laws "
        "define no motion the integrator can follow. Make the contact force continuous at "
        "closing, soften or damp the contact, use a Regularised friction law, or widen "
        "ZenoGuard if this is expected."),
    Status.INCONSISTENT: (
        "no consistent set of stick and slip modes {when}{where}: the interface needs more "
        "static friction than μ_s N to stick, yet slipping either way would reverse at once. "
        "Its friction law's kinetic coefficient near zero slip, μ(0⁺), must not exceed μ_s; "
        "and where its slip is held by other stuck contacts (the pairs of a patch that "
        "slide alike: rigid stick shares their static friction by least norm, whatever "
        "their limits), give the interface a tangential_stiffness= (elastic stick)."),
    Status.NO_PROGRESS: (
        "no progress {when}{where}: {max_idle} switches in a row changed no mode, so the "
        "event guards and the stick and slip rule disagree there. The laws cannot cause this "
        "(both read the same μ_s N): it is a defect of the mode rule; please report it with "
        "the scene file."),
    Status.STEP_TOO_SMALL: (
        "the adaptive step fell below {smallest_step:g} periods {when}{where}: the forces "
        "change too abruptly there for the tolerances (a jump in a contact law, or a very "
        "stiff contact); smooth the law, or loosen rtol/atol."),
    Status.STALLED: (
        "the adaptive steps stayed below {stall_step:g} periods for {stall_steps} steps in a "
        "row {when}{where}: the forces switch back and forth faster "
        "than the steps, with no event to follow (a contact law with a jump makes the motion "
        "chatter across it); make the law continuous, or loosen rtol/atol."),
    Status.NOT_FINITE: (
        "the state or the forces became non-finite {when}{where}: the motion left the range "
        "of a float there. Either a contact or friction law returned inf or NaN, "
        "{fixed_step_suspect}or the scene's forces and stiffnesses grow the motion beyond "
        "1e308 (check their units)."),
    Status.OVERCONSTRAINED: (
        "no consistent set of stick and slip modes {when}{where}: sticking there would tie "
        "two prescribed motions together (or a prescribed motion to a fixed node), and "
        "slipping either way would reverse at once. Give the interface a friction law whose "
        "static coefficient μ_s the forces there can exceed, or let the two motions meet "
        "through a coupling."),
    Status.FINISHED: "the run finished {when}{where}",
}

#: What NOT_FINITE suspects besides the laws and the scene's units in a run on a fixed grid.
_FIXED_STEP_SUSPECT = ("or the fixed step is too large for the stiffest contact (use "
                       "Adaptive, or more steps per period), ")

# The same codes as plain ints, for the compiled code.
OPEN, STICK, SLIP_POSITIVE, SLIP_NEGATIVE = (int(m) for m in Mode)
CLOSING, SEPARATION, STICKING, REVERSAL, BREAKAWAY = (int(k) for k in EventKind)
N_EVENT_KINDS = len(EventKind)
(FINISHED, ZENO, INCONSISTENT, NOT_FINITE, STEP_TOO_SMALL, NO_PROGRESS, STALLED,
 OVERCONSTRAINED) = (int(s) for s in Status)
#: Work columns integrated from the powers ``derivative`` returns, and all the columns.
N_POWERS = int(WorkColumn.CONTACT) + 1
N_WORK = len(WorkColumn)
PROJECTION = int(WorkColumn.PROJECTION)
