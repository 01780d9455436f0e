"""What a run of the paper's method records, and the driver's steps that record it.

:class:`RunLog` keeps the iterations (the columns of the paper's Table 7), the notes,
timings and backends used, and the first linearised plan (Fig. 19); :class:`LogSteps`
records an iteration and marks a rejected step, telling ``progress`` each time.

Equation, table and part numbers are those of Cerf's paper [1]_; the design
rationale is in ``docs/design.md``.

References
----------
.. [1] M. Cerf, "Multiple Space Debris Collecting Mission — Debris Selection and Trajectory
   Optimization", Journal of Optimization Theory and Applications 156(3), 761–796, 2013.
   doi:10.1007/s10957-012-0130-6
"""

from __future__ import annotations

import time
from dataclasses import dataclass, field, replace

import numpy as np

from ...milp.types import SolveReport
from ...solution import IterationRecord, Leg


@dataclass
class RunLog:
    """What a run records: the iterations (Table 7), notes, timings and backends used."""

    history: list[IterationRecord] = field(default_factory=list)
    notes: list[str] = field(default_factory=list)
    timings: dict = field(default_factory=dict)
    backends_used: set[str] = field(default_factory=set)
    last_switch: str | None = None  # the fallback message last noted (once per change)
    initial_legs: tuple[Leg, ...] | None = None  # the first linearised plan (paper Fig. 19)


class LogSteps:
    """The driver's steps that record the run.

    A part of :class:`~sdc_cvx.planner.paper.driver._Driver`: they write to its
    :class:`RunLog` (``log``) and call its ``progress``.
    """

    def id_path(self, path) -> tuple[str, ...]:
        return tuple(self.catalog.ids[k] for k in path)

    def record(self, report: SolveReport, path, legs, evaluation, start, note):
        record = IterationRecord(
            iteration=len(self.log.history),
            path=self.id_path(path),
            dv_linearized_mps=report.objective,
            dv_true_mps=self.total(path, evaluation) if path else None,
            duration_true_days=evaluation.end_day if path else None,
            nodes=report.nodes,
            seconds=time.perf_counter() - start,
            solve_seconds=report.solve_seconds,
            cvxpy_seconds=report.overhead_seconds,
            alpha_km=float(np.max(self.trust.region.alpha_km[legs])) if len(legs) else None,
            status=report.status.value,
            note=note,
        )
        self.log.history.append(record)
        self.progress(record)

    def mark_rejected(self, reason: str):
        """Mark the last iteration's step rejected (and tell ``progress`` again)."""
        record, tmax = self.log.history[-1], self.mission.tmax_days
        end = record.duration_true_days
        if "after T_max" not in reason and end is not None and end > tmax + 1e-6:
            reason += f"; its true plan also ends on day {end:.1f}, after T_max = {tmax:g}"
        record = replace(record, rejected=reason)
        self.log.history[-1] = record
        self.progress(record)
