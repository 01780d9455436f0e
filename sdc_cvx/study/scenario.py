"""Scenario files: catalog, mission parameters, solver options, candidate filters in one TOML.

A scenario file has four tables, each optional::

    [catalog]
    path = "debris.csv"        # relative to the scenario file
    format = "csv"             # csv | tle | omm | gtoc9; default from the extension
    start = 2020-05-24T00:00:00Z  # the date the RAANs and day 0 refer to (UTC when
                               # naive; an ISO string is fine); default the latest epoch
    strict = false             # true: refuse the catalog when the selection keeps an
                               # element set that is not an orbit of this model
    raan_rates = "j2"          # j2: the debris' first-order J2 RAAN rates; sgp4: each
                               # one's rate fitted to its SGP4 propagation over the
                               # mission window (Catalog.with_sgp4_rates)
    [mission]                  # exactly the fields of Mission
    n = 5
    tmax_days = 365.25
    deorbit_days = 0.0
    drift_altitude_km = [400.0, 1200.0]
    preopt_days = 61.0
    dv_max_mps = 1000.0
    [solver]                   # exactly the fields of SolverOptions
    backend = "HIGHS"
    time_limit_s = 60.0
    mip_gap = 1e-6
    [selection]                # candidate filters (sdc_cvx.inputs.selection.select); no key: none
    altitude_km = [600.0, 900.0]
    inclination_deg = [96.0, 100.0]
    max_eccentricity = 0.05    # the default; near-polar orbits are always dropped
    ids = ["43*"]              # shell-style patterns
    names = ["cosmos 2251*"]   # case-insensitive
    types = ["rocket-body"]    # rocket-body (R/B in the name), debris (DEB), payload
    exclude_ids = ["4350?"]

A fifth table, ``[campaign]``, makes the scenario a removal campaign (``python -m sdc_cvx
campaign``): K missions launched on given days, every ``[mission]`` key the default of
each mission::

    [campaign]
    launch_days = [0.0, 365.25, 730.5]   # or: missions = 3, first_launch_day = 0,
                                         #     period_days = 365.25
    n = [5, 5, 4]              # per mission, or one number [mission.n]; a range
                               # [n_min, n_max] per mission: between n_min and n_max
    tmax_days = 365.25         # per mission, or one number [mission.tmax_days]
    must_remove = ["43211"]    # removed by some mission [none]
    remove_all = false         # every candidate removed by some mission [false]

A missing ``[catalog]`` table, or one without ``path``, means the paper's Table 5 bundled
with the package (which has no epochs: ``catalog.start`` needs a path).  Missing keys keep
the defaults of :class:`Mission` and :class:`SolverOptions` (the paper's case, HiGHS) and
of :class:`Selection` (no filter).

Every problem is reported in a :class:`ScenarioError` with a one-line message that names
the file, the key as a dotted name (``mission.tmax_days``) and what is allowed.  Values
are checked for type first (an integer is fine where a number is expected, a boolean or
a string is not), then by the validation of :class:`Mission` and :class:`SolverOptions`
themselves, whose messages are re-labelled with the dotted key.  The candidate filters
are applied to the catalog read (:meth:`Selection.apply`): a pattern that matches no
debris is only found then.  The tables are checked by :mod:`~sdc_cvx.study.scenario_tables`
(:func:`~sdc_cvx.study.scenario_tables.scenario_fields`).
"""

from __future__ import annotations

import dataclasses
import difflib
import os
from collections.abc import Mapping
from dataclasses import dataclass, field
from datetime import datetime
from pathlib import Path

from ..errors import ScenarioError
from ..inputs.campaign import Campaign
from ..inputs.catalog import Catalog
from ..inputs.formats import EXTENSION_FORMATS, READERS
from ..inputs.mission import Mission
from ..inputs.selection import DEFAULT_MAX_ECCENTRICITY
from ..milp.types import MILP_BACKENDS, SolverOptions
from .scenario_tables import (
    CATALOG_FORMATS,
    PAPER_CASE,
    READABLE_FORMATS,
    TABLE_KEYS,
    Selection,
    scenario_fields,
    unsupported_format,
)
from .toml import read_toml, toml_value

