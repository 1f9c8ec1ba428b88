//! The stiffness factor from the indentation's linear rise, before the
//! first fracture.

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

/// One reading of the indentation not yet taken into the fit.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
struct PendingRow {
    /// Contact length squared, m².
    weight: f64,
    /// The model's normal and tangential forces per unit length at the
    /// nominal stiffness, N/m.
    model: [f64; 2],
    /// The measured ones, N/m.
    measured: [f64; 2],
}

/// Least squares of the measured normal and tangential forces per unit
/// length y on the model's at the nominal stiffness m, y = S·m + c, with
/// the stiffness factor S common and one offset c per force, over the
/// indentation's linear rise only.
///
/// Before the first fracture the forces are linear in the depth and in S
/// (seed 000 §III.C: linear elasticity until the crack starts), but the
/// depth the model is evaluated at is the arm's, not the plant's: the
/// touch height is a prior (or an observation good to a few ticks), so the
/// edge's depth is off by a near-constant δ, which offsets the force by
/// S·k·δ per unit length (k the section's indentation stiffness), as a
/// sensor bias offsets it. The offsets absorb both; the slope alone gives
/// S. The contact length the rows are divided by is a function of the
/// depth (the object's outline), continuous across the indentation, so one
/// offset per force holds throughout.
///
/// # The linear rise
/// The crack does not start where a detector sees it: under a flat top
/// the force may keep rising, only slower, as a tough, soft material's
/// crack grows steadily (for tens of ticks past the first fracture before
/// the force drops by the detector's fraction: docs/controllers.md,
/// "Online estimation"), and on a dome one section fractures while others
/// keep loading. Rows
/// from past the fracture, fitted with the unfractured model, read as a
/// softer material. So a row enters the fit only after [`Self::LAG`]
/// later readings have confirmed the rise went on: each new normal force
/// is compared with the line fitted so far, and [`Self::LAG`] readings in a
/// row below it by more than [`Self::SIGMAS`] prediction standard
/// deviations (the sensor's noise through the fit, plus
/// [`Self::RELATIVE_TOLERANCE`] of the force for the model's own error)
/// end the rise at the first of them: those are dropped and the fit is
/// closed. [`Self::close`] (at the detected first fracture) takes the
/// pending readings that had not fallen below the line.
///
/// Rows are weighted by the contact length squared: the sensor's noise on a
/// force per unit length is inversely proportional to it (this is least
/// squares on the total forces). On an indentation of n evenly spaced
/// ticks the slope's relative standard deviation from the sensor's noise
/// is √(12/(n(n² − 1))) times the noise over one tick's change of force
/// (0.066 times at n = 14).
/// Allocation-free.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct IndentationStiffness {
    sums: [CentredSums; 2],
    /// Rows taken.
    rows: usize,
    /// Σ w·m² over every row: the scale against which the model's spread
    /// Σ w·(m − m̄)² counts as excitation ([`Self::MIN_RELATIVE_SPREAD`]).
    magnitude: f64,
    /// Readings waiting for [`Self::LAG`] later ones, oldest first from
    /// `first`.
    pending: [PendingRow; Self::LAG],
    first: usize,
    waiting: usize,
    /// The newest pending readings that fell below the line, in a row.
    below: usize,
    /// Whether the rise has ended (or the fit was closed): no more rows.
    ended: bool,
    /// The sensor's noise level on a force, N (the latest given).
    noise: f64,
}

impl IndentationStiffness {
    /// Readings that confirm a row (and, below the line in a row, end the
    /// rise): 3. The rise's end is found 3 ticks late, at 5 mm/s 15 µm of
    /// travel, while three readings below the line by noise alone come
    /// with probability 0.00135³ ≈ 2.5·10⁻⁹ per tick.
    pub const LAG: usize = 3;

    /// Prediction standard deviations below the line that count as a fall:
    /// 3 (one-sided probability 0.00135 per reading from noise).
    pub const SIGMAS: f64 = 3.0;

    /// The model's own error in the shape of the rise, as a fraction of the
    /// predicted force per unit length, added to the fall's threshold
    /// (0.02): the surrogate's indentation force follows the section model
    /// to a few per cent, and a fracture's deficit grows well past that
    /// within [`Self::LAG`] ticks at the guarded touch's speed
    /// (docs/controllers.md, "Online estimation").
    pub const RELATIVE_TOLERANCE: f64 = 0.02;

    /// Rows the fit needs before it can call a fall (3: a line and one
    /// residual degree of freedom per force).
    pub const MIN_ROWS: usize = 3;

