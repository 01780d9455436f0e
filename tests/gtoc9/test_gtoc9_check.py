"""``sdc-cvx gtoc9-check`` on missions built by the tests' own GTOC9 (issue 47, item 4).

The valid mission is constructed with :mod:`tests.gtoc9.gtoc9_reference` (its own
ephemeris, ODE, Lambert and shooting), never with ``sdc_cvx.gtoc9``: launch at debris 113
(MJD2000 23500), a 5.5-day stay, a 75-minute transfer shot in two-body + J2 to debris 79,
a 6-day stay.  Each mutation breaks one rule, and the validator must name it.
"""

import math
import re
import subprocess
import sys

import numpy as np
import pytest
from click.testing import CliRunner

from sdc_cvx.cli import main
from tests.gtoc9 import gtoc9_reference as ref

pytestmark = pytest.mark.requires_shared_data("gtoc9/debris_data.txt")

A, B = 113, 79
T_ARRIVE_A = 23500.0
T_DEPART_A = 23505.5
TRANSFER_S = 4500.0
T_ARRIVE_B = T_DEPART_A + TRANSFER_S / 86400.0
T_DEPART_B = T_ARRIVE_B + 6.0


def line(epoch, r, v, dv, ident):
    return " ".join(repr(float(x)) for x in (epoch, *r, *v, *dv)) + f" {ident}"


@pytest.fixture(scope="module")
def rows():
    return ref.debris_rows()


@pytest.fixture(scope="module")
def transfer(rows):
    """The departure velocity from A and the arrival state at B of the shot transfer."""
    r_a, v_a = ref.debris_state(rows[A], T_DEPART_A)
    r_b, _ = ref.debris_state(rows[B], T_ARRIVE_B)
    guess, _ = ref.lambert(r_a, r_b, TRANSFER_S, np.cross(r_a, v_a))
    v_dep = ref.shoot(r_a, guess, TRANSFER_S, r_b)
    r_end, v_end, _ = ref.fly(r_a, v_dep, TRANSFER_S)
    return v_dep, r_end, v_end


def mission_lines(rows, transfer, *, t_arrive_a=T_ARRIVE_A, dv_last=(0.0, 0.0, 0.0),
                  arrival_a_offset=(0.0, 0.0, 0.0)):  # fmt: skip
    """The four events of the valid mission (with the mutations' knobs)."""
    v_dep, r_end, v_end = transfer
    r_a0, v_a0 = ref.debris_state(rows[A], t_arrive_a)
    r_a, v_a = ref.debris_state(rows[A], T_DEPART_A)
    r_b, v_b = ref.debris_state(rows[B], T_ARRIVE_B)
    r_b1, v_b1 = ref.debris_state(rows[B], T_DEPART_B)
    return [
        line(t_arrive_a, r_a0 + np.array(arrival_a_offset), v_a0, (0, 0, 0), A),
        line(T_DEPART_A, r_a, v_a, v_dep - v_a, A),
        line(T_ARRIVE_B, r_end, v_end, v_b - v_end, B),
        line(T_DEPART_B, r_b1, v_b1, dv_last, B),
    ]


def expected_m0(dvs):
    """The mass chain written from the rules: from 2000 kg after the last event, each
    impulse times exp(dv / (Isp g0)), each stay (before a departure) + 30 kg."""
    mass = 2000.0
    for dv, departure in reversed(dvs):
        mass *= math.exp(np.linalg.norm(dv) / ref.C_EXHAUST)
        mass += 30.0 if departure else 0.0
    return mass


def write(folder, *missions):
    (folder / "gtoc9").mkdir(parents=True, exist_ok=True)
    for number, lines in enumerate(missions, start=1):
        text = "# epoch x y z vx vy vz dvx dvy dvz id\n" + "\n".join(lines) + "\n"
        (folder / "gtoc9" / f"mission_{number:02d}.txt").write_text(text)
    return folder


def check(folder, *options):
    return CliRunner().invoke(main, ["gtoc9-check", str(folder), *options])


def violations(result, rule):
    return [ln for ln in result.stderr.splitlines() if f": {rule}: " in ln]


def test_a_valid_mission_is_accepted_with_its_cost(tmp_path, rows, transfer):
    v_dep, r_end, v_end = transfer
    _, v_a = ref.debris_state(rows[A], T_DEPART_A)
    _, v_b = ref.debris_state(rows[B], T_ARRIVE_B)
    result = check(write(tmp_path, mission_lines(rows, transfer)))
    assert result.exit_code == 0, result.stderr
    m0 = expected_m0([((0, 0, 0), False), (v_dep - v_a, True), (v_b - v_end, False),
                      ((0, 0, 0), True)])  # fmt: skip
    dv = np.linalg.norm(v_dep - v_a) + np.linalg.norm(v_b - v_end)
    cost = 55.0 + 2.0e-6 * (m0 - 2000.0) ** 2
    assert f"debris {A} {B};" in result.output
    assert f"ΔV {dv:.3f} m/s" in result.output and f"m0 {m0:.3f} kg" in result.output
    assert f"J = {cost:.4f} MEUR" in result.output


def test_a_stay_of_4_days_is_refused(tmp_path, rows, transfer):
    result = check(write(tmp_path, mission_lines(rows, transfer, t_arrive_a=T_DEPART_A - 4.0)))
    assert result.exit_code == 1
    (stay,) = violations(result, "stay")
    assert "mission_01.txt:3:" in stay and "4.000000 days" in stay
    assert result.stderr.count("error:") == 1


