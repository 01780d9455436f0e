"""Pre-optimisation of every ordered pair of debris (paper Part IV-B) into an edge table.

For each edge i -> j: the cheapest drift transfer whose duration is at most T0,
over both sides of the duration asymptote and the allowed drift inclinations.
Edges that cannot be done within T0 inside the altitude band, or that cost more
than ΔVmax, are marked and left out of the model (``EdgeTable.kept``).

Equation, table and part numbers are those of Cerf's paper [1]_; the design
rationale is in ``docs/design.md``.

References
----------
.. [1] M. Cerf, "Multiple Space Debris Collecting Mission — Debris Selection and Trajectory
   Optimization", Journal of Optimization Theory and Applications 156(3), 761–796, 2013.
   doi:10.1007/s10957-012-0130-6
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
import pandas as pd

from ..inputs.catalog import Catalog
from ..inputs.mission import Mission
from ..physics.eccentricity import Eccentricities
from ..physics.orbits import R_EARTH, SECONDS_PER_DAY
from ..physics.transfer import NodeOrbits

KEPT = "kept"
TOO_SLOW = "too_slow"
TOO_COSTLY = "too_costly"
PREOPT_CHUNK = 16384
"""Edges pre-optimised at once (the scan's temporaries are a few kB per edge)."""


def node_orbits(catalog: Catalog, mission: Mission) -> NodeOrbits:
    """The catalog's orbits at the mission start, with their RAAN rates.

    The J2 rates of the elements for the mission's ``j2`` (Eq. 7), or, for a catalog
    whose rates are fitted to SGP4 (``catalog.raan_rates == "sgp4"``,
    :meth:`~sdc_cvx.inputs.catalog.Catalog.with_sgp4_rates`), its
    ``raan_rate_deg_per_day`` (an orbit added to it, the injection orbit, has the J2
    rate at the package's ``J2`` there).  The drift orbits, the vehicle's, keep the J2
    rates of the mission (:func:`sdc_cvx.physics.transfer.drift_rate`).
    """
    orbits = NodeOrbits.from_elements(
        catalog.a_m, catalog.e, catalog.inc_rad, catalog.raan_rad, j2=mission.j2
    )
    if catalog.raan_rates == "sgp4":
        rate = catalog.frame["raan_rate_deg_per_day"].to_numpy(dtype=float)
        orbits = orbits._replace(rate=np.radians(rate) / SECONDS_PER_DAY)
    return orbits


def node_eccentricities(catalog: Catalog, mission: Mission) -> Eccentricities | None:
    """The catalog's mean eccentricity vectors at the mission start, or None when the
    mission does not price them (``mission.eccentricity`` resolved off).

    The argument of perigee at the start: the row's ``argp_deg`` at its epoch carried by
    the first-order J2 apsidal rate (Vallado, Eq. 9-41) for the mission's ``j2``, or as
    given for a catalog without epochs.  SGP4 element sets (TLE, OMM, CSV) add J3's
    constant term (:mod:`~sdc_cvx.physics.eccentricity`), GTOC9's do not.  A row without
    one (the injection orbit) is circular.
    """
    if mission.eccentricity != "on":
        return None
    frame = catalog.frame
    argp = (np.radians(frame["argp_deg"].to_numpy(dtype=float)) if "argp_deg" in frame.columns
            else np.full(len(frame), np.nan))  # fmt: skip
    e = np.where(np.isfinite(argp), catalog.e, 0.0)
    rates = Eccentricities.from_elements(catalog.a_m, e, catalog.inc_rad, 0.0, frozen=False,
                                         j2=mission.j2).argp_rate  # fmt: skip
    if "epoch" in frame.columns and catalog.start is not None:
        epochs = pd.to_datetime(frame["epoch"], utc=True)
        elapsed = (catalog.start - epochs).dt.total_seconds().to_numpy(dtype=float)
        argp = argp + rates * np.nan_to_num(elapsed)
    frozen = getattr(catalog, "ephemeris", "sgp4") == "sgp4"
    return Eccentricities.from_elements(catalog.a_m, e, catalog.inc_rad,
                                        np.nan_to_num(argp), frozen=frozen, j2=mission.j2)


def drift_radius_bounds(mission: Mission) -> tuple[float, float]:
    """Drift orbit radius bounds [m] from the mission's altitude bounds [km]."""
    low, high = mission.drift_altitude_km
    return R_EARTH + 1e3 * low, R_EARTH + 1e3 * high


@dataclass(frozen=True)
class EdgeTable:
    """Pre-optimised transfers of every ordered pair of candidate debris.

    Attributes
    ----------
    frame : pandas.DataFrame
        One row per ordered pair (i != j): ``from_id, to_id`` (catalog ids), ``i, j``
        (catalog positions), ``status`` (``kept``, ``too_slow``: no drift orbit in the
        altitude band reaches j within T0, ``too_costly``: ΔV > ΔVmax), ``side`` (+1:
        drift faster than the target, i.e. below it for retrograde orbits; -1 slower;
        0 if too slow), ``drift_a_km``, ``drift_alt_km``, ``drift_inc_deg``,
        ``departure_day``, ``duration_days``, ``dv_mps``.
    catalog : Catalog
    mission : Mission
    """

    frame: pd.DataFrame
    catalog: Catalog
    mission: Mission

    @property
    def kept(self) -> pd.DataFrame:
        """The feasible edges the model is built over (a view of ``frame``)."""
        return self.frame[self.frame["status"] == KEPT]

    def counts(self) -> dict[str, int]:
        """Number of edges per status."""
        counts = self.frame["status"].value_counts()
        return {status: int(counts.get(status, 0)) for status in (KEPT, TOO_SLOW, TOO_COSTLY)}

    def summary(self) -> str:
        """One line: how many edges were kept and why the others were dropped."""
        c = self.counts()
        total = len(self.frame)
        return (
            f"{c[KEPT]} of {total} edges kept ({c[TOO_SLOW]} cannot close the RAAN gap within "
            f"{'a coast of ' if self.mission.transfer == 'low-thrust' else ''}"
            f"T0 = {self.mission.preopt_days:g} days, {c[TOO_COSTLY]} cost more than "
            f"{self.mission.dv_max_mps:g} m/s)"
        )


def preoptimize(
    catalog: Catalog, mission: Mission, departure_day=0.0, *, sides=(1, -1)
) -> EdgeTable:
    """Pre-optimise every ordered pair of the catalog (Part IV-B).

    Parameters
    ----------
    catalog : Catalog
        Candidate debris, RAANs at the mission start t0.
    mission : Mission
        Uses ``preopt_days`` (T0), ``drift_altitude_km``, ``dv_max_mps``,
        ``drift_inclination``, ``j2`` and the transfer model (``transfer``, ``vehicle``).
    departure_day : float or array_like
        Reference departure date of each edge [days after t0]: a scalar, or an array
        of shape (N, N) indexed [i, j].
    sides : tuple of {1, -1}
        Sides of the duration asymptote considered (default both: the cheaper wins).

    Returns
    -------
    EdgeTable
    """
    n = len(catalog)
    orbits = node_orbits(catalog, mission)
    i, j = np.nonzero(~np.eye(n, dtype=bool))
    day = np.broadcast_to(np.asarray(departure_day, dtype=float), (n, n))[i, j]
    a_low, a_high = drift_radius_bounds(mission)
    model = mission.transfer_model()
    parts = []
    for start in range(0, max(len(i), 1), PREOPT_CHUNK):  # in chunks: small temporaries
        rows = slice(start, start + PREOPT_CHUNK)
        parts.append(model.cheapest_transfer(
            orbits.take(i[rows]), orbits.take(j[rows]), day[rows] * SECONDS_PER_DAY,
            mission.preopt_days * SECONDS_PER_DAY, a_low, a_high,
            inclination=mission.drift_inclination,
            sides=tuple(float(side) for side in sides), j2=mission.j2))  # fmt: skip
    choice = type(parts[0])(*(np.concatenate(field) for field in zip(*parts, strict=True)))
    status = np.where(
        ~np.isfinite(choice.dv),
        TOO_SLOW,
        np.where(choice.dv > mission.dv_max_mps, TOO_COSTLY, KEPT),
    )
    ids = np.asarray(catalog.ids, dtype=object)
    frame = pd.DataFrame(
        {
            "from_id": ids[i],
            "to_id": ids[j],
            "i": i,
            "j": j,
            "status": status,
            "side": choice.side.astype(int),
            "drift_a_km": choice.a_drift / 1e3,
            "drift_alt_km": (choice.a_drift - R_EARTH) / 1e3,
            "drift_inc_deg": np.rad2deg(choice.inc_drift),
            "departure_day": day,
            "duration_days": choice.duration / SECONDS_PER_DAY,
            "dv_mps": choice.dv,
        }
    )
    return EdgeTable(frame, catalog, mission)


def preoptimize_windows(
    catalog: Catalog,
    mission: Mission,
    window_bounds,
    *,
    reference_days=None,
    sides=(1, -1),
    reference_at=(0.0,),
) -> pd.DataFrame:  # fmt: skip
    """Pre-optimised copies of every edge, per departure-date window and side (time-expanded).

    With J2 rates that differ, the right drift orbit of an edge depends on when it is
    flown, and a single reference date per edge (Part IV-B) misjudges edges flown
    late in the mission.  Each window ``[lo, hi)`` gets its own copy of every edge,
    pre-optimised at the window's start, and one copy per side of the duration
    asymptote where both are feasible: the model then chooses an edge, its window
    and its side, instead of fixing the side at initialisation (Part IV-B) and only
    checking it at the end.  One window and the cheaper side is the paper's method.

    Parameters
    ----------
    catalog, mission : Catalog, Mission
    window_bounds : array_like
        K + 1 increasing dates [days]: window k is ``[bounds[k], bounds[k+1]]``.
    reference_days : float, optional
        Duration allowed to the reference transfer of a kept copy [days]; the copy is
        kept if it is feasible within ``mission.preopt_days`` (T0) and under ΔVmax.
        Default: T0.
    sides : tuple of {1, -1}
        Sides to make copies for; ``(1, -1)`` makes one copy per feasible side.
    reference_at : tuple of float
        Where in each window copies are referenced, as fractions of its width: ``(0,)``
        its earliest departure (for one window, the paper's first departure), ``(0,
        0.5)`` also its centre.  Each placement finds the optimum on cases where the
        other misses it (``tests/test_enumeration.py``); both double the copies.

    Returns
    -------
    pandas.DataFrame
        The kept copies: the columns of :class:`EdgeTable` plus ``window``,
        ``window_lo``, ``window_hi`` (days).
    """
    bounds = np.asarray(window_bounds, dtype=float)
    reference = mission if reference_days is None else mission.replace(
        preopt_days=min(reference_days, mission.preopt_days)
    )  # fmt: skip
    frames = []
    for k, (lo, hi) in enumerate(zip(bounds[:-1], bounds[1:], strict=True)):
        for reference_day in np.unique(lo + np.asarray(reference_at) * (hi - lo)):
            frames += _copies(catalog, mission, reference, reference_day, sides, k, lo, hi)
    frame = pd.concat(frames, ignore_index=True)
    frame[["i", "j", "side", "window"]] = frame[["i", "j", "side", "window"]].astype(int)
    return frame


def _copies(catalog, mission, reference, reference_day, sides, window, lo, hi):
    """Kept copies of every edge referenced at ``reference_day``, one frame per side."""
    frames = []
    for side in sides:
        kept = preoptimize(catalog, mission, departure_day=reference_day, sides=(side,)).frame
        ref = preoptimize(catalog, reference, departure_day=reference_day, sides=(side,)).frame
        use_ref = ref["status"] == KEPT
        copies = kept.where(~use_ref, ref)  # a faster reference where one exists
        copies = copies[kept["status"] == KEPT]
        frames.append(copies.assign(window=window, window_lo=lo, window_hi=hi))
    return frames
