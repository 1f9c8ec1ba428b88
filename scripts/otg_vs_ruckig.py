#!/usr/bin/env python3
"""Compare shearcut's trajectory generator with ruckig 0.19.4 (an external oracle).

Usage: otg_vs_ruckig.py --cases N --seed S --shearcut CMD... (see otg_vs_ruckig.sh)

1. Generates N random cases with ruckig's own test distributions: positions N(0, 4), velocities
   and accelerations N(0, 0.8) (zero with some probability), limits U(0.1, 12) plus the magnitude of
   the corresponding target value, 1 to 7 DoFs, time synchronisation.
2. Runs ruckig (Python binding) on every case, timing each calculation.
3. Runs `shearcut trajectory --cases FILE --out FILE`.
4. Reports: our duration longer than ruckig's by more than 1e-9*max(1, T) (regressions), shorter by
   more than 1e-6 (each re-run with dense sampling and checked against the limits and by finite
   differences), errors on either side, and ruckig's calculation time per DoF count.
"""
import argparse
import json
import math
import os
import statistics
import subprocess
import sys
import time

import numpy as np
from ruckig import ControlInterface, InputParameter, Ruckig, Trajectory, Synchronization

try:
    from ruckig import RuckigError
except ImportError:  # pragma: no cover
    RuckigError = RuntimeError


def gen_case(rng, dofs, idx):
    def normal(sd, p_nonzero=1.0):
        return [float(rng.normal(0.0, sd)) if rng.random() < p_nonzero else 0.0 for _ in range(dofs)]

    tv = normal(0.8, 0.7)
    ta = normal(0.8, 0.6)
    case = {
        "id": idx,
        "current_position": normal(4.0),
        "current_velocity": normal(0.8, 0.9),
        "current_acceleration": normal(0.8, 0.8),
        "target_position": normal(4.0),
        "target_velocity": tv,
        "target_acceleration": ta,
        "max_velocity": [float(rng.uniform(0.1, 12.0)) + abs(x) for x in tv],
        "max_acceleration": [float(rng.uniform(0.1, 12.0)) + abs(x) for x in ta],
        "max_jerk": [float(rng.uniform(0.1, 12.0)) for _ in range(dofs)],
        "synchronization": "time",
    }
    return case


def ruckig_run(case):
    dofs = len(case["current_position"])
    otg = Ruckig(dofs)
    inp = InputParameter(dofs)
    for k in ("current_position", "current_velocity", "current_acceleration", "target_position",
              "target_velocity", "target_acceleration", "max_velocity", "max_acceleration", "max_jerk"):
        setattr(inp, k, case[k])
    inp.synchronization = {"time": Synchronization.Time, "phase": Synchronization.Phase,
                           "none": Synchronization.No}[case["synchronization"]]
    if case.get("control_interface", "position") == "velocity":
        inp.control_interface = ControlInterface.Velocity
    traj = Trajectory(dofs)
    try:
        valid = otg.validate_input(inp, False, True)
    except Exception:  # noqa: BLE001 - ruckig raises on invalid input
        valid = False
    if not valid:
        return {"invalid": True}
    t0 = time.perf_counter()
    try:
        res = otg.calculate(inp, traj)
    except RuckigError as e:
        return {"error": str(e), "time": time.perf_counter() - t0}
    dt = time.perf_counter() - t0
    if int(res) < 0:
        return {"error": str(res), "time": dt}
    return {"duration": traj.duration, "time": dt}


