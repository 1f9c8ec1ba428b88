//! Contact: the tared normal force rising out of the sensor's noise.

use nalgebra::Vector3;
use serde::{Deserialize, Serialize};
use shearcut_sim::InvalidSetting;

use super::setting_range::{check_count, check_range};

/// Readings [`TouchDetector`] remembers for back-dating the touch.
pub const TOUCH_HISTORY: usize = 16;

/// Settings of [`TouchDetector`].
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct TouchSettings {
    /// Threshold on the tared normal force in units of its free-air noise
    /// level σ ([`WrenchTare::sigma`](super::WrenchTare::sigma) of fy)
    /// (default 5, in [1, 100]). σ̂ from N free-air samples may be
    /// 1/√(2(N − 1)) low, and 5 σ̂ is still high enough that pure noise
    /// rarely crosses it (the odds and probabilities: docs/observers.md,
    /// "Why these thresholds").
    pub sigmas: f64,
    /// Least threshold, N (default 0.02, in [0, 100]): the threshold with a
    /// noise-free sensor or no free-air samples.
    pub min_force: f64,
    /// Consecutive readings above the threshold that make a touch (default
    /// 2, in [1, 8]): two in a row by noise alone are rare over a whole
    /// approach (docs/observers.md, "Why these thresholds"); each extra
    /// reading delays the detection by a tick but not the back-dated touch.
    pub consecutive: usize,
}

impl Default for TouchSettings {
    fn default() -> Self {
        Self {
            sigmas: 5.0,
            min_force: 0.02,
            consecutive: 2,
        }
    }
}

impl TouchSettings {
    /// Checks every field, naming the key.
    pub fn validate(&self) -> Result<(), InvalidSetting> {
        check_range("sigmas", self.sigmas, 1.0, 100.0, "")?;
        check_range("min_force", self.min_force, 0.0, 100.0, "N")?;
        check_count("consecutive", self.consecutive, 1, 8)
    }
}

/// The touch: where and when the edge met the object.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Touch {
    /// The knife frame origin (world, m) when the force began to rise,
    /// back-dated (see [`TouchDetector`]).
    pub position: Vector3<f64>,
    /// Time the force began to rise, back-dated, s.
    pub time: f64,
    /// Time of the reading that detected the touch, s.
    pub detected_at: f64,
}

/// One remembered reading: time (s), knife position (m), tared normal force (N).
#[derive(Debug, Clone, Copy, PartialEq, Default)]
struct Sample {
    time: f64,
    position: Vector3<f64>,
    force: f64,
}

/// Detects the edge's touch from the tared normal force fy (the object's
/// resistance to the knife pressing down: +fy on the knife): the touch is
/// [`TouchSettings::consecutive`] readings in a row above
/// max([`TouchSettings::sigmas`]·σ, [`TouchSettings::min_force`]).
///
/// # Back-dating
/// Before the first fracture the normal force rises with the indentation
/// (linearly under a flat top, faster on a dome as more edge comes into
/// contact). The readings of the detecting run are fitted with a line
/// f = a + b·s in the knife's downward travel s = −y (least squares; with
/// one consecutive reading, the line through it and the reading before),
/// and the touch put where the line reaches zero, s₀ = −a/b: within a tick
/// under a flat top. On a convex rise (a dome) the secant's zero lies
/// between the true touch and the run, never before the touch. s₀ is kept
/// within the remembered readings ([`TOUCH_HISTORY`]) and not after the
/// run's first reading; a rise that does not rise (b ≤ 0, noise) gives that
/// first reading. Time and position at s₀ are interpolated between the
/// readings around it.
///
/// Allocation-free, O(1) per reading.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct TouchDetector {
    settings: TouchSettings,
    history: [Sample; TOUCH_HISTORY],
    /// Readings taken (the newest is at `(taken − 1) % TOUCH_HISTORY`).
    taken: usize,
    /// Readings in a row above the threshold.
    run: usize,
    touch: Option<Touch>,
}

impl TouchDetector {
    /// A detector that has seen nothing.
    ///
    /// # Errors
    /// A setting out of range.
    pub fn new(settings: TouchSettings) -> Result<Self, InvalidSetting> {
        settings.validate()?;
        Ok(Self {
            settings,
            history: [Sample::default(); TOUCH_HISTORY],
            taken: 0,
            run: 0,
            touch: None,
        })
    }

    /// The force threshold for the noise level `sigma` (N).
    pub fn threshold(&self, sigma: f64) -> f64 {
        (self.settings.sigmas * sigma).max(self.settings.min_force)
    }

