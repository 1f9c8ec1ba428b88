//! The fitted surrogate as the MPC's [`SliceModel`].

use shearcut_sim::surrogate::{CutState, ScaleFactors, ScaledParts, Surrogate, SurrogateOutput};

use super::slice_model::{ForceModel, SliceModel, StageCost, StageState};

/// Step of the differences in ξ of the onset quantities (the surrogate
/// gives the rates' derivatives analytically, not those of the work and
/// deflection at the onset depth).
const ONSET_STEP: f64 = 1e-3;

/// Intervals of the catch-up integral (trapezoidal rule).
const CATCH_UP_INTERVALS: usize = 32;

/// Normal travel after the first fracture that the onset's cost covers, in
/// onset depths d*(ξ): more than the crack's jump, the edge catching up
/// with the tip and the knee after it take in the full model
/// (`docs/surrogates.md`, "Structure").
const CATCH_UP_SPAN_ONSETS: f64 = 4.0;

/// Intervals of the indentation integral of [`SliceModel::onset_cost`]
/// (trapezoidal rule).
const INDENTATION_INTERVALS: usize = 8;

/// Smallest such travel, m (a few bevel heights: the wedge entering the
/// crack after a shallow onset).
const MIN_CATCH_UP_SPAN: f64 = 5e-3;

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
    /// indentation (the surrogate's pre-fracture stiffness), so the work to
    /// the onset is ½·w(d*)·d*; to it is added what the first `span` of
    /// travel after the onset costs beyond the rate at its end
    /// ([`Self::catch_up_excess`]).
    fn onset(&self, xi: f64, cut: &CutState, span: f64) -> (f64, f64, f64) {
        let (d_star, o) = self.at_onset(xi, cut);
        (
            0.5 * o.work_per_depth * d_star + self.catch_up_excess(xi, d_star, cut, span, |_| 1.0),
            o.deformation,
            o.force_normal,
        )
    }

    /// The onset depth d*(ξ), m, and the surrogate's answer there.
    fn at_onset(&self, xi: f64, cut: &CutState) -> (f64, SurrogateOutput) {
        let d_star = self
            .surrogate
            .evaluate(xi, cut, &self.scale)
            .fracture_onset_depth;
        let at_onset = CutState {
            depth: d_star,
            fractured: false,
            ..*cut
        };
        (d_star, self.surrogate.evaluate(xi, &at_onset, &self.scale))
    }

    /// [`Self::onset`]'s work for the whole edge, J, with `contact(d)` the
    /// length of edge in contact (m) at the sections' depth d: the
    /// indentation's force per unit length w(d*)·d/d* weighted by it over
    /// the indentation, ∫₀^{d*} L(d) w(d*) d/d* dd, and the catch-up's
    /// excess over it along the span (trapezoidal rules).
    fn weighted_onset_work<C: Fn(f64) -> f64>(
        &self,
        xi: f64,
        cut: &CutState,
        span: f64,
        contact: &C,
    ) -> f64 {
        let (d_star, o) = self.at_onset(xi, cut);
        let dd = d_star / INDENTATION_INTERVALS as f64;
        let force = |i: usize| {
            let d = i as f64 * dd;
            contact(d) * o.work_per_depth * d / d_star.max(f64::MIN_POSITIVE)
        };
        let inner: f64 = (1..INDENTATION_INTERVALS).map(force).sum();
        let indentation = (inner + 0.5 * force(INDENTATION_INTERVALS)) * dd;
        indentation + self.catch_up_excess(xi, d_star, cut, span, |s| contact(d_star + s))
    }

    /// What the first `span` of normal travel after a first fracture at
    /// `xi` (onset depth `d_star`) costs beyond cutting it at the rate
    /// reached at its end, each travel s since the fracture weighted by
    /// `weight(s)`: ∫₀^span weight(s) [w(ξ, s) − w(ξ, span)] ds
    /// (trapezoidal rule); J/m for a weight of 1, J for the length of edge
    /// in contact.
    ///
    /// The strain energy stored while indenting, about ½·r·R'_c·d* (seed
    /// 000 eq. 1), is not lost: it runs the crack ahead of the edge, and
    /// until the edge catches up the knife does no fracture work (the
    /// surrogate's catch-up, `docs/surrogates.md`), so this is mostly a
    /// saving (negative), the larger the deeper the onset; the drag that
    /// slicing builds up costs extra over it. It depends on the ratio at
    /// the fracture, not on those planned for the depths it spans, so it
    /// belongs to the onset's cost, and the stages planned before the
    /// fracture are priced at the rates after it.
    fn catch_up_excess<W: Fn(f64) -> f64>(
        &self,
        xi: f64,
        d_star: f64,
        cut: &CutState,
        span: f64,
        weight: W,
    ) -> f64 {
        if span <= 0.0 {
            return 0.0;
        }
        let at = |s: f64| {
            let after = CutState {
                depth: d_star + s,
                fractured: true,
                travel_since_fracture: s,
                ..*cut
            };
            self.surrogate
                .evaluate(xi, &after, &self.scale)
                .work_per_depth
        };
        let ds = span / CATCH_UP_INTERVALS as f64;
        let end = at(span);
        let excess = |s: f64| weight(s) * (at(s) - end);
        let inner: f64 = (1..CATCH_UP_INTERVALS).map(|i| excess(i as f64 * ds)).sum();
        (inner + 0.5 * excess(0.0)) * ds
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
        // Before the first fracture: the rates once cutting, at the end of
        // the span the onset's cost covers, plus that cost (central
        // differences in ξ; one-sided at 0).
        let span = state.travel_since_fracture.max(0.0);
        cut.fractured = true;
        cut.travel_since_fracture = span;
        let o = self.surrogate.evaluate(xi, &cut, &self.scale);
        cut.fractured = false;
        let h = ONSET_STEP;
        let (lo, hi) = ((xi - h).max(0.0), xi + h);
        let (w0, d0, f0) = self.onset(xi, &cut, span);
        let (wl, dl, fl) = self.onset(lo, &cut, span);
        let (wh, dh, fh) = self.onset(hi, &cut, span);
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

    fn onset_cost<C: Fn(f64) -> f64>(&self, xi: f64, state: &StageState, contact: C) -> [f64; 3] {
        let cut = CutState {
            fractured: false,
            ..Self::cut_state(state)
        };
        let span = state.travel_since_fracture.max(0.0);
        let h = ONSET_STEP;
        let (lo, hi) = ((xi - h).max(0.0), xi + h);
        let w0 = self.weighted_onset_work(xi, &cut, span, &contact);
        let wl = self.weighted_onset_work(lo, &cut, span, &contact);
        let wh = self.weighted_onset_work(hi, &cut, span, &contact);
        let curvature = if xi - lo > 0.0 {
            2.0 * ((wh - w0) / (hi - xi) - (w0 - wl) / (xi - lo)) / (hi - lo)
        } else {
            0.0
        };
        [w0, (wh - wl) / (hi - lo), curvature]
    }

    fn onset_deflection(&self, xi: f64, state: &StageState) -> (f64, f64) {
        let intact = CutState {
            depth: 0.0,
            fractured: false,
            travel_since_fracture: 0.0,
            ..Self::cut_state(state)
        };
        let h = ONSET_STEP;
        let (lo, hi) = ((xi - h).max(0.0), xi + h);
        let (_, d0, _) = self.onset(xi, &intact, 0.0);
        let (_, dl, _) = self.onset(lo, &intact, 0.0);
        let (_, dh, _) = self.onset(hi, &intact, 0.0);
        (d0, (dh - dl) / (hi - lo))
    }

    fn catch_up_span(&self, xi: f64, state: &StageState) -> f64 {
        let intact = CutState {
            fractured: false,
            ..Self::cut_state(state)
        };
        let d_star = self
            .surrogate
            .evaluate(xi, &intact, &self.scale)
            .fracture_onset_depth;
        (CATCH_UP_SPAN_ONSETS * d_star)
            .max(MIN_CATCH_UP_SPAN)
            .min((state.height - d_star).max(0.0))
    }

    fn force_model(&self, xi: f64, state: &StageState, scale: [f64; 3]) -> Option<[ForceModel; 2]> {
        let cut = Self::cut_state(state);
        let [t, s, f] = scale;
        let nominal = self.surrogate.evaluate(xi, &cut, &ScaleFactors::default());
        let at = self.surrogate.evaluate(
            xi,
            &cut,
            &ScaleFactors {
                toughness: t,
                stiffness: s,
                friction: f,
            },
        );
        // θ = (T, S, P = F·S): the parts at the current ratio ℓ = ln(S/T),
        // i.e. the derivatives holding ℓ (`ForceModel::gradient`).
        let linearised = |n: &ScaledParts, p: &ScaledParts| ForceModel {
            nominal: n.combine(1.0, 1.0, 1.0),
            value: p.combine(t, s, f),
            gradient: [p.by_toughness, p.by_stiffness, p.by_friction_stiffness],
        };
        Some([
            linearised(&nominal.force_normal_parts, &at.force_normal_parts),
            linearised(&nominal.force_tangential_parts, &at.force_tangential_parts),
        ])
    }

    fn set_scale(&mut self, toughness: f64, stiffness: f64, friction: f64) {
        self.scale = ScaleFactors {
            toughness,
            stiffness,
            friction,
        };
    }
}
