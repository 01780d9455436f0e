"""The whole public catalogue (issue 20): the filters act first, invalid element sets are
reported only when the selection keeps them, selection by name and type, the clusters.

Most tests read a cut of ``../shared/data/catalog_2020/all_2020.tle`` (the SL-16 rocket
bodies, the ISS and the element sets of the file that are not orbits of this model),
written by hand from the file's text, so that they stay fast; the slow ones read the
whole file.  Expected values (line numbers, catalogue numbers, counts, names) come from
the text, never from the code under test.
"""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np
import pandas as pd
import pytest
from click.testing import CliRunner

from sdc_cvx.cli import main
from sdc_cvx.inputs.catalog import Catalog, CatalogError
from sdc_cvx.inputs.clusters import find_clusters, raan_spread_deg
from sdc_cvx.inputs.formats import read_catalog, read_tle
from sdc_cvx.inputs.selection import object_type, select
from tests.conftest import computed_once, shared_file

WHOLE = "catalog_2020/all_2020.tle"
ISS = "25544"
# not orbits of this model (the data README): perigee below 150 km (45596, 45601), a above
# 100,000 km (1458), a mean motion of 30 rev/day (82778: a below the Earth's radius)
DECAYED = ("45596", "45601")
BEYOND = "1458"
TOO_FAST = "82778"


def element_sets(path: Path) -> dict[str, tuple[str, str, str]]:
    """``{catalogue number: (name line, line 1, line 2)}`` of a 3-line TLE file, by hand."""
    lines = [line.rstrip("\n") for line in path.read_text().splitlines() if line.strip()]
    sets = {}
    for k in range(0, len(lines), 3):
        title, one, two = lines[k : k + 3]
        sets[str(int(one[2:7]))] = (title, one, two)
    return sets


@pytest.fixture(scope="module")
@computed_once
def whole_sets() -> dict[str, tuple[str, str, str]]:
    return element_sets(shared_file(WHOLE))


@pytest.fixture(scope="module")
@computed_once
def sl16_ids(whole_sets) -> list[str]:
    """The SL-16 rocket bodies at 71 deg, by hand: name, inclination, mean motion."""
    return [
        number
        for number, (title, _, two) in whole_sets.items()
        if title[2:].strip() == "SL-16 R/B" and 70.5 <= float(two[8:16]) <= 71.5
        and 13.5 <= float(two[52:63]) <= 14.5  # about 800-880 km
    ]  # fmt: skip


def write_cut(folder: Path, whole_sets, numbers: list[str], name="cut.tle") -> tuple[Path, dict]:
    """A TLE file of the given element sets; ``{number: line of its line 1}``."""
    text, line_of = [], {}
    for number in numbers:
        title, one, two = whole_sets[number]
        line_of[number] = len(text) + 2
        text += [title, one, two]
    path = folder / name
    path.write_text("\n".join(text) + "\n")
    return path, line_of


@pytest.fixture
def cut(tmp_path, whole_sets, sl16_ids):
    numbers = [ISS, *sl16_ids, *DECAYED, BEYOND, TOO_FAST]
    return write_cut(tmp_path, whole_sets, numbers)


# ---------------------------------------------------------------------- reading
def test_the_cut_reads_and_has_the_18_sl16_rocket_bodies(sl16_ids):
    assert len(sl16_ids) == 18  # the data README's count


def test_invalid_element_sets_are_one_error_naming_line_and_number(cut):
    """By default every element set that is not an orbit is a problem, each named by the
    line of its line 1 and its catalogue number (not "row 1, field a_km", issue 20)."""
    path, line_of = cut
    with pytest.raises(CatalogError) as caught:
        read_tle(path)
    problems = caught.value.problems
    expected = [f"{path}, line {line_of[n]} (catalog number {n})" for n in
                sorted([*DECAYED, BEYOND, TOO_FAST], key=line_of.get)]  # fmt: skip
    assert [p.split(":")[0].split(", field")[0] for p in problems] == expected
    assert all("perigee" in p for p in problems[:2])
    assert "semi-major axis of at most 100,000 km" in problems[2]
    assert "mean motion 30.2262 rev/day" in problems[3]


