"""The low-thrust leg (issue 29) against computations written again here from its formulas.

Nothing of the leg's physics is imported to compute a reference: the J2 rate, the
spirals and the plane change are integrated numerically (scipy) from the averaged
equations, and the exact costs and bounds are compared with a dense scan of drift radii
flown by those equations.
"""

import numpy as np
import pytest
from scipy.integrate import quad, solve_ivp

from sdc_cvx.physics.leg_bounds import LegCosts
from sdc_cvx.physics.low_thrust import (
    LowThrustModel,
    edelbaum_transfer,
    leg_dv,
    leg_phases,
    spiral_raan_change,
)
from sdc_cvx.physics.low_thrust_bounds import (
    BOUND_TOL_MPS,
    _at_speed,
    _linear_range,
    _mean_value,
)
from sdc_cvx.physics.low_thrust_pieces import edge_table
from sdc_cvx.physics.transfer import NodeOrbits, hohmann_dv

R = 6378137.0
MU = 3.986e14
J2 = 1.08263e-3
DAY = 86400.0


def j2_rate(a, inc):
    """dOmega/dt [rad/s] of a circular orbit, written again (Eq. 7, e = 0)."""
    return -1.5 * J2 * np.sqrt(MU) * R**2 * a**-3.5 * np.cos(inc)


def speed(a):
    return np.sqrt(MU / a)


def test_spiral_matches_the_issue_figures_and_a_quadrature():
    """800 -> 700 km at 98.6 deg, f = 1e-4 m/s^2: 6.13139 deg, 52.455 m/s, 6.071 days."""
    f, inc = 1e-4, np.radians(98.6)
    a1, a2 = R + 800e3, R + 700e3
    # tangential thrust on a quasi-circular orbit: da/dt = -2 f a^(3/2) / sqrt(mu) (lowering)
    seconds, _ = quad(lambda a: 1.0 / (2.0 * f * a**1.5 / np.sqrt(MU)), a2, a1)
    turned, _ = quad(lambda a: j2_rate(a, inc) / (2.0 * f * a**1.5 / np.sqrt(MU)), a2, a1)
    assert seconds / DAY == pytest.approx(6.071, abs=5e-4)
    assert abs(np.degrees(turned)) == pytest.approx(6.13139, abs=5e-5)
    dv = leg_dv(a1, inc, a2, inc, a2)
    assert dv == pytest.approx(52.455, abs=5e-4)
    assert dv / f == pytest.approx(seconds, rel=1e-9)
    assert spiral_raan_change(a1, a2, inc, f, j2=J2, mu=MU) == pytest.approx(turned, rel=1e-9)


def test_edelbaum_general_formula_leo_to_geo():
    """poliastro's case: 7000 -> 42166 km, 28.5 deg, f = 3.5e-7 km/s^2."""
    mu = 3.986004418e14
    dv, seconds = edelbaum_transfer(np.sqrt(mu / 7000e3), np.sqrt(mu / 42166e3),
                                    np.radians(28.5), 3.5e-4)  # fmt: skip
    assert dv / 1e3 == pytest.approx(5.7838, abs=1e-4)
    assert seconds / DAY == pytest.approx(191.26, abs=0.01)


def averaged_flight(origin, target, a_d, inc_d, t_depart, f, coast_s):
    """The leg flown by integrating the averaged equations phase by phase [rad, s]."""
    (a_i, inc_i, raan_i, rate_i), (a_j, inc_j, _, _) = origin, target
    omega = raan_i + rate_i * t_depart

    def spiral(a_from, a_to, inc):
        sign = 1.0 if a_to > a_from else -1.0

        def rhs(_, y):
            return [sign * 2.0 * f * y[0] ** 1.5 / np.sqrt(MU), j2_rate(y[0], inc)]

        if a_to == a_from:
            return 0.0, 0.0
        hit = lambda _, y: y[0] - a_to  # noqa: E731
        hit.terminal = True
        sol = solve_ivp(rhs, (0, 1e9), [a_from, 0.0], events=hit, rtol=1e-11, atol=1e-6)
        return sol.t[-1], sol.y[1, -1]

    def plane_change():
        if inc_i == inc_j:
            return 0.0, 0.0
        rate = np.sign(inc_j - inc_i) * (2.0 / np.pi) * f / speed(a_d)
        seconds = (inc_j - inc_i) / rate
        sol = solve_ivp(lambda _, y: [rate, j2_rate(a_d, y[0])], (0, seconds), [inc_i, 0.0],
                        rtol=1e-11, atol=1e-12)  # fmt: skip
        return seconds, sol.y[1, -1]

    total_t = 0.0
    for seconds, turned in (spiral(a_i, a_d, inc_i), plane_change(), spiral(a_d, a_j, inc_j)):
        total_t += seconds
        omega += turned
    omega += j2_rate(a_d, inc_d) * coast_s
    return omega, total_t + coast_s


