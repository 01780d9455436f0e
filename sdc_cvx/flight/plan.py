"""What a flight needs of a plan: its legs, the mission's limits and the debris' catalog rows.

A :class:`FlightPlan` is built from a :class:`~sdc_cvx.solution.Solution` in memory
(:meth:`FlightPlan.from_solution`) or from a run folder's ``solution.json`` and the
catalog its ``scenario.toml`` names (:meth:`FlightPlan.from_run_folder`), so that
``Solution.fly()`` and ``python -m sdc_cvx fly RUN_DIR`` fly the same thing.
"""

from __future__ import annotations

import dataclasses
import json
from dataclasses import dataclass
from pathlib import Path

import numpy as np
import pandas as pd

from ..errors import CatalogError, InputError, SdcError, listing
from ..inputs.catalog import Catalog
from ..inputs.vehicle import Vehicle
from ..physics.orbits import SECONDS_PER_DAY
from .ephemeris import missing_phase
from .solution_file import SolutionFileError, checked_solution


def miss_text(km: float) -> str:
    """A rendezvous' distance for people: metres below a kilometre, else km."""
    return f"{km * 1e3:.2f} m" if km < 1.0 else f"{km:.2f} km"


class FlightError(InputError):
    """A plan that cannot be flown as asked: what is missing or wrong, and what to do."""


@dataclass(frozen=True)
class PlannedLeg:
    """One leg of the plan, in the planner's units (days, km, deg, m/s)."""

    from_id: str
    to_id: str
    departure_day: float
    duration_days: float
    drift_a_km: float
    drift_inc_deg: float
    side: int
    dv_mps: float
    laps: int = 0

    @property
    def arrival_day(self) -> float:
        return self.departure_day + self.duration_days


@dataclass(frozen=True)
class PlannedTank:
    """The vehicle of a plan whose propellant is known: what the flight's is measured
    against (:attr:`~sdc_cvx.flight.result.Flight.propellant`).

    Attributes
    ----------
    vehicle : Vehicle
        With its dry mass and Isp (and its tank, ``propellant_kg``, when given).
    operations_dv_mps : tuple of float
        ΔV of the operations at each debris of the path [m/s], in path order.
    planned_kg : float
        The propellant the plan needs [kg].
    """

    vehicle: Vehicle
    operations_dv_mps: tuple[float, ...]
    planned_kg: float

    @classmethod
    def of(cls, vehicle, block, operations, path) -> PlannedTank | None:
        """From a plan's mission vehicle, its solution's ``vehicle`` block and
        ``operations`` (``solution.json``'s, or a Solution's), over the path's ids; None
        without a vehicle whose propellant the plan computed."""
        if (vehicle is None or not vehicle.can_budget() or not isinstance(block, dict)
                or not isinstance(block.get("propellant_needed_kg"), int | float)):
            return None
        per_debris = (operations or {}).get("per_debris_mps") or {}
        return cls(vehicle, tuple(float(per_debris.get(name, 0.0)) for name in path),
                   float(block["propellant_needed_kg"]))  # fmt: skip


