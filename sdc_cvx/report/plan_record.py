"""What the report reads of a solved plan: the fields its figures draw and its run folder
writes, as protocols.

A :class:`~sdc_cvx.solution.Solution` is a :class:`DrawnPlan` and a :class:`SavedPlan`
(its :class:`~sdc_cvx.solution.Leg` a :class:`DrawnLeg`, its
:class:`~sdc_cvx.solution.IterationRecord` a :class:`DrawnStep`).  The solution draws
and saves itself through this package (``Solution.plot``, ``Solution.save``), so the
report names these protocols and never the solution's classes: the arrows between the
two go one way, solution -> report.
"""

from __future__ import annotations

from collections.abc import Sequence
from typing import Protocol

import pandas as pd

from ..inputs.catalog import Catalog
from ..inputs.mission import Mission


class DrawnLeg(Protocol):
    """A leg as the figures draw it (days after day 0, km, deg, m/s)."""

    from_id: str
    to_id: str
    departure_day: float
    duration_days: float
    drift_a_km: float
    drift_alt_km: float
    drift_inc_deg: float
    dv_mps: float
    phases: dict


class DrawnStep(Protocol):
    """A step of the search as ``iterations.png`` draws it (the paper's Table 7 row)."""

    iteration: int
    path: tuple[str, ...]
    dv_linearized_mps: float | None
    dv_true_mps: float | None
    duration_true_days: float | None
    status: str
    rejected: str
    elapsed_s: float | None


class DrawnPlan(Protocol):
    """A plan as the figures draw it: path, legs, totals, the search's history."""

    path: tuple[str, ...]
    legs: Sequence[DrawnLeg]
    initial_legs: Sequence[DrawnLeg]
    total_dv_mps: float
    status: str
    method: str
    mission: Mission
    catalog: Catalog | None
    iterations: Sequence[DrawnStep]
    operations: dict
    timings: dict
    lower_bound_mps: float | None
    search_trace: Sequence[tuple[float, float | None, float | None]]

    @property
    def gap_mps(self) -> float | None: ...
    @property
    def gap_rel(self) -> float | None: ...
    @property
    def operations_dv_mps(self) -> float: ...
    @property
    def has_history(self) -> bool: ...


class SavedPlan(DrawnPlan, Protocol):
    """A plan as its run folder is written: its figures, tables and ``solution.json``."""

    def legs_frame(self) -> pd.DataFrame: ...
    def iterations_frame(self) -> pd.DataFrame: ...
    def to_json(self) -> str: ...


__all__ = ["DrawnLeg", "DrawnPlan", "DrawnStep", "SavedPlan"]
