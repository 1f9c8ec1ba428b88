//! The stiffness-to-toughness ratio corrections (module `ratio`,
//! docs/surrogates.md "Structure"): at ρ = S/T = 1 the corrections drop
//! out bit for bit; the parts' ℓ-slopes (ℓ = ln ρ) and the
//! derivatives ∂/∂T, ∂/∂S built on them match central finite differences;
//! and the section model itself scales every force by k when E and R_c
//! (with R'_c) are both scaled by k, the dimensional argument for a
//! correction in ρ alone.

use std::path::PathBuf;

use shearcut_sim::surrogate::{
    CutState, RatioCorrection, ScaleFactors, ScaledParts, Surrogate, SurrogateOutput, SweepCase,
    SweepSettings, run_sweep, scaled_material,
};
use shearcut_sim::{KnifePreset, MaterialPreset};

include!("data/golden_grid.rs");

fn shipped(name: &str) -> Surrogate {
    let path =
        PathBuf::from(env!("CARGO_MANIFEST_DIR")).join(format!("../config/surrogates/{name}.toml"));
    Surrogate::from_path(&path).unwrap()
}

/// Shipped surrogates the bit-for-bit checks run on.
const GOLDEN: [&str; 4] = [
    "potato-cuboid-straight",
    "potato-whole-chef",
    "eggplant-whole-straight",
    "eggplant-cuboid-chef",
];

/// The corrections drop out at T = S whatever they are, to
/// the bit, in every output (the ℓ-slopes aside, which are the corrections'
/// own terms).
#[test]
fn at_unit_ratio_the_corrections_drop_out_bit_for_bit() {
    for name in GOLDEN {
        let s = shipped(name);
        let mut linear = s.clone();
        linear.ratio = RatioCorrection::default();
        let mut bent = s.clone();
        bent.ratio.face_reaction_linear = [0.37; 28];
        bent.ratio.face_reaction_quadratic = [-1.1; 28];
        bent.ratio.strain_energy_rate_linear = [2.5; 17];
        bent.ratio.strain_energy_rate_quadratic = [-0.8; 17];
        bent.ratio.face_reaction_slice_linear = [0.3, -0.2, 0.6];
        bent.ratio.face_reaction_slice_quadratic = [-0.1, 0.05, 0.2];
        bent.ratio.drag_linear = [0.4, -0.3, 0.2, 0.1];
        bent.ratio.drag_quadratic = [-0.2, 0.1, 0.3, -0.1];
        bent.ratio.catch_up_exponent = 0.8;
        for (xi, state, scale) in golden_grid() {
            let a = output_hash(FNV_START, &linear.evaluate(xi, &state, &scale));
            assert_eq!(a, output_hash(FNV_START, &s.evaluate(xi, &state, &scale)));
            assert_eq!(
                a,
                output_hash(FNV_START, &bent.evaluate(xi, &state, &scale))
            );
        }
    }
}

/// The shipped surrogate with test corrections of a realistic size where
/// its file has none (a format-3 file), so the slopes are exercised.
fn with_corrections(name: &str) -> Surrogate {
    let mut s = shipped(name);
    if s.ratio.is_zero() {
        let p = s.post_fracture;
        s.ratio.face_reaction_linear = p.face_reaction.map(|c| -0.2 * c);
        s.ratio.face_reaction_quadratic = p.face_reaction.map(|c| -0.05 * c);
        s.ratio.strain_energy_rate_linear = p.strain_energy_rate.map(|c| -0.15 * c);
        s.ratio.strain_energy_rate_quadratic = p.strain_energy_rate.map(|c| 0.04 * c);
        s.ratio.face_reaction_slice_linear = [-0.2, 0.03, -0.4];
        s.ratio.face_reaction_slice_quadratic = [0.05, -0.01, 0.1];
        s.ratio.drag_linear = p.drag.map(|c| -0.3 * c);
        s.ratio.drag_quadratic = p.drag.map(|c| 0.1 * c);
        s.ratio.catch_up_exponent = 1.0;
    }
    s
}

fn scale(toughness: f64, stiffness: f64, friction: f64) -> ScaleFactors {
    ScaleFactors {
        toughness,
        stiffness,
        friction,
    }
}

fn parts(o: &SurrogateOutput) -> [ScaledParts; 3] {
    [
        o.force_normal_parts,
        o.force_tangential_parts,
        o.work_per_depth_parts,
    ]
}

