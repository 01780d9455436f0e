"""An independent brute force of the low-thrust mission's optimum, for the solver's tests.

Nothing here comes from ``sdc_cvx``: the leg physics is written again from the model
statement (SI units inside: m, s, rad, m/s, m/s^2; days only at the API's edges).

The model
---------
Circular drift orbits, J2 RAAN rates ``rate(a, I, e) = -(3/2) J2 R^2 sqrt(mu) a^-3.5
cos I / (1 - e^2)^2`` (e = 0 for the vehicle).  A leg i -> j leaving at date t with drift
radius ``a_d`` in the band and drift inclination ``I_d`` in {I_i, I_j} flies a tangential
spiral a_i -> a_d at I_i (A), a plane change I_i -> I_j at a_d (B), a coast on
(a_d, I_d) (C: physically before B when I_d = I_i, the RAAN sums do not care), a spiral
a_d -> a_j at I_j (D).  Its cost is dV_A + dV_B + dV_D; the coast is the smallest
t_C >= 0 closing the RAAN at arrival, plus any whole number of relative laps.  Its
duration D (departure to arrival: thrust time plus coast, operations not counted) must be
at least ``min_transfer_days`` T_min (default 0): a leg whose smallest closing coast is
shorter takes the fewest whole relative laps that make D >= T_min (it never just waits;
at equal rates there are no laps: such a leg exists only if its thrust time reaches
T_min).  That is ``D = T_min + ((phi - rho L) mod 2 pi) / rho`` when ``L = T_min -
thrust time > 0`` (``phi`` the phase the coast closes at the relative rate ``rho``,
``D = thrust time + (phi mod 2 pi) / rho`` otherwise): T_min enters everything below as
a longer fixed part of the leg, ``max(thrust time, T_min)``, and a shifted phase.  A
mission is a path of n debris, the vehicle at the first at t = 0, each leg leaving
``deorbit_days`` after it reached its origin, ending ``deorbit_days`` after reaching the
last, by T_max.  Rules ``free`` (either inclination) and ``table3`` (I_d = max(I_i, I_j)
only where rate(a_d, I_d) >= rate_j, I_d = min only where <=; everything when I_i = I_j).

How :func:`optimum` is exhaustive
---------------------------------
*Grid.*  Every leg's drift orbits are ``radii`` (default 2049, a 390.6 m step over the
default 800 km band) equally spaced radii of the band plus the two debris radii (when in
the band), times the allowed inclinations.  Every lap count that can still end by T_max
is a separate state, from the fewest that make the leg last T_min.  Dates are never
discretised: each state carries its exact date.

*Chaining.*  The first leg leaves at ``deorbit_days``; a state is (date, cost so far,
back pointers).  Each middle leg takes every state times every grid orbit and lap count
(broadcast, in chunks) and computes the exact arrival date.  The last leg needs no
product: for one grid orbit, the departure dates from which it arrives by the deadline
are a few intervals in closed form (the wrapped RAAN gap is linear in the date between
wraps), so "cheapest grid orbit of the last leg that fits, from date t" is a step
function of t, built once per ordered pair (range-min painting over the interval
endpoints) and read by binary search; with T_min the same intervals hold for the
shifted phase and the longer fixed part.  The last leg takes the smallest coast lasting
T_min (extra laps cost nothing and only arrive later).  The plan it picks is replayed;
if the step function's reading were wrong (a date on a wrap, to rounding) that state is
recomputed directly over every grid orbit.

*Pruning, all by valid lower bounds of grid plans.*  For every ordered pair and grid
orbit, the shortest duration over every departure date of the mission (the fixed part
plus the smallest wrapped shifted phase over that window, so never below T_min) gives a
curve "cheapest leg cost vs duration budget" (nonincreasing, on 512 budget bins, rounded
the safe way).  The min-plus convolution of the remaining legs' curves, read at the
remaining budget ``T_max - date - (legs left) deorbit``, bounds the rest of any state
(another lap of a middle leg is tried only while ``(legs left) (deorbit + T_min)`` still
fit).  Paths are taken best-first by this bound (first the sum of the legs' cheapest
costs with the whole budget each, then the convolution) and the search stops when the
bound reaches the pruning threshold; states and (state, orbit) products whose cost plus
bound reach it are dropped.  The threshold is ``(1 + margin) x`` the best plan found (a
quick pass on every 32nd radius of the middle legs gives the first one), so every (path,
inclinations) combination whose grid optimum is within ``margin`` (default 0.2 %) of the
grid optimum is kept: the search returns the exact optimum over the grid (paths x radii
x inclinations x laps), not an approximation of it.

*Refinement.*  Each kept combination's grid optimum is then zoomed: windows of +/- 2 steps
around every leg's radius (both inclinations, all laps) with ``zoom_points`` (41) radii
for the first middle legs, 401 for the last middle leg and 2001 (plus the whole grid) for
the last leg -- one leg of a pair fine enough lets the search follow a thin diagonal
valley of the feasible set (two legs trading radius at a fixed arrival date) --, three
levels each 10x narrower (windows +/- 781 m, 78 m, 7.8 m), re-centred up to 8 times a
level while the best plan moves by more than a quarter of the window.  A window includes
its centre, so zooming never loses.

Grid error
----------
A leg's cost changes by at most ``(2 + (pi/2)|I_j - I_i|) V/(2a)`` <= 5.66e-4 (2 + (pi/2)
|I_j - I_i|) m/s per metre of radius in the default band (1.2e-3 for |I_j - I_i| <= 5
deg: 0.47 m/s per 390.6 m step).  Optima often sit on grid points (debris radii, band
ends); where they sit on an edge of the feasible set instead (the mission ending at
T_max, a zero coast), the grid optimum is within about a step's cost per leg of it.
Measured on 28 random cases (sso, cluster and mixed catalogs, N 6-8, n 3-4, T_max 366 d,
1e-4 m/s^2): the grid optimum of 2049 radii is up to 6.8e-4 (513 radii: 7.7e-3) above the
refined optimum; the refined optima from grids of 513, 2049 and 8193 radii agree within
2.5e-5 relative (most within 1e-7); plain grids of 8193-20001 radii (self-tests) are
never below the refined optimum.

A binding T_min makes the grid coarser in effect: a leg must then last between T_min and
what T_max leaves, and at a slow relative rate the duration sweeps up to days per 100 m
of radius, so the cheap plans can lie in slivers of radius narrower than a step (the
last leg's window is [T_min, T_max - date]).  Measured on 40 random cases with T_min
above a leg of the optimum without it (sso, cluster and mixed, N 6-8, n 3-4, T_max
365.25 d, 1e-4 to 3e-4 m/s^2): the grid optimum of 2049 radii is up to 1.1e-2 above its
refined optimum, which is within 1e-4 of the best plan known (the refined optima of 2049
and 8193 radii and an outside solver's plan replayed here) in 36 cases and up to 4.3e-2
above it in the others (no grid plan of the better path or inclinations within the
margin); with 8193 radii within 5.3e-5 in all 40.  The answer stays exact over its grid;
a tight reference under T_min wants a check that it does not move with ``radii``.

Every returned plan is replayed leg by leg with the physics (:func:`replay`; end date <=
T_max + 1e-6 s, every leg lasting T_min - 1e-6 s or more), so its cost is that of a plan
that flies: the brute force is never below the true optimum.

Readings of the model statement
-------------------------------
* When ``I_d = I_i`` the plane change is flown after the coast (A, C, B, D); the RAAN
  changes add up the same either way, so the closure does not depend on the order.
* The last leg takes the smallest coast lasting T_min (extra laps cost nothing and only
  arrive later); middle legs take every lap count from there that can still end by T_max
  (every later leg lasting T_min).  T_min bounds the leg (thrust and coast), never the
  operations; a plan is held to it within ``TOL_S``, as to T_max.
* Equal drift and target rates: the leg exists only with the gap already closed at
  arrival of the thrust phases (coast 0, no laps).  Such drift orbits are measure-zero on
  the grid (a drift orbit at the target's radius and inclination with e_j = 0).
* Table 3 at equal signed rates allows both inclinations; drift radii equal to a debris
  radius are grid points (no spiral on that side).
* Timings: seconds for N 8, n 4 (``Plan.info["seconds"]``; 0.1-5 s measured, worst when
  no plan fits and nothing prunes, e.g. 4.6 s).
"""

