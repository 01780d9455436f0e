"""``Solution.save`` and ``Flight.save`` as a notebook user calls them (issue 48, item 15):
a wrong argument or a folder that cannot take the results is one of the package's errors
(:class:`~sdc_cvx.errors.OutputError`, :class:`~sdc_cvx.errors.FolderError`), in one line
worded for the API, and nothing is written."""

import os

import pytest

from sdc_cvx.errors import FolderError, OutputError, SdcError


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
