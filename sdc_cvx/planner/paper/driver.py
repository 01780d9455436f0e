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
from dataclasses import dataclass, field, replace

import numpy as np
import pandas as pd

from ...errors import MissionInfeasible, SolverFailure
from ...inputs.catalog import Catalog
from ...inputs.mission import Mission
from ...milp.solve import chain_of, solve_with_fallback
from ...milp.types import SolveReport, SolverOptions, Status
from ...network.dominance import cheapest_paths, path_cost_floor, transfer_dv_floor
from ...network.edges import drift_radius_bounds, node_orbits, preoptimize, preoptimize_windows
from ...physics.leg_bounds import LegCosts
from ...physics.orbits import SECONDS_PER_DAY
from ...physics.plan import PlanEvaluation, evaluate_plan
from ...physics.transfer import cheapest_transfer
from ...solution import IterationRecord, Leg, RunStatus, Solution
from ..fixed_path import PathProblem, schedule_plan, solve_path
from ..nodes import MissionNodes, make_legs
from .decisions import Action, Outcome, Phase, decide
from .linearize import EdgeGeometry, TrustRegion, linearize
from .model import ModelSize, PathModel
from .reoptimize import reoptimize

FROZEN_GAP_DEG = 0.1
MAX_WINDOW_COPIES = 120
SEED_BISECTION_STEPS = 12  # a seed plan is an estimate: the driver re-optimises its answer
SCHEDULE_TOL_MPS = 0.01
"""Certificate of the final path's schedule [m/s] (:meth:`_Driver.global_schedule`)."""


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
        Convergence when the path is unchanged and the true ΔV moved less than this
        [m/s].  The re-optimisation in the true model (Part IV-D) then settles the
        radii, so phase 2 need not: with 0.5 instead of 0.05 the paper case takes 8
        iterations instead of 10 to the same plan, and the enumeration cases end the same.
    max_iterations : int
    max_repeats : int
        The run stops (status ``stalled``) when this many iterations in a row return the
        solution of the one before them (same path, copies, radii and true ΔV): the
        steps between them changed nothing.  On the enumeration catalogs 5 of 8 runs
        otherwise spent up to 39 of their 40 iterations repeating one solution.
    max_assumption_rounds : int
        How many times the side/inclination check may resume the iterations.
    max_confirmations : int
        How many times a re-optimised point is confirmed by one more MILP.
    initial_retries : int
        How many times the first MILP is retried with halved radius intervals before
        the mission is declared infeasible.
    date_windows : int, optional
        Number of departure-date windows over which every edge is replicated, each with
        its own reference (:func:`~sdc_cvx.network.edges.preoptimize_windows`); default
        :func:`default_date_windows`.  1 is the paper's single reference per edge.
    duration_model : {"secant", "two_segments"}
        The paper's secant duration (Eq. 17-18) or its two half-segments (Fig. 14),
        tighter at the cost of one more binary per edge (see ``benchmarks``).
    seed_paths : int
        Before the first MILP, the cheapest ``seed_paths`` paths of each of two rankings
        are re-optimised in the true model (:meth:`_Driver.seed`); the cheapest plan that
        ends by T_max is held from the start, bounds the answer (dominated edges leave
        the first MILP) and is the first MILP's starting point.  0: none.
    """

    alpha_km: float = 50.0
    tau_days: float | None = None
    shrink: float = 0.5
    min_alpha_km: float = 0.01
    dv_tol_mps: float = 0.5
    max_iterations: int = 40
    max_repeats: int = 3
    max_assumption_rounds: int = 2
    max_confirmations: int = 3
    initial_retries: int = 3
    date_windows: int | None = None
    duration_model: str = "secant"
    seed_paths: int = 5


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
    )


def frozen_gaps(catalog: Catalog, mission: Mission) -> bool:
    """True if no RAAN gap moves by more than ``FROZEN_GAP_DEG`` over the mission."""
    rates = node_orbits(catalog, mission).rate * SECONDS_PER_DAY  # rad/day
    return bool(np.rad2deg(rates.max() - rates.min()) * mission.tmax_days < FROZEN_GAP_DEG)


def default_date_windows(catalog: Catalog, mission: Mission, kept_edges: int, legs: int) -> int:
    """One departure-date window per leg on small date-sensitive cases, else one.

    - If no RAAN gap moves by more than ``FROZEN_GAP_DEG`` over the mission (the
      paper's case: 0.02 deg), a leg's date does not change its transfer: one window.
    - Windows multiply the model by n - 1.  Measured: on small catalogs whose J2 rates
      differ they find the enumerated optimum more often (3 of 8 cases against 1 of 8,
      ``tests/test_enumeration.py``); on a synthetic N = 30 catalog (83 edges, n = 5)
      they took 246 s against 5.5 s and ended 16 m/s worse.  So they are the default
      only while the time-expanded model stays under ``MAX_WINDOW_COPIES`` edge copies.
    """
    windows = legs
    if frozen_gaps(catalog, mission) or kept_edges * windows > MAX_WINDOW_COPIES:
        return 1
    return windows


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


@dataclass
class RunLog:
    """What a run records: the iterations (Table 7), notes, timings and backends used."""

    history: list[IterationRecord] = field(default_factory=list)
    notes: list[str] = field(default_factory=list)
    timings: dict = field(default_factory=dict)
    backends_used: set[str] = field(default_factory=set)
    last_switch: str | None = None  # the fallback message last noted (once per change)
    initial_legs: tuple[Leg, ...] | None = None  # the first linearised plan (paper Fig. 19)


@dataclass
class Incumbents:
    """The plans in hand: they bound the answer and prune the MILP."""

    upper: tuple = (np.inf, None)  # cheapest plan that ends by T_max: (ΔV, (path, legs, a))
    best: tuple | None = None  # cheapest re-optimised plan that ends by T_max: (path, legs, final)
    stopped: bool = False  # a MILP reached its time limit without a solution


@dataclass
class TrustState:
    """The references and trust intervals of the edge copies (paper Part IV-C)."""

    region: TrustRegion
    alpha0: float  # the wide radius half-width restored on a new path [km]
    tau0: float  # the wide date half-width [days]
    windows: tuple[np.ndarray, np.ndarray]  # each copy's departure-date window [days]
    visited_paths: set[tuple[int, ...]] = field(default_factory=set)
    initial_retries: int = 0  # narrowings before any path was found
    last_solution: tuple | None = None  # the last MILP's path, copies, radii and true ΔV
    same_solution: int = 0  # iterations in a row before the last that gave its solution


class _Driver:
    """One sequential solve (kept private: :func:`solve` is the API).

    It holds the problem as built (nodes, edge copies, geometry, dominance floor, the
    CVXPY model: set up in ``__init__``), the :class:`TrustState` (``trust``), the
    :class:`Incumbents` (``held``) and the :class:`RunLog` (``log``); :meth:`run`
    dispatches on :func:`~sdc_cvx.planner.paper.decisions.decide`.
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
        edge_floor = transfer_dv_floor(g.origin, g.target, g.a_low, g.a_high)
        self.floor = path_cost_floor(self.kept["i"], self.kept["j"], edge_floor, nodes.cost_mps,
                                     nodes.legs, first=nodes.first)  # fmt: skip
        start = time.perf_counter()
        self.model = PathModel(
            len(catalog), self.kept["i"].to_numpy(), self.kept["j"].to_numpy(),
            n=nodes.legs + 1, tmax_days=mission.tmax_days, deorbit_days=nodes.deorbit_days,
            min_transfer_days=mission.min_transfer_days, operations_dv_mps=nodes.cost_mps,
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

    def worse_than_held(self, path, evaluation) -> bool:
        """The MILP kept the held plan's path but its step made the true ΔV worse.

        (A step that only ends late is rejected in :meth:`run`, around the same point.)
        """
        cost, plan = self.held.upper
        if plan is None or list(plan[0]) != list(path):
            return False
        return self.total(path, evaluation) > cost + self.settings.dv_tol_mps

    def return_to_held(self):
        """Reject the step: linearise the held plan's copies around it, narrower."""
        path, legs, a_drift = self.held.upper[1]
        self.set_references(legs, a_drift, self.evaluate(path, legs, a_drift).departure_day)
        self.narrow(legs, dates=True)
        self.log.notes.append(
            f"iteration {len(self.log.history) - 1}: the step made the held plan worse in the true "
            "model: rejected, intervals narrowed around the held plan"
        )
        self.mark_rejected("made the held plan worse in the true model; back to the held plan")

    def id_path(self, path) -> tuple[str, ...]:
        return tuple(self.catalog.ids[k] for k in path)

    def undominated(self) -> np.ndarray:
        """Edges on some path that may cost less than the cheapest plan in hand."""
        cost = self.held.upper[0]
        return self.floor <= cost + 1e-9 * abs(cost) + 1e-6

    def bound_by(self, path, legs, a_drift, evaluation: PlanEvaluation):
        """Keep the cheapest plan seen that meets T_max and T_min in the true model.

        The plan is held in the copies whose date windows contain its departures
        (:meth:`copies_holding`), so that the MILP restricted to them admits it.
        """
        ends_in_time = self.fits(evaluation)
        cost = self.total(path, evaluation)
        if ends_in_time and cost < self.held.upper[0]:
            legs = self.copies_holding(legs, evaluation.departure_day)
            self.held.upper = (cost, (path, legs, np.asarray(a_drift, dtype=float)))
        return ends_in_time

    def copies_holding(self, legs, departure_day) -> list[int]:
        """For each leg, the copy of its edge whose date window holds its departure [days].

        A copy is taken only with the leg's own drift side and inclination (the plan
        flew those); a leg with no such copy keeps its own.
        """
        g, (lo, hi) = self.geometry, self.trust.windows
        edge = self.kept["i"].to_numpy() * len(self.catalog) + self.kept["j"].to_numpy()
        out = []
        for copy, day in zip(legs, departure_day, strict=True):
            holds = (edge == edge[copy]) & (lo <= day + 1e-9) & (day <= hi + 1e-9)
            holds &= (g.side == g.side[copy]) & np.isclose(g.inc_drift, g.inc_drift[copy])
            out.append(int(copy) if holds[copy] or not holds.any() else int(np.argmax(holds)))
        return out

    def fits(self, evaluation: PlanEvaluation) -> bool:
        """The plan ends by T_max and no transfer is shorter than T_min (true model)."""
        return evaluation.end_day <= self.mission.tmax_days + 1e-6 and bool(
            np.all(evaluation.duration_days >= self.mission.min_transfer_days - 1e-6)
        )

    def total(self, path, evaluation) -> float:
        """Total ΔV of a plan: its transfers plus the operations at its debris [m/s]."""
        return float(evaluation.dv_mps.sum() + self.nodes.cost_mps[path].sum())

    def answer(self, status: RunStatus):
        """The best re-optimised plan, after re-optimising a cheaper iterate if one was seen."""
        cost, plan = self.held.upper
        best = (
            np.inf
            if self.held.best is None
            else self.total(self.held.best[0], self.held.best[2].evaluation)
        )
        if plan is not None and cost < best - 1e-6:
            self.reoptimize(*plan)
        if self.held.best is None:
            raise SolverFailure("no re-optimised plan ends by T_max")
        return self.held.best + (status,)

    def evaluate(self, path, legs, a_legs) -> PlanEvaluation:
        return evaluate_plan(
            self.orbits, path, a_legs, self.geometry.inc_drift[legs],
            deorbit_days=self.nodes.deorbit_days, j2=self.mission.j2,
        )  # fmt: skip

    def record(self, report: SolveReport, path, legs, evaluation, start, note):
        record = IterationRecord(
            iteration=len(self.log.history),
            path=self.id_path(path),
            dv_linearized_mps=report.objective,
            dv_true_mps=self.total(path, evaluation) if path else None,
            duration_true_days=evaluation.end_day if path else None,
            nodes=report.nodes,
            seconds=time.perf_counter() - start,
            solve_seconds=report.solve_seconds,
            cvxpy_seconds=report.overhead_seconds,
            alpha_km=float(np.max(self.trust.region.alpha_km[legs])) if len(legs) else None,
            status=report.status.value,
            note=note,
        )
        self.log.history.append(record)
        self.progress(record)

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

    # -- references and intervals ----------------------------------------------------------
    def move_references(self, path, legs, a_legs, evaluation: PlanEvaluation, path_changed: bool):
        """Move the chosen edges' references to the solution; update the trust intervals.

        A chosen edge's reference becomes the solution's radius and its true departure
        date (kept inside its date window); other edges keep theirs.  A new path
        restores the wide intervals (phase 1); a stable path halves them (phase 2).
        """
        self.set_references(legs, a_legs, evaluation.departure_day)
        if path_changed:
            m = len(self.trust.region.a_ref)
            self.trust.region = replace(self.trust.region, alpha_km=np.full(m, self.trust.alpha0),
                                  tau_days=np.full(m, self.trust.tau0))  # fmt: skip
        else:
            self.narrow(legs, dates=True)

    def set_references(self, legs, a_drift, departure_day):
        """Linearise ``legs`` around these radii [m] and departure dates (within windows)."""
        a_ref, t_ref = self.trust.region.a_ref.copy(), self.trust.region.t_ref.copy()
        a_ref[legs] = a_drift
        t_ref[legs] = np.clip(
            departure_day, self.trust.windows[0][legs], self.trust.windows[1][legs]
        )
        self.trust.region = replace(self.trust.region, a_ref=a_ref, t_ref=t_ref)

    def narrow(self, edges, *, dates: bool):
        """Halve the radius (and date) intervals of ``edges``; other edges stay wide."""
        alpha, tau = self.trust.region.alpha_km.copy(), self.trust.region.tau_days.copy()
        alpha[edges] = np.maximum(alpha[edges] * self.settings.shrink, self.settings.min_alpha_km)
        if dates:
            tau[edges] = tau[edges] * self.settings.shrink
        self.trust.region = replace(self.trust.region, alpha_km=alpha, tau_days=tau)

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

    def reject_late(self, legs, evaluation: PlanEvaluation):
        """The linear durations under-estimated (date cross terms): narrow the chosen copies."""
        self.narrow(legs, dates=True)
        self.log.notes.append(
            f"iteration {len(self.log.history) - 1}: true plan ends on day "
            f"{evaluation.end_day:.1f}, after T_max: step rejected, intervals narrowed"
        )
        self.mark_rejected(
            f"true plan ends on day {evaluation.end_day:.1f}, after T_max = "
            f"{self.mission.tmax_days:g}; intervals narrowed"
        )

    def mark_rejected(self, reason: str):
        """Mark the last iteration's step rejected (and tell ``progress`` again)."""
        record, tmax = self.log.history[-1], self.mission.tmax_days
        end = record.duration_true_days
        if "after T_max" not in reason and end is not None and end > tmax + 1e-6:
            reason += f"; its true plan also ends on day {end:.1f}, after T_max = {tmax:g}"
        record = replace(record, rejected=reason)
        self.log.history[-1] = record
        self.progress(record)

    def advance(self, path, legs, a_legs, evaluation: PlanEvaluation, changed: bool):
        """Move the references to the solution (phase 1 or 2, see :meth:`move_references`).

        A path seen before does not restore wide intervals (no ping-pong between paths).
        """
        revisited = changed and tuple(path) in self.trust.visited_paths
        self.trust.visited_paths.add(tuple(path))
        self.move_references(path, legs, a_legs, evaluation, changed and not revisited)

    def seed(self):
        """Hold the cheapest re-optimised plan among paths that are cheap leg by leg.

        Skipped when the RAAN gaps are frozen (the paper's case: same answer and
        iterations with or without, three times slower with).  Two rankings,
        ``seed_paths`` paths each: by the pre-optimised edge costs (Part
        IV-B, at the references), and with leg k costed as the cheapest transfer leaving
        on the day it would leave if every leg took an equal share of the mission,
        within that share (the same pre-optimisation at the leg's own date).  On GTOC9
        the second ranks first the path that sequential linearisation alone reached
        only by chance (815th by the first); on small catalogs either may be the one.
        """
        count = self.settings.seed_paths
        if count <= 0 or frozen_gaps(self.catalog, self.mission):
            return  # frozen gaps: the day-0 costs hold all year and the MILP finds the plan
        start = time.perf_counter()
        kept, g, legs_count = self.kept, self.geometry, self.nodes.legs
        first_ops, ops = self.depart_range[0], float(self.mission.deorbit_days)
        share = (self.mission.tmax_days - first_ops - legs_count * ops) / legs_count
        if share <= 0:
            return
        leg_costs = np.stack([
            cheapest_transfer(g.origin, g.target, (first_ops + k * (share + ops)) * SECONDS_PER_DAY,
                              share * SECONDS_PER_DAY, g.a_low, g.a_high,
                              inclination=self.mission.drift_inclination, j2=self.mission.j2).dv
            for k in range(legs_count)
        ])  # fmt: skip
        candidates = {}  # path -> edges, in order of ranking
        for cost in (kept["dv_mps"].to_numpy(dtype=float), leg_costs):
            ranked = cheapest_paths(
                kept["i"], kept["j"], cost, legs_count, first=self.nodes.first,
                must_visit=self.nodes.must_visit, width=max(200, count),
            )  # fmt: skip
            distinct = {}  # the ranking lists date-window copies of a route: count routes
            for _, path, legs in ranked:
                distinct.setdefault(path, legs)
                if len(distinct) == count:
                    break
            for path, legs in distinct.items():
                candidates.setdefault(path, legs)
        a_ref = kept["drift_a_km"].to_numpy(dtype=float) * 1e3
        # a quick estimate of every candidate, then the full re-optimisation of the best
        fits = []
        for path, legs in candidates.items():
            path, legs = list(path), list(legs)
            final = self.true_optimum(path, legs, a_ref[legs], polish=False,
                                      bisection_steps=SEED_BISECTION_STEPS)  # fmt: skip
            if self.bound_by(path, legs, final.a_drift, final.evaluation):
                fits.append((self.total(path, final.evaluation), path, legs))
        held = None
        if fits:
            _, path, legs = min(fits, key=lambda fit: fit[0])
            final = self.true_optimum(path, legs, a_ref[legs])
            if self.bound_by(path, legs, final.a_drift, final.evaluation):
                held = (self.copies_holding(legs, final.evaluation.departure_day), final)
        self.log.timings["seed_s"] = time.perf_counter() - start
        if held is not None:
            # the held plan's copies take its sides, inclinations, radii and dates: the
            # first MILP is linearised around it and can start from it
            legs, final = held
            self.adopt(legs, final)
            self.set_references(legs, final.a_drift, final.evaluation.departure_day)
            shown = "->".join(self.id_path(self.held.upper[1][0]))
            self.log.notes.append(
                f"held before the first MILP: {shown} at {self.held.upper[0]:.1f} m/s (cheapest of "
                f"{len(candidates)} paths re-optimised); {int((~self.undominated()).sum())} of "
                f"{len(kept)} edge copies dominated"
            )

    def true_optimum(self, path, legs, a_start, **options):
        """:func:`~sdc_cvx.planner.paper.reoptimize.reoptimize` of ``path`` from the copies'
        choices."""
        g = self.geometry
        return reoptimize(
            self.orbits, path, g.side[legs], g.inc_drift[legs], a_start,
            tmax_days=self.mission.tmax_days, deorbit_days=self.nodes.deorbit_days,
            a_low=g.a_low, a_high=g.a_high, j2=self.mission.j2,
            inclination=self.mission.drift_inclination,
            min_days=self.mission.min_transfer_days, **options,
        )  # fmt: skip

    def adopt(self, legs, final):
        """The copies ``legs`` take the sides and drift inclinations of a re-optimised plan."""
        side, inc = self.geometry.side.copy(), self.geometry.inc_drift.copy()
        side[legs], inc[legs] = final.side, final.inc_drift
        self.geometry = self.geometry._replace(side=side, inc_drift=inc)

    def reoptimize(self, path, legs, a_legs):
        start = time.perf_counter()
        final = self.true_optimum(path, legs, a_legs)
        self.adopt(legs, final)  # the confirming MILP linearises around this plan
        self.log.timings["reoptimize_s"] = self.log.timings.get("reoptimize_s", 0.0) + (
            time.perf_counter() - start
        )
        self.log.notes.append(f"re-optimisation: {final.message}; {final.improved_by_mps:+.2f} m/s")
        ends_in_time = self.bound_by(path, legs, final.a_drift, final.evaluation)
        cost = self.total(path, final.evaluation)
        if ends_in_time and (
            self.held.best is None
            or cost < self.total(self.held.best[0], self.held.best[2].evaluation)
        ):
            self.held.best = (path, legs, final)
        return final

    def global_schedule(self, path, final):
        """The final path's schedule, optimised globally (:func:`solve_path`).

        The re-optimisation (Part IV-D) is local: on the same path it can stop tens of
        m/s above the best schedule.  The path's certified schedule replaces it when it
        is cheaper; either way a note says what is known of the schedule (not of the path,
        which only the certified method can prove).

        Returns
        -------
        PlanEvaluation, tuple
            The plan, and the legs' ``(a_drift, inc_drift, side)``.
        """
        start = time.perf_counter()
        g, mission, ops = self.geometry, self.mission, self.nodes.deorbit_days
        legs_table = LegCosts.build(self.orbits.take(path[:-1]), self.orbits.take(path[1:]),
                                    g.a_low, g.a_high)  # fmt: skip
        problem = PathProblem(legs_table, tuple(range(len(path) - 1)),
                              tuple(float(ops[k]) for k in path), mission.tmax_days,
                              mission.min_transfer_days, mission.drift_inclination,
                              mission.j2)  # fmt: skip
        schedule = solve_path(problem, tol_mps=SCHEDULE_TOL_MPS)
        local = float(final.evaluation.dv_mps.sum())
        self.log.timings["global_schedule_s"] = time.perf_counter() - start
        if not schedule.feasible or schedule.upper_mps >= local - SCHEDULE_TOL_MPS:
            if schedule.lower_mps >= local - SCHEDULE_TOL_MPS:
                self.log.notes.append(
                    f"the path's schedule is its optimum within "
                    f"{SCHEDULE_TOL_MPS:g} m/s (the path itself is not proven)"
                )
            return final.evaluation, (final.a_drift, final.inc_drift, final.side)
        plan, notes = schedule_plan(self.orbits, path, schedule, deorbit_days=ops,
                                    tmax_days=mission.tmax_days, j2=mission.j2)  # fmt: skip
        self.log.notes += notes + [
            f"the path's schedule optimised globally: {local:.2f} -> "
            f"{schedule.upper_mps:.2f} m/s of transfers (the local re-optimisation stopped "
            f"above it; the path itself is not proven)"
        ]  # fmt: skip
        return plan, (schedule.a_drift, schedule.inc_drift, schedule.side)

    def flip_assumptions(self, path, legs, a_legs, evaluation) -> bool:
        """Resume with another side/inclination for legs where one is clearly cheaper."""
        origins, targets = self.orbits.take(path[:-1]), self.orbits.take(path[1:])
        # each leg may take its own time plus all of the mission's slack
        slack = max(self.mission.tmax_days - evaluation.end_day, 0.0)
        allotted = (evaluation.duration_days + slack) * SECONDS_PER_DAY
        best = cheapest_transfer(
            origins, targets, evaluation.departure_day * SECONDS_PER_DAY, allotted,
            self.geometry.a_low, self.geometry.a_high,
            inclination=self.mission.drift_inclination, j2=self.mission.j2,
        )  # fmt: skip
        better = best.dv < evaluation.dv_mps - 0.5
        differs = (best.side != self.geometry.side[legs]) | ~np.isclose(
            best.inc_drift, self.geometry.inc_drift[legs]
        )
        flip = np.flatnonzero(better & differs)
        if flip.size == 0:
            return False
        side, inc = self.geometry.side.copy(), self.geometry.inc_drift.copy()
        a_ref = self.trust.region.a_ref.copy()
        ids = self.catalog.ids
        for leg in flip:
            edge = legs[leg]
            side[edge], inc[edge], a_ref[edge] = (
                best.side[leg],
                best.inc_drift[leg],
                best.a_drift[leg],
            )
            self.log.notes.append(
                f"leg {ids[path[leg]]}->{ids[path[leg + 1]]}: resumed with "
                f"side {int(best.side[leg]):+d}, drift inclination "
                f"{np.rad2deg(best.inc_drift[leg]):.2f} deg ({best.dv[leg]:.1f} m/s "
                f"instead of {evaluation.dv_mps[leg]:.1f})"
            )
        self.geometry = self.geometry._replace(side=side, inc_drift=inc)
        m = len(a_ref)
        self.trust.region = TrustRegion(a_ref, self.trust.region.t_ref,
                                        np.full(m, self.trust.alpha0),
                                        np.full(m, self.trust.tau0))  # fmt: skip
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
    legs_out = make_legs(ids, path, *drift, plan)
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
        notes=tuple(driver.log.notes),
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
    )
