"""Dense groups of a catalogue: where the removal targets are, before choosing a selection.

A public catalogue holds thousands of objects; removal studies target *clusters*: many
objects of one kind on nearly the same orbit (the SL-8 rocket bodies at 83 deg, the
SL-16 ones at 71 deg, the sun-synchronous rocket bodies).  :func:`find_clusters` finds
them as the connected groups of dense cells of an altitude x inclination grid:

1. every object falls in a cell of ``altitude_step_km`` x ``inclination_step_deg``
   (25 km x 0.5 deg by default: a drift transfer between two cells costs tens of m/s);
2. a cell is dense when it holds at least ``min_cell`` objects;
3. dense cells that touch (side or corner) form a group; groups of fewer than
   ``min_objects`` objects are left out.

For each group the table gives what decides whether it is a good removal target
(Part III of the paper): the count, the altitude and inclination ranges, the spread of
the J2 RAAN rates (Eq. 7) and of the RAANs at the start date.  The RAAN gaps between
members close at the differences of their rates: a spread of ``s`` deg/day lets any gap
close within ``360 / s`` days (the ``raan_cycle_days`` column) without a drift orbit;
drift orbits (the paper's strategy) shorten it.  ``select`` holds the command-line flags
that pick the group out.

Pure numpy and pandas; the figure is :func:`sdc_cvx.report.clusters.plot_clusters`.
"""

from __future__ import annotations

import math
from collections import Counter, deque
from dataclasses import dataclass

import numpy as np
import pandas as pd

from .catalog import Catalog

__all__ = ["Clusters", "clusters_table", "find_clusters", "raan_spread_deg"]

TABLE_COLUMNS = (
    "cluster", "objects", "altitude_km", "inclination_deg", "j2_rate_deg_per_day",
    "j2_rate_spread", "raan_spread_deg", "raan_cycle_days", "types", "common_name", "select",
)  # fmt: skip
"""Columns of :attr:`Clusters.table`."""


@dataclass(frozen=True)
class Clusters:
    """The dense groups of a catalogue (:func:`find_clusters`).

    Attributes
    ----------
    table : pandas.DataFrame
        One row per group, the largest first: ``cluster`` (1, 2, ...), ``objects``,
        ``altitude_min_km`` / ``altitude_max_km``, ``inc_min_deg`` / ``inc_max_deg``,
        ``rate_min_deg_per_day`` / ``rate_max_deg_per_day`` (J2 RAAN rates),
        ``rate_spread_deg_per_day``, ``raan_spread_deg`` (the smallest arc holding every
        RAAN at the start date), ``raan_cycle_days`` (``360 / rate spread``: the longest
        time a RAAN gap takes to close by the rates alone), ``rocket_bodies``,
        ``debris``, ``payloads`` (by name, :func:`~sdc_cvx.inputs.selection.object_type`;
        0 without names), ``common_name`` (the most frequent name and its count, or "")
        and ``select`` (flags of ``run`` and ``catalog`` that keep the group).
    labels : numpy.ndarray of int
        The ``cluster`` number of each catalog row, 0 for rows in no group.
    altitude_step_km, inclination_step_deg : float
        The grid cells.
    """

    table: pd.DataFrame
    labels: np.ndarray
    altitude_step_km: float
    inclination_step_deg: float


def raan_spread_deg(raan_deg: np.ndarray) -> float:
    """The smallest arc [deg] of the circle that holds every angle of ``raan_deg``.

    ``360 -`` the largest gap between neighbours on the circle; 0 for one angle.
    """
    angles = np.sort(np.mod(np.asarray(raan_deg, dtype=float), 360.0))
    if len(angles) < 2:
        return 0.0
    gaps = np.diff(np.append(angles, angles[0] + 360.0))
    return float(360.0 - gaps.max())


