"""Mission parameters: the knobs of the paper's Eq. 16 / Eq. 22 and of the pre-optimisation.

A frozen dataclass, validated on construction, in the units people use (days, km,
m/s).  Defaults are the paper's application case (Part V).

Equation, table and part numbers are those of Cerf's paper [1]_; the design
rationale is in ``docs/design.md``.

References
----------
.. [1] M. Cerf, "Multiple Space Debris Collecting Mission — Debris Selection and Trajectory
   Optimization", Journal of Optimization Theory and Applications 156(3), 761–796, 2013.
   doi:10.1007/s10957-012-0130-6
"""

from __future__ import annotations

import dataclasses
import math
import numbers
from collections.abc import Iterable
from dataclasses import dataclass

from ..errors import MissionError
from ..physics.models import TRANSFER_MODELS, TransferModel, transfer_model
from ..physics.orbits import J2, R_EARTH
from .vehicle import Vehicle

DRIFT_INCLINATION_RULES = ("table3", "free")
ECCENTRICITY_CHOICES = ("auto", "on", "off")
"""``Mission.eccentricity``: price the eccentricity a leg must change (issue 46) where the
catalog gives each debris' argument of perigee (``auto``), always, or never."""
FLIGHT_MIN_DAYS = 10.0
"""The shortest leg a flight phases cheaply [days] (issue 46, ``benchmarks/flight.py``:
a zero-length leg of the SSO rocket bodies flown in 5 days costs 1.5 m/s more than its
12.6 m/s plan, in 10 days 0.1 m/s): the default ``flight_min_days`` where a plan can fly."""


INJECTION_MIN_PERIGEE_KM = 150.0
"""Lowest perigee altitude of an injection orbit [km], that of a catalog orbit
(``inputs.catalog.MIN_PERIGEE_KM``; not imported: this module stays free of pandas)."""
INJECTION_MAX_A_KM = 100_000.0
"""Largest semi-major axis of an injection orbit [km], that of a catalog orbit
(``inputs.catalog.MAX_A_KM``): an Earth orbit; an ``a_km`` in metres is far above."""
DRIFT_ALTITUDE_RANGE_KM = (150.0, 2000.0)
"""Where a drift altitude band may lie [km]: from the lowest perigee of a catalog orbit
to the top of LEO (the catalog's limits, docs/guide/catalogues.md, "Physical domain")."""
MAX_TMAX_DAYS = 3652.5
"""The longest mission planned [days]: 10 years (beyond, drag and the debris' decay,
which the model leaves out, change the orbits more than the drift does)."""


