"""Command line: ``python -m sdc_cvx`` (or ``sdc-cvx``).

Commands: ``run [SCENARIO.toml]``, ``campaign SCENARIO.toml``, ``sweep STUDY.toml``,
``edges [SCENARIO.toml]``, ``catalog [FILE]``, ``solvers``.  Exit codes: 0 success,
2 invalid input (nothing written), 3 infeasible mission or campaign, 4 solver failure or a
full disk, 130 interrupted (Ctrl-C) with nothing written.
"""

from __future__ import annotations

import contextlib
import errno
import importlib.metadata
import importlib.util
import sys
import warnings
from functools import partial
from pathlib import Path
from typing import TYPE_CHECKING

import click

from .errors import (
    CatalogError,
    IgnoredOptionWarning,
    InputError,
    MissionError,
    MissionInfeasible,
    ScenarioError,
    SdcError,
    SolverFailure,
    SweepError,
)
from .milp.types import DEFAULT_BACKEND, MILP_BACKENDS, package_version
from .physics.orbits import DEFAULT_MAX_ECCENTRICITY

if TYPE_CHECKING:  # the commands import what they use: --help stays light
    import pandas as pd

    from .inputs.catalog import Catalog
    from .milp.types import SolverOptions
    from .study.scenario import Scenario

INPUT_ERROR = 2
INFEASIBLE = 3
SOLVER_FAILED = 4
INTERRUPTED = 130  # 128 + SIGINT, the shell's convention
EXIT_CODES: dict[type[SdcError], int] = {
    InputError: INPUT_ERROR,  # CatalogError, MissionError, ScenarioError
    SweepError: INPUT_ERROR,
    MissionInfeasible: INFEASIBLE,
    SolverFailure: SOLVER_FAILED,
}
"""Exit code of each family of :mod:`sdc_cvx.errors` (0 is success)."""
SYSTEM_ERRNOS = {errno.ENOSPC, errno.EDQUOT, errno.EIO, errno.EROFS}
"""Write failures of the machine, not of the input (a full disk): exit 4, not 2."""
MAX_DROPPED_SHOWN = 20


def exit_code(err: SdcError) -> int:
    """The exit code of an error's family (:data:`EXIT_CODES`)."""
    for family, code in EXIT_CODES.items():
        if isinstance(err, family):
            return code
    return INPUT_ERROR


def interrupted_exit(message: str):
    """Ctrl-C with worker processes about: print ``message`` and end at once (exit 130).

    The workers were terminated and die with this process anyway (``study.executors``),
    and every file was written atomically: the interpreter's exit hooks (the process
    pool's joins its manager thread) have nothing left to do but wait.
    """
    import os

    click.echo(f"error: {message}", err=True)
    sys.stdout.flush()
    sys.stderr.flush()
    os._exit(INTERRUPTED)


def fail(message: str, code: int = INPUT_ERROR):
    """Print ``message`` to stderr and exit with ``code`` (no traceback)."""
    click.echo(f"error: {message}", err=True)
    sys.exit(code)


def build_scenario(scenario_file: str | None, **overrides) -> Scenario:
    """The scenario file (or the paper case) with the command-line values applied."""
    from .study.scenario import Scenario, apply_overrides

    try:
        scenario = Scenario() if scenario_file is None else Scenario.load(scenario_file)
        return apply_overrides(scenario, overrides, origin="command line")
    except ScenarioError as err:
        fail(str(err))


def read_catalog(scenario: Scenario, on_invalid: str = "raise") -> Catalog:
    """The scenario's catalog, validated; exit 2 with its problems if invalid.

    With ``on_invalid="set aside"`` the element sets that are not orbits of this model are
    kept aside for :func:`select_candidates` (the filters act first).
    """
    import warnings

    from .errors import CatalogWarning

    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always", CatalogWarning)
        try:
            catalog = scenario.load_catalog(on_invalid=on_invalid)
        except (CatalogError, ScenarioError) as err:
            fail(str(err))
    for warning in caught:
        if issubclass(warning.category, CatalogWarning):
            click.echo(f"warning: {warning.message}", err=True)
        else:
            warnings.showwarning(warning.message, warning.category, warning.filename,
                                 warning.lineno)  # fmt: skip
    return catalog


