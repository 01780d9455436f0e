"""The Python API as a notebook user calls it (issue 48, items 13-16): a wrong argument is
one of the package's errors (:mod:`sdc_cvx.errors`), in one line naming the argument,
never a raw ``TypeError``, ``ValueError`` or numpy error."""

import pytest

from sdc_cvx import Campaign, Catalog, Mission, SolverOptions
from sdc_cvx.errors import CatalogError, MissionError
from sdc_cvx.milp.types import MILP_BACKENDS


def assert_one_line(err: pytest.ExceptionInfo, *words: str) -> None:
    text = str(err.value)
    assert "\n" not in text, text
    for word in words:
        assert word in text, text


# --------------------------------------------------------------- item 16: solver options
@pytest.mark.parametrize(("options", "named"), [
    (dict(gap=2), "gap must be a number in [0, 1)"),
    (dict(gap="0.1"), "gap must be"),
    (dict(method="fast"), "method must be one of certified, paper"),
    (dict(backend="NOPE"), "backend must be one of HIGHS, SCIP"),
    (dict(backend=5), "backend must be the name of a MILP backend"),
    (dict(fallback=[5]), "fallback must name MILP backends"),
    (dict(fallback=3), "fallback must be a backend name"),
    (dict(time_limit_s=float("nan")), "time_limit_s must be > 0"),
    (dict(time_limit_s="60"), "time_limit_s must be"),
    (dict(mip_gap=1.5), "mip_gap must be in [0, 1)"),
    (dict(threads=0), "threads must be a positive integer"),
    (dict(seed=1.5), "seed must be an integer"),
    (dict(verbose="yes"), "verbose must be True or False"),
])  # fmt: skip
def test_solver_options_raise_the_package_error_of_option_rules(options, named):
    """``SolverOptions(gap=2)`` is refused as ``solve_campaign(gap=2)`` is: a MissionError
    (it was a ValueError), and an unknown backend when the options are made, not when a
    MILP runs (or never: a certified search that needs no MILP ran with ``NOPE``)."""
    with pytest.raises(MissionError) as err:
        SolverOptions(**options)
    assert_one_line(err, named)


def test_a_known_backend_is_accepted_installed_or_not_an_unknown_one_never():
    """A known backend not installed here is accepted when the options are made (and
    refused when a MILP runs: ``SolverFailure``, 'is not installed'); a name no backend
    has is refused at once, in the fallback chain too."""
    for name in MILP_BACKENDS:
        assert SolverOptions(backend=name.lower(), fallback=name).backend == name
    with pytest.raises(MissionError, match="fallback must name MILP backends.*got HIGS"):
        SolverOptions(fallback=("SCIP", "HiGS"))


# ------------------------------------------------------------------ item 13: the catalog
@pytest.mark.parametrize("days", [float("nan"), float("inf"), "10", None, True, 1e12])
def test_advanced_refuses_what_is_not_a_number_of_days(days):
    """``advanced(nan)`` gave NaN RAANs (then a raw ValueError in ``solve``),
    ``advanced("10")`` a numpy UFuncTypeError."""
    with pytest.raises(CatalogError) as err:
        Catalog.paper_case().advanced(days)
    assert_one_line(err, "Catalog.advanced(days)", "days must be a number", repr(days))


def test_advanced_refuses_a_j2_that_is_not_a_positive_number():
    with pytest.raises(CatalogError, match=r"j2 must be a number > 0, got 'x'"):
        Catalog.paper_case().advanced(10.0, j2="x")


def test_subset_takes_one_int_id_as_a_one_element_selection():
    catalog = Catalog.paper_case()
    assert catalog.subset(3).ids == ("3",) == catalog.subset("3").ids
    assert catalog.subset([3, "5"]).ids == ("3", "5")


@pytest.mark.parametrize(("ids", "shown"), [(3.0, "3.0"), ([["3"]], "['3']"), ([None], "None")])
def test_subset_refuses_what_is_not_an_id(ids, shown):
    with pytest.raises(CatalogError) as err:
        Catalog.paper_case().subset(ids)
    assert_one_line(err, "Catalog.subset(ids)", "strings or integers", shown)


