"""Figures of the paper case (Fig. 17, 18, 19, Table 7): valid files, labels, and what is drawn."""

import dataclasses
import io
import math
import xml.etree.ElementTree as ET

import numpy as np
import pytest
from matplotlib.figure import Figure
from matplotlib.image import imread

from sdc_cvx import Catalog, solve
from sdc_cvx.physics.plan import evaluate_plan
from sdc_cvx.physics.transfer import NodeOrbits
from sdc_cvx.report.plots import (
    FIGURE_NAMES,
    plot_cost,
    plot_iterations,
    plot_orbits,
    plot_raan,
    save_figures,
)
from sdc_cvx.solution import Leg

PNG_SIGNATURE = b"\x89PNG\r\n\x1a\n"
MU = 3.986e14
R_EQ = 6378137.0


@pytest.fixture(scope="module")
def figures(solution, catalog):
    return {
        "orbits": plot_orbits(solution, catalog),
        "raan": plot_raan(solution, catalog),
        "cost": plot_cost(solution),
        "iterations": plot_iterations(solution),
    }


def _check_png(data: bytes) -> None:
    assert data[:8] == PNG_SIGNATURE
    pixels = imread(io.BytesIO(data), format="png")
    assert pixels.ndim == 3 and pixels.shape[:2] == (450, 800)  # 8 x 4.5 in at 100 dpi
    assert pixels[..., :3].std() > 0.05  # not a blank canvas
    colours = np.unique(np.round(pixels[..., :3].reshape(-1, 3) * 255).astype(int), axis=0)
    assert len(colours) > 20


def _check_svg(data: bytes) -> None:
    root = ET.fromstring(data)
    assert root.tag.endswith("svg")


@pytest.mark.slow
@pytest.mark.parametrize("name", FIGURE_NAMES)
def test_each_figure_renders_to_valid_png_and_svg(figures, name):
    fig = figures[name]
    assert isinstance(fig, Figure)
    png, svg = io.BytesIO(), io.BytesIO()
    fig.savefig(png, format="png", dpi=100)
    fig.savefig(svg, format="svg")
    _check_png(png.getvalue())
    _check_svg(svg.getvalue())


def test_axis_labels_titles_and_sizes(figures):
    expected = {
        "orbits": ("mission time [days]", "altitude [km]"),
        "raan": ("mission time [days]", "[deg]"),
        "cost": ("leg", "\u0394V [m/s]"),
        "iterations": ("iteration", "\u0394V [m/s]"),
    }
    for name, (xlabel, ylabel) in expected.items():
        fig = figures[name]
        ax = fig.axes[0]
        assert ax.get_xlabel() == xlabel, name
        assert ylabel in ax.get_ylabel(), name
        assert ax.get_title(), name
        assert tuple(fig.get_size_inches()) == pytest.approx((8.0, 4.5))
        for text in (ax.xaxis.label, ax.yaxis.label, ax.title):
            assert text.get_fontsize() >= 9
    assert "\u03a9" in figures["raan"].axes[0].get_ylabel()
    assert "Fig. 17" in figures["orbits"].axes[0].get_title()
    assert "Fig. 18" in figures["raan"].axes[0].get_title()
    assert "Fig. 19" in figures["cost"].axes[0].get_title()
    assert figures["iterations"].axes[1].get_ylabel() == "duration [days]"


def _rate_deg_per_day(a_m, e, inc_deg, j2):
    """Eq. 7 by hand."""
    n = math.sqrt(MU / a_m**3)
    rate = -1.5 * j2 * n * (R_EQ / a_m) ** 2 * math.cos(math.radians(inc_deg)) / (1 - e**2) ** 2
    return math.degrees(rate) * 86400.0


def _wrap(angle):
    return (angle + 180.0) % 360.0 - 180.0


