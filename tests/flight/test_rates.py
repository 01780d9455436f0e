"""Where the phasing expects a target: its mean orbit fitted over a leg's window.

The target here is an analytic circular orbit whose argument of latitude speeds up as
drag would make it (a constant ``du/dt`` rate of change), its states written from the
formula, not from the package's propagators: the fit must follow it over the whole
window, where a line through the window's ends is tens of degrees off in the middle.
"""

import numpy as np
import pytest

from sdc_cvx.flight.propagation import ForceModel
from sdc_cvx.flight.rates import fitted_orbit
from sdc_cvx.physics.phasing import MeanOrbit

MU = 3.986004418e14
DAY = 86400.0
A = 6378137.0 + 760e3
INC = np.radians(98.5)
POLE = np.array([0.0, 0.0, 1.0])
N = np.sqrt(MU / A**3)  # [rad/s]
RAAN_RATE = np.radians(0.9856) / DAY  # sun-synchronous [rad/s]
# drag at 760 km, B* 3e-4: the argument of latitude gains 100 deg on its initial rate in
# the middle of 300 days (u'' T^2 / 8)
SPEED_UP = 8.0 * np.radians(100.0) / (300.0 * DAY) ** 2  # [rad/s^2]


class DraggedDebris:
    """One debris, circular, its argument of latitude u0 + n t + SPEED_UP t^2 / 2."""

    u0, raan0 = 1.0, 2.0

    def arglat(self, t):
        return self.u0 + N * t + 0.5 * SPEED_UP * t**2

    def raan(self, t):
        return self.raan0 + RAAN_RATE * t

    def state(self, position, seconds):
        t = np.atleast_1d(np.asarray(seconds, dtype=float))
        u, raan = self.arglat(t), self.raan(t)
        # the orbit's in-plane unit vectors (node line, and 90 deg ahead of it)
        p = np.stack([np.cos(raan), np.sin(raan), np.zeros_like(t)], axis=1)
        q = np.stack([-np.sin(raan) * np.cos(INC), np.cos(raan) * np.cos(INC),
                      np.full_like(t, np.sin(INC))], axis=1)  # fmt: skip
        radial = np.cos(u)[:, None] * p + np.sin(u)[:, None] * q
        along = -np.sin(u)[:, None] * p + np.cos(u)[:, None] * q
        return A * radial, np.sqrt(MU / A) * along


def wrapped_deg(x):
    return np.degrees(np.mod(x + np.pi, 2.0 * np.pi) - np.pi)


def test_a_dragged_target_is_followed_over_the_whole_window():
    debris = DraggedDebris()
    guess = MeanOrbit(A, 0.0, INC, debris.raan0, debris.u0, RAAN_RATE, N)
    fitted = fitted_orbit(debris, 0, 0.0, 300.0 * DAY, guess, ForceModel(mu=MU), POLE)
    t = np.linspace(0.0, 295.0 * DAY, 400)
    assert np.max(np.abs(wrapped_deg(fitted.arglat_at(t) - debris.arglat(t)))) < 0.05
    assert np.max(np.abs(wrapped_deg(fitted.raan_at(t) - debris.raan(t)))) < 1e-3
    # the line through the window's ends alone: far off in the middle
    line = fitted._replace(wander=None)
    assert np.max(np.abs(wrapped_deg(line.arglat_at(t) - debris.arglat(t)))) > 50.0
    # past the window, on the line through its ends
    late = 400.0 * DAY
    assert fitted.arglat_at(late) == pytest.approx(line.arglat_at(late))
