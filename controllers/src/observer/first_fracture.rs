//! The first fracture: the normal force giving way under an advancing edge.

use nalgebra::Vector3;
use serde::{Deserialize, Serialize};
use shearcut_sim::InvalidSetting;

use super::setting_range::check_range;

/// Settings of [`FractureDetector`].
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct FractureSettings {
    /// Least drop below the peak that counts, in units of the noise level
    /// of a difference of two readings, √2·σ (default 5, in [1, 100]):
    /// noise alone exceeds it with probability 3·10⁻⁷ per reading. The peak
    /// is the largest of many noisy readings, so it sits about a σ above
    /// the force; 5 leaves room for that.
    pub sigmas: f64,
    /// Least drop below the peak that counts, as a fraction of the peak
    /// (default 0.04, in [0, 0.5]). A fraction rather than the noise alone
    /// because a first fracture may drop the force by far less than
    /// another fall does: on a dome one section of many fractures first,
    /// while the plant's force can fall without any fracture. 0.04 balances
    /// a late detection on the half potato against an early one on the
    /// eggplant (the drops and delays at 0.02, 0.04 and 0.06 are measured
    /// in docs/observers.md, "First fracture").
    pub drop_fraction: f64,
    /// Travel of the knife past the force's peak without a new peak after
    /// which the force has stopped rising, m (default 1e-3, in [1e-5, 0.1]):
    /// a fracture that plateaus the force without a drop is detected at
    /// most this far past the peak. Before the first fracture the force
    /// rises with every step of indentation, so the default lies above the
    /// longest stretch without a new peak that precedes a fracture on the
    /// shipped plants (docs/observers.md, "First fracture").
    pub plateau_travel: f64,
}

impl Default for FractureSettings {
    fn default() -> Self {
        Self {
            sigmas: 5.0,
            drop_fraction: 0.04,
            plateau_travel: 1e-3,
        }
    }
}

impl FractureSettings {
    /// Checks every field, naming the key.
    pub fn validate(&self) -> Result<(), InvalidSetting> {
        check_range("sigmas", self.sigmas, 1.0, 100.0, "")?;
        check_range("drop_fraction", self.drop_fraction, 0.0, 0.5, "")?;
        check_range("plateau_travel", self.plateau_travel, 1e-5, 0.1, "m")
    }
}

/// The first fracture: where and when the force peaked before giving way.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct FirstFracture {
    /// The knife frame origin (world, m) at the force's peak.
    pub position: Vector3<f64>,
    /// Time of the peak, s.
    pub time: f64,
    /// The peak tared normal force, N (≈ R'_c times the edge in contact,
    /// plus friction; seed 000 §III.C).
    pub force: f64,
    /// Time of the reading that detected it, s.
    pub detected_at: f64,
}

/// Detects the first fracture from the tared normal force fy after the
/// touch.
///
/// Before the first fracture the material only deforms: every step of the
/// edge into it raises the normal force (linearly with the indentation
/// under a flat top, faster on a dome as more edge touches). At the first
/// fracture the crack starts and the force gives way: it drops, or stops
/// rising (seed 000 §V.B; the steady cut's force r·R_c per unit length is
/// below the R'_c that started it, or equal to it). So the detector tracks
/// the force's peak since the touch and reports the first fracture at the
/// peak when either
/// - the force falls below the peak by more than
///   max([`FractureSettings::sigmas`]·√2·σ, [`FractureSettings::drop_fraction`]·peak)
///   while the knife is deeper than at the peak (a knife that stops or backs
///   off unloads elastically: that is no fracture), or
/// - the knife has travelled [`FractureSettings::plateau_travel`] past the
///   peak without a new one.
///
/// The detection's delay is bounded by the second rule; the report's time
/// is the peak's, which is when the crack started to within a reading.
/// A reading equal to the previous one bit for bit is a held sample of a
/// sensor slower than the loop, and is skipped.
///
/// Allocation-free, O(1) per reading.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct FractureDetector {
    settings: FractureSettings,
    /// The peak: force (N), time (s), position (m).
    peak: Option<(f64, f64, Vector3<f64>)>,
    previous: Option<f64>,
    fracture: Option<FirstFracture>,
}

impl FractureDetector {
    /// A detector that has seen nothing.
    ///
    /// # Errors
    /// A setting out of range.
    pub fn new(settings: FractureSettings) -> Result<Self, InvalidSetting> {
        settings.validate()?;
        Ok(Self {
            settings,
            peak: None,
            previous: None,
            fracture: None,
        })
    }

