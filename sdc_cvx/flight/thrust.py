"""Thrust arcs of a low-thrust vehicle: a constant acceleration along a direction law.

A low-thrust leg (:mod:`~sdc_cvx.physics.low_thrust`) is flown as arcs of constant
thrust acceleration ``f`` [m/s^2] added to the force model of
:func:`~sdc_cvx.flight.propagation.propagate`:

- ``"tangential"``: along the velocity (``sign`` +1, raising the orbit) or against it
  (-1): the spirals;
- ``"plane"``: along the orbit normal ``h/|h|``, its sign switched at the antinodes so
  that it is ``sign * sign(cos u)`` (``u`` the argument of latitude from the ascending
  node ``p x h`` of the Earth's pole ``p``): the inclination changes at
  ``di/dt = f r |cos u| / h`` (``(2/pi) f / V`` averaged over an orbit, Edelbaum [1]_) and
  the RAAN, whose rate goes as ``sin u cos u``, does not.

With a ``reference`` direction ``d`` (inertial, in the plane) the sign switches with
``r . d`` instead of ``cos u``:

- ``"tangential"``: the eccentricity vector moves along ``d`` at ``(4/pi) f / V`` on
  average (Gauss: ``de/dt = 2 f_t r_hat / V`` on a near-circular orbit, and the mean of
  ``sign(r_hat . d) r_hat`` is ``(2/pi) d``) while ``a`` does not (as long prograde as
  retrograde);
- ``"plane"``: the direction of the angular momentum moves along ``d x h_hat`` at
  ``(2/pi) f / V`` [rad/s] on average (``dh/dt = r x f``): to turn the plane towards a
  normal ``n``, ``d = h_hat x n``.

References
----------
.. [1] T. N. Edelbaum, "Propulsion Requirements for Controllable Satellites", ARS Journal
   31(8), 1079–1089, 1961.
.. [2] D. A. Vallado, *Fundamentals of Astrodynamics and Applications*, 4th ed.,
   Microcosm Press, 2013, §9.3 (Gauss's variational equations).
"""

from __future__ import annotations

import math
from collections.abc import Callable
from typing import NamedTuple

import numpy as np

LAWS = ("tangential", "plane")


class Thrust(NamedTuple):
    """A constant thrust acceleration ``accel`` [m/s^2] along ``law``, ``sign`` +-1
    (module docstring)."""

    accel: float
    law: str
    sign: float = 1.0
    reference: tuple | None = None

    def acceleration(self, r, v, pole) -> np.ndarray:
        """The thrust acceleration [m/s^2] at states ``r`` [m], ``v`` [m/s], (..., 3)."""
        r, v = np.asarray(r, dtype=float), np.asarray(v, dtype=float)
        h = np.cross(r, v)
        if self.reference is not None:
            switch = np.sum(r * np.asarray(self.reference, dtype=float), axis=-1)
        elif self.law == "plane":
            switch = np.sum(r * np.cross(np.asarray(pole, dtype=float), h), axis=-1)
        else:
            switch = np.ones(r.shape[:-1])
        if self.law == "tangential":
            direction = v / np.linalg.norm(v, axis=-1, keepdims=True)
        elif self.law == "plane":
            direction = h / np.linalg.norm(h, axis=-1, keepdims=True)
        else:
            raise ValueError(f"unknown thrust law {self.law!r}: one of {LAWS}")
        return self.sign * self.accel * np.where(switch[..., None] >= 0.0, 1.0, -1.0) * direction

    def added_to(self, rhs: Callable, pole) -> Callable:
        """``rhs(t, y)`` of the propagator with this thrust added (scalar math, fast)."""
        k = self.sign * self.accel
        px, py, pz = (float(x) for x in np.asarray(pole, dtype=float) / np.linalg.norm(pole))
        sqrt = math.sqrt
        if self.reference is not None:
            if self.law not in LAWS:
                raise ValueError(f"unknown thrust law {self.law!r}: one of {LAWS}")
            dx, dy, dz = (float(x) for x in self.reference)
            along = self.law == "tangential"

            def switched(t, y):
                out = rhs(t, y)
                x, yy, z, vx, vy, vz = y.tolist()
                if along:
                    ux, uy, uz = vx, vy, vz
                else:
                    ux, uy, uz = yy * vz - z * vy, z * vx - x * vz, x * vy - yy * vx
                c = (k if x * dx + yy * dy + z * dz >= 0.0 else -k) / sqrt(
                    ux * ux + uy * uy + uz * uz)  # fmt: skip
                out[3], out[4], out[5] = out[3] + c * ux, out[4] + c * uy, out[5] + c * uz
                return out

            return switched
        if self.law == "tangential":

            def tangential(t, y):
                out = rhs(t, y)
                vx, vy, vz = out[0], out[1], out[2]
                c = k / sqrt(vx * vx + vy * vy + vz * vz)
                out[3], out[4], out[5] = out[3] + c * vx, out[4] + c * vy, out[5] + c * vz
                return out

            return tangential
        if self.law != "plane":
            raise ValueError(f"unknown thrust law {self.law!r}: one of {LAWS}")

        def plane(t, y):
            out = rhs(t, y)
            x, yy, z, vx, vy, vz = y.tolist()
            hx, hy, hz = yy * vz - z * vy, z * vx - x * vz, x * vy - yy * vx
            at_node = x * (py * hz - pz * hy) + yy * (pz * hx - px * hz) + z * (px * hy - py * hx)
            c = (k if at_node >= 0.0 else -k) / sqrt(hx * hx + hy * hy + hz * hz)
            out[3], out[4], out[5] = out[3] + c * hx, out[4] + c * hy, out[5] + c * hz
            return out

        return plane

    def describe(self) -> str:
        """The law as ``maneuvers.csv`` lists it."""
        if self.reference is not None:
            d = ", ".join(f"{x:.4f}" for x in self.reference)
            what = "tangential" if self.law == "tangential" else "out of plane"
            return f"{what}, its sign that of r . ({d}) (GCRF)"
        if self.law == "tangential":
            return "tangential, along the velocity" if self.sign > 0 else (
                "tangential, against the velocity")  # fmt: skip
        side = "raising" if self.sign > 0 else "lowering"
        return f"out of plane, switched at the antinodes ({side} the inclination)"
