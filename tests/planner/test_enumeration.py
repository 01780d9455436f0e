"""The solver against exhaustive enumeration on small hand-built catalogs.

The brute force below enumerates every ordered path of n debris and, for each, searches
the drift orbits of every leg on a radius grid with the true physics (Eq. 7-13 through
``sdc_cvx.physics.transfer``): no linearisation, no MILP, no re-optimisation, nothing from the
code under test (``sequential``, ``model``, ``linearize``, ``reoptimize``, ``edges``,
``solution``).  The model is the solver's: the vehicle is at the first debris at t = 0,
each leg leaves as soon as the previous one arrives (T_deorb = 0), each drift orbit is
circular with a radius in the altitude band and the inclination of one of the two debris,
and the mission ends (arrival at the last debris) by T_max.

Two optima are enumerated for every path:

* ``table3``: the drift inclination is Table 3's for the side of the asymptote the drift
  orbit is on (``drift_inclination(I_i, I_j, side)``), the solver's default rule;
* ``free``: either debris inclination on either side.

The solver starts from Table 3 and may resume a leg with the other inclination when it
is clearly cheaper (``flip_assumptions``), so its answer must lie between the two:
never worse than the Table-3 optimum, never below the free optimum (that would be
physics the brute force does not allow).  When every leg of its plan follows Table 3 it
must match the Table-3 optimum.

How the grid search stays exhaustive and fast.  The middle legs (all but the last) are
gridded and chained by broadcasting: every grid point of leg k departs at every arrival
date of leg k-1.  The last leg does not need the full matrix: its duration at departure
date t is ``W_s(t) / |rate_d - rate_j|`` where ``W_s(t)`` is the RAAN gap wrapped for
side s, which does not depend on the drift orbit.  "Duration <= budget" is then
"``|rate_d - rate_j| >= W_s(t) / budget``", and the cheapest grid point meeting it is a
prefix minimum over the grid sorted by relative rate, found by binary search for every
departure date at once.  This is the same minimum as the full (dates x radii) matrix
(checked on a coarse grid by ``test_brute_force_last_leg_equals_the_full_matrix``), with a
grid of 32 000 radii per inclination.  The best grid points of each (inclination, side)
branch of the middle legs are then refined by zooming (a grid of +/- 2 steps around
them, three times), so the grid error is far below the 0.5 m/s tolerance.
"""

from __future__ import annotations

import itertools
from dataclasses import dataclass
from functools import cached_property

import numpy as np
import pandas as pd
import pytest

from sdc_cvx import Catalog, Mission
from sdc_cvx.physics.orbits import R_EARTH, SECONDS_PER_DAY
from sdc_cvx.physics.transfer import NodeOrbits, drift_inclination, transfer_duration, transfer_dv

pytestmark = pytest.mark.slow  # solves many missions (see tests/conftest.py)

DAY = SECONDS_PER_DAY
A_LOW, A_HIGH = R_EARTH + 400e3, R_EARTH + 1200e3  # Mission's default drift altitude band
RULES = ("table3", "free")

# ---------------------------------------------------------------------------------------
# Brute force (independent of the code under test)
# ---------------------------------------------------------------------------------------


def orbits_of(catalog: Catalog) -> NodeOrbits:
    return NodeOrbits.from_elements(catalog.a_m, catalog.e, catalog.inc_rad, catalog.raan_rad)


def drift_rate(a, inc):
    """J2 RAAN rate [rad/s] of circular drift orbits (Eq. 7 with e = 0)."""
    return NodeOrbits.from_elements(a, 0.0, inc, 0.0).rate


