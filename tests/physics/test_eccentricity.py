"""The eccentricity priced in the planner's leg (issue 46, item 2).

- The form and the required change, written again here from the issue's text.
- SGP4's mean eccentricity vector: an element set's osculating vector, averaged over one
  orbit of SGP4's own propagation (the sgp4 package, TEME, read here), is the element
  set's ``e (cos w, sin w)`` plus J3's constant along the node frame's y axis.
- The bound: no leg of a box costs less than its bound (a brute force over the box's
  dates, GTOC9's debris, whose eccentricities reach 0.019), and the bound of a small box
  is its legs' cost (the search converges).
"""

import math

import numpy as np
import pytest

from sdc_cvx.physics.eccentricity import (
    Eccentricities,
    priced,
    required_change,
    room,
)
from tests.conftest import shared_file

MU = 3.986e14
J2 = 1.08263e-3
R_EQ = 6378137.0


def argp_rate(a, e, inc):
    """Vallado Eq. 9-41, written again [rad/s]."""
    n = math.sqrt(MU / a**3)
    return 0.75 * n * J2 * (R_EQ / (a * (1 - e * e))) ** 2 * (5 * math.cos(inc) ** 2 - 1)


def test_the_form_is_the_issues():
    # dv = sqrt(dv_paper^2 + (v/2)^2 (max(de, rho)^2 - rho^2))
    for dv, de, rho, v in ((30.0, 0.004, 0.001, 7500.0), (12.0, 0.001, 0.003, 7400.0),
                           (0.0, 0.01, 0.0, 7600.0)):  # fmt: skip
        expected = math.sqrt(dv**2 + (v / 2) ** 2 * (max(de, rho) ** 2 - rho**2))
        assert priced(dv, de, rho, v) == pytest.approx(expected, rel=1e-12)
    assert room(7000e3, 7050e3, 7020e3) == pytest.approx((50e3 + 30e3) / 7010e3, rel=1e-12)
    assert room(7000e3, 7010e3, 7020e3) == pytest.approx(20e3 / 7010e3, rel=1e-12)


def test_the_required_change_turns_each_vector_at_its_rate():
    a_i, a_j, inc = 7100e3, 7150e3, math.radians(98.5)
    ecc = Eccentricities.from_elements(np.array([a_i, a_j]), np.array([0.004, 0.01]),
                                       np.array([inc, inc]), np.radians([30.0, 200.0]),
                                       frozen=False, j2=J2, mu=MU)  # fmt: skip
    t_d, t_a, drift = 5 * 86400.0, 60 * 86400.0, argp_rate(7120e3, 0.0, inc)
    w_i = math.radians(30.0) + argp_rate(a_i, 0.004, inc) * t_d + drift * (t_a - t_d)
    w_j = math.radians(200.0) + argp_rate(a_j, 0.01, inc) * t_a
    expected = math.hypot(0.01 * math.cos(w_j) - 0.004 * math.cos(w_i),
                          0.01 * math.sin(w_j) - 0.004 * math.sin(w_i))  # fmt: skip
    got = required_change(ecc.take(0), ecc.take(1), t_d, t_a, drift)
    assert got == pytest.approx(expected, rel=1e-9)


@pytest.mark.requires_shared_data("sso_rocket_bodies_2020/sso_rb.tle")
def test_sgp4s_mean_vector_has_j3s_constant_term():
    from sgp4.api import Satrec

    lines = shared_file("sso_rocket_bodies_2020/sso_rb.tle").read_text().splitlines()
    checked = 0
    for k in range(0, 60, 3):
        satrec = Satrec.twoline2rv(lines[k + 1], lines[k + 2])
        period = 2 * math.pi / satrec.no_kozai * 60.0  # [s]
        minutes = np.arange(64) * period / 64 / 60.0
        errors, r, v = satrec.sgp4_array(np.full(64, satrec.jdsatepoch),
                                         satrec.jdsatepochF + minutes / 1440.0)  # fmt: skip
        assert not errors.any()
        r, v = np.asarray(r) * 1e3, np.asarray(v) * 1e3
        mu = 398600.8e9  # WGS-72, SGP4's
        e_vec = ((np.sum(v * v, 1) - mu / np.linalg.norm(r, axis=1))[:, None] * r
                 - np.sum(r * v, 1)[:, None] * v) / mu  # fmt: skip
        h = np.cross(r, v).mean(0)
        h /= np.linalg.norm(h)
        node = np.cross([0, 0, 1.0], h)
        node /= np.linalg.norm(node)
        mean = e_vec.mean(0)
        got = np.array([mean @ node, mean @ np.cross(h, node)])
        a = (mu / (satrec.no_kozai / 60.0) ** 2) ** (1 / 3)
        ours = Eccentricities.from_elements(a, satrec.ecco, satrec.inclo, satrec.argpo,
                                            frozen=True)  # fmt: skip
        expected = np.array([float(ours.ex), float(ours.ey + ours.fixed_y)])
        # the averaging leaves J2's short-period terms at a few 1e-5
        assert np.linalg.norm(got - expected) < 1e-4, (k, got, expected)
        without = np.array([float(ours.ex), float(ours.ey)])
        assert np.linalg.norm(got - without) > 5e-4  # the term is there: ~1e-3
        checked += 1
    assert checked == 20


