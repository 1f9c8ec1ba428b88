//! The depth the MPC's model is indexed by: the edge's travel into the
//! object.

/// The knife edge's depth below the object's top: the knife's normal travel
/// since the edge first touched (the first tick with edge in contact), m.
///
/// The surrogate's state (`StageState::depth`, the fit's `CutState::depth`)
/// is this depth, not the crack's: after the first fracture the crack runs
/// ahead of the edge, by an amount that grows steeply with E/R_c (potato,
/// 30 × 15 mm at ξ = 1: 0.34 / 0.69 / 3.6 mm at E/R_c ×0.5 / 1 / 2;
/// `docs/surrogates.md`), and the work per unit depth that the MPC's stages
/// sum (seed 000 eq. 11) is per unit of the knife's travel. A real arm knows
/// it from its own position and the force's onset; the crack's depth it
/// cannot measure.
///
/// The edge touches within a tick, so the depth lags the indentation by up
/// to one tick's normal travel (5 µm at the touch speed of 5 mm/s); the
/// estimator's indentation fit absorbs such an offset
/// ([`IndentationStiffness`](super::IndentationStiffness)). The object's
/// top is where the edge first touches: on a dome (the half potato) the
/// depth is below its crest, as the [`DepthProfile`](super::DepthProfile)
/// is.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct EdgeDepth {
    /// Knife height when the edge first touched, m.
    touch_height: Option<f64>,
}

impl EdgeDepth {
    /// Takes one tick's knife height `y` (m, the measured knife frame's
    /// origin) and length of edge in contact (m), and returns the edge's
    /// depth after it (0 until the edge touches).
    pub fn observe(&mut self, y: f64, contact_length: f64) -> f64 {
        if self.touch_height.is_none() && contact_length > 0.0 {
            self.touch_height = Some(y);
        }
        self.depth_at(y)
    }

    /// The edge's depth with the knife at height `y` (m), 0 before the
    /// touch.
    pub fn depth_at(&self, y: f64) -> f64 {
        self.touch_height.map_or(0.0, |t| (t - y).max(0.0))
    }

    /// Whether the edge has touched the object.
    pub fn touched(&self) -> bool {
        self.touch_height.is_some()
    }
}

#[cfg(test)]
mod tests {
    use super::EdgeDepth;

    #[test]
    fn depth_counts_from_the_first_contact() {
        let mut d = EdgeDepth::default();
        assert_eq!(d.observe(0.030, 0.0), 0.0);
        assert_eq!(d.observe(0.029, 0.0), 0.0);
        assert!(!d.touched());
        // Touch at 28 mm; from then on the depth is the travel below it,
        // whatever the contact length does (a crack that runs ahead, a
        // segment sliding off).
        assert_eq!(d.observe(0.028, 0.01), 0.0);
        assert!((d.observe(0.0255, 0.02) - 0.0025).abs() < 1e-15);
        assert!((d.observe(0.0205, 0.0) - 0.0075).abs() < 1e-15);
        // Never negative when the knife is drawn back up.
        assert_eq!(d.observe(0.031, 0.0), 0.0);
    }
}
