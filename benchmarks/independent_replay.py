"""Flown folders checked by physics of their own (issue 46, "How we will know").

``python -m sdc_cvx fly FOLDER`` writes ``FOLDER/flight/``; this script reads only the
files (``solution.json``, ``scenario.toml``, ``flight/maneuvers.csv``, ``rendezvous.csv``,
``flight.json``, ``trajectory.oem``) and the catalog, and with the physics of
``benchmarks/replay_physics.py`` (none of sdc_cvx's):

(a) re-integrates the vehicle by two-body + J2 (DOP853, rtol 1e-12), applying each
    impulse of ``maneuvers.csv`` (its x-y-z vector) at its epoch: each OEM arc from its own
    first state (worst difference at its end; the velocity jumps between segments against
    the impulses), and each leg flown open-loop from the debris at the leg's start against
    every OEM state of the leg (worst position and velocity);
(b) meets each rendezvous of ``rendezvous.csv`` with the debris computed here (SGP4 of the
    TLE, TEME -> GCRS by skyfield; GTOC9's ephemeris from its equations page): the miss of
    the OEM's state, of each leg flown open-loop (and the ΔV a last correction, three
    quarters of an orbit before the arrival, adds to meet it exactly), of the whole flight
    flown open-loop from the OEM's first state, and of each leg about the moving pole;
(c) adds the impulses' ``|dv|`` against ``flight.json``'s flown total and the plan's
    (``solution.json``), leg by leg; the ratio against issue 46's goals (flown at most 1.03
    times the plan for rocket bodies, 1.05 for GTOC9, 1.10 for any other).

An open-loop replay of months is ill-conditioned (1 m of semi-major axis is ~12 km along
the track after 100 days): the flight's impulses come from a closed loop in the package's
model, so its small differences from this one (the pole of date: ~31 mas between the
package's IAU 1976/1980 and skyfield's IAU 2006/2000A) grow into the open-loop misses;
the last correction says what they cost.

The pole J2 acts about is read from the OEM's header: ``GCRF`` is the Earth's true pole of
date (TEME's z axis), which the package holds constant over each leg at the leg's middle
(README "Flying a plan", the OEM's comment); the replay takes the same constant poles, from
skyfield, and also flies once with the pole moving as the Earth's does (the "moving pole"
column: what the constant pole costs). GTOC9's frame (``EME2000`` for a GTOC9 catalog):
J2 about its z axis, as GTOC9 defines it.

    python benchmarks/independent_replay.py FOLDER [FOLDER ...]     # flown folders
    python benchmarks/independent_replay.py --make sso gtoc9 sl16 rb30 deb30 band2020 gtoc9n4

``--make`` plans (``sdc_cvx run``) and flies (``sdc_cvx fly``) each case as a user would,
as subprocesses, into ``--work`` (default a temporary folder), then replays it. Cases:
``sso``, ``gtoc9``, ``sl16`` are ``benchmarks/flight.py``'s (n = 5, one year, the J2
planner's rates); the others no one tuned the flight on: ``rb30`` 30 random SSO rocket
bodies (seed 46), ``deb30`` 30 random fragments (DEB) of the 2020 catalogue at 700-850 km,
97.5-99.5 deg, ``band2020`` every object of the 2020 catalogue at 900-1000 km,
99.0-99.6 deg, ``gtoc9n4`` 40 random GTOC9 debris with n = 4. Everything found is printed,
the failures too.
"""

from __future__ import annotations

import argparse
import json
import os
import subprocess
import sys
import tempfile
import time
import tomllib
from pathlib import Path
from types import SimpleNamespace

import numpy as np
import pandas as pd

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT))
from benchmarks import replay_physics as rp  # noqa: E402

SHARED = ROOT.parent / "shared" / "data"
DAY = 86400.0
MIN_STAY_S = 60.0
"""A leg leaves a minute after the last arrival (README "Flying a plan", 3.)."""
GOAL_MISS_M, GOAL_MISS_MPS = 100.0, 0.1
GOAL_RB, GOAL_GTOC9, GOAL_ANY = 1.03, 1.05, 1.10
SEED = 46
DV_XYZ = ["dv_x_mps", "dv_y_mps", "dv_z_mps"]


