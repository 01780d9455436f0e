"""The ΔV of each leg (the paper's Fig. 19)."""

from __future__ import annotations

from collections.abc import Sequence

import numpy as np
from matplotlib.figure import Figure

from .plan_record import DrawnLeg, DrawnPlan
from .plot_common import (
    _AFTER_COLOR,
    _BEFORE_COLOR,
    _LABEL_SIZE,
    _NOTE_SIZE,
    _TITLE_SIZE,
    _leg_name,
    _new_figure,
    _path_name,
)


def plot_cost(solution: DrawnPlan) -> Figure:
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


def _operations_per_leg(solution: DrawnPlan) -> list[float] | None:
    """Operations ΔV carried by each leg (at its arrival debris; the first leg also those
    at the first debris), as in ``legs.csv``; None when there are none."""
    if not solution.operations_dv_mps or not solution.legs:
        return None
    per_debris = dict(solution.operations.get("per_debris_mps") or {})
    out = [float(per_debris.get(leg.to_id, 0.0)) for leg in solution.legs]
    out[0] += float(per_debris.get(solution.legs[0].from_id, 0.0))
    return out


def _legs_path(legs: Sequence[DrawnLeg]) -> list[str]:
    return [legs[0].from_id, *(leg.to_id for leg in legs)] if legs else []
