"""``solve``: plan a mission by the certified search (default) or the paper's method.

``SolverOptions.method`` chooses:

- ``"certified"``: :func:`~sdc_cvx.planner.certified.certify` brackets the optimum
  between a proven lower bound and the best plan, refined until they are within
  ``SolverOptions.gap`` (``docs/design.md`` §9); the answer carries its bound and gap;
- ``"paper"``: the sequential linearisation of Part IV-C
  (:func:`~sdc_cvx.planner.paper.solve`), a local method without a bound.

References
----------
.. [1] M. Cerf, "Multiple Space Debris Collecting Mission — Debris Selection and Trajectory
   Optimization", Journal of Optimization Theory and Applications 156(3), 761–796, 2013.
   doi:10.1007/s10957-012-0130-6
"""

from __future__ import annotations

import dataclasses
import time
import warnings
from collections.abc import Callable
from typing import TYPE_CHECKING

import numpy as np

from ..errors import IgnoredOptionWarning, MissionError, MissionInfeasible, SolverFailure
from ..inputs.catalog import Catalog
from ..inputs.mission import MAX_TMAX_DAYS, Mission
from ..milp.types import SolverOptions
from ..network.edges import drift_radius_bounds, node_eccentricities, node_orbits
from ..solution import OPTIMAL_GAP_MPS, OPTIMAL_GAP_REL, IterationRecord, RunStatus, Solution
from .certified import CertifiedNodes, CertifiedResult, certify
from .fixed_path import PathSchedule, schedule_plan
from .nodes import MissionNodes, make_legs, with_vehicle
from .size_guard import size_problem

if TYPE_CHECKING:  # the paper's room (and CVXPY) is imported only when its method runs
    from .paper import SequentialSettings


def solve(catalog: Catalog | None = None, mission: Mission | None = None, *,
          solver: SolverOptions | None = None, settings: SequentialSettings | None = None,
          progress: Callable[[IterationRecord], None] | None = None,
          log: Callable[[str], None] | None = None,
          stop: Callable[[], bool] | None = None) -> Solution:  # fmt: skip
    """Plan the mission: select, order and transfer between n of the catalog's debris.

    Parameters
    ----------
    catalog : Catalog, optional
        Candidate debris; default the paper's Table 5.
    mission : Mission, optional
        Mission parameters; default the paper's case (n = 5, T_max = 365.25 days).
    solver : SolverOptions, optional
        Method (``"certified"`` by default, or ``"paper"``), its gap and time limit, and
        the MILP backend with its settings; default HiGHS.
    settings : SequentialSettings, optional
        Settings of the paper's method (``method="paper"`` only).
    progress : callable, optional
        Called with each :class:`IterationRecord` as soon as it is known.
    log : callable, optional
        Called with one line of text per step of the certified search as it starts or
        ends (seeding plans, each refinement of the date cells, each relaxation MILP and
        its bound), so that a long run never goes silent.
    stop : callable, optional
        Certified search: asked between steps; True ends the search with the best plan so
        far and its gap, status ``feasible`` (the command line's Ctrl-C).

    Returns
    -------
    Solution
        With ``method="certified"``: ``status`` ``optimal`` (within the gap) or
        ``feasible`` (a time limit stopped the search), and ``lower_bound_mps``.

    Raises
    ------
    MissionError
        The catalog is too large for this machine's memory (the message gives the
        figures and the filters that narrow it: :mod:`~sdc_cvx.planner.size_guard`).
    MissionInfeasible
        No path meets the constraints (proven, with the certified method).
    SolverFailure
        The backend failed, or a limit stopped the search before any plan.
    """
    _check_types(catalog, mission, solver)
    solver = SolverOptions() if solver is None else solver
    ignored = ignored_options(mission, solver)
    for message in ignored:
        warnings.warn(message, IgnoredOptionWarning, stacklevel=2)
    if catalog is not None and (problem := size_problem(len(catalog))) is not None:
        raise MissionError(problem)  # before anything is built
    said = list(ignored)
    catalog = Catalog.paper_case() if catalog is None else catalog
    mission = (Mission() if mission is None else mission).for_catalog(catalog)
    if solver.method == "paper":
        from . import paper

        if mission.eccentricity == "on" and log is not None:  # the paper's circular legs
            log("the paper's method plans the paper's circular legs: the eccentricity of "
                "each leg is not priced (the certified search's is)")  # fmt: skip
        solution = paper.solve(catalog, mission.replace(eccentricity="off"), solver=solver,
                               settings=settings, progress=progress)  # fmt: skip
        return dataclasses.replace(solution, notes=(*solution.notes, *said))
    if log is not None:  # what the legs price, said once
        log(eccentricity_note(mission, catalog))
    mission.check_candidates(catalog)
    wall = time.perf_counter()
    nodes = MissionNodes.of(catalog, mission)
    catalog = nodes.catalog
    orbits = node_orbits(catalog, mission)
    a_low, a_high = drift_radius_bounds(mission)
    records: list[IterationRecord] = []
    ids = catalog.ids

    def on_iteration(row: dict) -> None:
        record = _record(row, ids, len(records))
        records.append(record)
        if progress is not None:
            progress(record)

    result = certify(orbits, certified_nodes(nodes, mission), a_low, a_high, solver=solver,
                     gap_rel=solver.gap, time_limit_s=solver.time_limit_s,
                     on_iteration=on_iteration, progress=log, names=ids, stop=stop,
                     fallback=True)  # fmt: skip
    if result.status == "infeasible":
        raise MissionInfeasible(_infeasible_message(mission))
    if result.status == "no_plan":
        bound = (f"; no plan costs less than {result.lower_mps:.2f} m/s"
                 if np.isfinite(result.lower_mps) and result.lower_mps > 0 else "")  # fmt: skip
        raise SolverFailure(
            f"the search stopped before finding any plan ({'; '.join(result.notes)}){bound}: "
            "allow more time (--time-limit, solver.time_limit_s)"
        )
    solution = _solution(result, nodes, mission, solver, orbits, records, wall)
    return dataclasses.replace(solution, notes=(*solution.notes, *said))


