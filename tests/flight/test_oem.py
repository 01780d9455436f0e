"""The CCSDS OEM writer: read back by an independent reader (the ``oem`` package), its
keywords, its segments at impulses, and Lagrange interpolation of its samples."""

import math

import numpy as np
import pandas as pd
import pytest

from sdc_cvx.flight.oem import (
    OEM_DEGREE,
    OEM_STEP_S,
    oem_text,
    sample_epochs,
    sample_times,
    write_oem,
)
from sdc_cvx.flight.propagation import ForceModel, propagate
from sdc_cvx.physics.elements import elements_to_state

FORCE = ForceModel()
Z = np.array([0.0, 0.0, 1.0])
START = pd.Timestamp("2026-03-01T00:00:00", tz="UTC")


def epochs(t):
    return START + pd.to_timedelta(np.asarray(t), unit="s")


def flight():
    """Two arcs of an 800 km orbit around a 5 m/s along-track impulse at t = 2 h (the
    impulse's epoch ends the first segment and begins the second), then a third arc of
    three samples only."""
    r, v = elements_to_state(FORCE.r_eq + 800e3, 0.001, 1.72, 0.3, 0.0, 0.4, mu=FORCE.mu)
    segments, t = [], 0.0
    for t_end, dv in ((7200.0, 5.0), (18000.0, -2.0), (18100.0, 0.0)):
        times = sample_times(t, t_end) if t_end - t > 1000 else np.linspace(t, t_end, 3)
        arc = propagate(r, v, t, t_end, FORCE, pole=Z, t_eval=times)
        segments.append((arc.t, arc.r, arc.v))
        r, v, t = arc.r1, arc.v1 + dv * arc.v1 / np.linalg.norm(arc.v1), t_end
    return segments


@pytest.fixture(scope="module")
def written(tmp_path_factory):
    segments = flight()
    path = tmp_path_factory.mktemp("oem") / "trajectory.oem"
    write_oem(path, [(epochs(t), r, v) for t, r, v in segments], object_name="SDC_CVX VEHICLE",
              object_id="SDC_CVX-TEST", comments=("a test flight", "two impulses"),
              creation_date=pd.Timestamp("2026-03-02T12:00:00", tz="UTC"))  # fmt: skip
    return path, segments


def test_read_back_by_an_independent_reader(written):
    oem = pytest.importorskip(
        "oem", reason="the independent OEM reader: pip install oem (a dev-only dependency)"
    )
    path, segments = written
    message = oem.OrbitEphemerisMessage.open(path)
    assert message.version == "2.0"
    read = list(message)
    assert len(read) == len(segments) == 3
    for segment, (t, r, v) in zip(read, segments, strict=True):
        states = list(segment.states)
        assert len(states) == len(t)
        stamps = pd.DatetimeIndex([s.epoch.to_datetime() for s in states]).tz_localize("UTC")
        elapsed = (stamps - START).total_seconds().to_numpy()
        assert np.abs(elapsed - t).max() < 1e-6  # s (the reader keeps microseconds)
        # states to 0.1 mm (the file) and to the reader's 1 us epoch (8 mm at most)
        position = np.array([s.position for s in states]) * 1e3
        velocity = np.array([s.velocity for s in states]) * 1e3
        assert np.abs(position - r).max() < 1e-3  # m
        assert np.abs(velocity - v).max() < 1e-6  # m/s
        assert segment.metadata["REF_FRAME"] == "GCRF"
        assert segment.metadata["CENTER_NAME"] == "EARTH"
        assert segment.metadata["TIME_SYSTEM"] == "UTC"
        assert segment.metadata["OBJECT_ID"] == "SDC_CVX-TEST"
    # consecutive segments share the impulse's epoch, on either side of the velocity jump
    first, second = (list(s.states) for s in read[:2])
    assert first[-1].epoch == second[0].epoch
    assert np.linalg.norm(first[-1].position - second[0].position) < 1e-9
    assert np.linalg.norm(first[-1].velocity - second[0].velocity) * 1e3 == pytest.approx(5.0)


def keyword_values(text):
    pairs = [line.split(" = ", 1) for line in text.splitlines() if " = " in line]
    return [(key.strip(), value.strip()) for key, value in pairs]


def test_keywords_of_the_standard(written):
    path, segments = written
    text = path.read_text()
    lines = text.splitlines()
    assert lines[0] == "CCSDS_OEM_VERS = 2.0"
    assert lines[1:3] == ["COMMENT a test flight", "COMMENT two impulses"]
    pairs = keyword_values(text)
    header = dict(pairs[:3])
    assert header["CREATION_DATE"].startswith("2026-03-02T12:00:00")
    assert header["ORIGINATOR"] == "SDC_CVX"
    assert text.count("META_START") == text.count("META_STOP") == 3
    order = ["OBJECT_NAME", "OBJECT_ID", "CENTER_NAME", "REF_FRAME", "TIME_SYSTEM",
             "START_TIME", "STOP_TIME", "INTERPOLATION", "INTERPOLATION_DEGREE"]  # fmt: skip
    blocks = text.split("META_START")[1:]
    for block, (t, _, _) in zip(blocks, segments, strict=True):
        meta = keyword_values(block.split("META_STOP")[0])
        assert [key for key, _ in meta] == order
        meta = dict(meta)
        assert meta["INTERPOLATION"] == "LAGRANGE"
        assert int(meta["INTERPOLATION_DEGREE"]) == min(OEM_DEGREE, len(t) - 1)
        assert (
            meta["START_TIME"]
            == np.datetime_as_string(
                epochs(t[:1]).tz_convert(None).values.astype("datetime64[ns]"), unit="ns"
            )[0]
        )
        data = [line for line in block.split("META_STOP")[1].splitlines() if line.strip()]
        assert len(data) == len(t) and len(data[0].split()) == 7
        assert data[0].split()[0] == meta["START_TIME"]
        assert data[-1].split()[0] == meta["STOP_TIME"]