# -- the cases -----------------------------------------------------------------------------
def _tle_rows(path: Path):
    """(id, altitude km, inclination deg, e, name) of each TLE (read here)."""
    lines = path.read_text(encoding="utf-8").splitlines()
    names = {b[2:7].strip(): a[2:].strip() for a, b in zip(lines[:-1], lines[1:], strict=True)
             if a.startswith("0 ") and b.startswith("1 ")}  # fmt: skip
    rows = []
    for ident, (_, two) in rp.tle_lines(path).items():
        n = float(two[52:63]) * 2.0 * np.pi / DAY
        a = (rp.MU / n**2) ** (1.0 / 3.0)
        rows.append((ident, a / 1e3 - 6378.137, float(two[8:16]), float("0." + two[26:33]),
                     names.get(ident, "")))  # fmt: skip
    return rows


def _sample(ids, count: int) -> list[str]:
    rng = np.random.default_rng(SEED)
    return sorted(rng.choice(sorted(ids), size=count, replace=False).tolist())


def case_args(case: str) -> list[str]:
    """``sdc_cvx run`` arguments of a case (module docstring)."""
    year = ["--tmax-days", "365.25", "--raan-rates", "j2"]
    sso_tle = SHARED / "sso_rocket_bodies_2020" / "sso_rb.tle"
    all_tle = SHARED / "catalog_2020" / "all_2020.tle"
    gtoc9 = SHARED / "gtoc9" / "debris_data.txt"
    if case == "sso":
        return ["--catalog", str(sso_tle), "--format", "tle", "--n", "5", *year]
    if case == "gtoc9":
        return ["--catalog", str(gtoc9), "--format", "gtoc9", "--n", "5", *year]
    if case == "sl16":
        return [str(ROOT / "examples" / "cluster_sl16_71deg.toml"), "--n", "5", *year]
    if case == "rb30":
        ids = _sample([r[0] for r in _tle_rows(sso_tle)], 30)
        return ["--catalog", str(sso_tle), "--format", "tle", "--n", "5", *year,
                *[x for i in ids for x in ("--ids", i)]]  # fmt: skip
    if case == "deb30":
        band = [r[0] for r in _tle_rows(all_tle) if 700 <= r[1] <= 850 and 97.5 <= r[2] <= 99.5
                and r[3] <= 0.01 and "DEB" in r[4]]  # fmt: skip
        return ["--catalog", str(all_tle), "--format", "tle", "--n", "5", *year,
                "--altitude-km", "700", "850", "--inclination-deg", "97.5", "99.5",
                "--max-eccentricity", "0.01",
                *[x for i in _sample(band, 30) for x in ("--ids", i)]]  # fmt: skip
    if case == "band2020":
        return ["--catalog", str(all_tle), "--format", "tle", "--n", "5", *year,
                "--altitude-km", "900", "1000", "--inclination-deg", "99.0", "99.6",
                "--max-eccentricity", "0.01"]  # fmt: skip
    if case == "gtoc9n4":
        ids = _sample(list(rp.gtoc9_rows(gtoc9)), 40)
        return ["--catalog", str(gtoc9), "--format", "gtoc9", "--n", "4", *year,
                *[x for i in ids for x in ("--ids", i)]]  # fmt: skip
    raise ValueError(f"unknown case {case!r}")


CASES = ("sso", "gtoc9", "sl16", "rb30", "deb30", "band2020", "gtoc9n4")


def make(case: str, work: Path) -> Path | None:
    """Plan and fly ``case`` into ``work/case`` by the package's CLI; the folder."""
    folder = work / case
    env = dict(os.environ, PYTHONPATH=str(ROOT))
    command = [sys.executable, "-m", "sdc_cvx"]
    for step in (["run", *case_args(case), "--out", str(folder), "--quiet"], ["fly", str(folder)]):
        start = time.perf_counter()
        done = subprocess.run(command + step, env=env, cwd=ROOT, capture_output=True, text=True)
        print(f"$ sdc_cvx {step[0]} ({case}): exit {done.returncode}, "
              f"{time.perf_counter() - start:.0f} s")  # fmt: skip
        for line in (done.stdout + done.stderr).splitlines():
            print(f"    {line}")
        if done.returncode not in (0, 3):  # 3: a flight that is late, incomplete or missed
            return None
    return folder


# -- the replay ----------------------------------------------------------------------------
def _catalog(folder: Path, override: Path | None):
    """(path, format) of the folder's catalog (``scenario.toml``, or ``override``)."""
    scenario = tomllib.loads((folder / "scenario.toml").read_text(encoding="utf-8"))
    path = Path(override or scenario["catalog"]["path"])
    if not path.is_absolute():
        path = (folder / path).resolve()
    fmt = scenario["catalog"].get("format") or path.suffix.lstrip(".")
    return path, fmt


