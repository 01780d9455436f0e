"""Peak memory of a certified run against the number of candidates (issue 28, 2.1).

The cost tables and the certified search's network grow with the ordered pairs of
candidates, N (N - 1).  Each N runs in its own process (its peak resident memory is
that process's), on the first N of the 481 debris fragments (TLE), n = 3, one year, a
time limit of 60 s; the fit of peak memory against the pairs gives the bytes per pair
that :mod:`sdc_cvx.planner.size_guard` uses to refuse a catalogue too large for the
machine before building anything.

    python benchmarks/memory.py
    python benchmarks/memory.py --sizes 100 200 400
"""

from __future__ import annotations

import argparse
import multiprocessing as mp
import platform
import resource
import time
from pathlib import Path

import numpy as np

SHARED = Path(__file__).resolve().parents[2] / "shared" / "data"
FRAGMENTS = SHARED / "pykep_tle" / "tle.txt"


def run(size: int, queue) -> None:
    from sdc_cvx import Mission, SolverOptions, solve
    from sdc_cvx.inputs.formats import read_catalog
    from sdc_cvx.study.scenario import Selection

    catalog, _ = Selection().apply(read_catalog(str(FRAGMENTS), "tle"))
    catalog = catalog.subset(list(catalog.ids[:size]))
    start = time.perf_counter()
    solution = solve(catalog, Mission(n=3), solver=SolverOptions(time_limit_s=60.0))
    peak = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss * 1024
    queue.put((len(catalog), peak, time.perf_counter() - start, str(solution.status)))


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--sizes", type=int, nargs="+", default=[60, 120, 240, 481])
    args = parser.parse_args()
    print(f"# {platform.machine()}, Python {platform.python_version()}")
    print(f"{'N':>5} {'pairs':>9} {'peak MB':>8} {'s':>6} status")
    rows = []
    for size in args.sizes:
        queue = mp.get_context("spawn").Queue()
        proc = mp.get_context("spawn").Process(target=run, args=(size, queue))
        proc.start()
        proc.join()
        n, peak, seconds, status = queue.get()
        rows.append((n * (n - 1), peak))
        print(f"{n:5d} {n * (n - 1):9d} {peak / 2**20:8.0f} {seconds:6.1f} {status}")
    pairs, peak = np.array(rows, dtype=float).T
    slope, base = np.polyfit(pairs, peak, 1)
    print(f"fit: peak = {base / 2**20:.0f} MB + {slope:.0f} bytes per ordered pair")


if __name__ == "__main__":
    main()
