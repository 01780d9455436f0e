"""Value campaigns whose missions may remove one debris or none (issue 48, item 11).

``n = [[1, 3]]``: a mission of one debris is the launch onto its orbit alone (0 m/s,
no operations cost here); ``n_min = 0``: a launch may stay unused.  The brute force
(``tests/campaign/bruteforce.py``: every set of every count of each range, the missions
of two or more by the mission brute force, one debris at 0 m/s, none at 0 m/s) gives
the optimum; a min-dv campaign keeps ``2 <= n_min`` and is told what its ranges do.
"""

from __future__ import annotations

import pytest

from sdc_cvx import Mission, MissionError
from sdc_cvx.campaign.pricing_runs import ignored_options
from sdc_cvx.campaign.search import solve_campaign
from sdc_cvx.inputs.campaign import Campaign
from sdc_cvx.milp.types import SolverOptions
from sdc_cvx.solution import RunStatus
from tests.campaign.bruteforce import value_optimum
from tests.campaign.test_max_value import GRID_TOL_MPS, Case

MIXED = Case("one-or-two", 8, 11, (0.0, 200.0), ((1, 2), (1, 2)), (250.0, 150.0),
             (260.0, 15.0), rule="free")  # fmt: skip
"""The second launch's budget flies no pair (15 m/s): one debris, the most valuable left."""


@pytest.mark.slow
def test_a_max_value_campaign_with_missions_of_one_debris_is_the_brute_forces():
    best = value_optimum(MIXED.catalog(), MIXED.launch_days, MIXED.ranges, MIXED.tmax,
                         MIXED.budgets, MIXED.values(), MIXED.rule)  # fmt: skip
    assert best.margin_mps > 2 * GRID_TOL_MPS
    assert sorted(map(len, best.sets)) == [1, 2]  # the case has a mission of one debris
    sol = solve_campaign(MIXED.catalog(), MIXED.campaign(), workers=1)
    found = f"solver {[m.path for m in sol.missions]}; brute {[sorted(s) for s in best.sets]}"
    assert sol.status == RunStatus.OPTIMAL and sol.certified, found
    assert sol.value == pytest.approx(best.value) and sol.value_bound == pytest.approx(best.value)
    assert sol.total_dv_mps == pytest.approx(best.dv_mps, abs=2 * GRID_TOL_MPS), found
    assert sorted(len(m.path) for m in sol.missions) == [1, 2]
    for mission, budget in zip(sol.missions, MIXED.budgets, strict=True):
        assert mission.total_dv_mps <= budget + 1e-9
    one = next(m for m in sol.missions if len(m.path) == 1)
    assert one.total_dv_mps == 0.0 and not one.legs


@pytest.mark.slow
def test_a_launch_that_adds_no_value_is_left_unused():
    """Two debris are worth anything and three launches may fly [0, 2] each: the most
    value (8) uses two launches; the third is left out of the campaign, with a note."""
    values = {"S002": 5.0, "S006": 3.0}
    days, tmax, budgets = (0.0, 200.0, 400.0), (150.0,) * 3, (15.0,) * 3
    best = value_optimum(MIXED.catalog(), days, ((0, 2),) * 3, tmax, budgets, values, "free")
    assert best.value == 8.0 and best.dv_mps == 0.0 and frozenset() in best.sets
    campaign = Campaign.of(days, Mission(drift_inclination="free"), n=[[0, 2]],
                           tmax_days=list(tmax), objective="max-value",
                           dv_budget_mps=list(budgets), values=values)  # fmt: skip
    sol = solve_campaign(MIXED.catalog(), campaign, workers=1)
    assert sol.status == RunStatus.OPTIMAL and sol.value == 8.0 and sol.value_bound == 8.0
    assert sol.total_dv_mps == 0.0
    assert sorted(m.path for m in sol.missions) == [("S002",), ("S006",)]
    assert len(sol.campaign) == 2 and set(sol.campaign.launch_days) < set(days)
    assert any("left unused (n_min = 0" in note for note in sol.notes), sol.notes
    assert "optimal (0 m/s" in sol.summary()


