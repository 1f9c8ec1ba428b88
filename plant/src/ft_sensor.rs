//! The F/T sensor: the true wrench plus bias and seeded white noise, sampled
//! at its own rate.

use rand::SeedableRng;
use rand_chacha::ChaCha8Rng;
use rand_distr::{Distribution, Normal};
use serde::{Deserialize, Serialize};

use shearcut_sim::invalid_setting::{InvalidSetting, non_negative, positive};

/// Settings of the simulated F/T sensor.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct FtSensorSettings {
    /// Standard deviation of the white noise on each force axis, N (default 0.01).
    pub force_noise: f64,
    /// Standard deviation of the white noise on each torque axis, N·m (default 0.0005).
    pub torque_noise: f64,
    /// Constant bias [fx, fy, fz, tx, ty, tz], N and N·m (default zeros).
    pub bias: [f64; 6],
    /// Sample rate, Hz (default 1000). Between samples the last sample is held.
    pub rate_hz: f64,
}

impl Default for FtSensorSettings {
    fn default() -> Self {
        Self {
            force_noise: 0.01,
            torque_noise: 0.0005,
            bias: [0.0; 6],
            rate_hz: 1000.0,
        }
    }
}

impl FtSensorSettings {
    /// Checks every field.
    pub fn validate(&self) -> Result<(), InvalidSetting> {
        non_negative("force_noise", self.force_noise)?;
        non_negative("torque_noise", self.torque_noise)?;
        positive("rate_hz", self.rate_hz)?;
        if let Some(b) = self.bias.iter().find(|b| !b.is_finite()) {
            return Err(InvalidSetting::new("bias", b, "must be finite"));
        }
        Ok(())
    }
}

/// A sensor with its own seeded noise stream. Deterministic: the same seed and
/// the same sequence of calls give bit-identical readings.
#[derive(Debug, Clone)]
pub struct FtSensor {
    settings: FtSensorSettings,
    rng: ChaCha8Rng,
    force_noise: Normal<f64>,
    torque_noise: Normal<f64>,
    held: [f64; 6],
    next_sample_time: f64,
}

impl FtSensor {
    /// A sensor with validated settings and the given seed.
    pub fn new(settings: FtSensorSettings, seed: u64) -> Result<Self, InvalidSetting> {
        settings.validate()?;
        let normal = |sd: f64, key: &str| {
            Normal::new(0.0, sd)
                .map_err(|_| InvalidSetting::new(key, sd, "must be a finite number >= 0"))
        };
        Ok(Self {
            settings,
            rng: ChaCha8Rng::seed_from_u64(seed),
            force_noise: normal(settings.force_noise, "force_noise")?,
            torque_noise: normal(settings.torque_noise, "torque_noise")?,
            held: [0.0; 6],
            next_sample_time: 0.0,
        })
    }

    /// The reading at simulated time `t` (s) of the true wrench `truth`
    /// (`[fx, fy, fz, tx, ty, tz]`): a new sample if a sample instant has been
    /// reached, otherwise the held one. Allocates nothing.
    pub fn read(&mut self, t: f64, truth: &[f64; 6]) -> [f64; 6] {
        if t + 1e-12 >= self.next_sample_time {
            for (i, out) in self.held.iter_mut().enumerate() {
                let noise = if i < 3 {
                    self.force_noise.sample(&mut self.rng)
                } else {
                    self.torque_noise.sample(&mut self.rng)
                };
                *out = truth[i] + self.settings.bias[i] + noise;
            }
            let period = 1.0 / self.settings.rate_hz;
            while self.next_sample_time <= t + 1e-12 {
                self.next_sample_time += period;
            }
        }
        self.held
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn same_seed_same_readings() {
        let s = FtSensorSettings::default();
        let (mut a, mut b) = (FtSensor::new(s, 7).unwrap(), FtSensor::new(s, 7).unwrap());
        for k in 0..100 {
            let t = k as f64 * 1e-3;
            let (ra, rb) = (a.read(t, &[1.0; 6]), b.read(t, &[1.0; 6]));
            assert!(
                ra.iter()
                    .zip(rb.iter())
                    .all(|(x, y)| x.to_bits() == y.to_bits())
            );
        }
    }

    #[test]
    fn noise_statistics_and_bias() {
        let s = FtSensorSettings {
            force_noise: 0.1,
            torque_noise: 0.0,
            bias: [0.5, 0.0, 0.0, 0.0, 0.0, 0.02],
            rate_hz: 1000.0,
        };
        let mut sensor = FtSensor::new(s, 1).unwrap();
        let n = 20_000;
        let (mut sum, mut sq) = (0.0, 0.0);
        for k in 0..n {
            let r = sensor.read(k as f64 * 1e-3, &[0.0; 6]);
            sum += r[0];
            sq += (r[0] - 0.5) * (r[0] - 0.5);
            assert_eq!(r[5], 0.02);
        }
        // Mean within 5 standard errors (0.1/√n ≈ 7e-4); sd within 3 %.
        assert!((sum / n as f64 - 0.5).abs() < 5.0 * 0.1 / (n as f64).sqrt());
        assert!(((sq / n as f64).sqrt() - 0.1).abs() < 0.003);
    }

    #[test]
    fn slower_sensor_holds_its_sample() {
        let s = FtSensorSettings {
            rate_hz: 250.0,
            ..FtSensorSettings::default()
        };
        let mut sensor = FtSensor::new(s, 3).unwrap();
        let r0 = sensor.read(0.0, &[0.0; 6]);
        // 1, 2, 3 ms later: still the sample taken at 0; at 4 ms a new one.
        for k in 1..4 {
            assert_eq!(sensor.read(k as f64 * 1e-3, &[5.0; 6]), r0);
        }
        assert!(sensor.read(4e-3, &[5.0; 6])[0] > 4.0);
    }
}
