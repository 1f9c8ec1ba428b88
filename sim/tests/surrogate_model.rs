//! The surrogate's analytic ξ-derivatives against finite differences, its
//! scale-factor parts, and the steady-state law without friction (seed 000
//! eq. 1 with dU → 0 and eq. 6: F_n + ξF_t → r(ξ,ν)·R_c).

use std::path::PathBuf;

use shearcut_sim::mechanics::toughness_ratio;
use shearcut_sim::surrogate::{CutState, ScaleFactors, Surrogate, SurrogateOutput};

fn shipped(name: &str) -> Surrogate {
    let path = PathBuf::from(env!("CARGO_MANIFEST_DIR"))
        .join(format!("../config/surrogates/{name}-straight.toml"));
    Surrogate::from_path(&path).unwrap()
}

fn potato() -> Surrogate {
    shipped("potato-cuboid")
}

/// Whole eggplant (R'_c/R_c = 2.5): its first crack jumps millimetres ahead
/// of the edge, so after fracture the catch-up and the knee gate depend on ξ
/// through the onset depth.
fn eggplant() -> Surrogate {
    shipped("eggplant-whole")
}

/// Fractured states of whole eggplant in a 30 × 30 mm section during the
/// catch-up, across the knee and beyond (the catch-up is 2–13 mm over ξ).
fn eggplant_states() -> Vec<CutState> {
    [0.3e-3, 1.5e-3, 2.5e-3, 4e-3, 6.5e-3, 9e-3, 14e-3]
        .into_iter()
        .map(|s| CutState {
            depth: 4e-3 + s,
            height: 0.03,
            half_width: 0.015,
            fractured: true,
            travel_since_fracture: s,
        })
        .collect()
}

fn states() -> [CutState; 4] {
    let base = CutState {
        depth: 2e-4,
        height: 0.03,
        half_width: 0.015,
        fractured: false,
        travel_since_fracture: 0.0,
    };
    [
        base,
        CutState {
            depth: 1.5e-3,
            fractured: true,
            travel_since_fracture: 1.2e-3,
            ..base
        },
        CutState {
            depth: 4e-3,
            fractured: true,
            travel_since_fracture: 3.7e-3,
            ..base
        },
        CutState {
            depth: 0.02,
            fractured: true,
            travel_since_fracture: 0.0197,
            ..base
        },
    ]
}

const SCALES: [ScaleFactors; 2] = [
    ScaleFactors {
        toughness: 1.0,
        stiffness: 1.0,
        friction: 1.0,
    },
    ScaleFactors {
        toughness: 1.3,
        stiffness: 0.7,
        friction: 1.6,
    },
];

/// Central difference of `f` in ξ with step 1e-6: truncation ~1e-12·f''',
/// round-off ~1e-16·|f|/1e-6 ≈ 1e-10·|f|, so 1e-6·(1 + |f|) is generous
/// yet catches any wrong term (the terms are O(1…100) N/m).
fn check(name: &str, xi: f64, analytic: f64, f: impl Fn(f64) -> f64) {
    let h = 1e-6;
    let fd = (f(xi + h) - f(xi - h)) / (2.0 * h);
    let scale = 1.0 + f(xi).abs().max(analytic.abs());
    assert!(
        (fd - analytic).abs() <= 1e-6 * scale,
        "{name} at xi {xi}: analytic {analytic}, finite difference {fd}"
    );
}

#[test]
fn derivatives_match_finite_differences() {
    let cases = states()
        .into_iter()
        .map(|st| (potato(), st))
        .chain(eggplant_states().into_iter().map(|st| (eggplant(), st)));
    for (s, state) in cases {
        for scale in SCALES {
            for xi in [0.05, 0.3, 0.75, 1.1, 1.7, 2.3, 2.9] {
                let o = s.evaluate(xi, &state, &scale);
                let e = |x: f64| s.evaluate(x, &state, &scale);
                check("F_n", xi, o.force_normal_slope, |x| e(x).force_normal);
                check("F_t", xi, o.force_tangential_slope, |x| {
                    e(x).force_tangential
                });
                check("work", xi, o.work_per_depth_slope, |x| e(x).work_per_depth);
                check("work slope", xi, o.work_per_depth_curvature, |x| {
                    e(x).work_per_depth_slope
                });
                check("r", xi, o.toughness_ratio_slope, |x| e(x).toughness_ratio);
                let q = s.work_quadratic(xi, &state, &scale);
                assert_eq!(q.value, o.work_per_depth);
                assert_eq!(q.slope, o.work_per_depth_slope);
                assert_eq!(q.curvature, o.work_per_depth_curvature);
            }
        }
    }
}

