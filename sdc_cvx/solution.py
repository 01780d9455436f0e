"""The solution returned to users: path, legs, totals, iterations and how the run ended.

The legs are plans evaluated with the true physics
(:func:`sdc_cvx.physics.plan.evaluate_plan`); :class:`RunStatus` is how the sequential
linearisation ended.

Equation, table and part numbers are those of Cerf's paper [1]_; the design
rationale is in ``docs/design.md``.

References
----------
.. [1] M. Cerf, "Multiple Space Debris Collecting Mission — Debris Selection and Trajectory
   Optimization", Journal of Optimization Theory and Applications 156(3), 761–796, 2013.
   doi:10.1007/s10957-012-0130-6
"""

from __future__ import annotations

import json
from dataclasses import asdict, dataclass, field, fields
from enum import StrEnum

import pandas as pd

from .inputs.catalog import Catalog
from .inputs.mission import Mission
from .report.out_folder import checked_save
from .report.run_folder import save_solution


class RunStatus(StrEnum):
    """How a run of the sequential linearisation ended (:attr:`Solution.status`).

    A ``str`` enum: its values are the strings written to ``solution.json`` and
    ``results.csv``, and a member compares equal to its value (``"converged"``).
    New outcomes are new members; :attr:`is_solved` says whether a run with that
    status returned a plan.
    """

    OPTIMAL = "optimal"  # certified: within OPTIMAL_GAP_REL (or 0.01 m/s) of a proven bound
    FEASIBLE = "feasible"  # a plan, with its gap to a proven bound; a limit stopped the search
    CONVERGED = "converged"  # the path survived a MILP around its re-optimised point
    CONVERGED_UNCONFIRMED = "converged_unconfirmed"  # kept changing after max_confirmations
    ITERATION_LIMIT = "iteration_limit"
    TIME_LIMIT = "time_limit"  # a MILP stopped at its time limit without a solution
    STALLED = "stalled"  # the next MILP would repeat an earlier one: nothing left to change
    WITHIN_GAP = "within_gap"  # certified: within a requested gap wider than OPTIMAL_GAP_REL
    OVER_CAPACITY = "over_capacity"  # the plan needs more propellant than the tank holds

    @property
    def is_solved(self) -> bool:
        """A plan came out (every run status so far: failures raise instead)."""
        return self in _SOLVED


OPTIMAL_GAP_REL = 1e-3
"""Widest relative gap called ``optimal`` (0.1 %); a gap of at most
:data:`OPTIMAL_GAP_MPS` is optimal whatever the plan's size."""
OPTIMAL_GAP_MPS = 0.01
"""Absolute gap always called ``optimal`` [m/s] (the certified search's path tolerance)."""
PLANNED_COLUMNS = ("a_km", "e", "inc_deg", "raan_deg", "raan_rate_deg_per_day")
"""The catalog columns of each debris that ``solution.json`` keeps as planned (``debris``)."""

_SOLVED = frozenset(
    {
        RunStatus.OPTIMAL,
        RunStatus.WITHIN_GAP,
        RunStatus.FEASIBLE,
        RunStatus.CONVERGED,
        RunStatus.CONVERGED_UNCONFIRMED,
        RunStatus.ITERATION_LIMIT,
        RunStatus.TIME_LIMIT,
        RunStatus.STALLED,
        RunStatus.OVER_CAPACITY,
    }
)


