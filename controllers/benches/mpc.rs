//! MPC solve time at the default horizon: the convex subproblem of N = 10
//! depth stages re-linearised and solved as in closed loop, many times.
//!
//! `cargo bench -p shearcut-controllers --bench mpc` prints median, p99 and
//! max per solve, the whole `Mpc::tick` on planning ticks, and the edge
//! depth of a section depth on a dome (`DepthProfile::edge_depth_at`: each
//! plan before the first fracture asks it for every depth of the onset's
//! cost).
#![allow(clippy::disallowed_methods)] // A benchmark reads the wall clock.

use std::sync::Arc;
use std::time::Instant;

use nalgebra::Vector2;

use shearcut_controllers::controller::{Controller, CutTask, MotionLimits};
use shearcut_controllers::mpc::{
    DepthProfile, DepthQp, Mpc, MpcSettings, QpLimits, SliceModel, StageCost, StageData, StageState,
};
use shearcut_controllers::observer::EdgeOutline;
use shearcut_controllers::planner::{LatencyMode, PlannerSettings};
use shearcut_sim::arm::{ArmReading, ArmStatus};
use shearcut_sim::geometry::Polygon;
use shearcut_sim::{Knife, KnifePreset};

/// w(ξ) = 150 − 120ξ + 45ξ² N/m, f(ξ) = 140/(1+ξ) N/m: the shape of the
/// potato surrogate (a minimum near ξ = 1.3).
#[derive(Debug, Clone, Copy)]
struct Quadratic;

impl SliceModel for Quadratic {
    fn stage(&self, xi: f64, s: &StageState) -> StageCost {
        let grow = 1.0 + 5.0 * s.depth;
        StageCost {
            work_per_depth: grow * (150.0 - 120.0 * xi + 45.0 * xi * xi),
            work_per_depth_slope: grow * (-120.0 + 90.0 * xi),
            work_per_depth_curvature: grow * 90.0,
            force_normal: 140.0 / (1.0 + xi),
            force_normal_slope: -140.0 / ((1.0 + xi) * (1.0 + xi)),
            deformation: 0.0,
            deformation_slope: 0.0,
            ..StageCost::default()
        }
    }
}

fn stats(mut v: Vec<f64>) -> (f64, f64, f64) {
    v.sort_by(f64::total_cmp);
    let at = |q: f64| v[((v.len() - 1) as f64 * q).round() as usize];
    (at(0.5), at(0.99), v[v.len() - 1])
}

/// `DepthProfile::edge_depth_at` on a dome's profile (41 samples, contact
/// ∝ √depth over 40 mm, as `DepthProfile::of_object` samples a half
/// potato): the time per call, from batches of 1000 targets across the
/// depth.
fn edge_depth_at() {
    let depths: Vec<f64> = (0..=40).map(|k| k as f64 * 1e-3).collect();
    let lengths: Vec<f64> = depths.iter().map(|h| 0.5 * h.sqrt()).collect();
    let profile = DepthProfile::new(depths, lengths, 0.035, 0.03).unwrap();
    let batches = 2_000;
    let mut per_call = Vec::with_capacity(batches);
    for b in 0..batches {
        let start = Instant::now();
        for k in 0..1000 {
            let target = 0.036 * ((k * 7 + b) % 1000) as f64 / 1000.0;
            std::hint::black_box(profile.edge_depth_at(std::hint::black_box(target)));
        }
        per_call.push(start.elapsed().as_secs_f64() * 1e9 / 1000.0);
    }
    let (med, p99, max) = stats(per_call);
    println!(
        "DepthProfile::edge_depth_at, a dome of 41 samples, {batches} batches of 1000: median {med:.1} ns, p99 {p99:.1} ns, max {max:.1} ns per call"
    );
}

