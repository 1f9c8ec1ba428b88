#!/usr/bin/env bash
# The MPC's servo tick in the closed loop while a second job keeps both cores
# busy: the main job's scenario (loop-potato-whole-realtime) over iceoryx2,
# its planner in realtime mode (the tick never waits for a plan), with two
# busy loops running beside it. Prints each run's controller tick statistics
# (wall clock, measured by the controller process around `Controller::tick`).
#
#   scripts/servo_tick_under_load.sh [RUNS] [SERVO_PRIORITY] [LATENCY]
#
# SERVO_PRIORITY (default 0) is `[loop] servo_priority`: 1-99 runs the
# controller's servo thread under SCHED_FIFO (needs root or CAP_SYS_NICE).
# LATENCY (default realtime) is `[controller.mpc.planner] latency`; with
# `lockstep` each planning tick waits for the plan due, so the planning
# ticks' times bound the planner's solve time from above.
set -euo pipefail
cd "$(dirname "$0")/.."
runs="${1:-5}"
priority="${2:-0}"
latency="${3:-realtime}"
cargo build --release --quiet
work="$(mktemp -d)"
trap 'kill $(jobs -p) 2>/dev/null || true; rm -rf "$work"' EXIT
scenario="$work/servo-tick.toml"
{
    cat config/scenarios/loop-potato-whole-realtime.toml
    printf '\n[loop]\nservo_priority = %s\n' "$priority"
    printf '\n[controller.mpc.planner]\nlatency = "%s"\n' "$latency"
} >"$scenario"
for _ in 1 2; do
    sh -c 'while :; do :; done' &
done
for i in $(seq "$runs"); do
    ./target/release/shearcut run "$scenario" --controller mpc --transport iceoryx2 \
        --out "$work/run-$i" | grep -E '^(controller tick|planning ticks|end:)'
done
