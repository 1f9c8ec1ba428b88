//! The model-predictive controller: plans ξ and speed over the rest of the
//! cut at its own rate, and commands jerk-limited velocities every tick.

use shearcut_sim::InvalidSetting;
use shearcut_sim::arm::{ArmReading, ArmStatus, KnifeCommand};

use super::depth_profile::DepthProfile;
use super::depth_qp::{DepthQp, QpLimits, QpStatus, StageData};
use super::force_tare::ForceTare;
use super::fracture_onset::FractureOnset;
use super::scale_estimator::ScaleEstimator;
use super::settings::MpcSettings;
use super::slice_model::{SliceModel, StageState};
use crate::controller::{
    BladeBudget, Controller, ControllerTelemetry, CutTask, SawingStroke, VelocityShaper,
    stopping_distance, stopping_duration,
};

/// Counters of the MPC's plans.
#[derive(Debug, Clone, Copy, PartialEq, Default, serde::Serialize)]
pub struct MpcStats {
    /// Plans attempted.
    pub plans: u64,
    /// Subproblems solved: one per plan, two while the blade budget binds
    /// and sawing is considered.
    pub solves: u64,
    /// Plans that fell back to the previous plan (not solved in budget).
    pub fallbacks: u64,
    /// Status of the last plan.
    pub last_status: Option<QpStatus>,
    /// Interior-point iterations of the last plan.
    pub last_iterations: u32,
    /// Most iterations of any plan.
    pub max_iterations: u32,
}

/// Prior variance of each scale factor (a ±100 % belief).
const ESTIMATOR_PRIOR_VARIANCE: f64 = 1.0;
/// How far the sections' mean depth ([`DepthProfile::section_depth`]) has
/// advanced past the first fracture before the estimator uses the forces
/// again, m (on a dome about 1.5 times as much edge travel): the transition (sections fracturing one by one, the
/// drag held at onset being released over a few bevel heights) is in
/// neither the pre- nor the post-fracture model.
const ESTIMATOR_SETTLE_DEPTH: f64 = 2e-3;
/// The surrogate's force error as a fraction of the force: its held-out
/// force RMS errors are 4–6 % (`config/surrogates/*.accuracy.toml`). Sets
/// the rows' weights (relative, the same for both rows) against the prior.
const ESTIMATOR_RELATIVE_ERROR: f64 = 0.05;

/// Most plans [`Mpc::planned_ratio_from_rest`] makes.
pub const FIRST_PLAN_ITERATIONS: usize = 50;

/// Model-predictive control of the slice (DESIGN §4).
///
/// Every `1/rate_hz` the remaining depth to the target is split into N
/// stages (a shrinking horizon that always ends at the target, so the blade
/// budget is planned over the whole rest of the cut), the [`SliceModel`] is
/// evaluated at the previous plan, and the convex subproblem of
/// [`DepthQp`] chooses each stage's ξ and time per unit depth. One
/// convexification per plan: successive plans re-linearise around the last
/// one (a real-time iteration scheme), with a trust region keeping each step
/// where the quadratic model holds. The first stage's plan becomes the
/// velocity target (v_n = 1/τ₀, v_t = ξ₀·v_n) that the jerk-limited
/// [`VelocityShaper`] follows on every servo tick in between.
///
/// A plan that is not solved within the iteration budget falls back to the
/// previous plan shifted to the edge's depth: the knife takes the ratio
/// and speed that plan gave the stage it is in now (ratios capped to what
/// is left of the blade in the current stroke: a fallback does not saw),
/// and the fallback is counted.
///
/// With `estimate` on, every tick in contact feeds the measured forces per
/// unit length to a [`ScaleEstimator`] with the model of them at the
/// executed ξ, linearised at the estimator's factors, and each plan uses
/// the latest scale factors.
///
/// Sawing: with `max_reversals` > 0, each plan is solved twice when the
/// blade budget binds — within what is left of the current stroke, and with
/// the reversals still allowed adding a full stroke each — and the second
/// is taken if its objective plus the time the reversals it needs lose
/// (each costs a stop and a restart, [`stopping_duration`] at
/// `time_weight`) is lower. The knife then reverses at the stroke's end at
/// constant ξ ([`SawingStroke`]). ξ is planned as a magnitude: seed 000's
/// r(ξ, ν) (eq. 6) and the surrogate depend on |ξ| only.
pub struct Mpc<M: SliceModel> {
    task: CutTask,
    settings: MpcSettings,
    model: M,
    profile: DepthProfile,
    qp: DepthQp,
    limits: QpLimits,
    stages: Vec<StageData>,
    plan_xi: Vec<f64>,
    ticks_per_plan: u64,
    ticks: u64,
    normal_speed: f64,
    tangential_speed: f64,
    /// The sections' mean depth at the first fracture, m.
    depth_at_fracture: Option<f64>,
    budget: BladeBudget,
    shaper: VelocityShaper,
    stroke: SawingStroke,
    /// Whether the plan in force needs more blade than the stroke has.
    saw: bool,
    /// The plan within the current stroke (ξ and τ per stage) while the
    /// sawing plan is solved.
    stroke_xi: Vec<f64>,
    stroke_tau: Vec<f64>,
    /// The plan in force: τ per stage (s/m), its stages starting at the
    /// edge's depth `plan_origin` (m), each `plan_step` deep (m; 0 before
    /// the first solved plan). A fallback shifts it ([`Mpc::shift_plan`]).
    plan_tau: Vec<f64>,
    plan_origin: f64,
    plan_step: f64,
    stats: MpcStats,
    replanned: bool,
    estimator: Option<ScaleEstimator>,
    /// The sensor's bias, from the free-air readings.
    tare: ForceTare,
    /// The first fracture, from the normal force.
    onset: FractureOnset,
    /// The edge's depth after the last measurement, m (below the object's
    /// top; the model's state is the sections' mean depth there,
    /// [`DepthProfile::section_depth`]).
    depth: f64,
    telemetry: ControllerTelemetry,
}