def check_backend(solver: SolverOptions) -> None:
    """Exit 2 unless the chosen backend (or one of its fallbacks) is installed."""
    from .milp.backends import installed_backends

    installed = set(installed_backends())
    usable_chain = [b for b in (solver.backend, *solver.fallback) if b in installed]
    if usable_chain and solver.backend not in installed:
        click.echo(f"warning: {solver.backend} is not installed here; the fallback "
                   f"{usable_chain[0]} will be used", err=True)  # fmt: skip
    if not usable_chain:
        usable = ", ".join(name for name in MILP_BACKENDS if name in installed) or "none"
        fail(
            f"solver.backend {solver.backend!r} is not installed here; installed MILP "
            f"backends: {usable} (see 'sdc-cvx solvers')"
        )


def scenario_argument(command):
    return click.argument("scenario_file", metavar="[SCENARIO.toml]", required=False,
                          type=click.Path(dir_okay=False))(command)  # fmt: skip


def start_option(command):
    return click.option("--start", default=None, metavar="DATE",
                        help="Mission start date the RAANs and day 0 refer to, ISO-8601 (UTC "
                        "when naive) [scenario's, else the latest epoch].")(command)  # fmt: skip


def catalog_options(command):
    command = start_option(command)
    command = click.option(
        "--format",
        "catalog_format",
        default=None,
        help="Catalog format: csv, tle, omm or gtoc9 [from the content; the extension "
        "when the content cannot tell].",
    )(command)
    return click.option(
        "--catalog",
        "catalog_path",
        type=click.Path(dir_okay=False),
        default=None,
        help="Debris catalog (CSV: id, a_km, e, inc_deg, raan_deg[, epoch]) "
        "[scenario's, else the paper's Table 5].",
    )(command)


def selection_options(command):
    """Candidate filters (:func:`sdc_cvx.inputs.selection.select`), over ``[selection]``."""
    options = [
        click.option("--altitude-km", nargs=2, type=float, default=None,
                     metavar="LOW HIGH", help="Keep altitudes a - R_T in [LOW, HIGH] km."),
        click.option("--inclination-deg", nargs=2, type=float, default=None,
                     metavar="LOW HIGH", help="Keep inclinations in [LOW, HIGH] deg."),
        click.option("--max-eccentricity", type=float, default=None, metavar="E",
                     help=f"Drop e > E [{DEFAULT_MAX_ECCENTRICITY:g}: orbits are costed as "
                     "circular]."),
        click.option("--ids", "ids", multiple=True, metavar="PATTERN",
                     help="Keep ids matching PATTERN (shell-style, repeatable)."),
        click.option("--exclude-ids", multiple=True, metavar="PATTERN",
                     help="Drop ids matching PATTERN (shell-style, repeatable)."),
        click.option("--names", "names", multiple=True, metavar="PATTERN",
                     help='Keep names matching PATTERN (shell-style, case-insensitive, '
                     'repeatable), e.g. "SL-16 R/B*".'),
        click.option("--type", "types", multiple=True,
                     type=click.Choice(["rocket-body", "debris", "payload"]),
                     help="Keep objects of this type, told from the name (R/B, DEB; "
                     "repeatable)."),
        click.option("--strict", is_flag=True, default=None,
                     help="Refuse the catalog when the selection keeps an element set that "
                     "is not an orbit of this model [drop it with a warning]."),
    ]  # fmt: skip
    for option in reversed(options):
        command = option(command)
    return command


def selection_overrides(altitude_km, inclination_deg, max_eccentricity, ids, exclude_ids,
                        names=(), types=(), strict=None) -> dict:  # fmt: skip
    """The ``selection.*`` (and ``catalog.strict``) overrides of the filter options (None: not
    given)."""
    return {"selection.altitude_km": altitude_km, "selection.inclination_deg": inclination_deg,
            "selection.max_eccentricity": max_eccentricity, "selection.ids": tuple(ids) or None,
            "selection.exclude_ids": tuple(exclude_ids) or None,
            "selection.names": tuple(names) or None, "selection.types": tuple(types) or None,
            "catalog.strict": strict}  # fmt: skip


def select_candidates(catalog: Catalog, scenario: Scenario, echo) -> tuple[Catalog, pd.DataFrame]:
    """The candidates kept by the scenario's selection; exit 2 if none or a bad pattern.

    ``echo`` gets the "kept K of N candidates (...)" line when a filter is set or a
    debris is dropped (near-polar orbits and e > 0.05 are always dropped).  Element sets
    of ``catalog.invalid`` that the filters keep get one warning line each (file, line,
    catalogue number, reason) and a count; with ``catalog.strict`` (``--strict``) they
    are refused (exit 2).
    """
    from .inputs.selection import summary as selection_summary
    from .study.scenario import Selection

    selection = scenario.selection
    try:
        kept, report = selection.apply(catalog, strict=scenario.catalog_strict)
    except CatalogError as err:
        fail(str(err))
    except ValueError as err:
        fail(f"candidate selection: {err}")
    invalid = report[report["checks"] == "invalid"]
    for reason in invalid["reason"]:
        click.echo(f"warning: dropped, not an orbit of this model: {reason}", err=True)
    if len(invalid):
        click.echo(f"warning: {len(invalid)} element set(s) in the selection dropped: not "
                   "orbits of this model (README, 'Physical domain'); --strict refuses them",
                   err=True)  # fmt: skip
    line = selection_summary(kept, report)
    if len(kept) == 0:
        fail(f"no candidate left in {catalog.source}: {line}")
    if len(report) or selection != Selection():
        echo(line)
    return kept, report


