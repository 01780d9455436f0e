"""The tables of a scenario file, checked: :func:`scenario_fields` turns them into the
fields of a :class:`~sdc_cvx.study.scenario.Scenario`, or raises every problem at once.

Each table's keys and types (:data:`TABLE_KEYS`), the candidate filters of
``[selection]`` (:class:`Selection`), the catalog's path, format and start date, and the
``[campaign]`` table are checked here.  A problem names the key as a dotted name
(``mission.tmax_days``) and what is allowed; values are checked for type first (an
integer is fine where a number is expected, a boolean or a string is not), then by the
validation of :class:`~sdc_cvx.inputs.mission.Mission` and
:class:`~sdc_cvx.milp.types.SolverOptions` themselves, whose messages are re-labelled
with the dotted key.
"""

from __future__ import annotations

import dataclasses
import difflib
import math
import re
import typing
from collections.abc import Mapping
from dataclasses import dataclass
from datetime import UTC, date, datetime, time
from pathlib import Path

from ..errors import ScenarioError
from ..inputs.campaign import DEFAULT_PERIOD_DAYS, Campaign
from ..inputs.catalog import RAAN_RATES, Catalog
from ..inputs.formats import EXTENSION_FORMATS, FORMATS, READERS, sniff_format
from ..inputs.mission import Mission, MissionError
from ..inputs.selection import OBJECT_TYPES, select
from ..inputs.vehicle import Vehicle
from ..milp.types import MILP_BACKENDS, SolverOptions
from .scenario_values import catalog_values

CATALOG_FORMATS = FORMATS
"""Catalog formats a scenario may name (:data:`~sdc_cvx.inputs.formats.FORMAT_TABLE`)."""
READABLE_FORMATS = FORMATS
"""Formats that can be read today (a format without a reader would be refused clearly)."""

PAPER_CASE = "the paper's Table 5 bundled with sdc_cvx"
"""The catalog of a scenario without ``catalog.path``, in words."""


@dataclass(frozen=True)
class Selection:
    """Candidate filters of a scenario (its ``[selection]`` table), validated.

    The arguments of :func:`sdc_cvx.inputs.selection.select`; ``Selection()`` filters nothing
    (eccentric orbits, ``e > 0.05``, and near-polar ones are dropped all the same).

    Attributes
    ----------
    altitude_km, inclination_deg : (low, high) or None
        Keep the debris with the altitude [km] / inclination [deg] in [low, high].
    max_eccentricity : float or None
        Drop ``e > max_eccentricity``; None: 0.05, ``inf``: keep every eccentricity.
    ids, names, exclude_ids : tuple of str
        Shell-style patterns: keep the ids / names (case-insensitive) matching one
        (none given: every debris), drop the ids matching one.
    types : tuple of str
        Keep the objects of these types (``rocket-body``, ``debris``, ``payload``, told
        from the name: :func:`sdc_cvx.inputs.selection.object_type`); none: every type.
    """

    altitude_km: tuple[float, float] | None = None
    inclination_deg: tuple[float, float] | None = None
    max_eccentricity: float | None = None
    ids: tuple[str, ...] = ()
    names: tuple[str, ...] = ()
    exclude_ids: tuple[str, ...] = ()
    types: tuple[str, ...] = ()

    def __post_init__(self):
        problems = []
        for name in ("altitude_km", "inclination_deg"):
            bounds = getattr(self, name)
            if bounds is not None and not bounds[0] <= bounds[1]:
                problems.append(f"{name} must be [low, high] with low <= high, got {list(bounds)}")
        if self.max_eccentricity is not None and not self.max_eccentricity >= 0.0:
            problems.append(f"max_eccentricity must be >= 0, got {self.max_eccentricity!r}")
        for name in ("ids", "names", "exclude_ids"):
            if any(not pattern.strip() for pattern in getattr(self, name)):
                problems.append(f"{name} must not hold an empty pattern, got {getattr(self, name)}")
        unknown = [kind for kind in self.types if kind not in OBJECT_TYPES]
        if unknown:
            problems.append(f"types must hold {', '.join(OBJECT_TYPES)}, got {list(unknown)}")
        if problems:
            raise ValueError("; ".join(problems))

    def to_dict(self) -> dict:
        """The filters that are set (lists for arrays); empty for ``Selection()``."""
        return {key: list(value) if isinstance(value, tuple) else value
                for key, value in dataclasses.asdict(self).items()
                if value is not None and value != ()}  # fmt: skip

    def apply(self, catalog: Catalog, *, strict: bool = False):
        """``(kept, report)`` of :func:`sdc_cvx.inputs.selection.select` with these filters.

        Raises
        ------
        ValueError
            A pattern of ``ids`` or ``names`` matches no debris, or ``names`` or
            ``types`` on a catalog without names.
        CatalogError
            With ``strict``: the filters keep an element set of ``catalog.invalid``.
        """
        return select(catalog, altitude_km=self.altitude_km, inclination_deg=self.inclination_deg,
                      eccentricity_max=self.max_eccentricity, ids=self.ids or None,
                      names=self.names or None, exclude_ids=self.exclude_ids or None,
                      types=self.types or None, strict=strict)  # fmt: skip


