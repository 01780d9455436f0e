"""The bad-input corpus: every malformed or hostile input is refused cleanly.

Each case is a few small files (written into a fresh folder) and a command line.  Every
one must give exit code 2, a message on stderr that names the file (and, where it
applies, the row, the field and what was expected), no traceback, and no file written
anywhere (not in the working folder, not at ``--out``).  The commands run in-process
(click's CliRunner) and fail before any solve, so the corpus takes a few seconds.
"""

from __future__ import annotations

import importlib.util
import os
from dataclasses import dataclass, field
from pathlib import Path

import pytest
from click.testing import CliRunner

from sdc_cvx.cli import main

HEADER = "id,a_km,e,inc_deg,raan_deg"
ROWS = "1,7000,0.001,98,10\n2,7050,0.001,98,40\n3,7100,0.001,98,70\n"
GOOD_CSV = f"{HEADER}\n{ROWS}"
TLE_1 = (
    "0 THOR AGENA D R/B\n"
    "1   733U 64002A   20145.30230088 +.00000007 +00000-0 +20152-4 0  9992\n"
    "2   733 099.0143 035.9085 0032950 303.3378 056.4651 14.32394256935785\n"
)
TLE_2 = (
    "0 THOR AGENA D R/B\n"
    "1   815U 64031C   20147.19804992 -.00000013  00000-0  17013-4 0  9995\n"
    "2   815  99.8646 150.6351 0012488  52.4516 307.7793 14.27329406905632\n"
)
GTOC9_ROW = "0 21947.6496 7165739.68 0.0014872 1.7084949 5.4251494 0.5189646 3.2208883\n"
STUDY = 'base = "../in/base.toml"\n[grid]\n"mission.n" = [3, 4]\n'


@dataclass
class Case:
    """Files to write into ``in/`` and the command; ``{in}`` in an argument is that folder."""

    files: dict[str, str | bytes]
    args: list[str]
    expect: list[str]  # parts of stderr, besides the file's name
    names: str | None = None  # the file stderr must name (default: the first file)
    skip: str | None = None
    extra: dict = field(default_factory=dict)


def csv_case(text: str, *expect: str, name="debris.csv", **kw) -> Case:
    return Case({name: text}, ["run", "--catalog", f"{{in}}/{name}"], list(expect), **kw)


def strict_csv_case(text: str, *expect: str, name="debris.csv") -> Case:
    return Case({name: text}, ["run", "--strict", "--catalog", f"{{in}}/{name}"], list(expect))


def scenario_case(mission: str, *expect: str, catalog=GOOD_CSV, extra_toml="") -> Case:
    toml = f'[catalog]\npath = "debris.csv"\n[mission]\n{mission}\n{extra_toml}'
    return Case(
        {"scenario.toml": toml, "debris.csv": catalog}, ["run", "{in}/scenario.toml"], list(expect)
    )


RANDOM_TEXT = "".join(f"{k * 7919 % 100003:x} lorem ipsum {k}\n" for k in range(3000))
JUNK_TLE = "".join(f"1 junk {k}\n2 more junk {k}\n" for k in range(400))