impl<M: SliceModel> std::fmt::Debug for Mpc<M> {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("Mpc")
            .field("settings", &self.settings)
            .field("stats", &self.stats)
            .finish_non_exhaustive()
    }
}

impl<M: SliceModel> Mpc<M> {
    /// An MPC for `task` with `model` of the material and `profile` of the
    /// object, starting from the plan ξ = `initial_xi` at every stage.
    ///
    /// # Errors
    /// Invalid settings or task.
    pub fn new(
        task: &CutTask,
        settings: &MpcSettings,
        model: M,
        profile: DepthProfile,
        initial_xi: f64,
    ) -> Result<Self, InvalidSetting> {
        task.validate()?;
        settings.validate().map_err(|e| e.prefixed("mpc"))?;
        let n = settings.stages;
        let l = &task.limits;
        let limits = QpLimits {
            xi_max: settings.max_slice_push_ratio,
            trust_region: settings.trust_region,
            normal_speed: l.normal_speed,
            tangential_speed: l.tangential_speed,
            max_force: settings.max_force.unwrap_or(f64::INFINITY),
            time_weight: settings.time_weight,
            smoothness_weight: settings.smoothness_weight,
            deformation_weight: settings.deformation_weight,
            force_penalty: settings.force_penalty,
        };
        let shaper = VelocityShaper::for_task(task)?;
        let ticks_per_plan = ((1.0 / settings.rate_hz) / task.period).round().max(1.0) as u64;
        let xi0 = initial_xi.clamp(0.0, settings.max_slice_push_ratio);
        Ok(Self {
            task: *task,
            settings: *settings,
            model,
            profile,
            qp: DepthQp::new(n, settings.max_iterations),
            limits,
            stages: vec![StageData::default(); n],
            plan_xi: vec![xi0; n],
            ticks_per_plan,
            ticks: 0,
            normal_speed: 0.0,
            tangential_speed: 0.0,
            depth_at_fracture: None,
            budget: BladeBudget::new(task.blade_budget),
            shaper,
            stroke: SawingStroke::new(settings.max_reversals),
            saw: false,
            stroke_xi: vec![0.0; n],
            stroke_tau: vec![0.0; n],
            plan_tau: vec![0.0; n],
            plan_origin: 0.0,
            plan_step: 0.0,
            stats: MpcStats::default(),
            replanned: false,
            estimator: settings.estimate.then(|| {
                ScaleEstimator::new(
                    ESTIMATOR_PRIOR_VARIANCE,
                    settings.forgetting,
                    ESTIMATOR_RELATIVE_ERROR,
                )
            }),
            tare: ForceTare::default(),
            onset: FractureOnset::default(),
            depth: 0.0,
            telemetry: ControllerTelemetry::default(),
        })
    }

    /// Plan counters.
    pub fn stats(&self) -> &MpcStats {
        &self.stats
    }

    /// Whether the last tick planned (solved the subproblem).
    pub fn replanned(&self) -> bool {
        self.replanned
    }

    /// The sawing state: direction, reversals, the reversal under way.
    pub fn stroke(&self) -> &SawingStroke {
        &self.stroke
    }

    /// The current plan's ratios, stage by stage.
    pub fn plan(&self) -> &[f64] {
        &self.plan_xi
    }

