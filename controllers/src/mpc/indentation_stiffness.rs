//! The stiffness factor from the indentation before the first fracture.

/// Weighted sums of one series, centred on its weighted means (West's
/// incremental algorithm: no cancellation when the forces are large
/// against their changes).
#[derive(Debug, Clone, Copy, PartialEq, Default)]
struct CentredSums {
    weight: f64,
    mean_model: f64,
    mean_measured: f64,
    /// Σ w·(m − m̄)².
    model_model: f64,
    /// Σ w·(m − m̄)·(y − ȳ).
    model_measured: f64,
}

impl CentredSums {
    fn add(&mut self, weight: f64, model: f64, measured: f64) {
        self.weight += weight;
        let share = weight / self.weight;
        let dm = model - self.mean_model;
        let dy = measured - self.mean_measured;
        self.mean_model += share * dm;
        self.mean_measured += share * dy;
        self.model_model += weight * dm * (model - self.mean_model);
        self.model_measured += weight * dm * (measured - self.mean_measured);
    }
}

/// Least squares of the measured normal and tangential forces per unit
/// length y on the model's at the nominal stiffness m, y = S·m + c, with
/// the stiffness factor S common and one offset c per force and per run of
/// ticks with the same length of edge in contact.
///
/// Before the first fracture the forces are linear in the depth and in S
/// (seed 000 §III.C: linear elasticity until the crack starts), but the
/// plant's depth is not known exactly: the edge touches within a tick, so
/// the knife's travel since the first tick in contact lags the indentation
/// by a fraction of a tick's travel, a near-constant offset of the force
/// (as is a sensor bias). The offsets absorb both; the slope alone gives S.
/// When the contact length changes (another part of the edge touched), the
/// force per unit length the model predicts is not the plant's across the
/// change, so a new run with its own offsets starts.
///
/// Against least squares on the tick-to-tick changes (which the estimator
/// used before: the changes telescope, so it weighed only the first and
/// last forces of a run), this uses every tick: on an indentation of n
/// evenly spaced ticks its standard deviation from the sensor's noise is
/// √(6(n − 1)/(n(n + 1))) of the changes' (0.61 at n = 14, the half
/// potato's 70 µm at 5 mm/s).
///
/// Rows are weighted by the contact length squared: the sensor's noise on a
/// force per unit length is inversely proportional to it. Allocation-free.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct IndentationStiffness {
    contact: f64,
    run: [CentredSums; 2],
    /// Σ w·(m − m̄)² and Σ w·(m − m̄)·(y − ȳ) of the finished runs.
    finished: [f64; 2],
    /// Σ w·m² over every row: the scale against which the model's spread
    /// Σ w·(m − m̄)² counts as excitation ([`Self::MIN_RELATIVE_SPREAD`]).
    magnitude: f64,
}

impl IndentationStiffness {
    /// One tick: `contact` metres of edge in contact, the measured normal
    /// and tangential forces per unit length `measured` and the model's at
    /// the nominal stiffness `model` (N/m).
    pub fn observe(&mut self, contact: f64, measured: [f64; 2], model: [f64; 2]) {
        if !(contact > 0.0 && measured.iter().chain(&model).all(|x| x.is_finite())) {
            return;
        }
        if (contact - self.contact).abs() > 1e-9 * contact {
            for r in &self.run {
                self.finished[0] += r.model_model;
                self.finished[1] += r.model_measured;
            }
            self.run = Default::default();
            self.contact = contact;
        }
        let weight = contact * contact;
        for i in 0..2 {
            self.run[i].add(weight, model[i], measured[i]);
            self.magnitude += weight * model[i] * model[i];
        }
    }

    /// The stiffness factor S, once the model's forces have changed within
    /// a run (`None` before, and while they have hardly changed: a relative
    /// spread of the model's forces under [`Self::MIN_RELATIVE_SPREAD`]).
    pub fn stiffness(&self) -> Option<f64> {
        let (mut mm, mut my) = (self.finished[0], self.finished[1]);
        for r in &self.run {
            mm += r.model_model;
            my += r.model_measured;
        }
        (mm > Self::MIN_RELATIVE_SPREAD * self.magnitude).then(|| my / mm)
    }

    /// The smallest Σ w·(m − m̄)² / Σ w·m² that identifies a slope: model
    /// forces whose spread is under 10⁻⁶ of their size (10⁻¹² of the
    /// squares) carry no excitation to fit a slope to, only the last digits
    /// of their arithmetic (an indentation takes the force from near zero,
    /// a relative spread of order one). Not a noise criterion: between the
    /// tick that first gives a slope and the fracture, S is re-set every
    /// tick as the indentation adds rows.
    pub const MIN_RELATIVE_SPREAD: f64 = 1e-12;
}

#[cfg(test)]
mod tests {
    use super::IndentationStiffness;

    #[test]
    fn offsets_per_run_leave_the_slope() {
        let mut fit = IndentationStiffness::default();
        // Two runs of contact, each with its own offset on each force.
        for (contact, offsets) in [(0.004, [0.7, -0.2]), (0.009, [-1.5, 0.4])] {
            for k in 0..10 {
                let m = [3.0 * k as f64, 1.2 * k as f64];
                let y = [0, 1].map(|i| 1.3 * m[i] + offsets[i]);
                fit.observe(contact, y, m);
            }
        }
        let s = fit.stiffness().unwrap();
        assert!((s - 1.3).abs() < 1e-12, "{s}");
    }

    #[test]
    fn nothing_is_known_before_the_model_changes() {
        let mut fit = IndentationStiffness::default();
        assert_eq!(fit.stiffness(), None);
        fit.observe(0.01, [5.0, 1.0], [4.0, 1.0]);
        assert_eq!(fit.stiffness(), None);
        fit.observe(0.01, [f64::NAN, 1.0], [4.0, 1.0]);
        assert_eq!(fit.stiffness(), None);
    }

    #[test]
    fn changes_at_the_rounding_level_identify_nothing() {
        // The model's forces differ only in their last bits: a slope
        // through them would be arbitrary. The criterion is relative: the
        // same at any scale of the forces.
        for scale in [1e-3, 1.0, 1e3] {
            let mut fit = IndentationStiffness::default();
            let m: f64 = 4.0e3 * scale;
            for k in 0..10 {
                let wobble = if k % 2 == 0 { m } else { m.next_up() };
                fit.observe(0.01, [(5.0e3 + k as f64) * scale, scale], [wobble, scale]);
            }
            assert_eq!(fit.stiffness(), None, "scale {scale}");
            // A spread of 1e-5 of the force (10⁻¹⁰ of the squares) does.
            fit.observe(0.01, [5.2e3 * scale, scale], [m * (1.0 + 3e-5), scale]);
            let s = fit.stiffness().unwrap();
            assert!(s.is_finite(), "scale {scale}: {s}");
        }
    }
}