from __future__ import annotations

import heapq
import itertools
import time
from dataclasses import dataclass, field
from typing import NamedTuple

import numpy as np

R_EARTH = 6378137.0
"""Earth's equatorial radius [m]."""
MU = 3.986e14
"""Earth's gravitational parameter [m^3/s^2]."""
J2 = 1.08263e-3
"""Earth's J2 [-]."""
DAY = 86400.0
"""Seconds per day [s]."""
TWO_PI = 2.0 * np.pi
A_LOW = R_EARTH + 400e3
"""Default lower end of the drift band [m]."""
A_HIGH = R_EARTH + 1200e3
"""Default upper end of the drift band [m]."""
RULES = ("free", "table3")
TOL_S = 1e-6
"""Rounding allowance of the replay's end date against T_max [s]."""

_K = -1.5 * J2 * R_EARTH**2 * np.sqrt(MU)  # rate = _K a^-3.5 cos I / (1 - e^2)^2
_EPS_S = 1e-7  # closing the step function's intervals on the right [s]
_CHUNK = 1 << 20  # elements per broadcast block
_BINS = 512  # duration-budget bins of the lower-bound curves

# ---------------------------------------------------------------------------------------
# Leg physics (vectorised numpy)
# ---------------------------------------------------------------------------------------


def speed(a):
    """Circular orbital speed ``sqrt(mu / a)`` [m/s] at radius ``a`` [m]."""
    return np.sqrt(MU / np.asarray(a, dtype=float))


def raan_rate(a, inc, e=0.0):
    """J2 RAAN rate [rad/s] of an orbit of semi-major axis ``a`` [m], inclination ``inc``
    [rad] and eccentricity ``e`` [-] (0: the vehicle's circular orbits)."""
    a = np.asarray(a, dtype=float)
    return _K * a**-3.5 * np.cos(inc) / (1.0 - np.asarray(e, dtype=float) ** 2) ** 2


def leg_dv(a_i, I_i, a_j, I_j, a_d):
    """Leg cost ``dV_A + dV_B + dV_D`` [m/s].

    Parameters
    ----------
    a_i, I_i : array_like
        Origin debris radius [m] and inclination [rad].
    a_j, I_j : array_like
        Target debris radius [m] and inclination [rad].
    a_d : array_like
        Drift radius [m].
    """
    v_d = speed(a_d)
    plane = 0.5 * np.pi * v_d * np.abs(np.subtract(I_j, I_i))
    return np.abs(speed(a_i) - v_d) + plane + np.abs(v_d - speed(a_j))


def leg_thrust_time(a_i, I_i, a_j, I_j, a_d, accel):
    """Thrust time ``t_A + t_B + t_D`` [s] of the leg at acceleration ``accel`` [m/s^2]
    (arguments as :func:`leg_dv`)."""
    return leg_dv(a_i, I_i, a_j, I_j, a_d) / accel


def spiral_raan(a_from, a_to, inc, accel):
    """RAAN change [rad] during a tangential spiral ``a_from`` -> ``a_to`` [m] at
    inclination ``inc`` [rad] and acceleration ``accel`` [m/s^2]:
    ``-(3 J2 R^2 cos I) / (16 mu^3 f) |V_to^8 - V_from^8|``."""
    c = -3.0 * J2 * R_EARTH**2 * np.cos(inc) / (16.0 * MU**3 * accel)
    return c * np.abs(speed(a_to) ** 8 - speed(a_from) ** 8)


def plane_change_raan(a_d, I_i, I_j, accel):
    """RAAN change [rad] during the plane change I_i -> I_j [rad] at radius ``a_d`` [m].

    The inclination changes linearly in time over ``t_B = (pi/2) V |I_j - I_i| / f``, so
    the change is ``rate(a_d, 0) t_B (sin I_j - sin I_i) / (I_j - I_i)``, written as
    ``cos(mid) sinc(half difference)`` (no cancellation, ``cos I_i`` when equal).
    """
    t_b = 0.5 * np.pi * speed(a_d) * np.abs(np.subtract(I_j, I_i)) / accel
    mean_cos = np.cos(0.5 * np.add(I_i, I_j)) * np.sinc(np.subtract(I_j, I_i) / TWO_PI)
    return _K * np.asarray(a_d, dtype=float) ** -3.5 * t_b * mean_cos


def thrust_raan(a_i, I_i, a_j, I_j, a_d, accel):
    """RAAN change ``dOmega_A + dOmega_B + dOmega_D`` [rad] of the leg's thrust phases
    (arguments as :func:`leg_dv`, ``accel`` [m/s^2])."""
    return (
        spiral_raan(a_i, a_d, I_i, accel)
        + plane_change_raan(a_d, I_i, I_j, accel)
        + spiral_raan(a_d, a_j, I_j, accel)
    )


