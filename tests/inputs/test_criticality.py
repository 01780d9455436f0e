"""The Criticality of Spacecraft Index (issue 27: ``[catalog] values = "csi"``) against its
published formula worked by hand, and the time an orbit spends in a shell against a
sampling of Kepler's equation."""

import json
import math

import numpy as np
import pytest

from sdc_cvx.errors import ScenarioError
from sdc_cvx.inputs.criticality import (
    criticality_index,
    inclination_factor,
    lifetime_factor,
    shell_fractions,
    spatial_density,
    time_below,
)
from sdc_cvx.study.scenario import Scenario
from tests.conftest import shared_file
from tests.test_cli import cli_process

R_KM = 6378.137
TLE = "sso_rocket_bodies_2020/sso_rb.tle"


def test_the_index_of_a_circular_orbit_is_the_published_product():
    """CSI = M/M0 D/D0 L/L0 (1 + k (1 - cos i)/2)/(1 + k), M0 = 1e4 kg, D0 = 6.8e-8 /km³,
    k = 0.6, ln L = 6.5215 h^0.2583 - 33.8481 normalised at 1031.5 km (Rossi et al. 2015,
    with Bombardelli et al.'s lifetime fit)."""
    h, inc, mass, density = 800.0, 71.0, 9000.0, 4e-8
    life = math.exp(6.5215 * h**0.2583 - 33.8481) / math.exp(6.5215 * 1031.5**0.2583 - 33.8481)
    expected = (mass / 1e4 * density / 6.8e-8 * life
                * (1 + 0.6 * (1 - math.cos(math.radians(inc))) / 2) / 1.6)  # fmt: skip
    edges = np.array([775.0, 825.0])
    got = criticality_index([mass], [R_KM + h], [0.0], [inc], edges, [density])
    assert got[0] == pytest.approx(expected, rel=1e-12)


def test_the_factors_at_their_ends():
    assert lifetime_factor([1031.5, 1200.0, 2000.0]) == pytest.approx([1.0, 1.0, 1.0])
    assert lifetime_factor(400.0) < lifetime_factor(800.0) < 1.0
    assert inclination_factor([0.0, 90.0, 180.0]) == pytest.approx([1 / 1.6, 1.3 / 1.6, 1.0])


@pytest.mark.parametrize(("a_km", "e"), [(R_KM + 800.0, 0.05), (R_KM + 1500.0, 0.2)])
def test_the_time_below_a_radius_is_kepler_sampled(a_km, e):
    """Mean anomaly uniform in time; r = a (1 - e cos E), E from Kepler's equation solved
    by Newton here."""
    mean = np.linspace(0.0, 2 * np.pi, 200_001)[:-1]
    anomaly = mean.copy()
    for _ in range(30):
        anomaly -= (anomaly - e * np.sin(anomaly) - mean) / (1 - e * np.cos(anomaly))
    radius = a_km * (1 - e * np.cos(anomaly))
    for r in np.linspace(a_km * (1 - e) - 10, a_km * (1 + e) + 10, 9):
        assert float(time_below(a_km, e, r)) == pytest.approx(np.mean(radius < r), abs=2e-5)


def test_the_density_counts_each_object_once_over_the_shells():
    rng = np.random.default_rng(5)
    a = R_KM + rng.uniform(300, 1500, 200)
    e = rng.uniform(0, 0.01, 200)  # every perigee above 200 km, every apogee below 3000
    edges = np.arange(100.0, 3000.0, 25.0)
    fractions = shell_fractions(a, e, edges)
    assert fractions.sum(axis=1) == pytest.approx(np.ones(200))
    radii = R_KM + edges
    volumes = 4 / 3 * np.pi * np.diff(radii**3)
    assert float((spatial_density(a, e, edges) * volumes).sum()) == pytest.approx(200.0)