def test_raan_gap_drawn_for_each_leg_starts_at_the_true_gap_and_closes_at_arrival(
    solution, catalog, figures
):
    ax = figures["raan"].axes[0]
    lines = {line.get_gid(): line for line in ax.get_lines() if line.get_gid()}
    rows = catalog.frame.set_index("id")
    j2 = solution.mission.j2
    assert len(solution.legs) == 4
    for k, leg in enumerate(solution.legs, start=1):
        line = lines[f"raan-leg-{k}"]
        days = np.asarray(line.get_xdata(), dtype=float)
        gap = np.asarray(line.get_ydata(), dtype=float)
        origin, target = rows.loc[leg.from_id], rows.loc[leg.to_id]
        rate_origin = _rate_deg_per_day(origin.a_km * 1000, origin.e, origin.inc_deg, j2)
        rate_target = _rate_deg_per_day(target.a_km * 1000, target.e, target.inc_deg, j2)
        rate_drift = _rate_deg_per_day(leg.drift_a_km * 1000, 0.0, leg.drift_inc_deg, j2)
        t1 = leg.departure_day
        t2 = t1 + leg.duration_days
        raan_origin_t1 = origin.raan_deg + rate_origin * t1
        start_gap = _wrap(raan_origin_t1 - (target.raan_deg + rate_target * t1))
        end_gap = _wrap(
            raan_origin_t1 + rate_drift * (t2 - t1) - (target.raan_deg + rate_target * t2)
        )
        assert abs(end_gap) < 0.05  # the independent model closes the gap too
        assert days[0] == pytest.approx(t1) and days[-1] == pytest.approx(t2)
        assert abs(_wrap(gap[0] - start_gap)) < 0.05
        assert abs(start_gap) > 1.0  # a real correction, not a trivial zero
        assert abs(gap[-1]) < 0.05
        assert np.all(np.abs(gap[np.isfinite(gap)]) <= 180.0)


def test_raan_line_breaks_at_the_wraparound_of_a_long_correction(solution, catalog):
    # 6 -> 10 on a low, fast drift orbit: the vehicle goes the long way round (~357 deg)
    j2 = solution.mission.j2
    orbits = NodeOrbits.from_elements(
        catalog.a_m, catalog.e, catalog.inc_rad, catalog.raan_rad, j2=j2
    )
    a_drift, inc_drift = R_EQ + 400e3, math.radians(98.9)
    path = [catalog.ids.index("6"), catalog.ids.index("10")]
    plan = evaluate_plan(orbits, path, a_drift, inc_drift, j2=j2)
    leg = Leg(
        "6",
        "10",
        0.0,
        float(plan.duration_days[0]),
        a_drift / 1000,
        400.0,
        98.9,
        1,
        float(plan.dv_mps[0]),
    )
    long_way = dataclasses.replace(solution, path=("6", "10"), legs=(leg,), initial_legs=())
    (line,) = [ln for ln in plot_raan(long_way, catalog).axes[0].get_lines() if ln.get_gid()]
    days = np.asarray(line.get_xdata(), dtype=float)
    gap = np.asarray(line.get_ydata(), dtype=float)
    assert np.isnan(gap).sum() == 1 and np.isnan(days).sum() == 1
    assert gap[0] == pytest.approx(194.1 - 191.0, abs=0.05)
    assert abs(gap[-1]) < 0.05
    steps = np.diff(gap)
    assert np.all(np.abs(steps[np.isfinite(steps)]) < 5.0)  # no line across the plot
    assert np.nanmax(gap) > 170.0 and np.nanmin(gap) < -170.0
    plot_orbits(long_way, catalog)  # a one-leg mission draws too


def test_vehicle_line_reaches_every_drift_altitude_and_debris(solution, catalog, figures):
    ax = figures["orbits"].axes[0]
    (vehicle,) = [line for line in ax.get_lines() if line.get_gid() == "vehicle"]
    days = np.asarray(vehicle.get_xdata(), dtype=float)
    alts = np.asarray(vehicle.get_ydata(), dtype=float)
    assert days[0] == 0.0 and np.all(np.diff(days) >= 0.0)
    assert days[-1] == pytest.approx(solution.total_duration_days)
    for leg in solution.legs:
        drifting = np.isclose(alts, leg.drift_alt_km, atol=1e-6)
        assert drifting.sum() >= 2  # a horizontal drift segment
        assert days[drifting].min() == pytest.approx(leg.departure_day)
        assert days[drifting].max() == pytest.approx(leg.departure_day + leg.duration_days)
    rows = catalog.frame.set_index("id")
    for debris in solution.path:
        assert np.isclose(alts, rows.loc[debris, "altitude_km"], atol=1e-6).any()


