//! The MPC in closed loop with a synthetic arm: it reaches the target depth
//! within the arm's limits and the blade budget, heads for the model's
//! optimum when the blade is plentiful, spends a short blade where more
//! edge is in contact when it may not saw, and saws (reverses the
//! tangential direction at constant ξ) when it may.

mod synthetic_arm;

use std::sync::Arc;

use nalgebra::Vector2;
use shearcut_controllers::controller::{Controller, CutPhase, CutTask, StrokePhase};
use shearcut_controllers::mpc::{
    DepthProfile, Mpc, MpcSettings, SliceModel, StageCost, StageState,
};
use shearcut_controllers::observer::EdgeOutline;
use shearcut_controllers::planner::{LatencyMode, PlannerSettings};
use shearcut_sim::arm::ArmStatus;
use shearcut_sim::geometry::Polygon;
use shearcut_sim::{Knife, KnifePreset};
use synthetic_arm::{QuadraticModel, SyntheticArm, task};

fn run<M: SliceModel + Clone + Send + 'static>(
    mpc: &mut Mpc<M>,
    ticks: usize,
) -> (SyntheticArm, Vec<(f64, f64)>) {
    let mut arm = SyntheticArm::new(0.0);
    let mut m = arm.measure(ArmStatus::Moving);
    let mut trace = Vec::new();
    for _ in 0..ticks {
        let c = mpc.tick(&m);
        m = arm.step(&c);
        trace.push((arm.depth(), mpc.telemetry().slice_push_ratio));
        if mpc.telemetry().phase == CutPhase::Done {
            break;
        }
    }
    (arm, trace)
}

#[test]
fn with_blade_to_spare_the_mpc_slices_at_the_model_optimum() {
    let profile = DepthProfile::uniform(0.03, 0.03, 0.015).unwrap();
    let settings = MpcSettings::default();
    let mut mpc = Mpc::new(&task(0.02, 1.0), &settings, QuadraticModel, profile, 0.5).unwrap();
    let (arm, trace) = run(&mut mpc, 20_000);
    assert_eq!(arm.refused, 0);
    assert_eq!(mpc.telemetry().phase, CutPhase::Done);
    assert_eq!(mpc.stats().fallbacks, 0, "{:?}", mpc.stats());
    // w'(ξ) = 0 at ξ = 4/3; the smoothness and time weights are tiny.
    let (_, xi_mid) = trace[trace.len() / 2];
    assert!((xi_mid - 4.0 / 3.0).abs() < 0.02, "ξ = {xi_mid}");
}

/// [`QuadraticModel`] flattened 200 times: w(ξ) = 150 − 0.6ξ + 0.225ξ² N/m,
/// its minimum at ξ = 4/3 only 0.27 % below pressing.
#[derive(Debug, Clone, Copy)]
struct ShallowModel;

impl SliceModel for ShallowModel {
    fn stage(&self, xi: f64, state: &StageState) -> StageCost {
        let steep = QuadraticModel.stage(xi, state);
        StageCost {
            work_per_depth: 150.0 - 0.6 * xi + 0.225 * xi * xi,
            work_per_depth_slope: -0.6 + 0.45 * xi,
            work_per_depth_curvature: 0.45,
            ..steep
        }
    }
}

/// The MPC at `min_saving` on `model`, from pressing, cutting 20 mm of a
/// 30 mm uniform object with blade to spare, to the end of the cut.
fn cut_from_pressing<M: SliceModel + Clone + Send + 'static>(
    model: M,
    min_saving: f64,
) -> (SyntheticArm, Vec<(f64, f64)>) {
    let profile = DepthProfile::uniform(0.03, 0.03, 0.015).unwrap();
    let settings = MpcSettings {
        min_saving,
        ..MpcSettings::default()
    };
    let mut mpc = Mpc::new(&task(0.02, 1.0), &settings, model, profile, 0.0).unwrap();
    let (arm, trace) = run(&mut mpc, 20_000);
    assert_eq!(mpc.telemetry().phase, CutPhase::Done);
    (arm, trace)
}