class _Limit(float):
    """Type of a number that may be ``inf`` (``selection.max_eccentricity``: no limit)."""


TABLES = ("catalog", "mission", "solver", "selection", "campaign", "vehicle")
"""The tables a scenario file may have."""
_CATALOG_KEYS = ("path", "format", "start", "strict", "raan_rates", "values", "values_columns",
                 "masses", "masses_columns")  # fmt: skip
_MISSION_KEYS = tuple(f.name for f in dataclasses.fields(Mission) if f.name != "vehicle")
_VEHICLE_KEYS = tuple(f.name for f in dataclasses.fields(Vehicle))
_SOLVER_KEYS = tuple(f.name for f in dataclasses.fields(SolverOptions))
_SELECTION_KEYS = tuple(f.name for f in dataclasses.fields(Selection))
_CAMPAIGN_KEYS = ("launch_days", "missions", "first_launch_day", "period_days", "n", "tmax_days",
                  "must_remove", "remove_all", "objective", "dv_budget_mps",
                  "price_per_value_mps")  # fmt: skip
TABLE_KEYS = {"catalog": _CATALOG_KEYS, "mission": _MISSION_KEYS, "solver": _SOLVER_KEYS,
              "selection": _SELECTION_KEYS, "campaign": _CAMPAIGN_KEYS,
              "vehicle": _VEHICLE_KEYS}  # fmt: skip
"""The keys each table may hold."""
_TYPES = {
    "catalog": {"path": str, "format": str, "start": object, "strict": bool,
                "raan_rates": str, "values": str, "values_columns": tuple[str, ...],
                "masses": str, "masses_columns": tuple[str, ...]},
    "mission": typing.get_type_hints(Mission),
    "solver": typing.get_type_hints(SolverOptions),
    "selection": typing.get_type_hints(Selection) | {"max_eccentricity": _Limit | None},
    "campaign": {
        "launch_days": object,
        "missions": int,
        "first_launch_day": float,
        "period_days": float,
        "n": object,
        "tmax_days": object,
        "must_remove": tuple[str, ...],
        "remove_all": bool,
        "objective": str,
        "dv_budget_mps": object,
        "price_per_value_mps": float,
    },  # launch_days, n, tmax_days, dv_budget_mps: _campaign
    "vehicle": typing.get_type_hints(Vehicle),
}