def ignored_options(mission: Mission | None, solver: SolverOptions) -> list[str]:
    """The options set away from their defaults that ``solver.method`` does not use."""
    out = []
    if (solver.method == "certified" and mission is not None
            and mission.dv_max_mps != Mission().dv_max_mps):  # fmt: skip
        out.append(
            f"mission.dv_max_mps = {mission.dv_max_mps:g} is ignored: it filters the edge "
            "table of the paper's method (method = 'paper'); the certified search prices "
            "every transfer"
        )
    if solver.method == "paper" and solver.gap != SolverOptions().gap:
        out.append(
            f"solver.gap = {solver.gap:g} is ignored: it is the stopping gap of the certified "
            "search (method = 'certified'); the paper's method proves no bound"
        )
    return out


def _check_types(catalog, mission, solver) -> None:
    """A clear :class:`TypeError` for an argument of the wrong kind (a path, a dict)."""
    import os

    if catalog is not None and not isinstance(catalog, Catalog):
        hint = ""
        if isinstance(catalog, str | os.PathLike):
            path = os.fspath(catalog)
            hint = (f": read the file first, e.g. solve(sdc_cvx.read_catalog({path!r}), "
                    "mission) (CSV, TLE, OMM or GTOC9, told from the content)")  # fmt: skip
        raise TypeError(f"solve: catalog must be a Catalog, got {type(catalog).__name__} "
                        f"{catalog!r:.80}{hint}")  # fmt: skip
    for name, value, kind in (("mission", mission, Mission), ("solver", solver, SolverOptions)):
        if value is not None and not isinstance(value, kind):
            hint = f": e.g. {kind.__name__}(**{value!r:.60})" if isinstance(value, dict) else ""
            raise TypeError(f"solve: {name} must be a {kind.__name__}, got "
                            f"{type(value).__name__} {value!r:.80}{hint}")  # fmt: skip


