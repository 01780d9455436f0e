"""The low-thrust drift leg: spiral, plane change, coast, spiral (pure vectorised numpy).

A low-thrust vehicle of constant thrust acceleration f cannot place an impulse at a
node; it reaches the drift orbit by a slow tangential spiral and changes plane by
out-of-plane thrust around the orbit.  The leg from debris i (a_i, I_i) to debris j
(a_j, I_j), departing at date t, with a circular drift orbit of radius a_d and
inclination I_d in {I_i, I_j}, is flown in four phases (McGrath & Macdonald [2]_'s
three-phase manoeuvre, with Edelbaum's [3]_ plane change):

1. spiral A, tangential thrust, a_i -> a_d at I_i:
   ``dV_A = |V(a_i) - V(a_d)|``, ``t_A = dV_A / f``,
   ``dOmega_A = -(3 J2 R^2 cos I_i) / (16 mu^3 f) |V(a_d)^8 - V(a_i)^8|``;
2. plane change |I_j - I_i| at a_d, the out-of-plane thrust switched at the antinodes
   (``di/dt = (2 / pi) f / V``: i is linear in time and the thrust turns no RAAN):
   ``dV_B = (pi / 2) V(a_d) |I_j - I_i|``, ``t_B = dV_B / f``,
   ``dOmega_B = -(3/2) J2 R^2 sqrt(mu) a_d^(-7/2) t_B (sin I_j - sin I_i) / (I_j - I_i)``;
   flown right after spiral A when I_d = I_j, right before spiral D when I_d = I_i
   (the RAAN it turns is the same either way);
3. coast on (a_d, I_d) for t_C >= 0: ``dOmega_C = Omega_dot(a_d, I_d) t_C``;
4. spiral D, tangential, a_d -> a_j at I_j, as spiral A.

``V(a) = sqrt(mu / a)``.  The leg costs ``dV_A + dV_B + dV_D`` (it does not depend on
the drift inclination) and lasts ``T = t_A + t_B + t_C + t_D``; the RAAN closes at
arrival: ``Omega_i(t) + dOmega_A + dOmega_B + dOmega_C + dOmega_D = Omega_j(t + T)``
(mod 2 pi).  The coast is the smallest ``t_C >= 0`` that closes it, or that plus whole
relative laps ``2 pi / |Omega_dot(a_d, I_d) - Omega_dot_j|``.

The spiral's RAAN change is the J2 rate (Eq. 7, circular) integrated along the spiral:
with tangential thrust on a quasi-circular orbit ``dV/dt = -f`` (raising) or ``+f``, and
``Omega_dot = -(3/2) J2 R^2 cos I V^7 / mu^3``, so ``dOmega = int Omega_dot dV / f``.

Written in the circular speed ``w = V(a_d)``, on each piece of the drift band between
the two debris' speeds the cost is linear in w (``dV = c0 + c1 w``), the thrust time is
``dV / f``, the RAAN the thrust turns is ``p0 + p1 w^8`` and the coast rate is ``q w^7``:
:mod:`~sdc_cvx.physics.low_thrust_bounds` builds the exact costs and the certified
bounds on that.

Units: SI (m, s, rad, m/s, m/s^2).

References
----------
.. [1] M. Cerf, "Multiple Space Debris Collecting Mission — Debris Selection and Trajectory
   Optimization", Journal of Optimization Theory and Applications 156(3), 761–796, 2013
   (Part III-E and the conclusion: non-impulsive manoeuvres).
.. [2] C. N. McGrath and M. Macdonald, "General Perturbation Method for Satellite
   Constellation Reconfiguration Using Low-Thrust Maneuvers", Journal of Guidance,
   Control, and Dynamics 42(8), 1676–1692, 2019.
.. [3] T. N. Edelbaum, "Propulsion Requirements for Controllable Satellites", ARS Journal
   31(8), 1079–1089, 1961.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import ClassVar, NamedTuple

import numpy as np

from . import low_thrust_bounds
from .orbits import J2, MU_EARTH, R_EARTH, SECONDS_PER_DAY, circular_speed, raan_rate
from .transfer import NodeOrbits, TransferChoice, drift_duration, raan_gap

PREOPT_GRID = 257
"""Drift radii per edge scanned by :func:`cheapest_transfer` (then zoomed around the best)."""
WINDOW_GRID = 257
"""Drift radii per edge scanned by :func:`duration_window`."""


def spiral_dv(a_from, a_to, *, mu=MU_EARTH):
    """ΔV [m/s] of a tangential spiral between circular radii [m]: ``|V_from - V_to|``."""
    return np.abs(circular_speed(a_from, mu=mu) - circular_speed(a_to, mu=mu))


def spiral_raan_change(a_from, a_to, inc, accel, *, j2=J2, mu=MU_EARTH, r_eq=R_EARTH):
    """RAAN [rad] that J2 turns during a tangential spiral ``a_from -> a_to`` at ``inc``.

    ``-(3 J2 R^2 cos I) / (16 mu^3 f) |V(a_to)^8 - V(a_from)^8|`` (the module docstring's
    derivation), for a constant acceleration ``accel`` [m/s^2].
    """
    v8 = np.abs(circular_speed(a_to, mu=mu) ** 8 - circular_speed(a_from, mu=mu) ** 8)
    return -3.0 * j2 * r_eq**2 * np.cos(inc) / (16.0 * mu**3 * accel) * v8


def plane_change_dv(a, inc_from, inc_to, *, mu=MU_EARTH):
    """ΔV [m/s] of Edelbaum's low-thrust plane change at radius ``a``: ``(pi/2) V |dI|``."""
    return 0.5 * np.pi * circular_speed(a, mu=mu) * np.abs(np.asarray(inc_to) - inc_from)


