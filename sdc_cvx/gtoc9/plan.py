"""A GTOC9 mission and campaign as planned (:class:`PlannedMission`, :class:`PlannedCampaign`).

A planned mission is its debris in visit order, each arrival and departure date [days
from the window's start] and each leg's ΔV and drift orbit in the planner's model
(:mod:`.legs`).  Its launch mass follows GTOC9's chain (:mod:`.check`): backward from
``m_dry`` after the last departure, ``+ m_de`` at each debris, ``× exp(ΔV / (Isp g0))``
over each leg, so with ``E_k = exp((ΔV_1 + ... + ΔV_k) / (Isp g0))``

``m0 = m_dry E_N + m_de (E_0 + E_1 + ... + E_N)``  (``E_0 = 1``, N legs),

and its cost ``c + α (m0 - m_dry)^2`` [MEUR] (:meth:`Gtoc9Rules.cost`).

Units: days, m/s, kg, MEUR.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from .rules import DEFAULT_RULES, Gtoc9Rules


def chain_mass(leg_dv, rules: Gtoc9Rules = DEFAULT_RULES) -> float:
    """The launch mass [kg] of a mission whose legs cost ``leg_dv`` [m/s] in visit order
    (module docstring)."""
    growth = np.exp(np.cumsum(np.asarray(leg_dv, float)) / (rules.isp_s * rules.g0_mps2))
    return float(rules.m_dry_kg * (growth[-1] if len(growth) else 1.0)
                 + rules.m_de_kg * (1.0 + growth.sum()))  # fmt: skip


@dataclass(frozen=True)
class PlannedMission:
    """One mission as planned (module docstring).

    Attributes
    ----------
    debris : tuple of int
        GTOC9 ids in visit order.
    arrivals, departures : tuple of float
        Each debris' arrival and departure [days from the window's start]; the first
        arrival is the launch, the last departure the mission's end.
    leg_dv : tuple of float
        Each leg's ΔV [m/s] (one fewer than the debris).
    a_drift, inc_drift : tuple of float
        Each leg's drift orbit [m, rad] (the flight's seed).
    """

    debris: tuple[int, ...]
    arrivals: tuple[float, ...]
    departures: tuple[float, ...]
    leg_dv: tuple[float, ...]
    a_drift: tuple[float, ...] = ()
    inc_drift: tuple[float, ...] = ()

    @property
    def launch(self) -> float:
        return self.arrivals[0]

    @property
    def end(self) -> float:
        return self.departures[-1]

    @property
    def dv(self) -> float:
        """The mission's ΔV [m/s]."""
        return float(sum(self.leg_dv))

    def m0(self, rules: Gtoc9Rules = DEFAULT_RULES) -> float:
        """Launch mass [kg]."""
        return chain_mass(self.leg_dv, rules)

    def cost(self, rules: Gtoc9Rules = DEFAULT_RULES) -> float:
        """``c + α (m0 - m_dry)^2`` [MEUR]."""
        return rules.cost(self.m0(rules))

    def fits(self, rules: Gtoc9Rules = DEFAULT_RULES) -> bool:
        """Within the propellant (``m0 - m_dry <= m_p``, :mod:`.check`'s reading)."""
        return self.m0(rules) - rules.m_dry_kg <= rules.max_propellant_kg

    def as_dict(self, rules: Gtoc9Rules = DEFAULT_RULES, start_mjd2000: float = 0.0) -> dict:
        """The mission as JSON values (dates [MJD2000] when ``start_mjd2000`` is given)."""
        return {
            "debris": list(self.debris),
            "arrivals_mjd2000": [start_mjd2000 + t for t in self.arrivals],
            "departures_mjd2000": [start_mjd2000 + t for t in self.departures],
            "leg_dv_mps": [round(v, 6) for v in self.leg_dv],
            "a_drift_m": list(self.a_drift),
            "inc_drift_rad": list(self.inc_drift),
            "dv_mps": round(self.dv, 6),
            "m0_kg": round(self.m0(rules), 6),
            "cost_meur": round(self.cost(rules), 6),
        }


@dataclass(frozen=True)
class PlannedCampaign:
    """Missions in sequence (each launched at least Δt_M after the previous one's end).

    Attributes
    ----------
    missions : tuple of PlannedMission
    lower_bound : float
        A lower bound [MEUR] on the cost J of every campaign removing all debris in the
        planner's model (``-inf`` when none is proven).
    """

    missions: tuple[PlannedMission, ...]
    lower_bound: float = -math.inf

    def cost(self, rules: Gtoc9Rules = DEFAULT_RULES) -> float:
        """J [MEUR]."""
        return float(sum(m.cost(rules) for m in self.missions))

    @property
    def removed(self) -> tuple[int, ...]:
        return tuple(k for m in self.missions for k in m.debris)

    @property
    def dv(self) -> float:
        return float(sum(m.dv for m in self.missions))

    def complete(self, count: int = 123) -> bool:
        """Every one of ``count`` debris removed."""
        return len(set(self.removed)) == count

    def as_dict(self, rules: Gtoc9Rules = DEFAULT_RULES, start_mjd2000: float = 0.0,
                count: int = 123) -> dict:
        """The campaign as JSON values: its status, J, bound and gap, the missions."""
        return {
            "status": "complete" if self.complete(count) else "incomplete",
            "removed": len(set(self.removed)),
            "debris": count,
            "J_meur": round(self.cost(rules), 6),
            "lower_bound_meur": (round(self.lower_bound, 6) if math.isfinite(self.lower_bound)
                                 else None),  # fmt: skip
            "gap": round(self.gap(rules), 6),
            "dv_mps": round(self.dv, 6),
            "missions": [m.as_dict(rules, start_mjd2000) for m in self.missions],
        }

    def gap(self, rules: Gtoc9Rules = DEFAULT_RULES) -> float:
        """``(J - bound) / J`` (1 with no bound)."""
        j = self.cost(rules)
        return 1.0 if not math.isfinite(self.lower_bound) else (j - self.lower_bound) / j
