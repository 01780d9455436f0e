"""Sequential linearisation to convergence (paper Part IV-C, Table 7), then re-optimisation.

Every kept edge may be replicated over departure-date windows
(:func:`~sdc_cvx.network.edges.preoptimize_windows`, :func:`default_date_windows`), each copy
with its own reference, so the MILP chooses an edge together with when it is flown.
Iteration k linearises every
copy around its reference (drift radius, departure date) within trust intervals,
solves the MILP, evaluates the chosen path with the true model, and moves the chosen
copies' references to the solution.  Phase 1 keeps the intervals wide while the path
changes; phase 2 halves the chosen copies' intervals once it is stable, until the
true ΔV stops moving; a new path restores them.  A step whose true plan breaks T_max
is rejected.  Before the first MILP a few cheap paths are re-optimised in the true
model and the best is held; every plan that meets the constraints in the true model
bounds the answer, edges on no path that could beat it (:mod:`~sdc_cvx.network.dominance`)
leave the MILP, and each MILP starts from the held plan.  Once
stable, each leg's side and inclination are checked against the
cheapest alternative at its date and time (plus the mission's slack), the fixed path
is re-optimised in the true model (Part IV-D), and one more MILP around that point
confirms the path or resumes from another.  The cheapest re-optimised plan that ends
by T_max is the answer.

Equation, table and part numbers are those of Cerf's paper [1]_; the design
rationale is in ``docs/design.md``.

References
----------
.. [1] M. Cerf, "Multiple Space Debris Collecting Mission — Debris Selection and Trajectory
   Optimization", Journal of Optimization Theory and Applications 156(3), 761–796, 2013.
   doi:10.1007/s10957-012-0130-6
"""

from __future__ import annotations

import time
from collections.abc import Callable
from dataclasses import replace

import numpy as np
import pandas as pd

from ...errors import MissionInfeasible, SolverFailure
from ...inputs.catalog import Catalog
from ...inputs.mission import Mission
from ...milp.solve import chain_of, solve_with_fallback
from ...milp.types import SolveReport, SolverOptions, Status
from ...network.dominance import path_cost_floor, transfer_dv_floor
from ...network.edges import drift_radius_bounds, node_orbits, preoptimize, preoptimize_windows
from ...solution import IterationRecord, RunStatus, Solution
from ..nodes import MissionNodes, make_legs, with_vehicle
from .decisions import Action, Outcome, Phase, decide
from .incumbents import Incumbents, IncumbentSteps
from .linearize import EdgeGeometry, TrustRegion, linearize
from .model import ModelSize, PathModel
from .run_log import LogSteps, RunLog
from .settings import SequentialSettings, default_date_windows
from .true_model import TrueModelSteps
from .trust import TrustState, TrustSteps


def edge_geometry(edges: pd.DataFrame, catalog: Catalog, mission: Mission) -> EdgeGeometry:
    """Fixed data of the edges in ``edges`` (rows with ``i, j, side, drift_inc_deg``)."""
    orbits = node_orbits(catalog, mission)
    a_low, a_high = drift_radius_bounds(mission)
    return EdgeGeometry(
        origin=orbits.take(edges["i"].to_numpy()),
        target=orbits.take(edges["j"].to_numpy()),
        side=edges["side"].to_numpy(dtype=float),
        inc_drift=np.deg2rad(edges["drift_inc_deg"].to_numpy(dtype=float)),
        a_low=a_low,
        a_high=a_high,
        j2=mission.j2,
        model=mission.transfer_model(),
    )


def read_path(model: PathModel, n: int) -> tuple[list[int], list[int]]:
    """Debris positions in visiting order and the edge index of each leg, from the MILP values."""
    chosen = np.flatnonzero(model.s.value > 0.5)
    successor = {int(model.edges_from[e]): (int(model.edges_to[e]), int(e)) for e in chosen}
    starts = set(successor) - {int(model.edges_to[e]) for e in chosen}
    if len(chosen) != n - 1 or len(starts) != 1:
        raise SolverFailure(f"MILP returned {len(chosen)} edges with starts {sorted(starts)}")
    node, path, legs = starts.pop(), [], []
    path.append(node)
    while node in successor:
        node, edge = successor[node]
        path.append(node)
        legs.append(edge)
    if len(path) != n:  # a disjoint cycle: the ordering rows must prevent it
        raise SolverFailure(f"MILP solution is not one path: {path} from edges {chosen.tolist()}")
    return path, legs