/// `min_saving`: a plan that changes the ratio for less than that fraction
/// of its predicted cost is not followed; the ratio held is the last one.
/// A saving well above it is followed as before.
#[test]
fn the_mpc_holds_its_ratio_against_savings_below_min_saving() {
    let mid = |trace: &[(f64, f64)]| trace[trace.len() / 2].1;
    // 0.27 % to gain: followed by default, held below a 0.5 % threshold.
    let (_, trace) = cut_from_pressing(ShallowModel, 0.0);
    let xi_mid = mid(&trace);
    // On so flat a law the objective's other terms keep it short of 4/3.
    assert!(
        xi_mid > 0.5,
        "ξ = {xi_mid}: leaves pressing for the optimum"
    );
    let (arm, trace) = cut_from_pressing(ShallowModel, 0.005);
    assert_eq!(arm.refused, 0);
    let xi_max = trace.iter().map(|(_, xi)| *xi).fold(0.0, f64::max);
    assert_eq!(xi_max, 0.0, "presses throughout");
    // 53 % to gain: followed through the same threshold.
    let (_, trace) = cut_from_pressing(QuadraticModel, 0.005);
    let xi_mid = mid(&trace);
    assert!((xi_mid - 4.0 / 3.0).abs() < 0.02, "ξ = {xi_mid}");
}

#[test]
fn a_min_saving_outside_its_range_is_refused_by_name() {
    let profile = DepthProfile::uniform(0.03, 0.03, 0.015).unwrap();
    for bad in [-0.01, 0.6, f64::NAN] {
        let settings = MpcSettings {
            min_saving: bad,
            ..MpcSettings::default()
        };
        let Err(e) = Mpc::new(
            &task(0.02, 1.0),
            &settings,
            ShallowModel,
            profile.clone(),
            0.0,
        ) else {
            panic!("min_saving = {bad} accepted");
        };
        let e = e.to_string();
        assert!(e.contains("min_saving") && e.contains("[0, 0.5]"), "{e}");
    }
}

#[test]
fn a_short_blade_is_respected_and_spent_where_the_contact_is_long() {
    // Contact grows from 10 mm at the top to 50 mm at 20 mm depth (a
    // widening object); 8 mm of blade for 20 mm of depth.
    let profile = DepthProfile::new(vec![0.0, 0.02], vec![0.01, 0.05], 0.03, 0.015).unwrap();
    let budget = 0.008;
    let settings = MpcSettings {
        max_reversals: 0,
        ..MpcSettings::default()
    };
    let mut mpc = Mpc::new(&task(0.02, budget), &settings, QuadraticModel, profile, 0.4).unwrap();
    let (arm, trace) = run(&mut mpc, 20_000);
    assert_eq!(arm.refused, 0);
    assert_eq!(mpc.telemetry().phase, CutPhase::Done);
    assert!(arm.position.z <= budget, "travel {}", arm.position.z);
    let xi_at = |depth: f64| {
        trace
            .iter()
            .find(|(d, _)| *d >= depth)
            .map(|(_, xi)| *xi)
            .unwrap()
    };
    // L·w'(ξ) is equalised along the cut: ξ rises with the contact length.
    assert!(
        xi_at(0.015) > xi_at(0.005) + 0.1,
        "{} {}",
        xi_at(0.005),
        xi_at(0.015)
    );
}

/// Blade of the sawing tests, m: 8 mm for 20 mm of depth.
const SHORT_BLADE: f64 = 0.008;

/// The MPC on a 30 mm uniform object with [`SHORT_BLADE`] for 20 mm of
/// depth, starting at ξ = 0.4.
fn short_blade_mpc() -> Mpc<QuadraticModel> {
    let profile = DepthProfile::uniform(0.03, 0.03, 0.015).unwrap();
    Mpc::new(
        &task(0.02, SHORT_BLADE),
        &MpcSettings::default(),
        QuadraticModel,
        profile,
        0.4,
    )
    .unwrap()
}