def check_samples(case, out, tol=1e-9):
    """Checks our densely sampled trajectory against the limits and by finite differences."""
    s = out["samples"]
    n = len(case["current_position"])
    t = np.array(s["t"])
    p, v, a = (np.array(s[k]) for k in ("p", "v", "a"))
    problems = []
    braking_end = out.get("brake_duration", 0.0)
    mask = t >= braking_end
    velocity_interface = case.get("control_interface") == "velocity"
    for i in range(n):
        vmax, amax = case["max_velocity"][i], case["max_acceleration"][i]
        if not velocity_interface and np.any(np.abs(v[mask, i]) > vmax * (1 + 1e-12) + 1e-12):
            problems.append(f"dof {i}: |v| {np.abs(v[mask, i]).max()} > {vmax}")
        if np.any(np.abs(a[mask, i]) > amax * (1 + 1e-12) + 1e-12):
            problems.append(f"dof {i}: |a| {np.abs(a[mask, i]).max()} > {amax}")
        h = np.diff(t)
        # jerk by finite differences of the acceleration (piecewise linear ⇒ exact up to kinks)
        jerk = np.abs(np.diff(a[:, i]) / h)
        if np.any(jerk > case["max_jerk"][i] * (1 + 1e-6) + 1e-6):
            problems.append(f"dof {i}: finite-difference jerk {jerk.max()} > {case['max_jerk'][i]}")
        # position consistent with velocity and acceleration: for a cubic p(t) the corrected
        # trapezoid rule dp = h (v0 + v1)/2 - h^2 (a1 - a0)/12 is exact; a jerk switch inside a
        # step adds at most h^3 * 2 j_max.
        dp = np.diff(p[:, i])
        vint = 0.5 * (v[1:, i] + v[:-1, i]) * h - h * h * np.diff(a[:, i]) / 12.0
        tol_p = 1e-11 * (1 + np.abs(p[:, i]).max()) + h ** 3 * 2 * case["max_jerk"][i]
        if np.any(np.abs(dp - vint) > tol_p):
            problems.append(f"dof {i}: position/velocity inconsistent")
        if (not velocity_interface and abs(p[-1, i] - case["target_position"][i]) > 1e-8) \
                or abs(v[-1, i] - case["target_velocity"][i]) > 1e-8 \
                or abs(a[-1, i] - case["target_acceleration"][i]) > 1e-10:
            problems.append(f"dof {i}: final state off")
    return problems


def start_unsafe(case):
    """True if the start state makes a limit violation unavoidable (braking needed)."""
    for v, a, vm, am, j in zip(case["current_velocity"], case["current_acceleration"], case["max_velocity"],
                               case["max_acceleration"], case["max_jerk"]):
        if abs(a) > am or abs(v) > vm or (v * a > 0 and abs(v) + a * a / (2 * j) > vm):
            return True
    return False


