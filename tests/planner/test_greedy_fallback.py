"""A time limit shorter than the edge cost tables still gives a plan that flies (issue 28).

The certified search stops its tables early when they are projected to use the time
limit, and returns a greedy plan (:mod:`sdc_cvx.planner.certified.greedy`), ``feasible``
with the bound every plan has.  The plan is replayed with the transfer physics by the
brute force's :func:`~tests.planner.bruteforce.replay` (nothing of the planner).
"""

import json
import subprocess
import sys
import time

import numpy as np
import pytest

from sdc_cvx import Mission, SolverOptions, solve
from sdc_cvx.inputs.formats import read_catalog
from sdc_cvx.planner.certified import network
from sdc_cvx.solution import RunStatus

from ..conftest import SHARED_DATA
from .bruteforce import orbits_of, replay

GTOC9 = SHARED_DATA / "gtoc9" / "debris_data.txt"
FRAGMENTS = SHARED_DATA / "pykep_tle" / "tle.txt"
GTOC9_OPTIMUM_MPS = 171.43  # n = 5, one year: certified (README, benchmarks/certify.py)


@pytest.mark.skipif(not GTOC9.is_file(), reason="GTOC9 data beside the repository")
def test_tables_projected_past_the_limit_give_a_greedy_plan_that_flies(monkeypatch):
    # every projection "past the limit" from the first chunk of tables on
    monkeypatch.setattr(network, "PROJECTION_S", 0.0)
    monkeypatch.setattr(network, "FALLBACK_RESERVE", 1.0)
    catalog = read_catalog(str(GTOC9), "gtoc9")
    mission = Mission(n=5, tmax_days=365.25)
    answer = solve(catalog, mission, solver=SolverOptions(time_limit_s=60))
    assert answer.status == RunStatus.FEASIBLE and not answer.certified
    assert any("greedy plan" in note for note in answer.notes)
    assert answer.lower_bound_mps == 0.0  # no better bound is known: transfers cost >= 0
    assert answer.total_dv_mps >= GTOC9_OPTIMUM_MPS - 0.01
    # the legs fly: each leg's cost and duration as the physics gives them, by T_max
    index = {name: k for k, name in enumerate(catalog.ids)}
    path = [index[name] for name in answer.path]
    plan = replay(orbits_of(catalog), path, [leg.drift_a_km * 1e3 for leg in answer.legs],
                  [np.radians(leg.drift_inc_deg) for leg in answer.legs])  # fmt: skip
    assert plan.dv == pytest.approx(answer.total_dv_mps, rel=1e-6)
    assert plan.end_day <= mission.tmax_days + 1e-6


@pytest.mark.slow
@pytest.mark.skipif(not FRAGMENTS.is_file(), reason="pykep TLE sample beside the repository")
def test_run_with_a_limit_shorter_than_the_tables_writes_a_feasible_plan(tmp_path):
    """481 fragments, 230 880 edges, tables of about 13 s: --time-limit 12 wrote nothing
    (exit 4); now a plan, feasible, with its gap, within the limit."""
    started = time.perf_counter()
    done = subprocess.run([sys.executable, "-m", "sdc_cvx", "run", "--catalog", str(FRAGMENTS),
                           "--time-limit", "12", "--out", str(tmp_path / "out")],
                          capture_output=True, text=True, timeout=120)  # fmt: skip
    wall = time.perf_counter() - started
    assert done.returncode == 0, done.stderr
    assert "Traceback" not in done.stderr
    solution = json.loads((tmp_path / "out" / "solution.json").read_text())
    assert solution["status"] == "feasible" and len(solution["path"]) == 5
    assert solution["total_dv_mps"] >= 26.05 - 0.01  # the certified optimum (README)
    assert wall < 12 + 8  # the limit, plus reading, selecting and writing the folder
