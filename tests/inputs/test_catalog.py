"""Tests of sdc_cvx.inputs.catalog: the paper's Table 5, validation messages, epochs, subsets."""

from __future__ import annotations

import math
import os
import re

import numpy as np
import pandas as pd
import pytest

from sdc_cvx.errors import CatalogWarning
from sdc_cvx.inputs.catalog import Catalog, CatalogError

# Paper Table 5: id -> (a km, e, inc deg, initial RAAN deg), typed in from the paper.
TABLE5 = {
    "1": (7030.5, 0.0001, 98.0, 221.1),
    "2": (7055.3, 0.0001, 98.1, 188.3),
    "3": (7080.0, 0.0001, 98.2, 164.4),
    "4": (7104.4, 0.0003, 98.3, 235.0),
    "5": (7128.5, 0.0000, 98.4, 174.7),
    "6": (7152.5, 0.0001, 98.5, 194.1),
    "7": (7176.3, 0.0001, 98.6, 149.0),
    "8": (7200.0, 0.0001, 98.7, 180.3),
    "9": (7223.2, 0.0002, 98.8, 200.6),
    "10": (7246.4, 0.0001, 98.9, 191.0),
    "11": (7269.3, 0.0003, 99.0, 160.2),
}

HEADER = "id,a_km,e,inc_deg,raan_deg"


def hand_rate_deg_per_day(a_km, inc_deg, e=0.0):
    """J2 RAAN rate of Eq. 7 written out independently, with the paper's R_T and mu."""
    j2, mu, r_t = 1.08263e-3, 3.986e14, 6378137.0
    a = a_km * 1000.0
    n = math.sqrt(mu / a**3)
    rate = -1.5 * j2 * n * (r_t / a) ** 2 * math.cos(math.radians(inc_deg)) / (1 - e**2) ** 2
    return math.degrees(rate) * 86400.0


def write(tmp_path, text, name="debris.csv"):
    path = tmp_path / name
    path.write_text(text, encoding="utf-8")
    return path


def error_of(tmp_path, text, **kwargs):
    with pytest.raises(CatalogError) as info:
        Catalog.from_csv(write(tmp_path, text), **kwargs)
    return str(info.value)


# ---------------------------------------------------------------------- paper case
def test_paper_case_matches_table5():
    cat = Catalog.paper_case()
    assert len(cat) == 11
    assert cat.ids == tuple(TABLE5)
    assert cat.source == "paper Table 5"
    assert cat.start is None
    expected = np.array(list(TABLE5.values()))
    got = cat.frame[["a_km", "e", "inc_deg", "raan_deg"]].to_numpy()
    np.testing.assert_allclose(got, expected, rtol=0, atol=1e-12)
    assert list(cat.frame.index) == list(range(11))


def test_paper_case_si_accessors_and_altitude():
    cat = Catalog.paper_case()
    a_km, e, inc_deg, raan_deg = np.array(list(TABLE5.values())).T
    np.testing.assert_allclose(cat.a_m, a_km * 1000.0)
    np.testing.assert_allclose(cat.e, e)
    np.testing.assert_allclose(cat.inc_rad, inc_deg * math.pi / 180.0)
    np.testing.assert_allclose(cat.raan_rad, raan_deg * math.pi / 180.0)
    np.testing.assert_allclose(cat.frame["altitude_km"], a_km - 6378.137)
    assert cat.a_m.dtype == float


def test_paper_case_debris_are_sun_synchronous():
    # Part V-A: "The 11 debris are on sun-synchronous orbits": 360 deg per tropical year.
    rates = Catalog.paper_case().frame["raan_rate_deg_per_day"].to_numpy()
    np.testing.assert_allclose(rates, 360.0 / 365.2422, rtol=1e-3)


