"""The README's example runs, timed, with the machine they ran on.

Usage: python benchmarks/readme_examples.py [--cases paper,sso_rb,gtoc9,gtoc9_paper,...]
                                            [--out FILE]

Runs each example as ``python -m sdc_cvx run ... --quiet --out <tmp>`` does (the same
scenario, one process) and prints its total ΔV, status and wall time, after a header
naming the machine (CPU model, cores, load average, Python, NumPy, CVXPY, HiGHS).  The
README quotes the times of ``benchmarks/results/readme_examples.txt``, this script's
output; rerun it to get the numbers of your machine (a busy machine is slower: the load
average is printed for that reason).
"""

from __future__ import annotations

import argparse
import importlib.metadata
import os
import platform
import sys
import tempfile
import time
from datetime import UTC, datetime
from pathlib import Path

from click.testing import CliRunner

from sdc_cvx.cli import main as cli

SHARED = Path(__file__).resolve().parents[2] / "shared" / "data"
CASES = {
    "paper": ("paper case (Table 5, n = 5)", []),
    "sso_rb": (
        "81 SSO rocket bodies, n = 5, --time-limit 30",
        [
            "--catalog",
            str(SHARED / "sso_rocket_bodies_2020" / "sso_rb.tle"),
            "--n",
            "5",
            "--time-limit",
            "30",
        ],
    ),  # fmt: skip
    "gtoc9": (
        "GTOC9's 123 debris, n = 5",
        ["--catalog", str(SHARED / "gtoc9" / "debris_data.txt"), "--n", "5"],
    ),
}
# the same runs with the paper's method, which the README compares (no bound)
CASES.update({
    f"{key}_paper": (f"{title}, --method paper", [*args, "--method", "paper"])
    for key, (title, args) in list(CASES.items())
})  # fmt: skip


def machine() -> list[str]:
    """Lines naming the machine, the load and the versions."""
    cpu = platform.processor() or "?"
    try:
        for line in Path("/proc/cpuinfo").read_text().splitlines():
            if line.startswith("model name"):
                cpu = line.split(":", 1)[1].strip()
                break
    except OSError:
        pass
    load = ", ".join(f"{x:.2f}" for x in os.getloadavg()) if hasattr(os, "getloadavg") else "?"
    versions = ", ".join(
        f"{name} {importlib.metadata.version(name)}"
        for name in ("numpy", "scipy", "cvxpy", "highspy")
    )
    return [
        f"date     {datetime.now(UTC).isoformat(timespec='seconds')}",
        f"machine  {platform.node()}: {cpu}, {os.cpu_count()} logical cores, "
        f"{platform.system()} {platform.release()}",
        f"load     {load} (1, 5, 15 min averages at the start)",
        f"python   {sys.version.split()[0]}; {versions}",
    ]


def run(args: list[str]) -> tuple[str, float]:
    with tempfile.TemporaryDirectory() as folder:
        start = time.perf_counter()
        result = CliRunner().invoke(cli, ["run", *args, "--quiet", "--out", f"{folder}/run"])
        seconds = time.perf_counter() - start
    lines = [line for line in result.stdout.splitlines() if line.startswith(("total", "status"))]
    return " | ".join(lines) or f"exit {result.exit_code}: {result.output.strip()}", seconds


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--cases", default=",".join(CASES))
    parser.add_argument("--out", type=Path, default=None, help="Also write the output here.")
    options = parser.parse_args()
    lines = machine() + [""]
    print("\n".join(lines), flush=True)
    for key in options.cases.split(","):
        title, args = CASES[key]
        answer, seconds = run(args)
        line = f"{key:<7} {seconds:7.1f} s  {title}: {answer}"
        print(line, flush=True)
        lines.append(line)
    if options.out is not None:
        options.out.write_text("\n".join(lines) + "\n")


if __name__ == "__main__":
    main()