@dataclass(frozen=True)
class FlightPlan:
    """A plan to fly: its legs, the mission's limits and the catalog rows of its debris.

    Attributes
    ----------
    legs : tuple of PlannedLeg
    catalog : Catalog
        The plan's debris, in path order (their RAANs at ``catalog.start``).
    tmax_days : float
        Mission duration limit [days].
    drift_altitude_km : (float, float)
        Altitude bounds of the drift orbits [km].
    plan_dv_mps : float
        The plan's transfer ΔV [m/s] (its operations at the debris excluded).
    plan_end_day : float
        The plan's mission duration [days].
    accel_mps2 : float or None
        A low-thrust plan's thrust acceleration [m/s^2]; None for an impulsive plan.
    notes : tuple of str
        What the flight must say of the plan (a catalog changed since the run).
    tank : PlannedTank or None
        The vehicle, where the plan computed its propellant.
    over_capacity : str or None
        Why the plan itself is not flyable (its status ``over_capacity``: it needs more
        propellant than the tank holds); ``fly`` does not fly it.
    """

    legs: tuple[PlannedLeg, ...]
    catalog: Catalog
    tmax_days: float
    drift_altitude_km: tuple[float, float]
    plan_dv_mps: float
    plan_end_day: float
    accel_mps2: float | None = None
    notes: tuple[str, ...] = ()
    tank: PlannedTank | None = None
    over_capacity: str | None = None

    @classmethod
    def from_solution(cls, solution) -> FlightPlan:
        """The plan of a :class:`~sdc_cvx.solution.Solution`."""
        _check_transfer(solution.mission.transfer, "this solution")
        _check_start(solution.mission.injection, "this solution")
        if solution.catalog is None:
            raise FlightError("this solution has no catalog: fly needs the debris' orbits")
        legs = tuple(PlannedLeg(leg.from_id, leg.to_id, leg.departure_day, leg.duration_days,
                                leg.drift_a_km, leg.drift_inc_deg, leg.side, leg.dv_mps,
                                int(leg.phases.get("laps", 0)))
                     for leg in solution.legs)  # fmt: skip
        mission = solution.mission
        built = cls._build(legs, solution.catalog, mission.tmax_days, mission.drift_altitude_km,
                           solution.total_duration_days,
                           accel=mission.transfer_model().describe().get("accel_mps2"))  # fmt: skip
        over = (solution.notes[-1] if str(solution.status) == "over_capacity" and solution.notes
                else None)  # fmt: skip
        return dataclasses.replace(
            built, over_capacity=over, tank=PlannedTank.of(
                mission.vehicle, solution.vehicle, solution.operations, solution.path))

    @classmethod
    def from_run_folder(cls, folder, *, scenario_file=None, campaign_start=None,
                        catalog_path=None) -> FlightPlan:  # fmt: skip
        """The plan of a run folder (``solution.json``, and the catalog of ``scenario.toml``,
        or ``catalog_path`` instead: a catalog moved since the run).

        ``scenario_file``: the scenario naming the catalog, default the folder's own (a
        campaign's mission folder has the campaign's, :func:`run_folder_plans`, and
        ``campaign_start``, the campaign's day 0, ISO-8601).  With ``[catalog] raan_rates
        = "sgp4"`` the plan's debris get the rates the run fitted: from the run's day 0
        (the campaign's) over the scenario's window
        (:meth:`~sdc_cvx.study.scenario.Scenario.with_raan_rates`), then carried to the
        plan's day 0.

        Raises
        ------
        FlightError
            Not a run folder of this version (files missing or from another version), or
            a plan that cannot be flown.
        """
        from ..study.scenario import Scenario  # the commands' reader of scenario files

        folder = Path(folder)
        data = _read_json(folder / "solution.json")
        try:
            plan = checked_solution(data, folder / "solution.json")
        except SolutionFileError as err:
            raise FlightError(str(err)) from None
        described = data.get("transfer") if isinstance(data.get("transfer"), dict) else {}
        transfer = plan["mission"].get("transfer", described.get("transfer", "impulsive"))
        _check_transfer(transfer, str(folder))
        accel = described.get("accel_mps2") if transfer == "low-thrust" else None
        if transfer == "low-thrust" and not (isinstance(accel, (int, float)) and accel > 0):
            raise FlightError(f"{folder / 'solution.json'}: a low-thrust plan without its "
                              f"thrust acceleration (transfer.accel_mps2 is {accel!r})")
        _check_start(plan["mission"].get("injection"), str(folder))
        scenario_file = Path(scenario_file or folder / "scenario.toml")
        if not scenario_file.exists():
            if (folder.parent / "campaign.json").exists():  # a mission of a campaign
                raise FlightError(f"{folder}: a mission folder of a campaign: fly the "
                                  f"campaign folder {folder.parent} (its scenario is there)")
            raise FlightError(f"{folder}: no scenario.toml, so no catalog to fly against (a "
                              "folder of Solution.save() without scenario_toml=: fly that "
                              "solution in Python, solution.fly())")  # fmt: skip
        start = plan["start"]
        try:
            scenario = Scenario.load(scenario_file, catalog_path=catalog_path)
            fitted = scenario.catalog_raan_rates != "j2"
            day0 = pd.Timestamp(campaign_start) if fitted and campaign_start else start
            if day0 is not None:  # the RAANs at the run's day 0, whatever the catalog holds now
                scenario = scenario.with_overrides(catalog_start=day0.to_pydatetime())
            catalog = scenario.load_catalog(on_invalid="set aside")
        except SdcError as err:
            moved = catalog_path is None and "catalog.path" in str(err)
            raise FlightError(_naming(scenario_file, err) + (
                " (moved since the run? fly RUN_DIR --catalog FILE flies against it where it "
                "is now)" if moved else "")) from None  # fmt: skip

        def rates(debris: Catalog) -> Catalog:  # as the run fitted them, at the plan's day 0
            if not fitted:
                return debris
            debris = scenario.with_raan_rates(debris)
            later = 0.0 if start is None or day0 is None else (start - day0).total_seconds()
            return debris.advanced(later / SECONDS_PER_DAY)

        legs = tuple(PlannedLeg(leg["from"], leg["to"], leg["departure_day"],
                                leg["duration_days"], leg["drift_a_km"], leg["drift_inc_deg"],
                                leg["side"], leg["dv_mps"], leg["laps"])
                     for leg in plan["legs"])  # fmt: skip
        try:
            built = cls._build(legs, catalog, plan["tmax_days"], plan["drift_altitude_km"],
                               plan["total_duration_days"], rates=rates, accel=accel)  # fmt: skip
        except CatalogError as err:  # SGP4 cannot fly a debris over the window of its rate
            raise FlightError(_naming(scenario_file, err)) from None
        built = dataclasses.replace(
            built, over_capacity=_over_capacity(data),
            tank=PlannedTank.of(scenario.mission.vehicle, data.get("vehicle"),
                                data.get("operations"),
                                built.catalog.frame["id"].astype(str).tolist()))
        changes = changed_since_plan(built.catalog, plan["debris"])
        if not changes:
            return built
        return dataclasses.replace(built, notes=(
            f"{catalog.source}: the catalog changed since the run ({listing(changes)}, at "
            "day 0): this flight meets the debris as the file has them now, not those the "
            f"plan was made for; plan again (run {scenario_file}) for a plan of these",))

    @classmethod
    def _build(cls, legs, catalog: Catalog, tmax_days, bounds, end_day, *, rates=None,
               accel=None) -> FlightPlan:  # fmt: skip
        """The plan over the catalog rows of its path, in path order; ``rates`` (of those
        rows' catalog): the RAAN rates of the run (:meth:`from_run_folder`); ``accel``: a
        low-thrust plan's acceleration [m/s^2]."""
        if not legs:
            raise FlightError("the plan has no leg to fly (a mission of one debris)")
        path = [legs[0].from_id] + [leg.to_id for leg in legs]
        ids = catalog.frame["id"].astype(str)
        missing = [name for name in path if name not in set(ids)]
        if missing:
            raise FlightError(f"{catalog.source}: no debris {listing(map(repr, missing))} of "
                              "the plan (the catalog changed since the run?)")  # fmt: skip
        rows = [int(np.flatnonzero(ids.to_numpy() == name)[0]) for name in path]
        frame = catalog.frame.iloc[rows].reset_index(drop=True)
        subset = dataclasses.replace(catalog, frame=frame, invalid=None)
        if rates is not None:
            subset = rates(subset)
        problem = missing_phase(subset)
        if problem is not None:
            raise FlightError(problem)
        return cls(tuple(legs), subset, float(tmax_days), (float(bounds[0]), float(bounds[1])),
                   float(sum(leg.dv_mps for leg in legs)), float(end_day),
                   None if accel is None else float(accel))  # fmt: skip

    @property
    def start(self) -> pd.Timestamp:
        """Day 0 of the plan (UTC)."""
        return self.catalog.start


