"""Figures of a removal campaign: timeline, RAANs, ΔV per mission, bound and plan.

Each function takes a campaign solution (:class:`~sdc_cvx.campaign.result.
CampaignSolution`: its ``missions``, ``launch_days``, ``catalog``, ``history``,
``greedy``) and returns a :class:`matplotlib.figure.Figure` built with the
object-oriented API (no pyplot), so it works headless; :func:`save_campaign_figures`
writes them atomically.  Days count from the campaign's start (day 0 of the catalog);
each mission's legs count from its own launch day.
"""

from __future__ import annotations

from pathlib import Path

import numpy as np
from matplotlib import colormaps
from matplotlib.figure import Figure

from ..network.edges import node_orbits
from ..physics.orbits import SECONDS_PER_DAY
from .atomic import write_figure

FIGURE_SIZE = (9.0, 4.8)
_CANDIDATE_COLOR = "#c7c7c7"
_MAX_LABELLED = 12
"""Missions whose debris are labelled by name on the timeline (more: markers only)."""
_MAX_IDS = 80
"""Rendezvous labelled with their debris' ids on the RAAN figure (more: markers only)."""


def _color(k: int):
    return colormaps["tab10"](k % 10)


def _figure():
    fig = Figure(figsize=FIGURE_SIZE, layout="constrained")
    return fig, fig.add_subplot()


def rendezvous_days(solution) -> list[list[tuple[str, float]]]:
    """Per mission, each debris and the day it is reached [days after the campaign start]
    (the first debris at the launch day)."""
    out = []
    for day, mission in zip(solution.launch_days, solution.missions, strict=True):
        if not mission.legs:
            out.append([(mission.path[0], day)])
            continue
        stops = [(mission.legs[0].from_id, day + mission.legs[0].departure_day)]
        stops += [(leg.to_id, day + leg.departure_day + leg.duration_days)
                  for leg in mission.legs]  # fmt: skip
        out.append(stops)
    return out


def plot_timeline(solution) -> Figure:
    """One row per mission: launch to end, each debris at its rendezvous date."""
    fig, ax = _figure()
    stops = rendezvous_days(solution)
    span = max(max(d for row in stops for _, d in row) - solution.launch_days[0], 1.0)
    for k, (day, mission, row) in enumerate(zip(solution.launch_days, solution.missions, stops,
                                                strict=True)):  # fmt: skip
        end = day + mission.total_duration_days
        ax.plot([day, end], [k, k], color=_color(k), linewidth=6, alpha=0.35,
                solid_capstyle="butt")  # fmt: skip
        ax.plot([d for _, d in row], [k] * len(row), "o", color=_color(k), markersize=6)
        if len(solution.missions) <= _MAX_LABELLED:
            for name, d, offset in zip(*zip(*row, strict=True), _label_levels(row, span),
                                       strict=True):  # fmt: skip
                ax.annotate(name, (d, k), textcoords="offset points", xytext=(0, offset),
                            ha="center", fontsize=8)  # fmt: skip
        ax.annotate(_mission_dv_text(solution, k), (end, k), textcoords="offset points",
                    xytext=(6, -3), fontsize=8, color="#444444")  # fmt: skip
    ax.set_yticks(range(len(solution.missions)),
                  [f"mission {k + 1}" for k in range(len(solution.missions))])  # fmt: skip
    ax.invert_yaxis()
    ax.set_ylim(len(solution.missions) - 0.4, -0.6)
    ax.set_xlabel("days after the campaign start")
    ax.set_title(f"Campaign timeline: {_value_text(solution)}{solution.total_dv_mps:.1f} m/s "
                 f"in {len(solution.missions)} missions")  # fmt: skip
    ax.grid(axis="x", alpha=0.3)
    return fig


def _budgets(solution) -> tuple[float, ...]:
    """Each mission's ΔV budget [m/s] of a value objective (its tank's ΔV where the
    tank sets it); empty for min-dv, which has none."""
    campaign = solution.campaign
    budgets = tuple(getattr(campaign, "dv_budget_mps", ()) or ())
    if getattr(campaign, "objective", "min-dv") == "min-dv":
        return ()
    return budgets if len(budgets) == len(solution.missions) else ()


