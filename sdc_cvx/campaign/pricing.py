"""Pricing: the cheapest missions of one launch under prices on the debris.

The master of a campaign (:mod:`~sdc_cvx.campaign.master`) prices each debris i at
``y_i`` (the dual of its "removed at most once" row, >= 0; of a ``must_remove`` row,
of any sign).  A mission's reduced cost is its ΔV plus the prices of the debris it
removes, less its launch's dual.  So the pricing problem of a launch is an ordinary
mission whose operations cost at debris i is raised by ``y_i``: the certified search
(:func:`~sdc_cvx.planner.certified.certify`) with node costs, which may be negative
(a prize) on a ``must_remove`` debris.  The search is valid with any node costs: every
comparison it makes is between sums of exactly n node costs on each side (see its
Notes, and ``docs/design.md`` §10).

Each pricing returns every path the search certified on the way (a column: the launch,
the path, its best schedule, its ΔV and its proven lower bound) and the proven lower
bound of the launch's best mission under the prices.

References
----------
.. [1] G. Desaulniers, J. Desrosiers and M. M. Solomon (eds.), *Column Generation*,
   Springer, 2005 (the master, pricing and Lagrangian bound).
"""

from __future__ import annotations

import time
from dataclasses import dataclass, replace

import numpy as np

from ..inputs.catalog import Catalog
from ..inputs.mission import Mission
from ..milp.types import SolverOptions
from ..network.edges import drift_radius_bounds, node_orbits
from ..planner.api import certified_nodes, solution_of
from ..planner.certified import certify
from ..planner.fixed_path import PathSchedule
from ..planner.nodes import MissionNodes
from ..study.executors import restore_malloc


@dataclass(frozen=True)
class Launch:
    """One mission of a campaign, as its pricing needs it.

    Attributes
    ----------
    index : int
        Position in the campaign (0-based).
    day : float
        Launch day [days after the catalog's start].
    mission : Mission
    catalog : Catalog
        The candidates with their RAANs at the launch day (``Catalog.advanced``): the
        mission's own day 0.
    """

    index: int
    day: float
    mission: Mission
    catalog: Catalog

    @classmethod
    def all_of(cls, campaign, catalog: Catalog) -> list[Launch]:
        """Every launch of ``campaign`` over ``catalog`` (RAANs carried to each day), each
        mission with its catalog's defaults set (:meth:`Mission.for_catalog`: the
        eccentricity priced where the catalog gives the argument of perigee, legs the flight
        can phase), as a single mission's ``solve`` sets them."""
        launches = []
        for k, (day, mission) in enumerate(zip(campaign.launch_days, campaign.missions,
                                               strict=True)):  # fmt: skip
            advanced = catalog.advanced(day, j2=mission.j2)
            launches.append(cls(k, float(day), mission.for_catalog(advanced), advanced))
        return launches

    def label(self) -> str:
        return f"mission {self.index + 1} (launch day {self.day:g})"


@dataclass(frozen=True)
class Column:
    """One flyable mission of a launch: a column of the master.

    Attributes
    ----------
    launch : int
    nodes : tuple of int
        Node positions of the path (catalog rows; the injection orbit, if any, is the
        row after the catalog's).
    debris : tuple of int
        Catalog rows it removes (sorted).
    dv_mps : float
        Total ΔV of its schedule, transfers and operations [m/s].
    lower_mps : float
        No schedule of this path costs less [m/s].
    schedule : PathSchedule
    """

    launch: int
    nodes: tuple[int, ...]
    debris: tuple[int, ...]
    dv_mps: float
    lower_mps: float
    schedule: PathSchedule

    @property
    def key(self) -> tuple:
        return (self.launch, self.nodes)


