"""Batches of runs on a GPU: many scenes of blades that differ in their numbers only, each
run by the fixed-step method in a GPU thread of its own (``engine.batch``).

A batch keeps of each run what a sweep reads (``BatchRuns``): the Poincaré points of one
blade over the recorded periods, E_ρ, the friction loss per cycle, the extent the
classification measures distances by, and the final state; never the time history. A
run that stops (the Zeno guard, a mode set with no consistent choice, a non-finite state)
is kept as a failure with the message ``simulate`` would raise, and the others go on.

``prepare_run`` checks one scene and turns it into numbers (``PreparedRun``, small and
picklable, so that many are made on every core); ``run_batch`` stacks them and runs them,
in the order given: the caller orders them so that neighbours in parameter are neighbours
in a warp, whose threads run in lockstep and wait for each other's switches.
"""

from __future__ import annotations

import time
from collections.abc import Sequence
from dataclasses import dataclass

import numpy as np

from contact_laws import check_instance, check_int

from ..engine.batch import (BatchInput, control_kind, cuda_missing, kernel_for, kernel_key,
                            launch, layout_of)
from ..engine.codes import FINISHED, Status, WorkColumn
from ..engine.generate import kernel_scene
from ..engine.records import Controls, KernelScene
from ..model.scene import Scene
from .methods import EVENT_TOLERANCE, FixedStep, ZenoGuard
from .scales import check_scales
from .simulate import _check_motions, _stop_message, initial_state, run_controls
from .simulation import SimulationError


class NoDevice(RuntimeError):
    """A batch was asked to run on a GPU where none can run it; the message says what is
    missing, in one line."""


def check_device(owner: str) -> None:
    """Raise ``NoDevice`` saying what is missing when batches cannot run here."""
    missing = cuda_missing()
    if missing is not None:
        raise NoDevice(f"{owner}: executor='cuda' cannot run here: {missing}")


@dataclass(frozen=True)
class PreparedRun:
    """One scene of a batch as numbers: the fields of its ``KernelScene`` (for the kernel
    of its own law classes), its start (x0, v0, prescribed motions included), the
    ``Controls`` of its transient and of its recorded run, the kernel it needs (its law
    classes' names and effects) and its excitation period [s]; or ``error``, the message
    of the ``SimulationError`` that refuses to run it (its numbers cannot be carried)."""

    fields: tuple
    x0: np.ndarray
    v0: np.ndarray
    controls: tuple[Controls, Controls]
    kernel: tuple
    period: float
    error: str | None = None


def check_batch_scene(owner: str, scene: Scene) -> None:
    """Refuse a scene that a batch cannot run: one with substructures or elastic
    contacts (a batch runs scenes of ``Blade``s with rigid stick)."""
    check_instance(owner, "scene_at(value)", scene, Scene, expected="a shroudnet.Scene")
    if scene.arrays.is_structure:
        raise ValueError(f"{owner}: executor='cuda' runs scenes of Blades whose stick is "
                         "rigid, not substructures or elastic contacts "
                         "(Interface.tangential_stiffness); run this one on the CPU")


def prepare_run(scene: Scene, *, transient: int, record: int, method: FixedStep,
                samples_per_period: int, event_tolerance: float = EVENT_TOLERANCE,
                zeno: ZenoGuard = ZenoGuard(), initial=None,
                owner: str = "run_batch") -> PreparedRun:
    """``scene`` checked and turned into the numbers of a batch (arguments as ``sweep``
    takes them; ``method`` a ``FixedStep``)."""
    check_batch_scene(owner, scene)
    n = scene.arrays.n_blades
    x0, v0 = initial_state(initial, n, owner)
    x_p, v_p = scene.arrays.prescribed_state(0.0)
    period = scene.excitation_period
    first = run_controls(scene, max(transient, 1), method, 1, event_tolerance, zeno, 0)[0]
    second = run_controls(scene, record, method, samples_per_period, event_tolerance, zeno,
                          0)[0]
    error = None
    try:
        check_scales(scene, transient + record, method, (x0, v0))
        _check_motions(scene, (transient + record) * period)
    except SimulationError as stopped:
        error = str(stopped)
    return PreparedRun(fields=tuple(kernel_scene(scene, shared=False)),
                       x0=np.concatenate([x0, x_p]), v0=np.concatenate([v0, v_p]),
                       controls=(first, second), kernel=kernel_key(scene), period=period,
                       error=error)


@dataclass(frozen=True)
class BatchRuns:
    """What a batch of runs kept, one entry per run in the order given.

    ``poincare`` (runs × (record + 1) × 2): (x [m], ẋ [m/s]) of the response at
    t = k T_e of the recorded periods; ``energy_density`` E_ρ [m²] and
    ``friction_loss`` [J per period] over them; ``extent`` (runs × 2): the largest |x|
    and |ẋ| of the response over their samples; ``final_x``, ``final_v`` (runs × blades)
    the state at the end; ``errors``: None for a run that finished, else the message
    ``simulate`` would raise (its Poincaré points and numbers are then NaN). ``seconds``:
    the wall time of the batch on the device, transfers included, and of it compiling
    (``compile_seconds``: the first launch of a kernel in a process).
    """

    poincare: np.ndarray
    energy_density: np.ndarray
    friction_loss: np.ndarray
    extent: np.ndarray
    final_x: np.ndarray
    final_v: np.ndarray
    errors: tuple[str | None, ...]
    seconds: float