CASES: dict[str, Case] = {
    # ---- CSV catalogs: the file, the row, the field and what was expected
    "csv-missing-file": Case(
        {}, ["run", "--catalog", "{in}/gone.csv"], ["file not found"], names="gone.csv"
    ),
    "csv-empty": csv_case("", "empty file"),
    "csv-header-only": csv_case(HEADER + "\n", "header but no data rows"),
    "csv-missing-column": csv_case(
        "id,a_km,e,inc_deg\n1,7000,0,98\n", "missing required column", "'raan_deg'"
    ),
    "csv-duplicate-column": csv_case(f"{HEADER},e\n1,7000,0,98,10,0\n", "appears more than once"),
    "csv-text-in-a_km": csv_case(
        f"{HEADER}\n1,seven,0,98,10\n", "row 1", "field 'a_km'", "expected"
    ),
    "csv-e-above-one": csv_case(f"{HEADER}\n1,7000,1.5,98,10\n", "field 'e'", "[0, 1)"),
    "csv-raan-1e308": csv_case(
        f"{HEADER}\n1,7000,0.001,98,1e308\n", "field 'raan_deg'", "[-36000, 36000]"
    ),
    "csv-negative-e": csv_case(f"{HEADER}\n1,7000,-0.1,98,10\n", "field 'e'", "[0, 1)"),
    "csv-inclination-200": csv_case(f"{HEADER}\n1,7000,0,200,10\n", "field 'inc_deg'", "[0, 180]"),
    "csv-a-below-earth": csv_case(f"{HEADER}\n1,6000,0,98,10\n", "field 'a_km'", "Earth's radius"),
    # an orbit the model cannot fly among good ones: refused with --strict (without it,
    # dropped with a warning: tests/inputs/test_whole_catalog.py)
    "csv-a-6400-perigee-22km": strict_csv_case(
        f"{HEADER}\n9,6400,0,98,10\n{ROWS}", "row 1", "field 'a_km'", "perigee", "at least 150 km"
    ),
    # the filters act first: an orbit beyond LEO or too eccentric is dropped, named, before
    # any validation (here too few candidates are then left for n = 5)
    "csv-a-1e9": strict_csv_case(
        f"{HEADER}\n9,1e9,0,98,10\n{ROWS}", "dropped: 1 above-leo", "exceeds the 3 candidate"
    ),
    "csv-eccentric-low-perigee": strict_csv_case(
        f"{HEADER}\n1,7000,0.5,98,10\n", "no candidate left", "eccentricity"
    ),
    "csv-nan-a": csv_case(f"{HEADER}\n1,nan,0,98,10\n", "field 'a_km'", "expected"),
    "csv-inf-a": csv_case(f"{HEADER}\n1,inf,0,98,10\n", "field 'a_km'", "expected"),
    "csv-blank-raan": csv_case(f"{HEADER}\n1,7000,0,98,\n", "field 'raan_deg'", "expected"),
    "csv-duplicate-id": csv_case(f"{HEADER}\n1,7000,0,98,10\n1,7050,0,98,20\n", "duplicate id"),
    "csv-ragged-row": csv_case(f"{HEADER}\n1,7000,0,98\n", "row 1", "expected 5 fields"),
    "csv-bad-epoch": csv_case(
        f"{HEADER},epoch\n1,7000,0,98,10,soon\n", "field 'epoch'", "ISO-8601"
    ),
    "csv-some-epochs-blank": csv_case(
        f"{HEADER},epoch\n1,7000,0,98,10,2020-01-01T00:00:00Z\n2,7050,0,98,20,\n",
        "field 'epoch'",
        "other rows have an epoch",
    ),
    "csv-not-utf8": csv_case(b"id,a_km,e,inc_deg,raan_deg\n\xff\xfe,7000,0,98,10\n", "UTF-8"),
    "csv-binary": csv_case(bytes(range(256)) * 8, "debris.csv"),
    # ---- other formats, and files that are no catalog at all
    "txt-random-text": csv_case(RANDOM_TEXT, "no TLE element sets", name="notes.txt"),
    "txt-junk-tle-like": csv_case(JUNK_TLE, "this is not a TLE file", name="junk.txt"),
    "tle-bad-checksum": csv_case(
        TLE_1.replace("9992", "9993"), "line 2", "checksum", name="sats.tle"
    ),
    "tle-truncated-line": csv_case(TLE_1[:-20] + "\n", "line 3", "69 characters", name="sats.tle"),
    "tle-duplicate-object": csv_case(TLE_1 + TLE_1, "again", name="sats.tle"),
    "tle-forced-csv": Case(
        {"sats.tle": TLE_1 + TLE_2},
        ["run", "--catalog", "{in}/sats.tle", "--format", "csv"],
        ["looks like a 'tle' catalog"],
    ),
    "gtoc9-seven-numbers": csv_case(
        "0 1 2 3 4 5 6\n" + GTOC9_ROW,
        "line 1",
        "expected 8 numbers",
        name="debris_data.txt",
        extra={"format": "gtoc9"},
    ),
    "gtoc9-e-negative": csv_case(
        GTOC9_ROW.replace("0.0014872", "-0.3"),
        "column 4",
        "[0, 1)",
        name="debris_data.txt",
        extra={"format": "gtoc9"},
    ),
    "catalog-unknown-format": Case(
        {"debris.csv": GOOD_CSV},
        ["catalog", "{in}/debris.csv", "--format", "xls"],
        ["catalog.format must be one of", "'xls'"],
        names="command line",
    ),
    "catalog-all-above-leo": csv_case(
        f"{HEADER}\n1,42164,0,1,10\n2,26560,0.01,55,20\n", "no candidate left", "above-leo"
    ),
    # ---- scenario files: the file and the dotted key
    "toml-syntax-error": Case(
        {"scenario.toml": "[mission\nn = 5\n"}, ["run", "{in}/scenario.toml"], ["scenario.toml"]
    ),
    "toml-unknown-key": scenario_case("n = 3\nbudget = 5", "mission.budget"),
    "toml-n-1": scenario_case("n = 1", "mission.n must be >= 2"),
    "toml-n-text": scenario_case('n = "five"', "mission.n"),
    "toml-n-exceeds": scenario_case("n = 5", "mission.n = 5 exceeds the 3 candidate debris"),
    "toml-must-include-99": scenario_case(
        'n = 3\nmust_include = ["99"]',
        "mission.must_include names debris not in the catalog",
        "99",
        "debris.csv",
    ),
    "toml-exclude-99": scenario_case('n = 2\nexclude = ["99"]', "mission.exclude", "99"),
    "toml-first-99": scenario_case('n = 2\nfirst = "99"', "mission.first", "'99'"),
    "toml-tmax-1e6": scenario_case(
        "n = 3\ntmax_days = 1e6", "mission.tmax_days must be at most", "3652.5 days (10 years"
    ),
    "toml-tmax-negative": scenario_case("n = 3\ntmax_days = -1", "tmax_days must be > 0"),
    "toml-tmax-nan": scenario_case("n = 3\ntmax_days = nan", "tmax_days"),
    "toml-tmax-inf": scenario_case("n = 3\ntmax_days = inf", "mission.tmax_days must be a finite"),
    "toml-drift-band-100-200": scenario_case(
        "n = 3\ndrift_altitude_km = [100.0, 200.0]", "mission.drift_altitude_km must lie within"
    ),
    "toml-drift-band-to-5000": scenario_case(
        "n = 3\ndrift_altitude_km = [400.0, 5000.0]", "[150, 2000] km"
    ),
    "toml-fallback-unknown": scenario_case(
        "n = 3",
        "solver.fallback must name MILP backends",
        "'NOPE'",
        extra_toml='[solver]\nfallback = ["NOPE"]\n',
    ),
    "cli-fallback-unknown": Case(
        {}, ["run", "--fallback", "FOO"], ["solver.fallback", "'FOO'"], names="command line"
    ),
    "toml-drift-band-reversed": scenario_case(
        "n = 3\ndrift_altitude_km = [1200.0, 400.0]", "drift_altitude_km"
    ),
    # ---- deorbit by the vehicle: a perigee "lowered" upwards would be a negative ΔV
    "toml-deorbit-perigee-5000": scenario_case(
        'n = 2\ndeorbit_by = "vehicle"\ndeorbit_perigee_km = 5000.0',
        "mission.deorbit_perigee_km = 5000 is not below the perigee",
        "3 candidate debris",
    ),
    "toml-deorbit-perigee-above-one": scenario_case(
        'n = 2\ndeorbit_by = "vehicle"\ndeorbit_perigee_km = 650.0',
        "deorbit_perigee_km = 650 is not below",
        "1 candidate debris (1 at 614.9 km)",
    ),
    "toml-injection-below-surface": scenario_case(
        "n = 2\ninjection = [6000.0, 0.0, 98.0, 0.0]", "mission.injection: injection a_km"
    ),
    "toml-injection-perigee-below-surface": scenario_case(
        "n = 2\ninjection = [7000.0, 0.1, 98.0, 0.0]",
        "mission.injection: injection perigee altitude",
        "below the Earth's surface",
    ),
    "toml-injection-raan-1e308": scenario_case(
        "n = 2\ninjection = [7000.0, 0.001, 98.0, 1e308]", "injection raan_deg must be an angle in"
    ),
    "csv-as-a-scenario": Case(
        {"debris.csv": GOOD_CSV},
        ["run", "{in}/debris.csv"],
        ["invalid TOML", "looks like a debris catalog", "--catalog"],
    ),
    "tle-as-a-scenario": Case(
        {"rb.dat": TLE_1 + TLE_2},
        ["run", "{in}/rb.dat"],
        ["invalid TOML", "looks like a debris catalog", "--catalog"],
    ),
    "toml-catalog-missing": Case(
        {"scenario.toml": '[catalog]\npath = "nowhere.csv"\n'},
        ["run", "{in}/scenario.toml"],
        ["catalog.path: file not found", "nowhere.csv"],
    ),
    "toml-backend-not-milp": scenario_case(
        "n = 3",
        "solver.backend must be a MILP backend",
        extra_toml='[solver]\nbackend = "CLARABEL"\n',
    ),
    "toml-mip-gap-negative": scenario_case(
        "n = 3", "solver.mip_gap", extra_toml="[solver]\nmip_gap = -1.0\n"
    ),
    "toml-selection-reversed": scenario_case(
        "n = 3", "selection.altitude_km", extra_toml="[selection]\naltitude_km = [900.0, 600.0]\n"
    ),
    "toml-bad-start": Case(
        {
            "scenario.toml": '[catalog]\npath = "debris.csv"\nstart = "soon"\n',
            "debris.csv": GOOD_CSV,
        },
        ["run", "{in}/scenario.toml"],
        ["catalog.start", "'soon'"],
    ),
    # ---- --out: checked before the solve
    "out-is-a-file": Case(
        {"debris.csv": GOOD_CSV, "taken": ""},
        ["run", "--catalog", "{in}/debris.csv", "--n", "2", "--out", "{in}/taken"],
        ["--out", "is a file"],
        names="taken",
    ),
    "out-inside-a-file": Case(
        {"debris.csv": GOOD_CSV, "taken": ""},
        ["run", "--catalog", "{in}/debris.csv", "--n", "2", "--out", "{in}/taken/run"],
        ["--out", "which is a file"],
        names="taken",
    ),
    "out-not-a-run-folder": Case(
        {"debris.csv": GOOD_CSV, "mine/notes.txt": "keep"},
        ["run", "--catalog", "{in}/debris.csv", "--n", "2", "--out", "{in}/mine"],
        ["not an earlier run folder"],
        names="mine",
    ),
    "out-run-folder-with-a-file-of-the-user": Case(
        {"debris.csv": GOOD_CSV, "run/solution.json": "{}", "run/notes.txt": "keep"},
        ["run", "--catalog", "{in}/debris.csv", "--n", "2", "--out", "{in}/run"],
        ["also holds notes.txt", "did not write"],
        names="run",
    ),
    "out-unwritable": Case(
        {"debris.csv": GOOD_CSV, "locked/.keep": ""},
        ["run", "--catalog", "{in}/debris.csv", "--n", "2", "--out", "{in}/locked/run"],
        ["not writable"],
        names="locked",
        skip="root writes anywhere" if os.geteuid() == 0 else None,
    ),
    "out-current-folder": Case(
        {"debris.csv": GOOD_CSV},
        ["run", "--catalog", "{in}/debris.csv", "--n", "2", "--out", "."],
        ["--out", "is the current folder"],
        names="--out",
    ),
    "out-in-proc": Case(
        {"debris.csv": GOOD_CSV},
        ["run", "--catalog", "{in}/debris.csv", "--n", "2", "--out", "/proc/sdc_cvx_x"],
        ["--out", "/proc/sdc_cvx_x", "/proc"],
        names="/proc/sdc_cvx_x",
    ),
    "out-beside-a-log-of-the-user": Case(
        {"debris.csv": GOOD_CSV, "r.log": "my notes\n"},
        ["run", "--catalog", "{in}/debris.csv", "--n", "2", "--out", "{in}/r"],
        ["is not a log of sdc_cvx", "never overwrites"],
        names="r.log",
    ),
    # ---- command-line values
    "cli-n-1": Case({}, ["run", "--n", "1"], ["mission.n must be >= 2"], names="command line"),
    "cli-tmax-1e6": Case(
        {}, ["run", "--tmax-days", "1e6"], ["at most 3652.5"], names="command line"
    ),
    "cli-start-not-a-date": Case(
        {"debris.csv": GOOD_CSV},
        ["run", "--catalog", "{in}/debris.csv", "--start", "soon"],
        ["catalog.start", "'soon'"],
        names="command line",
    ),
    "edges-departure-nan": Case(
        {},
        ["edges", "--departure-day", "nan"],
        ["--departure-day", "finite"],
        names="--departure-day",
    ),
    "edges-departure-negative": Case(
        {}, ["edges", "--departure-day", "-1"], ["--departure-day", ">= 0"], names="--departure-day"
    ),
    # ---- sweeps: refused before anything is written
    "sweep-workers-0": Case(
        {"study.toml": STUDY},
        ["sweep", "{in}/study.toml", "--workers", "0"],
        ["--workers", "0"],
        names="--workers",
    ),
    "sweep-resume-without-out": Case(
        {"study.toml": STUDY},
        ["sweep", "{in}/study.toml", "--resume"],
        ["--resume needs --out"],
        names="--resume",
    ),
    "sweep-scheduler-without-dask": Case(
        {"study.toml": STUDY},
        ["sweep", "{in}/study.toml", "--scheduler", "tcp://nowhere:8786"],
        ["dask.distributed", "pip install"],
        names="--scheduler",
        skip="dask installed" if importlib.util.find_spec("distributed") else None,
    ),
    "sweep-finished-folder-without-resume": Case(
        {"study.toml": STUDY, "done/results.csv": "key\n"},
        ["sweep", "{in}/study.toml", "--out", "{in}/done"],
        ["already holds results.csv", "--resume"],
        names="done",
    ),
    "sweep-into-a-run-folder": Case(
        {"study.toml": STUDY, "run/solution.json": "{}", "run/legs.csv": "x\n"},
        ["sweep", "{in}/study.toml", "--out", "{in}/run"],
        ["--out", "is not a sweep folder"],
        names="run",
    ),
    "sweep-into-a-folder-of-the-user": Case(
        {"study.toml": STUDY, "mine/notes.txt": "keep"},
        ["sweep", "{in}/study.toml", "--out", "{in}/mine"],
        ["--out", "not empty and is not a sweep folder"],
        names="mine",
    ),
    "sweep-refused-resume-leaves-no-lock": Case(
        {"study.toml": STUDY, "done/results.csv": "key,scenario_sha\nx,abc\n"},
        ["sweep", "{in}/study.toml", "--out", "{in}/done", "--resume"],
        ["is not a sweep results table"],
        names="done",
    ),
    "sweep-bad-study": Case(
        {"study.toml": 'base = "nowhere.toml"\n'}, ["sweep", "{in}/study.toml"], ["nowhere.toml"]
    ),
    # ---- issue 28, 2.3: names the system refuses, input nested past any OMM
    "omm-json-nested-100000-deep": Case(
        {"debris.json": "[" * 100000 + "]" * 100000},
        ["run", "--catalog", "{in}/debris.json"],
        ["nested too deeply"],
    ),
    "out-name-over-255-bytes": Case(
        {"debris.csv": GOOD_CSV},
        ["run", "--catalog", "{in}/debris.csv", "--n", "2", "--out", "{in}/" + "x" * 300],
        ["is 300 bytes long", "at most 255 bytes"],
        names="",
    ),
    "campaign-out-name-over-255-bytes": Case(
        {"c.toml": '[catalog]\npath = "debris.csv"\n[campaign]\nlaunch_days = [0, 365.25]\n'
                   "[mission]\nn = 2\n"},
        ["campaign", "{in}/c.toml", "--out", "{in}/" + "é" * 150],
        ["is 300 bytes long", "at most 255 bytes"],
        names="",
    ),
    "sweep-out-name-over-255-bytes": Case(
        {"study.toml": STUDY},
        ["sweep", "{in}/study.toml", "--out", "{in}/" + "x" * 300],
        ["is 300 bytes long", "at most 255 bytes"],
        names="",
    ),
}


