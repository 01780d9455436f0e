"""A catalogue too large for the machine is refused before anything is built (issue 28, 2.1).

The whole public catalogue (13,840 candidates) once ran for minutes and ended in a
MemoryError, or in the system's out-of-memory killer at 24 GB.  Here the available
memory is made small, so that a modest catalogue is too large, and every entry point
refuses it at once, with the figures and the filters to use.
"""

from __future__ import annotations

import pytest
from click.testing import CliRunner

from sdc_cvx import Campaign, Mission, solve, solve_campaign
from sdc_cvx.cli import main
from sdc_cvx.errors import MissionError
from sdc_cvx.inputs.synthetic import sso_catalog
from sdc_cvx.planner import size_guard


@pytest.fixture
def small_machine(monkeypatch):
    """A machine with room for a search over 30 candidates, not 40."""
    room = size_guard.estimated_bytes(35) / size_guard.USABLE_FRACTION
    monkeypatch.setattr(size_guard, "available_memory_bytes", lambda: int(room))


def test_the_estimate_grows_with_the_ordered_pairs():
    one, two = size_guard.estimated_bytes(100), size_guard.estimated_bytes(200)
    pairs = (201 * 200 - 101 * 100)  # the injection orbit is one node more
    assert two - one == size_guard.BYTES_PER_PAIR * pairs
    assert size_guard.estimated_bytes(100, processes=3) == 3 * one


def test_solve_refuses_before_building(small_machine, monkeypatch):
    from sdc_cvx.planner import api

    monkeypatch.setattr(api, "certify", lambda *a, **k: pytest.fail("built the tables"))
    with pytest.raises(MissionError, match=r"40 candidates are 1,560 ordered pairs.*--altitude-km"):
        solve(sso_catalog(40, seed=1), Mission(n=3))


def test_a_catalogue_that_fits_is_not_refused(small_machine):
    assert size_guard.size_problem(30) is None


def test_a_campaign_counts_its_pricings_at_once(small_machine):
    assert size_guard.size_problem(30, processes=2) is not None
    with pytest.raises(MissionError, match="in 2 processes at once"):
        solve_campaign(sso_catalog(30, seed=1), Campaign.yearly(2, Mission(n=2)), workers=2)


def test_the_command_line_refuses_with_exit_2_and_writes_nothing(small_machine, tmp_path,
                                                                 monkeypatch):  # fmt: skip
    path = tmp_path / "debris.csv"
    sso_catalog(40, seed=1).frame[["id", "a_km", "e", "inc_deg", "raan_deg"]].to_csv(path,
                                                                                    index=False)
    monkeypatch.chdir(tmp_path)
    result = CliRunner().invoke(main, ["run", "--catalog", str(path), "--n", "3", "--out", "r"])
    assert result.exit_code == 2, result.output
    assert "40 candidates are 1,560 ordered pairs" in result.stderr
    assert "Traceback" not in result.output
    assert sorted(p.name for p in tmp_path.iterdir()) == ["debris.csv"]