def _infeasible_message(mission: Mission) -> str:
    """Why no plan exists, with the requests that narrowed the search."""
    requests = mission.requests()
    asked = f" with {'; '.join(requests)}" if requests else ""
    relax = ["those requests"] if requests else []
    if mission.tmax_days < MAX_TMAX_DAYS:
        relax.append("a longer mission (tmax_days)")
    relax += [f"a wider drift altitude band {mission.drift_altitude_km}", "fewer debris (n)"]
    if mission.transfer != "impulsive":
        relax.append("more thrust (vehicle accel_mps2 or thrust_n: the spirals take time)")
    if mission.deorbit_days > 0:
        relax.append("shorter operations (deorbit_days)")
    return (
        f"proven: no path of n = {mission.n} debris ends within T_max = "
        f"{mission.tmax_days:g} days{asked} (certified search over every ordered pair of "
        f"debris). Relax one of: {', '.join(relax)}"
    )


def eccentricity_note(mission: Mission, catalog: Catalog) -> str:
    """What the plan's legs price, once: the eccentricity, or circular legs and why."""
    if mission.eccentricity == "on":
        return ("each leg prices the eccentricity it must change (the debris' mean "
                "eccentricity vectors turned by J2; issue 46)")  # fmt: skip
    if mission.transfer != "impulsive":
        return "the low-thrust legs join circular orbits: their eccentricity is not priced"
    why = ("it was turned off (eccentricity = \"off\")" if mission.eccentricity == "off"
           and "argp_deg" in catalog.frame.columns
           else "the catalog gives no argument of perigee")  # fmt: skip
    return f"the legs join circular orbits, the paper's model: {why}"


def certified_nodes(nodes: MissionNodes, mission: Mission) -> CertifiedNodes:
    """The mission as the certified search needs it (node positions into ``nodes``)."""
    return CertifiedNodes(
        legs=nodes.legs, ops_days=np.asarray(nodes.deorbit_days, dtype=float),
        cost_mps=np.asarray(nodes.cost_mps, dtype=float), first=nodes.first,
        must_visit=nodes.must_visit, excluded=nodes.excluded, tmax_days=mission.tmax_days,
        tmin_days=mission.shortest_leg_days, rule=mission.drift_inclination,
        j2=mission.j2, model=mission.transfer_model(),
        eccentricity=node_eccentricities(nodes.catalog, mission))  # fmt: skip


def _record(row: dict, ids, index: int) -> IterationRecord:
    """One iteration of the certified loop in the columns of the iteration table."""
    relaxation = "-".join(ids[k] for k in row["path"]) or "none"
    return IterationRecord(
        iteration=index, path=tuple(ids[k] for k in row.get("plan_path", ())),
        dv_linearized_mps=_finite(row["relaxation_mps"]), dv_true_mps=_finite(row["upper_mps"]),
        duration_true_days=None, nodes=row["nodes"], seconds=row["seconds"],
        solve_seconds=row["solve_seconds"], cvxpy_seconds=row["cvxpy_seconds"], alpha_km=None,
        status="bound", elapsed_s=row.get("elapsed"),
        note=f"lower bound {row['lower_mps']:.2f} m/s, best plan {row['upper_mps']:.2f} m/s "
             f"(path), relaxation's path {relaxation}, {row['arcs']} arcs over "
             f"{row['cells']} date cells")  # fmt: skip


def _finite(value):
    return float(value) if value is not None and np.isfinite(value) else None


def _solution(result: CertifiedResult, nodes: MissionNodes, mission: Mission,
              solver: SolverOptions, orbits, records, wall) -> Solution:  # fmt: skip
    return solution_of(
        nodes, mission, orbits, result.path, result.schedule,
        status=RunStatus.OPTIMAL if result.status == "optimal" else RunStatus.FEASIBLE,
        lower_bound_mps=result.lower_mps, gap_requested=solver.gap,
        search_trace=tuple((float(t), _finite(b), _finite(u)) for t, b, u in result.trace),
        backend="+".join(sorted({r["backend"] for r in result.log})) or solver.backend,
        records=records, notes=result.notes,
        model_size={
            "milp_solves": result.milp_solves,
            "date_cells": result.cells,
            "edges": result.edges,
            "paths_certified": result.paths_certified,
        },
        timings={"total_s": time.perf_counter() - wall, "search_s": result.seconds},
    )  # fmt: skip


