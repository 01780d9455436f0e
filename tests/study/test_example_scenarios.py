"""Every scenario of ``examples/`` reads as a scenario (its tables, keys and values), a
campaign's as a campaign, a GTOC9 Kessler Run's (``gtoc9_*.toml``) by its own reader: an
example broken by a change of the scenario format fails here, not in a user's hands."""

from __future__ import annotations

import pytest

from sdc_cvx.study.scenario import Scenario
from tests.conftest import EXAMPLES, SHARED_DATA

SCENARIOS = sorted(p for p in EXAMPLES.glob("*.toml")
                   if not p.name.startswith(("study_", "gtoc9_")))
KESSLER = sorted(EXAMPLES.glob("gtoc9_*.toml"))
"""GTOC9's Kessler Run scenarios: their own reader (:mod:`sdc_cvx.gtoc9.scenario`)."""


@pytest.mark.parametrize("path", SCENARIOS, ids=[p.stem for p in SCENARIOS])
def test_each_example_scenario_reads(path):
    if "shared/data" in path.read_text(encoding="utf-8") and not SHARED_DATA.is_dir():
        pytest.skip(f"{path.name} reads {SHARED_DATA}, absent")
    scenario = Scenario.load(path)
    assert (scenario.campaign is not None) == path.name.startswith("campaign_")


@pytest.mark.parametrize("path", KESSLER, ids=[p.stem for p in KESSLER])
def test_each_kessler_run_scenario_reads(path):
    from sdc_cvx.gtoc9.scenario import read_kessler_scenario

    scenario = read_kessler_scenario(path)
    assert scenario.debris_path is not None and scenario.debris_path.name == "debris_data.txt"


def test_the_programme_examples_say_what_they_ask():
    sl16 = Scenario.load(EXAMPLES / "campaign_sl16_all.toml").campaign
    assert sl16.remove_all and sl16.counts_text() == "4-5, 4-5, 4-5, 4-5"
    gtoc9 = Scenario.load(EXAMPLES / "campaign_gtoc9_all.toml").campaign
    assert gtoc9.remove_all and len(gtoc9) == 25 and gtoc9.most_removed == 125
    assert gtoc9.launch_days[1] - gtoc9.launch_days[0] == 117.0
