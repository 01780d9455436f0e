"""Campaigns: one launch is ``run``, the [campaign] table, the campaign folder and command."""

from __future__ import annotations

import json
import subprocess
import sys

import pandas as pd
import pytest

from sdc_cvx import Catalog, Mission, MissionError, solve
from sdc_cvx.campaign.search import solve_campaign
from sdc_cvx.errors import ScenarioError
from sdc_cvx.inputs.campaign import Campaign
from sdc_cvx.inputs.synthetic import sso_catalog
from sdc_cvx.study.scenario import Scenario
from tests.conftest import REPO


def test_one_launch_is_the_single_mission():
    """K = 1 from day 0 is the mission ``run`` plans (same path, same ΔV, both certified)."""
    catalog, mission = Catalog.paper_case(), Mission(n=4)
    alone = solve(catalog, mission)
    campaign = solve_campaign(catalog, Campaign.of([0.0], mission), workers=1)
    assert campaign.missions[0].path == alone.path
    assert campaign.total_dv_mps == pytest.approx(alone.total_dv_mps, abs=0.01)
    assert campaign.certified and alone.certified
    assert campaign.lower_bound_mps <= alone.total_dv_mps + 1e-6
    assert alone.lower_bound_mps <= campaign.total_dv_mps + 1e-6


def test_a_later_launch_meets_the_raans_of_its_day():
    """A mission launched on day d starts from the RAANs a day-0 mission meets on day d."""
    catalog = sso_catalog(6, seed=4, inclination_spread_deg=0.8)
    later = catalog.advanced(100.0)
    rate = catalog.frame["raan_rate_deg_per_day"].to_numpy()  # the catalog's own Eq. 7 rates
    moved = (catalog.frame["raan_deg"].to_numpy() + 100.0 * rate) % 360.0
    assert later.frame["raan_deg"].to_numpy() == pytest.approx(moved, abs=1e-9)
    assert catalog.advanced(0.0) is catalog


@pytest.mark.parametrize(
    ("kwargs", "message"),
    [
        (dict(launch_days=[0.0, 0.0]), "increase strictly"),
        (dict(launch_days=[-1.0]), r"in \[0, 3652.5\]"),
        (dict(launch_days=[0.0, 365.25], n=[5]), "n has 1 values for 2 launch days"),
        (dict(launch_days=[0.0], n=[1]), "n must be >= 2"),
        # a mission ending 20 years after the start: launch day + tmax_days past 10 years
        (dict(launch_days=[3652.5], tmax_days=[3652.5]), r"ends by day 7305 .*after 3652.5"),
        (dict(launch_days=[0.0, 3600.0]), r"mission 2 ends by day 3965.25"),
    ],
)
def test_invalid_campaigns_are_refused(kwargs, message):
    days = kwargs.pop("launch_days")
    with pytest.raises(MissionError, match=message):
        Campaign.of(days, Mission(), **kwargs)


def test_single_mission_options_are_refused_in_a_campaign():
    with pytest.raises(MissionError, match="use must_remove"):
        Campaign.of([0.0, 365.25], Mission(must_include=("1",)))


def test_yearly_launches():
    campaign = Campaign.yearly(3, Mission(n=4), first_launch_day=10.0, tmax_days=[100, 200, 300])
    assert campaign.launch_days == (10.0, 375.25, 740.5)
    assert [m.tmax_days for m in campaign.missions] == [100, 200, 300]
    assert all(m.n == 4 for m in campaign.missions)


def write(tmp_path, text: str, name="campaign.toml"):
    path = tmp_path / name
    path.write_text(text)
    return path


def test_the_campaign_table_defaults_to_the_mission_table(tmp_path):
    path = write(
        tmp_path,
        "[mission]\nn = 3\ntmax_days = 200\n[campaign]\nmissions = 2\n"
        "period_days = 100\ntmax_days = [150, 250]\nmust_remove = ['5']\n",
    )
    campaign = Scenario.load(path).campaign
    assert campaign.launch_days == (0.0, 100.0)
    assert [m.n for m in campaign.missions] == [3, 3]
    assert [m.tmax_days for m in campaign.missions] == [150.0, 250.0]
    assert campaign.must_remove == ("5",)
    again = write(tmp_path, Scenario.load(path).to_toml(), "again.toml")
    assert Scenario.load(again) == Scenario.load(path)  # to_toml reads back the same


def test_ranges_and_remove_all_read_and_write_back(tmp_path):
    path = write(tmp_path, "[campaign]\nmissions = 2\nn = [[2, 3], [3, 4]]\nremove_all = true\n")
    campaign = Scenario.load(path).campaign
    assert campaign.remove_all and campaign.must_remove == ()
    assert [m.n for m in campaign.missions] == [3, 4]
    assert [campaign.fewest(k) for k in range(2)] == [2, 3]
    assert campaign.counts_text() == "2-3, 3-4"
    again = write(tmp_path, Scenario.load(path).to_toml(), "again.toml")
    assert Scenario.load(again) == Scenario.load(path)


