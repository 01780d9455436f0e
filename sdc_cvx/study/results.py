"""The results of a study: the scenario statuses and ``results.csv``."""

from __future__ import annotations

import math
import os
from collections.abc import Mapping, Sequence
from enum import StrEnum
from pathlib import Path
from typing import TYPE_CHECKING

import pandas as pd

from ..inputs.vehicle import TANK_KEYS
from ..report.run_folder import CSV_FLOAT_FORMAT
from ..solution import RunStatus

if TYPE_CHECKING:
    from .study import Study


class ScenarioStatus(StrEnum):
    """How a scenario of a study ended without a plan (the ``status`` column of
    ``results.csv``; a solved scenario has its :class:`~sdc_cvx.solution.RunStatus`).

    A ``str`` enum: a member compares equal to its value.  ``infeasible``
    (:class:`~sdc_cvx.errors.MissionInfeasible`), ``solver_failure``
    (:class:`~sdc_cvx.errors.SolverFailure`) and ``error`` (anything else, e.g. an
    unreadable catalog) are terminal: a resume does not run them again.  ``lost`` (the
    task never returned: worker process killed, cluster lost, cancelled) is not: a
    resume runs it again.
    """

    INFEASIBLE = "infeasible"
    SOLVER_FAILURE = "solver_failure"
    ERROR = "error"
    LOST = "lost"

    @property
    def is_terminal(self) -> bool:
        """A resume keeps the scenario's row (it does not run it again)."""
        return self is not ScenarioStatus.LOST


def is_solved(status: str) -> bool:
    """Whether a ``status`` cell of ``results.csv`` is a run status with a plan."""
    return status in SOLVED_STATUSES


SOLVED_STATUSES = tuple(status.value for status in RunStatus if status.is_solved)
"""Statuses of a solved scenario (the :attr:`Solution.status` values with a plan)."""
FAILURE_STATUSES = tuple(status.value for status in ScenarioStatus if status.is_terminal)
"""Statuses of a scenario that ran and gave no solution (terminal; see :class:`ScenarioStatus`)."""
LOST = ScenarioStatus.LOST
"""Status of a scenario whose task never returned: not terminal, a resume runs it again."""

RESULT_COLUMNS = (
    "status",
    "path",
    "total_dv_mps",
    "lower_bound_mps",
    "gap_mps",
    "gap_rel",
    "certified",
    "method",
    "total_duration_days",
    "iterations",
    "seconds",
    "backend",
    *TANK_KEYS,
    "error",
)
"""Columns of ``results.csv`` that come from the solve, after ``key``, ``label`` and the
swept parameters (dotted names), and before ``scenario_sha``; the vehicle's
(:data:`VEHICLE_COLUMNS`) empty without a vehicle whose propellant the plan computed."""
VEHICLE_COLUMNS = TANK_KEYS
"""The plan's propellant against the tank (``solution.json``'s ``vehicle``): columns a
sweep folder of an earlier version lacks, which a resume leaves empty."""


_PANDAS_MAJOR = int(pd.__version__.split(".")[0])


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


def _columns(study: Study) -> list[str]:
    return ["key", "label", *study.parameters, *RESULT_COLUMNS, "scenario_sha"]


def _results_text(study: Study, keys: Sequence[str], rows: Mapping[str, dict]) -> str:
    """``results.csv``: the rows of the scenarios run so far, in the order of ``keys``."""
    table = [rows[key] for key in keys if key in rows]
    frame = pd.DataFrame(table, columns=_columns(study))
    for column in frame.select_dtypes("float").columns:  # 10 significant digits, as every
        frame[column] = [float(CSV_FLOAT_FORMAT % v) for v in frame[column]]  # CSV of sdc_cvx
    return frame.to_csv(index=False)  # (300.0, not 299.9999999999925: still a float)


def _missing_to_none(value):
    missing = value is None or value is pd.NA or (isinstance(value, float) and math.isnan(value))
    return None if missing else value