fn close(a: f64, b: f64) -> bool {
    (a - b).abs() <= 1e-12 * (1.0 + a.abs().max(b.abs()))
}

#[test]
fn outputs_are_consistent_and_linear_in_the_scale_factors() {
    let s = potato();
    for state in states() {
        for scale in SCALES {
            for xi in [0.0, 0.4, 1.2, 2.4] {
                let o: SurrogateOutput = s.evaluate(xi, &state, &scale);
                assert_linear(&o, xi, &scale);
                let t = scale.toughness;
                // The parts after fracture depend on the factors only
                // through the ratio ρ = S/T (the toughness part not at
                // all), and r is exact.
                if state.fractured {
                    let n = s.evaluate(xi, &state, &ScaleFactors::default());
                    let same_ratio = ScaleFactors {
                        toughness: 1.0,
                        stiffness: scale.stiffness / scale.toughness,
                        friction: 1.0,
                    };
                    let m = s.evaluate(xi, &state, &same_ratio);
                    assert!(close(
                        o.force_normal_parts.by_friction_stiffness,
                        m.force_normal_parts.by_friction_stiffness
                    ));
                    assert!(close(
                        o.force_normal_parts.by_stiffness,
                        m.force_normal_parts.by_stiffness
                    ));
                    assert!(close(
                        o.work_per_depth_parts.by_toughness,
                        n.work_per_depth_parts.by_toughness
                    ));
                    assert!(close(o.fracture, t * toughness_ratio(xi, 0.4) * 150.0));
                } else {
                    assert_eq!(o.fracture, 0.0);
                }
                assert!(close(o.toughness_ratio, toughness_ratio(xi, 0.4)));
            }
        }
    }
}

/// Work per depth = F_n + ξF_t = fracture + strain + friction, and every
/// force and the work are their parts combined with the factors.
fn assert_linear(o: &SurrogateOutput, xi: f64, scale: &ScaleFactors) {
    let (t, k, f) = (scale.toughness, scale.stiffness, scale.friction);
    assert!(close(
        o.work_per_depth,
        o.force_normal + xi * o.force_tangential
    ));
    assert!(close(o.work_per_depth, o.fracture + o.strain + o.friction));
    assert!(close(o.force_normal, o.force_normal_parts.combine(t, k, f)));
    assert!(close(
        o.force_tangential,
        o.force_tangential_parts.combine(t, k, f)
    ));
    assert!(close(
        o.work_per_depth,
        o.work_per_depth_parts.combine(t, k, f)
    ));
}

/// The catch-up (seed 000 eq. 1 at the first fracture: the released strain
/// energy drives the crack ahead of the edge at R_c < R'_c): right after the
/// onset the crack hardly grows, so the fracture work is well below
/// r(ξ,ν)·R_c and F_n falls far below its value at the onset; once the edge
/// has caught up the fracture work is r(ξ,ν)·R_c. The parts stay linear in
/// the factors throughout.
#[test]
fn eggplant_catches_up_with_its_crack_before_cutting_again() {
    let s = eggplant();
    let rc = s.material.fracture_toughness;
    let nu = s.material.poisson_ratio;
    for xi in [0.3, 1.0, 2.0] {
        let before = CutState {
            depth: 0.0,
            height: 0.03,
            half_width: 0.015,
            fractured: false,
            travel_since_fracture: 0.0,
        };
        let d_star = s
            .evaluate(xi, &before, &ScaleFactors::default())
            .fracture_onset_depth;
        let at_onset = s.evaluate(
            xi,
            &CutState {
                depth: d_star,
                ..before
            },
            &ScaleFactors::default(),
        );
        let after = |travel: f64| {
            s.evaluate(
                xi,
                &CutState {
                    depth: d_star + travel,
                    fractured: true,
                    travel_since_fracture: travel,
                    ..before
                },
                &ScaleFactors::default(),
            )
        };
        // The knee gate is centred on the catch-up length L with a width of
        // a few bevel heights, so for short catch-ups (large ξ) it has begun
        // to open at the onset; the crack still grows at well under its
        // steady rate there.
        let steady = toughness_ratio(xi, nu) * rc;
        let just_after = after(1e-5);
        assert!(
            just_after.fracture < 0.5 * steady,
            "xi {xi}: {} vs r R_c {steady}",
            just_after.fracture
        );
        assert!(
            just_after.force_normal < 0.5 * at_onset.force_normal,
            "xi {xi}: {} vs {} at the onset",
            just_after.force_normal,
            at_onset.force_normal
        );
        // 30 mm further the edge cuts (the catch-up is at most ~13 mm).
        let cutting = after(0.03);
        assert!(
            close(cutting.fracture, steady),
            "xi {xi}: {} vs r R_c {steady}",
            cutting.fracture
        );
        for state in eggplant_states() {
            for scale in SCALES {
                assert_linear(&s.evaluate(xi, &state, &scale), xi, &scale);
            }
        }
    }
}

