"""GTOC9's legs priced on their two dates (issue 47, item 2): :class:`Gtoc9Legs`.

A GTOC9 leg joins two debris between a departure and an arrival a few days to a few weeks
apart (the stays are 5 days, consecutive rendezvous at most Δt_R = 30 days apart).  Its
cost is the paper's impulsive drift leg (Part III: a Hohmann transfer with the plane
change combined to a circular drift orbit, the drift, a Hohmann transfer to the target;
the drift radius fixed by the two dates, Eq. 10 inverted) with the eccentricity it must
change priced (:mod:`sdc_cvx.physics.eccentricity`, issue 46): the exact cheapest such leg
of the two dates and a lower bound of it over a box of dates, those of
:class:`~sdc_cvx.physics.leg_bounds.LegCosts` (their proofs are in ``docs/design.md``).

GTOC9's legs are short, and a RAAN gap of a fraction of a degree is cheaper to turn in the
transfer's burns than to drift away: the **direct leg** (item 2's "cheaper leg
structure") is the Hohmann transfer between the two debris radii with the whole angle
between their planes combined (Eq. 11-13 with the plane angle
``cos θ = cos i_1 cos i_2 + sin i_1 sin i_2 cos ΔΩ`` for the inclination change, at the
date of the leg where the planes are closest), then a coast on the target's orbit; plus
the phasing it must do at worst (half a revolution, by a radius offset ``δ`` held over
the leg's days ``T``: ``δ / a = π / (1.5 n T)``, at ``v δ / a``), and the eccentricity it
changes priced as the drift leg's (the coast's apsides turning at the target's rate; the
transfers' room ``|a_j - a_i| / a``).  :meth:`Gtoc9Legs.cost` is the cheaper of the two
structures when ``direct`` is on (``side`` 0 marks a direct leg; off by default until a
flight has flown one), :meth:`Gtoc9Legs.bound` the lower of their
bounds (the direct leg's: its Hohmann transfer at the least plane angle over the box and
the phasing of the box's longest leg).

The debris are GTOC9's (:func:`~sdc_cvx.inputs.formats.read_catalog` with ``format =
"gtoc9"``) at the start of GTOC9's window, MJD2000 23467: dates here are days from it.
Their RAANs move at GTOC9's secular J2 rate (its equations page; GTOC9's J2, μ and r_eq
everywhere here, the drift orbits' rates and the transfers included), their eccentricity
vectors at its apsidal rate, from each debris' own epoch.  The drift orbits stay between
``drift_altitude_km``: the lower end at GTOC9's least perigee (6600 km) keeps every arc of
the leg above it (a transfer's perigee is the lower of its two circular radii).

Units: dates in days from :attr:`Gtoc9Legs.start_mjd2000`; ΔV in m/s; radii in m.

References
----------
.. [1] M. Cerf, "Multiple Space Debris Collecting Mission — Debris Selection and Trajectory
   Optimization", Journal of Optimization Theory and Applications 156(3), 761–796, 2013
   (Part III, Eq. 7-13).
.. [2] ESA Advanced Concepts Team, "GTOC9: The Kessler Run", problem, equations and
   constants pages, https://kelvins.esa.int/gtoc9-kessler-run/ (2017).
"""

from __future__ import annotations

import os
from dataclasses import dataclass

import numpy as np
import pandas as pd

from ..flight.gtoc9_ephemeris import GTOC9_J2, GTOC9_MU, GTOC9_R_EQ
from ..inputs.formats import read_catalog
from ..physics import eccentricity as ecc
from ..physics.leg_bounds import LegCosts
from ..physics.orbits import SECONDS_PER_DAY, hohmann_dv, raan_rate
from ..physics.transfer import LegAtDates, NodeOrbits
from .debris import MJD2000, find_debris_file
from .rules import DEFAULT_RULES, Gtoc9Rules

DRIFT_TOP_KM = 2000.0
"""The highest drift orbit [km above r_eq]: the package's own limit on drift altitudes."""
DIRECT_MIN_DAYS = 1.0
"""The shortest direct leg [days] (its phasing's price grows as 1 / T)."""


