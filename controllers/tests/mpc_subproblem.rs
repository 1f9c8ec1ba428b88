//! The MPC's convex subproblem against brute force, and its constraints.

use shearcut_controllers::mpc::{DepthQp, EnteringEdge, QpLimits, QpStatus, StageCost, StageData};

/// A convex work model per unit depth and length, N/m: w(ξ) = a − bξ + cξ²,
/// force per unit length f(ξ) = f₀/(1 + ξ) linearised at ξ̄.
fn stage(xi_bar: f64, contact_length: f64, depth_step: f64) -> StageData {
    let (a, b, c) = (150.0, 120.0, 45.0);
    let f0 = 140.0;
    StageData {
        depth_step,
        contact_length,
        xi_bar,
        cost: StageCost {
            work_per_depth: a - b * xi_bar + c * xi_bar * xi_bar,
            work_per_depth_slope: -b + 2.0 * c * xi_bar,
            work_per_depth_curvature: 2.0 * c,
            force_normal: f0 / (1.0 + xi_bar),
            force_normal_slope: -f0 / ((1.0 + xi_bar) * (1.0 + xi_bar)),
            deformation: 0.0,
            deformation_slope: 0.0,
            ..StageCost::default()
        },
        before_fracture: false,
        onset: [0.0; 3],
        entering: Default::default(),
        edge_descent_slope: 0.0,
        finish_slope: 0.0,
    }
}

fn limits(max_force: f64) -> QpLimits {
    QpLimits {
        xi_max: 2.5,
        trust_region: 2.5,
        normal_speed: 0.05,
        tangential_speed: 0.06,
        max_force,
        time_weight: 0.02,
        smoothness_weight: 1e-3,
        deformation_weight: 0.0,
        force_penalty: 10.0,
    }
}

/// The best objective over a grid of ξ (step 0.01) and normal speed (20
/// values up to the limit) per stage, for two stages, honouring every hard
/// constraint of the subproblem.
fn brute_force(stages: &[StageData], l: &QpLimits, prev: f64, blade: f64) -> f64 {
    let xis: Vec<f64> = (0..=250).map(|i| i as f64 * 0.01).collect();
    let speeds: Vec<f64> = (1..=20).map(|i| l.normal_speed * i as f64 / 20.0).collect();
    let mut best = f64::INFINITY;
    for &x0 in &xis {
        for &x1 in &xis {
            if stages[0].blade(x0) + stages[1].blade(x1) > blade {
                continue;
            }
            for &v0 in &speeds {
                if x0 * v0 > l.tangential_speed {
                    continue;
                }
                for &v1 in &speeds {
                    if x1 * v1 > l.tangential_speed {
                        continue;
                    }
                    let j = DepthQp::objective(stages, l, prev, &[x0, x1], &[1.0 / v0, 1.0 / v1]);
                    best = best.min(j);
                }
            }
        }
    }
    best
}

fn check_against_brute_force(stages: &[StageData], l: &QpLimits, prev: f64, blade: f64) {
    let mut qp = DepthQp::new(stages.len(), 50);
    assert_eq!(qp.solve(stages, l, prev, blade), QpStatus::Solved);
    let (xi, tau) = (qp.xi().to_vec(), qp.tau().to_vec());
    // Hard constraints hold.
    let travel: f64 = stages.iter().zip(&xi).map(|(s, x)| s.blade(*x)).sum();
    assert!(
        travel <= blade * (1.0 + 1e-7) + 1e-12,
        "travel {travel} > {blade}"
    );
    for k in 0..xi.len() {
        assert!(xi[k] >= 0.0 && xi[k] <= l.xi_max);
        assert!(tau[k] >= 1.0 / l.normal_speed * (1.0 - 1e-9));
        assert!(xi[k] <= l.tangential_speed * tau[k] * (1.0 + 1e-7) + 1e-9);
    }
    let j_qp = DepthQp::objective(stages, l, prev, &xi, &tau);
    let j_grid = brute_force(stages, l, prev, blade);
    // The continuous optimum is no worse than the grid's best (up to the
    // solver's tolerance), and the grid comes within 1 % of it.
    assert!(j_qp <= j_grid * (1.0 + 1e-6), "qp {j_qp} grid {j_grid}");
    assert!(
        (j_grid - j_qp).abs() <= 0.01 * j_qp.abs(),
        "qp {j_qp} grid {j_grid}"
    );
}

#[test]
fn unconstrained_blade_reaches_the_model_minimum() {
    let stages = [stage(0.5, 0.03, 0.005), stage(0.5, 0.05, 0.005)];
    check_against_brute_force(&stages, &limits(f64::INFINITY), 0.5, 1.0);
}

#[test]
fn a_short_blade_is_spent_where_more_edge_is_in_contact() {
    let stages = [stage(0.5, 0.02, 0.005), stage(0.5, 0.06, 0.005)];
    let l = limits(f64::INFINITY);
    check_against_brute_force(&stages, &l, 0.5, 0.004);
    let mut qp = DepthQp::new(2, 50);
    qp.solve(&stages, &l, 0.5, 0.004);
    // With the budget binding, d(work)/dξ per unit travel is equalised:
    // L₀ w'(ξ₀) = L₁ w'(ξ₁), so the longer contact gets the larger ratio.
    assert!(qp.xi()[1] > qp.xi()[0], "{:?}", qp.xi());
}