fn values(o: &SurrogateOutput) -> [f64; 3] {
    [o.force_normal, o.force_tangential, o.work_per_depth]
}

/// Central difference with step h = 1e-5: truncation ~h²·f‴/6 (the knee
/// gate is steep in ℓ: its width in ℓ is W/L ≳ 0.05, so f‴ ≲ 400·f′ and
/// the truncation ≲ 1e-8·|f′|) and round-off ~1e-16·|f|/h; both are below
/// 1e-7·(1 + |f| + |f′|), and a missing or wrong term is O(|f′|) or
/// O(|f|·0.01) or more.
fn assert_fd(what: &str, analytic: f64, fd: f64, size: f64) {
    assert!(
        (analytic - fd).abs() <= 1e-7 * (1.0 + size + analytic.abs()),
        "{what}: analytic {analytic}, finite difference {fd}"
    );
}

/// States after fracture of a 30 × 15 mm section (catch-up, knee and steady
/// cutting for eggplant; ramps and steady cutting for potato).
fn fractured_states() -> Vec<CutState> {
    [3e-4, 1.5e-3, 4e-3, 9e-3, 1.8e-2]
        .into_iter()
        .map(|s| CutState {
            depth: 3e-3 + s,
            height: 0.03,
            half_width: 0.015,
            fractured: true,
            travel_since_fracture: s,
        })
        .collect()
}

/// The parts combine to the outputs at the factors they were evaluated at
/// (to round-off: the sums are ordered differently), and their ℓ-slopes and
/// the derivatives ∂/∂T, ∂/∂S, ∂/∂F match central differences.
#[test]
fn parts_and_their_ratio_slopes_match_finite_differences() {
    let h = 1e-5;
    for name in ["potato-cuboid-straight", "eggplant-whole-straight"] {
        let s = with_corrections(name);
        for state in fractured_states() {
            for (t, k, f) in [
                (1.0, 1.0, 1.0),
                (0.7, 1.3, 1.2),
                (1.3, 0.7, 0.8),
                // Inside the fitted ratios near their end (ρ = 2 itself is
                // where the continuation's curvature jumps, which a central
                // difference straddles), and beyond it (ρ = 3: the
                // corrections continue along their tangents, the catch-up
                // length keeps scaling as T/S).
                (1.0, 1.9, 1.0),
                (1.0, 3.0, 1.0),
            ] {
                for xi in [0.0, 0.4, 1.1, 2.2] {
                    let o = s.evaluate(xi, &state, &scale(t, k, f));
                    let l = (k / t).ln();
                    // ℓ-slopes of the parts: move along ℓ at fixed T.
                    let up = s.evaluate(xi, &state, &scale(t, t * (l + h).exp(), f));
                    let down = s.evaluate(xi, &state, &scale(t, t * (l - h).exp(), f));
                    for ((p, u), d) in parts(&o).iter().zip(parts(&up)).zip(parts(&down)) {
                        let size = p.by_stiffness.abs() + p.by_friction_stiffness.abs();
                        assert_fd(
                            &format!("{name} by_stiffness slope, xi {xi}"),
                            p.by_stiffness_log_ratio_slope,
                            (u.by_stiffness - d.by_stiffness) / (2.0 * h),
                            size,
                        );
                        assert_fd(
                            &format!("{name} by_friction_stiffness slope, xi {xi}"),
                            p.by_friction_stiffness_log_ratio_slope,
                            (u.by_friction_stiffness - d.by_friction_stiffness) / (2.0 * h),
                            size,
                        );
                        assert_fd(
                            &format!("{name} by_toughness slope, xi {xi}"),
                            p.by_toughness_log_ratio_slope,
                            (u.by_toughness - d.by_toughness) / (2.0 * h),
                            p.by_toughness.abs(),
                        );
                    }
                    let at = |t, k, f| values(&s.evaluate(xi, &state, &scale(t, k, f)));
                    let dt = [at(t + h, k, f), at(t - h, k, f)];
                    let dk = [at(t, k + h, f), at(t, k - h, f)];
                    let df = [at(t, k, f + h), at(t, k, f - h)];
                    for (i, (p, v)) in parts(&o).iter().zip(values(&o)).enumerate() {
                        assert!(
                            (p.combine(t, k, f) - v).abs() <= 1e-12 * (1.0 + v.abs()),
                            "{name}: parts combine to {} not {v}",
                            p.combine(t, k, f)
                        );
                        let fd = |d: &[[f64; 3]; 2]| (d[0][i] - d[1][i]) / (2.0 * h);
                        let what = format!("{name} output {i} at xi {xi}, T {t}, S {k}");
                        assert_fd(&what, p.toughness_derivative(t, k, f), fd(&dt), v.abs());
                        assert_fd(&what, p.stiffness_derivative(t, k, f), fd(&dk), v.abs());
                        assert_fd(&what, p.friction_derivative(k), fd(&df), v.abs());
                    }
                }
            }
        }
    }
}

