"""The time-expanded network of the certified search: date cells, arcs and their bounds.

Each debris' dates ``[0, T_max]`` are split into cells (:class:`DateCells`); an arc is a
leg between two debris leaving in one cell and arriving in another, priced at the exact
lower bound of its cost over that box of dates
(``LegCosts.box_bound``, in the tables' transfer model).  :meth:`CellNetwork.pruned` keeps the
arcs that can lie on a plan better than the one held and solves the relaxation over them
by labels (:mod:`~sdc_cvx.network.path_bounds`); :func:`beam_paths` finds cheap paths
of the network, whose cells :func:`refine_cells` halves.

References
----------
.. [1] N. Boland, M. Hewitt, M. Savelsbergh and D. M. Vu, "Solving the traveling
   salesman problem with time windows through dynamically generated time-expanded
   networks", CPAIOR 2017 / Operations Research 2018.
"""

from __future__ import annotations

import time

import numpy as np

from ...network.ng_routes import route_relaxation
from ...network.path_bounds import (
    NetworkArcs,
    cheapest_path,
    elementary_bounds,
    grouped,
    leaving,
    walk_bounds,
)
from ...physics.leg_bounds import LegCosts
from .clock import OutOfTime
from .relaxation import Arcs
from .results import CertifiedNodes

BEAM_WIDTH = 1000
"""Partial paths kept per leg by :func:`beam_paths`."""
BOUND_CHUNK = 200_000
"""Arcs whose box bounds are computed together (memory: the first network of N = 481)."""


class DateCells:
    """Date cells of every debris, each a sorted list of [lo, hi], each cell with an id of
    its own (a cell never changes: a split makes new ones), so that what was derived of a
    cell (its arcs' bounds) can be kept, and of the cell it was split from (``parent``:
    an arc's bound holds for the arcs between the cells split from its ends)."""

    def __init__(self, n_debris, start, stop, count):
        self.lo = [np.linspace(start[i], stop, count + 1)[:-1] for i in range(n_debris)]
        self.hi = [np.linspace(start[i], stop, count + 1)[1:] for i in range(n_debris)]
        self.ids = [np.arange(i * count, (i + 1) * count) for i in range(n_debris)]
        self.next_id = n_debris * count
        self.parent = np.arange(self.next_id)  # by id: the cell it was split from, or itself
        self.arc_bounds = None  # the last network's arc bounds by key (CellNetwork)

    def split(self, debris: int, cell: int, pieces: int = 2):
        lo, hi = self.lo[debris][cell], self.hi[debris][cell]
        edges = np.linspace(lo, hi, pieces + 1)
        self.lo[debris] = np.r_[self.lo[debris][:cell], edges[:-1], self.lo[debris][cell + 1 :]]
        self.hi[debris] = np.r_[self.hi[debris][:cell], edges[1:], self.hi[debris][cell + 1 :]]
        new = np.arange(self.next_id, self.next_id + pieces)
        self.parent = np.r_[self.parent, np.full(pieces, self.ids[debris][cell])]
        self.ids[debris] = np.r_[self.ids[debris][:cell], new, self.ids[debris][cell + 1 :]]
        self.next_id += pieces

    def count(self) -> int:
        return sum(len(c) for c in self.lo)


_ID_BITS = 21
"""Bits of a cell's id (and of an edge's index) in an arc's key."""


def _lookup(known, keys, missing):
    """Values of ``keys`` in ``known`` (sorted keys, values), ``missing`` where absent."""
    where = np.minimum(np.searchsorted(known[0], keys), len(known[0]) - 1)
    hit = known[0][where] == keys
    return np.where(hit, known[1][where], missing)