#[test]
fn onset_scales_with_toughness_over_stiffness() {
    let s = potato();
    let st = states()[0];
    for xi in [0.0, 0.8, 2.0] {
        let a = s
            .evaluate(xi, &st, &ScaleFactors::default())
            .fracture_onset_depth;
        let b = s
            .evaluate(
                xi,
                &st,
                &ScaleFactors {
                    toughness: 2.0,
                    stiffness: 0.5,
                    friction: 1.0,
                },
            )
            .fracture_onset_depth;
        assert!(close(b, 4.0 * a), "xi {xi}: {a} {b}");
        // Slicing fractures earlier (seed 000 §V: r < 1 and the drag's work).
        if xi > 0.0 {
            let p = s
                .evaluate(0.0, &st, &ScaleFactors::default())
                .fracture_onset_depth;
            assert!(a < p, "xi {xi}: {a} vs pressing {p}");
        }
    }
}

/// Seed 000 eq. (1) in steady cutting: F·dd = r(ξ,ν)·R_c·dd + dU, so with
/// no friction F_n + ξF_t = r·R_c + dU/dd. Once the wedge's ramps are done
/// (travel ≫ their longest length, 3 bevel heights ≈ 11 mm) what is left of
/// dU/dd is the steady wedging energy E·Δ²·g(λ_H, λ_w)/H
/// (`basis::strain_depth_rate_basis`) and the (d/H)³, (d/H)⁴ terms, all
/// ∝ 1/H at a given d/H up to the logarithms: tens of N/m in the fitted
/// sections (20–45 mm; the section model's own is 11–18 N/m at 25–30 ×
/// 15 mm), and at H = 1 m still 0.5–2.4 % of r·R_c on the shipped potato
/// files (d/H = 0.1; potato whole +1.1 %, potato cuboid −1.9 % at
/// ξ = 0.75). The sign there is the extrapolation's: the potato cuboid's
/// term, fitted with window rows, turns negative above H ≈ 0.12 m
/// (w = H/2), the potato whole's and the unweighted fit's stay positive;
/// the fits' sizes end at 45 mm (`docs/surrogates.md`, "The strain rate's
/// settled mean"). So the law is checked as the limit it is, deep in sections of 10 m and 100 m
/// (d/H = 0.3): within 1 % at 10 m, within 0.1 % at 100 m, and decaying
/// at least as fast as 1/H up to logarithms (the 100 m excess at most a
/// quarter of the 10 m one). What it holds is the rest of the model: the
/// knee gate at 1, the drag held at the onset released, and the force split
/// that leaves the edge's F_n + ξF_t at exactly r·R_c; a constant offset
/// of ±0.1 % of r·R_c fails it (on the potato whole's file, whose excess
/// is positive; the potato cuboid's negative 1/H term would hide +0.1 %). (The section model meets the law within
/// 0.22 % with a razor blade, `sim/tests/section_steady_state.rs`; with the
/// shipped 2 mm blade its wedge splits the crack ahead of the edge.)
#[test]
fn frictionless_steady_state_is_the_slicing_toughness() {
    let no_friction = ScaleFactors {
        friction: 0.0,
        ..ScaleFactors::default()
    };
    for s in [potato(), shipped("potato-whole")] {
        for xi in [0.0, 0.33, 0.75, 1.4, 1.8, 2.4] {
            let m = &s.material;
            let target = toughness_ratio(xi, m.poisson_ratio) * m.fracture_toughness;
            let excess = |height: f64| {
                let state = CutState {
                    depth: 0.3 * height,
                    height,
                    half_width: 0.5 * height,
                    fractured: true,
                    travel_since_fracture: 0.3 * height,
                };
                let o = s.evaluate(xi, &state, &no_friction);
                assert_eq!(o.friction, 0.0);
                // With friction the work is larger by F·S·μN√(1+ξ²) ≥ 0.
                let w = s.evaluate(xi, &state, &ScaleFactors::default());
                assert!(w.work_per_depth >= o.work_per_depth);
                (o.force_normal + xi * o.force_tangential - target) / target
            };
            let (e10, e100) = (excess(10.0), excess(100.0));
            assert!(
                e10.abs() <= 0.01 && e100.abs() <= 0.001,
                "{} xi {xi}: F_n + xi F_t vs r R_c = {target}: {:+.3} % at 10 m, {:+.3} % at 100 m",
                s.material_name,
                100.0 * e10,
                100.0 * e100
            );
            assert!(
                e100.abs() <= 0.25 * e10.abs(),
                "{} xi {xi}: {e100} at 100 m, {e10} at 10 m",
                s.material_name
            );
        }
    }
}