class Candidates:
    """Drift orbits (radius ``a`` [m], inclination ``inc`` [rad]) for the leg i -> j.

    The inclination must be one of the two debris' (the Table-3 rule always picks one of
    them); ``table3`` marks those that are Table 3's for their side of the asymptote.
    Drift orbits exactly on the asymptote (infinite duration) are left out.
    """

    def __init__(self, orbits: NodeOrbits, i: int, j: int, a, inc):
        self.orbits, self.i, self.j = orbits, i, j
        self.origin, self.target = orbits.take(i), orbits.take(j)
        a, inc = np.broadcast_arrays(np.asarray(a, dtype=float), np.asarray(inc, dtype=float))
        rel = drift_rate(a, inc) - self.target.rate
        keep = rel != 0.0
        self.a, self.inc, self.rel = a[keep], inc[keep], rel[keep]
        self.side = np.sign(self.rel)
        table3_inc = drift_inclination(self.origin.inc, self.target.inc, self.side)
        self.table3 = self.inc == table3_inc
        o, t = self.origin, self.target
        self.dv = transfer_dv(o.a, o.inc, t.a, t.inc, self.a, self.inc)

    @classmethod
    def band(cls, orbits: NodeOrbits, i: int, j: int, count: int) -> Candidates:
        """``count`` radii across the band plus the two debris radii (kinks of the cost)."""
        kinks = orbits.a[[i, j]]
        kinks = kinks[(kinks >= A_LOW) & (kinks <= A_HIGH)]
        a = np.unique(np.concatenate([np.linspace(A_LOW, A_HIGH, count), kinks]))
        incs = np.unique(orbits.inc[[i, j]])
        return cls(orbits, i, j, a[None, :], incs[:, None])

    def subset(self, mask) -> Candidates:
        out = object.__new__(Candidates)
        out.__dict__.update(self.__dict__)
        for name in ("a", "inc", "rel", "side", "table3", "dv"):
            setattr(out, name, getattr(self, name)[mask])
        return out

    def rule(self, rule: str) -> Candidates:
        return self.subset(self.table3) if rule == "table3" else self

    def duration_days(self, depart_days):
        """Durations [days] of every candidate (last axis) for each departure date [days]."""
        t = np.asarray(depart_days, dtype=float)[..., None] * DAY
        return transfer_duration(self.origin, self.target, self.a, self.inc, t) / DAY


class LastLeg:
    """Cheapest candidate of the last leg whose duration fits a budget, for many dates at once."""

    def __init__(self, candidates: Candidates):
        self.c = candidates
        self.branches = []
        for side in (1.0, -1.0):
            members = np.flatnonzero(candidates.side == side)
            if members.size == 0:
                continue
            order = members[np.argsort(-np.abs(candidates.rel[members]), kind="stable")]
            dv = candidates.dv[order]
            prefix_min = np.minimum.accumulate(dv)
            arg = np.maximum.accumulate(np.where(dv <= prefix_min, np.arange(dv.size), 0))
            self.branches.append((order[0], -np.abs(candidates.rel[order]), prefix_min, order[arg]))

    def best(self, depart_days, budget_days):
        """Minimum cost [m/s] and candidate index (-1: none) with duration <= budget."""
        depart_days, budget = np.broadcast_arrays(
            np.asarray(depart_days, dtype=float), np.asarray(budget_days, dtype=float) * DAY
        )
        best = np.full(depart_days.shape, np.inf)
        which = np.full(depart_days.shape, -1)
        c = self.c
        for ref, neg_speed, prefix_min, arg in self.branches:
            # wrapped RAAN gap at departure for this side, from one member's duration
            duration = transfer_duration(
                c.origin, c.target, c.a[ref], c.inc[ref], depart_days * DAY
            )
            wrapped = duration * abs(c.rel[ref])
            with np.errstate(divide="ignore", invalid="ignore"):
                need = np.where(wrapped == 0.0, 0.0, wrapped / budget)
            need = np.where((budget < 0.0) | ((budget == 0.0) & (wrapped > 0.0)), np.inf, need)
            count = np.searchsorted(neg_speed, -need, side="right")
            k = np.maximum(count - 1, 0)
            value = np.where(count > 0, prefix_min[k], np.inf)
            better = value < best
            best = np.where(better, value, best)
            which = np.where(better, arg[k], which)
        return best, which


@dataclass(frozen=True)
class Plan:
    """Best plan found for one path: total cost, end date and each leg's drift orbit."""

    path: tuple[int, ...]
    dv: float
    end_day: float
    a_drift: tuple[float, ...] = ()
    inc_drift: tuple[float, ...] = ()
    leg_dv: tuple[float, ...] = ()


def chain(middle: list[Candidates], last: LastLeg, tmax):
    """Exhaustive minimum over the grids of the middle legs and the last leg.

    Returns the minimum cost, the index of each middle leg's candidate and of the last
    leg's, or ``(inf, None, None)`` when nothing meets T_max.
    """
    cost, arrival = np.zeros(1), np.zeros(1)
    index = np.zeros((1, 0), dtype=int)
    for leg in middle:
        duration = leg.duration_days(arrival)  # (frontier, candidates)
        cost = (cost[:, None] + leg.dv[None, :]).ravel()
        arrival = (arrival[:, None] + duration).ravel()
        picks = np.arange(leg.dv.size)
        index = np.concatenate(
            [np.repeat(index, leg.dv.size, axis=0), np.tile(picks, len(index))[:, None]], axis=1
        )
        alive = arrival <= tmax
        cost, arrival, index = cost[alive], arrival[alive], index[alive]
    if cost.size == 0:
        return np.inf, None, None
    last_dv, last_index = last.best(arrival, tmax - arrival)
    total = cost + last_dv
    k = int(np.argmin(total))
    if not np.isfinite(total[k]):
        return np.inf, None, None
    return float(total[k]), index[k], int(last_index[k])


