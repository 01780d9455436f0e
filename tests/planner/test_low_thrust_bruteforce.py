"""Self-tests of the independent low-thrust brute force (``low_thrust_bruteforce.py``).

The physics is checked against numerical integration of the averaged equations (not
against the closed forms it uses), the search against a plain finer grid written here
and against random plans.  Nothing from ``sdc_cvx`` is imported.
"""

from __future__ import annotations

import itertools

import numpy as np
import pytest
from scipy.integrate import solve_ivp

from tests.planner import low_thrust_bruteforce as lt

DEG = np.pi / 180.0
KM = 1e3
SLOPE = 1.2e-3
"""Bound of a leg's cost change per metre of drift radius in the band [m/s/m]."""


def j2_rate(a, inc):
    """J2 RAAN rate [rad/s] of a circular orbit, written again for the integrations."""
    return -1.5 * lt.J2 * lt.R_EARTH**2 * np.sqrt(lt.MU) * a**-3.5 * np.cos(inc)


# ---------------------------------------------------------------------------------------
# Physics against numerical integration
# ---------------------------------------------------------------------------------------


def integrate_spiral(a0, a1, inc, accel):
    """Tangential spiral a0 -> a1 integrated: da/dt = +-2 f a^1.5 / sqrt(mu) (Gauss'
    equation for a circular orbit, da/dt = 2 a^2 V f / mu).  Returns (time [s], RAAN
    change [rad])."""
    sign = 1.0 if a1 > a0 else -1.0

    def rhs(_, y):
        return [sign * 2.0 * accel * y[0] ** 1.5 / np.sqrt(lt.MU), j2_rate(y[0], inc)]

    def reached(_, y):
        return y[0] - a1

    reached.terminal = True
    sol = solve_ivp(rhs, (0.0, 1e9), [a0, 0.0], events=reached, rtol=1e-12, atol=[1e-6, 1e-14],
                    method="DOP853")  # fmt: skip
    return sol.t_events[0][0], sol.y_events[0][0][1]


def test_spiral_raan_against_quadrature():
    a0, a1, inc, f = lt.R_EARTH + 800 * KM, lt.R_EARTH + 700 * KM, 98.6 * DEG, 1e-4
    dv = lt.leg_dv(a0, inc, a1, inc, a1)
    draan = lt.spiral_raan(a0, a1, inc, f)
    assert dv == pytest.approx(52.455, abs=5e-4)
    assert dv / f / lt.DAY == pytest.approx(6.071, abs=5e-4)
    assert abs(draan) / DEG == pytest.approx(6.13139, abs=1e-5)  # 6.131397
    duration, integrated = integrate_spiral(a0, a1, inc, f)
    assert duration == pytest.approx(dv / f, rel=1e-9)
    assert integrated == pytest.approx(draan, rel=1e-9)
    # the other way round, and another inclination: the same magnitude law
    duration, integrated = integrate_spiral(a1, a0, 82.0 * DEG, 3e-4)
    assert integrated == pytest.approx(lt.spiral_raan(a1, a0, 82.0 * DEG, 3e-4), rel=1e-9)


def test_plane_change_raan_against_quadrature():
    a, f = lt.R_EARTH + 650 * KM, 2e-4
    for i0, i1 in [(97.0 * DEG, 99.5 * DEG), (99.5 * DEG, 97.0 * DEG), (80.0 * DEG, 83.0 * DEG)]:
        rate_i = np.sign(i1 - i0) * (2.0 / np.pi) * f / lt.speed(a)  # averaged di/dt
        t_b = (i1 - i0) / rate_i
        sol = solve_ivp(lambda t, y, r=rate_i, i=i0: [j2_rate(a, i + r * t)], (0.0, t_b), [0.0],
                        rtol=1e-12, atol=1e-14)  # fmt: skip
        dv = lt.leg_dv(a, i0, a, i1, a)
        assert dv / f == pytest.approx(t_b, rel=1e-12)
        assert lt.plane_change_raan(a, i0, i1, f) == pytest.approx(sol.y[0, -1], rel=1e-9)
    assert lt.plane_change_raan(a, 98.0 * DEG, 98.0 * DEG, f) == 0.0