class Debris:
    """The path's debris where this replay places them (GCRS by SGP4, or GTOC9's frame)."""

    def __init__(self, path: Path, fmt: str):
        self.gtoc9 = fmt == "gtoc9"
        self.sets = rp.gtoc9_rows(path) if self.gtoc9 else rp.tle_lines(path)
        self.names = {}
        if not self.gtoc9:
            self.names = {r[0]: r[4] for r in _tle_rows(path)}

    def state(self, ident: str, epoch: pd.Timestamp):
        epochs = pd.DatetimeIndex([epoch])
        if self.gtoc9:
            r, v = rp.gtoc9_state(self.sets[ident], epochs)
        else:
            r, v = rp.sgp4_gcrs(self.sets[ident], epochs)
        return r[0], v[0]

    def goal(self, path) -> tuple[float, str]:
        if self.gtoc9:
            return GOAL_GTOC9, "GTOC9"
        if all("R/B" in self.names.get(str(i), "") for i in path):
            return GOAL_RB, "rocket bodies"
        return GOAL_ANY, "other"


def leg_poles(solution: dict, meet_s: np.ndarray, delays_s: np.ndarray, oem_start_s: float,
              end_s: float, gtoc9: bool) -> tuple[list[np.ndarray], np.ndarray]:
    """Each leg's pole and the pole of the coast after the last rendezvous; times [s] after
    the plan's start. The package's rule (README "Flying a plan", 3.): the true pole of date
    at ``t_ready + duration / 2``, ``t_ready`` the plan's departure moved by the previous
    arrival's delay, at least a minute after the previous rendezvous."""
    legs = solution["legs"][: len(meet_s)]
    if gtoc9:
        z = np.array([0.0, 0.0, 1.0])
        return [z] * len(legs), z
    start = pd.Timestamp(solution["start"])
    middles, previous, delay = [], oem_start_s, 0.0
    for k, leg in enumerate(legs):
        ready = max(leg["departure_day"] * DAY + delay, previous + MIN_STAY_S)
        middles.append(ready + 0.5 * leg["duration_days"] * DAY)
        previous, delay = meet_s[k], delays_s[k]
    stamps = start + pd.to_timedelta(np.array(middles + [end_s]), unit="s")
    poles = rp.pole_of_date(pd.DatetimeIndex(stamps))
    return list(poles[:-1]), poles[-1]