@click.group()
@click.version_option(package_name="sdc_cvx")
def main():
    """Plan active debris removal missions (Cerf's method, CVXPY + MILP)."""


# ---------------------------------------------------------------------- edges
@main.command()
@scenario_argument
@catalog_options
@click.option("--preopt-days", type=float, default=None, help="Transfer duration bound T0 [days].")
@click.option("--dv-max", "dv_max_mps", type=float, default=None, help="Edge cost filter [m/s].")
@click.option(
    "--departure-day",
    type=float,
    default=0.0,
    show_default=True,
    help="Reference departure date of every edge [days after the start].",
)
@click.option("--all", "show_all", is_flag=True, help="Also list the dropped edges and why.")
def edges(scenario_file, catalog_path, catalog_format, start, preopt_days, dv_max_mps,
          departure_day, show_all):  # fmt: skip
    """Print the pre-optimised edge table (paper Part IV-B) as CSV on stdout.

    SCENARIO.toml (optional) gives the catalog and mission; the options override it.
    """
    import math

    from .network.edges import preoptimize

    if not (math.isfinite(departure_day) and departure_day >= 0):
        fail(f"--departure-day: expected a finite number of days >= 0, got {departure_day:g}")
    scenario = build_scenario(scenario_file, catalog_path=catalog_path,
                              catalog_format=catalog_format, catalog_start=start,
                              preopt_days=preopt_days, dv_max_mps=dv_max_mps)  # fmt: skip
    catalog = read_catalog(scenario)
    table = preoptimize(catalog, scenario.mission, departure_day=departure_day)
    frame = table.frame if show_all else table.kept
    click.echo(frame.to_csv(index=False, float_format="%.6g"), nl=False)
    click.echo(table.summary(), err=True)


# ---------------------------------------------------------------------- run
def iteration_line(record) -> str:
    """The progress line of an iteration of the paper's method, or of its rejection (the
    driver tells it twice); the certified search writes its own lines."""
    if record.rejected:
        return f"  it {record.iteration:2d}  step rejected: {record.rejected}"
    dv_lin = "-" if record.dv_linearized_mps is None else f"{record.dv_linearized_mps:8.1f}"
    dv_true = "-" if record.dv_true_mps is None else f"{record.dv_true_mps:8.1f}"
    days = "-" if record.duration_true_days is None else f"{record.duration_true_days:7.1f}"
    return (
        f"  it {record.iteration:2d}  {'->'.join(record.path) or '(none)':<28} "
        f"dV lin {dv_lin}  true {dv_true} m/s  {days} d  nodes {record.nodes}  "
        f"{record.seconds:6.2f} s  {record.note}"
    ).rstrip()


def remove_empty(folders: list[Path]) -> None:
    """Remove ``folders`` (innermost first) that are empty; leave the others."""
    for folder in folders:
        with contextlib.suppress(OSError):
            folder.rmdir()


