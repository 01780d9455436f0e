"""The search against time: the certified search's bound and best plan, or the paper's
method's iterations (its Table 7)."""

from __future__ import annotations

import numpy as np
from matplotlib.figure import Figure
from matplotlib.ticker import MaxNLocator

from .plan_record import DrawnPlan
from .plot_common import (
    _AFTER_COLOR,
    _LABEL_SIZE,
    _LIMIT_COLOR,
    _NOTE_SIZE,
    _TICK_SIZE,
    _TITLE_SIZE,
    _new_figure,
    _path_name,
)


def _plot_certified_search(solution: DrawnPlan) -> Figure:
    """The certified search over time: the proven lower bound and the best plan, and the
    gap between them.

    x: seconds since the search started (its setup included); y: ΔV [m/s].  The best
    plan (solid) and the proven bound (dashed) are steps that change at each plan found
    and each bound proven (``Solution.search_trace``); every relaxation MILP is a square
    at the time it ended, at its own bound; the gap between them is shaded.  Without a
    trace (a solution from an older file), the relaxations are placed by their index.
    """
    fig, ax = _new_figure()
    trace = [(t, lo, up) for t, lo, up in solution.search_trace]
    records = [r for r in solution.iterations if r.status == "bound"]
    end = max([t for t, *_ in trace] + [r.elapsed_s or 0.0 for r in records] + [0.0])
    end = max(end, float(solution.timings.get("search_s") or 0.0))
    values = []
    if trace:
        end = end * 1.04 + 1e-3  # the last values held to the right edge
        times = np.array([t for t, *_ in trace] + [end])
        lower = np.array([np.nan if lo is None else lo for _, lo, _ in trace], dtype=float)
        plan = np.array([np.nan if up is None else up for *_, up in trace], dtype=float)
        lower, plan = np.append(lower, lower[-1]), np.append(plan, plan[-1])
        ax.step(times, plan, where="post", color=_AFTER_COLOR, linewidth=1.6,
                label="best plan so far", gid="plan")  # fmt: skip
        ax.step(times, lower, where="post", color=_LIMIT_COLOR, linestyle="--", linewidth=1.4,
                label="proven lower bound", gid="lower-bound")  # fmt: skip
        ax.fill_between(times, lower, plan, step="post", where=np.isfinite(lower + plan),
                        color=_LIMIT_COLOR, alpha=0.12, label="gap", gid="gap")  # fmt: skip
        found = np.isfinite(plan[:-1]) & (np.r_[np.nan, plan[:-2]] != plan[:-1])
        ax.plot(times[:-1][found], plan[:-1][found], "o", color=_AFTER_COLOR, markersize=4,
                gid="plans")  # each plan found  # fmt: skip
        values += [v for v in np.concatenate([lower, plan]) if np.isfinite(v)]
        ax.set_xlabel("time since the search started [s]", fontsize=_LABEL_SIZE)
    else:
        ax.set_xlabel("relaxation MILP", fontsize=_LABEL_SIZE)
    at = [(r.elapsed_s if trace and r.elapsed_s is not None else r.iteration + 1,
           r.dv_linearized_mps) for r in records if r.dv_linearized_mps is not None]  # fmt: skip
    if at:
        ax.plot([t for t, _ in at], [v for _, v in at], "s", markersize=5, color="#6baed6",
                linestyle="none", label="relaxation MILP's bound", gid="relaxation")  # fmt: skip
        values += [v for _, v in at]
    if not trace and solution.lower_bound_mps is not None:
        ax.axhline(solution.lower_bound_mps, color=_LIMIT_COLOR, linestyle=":", linewidth=1.2,
                   label=f"proven lower bound {solution.lower_bound_mps:.2f} m/s",
                   gid="lower-bound")  # fmt: skip
    values += [solution.total_dv_mps] + (
        [] if solution.lower_bound_mps is None else [solution.lower_bound_mps]
    )
    finite = [v for v in values if np.isfinite(v)]
    if finite:  # a first bound far below the plan must not flatten the end of the search
        top = max(finite)
        floor = solution.lower_bound_mps if solution.lower_bound_mps is not None else top
        low = max(min(finite), floor - 3 * (top - floor) - 50.0)
        low = min(low, floor)
        ax.set_ylim(low - 0.02 * (top - low) - 1e-3, top + 0.05 * (top - low) + 1e-3)
    if trace:
        ax.set_xlim(0.0, end)
    elif at:
        ax.set_xlim(min(t for t, _ in at) - 0.5, max(t for t, _ in at) + 0.5)
    gap = "" if solution.gap_mps is None else (
        f"; gap {solution.gap_mps:.2f} m/s ({100 * solution.gap_rel:.2f} %)")  # fmt: skip
    ax.set_title(f"Certified search: {solution.total_dv_mps:.2f} m/s, {solution.status}{gap}",
                 fontsize=_LABEL_SIZE)  # fmt: skip
    ax.set_ylabel("\u0394V [m/s]", fontsize=_LABEL_SIZE)
    ax.grid(True, linewidth=0.4, alpha=0.5)
    ax.legend(fontsize=_NOTE_SIZE, loc="best")
    ax.tick_params(labelsize=_TICK_SIZE)
    return fig


