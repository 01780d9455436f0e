"""Trade studies: one base scenario, many overrides, solved in parallel, nothing lost.

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
invalid value is a :class:`~sdc_cvx.scenario.ScenarioError` naming the dotted key and
the cases.  A value that is valid but cannot be flown (a tiny ``tmax_days``) is not an
error of the study: its scenario fails when solved and is recorded as such.

:func:`run_study` solves the scenarios on a local process pool, on an existing Dask
cluster (``scheduler="tcp://host:8786"``) or on any ``concurrent.futures`` executor;
the work is the same top-level function :func:`solve_scenario` in every case, taking a
scenario's TOML text and returning a plain dict that never carries an exception.  The
output folder::

    out_dir/study.toml                       the study (verbatim copy, or written out)
    out_dir/results.csv                      one row per finished scenario, rewritten
                                             atomically after each one
    out_dir/scenarios/<key>/scenario.toml    the scenario as run (written first)
    out_dir/scenarios/<key>/solution.json    written as soon as the scenario is solved
    out_dir/scenarios/<key>/error.txt        or why it failed

``resume=True`` on the same folder skips every scenario already in ``results.csv`` with a
terminal status, so a killed sweep restarted finishes with each scenario exactly once.
:func:`sweep` is the one-call version for notebooks and :func:`plot_sweep` draws total ΔV
against any swept parameter.
"""

from __future__ import annotations

import concurrent.futures as cf
import contextlib
import ctypes
import dataclasses
import hashlib
import itertools
import json
import math
import multiprocessing
import os
import re
import sys
import time
import tomllib
import traceback
import warnings
from collections.abc import Callable, Iterator, Mapping, Sequence
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any, NamedTuple

import numpy as np
import pandas as pd
import tomli_w

from ..planner.sequential import MissionInfeasible, SolverFailure, solve
from ..report.run_folder import new_run_folder, write_atomic
from .scenario import Scenario, ScenarioError, read_toml

__all__ = [
    "FAILURE_STATUSES",
    "RESULT_COLUMNS",
    "SOLVED_STATUSES",
    "Study",
    "StudyScenario",
    "SweepError",
    "SweepProgress",
    "load_study",
    "plot_sweep",
    "run_study",
    "solve_scenario",
    "sweep",
]

SOLVED_STATUSES = ("converged", "converged_unconfirmed", "iteration_limit", "time_limit")
"""Statuses of a solved scenario (the :attr:`Solution.status` values)."""
FAILURE_STATUSES = ("infeasible", "solver_failure", "error")
"""Statuses of a scenario that ran and gave no solution: ``infeasible``
(:class:`MissionInfeasible`), ``solver_failure`` (:class:`SolverFailure`), ``error``
(anything else, e.g. an unreadable catalog).  These are terminal: a resume does not run
them again."""
LOST = "lost"
"""Status of a scenario whose task never returned (worker process killed, cluster lost,
cancelled): not terminal, a resume runs it again."""

RESULT_COLUMNS = (
    "status",
    "path",
    "total_dv_mps",
    "total_duration_days",
    "iterations",
    "seconds",
    "backend",
    "error",
)
"""Columns of ``results.csv`` that come from the solve, after ``key``, ``label`` and the
swept parameters (dotted names), and before ``scenario_sha``."""

_STUDY_KEYS = ("base", "grid", "cases")
_SCENARIO_TABLES = ("catalog", "mission", "solver", "selection")
_CASE_LABEL = "label"
_KEY_HASH_CHARS = 10
_SLUG_CHARS = 40
_LOCK_NAME = ".sweep.lock"
_PANDAS_MAJOR = int(pd.__version__.split(".")[0])


