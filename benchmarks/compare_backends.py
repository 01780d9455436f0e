"""Every installed MILP backend on the paper case and GTOC9-derived catalogs, end to end.

Usage: python benchmarks/compare_backends.py [--backends HIGHS SCIP ...] [--sizes 20 40]
       [--large] [--source gtoc9|synthetic] [--time-limit 30] [--timeout 600] [--out DIR]
       [--no-modelling]

Each (backend, case) runs in its own subprocess, ``python -m sdc_cvx run --backend NAME
--quiet --json --time-limit T [--catalog FILE]``, so a backend that crashes or hangs
cannot take the others with it and every run pays the same start-up.  The catalogs of
N debris are the first N of a seeded permutation of the GTOC9 set
(``../shared/data/gtoc9/debris_data.txt``, RAANs at its latest epoch), so each size
contains the smaller ones; ``--source synthetic`` uses
``sdc_cvx.inputs.synthetic.sso_catalog(N, seed)`` instead.  Each is written to a temporary CSV
(20 and 40 debris; ``--large`` adds 80 and 123, the whole GTOC9 set).  Writes
``compare_backends.csv`` (backend, case, N, seconds end to end, total nodes, iterations,
final dV, path, status, ...) and ``compare_backends.png`` to ``--out``, and prints a
table with whether every backend found the same path and dV (within 0.1 %) as the
reference (HiGHS when it succeeded).

Then the modelling layer's cost: the final MILP of the HiGHS run (paper case and the
first catalog size), solved by HiGHS through CVXPY (``solve_milp``: a re-solve with
the canonicalisation cached, as the driver does; and a cold first solve of a fresh
Problem) versus by ``highspy`` directly on the same model exported to MPS
(``write_model_file``; ``Highs.readModel``; ``run``), printed as ratios.  Times vary on
a shared machine: compare within one run.
"""

from __future__ import annotations

import argparse
import csv
import json
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path

import cvxpy as cp
import numpy as np

from sdc_cvx.inputs.catalog import Catalog
from sdc_cvx.inputs.formats import read_catalog
from sdc_cvx.inputs.mission import Mission
from sdc_cvx.inputs.synthetic import sso_catalog
from sdc_cvx.milp import solve as milp_solve
from sdc_cvx.milp.backends import installed_backends
from sdc_cvx.milp.solve import solve_milp
from sdc_cvx.milp.types import SolverOptions
from sdc_cvx.planner import paper
from sdc_cvx.planner.paper import driver

GTOC9 = Path(__file__).resolve().parents[2] / "shared" / "data" / "gtoc9" / "debris_data.txt"

DV_AGREEMENT = 1e-3  # relative
COLUMNS = ["backend", "case", "N", "seconds", "nodes", "iterations", "dv_mps", "path", "status",
           "milp_seconds", "cvxpy_seconds", "exit_code", "agrees"]  # fmt: skip


# --------------------------------------------------------------------------- cases
def write_catalog(catalog: Catalog, path: Path) -> Path:
    columns = ["id", "a_km", "e", "inc_deg", "raan_deg"]
    catalog.frame[columns].to_csv(path, index=False, float_format="%.12g")
    return path


def gtoc9_subset(n: int, seed: int) -> Catalog:
    """The first ``n`` debris of a seeded permutation of the GTOC9 catalog."""
    catalog = read_catalog(GTOC9, format="gtoc9")
    order = np.random.default_rng(seed).permutation(len(catalog))[:n]
    return catalog.subset([catalog.ids[k] for k in order]) if n < len(catalog) else catalog


def make_cases(sizes, seed, folder: Path, source="gtoc9"):
    """(case name, N, catalog CSV or None for the paper case, Catalog)."""
    paper = Catalog.paper_case()
    cases = [("paper", len(paper), None, paper)]
    for n in sizes:
        if source == "gtoc9":
            catalog, name = gtoc9_subset(n, seed), f"gtoc9_{n}"
        else:
            catalog, name = sso_catalog(n, seed=seed), f"sso{n}"
        cases.append((name, n, write_catalog(catalog, folder / f"{name}.csv"), catalog))
    return cases


