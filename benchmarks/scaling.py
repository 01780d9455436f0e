"""Scaling from the paper's 11 debris to GTOC9's 123: model size, iterations, seconds, ΔV.

Usage: python benchmarks/scaling.py [--time-limit 30] [--cases paper gtoc9_30 ...]
       [--out runs/scaling]

Cases (issue 5): the paper's Table 5 (N = 11); the first 30 and 60 debris of a seeded
permutation of the GTOC9 set (as ``compare_backends.py``); the 81 sun-synchronous rocket
bodies of 2020 (``sso_rb.tle``, the CLI's default candidate selection); the whole GTOC9
set (N = 123).  Each is solved in this process with HiGHS, n = 5, T_max = 365.25 days
and ``--time-limit`` seconds per MILP.  Prints one row per case and writes
``scaling.csv`` and ``scaling.png`` (seconds per phase and model size against N) to
``--out``.  Columns: edges kept (pairs), edge copies (date windows), dominated copies at
the end, binaries, constraint rows, iterations, iterations stopped by the time limit,
B&B nodes (all iterations), seconds in pre-optimisation, model build, seed plans, MILP
backend, CVXPY, re-optimisation and in total, final ΔV.  The machine is shared: compare within
one run.
"""

import argparse
from pathlib import Path

import pandas as pd
from compare_backends import GTOC9, gtoc9_subset
from solver_phases import phases

from sdc_cvx import Catalog
from sdc_cvx.inputs.formats import read_catalog
from sdc_cvx.inputs.selection import select
from sdc_cvx.milp.types import SolverOptions

SSO_RB = GTOC9.parents[1] / "sso_rocket_bodies_2020" / "sso_rb.tle"
CASES = {
    "paper": lambda: Catalog.paper_case(),
    "gtoc9_30": lambda: gtoc9_subset(30, seed=0),
    "gtoc9_60": lambda: gtoc9_subset(60, seed=0),
    "sso_rb_81": lambda: select(read_catalog(SSO_RB, format="tle"))[0],
    "gtoc9_123": lambda: read_catalog(GTOC9, format="gtoc9"),
}
PHASES = ["preopt_s", "build_s", "seed_s", "milp_s", "cvxpy_s", "reopt_s"]


def plot(table: pd.DataFrame, path: Path):
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, (ax_time, ax_size) = plt.subplots(1, 2, figsize=(11, 4.2))
    labels = [f"{case}\nN={n}" for case, n in zip(table["case"], table["N"], strict=True)]
    bottom = pd.Series(0.0, index=table.index)
    for phase in PHASES:
        ax_time.bar(labels, table[phase], bottom=bottom, label=phase.removesuffix("_s"))
        bottom += table[phase]
    other = (table["total_s"] - bottom).clip(lower=0)
    ax_time.bar(labels, other, bottom=bottom, label="other", color="0.8")
    for x, (total, dv) in enumerate(zip(table["total_s"], table["dv_mps"], strict=True)):
        ax_time.annotate(f"{total:.0f} s\n{dv:.0f} m/s", (x, total), ha="center", va="bottom",
                         fontsize=8)  # fmt: skip
    ax_time.set(ylabel="seconds end to end", title="Seconds per phase (label: total, final ΔV)")
    ax_time.legend(fontsize=8)
    for column, marker in (("copies", "o-"), ("binaries", "s-"), ("rows", "^-")):
        ax_size.plot(table["N"], table[column], marker, label=column)
    ax_size.set(xlabel="debris in the catalog N", yscale="log", title="MILP size")
    ax_size.grid(True, which="both", alpha=0.3)
    ax_size.legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(path, dpi=120)
    plt.close(fig)


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--cases", nargs="*", choices=list(CASES), default=list(CASES))
    parser.add_argument("--time-limit", type=float, default=30.0, help="per MILP solve [s]")
    parser.add_argument("--out", type=Path, default=Path("runs/scaling"))
    args = parser.parse_args()
    solver = SolverOptions(time_limit_s=args.time_limit)
    rows = []
    for case in args.cases:
        row = {"case": case, **phases(CASES[case](), solver)}
        rows.append(row)
        print("  ".join(f"{k}={v:.4g}" if isinstance(v, float) else f"{k}={v}"
                        for k, v in row.items()), flush=True)  # fmt: skip
    table = pd.DataFrame(rows)
    args.out.mkdir(parents=True, exist_ok=True)
    table.to_csv(args.out / "scaling.csv", index=False, float_format="%.6g")
    plot(table, args.out / "scaling.png")
    print()
    print(table.to_string(index=False, float_format=lambda v: f"{v:.3g}"))
    print(f"\nwrote {args.out / 'scaling.csv'} and {args.out / 'scaling.png'}")


if __name__ == "__main__":
    main()