@dataclass(frozen=True)
class Pricing:
    """What one pricing proved and found.

    Attributes
    ----------
    launch : int
    columns : tuple of Column
        Every path certified on the way that flies, cheapest first (by ΔV and prices).
    lower_mps : float
        No mission of this launch costs less under the prices (ΔV plus the prices of
        its debris) [m/s]; ``inf``: none flies.
    upper_mps : float
        The cheapest found, under the prices [m/s].
    status : str
        The search's (``optimal``, ``feasible``, ``infeasible``, ``no_plan``).
    seconds : float
    notes : tuple of str
    complete : bool
        The search ended by its own criterion, not a limit (an enumeration is whole).
    """

    launch: int
    columns: tuple[Column, ...]
    lower_mps: float
    upper_mps: float
    status: str
    seconds: float
    notes: tuple[str, ...] = ()
    complete: bool = True


def price(launch: Launch, prices=None, *, solver: SolverOptions | None = None,
          tol_mps: float = 0.01, gap_rel: float = 0.0, path_tol_rel: float = 0.0,
          stop_above_mps: float = np.inf,
          ceiling_mps: float = -np.inf,
          time_limit_s: float | None = None, exclude=(), must_visit=(), seeds=(),
          known=None, stop=None, sent_at: float | None = None,
          least_s: float = 0.0, deadline_at: float | None = None) -> Pricing:  # fmt: skip
    """The cheapest missions of ``launch`` with ``prices`` added to the debris' costs.

    Parameters
    ----------
    launch : Launch
    prices : array_like, optional
        Price of removing each catalog row [m/s] (default none); may be negative.
    solver : SolverOptions
        Backend of the search's relaxation MILPs.
    tol_mps, gap_rel : float
        Gap the search closes: ``max(tol_mps, gap_rel * plan)`` [m/s, -] (prices can make
        the plan's value any number: the relative gap is for pricing without prices).
    path_tol_rel : float
        Relative tolerance of each path's schedule (its transfers) [-]; 0.01 m/s at
        least.
    stop_above_mps : float
        Stop once no mission can cost less than this under the prices [m/s] (the
        launch's dual: no column of negative reduced cost is left).
    ceiling_mps : float
        Enumerate every path whose lower bound under the prices is below this [m/s].
    time_limit_s : float, optional
    sent_at : float, optional
        ``time.time()`` when the task was handed out: the time it waited for a worker
        counts against ``time_limit_s`` (a queue of 5 launches on 2 workers overran a
        15 s campaign by 4 s), down to ``least_s`` [s].
    deadline_at : float, optional
        ``time.time()`` of the campaign's own deadline: the limit never runs past it, a
        share ``least_s`` included, and a pricing that starts after it returns at once
        without a plan (the shares of 27 pricings on 2 workers, each a little over its
        own, ran a 60 s campaign to 70 s).
    exclude, must_visit : sequence of int
        Catalog rows this pricing must leave out / must remove (the greedy campaign).
    seeds : sequence of tuple of int
        Paths (node positions) tried first as incumbents.
    known : dict, optional
        Schedules of this launch's paths certified before (``{nodes: PathSchedule}``):
        not solved again (see ``certify``).
    stop : callable, optional
        Asked between the search's steps: True ends it as a time limit would.

    Returns
    -------
    Pricing
    """
    restore_malloc()  # a Dask worker's malloc thresholds make it 2-3 times slower
    clock = time.perf_counter()
    if time_limit_s is not None and sent_at is not None:  # time spent waiting counts
        time_limit_s = max(time_limit_s - (time.time() - sent_at), least_s, 0.0)
    if deadline_at is not None:
        time_limit_s = min(np.inf if time_limit_s is None else time_limit_s,
                           deadline_at - time.time())  # fmt: skip
        if time_limit_s <= 0.0:
            return Pricing(launch.index, (), -np.inf, np.inf, "no_plan", 0.0,
                           ("the time limit came before this pricing started",),
                           complete=False)  # fmt: skip
    mission = launch.mission
    nodes = MissionNodes.of(launch.catalog, mission)
    orbits = node_orbits(nodes.catalog, mission)
    a_low, a_high = drift_radius_bounds(mission)
    operations = np.asarray(nodes.cost_mps, dtype=float)
    extra = np.zeros(len(operations))
    if prices is not None:
        extra[: len(launch.catalog)] = np.asarray(prices, dtype=float)
    base = certified_nodes(nodes, mission)
    search_nodes = replace(
        base, cost_mps=operations + extra,
        excluded=tuple(sorted(set(base.excluded) | {int(k) for k in exclude})),
        must_visit=tuple(sorted(set(base.must_visit) | {int(k) for k in must_visit})))  # fmt: skip
    result = certify(orbits, search_nodes, a_low, a_high, solver=solver, gap_rel=gap_rel,
                     gap_abs_mps=tol_mps, time_limit_s=time_limit_s, seeds=seeds,
                     stop_above_mps=stop_above_mps, ceiling_mps=ceiling_mps,
                     names=nodes.catalog.ids, known=known,
                     path_tol_rel=max(path_tol_rel, gap_rel / 2), stop=stop)  # fmt: skip
    debris_rows = len(launch.catalog)
    columns = tuple(
        Column(launch.index, c.path, tuple(sorted(k for k in c.path if k < debris_rows)),
               float(c.schedule.upper_mps + operations[list(c.path)].sum()),
               float(c.schedule.lower_mps + operations[list(c.path)].sum()), c.schedule)
        for c in result.paths
    )  # fmt: skip
    return Pricing(launch.index, columns, float(result.lower_mps), float(result.upper_mps),
                   result.status, time.perf_counter() - clock, result.notes,
                   result.complete)  # fmt: skip