def run_batch(scene: Scene, prepared: Sequence[PreparedRun], *, response: int,
              transient: int, record: int, samples_per_period: int,
              zeno: ZenoGuard = ZenoGuard(), scene_of=None) -> BatchRuns:
    """Run the ``prepared`` scenes (``prepare_run``), in their order, one GPU thread each,
    and return what they kept. ``scene`` is one of them (the kernel is compiled for its
    law classes and effects, which all must share); ``response`` the position of the
    blade whose Poincaré points are kept; ``scene_of(k)`` the scene of run k, to name the
    interface in the message of a run that stopped (``scene`` where not given).

    Raises ``NoDevice`` where no GPU can run it, ``ValueError`` naming the first run whose
    scene differs from ``scene`` in anything but its numbers.
    """
    check_device("run_batch")
    response = check_int("run_batch", "response", response, low=0,
                         most=scene.arrays.n_blades - 1)
    key = kernel_key(scene)
    runnable = [k for k, run in enumerate(prepared) if run.error is None]
    runs = len(prepared)
    n_points = record + 1
    poincare = np.full((runs, n_points, 2), np.nan)
    energy_density, friction_loss = np.full(runs, np.nan), np.full(runs, np.nan)
    extent = np.full((runs, 2), np.nan)
    final_x = np.full((runs, scene.arrays.n_blades), np.nan)
    final_v = final_x.copy()
    errors: list[str | None] = [run.error for run in prepared]
    began = time.perf_counter()
    if runnable:
        layout = layout_of(scene, prepared[runnable[0]].controls[1])
        numbers = batch_input(prepared, runnable, key, response=response,
                              transient=transient, record=record,
                              samples_per_period=samples_per_period)
        out = launch(kernel_for(scene), layout, numbers)
        done = out["status"] == FINISHED
        rows = np.array(runnable)
        kept = rows[done]
        poincare[kept] = out["poincare"][done]
        extent[kept] = out["extent"][done]
        square, work = out["square"][done], out["work"][done]
        # as Simulation.energy_density and friction_loss_per_cycle take them: the samples'
        # span is the last one's time (the first is at t = 0)
        energy_density[kept] = square[:, 0] / square[:, 1]
        friction, lost = WorkColumn.FRICTION, WorkColumn.PROJECTION
        friction_loss[kept] = (work[:, 1, friction] + work[:, 1, lost] - work[:, 0, friction]
                               - work[:, 0, lost]) / record
        final_x[kept], final_v[kept] = out["final_x"][done], out["final_v"][done]
        for k, row in zip(rows[~done], np.flatnonzero(~done)):
            run = prepared[k]
            where = scene_of(k) if scene_of is not None else scene
            zeno_window = run.controls[1].zeno_window / run.period
            errors[k] = _stop_message(where, Status(int(out["status"][row])),
                                      float(out["stop_time"][row]),
                                      int(out["stop_interface"][row]), run.period,
                                      zeno.events, zeno_window)
    return BatchRuns(poincare=poincare, energy_density=energy_density,
                     friction_loss=friction_loss, extent=extent, final_x=final_x,
                     final_v=final_v, errors=tuple(errors),
                     seconds=time.perf_counter() - began)


def batch_input(prepared: Sequence[PreparedRun], runnable: Sequence[int], key: tuple, *,
                response: int, transient: int, record: int,
                samples_per_period: int) -> BatchInput:
    """The runs ``runnable`` of ``prepared`` as the numbers of a batch (``BatchInput``),
    keeping the Poincaré points of coordinate ``response`` over the ``record`` periods
    after ``transient``; ``ValueError`` naming the first run whose kernel is not ``key``
    or whose scene's shape differs."""
    for k in runnable:
        if prepared[k].kernel != key:
            raise ValueError(f"run_batch: run {k} needs another kernel than the first one (law "
                             f"classes and effects {prepared[k].kernel} against {key}): a "
                             "batch runs scenes that differ in their numbers only")
    runs = [prepared[k] for k in runnable]
    scene = {}
    for f, name in enumerate(KernelScene._fields):
        values = [run.fields[f] for run in runs]
        shape = np.shape(values[0])
        for k, value in zip(runnable, values):
            if np.shape(value) != shape:
                raise ValueError(f"run_batch: run {k}'s scene has {name} of shape "
                                 f"{np.shape(value)} where the first one's is {shape}: a "
                                 "batch runs scenes of the same blades, interfaces and laws")
        scene[name] = np.ascontiguousarray(np.array(values) if values else
                                           np.zeros((0, *shape)))
    kinds = {"real": np.float64, "whole": np.int64, "flag": np.bool_}
    controls = {}
    for kind, dtype in kinds.items():
        columns = [name for name in Controls._fields
                   if control_kind(getattr(runs[0].controls[1], name)) == kind] if runs else []
        controls[kind] = np.array([[[getattr(c, name) for name in columns]
                                    for c in run.controls] for run in runs],
                                  dtype=dtype).reshape(len(runs), 2, len(columns))
    return BatchInput(scene=scene, x0=np.array([run.x0 for run in runs]),
                      v0=np.array([run.v0 for run in runs]), controls=controls,
                      response=response,
                      every=np.array([transient + 1, samples_per_period], dtype=np.int64),
                      parts=2 if transient > 0 else 1, n_points=record + 1)

