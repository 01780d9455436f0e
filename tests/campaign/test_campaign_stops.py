"""A campaign stopped early keeps its answer and says only what is known (issue 28, part 1).

Stopped by the caller (``stop``: the command line's Ctrl-C) or before any bound: the best
campaign in hand is returned, ``feasible``, with its gap or no bound at all, and its
folder and ``campaign.json`` are written (a bound not yet known is ``null``).
"""

from __future__ import annotations

import json
import signal
import subprocess
import sys
import time

import numpy as np
import pytest

from sdc_cvx import Mission, SolverFailure
from sdc_cvx.campaign.pricing import Pricing
from sdc_cvx.campaign.result import CampaignSolution
from sdc_cvx.campaign.search import shown_bound, solve_campaign
from sdc_cvx.inputs.campaign import Campaign
from sdc_cvx.inputs.synthetic import sso_catalog
from sdc_cvx.solution import RunStatus
from tests.conftest import REPO, as_terminal_job


def stop_after(line: str, lines: list):
    """A ``stop`` that turns True once the search's log has said ``line``."""
    return lambda: any(line in said for said in lines)


@pytest.fixture(scope="module")
def catalog():
    return sso_catalog(9, seed=7, inclination_spread_deg=0.8)


def test_a_campaign_stopped_after_greedy_keeps_the_greedy_campaign(catalog, tmp_path):
    lines: list[str] = []
    campaign = Campaign.of([0.0, 365.25], Mission(n=3))
    answer = solve_campaign(catalog, campaign, workers=1, log=lines.append,
                            stop=stop_after("launches alone and greedy", lines))  # fmt: skip
    full = solve_campaign(catalog, campaign, workers=1)
    assert answer.status == RunStatus.FEASIBLE and not answer.certified
    assert any("interrupted" in note for note in answer.notes)
    assert answer.total_dv_mps >= full.total_dv_mps - 1e-6  # a campaign that flies
    # what is said of the bound is true: at most the optimum (or none)
    assert answer.lower_bound_mps is None or answer.lower_bound_mps <= full.total_dv_mps + 1e-6
    answer.save(tmp_path / "c", formats=())
    data = json.loads((tmp_path / "c" / "campaign.json").read_text())
    assert data["status"] == "feasible" and data["total_dv_mps"] == pytest.approx(
        answer.total_dv_mps)  # fmt: skip


def test_no_bound_is_null_and_a_poor_one_is_not_reported_below_zero(catalog):
    campaign = Campaign.of([0.0, 365.25], Mission(n=3))
    full = solve_campaign(catalog, campaign, workers=1)
    kwargs = {name: getattr(full, name) for name in CampaignSolution.__dataclass_fields__}
    unknown = CampaignSolution(**{**kwargs, "lower_bound_mps": shown_bound(-float("inf")),
                                  "status": RunStatus.FEASIBLE})  # fmt: skip
    data = json.loads(unknown.to_json())  # -inf once crashed the JSON writer
    assert data["lower_bound_mps"] is None and data["gap_mps"] is None and data["gap_rel"] is None
    assert data["greedy_gap_rel"] is None
    assert "no bound yet" in unknown.summary()
    poor = CampaignSolution(**{**kwargs, "lower_bound_mps": shown_bound(-99253.56),
                               "status": RunStatus.FEASIBLE})  # fmt: skip
    assert poor.lower_bound_mps == 0.0  # every mission costs at least 0
    assert "no useful bound yet" in poor.summary() and "-99" not in poor.summary()
    figures = poor.plot()
    low, _ = figures["bound"].axes[0].get_ylim()
    assert low > -0.5 * full.total_dv_mps  # no axis down to the artificial bound


def test_greedy_is_measured_above_the_bound_relative_to_the_bound(catalog):
    full = solve_campaign(catalog, Campaign.of([0.0, 365.25], Mission(n=3)), workers=1)
    greedy, bound = full.greedy.dv_mps, full.lower_bound_mps
    assert full.greedy_gap_rel() == pytest.approx((greedy - bound) / bound)
    assert f"{100 * (greedy - bound) / bound:.2f} % above the bound" in full.summary()


SCENARIO = """
[catalog]
path = "{catalog}"

[mission]
n = 3
tmax_days = 365.25

[campaign]
launch_days = [0, 365.25, 730.5]
"""


