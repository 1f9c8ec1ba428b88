//! Beyond the range of E/R_c they were fitted over (ρ = S/T in [0.5, 2],
//! the sweeps at E × 0.5 and × 2), the ratio corrections continue along
//! their tangents at the range's ends instead of along their quadratics:
//! the parts at ρ = 7 are those at ρ = 2 plus ln(7/2) times the ℓ-slopes
//! there, and the slopes stay those at ρ = 2 (down to the face reaction's
//! floor N ≥ 0, which the refitted potato cuboid's tangent reaches at ρ = 7
//! on this state).

use std::path::PathBuf;

use shearcut_sim::surrogate::{CutState, ScaleFactors, ScaledParts, Surrogate};

#[test]
fn beyond_the_fitted_ratios_the_corrections_continue_along_their_tangents() {
    let path = PathBuf::from(env!("CARGO_MANIFEST_DIR"))
        .join("../config/surrogates/potato-cuboid-straight.toml");
    let s = Surrogate::from_path(&path).unwrap();
    let state = CutState {
        depth: 0.012,
        height: 0.025,
        half_width: 0.015,
        fractured: true,
        travel_since_fracture: 0.008,
    };
    let at = |toughness: f64, stiffness: f64| {
        let scale = ScaleFactors {
            toughness,
            stiffness,
            friction: 1.0,
        };
        let o = s.evaluate(0.7, &state, &scale);
        [o.force_normal_parts, o.force_tangential_parts]
    };
    let parts = |p: &ScaledParts| [p.by_toughness, p.by_stiffness, p.by_friction_stiffness];
    let slopes = |p: &ScaledParts| {
        [
            p.by_toughness_log_ratio_slope,
            p.by_stiffness_log_ratio_slope,
            p.by_friction_stiffness_log_ratio_slope,
        ]
    };
    // (beyond, the range's end, ℓ beyond it).
    let seven = 3.5f64.ln();
    for (beyond, edge, excess) in [
        ((0.2, 1.4), (0.2, 0.4), seven),
        ((1.4, 0.2), (0.4, 0.2), -seven),
    ] {
        for (p, q) in at(beyond.0, beyond.1).iter().zip(&at(edge.0, edge.1)) {
            // The faces' reaction has a floor: where its tangent runs below
            // zero, N and its ℓ-slope are 0 (`Surrogate::evaluate`), and so
            // are the friction parts (index 2).
            let floor = parts(q)[2] + excess * slopes(q)[2] <= 0.0;
            let kept = if floor {
                assert_eq!(parts(p)[2], 0.0, "{beyond:?}");
                assert_eq!(slopes(p)[2], 0.0, "{beyond:?}");
                2
            } else {
                3
            };
            assert_eq!(slopes(p)[..kept], slopes(q)[..kept], "{beyond:?}");
            for k in 0..kept {
                let expected = parts(q)[k] + excess * slopes(q)[k];
                assert!(
                    (parts(p)[k] - expected).abs() <= 1e-9 * expected.abs().max(1.0),
                    "{beyond:?}: part {k} {} against {expected}",
                    parts(p)[k]
                );
            }
        }
        let slope = at(edge.0, edge.1)[0].by_stiffness_log_ratio_slope;
        assert!(slope != 0.0, "the corrections act near the range's end");
    }
}
