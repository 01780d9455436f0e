"""Removal programmes (issue 27): missions, debris removed, value, ΔV, bound, gap, greedy,
seconds and peak memory, on a process pool and on a Dask LocalCluster of 1 and 2 workers.

The programmes are the example scenarios:

- ``sl16-all``: every SL-16 stage of the 71 deg cluster (18) in four yearly missions of
  four or five (``examples/campaign_sl16_all.toml``, min-dv, ``remove_all``);
- ``sl16-value``: the most McKnight value among those stages, two missions of two to
  four within 250 m/s each (``examples/campaign_sl16_value.toml``, max-value);
- ``top50``: the most McKnight value among the 50 statistically most concerning derelicts,
  three yearly missions of two to five within 1 km/s each (``examples/campaign_top50.toml``,
  max-value; the value bound and its gap are printed beside the ΔV's);
- ``gtoc9-all``: GTOC9's 123 debris in 25 missions of four or five, one every 117 days
  (``examples/campaign_gtoc9_all.toml``): run with ``--only gtoc9-all``, it is long.

Issue 27's goals on 2 cores: SL-16-all and top-50 certified within 0.1 % in 5 minutes,
GTOC9-all within 1 % in 30 minutes; 2 workers faster than 1.  Each (programme, executor)
runs in a process of its own (its peak memory, workers included, is that run's).

    python benchmarks/programmes.py                          # sl16-all, sl16-value; pool 1, 2
    python benchmarks/programmes.py --dask                   # also Dask LocalCluster 1, 2
    python benchmarks/programmes.py --only gtoc9-all --time-limit 1800 --workers 2

The machine it ran on is printed first: compare times within one run.
"""

from __future__ import annotations

import argparse
import multiprocessing as mp
import os
import platform
import resource
import time
from pathlib import Path

EXAMPLES = Path(__file__).resolve().parents[1] / "examples"
PROGRAMMES = {
    "sl16-all": EXAMPLES / "campaign_sl16_all.toml",
    "sl16-value": EXAMPLES / "campaign_sl16_value.toml",
    "top50": EXAMPLES / "campaign_top50.toml",
    "gtoc9-all": EXAMPLES / "campaign_gtoc9_all.toml",
}
DEFAULT = ("sl16-all", "sl16-value")


def peak_mb() -> float:
    """Peak resident memory [MB] of this process and of its largest child (Linux: kB)."""
    own = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss
    children = resource.getrusage(resource.RUSAGE_CHILDREN).ru_maxrss
    return max(own, children) / 1e3


def run_programme(name: str, time_limit: float, workers: int, dask: bool, queue) -> None:
    """Solve one programme as ``campaign`` would, and put its row on ``queue``."""
    from sdc_cvx.campaign.search import solve_campaign
    from sdc_cvx.errors import SdcError
    from sdc_cvx.study.scenario import Scenario

    scenario = Scenario.load(PROGRAMMES[name])
    catalog, _ = scenario.select_candidates()
    cluster = client = None
    where = {"workers": workers}
    if dask:
        from distributed import Client, LocalCluster

        cluster = LocalCluster(n_workers=workers, threads_per_worker=1, processes=True,
                               dashboard_address=None)  # fmt: skip
        client = Client(cluster)
        where = {"scheduler": client}
    clock = time.perf_counter()
    try:
        solution = solve_campaign(catalog, scenario.campaign, solver=scenario.solver,
                                  time_limit_s=time_limit, **where)  # fmt: skip
    except SdcError as err:  # no campaign (infeasible, or none found within the limit)
        queue.put(dict(programme=name, failed=f"{type(err).__name__}: {err}",
                       seconds=time.perf_counter() - clock, peak_mb=peak_mb()))  # fmt: skip
        return
    finally:
        if client is not None:
            client.close()
            cluster.close()
    seconds = time.perf_counter() - clock
    removed = sum(len(m.path) for m in solution.missions)
    queue.put(dict(programme=name, N=len(catalog), K=len(scenario.campaign), removed=removed,
                   value=solution.value, value_bound=solution.value_bound,
                   dv=solution.total_dv_mps,
                   bound=solution.lower_bound_mps, gap=solution.gap_rel,
                   status=str(solution.status), greedy=solution.greedy.dv_mps,
                   seconds=seconds, peak_mb=peak_mb(), notes=list(solution.notes)))  # fmt: skip


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--only", nargs="*", choices=sorted(PROGRAMMES), default=list(DEFAULT))
    parser.add_argument("--time-limit", type=float, default=600.0, help="per run [s]")
    parser.add_argument("--workers", type=int, nargs="*", default=[1, 2],
                        help="worker counts to compare")  # fmt: skip
    parser.add_argument("--dask", action="store_true", help="also on a Dask LocalCluster")
    args = parser.parse_args()
    import numpy

    print(f"machine: {platform.machine()}, {os.cpu_count()} cores, load "
          f"{os.getloadavg()[0]:.2f}; Python {platform.python_version()}, numpy "
          f"{numpy.__version__}; time limit {args.time_limit:g} s a run", flush=True)  # fmt: skip
    context = mp.get_context("spawn")
    executors = [(False, w) for w in args.workers] + [(True, w) for w in args.workers] * args.dask
    print(f"{'programme':11} {'executor':10} {'N':>4} {'K':>3} {'removed':>7} {'value':>8} "
          f"{'ΔV':>9} {'bound':>9} {'gap':>7} {'status':>9} {'greedy':>9} {'seconds':>8} "
          f"{'peak MB':>8} {'value bound':>12}", flush=True)  # fmt: skip
    for name in args.only:
        for dask, workers in executors:
            queue = context.Queue()
            process = context.Process(target=run_programme,
                                      args=(name, args.time_limit, workers, dask, queue))
            process.start()
            process.join()
            label = f"{'dask' if dask else 'pool'} x{workers}"
            if process.exitcode != 0:
                print(f"{name:11} {label:10} failed (exit {process.exitcode})", flush=True)
                continue
            r = queue.get()
            if "failed" in r:
                print(f"{name:11} {label:10} {r['failed']} ({r['seconds']:.1f} s, "
                      f"{r['peak_mb']:.0f} MB)", flush=True)  # fmt: skip
                continue
            value = "-" if r["value"] is None else f"{r['value']:8.0f}"
            bound = "-" if r["bound"] is None else f"{r['bound']:9.2f}"
            gap = "-" if r["gap"] is None else f"{100 * r['gap']:6.3f}%"
            greedy = "-" if r["greedy"] is None else f"{r['greedy']:9.2f}"
            most = r["value_bound"]
            most = "-" if most is None else (
                f"{most:.0f} ({100 * (1 - r['value'] / most):.2f}%)" if most > 0 else f"{most:g}")
            print(f"{name:11} {label:10} {r['N']:4d} {r['K']:3d} {r['removed']:7d} {value:>8} "
                  f"{r['dv']:9.2f} {bound:>9} {gap:>7} {r['status']:>9} {greedy:>9} "
                  f"{r['seconds']:8.1f} {r['peak_mb']:8.0f} {most:>12}", flush=True)  # fmt: skip
            for note in r["notes"]:  # why a search stopped where it did
                print(f"{'':11} note: {note}", flush=True)


if __name__ == "__main__":
    main()
