//! Cost of seed 001's six-angle sweep (θ = 0, 15, …, 75°) on the finite-strain
//! wire–slab model at the default mesh, Newton's residual history in one load
//! step, and the mesh convergence of the nucleation forces.
//!
//! Run: `cargo bench -p shearcut-sim --bench finite_strain` (environment:
//! `SWEEP_SAMPLES`, default 3; `MESH_LEVELS`, elements per radius, default
//! "4,6,8,10"). Figures are in docs/seed001.md.

// A benchmark measures wall time by design.
#![allow(clippy::disallowed_methods)]

use std::time::Instant;

use shearcut_sim::finite_strain::{WireSlab, WireSlabSettings, sweep_angles};

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
    for _ in 0..samples {
        let t = Instant::now();
        let sweep = sweep_angles(&settings, &ANGLES, 2).unwrap();
        times.push(t.elapsed().as_secs_f64());
        std::hint::black_box(sweep);
    }
    times.sort_by(f64::total_cmp);
    println!(
        "six-angle sweep, 2 threads, {samples} samples: median {:.1} s, p99 {:.1} s, max {:.1} s",
        percentile(&times, 0.5),
        percentile(&times, 0.99),
        times[times.len() - 1]
    );

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
    println!("mesh convergence of nucleation (elements per radius: d_nuc mm, F_n N, F_t N):");
    for angle in [0.0f64, 45.0, 75.0] {
        for &epr in &levels {
            let s = WireSlabSettings {
                elements_per_radius: epr,
                ..settings
            };
            let mut slab = WireSlab::new(&s).unwrap();
            let run = slab.indent(angle.to_radians()).unwrap();
            match run.nucleation {
                Some(n) => println!(
                    "  θ = {angle:>2}°, {epr:>2}/R ({} unknowns): {:.4} mm, {:.4} N, {:.4} N",
                    slab.unknowns(),
                    n.depth * 1e3,
                    n.force_normal,
                    n.force_tangential
                ),
                None => println!("  θ = {angle:>2}°, {epr:>2}/R: no nucleation"),
            }
        }
    }
}