@pytest.mark.parametrize(
    ("a_km", "inc_deg", "table2"),
    [(7000.0, 98.0, 1.002), (7200.0, 98.0, 0.908), (7000.0, 99.0, 1.126), (7200.0, 99.0, 1.020)],
)
def test_raan_rate_column_matches_table2(a_km, inc_deg, table2):
    frame = pd.DataFrame({"id": ["x"], "a_km": [a_km], "e": [0.0], "inc_deg": [inc_deg]})
    frame["raan_deg"] = 0.0
    rate = Catalog.from_frame(frame).frame["raan_rate_deg_per_day"].iat[0]
    assert rate == pytest.approx(table2, rel=2e-3)


# ---------------------------------------------------------------------- reading
def test_the_unknown_column_warning_names_every_column_read(tmp_path):
    """Found as a user: it named id, a_km, e, inc_deg, raan_deg, name and epoch, not the
    position on the orbit (arglat_deg, or argp_deg and mean_anomaly_deg) that fly needs."""
    text = f"{HEADER},arg_lat\n1,7000,0,98,10,5\n"
    with pytest.warns(CatalogWarning) as said:
        Catalog.from_csv(write(tmp_path, text))
    read = str(said[0].message).split("the columns read are")[1]
    for column in ("id", "a_km", "inc_deg", "name", "epoch", "arglat_deg", "argp_deg",
                   "mean_anomaly_deg"):  # fmt: skip
        assert re.search(rf"\b{column}\b", read), column


def test_values_in_other_units_are_said(tmp_path):
    """Found as a user: a_km in metres was only 'dropped: above-leo', with no word on the
    units (angles in radians are refused: tests/cli/test_inputs_face_value.py)."""
    rows = "1,7178000,0.001,98,0.2\n2,7180000,0.001,98,100\n3,7190000,0.001,98,200\n"
    with pytest.warns(CatalogWarning, match=r"a_km: a median of 7.18e\+06: metres"):
        Catalog.from_csv(write(tmp_path, f"{HEADER}\n{rows}"), on_invalid="set aside")


def test_csv_ids_stay_strings_and_extra_columns_are_kept(tmp_path):
    text = (
        f"{HEADER},name,norad\n"
        "5,7000,0,98,10,SL-8 R/B,007\n007,7100,0,98,20,,1e3\n1e3,7200,0,98,30,x,5\n"
    )
    with pytest.warns(CatalogWarning, match="unknown column 'norad' is not used"):
        cat = Catalog.from_csv(write(tmp_path, text))
    assert cat.ids == ("5", "007", "1e3")
    assert all(isinstance(value, str) for value in cat.frame["id"])
    assert list(cat.frame["name"]) == ["SL-8 R/B", "", "x"]
    assert list(cat.frame["norad"]) == ["007", "1e3", "5"]
    assert cat.source == str(tmp_path / "debris.csv")
    assert cat.start is None
    assert "epoch" not in cat.frame.columns


def test_from_frame_integer_ids_become_strings():
    frame = pd.DataFrame(
        {"id": [5, 12], "a_km": [7000, 7100], "e": [0, 0], "inc_deg": [98, 98], "raan_deg": [1, 2]}
    )
    assert Catalog.from_frame(frame).ids == ("5", "12")


@pytest.mark.parametrize(
    ("raan_in", "raan_out"),
    [("-10", 350.0), ("370", 10.0), ("720", 0.0), ("-720.5", 359.5), ("359.25", 359.25)],
)
def test_raan_is_wrapped_into_0_360(tmp_path, raan_in, raan_out):
    cat = Catalog.from_csv(write(tmp_path, f"{HEADER}\n1,7000,0,98,{raan_in}\n"))
    assert cat.frame["raan_deg"].iat[0] == pytest.approx(raan_out, abs=1e-9)
    assert 0.0 <= cat.frame["raan_deg"].iat[0] < 360.0


def test_tiny_negative_raan_wraps_to_zero_not_360():
    frame = pd.DataFrame({"id": ["a"], "a_km": [7000.0], "e": [0.0], "inc_deg": [98.0]})
    frame["raan_deg"] = -1e-20
    raan = Catalog.from_frame(frame).frame["raan_deg"].iat[0]
    assert 0.0 <= raan < 360.0


