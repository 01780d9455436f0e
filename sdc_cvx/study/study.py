"""Study files: one base scenario and many overrides (a grid, a list of cases).

A study file is TOML::

    base = "paper.toml"              # a scenario file, relative to the study file
    # or inline tables: [base.mission], [base.solver], [base.catalog]
    # (no base at all: the paper's case with HiGHS)

    [grid]                           # dotted keys -> lists: the cartesian product
    "mission.tmax_days" = [300, 365.25, 450]
    "mission.n" = [4, 5, 6]

    [[cases]]                        # explicit scenarios, one table each
    label = "paper J2"               # optional readable label
    "mission.j2" = 1.086e-3

Unquoted dotted keys (``mission.n = [4, 5]``) and sub-tables (``[grid.mission]``) mean the
same.  The scenarios are the grid's product followed by the cases (a case is exactly one
scenario; it is not crossed with the grid); with neither, the base alone.  A relative
``catalog.path`` is taken from the study file's folder.

:func:`load_study` validates every scenario before anything runs: an unknown key or an
invalid value is a :class:`~sdc_cvx.errors.ScenarioError` naming the dotted key and
the cases.  A value that is valid but cannot be flown (a tiny ``tmax_days``) is not an
error of the study: its scenario fails when solved and is recorded as such.
"""

from __future__ import annotations

import hashlib
import itertools
import json
import os
import re
from collections.abc import Mapping, Sequence
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import pandas as pd

from ..errors import ScenarioError
from .scenario import Scenario
from .scenario_tables import TABLES
from .toml import read_toml, toml_line

_STUDY_KEYS = ("base", "grid", "cases")


_SCENARIO_TABLES = ("catalog", "mission", "solver", "selection", "vehicle")


_CASE_LABEL = "label"


_KEY_HASH_CHARS = 10


_SLUG_CHARS = 40


# ---------------------------------------------------------------------- the study
@dataclass(frozen=True)
class StudyScenario:
    """One scenario of a study.

    Attributes
    ----------
    key : str
        Stable id, also its folder name: a readable slug and a hash of the overrides
        (their validated values, sorted by key), e.g. ``tmax_days=300_n=4-1a2b3c4d5e``.
    label : str
        Readable label (``tmax_days=300 n=4``, or the case's ``label``).
    overrides : dict
        Dotted key -> validated value applied to the base.
    scenario : Scenario
        The base with the overrides, validated.
    """

    key: str
    label: str
    overrides: dict[str, Any]
    scenario: Scenario


