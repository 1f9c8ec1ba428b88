//! The first fracture, from the normal force alone.

/// Fraction of the peak normal force the force must fall by for a first
/// fracture: a crack that starts releases the load the indentation built
/// (seed 000 §V.B: the force drops at the first fracture).
const DROP_FRACTION: f64 = 0.03;
/// The smallest peak, N, that counts: ten times the default sensor noise
/// (0.01 N), so that noise alone cannot make a drop.
const MIN_PEAK: f64 = 0.1;

/// Detects the first fracture as the tared normal force falling a fixed
/// fraction below the largest value it reached since the edge touched.
/// Latches: once fractured, it stays so.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct FractureOnset {
    peak: f64,
    fractured: bool,
}

impl FractureOnset {
    /// Takes one tick's tared normal force (N, resistance to pressing down
    /// is positive) with the edge below the touch height.
    pub fn observe(&mut self, normal_force: f64) {
        if self.fractured || !normal_force.is_finite() {
            return;
        }
        self.peak = self.peak.max(normal_force);
        if self.peak > MIN_PEAK && normal_force < (1.0 - DROP_FRACTION) * self.peak {
            self.fractured = true;
        }
    }

    /// Whether the first fracture has been seen.
    pub fn fractured(&self) -> bool {
        self.fractured
    }
}

#[cfg(test)]
mod tests {
    use super::FractureOnset;

    #[test]
    fn a_rising_force_is_not_a_fracture_and_a_drop_is() {
        let mut f = FractureOnset::default();
        for k in 0..100 {
            f.observe(0.05 * f64::from(k));
        }
        assert!(!f.fractured());
        f.observe(4.6);
        assert!(f.fractured());
        f.observe(10.0);
        assert!(f.fractured());
    }
}