__all__ = [
    "CATALOG_FORMATS",
    "EXTENSION_FORMATS",
    "MILP_BACKENDS",
    "READABLE_FORMATS",
    "Scenario",
    "ScenarioError",
    "Selection",
    "load",
]

_UNSET = {"catalog": "the latest epoch in the catalog", "mission": "none",
          "solver": "no limit / backend default",
          "selection": f"no filter; max_eccentricity {DEFAULT_MAX_ECCENTRICITY:g}",
          "campaign": "none", "vehicle": "unknown"}  # fmt: skip
"""What a key left out of each table means (comments of :meth:`Scenario.to_toml`)."""


@dataclass(frozen=True)
class Scenario:
    """What to solve and how: catalog, mission, solver options and candidate filters.

    Build it with :meth:`load` (a TOML file) and change it with :meth:`with_overrides`;
    both validate every value.  ``Scenario()`` is the paper's case with HiGHS.

    Attributes
    ----------
    catalog_path : Path or None
        Absolute path of the debris catalog; None for the paper's Table 5.
    catalog_format : str
        One of :data:`CATALOG_FORMATS` (``"csv"`` for the paper's table).
    mission : Mission
    solver : SolverOptions
    catalog_start : datetime or None
        Mission start date (UTC) the RAANs and day 0 refer to; None: the latest epoch
        of the catalog (or none, for a catalog without epochs).
    selection : Selection
        Candidate filters; the CLI ``run`` applies them to the catalog.
    campaign : Campaign or None
        The ``[campaign]`` table (``python -m sdc_cvx campaign``), its missions built
        from ``mission``; None for a single mission.
    catalog_strict : bool
        True: refuse the catalog when the selection keeps an element set that is not an
        orbit of this model; False (default): drop it with a warning line.
    catalog_raan_rates : {"j2", "sgp4"}
        The debris' RAAN rates the planner uses: ``"j2"`` (default), the first-order J2
        rates of the elements; ``"sgp4"``, each debris' rate fitted to its SGP4
        propagation over :meth:`rate_window_days`, applied to the selected candidates
        (:meth:`with_raan_rates`).
    source : Path or None
        The scenario file read, if any.  Not compared: two scenarios with the same
        content are equal wherever they were read from.
    catalog_values : Path, "csi" or None
        ``[catalog] values``: the table of each debris' value (``id,value``) read into
        the campaign (``objective = "max-value"``), or ``"csi"``: the Criticality of
        Spacecraft Index computed from the catalogue and ``catalog_masses``
        (:mod:`~sdc_cvx.study.scenario_values`).
    catalog_masses : Path or None
        ``[catalog] masses``: each debris' mass [kg] (``id,mass_kg``), for ``"csi"``.
    """

    catalog_path: Path | None = None
    catalog_format: str = "csv"
    mission: Mission = field(default_factory=Mission)
    solver: SolverOptions = field(default_factory=SolverOptions)
    catalog_start: datetime | None = None
    selection: Selection = field(default_factory=Selection)
    campaign: Campaign | None = None
    source: Path | None = field(default=None, compare=False)
    catalog_strict: bool = False
    catalog_raan_rates: str = "j2"
    catalog_values: Path | str | None = None
    catalog_values_columns: tuple[str, str] = ("id", "value")
    catalog_masses: Path | None = None
    catalog_masses_columns: tuple[str, str] = ("id", "mass_kg")

    # ------------------------------------------------------------------ reading
    @classmethod
    def load(cls, path: str | os.PathLike, *, catalog_path=None) -> Scenario:
        """Read and validate a scenario TOML file.

        ``catalog_path`` replaces the file's ``[catalog] path`` before it is checked (a
        catalog moved since: the file's own need not exist); relative to the current
        folder, its format told again unless the file gives one.

        Raises
        ------
        ScenarioError
            Unreadable file, invalid TOML, unknown table or key, wrong type, value out
            of range, missing catalog file or unsupported catalog format.
        """
        where = os.fspath(path)
        text, data = read_toml(path, "scenario file")
        if catalog_path is not None and isinstance(data.get("catalog", {}), dict):
            table = data.setdefault("catalog", {})
            table["path"] = os.fspath(Path.cwd() / Path(catalog_path).expanduser())
        source = Path(path).resolve()
        return cls(**scenario_fields(data, where, base=source.parent), source=source)

    def with_overrides(self, **changes) -> Scenario:
        """A copy with some values changed, validated like a file.

        Keys are dotted names (``**{"mission.n": 4}``) or plain field names: the
        fields of :class:`Mission`, :class:`SolverOptions` and :class:`Selection`
        (``n=4``, ``backend="SCIP"``, ``altitude_km=(600, 900)``) and
        ``catalog_path`` / ``catalog_format`` / ``catalog_start`` (or ``catalog`` /
        ``format`` / ``start``).  None means "not given" and changes nothing.  A relative
        catalog path is taken from the current directory; changing the path without
        the format chooses the format again from the extension.

        Raises
        ------
        ScenarioError
            Unknown key or any invalid value (the message names the dotted key).
        """
        return apply_overrides(self, changes, origin="overrides")

    def load_catalog(self, *, on_invalid: str = "raise") -> Catalog:
        """The debris catalog (the paper's Table 5 when ``catalog_path`` is None).

        Its RAANs are at ``catalog_start`` (default: the latest epoch); a catalog without
        epochs takes them as they are, at that date.  The candidate filters are not
        applied: see :meth:`select_candidates`, which reads with ``on_invalid="set
        aside"`` so that the filters act first.

        Raises
        ------
        CatalogError
            The file fails the catalog's validation.
        ScenarioError
            The format cannot be read yet.
        """
        if self.catalog_path is None:
            return Catalog.paper_case()
        reader = READERS.get(self.catalog_format)
        if reader is None:
            raise ScenarioError.collect(
                self._where(),
                [unsupported_format(self.catalog_format, self.catalog_path, chosen=False)],
            )
        return reader(self.catalog_path, start=self.catalog_start, on_invalid=on_invalid)

    def select_candidates(self):
        """``(kept, report)``: the catalog read, then the candidate filters, then the RAAN
        rates (:meth:`with_raan_rates`), as ``run`` does.

        The filters act first: element sets that are not orbits of this model are
        reported only when the filters keep them (check ``invalid`` in the report), or
        refused when ``catalog_strict``.

        Raises
        ------
        CatalogError
            The file fails the catalog's validation (or, strict, the selection keeps an
            element set that is not an orbit of this model; or SGP4 cannot propagate a
            debris kept over the window of its fitted RAAN rate).
        ValueError
            A pattern matches no debris (see :meth:`Selection.apply`).
        """
        catalog = self.load_catalog(on_invalid="set aside")
        kept, report = self.selection.apply(catalog, strict=self.catalog_strict)
        return self.with_raan_rates(kept), report

    def rate_window_days(self) -> float:
        """The window the RAAN rates are fitted over [days from the catalog's start]: the
        mission's ``tmax_days``, or a campaign's last launch day plus its ``tmax_days``."""
        if self.campaign is None:
            return float(self.mission.tmax_days)
        return max(day + mission.tmax_days
                   for day, mission in zip(self.campaign.launch_days, self.campaign.missions,
                                           strict=True))  # fmt: skip

    def with_raan_rates(self, catalog: Catalog) -> Catalog:
        """``catalog`` with the RAAN rates the scenario asks for (``catalog_raan_rates``).

        ``"sgp4"``: :meth:`Catalog.with_sgp4_rates` over :meth:`rate_window_days` (about
        0.1 ms per debris: apply it to the candidates kept, not to a whole catalogue);
        ``"j2"``: ``catalog`` itself.

        Raises
        ------
        CatalogError
            SGP4 cannot propagate a debris over the window (the debris named).
        """
        if self.catalog_raan_rates == "j2":
            return catalog
        return catalog.with_sgp4_rates(self.rate_window_days())

    # ------------------------------------------------------------------ writing
    def to_dict(self) -> dict:
        """The scenario as nested dicts (``catalog``, ``mission``, ``solver``); None if unset.

        ``catalog.start`` (an ISO-8601 string) and the ``selection`` table (the filters
        set) are there only when set: the content of a scenario without them, and so a
        sweep's ``scenario_sha``, is what it was before they existed.
        """
        data = {
            "catalog": {
                "path": None if self.catalog_path is None else str(self.catalog_path),
                "format": self.catalog_format,
            },
            "mission": self.mission.to_dict(),
            "solver": dataclasses.asdict(self.solver),
        }
        if self.catalog_start is not None:
            data["catalog"]["start"] = self.catalog_start.isoformat()
        if self.catalog_strict:
            data["catalog"]["strict"] = True
        if self.catalog_raan_rates != "j2":
            data["catalog"]["raan_rates"] = self.catalog_raan_rates
        if self.selection.to_dict():
            data["selection"] = self.selection.to_dict()
        if self.catalog_values is not None:
            data["catalog"]["values"] = str(self.catalog_values)
            if self.catalog_masses is None:
                data["catalog"]["values_columns"] = list(self.catalog_values_columns)
        if self.catalog_masses is not None:
            data["catalog"]["masses"] = str(self.catalog_masses)
            data["catalog"]["masses_columns"] = list(self.catalog_masses_columns)
        if self.campaign is not None:
            campaign = self.campaign.to_dict()
            data["campaign"] = {key: campaign[key] for key in (
                "launch_days", "n", "tmax_days", "must_remove") + ("remove_all",) * (
                "remove_all" in campaign)}  # fmt: skip
            if "n_min" in campaign:
                data["campaign"]["n"] = [[low, high] for low, high in zip(
                    campaign["n_min"], campaign["n"], strict=True)]  # fmt: skip
            if self.campaign.objective != "min-dv":
                data["campaign"]["objective"] = campaign["objective"]
                if not self.campaign.budgets_from_tank:  # else the tanks give them again
                    data["campaign"]["dv_budget_mps"] = campaign["dv_budget_mps"]
                if "price_per_value_mps" in campaign:
                    data["campaign"]["price_per_value_mps"] = campaign["price_per_value_mps"]
        if "vehicle" in data["mission"]:
            data["vehicle"] = data["mission"].pop("vehicle")
        return data

    def to_toml(self, *, start: datetime | None = None) -> str:
        """The scenario as used, every default filled in and the catalog path absolute.

        ``Scenario.load`` of this text gives back an equal scenario.  Values that are
        not set (solver options, None: no time limit, backend's threads and seed;
        ``catalog.start``; candidate filters) are left out and named in a comment,
        which means the same on reading; a ``mip_gap`` of None (the backend's own gap)
        cannot be written in TOML and reads back as the default 1e-6.  ``start``: the
        day 0 the run took where ``catalog.start`` is not set (the latest epoch of the
        catalog then), written so that a catalog file refreshed since gives the same day 0.
        """
        data = self.to_dict()
        pinned = self.catalog_start is None and start is not None
        data["catalog"]["start"] = start if pinned else self.catalog_start  # or not set
        data["catalog"]["raan_rates"] = self.catalog_raan_rates
        data["selection"] = dict.fromkeys(TABLE_KEYS["selection"]) | self.selection.to_dict()
        lines = ["# sdc_cvx scenario, as used: every default filled in."]
        if self.source is not None:
            lines.append("# Read from " + os.fspath(self.source).replace("\n", " "))
        for table, values in data.items():
            lines += ["", f"[{table}]"]
            if table == "catalog" and self.catalog_path is None:
                lines.append(f"# no path: {PAPER_CASE}")
                if self.catalog_raan_rates != "j2":
                    lines.append(f"raan_rates = {toml_value(self.catalog_raan_rates)}")
                lines += [f"{key} = {toml_value(values[key])}"
                          for key in ("values", "values_columns", "masses", "masses_columns")
                          if key in values]  # fmt: skip
                continue
            unset = [key for key, value in values.items() if value is None]
            if table == "catalog" and pinned:
                lines.append("# start: not set in the scenario; the catalog's latest epoch at "
                             "the run, kept")  # fmt: skip
            lines += [f"{key} = {toml_value(value)}" for key, value in values.items()
                      if value is not None]  # fmt: skip
            if unset:
                lines.append(f"# not set ({_UNSET[table]}): {', '.join(unset)}")
        return "\n".join(lines) + "\n"

    def _where(self) -> str:
        return "scenario" if self.source is None else os.fspath(self.source)


