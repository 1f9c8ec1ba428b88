//! Diagnostic: why the finite-strain slab's nucleation force needs tall
//! elements near the wire and a criterion over a surface cell
//! (docs/seed001.md, "Mesh").
//!
//! `cargo run --release -p shearcut-sim --example seed001_mesh_study`
//!
//! 1. Pressing (θ = 0°, 6 element rows per R): nucleation depth and force
//!    against the columns per row (`column_refinement` 1 to 4), and with 12
//!    rows per R and square elements: the column spacing sets the answer.
//! 2. Slicing (θ = 75°): nucleation force against the rows per R (6, 8, 10,
//!    three columns per row) for a surface cell of 0.05R (nearly a point)
//!    and of R/4 (the default): the small cell's answer keeps moving with
//!    the rows, the default's settles.

use shearcut_sim::finite_strain::{WireSlab, WireSlabSettings};

fn nucleation(settings: &WireSlabSettings, angle_deg: f64) -> String {
    let mut slab = WireSlab::new(settings).expect("valid settings");
    let run = slab
        .indent(angle_deg.to_radians())
        .expect("the run converges");
    match run.nucleation {
        Some(n) => format!(
            "{:>6} unknowns: d = {:.4} mm, F_n = {:.4} N, F_t = {:.4} N",
            slab.unknowns(),
            n.depth * 1e3,
            n.force_normal,
            n.force_tangential
        ),
        None => "no nucleation".to_string(),
    }
}

fn main() {
    let base = WireSlabSettings::default();
    println!("pressing, theta = 0 deg:");
    for (rows, columns) in [(6, 1), (6, 2), (6, 3), (6, 4), (12, 1)] {
        let s = WireSlabSettings {
            elements_per_radius: rows,
            column_refinement: columns,
            ..base
        };
        println!(
            "  {rows:>2} rows x {:>2} columns per R: {}",
            rows * columns,
            nucleation(&s, 0.0)
        );
    }
    println!("slicing, theta = 75 deg:");
    for cell in [0.05, 0.25] {
        for rows in [6, 8, 10] {
            let s = WireSlabSettings {
                elements_per_radius: rows,
                nucleation_cell_radii: cell,
                ..base
            };
            println!(
                "  cell {cell:.2} R, {rows:>2} rows per R: {}",
                nucleation(&s, 75.0)
            );
        }
    }
}