    /// The current plan's times per unit depth τ (s/m), stage by stage (0
    /// before the first solved plan): its first stage's normal speed is
    /// 1/τ₀ within the speed limit.
    pub fn plan_times(&self) -> &[f64] {
        &self.plan_tau
    }

    /// The model (e.g. to update its scale factors).
    pub fn model_mut(&mut self) -> &mut M {
        &mut self.model
    }

    /// The scale factors (toughness, stiffness, friction) believed now.
    pub fn scale(&self) -> [f64; 3] {
        self.estimator
            .as_ref()
            .map_or([1.0; 3], ScaleEstimator::factors)
    }

    /// Feeds the measured forces per unit length of edge in contact to the
    /// estimator, with the model of them at the executed ξ, the current
    /// state and the estimator's factors: during the indentation (which
    /// identifies the stiffness) and after the first fracture.
    fn estimate(&mut self, m: &ArmReading, l: f64, fractured: bool) {
        let Some(estimator) = self.estimator.as_mut() else {
            return;
        };
        let v_n = -m.velocity.y;
        if !(v_n > 0.0 && l > 0.0) {
            return;
        }
        let xi = m.velocity.z.abs() / v_n;
        let depth = self.profile.section_depth(self.depth);
        let since = self.depth_at_fracture.map_or(0.0, |d| (depth - d).max(0.0));
        // Right after the first fracture the sections fracture one by one
        // and the crack runs in jumps: the measured force is neither the
        // pre- nor the post-fracture model's. Wait until the cut has settled.
        if fractured && since < ESTIMATOR_SETTLE_DEPTH {
            return;
        }
        let state = StageState {
            depth,
            height: self.profile.height(),
            half_width: self.profile.half_width(),
            fractured,
            travel_since_fracture: since,
        };
        let Some(model) = self.model.force_model(xi, &state, estimator.factors()) else {
            return;
        };
        // Measured resistance: up, and against the tangential motion.
        let w = self.tare.tared(&m.wrench);
        let force = [w[1], -w[2] * m.velocity.z.signum()];
        if fractured {
            let per_length = [
                Some(force[0] / l),
                (m.velocity.z != 0.0).then(|| force[1] / l),
            ];
            estimator.observe_cut(per_length, model);
        } else {
            estimator.observe_indentation(l, force.map(|f| f / l), model);
        }
    }

    /// The blade the first plan from the intact object asks for per unit
    /// depth: its mean slice-push ratio Σ Δd_k ξ_k / Σ Δd_k over the whole
    /// cut (with the sawing strokes it plans, if they pay). A plant plans its
    /// contact arc and first sections for a direction of motion; this is
    /// the one the MPC is going to cut along. Successive plans re-linearise
    /// within a trust region, so it replans (at most
    /// [`FIRST_PLAN_ITERATIONS`] times) until the plan settles. Plans on
    /// this controller, so call it on a fresh one that is then dropped.
    pub fn planned_ratio_from_rest(&mut self) -> f64 {
        let mean = |xi: &[f64]| xi.iter().sum::<f64>() / xi.len() as f64;
        let mut last = f64::NAN;
        for _ in 0..FIRST_PLAN_ITERATIONS {
            self.replan_at(0.0, self.task.target_depth, false);
            let now = mean(&self.plan_xi);
            if (now - last).abs() < 1e-4 {
                break;
            }
            last = now;
        }
        mean(&self.plan_xi)
    }

    fn replan(&mut self, fractured: bool) {
        let remaining = self.task.target_depth - self.depth;
        self.replan_at(self.depth, remaining, fractured);
    }

