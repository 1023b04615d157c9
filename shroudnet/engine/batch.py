"""The CUDA flavour of a kernel: a batch of runs of one kind of scene, one GPU thread each.

A batch is many runs of scenes of ``Blade``s that differ in their numbers only (the same
blades, interfaces, law classes and effects): a sweep's points, a map's cells. Each thread
integrates one of them by the fixed-step method, every switch located to the run's event
tolerance, stick clusters and the energy ledger as on the CPU, and keeps what a sweep
reads of it (``records.Reduction``: Poincaré points, ∫ x² dt, the work columns), never the
time history.

The device code is the CPU kernel's own: ``kernel_for`` loads the kernel module of the
scene's law classes and effects (``generate.load_kernel(..., shared=False)``), and numba
compiles its driver ``run``, with every phase function it calls, for the device from the
same Python source (numba-cuda compiles a CPU-compiled function called from device code
anew as a device function, with its options). What this module generates is the entry
around it (``batch_source``): one thread per run, the scene's arrays read from the batch
(a row of each array that differs between runs, the one copy of each that does not), and
the records the loop works in as arrays local to the thread, their sizes written into the
source as numbers when the kernel is built (``Layout``), so that the device compiler
knows every loop's length and keeps the small ones in registers. Every run reads its own
row of each scene field, the fields that the batch's scenes share included: a batch's
kernel then depends on the sizes of its scenes alone, never on which numbers differ (a
sweep of the speed and one of the gaps compile once), and a row is a few hundred bytes.
Arrays of no element (an event log of no capacity, the tangent of a run without one) are
one empty array in global memory that every thread shares. The runs of a batch are
ordered by the caller: threads of a warp run in lockstep, and neighbours in parameter
switch at about the same times (``run.batch``).

Each thread runs the transient periods with one sample a period, then the recorded ones
from where they ended, as two runs of ``simulate`` do (``studies.sweep.steady_point``):
the second starts afresh, from the first one's blades and the prescribed motions' start.

Double precision throughout. The device fuses multiplies and adds where the CPU kernel
does not, so a device run and a CPU run differ by rounding, which chaos amplifies.

``cuda_missing`` says what keeps batches off a GPU here; under numba's CUDA simulator
(``NUMBA_ENABLE_CUDASIM=1``) a batch runs on the CPU, each thread calling the CPU kernel,
which is how the tests check the entry without a GPU.
"""

from __future__ import annotations

import functools
import hashlib
import importlib.util
import os
import sys
from dataclasses import dataclass
from types import ModuleType

import numpy as np

from .cache import keep
from .codes import N_WORK
from .generate import _law_classes, flags, kernel_scene, load_kernel
from .records import Controls, allocate

#: Threads per block: two warps. A block's threads share its multiprocessor's registers,
#: and a thread of this loop needs many, so small blocks fill the multiprocessors best.
THREADS_PER_BLOCK = 64

#: The extra that installs the device compiler.
EXTRA = "pip install 'shroudnet[gpu]'"


def cuda_missing() -> str | None:
    """What keeps batches off a GPU here, in one line (numba-cuda not installed, or no
    CUDA device visible, with the driver's reason), or None when they can run (numba's
    CUDA simulator counts as a device)."""
    if importlib.util.find_spec("numba_cuda") is None:
        return f"numba-cuda is not installed ({EXTRA})"
    try:
        from numba import cuda

        if cuda.is_available():
            return None
        return "no CUDA GPU is visible to numba-cuda" + _driver_reason(cuda)
    except Exception as error:  # noqa: BLE001 - a broken driver or toolkit: say which
        return f"numba-cuda cannot reach a CUDA GPU ({_one_line(error)})"


def _driver_reason(cuda) -> str:
    """Why the CUDA driver gave no device, as " (reason)" (empty where it says nothing)."""
    try:
        cuda.cudadrv.driver.driver.cuInit(0)
    except Exception as error:  # noqa: BLE001 - whatever the driver raises is the reason
        return f" ({_one_line(error)})"
    return ""


def _one_line(error: Exception) -> str:
    """An error's message on one line: its lines that say something, joined."""
    lines = [line.strip(" :") for line in str(error).splitlines()]
    return "; ".join(line for line in lines if line) or type(error).__name__