class SweepError(RuntimeError):
    """The output folder cannot take this sweep (results of another study, a sweep
    already writing there, results present without ``resume``) or no executor."""


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
            lines += ["", f"[base.{table}]"] + [_toml_line(k, v) for k, v in kept.items()]
        if self.grid:
            lines += ["", "[grid]"] + [_toml_line(k, list(v)) for k, v in self.grid.items()]
        for case in self.cases:
            ordered = sorted(case.items(), key=lambda item: item[0] != _CASE_LABEL)
            lines += ["", "[[cases]]"] + [_toml_line(k, v) for k, v in ordered]
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
            duplicates.append(f"scenario {label!r} is the same scenario as {twin!r}")
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
        f"mission.tmax_days, solver.backend, catalog.path)"
    )


def _resolve_paths(flat: dict, base_dir: Path) -> dict:
    """Relative catalog paths are taken from the study file's folder."""
    out = dict(flat)
    value = out.get("catalog.path")
    if isinstance(value, str | os.PathLike):
        out["catalog.path"] = os.fspath(base_dir / Path(value).expanduser())  # absolute stays
    return out


def _value(scenario: Scenario, dotted: str):
    table, _, key = dotted.partition(".")
    return scenario.to_dict()[table][key]


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


def _toml_line(key: str, value) -> str:
    """``key = value`` with arrays inline; a dotted key is quoted (one key, not tables)."""
    quoted = tomli_w.dumps({key: 0}).rstrip("\n").removesuffix(" = 0")
    return f"{quoted} = {_toml_value(value)}"


def _toml_value(value) -> str:
    if isinstance(value, list | tuple):
        return "[" + ", ".join(_toml_value(v) for v in value) + "]"
    return tomli_w.dumps({"v": value}).removeprefix("v = ").rstrip("\n")


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


# ---------------------------------------------------------------------- the worker
def solve_scenario(scenario_toml: str, key: str = "") -> dict:
    """Solve one scenario given as TOML text (``Scenario.to_toml``); never raises.

    This is the function sent to worker processes and Dask workers: top-level and
    picklable, its input and output plain text and numbers.

    Returns
    -------
    dict
        ``key``, the :data:`RESULT_COLUMNS` (``status`` one of :data:`SOLVED_STATUSES`
        or :data:`FAILURE_STATUSES`; ``path`` as ``"5->8->2"``; NaN where unknown),
        ``solution_json`` (the ``solution.json`` text, or None) and ``traceback`` (for
        an ``error``, else None).
    """
    start = time.perf_counter()
    row: dict[str, Any] = {
        "key": key,
        "status": "error",
        "path": None,
        "total_dv_mps": math.nan,
        "total_duration_days": math.nan,
        "iterations": None,
        "seconds": math.nan,
        "backend": None,
        "error": None,
        "solution_json": None,
        "traceback": None,
    }
    try:
        data = tomllib.loads(scenario_toml)
        scenario = Scenario().with_overrides(**_flatten(data))
        row["backend"] = scenario.solver.backend
        catalog, _ = scenario.selection.apply(scenario.load_catalog())  # as `run` does
        solution = solve(catalog, scenario.mission, solver=scenario.solver)
        row.update(
            status=solution.status,
            path="->".join(solution.path),
            total_dv_mps=float(solution.total_dv_mps),
            total_duration_days=float(solution.total_duration_days),
            iterations=len(solution.iterations),
            backend=solution.backend,
            solution_json=solution.to_json(),
        )
    except MissionInfeasible as err:
        row.update(status="infeasible", error=_one_line(err))
    except SolverFailure as err:
        row.update(status="solver_failure", error=_one_line(err))
    except Exception as err:  # a worker never raises: the failure becomes the row
        row.update(
            status="error",
            error=f"{type(err).__name__}: {_one_line(err)}",
            traceback=traceback.format_exc(),
        )
    row["seconds"] = time.perf_counter() - start
    return row


def _one_line(err: BaseException) -> str:
    return " ".join(str(err).split()) or type(err).__name__


# ---------------------------------------------------------------------- running
class SweepProgress(NamedTuple):
    """Progress of a sweep, given to a ``progress`` callback after each scenario.

    ``done`` and ``failed`` count scenarios finished with and without a solution
    (including those kept from a previous run); ``eta_s`` extrapolates this run's rate.
    ``row`` is the results row just written (None for the first call, before any
    scenario ran).
    """

    done: int
    failed: int
    remaining: int
    total: int
    elapsed_s: float
    eta_s: float | None
    row: dict | None