CHANGE_TOLERANCE = {"a_km": 1e-6, "e": 1e-9, "inc_deg": 1e-7, "raan_deg": 1e-6,
                    "raan_rate_deg_per_day": 1e-9}
"""Differences of a debris' elements (``solution.json``'s ``debris``) that are rounding,
not a changed catalog [km, -, deg, deg, deg/day]: the same file gives the same floats."""


def changed_since_plan(catalog: Catalog, planned: list[dict]) -> list[str]:
    """What differs between the debris as the run planned them (``solution.json``'s
    ``debris``: at day 0) and in ``catalog`` now, one phrase per element that moved."""
    frame = catalog.frame.set_index(catalog.frame["id"].astype(str))
    out = []
    for entry in planned:
        name = str(entry.get("id"))
        if name not in frame.index:  # _build has refused a debris the catalog lacks
            continue
        for column, tolerance in CHANGE_TOLERANCE.items():
            then = entry.get(column)
            if not isinstance(then, int | float):
                continue
            now = float(frame.at[name, column])
            moved = now - float(then)
            if column == "raan_deg":
                moved = (moved + 180.0) % 360.0 - 180.0
            if abs(moved) > tolerance:
                out.append(f"{name} {column} {then:.6g} -> {now:.6g}")
    return out


def unflyable(catalog: Catalog, mission) -> str | None:
    """Why a plan of ``mission`` over ``catalog`` could not be flown, known before it is
    planned (``run --fly`` refuses it then), or None."""
    for problem in (_transfer_problem(mission.transfer), _start_problem(mission.injection)):
        if problem:
            return problem
    return missing_phase(catalog)