#[test]
fn an_edge_that_deepens_as_it_slides_needs_less_blade_per_depth() {
    // A rising edge (κ_d = 0.4 at the deepest point) deepens at 1 + κ_d ξ
    // times the knife's descent: a stage of edge depth Δd at ξ̄ = 0.5 takes
    // Δd/1.2 of descent and ξ times that of blade.
    let level = [stage(0.5, 0.02, 0.005), stage(0.5, 0.06, 0.005)];
    let rising = level.map(|s| StageData {
        edge_descent_slope: 0.4,
        ..s
    });
    assert!((rising[0].knife_descent() - 0.005 / 1.2).abs() < 1e-15);
    assert!((rising[0].blade(0.5) - 0.5 * 0.005 / 1.2).abs() < 1e-15);
    let l = limits(f64::INFINITY);
    check_against_brute_force(&rising, &l, 0.5, 0.004);
    // With the blade binding, the same blade buys larger ratios.
    let mut qp = DepthQp::new(2, 50);
    qp.solve(&level, &l, 0.5, 0.004);
    let on_level: f64 = qp.xi().iter().sum();
    qp.solve(&rising, &l, 0.5, 0.004);
    let on_rise: f64 = qp.xi().iter().sum();
    let used: f64 = rising.iter().zip(qp.xi()).map(|(s, x)| s.blade(*x)).sum();
    assert!((used - 0.004).abs() < 1e-6, "the blade row binds: {used}");
    // Σξ·Δd/1.2 = 0.004 against Σξ·Δd = 0.004.
    assert!(
        (on_rise / on_level - 1.2).abs() < 1e-3,
        "{on_rise} against {on_level}"
    );
}

#[test]
fn the_force_limit_pushes_the_ratio_up() {
    // Unlimited, the plan settles near ξ = 1.31, where the linearised force
    // is (93.3 − 62.2·0.81) N/m × 0.3 m = 12.9 N; a 10 N limit needs
    // ξ ≥ 1.46.
    let stages = [stage(0.5, 0.3, 0.005), stage(0.5, 0.3, 0.005)];
    check_against_brute_force(&stages, &limits(10.0), 0.5, 1.0);
    let mut free = DepthQp::new(2, 50);
    free.solve(&stages, &limits(f64::INFINITY), 0.5, 1.0);
    let mut limited = DepthQp::new(2, 50);
    limited.solve(&stages, &limits(10.0), 0.5, 1.0);
    assert!(free.xi()[0] < 1.4, "{:?}", free.xi());
    // The penalty (10 J/N) outweighs the work gradient: the limit holds.
    for &x in limited.xi() {
        assert!(x >= 1.46 - 1e-6, "{:?}", limited.xi());
    }
}

#[test]
fn the_speed_limit_makes_high_ratios_slower() {
    // ξ above v_t/v_n = 1.2 needs τ > 1/v_n: the time weight then matters.
    let stages = [stage(1.8, 0.05, 0.005), stage(1.8, 0.05, 0.005)];
    check_against_brute_force(&stages, &limits(f64::INFINITY), 1.8, 1.0);
}

#[test]
fn edge_entering_contact_draws_the_ratio_up_where_it_enters() {
    // 20 mm of edge meets intact material in the second stage; its
    // deflection at fracture falls by 0.1 mm per unit ξ. With the blade
    // binding (ξ₀ + ξ₁ ≤ 0.8) and no deformation weight the two stages
    // share it equally; weighted, the blade goes where the edge enters.
    let mut stages = [stage(0.4, 0.04, 0.005), stage(0.4, 0.04, 0.005)];
    stages[1].entering = EnteringEdge {
        length: 0.02,
        deflection: 2e-4,
        deflection_slope: -1e-4,
    };
    let blade = 0.004;
    let unweighted = limits(f64::INFINITY);
    let weighted = QpLimits {
        deformation_weight: 2000.0,
        ..unweighted
    };
    check_against_brute_force(&stages, &weighted, 0.4, blade);
    let mut qp = DepthQp::new(2, 50);
    assert_eq!(qp.solve(&stages, &unweighted, 0.4, blade), QpStatus::Solved);
    let even = qp.xi().to_vec();
    assert!((even[0] - even[1]).abs() < 0.02, "{even:?}");
    assert_eq!(qp.solve(&stages, &weighted, 0.4, blade), QpStatus::Solved);
    let xi = qp.xi();
    // Moving δ of ξ from the first stage to the second (the budget row
    // binds) costs ½·Δd·L·h·δ² on each stage (Δd·L·h = 0.005·0.04·90 =
    // 0.018 J per unit ξ²) plus smoothness w_S (δ² + (2δ)²) = 0.005 δ², and
    // gains w_D·ΔL·δ' δ = −0.004 δ J: δ = 0.004 / (2 · 0.023) = 0.087.
    assert!(
        (xi[1] - xi[0] - 2.0 * 0.087).abs() < 0.01,
        "{xi:?} against {even:?}"
    );
}