def fly_leg(a, e, inc, raan, i, j, a_d, inc_d, depart, accel, coast):
    """The leg integrated phase by phase (spirals, plane change at di/dt = (2/pi) f / V,
    coast), the plane change after the coast when the drift inclination is the
    origin's.  Returns (arrival date [s], vehicle RAAN at arrival [rad], phase times)."""
    state = {"t": depart, "a": a[i], "i": inc[i],
             "raan": raan[i] + lt.raan_rate(a[i], inc[i], e[i]) * depart}  # fmt: skip
    times = []

    def run(rhs, event=None, span=None):
        y0 = [state["a"], state["i"], state["raan"]]
        if event is not None:
            event.terminal = True
        end = state["t"] + (span if span is not None else 1e10)
        sol = solve_ivp(rhs, (state["t"], end), y0, events=event, rtol=1e-12,
                        atol=[1e-6, 1e-14, 1e-13], method="DOP853")  # fmt: skip
        if event is not None and sol.t_events[0].size:
            t, y = sol.t_events[0][0], sol.y_events[0][0]
        else:
            t, y = sol.t[-1], sol.y[:, -1]
        times.append(t - state["t"])
        state.update(t=t, a=y[0], i=y[1], raan=y[2])

    def spiral(target):
        sign = 1.0 if target > state["a"] else -1.0
        if target == state["a"]:
            times.append(0.0)
            return
        run(lambda t, y: [sign * 2 * accel * y[0] ** 1.5 / np.sqrt(lt.MU), 0.0,
                          j2_rate(y[0], y[1])],  # fmt: skip
            lambda t, y: y[0] - target)

    def plane(target):
        if target == state["i"]:
            times.append(0.0)
            return
        sign = 1.0 if target > state["i"] else -1.0
        run(lambda t, y: [0.0, sign * (2 / np.pi) * accel / lt.speed(y[0]), j2_rate(y[0], y[1])],
            lambda t, y: y[1] - target)

    def drift():
        if coast == 0.0:
            times.append(0.0)
            return
        run(lambda t, y: [0.0, 0.0, j2_rate(y[0], y[1])], span=coast)

    spiral(a_d)
    if inc_d == inc[j]:
        plane(inc[j])
        drift()
    else:
        drift()
        plane(inc[j])
    spiral(a[j])
    return state["t"], state["raan"], times


@pytest.mark.parametrize("laps", [0, 1])
def test_leg_closes_the_raan_against_integration(laps):
    a = lt.R_EARTH + np.array([800.0, 700.0]) * KM
    e = np.array([0.001, 0.003])
    inc = np.array([98.6, 99.4]) * DEG
    raan = np.array([10.0, 35.0]) * DEG
    f, depart = 3e-4, 12.5 * lt.DAY
    rate_j = lt.raan_rate(a[1], inc[1], e[1])
    for a_d, inc_d in itertools.product(lt.R_EARTH + np.array([450.0, 760.0, 700.0, 1150.0]) * KM,
                                        inc):  # fmt: skip
        arrive, dv = lt.leg(a[0], e[0], inc[0], raan[0], a[1], e[1], inc[1], raan[1], a_d, inc_d,
                            depart, f, laps)  # fmt: skip
        thrust = lt.leg_thrust_time(a[0], inc[0], a[1], inc[1], a_d, f)
        coast = arrive - depart - thrust
        assert coast >= 0.0
        flown, vehicle_raan, times = fly_leg(a, e, inc, raan, 0, 1, a_d, inc_d, depart, f, coast)
        assert flown == pytest.approx(arrive, abs=1e-3)  # the phases' times match the closed forms
        target = raan[1] + rate_j * flown
        miss = np.angle(np.exp(1j * (vehicle_raan - target)))
        assert abs(miss) < 1e-6, (a_d, inc_d, miss)
        if laps:
            assert coast >= lt.TWO_PI / abs(lt.raan_rate(a_d, inc_d) - rate_j)


