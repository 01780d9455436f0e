"""The servicing vehicle: masses, engine, deorbit kits, and the propellant a plan needs.

A frozen dataclass, validated on construction, in the units people use (kg, s, N,
m/s^2).  It gives the low-thrust model its acceleration and every plan its propellant
(:func:`propellant_budget`: the rocket equation leg by leg, a deorbit kit left at each
debris).

References
----------
.. [1] M. Cerf, "Multiple Space Debris Collecting Mission — Debris Selection and Trajectory
   Optimization", Journal of Optimization Theory and Applications 156(3), 761–796, 2013
   (Part I-B: deorbit kits; Part IV-D: burns short against the coast for the impulsive
   model to hold).
.. [2] K. Tsiolkovsky, the rocket equation ``dV = g0 Isp ln(m_before / m_after)``.
"""

from __future__ import annotations

import dataclasses
import math
import numbers
from dataclasses import dataclass
from typing import NamedTuple

from ..errors import MissionError

G0 = 9.80665
"""Standard gravity [m/s^2] (the exhaust speed is ``G0 * isp_s``)."""

_FIELDS = ("dry_mass_kg", "propellant_kg", "isp_s", "thrust_n", "accel_mps2", "kit_mass_kg")


@dataclass(frozen=True)
class Vehicle:
    """The servicing vehicle (every field optional; each use names what it needs).

    Parameters
    ----------
    dry_mass_kg : float, optional
        Mass without propellant and kits [kg].
    propellant_kg : float, optional
        Propellant capacity of the tank [kg].
    isp_s : float, optional
        Specific impulse [s].
    thrust_n : float, optional
        Engine thrust [N].  The low-thrust model then flies the acceleration at the
        wet mass at launch (full tank and every kit): the lowest the vehicle will have,
        so every duration is an upper bound and the plan stays flyable.
    accel_mps2 : float, optional
        Thrust acceleration [m/s^2], instead of ``thrust_n``.
    kit_mass_kg : float
        Mass of the deorbit kit left at each debris [kg] (default 0).
    """

    dry_mass_kg: float | None = None
    propellant_kg: float | None = None
    isp_s: float | None = None
    thrust_n: float | None = None
    accel_mps2: float | None = None
    kit_mass_kg: float = 0.0

    def __post_init__(self):
        problems = []
        for name in _FIELDS:
            value = getattr(self, name)
            if value is None:
                continue
            if isinstance(value, bool) or not isinstance(value, numbers.Real):
                problems.append(f"{name} must be a number, got {value!r}")
            elif not math.isfinite(value) or value < 0 or (value == 0 and name != "kit_mass_kg"):
                relation = ">= 0" if name == "kit_mass_kg" else "> 0"
                problems.append(f"{name} must be a finite number {relation}, got {value!r}")
        if self.thrust_n is not None and self.accel_mps2 is not None:
            problems.append("give thrust_n or accel_mps2, not both")
        if problems:
            raise MissionError("invalid vehicle: " + "; ".join(problems))

    def launch_mass_kg(self, kits: int) -> float | None:
        """Wet mass with a full tank and ``kits`` kits [kg] (None without the masses)."""
        if self.dry_mass_kg is None or self.propellant_kg is None:
            return None
        return self.dry_mass_kg + self.propellant_kg + kits * self.kit_mass_kg

    def acceleration(self, kits: int) -> float | None:
        """Thrust acceleration [m/s^2] the low-thrust model flies (None if unknown).

        ``accel_mps2`` when given, else ``thrust_n`` over :meth:`launch_mass_kg`.
        """
        if self.accel_mps2 is not None:
            return float(self.accel_mps2)
        mass = self.launch_mass_kg(kits)
        if self.thrust_n is None or mass is None:
            return None
        return float(self.thrust_n) / mass

    def missing_for_acceleration(self) -> list[str]:
        """The fields a low-thrust plan still needs (empty when it has an acceleration)."""
        if self.accel_mps2 is not None:
            return []
        if self.thrust_n is None:
            return ["accel_mps2 (or thrust_n with dry_mass_kg and propellant_kg)"]
        return [name for name in ("dry_mass_kg", "propellant_kg") if getattr(self, name) is None]

    def can_budget(self) -> bool:
        """Whether the propellant of a plan can be computed (dry mass and Isp known)."""
        return self.dry_mass_kg is not None and self.isp_s is not None

    def to_dict(self) -> dict:
        """The fields set, for JSON output."""
        return {k: v for k, v in dataclasses.asdict(self).items() if v is not None}


TANK_KEYS = ("propellant_needed_kg", "capacity_kg", "margin_kg", "fits")
"""The keys of a plan's ``vehicle`` block that say how it stands against its tank [kg]
(the columns a campaign's ``missions.csv`` and a sweep's ``results.csv`` take from it)."""


