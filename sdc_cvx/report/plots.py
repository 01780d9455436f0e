"""Figures of a planned mission: the paper's Fig. 17, 18, 19 and Table 7 as pictures.

Every function returns a :class:`matplotlib.figure.Figure` built with the
object-oriented API only (no pyplot, no global state), so it works headless and
in threads; :func:`save_figures` writes them all atomically.

The mission timeline drawn here is the one of :func:`~sdc_cvx.solution.evaluate_plan`:
the vehicle is at the first debris at t = 0; leg k leaves at ``departure_day``, makes a
Hohmann transfer (instantaneous at this scale) to its circular drift orbit
(``drift_alt_km``, ``drift_inc_deg``), coasts ``duration_days`` while J2 turns its RAAN at
the drift orbit's rate (Eq. 8), then transfers to the target debris, where operations
last ``mission.deorbit_days`` before the next departure.

All RAAN rates are recomputed from the catalog elements with the mission's J2
(``solution.mission.j2``), the same model the solver used, so the plotted RAAN gaps
close exactly at each arrival.
"""

from __future__ import annotations

import os
from collections.abc import Sequence
from functools import partial
from pathlib import Path
from typing import TYPE_CHECKING

import numpy as np
from matplotlib import colormaps
from matplotlib.figure import Figure
from matplotlib.lines import Line2D
from matplotlib.ticker import MaxNLocator

from ..inputs.catalog import Catalog
from ..physics.orbits import R_EARTH, SECONDS_PER_DAY
from ..physics.transfer import NodeOrbits, drift_rate
from .atomic import write_atomic

if TYPE_CHECKING:  # solution imports report (Solution.plot): the types are hints only
    from ..solution import Leg, Solution

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

FIGURE_SIZE = (8.0, 4.5)
"""Size of every figure [inch]: readable at report width."""

FIGURE_NAMES = ("orbits", "raan", "cost", "iterations")
"""File stems written by :func:`save_figures`, in order."""

SUPPORTED_FORMATS = ("png", "svg", "pdf")
"""File formats :func:`save_figures` accepts."""

ARROW = "\u2192"
_TITLE_SIZE = 12
_LABEL_SIZE = 11
_TICK_SIZE = 10
_NOTE_SIZE = 9
_RAAN_SAMPLES = 241
_VEHICLE_COLOR = "#1a1a1a"
_DEBRIS_COLOR = "#7f7f7f"
_BEFORE_COLOR = "#a6bddb"
_AFTER_COLOR = "#08519c"
_LIMIT_COLOR = "#d62728"


# ---------------------------------------------------------------------- helpers
def _new_figure(**subplot_kw) -> tuple[Figure, object]:
    """A constrained-layout figure of :data:`FIGURE_SIZE` with one axes."""
    fig = Figure(figsize=FIGURE_SIZE, layout="constrained")
    ax = fig.add_subplot(**subplot_kw)
    ax.tick_params(labelsize=_TICK_SIZE)
    return fig, ax


def _leg_color(k: int):
    """Colour of leg ``k`` (the same in every figure)."""
    return colormaps["tab10"](k % 10)


def _leg_name(leg: Leg) -> str:
    return f"{leg.from_id}{ARROW}{leg.to_id}"


def _path_name(path: Sequence[str]) -> str:
    return ARROW.join(str(node) for node in path)


def _wrap_deg(angle):
    """Angle [deg] wrapped into (-180, 180]."""
    return 180.0 - np.mod(180.0 - np.asarray(angle, dtype=float), 360.0)


def _break_wraps(values: np.ndarray) -> np.ndarray:
    """Insert NaN where a wrapped angle jumps by more than 180 deg, so no line crosses the plot."""
    values = np.asarray(values, dtype=float)
    jumps = np.flatnonzero(np.abs(np.diff(values)) > 180.0)
    return np.insert(values, jumps + 1, np.nan) if jumps.size else values


def _positions(solution: Solution, catalog: Catalog) -> dict[str, int]:
    """Catalog position of every debris of the solution's path and legs."""
    index = {debris: pos for pos, debris in enumerate(catalog.ids)}
    wanted = list(solution.path)
    for leg in (*solution.legs, *solution.initial_legs):
        wanted += [leg.from_id, leg.to_id]
    missing = sorted({debris for debris in wanted if debris not in index})
    if missing:
        raise ValueError(
            f"debris {', '.join(missing)} of the solution are not in the catalog "
            f"({catalog.source}); plot a solution with the catalog it was solved for"
        )
    return index