def start_campaign(folder, catalog, scenario_text: str, *args) -> subprocess.Popen:
    """``python -m sdc_cvx campaign`` on ``catalog`` (written as a CSV) in ``folder``, into
    ``folder/out``, with Ctrl-C as a terminal's foreground job has it."""
    csv = folder / "debris.csv"
    catalog.frame[["id", "a_km", "e", "inc_deg", "raan_deg"]].to_csv(csv, index=False)
    scenario = folder / "c.toml"
    scenario.write_text(scenario_text.format(catalog=csv))
    return subprocess.Popen([sys.executable, "-m", "sdc_cvx", "campaign", str(scenario),
                             "--out", str(folder / "out"), *args], cwd=folder,
                            stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True,
                            env={"PYTHONPATH": str(REPO), "PATH": "/usr/bin:/bin"},
                            preexec_fn=as_terminal_job)  # fmt: skip


def wait_for(run: subprocess.Popen, live, words: str, seconds: float = 300.0) -> None:
    """Until the live log says ``words`` (or the run ends, or ``seconds`` pass)."""
    deadline = time.monotonic() + seconds
    while time.monotonic() < deadline and run.poll() is None:
        if live.exists() and words in live.read_text():
            return
        time.sleep(0.02)


@pytest.mark.slow
def test_ctrl_c_on_campaign_keeps_the_campaign_in_hand(tmp_path, catalog):
    """Through a real process: one Ctrl-C once a campaign is held ends the search at its
    next step; the folder is written, feasible with its gap (or optimal if it got there)."""
    out, live = tmp_path / "out", tmp_path / "out.log"
    run = start_campaign(tmp_path, catalog, SCENARIO, "--workers", "1")
    wait_for(run, live, "launches alone and greedy")
    run.send_signal(signal.SIGINT)
    stdout, stderr = run.communicate(timeout=600)
    assert run.returncode == 0, stderr
    data = json.loads((out / "campaign.json").read_text())
    assert data["status"] in ("feasible", "optimal") and len(data["missions"]) == 3
    if data["status"] == "feasible":
        assert any("interrupted" in note for note in data["notes"])
        assert "interrupted" in stdout
    assert not live.exists()


@pytest.mark.slow
def test_ctrl_c_before_any_campaign_stops_at_once_and_says_so(tmp_path, catalog):
    """Found as a user: a Ctrl-C during the launches alone was said ("stopping at the next
    step") but the campaign went on with the other launches, greedy and a whole round.
    Now the launches not yet priced are not, greedy and the rounds are skipped, and the
    command ends as interrupted (exit 130), not as a solver failure."""
    live = tmp_path / "out.log"
    run = start_campaign(tmp_path, catalog, SCENARIO, "--workers", "1")
    wait_for(run, live, "pricing: 1 of 3 done")
    run.send_signal(signal.SIGINT)
    _, stderr = run.communicate(timeout=600)
    assert run.returncode == 130, stderr
    assert "interrupted before any campaign: nothing written" in stderr
    assert "Traceback" not in stderr and not (tmp_path / "out").exists()
    said = live.read_text() if live.exists() else ""
    assert "greedy campaign:" not in said and "round 1 (" not in said


def test_an_earlier_campaign_folder_with_files_of_the_user_is_refused(catalog, tmp_path):
    """Files of the user inside a mission folder, or a mission folder the earlier
    campaign.json does not list, are never deleted by a new campaign into that folder."""
    from sdc_cvx.report.campaign_folder import campaign_folder_problem

    answer = solve_campaign(catalog, Campaign.of([0.0, 365.25], Mission(n=3)), workers=1)
    folder = tmp_path / "out"
    answer.save(folder, formats=())
    assert campaign_folder_problem(folder) is None  # an earlier campaign folder: replaced
    answer.save(folder, formats=())
    (folder / "mission_01" / "notes.txt").write_text("keep")
    problem = campaign_folder_problem(folder)
    assert problem is not None and "mission_01/notes.txt" in problem
    with pytest.raises(FileExistsError):
        answer.save(folder, formats=())
    assert (folder / "mission_01" / "notes.txt").read_text() == "keep"
    (folder / "mission_01" / "notes.txt").unlink()
    (folder / "mission_09").mkdir()
    (folder / "mission_09" / "solution.json").write_text("{}")  # not one of the campaign's
    problem = campaign_folder_problem(folder)
    assert problem is not None and "mission_09" in problem
    with pytest.raises(FileExistsError):
        answer.save(folder, formats=())
    assert (folder / "mission_09" / "solution.json").read_text() == "{}"


