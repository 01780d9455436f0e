"""Global optimum of a fixed path: the best dates and drift orbits, with a certificate.

For an ordered path v_0 -> ... -> v_L, the vehicle leaves v_0 after its operations,
each leg arrives when its drift closes the RAAN gap (Eq. 10), the next leg leaves after
the operations at the debris reached, and the mission ends by T_max.  Choosing each
leg's arrival date is the same as choosing its drift orbit, so the problem is a chain
of dates ``x_0 <= x_1 <= ... <= x_L`` (x_k: the date the vehicle is ready to leave the
k-th debris; x_L: the end) with cost ``sum_k c_k(x_k, x_{k+1} - ops_{k+1})``, where
``c_k`` is the exact cost of leg k between two dates (``LegCosts.cost_at``, in the
transfer model of the cost tables: :mod:`~sdc_cvx.physics.models`).

A dynamic programme over date cells brackets the optimum:

- lower bound: each position's dates are split into cells; a leg between a cell of
  position k and a cell of position k+1 costs at least ``LegCosts.box_bound``, and the
  cheapest chain of cells under those bounds is a lower bound of every schedule;
- upper bound: the same programme over exact costs between dates of a grid (cell ends
  and centres, and the dates a leg may need exactly: for the impulsive leg, where two
  RAANs cross, for zero-length legs) is a schedule
  that flies;
- the cells of the lower bound's chain are halved, cells that cannot hold a schedule
  better than the upper bound are dropped, and the two are computed again until they
  differ by at most the tolerance (branch and bound over the date cells).

References
----------
.. [1] M. Cerf, "Multiple space debris collecting mission - Debris selection and
   trajectory optimization", Journal of Optimization Theory and Applications,
   156(3), 761-796, 2013.
"""

from __future__ import annotations

import time
from dataclasses import dataclass, field
from typing import NamedTuple

import numpy as np

from ..physics.leg_bounds import LegCosts
from ..physics.plan import PlanEvaluation, evaluate_plan

INITIAL_CELLS = 24
MIN_CELL_DAYS = 1e-5
SPLIT = 4
"""Parts a cell of the lower bound's chain is split into each round."""
SPLIT_CELLS = 16
"""Most cells of one position split in a round (those of the lowest bounds first)."""
GRID_CAP = 72
"""Most grid dates per position in the upper-bound programme (the best cells' first)."""


@dataclass(frozen=True)
class PathProblem:
    """One ordered path and the mission constraints that bind its schedule.

    Attributes
    ----------
    legs : LegCosts
        Cost tables of (at least) the path's edges.
    edges : tuple of int
        Edge of ``legs`` flown by each leg, length L.
    ops_days : tuple of float
        Operations time T_deorb at each debris of the path [days], length L + 1.
    tmax_days, tmin_days : float
        Mission duration limit T_max and minimum transfer duration T_min [days].
    rule : {"table3", "free"}
        Drift inclination rule.
    j2 : float
    """

    legs: LegCosts
    edges: tuple[int, ...]
    ops_days: tuple[float, ...]
    tmax_days: float
    tmin_days: float
    rule: str
    j2: float

    @property
    def n_legs(self) -> int:
        return len(self.edges)

    def earliest(self) -> np.ndarray:
        """Earliest date of each position [days] (T_min per leg, operations at each debris)."""
        steps = np.asarray(self.ops_days[1:]) + self.tmin_days
        return self.ops_days[0] + np.r_[0.0, np.cumsum(steps)]


@dataclass(frozen=True)
class PathSchedule:
    """Best schedule found for a path and the certified lower bound of every schedule.

    Attributes
    ----------
    upper_mps : float
        Transfer ΔV of the schedule [m/s] (``inf`` if none was found).
    lower_mps : float
        No schedule of this path costs less [m/s].
    departure_days, arrival_days : ndarray
        Per leg [days after t0].
    a_drift, inc_drift, side : ndarray
        Per leg: drift radius [m], inclination [rad], side of the asymptote.
    laps : ndarray of int
        Per leg: relative laps of the coast beyond the first that closes the RAAN gap.
    dv_mps : ndarray
        Per leg [m/s].
    end_day : float
        Arrival at the last debris plus its operations [days].
    rounds, cells : int
        Refinement rounds, and date cells in the last one.
    seconds : float
    """

    upper_mps: float
    lower_mps: float
    departure_days: np.ndarray = field(repr=False)
    arrival_days: np.ndarray = field(repr=False)
    a_drift: np.ndarray = field(repr=False)
    inc_drift: np.ndarray = field(repr=False)
    side: np.ndarray = field(repr=False)
    dv_mps: np.ndarray = field(repr=False)
    end_day: float
    rounds: int
    cells: int
    seconds: float
    laps: np.ndarray = field(repr=False, default_factory=lambda: np.zeros(0, dtype=int))

    @property
    def gap_mps(self) -> float:
        return self.upper_mps - self.lower_mps

    @property
    def feasible(self) -> bool:
        return bool(np.isfinite(self.upper_mps))