    /// Takes one reading after the touch: `time` (s), knife `position`
    /// (world, m), the tared normal force `force` (N, +fy) and the sensor's
    /// noise level `sigma` (N). Returns the first fracture once detected
    /// (and ever after).
    pub fn observe(
        &mut self,
        time: f64,
        position: &Vector3<f64>,
        force: f64,
        sigma: f64,
    ) -> Option<FirstFracture> {
        if self.fracture.is_some() || !force.is_finite() {
            return self.fracture;
        }
        if self
            .previous
            .is_some_and(|p| p.to_bits() == force.to_bits())
        {
            return None;
        }
        self.previous = Some(force);
        let Some((peak, peak_time, peak_position)) = self.peak else {
            self.peak = Some((force, time, *position));
            return None;
        };
        if force > peak {
            self.peak = Some((force, time, *position));
            return None;
        }
        // Travel below the peak's position (the knife's height falls as it
        // cuts).
        let travel = peak_position.y - position.y;
        let s = &self.settings;
        let least_drop = (s.sigmas * std::f64::consts::SQRT_2 * sigma).max(s.drop_fraction * peak);
        let dropped = travel > 0.0 && peak - force > least_drop;
        if dropped || travel > s.plateau_travel {
            self.fracture = Some(FirstFracture {
                position: peak_position,
                time: peak_time,
                force: peak,
                detected_at: time,
            });
        }
        self.fracture
    }

    /// The first fracture, once detected.
    pub fn fracture(&self) -> Option<FirstFracture> {
        self.fracture
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn at(y: f64) -> Vector3<f64> {
        Vector3::new(0.0, y, 0.0)
    }

    /// A linear rise of 0.3 N per 20 µm tick to the fracture at tick 14,
    /// then `after(k)` for k ticks past it.
    fn run(d: &mut FractureDetector, after: impl Fn(usize) -> f64) -> Option<FirstFracture> {
        for k in 0..200 {
            let f = if k <= 14 {
                0.3 * k as f64
            } else {
                after(k - 14)
            };
            if let Some(found) = d.observe(k as f64 * 1e-3, &at(0.025 - 20e-6 * k as f64), f, 0.01)
            {
                return Some(found);
            }
        }
        None
    }

    #[test]
    fn a_drop_is_the_fracture_at_the_peak() {
        let mut d = FractureDetector::new(FractureSettings::default()).unwrap();
        // 15 % down, then the sawtooth of a cut.
        let found = run(&mut d, |k| 4.2 * 0.85 + 0.1 * k as f64).unwrap();
        assert_eq!(found.time, 14e-3);
        assert!((found.force - 4.2).abs() < 1e-12);
        assert_eq!(found.detected_at, 15e-3);
    }

    #[test]
    fn a_plateau_is_the_fracture_after_the_plateau_travel() {
        let mut d = FractureDetector::new(FractureSettings::default()).unwrap();
        // The force stops rising and sags by 0.01 % per tick: the drop
        // stays below its threshold (4 % of 4.2 N) for 400 ticks, but the
        // knife passes 1 mm of travel (50 ticks of 20 µm) past the peak.
        let found = run(&mut d, |k| 4.2 * (1.0 - 1e-4 * k as f64)).unwrap();
        assert_eq!(found.time, 14e-3);
        let late = found.detected_at - found.time;
        assert!((50e-3..=51.0001e-3).contains(&late), "{late}");
    }

    #[test]
    fn held_samples_are_skipped() {
        let mut d = FractureDetector::new(FractureSettings::default()).unwrap();
        // The same 4.2 N again and again after the peak: held samples of a
        // stopped sensor, no evidence either way.
        assert!(run(&mut d, |_| 4.2).is_none());
    }

    #[test]
    fn a_dip_within_the_threshold_and_an_unloading_are_no_fracture() {
        let mut d = FractureDetector::new(FractureSettings::default()).unwrap();
        for k in 0..30 {
            // A 3 % dip every 6 ticks on a rise of 2 % per tick.
            let f = 1.0 + 0.02 * k as f64 - if k % 6 == 5 { 0.05 } else { 0.0 };
            assert!(
                d.observe(k as f64, &at(0.03 - 1e-5 * k as f64), f, 0.0)
                    .is_none()
            );
        }
        // The knife backs off: the force falls, the position rises.
        for k in 0..30 {
            let f = 1.58 - 0.05 * k as f64;
            let y = 0.03 - 2.9e-4 + 1e-5 * k as f64;
            assert!(d.observe(100.0 + k as f64, &at(y), f, 0.0).is_none());
        }
        assert!(d.fracture().is_none());
    }
}
