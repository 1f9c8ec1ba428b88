"""The Python API's contracts: errors name the problem, the plant behaves
like an arm, the controller restarts deterministically."""

import math

import numpy as np
import pytest

import shearcut

CUBOID = "loop-potato-cuboid"


def test_an_unknown_scenario_is_a_value_error_naming_it():
    with pytest.raises(ValueError, match="no-such-scenario"):
        shearcut.Scenario("no-such-scenario.toml")


def test_an_unknown_controller_is_a_value_error_listing_the_choices():
    with pytest.raises(ValueError, match="slice:XI"):
        shearcut.Scenario(CUBOID, controller="pid")


def test_a_ratio_or_setpoint_out_of_range_is_a_value_error_naming_it():
    with pytest.raises(ValueError, match="slice ratio"):
        shearcut.Scenario(CUBOID, controller="slice:1e6")
    with pytest.raises(ValueError, match="force setpoint"):
        shearcut.run(shearcut.Scenario(CUBOID), controller="force:1e9")


def test_a_reading_refuses_an_unknown_status():
    with pytest.raises(ValueError, match="jerk_limit"):
        shearcut.Reading(0.0, (0, 0, 0), (0, 0, 0), (0,) * 6, status="tired")


def test_the_plant_starts_at_rest_where_the_scenario_says():
    scenario = shearcut.Scenario(CUBOID, controller="press")
    plant = shearcut.Plant(scenario)
    reading, truth = plant.step(shearcut.Command())
    assert reading.status == "moving"
    assert reading.position == scenario.start_position
    assert reading.velocity == (0.0, 0.0, 0.0)
    assert truth.work == 0.0 and truth.crack_depth == 0.0
    assert math.isclose(reading.time, scenario.period, rel_tol=1e-12)


def test_the_arm_refuses_a_step_in_velocity():
    # 0 -> 1 m/s in one 1 ms tick: 1000 m/s^2 by finite differences, above
    # the default arm's 9 m/s^2 (FR3); the knife holds still.
    scenario = shearcut.Scenario(CUBOID, controller="press")
    plant = shearcut.Plant(scenario)
    plant.step(shearcut.Command())
    reading, _ = plant.step(shearcut.Command((0.0, -1.0, 0.0)))
    assert reading.status == "acceleration_limit"
    assert math.isclose(reading.violation, 1.0 / scenario.period, rel_tol=1e-9)
    assert reading.position == scenario.start_position


def test_a_reset_controller_repeats_its_commands_bit_for_bit():
    scenario = shearcut.Scenario(CUBOID, controller="slice:0.5")
    controller = shearcut.Controller(scenario)
    reading = shearcut.Reading(0.001, scenario.start_position, (0, 0, 0), (0,) * 6)
    first = [controller.tick(reading).velocity for _ in range(50)]
    controller.reset()
    again = [controller.tick(reading).velocity for _ in range(50)]
    assert first == again
    # It ramps towards its slicing velocity: down (-y) and along (+z) at ξ = 0.5.
    vy, vz = first[-1][1], first[-1][2]
    assert vy < 0.0 and vz > 0.0
    assert math.isclose(vz / -vy, 0.5, rel_tol=1e-9)


def test_run_returns_aligned_numpy_series_and_a_summary():
    series, summary = shearcut.run(CUBOID, controller="slice:0.5")
    n = len(series["time_s"])
    assert n > 0
    for name, values in series.items():
        assert isinstance(values, np.ndarray) and values.dtype == np.float64
        assert len(values) == (summary["ticks"] if name.startswith("plan_") else n)
    assert summary["end"] == "completed" and summary["completed"]
    assert summary["controller"] == "slice:0.5"
    # Work is the integral of force along the path: it never decreases.
    assert np.all(np.diff(series["work_j"]) >= 0.0)
    assert summary["work_j"] == series["work_j"][-1]
    assert summary["cut_depth_m"] >= summary["target_depth_m"]
