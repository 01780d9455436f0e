"""Random small campaigns against the brute force: answer, bound, status and time.

The hidden checks of issue 19 are campaigns of N 8-10 debris, K 2-3 launches, n 2-3
debris each, with certified optima.  This script draws such campaigns from seeds (near-
SSO catalogs with spread J2 rates, launch days 60-400 days apart, T_max 120-365 days,
either inclination rule, a must_remove debris on about a third of them), solves each
with ``solve_campaign`` and compares it with the independent brute force of
``tests/campaign/bruteforce.py`` (every ordered path of every launch on a radius grid,
every choice of disjoint debris sets).  Prints one line per seed: the brute force's
optimum (``inf``: no campaign), the answer, its bound and status, whether it is right
(bound not above the optimum, answer within 0.1 % of it, every mission's legs replayed
with the physics), and both times.

    python benchmarks/campaign_random.py            # seeds 0-19
    python benchmarks/campaign_random.py 20 40      # seeds 20-39
"""

from __future__ import annotations

import sys
import time
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))  # the tests' brute force

from sdc_cvx import Campaign, Mission, MissionInfeasible, solve_campaign  # noqa: E402
from sdc_cvx.inputs.synthetic import sso_catalog  # noqa: E402
from tests.campaign.bruteforce import advanced, campaign_optimum  # noqa: E402
from tests.planner.test_enumeration import solver_plan_checked  # noqa: E402

GRID_TOL_MPS = 0.05


def case(seed: int):
    """A random campaign: (catalog, launch days, n per mission, T_max per mission, rule,
    must_remove)."""
    rng = np.random.default_rng(1000 + seed)
    launches, size = int(rng.integers(2, 4)), int(rng.integers(8, 11))
    ns = [int(rng.integers(2, 4)) for _ in range(launches)]
    while sum(ns) > size:
        ns[int(np.argmax(ns))] -= 1
    days = [float(d) for d in np.cumsum(np.r_[0.0, rng.uniform(60, 400, launches - 1)])]
    tmax = [float(rng.uniform(120, 365)) for _ in range(launches)]
    rule = ["table3", "free"][int(rng.integers(2))]
    must = (f"S{int(rng.integers(size)):03d}",) if rng.random() < 0.3 else ()
    catalog = sso_catalog(size, seed=int(rng.integers(2**31)),
                          inclination_spread_deg=float(rng.uniform(0.5, 1.0)))  # fmt: skip
    return catalog, days, ns, tmax, rule, must


def check(seed: int) -> str:
    catalog, days, ns, tmax, rule, must = case(seed)
    clock = time.perf_counter()
    best = campaign_optimum(catalog, days, ns, tmax, rule, must)
    brute_s = time.perf_counter() - clock
    campaign = Campaign.of(days, Mission(drift_inclination=rule), n=ns, tmax_days=tmax,
                           must_remove=must)  # fmt: skip
    head = f"seed {seed:2d}: N={len(catalog)} n={ns} {rule:6} must={list(must)} brute "
    clock = time.perf_counter()
    try:
        sol = solve_campaign(catalog, campaign, workers=1)
    except MissionInfeasible as err:
        right = not np.isfinite(best.dv_mps)
        return (f"{head}inf  solver: infeasible ({str(err)[:60]}...) "
                f"{'OK' if right else 'WRONG'} ({time.perf_counter() - clock:.1f} s, "
                f"brute {brute_s:.1f} s)")  # fmt: skip
    solve_s = time.perf_counter() - clock
    right = (sol.certified and sol.lower_bound_mps <= best.dv_mps + 1e-3
             and sol.total_dv_mps <= best.dv_mps * 1.001 + 1e-3
             and sol.total_dv_mps >= best.dv_mps - GRID_TOL_MPS * len(ns))  # fmt: skip
    for day, limit, mission in zip(days, tmax, sol.missions, strict=True):
        try:
            solver_plan_checked(mission, advanced(catalog, day), limit, rule)
        except AssertionError:
            right = False
    greedy = "-" if sol.greedy.dv_mps is None else f"{sol.greedy.dv_mps:.2f}"
    return (f"{head}{best.dv_mps:9.3f}  answer {sol.total_dv_mps:9.3f}  bound "
            f"{sol.lower_bound_mps:9.3f}  greedy {greedy:>8}  {sol.status}  "
            f"{'OK' if right else 'WRONG'} ({solve_s:.1f} s, brute {brute_s:.1f} s)")  # fmt: skip


def main() -> None:
    first, last = (int(sys.argv[1]), int(sys.argv[2])) if len(sys.argv) > 2 else (0, 20)
    for seed in range(first, last):
        print(check(seed), flush=True)


if __name__ == "__main__":
    main()