class RunProgress:
    """The progress of a run: to stderr when asked (a terminal), and always to ``run.log``.

    Every phase is named: reading, each step of the certified search (plans, refinements,
    each relaxation MILP as it starts and its bound) or of the paper's method (each MILP
    iteration, the rejection of a step with why, the re-optimisation), and the writing.
    While a phase is silent, a heartbeat line says what is running and for how long,
    every ``heartbeat_s`` seconds.  With ``live_log``, every line is also appended to that
    file as it is said, so that a killed run leaves its progress behind.
    """

    def __init__(self, show: bool, heartbeat_s: float = 5.0, live_log: Path | None = None,
                 stream=None, made: list[Path] | None = None):  # fmt: skip
        import threading
        import time

        self.show, self.heartbeat_s, self._time = show, heartbeat_s, time.monotonic
        self.live_log = live_log
        self._made = list(made or [])
        self.log_failed = ""  # why the live log could not be written any more
        self._file = stream
        if live_log is not None and stream is None:
            live_log.parent.mkdir(parents=True, exist_ok=True)
            self._file = open(live_log, "w", encoding="utf-8", buffering=1)  # noqa: SIM115
        self.lines: list[str] = []
        self.started = self._last = self._time()
        self.phase = "reading the catalog"
        self.iterations = 0
        self._lock = threading.Lock()
        self._stop = threading.Event()
        self._thread = threading.Thread(target=self._beat, daemon=True)

    def __enter__(self):
        if self.show or self._file is not None:  # the heartbeat goes to the live log too
            self._thread.start()
        return self

    def __exit__(self, *exc):
        """Stop the heartbeat; the live log stays open (and locked) until discarded."""
        self._stop.set()
        if self._thread.is_alive():
            self._thread.join()

    def discard_live_log(self) -> None:
        """The run folder now holds ``run.log`` (or nothing is kept): remove the live copy
        beside it, then release it (removed while locked: no other run's log is hit)."""
        if self.live_log is not None:
            self.live_log.unlink(missing_ok=True)
        if self._file is not None:
            with self._lock, contextlib.suppress(OSError):
                self._file.close()
        remove_empty(self._made)  # the folders made for --out, unless the run folder is there

    def say(self, line: str, *, show: bool = True) -> None:
        from datetime import UTC, datetime

        with self._lock:
            stamp = datetime.now(UTC).strftime("%H:%M:%S")
            self.lines.append(f"{stamp} {line}")
            if self._file is not None and not self._file.closed and not self.log_failed:
                try:
                    self._file.write(f"{stamp} {line}\n")
                except OSError as err:  # a full disk: the run goes on, the log says no more
                    self.log_failed = f"{self.live_log}: {err.strerror or err}"
            self._last = self._time()
            if self.show and show:
                click.echo(line, err=True)

    def set_phase(self, phase: str) -> None:
        self.phase = phase
        self.say(f"  ... {phase}")

    def search_step(self, line: str) -> None:
        """The certified search's log callback: one line per step, the phase it is in."""
        self.say(line)
        self.phase = f"certified search, since: {line.strip()}"

    def iteration(self, record) -> None:
        """The solver's progress callback (:func:`sdc_cvx.planner.api.solve`)."""
        if record.status == "bound":  # the certified search: its own lines tell the step
            self.iterations = record.iteration + 1
            return
        self.say(iteration_line(record))
        if not record.rejected:
            self.iterations = record.iteration + 1
            self.phase = (
                f"after MILP iteration {record.iteration}: the next MILP, or the "
                "re-optimisation of the path in the true model"
            )

    def log_text(self) -> str:
        return "\n".join(self.lines) + "\n"

    def _beat(self) -> None:
        while not self._stop.wait(min(1.0, self.heartbeat_s)):
            now = self._time()
            if now - self._last >= self.heartbeat_s:
                self.say(f"  ... {now - self.started:5.0f} s: {self.phase}", show=self.show)


@main.command()
@scenario_argument
@catalog_options
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
@click.option("--verbose", is_flag=True, default=None,
              help="Show the MILP backend's own log (on stderr).")  # fmt: skip