def coast_time(gap, rate_drift, rate_target, thrust_time, thrust_raan_rad, laps=0):
    """Coast [s] closing the RAAN at arrival.

    Solves ``(rate_drift - rate_target) t_C = gap + rate_target thrust_time -
    thrust_raan_rad (mod 2 pi)`` for the smallest ``t_C >= 0``, plus ``laps`` whole
    relative laps ``2 pi / |rate_drift - rate_target|``.

    Parameters
    ----------
    gap : array_like
        ``Omega_j(t) - Omega_i(t)`` at departure [rad].
    rate_drift, rate_target : array_like
        RAAN rates of the drift orbit and of the target debris [rad/s].
    thrust_time : array_like
        ``t_A + t_B + t_D`` [s].
    thrust_raan_rad : array_like
        ``dOmega_A + dOmega_B + dOmega_D`` [rad].
    laps : array_like of int
        Extra relative laps (>= 0).

    Returns
    -------
    ndarray
        Coast [s]; ``inf`` when no coast closes (equal rates and an open gap, or
        ``laps > 0`` with equal rates: there are no relative laps).
    """
    x = gap + rate_target * thrust_time - thrust_raan_rad
    rel = np.subtract(rate_drift, rate_target)
    with np.errstate(divide="ignore", invalid="ignore"):
        wrapped = np.mod(np.sign(rel) * x, TWO_PI)
        t = (wrapped + TWO_PI * np.asarray(laps)) / np.abs(rel)
        residue = np.mod(x, TWO_PI)
        closed = (np.minimum(residue, TWO_PI - residue) <= 1e-12) & (np.asarray(laps) == 0)
    return np.where(rel != 0.0, t, np.where(closed, 0.0, np.inf))


def leg(a_i, e_i, I_i, raan_i, a_j, e_j, I_j, raan_j, a_d, I_d, depart_s, accel, laps=0):
    """Arrival date [s] and cost [m/s] of the leg i -> j.

    Parameters
    ----------
    a_i, e_i, I_i, raan_i : array_like
        Origin debris: semi-major axis [m], eccentricity [-], inclination [rad], RAAN at
        t = 0 [rad].
    a_j, e_j, I_j, raan_j : array_like
        Target debris, the same.
    a_d, I_d : array_like
        Drift radius [m] and inclination [rad] (the rule is not checked here).
    depart_s : array_like
        Departure date [s].
    accel : float
        Thrust acceleration [m/s^2].
    laps : array_like of int
        Extra relative laps of the coast.

    Returns
    -------
    arrive_s, dv_mps : ndarray
        Arrival date [s] (``inf``: no coast closes) and leg cost [m/s].
    """
    rate_i, rate_j = raan_rate(a_i, I_i, e_i), raan_rate(a_j, I_j, e_j)
    gap = (raan_j - raan_i) + (rate_j - rate_i) * depart_s
    thr = leg_thrust_time(a_i, I_i, a_j, I_j, a_d, accel)
    draan = thrust_raan(a_i, I_i, a_j, I_j, a_d, accel)
    coast = coast_time(gap, raan_rate(a_d, I_d), rate_j, thr, draan, laps)
    return depart_s + thr + coast, leg_dv(a_i, I_i, a_j, I_j, a_d)


def drift_allowed(I_i, I_j, a_d, I_d, rate_target, rule):
    """Whether the drift orbit (``a_d`` [m], ``I_d`` [rad]) is allowed by ``rule``.

    ``free``: ``I_d`` is one of the two debris inclinations.  ``table3``: judged on the
    coast orbit by signed rates, ``I_d = max(I_i, I_j)`` only where ``rate(a_d, I_d) >=
    rate_target`` [rad/s], ``I_d = min(I_i, I_j)`` only where ``<=``; both everywhere when
    ``I_i = I_j``.
    """
    if rule not in RULES:
        raise ValueError(f"rule must be one of {RULES}, not {rule!r}")
    I_d = np.asarray(I_d, dtype=float)
    one_of = (I_d == I_i) | (I_d == I_j)
    if rule == "free" or I_i == I_j:
        return one_of & np.isfinite(a_d)
    rate_d = raan_rate(a_d, I_d)
    upper = (I_d == max(I_i, I_j)) & (rate_d >= rate_target)
    lower = (I_d == min(I_i, I_j)) & (rate_d <= rate_target)
    return upper | lower


# ---------------------------------------------------------------------------------------
# Plans
# ---------------------------------------------------------------------------------------


@dataclass(frozen=True)
class Plan:
    """A mission plan, as replayed by the physics (one entry per leg in the tuples).

    Attributes
    ----------
    cost_mps : float
        Sum of the legs' dV [m/s].
    path : tuple of int
        Catalog positions of the visited debris, in order.
    a_drift_m, inc_drift_rad : tuple of float
        Drift radius [m] and inclination [rad] of each leg.
    depart_day, arrive_day : tuple of float
        Departure and arrival dates of each leg [days].
    dv_mps : tuple of float
        Cost of each leg [m/s].
    laps : tuple of int
        Extra relative laps of each leg's coast (0: the smallest coast).
    end_day : float
        Mission end: last arrival plus ``deorbit_days`` [days].
    info : dict
        Search statistics (not compared).
    """

    cost_mps: float
    path: tuple[int, ...]
    a_drift_m: tuple[float, ...]
    inc_drift_rad: tuple[float, ...]
    depart_day: tuple[float, ...]
    arrive_day: tuple[float, ...]
    dv_mps: tuple[float, ...]
    laps: tuple[int, ...]
    end_day: float
    info: dict = field(default_factory=dict, compare=False, repr=False)

    def __getitem__(self, key):
        return getattr(self, key)


class ShortLeg(ValueError):
    """A replayed leg lasts less than T_min."""


