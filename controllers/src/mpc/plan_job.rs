//! The MPC's planning half: one convexified subproblem per plan, run off
//! the servo tick by a [`Planner`](crate::planner::Planner).

use std::sync::Arc;

use super::depth_profile::DepthProfile;
use super::depth_qp::{DepthQp, EnteringEdge, QpLimits, QpStatus, StageData};
use super::settings::{MAX_STAGES, MpcSettings};
use super::slice_model::{SliceModel, StageState};
use crate::controller::{CutTask, MotionLimits, stopping_distance, stopping_duration};
use crate::observer::{EdgeOutline, INCLINATION_BINS};
use crate::planner::PlanJob;

/// What the servo tick knows when it asks for a plan.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PlanRequest {
    /// The edge's depth below the touch point, m.
    pub edge_depth: f64,
    /// Edge travel the plan covers, m: what is left to the target depth,
    /// and at least a millimetre (the crack's place near the target is
    /// uncertain by about that much).
    pub remaining: f64,
    /// Whether the first fracture has been seen.
    pub fractured: bool,
    /// The sections' mean depth at the first fracture, m.
    pub depth_at_fracture: Option<f64>,
    /// Scale factors (toughness, stiffness, friction) believed now.
    pub scale: [f64; 3],
    /// Blade left in the current stroke's direction, m.
    pub blade_left: f64,
    /// Length of a full sawing stroke, m.
    pub stroke_length: f64,
    /// Sawing reversals still allowed.
    pub reversals_left: u32,
    /// Normal speed commanded now, m/s.
    pub normal_speed: f64,
    /// Tangential speed commanded now, m/s.
    pub tangential_speed: f64,
    /// The normal speed allowed now, m/s (the guarded touch's before the
    /// first fracture while estimating).
    pub normal_limit: f64,
    /// The knife frame origin's world z now, m (the arm's pose).
    pub knife_z: f64,
    /// The current stroke's direction along world z (+1 or −1).
    pub direction: f64,
}

/// A plan: ξ and τ per stage from the edge's depth `origin`, and the
/// velocity target of its first stage. `clone_from` reuses the target's
/// buffers (a plan is copied into the planner's preallocated slots on every
/// plan).
#[derive(Debug, PartialEq)]
pub struct MpcPlan {
    /// Slice-push ratio per stage.
    pub xi: Vec<f64>,
    /// Time per unit depth per stage, s/m (0 before the first solved plan).
    pub tau: Vec<f64>,
    /// The edge's depth where the stages start, m.
    pub origin: f64,
    /// Depth of each stage, m (0 before the first solved plan).
    pub step: f64,
    /// Normal speed to command, m/s.
    pub normal_speed: f64,
    /// Tangential speed magnitude to command, m/s.
    pub tangential_speed: f64,
    /// Whether the plan saws (needs more blade than the stroke has).
    pub saw: bool,
    /// Status of the plan's subproblem (`None` for the initial plan).
    pub status: Option<QpStatus>,
    /// Whether the plan fell back to the previous one, shifted.
    pub fallback: bool,
    /// Subproblems solved for it.
    pub solves: u32,
    /// Interior-point iterations of its last solve.
    pub iterations: u32,
}

impl Clone for MpcPlan {
    fn clone(&self) -> Self {
        Self {
            xi: self.xi.clone(),
            tau: self.tau.clone(),
            ..*self
        }
    }

    fn clone_from(&mut self, source: &Self) {
        let (mut xi, mut tau) = (std::mem::take(&mut self.xi), std::mem::take(&mut self.tau));
        xi.clone_from(&source.xi);
        tau.clone_from(&source.tau);
        *self = Self { xi, tau, ..*source };
    }
}