def test_31_days_between_rendezvous_is_refused(tmp_path, rows, transfer):
    folder = write(tmp_path, mission_lines(rows, transfer, t_arrive_a=T_ARRIVE_B - 31.0))
    result = check(folder)
    assert result.exit_code == 1
    (gap,) = violations(result, "dt-r")
    assert "mission_01.txt:4:" in gap and "31.0000 days" in gap
    assert result.stderr.count("error:") == 1
    # the transfer-time reading (departure to arrival) accepts it: 75 minutes
    assert check(folder, "--dt-r-from", "departure").exit_code == 0


def test_a_debris_removed_twice_is_refused(tmp_path, rows, transfer):
    t = T_DEPART_B + 40.0  # a second mission, 40 days after the first's end, at A again
    (r1, v1), (r2, v2) = ref.debris_state(rows[A], t), ref.debris_state(rows[A], t + 5.0)
    again = [line(t, r1, v1, (0, 0, 0), A), line(t + 5.0, r2, v2, (0, 0, 0), A)]
    result = check(write(tmp_path, mission_lines(rows, transfer), again))
    assert result.exit_code == 1
    (twice,) = violations(result, "once")
    assert "mission_02.txt:2:" in twice and f"debris {A} removed twice" in twice
    assert result.stderr.count("error:") == 1


def test_missions_less_than_30_days_apart_are_refused(tmp_path, rows, transfer):
    t = T_DEPART_B + 10.0
    (r1, v1), (r2, v2) = ref.debris_state(rows[0], t), ref.debris_state(rows[0], t + 5.0)
    other = [line(t, r1, v1, (0, 0, 0), 0), line(t + 5.0, r2, v2, (0, 0, 0), 0)]
    result = check(write(tmp_path, mission_lines(rows, transfer), other))
    assert result.exit_code == 1
    (gap,) = violations(result, "dt-m")
    assert "mission_02.txt:2:" in gap and "10.0000 days" in gap


def test_an_arc_below_6600_km_perigee_is_refused(tmp_path, rows, transfer):
    """Depart A 300 m/s slower than the transfer (perigee below 6600 km), coast 10
    minutes, and shoot from there to B by a deep-space manoeuvre: every other rule holds."""
    v_dep, _, _ = transfer
    r_a, v_a = ref.debris_state(rows[A], T_DEPART_A)
    v_low = v_dep - 300.0 * v_dep / np.linalg.norm(v_dep)
    r_c, v_c, states = ref.fly(r_a, v_low, 600.0)
    assert ref.osculating_perigee(states).min() < 6.6e6  # the test's own perigee
    r_b, v_b = ref.debris_state(rows[B], T_ARRIVE_B)
    v_dsm = ref.shoot(r_c, v_c + 300.0 * v_c / np.linalg.norm(v_c), TRANSFER_S - 600.0, r_b)
    r_end, v_end, states2 = ref.fly(r_c, v_dsm, TRANSFER_S - 600.0)
    assert ref.osculating_perigee(states2).min() > 6.6e6
    lines = mission_lines(rows, transfer)
    lines[1] = line(T_DEPART_A, r_a, v_a, v_low - v_a, A)
    lines[2:3] = [line(T_DEPART_A + 600.0 / 86400.0, r_c, v_c, v_dsm - v_c, -1),
                  line(T_ARRIVE_B, r_end, v_end, v_b - v_end, B)]  # fmt: skip
    result = check(write(tmp_path, lines))
    assert result.exit_code == 1
    (low,) = violations(result, "perigee")
    assert "mission_01.txt:3:" in low and "expected >= 6600 km" in low
    assert result.stderr.count("error:") == 1


def test_propellant_over_5000_kg_is_refused(tmp_path, rows, transfer):
    burn = (4500.0, 0.0, 0.0)  # at the last departure: no arc after it, only the mass
    result = check(write(tmp_path, mission_lines(rows, transfer, dv_last=burn)))
    assert result.exit_code == 1
    (mass,) = violations(result, "propellant")
    assert "mission_01.txt:2:" in mass and "expected <= 5000 kg" in mass
    assert result.stderr.count("error:") == 1


def test_a_position_200_m_off_is_refused(tmp_path, rows, transfer):
    lines = mission_lines(rows, transfer, arrival_a_offset=(0.0, 200.0, 0.0))
    result = check(write(tmp_path, lines))
    assert result.exit_code == 1
    (off,) = violations(result, "rendezvous")
    assert "mission_01.txt:2:" in off
    found = float(re.search(r"position ([0-9.]+) m", off).group(1))
    assert found == pytest.approx(200.0, abs=0.01)  # the reader's epochs are to the µs
    assert result.stderr.count("error:") == 1


def test_a_line_of_10_fields_makes_the_file_unreadable(tmp_path, rows, transfer):
    lines = mission_lines(rows, transfer)
    lines[2] = lines[2].rsplit(" ", 1)[0]
    result = check(write(tmp_path, lines))
    assert result.exit_code == 2
    (bad,) = violations(result, "format")
    assert "mission_01.txt:4:" in bad and "10 fields, expected 11" in bad


def test_all_requires_every_debris(tmp_path, rows, transfer):
    result = check(write(tmp_path, mission_lines(rows, transfer)), "--all")
    assert result.exit_code == 1
    (missing,) = violations(result, "all")
    assert "121 of the 123 debris never removed" in missing


@pytest.mark.slow
def test_python_m_sdc_cvx_gtoc9_check(tmp_path, rows, transfer):
    folder = write(tmp_path, mission_lines(rows, transfer))
    done = subprocess.run([sys.executable, "-m", "sdc_cvx", "gtoc9-check", str(folder)],
                          capture_output=True, text=True, timeout=60)  # fmt: skip
    assert done.returncode == 0, done.stderr
    assert "J = " in done.stdout
