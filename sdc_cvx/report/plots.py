"""Figures of a planned mission: the paper's Fig. 17, 18, 19 and Table 7 as pictures.

Every function returns a :class:`matplotlib.figure.Figure` built with the
object-oriented API only (no pyplot, no global state), so it works headless and
in threads; :func:`save_figures` writes them all atomically.

The mission timeline drawn here is the one of :func:`~sdc_cvx.physics.plan.evaluate_plan`:
the vehicle is at the first debris at t = 0; leg k leaves at ``departure_day``, makes a
Hohmann transfer (instantaneous at this scale) to its circular drift orbit
(``drift_alt_km``, ``drift_inc_deg``), coasts ``duration_days`` while J2 turns its RAAN at
the drift orbit's rate (Eq. 8), then transfers to the target debris, where operations
last ``mission.deorbit_days`` before the next departure.

All RAAN rates are recomputed from the catalog elements with the mission's J2
(``solution.mission.j2``), the same model the solver used, so the plotted RAAN gaps
close exactly at each arrival.

The figures are drawn in :mod:`~sdc_cvx.report.orbit_plots` (Figs. 17, 18),
:mod:`~sdc_cvx.report.cost_plot` (Fig. 19) and :mod:`~sdc_cvx.report.iterations_plot`
(Table 7), with what they share in :mod:`~sdc_cvx.report.plot_common`.  They read a plan
through :class:`~sdc_cvx.report.plan_record.DrawnPlan` (a
:class:`~sdc_cvx.solution.Solution` is one), so that ``Solution.plot`` may call them.
"""

from __future__ import annotations

import os
from collections.abc import Sequence
from pathlib import Path

from matplotlib.figure import Figure

from ..inputs.catalog import Catalog
from .atomic import write_figure
from .cost_plot import plot_cost
from .iterations_plot import plot_iterations
from .orbit_plots import plot_orbits, plot_raan, raan_gap_history, vehicle_altitude
from .plan_record import DrawnPlan
from .plot_common import FIGURE_SIZE, _positions

__all__ = [
    "FIGURE_NAMES",
    "FIGURE_SIZE",
    "SUPPORTED_FORMATS",
    "plot_cost",
    "plot_iterations",
    "plot_orbits",
    "plot_raan",
    "raan_gap_history",
    "save_figures",
    "vehicle_altitude",
]

FIGURE_NAMES = ("orbits", "raan", "cost", "iterations")
"""File stems written by :func:`save_figures`, in order."""

SUPPORTED_FORMATS = ("png", "svg", "pdf")
"""File formats :func:`save_figures` accepts."""


def figures(solution: DrawnPlan, catalog: Catalog | None = None) -> dict[str, Figure]:
    """The four figures of a run folder, by name (:data:`FIGURE_NAMES`), not saved.

    ``catalog`` defaults to ``solution.catalog`` (set by :func:`sdc_cvx.solve`); without
    either, only ``cost`` and ``iterations`` are drawn.  :meth:`Solution.plot` calls this.
    """
    catalog = solution.catalog if catalog is None else catalog
    drawn = {}
    if catalog is not None:
        drawn["orbits"] = plot_orbits(solution, catalog)
        drawn["raan"] = plot_raan(solution, catalog)
    drawn["cost"] = plot_cost(solution)
    if solution.has_history:
        drawn["iterations"] = plot_iterations(solution)
    for fig in drawn.values():
        _head(fig, solution)
    return {name: drawn[name] for name in FIGURE_NAMES if name in drawn}


def transfer_line(solution: DrawnPlan) -> str | None:
    """A line saying the figures are of a low-thrust plan (None for the paper's impulsive
    model, which every figure's own title assumes)."""
    model = solution.mission.transfer_model().describe()
    if model["transfer"] == "impulsive":
        return None
    return (f"low-thrust vehicle, {model['accel_mps2']:.3g} m/s²: spiral, plane change, coast, "
            "spiral")  # fmt: skip


def _head(fig: Figure, solution: DrawnPlan, title: str | None = None) -> None:
    """The line above a figure: ``title`` (a campaign's mission) and the transfer model
    where it is not the paper's."""
    above = "; ".join(line for line in (title, transfer_line(solution)) if line)
    if above:
        fig.suptitle(above, fontsize=9, color="#444444")


# ---------------------------------------------------------------------- saving
def save_figures(
    solution: DrawnPlan,
    catalog: Catalog,
    folder: str | os.PathLike,
    formats: Sequence[str] = ("png",),
    dpi: int = 150,
    title: str | None = None,
) -> list[Path]:
    """Write the four figures as ``{name}.{fmt}`` in ``folder``, atomically.

    The names are :data:`FIGURE_NAMES`: ``orbits`` (Fig. 17), ``raan`` (Fig. 18),
    ``cost`` (Fig. 19), ``iterations`` (Table 7).  Each file is written to a hidden
    temporary file in ``folder`` and renamed over the target, so a reader never sees a
    partial image and a failure leaves no temporary file behind.

    Parameters
    ----------
    solution : Solution
    catalog : Catalog
        The catalog the solution was solved for.
    folder : str or path-like
        Output folder, created if missing.
    formats : sequence of str
        Any of :data:`SUPPORTED_FORMATS` (``"png"``, ``"svg"``, ``"pdf"``).
    dpi : int
        Resolution of raster formats [dots per inch].
    title : str, optional
        A line above each figure (a campaign's mission: which one, launched when).

    Returns
    -------
    list of Path
        The files written, figure by figure, format by format (``iterations`` only with
        a history to draw: ``Solution.has_history``).

    Raises
    ------
    ValueError
        An unsupported format, or debris of the solution missing from the catalog.
    """
    if isinstance(formats, str):
        formats = (formats,)
    formats = tuple(dict.fromkeys(fmt.lower().lstrip(".") for fmt in formats))
    unknown = [fmt for fmt in formats if fmt not in SUPPORTED_FORMATS]
    if unknown or not formats:
        raise ValueError(
            f"unsupported figure format(s) {unknown or '(none given)'}; "
            f"choose from {', '.join(SUPPORTED_FORMATS)}"
        )
    _positions(solution, catalog)  # fail before writing anything
    folder = Path(folder)
    folder.mkdir(parents=True, exist_ok=True)
    builders = {
        "orbits": lambda: plot_orbits(solution, catalog),
        "raan": lambda: plot_raan(solution, catalog),
        "cost": lambda: plot_cost(solution),
        "iterations": lambda: plot_iterations(solution),
    }
    if not solution.has_history:
        del builders["iterations"]
    written = []
    for name in builders:
        fig = builders[name]()
        _head(fig, solution, title)
        for fmt in formats:
            target = folder / f"{name}.{fmt}"
            write_figure(fig, target, fmt, dpi)  # 0644 under a 022 umask: meant to be shared
            written.append(target)
    return written
