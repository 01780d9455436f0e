"""Min-ΔV campaigns with a range of debris per mission and ``remove_all``, against the
independent enumeration of ``tests/campaign/bruteforce.py`` (RAANs carried with Eq. 7
re-derived from the paper, every ordered path of every count flown by the mission brute
force, every choice of disjoint debris sets enumerated).

A range matters only where debris must be removed: without it the fewest debris are the
cheapest (a path less its last debris is a mission too).  So each case here removes
every candidate, or names debris that must be removed.
"""

from __future__ import annotations

import numpy as np
import pytest

from sdc_cvx import Mission, MissionError
from sdc_cvx.campaign.search import solve_campaign
from sdc_cvx.inputs.campaign import Campaign
from sdc_cvx.inputs.synthetic import sso_catalog
from sdc_cvx.solution import RunStatus
from tests.campaign.bruteforce import advanced, campaigns_of, value_options
from tests.planner.test_enumeration import solver_plan_checked

EPS_MPS = 1e-3
GRID_TOL_MPS = 0.05
GAP = 1e-3


def ranged_optimum(catalog, launch_days, ranges, tmaxes, required):
    """The least ΔV of one debris set per launch (of a count in its range), no debris
    twice, every ``required`` id removed; ``(dv, sets)``."""
    options, _ = value_options(catalog, launch_days, ranges, tmaxes,
                               [np.inf] * len(launch_days))  # fmt: skip
    best = (np.inf, ())
    for _, total, chosen in campaigns_of(options, {}):
        if set(required) <= frozenset().union(*chosen) and total < best[0]:
            best = (total, chosen)
    return best


CASES = [
    # seven candidates, three launches of two or three debris: 3+2+2 in some order
    pytest.param(dict(size=7, seed=7, days=(0.0, 200.0, 400.0), ranges=((2, 3),) * 3,
                      tmax=(300.0,) * 3, remove_all=True), id="remove-all-7"),
    # two debris that must go, missions of two or three from eight candidates
    pytest.param(dict(size=8, seed=7, days=(0.0, 365.25), ranges=((2, 3), (2, 3)),
                      tmax=(150.0, 150.0), must=("S002", "S004", "S006")),
                 id="must-remove-ranges", marks=pytest.mark.slow),
]  # fmt: skip


@pytest.mark.parametrize("case", CASES)
def test_a_campaign_with_ranges_is_the_optimum(case):
    catalog = sso_catalog(case["size"], seed=case["seed"])
    required = catalog.ids if case.get("remove_all") else case["must"]
    dv, sets = ranged_optimum(catalog, case["days"], case["ranges"], case["tmax"], required)
    assert np.isfinite(dv)
    campaign = Campaign.of(case["days"], Mission(), n=[list(r) for r in case["ranges"]],
                           tmax_days=list(case["tmax"]), must_remove=case.get("must", ()),
                           remove_all=case.get("remove_all", False))  # fmt: skip
    sol = solve_campaign(catalog, campaign, workers=1, gap=GAP)
    found = (f"solver {[m.path for m in sol.missions]} {sol.total_dv_mps:.3f} (bound "
             f"{sol.lower_bound_mps:.3f}); brute {[sorted(s) for s in sets]} {dv:.3f}")
    assert sol.status == RunStatus.OPTIMAL and sol.certified, found
    assert sol.lower_bound_mps <= dv + EPS_MPS, found
    # the first bound (launches alone, their sizes adding up to the debris that must go)
    # is a proof before any price
    first = sol.history[0]
    assert first["step"] == "launches alone and greedy"
    assert 0.0 < first["lower_mps"] <= dv + EPS_MPS, (first, found)
    assert sol.total_dv_mps <= dv * (1 + GAP) + EPS_MPS, found
    assert sol.total_dv_mps >= dv - len(case["days"]) * GRID_TOL_MPS, found
    removed = [d for m in sol.missions for d in m.path]
    assert len(removed) == len(set(removed))
    assert set(required) <= set(removed)
    for day, (low, high), tmax, mission in zip(case["days"], case["ranges"], case["tmax"],
                                               sol.missions, strict=True):  # fmt: skip
        assert low <= len(mission.path) <= high
        assert mission.mission.n == len(mission.path)
        solver_plan_checked(mission, advanced(catalog, day), tmax, "table3")


def test_remove_all_needs_room_for_every_candidate():
    catalog = sso_catalog(8, seed=7)
    campaign = Campaign.of([0.0, 200.0], Mission(), n=[[2, 3], [2, 3]], remove_all=True)
    with pytest.raises(MissionError, match=r"remove_all: the catalog has 8 candidates but the "
                                           r"missions remove 6 at most \(2-3, 2-3\)"):
        solve_campaign(catalog, campaign, workers=1)


def test_remove_all_and_must_remove_together_are_refused():
    with pytest.raises(MissionError, match="remove_all removes every candidate"):
        Campaign.of([0.0], Mission(), n=2, must_remove=["S000"], remove_all=True)


def random_size_bounds(rng, *, every_launch_flies: bool = False) -> dict:
    """``bounds[k][n]``: 1 to 4 launches, sizes from 1-3 to 3-6, bounds of 10 n to
    10 n + 100 m/s; a launch's largest size flies no mission (inf) three times in ten
    (never its only size, with ``every_launch_flies``)."""
    launches = int(rng.integers(1, 5))
    bounds = {k: {size: float(rng.uniform(0, 100)) + 10 * size
                  for size in range(int(rng.integers(1, 4)), int(rng.integers(4, 7)))}
              for k in range(launches)}  # fmt: skip
    for k in range(launches):  # a size that no mission flies
        if rng.random() < 0.3 and (len(bounds[k]) > 1 or not every_launch_flies):
            bounds[k][max(bounds[k])] = np.inf
    return bounds


@pytest.mark.parametrize("seed", range(20))
def test_the_sizes_bound_is_the_least_sum_over_sizes_that_remove_enough(seed):
    """Against every choice of one size per launch: the least sum of the launches' bounds
    for their sizes among those that add up to at least the debris required."""
    import itertools

    from sdc_cvx.campaign.min_dv import sizes_bound

    rng = np.random.default_rng(seed)
    bounds = random_size_bounds(rng)
    launches = len(bounds)
    required = int(rng.integers(0, 6 * launches))
    best = min((sum(bounds[k][size] for k, size in enumerate(sizes))
                for sizes in itertools.product(*(sorted(b) for b in bounds.values()))
                if sum(sizes) >= required), default=np.inf)  # fmt: skip
    assert sizes_bound(bounds, required) == pytest.approx(best)
    assert sizes_bound(bounds, 0) == pytest.approx(sum(min(b.values()) for b in bounds.values()))
    bounds[0][min(bounds[0])] = -np.inf  # no bound proven for one size: none at all
    assert sizes_bound(bounds, required) == -np.inf