def test_format_and_orbit_problems_come_in_one_error(cut, tmp_path):
    """A bad checksum and the orbits beyond the model: one error with all five, by line (not
    "4 problems" then, once fixed, "6 problems")."""
    path, line_of = cut
    lines = path.read_text().splitlines()
    index = line_of[ISS] - 1  # line 1 of the ISS, 0-based
    digit = lines[index][68]
    lines[index] = lines[index][:68] + str((int(digit) + 1) % 10)
    bad = tmp_path / "bad.tle"
    bad.write_text("\n".join(lines) + "\n")
    with pytest.raises(CatalogError) as caught:
        read_tle(bad)
    problems = caught.value.problems
    assert len(problems) == 5
    assert problems[0].startswith(f"{bad}, line {line_of[ISS]}, column 69 (checksum)")
    assert str(caught.value).startswith(f"5 problems in {bad}:")


def test_set_aside_keeps_them_out_of_the_catalog(cut, whole_sets):
    path, line_of = cut
    catalog = read_catalog(path, on_invalid="set aside")
    invalid = catalog.invalid
    assert sorted(invalid["id"]) == sorted([*DECAYED, BEYOND, TOO_FAST])
    assert not set(invalid["id"]) & set(catalog.ids)
    assert len(catalog) == 1 + 18
    row = invalid.set_index("id").loc[TOO_FAST]
    assert row["problem"].startswith(f"{path}, line {line_of[TOO_FAST]} (catalog number 82778)")
    # its size for the filters: Kepler on the mean motion (sgp4's un-Kozai step moves it by
    # about 0.03 %), a below the Earth's radius
    n = float(whole_sets[TOO_FAST][2][52:63]) * 2 * math.pi / 86400  # from the text
    assert row["a_km"] == pytest.approx((3.986e14 / n**2) ** (1 / 3) / 1e3, rel=1e-3)


def test_epoch_decades_from_the_start_is_not_an_orbit_of_this_model(cut, tmp_path, whole_sets):
    """An element set dated 1960 among 2020 ones (a 2-digit year read in the other century):
    its RAAN would be moved with J2 for 60 years."""
    title, one, two = whole_sets[ISS]
    old = one[:18] + "60" + one[20:68]
    old += str((sum(int(c) for c in old if c.isdigit()) + old.count("-")) % 10)
    path, _ = write_cut(tmp_path, {**whole_sets, ISS: (title, old, two)}, [ISS, "22220"],
                        "old.tle")  # fmt: skip
    with pytest.raises(CatalogError) as caught:
        read_tle(path)
    (problem,) = caught.value.problems
    where = f"{path}, line 2 (catalog number 25544), field 'epoch'"
    assert problem.startswith(f"{where}: expected an epoch within 3652.5 days (10 years) of the "
                              "mission start")  # fmt: skip

    def epoch(line1: str, century: int) -> pd.Timestamp:  # by hand, from the text
        year = century + int(line1[18:20])
        return pd.Timestamp(f"{year}-01-01", tz="UTC") + pd.Timedelta(days=float(line1[20:32]) - 1)

    years = (epoch(whole_sets["22220"][1], 2000) - epoch(old, 1900)).days / 365.25
    assert f"({years:.1f} years away" in problem
    catalog = read_tle(path, on_invalid="set aside")
    assert catalog.ids == ("22220",) and list(catalog.invalid["id"]) == [ISS]