    /// Plans from the edge's depth `d0` (m, [`CutTask::edge_depth`]) for the cut to
    /// deepen by `remaining` (m), `fractured` or not.
    ///
    /// The plant's depth is the crack front's below the object's top, which
    /// the edge's travel advances one for one (the crack's lead over the
    /// edge is steady), so the stages split `remaining` of the edge's
    /// travel; each stage's model state is the sections' mean depth there
    /// ([`DepthProfile::section_depth`]), and its work is per unit of the
    /// edge's travel.
    fn replan_at(&mut self, d0: f64, remaining: f64, fractured: bool) {
        let n = self.settings.stages;
        let dd = remaining.max(1e-6) / n as f64;
        let since = self.depth_at_fracture;
        let section_depth = |d: f64| self.profile.section_depth(d);
        let s0 = section_depth(d0);
        let [t, st, f] = self.scale();
        self.model.set_scale(t, st, f);
        // Before the first fracture the onset's cost covers the catch-up
        // after it, whose length the ratio at the fracture sets; the later
        // stages are priced at the rates after that span (`SliceModel`).
        let span = if fractured {
            0.0
        } else {
            let first = StageState {
                depth: section_depth(d0 + 0.5 * dd),
                height: self.profile.height(),
                half_width: self.profile.half_width(),
                fractured: false,
                travel_since_fracture: 0.0,
            };
            self.model.catch_up_span(self.plan_xi[0], &first)
        };
        for k in 0..n {
            let edge = d0 + (k as f64 + 0.5) * dd;
            let depth = section_depth(edge);
            let state = StageState {
                depth,
                height: self.profile.height(),
                half_width: self.profile.half_width(),
                fractured: fractured || k > 0,
                travel_since_fracture: match since {
                    Some(at) if fractured => (depth - at).max(0.0),
                    _ if k == 0 => span,
                    _ => (depth - s0).max(span),
                },
            };
            let xi_bar = self.plan_xi[k];
            self.stages[k] = StageData {
                depth_step: dd,
                contact_length: self.profile.contact_length(edge),
                xi_bar,
                cost: self.model.stage(xi_bar, &state),
                before_fracture: !fractured && k == 0,
            };
        }
        let l = self.task.limits;
        let normal_limit = self.normal_speed_limit();
        // Keep what stopping at the current tangential speed needs.
        let reserve = stopping_distance(self.tangential_speed, l.acceleration, l.jerk);
        let blade = (self.budget.remaining_towards(self.stroke.direction()) - reserve).max(0.0);
        let previous = self.plan_xi[0];
        let mut status = self.qp.solve(&self.stages, &self.limits, previous, blade);
        self.stats.plans += 1;
        self.stats.solves += 1;
        self.stats.last_iterations = self.qp.iterations();
        self.stats.max_iterations = self.stats.max_iterations.max(self.qp.iterations());
        let within = status == QpStatus::Solved;
        if within {
            self.stroke_xi.copy_from_slice(self.qp.xi());
            self.stroke_tau.copy_from_slice(self.qp.tau());
        }
        self.saw = self.stroke.reversals_left() > 0 && self.sawing_pays(previous, blade, within);
        if self.saw {
            status = QpStatus::Solved;
            self.stroke_xi.copy_from_slice(self.qp.xi());
            self.stroke_tau.copy_from_slice(self.qp.tau());
        }
        self.stats.last_status = Some(status);
        if status == QpStatus::Solved {
            self.plan_xi.copy_from_slice(&self.stroke_xi);
            self.plan_tau.copy_from_slice(&self.stroke_tau);
            self.plan_origin = d0;
            self.plan_step = dd;
            let tau = self.stroke_tau[0];
            self.normal_speed = (1.0 / tau).min(normal_limit);
            self.tangential_speed = (self.plan_xi[0] * self.normal_speed).min(l.tangential_speed);
        } else {
            self.stats.fallbacks += 1;
            self.shift_plan(d0);
            // The trust region around a plan that no longer fits the blade
            // (after the last allowed reversal, say) leaves the next
            // subproblem infeasible too: linearise it around ratios that fit.
            let cap = blade / remaining;
            for x in &mut self.plan_xi {
                *x = x.min(cap);
            }
            if self.plan_step == 0.0 {
                // No plan yet: start at the initial plan's ratio, full speed.
                self.normal_speed =
                    normal_limit.min(l.tangential_speed / self.plan_xi[0].max(1e-12));
            } else {
                // The shifted plan's stage under the edge now.
                self.normal_speed = (1.0 / self.plan_tau[0]).min(normal_limit);
            }
            self.tangential_speed = (self.plan_xi[0] * self.normal_speed).min(l.tangential_speed);
        }
    }

    /// The fallback's plan: the last solved plan shifted to the edge's depth
    /// `d0`, so that its first stage is the one the edge is in (stages past
    /// the plan's end repeat its last). Nothing before the first solved plan.
    fn shift_plan(&mut self, d0: f64) {
        if self.plan_step <= 0.0 {
            return;
        }
        let n = self.plan_xi.len();
        let passed = ((d0 - self.plan_origin) / self.plan_step).floor();
        let j = if passed.is_finite() {
            passed.clamp(0.0, (n - 1) as f64) as usize
        } else {
            0
        };
        if j == 0 {
            return;
        }
        for plan in [&mut self.plan_xi, &mut self.plan_tau] {
            plan.copy_within(j.., 0);
            let last = plan[n - 1 - j];
            plan[n - j..].fill(last);
        }
        self.plan_origin += j as f64 * self.plan_step;
    }