def zoom(leg: Candidates, a: float, inc: float, half: float, count: int, rule: str):
    """Candidates of ``leg``'s pair with inclination ``inc``, radii within ``a`` +/- ``half``."""
    radii = np.linspace(max(A_LOW, a - half), min(A_HIGH, a + half), count)
    return Candidates(leg.orbits, leg.i, leg.j, radii, inc).rule(rule)


def search(legs: list[Candidates], last: LastLeg, tmax):
    """:func:`chain`, as (cost, [(a, inc) of every leg]) or (inf, None)."""
    dv, index, k_last = chain(legs, last, tmax)
    if index is None:
        return np.inf, None
    orbits = [(g.a[k], g.inc[k]) for g, k in zip(legs, index, strict=True)]
    return dv, orbits + [(last.c.a[k_last], last.c.inc[k_last])]


def path_optimum(grids, lasts, path, tmax, rule, *, step, zoom_count, zoom_levels=3) -> Plan:
    """Minimum total ΔV of ``path`` with arrival at its last debris by ``tmax`` days.

    ``grids`` and ``lasts`` hold the middle-leg candidates (radius grid ``step`` [m]) and
    the last-leg searches of every ordered pair.  The best grid point of every
    (inclination, side) branch of the middle legs is refined by zooming.
    """
    pairs = list(itertools.pairwise(path))
    middle = [grids[pair].rule(rule) for pair in pairs[:-1]]
    last = lasts[pairs[-1], rule]
    best_dv, best = np.inf, None
    branches = [sorted(set(zip(g.inc, g.side, strict=True))) for g in middle]
    for branch in itertools.product(*branches):
        legs = [
            g.subset((g.inc == inc) & (g.side == side))
            for g, (inc, side) in zip(middle, branch, strict=True)
        ]
        dv, drift = search(legs, last, tmax)
        half = 2.0 * step
        for _ in range(zoom_levels):
            if drift is None:
                break
            zoomed = [
                zoom(g, a, inc, half, zoom_count, rule)
                for g, (a, inc) in zip(legs, drift, strict=False)
            ]
            dv_zoom, drift_zoom = search(zoomed, last, tmax)
            if dv_zoom <= dv:
                dv, drift = dv_zoom, drift_zoom
            half = 2.0 * (2.0 * half) / (zoom_count - 1)
        if dv < best_dv:
            best_dv, best = dv, drift
    if best is None:
        return Plan(tuple(path), np.inf, np.inf)
    plan = replay(middle[0].orbits if middle else last.c.orbits, path, *zip(*best, strict=True))
    assert plan.dv == pytest.approx(best_dv, abs=1e-6)  # the search and the replay agree
    assert plan.end_day <= tmax + 1e-9
    return plan


def replay(orbits: NodeOrbits, path, a, inc) -> Plan:
    """Evaluate a plan leg by leg with the physics (what the brute force claims, recomputed)."""
    day, leg_dv = 0.0, []
    for (i, j), a_d, i_d in zip(itertools.pairwise(path), a, inc, strict=True):
        o, t = orbits.take(i), orbits.take(j)
        leg_dv.append(float(transfer_dv(o.a, o.inc, t.a, t.inc, a_d, i_d)))
        day += float(transfer_duration(o, t, a_d, i_d, day * DAY)) / DAY
    return Plan(tuple(path), sum(leg_dv), day, tuple(a), tuple(inc), tuple(leg_dv))


