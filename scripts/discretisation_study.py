#!/usr/bin/env python3
"""The plant's discretisation against real time (README, "Benchmarks":
"Real time takes a coarser plant").

Writes copies of `loop-potato-whole` with only the section mesh
(`[section] row_spacing`, `grading_ratio`, `max_element_width`) and the
plant's `update_distance` changed, runs each with the MPC in process
(`shearcut run FILE --controller mpc --transport inproc`) and prints a
markdown table of the work, the peak vertical force, the maximum
deformation and the user CPU the run took (the plant's worker threads
included; it depends on the machine's load, the physics does not).

Usage: scripts/discretisation_study.py [path/to/shearcut]  (default
target/release/shearcut; build it first with `cargo build --release`).
"""

import os
import pathlib
import sys
import tempfile

from mpc_run import run_mpc

ROOT = pathlib.Path(__file__).resolve().parent.parent
BASE = "loop-potato-whole"
# (row_spacing m, grading_ratio, max_element_width m, update_distance m);
# the reference is the scenario as shipped, the last row the main job's
# `loop-potato-whole-realtime`.
CONFIGURATIONS = [
    (1e-4, 1.3, 2e-3, 1e-3),
    (1.5e-4, 1.3, 2e-3, 1e-3),
    (2e-4, 1.3, 2e-3, 1e-3),
    (3e-4, 1.3, 2e-3, 1e-3),
    (4e-4, 1.3, 2e-3, 1e-3),
    (2e-4, 1.5, 4e-3, 1e-3),
    (2e-4, 1.3, 2e-3, 2e-3),
    (3e-4, 1.5, 4e-3, 2e-3),
    (4e-4, 1.5, 4e-3, 1e-3),
    (4e-4, 1.5, 4e-3, 2e-3),
]


def scenario_text(row_spacing, grading, max_width, update_distance):
    base = (ROOT / "config/scenarios" / f"{BASE}.toml").read_text()
    assert "[section]" not in base and "update_distance" not in base
    text = base.replace("[plant]\n", f"[plant]\nupdate_distance = {update_distance!r}\n")
    assert text != base, "the scenario has no [plant] table"
    return text + (
        f"\n[section]\nrow_spacing = {row_spacing!r}\n"
        f"grading_ratio = {grading!r}\nmax_element_width = {max_width!r}\n"
    )


def run(binary, text, out):
    before = os.times()
    _, summary = run_mpc(binary, text, out)
    after = os.times()
    return summary["cut"], after.children_user - before.children_user


def main():
    binary = sys.argv[1] if len(sys.argv) > 1 else str(ROOT / "target/release/shearcut")
    print("| `row_spacing` | `grading_ratio` / `max_element_width` | `update_distance` "
          "| work (J) | peak Fv (N) | max deformation (mm) | user CPU (s) |")
    print("|---|---|---|---|---|---|---|")
    with tempfile.TemporaryDirectory() as tmp:
        for k, (rows, grading, width, update) in enumerate(CONFIGURATIONS):
            out = pathlib.Path(tmp) / str(k)
            out.mkdir()
            cut, cpu = run(binary, scenario_text(rows, grading, width, update), out)
            print(f"| {rows * 1e3:g} mm | {grading:g} / {width * 1e3:g} mm | {update * 1e3:g} mm "
                  f"| {cut['work_j']:.4f} | {cut['peak_force_vertical_n']:.2f} "
                  f"| {cut['max_deformation_m'] * 1e3:.3f} | {cpu:.1f} |", flush=True)


if __name__ == "__main__":
    main()