@dataclass(frozen=True)
class _Planned:
    item: StudyScenario
    scenario: Scenario  # as run: one solver thread unless the study sets threads
    toml: str
    sha: str


def run_study(
    study: Study | str | os.PathLike,
    out_dir: str | os.PathLike,
    *,
    executor: cf.Executor | None = None,
    scheduler=None,
    workers: int | None = None,
    resume: bool = False,
    progress: bool | Callable[[SweepProgress], None] = True,
) -> pd.DataFrame:
    """Solve every scenario of ``study``, writing each result to ``out_dir`` as it comes.

    Parameters
    ----------
    study : Study or path
        A :class:`Study`, or a study file (read with :func:`load_study`).
    out_dir : path
        Output folder (created if needed; see the module docstring for its files).
    executor : concurrent.futures.Executor, optional
        Where to run the scenarios (not shut down here).  Default: a local process pool.
    scheduler : str or distributed.Client, optional
        A Dask scheduler address (``"tcp://host:8786"``) or a connected Client: the same
        tasks go to that cluster through ``Client.get_executor``.  Its workers need
        ``sdc_cvx`` installed and the catalog files at the same paths.
    workers : int, optional
        Processes of the local pool; default ``os.cpu_count()`` (never more than the
        scenarios to run).
    resume : bool
        Keep the rows of an earlier run of the same study in ``out_dir/results.csv``
        that have a terminal status and run only the others.  Without it, a folder that
        already holds ``results.csv`` is refused.
    progress : bool or callable
        True: a progress line on stderr when it is a terminal.  A callable is called
        with a :class:`SweepProgress` after each scenario.

    Every solve uses one solver thread (``solver.threads = 1``) unless the study sets
    ``solver.threads``, so that parallel scenarios do not compete for cores.

    Returns
    -------
    pandas.DataFrame
        ``results.csv`` as written: one row per scenario that finished, in study order
        (see :data:`RESULT_COLUMNS`); ``attrs["out_dir"]`` is the folder.

    Raises
    ------
    SweepError
        ``out_dir`` holds results of another study, or results without ``resume``, or
        another sweep is writing there.
    """
    study = study if isinstance(study, Study) else load_study(study)
    if executor is not None and scheduler is not None:
        raise ValueError("give an executor or a scheduler, not both")
    if workers is not None and (executor is not None or scheduler is not None):
        raise ValueError("workers sizes the local pool: not with an executor or a scheduler")
    if workers is not None and (
        isinstance(workers, bool) or not isinstance(workers, int) or workers < 1
    ):
        raise ValueError(f"workers must be a positive integer, got {workers!r}")
    out = Path(out_dir)
    planned = [_plan(item) for item in study.scenarios]
    out.mkdir(parents=True, exist_ok=True)
    with _locked(out):
        rows = _previous_rows(out, study, planned, resume)
        _write_inputs(out, study, planned)
        write_atomic(out / "results.csv", _results_text(study, planned, rows))
        pending = [p for p in planned if p.item.key not in rows]
        report = _reporter(progress, len(planned), out)
        report(rows, None, started=True, running=len(pending))
        if pending:
            lost = _execute(
                out, study, planned, pending, rows, report, executor, scheduler, workers
            )
            if lost:
                hint = ""
                if any("BrokenProcessPool" in (rows[key]["error"] or "") for key in lost):
                    hint = (
                        " (a worker process died; a script must start the sweep under "
                        "`if __name__ == '__main__':`, as worker processes import it)"
                    )
                warnings.warn(
                    f"{len(lost)} scenario(s) did not return (status {LOST!r}){hint}; run "
                    f"again with resume=True to finish them",
                    RuntimeWarning,
                    stacklevel=2,
                )
        report(rows, None, finished=True)
    return read_results(out)