def test_a_csi_scenario_needs_the_masses_and_the_catalogue(tmp_path):
    scenario = tmp_path / "s.toml"
    scenario.write_text('[catalog]\nvalues = "csi"\n[campaign]\nobjective = "max-value"\n'
                        'launch_days = [0.0]\nn = [[2, 3]]\ndv_budget_mps = 300.0\n',
                        encoding="utf-8")  # fmt: skip
    with pytest.raises(ScenarioError, match="catalog.masses") as err:
        Scenario.load(scenario)
    assert "catalog.path" not in str(err.value)  # one thing at a time: the masses first


@pytest.mark.slow
@pytest.mark.requires_shared_data(TLE)
def test_a_csi_campaign_reads_its_masses_and_names_a_candidate_without_one(tmp_path):
    """Through a real process: the campaign's values are the index of each candidate (the
    scenario as used says "csi"); a candidate with no mass stops it before any search."""
    from sdc_cvx.inputs.criticality import csi_values
    from sdc_cvx.inputs.formats import READERS
    from sdc_cvx.inputs.values import read_values

    catalog = READERS["tle"](shared_file(TLE), on_invalid="set aside")
    ids = [str(k) for k in catalog.ids[:6]]
    masses = tmp_path / "masses.csv"
    masses.write_text("id,mass_kg\n" + "".join(f"{k},{1000 + 100 * n}\n"
                                               for n, k in enumerate(ids[:5])),
                      encoding="utf-8")  # fmt: skip
    text = (f'[catalog]\npath = {json.dumps(str(shared_file(TLE)))}\nvalues = "csi"\n'
            f'masses = {json.dumps(str(masses))}\n[selection]\nids = {json.dumps(ids)}\n'
            '[mission]\ntmax_days = 120.0\n[campaign]\nobjective = "max-value"\n'
            'launch_days = [0.0]\nn = [[2, 3]]\ndv_budget_mps = 400.0\n')  # fmt: skip
    scenario = tmp_path / "csi.toml"
    scenario.write_text(text, encoding="utf-8")
    expected = csi_values(catalog, read_values(masses, ("id", "mass_kg")))
    assert dict(Scenario.load(scenario).campaign.values) == pytest.approx(expected)
    refused = cli_process("campaign", str(scenario), "--out", str(tmp_path / "no"))
    assert refused.returncode == 2 and ids[5] in refused.stderr and "no mass" in refused.stderr
    assert "Traceback" not in refused.stderr and not (tmp_path / "no").exists()
    scenario.write_text(text.replace(json.dumps(ids), json.dumps(ids[:5])), encoding="utf-8")
    done = cli_process("campaign", str(scenario), "--out", str(tmp_path / "out"), "--quiet")
    assert done.returncode == 0, done.stderr
    result = json.loads((tmp_path / "out" / "campaign.json").read_text(encoding="utf-8"))
    removed = [str(k) for m in result["missions"] for k in m["path"]]
    assert result["value"] == pytest.approx(sum(expected[k] for k in removed))
    used = (tmp_path / "out" / "scenario.toml").read_text(encoding="utf-8")
    assert 'values = "csi"' in used and str(masses) in used


@pytest.mark.requires_shared_data(TLE)
def test_a_bad_masses_file_is_named_with_its_line_and_field(tmp_path):
    masses = tmp_path / "masses.csv"
    masses.write_text("id,mass_kg\n7412,abc\n7817,-5\n", encoding="utf-8")
    scenario = tmp_path / "s.toml"
    scenario.write_text(f'[catalog]\npath = {json.dumps(str(shared_file(TLE)))}\n'
                        f'values = "csi"\nmasses = {json.dumps(str(masses))}\n',
                        encoding="utf-8")  # fmt: skip
    with pytest.raises(ScenarioError) as err:
        Scenario.load(scenario)
    text = str(err.value)
    assert "catalog.masses" in text and "line 2, field mass_kg" in text and "'abc'" in text
    assert "line 3" in text and "'-5'" in text
    masses.write_text("id,mass\n7412,3\n", encoding="utf-8")
    with pytest.raises(ScenarioError, match="a masses file needs the columns 'id' and 'mass_kg'"):
        Scenario.load(scenario)