def solution_of(nodes: MissionNodes, mission: Mission, orbits, path, schedule: PathSchedule, *,
                status: RunStatus, lower_bound_mps: float, backend: str, records=(),
                notes=(), model_size=None, timings=None, gap_requested: float | None = None,
                search_trace=()) -> Solution:  # fmt: skip
    """The :class:`Solution` of a certified path's schedule, flown in the true model.

    Parameters
    ----------
    nodes : MissionNodes
        The mission's nodes (its catalog: RAANs at the mission's own day 0).
    mission : Mission
    orbits : NodeOrbits
        ``node_orbits(nodes.catalog, mission)``.
    path : sequence of int
        Node positions.
    schedule : PathSchedule
        A feasible schedule of ``path`` (:func:`~sdc_cvx.planner.fixed_path.solve_path`).
    status : RunStatus
        ``optimal`` becomes ``within_gap`` when the gap is wider than what is called
        optimal (``OPTIMAL_GAP_REL``, ``OPTIMAL_GAP_MPS``).
    lower_bound_mps : float
        Proven bound of the mission [m/s] (capped at the plan's total).
    backend : str
    records, notes, model_size, timings, gap_requested, search_trace
        As in :class:`Solution`.

    Returns
    -------
    Solution
    """
    path = [int(k) for k in path]
    plan, plan_notes = schedule_plan(orbits, path, schedule, deorbit_days=nodes.deorbit_days,
                                     tmax_days=mission.tmax_days, j2=mission.j2,
                                     model=mission.transfer_model(),
                                     eccentricity=node_eccentricities(nodes.catalog,
                                                                      mission))  # fmt: skip
    ids = nodes.catalog.ids
    total = float(plan.dv_mps.sum() + nodes.cost_mps[path].sum())
    lower = float(min(lower_bound_mps, total))
    # no finer than the model's box bounds resolve a mission (low thrust: mm/s a leg)
    resolution = 2.0 * (len(path) - 1) * mission.transfer_model().bound_tol_mps
    optimal_gap = max(OPTIMAL_GAP_REL * total, OPTIMAL_GAP_MPS, resolution) * (1 + 1e-9)
    if status == RunStatus.OPTIMAL and total - lower > optimal_gap:
        status = RunStatus.WITHIN_GAP  # the gap asked for, wider than what is called optimal
    if status == RunStatus.OPTIMAL and total - lower > max(OPTIMAL_GAP_REL * total,
                                                           OPTIMAL_GAP_MPS) * (1 + 1e-9):
        notes = (*notes, f"optimal to the model's resolution: its bounds resolve about "
                         f"{resolution:.3f} m/s over the {len(path) - 1} legs, more than "
                         f"{100 * OPTIMAL_GAP_REL:g} % of this plan")  # fmt: skip
    legs = make_legs(ids, path, schedule.a_drift, schedule.inc_drift, schedule.side, plan,
                     orbits=orbits, mission=mission, laps=schedule.laps)  # fmt: skip
    legs, vehicle, status, vehicle_notes = with_vehicle(legs, nodes, path, mission, status)
    return Solution(
        path=tuple(ids[k] for k in path),
        legs=legs,
        total_dv_mps=total,
        total_duration_days=float(plan.end_day),
        status=status,
        backend=backend,
        mission=mission,
        iterations=tuple(records),
        operations=nodes.operations(path, mission),
        catalog=nodes.catalog,
        model_size=dict(model_size or {}),
        timings=dict(timings or {}),
        notes=(*plan_notes, *notes, *vehicle_notes),  # the plan's, the search's, the vehicle's
        method="certified",
        lower_bound_mps=lower,
        gap_requested=gap_requested,
        vehicle=vehicle,
        search_trace=tuple(search_trace),
    )