def run_folder_plans(folder, catalog_path=None) -> list[tuple[Path, FlightPlan]]:
    """``(folder, plan)`` of a run folder, or of each mission of a campaign folder (their
    catalog that of ``catalog_path`` if given, else their scenario's)."""
    folder = Path(folder)
    campaign = folder / "campaign.json"
    if not campaign.exists():
        return [(folder, FlightPlan.from_run_folder(folder, catalog_path=catalog_path))]
    data = _read_json(campaign)
    if not isinstance(data, dict):
        raise FlightError(f"{campaign}: expected a JSON object (a campaign's campaign.json), "
                          f"got {type(data).__name__}")  # fmt: skip
    missions = data.get("missions")
    if not isinstance(missions, list) or not missions:
        raise FlightError(f"{campaign}: no missions to fly (field 'missions': expected a "
                          "non-empty list)")  # fmt: skip
    subs = [_mission_folder(folder, campaign, k, entry) for k, entry in enumerate(missions)]
    # a mission of one debris (a value campaign's n_min = 1) is its launch: nothing to fly
    subs = [sub for sub, entry in zip(subs, missions, strict=True)
            if not (isinstance(entry.get("path"), list) and len(entry["path"]) == 1)]
    if not subs:
        raise FlightError(f"{campaign}: every mission removes one debris (its launch alone): "
                          "no leg to fly")  # fmt: skip
    return [(sub, FlightPlan.from_run_folder(sub, scenario_file=folder / "scenario.toml",
                                             campaign_start=data.get("start_utc"),
                                             catalog_path=catalog_path))
            for sub in subs]  # fmt: skip


def _mission_folder(folder: Path, campaign: Path, k: int, entry) -> Path:
    """Mission ``k``'s folder as ``campaign.json`` names it: a sub-folder of the campaign
    folder (a name of its own, never a path out of it), or FlightError naming the field."""
    where = f"{campaign}, missions[{k}]"
    if not isinstance(entry, dict):
        raise FlightError(f"{where}: expected an object with a 'folder', got "
                          f"{type(entry).__name__}")  # fmt: skip
    name = entry.get("folder")
    if not isinstance(name, str) or not name:
        raise FlightError(f"{where}, field 'folder': expected the name of a mission folder, "
                          f"got {name!r}")  # fmt: skip
    sub = folder / name
    inside = Path(name).name == name and name not in (".", "..") and not Path(name).is_absolute()
    if not inside or sub.resolve().parent != folder.resolve():
        raise FlightError(f"{where}, field 'folder': {name!r} is not a sub-folder of the "
                          f"campaign folder {folder} (a flight is written only inside "
                          "it)")  # fmt: skip
    return sub


def _transfer_problem(transfer: str) -> str | None:
    if transfer in ("impulsive", "low-thrust"):
        return None
    return f"a {transfer} plan; fly replays impulsive and low-thrust plans only"


def _start_problem(injection) -> str | None:
    if injection is None:
        return None
    return ("a plan that starts from an injection orbit; fly starts from the first debris "
            "only so far (where on the injection orbit the launcher leaves the vehicle is "
            "not known)")


def _check_transfer(transfer: str, what: str) -> None:
    if (problem := _transfer_problem(transfer)) is not None:
        raise FlightError(f"{what}: {problem}")


def _check_start(injection, what: str) -> None:
    if (problem := _start_problem(injection)) is not None:
        raise FlightError(f"{what}: {problem}")


def _over_capacity(data: dict) -> str | None:
    """Why a ``solution.json`` is not flyable with its vehicle (its last note), or None."""
    if data.get("status") != "over_capacity":
        return None
    notes = [n for n in data.get("notes") or () if isinstance(n, str)]
    said = next((n for n in reversed(notes) if n.startswith("not flyable")), None)
    return said or "the plan needs more propellant than the vehicle's tank holds"


def _read_json(path: Path) -> dict:
    try:
        return json.loads(path.read_text(encoding="utf-8"))
    except FileNotFoundError:
        raise FlightError(f"{path.parent}: no {path.name}: not a run folder of sdc_cvx") from None
    except (OSError, UnicodeDecodeError, json.JSONDecodeError) as err:
        raise FlightError(f"{path}: unreadable ({err})") from None


def _naming(path: Path, err: Exception) -> str:
    """``err``'s message, prefixed with ``path`` unless it names it first already."""
    text = str(err)
    return text if text.startswith(str(path)) else f"{path}: {text}"
