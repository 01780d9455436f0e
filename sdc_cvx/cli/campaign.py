"""``campaign``: plan K missions on given launch days and write the campaign folder."""

from __future__ import annotations

import contextlib
import importlib.util
import sys
import time
import warnings
from pathlib import Path

import click

from ..errors import (
    IgnoredOptionWarning,
    MissionError,
    MissionInfeasible,
    SolverFailure,
    SweepError,
    listing,
)
from .budget import MISSION_FOLDER_S, search_limit
from .exits import (
    INFEASIBLE,
    INPUT_ERROR,
    INTERRUPTED,
    SOLVER_FAILED,
    SYSTEM_ERRNOS,
    exit_code,
    fail,
    interrupted_exit,
)
from .fly import warn_replaced_flights
from .options import out_option, parallel_options, raan_rates_option
from .progress import RunProgress, interruptible, open_progress_log
from .reading import (
    build_scenario,
    check_backend,
    day_zero,
    read_catalog,
    select_candidates,
    with_raan_rates,
)


@click.command("campaign")
@click.argument("scenario_file", metavar="SCENARIO.toml", type=click.Path(dir_okay=False))
@out_option("sdc_campaign_")
@parallel_options
@raan_rates_option
@click.option(
    "--time-limit",
    "time_limit_s",
    type=float,
    default=None,
    help="Time limit of the whole search [s]; the best campaign is then returned with its "
         "gap (exit 4 if the limit came before every launch had a mission).",
)
@click.option(
    "--gap", type=float, default=None, help="Relative gap of a certified answer [0.001 = 0.1 %]."
)
@click.option("--quiet", is_flag=True, help="No progress, only the summary.")
@click.option("--json", "json_out", is_flag=True,
              help="Write campaign.json to stdout (and nothing else there).")  # fmt: skip
@click.option("--svg", is_flag=True, help="Also save the figures as SVG.")
@click.option("--pareto", type=click.IntRange(min=2), default=None, metavar="K",
              help="With objective = 'max-value': also K campaigns of value against ΔV, each "
              "the cheapest of at least a value (pareto.csv, pareto.png).")  # fmt: skip
