"""The files of a flown plan checked from outside (issue 26, "How we will know").

A real run folder (``python -m sdc_cvx run`` then ``fly``, as subprocesses) on the SSO
rocket bodies; then, reading only the files:

- an independent replay: the first state of ``trajectory.oem`` (read by a parser written
  here), propagated through every impulse of ``maneuvers.csv`` by a J2 integrator written
  here, against the debris by SGP4 (``Satrec.twoline2rv`` of the TLE lines read by hand)
  rotated TEME -> GCRF by skyfield: its misses are ``rendezvous.csv``'s;
- the tables agree with each other, with ``flight.json`` and with ``solution.json``;
- ``trajectory.oem`` read back by the ``oem`` package: one segment per arc between
  impulses, the velocity jumping by the impulse at each boundary;
- ``flight.png`` is a PNG.
"""

import json
import re
from pathlib import Path
from types import SimpleNamespace

import numpy as np
import pandas as pd
import pytest
from scipy.integrate import solve_ivp

from sdc_cvx.flight.frames import earth_pole_gcrf
from tests.conftest import computed_once, shared_file
from tests.test_cli import cli_process

TLE = "sso_rocket_bodies_2020/sso_rb.tle"
pytestmark = [pytest.mark.slow, pytest.mark.requires_shared_data(TLE)]

# n = 3 within 120 days: 40720 -> 28651 -> 33500, two legs that both drift (9 and 111
# days), solved in about 2 s and flown in about 10 s.
SCENARIO = """\
[catalog]
path = {path}

[mission]
n = 3
tmax_days = 120
"""
# J2 about the Earth's pole, the constants of ForceModel.named("j2") (issue 26)
MU = 3.986004418e14  # m^3/s^2
R_EQ = 6378137.0  # m
J2 = 1.08262668e-3
ISSUE_MANEUVER_COLUMNS = ["epoch_utc", "leg", "kind", "dv_mps", "dv_r_mps", "dv_t_mps",
                          "dv_n_mps", "dv_x_mps", "dv_y_mps", "dv_z_mps"]  # fmt: skip
ISSUE_RENDEZVOUS_COLUMNS = ["epoch_utc", "target", "miss_km", "miss_mps", "da_km", "di_deg",
                            "draan_deg", "correction_dv_mps", "phasing_shift_h",
                            "phasing_dv_mps"]  # fmt: skip
ISO_UTC = re.compile(r"^\d{4}-\d{2}-\d{2}T\d{2}:\d{2}:\d{2}(\.\d+)?Z$")
DV_GCRF = ["dv_x_mps", "dv_y_mps", "dv_z_mps"]


@pytest.fixture(scope="module")
@computed_once
def flown(tmp_path_factory):
    """A run folder of the SSO scenario, flown: ``run`` then ``fly``, real processes."""
    tle = shared_file(TLE)
    work = tmp_path_factory.mktemp("flown")
    scenario = work / "sso.toml"
    scenario.write_text(SCENARIO.format(path=json.dumps(str(tle))), encoding="utf-8")
    folder = work / "run"
    run = cli_process("run", str(scenario), "--out", str(folder), "--quiet")
    assert run.returncode == 0, run.stderr
    fly = cli_process("fly", str(folder))
    assert fly.returncode == 0, fly.stderr
    flight = folder / "flight"
    return SimpleNamespace(
        tle=tle, folder=folder, flight=flight, run=run, fly=fly,
        solution=json.loads((folder / "solution.json").read_text(encoding="utf-8")),
        summary=json.loads((flight / "flight.json").read_text(encoding="utf-8")),
        maneuvers=pd.read_csv(flight / "maneuvers.csv"),
        rendezvous=pd.read_csv(flight / "rendezvous.csv", dtype={"target": str}),
    )  # fmt: skip


def utc(stamps) -> pd.DatetimeIndex:
    return pd.DatetimeIndex(pd.to_datetime(list(stamps), utc=True))


# -- an OEM reader of our own: the first state only ------------------------------------
def first_oem_state(path: Path):
    """(epoch, r [m], v [m/s]) of the first data line of a KVN OEM (km, km/s)."""
    in_data = False
    for line in path.read_text(encoding="utf-8").splitlines():
        words = line.split()
        if not words or words[0] == "COMMENT":
            continue
        if words[0] == "META_STOP":
            in_data = True
        elif words[0] == "META_START":
            in_data = False
        elif in_data:
            numbers = np.array([float(w) for w in words[1:7]])
            return pd.Timestamp(words[0], tz="UTC"), numbers[:3] * 1e3, numbers[3:] * 1e3
    raise AssertionError(f"{path}: no data line")


