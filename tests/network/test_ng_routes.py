"""The route relaxation (ng-route labels) against every path enumerated."""

import numpy as np
import pytest

from sdc_cvx.network import ng_routes
from sdc_cvx.network.ng_routes import first_neighbourhoods, route_relaxation
from sdc_cvx.network.path_bounds import walk_bounds

from .test_path_bounds import every_path, random_network


def check_path(arcs, found, cost, excluded):
    """``found`` is a chain of arcs, visits each debris once, costs ``cost``."""
    rows = found.rows
    assert np.all(arcs.head[rows[:-1]] == arcs.tail[rows[1:]])
    assert arcs.cost[rows].sum() == pytest.approx(cost)
    assert (int(arcs.debris_from[rows[0]]),) + tuple(arcs.debris_to[rows]) == found.debris
    assert len(set(found.debris)) == len(found.debris)
    assert found.debris not in excluded


@pytest.mark.parametrize("seed", range(10))
@pytest.mark.parametrize("legs", [2, 3, 4])
@pytest.mark.parametrize("size", [0, 1, 8])
def test_routes_bound_every_path_and_find_the_cheapest_when_they_end_on_one(
    seed, legs, size, monkeypatch
):
    """From neighbourhoods of 0, 1 or 8 debris (0: a route only may not stay on a debris,
    every cycle allowed), excluding the cheapest few sequences as settled paths are: the
    bound is never above a path that is not excluded, and once the neighbourhoods have
    grown the answer is the cheapest such path, exactly."""
    monkeypatch.setattr(ng_routes, "NEIGHBOURS", size)
    arcs, node_debris = random_network(seed, n_debris=6, cells=2)
    paths = sorted(every_path(arcs, legs, node_debris))
    sequences = list(dict.fromkeys(debris for _, debris, _ in paths))
    for k in (0, 1, 3):
        excluded = sequences[:k]
        left = [c for c, d, _ in paths if d not in excluded]
        cheapest = min(left, default=np.inf)
        once = route_relaxation(arcs, legs, node_debris, 1e9, excluded=excluded, growths=0)
        assert once.bound <= cheapest + 1e-9
        found = route_relaxation(arcs, legs, node_debris, 1e9, excluded=excluded)
        assert found.path is not None  # 6 debris: the growths always end on a path
        assert found.bound == pytest.approx(cheapest)
        if np.isfinite(cheapest):
            check_path(arcs, found.path, cheapest, excluded)
        if once.path is not None:  # a path at once: the same answer
            assert once.bound == pytest.approx(cheapest)


def test_routes_are_between_walks_and_paths_and_grow_their_neighbourhoods(monkeypatch):
    """With no neighbourhood a route is a walk that never stays on a debris: on these
    networks some cheapest routes come back to a debris, their bound between the
    cheapest walk and the cheapest path; the debris repeated then joins the
    neighbourhoods of the debris between its two visits."""
    monkeypatch.setattr(ng_routes, "NEIGHBOURS", 0)
    between = 0
    for seed in range(10):
        arcs, node_debris = random_network(seed, n_debris=6, cells=2)
        legs = 4
        cheapest = min((c for c, _, _ in every_path(arcs, legs, node_debris)), default=np.inf)
        walk = float(np.min(walk_bounds(arcs, legs)[0][legs]))
        route = route_relaxation(arcs, legs, node_debris, 1e9, growths=0)
        assert walk - 1e-9 <= route.bound <= cheapest + 1e-9
        if route.path is None:  # a cycle: its debris joined the neighbourhoods
            between += route.bound < cheapest - 1e-9
            assert route.neighbourhoods.any()
        else:
            assert not route.neighbourhoods.any()
    assert between >= 1


def test_routes_give_up_beyond_the_label_budget():
    arcs, node_debris = random_network(4, n_debris=6, cells=2)
    out = route_relaxation(arcs, 4, node_debris, 1e9, max_labels=2)
    assert out.path is None and out.bound == -np.inf


def test_first_neighbourhoods_are_the_debris_of_the_cheapest_arcs():
    arcs, _ = random_network(2, n_debris=6, cells=2)
    near = first_neighbourhoods(arcs, 6, size=2)
    cheapest = np.full((6, 6), np.inf)
    for f, t, c in zip(arcs.debris_from, arcs.debris_to, arcs.cost, strict=True):
        cheapest[f, t] = min(cheapest[f, t], c)
        cheapest[t, f] = min(cheapest[t, f], c)
    for i in range(6):
        chosen = np.flatnonzero(near[i])
        assert len(chosen) == min(2, np.isfinite(cheapest[i]).sum())
        others = np.setdiff1d(np.flatnonzero(np.isfinite(cheapest[i])), chosen)
        assert all(cheapest[i, chosen].max() <= cheapest[i, o] for o in others)