@dataclass(frozen=True)
class Layout:
    """What a batch kernel is built for: the shape and dtype of each array of the loop's
    records (as ``records.allocate`` makes them for one run without an event log), by
    record and field; the shape and dtype of each field of a run's scene
    (``KernelScene``); how each ``Controls`` field is read (``controls``: "real", "whole"
    or "flag"); and the number of blades."""

    records: tuple[tuple[str, tuple[tuple[str, tuple[int, ...], str], ...]], ...]
    scene: tuple[tuple[str, tuple[int, ...], str], ...]
    controls: tuple[str, ...]
    n_blades: int

    def columns(self, kind: str) -> tuple[str, ...]:
        """The ``Controls`` fields read from the table of one ``kind``, in its order."""
        return tuple(name for name, k in zip(Controls._fields, self.controls) if k == kind)


def _shapes(record) -> tuple[tuple[str, tuple[int, ...], str], ...]:
    return tuple((name, tuple(value.shape), value.dtype.name)
                 for name, value in zip(record._fields, record) if isinstance(value, np.ndarray))


def control_kind(value) -> str:
    """How a ``Controls`` field of this value travels to a batch: "flag" (a bool), "real"
    (a float) or "whole" (an int)."""
    if isinstance(value, bool | np.bool_):
        return "flag"
    return "real" if isinstance(value, float | np.floating) else "whole"


def layout_of(scene, controls: Controls) -> Layout:
    """The ``Layout`` of a batch of runs like ``scene`` (a ``Scene`` of blades) under
    ``controls`` (those of one of its runs)."""
    s = kernel_scene(scene, shared=False)
    n = len(s.mass)
    logless = controls._replace(event_capacity=0)
    state, work, switching, events, _ = allocate(s, np.zeros(n), np.zeros(n),
                                                 np.zeros((2 * n, 0)), logless, flow=False)
    records = (("State", _shapes(state)), ("NoTangent", _shapes(state.tangent)),
               ("Work", _shapes(work)), ("Switching", _shapes(switching)),
               ("Events", _shapes(events)))
    scene_fields = tuple((name, np.shape(value), np.asarray(value).dtype.name)
                         for name, value in zip(s._fields, s))
    return Layout(records=records, scene=scene_fields,
                  controls=tuple(control_kind(value) for value in logless),
                  n_blades=scene.arrays.n_blades)


#: The fill of each array of the records at the start of a run, as ``records.allocate``
#: leaves it: zeros (where it leaves them empty, the loop writes before it reads), but the
#: Zeno guard's times of the latest switches, −inf (none yet).
FILLS = {("Events", "recent"): "-np.inf"}


def _fill(variable: str, shape: tuple[int, ...], value: str, indent: str) -> list[str]:
    """Lines that set every element of a local array to ``value``."""
    lines, index = [], []
    for depth, size in enumerate(shape):
        lines.append(f"{indent}{'    ' * depth}for j{depth} in range({size}):")
        index.append(f"j{depth}")
    lines.append(f"{indent}{'    ' * len(shape)}{variable}[{', '.join(index)}] = {value}")
    return lines


def _local(shape, dtype) -> str:
    size = shape[0] if len(shape) == 1 else f"({', '.join(map(str, shape))})"
    return f"cuda.local.array({size}, np.{dtype})"


#: The outputs of a batch kernel, one row per run: the ``records.Reduction`` of its
#: recorded periods, its final blades' state, its ``codes.Status``, the time [s] and
#: interface it stopped at, and in which run it did (0 the transient, 1 the recorded).
OUTPUTS = ("poincare", "extent", "square", "work", "final_x", "final_v", "status",
           "stop_time", "stop_interface", "stopped_in")


