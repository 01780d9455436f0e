"""``run``: plan one mission and write its run folder."""

from __future__ import annotations

import contextlib
import dataclasses
import sys
import time
import warnings
from pathlib import Path
from typing import TYPE_CHECKING

import click

from ..errors import IgnoredOptionWarning, MissionError, MissionInfeasible, SolverFailure
from ..milp.types import DEFAULT_BACKEND
from .budget import edges_s, run_writing_s, search_limit, writes_edges
from .exits import (
    INFEASIBLE,
    INPUT_ERROR,
    INTERRUPTED,
    SOLVER_FAILED,
    SYSTEM_ERRNOS,
    exit_code,
    fail,
)
from .fly import FORCE_MODELS, fly_folder, warn_replaced_flights
from .options import (
    catalog_options,
    raan_rates_option,
    scenario_argument,
    selection_options,
    selection_overrides,
)
from .progress import RunProgress, interruptible, open_progress_log
from .reading import (
    build_scenario,
    check_backend,
    day_zero,
    read_catalog,
    select_candidates,
    with_raan_rates,
)

if TYPE_CHECKING:
    from ..inputs.catalog import Catalog


@click.command("run")
@scenario_argument
@catalog_options
@raan_rates_option
@selection_options
@click.option("--n", type=int, default=None, help="Number of debris to remove [5].")
@click.option("--tmax-days", type=float, default=None, help="Mission duration limit [365.25 days].")
@click.option("--deorbit-days", type=float, default=None, help="Operations time per debris [0].")
@click.option("--preopt-days", type=float, default=None, help="Pre-optimisation bound T0 [61].")
@click.option(
    "--dv-max", "dv_max_mps", type=float, default=None, help="Edge cost filter [1000 m/s]."
)
@click.option(
    "--min-transfer-days", type=float, default=None, help="Minimum transfer duration [0 days]."
)
@click.option("--eccentricity", type=click.Choice(["auto", "on", "off"]), default=None,
              help="Price the eccentricity each leg must change [auto: where the catalog "
              "gives each debris' argument of perigee].")
@click.option("--flight-min-days", type=float, default=None,
              help="Shortest leg planned, the flight time a rendezvous needs [10 days where "
              "the debris' positions are known, else 0; 0 turns it off].")
@click.option("--transfer", type=click.Choice(["impulsive", "low-thrust"]), default=None,
              help="Transfer model: impulsive drift legs, or low-thrust spirals (needs the "
              "vehicle's acceleration: --accel or a [vehicle] table) [impulsive].")
@click.option("--accel", "accel_mps2", type=float, default=None, metavar="M/S2",
              help="Thrust acceleration of a low-thrust vehicle [m/s^2] (vehicle.accel_mps2).")
@click.option("--backend", default=None, help=f"MILP backend, a CVXPY name [{DEFAULT_BACKEND}].")
@click.option(
    "--method",
    type=click.Choice(["certified", "paper"]),
    default=None,
    help="certified: the optimum with a proven bound [default]; paper: Cerf's local method.",
)
@click.option(
    "--gap", type=float, default=None, help="Relative gap of a certified answer [0.001 = 0.1 %]."
)
@click.option(
    "--time-limit",
    "time_limit_s",
    type=float,
    default=None,
    help="Time limit [s]: of the whole run (certified; it returns its best plan and gap), "
    "or of each MILP (paper).",
)
@click.option("--mip-gap", type=float, default=None, help="Relative MIP gap [1e-6].")
@click.option("--threads", type=int, default=None, help="Threads of the MILP backend.")
@click.option(
    "--fallback",
    "fallback",
    multiple=True,
    metavar="BACKEND",
    help="Backend tried next when the previous one fails (repeatable).",
)
@click.option(
    "--out",
    "out_dir",
    type=click.Path(file_okay=False),
    default=None,
    help="Output folder [a new sdc_run_* folder here].",
)
@click.option("--quiet", is_flag=True, help="No progress, only the summary.")
@click.option(
    "--json",
    "json_out",
    is_flag=True,
    help="Write the solution JSON to stdout (and nothing else there).",
)
@click.option("--svg", is_flag=True, help="Also save the figures as SVG.")
@click.option("--fly", "fly_plan", is_flag=True,
              help="Then fly the plan (as 'fly RUN_DIR' does): RUN_DIR/flight/.")