def test_coast_time_rules():
    # the smallest coast closes, laps add whole relative laps, equal rates need a closed gap
    rel = 2e-7
    assert lt.coast_time(0.3, 1e-7 + rel, 1e-7, 0.0, 0.0) == pytest.approx(0.3 / rel)
    assert lt.coast_time(0.3, 1e-7 - rel, 1e-7, 0.0, 0.0) == pytest.approx((lt.TWO_PI - 0.3) / rel)
    assert lt.coast_time(0.3, 1e-7 + rel, 1e-7, 0.0, 0.0, 2) == pytest.approx(
        (0.3 + 2 * lt.TWO_PI) / rel
    )
    assert lt.coast_time(0.3, 1e-7, 1e-7, 0.0, 0.0) == np.inf
    assert lt.coast_time(lt.TWO_PI, 1e-7, 1e-7, 0.0, 0.0) == 0.0
    # thrust phases: the target moves on while thrusting, the vehicle's RAAN too
    assert lt.coast_time(0.0, 3e-7, 1e-7, 1e5, 0.01) == pytest.approx((1e-7 * 1e5 - 0.01) / 2e-7)


def test_table3_rule():
    lo, hi = 97.0 * DEG, 99.0 * DEG
    a = lt.R_EARTH + np.linspace(400, 1200, 81) * KM
    for inc_i, inc_j in [(lo, hi), (hi, lo)]:
        rate_target = lt.raan_rate(lt.R_EARTH + 800 * KM, inc_j, 0.002)
        upper = lt.drift_allowed(inc_i, inc_j, a, hi, rate_target, "table3")
        lower = lt.drift_allowed(inc_i, inc_j, a, lo, rate_target, "table3")
        assert np.array_equal(upper, lt.raan_rate(a, hi) >= rate_target)
        assert np.array_equal(lower, lt.raan_rate(a, lo) <= rate_target)
        assert upper.any() and lower.any()
        assert lt.drift_allowed(inc_i, inc_j, a, hi, rate_target, "free").all()
    rate_j = lt.raan_rate(lt.R_EARTH + 800 * KM, hi)
    assert lt.drift_allowed(hi, hi, a, hi, rate_j, "table3").all()
    assert not lt.drift_allowed(lo, hi, a, 98.0 * DEG, rate_j, "free").any()


# ---------------------------------------------------------------------------------------
# The search's pieces
# ---------------------------------------------------------------------------------------


def problem(cat, **kw):
    args = dict(n=3, tmax_days=366.0, accel_mps2=1e-4, rule="free", a_low=lt.A_LOW,
                a_high=lt.A_HIGH, deorbit_days=0.0, radii=2049, coarse_every=32,
                zoom_points=41, zoom_levels=3, margin=2e-3)  # fmt: skip
    args.update(kw)
    return lt._Problem(cat.a_m, cat.e, cat.inc_rad, cat.raan_rad, **args)


@pytest.mark.parametrize("rule", lt.RULES)
def test_last_leg_step_function_equals_direct_minimum(rule):
    cat = lt.random_catalog(3, 6, kind="sso")
    prob = problem(cat, rule=rule, deorbit_days=2.0)
    rng = np.random.default_rng(0)
    for pair in [(0, 1), (2, 5), (4, 3)]:
        last = prob.last(pair)
        dates = rng.uniform(prob.dd, prob.deadline, 300)
        cost, idx = last.lookup(dates)
        exact = np.array([last.exact(t)[0] for t in dates])
        assert np.array_equal(np.isfinite(cost), np.isfinite(exact))
        assert np.allclose(cost[np.isfinite(cost)], exact[np.isfinite(exact)], rtol=0, atol=1e-9)
        fits = idx >= 0
        arrive = last.cells.arrival(dates[fits], idx[fits])
        assert (arrive <= prob.deadline + lt.TOL_S).all()


