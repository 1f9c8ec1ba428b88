//! What the MPC needs to know of the cutting model at one stage.

/// The cut's state at a stage, as the model sees it.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct StageState {
    /// Crack depth below the object's top at the stage, m.
    pub depth: f64,
    /// Height of the object's section at the cut, m.
    pub height: f64,
    /// Half width of the object's section across the cut, m.
    pub half_width: f64,
    /// Whether the material has fractured (the crack runs) by the stage.
    /// When not, the model answers with the cut's rates after fracture plus
    /// the cost of reaching the fracture (`onset_work`, `deformation`, and
    /// the peak force as `force_normal`).
    pub fractured: bool,
    /// Normal knife travel since the first fracture, m (friction grows with
    /// it). Before the first fracture (`fractured` false): the travel after
    /// it whose cost beyond the rate at its end the onset's cost includes
    /// ([`SliceModel::catch_up_span`]); the stage's rates are those there.
    pub travel_since_fracture: f64,
}

/// The model's answer at one ξ, per unit length of edge in contact.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct StageCost {
    /// Knife work per unit of normal travel, N/m (= J/m per m): F_n + ξ·F_t.
    pub work_per_depth: f64,
    /// Its derivative with respect to ξ.
    pub work_per_depth_slope: f64,
    /// Its second derivative with respect to ξ (may be negative where the
    /// model is not convex; the MPC convexifies).
    pub work_per_depth_curvature: f64,
    /// Vertical force, N/m.
    pub force_normal: f64,
    /// Its derivative with respect to ξ.
    pub force_normal_slope: f64,
    /// Surface deflection before fracture, m (0 once fractured).
    pub deformation: f64,
    /// Its derivative with respect to ξ.
    pub deformation_slope: f64,
    /// Before the first fracture: the knife work per unit length spent
    /// indenting until the material fractures, plus what the catch-up span
    /// after it costs beyond the rate at the span's end (negative when the
    /// crack's jump saves work), J/m (0 once fractured). The crack does not
    /// advance while indenting, so it is a cost of the first stage, not a
    /// rate per depth.
    pub onset_work: f64,
    /// Its derivative with respect to ξ.
    pub onset_work_slope: f64,
    /// Its second derivative with respect to ξ.
    pub onset_work_curvature: f64,
}

/// A force per unit length of edge the model predicts at given scale
/// factors, linearised in them (for the [`super::ScaleEstimator`]).
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct ForceModel {
    /// At the nominal material (all factors 1), N/m: the scale the
    /// estimator weighs the row's error by.
    pub nominal: f64,
    /// At the factors asked for, N/m.
    pub value: f64,
    /// The parts the factors (T, S, F·S) — toughness, stiffness and
    /// friction × stiffness — multiply there, N/m per unit factor: its
    /// derivatives with respect to them at a fixed ratio ℓ = ln(S/T). Where
    /// the wedge's terms depend on E/R_c, the parts are those at the ratio
    /// of the factors asked for; the estimator regresses on them and moves
    /// the ratio only through its estimate, not through the full Jacobian,
    /// whose ℓ-terms let a few per cent of model error in the tangential
    /// force drive the toughness (docs/controllers.md).
    pub gradient: [f64; 3],
}

/// A cutting model the MPC can plan with: cost and force per unit length
/// of edge as functions of the slice-push ratio ξ at a stage. Evaluation
/// must not allocate (it runs inside the controller's tick).
pub trait SliceModel {
    /// The model at `xi` in `state`.
    fn stage(&self, xi: f64, state: &StageState) -> StageCost;

    /// Before the first fracture: the normal travel after it, m, over which
    /// what a fracture at `xi` leads to (the crack's jump, the edge catching
    /// up with the tip) depends on the ratio at the fracture rather than on
    /// the ratios planned for those depths. The onset's cost includes that
    /// span, and the stages planned before the fracture are priced at the
    /// rates after it. 0 (the default) for a model without a catch-up.
    fn catch_up_span(&self, _xi: f64, _state: &StageState) -> f64 {
        0.0
    }

    /// Before the first fracture: what reaching it at `xi` from `state`
    /// costs for the whole edge, J, with its first and second derivatives
    /// with respect to ξ — the onset's cost ([`StageCost::onset_work`])
    /// with each depth's work weighted by the length of edge in contact
    /// there. `contact(depth)` is that length, m, when the sections' depth
    /// is `depth` (m). A whole object's contact grows while it is indented
    /// and over the catch-up span after the fracture, so a deep onset's
    /// cost and saving fall where more edge is in contact than at the
    /// first stage. The default weighs the per-length cost by the contact
    /// at the stage's depth.
    fn onset_cost<C: Fn(f64) -> f64>(&self, xi: f64, state: &StageState, contact: C) -> [f64; 3] {
        let c = self.stage(xi, state);
        let l = contact(state.depth);
        [
            l * c.onset_work,
            l * c.onset_work_slope,
            l * c.onset_work_curvature,
        ]
    }

    /// The surface deflection, m, at which intact material in `state`
    /// (read with `fractured` false and no depth cut) fractures when
    /// indented at `xi`, and its derivative with respect to ξ: what the edge
    /// that comes into contact after the first fracture is pushed down by
    /// before it cuts. (0, 0) (the default) for a model without it.
    fn onset_deflection(&self, _xi: f64, _state: &StageState) -> (f64, f64) {
        (0.0, 0.0)
    }

    /// The normal and tangential forces per unit length at `xi` in `state`
    /// for the scale factors `scale` (toughness, stiffness, friction),
    /// linearised in them (for the [`super::ScaleEstimator`]); `None` if the
    /// model cannot tell (no online estimation).
    fn force_model(
        &self,
        _xi: f64,
        _state: &StageState,
        _scale: [f64; 3],
    ) -> Option<[ForceModel; 2]> {
        None
    }

    /// Sets the scale factors (toughness, stiffness, friction) the model
    /// predicts with; ignored by models without them.
    fn set_scale(&mut self, _toughness: f64, _stiffness: f64, _friction: f64) {}
}
