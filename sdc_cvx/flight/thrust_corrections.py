"""After a low-thrust arrival: the corrections flown as thrust arcs, not impulses.

The impulsive flight's corrections (:mod:`~sdc_cvx.flight.corrections`) are impulses at
chosen points of the orbit.  A low-thrust vehicle flies each as an arc of its acceleration
``f`` whose sign switches around the orbit (:mod:`~sdc_cvx.flight.thrust`, a
``reference`` direction ``d``):

1. the eccentricity: tangential thrust, its sign that of ``r . d`` with ``d`` the change
   wanted, ``Δe = e_debris - e``: ``de/dt = (4/pi) f / V`` along ``d`` while ``a`` stays,
   for ``pi V |Δe| / (4 f)`` (``pi/2`` times the two impulses' ``V |Δe| / 2``);
2. the plane: out-of-plane thrust, its sign that of ``r . (h x n)`` with ``n`` the
   debris' mean normal: the plane turns towards it at ``(2/pi) f / V``, for
   ``(pi/2) V θ / f`` (Edelbaum [1]_);
3. the semi-major axis: a tangential arc onto the debris' mean one (the arcs before end
   anywhere on the orbit and leave some);
4. the along-track gap: the impulsive correction's two tangential impulses, over
   :data:`PHASE_REVOLUTIONS` orbits, each flown as a tangential arc of ``|Δv| / f``.

Each is measured on mean (one-orbit averaged) states before it is flown; the first two in
arcs of at most :data:`CHUNK_S`, measured again between them (the apsides and nodes turn
under J2 meanwhile), the last two in up to :data:`PHASE_PASSES` passes.  The first and
third also serve the coast (:func:`~sdc_cvx.flight.thrust_legs.fly_leg`), with the
eccentricity and radius it wants.

References
----------
.. [1] T. N. Edelbaum, "Propulsion Requirements for Controllable Satellites", ARS Journal
   31(8), 1079–1089, 1961.
.. [2] D. A. Vallado, *Fundamentals of Astrodynamics and Applications*, 4th ed.,
   Microcosm Press, 2013, §9.3 (Gauss's variational equations).
"""

from __future__ import annotations

import numpy as np

from .corrections import (
    SMALLEST_DE,
    correct_phase,
    debris_eccentricity,
    debris_orbit,
    mean_eccentricity,
)
from .propagation import ForceModel, averaged_orbit, orbit_average
from .rates import SAMPLES
from .thrust import Thrust
from .track import Track

CHUNK_S = 3 * 3600.0
"""Longest arc [s] of an eccentricity or plane correction before it is measured again (two
orbits: the apsides and nodes of the vehicle and the debris turn by J2 meanwhile)."""
CHUNKS = 400
"""Arcs of one correction at most (400 x 3 h: 50 days, some 500 m/s at 1e-4 m/s^2)."""
PHASE_PASSES = 3
"""Passes of the along-track correction (each closes what the arcs of the last left)."""
SMALLEST_ANGLE_RAD = 1e-5
"""Plane differences below this are left alone (0.12 m/s of thrust at 800 km; the mean
normals are measured to about 1e-6 rad, so a smaller aim chatters)."""
SMALLEST_DA_M = 10.0
"""Semi-major axis differences below this [m] are left alone (0.5 m along-track an orbit)."""
PHASE_REVOLUTIONS = 15
"""Orbits over which the along-track gap is closed (three times the impulsive flight's:
its tangential arcs stay about an orbit long, and cost a third)."""


def eccentricity_change(track: Track, wanted, model: ForceModel, pole) -> np.ndarray:
    """``wanted(t)`` less the vehicle's mean eccentricity vector, in its plane (GCRF)."""
    delta = wanted(track.t) - mean_eccentricity(track, model, pole)
    return delta - np.dot(delta, track.normal) * track.normal