@pytest.mark.parametrize("inc_d_is_target", [False, True])
def test_a_whole_leg_closes_the_raan_at_arrival_in_the_averaged_equations(inc_d_is_target):
    rng = np.random.default_rng(29)
    f = 1e-4
    a = R + np.array([700e3, 820e3])
    inc = np.radians([98.2, 98.9])
    raan = np.array([0.3, 1.1])
    orbits = NodeOrbits.from_elements(a, np.zeros(2), inc, raan, j2=J2, mu=MU)
    origin, target = orbits.take([0]), orbits.take([1])
    model = LowThrustModel(f)
    for _ in range(3):
        a_d = R + rng.uniform(450e3, 1150e3)
        inc_d = inc[1] if inc_d_is_target else inc[0]
        t = rng.uniform(0, 100) * DAY
        total = model.leg_seconds(origin, target, a_d, inc_d, t, j2=J2, mu=MU)[0]
        thrust = leg_dv(a[0], inc[0], a[1], inc[1], a_d, mu=MU) / f
        coast = total - thrust
        assert coast >= 0
        omega, duration = averaged_flight((a[0], inc[0], raan[0], orbits.rate[0]),
                                          (a[1], inc[1], raan[1], orbits.rate[1]), a_d, inc_d,
                                          t, f, coast)  # fmt: skip
        target_raan = raan[1] + orbits.rate[1] * (t + duration)
        assert duration == pytest.approx(total, rel=1e-7)
        miss = np.angle(np.exp(1j * (omega - target_raan)))
        assert abs(miss) < 1e-6


def test_a_coplanar_leg_tends_to_the_impulsive_leg_to_first_order():
    """Spirals cost |V_i - V_d| + |V_d - V_j|; Hohmann the same to first order in da/a."""
    a_i, a_j = R + 700e3, R + 720e3
    for a_d in (R + 690e3, R + 710e3, R + 740e3):
        low = leg_dv(a_i, 1.7, a_j, 1.7, a_d)
        impulsive = hohmann_dv(a_i, a_d) + hohmann_dv(a_d, a_j)
        assert low == pytest.approx(impulsive, rel=2e-3)


def test_the_plane_change_costs_pi_over_two_more_than_an_impulse():
    a, di = R + 800e3, np.radians(0.5)
    phases = leg_phases(a, 1.70, a, 1.70 + di, a, 1e-4)
    assert phases.dv_plane == pytest.approx(0.5 * np.pi * hohmann_dv(a, a, di), rel=1e-4)


@pytest.fixture(scope="module", params=["sso", "prograde"])
def table(request):
    """Edges of six debris: SSO (retrograde, the J2 rate rises with the drift speed) or
    prograde at 70-75 deg (it falls: rel's ends swap)."""
    rng = np.random.default_rng(7)
    n = 6
    a = R + rng.uniform(600e3, 1000e3, n)
    low, high = (96.0, 100.0) if request.param == "sso" else (70.0, 75.0)
    inc = np.radians(rng.uniform(low, high, n))
    orbits = NodeOrbits.from_elements(a, np.zeros(n), inc, rng.uniform(0, 2 * np.pi, n), j2=J2,
                                      mu=MU)  # fmt: skip
    i, j = np.nonzero(~np.eye(n, dtype=bool))
    legs = LegCosts.build(orbits.take(i), orbits.take(j), R + 400e3, R + 1200e3, mu=MU,
                          model=LowThrustModel(1e-4))  # fmt: skip
    return orbits, i, j, legs