def _altitudes_km(catalog: Catalog) -> np.ndarray:
    return (catalog.a_m - R_EARTH) / 1000.0


def _end_day(solution: Solution) -> float:
    """End of the mission [days]: last arrival plus the operations there."""
    if not solution.legs:
        return float(solution.mission.deorbit_days)
    last = solution.legs[-1]
    return last.departure_day + last.duration_days + solution.mission.deorbit_days


def vehicle_altitude(solution: Solution, catalog: Catalog) -> tuple[np.ndarray, np.ndarray]:
    """Altitude of the vehicle over the mission, as the corners of a step line.

    Parameters
    ----------
    solution : Solution
    catalog : Catalog
        The catalog the solution was solved for.

    Returns
    -------
    days, altitude_km : ndarray
        Mission time [days after t0] and altitude [km]: the debris altitude while at a
        debris, the drift altitude while drifting, vertical steps at the (instantaneous)
        Hohmann transfers.
    """
    index = _positions(solution, catalog)
    altitude = _altitudes_km(catalog)
    first = solution.legs[0].from_id if solution.legs else solution.path[0]
    days, alts = [0.0], [altitude[index[first]]]
    for leg in solution.legs:
        arrival = leg.departure_day + leg.duration_days
        days += [leg.departure_day, leg.departure_day, arrival, arrival]
        alts += [altitude[index[leg.from_id]], leg.drift_alt_km, leg.drift_alt_km]
        alts += [altitude[index[leg.to_id]]]
    end = _end_day(solution)
    if end > days[-1]:
        days.append(end)
        alts.append(alts[-1])
    return np.asarray(days), np.asarray(alts)


def raan_gap_history(
    solution: Solution, catalog: Catalog, samples: int = _RAAN_SAMPLES
) -> list[tuple[np.ndarray, np.ndarray]]:
    """RAAN of the vehicle minus RAAN of its next target during each leg (paper Fig. 18).

    Vehicle RAAN = origin debris RAAN at departure + drift-orbit rate x elapsed time;
    target RAAN = its RAAN at t0 + its rate x t (Eq. 7-9, rates with ``solution.mission.j2``).

    Parameters
    ----------
    solution : Solution
    catalog : Catalog
        The catalog the solution was solved for.
    samples : int
        Points per leg, departure and arrival included.

    Returns
    -------
    list of (days, gap_deg)
        One pair per leg: mission time [days after t0] and the difference [deg] wrapped
        into (-180, 180]; it is 0 at arrival.
    """
    index = _positions(solution, catalog)
    j2 = solution.mission.j2
    orbits = NodeOrbits.from_elements(
        catalog.a_m, catalog.e, catalog.inc_rad, catalog.raan_rad, j2=j2
    )
    raan0 = np.degrees(orbits.raan)
    rate = np.degrees(orbits.rate) * SECONDS_PER_DAY  # deg/day
    history = []
    for leg in solution.legs:
        origin, target = index[leg.from_id], index[leg.to_id]
        rate_drift = (
            np.degrees(drift_rate(leg.drift_a_km * 1000.0, np.radians(leg.drift_inc_deg), j2=j2))
            * SECONDS_PER_DAY
        )
        days = leg.departure_day + np.linspace(0.0, leg.duration_days, samples)
        vehicle = raan0[origin] + rate[origin] * leg.departure_day
        vehicle = vehicle + rate_drift * (days - leg.departure_day)
        gap = _wrap_deg(vehicle - (raan0[target] + rate[target] * days))
        history.append((days, gap))
    return history


