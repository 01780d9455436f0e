"""The relaxation's cheapest path by ng-route labels, where the exact labels are too many.

The exact labels of :func:`~sdc_cvx.network.path_bounds.cheapest_path` keep one label per
(node, set of debris visited): on long missions over many debris (GTOC9, n = 10, two
years) the sets are too many, and a MILP solved the relaxation instead, its LP bound far
under the optimum (278 against 419 m/s on one network of that case, after 100 s).

An ng-route label remembers, instead of every debris visited, only those still in the
*neighbourhood* of the debris it stands on (Baldacci, Mingozzi & Roberti 2011): its
memory after a leg to debris j is ``(memory & ng(j)) | {j}``, and a leg may not go to a
debris in the memory.  Every path (each debris at most once) is such a route, so the
cheapest route is a lower bound of the cheapest path; labels with the same node, trie
state (of the excluded sequences, as the exact labels have it) and memory have the same
completions, so the cheapest of them is kept.  The memories are few where the
neighbourhoods are small: about 16 000 labels a leg on that network.

A route may still visit a debris twice, a cycle longer than the neighbourhoods see.  The
neighbourhoods then grow where it did (Roberti & Mingozzi 2014): the debris repeated
joins the neighbourhood of every debris between its two visits, which forbids that cycle,
and the labels run again.  When the cheapest route is a path, it is the cheapest path:
the relaxation is solved exactly (on that network: 3 growths, 3 s).

References
----------
.. [1] R. Baldacci, A. Mingozzi and R. Roberti, "New route relaxation and pricing
   strategies for the vehicle routing problem", Operations Research 59(5),
   1269-1283, 2011.
.. [2] R. Roberti and A. Mingozzi, "Dynamic ng-path relaxation for the delivery man
   problem", Transportation Science 48(3), 413-424, 2014.
"""

from __future__ import annotations

import time
from dataclasses import dataclass

import numpy as np

from .path_bounds import (
    _ROOT,
    MAX_LABELS,
    CheapestPath,
    NetworkArcs,
    _trie,
    cheapest_per_key,
    grouped,
    leaving,
    traced_path,
    walk_bounds,
)

NEIGHBOURS = 8
"""Debris in each first neighbourhood: those of the cheapest arcs to or from it."""
GROWTHS = 40
"""Times the neighbourhoods grow at most in one call."""


@dataclass(frozen=True)
class RouteRelaxation:
    """The cheapest route of a network: a bound, and the cheapest path when it is one.

    Attributes
    ----------
    bound : float
        No path of the network that is not excluded costs less [m/s] (``inf``: none
        within the ``upper`` asked).
    path : CheapestPath or None
        The cheapest path that is not excluded, when the cheapest route is one (then
        ``bound == path.cost``); None when the growths or labels ran out first.
    neighbourhoods : ndarray of bool
        ``[i, j]``: debris j in debris i's neighbourhood, as grown (for the next call).
    """

    bound: float
    path: CheapestPath | None
    neighbourhoods: np.ndarray


def first_neighbourhoods(arcs: NetworkArcs, n_debris: int, size: int = NEIGHBOURS) -> np.ndarray:
    """Each debris' ``size`` debris of the cheapest arcs to or from it (boolean matrix)."""
    cheapest = np.full((n_debris, n_debris), np.inf)
    np.minimum.at(cheapest, (arcs.debris_from, arcs.debris_to), arcs.cost)
    cheapest = np.minimum(cheapest, cheapest.T)
    out = np.zeros((n_debris, n_debris), dtype=bool)
    near = np.argsort(cheapest, axis=1, kind="stable")[:, :size]
    rows = np.repeat(np.arange(n_debris), near.shape[1])
    out[rows, near.ravel()] = np.isfinite(cheapest[rows, near.ravel()])
    return out