@dataclass
class Enumeration:
    """Optimum of every ordered path of n debris, for both inclination rules."""

    catalog: Catalog
    n: int
    tmax: float
    middle_count: int
    last_count: int = 32_000
    zoom_count: int = 401

    @cached_property
    def orbits(self):
        return orbits_of(self.catalog)

    @cached_property
    def plans(self) -> dict[str, list[Plan]]:
        """Per rule, the best plan of every path, cheapest first."""
        size = len(self.catalog)
        pairs = list(itertools.permutations(range(size), 2))
        grids = {p: Candidates.band(self.orbits, *p, self.middle_count) for p in pairs}
        fine = {p: Candidates.band(self.orbits, *p, self.last_count) for p in pairs}
        lasts = {(p, rule): LastLeg(fine[p].rule(rule)) for p in pairs for rule in RULES}
        step = (A_HIGH - A_LOW) / (self.middle_count - 1)
        out = {}
        for rule in RULES:
            plans = [
                path_optimum(
                    grids, lasts, path, self.tmax, rule, step=step, zoom_count=self.zoom_count
                )
                for path in itertools.permutations(range(size), self.n)
            ]
            out[rule] = sorted(plans, key=lambda plan: plan.dv)
        return out

    def ids(self, plan: Plan) -> tuple[str, ...]:
        return tuple(self.catalog.ids[k] for k in plan.path)


# ---------------------------------------------------------------------------------------
# Catalogs and cases
# ---------------------------------------------------------------------------------------


def catalog(rows) -> Catalog:
    """Circular (e = 1e-4) debris from (id, altitude km, inclination deg, RAAN deg) rows."""
    frame = pd.DataFrame(rows, columns=["id", "alt_km", "inc_deg", "raan_deg"])
    frame["a_km"] = R_EARTH / 1e3 + frame.pop("alt_km")
    frame["e"] = 1e-4
    return Catalog.from_frame(frame[["id", "a_km", "e", "inc_deg", "raan_deg"]])


# J2 rates from 0.90 to 1.07 deg/day (inclinations up to 0.8 deg off SSO): RAAN gaps move
# by degrees per month, so departure dates matter
SPREAD = [
    ("A", 650.0, 97.6, 10.0),
    ("B", 880.0, 99.3, 18.0),
    ("C", 750.0, 98.4, 4.0),
    ("D", 700.0, 98.9, 14.0),
    ("E", 820.0, 97.9, 22.0),
]

# Near sun-synchronous (inclinations within 0.03 deg of SSO): rates 0.985-0.989 deg/day, so
# the RAAN gaps are nearly frozen, as in the paper's Table 5
NEAR_SSO = [
    ("P", 610.0, 97.83, 40.0),
    ("Q", 690.0, 98.15, 52.0),
    ("R", 770.0, 98.47, 46.0),
    ("S", 845.0, 98.80, 35.0),
    ("T", 720.0, 98.30, 57.0),
]


@dataclass(frozen=True)
class Case:
    """A mission to enumerate: catalog rows, n, T_max, and whether T_max binds at the optimum."""

    name: str
    rows: tuple
    n: int
    tmax: float
    regime: str  # "binding": the Table-3 optimum ends within a day of T_max; "slack": earlier

    def catalog(self) -> Catalog:
        return catalog(self.rows)

    def mission(self) -> Mission:
        # T0 = T_max and a loose ΔVmax: the pre-optimisation keeps every edge (asserted below)
        return Mission(n=self.n, tmax_days=self.tmax, preopt_days=self.tmax, dv_max_mps=5000.0)


CASES = [
    Case("spread5-n3-200d", tuple(SPREAD), 3, 200.0, "binding"),
    Case("spread5-n3-250d", tuple(SPREAD), 3, 250.0, "slack"),
    Case("spread5-n3-120d", tuple(SPREAD), 3, 120.0, "binding"),
    Case("spread4-n3-120d", tuple(SPREAD[:4]), 3, 120.0, "slack"),
    Case("spread4-n3-200d", tuple(SPREAD[:4]), 3, 200.0, "binding"),
    Case("sso4-n3-250d", tuple(NEAR_SSO[:4]), 3, 250.0, "binding"),
    Case("sso5-n3-150d", tuple(NEAR_SSO), 3, 150.0, "binding"),
    Case("sso4-n4-365d", tuple(NEAR_SSO[:4]), 4, 365.0, "binding"),
]
CASE_PARAMS = [pytest.param(case, id=case.name) for case in CASES]