def _moving_poles(epoch0: pd.Timestamp, t_end: float):
    """``poles_at(t)``: the pole of date moving with time, sampled every 6 hours from
    skyfield and interpolated linearly (the nutation's shortest terms: 13.7 days)."""
    step = 6 * 3600.0
    grid = np.arange(-step, t_end + 2 * step, step)
    poles = rp.pole_of_date(epoch0 + pd.to_timedelta(grid, unit="s"))
    rows = poles.tolist()

    def poles_at(t):
        k = min(max(int((t - grid[0]) // step), 0), len(grid) - 2)
        w = (t - grid[k]) / step
        a, b = rows[k], rows[k + 1]
        p = [a[c] + w * (b[c] - a[c]) for c in range(3)]
        n = (p[0] ** 2 + p[1] ** 2 + p[2] ** 2) ** 0.5
        return p[0] / n, p[1] / n, p[2] / n

    return poles_at


def load(folder: Path, catalog: Path | None = None) -> SimpleNamespace:
    """A flown folder's files, on the OEM's time axis [s after its first epoch]."""
    flight = folder / "flight"
    f = SimpleNamespace(folder=folder)
    f.solution = json.loads((folder / "solution.json").read_text(encoding="utf-8"))
    f.summary = json.loads((flight / "flight.json").read_text(encoding="utf-8"))
    f.maneuvers = pd.read_csv(flight / "maneuvers.csv")
    f.meets = pd.read_csv(flight / "rendezvous.csv", dtype={"target": str})
    f.oem = rp.read_oem(flight / "trajectory.oem")
    f.cat_path, f.fmt = _catalog(folder, catalog)
    f.debris = Debris(f.cat_path, f.fmt)
    shift = (f.oem.epoch0 - pd.Timestamp(f.solution["start"])).total_seconds()
    f.t_man = (rp.utc(f.maneuvers["epoch_utc"]) - f.oem.epoch0).total_seconds().to_numpy()
    f.t_meet = (rp.utc(f.meets["epoch_utc"]) - f.oem.epoch0).total_seconds().to_numpy()
    f.dv = f.maneuvers[DV_XYZ].to_numpy(float)
    f.t_end = float(f.oem.times[-1][-1])
    f.poles, f.last_pole = leg_poles(f.solution, f.t_meet + shift,
                                     f.meets["delay_days"].to_numpy() * DAY, shift,
                                     f.t_end + shift, f.debris.gtoc9)  # fmt: skip
    f.stops = np.array(sorted(set(f.t_man[f.t_man > 1e-6]) | {f.t_end}))
    f.seg_start = np.array([t[0] for t in f.oem.times])
    f.targets = [str(x) for x in f.meets["target"]]
    f.goal_states = [f.debris.state(x, rp.utc([e])[0])
                     for x, e in zip(f.targets, f.meets["epoch_utc"], strict=True)]  # fmt: skip
    return f


def _impulse(f, t: float) -> np.ndarray:
    return f.dv[np.abs(f.t_man - t) < 5e-6].sum(axis=0)  # the CSV's epochs: microseconds


def _segment(f, t: float) -> int | None:
    j = int(np.argmin(np.abs(f.seg_start - t)))
    return j if abs(f.seg_start[j] - t) < 1e-5 else None


def _leg_of(f, stop: float) -> int:
    return int(np.searchsorted(f.t_meet, stop - 1e-6))


def leg_rhs(f):
    """``rhs_of(stop)``: the equations of motion of the arc ending at ``stop`` [s], J2
    about its leg's pole (:func:`leg_poles`)."""
    rhs = [rp.j2_rhs(p) for p in [*f.poles, f.last_pole]]
    return lambda stop: rhs[min(_leg_of(f, stop), len(f.poles))]


def _fly(f, y, t, stops, rhs_of, compare=False):
    """Fly ``(t, y)`` through ``stops`` (each impulse applied after its stop): the states
    before each stop's impulse; the worst difference from the OEM's states when asked."""
    before, worst = {}, [0.0, 0.0, ""]
    for stop in stops:
        j = _segment(f, t) if compare else None
        y_end, mine = rp.integrate(y, t, stop, rhs_of(stop),
                                   None if j is None else f.oem.times[j])  # fmt: skip
        if mine is not None:
            dr = np.linalg.norm(mine[:, :3] - f.oem.states[j][:, :3], axis=1)
            dv = np.linalg.norm(mine[:, 3:] - f.oem.states[j][:, 3:], axis=1)
            if dr.max() > worst[0]:
                worst[0] = float(dr.max())
                worst[2] = f"day {f.oem.times[j][dr.argmax()] / DAY:.2f}"
            worst[1] = max(worst[1], float(dv.max()))
        before[stop] = y_end.copy()
        y, t = y_end.copy(), stop
        y[3:] += _impulse(f, stop)
    return before, worst


def _correction(f, k: int, before: dict, rhs_of) -> float:
    """The ΔV [m/s] a last correction adds to leg ``k`` flown open-loop: an impulse three
    quarters of an orbit before the arrival aimed (Newton, finite differences) at the
    debris' position, the arrive impulse then matching its velocity (the leg's impulses
    in between kept)."""
    t_a = f.t_meet[k]
    r_goal, v_goal = f.goal_states[k]
    period = 2.0 * np.pi * np.sqrt(np.linalg.norm(r_goal) ** 3 / rp.MU)
    t_c = t_a - 0.75 * period
    t_prev = f.t_meet[k - 1] if k else 0.0
    earlier = [s for s in before if t_prev < s <= t_c]
    if not earlier:
        return np.nan
    s0 = max(earlier)
    y = before[s0].copy()
    y[3:] += _impulse(f, s0)
    y_c, _ = rp.integrate(y, s0, t_c, rhs_of(t_c))
    later = [s for s in before if t_c < s < t_a - 1e-6]

    def arrive(dv_c):
        y = y_c.copy()
        y[3:] += dv_c
        t = t_c
        for s in later:
            y, _ = rp.integrate(y, t, s, rhs_of(s))
            y[3:] += _impulse(f, s)
            t = s
        y, _ = rp.integrate(y, t, t_a, rhs_of(t_a))
        return y

    x = np.zeros(3)
    for _ in range(8):
        y = arrive(x)
        miss = y[:3] - r_goal
        if np.linalg.norm(miss) < 0.01:
            break
        jac = np.empty((3, 3))
        for c in range(3):
            step = np.zeros(3)
            step[c] = 1e-3
            jac[:, c] = (arrive(x + step)[:3] - y[:3]) / 1e-3
        x = x - np.linalg.solve(jac, miss)
    y = arrive(x)
    return (np.linalg.norm(x) + np.linalg.norm(v_goal - y[3:])
            - np.linalg.norm(_impulse(f, t_a)))  # fmt: skip


def rendezvous_misses(f, states: dict) -> list[tuple[float, float]]:
    out = []
    for k, t in enumerate(f.t_meet):
        y = states.get(t)
        if y is None:
            out.append((np.nan, np.nan))
            continue
        y = y.copy()
        y[3:] += _impulse(f, t)
        r, v = f.goal_states[k]
        out.append((float(np.linalg.norm(y[:3] - r)), float(np.linalg.norm(y[3:] - v))))
    return out


def fly_legs(f, rhs_of, compare: bool):
    """Each leg flown open-loop from the debris (this replay's) at the leg's start: the
    states before each impulse, the worst OEM difference, each leg's last correction."""
    states, worst, extra = {}, [0.0, 0.0, ""], []
    for k in range(len(f.t_meet)):
        t0 = f.t_meet[k - 1] if k else 0.0
        if k:
            r, v = f.goal_states[k - 1]
        else:
            r, v = f.debris.state(f.solution["path"][0], f.oem.epoch0)
        y = np.concatenate([r, v])
        if not k:
            y[3:] += _impulse(f, 0.0)
        stops = [s for s in f.stops if t0 + 1e-6 < s <= f.t_meet[k] + 1e-6]
        before, w = _fly(f, y, t0, stops, rhs_of, compare)
        if w[0] > worst[0]:
            worst = [w[0], max(worst[1], w[1]), w[2]]
        worst[1] = max(worst[1], w[1])
        states.update(before)
        extra.append(_correction(f, k, before, rhs_of))
    return states, worst, extra


def replay(folder: Path, catalog: Path | None = None, moving_pole: bool = True) -> dict:
    """Check one flown folder (module docstring); prints its report, returns its row."""
    started = time.perf_counter()
    f = load(folder, catalog)
    oem, sol = f.oem, f.solution
    print(f"\n== {folder.name}: {' -> '.join(sol['path'])} ({f.cat_path.name}, {f.fmt}; OEM "
          f"frame {oem.frame}, {len(oem.times)} segments, {sum(len(t) for t in oem.times)} "
          f"states; status {f.summary['status']})")  # fmt: skip
    for line in oem.comments[1:3]:
        print(f"   OEM: {line}")
    fixed = leg_rhs(f)
    # (a) each OEM arc from its own first state; the leg replays against every OEM state
    arc_r = arc_v = 0.0
    for t, s in zip(oem.times, oem.states, strict=True):
        if len(t) > 1:
            end, _ = rp.integrate(s[0], t[0], t[-1], fixed(t[-1]))
            arc_r = max(arc_r, float(np.linalg.norm(end[:3] - s[-1, :3])))
            arc_v = max(arc_v, float(np.linalg.norm(end[3:] - s[-1, 3:])))
    jumps = []
    for j in range(1, len(oem.times)):
        jump = oem.states[j][0, 3:] - oem.states[j - 1][-1, 3:]
        jumps.append(float(np.linalg.norm(jump - _impulse(f, oem.times[j][0]))))
    leg_states, leg_worst, leg_extra = fly_legs(f, fixed, compare=True)
    chained, _ = _fly(f, oem.states[0][0] + np.r_[0, 0, 0, _impulse(f, 0.0)], 0.0,
                      [s for s in f.stops if s <= f.t_meet.max() + 1e-6], fixed)  # fmt: skip
    print(f"(a) each OEM arc re-integrated from its first state: worst {arc_r:.3f} m, "
          f"{arc_v:.2e} m/s at its end; velocity jumps between segments against "
          f"maneuvers.csv: worst {max(jumps, default=0.0):.2e} m/s")  # fmt: skip
    print(f"    each leg flown open-loop from the debris: worst {leg_worst[0]:.3f} m "
          f"({leg_worst[2]}), {leg_worst[1]:.2e} m/s from the OEM's states")  # fmt: skip
    moved, moved_extra = {}, [np.nan] * len(f.t_meet)
    if moving_pole and not f.debris.gtoc9:
        moving = rp.moving_pole_rhs(_moving_poles(oem.epoch0, f.t_end))
        moved, _, moved_extra = fly_legs(f, lambda stop: moving, compare=False)

    # (b) each rendezvous against the debris computed here
    r0, v0 = f.debris.state(sol["path"][0], oem.epoch0)
    print(f"(b) OEM's first state against debris {sol['path'][0]}: "
          f"{np.linalg.norm(oem.states[0][0][:3] - r0):.3f} m, "
          f"{np.linalg.norm(oem.states[0][0][3:] - v0):.2e} m/s. Misses [m, m/s]: the OEM's "
          "state, each leg flown open-loop (then the ΔV a last correction adds), the whole "
          "flight open-loop, each leg with the moving pole")  # fmt: skip
    print(f"    {'leg':>3} {'target':>7} {'epoch (UTC)':<27} {'OEM m':>7} {'m/s':>8} "
          f"{'leg m':>9} {'m/s':>8} {'+dv':>7} {'chain m':>9} {'m/s':>8} {'moving m':>9} "
          f"{'m/s':>7} {'+dv':>6}")  # fmt: skip
    oem_miss = []
    for k, t in enumerate(f.t_meet):
        j = _segment(f, t)
        r, v = f.goal_states[k]
        o = oem.states[j][0] if j is not None else np.full(6, np.nan)
        oem_miss.append((float(np.linalg.norm(o[:3] - r)), float(np.linalg.norm(o[3:] - v))))
    legs_m, chain_m = rendezvous_misses(f, leg_states), rendezvous_misses(f, chained)
    moved_m = rendezvous_misses(f, moved)
    for k, row in f.meets.iterrows():
        print(f"    {k + 1:>3} {row['target']:>7} {row['epoch_utc']:<27} "
              f"{oem_miss[k][0]:>7.3f} {oem_miss[k][1]:>8.1e} {legs_m[k][0]:>9.1f} "
              f"{legs_m[k][1]:>8.4f} {leg_extra[k]:>7.3f} {chain_m[k][0]:>9.1f} "
              f"{chain_m[k][1]:>8.4f} {moved_m[k][0]:>9.1f} {moved_m[k][1]:>7.3f} "
              f"{moved_extra[k]:>6.3f}")  # fmt: skip
    flown_all = len(f.meets) == len(sol["legs"])

    def worst(misses):
        return (max((m[0] for m in misses), default=np.nan),
                max((m[1] for m in misses), default=np.nan))  # fmt: skip

    def met(misses):
        w = worst(misses)
        return flown_all and w[0] <= GOAL_MISS_M and w[1] <= GOAL_MISS_MPS

    for label, misses in (("the OEM's states", oem_miss), ("each leg open-loop", legs_m),
                          ("the whole flight open-loop", chain_m),
                          ("each leg, moving pole", moved_m)):  # fmt: skip
        if misses and np.isfinite(worst(misses)[0]):
            w = worst(misses)
            print(f"    worst, {label}: {w[0]:.3f} m, {w[1]:.2e} m/s (100 m and 0.1 m/s: "
                  f"{'met' if met(misses) else 'NOT met'})")  # fmt: skip
    if not flown_all:
        print(f"    {len(f.meets)} of {len(sol['legs'])} legs flown: NOT met")

    # (c) the impulses' total against flight.json and the plan
    norms = np.linalg.norm(f.dv, axis=1)
    total, plan = float(norms.sum()), float(sol["total_dv_mps"])
    goal, kind = f.debris.goal(sol["path"])
    print(f"(c) {'leg':>3} {'plan':>8} {'flown':>8} {'ratio':>6}")
    for k, leg in enumerate(sol["legs"]):
        flown_leg = float(norms[f.maneuvers["leg"].to_numpy() == k + 1].sum())
        print(f"    {k + 1:>3} {leg['dv_mps']:>8.2f} {flown_leg:>8.2f} "
              f"{flown_leg / leg['dv_mps'] if leg['dv_mps'] else np.nan:>6.3f}")  # fmt: skip
    ratio = total / plan
    dv_ok = ratio <= goal and flown_all
    fixed_total = total + float(np.nansum(leg_extra))
    moved_total = total + float(np.nansum(moved_extra)) if moved else np.nan
    print(f"    sum |dv| {total:.3f} m/s (dv_mps column {f.maneuvers['dv_mps'].sum():.3f}, "
          f"flight.json {f.summary['flown_dv_mps']:.3f}: {total - f.summary['flown_dv_mps']:+.1e}"
          f"); plan {plan:.3f} m/s (its legs {sum(g['dv_mps'] for g in sol['legs']):.3f}); "
          f"ratio {ratio:.4f} ({kind}: goal {goal:g}, {'met' if dv_ok else 'NOT met'}; "
          f"1.10: {'met' if ratio <= GOAL_ANY and flown_all else 'NOT met'})")  # fmt: skip
    print(f"    with each leg's last correction: {fixed_total:.3f} m/s (ratio "
          f"{fixed_total / plan:.4f}); with the moving pole: {moved_total:.3f} m/s (ratio "
          f"{moved_total / plan:.4f}); replayed in {time.perf_counter() - started:.0f} s",
          flush=True)  # fmt: skip
    return dict(case=folder.name, n=len(sol["path"]), plan=plan, flown=total, ratio=ratio,
                goal=goal, dv_ok=dv_ok, oem=worst(oem_miss), leg=worst(legs_m),
                chain=worst(chain_m), moved=worst(moved_m) if moved else (np.nan, np.nan),
                fixed_ratio=fixed_total / plan, moved_ratio=moved_total / plan,
                met_oem=met(oem_miss), met_leg=met(legs_m), arc=(arc_r, arc_v),
                status=f.summary["status"])  # fmt: skip


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("folders", nargs="*", type=Path, help="flown run folders")
    parser.add_argument("--make", nargs="*", choices=CASES, default=[],
                        help="plan and fly these cases first (module docstring)")
    parser.add_argument("--work", type=Path, help="where --make writes [a temporary folder]")
    parser.add_argument("--catalog", type=Path, help="the catalog (default: scenario.toml's)")
    parser.add_argument("--no-moving-pole", action="store_true",
                        help="skip the replay with the pole moving with the date")
    args = parser.parse_args(argv)
    work = args.work or Path(tempfile.mkdtemp(prefix="independent_replay_"))
    work.mkdir(parents=True, exist_ok=True)
    import platform

    print(f"# {platform.machine()}, {os.cpu_count()} cores, load {os.getloadavg()[0]:.1f}, "
          f"Python {platform.python_version()}; DOP853 rtol {rp.RTOL:g}, atol {rp.ATOL:g}")
    rows, folders = [], list(args.folders)
    for case in args.make:
        folder = make(case, work)
        if folder is None:
            rows.append(dict(case=case, failed="run or fly failed (output above)"))
        else:
            folders.append(folder)
    for folder in folders:
        try:
            rows.append(replay(folder, args.catalog, not args.no_moving_pole))
        except Exception as err:  # shown, the other folders still replayed
            import traceback

            traceback.print_exc()
            rows.append(dict(case=folder.name, failed=f"replay failed: {err}"))
    print(f"\n{'case':<9} {'n':>2} {'plan':>7} {'flown':>7} {'ratio':>6} {'goal':>4} "
          f"{'OEM m':>7} {'m/s':>7} {'leg m':>8} {'m/s':>7} {'ratio+':>6} {'chain m':>8} "
          f"{'moving m':>8} {'ratio+':>6} {'arc m':>6} {'status':<8} ratio/100m(OEM)/100m(leg)")
    for row in rows:
        if "failed" in row:
            print(f"{row['case']:<9} {row['failed']}")
            continue
        print(f"{row['case']:<9} {row['n']:>2} {row['plan']:>7.2f} {row['flown']:>7.2f} "
              f"{row['ratio']:>6.3f} {row['goal']:>4.2f} {row['oem'][0]:>7.3f} "
              f"{row['oem'][1]:>7.1e} {row['leg'][0]:>8.1f} {row['leg'][1]:>7.4f} "
              f"{row['fixed_ratio']:>6.3f} {row['chain'][0]:>8.1f} {row['moved'][0]:>8.1f} "
              f"{row['moved_ratio']:>6.3f} {row['arc'][0]:>6.2f} {row['status']:<8} "
              f"{'met' if row['dv_ok'] else 'NOT'}/{'met' if row['met_oem'] else 'NOT'}/"
              f"{'met' if row['met_leg'] else 'NOT'}")  # fmt: skip


if __name__ == "__main__":
    main()
