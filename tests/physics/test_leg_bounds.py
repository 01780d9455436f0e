"""Leg costs and box bounds (sdc_cvx.physics.leg_bounds) against the transfer physics.

Every check is made with ``sdc_cvx.physics.transfer`` directly: a drift orbit chosen at
random, its true duration from Eq. 10 and its true cost from Eq. 11-13.  If that leg
leaves and arrives inside a box, the box's bound must not exceed its cost.
"""

import numpy as np
import pytest

from sdc_cvx.inputs.synthetic import sso_catalog
from sdc_cvx.physics.leg_bounds import LegCosts, leg_box_bound, leg_cost_at
from sdc_cvx.physics.orbits import J2, R_EARTH, SECONDS_PER_DAY
from sdc_cvx.physics.transfer import (
    NodeOrbits,
    drift_inclination,
    drift_rate,
    transfer_duration,
    transfer_dv,
)

A_LOW, A_HIGH = R_EARTH + 400e3, R_EARTH + 1200e3


@pytest.fixture(scope="module")
def table():
    catalog = sso_catalog(12, seed=4, altitude_km=(500.0, 1100.0), inclination_spread_deg=2.0)
    orbits = NodeOrbits.from_elements(catalog.a_m, catalog.e, catalog.inc_rad, catalog.raan_rad)
    i, j = np.nonzero(~np.eye(len(catalog), dtype=bool))
    return orbits, i, j, LegCosts.build(orbits.take(i), orbits.take(j), A_LOW, A_HIGH)


def random_legs(orbits, i, j, rng, count, rule):
    """Random edges, departure dates and drift orbits, with their true duration and cost."""
    e = rng.integers(0, len(i), count)
    t = rng.uniform(0.0, 300.0, count)
    a = rng.uniform(A_LOW, A_HIGH, count)
    origin, target = orbits.take(i[e]), orbits.take(j[e])
    inc = np.where(rng.integers(0, 2, count) == 0, origin.inc, target.inc)
    side = np.sign(drift_rate(a, inc) - target.rate)
    allowed = np.ones(count, dtype=bool)
    if rule == "table3":
        allowed = inc == drift_inclination(origin.inc, target.inc, side)
    days = transfer_duration(origin, target, a, inc, t * SECONDS_PER_DAY) / SECONDS_PER_DAY
    cost = transfer_dv(origin.a, origin.inc, target.a, target.inc, a, inc)
    return e[allowed], t[allowed], days[allowed], cost[allowed]


@pytest.mark.parametrize("rule", ["table3", "free"])
@pytest.mark.parametrize("t_min", [0.0, 5.0])
def test_box_bound_never_exceeds_a_true_leg_inside_the_box(table, rule, t_min):
    orbits, i, j, legs = table
    rng = np.random.default_rng(11)
    e, t, days, cost = random_legs(orbits, i, j, rng, 40_000, rule)
    keep = (days >= t_min) & (days < 400)
    e, t, days, cost = e[keep], t[keep], days[keep], cost[keep]
    # a random box around each true leg: its departure and arrival inside
    w1, w2 = rng.exponential(3.0, len(e)), rng.exponential(3.0, len(e))
    f1, f2 = rng.uniform(size=len(e)), rng.uniform(size=len(e))
    t1, t3 = t - f1 * w1, t + days - f2 * w2
    bound = leg_box_bound(legs, e, t1, t1 + w1, t3, t3 + w2, rule=rule, j2=J2, t_min=t_min)
    assert len(e) > 3000
    assert np.all(bound <= cost + 1e-9), np.max(bound - cost)
    # a box shrunk to a point bounds by the exact cheapest leg between those two dates
    point = leg_box_bound(legs, e, t, t, t + days, t + days, rule=rule, j2=J2, t_min=t_min)
    exact, *_ = leg_cost_at(legs, e, t, t + days, rule=rule, j2=J2, t_min=t_min)
    np.testing.assert_allclose(point, exact, atol=1e-6)
    assert np.all(point <= cost + 1e-9)