# ---------------------------------------------------------------------- epochs
EPOCH_CSV = (
    f"{HEADER},epoch\nA,7000,0,98,100,2020-05-01T00:00:00Z\nB,7200,0,99,359,2020-05-31T00:00:00Z\n"
)


def test_epochs_propagate_to_latest_epoch(tmp_path):
    cat = Catalog.from_csv(write(tmp_path, EPOCH_CSV))
    assert cat.start == pd.Timestamp("2020-05-31T00:00:00", tz="UTC")
    rate = hand_rate_deg_per_day(7000.0, 98.0)
    assert rate == pytest.approx(1.0013, rel=1e-4)
    moved = cat.frame["raan_deg"].iat[0] - 100.0
    assert moved == pytest.approx(30 * rate, rel=1e-9)
    assert moved == pytest.approx(30 * 1.002, rel=2e-3)  # Table 2: 1.002 deg/day
    assert cat.frame["raan_deg"].iat[1] == pytest.approx(359.0)  # B is at its own epoch
    assert list(cat.frame["raan_epoch_deg"]) == [100.0, 359.0]
    assert list(cat.frame["epoch"]) == [
        pd.Timestamp("2020-05-01", tz="UTC"),
        pd.Timestamp("2020-05-31", tz="UTC"),
    ]


def test_epochs_propagate_to_explicit_start_backwards_and_wrap(tmp_path):
    cat = Catalog.from_csv(write(tmp_path, EPOCH_CSV), start="2020-05-21T00:00:00")
    assert cat.start == pd.Timestamp("2020-05-21", tz="UTC")  # naive means UTC
    rate_a = hand_rate_deg_per_day(7000.0, 98.0)
    rate_b = hand_rate_deg_per_day(7200.0, 99.0)
    assert cat.frame["raan_deg"].iat[0] == pytest.approx(100.0 + 20 * rate_a, rel=1e-9)
    assert cat.frame["raan_deg"].iat[1] == pytest.approx(359.0 - 10 * rate_b, rel=1e-9)

    later = Catalog.from_csv(write(tmp_path, EPOCH_CSV), start=pd.Timestamp("2020-06-10"))
    assert later.frame["raan_deg"].iat[1] == pytest.approx(359.0 + 10 * rate_b - 360.0, rel=1e-9)


def test_epoch_with_offset_and_naive_epoch_are_utc(tmp_path):
    text = f"{HEADER},epoch\nA,7000,0,98,0,2020-05-01T02:00:00+02:00\nB,7000,0,98,0,2020-05-01\n"
    cat = Catalog.from_csv(write(tmp_path, text))
    assert cat.start == pd.Timestamp("2020-05-01T00:00:00", tz="UTC")
    np.testing.assert_allclose(cat.frame["raan_deg"], [0.0, 0.0], atol=1e-12)


def test_start_without_epochs_is_kept_and_raans_unchanged(tmp_path):
    cat = Catalog.from_csv(write(tmp_path, f"{HEADER}\n1,7000,0,98,42\n"), start="2021-01-01")
    assert cat.start == pd.Timestamp("2021-01-01", tz="UTC")
    assert cat.frame["raan_deg"].iat[0] == 42.0


def test_all_blank_epochs_mean_no_epochs(tmp_path):
    cat = Catalog.from_csv(write(tmp_path, f"{HEADER},epoch\n1,7000,0,98,42,\n2,7000,0,98,43, \n"))
    assert cat.start is None
    assert "epoch" not in cat.frame.columns


def test_from_frame_accepts_datetime_epochs():
    frame = pd.DataFrame({"id": ["a", "b"], "a_km": [7000.0] * 2, "e": [0.0] * 2})
    frame["inc_deg"] = 98.0
    frame["raan_deg"] = 10.0
    frame["epoch"] = pd.to_datetime(["2020-01-01", "2020-01-02"])
    cat = Catalog.from_frame(frame)
    assert cat.start == pd.Timestamp("2020-01-02", tz="UTC")
    rate = hand_rate_deg_per_day(7000.0, 98.0)
    assert cat.frame["raan_deg"].iat[0] == pytest.approx(10.0 + rate, rel=1e-9)


