"""Walk and path bounds of a time-expanded network against every path and walk enumerated."""

import itertools

import numpy as np
import pytest

from sdc_cvx.network import path_bounds
from sdc_cvx.network.path_bounds import NetworkArcs, elementary_bounds, walk_bounds


def random_network(seed: int, n_debris: int = 5, cells: int = 2, density: float = 0.6):
    """Start nodes 0..n-1, then ``cells`` date cells per debris; arcs between debris."""
    rng = np.random.default_rng(seed)
    node_debris = np.r_[np.arange(n_debris), np.repeat(np.arange(n_debris), cells)]
    tails, heads = [], []
    for tail, head in itertools.product(range(len(node_debris)), range(n_debris, len(node_debris))):
        if node_debris[tail] != node_debris[head] and rng.random() < density:
            tails.append(tail)
            heads.append(head)
    tail, head = np.array(tails), np.array(heads)
    start_allowed = rng.random(n_debris) < 0.8
    start_allowed[0] = True
    cost = rng.uniform(1.0, 10.0, len(tail))
    arcs = NetworkArcs(tail, head, node_debris[tail], node_debris[head], cost,
                       len(node_debris), start_allowed)  # fmt: skip
    return arcs, node_debris


def enumerate_through(arcs: NetworkArcs, legs: int, node_debris, elementary: bool):
    """The cheapest sequence of ``legs`` arcs (a walk, or a path) through each arc."""
    leaving = {}
    for a in range(len(arcs.cost)):
        leaving.setdefault(int(arcs.tail[a]), []).append(a)
    best = np.full(len(arcs.cost), np.inf)
    cheapest = np.inf

    def grow(sequence, visited, cost):
        nonlocal cheapest
        if len(sequence) == legs:
            cheapest = min(cheapest, cost)
            best[list(sequence)] = np.minimum(best[list(sequence)], cost)
            return
        for a in leaving.get(int(arcs.head[sequence[-1]]), ()):
            debris = int(node_debris[arcs.head[a]])
            if elementary and debris in visited:
                continue
            grow(sequence + (a,), visited | {debris}, cost + arcs.cost[a])

    for start in np.flatnonzero(arcs.start_allowed):
        for a in leaving.get(int(start), ()):
            grow((a,), {int(start), int(node_debris[arcs.head[a]])}, arcs.cost[a])
    return best, cheapest


@pytest.mark.parametrize("seed", range(12))
@pytest.mark.parametrize("legs", [1, 2, 3, 4])
def test_walk_bounds_are_the_cheapest_walks(seed, legs):
    arcs, node_debris = random_network(seed)
    exact, _ = enumerate_through(arcs, legs, node_debris, elementary=False)
    _, _, through = walk_bounds(arcs, legs)
    np.testing.assert_allclose(through, exact)


@pytest.mark.parametrize("seed", range(12))
@pytest.mark.parametrize("legs", [2, 3, 4])
def test_path_bounds_are_the_cheapest_paths_when_every_label_is_paired(seed, legs):
    """With every label paired the bound is exact on the arcs of paths within ``upper``
    (5 debris: at most C(4, 2) = 6 labels of one length end on a node)."""
    assert path_bounds.TOP_LABELS >= 6
    arcs, node_debris = random_network(seed)
    exact, cheapest = enumerate_through(arcs, legs, node_debris, elementary=True)
    walk, _ = enumerate_through(arcs, legs, node_debris, elementary=False)
    assert np.any(exact > walk)  # the networks have walks that are not paths
    upper = float(np.quantile(exact[np.isfinite(exact)], 0.5))
    through, best = elementary_bounds(arcs, legs, node_debris, upper)
    within = exact <= upper
    np.testing.assert_allclose(through[within], exact[within])
    assert np.all(through[~within] > upper)
    assert best == pytest.approx(np.min(exact))
    assert best == pytest.approx(cheapest)
    finite = np.isfinite(exact)  # every path: exact wherever one passes
    through, _ = elementary_bounds(arcs, legs, node_debris, float(np.max(exact[finite])))
    np.testing.assert_allclose(through[finite], exact[finite])


@pytest.mark.parametrize("seed", range(12))
@pytest.mark.parametrize("top", [1, 2])
def test_path_bounds_stay_below_every_path_when_few_labels_are_paired(seed, top, monkeypatch):
    """Pairs beyond the top labels are bounded, never ignored: no arc of a path within
    ``upper`` is lost, and no bound exceeds the cheapest path through its arc."""
    monkeypatch.setattr(path_bounds, "TOP_LABELS", top)
    arcs, node_debris = random_network(seed, n_debris=6, cells=3)
    legs = 4
    exact, cheapest = enumerate_through(arcs, legs, node_debris, elementary=True)
    _, _, walk = walk_bounds(arcs, legs)
    upper = float(np.quantile(exact[np.isfinite(exact)], 0.3))
    through, best = elementary_bounds(arcs, legs, node_debris, upper)
    within = exact <= upper
    assert np.all(through[within] <= exact[within] + 1e-9)
    assert np.all(through[within] >= walk[within] - 1e-9)
    assert best == pytest.approx(cheapest)


@pytest.mark.parametrize(("upper", "max_labels"), [(50.0, 3), (np.inf, 10**6)])
def test_path_bounds_give_up_beyond_the_label_budget_or_without_a_plan(upper, max_labels):
    arcs, node_debris = random_network(0, n_debris=6, cells=3)
    forward, _, _ = walk_bounds(arcs, 4)
    through, best = elementary_bounds(arcs, 4, node_debris, upper, max_labels=max_labels)
    assert through is None
    assert best == pytest.approx(np.min(forward[4]))


