"""Close shearcut's loop in Python: the MPC against the simulated plant, then a plot.

    python examples/close_the_loop.py [OUT.png]
"""
import sys

import matplotlib.pyplot as plt

import shearcut

scenario = shearcut.Scenario("loop-potato-whole-realtime", controller="mpc")
plant, controller = shearcut.Plant(scenario), shearcut.Controller(scenario)
reading, truth = plant.step(shearcut.Command())  # the first command: the arm at rest
time, force, xi = [], [], []
for _ in range(scenario.max_ticks):
    command = controller.tick(reading)  # on a real arm: your 1 kHz callback
    reading, truth = plant.step(command)  # on a real arm: send command, read the arm
    time.append(reading.time)
    force.append(truth.force[1])
    xi.append(controller.telemetry().slice_push_ratio)
    if truth.crack_depth >= scenario.target_depth:
        break
print(f"work {truth.work:.4f} J, peak Fv {max(force):.3f} N, {len(time)} ticks")
fig, (top, bottom) = plt.subplots(2, 1, sharex=True, figsize=(7, 5))
top.plot(time, force), top.set_ylabel("vertical force on the knife (N)")
bottom.plot(time, xi), bottom.set_ylabel("planned slice-push ratio ξ")
bottom.set_xlabel("time (s)")
fig.savefig(sys.argv[1] if len(sys.argv) > 1 else "close_the_loop.png", dpi=120)
