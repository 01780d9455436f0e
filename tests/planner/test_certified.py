"""Pieces of the certified search that the brute-force tests cannot isolate."""

import numpy as np

from sdc_cvx import Catalog
from sdc_cvx.physics.leg_bounds import LegCosts
from sdc_cvx.physics.orbits import R_EARTH
from sdc_cvx.physics.transfer import NodeOrbits
from sdc_cvx.planner.certified import CertifiedNodes, _Network, _Partitions

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
    parts = _Partitions(n, nodes.ops_days, nodes.tmax_days, 4)
    net = _Network(nodes, legs, i, j, parts, np.ones(len(i), dtype=bool))
    assert np.any(net.arcs.tail < n)  # first legs from every start exist before pruning
    arcs, walk = net.pruned(nodes, np.arange(n) == first, np.inf)
    starts = arcs.tail[arcs.tail < n]
    assert len(starts) > 0 and np.all(starts == first)
    assert np.isfinite(walk)
