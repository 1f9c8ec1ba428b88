//! Beyond the section sizes they were fitted over (heights 20–45 mm, half
//! widths 10–30 mm) the shipped surrogates extrapolate, as the eggplant's
//! equivalent section (91.8 mm half width) and any user's larger or
//! narrower object make them: there every output must stay finite, so that
//! the MPC's program is well posed. The fitted onset stiffness, linear in
//! (λ_H, λ_w, H/w), reaches zero in tall narrow sections (H/w ≳ 10) and in
//! sections of metres; before it was held at the stiffness of an onset at
//! the section's height (`Surrogate::evaluate`), an 80 mm tall section of
//! 5 mm half width gave infinite forces after fracture.

use std::path::PathBuf;

use proptest::prelude::*;
use shearcut_sim::surrogate::{CutState, ScaleFactors, Surrogate};

/// Every shipped surrogate file: the eight built into `shearcut` and the
/// whole eggplant's fit over wider sections (`eggplant-whole-chef-wide`).
fn shipped() -> Vec<Surrogate> {
    let dir = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../config/surrogates");
    let mut files: Vec<PathBuf> = std::fs::read_dir(&dir)
        .unwrap()
        .map(|e| e.unwrap().path())
        .filter(|p| {
            p.extension().is_some_and(|e| e == "toml")
                && !p.to_string_lossy().ends_with(".accuracy.toml")
        })
        .collect();
    files.sort();
    assert_eq!(files.len(), 9, "{files:?}");
    files
        .iter()
        .map(|p| Surrogate::from_path(p).unwrap())
        .collect()
}

/// Whether every number of an output (its Debug form lists them all) is
/// finite.
fn all_finite(o: &impl std::fmt::Debug) -> bool {
    let text = format!("{o:?}");
    !text.contains("NaN") && !text.contains("inf")
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(512))]

    #[test]
    fn every_output_is_finite_at_sizes_from_a_millimetre_to_ten_metres(
        log_height in (1e-3f64).ln()..(10.0f64).ln(),
        log_half_width in (1e-3f64).ln()..(10.0f64).ln(),
        depth_ratio in 0.0f64..1.0,
        travel_ratio in 0.0f64..1.0,
        fractured in any::<bool>(),
        xi in 0.0f64..3.0,
        toughness in 0.5f64..2.0,
        stiffness in 0.5f64..2.0,
        friction in 0.0f64..2.0,
    ) {
        let (height, half_width) = (log_height.exp(), log_half_width.exp());
        let depth = depth_ratio * height;
        let state = CutState {
            depth,
            height,
            half_width,
            fractured,
            travel_since_fracture: if fractured { travel_ratio * depth } else { 0.0 },
        };
        let scale = ScaleFactors { toughness, stiffness, friction };
        for s in shipped() {
            let o = s.evaluate(xi, &state, &scale);
            prop_assert!(
                all_finite(&o),
                "{}-{}: {state:?} xi {xi} {scale:?}: {o:?}",
                s.material_name,
                s.knife_name
            );
            // The nominal onset depth is at most the section's height.
            let onset_bound = toughness / stiffness * height.max(s.blade.edge_width);
            prop_assert!(
                o.fracture_onset_depth <= onset_bound * (1.0 + 1e-12),
                "{}: onset {} beyond {onset_bound}",
                s.material_name,
                o.fracture_onset_depth
            );
        }
    }
}

#[test]
fn a_tall_narrow_section_beyond_the_fit_has_finite_forces() {
    // The case that was infinite: 80 mm tall, 5 mm half width, right at
    // the first fracture.
    let state = CutState {
        depth: 0.0,
        height: 0.08,
        half_width: 0.005,
        fractured: true,
        travel_since_fracture: 0.0,
    };
    for s in shipped() {
        for xi in [0.0, 0.5, 1.0, 2.4] {
            let o = s.evaluate(xi, &state, &ScaleFactors::default());
            assert!(all_finite(&o), "{} xi {xi}: {o:?}", s.material_name);
            assert!(o.fracture_onset_depth <= 0.08 * (1.0 + 1e-12));
        }
    }
}

#[test]
fn the_fit_range_covers_its_own_sizes_and_no_others() {
    let s = shipped().remove(0);
    let r = s.range;
    assert!(r.covers_section(r.height[0], r.half_width[1]));
    assert!(r.covers_section(0.5 * (r.height[0] + r.height[1]), r.half_width[0]));
    assert!(!r.covers_section(1.01 * r.height[1], r.half_width[0]));
    assert!(!r.covers_section(r.height[0], 0.99 * r.half_width[0]));
    // The whole eggplant's equivalent section (91.8 mm half width) is beyond.
    assert!(!r.covers_section(0.035, 0.0918));
}