@dataclass(frozen=True)
class Study:
    """A base scenario and the scenarios derived from it (see :func:`load_study`).

    Attributes
    ----------
    base : Scenario
    scenarios : tuple of StudyScenario
        The grid's product (first grid key slowest), then the cases.
    parameters : tuple of str
        Every dotted key that some scenario overrides, in order of appearance: the
        parameter columns of ``results.csv``.
    grid : dict
        Dotted key -> tuple of values, as written.
    cases : tuple of dict
        The explicit cases, as written (with their ``label`` if any).
    source : Path or None
        The study file read, if any.
    text : str or None
        Its text, copied to the output folder.
    """

    base: Scenario
    scenarios: tuple[StudyScenario, ...]
    parameters: tuple[str, ...]
    grid: dict[str, tuple] = field(default_factory=dict)
    cases: tuple[dict, ...] = ()
    source: Path | None = field(default=None, compare=False)
    text: str | None = field(default=None, compare=False, repr=False)

    def __len__(self) -> int:
        return len(self.scenarios)

    @classmethod
    def from_dict(
        cls,
        data: Mapping,
        *,
        where: str = "study",
        base_dir: str | os.PathLike | None = None,
        source: Path | None = None,
        text: str | None = None,
    ) -> Study:
        """Build and validate a study from parsed TOML (or a dict written in Python).

        ``base_dir`` (default the current directory) resolves a relative ``base`` file
        and relative catalog paths; ``where`` starts the error messages.

        Raises
        ------
        ScenarioError
            Every problem found, each naming the dotted key and the case.
        """
        base_dir = Path.cwd() if base_dir is None else Path(base_dir)
        problems: list[str] = []
        if data and not set(data) & set(_STUDY_KEYS) and set(data) <= set(TABLES) | {"defaults"}:
            raise ScenarioError.collect(where, [
                f"a scenario file (its tables: {', '.join(data)}), not a study: python -m "
                f"sdc_cvx run {where} runs it; a study has base, [grid] and/or [[cases]]"])
        for name in data:
            if name not in _STUDY_KEYS:
                problems.append(
                    f"unknown study key {name!r}; allowed: base (a scenario file or "
                    "[base.mission]/[base.solver]/[base.catalog]/[base.selection] tables), "
                    "[grid], [[cases]]"
                )
        base = _study_base(data.get("base"), where, base_dir, problems)
        grid = _study_grid(data.get("grid", {}), base_dir, problems)
        cases = _study_cases(data.get("cases", []), base_dir, problems)
        if problems:
            raise ScenarioError.collect(where, problems)
        return _expand(base, grid, cases, where, source=source, text=text)

    def table(self) -> pd.DataFrame:
        """The planned scenarios: ``key``, ``label`` and one column per parameter."""
        return pd.DataFrame([_identity(item, self.parameters) for item in self.scenarios])

    def to_toml(self) -> str:
        """A self-contained study: the base written inline, the grid and the cases."""
        lines = ["# sdc_cvx study" + (f", read from {self.source}" if self.source else "")]
        for table, values in self.base.to_dict().items():
            kept = {k: v for k, v in values.items() if v is not None}
            if table == "catalog" and self.base.catalog_path is None:
                continue  # the paper's Table 5
            lines += ["", f"[base.{table}]"] + [toml_line(k, v) for k, v in kept.items()]
        if self.grid:
            lines += ["", "[grid]"] + [toml_line(k, list(v)) for k, v in self.grid.items()]
        for case in self.cases:
            ordered = sorted(case.items(), key=lambda item: item[0] != _CASE_LABEL)
            lines += ["", "[[cases]]"] + [toml_line(k, v) for k, v in ordered]
        return "\n".join(lines) + "\n"


def load_study(path: str | os.PathLike) -> Study:
    """Read a study TOML file and validate every scenario (see the module docstring).

    Raises
    ------
    ScenarioError
        Unreadable file, invalid TOML, unknown study key, a grid entry that is not a
        non-empty array, a key that is not dotted, an unknown key or an invalid value in
        any scenario (named by dotted key and case), or duplicate scenarios.
    """
    where = os.fspath(path)
    text, data = read_toml(path, "study file")
    source = Path(path).resolve()
    return Study.from_dict(data, where=where, base_dir=source.parent, source=source, text=text)


def _study_base(value, where: str, base_dir: Path, problems: list[str]) -> Scenario:
    if value is None:
        return Scenario()
    if isinstance(value, str | os.PathLike):
        file = base_dir / Path(value).expanduser()
        try:
            return Scenario.load(file)
        except ScenarioError as err:
            problems.append(f"base = {value!r}: {err}")
            return Scenario()
    if not isinstance(value, Mapping):
        problems.append(
            f"base must be a scenario file name or tables [base.mission], [base.solver], "
            f"[base.catalog]; got {type(value).__name__}"
        )
        return Scenario()
    flat: dict[str, Any] = {}
    for table, values in value.items():
        if table not in _SCENARIO_TABLES:
            problems.append(
                f"unknown table [base.{table}]; allowed: "
                + ", ".join(f"base.{name}" for name in _SCENARIO_TABLES)
            )
        elif not isinstance(values, Mapping):
            problems.append(f"base.{table} must be a table ([base.{table}])")
        else:
            flat.update(_flatten(values, table))
    try:
        return Scenario().with_overrides(**_resolve_paths(flat, base_dir))
    except ScenarioError as err:
        problems += [f"base: {problem}" for problem in err.problems]
        return Scenario()