# --------------------------------------------------------------------------- one run
def run_one(backend, case, n, catalog_csv, time_limit, timeout, folder: Path) -> dict:
    command = [sys.executable, "-m", "sdc_cvx", "run", "--backend", backend, "--quiet",
               "--json", "--time-limit", str(time_limit),
               "--out", str(folder / f"run_{case}_{backend}")]  # fmt: skip
    if catalog_csv is not None:
        command += ["--catalog", str(catalog_csv)]
    row = {"backend": backend, "case": case, "N": n}
    start = time.perf_counter()
    try:
        done = subprocess.run(command, capture_output=True, text=True, timeout=timeout)
    except subprocess.TimeoutExpired:
        return {**row, "seconds": time.perf_counter() - start, "status": f"timeout {timeout:g} s"}
    row["seconds"] = time.perf_counter() - start
    row["exit_code"] = done.returncode
    if done.returncode != 0:
        last = (done.stderr.strip().splitlines() or ["(no message)"])[-1]
        return {**row, "status": f"exit {done.returncode}: {last[:160]}"}
    solution = json.loads(done.stdout)
    iterations = solution["iterations"]
    nodes = [record["nodes"] for record in iterations]
    return {
        **row,
        "nodes": None if any(k is None for k in nodes) else sum(nodes),
        "iterations": len(iterations),
        "dv_mps": solution["total_dv_mps"],
        "path": "->".join(solution["path"]),
        "status": solution["status"],
        "milp_seconds": sum(record["solve_seconds"] for record in iterations),
        "cvxpy_seconds": sum(record["cvxpy_seconds"] for record in iterations),
    }


def mark_agreement(rows):
    """Per case: does each run have the reference's path and dV (within 0.1 %)?"""
    verdicts = {}
    for case in dict.fromkeys(row["case"] for row in rows):
        runs = [row for row in rows if row["case"] == case]
        solved = [row for row in runs if row.get("dv_mps") is not None]
        if not solved:
            verdicts[case] = "no backend solved it"
            continue
        ref = next((row for row in solved if row["backend"] == "HIGHS"), solved[0])
        for row in runs:
            if row.get("dv_mps") is None:
                row["agrees"] = "-"
                continue
            same_dv = abs(row["dv_mps"] - ref["dv_mps"]) <= DV_AGREEMENT * abs(ref["dv_mps"])
            same_path = row["path"] == ref["path"]
            verdict = {(True, True): "yes", (True, False): "dV only", (False, True): "path only"}
            row["agrees"] = verdict.get((same_dv, same_path), "no")
        all_agree = all(row.get("agrees") == "yes" for row in runs)
        verdicts[case] = (
            f"all {len(runs)} backends agree on path and dV (reference {ref['backend']})"
            if all_agree
            else "backends DISAGREE or failed: "
            + ", ".join(
                f"{r['backend']}={r.get('agrees')}" for r in runs if r.get("agrees") != "yes"
            )
        )
    return verdicts


# --------------------------------------------------------------------------- output
def fmt(value, spec=""):
    if value is None or value == "":
        return "-"
    return format(value, spec) if spec else str(value)


def print_table(rows, verdicts):
    header = ["case", "N", "backend", "seconds", "MILP s", "nodes", "iters", "dV [m/s]",
              "agrees", "status", "path"]  # fmt: skip
    lines = [header]
    for row in rows:
        lines.append([
            row["case"], str(row["N"]), row["backend"], fmt(row.get("seconds"), ".2f"),
            fmt(row.get("milp_seconds"), ".2f"), fmt(row.get("nodes")),
            fmt(row.get("iterations")), fmt(row.get("dv_mps"), ".3f"), fmt(row.get("agrees")),
            fmt(row.get("status")), fmt(row.get("path")),
        ])  # fmt: skip
    widths = [max(len(line[k]) for line in lines) for k in range(len(header))]
    for k, line in enumerate(lines):
        print("  ".join(cell.ljust(w) for cell, w in zip(line, widths, strict=True)).rstrip())
        if k == 0:
            print("  ".join("-" * w for w in widths))
    print()
    for case, verdict in verdicts.items():
        print(f"{case}: {verdict}")


def write_csv(rows, path: Path):
    with path.open("w", newline="") as stream:
        writer = csv.DictWriter(stream, fieldnames=COLUMNS, extrasaction="ignore")
        writer.writeheader()
        for row in rows:
            writer.writerow({key: row.get(key, "") for key in COLUMNS})