# -- a J2 integrator of our own --------------------------------------------------------
def j2_rhs(pole):
    """d(r, v)/dt under U = mu/r - mu J2 R^2 / (2 r^3) (3 z^2/r^2 - 1), z = r . pole.

    grad U = -mu r/r^3 - (3/2) mu J2 R^2 / r^5 [(1 - 5 z^2/r^2) r + 2 z pole].
    """
    pole = np.asarray(pole, dtype=float) / np.linalg.norm(pole)
    k = 1.5 * MU * J2 * R_EQ**2

    def rhs(t, y):
        r = y[:3]
        r2 = r @ r
        rn = np.sqrt(r2)
        z = r @ pole
        acc = -MU * r / (r2 * rn) - k / (r2 * r2 * rn) * ((1.0 - 5.0 * z * z / r2) * r
                                                          + 2.0 * z * pole)  # fmt: skip
        return np.concatenate([y[3:], acc])

    return rhs


def leg_poles(solution, rendezvous, start: pd.Timestamp) -> list[np.ndarray]:
    """The pole of each leg as the package takes it (replay.py ``_pole``): the true pole
    of date at the leg's middle, from when the vehicle is ready (the planned departure,
    moved by the previous arrival's delay, not before the previous rendezvous).

    Measured on this plan: the pole at the mission start instead moves the second leg's
    miss (111 days) by 3.2 km; a pole varying with time, as the Earth's does, by 2.1 km:
    the package's constant pole per leg is part of its model, mirrored here.
    """
    poles, t_prev, delay = [], 0.0, 0.0
    for k, leg in enumerate(solution["legs"]):
        t_ready = max(leg["departure_day"] * 86400.0 + delay, t_prev)
        middle = start + pd.to_timedelta(t_ready + 0.5 * leg["duration_days"] * 86400.0, "s")
        poles.append(earth_pole_gcrf(pd.DatetimeIndex([middle]))[0])
        t_prev = (utc([rendezvous["epoch_utc"][k]])[0] - start).total_seconds()
        delay = rendezvous["delay_days"][k] * 86400.0
    return poles


@pytest.fixture(scope="module")
@computed_once
def replay(flown):
    """The vehicle replayed from the OEM's first state through every impulse: its state
    at each rendezvous epoch (after the impulses at that epoch) and at each impulse epoch
    (before and after the impulse)."""
    epoch0, r0, v0 = first_oem_state(flown.flight / "trajectory.oem")
    start = pd.Timestamp(flown.solution["start"])
    man_t = (utc(flown.maneuvers["epoch_utc"]) - epoch0).total_seconds().to_numpy()
    meet_t = (utc(flown.rendezvous["epoch_utc"]) - epoch0).total_seconds().to_numpy()
    dv = flown.maneuvers[DV_GCRF].to_numpy()
    poles = leg_poles(flown.solution, flown.rendezvous, start)
    y, t = np.concatenate([r0, v0]), 0.0
    meetings, at_impulses = [], {}
    for k, t_meet in enumerate(meet_t):
        rhs = j2_rhs(poles[k])
        for t_stop in sorted(set(man_t[(man_t > t) & (man_t <= t_meet)]) | {t_meet}):
            if t_stop > t:
                arc = solve_ivp(rhs, (t, t_stop), y, method="DOP853", rtol=1e-12, atol=1e-7)
                assert arc.success, arc.message
                y, t = arc.y[:, -1].copy(), t_stop
            before = y.copy()
            y[3:] += dv[man_t == t_stop].sum(axis=0)
            at_impulses[t_stop] = (before, y.copy())
        meetings.append(y.copy())
    return SimpleNamespace(epoch0=epoch0, meetings=meetings, meet_t=meet_t,
                           at_impulses=at_impulses)  # fmt: skip


