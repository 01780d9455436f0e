"""``solve_campaign`` from Python: its options checked as the command line checks them, and
a plain script without a main guard still runs (issue 28, 1.5)."""

from __future__ import annotations

import subprocess
import sys

import pytest

from sdc_cvx import Campaign, Catalog, Mission, solve_campaign
from sdc_cvx.errors import SdcError
from tests.conftest import REPO


@pytest.mark.parametrize("kwargs, words", [
    (dict(gap=2), "gap must be"),
    (dict(gap=-1), "gap must be"),
    (dict(gap="0.1"), "gap must be"),
    (dict(workers=0), "workers must be"),
    (dict(workers="two"), "workers must be"),
    (dict(workers=True), "workers must be"),
    (dict(solver={"backend": "HIGHS"}), "solver must be a SolverOptions"),
    (dict(time_limit_s=-5), "time_limit_s must be"),
    (dict(workers=2, scheduler="tcp://127.0.0.1:1"), "give one of"),
])  # fmt: skip
def test_bad_options_are_refused_with_an_sdc_error(kwargs, words):
    campaign = Campaign.yearly(2, Mission(n=2))
    with pytest.raises(SdcError, match=words):
        solve_campaign(Catalog.paper_case(), campaign, **kwargs)


SCRIPT = """
from sdc_cvx import Campaign, Catalog, Mission, solve_campaign

answer = solve_campaign(Catalog.paper_case(), Campaign.yearly(2, Mission(n=2)), workers=2)
print("total", round(answer.total_dv_mps, 2), answer.status)
"""


@pytest.mark.slow
def test_a_script_without_a_main_guard_prices_in_its_own_process(tmp_path):
    """Its pool's workers would import the script and start the campaign again
    (BrokenProcessPool): the launches are priced in the script's process, with a warning
    that says why and how to get the pool back."""
    script = tmp_path / "plan.py"
    script.write_text(SCRIPT)
    done = subprocess.run([sys.executable, str(script)], capture_output=True, text=True,
                          cwd=tmp_path, timeout=600,
                          env={"PYTHONPATH": str(REPO), "PATH": "/usr/bin:/bin"})  # fmt: skip
    assert done.returncode == 0, done.stderr
    assert "total" in done.stdout and "optimal" in done.stdout
    assert "line 4" in done.stderr and '__name__ == "__main__"' in done.stderr
    assert "Traceback" not in done.stderr


def test_options_a_campaign_does_not_use_are_said_not_silently_dropped():
    from sdc_cvx import SolverOptions
    from sdc_cvx.errors import IgnoredOptionWarning

    campaign = Campaign.yearly(2, Mission(n=2, dv_max_mps=800.0))
    with pytest.warns(IgnoredOptionWarning) as said:
        solve_campaign(Catalog.paper_case(), campaign, workers=1,
                       solver=SolverOptions(method="paper"))  # fmt: skip
    text = " ".join(str(w.message) for w in said)
    assert "solver.method = 'paper' is ignored" in text
    assert "mission.dv_max_mps = 800 is ignored" in text


@pytest.mark.slow
def test_run_on_a_campaign_scenario_says_it_plans_one_mission(tmp_path):
    scenario = tmp_path / "c.toml"
    scenario.write_text("[mission]\nn = 2\n\n[campaign]\nlaunch_days = [0, 365.25]\n")
    done = subprocess.run([sys.executable, "-m", "sdc_cvx", "run", str(scenario), "--quiet",
                           "--out", "out"], capture_output=True, text=True, cwd=tmp_path,
                          timeout=600,
                          env={"PYTHONPATH": str(REPO), "PATH": "/usr/bin:/bin"})  # fmt: skip
    assert done.returncode == 0, done.stderr
    assert "has a [campaign] table" in done.stderr and "sdc_cvx campaign" in done.stderr


def test_each_pricing_done_is_said_so_a_long_round_is_never_silent():
    """Issue 28, 3.3: heartbeats repeated one line for minutes with no fraction done."""
    lines: list[str] = []
    solve_campaign(Catalog.paper_case(), Campaign.yearly(2, Mission(n=2)), workers=1,
                   log=lines.append)  # fmt: skip
    done = [line for line in lines if "pricing:" in line]
    assert "  pricing: 1 of 2 done (mission 1, n = 2)" in done
    assert "  pricing: 2 of 2 done (mission 2, n = 2)" in done


def test_one_must_remove_id_may_be_a_string_as_for_a_mission():
    """``Mission(must_include="5")`` is ``("5",)``: a campaign's ``must_remove`` too."""
    campaign = Campaign.yearly(2, Mission(n=3), must_remove="5")
    assert campaign.must_remove == ("5",)
    assert Mission(n=3, must_include="5").must_include == campaign.must_remove


def test_a_sweep_says_its_warnings_as_warning_lines(tmp_path):
    """Issue 28, 1.6 and 3.2: sdc_cvx's own warnings read as the commands' other warning
    lines, not as Python's ``path:line: UserWarning:`` with a line of source."""
    (tmp_path / "c.toml").write_text("[mission]\nn = 2\ntmax_days = 100\n\n"
                                     "[campaign]\nlaunch_days = [0, 365.25]\n")  # fmt: skip
    (tmp_path / "study.toml").write_text('base = "c.toml"\n[grid]\n"mission.n" = [2]\n')
    done = subprocess.run([sys.executable, "-m", "sdc_cvx", "sweep", "study.toml", "--out",
                           "out"], capture_output=True, text=True, cwd=tmp_path, timeout=300,
                          env={"PYTHONPATH": str(REPO), "PATH": "/usr/bin:/bin"})  # fmt: skip
    assert done.returncode == 0, done.stderr
    said = [line for line in done.stderr.splitlines() if "[campaign] table" in line]
    assert len(said) == 1 and said[0].startswith("warning: 1 scenario(s) have a [campaign]")
    assert "UserWarning" not in done.stderr and "warnings.warn" not in done.stderr


@pytest.mark.requires_shared_data("gtoc9/debris_data.txt")
def test_a_campaigns_missions_price_the_eccentricity_as_a_single_mission_does():
    """Found in review (issue 46, item 2: campaigns price the eccentricity too): a campaign's
    launches kept ``eccentricity = "auto"`` unresolved, so its pricing planned circular
    legs (GTOC9's first 20 debris, n = 3 in 120 days: 162.50 m/s against the single
    mission's 199.18).  A campaign of one launch is that launch's single mission."""
    from sdc_cvx import read_catalog, solve
    from tests.conftest import shared_file

    catalog = read_catalog(shared_file("gtoc9/debris_data.txt"))
    catalog = catalog.subset(list(catalog.ids[:20]))
    mission = Mission(n=3, tmax_days=120.0)
    single = solve(catalog, mission)
    campaign = solve_campaign(catalog, Campaign.yearly(1, mission), workers=1)
    assert campaign.total_dv_mps == pytest.approx(single.total_dv_mps, abs=0.1)
    legs = campaign.missions[0].legs
    assert all(leg.eccentricity_dv_mps is not None for leg in legs)
    assert sum(leg.eccentricity_dv_mps for leg in legs) > 0.0