def _mission_values(solution) -> list[float] | None:
    """The value each mission removes (None: not a value objective)."""
    if solution.value is None:
        return None
    return [float(np.sum(solution.campaign.value_of(m.path))) for m in solution.missions]


def _value_text(solution) -> str:
    """``"value 5 removed, "`` for a value objective, else nothing."""
    return "" if solution.value is None else f"value {solution.value:g} removed, "


def _mission_dv_text(solution, k: int) -> str:
    """Mission ``k``'s ΔV, with its budget and value under a value objective."""
    text = f"{solution.missions[k].total_dv_mps:.0f}"
    budgets = _budgets(solution)
    text += f" of {budgets[k]:.0f} m/s" if budgets else " m/s"
    values = _mission_values(solution)
    return text if values is None else f"{text}, value {values[k]:g}"


def _label_levels(row, span: float) -> list[float]:
    """Vertical offsets [points] of a row's labels, above and below in turn, a label moved
    further out when it would touch the last one at its level (ids of debris met a few
    days apart once printed as one: "73" and "11" as "7311")."""
    levels = (8.0, -14.0, 17.0, -23.0)
    last = dict.fromkeys(levels, -np.inf)
    out = []
    for n, (name, day) in enumerate(row):
        width = 0.012 * span * (len(str(name)) + 1)  # a label's width in days, roughly
        order = levels[n % 2 :: 2] + levels[1 - n % 2 :: 2]
        level = next((lv for lv in order if day - last[lv] > width), order[0])
        last[level] = day
        out.append(level)
    return out


def plot_raan(solution) -> Figure:
    """The RAAN of every candidate against time, seen from a frame turning at their median
    RAAN rate (so that 123 debris are 123 slow lines, not a saw of wraps), each mission's
    debris coloured while it flies and marked, with its id, where the vehicle meets them
    (the rates the missions were planned with: :func:`sdc_cvx.network.edges.node_orbits`)."""
    fig, ax = _figure()
    catalog = solution.catalog
    rate = np.degrees(node_orbits(catalog, solution.missions[0].mission).rate) * SECONDS_PER_DAY
    frame_rate = float(np.median(rate))
    raan0 = np.asarray(catalog.frame["raan_deg"], dtype=float)
    stops = rendezvous_days(solution)
    end = max(d for row in stops for _, d in row)
    days = np.linspace(0.0, max(end, 1.0), 400)

    def relative(rows, when):
        return np.mod(raan0[rows, None] + (rate[rows, None] - frame_rate) * when + 180.0,
                      360.0) - 180.0  # fmt: skip

    def unwrapped(values):  # no line across the +/-180 deg seam
        jump = np.abs(np.diff(values, axis=-1, prepend=values[..., :1])) > 180.0
        return np.where(jump, np.nan, values)

    for row in unwrapped(relative(np.arange(len(catalog)), days)):
        ax.plot(days, row, color=_CANDIDATE_COLOR, linewidth=0.5, zorder=1)
    index = {name: k for k, name in enumerate(catalog.ids)}
    labelled = sum(len(row) for row in stops) <= _MAX_IDS
    for k, (day, mission, row) in enumerate(zip(solution.launch_days, solution.missions, stops,
                                                strict=True)):  # fmt: skip
        rows = [index[name] for name, _ in row if name in index]
        window = np.linspace(day, day + mission.total_duration_days, 100)
        for track in unwrapped(relative(np.asarray(rows), window)):
            ax.plot(window, track, color=_color(k), linewidth=1.4, alpha=0.7, zorder=2)
        when = np.array([d for name, d in row if name in index])
        at = relative(np.asarray(rows), when[None, :])[np.arange(len(rows)), np.arange(len(rows))]
        ax.plot(when, at, "o", color=_color(k), markersize=5, zorder=3, label=f"mission {k + 1}")
        if labelled:
            names = [n for n, _ in row if n in index]
            for m, (name, x, y) in enumerate(zip(names, when, at, strict=True)):
                ax.annotate(name, (x, y), textcoords="offset points", fontsize=7,
                            xytext=(3, 5) if m % 2 == 0 else (3, -11), color=_color(k))  # fmt: skip
    ax.set_xlabel("days after the campaign start")
    ax.set_ylabel("RAAN in the turning frame [deg]")
    ax.set_ylim(-180, 180)
    ax.set_yticks(range(-180, 181, 60))
    ax.set_title(f"RAANs of the {len(catalog)} candidates (grey) in a frame turning at their "
                 f"median RAAN rate, {frame_rate:.3f} deg/day", fontsize=10)  # fmt: skip
    ax.legend(fontsize=8, loc="center left", bbox_to_anchor=(1.01, 0.5))
    return fig