def scenario_fields(data: Mapping, where: str, *, base: Path) -> dict:
    """The fields of a :class:`~sdc_cvx.study.scenario.Scenario` from its parsed tables.

    ``base`` is the folder a relative ``catalog.path`` starts from; ``where`` (the file,
    or ``"command line"``) starts the error message.

    Raises
    ------
    ScenarioError
        Every problem of the tables at once: unknown table or key, wrong type, value out
        of range, missing catalog file or unsupported catalog format.
    """
    problems: list[str] = []
    tables = {}
    for name, table in data.items():
        if name not in TABLES:
            if isinstance(table, Mapping):
                problems.append(
                    f"unknown table [{name}]{_hint(name, TABLES)}; "
                    f"allowed tables: {', '.join(TABLES)}"
                )
            else:
                owner = [t for t in TABLES if name in TABLE_KEYS[t]]
                hint = f" (did you mean {owner[0]}.{name}?)" if owner else ""
                problems.append(
                    f"key {name!r} outside a table{hint}; "
                    f"keys go in [catalog], [mission], [solver], [selection], [campaign] "
                    "or [vehicle]"
                )
        elif not isinstance(table, Mapping):
            problems.append(f"{name} must be a table ([{name}]), got {_kind(table)}")
        else:
            tables[name] = _checked_table(name, table, problems)
    catalog = tables.get("catalog", {})
    catalog_path, catalog_format = _catalog(catalog, base, problems)
    start = _start(catalog.get("start"), catalog_path, problems)
    mission_values = tables.get("mission", {})
    if "vehicle" in tables:
        vehicle = _make(Vehicle, "vehicle", tables["vehicle"], problems)
        # a vehicle refused is said once: not again as a low-thrust mission without one
        mission_values = mission_values | ({"vehicle": vehicle} if vehicle is not None
                                           else {"transfer": "impulsive"})  # fmt: skip
    mission = _make(Mission, "mission", mission_values, problems)
    solver = _make(SolverOptions, "solver", tables.get("solver", {}), problems)
    selection = _make(Selection, "selection", tables.get("selection", {}), problems)
    strict = catalog.get("strict", False)
    if strict and catalog_path is None:
        problems.append(f"catalog.strict needs catalog.path ({PAPER_CASE} is all orbits)")
    raan_rates = catalog.get("raan_rates", "j2").lower()
    if raan_rates not in RAAN_RATES:
        problems.append(
            f"catalog.raan_rates must be one of {', '.join(RAAN_RATES)} (j2: the first-order "
            "J2 rates of the elements; sgp4: each debris' rate fitted to its SGP4 "
            f"propagation), got {_show(catalog['raan_rates'])}"
        )
    values, values_path, masses_path = catalog_values(catalog, base, catalog_path,
                                                      catalog_format, start, problems)
    campaign = None
    if "campaign" in tables and mission is not None:
        campaign = _campaign(tables["campaign"], mission, problems, values)
        if (values_path is not None and campaign is not None
                and campaign.objective == "min-dv"):  # fmt: skip
            problems.append("catalog.values is for objective = 'max-value' or 'value-per-dv' "
                            "(the campaign's objective is 'min-dv', which removes n debris "
                            "per mission whatever their value)")  # fmt: skip
    elif values_path is not None:
        problems.append("catalog.values is for a campaign with objective = 'max-value' "
                        "([campaign] table)")  # fmt: skip
    if problems:
        raise ScenarioError.collect(where, problems)
    return {"catalog_path": catalog_path, "catalog_format": catalog_format, "mission": mission,
            "solver": solver, "catalog_start": start, "selection": selection,
            "campaign": campaign, "catalog_strict": strict,
            "catalog_raan_rates": raan_rates, "catalog_values": values_path,
            "catalog_values_columns": tuple(catalog.get("values_columns", ("id", "value"))),
            "catalog_masses": masses_path,
            "catalog_masses_columns": tuple(catalog.get("masses_columns",
                                                        ("id", "mass_kg")))}  # fmt: skip


def _campaign(values: dict, mission: Mission, problems: list[str],
              debris_values: dict) -> Campaign | None:  # fmt: skip
    """The ``[campaign]`` table as a :class:`Campaign` of ``mission``s (problems reported);
    ``debris_values`` from ``catalog.values``."""
    before = len(problems)
    days = values.get("launch_days")
    if days is not None and not (
        isinstance(days, list | tuple) and days and all(_typed(d, float)[1] is None for d in days)
    ):
        problems.append(f"campaign.launch_days must be a non-empty array of numbers [days], "
                        f"got {_show(days)}")  # fmt: skip
    for key, kind, one, words in (("n", int, "an integer", "integers"),
                                  ("tmax_days", float, "a number", "numbers"),
                                  ("dv_budget_mps", float, "a number", "numbers")):  # fmt: skip
        value = values.get(key)
        if value is None or _typed(value, kind)[1] is None:
            continue

        def fits(v, kind=kind, key=key):  # n: an integer or an [n_min, n_max] pair
            pair = key == "n" and isinstance(v, list | tuple) and len(v) == 2
            return all(_typed(w, kind)[1] is None for w in v) if pair else \
                _typed(v, kind)[1] is None  # fmt: skip

        if not (isinstance(value, list | tuple) and all(fits(v) for v in value)):
            also = " ([n_min, n_max] pairs too)" if key == "n" else ""
            problems.append(f"campaign.{key} must be {one} or an array of {words}{also} "
                            f"(one per launch), got {_show(value)}")  # fmt: skip
    yearly = [key for key in ("missions", "first_launch_day", "period_days") if key in values]
    if days is not None and yearly:
        problems.append(
            f"campaign: give launch_days, or missions (with first_launch_day and "
            f"period_days), not both; got launch_days and {', '.join(yearly)}"
        )
    elif days is None and "missions" not in values:
        problems.append(
            "campaign: needs launch_days = [day, ...] or missions = K (launches "
            "period_days apart from first_launch_day)"
        )
    if len(problems) > before:
        return None
    options = {"n": values.get("n"), "tmax_days": values.get("tmax_days"),
               "must_remove": values.get("must_remove", ()),
               "remove_all": values.get("remove_all", False)}  # fmt: skip
    if values.get("objective", "min-dv") != "min-dv" or "dv_budget_mps" in values:
        budget = values.get("dv_budget_mps", ())
        options |= {"objective": values.get("objective", "min-dv"),
                    "dv_budget_mps": budget if isinstance(budget, list | tuple) else [budget],
                    "values": debris_values,
                    "price_per_value_mps": values.get("price_per_value_mps")}  # fmt: skip
    try:
        if days is not None:
            return Campaign.of([float(d) for d in days], mission, **options)
        return Campaign.yearly(values["missions"], mission,
                               first_launch_day=values.get("first_launch_day", 0.0),
                               period_days=values.get("period_days", DEFAULT_PERIOD_DAYS),
                               **options)  # fmt: skip
    except MissionError as err:
        problems.append("campaign: " + str(err).removeprefix("invalid campaign: "))
        return None