@pytest.mark.parametrize(
    ("table", "message"),
    [
        ("launch_days = [0]\nremove_all = 'yes'", "campaign.remove_all"),
        ("launch_days = [0, 'x']", "campaign.launch_days must be a non-empty array of numbers"),
        ("missions = 2\nlaunch_days = [0]", "give launch_days, or missions"),
        ("n = 3", "needs launch_days"),
        ("launch_days = [0]\nn = 'five'", "campaign.n must be an integer or an array"),
        ("launch_days = [0]\nspeed = 1", "unknown key campaign.speed"),
        ("launch_days = [0, 365.25]\nn = [3]", "n has 1 values for 2 launch days"),
    ],
)
def test_bad_campaign_tables_name_the_key(tmp_path, table, message):
    path = write(tmp_path, f"[campaign]\n{table}\n")
    with pytest.raises(ScenarioError, match=message):
        Scenario.load(path)


SCENARIO = """
[catalog]
path = "{catalog}"
[mission]
n = 2
tmax_days = 150
[campaign]
launch_days = [0, 365.25]
"""


def small_catalog(tmp_path):
    frame = sso_catalog(7, seed=7, inclination_spread_deg=0.8).frame
    path = tmp_path / "debris.csv"
    frame[["id", "a_km", "e", "inc_deg", "raan_deg"]].to_csv(path, index=False)
    return path


def cli(*args, cwd):
    return subprocess.run([sys.executable, "-m", "sdc_cvx", *args], capture_output=True,
                          text=True, cwd=cwd, timeout=600,
                          env={"PYTHONPATH": str(REPO), "PATH": "/usr/bin:/bin"})  # fmt: skip


@pytest.mark.slow
def test_campaign_command_writes_the_campaign_folder(tmp_path):
    scenario = write(tmp_path, SCENARIO.format(catalog=small_catalog(tmp_path)))
    done = cli("campaign", str(scenario), "--out", "out", "--json", "--workers", "1",
               cwd=tmp_path)  # fmt: skip
    assert done.returncode == 0, done.stderr
    data = json.loads(done.stdout)  # --json: JSON only on stdout
    folder = tmp_path / "out"
    assert json.loads((folder / "campaign.json").read_text()) == data
    assert data["status"] == "optimal" and data["certified"] is True
    assert data["lower_bound_mps"] <= data["total_dv_mps"]
    assert data["gap_rel"] <= 1e-3
    assert [m["launch_day"] for m in data["missions"]] == [0, 365.25]
    assert sum(m["total_dv_mps"] for m in data["missions"]) == pytest.approx(data["total_dv_mps"])
    removed = [d for m in data["missions"] for d in m["path"]]
    assert len(removed) == len(set(removed)) == 4
    for mission in data["missions"]:
        run = json.loads((folder / mission["folder"] / "solution.json").read_text())
        assert run["path"] == mission["path"]
        assert run["total_dv_mps"] == pytest.approx(mission["total_dv_mps"])
        assert (folder / mission["folder"] / "legs.csv").is_file()
    table = pd.read_csv(folder / "missions.csv")
    assert list(table["path"]) == ["->".join(m["path"]) for m in data["missions"]]
    for name in ("timeline", "raan", "dv", "bound"):
        assert (folder / f"{name}.png").stat().st_size > 0
    log = (folder / "campaign.log").read_text()
    assert "greedy campaign" in log and "alone" in log
    assert not (tmp_path / "out.log").exists()  # the live log moved into the folder
    # an earlier campaign folder is replaced; a foreign non-empty folder is refused
    (tmp_path / "mine").mkdir()
    (tmp_path / "mine" / "notes.txt").write_text("keep")
    refused = cli("campaign", str(scenario), "--out", "mine", cwd=tmp_path)
    assert refused.returncode == 2 and "not an earlier campaign folder" in refused.stderr
    assert (tmp_path / "mine" / "notes.txt").read_text() == "keep"


@pytest.mark.slow
def test_campaign_command_infeasible_launch_exit_3(tmp_path):
    text = SCENARIO.format(catalog=small_catalog(tmp_path)).replace(
        "launch_days = [0, 365.25]", "launch_days = [0, 365.25]\ntmax_days = [150, 1]"
    )
    scenario = write(tmp_path, text)
    done = cli("campaign", str(scenario), "--out", "out", "--workers", "1", cwd=tmp_path)
    assert done.returncode == 3, done.stderr
    assert "mission 2 (launch day 365.25)" in done.stderr
    data = json.loads((tmp_path / "out" / "campaign.json").read_text())
    assert data["status"] == "infeasible" and data["missions"] == []
    assert "mission 2 (launch day 365.25)" in data["reason"]


def test_campaign_command_needs_a_campaign_table(tmp_path):
    scenario = write(tmp_path, "[mission]\nn = 3\n")
    done = cli("campaign", str(scenario), cwd=tmp_path)
    assert done.returncode == 2
    assert "no [campaign] table" in done.stderr
    assert "Traceback" not in done.stderr