def find_clusters(
    catalog: Catalog,
    *,
    altitude_step_km: float = 25.0,
    inclination_step_deg: float = 0.5,
    min_cell: int = 3,
    min_objects: int = 10,
) -> Clusters:
    """The dense altitude x inclination groups of ``catalog`` (see the module docstring).

    Parameters
    ----------
    catalog : Catalog
        The objects (usually a selection: ``--type rocket-body``, LEO).
    altitude_step_km : float
        Cell height [km] (> 0).
    inclination_step_deg : float
        Cell width [deg] (> 0).
    min_cell : int
        Objects a cell needs to be dense (>= 1).
    min_objects : int
        Objects a group needs to be listed (>= 1).

    Returns
    -------
    Clusters

    Raises
    ------
    ValueError
        A step that is not a finite number > 0, or a count below 1.
    """
    for name, step in (("altitude_step_km", altitude_step_km),
                       ("inclination_step_deg", inclination_step_deg)):  # fmt: skip
        if not (isinstance(step, int | float) and math.isfinite(step) and step > 0):
            raise ValueError(f"{name} must be a finite number > 0, got {step!r}")
    for name, count in (("min_cell", min_cell), ("min_objects", min_objects)):
        if not (isinstance(count, int) and count >= 1):
            raise ValueError(f"{name} must be an integer >= 1, got {count!r}")
    frame = catalog.frame
    altitude = frame["altitude_km"].to_numpy(dtype=float)
    inc = frame["inc_deg"].to_numpy(dtype=float)
    rows_cell = np.floor(altitude / altitude_step_km).astype(int).tolist()
    columns_cell = np.floor(inc / inclination_step_deg).astype(int).tolist()
    cells = list(zip(rows_cell, columns_cell, strict=True))
    counts = Counter(cells)
    dense = {cell for cell, count in counts.items() if count >= min_cell}
    group_of: dict[tuple[int, int], int] = {}
    groups: list[list[tuple[int, int]]] = []
    for cell in sorted(dense):
        if cell in group_of:
            continue
        group_of[cell] = len(groups)
        members, queue = [cell], deque([cell])
        while queue:
            a, i = queue.popleft()
            for da in (-1, 0, 1):
                for di in (-1, 0, 1):
                    near = (a + da, i + di)
                    if near in dense and near not in group_of:
                        group_of[near] = len(groups)
                        members.append(near)
                        queue.append(near)
        groups.append(members)
    row_group = np.array([group_of.get(cell, -1) for cell in cells], dtype=int)
    sizes = np.bincount(row_group[row_group >= 0], minlength=len(groups))
    order = [g for g in np.argsort(-sizes, kind="stable") if sizes[g] >= min_objects]
    labels = np.zeros(len(frame), dtype=int)
    rows = []
    for rank, group in enumerate(order, start=1):
        members = np.flatnonzero(row_group == group)
        labels[members] = rank
        rows.append(_describe(frame.iloc[members], rank))
    columns = ["cluster", "objects", "altitude_min_km", "altitude_max_km", "inc_min_deg",
               "inc_max_deg", "rate_min_deg_per_day", "rate_max_deg_per_day",
               "rate_spread_deg_per_day", "raan_spread_deg", "raan_cycle_days",
               "rocket_bodies", "debris", "payloads", "common_name", "select"]  # fmt: skip
    return Clusters(pd.DataFrame(rows, columns=columns), labels, float(altitude_step_km),
                    float(inclination_step_deg))  # fmt: skip


def _describe(members: pd.DataFrame, rank: int) -> dict:
    """One row of the clusters table."""
    from .selection import object_type

    altitude = members["altitude_km"].to_numpy(dtype=float)
    inc = members["inc_deg"].to_numpy(dtype=float)
    rate = members["raan_rate_deg_per_day"].to_numpy(dtype=float)
    spread = float(rate.max() - rate.min())
    kinds = Counter()
    common = ""
    if "name" in members.columns:
        names = [str(name) for name in members["name"]]
        kinds = Counter(object_type(name) for name in names)
        name, count = Counter(names).most_common(1)[0]
        common = f"{name} ({count})" if name else ""
    low, high = math.floor(altitude.min()), math.ceil(altitude.max())
    inc_low, inc_high = math.floor(inc.min() * 10) / 10, math.ceil(inc.max() * 10) / 10
    select = f"--altitude-km {low} {high} --inclination-deg {inc_low:.1f} {inc_high:.1f}"
    return {
        "cluster": rank,
        "objects": len(members),
        "altitude_min_km": float(altitude.min()),
        "altitude_max_km": float(altitude.max()),
        "inc_min_deg": float(inc.min()),
        "inc_max_deg": float(inc.max()),
        "rate_min_deg_per_day": float(rate.min()),
        "rate_max_deg_per_day": float(rate.max()),
        "rate_spread_deg_per_day": spread,
        "raan_spread_deg": raan_spread_deg(members["raan_deg"].to_numpy(dtype=float)),
        "raan_cycle_days": 360.0 / spread if spread > 0 else math.inf,
        "rocket_bodies": kinds["rocket-body"],
        "debris": kinds["debris"],
        "payloads": kinds["payload"],
        "common_name": common,
        "select": select,
    }


def clusters_table(clusters: Clusters) -> str:
    """The clusters as an aligned text table, in people's units."""
    table = clusters.table
    if table.empty:
        return "(no group: narrow the selection, or lower --min-objects)"
    shown = pd.DataFrame({
        "#": table["cluster"],
        "objects": table["objects"],
        "altitude [km]": [f"{a:.0f}-{b:.0f}" for a, b in
                          zip(table["altitude_min_km"], table["altitude_max_km"], strict=True)],
        "inclination [deg]": [f"{a:.2f}-{b:.2f}" for a, b in
                              zip(table["inc_min_deg"], table["inc_max_deg"], strict=True)],
        "J2 rate [deg/day]": [f"{a:+.3f}..{b:+.3f}" for a, b in
                              zip(table["rate_min_deg_per_day"], table["rate_max_deg_per_day"],
                                  strict=True)],
        "rate spread": table["rate_spread_deg_per_day"].map("{:.3f}".format),
        "RAAN spread [deg]": table["raan_spread_deg"].map("{:.0f}".format),
        "RAAN cycle [days]": table["raan_cycle_days"].map("{:,.0f}".format),
        "R/B/DEB/payload": [f"{r}/{d}/{p}" for r, d, p in
                            zip(table["rocket_bodies"], table["debris"], table["payloads"],
                                strict=True)],
        "most common name": table["common_name"],
        "select": table["select"],
    })  # fmt: skip
    return shown.to_string(index=False)
