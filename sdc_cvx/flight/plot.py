"""``flight.png``: what the replay found, per leg, and the altitude flown against the plan's.

The figure reads a flight through :class:`Flown`, what it draws of one: a
:class:`~sdc_cvx.flight.result.Flight` is one, and its ``save`` calls
:func:`flight_figure` (this module does not import the result's: no circle).
"""

from __future__ import annotations

from collections.abc import Sequence
from pathlib import Path
from typing import Protocol

import numpy as np
from matplotlib.figure import Figure

from ..physics.orbits import SECONDS_PER_DAY
from ..report.atomic import write_figure
from .plan import FlightPlan, miss_text
from .propagation import ForceModel

FIGURE_SIZE = (9.0, 9.0)


class Meeting(Protocol):
    """What the figure draws of a rendezvous (:class:`~sdc_cvx.flight.result.Rendezvous`)."""

    epoch_s: float
    target: str
    miss_km: float
    phasing_dv_mps: float
    correction_dv_mps: float


class Flown(Protocol):
    """What the figure draws of a flight (:class:`~sdc_cvx.flight.result.Flight`)."""

    plan: FlightPlan
    force: ForceModel
    rendezvous: Sequence[Meeting]
    status: str
    flown_dv_mps: float
    planned_dv_flown_mps: float
    complete: bool
    worst_miss_km: float

    def altitude_profile(self) -> tuple[np.ndarray, np.ndarray]: ...


def plan_altitude(flight: Flown) -> tuple[np.ndarray, np.ndarray]:
    """The plan's altitude [km] against days: at each debris, then on each drift orbit
    (impulsive transfers drawn as instants, as the model has them; a low-thrust plan's
    spirals as the straight ramps of their durations, ``|V(a) - V(a_d)| / f``)."""
    frame = flight.plan.catalog.frame
    a_km = frame["a_km"].to_numpy()
    alt = a_km - flight.force.r_eq / 1e3
    accel = flight.plan.accel_mps2
    days, heights = [0.0], [alt[0]]
    for k, leg in enumerate(flight.plan.legs):
        drift = leg.drift_a_km - flight.force.r_eq / 1e3
        out = back = 0.0
        if accel is not None:
            speed = np.sqrt(flight.force.mu / (1e3 * np.array([a_km[k], leg.drift_a_km,
                                                                a_km[k + 1]])))  # fmt: skip
            out, back = np.abs(np.diff(speed)) / accel / SECONDS_PER_DAY
        days += [leg.departure_day, leg.departure_day + out, leg.arrival_day - back,
                 leg.arrival_day]  # fmt: skip
        heights += [alt[k], drift, drift, alt[k + 1]]
    days.append(flight.plan.plan_end_day)  # the plan's end, not the flight's
    heights.append(alt[-1])
    return np.array(days), np.array(heights)


def _orbit_means(days, altitude, period_days=100.0 / 1440.0):
    """The altitude averaged over each whole orbit (about 100 min): the eccentricity's and
    the short-period terms' ripple, kilometres wide, hides the drift altitude otherwise."""
    edges = np.arange(days[0], days[-1] + period_days, period_days)
    which = np.clip(np.searchsorted(edges, days, side="right") - 1, 0, len(edges) - 1)
    counts = np.bincount(which, minlength=len(edges))
    sums = np.bincount(which, weights=altitude, minlength=len(edges))
    kept = counts > 0
    return (edges[kept] + 0.5 * period_days), sums[kept] / counts[kept]


def flight_figure(flight: Flown, path: Path, dpi: int = 110) -> None:
    """Write ``flight.png`` (:func:`flight_plot`)."""
    write_figure(flight_plot(flight), Path(path), "png", dpi)


def flight_plot(flight: Flown) -> Figure:
    """``flight.png``'s figure: ΔV per leg (top), the miss at each rendezvous (middle),
    altitudes (bottom).  The misses have a panel of their own: on a second axis of the
    ΔV panel their zero sat at the bottom, below the ΔV's zero whenever a leg's ΔV was
    negative, and a miss of a millimetre was drawn metres of ΔV below zero."""
    fig = Figure(figsize=FIGURE_SIZE, layout="constrained")
    top, middle, bottom = fig.subplots(3, 1, height_ratios=(1.0, 0.7, 1.4))
    meetings = flight.rendezvous
    legs = np.arange(1, len(meetings) + 1)
    width = 0.38
    guided = flight.plan.accel_mps2 is None  # an impulsive flight's legs are guided
    top.bar(legs - width / 2, [m.phasing_dv_mps for m in meetings], width,
            label="guided leg less the plan's" if guided else "phasing ΔV",
            color="#6baed6")  # fmt: skip
    top.bar(legs + width / 2, [m.correction_dv_mps for m in meetings], width,
            label="closed loop (trims, approach)" if guided else "correction ΔV",
            color="#fd8d3c")  # fmt: skip
    top.axhline(0.0, color="#444444", lw=0.8)
    top.set_ylabel("ΔV [m/s]")
    names = [f"leg {k}\n→ {m.target}" for k, m in zip(legs, meetings, strict=True)]
    top.set_xticks(legs, names)
    top.legend(fontsize=9, loc="best")
    metres = max((m.miss_km for m in meetings), default=0.0) < 1.0  # guided: metres at most
    scale, unit = (1e3, "m") if metres else (1.0, "km")
    middle.plot(legs, [m.miss_km * scale for m in meetings], "ko", label=f"miss [{unit}]")
    middle.set_ylabel(f"miss [{unit}]")
    middle.set_title("position miss at each rendezvous", fontsize=9)
    middle.set_xticks(legs, names)
    middle.set_xlim(top.get_xlim())
    found = [m.miss_km for m in meetings if m.miss_km > 0]
    if found and max(found) > 100.0 * min(found):  # a missed debris beside km-size misses
        middle.set_yscale("log")
    else:
        middle.set_ylim(0.0, 1.15 * max(found, default=1.0 / scale) * scale)
    middle.grid(axis="y", alpha=0.3)
    status = flight.status
    top.set_title(f"Status {status}: {flight.flown_dv_mps:.2f} m/s flown against the "
                  f"plan's {flight.planned_dv_flown_mps:.2f} m/s"
                  + ("" if flight.complete else f" ({len(meetings)} of "
                     f"{len(flight.plan.legs)} legs flown)")
                  + f"; worst miss {miss_text(flight.worst_miss_km)}", fontsize=11,
                  color="#222222" if status == "flown" else "#b2182b")  # fmt: skip
    days, altitude = flight.altitude_profile()
    bottom.plot(days, altitude, lw=0.3, color="#c6dbef", label="propagated (osculating)")
    bottom.plot(*_orbit_means(days, altitude), lw=1.2, color="#08519c",
                label="propagated, mean over each orbit")  # fmt: skip
    plan_days, plan_alt = plan_altitude(flight)
    bottom.plot(plan_days, plan_alt, lw=1.5, color="#d62728", label="plan (mean)")
    for meeting in meetings:
        bottom.axvline(meeting.epoch_s / SECONDS_PER_DAY, color="#999999", lw=0.6, ls=":")
    bottom.axvline(flight.plan.tmax_days, color="#b2182b", lw=1.0, ls="--",
                   label=f"T_max {flight.plan.tmax_days:g} d")  # fmt: skip
    bottom.set_xlabel(f"days after {flight.plan.start:%Y-%m-%d %H:%M} UTC")
    bottom.set_ylabel("altitude [km]")
    bottom.legend(fontsize=9, loc="best")
    return fig
