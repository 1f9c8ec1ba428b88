//! The model-predictive controller: plans ξ and speed over the rest of the
//! cut at its own rate, and commands jerk-limited velocities every tick.

use shearcut_sim::InvalidSetting;
use shearcut_sim::arm::{ArmReading, ArmStatus, KnifeCommand};

use super::depth_profile::DepthProfile;
use super::depth_qp::QpStatus;
use super::plan_job::{MpcPlan, MpcPlanJob, PlanRequest};
use super::scale_estimator::ScaleEstimator;
use super::settings::MpcSettings;
use super::slice_model::{SliceModel, StageState};
use crate::controller::{
    BladeBudget, Controller, ControllerTelemetry, CutTask, SawingStroke, VelocityShaper,
};
use crate::observer::{
    EdgeOutline, FractureDetector, FractureSettings, TouchDetector, TouchSettings, WrenchTare,
    WrenchTareSettings,
};
use crate::planner::{PlanJob, Planner, SubmitStatus};

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
/// again, m (on a dome about 1.5 times as much edge travel): the
/// transition (sections fracturing one by one, the drag held at onset being
/// released over a few bevel heights) is in neither the pre- nor the
/// post-fracture model.
const ESTIMATOR_SETTLE_DEPTH: f64 = 2e-3;
/// The surrogate's force error as a fraction of the force: its held-out
/// force RMS errors (`config/surrogates/*.accuracy.toml`; docs/controllers.md,
/// "Online estimation"). Sets the rows' weights (relative, the same for both
/// rows) against the prior.
const ESTIMATOR_RELATIVE_ERROR: f64 = 0.05;

/// Most plans [`Mpc::planned_ratio_from_rest`] makes.
pub const FIRST_PLAN_ITERATIONS: usize = 50;

/// Least edge travel a plan covers, m. Near the target the crack runs ahead
/// of the edge or lags it by up to a few millimetres (the indentation under
/// the edge), and the cut goes on until the edge is the task's overtravel
/// past the target: a plan's horizon does not shrink below this.
const MIN_PLANNED_TRAVEL: f64 = 1e-3;