def test_no_path_from_a_barred_start():
    arcs, node_debris = random_network(3)
    only = np.zeros_like(arcs.start_allowed)
    only[1] = True
    barred = NetworkArcs(arcs.tail, arcs.head, arcs.debris_from, arcs.debris_to, arcs.cost,
                         arcs.n_nodes, only)  # fmt: skip
    through, _ = elementary_bounds(barred, 3, node_debris, 1e6)
    first = arcs.tail < len(only)
    assert np.all(np.isinf(through[first & (arcs.tail != 1)]))
    assert np.any(np.isfinite(through[first & (arcs.tail == 1)]))


def every_path(arcs: NetworkArcs, legs: int, node_debris):
    """Every path of ``legs`` arcs (each debris at most once): (cost, debris, arcs)."""
    leaving = {}
    for a in range(len(arcs.cost)):
        leaving.setdefault(int(arcs.tail[a]), []).append(a)
    out = []

    def grow(sequence, debris, cost):
        if len(sequence) == legs:
            out.append((cost, debris, sequence))
            return
        for a in leaving.get(int(arcs.head[sequence[-1]]), ()):
            d = int(node_debris[arcs.head[a]])
            if d not in debris:
                grow(sequence + (a,), debris + (d,), cost + arcs.cost[a])

    for start in np.flatnonzero(arcs.start_allowed):
        for a in leaving.get(int(start), ()):
            grow((a,), (int(start), int(node_debris[arcs.head[a]])), arcs.cost[a])
    return out


@pytest.mark.parametrize("seed", range(10))
@pytest.mark.parametrize("legs", [1, 2, 3])
def test_cheapest_path_skips_the_excluded_sequences(seed, legs):
    """Against every path enumerated: the cheapest whose debris sequence is neither one of
    the cheapest few sequences (excluded, as settled paths are) nor misses a must-visit
    debris; its arcs are a path of that cost."""
    arcs, node_debris = random_network(seed, n_debris=5, cells=2)
    paths = sorted(every_path(arcs, legs, node_debris))
    if not paths:
        pytest.skip("no path of this length in this network")
    sequences = list(dict.fromkeys(debris for _, debris, _ in paths))
    rng = np.random.default_rng(seed)
    must = (int(rng.integers(5)),) if seed % 2 else ()
    for k in range(min(4, len(sequences)) + 1):
        excluded = sequences[:k]
        left = [(c, d) for c, d, _ in paths if d not in excluded and set(must) <= set(d)]
        found = path_bounds.cheapest_path(arcs, legs, node_debris, 1e9, excluded=excluded,
                                          must_visit=must)  # fmt: skip
        if not left:
            assert found.cost == np.inf and found.debris == ()
            continue
        assert found.cost == pytest.approx(min(c for c, _ in left))
        assert found.debris not in excluded and set(must) <= set(found.debris)
        rows = found.rows
        assert np.all(arcs.head[rows[:-1]] == arcs.tail[rows[1:]])  # a chain of arcs
        assert arcs.cost[rows].sum() == pytest.approx(found.cost)
        assert (int(arcs.debris_from[rows[0]]),) + tuple(arcs.debris_to[rows]) == found.debris


def test_cheapest_path_within_upper_only():
    arcs, node_debris = random_network(3)
    cheapest = min(c for c, _, _ in every_path(arcs, 2, node_debris))
    assert path_bounds.cheapest_path(arcs, 2, node_debris, cheapest - 1e-3).cost == np.inf
    assert path_bounds.cheapest_path(arcs, 2, node_debris, cheapest + 1e-3).cost == \
        pytest.approx(cheapest)  # fmt: skip


@pytest.mark.parametrize("seed", range(8))
@pytest.mark.parametrize("legs", [2, 3])
def test_labels_and_the_relaxation_milp_agree_on_negative_costs(seed, legs):
    """A campaign's prizes make node costs negative, folded into the arcs: the labels'
    cheapest path and the relaxation MILP (the two ways the certified search solves its
    relaxation) are both the cheapest path enumerated (issue 27, part 5)."""
    from sdc_cvx.milp.types import SolverOptions
    from sdc_cvx.planner.certified.relaxation import Arcs, solve_relaxation

    arcs, node_debris = random_network(seed)
    cost = np.random.default_rng(100 + seed).uniform(-6.0, 10.0, len(arcs.cost))
    arcs = NetworkArcs(arcs.tail, arcs.head, arcs.debris_from, arcs.debris_to, cost,
                       arcs.n_nodes, arcs.start_allowed)  # fmt: skip
    assert (cost < 0).any()
    _, cheapest = enumerate_through(arcs, legs, node_debris, elementary=True)
    assert np.isfinite(cheapest)
    labels = path_bounds.cheapest_path(arcs, legs, node_debris, 1e9)
    assert labels.cost == pytest.approx(cheapest)
    n_debris = len(arcs.start_allowed)
    usable = (arcs.tail >= n_debris) | arcs.start_allowed[np.minimum(arcs.tail, n_debris - 1)]
    milp = solve_relaxation(Arcs(arcs.tail, arcs.head, arcs.debris_from, arcs.debris_to,
                                 cost).take(usable), n_nodes=arcs.n_nodes, n_debris=n_debris,
                            legs=legs, solver=SolverOptions(), solver_gap=0.0)  # fmt: skip
    assert milp.lower_mps == pytest.approx(cheapest, abs=1e-6)
    assert sum(cost[a] for a in labels.rows) == pytest.approx(cheapest)
