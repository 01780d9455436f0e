"""After the arrival: the impulses that close what the transfer left (issue 26, item 3).

The arrival impulse puts the vehicle on the debris' semi-major axis; what is left is the
orbit's shape and plane, which the planner's circular model does not see:

- :func:`correct_eccentricity`: the mean eccentricity vectors of the vehicle and the
  debris differ by ``dE`` (the debris' own eccentricities, about 0.004 for the SSO rocket
  bodies).  Two tangential impulses half an orbit apart, of ``+-v |dE| / 4`` where the
  radius points along ``+-dE``, close it without changing the semi-major axis: a
  tangential impulse ``dv`` moves the eccentricity vector by ``2 dv / v`` along the
  radius (Vallado [1]_ §6.3, near-circular orbits), the cheapest way, ``v |dE| / 2``.
- :func:`correct_plane`: a rotation onto the debris' plane where the vehicle crosses it.

The along-track miss is left to proximity operations (not modelled).  SI units.

References
----------
.. [1] D. A. Vallado, *Fundamentals of Astrodynamics and Applications*, 4th ed.,
   Microcosm Press, 2013, §6.3-6.5.
"""

from __future__ import annotations

import numpy as np

from ..physics.impulses import rotated_into, with_horizontal_speed
from .propagation import ForceModel, propagate
from .rates import SAMPLES
from .result import Maneuver
from .track import Track

SMALLEST_DE = 1e-5
"""Eccentricity differences below this are left alone (0.04 m/s at 800 km)."""


def eccentricity_vector(r, v, *, mu: float) -> np.ndarray:
    """Osculating eccentricity vectors [-] of states (..., 3)."""
    r, v = np.asarray(r, dtype=float), np.asarray(v, dtype=float)
    radius = np.linalg.norm(r, axis=-1, keepdims=True)
    speed2 = np.sum(v * v, axis=-1, keepdims=True)
    radial = np.sum(r * v, axis=-1, keepdims=True)
    return ((speed2 - mu / radius) * r - radial * v) / mu


def _period(track: Track, model: ForceModel) -> float:
    return 2.0 * np.pi * np.sqrt(np.linalg.norm(track.r) ** 3 / model.mu)


def _mean_eccentricity(track: Track, model, pole) -> np.ndarray:
    times = track.t + np.linspace(0.0, _period(track, model), SAMPLES, endpoint=False)
    arc = propagate(track.r, track.v, track.t, times[-1], model, pole=pole, t_eval=times)
    return np.mean(eccentricity_vector(arc.r, arc.v, mu=model.mu), axis=0)


def debris_eccentricity(ephemeris, target: int, t: float, model: ForceModel) -> np.ndarray:
    """Debris ``target``'s mean eccentricity vector over the orbit from ``t`` [s] (GCRF)."""
    period = 2.0 * np.pi / np.sqrt(model.mu / ephemeris.a_m[target] ** 3)
    times = t + np.linspace(0.0, period, SAMPLES, endpoint=False)
    r_d, v_d = ephemeris.state(target, times)
    return np.mean(eccentricity_vector(r_d, v_d, mu=model.mu), axis=0)


def _node(normal, pole) -> np.ndarray:
    node = np.cross(pole, normal)
    return node / np.linalg.norm(node)


def turned_eccentricity(wanted, wanted_normal, track: Track, pole, argp_turn: float):
    """The eccentricity vector ``wanted`` of the plane ``wanted_normal``, its argument of
    perigee turned back by ``argp_turn`` [rad] and laid in the vehicle's plane: what the
    vehicle's must be now to become ``wanted`` once both planes meet and its apsides have
    turned by ``argp_turn``."""
    node_w = _node(wanted_normal, pole)
    argp = np.arctan2(np.dot(wanted, np.cross(wanted_normal, node_w)), np.dot(wanted, node_w))
    argp -= argp_turn
    node = _node(track.normal, pole)
    e = float(np.linalg.norm(wanted))
    return e * (np.cos(argp) * node + np.sin(argp) * np.cross(track.normal, node))


def correct_eccentricity(track: Track, leg: int, wanted, model: ForceModel,
                         pole) -> list[Maneuver]:  # fmt: skip
    """The two tangential impulses that give the vehicle the mean eccentricity vector
    ``wanted`` (GCRF; its part in the vehicle's plane)."""
    delta = wanted - _mean_eccentricity(track, model, pole)
    delta -= np.dot(delta, track.normal) * track.normal  # in the plane
    size = float(np.linalg.norm(delta))
    if size < SMALLEST_DE:
        return []
    across = np.cross(track.normal, delta / size)

    def aligned(t, r, v):
        return float(np.dot(r, across))

    arc = propagate(track.r, track.v, track.t, track.t + 1.6 * _period(track, model), model,
                    pole=pole, events=[aligned])  # fmt: skip
    done = []
    for t, r in zip(arc.t_events[0], arc.r_events[0], strict=True):
        if t <= track.t or (not done and np.dot(r, delta) <= 0.0):
            continue  # the first impulse where the radius points along +dE
        track.coast(float(t), model, pole)
        sign = 1.0 if np.dot(track.r, delta) > 0.0 else -1.0
        r_hat = track.r / np.linalg.norm(track.r)
        horizontal = np.linalg.norm(track.v - np.dot(track.v, r_hat) * r_hat)
        speed = horizontal + sign * 0.25 * np.linalg.norm(track.v) * size
        done.append(track.impulse(leg, "correction",
                                  with_horizontal_speed(track.r, track.v, track.normal, speed)))
        if len(done) == 2:
            break
    return done


def correct_plane(track: Track, leg: int, ephemeris, target: int, model: ForceModel,
                  pole) -> Maneuver | None:  # fmt: skip
    """Turn onto the debris' plane where the vehicle next crosses it (within half an orbit;
    the plane is the debris' osculating one then: side by side, their short-period terms
    are the same)."""
    r_d, v_d = ephemeris.state(target, np.array([track.t]))
    normal = np.cross(r_d[0], v_d[0])
    normal /= np.linalg.norm(normal)
    period = 2.0 * np.pi * np.sqrt(np.linalg.norm(track.r) ** 3 / model.mu)

    def crossing(t, r, v):
        return float(np.dot(r, normal))

    arc = propagate(track.r, track.v, track.t, track.t + 0.6 * period, model, pole=pole,
                    events=[crossing])  # fmt: skip
    later = [t for t in arc.t_events[0] if t > track.t + 60.0]  # not one it is on now
    if not later:
        return None
    track.coast(float(later[0]), model, pole)
    r_d, v_d = ephemeris.state(target, np.array([track.t]))
    normal = np.cross(r_d[0], v_d[0])
    return track.impulse(leg, "correction",
                         rotated_into(track.r, track.v, normal / np.linalg.norm(normal)))