@dataclass(frozen=True)
class Leg:
    """One transfer of the solution, evaluated with the true model."""

    from_id: str
    to_id: str
    departure_day: float
    duration_days: float
    drift_a_km: float
    drift_alt_km: float
    drift_inc_deg: float
    side: int
    dv_mps: float
    phases: dict = field(default_factory=dict)
    """The transfer model's phases [days] (low thrust: ``spiral_out_days``,
    ``plane_change_days``, ``coast_days``, ``spiral_in_days``) and ``laps`` (relative laps
    of the coast beyond the first that closes the RAAN gap); empty for impulsive legs."""
    masses: dict = field(default_factory=dict)
    """With a vehicle's dry mass and Isp: ``propellant_kg`` burned by the leg and the
    vehicle's ``mass_before_kg`` and ``mass_after_kg`` [kg]; an impulsive leg's ``burn_s``
    [s] with the vehicle's thrust or acceleration; else empty."""
    eccentricity_dv_mps: float | None = None
    """The part of ``dv_mps`` that prices the eccentricity the leg must change [m/s]
    (:mod:`~sdc_cvx.physics.eccentricity`); None where the legs are circular."""

    def to_dict(self) -> dict:
        out = asdict(self)
        if out["eccentricity_dv_mps"] is None:  # circular legs: the columns they always had
            del out["eccentricity_dv_mps"]
        out["from"], out["to"] = out.pop("from_id"), out.pop("to_id")
        phases, masses = out.pop("phases"), out.pop("masses")
        return out | phases | masses


@dataclass(frozen=True)
class IterationRecord:
    """One iteration of the sequential linearisation (the columns of the paper's Table 7)."""

    iteration: int
    path: tuple[str, ...]
    dv_linearized_mps: float | None
    dv_true_mps: float | None
    duration_true_days: float | None
    nodes: int | None
    seconds: float
    solve_seconds: float
    cvxpy_seconds: float
    alpha_km: float | None  # widest radius interval of the chosen copies; None without a path
    status: str
    note: str = ""
    rejected: str = ""  # why the driver rejected this step ("" if it was not)
    elapsed_s: float | None = None  # certified search: seconds from its start to this bound

    def to_dict(self) -> dict:
        out = asdict(self)
        out["path"] = list(self.path)
        return out