class _Cells:
    """Date cells of one position: sorted, disjoint ``[lo, hi]`` with stable ids, the id of
    the cell each was split from (``parents``: its own if none), and the least cost to
    reach each (``into``) and to end the path from it (``onward``) that the last round's
    bounds proved (0 before any: no information)."""

    def __init__(self, lo, hi, ids, next_id, into=None, onward=None, parents=None):
        self.lo, self.hi, self.ids, self.next_id = lo, hi, ids, next_id
        self.into = np.zeros(len(lo)) if into is None else into
        self.onward = np.zeros(len(lo)) if onward is None else onward
        self.parents = ids if parents is None else parents

    @classmethod
    def uniform(cls, start, stop, count, first_id=0):
        edges = np.array([start, start]) if stop <= start else np.linspace(start, stop, count + 1)
        n = len(edges) - 1
        return cls(edges[:-1].copy(), edges[1:].copy(), np.arange(first_id, first_id + n),
                   first_id + n)  # fmt: skip

    def __len__(self):
        return len(self.lo)

    def refine(self, split, keep, into, onward):
        """Split the cells in ``split`` in ``SPLIT`` parts; drop those not in ``keep``.

        ``into`` and ``onward`` are this round's bounds of each cell; a part inherits its
        cell's (a part's own are at least as high, the exact ones at least).
        """
        lo, hi, ids, parents, into_out, onward_out = [], [], [], [], [], []
        next_id = self.next_id
        for k in range(len(self.lo)):
            if not keep[k]:
                continue
            if split[k] and self.hi[k] - self.lo[k] > MIN_CELL_DAYS:
                edges = np.linspace(self.lo[k], self.hi[k], SPLIT + 1)
                lo += list(edges[:-1])
                hi += list(edges[1:])
                ids += list(range(next_id, next_id + SPLIT))
                parents += [self.ids[k]] * SPLIT
                next_id += SPLIT
                into_out += [into[k]] * SPLIT
                onward_out += [onward[k]] * SPLIT
            else:
                lo.append(self.lo[k])
                hi.append(self.hi[k])
                ids.append(self.ids[k])
                parents.append(self.ids[k])
                into_out.append(into[k])
                onward_out.append(onward[k])
        return _Cells(np.array(lo), np.array(hi), np.array(ids, dtype=int), next_id,
                      np.array(into_out), np.array(onward_out),
                      np.array(parents, dtype=int))  # fmt: skip


class _BoundCache:
    """Leg box bounds between the cells of two positions, recomputed only for new cells.

    A new box lies inside the box of its cells' parents, whose bound therefore holds for it
    too: the box is bounded again only where that bound is below the box's cap.
    """

    def __init__(self):
        self.rows = self.cols = np.empty(0, dtype=int)
        self.matrix = np.empty((0, 0))

    def update(self, problem: PathProblem, k: int, cells_from: _Cells, cells_to: _Cells,
               limit: float = np.inf, floor_elsewhere: float = 0.0) -> _BoxRequest:  # fmt: skip
        """The bounds between the cells of positions k and k + 1: the known ones, and the
        boxes still to bound (:func:`_bound_all` bounds every leg's at once).

        A new box's bound may stop once a schedule through it would cost more than
        ``limit``: at ``limit`` less what the cells' ``into`` and ``onward`` bounds (or the
        other legs' floors, ``floor_elsewhere``, when larger) already prove of the rest.
        """
        r_map = _positions(self.rows, cells_from.ids)
        c_map = _positions(self.cols, cells_to.ids)
        out = np.full((len(cells_from), len(cells_to)), np.nan)
        known = (r_map[:, None] >= 0) & (c_map[None, :] >= 0)
        if known.any():
            rr, cc = np.nonzero(known)
            out[rr, cc] = self.matrix[r_map[rr], c_map[cc]]
        rr, cc = np.nonzero(~known)
        rest = np.maximum(cells_from.into[rr] + cells_to.onward[cc], floor_elsewhere)
        with np.errstate(invalid="ignore"):  # inf - inf: no limit yet
            cap = np.nan_to_num(limit - rest + 1e-6, nan=np.inf)
        inherited = np.zeros(len(rr))
        pr = _positions(self.rows, cells_from.parents[rr])
        pc = _positions(self.cols, cells_to.parents[cc])
        has = (pr >= 0) & (pc >= 0)
        inherited[has] = self.matrix[pr[has], pc[has]]
        out[rr, cc] = inherited
        todo = np.flatnonzero(inherited < cap)
        r, c = rr[todo], cc[todo]
        ops = problem.ops_days[k + 1]
        self.rows, self.cols, self.matrix = cells_from.ids.copy(), cells_to.ids.copy(), out
        return _BoxRequest(out, r, c, np.full(len(todo), problem.edges[k]),
                           (cells_from.lo[r], cells_from.hi[r], cells_to.lo[c] - ops,
                            cells_to.hi[c] - ops), cap[todo], inherited[todo])  # fmt: skip