def replay(a_m, e, inc_rad, raan_rad, path, a_drift_m, inc_drift_rad, laps, *, accel_mps2,
           rule=None, a_low=A_LOW, a_high=A_HIGH, deorbit_days=0.0, min_transfer_days=0.0,
           tol_s=TOL_S) -> Plan:  # fmt: skip
    """Fly a plan leg by leg with the physics.

    Parameters
    ----------
    a_m, e, inc_rad, raan_rad : array_like
        Catalog: semi-major axes [m], eccentricities, inclinations [rad], RAANs at t = 0
        [rad].
    path : sequence of int
        Visited catalog positions.
    a_drift_m, inc_drift_rad, laps : sequence
        Per leg: drift radius [m], inclination [rad], extra laps.
    accel_mps2 : float
        Thrust acceleration [m/s^2].
    rule : str or None
        When given, each drift orbit must be allowed by it (``ValueError`` otherwise), and
        lie in the band [a_low, a_high] [m].
    deorbit_days : float
        Operations time at each debris [days].
    min_transfer_days : float
        T_min [days]: every leg must last (departure to arrival) at least T_min - ``tol_s``
        (:class:`ShortLeg` otherwise).
    tol_s : float
        Rounding allowance of that check [s].

    Returns
    -------
    Plan
        Dates, costs and end date (``end_day`` may exceed T_max: the caller checks).
    """
    a_m, e, inc, raan = (np.asarray(x, dtype=float) for x in (a_m, e, inc_rad, raan_rad))
    rates = raan_rate(a_m, inc, e)
    dd = float(deorbit_days) * DAY
    t = dd
    departs, arrives, dvs = [], [], []
    for (i, j), a_d, i_d, q in zip(itertools.pairwise(path), a_drift_m, inc_drift_rad, laps,
                                   strict=True):  # fmt: skip
        if rule is not None:
            ok = drift_allowed(inc[i], inc[j], a_d, i_d, rates[j], rule)
            if not (bool(ok) and a_low <= a_d <= a_high):
                raise ValueError(f"drift orbit ({a_d}, {i_d}) of leg {i}->{j} not allowed")
        arrive, dv = leg(a_m[i], e[i], inc[i], raan[i], a_m[j], e[j], inc[j], raan[j],
                         a_d, i_d, t, accel_mps2, q)  # fmt: skip
        if not float(arrive) - t >= float(min_transfer_days) * DAY - tol_s:
            raise ShortLeg(f"leg {i}->{j} lasts {(float(arrive) - t) / DAY} days, less "
                             f"than T_min = {min_transfer_days} days")  # fmt: skip
        departs.append(t / DAY)
        arrives.append(float(arrive) / DAY)
        dvs.append(float(dv))
        t = float(arrive) + dd
    return Plan(
        cost_mps=float(sum(dvs)),
        path=tuple(int(k) for k in path),
        a_drift_m=tuple(float(x) for x in a_drift_m),
        inc_drift_rad=tuple(float(x) for x in inc_drift_rad),
        depart_day=tuple(departs),
        arrive_day=tuple(arrives),
        dv_mps=tuple(dvs),
        laps=tuple(int(q) for q in laps),
        end_day=t / DAY,
    )


# ---------------------------------------------------------------------------------------
# Search machinery
# ---------------------------------------------------------------------------------------


class _Cells:
    """Drift orbits (radius x inclination) of the ordered pair i -> j allowed by the rule,
    sorted by cost, with what the arrival date needs.

    With T_min a leg lasts ``fixed + ((phase0 + sigma t) mod 2 pi) / rho`` from date t:
    ``fixed = max(thrust time, T_min)``, ``phase0`` the closing phase at t = 0 shifted by
    ``-rho (fixed - thrust time)``, ``sigma`` the gap's signed rate, ``rho = |rel|``.
    """

    def __init__(self, prob: _Problem, i: int, j: int, radii, incs):
        radii = np.asarray(radii, dtype=float)
        incs = np.unique(np.asarray(incs, dtype=float))
        a = np.tile(radii, incs.size)
        inc = np.repeat(incs, radii.size)
        ai, aj, ii, ij = prob.a[i], prob.a[j], prob.inc[i], prob.inc[j]
        self.i, self.j = i, j
        self.rate_j = prob.rate[j]
        self.gap0 = prob.raan[j] - prob.raan[i]
        self.gap_rate = prob.rate[j] - prob.rate[i]
        keep = drift_allowed(ii, ij, a, inc, self.rate_j, prob.rule)
        keep &= (a >= prob.a_low) & (a <= prob.a_high)
        a, inc = a[keep], inc[keep]
        dv = leg_dv(ai, ii, aj, ij, a)
        order = np.lexsort((inc, a, dv))
        self.a, self.inc, self.dv = a[order], inc[order], dv[order]
        self.thr = leg_thrust_time(ai, ii, aj, ij, self.a, prob.accel)
        self.draan = thrust_raan(ai, ii, aj, ij, self.a, prob.accel)
        self.rate_d = raan_rate(self.a, self.inc)
        self.rel = self.rate_d - self.rate_j
        with np.errstate(divide="ignore"):
            self.period = TWO_PI / np.abs(self.rel)
        self.upper = self.inc == ij  # inclination flag, for the combinations
        self.t_min = prob.t_min
        self.fixed = np.maximum(self.thr, self.t_min)
        s = np.sign(self.rel)
        self.phase0 = (s * (self.gap0 + self.rate_j * self.thr - self.draan)
                       - np.abs(self.rel) * (self.fixed - self.thr))  # fmt: skip

    @property
    def size(self) -> int:
        return self.dv.size

    def arrival(self, t, cols, laps=0):
        """Arrival dates [s] for departures ``t`` [s] on the orbits ``cols``."""
        gap = self.gap0 + self.gap_rate * t
        thr = self.thr[cols]
        coast = coast_time(gap, self.rate_d[cols], self.rate_j, thr, self.draan[cols], laps)
        return t + thr + coast

    def first_arrival(self, t, cols):
        """Arrival dates [s] and lap counts of the legs from ``t`` [s] on the orbits
        ``cols`` with the fewest laps that last T_min (date ``inf``: none)."""
        t, cols = np.broadcast_arrays(np.asarray(t, dtype=float), np.asarray(cols))
        arrive = self.arrival(t, cols)
        laps = np.zeros(arrive.shape, dtype=np.int64)
        if self.t_min <= 0.0:
            return arrive, laps
        short = np.flatnonzero((arrive - t < self.t_min) & np.isfinite(arrive))
        period = self.period[cols[short]]
        arrive[short[~np.isfinite(period)]] = np.inf  # equal rates: no laps to add
        short, period = short[np.isfinite(period)], period[np.isfinite(period)]
        need = np.maximum(np.ceil((self.t_min - (arrive[short] - t[short])) / period), 1.0)
        laps[short] = need.astype(np.int64)
        while short.size:  # one more lap where rounding left the leg short
            arrive[short] = self.arrival(t[short], cols[short], laps[short])
            short = short[arrive[short] - t[short] < self.t_min]
            laps[short] += 1
        return arrive, laps

    def min_duration(self, t_lo: float, t_hi: float):
        """Shortest duration [s] of each orbit over departures in [t_lo, t_hi] [s]."""
        sigma = np.sign(self.rel) * self.gap_rate
        pa, pb = self.phase0 + sigma * t_lo, self.phase0 + sigma * t_hi
        lo, hi = np.minimum(pa, pb), np.maximum(pa, pb)
        wraps = np.ceil(lo / TWO_PI) * TWO_PI <= hi
        w = np.where(wraps, 0.0, np.mod(lo, TWO_PI))
        with np.errstate(divide="ignore", invalid="ignore"):
            coast = np.where(self.rel != 0.0, w / np.abs(self.rel), 0.0)
        return self.fixed + coast