# ---------------------------------------------------------------------- selection
def test_filters_act_first_and_never_report_what_they_drop(cut, sl16_ids):
    catalog = read_catalog(cut[0], on_invalid="set aside")
    kept, report = select(catalog, names="SL-16 R/B*", altitude_km=(800, 880),
                          inclination_deg=(70.5, 71.5), strict=True)  # fmt: skip
    assert sorted(kept.ids) == sorted(sl16_ids)
    assert "invalid" not in ",".join(report["checks"])
    assert len(kept) + len(report) == 1 + 18 + 4  # every element set of the file counted


def test_the_default_filters_drop_the_far_orbit_before_its_validation(cut):
    """1458 (a = 118,000 km, e = 0.5) is dropped by the eccentricity and LEO filters, which
    act first: it is not reported as an invalid orbit."""
    catalog = read_catalog(cut[0], on_invalid="set aside")
    kept, report = select(catalog, ids=[BEYOND, ISS], strict=True)
    assert kept.ids == (ISS,)
    row = report.set_index("id").loc[BEYOND]
    assert row["checks"] == "eccentricity,above-leo"


def test_invalid_orbit_inside_the_selection_is_dropped_or_refused(cut):
    path, line_of = cut
    catalog = read_catalog(path, on_invalid="set aside")
    kept, report = select(catalog, ids=[DECAYED[0], ISS])
    assert kept.ids == (ISS,)
    row = report.set_index("id").loc[DECAYED[0]]
    assert row["checks"] == "invalid"
    assert row["reason"].startswith(f"{path}, line {line_of[DECAYED[0]]} (catalog number 45596)")
    assert "perigee" in row["reason"]
    with pytest.raises(CatalogError) as caught:
        select(catalog, ids=[DECAYED[0], ISS], strict=True)
    assert caught.value.problems[0] == row["reason"]
    assert "1 element set(s) in the selection are not orbits" in caught.value.problems[-1]


@pytest.mark.parametrize(
    ("name", "kind"),
    [
        ("SL-8 R/B", "rocket-body"),
        ("SL-12 R/B(AUX MOTOR)", "rocket-body"),
        ("THOR AGENA D R/B", "rocket-body"),
        ("COSMOS 2251 DEB", "debris"),
        ("ARIANE 5 DEB (SYLDA)", "debris"),
        ("fengyun 1c deb", "debris"),
        ("ISS (ZARYA)", "payload"),
        ("DEBUT (ORIZURU)", "payload"),  # DEB only as a word
        ("TBA - TO BE ASSIGNED", "payload"),
    ],
)
def test_object_type_from_the_name(name, kind):
    assert object_type(name) == kind


def test_type_filter(cut, sl16_ids):
    catalog = read_catalog(cut[0], on_invalid="set aside")
    kept, report = select(catalog, types=["rocket-body"])
    assert sorted(kept.ids) == sorted(sl16_ids)  # the ISS is a payload; 45601 (CZ-5B R/B)
    assert report.set_index("id").loc[ISS, "checks"] == "type"  # is invalid, 45596 (SL-4
    with pytest.raises(ValueError, match="unknown type"):  # R/B) too: warned, dropped
        select(catalog, types=["rocket"])


# ---------------------------------------------------------------------- command line
def test_cli_warns_once_per_invalid_orbit_in_the_selection_and_counts(cut):
    path, line_of = cut
    args = ["catalog", str(path), "--ids", DECAYED[0], "--ids", DECAYED[1], "--ids", ISS]
    result = CliRunner().invoke(main, args)
    assert result.exit_code == 0, result.output
    warnings = [line for line in result.stderr.splitlines() if line.startswith("warning:")]
    assert len(warnings) == 3
    for number, warning in zip(DECAYED, warnings, strict=False):
        assert f"{path}, line {line_of[number]} (catalog number {number})" in warning
    assert "2 element set(s) in the selection dropped" in warnings[2]
    assert result.stdout.splitlines()[1].split()[0] == ISS
    strict = CliRunner().invoke(main, [*args, "--strict"])
    assert strict.exit_code == 2
    assert "Traceback" not in strict.output
    assert f"line {line_of[DECAYED[0]]} (catalog number 45596)" in strict.stderr


