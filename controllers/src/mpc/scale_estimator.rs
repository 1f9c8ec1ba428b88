//! Online estimation of the material's scale factors from the measured
//! forces (recursive least squares with forgetting, on the model's parts at
//! the current estimate's E/R_c).

use nalgebra::{Matrix3, Vector3};

use super::indentation_stiffness::IndentationStiffness;
use super::slice_model::ForceModel;

/// Estimates θ = (toughness, stiffness, friction × stiffness) in
///
///   F = θ₁·a(ℓ) + θ₂·b(ℓ) + θ₃·c(ℓ),  ℓ = ln(θ₂/θ₁),
///
/// where (a, b, c) are the model's parts of a force per unit length at the
/// current state (the surrogate's `ScaledParts`: what multiplies R_c, E and
/// μ·E) and F the measured force per unit length. The wedge's parts depend
/// on E/R_c (the crack runs further ahead of a stiffer, less tough
/// material's wedge; `docs/surrogates.md`), so F is not linear in θ: each
/// row takes the parts at the ratio of the estimate when it arrives
/// ([`ForceModel`]) and the update is recursive least squares on them; ℓ
/// moves only through the estimate, and rows already taken are not
/// re-linearised (the early rows, taken at ratios the estimate has since
/// left, bias the end estimate: measured in docs/controllers.md, "Online
/// estimation"; with parts independent of ℓ this is plain recursive least
/// squares). Before the first
/// fracture only the stiffness part is non-zero and the stiffness is the
/// slope of the indentation's forces ([`Self::observe_indentation`]); after
/// it each tick brings two rows (normal and tangential force), weighed by
/// the model's relative error ([`Self::observe_cut`]). An optional
/// forgetting factor λ per row follows slow changes (skin, then flesh);
/// each factor is kept within [`ScaleEstimator::BOUNDS`].
///
/// Rows whose parts are all tiny carry no information and are skipped (no
/// contact, or pressing with no tangential force). Allocation-free.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ScaleEstimator {
    theta: Vector3<f64>,
    covariance: Matrix3<f64>,
    forgetting: f64,
    updates: u64,
    relative_error: f64,
    /// The stiffness from the indentation before the first fracture.
    indentation: IndentationStiffness,
}

impl ScaleEstimator {
    /// Smallest and largest factor accepted.
    pub const BOUNDS: (f64, f64) = (0.2, 5.0);

    /// The plant's tangential force that no factor explains, as a fraction
    /// of the normal force: where the model's tangential force is 0
    /// (pressing, ξ = 0) a curved edge's inclination and the sections'
    /// asymmetry still give the plant one; 0.02 covers what pressing the
    /// half potato with the chef's knife shows (docs/controllers.md,
    /// "Online estimation").
    pub const LATERAL_FORCE: f64 = 0.02;

    /// Starts at the nominal material (all factors 1) with prior variance
    /// `prior_variance` per factor and forgetting factor `forgetting` in
    /// (0, 1] (1: no forgetting) per row. `relative_error` is the model's
    /// force error as a fraction of the force (the surrogates' held-out
    /// force RMS errors, `config/surrogates/*.accuracy.toml`):
    /// [`Self::observe_cut`] weighs each row by it.
    pub fn new(prior_variance: f64, forgetting: f64, relative_error: f64) -> Self {
        Self {
            theta: Vector3::new(1.0, 1.0, 1.0),
            covariance: Matrix3::identity() * prior_variance,
            forgetting,
            updates: 0,
            relative_error,
            indentation: IndentationStiffness::default(),
        }
    }

    /// The factors (toughness, stiffness, friction) believed now: those to
    /// linearise the model at for the next rows.
    pub fn factors(&self) -> [f64; 3] {
        [self.toughness(), self.stiffness(), self.friction()]
    }

    /// One tick of the cut after the first fracture: the measured normal
    /// and tangential forces per unit length `force` (N/m; the tangential
    /// one `None` when the knife does not move along its edge) and the
    /// model of them at [`Self::factors`].
    ///
    /// Each row's standard deviation is the model's relative error times
    /// the force the model predicts for the nominal material (not at the
    /// current factors: weights that follow the estimate can run away with
    /// it), plus [`Self::LATERAL_FORCE`] times the normal force: the rows
    /// are compared in relative terms, so the tangential force — a third
    /// of the normal one or less, and mostly friction — weighs about as
    /// much as the normal one (absolute weights let the normal force's
    /// model error set the friction), while near pressing, where the model's
    /// tangential force vanishes, the plant's unmodelled lateral force
    /// keeps the tangential row from dominating. The crack-jump sawtooth is
    /// zero-mean noise on these rows: least squares without forgetting
    /// averages it over the cut.
    pub fn observe_cut(&mut self, force: [Option<f64>; 2], model: [ForceModel; 2]) {
        let normal = model[0].nominal.abs();
        for (measured, row) in force.into_iter().zip(model) {
            let Some(measured) = measured else {
                continue;
            };
            let noise = self.relative_error * row.nominal.abs() + Self::LATERAL_FORCE * normal;
            if noise > 0.0 {
                self.update_linearised(row.gradient, row.value, measured, noise);
            }
        }
    }

