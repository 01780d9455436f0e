"""A flown plan: its manoeuvres, its rendezvous, its trajectory, and the files that hold them.

:class:`Flight` is what :func:`~sdc_cvx.flight.replay.fly` returns.  ``save(run_folder)``
writes ``flight/`` inside a run folder, the whole folder at once (written aside, then
swapped in, as the run folder itself is):

- ``maneuvers.csv``: ``epoch_utc, leg, kind, dv_mps, dv_r_mps, dv_t_mps, dv_n_mps,
  dv_x_mps, dv_y_mps, dv_z_mps`` (RTN: radial, transverse, normal of the state before the
  impulse; x, y, z in GCRF); a low-thrust flight's thrust arcs add ``end_utc,
  accel_mps2, law`` (empty for its impulses), ``epoch_utc`` being the arc's start (an
  arc's ``dv_mps`` is its acceleration times its duration; its vectors the thrust
  integrated, the RTN one in the turning local frame: a net change of velocity far below
  ``dv_mps`` over several orbits, not a burn's direction);
- ``rendezvous.csv``: per arrival ``epoch_utc, target, miss_km, miss_mps, da_km, di_deg,
  draan_deg, correction_dv_mps, phasing_shift_h, phasing_dv_mps``, then ``delay_days``
  (the ``arrive`` impulse after the plan's arrival) and ``in_time`` (the corrections done
  by the plan's departure from that debris, or its end); ``da_km, di_deg, draan_deg``
  measured just after the ``arrive`` impulse, ``epoch_utc, miss_km, miss_mps`` after the
  corrections (the vehicle on the debris' orbit), ``correction_dv_mps`` the leg's flown
  ΔV less the plan's and the phasing's (negative where the flight's transfers cost less);
- ``trajectory.oem``: CCSDS OEM 2.0 (KVN, GCRF, UTC), one segment per arc between impulses;
- ``flight.json``: the totals, the force model and the status (with a vehicle whose
  propellant the plan computed, ``propellant``: the flight's by the rocket equation
  against the plan's and the tank); ``flight.png``: misses and ΔV per leg, the
  propagated altitude against the plan's.
"""

from __future__ import annotations

import json
import os
import shutil
from dataclasses import dataclass
from pathlib import Path

import numpy as np
import pandas as pd

from ..errors import FolderError, OutputError
from ..inputs.vehicle import PropellantBudget, propellant_budget
from ..physics.orbits import SECONDS_PER_DAY
from ..report.atomic import write_atomic
from ..report.out_folder import FLIGHT_FILES, FLIGHT_FOLDER, is_ours, writable_problem
from .oem import write_oem
from .plan import FlightError, FlightPlan, miss_text
from .propagation import ForceModel

MANEUVER_COLUMNS = ("epoch_utc", "leg", "kind", "dv_mps", "dv_r_mps", "dv_t_mps", "dv_n_mps",
                    "dv_x_mps", "dv_y_mps", "dv_z_mps")  # fmt: skip
MISSED_KM = 100.0
"""A rendezvous farther than this from its debris after the corrections is *missed* [km]
(the flights of README's table end within 21 km; a plan flown against debris that
moved as it did not expect ends hundreds of km away)."""
RENDEZVOUS_COLUMNS = ("epoch_utc", "target", "miss_km", "miss_mps", "da_km", "di_deg",
                      "draan_deg", "correction_dv_mps", "phasing_shift_h", "phasing_dv_mps",
                      "delay_days", "in_time")  # fmt: skip


def flight_folder_problem(run_folder) -> str | None:
    """Why ``run_folder/flight/`` may not be (re)written, or None: it holds a file a flight
    does not write (the user's: never replaced)."""
    target = Path(run_folder) / FLIGHT_FOLDER
    if target.exists() and not is_ours(target, ()):
        return (f"{target} holds files sdc_cvx did not write: move them, or the flight is "
                "not written there")
    return None


