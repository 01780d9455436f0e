"""The vehicle as it flies: its state, the arcs flown so far, and the impulses it takes.

A :class:`Track` coasts by numerical propagation (:func:`~sdc_cvx.flight.propagation.propagate`)
and keeps each arc between two impulses as one trajectory segment, sampled as the OEM
wants them (:func:`~sdc_cvx.flight.oem.sample_times`); :meth:`Track.impulse` changes
its velocity and records the :class:`~sdc_cvx.flight.result.Maneuver`.
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np
from scipy.integrate import trapezoid

from ..physics.elements import rtn_basis
from ..physics.impulses import rtn
from .oem import sample_times
from .propagation import ForceModel, propagate
from .result import Maneuver
from .thrust import Thrust


@dataclass
class Track:
    """The vehicle's state at ``t`` [s after day 0]: ``r`` [m], ``v`` [m/s] (GCRF)."""

    t: float
    r: np.ndarray
    v: np.ndarray
    segments: list = field(default_factory=list)
    coasting: bool = False
    """The last segment is a coast no impulse has ended yet: the next coast continues it
    (the OEM has one segment per arc between impulses)."""

    def coast(self, t_end: float, force: ForceModel, pole: np.ndarray) -> None:
        """Propagate to ``t_end`` [s] and keep the arc's samples as one segment (nothing
        for a coast of under a microsecond: the epochs of the files)."""
        if t_end <= self.t + 1e-6:
            return
        samples = sample_times(self.t, t_end)
        arc = propagate(self.r, self.v, self.t, t_end, force, pole=pole, t_eval=samples)
        if self.coasting and self.segments:  # the same arc, on: its first sample is a repeat
            t, r, v = self.segments.pop()
            self.segments.append((np.concatenate([t, arc.t[1:]]), np.vstack([r, arc.r[1:]]),
                                  np.vstack([v, arc.v[1:]])))
        else:
            self.segments.append((arc.t, arc.r, arc.v))
        self.t, self.r, self.v = t_end, arc.r1, arc.v1
        self.coasting = True

    def thrust(self, t_end: float, thrust: Thrust, force: ForceModel, pole: np.ndarray,
               leg: int, kind: str) -> Maneuver | None:  # fmt: skip
        """Fly a thrust arc to ``t_end`` [s] (one segment); the manoeuvre, its thrust
        integrated over the OEM's samples (trapezoids), or None for an empty arc."""
        if t_end <= self.t:
            return None
        start, samples = self.t, sample_times(self.t, t_end)
        arc = propagate(self.r, self.v, self.t, t_end, force, pole=pole, t_eval=samples,
                        thrust=thrust)  # fmt: skip
        self.segments.append((arc.t, arc.r, arc.v))
        self.t, self.r, self.v = t_end, arc.r1, arc.v1
        self.coasting = False
        accel = thrust.acceleration(arc.r, arc.v, pole)
        local = np.einsum("nij,nj->ni", rtn_basis(arc.r, arc.v), accel)  # each sample's RTN
        return Maneuver(start, leg, kind, trapezoid(accel, arc.t, axis=0),
                        trapezoid(local, arc.t, axis=0), end_s=t_end,
                        accel_mps2=thrust.accel, law=thrust.describe())  # fmt: skip

    def impulse(self, leg: int, kind: str, v_new) -> Maneuver:
        """Change the velocity to ``v_new`` [m/s] now; the manoeuvre that did it."""
        dv = np.asarray(v_new, dtype=float) - self.v
        maneuver = Maneuver(self.t, leg, kind, dv, rtn(self.r, self.v, dv))
        self.v = np.asarray(v_new, dtype=float)
        self.coasting = False
        return maneuver

    @property
    def normal(self) -> np.ndarray:
        """Unit normal of the osculating plane."""
        h = np.cross(self.r, self.v)
        return h / np.linalg.norm(h)
