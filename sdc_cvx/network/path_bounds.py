"""The cheapest path of a time-expanded network through each of its arcs: walks, then paths.

The certified search (:mod:`sdc_cvx.planner.certified`) prices every arc of its
time-expanded network (a leg between two debris, leaving in one date cell and arriving
in another) at a lower bound of its cost.  An arc that lies on no path of ``legs`` arcs
cheaper than the plan in hand can leave the relaxation MILP without losing a better
plan.  Two bounds prove it, both pure numpy:

- :func:`walk_bounds`: the cheapest *walk* of k arcs to and from every network node,
  by dynamic programming.  A walk may come back to a debris, so it relaxes a path;
- :func:`elementary_bounds`: the cheapest *path* (each debris at most once) through
  every arc, by labels: a label is a partial path (its node, the debris it visited,
  its cost), extended arc by arc, kept only while the walk bound of its completion
  leaves it under the plan, and dominated by a cheaper label on the same node with the
  same debris.  Forward and backward labels meet on each arc.

The second is much the stronger on the cases of ``benchmarks/certify.py``: walks go back
and forth between two cheap debris, or loop on three, and so keep most arcs; the
relaxation MILP then spends seconds in branching to tell those walks from paths
(measured: paper case 1248 arcs, 5 s, against 197 arcs, 0.5 s; rb08 2634 against 162).
It is exact where a node holds at most :data:`TOP_LABELS` labels, a lower bound
elsewhere; its labels grow with the cheap partial paths, so it gives up, and the walk
bounds stand, beyond a budget of labels or without a plan to prune against.

References
----------
.. [1] N. Boland, M. Hewitt, M. Savelsbergh and D. M. Vu, "Solving the traveling
   salesman problem with time windows through dynamically generated time-expanded
   networks", CPAIOR 2017 / Operations Research 2018.
.. [2] M. Desrochers, J. Desrosiers and M. Solomon, "A new optimization algorithm for
   the vehicle routing problem with time windows", Operations Research 40(2),
   342-354, 1992 (labels over elementary paths).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

MAX_LABELS = 1_000_000
"""Labels of one leg at most (and partial paths tried per chunk): beyond, the
elementary bounds give up and the walk bounds stand."""
TOP_LABELS = 8
"""Labels per node paired on each arc; the rest are bounded by the cheapest of them."""
_PAIR_CHUNK = 20_000
"""Arcs paired together (memory: arcs x TOP_LABELS^2 x debris^2 booleans)."""


@dataclass(frozen=True)
class NetworkArcs:
    """Arcs of a time-expanded network, as the bounds need them.

    Attributes
    ----------
    tail, head : ndarray of int
        Network node each arc leaves and enters; nodes below ``len(start_allowed)``
        are the debris' start nodes (the first leg leaves one), the others date cells.
    debris_from, debris_to : ndarray of int
        Debris of the arc's ends.
    cost : ndarray
        Lower bound of the arc's cost [m/s] (a first leg's includes its start's).
    n_nodes : int
        Network nodes.
    start_allowed : ndarray of bool
        Debris a path may start from, shape (n_debris,).
    """

    tail: np.ndarray
    head: np.ndarray
    debris_from: np.ndarray
    debris_to: np.ndarray
    cost: np.ndarray
    n_nodes: int
    start_allowed: np.ndarray

    @property
    def first(self) -> np.ndarray:
        """Arcs that leave a start node (first legs)."""
        return self.tail < len(self.start_allowed)

    def take(self, rows) -> NetworkArcs:
        """The arcs ``rows`` (indices or a mask) of the same network."""
        return NetworkArcs(self.tail[rows], self.head[rows], self.debris_from[rows],
                           self.debris_to[rows], self.cost[rows], self.n_nodes,
                           self.start_allowed)  # fmt: skip


def walk_bounds(arcs: NetworkArcs, legs: int):
    """Cheapest walks of k arcs to and from every node [m/s].

    Parameters
    ----------
    arcs : NetworkArcs
    legs : int
        Arcs on a path (L).

    Returns
    -------
    forward : list of ndarray
        ``forward[k][v]``: the cheapest walk of k arcs from an allowed start to node v
        (``k = 0..L``, shape (n_nodes,) each).
    backward : list of ndarray
        ``backward[r][v]``: the cheapest walk of r arcs leaving node v, none of them a
        first leg (``r = 0..L``).
    through : ndarray
        The cheapest walk of L arcs through each arc, ``min over k of forward[k][tail]
        + cost + backward[L - 1 - k][head]`` with the arc as leg k.
    """
    first = arcs.first
    n_starts = len(arcs.start_allowed)
    start = np.full(arcs.n_nodes, np.inf)
    start[:n_starts] = np.where(arcs.start_allowed, 0.0, np.inf)
    forward, backward = [start], [np.zeros(arcs.n_nodes)]
    inner = ~first
    for k in range(legs):
        leg = first if k == 0 else inner
        step = np.full(arcs.n_nodes, np.inf)
        np.minimum.at(step, arcs.head[leg], forward[-1][arcs.tail[leg]] + arcs.cost[leg])
        forward.append(step)
        step = np.full(arcs.n_nodes, np.inf)
        np.minimum.at(step, arcs.tail[inner], arcs.cost[inner] + backward[-1][arcs.head[inner]])
        backward.append(step)
    through = np.full(len(arcs.cost), np.inf)
    for k in range(legs):
        walk = forward[k][arcs.tail] + arcs.cost + backward[legs - 1 - k][arcs.head]
        through = np.minimum(through, np.where(first if k == 0 else inner, walk, np.inf))
    return forward, backward, through


@dataclass(frozen=True)
class _Labels:
    """Partial paths of one length: node, visited debris (sorted, one row each), cost; and
    for :func:`cheapest_path`, the excluded paths' trie state, the parent label (one
    length shorter) and the arc that made each."""

    node: np.ndarray
    visited: np.ndarray
    cost: np.ndarray
    state: np.ndarray | None = None
    parent: np.ndarray | None = None
    arc: np.ndarray | None = None

    def __len__(self):
        return len(self.cost)


def elementary_bounds(arcs: NetworkArcs, legs: int, node_debris, upper: float,
                      walks=None, *, max_labels: int = MAX_LABELS):  # fmt: skip
    """The cheapest path (each debris at most once) of L arcs through each arc [m/s].

    Only paths within ``upper`` are looked for: a label whose cost plus the walk bound
    of its completion exceeds ``upper`` is dropped, so an arc whose bound comes back
    above ``upper`` lies on no path within it (its exact value is then not known).

    Parameters
    ----------
    arcs : NetworkArcs
    legs : int
        Arcs on a path (L).
    node_debris : array_like of int
        Debris of each network node, shape (n_nodes,).
    upper : float
        Cost of the plan in hand [m/s] (``inf``: none).
    walks : tuple, optional
        :func:`walk_bounds` of the same arcs (computed when not given).
    max_labels : int
        Labels of one length at most; beyond it the function gives up.

    Returns
    -------
    through : ndarray or None
        A lower bound of every path of L arcs through each arc that costs at most
        ``upper``, shape (m,) (``inf``: no such path); None when the labels exceeded
        ``max_labels`` or ``upper`` is infinite (measured on GTOC9's first network:
        2.3 s to give up).
    cheapest : float
        The cheapest path of L arcs (``inf`` if none within ``upper``; the walk bound
        when the function gave up).

    Notes
    -----
    The bound pairs, on each arc as leg k, the :data:`TOP_LABELS` cheapest forward
    labels of k arcs at its tail with the cheapest backward labels of ``L - 1 - k``
    arcs at its head whose debris are disjoint from them; a pair beyond those is
    bounded by the cheapest label of the other side.
    """
    node_debris = np.asarray(node_debris, dtype=np.int64)
    forward_walk, backward_walk, through_walk = walks or walk_bounds(arcs, legs)
    gave_up = None, float(np.min(forward_walk[legs]))
    if not np.isfinite(upper):  # nothing to prune against: every partial path is a label
        return gave_up
    first, n = arcs.first, arcs.n_nodes
    leaving_start, leaving_cell = grouped(arcs.tail, first, n), grouped(arcs.tail, ~first, n)
    entering_cell = grouped(arcs.head, ~first, n)
    starts = np.flatnonzero(np.isfinite(forward_walk[0]))
    forward = [_Labels(starts, node_debris[starts][:, None], np.zeros(len(starts)))]
    for k in range(legs):
        grown = _extend(forward[-1], leaving_start if k == 0 else leaving_cell, arcs.head,
                        arcs.debris_to, arcs.cost, backward_walk[legs - 1 - k], upper,
                        max_labels)  # fmt: skip
        if grown is None:
            return gave_up
        forward.append(grown)
    cheapest = float(np.min(forward[legs].cost, initial=np.inf))
    heads = np.unique(arcs.head)
    backward = [_Labels(heads, node_debris[heads][:, None], np.zeros(len(heads)))]
    for r in range(legs - 1):
        grown = _extend(backward[-1], entering_cell, arcs.tail, arcs.debris_from, arcs.cost,
                        forward_walk[legs - 1 - r], upper, max_labels)  # fmt: skip
        if grown is None:
            return gave_up
        backward.append(grown)
    through = np.full(len(arcs.cost), np.inf)
    for k in range(legs):
        leg = np.flatnonzero((first if k == 0 else ~first) & (through_walk <= upper + 1e-9))
        if len(leg):
            through[leg] = np.minimum(through[leg], _paired(
                forward[k], backward[legs - 1 - k], arcs, leg, n))  # fmt: skip
    return through, cheapest


def grouped(source, usable, n_nodes: int):
    """The usable arcs sorted by their ``source`` node, and where each node's run starts."""
    rows = np.flatnonzero(usable)
    rows = rows[np.argsort(source[rows], kind="stable")]
    return rows, np.searchsorted(source[rows], np.arange(n_nodes + 1))


