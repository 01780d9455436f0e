"""Refuse a catalogue too large for this machine before building its cost tables.

The certified search prices every ordered pair of candidates: its cost tables and its
network of date cells grow with N (N - 1).  Measured (``benchmarks/memory.py``, the 481
debris fragments and subsets): a run's peak memory is about 235 MB plus 1,219 bytes per
ordered pair.  A catalogue whose estimate passes the memory this machine has available
would end in a MemoryError (or the system's out-of-memory killer) minutes later; it is
refused at once, with the figures and the filters that narrow it.
"""

from __future__ import annotations

import contextlib
import os
from pathlib import Path

BYTES_PER_PAIR = 1300
"""Peak memory per ordered pair of candidates [bytes] (1,219 measured, rounded up)."""
BASE_BYTES = 300 * 2**20
"""Peak memory of a run of a few candidates [bytes] (235 MB measured, rounded up)."""
USABLE_FRACTION = 0.8
"""Part of the available memory a run may plan to use."""
FILTERS = ("narrow the candidates: --altitude-km, --inclination-deg, --max-eccentricity, "
           "--type, --names, --ids (or [selection] in the scenario; "
           "docs/guide/catalogues.md, 'A whole public catalogue')")  # fmt: skip


def available_memory_bytes() -> int | None:
    """Memory this process may still use [bytes]: the system's available memory, or less
    under a container's limit (cgroup v2); None where neither can be read."""
    found = []
    try:
        for line in Path("/proc/meminfo").read_text().splitlines():
            if line.startswith("MemAvailable:"):
                found.append(int(line.split()[1]) * 1024)
    except (OSError, ValueError, IndexError):
        pass
    try:
        limit = Path("/sys/fs/cgroup/memory.max").read_text().strip()
        used = int(Path("/sys/fs/cgroup/memory.current").read_text().strip())
        if limit != "max":
            found.append(int(limit) - used)
    except (OSError, ValueError):
        pass
    if not found and hasattr(os, "sysconf"):
        with contextlib.suppress(ValueError, OSError):
            found.append(os.sysconf("SC_AVPHYS_PAGES") * os.sysconf("SC_PAGE_SIZE"))
    return min(found) if found else None


def estimated_bytes(candidates: int, processes: int = 1) -> int:
    """Peak memory [bytes] of ``processes`` searches over ``candidates`` at once (and an
    injection orbit: one node more)."""
    nodes = candidates + 1
    return processes * (BASE_BYTES + BYTES_PER_PAIR * nodes * (nodes - 1))


def size_problem(candidates: int, processes: int = 1) -> str | None:
    """Why ``candidates`` (in ``processes`` searches at once) do not fit in this machine's
    memory, or None (also None when the available memory cannot be read)."""
    available = available_memory_bytes()
    need = estimated_bytes(candidates, processes)
    if available is None:
        return None
    usable = USABLE_FRACTION * available
    if need <= usable:
        return None
    pairs = candidates * (candidates - 1)
    at_once = f" in {processes} processes at once" if processes > 1 else ""
    return (f"{candidates:,} candidates are {pairs:,} ordered pairs, whose cost tables need "
            f"about {need / 1e9:.3g} GB{at_once}, more than the {usable / 1e9:.3g} GB a run "
            f"may use here ({USABLE_FRACTION:.0%} of the memory available): {FILTERS}")  # fmt: skip