class _LastLeg:
    """Cheapest orbit of ``cells`` arriving by ``deadline`` [s] from any departure date in
    [t_lo, t_hi] [s]: a step function of the date, exact on the grid."""

    def __init__(self, cells: _Cells, t_lo: float, t_hi: float, deadline: float):
        self.cells = cells
        self.deadline = deadline
        lefts, rights, ranks = self._intervals(cells, t_lo, t_hi, deadline)
        if lefts.size == 0:
            self.edges = np.array([0.0])
            self.best = np.zeros(0, dtype=np.int64)
            return
        rights = rights + _EPS_S
        edges = np.unique(np.concatenate([lefts, rights]))
        lo = np.searchsorted(edges, lefts)
        hi = np.searchsorted(edges, rights)
        segs = edges.size - 1
        big = np.iinfo(np.int64).max
        levels = max(1, int(np.floor(np.log2(max(segs, 1)))) + 1)
        table = np.full((levels, segs), big, dtype=np.int64)
        length = hi - lo
        ok = length > 0
        lo, hi, length, ranks = lo[ok], hi[ok], length[ok], ranks[ok]
        k = np.floor(np.log2(length)).astype(np.int64)
        np.minimum.at(table, (k, lo), ranks)
        np.minimum.at(table, (k, hi - (np.int64(1) << k)), ranks)
        for level in range(levels - 1, 0, -1):
            half = 1 << (level - 1)
            span = segs - (1 << level) + 1  # blocks [x, x + 2^level) inside the segments
            if span <= 0:
                continue
            row = table[level, :span]
            np.minimum(table[level - 1, :span], row, out=table[level - 1, :span])
            np.minimum(table[level - 1, half : half + span], row,
                       out=table[level - 1, half : half + span])  # fmt: skip
        self.edges = edges
        self.best = np.where(table[0] == big, -1, table[0])

    @staticmethod
    def _intervals(cells: _Cells, t_lo, t_hi, deadline):
        rel = cells.rel
        s = np.sign(rel)
        rho = np.abs(rel)
        phi0 = cells.phase0  # with T_min: shifted, and the fixed part for the thrust time
        sigma = s * cells.gap_rate
        pa, pb = phi0 + sigma * t_lo, phi0 + sigma * t_hi
        m_lo = np.floor(np.minimum(pa, pb) / TWO_PI)
        m_hi = np.floor(np.maximum(pa, pb) / TWO_PI)
        moving = rel != 0.0
        kappa = sigma + rho
        lefts, rights, ranks = [], [], []
        pieces = int(np.max(m_hi - m_lo, initial=0)) + 1 if moving.any() else 0
        index = np.arange(cells.size)
        for p in range(pieces):
            m = m_lo + p
            valid = moving & (m <= m_hi)
            with np.errstate(divide="ignore", invalid="ignore"):
                ta = (TWO_PI * m - phi0) / sigma
                tb = (TWO_PI * (m + 1) - phi0) / sigma
                rhs = rho * (deadline - cells.fixed) - phi0 + TWO_PI * m
                cut = rhs / kappa
            left = np.where(sigma > 0, ta, np.where(sigma < 0, tb, -np.inf))
            right = np.where(sigma > 0, tb, np.where(sigma < 0, ta, np.inf))
            left = np.maximum(np.maximum(left, t_lo), np.where(kappa < 0, cut, -np.inf))
            right = np.minimum(np.minimum(right, t_hi), np.where(kappa > 0, cut, np.inf))
            valid &= ~((kappa == 0) & (rhs < 0)) & (left <= right)
            lefts.append(left[valid])
            rights.append(right[valid])
            ranks.append(index[valid])
        # equal rates: a leg only where the gap is closed; a whole interval when it stays so
        # (and only if the thrust time reaches T_min: no laps to add)
        still = ~moving & (cells.gap_rate == 0.0) & (cells.thr >= cells.t_min)
        if still.any():
            coast = coast_time(cells.gap0, cells.rate_d[still], cells.rate_j, cells.thr[still],
                               cells.draan[still])  # fmt: skip
            right = np.minimum(t_hi, deadline - cells.thr[still])
            valid = np.isfinite(coast) & (right >= t_lo)
            lefts.append(np.full(int(valid.sum()), float(t_lo)))
            rights.append(right[valid])
            ranks.append(index[still][valid])
        if not lefts:
            return np.zeros(0), np.zeros(0), np.zeros(0, dtype=np.int64)
        return (np.concatenate(lefts), np.concatenate(rights),
                np.concatenate(ranks).astype(np.int64))  # fmt: skip

    def lookup(self, t):
        """Cheapest cost [m/s] (inf: none) and orbit index (-1) from departures ``t`` [s]."""
        t = np.asarray(t, dtype=float)
        if self.best.size == 0:
            return np.full(t.shape, np.inf), np.full(t.shape, -1)
        seg = np.searchsorted(self.edges, t, side="right") - 1
        inside = (seg >= 0) & (seg < self.best.size)
        idx = np.where(inside, self.best[np.clip(seg, 0, self.best.size - 1)], -1)
        return np.where(idx >= 0, self.cells.dv[np.maximum(idx, 0)], np.inf), idx

    def exact(self, t: float):
        """Cheapest cost and orbit index from departure ``t`` [s], computed directly."""
        cols = np.arange(self.cells.size)
        arrive, _ = self.cells.first_arrival(t, cols)
        fits = np.flatnonzero(arrive <= self.deadline + TOL_S)
        if fits.size == 0:
            return np.inf, -1
        k = int(fits[np.argmin(self.cells.dv[fits])])
        return float(self.cells.dv[k]), k


class _Lasts:
    """Several last-leg step functions read as one (their minimum)."""

    def __init__(self, parts: list[_LastLeg]):
        self.parts = parts

    def lookup(self, t):
        best = np.full(np.shape(t), np.inf)
        which = np.full(np.shape(t), -1)
        part = np.full(np.shape(t), -1)
        for p, last in enumerate(self.parts):
            cost, idx = last.lookup(t)
            better = cost < best
            best = np.where(better, cost, best)
            which = np.where(better, idx, which)
            part = np.where(better, p, part)
        return best, which, part


@dataclass
class _Candidate:
    cost: float
    path: tuple[int, ...]
    a: tuple[float, ...]
    inc: tuple[float, ...]
    laps: tuple[int, ...]


