"""The arguments and options several commands share: the scenario file, the catalog and
its start date, the candidate filters, ``--out`` and where independent solves run."""

from __future__ import annotations

import click

from ..physics.orbits import DEFAULT_MAX_ECCENTRICITY


def scenario_argument(command):
    return click.argument("scenario_file", metavar="[SCENARIO.toml]", required=False,
                          type=click.Path(dir_okay=False))(command)  # fmt: skip


def start_option(command):
    return click.option("--start", default=None, metavar="DATE",
                        help="Mission start date the RAANs and day 0 refer to, ISO-8601 (UTC "
                        "when naive) [scenario's, else the latest epoch within 10 years of "
                        "the median one].")(command)  # fmt: skip


def raan_rates_option(command):
    """``--raan-rates j2|sgp4``: the debris' RAAN rates the planner uses (``[catalog]
    raan_rates``)."""
    return click.option("--raan-rates", "raan_rates", default=None,
                        type=click.Choice(["j2", "sgp4"], case_sensitive=False),
                        help="The debris' RAAN rates: j2, the first-order J2 rates of the "
                        "elements; sgp4, each debris' rate fitted to its SGP4 propagation over "
                        "the mission window [scenario's, else j2].")(command)  # fmt: skip


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
        help="Debris catalog: CSV (id, a_km, e, inc_deg, raan_deg[, epoch]), TLE, OMM or "
        "GTOC9 (--format) [scenario's, else the paper's Table 5].",
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