def test_cli_names_and_type_select_the_cluster_without_a_warning(cut, sl16_ids):
    args = ["catalog", str(cut[0]), "--names", "sl-16 r/b*", "--type", "rocket-body"]
    result = CliRunner().invoke(main, args)
    assert result.exit_code == 0, result.output
    assert "warning" not in result.stderr
    ids = [line.split()[0] for line in result.stdout.splitlines()[1:]]
    assert sorted(ids) == sorted(sl16_ids)
    bad = CliRunner().invoke(main, ["catalog", str(cut[0]), "--type", "rocket"])
    assert bad.exit_code == 2 and "Traceback" not in bad.output


def test_cli_clusters_table_and_figure(cut, tmp_path):
    figure = tmp_path / "clusters.png"
    args = ["catalog", str(cut[0]), "--clusters", "--min-objects", "5", "--figure", str(figure)]
    result = CliRunner().invoke(main, args)
    assert result.exit_code == 0, result.output
    rows = result.stdout.splitlines()
    assert len(rows) == 2  # header and the SL-16 group (the ISS is alone)
    assert "SL-16 R/B (18)" in rows[1] and rows[1].split()[1] == "18"
    assert figure.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
    no_clusters = CliRunner().invoke(main, ["catalog", str(cut[0]), "--figure", str(figure)])
    assert no_clusters.exit_code == 2 and "--figure needs --clusters" in no_clusters.stderr


# ---------------------------------------------------------------------- clusters
@pytest.mark.parametrize(
    ("angles", "spread"),
    [([0.0], 0.0), ([350.0, 10.0, 0.0], 20.0), ([0.0, 90.0, 180.0, 270.0], 270.0),
     ([100.0, 130.0, 115.0], 30.0), ([359.5, 0.5], 1.0)],
)  # fmt: skip
def test_raan_spread_is_the_smallest_arc(angles, spread):
    assert raan_spread_deg(np.array(angles)) == pytest.approx(spread)


def test_find_clusters_finds_the_dense_groups():
    rng = np.random.default_rng(7)
    rows = []
    for k in range(12):  # 12 objects at 71 deg, 830-845 km
        rows.append((f"A{k}", 6378.137 + 830 + 15 * rng.random(), 70.9 + 0.1 * rng.random()))
    for k in range(15):  # 15 at 83 deg, 955-990 km
        rows.append((f"B{k}", 6378.137 + 955 + 35 * rng.random(), 82.6 + 0.3 * rng.random()))
    for k, (alt, inc) in enumerate([(500, 20), (700, 45), (1200, 60), (600, 140), (900, 30)]):
        rows.append((f"C{k}", 6378.137 + alt, inc))  # scattered
    frame = pd.DataFrame(rows, columns=["id", "a_km", "inc_deg"])
    frame["e"], frame["raan_deg"] = 0.001, rng.uniform(0, 360, len(frame))
    catalog = Catalog.from_frame(frame)
    found = find_clusters(catalog, min_objects=5)
    assert list(found.table["objects"]) == [15, 12]
    assert [i for i, label in zip(catalog.ids, found.labels, strict=True) if label == 1] == [
        f"B{k}" for k in range(15)
    ]
    assert all(label == 0 for i, label in zip(catalog.ids, found.labels, strict=True)
               if i.startswith("C"))  # fmt: skip
    first = found.table.iloc[0]
    rates = catalog.frame["raan_rate_deg_per_day"][catalog.frame["id"].str.startswith("B")]
    assert first["rate_spread_deg_per_day"] == pytest.approx(rates.max() - rates.min())
    assert first["select"].startswith("--altitude-km 955 ")