def test_duration_curves_bound_grid_legs():
    cat = lt.random_catalog(1, 6, kind="mixed")
    prob = problem(cat, deorbit_days=1.0)
    rng = np.random.default_rng(1)
    for pair in itertools.permutations(range(6), 2):
        cells = prob.fine(pair)
        k = rng.integers(0, cells.size, 200)
        t = rng.uniform(prob.dd, prob.deadline, 200)
        duration = cells.arrival(t, k) - t
        curve = prob.curve(pair)
        bound = prob.bound_at(curve, duration)
        ok = np.isfinite(duration) & (duration <= prob.budget)
        assert (bound[ok] <= cells.dv[k][ok] + 1e-9).all()


# ---------------------------------------------------------------------------------------
# The optimum
# ---------------------------------------------------------------------------------------


def check_plan(plan, cat, *, n, tmax_days, accel_mps2, rule, deorbit_days=0.0):
    again = lt.replay(cat.a_m, cat.e, cat.inc_rad, cat.raan_rad, plan.path, plan.a_drift_m,
                      plan.inc_drift_rad, plan.laps, accel_mps2=accel_mps2, rule=rule,
                      deorbit_days=deorbit_days)  # fmt: skip
    assert len(plan.path) == len(set(plan.path)) == n
    assert again.cost_mps == pytest.approx(plan.cost_mps, rel=1e-12)
    assert again.end_day <= tmax_days + lt.TOL_S / lt.DAY
    assert plan.depart_day[0] == deorbit_days
    for k in range(n - 2):
        assert plan.depart_day[k + 1] == pytest.approx(plan.arrive_day[k] + deorbit_days)
    assert plan.end_day == pytest.approx(plan.arrive_day[-1] + deorbit_days)


def random_plans(cat, plan, rule, rng, count, accel, tmax_days):
    """Feasible plans drawn at random: any path with random radii and inclinations, and the
    optimum's path with its radii jittered (+/- 5 km) and inclinations redrawn."""
    N, n = cat.a_m.size, len(plan.path)
    rates = lt.raan_rate(cat.a_m, cat.inc_rad, cat.e)
    costs = []
    for draw in range(count):
        if draw % 2:
            path = tuple(int(x) for x in rng.permutation(N)[:n])
            radii = rng.uniform(lt.A_LOW, lt.A_HIGH, n - 1)
            laps = rng.integers(0, 2, n - 1) * (rng.random(n - 1) < 0.2)
        else:
            path = plan.path
            radii = np.clip(np.array(plan.a_drift_m) + rng.uniform(-5e3, 5e3, n - 1), lt.A_LOW,
                            lt.A_HIGH)  # fmt: skip
            laps = np.zeros(n - 1, dtype=int)
        incs = []
        for (i, j), a_d in zip(itertools.pairwise(path), radii, strict=True):
            pair = (cat.inc_rad[i], cat.inc_rad[j])
            options = [x for x in set(pair) if lt.drift_allowed(*pair, a_d, x, rates[j], rule)]
            incs.append(options[rng.integers(len(options))])
        flown = lt.replay(cat.a_m, cat.e, cat.inc_rad, cat.raan_rad, path, radii, incs, laps,
                          accel_mps2=accel, rule=rule)  # fmt: skip
        if flown.end_day <= tmax_days:
            costs.append(flown.cost_mps)
    return np.array(costs)


@pytest.mark.slow
@pytest.mark.parametrize("rule", lt.RULES)
def test_optimum_is_never_above_random_feasible_plans(rule):
    cat = lt.random_catalog(5, 8, kind="sso")
    kw = dict(n=4, tmax_days=366.0, accel_mps2=1e-4, rule=rule)
    plan = lt.optimum(cat.a_m, cat.e, cat.inc_rad, cat.raan_rad, **kw)
    check_plan(plan, cat, **kw)
    costs = random_plans(cat, plan, rule, np.random.default_rng(7), 4000, 1e-4, 366.0)
    assert costs.size >= 100  # enough of them fly for the test to mean something
    assert costs.min() >= plan.cost_mps - 1e-9, (costs.min(), plan.cost_mps)