def sweep(
    study_or_path: Study | str | os.PathLike | Mapping,
    out_dir: str | os.PathLike | None = None,
    **kwargs,
) -> pd.DataFrame:
    """Run a study and return its results table (the notebook entry point).

    ``study_or_path`` is a :class:`Study`, a study file, or a dict laid out like one
    (relative paths from the current directory).  ``out_dir`` defaults to a new folder
    ``sdc_sweep_YYYYmmdd-HHMMSS`` in the current directory (``attrs["out_dir"]`` of the
    result).  Other keyword arguments go to :func:`run_study`.
    """
    if isinstance(study_or_path, Study):
        study = study_or_path
    elif isinstance(study_or_path, Mapping):
        study = Study.from_dict(study_or_path)
    else:
        study = load_study(study_or_path)
    folder = Path(out_dir) if out_dir is not None else new_run_folder(prefix="sdc_sweep_")
    return run_study(study, folder, **kwargs)


def read_results(out_dir: str | os.PathLike) -> pd.DataFrame:
    """``results.csv`` of a sweep folder (or the file itself) as a DataFrame."""
    path = Path(out_dir)
    file = path / "results.csv" if path.is_dir() else path
    exact = {} if _PANDAS_MAJOR >= 3 else {"float_precision": "round_trip"}  # 3: the default
    text = {c: str for c in ("key", "label", "status", "path", "backend", "error", "scenario_sha")}
    frame = pd.read_csv(file, keep_default_na=False, na_values=[""], dtype=text, **exact)
    if "iterations" in frame:
        frame["iterations"] = frame["iterations"].astype("Int64")
    for column in ("path", "error", "backend"):
        if column in frame:
            frame[column] = frame[column].astype(object).where(frame[column].notna(), None)
    frame.attrs["out_dir"] = os.fspath(file.parent)
    return frame


def _plan(item: StudyScenario) -> _Planned:
    scenario = item.scenario
    if scenario.solver.threads is None:
        scenario = dataclasses.replace(
            scenario, solver=dataclasses.replace(scenario.solver, threads=1)
        )
    sha = hashlib.sha1(_canonical(scenario.to_dict()).encode()).hexdigest()[:12]
    overrides = ", ".join(f"{k} = {_show_value(v)}" for k, v in item.overrides.items())
    header = (
        f"# sdc_cvx sweep scenario {item.key}: {item.label}\n"
        f"# overrides of the study's base: {overrides or 'none'}\n"
    )
    return _Planned(item, scenario, header + scenario.to_toml(), sha)


def _columns(study: Study) -> list[str]:
    return ["key", "label", *study.parameters, *RESULT_COLUMNS, "scenario_sha"]


def _results_text(study: Study, planned: Sequence[_Planned], rows: Mapping[str, dict]) -> str:
    table = [rows[p.item.key] for p in planned if p.item.key in rows]
    return pd.DataFrame(table, columns=_columns(study)).to_csv(index=False)


def _previous_rows(out: Path, study: Study, planned, resume: bool) -> dict[str, dict]:
    """Rows of an earlier run to keep, by key; refuses a folder of another study."""
    file = out / "results.csv"
    if not file.exists():
        return {}
    if not resume:
        raise SweepError(
            f"{out} already holds results.csv: pass resume=True to finish that sweep, or "
            f"choose a new folder"
        )
    previous = read_results(file)
    if previous.empty:
        return {}
    expected = {p.item.key: p for p in planned}
    missing = [c for c in ("key", "scenario_sha", *RESULT_COLUMNS) if c not in previous]
    if missing:
        raise SweepError(f"{file} is not a sweep results table (no {', '.join(missing)})")
    rows = {}
    for record in previous.to_dict("records"):
        key = record["key"]
        plan = expected.get(key)
        if plan is None or record["scenario_sha"] != plan.sha:
            why = "is not in this study" if plan is None else "was run with other values"
            raise SweepError(
                f"cannot resume in {out}: its scenario {key} {why}; the folder holds "
                f"results of another study: choose a new folder"
            )
        if record["status"] == LOST:
            continue
        row = _identity(plan.item, study.parameters)
        row.update({c: _missing_to_none(record[c]) for c in RESULT_COLUMNS})
        row["scenario_sha"] = plan.sha
        rows[key] = row
    return rows