def debris_gcrf(tle: Path, ident: str, epoch: pd.Timestamp):
    """SGP4 of the TLE of ``ident`` (lines read here), TEME -> GCRS by skyfield [m, m/s]."""
    skyfield_api = pytest.importorskip(
        "skyfield.api", reason="skyfield rotates TEME to the GCRF independently (pip install "
        "skyfield)")  # fmt: skip
    from sgp4.api import Satrec, jday
    from skyfield.sgp4lib import TEME

    lines = tle.read_text(encoding="utf-8").splitlines()
    line1 = next(x for x in lines if x.startswith("1 ") and x[2:7].strip() == ident)
    line2 = next(x for x in lines if x.startswith("2 ") and x[2:7].strip() == ident)
    satrec = Satrec.twoline2rv(line1, line2)
    seconds = epoch.second + epoch.microsecond * 1e-6 + epoch.nanosecond * 1e-9
    jd, fraction = jday(epoch.year, epoch.month, epoch.day, epoch.hour, epoch.minute, seconds)
    error, r_teme, v_teme = satrec.sgp4(jd, fraction)
    assert error == 0, f"SGP4 error {error} for {ident}"
    ts = skyfield_api.load.timescale(builtin=True)
    when = ts.utc(epoch.year, epoch.month, epoch.day, epoch.hour, epoch.minute, seconds)
    to_gcrs = TEME.rotation_at(when).T  # rotation_at: GCRS -> TEME
    return to_gcrs @ np.array(r_teme) * 1e3, to_gcrs @ np.array(v_teme) * 1e3


# -- the commands ----------------------------------------------------------------------
def test_the_plan_has_two_drifting_legs_and_fly_reports_each(flown):
    legs = flown.solution["legs"]
    assert len(legs) == 2 and all(leg["duration_days"] > 1.0 for leg in legs)
    out = flown.fly.stdout.splitlines()
    assert out[0].startswith("flight ") and "plan" in out[0] and "flown" in out[0]
    assert "worst miss" in out[0]
    assert out[1].startswith("results ")
    leg_lines = [line for line in flown.fly.stderr.splitlines() if line.startswith("leg ")]
    assert len(leg_lines) == len(legs), flown.fly.stderr
    assert "Traceback" not in flown.fly.stderr


# -- the independent replay ------------------------------------------------------------
def test_an_independent_replay_finds_the_misses_of_rendezvous_csv(flown, replay):
    for k, row in flown.rendezvous.iterrows():
        r_d, v_d = debris_gcrf(flown.tle, row["target"], utc([row["epoch_utc"]])[0])
        miss_km = np.linalg.norm(replay.meetings[k][:3] - r_d) / 1e3
        miss_mps = np.linalg.norm(replay.meetings[k][3:] - v_d)
        # issue 46: every rendezvous within 100 m and 0.1 m/s, seen from outside (the
        # package's own misses are millimetres; DOP853 at rtol 1e-12 / atol 1e-7 leaves
        # about 1.4 m and 1.6 mm/s after 111 days, skyfield's TEME ~1 m from ours; at
        # rtol 1e-11 / atol 1e-4 it was 65 m and 0.072 m/s)
        assert miss_km < 0.1 and miss_mps < 0.1, (row["target"], miss_km, miss_mps)
        assert miss_km == pytest.approx(row["miss_km"], abs=0.02), row["target"]
        assert miss_mps == pytest.approx(row["miss_mps"], abs=0.02), row["target"]


def test_the_oem_states_at_the_impulses_are_the_replays(flown, replay):
    """The trajectory itself: the OEM's states on either side of each impulse (read by
    our own parser) against the replay's, same measured error as the misses."""
    stamps, states = [], []
    for line in (flown.flight / "trajectory.oem").read_text(encoding="utf-8").splitlines():
        words = line.split()
        if len(words) == 7 and words[0][:1].isdigit():
            stamps.append(words[0])
            states.append([float(w) * 1e3 for w in words[1:]])
    t = (utc(stamps) - replay.epoch0).total_seconds().to_numpy()
    states = np.array(states)
    worst_r, worst_v = 0.0, 0.0
    for t_imp, (before, after) in replay.at_impulses.items():
        rows = np.flatnonzero(np.abs(t - t_imp) < 2e-6)  # the CSV's epochs: microseconds
        assert len(rows) == 2, f"impulse at {t_imp} s: {len(rows)} OEM states"
        for row, mine in zip(rows, (before, after), strict=True):
            worst_r = max(worst_r, np.linalg.norm(states[row, :3] - mine[:3]))
            worst_v = max(worst_v, np.linalg.norm(states[row, 3:] - mine[3:]))
    assert worst_r < 20.0 and worst_v < 0.02, (worst_r, worst_v)  # the replay's own error


# -- the files agree -------------------------------------------------------------------
def test_the_columns_are_the_issues(flown):
    assert list(flown.maneuvers.columns) == ISSUE_MANEUVER_COLUMNS
    assert list(flown.rendezvous.columns) == ISSUE_RENDEZVOUS_COLUMNS + ["delay_days",
                                                                         "in_time"]  # fmt: skip


