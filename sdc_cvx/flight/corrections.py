"""Small impulses of a low-thrust flight: its trims, its arrival onto an averaged orbit, the
along-track gap after the arrival (issue 26); and the orbit averages they measure.

- :func:`trim` / :func:`trim_epochs`: a tangential impulse that sets a coast's mean
  motion, at fractions of the coast left (:data:`TRIMS`);
- :func:`aim_at`: the velocity whose orbit averages to a semi-major axis (one-orbit
  shots: a mean element taken as an osculating one would miss by kilometres);
- :func:`correct_phase`: the along-track gap closed over a few orbits.

An impulsive leg needs none of them: its guidance (:mod:`~sdc_cvx.flight.guidance`)
re-plans from measured states and targets the arrival in the force model.  SI units.

References
----------
.. [1] D. A. Vallado, *Fundamentals of Astrodynamics and Applications*, 4th ed.,
   Microcosm Press, 2013, §6.3-6.5.
"""

from __future__ import annotations

import numpy as np

from ..physics.impulses import with_horizontal_speed
from ..physics.orbits import SECONDS_PER_DAY
from .propagation import ForceModel, averaged_orbit, propagate
from .rates import SAMPLES, mean_state, propagated_mean_state
from .result import Maneuver
from .track import Track

SMALLEST_DE = 1e-5
"""Eccentricity differences below this are left alone (0.04 m/s at 800 km)."""
SMALLEST_GAP_M = 10.0
"""Along-track gaps below this [m] are left to the proximity operations."""
TRIMS = (0.5, 0.2, 0.05, 0.01)
"""When a coast's mean motion is trimmed: at these fractions of the coast left."""
AIM_SHOTS = 3
"""One-orbit shots of a circularising impulse on the averaged orbit it aims at."""
PHASING_REVOLUTIONS = 5
"""Orbits over which the along-track gap left at the arrival is closed (8 h at 800 km)."""


def eccentricity_vector(r, v, *, mu: float) -> np.ndarray:
    """Osculating eccentricity vectors [-] of states (..., 3)."""
    r, v = np.asarray(r, dtype=float), np.asarray(v, dtype=float)
    radius = np.linalg.norm(r, axis=-1, keepdims=True)
    speed2 = np.sum(v * v, axis=-1, keepdims=True)
    radial = np.sum(r * v, axis=-1, keepdims=True)
    return ((speed2 - mu / radius) * r - radial * v) / mu


def _period(track: Track, model: ForceModel) -> float:
    return 2.0 * np.pi * np.sqrt(np.linalg.norm(track.r) ** 3 / model.mu)


def mean_eccentricity(track: Track, model: ForceModel, pole) -> np.ndarray:
    """The vehicle's mean eccentricity vector over its next orbit (GCRF)."""
    times = track.t + np.linspace(0.0, _period(track, model), SAMPLES, endpoint=False)
    arc = propagate(track.r, track.v, track.t, times[-1], model, pole=pole, t_eval=times)
    return np.mean(eccentricity_vector(arc.r, arc.v, mu=model.mu), axis=0)


def debris_orbit(ephemeris, target: int, t: float,
                 model: ForceModel) -> tuple[np.ndarray, np.ndarray]:  # fmt: skip
    """Debris ``target``'s states [m, m/s] over one orbit from ``t`` [s] (GCRF), sampled
    uniformly for an orbit average."""
    period = 2.0 * np.pi / np.sqrt(model.mu / ephemeris.a_m[target] ** 3)
    return ephemeris.state(target, t + np.linspace(0.0, period, SAMPLES, endpoint=False))


def debris_eccentricity(ephemeris, target: int, t: float, model: ForceModel) -> np.ndarray:
    """Debris ``target``'s mean eccentricity vector over the orbit from ``t`` [s] (GCRF)."""
    r_d, v_d = debris_orbit(ephemeris, target, t, model)
    return np.mean(eccentricity_vector(r_d, v_d, mu=model.mu), axis=0)


def _node(normal, pole) -> np.ndarray:
    node = np.cross(pole, normal)
    return node / np.linalg.norm(node)


def in_node_frame(vector, normal, pole) -> np.ndarray:
    """Components of an in-plane vector along the ascending node and 90 deg after it."""
    node = _node(normal, pole)
    return np.array([np.dot(vector, node), np.dot(vector, np.cross(normal, node))])


