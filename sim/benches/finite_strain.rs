//! Cost of seed 001's six-angle sweep (θ = 0, 15, …, 75°) on the finite-strain
//! wire–slab model at the default mesh, Newton's residual history in one load
//! step, and the mesh convergence of the nucleation forces at every angle.
//!
//! It also prints the nucleation envelope of the default mesh's sweep,
//! extended beyond its sliding limit by the slab with friction coefficient 3
//! at θ = 75° and 85°: the table of [`NucleationEnvelope::SEED_GEL`].
//!
//! Run: `cargo bench -p shearcut-sim --bench finite_strain` (environment:
//! `SWEEP_SAMPLES`, default 3; `MESH_LEVELS`, element rows per radius,
//! default "4,6,8,10", empty for none). Figures are in docs/seed001.md.

// A benchmark measures wall time by design.
#![allow(clippy::disallowed_methods)]

use std::time::Instant;

use shearcut_sim::finite_strain::{NucleationEnvelope, WireSlab, WireSlabSettings, sweep_angles};

const ANGLES: [f64; 6] = [0.0, 15.0, 30.0, 45.0, 60.0, 75.0];

fn percentile(sorted: &[f64], p: f64) -> f64 {
    let i = ((sorted.len() as f64 - 1.0) * p).round() as usize;
    sorted[i]
}

fn main() {
    let samples: usize = std::env::var("SWEEP_SAMPLES")
        .ok()
        .and_then(|s| s.parse().ok())
        .unwrap_or(3);
    let settings = WireSlabSettings::default();
    let slab = WireSlab::new(&settings).unwrap();
    println!(
        "default mesh: {} elements, {} unknowns",
        slab.element_count(),
        slab.unknowns()
    );
    let mut times = Vec::new();
    let mut envelope = None;
    for _ in 0..samples {
        let t = Instant::now();
        let sweep = sweep_angles(&settings, &ANGLES, 2).unwrap();
        times.push(t.elapsed().as_secs_f64());
        envelope = NucleationEnvelope::from_runs(&settings, &sweep.runs);
        std::hint::black_box(sweep);
    }
    times.sort_by(f64::total_cmp);
    println!(
        "six-angle sweep, 2 threads, {samples} samples: median {:.1} s, p99 {:.1} s, max {:.1} s",
        percentile(&times, 0.5),
        percentile(&times, 0.99),
        times[times.len() - 1]
    );

    // Beyond the default slab's sliding limit (ψ ≈ 47°): the slab with
    // friction coefficient 3 at θ = 75° and 85°.
    let sliding = WireSlabSettings {
        friction_coefficient: 3.0,
        ..settings
    };
    let beyond = sweep_angles(&sliding, &[75.0, 85.0], 2).unwrap();
    if let Some(e) = envelope.and_then(|e| e.extended_by(&sliding, &beyond.runs)) {
        println!(
            "nucleation envelope (f_n, f_t)/(μR) at θ = 0, 15, …, 75° and, friction coefficient 3, 75°, 85°: {:?}",
            &e.points[..e.len]
        );
    }

    let mut slab = WireSlab::new(&settings).unwrap();
    slab.reset(45f64.to_radians());
    slab.advance_to(0.4e-3).unwrap();
    println!(
        "Newton residuals (N/m) of the load step to d = 0.4 mm at θ = 45°: {:?}",
        slab.last_newton().residuals
    );

    let levels: Vec<usize> = std::env::var("MESH_LEVELS")
        .unwrap_or_else(|_| "4,6,8,10".to_string())
        .split(',')
        .filter_map(|s| s.trim().parse().ok())
        .collect();
    println!(
        "mesh convergence of nucleation (rows per radius, {} columns per row; d_nuc mm, F_n N, F_t N):",
        settings.column_refinement
    );
    let mut finest: Vec<Vec<(f64, f64)>> = Vec::new();
    for &epr in &levels {
        let s = WireSlabSettings {
            elements_per_radius: epr,
            ..settings
        };
        let unknowns = WireSlab::new(&s).unwrap().unknowns();
        let sweep = sweep_angles(&s, &ANGLES, 2).unwrap();
        let mut forces = Vec::new();
        for run in &sweep.runs {
            let angle = run.angle.to_degrees();
            match run.nucleation {
                Some(n) => {
                    println!(
                        "  θ = {angle:>2.0}°, {epr:>2}/R ({unknowns} unknowns): {:.4} mm, {:.4} N, {:.4} N",
                        n.depth * 1e3,
                        n.force_normal,
                        n.force_tangential
                    );
                    forces.push((n.force_normal, n.force_tangential));
                }
                None => {
                    println!("  θ = {angle:>2.0}°, {epr:>2}/R: no nucleation");
                    forces.push((f64::NAN, f64::NAN));
                }
            }
        }
        finest.push(forces);
    }
    if let [.., coarse, fine] = finest.as_slice() {
        println!("change between the two finest meshes:");
        for ((a, b), angle) in coarse.iter().zip(fine).zip(ANGLES) {
            let rel = |x: f64, y: f64| {
                if x == 0.0 && y == 0.0 {
                    0.0
                } else {
                    100.0 * (y - x) / x
                }
            };
            println!(
                "  θ = {angle:>2.0}°: F_n {:+.1} %, F_t {:+.1} %",
                rel(a.0, b.0),
                rel(a.1, b.1)
            );
        }
    }
}