# ---------------------------------------------------------------------- Fig. 17
def plot_orbits(solution: Solution, catalog: Catalog) -> Figure:
    """Altitude of the vehicle over the mission: the paper's Fig. 17 ("optimal path orbits").

    A step line (gid ``"vehicle"``) at the debris altitude while the vehicle is at a
    debris and at the drift altitude while it drifts, with vertical steps at the
    Hohmann transfers; each drift orbit is over-drawn in its leg's colour (gid
    ``"drift-k"``, k from 1) and annotated with the leg (``5→8``), its altitude and its
    inclination.  The altitude of each selected debris is a dashed reference line
    labelled at the right, and the duration limit T_max a dotted vertical line.

    Parameters
    ----------
    solution : Solution
    catalog : Catalog
        The catalog the solution was solved for (debris altitudes).

    Returns
    -------
    matplotlib.figure.Figure
        x: mission time [days]; y: altitude [km].
    """
    index = _positions(solution, catalog)
    altitude = _altitudes_km(catalog)
    fig, ax = _new_figure()
    days, alts = vehicle_altitude(solution, catalog)

    debris_alts = {debris: float(altitude[index[debris]]) for debris in solution.path}
    every = np.concatenate([alts, list(debris_alts.values())])
    low, high = float(np.min(every)), float(np.max(every))
    span = max(high - low, 10.0)
    ax.set_ylim(low - 0.2 * span, high + 0.08 * span)
    end = max(_end_day(solution), solution.mission.tmax_days)
    ax.set_xlim(-0.015 * end, end * 1.015)  # transfers at t = 0 and at the end stay visible

    for alt in debris_alts.values():
        ax.axhline(alt, color=_DEBRIS_COLOR, linestyle="--", linewidth=0.8, zorder=1)
    _label_debris_lines(ax, debris_alts)

    ax.plot(
        days, alts, color=_VEHICLE_COLOR, linewidth=1.3, label="vehicle", gid="vehicle", zorder=3
    )
    last_label = None  # x [days] of the previous leg's label
    for k, leg in enumerate(solution.legs):
        start, stop = leg.departure_day, leg.departure_day + leg.duration_days
        color = _leg_color(k)
        # a leg too short to hold its label (e.g. 1e-9 d at a RAAN crossing) would put it
        # on top of its neighbour's: such a label goes above the line instead of below
        middle = 0.5 * (start + stop)
        crowded = last_label is not None and abs(middle - last_label) < 0.08 * end
        last_label = None if crowded else middle
        ax.axvspan(start, stop, color=color, alpha=0.08, linewidth=0, zorder=0)
        ax.plot(
            [start, stop],
            [leg.drift_alt_km] * 2,
            color=color,
            linewidth=3.5,
            solid_capstyle="butt",
            gid=f"drift-{k + 1}",
            zorder=4,
        )
        ax.annotate(
            f"{_leg_name(leg)}\n{leg.drift_alt_km:.0f} km, {leg.drift_inc_deg:.2f}\u00b0",
            xy=(middle, leg.drift_alt_km),
            xytext=(0, 5) if crowded else (0, -5),
            textcoords="offset points",
            ha="center",
            va="bottom" if crowded else "top",
            fontsize=_NOTE_SIZE,
            color=color,
            fontweight="bold",
            bbox={"boxstyle": "square,pad=0.1", "facecolor": "white", "alpha": 0.6, "linewidth": 0},
        )
    tmax = solution.mission.tmax_days
    ax.axvline(tmax, color=_LIMIT_COLOR, linestyle=":", linewidth=1.2, zorder=2)
    ax.annotate(
        f"T$_{{max}}$ = {tmax:g} d",
        xy=(tmax, 1.0),
        xycoords=ax.get_xaxis_transform(),
        xytext=(-3, -3),
        textcoords="offset points",
        ha="right",
        va="top",
        fontsize=_NOTE_SIZE,
        color=_LIMIT_COLOR,
    )

    proxies = [
        Line2D([], [], color=_VEHICLE_COLOR, linewidth=1.3, label="vehicle"),
        Line2D(
            [], [], color=_leg_color(0), linewidth=3.5, label="drift orbit (one colour per leg)"
        ),
        Line2D([], [], color=_DEBRIS_COLOR, linestyle="--", linewidth=0.8, label="debris orbit"),
    ]
    ax.legend(
        handles=proxies,
        fontsize=_NOTE_SIZE,
        loc="upper center",
        ncols=3,
        bbox_to_anchor=(0.5, -0.14),
        frameon=False,
    )
    ax.set_xlabel("mission time [days]", fontsize=_LABEL_SIZE)
    ax.set_ylabel("altitude [km]", fontsize=_LABEL_SIZE)
    ax.set_title(
        f"Vehicle orbits along the path {_path_name(solution.path)} (paper Fig. 17)",
        fontsize=_TITLE_SIZE,
    )
    ax.grid(True, axis="x", linewidth=0.4, alpha=0.5)
    return fig