def test_mission_folders_say_what_they_are(catalog, tmp_path):
    """Issue 28, 1.7: each mission folder's run.log points to the campaign's log, its
    figures say which mission and launch day, and it draws no empty search history."""
    answer = solve_campaign(catalog, Campaign.of([0.0, 365.25], Mission(n=3)), workers=1)
    answer.save(tmp_path / "c", formats=("svg",))
    second = tmp_path / "c" / "mission_02"
    log = (second / "run.log").read_text()
    assert "mission 2 of the campaign, launched on day 365.25" in log
    assert "../campaign.log" in log and " -> ".join(answer.missions[1].path) in log
    assert "launched on day 365.25" in (second / "orbits.svg").read_text()
    assert not (second / "iterations.svg").exists()  # the campaign's bound.svg draws it
    assert not (second / "iterations.csv").exists()  # was a header alone: history.csv tells
    assert (tmp_path / "c" / "bound.svg").exists() and (tmp_path / "c" / "history.csv").exists()


def test_a_default_run_tells_its_search_in_iterations_csv(tmp_path):
    """A certified search that needs no relaxation round wrote a header-only table."""
    import pandas as pd

    from sdc_cvx import Catalog, solve

    solution = solve(Catalog.paper_case(), Mission(n=3))
    solution.save(tmp_path / "r", formats=())
    table = pd.read_csv(tmp_path / "r" / "iterations.csv")
    assert len(table) >= 1 and (table["status"] == "bound").all()
    assert table["dv_true_mps"].dropna().iloc[-1] == pytest.approx(solution.total_dv_mps)


@pytest.mark.slow
@pytest.mark.parametrize("after_s", [0.0, 1.0])
def test_a_second_ctrl_c_leaves_no_noise_about_leaked_semaphores(tmp_path, after_s):
    """Issue 28, 3.3: after a pool stopped at once, multiprocessing's resource tracker
    printed 'There appear to be 5 leaked semaphore objects to clean up at shutdown'.  And
    stopped while its fork server still started (``after_s`` 0), the fork server outlived
    the command with its stderr open: reading it to the end took minutes."""
    run = start_campaign(tmp_path, sso_catalog(60, seed=3), SCENARIO.replace("n = 3", "n = 4"),
                         "--workers", "2")  # fmt: skip
    wait_for(run, tmp_path / "out.log", "each launch alone")
    time.sleep(after_s)  # 1 s: the pool's workers at work
    if run.poll() is not None:
        pytest.skip("the campaign ended before the Ctrl-C")
    run.send_signal(signal.SIGINT)
    time.sleep(0.3)
    run.send_signal(signal.SIGINT)  # the second: at once
    _, stderr = run.communicate(timeout=60)  # to the end of stderr: no process left with it
    assert run.returncode == 130, stderr
    assert "leaked semaphore" not in stderr and "Traceback" not in stderr


def test_a_pricing_that_waited_for_a_worker_counts_the_wait_against_its_limit(catalog):
    """Five launches on two workers: the last ones wait; their limit is what is left when
    they start, not the whole of it again (GTOC9: a search given 8 s ran 12 s)."""
    from sdc_cvx.campaign.pricing import Launch, price

    launch = Launch(0, 0.0, Mission(n=3), catalog)
    fresh = price(launch, time_limit_s=30.0, sent_at=time.time())
    assert fresh.status == "optimal"
    waited = price(launch, time_limit_s=30.0, sent_at=time.time() - 31.0)
    assert waited.status == "no_plan" and not waited.columns


def test_each_pricing_of_a_round_has_its_share_from_when_it_starts(catalog):
    """A round of column generation: each pricing's limit is its share of a quarter of the
    time left, and a pricing that waited for a worker still has all of it (its share was
    counted from the round's start: the last of 50 pricings on two workers had waited
    past it and proved nothing, GTOC9-all).  Its floor is 10 s, within the time left."""
    from sdc_cvx.campaign.min_dv import ROUND_SHARE, CampaignSearch
    from sdc_cvx.milp.types import SolverOptions

    handed: list[dict] = []

    def run(tasks):
        handed.extend(kwargs for _, kwargs in tasks)
        return []

    campaign = Campaign.of([0.0, 100.0, 200.0, 300.0], Mission(n=2))
    search = CampaignSearch(catalog, campaign, SolverOptions(), 1e-3,
                            time.perf_counter() + 800.0, lambda line: None, run)  # fmt: skip
    search.at_once = 2  # four launches: two waves
    search.price_all([(launch, {}) for launch in search.variants], round_share=ROUND_SHARE)
    assert len(handed) == 4
    for kwargs in handed:  # 800 s left, two waves: a quarter of 400 s each
        assert kwargs["time_limit_s"] == pytest.approx(ROUND_SHARE * 400.0, rel=1e-3)
        assert kwargs["least_s"] == kwargs["time_limit_s"]
    handed.clear()
    search.deadline = time.perf_counter() + 30.0  # the floor, but never past the time left
    search.price_all([(launch, {}) for launch in search.variants], round_share=ROUND_SHARE)
    assert all(k["least_s"] == pytest.approx(10.0, rel=1e-3) for k in handed)
    handed.clear()
    search.deadline = time.perf_counter() + 12.0
    search.price_all([(launch, {}) for launch in search.variants], round_share=ROUND_SHARE)
    assert all(k["least_s"] == pytest.approx(6.0, rel=1e-2) for k in handed)


