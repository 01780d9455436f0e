"""The most valuable campaign (issue 27: ``objective = "max-value"``) against a brute force.

The brute force (``tests/campaign/bruteforce.py``: ``value_optimum``) enumerates, for
each launch, every debris set of every size in the launch's range with the best order
the mission brute force finds (a grid over the drift orbits, RAANs carried by Eq. 7
re-derived there), keeps those within the launch's ΔV budget, and every choice of one
set per launch with no debris twice: the most value, then the least ΔV.
"""

from __future__ import annotations

import concurrent.futures as cf
import functools
from dataclasses import dataclass

import numpy as np
import pytest

from sdc_cvx import Mission, MissionError, MissionInfeasible
from sdc_cvx.campaign.pricing import Launch, price
from sdc_cvx.campaign.search import solve_campaign
from sdc_cvx.campaign.value_bound import lagrangian_bound
from sdc_cvx.inputs.campaign import Campaign
from sdc_cvx.inputs.synthetic import sso_catalog
from sdc_cvx.milp.types import SolverOptions
from sdc_cvx.solution import RunStatus
from tests.campaign.bruteforce import advanced, value_optimum
from tests.planner.test_enumeration import solver_plan_checked

GRID_TOL_MPS = 0.05  # the mission brute force's grid error per mission


@dataclass(frozen=True)
class Case:
    name: str
    size: int
    seed: int
    launch_days: tuple
    ranges: tuple
    tmax: tuple
    budgets: tuple
    rule: str = "table3"

    def catalog(self):
        return sso_catalog(self.size, seed=self.seed, inclination_spread_deg=0.8)

    def values(self) -> dict:
        rng = np.random.default_rng(self.seed)
        return {k: float(rng.integers(1, 10)) for k in self.catalog().ids}

    def campaign(self) -> Campaign:
        return Campaign.of(self.launch_days, Mission(drift_inclination=self.rule),
                           n=[list(r) for r in self.ranges], tmax_days=list(self.tmax),
                           objective="max-value", dv_budget_mps=list(self.budgets),
                           values=self.values())  # fmt: skip


@functools.cache
def brute_force(case: Case):
    """The brute force's most valuable campaign of ``case`` (computed once per case: each
    takes seconds, and three tests compare with it)."""
    return value_optimum(case.catalog(), case.launch_days, case.ranges, case.tmax,
                         case.budgets, case.values(), case.rule)  # fmt: skip


CASES = [
    pytest.param(Case("ranges-2-3", 8, 7, (0.0, 365.25), ((2, 3), (2, 3)), (200.0, 200.0),
                      (300.0, 250.0)), id="ranges-2-3",
                 marks=pytest.mark.slow),
    pytest.param(Case("budget-binds-free", 8, 11, (0.0, 200.0), ((2, 3), (2, 2)),
                      (250.0, 150.0), (260.0, 200.0), rule="free"), id="budget-binds-free"),
    pytest.param(Case("a-mission-of-three", 8, 23, (0.0, 365.25), ((2, 3), (2, 3)),
                      (300.0, 300.0), (400.0, 250.0)), id="a-mission-of-three",
                 marks=pytest.mark.slow),
    pytest.param(Case("two-of-three", 8, 23, (0.0, 365.25), ((2, 3), (2, 3)),
                      (300.0, 300.0), (550.0, 300.0)), id="two-of-three",
                 marks=pytest.mark.slow),
]  # fmt: skip


@pytest.mark.parametrize("case", CASES)
def test_the_most_valuable_campaign_is_the_brute_forces(case):
    best = brute_force(case)
    assert np.isfinite(best.value) and best.margin_mps > 2 * GRID_TOL_MPS  # not on the edge
    sol = solve_campaign(case.catalog(), case.campaign(), workers=1)
    found = f"solver {[m.path for m in sol.missions]}; brute {[sorted(s) for s in best.sets]}"
    assert sol.status == RunStatus.OPTIMAL and sol.certified, found
    assert sol.value == pytest.approx(best.value) and sol.value_bound == pytest.approx(best.value)
    assert sol.total_dv_mps <= best.dv_mps * (1 + 1e-3) + 1e-6, found
    assert sol.total_dv_mps >= best.dv_mps - len(case.ranges) * GRID_TOL_MPS, found
    assert sol.lower_bound_mps <= best.dv_mps + 1e-6
    removed = [d for m in sol.missions for d in m.path]
    assert len(removed) == len(set(removed))
    for day, (low, high), tmax, budget, mission in zip(
            case.launch_days, case.ranges, case.tmax, case.budgets, sol.missions, strict=True):
        assert low <= len(mission.path) <= high and mission.total_dv_mps <= budget + 1e-9
        solver_plan_checked(mission, advanced(case.catalog(), day), tmax, case.rule)