@dataclass(frozen=True)
class Maneuver:
    """One impulse: epoch [s after the plan's day 0], leg (1-based), kind, vectors [m/s].

    A thrust arc (a low-thrust vehicle's) also has its end ``end_s`` [s], its acceleration
    ``accel_mps2`` and its direction ``law`` (:mod:`~sdc_cvx.flight.thrust`); its vectors
    are the thrust integrated over the arc (RTN: in the turning local frame), its ΔV the
    acceleration times the duration.
    """

    epoch_s: float
    leg: int
    kind: str
    dv_gcrf: np.ndarray
    dv_rtn: np.ndarray
    end_s: float | None = None
    accel_mps2: float | None = None
    law: str | None = None

    @property
    def dv_mps(self) -> float:
        if self.end_s is not None:
            return float(self.accel_mps2 * (self.end_s - self.epoch_s))
        return float(np.linalg.norm(self.dv_gcrf))


@dataclass(frozen=True)
class Rendezvous:
    """One arrival, measured after its ``arrive`` impulse (see the module docstring)."""

    epoch_s: float
    target: str
    miss_km: float
    miss_mps: float
    da_km: float
    di_deg: float
    draan_deg: float
    correction_dv_mps: float
    phasing_shift_h: float
    phasing_dv_mps: float
    delay_days: float
    in_time: bool


