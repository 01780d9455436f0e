"""The worker of a study: one scenario's TOML text in, one plain results row out."""

from __future__ import annotations

import math
import time
import tomllib
import traceback
from typing import Any

from ..errors import MissionInfeasible, SolverFailure
from ..planner.api import solve
from .executors import restore_malloc
from .results import VEHICLE_COLUMNS, ScenarioStatus
from .scenario import Scenario
from .study import _flatten


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
    restore_malloc()  # a Dask worker's malloc thresholds make it 2-3 times slower
    start = time.perf_counter()
    row: dict[str, Any] = {
        "key": key,
        "status": ScenarioStatus.ERROR.value,
        "path": None,
        "total_dv_mps": math.nan,
        "lower_bound_mps": math.nan,
        "gap_mps": math.nan,
        "gap_rel": math.nan,
        "certified": False,
        "method": None,
        "total_duration_days": math.nan,
        "iterations": None,
        "seconds": math.nan,
        "backend": None,
        **dict.fromkeys(VEHICLE_COLUMNS),
        "error": None,
        "solution_json": None,
        "traceback": None,
    }
    try:
        data = tomllib.loads(scenario_toml)
        scenario = Scenario().with_overrides(**_flatten(data))
        row["backend"] = scenario.solver.backend
        catalog, _ = scenario.select_candidates()  # as `run` does
        row["method"] = scenario.solver.method
        solution = solve(catalog, scenario.mission, solver=scenario.solver)
        row.update(
            status=str(solution.status),
            path="->".join(solution.path),
            total_dv_mps=float(solution.total_dv_mps),
            lower_bound_mps=_or_nan(solution.lower_bound_mps),
            gap_mps=_or_nan(solution.gap_mps),
            gap_rel=_or_nan(solution.gap_rel),
            certified=solution.certified,
            method=solution.method,
            total_duration_days=float(solution.total_duration_days),
            iterations=len(solution.iterations),
            backend=solution.backend,
            solution_json=solution.to_json(),
        )
        tank = solution.vehicle or {}
        row.update({c: tank[c] for c in VEHICLE_COLUMNS if c in tank})
    except MissionInfeasible as err:
        row.update(status=ScenarioStatus.INFEASIBLE.value, error=_one_line(err))
    except SolverFailure as err:
        row.update(status=ScenarioStatus.SOLVER_FAILURE.value, error=_one_line(err))
    except Exception as err:  # a worker never raises: the failure becomes the row
        row.update(
            status=ScenarioStatus.ERROR.value,
            error=f"{type(err).__name__}: {_one_line(err)}",
            traceback=traceback.format_exc(),
        )
    row["seconds"] = time.perf_counter() - start
    return row


def _or_nan(value) -> float:
    return math.nan if value is None else float(value)


def _one_line(err: BaseException) -> str:
    return " ".join(str(err).split()) or type(err).__name__
