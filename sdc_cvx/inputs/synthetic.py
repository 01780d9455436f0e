"""Synthetic debris catalogs for benchmarks, tests and examples.

Debris near sun-synchronous orbits with spread altitudes, so that their J2 rates
differ (unlike the paper's Table 5, whose debris all precess within 1e-4 deg/day of
each other): departure dates then matter, which exercises the date terms of the model.
"""

from __future__ import annotations

import numpy as np
import pandas as pd

from ..physics.orbits import J2, MU_EARTH, R_EARTH, SECONDS_PER_DAY
from .catalog import Catalog

SUN_SYNCHRONOUS_RATE = 2.0 * np.pi / (365.2422 * SECONDS_PER_DAY)
"""RAAN rate of a sun-synchronous orbit [rad/s] (360 deg per tropical year)."""


def sun_synchronous_inclination(a, *, j2=J2, mu=MU_EARTH, r_eq=R_EARTH):
    """Inclination [rad] of the circular orbit of radius ``a`` [m] that precesses like the Sun.

    Inverse of Eq. 7 for ``e = 0``: ``cos I = -rate / (3/2 J2 n (R_T / a)^2)``.
    """
    a = np.asarray(a, dtype=float)
    n = np.sqrt(mu / a**3)
    return np.arccos(-SUN_SYNCHRONOUS_RATE / (1.5 * j2 * n * (r_eq / a) ** 2))


def sso_catalog(
    count: int,
    *,
    seed: int = 0,
    altitude_km=(600.0, 900.0),
    inclination_spread_deg: float = 0.5,
    raan_span_deg: float = 360.0,
) -> Catalog:
    """A random catalog of ``count`` near-SSO debris on circular orbits.

    Parameters
    ----------
    count : int
        Number of debris.
    seed : int
        Seed of the random generator (same seed, same catalog).
    altitude_km : (float, float)
        Uniform altitude range [km].
    inclination_spread_deg : float
        Uniform offset from the sun-synchronous inclination, +/- this [deg]; the
        offset is what makes the J2 rates differ.
    raan_span_deg : float
        RAANs are uniform in [0, raan_span_deg) [deg].
    """
    rng = np.random.default_rng(seed)
    altitude = rng.uniform(*altitude_km, count)
    a_km = R_EARTH / 1e3 + altitude
    inc = np.rad2deg(sun_synchronous_inclination(a_km * 1e3))
    inc += rng.uniform(-inclination_spread_deg, inclination_spread_deg, count)
    frame = pd.DataFrame(
        {
            "id": [f"S{k:03d}" for k in range(count)],
            "a_km": a_km,
            "e": rng.uniform(0.0, 2e-3, count),
            "inc_deg": inc,
            "raan_deg": rng.uniform(0.0, raan_span_deg, count),
        }
    )
    return Catalog.from_frame(frame, source=f"synthetic SSO catalog (count={count}, seed={seed})")