def test_the_magnitudes_are_the_norms_of_both_vectors(flown):
    m = flown.maneuvers
    for columns in (DV_GCRF, ["dv_r_mps", "dv_t_mps", "dv_n_mps"]):
        norms = np.linalg.norm(m[columns].to_numpy(), axis=1)
        np.testing.assert_allclose(norms, m["dv_mps"], rtol=1e-8, atol=1e-9)


def test_the_totals_are_flight_json_and_solution_json(flown):
    s, f = flown.summary, flown.solution
    assert flown.maneuvers["dv_mps"].sum() == pytest.approx(s["flown_dv_mps"], rel=1e-9)
    assert s["plan_dv_mps"] == pytest.approx(sum(leg["dv_mps"] for leg in f["legs"]), rel=1e-12)
    r = flown.rendezvous
    assert s["worst_miss_km"] == pytest.approx(r["miss_km"].max(), rel=1e-9)
    assert s["phasing_dv_mps"] == pytest.approx(r["phasing_dv_mps"].sum(), abs=1e-6)
    assert s["correction_dv_mps"] == pytest.approx(r["correction_dv_mps"].sum(), abs=1e-6)
    assert pd.Timestamp(s["start"]) == pd.Timestamp(f["start"])
    assert s["tmax_days"] == f["mission"]["tmax_days"]
    # the flight ends at its last rendezvous (corrections done), then the plan's stay there
    last_meeting = (
        pd.Timestamp(r["epoch_utc"].iloc[-1]) - pd.Timestamp(f["start"])
    ) / pd.Timedelta(days=1)
    last_leg = f["legs"][-1]
    stay = f["total_duration_days"] - last_leg["departure_day"] - last_leg["duration_days"]
    assert s["end_day"] == pytest.approx(last_meeting + stay, abs=1e-6)
    assert s["status"] == ("flown" if s["end_day"] <= s["tmax_days"] + 1e-9 else "late")
    assert s["force"]["name"] == "j2"


def test_plan_phasing_and_corrections_add_up_to_the_flown_dv_per_leg(flown):
    """replay.py: "plan + phasing + corrections = flown", per leg (the plan's leg dv of
    solution.json, the phasing and correction of rendezvous.csv, the impulses flown)."""
    for k, leg in enumerate(flown.solution["legs"]):
        flown_leg = flown.maneuvers.loc[flown.maneuvers["leg"] == k + 1, "dv_mps"].sum()
        row = flown.rendezvous.iloc[k]
        parts = leg["dv_mps"] + row["phasing_dv_mps"] + row["correction_dv_mps"]
        assert parts == pytest.approx(flown_leg, abs=0.01), f"leg {k + 1}"


def test_one_rendezvous_per_leg_with_the_paths_debris(flown):
    path = [str(x) for x in flown.solution["path"]]
    legs = flown.solution["legs"]
    assert list(flown.rendezvous["target"]) == path[1:] == [str(leg["to"]) for leg in legs]
    m = flown.maneuvers
    assert sorted(set(m["leg"])) == list(range(1, len(legs) + 1))
    meet = utc(flown.rendezvous["epoch_utc"])
    epochs = utc(m["epoch_utc"])
    for k in range(len(legs)):
        mine = m["leg"] == k + 1
        assert {"depart", "arrive"} <= set(m.loc[mine, "kind"])
        # a leg's impulses come after the previous rendezvous, up to its own
        assert epochs[mine.to_numpy()].max() <= meet[k]
        if k:
            assert epochs[mine.to_numpy()].min() >= meet[k - 1]
        arrive = epochs[(mine & (m["kind"] == "arrive")).to_numpy()]
        assert arrive.max() <= meet[k]



def test_delay_and_in_time_are_the_flights_own(flown):
    """Found as a user: ``delay_days`` and ``in_time`` were the phasing's prediction (a
    low-thrust leg said +0.23 days and in time; its arrive impulse came 3.2 days after the
    plan's arrival).  Read from the files: the delay is the arrive impulse's epoch less the
    plan's arrival; in time means the corrections done (the rendezvous epoch) by the
    plan's departure from that debris, or the plan's end after the last."""
    start = pd.Timestamp(flown.solution["start"])
    legs = flown.solution["legs"]
    m = flown.maneuvers
    arrivals = utc(m.loc[m["kind"] == "arrive", "epoch_utc"])
    meets = utc(flown.rendezvous["epoch_utc"])
    leaves = [leg["departure_day"] for leg in legs[1:]] + [flown.solution["total_duration_days"]]
    for k, leg in enumerate(legs):
        planned = start + pd.to_timedelta(leg["departure_day"] + leg["duration_days"], "D")
        assert flown.rendezvous["delay_days"][k] == pytest.approx(
            (arrivals[k] - planned).total_seconds() / 86400.0, abs=1e-6)  # fmt: skip
        leave = start + pd.to_timedelta(leaves[k], "D")
        assert bool(flown.rendezvous["in_time"][k]) == (meets[k] <= leave + pd.Timedelta("1s"))


