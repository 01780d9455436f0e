"""Mean elements measured on a flight: the vehicle's, and a debris' along a leg.

The guidance (:mod:`~sdc_cvx.flight.guidance`) plans in the mean elements of
:mod:`sdc_cvx.physics.mean_elements` and flies in a numerical force model; these two
functions tie them together:

- :func:`measure`: the mean elements of the force model's trajectory through a state:
  one orbit propagated and averaged (the short-period J2 terms, about 9 km in ``a`` at
  800 km, average out over a period; Kozai [1]_).  Two passes: the second over the
  period of the first's mean elements (30 m of short-period terms are left in ``a`` by a
  window 1e-3 too long, 10 km of drift a month later).
- :class:`DebrisTrack`: where a debris is, in the same mean elements, over a leg.  What
  the vehicle must reach at an epoch ``t`` is the mean of the *force model's* trajectory
  through the debris' state then (:func:`measure` of the debris' state): both then have
  the same state at ``t``.  For SGP4 debris it is within metres of the debris' own orbit
  average (SGP4's short-period terms are J2's to first order); GTOC9's debris move on
  Keplerian orbits whose elements precess (their ephemeris has no short-period terms),
  so theirs differs by the short-period terms themselves, up to 9 km in ``a`` over an
  orbit.  So the track is the debris' orbit average, on lines through states every
  :data:`LINE_STEP_DAYS` (drag bends them), plus a *ripple*: the difference between the
  two over one orbit near the arrival, as harmonics of the argument of latitude.

All SI; angles from the equator of a leg's frame (``basis``: rows x, y, z of its equatorial
frame in the flight's, :func:`~sdc_cvx.flight.frames.equatorial_basis`).

References
----------
.. [1] Y. Kozai, "The motion of a close earth satellite", Astronomical Journal 64, 367, 1959.
"""

from __future__ import annotations

import numpy as np

from ..physics.elements import secular_rates
from ..physics.mean_elements import RAAN, TWO_PI, U, mean_of, wrap
from ..physics.orbits import SECONDS_PER_DAY
from .propagation import ForceModel, propagate

SAMPLES = 64
"""States averaged over one orbit."""
RIPPLE_SAMPLES = 16
"""Epochs over one orbit where the ripple is measured (its harmonics need 9)."""
RIPPLE_HARMONICS = 4
"""Harmonics of the argument of latitude in the ripple (J2's short-period terms of a
near-circular orbit are at u, 2u and 3u)."""
LINE_STEP_DAYS = 5.0
"""Step between a debris' orbit averages along a leg [days] (where drag is strongest in
the catalogues, 3 km at most between two averages followed linearly)."""


def orbit_mean(times, r, v, basis, *, mu: float) -> np.ndarray:
    """Mean elements ``(a, ex, ey, inc, raan, u)`` at ``times[0]`` of states sampled
    uniformly over one period (``times`` (m,) [s], ``r``, ``v`` (m, 3) in the flight's
    frame): each element averaged (the angles unwrapped), ``u`` carried back from the
    middle of the samples by its secular rate."""
    local_r, local_v = np.asarray(r) @ basis.T, np.asarray(v) @ basis.T
    elements = mean_of(local_r, local_v, mu=mu)
    normal = np.cross(local_r, local_v)
    normal = np.mean(normal / np.linalg.norm(normal, axis=-1, keepdims=True), axis=0)
    inc = float(np.arctan2(np.hypot(normal[0], normal[1]), normal[2]))
    raan = float(np.arctan2(normal[0], -normal[1]))
    # the eccentricity vector in the averaged plane's node frame
    radius = np.linalg.norm(local_r, axis=-1)
    speed2 = np.sum(local_v * local_v, axis=-1)
    radial_speed = np.sum(local_r * local_v, axis=-1)
    e_vec = np.mean((speed2 - mu / radius)[:, None] * local_r
                    - radial_speed[:, None] * local_v, axis=0) / mu  # fmt: skip
    node = np.array([np.cos(raan), np.sin(raan), 0.0])
    side = np.cross(normal / np.linalg.norm(normal), node)
    a = float(np.mean(elements[:, 0]))
    ex, ey = float(e_vec @ node), float(e_vec @ side)
    u_mid = float(np.mean(np.unwrap(elements[:, U])))
    rate = float(secular_rates(a, np.hypot(ex, ey), inc).arglat)
    u0 = u_mid - rate * (float(np.mean(times)) - float(times[0]))
    return np.array([a, ex, ey, inc, raan, u0])


def measure(r, v, t: float, force: ForceModel, pole, basis, period=None) -> np.ndarray:
    """Mean elements at ``t`` [s] of the trajectory of ``force`` through ``(r, v)``
    (module docstring): ``(a, ex, ey, inc, raan, u)``, ``u`` in [-pi, pi).  Given its
    draconic ``period`` [s], one pass over it (else two)."""
    r, v = np.asarray(r, dtype=float), np.asarray(v, dtype=float)
    a = 1.0 / (2.0 / np.linalg.norm(r) - v @ v / force.mu)
    rate = np.sqrt(force.mu / a**3) if period is None else TWO_PI / period
    for _ in range(2 if period is None else 1):
        times = t + TWO_PI / rate * np.arange(SAMPLES) / SAMPLES
        arc = propagate(r, v, t, t + TWO_PI / rate, force, pole=pole, t_eval=times)
        mean = orbit_mean(times, arc.r, arc.v, basis, mu=force.mu)
        rate = float(secular_rates(mean[0], np.hypot(mean[1], mean[2]), mean[3],
                                   j2=force.j2, mu=force.mu, r_eq=force.r_eq).arglat)  # fmt: skip
    mean[U] = wrap(mean[U])
    return mean