class _Problem:
    """One mission's brute force (see the module docstring)."""

    def __init__(self, a_m, e, inc_rad, raan_rad, *, n, tmax_days, accel_mps2, rule, a_low,
                 a_high, deorbit_days, radii, coarse_every, zoom_points, zoom_levels,
                 margin, min_transfer_days=0.0):  # fmt: skip
        self.a, self.e, self.inc, self.raan = (
            np.asarray(x, dtype=float).ravel() for x in (a_m, e, inc_rad, raan_rad)
        )
        if not (self.a.size == self.e.size == self.inc.size == self.raan.size):
            raise ValueError("a_m, e, inc_rad and raan_rad must have the same length")
        if rule not in RULES:
            raise ValueError(f"rule must be one of {RULES}, not {rule!r}")
        if n < 2 or n > self.a.size:
            raise ValueError(f"n must be in [2, {self.a.size}], not {n}")
        self.rate = raan_rate(self.a, self.inc, self.e)
        self.n, self.rule, self.accel = int(n), rule, float(accel_mps2)
        self.a_low, self.a_high = float(a_low), float(a_high)
        self.tmax = float(tmax_days) * DAY
        self.deorbit_days = float(deorbit_days)
        self.dd = self.deorbit_days * DAY
        self.min_transfer_days = float(min_transfer_days)
        self.t_min = self.min_transfer_days * DAY  # every leg's duration at least
        self.deadline = self.tmax - self.dd  # last arrival
        self.budget = self.tmax - self.n * self.dd  # sum of the legs' durations
        self.radii = int(radii)
        self.grid = np.linspace(self.a_low, self.a_high, self.radii)
        self.step = (self.a_high - self.a_low) / (self.radii - 1)
        self.coarse_grid = self.grid[::coarse_every]
        self.zoom_points, self.zoom_levels, self.margin = zoom_points, zoom_levels, margin
        self.delta = self.budget / _BINS if self.budget > 0 else 1.0
        j = np.arange(_BINS + 1)
        self._diff = j[:, None] - j[None, :]
        self._mask = self._diff >= 0
        self._diff = np.where(self._mask, self._diff, 0)
        self._fine, self._coarse, self._lasts, self._curves, self._suffix = {}, {}, {}, {}, {}
        self.stats = {"paths_evaluated": 0, "states": 0, "products": 0, "zooms": 0}

    # -- grids ------------------------------------------------------------------------
    def kinks(self, i, j, lo=-np.inf, hi=np.inf):
        k = np.array([self.a[i], self.a[j], self.a_low, self.a_high])
        return k[(k >= max(lo, self.a_low)) & (k <= min(hi, self.a_high))]

    def cells(self, i, j, radii, incs=None):
        incs = (self.inc[i], self.inc[j]) if incs is None else incs
        return _Cells(self, i, j, np.unique(np.concatenate([radii, self.kinks(i, j)])), incs)

    def fine(self, pair):
        if pair not in self._fine:
            self._fine[pair] = self.cells(*pair, self.grid)
        return self._fine[pair]

    def coarse(self, pair):
        if pair not in self._coarse:
            self._coarse[pair] = self.cells(*pair, self.coarse_grid)
        return self._coarse[pair]

    def last(self, pair):
        if pair not in self._lasts:
            self._lasts[pair] = _LastLeg(self.fine(pair), self.dd, self.deadline, self.deadline)
        return self._lasts[pair]

    # -- lower bounds -------------------------------------------------------------------
    def curve(self, pair):
        """Cheapest grid cost of the leg [m/s] against its duration budget bin."""
        if pair not in self._curves:
            c = self.fine(pair)
            dmin = c.min_duration(self.dd, self.deadline)
            bins = np.floor(dmin / self.delta)
            ok = np.isfinite(bins) & (bins <= _BINS)
            raw = np.full(_BINS + 1, np.inf)
            np.minimum.at(raw, bins[ok].astype(np.int64), c.dv[ok])
            self._curves[pair] = np.minimum.accumulate(raw)
        return self._curves[pair]

    def suffix(self, pairs: tuple):
        """Min-plus convolution of the curves of ``pairs``: bound of those legs' cost
        against the sum of their durations' budget bin."""
        if pairs not in self._suffix:
            if len(pairs) == 1:
                self._suffix[pairs] = self.curve(pairs[0])
            else:
                head, rest = self.curve(pairs[0]), self.suffix(pairs[1:])
                table = np.where(self._mask, head[None, :] + rest[self._diff], np.inf)
                self._suffix[pairs] = table.min(axis=1)
        return self._suffix[pairs]

    def bound_at(self, curve, budget):
        """``curve`` read at the remaining duration budget(s) [s] (inf when negative)."""
        budget = np.asarray(budget, dtype=float)
        k = np.clip(np.floor(budget / self.delta), 0, _BINS).astype(np.int64)
        return np.where(budget >= 0.0, curve[k], np.inf)

    # -- one path -------------------------------------------------------------------------
    def evaluate(self, path, middles, lasts: _Lasts, threshold=np.inf, bounds=True):
        """Best plan of ``path`` per inclination combination with cost < ``threshold``.

        ``middles``: the middle legs' orbits; ``lasts``: the last leg's step functions.
        Returns a list of :class:`_Candidate` (replayed, cost < threshold).
        """
        pairs = list(itertools.pairwise(path))
        t = np.array([self.dd])
        c = np.zeros(1)
        history = []
        for k, cells in enumerate(middles):
            rest = tuple(pairs[k + 1 :])
            legs_left = len(rest)
            curve = self.suffix(rest) if bounds else np.zeros(_BINS + 1)
            floor = float(curve[-1])
            allow = np.searchsorted(cells.dv, threshold - floor - c, side="left")
            new_t, new_c, parent, col, lap = [], [], [], [], []
            cum = np.cumsum(allow)
            start = 0
            while start < t.size:
                done = int(cum[start - 1]) if start else 0
                stop = max(int(np.searchsorted(cum, done + _CHUNK, side="right")), start + 1)
                block = np.arange(start, stop)
                counts = allow[block]
                total = int(counts.sum())
                start = stop
                if total == 0:
                    continue
                rows = np.repeat(block, counts)
                offsets = np.repeat(np.cumsum(counts) - counts, counts)
                cols = np.arange(total) - offsets
                self.stats["products"] += total
                base, first = cells.first_arrival(t[rows], cols)  # the fewest laps for T_min
                cost = c[rows] + cells.dv[cols]
                q = 0
                while rows.size:
                    arrive = base + q * cells.period[cols] if q else base
                    depart = arrive + self.dd
                    lb = cost + self.bound_at(curve, self.tmax - depart - legs_left * self.dd)
                    fits = np.isfinite(lb) & (lb < threshold)
                    new_t.append(depart[fits])
                    new_c.append(cost[fits])
                    parent.append(rows[fits])
                    col.append(cols[fits])
                    lap.append(first[fits] + q)
                    room = self.tmax - legs_left * (self.dd + self.t_min)
                    later = depart + cells.period[cols] <= room
                    rows, cols, base, cost = rows[later], cols[later], base[later], cost[later]
                    first = first[later]
                    q += 1
            if not new_t:
                return []
            t, c = np.concatenate(new_t), np.concatenate(new_c)
            history.append((np.concatenate(parent), np.concatenate(col), np.concatenate(lap)))
            self.stats["states"] += t.size
            if t.size == 0:
                return []
        last_cost, last_idx, last_part = lasts.lookup(t)
        total = c + last_cost
        alive = np.flatnonzero(total < threshold)
        if alive.size == 0:
            return []
        # inclination combination of every live state
        combo = np.zeros(alive.size, dtype=np.int64)
        s = alive.copy()
        for k in range(len(middles) - 1, -1, -1):
            parent, col, _ = history[k]
            combo |= middles[k].upper[col[s]].astype(np.int64) << k
            s = parent[s]
        upper = np.zeros(alive.size, dtype=bool)
        for p, part in enumerate(lasts.parts):
            mine = last_part[alive] == p
            upper[mine] = part.cells.upper[last_idx[alive][mine]]
        combo |= upper.astype(np.int64) << len(middles)
        out = []
        for code in np.unique(combo):
            members = alive[combo == code]
            out_one = self._settle(path, middles, lasts, history, members, total, t, c)
            if out_one is not None and out_one.cost < threshold:
                out.append(out_one)
        return out

    def _settle(self, path, middles, lasts, history, members, total, t, c):
        """The cheapest of ``members`` whose replay agrees (recomputing the last leg
        directly where the step function's reading does not fly)."""
        total = total.copy()
        for _ in range(50):
            k = int(members[np.argmin(total[members])])
            if not np.isfinite(total[k]):
                return None
            _, idx, part = lasts.lookup(t[k : k + 1])
            last = lasts.parts[int(part[0])]
            cand = self._rebuild(path, middles, history, k, last.cells, int(idx[0]), total[k],
                                 t[k])  # fmt: skip
            plan = self.replay(cand)
            if plan is not None and abs(plan.cost_mps - cand.cost) <= 1e-6 * max(1, cand.cost):
                return cand
            exact = [one.exact(float(t[k])) for one in lasts.parts]
            p = int(np.argmin([x[0] for x in exact]))
            total[k] = c[k] + exact[p][0]
            if np.isfinite(total[k]):
                cand = self._rebuild(path, middles, history, k, lasts.parts[p].cells,
                                     exact[p][1], total[k], t[k])  # fmt: skip
                plan = self.replay(cand)
                if plan is not None:
                    return cand
                total[k] = np.inf
        return None

    def _rebuild(self, path, middles, history, k, last_cells, last_idx, cost, depart):
        _, last_laps = last_cells.first_arrival([depart], [last_idx])  # the fewest for T_min
        a, inc = [float(last_cells.a[last_idx])], [float(last_cells.inc[last_idx])]
        laps = [int(last_laps[0])]
        s = k
        for m in range(len(middles) - 1, -1, -1):
            parent, col, lap = history[m]
            a.append(float(middles[m].a[col[s]]))
            inc.append(float(middles[m].inc[col[s]]))
            laps.append(int(lap[s]))
            s = parent[s]
        return _Candidate(float(cost), tuple(path), tuple(a[::-1]), tuple(inc[::-1]),
                          tuple(laps[::-1]))  # fmt: skip

    def replay(self, cand: _Candidate) -> Plan | None:
        """The candidate flown; None when it ends after T_max or a leg is short of T_min
        (to rounding: the dates of the search and of the replay may differ by ulps)."""
        try:
            plan = replay(self.a, self.e, self.inc, self.raan, cand.path, cand.a, cand.inc,
                          cand.laps, accel_mps2=self.accel, rule=self.rule, a_low=self.a_low,
                          a_high=self.a_high, deorbit_days=self.deorbit_days,
                          min_transfer_days=self.min_transfer_days)  # fmt: skip
        except ShortLeg:
            return None
        return plan if plan.end_day * DAY <= self.tmax + TOL_S else None

    # -- the mission -----------------------------------------------------------------------
    def paths_by_bound(self):
        """Paths as a heap of (bound, strong?, path), every leg's curve with all the budget."""
        n_all = self.a.size
        pairs = list(itertools.permutations(range(n_all), 2))
        floor = {p: float(self.curve(p)[-1]) for p in pairs}
        heap = []
        for path in itertools.permutations(range(n_all), self.n):
            bound = sum(floor[p] for p in itertools.pairwise(path))
            if np.isfinite(bound):
                heap.append((bound, 0, path))
        heapq.heapify(heap)
        return heap

    def strong_bound(self, path):
        return float(self.suffix(tuple(itertools.pairwise(path)))[-1])

    def search(self, middles_of, threshold_of, *, limit=None, record=None):
        """Best-first over paths; ``middles_of(pair)`` gives a middle leg's orbits.

        ``threshold_of(best)`` is the pruning threshold for the best cost so far.
        Returns the best cost; appends every candidate under the threshold to ``record``.
        """
        best = self.best_cost
        heap = self.paths_by_bound()
        done = 0
        while heap:
            bound, strong, path = heapq.heappop(heap)
            if bound >= threshold_of(best):
                break
            if not strong:
                bound = self.strong_bound(path)
                if np.isfinite(bound):
                    heapq.heappush(heap, (bound, 1, path))
                continue
            pairs = list(itertools.pairwise(path))
            middles = [middles_of(p) for p in pairs[:-1]]
            lasts = _Lasts([self.last(pairs[-1])])
            found = self.evaluate(path, middles, lasts, threshold_of(best))
            self.stats["paths_evaluated"] += 1
            done += 1
            for cand in found:
                best = min(best, cand.cost)
                if record is not None:
                    record.append(cand)
            if limit is not None and done >= limit:
                break
        self.best_cost = best
        return best

    def zoom(self, cand: _Candidate) -> _Candidate:
        """Refine a candidate by zooming every leg's radius grid around it.

        Windows of +/- 2 steps: ``zoom_points`` radii for the first middle legs, 10x as
        many for the last middle leg and 50x for the last leg (one leg of a pair fine is
        enough to follow a diagonal valley of the feasible set), re-centred up to 8 times
        a level while the best moves by more than a quarter of a window.
        """
        pairs = list(itertools.pairwise(cand.path))
        counts = [self.zoom_points] * (len(pairs) - 2) + [10 * self.zoom_points - 9] * (
            len(pairs) > 1
        )
        counts.append(50 * self.zoom_points - 49)
        half = 2.0 * self.step
        best = cand
        for _ in range(self.zoom_levels):
            for _walk in range(9):
                windows = []
                for (i, j), a, count in zip(pairs, best.a, counts, strict=True):
                    lo, hi = max(self.a_low, a - half), min(self.a_high, a + half)
                    radii = np.concatenate([np.linspace(lo, hi, count), [a],
                                            self.kinks(i, j, lo, hi)])  # fmt: skip
                    windows.append(np.unique(radii))
                middles = [self.cells(i, j, w) for (i, j), w in zip(pairs[:-1], windows,
                                                                     strict=False)]  # fmt: skip
                window_last = _LastLeg(self.cells(*pairs[-1], windows[-1]), self.dd,
                                       self.deadline, self.deadline)  # fmt: skip
                lasts = _Lasts([self.last(pairs[-1]), window_last])
                self.stats["zooms"] += 1
                found = self.evaluate(cand.path, middles, lasts, np.inf, bounds=False)
                if not found:
                    break
                new = min(found, key=lambda x: x.cost)
                if new.cost > best.cost - 1e-9:
                    break
                moved = max(abs(x - y) for x, y in zip(new.a, best.a, strict=True))
                best = new
                if moved < 0.25 * half:
                    break
            half = 2.0 * (2.0 * half) / (self.zoom_points - 1)
        return best

    def solve(self) -> Plan | None:
        started = time.perf_counter()
        self.best_cost = np.inf
        if self.budget < (self.n - 1) * self.t_min:
            return None
        # quick pass (every coarse_every-th radius on the middle legs) for a first threshold
        self.search(self.coarse, lambda best: best, limit=30)
        quick = self.best_cost
        record: list[_Candidate] = []
        self.best_cost = np.inf
        first = quick * (1.0 + self.margin)

        def threshold(best):
            return min(first, best * (1.0 + self.margin)) * (1.0 + 1e-12)

        grid_best = self.search(self.fine, threshold, record=record)
        if not np.isfinite(grid_best):
            return None
        self.stats["grid_cost_mps"] = grid_best
        self.stats["search_s"] = time.perf_counter() - started
        keep = [r for r in record if r.cost <= grid_best * (1.0 + self.margin)]
        self.stats["candidates"] = len(keep)
        refined = [self.zoom(r) for r in keep]
        best = min(refined, key=lambda x: x.cost)
        plan = self.replay(best)
        assert plan is not None and abs(plan.cost_mps - best.cost) <= 1e-6 * best.cost, best
        self.stats["seconds"] = time.perf_counter() - started
        return Plan(**{**plan.__dict__, "info": dict(self.stats)})


