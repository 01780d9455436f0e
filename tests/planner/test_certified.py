"""Pieces of the certified search that the brute-force tests cannot isolate."""

import numpy as np
import pytest

from sdc_cvx import Catalog
from sdc_cvx.physics.leg_bounds import LegCosts
from sdc_cvx.physics.orbits import R_EARTH
from sdc_cvx.physics.transfer import NodeOrbits
from sdc_cvx.planner.certified import CertifiedNodes
from sdc_cvx.planner.certified.network import CellNetwork, DateCells

A_LOW, A_HIGH = R_EARTH + 400e3, R_EARTH + 1200e3


def test_no_arc_leaves_a_barred_start_even_without_a_plan_in_hand():
    """With ``first`` set and no plan yet (bound infinite), every first leg leaves ``first``."""
    catalog = Catalog.paper_case()  # n = 4 of these 11 fly within 365 days
    orbits = NodeOrbits.from_elements(catalog.a_m, catalog.e, catalog.inc_rad, catalog.raan_rad)
    n, first = len(catalog), 2
    nodes = CertifiedNodes(legs=3, ops_days=np.zeros(n), cost_mps=np.zeros(n), first=first,
                           must_visit=(), excluded=(), tmax_days=365.25, tmin_days=0.0,
                           rule="table3", j2=1.08263e-3)  # fmt: skip
    i, j = np.nonzero(~np.eye(n, dtype=bool))
    keep = j != first
    i, j = i[keep], j[keep]
    legs = LegCosts.build(orbits.take(i), orbits.take(j), A_LOW, A_HIGH)
    parts = DateCells(n, nodes.ops_days, nodes.tmax_days, 4)
    net = CellNetwork(nodes, legs, i, j, parts, np.ones(len(i), dtype=bool))
    assert np.any(net.arcs.tail < n)  # first legs from every start exist before pruning
    arcs, _, walk = net.pruned(nodes, np.arange(n) == first, np.inf)
    starts = arcs.tail[arcs.tail < n]
    assert len(starts) > 0 and np.all(starts == first)
    assert np.isfinite(walk)


def test_a_network_bounds_again_only_the_arcs_of_cells_split_since_the_last(monkeypatch):
    """Each round's network kept no bound of the last: 30 % of a low-thrust search's box
    bounds (the paper case) were of arcs between cells no split had touched."""
    catalog = Catalog.paper_case()
    orbits = NodeOrbits.from_elements(catalog.a_m, catalog.e, catalog.inc_rad, catalog.raan_rad)
    n = len(catalog)
    nodes = CertifiedNodes(legs=3, ops_days=np.zeros(n), cost_mps=np.zeros(n), first=None,
                           must_visit=(), excluded=(), tmax_days=365.25, tmin_days=0.0,
                           rule="table3", j2=1.08263e-3)  # fmt: skip
    i, j = np.nonzero(~np.eye(n, dtype=bool))
    legs = LegCosts.build(orbits.take(i), orbits.take(j), A_LOW, A_HIGH)
    bounded = []
    real = LegCosts.box_bound

    def counted(self, e, *args, **kwargs):
        bounded.append(np.size(e))
        return real(self, e, *args, **kwargs)

    monkeypatch.setattr(LegCosts, "box_bound", counted)
    alive = np.ones(len(i), dtype=bool)
    parts = DateCells(n, nodes.ops_days, nodes.tmax_days, 4)
    first = CellNetwork(nodes, legs, i, j, parts, alive)
    assert sum(bounded) > 0
    bounded.clear()
    again = CellNetwork(nodes, legs, i, j, parts, alive)
    assert sum(bounded) == 0  # nothing split: every bound kept
    np.testing.assert_array_equal(again.arcs.cost, first.arcs.cost)
    parts.split(3, 1)  # debris 3's second cell halved: only arcs into or out of it again
    touching = sum(4 + 1 for k in range(len(i)) if 3 in (i[k], j[k]))  # starts + cells
    split = CellNetwork(nodes, legs, i, j, parts, alive)
    assert 0 < sum(bounded) <= 2 * touching
    fresh = DateCells(n, nodes.ops_days, nodes.tmax_days, 4)
    fresh.split(3, 1)
    monkeypatch.setattr(LegCosts, "box_bound", real)
    whole = CellNetwork(nodes, legs, i, j, fresh, alive)  # no bound kept: the same arcs
    np.testing.assert_array_equal(split.arcs.cost, whole.arcs.cost)
    np.testing.assert_array_equal(split.arcs.tail, whole.arcs.tail)


# ------------------------------------------------------- issue 20, item 9: the setup's clock
def test_the_cost_tables_report_each_chunk_and_can_be_stopped():
    from sdc_cvx import Mission
    from sdc_cvx.inputs.synthetic import sso_catalog
    from sdc_cvx.network.edges import drift_radius_bounds, node_orbits
    from sdc_cvx.physics import leg_minima

    catalog, mission = sso_catalog(12, seed=3), Mission(n=3)
    orbits = node_orbits(catalog, mission)
    a_low, a_high = drift_radius_bounds(mission)
    ii, jj = np.nonzero(~np.eye(12, dtype=bool))
    seen = []
    whole = LegCosts.build(orbits.take(ii), orbits.take(jj), a_low, a_high)
    leg_minima._TABLES.clear()  # scanned again, not taken from the process's last scans
    chunked = LegCosts.build(orbits.take(ii), orbits.take(jj), a_low, a_high, chunk=50,
                             on_chunk=lambda done, total: seen.append((done, total)))  # fmt: skip
    assert seen == [(min(k + 50, 132), 132) for k in range(0, 132, 50)]
    np.testing.assert_array_equal(whole.candidate_cost, chunked.candidate_cost)


