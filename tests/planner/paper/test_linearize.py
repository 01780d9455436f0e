"""Linearisation (Eq. 17, 18, 20): over-estimated duration, exact date slope, kink-aware cost."""

import numpy as np
import pytest

from sdc_cvx import Catalog, Mission, preoptimize
from sdc_cvx.inputs.synthetic import sso_catalog
from sdc_cvx.planner.paper.driver import edge_geometry
from sdc_cvx.planner.paper.linearize import TrustRegion, linearize


@pytest.fixture(scope="module", params=["paper", "synthetic"])
def setup(request):
    catalog = Catalog.paper_case() if request.param == "paper" else sso_catalog(20, seed=5)
    mission = Mission()
    table = preoptimize(catalog, mission)
    geometry = edge_geometry(table.kept, catalog, mission)
    kept = table.kept
    m = len(kept)
    region = TrustRegion(
        a_ref=kept["drift_a_km"].to_numpy() * 1e3,
        t_ref=np.full(m, 40.0),
        alpha_km=np.full(m, 30.0),
        tau_days=np.full(m, 50.0),
    )
    coefficients = linearize(geometry, region, tmax_days=365.25, depart_range=(0.0, 365.25))
    return geometry, coefficients


def test_duration_secant_over_estimates_on_the_interval(setup):
    geometry, k = setup
    assert k.available.any()
    for frac in np.linspace(0.0, 1.0, 21):
        alpha = k.alpha_lo + frac * (k.alpha_hi - k.alpha_lo)
        true = geometry.duration_days(k.a_ref + alpha * 1e3, k.t_ref)
        linear = k.duration(alpha, k.t_ref)
        ok = k.available
        assert np.all(linear[ok] >= true[ok] - 1e-6)
    # exact at both ends of the interval (Eq. 17-18 secant)
    for alpha in (k.alpha_lo, k.alpha_hi):
        true = geometry.duration_days(k.a_ref + alpha * 1e3, k.t_ref)
        assert np.allclose(k.duration(alpha, k.t_ref)[k.available], true[k.available], rtol=1e-9)


def test_date_term_is_exact_at_the_reference_radius(setup):
    """T2 (t - t_ref) is the true change of the duration with the date at a_ref (Eq. 10)."""
    geometry, k = setup
    ok = k.available
    base = geometry.duration_days(k.a_ref, k.t_ref)
    for frac in (0.0, 0.3, 1.0):
        t = k.depart_lo + frac * (k.depart_hi - k.depart_lo)
        true_change = geometry.duration_days(k.a_ref, t) - base
        linear_change = k.duration(0.0, t) - k.duration(0.0, k.t_ref)
        assert np.allclose(linear_change[ok], true_change[ok], rtol=1e-7, atol=1e-6)


def test_cost_two_secants_at_their_nodes(setup):
    """C_L >= C at the interval ends and the split (kink); equal there where C is convex."""
    geometry, k = setup
    ok = k.available
    kink = (geometry.target.a - k.a_ref) / 1e3
    has_kink = ok & (kink > k.alpha_lo) & (kink < k.alpha_hi)
    grid = k.alpha_lo + np.linspace(0, 1, 401)[:, None] * (k.alpha_hi - k.alpha_lo)
    values = geometry.cost(k.a_ref + grid * 1e3)
    convex = np.all(np.diff(values, 2, axis=0) >= -1e-7, axis=0)
    for alpha, where in ((k.alpha_lo, ok), (k.alpha_hi, ok), (kink, has_kink)):
        true = geometry.cost(k.a_ref + alpha * 1e3)
        assert np.all(k.cost(alpha)[where] >= true[where] - 1e-6)
        assert np.allclose(k.cost(alpha)[where & convex], true[where & convex], atol=1e-6)
    assert (ok & convex).sum() >= ok.sum() // 2  # most edges are convex on their interval


def test_trust_interval_stays_on_its_side_and_in_the_band(setup):
    geometry, k = setup
    ok = k.available
    for alpha in (k.alpha_lo, k.alpha_hi):
        a = k.a_ref + alpha * 1e3
        assert np.all((a[ok] >= geometry.a_low - 1e-6) & (a[ok] <= geometry.a_high + 1e-6))
        days = geometry.duration_days(a, k.t_ref)
        assert np.all(np.isfinite(days[ok]) & (days[ok] <= 365.25 + 1e-6))
    assert np.all(k.alpha_lo[ok] <= 0) and np.all(k.alpha_hi[ok] >= 0)


def test_two_half_segments_pass_through_the_reference_and_over_estimate(setup):
    """Fig. 14: exact at alpha = 0 and at both ends, above the true convex duration between."""
    geometry, k = setup
    ok = k.available
    true_at_ref = geometry.duration_days(k.a_ref, k.t_ref)
    assert np.allclose(k.duration(0.0, k.t_ref, two_segments=True)[ok], true_at_ref[ok])
    for frac in np.linspace(0.0, 1.0, 21):
        alpha = k.alpha_lo + frac * (k.alpha_hi - k.alpha_lo)
        true = geometry.duration_days(k.a_ref + alpha * 1e3, k.t_ref)
        halves = k.duration(alpha, k.t_ref, two_segments=True)
        secant = k.duration(alpha, k.t_ref)
        assert np.all(halves[ok] >= true[ok] - 1e-6)
        assert np.all(halves[ok] <= secant[ok] + 1e-6)  # never looser than one secant