# ---------------------------------------------------------------------- errors
def test_missing_file(tmp_path):
    path = tmp_path / "nope.csv"
    with pytest.raises(CatalogError, match=r"nope\.csv: file not found"):
        Catalog.from_csv(path)


def test_directory_is_not_a_file(tmp_path):
    with pytest.raises(CatalogError, match="is a directory"):
        Catalog.from_csv(tmp_path)


@pytest.mark.skipif(os.name != "posix" or os.geteuid() == 0, reason="root reads any file")
def test_unreadable_file(tmp_path):
    path = write(tmp_path, f"{HEADER}\n1,7000,0,98,0\n")
    path.chmod(0)
    with pytest.raises(CatalogError, match="not readable"):
        Catalog.from_csv(path)


def test_not_utf8(tmp_path):
    path = tmp_path / "debris.csv"
    path.write_bytes(b"id,a_km,e,inc_deg,raan_deg\n1,7000,0,98,\xff\n")
    with pytest.raises(CatalogError, match="not a UTF-8 text file"):
        Catalog.from_csv(path)


@pytest.mark.parametrize("text", ["", "\n\n  \n"])
def test_empty_file(tmp_path, text):
    message = error_of(tmp_path, text)
    assert "debris.csv: empty file (no header line)" in message


def test_header_without_rows(tmp_path):
    assert "debris.csv: header but no data rows" in error_of(tmp_path, f"{HEADER}\n\n")


def test_missing_columns_are_all_named_with_columns_found(tmp_path):
    message = error_of(tmp_path, "id,a_km,inclination,raan_deg\n1,7000,98,0\n")
    assert "missing required column(s) 'e', 'inc_deg'" in message
    assert "found 'id', 'a_km', 'inclination', 'raan_deg'" in message


def test_duplicate_and_blank_column_names(tmp_path):
    message = error_of(tmp_path, f"{HEADER},e,\n1,7000,0,98,0,0,\n")
    assert "column 'e' appears more than once" in message
    assert "column 7 has no name" in message


@pytest.mark.parametrize(
    ("row", "field", "expected"),
    [
        ("1,abc,0,98,0", "a_km", "expected a number, got 'abc'"),
        ("1,,0,98,0", "a_km", "expected a number, got a blank value"),
        ("1,7000,nan,98,0", "e", "expected a number, got 'nan' (NaN)"),
        (
            "1,6000,0,98,0",
            "a_km",
            "expected a number > 6378.137, got '6000' (below the Earth's radius 6378.137 km)",
        ),
        ("1,6378.137,0,98,0", "a_km", "expected a number > 6378.137, got '6378.137' (at the"),
        ("1,7000,1.2,98,0", "e", "expected a number in [0, 1), got '1.2'"),
        ("1,7000,1,98,0", "e", "expected a number in [0, 1), got '1'"),
        ("1,7000,-0.1,98,0", "e", "expected a number in [0, 1), got '-0.1'"),
        ("1,7000,0,180.5,0", "inc_deg", "expected a number in [0, 180], got '180.5'"),
        ("1,7000,0,-1,0", "inc_deg", "expected a number in [0, 180], got '-1'"),
        ("1,7000,0,98,inf", "raan_deg", "expected a finite number, got 'inf'"),
        ("  ,7000,0,98,0", "id", "expected a non-blank id, got a blank value"),
    ],
)
def test_bad_value_names_file_row_line_field(tmp_path, row, field, expected):
    # The bad row is data row 2, on line 4 because of the blank line 3.
    message = error_of(tmp_path, f"{HEADER}\nok,7000,0,98,0\n\n{row}\n")
    assert message.splitlines()[0] == f"1 problem in {tmp_path / 'debris.csv'}:"
    assert f"debris.csv, row 2 (line 4), field '{field}': {expected}" in message


def test_inclination_bounds_are_inclusive(tmp_path):
    cat = Catalog.from_csv(write(tmp_path, f"{HEADER}\n1,7000,0,0,0\n2,7000,0,180,0\n"))
    assert list(cat.frame["inc_deg"]) == [0.0, 180.0]


