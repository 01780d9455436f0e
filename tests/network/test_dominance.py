"""Dominated-edge bounds against brute force: a dense radius grid and every walk."""

import itertools

import numpy as np
import pytest

from sdc_cvx import Mission
from sdc_cvx.inputs.synthetic import sso_catalog
from sdc_cvx.network.dominance import (
    FLOOR_MARGIN_MPS,
    cheapest_paths,
    path_cost_floor,
    transfer_dv_floor,
)
from sdc_cvx.network.edges import drift_radius_bounds, node_orbits
from sdc_cvx.physics.orbits import SECONDS_PER_DAY
from sdc_cvx.physics.transfer import cheapest_transfer, transfer_dv


@pytest.fixture(scope="module")
def pairs():
    catalog = sso_catalog(12, seed=3)
    mission = Mission()
    orbits = node_orbits(catalog, mission)
    i, j = np.nonzero(~np.eye(len(catalog), dtype=bool))
    return orbits.take(i), orbits.take(j), drift_radius_bounds(mission)


def test_transfer_floor_matches_a_dense_grid(pairs):
    origin, target, (a_low, a_high) = pairs
    grid = np.linspace(a_low, a_high, 40_001)  # 20 m steps, plus the kinks at both radii
    brute = np.full(len(origin.a), np.inf)
    for k in range(len(origin.a)):
        radii = np.concatenate([grid, [origin.a[k], target.a[k]]])
        radii = radii[(radii >= a_low) & (radii <= a_high)]
        for inc in (origin.inc[k], target.inc[k]):
            dv = transfer_dv(origin.a[k], origin.inc[k], target.a[k], target.inc[k], radii, inc)
            brute[k] = min(brute[k], dv.min())
    floor = transfer_dv_floor(origin, target, a_low, a_high)
    assert np.all(floor <= brute)
    assert np.allclose(floor, np.maximum(brute - FLOOR_MARGIN_MPS, 0), atol=0.02)


@pytest.mark.parametrize("day", [0.0, 90.0, 300.0])
@pytest.mark.parametrize("max_days", [20.0, 61.0, 365.0])
def test_no_transfer_is_cheaper_than_its_floor(pairs, day, max_days):
    origin, target, (a_low, a_high) = pairs
    floor = transfer_dv_floor(origin, target, a_low, a_high)
    for inclination in ("table3", "free"):
        best = cheapest_transfer(origin, target, day * SECONDS_PER_DAY,
                                 max_days * SECONDS_PER_DAY, a_low, a_high,
                                 inclination=inclination)  # fmt: skip
        feasible = np.isfinite(best.dv)
        assert feasible.any()
        assert np.all(floor[feasible] <= best.dv[feasible])


def brute_force_floor(edges, weight, node_cost, legs, first=None):
    """Cheapest walk of ``legs`` edges through each edge, by listing every walk."""
    out = np.full(len(edges), np.inf)
    by_start = {}
    for e, (a, _) in enumerate(edges):
        by_start.setdefault(a, []).append(e)
    for walk in itertools.product(range(len(edges)), repeat=legs):
        if any(edges[walk[k]][1] != edges[walk[k + 1]][0] for k in range(legs - 1)):
            continue
        head = edges[walk[0]][0]
        if first is not None and head != first:
            continue
        cost = node_cost[head] + sum(weight[e] + node_cost[edges[e][1]] for e in walk)
        for e in set(walk):
            out[e] = min(out[e], cost)
    return out


@pytest.mark.parametrize("first", [None, 2])
@pytest.mark.parametrize("legs", [1, 2, 3, 4])
def test_path_floor_equals_the_cheapest_walk(legs, first):
    rng = np.random.default_rng(legs)
    nodes = 6
    edges = [(a, b) for a in range(nodes) for b in range(nodes) if a != b and rng.random() < 0.5]
    edges += [edges[0]]  # a repeated pair (date-window copies) with its own cost
    weight = rng.uniform(0, 100, len(edges))
    node_cost = rng.uniform(0, 10, nodes)
    frm, to = np.array(edges).T
    got = path_cost_floor(frm, to, weight, node_cost, legs, first=first)
    expected = brute_force_floor(edges, weight, node_cost, legs, first=first)
    assert np.array_equal(np.isinf(got), np.isinf(expected))
    finite = np.isfinite(expected)
    assert np.allclose(got[finite], expected[finite])


@pytest.mark.parametrize("per_leg", [False, True])
@pytest.mark.parametrize("first", [None, 1])
def test_cheapest_paths_with_a_wide_beam_are_the_cheapest_simple_paths(first, per_leg):
    rng = np.random.default_rng(7)
    nodes, legs = 6, 3
    edges = [(a, b) for a in range(nodes) for b in range(nodes) if a != b and rng.random() < 0.6]
    cost = rng.uniform(0, 100, (legs, len(edges)) if per_leg else len(edges))
    if per_leg:
        cost[1, ::4] = np.inf  # edges barred as the second leg
    leg_cost = np.broadcast_to(cost, (legs, len(edges)))
    frm, to = np.array(edges).T
    found = cheapest_paths(frm, to, cost, legs, first=first, width=10_000)
    simple = []  # every simple path, listed directly
    for walk in itertools.product(range(len(edges)), repeat=legs):
        visited = [edges[walk[0]][0]] + [edges[e][1] for e in walk]
        linked = all(edges[walk[k]][1] == edges[walk[k + 1]][0] for k in range(legs - 1))
        total = sum(leg_cost[k, e] for k, e in enumerate(walk))
        simple_path = linked and len(set(visited)) == legs + 1
        if simple_path and first in (None, visited[0]) and np.isfinite(total):
            simple.append((total, tuple(visited)))
    simple.sort()
    assert [path for _, path, _ in found] == [path for _, path in simple]
    assert np.allclose([c for c, _, _ in found], [c for c, _ in simple])
    for _, path, used in found:
        assert [edges[e] for e in used] == list(zip(path[:-1], path[1:], strict=True))
    narrow = cheapest_paths(frm, to, cost, legs, first=first, width=3, must_visit=(2,))
    assert all(2 in path for _, path, _ in narrow) and len(narrow) <= 3
