//! A skin layer (`Material::skin_thickness`): the crack pays R'_c within the
//! skin and R_c below it, so the fracture energy per unit length of a cut to
//! depth a is r·(R'_c·t + R_c·(a − t)) (seed 000 Table I "with skin" rows;
//! eq. 1 with the layered toughness), to the section's fracture tolerance.

use shearcut_sim::{
    BladeSection, CrossSection, Material, MaterialPreset, SectionGeometry, SectionSettings,
    toughness_ratio,
};

/// Presses an eggplant-with-skin rectangle until the crack is `depth` deep
/// (after a restart at `start_depth`) and returns (fracture energy, final
/// crack depth, the depth it started from, the toughness ratio r(0, ν)).
fn press(skin: Option<f64>, start_depth: f64, depth: f64) -> (f64, f64, f64, f64) {
    let material = Material {
        skin_thickness: skin,
        ..MaterialPreset::EggplantWhole.material()
    };
    let geometry = SectionGeometry::rectangle(0.03, 0.02).unwrap();
    let settings = SectionSettings {
        row_spacing: 5e-4,
        ..SectionSettings::default()
    };
    let mut s =
        CrossSection::new(&geometry, &material, &BladeSection::default(), &settings).unwrap();
    if start_depth > 0.0 {
        // A successor deep in the cut, its first-fracture flag not set.
        s.restart_with_crack(start_depth, false);
    }
    let a0 = s.state().crack_depth;
    for _ in 0..20_000 {
        let st = s.advance(6.25e-6, 0.0).unwrap();
        if st.crack_depth >= depth {
            break;
        }
    }
    let st = *s.state();
    assert!(st.crack_depth >= depth, "reached {}", st.crack_depth);
    assert!(!s.is_cut_through());
    let w = st.work;
    if start_depth == 0.0 {
        // The balance closes: knife = fracture + strain + friction +
        // unstable. (A restart opens the crack onto the blade and restarts
        // the energies at zero, so there the stored energy starts nonzero.)
        let closure = w.knife - (w.fracture + w.strain_energy + w.friction + w.unstable);
        assert!(closure.abs() <= 1e-6 * w.knife, "balance off by {closure}");
    }
    (
        w.fracture,
        st.crack_depth,
        a0,
        toughness_ratio(0.0, material.poisson_ratio),
    )
}

/// The section's fracture tolerance: |R − r·R_c^s| ≤ tol·r·R_c^s per step
/// (`bisection_tolerance`, 1e-7), so the sum is within 1e-7 of the layered
/// integral; 1e-6 leaves room for the sums' round-off.
const REL: f64 = 1e-6;

#[test]
fn thin_skin_costs_skin_toughness_then_interior_toughness() {
    let t = 1e-3;
    let (fracture, a, a0, r) = press(Some(t), 0.0, 6e-3);
    assert_eq!(a0, 0.0);
    let m = MaterialPreset::EggplantWhole.material();
    let expect = r * (m.initial_fracture_toughness * t + m.fracture_toughness * (a - t));
    assert!(
        (fracture - expect).abs() <= REL * expect,
        "fracture {fracture} vs {expect} J/m (depth {a})"
    );
    // Not the first-fracture rule: that would pay R_c below the first
    // extension, far less than R'_c over a whole millimetre of skin.
    let legacy_upper = r * (m.initial_fracture_toughness * 2e-4 + m.fracture_toughness * a);
    assert!(fracture > legacy_upper, "{fracture} vs {legacy_upper}");
}

#[test]
fn zero_skin_is_interior_toughness_throughout() {
    let (fracture, a, _, r) = press(Some(0.0), 0.0, 5e-3);
    let expect = r * MaterialPreset::EggplantWhole.material().fracture_toughness * a;
    assert!(
        (fracture - expect).abs() <= REL * expect,
        "fracture {fracture} vs {expect} J/m (depth {a})"
    );
}

#[test]
fn a_section_starting_below_the_skin_cuts_the_interior() {
    // A moving section's successor whose crack starts 4 mm deep, below a
    // 1 mm skin, pays R_c only, although its first-fracture flag is unset.
    let (fracture, a, a0, r) = press(Some(1e-3), 4e-3, 8e-3);
    assert!((a0 - 4e-3).abs() < 1e-12);
    let expect = r * MaterialPreset::EggplantWhole.material().fracture_toughness * (a - a0);
    assert!(
        (fracture - expect).abs() <= REL * expect,
        "fracture {fracture} vs {expect} J/m (from {a0} to {a})"
    );
}