@pytest.mark.parametrize("case", CASES[1:3])  # the two where the bound rules a count out
def test_the_narrowed_enumeration_finds_the_brute_forces_campaign(case, monkeypatch):
    """With no share of the time for the plain enumeration, the Lagrangian rounds, then the
    enumeration narrowed by their bound and prices (every count, not only where that is
    faster), give the same campaign as the brute force (``campaign/value_bound.py``: the
    narrowing drops no mission that matters)."""
    from sdc_cvx.campaign import value, value_bound

    monkeypatch.setattr(value, "PLAIN_SHARE", 0.0)
    monkeypatch.setattr(value_bound, "NARROW_ONLY_SUBSETS", False)  # every count narrowed
    best = brute_force(case)
    lines: list[str] = []
    sol = solve_campaign(case.catalog(), case.campaign(), workers=1, time_limit_s=3600.0,
                         log=lines.append)  # fmt: skip
    assert any("value bound, round 1" in line for line in lines)
    assert sol.status == RunStatus.OPTIMAL and sol.value == pytest.approx(best.value)
    assert sol.value_bound == pytest.approx(best.value)
    assert sol.total_dv_mps <= best.dv_mps * (1 + 1e-3) + 1e-6
    assert best.dv_mps - len(case.ranges) * GRID_TOL_MPS <= sol.total_dv_mps
    assert sol.lower_bound_mps <= best.dv_mps + 1e-6


@pytest.mark.parametrize("case", CASES)
def test_the_lagrangian_bound_is_above_the_brute_forces_optimum(case):
    """The rounds' bound alone (before any enumeration) is a proof: never below the most
    value the brute force finds, and every mission they found flies within its budget."""
    best = brute_force(case)
    catalog, campaign = case.catalog(), case.campaign()
    values = campaign.value_of(catalog.ids)
    run = lambda tasks: [price(launch, **kwargs) for launch, kwargs in tasks]  # noqa: E731
    bound = lagrangian_bound(Launch.all_of(campaign, catalog), campaign, values,
                             solver=SolverOptions(), deadline=np.inf, say=lambda _: None,
                             stop=lambda: False, run=run, best_value=lambda _: -np.inf,
                             max_rounds=4)  # fmt: skip
    assert best.value <= bound.proven + 1e-9 and bound.proven <= bound.upper
    removable = sum(high for _, high in case.ranges)  # the cardinality bound, by hand
    assert bound.most == pytest.approx(sum(sorted(values)[-removable:]))
    assert np.isfinite(bound.upper) and bound.rounds >= 1
    for (k, debris), column in bound.columns.items():
        assert column.dv_mps <= case.budgets[k] + 1e-9 and len(set(debris)) == len(debris)


def test_debris_and_counts_ruled_out_by_their_value_alone():
    """Worked by hand: values 10, 8, 6, 1, 0.5, -3 and missions of at most 2 and 1 debris
    (three in all, worth at most 24).  To reach 20, every campaign needs the three most
    valuable (10 + 8 = 18 < 20), so a debris worth under 2 is never in one (w + 24 - 6 < 20)
    and the launches fly 2 and 1; to reach 17, two debris may do (18 >= 17)."""
    from sdc_cvx.campaign.value_bound import cardinality_narrowing

    values = np.array([10.0, 8.0, 6.0, 1.0, 0.5, -3.0])
    excluded, fewest = cardinality_narrowing(values, [2, 1], 20.0)
    assert excluded.tolist() == [3, 4, 5] and fewest == [2, 1]
    excluded, fewest = cardinality_narrowing(values, [2, 1], 17.0)
    assert excluded.tolist() == [] and fewest == [1, 0]
    excluded, fewest = cardinality_narrowing(values, [2, 1], 24.0)  # exactly the top three
    assert excluded.tolist() == [3, 4, 5] and fewest == [2, 1]