fn main() {
    edge_depth_at();
    let settings = MpcSettings::default();
    let n = settings.stages;
    let limits = QpLimits {
        xi_max: 2.5,
        trust_region: 0.5,
        normal_speed: 0.05,
        tangential_speed: 0.1,
        max_force: 30.0,
        time_weight: 0.01,
        smoothness_weight: 1e-4,
        deformation_weight: 1.0,
        force_penalty: 10.0,
    };
    let mut qp = DepthQp::new(n, settings.max_iterations);
    let mut stages = vec![StageData::default(); n];
    let mut xi_bar = vec![0.5; n];
    let solves = 20_000;
    let mut times = Vec::with_capacity(solves);
    let mut iterations = Vec::with_capacity(solves);
    for i in 0..solves {
        // A cut progressing and restarting: the data change every solve.
        let d0 = 0.02 * (i % 200) as f64 / 200.0;
        let dd = (0.025 - d0) / n as f64;
        for k in 0..n {
            let depth = d0 + (k as f64 + 0.5) * dd;
            let state = StageState {
                depth,
                height: 0.03,
                half_width: 0.015,
                fractured: true,
                travel_since_fracture: depth,
            };
            stages[k] = StageData {
                depth_step: dd,
                contact_length: 0.02 + 1.5 * depth,
                xi_bar: xi_bar[k],
                cost: Quadratic.stage(xi_bar[k], &state),
                before_fracture: false,
                onset: [0.0; 3],
                entering: Default::default(),
                edge_descent_slope: 0.0,
                finish_slope: 0.0,
            };
        }
        let budget = 0.03 * (1.0 - (i % 200) as f64 / 250.0);
        let start = Instant::now();
        let status = qp.solve(&stages, &limits, xi_bar[0], budget);
        times.push(start.elapsed().as_secs_f64() * 1e6);
        iterations.push(qp.iterations() as f64);
        assert_eq!(status, shearcut_controllers::mpc::QpStatus::Solved);
        xi_bar.copy_from_slice(qp.xi());
    }
    let (med, p99, max) = stats(times);
    let (it_med, _, it_max) = stats(iterations);
    println!(
        "DepthQp::solve, N = {n} stages ({} variables, {} constraints), {solves} solves: median {med:.1} us, p99 {p99:.1} us, max {max:.1} us; iterations median {it_med}, max {it_max}",
        3 * n,
        8 * n + 1
    );

    // The controller's servo ticks against a reading stream: with the plan
    // made on the tick (`inline`: estimation, linearisation, solve,
    // shaping on the planning ticks) and off it (`lockstep`: the tick only
    // observes, submits and shapes; the planner thread solves).
    for latency in [LatencyMode::Inline, LatencyMode::Lockstep] {
        let settings = MpcSettings {
            planner: PlannerSettings {
                latency,
                ..PlannerSettings::default()
            },
            ..settings
        };
        // The straight 0.2 m edge (401 samples, as many as the chef's) over
        // a block 1 m deep whose top is at y = 0.
        let knife = Knife::new(&KnifePreset::Straight.settings()).unwrap();
        let block = Polygon::new(vec![
            Vector2::new(-1.0, -1.0),
            Vector2::new(1.0, -1.0),
            Vector2::new(1.0, 0.0),
            Vector2::new(-1.0, 0.0),
        ]);
        let task = CutTask {
            target_depth: 1.0,
            outline: Arc::new(EdgeOutline::new(knife.edge(), &block)),
            overtravel: 0.0,
            period: 1e-3,
            blade_budget: 1.0,
            limits: MotionLimits::within_arm(0.05, 0.1, 9.0, 4500.0, 0.9),
        };
        let profile = DepthProfile::new(vec![0.0, 0.03], vec![0.02, 0.065], 0.03, 0.015).unwrap();
        let mut mpc = Mpc::new(&task, &settings, Quadratic, profile, 0.5).unwrap();
        let (mut plan_ticks, mut all_ticks) = (Vec::new(), Vec::new());
        for i in 0..50_000u64 {
            let depth = 1e-6 * i as f64 % 0.9;
            // The force drops from 20 to 10 N after 100 ticks: the first
            // fracture, so that the plans are the cutting phase's.
            let normal_force = if i < 100 { 20.0 } else { 10.0 };
            let m = ArmReading {
                time: i as f64 * 1e-3,
                position: nalgebra::Vector3::new(0.0, -depth, 0.0),
                velocity: nalgebra::Vector3::new(0.0, -0.02, 0.02),
                wrench: [0.0, normal_force, -3.0, 0.0, 0.0, 0.0],
                status: ArmStatus::Moving,
            };
            let start = Instant::now();
            std::hint::black_box(mpc.tick(&m));
            let us = start.elapsed().as_secs_f64() * 1e6;
            all_ticks.push(us);
            if mpc.replanned() {
                plan_ticks.push(us);
            }
        }
        let (med, p99, max) = stats(plan_ticks);
        let (all_med, all_p99, all_max) = stats(all_ticks);
        println!(
            "Mpc::tick, planner {latency:?}: planning ticks median {med:.1} us, p99 {p99:.1} us, max {max:.1} us; all ticks median {all_med:.2} us, p99 {all_p99:.1} us, max {all_max:.1} us; plans {}, fallbacks {}",
            mpc.stats().plans,
            mpc.stats().fallbacks
        );
    }
}