/// Along a ray of constant ρ the outputs after fracture are exactly linear
/// in (T, S) together: scaling T and S by the same k scales every force by
/// k (the dimensional argument; the onset depth is unchanged).
#[test]
fn outputs_scale_with_toughness_and_stiffness_together() {
    for name in ["potato-cuboid-straight", "eggplant-whole-straight"] {
        let s = with_corrections(name);
        for state in fractured_states() {
            for (t, k) in [(0.7, 1.3), (1.3, 0.7), (1.0, 2.0)] {
                for xi in [0.0, 0.6, 1.8] {
                    let o = s.evaluate(xi, &state, &scale(t, k, 1.0));
                    let o2 = s.evaluate(xi, &state, &scale(1.5 * t, 1.5 * k, 1.0));
                    for (a, b) in values(&o).iter().zip(values(&o2)) {
                        assert!((1.5 * a - b).abs() <= 1e-12 * (1.0 + b.abs()), "{a} {b}");
                    }
                    let d = o.fracture_onset_depth;
                    assert!((d - o2.fracture_onset_depth).abs() <= 1e-15 + 1e-12 * d);
                }
            }
        }
    }
}

/// Dimensional analysis of the section (linear elasticity, the Griffith
/// balance G = R_c of seed 000 eq. 1 with R'_c before the first fracture,
/// Coulomb friction, a fixed blade): scaling E, R_c and R'_c by the same
/// k = 2 leaves the displacements and the crack path unchanged and scales
/// every force by k. Checked on the full section model (potato, a 16 × 24 mm
/// section, ξ = 0 and 1.2, to 60 % of its height): the forces at every step
/// are 2× the nominal ones to 1e-9 of the run's largest force (measured:
/// 1.4e-12, round-off; the section's tolerances are relative) and the crack
/// path is the same.
#[test]
fn section_forces_scale_with_stiffness_and_toughness_together() {
    let material = MaterialPreset::PotatoCuboid.material();
    let doubled = scaled_material(&material, 2.0, 2.0);
    let blade = KnifePreset::Straight.settings().blade;
    let settings = SweepSettings {
        depth_fraction: 0.6,
        ..SweepSettings::default()
    };
    let cases = [0.0, 1.2].map(|xi| SweepCase {
        xi,
        height: 0.016,
        half_width: 0.012,
    });
    let a = run_sweep(&material, &blade, &cases, &settings, 2, &|| {}).unwrap();
    let b = run_sweep(&doubled, &blade, &cases, &settings, 2, &|| {}).unwrap();
    for (ra, rb) in a.iter().zip(&b) {
        assert_eq!(ra.samples.len(), rb.samples.len());
        assert_eq!(ra.onset_depth, rb.onset_depth);
        let largest = ra
            .samples
            .iter()
            .map(|s| s.force_normal.abs().max(s.force_tangential.abs()))
            .fold(0.0, f64::max);
        let mut worst: f64 = 0.0;
        for (sa, sb) in ra.samples.iter().zip(&rb.samples) {
            assert_eq!(sa.fractured, sb.fractured);
            for (x, y) in [
                (sa.force_normal, sb.force_normal),
                (sa.force_tangential, sb.force_tangential),
                (sa.force_normal_friction, sb.force_normal_friction),
            ] {
                worst = worst.max((2.0 * x - y).abs() / largest);
            }
            assert!(
                (sa.crack_depth - sb.crack_depth).abs() <= 1e-9,
                "crack {} vs {}",
                sa.crack_depth,
                sb.crack_depth
            );
        }
        eprintln!(
            "xi {}: largest |2F - F(2E, 2R_c)| / max|F| = {worst:e}",
            ra.case.xi
        );
        assert!(worst <= 1e-9, "xi {}: {worst}", ra.case.xi);
    }
}
