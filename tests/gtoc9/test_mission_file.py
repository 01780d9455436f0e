"""GTOC9 mission files written by :func:`sdc_cvx.gtoc9.write_mission_file` (issue 47,
item 4): every number back bit for bit, and files a GTOC9 validator can read."""

import json

import numpy as np
import pytest

from sdc_cvx.errors import MissionError
from sdc_cvx.gtoc9 import Event, read_mission_file, write_campaign, write_mission_file
from tests.gtoc9 import gtoc9_reference as ref
from tests.gtoc9.test_gtoc9_check import (  # noqa: F401 (the fixtures rows, transfer)
    T_DEPART_B,
    A,
    B,
    check,
    expected_m0,
    mission_lines,
    rows,
    transfer,
)


def test_the_file_holds_every_number_to_the_last_bit(tmp_path):
    epoch = 23505.5 + 4500.0 / 86400.0  # needs 17 digits: a day's 1e-11 is 1 µs
    events = [Event(epoch, (1.0 / 3.0, -7.1e6, 2e-300), (7.5e3, 0.1, -0.0), (0, 0, 1e-9), 3),
              Event(epoch + 5.000000000001, (1, 2, 3), (4, 5, 6), (7, 8, 9), -1)]  # fmt: skip
    path = write_mission_file(tmp_path / "mission_01.txt", events, comment="two\nlines")
    text = path.read_text()
    assert text.startswith("# two\n# lines\n# epoch x y z vx vy vz dvx dvy dvz id\n")
    table = np.loadtxt(path)  # numpy's reader, not ours
    expected = [[*e.fields(), e.ident] for e in events]
    assert table.tolist() == expected
    assert [line.split()[-1] for line in text.splitlines()[3:]] == ["3", "-1"]


def test_a_written_mission_is_valid(tmp_path, rows, transfer):  # noqa: F811
    numbers = [np.array(line.split(), float) for line in mission_lines(rows, transfer)]
    events = [Event(n[0], n[1:4], n[4:7], n[7:10], int(n[10])) for n in numbers]
    write_mission_file(tmp_path / "gtoc9" / "mission_01.txt", events)
    result = check(tmp_path)
    assert result.exit_code == 0, result.stderr
    assert f"debris {A} " in result.output


def test_an_event_is_refused_without_3_components_or_a_valid_id():
    with pytest.raises(MissionError, match="Event.dv: expected 3 components, got 2"):
        Event(23500.0, (1, 2, 3), (4, 5, 6), (7, 8), 1)
    with pytest.raises(MissionError, match="Event.ident: expected -1 or a debris id"):
        Event(23500.0, (1, 2, 3), (4, 5, 6), (7, 8, 9), -2)


def test_every_malformed_line_is_named(tmp_path):
    path = tmp_path / "mission_01.txt"
    path.write_text("# header\n1 2 3\n" + " ".join(["1"] * 10) + " x\n"
                    + " ".join(["1"] * 10) + " 2.5\n" + " ".join(["nan"] + ["1"] * 10) + "\n")
    events, problems = read_mission_file(path)
    assert events == []
    assert [p.line for p in problems] == [2, 3, 4, 5]
    assert "3 fields, expected 11" in problems[0].message
    assert "id 'x' is not a finite number" in problems[1].message
    assert "id '2.5': expected -1 or a debris id" in problems[2].message
    assert "epoch 'nan' is not a finite number" in problems[3].message


def test_a_launch_before_the_window_is_refused(tmp_path, rows):  # noqa: F811
    t = 23400.0
    (r1, v1), (r2, v2) = ref.debris_state(rows[5], t), ref.debris_state(rows[5], t + 5.0)
    events = [Event(t, r1, v1, (0, 0, 0), 5), Event(t + 5.0, r2, v2, (0, 0, 0), 5)]
    write_mission_file(tmp_path / "mission_01.txt", events)
    result = check(tmp_path)
    assert result.exit_code == 1
    assert "mission_01.txt:2: window: launch at MJD2000 23400.000000; expected >= 23467" \
        in result.stderr


def test_an_impulse_during_a_stay_is_refused(tmp_path, rows):  # noqa: F811
    t = 23500.0
    states = [ref.debris_state(rows[5], t + d) for d in (0.0, 2.0, 6.0)]
    events = [Event(t, *states[0], (0, 0, 0), 5), Event(t + 2.0, *states[1], (0.5, 0, 0), -1),
              Event(t + 6.0, *states[2], (0, 0, 0), 5)]  # fmt: skip
    write_mission_file(tmp_path / "mission_01.txt", events)
    result = check(tmp_path)
    assert result.exit_code == 1
    assert "mission_01.txt:3: stay: an impulse (-1) during the stay at debris 5" in result.stderr
    assert result.stderr.count("error:") == 1  # the stay is not propagated, its debris once
    assert "debris 5;" in result.output