def test_cost_bars_are_the_leg_costs_and_labels_follow_each_path(solution):
    fig = plot_cost(solution)
    ax = fig.axes[0]
    heights = [patch.get_height() for patch in ax.patches]
    expected = [leg.dv_mps for leg in solution.initial_legs] + [leg.dv_mps for leg in solution.legs]
    assert heights == pytest.approx(expected)
    legend = " ".join(text.get_text() for text in ax.get_legend().get_texts())
    assert f"{solution.total_dv_mps:.1f} m/s" in legend

    # an initial plan on another path: each bar is labelled with its own leg
    old = list(solution.initial_legs)
    old[2] = dataclasses.replace(old[2], to_id="10")
    old[3] = dataclasses.replace(old[3], from_id="10", to_id="6")
    other = dataclasses.replace(solution, initial_legs=tuple(old))
    ax = plot_cost(other).axes[0]
    minor = [label.get_text() for label in ax.get_xticklabels(minor=True)]
    assert "2\u219210" in minor and "2\u21926" in minor and "6\u219210" in minor
    assert [label.get_text() for label in ax.get_xticklabels()] == [f"leg {k}" for k in range(1, 5)]


def test_iterations_skip_missing_values_and_mark_path_changes(solution):
    records = list(solution.iterations)
    records[0] = dataclasses.replace(records[0], path=("5", "8", "2", "10", "6"))
    empty = dataclasses.replace(
        records[1],
        iteration=99,
        path=(),
        dv_linearized_mps=None,
        dv_true_mps=None,
        duration_true_days=None,
        nodes=None,
        note="no path",
    )
    other = dataclasses.replace(solution, iterations=(*records, empty))
    fig = plot_iterations(other)
    left, right = fig.axes[0], fig.axes[1]
    lines = {line.get_gid(): line for line in (*left.get_lines(), *right.get_lines())}
    assert list(lines["dv-true"].get_xdata()) == [r.iteration for r in records]
    assert list(lines["dv-true"].get_ydata()) == pytest.approx([r.dv_true_mps for r in records])
    assert list(lines["duration"].get_ydata()) == pytest.approx(
        [r.duration_true_days for r in records]
    )
    assert lines["tmax"].get_ydata()[0] == pytest.approx(solution.mission.tmax_days)
    notes = [text.get_text() for text in left.texts]
    assert any("path \u2192 5\u21928\u21922\u21926\u219210" in note for note in notes)
    assert any("5\u21928\u21922\u219210\u21926" in note for note in notes)


@pytest.mark.slow
def test_save_figures_writes_png_and_svg_atomically(solution, catalog, tmp_path):
    folder = tmp_path / "figs"
    paths = save_figures(solution, catalog, folder, formats=("png", "svg"), dpi=60)
    assert sorted(p.name for p in paths) == sorted(
        f"{name}.{fmt}" for name in FIGURE_NAMES for fmt in ("png", "svg")
    )
    assert sorted(p.name for p in folder.iterdir()) == sorted(p.name for p in paths)
    for path in paths:
        if path.suffix == ".png":
            assert path.read_bytes()[:8] == PNG_SIGNATURE
        else:
            _check_svg(path.read_bytes())

    only_png = save_figures(solution, catalog, folder, dpi=50)  # default: png, overwriting
    assert [p.suffix for p in only_png] == [".png"] * 4
    assert len(list(folder.iterdir())) == 8  # no temporary file left behind


def test_save_figures_rejects_bad_input_before_writing(solution, catalog, tmp_path):
    with pytest.raises(ValueError, match="unsupported"):
        save_figures(solution, catalog, tmp_path / "a", formats=("bmp",))
    assert not (tmp_path / "a").exists()
    wrong = Catalog.from_frame(
        catalog.frame[["id", "a_km", "e", "inc_deg", "raan_deg"]].iloc[:3].copy()
    )
    with pytest.raises(ValueError, match="not in the catalog"):
        save_figures(solution, wrong, tmp_path / "b")
    assert not (tmp_path / "b").exists()


