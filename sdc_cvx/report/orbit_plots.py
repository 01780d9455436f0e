"""The vehicle's altitude (the paper's Fig. 17) and the RAAN gaps closing (Fig. 18).

All RAAN rates are those the solver used (:func:`sdc_cvx.network.edges.node_orbits`: the
J2 rates of the catalog elements with the mission's J2, ``solution.mission.j2``, or the
catalog's rates fitted to SGP4), so the plotted RAAN gaps close exactly at each arrival.
"""

from __future__ import annotations

import numpy as np
from matplotlib.figure import Figure
from matplotlib.lines import Line2D

from ..inputs.catalog import Catalog
from ..network.edges import node_orbits
from ..physics.low_thrust import plane_change_raan_change, spiral_raan_change
from ..physics.orbits import R_EARTH, SECONDS_PER_DAY
from ..physics.transfer import NodeOrbits, drift_rate
from .plan_record import DrawnPlan
from .plot_common import (
    _DEBRIS_COLOR,
    _LABEL_SIZE,
    _LIMIT_COLOR,
    _NOTE_SIZE,
    _RAAN_SAMPLES,
    _TITLE_SIZE,
    _VEHICLE_COLOR,
    _altitudes_km,
    _break_wraps,
    _end_day,
    _leg_color,
    _leg_name,
    _new_figure,
    _path_name,
    _positions,
    _wrap_deg,
)