def plot_dv(solution) -> Figure:
    """ΔV of each mission: transfers and operations, with greedy's missions beside; under
    a value objective each mission's budget (a bar over it) and value (under its name)."""
    fig, ax = _figure()
    k = np.arange(len(solution.missions))
    transfers = [m.transfers_dv_mps for m in solution.missions]
    operations = [m.operations_dv_mps for m in solution.missions]
    greedy = [c.dv_mps for c in solution.greedy.missions]
    width = 0.38
    # a mission's bar beside greedy's where greedy has that mission, centred on its tick else
    x = np.where(k < len(greedy), k - width / 2, k) if greedy else k.astype(float)
    ax.bar(x, transfers, width, color=[_color(i) for i in k], label="transfers")
    if any(operations):
        ax.bar(x, operations, width, bottom=transfers, color="#444444", alpha=0.5,
               label="operations")  # fmt: skip
    if greedy:
        ax.bar(
            np.arange(len(greedy)) + width / 2,
            greedy,
            width,
            color="none",
            edgecolor="#444444",
            hatch="//",
            label="greedy (one mission at a time)",
        )
    budgets = _budgets(solution)
    if budgets:
        ax.hlines(budgets, x - 0.6 * width, x + 0.6 * width, colors="#b2182b", linewidth=2,
                  label="ΔV budget", gid="budget")  # fmt: skip
        ax.set_ylim(0.0, 1.08 * max(max(budgets), *(np.add(transfers, operations))))
    values = _mission_values(solution)
    names = [f"mission {i + 1}\nday {d:g}" for i, d in zip(k, solution.launch_days, strict=True)]
    if values is not None:
        names = [f"{name}\nvalue {v:g}" for name, v in zip(names, values, strict=True)]
    ax.set_xticks(k, names)
    ax.set_ylabel("ΔV [m/s]")
    greedy_text = (f"; greedy {solution.greedy.dv_mps:.1f} m/s"
                   if solution.greedy.dv_mps is not None else "")  # fmt: skip
    bound = (f"bound {solution.lower_bound_mps:.1f}" if solution.bound_known
             else "no useful bound yet")  # fmt: skip
    ax.set_title(f"ΔV per mission: {_value_text(solution)}total {solution.total_dv_mps:.1f} "
                 f"m/s ({bound}){greedy_text}")  # fmt: skip
    ax.legend(fontsize=8)
    ax.grid(axis="y", alpha=0.3)
    return fig