def load(path: str | os.PathLike) -> Scenario:
    """Read and validate a scenario TOML file (see :meth:`Scenario.load`)."""
    return Scenario.load(path)


def apply_overrides(scenario: Scenario, changes: Mapping, origin: str = "overrides") -> Scenario:
    """``scenario`` with ``changes`` applied (see :meth:`Scenario.with_overrides`).

    ``origin`` starts the error message (e.g. ``"command line"``).
    """
    data = scenario.to_dict()
    cwd = Path.cwd()
    problems = []
    format_given = any(
        changes.get(k) is not None for k in ("catalog_format", "catalog.format", "format")
    )
    for name, value in changes.items():
        if value is None:
            continue
        dotted = _dotted_name(name)
        if dotted is None:
            problems.append(f"unknown override {name!r}{_override_hint(name)}; "
                            f"{_allowed_overrides()}")
            continue
        table, key = dotted.split(".")
        if dotted == "catalog.path":
            if isinstance(value, str | os.PathLike):
                value = os.fspath(cwd / Path(value).expanduser())
            if not format_given:
                data["catalog"].pop("format", None)  # choose it again from the extension
        data.setdefault(table, {})[key] = value
        alternative = {"accel_mps2": "thrust_n", "thrust_n": "accel_mps2"}.get(key)
        if table == "vehicle" and alternative is not None:  # given one, the other goes
            data["vehicle"].pop(alternative, None)
    if problems:
        raise ScenarioError.collect(origin, problems)
    if data["catalog"]["path"] is None:
        del data["catalog"]["path"]
    return Scenario(**scenario_fields(data, origin, base=cwd), source=scenario.source)


