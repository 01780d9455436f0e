"""What a transfer model provides: the one signature of the leg physics (:class:`TransferModel`).

A *transfer model* is what every room of the package needs to know of a leg between
two debris (the pvlib ``ModelChain`` shape: one signature, swappable models):

- ``leg_dv(origin_a, origin_inc, target_a, target_inc, a_drift, inc_drift)`` [m/s] and
  ``leg_seconds(origin, target, a_drift, inc_drift, t_depart, *, laps, j2)`` [s]: the
  leg flown in the true model (plans, reports, the paper's method);
- ``cost_at(legs, e, t, t_arrive, *, rule, j2, t_min)``: the exact cheapest leg
  between two dates [days] (:class:`~sdc_cvx.physics.transfer.LegAtDates`; the
  certified search's plans);
- ``box_bound(legs, e, t1, t2, t3, t4, *, rule, j2, t_min, cap)``: a lower bound of the
  cost over a box of dates, never above the cost of a leg in the box and exact in the
  limit (the certified search's bounds; each model's proof is in ``docs/design.md``); it
  may stop refining a box once its bound reaches ``cap``;
- ``special_dates(legs, e, start, stop)``: dates a schedule may need exactly;
- ``cheapest_transfer(...)``: the pre-optimised leg of Part IV-B (edge table, paper's
  method);
- ``phase_days(...)``: the leg's phases for the report; ``describe()``: name and
  parameters for ``solution.json``.

The models (:class:`~sdc_cvx.physics.leg_bounds.ImpulsiveModel`,
:class:`~sdc_cvx.physics.low_thrust.LowThrustModel`) are chosen by name in
:mod:`~sdc_cvx.physics.models`; this module imports none of them, so the modules that
implement a model may name the protocol.

:class:`~sdc_cvx.physics.leg_bounds.LegCosts` tables carry their model, so the
certified search, campaigns and reports ask the table and never test a model's name.

References
----------
.. [1] M. Cerf, "Multiple Space Debris Collecting Mission — Debris Selection and Trajectory
   Optimization", Journal of Optimization Theory and Applications 156(3), 761–796, 2013.
.. [2] W. F. Holmgren, C. W. Hansen and M. A. Mikofski, "pvlib python: a python package
   for modeling solar energy systems", Journal of Open Source Software 3(29), 884, 2018
   (the ModelChain pattern).
"""

from __future__ import annotations

from typing import Protocol

from .transfer import LegAtDates


class TransferModel(Protocol):
    """What a transfer model provides (see the module docstring)."""

    name: str
    bound_tol_mps: float  # how far below the exact cost a point's box bound may stay [m/s]

    def leg_dv(self, origin_a, origin_inc, target_a, target_inc, a_drift, inc_drift, *, mu=...): ...

    def leg_seconds(self, origin, target, a_drift, inc_drift, t_depart, *, laps=0, j2, mu=...): ...

    def cost_at(self, legs, e, t, t_arrive, *, rule, j2, t_min=0.0) -> LegAtDates: ...

    def box_bound(self, legs, e, t1, t2, t3, t4, *, rule, j2, t_min=0.0, cap=..., floor=...): ...

    def special_dates(self, legs, e, start, stop): ...

    def cheapest_transfer(self, origin, target, t_depart, max_duration, a_low, a_high, *,
                          inclination="table3", sides=(1.0, -1.0), j2, mu=...): ...  # fmt: skip

    def phase_days(self, origin_a, origin_inc, target_a, target_inc, a_drift,
                   duration_days) -> dict: ...  # fmt: skip

    def describe(self) -> dict: ...


__all__ = ["TransferModel"]
