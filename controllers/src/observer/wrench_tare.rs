//! The F/T sensor's bias and noise level, measured in free air.

use serde::{Deserialize, Serialize};
use shearcut_sim::InvalidSetting;

use super::setting_range::check_range;

/// Settings of [`WrenchTare`].
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct WrenchTareSettings {
    /// Clearance of the edge above the object's outline (as the task gives
    /// it) above which the knife counts as in free air, m (default 2.5e-4,
    /// in [0, 0.05]). It covers the outline's error: a vision system's top
    /// is good to a few tenths of a millimetre. A knife starting 1 mm above
    /// the object (the loop scenarios' start) keeps 0.75 mm of free air:
    /// (0.75 mm / v)·1 kHz samples at speed v, plus those of the ramp-up
    /// (the counts per scenario: docs/observers.md, "Tare").
    pub clearance: f64,
}

impl Default for WrenchTareSettings {
    fn default() -> Self {
        Self { clearance: 2.5e-4 }
    }
}

impl WrenchTareSettings {
    /// Checks every field, naming the key.
    pub fn validate(&self) -> Result<(), InvalidSetting> {
        check_range("clearance", self.clearance, 0.0, 0.05, "m")
    }
}

/// The F/T sensor's bias (its mean reading with nothing touching the knife)
/// and its noise level (the standard deviation of that reading), per axis
/// of `[fx, fy, fz, tx, ty, tz]`, from the readings taken while the edge is
/// in free air: its clearance above the object's outline is above
/// [`WrenchTareSettings::clearance`]. The first reading closer than that
/// freezes the estimate for the rest of the cut.
///
/// Mean and variance are accumulated by Welford's update: one pass, no
/// stored samples, exact to rounding. From N samples the bias has the
/// standard error σ/√N and the noise level the relative standard error
/// 1/√(2(N − 1)) (26 % at N = 10, 11 % at N = 40): a threshold tied to it
/// must allow for that ([`TouchSettings::sigmas`](super::TouchSettings::sigmas)).
///
/// The simulated sensor has no gravity or inertia: a real knife's weight is
/// part of the bias only while the arm holds its orientation, and its
/// inertia adds m·a to the readings while the knife accelerates.
///
/// Allocation-free, O(1) per reading.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct WrenchTare {
    settings: WrenchTareSettings,
    count: u64,
    mean: [f64; 6],
    /// Sums of squared deviations from the running mean (Welford's M2).
    squares: [f64; 6],
    frozen: bool,
}

impl WrenchTare {
    /// An empty tare.
    ///
    /// # Errors
    /// A setting out of range.
    pub fn new(settings: WrenchTareSettings) -> Result<Self, InvalidSetting> {
        settings.validate()?;
        Ok(Self {
            settings,
            count: 0,
            mean: [0.0; 6],
            squares: [0.0; 6],
            frozen: false,
        })
    }

    /// Takes one reading `wrench` (N, N·m) taken with the edge `clearance`
    /// (m) above the object's outline ([`EdgeOutline::clearance`](super::EdgeOutline::clearance)).
    pub fn observe(&mut self, wrench: &[f64; 6], clearance: f64) {
        if self.frozen {
            return;
        }
        // A NaN clearance is no evidence of free air either.
        let free_air = clearance > self.settings.clearance;
        if !free_air {
            self.frozen = true;
            return;
        }
        if wrench.iter().any(|w| !w.is_finite()) {
            return;
        }
        self.count += 1;
        let n = self.count as f64;
        for (i, w) in wrench.iter().enumerate() {
            let delta = w - self.mean[i];
            self.mean[i] += delta / n;
            self.squares[i] += delta * (w - self.mean[i]);
        }
    }

    /// The bias per axis, N and N·m (0 before the first sample).
    pub fn bias(&self) -> [f64; 6] {
        self.mean
    }

    /// The noise level per axis (sample standard deviation), N and N·m (0
    /// with fewer than two samples).
    pub fn sigma(&self) -> [f64; 6] {
        if self.count < 2 {
            return [0.0; 6];
        }
        let n = (self.count - 1) as f64;
        self.squares.map(|s| (s / n).sqrt())
    }

    /// `wrench` less the bias.
    pub fn tared(&self, wrench: &[f64; 6]) -> [f64; 6] {
        std::array::from_fn(|i| wrench[i] - self.mean[i])
    }

    /// Number of free-air samples taken.
    pub fn samples(&self) -> u64 {
        self.count
    }

    /// Whether the edge has come within the clearance (no more samples).
    pub fn frozen(&self) -> bool {
        self.frozen
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn mean_and_deviation_of_known_samples() {
        let mut t = WrenchTare::new(WrenchTareSettings::default()).unwrap();
        for (k, v) in [1.0, 2.0, 3.0, 4.0].iter().enumerate() {
            t.observe(&[*v, 0.5, 0.0, 0.0, 0.0, -0.1], 1e-3 - k as f64 * 1e-4);
        }
        // 1..4: mean 2.5, sample variance 5/3.
        assert_eq!(t.bias()[0], 2.5);
        assert!((t.sigma()[0] - (5.0f64 / 3.0).sqrt()).abs() < 1e-15);
        assert_eq!(t.bias()[1], 0.5);
        assert_eq!(t.sigma()[1], 0.0);
        assert_eq!(t.tared(&[3.0, 0.5, 0.0, 0.0, 0.0, 0.0])[0], 0.5);
        // Within the clearance: frozen for good.
        t.observe(&[100.0; 6], 1e-4);
        t.observe(&[100.0; 6], 1e-3);
        assert!(t.frozen());
        assert_eq!(t.samples(), 4);
        assert_eq!(t.bias()[0], 2.5);
    }

    #[test]
    fn a_bad_clearance_is_refused_with_its_key() {
        let e = WrenchTare::new(WrenchTareSettings { clearance: -1.0 }).unwrap_err();
        assert!(e.to_string().contains("`clearance` = -1"), "{e}");
    }
}