def test_iterations_mark_rejected_steps_and_an_outlier_does_not_flatten_the_axis(solution):
    """A rejected plan ending on day 85,519 of a 365-day mission (the TLE example): a red
    cross, a marker at the top edge with its value, and an axis that still shows T_max."""
    records = list(solution.iterations)
    far = dataclasses.replace(
        records[1], duration_true_days=85_519.0, rejected="true plan ends on day 85519.0"
    )
    other = dataclasses.replace(solution, iterations=(records[0], far, *records[2:]))
    fig = plot_iterations(other)
    left, right = fig.axes[0], fig.axes[1]
    tmax = solution.mission.tmax_days
    low, high = right.get_ylim()
    assert tmax < high < 2 * tmax and low > 0  # the accepted durations and T_max set the axis
    lines = {line.get_gid(): line for line in (*left.get_lines(), *right.get_lines())}
    assert list(lines["rejected"].get_xdata()) == [far.iteration]
    clipped = [line for line in right.get_lines() if line.get_gid() == "duration-clipped"]
    assert len(clipped) == 1 and clipped[0].get_ydata()[0] == pytest.approx(high)
    assert any("85,519 d" in text.get_text() for text in right.texts)
    # the same figure without the rejection mark: the outlier still does not set the axis
    assert plot_iterations(solution).axes[1].get_ylim()[1] < 2 * tmax


def test_zero_length_leg_label_does_not_cover_its_neighbour(solution, catalog):
    """A 1e-9-day leg (a RAAN crossing) gets its label above the line, not on the last one."""
    legs = list(solution.legs)
    legs[0] = dataclasses.replace(legs[0], duration_days=20.0)  # a short leg, then a 1e-9 d one
    tiny = dataclasses.replace(
        legs[1],
        departure_day=legs[0].departure_day + legs[0].duration_days,
        duration_days=1e-9,
        drift_alt_km=legs[0].drift_alt_km,
    )
    other = dataclasses.replace(solution, legs=(legs[0], tiny, *legs[2:]))
    ax = plot_orbits(other, catalog).axes[0]
    boxes = {}
    from matplotlib.backends.backend_agg import FigureCanvasAgg

    canvas = FigureCanvasAgg(ax.figure)
    canvas.draw()
    renderer = canvas.get_renderer()
    for text in ax.texts:
        if "\u2192" in text.get_text() and "km," in text.get_text():
            boxes[text.get_text().split("\n")[0]] = text.get_window_extent(renderer)
    first, second = (
        boxes[f"{legs[0].from_id}\u2192{legs[0].to_id}"],
        boxes[f"{tiny.from_id}\u2192{tiny.to_id}"],
    )
    assert not first.overlaps(second)


def test_no_two_leg_labels_overlap_on_a_crowded_mission(solution, catalog):
    """GTOC9 with n = 8: short legs whose drift orbits sit a few km apart printed their
    labels on top of each other; here every leg is 3 days long at one altitude."""
    from matplotlib.backends.backend_agg import FigureCanvasAgg

    legs, day = [], 0.0
    for leg in solution.legs:
        legs.append(dataclasses.replace(leg, departure_day=day, duration_days=3.0,
                                        drift_alt_km=solution.legs[0].drift_alt_km))  # fmt: skip
        day += 3.0
    ax = plot_orbits(dataclasses.replace(solution, legs=tuple(legs)), catalog).axes[0]
    canvas = FigureCanvasAgg(ax.figure)
    canvas.draw()
    boxes = [text.get_window_extent(canvas.get_renderer()) for text in ax.texts
             if "\u2192" in text.get_text() and "km," in text.get_text()]  # fmt: skip
    assert len(boxes) == len(legs) >= 4
    for k, box in enumerate(boxes):
        for other in boxes[k + 1:]:
            assert not box.overlaps(other)


