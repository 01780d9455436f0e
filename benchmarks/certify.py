"""Certified answers: bound, gap and time per case (issue 13's goals).

Prints, per case: N, n, T_max, the answer, its proven lower bound, the gap, the seconds,
the relaxation MILPs solved, the date cells at the end and the peak memory of the case's
process; for the reference cases (with their independently certified optimum and the
ratio to it), the paper case, the paper's catalog at other n and T_max, GTOC9 (N = 123,
n = 5) and the pykep sample of 499 TLE fragments (481 kept, as ``run`` keeps them).
Each case runs in its own process with a time limit (``--time-limit``), so one slow case
cannot hold the rest.

    python benchmarks/certify.py                       # every case, 120 s each
    python benchmarks/certify.py --only syn05 paper    # some cases
    python benchmarks/certify.py --csv benchmarks/results/certify.csv
    python benchmarks/certify.py --large --time-limit 600   # issue 21's goals

``--large`` runs the n = 7-10 goals instead: the reference cases lg7, lg8, lg8b beside
the exhaustive search's recorded time (``oracle s``), catalogs drawn as they were but
harder (N 14-16, RAANs over 60 degrees, T_max up to 730 days, the free inclination
rule), the 81 SSO rocket bodies with n = 7 and 8, GTOC9 with n = 8, and GTOC9 with
n = 10 over 730 days.

The machine it ran on is printed first: compare times within one run.
"""

from __future__ import annotations

import argparse
import json
import multiprocessing as mp
import os
import platform
import sys
import time
from pathlib import Path

SHARED = Path(__file__).resolve().parents[2] / "shared" / "data"
REFERENCE = SHARED / "reference_cases"


ORACLE_S = {"lg7": 58.0, "lg8": 160.0, "lg8b": 118.0}
"""The exhaustive search's wall time on these cases (reference_cases/README.md) [s]."""
RANDOM_LARGE = [  # (seed, N, n, RAAN span [deg], T_max [days], inclination rule)
    (9701, 14, 7, 60.0, 450.0, "table3"),
    (9702, 16, 8, 60.0, 450.0, "table3"),
    (9703, 14, 8, 40.0, 730.0, "table3"),
    (9704, 12, 8, 30.0, 450.0, "free"),
    (9705, 16, 7, 90.0, 600.0, "table3"),
    (9706, 15, 8, 50.0, 500.0, "table3"),
]
"""Catalogs drawn as the reference cases lg7-lg8b were (README of reference_cases), with
more debris, wider RAAN spreads and longer missions."""


def random_large(seed, count, span_deg):
    """A catalog drawn as reference cases lg7-lg8b: a, I, e, RAAN uniform, rounded."""
    import numpy as np
    import pandas as pd

    from sdc_cvx import Catalog

    rng = np.random.default_rng(seed)
    a = np.round(rng.uniform(6950.0, 7400.0, count), 1)
    inc = np.round(rng.uniform(97.6, 98.7, count), 2)
    e = np.round(rng.uniform(0.0, 5e-4, count), 5)
    raan = np.round(rng.uniform(0.0, span_deg, count) + rng.uniform(0.0, 360.0), 2) % 360.0
    frame = pd.DataFrame(dict(id=[f"R{seed}-{k}" for k in range(count)], a_km=a, e=e,
                              inc_deg=inc, raan_deg=raan))  # fmt: skip
    return Catalog.from_frame(frame, source=f"random seed {seed}")


def large_cases():
    """The n = 7-10 goals of issue 21 (see the module docstring)."""
    out = [case for case in cases() if case[0].startswith("lg")]
    for seed, count, n, span, tmax, rule in RANDOM_LARGE:
        out.append((f"r{seed}-N{count}-n{n}-{tmax:g}d-{rule}", ("random", (seed, count, span)),
                    dict(n=n, tmax_days=tmax, drift_inclination=rule), None))  # fmt: skip
    rb = SHARED / "sso_rocket_bodies_2020" / "sso_rb.tle"
    if rb.is_file():  # the 81 SSO rocket bodies, as `run` selects them
        for n in (7, 8):
            out.append((f"sso-rb-n{n}", ("tle", str(rb)), dict(n=n, tmax_days=365.25), None))
    gtoc9 = SHARED / "gtoc9" / "debris_data.txt"
    if gtoc9.is_file():
        out.append(("gtoc9-n8", ("gtoc9", str(gtoc9)), dict(n=8, tmax_days=365.25), None))
        out.append(("gtoc9-n10-730d", ("gtoc9", str(gtoc9)), dict(n=10, tmax_days=730.0),
                    None))  # fmt: skip
    return out


