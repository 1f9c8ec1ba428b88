//! The blade travel a cut may use along the edge.

use shearcut_sim::arm::ArmReading;

/// Tracks the knife's tangential travel against the blade length available,
/// so that the contact arc stays on the edge.
///
/// The budget is on the net displacement along the edge from where the
/// knife was at the first reading (the arc's position on the blade), not
/// on the path length: a stroke back frees blade again.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct BladeBudget {
    budget: f64,
    start: Option<f64>,
    used: f64,
}

impl BladeBudget {
    /// `budget` m of travel towards the tip.
    pub fn new(budget: f64) -> Self {
        Self {
            budget,
            start: None,
            used: 0.0,
        }
    }

    /// Updates the travel used from the arm's reading of the knife's pose.
    pub fn observe(&mut self, reading: &ArmReading) {
        let z = reading.position.z;
        let start = *self.start.get_or_insert(z);
        self.used = z - start;
    }

    /// Net travel towards the tip so far, m.
    pub fn used(&self) -> f64 {
        self.used
    }

    /// Travel left towards the tip, m (≥ 0).
    pub fn remaining(&self) -> f64 {
        (self.budget - self.used).max(0.0)
    }

    /// Travel left in `direction` (+1 towards the tip, −1 back towards
    /// where the cut started), m (≥ 0): a stroke back may return the arc to
    /// its starting place on the blade, not beyond.
    pub fn remaining_towards(&self, direction: f64) -> f64 {
        if direction >= 0.0 {
            self.remaining()
        } else {
            self.used.max(0.0)
        }
    }

    /// The length of one full stroke, m: the whole budget.
    pub fn stroke_length(&self) -> f64 {
        self.budget
    }

    /// The tangential speed allowed now towards the tip for a wish of
    /// `speed` (m/s, ≥ 0): `speed` while the knife can still stop within
    /// the remaining blade under `acceleration` and `jerk` limits, else 0.
    pub fn allowed_speed(&self, speed: f64, acceleration: f64, jerk: f64) -> f64 {
        self.allowed_speed_towards(1.0, speed, acceleration, jerk)
    }

    /// [`Self::allowed_speed`] in `direction` (+1 towards the tip, −1 back).
    pub fn allowed_speed_towards(
        &self,
        direction: f64,
        speed: f64,
        acceleration: f64,
        jerk: f64,
    ) -> f64 {
        if speed <= 0.0 {
            return 0.0;
        }
        // One tick of travel at the current wish is spent before the shaper
        // reacts: keep a 1 % margin plus the stopping distance.
        if stopping_distance(speed, acceleration, jerk) < 0.99 * self.remaining_towards(direction) {
            speed
        } else {
            0.0
        }
    }
}

/// Time to stop from `speed` (m/s) at rest acceleration under the
/// `acceleration` and `jerk` limits, s (time-optimal: a constant-deceleration
/// phase only when v·j ≥ a²).
pub fn stopping_duration(speed: f64, acceleration: f64, jerk: f64) -> f64 {
    let v = speed.abs();
    if v * jerk >= acceleration * acceleration {
        v / acceleration + acceleration / jerk
    } else {
        2.0 * (v / jerk).sqrt()
    }
}

/// Distance to stop from `speed` (m/s) at rest acceleration under the
/// `acceleration` and `jerk` limits, m: the time-optimal stop is symmetric,
/// so the distance is speed × duration / 2.
pub fn stopping_distance(speed: f64, acceleration: f64, jerk: f64) -> f64 {
    0.5 * speed.abs() * stopping_duration(speed, acceleration, jerk)
}

#[cfg(test)]
mod tests {
    use super::stopping_distance;

    #[test]
    fn stopping_distance_matches_the_profiles() {
        // Jerk-limited only (v < a²/j): v = j·(T/2)², distance v·T/2.
        let (a, j): (f64, f64) = (10.0, 100.0);
        let v: f64 = 0.25; // a²/j = 1
        let t = 2.0 * (v / j).sqrt();
        assert!((stopping_distance(v, a, j) - 0.5 * v * t).abs() < 1e-15);
        // With a constant-deceleration phase: T = v/a + a/j.
        let v = 4.0;
        let t = v / a + a / j;
        assert!((stopping_distance(v, a, j) - 0.5 * v * t).abs() < 1e-15);
        // The two branches meet at v = a²/j.
        let v = a * a / j;
        let lo = stopping_distance(v * (1.0 - 1e-12), a, j);
        let hi = stopping_distance(v * (1.0 + 1e-12), a, j);
        assert!((lo - hi).abs() < 1e-9);
    }
}