def test_a_gap_too_wide_to_enumerate_is_said_and_not_closed(catalog):
    """The closing step enumerates every mission within the gap of its launch's best; a gap
    of a quarter of the plan or more would be about every mission (GTOC9-all: 2 GB a
    worker, past the time limit), so it is not started, and the notes say why."""
    from sdc_cvx.campaign.min_dv import CLOSING_SHARE, CampaignSearch
    from sdc_cvx.milp.types import SolverOptions

    handed: list = []
    campaign = Campaign.of([0.0, 100.0], Mission(n=2))
    search = CampaignSearch(catalog, campaign, SolverOptions(), 1e-3,
                            time.perf_counter() + 60, lambda line: None,
                            lambda tasks: handed.extend(tasks) or [])  # fmt: skip
    search.plan, search.upper = ["a campaign"], 100.0
    search.lagrangian = 100.0 * (1 - CLOSING_SHARE) - 1.0
    search.close(np.zeros(len(catalog)), np.zeros(2))
    assert handed == [] and "the closing step was not run" in search.notes[-1]
    assert "(26% of the plan)" in search.notes[-1]


def test_launches_left_without_a_plan_by_the_time_limit_are_named_together(catalog):
    """Found as a new user (``--time-limit 15`` on a loaded machine): one launch's search
    had found no mission in its share, and the error named that launch alone, as if it
    were the campaign's only problem.  Every launch without a plan is named, with the
    time spent, and nothing is claimed infeasible."""
    from sdc_cvx.campaign.min_dv import CampaignSearch
    from sdc_cvx.campaign.pricing import Column, Pricing
    from sdc_cvx.errors import SolverFailure
    from sdc_cvx.milp.types import SolverOptions

    def run(tasks):  # launches 1 and 3 found nothing in their share of the time
        return [Pricing(launch.index, (), -np.inf, np.inf, "no_plan", 1.0, (), False)
                if launch.index in (0, 2) else
                Pricing(launch.index, (Column(launch.index, (0, 1), (0, 1), 12.0, 10.0, None),),
                        10.0, 12.0, "feasible", 1.0, (), False)
                for launch, _ in tasks]  # fmt: skip

    campaign = Campaign.of([0.0, 100.0, 200.0], Mission(n=2))
    search = CampaignSearch(catalog, campaign, SolverOptions(), 1e-3,
                            time.perf_counter() + 30, lambda line: None, run)  # fmt: skip
    with pytest.raises(SolverFailure) as raised:
        search.launches_alone()
    said = str(raised.value)
    assert said.startswith("mission 1 (launch day 0) and mission 3 (launch day 200): ")
    assert "mission 2" not in said and "allow more time" in said


def test_the_column_generation_stops_where_the_gap_left_is_the_integer_gap(catalog):
    """GTOC9-all: rounds 10-15 (2 minutes each) raised the bound from 5473.76 to 5483.23
    m/s under an LP of 5489.30 against a plan of 9560.46 m/s, and the dive after them had
    50 s left.  Where the gap is too wide to close and the LP (not boxed) is within 1 % of
    that gap above the bound, the rounds stop; not where the gap could be closed, nor
    while the box binds or the LP needs its artificial columns."""
    from sdc_cvx.campaign.master import MasterLP
    from sdc_cvx.campaign.min_dv import CampaignSearch
    from sdc_cvx.milp.types import SolverOptions

    def lp(value, boxed=0.0, artificial=0.0):
        return MasterLP(value, np.zeros(2), np.zeros(len(catalog)), np.zeros(0), artificial,
                        boxed)  # fmt: skip

    search = CampaignSearch(catalog, Campaign.of([0.0, 100.0], Mission(n=2)), SolverOptions(),
                            1e-3, np.inf, lambda line: None, lambda tasks: [])  # fmt: skip
    search.plan, search.upper, search.lagrangian = ["a campaign"], 9560.46, 5473.76
    assert search.integer_gap(lp(5489.96))  # 16.20 m/s of a 4086.70 m/s gap
    assert not search.integer_gap(lp(5520.0))  # 46.24 m/s: 1.1 % of the gap
    assert not search.integer_gap(lp(5489.96, boxed=1.0))
    assert not search.integer_gap(lp(5489.96, artificial=0.5))
    search.upper = 7000.0  # a gap of 22 % of the plan: the closing step runs instead
    assert not search.integer_gap(lp(5474.0))