#[test]
fn a_short_blade_is_sawn_through_at_the_model_optimum_and_ratio() {
    // 8 mm of blade for 20 mm of depth, but the model's optimum ξ = 4/3
    // wants 27 mm: sawing pays (a reversal costs only time).
    let budget = SHORT_BLADE;
    let mut mpc = short_blade_mpc();
    let mut arm = SyntheticArm::new(0.0);
    let mut m = arm.measure(ArmStatus::Moving);
    let mut reversing_ticks = 0;
    let mut mid_ratios = Vec::new();
    for _ in 0..40_000 {
        let c = mpc.tick(&m);
        // Never beyond the blade: the net travel stays within [0, budget]
        // (a micrometre for the last tick before a stop).
        assert!(
            arm.position.z >= -1e-6 && arm.position.z <= budget + 1e-6,
            "blade at {} m",
            arm.position.z
        );
        if let StrokePhase::Stopping { xi } | StrokePhase::Restarting { xi, .. } =
            mpc.stroke().phase()
        {
            // A reversal stops and restarts on straight lines through rest:
            // whenever the knife moves, its ratio is the one held.
            let (v_n, v_t) = (-c.velocity.y, c.velocity.z.abs());
            if v_n > 1e-9 {
                assert!(
                    (v_t / v_n - xi).abs() < 1e-9 * (1.0 + xi),
                    "{v_t} / {v_n} vs {xi}"
                );
                reversing_ticks += 1;
            }
        }
        m = arm.step(&c);
        if (0.008..0.012).contains(&arm.depth()) && m.velocity.y < 0.0 {
            mid_ratios.push(m.velocity.z.abs() / -m.velocity.y);
        }
        if mpc.telemetry().phase == CutPhase::Done {
            break;
        }
    }
    assert_eq!(arm.refused, 0);
    assert_eq!(mpc.telemetry().phase, CutPhase::Done);
    assert!(
        mpc.stroke().reversals() >= 2,
        "{} reversals",
        mpc.stroke().reversals()
    );
    assert!(reversing_ticks > 0);
    assert_eq!(mpc.stats().fallbacks, 0, "{:?}", mpc.stats());
    // Between reversals the knife cuts near the model's optimum (the ticks
    // of a reversal hold the ratio too).
    let mean = mid_ratios.iter().sum::<f64>() / mid_ratios.len() as f64;
    assert!((mean - 4.0 / 3.0).abs() < 0.1, "mean ξ = {mean}");
}

#[test]
fn a_sawing_cut_never_presses_at_the_strokes_ends() {
    // The same short blade: at each stroke's end the knife reverses at the
    // ratio it cuts at, so no tick of the cut between the first and last
    // millimetre moves down at a ratio far below the planned optimum (a
    // stroke whose tangential speed the blade's end ramps down while the
    // knife goes on pressing would reach ξ = 0).
    let mut mpc = short_blade_mpc();
    let mut arm = SyntheticArm::new(0.0);
    let mut m = arm.measure(ArmStatus::Moving);
    let mut lowest = f64::INFINITY;
    for _ in 0..40_000 {
        let c = mpc.tick(&m);
        let (v_n, v_t) = (-c.velocity.y, c.velocity.z.abs());
        if (0.001..0.019).contains(&arm.depth()) && v_n > 1e-6 {
            lowest = lowest.min(v_t / v_n);
        }
        m = arm.step(&c);
        if mpc.telemetry().phase == CutPhase::Done {
            break;
        }
    }
    assert_eq!(mpc.telemetry().phase, CutPhase::Done);
    assert!(mpc.stroke().reversals() >= 2);
    assert!(lowest > 1.0, "lowest ratio while moving down: {lowest}");
}