def mean_cosine(inc_from, inc_to):
    """Mean of ``cos i`` while i goes linearly from ``inc_from`` to ``inc_to`` [rad].

    ``(sin I_j - sin I_i) / (I_j - I_i)``, and ``cos I_i`` when the two are equal.
    """
    inc_from, inc_to = np.asarray(inc_from, dtype=float), np.asarray(inc_to, dtype=float)
    delta = inc_to - inc_from
    with np.errstate(divide="ignore", invalid="ignore"):
        secant = (np.sin(inc_to) - np.sin(inc_from)) / delta
    return np.where(np.abs(delta) > 1e-9, secant, np.cos(0.5 * (inc_from + inc_to)))


def plane_change_raan_change(a, inc_from, inc_to, accel, *, j2=J2, mu=MU_EARTH, r_eq=R_EARTH):
    """RAAN [rad] that J2 turns during the plane change at radius ``a`` (phase 2).

    ``-(3/2) J2 R^2 sqrt(mu) a^(-7/2) t_B (sin I_j - sin I_i) / (I_j - I_i)``, with
    ``t_B = dV_B / f``: the J2 rate averaged over the linear change of inclination.
    """
    t_b = plane_change_dv(a, inc_from, inc_to, mu=mu) / accel
    return raan_rate(a, 0.0, 0.0, j2=j2, mu=mu, r_eq=r_eq) * t_b * mean_cosine(inc_from, inc_to)


class LowThrustPhases(NamedTuple):
    """The thrust phases of low-thrust legs (arrays broadcast over the inputs).

    Attributes
    ----------
    dv_spiral_out, dv_plane, dv_spiral_in : ndarray
        ΔV of spiral A (to the drift orbit), of the plane change and of spiral D [m/s].
    raan_thrust : ndarray
        RAAN that J2 turns during the three thrust phases [rad].
    accel : float
        Thrust acceleration [m/s^2].
    """

    dv_spiral_out: np.ndarray
    dv_plane: np.ndarray
    dv_spiral_in: np.ndarray
    raan_thrust: np.ndarray
    accel: float

    @property
    def dv(self):
        """Leg ΔV [m/s]."""
        return self.dv_spiral_out + self.dv_plane + self.dv_spiral_in

    @property
    def thrust_seconds(self):
        """Time under thrust [s]: ``dV / f``."""
        return self.dv / self.accel