class _BoxRequest(NamedTuple):
    """One leg's boxes to bound: rows and columns of its bound matrix ``out`` (which
    holds their parents' bounds so far), their edge, dates, caps and parents' bounds."""

    out: np.ndarray
    rows: np.ndarray
    cols: np.ndarray
    edges: np.ndarray
    dates: tuple
    cap: np.ndarray
    floor: np.ndarray


def _bound_all(problem: PathProblem, requests: list[_BoxRequest]) -> list[np.ndarray]:
    """Every leg's bound matrix, the new boxes of all legs bounded in one call (the box
    bounds are vectorised: one call over all legs costs little more than one over one)."""
    if sum(len(q.rows) for q in requests):
        joined = (np.concatenate([q.edges for q in requests]),
                  *(np.concatenate([q.dates[i] for q in requests]) for i in range(4)))
        bounds = problem.legs.box_bound(*joined, rule=problem.rule, j2=problem.j2,
                                        t_min=problem.tmin_days,
                                        cap=np.concatenate([q.cap for q in requests]),
                                        floor=np.concatenate([q.floor for q in requests]))
        start = 0
        for q in requests:
            part = bounds[start:start + len(q.rows)]
            q.out[q.rows, q.cols] = np.maximum(q.out[q.rows, q.cols], part)
            start += len(q.rows)
    return [q.out for q in requests]


def _positions(old_ids, ids):
    """Index of each of ``ids`` in ``old_ids`` (-1 where absent)."""
    size = int(max(old_ids.max(initial=-1), ids.max(initial=-1))) + 1
    where = np.full(size, -1, dtype=int)
    where[old_ids] = np.arange(len(old_ids))
    return where[ids]


