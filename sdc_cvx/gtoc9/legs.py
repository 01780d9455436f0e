"""GTOC9's legs priced on their two dates (issue 47, item 2): :class:`Gtoc9Legs`.

A GTOC9 leg joins two debris between a departure and an arrival a few days to a few weeks
apart (the stays are 5 days, consecutive rendezvous at most Δt_R = 30 days apart).  Its
cost is the paper's impulsive drift leg (Part III: a Hohmann transfer with the plane
change combined to a circular drift orbit, the drift, a Hohmann transfer to the target;
the drift radius fixed by the two dates, Eq. 10 inverted) with the eccentricity it must
change priced (:mod:`sdc_cvx.physics.eccentricity`, issue 46): the exact cheapest such leg
of the two dates (:meth:`Gtoc9Legs.cost`) and a lower bound of it over a box of dates
(:meth:`Gtoc9Legs.bound`), both those of :class:`~sdc_cvx.physics.leg_bounds.LegCosts`
(their proofs are in ``docs/design.md``).

The debris are GTOC9's (:func:`~sdc_cvx.inputs.formats.read_catalog` with ``format =
"gtoc9"``) at the start of GTOC9's window, MJD2000 23467: dates here are days from it.
Their RAANs move at GTOC9's secular J2 rate (its equations page; GTOC9's J2, μ and r_eq),
their eccentricity vectors at its apsidal rate.  The drift orbits stay between
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

from ..inputs.formats import read_catalog
from ..inputs.mission import Mission
from ..network.edges import node_eccentricities, node_orbits
from ..physics.leg_bounds import LegCosts
from ..physics.orbits import R_EARTH
from ..physics.transfer import LegAtDates
from .debris import MJD2000, find_debris_file
from .rules import DEFAULT_RULES, Gtoc9Rules

GTOC9_J2 = 1.08262668e-3
"""GTOC9's J2 [-] (its constants page)."""
DRIFT_TOP_KM = 2000.0
"""The highest drift orbit [km above r_eq]: the package's own limit on drift altitudes."""


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

    @classmethod
    def build(cls, path: str | os.PathLike | None = None, *, rules: Gtoc9Rules = DEFAULT_RULES,
              drift_altitude_km: tuple[float, float] | None = None,
              eccentricity: bool = True) -> Gtoc9Legs:  # fmt: skip
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
        """
        path = find_debris_file() if path is None else path
        start = MJD2000 + pd.Timedelta(days=rules.start_mjd2000)
        catalog = read_catalog(path, "gtoc9", start=start)
        if drift_altitude_km is None:
            drift_altitude_km = ((rules.min_perigee_m - R_EARTH) / 1e3, DRIFT_TOP_KM)
        mission = Mission(n=2, j2=GTOC9_J2, drift_altitude_km=tuple(drift_altitude_km),
                          eccentricity="on" if eccentricity else "off")  # fmt: skip
        orbits = node_orbits(catalog, mission)
        count = len(catalog)
        origin, target = np.nonzero(~np.eye(count, dtype=bool))
        vectors = node_eccentricities(catalog, mission)
        pairs = None if vectors is None else (vectors.take(origin), vectors.take(target))
        a_low, a_high = (R_EARTH + 1e3 * h for h in drift_altitude_km)
        table = LegCosts.build(orbits.take(origin), orbits.take(target), a_low, a_high,
                               eccentricity=pairs)  # fmt: skip
        return cls(tuple(catalog.ids), origin, target, table, float(rules.start_mjd2000))

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
        arriving at ``t_arrive`` [days] (broadcast): ΔV [m/s] (``inf`` where no drift orbit
        of the band joins them), its drift radius, inclination and side."""
        return self.table.cost_at(self.edge(i, j), t_depart, t_arrive, rule=self.rule,
                                  j2=self.j2)  # fmt: skip

    def bound(self, i, j, t1, t2, t3, t4) -> np.ndarray:
        """A lower bound [m/s] of :meth:`cost` over departures in ``[t1, t2]`` and
        arrivals in ``[t3, t4]`` [days] (broadcast)."""
        return self.table.box_bound(self.edge(i, j), t1, t2, t3, t4, rule=self.rule,
                                    j2=self.j2)  # fmt: skip

    def floor(self) -> np.ndarray:
        """The cheapest leg of each edge at any date [m/s], shape (E,): the circular part
        only (the eccentricity's price is >= 0), a bound of :meth:`cost` everywhere."""
        return self.table.floor(np.arange(len(self.origin)))