def leaving(groups, nodes, *, limit: float = np.inf):
    """Every pair (position in ``nodes``, arc leaving that node), the arcs of each node
    from ``groups`` (:func:`grouped`); None when they are more than ``limit``."""
    rows, starts = groups
    degree = (starts[1:] - starts[:-1])[nodes]
    if int(degree.sum()) > limit:
        return None
    which = np.repeat(np.arange(len(nodes)), degree)
    offset = np.arange(len(which)) - np.repeat(np.cumsum(degree) - degree, degree)
    return which, rows[starts[nodes[which]] + offset]


def _extend(labels: _Labels, groups, target, new_debris, cost, rest, upper,
            max_labels, trie=None) -> _Labels | None:  # fmt: skip
    """Labels one arc longer: along the arcs leaving each label's node (``groups``, from
    :func:`grouped`) for a debris not visited yet, kept while ``cost + rest[node] <=
    upper``, one per (node, visited debris), the cheapest.

    With ``trie`` (:func:`_trie`'s transition table), one per (node, visited debris,
    trie state), each label keeping its parent and arc.
    """
    pairs = leaving(groups, labels.node, limit=max_labels * 8)
    if pairs is None:
        return None
    which, arc = pairs
    debris = new_debris[arc]
    total = labels.cost[which] + cost[arc]
    node = target[arc]
    fresh = ~(labels.visited[which] == debris[:, None]).any(axis=1)
    ok = fresh & (total + rest[node] <= upper + 1e-9)
    which, debris, total, node, arc = which[ok], debris[ok], total[ok], node[ok], arc[ok]
    visited = np.sort(np.column_stack([labels.visited[which], debris]), axis=1)
    state = None if trie is None else trie[labels.state[which], debris]
    keys = np.column_stack([node, visited] if trie is None else [node, state, visited])
    order, new = cheapest_per_key(keys, total)
    keys, total = keys[order], total[order]
    if int(new.sum()) > max_labels:
        return None
    if trie is None:
        return _Labels(keys[new, 0], keys[new, 1:], total[new])
    kept = order[new]
    return _Labels(keys[new, 0], keys[new, 2:], total[new], keys[new, 1], which[kept], arc[kept])


