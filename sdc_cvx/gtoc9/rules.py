"""GTOC9's rules and constants as the validator reads them (:class:`Gtoc9Rules`).

The values are those of GTOC9's constants page ([1]_ of :mod:`sdc_cvx.gtoc9`); each is a
field of :class:`Gtoc9Rules`, so a study can relax or tighten one (``Gtoc9Rules(dt_r_days=25)``).
Units: days, m, m/s, kg, s, MEUR.
"""

from __future__ import annotations

from dataclasses import dataclass

from ..errors import MissionError

DEBRIS_COUNT = 123
"""The debris of GTOC9's ``debris.csv`` (ids 0..122)."""
FIELDS = ("epoch", "x", "y", "z", "vx", "vy", "vz", "dvx", "dvy", "dvz", "id")
"""The 11 fields of an event line, in order (epoch MJD2000; m; m/s; m/s; the event id)."""
DSM = -1
"""The event id of a deep-space manoeuvre."""


@dataclass(frozen=True)
class Gtoc9Rules:
    """GTOC9's constraints and cost (constants page; module docstring of
    :mod:`sdc_cvx.gtoc9.check` for the readings of the ambiguous ones).

    Attributes
    ----------
    start_mjd2000, end_mjd2000 : float
        The window [MJD2000]: every launch (first event) at or after ``start``, every
        mission's end (last event) at or before ``end`` (23467 + 8 years of 365.25 days).
    stay_days : float
        ``t_w``: least time between the arrival and the departure at a debris [days].
    dt_r_days : float
        ``Δt_R``: most time between consecutive rendezvous of a mission [days], measured
        from the arrival at a debris (``dt_r_from="arrival"``) or from the departure from
        it (``"departure"``: the transfer time alone) to the arrival at the next.
    dt_m_days : float
        ``Δt_M``: least time between a mission's end and the next mission's launch [days].
    min_perigee_m : float
        ``r_pm``: least osculating perigee radius on every arc [m].
    eps_r_m, eps_v_mps : float
        Rendezvous (and arc continuity) tolerances on position [m] and velocity [m/s].
    m_dry_kg, m_de_kg, max_propellant_kg : float
        Dry mass, de-orbit package mass, most propellant [kg].
    isp_s, g0_mps2 : float
        Specific impulse [s] and standard gravity [m/s^2].
    launch_cost_meur, alpha_meur_per_kg2 : float
        ``c`` (c_M, the cost of a launch since the competition ended) and ``α`` of the
        cost ``C_i = c + α (m0_i - m_dry)^2`` [MEUR, MEUR/kg^2].
    """

    start_mjd2000: float = 23467.0
    end_mjd2000: float = 26419.0
    stay_days: float = 5.0
    dt_r_days: float = 30.0
    dt_r_from: str = "arrival"
    dt_m_days: float = 30.0
    min_perigee_m: float = 6600000.0
    eps_r_m: float = 100.0
    eps_v_mps: float = 1.0
    m_dry_kg: float = 2000.0
    m_de_kg: float = 30.0
    max_propellant_kg: float = 5000.0
    isp_s: float = 340.0
    g0_mps2: float = 9.80665
    launch_cost_meur: float = 55.0
    alpha_meur_per_kg2: float = 2.0e-6

    def __post_init__(self):
        if self.dt_r_from not in ("arrival", "departure"):
            raise MissionError(f"Gtoc9Rules.dt_r_from: expected 'arrival' or 'departure', "
                               f"got {self.dt_r_from!r}")

    def cost(self, m0_kg: float) -> float:
        """A mission's cost ``c + α (m0 - m_dry)^2`` [MEUR] for a launch mass ``m0_kg`` [kg]."""
        return self.launch_cost_meur + self.alpha_meur_per_kg2 * (m0_kg - self.m_dry_kg) ** 2


DEFAULT_RULES = Gtoc9Rules()
"""GTOC9's rules as the competition set them."""