    /// One tick of the indentation before the first fracture: the measured
    /// normal and tangential forces per unit length `force` (N/m) with
    /// `contact` metres of edge in contact, the model of them, and `noise`
    /// the sensor's noise level on a force (N).
    ///
    /// Before the fracture the forces are linear in the stiffness alone, so
    /// the stiffness factor is set to the least-squares slope of the
    /// measured forces on the model's nominal ones over the indentation's
    /// linear rise, with an offset per force ([`IndentationStiffness`]:
    /// the arm's depth is off the plant's by a near-constant amount, as a
    /// sensor bias offsets the force; the rise ends where the force falls
    /// below its line, which may be before the first fracture is detected).
    pub fn observe_indentation(
        &mut self,
        contact: f64,
        force: [f64; 2],
        model: [ForceModel; 2],
        noise: f64,
    ) {
        self.indentation
            .observe(contact, force, model.map(|m| m.nominal), noise);
        self.take_indentation();
    }

    /// Sets the stiffness factor to the indentation's slope, once there is
    /// one.
    fn take_indentation(&mut self) {
        if let Some(s) = self.indentation.stiffness() {
            self.theta[1] = s;
            self.clamp_factors();
            self.updates += 1;
        }
    }

    /// One measurement row of a model linear in θ: `parts` = (a, b, c),
    /// `measured` F. `noise` is the row's standard deviation (the same
    /// units as F): rows are weighted by 1/noise², so normal and tangential
    /// forces, or sensors of different quality, combine correctly.
    pub fn update(&mut self, parts: [f64; 3], measured: f64, noise: f64) {
        let predicted = Vector3::from(parts).dot(&self.theta);
        self.update_linearised(parts, predicted, measured, noise);
    }

    /// One measurement row linearised at the current θ: the model's
    /// `gradient` (∂F/∂θ, or the parts at the current ratio) and `predicted`
    /// F there, `measured` F, `noise` its standard deviation. Rows that are
    /// not finite or carry no information (gradient ≈ 0) are skipped.
    pub fn update_linearised(
        &mut self,
        gradient: [f64; 3],
        predicted: f64,
        measured: f64,
        noise: f64,
    ) {
        let phi = Vector3::from(gradient) / noise;
        let innovation = (measured - predicted) / noise;
        if !(phi.iter().all(|x| x.is_finite()) && innovation.is_finite()) || phi.norm() < 1e-9 {
            return;
        }
        let p_phi = self.covariance * phi;
        let gain = p_phi / (self.forgetting + phi.dot(&p_phi));
        self.theta += gain * innovation;
        self.covariance = (self.covariance - gain * p_phi.transpose()) / self.forgetting;
        // Keep P symmetric against rounding.
        self.covariance = 0.5 * (self.covariance + self.covariance.transpose());
        self.clamp_factors();
        self.updates += 1;
    }

    /// Keeps each factor within [`Self::BOUNDS`]: θ₁ (toughness), θ₂
    /// (stiffness), and the friction factor F = θ₃/θ₂ itself, so θ₃ = F·S
    /// within [lo·θ₂, hi·θ₂] (after θ₂ is).
    fn clamp_factors(&mut self) {
        let (lo, hi) = Self::BOUNDS;
        self.theta[0] = self.theta[0].clamp(lo, hi);
        self.theta[1] = self.theta[1].clamp(lo, hi);
        self.theta[2] = self.theta[2].clamp(lo * self.theta[1], hi * self.theta[1]);
    }

    /// Holds the stiffness factor from now on at the indentation's slope
    /// (its pending rows on the line taken, [`IndentationStiffness::close`]),
    /// or where it is if the indentation gave none: its row and
    /// column of the covariance are zeroed, so no later row moves it (a
    /// parameter fixed in recursive least squares). Used after the first
    /// fracture, when the toughness and stiffness parts of the forces are
    /// nearly collinear at a near-constant ξ and only the indentation before
    /// it has identified E.
    pub fn freeze_stiffness(&mut self) {
        // The indentation's rows still pending on the line count.
        if !self.indentation.ended() {
            self.indentation.close();
            self.take_indentation();
        }
        for k in 0..3 {
            self.covariance[(1, k)] = 0.0;
            self.covariance[(k, 1)] = 0.0;
        }
    }

