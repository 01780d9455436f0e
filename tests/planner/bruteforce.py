"""An independent brute force of the mission's optimum, for the solver's tests.

It enumerates every ordered path of n debris and, for each, searches the drift orbits
of every leg on a radius grid with the true physics (Eq. 7-13 and Table 3, re-derived from
the paper in ``tests/paper_physics.py``, which imports nothing of ``sdc_cvx``): no
linearisation, no MILP, no date cells, no bounds, nothing from the code under test (the
package's ``physics`` layer included, so that a physics error there is not repeated here;
only ``sdc_cvx.Catalog`` is used, to read the debris' elements).  The model is the solver's: the
vehicle is at the first debris at t = 0, each leg leaves as soon as the previous one
arrives (T_deorb = 0), each drift orbit is circular with a radius in the altitude band
and the inclination of one of the two debris, and the mission ends (arrival at the last
debris) by T_max.  Two drift inclination rules (``Mission.drift_inclination``):

* ``table3``: the drift inclination is Table 3's for the side of the asymptote the drift
  orbit is on (``drift_inclination(I_i, I_j, side)``);
* ``free``: either debris inclination on either side.

Every plan it returns is replayed leg by leg with the physics (:func:`replay`), so its
cost is that of a plan that flies: the brute-force optimum is never below the true
optimum, and exceeds it by at most the grid error (measured by the tests that use it).

How the grid search stays exhaustive and fast.  The middle legs (all but the last) are
gridded and chained by broadcasting: every grid point of leg k departs at every arrival
date of leg k-1.  The last leg does not need the full matrix: its duration at departure
date t is ``W_s(t) / |rate_d - rate_j|`` where ``W_s(t)`` is the RAAN gap wrapped for
side s, which does not depend on the drift orbit.  "Duration <= budget" is then
"``|rate_d - rate_j| >= W_s(t) / budget``", and the cheapest grid point meeting it is a
prefix minimum over the grid sorted by relative rate, found by binary search for every
departure date at once.  This is the same minimum as the full (dates x radii) matrix
(checked by ``test_brute_force_last_leg_equals_the_full_matrix`` in
``test_enumeration.py``), with a grid of 32 000 radii per inclination.  The best grid
points of each (inclination, side) branch of the middle legs are then refined by
zooming (a grid of +/- 2 steps around them, three times).

:meth:`Enumeration.optimum` finds the cheapest plan best-first: paths in increasing
order of the sum of their legs' cheapest costs at any date (a lower bound of every plan
of the path, see :data:`FLOOR_MARGIN_MPS`), stopping at the first path whose bound
exceeds the best plan found.  It returns the same plan as the full enumeration
(:attr:`Enumeration.plans`), only sooner.
"""

from __future__ import annotations

import itertools
from dataclasses import dataclass
from functools import cached_property

import numpy as np

from sdc_cvx import Catalog
from tests.paper_physics import (
    R_EARTH,
    SECONDS_PER_DAY,
    NodeOrbits,
    drift_inclination,
    drift_rate,
    transfer_duration,
    transfer_dv,
)

DAY = SECONDS_PER_DAY
A_LOW, A_HIGH = R_EARTH + 400e3, R_EARTH + 1200e3  # Mission's default drift altitude band
RULES = ("table3", "free")

# ---------------------------------------------------------------------------------------
# Brute force (independent of the code under test)
# ---------------------------------------------------------------------------------------


def orbits_of(catalog: Catalog) -> NodeOrbits:
    return NodeOrbits.from_elements(catalog.a_m, catalog.e, catalog.inc_rad, catalog.raan_rad)


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


def chain(middle: list[Candidates], last: LastLeg, tmax, reached: list | None = None):
    """Exhaustive minimum over the grids of the middle legs and the last leg.

    Returns the minimum cost, the index of each middle leg's candidate and of the last
    leg's, or ``(inf, None, None)`` when nothing meets T_max.  Appends to ``reached``
    (if given) the number of middle legs after which some grid point still met T_max.
    """
    cost, arrival = np.zeros(1), np.zeros(1)
    index = np.zeros((1, 0), dtype=int)
    depth = 0
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
        if reached is not None and cost.size:
            depth += 1
    if reached is not None:
        reached.append(depth)
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