@dataclass(frozen=True)
class Solution:
    """The planned mission: path, legs, totals, and how it was found.

    ``legs`` come from the nonlinear re-optimisation and are re-evaluated with the
    physics module; ``catalog`` is the catalog solved over (with the injection
    orbit when there is one); ``initial_legs`` is the first iteration's plan (the paper's
    "before optimisation" of Fig. 19); ``iterations`` is the history of the
    search (the certified loop, or the paper's sequential linearisation).

    ``method`` is ``"certified"`` or ``"paper"``.  A certified answer carries
    ``lower_bound_mps``: no plan of the mission costs less, so the plan is at most
    ``gap_mps`` (``gap_rel`` of it) above the optimum; ``status`` is then ``optimal``
    (within 0.1 % or 0.01 m/s, :data:`OPTIMAL_GAP_REL`), ``within_gap`` (within a wider
    gap the user asked for, ``gap_requested``) or ``feasible`` (a limit or an interrupt
    stopped the search first); ``search_trace`` is how the bound and the best plan
    moved: ``(seconds, bound, plan)`` at each change, None where there was none yet.  The
    paper's method proves no bound (``lower_bound_mps`` is None); its
    ``status``: ``converged`` (the path survived a MILP
    around its re-optimised point), ``converged_unconfirmed`` (it kept changing after
    ``max_confirmations``), ``iteration_limit``, ``time_limit`` (a MILP stopped at its
    time limit without a solution; the cheapest plan held is returned, see ``notes``), or
    ``stalled`` (the next MILP would have repeated an earlier one, same coefficients and
    intervals: the cheapest plan held is returned).
    """

    path: tuple[str, ...]
    legs: tuple[Leg, ...]
    total_dv_mps: float
    total_duration_days: float
    status: RunStatus
    backend: str
    mission: Mission
    iterations: tuple[IterationRecord, ...]
    initial_legs: tuple[Leg, ...] = ()
    operations: dict = field(default_factory=dict)
    catalog: Catalog | None = field(default=None, repr=False, compare=False)
    model_size: dict = field(default_factory=dict)
    timings: dict = field(default_factory=dict)
    notes: tuple[str, ...] = ()
    method: str = "paper"
    lower_bound_mps: float | None = None
    gap_requested: float | None = None
    search_trace: tuple[tuple[float, float | None, float | None], ...] = ()
    vehicle: dict | None = None

    @property
    def certified(self) -> bool:
        """True when the plan is proven within the requested gap of the optimum."""
        return self.status in (RunStatus.OPTIMAL, RunStatus.WITHIN_GAP)

    @property
    def gap_mps(self) -> float | None:
        """Plan minus proven lower bound [m/s] (None without a bound)."""
        if self.lower_bound_mps is None:
            return None
        return max(self.total_dv_mps - self.lower_bound_mps, 0.0)

    @property
    def gap_rel(self) -> float | None:
        """``gap_mps`` relative to the plan's total ΔV (None without a bound)."""
        gap = self.gap_mps
        if gap is None:
            return None
        return gap / self.total_dv_mps if self.total_dv_mps > 0 else 0.0

    def quality(self) -> str:
        """What is known of the answer, in words: ``optimal (gap 0.01 m/s, ...)`` and the like."""
        if self.lower_bound_mps is None:
            return "no proven bound (the paper's method is a local search)"
        gap = f"gap {self.gap_mps:.2f} m/s, {100 * self.gap_rel:.2f} %"
        if self.status == RunStatus.OPTIMAL:
            return f"optimal ({gap}; lower bound {self.lower_bound_mps:.2f} m/s)"
        if self.status == RunStatus.WITHIN_GAP:
            asked = self.gap_requested
            asked = "" if asked is None else f" (requested {100 * asked:g} %)"
            return (
                f"within {100 * self.gap_rel:.2f} % of the optimum{asked}: gap "
                f"{self.gap_mps:.2f} m/s, lower bound {self.lower_bound_mps:.2f} m/s"
            )
        why = "; ".join(self.notes[-1:]) or "a limit stopped the search"
        return f"{self.status}, {gap} ({why}; lower bound {self.lower_bound_mps:.2f} m/s)"

    def legs_frame(self) -> pd.DataFrame:
        """The legs as ``legs.csv`` has them (km, deg, days, m/s), with the operations each
        leg brings and the running total.

        ``operations_dv_mps`` is the ΔV of the operations at the leg's arrival debris (the
        first leg also carries those at the first debris when the mission starts there);
        ``cumulative_dv_mps`` is the total so far, so its last value is ``total_dv_mps``
        (transfers plus operations), as in the summary, ``cost.png`` and ``solution.json``.
        """
        frame = pd.DataFrame([leg.to_dict() for leg in self.legs])
        if frame.empty:
            return frame
        per_debris = dict(self.operations.get("per_debris_mps") or {})
        operations = [float(per_debris.get(leg.to_id, 0.0)) for leg in self.legs]
        operations[0] += float(per_debris.get(self.legs[0].from_id, 0.0))
        frame["operations_dv_mps"] = operations
        frame["cumulative_dv_mps"] = (frame["dv_mps"] + frame["operations_dv_mps"]).cumsum()
        # the sum of rounded parts can differ from the total in the last digits: end on it
        frame.loc[frame.index[-1], "cumulative_dv_mps"] = self.total_dv_mps
        return frame

    @property
    def has_history(self) -> bool:
        """True when it holds a search history (``iterations.csv``, ``iterations.png``): a
        campaign's mission has none, its search is the campaign's (``history.csv``,
        ``bound.png``)."""
        return bool(self.iterations or self.search_trace) or self.method != "certified"

    def iterations_frame(self) -> pd.DataFrame:
        """The search's history as ``iterations.csv`` has it: the paper's Table 7 and more.

        One row per iteration of the sequential linearisation, ``step`` saying what became
        of it: ``accepted``, ``rejected`` (the ``rejected`` column says why, e.g. a plan
        that ends after T_max) or ``no path``, followed by ``, repeats iteration k`` when
        the path and values are an earlier iteration's.  A certified search that needed no
        relaxation rounds has a row each time its bound or plan changed (``step``
        ``bound``).
        """
        columns = [f.name for f in fields(IterationRecord)]  # also when there is no row
        frame = pd.DataFrame([record.to_dict() for record in self.iterations], columns=columns)
        frame["path"] = frame["path"].map(lambda p: "->".join(p))
        if frame.empty and self.search_trace:  # the bound and the plan at each change
            rows = [{"iteration": k, "dv_true_mps": plan, "status": "bound", "elapsed_s": seconds,
                     "note": "lower bound " + ("none yet" if bound is None
                                               else f"{bound:.2f} m/s")}
                    for k, (seconds, bound, plan) in enumerate(self.search_trace)]  # fmt: skip
            return pd.DataFrame(rows, columns=columns).assign(path="", step="bound")
        seen: dict[tuple, int] = {}
        steps = []
        for record in self.iterations:
            key = (record.path, record.dv_linearized_mps, record.dv_true_mps,
                   record.duration_true_days)  # fmt: skip
            step = "rejected" if record.rejected else "accepted" if record.path else "no path"
            if record.path and key in seen:
                step += f", repeats iteration {seen[key]}"
            steps.append(step)
            seen.setdefault(key, record.iteration)
        return frame.assign(step=steps)

    def to_dict(self) -> dict:
        """JSON-ready dict with the documented keys of ``solution.json``.

        ``start`` is the date the RAANs and day 0 refer to (the catalog's start, an
        ISO-8601 UTC string such as ``"2020-05-24T00:00:00+00:00"``); the legs'
        ``departure_day`` counts from it.  It is None (``null``) for a catalog without
        epochs, such as the paper's Table 5, or a solution without its catalog.
        ``debris`` is the path's debris as planned (:meth:`planned_debris`).
        """
        start = None if self.catalog is None else self.catalog.start
        return {
            "path": list(self.path),
            "total_dv_mps": self.total_dv_mps,
            "total_duration_days": self.total_duration_days,
            "status": self.status,
            "method": self.method,
            "certified": self.certified,
            "lower_bound_mps": self.lower_bound_mps,
            "gap_mps": self.gap_mps,
            "gap_rel": self.gap_rel,
            "gap_requested": self.gap_requested,
            "search_trace": [
                {"seconds": t, "lower_bound_mps": lower, "plan_mps": plan}
                for t, lower, plan in self.search_trace
            ],
            "backend": self.backend,
            "legs": [leg.to_dict() for leg in self.legs],
            "initial_legs": [leg.to_dict() for leg in self.initial_legs],
            "iterations": [record.to_dict() for record in self.iterations],
            "start": None if start is None else start.isoformat(),
            "debris": self.planned_debris(),
            "mission": self.mission.to_dict(),
            "transfer": self.mission.transfer_model().describe(),
            "vehicle": self.vehicle,
            "operations": self.operations,
            "model_size": self.model_size,
            "timings": self.timings,
            "notes": list(self.notes),
        }

    def planned_debris(self) -> list[dict]:
        """The path's debris as the plan had them at day 0 (``start``): ``id``, ``a_km``,
        ``e``, ``inc_deg``, ``raan_deg`` and ``raan_rate_deg_per_day`` [km, -, deg,
        deg/day]; ``fly`` compares them with the catalog it reads (a file refreshed since
        the run is said).  Empty without the catalog."""
        if self.catalog is None:
            return []
        frame = self.catalog.frame.set_index(self.catalog.frame["id"].astype(str))
        return [{"id": name, **{column: float(frame.at[name, column])
                                for column in PLANNED_COLUMNS}}
                for name in self.path if name in frame.index]  # fmt: skip

    def to_json(self, indent=2) -> str:
        return json.dumps(self.to_dict(), indent=indent, allow_nan=False)

    def summary(self) -> str:
        """A few lines for people: path, ΔV, duration, iterations."""
        lines = [
            f"path      {' -> '.join(self.path)}",
            f"total dV  {self.total_dv_mps:.2f} m/s, {self.quality()}",
            f"duration  {self.total_duration_days:.2f} days (limit {self.mission.tmax_days:g})",
            f"status    {self.status}: {self.plan_origin()}",
        ]
        if self.operations_dv_mps:
            lines.append(
                f"          transfers {self.transfers_dv_mps:.1f} m/s + operations "
                f"{self.operations_dv_mps:.1f} m/s (deorbit by {self.operations.get('scenario')})"
            )
        model = self.mission.transfer_model().describe()
        if len(model) > 1:  # a model with parameters (the impulsive one has none)
            thrust = (self.vehicle or {}).get("thrust_n")
            accel = model.get("accel_mps2")
            why = ("" if not (thrust and accel) else f" ({thrust:g} N over {thrust / accel:.1f} "
                   "kg: the full tank and every kit, the least acceleration flown)")
            lines.append(f"transfer  {model.pop('transfer')}"
                         + "".join(f", {k} {v:g}" for k, v in model.items()) + why)  # fmt: skip
        if self.vehicle and "propellant_needed_kg" in self.vehicle:
            v = self.vehicle
            tank = ("" if v.get("capacity_kg") is None else
                    f" of {v['capacity_kg']:.1f} kg (margin {v['margin_kg']:.1f} kg)")  # fmt: skip
            lines.append(f"vehicle   propellant {v['propellant_needed_kg']:.1f} kg{tank}, wet mass "
                         f"at launch {v['wet_mass_kg']:.1f} kg (with the propellant the plan "
                         "needs)")  # fmt: skip
        elif self.vehicle and {"dry_mass_kg", "propellant_kg"} & set(self.vehicle):
            missing = [k for k in ("dry_mass_kg", "isp_s") if k not in self.vehicle]
            lines.append(f"vehicle   no propellant computed, the tank not checked: "
                         f"{' and '.join(missing)} missing")  # fmt: skip
        if self.vehicle and self.vehicle.get("long_burns"):
            lines.append(f"warning   the burns of {len(self.vehicle['long_burns'])} leg(s) are "
                         "long against their coast: the impulsive model may not hold (notes)")
        return "\n".join(lines)

    # -- for Python users: the run folder and the figures (issue 14) ------------------
    def save(self, folder, *, formats=("png",), scenario_toml: str | None = None) -> list:
        """Write the run folder ``folder`` as ``python -m sdc_cvx run --out folder`` does.

        ``solution.json``, ``legs.csv``, ``iterations.csv``, ``edges.csv``, the four
        figures in each of ``formats`` and, if given, ``scenario.toml``; the whole folder
        is written aside and swapped in at once (an earlier run folder there is replaced,
        any other non-empty folder refused: see :mod:`sdc_cvx.report.run_folder`).
        ``formats``: ``"png"``, ``"svg"``, ``"pdf"`` or a sequence of them (``()``: no
        figures).  Returns the paths written.

        Raises
        ------
        OutputError
            ``folder`` is not a path, ``scenario_toml`` not text, a format unknown.
        FolderError
            ``folder`` cannot take the run folder (a file, a folder of the user's, the
            current folder, a name too long, a place that refuses new files).
        OSError
            The system refused a write (a full disk); nothing is left behind.
        """
        folder, formats = checked_save("Solution.save", folder, formats,
                                       {"scenario_toml": scenario_toml})  # fmt: skip
        return save_solution(self, folder, formats=formats, scenario_toml=scenario_toml)

    @classmethod
    def load(cls, folder) -> Solution:
        """The solution a run folder holds (``solution.json``, written by :meth:`save`,
        ``python -m sdc_cvx run --out`` or a campaign's mission folder), for a notebook.

        Path, legs, totals, status, mission, history and notes are those saved (a
        ``save`` of the loaded solution writes the same ``solution.json``).  Its
        ``catalog`` holds the path's debris as planned (``solution.json``'s ``debris``,
        at day 0) and no other candidate: the figures draw those; to fly the plan
        against the catalog file, ``python -m sdc_cvx fly FOLDER``
        (:meth:`sdc_cvx.flight.Flight.load` reopens its flight).

        Raises
        ------
        SolutionFileError
            (an ``InputError``) no ``solution.json`` in ``folder``, or one that is not
            what ``save`` writes: the message names the file and the field.
        """
        from .flight.solution_file import read_solution  # pandas only; flight's reader

        return read_solution(folder, cls, Leg, IterationRecord, RunStatus)

    def plot(self) -> dict:
        """The run folder's four figures (matplotlib ``Figure`` by name: ``orbits``,
        ``raan``, ``cost``, ``iterations``), drawn and not saved."""
        from .report.plots import figures  # matplotlib only when asked

        return figures(self)

    def fly(self, *, force_model: str = "j2", progress=None):
        """Fly this plan against the debris (issue 26): phasing, manoeuvres, a numerical
        replay (SGP4 debris), as ``python -m sdc_cvx fly`` does.

        Returns a :class:`sdc_cvx.flight.Flight`; its ``save(run_folder)`` writes
        ``flight/`` (manoeuvres, rendezvous, CCSDS OEM, figure).  ``force_model``:
        ``"j2"``, ``"j2-j4"`` or ``"j2-j4-drag"``.  Raises
        :class:`sdc_cvx.flight.FlightError` when the plan cannot be flown (a catalog
        without the debris' positions on their orbits, a plan from an injection orbit);
        a low-thrust plan is flown as thrust arcs (:mod:`sdc_cvx.flight.thrust_legs`).
        """
        from .flight import FlightPlan, fly  # scipy, sgp4 and erfa only when asked

        return fly(FlightPlan.from_solution(self), force=force_model, progress=progress)

    # -- what the run folder and the summary share (issue 14) ------------------------
    @property
    def operations_dv_mps(self) -> float:
        """ΔV of the operations at the debris (deorbiting), included in ``total_dv_mps``."""
        return float(self.operations.get("total_mps", 0.0) or 0.0)

    @property
    def transfers_dv_mps(self) -> float:
        """ΔV of the transfers alone: ``total_dv_mps`` less the operations [m/s]."""
        return self.total_dv_mps - self.operations_dv_mps

    def plan_origin(self) -> str:
        """Where the returned plan's path came from, in words, and the MILP iterations run.

        For the certified search: the relaxations solved (its answer is proven, not found
        by one step).

        A path held before the first MILP (the seeding) is said to be so, not to be the
        MILP iterations' result; rejected steps are counted.
        """
        count = len(self.iterations)
        if self.method == "certified":
            solves = self.model_size.get("milp_solves", count)
            if self.model_size.get("date_cells", 1) == 0:  # stopped in the cost tables
                return "greedy chains of pre-optimised legs, each scheduled exactly (no relaxation)"
            if solves == 0:
                return "certified search, every relaxation solved by labels (no MILP)"
            return (
                f"certified search, {solves} relaxation MILP{'' if solves == 1 else 's'} "
                f"({self.backend})"
            )
        rejected = sum(1 for record in self.iterations if record.rejected)
        tail = f"{count} MILP iteration{'' if count == 1 else 's'}"
        tail += f", {rejected} rejected" if rejected else ""
        shown = "->".join(self.path)
        if any(note.startswith(f"held before the first MILP: {shown} ") for note in self.notes):
            return f"path from the seeding, held before the first MILP; {tail}"
        for record in self.iterations:
            if tuple(record.path) == tuple(self.path) and not record.rejected:
                return f"path from MILP iteration {record.iteration}; {tail}"
        return tail