def route_relaxation(arcs: NetworkArcs, legs: int, node_debris, upper: float, walks=None, *,
                     excluded=(), neighbourhoods=None, max_labels: int = MAX_LABELS,
                     growths: int = GROWTHS,
                     deadline: float = np.inf) -> RouteRelaxation:  # fmt: skip
    """The cheapest route of L arcs within ``upper`` whose debris sequence is not excluded
    (module docstring), the neighbourhoods grown until it is a path or a limit.

    Parameters
    ----------
    arcs : NetworkArcs
    legs : int
        Arcs on a path (L).
    node_debris : array_like of int
        Debris of each network node.
    upper : float
        Routes above this are not looked for [m/s].
    walks : tuple, optional
        :func:`~sdc_cvx.network.path_bounds.walk_bounds` of the same arcs.
    excluded : iterable of sequence of int
        Debris sequences (L + 1 debris each) that may not be the answer.
    neighbourhoods : ndarray of bool, optional
        Neighbourhoods to start from (a previous call's); with :func:`first_neighbourhoods`.
    max_labels : int
        Labels of one length at most; beyond, the last bound found is returned.
    growths : int
        Times the neighbourhoods may grow.
    deadline : float
        ``time.perf_counter()`` past which no growth starts.

    Returns
    -------
    RouteRelaxation
    """
    node_debris = np.asarray(node_debris, dtype=np.int64)
    walks = walks or walk_bounds(arcs, legs)
    n_debris = int(max(np.max(node_debris, initial=-1), np.max(arcs.debris_to, initial=-1))) + 1
    grown = first_neighbourhoods(arcs, n_debris, NEIGHBOURS)
    if neighbourhoods is not None and neighbourhoods.shape == grown.shape:
        grown |= neighbourhoods
    trie, leaf = _trie(excluded, n_debris)
    bound = -np.inf
    for _ in range(growths + 1):
        found = _cheapest_route(arcs, legs, node_debris, upper, walks, trie, leaf, grown,
                                max_labels)  # fmt: skip
        if found is None:  # too many labels: the last bound stands
            break
        bound = max(bound, found.cost)
        repeat = _first_cycle(found.debris)
        if repeat is None:  # a path (or none at all): the relaxation is solved
            return RouteRelaxation(found.cost, found, grown)
        first, again = repeat
        grown[list(found.debris[first + 1:again]), found.debris[first]] = True
        if time.perf_counter() >= deadline:
            break
    return RouteRelaxation(bound, None, grown)


def _first_cycle(debris) -> tuple[int, int] | None:
    """Positions of the first debris a sequence visits twice (None: a path)."""
    seen: dict[int, int] = {}
    for position, d in enumerate(debris):
        if d in seen:
            return seen[d], position
        seen[d] = position
    return None


def _bits(debris, words: int) -> np.ndarray:
    """One bit per debris, rows of ``words`` 64-bit words."""
    out = np.zeros((len(debris), words), dtype=np.uint64)
    out[np.arange(len(debris)), debris // 64] = np.left_shift(np.uint64(1),
                                                              (debris % 64).astype(np.uint64))
    return out


def _cheapest_route(arcs: NetworkArcs, legs: int, node_debris, upper: float, walks, trie, leaf,
                    neighbourhoods, max_labels: int) -> CheapestPath | None:  # fmt: skip
    """The cheapest route for these neighbourhoods (None: more than ``max_labels``)."""
    n_debris = len(neighbourhoods)
    words = (n_debris + 63) // 64
    masks = np.zeros((n_debris, words), dtype=np.uint64)
    rows, columns = np.nonzero(neighbourhoods)
    np.bitwise_or.at(masks, rows, _bits(columns, words))
    forward_walk, backward_walk, _ = walks
    first, n = arcs.first, arcs.n_nodes
    leaving_start, leaving_cell = grouped(arcs.tail, first, n), grouped(arcs.tail, ~first, n)
    node = np.flatnonzero(np.isfinite(forward_walk[0]))
    memory, cost = _bits(node_debris[node], words), np.zeros(len(node))
    state = trie[_ROOT, node_debris[node]]
    parents, made_by = [], []
    for k in range(legs):
        pairs = leaving(leaving_start if k == 0 else leaving_cell, node, limit=max_labels * 8)
        if pairs is None:
            return None
        which, arc = pairs
        debris = arcs.debris_to[arc]
        step = _bits(debris, words)
        total = cost[which] + arcs.cost[arc]
        head = arcs.head[arc]
        ok = (~(memory[which] & step).any(axis=1)
              & (total + backward_walk[legs - 1 - k][head] <= upper + 1e-9))  # fmt: skip
        which, arc, debris, step, total, head = (v[ok] for v in (which, arc, debris, step,
                                                                  total, head))  # fmt: skip
        after = trie[state[which], debris]
        keys = np.column_stack([head.astype(np.uint64), after.astype(np.uint64),
                                (memory[which] & masks[debris]) | step])  # fmt: skip
        order, new = cheapest_per_key(keys, total)
        keys, total = keys[order], total[order]
        if int(new.sum()) > max_labels:
            return None
        kept = order[new]
        node, state, memory, cost = (keys[new, 0].astype(np.int64), keys[new, 1].astype(np.int64),
                                     keys[new, 2:], total[new])  # fmt: skip
        parents.append(which[kept])
        made_by.append(arc[kept])
    return traced_path(arcs, cost, np.flatnonzero(~leaf[state]), made_by, parents)
