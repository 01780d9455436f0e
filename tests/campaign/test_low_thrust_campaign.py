"""A low-thrust campaign against an enumeration of disjoint debris sets.

Each mission's optimum over a set of debris comes from the independent low-thrust brute
force (:mod:`tests.planner.low_thrust_bruteforce`, nothing of sdc_cvx), with the RAANs
carried to its launch day by that module's own J2 rate; every choice of disjoint sets is
enumerated.  ``solve_campaign`` must be within its 0.1 % gap of that optimum, certified,
with a bound never above it, and each of its missions must be a low-thrust mission.
"""

import itertools

import numpy as np

from sdc_cvx import Mission
from sdc_cvx.campaign.search import solve_campaign
from sdc_cvx.inputs.campaign import Campaign

from ..planner.low_thrust_bruteforce import optimum, raan_rate, random_catalog
from ..planner.test_low_thrust_certified import catalog_of

DAY = 86400.0
ACCEL = 1e-4


def mission_cost(synthetic, members, launch_day, n, tmax):
    index = list(members)
    raan = synthetic.raan_rad[index] + raan_rate(synthetic.a_m[index], synthetic.inc_rad[index],
                                                 synthetic.e[index]) * launch_day * DAY  # fmt: skip
    plan = optimum(synthetic.a_m[index], synthetic.e[index], synthetic.inc_rad[index], raan, n=n,
                   tmax_days=tmax, accel_mps2=ACCEL, rule="table3")  # fmt: skip
    return np.inf if plan is None else plan.cost_mps


def test_a_low_thrust_campaign_is_the_optimum_of_the_enumeration():
    synthetic = random_catalog(41, 6, kind="sso")
    launches, n, tmax = (0.0, 200.0), 2, 200.0
    debris = range(len(synthetic.a_m))
    brute = min(
        mission_cost(synthetic, first, launches[0], n, tmax)
        + mission_cost(synthetic, second, launches[1], n, tmax)
        for first in itertools.combinations(debris, n)
        for second in itertools.combinations(sorted(set(debris) - set(first)), n)
    )
    assert np.isfinite(brute)
    mission = Mission(n=n, tmax_days=tmax, transfer="low-thrust", vehicle={"accel_mps2": ACCEL})
    answer = solve_campaign(catalog_of(synthetic), Campaign.of(list(launches), mission),
                            workers=1)  # fmt: skip
    assert answer.certified
    assert answer.lower_bound_mps <= brute + 1e-6
    assert answer.total_dv_mps <= brute * 1.001
    assert all(m.mission.transfer == "low-thrust" for m in answer.missions)