@dataclass(frozen=True)
class Mission:
    """Parameters of a debris collecting mission (paper Part II-B, III-I, IV-B, V).

    Parameters
    ----------
    n : int
        Number of debris to remove (paper: 5).
    tmax_days : float
        Maximum mission duration T_max [days] (paper: 1 year).
    deorbit_days : float
        Duration T_deorb of the operations at each debris [days] (paper: 0).
    operations_dv_mps : float
        Cost C_k of the operations at each debris [m/s] (paper: 0, deorbit-kit scenario).
    min_transfer_days : float
        Minimum transfer duration T_min [days] (paper: 0 in Eq. 16).
    drift_altitude_km : tuple of float
        Lower and upper altitude bounds of the drift orbits above R_T [km] (paper: 400-1200),
        within :data:`DRIFT_ALTITUDE_RANGE_KM` (150-2000 km).
    preopt_days : float
        Bound T0 of the pre-optimisation on each leg's drift [days] (paper: 2 months): the
        whole leg for the impulsive model, the coast for low thrust (its spirals and plane
        change come on top).
    dv_max_mps : float
        Edges whose pre-optimised cost exceeds this are dropped [m/s] (paper's ΔVmax).
    drift_inclination : {"table3", "free"}
        Drift inclination rule: the paper's Table 3 (fastest RAAN correction), or
        ``"free"``: whichever of the two debris inclinations is cheaper.
    j2 : float
        Zonal coefficient used by all the transfer physics (docs/design.md §3).
    deorbit_by : {"kit", "vehicle"}
        Debris operations scenario (Part I-B): ``"kit"``, a deorbit kit is attached and
        the vehicle goes on from the debris orbit (cost ``operations_dv_mps``);
        ``"vehicle"``, the vehicle lowers the debris' perigee to
        ``deorbit_perigee_km``, releases it and raises its own perigee back, which adds
        those two burns to each debris' cost (the paper's "about 200 m/s per debris"
        is the first of them).
    deorbit_perigee_km : float
        Target perigee altitude of a deorbited debris [km] (``deorbit_by="vehicle"``).
    must_include, exclude : tuple of str
        Debris ids that must be visited / must not be (a single string is one id:
        ``must_include="35"`` is ``("35",)``).
    first : str, optional
        Debris id fixed as the first of the path.
    injection : (a_km, e, inc_deg, raan_deg), optional
        Orbit the launcher leaves the vehicle on at t0 (Part II-C): a fictitious debris
        fixed at the head of the path, so the first transfer's cost and duration count.
        It is not one of the ``n`` debris and has no operations.
    transfer : {"impulsive", "low-thrust"}
        Transfer model (:mod:`~sdc_cvx.physics.models`): the paper's impulsive drift
        leg, or the low-thrust leg (spiral, plane change, coast, spiral), which needs
        the vehicle's acceleration.
    vehicle : Vehicle or dict, optional
        The servicing vehicle (:class:`~sdc_cvx.inputs.vehicle.Vehicle`): its
        acceleration for ``transfer = "low-thrust"``, and the propellant and masses of
        the plan when its dry mass and Isp are given.
    eccentricity : {"auto", "on", "off"}
        Price the eccentricity each impulsive leg must change
        (:mod:`~sdc_cvx.physics.eccentricity`): ``auto`` (default) where the catalog
        gives every debris' argument of perigee (TLE, OMM, GTOC9, a CSV with
        ``argp_deg``), the paper's circular legs elsewhere (Table 5 keeps 499.99 m/s).
    flight_min_days : float, optional
        Legs shorter than this are not planned [days], on top of ``min_transfer_days``:
        the flight time a rendezvous needs to phase (a zero-length leg, RAANs meeting on
        an arrival's day, cannot be flown cheaply).  Default: :data:`FLIGHT_MIN_DAYS`
        where the catalog gives each debris' position on its orbit (an impulsive plan
        that can fly), 0 elsewhere; 0 turns it off.
    """

    n: int = 5
    tmax_days: float = 365.25
    deorbit_days: float = 0.0
    operations_dv_mps: float = 0.0
    min_transfer_days: float = 0.0
    drift_altitude_km: tuple[float, float] = (400.0, 1200.0)
    preopt_days: float = 61.0
    dv_max_mps: float = 1000.0
    drift_inclination: str = "table3"
    j2: float = J2
    deorbit_by: str = "kit"
    deorbit_perigee_km: float = 50.0
    must_include: tuple[str, ...] = ()
    exclude: tuple[str, ...] = ()
    first: str | None = None
    injection: tuple[float, float, float, float] | None = None
    transfer: str = "impulsive"
    vehicle: Vehicle | None = None
    eccentricity: str = "auto"
    flight_min_days: float | None = None

    def __post_init__(self):
        if isinstance(self.vehicle, dict):
            object.__setattr__(self, "vehicle", _vehicle_of(self.vehicle))
        if _is_sequence(self.drift_altitude_km):  # a string or a number is said, not split
            object.__setattr__(self, "drift_altitude_km", tuple(self.drift_altitude_km))
        problems = list(self._id_problems())
        for name in ("must_include", "exclude"):
            value = getattr(self, name)
            if _is_id(value):  # one id, not its characters
                value = (value,)
            if _is_sequence(value) and all(_is_id(k) for k in value):
                object.__setattr__(self, name, tuple(str(k) for k in value))
        if _is_id(self.first):
            object.__setattr__(self, "first", str(self.first))
        if _is_sequence(self.injection):
            object.__setattr__(self, "injection", tuple(self.injection))
        if problems:  # ids of the wrong type: the checks below compare ids as strings
            raise MissionError("invalid mission: " + "; ".join(problems))
        problems = list(self._problems())
        if problems:
            raise MissionError("invalid mission: " + "; ".join(problems))

    def _id_problems(self):
        """Debris ids that are not ids: a catalog's ids are strings, an integer is taken
        for its string (``5`` is ``"5"``), anything else (``5.0``, a list for ``first``)
        would never match one."""
        for name in ("must_include", "exclude"):
            value = getattr(self, name)
            if _is_id(value):
                continue
            if not _is_sequence(value):
                yield (f"{name} must be debris ids (strings or integers) or one id, got "
                       f"{value!r}")  # fmt: skip
            elif wrong := [k for k in value if not _is_id(k)]:
                yield (f"{name} must be debris ids (strings or integers), got "
                       f"{', '.join(map(repr, wrong[:5]))}{' ...' if len(wrong) > 5 else ''}")
        if self.first is not None and not _is_id(self.first):
            several = "; must_include takes several" if _is_sequence(self.first) else ""
            yield (f"first must be one debris id (a string or an integer), got "
                   f"{self.first!r}{several}")  # fmt: skip

    def _problems(self):
        if isinstance(self.n, bool) or not isinstance(self.n, numbers.Integral):
            yield f"n must be an integer, got {self.n!r}"
        elif self.n < 2:
            yield f"n must be >= 2 (a mission visits at least two debris), got {self.n}"
        numeric = ("tmax_days", "preopt_days", "dv_max_mps", "j2", "deorbit_days",
                   "operations_dv_mps", "min_transfer_days")  # fmt: skip
        wrong_type = {name for name in numeric if not _is_real(getattr(self, name))}
        for name in sorted(wrong_type):
            value = getattr(self, name)
            yield (f"{name} is missing (None): give a number" if value is None
                   else f"{name} must be a number, got {value!r}")  # fmt: skip
        infinite = {name for name in numeric if name not in wrong_type
                    and not math.isfinite(getattr(self, name))
                    and not (name == "dv_max_mps" and getattr(self, name) > 0)}  # inf: no cap
        for name in sorted(infinite):
            yield f"{name} is not finite ({getattr(self, name)!r}): give a finite number"
        wrong_type |= infinite
        for name in ("tmax_days", "preopt_days", "dv_max_mps", "j2"):
            if name not in wrong_type and not getattr(self, name) > 0:
                yield f"{name} must be > 0, got {getattr(self, name)!r}"
        for name in ("deorbit_days", "operations_dv_mps", "min_transfer_days"):
            if name not in wrong_type and not getattr(self, name) >= 0:
                yield f"{name} must be >= 0, got {getattr(self, name)!r}"
        if self.flight_min_days is not None and not (
                _is_real(self.flight_min_days) and self.flight_min_days >= 0):  # fmt: skip
            yield f"flight_min_days must be a number >= 0 (or unset), got {self.flight_min_days!r}"
        if self.eccentricity not in ECCENTRICITY_CHOICES:
            yield (f"eccentricity must be one of {', '.join(ECCENTRICITY_CHOICES)}, got "
                   f"{self.eccentricity!r}")  # fmt: skip
        if "tmax_days" not in wrong_type and self.tmax_days > MAX_TMAX_DAYS:
            yield (
                f"tmax_days must be at most {MAX_TMAX_DAYS:g} days (10 years: the model "
                f"leaves out drag and the debris' own decay), got {self.tmax_days:g}"
            )
        if wrong_type:
            return
        yield from self._option_problems()
        bounds = self.drift_altitude_km
        if not isinstance(bounds, tuple):  # a string, or one number: a band has two ends
            what = "a string" if isinstance(bounds, str) else "not a pair"
            yield (f"drift_altitude_km must be (low, high) [km], two numbers such as "
                   f"(400, 1200), got {bounds!r} ({what})")  # fmt: skip
        elif len(bounds) != 2:
            yield f"drift_altitude_km must be (low, high), got {bounds!r}"
        elif not all(_is_real(b) for b in bounds):
            yield f"drift_altitude_km must be two numbers (low, high), got {bounds!r}"
        elif not 0 < bounds[0] < bounds[1]:
            yield f"drift_altitude_km must satisfy 0 < low < high, got {bounds!r}"
        elif not DRIFT_ALTITUDE_RANGE_KM[0] <= bounds[0] < bounds[1] <= DRIFT_ALTITUDE_RANGE_KM[1]:
            low, high = DRIFT_ALTITUDE_RANGE_KM
            yield (
                f"drift_altitude_km must lie within [{low:g}, {high:g}] km, got {bounds!r}: "
                f"below {low:g} km a drift orbit decays within days, above {high:g} km it "
                "leaves LEO, where J2 drift takes centuries (the paper: 400-1200 km)"
            )
        if self.drift_inclination not in DRIFT_INCLINATION_RULES:
            yield (
                f"drift_inclination must be one of {DRIFT_INCLINATION_RULES}, "
                f"got {self.drift_inclination!r}"
            )
        if isinstance(self.n, numbers.Integral) and self.n >= 2 and self.tmax_days > 0:
            # operations at every debris (the last included) and n - 1 transfers
            floor = self.n * self.deorbit_days + (self.n - 1) * self.min_transfer_days
            if floor >= self.tmax_days:
                yield (
                    f"n * deorbit_days + (n - 1) * min_transfer_days = {floor:g} days leaves no "
                    f"time for transfers within tmax_days = {self.tmax_days:g}"
                )
            flight = self.n * self.deorbit_days + (self.n - 1) * self.shortest_leg_days
            if floor < self.tmax_days <= flight:
                yield (
                    f"n * deorbit_days + (n - 1) * flight_min_days = {flight:g} days leaves no "
                    f"time for transfers within tmax_days = {self.tmax_days:g}: lower "
                    "flight_min_days (0 turns it off)"
                )

    def check_candidates(self, ids) -> None:
        """Raise :class:`MissionError` if the mission does not fit the catalog's debris ``ids``.

        Checks that every id named by ``must_include``, ``exclude`` and ``first``
        exists, and that ``n`` debris remain once the excluded ones are removed.
        ``ids`` may also be a count (then only ``n`` is checked), or the
        :class:`~sdc_cvx.inputs.catalog.Catalog` itself: then, with
        ``deorbit_by="vehicle"``, ``deorbit_perigee_km`` must also be below the perigee
        of every candidate that is not excluded (lowering a perigee to above where it is
        would be a negative ΔV).
        """
        catalog = ids if hasattr(ids, "ids") and hasattr(ids, "a_m") else None
        if catalog is not None:
            ids = catalog.ids
        if isinstance(ids, numbers.Integral):
            ids = [f"#{k}" for k in range(ids)]
            if self.must_include or self.exclude or self.first:
                raise TypeError("check_candidates needs the catalog ids to check debris names")
        ids = [str(k) for k in ids]
        known = set(ids)
        problems = []
        for name in ("must_include", "exclude"):
            unknown = [k for k in getattr(self, name) if k not in known]
            if unknown:
                problems.append(f"{name} names debris not in the catalog: {_ids_text(unknown)}")
        if self.first is not None and self.first not in known:
            problems.append(f"first = {self.first!r} is not in the catalog")
        available = len(known - set(self.exclude))
        if self.n > available:
            excluded = f" ({len(ids) - available} excluded)" if self.exclude else ""
            problems.append(f"n = {self.n} exceeds the {available} candidate debris{excluded}")
        if catalog is not None and self.deorbit_by == "vehicle":
            problems += self._deorbit_problems(catalog)
        if problems:
            raise MissionError("; ".join(problems))

    def _deorbit_problems(self, catalog) -> list[str]:
        """``deorbit_perigee_km`` at or above a candidate's perigee (``deorbit_by="vehicle"``)."""
        perigee_km = (catalog.a_m * (1.0 - catalog.e) - R_EARTH) / 1e3
        excluded = set(self.exclude)
        high = [(float(p), k) for k, p in zip(catalog.ids, perigee_km, strict=True)
                if k not in excluded and not p > self.deorbit_perigee_km]  # fmt: skip
        if not high:
            return []
        shown = ", ".join(f"{k} at {p:.1f} km" for p, k in sorted(high)[:5])
        more = f" and {len(high) - 5} more" if len(high) > 5 else ""
        return [
            f"deorbit_perigee_km = {self.deorbit_perigee_km:g} is not below the perigee "
            f"altitude of {len(high)} candidate debris ({shown}{more}): with deorbit_by = "
            "'vehicle' each debris' perigee is lowered to deorbit_perigee_km, which must be "
            "below every candidate's perigee (the usual value is 50 km), or exclude those debris"
        ]

    def _vehicle_problems(self):
        if self.transfer not in TRANSFER_MODELS:
            yield f"transfer must be one of {TRANSFER_MODELS}, got {self.transfer!r}"
        if self.vehicle is not None and not isinstance(self.vehicle, Vehicle):
            yield f"vehicle must be a Vehicle or a table of its fields, got {self.vehicle!r}"
        elif self.transfer == "low-thrust":
            missing = (["a [vehicle] table with accel_mps2 (or thrust_n, dry_mass_kg and "
                        "propellant_kg)"] if self.vehicle is None
                       else self.vehicle.missing_for_acceleration())  # fmt: skip
            if missing:
                yield ("transfer = 'low-thrust' needs the vehicle's acceleration: missing "
                       + ", ".join(missing))  # fmt: skip
            else:
                try:
                    self.transfer_model()
                except ValueError as err:  # an acceleration the model does not hold for
                    yield f"transfer = 'low-thrust': {err}"

    @property
    def shortest_leg_days(self) -> float:
        """The shortest leg planned [days]: ``min_transfer_days``, or ``flight_min_days``
        where that is longer (unset: 0 until :meth:`for_catalog` sets it)."""
        return max(float(self.min_transfer_days), float(self.flight_min_days or 0.0))

    def for_catalog(self, catalog) -> Mission:
        """The mission with its catalog-dependent defaults set (``eccentricity`` on or
        off, ``flight_min_days`` a number), as the planner uses it.

        ``eccentricity = "auto"`` is on where every debris of ``catalog`` has an
        argument of perigee (``argp_deg``); ``flight_min_days`` unset is
        :data:`FLIGHT_MIN_DAYS` where every debris' position on its orbit and the date
        of its elements are known (a plan that can fly), 0 elsewhere.
        """
        frame = catalog.frame
        has_argp = "argp_deg" in frame.columns and bool(frame["argp_deg"].notna().all())
        changes = {}
        if self.eccentricity == "auto" and self.transfer == "impulsive":
            changes["eccentricity"] = "on" if has_argp else "off"
        elif self.eccentricity == "auto":  # the low-thrust leg prices no eccentricity
            changes["eccentricity"] = "off"
        if self.flight_min_days is None:
            placed = has_argp and "mean_anomaly_deg" in frame.columns and bool(
                frame["mean_anomaly_deg"].notna().all())  # fmt: skip
            placed |= "arglat_deg" in frame.columns and bool(frame["arglat_deg"].notna().all())
            dated = catalog.start is not None
            flies = placed and dated and self.transfer == "impulsive"
            changes["flight_min_days"] = FLIGHT_MIN_DAYS if flies else 0.0
        return self.replace(**changes) if changes else self

    def transfer_model(self) -> TransferModel:
        """The transfer model of the mission, with the vehicle's acceleration."""
        accel = self.vehicle.acceleration(self.n) if self.vehicle is not None else None
        return transfer_model(self.transfer, accel_mps2=accel)

    def _option_problems(self):
        yield from self._vehicle_problems()
        if self.deorbit_by not in ("kit", "vehicle"):
            yield f"deorbit_by must be 'kit' or 'vehicle', got {self.deorbit_by!r}"
        if self.deorbit_perigee_km is None:
            yield "deorbit_perigee_km is missing (None): give a number >= 0 [km]"
        elif not (_is_real(self.deorbit_perigee_km) and 0 <= self.deorbit_perigee_km < math.inf):
            yield ("deorbit_perigee_km must be a finite number >= 0 [km], got "
                   f"{self.deorbit_perigee_km!r}")  # fmt: skip
        both = sorted(set(self.must_include) & set(self.exclude))
        if both:
            yield f"debris both in must_include and exclude: {', '.join(both)}"
        required = set(self.must_include) | ({self.first} if self.first else set())
        if required and isinstance(self.n, numbers.Integral) and len(required) > self.n >= 2:
            yield (
                f"must_include and first name {len(required)} debris but n = {self.n}: "
                "raise n or drop some"
            )
        if self.first is not None and self.first in self.exclude:
            yield f"first = {self.first!r} is also excluded"
        if self.injection is not None:
            if self.first is not None:
                yield "first and injection cannot both be set: the injection orbit is the start"
            if not isinstance(self.injection, tuple):  # a string or a number, not split
                what = "a string" if isinstance(self.injection, str) else "not four numbers"
                yield (f"injection must be (a_km, e, inc_deg, raan_deg), four numbers, got "
                       f"{self.injection!r} ({what})")  # fmt: skip
            elif len(self.injection) != 4 or not all(_is_real(v) for v in self.injection):
                yield f"injection must be (a_km, e, inc_deg, raan_deg), got {self.injection!r}"
            else:
                a_km, e, inc, _ = self.injection
                if not a_km > R_EARTH / 1e3:
                    yield f"injection a_km must exceed the Earth's radius, got {a_km!r}"
                elif a_km > INJECTION_MAX_A_KM:
                    yield (f"injection a_km must be at most {INJECTION_MAX_A_KM:,.0f} km (an "
                           f"Earth orbit), got {a_km!r}: metres? (kilometres are expected)")
                if not 0 <= e < 1:
                    yield f"injection e must be in [0, 1), got {e!r}"
                if not 0 <= inc <= 180:
                    yield f"injection inc_deg must be in [0, 180], got {inc!r}"
                if not -36_000 <= self.injection[3] <= 36_000:  # 1e308 % 360 is noise
                    yield (f"injection raan_deg must be an angle in [-36000, 36000] deg, "
                           f"got {self.injection[3]!r}")  # fmt: skip
                perigee = a_km * (1.0 - e) - R_EARTH / 1e3
                if a_km > R_EARTH / 1e3 and 0 <= e < 1 and perigee < INJECTION_MIN_PERIGEE_KM:
                    where = "below the Earth's surface" if perigee < 0 else "too low"
                    yield (
                        f"injection perigee altitude a_km * (1 - e) - {R_EARTH / 1e3:g} must be "
                        f"at least {INJECTION_MIN_PERIGEE_KM:g} km, got {perigee:.1f} km "
                        f"({where}, from a_km = {a_km:g} and e = {e:g})"
                    )

    def requests(self) -> list[str]:
        """The options that narrow the search, as ``name = value`` text (for messages)."""
        out = [
            f"{name} = {', '.join(value) if isinstance(value, tuple) else value}"
            for name, value in (("must_include", self.must_include), ("exclude", self.exclude),
                                ("first", self.first),
                                ("min_transfer_days", self.min_transfer_days or None))
            if value
        ]  # fmt: skip
        if self.injection is not None:
            out.append(f"injection = {list(self.injection)}")
        return out

    def replace(self, **changes) -> Mission:
        """A copy with some fields changed (validated again)."""
        return dataclasses.replace(self, **changes)

    def to_dict(self) -> dict:
        """Plain dict of the parameters (lists for tuples), e.g. for JSON output.

        ``transfer`` only when not impulsive, ``vehicle`` (its fields set) only when given.
        """
        out = dataclasses.asdict(self)
        out["drift_altitude_km"] = list(self.drift_altitude_km)
        for name in ("must_include", "exclude"):
            out[name] = list(out[name])
        if self.injection is not None:
            out["injection"] = list(self.injection)
        # the impulsive model without a vehicle writes what it wrote before they existed
        # (a sweep's scenario_sha stays)
        if self.transfer == "impulsive":
            del out["transfer"]
        if self.vehicle is None:
            del out["vehicle"]
        else:
            out["vehicle"] = self.vehicle.to_dict()
        # the catalog-dependent defaults, unset, write nothing (a sweep's scenario_sha stays)
        if self.eccentricity == "auto":
            del out["eccentricity"]
        if self.flight_min_days is None:
            del out["flight_min_days"]
        return out