def _checked_table(table: str, values: Mapping, problems: list[str]) -> dict:
    """The values of ``table`` with known keys and the right types (others reported)."""
    allowed = TABLE_KEYS[table]
    out = {}
    for key, value in values.items():
        dotted = f"{table}.{key}"
        if key not in allowed:
            problems.append(
                f"unknown key {dotted}{_hint(key, allowed)}; "
                f"allowed keys in [{table}]: {', '.join(allowed)}"
            )
            continue
        checked, problem = _typed(value, _TYPES[table][key])
        if problem:
            problems.append(f"{dotted} must be {problem}, got {_show(value)}")
        else:
            out[key] = checked
    return out


def _typed(value, kind):
    """``(converted value, None)`` or ``(None, expected type in words)``."""
    args = typing.get_args(kind)
    if type(None) in args:  # X | None: None (from to_dict or Python) keeps the default
        if value is None:
            return None, None
        kind = next(arg for arg in args if arg is not type(None))
    if kind is bool:
        return (value, None) if isinstance(value, bool) else (None, "a boolean (true or false)")
    if kind is int:
        ok = isinstance(value, int) and not isinstance(value, bool)
        return (value, None) if ok else (None, "an integer")
    if kind is float:
        ok = isinstance(value, int | float) and not isinstance(value, bool)
        if ok and math.isfinite(value):
            return float(value), None
        return None, "a finite number"
    if kind is _Limit:
        ok = isinstance(value, int | float) and not isinstance(value, bool)
        return (float(value), None) if ok and not math.isnan(value) else (None, "a number or inf")
    if kind is str:
        return (value, None) if isinstance(value, str) else (None, "a string")
    if typing.get_origin(kind) is tuple:
        args = typing.get_args(kind)  # of the tuple itself (X | None was unwrapped above)
        if len(args) == 2 and args[1] is Ellipsis:  # tuple[str, ...]: any number of ids
            ok = isinstance(value, list | tuple) and all(isinstance(v, str) for v in value)
            return (tuple(value), None) if ok else (None, "an array of strings")
        size = len(args)
        ok = isinstance(value, list | tuple) and len(value) == size
        ok = ok and all(_typed(item, float)[1] is None for item in value)
        if ok:
            return tuple(float(item) for item in value), None
        return None, f"an array of {size} numbers"
    return value, None  # a type this module does not know: the dataclass checks it


def _make(cls, table: str, values: dict, problems: list[str]):
    """``cls(**values)``, its validation messages re-labelled with dotted keys."""
    if table == "solver" and "backend" in values:
        backend = values["backend"].upper()
        if backend not in MILP_BACKENDS:
            problems.append(
                f"solver.backend must be a MILP backend, one of "
                f"{', '.join(MILP_BACKENDS)}; got {_show(values['backend'])}"
            )
            del values["backend"]
    if table == "solver" and "fallback" in values:
        unknown = [b for b in values["fallback"] if str(b).upper() not in MILP_BACKENDS]
        if unknown:
            problems.append(
                f"solver.fallback must name MILP backends, from "
                f"{', '.join(MILP_BACKENDS)}; got {', '.join(_show(b) for b in unknown)}"
            )
            del values["fallback"]
    try:
        return cls(**values)
    except (MissionError, ValueError) as err:
        problems += _relabel(table, str(err))
        return None