def reference(cat, *, n, tmax_days, accel, rule, radii, a_low=lt.A_LOW, a_high=lt.A_HIGH,
              max_laps=3, ceiling=np.inf):  # fmt: skip
    """A plain grid search for n <= 3 (independent of the brute force's machinery): every
    path, the first leg on ``radii`` radii x inclinations x laps, the last leg on the same
    grid by direct evaluation at every arrival date (smallest coast: extra laps cannot help
    the last leg).  Only plans under ``ceiling`` [m/s] are looked for."""
    a, e, inc, raan = cat.a_m, cat.e, cat.inc_rad, cat.raan_rad
    tmax = tmax_days * lt.DAY
    rates = lt.raan_rate(a, inc, e)
    grid = np.linspace(a_low, a_high, radii)

    def orbits(i, j):
        r = np.unique(np.concatenate([grid, [x for x in (a[i], a[j]) if a_low <= x <= a_high]]))
        radius, incl = np.tile(r, 2), np.repeat([inc[i], inc[j]], r.size)
        ok = lt.drift_allowed(inc[i], inc[j], radius, incl, rates[j], rule)
        return radius[ok], incl[ok]

    def fly(i, j, a_d, i_d, t, laps=0):
        return lt.leg(a[i], e[i], inc[i], raan[i], a[j], e[j], inc[j], raan[j], a_d, i_d, t,
                      accel, laps)  # fmt: skip

    best, where = ceiling, None
    for path in itertools.permutations(range(a.size), n):
        if n == 2:
            a_d, i_d = orbits(*path)
            arrive, dv = fly(*path, a_d, i_d, 0.0)
            dv = np.where(arrive <= tmax, dv, np.inf)
            k = int(np.argmin(dv))
            if dv[k] < best:
                best, where = float(dv[k]), (path, (a_d[k],), (i_d[k],), (0,))
            continue
        (i, j), (_, k) = itertools.pairwise(path)
        a1, i1 = orbits(i, j)
        states = []
        for q in range(max_laps + 1):
            arrive, dv = fly(i, j, a1, i1, 0.0, q)
            ok = arrive <= tmax
            states.append((arrive[ok], dv[ok], a1[ok], i1[ok], np.full(int(ok.sum()), q)))
        t1, c1, sa, si, sq = (np.concatenate(x) for x in zip(*states, strict=True))
        a2, i2 = orbits(j, k)
        dv2 = lt.leg_dv(a[j], inc[j], a[k], inc[k], a2)
        order = np.argsort(dv2)
        a2, i2, dv2 = a2[order], i2[order], dv2[order]
        for s in np.argsort(c1):
            m = int(np.searchsorted(dv2, best - c1[s]))
            if m == 0:
                if c1[s] + dv2[0] >= best:
                    break
                continue
            arrive, _ = fly(j, k, a2[:m], i2[:m], t1[s])
            fits = np.flatnonzero(arrive <= tmax)
            if fits.size and c1[s] + dv2[fits[0]] < best:
                best = float(c1[s] + dv2[fits[0]])
                where = (path, (sa[s], a2[fits[0]]), (si[s], i2[fits[0]]), (int(sq[s]), 0))
    return best, where


@pytest.mark.slow
@pytest.mark.parametrize("rule", lt.RULES)
def test_tiny_case_equals_a_much_finer_plain_grid(rule):
    cat = lt.random_catalog(7, 4, kind="sso")
    kw = dict(n=3, tmax_days=366.0, accel_mps2=1e-4, rule=rule)
    coarse = lt.optimum(cat.a_m, cat.e, cat.inc_rad, cat.raan_rad, radii=257, **kw)
    plan = lt.optimum(cat.a_m, cat.e, cat.inc_rad, cat.raan_rad, **kw)
    check_plan(plan, cat, **kw)
    best, where = reference(cat, n=3, tmax_days=366.0, accel=1e-4, rule=rule, radii=8193,
                            ceiling=plan.cost_mps * 1.002)  # fmt: skip
    assert where is not None
    # the finer grid finds nothing cheaper, and the refined optimum is not above it
    assert abs(plan.cost_mps - best) <= 1e-4 * best, (plan.cost_mps, best, where)
    assert plan.cost_mps <= best + 1e-9
    assert abs(coarse.cost_mps - plan.cost_mps) <= 1e-4 * plan.cost_mps


