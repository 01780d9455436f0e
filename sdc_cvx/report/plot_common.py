"""What the run's figures share: their size, fonts and colours, the names of legs and
paths, wrapped angles, and where a solution's debris and days are in its catalog."""

from __future__ import annotations

from collections.abc import Sequence

import numpy as np
from matplotlib import colormaps
from matplotlib.figure import Figure

from ..errors import listing
from ..inputs.catalog import Catalog
from ..physics.orbits import R_EARTH
from .plan_record import DrawnLeg, DrawnPlan

FIGURE_SIZE = (8.0, 4.5)
"""Size of every figure [inch]: readable at report width."""

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


def _leg_name(leg: DrawnLeg) -> str:
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


def _positions(solution: DrawnPlan, catalog: Catalog) -> dict[str, int]:
    """Catalog position of every debris of the solution's path and legs."""
    index = {debris: pos for pos, debris in enumerate(catalog.ids)}
    wanted = list(solution.path)
    for leg in (*solution.legs, *solution.initial_legs):
        wanted += [leg.from_id, leg.to_id]
    missing = sorted({debris for debris in wanted if debris not in index})
    if missing:
        raise ValueError(
            f"debris {listing(missing)} of the solution are not in the catalog "
            f"({catalog.source}); plot a solution with the catalog it was solved for"
        )
    return index


def _altitudes_km(catalog: Catalog) -> np.ndarray:
    return (catalog.a_m - R_EARTH) / 1000.0


def _end_day(solution: DrawnPlan) -> float:
    """End of the mission [days]: last arrival plus the operations there."""
    if not solution.legs:
        return float(solution.mission.deorbit_days)
    last = solution.legs[-1]
    return last.departure_day + last.duration_days + solution.mission.deorbit_days
