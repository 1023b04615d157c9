"""The memory a run needs, estimated from the sizes of its scene before any work is done.

A run of a scene with N nodes (its blades, or with substructures its coordinates, and its
prescribed-motion nodes), m interfaces, S samples, an event log of capacity E, and k tangent
columns (with the tangent flow) holds at once, in bytes (``engine.records.allocate``):

===========  ==============================================================================
record       S (8 (1 + 2N + 2m + W) + m) + 17 E: per sample t, x, v, the normal and the
             friction force of each interface, W = 5 work columns (float64) and the modes
             (int8); per event its time, interface and kind
matrices     8 (3 m N + 3 q²): the stick clusters' bookkeeping, an m × N and an m × 2N
             matrix and three q × q ones (G Gᵀ, its factor and inverse), q = N (with
             substructures max(N, m))
vectors      8 (35 N + 24 m): the state, the Runge–Kutta stages and the per-node and
             per-interface work vectors (a bound; the exact count is a few per cent less)
tangent      8 (28 N² + 32 N k + S k + 4 N + 58 m) + 8 (35 N + 24 m), with the tangent
             flow only: the matrix exponentials' slots, the tangent's stages and history,
             the forces kept at each stage and their keys, a second set of work vectors
===========  ==============================================================================

The matrices grow as N² and outweigh the rest from a few thousand blades on: a ring of
10,000 blades needs 4.5 GiB of them, one of a million blades 44,700 GiB. Below that the
record dominates, as S times the blades and interfaces. The energy ledger that follows a run
builds one N × N matrix, less than the run's own matrices, once they are freed.

``check_footprint`` refuses a run whose matrices, vectors and tangent exceed the machine's
memory, since no choice of periods can save it; the record is ``simulate``'s check.
``check_group_size`` makes the same check from the counts of nodes and interfaces alone,
before a group is built (a scene file's ``[group] count``), since building a group of a
million blades takes a minute and gigabytes of its own.
"""

from __future__ import annotations

from typing import NamedTuple

from contact_laws import check_int

from ..machine import machine_memory

#: Bytes of a float64.
WORD = 8
#: Work columns of the record (``engine.codes.WorkColumn``).
WORK_COLUMNS = 5
#: Bytes of one logged event: its time (float64), interface (int64) and kind (int8).
EVENT_BYTES = 17
#: Words per node and per interface of the vectors a run works in (a bound).
NODE_WORDS, INTERFACE_WORDS = 35, 24
#: Matrix-exponential slots of the tangent flow, each 2N × 2N (``engine.exponential``).
TANGENT_SLOTS = 7


class Footprint(NamedTuple):
    """The bytes a run holds at once, by part (the module docstring gives each formula)."""

    record: int
    matrices: int
    vectors: int
    tangent: int

    @property
    def total(self) -> int:
        return self.record + self.matrices + self.vectors + self.tangent


def run_footprint(nodes: int, interfaces: int, samples: int, event_capacity: int, *,
                  square: int | None = None, tangent_columns: int | None = None
                  ) -> Footprint:
    """The ``Footprint`` of a run of ``nodes`` nodes (coordinates and prescribed-motion
    nodes), ``interfaces`` interfaces and ``samples`` samples, with an event log of
    ``event_capacity`` events; ``square`` is the side of the stick-cluster matrices (default
    ``nodes``), ``tangent_columns`` the columns of the tangent flow (None: no tangent)."""
    owner = "run_footprint"
    n = check_int(owner, "nodes", nodes, low=0)
    m = check_int(owner, "interfaces", interfaces, low=0)
    s = check_int(owner, "samples", samples, low=0)
    e = check_int(owner, "event_capacity", event_capacity, low=0)
    q = n if square is None else check_int(owner, "square", square, low=0)
    record = s * (WORD * (1 + 2 * n + 2 * m + WORK_COLUMNS) + m) + EVENT_BYTES * e
    vectors = WORD * (NODE_WORDS * n + INTERFACE_WORDS * m)
    tangent = 0
    if tangent_columns is not None:
        k = check_int(owner, "tangent_columns", tangent_columns, low=0)
        tangent = WORD * (4 * TANGENT_SLOTS * n * n + 32 * n * k + s * k + 4 * n
                          + 58 * m) + vectors
    return Footprint(record=record, matrices=WORD * (3 * m * n + 3 * q * q), vectors=vectors,
                     tangent=tangent)