def leg_phases(origin_a, origin_inc, target_a, target_inc, a_drift, accel, *, j2=J2,
               mu=MU_EARTH, r_eq=R_EARTH) -> LowThrustPhases:  # fmt: skip
    """ΔV and RAAN change of the thrust phases of legs i -> (a_d) -> j.

    Parameters
    ----------
    origin_a, origin_inc, target_a, target_inc : array_like
        Radii [m] and inclinations [rad] of the two debris.
    a_drift : array_like
        Drift radius [m].
    accel : float
        Thrust acceleration f [m/s^2], > 0.

    Returns
    -------
    LowThrustPhases
    """
    constants = {"j2": j2, "mu": mu, "r_eq": r_eq}
    raan = (spiral_raan_change(origin_a, a_drift, origin_inc, accel, **constants)
            + plane_change_raan_change(a_drift, origin_inc, target_inc, accel, **constants)
            + spiral_raan_change(a_drift, target_a, target_inc, accel, **constants))  # fmt: skip
    return LowThrustPhases(spiral_dv(origin_a, a_drift, mu=mu),
                           plane_change_dv(a_drift, origin_inc, target_inc, mu=mu),
                           spiral_dv(a_drift, target_a, mu=mu), raan, float(accel))  # fmt: skip


def leg_dv(origin_a, origin_inc, target_a, target_inc, a_drift, *, mu=MU_EARTH):
    """ΔV [m/s] of the low-thrust leg: spiral, plane change, spiral (independent of f and I_d)."""
    return (spiral_dv(origin_a, a_drift, mu=mu)
            + plane_change_dv(a_drift, origin_inc, target_inc, mu=mu)
            + spiral_dv(a_drift, target_a, mu=mu))  # fmt: skip


def closure_gap(origin: NodeOrbits, target: NodeOrbits, a_drift, t_depart, accel, *, j2=J2,
                mu=MU_EARTH):  # fmt: skip
    """The RAAN gap [rad] the coast must close (mod 2 pi): ``G(t) + Omega_dot_j t_thrust -
    dOmega_thrust`` for the leg leaving at ``t_depart`` [s] with drift radius ``a_drift``."""
    phases = leg_phases(origin.a, origin.inc, target.a, target.inc, a_drift, accel, j2=j2, mu=mu)
    return _closure_gap(origin, target, phases, t_depart)


def _closure_gap(origin: NodeOrbits, target: NodeOrbits, phases: LowThrustPhases, t_depart):
    """:func:`closure_gap` from the legs' thrust phases, already computed."""
    return (raan_gap(origin, target, t_depart) + target.rate * phases.thrust_seconds
            - phases.raan_thrust)  # fmt: skip