def cheapest_per_key(keys, total):
    """The order that sorts the rows of ``keys``, then ``total``; and, in that order, the
    first row of each key (its cheapest), as a mask."""
    order = np.lexsort((total,) + tuple(keys[:, c] for c in range(keys.shape[1] - 1, -1, -1)))
    ordered = keys[order]
    new = np.ones(len(order), dtype=bool)
    new[1:] = (ordered[1:] != ordered[:-1]).any(axis=1)
    return order, new


def traced_path(arcs: NetworkArcs, cost, usable, made_by, parents) -> CheapestPath:
    """The cheapest of the last labels ``usable`` (their ``cost``), as a path: its arcs
    traced back through each length's arc and parent label (``made_by[k]``,
    ``parents[k]`` for the labels of k + 1 arcs)."""
    if not len(usable):
        return CheapestPath(np.inf, (), np.empty(0, dtype=int))
    label = int(usable[np.argmin(cost[usable])])
    best, rows = float(cost[label]), []
    for k in range(len(made_by) - 1, -1, -1):
        rows.append(int(made_by[k][label]))
        label = int(parents[k][label])
    rows = np.array(rows[::-1], dtype=int)
    debris = (int(arcs.debris_from[rows[0]]),) + tuple(int(d) for d in arcs.debris_to[rows])
    return CheapestPath(best, debris, rows)