# --------------------------------------------------------------- item 14: the mission
@pytest.mark.parametrize(("fields", "words"), [
    (dict(drift_altitude_km=400), ["drift_altitude_km must be (low, high)",
                                   "got 400 (not a pair)"]),
    (dict(drift_altitude_km="400-1200"), ["drift_altitude_km", "got '400-1200' (a string)"]),
    (dict(injection="orbit"), ["injection must be (a_km, e, inc_deg, raan_deg)",
                               "got 'orbit' (a string)"]),
    (dict(injection=7000.0), ["injection must be", "got 7000.0"]),
    (dict(first=["5", "6"]), ["first must be one debris id", "['5', '6']",
                              "must_include takes several"]),
    (dict(first=5.0), ["first must be one debris id (a string or an integer), got 5.0"]),
    (dict(must_include=[5.0, "6"]), ["must_include must be debris ids", "got 5.0"]),
    (dict(exclude=[["1"]]), ["exclude must be debris ids", "got ['1']"]),
    (dict(must_include=None), ["must_include must be debris ids", "got None"]),
])  # fmt: skip
def test_a_mission_refuses_what_is_not_of_its_fields_kind(fields, words):
    """A scalar where a (low, high) pair is expected was a TypeError, a string was split
    into its characters in the message, a list as ``first`` (or a float id, which no
    catalog id matches) was taken as one id and failed only in ``solve``."""
    with pytest.raises(MissionError) as err:
        Mission(**fields)
    assert_one_line(err, *words)
    assert "'4', '0', '0'" not in str(err.value) and "'o', 'r'" not in str(err.value)


@pytest.mark.parametrize(("options", "said"), [
    (dict(n="3"), "n must be a number or a sequence of numbers, got '3' (a string)"),
    (dict(tmax_days="100"), "tmax_days must be a number or a sequence of numbers, got '100'"),
    (dict(n=["3", "4"]), "n must be an integer, got '3'"),
])  # fmt: skip
def test_a_campaign_says_a_string_as_given(options, said):
    """``Campaign.of([0, 100], n="3")`` said "n ranges must be [n_min, n_max] pairs, got
    ['3']": the string split into characters, each taken for a range."""
    with pytest.raises(MissionError) as err:
        Campaign.of([0.0, 100.0], **options)
    assert_one_line(err, said)


def test_a_campaign_says_a_string_of_launch_days_as_given():
    with pytest.raises(MissionError, match=r"launch_days must be .*got '01' \(a string\)"):
        Campaign.of("01")
    with pytest.raises(MissionError, match=r"launch_days must be numbers .*got '01' \(a string"):
        Campaign(launch_days="01", missions=(Mission(), Mission()))


# ------------------------------------------------- item 20: "missing", "not finite"
@pytest.mark.parametrize(("fields", "said"), [
    (dict(tmax_days=None), "tmax_days is missing (None)"),
    (dict(tmax_days=float("inf")), "tmax_days is not finite (inf)"),
    (dict(preopt_days=float("inf")), "preopt_days is not finite (inf)"),  # was accepted
    (dict(operations_dv_mps=float("inf")), "operations_dv_mps is not finite (inf)"),
    (dict(j2=float("nan")), "j2 is not finite (nan)"),
    (dict(deorbit_perigee_km=None), "deorbit_perigee_km is missing (None)"),
])  # fmt: skip
def test_a_mission_says_a_value_missing_or_not_finite(fields, said):
    """"got None" said nothing of a value left out, "got inf" of one not finite (and
    ``preopt_days = inf`` or ``operations_dv_mps = inf`` were taken)."""
    with pytest.raises(MissionError) as err:
        Mission(**fields)
    assert_one_line(err, said)


@pytest.mark.parametrize(("must_remove", "shown"), [([["1"]], "got ['1']"),
                                                   (["2", 5.0], "got 5.0"), (None, "got None")])
def test_a_campaign_refuses_must_remove_ids_that_are_not_ids(must_remove, shown):
    """``must_remove=[["1"]]`` was taken as the id "['1']" (no catalog has it)."""
    with pytest.raises(MissionError) as err:
        Campaign.of([0.0], must_remove=must_remove)
    assert_one_line(err, "must_remove must be debris ids (strings or integers)", shown)
