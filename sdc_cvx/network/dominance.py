"""Bounds on the answer: edges that cannot beat a plan in hand, and cheap plans to hold.

Part IV-B drops the edges that cost more than a fixed ΔVmax.  Once the driver holds a
plan that meets every constraint in the true model, its total ΔV U is a sharper bound:
an edge is *dominated* when every path of n debris through it costs more than U,
whatever its dates and drift orbits, so it can leave the MILP without losing any plan
cheaper than the one in hand.  Two lower bounds prove it, both pure numpy:

- :func:`transfer_dv_floor`: the cheapest transfer between two debris with no limit on
  its duration (Eq. 11-13 minimised over the drift radius and inclination): no leg
  between them costs less, at any departure date;
- :func:`path_cost_floor`: the cheapest walk of ``legs`` edges through each edge, by
  dynamic programming over those floors plus each debris' operations cost.  A walk may
  visit a debris twice, so it relaxes the path and stays a lower bound.

:func:`cheapest_paths` lists cheap candidate paths over the pre-optimised costs; the
driver re-optimises a few in the true model to hold a plan before the first MILP.

Equation, table and part numbers are those of Cerf's paper [1]_; the design
rationale is in ``docs/design.md``.

References
----------
.. [1] M. Cerf, "Multiple Space Debris Collecting Mission — Debris Selection and Trajectory
   Optimization", Journal of Optimization Theory and Applications 156(3), 761–796, 2013.
   doi:10.1007/s10957-012-0130-6
"""

from __future__ import annotations

import heapq

import numpy as np

from ..physics.leg_bounds import IMPULSIVE
from ..physics.orbits import MU_EARTH
from ..physics.transfer import NodeOrbits, minimize_on_interval

FLOOR_MARGIN_MPS = 0.01
"""Subtracted from each transfer floor [m/s]: covers the 1-D search's tolerance."""


def transfer_dv_floor(origin: NodeOrbits, target: NodeOrbits, a_low, a_high, *, mu=MU_EARTH,
                      model=IMPULSIVE):  # fmt: skip
    """Lower bound on the cost of any drift transfer from ``origin`` to ``target`` [m/s].

    ``min over a_d in [a_low, a_high], I_d in {I_i, I_j} of DV(a_d, I_d)`` (Eq. 11-13)
    with no duration constraint, minus :data:`FLOOR_MARGIN_MPS`.  The drift duration
    (Eq. 10) only restricts which radii are allowed, so no transfer between the two
    debris, leaving at any date with any duration, costs less.

    Parameters
    ----------
    origin, target : NodeOrbits
        Departure and target debris, arrays of shape (M,).
    a_low, a_high : float
        Drift radius bounds [m].

    Returns
    -------
    ndarray
        Shape (M,) [m/s].
    """
    m = len(origin.a)
    lo, hi = np.full(m, float(a_low)), np.full(m, float(a_high))
    kinks = np.stack([origin.a, target.a], axis=1)
    best = np.full(m, np.inf)
    for inc_drift in (origin.inc, target.inc):

        def cost(a, inc_drift=inc_drift):
            return model.leg_dv(origin.a[:, None], origin.inc[:, None], target.a[:, None],
                                target.inc[:, None], a, inc_drift[:, None], mu=mu)  # fmt: skip

        best = np.minimum(best, minimize_on_interval(cost, lo, hi, kinks)[1])
    return np.maximum(best - FLOOR_MARGIN_MPS, 0.0)


def path_cost_floor(edges_from, edges_to, edge_floor, node_cost, legs: int, first=None):
    """Lower bound on the cost of any path of ``legs`` edges that uses each edge [m/s].

    ``min over a + b = legs - 1 of E_a(i) + w_ij + L_b(j)`` where ``w_ij`` is the edge's
    floor plus the operations cost at j, ``E_a(v)`` the cheapest walk of a edges ending
    at v (its first debris' operations cost included) and ``L_b(v)`` the cheapest walk of
    b edges leaving v (v's cost excluded), both over the same edge list.

    Parameters
    ----------
    edges_from, edges_to : array_like of int
        Node positions of the edges, shape (m,); repeated pairs are allowed.
    edge_floor : array_like
        Lower bound on each edge's transfer cost [m/s], shape (m,).
    node_cost : array_like
        Operations cost C_k at each node [m/s], shape (N,).
    legs : int
        Edges on a path (n - 1, or n with an injection orbit).
    first : int, optional
        Node every path starts from.

    Returns
    -------
    ndarray
        Shape (m,) [m/s]; ``inf`` for an edge on no walk of ``legs`` edges.
    """
    i, j = np.asarray(edges_from, dtype=int), np.asarray(edges_to, dtype=int)
    node_cost = np.asarray(node_cost, dtype=float)
    weight = np.asarray(edge_floor, dtype=float) + node_cost[j]
    ending = node_cost.copy()
    if first is not None:
        ending = np.where(np.arange(len(node_cost)) == first, node_cost, np.inf)
    ending, leaving = [ending], [np.zeros_like(node_cost)]
    for _ in range(legs - 1):
        step = np.full_like(node_cost, np.inf)
        np.minimum.at(step, j, ending[-1][i] + weight)
        ending.append(step)
        step = np.full_like(node_cost, np.inf)
        np.minimum.at(step, i, weight + leaving[-1][j])
        leaving.append(step)
    through = [ending[a][i] + weight + leaving[legs - 1 - a][j] for a in range(legs)]
    return np.min(through, axis=0)


def cheapest_paths(edges_from, edges_to, cost, legs: int, *, first=None, must_visit=(),
                   width: int = 200) -> list[tuple]:  # fmt: skip
    """Cheap simple paths of ``legs`` edges by summed edge cost, from a beam search.

    Step k extends the ``width`` cheapest partial paths by every edge that leaves their
    last node for a node not yet on them, at that edge's cost as leg k.  A heuristic:
    the cheapest path may fall out of the beam (it cannot when ``width`` covers every
    partial path).

    Parameters
    ----------
    edges_from, edges_to : array_like of int
        Node positions of the edges, shape (m,).
    cost : array_like
        Cost of each edge, shape (m,), or of each edge as each leg, shape (legs, m),
        e.g. pre-optimised ΔV [m/s]; an infinite cost bars the edge (at that leg).
    legs : int
        Edges on a path.
    first : int, optional
        Node every path starts from.
    must_visit : sequence of int
        Nodes every returned path contains.
    width : int
        Partial paths kept at each step.

    Returns
    -------
    list of (float, tuple of int, tuple of int)
        ``(cost, nodes, edges)`` of each path, cheapest first, at most ``width``.
    """
    i, j = np.asarray(edges_from, dtype=int), np.asarray(edges_to, dtype=int)
    cost = np.broadcast_to(np.asarray(cost, dtype=float), (legs, len(i)))
    leaving: dict[int, list[int]] = {}
    for e in range(len(i)):
        leaving.setdefault(int(i[e]), []).append(e)
    starts = [first] if first is not None else sorted(leaving)
    beam = [(0.0, (int(v),), ()) for v in starts]
    for leg in range(legs):
        grown = [(total + cost[leg, e], nodes + (int(j[e]),), edges + (e,))
                 for total, nodes, edges in beam for e in leaving.get(nodes[-1], ())
                 if j[e] not in nodes and np.isfinite(cost[leg, e])]  # fmt: skip
        beam = heapq.nsmallest(width, grown)
    required = set(must_visit)
    return [path for path in beam if required <= set(path[1])]