def _top(labels: _Labels, n_nodes: int, count: int):
    """The ``count`` cheapest labels of every node, padded, and the next one's cost."""
    width = labels.visited.shape[1]
    cost = np.full((n_nodes, count), np.inf)
    visited = np.full((n_nodes, count, width), -1, dtype=np.int64)
    after = np.full(n_nodes, np.inf)
    order = np.lexsort((labels.cost, labels.node))
    node, value = labels.node[order], labels.cost[order]
    rank = np.arange(len(node)) - np.searchsorted(node, node)
    kept = rank < count
    cost[node[kept], rank[kept]] = value[kept]
    visited[node[kept], rank[kept]] = labels.visited[order][kept]
    after[node[rank == count]] = value[rank == count]
    return cost, visited, after


def _paired(forward: _Labels, backward: _Labels, arcs: NetworkArcs, rows, n_nodes: int):
    """Lower bound of forward label + arc + backward label over disjoint pairs, per arc."""
    f_cost, f_visited, f_after = _top(forward, n_nodes, TOP_LABELS)
    b_cost, b_visited, b_after = _top(backward, n_nodes, TOP_LABELS)
    out = np.empty(len(rows))
    for part in np.array_split(np.arange(len(rows)), max(1, len(rows) // _PAIR_CHUNK)):
        tail, head = arcs.tail[rows[part]], arcs.head[rows[part]]
        clash = (f_visited[tail][:, :, None, :, None]
                 == b_visited[head][:, None, :, None, :]).any(axis=(3, 4))  # fmt: skip
        pair = f_cost[tail][:, :, None] + b_cost[head][:, None, :]
        best = np.where(clash, np.inf, pair).min(axis=(1, 2))
        # a pair with a label beyond the top ones costs at least this much
        beyond = np.minimum(f_after[tail] + b_cost[head][:, 0], f_cost[tail][:, 0] + b_after[head])
        out[part] = np.minimum(best, beyond) + arcs.cost[rows[part]]
    return out


@dataclass(frozen=True)
class CheapestPath:
    """The cheapest path of a network that is none of the excluded ones.

    Attributes
    ----------
    cost : float
        Its cost [m/s] (``inf``: no such path within the ``upper`` it was asked under).
    debris : tuple of int
        Its debris, in order (empty when ``cost`` is ``inf``).
    rows : ndarray of int
        Its arcs, in order.
    """

    cost: float
    debris: tuple[int, ...]
    rows: np.ndarray


def cheapest_path(arcs: NetworkArcs, legs: int, node_debris, upper: float, walks=None, *,
                  excluded=(), must_visit=(), max_labels: int = MAX_LABELS,
                  ) -> CheapestPath | None:  # fmt: skip
    """The cheapest path of L arcs within ``upper`` whose debris sequence is not excluded.

    Exact, by labels: a label is a partial path (node, visited debris, cost) with the
    state of its debris sequence in the trie of the excluded sequences (their longest
    prefix it follows, or none); one label per (node, visited debris, trie state), the
    cheapest, so two partial paths are compared only when every completion does the
    same to both.  A label whose cost plus the walk bound of its completion exceeds
    ``upper`` is dropped.  This is the time-expanded relaxation of the certified search
    with its no-good rows (:func:`~sdc_cvx.planner.certified.relaxation.solve_relaxation`) solved
    exactly without a MILP.

    Parameters
    ----------
    arcs : NetworkArcs
    legs : int
        Arcs on a path (L).
    node_debris : array_like of int
        Debris of each network node.
    upper : float
        Paths above this are not looked for [m/s] (finite).
    walks : tuple, optional
        :func:`walk_bounds` of the same arcs.
    excluded : iterable of sequence of int
        Debris sequences (L + 1 debris each) that may not be the answer.
    must_visit : sequence of int
        Debris the path must visit.
    max_labels : int
        Labels of one length at most; beyond, the function gives up.

    Returns
    -------
    CheapestPath or None
        None when the labels exceeded ``max_labels``.
    """
    node_debris = np.asarray(node_debris, dtype=np.int64)
    forward_walk, backward_walk, _ = walks or walk_bounds(arcs, legs)
    n_debris = int(max(np.max(node_debris, initial=-1), np.max(arcs.debris_to, initial=-1))) + 1
    trie, leaf = _trie(excluded, n_debris)
    first, n = arcs.first, arcs.n_nodes
    leaving_start, leaving_cell = grouped(arcs.tail, first, n), grouped(arcs.tail, ~first, n)
    starts = np.flatnonzero(np.isfinite(forward_walk[0]))
    labels = [_Labels(starts, node_debris[starts][:, None], np.zeros(len(starts)),
                      trie[_ROOT, node_debris[starts]], np.full(len(starts), -1),
                      np.full(len(starts), -1))]  # fmt: skip
    for k in range(legs):
        grown = _extend(labels[-1], leaving_start if k == 0 else leaving_cell, arcs.head,
                        arcs.debris_to, arcs.cost, backward_walk[legs - 1 - k], upper,
                        max_labels, trie)  # fmt: skip
        if grown is None:
            return None
        labels.append(grown)
    last = labels[-1]
    required = np.asarray(list(must_visit), dtype=np.int64)
    has_all = np.ones(len(last), dtype=bool)
    for debris in required:
        has_all &= (last.visited == debris).any(axis=1)
    usable = np.flatnonzero(~leaf[last.state] & has_all)
    return traced_path(arcs, last.cost, usable, [grown.arc for grown in labels[1:]],
                       [grown.parent for grown in labels[1:]])  # fmt: skip


_FREE, _ROOT = 0, 1
"""Trie states: a sequence that follows no excluded one, and the empty sequence."""


def _trie(sequences, n_debris: int):
    """Transition table ``next[state, debris]`` of the trie of ``sequences`` (``_FREE``
    where a sequence leaves every one of them) and which states end an excluded one."""
    children: list[dict[int, int]] = [{}, {}]  # _FREE, _ROOT
    ends = {_FREE: False, _ROOT: False}
    for sequence in sequences:
        state = _ROOT
        for debris in sequence:
            if int(debris) not in children[state]:
                children[state][int(debris)] = len(children)
                children.append({})
                ends[len(children) - 1] = False
            state = children[state][int(debris)]
        ends[state] = True
    table = np.zeros((len(children), n_debris), dtype=np.int64)
    for state, out in enumerate(children):
        for debris, child in out.items():
            if debris < n_debris:
                table[state, debris] = child
    return table, np.array([ends[k] for k in range(len(children))], dtype=bool)
