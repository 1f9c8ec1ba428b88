//! The F/T sensor's bias, taken from the readings while the knife is in
//! free air.

/// The mean of the wrench readings taken while the edge was above the
/// object's top (the task's touch height), subtracted from later readings:
/// a sensor's bias is constant over a cut, and the only load in free air
/// is none. Before any free-air reading the tare is zero.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct ForceTare {
    sum: [f64; 6],
    count: u32,
    bias: [f64; 6],
}

impl ForceTare {
    /// Takes one tick's wrench; `in_air` while the edge is above the
    /// object's top.
    pub fn observe(&mut self, wrench: &[f64; 6], in_air: bool) {
        if !in_air || wrench.iter().any(|w| !w.is_finite()) {
            return;
        }
        self.count = self.count.saturating_add(1);
        for (k, w) in wrench.iter().enumerate() {
            self.sum[k] += w;
            self.bias[k] = self.sum[k] / f64::from(self.count);
        }
    }

    /// The wrench less the bias, N and N·m.
    pub fn tared(&self, wrench: &[f64; 6]) -> [f64; 6] {
        std::array::from_fn(|k| wrench[k] - self.bias[k])
    }

    /// The bias taken so far, N and N·m.
    pub fn bias(&self) -> [f64; 6] {
        self.bias
    }
}

#[cfg(test)]
mod tests {
    use super::ForceTare;

    #[test]
    fn free_air_readings_set_the_bias_and_contact_readings_do_not() {
        let mut t = ForceTare::default();
        t.observe(&[0.0, 0.4, 0.0, 0.0, 0.0, 0.0], true);
        t.observe(&[0.0, 0.6, 0.0, 0.0, 0.0, 0.0], true);
        t.observe(&[0.0, 9.0, 0.0, 0.0, 0.0, 0.0], false);
        assert!((t.bias()[1] - 0.5).abs() < 1e-15);
        assert!((t.tared(&[0.0, 3.5, 0.0, 0.0, 0.0, 0.0])[1] - 3.0).abs() < 1e-15);
    }
}