def _missing_to_none(value):
    missing = value is None or value is pd.NA or (isinstance(value, float) and math.isnan(value))
    return None if missing else value


def _write_inputs(out: Path, study: Study, planned: Sequence[_Planned]) -> None:
    write_atomic(out / "study.toml", study.text if study.text is not None else study.to_toml())
    for p in planned:
        folder = out / "scenarios" / p.item.key
        folder.mkdir(parents=True, exist_ok=True)
        write_atomic(folder / "scenario.toml", p.toml)


def _execute(out, study, planned, pending, rows, report, executor, scheduler, workers) -> list:
    """Submit ``pending``, record each result as it arrives; the keys of those lost."""
    lost = []
    with _executor(executor, scheduler, workers, len(pending)) as pool:
        futures = {pool.submit(solve_scenario, p.toml, p.item.key): p for p in pending}
        try:
            for future in cf.as_completed(futures):
                plan = futures.pop(future)
                try:
                    result = future.result()
                except Exception as exc:  # the task never returned: worker or cluster lost
                    result = _lost(plan, exc)
                    lost.append(plan.item.key)
                _record(out, study, planned, plan, result, rows)
                report(rows, rows[plan.item.key])
        finally:
            for future in futures:  # interrupted: nothing more to start
                future.cancel()
    return lost


def _lost(plan: _Planned, exc: BaseException) -> dict:
    return {
        "key": plan.item.key,
        "status": LOST,
        "backend": plan.scenario.solver.backend,
        "error": f"{type(exc).__name__}: {_one_line(exc)}",
    }


def _record(out: Path, study: Study, planned, plan: _Planned, result: Mapping, rows) -> None:
    """Write the scenario's files, then the results table with its row: atomically."""
    folder = out / "scenarios" / plan.item.key
    folder.mkdir(parents=True, exist_ok=True)
    if result.get("solution_json"):
        write_atomic(folder / "solution.json", result["solution_json"])
        (folder / "error.txt").unlink(missing_ok=True)
    elif result.get("error"):
        detail = result.get("traceback") or ""
        write_atomic(folder / "error.txt", f"{result['status']}: {result['error']}\n\n{detail}")
        (folder / "solution.json").unlink(missing_ok=True)
    row = _identity(plan.item, study.parameters)
    row.update({c: result.get(c) for c in RESULT_COLUMNS})
    row["scenario_sha"] = plan.sha
    rows[plan.item.key] = row
    write_atomic(out / "results.csv", _results_text(study, planned, rows))


@contextlib.contextmanager
def _executor(executor, scheduler, workers, pending: int) -> Iterator[cf.Executor]:
    if executor is not None:
        yield executor
        return
    if scheduler is not None:
        client, own = scheduler, False
        if isinstance(scheduler, str | os.PathLike):
            try:
                from distributed import Client
            except ImportError as err:
                raise SweepError(
                    "a Dask scheduler needs dask.distributed: pip install 'sdc_cvx[dask]'"
                ) from err
            client, own = Client(os.fspath(scheduler)), True
        elif not hasattr(scheduler, "get_executor"):
            raise TypeError(
                f"scheduler must be an address or a distributed.Client, "
                f"got {type(scheduler).__name__}"
            )
        pool = client.get_executor(pure=False)
        try:
            yield pool
        except BaseException:
            pool.shutdown(wait=False)  # cancels what is still queued
            raise
        finally:
            if own:
                client.close()
        return
    size = max(1, min(workers or os.cpu_count() or 1, pending))
    pool = cf.ProcessPoolExecutor(
        max_workers=size, mp_context=_mp_context(), initializer=_one_thread_per_worker
    )
    try:
        yield pool
    except BaseException:
        pool.shutdown(wait=False, cancel_futures=True)
        raise
    else:
        pool.shutdown(wait=True)


