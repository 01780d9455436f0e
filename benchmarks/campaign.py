"""Removal campaigns on real catalogs: plan, bound, gap, greedy, columns, time, memory.

Issue 19's goals: GTOC9's 123 debris in 5 yearly missions of 5 (launch days 0, 365.25,
..., 1461) and the 81 SSO rocket bodies in 4 yearly missions of 5, each within a 1 %
gap in 20 minutes on a 2-core machine, on a local process pool and on a Dask
LocalCluster.  Prints, per case and executor: the campaign's ΔV, its proven lower
bound, the gap, the greedy campaign (one mission at a time) and its gap to the bound,
the missions priced into the master, the pricing problems, the seconds and the peak
memory (this process and its workers).

    python benchmarks/campaign.py                       # both cases, process pool
    python benchmarks/campaign.py --dask                # also on a Dask LocalCluster
    python benchmarks/campaign.py --only gtoc9 --time-limit 600

The machine it ran on is printed first: compare times within one run.
"""

from __future__ import annotations

import argparse
import os
import platform
import resource
import sys
import time
from pathlib import Path

SHARED = Path(__file__).resolve().parents[2] / "shared" / "data"
CASES = {
    "gtoc9": (SHARED / "gtoc9" / "debris_data.txt", 5, 5),
    "sso-rb": (SHARED / "sso_rocket_bodies_2020" / "sso_rb.tle", 4, 5),
}
"""name: (catalog, missions, debris per mission); yearly launches from day 0."""


def peak_mb() -> float:
    """Peak resident memory [MB] of this process and of its largest child (Linux: kB)."""
    own = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss
    children = resource.getrusage(resource.RUSAGE_CHILDREN).ru_maxrss
    return max(own, children) / 1e3


def run_case(name: str, time_limit: float, workers: int, scheduler=None) -> dict:
    import sdc_cvx
    from sdc_cvx.campaign.search import solve_campaign
    from sdc_cvx.inputs.campaign import Campaign
    from sdc_cvx.study.scenario import Scenario

    path, missions, n = CASES[name]
    scenario = Scenario().with_overrides(catalog=str(path))
    catalog, _ = scenario.selection.apply(scenario.load_catalog())
    campaign = Campaign.yearly(missions, sdc_cvx.Mission(n=n))
    clock = time.perf_counter()
    pool = {"workers": workers} if scheduler is None else {"scheduler": scheduler}
    solution = solve_campaign(catalog, campaign, time_limit_s=time_limit, **pool,
                              log=lambda line: print(f"    {time.perf_counter() - clock:7.1f} s"
                                                     f" {line}", flush=True))  # fmt: skip
    return dict(case=name, N=len(catalog), K=missions, n=n, plan=solution.total_dv_mps,
                bound=solution.lower_bound_mps, gap=solution.gap_rel, status=solution.status,
                greedy=solution.greedy.dv_mps, greedy_gap=solution.greedy_gap_rel(),
                columns=solution.columns, pricings=solution.pricings,
                seconds=time.perf_counter() - clock, peak_mb=peak_mb(),
                paths=[" ".join(m.path) for m in solution.missions])  # fmt: skip


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--only", nargs="*", choices=sorted(CASES), default=sorted(CASES))
    parser.add_argument("--time-limit", type=float, default=1200.0, help="per case [s]")
    parser.add_argument("--workers", type=int, default=2, help="local processes")
    parser.add_argument("--dask", action="store_true", help="also on a Dask LocalCluster")
    args = parser.parse_args()
    import numpy

    import sdc_cvx  # noqa: F401

    print(f"machine: {platform.machine()}, {os.cpu_count()} cores, load "
          f"{os.getloadavg()[0]:.2f}; Python {platform.python_version()}, numpy "
          f"{numpy.__version__}")  # fmt: skip
    executors = [("process pool", None)]
    cluster = None
    if args.dask:
        from distributed import Client, LocalCluster

        cluster = LocalCluster(n_workers=args.workers, threads_per_worker=1,
                               processes=True)  # fmt: skip
        executors.append(("dask LocalCluster", Client(cluster)))
    rows = []
    for name in args.only:
        if not CASES[name][0].is_file():
            print(f"{name}: {CASES[name][0]} not found, skipped")
            continue
        for label, scheduler in executors:
            print(f"{name} on {label}:", flush=True)
            row = run_case(name, args.time_limit, args.workers, scheduler)
            row["executor"] = label
            rows.append(row)
    print()
    print(f"{'case':8} {'executor':18} {'N':>4} {'K x n':>6} {'plan':>9} {'bound':>9} "
          f"{'gap':>7} {'status':>9} {'greedy':>9} {'greedy gap':>10} {'columns':>7} "
          f"{'pricings':>8} {'seconds':>8} {'peak MB':>8}")  # fmt: skip
    for r in rows:
        greedy = "-" if r["greedy"] is None else f"{r['greedy']:9.2f}"
        greedy_gap = "-" if r["greedy_gap"] is None else f"{100 * r['greedy_gap']:9.2f}%"
        bound = "-" if r["bound"] is None else f"{r['bound']:9.2f}"  # no bound proven yet
        gap = "-" if r["gap"] is None else f"{100 * r['gap']:6.3f}%"
        print(f"{r['case']:8} {r['executor']:18} {r['N']:4d} {r['K']:>2} x {r['n']:<2} "
              f"{r['plan']:9.2f} {bound:>9} {gap:>7} {r['status']:>9} "
              f"{greedy:>9} {greedy_gap:>10} {r['columns']:7d} {r['pricings']:8d} "
              f"{r['seconds']:8.1f} {r['peak_mb']:8.0f}")  # fmt: skip
    for r in rows:
        print(f"{r['case']} ({r['executor']}): " + " | ".join(r["paths"]))
    if cluster is not None:
        cluster.close()


if __name__ == "__main__":
    sys.exit(main())