    /// One tick: `contact` metres of edge in contact, the measured normal
    /// and tangential forces per unit length `measured` and the model's at
    /// the nominal stiffness `model` (N/m), and `noise` the sensor's noise
    /// level on a force, N.
    pub fn observe(&mut self, contact: f64, measured: [f64; 2], model: [f64; 2], noise: f64) {
        if self.ended || !(contact > 0.0 && measured.iter().chain(&model).all(|x| x.is_finite())) {
            return;
        }
        self.noise = noise;
        let row = PendingRow {
            weight: contact * contact,
            model,
            measured,
        };
        self.below = if self.falls_below(&row, noise / contact) {
            self.below + 1
        } else {
            0
        };
        if self.waiting == Self::LAG {
            // Followed by LAG readings, not all below the line: confirmed.
            let oldest = self.pending[self.first];
            self.take(&oldest);
            self.first = (self.first + 1) % Self::LAG;
            self.waiting -= 1;
        }
        self.pending[(self.first + self.waiting) % Self::LAG] = row;
        self.waiting += 1;
        if self.below >= Self::LAG {
            // The rise ended at the first of the readings below the line.
            self.close();
        }
    }

    /// Ends the fit (at the first fracture): the pending readings that had
    /// not fallen below the line are taken, and no more rows.
    pub fn close(&mut self) {
        if self.ended {
            return;
        }
        let confirmed = self.waiting - self.below.min(self.waiting);
        for k in 0..confirmed {
            let row = self.pending[(self.first + k) % Self::LAG];
            self.take(&row);
        }
        self.waiting = 0;
        self.ended = true;
    }

    /// Whether the fit has ended: the rise fell below its line, or
    /// [`Self::close`].
    pub fn ended(&self) -> bool {
        self.ended
    }

    /// The stiffness factor S, once the rows taken identify it: the
    /// model's forces have changed over them (a relative spread of the
    /// model's forces of at least [`Self::MIN_RELATIVE_SPREAD`]) and the
    /// sensor's noise leaves S a relative standard deviation of at most
    /// [`Self::MAX_RELATIVE_ERROR`]; `None` before.
    pub fn stiffness(&self) -> Option<f64> {
        let s = self.slope()?;
        let spread = self.sums[0].model_model + self.sums[1].model_model;
        // Var(S) = σ²/Σ w·(m − m̄)²: the weights make the sums those of the
        // total forces, on which the sensor's noise σ is the same.
        (self.noise <= Self::MAX_RELATIVE_ERROR * s.abs() * spread.sqrt()).then_some(s)
    }

    /// The largest relative standard deviation of S from the sensor's
    /// noise that counts as an identification: 0.05, the accuracy asked of
    /// the estimator (what the shipped plants' indentations reach:
    /// docs/controllers.md, "Online estimation").
    pub const MAX_RELATIVE_ERROR: f64 = 0.05;

    /// The least-squares slope once the model's forces have changed over
    /// the rows taken (the line [`Self::falls_below`] tests against).
    fn slope(&self) -> Option<f64> {
        let mm = self.sums[0].model_model + self.sums[1].model_model;
        let my = self.sums[0].model_measured + self.sums[1].model_measured;
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

    fn take(&mut self, row: &PendingRow) {
        for i in 0..2 {
            self.sums[i].add(row.weight, row.model[i], row.measured[i]);
            self.magnitude += row.weight * row.model[i] * row.model[i];
        }
        self.rows += 1;
    }

    /// Whether `row`'s normal force per unit length lies below the line
    /// fitted so far by more than the threshold, with `noise` the sensor's
    /// noise on it (N/m). The prediction's variance at m, in the total
    /// forces the weights stand for: σ²(1 + w/Σw + w(m − m̄)²/Σw(m − m̄)²)
    /// (the offset's and the common slope's share).
    fn falls_below(&self, row: &PendingRow, noise: f64) -> bool {
        if self.rows < Self::MIN_ROWS {
            return false;
        }
        let Some(s) = self.slope() else {
            return false;
        };
        let n = &self.sums[0];
        let spread = self.sums[0].model_model + self.sums[1].model_model;
        let dm = row.model[0] - n.mean_model;
        let predicted = n.mean_measured + s * dm;
        let leverage = row.weight / n.weight + row.weight * dm * dm / spread;
        let threshold = Self::SIGMAS * noise * (1.0 + leverage).sqrt()
            + Self::RELATIVE_TOLERANCE * predicted.abs();
        row.measured[0] < predicted - threshold
    }
}

#[cfg(test)]
mod tests {
    use super::IndentationStiffness;

