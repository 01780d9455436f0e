"""Low-thrust certified answers against the independent brute force, on random catalogs.

For each of ``--cases`` random catalogs (N 6-8 debris of the kinds the package is judged
on: SSO-like, one inclination cluster, or mixed; n 3-4; accelerations 3e-5, 1e-4 and
3e-4 m/s^2; both inclination rules; T_max 300-500 days), the optimum of
``tests/planner/low_thrust_bruteforce.py`` (the leg written again from issue 29's
statement, nothing of sdc_cvx imported) beside sdc_cvx's certified answer: the ratio of the
answers, whether the bound stays at or under the brute force, and the seconds of each.

    python benchmarks/low_thrust_census.py              # 30 catalogs
    python benchmarks/low_thrust_census.py --cases 60

Run from the repository root (it imports the brute force from ``tests``).
"""

from __future__ import annotations

import argparse
import sys
import time
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))

from sdc_cvx import solve  # noqa: E402
from sdc_cvx.errors import MissionInfeasible  # noqa: E402
from tests.planner.low_thrust_bruteforce import optimum, random_catalog  # noqa: E402
from tests.planner.test_low_thrust_certified import catalog_of, mission  # noqa: E402


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--cases", type=int, default=30)
    args = parser.parse_args(argv)
    rng = np.random.default_rng(2026)
    print(f"{'seed':>4} {'N':>2} {'n':>2} {'kind':<7} {'f':>6} {'rule':<6} {'T_max':>6} "
          f"{'brute':>9} {'s':>5} {'sdc_cvx':>9} {'bound':>9} {'s':>5} {'ratio':>8} verdict")
    worst, bad = 1.0, 0
    for k in range(args.cases):
        seed, count, n = 100 + k, int(rng.integers(6, 9)), int(rng.integers(3, 5))
        kind = ("sso", "cluster", "mixed")[k % 3]
        accel = (3e-5, 1e-4, 3e-4)[(k // 3) % 3]
        rule = ("table3", "free")[k % 2]
        tmax = float(rng.choice([300.0, 365.25, 500.0]))
        synthetic = random_catalog(seed, count, kind=kind)
        start = time.perf_counter()
        reference = optimum(synthetic.a_m, synthetic.e, synthetic.inc_rad, synthetic.raan_rad,
                            n=n, tmax_days=tmax, accel_mps2=accel, rule=rule)
        brute_s = time.perf_counter() - start
        start = time.perf_counter()
        try:
            answer = solve(catalog_of(synthetic), mission(n, accel, rule, tmax))
            got, bound = answer.total_dv_mps, answer.lower_bound_mps
        except MissionInfeasible:
            got = bound = None
        ours_s = time.perf_counter() - start
        brute = None if reference is None else reference.cost_mps
        if brute is None or got is None:
            ok, ratio = brute is None and got is None, float("nan")
        else:
            ratio = got / brute
            ok = ratio <= 1.001 and bound <= brute + 1e-6
            worst = max(worst, ratio)
        bad += not ok

        def show(value):
            return f"{value:9.2f}" if value is not None else f"{'none':>9}"

        print(f"{seed:>4} {count:>2} {n:>2} {kind:<7} {accel:>6g} {rule:<6} {tmax:>6g} "
              f"{show(brute)} {brute_s:>5.1f} {show(got)} {show(bound)} {ours_s:>5.1f} "
              f"{ratio:>8.5f} {'ok' if ok else 'MISMATCH'}", flush=True)
    print(f"# {args.cases - bad} of {args.cases} agree (within 0.1 %, bound never above; "
          f"infeasible both); worst ratio {worst:.5f}")


if __name__ == "__main__":
    main()
