//! Cost of building a cross section (`CrossSection::new`: mesh, assembly,
//! sparse factorisation and static condensation onto the cut line, the
//! last being nearly all of it) for the sections the closed loop
//! `loop-potato-whole` builds: the half potato (90 × 60 × 35 mm) cut by the
//! chef's knife, default section mesh (rows every 0.2 mm). The plant builds
//! one section per edge segment at start and one on its worker thread for
//! every re-choice of a segment's section, so this is the cost of a plant
//! build divided by its segments and of every rebuild.
//!
//! Prints, for sections across the potato at several positions along its
//! length (vertical planes) and a 30 × 30 mm rectangle (the `section`
//! bench's naive-step lower bound), the first build (cold: the mesh
//! topology's stiffness pattern and symbolic factorisation are computed)
//! and the median and worst of the repeated ones (warm: taken from the
//! section's factor cache, bit-identical), then cold builds of rectangles
//! of distinct heights (a new topology each); with each series the
//! process's CPU time per build (from `/proc/self/stat`, 10 ms ticks), which
//! the load of a shared machine inflates much less than the wall time.
//!
//! Run: `cargo bench -p shearcut-sim --bench section_condense`.
//!
//! Figures (median of 15 builds, wall clock, 2 shared cores under a load
//! of 10–14, so several times slower than on a quiet machine; the ratios
//! are the point):
//!
//! | section (rows)              | unit solves (cf8fe01) | partial factorisation |
//! |-----------------------------|-----------------------|-----------------------|
//! | potato, z = 45 mm (175)     | 700 ms                | 113 ms                |
//! | potato, z = 20 mm (146)     | 389 ms                | 71 ms                 |
//! | potato, z = 10 mm (110)     | 210 ms                | 39 ms                 |
//! | 30 × 30 mm rectangle (150)  | 321 ms                | 59 ms                 |
//!
//! CPU time of the whole bench (60 builds) with the partial factorisation:
//! 1.40 s, i.e. 23 ms per build on average.
//!
//! With the factor cache (pattern, summation order and symbolic
//! factorisation reused per topology, assembly straight into the
//! factorisation's order, scratch memory kept), CPU ms per build, range
//! of 3 runs each of this bench on the code before (a47ccc0) and after,
//! interleaved, load 11–14:
//!
//! | series (rows)                        | before    | after, warm | after, cold |
//! |--------------------------------------|-----------|-------------|-------------|
//! | potato, z = 45 mm (175)              | 36–43     | 29–30       |             |
//! | potato, z = 20 mm (146)              | 24–27     | 18–20       |             |
//! | potato, z = 10 mm (110)              | 14–15     | 10–11       |             |
//! | 30 × 30 mm rectangle (150)           | 20–21     | 15–16       |             |
//! | 30 mm rectangles, 130–144 rows       | 18–25     |             | 19–20       |
//!
//! A warm build is about 1.3× cheaper, a cold one about the same as before
//! (the numeric factorisation, unchanged to keep results bit-identical, is
//! most of it). Whole bench (75 builds): 1.66–1.90 s CPU before, 1.39–1.48 s
//! after.