def mission_solution(launch: Launch, column: Column, status, backend: str):
    """The :class:`~sdc_cvx.solution.Solution` of one chosen mission of a campaign (its
    status is the campaign's; its lower bound bounds this path's schedules)."""
    nodes = MissionNodes.of(launch.catalog, launch.mission)
    orbits = node_orbits(nodes.catalog, launch.mission)
    note = (f"mission {launch.index + 1} of a campaign, launched on day {launch.day:g}: its "
            "status is the campaign's; lower_bound_mps bounds this path's schedules")  # fmt: skip
    return solution_of(nodes, launch.mission, orbits, column.nodes, column.schedule,
                       status=status, lower_bound_mps=column.lower_mps, backend=backend,
                       notes=(note,), model_size={"launch_day": launch.day},
                       timings={})  # fmt: skip


def best_of_counts(results: list[Pricing]) -> Pricing:
    """One launch's variants priced alone, as one pricing: every column, cheapest first;
    infeasible only if every count is; no plan if none has one."""
    columns = tuple(sorted((c for r in results for c in r.columns), key=lambda c: c.dv_mps))
    statuses = {r.status for r in results}
    status = ("infeasible" if statuses == {"infeasible"} else "no_plan" if not columns
              else "optimal" if statuses <= {"optimal", "infeasible"} else "feasible")
    return Pricing(results[0].launch, columns, min(r.lower_mps for r in results),
                   min(r.upper_mps for r in results), status,
                   max(r.seconds for r in results),
                   tuple(note for r in results for note in r.notes),
                   all(r.complete for r in results))  # fmt: skip


def infeasible_launch(launch: Launch, campaign) -> str:
    """Why ``launch`` makes its campaign infeasible (every count of it proven so)."""
    mission = launch.mission
    count = campaign.counts_text().split(", ")[launch.index]
    return (
        f"{launch.label()}: proven that no mission of n = {count} debris ends within "
        f"T_max = {mission.tmax_days:g} days from that day (certified search over every "
        "ordered pair of debris), so no campaign does. Relax one of: a longer mission "
        "(tmax_days), fewer debris (n), a wider drift altitude band "
        f"{mission.drift_altitude_km}, another launch day"
    )


def renumbered(column: Column, rows: list[int], sub: int, full: int,
               launches: list[int] | None = None) -> Column:  # fmt: skip
    """``column`` of a search over a sub-catalog and some launches, as a column of the
    whole: its row r is ``rows[r]`` of the catalog (a node past the sub-catalog's rows,
    the injection orbit, is as far past the catalog's), its launch k is ``launches[k]``
    (default: the same)."""
    def row(node: int) -> int:
        return rows[node] if node < sub else full + node - sub

    launch = column.launch if launches is None else launches[column.launch]
    return replace(column, launch=launch, nodes=tuple(row(k) for k in column.nodes),
                   debris=tuple(sorted(rows[k] for k in column.debris)))