impl MpcPlan {
    /// The plan before any solve: ξ = `xi0` at every one of `n` stages,
    /// at rest.
    pub fn initial(n: usize, xi0: f64) -> Self {
        Self {
            xi: vec![xi0; n],
            tau: vec![0.0; n],
            origin: 0.0,
            step: 0.0,
            normal_speed: 0.0,
            tangential_speed: 0.0,
            saw: false,
            status: None,
            fallback: false,
            solves: 0,
            iterations: 0,
        }
    }
}

/// The MPC's planning half (DESIGN §4): owns the model, the object's
/// profile and the persistent subproblem; each plan linearises the model
/// around the previous plan (a real-time iteration with a trust region)
/// and solves [`DepthQp`], twice when sawing is considered.
///
/// ## Memory allocation
/// Everything at construction (n stages); a plan allocates nothing in our
/// code (clarabel 0.11.1 allocates one block per solve in its timers).
pub struct MpcPlanJob<M: SliceModel> {
    /// The task's motion limits.
    motion: MotionLimits,
    /// The task's edge against the object's outline (for the edge's
    /// inclination, [`MpcSettings::edge_inclination`]).
    outline: Arc<EdgeOutline>,
    settings: MpcSettings,
    model: M,
    profile: DepthProfile,
    qp: DepthQp,
    limits: QpLimits,
    stages: Vec<StageData>,
    /// The previous plan: the linearisation point, and the fallback.
    last: MpcPlan,
    /// The plan within the current stroke while the sawing plan is solved.
    stroke_xi: Vec<f64>,
    stroke_tau: Vec<f64>,
    /// The finish's price per unit of each stage's slide this plan, J/m
    /// ([`Self::price_finish`]; 0 when not priced).
    finish_rate: f64,
}

impl<M: SliceModel> MpcPlanJob<M> {
    /// The job for `task` with `model` of the material and `profile` of the
    /// object, starting from ξ = `initial_xi` at every stage (settings and
    /// task already validated).
    pub fn new(
        task: &CutTask,
        settings: &MpcSettings,
        model: M,
        profile: DepthProfile,
        initial_xi: f64,
    ) -> Self {
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
        Self {
            motion: task.limits,
            outline: Arc::clone(&task.outline),
            settings: *settings,
            model,
            profile,
            qp: DepthQp::new(n, settings.max_iterations),
            limits,
            stages: vec![StageData::default(); n],
            last: MpcPlan::initial(n, initial_xi.clamp(0.0, settings.max_slice_push_ratio)),
            stroke_xi: vec![0.0; n],
            stroke_tau: vec![0.0; n],
            finish_rate: 0.0,
        }
    }

    /// The plan the job starts from.
    pub fn initial_plan(&self) -> MpcPlan {
        self.last.clone()
    }

    /// The last plan made.
    pub fn last_plan(&self) -> &MpcPlan {
        &self.last
    }