#[test]
fn work_is_convex_in_xi_beyond_the_concave_shoulder_of_eq_6() {
    // Documented on `Surrogate::work_quadratic`: r(ξ,ν)·R_c is concave below
    // ξ_c(ν); the fitted face reaction's ξ² terms can make the friction's
    // work concave too, beyond the fitted ξ range (format 3: potato, ξ = 3
    // right after fracture) and for eggplant through the ξ-dependent
    // catch-up, so this checks potato on [ξ_c, ξ_max] of its fit.
    let s = potato();
    let xi_c = shearcut_sim::surrogate::concave_up_to(0.4, 3.0);
    let xi_max = s.range.xi_max;
    for state in states() {
        for xi in [xi_c + 0.01, 1.0, 1.5, 2.0, xi_max] {
            let q = s.work_quadratic(xi, &state, &ScaleFactors::default());
            assert!(q.curvature > 0.0, "{state:?} xi {xi}: {}", q.curvature);
        }
    }
}

/// One output of an evaluation.
type Field = fn(&SurrogateOutput) -> f64;

/// The largest change of `f` between neighbouring travels s and s + h over
/// the catch-up and the knee of whole eggplant (30 × 30 mm section, depth
/// d*₀ + s), for s in [0, 20 mm).
fn largest_step(s: &Surrogate, xi: f64, h: f64, f: impl Fn(&SurrogateOutput) -> f64) -> f64 {
    let onset = s
        .evaluate(
            xi,
            &CutState {
                depth: 0.0,
                height: 0.03,
                half_width: 0.015,
                fractured: false,
                travel_since_fracture: 0.0,
            },
            &ScaleFactors::default(),
        )
        .fracture_onset_depth;
    let at = |travel: f64| {
        f(&s.evaluate(
            xi,
            &CutState {
                depth: onset + travel,
                height: 0.03,
                half_width: 0.015,
                fractured: true,
                travel_since_fracture: travel,
            },
            &ScaleFactors::default(),
        ))
    };
    let n = (0.02 / h).round() as usize;
    (0..n)
        .map(|i| (at((i + 1) as f64 * h) - at(i as f64 * h)).abs())
        .fold(0.0, f64::max)
}

/// The catch-up's progress v is C¹ (min(s/L, 1) with its corner rounded), so
/// through the knee the ξ-derivatives of F_n, F_t and the work are
/// continuous in the travel and the travel-derivatives of the forces too:
/// halving the step roughly halves the largest change of a ξ-slope between
/// neighbouring travels and quarters the largest second difference of a
/// force. A jump (the kink of min(s/L, 1)) would keep the first ratio near 1
/// and the second near ½.
#[test]
fn eggplant_outputs_are_smooth_through_the_knee() {
    let s = eggplant();
    for xi in [0.3, 1.0, 2.0] {
        let slopes: [(&str, Field); 3] = [
            ("F_n slope", |o| o.force_normal_slope),
            ("F_t slope", |o| o.force_tangential_slope),
            ("work slope", |o| o.work_per_depth_slope),
        ];
        for (name, f) in slopes {
            let coarse = largest_step(&s, xi, 4e-6, f);
            let fine = largest_step(&s, xi, 2e-6, f);
            assert!(
                fine < 0.6 * coarse,
                "xi {xi}: {name} changes by {coarse} over 4 µm, {fine} over 2 µm"
            );
        }
        // Second differences of F_n in the travel: the largest over the
        // range, at steps h and h/2.
        let second = |h: f64| {
            let at = |i: usize| {
                let travel = i as f64 * h;
                s.evaluate(
                    xi,
                    &CutState {
                        depth: 5e-3 + travel,
                        height: 0.03,
                        half_width: 0.015,
                        fractured: true,
                        travel_since_fracture: travel,
                    },
                    &ScaleFactors::default(),
                )
                .force_normal
            };
            let n = (0.02 / h).round() as usize;
            (1..n)
                .map(|i| (at(i + 1) - 2.0 * at(i) + at(i - 1)).abs())
                .fold(0.0, f64::max)
        };
        let (coarse, fine) = (second(4e-6), second(2e-6));
        assert!(
            fine < 0.4 * coarse,
            "xi {xi}: F_n second difference {coarse} at 4 µm, {fine} at 2 µm"
        );
    }
}