class _Driver(IncumbentSteps, TrustSteps, TrueModelSteps, LogSteps):
    """One sequential solve (kept private: :func:`solve` is the API).

    It holds the problem as built (nodes, edge copies, geometry, dominance floor, the
    CVXPY model: set up in ``__init__``), the :class:`TrustState` (``trust``), the
    :class:`Incumbents` (``held``) and the :class:`RunLog` (``log``); :meth:`run`
    dispatches on :func:`~sdc_cvx.planner.paper.decisions.decide`.  Its other steps come
    by phase from :class:`~sdc_cvx.planner.paper.incumbents.IncumbentSteps` (the seeding and
    the plans held), :class:`~sdc_cvx.planner.paper.trust.TrustSteps` (references and
    intervals), :class:`~sdc_cvx.planner.paper.true_model.TrueModelSteps` (evaluation and
    re-optimisation) and :class:`~sdc_cvx.planner.paper.run_log.LogSteps` (the record).
    """

    def __init__(self, nodes: MissionNodes, mission, solver, settings, progress):
        catalog = nodes.catalog
        self.nodes = nodes
        self.catalog, self.mission, self.solver, self.settings = catalog, mission, solver, settings
        self.progress = progress or (lambda record: None)
        self.chain = chain_of(solver)
        self.log = RunLog()
        self.held = Incumbents()
        first_ops = (
            nodes.deorbit_days.min() if nodes.first is None else nodes.deorbit_days[nodes.first]
        )
        self.depart_range = (float(first_ops), mission.tmax_days - nodes.deorbit_days.min())
        self.kept = self.edge_copies()
        self.build()

    def edge_copies(self) -> pd.DataFrame:
        """The edge copies: every kept edge over its departure-date windows (Part IV-B)."""
        nodes, catalog, mission, settings = self.nodes, self.catalog, self.mission, self.settings
        start = time.perf_counter()
        # the first transfer leaves after the operations at the first debris
        self.table = preoptimize(catalog, mission, departure_day=self.depart_range[0])
        # Reference transfers take 2/3 of a leg's fair share of the mission (the paper's
        # T0 = 2 months for 4 legs in a year, Part IV-B), or T0 if shorter: references
        # that each use the whole mission would make the first MILP infeasible.
        share = (
            mission.tmax_days - nodes.deorbit_days.sum() / len(catalog) * mission.n
        ) / nodes.legs
        windows = settings.date_windows or default_date_windows(
            catalog, mission, self.table.counts()["kept"], nodes.legs
        )
        bounds = np.linspace(*self.depart_range, windows + 1)
        kept = preoptimize_windows(
            catalog, mission, bounds, reference_days=2 / 3 * share,
            reference_at=(0.0,) if windows == 1 else (0.0, 0.5),
        )  # fmt: skip
        self.log.timings["preoptimize_s"] = time.perf_counter() - start
        # excluded debris lose their edges; nothing returns to the injection orbit
        barred = np.array(nodes.excluded + ((nodes.first,) if mission.injection else ()), int)
        touches = kept["i"].isin(nodes.excluded) | kept["j"].isin(barred)
        kept = kept[~touches].reset_index(drop=True)
        if kept[["i", "j"]].drop_duplicates().shape[0] < nodes.legs:
            raise MissionInfeasible(_relax_message(mission, self.table.summary()))
        return kept

    def build(self):
        """The geometry, dominance floor, CVXPY model and trust state of the edge copies."""
        nodes, catalog, mission, settings = self.nodes, self.catalog, self.mission, self.settings
        self.orbits = node_orbits(catalog, mission)
        self.geometry = edge_geometry(self.kept, catalog, mission)
        g = self.geometry
        edge_floor = transfer_dv_floor(g.origin, g.target, g.a_low, g.a_high, model=g.model)
        self.floor = path_cost_floor(self.kept["i"], self.kept["j"], edge_floor, nodes.cost_mps,
                                     nodes.legs, first=nodes.first)  # fmt: skip
        start = time.perf_counter()
        self.model = PathModel(
            len(catalog), self.kept["i"].to_numpy(), self.kept["j"].to_numpy(),
            n=nodes.legs + 1, tmax_days=mission.tmax_days, deorbit_days=nodes.deorbit_days,
            min_transfer_days=mission.shortest_leg_days, operations_dv_mps=nodes.cost_mps,
            first=nodes.first, must_visit=nodes.must_visit,
            duration_model=settings.duration_model,
        )  # fmt: skip
        self.log.timings["build_s"] = time.perf_counter() - start
        m = len(self.kept)
        alpha0 = settings.alpha_km
        tau0 = settings.tau_days if settings.tau_days is not None else mission.tmax_days
        self.trust = TrustState(
            region=TrustRegion(
                a_ref=self.kept["drift_a_km"].to_numpy(dtype=float) * 1e3,
                t_ref=self.kept["departure_day"].to_numpy(dtype=float),
                alpha_km=np.full(m, alpha0),
                tau_days=np.full(m, tau0),
            ),
            alpha0=alpha0,
            tau0=tau0,
            windows=(self.kept["window_lo"].to_numpy(), self.kept["window_hi"].to_numpy()),
        )

    # -- one iteration -------------------------------------------------------------------
    def iterate(self, note=""):
        k = len(self.log.history)
        start = time.perf_counter()
        coefficients = linearize(self.geometry, self.trust.region, tmax_days=self.mission.tmax_days,
                                 depart_range=self.trust.windows)  # fmt: skip
        coefficients = replace(coefficients, available=coefficients.available & self.undominated())
        warm = self.start_from_held(coefficients) or k > 0
        self.model.update(coefficients)
        report = solve_with_fallback(self.model.problem, self.chain, warm_start=warm)
        self.log.backends_used.add(report.backend)
        if report.fallbacks:
            switched = "; ".join(report.fallbacks)
            note = (note + "; " if note else "") + switched
            if switched != self.log.last_switch:  # once per change, not once per iteration
                self.log.notes.append(f"from iteration {k}: {switched}")
            self.log.last_switch = switched
        if k == 0:
            self.log.timings["first_solve_overhead_s"] = report.overhead_seconds
        if not report.status.has_solution:
            return self._no_solution(report, start)
        path, legs = read_path(self.model, self.nodes.legs + 1)
        alpha_km = np.asarray(self.model.p.value)[legs]
        a_legs = coefficients.a_ref[legs] + alpha_km * 1e3
        evaluation = self.evaluate(path, legs, a_legs)
        self.bound_by(path, legs, a_legs, evaluation)
        if report.status == Status.TIME_LIMIT:
            gap = "unknown" if report.mip_gap is None else f"{report.mip_gap:.2%}"
            note = (note + "; " if note else "") + f"time limit: incumbent used (gap {gap})"
            self.log.notes.append(f"iteration {len(self.log.history)}: {note}")
        self.record(report, path, legs, evaluation, start, note)
        if self.log.initial_legs is None:
            g = self.geometry
            self.log.initial_legs = make_legs(
                self.catalog.ids, path, a_legs, g.inc_drift[legs], g.side[legs], evaluation
            )
        return path, legs, a_legs, evaluation

    def start_from_held(self, coefficients) -> bool:
        """Solve the MILP restricted to the held plan's path, as the next solve's start.

        CVXPY warm-starts HiGHS (and the commercial backends) from the last solution, so
        the full MILP then starts with the held plan as its incumbent instead of
        searching for one.  Done every iteration: the last MILP's solution is not a start
        once the intervals have moved (measured at N = 123 with a 10 s limit: HiGHS
        then found no incumbent).  False if the linearised model does not admit the path.
        """
        plan = self.held.upper[1]
        if plan is None:
            return False
        only = np.zeros_like(coefficients.available)
        only[plan[1]] = coefficients.available[plan[1]]
        self.model.update(replace(coefficients, available=only))
        return solve_with_fallback(self.model.problem, self.chain).status.has_solution

    def _no_solution(self, report: SolveReport, start):
        if report.status == Status.NO_SOLUTION and self.held.upper[1] is not None:
            # the time limit struck before any MILP solution, but a plan is held: keep it
            self.held.stopped = True
            self.record(report, [], [], None, start, "time limit without a solution")
            self.log.notes.append(
                f"iteration {len(self.log.history) - 1}: {report.backend} reached its time limit "
                "without a solution; the cheapest plan held is returned (raise the time limit "
                "to let the iterations continue)"
            )
            return None
        if report.status in (Status.ERROR, Status.NO_SOLUTION, Status.UNBOUNDED):
            hint = " (raise the time limit)" if report.status == Status.NO_SOLUTION else ""
            raise SolverFailure(f"{report.backend}: {report.status.value}: {report.message}{hint}")
        if not any(record.path for record in self.log.history):
            # over-estimated durations (wide secants) can make a feasible mission look
            # infeasible: narrow the radius intervals a few times before concluding
            if self.trust.initial_retries == self.settings.initial_retries:
                raise MissionInfeasible(_relax_message(self.mission, self.table.summary()))
            self.trust.initial_retries += 1
            self.trust.region = replace(
                self.trust.region, alpha_km=self.trust.region.alpha_km * self.settings.shrink
            )
            self.record(report, [], [], None, start, "no path yet: radius intervals narrowed")
            return None
        # infeasible around the new references: the secants over-estimate too much; narrow them
        self.narrow(np.arange(len(self.kept)), dates=False)
        self.record(report, [], [], None, start, "infeasible linearisation: intervals narrowed")
        return None

    def run(self):
        """Iterate until the path is stable and the true ΔV stops moving, then re-optimise.

        After the re-optimisation (Part IV-D) one more MILP around the re-optimised
        point confirms the path: the linear iterations settle the discrete choice, the
        nonlinear step the continuous one.  If that MILP prefers another path, the
        iterations resume from it.  What to do after each iteration is
        :func:`~sdc_cvx.planner.paper.decisions.decide`'s rule; this loop carries it out.
        """
        self.seed()
        phase = Phase()
        last_path, last_dv = None, None
        while len(self.log.history) < self.settings.max_iterations:
            outcome = self.iterate(
                note="confirming the re-optimised point" if phase.confirming else ""
            )
            if self.repeats(outcome) >= self.settings.max_repeats:
                self.log.notes.append(
                    f"iterations {len(self.log.history) - self.settings.max_repeats - 1}-"
                    f"{len(self.log.history) - 1} gave the same solution: the steps changed "
                    "nothing, stopped"
                )
                return self.answer(RunStatus.STALLED)
            seen = self.observe(outcome, last_path, last_dv)
            action = decide(phase, seen, self.settings)
            if action is Action.TRY_FLIP:
                if self.flip_assumptions(*outcome):
                    phase = replace(phase, flips=phase.flips + 1)
                    last_path = None
                    continue
                no_rounds_left = replace(phase, flips=self.settings.max_assumption_rounds)
                action = decide(no_rounds_left, seen, self.settings)
            if action is Action.FINISH_TIME_LIMIT:
                return self.answer(RunStatus.TIME_LIMIT)
            if action is Action.ITERATE:
                continue
            path, legs, a_legs, evaluation = outcome
            dv_true = float(evaluation.dv_mps.sum())
            if action is Action.RETURN_TO_HELD:
                self.return_to_held()
            elif action is Action.REJECT_LATE:
                self.reject_late(legs, evaluation)
            elif action is Action.FINISH_CONVERGED:
                return self.answer(RunStatus.CONVERGED)
            elif action is Action.REOPTIMIZE_AND_FINISH:
                self.reoptimize(path, legs, a_legs)
                return self.answer(RunStatus.CONVERGED_UNCONFIRMED)
            elif action is Action.REOPTIMIZE_AND_CONFIRM:
                final = self.reoptimize(path, legs, a_legs)
                phase = replace(phase, confirming=True, confirmations=phase.confirmations + 1)
                self.move_references(path, legs, final.a_drift, final.evaluation, False)
                last_path, last_dv = path, dv_true
            else:  # MOVE, or LEAVE_CONFIRMATION and then move
                if action is Action.LEAVE_CONFIRMATION:
                    self.log.notes.append(
                        "the MILP around the re-optimised point chose another path"
                    )
                    phase = replace(phase, confirming=False)
                self.advance(path, legs, a_legs, evaluation, seen.changed)
                last_path, last_dv = path, dv_true
        if self.held.best is not None or self.held.upper[1] is not None:
            self.log.notes.append(f"iteration limit {self.settings.max_iterations} reached")
            return self.answer(RunStatus.ITERATION_LIMIT)
        raise SolverFailure(
            f"no converged path within {self.settings.max_iterations} iterations; raise "
            "max_iterations or loosen dv_tol_mps"
        )

    def repeats(self, outcome) -> int:
        """How many iterations in a row, before this one, gave this one's solution."""
        key = None
        if outcome is not None:
            path, legs, a_legs, evaluation = outcome
            key = (tuple(path), tuple(legs), tuple(np.round(a_legs, 3)),
                   round(float(evaluation.dv_mps.sum()), 6))  # fmt: skip
        self.trust.same_solution = (
            self.trust.same_solution + 1
            if key == self.trust.last_solution and key is not None
            else 0
        )
        self.trust.last_solution = key
        return self.trust.same_solution

    def observe(self, outcome, last_path, last_dv) -> Outcome:
        """What :func:`~sdc_cvx.planner.paper.decisions.decide` needs to know of an iteration."""
        if outcome is None:
            return Outcome(solved=False, stopped=self.held.stopped)
        path, legs, _, evaluation = outcome
        changed = path != last_path
        dv_true = float(evaluation.dv_mps.sum())
        return Outcome(
            worse_than_held=self.worse_than_held(path, evaluation),
            changed=changed,
            first=last_path is None,
            late=not self.fits(evaluation),
            stalled=not changed and abs(last_dv - dv_true) <= self.settings.dv_tol_mps,
            narrowest=bool(np.max(self.trust.region.alpha_km[legs]) <= self.settings.min_alpha_km),
        )


