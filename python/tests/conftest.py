"""A Python-driven closed loop with the same lockstep as `shearcut run`."""

import pytest

import shearcut

MAIN_JOB = "loop-potato-whole-realtime"


def python_loop(scenario):
    """Runs scenario's controller against its plant from Python, stopping as
    `shearcut run` does; returns (end, rows) with one (reading, truth,
    telemetry) row per tick."""
    plant, controller = shearcut.Plant(scenario), shearcut.Controller(scenario)
    reading, truth = plant.step(shearcut.Command())
    rows, end = [], "timed_out"
    for _ in range(scenario.max_ticks):
        command = controller.tick(reading)
        telemetry = controller.telemetry()
        reading, truth = plant.step(command)
        rows.append((reading, truth, telemetry))
        if truth.crack_depth >= scenario.target_depth:
            end = "completed"
            break
        if telemetry.phase == "done" and reading.velocity == (0.0, 0.0, 0.0):
            end = "controller_done"
            break
    return end, rows


@pytest.fixture(scope="session")
def main_job():
    """The main job's scenario under the MPC: the Rust run and the Python loop."""
    scenario = shearcut.Scenario(MAIN_JOB, controller="mpc")
    series, summary = shearcut.run(scenario)
    end, rows = python_loop(scenario)
    return scenario, series, summary, end, rows
