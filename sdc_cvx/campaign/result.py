"""``CampaignSolution``: the campaign's missions, its bound and gap, and the greedy baseline."""

from __future__ import annotations

import json
from dataclasses import dataclass

import pandas as pd

from ..inputs.campaign import Campaign
from ..inputs.catalog import Catalog
from ..inputs.vehicle import TANK_KEYS
from ..solution import RunStatus, Solution


@dataclass(frozen=True)
class GreedyCampaign:
    """The one-mission-at-a-time campaign: the cheapest first mission, its debris removed,
    the cheapest second mission, and so on.

    Attributes
    ----------
    dv_mps : float or None
        Its total ΔV [m/s]; None when a later launch found no mission among the debris
        left (``why`` says so).
    missions : tuple
        Its columns, in launch order.
    why : str
    paths : tuple of str
        Each mission's path, as text.
    left_over : tuple of int
        The debris that had to be removed and were still left where it failed (catalog
        indices).
    """

    dv_mps: float | None
    missions: tuple = ()
    why: str = ""
    paths: tuple[str, ...] = ()
    left_over: tuple[int, ...] = ()


@dataclass(frozen=True)
class CampaignSolution:
    """The best campaign found and what is proven about the optimum.

    Attributes
    ----------
    campaign : Campaign
    catalog : Catalog
        The candidates at day 0 (the campaign's start).
    missions : tuple of Solution
        One per launch, in launch order; each mission's day 0 is its launch day (its
        catalog's start is the campaign's plus the launch day).
    total_dv_mps : float
        Sum of the missions' total ΔV [m/s].
    lower_bound_mps : float or None
        No campaign of these missions costs less [m/s]; at least 0 (every cost is); None
        when the search stopped before it proved any bound.
    status : RunStatus
        ``optimal`` (within 0.1 %, or 0.01 m/s per mission), ``within_gap`` (within a
        wider requested gap) or ``feasible`` (a limit stopped the search; the gap says
        how far it may be).
    greedy : GreedyCampaign
    history : tuple of dict
        Each step: ``step``, ``seconds``, ``lower_mps``, ``upper_mps``, ``lp_mps``,
        ``columns``, ``pricings``.
    columns, pricings : int
        Missions in the master's pool; pricing problems solved.
    seconds : float
    notes : tuple of str
    gap_requested : float
    value, value_bound : float or None
        ``objective = "max-value"``: the value the campaign removes, and the most any
        campaign could (None: not proven); ``lower_bound_mps`` then bounds the ΔV of the
        campaigns of that value.
    pareto : tuple of dict
        ``--pareto K``: campaigns of value against ΔV (``target_value``, ``value``,
        ``dv_mps``, ``dv_bound_mps``, ``missions``), each the cheapest of at least its
        target (``pareto.csv``, ``pareto.png``).
    """

    campaign: Campaign
    catalog: Catalog
    missions: tuple[Solution, ...]
    total_dv_mps: float
    lower_bound_mps: float | None
    status: RunStatus
    greedy: GreedyCampaign
    history: tuple[dict, ...] = ()
    columns: int = 0
    pricings: int = 0
    seconds: float = 0.0
    notes: tuple[str, ...] = ()
    gap_requested: float = 1e-3
    value: float | None = None
    value_bound: float | None = None
    pareto: tuple[dict, ...] = ()

    @property
    def certified(self) -> bool:
        """True when the campaign is proven within the requested gap of the optimum."""
        return self.status in (RunStatus.OPTIMAL, RunStatus.WITHIN_GAP)

    @property
    def bound_known(self) -> bool:
        """True when a bound above 0 is proven (0 holds for every campaign: no information)."""
        return self.lower_bound_mps is not None and self.lower_bound_mps > 0

    @property
    def gap_mps(self) -> float | None:
        """Plan minus proven lower bound [m/s] (None: no bound yet)."""
        if self.lower_bound_mps is None:
            return None
        return max(self.total_dv_mps - self.lower_bound_mps, 0.0)

    @property
    def gap_rel(self) -> float | None:
        """The gap relative to the plan [-] (None: no bound yet)."""
        if self.gap_mps is None:
            return None
        return self.gap_mps / self.total_dv_mps if self.total_dv_mps > 0 else 0.0

    @property
    def launch_days(self) -> tuple[float, ...]:
        return self.campaign.launch_days

    def greedy_gap_rel(self) -> float | None:
        """How far greedy is above the proven bound, relative to the bound [-] (None
        without greedy or a bound above 0)."""
        dv = self.greedy.dv_mps
        if dv is None or not self.bound_known:
            return None
        return max(dv - self.lower_bound_mps, 0.0) / self.lower_bound_mps

    def quality(self) -> str:
        why = "; ".join(self.notes[-1:]) or "a limit stopped the search"
        if self.lower_bound_mps is None:
            return f"{self.status}, no bound yet ({why})"
        if self.status == RunStatus.OPTIMAL and self.total_dv_mps <= 0.0:
            return "optimal (0 m/s: each mission flies its launch alone, no transfer)"
        if not self.bound_known:
            return f"{self.status}, no useful bound yet: 0 m/s ({why})"
        gap = f"gap {self.gap_mps:.2f} m/s, {100 * self.gap_rel:.2f} %"
        if self.status == RunStatus.OPTIMAL:
            return f"optimal ({gap}; lower bound {self.lower_bound_mps:.2f} m/s)"
        if self.status == RunStatus.WITHIN_GAP:
            return (
                f"within {100 * self.gap_rel:.2f} % of the optimum (requested "
                f"{100 * self.gap_requested:g} %): gap {self.gap_mps:.2f} m/s, lower bound "
                f"{self.lower_bound_mps:.2f} m/s"
            )
        if self.status == RunStatus.OVER_CAPACITY:  # the note says so on its own line
            return f"{self.status}, {gap} (lower bound {self.lower_bound_mps:.2f} m/s)"
        return f"{self.status}, {gap} ({why}; lower bound {self.lower_bound_mps:.2f} m/s)"

    def summary(self) -> str:
        """A few lines for people: each mission, the total, the bound, greedy."""
        lines = []
        for k, (day, mission) in enumerate(zip(self.launch_days, self.missions, strict=True)):
            lines.append(
                f"mission {k + 1:<2d} day {day:8.2f}  {' -> '.join(mission.path):<40} "
                f"{mission.total_dv_mps:8.2f} m/s  {mission.total_duration_days:7.2f} d"
            )
        price = self.campaign.price_per_value_mps
        if self.value is not None and price is not None:
            lines.append(f"value     {self.value:g} removed at {price:g} m/s a unit: ΔV - "
                         f"price x value = {self.total_dv_mps - price * self.value:.2f} m/s")
        elif self.value is not None:
            bound = "not proven" if self.value_bound is None else f"{self.value_bound:g}"
            if self.value_bound is not None and self.value_bound > self.value * (1 + 1e-9):
                bound += f": value gap {100 * (1 - self.value / self.value_bound):.2f} %"
            lines.append(f"value     {self.value:g} removed (the most any campaign removes: "
                         f"{bound})")  # fmt: skip
        lines.append(f"total dV  {self.total_dv_mps:.2f} m/s, {self.quality()}")
        if (tank := self.tank_text()) is not None:
            lines.append(f"vehicle   {tank}")
        if self.greedy.dv_mps is not None:
            rel = self.greedy_gap_rel()
            above = "" if rel is None else f"; {100 * rel:.2f} % above the bound"
            lines.append(f"greedy    {self.greedy.dv_mps:.2f} m/s (one mission at a time"
                         f"{above})")  # fmt: skip
        else:
            lines.append(f"greedy    none ({self.greedy.why})")
        lines.append(f"search    {self.columns} missions priced into the master, "
                     f"{self.pricings} pricing problems, {self.seconds:.1f} s")  # fmt: skip
        return "\n".join(lines)

    def tank_text(self) -> str | None:
        """Each mission's propellant against its tank, in a line (None without a vehicle
        whose propellant is known)."""
        blocks = [m.vehicle for m in self.missions]
        if not all(b and "propellant_needed_kg" in b for b in blocks):
            return None
        needed = ", ".join(f"{b['propellant_needed_kg']:.1f}" for b in blocks)
        tanks = {b.get("capacity_kg") for b in blocks}
        if tanks == {None}:
            return f"propellant per mission {needed} kg"
        over = [str(k + 1) for k, b in enumerate(blocks) if not b["fits"]]
        tank = "" if len(tanks) > 1 else f" of a {next(iter(tanks)):.1f} kg tank each"
        return (f"propellant per mission {needed} kg{tank}; "
                + (f"over the tank: mission {', '.join(over)}" if over else "every one fits"))

    def missions_frame(self) -> pd.DataFrame:
        """``missions.csv``: one row per mission (launch day, path, ΔV, dates, folder; with
        a vehicle whose propellant is known, its propellant, tank, margin and fit)."""
        rows = []
        for k, (day, mission) in enumerate(zip(self.launch_days, self.missions, strict=True)):
            tank = mission.vehicle if mission.vehicle and "fits" in mission.vehicle else {}
            rows.append({
                "mission": k + 1, "launch_day": day, "path": "->".join(mission.path),
                "n": len(mission.path), "total_dv_mps": mission.total_dv_mps,
                "value": float(self.campaign.value_of(mission.path).sum()),
                "transfers_dv_mps": mission.transfers_dv_mps,
                "operations_dv_mps": mission.operations_dv_mps,
                "duration_days": mission.total_duration_days,
                "end_day": day + mission.total_duration_days,
                "tmax_days": mission.mission.tmax_days, "folder": mission_folder(k),
            } | {key: tank[key] for key in TANK_KEYS if key in tank})  # fmt: skip
        return pd.DataFrame(rows)

    def pareto_frame(self) -> pd.DataFrame:
        """``pareto.csv``: the campaigns of value against ΔV, one row each."""
        return pd.DataFrame([row | {"missions": " | ".join("->".join(m) for m in row["missions"])}
                             for row in self.pareto])  # fmt: skip

    def history_frame(self) -> pd.DataFrame:
        """The bound and the plan against elapsed time, one row per step."""
        return pd.DataFrame(list(self.history), columns=HISTORY_COLUMNS)

    def to_dict(self) -> dict:
        """JSON-ready dict: the keys of ``campaign.json``."""
        start = self.catalog.start
        return {
            "status": str(self.status),
            "certified": self.certified,
            "objective": self.campaign.objective,
            "value": self.value,
            "value_bound": self.value_bound,
            "total_dv_mps": self.total_dv_mps,
            "lower_bound_mps": self.lower_bound_mps,
            "gap_mps": self.gap_mps,
            "gap_rel": self.gap_rel,
            "gap_requested": self.gap_requested,
            "greedy_dv_mps": self.greedy.dv_mps,
            "greedy_gap_rel": self.greedy_gap_rel(),
            "greedy_paths": [p.split(" -> ") for p in self.greedy.paths],
            "start_utc": None if start is None else start.isoformat(),
            "missions": [
                {
                    "launch_day": day,
                    "path": list(m.path),
                    "total_dv_mps": m.total_dv_mps,
                    "duration_days": m.total_duration_days,
                    "folder": mission_folder(k),
                }
                for k, (day, m) in enumerate(zip(self.launch_days, self.missions, strict=True))
            ],  # fmt: skip
            "campaign": self.campaign.to_dict(),
            "columns": self.columns,
            "pricings": self.pricings,
            "seconds": self.seconds,
            "history": [_finite(row) for row in self.history],
            "pareto": [_finite(row) for row in self.pareto],
            "notes": list(self.notes),
        }

    def to_json(self, indent=2) -> str:
        return json.dumps(self.to_dict(), indent=indent, allow_nan=False)

    def save(self, folder, *, formats=("png",), scenario_toml: str | None = None,
             log: str | None = None) -> list:  # fmt: skip
        """Write the campaign folder (see :func:`sdc_cvx.report.campaign_folder.write_campaign`).

        Its arguments are checked first as :meth:`Solution.save`'s are (``OutputError``,
        ``FolderError``: one line, nothing written).
        """
        from ..report.campaign_folder import (
            CAMPAIGN_FOLDER_FILES,
            CAMPAIGN_FOLDER_MARKERS,
            KIND,
            write_campaign,
        )
        from ..report.out_folder import checked_save

        folder, formats = checked_save("CampaignSolution.save", folder, formats,
                                       {"scenario_toml": scenario_toml, "log": log},
                                       CAMPAIGN_FOLDER_MARKERS, CAMPAIGN_FOLDER_FILES, KIND)
        return write_campaign(folder, self, formats=formats, scenario_toml=scenario_toml,
                              log=log)  # fmt: skip

    def plot(self) -> dict:
        """The campaign's figures (matplotlib ``Figure`` by name: ``timeline``, ``raan``,
        ``dv``, ``bound``), drawn and not saved."""
        from ..report.campaign_plots import campaign_figures

        return campaign_figures(self)