def scan(orbits, i, j, t, rule, laps=3, points=40001):
    """Arrival dates and costs of every drift radius of a dense grid leaving at t [days],
    flown with the formulas of this file (coast closed by J2, then whole laps)."""
    f = 1e-4
    a_d = np.linspace(R + 400e3, R + 1200e3, points)
    out = []
    for inc_d in (orbits.inc[i], orbits.inc[j]):
        dv = (np.abs(speed(orbits.a[i]) - speed(a_d)) + np.abs(speed(a_d) - speed(orbits.a[j]))
              + 0.5 * np.pi * speed(a_d) * abs(orbits.inc[j] - orbits.inc[i]))  # fmt: skip
        thrust = dv / f
        turned = 0.0
        for a_from, a_to, inc in ((orbits.a[i], a_d, orbits.inc[i]),
                                  (a_d, orbits.a[j], orbits.inc[j])):  # fmt: skip
            turned = turned - 3 * J2 * R**2 * np.cos(inc) / (16 * MU**3 * f) * np.abs(
                speed(a_to) ** 8 - speed(a_from) ** 8)  # fmt: skip
        d_inc = orbits.inc[j] - orbits.inc[i]
        mean_cos = (np.sin(orbits.inc[j]) - np.sin(orbits.inc[i])) / d_inc if d_inc else 1.0
        turned = turned + j2_rate(a_d, 0.0) * (0.5 * np.pi * speed(a_d) * abs(d_inc) / f) * mean_cos
        rel = j2_rate(a_d, inc_d) - orbits.rate[j]
        gap = (orbits.raan[j] + orbits.rate[j] * (t * DAY + thrust)
               - orbits.raan[i] - orbits.rate[i] * t * DAY - turned)  # fmt: skip
        coast = np.mod(np.where(rel > 0, gap, -gap), 2 * np.pi) / np.abs(rel)
        big, small = max(orbits.inc[i], orbits.inc[j]), min(orbits.inc[i], orbits.inc[j])
        allowed = np.ones_like(a_d, dtype=bool) if rule == "free" or big == small else (
            (inc_d == big) & (rel >= 0) | (inc_d == small) & (rel <= 0))  # fmt: skip
        for k in range(laps):
            arrive = t + (thrust + coast + k * 2 * np.pi / np.abs(rel)) / DAY
            out.append((arrive[allowed], dv[allowed]))
    return np.concatenate([o[0] for o in out]), np.concatenate([o[1] for o in out])


@pytest.mark.parametrize("rule", ["table3", "free"])
def test_exact_cost_and_box_bound_against_a_dense_scan(table, rule):
    orbits, i, j, legs = table
    rng = np.random.default_rng(11)
    checked = 0
    for e in rng.permutation(len(i)):
        t = rng.uniform(0, 120)
        arrive, dv = scan(orbits, i[e], j[e], t, rule)
        within = arrive[(arrive > t) & (arrive < t + 300)]
        if checked >= 24 or len(within) < 3:
            continue
        for target in rng.choice(within, 3, replace=False):
            exact = legs.cost_at(e, t, target, rule=rule, j2=J2)
            near = np.abs(arrive - target) < 0.005
            # the exact cheapest leg between the two dates is never dearer than a scanned
            # leg arriving on that date (to the scan's date resolution), and no cheaper than
            # the bound of a small box around it
            assert exact.cost <= dv[np.abs(arrive - target) < 1e-9].min() + 1e-6
            box = legs.box_bound(e, t, t, target - 0.005, target + 0.005, rule=rule, j2=J2)
            assert box <= dv[near].min() + 1e-9
            assert box <= exact.cost + 1e-9
            assert exact.cost - box < 0.05 * (exact.cost - legs.floor(e)) + 1.0
            checked += 1
    assert checked == 24


def test_box_bounds_are_never_above_a_leg_of_the_box_and_tighten_as_it_shrinks(table):
    orbits, i, j, legs = table
    rng = np.random.default_rng(5)
    for e in rng.choice(len(i), 6, replace=False):
        t1 = rng.uniform(0, 100)
        arrive, dv = scan(orbits, i[e], j[e], t1, "table3", points=20001)
        ok = (arrive > t1 + 20) & (arrive < t1 + 250)
        if not ok.any():
            continue
        k = np.flatnonzero(ok)[np.argmin(dv[ok])]
        previous, box = -np.inf, (-np.inf, np.inf)
        for width in (40.0, 10.0, 2.0, 0.2, 0.01):
            # around the cheapest leg, inside the last box
            t3 = np.clip(arrive[k] - width * rng.uniform(0.1, 0.9), box[0], box[1] - width)
            box = (t3, t3 + width)
            bound = legs.box_bound(e, t1, t1, t3, t3 + width, rule="table3", j2=J2)
            # the search may start from the bound of the box that holds this one
            warm = legs.box_bound(e, t1, t1, t3, t3 + width, rule="table3", j2=J2,
                                  floor=previous)  # fmt: skip
            inside = (arrive >= t3) & (arrive <= t3 + width)
            assert max(bound, warm) <= dv[inside].min() + 1e-9
            assert bound >= previous - 1e-6  # a box inside the last one: no looser
            assert warm >= previous
            previous = bound
        assert dv[k] - previous < 0.05