def trim_epochs(start: float, t_leave: float):
    """The epochs [s] of the trims of a coast from ``start`` to ``t_leave`` (:data:`TRIMS`;
    none in its first half day nor in its last quarter day)."""
    span = t_leave - start
    for fraction in TRIMS:
        t_trim = t_leave - fraction * span
        if t_trim < start + 0.5 * SECONDS_PER_DAY or t_leave - t_trim < 0.25 * SECONDS_PER_DAY:
            continue
        yield t_trim


def trim(track: Track, leg: int, da: float, a: float) -> Maneuver:
    """The tangential impulse that changes the mean semi-major axis ``a`` [m] by ``da``
    [m] (vis-viva: ``dv = v da / (2 a)``)."""
    r_hat = track.r / np.linalg.norm(track.r)
    horizontal = np.linalg.norm(track.v - np.dot(track.v, r_hat) * r_hat)
    dv = 0.5 * np.linalg.norm(track.v) * da / a
    return track.impulse(leg, "trim", with_horizontal_speed(track.r, track.v, track.normal,
                                                            horizontal + dv))  # fmt: skip


def aim_at(track: Track, model: ForceModel, pole, a_goal, normal) -> np.ndarray:
    """The velocity in the plane ``normal`` whose orbit averages to ``a_goal`` (its radial
    part kept: an eccentric drift orbit precesses as a circular one does; the arrival's
    eccentricity is corrected after it, :func:`correct_eccentricity`)."""
    r_hat = track.r / np.linalg.norm(track.r)
    radial = np.dot(track.v, r_hat)
    speed = np.sqrt(model.mu * (2.0 / np.linalg.norm(track.r) - 1.0 / a_goal) - radial**2)
    for _ in range(AIM_SHOTS):
        v_new = with_horizontal_speed(track.r, track.v, normal, speed)
        averaged = averaged_orbit(track.r, v_new, track.t, model, pole=pole, samples=SAMPLES)
        # vis-viva: d(a) = 2 a^2 v d(v) / mu
        speed += (a_goal - averaged.a) * model.mu / (2.0 * averaged.a**2 * speed)
    return with_horizontal_speed(track.r, track.v, normal, speed)


def correct_phase(track: Track, leg: int, ephemeris, target: int, model: ForceModel, pole,
                  revolutions: int = PHASING_REVOLUTIONS) -> list[Maneuver]:  # fmt: skip
    """Close the along-track gap to the debris in ``revolutions`` orbits: a tangential
    impulse that changes the mean motion by ``d(lambda) / T``, the coast, and the
    impulse that gives the debris' semi-major axis back.

    The cost is ``2/3 v |d(lambda)| / (2 pi N)`` [m/s] for ``N`` revolutions
    (``da / a = -2/3 d(n) / n``; two tangential impulses of ``v |da| / (2 a)``): 0.3 m/s
    for 15 km at 800 km over 5 orbits.
    """
    mine = propagated_mean_state(track.r, track.v, track.t, model, pole)
    window = np.linspace(0.0, _period(track, model), SAMPLES, endpoint=False)
    times = mine.t - window.mean() + window  # centred where the vehicle's mean state is
    r_d, v_d = ephemeris.state(target, times)
    theirs = mean_state(times, r_d, v_d, mu=model.mu, pole=pole)
    gap = float(np.mod(theirs.arglat - mine.arglat + np.pi, 2.0 * np.pi) - np.pi)
    if abs(gap) * mine.a < SMALLEST_GAP_M:
        return []
    rate = 2.0 * np.pi / _period(track, model)
    coast = revolutions * 2.0 * np.pi / rate
    da = -2.0 / 3.0 * mine.a * (gap / coast) / rate
    done = []
    for sign in (1.0, -1.0):
        r_hat = track.r / np.linalg.norm(track.r)
        horizontal = np.linalg.norm(track.v - np.dot(track.v, r_hat) * r_hat)
        dv = sign * 0.5 * np.linalg.norm(track.v) * da / mine.a
        done.append(track.impulse(leg, "correction",
                                  with_horizontal_speed(track.r, track.v, track.normal,
                                                        horizontal + dv)))  # fmt: skip
        if sign > 0:
            track.coast(track.t + coast, model, pole)
    return done
