//! `[controller.mpc]`: the MPC's horizon, weights and limits.

use serde::{Deserialize, Serialize};
use shearcut_sim::InvalidSetting;
use shearcut_sim::physical_range::{KNIFE_SPEED, PhysicalRange};

use crate::planner::PlannerSettings;

/// Most depth stages a plan may have ([`MpcSettings::stages`]).
pub const MAX_STAGES: usize = 200;

/// Most interior-point iterations a plan may take
/// ([`MpcSettings::max_iterations`]): the iteration cap is the plan's
/// deterministic time budget, and a bound keeps it one.
pub const MAX_ITERATIONS: u32 = 1000;

/// Most reversals of the stroke a cut may make
/// ([`MpcSettings::max_reversals`]).
pub const MAX_REVERSALS: u32 = 10_000;

/// Planning rate, Hz: at most the servo rate of an arm's loop.
const RATE: PhysicalRange = PhysicalRange::new(0.1, 1000.0, "Hz");
/// Largest planned slice-push ratio and the trust region (> 0, at most the
/// model's ratio range).
const RATIO_BOUND: PhysicalRange = PhysicalRange::new(1e-3, 20.0, "");
/// Weight of time, J/s.
const TIME_WEIGHT: PhysicalRange = PhysicalRange::new(0.0, 1e3, "J/s");
/// Weight of ξ changes, J.
const SMOOTHNESS_WEIGHT: PhysicalRange = PhysicalRange::new(0.0, 1e6, "J");
/// Weight of deflection × edge length, J/m².
const DEFORMATION_WEIGHT: PhysicalRange = PhysicalRange::new(0.0, 1e9, "J/m²");
/// Cost of a newton over the force limit, J/N.
const FORCE_PENALTY: PhysicalRange = PhysicalRange::new(0.0, 1e6, "J/N");
/// Vertical force limit, N.
const MAX_FORCE: PhysicalRange = PhysicalRange::new(1e-3, 1e4, "N");

/// Settings of the [`super::Mpc`].
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct MpcSettings {
    /// Planning rate, Hz (default 100); the trajectory generator fills the
    /// servo ticks in between.
    pub rate_hz: f64,
    /// Stages of the depth horizon (default 10): the remaining depth is
    /// split into this many equal stages, so the horizon always reaches the
    /// target depth (a shrinking horizon) and the blade budget is planned
    /// over the whole rest of the cut.
    pub stages: usize,
    /// Largest slice-push ratio planned (default 2.5).
    pub max_slice_push_ratio: f64,
    /// Trust region of the sequential convexification: |ξ − ξ̄| per stage
    /// around the previous plan (default 0.5).
    pub trust_region: f64,
    /// Weight of completion time, J/s (default 0.01): a second of cutting
    /// is worth this much work.
    pub time_weight: f64,
    /// Weight of stage-to-stage changes of ξ, J (default 1e-4 per unit ξ²).
    pub smoothness_weight: f64,
    /// Weight of surface deflection, J per m² of deflection × edge length
    /// (default 1): the deflection the edge in contact at the first
    /// fracture reaches before it, and that of each length of edge that
    /// comes into contact later and is indented until it fractures
    /// ([`super::DepthQp`]).
    pub deformation_weight: f64,
    /// Vertical force limit, N (default: none). Soft: a violation costs
    /// `force_penalty` per newton.
    pub max_force: Option<f64>,
    /// Cost of a newton above `max_force`, J/N (default 10).
    pub force_penalty: f64,
    /// Iteration cap of the interior-point solver per plan (default 40):
    /// the deterministic time budget; a plan that is not solved within it
    /// falls back to the previous plan, shifted.
    pub max_iterations: u32,
    /// Estimate the material's toughness, stiffness and friction scale
    /// factors online from the arm's reading ([`super::ScaleEstimator`])
    /// and plan with them (default false: how close the estimates come on
    /// plants off the preset, and what estimating saves or costs in work,
    /// are measured in docs/controllers.md).
    pub estimate: bool,
    /// Forgetting factor of the estimator per row (two rows per tick), in
    /// (0, 1] (default 1: none — the material of a cut is one, and
    /// forgetting lets the crack-jump sawtooth of the last few hundred
    /// ticks into the factors; 0.999 remembers about half a second at
    /// 1 kHz).
    pub forgetting: f64,
    /// Normal speed limit from the start until the first fracture while
    /// estimating, m/s (default 0.005; only with `estimate = true`): a
    /// guarded touch. The stiffness factor is identified only by the
    /// indentation before the first fracture (after it, toughness and
    /// stiffness are nearly collinear), which lasts a fraction of a
    /// millimetre of travel: at full speed a few servo ticks or none, at
    /// the default enough ticks for a fit (measured in docs/controllers.md,
    /// "Online estimation"). Costs the approach from rest at this speed.
    pub touch_speed: f64,
    /// Sawing: the most reversals of the tangential direction the MPC may
    /// make in one cut (default 16; 0 keeps the whole cut within one stroke
    /// of the blade budget). A plan uses strokes only if their cost (the
    /// time a reversal loses, at `time_weight`) is below the work they save.
    pub max_reversals: u32,
    /// Price each stage at the edge's local slice-push ratios (default
    /// false): where the edge in contact is inclined (a chef's edge along
    /// its rise), a point of slope κ is cut at the local ratio
    /// (ξ − κ)/(1 + κξ) and moves into the material at (1 + κξ) times the
    /// knife's descent (seed 000 §IV, Fig. 4(a); [`EdgeOutline::contact_inclination`](crate::observer::EdgeOutline::contact_inclination)),
    /// and the edge's depth grows at 1 + κ_d·ξ times the descent with κ_d
    /// the slope at its deepest point. The stage's work per unit of the
    /// edge's depth is then the mean over the contact of
    /// (1 + κξ)·w((ξ − κ)/(1 + κξ)) / (1 + κ_d ξ), from the task's edge and
    /// outline at the knife's pose, the slide the plan makes before the
    /// stage included; the indentation before the first fracture and the
    /// edge entering contact at the contact's ends deflect the material at
    /// their local ratios, and a stage's time and blade count the knife's
    /// descent, 1/(1 + κ_d ξ) of the edge's. With false every point is cut
    /// at ξ, as under a straight horizontal edge. Measured in
    /// docs/heldout.md.
    pub edge_inclination: bool,
    /// Smallest predicted saving for which a plan changes the ratio, as a
    /// fraction of the plan's predicted cost of the rest of the cut
    /// (default 0: every plan is followed). A plan whose objective is
    /// within this fraction of holding the last plan's first ratio over
    /// every stage is replaced by that hold: a change the model prices
    /// below its own resolution is not made. Measured in docs/heldout.md.
    pub min_saving: f64,
    /// Read the object's contact length under the knife's own edge at the
    /// knife's start pose (default false;
    /// [`DepthProfile::under_edge`](super::DepthProfile::under_edge)): the
    /// edge's length inside the object's outline at each depth of the edge,
    /// from the task's edge and outline. With false it is the chord of the
    /// outline, as a straight horizontal edge presses it. Measured in
    /// docs/heldout.md.
    pub edge_contact: bool,
    /// Price the cut's finish (default false): a run ends when the
    /// sections' mean depth reaches the target, and along a curved edge
    /// (a chef's rise over the object) the sections under its higher part
    /// lag the edge's deepest point, by a gap that depends on where the
    /// object lies along the edge. The slide a plan makes moves the object
    /// along the edge, so it changes that gap: the plan pays for the edge
    /// travel past its horizon's end that the gap needs, at the last
    /// stage's price per unit of the edge's depth, linearised in each
    /// stage's ratio ([`EdgeOutline::mean_cut_depth`](crate::observer::EdgeOutline::mean_cut_depth)
    /// at the plan's predicted end pose). Where the slide does not move
    /// the gap (a straight edge below a level top, the flat of a chef's
    /// edge) the price is zero.
    /// Measured in docs/heldout.md.
    pub finish_gap: bool,
    /// How plans reach the servo tick (`[controller.mpc.planner]`; default
    /// lockstep, one tick after their request).
    pub planner: PlannerSettings,
}