def test_duplicate_id_names_both_rows(tmp_path):
    message = error_of(tmp_path, f"{HEADER}\n7,7000,0,98,0\n8,7000,0,98,0\n7,7100,0,98,0\n")
    assert "row 3 (line 4), field 'id': duplicate id '7', also in row 1 (line 2)" in message


def test_bad_epoch(tmp_path):
    message = error_of(
        tmp_path, f"{HEADER},epoch\n1,7000,0,98,0,2020-05-24T12:00:00Z\n2,7000,0,98,0,yesterday\n"
    )
    assert "row 2 (line 3), field 'epoch': expected an ISO-8601 UTC date" in message
    assert "got 'yesterday'" in message


def test_epochs_for_some_rows_only(tmp_path):
    text = f"{HEADER},epoch\n1,7000,0,98,0,2020-05-24\n2,7000,0,98,0,\n3,7000,0,98,0,2020-05-25\n"
    message = error_of(tmp_path, text)
    assert message.startswith("1 problem in")
    assert "row 2 (line 3), field 'epoch': blank, but other rows have an epoch" in message


def test_bad_start_argument(tmp_path):
    message = error_of(tmp_path, f"{HEADER}\n1,7000,0,98,0\n", start="soon")
    assert "argument 'start'" in message and "got 'soon'" in message


def test_row_with_wrong_number_of_fields(tmp_path):
    message = error_of(tmp_path, f"{HEADER}\n1,7000,0,98\n2,7000,0,98,0,5\n")
    assert "row 1 (line 2): expected 5 fields as in the header, got 4" in message
    assert "row 2 (line 3): expected 5 fields as in the header, got 6" in message


def test_line_numbers_follow_multiline_quoted_fields(tmp_path):
    text = f'{HEADER},name\n1,7000,0,98,0,"two\nlines"\n2,7000,0,98,x,b\n'
    assert "row 2 (line 4), field 'raan_deg'" in error_of(tmp_path, text)


def test_all_problems_of_a_file_are_reported_together(tmp_path):
    text = f"{HEADER}\n1,7000,1.5,98,0\n2,7000,0,98,0\n2,6000,0,200,0\n"
    with pytest.raises(CatalogError) as info:
        Catalog.from_csv(write(tmp_path, text))
    lines = str(info.value).splitlines()
    assert lines[0] == f"4 problems in {tmp_path / 'debris.csv'}:"
    assert len(lines) == 5
    assert "row 1 (line 2), field 'e'" in lines[1]
    assert "row 3 (line 4), field 'id': duplicate id '2', also in row 2 (line 3)" in lines[2]
    assert "row 3 (line 4), field 'a_km'" in lines[3]
    assert "row 3 (line 4), field 'inc_deg'" in lines[4]
    assert len(info.value.problems) == 4
    assert isinstance(info.value, ValueError)


def test_long_reports_are_capped(tmp_path):
    rows = "".join(f"{k},7000,2,98,0\n" for k in range(30))
    with pytest.raises(CatalogError) as info:
        Catalog.from_csv(write(tmp_path, HEADER + "\n" + rows))
    lines = str(info.value).splitlines()
    assert lines[0].startswith("30 problems in")
    assert len(lines) == 22
    assert lines[-1].strip() == "... and 10 more"
    assert len(info.value.problems) == 30
    assert "row 30 (line 31)" in info.value.problems[-1]


def test_from_frame_validates_like_csv():
    frame = pd.DataFrame(
        {"id": ["a", "b"], "a_km": [7000.0, 7000.0], "e": [0.0, 1.5], "inc_deg": [98.0, np.nan]},
        index=["p", "q"],
    )
    frame["raan_deg"] = 0.0
    with pytest.raises(CatalogError) as info:
        Catalog.from_frame(frame, source="mine")
    message = str(info.value)
    assert message.startswith("2 problems in mine:")
    assert "mine, row 2 (index 'q'), field 'e': expected a number in [0, 1), got 1.5" in message
    assert (
        "mine, row 2 (index 'q'), field 'inc_deg': expected a number, got a blank value" in message
    )