@click.option(
    "--progress/--no-progress",
    default=None,
    hidden=True,
    help="Force the per-iteration lines on or off [on when stderr is a terminal].",
)
def run(scenario_file, catalog_path, catalog_format, start, altitude_km, inclination_deg,
        max_eccentricity, ids, exclude_ids, names, types, strict, n, tmax_days, deorbit_days,
        preopt_days, dv_max_mps,
        min_transfer_days, backend, method, gap, time_limit_s, mip_gap, threads, fallback,
        out_dir, quiet, json_out, svg, verbose, progress):  # fmt: skip
    """Select, order and plan the transfers; write solution.json and tables to a run folder.

    SCENARIO.toml (optional; default the paper's case) gives the catalog, mission,
    solver and candidate filters; the options override it ([defaults] apply when neither
    sets a value).  The run folder also gets scenario.toml, the scenario as used.  Exit
    codes: 2 invalid input (nothing written), 3 infeasible mission, 4 solver failure.
    """
    from .network.edges import preoptimize
    from .planner.api import solve
    from .report.run_folder import new_run_folder, out_folder_problem, write_run
    from .solution import RunStatus

    # a plan, but the run did not settle: say so (a new solved status needs no warning)
    unsettled = {RunStatus.CONVERGED_UNCONFIRMED, RunStatus.ITERATION_LIMIT, RunStatus.TIME_LIMIT,
                 RunStatus.FEASIBLE, RunStatus.STALLED}  # fmt: skip

    scenario = build_scenario(
        scenario_file, catalog_path=catalog_path, catalog_format=catalog_format,
        catalog_start=start, n=n, tmax_days=tmax_days, deorbit_days=deorbit_days,
        preopt_days=preopt_days, dv_max_mps=dv_max_mps, min_transfer_days=min_transfer_days,
        backend=backend, method=method, gap=gap, time_limit_s=time_limit_s, mip_gap=mip_gap,
        threads=threads, verbose=verbose or None,
        fallback=tuple(fallback) or None,
        **selection_overrides(altitude_km, inclination_deg, max_eccentricity, ids, exclude_ids,
                              names, types, strict),
    )  # fmt: skip
    if out_dir is not None:  # before the solve: a bad --out must not cost a solve
        problem = out_folder_problem(Path(out_dir))
        if problem is not None:
            fail(f"--out: {problem}")
    catalog = read_catalog(scenario, on_invalid="set aside")  # the filters act first
    mission, solver = scenario.mission, scenario.solver

    def info(message: str) -> None:
        if not quiet:
            click.echo(message, err=True)

    catalog, _ = select_candidates(catalog, scenario, info)
    try:
        mission.check_candidates(catalog)
    except MissionError as err:
        where = f"{scenario.source}: " if scenario.source is not None else ""
        problems = "; ".join(f"mission.{problem}" for problem in str(err).split("; "))
        fail(f"{where}{problems} (catalog: {catalog.source})")
    check_backend(solver)

    show_progress = (sys.stderr.isatty() if progress is None else progress) and not quiet
    header = run_header(catalog, mission, solver)
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
        from .planner.api import ignored_options

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
            fail(f"solver failure: {err}{kept}", exit_code(err))
        steps.set_phase("writing the run folder")
        steps.say(solution.summary(), show=False)
        edge_table = preoptimize(catalog, mission, departure_day=mission.deorbit_days)
    folder = Path(out_dir) if out_dir else None
    try:
        folder = folder or new_run_folder()
        write_run(folder, solution, edge_table, scenario_toml=scenario.to_toml(),
                  catalog=catalog, formats=("png", "svg") if svg else ("png",),
                  log=steps.log_text())  # fmt: skip
        steps.discard_live_log()
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
    if not solution.status.is_solved or solution.status in unsettled:
        click.echo(f"warning: {solution.status}; see the notes in solution.json", err=True)


def open_progress_log(out_dir):
    """``(live_log, stream, made)``: the progress log beside ``--out`` while a run lasts.

    ``OUT.log`` beside the folder (a killed run leaves it there, the next run into OUT
    replaces it), locked, so a second run into OUT at once is refused; the hidden stages a
    killed run left are removed now that OUT is ours.  ``made``: the folders above
    ``--out`` created for it (removed if unused).  Without ``--out``: no log.  Exit 2
    when OUT is busy, the log is a file of the user's, or it cannot be written.
    """
    from .report.run_folder import live_log_path, open_live_log, remove_stale_stages

    if out_dir is None:
        return None, None, []
    live_log = live_log_path(out_dir)
    made = [p for p in (live_log.parent, *live_log.parent.parents) if not p.exists()]
    try:
        live_log.parent.mkdir(parents=True, exist_ok=True)
        stream = open_live_log(out_dir)
        remove_stale_stages(out_dir)
    except OSError as err:  # FileExistsError: another run is writing OUT, a user's file
        remove_empty(made)
        if isinstance(err, FileExistsError):
            fail(f"--out: {err}")
        fail(f"--out: cannot write the progress log {live_log}: {err.strerror or err}")
    return live_log, stream, made


@contextlib.contextmanager
def interruptible(steps: RunProgress, method: str):
    """Ctrl-C during a solve: the certified search stops at its next step with the best
    plan so far (a second Ctrl-C, or the paper's method, stops at once: nothing written).

    Yields the ``stop`` callable of :func:`sdc_cvx.planner.api.solve`.
    """
    import signal
    import threading

    asked = threading.Event()

    def on_sigint(signum, frame):
        if asked.is_set() or method != "certified":
            raise KeyboardInterrupt
        asked.set()
        steps.say("interrupted: stopping at the next step with the best plan so far and its "
                  "gap (Ctrl-C again to stop at once, writing nothing)")  # fmt: skip

    if signal.getsignal(signal.SIGINT) is signal.SIG_IGN:  # started to ignore Ctrl-C (a
        yield asked.is_set  # script's background job): it stays ignored, as for sweep
        return
    try:
        previous = signal.signal(signal.SIGINT, on_sigint)
    except ValueError:  # not the main thread: Ctrl-C keeps its usual meaning
        yield asked.is_set
        return
    try:
        yield asked.is_set
    finally:
        signal.signal(signal.SIGINT, previous)