def test_spirals_longer_than_the_box_prove_no_leg(table):
    """At low acceleration the thrust alone outlasts a short box: the bound is inf."""
    orbits, i, j, _ = table
    slow = LegCosts.build(orbits.take(i), orbits.take(j), R + 400e3, R + 1200e3, mu=MU,
                          model=LowThrustModel(1e-6))  # fmt: skip
    e = int(np.argmax(np.abs(orbits.a[i] - orbits.a[j])))
    shortest_days = (legs_floor := slow.floor(e)) / 1e-6 / DAY
    assert legs_floor > 0
    assert np.isinf(slow.box_bound(e, 0.0, 0.0, 0.0, 0.9 * shortest_days, rule="free", j2=J2))
    assert np.isinf(slow.cost_at(e, 0.0, 0.9 * shortest_days, rule="free", j2=J2).cost)


@pytest.mark.parametrize("rule", ["table3", "free"])
def test_boxes_of_departures_and_arrivals_are_never_above_a_leg_inside(table, rule):
    """Boxes wide in both dates, including ones whose shortest legs the thrust time cuts
    (arrivals starting before the last departure): the bound is below every scanned leg
    of any departure of the box that arrives in it."""
    orbits, i, j, legs = table
    rng = np.random.default_rng(23)
    checked = 0
    for e in rng.permutation(len(i))[:10]:
        t1 = rng.uniform(0, 100)
        for width in (0.5, 5.0, 40.0):
            departures = np.linspace(t1, t1 + width, 21)
            scans = [scan(orbits, i[e], j[e], t, rule, laps=2, points=4001) for t in departures]
            first = min(arrive.min() for arrive, _ in scans)
            for t3 in (first - 1.0, first + 0.3 * width, t1 + 0.5 * width + 30.0):
                t4 = t3 + rng.choice([1.0, 20.0, 120.0])
                inside = [dv[(arrive >= t3) & (arrive <= t4) & (arrive >= t)]
                          for t, (arrive, dv) in zip(departures, scans, strict=True)]
                cheapest = min((d.min() for d in inside if len(d)), default=np.inf)
                bound = legs.box_bound(e, t1, t1 + width, t3, t4, rule=rule, j2=J2)
                assert bound <= cheapest + 1e-9
                checked += np.isfinite(cheapest)
    assert checked >= 40


def test_the_linear_part_range_is_the_exact_range_over_the_dates():
    """``rel D - g t`` over rates and the polygon of dates cut by D >= d_min: every sampled
    point inside the range returned, and its ends reached to the sampling's resolution."""
    rng = np.random.default_rng(3)
    for _ in range(300):
        t1 = rng.uniform(0, 10)
        t2 = t1 + rng.choice([0.0, rng.uniform(0, 10)])
        t3 = t1 + rng.uniform(-5, 15)
        t4 = t3 + rng.choice([0.0, rng.uniform(0, 10)])
        d_min = rng.uniform(0, 8)
        r_lo, r_hi = np.sort(rng.normal(0, 1e-3, 2))
        g = rng.normal(0, 1e-3)
        t, arrive, rel = np.meshgrid(np.linspace(t1, t2, 201), np.linspace(t3, t4, 201),
                                     [r_lo, r_hi])  # fmt: skip
        d = arrive - t
        ok = d >= d_min
        lo, hi = _linear_range(r_lo, r_hi, g, t1, t2, t3, t4, d_min)
        if not ok.any():
            assert lo == np.inf and hi == -np.inf or t2 + d_min > t4 - 0.1  # empty (or nearly)
            continue
        values = (rel * d - g * t)[ok]
        scale = (abs(r_lo) + abs(r_hi) + abs(g)) * 25 / 200
        assert lo <= values.min() + 1e-15 and hi >= values.max() - 1e-15
        assert values.min() - lo <= scale and hi - values.max() <= scale


