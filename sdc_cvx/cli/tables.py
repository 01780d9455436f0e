"""The commands that print a table: ``edges`` (the pre-optimised edges), ``catalog``
(the validated catalog, or its dense groups) and ``solvers`` (the MILP backends here)."""

from __future__ import annotations

import importlib.metadata
import math
from functools import partial
from pathlib import Path
from typing import TYPE_CHECKING

import click

from ..milp.types import DEFAULT_BACKEND, package_version
from .exits import fail
from .options import (
    catalog_options,
    scenario_argument,
    selection_options,
    selection_overrides,
    start_option,
)
from .reading import build_scenario, read_catalog, select_candidates

if TYPE_CHECKING:
    from ..inputs.catalog import Catalog


MAX_DROPPED_SHOWN = 20


@click.command("edges")
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
@selection_options
def edges_command(scenario_file, catalog_path, catalog_format, start, preopt_days, dv_max_mps,
                  departure_day, show_all, altitude_km, inclination_deg, max_eccentricity, ids,
                  exclude_ids, names, types, strict):  # fmt: skip
    """Print the pre-optimised edge table (paper Part IV-B) as CSV on stdout.

    SCENARIO.toml (optional) gives the catalog and mission; the options override it.  The
    candidate filters act first, as for ``run`` (element sets that are not orbits of this
    model are dropped with a warning, refused with --strict).
    """
    from ..network.edges import preoptimize
    from ..planner.size_guard import size_problem

    if not (math.isfinite(departure_day) and departure_day >= 0):
        fail(f"--departure-day: expected a finite number of days >= 0, got {departure_day:g}")
    filters = selection_overrides(altitude_km, inclination_deg, max_eccentricity, ids, exclude_ids,
                                  names, types, strict)  # fmt: skip
    scenario = build_scenario(scenario_file, catalog_path=catalog_path,
                              catalog_format=catalog_format, catalog_start=start,
                              preopt_days=preopt_days, dv_max_mps=dv_max_mps,
                              **filters)  # fmt: skip
    catalog = read_catalog(scenario, on_invalid="set aside")  # the filters act first
    catalog, _ = select_candidates(catalog, scenario, partial(click.echo, err=True))
    if (problem := size_problem(len(catalog))) is not None:  # a table of every ordered pair
        fail(f"{catalog.source}: {problem}")
    table = preoptimize(catalog, scenario.mission, departure_day=departure_day)
    frame = table.frame if show_all else table.kept
    click.echo(frame.to_csv(index=False, float_format="%.6g"), nl=False)
    click.echo(table.summary(), err=True)


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


@click.command("catalog")
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
    from ..inputs.clusters import clusters_table, find_clusters

    found = find_clusters(catalog, min_objects=min_objects)
    click.echo(clusters_table(found))
    click.echo(f"{len(found.table)} groups of at least {min_objects} objects among "
               f"{len(catalog)} from {catalog.source}; narrow the selection to one with the "
               "flags of its 'select' column", err=True)  # fmt: skip
    if figure_path is not None:
        from ..report.clusters import plot_clusters

        figure = plot_clusters(catalog, found)
        try:
            figure.savefig(figure_path, dpi=120)
        except OSError as err:
            fail(f"--figure: cannot write {figure_path}: {err.strerror or err}")
        click.echo(f"figure    {figure_path}", err=True)


@click.command("solvers")
def solvers_command():
    """List the MILP backends CVXPY can use here, with their package versions."""
    from ..milp.backends import BACKENDS, installed_backends

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
