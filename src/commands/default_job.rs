//! What `shearcut` does with no subcommand: the main job on the built-in
//! default scenario.
//!
//! Until the cross-section model lands, the main job evaluates the slice-push
//! toughness law for the default scenario's material and slice-push ratios and
//! draws seed 000 Fig. 3 into the scenario's result directory.

use shearcut_sim::mechanics::{force_ratio, toughness_ratio};

use crate::commands::toughness::write_fig3;
use crate::error::RunError;
use crate::run_dir;
use crate::scenario::{DEFAULT_SCENARIO, Scenario};

/// Runs the main job on the default scenario.
pub fn run() -> Result<(), RunError> {
    let (name, text) = DEFAULT_SCENARIO;
    let s = Scenario::parse(text, name, name)?;
    let m = &s.material;
    println!(
        "shearcut: default scenario `{}` — {}",
        s.name, s.description
    );
    println!(
        "material: E = {} Pa, nu = {}, mu = {}, R_c = {} N/m, R'_c = {} N/m",
        m.youngs_modulus,
        m.poisson_ratio,
        m.friction_coefficient,
        m.fracture_toughness,
        m.initial_fracture_toughness
    );
    println!("   xi   alpha(deg)  r(xi,nu)  R_c^s (N/m)  F_t/F_n");
    for &xi in &s.motion.slice_push_ratios {
        let r = toughness_ratio(xi, m.poisson_ratio);
        println!(
            "{xi:>5.2}  {:>10.1}  {r:>8.4}  {:>11.1}  {:>7.4}",
            xi.atan().to_degrees(),
            r * m.fracture_toughness,
            force_ratio(xi, m.poisson_ratio)
        );
    }
    let dir = run_dir::create(&s.name, None)?;
    let plot = dir.join("toughness_ratio.svg");
    let csv = write_fig3(&plot)?;
    println!("wrote {} and {}", plot.display(), csv.display());
    Ok(())
}