@pytest.mark.slow
def test_when_few_debris_matter_the_value_rules_keep_the_brute_forces_campaign(monkeypatch):
    """Values that make the debris of a campaign of the most debris the brute force finds
    worth 50 and every other 1 (or nothing): the best campaign is then worth the most any
    could be, the values alone rule debris and counts out before the narrowed enumeration,
    and its answer is still the brute force's with these values."""
    from sdc_cvx.campaign import value
    from tests.campaign.bruteforce import campaigns_of, value_options

    case = CASES[-1].values[0]  # its budgets let two missions of three fly
    options, _ = value_options(case.catalog(), case.launch_days, case.ranges, case.tmax,
                               case.budgets, case.rule)  # fmt: skip
    first = max(campaigns_of(options, {}), key=lambda c: (sum(map(len, c[2])), -c[1]))
    heavy = {d: 50.0 for chosen in first[2] for d in chosen}
    ids = case.catalog().ids
    worth = {d: heavy.get(d, 1.0 if k % 2 else 0.0) for k, d in enumerate(ids)}
    best = max(campaigns_of(options, worth), key=lambda c: (c[0], -c[1]))
    monkeypatch.setattr(value, "PLAIN_SHARE", 0.0)
    lines: list[str] = []
    campaign = Campaign.of(case.launch_days, Mission(drift_inclination=case.rule),
                           n=[list(r) for r in case.ranges], tmax_days=list(case.tmax),
                           objective="max-value", dv_budget_mps=list(case.budgets),
                           values=worth)  # fmt: skip
    sol = solve_campaign(case.catalog(), campaign, workers=1, time_limit_s=3600.0,
                         log=lines.append)  # fmt: skip
    said = [line for line in lines if "ruled out by their value" in line]
    assert said and not said[0].split(": ")[1].startswith("0 debris"), said
    assert sol.status == RunStatus.OPTIMAL and sol.value == pytest.approx(best[0])
    assert sol.total_dv_mps == pytest.approx(best[1], abs=len(case.ranges) * GRID_TOL_MPS)


def test_the_enumeration_runs_on_the_campaign_executor():
    """Each launch's searches go to the executor given (a pool or a Dask cluster: issue 27,
    2 workers faster than 1), one count at a time, with this process's answer."""
    case = CASES[0].values[0]
    sent: list[tuple[int, int]] = []

    class Counted(cf.ThreadPoolExecutor):
        def submit(self, fn, /, *args, **kwargs):
            sent.append((args[0].index, args[0].mission.n))
            return super().submit(fn, *args, **kwargs)

    with Counted(max_workers=1) as pool:
        there = solve_campaign(case.catalog(), case.campaign(), executor=pool)
    here = solve_campaign(case.catalog(), case.campaign(), workers=1)
    assert sent == [(0, 2), (1, 2), (0, 3), (1, 3)]
    assert there.status == here.status and there.value == here.value
    assert there.total_dv_mps == pytest.approx(here.total_dv_mps)


def test_a_budget_no_mission_fits_is_proven_infeasible():
    catalog = sso_catalog(8, seed=7, inclination_spread_deg=0.8)
    campaign = Campaign.of([0.0, 365.25], Mission(n=2, tmax_days=200.0), objective="max-value",
                           dv_budget_mps=1.0)  # fmt: skip
    with pytest.raises(MissionInfeasible, match="fits its ΔV budget"):
        solve_campaign(catalog, campaign, workers=1)


def test_max_value_options_are_checked():
    from sdc_cvx import MissionError

    with pytest.raises(MissionError, match="dv_budget_mps"):
        Campaign.of([0.0], Mission(n=3), objective="max-value")
    with pytest.raises(MissionError, match="n ranges"):
        Campaign.of([0.0], Mission(n=3), n=[[4, 3]], objective="max-value", dv_budget_mps=100)
    with pytest.raises(MissionError, match="objective must be one of"):
        Campaign.of([0.0], Mission(n=3), objective="max-dv")
    with pytest.raises(MissionError, match="for objective = 'max-value'"):
        Campaign.of([0.0], Mission(n=3), dv_budget_mps=100)


def test_values_that_name_no_candidate_are_refused():
    """Found as a user: a ranking read by its rank column instead of its NORAD ids named
    no candidate, and the campaign removed a value of 0 as if it were an answer."""
    from sdc_cvx import MissionError

    ranked = Campaign.of([0.0], Mission(n=2), objective="max-value", dv_budget_mps=100,
                         values={"1": 5.0, "2": 3.0})  # fmt: skip
    with pytest.raises(MissionError, match="none of the 2 ids of the values .* is a candidate"):
        ranked.check_candidates(["16182", "17590", "17974"])
    ranked.check_candidates(["16182", "2"])  # one named is enough: the others are worth 0