def optimum(a_m, e, inc_rad, raan_rad, *, n, tmax_days, accel_mps2, rule, a_low=A_LOW,
            a_high=A_HIGH, deorbit_days=0.0, min_transfer_days=0.0, radii=2049,
            coarse_every=32, zoom_points=41, zoom_levels=3,
            margin=2e-3) -> Plan | None:  # fmt: skip
    """Cheapest mission of ``n`` debris by brute force (see the module docstring).

    Parameters
    ----------
    a_m, e, inc_rad, raan_rad : array_like
        Catalog: semi-major axes [m], eccentricities [-], inclinations [rad], RAANs at
        t = 0 [rad].
    n : int
        Debris visited (>= 2).
    tmax_days : float
        Mission duration limit T_max [days].
    accel_mps2 : float
        Constant thrust acceleration [m/s^2].
    rule : {"free", "table3"}
        Drift inclination rule.
    a_low, a_high : float
        Drift radius band [m] (inclusive).
    deorbit_days : float
        Operations time at each debris [days].
    min_transfer_days : float
        T_min [days]: every leg (departure to arrival) lasts at least this, by whole
        relative laps of its coast where needed.
    radii : int
        Radii spanning the band for every leg's grid (plus the debris radii).
    coarse_every : int
        Middle legs of the quick first pass use every ``coarse_every``-th radius.
    zoom_points, zoom_levels : int
        Refinement: radii per window (+/- 2 steps) and levels (each 10x finer at 41).
    margin : float
        Relative margin: every (path, inclinations) grid optimum within it of the grid
        optimum is refined.

    Returns
    -------
    Plan or None
        The replayed cheapest plan (``info``: search statistics and timings), or None when
        no plan of the grid ends by T_max.
    """
    prob = _Problem(a_m, e, inc_rad, raan_rad, n=n, tmax_days=tmax_days,
                    accel_mps2=accel_mps2, rule=rule, a_low=a_low, a_high=a_high,
                    deorbit_days=deorbit_days, radii=radii, coarse_every=coarse_every,
                    zoom_points=zoom_points, zoom_levels=zoom_levels, margin=margin,
                    min_transfer_days=min_transfer_days)  # fmt: skip
    return prob.solve()