def batch_source(layout: Layout, key: str) -> str:
    """The generated entry of a batch kernel for ``layout``: ``runs``, one thread per run,
    and the records it works in (``key``: the CPU kernel's, which the source names so that
    a change of the kernel's code gives another file and no stale compiled code).

    ``runs`` takes every scene field as an array with one row per run; the start x0, v0
    (runs × coordinates); each run's ``Controls`` for the transient and the recorded run
    in tables of real, whole and flag values (runs × 2 × columns); the response's
    coordinate, the samples between two Poincaré points of each run (2) and the runs to
    make (1: the recorded alone, 2: the transient first); the shared empty arrays; and
    the ``OUTPUTS``."""
    scene = [name for name, _, _ in layout.scene]
    records = dict(layout.records)
    empty = [(record, name) for record, fields in layout.records
             for name, shape, _ in fields if 0 in shape]
    inputs = ([f"scene_{name}" for name in scene]
              + ["x0", "v0", "real_controls", "whole_controls", "flag_controls", "response",
                 "every", "parts"]
              + [f"empty_{record}_{name}" for record, name in empty] + list(OUTPUTS))
    lines = [
        f"# Generated by shroudnet.engine.batch for the kernel {key}. Do not edit.",
        "# One thread per run of a batch: the kernel's driver on records local to the thread.",
        "import numpy as np",
        "from numba import cuda",
        "from shroudnet.engine.codes import FINISHED",
        "from shroudnet.engine.records import (Controls, Events, KernelScene, NoPropagation,",
        "                                      NoTangent, Reduction, State, Switching, Work)",
        "",
        "run = None  # the driver of the CPU kernel, set by shroudnet.engine.batch",
        "",
        "",
        "@cuda.jit(device=True, inline='always')",
        "def view(array):",
        "    \"\"\"An array of the batch in global memory, as the driver takes it (replaced",
        "    under the simulator, whose arrays in global memory are wrappers).\"\"\"",
        "    return array",
        "",
        "",
        f"def runs({', '.join(inputs)}):",
        "    i = cuda.grid(1)",
        "    if i >= status.shape[0]:",
        "        return",
        "    s = KernelScene(" + ", ".join(f"view(scene_{name}[i])" if shape else
                                      f"scene_{name}[i]"
                                      for name, shape, _ in layout.scene) + ")",
    ]
    variables = {}
    for record, fields in layout.records:
        for name, shape, dtype in fields:
            variables[record, name] = variable = f"{record.lower()}_{name}"
            lines.append(f"    {variable} = " + (f"view(empty_{record}_{name})" if 0 in shape
                                                 else _local(shape, dtype)))
    lines += [
        "    for part in range(2 - parts, 2):",
        "        for j in range(x0.shape[1]):  # the recorded run goes on from the blades'",
        f"            if part == 2 - parts or j >= {layout.n_blades}:  # state, and restarts "
        "the prescribed motions",
        "                state_x[j] = x0[i, j]",
        "                state_v[j] = v0[i, j]",
    ]
    for record, fields in layout.records:
        for name, shape, _ in fields:
            if (record, name) not in (("State", "x"), ("State", "v")) and 0 not in shape:
                lines += _fill(variables[record, name], shape,
                               FILLS.get((record, name), "0"), "        ")

    def built(record):
        return f"{record}({', '.join(variables[record, n] for n, _, _ in records[record])})"

    state = [variables["State", name] for name in ("x", "v", "energy", "modes",
                                                    "contact_before", "motion_before")]
    tables = {"real": "real_controls", "whole": "whole_controls", "flag": "flag_controls"}
    controls = [f"{tables[kind]}[i, part, {layout.columns(kind).index(name)}]"
                for name, kind in zip(Controls._fields, layout.controls)]
    lines += [
        f"        state = State({', '.join(state)}, {built('NoTangent')}, NoPropagation())",
        f"        w = {built('Work')}",
        f"        sw = {built('Switching')}",
        f"        events = {built('Events')}",
        f"        controls = Controls({', '.join(controls)})",
        "        out = Reduction(response, every[part], view(poincare[i]), view(extent[i]), "
        "view(square[i]), view(work[i]))",
        "        done = run(state, s, w, sw, events, controls, out)",
        "        status[i] = done[0]",
        "        stop_time[i] = done[1]",
        "        stop_interface[i] = done[2]",
        "        stopped_in[i] = part",
        "        if done[0] != FINISHED:",
        "            return",
        f"    for j in range({layout.n_blades}):",
        "        final_x[i, j] = state_x[j]",
        "        final_v[i, j] = state_v[j]",
        "",
    ]
    return "\n".join(lines)


def kernel_key(scene) -> tuple:
    """What the batch kernel of ``scene`` is compiled for (``kernel_for``): the names of
    its law classes and its effects. Scenes of one key run in one batch."""
    normal, friction = _law_classes(scene.arrays, shared=False)
    return (tuple(c.__qualname__ for c in normal), tuple(c.__qualname__ for c in friction),
            tuple(sorted(flags(scene.arrays).items())))