def solve_path(problem: PathProblem, *, tol_mps: float = 0.01, tol_rel: float = 0.0,
               cutoff_mps: float = np.inf, max_rounds: int = 200, time_limit_s: float = np.inf,
               initial_cells: int = INITIAL_CELLS) -> PathSchedule:  # fmt: skip
    """Certified minimum ΔV schedule of a fixed path (branch and bound over date cells).

    Parameters
    ----------
    problem : PathProblem
    tol_mps, tol_rel : float
        Stop when the best schedule is within ``max(tol_mps, tol_rel * schedule)`` of
        the lower bound [m/s, -].
    cutoff_mps : float
        Stop as soon as the lower bound exceeds this [m/s] (the path cannot beat a plan
        in hand); the schedule returned is then the best found so far, and its lower
        bound a true one still (the cells dropped above the cutoff count in it).
    max_rounds : int
    time_limit_s : float

    Returns
    -------
    PathSchedule
    """
    start_clock = time.perf_counter()
    L = problem.n_legs
    earliest = problem.earliest()
    tmax = problem.tmax_days
    first = problem.ops_days[0]
    if earliest[-1] > tmax:
        return _no_schedule(L, np.inf, 0, 0, start_clock)
    cells = [_Cells(np.array([first]), np.array([first]), np.array([0]), 1)]
    for k in range(1, L + 1):
        cells.append(_Cells.uniform(earliest[k], tmax, initial_cells))
    caches = [_BoundCache() for _ in range(L)]
    best_upper, best_plan = np.inf, None
    lower = -np.inf
    dropped_floor = np.inf  # no schedule through a cell dropped above the limit costs less
    rounds = 0
    special = _special_dates(problem, earliest)
    floors = problem.legs.floor(np.asarray(problem.edges))
    for rounds in range(1, max_rounds + 1):  # noqa: B007 - reported after the loop
        # a box on no schedule under the limit need not have its bound refined past it
        limit = min(best_upper, cutoff_mps)
        bounds = _bound_all(problem, [caches[k].update(problem, k, cells[k], cells[k + 1], limit,
                                                       floors.sum() - floors[k])
                                      for k in range(L)])  # fmt: skip
        backward = [None] * (L + 1)
        backward[L] = np.zeros(len(cells[L]))
        choice = [None] * L
        for k in range(L - 1, -1, -1):
            total = bounds[k] + backward[k + 1][None, :]
            choice[k] = np.argmin(total, axis=1)
            backward[k] = total[np.arange(len(cells[k])), choice[k]]
        lower = float(backward[0][0])
        forward = [np.zeros(1)]
        for k in range(L):
            forward.append(np.min(forward[k][:, None] + bounds[k], axis=0))
        if not np.isfinite(lower):
            break
        plan = _grid_schedule(problem, cells, special, forward, backward)
        if plan is not None and plan[0] < best_upper:
            best_upper, best_plan = plan
        tol = max(tol_mps, tol_rel * best_upper) if np.isfinite(best_upper) else tol_mps
        if best_upper - lower <= tol or lower > cutoff_mps:
            break
        if time.perf_counter() - start_clock > time_limit_s:
            break
        chain = [0]
        for k in range(L):
            chain.append(int(choice[k][chain[-1]]))
        limit = min(best_upper, cutoff_mps) + 1e-9
        new_cells = [cells[0]]
        for k in range(1, L + 1):
            through = forward[k] + backward[k]
            keep = through <= limit
            if not keep.all():  # above a cutoff, the path's optimum may lie in them
                dropped_floor = min(dropped_floor, float(through[~keep].min()))
            split = np.zeros(len(cells[k]), dtype=bool)
            split[np.argsort(through)[:SPLIT_CELLS]] = True
            split &= through < limit - tol
            split[chain[k]] = True
            new_cells.append(cells[k].refine(split, keep, forward[k], backward[k]))
        unchanged = (np.array_equal(a.ids, b.ids) for a, b in zip(cells, new_cells, strict=True))
        if all(unchanged):
            break  # nothing left to split: the cells are at their narrowest
        cells = new_cells
    lower = max(lower, -np.inf) if np.isfinite(lower) else (np.inf if best_plan is None else lower)
    # the DP covers the cells kept; a cutoff below the path's optimum may have dropped the
    # cells that hold it: the bound is the least of the two (a proof, reusable as one)
    lower = min(lower, dropped_floor)
    if best_plan is None:
        return _no_schedule(L, lower, rounds, sum(map(len, cells)), start_clock)
    lower = min(lower, best_upper)
    dates = best_plan
    return _schedule(problem, dates, best_upper, lower, rounds, sum(map(len, cells)), start_clock)


def _special_dates(problem: PathProblem, earliest):
    """Per position, dates a schedule may need exactly (the model's: for the impulsive leg,
    RAAN crossings, where a leg of zero length is possible)."""
    out = [np.empty(0) for _ in range(problem.n_legs + 1)]
    if problem.tmin_days > 0:
        return out
    for k, e in enumerate(problem.edges):
        dates = problem.legs.special_dates(e, earliest[k], problem.tmax_days)
        out[k] = np.concatenate([out[k], dates])
        out[k + 1] = np.concatenate([out[k + 1], dates + problem.ops_days[k + 1]])
    return out