//!
//! Nested dissection of the node grid (near-square blocks instead of
//! three-row leaves between whole-row separators) and only the entries of
//! C and C_z the solves read (a band of rows at most one apart, and C's top
//! row) instead of the whole inverses: new rounding (the matrices agree
//! with unit solves to 1e-13, the closed loop and Fig. 7 to 1e-11), the
//! surrogates refitted. Flops of the in-plane partial factorisation of the
//! 175-row potato section 225 → 130 MFlop, antiplane 23 → 13, the dense
//! work after it ≈ 89 → 55 MFlop. CPU ms per build, two interleaved runs
//! of this bench on the code before (a2c1077) and after, load 5–7:
//!
//! | series (rows)                        | before     | after      |
//! |--------------------------------------|------------|------------|
//! | potato, z = 45 mm (175)              | 25.7, 29.3 | 17.9, 15.7 |
//! | potato, z = 20 mm (146)              | 16.4, 16.4 | 11.4, 11.4 |
//! | potato, z = 10 mm (110)              | 9.3, 9.3   | 5.7, 6.4   |
//! | 30 × 30 mm rectangle (150)           | 14.3, 13.6 | 10.0, 9.3  |
//! | 30 mm rectangles, 130–144 rows, cold | 17.3, 17.3 | 13.3, 13.3 |
//!
//! About 1.5× where the shape is cached and 1.3× for a new shape (whose
//! stiffness pattern and symbolic factorisation are computed: a larger
//! share now). Most of what is left is dense and inherent to condensing
//! onto the 525 kept in-plane DOFs: the trailing block's Cholesky
//! (≈ 48 MFlop), L_YY⁻¹ (≈ 14) and Eᵀ = L_XY L_YY⁻¹ (≈ 21), and for the
//! antiplane problem the 350-DOF block and its inverse (≈ 28).
//!
//! Where a whole run's section work goes (issue #8; counters and timers
//! added for the measurement only, not kept). The default closed loop
//! (`shearcut run loop-potato-whole --controller mpc --transport inproc`)
//! builds about 345 sections, of which 295 are taken; the others: the 20
//! that `Plant::new` builds for the planned direction (the MPC slices along
//! other directions: 15 were re-ordered and 5 cancelled on the way; built
//! anyway so that a real-time loop moving as planned never waits), about
//! 23 finished successors superseded (7 of them at the stroke's reversal),
//! about 17 successors of the last re-choices left when the run ends, and
//! 3–5 superseded while being built. 70 % of the builds (242 of 346) met
//! an in-plane topology the factor cache did not hold: the run has 114
//! distinct topologies and looks a pattern up 690 times, of which 475
//! missed with room for 32 patterns; an LRU replay of the lookups gives
//! 386 misses for 64 patterns, 265 for 128 (now the capacity) and 228 (the
//! first uses) for 256. Share of the build time, summed over a run's builds
//! (wall time on the worker threads at a load of 3–5):
//!
//! | part of `CrossSection::new`                               | share |
//! |-----------------------------------------------------------|-------|
//! | in-plane numeric partial factorisation (faer supernodal)  | 44 %  |
//! | in-plane symbolic analysis of a new topology              | 18 %  |
//! | antiplane (assembly, symbolic if new, factorisation)      | 19 %  |
//! | dense work after it (L_bb read-out, L_YY⁻¹, bands, Eᵀ, A) | 9 %   |
//! | in-plane assembly                                         | 6 %   |
//! | antiplane L⁻¹ and band                                    | 3 %   |
//! | mesh                                                      | 1 %   |
//!
//! Of a new topology's symbolic analysis, the nested dissection is
//! negligible; the pattern's counting sort and per-column sorts take about
//! 35 %, faer's symbolic Cholesky 40 %, the permuted pattern 20 %. Across
//! the process (perf, 2 kHz sampling), the worker threads take 79 % of the
//! CPU and the plant's own thread 21 %, most of it in the condensed-line
//! solves of the ticks (`solve_released`).
//!
//! With 128 cached patterns (bit-identical results; the run's peak RSS
//! 158–165 → 271–287 MB) and the trailing factor's and L⁻¹'s scratch no
//! longer zeroed where only lower triangles are read, the default run's
//! CPU time, three interleaved runs each of the code before (507ff9f) and
//! after, load 4.2–4.9: user 7.21, 7.40, 7.24 s → 6.52, 6.72, 6.58 s (sys
//! 0.10–0.17 → 0.21–0.25 s); wall 7.5–9.3 s → 7.0–7.7 s (noisy). This
//! bench repeats few topologies, so its CPU per build is unchanged within
//! its 10 ms ticks' resolution (175 rows 16.4 ms, 146 rows 10.7 ms, 110
//! rows 5.7–6.4 ms, rectangle 9.3–10.0 ms, new topologies 13.3–14.0 ms,
//! two interleaved runs each at a load of 4.8).

// A benchmark measures wall time by design.
#![allow(clippy::disallowed_methods)]

use std::hint::black_box;
use std::time::Instant;

use nalgebra::Vector3;
use shearcut_sim::geometry::SectionPlane;
use shearcut_sim::knife_plane::section_shape::section_geometry;
use shearcut_sim::{
    CrossSection, Knife, KnifePreset, MaterialPreset, ObjectShape, SectionGeometry, SectionSettings,
};

const REPEATS: usize = 15;