def cases():
    """(name, catalog loader spec, mission keywords, reference optimum or None)."""
    out = []
    if (REFERENCE / "optima.json").is_file():
        optima = json.loads((REFERENCE / "optima.json").read_text())
        for case, data in sorted(optima.items()):
            for rule in ("table3", "free"):
                if rule in data:
                    out.append((f"{case}-{rule}", ("csv", str(REFERENCE / data["catalog"])),
                                dict(n=data["n"], tmax_days=data["tmax_days"],
                                     drift_inclination=rule),
                                data[rule]["optimum_dv_mps"]))  # fmt: skip
    out.append(("paper", ("paper", None), dict(n=5, tmax_days=365.25), None))
    for n, tmax in ((4, 365.25), (6, 365.25), (5, 300.0), (5, 450.0)):
        out.append((f"paper-n{n}-{tmax:g}d", ("paper", None), dict(n=n, tmax_days=tmax), None))
    gtoc9 = SHARED / "gtoc9" / "debris_data.txt"
    if gtoc9.is_file():
        out.append(("gtoc9-123", ("gtoc9", str(gtoc9)), dict(n=5, tmax_days=365.25), None))
    tle = SHARED / "pykep_tle" / "tle.txt"
    if tle.is_file():  # fragment clouds; the candidates `run` keeps (481 of 499)
        out.append(("tle-fragments", ("tle", str(tle)), dict(n=5, tmax_days=365.25), None))
    return out


def peak_mb() -> float:
    """Peak resident memory of this process [MB] (Linux: ru_maxrss is in kB)."""
    import resource

    return resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024


def run_case(spec, mission_kw, time_limit, queue):
    from sdc_cvx import Catalog, Mission, MissionInfeasible, SolverOptions, solve

    kind, path = spec
    if kind == "paper":
        catalog = Catalog.paper_case()
    elif kind == "csv":
        catalog = Catalog.from_csv(path)
    elif kind == "random":
        catalog = random_large(*path)
    else:
        from sdc_cvx.inputs.formats import read_catalog
        from sdc_cvx.study.scenario import Selection

        catalog, _ = Selection().apply(read_catalog(path, kind))  # as `run` selects
    start = time.perf_counter()
    try:
        solution = solve(catalog, Mission(**mission_kw),
                         solver=SolverOptions(time_limit_s=time_limit))  # fmt: skip
    except MissionInfeasible:
        queue.put(dict(N=len(catalog), status="infeasible", seconds=time.perf_counter() - start,
                       peak_mb=peak_mb()))  # fmt: skip
        return
    queue.put(dict(
        N=len(catalog), peak_mb=peak_mb(), status=str(solution.status),
        answer=solution.total_dv_mps,
        lower=solution.lower_bound_mps, gap_mps=solution.gap_mps, gap_rel=solution.gap_rel,
        seconds=time.perf_counter() - start, milps=solution.model_size.get("milp_solves"),
        cells=solution.model_size.get("date_cells"), path="-".join(solution.path)))  # fmt: skip


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--time-limit", type=float, default=120.0, help="per case [s]")
    parser.add_argument("--only", nargs="*", help="case names (or prefixes) to run")
    parser.add_argument("--csv", help="also write the table here")
    parser.add_argument("--large", action="store_true", help="the n = 7-10 goals instead")
    args = parser.parse_args(argv)
    load = os.getloadavg()[0] if hasattr(os, "getloadavg") else float("nan")
    print(f"# {platform.processor() or platform.machine()}, {os.cpu_count()} cores, "
          f"load {load:.1f}, Python {platform.python_version()}, "
          f"time limit {args.time_limit:g} s per case")  # fmt: skip
    header = (f"{'case':<20} {'N':>4} {'n':>2} {'T_max':>7} {'answer':>9} {'bound':>9} "
              f"{'gap m/s':>8} {'gap %':>6} {'s':>6} {'MILPs':>5} {'cells':>5} "
              f"{'status':<10} {'/opt':>7} {'MB':>5} {'oracle s':>8}")  # fmt: skip
    print(header)
    rows = []
    for name, spec, mission_kw, optimum in large_cases() if args.large else cases():
        if args.only and not any(name.startswith(k) for k in args.only):
            continue
        queue = mp.get_context("spawn").Queue()
        proc = mp.get_context("spawn").Process(
            target=run_case, args=(spec, mission_kw, args.time_limit, queue)
        )
        proc.start()
        proc.join(args.time_limit * 2 + 60)
        if proc.is_alive():
            proc.kill()
            result = dict(status="killed")
        else:
            result = queue.get() if not queue.empty() else dict(status="crashed")
        ratio = (result.get("answer", float("nan")) / optimum) if optimum else float("nan")
        row = dict(case=name, n=mission_kw["n"], tmax_days=mission_kw["tmax_days"],
                   optimum=optimum, ratio=ratio, **result)  # fmt: skip
        if isinstance(row.get("gap_rel"), float):
            row["gap_pct"] = 100 * row["gap_rel"]
        rows.append(row)

        def num(key, fmt, row=row):
            value = row.get(key)
            return format(value, fmt) if isinstance(value, int | float) else "-"

        print(f"{name:<20} {num('N', '4d'):>4} {row['n']:>2} {row['tmax_days']:>7g} "
              f"{num('answer', '9.2f'):>9} {num('lower', '9.2f'):>9} {num('gap_mps', '8.2f'):>8} "
              f"{num('gap_pct', '6.3f'):>6} "
              f"{num('seconds', '6.1f'):>6} {num('milps', '5d'):>5} {num('cells', '5d'):>5} "
              f"{row['status']:<10} {num('ratio', '7.4f'):>7} {num('peak_mb', '5.0f'):>5} "
              f"{ORACLE_S.get(name.split('-')[0], float('nan')):>8g}", flush=True)  # fmt: skip
    if args.csv:
        import pandas as pd

        pd.DataFrame(rows).to_csv(args.csv, index=False, float_format="%.6g")
        print(f"# written {args.csv}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