def _dotted_name(name: str) -> str | None:
    """Dotted key of an override name, or None if unknown."""
    aliases = {"catalog": "catalog.path", "catalog_path": "catalog.path",
               "format": "catalog.format", "catalog_format": "catalog.format",
               "start": "catalog.start", "catalog_start": "catalog.start",
               "strict": "catalog.strict", "catalog_strict": "catalog.strict",
               "raan_rates": "catalog.raan_rates",
               "catalog_raan_rates": "catalog.raan_rates"}  # fmt: skip
    if name in aliases:
        return aliases[name]
    if "." in name:
        table, _, key = name.partition(".")
        return name if table in TABLE_KEYS and key in TABLE_KEYS[table] else None
    for table in ("mission", "solver", "selection", "vehicle"):
        if name in TABLE_KEYS[table]:
            return f"{table}.{name}"
    return None


def _override_hint(name: str) -> str:
    """`` (did you mean mission.tmax_days?)`` for a misspelt override, or nothing."""
    dotted = [f"{table}.{key}" for table, keys in TABLE_KEYS.items() for key in keys]
    close = difflib.get_close_matches(name, dotted, n=1)
    return f" (did you mean {close[0]}?)" if close else ""


def _allowed_overrides() -> str:
    return (
        "allowed: catalog_path, catalog_format, catalog_start, catalog_raan_rates, a field "
        "of Mission, SolverOptions, Selection or Vehicle, or a dotted key such as mission.n"
    )
