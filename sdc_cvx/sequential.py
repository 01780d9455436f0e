"""Sequential linearisation to convergence (paper Part IV-C, Table 7), then re-optimisation.

Iteration k linearises every kept edge around its reference (drift radius, departure
date) within trust intervals, solves the MILP, evaluates the chosen path with the true
model, and moves the references of the chosen edges to the solution.  Phase 1 keeps
the intervals wide while the path changes; phase 2 halves them once it is stable
until the true ΔV stops moving; a path change restores them.  At the end each leg's
side and inclination are checked against the cheapest alternative at its date and
allotted time, and the iterations resume with the better assumption if one is found.
The fixed path is finally re-optimised in the true model (Part IV-D).
"""

from __future__ import annotations

import time
from collections.abc import Callable
from dataclasses import dataclass, replace

import numpy as np

from .backends import SolveReport, SolverOptions, Status, solve_milp
from .catalog import Catalog
from .edges import EdgeTable, drift_radius_bounds, node_orbits, preoptimize
from .linearize import EdgeGeometry, TrustRegion, linearize
from .mission import Mission
from .model import ModelSize, PathModel
from .orbits import R_EARTH, SECONDS_PER_DAY
from .reoptimize import reoptimize
from .solution import IterationRecord, Leg, PlanEvaluation, Solution, evaluate_plan
from .transfer import cheapest_transfer


class MissionInfeasible(RuntimeError):
    """No path meets the mission's constraints; the message says what could be relaxed."""


class SolverFailure(RuntimeError):
    """The MILP backend failed or stopped before finding any solution."""


@dataclass(frozen=True)
class SequentialSettings:
    """Settings of the sequential linearisation.

    Parameters
    ----------
    alpha_km : float
        Initial (and restored) half-width of the drift-radius trust interval [km].
    tau_days : float, optional
        Initial half-width of the departure-date trust interval [days]; default T_max.
    shrink : float
        Factor applied to both half-widths once the path is stable (paper: halve).
    min_alpha_km : float
        Narrowest radius half-width [km]; reaching it ends phase 2.
    dv_tol_mps : float
        Convergence when the path is unchanged and the true ΔV moved less than this.
    max_iterations : int
    max_assumption_rounds : int
        How many times the side/inclination check may resume the iterations.
    max_confirmations : int
        How many times a re-optimised point is confirmed by one more MILP.
    initial_retries : int
        How many times the first MILP is retried with halved radius intervals before
        the mission is declared infeasible.
    """

    alpha_km: float = 50.0
    tau_days: float | None = None
    shrink: float = 0.5
    min_alpha_km: float = 0.01
    dv_tol_mps: float = 0.05
    max_iterations: int = 40
    max_assumption_rounds: int = 2
    max_confirmations: int = 3
    initial_retries: int = 3


def edge_geometry(table: EdgeTable) -> EdgeGeometry:
    """Fixed data of the kept edges of ``table``: ends, pre-optimised side and inclination."""
    kept = table.kept
    orbits = node_orbits(table.catalog, table.mission)
    a_low, a_high = drift_radius_bounds(table.mission)
    return EdgeGeometry(
        origin=orbits.take(kept["i"].to_numpy()),
        target=orbits.take(kept["j"].to_numpy()),
        side=kept["side"].to_numpy(dtype=float),
        inc_drift=np.deg2rad(kept["drift_inc_deg"].to_numpy()),
        a_low=a_low,
        a_high=a_high,
        j2=table.mission.j2,
    )


def read_path(model: PathModel, n: int) -> tuple[list[int], list[int]]:
    """Debris positions in visiting order and the edge index of each leg, from the MILP values."""
    chosen = np.flatnonzero(model.s.value > 0.5)
    successor = {int(model.edges_from[e]): (int(model.edges_to[e]), int(e)) for e in chosen}
    starts = set(successor) - {int(model.edges_to[e]) for e in chosen}
    if len(chosen) != n - 1 or len(starts) != 1:
        raise RuntimeError(f"MILP returned {len(chosen)} edges with starts {sorted(starts)}")
    node, path, legs = starts.pop(), [], []
    path.append(node)
    while node in successor:
        node, edge = successor[node]
        path.append(node)
        legs.append(edge)
    if len(path) != n:  # a disjoint cycle: the ordering rows must prevent it
        raise RuntimeError(f"MILP solution is not one path: {path} from edges {chosen.tolist()}")
    return path, legs