@pytest.fixture(scope="module")
def gtoc9_legs():
    from sdc_cvx import Mission, read_catalog
    from sdc_cvx.network.edges import drift_radius_bounds, node_eccentricities, node_orbits
    from sdc_cvx.physics.leg_bounds import LegCosts

    catalog = read_catalog(shared_file("gtoc9/debris_data.txt"))
    mission = Mission().for_catalog(catalog)
    assert mission.eccentricity == "on"
    orbits, ecc = node_orbits(catalog, mission), node_eccentricities(catalog, mission)
    # pairs of close radii and inclinations (cheap legs, whose ΔV the eccentricity weighs
    # on) of the most eccentric debris
    a, inc, ecc_size = catalog.a_m, catalog.inc_rad, catalog.e
    pairs = [(i, j) for i in range(len(a)) for j in range(len(a))
             if i != j and abs(a[i] - a[j]) < 15e3 and abs(inc[i] - inc[j]) < 0.005]
    pairs = sorted(pairs, key=lambda p: -max(ecc_size[p[0]], ecc_size[p[1]]))[:40]
    origin, target = np.array([p[0] for p in pairs]), np.array([p[1] for p in pairs])
    low, high = drift_radius_bounds(mission)
    return LegCosts.build(orbits.take(origin), orbits.take(target), low, high,
                          eccentricity=(ecc.take(origin), ecc.take(target)))  # fmt: skip


@pytest.mark.requires_shared_data("gtoc9/debris_data.txt")
@pytest.mark.parametrize("seed", range(4))
def test_no_leg_of_a_box_costs_less_than_its_bound(gtoc9_legs, seed):
    rng = np.random.default_rng(seed)
    legs = gtoc9_legs
    e = np.arange(len(legs.origin.a))
    t1 = rng.uniform(0.0, 200.0, len(e))
    t2 = t1 + rng.uniform(0.5, 20.0, len(e))
    t3 = t2 + rng.uniform(5.0, 120.0, len(e))
    t4 = t3 + rng.uniform(0.5, 20.0, len(e))
    bound = legs.box_bound(e, t1, t2, t3, t4, rule="table3", j2=J2, t_min=10.0)
    worst = np.inf
    for f in np.linspace(0.0, 1.0, 9):
        for g in np.linspace(0.0, 1.0, 9):
            t, t_arrive = t1 + f * (t2 - t1), t3 + g * (t4 - t3)
            cost = legs.cost_at(e, t, t_arrive, rule="table3", j2=J2, t_min=10.0).cost
            finite = np.isfinite(cost)
            assert np.all(cost[finite] >= bound[finite] - 1e-9)
            margin = np.where(finite, cost - np.where(finite, bound, 0.0), np.inf)
            worst = min(worst, float(np.min(margin)))
    assert np.isfinite(worst)  # some legs of every box fly


@pytest.mark.requires_shared_data("gtoc9/debris_data.txt")
def test_the_bound_of_a_small_box_is_its_legs_cost(gtoc9_legs):
    legs = gtoc9_legs
    e = np.arange(len(legs.origin.a))
    t, t_arrive, least = np.full(len(e), 40.0), np.full(len(e), np.nan), np.full(len(e), np.inf)
    for duration in np.arange(10.0, 700.0, 5.0):  # each leg's cheapest duration
        cost = legs.cost_at(e, t, t + duration, rule="table3", j2=J2).cost
        t_arrive = np.where(cost < least, t + duration, t_arrive)
        least = np.minimum(cost, least)
    cost = legs.cost_at(e, t, t_arrive, rule="table3", j2=J2).cost
    width = 1e-4  # days
    bound = legs.box_bound(e, t, t + width, t_arrive, t_arrive + width, rule="table3", j2=J2)
    finite = np.isfinite(cost)
    assert finite.sum() > 8
    # the eccentricity is priced on these legs: a bound of the paper's part would not do
    paper = LegCostsPaper(legs).cost_at(e, t, t_arrive, rule="table3", j2=J2).cost
    assert np.sum(cost[finite] > paper[finite] + 5.0) >= 3
    np.testing.assert_allclose(bound[finite], cost[finite], rtol=1e-3)


def LegCostsPaper(legs):  # noqa: N802 - the same table without the eccentricity
    import dataclasses

    return dataclasses.replace(legs, eccentricity=None)
