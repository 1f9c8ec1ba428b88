//! The fitted surrogate as the MPC's [`SliceModel`].

use shearcut_sim::surrogate::{CutState, ScaleFactors, Surrogate};

use super::slice_model::{SliceModel, StageCost, StageState};

/// Step of the differences in ξ of the onset quantities (the surrogate
/// gives the rates' derivatives analytically, not those of the work and
/// deflection at the onset depth).
const ONSET_STEP: f64 = 1e-3;

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

impl SurrogateModel {
    /// What reaching the first fracture costs at `xi` from an intact
    /// surface: (work per unit length, deflection, vertical force per unit
    /// length) at the onset depth d*(ξ). The force grows linearly with the
    /// indentation (the surrogate's pre-fracture stiffness), so the work is
    /// ½·w(d*)·d*.
    fn onset(&self, xi: f64, cut: &CutState) -> (f64, f64, f64) {
        let d_star = self
            .surrogate
            .evaluate(xi, cut, &self.scale)
            .fracture_onset_depth;
        let at_onset = CutState {
            depth: d_star,
            fractured: false,
            ..*cut
        };
        let o = self.surrogate.evaluate(xi, &at_onset, &self.scale);
        (
            0.5 * o.work_per_depth * d_star,
            o.deformation,
            o.force_normal,
        )
    }
}

impl SliceModel for SurrogateModel {
    fn stage(&self, xi: f64, state: &StageState) -> StageCost {
        let mut cut = Self::cut_state(state);
        if state.fractured {
            let o = self.surrogate.evaluate(xi, &cut, &self.scale);
            return StageCost {
                work_per_depth: o.work_per_depth,
                work_per_depth_slope: o.work_per_depth_slope,
                work_per_depth_curvature: o.work_per_depth_curvature,
                force_normal: o.force_normal,
                force_normal_slope: o.force_normal_slope,
                ..StageCost::default()
            };
        }
        // Before the first fracture: the rates once cutting, plus the cost
        // of getting there (central differences in ξ; one-sided at 0).
        cut.fractured = true;
        cut.travel_since_fracture = 0.0;
        let o = self.surrogate.evaluate(xi, &cut, &self.scale);
        cut.fractured = false;
        let h = ONSET_STEP;
        let (lo, hi) = ((xi - h).max(0.0), xi + h);
        let (w0, d0, f0) = self.onset(xi, &cut);
        let (wl, dl, fl) = self.onset(lo, &cut);
        let (wh, dh, fh) = self.onset(hi, &cut);
        let span = hi - lo;
        // Second difference on the possibly uneven stencil.
        let curvature = 2.0 * ((wh - w0) / (hi - xi) - (w0 - wl) / (xi - lo).max(h)) / span;
        StageCost {
            work_per_depth: o.work_per_depth,
            work_per_depth_slope: o.work_per_depth_slope,
            work_per_depth_curvature: o.work_per_depth_curvature,
            // The peak force is the one at the onset.
            force_normal: f0.max(o.force_normal),
            force_normal_slope: if f0 > o.force_normal {
                (fh - fl) / span
            } else {
                o.force_normal_slope
            },
            deformation: d0,
            deformation_slope: (dh - dl) / span,
            onset_work: w0,
            onset_work_slope: (wh - wl) / span,
            onset_work_curvature: if xi - lo > 0.0 { curvature } else { 0.0 },
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