def kernel_for(scene) -> ModuleType:
    """The CPU kernel whose driver a batch of runs like ``scene`` compiles for the device:
    the fixed-step method's, of the scene's own law classes and effects."""
    return load_kernel(scene, method="fixed_step", shared=False)


@functools.cache
def batch_kernel(kernel: ModuleType, layout: Layout):
    """The CUDA kernel ``runs`` of ``batch_source`` for ``layout``, calling ``kernel``'s
    driver (once per process; numba-cuda keeps the compiled code on disk beside the
    generated source, and compiles when first launched)."""
    from numba import cuda

    source = batch_source(layout, kernel.CACHE_KEY)
    key = hashlib.sha256(source.encode()).hexdigest()[:20]
    path = keep(f"batch_{key}.py", source)
    name = f"shroudnet_batch_{key}"
    spec = importlib.util.spec_from_file_location(name, path)
    module = importlib.util.module_from_spec(spec)
    sys.modules[name] = module
    spec.loader.exec_module(module)
    module.run = kernel.run
    if _simulated():
        module.view = _unwrapped
    return cuda.jit(module.runs, cache=not _simulated())


def _simulated() -> bool:
    """Whether numba's CUDA simulator stands in for the GPU in this process."""
    return os.environ.get("NUMBA_ENABLE_CUDASIM", "0") not in ("", "0")


def _unwrapped(array):
    """The numpy array inside the simulator's stand-in for an array in global memory, which
    the CPU driver the simulator calls takes (it cannot take the wrapper)."""
    return getattr(array, "_ary", array)


@dataclass(frozen=True)
class BatchInput:
    """The numbers of a batch of runs, one row per run (``batch_source`` says how each is
    read): the scene fields (``scene``, by name), the start (x0, v0), the ``Controls``
    tables (runs × 2 × columns, by kind), the response's coordinate, the samples between
    Poincaré points of the transient and the recorded run, the runs to make per thread,
    and the Poincaré points the recorded run keeps."""

    scene: dict
    x0: np.ndarray
    v0: np.ndarray
    controls: dict
    response: int
    every: np.ndarray
    parts: int
    n_points: int


def _outputs(runs: int, layout: Layout, n_points: int) -> dict[str, np.ndarray]:
    """The ``OUTPUTS`` of a batch of ``runs``, zeroed."""
    return {"poincare": np.zeros((runs, n_points, 2)),
            "extent": np.zeros((runs, 2)), "square": np.zeros((runs, 3)),
            "work": np.zeros((runs, 2, N_WORK)),
            "final_x": np.zeros((runs, layout.n_blades)),
            "final_v": np.zeros((runs, layout.n_blades)),
            "status": np.zeros(runs, dtype=np.int64), "stop_time": np.zeros(runs),
            "stop_interface": np.zeros(runs, dtype=np.int64),
            "stopped_in": np.zeros(runs, dtype=np.int64)}


def _arguments(layout: Layout, numbers: BatchInput, outputs: dict, place) -> list:
    """The arguments of ``runs`` in its order, each array put by ``place`` (onto the device,
    or left as it is)."""
    empty = [np.zeros(shape, dtype=dtype) for _, fields in layout.records
             for _, shape, dtype in fields if 0 in shape]
    return ([place(numbers.scene[name]) for name, _, _ in layout.scene]
            + [place(numbers.x0), place(numbers.v0)]
            + [place(numbers.controls[kind]) for kind in ("real", "whole", "flag")]
            + [np.int64(numbers.response), place(numbers.every), np.int64(numbers.parts)]
            + [place(array) for array in empty] + [outputs[name] for name in OUTPUTS])


def launch(kernel: ModuleType, layout: Layout, numbers: BatchInput) -> dict[str, np.ndarray]:
    """Run the batch ``numbers`` on the GPU (or the simulator) and return its ``OUTPUTS``
    by name, one row per run."""
    from numba import cuda

    runs = len(numbers.x0)
    entry = batch_kernel(kernel, layout)
    device = {name: cuda.to_device(value)
              for name, value in _outputs(runs, layout, numbers.n_points).items()}
    blocks = (runs + THREADS_PER_BLOCK - 1) // THREADS_PER_BLOCK
    entry[blocks, THREADS_PER_BLOCK](*_arguments(layout, numbers, device, cuda.to_device))
    cuda.synchronize()
    return {name: device[name].copy_to_host() for name in OUTPUTS}