def vehicle_altitude(solution: DrawnPlan, catalog: Catalog) -> tuple[np.ndarray, np.ndarray]:
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
        Hohmann transfers, or the spirals of a low-thrust leg (under tangential thrust the
        circular speed changes linearly in time).
    """
    index = _positions(solution, catalog)
    altitude = _altitudes_km(catalog)
    first = solution.legs[0].from_id if solution.legs else solution.path[0]
    days, alts = [0.0], [altitude[index[first]]]
    for leg in solution.legs:  # a low-thrust leg's spirals: the speed linear in time
        arrival = leg.departure_day + leg.duration_days
        start_alt, end_alt = altitude[index[leg.from_id]], altitude[index[leg.to_id]]
        out = leg.phases.get("spiral_out_days", 0.0)
        back = leg.phases.get("spiral_in_days", 0.0)
        ramp_out, alt_out = _spiral(leg.departure_day, out, start_alt, leg.drift_alt_km)
        ramp_in, alt_in = _spiral(arrival - back, back, leg.drift_alt_km, end_alt)
        days += [leg.departure_day, *ramp_out, *ramp_in, arrival]
        alts += [start_alt, *alt_out, *alt_in, end_alt]
    end = _end_day(solution)
    if end > days[-1]:
        days.append(end)
        alts.append(alts[-1])
    return np.asarray(days), np.asarray(alts)


def _spiral(start, length, alt_from, alt_to, points=12):
    """Times [days] and altitudes [km] of a spiral from ``alt_from`` to ``alt_to`` lasting
    ``length`` days (a step when it takes no time): the speed is linear in time."""
    if length <= 0:
        return [start, start], [alt_from, alt_to]
    v_from, v_to = 1.0 / np.sqrt(R_EARTH / 1e3 + alt_from), 1.0 / np.sqrt(R_EARTH / 1e3 + alt_to)
    v = np.linspace(v_from, v_to, points)
    return list(start + np.linspace(0.0, length, points)), list(1.0 / v**2 - R_EARTH / 1e3)


def _vehicle_raan_turned(solution: DrawnPlan, leg, orbits: NodeOrbits, origin: int, target: int,
                         elapsed, rate_drift):  # fmt: skip
    """RAAN [deg] the vehicle has turned ``elapsed`` days into ``leg``: the drift rate times
    the time for an impulsive leg; for a low-thrust leg, each phase's own turn (spirals,
    plane change, coast; linear in time within a phase, exact at its ends)."""
    if "spiral_out_days" not in leg.phases:
        return rate_drift * elapsed
    accel = solution.mission.transfer_model().describe()["accel_mps2"]
    a_d = leg.drift_a_km * 1e3
    j2 = solution.mission.j2
    a, inc = orbits.a, orbits.inc
    spiral_out = spiral_raan_change(a[origin], a_d, inc[origin], accel, j2=j2)
    plane = plane_change_raan_change(a_d, inc[origin], inc[target], accel, j2=j2)
    spiral_in = spiral_raan_change(a_d, a[target], inc[target], accel, j2=j2)
    p = leg.phases
    coast = np.radians(rate_drift) * p["coast_days"]
    # the plane change is flown after spiral A when the coast has the target's inclination
    after_spiral = np.isclose(np.radians(leg.drift_inc_deg), inc[target]) and inc[origin] != inc[
        target]  # fmt: skip
    phases = [(p["spiral_out_days"], spiral_out)]
    middle = [(p["plane_change_days"], plane), (p["coast_days"], coast)]
    phases += middle if after_spiral else middle[::-1]
    phases.append((p["spiral_in_days"], spiral_in))
    ends = np.cumsum([0.0] + [length for length, _ in phases])
    turned = np.cumsum([0.0] + [np.degrees(value) for _, value in phases])
    return np.interp(elapsed, ends, turned)


def raan_gap_history(
    solution: DrawnPlan, catalog: Catalog, samples: int = _RAAN_SAMPLES
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
    orbits = node_orbits(catalog, solution.mission)
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
        vehicle = vehicle + _vehicle_raan_turned(solution, leg, orbits, origin, target,
                                                 days - leg.departure_day, rate_drift)  # fmt: skip
        gap = _wrap_deg(vehicle - (raan0[target] + rate[target] * days))
        history.append((days, gap))
    return history


# ---------------------------------------------------------------------- Fig. 17
def plot_orbits(solution: DrawnPlan, catalog: Catalog) -> Figure:
    """Altitude of the vehicle over the mission: the paper's Fig. 17 ("optimal path orbits").

    A step line (gid ``"vehicle"``) at the debris altitude while the vehicle is at a
    debris and at the drift altitude while it drifts, with vertical steps at the
    Hohmann transfers; each drift orbit is over-drawn in its leg's colour (gid
    ``"drift-k"``, k from 1) and annotated with the leg (``5→8``), its altitude and its
    inclination.  A low-thrust leg's spirals are the slopes between the debris and the
    drift orbit.  The altitude of each selected debris is a dashed reference line
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
    labels = []
    for k, leg in enumerate(solution.legs):
        start, stop = leg.departure_day, leg.departure_day + leg.duration_days
        color = _leg_color(k)
        middle = 0.5 * (start + stop)
        ax.axvspan(start, stop, color=color, alpha=0.08, linewidth=0, zorder=0)
        ax.plot(  # on the drift orbit: between a low-thrust leg's spirals
            [start + leg.phases.get("spiral_out_days", 0.0),
             stop - leg.phases.get("spiral_in_days", 0.0)],
            [leg.drift_alt_km] * 2,
            color=color,
            linewidth=3.5,
            solid_capstyle="butt",
            gid=f"drift-{k + 1}",
            zorder=4,
        )
        # a label near an edge is held inside the frame (not over the tick labels)
        x, ha = ((start, "left") if middle < 0.12 * end else (stop, "right")
                 if middle > 0.88 * end else (middle, "center"))  # fmt: skip
        labels.append(ax.annotate(
            f"{_leg_name(leg)}\n{leg.drift_alt_km:.0f} km, {leg.drift_inc_deg:.2f}\u00b0",
            xy=(x, leg.drift_alt_km),
            xytext=(0, -5),
            textcoords="offset points",
            ha=ha,
            va="top",
            fontsize=_NOTE_SIZE,
            color=color,
            fontweight="bold",
            bbox={"boxstyle": "square,pad=0.1", "facecolor": "white", "alpha": 0.6, "linewidth": 0},
        ))  # fmt: skip
    _apart(fig, labels)
    tmax = solution.mission.tmax_days
    ax.axvline(tmax, color=_LIMIT_COLOR, linestyle=":", linewidth=1.2, zorder=2)
    ax.annotate(
        f"T\u2098\u2090\u2093 = {tmax:g} d",
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


def _apart(fig: Figure, labels: list) -> None:
    """Move each leg label, in leg order, to the first place that overlaps no label placed
    before it: below its drift line, above it, then further below and above in steps of
    its own height (short legs and drift orbits of nearby altitudes crowded them)."""
    from matplotlib.backends.backend_agg import FigureCanvasAgg

    canvas = fig.canvas if hasattr(fig.canvas, "get_renderer") else FigureCanvasAgg(fig)
    fig.draw_without_rendering()  # the constrained layout first: the axes' final size
    renderer = canvas.get_renderer()
    placed = []
    for label in labels:
        height = label.get_window_extent(renderer).height * 72.0 / fig.dpi  # [points]
        for step in range(8):
            above, level = step % 2 == 1, step // 2
            offset = 5.0 + 1.1 * height * level
            label.set_position((0.0, offset if above else -offset))
            label.set_verticalalignment("bottom" if above else "top")
            box = label.get_window_extent(renderer)
            if not any(box.overlaps(other) for other in placed):
                break
        placed.append(label.get_window_extent(renderer))


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
def plot_raan(solution: DrawnPlan, catalog: Catalog) -> Figure:
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
    ax.set_ylabel("\u03a9 vehicle \u2212 \u03a9 target [deg]", fontsize=_LABEL_SIZE)
    ax.set_title("RAAN correction on the drift orbits (paper Fig. 18)", fontsize=_TITLE_SIZE)
    ax.grid(True, linewidth=0.4, alpha=0.5)
    if solution.legs:
        ax.legend(fontsize=_NOTE_SIZE, title="leg", title_fontsize=_NOTE_SIZE, loc="best")
    return fig
