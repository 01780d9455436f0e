"""Every scenario of ``examples/`` reads as a scenario (its tables, keys and values), and a
campaign's as a campaign: an example broken by a change of the scenario format fails here,
not in a user's hands."""

from __future__ import annotations

import pytest

from sdc_cvx.study.scenario import Scenario
from tests.conftest import EXAMPLES, SHARED_DATA

SCENARIOS = sorted(p for p in EXAMPLES.glob("*.toml") if not p.name.startswith("study_"))


@pytest.mark.parametrize("path", SCENARIOS, ids=[p.stem for p in SCENARIOS])
def test_each_example_scenario_reads(path):
    if "shared/data" in path.read_text(encoding="utf-8") and not SHARED_DATA.is_dir():
        pytest.skip(f"{path.name} reads {SHARED_DATA}, absent")
    scenario = Scenario.load(path)
    assert (scenario.campaign is not None) == path.name.startswith("campaign_")


def test_the_programme_examples_say_what_they_ask():
    sl16 = Scenario.load(EXAMPLES / "campaign_sl16_all.toml").campaign
    assert sl16.remove_all and sl16.counts_text() == "4-5, 4-5, 4-5, 4-5"
    gtoc9 = Scenario.load(EXAMPLES / "campaign_gtoc9_all.toml").campaign
    assert gtoc9.remove_all and len(gtoc9) == 25 and gtoc9.most_removed == 125
    assert gtoc9.launch_days[1] - gtoc9.launch_days[0] == 117.0
