"""Command line: ``python -m sdc_cvx`` (or ``sdc-cvx``)."""

from __future__ import annotations

import sys

import click

from .catalog import Catalog, CatalogError
from .edges import preoptimize
from .mission import Mission, MissionError

INPUT_ERROR = 2


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