def run_header(catalog: Catalog, mission, solver) -> str:
    """The first line of ``run``: what is planned, in a sentence."""
    start = "" if catalog.start is None else f", RAANs at {catalog.start.isoformat()}"
    return (
        f"Choosing {mission.n} of {len(catalog)} debris from {catalog.source}{start}; "
        f"T_max {mission.tmax_days:g} days; MILP backend {solver.backend}."
    )


# ---------------------------------------------------------------------- catalog
def catalog_table(catalog: Catalog) -> str:
    """The catalog as an aligned text table, in people's units."""
    import pandas as pd

    frame = catalog.frame
    columns = {"id": frame["id"].astype(str)}
    if "name" in frame.columns:
        columns["name"] = frame["name"].astype(str)
    formats = [
        ("altitude [km]", "altitude_km", "{:.1f}"),
        ("inclination [deg]", "inc_deg", "{:.4f}"),
        ("RAAN [deg]", "raan_deg", "{:.4f}"),
        ("J2 rate [deg/day]", "raan_rate_deg_per_day", "{:.6f}"),
        ("e", "e", "{:.6f}"),
        ("a_km", "a_km", "{:.3f}"),
    ]
    for title, column, fmt in formats:
        columns[title] = frame[column].map(fmt.format)
    return pd.DataFrame(columns).to_string(index=False)


@main.command("catalog")
@click.argument("file", metavar="[FILE]", required=False, type=click.Path(dir_okay=False))
@click.option(
    "--format",
    "catalog_format",
    default=None,
    help="csv, tle, omm or gtoc9 [from the content; the extension when it cannot tell].",
)
@start_option
@selection_options
@click.option(
    "--clusters",
    is_flag=True,
    help="Print the dense groups of the selection (altitude x inclination cells) "
    "with their counts, J2 rate and RAAN spreads, instead of every object.",
)
@click.option(
    "--min-objects",
    type=click.IntRange(min=2),
    default=10,
    show_default=True,
    help="With --clusters: the fewest objects a group has.",
)
@click.option(
    "--figure",
    "figure_path",
    type=click.Path(dir_okay=False),
    default=None,
    help="With --clusters: also save the figure (altitude against inclination, "
    "RAAN against J2 rate) to this .png or .svg file.",
)
def catalog_command(file, catalog_format, start, altitude_km, inclination_deg, max_eccentricity,
                    ids, exclude_ids, names, types, strict, clusters, min_objects,
                    figure_path):  # fmt: skip
    """Validate a debris catalog and print it as a table (default: the paper's Table 5).

    The candidate filters drop debris as ``run`` does, and act first: element sets they
    drop are never validated; those they keep that are not orbits of this model are
    dropped with a warning line each (refused with --strict).  The dropped ones and why
    go to stderr.  --clusters prints the catalogue's dense groups instead, so that a
    selection can be chosen (e.g. ``--type rocket-body --clusters``).
    """
    if figure_path is not None and not clusters:
        fail("--figure needs --clusters (the figure is the clusters' figure)")
    if figure_path is not None and Path(figure_path).suffix.lower() not in (".png", ".svg"):
        fail(f"--figure: expected a .png or .svg file name, got {figure_path!r}")
    filters = selection_overrides(altitude_km, inclination_deg, max_eccentricity, ids, exclude_ids,
                                  names, types, strict)  # fmt: skip
    scenario = build_scenario(None, catalog_path=file, catalog_format=catalog_format,
                              catalog_start=start, **filters)  # fmt: skip
    catalog = read_catalog(scenario, on_invalid="set aside")  # the filters act first
    catalog, report = select_candidates(catalog, scenario, partial(click.echo, err=True))
    if clusters:
        clusters_output(catalog, min_objects, figure_path)
        return
    # the orbits dropped, and why (not those the patterns or types leave out, nor the
    # element sets already warned about)
    chosen = {"ids", "names", "type", "excluded", "invalid"}
    listed = report["checks"].map(lambda checks: not set(checks.split(",")) & chosen)
    orbits = report[listed.astype(bool)]
    for row in orbits.head(MAX_DROPPED_SHOWN).itertuples():
        click.echo(f"  dropped {row.id}: {row.reason}", err=True)
    if len(orbits) > MAX_DROPPED_SHOWN:
        click.echo(f"  ... and {len(orbits) - MAX_DROPPED_SHOWN} more dropped", err=True)
    click.echo(catalog_table(catalog))
    start = "" if catalog.start is None else f", RAANs at {catalog.start.isoformat()}"
    click.echo(f"{len(catalog)} debris from {catalog.source}{start}", err=True)