def test_values_with_a_least_dv_campaign_are_refused(tmp_path):
    """Found as a user: [catalog] values beside a min-dv campaign were silently unused."""
    from sdc_cvx.study.scenario import Scenario, ScenarioError

    (tmp_path / "values.csv").write_text("id,value\n1,2\n")
    (tmp_path / "s.toml").write_text('[catalog]\nvalues = "values.csv"\n'
                                     "[campaign]\nlaunch_days = [0.0, 100.0]\nn = 2\n")
    with pytest.raises(ScenarioError, match="catalog.values is for objective = 'max-value'"):
        Scenario.load(tmp_path / "s.toml")


@pytest.mark.slow
def test_a_max_value_scenario_runs_from_the_command_line(tmp_path):
    """[catalog] values (a ranking with its own column names) and [campaign] objective,
    n ranges and dv_budget_mps, through a real subprocess: campaign.json says the value,
    its bound and the objective; the scenario written back reads the same."""
    import json
    import subprocess
    import sys

    from sdc_cvx.study.scenario import Scenario
    from tests.conftest import REPO

    (tmp_path / "ranking.csv").write_text("rank,norad,score\n1,5,10\n2,8,7\n3,2,6\n4,6,1\n")
    (tmp_path / "value.toml").write_text(
        '[catalog]\nvalues = "ranking.csv"\nvalues_columns = ["norad", "score"]\n'
        "[mission]\ntmax_days = 365.25\n"
        '[campaign]\nobjective = "max-value"\nlaunch_days = [0.0, 365.25]\n'
        "n = [[2, 3], [2, 2]]\ndv_budget_mps = 150.0\n")  # fmt: skip
    done = subprocess.run([sys.executable, "-m", "sdc_cvx", "campaign",
                           str(tmp_path / "value.toml"), "--pareto", "4",
                           "--out", str(tmp_path / "out")],
                          capture_output=True, text=True, cwd=REPO, timeout=300)  # fmt: skip
    assert done.returncode == 0, done.stderr
    summary = json.loads((tmp_path / "out" / "campaign.json").read_text())
    assert summary["objective"] == "max-value" and summary["status"] == "optimal"
    assert summary["value"] == summary["value_bound"] > 0
    assert all(m["total_dv_mps"] <= 150.0 and 2 <= len(m["path"]) <= 3
               for m in summary["missions"])  # fmt: skip
    assert (tmp_path / "out" / "pareto.png").is_file()
    front = (tmp_path / "out" / "pareto.csv").read_text().splitlines()
    assert front[0] == "target_value,value,dv_mps,dv_bound_mps,missions" and len(front) >= 2
    again = Scenario.load(tmp_path / "value.toml")
    written = tmp_path / "again.toml"
    written.write_text(again.to_toml())
    assert Scenario.load(written).campaign == again.campaign


@pytest.mark.slow
def test_the_campaigns_of_value_against_dv_are_the_brute_forces_front():
    """``pareto``: each campaign is the cheapest of at least its target value (the brute
    force's, to its grid), none dominates another, and the last is the most valuable."""
    from tests.campaign.bruteforce import campaigns_of, value_options

    case = CASES[-1].values[0]  # two-of-three: five campaigns from 84 to 577 m/s
    options, margin = value_options(case.catalog(), case.launch_days, case.ranges, case.tmax,
                                    case.budgets, case.rule)  # fmt: skip
    assert margin > 2 * GRID_TOL_MPS
    every = list(campaigns_of(options, case.values()))
    sol = solve_campaign(case.catalog(), case.campaign(), workers=1, pareto=5)
    front = sorted(sol.pareto, key=lambda row: row["value"])
    assert len(front) >= 3
    for row in front:
        cheapest = min(dv for worth, dv, _ in every if worth >= row["target_value"] - 1e-9)
        assert row["dv_mps"] == pytest.approx(cheapest, abs=len(case.ranges) * GRID_TOL_MPS)
        assert row["dv_bound_mps"] <= cheapest + 1e-6 and row["value"] >= row["target_value"]
    values, costs = [r["value"] for r in front], [r["dv_mps"] for r in front]
    assert values == sorted(values) and costs == sorted(costs)  # more value costs more
    assert front[-1]["value"] == pytest.approx(sol.value)
    with pytest.raises(MissionError, match="needs objective = 'max-value'"):
        solve_campaign(case.catalog(), Campaign.of([0.0], Mission(n=2)), pareto=3)