@pytest.mark.parametrize("rule", ["table3", "free"])
@pytest.mark.parametrize("t_min", [0.0, 5.0])
def test_one_edge_over_many_boxes_is_that_edge_repeated_per_box(table, rule, t_min):
    """A scalar edge (the fixed path's call: its constants computed once) bounds each box
    exactly as the edge given once per box (the certified network's call)."""
    _, i, _, legs = table
    rng = np.random.default_rng(7)
    finite = 0
    for e in rng.integers(0, len(i), 6):
        t1, t3 = rng.uniform(0.0, 300.0, 2000), rng.uniform(0.0, 365.0, 2000)
        t2, t4 = t1 + rng.exponential(10.0, 2000), t3 + rng.exponential(10.0, 2000)
        scalar = leg_box_bound(legs, e, t1, t2, t3, t4, rule=rule, j2=J2, t_min=t_min)
        repeated = leg_box_bound(legs, np.full(2000, e), t1, t2, t3, t4, rule=rule, j2=J2,
                                 t_min=t_min)  # fmt: skip
        np.testing.assert_array_equal(scalar, repeated)
        finite += np.isfinite(scalar).sum()
        cost, a, *_ = leg_cost_at(legs, e, t1, t3, rule=rule, j2=J2, t_min=t_min)
        cost_r, a_r, *_ = leg_cost_at(legs, np.full(2000, e), t1, t3, rule=rule, j2=J2,
                                      t_min=t_min)  # fmt: skip
        np.testing.assert_array_equal(cost, cost_r)
        np.testing.assert_array_equal(a, a_r)
    assert finite > 500


def test_cost_at_dates_reproduces_the_transfer_physics(table):
    """leg_cost_at's drift orbit, flown from the departure date, arrives on the date asked."""
    orbits, i, j, legs = table
    rng = np.random.default_rng(3)
    e = rng.integers(0, len(i), 5000)
    t = rng.uniform(0, 300, 5000)
    arrive = t + rng.uniform(0.5, 150, 5000)
    cost, a, inc, *_ = leg_cost_at(legs, e, t, arrive, rule="free", j2=J2)
    ok = np.isfinite(cost)
    assert ok.sum() > 300
    origin, target = orbits.take(i[e[ok]]), orbits.take(j[e[ok]])
    days = transfer_duration(origin, target, a[ok], inc[ok], t[ok] * SECONDS_PER_DAY)
    np.testing.assert_allclose(t[ok] + days / SECONDS_PER_DAY, arrive[ok], atol=1e-6)
    true_cost = transfer_dv(origin.a, origin.inc, target.a, target.inc, a[ok], inc[ok])
    np.testing.assert_allclose(cost[ok], true_cost, atol=1e-9)


def test_minimum_on_an_interval_matches_a_dense_grid(table):
    """The exact minimum (ends, kinks, local minima) is never above a 2 m radius grid's."""
    _, i, _, legs = table
    rng = np.random.default_rng(5)
    for _ in range(200):
        e, c = int(rng.integers(0, len(i))), int(rng.integers(0, 2))
        lo = rng.uniform(A_LOW, A_HIGH)
        hi = min(A_HIGH, lo + rng.exponential(150e3))
        value, argmin = legs.minimum_on(e, c, lo, hi)
        grid = np.linspace(lo, hi, max(2, int((hi - lo) / 2.0)))
        dense = legs.cost(e, c, grid).min()
        assert value <= dense + 1e-9
        assert value >= dense - 2e-3  # 2 m of radius costs at most ~2 mm/s
        assert lo <= argmin <= hi
        assert legs.cost(e, c, argmin) == pytest.approx(value, abs=1e-9)


def test_a_table_built_again_reuses_its_scan_and_only_for_the_same_legs(table):
    """A campaign builds each launch's tables every round: the scan of minimisers (no date
    in it) is kept; another launch day (other RAANs) shares it, other radii do not."""
    from sdc_cvx.physics import leg_minima

    orbits, i, j, legs = table
    later = orbits._replace(raan=orbits.raan + 1.0)  # the same debris at another launch day
    again = LegCosts.build(later.take(i), later.take(j), A_LOW, A_HIGH)
    assert again.candidates is legs.candidates and not legs.candidates.flags.writeable
    leg_minima._TABLES.clear()
    fresh = LegCosts.build(orbits.take(i), orbits.take(j), A_LOW, A_HIGH)
    assert fresh.candidates is not legs.candidates
    np.testing.assert_array_equal(fresh.candidates, legs.candidates)
    moved = orbits._replace(a=orbits.a + 1e3)
    other = LegCosts.build(moved.take(i), moved.take(j), A_LOW, A_HIGH)
    assert other.candidates is not fresh.candidates
    assert not np.allclose(np.nan_to_num(other.candidates), np.nan_to_num(fresh.candidates))
