"""A time limit shorter than the edge cost tables still gives a plan that flies (issue 28).

When the tables are projected to take most of the limit, the certified search first finds
a greedy plan without them (:mod:`sdc_cvx.planner.certified.greedy`), then goes on; if
the limit stops the tables, that plan is the answer, ``feasible``.  Plans are replayed
with the transfer physics by the brute force's :func:`~tests.planner.bruteforce.replay`
(nothing of the planner).
"""

import json
import subprocess
import sys
import time

import pytest

from sdc_cvx import Mission, SolverOptions, solve
from sdc_cvx.inputs.formats import read_catalog
from sdc_cvx.network.edges import drift_radius_bounds, node_orbits
from sdc_cvx.planner.api import certified_nodes
from sdc_cvx.planner.certified import clock
from sdc_cvx.planner.certified.greedy import greedy_plan
from sdc_cvx.planner.nodes import MissionNodes
from sdc_cvx.solution import RunStatus

from ..conftest import SHARED_DATA
from .bruteforce import orbits_of, replay

GTOC9 = SHARED_DATA / "gtoc9" / "debris_data.txt"
FRAGMENTS = SHARED_DATA / "pykep_tle" / "tle.txt"
GTOC9_OPTIMUM_MPS = 171.43  # n = 5, one year, the paper's circular legs: certified
PAPER_LEGS = {"eccentricity": "off", "flight_min_days": 0.0}  # the model 171.43 is optimal in
needs_gtoc9 = pytest.mark.skipif(not GTOC9.is_file(), reason="GTOC9 data beside the repository")


@needs_gtoc9
def test_a_greedy_plan_flies_and_ends_by_tmax():
    catalog = read_catalog(str(GTOC9), "gtoc9")
    mission = Mission(n=5, tmax_days=365.25, **PAPER_LEGS)
    nodes = MissionNodes.of(catalog, mission)
    deadline = time.perf_counter() + 60
    found = greedy_plan(node_orbits(nodes.catalog, mission), certified_nodes(nodes, mission),
                        *drift_radius_bounds(mission), deadline=deadline)  # fmt: skip
    assert found is not None
    path, schedule = found
    assert len(set(path)) == 5 and schedule.feasible
    assert schedule.upper_mps >= GTOC9_OPTIMUM_MPS - 0.01
    # the schedule's legs fly: cost and arrival as the physics gives them, by T_max
    plan = replay(orbits_of(nodes.catalog), list(path), schedule.a_drift, schedule.inc_drift)
    assert plan.dv == pytest.approx(schedule.upper_mps, rel=1e-6)
    assert plan.end_day <= mission.tmax_days + 1e-6


@needs_gtoc9
def test_late_tables_give_a_greedy_plan_first_and_the_search_goes_on(monkeypatch):
    # every projection "late" from the first chunk of tables on
    monkeypatch.setattr(clock, "PROJECTION_S", 0.0)
    monkeypatch.setattr(clock, "FALLBACK_RESERVE", 1.0)
    lines = []
    catalog = read_catalog(str(GTOC9), "gtoc9")
    answer = solve(catalog, Mission(n=5, tmax_days=365.25, **PAPER_LEGS),
                   solver=SolverOptions(time_limit_s=120), log=lines.append)  # fmt: skip
    assert any("greedy plan" in line for line in lines)
    assert answer.status == RunStatus.OPTIMAL
    assert answer.total_dv_mps == pytest.approx(GTOC9_OPTIMUM_MPS, abs=0.01)


@pytest.mark.slow
@pytest.mark.skipif(not FRAGMENTS.is_file(), reason="pykep TLE sample beside the repository")
@pytest.mark.parametrize("limit", [12])
def test_run_with_a_limit_shorter_than_the_tables_writes_a_feasible_plan(tmp_path, limit):
    """481 fragments, 230 880 edges, tables of about 15 s: --time-limit 12 or 20 wrote
    nothing (exit 4); now a plan that flies, feasible, with its gap (the wall time against
    the limit is measured by benchmarks/time_limit.py; 20 s, which passed too, is left
    out of the suite for its time)."""
    done = subprocess.run([sys.executable, "-m", "sdc_cvx", "run", "--catalog", str(FRAGMENTS),
                           "--time-limit", str(limit), "--out", str(tmp_path / "out")],
                          capture_output=True, text=True, timeout=180)  # fmt: skip
    assert done.returncode == 0, done.stderr
    assert "Traceback" not in done.stderr
    solution = json.loads((tmp_path / "out" / "solution.json").read_text())
    assert solution["status"] == "feasible" and len(solution["path"]) == 5
    assert solution["total_dv_mps"] >= 26.05 - 0.01  # the certified optimum (README)
    assert "The search may run up to" in done.stderr  # the limit covers reading and writing too
