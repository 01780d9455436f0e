"""The dive (``campaign/dive.py``): a campaign built on the master LP one mission at a
time, against the brute force (``tests/campaign/bruteforce.py``), and what it says when it
cannot finish."""

from __future__ import annotations

import time

import numpy as np
import pytest

from sdc_cvx import Mission
from sdc_cvx.campaign.dive import dive, residual
from sdc_cvx.campaign.min_dv import CampaignSearch
from sdc_cvx.campaign.pricing import Column
from sdc_cvx.campaign.pricing_runs import PricingRuns
from sdc_cvx.inputs.campaign import Campaign
from sdc_cvx.inputs.synthetic import sso_catalog
from sdc_cvx.milp.types import SolverOptions
from tests.campaign.test_campaign_bruteforce import GAP, GRID_TOL_MPS, REPAIRED, brute


def column(launch: int, debris: tuple, dv: float) -> Column:
    return Column(launch, debris, debris, dv, dv, None)


def test_the_residual_keeps_the_fixed_missions_and_those_that_share_no_debris():
    fixed = {0: column(0, (0, 1), 5.0)}
    pool = [column(0, (2, 3), 1.0), column(1, (1, 2), 1.0), column(1, (2, 3), 2.0),
            column(2, (4,), 3.0), column(2, (0, 4), 1.0)]  # fmt: skip
    kept = residual(pool, fixed)
    assert kept == [fixed[0], pool[2], pool[3]]


def test_a_dive_after_the_column_generation_builds_the_brute_forces_optimum():
    """Every debris must go (three launches of two debris, six debris): after the column
    generation, the dive, from no plan, fixes one mission at a time and ends on a campaign
    that flies: one mission per launch, every debris once, at the brute force's optimum."""
    best = brute(REPAIRED)
    catalog = REPAIRED.catalog()
    with PricingRuns(True, None, None, 1, 1) as run:
        search = CampaignSearch(catalog, REPAIRED.campaign(), SolverOptions(), GAP, np.inf,
                                lambda line: None, run)  # fmt: skip
        search.launches_alone()
        search.generate_columns()
        lower = search.lower
        search.plan, search.upper = None, np.inf  # the dive's own campaign, whatever the pool's
        dive(search)
    assert search.plan is not None, search.notes
    assert [c.launch for c in search.plan] == [0, 1, 2]
    removed = sorted(i for c in search.plan for i in c.debris)
    assert removed == list(range(len(catalog)))
    assert search.upper == pytest.approx(sum(c.dv_mps for c in search.plan), abs=1e-9)
    assert best.dv_mps - 3 * GRID_TOL_MPS <= search.upper <= best.dv_mps * (1 + GAP) + 1e-3
    assert search.lower == lower  # a dive proves nothing
    dives = [h["step"] for h in search.history if h["step"].startswith("dive")]
    # one mission fixed on the LP, the two launches left shared out by their own search
    assert dives[0].startswith("dive (1 of 3 missions fixed")
    assert dives[-1].startswith("dive (the 2 launches left shared out by their own search")


def diving(monkeypatch, finish_fails):
    """The dive on REPAIRED after the column generation, its step 4 failing the first
    ``finish_fails`` times; the search, the keys of the missions fixed before each
    failure, and the brute force's optimum."""
    from sdc_cvx.campaign import dive as module

    real, undone = module._finish, []

    def finish(search, fixed):
        if len(undone) < finish_fails:
            undone.append(set(c.key for c in fixed.values()))
            return None
        return real(search, fixed)

    monkeypatch.setattr(module, "_finish", finish)
    return dived_after_the_rounds(), undone, brute(REPAIRED)


def dived_after_the_rounds():
    """REPAIRED's search after its column generation, dived from no plan."""
    with PricingRuns(True, None, None, 1, 1) as run:
        search = CampaignSearch(REPAIRED.catalog(), REPAIRED.campaign(), SolverOptions(), GAP,
                                np.inf, lambda line: None, run)  # fmt: skip
        search.launches_alone()
        search.generate_columns()
        search.plan, search.upper = None, np.inf
        dive(search)
    return search


def test_where_the_launches_left_have_no_campaign_the_last_mission_is_undone(monkeypatch):
    """Step 4 finding no campaign: the mission fixed last is undone and barred (the next
    one fixed is another), and the dive ends on a campaign that flies (one mission per
    launch, every debris once), never below the brute force's optimum."""
    search, undone, best = diving(monkeypatch, 2)
    assert len(undone) == 2 and undone[1] != undone[0]
    assert search.plan is not None, search.notes
    assert sorted(i for c in search.plan for i in c.debris) == list(range(6))
    assert [c.launch for c in search.plan] == [0, 1, 2]
    assert search.upper >= best.dv_mps - 3 * GRID_TOL_MPS


def test_a_dive_whose_launches_left_never_have_a_campaign_says_so(monkeypatch):
    """Step 4 never finding one: at most :data:`BACKTRACKS` missions undone, then the dive
    ends without a campaign and says so."""
    from sdc_cvx.campaign.dive import BACKTRACKS

    search, undone, _ = diving(monkeypatch, 99)
    assert 1 <= len(undone) <= BACKTRACKS + 1 and search.plan is None
    assert search.notes[-1].startswith("the dive ended with ")


def test_a_dive_that_finds_no_campaign_keeps_the_plan_and_says_why():
    """Where the missions left cannot remove the debris that must go and the pricing
    brings no new one, the dive stops: the plan stays, and the notes say how far it got."""
    catalog = sso_catalog(4, seed=3)
    campaign = Campaign.of([0.0, 100.0], Mission(n=2), must_remove=list(catalog.ids))
    search = CampaignSearch(catalog, campaign, SolverOptions(), GAP, time.perf_counter() + 60,
                            lambda line: None, lambda tasks: [])  # fmt: skip
    search.pool.add([column(0, (0, 1), 10.0), column(1, (0, 2), 10.0)])  # debris 3: none
    search.plan, search.upper = ["a campaign"], 500.0
    search.regroups = False  # a search over a part of a campaign: no step 4 of its own
    dive(search)
    assert search.plan == ["a campaign"] and search.upper == 500.0
    assert search.notes[-1].startswith("the dive ended with 0 of 2 missions fixed")


def test_the_dives_repeat_each_from_another_first_mission(monkeypatch):
    """``dive`` repeats (at most DIVES times, here with no time limit): each dive's first
    mission is barred from the next ones' first step, and every campaign it keeps flies."""
    from sdc_cvx.campaign import dive as module

    real, seen = module._dive_once, []

    def once(search, firsts):
        seen.append(set(firsts))
        first = real(search, firsts)
        assert first is None or first not in seen[-1]
        return first

    monkeypatch.setattr(module, "_dive_once", once)
    search = dived_after_the_rounds()
    assert 2 <= len(seen) <= module.DIVES
    assert seen[0] == set() and all(len(b) == k for k, b in enumerate(seen))
    assert search.plan is not None
    assert sorted(i for c in search.plan for i in c.debris) == list(range(6))