_THREAD_VARIABLES = ("OMP_NUM_THREADS", "OPENBLAS_NUM_THREADS", "MKL_NUM_THREADS")
_OPENBLAS_SETTERS = (
    "openblas_set_num_threads",
    "scipy_openblas_set_num_threads",
    "openblas_set_num_threads64_",
    "scipy_openblas_set_num_threads64_",
)


def _one_thread_per_worker() -> None:
    """Initializer of the local pool's processes: one BLAS thread, like a Dask worker.

    Parallel scenarios should not compete for cores, and the BLAS thread count changes
    the last digits of the re-optimisation (about 1e-9 relative): with one thread
    everywhere, the local pool and a Dask cluster (whose nanny sets these variables)
    give the same numbers.  The variables cover libraries loaded later; the OpenBLAS
    copies already loaded (numpy's and scipy's, found in /proc/self/maps) are told
    directly.  Best effort: elsewhere than Linux only the variables are set.
    """
    for name in _THREAD_VARIABLES:
        os.environ[name] = "1"
    try:
        with open("/proc/self/maps", encoding="utf-8", errors="replace") as maps:
            libraries = {line.split()[-1] for line in maps if "openblas" in line.lower()}
    except OSError:
        return
    for library in sorted(libraries):
        try:
            handle = ctypes.CDLL(library)
        except OSError:
            continue
        for setter in _OPENBLAS_SETTERS:
            function = getattr(handle, setter, None)
            if function is not None:
                function(1)
                break


def _mp_context():
    """Fork server with sdc_cvx preloaded: fast workers, and no fork of a threaded process
    (a Dask client, a notebook kernel); spawn where there is no fork server."""
    if "forkserver" in multiprocessing.get_all_start_methods():
        context = multiprocessing.get_context("forkserver")
        context.set_forkserver_preload(["sdc_cvx.sweep"])
        return context
    return multiprocessing.get_context("spawn")


@contextlib.contextmanager
def _locked(out: Path) -> Iterator[None]:
    """One sweep at a time per folder (a POSIX record lock, released if the process dies)."""
    try:
        import fcntl
    except ImportError:  # no fcntl (Windows): no lock
        yield
        return
    handle = open(out / _LOCK_NAME, "a+b")  # noqa: SIM115 (held for the whole sweep)
    try:
        try:
            fcntl.lockf(handle, fcntl.LOCK_EX | fcntl.LOCK_NB)
        except OSError:
            raise SweepError(f"another sweep is writing to {out}") from None
        yield
    finally:
        handle.close()


def _reporter(progress, total: int, out: Path):
    """A function called with the rows after each scenario (see :class:`SweepProgress`)."""
    callback = progress if callable(progress) else None
    show = progress is True and sys.stderr.isatty()
    start = time.perf_counter()
    state = {"kept": 0, "width": 0}

    def report(rows, row, *, started=False, finished=False, running=0):
        if not (callback or show):
            return
        failed = sum(r["status"] not in SOLVED_STATUSES for r in rows.values())
        done = len(rows) - failed
        remaining = total - len(rows)
        if started:
            state["kept"] = len(rows)
        elapsed = time.perf_counter() - start
        ran = len(rows) - state["kept"]
        eta = elapsed / ran * remaining if ran else None
        info = SweepProgress(done, failed, remaining, total, elapsed, eta, row)
        if callback and not finished:
            callback(info)
        if not show:
            return
        if started:
            kept = f", {len(rows)} kept from before" if rows else ""
            print(f"sweep: {total} scenarios{kept}, {running} to run -> {out}", file=sys.stderr)
        line = (
            f"sweep: {done} done, {failed} failed, {remaining} remaining of {total}"
            f" | {_clock(elapsed)} elapsed"
            + (f", ETA {_clock(eta)}" if eta is not None and remaining else "")
        )
        pad = " " * max(0, state["width"] - len(line))
        state["width"] = len(line)
        end = "\n" if finished else ""
        print("\r" + line + pad, end=end, file=sys.stderr, flush=True)

    return report