@pytest.mark.slow
def test_laps_case_equals_a_finer_plain_grid():
    """A narrow drift band (no slower orbit to wait on): the optimum waits a relative lap."""
    a = lt.R_EARTH + np.array([800.0, 1150.0, 700.0]) * KM
    cat = lt.SyntheticCatalog(a, np.zeros(3), np.full(3, 40.0 * DEG),
                              np.radians([204.1, 155.1, 33.9]), ("A", "B", "C"))  # fmt: skip
    band = dict(a_low=lt.R_EARTH + 690 * KM, a_high=lt.R_EARTH + 710 * KM)
    kw = dict(n=3, tmax_days=718.0, accel_mps2=1e-3, rule="free")
    plan = lt.optimum(cat.a_m, cat.e, cat.inc_rad, cat.raan_rad, radii=257, **kw, **band)
    check_plan(plan, cat, **kw)
    assert any(plan.laps)
    best, where = reference(cat, n=3, tmax_days=718.0, accel=1e-3, rule="free", radii=2001,
                            ceiling=plan.cost_mps * 1.01, **band)  # fmt: skip
    # a 10 m plain grid: at most two legs' step cost above the refined optimum
    assert plan.cost_mps <= best + 1e-9
    assert best - plan.cost_mps <= 2 * SLOPE * 10.0, (plan, best, where)
    assert any(where[3])


def test_single_leg_equals_plain_grid():
    cat = lt.random_catalog(2, 5, kind="cluster")
    for rule in lt.RULES:
        kw = dict(n=2, tmax_days=200.0, accel_mps2=1e-4, rule=rule)
        plan = lt.optimum(cat.a_m, cat.e, cat.inc_rad, cat.raan_rad, radii=513, **kw)
        check_plan(plan, cat, **kw)
        best, _ = reference(cat, n=2, tmax_days=200.0, accel=1e-4, rule=rule, radii=20001)
        # the plain grid is at most a step's cost (slope x 40 m) above the refined optimum
        assert plan.cost_mps <= best + 1e-9
        assert best - plan.cost_mps <= SLOPE * (lt.A_HIGH - lt.A_LOW) / 20000


def test_operations_time_and_infeasible():
    cat = lt.random_catalog(3, 6, kind="mixed")
    kw = dict(n=3, tmax_days=366.0, accel_mps2=1e-4, rule="table3", deorbit_days=15.0)
    plan = lt.optimum(cat.a_m, cat.e, cat.inc_rad, cat.raan_rad, **kw)
    check_plan(plan, cat, **kw)
    loose = lt.optimum(cat.a_m, cat.e, cat.inc_rad, cat.raan_rad,
                       **{**kw, "deorbit_days": 0.0})  # fmt: skip
    assert loose.cost_mps <= plan.cost_mps + 1e-9
    # the spirals and plane changes alone outlast a short T_max
    assert lt.optimum(cat.a_m, cat.e, cat.inc_rad, cat.raan_rad,
                      **{**kw, "tmax_days": 5.0}) is None  # fmt: skip


def test_random_catalog():
    for kind in ("sso", "cluster", "mixed"):
        cat = lt.random_catalog(11, 8, kind=kind)
        again = lt.random_catalog(11, 8, kind=kind)
        assert all(np.array_equal(x, y) for x, y in zip(cat[:4], again[:4], strict=True))
        alt = (cat.a_m - lt.R_EARTH) / KM
        assert ((alt >= 600) & (alt <= 1000)).all()
        assert ((cat.e >= 0) & (cat.e <= 0.005)).all()
        inc = np.degrees(cat.inc_rad)
        assert (((inc >= 97) & (inc <= 100)) | ((inc >= 70) & (inc <= 84))).all()
        assert len(set(cat.ids)) == 8
        rates = lt.raan_rate(cat.a_m, cat.inc_rad, cat.e)
        assert np.unique(rates).size == 8
    with pytest.raises(ValueError):
        lt.random_catalog(0, 4, kind="geo")