def _study_grid(grid, base_dir: Path, problems: list[str]) -> dict[str, tuple]:
    if not isinstance(grid, Mapping):
        problems.append("grid must be a table ([grid]) of dotted keys -> arrays of values")
        return {}
    out = {}
    for key, values in _flatten(grid).items():
        if not _dotted(key):
            problems.append(f"grid: {_not_dotted(key)}")
        elif not isinstance(values, list | tuple):
            problems.append(
                f"grid: {key} must be an array of the values to sweep, got {values!r} "
                f"(a fixed value belongs in the base)"
            )
        elif not values:
            problems.append(f"grid: {key} has no values")
        else:
            out[key] = tuple(_resolve_paths({key: v}, base_dir)[key] for v in values)
    return out


def _study_cases(cases, base_dir: Path, problems: list[str]) -> tuple[dict, ...]:
    if not isinstance(cases, list | tuple) or not all(isinstance(c, Mapping) for c in cases):
        problems.append("cases must be an array of tables ([[cases]]) of dotted keys -> values")
        return ()
    out = []
    for number, case in enumerate(cases, start=1):
        flat = _flatten(case)
        label = flat.pop(_CASE_LABEL, None)
        if label is not None and not isinstance(label, str):
            problems.append(f"case {number}: label must be a string, got {label!r}")
            label = None
        bad = [key for key in flat if not _dotted(key)]
        problems += [f"case {number}: {_not_dotted(key)}" for key in bad]
        case_out = _resolve_paths({k: v for k, v in flat.items() if k not in bad}, base_dir)
        if label is not None:
            case_out[_CASE_LABEL] = label
        out.append(case_out)
    return tuple(out)


def _expand(base: Scenario, grid: dict, cases: tuple, where: str, *, source, text) -> Study:
    """Every scenario of the study, validated; all problems raised together."""
    requested: list[tuple[str | None, dict]] = []  # (label given by a case, overrides)
    keys = list(grid)
    for values in itertools.product(*grid.values()):
        requested.append((None, dict(zip(keys, values, strict=True))))
    for case in cases:
        overrides = {k: v for k, v in case.items() if k != _CASE_LABEL}
        requested.append((case.get(_CASE_LABEL), overrides))
    if not requested:
        requested.append((None, {}))
    parameters = tuple(dict.fromkeys(k for _, overrides in requested for k in overrides))
    names = _short_names(parameters)

    invalid: dict[str, list[str]] = {}  # problem -> labels of the cases that have it
    duplicates: list[str] = []
    scenarios, seen = [], {}
    for given, overrides in requested:
        try:
            scenario = base.with_overrides(**overrides)
        except ScenarioError as err:
            label = given or _label(overrides, names)
            for problem in err.problems:
                invalid.setdefault(problem, []).append(label)
            continue
        effective = {key: _value(scenario, key) for key in overrides}
        label = given or _label(effective, names)  # validated values: 300 and 300.0 agree
        key = _scenario_key(label, effective)
        content = _canonical(scenario.to_dict())
        twin = seen.get(content)
        if twin is not None:
            duplicates.append(
                f"scenario {label!r} is given twice ([grid] or [[cases]] name the same values "
                "twice)" if label == twin else f"scenario {label!r} is the same scenario as "
                f"{twin!r}")  # fmt: skip
            continue
        seen[content] = label
        scenarios.append(StudyScenario(key, label, effective, scenario))
    problems = []
    for problem, labels in invalid.items():
        shown = ", ".join(repr(x) for x in labels[:3])
        more = f" and {len(labels) - 3} more" if len(labels) > 3 else ""
        problems.append(f"{problem} (case{'s' if len(labels) > 1 else ''} {shown}{more})")
    problems += duplicates
    if not problems and len({s.key for s in scenarios}) < len(scenarios):
        problems.append("two scenarios have the same key; give the cases distinct labels")
    if problems:
        raise ScenarioError.collect(where, problems)
    return Study(base, tuple(scenarios), parameters, dict(grid), tuple(cases), source, text)