class CellNetwork:
    """Time-expanded network over the current partitions: node ids, arcs and their bounds."""

    def __init__(self, nodes: CertifiedNodes, legs_table: LegCosts, edge_from, edge_to,
                 parts: DateCells, alive_edges, deadline: float = np.inf):  # fmt: skip
        """An arc between two cells that were not split since the last network over
        ``parts`` is not bounded again (``parts.arc_bounds``)."""
        n = len(nodes.ops_days)
        self.n_debris = n
        self.deadline = deadline
        self.neighbourhoods = None  # the route relaxation's, as grown (:meth:`pruned`)
        # node ids: starts 0..n-1, then the cells of each debris in order
        self.offset = np.cumsum([n] + [len(parts.lo[i]) for i in range(n)])[:-1]
        self.n_nodes = int(self.offset[-1] + len(parts.lo[n - 1])) if n else 0
        self.node_debris = np.r_[np.arange(n), np.concatenate(
            [np.full(len(parts.lo[i]), i) for i in range(n)])].astype(int)  # fmt: skip
        self.node_lo = np.r_[nodes.ops_days, np.concatenate(parts.lo)]
        self.node_hi = np.r_[nodes.ops_days, np.concatenate(parts.hi)]
        self.node_cell = np.r_[np.full(n, -1), np.concatenate(
            [np.arange(len(parts.lo[i])) for i in range(n)])].astype(int)  # fmt: skip
        tails, heads, edges = [], [], []
        for e in np.flatnonzero(alive_edges):
            i, j = int(edge_from[e]), int(edge_to[e])
            t_ids = np.r_[i, self.offset[i] + np.arange(len(parts.lo[i]))]
            h_ids = self.offset[j] + np.arange(len(parts.lo[j]))
            tt, hh = np.meshgrid(t_ids, h_ids, indexing="ij")
            tt, hh = tt.ravel(), hh.ravel()
            ok = self.node_hi[hh] - nodes.ops_days[j] - self.node_lo[tt] >= nodes.tmin_days
            tails.append(tt[ok])
            heads.append(hh[ok])
            edges.append(np.full(int(ok.sum()), e))
        tail = np.concatenate(tails) if tails else np.empty(0, dtype=int)
        head = np.concatenate(heads) if heads else np.empty(0, dtype=int)
        edge = np.concatenate(edges) if edges else np.empty(0, dtype=int)
        # an arc's key: its edge and its two cells' ids (a start node: an id of its own)
        uid = np.r_[np.arange(n), n + np.concatenate(parts.ids)].astype(np.int64)
        known = parts.arc_bounds
        if uid.max(initial=0) >= 1 << _ID_BITS or len(edge_from) >= 1 << _ID_BITS:
            known, keys = None, np.zeros(len(edge), dtype=np.int64)  # too many to key
        else:
            keys = (edge.astype(np.int64) << 2 * _ID_BITS) | (uid[tail] << _ID_BITS) | uid[head]
        bound = np.full(len(edge), np.nan)
        floor = np.full(len(edge), -np.inf)  # the bound of the arc between the cells' parents
        if known is not None and len(known[0]):
            bound = _lookup(known, keys, np.nan)
        todo = np.flatnonzero(np.isnan(bound))
        if known is not None and len(known[0]) and len(todo):
            up = np.r_[np.arange(n), n + parts.parent]  # a node's uid -> its parent's
            parent_keys = ((edge[todo].astype(np.int64) << 2 * _ID_BITS)
                           | (up[uid[tail[todo]]] << _ID_BITS) | up[uid[head[todo]]])  # fmt: skip
            floor[todo] = _lookup(known, parent_keys, -np.inf)
        for part in np.array_split(todo, max(1, len(todo) // BOUND_CHUNK)):
            if time.perf_counter() >= deadline:
                raise OutOfTime(f"time limit reached while bounding the {len(edge)} arcs of "
                                 "a network of date cells")  # fmt: skip
            j = edge_to[edge[part]]  # in parts: the bound's temporaries stay small
            bound[part] = legs_table.box_bound(
                edge[part], self.node_lo[tail[part]], self.node_hi[tail[part]],
                self.node_lo[head[part]] - nodes.ops_days[j],
                self.node_hi[head[part]] - nodes.ops_days[j], rule=nodes.rule, j2=nodes.j2,
                t_min=nodes.tmin_days, floor=floor[part])  # fmt: skip
        order = np.argsort(keys)
        parts.arc_bounds = (keys[order], bound[order])  # for the next network
        finite = np.isfinite(bound)
        self.edge = edge[finite]
        self.arcs = Arcs(tail[finite], head[finite], edge_from[self.edge], edge_to[self.edge],
                         bound[finite] + nodes.cost_mps[edge_to[self.edge]])  # fmt: skip

    def pruned(self, nodes: CertifiedNodes, start_allowed, upper: float, settled=(),
               neighbourhoods=None):  # fmt: skip
        """Arcs that can lie on a plan within ``upper``, and the relaxation over them.

        Leg 0 leaves a start node (its operations cost added to the arc), later legs
        leave cells.  An arc leaves when the cheapest walk of L legs through it exceeds
        ``upper`` (:func:`~sdc_cvx.network.path_bounds.walk_bounds`).  The relaxation,
        the cheapest path of the network that is none of the ``settled`` ones, is then
        solved by labels (:func:`~sdc_cvx.network.path_bounds.cheapest_path`); where
        they are too many, by ng-route labels (:func:`~sdc_cvx.network.ng_routes.
        route_relaxation`, from ``neighbourhoods``, a previous network's; the grown ones
        are kept in ``self.neighbourhoods``), exact when the cheapest route is a path.
        Where neither solves it, arcs also leave when the cheapest path through them
        exceeds ``upper`` (:func:`~sdc_cvx.network.path_bounds.elementary_bounds`),
        for the relaxation MILP that then solves it (the routes' bound still counts).

        Returns
        -------
        arcs : Arcs
        exact : CheapestPath or None
            The relaxation's path, None when the labels were too many.
        bound : float
            No path of the network that is not settled costs less [m/s].
        """
        a = self.arcs
        from_start = a.tail < self.n_debris
        cost = np.where(from_start, a.cost + nodes.cost_mps[a.debris_from], a.cost)
        priced = Arcs(a.tail, a.head, a.debris_from, a.debris_to, cost)
        network = NetworkArcs(priced.tail, priced.head, priced.debris_from, priced.debris_to,
                              priced.cost, self.n_nodes, np.asarray(start_allowed))  # fmt: skip
        walks = walk_bounds(network, nodes.legs)
        self.completion = walks[1]
        near = walks[2] <= upper + 1e-9  # inf: on no walk
        routes, self.neighbourhoods = -np.inf, neighbourhoods  # -inf: no route bound yet
        if np.isfinite(upper):
            exact = cheapest_path(network.take(near), nodes.legs, self.node_debris, upper,
                                  walks, excluded=settled,
                                  must_visit=nodes.must_visit)  # fmt: skip
            if exact is None and not len(nodes.must_visit):  # routes forget what they visited
                relaxed = route_relaxation(network.take(near), nodes.legs, self.node_debris,
                                           upper, walks, excluded=settled,
                                           neighbourhoods=neighbourhoods,
                                           deadline=self.deadline)  # fmt: skip
                self.neighbourhoods, exact, routes = (relaxed.neighbourhoods, relaxed.path,
                                                      relaxed.bound)  # fmt: skip
            if exact is not None:
                return priced.take(near), exact, exact.cost
        through, cheapest = elementary_bounds(network, nodes.legs, self.node_debris, upper, walks)
        if through is None:
            through = walks[2]
        keep = np.isfinite(through) & (through <= upper + 1e-9)  # inf: on no path
        return priced.take(keep), None, max(cheapest, routes)


def refine_cells(parts: DateCells, net: CellNetwork, arcs: Arcs, chosen, pieces: int = 2):
    """Halve the date cells the relaxation's arcs leave from and arrive in."""
    cells = set()
    for a in chosen:
        for node in (arcs.tail[a], arcs.head[a]):
            if net.node_cell[node] >= 0:
                cells.add((int(net.node_debris[node]), int(net.node_cell[node])))
    for debris, cell in sorted(cells, key=lambda dc: (dc[0], -dc[1])):
        parts.split(debris, cell, pieces)


def beam_paths(
    arcs: Arcs,
    n_debris: int,
    nodes: CertifiedNodes,
    start_allowed,
    *,
    exclude=(),
    width: int = BEAM_WIDTH,
    count: int = 1,
    completion=None,
) -> list[tuple[float, tuple, tuple]]:
    """Cheapest simple paths under the arc bounds, leg by leg (a beam search).

    Partial paths are ranked by their cost plus ``completion[k][node]``, the cheapest walk
    of the k legs left from their last node (A*-like; without it, by cost so far).

    Returns up to ``count`` distinct debris paths not in ``exclude`` that visit
    ``must_visit``, as ``(cost, debris path, rows of arcs)``, cheapest first.
    """
    L = nodes.legs
    n_nodes = int(max(np.max(arcs.tail, initial=-1), np.max(arcs.head, initial=-1))) + 1
    groups = grouped(arcs.tail, np.ones(len(arcs), dtype=bool), max(n_nodes, n_debris))
    node = np.flatnonzero(start_allowed)  # the start nodes are the debris' positions
    cost = np.zeros(len(node))
    paths, rows = node[:, None], np.empty((len(node), 0), dtype=int)
    for k in range(L):
        which, arc = leaving(groups, node)
        fresh = ~(paths[which] == arcs.debris_to[arc][:, None]).any(axis=1)
        which, arc = which[fresh], arc[fresh]
        grown = cost[which] + arcs.cost[arc]
        rank = grown + (completion[L - 1 - k][arcs.head[arc]] if completion is not None else 0.0)
        top = np.argsort(rank, kind="stable")[:width]
        which, arc = which[top], arc[top]
        node, cost = arcs.head[arc], grown[top]
        paths = np.column_stack([paths[which], arcs.debris_to[arc]])
        rows = np.column_stack([rows[which], arc])
    required, excluded = set(nodes.must_visit), set(exclude)
    out, seen = [], set()
    for best in np.argsort(cost, kind="stable"):
        path = tuple(int(v) for v in paths[best])
        if path not in seen and path not in excluded and required <= set(path):
            seen.add(path)
            out.append((float(cost[best]), path, tuple(int(r) for r in rows[best])))
        if len(out) >= count:
            break
    return out
