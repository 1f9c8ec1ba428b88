#!/usr/bin/env python3
"""Markdown accuracy tables of the shipped surrogates, for docs/surrogates.md.

Prints, from the accuracy files written by `shearcut fit`
(`config/surrogates/<material>-<knife>.accuracy.toml`), the tables of the
section "## Accuracy against held-out runs" of docs/surrogates.md, in the
order the section shows them:

1. the worst over the six held-out runs per material (F_n, F_t and work RMS,
   peak F_n and onset; absolute values, as `worst_*` in the files);
2. the per-run tables at nominal (T = S = 1) of whole eggplant, cuboid
   eggplant and potato-cuboid: xi, H x w/2, F_n / F_t / work RMS, the signed
   peak F_n error (`peak_force_error_pct`, surrogate minus full model over the
   full model's window-averaged peak) and the signed onset error with the
   depths (`onset_depth_full` -> `onset_depth_surrogate`, mm);
3. the `[[scaled]]` summary: worst / mean F_n and F_t RMS over the six runs
   with the ratio corrections and with linear scaling, per material and
   (T, S), rho = S / T;
4. the per-run `[[scaled]]` tables ("corrected -> linear") of potato-cuboid
   and whole eggplant.

RMS errors are in % of the full model's range over the run, one decimal;
negative numbers carry a unicode minus as the doc does. With --all the
per-run tables of every material are printed, not only the doc's.

With the default files (the straight knife's) the chef knife's files are
checked to hold the same figures (they differ only in their header comment
and knife_name); a difference is reported on stderr.

Run from the repository root (standard library only, Python >= 3.11):

    python3 scripts/accuracy_tables.py            # the doc's tables
    python3 scripts/accuracy_tables.py --all      # every material's per-run tables
    python3 scripts/accuracy_tables.py FILE...    # other accuracy files
"""

import argparse
import glob
import os
import sys
import tomllib

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
DEFAULT_GLOB = os.path.join(ROOT, "config", "surrogates", "*-straight.accuracy.toml")

# The doc's order of materials in each kind of table.
SUMMARY_ORDER = ["potato-cuboid", "eggplant-cuboid", "potato-whole", "eggplant-whole"]
PER_RUN_ORDER = ["eggplant-whole", "eggplant-cuboid", "potato-cuboid"]
SCALED_ORDER = ["potato-cuboid", "potato-whole", "eggplant-cuboid", "eggplant-whole"]
SCALED_PER_RUN_ORDER = ["potato-cuboid", "eggplant-whole"]


def num(x, digits=1):
    """Unsigned-style number with a unicode minus if negative."""
    return f"{x:.{digits}f}".replace("-", "\u2212")


def signed(x, digits=1):
    """Number with an explicit sign, unicode minus for negatives."""
    return f"{x:+.{digits}f}".replace("-", "\u2212")


def size(run):
    """H x w/2 in mm."""
    return f"{run['height'] * 1e3:.0f} \u00d7 {run['half_width'] * 1e3:.0f}"


def order(names, preferred):
    """The materials in the doc's order, any others after them, sorted."""
    return [m for m in preferred if m in names] + sorted(m for m in names if m not in preferred)


def table(header, rows):
    out = ["| " + " | ".join(header) + " |", "|" + "---|" * len(header)]
    out += ["| " + " | ".join(r) + " |" for r in rows]
    return "\n".join(out)


def summary(reports):
    rows = []
    for m in order(reports, SUMMARY_ORDER):
        r = reports[m]
        rows.append([m] + [f"{num(r[k])} %" for k in (
            "worst_force_normal_rms_pct",
            "worst_force_tangential_rms_pct",
            "worst_work_rms_pct",
            "worst_peak_force_error_pct",
            "worst_onset_depth_error_pct",
        )])
    return table(["material", "F_n RMS", "F_t RMS", "work RMS", "peak F_n", "onset"], rows)


def per_run(report):
    rows = []
    for r in report["runs"]:
        onset = (f"{signed(r['onset_depth_error_pct'])} % "
                 f"({r['onset_depth_full'] * 1e3:.3f} \u2192 {r['onset_depth_surrogate'] * 1e3:.3f} mm)")
        rows.append([
            f"{r['xi']:.1f}", size(r),
            f"{num(r['force_normal_rms_pct'])} %",
            f"{num(r['force_tangential_rms_pct'])} %",
            f"{num(r['work_rms_pct'])} %",
            f"{signed(r['peak_force_error_pct'])} %",
            onset,
        ])
    return table(["\u03be", "H \u00d7 w/2 (mm)", "F_n RMS", "F_t RMS", "work RMS", "peak F_n",
                  "onset (full \u2192 surrogate)"], rows)


