"""What the commands read: the scenario with the flags applied, its catalog, its backend
and the candidates it selects; a bad input ends the command with exit 2 and its message.
"""

from __future__ import annotations

import time
import warnings
from typing import TYPE_CHECKING

import click

from ..errors import CatalogError, CatalogWarning, ScenarioError
from ..milp.types import MILP_BACKENDS, backend_importable
from .exits import fail

if TYPE_CHECKING:  # the commands import what they use: --help stays light
    import pandas as pd

    from ..inputs.catalog import Catalog
    from ..milp.types import SolverOptions
    from ..study.scenario import Scenario


def build_scenario(scenario_file: str | None, **overrides) -> Scenario:
    """The scenario file (or the paper case) with the command-line values applied."""
    from ..study.scenario import Scenario, apply_overrides

    try:
        scenario = Scenario() if scenario_file is None else Scenario.load(
            scenario_file, catalog_path=overrides.get("catalog_path"))  # its own may be gone
        return apply_overrides(scenario, overrides, origin="command line")
    except ScenarioError as err:
        if scenario_file is not None and _asks_gtoc9_cost(scenario_file):
            fail(f"{scenario_file}: objective = 'gtoc9-cost' is GTOC9's Kessler Run: plan it "
                 f"with 'python -m sdc_cvx gtoc9-plan {scenario_file}'")  # fmt: skip
        fail(str(err))


def _asks_gtoc9_cost(scenario_file: str) -> bool:
    """Whether the file's ``[campaign]`` asks GTOC9's cost J (a Kessler Run scenario)."""
    import tomllib

    try:
        with open(scenario_file, "rb") as handle:
            campaign = tomllib.load(handle).get("campaign", {})
    except (OSError, tomllib.TOMLDecodeError):
        return False
    return isinstance(campaign, dict) and campaign.get("objective") == "gtoc9-cost"


def read_catalog(scenario: Scenario, on_invalid: str = "raise") -> Catalog:
    """The scenario's catalog, validated; exit 2 with its problems if invalid.

    With ``on_invalid="set aside"`` the element sets that are not orbits of this model are
    kept aside for :func:`select_candidates` (the filters act first).
    """
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
    """Exit 2 unless the chosen backend (or one of its fallbacks) is installed.

    When the chosen backend's module is here, CVXPY is not imported to ask: a run of the
    certified search whose relaxations the labels solve never needs it (the paper case:
    1-2 s of a 4-6 s run).
    """
    if backend_importable(solver.backend):
        return
    from ..milp.backends import installed_backends

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


def select_candidates(catalog: Catalog, scenario: Scenario, echo) -> tuple[Catalog, pd.DataFrame]:
    """The candidates kept by the scenario's selection; exit 2 if none or a bad pattern.

    ``echo`` gets the "kept K of N candidates (...)" line when a filter is set or a
    debris is dropped (near-polar orbits and e > 0.05 are always dropped).  Element sets
    of ``catalog.invalid`` that the filters keep get one warning line each (file, line,
    catalogue number, reason) and a count; with ``catalog.strict`` (``--strict``) they
    are refused (exit 2).
    """
    from ..inputs.selection import summary as selection_summary
    from ..study.scenario import Selection

    selection = scenario.selection
    try:
        kept, report = selection.apply(catalog, strict=scenario.catalog_strict)
    except CatalogError as err:
        fail(str(err))
    except ValueError as err:  # a pattern matching nothing: where it was written, and what
        where = ("" if scenario.source is None
                 else f" ({scenario.source} [selection], or the filters given as options)")
        fail(f"candidate selection{where}: {err} ({catalog.source})")
    invalid = report[report["checks"] == "invalid"]
    for reason in invalid["reason"]:
        click.echo(f"warning: dropped, not an orbit of this model: {reason}", err=True)
    if len(invalid):
        click.echo(f"warning: {len(invalid)} element set(s) in the selection dropped: not "
                   "orbits of this model (docs/guide/catalogues.md, 'Physical domain'); "
                   "--strict refuses them",
                   err=True)  # fmt: skip
    line = selection_summary(kept, report)
    if len(kept) == 0:
        fail(f"no candidate left in {catalog.source}: {line}")
    if len(report) or selection != Selection():
        echo(line)
    return kept, report


def with_raan_rates(catalog: Catalog, scenario: Scenario, echo) -> Catalog:
    """The candidates with the scenario's RAAN rates (``catalog.raan_rates``); exit 2 when
    SGP4 cannot propagate one over the window.

    ``echo`` gets a line with the window, the time the fit took and how far the fitted
    rates are from the J2 ones.  Apply it after the selection: about 0.1 ms per debris.
    """
    if scenario.catalog_raan_rates == "j2":
        return catalog
    started = time.perf_counter()
    try:
        fitted = scenario.with_raan_rates(catalog)
    except CatalogError as err:
        fail(str(err))
    except ValueError as err:
        fail(f"catalog.raan_rates: {err}")
    seconds = time.perf_counter() - started
    shift = fitted.frame["raan_rate_deg_per_day"] - catalog.frame["raan_rate_deg_per_day"]
    built = "" if "epoch" in catalog.frame.columns else (
        "; the element sets are the catalog's elements dated at its start (no epochs)")
    echo(f"RAAN rates fitted to SGP4 over {scenario.rate_window_days():g} days for "
         f"{len(fitted)} debris in {seconds:.2f} s: {shift.min():+.4f} to {shift.max():+.4f} "
         f"deg/day from the J2 rates{built}")  # fmt: skip
    return fitted


def day_zero(catalog: Catalog):
    """The date the catalog's RAANs and day 0 refer to, as a ``datetime`` (None without
    epochs): kept in the run folder's ``scenario.toml``."""
    return None if catalog.start is None else catalog.start.to_pydatetime()
