"""Messages a new user reads (issue 48, item 20): a count where a list would be a line of
thousands of characters, the help naming every catalog format, no "others" when there are
none."""

import pytest
from click.testing import CliRunner

from sdc_cvx import Campaign
from sdc_cvx.cli import main
from sdc_cvx.errors import MissionError, ScenarioError


def test_launch_days_past_ten_years_are_counted_not_listed():
    """360 launches 30 days apart, 307 of them past 10 years: a 5,489-character line."""
    days = [3600.0 + k for k in range(360)]
    try:
        Campaign.of(days)
    except MissionError as err:
        text = str(err)
    assert len(text) < 400 and "\n" not in text, text
    assert "307 of the 360 given are not: 3653.0, 3654.0" in text and "and 295 more" in text


def test_run_help_names_every_catalog_format():
    """``run --help`` said the catalog is a CSV (TLE, OMM and GTOC9 files are read too)."""
    text = CliRunner().invoke(main, ["run", "--help"], terminal_width=200).output
    catalog = " ".join(text.split("--catalog", 1)[1].split("--format", 1)[0].split())
    assert "CSV" in catalog and "TLE" in catalog and "OMM" in catalog and "GTOC9" in catalog


def test_values_named_says_no_others_when_every_candidate_is_named():
    """"18 of the 18 candidates are named (the others are worth 0)"."""
    from sdc_cvx.cli.campaign import values_named

    assert "others" not in values_named(18, 18, "values.csv")
    assert "every one of the 18 candidates" in values_named(18, 18, "values.csv")
    assert "(the other 15 are worth 0)" in values_named(3, 18, "values.csv")


def test_a_sweep_of_a_scenario_file_says_run_it(tmp_path):
    """``sweep examples/paper.toml`` said "unknown study key 'catalog'" three times."""
    from sdc_cvx.study.study import load_study

    path = tmp_path / "plain.toml"
    path.write_text("[catalog]\n[mission]\nn = 3\n", encoding="utf-8")
    with pytest.raises(ScenarioError) as err:
        load_study(path)
    text = str(err.value)
    assert "a scenario file (its tables: catalog, mission), not a study" in text
    assert f"python -m sdc_cvx run {path} runs it" in text and "unknown study key" not in text


def test_a_grid_value_given_twice_is_said_so(tmp_path):
    """"scenario 'n=3' is the same scenario as 'n=3'"."""
    from sdc_cvx.study.study import load_study

    path = tmp_path / "study.toml"
    path.write_text('[grid]\n"mission.n" = [3, 4, 3]\n', encoding="utf-8")
    with pytest.raises(ScenarioError) as err:
        load_study(path)
    assert "scenario 'n=3' is given twice ([grid] or [[cases]]" in str(err.value)
    assert "same scenario as" not in str(err.value)


def test_the_search_share_of_a_time_limit_reads_as_a_bound(tmp_path):
    """"The search gets 117.4 s of the 120 s limit" read as how long the search takes."""
    result = CliRunner().invoke(main, ["run", "--n", "3", "--time-limit", "60", "--out",
                                       str(tmp_path / "out")])  # fmt: skip
    assert result.exit_code == 0, result.output
    assert "The search may run up to" in result.output
    assert "it stops sooner once the plan is proven" in result.output


def test_a_selection_pattern_matching_nothing_names_the_scenario_file(tmp_path):
    """The scenario file whose ``[selection]`` held the pattern was not named."""
    path = tmp_path / "sel.toml"
    path.write_text('[selection]\nids = ["zzz*"]\n', encoding="utf-8")
    result = CliRunner().invoke(main, ["run", str(path), "--out", str(tmp_path / "out")])
    assert result.exit_code == 2
    assert f"candidate selection ({path} [selection]" in result.output
    assert "'zzz*' match no debris of the catalog (paper Table 5)" in result.output


@pytest.mark.slow
def test_a_campaigns_header_says_the_range_written_once_and_the_search_limit_as_a_bound(
        tmp_path):  # fmt: skip
    """``n = [[2, 3]]`` was echoed "n = 2-3, 2-3", and "The search gets 13.9 s of the 20 s
    limit" read as how long it would take (a budget of 1 m/s: proven infeasible at once,
    after the header)."""
    scenario = tmp_path / "value.toml"
    scenario.write_text('[mission]\nn = 3\ntmax_days = 365.25\n\n[campaign]\nobjective = '
                        '"max-value"\nlaunch_days = [0.0, 365.25]\nn = [[2, 3]]\n'
                        "dv_budget_mps = 1.0\n", encoding="utf-8")  # fmt: skip
    result = CliRunner().invoke(main, ["campaign", str(scenario), "--time-limit", "20",
                                       "--out", str(tmp_path / "out")])  # fmt: skip
    assert "n = 2-3 each)" in result.output, result.output
    assert "The search may run up to" in result.output
    assert "it stops sooner once the campaign is proven" in result.output
    assert "The search gets" not in result.output


@pytest.mark.parametrize("ranges, written", [([[4, 3]], "n = [[4, 3]]"),
                                             ([[2, 3], [4, 3]], "n = [[2, 3], [4, 3]]")])
def test_n_ranges_refused_are_echoed_as_written(ranges, written):
    """``n = [[4, 3]]`` was refused as "got n_min [4, 4] for n_max [3, 3]": two ranges, and
    in a form, that the user did not write."""
    with pytest.raises(MissionError) as err:
        Campaign.of([0.0, 365.25], n=ranges, objective="max-value", dv_budget_mps=100.0)
    assert f"got {written}" in str(err.value) and "n_min [" not in str(err.value)


def test_a_tank_too_small_for_any_mission_says_the_tank_not_the_budget():
    """The budgets came from the tank (none written): "raise dv_budget_mps" named a key the
    scenario did not have; the limit is the tank's."""
    from sdc_cvx import Mission, MissionInfeasible, Vehicle, solve_campaign
    from sdc_cvx.inputs.synthetic import sso_catalog

    vehicle = Vehicle(dry_mass_kg=500.0, propellant_kg=0.5, isp_s=300.0, kit_mass_kg=150.0)
    campaign = Campaign.of([0.0, 365.25], Mission(n=2, tmax_days=200.0, vehicle=vehicle),
                           objective="max-value")  # fmt: skip
    catalog = sso_catalog(8, seed=7, inclination_spread_deg=0.8)
    with pytest.raises(MissionInfeasible) as err:
        solve_campaign(catalog, campaign, workers=1)
    text = str(err.value)
    assert "fits its tank's ΔV" in text and "a larger tank (propellant_kg)" in text, text
    assert "dv_budget_mps" not in text