@dataclass(frozen=True, eq=False, repr=False)
class Gtoc9Legs:
    """Every debris-to-debris leg of GTOC9's catalog, priced on its dates (module docstring).

    Build it with :meth:`build`.  Edge ``e`` runs from debris ``origin[e]`` to
    ``target[e]`` (catalog rows, which are GTOC9's ids: row k is debris k);
    :meth:`edge` gives the edge of a pair.

    Attributes
    ----------
    ids : tuple of str
        The catalog's ids, row by row.
    origin, target : ndarray of int
        The edges' ends (rows), shape (E,).
    table : LegCosts
        The edges' cost tables, in the impulsive model with the eccentricity priced.
    start_mjd2000 : float
        Day 0 of the dates [MJD2000].
    rule : str
        The drift inclination rule (``"free"``: either debris' inclination).
    """

    ids: tuple[str, ...]
    origin: np.ndarray
    target: np.ndarray
    table: LegCosts
    start_mjd2000: float
    rule: str = "free"
    j2: float = GTOC9_J2
    direct: bool = False
    """Price the direct leg too (module docstring); False (default): the drift leg alone,
    the structure GTOC9 legs have been flown with (:mod:`.flying`)."""

    @classmethod
    def build(cls, path: str | os.PathLike | None = None, *, rules: Gtoc9Rules = DEFAULT_RULES,
              drift_altitude_km: tuple[float, float] | None = None,
              eccentricity: bool = True, direct: bool = False) -> Gtoc9Legs:  # fmt: skip
        """The legs of GTOC9's debris file ``path`` (default :func:`find_debris_file`).

        Parameters
        ----------
        rules : Gtoc9Rules
            The window's start is day 0; the least perigee is the lowest drift radius.
        drift_altitude_km : (float, float), optional
            Drift orbit altitudes [km above r_eq] (default: GTOC9's least perigee to
            :data:`DRIFT_TOP_KM`).
        eccentricity : bool
            Price the eccentricity each leg changes (default); False: the paper's
            circular legs.
        direct : bool
            Price the direct leg too (module docstring; not yet flown, so off by default).
        """
        path = find_debris_file() if path is None else path
        start = MJD2000 + pd.Timedelta(days=rules.start_mjd2000)
        frame = read_catalog(path, "gtoc9", start=start).frame
        if drift_altitude_km is None:
            drift_altitude_km = ((rules.min_perigee_m - GTOC9_R_EQ) / 1e3, DRIFT_TOP_KM)
        a, e = 1e3 * frame["a_km"].to_numpy(float), frame["e"].to_numpy(float)
        inc = np.radians(frame["inc_deg"].to_numpy(float))
        since_epoch = (rules.start_mjd2000 - (pd.to_datetime(frame["epoch"], utc=True) - MJD2000)
                       .dt.total_seconds().to_numpy(float) / 86400.0) * SECONDS_PER_DAY
        constants = {"j2": GTOC9_J2, "mu": GTOC9_MU, "r_eq": GTOC9_R_EQ}
        rate = raan_rate(a, e, inc, **constants)
        raan = np.radians(frame["raan_epoch_deg"].to_numpy(float)) + rate * since_epoch
        orbits = NodeOrbits(a, inc, raan, rate)
        count = len(frame)
        origin, target = np.nonzero(~np.eye(count, dtype=bool))
        pairs = None
        if eccentricity:
            argp = np.radians(frame["argp_deg"].to_numpy(float))
            vectors = ecc.Eccentricities.from_elements(a, e, inc, argp, frozen=False,
                                                       **constants)  # fmt: skip
            vectors = ecc.Eccentricities.from_elements(
                a, e, inc, argp + vectors.argp_rate * since_epoch, frozen=False, **constants)
            pairs = (vectors.take(origin), vectors.take(target))
        a_low, a_high = (GTOC9_R_EQ + 1e3 * h for h in drift_altitude_km)
        table = LegCosts.build(orbits.take(origin), orbits.take(target), a_low, a_high,
                               mu=GTOC9_MU, eccentricity=pairs)  # fmt: skip
        return cls(tuple(frame["id"].astype(str)), origin, target, table,
                   float(rules.start_mjd2000), direct=direct)

    @property
    def count(self) -> int:
        """Debris in the catalog."""
        return len(self.ids)

    def edge(self, i, j) -> np.ndarray:
        """The edge index of the legs from rows ``i`` to rows ``j`` (``i != j``)."""
        i, j = np.asarray(i), np.asarray(j)
        return i * (self.count - 1) + j - (j > i)

    def cost(self, i, j, t_depart, t_arrive) -> LegAtDates:
        """The cheapest leg from debris ``i`` leaving at ``t_depart`` to debris ``j``
        arriving at ``t_arrive`` [days] (broadcast): ΔV [m/s] (``inf`` where neither
        structure joins them), its drift radius and inclination (a direct leg's: the
        target's), its side (0: a direct leg)."""
        e = self.edge(i, j)
        drift = self.table.cost_at(e, t_depart, t_arrive, rule=self.rule, j2=self.j2)
        if not self.direct:
            return drift
        dv = self.direct_cost(e, t_depart, t_arrive)
        better = dv < drift.cost
        target = self.table.target
        return LegAtDates(np.where(better, dv, drift.cost),
                          np.where(better, target.a[e], drift.a_drift),
                          np.where(better, target.inc[e], drift.inc_drift),
                          np.where(better, 0.0, drift.side), drift.laps)  # fmt: skip

    def _least_plane_angle(self, e, t1, t2):
        """The least angle [rad] between the planes of edges ``e``' debris over dates
        ``[t1, t2]`` [days]: at an end, or where their RAANs cross."""
        o, t = self.table.origin, self.table.target
        gap1, gap2 = (np.angle(np.exp(1j * (t.raan[e] - o.raan[e] + (t.rate[e] - o.rate[e])
                                            * np.asarray(d) * SECONDS_PER_DAY)))
                      for d in (t1, t2))  # fmt: skip
        i1, i2 = o.inc[e], t.inc[e]

        def angle(gap):
            cos = np.cos(i1) * np.cos(i2) + np.sin(i1) * np.sin(i2) * np.cos(gap)
            return np.arccos(np.clip(cos, -1.0, 1.0))

        # the gap moves linearly (by far less than a turn over a leg): a sign change inside
        # with both ends near zero is a crossing
        crossing = (np.sign(gap1) != np.sign(gap2)) & (np.abs(gap1 - gap2) < np.pi)
        least = np.minimum(angle(gap1), angle(gap2))
        return np.where(crossing, np.abs(i2 - i1), least)

    def _phasing(self, e, days):
        """The direct leg's phasing at worst [m/s] over ``days`` (module docstring)."""
        a = self.table.target.a[e]
        n = np.sqrt(GTOC9_MU / a**3)
        with np.errstate(divide="ignore"):
            return np.sqrt(GTOC9_MU / a) * np.pi / (1.5 * n * days * SECONDS_PER_DAY)

    def direct_cost(self, e, t_depart, t_arrive) -> np.ndarray:
        """The direct leg's ΔV [m/s] of edges ``e`` between the dates [days] (module
        docstring; ``inf`` for legs shorter than :data:`DIRECT_MIN_DAYS`)."""
        e, t_depart, t_arrive = np.broadcast_arrays(e, np.asarray(t_depart, float),
                                                    np.asarray(t_arrive, float))  # fmt: skip
        o, t = self.table.origin, self.table.target
        days = t_arrive - t_depart
        plane = self._least_plane_angle(e, t_depart, t_arrive)
        dv = hohmann_dv(o.a[e], t.a[e], plane, mu=GTOC9_MU) + self._phasing(e, days)
        if self.table.eccentricity is not None:
            first, second = (v.take(e) for v in self.table.eccentricity)
            turn = ecc.drift_argp_rate(t.a[e], t.inc[e], j2=self.j2, mu=GTOC9_MU,
                                       r_eq=GTOC9_R_EQ)  # fmt: skip
            need = ecc.required_change(first, second, t_depart * SECONDS_PER_DAY,
                                       t_arrive * SECONDS_PER_DAY, turn)  # fmt: skip
            rho = ecc.room(o.a[e], t.a[e], t.a[e])
            dv = ecc.priced(dv, need, rho, ecc.speed(first, second, mu=GTOC9_MU))
        return np.where(days >= DIRECT_MIN_DAYS, dv, np.inf)

    def bound(self, i, j, t1, t2, t3, t4) -> np.ndarray:
        """A lower bound [m/s] of :meth:`cost` over departures in ``[t1, t2]`` and
        arrivals in ``[t3, t4]`` [days] (broadcast)."""
        e = self.edge(i, j)
        drift = self.table.box_bound(e, t1, t2, t3, t4, rule=self.rule, j2=self.j2)
        if not self.direct:
            return drift
        o, t = self.table.origin, self.table.target
        longest = np.asarray(t4, float) - np.asarray(t1, float)
        direct = (hohmann_dv(o.a[e], t.a[e], self._least_plane_angle(e, t1, t4), mu=GTOC9_MU)
                  + self._phasing(e, np.maximum(longest, DIRECT_MIN_DAYS)))  # fmt: skip
        shortest_possible = longest >= DIRECT_MIN_DAYS
        return np.minimum(drift, np.where(shortest_possible, direct, np.inf))

    def floor(self) -> np.ndarray:
        """The cheapest leg of each edge at any date [m/s], shape (E,): the circular part
        only (the eccentricity's price is >= 0), a bound of :meth:`cost` everywhere (the
        direct leg's least, a Hohmann transfer with the inclination change alone, is the
        drift leg drifting on the target's orbit, so is never below it)."""
        return self.table.floor(np.arange(len(self.origin)))