def search(legs: list[Candidates], last: LastLeg, tmax, reached: list | None = None):
    """:func:`chain`, as (cost, [(a, inc) of every leg]) or (inf, None)."""
    dv, index, k_last = chain(legs, last, tmax, reached)
    if index is None:
        return np.inf, None
    orbits = [(g.a[k], g.inc[k]) for g, k in zip(legs, index, strict=True)]
    return dv, orbits + [(last.c.a[k_last], last.c.inc[k_last])]


def path_optimum(grids, lasts, path, tmax, rule, *, step, zoom_count, zoom_levels=3,
                 walk=0, reached: list | None = None) -> Plan:  # fmt: skip
    """Minimum total ΔV of ``path`` with arrival at its last debris by ``tmax`` days.

    ``grids`` and ``lasts`` hold the middle-leg candidates (radius grid ``step`` [m]) and
    the last-leg searches of every ordered pair.  The best grid point of every
    (inclination, side) branch of the middle legs is refined by zooming: a grid of
    ``zoom_count`` radii per middle leg over +/- 2 steps around it, ``zoom_levels``
    times, each level on a window of +/- 2 steps of the previous zoom grid.  With
    ``walk`` > 0, each level is repeated (at most ``walk`` more times) around the new
    best point while it improves, so that the search can follow a plan that slides
    along the edge of the feasible set (a RAAN gap that wraps, T_max) beyond the window.
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
        dv, drift = search(legs, last, tmax, reached)
        half = 2.0 * step
        for _ in range(zoom_levels if legs else 0):
            for _ in range(1 + walk):
                if drift is None:
                    break
                zoomed = [
                    zoom(g, a, inc, half, zoom_count, rule)
                    for g, (a, inc) in zip(legs, drift, strict=False)
                ]
                dv_zoom, drift_zoom = search(zoomed, last, tmax)
                improved = dv_zoom < dv - 1e-9
                if dv_zoom <= dv:
                    dv, drift = dv_zoom, drift_zoom
                if not improved:
                    break
            half = 2.0 * (2.0 * half) / (zoom_count - 1)
        if dv < best_dv:
            best_dv, best = dv, drift
    if best is None:
        return Plan(tuple(path), np.inf, np.inf)
    plan = replay(middle[0].orbits if middle else last.c.orbits, path, *zip(*best, strict=True))
    assert abs(plan.dv - best_dv) <= 1e-6, (plan, best_dv)  # the search and the replay agree
    assert plan.end_day <= tmax + 1e-9, plan
    return plan


def replay(orbits: NodeOrbits, path, a, inc) -> Plan:
    """Evaluate a plan leg by leg with the physics (what the brute force claims, recomputed)."""
    day, leg_dv = 0.0, []
    for (i, j), a_d, i_d in zip(itertools.pairwise(path), a, inc, strict=True):
        o, t = orbits.take(i), orbits.take(j)
        leg_dv.append(float(transfer_dv(o.a, o.inc, t.a, t.inc, a_d, i_d)))
        day += float(transfer_duration(o, t, a_d, i_d, day * DAY)) / DAY
    return Plan(tuple(path), sum(leg_dv), day, tuple(a), tuple(inc), tuple(leg_dv))


class _LastLegs(dict):
    """``{((i, j), rule): LastLeg}``, each built on first use from the fine grids."""

    def __init__(self, fine):
        super().__init__()
        self.fine = fine

    def __missing__(self, key):
        pair, rule = key
        self[key] = LastLeg(self.fine[pair].rule(rule))
        return self[key]


FLOOR_MARGIN_MPS = 0.1
"""Slack of a leg's cost floor below the minimum over its 32 000-radius grid [m/s].