def plot_iterations(solution: DrawnPlan) -> Figure:
    """The sequential linearisation's history: the paper's Table 7 as a picture.

    Left axis: linearised and true ΔV [m/s] of each iteration's plan; right axis
    (``fig.axes[1]``): its true duration [days] with the T_max limit as a dotted
    line.  Iterations whose path differs from the previous one are marked by a
    vertical line and their new path; the first path is in the bottom-left box.
    Records with a missing value (an iteration that found no path) are skipped for
    that series.

    Parameters
    ----------
    solution : Solution

    Returns
    -------
    matplotlib.figure.Figure
        x: iteration; y (left): ΔV [m/s]; y (right): duration [days].
    """
    if solution.method == "certified":
        return _plot_certified_search(solution)
    fig, ax = _new_figure()
    right = ax.twinx()
    right.tick_params(labelsize=_TICK_SIZE)
    records = solution.iterations

    def series(attribute):
        pairs = [(r.iteration, getattr(r, attribute)) for r in records]
        pairs = [(i, v) for i, v in pairs if v is not None and np.isfinite(v)]
        return [i for i, _ in pairs], [v for _, v in pairs]

    handles = []
    handles += ax.plot(
        *series("dv_linearized_mps"),
        marker="s",
        markersize=5,
        linestyle="--",
        color="#6baed6",
        label="\u0394V linearised",
        gid="dv-linearized",
    )
    handles += ax.plot(
        *series("dv_true_mps"),
        marker="o",
        markersize=5,
        color=_AFTER_COLOR,
        label="\u0394V true",
        gid="dv-true",
    )
    handles += right.plot(
        *series("duration_true_days"),
        marker="^",
        markersize=5,
        color="#2ca02c",
        label="duration (true)",
        gid="duration",
    )
    tmax = solution.mission.tmax_days
    handles.append(
        right.axhline(
            tmax,
            color=_LIMIT_COLOR,
            linestyle=":",
            linewidth=1.2,
            label=f"T\u2098\u2090\u2093 = {tmax:g} d",
            gid="tmax",
        )
    )

    previous, first = None, None
    for record in records:
        if not record.path:
            continue
        path = tuple(record.path)
        if previous is None:
            first = (record.iteration, path)
        elif path != previous:
            ax.axvline(record.iteration - 0.5, color="#9467bd", linewidth=1.0, linestyle="-.")
            ax.annotate(
                f"path \u2192 {_path_name(path)}",
                xy=(record.iteration - 0.5, 1.0),
                xycoords=ax.get_xaxis_transform(),
                xytext=(3, -3),
                textcoords="offset points",
                ha="left",
                va="top",
                fontsize=_NOTE_SIZE,
                color="#9467bd",
            )
        previous = path
    if first is not None:
        ax.text(
            0.01,
            0.03,
            f"path at iteration {first[0]}: {_path_name(first[1])}",
            transform=ax.transAxes,
            fontsize=_NOTE_SIZE,
            va="bottom",
            ha="left",
            bbox={"boxstyle": "round", "facecolor": "white", "alpha": 0.85, "edgecolor": "#bbbbbb"},
        )

    # rejected steps: a red cross on their true ΔV and duration
    rejected = [r for r in records if r.rejected and r.dv_true_mps is not None]
    if rejected:
        handles += ax.plot(
            [r.iteration for r in rejected], [r.dv_true_mps for r in rejected], linestyle="none",
            marker="x", markersize=9, markeredgewidth=2, color=_LIMIT_COLOR,
            label="step rejected", gid="rejected", zorder=5,
        )  # fmt: skip
        right.plot(
            [r.iteration for r in rejected], [r.duration_true_days for r in rejected],
            linestyle="none", marker="x", markersize=9, markeredgewidth=2, color=_LIMIT_COLOR,
            gid="rejected-duration", zorder=5,
        )  # fmt: skip

    # an outlier (a rejected plan ending on day 85,000 of a 365-day mission) does not
    # stretch the axis: it is drawn as a marker at the edge, with its value
    durations = series("duration_true_days")
    kept = [d for d in durations[1] if d <= OUTLIER_FACTOR * tmax] + [tmax]
    d_low, d_high = min(kept), max(kept)
    d_span = max(d_high - d_low, 1.0)
    d_limits = (d_low - 0.1 * d_span, d_high + 0.1 * d_span)
    right.set_ylim(*d_limits)
    _mark_clipped(right, durations, d_limits, "d", "duration-clipped")
    dv_series = [series("dv_linearized_mps"), series("dv_true_mps")]
    accepted = [
        v
        for r in records
        if not r.rejected
        for v in (r.dv_linearized_mps, r.dv_true_mps)
        if v is not None and np.isfinite(v)
    ]
    every = [v for _, values in dv_series for v in values]
    if every:
        reference = max(accepted or every)
        dvs = [v for v in every if abs(v) <= OUTLIER_FACTOR * abs(reference)] or every
        v_low, v_high = min(dvs), max(dvs)
        v_span = max(v_high - v_low, 1.0)
        v_limits = (v_low - 0.15 * v_span, v_high + 0.15 * v_span)
        ax.set_ylim(*v_limits)
        for name, points in zip(("dv-linearized", "dv-true"), dv_series, strict=True):
            _mark_clipped(ax, points, v_limits, "m/s", f"{name}-clipped")

    ax.xaxis.set_major_locator(MaxNLocator(integer=True))
    ax.set_xlabel("iteration", fontsize=_LABEL_SIZE)
    ax.set_ylabel("\u0394V [m/s]", fontsize=_LABEL_SIZE, color=_AFTER_COLOR)
    right.set_ylabel("duration [days]", fontsize=_LABEL_SIZE, color="#2ca02c")
    ax.set_title(
        "Sequential linearisation: cost and duration per iteration (paper Table 7)",
        fontsize=_TITLE_SIZE,
    )
    ax.grid(True, linewidth=0.4, alpha=0.5)
    ax.legend(
        handles=handles,
        fontsize=_NOTE_SIZE,
        loc="upper center",
        ncols=len(handles),
        bbox_to_anchor=(0.5, -0.14),
        frameon=False,
    )
    return fig


