"""Phasing a leg: a mean orbit moving by secular rates, and the zeros of a phase error.

A leg that flies must arrive at the debris itself, not only in its plane: the paper's
model neglects "the phasing, negligible provided that the return transfer takes place at
the adequate phasing opportunity" (Part III-F).  This module holds what a phasing search
needs whatever the transfer: :class:`MeanOrbit` (an orbit whose RAAN and argument of
latitude move at constant rates, optionally with a measured wander about those lines)
and :func:`grid_zeros` (the zeros of a phase error along a grid of drift radii, each
bracket refined by bisection, all at once).  The low-thrust leg's phasing is
:mod:`~sdc_cvx.physics.low_thrust_phasing`; an impulsive leg is planned as an optimised
rendezvous instead (:mod:`sdc_cvx.flight.rendezvous`, issue 46).

Everything here is the mean-element model with first-order secular J2 rates
(:func:`~sdc_cvx.physics.elements.secular_rates`).  All angles rad, lengths m, times s.

References
----------
.. [1] M. Cerf, "Multiple Space Debris Collecting Mission — Debris Selection and Trajectory
   Optimization", Journal of Optimization Theory and Applications 156(3), 761–796, 2013.
.. [2] D. A. Vallado, *Fundamentals of Astrodynamics and Applications*, 4th ed.,
   Microcosm Press, 2013, §6.6 (phasing) and §9.6 (secular J2 effects).
"""

from __future__ import annotations

from typing import NamedTuple

import numpy as np

from .elements import secular_rates
from .orbits import J2, MU_EARTH, R_EARTH

TWO_PI = 2.0 * np.pi
PHASE_TOL_RAD = 1e-6
"""Largest phase error [rad] of a phased leg (about 7 m along an orbit at 800 km)."""
RADIUS_SPANS_M = (12e3, 50e3, 200e3)
"""Half-widths [m] of the brackets of drift radii searched around the plan's, the next
only when the one before meets the target nowhere (a leg whose drift orbit is its
departure orbit, the plan's zero-length legs, phases only by moving it far)."""
BISECTIONS = 30
"""Halvings of a bracket of radii (2 m to 33 m wide): 2e-9 to 3e-8 m, a phase error far
below :data:`PHASE_TOL_RAD` at the steepest 8 rad per km."""
LATE_COST_MPS_PER_DAY = 2.0
"""What a day of lateness is worth [m/s] when no phasing arrives in time (a zero-length leg
of the plan, flown after corrections): waiting a synodic period is then cheaper than a
drift fast enough to keep the date, and the legs after it may make the days up."""
RADIUS_POINTS = 12001
"""Points of each bracket before the zeros are refined by bisection (2 m apart in the
first: the phase error turns up to about 8 rad per km on a half-year drift)."""


class MeanOrbit(NamedTuple):
    """A near-circular orbit in mean elements, carried by secular J2 rates.

    Attributes
    ----------
    a, e, inc : float
        Mean semi-major axis [m], eccentricity [-] and inclination [rad].
    raan, arglat : float
        RAAN and mean argument of latitude [rad] at t = 0.
    raan_rate, arglat_rate : float
        Their secular rates [rad/s].
    wander : tuple of ndarray, optional
        ``(t, raan, arglat)``: dates [s] and how far from those lines the RAAN and the
        argument of latitude are there [rad], followed linearly between the dates, 0
        outside them (a debris fitted to its SGP4 states over a window,
        :func:`sdc_cvx.flight.rates.fitted_orbit`: drag lowers it and speeds its argument
        of latitude up; ``None``, the lines alone).
    """

    a: float
    e: float
    inc: float
    raan: float
    arglat: float
    raan_rate: float
    arglat_rate: float
    wander: tuple | None = None

    @classmethod
    def from_elements(cls, a, e, inc, raan, arglat, *, j2=J2, mu=MU_EARTH, r_eq=R_EARTH):
        rates = secular_rates(a, e, inc, j2=j2, mu=mu, r_eq=r_eq)
        return cls(float(a), float(e), float(inc), float(raan), float(arglat),
                   float(rates.raan), float(rates.arglat))  # fmt: skip

    def raan_at(self, t):
        t = np.asarray(t, dtype=float)
        return self.raan + self.raan_rate * t + self._wander(t, 1)

    def arglat_at(self, t):
        t = np.asarray(t, dtype=float)
        return self.arglat + self.arglat_rate * t + self._wander(t, 2)

    def _wander(self, t, column: int):
        if self.wander is None:
            return 0.0
        return np.interp(t, self.wander[0], self.wander[column], left=0.0, right=0.0)


class Brackets(NamedTuple):
    """Brackets of radii where a phase error changes sign: ``[lo, hi]``, the error at
    ``lo``, and each one's row (departure node or delay)."""

    lo: np.ndarray
    hi: np.ndarray
    e_lo: np.ndarray
    rows: np.ndarray

    def take(self, mask) -> Brackets:
        return Brackets(*(v[mask] for v in self))


def grid_brackets(error_at, grid, rows) -> Brackets:
    """Where ``error_at(row, x)`` changes sign between neighbours of ``grid`` (not a jump
    at +/- pi), for each of ``rows``."""
    error = error_at(rows[:, None], grid[None, :])
    cross = (np.sign(error[:, :-1]) != np.sign(error[:, 1:])) & (
        np.abs(error[:, :-1] - error[:, 1:]) < np.pi)  # fmt: skip
    at, cols = np.nonzero(cross)
    return Brackets(grid[cols], grid[cols + 1], error[at, cols], rows[at])


def refine(error_at, brackets: Brackets):
    """The zeros in ``brackets``, by :data:`BISECTIONS` halvings all at once; the zeros
    and their rows."""
    lo, hi, e_lo, rows = brackets
    for _ in range(BISECTIONS):
        mid = 0.5 * (lo + hi)
        e_mid = error_at(rows, mid)
        same = np.sign(e_mid) == np.sign(e_lo)
        lo, e_lo = np.where(same, mid, lo), np.where(same, e_mid, e_lo)
        hi = np.where(same, hi, mid)
    return 0.5 * (lo + hi), rows


def grid_zeros(error_at, grid, rows):
    """Where ``error_at(row, x)`` vanishes along ``grid`` for each of ``rows``: every sign
    change between neighbours (not a jump at +/- pi) refined by :data:`BISECTIONS`
    halvings, all brackets at once; the zeros and their rows."""
    return refine(error_at, grid_brackets(error_at, grid, rows))
