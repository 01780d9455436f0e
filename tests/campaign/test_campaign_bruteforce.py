"""Campaigns against an independent enumeration over disjoint debris sets.

The brute force (``tests/campaign/bruteforce.py``) carries the RAANs to each launch day
with Eq. 7 re-derived from the paper, optimises every ordered path of each launch with
the mission brute force (a radius grid and the true physics, nothing of the code under
test) and enumerates every choice of disjoint debris sets.  For each case, of
``solve_campaign`` with its default gap (0.1 %):

* every mission flies: its legs replayed with the physics from its own launch day
  (``solver_plan_checked`` on the catalog carried to that day), drift orbits in the band
  and by the rule, each mission within its T_max;
* no debris is removed twice, and every ``must_remove`` debris is removed;
* ``status`` is optimal and ``certified`` is true, within its own gap;
* the bound is proven: ``lower_bound <= brute + EPS`` (the brute force's plans fly, so
  ``brute`` is at or above the optimum);
* the answer is the optimum: ``answer <= brute * 1.001 + EPS`` and ``answer >= brute -
  K * GRID_TOL_MPS`` (the mission brute force's grid error, per mission).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
import pytest

from sdc_cvx import Mission, MissionError, MissionInfeasible
from sdc_cvx.campaign.search import solve_campaign
from sdc_cvx.inputs.campaign import Campaign
from sdc_cvx.inputs.synthetic import sso_catalog
from sdc_cvx.solution import RunStatus
from tests.campaign.bruteforce import advanced, campaign_optimum
from tests.planner.test_enumeration import solver_plan_checked

EPS_MPS = 1e-3
GRID_TOL_MPS = 0.05
GAP = 1e-3


@dataclass(frozen=True)
class Case:
    name: str
    size: int
    seed: int
    launch_days: tuple
    n: tuple
    tmax: tuple
    rule: str = "table3"
    must_remove: tuple = ()
    spread_deg: float = 0.8

    def catalog(self):
        return sso_catalog(self.size, seed=self.seed, inclination_spread_deg=self.spread_deg)

    def campaign(self) -> Campaign:
        return Campaign.of(self.launch_days, Mission(drift_inclination=self.rule),
                           n=list(self.n), tmax_days=list(self.tmax),
                           must_remove=self.must_remove)  # fmt: skip


FAST = Case("k2-n2", 8, 7, (0.0, 365.25), (2, 2), (150.0, 150.0))
CASES = [
    pytest.param(FAST, id=FAST.name),
    pytest.param(
        Case("greedy-loses", 10, 101, (0.0, 365.25), (3, 3), (200.0, 200.0)),
        id="greedy-loses",
        marks=pytest.mark.slow,
    ),
    pytest.param(
        Case(
            "k3-n2-free", 9, 23, (0.0, 180.0, 400.0), (2, 2, 2), (120.0, 120.0, 200.0), rule="free"
        ),
        id="k3-n2-free",
        marks=pytest.mark.slow,
    ),
    pytest.param(
        Case("k3-mixed", 9, 31, (0.0, 365.25, 730.5), (3, 2, 3), (250.0, 150.0, 300.0)),
        id="k3-mixed",
        marks=pytest.mark.slow,
    ),
    pytest.param(
        Case(
            "must-remove", 8, 7, (0.0, 365.25), (2, 2), (150.0, 150.0), must_remove=("S002", "S004")
        ),
        id="must-remove",
        marks=pytest.mark.slow,
    ),
]

REPAIRED = Case("remove-all-repaired", 6, 18, (0.0, 365.25, 730.5), (2, 2, 2),
                (100.0, 100.0, 100.0), must_remove=tuple(f"S{k:03d}" for k in range(6)))
"""Every debris must be removed, and greedy leaves two that no mission of the last launch
removes together (found by a search over seeds)."""
CASES.append(pytest.param(REPAIRED, id=REPAIRED.name))

_BRUTE: dict = {}


def brute(case: Case):
    if case.name not in _BRUTE:
        _BRUTE[case.name] = campaign_optimum(case.catalog(), case.launch_days, case.n, case.tmax,
                                             case.rule, case.must_remove)  # fmt: skip
    return _BRUTE[case.name]


@pytest.mark.parametrize("case", CASES)
def test_campaign_is_the_optimum(case):
    best = brute(case)
    assert np.isfinite(best.dv_mps)
    sol = solve_campaign(case.catalog(), case.campaign(), workers=1, gap=GAP)
    found = (f"solver {[m.path for m in sol.missions]} {sol.total_dv_mps:.3f} (bound "
             f"{sol.lower_bound_mps:.3f}); brute {[sorted(s) for s in best.sets]} "
             f"{best.dv_mps:.3f}")  # fmt: skip
    assert sol.status == RunStatus.OPTIMAL and sol.certified, found
    assert sol.total_dv_mps - sol.lower_bound_mps <= max(GAP * sol.total_dv_mps, 0.02) + 1e-9
    assert sol.lower_bound_mps <= best.dv_mps + EPS_MPS, found
    # the first bound, the launches alone (each flies one mission, none cheaper than its
    # least): a proof already, before any price
    first = sol.history[0]
    assert first["step"] == "launches alone and greedy"
    assert 0.0 < first["lower_mps"] <= best.dv_mps + EPS_MPS, (first, found)
    assert sol.total_dv_mps <= best.dv_mps * (1 + GAP) + EPS_MPS, found
    assert sol.total_dv_mps >= best.dv_mps - len(case.n) * GRID_TOL_MPS, found
    removed = [d for m in sol.missions for d in m.path]
    assert len(removed) == len(set(removed)) == sum(case.n)
    assert set(case.must_remove) <= set(removed)
    for day, n, tmax, mission in zip(case.launch_days, case.n, case.tmax, sol.missions,
                                     strict=True):  # fmt: skip
        assert len(mission.path) == n
        solver_plan_checked(mission, advanced(case.catalog(), day), tmax, case.rule)
    total = sum(m.total_dv_mps for m in sol.missions)
    assert sol.total_dv_mps == pytest.approx(total, abs=1e-9)


@pytest.mark.slow
def test_greedy_is_worse_than_the_optimum_here():
    """Greedy takes for the first mission debris the second one needed."""
    case = CASES[1].values[0]
    best = brute(case)
    sol = solve_campaign(case.catalog(), case.campaign(), workers=1)
    assert sol.greedy.dv_mps is not None
    assert sol.greedy.dv_mps > best.dv_mps + 50.0  # 1368.8 against 1164.7 m/s
    # and greedy's first mission is the first launch's cheapest alone (brute force)
    first_alone = min(best.per_launch[0].values())
    assert sol.greedy.missions[0].dv_mps == pytest.approx(first_alone, abs=GRID_TOL_MPS)


@pytest.mark.slow
def test_must_remove_binds_in_its_case():
    """The must_remove case is a test of it: without it the optimum is cheaper."""
    case = CASES[4].values[0]
    free = brute(Case("no-must", case.size, case.seed, case.launch_days, case.n, case.tmax))
    assert brute(case).dv_mps > free.dv_mps + 100.0  # 502.3 against 229.0 m/s
    assert not {"S002", "S004"} <= set().union(*free.sets)


def test_an_infeasible_launch_day_is_named():
    case = FAST
    campaign = Campaign.of(case.launch_days, Mission(), n=[2, 3], tmax_days=[150.0, 1.0])
    with pytest.raises(MissionInfeasible, match=r"mission 2 \(launch day 365.25\)"):
        solve_campaign(case.catalog(), campaign, workers=1)


def test_must_remove_beyond_the_missions_is_refused():
    campaign = Campaign.of([0.0, 30.0], Mission(), n=[2, 2], tmax_days=[150.0, 150.0],
                           must_remove=["S000", "S001", "S002", "S003", "S004"])  # fmt: skip
    with pytest.raises(MissionError, match="must_remove names 5 debris but the missions remove 4"):
        solve_campaign(FAST.catalog(), campaign, workers=1)


def test_missions_that_cannot_share_the_debris_are_infeasible():
    """Each launch flies alone, but the first may not take S000-S002 and the second holds
    two debris: three must_remove debris cannot all be removed (the master LP needs its
    artificial columns; the enumeration of every mission that flies proves it)."""
    first = Mission(n=2, tmax_days=365.25, exclude=("S000", "S001", "S002"))
    campaign = Campaign((0.0, 30.0), (first, Mission(n=2, tmax_days=365.25)),
                        must_remove=("S000", "S001", "S002"))  # fmt: skip
    lines: list[str] = []
    # the closing step's proof, not the LP's artificial columns (a big-M cost is no proof
    # where a price could reach it): its message says what was enumerated
    with pytest.raises(MissionInfeasible, match="no campaign removes each debris at most once"
                       r".*every mission that flies from each launch was enumerated"):
        solve_campaign(FAST.catalog(), campaign, workers=1, log=lines.append)
    assert any("the master LP needs its artificial columns" in line for line in lines), lines


@pytest.mark.slow
def test_a_fractional_master_with_no_campaign_is_proven_infeasible():
    """Every launch flies alone and the master LP has a solution (missions at weight 1/2),
    but no choice of one mission per launch shares no debris: the brute force finds none,
    and the search proves it by enumerating every mission that flies."""
    case = Case("fractional", 9, 1955924217, (0.0, 192.42725249566993, 367.0518560075124),
                (3, 2, 3), (255.9491597347579, 165.8685084078223, 149.31483286403528),
                rule="free", spread_deg=0.964425726499131)  # fmt: skip
    assert not np.isfinite(brute(case).dv_mps)
    assert all(brute(case).per_launch)  # each launch flies alone
    with pytest.raises(MissionInfeasible, match="every mission that flies from each launch"):
        solve_campaign(case.catalog(), case.campaign(), workers=1)


@pytest.mark.parametrize("mend", ["exchange", "pass"])
def test_where_greedy_leaves_debris_over_a_campaign_is_in_hand_before_any_round(monkeypatch,
                                                                                mend):
    """Greedy leaves two debris to the last launch that no mission of it removes together.
    ``exchange`` (campaign/greedy.swap_in): the last launch takes one of them and a debris
    of an earlier mission, which takes the other in its place.  ``pass`` (the exchange
    left out; campaign/greedy.repair): the debris left over get more prize and an earlier
    mission takes them (squeaky wheel).  Either way a campaign is in hand before any round
    of the column generation, and the search ends at the brute force's optimum."""
    from sdc_cvx.campaign import greedy

    if mend == "pass":
        monkeypatch.setattr(greedy, "swap_in", lambda *args: None)
    best = brute(REPAIRED)
    lines: list[str] = []
    sol = solve_campaign(REPAIRED.catalog(), REPAIRED.campaign(), workers=1, gap=GAP,
                         log=lines.append)  # fmt: skip
    assert sol.greedy.dv_mps is None and len(sol.greedy.left_over) == 2
    said = {"exchange": "takes 1 of the 2 debris left over", "pass": "greedy pass 2"}[mend]
    assert any(said in line for line in lines), lines
    after_greedy = next(line for line in lines if "launches alone and greedy:" in line)
    assert "plan none yet" not in after_greedy, after_greedy
    assert sol.total_dv_mps <= best.dv_mps * (1 + GAP) + EPS_MPS


