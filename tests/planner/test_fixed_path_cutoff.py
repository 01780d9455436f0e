"""A schedule search stopped by a cutoff still proves a true bound (issue 27, 5).

``solve_path`` with a cutoff once returned, as the path's lower bound, the DP over the date
cells it kept: the cells it dropped above the cutoff could hold the path's optimum, and the
bound then exceeded it (by up to 4 mm/s here; 11 mm/s in the review).  A campaign reuses
such bounds as proven.  The reference is the independent brute force's plan of the path,
which flies (:mod:`tests.planner.bruteforce`): no bound may exceed it.
"""

from __future__ import annotations

import numpy as np
import pytest

from sdc_cvx import Catalog
from sdc_cvx.physics.leg_bounds import LegCosts
from sdc_cvx.physics.orbits import R_EARTH
from sdc_cvx.physics.transfer import NodeOrbits
from sdc_cvx.planner.fixed_path import PathProblem, solve_path

from .bruteforce import Enumeration


@pytest.fixture(scope="module")
def brute():
    return Enumeration(Catalog.paper_case(), 4, 365.25, middle_count=2001)


@pytest.mark.parametrize("path", [(9, 1, 7, 5), (7, 8, 9, 10)])
def test_the_bound_of_a_cut_off_search_is_never_above_a_plan_that_flies(brute, path):
    flies = brute.path_optimum(list(path), "table3").dv
    catalog = Catalog.paper_case()
    orbits = NodeOrbits.from_elements(catalog.a_m, catalog.e, catalog.inc_rad, catalog.raan_rad)
    i, j = np.array(path[:-1]), np.array(path[1:])
    legs = LegCosts.build(orbits.take(i), orbits.take(j), R_EARTH + 400e3, R_EARTH + 1200e3)
    problem = PathProblem(legs, (0, 1, 2), (0.0,) * 4, 365.25, 0.0, "table3", 1.08263e-3)
    for below in (0.003, 0.01, 0.03, 0.1, 0.3):
        schedule = solve_path(problem, tol_mps=0.01, cutoff_mps=flies - below)
        assert schedule.lower_mps <= flies + 1e-9, below
        assert schedule.lower_mps > flies - below - 0.05  # and still proves about the cutoff