def run_ours(cmd, cases_path, out_path):
    subprocess.run(cmd + ["trajectory", "--cases", cases_path, "--out", out_path], check=True)
    res = {}
    with open(out_path) as f:
        for line in f:
            r = json.loads(line)
            res[r["id"]] = r
    return res


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--cases", type=int, default=100000)
    ap.add_argument("--seed", type=int, default=42)
    ap.add_argument("--workdir", default="target/otg_vs_ruckig")
    ap.add_argument("--timing-cases", type=int, default=20000)
    ap.add_argument("--control-interface", choices=["position", "velocity"], default="position")
    ap.add_argument("--timing-only", action="store_true",
                    help="only time ruckig per DoF count (to measure it back to back with "
                         "`cargo bench -p shearcut-controllers --bench trajectory`)")
    ap.add_argument("--dump-timing-cases", metavar="FILE",
                    help="only write the cases that --timing-only would time (same seed, same order) "
                         "to FILE, one per line: DoF count, then the nine input vectors (for "
                         "scripts/ruckig_cpp_timing.sh)")
    ap.add_argument("shearcut", nargs="+", help="command that runs the shearcut binary")
    args = ap.parse_args()
    os.makedirs(args.workdir, exist_ok=True)
    rng = np.random.default_rng(args.seed)
    if args.dump_timing_cases:
        dump_timing_cases(rng, args.timing_cases, args.dump_timing_cases)
        return 0
    if args.timing_only:
        ruckig_timing(rng, args.timing_cases)
        return 0

    cases = [gen_case(rng, int(rng.integers(1, 8)), k) for k in range(args.cases)]
    for c in cases:
        c["control_interface"] = args.control_interface
    cases_path = os.path.join(args.workdir, "cases.jsonl")
    with open(cases_path, "w") as f:
        for c in cases:
            f.write(json.dumps(c) + "\n")

    t0 = time.time()
    ruck = [ruckig_run(c) for c in cases]
    print(f"ruckig: {len(cases)} cases in {time.time() - t0:.1f} s")
    t0 = time.time()
    ours = run_ours(args.shearcut, cases_path, os.path.join(args.workdir, "ours.jsonl"))
    print(f"shearcut: {len(cases)} cases in {time.time() - t0:.1f} s (including process start and JSON)")

    invalid = [c for c, r in zip(cases, ruck) if r.get("invalid")]
    r_err = [c for c, r in zip(cases, ruck) if "error" in r]
    o_err = [c for c, r in zip(cases, ruck) if not r.get("invalid") and "error" in ours[c["id"]]]
    o_err_on_invalid = [c for c in invalid if "error" not in ours[c["id"]]]
    longer, shorter, braking, longer_brake = [], [], 0, []
    for c, r in zip(cases, ruck):
        o = ours[c["id"]]
        if "duration" not in r or "duration" not in o:
            continue
        if o.get("braking"):
            braking += 1
        tr, to = r["duration"], o["duration"]
        if to > tr + 1e-9 * max(1.0, tr):
            (longer_brake if o.get("braking") else longer).append((c, tr, to))
        elif to < tr - 1e-6:
            shorter.append((c, tr, to))

    # Re-run the cases where we are shorter with dense samples, check them independently.
    shorter_bad = []
    if shorter:
        path = os.path.join(args.workdir, "shorter.jsonl")
        with open(path, "w") as f:
            for c, _, _ in shorter:
                f.write(json.dumps(dict(c, sample_count=4000)) + "\n")
        res = run_ours(args.shearcut, path, os.path.join(args.workdir, "shorter_out.jsonl"))
        for c, tr, to in shorter:
            probs = check_samples(c, res[c["id"]])
            if probs:
                shorter_bad.append((c, probs))

    print(f"cases: {len(cases)} (1-7 DoFs, time synchronisation, {args.control_interface} interface, seed {args.seed})")
    print(f"  rejected by ruckig's input validation: {len(invalid)} (of which we still solved: {len(o_err_on_invalid)})")
    print(f"  ruckig errors: {len(r_err)}")
    o_err_brake = [c for c in o_err if start_unsafe(c)]
    o_err = [c for c in o_err if not start_unsafe(c)]
    print(f"  shearcut errors (on inputs ruckig accepts): {len(o_err)} with the start inside the limits, "
          f"{len(o_err_brake)} with a start that makes a violation unavoidable")
    print(f"  shearcut braking pre-phase used: {braking}")
    print(f"  ours longer than ruckig by > 1e-9*max(1,T): {len(longer)} "
          f"(plus {len(longer_brake)} cases where a start state outside the limits makes both brake first)")
    n_sb = sum(1 for c, _, _ in shorter if ours[c["id"]].get("braking"))
    print(f"  ours shorter than ruckig by > 1e-6: {len(shorter)} ({n_sb} with braking; "
          f"violating limits or inconsistent in dense sampling: {len(shorter_bad)})")
    for c, tr, to in longer[:5]:
        print("  LONGER", json.dumps(c), "ruckig", tr, "ours", to)
    for c, tr, to in longer_brake[:3]:
        print("  LONGER WITH BRAKING", json.dumps(c), "ruckig", tr, "ours", to)
    with open(os.path.join(args.workdir, "longer_ids.txt"), "w") as f:
        f.write(" ".join(str(c["id"]) for c, _, _ in longer) + "\n")
        f.write(" ".join(str(c["id"]) for c, _, _ in longer_brake) + "\n")
        f.write(" ".join(str(c["id"]) for c, _ in shorter_bad) + "\n")
        f.write(" ".join(str(c["id"]) for c in o_err) + "\n")
    for c in o_err[:5]:
        print("  OUR ERROR", json.dumps(c), ours[c["id"]]["error"])
    for c, tr, to in shorter[:3]:
        print("  SHORTER", json.dumps(c), "ruckig", tr, "ours", to)
    for c, probs in shorter_bad[:3]:
        print("  SHORTER BUT VIOLATING", c["id"], probs[:4])

    ruckig_timing(rng, args.timing_cases)
    return 1 if longer or shorter_bad or o_err else 0


TIMING_FIELDS = ("current_position", "current_velocity", "current_acceleration", "target_position",
                 "target_velocity", "target_acceleration", "max_velocity", "max_acceleration", "max_jerk")


def dump_timing_cases(rng, timing_cases, path):
    """Writes the cases of `ruckig_timing` (same rng sequence) as plain text lines."""
    with open(path, "w") as f:
        for dofs in (1, 3, 6, 7):
            for k in range(timing_cases):
                c = gen_case(rng, dofs, k)
                vals = [repr(float(x)) for key in TIMING_FIELDS for x in c[key]]
                f.write(f"{dofs} " + " ".join(vals) + "\n")


def ruckig_timing(rng, timing_cases):
    """ruckig timing per DoF count (Python binding: includes the call overhead)."""
    print("ruckig calculation time through the Python binding (per calculation):")
    for dofs in (1, 3, 6, 7):
        times = []
        for k in range(timing_cases):
            c = gen_case(rng, dofs, k)
            r = ruckig_run(c)
            if "time" in r:
                times.append(r["time"])
        times.sort()
        print(f"  {dofs} DoF: median {statistics.median(times) * 1e6:.2f} us, "
              f"p99 {times[int(0.99 * len(times))] * 1e6:.2f} us, max {times[-1] * 1e6:.2f} us ({len(times)} cases)")


if __name__ == "__main__":
    sys.exit(main())
