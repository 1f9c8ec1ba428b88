//! The length of edge in contact, from the geometry of the knife and the
//! object's outline, pinned to the observed touch.

use nalgebra::Vector3;

use super::edge_outline::EdgeOutline;
use super::touch::Touch;

/// The length of edge in contact with the object, m: the edge inside the
/// object's outline in the knife plane ([`EdgeOutline::contact_length`]),
/// with the outline moved up or down so that the edge just meets it where
/// the [`Touch`] was observed (the outline's own height is the vision
/// system's, good to a few tenths of a millimetre; the touch is good to a
/// few micrometres). 0 before the touch.
///
/// It is the edge below the intact surface: after the first fracture the
/// crack runs ahead of the edge, but the faces of the cut still press on the
/// blade's sides and the edge is still in the material, so the plant counts
/// it in contact too. Compared with the plant's contact length, and with
/// the `DepthProfile` read at the observed depth, in `docs/observers.md`.
///
/// Allocation-free; a fixed cost per reading ([`EdgeOutline`]).
#[derive(Debug, Clone, PartialEq)]
pub struct ContactLength {
    outline: EdgeOutline,
    /// Height of the outline's error at the touch (the edge's clearance
    /// above the given outline when it touched), m.
    offset: Option<f64>,
}

impl ContactLength {
    /// Contact lengths of the edge against `outline`.
    pub fn new(outline: EdgeOutline) -> Self {
        Self {
            outline,
            offset: None,
        }
    }

    /// Takes the knife frame origin `position` (world, m) and the touch if
    /// detected; returns the length of edge in contact, m.
    pub fn observe(&mut self, position: &Vector3<f64>, touch: Option<&Touch>) -> f64 {
        if self.offset.is_none()
            && let Some(t) = touch
        {
            let c = self.outline.clearance(t.position.z, t.position.y);
            self.offset = Some(if c.is_finite() { c } else { 0.0 });
        }
        match self.offset {
            Some(offset) => self.outline.contact_length(position.z, position.y - offset),
            None => 0.0,
        }
    }

    /// How far above the given outline the object's surface was found at
    /// the touch, m (negative: below), once touched.
    pub fn outline_offset(&self) -> Option<f64> {
        self.offset
    }

    /// The edge against the outline as given.
    pub fn outline(&self) -> &EdgeOutline {
        &self.outline
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use nalgebra::Vector2;
    use shearcut_sim::geometry::Polygon;
    use shearcut_sim::{Knife, KnifePreset};

    #[test]
    fn the_outline_is_pinned_to_the_touch() {
        let knife = Knife::new(&KnifePreset::Straight.settings()).unwrap();
        // The outline as given: a block 25 mm high over z 0.02..0.05; the
        // object is really 0.2 mm higher.
        let block = Polygon::new(vec![
            Vector2::new(0.02, 0.0),
            Vector2::new(0.05, 0.0),
            Vector2::new(0.05, 0.025),
            Vector2::new(0.02, 0.025),
        ]);
        let mut c = ContactLength::new(EdgeOutline::new(knife.edge(), &block));
        let above = Vector3::new(0.0, 0.0251, 0.0);
        assert_eq!(c.observe(&above, None), 0.0);
        let touch = Touch {
            position: Vector3::new(0.0, 0.0252, 0.0),
            time: 0.0,
            detected_at: 0.0,
        };
        // 10 µm below the touch: the whole 30 mm, though the knife is
        // still above the given outline's top.
        let l = c.observe(&Vector3::new(0.0, 0.02519, 0.0), Some(&touch));
        assert!((l - 0.03).abs() < 3e-5, "{l}");
        assert!((c.outline_offset().unwrap() - 2e-4).abs() < 1e-12);
    }
}