impl Default for MpcSettings {
    fn default() -> Self {
        Self {
            rate_hz: 100.0,
            stages: 10,
            max_slice_push_ratio: 2.5,
            trust_region: 0.5,
            time_weight: 0.01,
            smoothness_weight: 1e-4,
            deformation_weight: 1.0,
            max_force: None,
            force_penalty: 10.0,
            max_iterations: 40,
            estimate: false,
            forgetting: 1.0,
            touch_speed: 0.005,
            max_reversals: 16,
            edge_inclination: false,
            min_saving: 0.0,
            edge_contact: false,
            finish_gap: false,
            planner: PlannerSettings::default(),
        }
    }
}

impl MpcSettings {
    /// Checks every value, naming the key.
    pub fn validate(&self) -> Result<(), InvalidSetting> {
        for (key, range, v) in [
            ("rate_hz", RATE, self.rate_hz),
            (
                "max_slice_push_ratio",
                RATIO_BOUND,
                self.max_slice_push_ratio,
            ),
            ("trust_region", RATIO_BOUND, self.trust_region),
            ("touch_speed", KNIFE_SPEED, self.touch_speed),
            ("time_weight", TIME_WEIGHT, self.time_weight),
            (
                "smoothness_weight",
                SMOOTHNESS_WEIGHT,
                self.smoothness_weight,
            ),
            (
                "deformation_weight",
                DEFORMATION_WEIGHT,
                self.deformation_weight,
            ),
            ("force_penalty", FORCE_PENALTY, self.force_penalty),
        ] {
            range.check(key, v)?;
        }
        if !(self.min_saving.is_finite() && (0.0..=0.5).contains(&self.min_saving)) {
            return Err(InvalidSetting::new(
                "min_saving",
                self.min_saving,
                "in [0, 0.5] (a fraction of the plan's cost)",
            ));
        }
        if !(1..=MAX_STAGES).contains(&self.stages) {
            return Err(InvalidSetting::new("stages", self.stages, "in 1..=200"));
        }
        if !(self.forgetting > 0.0 && self.forgetting <= 1.0) {
            return Err(InvalidSetting::new(
                "forgetting",
                self.forgetting,
                "in (0, 1]",
            ));
        }
        if !(1..=MAX_ITERATIONS).contains(&self.max_iterations) {
            return Err(InvalidSetting::new(
                "max_iterations",
                self.max_iterations,
                format!("in 1..={MAX_ITERATIONS} (the plan's time budget)"),
            ));
        }
        if self.max_reversals > MAX_REVERSALS {
            return Err(InvalidSetting::new(
                "max_reversals",
                self.max_reversals,
                format!("in 0..={MAX_REVERSALS}"),
            ));
        }
        if let Some(f) = self.max_force {
            MAX_FORCE.check("max_force", f)?;
        }
        self.planner.policy().map_err(|e| e.prefixed("planner"))?;
        Ok(())
    }
}
