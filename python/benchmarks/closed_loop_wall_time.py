"""Wall time of the main job's closed loop driven from Python against the
same loop in Rust (`shearcut.run`, i.e. `shearcut run ... --transport
inproc`), both on the same scenario, plant and MPC.

    python python/benchmarks/closed_loop_wall_time.py [REPEATS]

Times from the first command to the last answer, as the Rust loop's
`wall_s` does (the plant's and controller's construction excluded); prints
the median and the range over REPEATS runs (default 7) of each, and the
ratio of the medians. Wall-clock figures: quote them with the machine's load.
"""
import statistics
import sys
import time

import shearcut

SCENARIO = "loop-potato-whole-realtime"


def python_loop_seconds(scenario):
    plant, controller = shearcut.Plant(scenario), shearcut.Controller(scenario)
    started = time.perf_counter()
    reading, truth = plant.step(shearcut.Command())
    for _ in range(scenario.max_ticks):
        command = controller.tick(reading)
        telemetry = controller.telemetry()
        reading, truth = plant.step(command)
        if truth.crack_depth >= scenario.target_depth:
            break
        if telemetry.phase == "done" and reading.velocity == (0.0, 0.0, 0.0):
            break
    return time.perf_counter() - started, truth.work


def main():
    repeats = int(sys.argv[1]) if len(sys.argv) > 1 else 7
    scenario = shearcut.Scenario(SCENARIO, controller="mpc")
    rust, python = [], []
    for _ in range(repeats):  # interleaved, so that load drifts hit both alike
        _, summary = shearcut.run(scenario)
        rust.append(summary["wall_s"])
        seconds, work = python_loop_seconds(scenario)
        python.append(seconds)
        assert work == summary["work_j"], "the loops must agree bit for bit"
    for name, xs in (("Rust loop (shearcut.run)", rust), ("Python loop", python)):
        print(f"{name}: median {statistics.median(xs):.3f} s "
              f"(min {min(xs):.3f}, max {max(xs):.3f}) over {repeats} runs")
    print(f"Python / Rust (medians): {statistics.median(python) / statistics.median(rust):.3f}")


if __name__ == "__main__":
    main()
