//! The fitted surrogate as the MPC's [`SliceModel`].

use shearcut_sim::surrogate::{CutState, ScaleFactors, Surrogate};

use super::slice_model::{SliceModel, StageCost, StageState};

/// Step of the central difference for the deflection's ξ-slope (the
/// surrogate gives the forces' and work's derivatives analytically, not
/// the deflection's).
const DEFLECTION_STEP: f64 = 1e-4;

/// A [`Surrogate`] (seed 000's model reduced by `shearcut fit`) with the
/// scale factors the estimator last set.
#[derive(Debug, Clone)]
pub struct SurrogateModel {
    surrogate: Surrogate,
    scale: ScaleFactors,
}

impl SurrogateModel {
    /// The surrogate at the nominal material (all factors 1).
    pub fn new(surrogate: Surrogate) -> Self {
        Self {
            surrogate,
            scale: ScaleFactors::default(),
        }
    }

    /// The surrogate.
    pub fn surrogate(&self) -> &Surrogate {
        &self.surrogate
    }

    fn cut_state(state: &StageState) -> CutState {
        CutState {
            depth: state.depth,
            height: state.height,
            half_width: state.half_width,
            fractured: state.fractured,
            travel_since_fracture: state.travel_since_fracture,
        }
    }
}

impl SliceModel for SurrogateModel {
    fn stage(&self, xi: f64, state: &StageState) -> StageCost {
        let cut = Self::cut_state(state);
        let o = self.surrogate.evaluate(xi, &cut, &self.scale);
        let deformation_slope = if state.fractured {
            0.0
        } else {
            let lo = (xi - DEFLECTION_STEP).max(0.0);
            let hi = xi + DEFLECTION_STEP;
            let d_lo = self.surrogate.evaluate(lo, &cut, &self.scale).deformation;
            let d_hi = self.surrogate.evaluate(hi, &cut, &self.scale).deformation;
            (d_hi - d_lo) / (hi - lo)
        };
        StageCost {
            work_per_depth: o.work_per_depth,
            work_per_depth_slope: o.work_per_depth_slope,
            work_per_depth_curvature: o.work_per_depth_curvature,
            force_normal: o.force_normal,
            force_normal_slope: o.force_normal_slope,
            deformation: if state.fractured { 0.0 } else { o.deformation },
            deformation_slope,
        }
    }

    fn force_parts(&self, xi: f64, state: &StageState) -> Option<([f64; 3], [f64; 3])> {
        let o = self
            .surrogate
            .evaluate(xi, &Self::cut_state(state), &ScaleFactors::default());
        let p = |s: &shearcut_sim::surrogate::ScaledParts| {
            [s.by_toughness, s.by_stiffness, s.by_friction_stiffness]
        };
        Some((p(&o.force_normal_parts), p(&o.force_tangential_parts)))
    }

    fn set_scale(&mut self, toughness: f64, stiffness: f64, friction: f64) {
        self.scale = ScaleFactors {
            toughness,
            stiffness,
            friction,
        };
    }
}