def _relabel(table: str, message: str) -> list[str]:
    """``"tmax_days must be > 0, got -1"`` -> ``"mission.tmax_days must be > 0, got -1"``.

    A problem that involves several keys names every key it mentions.
    """
    keys = TABLE_KEYS[table]
    out = []
    for prefix in ("invalid mission: ", "invalid vehicle: ", "invalid solver options: "):
        message = message.removeprefix(prefix)
    for problem in message.split("; "):
        first = problem.split(" ", 1)[0]
        if first in keys and problem.startswith(f"{first} must"):
            out.append(f"{table}.{problem}")
        else:
            named = [f"{table}.{key}" for key in keys if re.search(rf"\b{key}\b", problem)]
            out.append(f"{', '.join(named) or table}: {problem}")
    return out


def _catalog(values: dict, base: Path, problems: list[str]) -> tuple[Path | None, str]:
    """Resolved catalog path (None: paper case) and format; problems reported."""
    fmt = values.get("format")
    known = True
    if fmt is not None:
        fmt = fmt.lower()
        if fmt not in CATALOG_FORMATS:
            problems.append(
                f"catalog.format must be one of {', '.join(CATALOG_FORMATS)}, "
                f"got {_show(values['format'])}"
            )
            fmt, known = "csv", False
    if "path" not in values:
        if known and fmt is not None and fmt != "csv":
            problems.append(
                f"catalog.format = {fmt!r} needs catalog.path (without a path the "
                f"catalog is {PAPER_CASE}, a CSV table)"
            )
        return None, "csv"
    path = (base / Path(values["path"]).expanduser()).resolve()
    if not path.exists():
        problems.append(f"catalog.path: file not found: {path}")
    elif path.is_dir():
        problems.append(f"catalog.path: is a directory, not a catalog file: {path}")
    if not known:
        return path, fmt
    chosen = fmt is None
    if chosen:  # the content decides; the extension only when the content cannot tell
        fmt = (sniff_format(path) if path.is_file() else None) or EXTENSION_FORMATS.get(
            path.suffix.lower()
        )
        if fmt is None:
            problems.append(
                f"catalog.format: cannot tell the format of {path.name} from its "
                f"content or its extension; set catalog.format to one of "
                f"{', '.join(CATALOG_FORMATS)}"
            )
            return path, "csv"
    if fmt not in READERS:
        problems.append(f"catalog.format: {unsupported_format(fmt, path, chosen)}")
    return path, fmt


def _start(value, catalog_path: Path | None, problems: list[str]) -> datetime | None:
    """``catalog.start`` as a UTC datetime (naive: UTC; a date: its midnight), or None."""
    if value is None:
        return None
    stamp = value
    if isinstance(value, str):
        try:
            stamp = datetime.fromisoformat(value.strip())
        except ValueError:
            stamp = None
    elif isinstance(value, date) and not isinstance(value, datetime):
        stamp = datetime.combine(value, time())
    if not isinstance(stamp, datetime):
        problems.append(
            f"catalog.start must be a date and time, a TOML datetime or an ISO-8601 string "
            f"such as 2020-05-24T12:00:00Z; got {_show(value)}"
        )
        return None
    if catalog_path is None:
        problems.append(
            f"catalog.start needs catalog.path: {PAPER_CASE} has no epochs, its RAANs are "
            f"at the mission start whatever its date"
        )
    stamp = datetime.combine(stamp.date(), stamp.timetz())  # a plain datetime, not pandas'
    return stamp.replace(tzinfo=UTC) if stamp.tzinfo is None else stamp.astimezone(UTC)


def unsupported_format(fmt: str, path: Path, chosen: bool) -> str:
    how = f" (chosen from the extension {path.suffix!r} of catalog.path)" if chosen else ""
    return (
        f"format {fmt!r} is not supported yet{how}; formats that can be read today: "
        f"{', '.join(READABLE_FORMATS)}"
    )


def _hint(name: str, allowed) -> str:
    close = difflib.get_close_matches(name, allowed, n=1)
    return f" (did you mean {close[0]}?)" if close else ""


def _kind(value) -> str:
    if isinstance(value, bool):
        return "boolean"
    for kind, word in ((int, "integer"), (float, "float"), (str, "string"),
                       (list, "array"), (tuple, "array"), (Mapping, "table")):  # fmt: skip
        if isinstance(value, kind):
            return word
    return type(value).__name__


def _show(value) -> str:
    if isinstance(value, bool):
        shown = "true" if value else "false"
    elif isinstance(value, Mapping):
        return "a table"
    else:
        shown = repr(value)
    return f"{shown} ({_kind(value)})"
