"""The figure of a study: total ΔV against a swept parameter (matplotlib imported when drawn)."""

from __future__ import annotations

import os

import numpy as np
import pandas as pd

from .results import SOLVED_STATUSES, read_results
from .study import _show_value


# ---------------------------------------------------------------------- the figure
def plot_sweep(
    results: pd.DataFrame | str | os.PathLike,
    x: str,
    *,
    hue: str | None = None,
    ax=None,
    annotate: bool = False,
):
    """Total ΔV against a swept parameter, one line per value of ``hue``.

    Parameters
    ----------
    results : DataFrame or path
        What :func:`run_study` returned, or a sweep folder / its ``results.csv``.
    x, hue : str
        Columns: a dotted parameter (``mission.tmax_days``) or its short name
        (``tmax_days``) when unambiguous, or any other column.
    ax : matplotlib Axes, optional
        Draw there; default a new :class:`~matplotlib.figure.Figure`.
    annotate : bool
        Write each solved scenario's path beside its marker.

    Scenarios without a solution leave a gap in their line and are marked with an x
    at the bottom of the axes.  Where several scenarios of a line share an x (another
    parameter varies and is not the ``hue``), markers are drawn without a line.

    Returns
    -------
    matplotlib.figure.Figure
    """
    from matplotlib.figure import Figure
    from matplotlib.lines import Line2D

    frame = results if isinstance(results, pd.DataFrame) else read_results(results)
    x_col = _column(frame, x)
    hue_col = _column(frame, hue) if hue is not None else None
    if ax is None:
        fig = Figure(figsize=(8.0, 4.5), layout="constrained")
        ax = fig.add_subplot()
    solved = frame["status"].isin(SOLVED_STATUSES)
    groups = [(None, frame)] if hue_col is None else list(frame.groupby(hue_col, sort=True))
    any_failed = False
    for value, group in groups:
        group = group.sort_values(x_col, kind="stable")
        ok = solved.loc[group.index]
        dv = group["total_dv_mps"].where(ok)
        style = "" if group[x_col].duplicated().any() else "-"
        name = None if hue_col is None else f"{_short(hue_col)} = {_show_value(value)}"
        (line,) = ax.plot(group[x_col], dv, marker="o", linestyle=style, label=name)
        failed = group[~ok]
        if len(failed):
            any_failed = True
            ax.plot(
                failed[x_col],
                np.full(len(failed), 0.03),
                linestyle="",
                marker="x",
                markersize=8,
                color=line.get_color(),
                transform=ax.get_xaxis_transform(),
                clip_on=False,
            )
        if annotate:
            for xv, yv, path in zip(group[x_col][ok], dv[ok], group["path"][ok], strict=True):
                ax.annotate(
                    str(path).replace("->", "\u2192"),
                    (xv, yv),
                    xytext=(4, 4),
                    textcoords="offset points",
                    fontsize=7,
                )
    ax.set_xlabel(x_col)
    ax.set_ylabel("total \u0394V [m/s]")
    ax.set_title(f"Total \u0394V against {_short(x_col)}")
    ax.grid(True, alpha=0.3)
    handles, labels = ax.get_legend_handles_labels()
    if any_failed:
        handles.append(Line2D([], [], linestyle="", marker="x", color="0.3"))
        labels.append("no solution (infeasible / failed)")
    if handles:
        ax.legend(handles, labels, fontsize=9)
    return ax.figure


def _column(frame: pd.DataFrame, name: str) -> str:
    if name in frame.columns:
        return name
    matches = [c for c in frame.columns if isinstance(c, str) and c.partition(".")[2] == name]
    if len(matches) == 1:
        return matches[0]
    known = ", ".join(str(c) for c in frame.columns)
    raise KeyError(f"no column {name!r} in the results (columns: {known})")


def _short(column: str) -> str:
    return column.partition(".")[2] or column
