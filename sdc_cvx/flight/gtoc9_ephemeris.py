"""GTOC9's debris where GTOC9 has them (issue 46, item 4): its own ephemeris, not SGP4.

GTOC9 ("The Kessler Run", its *equations* page [1]_) defines each debris by osculating
Keplerian elements ``t0, a, e, i, Omega0, omega0, M0``; at an epoch ``t`` the elements are
advanced by the mean motion and the secular J2 rates, ``a``, ``e`` and ``i`` fixed,

- ``n = sqrt(mu / a^3)``, ``p = a (1 - e^2)``,
- ``dOmega/dt = -3/2 J2 (r_eq / p)^2 n cos i``,
- ``domega/dt = 3/4 J2 (r_eq / p)^2 n (5 cos^2 i - 1)``,
- ``M = M0 + n (t - t0)``,

then converted to position and velocity as Keplerian elements (the velocity due to the
rates neglected, as GTOC9 says).  The frame is the one of GTOC9's elements: an inertial
equatorial frame whose z axis is the axis J2 acts about (:meth:`Gtoc9Ephemeris.pole_at`);
GTOC9's spacecraft obey two-body + J2 about that axis with GTOC9's constants below, which
are :meth:`~sdc_cvx.flight.propagation.ForceModel.named` ``"j2"``'s.

Units: m, m/s, rad, s (times after the catalog's start).

References
----------
.. [1] ESA Advanced Concepts Team, "GTOC9: The Kessler Run", problem, equations and
   constants pages, https://kelvins.esa.int/gtoc9-kessler-run/ (2017).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
import pandas as pd

from ..errors import CatalogError
from ..inputs.catalog import Catalog
from ..physics.elements import elements_to_state

GTOC9_MU = 398600.4418e9
"""GTOC9's gravitational parameter [m^3/s^2] (its constants page)."""
GTOC9_J2 = 1.08262668e-3
"""GTOC9's J2 [-]."""
GTOC9_R_EQ = 6378137.0
"""GTOC9's equatorial radius [m]."""
GTOC9_FRAME = "EME2000"
"""The OEM name given to GTOC9's frame (an inertial equatorial frame; GTOC9 names none)."""


@dataclass(frozen=True, eq=False, repr=False)
class Gtoc9Ephemeris:
    """The debris of a GTOC9 catalog moving as GTOC9 defines them (module docstring).

    Build it with :meth:`from_catalog`.  ``a_m``, ``e``, ``inc_rad`` [m, -, rad];
    ``raan0``, ``argp0``, ``m0`` [rad] at each row's epoch, ``since_start_s`` [s] from each
    epoch to the catalog's start; the rates [rad/s].
    """

    ids: tuple[str, ...]
    start: pd.Timestamp
    source: str
    a_m: np.ndarray
    e: np.ndarray
    inc_rad: np.ndarray
    raan0: np.ndarray
    argp0: np.ndarray
    m0: np.ndarray
    since_epoch_s: np.ndarray
    raan_rate: np.ndarray
    argp_rate: np.ndarray
    mean_motion: np.ndarray

    frame_name = GTOC9_FRAME

    @classmethod
    def from_catalog(cls, catalog: Catalog) -> Gtoc9Ephemeris:
        """The ephemeris of a catalog read from a GTOC9 file (``catalog.ephemeris ==
        "gtoc9"``); CatalogError if it lacks the epoch elements GTOC9 defines."""
        frame = catalog.frame
        needed = ("epoch", "raan_epoch_deg", "argp_deg", "mean_anomaly_deg")
        missing = [name for name in needed if name not in frame.columns]
        if missing or catalog.start is None:
            raise CatalogError(f"{catalog.source}: not a GTOC9 catalog with its epoch elements "
                               f"(missing {', '.join(missing) or 'the start date'})")  # fmt: skip
        a = frame["a_km"].to_numpy(float) * 1e3
        e = frame["e"].to_numpy(float)
        inc = np.radians(frame["inc_deg"].to_numpy(float))
        n = np.sqrt(GTOC9_MU / a**3)
        k = GTOC9_J2 * (GTOC9_R_EQ / (a * (1.0 - e**2))) ** 2 * n
        epochs = pd.DatetimeIndex(frame["epoch"])
        return cls(
            ids=tuple(frame["id"].astype(str)), start=catalog.start, source=catalog.source,
            a_m=a, e=e, inc_rad=inc,
            raan0=np.radians(frame["raan_epoch_deg"].to_numpy(float)),
            argp0=np.radians(frame["argp_deg"].to_numpy(float)),
            m0=np.radians(frame["mean_anomaly_deg"].to_numpy(float)),
            since_epoch_s=(catalog.start - epochs).total_seconds().to_numpy(),
            raan_rate=-1.5 * k * np.cos(inc), argp_rate=0.75 * k * (5.0 * np.cos(inc) ** 2 - 1.0),
            mean_motion=n,
        )  # fmt: skip

    def __len__(self) -> int:
        return len(self.ids)

    def __repr__(self) -> str:
        return f"Gtoc9Ephemeris({len(self)} debris from {self.source!r}, start={self.start})"

    def elements(self, position: int, seconds):
        """GTOC9's osculating ``(a, e, i, Omega, omega, M)`` [m, -, rad] of one debris at
        ``seconds`` [s] after the start (each an array like ``seconds``)."""
        dt = self.since_epoch_s[position] + np.atleast_1d(np.asarray(seconds, dtype=float))
        k = position
        return (np.full(dt.shape, self.a_m[k]), np.full(dt.shape, self.e[k]),
                np.full(dt.shape, self.inc_rad[k]), self.raan0[k] + self.raan_rate[k] * dt,
                self.argp0[k] + self.argp_rate[k] * dt,
                self.m0[k] + self.mean_motion[k] * dt)  # fmt: skip

    def state(self, position: int, seconds) -> tuple[np.ndarray, np.ndarray]:
        """Position [m] and velocity [m/s] (m, 3) of one debris at ``seconds`` [s] after
        the start, in GTOC9's frame (the Keplerian conversion of :meth:`elements`)."""
        return elements_to_state(*self.elements(position, seconds), mu=GTOC9_MU)

    def arglat_at_start(self) -> np.ndarray:
        """Mean argument of latitude ``omega + M`` of every debris at the start [rad]."""
        u = self.argp0 + self.argp_rate * self.since_epoch_s
        return np.mod(u + self.m0 + self.mean_motion * self.since_epoch_s, 2.0 * np.pi)

    def pole_at(self, seconds) -> np.ndarray:
        """The axis J2 acts about: GTOC9's z axis, whatever the date."""
        return np.array([0.0, 0.0, 1.0])
