//! # 01: the slicing toughness (seed 000 eq. 6) and one cross-section cut
//!
//! Shows the two layers of the cutting model:
//!
//! 1. the closed-form toughness ratio r(ξ, ν) = R_c^s/R_c of seed 000 eq. 6
//!    for potato (ν = 0.4): slicing (ξ > 0) lowers the toughness the crack
//!    has to overcome, down to a minimum near ξ ≈ 1.4;
//! 2. one 2D cross section (a 30 mm wide, 25 mm tall potato cuboid, Table I)
//!    cut 20 mm deep by a straight edge moving at ξ = 0.75: the FEM section
//!    model with the seed's energy balance (eq. 1), which is what the plant
//!    runs per edge segment.
//!
//! Prints a table of r(ξ, 0.4), then the cut every 2 mm of knife travel
//! (crack depth, forces per unit length of edge: a sawtooth, since the
//! crack advances in energy-balanced jumps) and its energy split, whose
//! balance knife = fracture + strain energy + friction closes to
//! round-off. The fracture work is r·R_c = 93 N/m per unit of cut depth;
//! the friction of the blade's wedge faces adds more than that again.
//!
//! ```sh
//! cargo run --release --example 01_toughness_and_section
//! ```

use shearcut_sim::{
    CrossSection, KnifePreset, MaterialPreset, SectionError, SectionGeometry, SectionSettings,
    StepStatus, WorkSplit, toughness_ratio,
};

/// Slice-push ratio of the cut, ξ = tangential / normal knife travel.
const XI: f64 = 0.75;
/// Depth of the cut below the section's top, m.
const DEPTH: f64 = 0.02;
/// Normal knife travel per model step, m (`[motion] step`'s default).
const STEP: f64 = 1e-5;

fn main() -> Result<(), SectionError> {
    let potato = MaterialPreset::PotatoCuboid.material();
    println!("Seed 000 eq. 6, potato (nu = {}):", potato.poisson_ratio);
    println!("   xi   r(xi, nu) = R_c^s / R_c");
    for xi in [0.0, 0.33, 0.75, 1.0, 1.8, 3.0] {
        println!(
            "{xi:5.2}   {:.4}",
            toughness_ratio(xi, potato.poisson_ratio)
        );
    }

    let (split, samples) = cut(XI, DEPTH)?;
    println!(
        "\nOne cross section, 30 x 25 mm potato cuboid, straight edge, xi = {XI}, {} mm deep:",
        DEPTH * 1e3
    );
    println!("  knife (mm)  crack depth (mm)  F_n (N/m)  F_t (N/m)");
    for s in &samples {
        println!(
            "{:11.2} {:17.2} {:10.1} {:10.1}",
            s.knife_displacement * 1e3,
            s.crack_depth * 1e3,
            s.force_vertical,
            s.force_tangential,
        );
    }
    let r = toughness_ratio(XI, potato.poisson_ratio);
    println!(
        "r(xi, nu) * R_c = {:.1} N/m: fracture work per unit cut depth",
        r * potato.fracture_toughness
    );
    println!(
        "work per length of edge (J/m): knife {:.3} = fracture {:.3} + strain energy {:.3} + friction {:.3}",
        split.knife, split.fracture, split.strain_energy, split.friction
    );
    Ok(())
}

/// Cuts the potato section at `xi` until its crack is `depth` deep (or the
/// section is cut through) and returns the energy split and the state every
/// 2 mm of knife travel.
fn cut(xi: f64, depth: f64) -> Result<(WorkSplit, Vec<shearcut_sim::SectionStep>), SectionError> {
    let potato = MaterialPreset::PotatoCuboid.material();
    let blade = KnifePreset::Straight.settings().blade;
    let geometry = SectionGeometry::rectangle(0.03, 0.025)?;
    let mut section = CrossSection::new(&geometry, &potato, &blade, &SectionSettings::default())?;
    let mut samples = Vec::new();
    let mut next_sample = 0.0;
    loop {
        let s = section.advance(STEP, xi * STEP)?;
        if s.knife_displacement >= next_sample - 1e-12 {
            samples.push(s);
            next_sample += 2e-3;
        }
        if s.crack_depth >= depth || s.status == StepStatus::CutThrough {
            samples.push(s);
            return Ok((s.work, samples));
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The example's claims: eq. 6's hand value, a cut that reaches its
    /// depth, and an energy balance closed to 1e-9 of the knife's work (the
    /// section model's own guarantee, `WorkSplit`).
    #[test]
    fn the_example_cuts_and_balances() {
        assert!((toughness_ratio(0.75, 0.4) - 0.6224).abs() < 5e-5);
        let (w, samples) = cut(XI, DEPTH).unwrap();
        assert!(samples.last().unwrap().crack_depth >= DEPTH);
        let balance = w.fracture + w.strain_energy + w.friction + w.unstable - w.knife;
        assert!(balance.abs() <= 1e-9 * w.knife, "{w:?}");
    }

    /// The example runs as a user runs it (`cargo run --example`): `main`
    /// prints its output and succeeds.
    #[test]
    fn the_example_runs() {
        main().unwrap();
    }
}