class PropellantBudget(NamedTuple):
    """Masses along a plan (:func:`propellant_budget`).

    Attributes
    ----------
    mass_before_kg, mass_after_kg : tuple of float
        Vehicle mass before and after each leg's burns [kg] (kits of the debris not yet
        reached aboard).
    propellant_kg : tuple of float
        Propellant each leg burns [kg].
    operations_kg : float
        Propellant of the operations at the debris (their ΔV) [kg].
    wet_mass_kg : float
        Mass at launch with the propellant the plan needs and every kit [kg].
    needed_kg : float
        Propellant the plan needs [kg].
    capacity_kg : float or None
        The tank's capacity [kg].
    """

    mass_before_kg: tuple[float, ...]
    mass_after_kg: tuple[float, ...]
    propellant_kg: tuple[float, ...]
    operations_kg: float
    wet_mass_kg: float
    needed_kg: float
    capacity_kg: float | None

    @property
    def margin_kg(self) -> float | None:
        """Capacity minus the propellant needed [kg] (negative: the tank is too small)."""
        return None if self.capacity_kg is None else self.capacity_kg - self.needed_kg

    @property
    def fits(self) -> bool:
        """The tank holds the propellant the plan needs (True when no capacity is given)."""
        return self.capacity_kg is None or self.needed_kg <= self.capacity_kg * (1 + 1e-12)


def dv_ceiling_mps(vehicle: Vehicle) -> float:
    """The most ΔV [m/s] any plan flies on the vehicle's full tank: ``G0 Isp ln(1 + P /
    (m_dry + m_kit))``.

    Every burn of a plan, legs and operations alike, happens with at least the dry mass,
    the kit of the last debris (left after its operations) and the propellant still to
    burn aboard; so ``P >= (m_dry + m_kit) (exp(ΔV / (G0 Isp)) - 1)`` for a plan of total
    ΔV, with equality when all of it is burned last.  A plan of more ΔV than this never
    fits the tank (the bound a campaign's value search uses as its ΔV budget; each
    mission found is then checked by :func:`propellant_budget`).

    Raises
    ------
    MissionError
        Without ``dry_mass_kg``, ``isp_s`` or ``propellant_kg``.
    """
    if not vehicle.can_budget() or vehicle.propellant_kg is None:
        raise MissionError("a ΔV budget from the tank needs the vehicle's dry_mass_kg, "
                           "propellant_kg and isp_s")  # fmt: skip
    lightest = float(vehicle.dry_mass_kg) + float(vehicle.kit_mass_kg)
    return G0 * float(vehicle.isp_s) * math.log1p(float(vehicle.propellant_kg) / lightest)


def propellant_budget(vehicle: Vehicle, leg_dv_mps, operations_dv_mps, *,
                      kit_at_start: bool = True) -> PropellantBudget:  # fmt: skip
    """Propellant and masses of a plan, from its end back to its launch (rocket equation).

    The vehicle ends dry.  Events in flight order: at each debris the operations burn
    ``operations_dv_mps[k]`` and the kit is left (at the first debris too, reached at
    t = 0, unless ``kit_at_start`` is False: an injection orbit), then leg k burns
    ``leg_dv_mps[k]``.  Each burn multiplies the mass by ``exp(-dV / (G0 Isp))``.

    Parameters
    ----------
    vehicle : Vehicle
        Needs ``dry_mass_kg`` and ``isp_s``.
    leg_dv_mps : sequence of float
        ΔV of each leg [m/s].
    operations_dv_mps : sequence of float
        ΔV of the operations at each node of the path [m/s] (length legs + 1).
    kit_at_start : bool
        Whether the first node is a debris (a kit is left there).

    Returns
    -------
    PropellantBudget
    """
    if not vehicle.can_budget():
        raise MissionError("a propellant budget needs the vehicle's dry_mass_kg and isp_s")
    exhaust = G0 * float(vehicle.isp_s)
    kit = float(vehicle.kit_mass_kg)
    legs = [float(v) for v in leg_dv_mps]
    ops = [float(v) for v in operations_dv_mps]
    mass = float(vehicle.dry_mass_kg)
    ops_kg = 0.0
    before, after = [0.0] * len(legs), [0.0] * len(legs)
    for k in range(len(legs), -1, -1):  # node k: its operations, its kit; then leg k - 1
        if k > 0 or kit_at_start:
            mass += kit
        burned = mass * math.expm1(ops[k] / exhaust)
        ops_kg += burned
        mass += burned
        if k == 0:
            break
        after[k - 1] = mass
        mass *= math.exp(legs[k - 1] / exhaust)
        before[k - 1] = mass
    kits = len(legs) + (1 if kit_at_start else 0)
    needed = mass - float(vehicle.dry_mass_kg) - kits * kit
    return PropellantBudget(tuple(before), tuple(after),
                            tuple(b - a for b, a in zip(before, after, strict=True)), ops_kg,
                            mass, needed, vehicle.propellant_kg)  # fmt: skip