def test_from_frame_rejects_non_frames():
    with pytest.raises(CatalogError, match="expected a DataFrame, got list"):
        Catalog.from_frame([{"id": "a"}])


def test_from_frame_missing_columns_and_no_rows():
    with pytest.raises(CatalogError, match="missing required column"):
        Catalog.from_frame(pd.DataFrame({"id": ["a"], "a_km": [7000.0]}))
    with pytest.raises(CatalogError, match="<DataFrame>: no rows"):
        Catalog.from_frame(pd.DataFrame(columns=["id", "a_km", "e", "inc_deg", "raan_deg"]))


# ---------------------------------------------------------------------- subset
def test_subset_keeps_catalog_order():
    cat = Catalog.paper_case()
    sub = cat.subset(["8", "2", "5"])
    assert sub.ids == ("2", "5", "8")
    assert list(sub.frame.index) == [0, 1, 2]
    np.testing.assert_allclose(sub.frame["a_km"], [7055.3, 7128.5, 7200.0])
    assert sub.start == cat.start
    assert len(cat) == 11  # the original is untouched


def test_subset_unknown_id_is_named():
    with pytest.raises(CatalogError) as info:
        Catalog.paper_case().subset(["1", "12", "x"])
    assert "paper Table 5: unknown debris id(s) '12', 'x';" in str(info.value)


def test_subset_single_string_id_and_empty_selection():
    assert Catalog.paper_case().subset("10").ids == ("10",)
    with pytest.raises(CatalogError, match="at least one debris id"):
        Catalog.paper_case().subset([])


# ---------------------------------------------------------------------- spreadsheet CSV
@pytest.mark.parametrize(
    "text",
    [
        "ID,A_KM,E,INC_DEG,RAAN_DEG\n1,7000,0.001,98,10\n2,7100,0.001,98.2,20\n",
        "id;a_km;e;inc_deg;raan_deg\n1;7000;0.001;98;10\n2;7100;0.001;98.2;20\n",
        "Id\tA_km\te\tinc_deg\tRAAN_deg\n1\t7000\t0.001\t98\t10\n2\t7100\t0.001\t98.2\t20\n",
    ],
    ids=["upper-case", "semicolons", "tabs"],
)
def test_upper_case_and_semicolon_headers_are_read(tmp_path, text):
    """Issue 20: a spreadsheet's export is read as the plain CSV it stands for."""
    cat = Catalog.from_csv(write(tmp_path, text))
    assert cat.ids == ("1", "2")
    assert list(cat.frame["a_km"]) == [7000.0, 7100.0]
    assert list(cat.frame["raan_deg"]) == [10.0, 20.0]


def test_decimal_comma_names_the_fix(tmp_path):
    message = error_of(tmp_path, "id;a_km;e;inc_deg;raan_deg\n1;7000,5;0.001;98;10\n")
    assert "row 1 (line 2), field 'a_km': expected a number, got '7000,5' (a decimal comma? " \
        "write 7000.5)" in message  # fmt: skip


def test_far_epoch_and_bad_field_come_in_one_error(tmp_path):
    """Issue 20: an epoch 60 years before the others and a bad number are one error (not
    one, then the other once the first is fixed)."""
    text = (f"{HEADER},epoch\n1,7000,0,98,0,1960-05-24T00:00:00Z\n2,7000,0,x,0,2020-05-24\n"
            "3,7000,0,98,0,2020-05-24\n")  # fmt: skip
    message = error_of(tmp_path, text)
    assert message.startswith("2 problems in")
    assert "row 1 (line 2), field 'epoch': expected an epoch within 3652.5 days (10 years) of " \
        "the mission start 2020-05-24T00:00:00+00:00, got 1960-05-24T00:00:00+00:00 (60.0 " \
        "years away" in message  # fmt: skip
    assert "row 2 (line 3), field 'inc_deg': expected a number, got 'x'" in message