def plot(rows, path: Path):
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, (ax_time, ax_nodes) = plt.subplots(1, 2, figsize=(11, 4.2))
    for backend in dict.fromkeys(row["backend"] for row in rows):
        runs = sorted((r for r in rows if r["backend"] == backend), key=lambda r: r["N"])
        ok = [r for r in runs if r.get("dv_mps") is not None]
        ax_time.plot([r["N"] for r in ok], [r["seconds"] for r in ok], "o-", label=backend)
        color = ax_time.lines[-1].get_color()
        stopped = [r for r in ok if r.get("status") not in ("converged", "converged_unconfirmed")]
        if stopped:  # a plan, but the iterations stopped at a limit
            ax_time.plot([r["N"] for r in stopped], [r["seconds"] for r in stopped], "o",
                         markersize=11, markerfacecolor="none", color=color)  # fmt: skip
        failed = [r for r in runs if r.get("dv_mps") is None]
        if failed:
            ax_time.plot([r["N"] for r in failed], [r["seconds"] for r in failed], "x",
                         color=color)  # fmt: skip
        with_nodes = [r for r in ok if r.get("nodes") is not None]
        if with_nodes:
            ax_nodes.plot([r["N"] for r in with_nodes], [max(r["nodes"], 1) for r in with_nodes],
                          "o-", label=backend)  # fmt: skip
    ax_time.set(
        xlabel="debris in the catalog N",
        ylabel="end-to-end seconds (subprocess)",
        yscale="log",
        title="Per backend (ringed: stopped at a limit, x: failed)",
    )
    ax_nodes.set(xlabel="debris in the catalog N", ylabel="B&B nodes, all iterations",
                 yscale="log", title="Nodes (backends that report them)")  # fmt: skip
    for ax in (ax_time, ax_nodes):
        ax.grid(True, which="both", alpha=0.3)
        ax.legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(path, dpi=120)
    plt.close(fig)


# --------------------------------------------------------------------------- modelling layer
def final_milp(catalog: Catalog, time_limit: float):
    """Run the driver with HiGHS in-process and keep its last MILP (parameter values)."""
    captured = {}
    real = driver.solve_with_fallback

    def spy(problem, chain, **kwargs):
        captured["problem"] = problem
        captured["values"] = [(p, None if p.value is None else p.value.copy())
                              for p in problem.parameters()]  # fmt: skip
        return real(problem, chain, **kwargs)

    driver.solve_with_fallback = spy
    try:
        paper.solve(catalog, Mission(), solver=SolverOptions(time_limit_s=time_limit))
    finally:
        driver.solve_with_fallback = real
    for parameter, value in captured["values"]:
        parameter.value = value
    return captured["problem"]


def modelling_cost(name: str, problem: cp.Problem, folder: Path, repeats=5) -> dict:
    import highspy

    options = SolverOptions()
    warm = []
    for _ in range(repeats):
        start = time.perf_counter()
        report = solve_milp(problem, options)
        warm.append((time.perf_counter() - start, report.solve_seconds, report.objective))
    fresh = cp.Problem(problem.objective, problem.constraints)
    start = time.perf_counter()
    cold_report = solve_milp(fresh, options)
    cold = time.perf_counter() - start

    mps = folder / f"final_{name}.mps"
    problem.solve(solver="HIGHS", mip_rel_gap=options.mip_gap, write_model_file=str(mps))
    direct = []
    for _ in range(repeats):
        highs = highspy.Highs()
        highs.setOptionValue("output_flag", False)
        highs.setOptionValue("mip_rel_gap", options.mip_gap)
        start = time.perf_counter()
        highs.readModel(str(mps))
        read = time.perf_counter() - start
        start = time.perf_counter()
        highs.run()
        direct.append((read, time.perf_counter() - start, highs.getInfo().objective_function_value))
    cvxpy_wall = statistics.median(w for w, _, _ in warm)
    highs_inside = statistics.median(s for _, s, _ in warm)
    direct_run = statistics.median(r for _, r, _ in direct)
    direct_read = statistics.median(r for r, _, _ in direct)
    size = sum(v.size for v in problem.variables()), sum(c.size for c in problem.constraints)
    return {
        "case": name,
        "columns": size[0],
        "rows": size[1],
        "cvxpy_resolve_s": cvxpy_wall,
        "highs_in_cvxpy_s": highs_inside,
        "cvxpy_cold_s": cold,
        "highspy_read_s": direct_read,
        "highspy_run_s": direct_run,
        "ratio_resolve": cvxpy_wall / direct_run,
        "ratio_cold": cold / (direct_read + direct_run),
        "objective_cvxpy": warm[-1][2],
        "objective_cold": cold_report.objective,
        "objective_highspy_plus_constant": direct[-1][2] + _constant(problem),
    }