def test_cost_figure_total_is_the_solution_total_with_operations(solution):
    ops = {"scenario": "vehicle", "per_debris_mps": {"8": 400.0, "2": 500.0}, "total_mps": 900.0}
    other = dataclasses.replace(solution, operations=ops, total_dv_mps=solution.total_dv_mps + 900)
    labels = [t.get_text() for t in plot_cost(other).axes[0].get_legend().get_texts()]
    assert any(f"= {other.total_dv_mps:.1f} m/s" in label for label in labels)
    assert any("900.0 m/s operations" in label for label in labels)


def test_certified_search_history_shows_the_bound_and_the_plan():
    """The iterations figure of a certified answer: its proven bound, not Table 7's axes."""
    from sdc_cvx import Mission

    certified = solve(mission=Mission(n=3))
    fig = plot_iterations(certified)
    ax = fig.axes[0]
    assert len(fig.axes) == 1  # no duration axis: the search has no "true duration" per step
    lines = {line.get_gid(): line for line in ax.get_lines()}
    assert lines["lower-bound"].get_ydata()[-1] == pytest.approx(certified.lower_bound_mps)
    assert lines["plan"].get_ydata()[-1] == pytest.approx(certified.total_dv_mps, abs=1e-6)
    assert "optimal" in ax.get_title() and "gap" in ax.get_title()
    # against elapsed time, every plan and every bound (issue 20, item 10: not one point)
    assert ax.get_xlabel().startswith("time since the search started")
    trace = certified.search_trace
    assert len(trace) >= 2 and list(lines["plan"].get_xdata()[:-1]) == [t for t, *_ in trace]
    plans = sum(1 for k, (*_, up) in enumerate(trace) if up is not None and (
        k == 0 or up != trace[k - 1][2]))  # fmt: skip
    assert len(lines["plans"].get_xdata()) >= plans
    relaxations = [r for r in certified.iterations if r.dv_linearized_mps is not None]
    shown = lines["relaxation"].get_xdata() if "relaxation" in lines else []
    assert len(shown) == len(relaxations)
    # iterations.csv: the best plan's ΔV beside the best plan's path, not the relaxation's
    for record in relaxations:
        assert record.path and "relaxation's path " in record.note
    if relaxations:
        assert relaxations[-1].path == certified.path
    assert any(c.get_gid() == "gap" for c in ax.collections)


def _overlap(labels, renderer) -> bool:
    boxes = [label.get_window_extent(renderer) for label in labels if label.get_text()]
    return any(a.overlaps(b) for k, a in enumerate(boxes) for b in boxes[k + 1 :])


@pytest.mark.parametrize("ids", ["short", "long"])
def test_cost_figure_without_a_before_says_so_and_its_labels_do_not_collide(solution, ids):
    """Issue 20, item 10: no "before and after" with only an after; n = 10 and long ids
    (GTOC9, TLE names) keep their leg labels apart; operations are bars, not a footnote."""
    name = (lambda k: f"{k + 100}") if ids == "short" else (lambda k: f"DEB-2020-{k:03d}A")
    legs = tuple(dataclasses.replace(solution.legs[0], from_id=name(k), to_id=name(k + 1),
                                     dv_mps=50.0 + 10 * k) for k in range(9))  # fmt: skip
    ops = {"scenario": "vehicle", "per_debris_mps": {leg.to_id: 400.0 for leg in legs},
           "total_mps": 3600.0}  # fmt: skip
    total = sum(leg.dv_mps for leg in legs) + 3600.0
    ten = dataclasses.replace(solution, legs=legs, initial_legs=(), operations=ops,
                              total_dv_mps=total)  # fmt: skip
    fig = plot_cost(ten)
    ax = fig.axes[0]
    assert "before" not in ax.get_title()
    from matplotlib.backends.backend_agg import FigureCanvasAgg

    canvas = FigureCanvasAgg(fig)
    canvas.draw()
    renderer = canvas.get_renderer()
    assert not _overlap(ax.get_xticklabels(), renderer)
    stacked = [p for p in ax.patches if p.get_gid() == "operations"]
    assert [p.get_height() for p in stacked] == [400.0] * 9
    assert [p.get_y() for p in stacked] == pytest.approx([leg.dv_mps for leg in legs])
    legend = " ".join(t.get_text() for t in ax.get_legend().get_texts())
    assert f"= {total:.1f} m/s" in legend and "3600.0 m/s operations" in legend
