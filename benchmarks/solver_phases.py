"""End-to-end solve time split by phase, for the paper case and synthetic SSO catalogs.

Usage: python benchmarks/solver_phases.py [--sizes 60 123] [--time-limit 60]

Phases: pre-optimisation, model build, first compile (CVXPY's part of the first
solve), per-iteration re-solve split into CVXPY's part and HiGHS's part (medians
over iterations after the first), nonlinear re-optimisation, total.  Goals (issue
3): paper case < 2 s end to end, re-solve CVXPY overhead < 10 ms, first compile at
N = 123 < 1 s.  Times vary on a shared machine: compare ratios within one run.
"""

import argparse
import statistics

from sdc_cvx import Catalog, Mission
from sdc_cvx.inputs.synthetic import sso_catalog
from sdc_cvx.milp.types import SolverOptions
from sdc_cvx.planner.paper import solve


def phases(catalog, solver, mission=None):
    """One solve's model size, iterations, seconds per phase and answer, as a flat dict."""
    sol = solve(catalog, mission or Mission(), solver=solver)
    later = sol.iterations[1:] or sol.iterations
    t = sol.timings
    return {
        "N": len(catalog),
        "edges": sol.model_size["edges_kept"],
        "copies": sol.model_size["edge_copies"],
        "dominated": sol.model_size["edges_dominated"],
        "binaries": sol.model_size["binaries"],
        "rows": sol.model_size["constraints"],
        "iters": len(sol.iterations),
        "preopt_s": t["preoptimize_s"],
        "build_s": t["build_s"],
        "seed_s": t.get("seed_s", 0.0),
        "1st_compile_s": t["first_solve_overhead_s"],
        "1st_highs_s": sol.iterations[0].solve_seconds,
        "resolve_cvxpy_ms": 1e3 * statistics.median(r.cvxpy_seconds for r in later),
        "resolve_highs_s": statistics.median(r.solve_seconds for r in later),
        "milp_s": sum(r.solve_seconds for r in sol.iterations),
        "cvxpy_s": sum(r.cvxpy_seconds for r in sol.iterations),
        "reopt_s": t.get("reoptimize_s", 0.0),
        "total_s": t["total_s"],
        "dv_mps": sol.total_dv_mps,
        "nodes": sum(r.nodes or 0 for r in sol.iterations),
        "time_limited": sum(r.status == "time_limit" for r in sol.iterations),
        "status": sol.status,
    }


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--sizes", type=int, nargs="*", default=[60, 123])
    parser.add_argument("--time-limit", type=float, default=60.0, help="per MILP solve [s]")
    args = parser.parse_args()
    solver = SolverOptions(time_limit_s=args.time_limit)
    cases = [("paper Table 5", Catalog.paper_case())]
    cases += [(f"synthetic N={n}", sso_catalog(n, seed=1)) for n in args.sizes]
    rows = []
    for name, catalog in cases:
        row = {"case": name, **phases(catalog, solver)}
        rows.append(row)
        cells = (f"{k}={v:.4g}" if isinstance(v, float) else f"{k}={v}" for k, v in row.items())
        print("  ".join(cells), flush=True)
    keys = list(rows[0])
    print("\n" + " | ".join(keys))
    for row in rows:
        print(
            " | ".join(f"{row[k]:.3g}" if isinstance(row[k], float) else str(row[k]) for k in keys)
        )


if __name__ == "__main__":
    main()