def duration_window(origin: NodeOrbits, target: NodeOrbits, side, inc_drift, t_depart,
                    min_seconds, max_seconds, a_low, a_high, accel, *, j2=J2, mu=MU_EARTH,
                    points=WINDOW_GRID):  # fmt: skip
    """Drift radii [m] on ``side`` whose leg from ``t_depart`` [s] lasts between the bounds [s].

    The low-thrust counterpart of
    :func:`~sdc_cvx.physics.transfer.duration_window_interval` (for the paper's method):
    the set is not one interval here (the thrust time rises away from the debris radii,
    and the gap the coast closes moves with the radius, so the duration jumps by a lap
    where it wraps), so a grid of ``points`` radii is scanned and the run of allowed radii
    that holds the cheapest one is returned (to the grid's resolution).

    Parameters
    ----------
    origin, target : NodeOrbits
        Shape (M,) or broadcastable with ``side`` and ``inc_drift``.
    side : array_like
        +1 (the coast precesses faster than the target) or -1.
    inc_drift : array_like
        Drift inclination [rad].

    Returns
    -------
    lo, hi : ndarray
        ``nan`` where no radius of the band does it.
    """
    side, inc_drift = np.broadcast_arrays(np.asarray(side, float), np.asarray(inc_drift, float))
    shape = np.broadcast_shapes(side.shape, np.shape(origin.a), np.shape(t_depart))
    o = NodeOrbits(*(np.broadcast_to(v, shape)[..., None] for v in origin))
    t = NodeOrbits(*(np.broadcast_to(v, shape)[..., None] for v in target))
    grid = np.linspace(a_low, a_high, points)
    inc = np.broadcast_to(inc_drift, shape)[..., None]
    seconds = leg_seconds(o, t, grid, inc, np.broadcast_to(t_depart, shape)[..., None], accel,
                          j2=j2, mu=mu)  # fmt: skip
    rel = raan_rate(grid, 0.0, inc, j2=j2, mu=mu) - t.rate
    ok = ((np.sign(rel) == np.broadcast_to(side, shape)[..., None]) & (seconds >= min_seconds)
          & (seconds <= max_seconds))  # fmt: skip
    cost = np.where(ok, leg_dv(o.a, o.inc, t.a, t.inc, grid, mu=mu), np.inf)
    best = np.argmin(cost, axis=-1)
    # the run of allowed grid points around the cheapest: its ends by run labels
    run = np.cumsum(~ok, axis=-1)  # constant along a run of allowed points
    mine = ok & (run == np.take_along_axis(run, best[..., None], axis=-1))
    index = np.arange(points)
    lo = grid[np.min(np.where(mine, index, points - 1), axis=-1)]
    hi = grid[np.max(np.where(mine, index, 0), axis=-1)]
    found = np.isfinite(np.take_along_axis(cost, best[..., None], axis=-1)[..., 0])
    return np.where(found, lo, np.nan), np.where(found, hi, np.nan)


def coast_seconds(origin: NodeOrbits, target: NodeOrbits, a_drift, inc_drift, t_depart, accel,
                  *, laps=0, j2=J2, mu=MU_EARTH,
                  phases: LowThrustPhases | None = None):  # fmt: skip
    """Coast time t_C [s] that closes the RAAN of the leg leaving at ``t_depart`` [s].

    The smallest ``t_C >= 0`` with ``(Omega_dot_d - Omega_dot_j) t_C = G(t) + Omega_dot_j
    t_thrust - dOmega_thrust (mod 2 pi)``, plus ``laps`` relative laps; ``inf`` when the
    drift orbit precesses at the target's rate and the gap is not closed.  ``phases``: the
    legs' :func:`leg_phases`, when already computed.
    """
    if phases is None:
        phases = leg_phases(origin.a, origin.inc, target.a, target.inc, a_drift, accel, j2=j2,
                            mu=mu)  # fmt: skip
    rate_drift = raan_rate(a_drift, 0.0, inc_drift, j2=j2, mu=mu)
    gap = _closure_gap(origin, target, phases, t_depart)
    smallest = drift_duration(gap, target.rate, rate_drift)
    with np.errstate(divide="ignore", invalid="ignore"):
        lap = 2.0 * np.pi / np.abs(rate_drift - target.rate)
        return smallest + np.where(np.asarray(laps) > 0, laps * lap, 0.0)


def leg_seconds(origin: NodeOrbits, target: NodeOrbits, a_drift, inc_drift, t_depart, accel, *,
                laps=0, j2=J2, mu=MU_EARTH):  # fmt: skip
    """Duration [s] of the low-thrust leg leaving at ``t_depart`` [s]: thrust plus coast."""
    phases = leg_phases(origin.a, origin.inc, target.a, target.inc, a_drift, accel, j2=j2, mu=mu)
    return phases.thrust_seconds + coast_seconds(origin, target, a_drift, inc_drift, t_depart,
                                                 accel, laps=laps, j2=j2, mu=mu,
                                                 phases=phases)  # fmt: skip