@click.option("--progress/--no-progress", default=None, hidden=True)
def campaign_command(scenario_file, out_dir, time_limit_s, gap, workers, scheduler, raan_rates,
                     quiet, json_out, svg, pareto, progress):  # fmt: skip
    """Plan a removal campaign: K missions on given launch days, each debris removed once.

    SCENARIO.toml has a [campaign] table (launch_days, or missions with first_launch_day
    and period_days; n, a count or [n_min, n_max], and tmax_days per mission; must_remove
    or remove_all; objective "min-dv", "max-value" with dv_budget_mps, or "value-per-dv"
    with price_per_value_mps, the values from [catalog] values) and the usual [catalog],
    [mission] (every mission's defaults), [vehicle], [solver] and [selection] tables
    (every key: examples/README.md).  Writes a campaign folder: campaign.json,
    missions.csv, history.csv, campaign.log, the figures and one run folder per mission.
    Exit codes: 2 invalid input (nothing written), 3 infeasible campaign (campaign.json
    says why) or a campaign whose missions need more propellant than the vehicle's tank
    holds (written, never called flyable), 4 solver failure.
    """
    started = time.perf_counter()  # --time-limit covers the whole command (cli/budget.py)
    from ..campaign.pricing_runs import ignored_options, pricings_at_once
    from ..campaign.search import solve_campaign
    from ..planner.size_guard import size_problem
    from ..report.campaign_folder import (
        campaign_folder_problem,
        write_infeasible_campaign,
    )
    from ..report.out_folder import new_folder_problem
    from ..report.run_folder import new_run_folder
    from ..study.executors import scheduler_problem

    if scheduler is not None and importlib.util.find_spec("distributed") is None:
        fail("--scheduler needs dask.distributed, which is not installed here: "
             "pip install 'sdc_cvx[dask]'")  # fmt: skip
    if gap is not None and not 0 <= gap < 1:
        fail(f"--gap must be in [0, 1), got {gap:g}")
    if time_limit_s is not None and not time_limit_s > 0:
        fail(f"--time-limit must be > 0 seconds, got {time_limit_s:g}")
    scenario = build_scenario(scenario_file, catalog_raan_rates=raan_rates)
    if scenario.campaign is None:
        fail(
            f"{scenario_file} has no [campaign] table: add launch_days = [0.0, 365.25] (or "
            "missions = K) to plan a campaign (see examples/campaign_gtoc9.toml), or use "
            "'run' for one mission"
        )
    if out_dir is not None:
        problem = campaign_folder_problem(out_dir)
        if problem is not None:
            fail(f"--out: {problem}")
        warn_replaced_flights(out_dir)
    elif (problem := new_folder_problem()) is not None:
        fail(problem)
    campaign = scenario.campaign
    if pareto and campaign.objective != "max-value":
        fail(f"--pareto: value against ΔV needs [campaign] objective = 'max-value' (with "
             f"dv_budget_mps) in {scenario_file}")  # fmt: skip
    gap = scenario.solver.gap if gap is None else gap
    time_limit_s = scenario.solver.time_limit_s if time_limit_s is None else time_limit_s
    catalog = read_catalog(scenario, on_invalid="set aside")  # the filters act first

    def info(message: str) -> None:
        if not quiet:
            click.echo(message, err=True)

    catalog, _ = select_candidates(catalog, scenario, info)
    catalog = with_raan_rates(catalog, scenario, info)  # from day 0 to the last mission's end
    try:
        campaign.check_candidates(catalog)
    except MissionError as err:
        fail(f"{scenario_file}: campaign: {err} (catalog: {catalog.source})")
    from ..study.scenario_values import CSI, candidates_without_mass  # pandas: not at --help

    if scenario.catalog_values == CSI and (missing := candidates_without_mass(
            catalog, dict(campaign.values))):  # fmt: skip
        fail(f"{scenario.catalog_masses}: no mass for {len(missing)} of the {len(catalog)} "
             f"candidates ({listing(missing)}): the criticality index (values = \"csi\") "
             "needs each one's mass [kg]; add them, or filter those out")  # fmt: skip
    if campaign.values and scenario.catalog_values != CSI:
        table = dict(campaign.values)
        info(values_named(sum(str(k) in table for k in catalog.ids), len(catalog),
                          scenario.catalog_values))  # fmt: skip
    at_once = pricings_at_once(workers, scheduler, None, len(campaign))
    if (problem := size_problem(len(catalog), at_once)) is not None:
        fail(f"{catalog.source}: {problem}")
    check_backend(scenario.solver)
    if (problem := scheduler_problem(scheduler)) is not None:  # before any work
        fail(f"--scheduler: {problem}")
    header = (
        f"Campaign of {len(campaign)} missions (launch days {_days_text(campaign.launch_days)}"
        f"; n = {_shortened(campaign.counts_text().split(', '))}) from {len(catalog)} "
        f"candidates of "
        f"{catalog.source}; gap {gap:g}."
    )
    if time_limit_s is not None:  # covers the command: a folder per mission to write after
        limit, time_limit_s = time_limit_s, search_limit(
            time_limit_s, started, MISSION_FOLDER_S * (len(campaign) + 1))  # fmt: skip
        header += (f"\nThe search may run up to {time_limit_s:.1f} s of the {limit:g} s limit: "
                   "it stops sooner once the campaign is proven (the rest reads the catalog "
                   "and writes the campaign folder).")  # fmt: skip
    info(header)
    show_progress = (sys.stderr.isatty() if progress is None else progress) and not quiet
    live_log, stream, made = open_progress_log(out_dir)
    folder = Path(out_dir) if out_dir else None
    start_utc = None if catalog.start is None else catalog.start.isoformat()
    with RunProgress(show_progress, live_log=live_log, stream=stream, made=made) as steps:
        steps.say(header, show=False)
        steps.set_phase("campaign: each launch alone, then the greedy campaign")
        for message in ignored_options(campaign, scenario.solver):  # said once, up front
            click.echo(f"warning: {message}", err=True)
            steps.say(f"warning: {message}", show=False)
        try:
            with warnings.catch_warnings(), interruptible(steps, "certified") as stop:
                warnings.simplefilter("ignore", IgnoredOptionWarning)
                solution = solve_campaign(catalog, campaign, solver=scenario.solver, gap=gap,
                                          time_limit_s=time_limit_s, workers=workers,
                                          scheduler=scheduler, log=steps.search_step,
                                          stop=stop, pareto=pareto or 0)  # fmt: skip
        except MissionInfeasible as err:
            steps.say(f"infeasible: {err}")
            try:
                folder = folder or new_run_folder(prefix="sdc_campaign_")
                write_infeasible_campaign(folder, str(err), start_utc=start_utc,
                                          campaign=campaign.to_dict(),
                                          scenario_toml=scenario.to_toml(start=day_zero(catalog)),
                                          log=steps.log_text())  # fmt: skip
                steps.discard_live_log()
            except OSError as write_err:
                click.echo(f"warning: cannot write {folder}: {write_err}", err=True)
            fail(f"infeasible campaign: {err} ({folder}/campaign.json)", exit_code(err))
        except KeyboardInterrupt:
            kept = f" (progress in {live_log})" if live_log is not None else ""
            steps.__exit__(None, None, None)  # the log closed before the hard exit
            interrupted_exit(f"interrupted: nothing written{kept}")
        except (SolverFailure, SweepError) as err:
            kept = f" (progress in {live_log})" if live_log is not None else ""
            if stop():  # a Ctrl-C before any campaign: interrupted, not a failure
                steps.__exit__(None, None, None)
                interrupted_exit(f"interrupted before any campaign: nothing written{kept}")
            fail(f"solver failure: {err}{kept}", exit_code(err))
        steps.set_phase("writing the campaign folder")
        steps.say(solution.summary(), show=False)
    try:
        folder = folder or new_run_folder(prefix="sdc_campaign_")
        solution.save(folder, formats=("png", "svg") if svg else ("png",),
                      scenario_toml=scenario.to_toml(start=day_zero(catalog)),
                      log=steps.log_text())  # fmt: skip
        steps.discard_live_log()
    except (OSError, KeyboardInterrupt) as err:
        steps.discard_live_log()
        if out_dir is None and folder is not None:
            with contextlib.suppress(OSError):
                folder.rmdir()  # the new sdc_campaign_* folder, if still empty
        if isinstance(err, KeyboardInterrupt):
            fail(f"interrupted while writing: nothing written to {folder}", INTERRUPTED)
        code = SOLVER_FAILED if err.errno in SYSTEM_ERRNOS else INPUT_ERROR
        message = err.strerror or str(err)
        if not message.startswith("cannot write"):
            message = f"cannot write the campaign folder {folder or '.'}: {message}"
        fail(message, code)
    lines = [solution.summary()]
    if start_utc:
        lines.append(f"start     {start_utc} (day 0 of the launch days)")
    lines.append(f"results   {folder}/campaign.json")
    if json_out:
        click.echo(solution.to_json())
        for line in lines:
            info(line)
    else:
        click.echo("\n".join(lines))
    from ..solution import RunStatus  # pandas: not at --help

    if solution.status == RunStatus.OVER_CAPACITY:  # written, but never called flyable
        fail(f"{solution.notes[-1]} (campaign folder {folder})", INFEASIBLE)
    if not solution.certified:
        click.echo(f"warning: {solution.status}; see the notes in campaign.json", err=True)


def _shortened(items: list[str], most: int = 8) -> str:
    """``items`` joined, the middle left out past ``most`` (``a, b, c, ..., z (25)``); one
    item for all, as ``n = [[2, 3]]`` is written, is said once (``2-3 each``)."""
    if len(items) > 1 and len(set(items)) == 1:
        return f"{items[0]} each"
    if len(items) <= most:
        return ", ".join(items)
    return f"{', '.join(items[:3])}, ..., {items[-1]} ({len(items)})"


def _days_text(days) -> str:
    """Launch days as text: every one, or the first, last and period when evenly spaced."""
    import numpy as np

    steps = np.diff(days)
    if len(days) > 8 and np.allclose(steps, steps[0]):
        return f"{days[0]:g} to {days[-1]:g}, every {steps[0]:g}"
    return _shortened([f"{d:g}" for d in days])


def values_named(named: int, candidates: int, source) -> str:
    """How many of the candidates the values file names, in words (``the others are worth
    0`` only where there are others)."""
    if named == candidates:
        return f"values: every one of the {candidates} candidates is named in {source}"
    return (f"values: {named} of the {candidates} candidates are named in {source} (the "
            f"other {candidates - named} are worth 0)")
