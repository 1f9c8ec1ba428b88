#!/usr/bin/env python3
"""MPC work with and without online estimation on plants whose material
differs from the preset (docs/controllers.md, "MPC work with and without
estimation"), and the estimator's end-of-cut factors.

Writes one scenario per (scenario, plant, estimate) under a temporary
directory: the shipped closed-loop scenario with the material's R_c, R'_c,
E and mu scaled under [material] (the MPC keeps the preset's surrogate,
named under [controller]) and
`estimate` set under [controller.mpc]; runs `shearcut run FILE --controller
mpc --transport inproc` and prints a markdown table of the work (J) and the
estimator's end-of-cut factors.

Usage: scripts/estimation_table.py [path/to/shearcut]  (default
target/release/shearcut; build it first with `cargo build --release`).
"""

import pathlib
import sys
import tempfile
import tomllib

from mpc_run import run_mpc

ROOT = pathlib.Path(__file__).resolve().parent.parent
SCENARIOS = ["loop-potato-cuboid", "loop-potato-whole"]
PLANTS = [
    ("nominal", 1.0, 1.0, 1.0),
    ("R_c ×1.3, E ×0.7", 1.3, 0.7, 1.0),
    ("R_c ×0.7, E ×1.3", 0.7, 1.3, 1.0),
    ("μ ×1.3", 1.0, 1.0, 1.3),
    ("μ ×0.7", 1.0, 1.0, 0.7),
]


def scenario_text(name, toughness, stiffness, friction, estimate):
    base = (ROOT / "config/scenarios" / f"{name}.toml").read_text()
    parsed = tomllib.loads(base)
    preset = parsed["material"]["preset"]
    m = tomllib.loads((ROOT / "config/materials" / f"{preset}.toml").read_text())
    material = (
        f'[material]\npreset = "{preset}"\n'
        f"youngs_modulus = {m['youngs_modulus'] * stiffness!r}\n"
        f"friction_coefficient = {m['friction_coefficient'] * friction!r}\n"
        f"fracture_toughness = {m['fracture_toughness'] * toughness!r}\n"
        f"initial_fracture_toughness = {m['initial_fracture_toughness'] * toughness!r}\n"
    )
    lines = base.replace(f'[material]\npreset = "{preset}"\n', material)
    assert lines != base, "the scenario's [material] table is not a bare preset"
    # An overridden material is no preset: name the preset's surrogate.
    surrogate = f"{preset}-{parsed['knife']['preset']}"
    lines = lines.replace("[controller]\n", f'[controller]\nsurrogate = "{surrogate}"\n')
    assert "[controller.mpc]" not in lines
    return lines + f"\n[controller.mpc]\nestimate = {'true' if estimate else 'false'}\n"


def run(binary, text, out):
    run_dir, summary = run_mpc(binary, text, out)
    rows = (run_dir / "controller.csv").read_text().strip().splitlines()
    header, last = rows[0].split(","), rows[-1].split(",")
    factors = [float(last[header.index(f"scale_{k}")]) for k in ("toughness", "stiffness", "friction")]
    return summary["cut"]["work_j"], factors


def main():
    binary = sys.argv[1] if len(sys.argv) > 1 else str(ROOT / "target/release/shearcut")
    print("| scenario | plant | work, estimating (J) | work, not (J) | change | end-of-cut T, S, F (error) |")
    print("|---|---|---|---|---|---|")
    with tempfile.TemporaryDirectory() as tmp:
        for name in SCENARIOS:
            for label, t, s, f in PLANTS:
                works, estimated = [], None
                for estimate in (True, False):
                    out = pathlib.Path(tmp) / f"{name}-{t}-{s}-{f}-{estimate}"
                    out.mkdir()
                    work, factors = run(binary, scenario_text(name, t, s, f, estimate), out)
                    works.append(work)
                    estimated = estimated or factors
                change = 100.0 * (works[0] / works[1] - 1.0)
                errors = ", ".join(
                    f"{e:.3f} ({100.0 * (e / x - 1.0):+.1f} %)" for e, x in zip(estimated, (t, s, f)))
                print(f"| `{name}` | {label} | {works[0]:.4f} | {works[1]:.4f} | {change:+.1f} % | {errors} |",
                      flush=True)


if __name__ == "__main__":
    main()
