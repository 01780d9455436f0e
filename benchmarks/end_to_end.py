"""The paper case end to end against the bare import of CVXPY, pandas and SciPy.

Usage: python benchmarks/end_to_end.py [--repeat 5] [--out FILE]

Issue 21's goal: ``python -m sdc_cvx run`` on the bundled paper case (README's first
command, here with ``--out`` in a temporary folder) within twice the time a fresh
interpreter takes to ``import cvxpy, pandas, scipy``.  Both are timed in the same run, as
fresh subprocesses, alternately (so a change of the machine's load falls on both), after
one untimed pair that warms the disk cache; the medians of ``--repeat`` are printed with
their ratio, after a header naming the machine (CPU, cores, load, versions).

Then where the run's time goes, from two more runs:

- ``python -X importtime``: the modules the run imports beyond the bare import, by
  top-level package (their own import time, summed);
- cProfile, on the run's work once its modules are imported: the search, its
  fixed-path schedules and relaxation MILPs, the pre-optimised edge table
  (``edges.csv``), the run folder and its figures.  The profiler slows Python code more
  than compiled code: its seconds are longer than the run's, its shares are what
  carries over.

``benchmarks/results/end_to_end.txt`` is one such output (a shared 2-core machine).
"""

from __future__ import annotations

import argparse
import json
import os
import pstats
import re
import statistics
import subprocess
import sys
import tempfile
import time
from collections import Counter
from pathlib import Path

HERE = Path(__file__).resolve().parent
sys.path.insert(0, str(HERE))  # readme_examples.machine

from readme_examples import machine  # noqa: E402

ROOT = HERE.parent
BARE = ["-c", "import cvxpy, pandas, scipy"]
RUN = ["-m", "sdc_cvx", "run"]  # README's first command; --out is added
PHASES = (  # label, module file, function: cumulative time under cProfile
    ("search (planner.api.solve)", "planner/api.py", "solve"),
    ("  fixed-path schedules", "planner/fixed_path.py", "solve_path"),
    ("  relaxation MILPs", "planner/relaxation.py", "solve_relaxation"),
    ("edges.csv pre-optimisation", "network/edges.py", "preoptimize"),
    ("run folder", "report/run_folder.py", "write_run"),
    ("  figures", "report/plots.py", "save_figures"),
)


def python(args: list[str], **kwargs) -> subprocess.CompletedProcess:
    """``args`` run by a fresh interpreter that imports this checkout's sdc_cvx."""
    env = {**os.environ, "PYTHONPATH": str(ROOT)}
    return subprocess.run([sys.executable, *args], env=env, cwd=ROOT, capture_output=True,
                          text=True, check=True, **kwargs)  # fmt: skip


def timed(args: list[str]) -> float:
    """Wall-clock seconds of ``python args``."""
    start = time.perf_counter()
    python(args)
    return time.perf_counter() - start


def run_args(folder: str) -> list[str]:
    return [*RUN, "--out", f"{folder}/run"]


def imports(args: list[str]) -> dict[str, float]:
    """Own import time [s] of every module ``python -X importtime args`` imports."""
    table = {}
    for line in python(["-X", "importtime", *args]).stderr.splitlines():
        found = re.match(r"import time:\s+(\d+) \|\s+\d+ \|\s*(\S+)", line)
        if found:
            table[found[2]] = int(found[1]) * 1e-6
    return table


def import_lines(folder: str) -> list[str]:
    """The imports of the run beyond the bare import, by top-level package."""
    bare, run = imports(BARE), imports(run_args(folder))
    extra = Counter()
    for module, seconds in run.items():
        if module not in bare:
            extra[module.split(".")[0]] += seconds
    top = ", ".join(f"{name} {seconds:.2f}" for name, seconds in extra.most_common(6))
    return [
        f"imports (python -X importtime): the bare import {sum(bare.values()):.2f} s; the run "
        f"{sum(run.values()):.2f} s, of which {sum(extra.values()):.2f} s beyond the bare "
        f"import ({top})",
    ]


PROFILE = """
import cProfile, sys
import sdc_cvx.cli, sdc_cvx.network.edges, sdc_cvx.planner.api, sdc_cvx.report.plots
cProfile.run("sdc_cvx.cli.main(sys.argv[2:])", sys.argv[1])
"""
"""The run's work after its imports, under cProfile: ``python -c PROFILE STATS run ...``."""


def profile_lines(folder: str) -> list[str]:
    """Cumulative time of the run's phases, after its imports, under cProfile."""
    stats_file = f"{folder}/run.prof"
    python(["-c", PROFILE, stats_file, *run_args(folder)[2:]])
    stats = pstats.Stats(stats_file).stats  # (file, line, name) -> (cc, nc, tt, ct, callers)

    def cumulative(file: str, name: str) -> tuple[int, float]:
        found = [(entry[1], entry[3]) for (path, _, function), entry in stats.items()
                 if path.replace(os.sep, "/").endswith(file) and function == name]  # fmt: skip
        return sum(n for n, _ in found), sum(t for _, t in found)

    _, total = cumulative("sdc_cvx/cli.py", "run")
    lines = [f"the run after its imports, under cProfile: {total:.2f} s"]
    rows = [(label, *cumulative(file, name)) for label, file, name in PHASES]
    rows.append(("imports left to the run", *cumulative("<frozen importlib._bootstrap>",
                                                        "_find_and_load")))  # fmt: skip
    for label, calls, seconds in rows:
        lines.append(f"  {label:<30} {seconds:6.2f} s  {seconds / total:4.0%}  ({calls} calls)")
    return lines


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--repeat", type=int, default=5)
    parser.add_argument("--out", type=Path, default=None, help="Also write the output here.")
    options = parser.parse_args()
    lines = machine() + [""]
    print("\n".join(lines), flush=True)

    def say(line: str = "") -> None:
        print(line, flush=True)
        lines.append(line)

    bare, run = [], []
    with tempfile.TemporaryDirectory() as folder:
        timed(BARE)  # warm the disk cache: not counted
        timed(run_args(folder))
        for _ in range(options.repeat):
            bare.append(timed(BARE))
            run.append(timed(run_args(folder)))
        summary = python(run_args(folder)).stdout.splitlines()
        size = json.loads(Path(folder, "run", "solution.json").read_text())["model_size"]
        bare_s, run_s = statistics.median(bare), statistics.median(run)
        say(f"bare import {bare_s:6.2f} s  python {' '.join(BARE)!r}, median of "
            f"{len(bare)}: {' '.join(f'{s:.2f}' for s in bare)}")  # fmt: skip
        say(f"run         {run_s:6.2f} s  python {' '.join(RUN)} --out DIR, median of "
            f"{len(run)}: {' '.join(f'{s:.2f}' for s in run)}")  # fmt: skip
        say(f"ratio       {run_s / bare_s:6.2f}    run / bare import (issue 21's goal: 2 or less)")
        say("answer      " + " | ".join(s for s in summary if s.startswith(("total", "status"))))
        say(
            f"            {size['paths_certified']} paths certified (a fixed-path schedule "
            f"each), {size['milp_solves']} relaxation MILP(s), {size['date_cells']} date cells"
        )
        say()
        say("where the run's time goes:")
        for line in import_lines(folder) + profile_lines(folder):
            say(line)
    if options.out is not None:
        options.out.write_text("\n".join(lines) + "\n")


if __name__ == "__main__":
    main()