    /// Toughness factor (multiplies R_c and R'_c).
    pub fn toughness(&self) -> f64 {
        self.theta[0]
    }

    /// Stiffness factor (multiplies E).
    pub fn stiffness(&self) -> f64 {
        self.theta[1]
    }

    /// Friction factor (multiplies μ): θ₃/θ₂.
    pub fn friction(&self) -> f64 {
        self.theta[2] / self.theta[1]
    }

    /// Rows used so far.
    pub fn updates(&self) -> u64 {
        self.updates
    }
}

#[cfg(test)]
mod tests {
    use super::ScaleEstimator;

    /// 400 exact rows of deterministic, varied parts (as the state and ξ
    /// change) for the factors `truth`.
    fn feed_exciting_rows(e: &mut ScaleEstimator, truth: [f64; 3]) {
        for k in 0..400 {
            let t = k as f64 * 0.1;
            let parts = [
                100.0 + 20.0 * t.sin(),
                40.0 + 30.0 * (0.7 * t).cos(),
                15.0 + 10.0 * (1.3 * t).sin(),
            ];
            let f: f64 = parts.iter().zip(truth).map(|(p, q)| p * q).sum();
            e.update(parts, f, 1.0);
        }
    }

    #[test]
    fn recovers_factors_from_exciting_rows() {
        let truth = [1.3, 0.7, 0.7 * 1.25];
        let mut e = ScaleEstimator::new(1.0, 1.0, 0.05);
        feed_exciting_rows(&mut e, truth);
        // Exact data: what remains is the prior's pull, of order
        // ‖θ₀ − θ‖ / (P₀·λ_min(Σφφᵀ)) ≈ 1e-6 here.
        assert!((e.toughness() - 1.3).abs() < 1e-4, "{}", e.toughness());
        assert!((e.stiffness() - 0.7).abs() < 1e-4, "{}", e.stiffness());
        assert!((e.friction() - 1.25).abs() < 1e-4, "{}", e.friction());
    }

    #[test]
    fn a_frozen_stiffness_stays_while_the_others_are_identified() {
        let truth = [1.3, 0.7, 0.7 * 1.25];
        let mut e = ScaleEstimator::new(1.0, 1.0, 0.05);
        // Rows with only the stiffness part (an indentation) identify it.
        for k in 0..200 {
            let b = 40.0 + k as f64 * 0.1;
            e.update([0.0, b, 0.0], truth[1] * b, 1.0);
        }
        assert!((e.stiffness() - 0.7).abs() < 1e-3, "{}", e.stiffness());
        let held = e.stiffness();
        e.freeze_stiffness();
        // Then rows with all three parts: θ₂ is held, θ₁ and θ₃ converge.
        feed_exciting_rows(&mut e, truth);
        assert_eq!(e.stiffness(), held);
        assert!((e.toughness() - 1.3).abs() < 2e-3, "{}", e.toughness());
        assert!((e.friction() - 1.25).abs() < 5e-3, "{}", e.friction());
    }

    #[test]
    fn the_friction_factor_itself_stays_within_the_bounds() {
        let (lo, hi) = ScaleEstimator::BOUNDS;
        // Rows asking for F = 20 at S = 1: F is held at the upper bound
        // (θ₃ = F·S alone would have been allowed up to hi²).
        let mut e = ScaleEstimator::new(1.0, 1.0, 0.05);
        for k in 0..50 {
            let c = 10.0 + k as f64;
            e.update([0.0, 0.0, c], 20.0 * c, 1.0);
        }
        assert!((e.friction() - hi).abs() < 1e-12, "{}", e.friction());
        // A stiffness at its lower bound with F·S asking for F = 0.05:
        // F is held at the lower bound, not 0.05 (the old [lo², hi²] on F·S
        // admitted it).
        let mut e = ScaleEstimator::new(1.0, 1.0, 0.05);
        for k in 0..50 {
            let b = 40.0 + k as f64;
            e.update([0.0, b, 0.0], 0.1 * b, 1.0);
        }
        e.freeze_stiffness();
        for k in 0..50 {
            let c = 10.0 + k as f64;
            e.update([0.0, 0.0, c], 0.05 * lo * c, 1.0);
        }
        assert_eq!(e.stiffness(), lo);
        assert!((e.friction() - lo).abs() < 1e-12, "{}", e.friction());
    }

    #[test]
    fn uninformative_rows_change_nothing() {
        let mut e = ScaleEstimator::new(1.0, 0.99, 0.05);
        e.update([0.0; 3], 5.0, 1.0);
        e.update([f64::NAN, 1.0, 1.0], 5.0, 1.0);
        assert_eq!(
            (e.toughness(), e.stiffness(), e.friction(), e.updates()),
            (1.0, 1.0, 1.0, 0)
        );
    }
}