def tree(root: Path) -> dict[str, bytes | None]:
    return {
        str(p.relative_to(root)): (p.read_bytes() if p.is_file() else None)
        for p in sorted(root.rglob("*"))
    }


@pytest.mark.parametrize("name", list(CASES))
def test_bad_input_exits_2_names_the_file_and_writes_nothing(name, tmp_path, monkeypatch):
    case = CASES[name]
    if case.skip:
        pytest.skip(case.skip)
    folder, work = tmp_path / "in", tmp_path / "work"
    folder.mkdir()
    work.mkdir()
    for relative, content in case.files.items():
        path = folder / relative
        path.parent.mkdir(parents=True, exist_ok=True)
        (path.write_bytes if isinstance(content, bytes) else path.write_text)(content)
    base = '[catalog]\npath = "debris.csv"\n'  # a sweep's base scenario
    (folder / "base.toml").write_text(base)
    (folder / "debris.csv").exists() or (folder / "debris.csv").write_text(GOOD_CSV)
    if name == "out-unwritable":
        (folder / "locked").chmod(0o555)
    args = [arg.replace("{in}", str(folder)) for arg in case.args]
    if "format" in case.extra:
        args += ["--format", case.extra["format"]]
    before = tree(tmp_path)
    monkeypatch.chdir(work)
    result = CliRunner().invoke(main, args)
    assert result.exit_code == 2, (result.output, result.exception)
    assert isinstance(result.exception, SystemExit), result.exception
    assert "Traceback" not in result.output
    for part in case.expect:
        assert part in result.stderr, (part, result.stderr)
    named = case.names if case.names is not None else next(iter(case.files), None)
    if named:
        assert named.split("/")[0] in result.stderr, (named, result.stderr)
    assert tree(tmp_path) == before, "a file was written"