# Known limitations of the solver, measured against this brute force (sdc_cvx 0.1.0):
# 6 of the 8 cases are solved to the optimum, the other 2 end 1-2.5 % above it.
# Sequential linearisation is a local method (Part IV: "the solution found is only valid
# in the vicinity of the starting point"): on catalogs whose J2 rates differ, where a
# leg's best drift orbit depends strongly on its date and RAAN gaps close and wrap
# during the mission, it can settle on the second-best path or on a plan short of the
# optimum.  Since the driver re-optimises a few cheap paths before the first MILP and
# starts from the best (seed paths), spread5-n3-250d (7 % above before) and
# spread4-n3-200d (0.6 %) are solved.  Strict: a fix makes these tests fail until the
# mark is removed.
KNOWN_GAPS = {
    "spread5-n3-200d": "second-best path A-C-E 221.9 m/s vs optimum A-E-C 216.4",
    "sso4-n4-365d": "path S-P-R-Q 461.1 m/s vs optimum P-S-R-Q 456.3",
}
SOLVER_PARAMS = [
    pytest.param(
        case,
        id=case.name,
        marks=[pytest.mark.xfail(strict=True, reason=KNOWN_GAPS[case.name])]
        if case.name in KNOWN_GAPS
        else [],
    )
    for case in CASES
]

_ENUMERATIONS: dict[str, Enumeration] = {}


def enumeration(case: Case) -> Enumeration:
    """The brute force of ``case``, computed once per test session."""
    if case.name not in _ENUMERATIONS:
        middle_count = 8001 if case.n == 3 else 401  # 100 m / 2 km steps, then zoomed
        zoom_count = 401 if case.n == 3 else 101
        _ENUMERATIONS[case.name] = Enumeration(
            case.catalog(), case.n, case.tmax, middle_count=middle_count, zoom_count=zoom_count
        )
    return _ENUMERATIONS[case.name]


def describe(en: Enumeration, plan: Plan) -> str:
    alts = ", ".join(f"{(a - R_EARTH) / 1e3:.3f}" for a in plan.a_drift)
    incs = ", ".join(f"{np.degrees(i):.2f}" for i in plan.inc_drift)
    return (
        f"{'-'.join(en.ids(plan))}: {plan.dv:.3f} m/s, ends day {plan.end_day:.2f} "
        f"(drift alt [{alts}] km, inc [{incs}] deg)"
    )


# ---------------------------------------------------------------------------------------
# The brute force checks itself
# ---------------------------------------------------------------------------------------


def test_brute_force_last_leg_equals_the_full_matrix():
    """The sorted prefix-minimum search of the last leg is the full (dates x radii) minimum."""
    orbits = orbits_of(catalog(SPREAD))
    for path, tmax in [((0, 3, 1), 120.0), ((2, 4, 0), 250.0), ((4, 3, 1), 120.0)]:
        for rule in RULES:
            first = Candidates.band(orbits, path[0], path[1], 301).rule(rule)
            second = Candidates.band(orbits, path[1], path[2], 301).rule(rule)
            arrival = first.duration_days(0.0)
            end = arrival[:, None] + second.duration_days(arrival)
            matrix = first.dv[:, None] + second.dv[None, :]
            full = np.min(np.where(end <= tmax, matrix, np.inf))
            fast, index, k_last = chain([first], LastLeg(second), tmax)
            assert np.isfinite(full)
            assert fast == pytest.approx(full, abs=1e-9)
            plan = replay(orbits, path, [first.a[index[0]], second.a[k_last]],
                          [first.inc[index[0]], second.inc[k_last]])  # fmt: skip
            assert plan.dv == pytest.approx(fast, abs=1e-9)
            assert plan.end_day <= tmax + 1e-9


@pytest.mark.parametrize("name", ["spread4-n3-200d", "sso4-n4-365d"])
def test_brute_force_grid_is_converged(name):
    """A finer brute force moves the optimum of every path by less than 0.05 m/s."""
    case = next(case for case in CASES if case.name == name)
    base = enumeration(case)
    fine = Enumeration(
        case.catalog(),
        case.n,
        case.tmax,
        middle_count=(3 if case.n == 3 else 2) * base.middle_count,
        last_count=2 * base.last_count,
        zoom_count=base.zoom_count,
    )
    for rule in RULES:
        coarse = {plan.path: plan.dv for plan in base.plans[rule]}
        for plan in fine.plans[rule]:
            assert np.isfinite(plan.dv) == np.isfinite(coarse[plan.path])
            if np.isfinite(plan.dv):
                assert coarse[plan.path] == pytest.approx(plan.dv, abs=0.05)


# ---------------------------------------------------------------------------------------
# The cases are well posed
# ---------------------------------------------------------------------------------------