def allowed_inclination(inc_drift, origin_inc, target_inc, rate_drift, rate_target, rule):
    """Where a drift inclination is allowed by the rule, judged on the coast orbit.

    ``table3``: ``max(I_i, I_j)`` only where the coast precesses at least as fast as the
    target (signed rates), ``min(I_i, I_j)`` only where at most; equal inclinations
    everywhere.  ``free``: everywhere.
    """
    if rule == "free":
        return np.ones(np.broadcast_shapes(np.shape(inc_drift), np.shape(rate_drift)), dtype=bool)
    faster = rate_drift >= rate_target
    slower = rate_drift <= rate_target
    is_max = inc_drift >= np.maximum(origin_inc, target_inc)
    is_min = inc_drift <= np.minimum(origin_inc, target_inc)
    return (origin_inc == target_inc) | (is_max & faster) | (is_min & slower)


def cheapest_transfer(origin: NodeOrbits, target: NodeOrbits, t_depart, max_duration, a_low,
                      a_high, accel, *, inclination="table3", sides=(1.0, -1.0), j2=J2,
                      mu=MU_EARTH) -> TransferChoice:  # fmt: skip
    """Pre-optimised low-thrust leg of each edge: the cheapest whose coast lasts at most
    ``max_duration``.

    The low-thrust counterpart of :func:`~sdc_cvx.physics.transfer.cheapest_transfer`
    (Part IV-B's heuristic, for the edge table and the paper's method): drift radii on a
    grid of :data:`PREOPT_GRID` points plus the two debris radii, zoomed once around the
    best; both drift inclinations where the rule allows them; the smallest coast.  T0
    bounds the drift, as the paper's two months do (its impulsive leg is all drift): the
    spirals and the plane change come on top, so one T0 suits both models and every
    acceleration.

    Parameters
    ----------
    origin, target : NodeOrbits
        Shape (M,).
    t_depart : float or array_like
        Departure date [s].
    max_duration : float or array_like
        Bound T0 of the coast [s] (one, or one per edge).
    a_low, a_high : float
        Drift radius bounds [m].
    accel : float
        Thrust acceleration [m/s^2].
    inclination : {"table3", "free"}
    sides : tuple of {1, -1}
        Sides of the asymptote allowed (+1: the coast precesses faster than the target).

    Returns
    -------
    TransferChoice
    """
    m = len(origin.a)
    t_depart = np.broadcast_to(np.asarray(t_depart, dtype=float), (m,))[:, None]
    max_duration = np.broadcast_to(np.asarray(max_duration, dtype=float), (m,))[:, None]
    grid = np.linspace(a_low, a_high, PREOPT_GRID)
    kinks = np.clip(np.stack([origin.a, target.a], axis=1), a_low, a_high)
    points = np.concatenate([np.broadcast_to(grid, (m, PREOPT_GRID)), kinks], axis=1)
    best = _best_on(origin, target, points, t_depart, max_duration, accel, inclination, sides,
                    j2, mu)  # fmt: skip
    step = (a_high - a_low) / (PREOPT_GRID - 1)
    centre = np.where(np.isfinite(best[0]), best[0], a_low)[:, None]
    zoom = np.clip(centre + step * np.linspace(-1.0, 1.0, 65), a_low, a_high)
    fine = _best_on(origin, target, zoom, t_depart, max_duration, accel, inclination, sides, j2,
                    mu)  # fmt: skip
    better = fine[4] < best[4]
    return TransferChoice(*(np.where(better, f, b) for f, b in zip(fine, best, strict=True)))