    /// Takes one reading: `time` (s), knife `position` (world, m), the
    /// tared normal force `force` (N, +fy) and the sensor's noise level
    /// `sigma` (N). Returns the touch once detected (and ever after).
    pub fn observe(
        &mut self,
        time: f64,
        position: &Vector3<f64>,
        force: f64,
        sigma: f64,
    ) -> Option<Touch> {
        if self.touch.is_some() {
            return self.touch;
        }
        self.history[self.taken % TOUCH_HISTORY] = Sample {
            time,
            position: *position,
            force,
        };
        self.taken += 1;
        self.run = if force > self.threshold(sigma) {
            self.run + 1
        } else {
            0
        };
        if self.run >= self.settings.consecutive {
            self.touch = Some(self.back_dated(time));
        }
        self.touch
    }

    /// The touch, once detected.
    pub fn touch(&self) -> Option<Touch> {
        self.touch
    }

    /// The `back`-th reading before the newest (0: the newest).
    fn sample(&self, back: usize) -> Sample {
        self.history[(self.taken - 1 - back) % TOUCH_HISTORY]
    }

    /// The touch back-dated from the current run (see the type's docs).
    fn back_dated(&self, detected_at: f64) -> Touch {
        let remembered = self.taken.min(TOUCH_HISTORY);
        let fitted = self.run.max(2).min(remembered);
        let first = self.sample(self.run.min(remembered) - 1);
        // Least squares over the `fitted` newest readings, in s = −y.
        let n = fitted as f64;
        let (mut ss, mut sf, mut sss, mut ssf) = (0.0, 0.0, 0.0, 0.0);
        for back in 0..fitted {
            let p = self.sample(back);
            let s = -p.position.y;
            ss += s;
            sf += p.force;
            sss += s * s;
            ssf += s * p.force;
        }
        let det = n * sss - ss * ss;
        let slope = if det > 0.0 {
            (n * ssf - ss * sf) / det
        } else {
            0.0
        };
        let s_first = -first.position.y;
        let oldest = self.sample(remembered - 1);
        let s0 = if slope > 0.0 {
            let intercept = (sf - slope * ss) / n;
            (-intercept / slope).clamp(-oldest.position.y, s_first)
        } else {
            s_first
        };
        // The remembered readings around s₀ (travel grows towards the newest).
        for back in 0..remembered - 1 {
            let (late, early) = (self.sample(back), self.sample(back + 1));
            let (s_late, s_early) = (-late.position.y, -early.position.y);
            if s_early <= s0 && s0 <= s_late {
                let t = if s_late > s_early {
                    (s0 - s_early) / (s_late - s_early)
                } else {
                    1.0
                };
                return Touch {
                    position: early.position + (late.position - early.position) * t,
                    time: early.time + (late.time - early.time) * t,
                    detected_at,
                };
            }
        }
        Touch {
            position: first.position,
            time: first.time,
            detected_at,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn at(y: f64) -> Vector3<f64> {
        Vector3::new(0.0, y, 0.0)
    }

    #[test]
    fn a_linear_rise_is_back_dated_to_its_zero() {
        let mut d = TouchDetector::new(TouchSettings::default()).unwrap();
        // 20 µm per tick; the force rises 0.3 N per tick from y = 24.99 mm
        // (between the readings at 25.000 and 24.980 mm).
        let mut found = None;
        for k in 0..80 {
            let y = 0.026 - 20e-6 * k as f64;
            let f = (0.02499 - y).max(0.0) / 20e-6 * 0.3;
            found = d.observe(k as f64 * 1e-3, &at(y), f, 0.01);
            if found.is_some() {
                // Threshold 0.05 N: the readings at 24.98 mm (0.15 N, k = 51)
                // and 24.96 mm make the run.
                assert_eq!(k, 52);
                break;
            }
        }
        let t = found.expect("touch detected");
        // A line through exact points: its zero exactly, to rounding.
        assert!((t.position.y - 0.02499).abs() < 1e-12, "{}", t.position.y);
        assert!((t.time - 0.0505).abs() < 1e-9, "{}", t.time);
        assert_eq!(t.detected_at, 52.0 * 1e-3);
    }

    #[test]
    fn noise_below_the_threshold_is_no_touch() {
        let mut d = TouchDetector::new(TouchSettings::default()).unwrap();
        // Alternating ±4.9 σ, and single readings above 5 σ: never two in
        // a row.
        for k in 0..200 {
            let f = match k % 3 {
                0 => 0.049,
                1 => 0.06,
                _ => -0.049,
            };
            assert!(d.observe(k as f64, &at(0.03), f, 0.01).is_none(), "{k}");
        }
    }

    #[test]
    fn a_noise_free_sensor_uses_the_least_threshold() {
        let d = TouchDetector::new(TouchSettings::default()).unwrap();
        assert_eq!(d.threshold(0.0), 0.02);
        assert_eq!(d.threshold(0.01), 0.05);
        let bad = TouchSettings {
            consecutive: 0,
            ..TouchSettings::default()
        };
        let e = TouchDetector::new(bad).unwrap_err();
        assert!(e.to_string().starts_with("`consecutive` = 0"), "{e}");
    }
}
