"""The values file of a removal programme (issue 27): what it reads and what it refuses."""

import pytest

from sdc_cvx.errors import CatalogError
from sdc_cvx.inputs.values import read_values


def test_a_ranking_is_read_by_its_own_column_names(tmp_path):
    path = tmp_path / "top.csv"
    path.write_text("\ufeffrank,norad_id,listed_score\n1,22566,4048\n2,22220,3710\n\n")
    assert read_values(path, ("norad_id", "listed_score")) == {"22566": 4048.0, "22220": 3710.0}


def test_every_bad_row_is_named_with_its_line_and_field(tmp_path):
    path = tmp_path / "values.csv"
    path.write_text("id,value\n1,2.5\n,3\n1,4\n2,-1\n3,many\n4\n")
    with pytest.raises(CatalogError) as caught:
        read_values(path)
    message = str(caught.value)
    assert "5 problems" in message
    for said in ("line 3, field id: blank", "line 4, field id: '1' repeats line 2",
                 "line 5, field value: expected a number >= 0, got '-1'",
                 "line 6, field value: expected a number >= 0, got 'many'",
                 "line 7: 1 fields, expected 2"):  # fmt: skip
        assert said in message


def test_a_file_without_the_columns_says_which_it_has(tmp_path):
    path = tmp_path / "values.csv"
    path.write_text("norad,score\n1,2\n")
    with pytest.raises(CatalogError, match="the columns 'id' and 'value', found norad, score"):
        read_values(path)
    with pytest.raises(CatalogError, match="cannot read the values file"):
        read_values(tmp_path / "missing.csv")


def test_a_header_alone_is_refused(tmp_path):
    """Found as a user: a values file with no rows made every debris worth 1 (the
    campaign's rule without values), the opposite of "not named: worth 0"."""
    path = tmp_path / "values.csv"
    path.write_text("id,value\n\n")
    with pytest.raises(CatalogError, match="values.csv: no rows under the header"):
        read_values(path)


@pytest.mark.parametrize("mark", [";", "\t"])
def test_a_spreadsheets_export_with_semicolons_or_tabs_is_read(tmp_path, mark):
    """Found as a user: a values CSV exported with ';' (a locale whose decimal mark is the
    comma) was refused for want of the columns 'id' and 'value'."""
    path = tmp_path / "values.csv"
    path.write_text(f"id{mark}value\n22566{mark}4048.5\n22220{mark}3710\n")
    assert read_values(path) == {"22566": 4048.5, "22220": 3710.0}
    path.write_text(f"id{mark}value\n22566{mark}4048,5\n")  # a decimal comma: named
    with pytest.raises(CatalogError, match="line 2, field value: expected a number >= 0, "
                       "got '4048,5'"):  # fmt: skip
        read_values(path)
