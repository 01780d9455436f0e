"""The vehicle (issue 29): validation, the acceleration it flies, its propellant budget,
the [vehicle] table, and the command line with a low-thrust vehicle (real processes)."""

import json
import math

import pandas as pd
import pytest

from sdc_cvx import Mission
from sdc_cvx.errors import MissionError, ScenarioError
from sdc_cvx.inputs.vehicle import Vehicle, propellant_budget
from sdc_cvx.study.scenario import Scenario

from ..test_cli import cli_process


def test_propellant_against_a_hand_computation_with_kits_dropped():
    """Two legs, a kit left at each of three debris, an operations burn at the second."""
    vehicle = Vehicle(dry_mass_kg=500.0, propellant_kg=80.0, isp_s=300.0, kit_mass_kg=10.0)
    budget = propellant_budget(vehicle, [100.0, 200.0], [0.0, 50.0, 0.0])
    ve = 9.80665 * 300.0
    # backwards from the end, dry: the last kit, leg 2, the second kit and its burn, leg 1,
    # the first kit
    m = 500.0 + 10.0
    after_2 = m
    m *= math.exp(200.0 / ve)
    before_2 = m
    m = (m + 10.0) * math.exp(50.0 / ve)
    after_1 = m
    m *= math.exp(100.0 / ve)
    before_1 = m
    m += 10.0
    assert budget.wet_mass_kg == pytest.approx(m, rel=1e-12)
    assert budget.needed_kg == pytest.approx(m - 500.0 - 30.0, rel=1e-12)
    assert budget.mass_before_kg == pytest.approx((before_1, before_2), rel=1e-12)
    assert budget.mass_after_kg == pytest.approx((after_1, after_2), rel=1e-12)
    assert budget.propellant_kg == pytest.approx((before_1 - after_1, before_2 - after_2))
    assert budget.operations_kg == pytest.approx((before_2 + 10.0) * math.expm1(50.0 / ve))
    assert budget.fits and budget.margin_kg == pytest.approx(80.0 - budget.needed_kg)
    tank = Vehicle(dry_mass_kg=500.0, propellant_kg=30.0, isp_s=300.0, kit_mass_kg=10.0)
    small = propellant_budget(tank, [100.0, 200.0], [0.0, 50.0, 0.0])
    assert not small.fits and small.margin_kg < 0


def test_the_low_thrust_acceleration_is_the_thrust_over_the_wet_mass_at_launch():
    vehicle = Vehicle(dry_mass_kg=800.0, propellant_kg=150.0, thrust_n=0.1, kit_mass_kg=20.0)
    assert vehicle.acceleration(5) == pytest.approx(0.1 / (800.0 + 150.0 + 100.0))
    mission = Mission(n=5, transfer="low-thrust", vehicle=vehicle)
    assert mission.transfer_model().accel_mps2 == pytest.approx(0.1 / 1050.0)
    assert Mission(transfer="low-thrust", vehicle={"accel_mps2": 2e-4}).transfer_model(
        ).accel_mps2 == 2e-4  # fmt: skip


@pytest.mark.parametrize("fields, words", [
    ({"dry_mass_kg": -1.0}, "dry_mass_kg must be a finite number > 0, got -1.0"),
    ({"isp_s": "300"}, "isp_s must be a number"),
    ({"thrust_n": 0.1, "accel_mps2": 1e-4}, "give thrust_n or accel_mps2, not both"),
    ({"kit_mass_kg": float("nan")}, "kit_mass_kg must be a finite number >= 0"),
])  # fmt: skip
def test_a_bad_vehicle_says_which_field_and_what_was_expected(fields, words):
    with pytest.raises(MissionError, match=words):
        Vehicle(**fields)


def test_a_low_thrust_mission_needs_the_acceleration():
    with pytest.raises(MissionError, match="transfer = 'low-thrust' needs the vehicle's "
                       "acceleration: missing dry_mass_kg, propellant_kg"):  # fmt: skip
        Mission(transfer="low-thrust", vehicle={"thrust_n": 0.1})
    with pytest.raises(MissionError, match="transfer must be one of"):
        Mission(transfer="solar-sail")
    with pytest.raises(MissionError, match="unknown vehicle field"):
        Mission(vehicle={"mass_kg": 3})


def test_the_vehicle_table_reads_back_from_the_scenario_as_used(tmp_path):
    path = tmp_path / "s.toml"
    path.write_text('[mission]\ntransfer = "low-thrust"\n[vehicle]\naccel_mps2 = 1e-4\n'
                    "dry_mass_kg = 900\n")  # fmt: skip
    scenario = Scenario.load(path)
    assert scenario.mission.vehicle == Vehicle(accel_mps2=1e-4, dry_mass_kg=900.0)
    again = tmp_path / "again.toml"
    again.write_text(scenario.to_toml())
    assert Scenario.load(again).mission == scenario.mission
    # an impulsive scenario writes no vehicle and no transfer: its content is unchanged
    assert "vehicle" not in Scenario().to_dict() and "transfer" not in Scenario().to_dict()[
        "mission"]  # fmt: skip
    path.write_text('[vehicle]\naccel = 1e-4\n')
    with pytest.raises(ScenarioError, match=r"unknown key vehicle\.accel"):
        Scenario.load(path)
    path.write_text('[vehicle]\nisp_s = -3\n')
    with pytest.raises(ScenarioError, match=r"vehicle\.isp_s must be a finite number > 0"):
        Scenario.load(path)
    # a bad acceleration is said once, not again as a low-thrust mission without one
    path.write_text('[mission]\ntransfer = "low-thrust"\n[vehicle]\naccel_mps2 = -1e-4\n')
    with pytest.raises(ScenarioError) as refused:
        Scenario.load(path)
    assert "vehicle.accel_mps2 must be a finite number > 0" in str(refused.value)
    assert "needs the vehicle's acceleration" not in str(refused.value)



