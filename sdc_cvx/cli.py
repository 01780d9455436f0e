"""Command line: ``python -m sdc_cvx`` (or ``sdc-cvx``)."""

from __future__ import annotations

import sys
from pathlib import Path

import click

from .backends import SolverOptions
from .catalog import Catalog, CatalogError
from .edges import preoptimize
from .mission import Mission, MissionError
from .output import new_run_folder, write_run
from .sequential import MissionInfeasible, SolverFailure, solve

INPUT_ERROR = 2
INFEASIBLE = 3
SOLVER_FAILED = 4


def fail(message: str, code: int = INPUT_ERROR):
    """Print ``message`` to stderr and exit with ``code`` (no traceback)."""
    click.echo(f"error: {message}", err=True)
    sys.exit(code)


def load_catalog(path) -> Catalog:
    """The catalog at ``path``, or the paper's Table 5 when ``path`` is None."""
    try:
        return Catalog.paper_case() if path is None else Catalog.from_csv(path)
    except CatalogError as err:
        fail(str(err))


def make_mission(**fields) -> Mission:
    """A validated mission from the options that were given (others keep their defaults)."""
    try:
        return Mission(**{k: v for k, v in fields.items() if v is not None})
    except MissionError as err:
        fail(str(err))


catalog_option = click.option(
    "--catalog",
    "catalog_path",
    type=click.Path(dir_okay=False),
    default=None,
    help="Debris catalog CSV (id, a_km, e, inc_deg, raan_deg[, epoch]); default: paper Table 5.",
)


@click.group()
@click.version_option(package_name="sdc_cvx")
def main():
    """Plan active debris removal missions (Cerf's method, CVXPY + MILP)."""


@main.command()
@catalog_option
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
def edges(catalog_path, preopt_days, dv_max_mps, departure_day, show_all):
    """Print the pre-optimised edge table (paper Part IV-B) as CSV on stdout."""
    catalog = load_catalog(catalog_path)
    mission = make_mission(preopt_days=preopt_days, dv_max_mps=dv_max_mps)
    table = preoptimize(catalog, mission, departure_day=departure_day)
    frame = table.frame if show_all else table.kept
    click.echo(frame.to_csv(index=False, float_format="%.6g"), nl=False)
    click.echo(table.summary(), err=True)


def print_iteration(record):
    """One progress line per iteration (to stderr)."""
    dv_lin = "-" if record.dv_linearized_mps is None else f"{record.dv_linearized_mps:8.1f}"
    dv_true = "-" if record.dv_true_mps is None else f"{record.dv_true_mps:8.1f}"
    days = "-" if record.duration_true_days is None else f"{record.duration_true_days:7.1f}"
    click.echo(
        f"  it {record.iteration:2d}  {'->'.join(record.path) or '(none)':<28} "
        f"dV lin {dv_lin}  true {dv_true} m/s  {days} d  nodes {record.nodes}  "
        f"{record.seconds:6.2f} s  {record.note}",
        err=True,
    )


@main.command()
@catalog_option
@click.option("--n", type=int, default=None, help="Number of debris to remove [5].")
@click.option("--tmax-days", type=float, default=None, help="Mission duration limit [365.25 days].")
@click.option("--deorbit-days", type=float, default=None, help="Operations time per debris [0].")
@click.option("--preopt-days", type=float, default=None, help="Pre-optimisation bound T0 [61].")
@click.option("--backend", default="HIGHS", show_default=True, help="MILP backend (CVXPY name).")
@click.option(
    "--time-limit", "time_limit_s", type=float, default=None, help="Time limit per MILP solve [s]."
)
@click.option(
    "--out",
    "out_dir",
    type=click.Path(file_okay=False),
    default=None,
    help="Output folder [a new sdc_run_* folder here].",
)
@click.option("--quiet", is_flag=True, help="No progress, only the summary.")
def run(catalog_path, n, tmax_days, deorbit_days, preopt_days, backend, time_limit_s, out_dir,
        quiet):  # fmt: skip
    """Select, order and plan the transfers; write solution.json and tables to a run folder."""
    catalog = load_catalog(catalog_path)
    mission = make_mission(n=n, tmax_days=tmax_days, deorbit_days=deorbit_days,
                           preopt_days=preopt_days)  # fmt: skip
    try:
        solver = SolverOptions(backend=backend, time_limit_s=time_limit_s)
        mission.check_candidates(len(catalog))
    except ValueError as err:
        fail(str(err))
    if not quiet:
        click.echo(f"{catalog!r}: choosing {mission.n}, T_max {mission.tmax_days:g} days", err=True)
    try:
        solution = solve(
            catalog, mission, solver=solver, progress=None if quiet else print_iteration
        )
    except MissionInfeasible as err:
        fail(f"infeasible mission: {err}", INFEASIBLE)
    except SolverFailure as err:
        fail(f"solver failure: {err}", SOLVER_FAILED)
    folder = Path(out_dir) if out_dir else new_run_folder()
    write_run(folder, solution, preoptimize(catalog, mission, departure_day=mission.deorbit_days))
    click.echo(solution.summary())
    if solution.status != "converged":
        click.echo(f"warning: {solution.status}; see the notes in solution.json", err=True)
    click.echo(f"results   {folder}/solution.json")