def _constant(problem: cp.Problem) -> float:
    """The objective constant CVXPY keeps out of the exported model."""
    _, _, inverse = problem.get_problem_data("HIGHS")
    return milp_solve._offset(inverse)


def print_modelling(results):
    print("\nModelling layer: the final MILP by HiGHS through CVXPY vs highspy on its MPS export")
    print("(median of 5; 're-solve' = canonicalisation cached as in the driver's iterations;")
    print(" 'cold' = a fresh Problem compiled from scratch vs readModel + run)")
    for r in results:
        print(
            f"  {r['case']}: {r['columns']} columns x {r['rows']} rows | CVXPY re-solve "
            f"{1e3 * r['cvxpy_resolve_s']:.1f} ms (HiGHS inside {1e3 * r['highs_in_cvxpy_s']:.1f}"
            f" ms) vs highspy run {1e3 * r['highspy_run_s']:.1f} ms: ratio "
            f"{r['ratio_resolve']:.2f} | cold {1e3 * r['cvxpy_cold_s']:.1f} ms vs read+run "
            f"{1e3 * (r['highspy_read_s'] + r['highspy_run_s']):.1f} ms: ratio "
            f"{r['ratio_cold']:.2f} | objective {r['objective_cvxpy']:.6f} / "
            f"{r['objective_highspy_plus_constant']:.6f}"
        )


# --------------------------------------------------------------------------- main
def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--backends", nargs="*", default=None, help="[every installed one]")
    parser.add_argument("--sizes", type=int, nargs="*", default=[20, 40])
    parser.add_argument("--large", action="store_true", help="also N = 80 and 123")
    parser.add_argument("--source", choices=["gtoc9", "synthetic"], default="gtoc9",
                        help="GTOC9 subsets or synthetic SSO catalogs")  # fmt: skip
    parser.add_argument("--seed", type=int, default=0, help="of the subsets / synthetic sets")
    parser.add_argument("--time-limit", type=float, default=30.0, help="per MILP solve [s]")
    parser.add_argument("--timeout", type=float, default=600.0, help="per subprocess [s]")
    parser.add_argument("--out", type=Path, default=Path("runs/compare_backends"))
    parser.add_argument("--no-modelling", action="store_true",
                        help="skip the CVXPY-vs-highspy comparison")  # fmt: skip
    args = parser.parse_args(argv)
    names = [b.upper() for b in args.backends] if args.backends else installed_backends()
    missing = [b for b in names if b not in installed_backends()]
    if missing:
        print(f"not installed, skipped: {', '.join(missing)}", file=sys.stderr)
    names = [b for b in names if b not in missing]
    sizes = list(args.sizes) + ([80, 123] if args.large else [])
    args.out.mkdir(parents=True, exist_ok=True)
    rows = []
    with tempfile.TemporaryDirectory(prefix="compare_backends_") as tmp:
        folder = Path(tmp)
        cases = make_cases(sizes, args.seed, folder, args.source)
        for case, n, csv_path, _ in cases:
            for name in names:
                row = run_one(name, case, n, csv_path, args.time_limit, args.timeout, folder)
                rows.append(row)
                print(f"  {case:>6} {name:<8} {row['seconds']:7.2f} s  {row.get('status')}",
                      file=sys.stderr, flush=True)  # fmt: skip
        verdicts = mark_agreement(rows)
        print()
        print_table(rows, verdicts)
        write_csv(rows, args.out / "compare_backends.csv")
        plot(rows, args.out / "compare_backends.png")
        print(
            f"\nwrote {args.out / 'compare_backends.csv'} and {args.out / 'compare_backends.png'}"
        )
        if not args.no_modelling and "HIGHS" in installed_backends():
            results = []
            for case, _, _, catalog in cases[: min(2, len(cases))]:
                problem = final_milp(catalog, args.time_limit)
                results.append(modelling_cost(case, problem, folder))
            print_modelling(results)


if __name__ == "__main__":
    main()