# ---------------------------------------------------------------------------------------
# Synthetic catalogs
# ---------------------------------------------------------------------------------------


class SyntheticCatalog(NamedTuple):
    """Debris elements: semi-major axes [m], eccentricities [-], inclinations [rad], RAANs
    at t = 0 [rad] and ids."""

    a_m: np.ndarray
    e: np.ndarray
    inc_rad: np.ndarray
    raan_rad: np.ndarray
    ids: tuple[str, ...]


CLUSTERS_DEG = (71.0, 74.0, 81.0, 83.0)
"""Inclinations [deg] of the non-SSO clusters (the rocket-body families of LEO)."""


def random_catalog(seed, N, *, kind="mixed", alt_km=(600.0, 1000.0), raan_span_deg=40.0,
                   ecc_max=0.005) -> SyntheticCatalog:  # fmt: skip
    """A small synthetic LEO debris catalog.

    Parameters
    ----------
    seed : int
        Seed of ``numpy.random.default_rng``.
    N : int
        Number of debris.
    kind : {"sso", "cluster", "mixed"}
        ``sso``: inclinations uniform in 97-100 deg.  ``cluster``: one cluster, a centre of
        :data:`CLUSTERS_DEG` +/- 1 deg.  ``mixed``: about three quarters SSO-like, the rest
        in one or two clusters (cross-family legs are then very expensive).
    alt_km : (float, float)
        Altitude range above ``R_EARTH`` [km], uniform.
    raan_span_deg : float
        RAANs uniform over a window of this width [deg] at a random start, so that the
        gaps are closable in about a year at 1e-4 m/s^2 while the rates differ.
    ecc_max : float
        Eccentricities uniform in [0, ecc_max].

    Returns
    -------
    SyntheticCatalog
        ``(a_m, e, inc_rad, raan_rad, ids)``.
    """
    rng = np.random.default_rng(seed)
    alt = rng.uniform(alt_km[0], alt_km[1], N) * 1e3
    if kind == "sso":
        inc = rng.uniform(97.0, 100.0, N)
    elif kind == "cluster":
        inc = rng.choice(CLUSTERS_DEG) + rng.uniform(-1.0, 1.0, N)
    elif kind == "mixed":
        centres = rng.choice(CLUSTERS_DEG, size=2, replace=False)
        family = rng.choice(3, size=N, p=(0.75, 0.15, 0.10))
        inc = np.where(family == 0, rng.uniform(97.0, 100.0, N),
                       centres[np.maximum(family - 1, 0)] + rng.uniform(-1.0, 1.0, N))  # fmt: skip
    else:
        raise ValueError(f"kind must be 'sso', 'cluster' or 'mixed', not {kind!r}")
    raan = rng.uniform(0.0, 360.0) + rng.uniform(0.0, raan_span_deg, N)
    e = rng.uniform(0.0, ecc_max, N)
    ids = tuple(f"D{seed % 1000:03d}-{k:02d}" for k in range(N))
    return SyntheticCatalog(R_EARTH + alt, e, np.radians(inc), np.radians(raan % 360.0), ids)