# ---------------------------------------------------------------------- the whole file
@pytest.mark.slow
def test_the_whole_catalogue_and_its_example_clusters():
    """The whole file reads (about 20 element sets set aside), and the example scenarios
    select the README's clusters; the SSO one is exactly the 81 of sso_rb.tle."""
    from sdc_cvx.study.scenario import Scenario
    from tests.conftest import EXAMPLES

    whole = shared_file(WHOLE)
    sets = element_sets(whole)
    catalog = read_catalog(whole, on_invalid="set aside")
    assert len(catalog) + len(catalog.invalid) == len(sets) == 19084
    assert {*DECAYED, BEYOND, TOO_FAST} <= set(catalog.invalid["id"])
    assert 15 <= len(catalog.invalid) <= 30
    counts = {}
    for name in ("sl16_71deg", "sl8_83deg", "sl8_74deg", "sso_rocket_bodies"):
        kept, report = Scenario.load(EXAMPLES / f"cluster_{name}.toml").select_candidates()
        assert "invalid" not in ",".join(report["checks"])
        counts[name] = kept
    assert len(counts["sl16_71deg"]) == 18
    assert len(counts["sl8_83deg"]) == 142  # 143 in the README: one has e > 0.05
    _, report = Scenario.load(EXAMPLES / "cluster_sl8_83deg.toml").select_candidates()
    named = report[report["name"] == "SL-8 R/B"]
    assert list(named["checks"]).count("eccentricity") == 1
    assert len(counts["sl8_74deg"]) == 50
    sso = read_tle(shared_file("sso_rocket_bodies_2020/sso_rb.tle"))
    assert sorted(counts["sso_rocket_bodies"].ids) == sorted(sso.ids)


@pytest.mark.slow
def test_the_sl16_example_runs_certified_end_to_end(tmp_path):
    """``run examples/cluster_sl16_71deg.toml``: the whole file read, the 18 SL-16 rocket
    bodies selected, five of them certified optimal (about 20 s)."""
    from tests.conftest import EXAMPLES

    shared_file(WHOLE)
    out = tmp_path / "run"
    args = ["run", str(EXAMPLES / "cluster_sl16_71deg.toml"), "--out", str(out), "--quiet"]
    result = CliRunner().invoke(main, args)
    assert result.exit_code == 0, result.output
    assert "Traceback" not in result.output and "warning" not in result.stderr
    assert "total dV" in result.stdout and "optimal (gap" in result.stdout
    assert (out / "solution.json").is_file() and (out / "orbits.png").is_file()


def test_sweeps_select_by_name_and_type_and_honour_strict(cut, tmp_path):
    """A sweep's scenarios take ``selection.names`` / ``selection.types`` and
    ``catalog.strict`` as ``run`` does (its worker selects through the same call)."""
    from sdc_cvx.study.study import Study
    from sdc_cvx.study.worker import solve_scenario

    path, line_of = cut
    base = (f'[catalog]\npath = "{path}"\n[mission]\nn = 2\ntmax_days = 60.0\n'
            '[selection]\ntypes = ["rocket-body"]\n')  # fmt: skip
    (tmp_path / "base.toml").write_text(base)
    study = Study.from_dict({"base": str(tmp_path / "base.toml"),
                             "grid": {"selection.names": [["SL-16 R/B*"], ["*R/B*"]],
                                      "catalog.strict": [False, True]}})  # fmt: skip
    rows = {(item.scenario.selection.names, item.scenario.catalog_strict): solve_scenario(
        item.scenario.to_toml()) for item in study.scenarios}  # fmt: skip
    for names in (("SL-16 R/B*",), ("*R/B*",)):
        assert rows[names, False]["status"] == "optimal", rows[names, False]["error"]
    # SL-4 R/B 45596 and CZ-5B R/B 45601 (perigee below 150 km) are rocket bodies: the
    # second selection keeps them, which strict refuses; the first never looks at them
    assert rows[("SL-16 R/B*",), True]["status"] == "optimal"
    refused = rows[("*R/B*",), True]
    assert refused["status"] == "error"
    assert f"line {line_of['45596']} (catalog number 45596)" in refused["error"]
