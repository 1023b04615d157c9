"""What this machine has, read once: its memory, which every run and file reader that
could ask for more checks against before any work."""

import functools
import os
from pathlib import Path


@functools.cache
def machine_memory() -> int | None:
    """Bytes of memory this machine has (``os.sysconf``: physical pages × page size),
    lowered to a cgroup v2 limit where one is set; None where neither can be read. Read
    once: every run checks against it."""
    found = []
    try:
        found.append(os.sysconf("SC_PHYS_PAGES") * os.sysconf("SC_PAGE_SIZE"))
    except (AttributeError, OSError, ValueError):
        pass
    try:
        limit = Path("/sys/fs/cgroup/memory.max").read_text().strip()
        if limit != "max":
            found.append(int(limit))
    except (OSError, ValueError):
        pass
    found = [size for size in found if size > 0]
    return min(found) if found else None