/// Model-predictive control of the slice (DESIGN §4).
///
/// The servo tick ([`Controller::tick`]) reads the arm, updates the
/// observers (the sensor's tare, the first fracture, the edge's depth and
/// contact length from the knife's edge against the object's outline at the
/// reported pose, [`CutTask::edge_depth`]; while estimating, the touch) and
/// the estimator, follows the plan in force through the jerk-limited
/// shaper, and every `1/rate_hz` hands a [`PlanRequest`] to the planning
/// half ([`MpcPlanJob`]) on a [`Planner`] thread (`[controller.mpc.planner]`:
/// in lockstep the plan arrives a fixed number of ticks later, so runs are
/// bit-identical; in realtime when it is ready). The tick never solves,
/// waits (but for a lockstep plan that is due) or allocates.
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
///
/// # Example
///
/// The MPC for a 20 mm cut into a potato cuboid 25 mm high under a straight
/// 30 mm edge, planning from rest, then its first tick with the knife above
/// the object (a real cell builds the task from its knife, the object's
/// outline and its arm's limits, `docs/arm_interface.md`):
///
/// ```
/// use std::sync::Arc;
/// use nalgebra::{Vector2, Vector3};
/// use shearcut_controllers::controller::{Controller, CutTask, MotionLimits};
/// use shearcut_controllers::mpc::{DepthProfile, Mpc, MpcSettings, SurrogateModel};
/// use shearcut_controllers::observer::EdgeOutline;
/// use shearcut_sim::arm::{ArmLimits, ArmReading, ArmStatus};
/// use shearcut_sim::geometry::Polygon;
/// use shearcut_sim::surrogate::Surrogate;
/// use shearcut_sim::{EdgeShape, Knife, KnifePreset, KnifeSettings};
///
/// let knife = Knife::new(&KnifeSettings {
///     edge: EdgeShape::Straight { length: 0.03 },
///     ..KnifePreset::Straight.settings()
/// })?;
/// // The object in the knife plane (world z, y): 30 mm along the edge, 25 mm high.
/// let outline = Polygon::new(vec![
///     Vector2::new(0.0, 0.0),
///     Vector2::new(0.03, 0.0),
///     Vector2::new(0.03, 0.025),
///     Vector2::new(0.0, 0.025),
/// ]);
/// let arm = ArmLimits::default();
/// let task = CutTask {
///     target_depth: 0.02,
///     overtravel: 0.002,
///     outline: Arc::new(EdgeOutline::new(knife.edge(), &outline)),
///     period: 1e-3,
///     blade_budget: 0.012,
///     limits: MotionLimits::within_arm(0.05, 0.1, arm.acceleration, arm.jerk, 0.9),
/// };
/// let dir = concat!(env!("CARGO_MANIFEST_DIR"), "/../config/surrogates/");
/// let surrogate = Surrogate::from_path(format!("{dir}potato-cuboid-straight.toml").as_ref())?;
/// // The whole 30 mm of edge in contact at every depth; a 25 × 30 mm section.
/// let profile = DepthProfile::new(vec![0.0, 0.02], vec![0.03, 0.03], 0.025, 0.015)?;
/// let settings = MpcSettings::default();
/// let model = SurrogateModel::new(surrogate);
/// let xi = Mpc::planned_ratio_from_rest(&task, &settings, model.clone(), profile.clone(), 0.6, 0.0)?;
/// assert!((0.0..=1.0).contains(&xi), "{xi}");
///
/// let mut mpc = Mpc::new(&task, &settings, model, profile, 0.6)?;
/// let above = ArmReading {
///     time: 0.0,
///     position: Vector3::new(0.0, 0.03, 0.0), // the edge 5 mm above the top
///     velocity: Vector3::zeros(),
///     wrench: [0.0; 6],
///     status: ArmStatus::Moving,
/// };
/// let command = mpc.tick(&above);
/// // The first command starts a jerk-limited move down (or holds still).
/// assert!(command.velocity.y <= 0.0 && command.velocity.iter().all(|v| v.is_finite()));
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
pub struct Mpc<M: SliceModel + Clone + Send + 'static> {
    task: CutTask,
    settings: MpcSettings,
    /// The model, for the estimator's force rows on the tick (the planner
    /// has its own copy).
    model: M,
    profile: DepthProfile,
    planner: Planner<MpcPlanJob<M>>,
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
    stats: MpcStats,
    replanned: bool,
    estimator: Option<ScaleEstimator>,
    /// The sensor's bias and noise, from the free-air readings (the edge
    /// above the object's outline).
    tare: WrenchTare,
    /// The first fracture, from the tared normal force after the touch.
    fracture: FractureDetector,
    /// The edge's touch, from the tared normal force rising out of the
    /// noise: the estimator's indentation rows start there (the task's
    /// outline is a prior; before the edge meets the object the model
    /// would take the free air for a soft material).
    touch: TouchDetector,
    /// The edge's depth after the last reading, m ([`CutTask::edge_depth`];
    /// the model's state is the sections' mean depth there,
    /// [`DepthProfile::section_depth`]).
    depth: f64,
    telemetry: ControllerTelemetry,
}

impl<M: SliceModel + Clone + Send + 'static> std::fmt::Debug for Mpc<M> {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("Mpc")
            .field("settings", &self.settings)
            .field("stats", &self.stats)
            .finish_non_exhaustive()
    }
}