def clusters_output(catalog: Catalog, min_objects: int, figure_path: str | None) -> None:
    """The ``catalog --clusters`` table on stdout, the figure to ``figure_path``."""
    from .inputs.clusters import clusters_table, find_clusters

    found = find_clusters(catalog, min_objects=min_objects)
    click.echo(clusters_table(found))
    click.echo(f"{len(found.table)} groups of at least {min_objects} objects among "
               f"{len(catalog)} from {catalog.source}; narrow the selection to one with the "
               "flags of its 'select' column", err=True)  # fmt: skip
    if figure_path is not None:
        from .report.clusters import plot_clusters

        figure = plot_clusters(catalog, found)
        try:
            figure.savefig(figure_path, dpi=120)
        except OSError as err:
            fail(f"--figure: cannot write {figure_path}: {err.strerror or err}")
        click.echo(f"figure    {figure_path}", err=True)


# ---------------------------------------------------------------------- solvers
@main.command()
def solvers():
    """List the MILP backends CVXPY can use here, with their package versions."""
    from .milp.backends import BACKENDS, installed_backends

    installed = set(installed_backends())
    rows = [("backend", "installed", "package", "version")]
    for name, backend in BACKENDS.items():
        package = backend.module
        rows.append(
            (
                name + (" *" if name == DEFAULT_BACKEND else ""),
                "yes" if name in installed else "no",
                package,
                package_version(package) or "-",
            )
        )
    widths = [max(len(row[k]) for row in rows) for k in range(len(rows[0]))]
    for row in rows:
        click.echo("  ".join(cell.ljust(w) for cell, w in zip(row, widths, strict=True)).rstrip())
    click.echo(f"* default backend; cvxpy {importlib.metadata.version('cvxpy')}")


def out_option(prefix: str):
    """``--out DIR``, defaulting to a new ``{prefix}*`` folder here."""
    return click.option("--out", "out_dir", type=click.Path(file_okay=False), default=None,
                        help=f"Output folder [a new {prefix}* folder here].")  # fmt: skip


def parallel_options(command):
    """``--workers`` and ``--scheduler``: where independent solves run."""
    command = click.option(
        "--scheduler", default=None,
        help="Address of a Dask distributed scheduler (tcp://host:8786) instead of a local "
        "pool; needs the dask extra.")(command)  # fmt: skip
    return click.option("--workers", type=click.IntRange(min=1), default=None,
                        help="Local processes [one per core].")(command)  # fmt: skip


@main.command("sweep")
@click.argument("study_file", metavar="STUDY.toml", type=click.Path(dir_okay=False))
@out_option("sdc_sweep_")
@parallel_options
@click.option("--resume", is_flag=True, help="Skip the scenarios already finished in --out.")
@click.option("--progress/--no-progress", default=None, hidden=True)
def sweep_command(study_file, out_dir, workers, scheduler, resume, progress):
    """Run a trade study: a base scenario and a grid / list of overrides, one row each.

    Every scenario is validated before any solve; each result is written as soon as it
    finishes (results.csv and one solution.json per scenario), so --resume after an
    interruption only runs what is missing.
    """
    from .report.run_folder import new_run_folder
    from .study.results import SOLVED_STATUSES
    from .study.runner import run_study, sweep_folder_problem
    from .study.study import load_study

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
        out = Path(out_dir)
        if out.exists() and not out.is_dir():
            fail(f"--out: {out} is a file, not a folder")
        if (out / "results.csv").exists() and not resume:
            fail(f"--out: {out} already holds results.csv: add --resume to finish that "
                 "sweep, or choose a new folder")  # fmt: skip
        problem = sweep_folder_problem(out)
        if problem is not None:
            fail(f"--out: {problem}")
    folder = Path(out_dir) if out_dir else new_run_folder(prefix="sdc_sweep_")
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
    click.echo(f"{int(done.sum())} of {len(results)} scenarios solved; results in "
               f"{folder}/results.csv")  # fmt: skip