fn main() {
    let material = MaterialPreset::PotatoWhole.material();
    let knife = Knife::new(&KnifePreset::Chef.settings()).unwrap();
    let settings = SectionSettings::default();
    let object = ObjectShape::HalfPotato {
        length: 0.09,
        width: 0.06,
        height: 0.035,
    }
    .mesh()
    .unwrap();
    let mut cases: Vec<(String, SectionGeometry)> = Vec::new();
    // Vertical section planes at z along the potato's length (0..0.09 m).
    for z in [0.045, 0.02, 0.01] {
        let plane = SectionPlane::normal_to_segment(Vector3::new(0.0, 0.01, z), Vector3::y());
        let polygon = plane.section(&object).expect("the plane cuts the potato");
        let height = polygon.bounds().1.y;
        // The plant's default rim fraction (PlantSettings::rim_fraction).
        let geometry = section_geometry(&polygon, 0.05 * height).unwrap();
        cases.push((
            format!(
                "half potato at z = {:.0} mm ({:.1} mm high, {:.1} mm half width)",
                z * 1e3,
                geometry.height_at_cut() * 1e3,
                geometry.half_width() * 1e3
            ),
            geometry,
        ));
    }
    cases.push((
        "30 x 30 mm rectangle".to_string(),
        SectionGeometry::rectangle(0.03, 0.03).unwrap(),
    ));
    let build = |geometry: &SectionGeometry| {
        let t = Instant::now();
        black_box(CrossSection::new(geometry, &material, knife.blade(), &settings).unwrap());
        t.elapsed().as_secs_f64() * 1e3
    };
    let median = |mut v: Vec<f64>| {
        v.sort_by(f64::total_cmp);
        (v[v.len() / 2], v[v.len() - 1])
    };
    // The first build of a mesh topology computes the stiffness pattern and
    // the symbolic factorisation (cold); the others take them from the
    // factor cache (warm), as the plant's rebuilds of a topology built
    // before do. Results are bit-identical either way. Wall time suffers
    // from the load of a shared machine; the process's CPU time per build
    // (mean over the series) much less.
    for (name, geometry) in &cases {
        let rows = (geometry.height_at_cut() / settings.row_spacing).round();
        let cold = build(geometry);
        let cpu = cpu_seconds();
        let (warm, worst) = median((1..REPEATS).map(|_| build(geometry)).collect());
        let cpu = per_build(cpu, REPEATS - 1);
        println!(
            "CrossSection::new, {name}, {rows} rows: first (cold) {cold:.2} ms, then median {warm:.2} ms, worst {worst:.2} ms, CPU {cpu} ({} builds)",
            REPEATS - 1
        );
    }
    // Cold builds: rectangles of distinct heights, so distinct topologies.
    let cpu = cpu_seconds();
    let (cold, worst) = median(
        (0..REPEATS)
            .map(|i| {
                let rows = 130 + i;
                let height = rows as f64 * settings.row_spacing;
                build(&SectionGeometry::rectangle(0.03, height).unwrap())
            })
            .collect(),
    );
    let cpu = per_build(cpu, REPEATS);
    println!(
        "CrossSection::new, 30 mm wide rectangles of 130..{} rows, each a new topology (cold): median {cold:.2} ms, worst {worst:.2} ms, CPU {cpu} ({REPEATS} builds)",
        130 + REPEATS - 1
    );
}

/// CPU time (user + system) of this process so far, s, from `/proc/self/stat`
/// (Linux; ticks of 1/100 s, the fixed USER_HZ of /proc), if readable.
fn cpu_seconds() -> Option<f64> {
    let stat = std::fs::read_to_string("/proc/self/stat").ok()?;
    // Fields after the command name (which ends with the last ')'):
    // state is field 3, utime and stime fields 14 and 15.
    let rest = &stat[stat.rfind(')')? + 2..];
    let fields: Vec<&str> = rest.split_whitespace().collect();
    let utime: f64 = fields.get(11)?.parse().ok()?;
    let stime: f64 = fields.get(12)?.parse().ok()?;
    Some((utime + stime) / 100.0)
}

/// Mean CPU time per build since `start` over `builds` builds, formatted.
fn per_build(start: Option<f64>, builds: usize) -> String {
    match (start, cpu_seconds()) {
        (Some(a), Some(b)) => format!("{:.1} ms/build", (b - a) * 1e3 / builds as f64),
        _ => "n/a".to_string(),
    }
}