#[test]
fn while_estimating_the_mpc_touches_at_the_touch_speed_until_the_first_fracture() {
    // The stiffness is identified only by the indentation before the first
    // fracture, so with `estimate` on the knife goes down at the guarded
    // touch speed until the material first fractures (here at 0.5 mm of
    // depth), then at the plan's speed.
    let profile = DepthProfile::uniform(0.03, 0.03, 0.015).unwrap();
    let touch = 0.004;
    let fracture_depth = 0.5e-3;
    let settings = MpcSettings {
        estimate: true,
        touch_speed: touch,
        ..MpcSettings::default()
    };
    let mut mpc = Mpc::new(&task(0.01, 1.0), &settings, QuadraticModel, profile, 0.5).unwrap();
    // 2 N at the fracture: well above the fracture detector's floor.
    let mut arm = SyntheticArm::new(4000.0);
    arm.fracture_depth = Some(fracture_depth);
    let mut m = arm.measure(ArmStatus::Moving);
    let (mut before, mut after) = (0.0f64, 0.0f64);
    for _ in 0..20_000 {
        let c = mpc.tick(&m);
        m = arm.step(&c);
        let depth = -m.position.y;
        if depth >= fracture_depth {
            after = after.max(-m.velocity.y);
        } else {
            before = before.max(-m.velocity.y);
        }
        if mpc.telemetry().phase == CutPhase::Done {
            break;
        }
    }
    assert_eq!(mpc.telemetry().phase, CutPhase::Done);
    assert_eq!(arm.refused, 0);
    // The jerk-limited shaper reaches the touch speed without overshoot.
    assert!(
        before <= touch * (1.0 + 1e-9),
        "{before} m/s before the fracture"
    );
    assert!(before > 0.99 * touch, "{before} m/s before the fracture");
    assert!(after > 5.0 * touch, "{after} m/s after the fracture");

    // Without estimation there is no touch phase.
    let settings = MpcSettings {
        touch_speed: touch,
        ..MpcSettings::default()
    };
    let profile = DepthProfile::uniform(0.03, 0.03, 0.015).unwrap();
    let mut mpc = Mpc::new(&task(0.01, 1.0), &settings, QuadraticModel, profile, 0.5).unwrap();
    let mut arm = SyntheticArm::new(0.0);
    let mut m = arm.measure(ArmStatus::Moving);
    let mut early = 0.0f64;
    for _ in 0..20_000 {
        let c = mpc.tick(&m);
        m = arm.step(&c);
        if -m.position.y < fracture_depth {
            early = early.max(-m.velocity.y);
        }
        if mpc.telemetry().phase == CutPhase::Done {
            break;
        }
    }
    assert!(early > 2.0 * touch, "{early} m/s");
}

/// The quadratic model with its optimum moving with depth
/// (ξ* = 4/3 + 40·(0.01 − d), 1.73 at the top, 0.93 at 20 mm) so that the
/// plan's stages differ, and failing (a NaN work slope) while `failing` is set: the
/// subproblem then cannot be solved.
#[derive(Clone)]
struct FailingModel {
    failing: std::sync::Arc<std::sync::atomic::AtomicBool>,
}

impl shearcut_controllers::mpc::SliceModel for FailingModel {
    fn stage(
        &self,
        xi: f64,
        state: &shearcut_controllers::mpc::StageState,
    ) -> shearcut_controllers::mpc::StageCost {
        let shifted = xi - 40.0 * (0.01 - state.depth);
        let mut c = QuadraticModel.stage(shifted, state);
        if self.failing.load(std::sync::atomic::Ordering::SeqCst) {
            c.work_per_depth_slope = f64::NAN;
        }
        c
    }
}

/// `plan` is `solved` shifted by `j` stages (the stages past its end repeat
/// its last): the fallback's plan.
fn shifted_by(plan: &[f64], solved: &[f64]) -> Option<usize> {
    let n = solved.len();
    (0..n).find(|&j| (0..n).all(|k| plan[k] == solved[(k + j).min(n - 1)]))
}