@click.option("--force-model", type=click.Choice(FORCE_MODELS), default=None,
              help="With --fly: the vehicle's force model [j2].")  # fmt: skip
@click.option("--verbose", is_flag=True, default=None,
              help="Show the MILP backend's own log (on stderr).")  # fmt: skip
@click.option(
    "--progress/--no-progress",
    default=None,
    hidden=True,
    help="Force the per-iteration lines on or off [on when stderr is a terminal].",
)
def run_command(scenario_file, catalog_path, catalog_format, start, raan_rates, altitude_km,
        inclination_deg,
        max_eccentricity, ids, exclude_ids, names, types, strict, n, tmax_days, deorbit_days,
        preopt_days, dv_max_mps, min_transfer_days, eccentricity, flight_min_days, transfer,
        accel_mps2, backend, method, gap,
        time_limit_s, mip_gap, threads, fallback, out_dir, quiet, json_out, svg, fly_plan,
        force_model, verbose, progress):  # fmt: skip
    """Select, order and plan the transfers; write solution.json and tables to a run folder.

    SCENARIO.toml (optional; default the paper's case) gives the catalog, mission,
    solver, vehicle and candidate filters; the options override it ([defaults] apply when
    neither sets a value).  The run folder also gets scenario.toml, the scenario as used.
    Exit codes: 2 invalid input (nothing written), 3 infeasible mission (or a plan that
    needs more propellant than the vehicle's tank holds: its folder is written), 4 solver
    failure.
    """
    started = time.perf_counter()  # --time-limit covers the whole command (cli/budget.py)
    from ..network.edges import preoptimize
    from ..planner.api import ignored_options, solve
    from ..planner.size_guard import size_problem
    from ..report.out_folder import new_folder_problem, out_folder_problem
    from ..report.run_folder import being_flown, new_run_folder, write_run
    from ..solution import RunStatus

    # a plan, but the run did not settle: say so (a new solved status needs no warning)
    unsettled = {RunStatus.CONVERGED_UNCONFIRMED, RunStatus.ITERATION_LIMIT, RunStatus.TIME_LIMIT,
                 RunStatus.FEASIBLE, RunStatus.STALLED}  # fmt: skip

    scenario = build_scenario(
        scenario_file, catalog_path=catalog_path, catalog_format=catalog_format,
        catalog_start=start, catalog_raan_rates=raan_rates, n=n, tmax_days=tmax_days,
        deorbit_days=deorbit_days,
        preopt_days=preopt_days, dv_max_mps=dv_max_mps, min_transfer_days=min_transfer_days,
        eccentricity=eccentricity, flight_min_days=flight_min_days, transfer=transfer,
        **{"vehicle.accel_mps2": accel_mps2}, backend=backend,
        method=method, gap=gap, time_limit_s=time_limit_s, mip_gap=mip_gap,
        threads=threads, verbose=verbose or None,
        fallback=tuple(fallback) or None,
        **selection_overrides(altitude_km, inclination_deg, max_eccentricity, ids, exclude_ids,
                              names, types, strict),
    )  # fmt: skip
    vehicle = scenario.mission.vehicle
    if (vehicle is not None and vehicle.accel_mps2 is not None
            and scenario.mission.transfer != "low-thrust"):  # fmt: skip
        given = "--accel" if accel_mps2 is not None else f"{scenario_file}'s vehicle.accel_mps2"
        click.echo(f"warning: {given} is a low-thrust vehicle's: the impulsive model plans "
                   "without it and only checks that its burns are short against the legs "
                   "(--transfer low-thrust plans with it)", err=True)  # fmt: skip
    if force_model is not None and not fly_plan:
        click.echo("warning: --force-model is --fly's: no flight without --fly", err=True)
    force_model = force_model or "j2"
    if scenario.campaign is not None:
        click.echo(f"warning: {scenario_file} has a [campaign] table: `run` plans the one "
                   "mission of its [mission] table; `python -m sdc_cvx campaign "
                   f"{scenario_file}` plans the campaign", err=True)  # fmt: skip
    if out_dir is not None:  # before the solve: a bad --out must not cost a solve
        problem = out_folder_problem(Path(out_dir))
        if problem is None and being_flown(out_dir):
            problem = (f"{out_dir} is being flown now (python -m sdc_cvx fly): wait for it to "
                       "end, or write to another folder")  # fmt: skip
        if problem is not None:
            fail(f"--out: {problem}")
        warn_replaced_flights(out_dir)
    elif (problem := new_folder_problem()) is not None:
        fail(problem)
    catalog = read_catalog(scenario, on_invalid="set aside")  # the filters act first
    mission, solver = scenario.mission, scenario.solver

    def info(message: str) -> None:
        if not quiet:
            click.echo(message, err=True)

    catalog, _ = select_candidates(catalog, scenario, info)
    catalog = with_raan_rates(catalog, scenario, info)  # on the candidates: ~0.1 ms each
    if fly_plan:  # refused before the search: exit 2 means nothing written
        from ..flight import unflyable

        if (problem := unflyable(catalog, mission)) is not None:
            fail(f"{problem} (asked by --fly)")
    try:
        mission.check_candidates(catalog)
    except MissionError as err:
        where = f"{scenario.source}: " if scenario.source is not None else ""
        problems = "; ".join(f"mission.{problem}" for problem in str(err).split("; "))
        fail(f"{where}{problems} (catalog: {catalog.source})")
    if (problem := size_problem(len(catalog))) is not None:  # before a MemoryError, minutes on
        fail(f"{catalog.source}: {problem}")
    check_backend(solver)

    show_progress = (sys.stderr.isatty() if progress is None else progress) and not quiet
    header = run_header(catalog, mission, solver)
    edges = writes_edges(solver.time_limit_s, len(catalog), mission.transfer)
    if not edges:
        header += (f"\nNo edges.csv: the pre-optimised edge table would take about "
                   f"{edges_s(len(catalog), mission.transfer):.0f} s of the time limit "
                   "(python -m sdc_cvx edges writes it).")  # fmt: skip
    if solver.method == "certified" and solver.time_limit_s is not None:
        limit = solver.time_limit_s
        solver = dataclasses.replace(solver, time_limit_s=search_limit(
            limit, started, run_writing_s(len(catalog), mission.transfer, edges)))  # fmt: skip
        header += (f"\nThe search may run up to {solver.time_limit_s:.1f} s of the {limit:g} s "
                   "limit: it stops sooner once the plan is proven (the rest reads the catalog "
                   "and writes the run folder).")  # fmt: skip
    info(header)
    # the progress goes to OUT.log beside the run folder while the run lasts (a killed run
    # leaves it there, the next run into OUT replaces it), then into the folder as run.log;
    # it also locks OUT against a second run at once
    live_log, stream, made = open_progress_log(out_dir)
    with RunProgress(show_progress, live_log=live_log, stream=stream, made=made) as steps:
        steps.say(header, show=False)
        steps.set_phase(
            "certified search: leg costs of every pair, cheap paths, then the first relaxation"
            if solver.method == "certified"
            else "seeding: re-optimising cheap paths, then building the first MILP"
        )
        for message in ignored_options(mission, solver):  # said once, up front
            click.echo(f"warning: {message}", err=True)
            steps.say(f"warning: {message}", show=False)
        try:
            with warnings.catch_warnings(), interruptible(steps, solver.method) as stop:
                warnings.simplefilter("ignore", IgnoredOptionWarning)
                solution = solve(catalog, mission, solver=solver, progress=steps.iteration,
                                 log=steps.search_step, stop=stop)  # fmt: skip
        except KeyboardInterrupt:
            kept = f" (progress in {live_log})" if live_log is not None else ""
            fail(f"interrupted: nothing written{kept}", INTERRUPTED)
        except MissionInfeasible as err:
            steps.discard_live_log()  # a proven answer: the message says it all
            fail(f"infeasible mission: {err}", exit_code(err))
        except SolverFailure as err:
            kept = f" (progress in {live_log})" if live_log is not None else ""
            if stop():  # a Ctrl-C before any plan: interrupted, not a failure
                fail(f"interrupted before any plan: nothing written{kept}", INTERRUPTED)
            fail(f"solver failure: {err}{kept}", exit_code(err))
        steps.set_phase("writing the run folder")
        steps.say(solution.summary(), show=False)
        try:  # the edge table (edges.csv) is extra: a Ctrl-C here keeps the answer
            edge_table = preoptimize(catalog, mission, departure_day=mission.deorbit_days) \
                if edges else None  # fmt: skip
        except KeyboardInterrupt:
            edge_table = None
            steps.say("interrupted while pre-optimising the edge table: the run folder is "
                      "written without edges.csv (Ctrl-C again to stop at once, writing "
                      "nothing)")  # fmt: skip
    folder = Path(out_dir) if out_dir else None
    try:
        folder = folder or new_run_folder()
        with interruptible(steps, "certified", "finishing the run folder first") as stopped:
            write_run(folder, solution, edge_table,
                      scenario_toml=scenario.to_toml(start=day_zero(catalog)), catalog=catalog,
                      formats=("png", "svg") if svg else ("png",),
                      log=steps.log_text())  # fmt: skip
        steps.discard_live_log()
        if stopped() and fly_plan:  # the answer is kept; the user asked for no more
            fly_plan = False
            click.echo(f"not flown (interrupted): python -m sdc_cvx fly {folder} flies it",
                       err=True)  # fmt: skip
    except KeyboardInterrupt:
        steps.discard_live_log()
        if out_dir is None and folder is not None:
            with contextlib.suppress(OSError):
                folder.rmdir()  # the new sdc_run_* folder, if still empty
        fail(f"interrupted while writing: nothing written to {folder} (an earlier run folder "
             "there is kept whole)", INTERRUPTED)  # fmt: skip
    except OSError as err:
        steps.discard_live_log()  # nothing is kept beside the folder
        if out_dir is None and folder is not None:
            with contextlib.suppress(OSError):
                folder.rmdir()  # the new sdc_run_* folder, if still empty
        code = SOLVER_FAILED if err.errno in SYSTEM_ERRNOS else INPUT_ERROR
        message = err.strerror or str(err)
        if not message.startswith("cannot write"):
            message = f"cannot write the run folder {folder or '.'}: {message}"
        fail(message, code)
    start = None  # the mission start date the RAANs refer to (Catalog.start)
    if catalog.start is not None:
        start = f"start     {catalog.start.isoformat()} (the catalog's RAANs are at this date)"
    if json_out:
        click.echo(solution.to_json())
        info(solution.summary())
        if start:
            info(start)
        info(f"results   {folder}/solution.json")
    else:
        click.echo(solution.summary())
        if start:
            click.echo(start)
        click.echo(f"results   {folder}/solution.json")
    if fly_plan and solution.status == RunStatus.OVER_CAPACITY:
        info("not flown: the plan needs more propellant than the vehicle's tank holds")
    elif fly_plan and solution.status.is_solved:
        fly_folder(folder, force_model, quiet=quiet, stdout=not json_out, after_run=True)
    if solution.status == RunStatus.OVER_CAPACITY:  # written, but never called flyable
        fail(f"{solution.notes[-1]} (run folder {folder})", INFEASIBLE)
    if not solution.status.is_solved or solution.status in unsettled:
        click.echo(f"warning: {solution.status}; see the notes in solution.json", err=True)


def run_header(catalog: Catalog, mission, solver) -> str:
    """The first line of ``run``: what is planned, in a sentence."""
    start = "" if catalog.start is None else f", RAANs at {catalog.start.isoformat()}"
    return (
        f"Choosing {mission.n} of {len(catalog)} debris from {catalog.source}{start}; "
        f"T_max {mission.tmax_days:g} days; MILP backend {solver.backend}."
    )