def lagrange(nodes, values, t, degree):
    """Lagrange interpolation on the ``degree + 1`` samples about ``t`` (a centred window,
    clamped at the segment's ends)."""
    k = int(np.searchsorted(nodes, t)) - (degree + 1) // 2
    k = min(max(k, 0), len(nodes) - degree - 1)
    xs, ys = nodes[k : k + degree + 1], values[k : k + degree + 1]
    weights = [math.prod((t - xs[m]) / (xs[j] - xs[m]) for m in range(degree + 1) if m != j)
               for j in range(degree + 1)]  # fmt: skip
    return np.asarray(weights) @ ys


def read_samples(path):
    """The samples of each segment, read with nothing but the text: seconds from START,
    positions [m]."""
    out = []
    for block in path.read_text().split("META_START")[1:]:
        meta = dict(keyword_values(block.split("META_STOP")[0]))
        rows = [line.split() for line in block.split("META_STOP")[1].splitlines() if line.strip()]
        stamps = pd.DatetimeIndex([row[0] for row in rows]).tz_localize("UTC")
        t = (stamps - START).total_seconds().to_numpy()
        r = np.array([[float(x) for x in row[1:4]] for row in rows]) * 1e3
        out.append((t, r, int(meta["INTERPOLATION_DEGREE"])))
    return out


def test_lagrange_interpolation_of_the_file_matches_the_propagation(written):
    """Between samples, the stated Lagrange interpolation is within 10 m of the propagation
    (measured: 0.5 m at most, at a segment's ends; OEM_STEP_S's docstring)."""
    path, segments = written
    for (t, r_file, degree), (_, r, v) in zip(read_samples(path)[:2], segments[:2], strict=True):
        assert np.abs(r_file - r).max() < 1e-3
        between = (t[:-1] + t[1:]) / 2
        truth = propagate(r[0], v[0], t[0], t[-1], FORCE, pole=Z, t_eval=between)
        errors = [np.linalg.norm(lagrange(t, r_file, tk, degree) - rk)
                  for tk, rk in zip(between, truth.r, strict=True)]  # fmt: skip
        assert max(errors) < 10.0
        assert np.diff(t).max() <= OEM_STEP_S + 1e-9


def test_sample_helpers_include_both_ends():
    e = sample_epochs("2026-01-01", "2026-01-01T00:10:00.5", 240)
    assert e[0] == pd.Timestamp("2026-01-01", tz="UTC")
    assert e[-1] == pd.Timestamp("2026-01-01T00:10:00.5", tz="UTC")
    assert len(e) == 4 and str(e.tz) == "UTC"
    assert len(sample_epochs(START, START + pd.Timedelta(minutes=8), pd.Timedelta(minutes=4))) == 3
    with pytest.raises(ValueError):
        sample_epochs(START, START - pd.Timedelta(1, "s"), 60)
    times = sample_times(0.0, 100.0)
    assert times[0] == 0.0 and times[-1] == 100.0 and len(times) == OEM_DEGREE + 1
    times = sample_times(0.0, 86400.0)
    assert np.diff(times).max() <= OEM_STEP_S and times[-1] == 86400.0


def test_invalid_segments_are_refused():
    t = np.array([0.0, 60.0, 120.0])
    r = np.ones((3, 3)) * 7e6
    keywords = {"object_name": "X", "object_id": "Y"}
    with pytest.raises(ValueError, match="at least one segment"):
        oem_text([], **keywords)
    with pytest.raises(ValueError, match="not strictly increasing"):
        oem_text([(epochs(t[::-1]), r, r)], **keywords)
    with pytest.raises(ValueError, match="need"):
        oem_text([(epochs(t), r[:2], r)], **keywords)
    with pytest.raises(ValueError, match="starts before"):
        oem_text([(epochs(t), r, r), (epochs(t + 60.0), r, r)], **keywords)
    with pytest.raises(ValueError, match="OBJECT_NAME"):
        oem_text([(epochs(t), r, r)], object_name="two\nlines", object_id="Y")
    # a naive DatetimeIndex is taken as UTC; no interpolation keywords when asked
    text = oem_text([(epochs(t).tz_convert(None), r, r)], interpolation=None, **keywords)
    assert "INTERPOLATION" not in text and "START_TIME = 2026-03-01T00:00:00.000000000" in text