class _Driver:
    """State of one sequential solve (kept private: :func:`solve` is the API)."""

    def __init__(self, catalog, mission, solver, settings, progress):
        self.catalog, self.mission, self.solver, self.settings = catalog, mission, solver, settings
        self.progress = progress or (lambda record: None)
        self.timings = {}
        start = time.perf_counter()
        # the first transfer leaves after the operations at the first debris
        self.table = preoptimize(catalog, mission, departure_day=mission.deorbit_days)
        self.timings["preoptimize_s"] = time.perf_counter() - start
        self.kept = self.table.kept
        if len(self.kept) < mission.n - 1:
            raise MissionInfeasible(_relax_message(mission, self.table.summary()))
        self.orbits = node_orbits(catalog, mission)
        self.geometry = edge_geometry(self.table)
        start = time.perf_counter()
        self.model = PathModel(
            len(catalog), self.kept["i"].to_numpy(), self.kept["j"].to_numpy(), n=mission.n,
            tmax_days=mission.tmax_days, deorbit_days=mission.deorbit_days,
            min_transfer_days=mission.min_transfer_days,
            operations_dv_mps=mission.operations_dv_mps,
        )  # fmt: skip
        self.timings["build_s"] = time.perf_counter() - start
        m = len(self.kept)
        self.alpha0 = settings.alpha_km
        self.tau0 = settings.tau_days if settings.tau_days is not None else mission.tmax_days
        self.region = TrustRegion(
            a_ref=self.kept["drift_a_km"].to_numpy() * 1e3,
            t_ref=self.kept["departure_day"].to_numpy(dtype=float),
            alpha_km=np.full(m, self.alpha0),
            tau_days=np.full(m, self.tau0),
        )
        self.depart_range = (mission.deorbit_days, mission.tmax_days - mission.deorbit_days)
        self.history: list[IterationRecord] = []
        self.initial_retries = 0
        self.notes: list[str] = []

    # -- one iteration -------------------------------------------------------------------
    def iterate(self, note=""):
        k = len(self.history)
        start = time.perf_counter()
        coefficients = linearize(self.geometry, self.region, tmax_days=self.mission.tmax_days,
                                 depart_range=self.depart_range)  # fmt: skip
        self.model.update(coefficients)
        report = solve_milp(self.model.problem, self.solver, warm_start=k > 0)
        if k == 0:
            self.timings["first_solve_overhead_s"] = report.overhead_seconds
        if not report.status.has_solution:
            return self._no_solution(report, start)
        path, legs = read_path(self.model, self.mission.n)
        alpha_km = np.asarray(self.model.p.value)[legs]
        a_legs = coefficients.a_ref[legs] + alpha_km * 1e3
        evaluation = self.evaluate(path, legs, a_legs)
        self.record(report, path, evaluation, start, note)
        return path, legs, a_legs, evaluation

    def evaluate(self, path, legs, a_legs) -> PlanEvaluation:
        return evaluate_plan(
            self.orbits, path, a_legs, self.geometry.inc_drift[legs],
            deorbit_days=self.mission.deorbit_days, j2=self.mission.j2,
        )  # fmt: skip

    def record(self, report: SolveReport, path, evaluation, start, note):
        ids = self.catalog.ids
        record = IterationRecord(
            iteration=len(self.history),
            path=tuple(ids[k] for k in path) if path else (),
            dv_linearized_mps=report.objective,
            dv_true_mps=float(evaluation.dv_mps.sum()) + self._operations() if path else None,
            duration_true_days=evaluation.end_day if path else None,
            nodes=report.nodes,
            seconds=time.perf_counter() - start,
            solve_seconds=report.solve_seconds,
            cvxpy_seconds=report.overhead_seconds,
            alpha_km=float(np.max(self.region.alpha_km)),
            status=report.status.value,
            note=note,
        )
        self.history.append(record)
        self.progress(record)

    def _operations(self):
        return self.mission.n * self.mission.operations_dv_mps

    def _no_solution(self, report: SolveReport, start):
        if report.status in (Status.ERROR, Status.NO_SOLUTION, Status.UNBOUNDED):
            hint = " (raise the time limit)" if report.status == Status.NO_SOLUTION else ""
            raise SolverFailure(f"{report.backend}: {report.status.value}: {report.message}{hint}")
        if not any(record.path for record in self.history):
            # over-estimated durations (wide secants) can make a feasible mission look
            # infeasible: narrow the radius intervals a few times before concluding
            if self.initial_retries == self.settings.initial_retries:
                raise MissionInfeasible(_relax_message(self.mission, self.table.summary()))
            self.initial_retries += 1
            self.region = replace(self.region, alpha_km=self.region.alpha_km * self.settings.shrink)
            self.record(report, [], None, start, "no path yet: radius intervals narrowed")
            return None
        # infeasible around the new references: the secants over-estimate too much; narrow them
        self.region = replace(
            self.region,
            alpha_km=self.region.alpha_km * self.settings.shrink,
            tau_days=self.region.tau_days * self.settings.shrink,
        )
        self.record(report, [], None, start, "infeasible linearisation: intervals narrowed")
        return None

    # -- references and intervals ----------------------------------------------------------
    def move_references(self, path, legs, a_legs, evaluation: PlanEvaluation, path_changed: bool):
        """Move the references to the solution and update the trust intervals.

        References of the chosen edges go to the solution's radii; every edge leaving a
        visited debris gets that debris' true departure date.  A new path restores the
        wide intervals (phase 1); a stable path halves them (phase 2, Part IV-C).
        """
        a_ref, t_ref = self.region.a_ref.copy(), self.region.t_ref.copy()
        a_ref[legs] = a_legs
        departure_from = dict(zip(path[:-1], evaluation.departure_day, strict=True))
        departure_from[path[-1]] = evaluation.end_day
        origins = self.kept["i"].to_numpy()
        for node, day in departure_from.items():
            t_ref[origins == node] = day
        if path_changed:
            alpha = np.full_like(a_ref, self.alpha0)
            tau = np.full_like(a_ref, self.tau0)
        else:
            alpha = np.maximum(
                self.region.alpha_km * self.settings.shrink, self.settings.min_alpha_km
            )
            tau = self.region.tau_days * self.settings.shrink
        self.region = TrustRegion(a_ref, t_ref, alpha, tau)

    def run(self):
        """Iterate until the path is stable and the true ΔV stops moving, then re-optimise.

        After the re-optimisation (Part IV-D) one more MILP around the re-optimised
        point confirms the path: the linear iterations settle the discrete choice, the
        nonlinear step the continuous one.  If that MILP prefers another path, the
        iterations resume from it.
        """
        last_path, last_dv = None, None
        pending = None  # re-optimised plan waiting for the confirming MILP
        flips = confirmations = 0
        while len(self.history) < self.settings.max_iterations:
            outcome = self.iterate(note="confirming the re-optimised point" if pending else "")
            if outcome is None:
                continue
            path, legs, a_legs, evaluation = outcome
            dv_true = float(evaluation.dv_mps.sum())
            changed = path != last_path
            if pending is not None:
                if not changed:
                    return path, legs, pending, "converged"
                self.notes.append("the MILP around the re-optimised point chose another path")
                pending = None
            elif not changed:
                stalled = abs(last_dv - dv_true) <= self.settings.dv_tol_mps
                narrowest = np.max(self.region.alpha_km[legs]) <= self.settings.min_alpha_km
                if (stalled or narrowest) and evaluation.end_day <= self.mission.tmax_days + 1e-6:
                    if flips < self.settings.max_assumption_rounds and self.flip_assumptions(
                        path, legs, a_legs, evaluation
                    ):
                        flips += 1
                        last_path = None
                        continue
                    final = self.reoptimize(path, legs, a_legs)
                    if confirmations == self.settings.max_confirmations:
                        return path, legs, final, "converged_unconfirmed"
                    confirmations += 1
                    self.move_references(path, legs, final.a_drift, final.evaluation, False)
                    pending, last_path, last_dv = final, path, dv_true
                    continue
            self.move_references(path, legs, a_legs, evaluation, changed)
            last_path, last_dv = path, dv_true
        raise SolverFailure(
            f"no converged path within {self.settings.max_iterations} iterations; raise "
            "max_iterations or loosen dv_tol_mps"
        )

    def reoptimize(self, path, legs, a_legs):
        start = time.perf_counter()
        geometry = self.geometry
        final = reoptimize(
            self.orbits, path, geometry.side[legs], geometry.inc_drift[legs], a_legs,
            tmax_days=self.mission.tmax_days, deorbit_days=self.mission.deorbit_days,
            a_low=geometry.a_low, a_high=geometry.a_high, j2=self.mission.j2,
        )  # fmt: skip
        self.timings["reoptimize_s"] = self.timings.get("reoptimize_s", 0.0) + (
            time.perf_counter() - start
        )
        self.notes.append(f"re-optimisation: {final.message}; {final.improved_by_mps:+.2f} m/s")
        return final

    def flip_assumptions(self, path, legs, a_legs, evaluation) -> bool:
        """Resume with another side/inclination for legs where one is clearly cheaper."""
        origins, targets = self.orbits.take(path[:-1]), self.orbits.take(path[1:])
        allotted = evaluation.duration_days * SECONDS_PER_DAY
        best = cheapest_transfer(
            origins, targets, evaluation.departure_day * SECONDS_PER_DAY, allotted,
            self.geometry.a_low, self.geometry.a_high, inclination="free", j2=self.mission.j2,
        )  # fmt: skip
        better = best.dv < evaluation.dv_mps - 0.5
        differs = (best.side != self.geometry.side[legs]) | ~np.isclose(
            best.inc_drift, self.geometry.inc_drift[legs]
        )
        flip = np.flatnonzero(better & differs)
        if flip.size == 0:
            return False
        side, inc = self.geometry.side.copy(), self.geometry.inc_drift.copy()
        a_ref = self.region.a_ref.copy()
        ids = self.catalog.ids
        for leg in flip:
            edge = legs[leg]
            side[edge], inc[edge], a_ref[edge] = (
                best.side[leg],
                best.inc_drift[leg],
                best.a_drift[leg],
            )
            self.notes.append(
                f"leg {ids[path[leg]]}->{ids[path[leg + 1]]}: resumed with "
                f"side {int(best.side[leg]):+d}, drift inclination "
                f"{np.rad2deg(best.inc_drift[leg]):.2f} deg ({best.dv[leg]:.1f} m/s "
                f"instead of {evaluation.dv_mps[leg]:.1f})"
            )
        self.geometry = self.geometry._replace(side=side, inc_drift=inc)
        m = len(a_ref)
        self.region = TrustRegion(a_ref, self.region.t_ref, np.full(m, self.alpha0),
                                  np.full(m, self.tau0))  # fmt: skip
        return True


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
        Called with each :class:`IterationRecord` as soon as it is known.

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
    mission.check_candidates(len(catalog))
    wall = time.perf_counter()
    driver = _Driver(catalog, mission, solver, settings, progress)
    path, legs, final, status = driver.run()
    driver.timings["iterations_s"] = sum(r.seconds for r in driver.history)
    driver.timings["total_s"] = time.perf_counter() - wall
    geometry = driver.geometry
    ids = catalog.ids
    plan = final.evaluation
    legs_out = tuple(
        Leg(
            from_id=ids[path[k]],
            to_id=ids[path[k + 1]],
            departure_day=float(plan.departure_day[k]),
            duration_days=float(plan.duration_days[k]),
            drift_a_km=float(final.a_drift[k] / 1e3),
            drift_alt_km=float((final.a_drift[k] - R_EARTH) / 1e3),
            drift_inc_deg=float(np.rad2deg(geometry.inc_drift[legs[k]])),
            side=int(geometry.side[legs[k]]),
            dv_mps=float(plan.dv_mps[k]),
        )  # fmt: skip
        for k in range(len(legs))
    )
    size = driver.model.size()
    return Solution(
        path=tuple(ids[k] for k in path),
        legs=legs_out,
        total_dv_mps=float(plan.dv_mps.sum()) + mission.n * mission.operations_dv_mps,
        total_duration_days=plan.end_day,
        status=status,
        backend=solver.backend,
        mission=mission,
        iterations=tuple(driver.history),
        model_size={
            "edges_kept": len(driver.kept),
            "edges_total": len(driver.table.frame),
            "binaries": size.binaries,
            "continuous": size.continuous,
            "constraints": size.constraints,
            "paper_unfiltered": vars(ModelSize.paper(len(catalog))),
        },
        timings=driver.timings,
        notes=tuple(driver.notes),
    )


def _relax_message(mission: Mission, edges_summary: str) -> str:
    return (
        f"no path of n = {mission.n} debris ends within T_max = {mission.tmax_days:g} days in "
        f"the linearised model over the kept edges ({edges_summary}). Relax one of: "
        f"a longer mission (tmax_days), "
        f"a longer pre-optimisation bound (preopt_days = {mission.preopt_days:g}), a higher "
        f"dv_max_mps ({mission.dv_max_mps:g}), a wider drift altitude band "
        f"{mission.drift_altitude_km}, fewer debris (n), or shorter operations (deorbit_days)"
    )
