"""The paper case end to end against the bare import of CVXPY, pandas and SciPy.

Usage: python benchmarks/end_to_end.py [--repeat 5] [--out FILE]

Issue 21's goal: ``python -m sdc_cvx run`` on the bundled paper case (README's first
command, here with ``--out`` in a temporary folder) within twice the time a fresh
interpreter takes to ``import cvxpy, pandas, scipy``.  Both are timed in the same run, as
fresh subprocesses, alternately (so a change of the machine's load falls on both), after
one untimed pair that warms the disk cache; the medians of ``--repeat`` are printed with
their ratio (and the CPU time's, which a loaded machine disturbs less), after a header
naming the machine (CPU, cores, load, versions).

Then where the run's time goes, from three more runs:

- ``python -X importtime``: the modules the run imports beyond the bare import, by
  top-level package (their own import time, summed);
- the run once its modules are imported, with a clock around the functions of its
  phases: the search, its fixed-path schedules and relaxation MILPs, the pre-optimised
  edge table (``edges.csv``), the run folder and its figures.  (A profiler would slow
  matplotlib's Python more than the search's NumPy and misstate the shares.)

``benchmarks/results/end_to_end.txt`` is one such output (a shared 2-core machine).
"""

from __future__ import annotations

import argparse
import json
import os
import re
import resource
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
PHASES = (  # label, and the function timed, named where its caller looks it up
    ("search (planner.api.solve)", "sdc_cvx.planner.api", "solve"),
    ("  fixed-path schedules", "sdc_cvx.planner.certified.state", "solve_path"),
    ("edges.csv pre-optimisation", "sdc_cvx.network.edges", "preoptimize"),
    ("run folder (write_run)", "sdc_cvx.report.run_folder", "write_run"),
    ("  figures", "sdc_cvx.report.plots", "save_figures"),
)


def python(args: list[str], **kwargs) -> subprocess.CompletedProcess:
    """``args`` run by a fresh interpreter that imports this checkout's sdc_cvx."""
    env = {**os.environ, "PYTHONPATH": str(ROOT)}
    return subprocess.run([sys.executable, *args], env=env, cwd=ROOT, capture_output=True,
                          text=True, check=True, **kwargs)  # fmt: skip


def timed(args: list[str]) -> tuple[float, float]:
    """Wall-clock and CPU (user + system) seconds of ``python args``."""
    before, start = resource.getrusage(resource.RUSAGE_CHILDREN), time.perf_counter()
    python(args)
    wall, after = time.perf_counter() - start, resource.getrusage(resource.RUSAGE_CHILDREN)
    return wall, after.ru_utime - before.ru_utime + after.ru_stime - before.ru_stime


def medians(times: list[tuple[float, float]]) -> tuple[float, float]:
    """Median wall-clock and median CPU seconds."""
    return statistics.median(w for w, _ in times), statistics.median(c for _, c in times)


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


TIMERS = """
import importlib, json, sys, time

import sdc_cvx.cli

spent = {}


def timer(label, owner, name):
    inner = getattr(owner, name)

    def timed(*args, **kwargs):
        start = time.perf_counter()
        try:
            return inner(*args, **kwargs)
        finally:
            calls, seconds = spent.get(label, (0, 0.0))
            spent[label] = (calls + 1, seconds + time.perf_counter() - start)

    setattr(owner, name, timed)


for label, module, name in json.loads(sys.argv[2]):
    owner = importlib.import_module(module)  # imported here: the run's imports are not timed
    if hasattr(owner, name):
        timer(label, owner, name)
start = time.perf_counter()
try:
    sdc_cvx.cli.main(sys.argv[3:])
except SystemExit as stop:
    if stop.code:
        raise
spent["run"] = (1, time.perf_counter() - start)
with open(sys.argv[1], "w") as out:
    json.dump(spent, out)
"""
"""``python -c TIMERS OUT.json PHASES run ...``: the run with each phase's function wrapped
in a clock, where its caller looks it up."""


def phase_lines(folder: str) -> list[str]:
    """Wall-clock seconds of the run's phases, its modules imported first."""
    out = Path(folder, "phases.json")
    python(["-c", TIMERS, str(out), json.dumps(PHASES), *run_args(folder)[2:]])
    spent = json.loads(out.read_text())
    _, total = spent["run"]
    lines = [f"the run once its modules are imported: {total:.2f} s"]
    for label, module, name in PHASES:
        if label not in spent:
            lines.append(f"  {label:<30} (not timed: {module}.{name} not found)")
            continue
        calls, seconds = spent[label]
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
        (bare_s, bare_cpu), (run_s, run_cpu) = medians(bare), medians(run)
        say(f"bare import {bare_s:6.2f} s  python {' '.join(BARE)!r}, median of "
            f"{len(bare)}: {' '.join(f'{s:.2f}' for s, _ in bare)}")  # fmt: skip
        say(f"run         {run_s:6.2f} s  python {' '.join(RUN)} --out DIR, median of "
            f"{len(run)}: {' '.join(f'{s:.2f}' for s, _ in run)}")  # fmt: skip
        say(f"ratio       {run_s / bare_s:6.2f}    run / bare import (issue 21's goal: 2 or less)")
        say(f"cpu         {bare_cpu:.2f} s and {run_cpu:.2f} s (user + system, medians): ratio "
            f"{run_cpu / bare_cpu:.2f}, less sensitive to the machine's load")  # fmt: skip
        say("answer      " + " | ".join(s for s in summary if s.startswith(("total", "status"))))
        say(
            f"            {size['paths_certified']} paths certified (a fixed-path schedule "
            f"each), {size['milp_solves']} relaxation MILP(s), {size['date_cells']} date cells"
        )
        say()
        say("where the run's time goes:")
        for line in import_lines(folder) + phase_lines(folder):
            say(line)
    if options.out is not None:
        options.out.write_text("\n".join(lines) + "\n")


if __name__ == "__main__":
    main()