def solve(catalog: Catalog | None = None, mission: Mission | None = None, *,
          solver: SolverOptions | None = None, settings: SequentialSettings | None = None,
          progress: Callable[[IterationRecord], None] | None = None) -> Solution:  # fmt: skip
    """Plan the mission: select, order and transfer between n of the catalog's debris.

    Parameters
    ----------
    catalog : Catalog, optional
        Candidate debris; default the paper's Table 5.
    mission : Mission, optional
        Mission parameters; default the paper's case (n = 5, T_max = 365.25 days).
    solver : SolverOptions, optional
        MILP backend and its settings; default HiGHS.
    settings : SequentialSettings, optional
        Trust intervals and convergence settings.
    progress : callable, optional
        Called with each :class:`IterationRecord` as soon as it is known, and again
        (its ``rejected`` set to why) when the driver rejects that step.

    Returns
    -------
    Solution

    Raises
    ------
    MissionInfeasible
        No path meets the constraints; the message says what could be relaxed.
    SolverFailure
        The backend failed or hit its time limit without any solution.
    """
    catalog = Catalog.paper_case() if catalog is None else catalog
    mission = Mission() if mission is None else mission
    solver = SolverOptions() if solver is None else solver
    settings = SequentialSettings() if settings is None else settings
    mission.check_candidates(catalog)
    wall = time.perf_counter()
    nodes = MissionNodes.of(catalog, mission)
    catalog = nodes.catalog
    driver = _Driver(nodes, mission, solver, settings, progress)
    path, legs, final, status = driver.run()
    driver.log.timings["iterations_s"] = sum(r.seconds for r in driver.log.history)
    plan, drift = driver.global_schedule(path, final)
    driver.log.timings["total_s"] = time.perf_counter() - wall
    ids = catalog.ids
    legs_out = make_legs(ids, path, *drift, plan, orbits=driver.orbits, mission=mission)
    legs_out, vehicle, status, vehicle_notes = with_vehicle(legs_out, nodes, path, mission, status)
    size = driver.model.size()
    return Solution(
        path=tuple(ids[k] for k in path),
        legs=legs_out,
        initial_legs=driver.log.initial_legs or (),
        catalog=catalog,
        total_dv_mps=float(plan.dv_mps.sum() + nodes.cost_mps[path].sum()),
        operations=nodes.operations(path, mission),
        total_duration_days=plan.end_day,
        status=status,
        backend="+".join(sorted(driver.log.backends_used)) or solver.backend,
        mission=mission,
        iterations=tuple(driver.log.history),
        model_size={
            "edges_kept": len(driver.kept[["i", "j"]].drop_duplicates()),
            "edge_copies": len(driver.kept),
            "date_windows": int(driver.kept["window"].max()) + 1,
            "edges_total": len(driver.table.frame),
            "edges_dominated": int((~driver.undominated()).sum()),
            "binaries": size.binaries,
            "continuous": size.continuous,
            "constraints": size.constraints,
            "paper_unfiltered": vars(ModelSize.paper(len(catalog))),
        },
        timings=driver.log.timings,
        notes=(*driver.log.notes, *vehicle_notes),
        vehicle=vehicle,
    )


def _relax_message(mission: Mission, edges_summary: str) -> str:
    requests = mission.requests()
    asked = f" with {'; '.join(requests)}" if requests else ""
    return (
        f"no path of n = {mission.n} debris ends within T_max = {mission.tmax_days:g} days"
        f"{asked} in the linearised model over the kept edges ({edges_summary}). Relax one "
        f"of: {'those requests, ' if requests else ''}a longer mission (tmax_days), a longer "
        f"pre-optimisation bound (preopt_days = {mission.preopt_days:g}), a higher "
        f"dv_max_mps ({mission.dv_max_mps:g}), a wider drift altitude band "
        f"{mission.drift_altitude_km}, fewer debris (n), or shorter operations (deorbit_days)"
        + ("; with low thrust T0 bounds each leg's coast (the spirals and the plane change "
           "come on top): more thrust (vehicle accel_mps2 or thrust_n) shortens them, and the "
           "certified method (the default) does not use T0" if mission.transfer == "low-thrust"
           else "")
    )