impl<M: SliceModel + Clone + Send + 'static> Mpc<M> {
    /// An MPC for `task` with `model` of the material and `profile` of the
    /// object, starting from the plan ξ = `initial_xi` at every stage; its
    /// planner thread starts here.
    ///
    /// # Errors
    /// Invalid settings or task, or the planner thread cannot start.
    pub fn new(
        task: &CutTask,
        settings: &MpcSettings,
        model: M,
        profile: DepthProfile,
        initial_xi: f64,
    ) -> Result<Self, InvalidSetting> {
        task.validate()?;
        settings.validate().map_err(|e| e.prefixed("mpc"))?;
        let policy = settings
            .planner
            .policy()
            .map_err(|e| e.prefixed("mpc.planner"))?;
        let shaper = VelocityShaper::for_task(task)?;
        let ticks_per_plan = ((1.0 / settings.rate_hz) / task.period).round().max(1.0) as u64;
        let job = MpcPlanJob::new(task, settings, model.clone(), profile.clone(), initial_xi);
        let initial = job.initial_plan();
        let planner = Planner::new(job, initial, policy).map_err(|e| {
            InvalidSetting::new("mpc.planner", "thread", format!("cannot start: {e}"))
        })?;
        Ok(Self {
            task: task.clone(),
            settings: *settings,
            model,
            profile,
            planner,
            ticks_per_plan,
            ticks: 0,
            normal_speed: 0.0,
            tangential_speed: 0.0,
            depth_at_fracture: None,
            budget: BladeBudget::new(task.blade_budget),
            shaper,
            stroke: SawingStroke::new(settings.max_reversals),
            saw: false,
            stats: MpcStats::default(),
            replanned: false,
            estimator: settings.estimate.then(|| {
                ScaleEstimator::new(
                    ESTIMATOR_PRIOR_VARIANCE,
                    settings.forgetting,
                    ESTIMATOR_RELATIVE_ERROR,
                )
            }),
            tare: WrenchTare::new(WrenchTareSettings::default())?,
            fracture: FractureDetector::new(FractureSettings::default())?,
            touch: TouchDetector::new(TouchSettings::default())?,
            depth: 0.0,
            telemetry: ControllerTelemetry::default(),
        })
    }

    /// Plan counters.
    pub fn stats(&self) -> &MpcStats {
        &self.stats
    }

    /// Whether the last tick asked for a plan.
    pub fn replanned(&self) -> bool {
        self.replanned
    }

    /// The sawing state: direction, reversals, the reversal under way.
    pub fn stroke(&self) -> &SawingStroke {
        &self.stroke
    }

    /// The plan in force: its ratios, stage by stage.
    pub fn plan(&self) -> &[f64] {
        &self.planner.plan().plan.xi
    }

    /// The plan in force: its times per unit depth τ (s/m), stage by stage
    /// (0 before the first solved plan); its first stage's normal speed is
    /// 1/τ₀ within the speed limit.
    pub fn plan_times(&self) -> &[f64] {
        &self.planner.plan().plan.tau
    }

    /// The scale factors (toughness, stiffness, friction) believed now.
    pub fn scale(&self) -> [f64; 3] {
        self.estimator
            .as_ref()
            .map_or([1.0; 3], ScaleEstimator::factors)
    }

    /// The blade the first plan from the intact object asks for per unit
    /// depth: its mean slice-push ratio Σ Δd_k ξ_k / Σ Δd_k over the whole
    /// cut (with the sawing strokes it plans, if they pay), for an MPC of
    /// these arguments ([`Mpc::new`]'s). A plant plans its contact arc and
    /// first sections for a direction of motion; this is the one the MPC
    /// is going to cut along. Successive plans re-linearise within a trust
    /// region, so it replans (at most [`FIRST_PLAN_ITERATIONS`] times)
    /// until the plan settles. Plans here, on the caller's thread, with the
    /// knife frame origin at world z = `knife_z` (m; where the edge meets
    /// the object matters along an inclined edge,
    /// [`MpcSettings::edge_inclination`]).
    ///
    /// # Errors
    /// Invalid settings or task.
    pub fn planned_ratio_from_rest(
        task: &CutTask,
        settings: &MpcSettings,
        model: M,
        profile: DepthProfile,
        initial_xi: f64,
        knife_z: f64,
    ) -> Result<f64, InvalidSetting> {
        task.validate()?;
        settings.validate().map_err(|e| e.prefixed("mpc"))?;
        let mut job = MpcPlanJob::new(task, settings, model, profile, initial_xi);
        let mut plan = job.initial_plan();
        let budget = BladeBudget::new(task.blade_budget);
        let request = PlanRequest {
            edge_depth: 0.0,
            remaining: task.target_depth,
            fractured: false,
            depth_at_fracture: None,
            scale: [1.0; 3],
            blade_left: budget.remaining_towards(1.0),
            stroke_length: budget.stroke_length(),
            reversals_left: settings.max_reversals,
            normal_speed: 0.0,
            tangential_speed: 0.0,
            normal_limit: normal_speed_limit(task, settings, settings.estimate, false),
            knife_z,
            direction: 1.0,
        };
        let mean = |xi: &[f64]| xi.iter().sum::<f64>() / xi.len() as f64;
        let mut last = f64::NAN;
        for _ in 0..FIRST_PLAN_ITERATIONS {
            job.plan(&request, &mut plan);
            let now = mean(&plan.xi);
            if (now - last).abs() < 1e-4 {
                break;
            }
            last = now;
        }
        Ok(mean(&plan.xi))
    }

    /// Feeds the measured forces per unit length of edge in contact to the
    /// estimator, with the model of them at the executed ξ, the current
    /// state and the estimator's factors: during the indentation (which
    /// identifies the stiffness), from the observed touch on, and after the
    /// first fracture.
    fn estimate(&mut self, m: &ArmReading, l: f64, fractured: bool) {
        let Some(estimator) = self.estimator.as_mut() else {
            return;
        };
        let w = self.tare.tared(&m.wrench);
        let noise = self.tare.sigma()[1];
        let touched = self.tare.frozen()
            && self
                .touch
                .observe(m.time, &m.position, w[1], noise)
                .is_some();
        if !touched {
            return;
        }
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
        let force = [w[1], -w[2] * m.velocity.z.signum()];
        if fractured {
            let per_length = [
                Some(force[0] / l),
                (m.velocity.z != 0.0).then(|| force[1] / l),
            ];
            estimator.observe_cut(per_length, model);
        } else {
            estimator.observe_indentation(l, force.map(|f| f / l), model, noise);
        }
    }

    /// Takes the plan that arrived this tick: its velocity target and
    /// counters.
    fn apply(&mut self) {
        let p: &MpcPlan = self.planner.plan().plan;
        let (v_n, v_t, saw) = (p.normal_speed, p.tangential_speed, p.saw);
        let (solves, fallback, status, iterations) = (p.solves, p.fallback, p.status, p.iterations);
        self.normal_speed = v_n;
        self.tangential_speed = v_t;
        self.saw = saw;
        self.stats.plans += 1;
        self.stats.solves += u64::from(solves);
        self.stats.fallbacks += u64::from(fallback);
        self.stats.last_status = status;
        self.stats.last_iterations = iterations;
        self.stats.max_iterations = self.stats.max_iterations.max(iterations);
    }

    /// The request for a plan from the state after this tick's reading.
    fn request(&self, fractured: bool, knife_z: f64) -> PlanRequest {
        PlanRequest {
            edge_depth: self.depth,
            remaining: (self.task.target_depth - self.depth).max(MIN_PLANNED_TRAVEL),
            fractured,
            depth_at_fracture: self.depth_at_fracture,
            scale: self.scale(),
            blade_left: self.budget.remaining_towards(self.stroke.direction()),
            stroke_length: self.budget.stroke_length(),
            reversals_left: self.stroke.reversals_left(),
            normal_speed: self.normal_speed,
            tangential_speed: self.tangential_speed,
            normal_limit: normal_speed_limit(
                &self.task,
                &self.settings,
                self.estimator.is_some(),
                self.depth_at_fracture.is_some(),
            ),
            knife_z,
            direction: self.stroke.direction(),
        }
    }
}

