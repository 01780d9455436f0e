"""Campaign figures people can read (issue 28, 3.2)."""

from __future__ import annotations

import warnings

import numpy as np
import pytest

from sdc_cvx import Campaign, Mission, solve_campaign
from sdc_cvx.inputs.synthetic import sso_catalog
from sdc_cvx.report import atomic
from sdc_cvx.report.campaign_plots import _label_levels, plot_raan, plot_timeline


@pytest.fixture(scope="module")
def answer():
    catalog = sso_catalog(9, seed=7, inclination_spread_deg=0.8)
    return solve_campaign(catalog, Campaign.of([0.0, 365.25], Mission(n=3)), workers=1)


def test_labels_of_debris_met_days_apart_do_not_share_a_place():
    """GTOC9's "73" and "11", met 36 days apart on a 1,800-day axis, printed as "7311"."""
    row = [("111", 733.0), ("10", 758.0), ("73", 1033.0), ("85", 1033.5), ("11", 1069.0)]
    placed = {}
    for (name, day), level in zip(row, _label_levels(row, span=1800.0), strict=True):
        for other_day, other_name in placed.get(level, []):
            assert abs(day - other_day) > 0.012 * 1800 * (len(name) + 1), (name, other_name)
        placed.setdefault(level, []).append((day, name))


def test_the_raan_figure_draws_no_line_across_the_seam_and_names_the_debris(answer):
    fig = plot_raan(answer)
    ax = fig.axes[0]
    for line in ax.get_lines():
        if line.get_linestyle() == "None":  # markers only: nothing drawn between them
            continue
        y = np.asarray(line.get_ydata(), dtype=float)
        steps = np.abs(np.diff(y))
        assert np.all(steps[np.isfinite(steps)] < 180.0)  # no line across +/-180 deg
        assert np.nanmax(np.abs(y)) <= 180.0
    names = {text.get_text() for text in ax.texts}
    assert {d for m in answer.missions for d in m.path} <= names


def test_a_missing_glyph_is_said_once_not_once_per_glyph_and_figure(answer, tmp_path,
                                                                    monkeypatch):  # fmt: skip
    monkeypatch.setattr(atomic, "_GLYPHS_SAID", [])
    fig = plot_timeline(answer)
    fig.axes[0].set_title("碎片 一 二 三")  # glyphs the default font lacks
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        atomic.write_figure(fig, tmp_path / "a.png", "png", 50)
        atomic.write_figure(fig, tmp_path / "b.png", "png", 50)
    said = [w for w in caught if "font" in str(w.message)]
    assert len(said) == 1 and "show as boxes" in str(said[0].message)


def test_the_bound_figure_keeps_greedy_and_the_plan_in_its_frame(answer):
    """A plan with no bound yet and greedy far above it: the plan's marker sat half cut on
    the frame and greedy's line on the other (the span came from plan and bound alone)."""
    import dataclasses

    from sdc_cvx.report.campaign_plots import plot_bound

    history = ({**answer.history[0], "lower_mps": None, "upper_mps": 821.4},)
    greedy = dataclasses.replace(answer.greedy, dv_mps=1200.0)
    fig = plot_bound(dataclasses.replace(answer, history=history, greedy=greedy))
    low, high = fig.axes[0].get_ylim()
    assert low < 821.4 - 10.0 and high > 1200.0 + 10.0


@pytest.fixture(scope="module")
def most_value():
    """Two launches of at most 3 debris each within 400 and 300 m/s: every debris worth
    1, so each mission's value is its number of debris."""
    catalog = sso_catalog(9, seed=7, inclination_spread_deg=0.8)
    campaign = Campaign.of([0.0, 365.25], Mission(n=3), n=[[2, 3], [2, 3]],
                           objective="max-value", dv_budget_mps=[400.0, 300.0])  # fmt: skip
    return solve_campaign(catalog, campaign, workers=1)


def test_a_max_value_dv_figure_shows_each_missions_value_and_budget_over_its_bar(most_value):
    """Issue 48, item 19: the figure of a max-value campaign said neither the value removed
    nor the budgets (its objective), and its bars sat half a bar left of their ticks (the
    place kept for greedy's, which max-value has not)."""
    from sdc_cvx.report.campaign_plots import plot_dv

    ax = plot_dv(most_value).axes[0]
    removed = [len(m.path) for m in most_value.missions]
    assert f"value {sum(removed)} removed" in ax.get_title()
    ticks = ax.get_xticks()
    labels = [label.get_text() for label in ax.get_xticklabels()]
    assert [f"value {n}" in text for n, text in zip(removed, labels, strict=True)] == [True] * 2
    bars = [patch for patch in ax.patches if patch.get_height() > 0]
    centres = sorted(bar.get_x() + bar.get_width() / 2 for bar in bars)
    np.testing.assert_allclose(centres, ticks, atol=1e-9)
    (budget,) = [c for c in ax.collections if c.get_label() == "ΔV budget"]
    segments = budget.get_segments()
    np.testing.assert_allclose([s[0][1] for s in segments], [400.0, 300.0])
    np.testing.assert_allclose([s[:, 0].mean() for s in segments], ticks, atol=1e-9)
    assert ax.get_ylim()[1] > 400.0


def test_a_max_value_timeline_shows_the_value_and_each_missions_budget(most_value):
    ax = plot_timeline(most_value).axes[0]
    removed = [len(m.path) for m in most_value.missions]
    assert f"value {sum(removed)} removed" in ax.get_title()
    texts = [text.get_text() for text in ax.texts]
    for n, (dv, budget) in zip(removed, [(m.total_dv_mps, b) for m, b in
                                         zip(most_value.missions, (400, 300), strict=True)],
                               strict=True):  # fmt: skip
        assert f"{dv:.0f} of {budget} m/s, value {n}" in texts
