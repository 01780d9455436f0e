"""``Solution.save`` and ``Flight.save`` as a notebook user calls them (issue 48, item 15):
a wrong argument or a folder that cannot take the results is one of the package's errors
(:class:`~sdc_cvx.errors.OutputError`, :class:`~sdc_cvx.errors.FolderError`), in one line
worded for the API, and nothing is written."""

import os
from dataclasses import replace

import numpy as np
import pandas as pd
import pytest

from sdc_cvx import Solution
from sdc_cvx.errors import FolderError, OutputError, SdcError
from sdc_cvx.flight import Flight, FlightPlan
from sdc_cvx.flight.plan import PlannedLeg
from sdc_cvx.flight.propagation import ForceModel
from sdc_cvx.flight.result import Maneuver, Rendezvous


def assert_one_line(err: pytest.ExceptionInfo, *words: str) -> None:
    text = str(err.value)
    assert isinstance(err.value, SdcError) and "\n" not in text, text
    for word in words:
        assert word in text, text


@pytest.mark.parametrize("folder", [None, 123, b"run"])
def test_save_refuses_a_folder_that_is_not_a_path(solution, folder, tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    with pytest.raises(OutputError) as err:
        solution.save(folder)
    assert_one_line(err, "Solution.save(folder): folder must be a path", repr(folder))
    assert os.listdir(tmp_path) == []


def test_save_refuses_a_scenario_toml_that_is_not_text(solution, tmp_path):
    with pytest.raises(OutputError) as err:
        solution.save(tmp_path / "d", scenario_toml=5)
    assert_one_line(err, "scenario_toml must be text (a str) or None, got int 5")
    assert not (tmp_path / "d").exists()  # refused before anything is written


def test_save_refuses_a_name_too_long_in_one_line(solution, tmp_path):
    with pytest.raises(FolderError) as err:
        solution.save(tmp_path / ("x" * 300))
    assert_one_line(err, "Solution.save:", "is 300 bytes long", "at most 255 bytes")


def test_save_of_the_current_folder_is_refused_in_the_apis_words(solution, tmp_path,
                                                                 monkeypatch):  # fmt: skip
    """The advice named ``--out`` (the command line's) to a notebook user."""
    monkeypatch.chdir(tmp_path)
    with pytest.raises(FolderError) as err:
        solution.save(".")
    assert_one_line(err, "is the current folder", "e.g. Solution.save('run')")
    assert "--out" not in str(err.value)
    assert isinstance(err.value, FileExistsError)  # what the refusal was before


@pytest.mark.parametrize(("where", "said"), [("file", "is a file, not a folder"),
                                            ("/proc/x", "/proc refuses new files")])
def test_save_refuses_a_folder_that_cannot_take_the_run(solution, tmp_path, where, said):
    if where == "file":
        where = tmp_path / "file"
        where.write_text("mine", encoding="utf-8")
    with pytest.raises(FolderError) as err:
        solution.save(where)
    assert_one_line(err, "Solution.save:", said)


def test_save_takes_one_format_as_a_string(solution, tmp_path):
    """``save(formats="svg")`` was refused as the formats 's', 'v', 'g'."""
    written = {path.name for path in solution.save(tmp_path / "run", formats="svg")}
    assert {"orbits.svg", "raan.svg", "cost.svg"} <= written
    assert not any(name.endswith(".png") for name in written)


@pytest.mark.parametrize(("formats", "said"), [(("bmp",), "unknown figure format(s) bmp"),
                                              (5, "formats must be a figure format or a")])
def test_save_refuses_an_unknown_format_before_writing(solution, tmp_path, formats, said):
    with pytest.raises(OutputError) as err:
        solution.save(tmp_path / "run", formats=formats)
    assert_one_line(err, said, "png, svg, pdf")
    assert not (tmp_path / "run").exists()


# ------------------------------------------------------- item 17: reopening a run folder
START = pd.Timestamp("2020-05-24T00:00:00", tz="UTC")
MU = 3.986004418e14  # m^3/s^2


def test_solution_load_reopens_what_save_wrote(solution, tmp_path):
    """The paper case (its method: iterations, initial legs): saved, loaded, the same path,
    totals, legs, history and ``solution.json``."""
    folder = tmp_path / "run"
    solution.save(folder, formats=())
    loaded = Solution.load(folder)
    assert loaded.path == solution.path and loaded.legs == solution.legs
    assert loaded.total_dv_mps == solution.total_dv_mps
    assert loaded.total_duration_days == solution.total_duration_days
    assert loaded.iterations == solution.iterations
    assert loaded.initial_legs == solution.initial_legs
    assert loaded.mission == solution.mission and loaded.status == solution.status
    assert loaded.to_dict() == solution.to_dict()
    assert loaded.catalog.ids == solution.path  # the path's debris as planned
    assert loaded.summary() == solution.summary()


def test_solution_load_names_the_file_and_the_field(tmp_path):
    with pytest.raises(SdcError) as err:
        Solution.load(tmp_path)
    assert_one_line(err, f"{tmp_path}: no solution.json: not a run folder")
    (tmp_path / "solution.json").write_text('{"legs": [], "mission": {"tmax_days": 0}}')
    with pytest.raises(SdcError) as err:
        Solution.load(tmp_path)
    assert_one_line(err, "solution.json: mission.tmax_days: expected a number")


def synthetic_flight(solution) -> Flight:
    """A flight of ``solution``'s plan made by hand: two impulses per leg, one
    rendezvous, a circular arc of 20 samples per leg (its tables and files are what the
    round trip compares, not a replay)."""
    frame = solution.catalog.frame.set_index("id").loc[list(solution.path)].reset_index()
    catalog = replace(solution.catalog, frame=frame, start=START, invalid=None)
    legs = tuple(PlannedLeg(leg.from_id, leg.to_id, leg.departure_day, leg.duration_days,
                            leg.drift_a_km, leg.drift_inc_deg, leg.side, leg.dv_mps)
                 for leg in solution.legs)  # fmt: skip
    plan = FlightPlan(legs, catalog, solution.mission.tmax_days, solution.mission.drift_altitude_km,
                      sum(leg.dv_mps for leg in legs), solution.total_duration_days)
    rng = np.random.default_rng(48)
    maneuvers, meetings, segments = [], [], []
    t1 = legs[0].departure_day * 86400.0 + 0.25
    for k, leg in enumerate(legs, start=1):
        t0, t1 = t1, t1 + max(leg.duration_days, 0.1) * 86400.0 + 0.123
        for kind, t in (("depart", t0), ("arrive", t1)):
            maneuvers.append(Maneuver(t, k, kind, rng.normal(size=3), rng.normal(size=3)))
        meetings.append(Rendezvous(t1, leg.to_id, *rng.uniform(0.0, 2.0, 9),
                                   in_time=bool(k % 2)))  # fmt: skip
        a = leg.drift_a_km * 1e3
        t = np.linspace(t0, t1, 20)
        angle = np.sqrt(MU / a**3) * t
        r = a * np.column_stack([np.cos(angle), np.sin(angle), np.zeros_like(t)])
        v = np.sqrt(MU / a) * np.column_stack([-np.sin(angle), np.cos(angle), np.zeros_like(t)])
        segments.append((t, r, v))
    return Flight(plan, tuple(maneuvers), tuple(meetings), tuple(segments),
                  ForceModel.named("j2-j4"), "j2", 12.5, notes=("a note",))


def test_flight_load_reopens_what_save_wrote(solution, tmp_path):
    folder = tmp_path / "run"
    solution.save(folder, formats=())
    flight = synthetic_flight(solution)
    flight.save(folder)
    for where in (folder, folder / "flight"):  # the run folder, or its flight/
        loaded = Flight.load(where)
        assert loaded.status == flight.status and loaded.summary() == flight.summary()
        saved, read = flight.to_dict(), loaded.to_dict()
        assert read.keys() == saved.keys()
        for key, value in saved.items():  # floats to the files' 10 digits, the rest as is
            assert read[key] == (pytest.approx(value, rel=1e-9) if isinstance(value, float)
                                 else value), key  # fmt: skip
        for read, saved in ((loaded.maneuvers_frame(), flight.maneuvers_frame()),
                            (loaded.rendezvous_frame(), flight.rendezvous_frame())):
            late = pd.to_datetime(read.pop("epoch_utc")) - pd.to_datetime(saved.pop("epoch_utc"))
            assert late.abs().max() <= pd.Timedelta(microseconds=1)  # written to the µs
            pd.testing.assert_frame_equal(read, saved, rtol=1e-9)
        assert [r.in_time for r in loaded.rendezvous] == [True, False, True, False]
        assert loaded.plan.legs == flight.plan.legs
        assert loaded.plan.catalog.ids == flight.plan.catalog.ids
        assert len(loaded.segments) == len(flight.segments)
        for (t, r, v), (t_saved, r_saved, v_saved) in zip(loaded.segments, flight.segments,
                                                          strict=True):  # fmt: skip
            np.testing.assert_allclose(t, t_saved, atol=1e-6)  # epochs to the microsecond
            np.testing.assert_allclose(r, r_saved, atol=1e-4)  # km to 0.1 mm
            np.testing.assert_allclose(v, v_saved, atol=1e-7)  # km/s to 1e-7 m/s


def test_flight_load_says_a_folder_not_flown(solution, tmp_path):
    solution.save(tmp_path / "run", formats=())
    with pytest.raises(SdcError) as err:
        Flight.load(tmp_path / "run")
    assert_one_line(err, "no flight/flight.json: not a flown run folder")


@pytest.mark.parametrize(("where", "error", "said"), [
    ("/proc/x", FolderError, "Flight.save: cannot write the flight folder /proc/x: /proc "
                             "refuses new files"),
    (None, OutputError, "Flight.save(run_folder): run_folder must be a path"),
])  # fmt: skip
def test_flight_save_refuses_a_folder_it_cannot_write(solution, where, error, said):
    """Item 15: ``Flight.save("/proc/x")`` was a raw FileNotFoundError."""
    with pytest.raises(error) as err:
        synthetic_flight(solution).save(where)
    assert_one_line(err, said)