OUTLIER_FACTOR = 2.0
"""Iterations figure: durations above this many T_max, and ΔVs above this many times the
largest ΔV of an accepted step, are drawn at the axis edge with their value instead of
stretching the axis."""


def _mark_clipped(ax, points, limits, unit: str, gid: str) -> None:
    """Points of ``points`` = (x, y) outside ``limits``: a marker at the edge, and the value."""
    low, high = limits
    for x, y in zip(*points, strict=True):
        if low <= y <= high:
            continue
        edge, marker, va = (high, "^", "top") if y > high else (low, "v", "bottom")
        ax.plot([x], [edge], linestyle="none", marker=marker, markersize=8, clip_on=False,
                color=_LIMIT_COLOR, gid=gid, zorder=6)  # fmt: skip
        # vertical, into the axes: neighbouring outliers' values do not run into each other
        ax.annotate(f"{y:,.0f} {unit}", xy=(x, edge), xytext=(0, -8 if va == "top" else 8),
                    textcoords="offset points", fontsize=_NOTE_SIZE, color=_LIMIT_COLOR,
                    va=va, ha="center", rotation=90,
                    bbox={"boxstyle": "square,pad=0.1", "facecolor": "white", "alpha": 0.7,
                          "linewidth": 0})  # fmt: skip