    /// The normal speed allowed now, m/s: the arm's, or while estimating
    /// before the first fracture the guarded touch's
    /// ([`MpcSettings::touch_speed`]), so that the indentation, which alone
    /// identifies the stiffness, spans many ticks.
    fn normal_speed_limit(&self) -> f64 {
        let l = self.task.limits.normal_speed;
        if self.estimator.is_some() && self.depth_at_fracture.is_none() {
            l.min(self.settings.touch_speed)
        } else {
            l
        }
    }

    /// Whether sawing pays, after the plan within the stroke (`blade` m
    /// left) was solved (`within`; its solution in `stroke_xi`/`stroke_tau`)
    /// or not: if that plan's budget row binds, or it failed (the trust
    /// region around a sawing plan can leave no ratio that fits the
    /// stroke), solves again with every reversal still allowed adding a
    /// stroke, and compares the objectives, charging the second the time
    /// each reversal it needs loses. True leaves the sawing plan in the
    /// solver.
    fn sawing_pays(&mut self, previous: f64, blade: f64, within: bool) -> bool {
        let demand = |stages: &[StageData], xi: &[f64]| -> f64 {
            stages.iter().zip(xi).map(|(s, x)| s.depth_step * x).sum()
        };
        if within && demand(&self.stages, &self.stroke_xi) < blade * (1.0 - 1e-6) {
            return false;
        }
        let stroke = 0.98 * self.budget.stroke_length();
        let extra = f64::from(self.stroke.reversals_left()) * stroke;
        self.stats.solves += 1;
        if self
            .qp
            .solve(&self.stages, &self.limits, previous, blade + extra)
            != QpStatus::Solved
        {
            return false;
        }
        self.stats.last_iterations = self.qp.iterations();
        self.stats.max_iterations = self.stats.max_iterations.max(self.qp.iterations());
        if !within {
            return true;
        }
        let xi = self.qp.xi();
        let needed = ((demand(&self.stages, xi) - blade) / stroke)
            .ceil()
            .max(0.0);
        if needed < 1.0 {
            return false;
        }
        let l = &self.task.limits;
        let speed = self
            .normal_speed
            .hypot(self.tangential_speed)
            .max(l.normal_speed);
        let reversal = self.limits.time_weight * stopping_duration(speed, l.acceleration, l.jerk);
        let within = DepthQp::objective(
            &self.stages,
            &self.limits,
            previous,
            &self.stroke_xi,
            &self.stroke_tau,
        );
        let sawing = DepthQp::objective(&self.stages, &self.limits, previous, xi, self.qp.tau());
        sawing + needed * reversal < within
    }
}

impl<M: SliceModel> Controller for Mpc<M> {
    fn name(&self) -> &str {
        "mpc"
    }

    fn tick(&mut self, m: &ArmReading) -> KnifeCommand {
        if matches!(m.status, ArmStatus::LimitViolation(_)) {
            self.shaper.resync(&m.velocity);
        }
        self.budget.observe(m);
        self.depth = self.task.edge_depth(m.position.y);
        let in_air = m.position.y > self.task.touch_height;
        self.tare.observe(&m.wrench, in_air);
        let contact = self.profile.contact_length(self.depth);
        if !in_air {
            self.onset.observe(self.tare.tared(&m.wrench)[1]);
        }
        let fractured = self.onset.fractured();
        if fractured && self.depth_at_fracture.is_none() {
            self.depth_at_fracture = Some(self.profile.section_depth(self.depth));
            // E is identified by the indentation before the first fracture;
            // after it, toughness and stiffness are nearly collinear.
            if let Some(estimator) = self.estimator.as_mut() {
                estimator.freeze_stiffness();
            }
        }
        self.estimate(m, contact, fractured);
        let done = self.task.reached(m.position.y);
        self.replanned = false;
        if !done && self.ticks.is_multiple_of(self.ticks_per_plan) {
            self.replan(fractured);
            self.replanned = true;
        }
        self.ticks += 1;
        let (command, v_n, v_t) = if done {
            (self.shaper.command(0.0, 0.0), 0.0, 0.0)
        } else {
            let command = self.stroke.command(
                &mut self.shaper,
                &self.budget,
                &self.task,
                self.normal_speed,
                self.tangential_speed,
                self.saw,
            );
            (
                command,
                self.normal_speed,
                self.stroke.direction() * self.tangential_speed,
            )
        };
        self.telemetry = ControllerTelemetry {
            planned: self.replanned,
            fallbacks: self.stats.fallbacks,
            scale: self.scale(),
            ..ControllerTelemetry::moving(v_n, v_t, self.budget.used(), done)
        };
        command
    }

    fn telemetry(&self) -> ControllerTelemetry {
        self.telemetry
    }
}