def test_the_dearest_campaign_shared_out_again_is_the_brute_forces_optimum():
    """campaign/regroup: the dearest campaign of the brute force (a set per launch, no
    debris twice, every debris removed) put in as the plan, its launches shared out again
    (one window: the case has three launches) give the brute force's optimum, with no
    round of the column generation."""
    import itertools

    from sdc_cvx.campaign.min_dv import CampaignSearch
    from sdc_cvx.campaign.pricing_runs import PricingRuns
    from sdc_cvx.campaign.regroup import regroup
    from sdc_cvx.milp.types import SolverOptions

    best = brute(REPAIRED)
    campaigns = [(sum(dv for _, dv in choice), [s for s, _ in choice])
                 for choice in itertools.product(*(b.items() for b in best.per_launch))
                 if len(frozenset().union(*(s for s, _ in choice))) == sum(REPAIRED.n)]
    dearest, sets = max(campaigns, key=lambda c: c[0])
    assert dearest > best.dv_mps + 30.0  # what regroup must find its way down from (927.4)
    catalog = REPAIRED.catalog()
    with PricingRuns(True, None, None, 1, 1) as run:
        search = CampaignSearch(catalog, REPAIRED.campaign(), SolverOptions(), GAP, np.inf,
                                lambda line: None, run)  # fmt: skip
        tasks = [(search.variant(k, len(s)), search.unpriced(
            exclude=[i for i, name in enumerate(catalog.ids) if name not in s]))
            for k, s in enumerate(sets)]  # fmt: skip
        plan = [result.columns[0] for result in search.price_all(tasks)]
        search.pool.add(plan)
        search.plan, search.upper = plan, sum(c.dv_mps for c in plan)
        assert search.upper == pytest.approx(dearest, abs=len(sets) * GRID_TOL_MPS)
        regroup(search)
    assert search.upper <= best.dv_mps * (1 + GAP) + EPS_MPS
    assert search.upper >= best.dv_mps - len(sets) * GRID_TOL_MPS
    removed = sorted(i for c in search.plan for i in c.debris)
    assert removed == list(range(len(catalog)))