def _best_on(origin, target, a, t_depart, max_duration, accel, rule, sides, j2, mu):
    """The cheapest of the drift radii ``a`` (M, K) whose coast fits the bound, per edge."""
    o = NodeOrbits(*(np.asarray(v)[:, None] for v in origin))
    t = NodeOrbits(*(np.asarray(v)[:, None] for v in target))
    dv = leg_dv(o.a, o.inc, t.a, t.inc, a, mu=mu)
    rows = np.arange(len(a))
    out = [np.full(len(a), np.nan), np.full(len(a), np.nan), np.zeros(len(a)),
           np.full(len(a), np.inf), np.full(len(a), np.inf)]  # fmt: skip
    for inc in (o.inc, t.inc):
        inc = np.broadcast_to(inc, a.shape)
        rate = raan_rate(a, 0.0, inc, j2=j2, mu=mu)
        side = np.where(rate >= t.rate, 1.0, -1.0)
        seconds = leg_seconds(o, t, a, inc, t_depart, accel, j2=j2, mu=mu)
        ok = (allowed_inclination(inc, o.inc, t.inc, rate, t.rate, rule)
              & np.isin(side, sides) & (seconds - dv / accel <= max_duration))  # fmt: skip
        cost = np.where(ok, dv, np.inf)
        k = np.argmin(cost, axis=1)
        better = cost[rows, k] < out[4]
        for slot, value in enumerate((a[rows, k], inc[rows, k], side[rows, k],
                                      seconds[rows, k], cost[rows, k])):  # fmt: skip
            out[slot] = np.where(better, value, out[slot])
    return tuple(out)


def edelbaum_transfer(v_from, v_to, plane_change, accel):
    """Edelbaum's combined low-thrust transfer between circular orbits (general formula).

    ``dV = sqrt(V0^2 - 2 V0 V1 cos(pi/2 dI) + V1^2)``, duration ``dV / f``.  Not used by
    the drift leg (which changes plane at constant radius, where Edelbaum's optimum is
    the ``(pi/2) V dI`` of :func:`plane_change_dv`); kept as the reference a combined
    spiral option would start from.

    Parameters
    ----------
    v_from, v_to : array_like
        Circular speeds of the two orbits [m/s].
    plane_change : array_like
        Inclination change [rad].
    accel : float
        Thrust acceleration [m/s^2].

    Returns
    -------
    dv, seconds : ndarray
        ΔV [m/s] and time under thrust [s].
    """
    v_from, v_to = np.asarray(v_from, dtype=float), np.asarray(v_to, dtype=float)
    dv = np.sqrt(v_from**2 - 2.0 * v_from * v_to * np.cos(0.5 * np.pi * np.asarray(plane_change))
                 + v_to**2)  # fmt: skip
    return dv, dv / accel


MAX_ACCEL_MPS2 = 1e-2
"""The highest thrust acceleration the model takes [m/s^2].  Its phases average the thrust
over revolutions (quasi-circular spirals, the plane change switched at the antinodes); at
1e-2 m/s^2 a vehicle gains 60 m/s a revolution at 800 km, so a phase of a few tens of m/s
lasts less than one and is an impulse, which the impulsive model plans better.  Electric
propulsion is 1e-5 to 1e-3 m/s^2; chemical thrusters 1e-2 and up."""