@pytest.mark.parametrize("case", CASE_PARAMS)
def test_case_is_well_posed(case):
    """Every edge survives the pre-optimisation, the optimum is unique, T_max binds or not."""
    en = enumeration(case)
    mission = case.mission()
    orbits = en.orbits
    # the pre-optimisation keeps i -> j iff a Table-3 drift orbit reaches j within T0 from
    # day 0 and the cheapest one costs at most ΔVmax: require it with a day to spare
    for i, j in itertools.permutations(range(len(case.catalog())), 2):
        leg = Candidates.band(orbits, i, j, 4001).rule("table3")
        fast = leg.duration_days(0.0) <= mission.preopt_days - 1.0
        assert fast.any(), f"edge {i}->{j} too slow for T0"
        assert leg.dv[fast].min() <= mission.dv_max_mps
    for rule in RULES:
        best, second = en.plans[rule][:2]
        assert second.dv - best.dv > 1.0, f"{rule}: near tie {describe(en, best)} / {second.dv}"
        assert best.end_day <= case.tmax + 1e-9
        assert best.path == en.plans["table3"][0].path  # both rules agree on the path
    best = en.plans["table3"][0]
    if case.regime == "binding":
        assert best.end_day >= case.tmax - 1.0, describe(en, best)
    else:
        assert best.end_day < case.tmax - 1.0, describe(en, best)


# ---------------------------------------------------------------------------------------
# The solver against the brute force
# ---------------------------------------------------------------------------------------


def solver_plan_checked(sol, catalog_: Catalog, tmax) -> list[bool]:
    """Check the solver's legs against the physics; return whether each follows Table 3."""
    orbits = orbits_of(catalog_)
    index = {name: k for k, name in enumerate(catalog_.ids)}
    day, total, table3 = 0.0, 0.0, []
    for leg in sol.legs:
        o, t = orbits.take(index[leg.from_id]), orbits.take(index[leg.to_id])
        a, inc = leg.drift_a_km * 1e3, np.radians(leg.drift_inc_deg)
        assert A_LOW - 1.0 <= a <= A_HIGH + 1.0
        dv = float(transfer_dv(o.a, o.inc, t.a, t.inc, a, inc))
        assert dv == pytest.approx(leg.dv_mps, abs=0.01)
        assert leg.departure_day == pytest.approx(day, abs=1e-3)
        day += float(transfer_duration(o, t, a, inc, day * DAY)) / DAY
        assert leg.departure_day + leg.duration_days == pytest.approx(day, abs=1e-3)
        total += dv
        side = np.sign(drift_rate(a, inc) - t.rate)
        table3.append(bool(np.isclose(inc, drift_inclination(o.inc, t.inc, side), atol=1e-9)))
    assert sol.total_dv_mps == pytest.approx(total, abs=0.01)
    assert sol.total_duration_days == pytest.approx(day, abs=1e-3)
    assert [leg.from_id for leg in sol.legs] + [sol.legs[-1].to_id] == list(sol.path)
    return table3


@pytest.mark.parametrize("case", SOLVER_PARAMS)
def test_solver_finds_the_enumerated_optimum(case):
    from sdc_cvx.planner.sequential import MissionInfeasible, solve

    en = enumeration(case)
    reference, free = en.plans["table3"][0], en.plans["free"][0]
    expected = (
        f"brute force: Table 3 {describe(en, reference)}; free {describe(en, free)}; "
        f"second best {describe(en, en.plans['table3'][1])}"
    )
    try:
        sol = solve(case.catalog(), case.mission())
    except MissionInfeasible as exc:
        sol, infeasible = None, str(exc)
    if sol is None:
        pytest.fail(f"solver: MissionInfeasible ({infeasible}), but {expected}")
    legs = ", ".join(
        f"{leg.from_id}->{leg.to_id} alt {leg.drift_alt_km:.3f} inc {leg.drift_inc_deg:.2f} "
        f"side {leg.side:+d} {leg.dv_mps:.3f} m/s {leg.duration_days:.2f} d"
        for leg in sol.legs
    )
    got = (
        f"solver: {'-'.join(sol.path)}: {sol.total_dv_mps:.3f} m/s, ends day "
        f"{sol.total_duration_days:.2f} ({legs}); {expected}"
    )
    table3 = solver_plan_checked(sol, case.catalog(), case.tmax)
    assert sol.total_duration_days <= case.tmax + 1e-6, got
    # below the free optimum would be a plan the physics does not allow
    assert sol.total_dv_mps >= free.dv - 0.5, got
    assert sol.path == en.ids(reference), got
    assert sol.total_dv_mps <= reference.dv + 0.5, got
    if all(table3):  # a plan within the Table-3 rule cannot beat its optimum
        assert sol.total_dv_mps >= reference.dv - 0.5, got
