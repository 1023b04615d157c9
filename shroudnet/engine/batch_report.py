"""What the device compiler says of a batch kernel (``engine.batch``) for one GPU
generation, compiled without a device: registers, stack, spills and occupancy.

The report needs numba-cuda's CUDA toolkit (NVVM and nvJitLink), not a GPU: numba-cuda
compiles the entry to PTX for a given compute capability, and nvJitLink assembles it,
telling what a thread of it uses.
"""

from __future__ import annotations

import re
import time
from contextlib import contextmanager
from dataclasses import dataclass
from types import ModuleType

from .batch import THREADS_PER_BLOCK, BatchInput, Layout, _arguments, _outputs, batch_kernel


@dataclass(frozen=True)
class KernelReport:
    """What the device compiler says of a batch kernel for one GPU generation, compiled
    without a device: the PTX's size [bytes], the registers and stack [bytes] a thread
    uses and what spills to local memory [bytes stored, loaded], the seconds the
    compiles took (numba and NVVM to PTX; the assembler, through nvJitLink), and the
    occupancy of a multiprocessor at ``THREADS_PER_BLOCK`` threads a block
    (``occupancy``)."""

    compute_capability: tuple[int, int]
    ptx_bytes: int
    registers: int
    stack: int
    spill_stores: int
    spill_loads: int
    ptx_seconds: float
    assembly_seconds: float

    @property
    def occupancy(self) -> float:
        """The fraction of a multiprocessor's warps that can be resident: registers are
        the limit (no shared memory is used). Per multiprocessor (compute capability
        7.0–9.0): 65,536 registers, 64 warps, 32 blocks; a warp's registers are allotted
        in units of 256."""
        per_warp = -(-self.registers * 32 // 256) * 256
        warps_per_block = THREADS_PER_BLOCK // 32
        blocks = min(65536 // per_warp // warps_per_block, 32)
        return min(blocks * warps_per_block, 64) / 64


def kernel_report(kernel: ModuleType, layout: Layout, numbers: BatchInput,
                  compute_capability: tuple[int, int] = (9, 0)) -> KernelReport:
    """Compile the batch kernel for ``numbers`` to PTX for ``compute_capability`` and
    assemble it with nvJitLink (both need numba-cuda's CUDA toolkit, not a device), and
    return what the assembler reports (``KernelReport``). Takes minutes."""
    from cuda.bindings import nvjitlink
    from numba import cuda, typeof

    entry = batch_kernel(kernel, layout)
    arguments = _arguments(layout, numbers, _outputs(len(numbers.x0), layout,
                                                     numbers.n_points), lambda a: a)
    began = time.perf_counter()
    with _compiling_for(compute_capability):
        ptx, _ = cuda.compile_ptx(entry.py_func, tuple(typeof(a) for a in arguments),
                                  cc=compute_capability)
    compiled_at = time.perf_counter()
    major, minor = compute_capability
    handle = nvjitlink.create(2, [f"-arch=sm_{major}{minor}".encode(), b"-verbose"])
    try:
        data = ptx.encode()
        nvjitlink.add_data(handle, nvjitlink.InputType.PTX, data, len(data), "runs")
        nvjitlink.complete(handle)
        log = bytearray(nvjitlink.get_info_log_size(handle))
        nvjitlink.get_info_log(handle, log)
    finally:
        nvjitlink.destroy(handle)
    text = log.decode(errors="replace")
    return KernelReport(
        compute_capability=compute_capability, ptx_bytes=len(data),
        registers=_reported(r"Used (\d+) registers", text),
        stack=_reported(r"(\d+) bytes stack frame", text),
        spill_stores=_reported(r"(\d+) bytes spill stores", text),
        spill_loads=_reported(r"(\d+) bytes spill loads", text),
        ptx_seconds=compiled_at - began, assembly_seconds=time.perf_counter() - compiled_at)


def _reported(pattern: str, log: str) -> int:
    """The largest number the assembler's log gives for ``pattern`` (its entry's)."""
    return max((int(found) for found in re.findall(pattern, log)), default=0)


@contextmanager
def _compiling_for(compute_capability: tuple[int, int]):
    """Compile device functions for ``compute_capability`` without a device: numba-cuda
    asks the current device for its compute capability as it compiles each one (its
    ``compile_ptx`` takes one for the kernel alone), and here there is none to ask."""
    from numba.cuda import dispatcher

    class Device:
        pass

    Device.compute_capability = compute_capability
    asked = dispatcher.get_current_device
    dispatcher.get_current_device = Device
    try:
        yield
    finally:
        dispatcher.get_current_device = asked