def scene_footprint(scene, samples: int, event_capacity: int, *,
                    tangent_columns: int | None = None) -> Footprint:
    """``run_footprint`` of a run of ``scene`` (a ``Scene``) over ``samples`` samples."""
    a = scene.arrays
    nodes = a.n_blades + a.n_prescribed
    return run_footprint(nodes, a.n_interfaces, samples, event_capacity,
                         square=max(nodes, a.n_interfaces) if a.is_structure else nodes,
                         tangent_columns=tangent_columns)


def check_footprint(scene, samples: int, event_capacity: int, *,
                    tangent_columns: int | None = None, memory: int | None = None) -> None:
    """Refuse, before any work, a run of ``scene`` whose size alone could not fit in
    ``memory`` bytes (default ``machine_memory()``; nothing is refused where it is unknown):
    a ValueError of one line with the blades, interfaces and samples, the GiB the whole run
    needs, and the GiB the machine has.

    What the blades and interfaces set (the matrices, the vectors and the tangent flow) is
    checked here, since fewer periods cannot shrink it; the record, which ``samples`` set, is
    ``simulate``'s own check against the memory available as the run starts.
    """
    need = scene_footprint(scene, samples, event_capacity, tangent_columns=tangent_columns)
    excess = _excess(need, memory)
    if excess is None:
        return
    a = scene.arrays
    nodes = f"{a.n_blades:,} coordinates" if a.is_structure else f"{a.n_blades:,} blades"
    raise ValueError(f"a run of {nodes} and {a.n_interfaces:,} interfaces over {samples:,} "
                     f"samples would need {excess}; simulate fewer blades")


def check_group_size(nodes: int, interfaces: int, *, memory: int | None = None) -> None:
    """Refuse a group of ``nodes`` nodes (blades and prescribed-motion nodes; with
    substructures, each counts as at least one coordinate) and ``interfaces`` interfaces
    whose run could not fit in ``memory`` bytes (default ``machine_memory()``; nothing is
    refused where it is unknown), whatever its periods: ``check_footprint``'s check, made
    from the counts before the group is built. A ValueError of one line with the GiB a run
    would need at least, and the GiB the machine has; the caller names where the counts
    come from."""
    nodes = check_int("check_group_size", "nodes", nodes, low=0)
    interfaces = check_int("check_group_size", "interfaces", interfaces, low=0)
    excess = _excess(run_footprint(nodes, interfaces, 0, 0), memory)
    if excess is not None:
        raise ValueError(f"a run of {nodes:,} nodes and {interfaces:,} interfaces would need "
                         f"at least {excess}")


def _excess(need: Footprint, memory: int | None) -> str | None:
    """None where what the blades and interfaces set (all of ``need`` but the record) fits
    in ``memory`` bytes (default ``machine_memory()``, None: unknown, so it fits); else
    the words "… GiB (… of it …), more than the … GiB of memory this machine has"."""
    if memory is None:
        memory = machine_memory()
    if memory is None or need.total - need.record <= memory:
        return None
    largest = max(("the stick-cluster matrices", need.matrices),
                  ("the tangent flow", need.tangent), key=lambda part: part[1])
    return (f"{_gib(need.total)} GiB ({_gib(largest[1])} GiB of it {largest[0]}, whatever "
            f"the periods), more than the {_gib(memory)} GiB of memory this machine has")


def _gib(size: int) -> str:
    """``size`` bytes in GiB, to three significant figures, with thousands separated."""
    gib = size / 2**30
    return f"{gib:,.0f}" if gib >= 100 else f"{gib:.3g}"