def _node_name(node_id: str) -> str:
    """How a path node is named on a figure: the injection orbit is not a debris."""
    return "injection orbit" if node_id == "injection" else f"debris {node_id}"


def _label_debris_lines(ax, debris_alts: dict[str, float]) -> None:
    """Label the debris reference lines in the right margin, spread so labels never overlap."""
    if not debris_alts:
        return
    bottom, top = ax.get_ylim()
    order = sorted(debris_alts, key=debris_alts.get)
    wanted = np.array([(debris_alts[d] - bottom) / (top - bottom) for d in order])
    gap = 0.105  # axes fraction between label centres: two 9 pt lines on a ~3.2 in axes
    placed = wanted.copy()
    for k in range(1, len(placed)):
        placed[k] = max(placed[k], placed[k - 1] + gap)
    overflow = placed[-1] - 1.0
    if overflow > 0:  # shift down what went past the top, keeping the gaps
        placed -= overflow
        for k in range(len(placed) - 2, -1, -1):
            placed[k] = min(placed[k], placed[k + 1] - gap)
    for debris, y_wanted, y_placed in zip(order, wanted, placed, strict=True):
        ax.annotate(
            f"{_node_name(debris)}\n{debris_alts[debris]:.0f} km",
            xy=(1.0, y_wanted),
            xycoords="axes fraction",
            xytext=(1.015, y_placed),
            textcoords="axes fraction",
            va="center",
            ha="left",
            fontsize=_NOTE_SIZE,
            color="#404040",
            linespacing=0.95,
            annotation_clip=False,
            arrowprops={"arrowstyle": "-", "color": _DEBRIS_COLOR, "linewidth": 0.6}
            if abs(y_placed - y_wanted) > 0.01
            else None,
        )


# ---------------------------------------------------------------------- Fig. 18
def plot_raan(solution: Solution, catalog: Catalog) -> Figure:
    """RAAN correction during each leg: the paper's Fig. 18.

    For leg k (line gid ``"raan-leg-k"``, k from 1, labelled ``5→8``): RAAN of the
    vehicle minus RAAN of the leg's target [deg], wrapped into (-180, 180], from the
    departure to the arrival.  Vehicle RAAN = origin debris' RAAN at departure +
    drift-orbit J2 rate x elapsed time; target RAAN = its RAAN at t0 + its rate x t.
    The gap reaches 0 at each arrival (round marker); the departure is a square.
    Wrap-arounds are broken with NaN so no line crosses the plot.

    Parameters
    ----------
    solution : Solution
    catalog : Catalog
        The catalog the solution was solved for (RAANs at t0, elements for the rates).

    Returns
    -------
    matplotlib.figure.Figure
        x: mission time [days]; y: RAAN difference [deg].
    """
    fig, ax = _new_figure()
    ax.axhline(0.0, color=_VEHICLE_COLOR, linewidth=0.8, zorder=1)
    for k, (leg, (days, gap)) in enumerate(
        zip(solution.legs, raan_gap_history(solution, catalog), strict=True)
    ):
        color = _leg_color(k)
        broken = _break_wraps(gap)
        if broken.size != gap.size:  # keep x and y aligned around the inserted NaN
            jumps = np.flatnonzero(np.abs(np.diff(gap)) > 180.0)
            days = np.insert(days, jumps + 1, np.nan)
        label = f"{_leg_name(leg)}  (drift {leg.drift_alt_km:.0f} km, {leg.duration_days:.1f} d)"
        ax.plot(
            days, broken, color=color, linewidth=2.0, label=label, gid=f"raan-leg-{k + 1}", zorder=3
        )
        ax.plot(days[0], broken[0], marker="s", color=color, markersize=5, zorder=4)
        ax.plot(
            days[-1],
            broken[-1],
            marker="o",
            color=color,
            markersize=6,
            zorder=4,
            markeredgecolor="white",
        )
        ax.axvline(leg.departure_day, color=_DEBRIS_COLOR, linestyle=":", linewidth=0.7)
    end = max(_end_day(solution), 1.0)
    ax.set_xlim(-0.015 * end, end * 1.015)
    ax.set_xlabel("mission time [days]", fontsize=_LABEL_SIZE)
    ax.set_ylabel("\u03a9$_{vehicle}$ \u2212 \u03a9$_{target}$ [deg]", fontsize=_LABEL_SIZE)
    ax.set_title("RAAN correction on the drift orbits (paper Fig. 18)", fontsize=_TITLE_SIZE)
    ax.grid(True, linewidth=0.4, alpha=0.5)
    if solution.legs:
        ax.legend(fontsize=_NOTE_SIZE, title="leg", title_fontsize=_NOTE_SIZE, loc="best")
    return fig