def _clock(seconds: float) -> str:
    seconds = int(round(seconds))
    return f"{seconds // 3600}:{seconds // 60 % 60:02d}:{seconds % 60:02d}"


# ---------------------------------------------------------------------- the figure
def plot_sweep(
    results: pd.DataFrame | str | os.PathLike,
    x: str,
    *,
    hue: str | None = None,
    ax=None,
    annotate: bool = False,
):
    """Total ΔV against a swept parameter, one line per value of ``hue``.

    Parameters
    ----------
    results : DataFrame or path
        What :func:`run_study` returned, or a sweep folder / its ``results.csv``.
    x, hue : str
        Columns: a dotted parameter (``mission.tmax_days``) or its short name
        (``tmax_days``) when unambiguous, or any other column.
    ax : matplotlib Axes, optional
        Draw there; default a new :class:`~matplotlib.figure.Figure`.
    annotate : bool
        Write each solved scenario's path beside its marker.

    Scenarios without a solution leave a gap in their line and are marked with an x
    at the bottom of the axes.  Where several scenarios of a line share an x (another
    parameter varies and is not the ``hue``), markers are drawn without a line.

    Returns
    -------
    matplotlib.figure.Figure
    """
    from matplotlib.figure import Figure
    from matplotlib.lines import Line2D

    frame = results if isinstance(results, pd.DataFrame) else read_results(results)
    x_col = _column(frame, x)
    hue_col = _column(frame, hue) if hue is not None else None
    if ax is None:
        fig = Figure(figsize=(8.0, 4.5), layout="constrained")
        ax = fig.add_subplot()
    solved = frame["status"].isin(SOLVED_STATUSES)
    groups = [(None, frame)] if hue_col is None else list(frame.groupby(hue_col, sort=True))
    any_failed = False
    for value, group in groups:
        group = group.sort_values(x_col, kind="stable")
        ok = solved.loc[group.index]
        dv = group["total_dv_mps"].where(ok)
        style = "" if group[x_col].duplicated().any() else "-"
        name = None if hue_col is None else f"{_short(hue_col)} = {_show_value(value)}"
        (line,) = ax.plot(group[x_col], dv, marker="o", linestyle=style, label=name)
        failed = group[~ok]
        if len(failed):
            any_failed = True
            ax.plot(
                failed[x_col],
                np.full(len(failed), 0.03),
                linestyle="",
                marker="x",
                markersize=8,
                color=line.get_color(),
                transform=ax.get_xaxis_transform(),
                clip_on=False,
            )
        if annotate:
            for xv, yv, path in zip(group[x_col][ok], dv[ok], group["path"][ok], strict=True):
                ax.annotate(
                    str(path).replace("->", "\u2192"),
                    (xv, yv),
                    xytext=(4, 4),
                    textcoords="offset points",
                    fontsize=7,
                )
    ax.set_xlabel(x_col)
    ax.set_ylabel("total \u0394V [m/s]")
    ax.set_title(f"Total \u0394V against {_short(x_col)}")
    ax.grid(True, alpha=0.3)
    handles, labels = ax.get_legend_handles_labels()
    if any_failed:
        handles.append(Line2D([], [], linestyle="", marker="x", color="0.3"))
        labels.append("no solution (infeasible / failed)")
    if handles:
        ax.legend(handles, labels, fontsize=9)
    return ax.figure


def _column(frame: pd.DataFrame, name: str) -> str:
    if name in frame.columns:
        return name
    matches = [c for c in frame.columns if isinstance(c, str) and c.partition(".")[2] == name]
    if len(matches) == 1:
        return matches[0]
    known = ", ".join(str(c) for c in frame.columns)
    raise KeyError(f"no column {name!r} in the results (columns: {known})")


def _short(column: str) -> str:
    return column.partition(".")[2] or column