/// The normal speed allowed, m/s: the arm's, or while estimating before the
/// first fracture the guarded touch's ([`MpcSettings::touch_speed`]), so
/// that the indentation, which alone identifies the stiffness, spans many
/// ticks.
fn normal_speed_limit(
    task: &CutTask,
    settings: &MpcSettings,
    estimating: bool,
    fractured: bool,
) -> f64 {
    let l = task.limits.normal_speed;
    if estimating && !fractured {
        l.min(settings.touch_speed)
    } else {
        l
    }
}

impl<M: SliceModel + Clone + Send + 'static> Controller for Mpc<M> {
    fn name(&self) -> &str {
        "mpc"
    }

    fn tick(&mut self, m: &ArmReading) -> KnifeCommand {
        if matches!(m.status, ArmStatus::LimitViolation(_)) {
            self.shaper.resync(&m.velocity);
        }
        self.budget.observe(m);
        let clearance = self.task.clearance(&m.position);
        self.depth = EdgeOutline::penetration(clearance);
        self.tare.observe(&m.wrench, clearance);
        let contact = self.task.contact_length(&m.position);
        if clearance <= 0.0 {
            let force = self.tare.tared(&m.wrench)[1];
            self.fracture
                .observe(m.time, &m.position, force, self.tare.sigma()[1]);
        }
        let fractured = self.fracture.fracture().is_some();
        if fractured && self.depth_at_fracture.is_none() {
            self.depth_at_fracture = Some(self.profile.section_depth(self.depth));
            // E is identified by the indentation before the first fracture;
            // after it, toughness and stiffness are nearly collinear.
            if let Some(estimator) = self.estimator.as_mut() {
                estimator.freeze_stiffness();
            }
        }
        self.estimate(m, contact, fractured);
        let done = self.task.reached(self.depth);
        // The plan due now (lockstep) or the newest (realtime).
        let arrived = self.planner.poll().fresh;
        self.replanned = !done
            && self.ticks.is_multiple_of(self.ticks_per_plan)
            && self.planner.submit(&self.request(fractured, m.position.z))
                == SubmitStatus::Accepted;
        // Inline plans arrive in the submit.
        if arrived || self.planner.plan().fresh {
            self.apply();
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

    fn solve_times_us(&self) -> Vec<f64> {
        self.planner.solve_times_us()
    }
}