# ---------------------------------------------------------------------- Fig. 19
def plot_cost(solution: Solution) -> Figure:
    """ΔV per leg, and before the optimisation when there was a before: the paper's Fig. 19.

    Bars per leg index 1..n-1: ``solution.legs`` (the plan), and beside them
    ``solution.initial_legs`` (the first iteration's plan, "before optimisation") when
    the solution has one (the paper's method; the certified search has no "before").
    Operations ΔV (``deorbit_by = "vehicle"``, ``operations_dv_mps``) is drawn stacked
    on each leg's bar, at the leg's arrival debris as in ``legs.csv``, and counted in
    the legend's total, which is the summary's.  Each bar is labelled with its value
    [m/s]; the tick under each group names the leg (``leg 1`` and ``5→8``), turned when
    the names would collide (GTOC9's long ids, n = 10); when the two plans follow
    different paths, each bar gets its own ``from→to`` (minor tick labels).

    Returns
    -------
    matplotlib.figure.Figure
        x: leg; y: ΔV [m/s].
    """
    fig, ax = _new_figure()
    before, after = list(solution.initial_legs), list(solution.legs)
    count = max(len(before), len(after))
    x = np.arange(1, count + 1)
    width = 0.38 if before else 0.6
    names = [_leg_name(leg) for leg in after]
    longest = max((len(name) for name in names), default=0)
    crowded = count * (2 if before else 1) > 8 or count * max(longest, 6) > 60
    value_size = _NOTE_SIZE - 2 if crowded else _NOTE_SIZE
    series = []
    plan_name = "after optimisation" if before else "plan"
    if before:
        total = sum(leg.dv_mps for leg in before)
        series.append(
            (
                before,
                -width / 2,
                _BEFORE_COLOR,
                f"before optimisation ({_short(_path_name(_legs_path(before)))}): "
                f"{total:.1f} m/s" + (" transfers" if solution.operations_dv_mps else ""),
            )
        )
    total = sum(leg.dv_mps for leg in after)
    label = f"{plan_name} ({_short(_path_name(_legs_path(after)))}): {total:.1f} m/s"
    if solution.operations_dv_mps:  # the total ΔV is that of the summary and solution.json
        label = f"{plan_name} ({_short(_path_name(_legs_path(after)))}): {total:.1f} m/s transfers"
    series.append((after, width / 2 if before else 0.0, _AFTER_COLOR, label))
    for legs, shift, color, label in series:
        bars = ax.bar(
            x[: len(legs)] + shift,
            [leg.dv_mps for leg in legs],
            width,
            color=color,
            edgecolor="#303030",
            linewidth=0.5,
            label=label,
        )
        ax.bar_label(bars, fmt="%.1f", fontsize=value_size, padding=2,
                     rotation=90 if crowded else 0, label_type="center" if crowded else "edge",
                     color="white" if crowded and color == _AFTER_COLOR else "black")  # fmt: skip
    operations = _operations_per_leg(solution)
    tops = [leg.dv_mps for leg in after]
    if operations is not None:
        shift = width / 2 if before else 0.0
        bars = ax.bar(
            x[: len(after)] + shift, operations, width, bottom=tops, color="#fdae6b",
            edgecolor="#303030", linewidth=0.5, hatch="//", gid="operations",
            label=(f"operations (deorbit by {solution.operations.get('scenario', '?')}): "
                   f"{total:.1f} m/s transfers + {solution.operations_dv_mps:.1f} m/s "
                   f"operations = {solution.total_dv_mps:.1f} m/s"),
        )  # fmt: skip
        ax.bar_label(bars, fmt="%.1f", fontsize=value_size, padding=2,
                     rotation=90 if crowded else 0,
                     label_type="center" if crowded else "edge")  # fmt: skip
        tops = [a + b for a, b in zip(tops, operations, strict=True)]

    same_path = [_leg_name(leg) for leg in before] == names
    turn = count * max(longest, 6) > 60  # the names would run into each other
    if not before or same_path:
        if turn:
            ax.set_xticks(x, [f"{k + 1}: {names[k]}" for k in range(count)],
                          rotation=90 if longest > 12 else 35, ha="right",
                          rotation_mode="anchor", fontsize=_NOTE_SIZE - 1)  # fmt: skip
        else:
            ax.set_xticks(x, [f"leg {k + 1}\n{names[k]}" for k in range(count)])
    else:  # each bar's own from→to right under it, the leg index below
        ax.set_xticks(x, [f"leg {k + 1}" for k in range(count)])
        ax.tick_params(axis="x", which="major", length=0, pad=20 if not turn else 60)
        positions, labels = [], []
        for legs, shift, *_ in series:
            positions += list(x[: len(legs)] + shift)
            labels += [_leg_name(leg) for leg in legs]
        ax.set_xticks(positions, labels, minor=True)
        ax.tick_params(axis="x", which="minor", length=3, labelsize=_NOTE_SIZE - (2 if turn else 0))
        if turn:
            for text in ax.get_xticklabels(minor=True):
                text.set_rotation(90)
    ax.set_xlim(0.4, count + 0.6)
    top = max([leg.dv_mps for leg in before] + tops, default=1.0)
    ax.set_ylim(0.0, top * 1.32)
    ax.set_xlabel("leg", fontsize=_LABEL_SIZE)
    ax.set_ylabel("\u0394V [m/s]", fontsize=_LABEL_SIZE)
    title = ("Mission cost before and after optimisation (paper Fig. 19)" if before
             else "Mission cost per leg (paper Fig. 19)")  # fmt: skip
    ax.set_title(title, fontsize=_TITLE_SIZE)
    ax.grid(True, axis="y", linewidth=0.4, alpha=0.5)
    ax.set_axisbelow(True)
    ax.legend(
        fontsize=_NOTE_SIZE, title="total \u0394V", title_fontsize=_NOTE_SIZE, loc="upper right"
    )
    return fig


