//! A segment of the edge with its cross section (seed 000 §IV, assumption
//! A2): the section, the plane it lies in, and the bookkeeping the plant's
//! tick, placement and re-choice share (where the segment's midpoint is
//! relative to the plane, where the crack tip is in the knife plane, which
//! sections have started cutting).

use std::sync::Arc;

use nalgebra::{Vector2, Vector3};

use shearcut_sim::geometry::SectionPlane;
use shearcut_sim::knife_plane::contact_arc::EdgeSegment;
use shearcut_sim::section::{CrossSection, SectionGeometry};

use crate::crack_front::CrackFront;

/// One segment's section and its bookkeeping.
#[derive(Debug, Clone)]
pub(super) struct SegmentSection {
    /// Index of the segment on the contact arc (heel 0); the worker's slot.
    pub(super) slot: usize,
    pub(super) segment: EdgeSegment,
    /// The section: always here between ticks; away only while a stepping
    /// thread advances it inside a tick ([`crate::section_stepper`]).
    pub(super) home: Option<Box<CrossSection>>,
    /// The section's plane in the world.
    pub(super) plane: SectionPlane,
    /// The section's shape, to tell whether a re-chosen plane cuts the same
    /// one (shared with the worker's jobs).
    pub(super) geometry: Arc<SectionGeometry>,
    /// Whether the plane cuts the object (a segment that slid off the piece
    /// has no material: no force, not advanced).
    pub(super) active: bool,
    /// Knife work per unit length done on the section's predecessors, J/m.
    pub(super) work_offset: f64,
    /// Signed distance of the segment's midpoint from the plane when the
    /// plane was chosen, m: q lies on the midpoint's path, not at the
    /// midpoint (the edge indents below the crack tip), so a slicing segment
    /// starts off its new plane by λ·(d·t); the slide is counted from there.
    /// 0 for a fresh section: the midpoint reaches its first contact when
    /// the section starts.
    pub(super) slide_reference: f64,
    /// Normal distance the edge still has to travel to reach the section's top, m.
    pub(super) gap: f64,
    /// Normal distance the edge has been pulled back out, m.
    pub(super) lift: f64,
    /// Sign of the last tangential motion (+1 towards the tip).
    pub(super) tangential_sign: f64,
    /// Side (±1) of the plane towards which the pending successor was
    /// foreseen; 0 when none is pending.
    pub(super) predicted_sign: f64,
    /// Whether the section took over a cut (a re-chosen successor, or a
    /// near-face segment's first section): its plane follows the segment
    /// even before its edge advances (a successor restarted at the top of
    /// its section has not advanced yet).
    pub(super) successor: bool,
    /// Condensed-line solves of the section's last advance: its cost, for
    /// dealing a tick's sections to the stepping threads (0 before its
    /// first advance).
    pub(super) solves_last_advance: u64,
}

impl SegmentSection {
    /// The section.
    pub(super) fn section(&self) -> &CrossSection {
        self.home
            .as_deref()
            .expect("a section is home between the steps of a tick")
    }

    /// The section, to advance or replace.
    pub(super) fn section_mut(&mut self) -> &mut Box<CrossSection> {
        self.home
            .as_mut()
            .expect("a section is home between the steps of a tick")
    }

    /// Lends the section to a stepping thread (see [`Self::put_back`]).
    pub(super) fn lend(&mut self) -> Option<Box<CrossSection>> {
        self.home.take()
    }

    /// Takes back the section lent by [`Self::lend`].
    pub(super) fn put_back(&mut self, section: Box<CrossSection>) {
        self.home = Some(section);
    }
}

/// The crack front over the tips of the active started sections (`tips` is
/// the preallocated buffer). Allocates nothing.
pub(super) fn fit_front(
    sections: &[SegmentSection],
    tips: &mut Vec<Vector2<f64>>,
) -> Option<CrackFront> {
    tips.clear();
    for s in sections {
        if s.active && started(s) {
            tips.push(tip_of(s));
        }
    }
    CrackFront::fit(tips)
}

/// The started active section nearest along the edge to slot `slot`.
pub(super) fn nearest_started(sections: &[SegmentSection], slot: usize) -> Option<&CrossSection> {
    nearest_started_of(sections.iter(), slot)
}

/// The started active section of `sections` nearest along the edge to slot
/// `slot`.
pub(super) fn nearest_started_of<'a>(
    sections: impl Iterator<Item = &'a SegmentSection>,
    slot: usize,
) -> Option<&'a CrossSection> {
    sections
        .filter(|s| s.active && started(s))
        .min_by_key(|s| s.slot.abs_diff(slot))
        .map(SegmentSection::section)
}

/// Whether a section has started cutting (its edge reached the material).
pub(super) fn started(s: &SegmentSection) -> bool {
    s.section().state().knife_displacement > 0.0
}

/// Whether a section's plane follows its segment: it has started cutting or
/// took over a cut.
pub(super) fn tracked(s: &SegmentSection) -> bool {
    s.successor || started(s)
}

/// How far the segment's midpoint slid off the section's plane since it was
/// chosen (signed, along the plane's normal), m.
pub(super) fn slide_of(s: &SegmentSection, position: &Vector3<f64>) -> f64 {
    signed_offset(&s.plane, &midpoint_world(position, &s.segment)) - s.slide_reference
}

/// A segment's midpoint in the world (x = 0) for the knife at `position`.
pub(super) fn midpoint_world(position: &Vector3<f64>, segment: &EdgeSegment) -> Vector3<f64> {
    position + Vector3::new(0.0, segment.midpoint.y, segment.midpoint.x)
}

/// Signed distance of `p` from `plane` along its normal, m.
pub(super) fn signed_offset(plane: &SectionPlane, p: &Vector3<f64>) -> f64 {
    (p - plane.origin).dot(&plane.normal())
}

/// A section's crack tip in the knife plane (world z, y).
pub(super) fn tip_of(s: &SegmentSection) -> Vector2<f64> {
    let w = s
        .plane
        .to_world(&Vector2::new(0.0, s.section().state().crack_tip_height));
    Vector2::new(w.z, w.y)
}