# ---------------------------------------------------------------------- campaign
@main.command("campaign")
@click.argument("scenario_file", metavar="SCENARIO.toml", type=click.Path(dir_okay=False))
@out_option("sdc_campaign_")
@parallel_options
@click.option(
    "--time-limit",
    "time_limit_s",
    type=float,
    default=None,
    help="Time limit of the whole search [s]; the best campaign is then returned with its gap.",
)
@click.option(
    "--gap", type=float, default=None, help="Relative gap of a certified answer [0.001 = 0.1 %]."
)
@click.option("--quiet", is_flag=True, help="No progress, only the summary.")
@click.option("--json", "json_out", is_flag=True,
              help="Write campaign.json to stdout (and nothing else there).")  # fmt: skip
@click.option("--svg", is_flag=True, help="Also save the figures as SVG.")
@click.option("--progress/--no-progress", default=None, hidden=True)
def campaign_command(scenario_file, out_dir, time_limit_s, gap, workers, scheduler, quiet,
                     json_out, svg, progress):  # fmt: skip
    """Plan a removal campaign: K missions on given launch days, each debris removed once.

    SCENARIO.toml has a [campaign] table (launch_days, or missions with first_launch_day
    and period_days; n and tmax_days per mission; must_remove) and the usual [catalog],
    [mission] (every mission's defaults), [solver] and [selection] tables.  Writes a
    campaign folder: campaign.json, missions.csv, history.csv, campaign.log, the figures
    and one run folder per mission.  Exit codes: 2 invalid input (nothing written),
    3 infeasible campaign (campaign.json says why), 4 solver failure.
    """
    from .campaign.search import solve_campaign
    from .report.campaign_folder import (
        campaign_folder_problem,
        write_infeasible_campaign,
    )
    from .report.run_folder import new_run_folder

    if scheduler is not None and importlib.util.find_spec("distributed") is None:
        fail("--scheduler needs dask.distributed, which is not installed here: "
             "pip install 'sdc_cvx[dask]'")  # fmt: skip
    if gap is not None and not 0 <= gap < 1:
        fail(f"--gap must be in [0, 1), got {gap:g}")
    if time_limit_s is not None and not time_limit_s > 0:
        fail(f"--time-limit must be > 0 seconds, got {time_limit_s:g}")
    scenario = build_scenario(scenario_file)
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
    campaign = scenario.campaign
    gap = scenario.solver.gap if gap is None else gap
    time_limit_s = scenario.solver.time_limit_s if time_limit_s is None else time_limit_s
    catalog = read_catalog(scenario, on_invalid="set aside")  # the filters act first

    def info(message: str) -> None:
        if not quiet:
            click.echo(message, err=True)

    catalog, _ = select_candidates(catalog, scenario, info)
    try:
        campaign.check_candidates(catalog)
    except MissionError as err:
        fail(f"{scenario_file}: campaign: {err} (catalog: {catalog.source})")
    check_backend(scenario.solver)
    header = (
        f"Campaign of {len(campaign)} missions (launch days "
        f"{', '.join(f'{d:g}' for d in campaign.launch_days)}; n = "
        f"{', '.join(str(m.n) for m in campaign.missions)}) from {len(catalog)} candidates of "
        f"{catalog.source}; gap {gap:g}."
    )
    info(header)
    show_progress = (sys.stderr.isatty() if progress is None else progress) and not quiet
    live_log, stream, made = open_progress_log(out_dir)
    folder = Path(out_dir) if out_dir else None
    start_utc = None if catalog.start is None else catalog.start.isoformat()
    with RunProgress(show_progress, live_log=live_log, stream=stream, made=made) as steps:
        steps.say(header, show=False)
        steps.set_phase("campaign: each launch alone, then the greedy campaign")
        try:
            solution = solve_campaign(catalog, campaign, solver=scenario.solver, gap=gap,
                                      time_limit_s=time_limit_s, workers=workers,
                                      scheduler=scheduler, log=steps.search_step)  # fmt: skip
        except MissionInfeasible as err:
            steps.say(f"infeasible: {err}")
            try:
                folder = folder or new_run_folder(prefix="sdc_campaign_")
                write_infeasible_campaign(folder, str(err), start_utc=start_utc,
                                          campaign=campaign.to_dict(),
                                          scenario_toml=scenario.to_toml(),
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
            fail(f"solver failure: {err}{kept}", exit_code(err))
        steps.set_phase("writing the campaign folder")
        steps.say(solution.summary(), show=False)
    try:
        folder = folder or new_run_folder(prefix="sdc_campaign_")
        solution.save(folder, formats=("png", "svg") if svg else ("png",),
                      scenario_toml=scenario.to_toml(), log=steps.log_text())  # fmt: skip
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
    if not solution.certified:
        click.echo(f"warning: {solution.status}; see the notes in campaign.json", err=True)