def _flatten(table: Mapping, prefix: str = "") -> dict[str, Any]:
    """``{"mission": {"n": [4]}}`` -> ``{"mission.n": [4]}`` (no scenario value is a table)."""
    out = {}
    for key, value in table.items():
        name = f"{prefix}.{key}" if prefix else str(key)
        if isinstance(value, Mapping):
            out.update(_flatten(value, name))
        else:
            out[name] = value
    return out


def _dotted(key: str) -> bool:
    table, dot, name = key.partition(".")
    return bool(dot) and table in _SCENARIO_TABLES and bool(name)


def _not_dotted(key: str) -> str:
    return (
        f"key {key!r} is not a dotted key table.name of a scenario value (e.g. mission.n, "
        f"mission.tmax_days, solver.backend, catalog.path, vehicle.thrust_n)"
    )


def _resolve_paths(flat: dict, base_dir: Path) -> dict:
    """Relative catalog paths are taken from the study file's folder."""
    out = dict(flat)
    value = out.get("catalog.path")
    if isinstance(value, str | os.PathLike):
        out["catalog.path"] = os.fspath(base_dir / Path(value).expanduser())  # absolute stays
    return out


def _value(scenario: Scenario, dotted: str):
    """The value of a dotted key in a scenario, also when ``to_dict`` leaves it out (a
    selection filter, ``catalog.strict`` or ``catalog.raan_rates`` at its default)."""
    table, _, key = dotted.partition(".")
    values = scenario.to_dict().get(table, {})
    if key in values:
        return values[key]
    if dotted == "catalog.strict":
        return scenario.catalog_strict
    if dotted == "catalog.raan_rates":
        return scenario.catalog_raan_rates
    if table == "selection":
        value = getattr(scenario.selection, key)
        return list(value) if isinstance(value, tuple) else value
    return None


def _short_names(parameters: Sequence[str]) -> dict[str, str]:
    """``mission.n`` -> ``n`` where the short name is unambiguous."""
    shorts = [p.partition(".")[2] for p in parameters]
    return {p: s if shorts.count(s) == 1 else p for p, s in zip(parameters, shorts, strict=True)}


def _show_value(value) -> str:
    if isinstance(value, bool):
        return "true" if value else "false"
    if isinstance(value, float):
        return f"{value:g}"
    if isinstance(value, list | tuple):
        return "[" + ",".join(_show_value(v) for v in value) + "]"
    if isinstance(value, str) and os.sep in value:
        return Path(value).name  # a catalog path: its file name
    return str(value)


def _label(overrides: Mapping, names: Mapping[str, str]) -> str:
    if not overrides:
        return "base"
    return " ".join(f"{names.get(k, k)}={_show_value(v)}" for k, v in overrides.items())


def _scenario_key(label: str, effective: Mapping) -> str:
    digest = hashlib.sha1(_canonical(effective).encode()).hexdigest()[:_KEY_HASH_CHARS]
    slug = label.replace(" ", "_").replace(",", "-").replace("[", "").replace("]", "")
    slug = re.sub(r"[^A-Za-z0-9._=+-]+", "-", slug).strip("-._")
    slug = slug[:_SLUG_CHARS].rstrip("-._") or "scenario"
    return f"{slug}-{digest}"


def _canonical(data) -> str:
    return json.dumps(data, sort_keys=True, default=list, allow_nan=True)


def _plain(value):
    """A TOML-writable value (tuples as lists)."""
    if isinstance(value, tuple | list):
        return [_plain(v) for v in value]
    return value


def _cell(value):
    """A results-table cell: scalars as they are, arrays as JSON, None empty."""
    if value is None:
        return None
    if isinstance(value, tuple | list):
        return json.dumps(_plain(value))
    return value


def _identity(item: StudyScenario, parameters: Sequence[str]) -> dict:
    row = {"key": item.key, "label": item.label}
    for name in parameters:
        row[name] = _cell(_value(item.scenario, name))
    return row