@dataclass(frozen=True)
class LowThrustModel:
    """The low-thrust drift leg (:mod:`~sdc_cvx.physics.low_thrust`) as a transfer model.

    Parameters
    ----------
    accel_mps2 : float
        Constant thrust acceleration f [m/s^2] (the vehicle's lowest: thrust over the
        wet mass at launch, so every duration is an upper bound).
    """

    accel_mps2: float
    name: ClassVar[str] = "low-thrust"
    bound_tol_mps: ClassVar[float] = low_thrust_bounds.BOUND_TOL_MPS
    """How far below the exact cost a box shrunk to a point may still be bounded [m/s]."""

    def __post_init__(self):
        if not (np.isfinite(self.accel_mps2) and self.accel_mps2 > 0):
            raise ValueError(f"accel_mps2 must be a positive number, got {self.accel_mps2!r}")
        if self.accel_mps2 > MAX_ACCEL_MPS2:
            raise ValueError(
                f"a thrust acceleration of {self.accel_mps2:g} m/s^2 is not low thrust: the "
                f"low-thrust model averages the thrust over revolutions and holds up to "
                f"{MAX_ACCEL_MPS2:g} m/s^2 (60 m/s a revolution at 800 km): above that, the "
                "burns are short against an orbit: use the impulsive model")  # fmt: skip

    def leg_dv(self, origin_a, origin_inc, target_a, target_inc, a_drift, inc_drift=None, *,
               mu=MU_EARTH):  # fmt: skip
        """Leg ΔV [m/s]: spiral, plane change, spiral (the drift inclination does not count)."""
        return leg_dv(origin_a, origin_inc, target_a, target_inc, a_drift, mu=mu)

    def leg_seconds(self, origin: NodeOrbits, target: NodeOrbits, a_drift, inc_drift, t_depart,
                    *, laps=0, j2, mu=MU_EARTH):  # fmt: skip
        """Leg duration [s] leaving at ``t_depart`` [s]: thrust phases and coast."""
        return leg_seconds(origin, target, a_drift, inc_drift, t_depart, self.accel_mps2,
                           laps=laps, j2=j2, mu=mu)  # fmt: skip

    def phase_days(self, origin_a, origin_inc, target_a, target_inc, a_drift, duration_days):
        """The leg's phases [days]: spiral out, plane change, coast, spiral in."""
        phases = leg_phases(origin_a, origin_inc, target_a, target_inc, a_drift,
                            self.accel_mps2)  # fmt: skip
        day = self.accel_mps2 * SECONDS_PER_DAY
        out = {"spiral_out_days": phases.dv_spiral_out / day,
               "plane_change_days": phases.dv_plane / day,
               "spiral_in_days": phases.dv_spiral_in / day}  # fmt: skip
        out["coast_days"] = np.asarray(duration_days, dtype=float) - sum(out.values())
        return out

    def cost_at(self, legs, e, t, t_arrive, *, rule: str, j2: float, t_min: float = 0.0):
        """:func:`~sdc_cvx.physics.low_thrust_bounds.cost_at` at this acceleration."""
        return low_thrust_bounds.cost_at(legs, e, t, t_arrive, accel=self.accel_mps2,
                                         rule=rule, j2=j2, t_min=t_min)  # fmt: skip

    def box_bound(self, legs, e, t1, t2, t3, t4, *, rule: str, j2: float, t_min: float = 0.0,
                  cap=np.inf, floor=-np.inf):  # fmt: skip
        """:func:`~sdc_cvx.physics.low_thrust_bounds.box_bound` at this acceleration."""
        return low_thrust_bounds.box_bound(legs, e, t1, t2, t3, t4, accel=self.accel_mps2,
                                           rule=rule, j2=j2, t_min=t_min, cap=cap,
                                           floor=floor)  # fmt: skip

    def closure_gap(self, origin, target, a_drift, t_depart, *, j2, mu=MU_EARTH):
        """:func:`closure_gap` at this acceleration."""
        return closure_gap(origin, target, a_drift, t_depart, self.accel_mps2, j2=j2, mu=mu)

    def duration_window(self, origin, target, side, inc_drift, t_depart, min_seconds,
                        max_seconds, a_low, a_high, *, j2, mu=MU_EARTH):  # fmt: skip
        """:func:`duration_window` at this acceleration."""
        return duration_window(origin, target, side, inc_drift, t_depart, min_seconds,
                               max_seconds, a_low, a_high, self.accel_mps2, j2=j2,
                               mu=mu)  # fmt: skip

    def special_dates(self, legs, e, start, stop):
        """None: thrust takes time, so no leg needs one exact date (only two debris on one
        orbit could fly a leg of zero length)."""
        return np.empty(0)

    def cheapest_transfer(self, origin, target, t_depart, max_duration, a_low, a_high, *,
                          inclination="table3", sides=(1.0, -1.0), j2, mu=MU_EARTH):  # fmt: skip
        """:func:`cheapest_transfer` at this acceleration."""
        return cheapest_transfer(origin, target, t_depart, max_duration, a_low, a_high,
                                 self.accel_mps2, inclination=inclination, sides=sides, j2=j2,
                                 mu=mu)  # fmt: skip

    def describe(self) -> dict:
        """The model's name and parameters, for ``solution.json``."""
        return {"transfer": self.name, "accel_mps2": self.accel_mps2}