def test_the_launches_alone_share_the_time_left_and_none_runs_past_the_deadline(catalog):
    """Found as a user (issue 48, item 12): ``--time-limit 60`` on a GTOC9 campaign of
    three launches with ``n = [[2, 10]]`` took 121 s.  Its 27 pricings on 2 workers each
    got the whole time left at first (then each later one its share): now each has its
    share (a launch's fewest debris more: its plan is the first campaign's), the shares
    add up to the time left on the workers, the fewest of every launch go first, and
    every pricing is told the deadline (benchmarks/time_limit.py --ranges measures it)."""
    from sdc_cvx.campaign.min_dv import FEWEST_WEIGHT, CampaignSearch
    from sdc_cvx.milp.types import SolverOptions

    sent = []

    def run(tasks):  # what each pricing would be told, and no plan from any
        sent.extend(tasks)
        return [Pricing(launch.index, (), -np.inf, np.inf, "no_plan", 0.0, complete=False)
                for launch, _ in tasks]  # fmt: skip

    campaign = Campaign.of([0.0, 200.0, 400.0], Mission(tmax_days=300.0), n=[[2, 4]])
    limit = 60.0
    search = CampaignSearch(catalog, campaign, SolverOptions(), 1e-3,
                            time.perf_counter() + limit, lambda line: None, run)  # fmt: skip
    search.at_once = 2
    with pytest.raises(SolverFailure, match="before any plan"):
        search.launches_alone()
    assert len(sent) == 9
    counts = [launch.mission.n for launch, _ in sent]
    assert counts == sorted(counts) and counts[:3] == [2, 2, 2]
    limits = np.array([options["time_limit_s"] for _, options in sent])
    assert limits.sum() == pytest.approx(2 * limit, rel=1e-3)  # the two workers' time
    assert limits[:3] == pytest.approx(FEWEST_WEIGHT * limits[3:].mean(), rel=1e-6)
    assert all(options["least_s"] == options["time_limit_s"] for _, options in sent)
    deadline = {options["deadline_at"] for _, options in sent}
    assert len(deadline) == 1 and deadline.pop() == pytest.approx(time.time() + limit, abs=1.0)


def test_a_pricing_that_starts_after_the_deadline_returns_at_once(catalog):
    from sdc_cvx.campaign.pricing import Launch, price

    (launch,) = Launch.all_of(Campaign.of([0.0], Mission(n=3, tmax_days=300.0)), catalog)
    clock = time.perf_counter()
    result = price(launch, time_limit_s=30.0, least_s=30.0, deadline_at=time.time() - 0.1)
    assert time.perf_counter() - clock < 0.05
    assert result.status == "no_plan" and not result.complete and not result.columns
    assert "the time limit came before this pricing started" in result.notes
    # within its deadline, the least of its limit and the time to it
    clock = time.perf_counter()
    price(launch, time_limit_s=30.0, deadline_at=time.time() + 0.5)
    assert time.perf_counter() - clock < 5.0


@pytest.mark.slow
def test_the_header_says_the_search_may_run_up_to_its_share_of_the_limit(tmp_path):
    """Found as a user (issue 48, item 20): 'The search gets 117.4 s of the 120 s limit'
    read as how long the campaign would take; it stops sooner once proven."""
    (tmp_path / "c.toml").write_text("[mission]\ntmax_days = 365.25\n[campaign]\n"
                                     "launch_days = [0.0, 365.25]\nn = 2\n")  # fmt: skip
    done = subprocess.run([sys.executable, "-m", "sdc_cvx", "campaign", str(tmp_path / "c.toml"),
                           "--time-limit", "120", "--out", str(tmp_path / "out")],
                          capture_output=True, text=True, cwd=REPO, timeout=300)  # fmt: skip
    assert done.returncode == 0, done.stderr
    assert "The search may run up to" in done.stderr and "of the 120 s limit: it stops " \
        "sooner once the campaign is proven" in done.stderr, done.stderr  # fmt: skip