def test_a_time_limit_that_ends_in_the_setup_stops_it_with_a_clear_failure():
    import pytest

    from sdc_cvx import Mission, SolverOptions, solve
    from sdc_cvx.errors import SolverFailure
    from sdc_cvx.inputs.synthetic import sso_catalog

    catalog = sso_catalog(50, seed=1)  # 2450 edges: two chunks of cost tables
    with pytest.raises(SolverFailure, match="while building the edge cost tables") as caught:
        solve(catalog, Mission(n=3), solver=SolverOptions(time_limit_s=1e-6))
    assert "allow more time" in str(caught.value) and "inf" not in str(caught.value)


def test_the_setup_says_up_front_when_the_limit_cannot_be_met():
    import time

    import pytest

    from sdc_cvx.planner.certified.clock import OutOfTime, cost_table_clock

    lines = []
    asked = []
    clock = type("Clock", (), {"deadline": time.perf_counter() + 1e3, "say": lines.append,
                               "stop": lambda self: bool(asked)})()  # fmt: skip
    on_chunk = cost_table_clock(clock, every_s=0.0)
    on_chunk(1, 10**12)  # at this pace the tables need far more than the 1000 s left
    on_chunk(2, 10**12)
    assert sum("the edge cost tables alone need about" in line for line in lines) == 1
    assert any(line.startswith("  cost tables: 0% done (2 of") for line in lines)
    on_chunk(10**12, 10**12)  # done: the heartbeat's phase moves on to the network
    assert lines[-1].startswith("  cost tables done (1000000000000 edges")
    asked.append(True)  # a Ctrl-C: the tables stop at their next chunk
    with pytest.raises(OutOfTime, match="interrupted while building the edge cost tables"):
        on_chunk(3, 10**12)
    asked.clear()
    clock.deadline = 0.0
    with pytest.raises(OutOfTime, match=r"time limit reached .*\(3 of 1000000000000 edges"):
        on_chunk(3, 10**12)


def reference_case(name: str):
    """A reference case's catalog, mission and certified optimum (skip without them)."""
    import json

    from sdc_cvx import Mission

    from ..conftest import SHARED_DATA

    cases = SHARED_DATA / "reference_cases"
    if not (cases / "optima.json").is_file():
        pytest.skip("reference cases not found")
    data = json.loads((cases / "optima.json").read_text())[name]
    return (Catalog.from_csv(cases / data["catalog"]),
            Mission(n=data["n"], tmax_days=data["tmax_days"]),
            data["table3"]["optimum_dv_mps"])  # fmt: skip


@pytest.mark.slow
def test_the_milp_relaxation_still_certifies_where_labels_give_up(monkeypatch):
    """Labels give up on large networks (more than a million of one length) and the MILP
    solves the relaxation instead: with both kinds of labels always giving up, the search
    still reaches the reference optimum of syn10 (an independent exhaustive search's) with
    a valid bound."""
    from sdc_cvx import solve
    from sdc_cvx.network.ng_routes import RouteRelaxation
    from sdc_cvx.planner.certified import network

    catalog, mission, optimum = reference_case("syn10")
    monkeypatch.setattr(network, "cheapest_path", lambda *args, **kwargs: None)
    monkeypatch.setattr(network, "route_relaxation",
                        lambda *args, **kwargs: RouteRelaxation(-np.inf, None, None))  # fmt: skip
    solution = solve(catalog, mission)
    assert solution.certified and solution.backend != "labels"
    assert solution.total_dv_mps <= optimum * 1.001 + 0.01
    assert solution.lower_bound_mps <= optimum + 1e-6


@pytest.mark.parametrize("name", ["syn10", "lg8"])
def test_route_labels_certify_where_the_exact_labels_give_up(name, monkeypatch):
    """Where the exact labels give up, the ng-route labels solve the relaxation (exactly,
    once their cheapest route is a path): with the exact labels always giving up, the
    search reaches the reference optimum (an independent exhaustive search's) with a
    valid bound and no MILP."""
    from sdc_cvx import solve
    from sdc_cvx.network import ng_routes
    from sdc_cvx.planner.certified import network

    catalog, mission, optimum = reference_case(name)
    calls = []

    def counted(*args, **kwargs):
        calls.append(1)
        return ng_routes.route_relaxation(*args, **kwargs)

    monkeypatch.setattr(network, "cheapest_path", lambda *args, **kwargs: None)
    monkeypatch.setattr(network, "route_relaxation", counted)
    solution = solve(catalog, mission)
    assert calls and solution.certified
    assert solution.model_size["milp_solves"] == 0
    assert solution.total_dv_mps <= optimum * 1.001 + 0.01
    assert solution.lower_bound_mps <= optimum + 1e-6


def test_the_beam_paths_are_certified_best_quick_plan_first():
    """The paper case's four first beam paths, in the beam's order (by their bounds),
    have the optimum last (530.79, 528.18, 543.90, 499.99 m/s by their certificates):
    ranked by a quick schedule each, the optimum is certified first, so it is the only
    plan the beam announces and the three others stop at its cutoff."""
    from sdc_cvx import Catalog, Mission, solve

    lines = []
    solution = solve(Catalog.paper_case(), Mission(), log=lines.append)
    beam_plans = [line for line in lines if line.endswith("(beam)")]
    assert len(beam_plans) == 1 and "5-8-2-6-10: 499.99 m/s" in beam_plans[0], lines
    assert solution.status == "optimal" and round(solution.total_dv_mps, 2) == 499.99