@dataclass(frozen=True)
class Flight:
    """The plan flown: manoeuvres, rendezvous, trajectory segments (see the module)."""

    plan: FlightPlan
    maneuvers: tuple[Maneuver, ...]
    rendezvous: tuple[Rendezvous, ...]
    segments: tuple
    force: ForceModel
    rates: str
    seconds: float
    notes: tuple[str, ...] = ()
    frame: str = "GCRF"
    """The frame of the states and vectors: ``GCRF`` (SGP4 debris), or ``EME2000`` for
    GTOC9's (its elements' frame, J2 about its z axis)."""

    # -- totals ---------------------------------------------------------------------
    @property
    def plan_dv_mps(self) -> float:
        """The plan's transfer ΔV [m/s] (operations at the debris excluded)."""
        return self.plan.plan_dv_mps

    @property
    def flown_dv_mps(self) -> float:
        """Sum of the impulses flown, corrections included [m/s]."""
        return float(sum(m.dv_mps for m in self.maneuvers))

    @property
    def worst_miss_km(self) -> float:
        return float(max((r.miss_km for r in self.rendezvous), default=np.nan))

    @property
    def complete(self) -> bool:
        """Every leg flown (a leg that cannot arrive near T_max is not, nor those after)."""
        return len(self.rendezvous) == len(self.plan.legs)

    @property
    def end_day(self) -> float:
        """Mission duration as flown [days]: the last rendezvous (its corrections done),
        then the plan's operations at the last debris."""
        last = self.plan.legs[-1]
        if not self.rendezvous:
            return np.nan
        return self.rendezvous[-1].epoch_s / SECONDS_PER_DAY + (self.plan.plan_end_day
                                                                - last.arrival_day)  # fmt: skip

    @property
    def within_tmax(self) -> bool:
        return self.end_day <= self.plan.tmax_days + 1e-9

    @property
    def propellant(self) -> PropellantBudget | None:
        """The flight's propellant and masses by the rocket equation
        (:func:`~sdc_cvx.inputs.vehicle.propellant_budget`): each leg's flown ΔV (a leg
        not flown, the plan's) and the plan's operations at each debris; None without a
        vehicle whose propellant the plan computed (:class:`~sdc_cvx.flight.plan.PlannedTank`)."""
        tank = self.plan.tank
        if tank is None:
            return None
        legs = [sum(m.dv_mps for m in self.maneuvers if m.leg == k + 1)
                if k < len(self.rendezvous) else leg.dv_mps
                for k, leg in enumerate(self.plan.legs)]  # fmt: skip
        return propellant_budget(tank.vehicle, legs, tank.operations_dv_mps)

    @property
    def status(self) -> str:
        """``flown``; ``late`` when the flight ends after T_max; ``incomplete`` when a leg
        could not be flown (``notes`` says which and why); ``missed`` when a rendezvous
        stays more than :data:`MISSED_KM` from its debris; ``over_capacity`` when the
        flight burns more propellant than the vehicle's tank holds."""
        if not self.complete:
            return "incomplete"
        if self.worst_miss_km > MISSED_KM:
            return "missed"
        if (burnt := self.propellant) is not None and not burnt.fits:
            return "over_capacity"
        return "flown" if self.within_tmax else "late"

    @property
    def planned_dv_flown_mps(self) -> float:
        """The plan's ΔV of the legs flown [m/s] (all of them when the flight is complete):
        what the flown ΔV compares with."""
        return float(sum(leg.dv_mps for leg in self.plan.legs[: len(self.rendezvous)]))

    def warning(self) -> str | None:
        """What a user must not miss about this flight (None: it flew as planned)."""
        if not self.complete:
            return f"incomplete flight: {self.notes[-1]}"
        if self.worst_miss_km > MISSED_KM:
            return (f"a rendezvous missed by {self.worst_miss_km:.0f} km (more than "
                    f"{MISSED_KM:g} km): the corrections did not close it")  # fmt: skip
        if (burnt := self.propellant) is not None and not burnt.fits:
            return (f"the flight burns {burnt.needed_kg:.1f} kg of propellant (the plan "
                    f"{self.plan.tank.planned_kg:.1f} kg), the tank holds "
                    f"{burnt.capacity_kg:.1f} kg")  # fmt: skip
        if not self.within_tmax:
            return f"the flight ends on day {self.end_day:.2f}, after T_max"
        return None

    def summary(self) -> str:
        base = self.planned_dv_flown_mps
        extra = 100.0 * (self.flown_dv_mps / base - 1.0) if base else 0.0
        limit = "within" if self.within_tmax else "LATE: beyond"
        limit += f" T_max {self.plan.tmax_days:g} d"
        planned = f"plan {self.plan_dv_mps:.2f} m/s"
        ends = f"ends day {self.end_day:.2f}"
        if not self.complete:  # its end is the last debris met, not the mission's
            limit = f"INCOMPLETE: {self.notes[-1]}"
            ends = f"the last debris met on day {self.end_day:.2f}"
            planned += (f" ({base:.2f} m/s over the {len(self.rendezvous)} of "
                        f"{len(self.plan.legs)} legs flown)")  # fmt: skip
        met = (f"worst miss {miss_text(self.worst_miss_km)}; {ends}" if self.rendezvous
               else "no debris met")  # fmt: skip
        line = (f"flight    {planned}, flown {self.flown_dv_mps:.2f} m/s "
                f"({extra:+.2f} %), {met}, {limit} ({self.force.describe()['name']}, "
                f"{self.rates} rates, {self.seconds:.0f} s)")  # fmt: skip
        if (burnt := self.propellant) is None:
            return line
        tank = ("" if burnt.capacity_kg is None else f" of a {burnt.capacity_kg:.1f} kg tank"
                + ("" if burnt.fits else ": OVER CAPACITY"))  # fmt: skip
        return (f"{line}\n          propellant flown {burnt.needed_kg:.1f} kg (the plan "
                f"{self.plan.tank.planned_kg:.1f} kg){tank}")  # fmt: skip

    # -- tables -----------------------------------------------------------------------
    def epochs(self, seconds) -> pd.DatetimeIndex:
        """UTC epochs of ``seconds`` after the plan's day 0."""
        return self.plan.start + pd.to_timedelta(np.atleast_1d(seconds), unit="s")

    def maneuvers_frame(self) -> pd.DataFrame:
        rtn_names, gcrf_names = ("dv_r_mps", "dv_t_mps", "dv_n_mps"), MANEUVER_COLUMNS[7:]
        rows = [{"leg": m.leg, "kind": m.kind, "dv_mps": m.dv_mps,
                 **dict(zip(rtn_names, map(float, m.dv_rtn), strict=True)),
                 **dict(zip(gcrf_names, map(float, m.dv_gcrf), strict=True))}
                for m in self.maneuvers]  # fmt: skip
        frame = pd.DataFrame(rows, columns=MANEUVER_COLUMNS[1:])
        frame.insert(0, "epoch_utc", _iso(self.epochs([m.epoch_s for m in self.maneuvers])))
        arcs = [m.end_s is not None for m in self.maneuvers]
        if any(arcs):  # a low-thrust flight: its thrust arcs' ends, accelerations, laws
            ends = _iso(self.epochs([m.end_s if arc else m.epoch_s
                                     for m, arc in zip(self.maneuvers, arcs, strict=True)]))
            frame["end_utc"] = [end if arc else "" for end, arc in zip(ends, arcs, strict=True)]
            frame["accel_mps2"] = [m.accel_mps2 for m in self.maneuvers]
            frame["law"] = [m.law or "" for m in self.maneuvers]
        return frame

    def rendezvous_frame(self) -> pd.DataFrame:
        rows = [{name: getattr(r, name) for name in RENDEZVOUS_COLUMNS[1:]}
                for r in self.rendezvous]  # fmt: skip
        frame = pd.DataFrame(rows, columns=RENDEZVOUS_COLUMNS[1:])
        frame.insert(0, "epoch_utc", _iso(self.epochs([r.epoch_s for r in self.rendezvous])))
        return frame

    def to_dict(self) -> dict:
        """``flight.json``: totals, status, force model and rates, notes (null: not known)."""
        out = {
            "status": self.status,
            "plan_dv_mps": self.plan_dv_mps,
            "flown_dv_mps": self.flown_dv_mps,
            "phasing_dv_mps": float(sum(r.phasing_dv_mps for r in self.rendezvous)),
            "correction_dv_mps": float(sum(r.correction_dv_mps for r in self.rendezvous)),
            "worst_miss_km": self.worst_miss_km,
            "end_day": self.end_day,
            "tmax_days": self.plan.tmax_days,
            "start": self.plan.start.isoformat(),
            "force": self.force.describe(),
            "frame": self.frame,
            "rates": self.rates,
            "seconds": self.seconds,
            "propellant": self._propellant_dict(),
            "notes": list(self.notes),
        }
        return {k: (None if isinstance(v, float) and not np.isfinite(v) else v)
                for k, v in out.items()}

    def _propellant_dict(self) -> dict | None:
        """``flight.json``'s ``propellant`` [kg]: flown, planned, the tank, margin, fit."""
        if (burnt := self.propellant) is None:
            return None
        return {"flown_kg": burnt.needed_kg, "planned_kg": self.plan.tank.planned_kg,
                "capacity_kg": burnt.capacity_kg, "margin_kg": burnt.margin_kg,
                "fits": burnt.fits}  # fmt: skip

    # -- files ------------------------------------------------------------------------
    @classmethod
    def load(cls, folder) -> Flight:
        """The flight :meth:`save` wrote in ``folder`` (a run folder flown, or its
        ``flight/``), for a notebook: tables, totals, status and trajectory as saved, the
        plan the run folder's ``solution.json`` (:meth:`sdc_cvx.Solution.load`).

        Raises
        ------
        FlightError
            No flight there, or a file that is not what ``save`` writes.
        """
        from .reopen import read_flight

        return read_flight(folder, cls, Maneuver, Rendezvous)

    def save(self, run_folder) -> list[str]:
        """Write ``run_folder/flight/`` at once (aside, then swapped in; ``run_folder``
        made if need be); the paths written.

        An earlier ``flight/`` is replaced only when it holds nothing but the files a
        flight writes: a folder of the user's there is refused (:class:`FlightError`).

        Raises
        ------
        FlightError
            ``run_folder/flight/`` holds files of the user's.
        OutputError
            ``run_folder`` is not a path.
        FolderError
            Nothing can be written there (a file on the way, a name too long, a place
            that refuses new files): checked before anything is written.
        """
        if isinstance(run_folder, bytes) or not isinstance(run_folder, str | os.PathLike):
            raise OutputError(f"Flight.save(run_folder): run_folder must be a path (a str or "
                              f"os.PathLike), got {run_folder!r}")  # fmt: skip
        run_folder = Path(run_folder)
        if run_folder.exists() and not run_folder.is_dir():
            raise FolderError(f"Flight.save: {run_folder} is a file, not a (run) folder")
        if (problem := writable_problem(run_folder, "flight folder")) is not None:
            raise FolderError(f"Flight.save: {problem}")
        target = run_folder / FLIGHT_FOLDER
        if (problem := flight_folder_problem(run_folder)) is not None:
            raise FlightError(problem)
        stage = run_folder / f".{FLIGHT_FOLDER}.{os.getpid()}.partial"
        shutil.rmtree(stage, ignore_errors=True)
        stage.mkdir(parents=True)  # the run folder too, where the plan was not saved
        try:
            names = self._write(stage)
            old = run_folder / f".{FLIGHT_FOLDER}.{os.getpid()}.old"
            if target.exists():
                os.replace(target, old)
            os.replace(stage, target)
            shutil.rmtree(old, ignore_errors=True)
        except BaseException:
            shutil.rmtree(stage, ignore_errors=True)
            raise
        return [str(target / name) for name in names]

    def _write(self, folder: Path) -> list[str]:
        write_atomic(folder / "maneuvers.csv",
                     self.maneuvers_frame().to_csv(index=False, float_format="%.10g"))  # fmt: skip
        write_atomic(folder / "rendezvous.csv",
                     self.rendezvous_frame().to_csv(index=False, float_format="%.10g"))  # fmt: skip
        write_atomic(folder / "flight.json",
                     json.dumps(self.to_dict(), indent=2, allow_nan=False) + "\n")  # fmt: skip
        segments = [(self.epochs(t), r, v) for t, r, v in self.segments]
        first = self.plan.catalog.frame["id"].iloc[0]
        pole = ("zonal terms about the true pole of date (TEME z axis) at the middle of each "
                "leg" if self.frame == "GCRF" else "J2 about the frame's z axis (GTOC9's "
                "elements' frame, its debris by GTOC9's ephemeris)")  # fmt: skip
        write_oem(folder / "trajectory.oem", segments, object_name="SDC_CVX VEHICLE",
                  object_id=f"SDC_CVX-{first}", ref_frame=self.frame,
                  comments=(f"sdc_cvx flown plan {' -> '.join(self.plan.catalog.frame['id'])}",
                            f"force model {_force_text(self.force.describe())}",
                            f"{pole}; manoeuvres (impulses, thrust arcs) in "
                            "maneuvers.csv"))  # fmt: skip
        from .plot import flight_figure  # matplotlib only when the files are written

        flight_figure(self, folder / "flight.png")
        return sorted(FLIGHT_FILES)

    def altitude_profile(self) -> tuple[np.ndarray, np.ndarray]:
        """Propagated altitude [km] against days after day 0 (every OEM sample)."""
        days = np.concatenate([t for t, _, _ in self.segments]) / SECONDS_PER_DAY
        radius = np.concatenate([np.linalg.norm(r, axis=1) for _, r, _ in self.segments])
        return days, (radius - self.force.r_eq) / 1e3


def _iso(epochs: pd.DatetimeIndex) -> list[str]:
    return [e.strftime("%Y-%m-%dT%H:%M:%S.%fZ") for e in epochs.tz_convert("UTC")]


def _force_text(model: dict) -> str:
    """The force model for a comment line: ``j2 (mu 3.986004418e+14 m^3/s^2, ...)``."""
    terms = [f"mu {model['mu']:.10g} m^3/s^2", f"r_eq {model['r_eq']:.10g} m"]
    terms += [f"{name.upper()} {model[name]:.9g}" for name in ("j2", "j3", "j4") if model[name]]
    if model["drag"]:
        terms.append(f"drag: Cd {model['cd']:g}, A/m {model['area_to_mass_m2_per_kg']:g} "
                     f"m^2/kg, atmosphere {model['atmosphere']}")  # fmt: skip
    return f"{model['name']} ({', '.join(terms)})"