def test_the_corpus_is_large_enough():
    assert len(CASES) >= 40


def test_an_unknown_catalog_column_warns_and_names_the_epoch_column(tmp_path):
    path = tmp_path / "debris.csv"
    path.write_text(
        f"{HEADER},epoch_utc\n"
        + "".join(f"{row},2020-01-01T00:00:00Z\n" for row in ROWS.splitlines())
    )
    result = CliRunner().invoke(main, ["catalog", str(path)])
    assert result.exit_code == 0
    assert f"warning: {path}, header: unknown column 'epoch_utc' is not used" in result.stderr
    assert "the epoch column is named 'epoch'" in result.stderr


def test_a_gtoc9_file_is_read_whatever_its_extension(tmp_path):
    for name in ("debris.txt", "debris.csv", "debris"):
        path = tmp_path / name
        path.write_text(GTOC9_ROW + GTOC9_ROW.replace("0 21947", "1 21947"))
        result = CliRunner().invoke(main, ["catalog", str(path)])
        assert result.exit_code == 0, result.output
        assert "2 debris from" in result.stderr


@pytest.mark.requires_shared_data("gtoc9/debris_data.txt")
def test_the_gtoc9_file_of_the_readme_reads_without_format():
    from tests.conftest import SHARED_DATA

    result = CliRunner().invoke(main, ["catalog", str(SHARED_DATA / "gtoc9/debris_data.txt")])
    assert result.exit_code == 0 and "123 debris from" in result.stderr