def test_a_front_whose_enumeration_was_stopped_claims_no_bound(monkeypatch):
    """Found as a user: with the enumeration of the missions within budget stopped by the
    time limit, pareto.csv still gave each campaign a proven ΔV bound (and the figure's
    legend said so).  Every point's bound is then unknown, and a note says why; the
    front and the one step of a max-value search reach campaign.json and history.csv."""
    import json

    from sdc_cvx.campaign import value as module

    real = module.enumerate_missions

    def stopped(*args, **kwargs):  # every mission found, but told incomplete
        columns, undecided, _ = real(*args, **kwargs)
        return columns, undecided, False

    monkeypatch.setattr(module, "enumerate_missions", stopped)
    case = CASES[-1].values[0]
    sol = solve_campaign(case.catalog(), case.campaign(), workers=1, pareto=5)
    assert sol.pareto and all(row["dv_bound_mps"] is None for row in sol.pareto)
    assert any("front's ΔV bounds are not proven" in note for note in sol.notes)
    assert not sol.certified and sol.lower_bound_mps is None
    saved = json.loads(sol.to_json())
    assert len(saved["pareto"]) == len(sol.pareto)
    assert all(row["dv_bound_mps"] is None for row in saved["pareto"])
    history = sol.history_frame()
    assert len(history) == 1 and history["upper_mps"].iloc[0] == pytest.approx(sol.total_dv_mps)


@pytest.mark.slow
def test_a_front_after_the_narrowed_enumeration_claims_bounds_only_where_it_has_them(
        monkeypatch):  # fmt: skip
    """Review of the bound (issue 48, item 21): the narrowed enumeration holds only the
    missions of campaigns worth at least the best found before it (21 here), so the
    front's ΔV bounds of lower targets (18 to 20) are not proven; from 21 on they are,
    and they are below the brute force's cheapest campaign of each target."""
    from sdc_cvx.campaign import value
    from tests.campaign.bruteforce import campaigns_of, value_options

    monkeypatch.setattr(value, "PLAIN_SHARE", 0.0)
    case = CASES[-1].values[0]
    lines: list[str] = []
    sol = solve_campaign(case.catalog(), case.campaign(), workers=1, pareto=8,
                         time_limit_s=3600.0, log=lines.append)  # fmt: skip
    said = [line for line in lines if "to beat " in line]
    assert said, lines
    narrowed_to = float(said[0].split("to beat ")[1].split(":")[0])
    front = sorted(sol.pareto, key=lambda row: row["value"])
    below = [row for row in front if row["target_value"] < narrowed_to - 1e-9]
    above = [row for row in front if row["target_value"] >= narrowed_to - 1e-9]
    assert below and above, (narrowed_to, front)
    assert all(row["dv_bound_mps"] is None for row in below), below
    assert any(f"values below {narrowed_to:g} are not proven" in note for note in sol.notes)
    options, margin = value_options(case.catalog(), case.launch_days, case.ranges, case.tmax,
                                    case.budgets, case.rule)  # fmt: skip
    assert margin > 2 * GRID_TOL_MPS
    every = list(campaigns_of(options, case.values()))
    for row in above:
        cheapest = min(dv for worth, dv, _ in every if worth >= row["target_value"] - 1e-9)
        assert row["dv_bound_mps"] is not None and row["dv_bound_mps"] <= cheapest + 1e-6
    assert sol.status == RunStatus.OPTIMAL  # the most valuable campaign's bound holds


