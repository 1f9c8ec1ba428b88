//! The edge's depth below the touch point.

use super::touch::Touch;

/// The knife edge's depth below the point where it touched the object: the
/// knife's downward travel since the [`Touch`] (its back-dated height less
/// the knife's height now), m; 0 before the touch and never negative.
///
/// This is the depth the MPC's model is indexed by (the knife's travel
/// into the object, `mpc::EdgeDepth`), with the touch observed from the
/// force instead of read off the plant's contact length. The crack runs
/// ahead of the edge after the first fracture, so the crack's depth is
/// larger by an amount that grows with E/R_c (`docs/surrogates.md`); the
/// offset at the end of each shipped cut is in `docs/observers.md`.
///
/// Allocation-free, O(1).
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct EdgeDepth {
    /// Knife height at the touch, m.
    touch_height: Option<f64>,
}

impl EdgeDepth {
    /// Takes the knife height `y` (m, the knife frame origin's world y) and
    /// the touch if detected; returns the edge's depth.
    pub fn observe(&mut self, y: f64, touch: Option<&Touch>) -> f64 {
        if self.touch_height.is_none() {
            self.touch_height = touch.map(|t| t.position.y);
        }
        self.depth_at(y)
    }

    /// The edge's depth with the knife at height `y` (m), 0 before the touch.
    pub fn depth_at(&self, y: f64) -> f64 {
        self.touch_height.map_or(0.0, |t| (t - y).max(0.0))
    }

    /// Knife height at the touch, m, once touched.
    pub fn touch_height(&self) -> Option<f64> {
        self.touch_height
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use nalgebra::Vector3;

    #[test]
    fn depth_is_the_travel_below_the_back_dated_touch() {
        let mut d = EdgeDepth::default();
        assert_eq!(d.observe(0.0251, None), 0.0);
        let touch = Touch {
            position: Vector3::new(0.0, 0.02499, -0.02),
            time: 0.05,
            detected_at: 0.052,
        };
        // Detected two ticks late: the depth is already two ticks deep.
        assert!((d.observe(0.02495, Some(&touch)) - 4e-5).abs() < 1e-15);
        // The first touch stays.
        let later = Touch {
            position: Vector3::new(0.0, 0.02, 0.0),
            ..touch
        };
        assert!((d.observe(0.01499, Some(&later)) - 0.01).abs() < 1e-15);
        assert_eq!(d.observe(0.03, Some(&touch)), 0.0);
        assert_eq!(d.touch_height(), Some(0.02499));
    }
}