The cost of a leg is continuous in the drift radius, with kinks only at the two debris
radii (grid points), and changes by less than 2e-3 m/s per metre of radius in the band;
the grid step is 25 m, so the true minimum over the band is at most 0.025 m/s below the
grid's.  A floor 0.1 m/s below it is below every plan of the leg, at any date."""


@dataclass
class Enumeration:
    """The brute force of one mission: the optimum of every ordered path of n debris.

    ``middle_count`` radii span the band for the middle legs (then zoomed with
    ``zoom_count`` radii), ``last_count`` for the last leg.
    """

    catalog: Catalog
    n: int
    tmax: float
    middle_count: int
    last_count: int = 32_000
    zoom_count: int = 401
    walk: int = 0

    @cached_property
    def orbits(self):
        return orbits_of(self.catalog)

    @cached_property
    def pairs(self) -> list[tuple[int, int]]:
        return list(itertools.permutations(range(len(self.catalog)), 2))

    @cached_property
    def grids(self) -> dict[tuple[int, int], Candidates]:
        return {p: Candidates.band(self.orbits, *p, self.middle_count) for p in self.pairs}

    @cached_property
    def fine(self) -> dict[tuple[int, int], Candidates]:
        return {p: Candidates.band(self.orbits, *p, self.last_count) for p in self.pairs}

    @cached_property
    def lasts(self) -> _LastLegs:
        """The last-leg search of each (pair, rule), built when first needed."""
        return _LastLegs(self.fine)

    def path_optimum(self, path, rule: str, reached: list | None = None) -> Plan:
        """Cheapest plan of ``path`` under ``rule`` (``dv = inf`` when none meets T_max).

        ``reached`` receives, per (inclination, side) branch, the number of middle legs
        after which some grid point still meets T_max (:func:`chain`).
        """
        step = (A_HIGH - A_LOW) / (self.middle_count - 1)
        return path_optimum(self.grids, self.lasts, tuple(path), self.tmax, rule, step=step,
                            zoom_count=self.zoom_count, walk=self.walk,
                            reached=reached)  # fmt: skip

    def paths(self):
        return itertools.permutations(range(len(self.catalog)), self.n)

    @cached_property
    def plans(self) -> dict[str, list[Plan]]:
        """Per rule, the best plan of every path, cheapest first."""
        return {
            rule: sorted(
                (self.path_optimum(path, rule) for path in self.paths()), key=lambda plan: plan.dv
            )  # fmt: skip
            for rule in RULES
        }

    def optimum(self, rule: str) -> Plan:
        """The cheapest plan of every path under ``rule`` (``dv = inf``: no path meets T_max).

        Best-first: the paths in increasing order of the sum of their legs' floors (the
        cheapest cost of each leg at any date, minus :data:`FLOOR_MARGIN_MPS`), until a
        path's floor exceeds the best plan found, which no plan of it can then beat.
        Paths whose first legs already end after T_max at every grid point of another
        path with the same first legs are skipped (they would return ``inf``).
        """
        floor = {p: float(self.fine[p].rule(rule).dv.min()) - FLOOR_MARGIN_MPS
                 for p in self.pairs}  # fmt: skip
        ranked = sorted(
            (sum(floor[pair] for pair in itertools.pairwise(path)), path) for path in self.paths()
        )
        best = Plan((), np.inf, np.inf)
        dead: set[tuple[int, ...]] = set()
        for bound, path in ranked:
            if bound > best.dv:
                break
            if any(path[:k] in dead for k in range(2, self.n)):
                continue  # every grid point of a prefix ends after T_max
            reached: list[int] = []
            plan = self.path_optimum(path, rule, reached)
            if plan.dv < best.dv:
                best = plan
            if reached and max(reached) < self.n - 2:
                # no branch's grid got past middle leg max(reached): the paths that
                # share the legs up to it are searched on the same grids, and die there
                dead.add(path[: max(reached) + 2])
        return best

    def ids(self, plan: Plan) -> tuple[str, ...]:
        return tuple(self.catalog.ids[k] for k in plan.path)
