"""Running a study: solved in parallel, each result written as it comes, nothing lost.

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
import dataclasses
import hashlib
import importlib.util
import os
import sys
import time
import warnings
from collections.abc import Callable, Mapping, Sequence
from dataclasses import dataclass
from pathlib import Path
from typing import NamedTuple

import pandas as pd

from ..errors import SweepError
from ..report.atomic import write_atomic
from ..report.out_folder import name_problem
from ..report.run_folder import new_run_folder
from .executors import _executor, _locked, unguarded_call_site
from .figure import plot_sweep
from .results import (
    FAILURE_STATUSES,
    LOST,
    RESULT_COLUMNS,
    SOLVED_STATUSES,
    VEHICLE_COLUMNS,
    _missing_to_none,
    _results_text,
    read_results,
)
from .scenario import Scenario
from .study import Study, StudyScenario, _canonical, _identity, _show_value, load_study
from .worker import _one_line, solve_scenario

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
    if isinstance(scheduler, str | os.PathLike) and importlib.util.find_spec("distributed") is None:
        raise SweepError("a Dask scheduler needs dask.distributed: pip install 'sdc_cvx[dask]'")
    if executor is None and scheduler is None:
        _check_main_guard()
    out = Path(out_dir)
    problem = sweep_folder_problem(out)
    if problem is not None:
        raise SweepError(problem)
    campaigns = [item.key for item in study.scenarios if item.scenario.campaign is not None]
    if campaigns:
        warnings.warn(f"{len(campaigns)} scenario(s) have a [campaign] table (first "
                      f"{campaigns[0]}): a sweep plans the one mission of each [mission] "
                      "table; `python -m sdc_cvx campaign` plans a campaign",
                      UserWarning, stacklevel=2)  # fmt: skip
    planned = [_plan(item) for item in study.scenarios]
    out.mkdir(parents=True, exist_ok=True)
    with _locked(out):
        rows = _previous_rows(out, study, planned, resume)
        _write_inputs(out, study, planned)
        write_atomic(out / "results.csv", _results_text(study, [p.item.key for p in planned], rows))
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
                    f"again with resume=True (--resume) to finish them",
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


SWEEP_FOLDER_MARKERS = ("results.csv", "study.toml", "scenarios")
"""A folder holding one of these is a sweep folder (finished, or killed early)."""


def sweep_folder_problem(out: Path, *, resume: bool = True) -> str | None:
    """Why ``out`` cannot take a sweep, or None: a file, a name the system refuses, or a
    non-empty folder that is not a sweep folder (an earlier run folder, a folder of the
    user's) is refused, as ``run`` refuses a folder that is not a run folder; without
    ``resume``, so is a sweep folder that already holds results."""
    out = Path(out)
    if (problem := name_problem(out)) is not None:
        return problem
    try:
        if out.exists() and not out.is_dir():
            return f"{out} is a file, not a folder"
        if (out / "results.csv").exists() and not resume:
            return (f"{out} already holds results.csv: add --resume to finish that sweep, "
                    "or choose a new folder")  # fmt: skip
        foreign = not any((out / name).exists() for name in SWEEP_FOLDER_MARKERS)
        if out.is_dir() and any(out.iterdir()) and foreign:
            return (
                f"{out} is not empty and is not a sweep folder (no "
                f"{', '.join(SWEEP_FOLDER_MARKERS)}); choose a new or empty folder"
            )
    except OSError as err:  # a path the system refuses
        return f"{out} cannot be used: {err.strerror or err}"
    return None


def _check_main_guard() -> None:
    """Refuse a sweep started at the top level of a script without a main guard
    (:func:`~sdc_cvx.study.executors.unguarded_call_site`)."""
    site = unguarded_call_site()
    if site is not None:
        raise SweepError(
            f"{site}: the sweep is started at the top level of the script, "
            'without `if __name__ == "__main__":`; its worker processes import the script '
            "and would start the sweep again: put the call under that guard (or pass "
            "executor= or scheduler=)"
        )


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


def _previous_rows(out: Path, study: Study, planned, resume: bool) -> dict[str, dict]:
    """Rows of an earlier run to keep, by key; refuses a folder of another study."""
    file = out / "results.csv"
    if not file.exists():
        return {}
    if not resume:
        raise SweepError(
            f"{out} already holds results.csv: pass resume=True (--resume on the command "
            f"line) to finish that sweep, or choose a new folder"
        )
    previous = read_results(file)
    if previous.empty:
        return {}
    expected = {p.item.key: p for p in planned}
    missing = [c for c in ("key", "scenario_sha", *RESULT_COLUMNS)
               if c not in previous and c not in VEHICLE_COLUMNS]  # fmt: skip
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
        row.update({c: _missing_to_none(record.get(c)) for c in RESULT_COLUMNS})
        row["scenario_sha"] = plan.sha
        rows[key] = row
    return rows


def _write_inputs(out: Path, study: Study, planned: Sequence[_Planned]) -> None:
    """``study.toml`` (self-contained: it resumes the sweep from the folder, wherever the
    original's relative paths pointed; the original text follows as comments) and each
    scenario's TOML."""
    text = study.to_toml()
    source = getattr(study, "source", None)
    if (
        study.text is not None
        and source is not None
        and Path(source).resolve() == (out / "study.toml").resolve()
    ):
        text = study.text  # resumed from the folder's own copy: kept as it is
    elif study.text is not None:
        where = f" ({study.source})" if getattr(study, "source", None) else ""
        original = "".join(f"# {line}\n" for line in study.text.splitlines())
        text = (f"# the study as run, self-contained (resume: sdc-cvx sweep THIS_FILE "
                f"--resume --out THIS_FOLDER)\n{text}\n# the study file as given{where}:\n"
                f"{original}")  # fmt: skip
    write_atomic(out / "study.toml", text)
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
        "status": LOST.value,
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
    write_atomic(out / "results.csv", _results_text(study, [p.item.key for p in planned], rows))


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