    /// Plans from the edge's depth `r.edge_depth` for the cut to deepen by
    /// `r.remaining` (m).
    ///
    /// The stages split the edge's remaining travel; each stage's model
    /// state is the sections' mean depth there
    /// ([`DepthProfile::section_depth`]), and its work is per unit of the
    /// edge's travel.
    fn replan(&mut self, r: &PlanRequest) {
        let n = self.settings.stages;
        let d0 = r.edge_depth;
        let remaining = r.remaining;
        let fractured = r.fractured;
        let dd = remaining.max(1e-6) / n as f64;
        let since = r.depth_at_fracture;
        let section_depth = |d: f64| self.profile.section_depth(d);
        let s0 = section_depth(d0);
        let [t, st, f] = r.scale;
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
            self.model.catch_up_span(self.last.xi[0], &first)
        };
        // The tangential travel the plan makes before a stage's middle, m.
        let mut slide = 0.0;
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
            let xi_bar = self.last.xi[k];
            let before_fracture = !fractured && k == 0;
            // Edge entering contact over the stage; before the first
            // fracture the first stage's onset term covers all its contact.
            let entering_length = if before_fracture {
                0.0
            } else {
                let start = d0 + k as f64 * dd;
                (self.profile.contact_length(start + dd) - self.profile.contact_length(start))
                    .max(0.0)
            };
            let slopes = if self.settings.edge_inclination {
                let z = r.knife_z + r.direction * (slide + 0.5 * xi_bar * dd);
                contact_slopes(&self.outline, z, edge, r.direction)
            } else {
                None
            };
            let profile = &self.profile;
            let model = &self.model;
            // The edge entering contact is at the contact's two ends, each
            // indented at its own local ratio.
            let entering = if entering_length > 0.0 && self.limits.deformation_weight > 0.0 {
                let deflection_at = |xi: f64| {
                    let (deflection, slope) = model.onset_deflection(xi, &state);
                    [deflection, slope, 0.0]
                };
                let [deflection, deflection_slope, _] = slopes
                    .and_then(|s| s.mean_at_ends(xi_bar, deflection_at))
                    .unwrap_or_else(|| deflection_at(xi_bar));
                EnteringEdge {
                    length: entering_length,
                    deflection,
                    deflection_slope,
                }
            } else {
                EnteringEdge::default()
            };
            let onset_at =
                |xi: f64| model.onset_cost(xi, &state, |d| profile.contact_at_section_depth(d));
            let onset = if !before_fracture {
                [0.0; 3]
            } else if let Some(o) = slopes.and_then(|s| s.mean(xi_bar, false, onset_at)) {
                o
            } else {
                onset_at(xi_bar)
            };
            let mut cost = model.stage(xi_bar, &state);
            let rates = |xi: f64| {
                let c = model.stage(xi, &state);
                [
                    c.work_per_depth,
                    c.work_per_depth_slope,
                    c.work_per_depth_curvature,
                ]
            };
            let mut edge_descent_slope = 0.0;
            if let Some(s) = slopes
                && let Some([w, g, h]) = s.mean(xi_bar, true, rates)
            {
                cost.work_per_depth = w;
                cost.work_per_depth_slope = g;
                cost.work_per_depth_curvature = h;
                edge_descent_slope = s.deepest;
                if before_fracture {
                    // The whole contact is indented, each share at its own
                    // local ratio.
                    let indentation = |xi: f64| {
                        let c = model.stage(xi, &state);
                        [c.deformation, c.deformation_slope, 0.0]
                    };
                    if let Some([d, d1, _]) = s.mean(xi_bar, false, indentation) {
                        cost.deformation = d;
                        cost.deformation_slope = d1;
                    }
                }
            }
            slide += xi_bar * dd;
            self.stages[k] = StageData {
                depth_step: dd,
                contact_length: self.profile.contact_length(edge),
                xi_bar,
                cost,
                before_fracture,
                onset,
                entering,
                edge_descent_slope,
                finish_slope: 0.0,
            };
        }
        self.finish_rate = 0.0;
        if self.settings.finish_gap {
            self.price_finish(r.knife_z, r.direction, d0 + remaining, r.blade_left);
        }
        let l = self.motion;
        // Keep what stopping at the current tangential speed needs.
        let reserve = stopping_distance(r.tangential_speed, l.acceleration, l.jerk);
        let blade = (r.blade_left - reserve).max(0.0);
        let previous = self.last.xi[0];
        let mut status = self.qp.solve(&self.stages, &self.limits, previous, blade);
        self.last.solves = 1;
        self.last.iterations = self.qp.iterations();
        let within = status == QpStatus::Solved;
        if within {
            self.stroke_xi.copy_from_slice(self.qp.xi());
            self.stroke_tau.copy_from_slice(self.qp.tau());
        }
        let saw = r.reversals_left > 0 && self.sawing_pays(r, previous, blade, within);
        if within && !saw && self.holding_pays(previous, blade) {
            self.stroke_xi.fill(previous);
        }
        if saw {
            status = QpStatus::Solved;
            self.stroke_xi.copy_from_slice(self.qp.xi());
            self.stroke_tau.copy_from_slice(self.qp.tau());
        }
        let plan = &mut self.last;
        plan.saw = saw;
        plan.status = Some(status);
        plan.fallback = status != QpStatus::Solved;
        if status == QpStatus::Solved {
            plan.xi.copy_from_slice(&self.stroke_xi);
            plan.tau.copy_from_slice(&self.stroke_tau);
            plan.origin = d0;
            plan.step = dd;
            plan.normal_speed = (1.0 / plan.tau[0]).min(r.normal_limit);
            plan.tangential_speed = (plan.xi[0] * plan.normal_speed).min(l.tangential_speed);
        } else {
            shift_plan(plan, d0);
            // The trust region around a plan that no longer fits the blade
            // (after the last allowed reversal, say) leaves the next
            // subproblem infeasible too: linearise it around ratios that fit.
            let cap = blade / remaining;
            for x in &mut plan.xi {
                *x = x.min(cap);
            }
            plan.normal_speed = if plan.step == 0.0 {
                // No plan yet: start at the initial plan's ratio, full speed.
                r.normal_limit
                    .min(l.tangential_speed / plan.xi[0].max(1e-12))
            } else {
                // The shifted plan's stage under the edge now.
                (1.0 / plan.tau[0]).min(r.normal_limit)
            };
            plan.tangential_speed = (plan.xi[0] * plan.normal_speed).min(l.tangential_speed);
        }
    }

    /// Sets each stage's [`StageData::finish_slope`]
    /// ([`MpcSettings::finish_gap`]): with the knife frame origin at world
    /// z = `knife_z` now, sliding along `direction`, and the horizon ending
    /// at the edge's depth `end_depth` (m), the plan's slide at ξ̄ puts the
    /// knife at z_e = `knife_z` + direction·Σ_k ξ̄_k Δz_k there (at most the
    /// `blade` m left in the stroke). The
    /// sections' mean depth then falls short of the edge's by the gap
    /// g(z_e) = `end_depth` − [`EdgeOutline::mean_cut_depth`], which the edge
    /// travels on past the horizon at the last stage's price p = L·w per
    /// unit of its depth. Linearised: stage k's ratio costs
    /// p·g′(z_e)·direction·Δz_k per unit (g′ by central differences over
    /// ±[`FINISH_PROBE`]); 0 where the gap is not defined.
    fn price_finish(&mut self, knife_z: f64, direction: f64, end_depth: f64, blade: f64) {
        let planned: f64 = self.stages.iter().map(|s| s.blade(s.xi_bar)).sum();
        let slide = planned.min(blade.max(0.0));
        let z_end = knife_z + direction * slide;
        let outline = &self.outline;
        let gap = |z: f64| {
            let y = outline.touch_height(z)? - end_depth;
            Some(end_depth - outline.mean_cut_depth(z, y)?)
        };
        let slope = match (gap(z_end + FINISH_PROBE), gap(z_end - FINISH_PROBE)) {
            (Some(ahead), Some(behind)) => (ahead - behind) / (2.0 * FINISH_PROBE),
            _ => return,
        };
        let last = &self.stages[self.stages.len() - 1];
        let price = last.contact_length * last.cost.work_per_depth;
        self.set_finish(price * slope * direction);
    }

    /// Sets each stage's finish slope to `rate` (J per m of the knife's
    /// travel along z, signed with the direction of motion) times its
    /// descent, and keeps `rate`.
    fn set_finish(&mut self, rate: f64) {
        self.finish_rate = rate;
        for s in &mut self.stages {
            s.finish_slope = rate * s.knife_descent();
        }
    }

    /// Whether holding the ratio `previous` over every stage, at the solved
    /// plan's times (slowed where the tangential speed limit needs it),
    /// costs less than [`MpcSettings::min_saving`] of the solved plan's
    /// objective more than that plan, within the `blade` m left. True
    /// leaves the hold's times in `stroke_tau`.
    fn holding_pays(&mut self, previous: f64, blade: f64) -> bool {
        let fraction = self.settings.min_saving;
        if fraction <= 0.0 {
            return false;
        }
        let demand: f64 = self.stages.iter().map(|s| s.blade(previous)).sum();
        if demand > blade {
            return false;
        }
        let plan = DepthQp::objective(
            &self.stages,
            &self.limits,
            previous,
            &self.stroke_xi,
            &self.stroke_tau,
        );
        let slowest = previous / self.limits.tangential_speed.max(f64::MIN_POSITIVE);
        let n = self.stages.len();
        let mut hold_tau = [0.0; MAX_STAGES];
        let hold_tau = &mut hold_tau[..n];
        for (t, s) in hold_tau.iter_mut().zip(&self.stroke_tau) {
            *t = s.max(slowest);
        }
        let hold_xi = [previous; MAX_STAGES];
        let hold = DepthQp::objective(
            &self.stages,
            &self.limits,
            previous,
            &hold_xi[..n],
            hold_tau,
        );
        if hold - plan < fraction * plan.abs() {
            self.stroke_tau.copy_from_slice(hold_tau);
            true
        } else {
            false
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
    fn sawing_pays(&mut self, r: &PlanRequest, previous: f64, blade: f64, within: bool) -> bool {
        // Strokes go back and forth: a sawing plan does not move the object
        // along the edge for good, so the finish's price
        // ([`Self::price_finish`]) is not its to claim, and both plans are
        // compared without it.
        let finish = self.finish_rate;
        if finish == 0.0 {
            return self.sawing_beats(r, previous, blade, within);
        }
        self.set_finish(0.0);
        let pays = self.sawing_beats(r, previous, blade, within);
        self.set_finish(finish);
        pays
    }

    /// [`Self::sawing_pays`] with the stages as they stand.
    fn sawing_beats(&mut self, r: &PlanRequest, previous: f64, blade: f64, within: bool) -> bool {
        let demand = |stages: &[StageData], xi: &[f64]| -> f64 {
            stages.iter().zip(xi).map(|(s, x)| s.blade(*x)).sum()
        };
        if within && demand(&self.stages, &self.stroke_xi) < blade * (1.0 - 1e-6) {
            return false;
        }
        let stroke = 0.98 * r.stroke_length;
        let extra = f64::from(r.reversals_left) * stroke;
        self.last.solves += 1;
        if self
            .qp
            .solve(&self.stages, &self.limits, previous, blade + extra)
            != QpStatus::Solved
        {
            return false;
        }
        self.last.iterations = self.qp.iterations();
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
        let l = &self.motion;
        let speed = r.normal_speed.hypot(r.tangential_speed).max(l.normal_speed);
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

/// The edge in contact with the knife frame origin at world `z`, the edge
/// `edge_depth` (m) deep, moving along `direction` (±1 in world z): the
/// slope κ of each share of the contact and κ_d at the deepest point, each
/// times `direction` (so that a point of slope κ descends at 1 + κξ times
/// the knife's descent). `None` where the edge does not meet the outline
/// at `z`.
fn contact_slopes(
    outline: &EdgeOutline,
    z: f64,
    edge_depth: f64,
    direction: f64,
) -> Option<Slopes> {
    let y = outline.touch_height(z)? - edge_depth;
    let inclination = outline.contact_inclination(z, y);
    Some(Slopes {
        shares: inclination.bins.map(|k| direction * k),
        deepest: direction * inclination.deepest,
    })
}

/// Half the span over which [`MpcPlanJob::price_finish`] differentiates the
/// finishing gap along z, m: wide against the edge's 0.5 mm samples (the
/// touch height is the deepest sample's, so the gap steps by up to a few
/// hundredths of a millimetre as a sample crosses the outline's end), narrow
/// against a chef's rise (140 mm).
const FINISH_PROBE: f64 = 5e-3;

/// The contact's slopes along the direction of motion ([`contact_slopes`]).
#[derive(Debug, Clone, Copy)]
struct Slopes {
    shares: [f64; INCLINATION_BINS],
    deepest: f64,
}

impl Slopes {
    /// The mean over the shares of the contact of m(ξ)·f(|x(ξ)|) and its
    /// first and second derivatives in ξ at the commanded ratio `xi`, by
    /// the chain rule from `f`'s value and derivatives at the local ratio
    /// (`f(x)` = [f, f′, f″] at x ≥ 0): each share of slope κ is cut at
    /// x = (ξ − κ)/(1 + κξ) (seed 000 §IV, Fig. 4(a)); with `per_depth`, m
    /// = (1 + κξ)/(1 + κ_d ξ), the share's descent per unit of the edge's
    /// depth (a rate per unit depth), else m = 1 (a cost per unit length).
    /// `None` if a share, or the deepest point, does not move into the
    /// material at `xi` (1 + κξ ≤ 0).
    fn mean<F: Fn(f64) -> [f64; 3]>(&self, xi: f64, per_depth: bool, f: F) -> Option<[f64; 3]> {
        mean_over(&self.shares, per_depth.then_some(self.deepest), xi, f)
    }

    /// [`Self::mean`] of a cost per unit length over the contact's first
    /// and last shares, where the contact's ends lie (the edge that comes
    /// into contact as the edge deepens).
    fn mean_at_ends<F: Fn(f64) -> [f64; 3]>(&self, xi: f64, f: F) -> Option<[f64; 3]> {
        let ends = [self.shares[0], self.shares[INCLINATION_BINS - 1]];
        mean_over(&ends, None, xi, f)
    }
}

/// [`Slopes::mean`] over the slopes `shares` (equal shares of some length
/// of edge): a rate per unit of the edge's depth with `deepest` the slope
/// κ_d at the deepest point, a cost per unit length with `None`.
fn mean_over<F: Fn(f64) -> [f64; 3]>(
    shares: &[f64],
    deepest: Option<f64>,
    xi: f64,
    f: F,
) -> Option<[f64; 3]> {
    let per_depth = deepest.is_some();
    let kd = deepest.unwrap_or(0.0);
    let qd = 1.0 + kd * xi;
    if qd <= 0.0 {
        return None;
    }
    let mut sum = [0.0; 3];
    for &k in shares {
        let q = 1.0 + k * xi;
        if q <= 0.0 {
            return None;
        }
        let x = (xi - k) / q;
        let sign = if x < 0.0 { -1.0 } else { 1.0 };
        let [w, w1, w2] = f(x.abs());
        let w1 = sign * w1;
        let x1 = (1.0 + k * k) / (q * q);
        let x2 = -2.0 * k * (1.0 + k * k) / (q * q * q);
        let (m, m1, m2) = if per_depth {
            (
                q / qd,
                (k - kd) / (qd * qd),
                -2.0 * kd * (k - kd) / (qd * qd * qd),
            )
        } else {
            (1.0, 0.0, 0.0)
        };
        sum[0] += m * w;
        sum[1] += m1 * w + m * w1 * x1;
        sum[2] += m2 * w + 2.0 * m1 * w1 * x1 + m * (w2 * x1 * x1 + w1 * x2);
    }
    Some(sum.map(|v| v / shares.len() as f64))
}

/// The fallback's plan: the last solved plan shifted to the edge's depth
/// `d0`, so that its first stage is the one the edge is in (stages past
/// the plan's end repeat its last). Nothing before the first solved plan.
fn shift_plan(plan: &mut MpcPlan, d0: f64) {
    if plan.step <= 0.0 {
        return;
    }
    let n = plan.xi.len();
    let passed = ((d0 - plan.origin) / plan.step).floor();
    let j = if passed.is_finite() {
        passed.clamp(0.0, (n - 1) as f64) as usize
    } else {
        0
    };
    if j == 0 {
        return;
    }
    for stages in [&mut plan.xi, &mut plan.tau] {
        stages.copy_within(j.., 0);
        let last = stages[n - 1 - j];
        stages[n - j..].fill(last);
    }
    plan.origin += j as f64 * plan.step;
}

impl<M: SliceModel + Send + 'static> PlanJob for MpcPlanJob<M> {
    type Request = PlanRequest;
    type Plan = MpcPlan;

    fn plan(&mut self, request: &PlanRequest, out: &mut MpcPlan) {
        self.replan(request);
        out.clone_from(&self.last);
    }
}

#[cfg(test)]
mod tests {
    use super::{INCLINATION_BINS, Slopes};

    /// A smooth even work law w(x) = a + b·x² + c·x⁴ with its derivatives.
    fn law(x: f64) -> [f64; 3] {
        let (a, b, c) = (100.0, -30.0, 8.0);
        [
            a + b * x * x + c * x.powi(4),
            2.0 * b * x + 4.0 * c * x.powi(3),
            2.0 * b + 12.0 * c * x * x,
        ]
    }

    #[test]
    fn a_level_edge_is_cut_at_the_commanded_ratio() {
        let level = Slopes {
            shares: [0.0; INCLINATION_BINS],
            deepest: 0.0,
        };
        for xi in [0.0, 0.3, 1.2] {
            let got = level.mean(xi, true, law).unwrap();
            for (a, b) in got.iter().zip(law(xi)) {
                // The mean of four equal terms, to rounding.
                assert!((a - b).abs() <= 1e-14 * b.abs(), "ξ = {xi}: {got:?}");
            }
        }
    }

    #[test]
    fn an_inclined_edge_is_cut_at_the_local_ratio_and_its_derivatives_agree() {
        let inclined = Slopes {
            shares: [0.05, 0.15, 0.25, 0.35],
            deepest: 0.05,
        };
        // Pressing along a rising edge slices it locally: a share of slope κ
        // is cut at |−κ| and descends as fast as the knife.
        let [w0, _, _] = inclined.mean(0.0, true, law).unwrap();
        let expected: f64 = inclined.shares.iter().map(|k| law(*k)[0]).sum::<f64>() / 4.0;
        assert!((w0 - expected).abs() < 1e-12, "{w0} against {expected}");
        // Central differences of the value and the slope (away from the
        // local ratio's kink at ξ = κ).
        let h = 1e-5;
        for xi in [0.5, 0.9] {
            let at = |x: f64| inclined.mean(x, true, law).unwrap();
            let [_, g, c] = at(xi);
            let g_fd = (at(xi + h)[0] - at(xi - h)[0]) / (2.0 * h);
            let c_fd = (at(xi + h)[1] - at(xi - h)[1]) / (2.0 * h);
            assert!(
                (g - g_fd).abs() < 1e-6 * (1.0 + g.abs()),
                "ξ = {xi}: {g} against {g_fd}"
            );
            assert!(
                (c - c_fd).abs() < 1e-5 * (1.0 + c.abs()),
                "ξ = {xi}: {c} against {c_fd}"
            );
        }
        // The contact's ends (its first and last shares) are indented at
        // their own local ratios.
        let [e0, _, _] = inclined.mean_at_ends(0.0, law).unwrap();
        let ends = 0.5 * (law(0.05)[0] + law(0.35)[0]);
        assert!((e0 - ends).abs() < 1e-12, "{e0} against {ends}");
        // A share that would move out of the material is refused.
        let steep = Slopes {
            shares: [-2.0; INCLINATION_BINS],
            deepest: 0.0,
        };
        assert_eq!(steep.mean(0.6, true, law), None);
    }
}