@pytest.mark.parametrize("vehicle", [{"accel_mps2": 0.05},
                                     {"thrust_n": 100.0, "dry_mass_kg": 800.0,
                                      "propellant_kg": 200.0}])  # fmt: skip
def test_an_acceleration_that_is_not_low_thrust_is_refused(vehicle):
    """Found as a user: accel_mps2 = 100 was planned as low thrust.  0.05 m/s^2 gains 300 m/s
    a revolution at 800 km (period 6052 s): a leg's phases would be shorter than an orbit,
    which the model averages over; the thrust of 100 N on one tonne is 0.1 m/s^2."""
    with pytest.raises(MissionError, match="is not low thrust.*use the impulsive model"):
        Mission(n=3, transfer="low-thrust", vehicle=vehicle)
    Mission(n=3, transfer="low-thrust", vehicle={"accel_mps2": 1e-3})  # electric: accepted


def test_an_impulsive_plan_with_an_acceleration_says_how_long_its_burns_last():
    """Found as a user: accel_mps2 with the impulsive model was silently unused.  Each leg's
    burns last its ΔV over the acceleration; a note names each leg whose burns take more
    than 1 % of it (the paper's Part IV-D condition for impulses)."""
    from sdc_cvx import solve
    from sdc_cvx.inputs.catalog import Catalog
    from tests.conftest import PAPER_CSV

    accel = 2e-5  # a weak engine: 80 m/s take 46 days
    answer = solve(Catalog.from_csv(PAPER_CSV), Mission(n=3, vehicle={"accel_mps2": accel}))
    seconds = [leg.dv_mps / accel for leg in answer.legs]
    assert [leg.masses["burn_s"] for leg in answer.legs] == pytest.approx(seconds)
    long = [k for k, leg in enumerate(answer.legs)
            if seconds[k] > 0.01 * leg.duration_days * 86400.0]  # fmt: skip
    assert long and answer.vehicle["long_burns"] == long
    for k in long:
        leg = answer.legs[k]
        assert any(f"leg {leg.from_id} -> {leg.to_id}: its burns last "
                   f"{seconds[k] / 3600:.1f} h" in note for note in answer.notes)  # fmt: skip
    assert f"warning   the burns of {len(long)} leg(s) are long" in answer.summary()


def test_a_tank_without_an_isp_says_that_it_was_not_checked():
    """Found as a user: a [vehicle] with a dry mass and a tank but no Isp planned as if
    there were no vehicle, exit 0, nothing said."""
    from sdc_cvx import solve
    from sdc_cvx.inputs.catalog import Catalog
    from tests.conftest import PAPER_CSV

    vehicle = {"dry_mass_kg": 800.0, "propellant_kg": 1.0}  # a tank far too small
    answer = solve(Catalog.from_csv(PAPER_CSV), Mission(n=3, vehicle=vehicle))
    assert ("vehicle   no propellant computed, the tank not checked: isp_s missing"
            in answer.summary().splitlines())  # fmt: skip


@pytest.mark.slow
def test_run_with_a_low_thrust_vehicle_through_a_real_process(tmp_path):
    out = tmp_path / "lt"
    result = cli_process("run", "examples/low_thrust.toml", "--n", "3", "--json", "--out",
                         str(out))  # fmt: skip
    assert result.returncode == 0, result.stderr
    data = json.loads(result.stdout)
    assert data["transfer"] == {"transfer": "low-thrust", "accel_mps2": pytest.approx(0.1 / 1010)}
    assert data["vehicle"]["fits"] and data["certified"]
    legs = pd.read_csv(out / "legs.csv")
    for column in ("spiral_out_days", "plane_change_days", "coast_days", "spiral_in_days",
                   "propellant_kg", "mass_before_kg", "mass_after_kg"):  # fmt: skip
        assert column in legs
    phases = legs[["spiral_out_days", "plane_change_days", "coast_days", "spiral_in_days"]]
    assert (phases >= -1e-9).all().all()
    assert phases.sum(axis=1).to_numpy() == pytest.approx(legs["duration_days"].to_numpy())
    # the tank too small for the plan: written, status over_capacity, exit 3
    small = tmp_path / "small.toml"
    small.write_text('[mission]\nn = 3\ntransfer = "low-thrust"\n[vehicle]\ndry_mass_kg = 800\n'
                     "propellant_kg = 2\nisp_s = 1600\nthrust_n = 0.1\n")  # fmt: skip
    result = cli_process("run", str(small), "--quiet", "--out", str(tmp_path / "small"))
    assert result.returncode == 3
    assert "not flyable with this vehicle" in result.stderr and "Traceback" not in result.stderr
    saved = json.loads((tmp_path / "small" / "solution.json").read_text())
    assert saved["status"] == "over_capacity" and not saved["vehicle"]["fits"]
    # no acceleration: refused before any solve, which field is missing said
    result = cli_process("run", "--transfer", "low-thrust", "--quiet")
    assert result.returncode == 2 and "accel_mps2" in result.stderr
