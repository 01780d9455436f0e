"""What a time limit gives, and how long the command then takes (issue 28, 2.1 and 2.2).

The 481 debris fragments (TLE; 230 880 edges) through the command line, as a user runs
them, with time limits below and above the cost tables' time: exit code, status, plan,
bound and wall time of each, beside the certified optimum of README (26.05 m/s).  With
``--campaign``, the GTOC9 campaign of examples/campaign_gtoc9.toml (five yearly missions
of five) under the same limits; with ``--ranges``, GTOC9 in three yearly missions of
``n = [[2, 10]]`` (27 pricings of the launches alone: ``--time-limit 60`` took 121 s
before issue 48, item 12).  ``--time-limit`` covers the whole command: the wall time is
the limit plus Python's start (about a second) and what the estimates missed.

    python benchmarks/time_limit.py
    python benchmarks/time_limit.py --limits 8 12 20
    python benchmarks/time_limit.py --campaign --limits 15 30
    python benchmarks/time_limit.py --ranges --limits 30 60
"""

from __future__ import annotations

import argparse
import json
import os
import platform
import subprocess
import sys
import tempfile
import time
from pathlib import Path

SHARED = Path(__file__).resolve().parents[2] / "shared" / "data"
FRAGMENTS = SHARED / "pykep_tle" / "tle.txt"
CAMPAIGN = Path(__file__).resolve().parents[1] / "examples" / "campaign_gtoc9.toml"
RANGES = f"""[catalog]
path = "{SHARED / "gtoc9" / "debris_data.txt"}"

[mission]
tmax_days = 365.25

[campaign]
missions = 3
period_days = 365.25
n = [[2, 10]]
"""
"""The campaign of issue 48, item 12 (written to a temporary folder for each run)."""


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--limits", type=float, nargs="*", default=[8.0, 12.0, 20.0],
                        help="time limits [s]")  # fmt: skip
    parser.add_argument("--campaign", action="store_true",
                        help="the GTOC9 campaign (examples/campaign_gtoc9.toml) instead")
    parser.add_argument("--ranges", action="store_true",
                        help="GTOC9 in three missions of n = [[2, 10]] instead")
    args = parser.parse_args(argv)
    print(f"# {platform.machine()}, {os.cpu_count()} cores, load {os.getloadavg()[0]:.1f}, "
          f"Python {platform.python_version()}")  # fmt: skip
    print(f"{'limit s':>8} {'exit':>4} {'wall s':>7} {'status':<9} {'plan m/s':>9} "
          f"{'bound':>8}  path")  # fmt: skip
    for limit in args.limits:
        with tempfile.TemporaryDirectory() as tmp:
            started = time.perf_counter()
            out = str(Path(tmp) / "out")
            scenario = CAMPAIGN
            if args.ranges:
                scenario = Path(tmp) / "gtoc9_ranges.toml"
                scenario.write_text(RANGES)
            campaign = args.campaign or args.ranges
            command = ([sys.executable, "-m", "sdc_cvx", "campaign", str(scenario)] if campaign
                       else [sys.executable, "-m", "sdc_cvx", "run", "--catalog", str(FRAGMENTS)])
            command += ["--time-limit", f"{limit:g}", "--out", out]
            done = subprocess.run(command, capture_output=True, text=True)
            wall = time.perf_counter() - started
            file = Path(out) / ("campaign.json" if campaign else "solution.json")
            if not file.is_file():
                print(f"{limit:>8g} {done.returncode:>4} {wall:>7.1f} no plan", flush=True)
                continue
            solution = json.loads(file.read_text())
            bound = solution["lower_bound_mps"]
            path = (" ".join("-".join(m["path"]) for m in solution["missions"]) if campaign
                    else "-".join(solution["path"]))
            print(f"{limit:>8g} {done.returncode:>4} {wall:>7.1f} {solution['status']:<9} "
                  f"{solution['total_dv_mps']:>9.2f} "
                  f"{'-' if bound is None else f'{bound:.2f}':>8}  {path}", flush=True)  # fmt: skip


if __name__ == "__main__":
    main()