def test_a_folder_without_mission_files_or_debris_file_exits_2(tmp_path, rows):  # noqa: F811
    assert check(tmp_path).exit_code == 2
    t = 23500.0
    (r1, v1), (r2, v2) = ref.debris_state(rows[5], t), ref.debris_state(rows[5], t + 5.0)
    write_mission_file(tmp_path / "mission_01.txt",
                       [Event(t, r1, v1, (0, 0, 0), 5), Event(t + 5.0, r2, v2, (0, 0, 0), 5)])
    result = check(tmp_path, "--debris", str(tmp_path / "none.txt"))
    assert result.exit_code == 2 and "none.txt" in result.stderr
    assert check(tmp_path).exit_code == 0


def test_a_campaign_folder_has_its_files_and_its_summary(tmp_path, rows, transfer):  # noqa: F811
    numbers = [np.array(line.split(), float) for line in mission_lines(rows, transfer)]
    first = [Event(n[0], n[1:4], n[4:7], n[7:10], int(n[10])) for n in numbers]
    t = T_DEPART_B + 40.0
    (r1, v1), (r2, v2) = ref.debris_state(rows[5], t), ref.debris_state(rows[5], t + 5.0)
    second = [Event(t, r1, v1, (0, 0, 0), 5), Event(t + 5.0, r2, v2, (0, 0, 0), 5)]
    path = write_campaign(tmp_path, [first, second])
    summary = json.loads(path.read_text())
    m0 = expected_m0([(n[7:10], k in (1, 3)) for k, n in enumerate(numbers)])
    assert [m["debris"] for m in summary["missions"]] == [[A, B], [5]]
    assert [m["file"] for m in summary["missions"]] == ["gtoc9/mission_01.txt",
                                                        "gtoc9/mission_02.txt"]  # fmt: skip
    assert summary["missions"][0]["m0_kg"] == pytest.approx(m0, rel=1e-12)
    assert summary["missions"][1]["m0_kg"] == pytest.approx(2030.0, rel=1e-12)
    cost = 55 + 2e-6 * (m0 - 2000) ** 2 + 55 + 2e-6 * 30.0**2
    assert summary["J_meur"] == pytest.approx(cost, rel=1e-12)
    result = check(tmp_path)
    assert result.exit_code == 0, result.stderr
    assert f"J = {cost:.4f} MEUR" in result.output
    with pytest.raises(MissionError, match="holds 2 mission files already"):
        write_campaign(tmp_path, [second])


def test_a_flight_in_gtoc9_frame_becomes_the_mission_it_flew(tmp_path, rows, transfer):  # noqa: F811
    """A flight's manoeuvres and segments (the shape :func:`sdc_cvx.flight.fly` returns)
    built from the tests' valid mission: its events are that mission's, and valid."""
    from types import SimpleNamespace

    import pandas as pd

    from sdc_cvx.flight.result import Maneuver
    from sdc_cvx.gtoc9 import flight_events
    from tests.gtoc9.test_gtoc9_check import T_ARRIVE_A, T_ARRIVE_B, T_DEPART_A

    numbers = [np.array(line.split(), float) for line in mission_lines(rows, transfer)]
    day = 86400.0
    t_dep, t_arr, t_end = [(t - T_ARRIVE_A) * day for t in (T_DEPART_A, T_ARRIVE_B, T_DEPART_B)]
    v_dep, r_end, v_end = transfer
    r_a, v_a = numbers[1][1:4], numbers[1][4:7]
    segments = [
        ([0.0, t_dep], [numbers[0][1:4], r_a], [numbers[0][4:7], v_a]),
        ([t_dep, t_arr], [r_a, r_end], [v_dep, v_end]),
        ([t_arr, t_end], [r_end, numbers[3][1:4]], [v_end + numbers[2][7:10], numbers[3][4:7]]),
    ]  # fmt: skip
    maneuvers = [Maneuver(t_dep, 1, "depart", numbers[1][7:10], np.zeros(3)),
                 Maneuver(t_arr, 1, "arrive", numbers[2][7:10], np.zeros(3))]  # fmt: skip
    plan = SimpleNamespace(start=pd.Timestamp("2000-01-01", tz="UTC") + pd.Timedelta(days=23500),
                           legs=[SimpleNamespace(from_id=str(A), to_id=str(B))])  # fmt: skip
    flight = SimpleNamespace(plan=plan, maneuvers=maneuvers, segments=segments, frame="EME2000")
    events = flight_events(flight)
    assert [e.ident for e in events] == [A, A, B, B]
    for event, expected in zip(events, numbers, strict=True):
        assert [*event.fields(), event.ident] == pytest.approx(expected.tolist(), rel=1e-15)
    write_mission_file(tmp_path / "mission_01.txt", events)
    result = check(tmp_path)
    assert result.exit_code == 0, result.stderr
    with pytest.raises(MissionError, match="expected 'EME2000'"):
        flight_events(SimpleNamespace(**{**vars(flight), "frame": "GCRF"}))