def _vehicle_of(table: dict) -> Vehicle:
    """A :class:`Vehicle` from a table of its fields (unknown fields named)."""
    unknown = sorted(set(table) - {f.name for f in dataclasses.fields(Vehicle)})
    if unknown:
        known = ", ".join(f.name for f in dataclasses.fields(Vehicle))
        raise MissionError(f"unknown vehicle field(s) {', '.join(unknown)}: expected {known}")
    return Vehicle(**table)


def _is_real(value) -> bool:
    return isinstance(value, numbers.Real) and not isinstance(value, bool)


def _is_id(value) -> bool:
    """A debris id as a mission takes one: a string, or an integer (``5`` is ``"5"``)."""
    return isinstance(value, str | numbers.Integral) and not isinstance(value, bool)


def _is_sequence(value) -> bool:
    """A sequence of values (a tuple, a list, an array), not a string (never split into
    its characters) nor a number."""
    return isinstance(value, Iterable) and not isinstance(value, str | bytes | dict)


def _ids_text(ids) -> str:
    """Debris ids for a message: each as written, quoted where a plain one would hide
    something (blank, spaces at an end), at most 20 of them."""
    shown = [repr(k) if (not k.strip() or k != k.strip()) else k for k in ids]
    more = f" and {len(shown) - 20} more" if len(shown) > 20 else ""
    return ", ".join(shown[:20]) + more