HISTORY_COLUMNS = ("step", "seconds", "lower_mps", "upper_mps", "lp_mps", "columns", "pricings")
"""The columns of ``history.csv`` (each step's bound, plan, LP, pool and pricings)."""


def tank_status(missions, status: RunStatus, notes) -> tuple[RunStatus, tuple[str, ...]]:
    """A campaign's status and notes once its missions' tanks are read: ``over_capacity``
    and a note naming them where one needs more propellant than its tank holds (a
    campaign never reported as flyable that is not), else unchanged."""
    over = [(k, m.vehicle) for k, m in enumerate(missions)
            if m.status == RunStatus.OVER_CAPACITY]  # fmt: skip
    if not over:
        return status, tuple(notes)
    needs = ", ".join(f"mission {k + 1} needs {v['propellant_needed_kg']:.1f} kg of "
                      f"{v['capacity_kg']:.1f} kg" for k, v in over)  # fmt: skip
    note = (f"not flyable with this vehicle: {needs} (the least-ΔV campaign, searched without "
            "the tank; objective = 'max-value' searches only missions that fit it)")
    return RunStatus.OVER_CAPACITY, (*notes, note)


def mission_folder(k: int) -> str:
    """Folder of the k-th mission (0-based) in the campaign folder: ``mission_01``, ..."""
    return f"mission_{k + 1:02d}"


def _finite(row: dict) -> dict:
    return {key: (None if isinstance(value, float) and not abs(value) < float("inf") else value)
            for key, value in row.items()}  # fmt: skip