def thrust_eccentricity(track: Track, leg: int, ephemeris, target: int, accel: float,
                        model: ForceModel, pole, wanted=None, until=np.inf) -> list:  # fmt: skip
    """Tangential arcs that give the vehicle the debris' mean eccentricity vector, or
    ``wanted(t)`` (GCRF) where given (:func:`~sdc_cvx.flight.thrust_legs.fly_leg`: the
    coast's, which the apsides then turn onto the debris'), ending by ``until`` [s]."""
    if wanted is None:
        def wanted(t):
            return debris_eccentricity(ephemeris, target, t, model)
    done = []
    for _ in range(CHUNKS):
        delta = eccentricity_change(track, wanted, model, pole)
        size = float(np.linalg.norm(delta))
        if size < SMALLEST_DE or track.t >= until:
            break
        seconds = min(np.pi * np.linalg.norm(track.v) * size / (4.0 * accel), CHUNK_S,
                      until - track.t)  # fmt: skip
        law = Thrust(accel, "tangential", 1.0, tuple(delta / size))
        done.append(track.thrust(track.t + seconds, law, model, pole, leg, "correction"))
    return done


def thrust_plane(track: Track, leg: int, ephemeris, target: int, accel: float,
                 model: ForceModel, pole) -> list:  # fmt: skip
    """Out-of-plane arcs that turn the vehicle's mean plane onto the debris'."""
    done, last = [], np.inf
    for _ in range(CHUNKS):
        r_d, v_d = debris_orbit(ephemeris, target, track.t, model)
        theirs = orbit_average(r_d, v_d, mu=model.mu, pole=pole).normal
        mine = averaged_orbit(track.r, track.v, track.t, model, pole=pole,
                              samples=SAMPLES).normal  # fmt: skip
        angle = float(np.arccos(np.clip(np.dot(mine, theirs), -1.0, 1.0)))
        if angle < SMALLEST_ANGLE_RAD or angle > 0.9 * last:  # done, or measured noise
            break
        last = angle
        towards = theirs - np.dot(theirs, mine) * mine
        reference = np.cross(mine, towards / np.linalg.norm(towards))
        seconds = min(0.5 * np.pi * np.linalg.norm(track.v) * angle / accel, CHUNK_S)
        law = Thrust(accel, "plane", 1.0, tuple(reference))
        done.append(track.thrust(track.t + seconds, law, model, pole, leg, "correction"))
    return done


def thrust_semi_major_axis(track: Track, leg: int, ephemeris, target: int, accel: float,
                           model: ForceModel, pole, goal_m=None) -> list:  # fmt: skip
    """A tangential arc onto the debris' mean semi-major axis, or ``goal_m`` [m] where
    given (the arcs before it end anywhere on the orbit, and an arc that is not a whole
    number of orbits long leaves some ``da``: hundreds of metres, kilometres of
    along-track drift an orbit)."""
    if goal_m is None:
        r_d, v_d = debris_orbit(ephemeris, target, track.t, model)
        goal_m = orbit_average(r_d, v_d, mu=model.mu, pole=pole).a
    done = []
    for _ in range(PHASE_PASSES):
        mine = averaged_orbit(track.r, track.v, track.t, model, pole=pole, samples=SAMPLES).a
        if abs(goal_m - mine) < SMALLEST_DA_M:
            break
        dv = 0.5 * np.linalg.norm(track.v) * abs(goal_m - mine) / mine  # vis-viva
        law = Thrust(accel, "tangential", 1.0 if goal_m > mine else -1.0)
        done.append(track.thrust(track.t + dv / accel, law, model, pole, leg, "correction"))
    return done


def thrust_phase(track: Track, leg: int, ephemeris, target: int, accel: float,
                 model: ForceModel, pole) -> list:  # fmt: skip
    """The along-track gap closed by the impulsive correction's two tangential impulses,
    each flown as a tangential arc of ``|Δv| / f`` centred where the impulse would be."""
    done = []
    for _ in range(PHASE_PASSES):
        shadow = Track(track.t, track.r.copy(), track.v.copy())
        impulses = correct_phase(shadow, leg, ephemeris, target, model, pole,
                                 revolutions=PHASE_REVOLUTIONS)  # fmt: skip
        if not impulses:
            break
        for impulse in impulses:
            along = float(impulse.dv_rtn[1])
            half = 0.5 * abs(along) / accel
            track.coast(max(impulse.epoch_s - half, track.t), model, pole)
            law = Thrust(accel, "tangential", 1.0 if along > 0 else -1.0)
            done.append(track.thrust(track.t + 2.0 * half, law, model, pole, leg,
                                     "correction"))  # fmt: skip
    return done
