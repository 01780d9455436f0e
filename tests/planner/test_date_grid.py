"""First plans from a grid of dates, against the reference cases' certified optima.

A schedule on the grid flies (every leg priced exactly between two grid dates), so no
plan of the grid may cost less than the certified optimum, and the grid's best sequence
should be the optimal one on these cases (why the certified search starts from it).
"""

import json

import numpy as np
import pytest

from sdc_cvx import Catalog, Mission
from sdc_cvx.network.edges import drift_radius_bounds, node_orbits
from sdc_cvx.physics.leg_bounds import LegCosts
from sdc_cvx.planner.api import certified_nodes
from sdc_cvx.planner.certified.date_grid import grid_plans
from sdc_cvx.planner.nodes import MissionNodes

from ..conftest import SHARED_DATA

CASES = SHARED_DATA / "reference_cases"


def setup(case):
    data = json.loads((CASES / "optima.json").read_text())[case]
    catalog = Catalog.from_csv(CASES / data["catalog"])
    mission = Mission(n=data["n"], tmax_days=data["tmax_days"])
    nodes = MissionNodes.of(catalog, mission)
    orbits = node_orbits(nodes.catalog, mission)
    n = len(nodes.catalog)
    i, j = np.nonzero(~np.eye(n, dtype=bool))
    legs = LegCosts.build(orbits.take(i), orbits.take(j), *drift_radius_bounds(mission))
    return data, nodes, certified_nodes(nodes, mission), legs, i, j


@pytest.mark.requires_shared_data("reference_cases/optima.json")
@pytest.mark.parametrize(
    "case",
    [
        "syn10",
        pytest.param("rb08", marks=pytest.mark.slow),
        pytest.param("lg7", marks=pytest.mark.slow),
    ],
)
def test_the_grids_best_sequence_is_the_optimal_one_and_flies(case):
    data, nodes, certified, legs, i, j = setup(case)
    plans = grid_plans(legs, i, j, certified)
    ids = nodes.catalog.ids
    optimum = data["table3"]["optimum_dv_mps"]
    assert plans and tuple(ids[k] for k in plans[0].path) == tuple(data["table3"]["path"])
    costs = [plan.cost_mps for plan in plans]
    assert costs == sorted(costs) and costs[0] >= optimum - 0.01  # grid schedules fly
    assert all(len(set(plan.path)) == data["n"] for plan in plans)


@pytest.mark.requires_shared_data("reference_cases/optima.json")
def test_a_grid_past_its_deadline_gives_no_plan_and_first_and_must_visit_hold():
    data, nodes, certified, legs, i, j = setup("syn10")
    assert grid_plans(legs, i, j, certified, deadline=0.0) == []
    from dataclasses import replace

    keep = j != 3  # nothing flies back to the first debris
    plans = grid_plans(legs, i[keep], j[keep], replace(certified, first=3, must_visit=(7,)))
    assert plans and all(p.path[0] == 3 and 7 in p.path for p in plans)