@pytest.mark.parametrize("rule", ["table3", "free"])
def test_a_box_shrunk_to_a_point_is_bounded_within_the_stated_tolerance(table, rule):
    """The certified search's resolution rests on it: the bound of a point box (one
    departure, one arrival) is at most BOUND_TOL_MPS under the exact cost there, never
    above it, and inf exactly where no leg flies."""
    _, i, _, legs = table
    rng = np.random.default_rng(17)
    e = rng.integers(0, len(i), 3000)
    t = rng.uniform(0, 300, 3000)
    arrive = t + rng.uniform(0, 200, 3000)
    exact = legs.cost_at(e, t, arrive, rule=rule, j2=J2).cost
    bound = legs.box_bound(e, t, t, arrive, arrive, rule=rule, j2=J2)
    flies = np.isfinite(exact)
    assert flies.sum() > 200
    assert (np.isinf(bound) == ~flies).all()
    assert (bound[flies] <= exact[flies] + 1e-9).all()
    assert (exact[flies] - bound[flies]).max() <= BOUND_TOL_MPS


def test_the_mean_value_enclosure_holds_phi_over_the_step_and_the_box(table):
    """phi at sampled speeds of a step away from the cheap end, departures and arrivals
    of the box, with D at least the thrust time at that speed and T_min, lies inside the
    enclosure: its range at the step's start plus the step times its slope's range."""
    _, i, _, legs = table
    rng = np.random.default_rng(29)
    f = 1e-4
    pieces = edge_table(legs, np.arange(len(i)), f, "free", J2)
    checked = 0
    for _ in range(400):
        e, piece = int(rng.integers(len(i))), int(rng.integers(pieces.lo.shape[0]))
        p = pieces.rows(np.array([piece]), np.array([e]))
        if not p.hi[0] > p.lo[0]:
            continue
        up = p.c1[0] >= 0
        cheap = p.lo if up else p.hi
        pos = cheap + (1 if up else -1) * rng.uniform(0, 0.5) * (p.hi - p.lo)
        nxt = pos + (1 if up else -1) * rng.choice([1e-3, 0.1, 10.0]) * rng.uniform(0, 1)
        nxt = np.clip(nxt, p.lo, p.hi)
        t1 = rng.uniform(0, 200)
        t3 = t1 + rng.uniform(0, 150)
        dates = tuple(np.array([v]) for v in (t1, t1 + rng.uniform(0, 5), t3,
                                              t3 + rng.uniform(0, 5)))  # fmt: skip
        t_min = rng.choice([0.0, 20.0])
        lo, hi = _mean_value(p, _at_speed(p, dates, pos, t_min), pos, nxt)
        w = np.linspace(pos[0], nxt[0], 41)[:, None, None]
        t = np.linspace(dates[0][0], dates[1][0], 21)[None, :, None]
        arrive = np.linspace(dates[2][0], dates[3][0], 21)[None, None, :]
        d = arrive - t
        flies = (d >= np.maximum(t_min, p.thrust_days(w))) & (d >= 0)
        if not flies.any():
            continue
        phi = p.phi(w, t, d)[flies]
        scale = 1e-9 * (1.0 + np.abs(phi).max())
        assert lo[0] <= phi.min() + scale and phi.max() - scale <= hi[0]
        checked += 1
    assert checked > 150


def test_the_pre_optimisation_bound_t0_bounds_the_coast_and_thrust_comes_on_top(table):
    """Part IV-B's pre-optimised leg with low thrust: the cheapest whose *coast* lasts at
    most T0 (the paper's two months of drift), against the dense scan of this file."""
    orbits, i, j, _ = table
    t0_days, f = 30.0, 1e-4
    choice = LowThrustModel(f).cheapest_transfer(orbits.take(i), orbits.take(j), 0.0,
                                                 t0_days * DAY, R + 400e3, R + 1200e3,
                                                 j2=J2, mu=MU)  # fmt: skip
    longer = 0
    for e in range(len(i)):
        arrive, dv = scan(orbits, i[e], j[e], 0.0, "table3", laps=1)
        coast = arrive - dv / f / DAY
        fits = coast <= t0_days
        if not fits.any():
            assert not np.isfinite(choice.dv[e])
            continue
        # as cheap as the scan's cheapest within T0 of coast (to the pre-optimisation's grid)
        assert choice.dv[e] == pytest.approx(dv[fits].min(), abs=0.5)
        assert choice.duration[e] / DAY - choice.dv[e] / f / DAY <= t0_days + 1e-6
        longer += choice.duration[e] / DAY > t0_days
    assert longer > 0  # the spirals and plane change on top of T0