@pytest.mark.slow
def test_a_stopped_enumeration_returns_the_campaign_it_has_and_its_bound(monkeypatch):
    """A limit during the narrowed enumeration still returns the best campaign found,
    within the budgets: ``feasible``, no ΔV bound claimed, and the value bound the
    Lagrangian rounds proved before it (``campaign/value_bound.py``), above the brute
    force's optimum."""
    from sdc_cvx.campaign import value

    monkeypatch.setattr(value, "PLAIN_SHARE", 0.0)
    case = CASES[-1].values[0]
    lines: list[str] = []
    said = "mission 2 (launch day 365.25), n = 2: "
    sol = solve_campaign(case.catalog(), case.campaign(), workers=1, log=lines.append,
                         time_limit_s=3600.0,
                         stop=lambda: any(said in line for line in lines))  # fmt: skip
    best = brute_force(case)
    assert sol.status == RunStatus.FEASIBLE and not sol.certified
    assert sol.lower_bound_mps is None
    assert sol.value <= best.value + 1e-9 <= sol.value_bound + 2e-9
    for mission, (low, high), budget in zip(sol.missions, case.ranges, case.budgets,
                                            strict=True):  # fmt: skip
        assert low <= len(mission.path) <= high and mission.total_dv_mps <= budget + 1e-9
    assert not any("n = 3: " in line for line in lines)  # the enumeration stopped before


@pytest.mark.slow
@pytest.mark.parametrize("price", [2.0, 200.0])  # 18 for 84 m/s; 22 for 577 m/s
def test_value_per_dv_is_the_brute_forces_least_priced_campaign(price):
    """``objective = "value-per-dv"``: the least Σ ΔV − price · Σ value under the same
    budgets and ranges; a low price buys little value, a high one much."""
    from tests.campaign.bruteforce import campaigns_of, value_options

    case = CASES[-1].values[0]
    options, margin = value_options(case.catalog(), case.launch_days, case.ranges, case.tmax,
                                    case.budgets, case.rule)  # fmt: skip
    best = min(dv - price * worth for worth, dv, _ in campaigns_of(options, case.values()))
    campaign = Campaign.of(case.launch_days, Mission(drift_inclination=case.rule),
                           n=[list(r) for r in case.ranges], tmax_days=list(case.tmax),
                           objective="value-per-dv", dv_budget_mps=list(case.budgets),
                           values=case.values(), price_per_value_mps=price)  # fmt: skip
    sol = solve_campaign(case.catalog(), campaign, workers=1)
    assert sol.status == RunStatus.OPTIMAL
    priced = sol.total_dv_mps - price * sol.value
    assert priced == pytest.approx(best, abs=len(case.ranges) * GRID_TOL_MPS)
    assert sol.lower_bound_mps - price * sol.value <= best + 1e-6
    assert f"price x value = {priced:.2f} m/s" in sol.summary()
    with pytest.raises(MissionError, match="needs price_per_value_mps"):
        Campaign.of([0.0], Mission(n=3), objective="value-per-dv", dv_budget_mps=100)


def test_a_first_campaign_takes_the_most_valuable_debris_that_fly_with_one_taken_before():
    """campaign/value_start.pairable_by_value: by decreasing value, a debris joins only
    if a mission within budget removes it with one already taken."""
    from types import SimpleNamespace

    from sdc_cvx.campaign.value_start import pairable_by_value

    values = np.array([5.0, 4.0, 3.0, 2.0, 1.0, 0.0])
    missions = [SimpleNamespace(debris=d) for d in ((0, 1), (1, 3), (2, 4), (3, 5))]
    assert pairable_by_value(values, missions, 3) == [0, 1, 3]  # 2 flies with 4 only
    assert pairable_by_value(values, missions, 9) == [0, 1, 3]  # 5 is worth nothing
    assert pairable_by_value(values, [SimpleNamespace(debris=(0, 2, 4))], 3) == [0, 2, 4]


def test_a_first_campaigns_mission_of_a_sub_catalog_names_the_same_debris_in_the_catalog():
    """campaign/value_start._in_catalog: rows of the sub-catalog become the catalog's rows
    of the same ids; the injection orbit (the node past the rows) stays past them."""
    from sdc_cvx.campaign.pricing import Column
    from sdc_cvx.campaign.value_start import _in_catalog

    catalog = sso_catalog(8, seed=3)
    ids = ("S006", "S001", "S004")
    rows = [catalog.ids.index(k) for k in ids]
    sub = Column(launch=1, nodes=(3, 2, 0), debris=(0, 2), dv_mps=10.0, lower_mps=9.0,
                 schedule=None)  # fmt: skip
    full = _in_catalog(sub, rows, len(ids), len(catalog))
    assert [catalog.ids[k] for k in full.nodes[1:]] == ["S004", "S006"]
    assert full.nodes[0] == len(catalog)  # the injection orbit
    assert sorted(catalog.ids[k] for k in full.debris) == ["S004", "S006"]
    assert (full.launch, full.dv_mps, full.lower_mps) == (1, 10.0, 9.0)