def _short(text: str, width: int = 44) -> str:
    """``text``, cut to ``width`` characters with an ellipsis (a legend stays a legend)."""
    return text if len(text) <= width else text[: width - 1] + "\u2026"


def _operations_per_leg(solution: Solution) -> list[float] | None:
    """Operations ΔV carried by each leg (at its arrival debris; the first leg also those
    at the first debris), as in ``legs.csv``; None when there are none."""
    if not solution.operations_dv_mps or not solution.legs:
        return None
    per_debris = dict(solution.operations.get("per_debris_mps") or {})
    out = [float(per_debris.get(leg.to_id, 0.0)) for leg in solution.legs]
    out[0] += float(per_debris.get(solution.legs[0].from_id, 0.0))
    return out


def _legs_path(legs: Sequence[Leg]) -> list[str]:
    return [legs[0].from_id, *(leg.to_id for leg in legs)] if legs else []


# ---------------------------------------------------------------------- Table 7
def _plot_certified_search(solution: Solution) -> Figure:
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


def plot_iterations(solution: Solution) -> Figure:
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
            label=f"T$_{{max}}$ = {tmax:g} d",
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


def figures(solution: Solution, catalog: Catalog | None = None) -> dict[str, Figure]:
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
    drawn["iterations"] = plot_iterations(solution)
    return {name: drawn[name] for name in FIGURE_NAMES if name in drawn}


# ---------------------------------------------------------------------- saving
def save_figures(
    solution: Solution,
    catalog: Catalog,
    folder: str | os.PathLike,
    formats: Sequence[str] = ("png",),
    dpi: int = 150,
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

    Returns
    -------
    list of Path
        The files written, figure by figure, format by format.

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
    written = []
    for name in FIGURE_NAMES:
        fig = builders[name]()
        for fmt in formats:
            target = folder / f"{name}.{fmt}"
            save = partial(fig.savefig, format=fmt, dpi=dpi)
            write_atomic(target, save)  # 0644 under a 022 umask: meant to be shared
            written.append(target)
    return written