/// An MPC on [`FailingModel`] for `task`'s cut of `profile`, run against a
/// spring-free synthetic arm with every plan failing while the crack is
/// between 6 and 12 mm deep; `observe` sees the MPC and the command after
/// each tick. Returns the MPC and the arm at the end of the cut.
fn run_failing(
    budget: f64,
    settings: &MpcSettings,
    profile: DepthProfile,
    initial_xi: f64,
    mut observe: impl FnMut(&Mpc<FailingModel>, &shearcut_sim::arm::KnifeCommand),
) -> (Mpc<FailingModel>, SyntheticArm) {
    let failing = std::sync::Arc::new(std::sync::atomic::AtomicBool::new(false));
    let model = FailingModel {
        failing: failing.clone(),
    };
    // The test flips the failure between ticks, so each plan is made on the
    // tick that asks for it.
    let settings = MpcSettings {
        planner: PlannerSettings {
            latency: LatencyMode::Inline,
            ..PlannerSettings::default()
        },
        ..*settings
    };
    let mut mpc = Mpc::new(&task(0.02, budget), &settings, model, profile, initial_xi).unwrap();
    let mut arm = SyntheticArm::new(0.0);
    let mut m = arm.measure(ArmStatus::Moving);
    for _ in 0..20_000 {
        failing.store(
            (0.006..0.012).contains(&arm.depth()),
            std::sync::atomic::Ordering::SeqCst,
        );
        let c = mpc.tick(&m);
        m = arm.step(&c);
        observe(&mpc, &c);
        if mpc.telemetry().phase == CutPhase::Done {
            break;
        }
    }
    (mpc, arm)
}

#[test]
fn a_plan_that_fails_falls_back_to_the_last_plan_shifted_to_the_edge() {
    use shearcut_controllers::mpc::QpStatus;
    let profile = DepthProfile::uniform(0.03, 0.03, 0.015).unwrap();
    let mut last_solved: Option<Vec<f64>> = None;
    let (mut fallbacks, mut largest_shift, mut shifts_in_order) = (0, 0, true);
    let mut previous_shift = 0;
    let (mpc, arm) = run_failing(1.0, &MpcSettings::default(), profile, 0.5, |mpc, c| {
        if !mpc.replanned() {
            return;
        }
        if mpc.stats().last_status == Some(QpStatus::Solved) {
            last_solved = Some(mpc.plan().to_vec());
            previous_shift = 0;
            return;
        }
        fallbacks += 1;
        let solved = last_solved.as_ref().expect("a plan was solved before 6 mm");
        let j = shifted_by(mpc.plan(), solved)
            .unwrap_or_else(|| panic!("{:?} is not a shift of {solved:?}", mpc.plan()));
        largest_shift = largest_shift.max(j);
        shifts_in_order &= j >= previous_shift;
        previous_shift = j;
        // The knife's target is the shifted plan's first stage (within the
        // arm's 0.05 m/s normal speed).
        let t = mpc.telemetry();
        let v_n = (1.0 / mpc.plan_times()[0]).min(0.05);
        assert!((t.normal_speed - v_n).abs() <= 1e-12, "{t:?} vs {v_n}");
        let xi = t.tangential_speed / t.normal_speed;
        assert!(
            (xi - mpc.plan()[0]).abs() <= 1e-9,
            "{t:?} vs {:?}",
            mpc.plan()
        );
        assert!(c.velocity.iter().all(|v| v.is_finite()), "{c:?}");
    });
    eprintln!(
        "{fallbacks} fallbacks, largest shift {largest_shift}; {:?}",
        mpc.stats()
    );
    assert_eq!(mpc.telemetry().phase, CutPhase::Done);
    assert_eq!(arm.refused, 0);
    assert_eq!(mpc.stats().fallbacks, fallbacks, "{:?}", mpc.stats());
    assert!(fallbacks >= 5, "{:?}", mpc.stats());
    // 6 mm of depth at the plans' 2 mm stages (and less): the plan is
    // shifted by more than one stage, never backwards.
    assert!(largest_shift >= 2, "largest shift {largest_shift}");
    assert!(shifts_in_order);
}

#[test]
fn fallbacks_on_a_short_blade_stay_within_it() {
    // 8 mm of blade for 20 mm of depth, no sawing, plans failing for 6 mm
    // of depth: the shifted plans (capped to what is left of the blade
    // over the remaining depth) finish the cut within the blade and the
    // arm's limits.
    let profile = DepthProfile::new(vec![0.0, 0.02], vec![0.01, 0.05], 0.03, 0.015).unwrap();
    let budget = 0.008;
    let settings = MpcSettings {
        max_reversals: 0,
        ..MpcSettings::default()
    };
    let (mpc, arm) = run_failing(budget, &settings, profile, 0.4, |_, _| {});
    assert_eq!(mpc.telemetry().phase, CutPhase::Done);
    assert_eq!(arm.refused, 0);
    assert!(mpc.stats().fallbacks >= 5, "{:?}", mpc.stats());
    assert!(arm.position.z <= budget, "travel {}", arm.position.z);
}

