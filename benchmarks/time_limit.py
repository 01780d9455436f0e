"""What a time limit shorter than the certified search's setup gives (issue 28, 2.1).

The 481 debris fragments (TLE; 230 880 edges) through the command line, as a user runs
them, with time limits below and above the cost tables' time: exit code, status, plan,
bound and wall time of each, beside the certified optimum of README (26.05 m/s).

    python benchmarks/time_limit.py
    python benchmarks/time_limit.py --limits 8 12 20
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


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--limits", type=float, nargs="*", default=[8.0, 12.0, 20.0],
                        help="time limits [s]")  # fmt: skip
    args = parser.parse_args(argv)
    print(f"# {platform.machine()}, {os.cpu_count()} cores, load {os.getloadavg()[0]:.1f}, "
          f"Python {platform.python_version()}")  # fmt: skip
    print(f"{'limit s':>8} {'exit':>4} {'wall s':>7} {'status':<9} {'plan m/s':>9} "
          f"{'bound':>8}  path")  # fmt: skip
    for limit in args.limits:
        with tempfile.TemporaryDirectory() as tmp:
            started = time.perf_counter()
            command = [sys.executable, "-m", "sdc_cvx", "run", "--catalog", str(FRAGMENTS),
                       "--time-limit", f"{limit:g}", "--out", str(Path(tmp) / "out")]
            done = subprocess.run(command, capture_output=True, text=True)
            wall = time.perf_counter() - started
            file = Path(tmp) / "out" / "solution.json"
            if not file.is_file():
                print(f"{limit:>8g} {done.returncode:>4} {wall:>7.1f} no plan", flush=True)
                continue
            solution = json.loads(file.read_text())
            print(f"{limit:>8g} {done.returncode:>4} {wall:>7.1f} {solution['status']:<9} "
                  f"{solution['total_dv_mps']:>9.2f} {solution['lower_bound_mps']:>8.2f}  "
                  f"{'-'.join(solution['path'])}", flush=True)  # fmt: skip


if __name__ == "__main__":
    main()