class DebrisTrack:
    """A debris' mean elements over ``[t_start, t_end]`` [s] (module docstring).

    Parameters
    ----------
    ephemeris
        Anything with ``state(position, seconds)`` (the debris, in the flight's frame).
    position : int
        The debris' row.
    t_start, t_end : float
        The span the track must cover [s].
    near : float
        An epoch [s] near which the ripple is measured (the planned arrival).
    force, pole, basis
        The vehicle's force model, the pole it is about, the leg's equatorial frame.
    """

    def __init__(self, ephemeris, position: int, t_start: float, t_end: float, near: float,
                 force: ForceModel, pole, basis):  # fmt: skip
        self.ephemeris, self.position = ephemeris, position
        self.force, self.pole, self.basis = force, pole, basis
        first = self._average(t_start)
        rate = float(secular_rates(first[0], np.hypot(first[1], first[2]), first[3]).arglat)
        self.period = TWO_PI / rate
        span = max(t_end - t_start, self.period)
        count = max(int(np.ceil(span / (LINE_STEP_DAYS * SECONDS_PER_DAY))), 1) + 1
        self.times = np.linspace(t_start, t_start + span, count)
        lines = [first] + [self._average(t) for t in self.times[1:]]
        self.lines = _unwrapped(np.array(lines), self.times, first)
        self.ripple = self._ripple(near)

    def _average(self, t: float) -> np.ndarray:
        times = t + self._one_orbit(t)
        r, v = self.ephemeris.state(self.position, times)
        return orbit_mean(times, r, v, self.basis, mu=self.force.mu)

    def _one_orbit(self, t: float) -> np.ndarray:
        period = getattr(self, "period", None)
        if period is None:
            period = TWO_PI * np.sqrt(self.ephemeris.a_m[self.position] ** 3 / self.force.mu)
        return period * np.arange(SAMPLES) / SAMPLES

    def line(self, t) -> np.ndarray:
        """The debris' own orbit average at ``t`` [s] (``(..., 6)``), followed linearly
        between the averages (and beyond the ends, along the end spans)."""
        t = np.asarray(t, dtype=float)
        k = np.clip(np.searchsorted(self.times, t) - 1, 0, len(self.times) - 2)
        f = (t - self.times[k]) / (self.times[k + 1] - self.times[k])
        return self.lines[k] + f[..., None] * (self.lines[k + 1] - self.lines[k])

    def _ripple(self, near: float) -> np.ndarray:
        """Harmonic coefficients (6, 2K+1) of the force model's mean less the line, in the
        line's argument of latitude, from :data:`RIPPLE_SAMPLES` epochs over an orbit."""
        epochs = near + self.period * (np.arange(RIPPLE_SAMPLES) / RIPPLE_SAMPLES - 0.5)
        r, v = self.ephemeris.state(self.position, epochs)
        line = self.line(epochs)
        diffs = []
        for k, t in enumerate(epochs):
            exact = measure(r[k], v[k], float(t), self.force, self.pole, self.basis,
                            self.period)
            d = exact - line[k]
            d[RAAN] = wrap(d[RAAN])
            d[U] = wrap(d[U])
            diffs.append(d)
        basis = _harmonics(line[:, U])
        coefficients, *_ = np.linalg.lstsq(basis, np.array(diffs), rcond=None)
        return coefficients.T

    def at(self, t) -> np.ndarray:
        """The mean elements [m, rad] the vehicle must have to be at the debris at ``t``
        [s] (``(..., 6)``, ``u`` unwrapped on the track's count)."""
        line = self.line(t)
        return line + _harmonics(line[..., U]) @ self.ripple.T

    def state(self, t: float) -> tuple[np.ndarray, np.ndarray]:
        """The debris' position [m] and velocity [m/s] at ``t`` [s], the flight's frame."""
        r, v = self.ephemeris.state(self.position, np.array([t]))
        return r[0], v[0]


def _harmonics(u) -> np.ndarray:
    """``[1, cos u, sin u, ..., cos Ku, sin Ku]`` (``(..., 2K+1)``)."""
    u = np.asarray(u, dtype=float)[..., None]
    k = np.arange(1, RIPPLE_HARMONICS + 1)
    columns = np.concatenate([np.cos(k * u), np.sin(k * u)], axis=-1)
    return np.concatenate([np.ones_like(u), columns], axis=-1)


def _unwrapped(means: np.ndarray, times: np.ndarray, first: np.ndarray) -> np.ndarray:
    """Orbit averages with the RAAN and ``u`` unwrapped along time, whole turns between
    neighbours counted with the rate of the span before (the first span: the secular
    rate of ``first``)."""
    rates = secular_rates(first[0], np.hypot(first[1], first[2]), first[3])
    out = means.copy()
    for column, rate in ((RAAN, float(rates.raan)), (U, float(rates.arglat))):
        for k in range(1, len(times)):
            dt = times[k] - times[k - 1]
            step = means[k, column] - means[k - 1, column]
            step += TWO_PI * np.round((rate * dt - step) / TWO_PI)
            out[k, column] = out[k - 1, column] + step
            rate = step / dt
    return out