def test_n_min_below_two_is_a_value_objectives_choice():
    value = dict(objective="max-value", dv_budget_mps=100.0)
    assert Campaign.of([0.0, 100.0], n=[[1, 3]], **value).n_min == (1, 1)
    assert Campaign.of([0.0, 100.0], n=[[0, 3], [1, 2]], **value).n_min == (0, 1)
    with pytest.raises(MissionError, match=r"0 <= n_min <= n_max.*got n = \[\[-1, 3\]\]"):
        Campaign.of([0.0, 100.0], n=[[-1, 3]], **value)
    with pytest.raises(MissionError, match=r"2 <= n_min <= n_max.*objective = 'min-dv'"):
        Campaign.of([0.0, 100.0], n=[[1, 3]])
    injected = Mission(injection=(6978.0, 0.0, 97.0, 150.0))
    with pytest.raises(MissionError, match="mission 1, 2: n_min = 1 with an injection orbit"):
        Campaign.of([0.0, 100.0], injected, n=[[1, 3]], **value)
    assert Campaign.of([0.0, 100.0], injected, n=[[0, 3]], **value).n_min == (0, 0)


def test_a_min_dv_campaign_with_ranges_and_nothing_to_remove_is_told_it_takes_n_min():
    """Found as a user: a GTOC9 campaign with n = [[2, 10]] returned three missions of 2,
    nothing said (the least ΔV removes the fewest debris)."""
    said = ignored_options(Campaign.of([0.0, 100.0], n=[[2, 4]]), SolverOptions())
    assert len(said) == 1 and "takes each mission's n_min" in said[0], said
    for forced in (dict(must_remove=["S001"]), dict(remove_all=True)):
        assert ignored_options(Campaign.of([0.0, 100.0], n=[[2, 4]], **forced),
                               SolverOptions()) == []  # fmt: skip
    assert ignored_options(Campaign.of([0.0, 100.0], n=[4, 3]), SolverOptions()) == []
    from sdc_cvx.errors import IgnoredOptionWarning

    # said before the catalog is checked (9 debris from 8 candidates is refused then)
    with pytest.warns(IgnoredOptionWarning, match="takes each mission's n_min") as warned, \
            pytest.raises(MissionError):  # fmt: skip
        solve_campaign(MIXED.catalog(), Campaign.of([0.0, 100.0], n=[[2, 9]]), workers=1)
    assert len([w for w in warned if "n_min" in str(w.message)]) == 1  # once


def test_a_mission_of_one_debris_is_not_flown(tmp_path):
    """A mission of one debris has no leg: ``fly`` leaves it out of a campaign's flights
    (flight/plan.run_folder_plans), and says so when no mission has a leg."""
    import json

    from sdc_cvx.flight.plan import FlightError, run_folder_plans

    (tmp_path / "mission_01").mkdir()
    (tmp_path / "campaign.json").write_text(json.dumps({"missions": [
        {"launch_day": 0.0, "path": ["5"], "total_dv_mps": 0.0, "folder": "mission_01"}]}))
    with pytest.raises(FlightError, match="every mission removes one debris"):
        run_folder_plans(tmp_path)


def test_a_launch_left_unused_fits_any_tank():
    """With a vehicle's tank (each mission must fit it), a launch of no debris flies no
    vehicle: it fits (the propellant budget of no node is not asked for)."""
    from sdc_cvx.inputs.vehicle import Vehicle

    vehicle = Vehicle(dry_mass_kg=500.0, propellant_kg=20.0, isp_s=300.0, kit_mass_kg=20.0)
    campaign = Campaign.of([0.0, 200.0], Mission(drift_inclination="free", vehicle=vehicle),
                           n=[[0, 2]], tmax_days=[250.0, 150.0], objective="max-value",
                           values={"S002": 5.0, "S006": 1.0})  # fmt: skip
    sol = solve_campaign(MIXED.catalog(), campaign, workers=1)
    # the two debris of any value, each the launch onto its orbit (0 m/s, no propellant)
    assert sol.status == RunStatus.OPTIMAL and sol.value == 6.0 and sol.total_dv_mps == 0.0
    assert sorted(m.path for m in sol.missions) == [("S002",), ("S006",)]
