"""``sweep``: run a trade study, one result row per scenario, resumable."""

from __future__ import annotations

import importlib.util
import sys
from pathlib import Path

import click

from ..errors import ScenarioError, SweepError
from .exits import INFEASIBLE, INPUT_ERROR, SOLVER_FAILED, SYSTEM_ERRNOS, fail, interrupted_exit
from .options import out_option, parallel_options


@click.command("sweep")
@click.argument("study_file", metavar="STUDY.toml", type=click.Path(dir_okay=False))
@out_option("sdc_sweep_")
@parallel_options
@click.option("--resume", is_flag=True, help="Skip the scenarios already finished in --out.")
@click.option("--progress/--no-progress", default=None, hidden=True)
def sweep_command(study_file, out_dir, workers, scheduler, resume, progress):
    """Run a trade study: a base scenario and a grid / list of overrides, one row each.

    Every scenario is validated before any solve; each result is written as soon as it
    finishes (results.csv and one solution.json per scenario), so --resume after an
    interruption only runs what is missing.  The study file's format: examples/README.md
    ("Trade studies"); a time limit per solve is [base.solver] time_limit_s there.
    """
    from ..report.out_folder import new_folder_problem
    from ..report.run_folder import new_run_folder
    from ..study.executors import scheduler_problem
    from ..study.results import SOLVED_STATUSES
    from ..study.runner import run_study, sweep_folder_problem
    from ..study.study import load_study

    if resume and out_dir is None:
        fail("--resume needs --out, the folder of the sweep to finish")
    if scheduler is not None and importlib.util.find_spec("distributed") is None:
        fail("--scheduler needs dask.distributed, which is not installed here: "
             "pip install 'sdc_cvx[dask]'")  # fmt: skip
    try:
        study = load_study(study_file)
    except (ScenarioError, SweepError, OSError) as err:
        fail(str(err))
    if out_dir is not None:
        problem = sweep_folder_problem(Path(out_dir), resume=resume)
        if problem is not None:
            fail(f"--out: {problem}")
    elif (problem := new_folder_problem()) is not None:
        fail(problem)
    if (problem := scheduler_problem(scheduler)) is not None:  # before the folder is made
        fail(f"--scheduler: {problem}")
    try:
        folder = Path(out_dir) if out_dir else new_run_folder(prefix="sdc_sweep_")
    except OSError as err:
        fail(f"cannot create a sweep folder in {Path.cwd()}: {err.strerror or err}; choose "
             "one with --out")  # fmt: skip
    show = sys.stderr.isatty() if progress is None else progress
    try:
        results = run_study(study, folder, workers=workers, scheduler=scheduler, resume=resume,
                            progress=show)  # fmt: skip
    except SweepError as err:
        fail(str(err))
    except OSError as err:  # a full disk while writing results
        code = SOLVER_FAILED if err.errno in SYSTEM_ERRNOS else INPUT_ERROR
        fail(f"cannot write the sweep folder {folder}: {err.strerror or err}"
             + (f" ({err.filename})" if err.filename else "")
             + f"; finish later with --resume --out {folder}", code)  # fmt: skip
    except KeyboardInterrupt:
        interrupted_exit(f"interrupted: the scenarios finished so far are in "
                         f"{folder}/results.csv; finish the others with: python -m sdc_cvx "
                         f"sweep {study_file} --resume --out {folder}")  # fmt: skip
    done = results["status"].isin(SOLVED_STATUSES)
    over = int((results["status"] == "over_capacity").sum())
    tank = f" ({over} over the vehicle's tank: status over_capacity)" if over else ""
    click.echo(f"{int(done.sum())} of {len(results)} scenarios solved{tank}; results in "
               f"{folder}/results.csv")  # fmt: skip
    if len(results) and not done.any():  # nothing solved is not a success
        counts = results["status"].value_counts()
        said = ", ".join(f"{count} {status}" for status, count in counts.items())
        infeasible = set(counts.index) == {"infeasible"}
        fail(f"no scenario was solved ({said}): see the error column of {folder}/results.csv",
             INFEASIBLE if infeasible else SOLVER_FAILED)  # fmt: skip