/// [`QuadraticModel`] with its slope reversed and flattened:
/// w(ξ) = 150 + 0.6ξ + 0.225ξ² N/m, least at pressing.
#[derive(Debug, Clone, Copy)]
struct PressingModel;

impl SliceModel for PressingModel {
    fn stage(&self, xi: f64, state: &StageState) -> StageCost {
        StageCost {
            work_per_depth: 150.0 + 0.6 * xi + 0.225 * xi * xi,
            work_per_depth_slope: 0.6 + 0.45 * xi,
            work_per_depth_curvature: 0.45,
            ..QuadraticModel.stage(xi, state)
        }
    }
}

/// A 60 mm block (top at y = 0) under 100–160 mm of the chef's edge with
/// the knife frame origin at z = 0: wholly under its rise, where sliding
/// towards the tip brings the lower part of the edge over the block.
fn block_under_the_rise() -> Arc<EdgeOutline> {
    let chef = Knife::new(&KnifePreset::Chef.settings()).unwrap();
    let block = Polygon::new(vec![
        Vector2::new(0.1, -0.05),
        Vector2::new(0.16, -0.05),
        Vector2::new(0.16, 0.0),
        Vector2::new(0.1, 0.0),
    ]);
    Arc::new(EdgeOutline::new(chef.edge(), &block))
}

/// `finish_gap`: under a chef's rise the sections' mean depth lags the
/// edge's deepest point by a gap that sliding towards the tip narrows, so
/// pricing it slices where the work law alone presses; a straight edge
/// below a level top has no gap to move, and the cut is the same to the
/// bit.
#[test]
fn pricing_the_finish_slices_under_a_rise_and_changes_nothing_under_a_straight_edge() {
    let cut = |outline: Arc<EdgeOutline>, finish_gap: bool| {
        let task = CutTask {
            outline,
            ..task(0.02, 0.01)
        };
        let settings = MpcSettings {
            finish_gap,
            ..MpcSettings::default()
        };
        let profile = DepthProfile::uniform(0.03, 0.03, 0.015).unwrap();
        let mut mpc = Mpc::new(&task, &settings, PressingModel, profile, 0.0).unwrap();
        let (arm, trace) = run(&mut mpc, 20_000);
        assert_eq!(arm.refused, 0);
        assert_eq!(mpc.telemetry().phase, CutPhase::Done);
        (arm.position.z, trace)
    };
    let (slide_off, trace_off) = cut(block_under_the_rise(), false);
    let (slide_on, trace_on) = cut(block_under_the_rise(), true);
    let xi_max = |t: &[(f64, f64)]| t.iter().map(|(_, xi)| *xi).fold(0.0, f64::max);
    assert!(xi_max(&trace_off) < 0.01, "presses: {}", xi_max(&trace_off));
    // The finish's price per unit ξ and descent, L·w·g′ with g′ about the
    // rise's mean slope over the contact less its slope at the deepest point
    // (0.25 − 0.14 ≈ 0.1), about 0.5 N, dwarfs the law's L·w′ = 0.018 N: the
    // plan spends the blade (10 mm).
    assert!(slide_off < 1e-4, "{slide_off}");
    assert!(slide_on > 0.009 && slide_on <= 0.01, "{slide_on}");
    assert!(xi_max(&trace_on) > 0.3, "slices: {}", xi_max(&trace_on));
    let (_, straight_off) = cut(synthetic_arm::flat_outline(), false);
    let (_, straight_on) = cut(synthetic_arm::flat_outline(), true);
    let bits = |t: &[(f64, f64)]| -> Vec<(u64, u64)> {
        t.iter()
            .map(|(d, xi)| (d.to_bits(), xi.to_bits()))
            .collect()
    };
    assert_eq!(bits(&straight_off), bits(&straight_on));
}