def _grid_schedule(problem: PathProblem, cells, special, forward, backward):
    """Cheapest schedule over exact costs between grid dates of the live cells.

    Returns ``(cost, dates)`` with dates per position, or None.
    """
    L = problem.n_legs
    points = []
    for k in range(L + 1):
        c = cells[k]
        if k == 0:
            points.append(np.array([c.lo[0]]))
            continue
        order = np.argsort(forward[k] + backward[k])[: GRID_CAP // 3]
        pts = np.concatenate([c.lo[order], c.hi[order], 0.5 * (c.lo[order] + c.hi[order])])
        sp = special[k]
        if len(sp):
            live = np.zeros(len(sp), dtype=bool)
            for lo, hi in zip(c.lo[order], c.hi[order], strict=True):
                live |= (sp >= lo) & (sp <= hi)
            pts = np.concatenate([pts, sp[live]])
        points.append(np.unique(pts[pts <= problem.tmax_days]))
    costs = []
    for k in range(L):
        t = points[k][:, None]
        t_arrive = points[k + 1][None, :] - problem.ops_days[k + 1]
        costs.append(problem.legs.cost_at(problem.edges[k], t, t_arrive, rule=problem.rule,
                                          j2=problem.j2, t_min=problem.tmin_days).cost)
    value = np.zeros(len(points[L]))
    choice = [None] * L
    for k in range(L - 1, -1, -1):
        total = costs[k] + value[None, :]
        choice[k] = np.argmin(total, axis=1)
        value = total[np.arange(len(points[k])), choice[k]]
    if not np.isfinite(value[0]):
        return None
    index = [0]
    for k in range(L):
        index.append(int(choice[k][index[-1]]))
    return float(value[0]), np.array([points[k][index[k]] for k in range(L + 1)])


def _schedule(problem: PathProblem, dates, upper, lower, rounds, cells, start_clock):
    L = problem.n_legs
    ops = np.asarray(problem.ops_days)
    departure = dates[:-1]
    arrival = dates[1:] - ops[1:]
    leg = problem.legs.cost_at(np.asarray(problem.edges), departure, arrival, rule=problem.rule,
                               j2=problem.j2, t_min=problem.tmin_days)  # fmt: skip
    return PathSchedule(
        float(np.sum(leg.cost)),
        float(lower),
        departure,
        arrival,
        leg.a_drift,
        leg.inc_drift,
        leg.side,
        leg.cost,
        float(dates[L]),
        rounds,
        cells,
        time.perf_counter() - start_clock,
        leg.laps,
    )


def _no_schedule(L, lower, rounds, cells, start_clock):
    nan = np.full(L, np.nan)
    return PathSchedule(np.inf, float(lower), nan, nan, nan, nan, np.zeros(L), nan, np.nan,
                        rounds, cells, time.perf_counter() - start_clock,
                        np.zeros(L, dtype=int))  # fmt: skip


def schedule_plan(orbits, path, schedule: PathSchedule, *, deorbit_days, tmax_days: float,
                  j2: float, model=None,
                  eccentricity=None) -> tuple[PlanEvaluation, list[str]]:  # fmt: skip
    """A certified schedule flown in the true model (Eq. 10 arrivals), and notes.

    Parameters
    ----------
    orbits : NodeOrbits
    path : sequence of int
        Node positions.
    schedule : PathSchedule
        A feasible schedule of ``path`` (:func:`solve_path`).
    deorbit_days : ndarray
        Operations time at every node [days].
    tmax_days, j2 : float
    model : TransferModel, optional
        The transfer model the schedule was found in (default impulsive).
    eccentricity : Eccentricities, optional
        The nodes' eccentricity vectors, where the legs price them.

    Returns
    -------
    PlanEvaluation, list of str
        The plan replayed from the schedule's drift orbits, or the schedule's own dates
        where a zero-length leg (RAANs crossing) rounds to a full cycle in Eq. 10's wrap
        (then a note says so).
    """
    laps = schedule.laps if len(schedule.laps) else 0
    plan = evaluate_plan(orbits, list(path), schedule.a_drift, schedule.inc_drift,
                         deorbit_days=deorbit_days, j2=j2, model=model, laps=laps,
                         eccentricity=eccentricity)  # fmt: skip
    if abs(plan.end_day - schedule.end_day) < 1e-6 and plan.end_day <= tmax_days + 1e-6:
        return plan, []
    part = plan.eccentricity_dv_mps  # at the schedule's dates: its cost, its priced part
    part = None if part is None else part + (schedule.dv_mps - plan.dv_mps)
    plan = PlanEvaluation(schedule.departure_days, schedule.arrival_days - schedule.departure_days,
                          schedule.arrival_days, schedule.dv_mps, schedule.end_day,
                          part)  # fmt: skip
    return plan, ["legs reported with the schedule's dates (Eq. 10 rounding at a RAAN crossing)"]