def test_the_epochs_are_iso_utc_and_increasing(flown):
    for frame, strict in ((flown.maneuvers, False), (flown.rendezvous, True)):
        stamps = list(frame["epoch_utc"])
        assert all(ISO_UTC.match(s) for s in stamps), stamps
        steps = np.diff(utc(stamps).asi8)
        assert (steps > 0).all() if strict else (steps >= 0).all()
    start = pd.Timestamp(flown.solution["start"])
    assert utc(flown.maneuvers["epoch_utc"])[0] >= start


# -- trajectory.oem, read by the oem package -------------------------------------------
def test_the_oem_read_back_has_one_segment_per_arc(flown):
    oem = pytest.importorskip("oem", reason="the independent OEM reader: pip install oem")
    message = oem.OrbitEphemerisMessage.open(flown.flight / "trajectory.oem")
    assert message.version == "2.0"
    segments = list(message)
    for segment in segments:
        assert segment.metadata["REF_FRAME"] == "GCRF"
        assert segment.metadata["TIME_SYSTEM"] == "UTC"
        assert segment.metadata["CENTER_NAME"] == "EARTH"
    m = flown.maneuvers
    impulse_epochs = utc(m["epoch_utc"])
    first_epoch, _, _ = first_oem_state(flown.flight / "trajectory.oem")
    # an impulse at the OEM's first epoch (a departure at the mission's start) is in its
    # first state already: the segments are the arcs after it
    distinct = impulse_epochs[impulse_epochs > first_epoch + pd.Timedelta(microseconds=2)].unique()
    assert len(segments) == len(distinct) + 1
    read_first = pd.Timestamp(list(segments[0].states)[0].epoch.to_datetime(), tz="UTC")
    assert abs(read_first - first_epoch) < pd.Timedelta(microseconds=2)
    for k, (ending, beginning) in enumerate(zip(segments[:-1], segments[1:], strict=True)):
        last, first = list(ending.states)[-1], list(beginning.states)[0]
        assert abs((first.epoch - last.epoch).to_value("s")) < 1e-6
        boundary = pd.Timestamp(last.epoch.to_datetime(), tz="UTC")
        at = np.abs((impulse_epochs - boundary).total_seconds().to_numpy()) < 2e-6
        assert at.any(), f"segment {k + 1} ends at {boundary}, no impulse then"
        assert abs(boundary - distinct[k]) < pd.Timedelta(microseconds=2)
        jump = (np.asarray(first.velocity) - np.asarray(last.velocity)) * 1e3  # m/s
        step = (np.asarray(first.position) - np.asarray(last.position)) * 1e3  # m
        assert np.linalg.norm(step) < 1.0
        np.testing.assert_allclose(jump, m.loc[at, DV_GCRF].to_numpy().sum(axis=0), atol=1e-3)


def test_flight_png_is_a_png(flown):
    assert (flown.flight / "flight.png").read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"


def test_flight_load_reopens_the_folder_fly_wrote(flown):
    """Issue 48, item 17: a notebook reopens a run folder ``fly`` wrote, its plan and its
    flight, as the files say them."""
    from sdc_cvx import Solution
    from sdc_cvx.flight import Flight

    solution = Solution.load(flown.folder)
    assert list(solution.path) == flown.solution["path"]
    assert solution.total_dv_mps == flown.solution["total_dv_mps"]
    assert solution.catalog.start == pd.Timestamp(flown.solution["start"])
    flight = Flight.load(flown.folder)
    for key in ("status", "rates", "frame", "notes", "start"):
        assert flight.to_dict()[key] == flown.summary[key], key
    for key in ("plan_dv_mps", "flown_dv_mps", "phasing_dv_mps", "correction_dv_mps",
                "worst_miss_km", "end_day"):  # fmt: skip
        assert flight.to_dict()[key] == pytest.approx(flown.summary[key], rel=1e-8), key
    np.testing.assert_allclose([m.dv_mps for m in flight.maneuvers], flown.maneuvers["dv_mps"],
                               rtol=1e-9)  # fmt: skip
    assert [r.target for r in flight.rendezvous] == list(flown.rendezvous["target"])
    assert [r.in_time for r in flight.rendezvous] == list(flown.rendezvous["in_time"])