    /// A rise of 3 N/m per tick in the model (and 1.2 N/m tangential), the
    /// plant's at stiffness 1.3 with offsets, on 9 mm of edge; `after(k)`
    /// is the plant's normal force per unit length k ticks past tick
    /// `fracture`, or the rise goes on if `None`.
    fn indent(
        fit: &mut IndentationStiffness,
        ticks: usize,
        fracture: usize,
        after: impl Fn(usize, f64) -> f64,
    ) {
        for k in 0..ticks {
            let m = [3.0 * k as f64, 1.2 * k as f64];
            let mut y = [1.3 * m[0] + 0.7, 1.3 * m[1] - 0.2];
            if k > fracture {
                y[0] = after(k - fracture, 1.3 * 3.0 * fracture as f64 + 0.7);
            }
            fit.observe(0.009, y, m, 0.0);
        }
    }

    #[test]
    fn offsets_leave_the_slope() {
        let mut fit = IndentationStiffness::default();
        indent(&mut fit, 20, usize::MAX, |_, _| 0.0);
        // The last LAG rows are pending until the fit is closed.
        let s = fit.stiffness().unwrap();
        assert!((s - 1.3).abs() < 1e-12, "{s}");
        fit.close();
        let s = fit.stiffness().unwrap();
        assert!((s - 1.3).abs() < 1e-12, "{s}");
        assert!(fit.ended());
    }

    #[test]
    fn a_rise_that_slows_past_the_fracture_ends_the_fit_there() {
        // Past tick 14 the force rises at a fifth of the rate (a crack
        // growing steadily): the fit ends LAG ticks later, with the slope
        // of the linear rise only. Without the end the slope over 40 ticks
        // would be about half.
        let mut fit = IndentationStiffness::default();
        indent(&mut fit, 40, 14, |k, peak| peak + 0.2 * 3.9 * k as f64);
        assert!(fit.ended());
        let s = fit.stiffness().unwrap();
        assert!((s - 1.3).abs() < 1e-12, "{s}");
        // The tangential rows stopped with the normal ones: they are exact
        // on the line too, so any row past the fracture would show in S.
    }

    #[test]
    fn noise_within_the_threshold_does_not_end_the_fit() {
        // ±2 σ alternating on the normal force (σ 0.01 N on 9 mm of edge):
        // never three readings in a row beyond 3 σ of the prediction.
        let mut fit = IndentationStiffness::default();
        let noise = 0.01;
        for k in 0..30 {
            let m = [3.0 * k as f64, 1.2 * k as f64];
            let wobble = if k % 2 == 0 { 2.0 } else { -2.0 } * noise / 0.009;
            fit.observe(0.009, [1.3 * m[0] + wobble, 1.3 * m[1]], m, noise);
        }
        assert!(!fit.ended());
        fit.close();
        // The alternating ±2 σ on 30 evenly spaced rows moves the slope by
        // under 1 % of it.
        let s = fit.stiffness().unwrap();
        assert!((s - 1.3).abs() < 0.013, "{s}");
    }

    #[test]
    fn closing_takes_the_pending_rows_still_on_the_line() {
        // The force drops on the fracture's own tick (the cuboid's 11–33 %):
        // the detector reports it before the fit sees LAG rows below the
        // line; the rows before the drop still count, the drop does not.
        let mut fit = IndentationStiffness::default();
        indent(&mut fit, 16, 14, |_, peak| 0.8 * peak);
        assert!(!fit.ended());
        fit.close();
        assert_eq!(fit.rows, 15);
        let s = fit.stiffness().unwrap();
        assert!((s - 1.3).abs() < 1e-12, "{s}");
    }

    #[test]
    fn a_short_noisy_rise_identifies_nothing() {
        // Five readings of a rise of 0.015 N per tick (the half potato's
        // first segment) under σ = 10 mN: the slope's relative standard
        // deviation is σ/(0.015 N·√10) = 21 %, no identification; fifty
        // exact readings of the same rise are (0.7 %).
        let contact = 0.0045;
        let rise = |fit: &mut IndentationStiffness, n: usize| {
            for k in 0..n {
                let m = 0.015 / contact * k as f64;
                fit.observe(contact, [m, 0.0], [m, 0.0], 0.01);
            }
            fit.close();
        };
        let mut fit = IndentationStiffness::default();
        rise(&mut fit, 5);
        assert_eq!(fit.stiffness(), None);
        let mut fit = IndentationStiffness::default();
        rise(&mut fit, 50);
        assert_eq!(fit.stiffness(), Some(1.0));
    }

    #[test]
    fn nothing_is_known_before_the_model_changes() {
        let mut fit = IndentationStiffness::default();
        assert_eq!(fit.stiffness(), None);
        for _ in 0..5 {
            fit.observe(0.01, [5.0, 1.0], [4.0, 1.0], 0.01);
        }
        fit.observe(0.01, [f64::NAN, 1.0], [4.0, 1.0], 0.01);
        fit.close();
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
                fit.observe(0.01, [5.0e3 * scale, scale], [wobble, scale], 0.0);
            }
            fit.close();
            assert_eq!(fit.stiffness(), None, "scale {scale}");
        }
    }
}