def rho(block):
    return block["stiffness"] / block["toughness"]


def scaled_summary(reports):
    rows = []
    for m in order(reports, SCALED_ORDER):
        for s in reports[m].get("scaled", []):
            def pair(k):
                return f"{num(s['worst_' + k])} / {num(s['mean_' + k])} %"
            rows.append([
                m, f"{s['toughness']:g}, {s['stiffness']:g} ({rho(s):.2f})",
                pair("force_normal_rms_pct"), pair("force_normal_rms_pct_linear"),
                pair("force_tangential_rms_pct"), pair("force_tangential_rms_pct_linear"),
            ])
    return table(["material", "T, S (\u03c1)", "F_n RMS worst / mean, corrected", "F_n linear",
                  "F_t RMS worst / mean, corrected", "F_t linear"], rows)


def scaled_per_run(report):
    blocks = report.get("scaled", [])
    header = ["\u03be", "H \u00d7 w/2 (mm)"]
    for s in blocks:
        header += [f"\u03c1 = {rho(s):.2f} F_n", f"\u03c1 = {rho(s):.2f} F_t"]
    runs = blocks[0]["runs"] if blocks else []
    rows = []
    for i, r in enumerate(runs):
        row = [f"{r['xi']:.1f}", size(r)]
        for s in blocks:
            q = s["runs"][i]
            if (q["xi"], q["height"], q["half_width"]) != (r["xi"], r["height"], r["half_width"]):
                sys.exit(f"{report['material_name']}: [[scaled]] blocks list their runs in different orders")
            for k in ("force_normal_rms_pct", "force_tangential_rms_pct"):
                row.append(f"{num(q[k])} \u2192 {num(q[k + '_linear'])}")
        rows.append(row)
    return table(header, rows)


def strip_knife(path):
    """The file's data without its header comment and knife_name."""
    with open(path, "rb") as f:
        d = tomllib.load(f)
    d.pop("knife_name", None)
    return d


def check_chef(paths):
    ok = True
    for p in paths:
        q = p.replace("-straight.accuracy.toml", "-chef.accuracy.toml")
        if q == p or not os.path.exists(q):
            print(f"note: no chef file for {p}", file=sys.stderr)
            ok = False
        elif strip_knife(p) != strip_knife(q):
            print(f"warning: {q} differs from {p} (beyond knife_name)", file=sys.stderr)
            ok = False
    return ok


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("files", nargs="*", help="accuracy files (default: config/surrogates/*-straight.accuracy.toml)")
    ap.add_argument("--all", action="store_true", help="per-run tables of every material")
    a = ap.parse_args()
    paths = a.files or sorted(glob.glob(DEFAULT_GLOB))
    if not paths:
        sys.exit(f"no accuracy files ({DEFAULT_GLOB})")
    if not a.files:
        check_chef(paths)
    reports = {}
    for p in paths:
        with open(p, "rb") as f:
            d = tomllib.load(f)
        name = d["material_name"]
        if name in reports:
            sys.exit(f"{name} given twice ({p}); pass one knife's files")
        reports[name] = d

    per_run_materials = order(reports, PER_RUN_ORDER if not a.all else SUMMARY_ORDER)
    scaled_materials = order([m for m in reports if reports[m].get("scaled")],
                             SCALED_PER_RUN_ORDER if not a.all else SCALED_ORDER)
    if not a.all:
        per_run_materials = [m for m in per_run_materials if m in PER_RUN_ORDER]
        scaled_materials = [m for m in scaled_materials if m in SCALED_PER_RUN_ORDER]

    parts = ["Worst over the held-out runs (absolute values):", summary(reports)]
    for m in per_run_materials:
        parts += [f"{m} per run (peak F_n and onset signed: surrogate \u2212 full model):", per_run(reports[m])]
    if any(r.get("scaled") for r in reports.values()):
        parts += ["Scaled materials, worst / mean over the runs, % of the full model's range:",
                  scaled_summary(reports)]
        for m in scaled_materials:
            parts += [f"{m} per run (F_n / F_t RMS % of range, corrected \u2192 linear):",
                      scaled_per_run(reports[m])]
    print("\n\n".join(parts))


if __name__ == "__main__":
    main()
