"""Low-thrust against impulsive: the certified answer, its bound, gap, time and memory.

Issue 29's goal: at f = 1e-4 m/s^2 the low-thrust model certified within 0.1 % in at most
twice the impulsive model's time, on the paper case and on the 81 SSO rocket bodies
(n = 5, one year).  Each (case, model) runs in its own process (its peak memory is that
process's), the impulsive run first, so the two see the same machine; the ratio of their
times is printed.

    python benchmarks/low_thrust.py
    python benchmarks/low_thrust.py --accel 3e-5 1e-4 3e-4 --only paper
    python benchmarks/low_thrust.py --repeat 3       # the median of 3 runs per row
    python benchmarks/low_thrust.py --paper          # the paper's method too (its plan)

The machine it ran on is printed first: compare times within one run.
"""

from __future__ import annotations

import argparse
import multiprocessing as mp
import os
import platform
import statistics
import time
from pathlib import Path

SHARED = Path(__file__).resolve().parents[2] / "shared" / "data"
RB = SHARED / "sso_rocket_bodies_2020" / "sso_rb.tle"


def peak_mb() -> float:
    """Peak resident memory of this process [MB] (Linux: ru_maxrss is in kB)."""
    import resource

    return resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024


def load(case: str):
    from sdc_cvx import Catalog

    if case == "paper":
        return Catalog.paper_case()
    from sdc_cvx.inputs.formats import read_catalog
    from sdc_cvx.study.scenario import Selection

    catalog, _ = Selection().apply(read_catalog(str(RB), "tle"))  # as `run` selects
    return catalog


def run_case(case, accel, time_limit, queue, method="certified"):
    from sdc_cvx import Mission, MissionInfeasible, SolverOptions, solve

    catalog = load(case)
    transfer = {} if accel is None else dict(transfer="low-thrust",
                                             vehicle={"accel_mps2": accel})  # fmt: skip
    start = time.perf_counter()
    try:
        solution = solve(catalog, Mission(n=5, tmax_days=365.25, **transfer),
                         solver=SolverOptions(time_limit_s=time_limit, method=method))  # fmt: skip
    except MissionInfeasible:  # proven: no plan (the spirals alone outlast T_max)
        queue.put(dict(N=len(catalog), seconds=time.perf_counter() - start, peak_mb=peak_mb(),
                       status="infeasible"))  # fmt: skip
        return
    queue.put(dict(N=len(catalog), seconds=time.perf_counter() - start, peak_mb=peak_mb(),
                   answer=solution.total_dv_mps, lower=solution.lower_bound_mps,
                   gap_pct=None if solution.gap_rel is None else 100 * solution.gap_rel,
                   status=str(solution.status),
                   path="-".join(solution.path)))  # fmt: skip


def measure(case, accel, time_limit, repeat, method="certified"):
    runs = []
    for _ in range(repeat):
        queue = mp.get_context("spawn").Queue()
        proc = mp.get_context("spawn").Process(target=run_case,
                                               args=(case, accel, time_limit, queue,
                                                     method))  # fmt: skip
        proc.start()
        proc.join(time_limit * 2 + 60)
        if proc.is_alive():
            proc.kill()
            return dict(status="killed")
        if queue.empty():
            return dict(status="crashed")
        runs.append(queue.get())
    best = runs[0] | {"seconds": statistics.median(r["seconds"] for r in runs),
                      "peak_mb": max(r["peak_mb"] for r in runs)}  # fmt: skip
    return best


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--accel", type=float, nargs="*", default=[1e-4],
                        help="thrust accelerations [m/s^2]")  # fmt: skip
    parser.add_argument("--only", nargs="*", help="cases: paper, sso-rb")
    parser.add_argument("--time-limit", type=float, default=600.0, help="per run [s]")
    parser.add_argument("--repeat", type=int, default=1, help="runs per row (median time)")
    parser.add_argument("--paper", action="store_true",
                        help="also the paper's method (method = \"paper\", its default T0)")
    args = parser.parse_args(argv)
    load_avg = os.getloadavg()[0] if hasattr(os, "getloadavg") else float("nan")
    print(f"# {platform.processor() or platform.machine()}, {os.cpu_count()} cores, "
          f"load {load_avg:.1f}, Python {platform.python_version()}")  # fmt: skip
    print(f"{'case':<8} {'N':>3} {'model':<24} {'answer':>8} {'bound':>8} {'gap %':>6} "
          f"{'s':>6} {'x imp.':>6} {'MB':>5} {'status':<8} path")  # fmt: skip
    cases = [c for c in ("paper", "sso-rb") if not args.only or c in args.only]
    if not RB.is_file():
        cases = [c for c in cases if c != "sso-rb"]
    for case in cases:
        base = None
        runs = [(accel, "certified") for accel in [None, *args.accel]]
        if args.paper:
            runs += [(accel, "paper") for accel in [None, *args.accel]]
        for accel, method in runs:
            row = measure(case, accel, args.time_limit, args.repeat, method)
            model = "impulsive" if accel is None else f"low-thrust {accel:g}"
            model += " paper" if method == "paper" else ""
            if "seconds" not in row:
                print(f"{case:<8} {'-':>3} {model:<24} {row['status']}")
                continue
            base = row["seconds"] if accel is None else base
            ratio = row["seconds"] / base if base else float("nan")
            if "answer" not in row:  # proven infeasible
                print(f"{case:<8} {row['N']:>3} {model:<24} {'-':>8} {'-':>8} {'-':>6} "
                      f"{row['seconds']:>6.1f} {ratio:>6.2f} {row['peak_mb']:>5.0f} "
                      f"{row['status']:<8}", flush=True)  # fmt: skip
                continue
            lower = "-" if row["lower"] is None else f"{row['lower']:.2f}"
            gap = "-" if row["gap_pct"] is None else f"{row['gap_pct']:.3f}"
            print(f"{case:<8} {row['N']:>3} {model:<24} {row['answer']:>8.2f} "
                  f"{lower:>8} {gap:>6} {row['seconds']:>6.1f} "
                  f"{ratio:>6.2f} {row['peak_mb']:>5.0f} {row['status']:<8} {row['path']}",
                  flush=True)  # fmt: skip

if __name__ == "__main__":
    main()