def plot_bound(solution) -> Figure:
    """The proven lower bound and the best campaign against elapsed time, with the gap."""
    fig, ax = _figure()
    rows = [r for r in solution.history]
    t = np.array([r["seconds"] for r in rows], dtype=float)
    upper = np.array([r["upper_mps"] if r["upper_mps"] is not None else np.nan for r in rows],
                     dtype=float)  # fmt: skip
    lower = np.array([r["lower_mps"] if r["lower_mps"] is not None else np.nan for r in rows],
                     dtype=float)  # fmt: skip
    upper[~np.isfinite(upper)] = np.nan
    lower[~(np.isfinite(lower) & (lower > 0))] = np.nan  # 0 bounds every campaign: no news
    ax.step(t, upper, where="post", marker="o", color="#08519c", label="best campaign (plan)")
    ax.step(t, lower, where="post", marker="s", color="#d62728", label="proven lower bound")
    if solution.greedy.dv_mps is not None:
        ax.axhline(solution.greedy.dv_mps, color="#444444", linestyle="--", linewidth=1,
                   label=f"greedy {solution.greedy.dv_mps:.1f} m/s")  # fmt: skip
    greedy = [] if solution.greedy.dv_mps is None else [solution.greedy.dv_mps]
    finite = np.r_[upper[np.isfinite(upper)], lower[np.isfinite(lower)]]
    if finite.size:  # every line and marker inside the frame, greedy's too
        shown = np.r_[finite, greedy]
        span = max(shown.max() - shown.min(), 1.0)
        ax.set_ylim(shown.min() - 0.1 * span, shown.max() + 0.1 * span)
    if t.size:  # from the start, the last step's markers inside the frame
        ax.set_xlim(0.0, 1.05 * float(np.nanmax(t)) + 0.5)
    ax.set_xlabel("elapsed [s]")
    ax.set_ylabel("campaign ΔV [m/s]")
    gap = (f"gap {solution.gap_mps:.2f} m/s ({100 * solution.gap_rel:.2f} %)"
           if solution.bound_known else "no useful bound yet")  # fmt: skip
    ax.set_title(f"Bound and plan: {solution.status}, {gap}")
    ax.legend(fontsize=8)
    ax.grid(alpha=0.3)
    return fig


def plot_pareto(solution) -> Figure:
    """Value removed against campaign ΔV: the campaigns of ``--pareto``, each the cheapest
    of at least its target value, with the bound below it (no campaign of that value
    costs less); the campaign chosen (the most value) circled."""
    fig, ax = _figure()
    rows = sorted(solution.pareto, key=lambda row: row["value"])
    value = np.array([row["value"] for row in rows])
    dv = np.array([row["dv_mps"] for row in rows])
    bound = np.array([np.nan if row["dv_bound_mps"] is None else row["dv_bound_mps"]
                      for row in rows])  # fmt: skip
    ax.step(dv, value, where="post", color="#888888", linewidth=1)
    ax.plot(dv, value, "o", color=_color(0), label="campaign: the least ΔV of its value")
    if np.isfinite(bound).any():  # none where a limit stopped the enumeration
        ax.plot(bound, value, "|", color="#444444", markersize=10,
                label="bound: no campaign of that value costs less")  # fmt: skip
    ax.plot([solution.total_dv_mps], [solution.value], "o", markersize=14, markerfacecolor="none",
            markeredgecolor="#d62728", label="chosen: the most value")  # fmt: skip
    ax.set_xlabel("campaign ΔV [m/s]")
    ax.set_ylabel("value removed")
    proven = "" if np.isfinite(bound).any() else " (no bound: the enumeration was stopped)"
    ax.set_title(f"Value against ΔV: {len(rows)} campaigns, each mission within its "
                 f"budget{proven}", fontsize=10)  # fmt: skip
    ax.legend(fontsize=8, loc="lower right")
    ax.grid(alpha=0.3)
    return fig


def campaign_figures(solution) -> dict[str, Figure]:
    """The figures by name (``CAMPAIGN_FIGURE_NAMES`` of
    :mod:`~sdc_cvx.report.campaign_folder`, which lists them without matplotlib; ``pareto``
    only with a front)."""
    draw = {"timeline": plot_timeline, "raan": plot_raan, "dv": plot_dv, "bound": plot_bound}
    if getattr(solution, "pareto", ()):
        draw["pareto"] = plot_pareto
    return {name: plot(solution) for name, plot in draw.items()}


def save_campaign_figures(solution, folder, formats=("png",), dpi: int = 150) -> list[Path]:
    """Write the four figures as ``{name}.{fmt}`` in ``folder``, each atomically."""
    written = []
    for name, fig in campaign_figures(solution).items():
        for fmt in formats:
            target = Path(folder) / f"{name}.{fmt}"
            write_figure(fig, target, fmt, dpi)
            written.append(target)
    return written
