//! The placement of the plant's first sections where the edge arrives
//! ([`Plant`]'s docs, "Sections placed where the edge arrives"): a segment
//! without a section orders one from the worker as its midpoint's path
//! along the direction of motion nears the material, fresh on an intact
//! surface or taking over the cut behind the crack front, and takes it when
//! the midpoint gets there. Allocates nothing on the tick's thread.

use nalgebra::{Vector2, Vector3};

use shearcut_sim::geometry::SectionPlane;
use shearcut_sim::knife_plane::contact_arc::ray_hit;
use shearcut_sim::section::SectionError;

use super::Plant;
use super::segment_section::{
    SegmentSection, fit_front, midpoint_world, nearest_started, signed_offset,
};
use crate::crack_front::CrackFront;
use crate::successor::{Preparation, SuccessorJob};
use crate::successor_policy::SuccessorPolicy;

impl Plant {
    /// Gives the dormant segments their first sections where their
    /// midpoints' paths along the direction of motion u reach the material
    /// (see the type's docs, "Sections placed where the edge arrives").
    /// Within `ORDER_LEAD × update_distance` of the material a segment
    /// orders its section from the worker, re-ordering it when the predicted
    /// plane moves by more than the tolerance of its kind, and takes it
    /// (waiting if the worker is late): an intact surface's section when the
    /// midpoint is within `TAKE_LEAD × update_distance` of it, one behind
    /// the crack front when the midpoint is in the material. Under
    /// [`SuccessorPolicy::KeepCurrent`] a section not built yet is taken on
    /// the first tick after the worker finished it: until then that strip of
    /// the edge cuts nothing (no force, no work), and an intact surface's
    /// section taken after the midpoint passed the surface starts at its top
    /// (the material there is met late, by the edge's further travel). `lookahead`
    /// [`Lookahead::Everywhere`] orders every intact entry whatever its
    /// distance (at construction). Allocates nothing; an error names the
    /// segment's slot.
    pub(super) fn place(&mut self, lookahead: Lookahead) -> Result<(), (usize, SectionError)> {
        if self.dormant.is_empty() {
            return Ok(());
        }
        let position = self.position;
        let u = self.motion;
        let ud = self.update_distance;
        let lead = match lookahead {
            Lookahead::Lead => ORDER_LEAD * ud,
            Lookahead::Everywhere => f64::INFINITY,
        };
        let size = self.factory.object.size();
        let side_tolerance = 1e-9 * size;
        // The front over the started sections' tips (the tips stay in
        // self.tips for `surface_is_cut`), fitted when first needed.
        let mut fitted: Option<Option<CrackFront>> = None;
        let mut k = 0;
        while k < self.dormant.len() {
            let DormantSegment { slot, order } = self.dormant[k];
            let segment = self.edge_segments[slot];
            let m = midpoint_world(&position, &segment);
            let m2 = Vector2::new(m.z, m.y);
            let inside = self
                .silhouette
                .top_at(m2.x)
                .is_some_and(|top| m2.y >= 0.0 && m2.y < top);
            let entry = if inside {
                Some(0.0)
            } else {
                ray_hit(&self.silhouette, m2, u)
            };
            let Some(entry) = entry else {
                // The path misses the object: nothing to prepare.
                self.worker.cancel(slot);
                self.dormant[k].order = None;
                k += 1;
                continue;
            };
            if entry > lead {
                // Far yet: keep what was ordered for the planned direction.
                k += 1;
                continue;
            }
            let ahead = m2 + u * entry;
            let front = *fitted.get_or_insert_with(|| fit_front(&self.sections, &mut self.tips));
            let pending = self.worker.is_pending(slot);
            let on_top = !inside
                && self
                    .silhouette
                    .top_at(ahead.x)
                    .is_some_and(|top| ahead.y >= top - side_tolerance);
            let intact = on_top
                && !(front.is_some()
                    && surface_is_cut(&self.tips, ahead, 0.5 * segment.length, SURFACE_CUT * ud));
            let target = match (order, front) {
                // A midpoint that passed an intact surface before its
                // section was taken (more than the take lead in one tick)
                // still takes the section ordered for it.
                (Some(o), _) if inside && pending && o.kind == EntryKind::Intact => {
                    Some((o.q, EntryKind::Intact))
                }
                _ if intact => Some((ahead, EntryKind::Intact)),
                (_, Some(front)) => {
                    // q: the front's crossing of the path if it lies in the
                    // material (the front is extrapolated beyond the tips
                    // here), else the entry point itself.
                    let q = front
                        .intersect_nearest(ahead, u)
                        .map(|l| ahead + u * l)
                        .filter(|q| {
                            self.silhouette
                                .top_at(q.x)
                                .is_some_and(|top| q.y >= 0.0 && q.y <= top)
                        })
                        .unwrap_or(ahead);
                    Some((q, EntryKind::BehindFront))
                }
                // Entering behind a crack front that does not exist yet
                // (a side face before any section started): wait.
                (_, None) => None,
            };
            let Some((q, kind)) = target else {
                self.worker.cancel(slot);
                self.dormant[k].order = None;
                k += 1;
                continue;
            };
            let keep = order.is_some_and(|o| {
                o.kind == kind && (o.q - q).norm() <= kind.reorder_tolerance() * ud
            });
            if !keep {
                let up = -Vector3::new(0.0, segment.normal.y, segment.normal.x);
                let plane = SectionPlane::normal_to_segment(Vector3::new(0.0, q.y, q.x), up);
                self.worker.submit(
                    slot,
                    SuccessorJob {
                        plane,
                        current: None,
                    },
                );
                self.dormant[k].order = Some(EntryOrder { q, kind });
            }
            let due = match kind {
                EntryKind::Intact => entry <= TAKE_LEAD * ud,
                EntryKind::BehindFront => inside,
            };
            if !(due && self.worker.is_pending(slot)) {
                k += 1;
                continue;
            }
            if self.policy == SuccessorPolicy::KeepCurrent && !self.worker.is_ready(slot) {
                // Not built yet: the segment stays without a section (that
                // strip of the edge cuts nothing) until a later tick takes it.
                self.deferrals += 1;
                k += 1;
                continue;
            }
            let Some((plane, prepared)) = self.worker.take(slot) else {
                k += 1;
                continue;
            };
            let (geometry, mut section) = match prepared {
                Preparation::New { geometry, section } => (geometry, section),
                Preparation::Failed(e) => return Err((slot, e)),
                Preparation::Panicked(p) => std::panic::resume_unwind(p),
                // No material worth a section on that plane: the order
                // stays on record (not pending), so it is re-ordered only
                // once the predicted plane moves on.
                Preparation::NoMaterial | Preparation::SameShape => {
                    k += 1;
                    continue;
                }
            };
            let edge = (m - plane.origin).dot(&plane.v_axis);
            let (gap, slide_reference, successor) = match kind {
                EntryKind::Intact => {
                    // A fresh section: the edge has the rest of the way to
                    // its top to travel. The slide is counted once it starts
                    // cutting, when the midpoint is at q.
                    self.first_contacts += 1;
                    ((edge - geometry.height_at_cut()).max(0.0), 0.0, false)
                }
                EntryKind::BehindFront => {
                    let o = Vector2::new(plane.origin.z, plane.origin.y);
                    let up = Vector2::new(plane.v_axis.z, plane.v_axis.y);
                    let along = front
                        .and_then(|f| f.intersect_nearest(o, up))
                        .filter(|l| *l >= 0.0 && *l <= size)
                        .unwrap_or(m2.y / up.y);
                    let depth = (geometry.height_at_cut() - along).max(0.0);
                    // The material here was cut by the neighbouring part of
                    // the edge, which moved on: the section takes over the
                    // state of the nearest started section (its first
                    // fracture and drag) with the knife where it is, so an
                    // edge already below the front keeps its indentation
                    // (like a re-chosen section, `CrossSection::take_over`).
                    // Without a started neighbour (cannot happen with a
                    // front), a crack below the top still means the first
                    // fracture is done.
                    match nearest_started(&self.sections, slot) {
                        Some(neighbour) => section.take_over(neighbour, depth, edge),
                        None => section.restart_with_crack(depth, depth > 0.0),
                    }
                    self.wakes += 1;
                    (
                        (edge - geometry.height_at_cut()).max(0.0),
                        signed_offset(&plane, &m),
                        true,
                    )
                }
            };
            let at = self
                .sections
                .iter()
                .position(|s| s.slot > slot)
                .unwrap_or(self.sections.len());
            self.sections.insert(
                at,
                SegmentSection {
                    slot,
                    segment,
                    home: Some(section),
                    plane,
                    geometry,
                    active: true,
                    work_offset: 0.0,
                    slide_reference,
                    gap,
                    lift: 0.0,
                    tangential_sign: 0.0,
                    predicted_sign: 0.0,
                    successor,
                    solves_last_advance: 0,
                },
            );
            self.dormant.remove(k);
            // A new section changes the tips: refit when next needed.
            fitted = None;
        }
        Ok(())
    }
}

/// How far ahead [`Plant::place`] orders sections.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(super) enum Lookahead {
    /// Within `ORDER_LEAD × update_distance` of the material (every tick).
    Lead,
    /// Every path that meets the object (at construction, for the planned
    /// direction).
    Everywhere,
}

/// Where a dormant segment's midpoint path enters the material.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum EntryKind {
    /// Through the intact surface: a fresh section (no crack) through the
    /// entry point, taken just before the midpoint gets there.
    Intact,
    /// Through a side face below the top, a surface the knife has already
    /// cut, or with the midpoint already in the material: a section through
    /// the crack front's crossing of the path, taken when the midpoint is
    /// in the material and takes over the cut there.
    BehindFront,
}

impl EntryKind {
    /// How far (in update distances) the predicted plane may move before
    /// the order is renewed. An intact entry's section is fixed until its
    /// edge starts cutting, so it is placed to a tenth of the update
    /// distance; a section behind the front follows its segment at once
    /// (re-chosen after one update distance of slide), so its first plane
    /// need be no closer than that.
    fn reorder_tolerance(self) -> f64 {
        match self {
            Self::Intact => 0.1,
            Self::BehindFront => 1.0,
        }
    }
}

/// The order a dormant segment placed with the worker.
#[derive(Debug, Clone, Copy, PartialEq)]
struct EntryOrder {
    /// The point the section's plane passes through (knife plane (z, y)).
    q: Vector2<f64>,
    /// How the path enters the material there.
    kind: EntryKind,
}

/// A segment without a section yet.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(super) struct DormantSegment {
    /// Its index in the edge's grid (the worker's slot).
    slot: usize,
    /// The last order placed for it (pending with the worker, or taken and
    /// found without material).
    order: Option<EntryOrder>,
}

impl DormantSegment {
    /// The segment at `slot` of the edge's grid, nothing ordered yet.
    pub(super) fn new(slot: usize) -> Self {
        Self { slot, order: None }
    }
}

/// How far ahead of the material (in update distances, along the direction
/// of motion) a dormant segment orders its first section from the worker.
const ORDER_LEAD: f64 = 2.0;

/// How close to an intact surface (in update distances, along the direction
/// of motion) a dormant segment's midpoint takes its first section.
const TAKE_LEAD: f64 = 0.25;

/// Depth below the surface (in update distances) from which the crack
/// interpolated between the started sections' tips counts as having cut
/// the surface. It exceeds the sag of the chord between neighbouring tips
/// on a curved top (0.06 mm for 4.5 mm segments on a 45 mm radius), so an
/// intact curved surface is not taken for a cut one.
const SURFACE_CUT: f64 = 0.25;

/// Whether the surface point `point` (on the silhouette's top) has been cut:
/// the crack interpolated linearly between the started sections' tips
/// (`tips`, any order) bracketing its z, or the nearest tip's within
/// `margin` beyond the outermost, lies more than `depth` below it.
fn surface_is_cut(tips: &[Vector2<f64>], point: Vector2<f64>, margin: f64, depth: f64) -> bool {
    let (mut below, mut above): (Option<Vector2<f64>>, Option<Vector2<f64>>) = (None, None);
    for t in tips {
        if t.x <= point.x && below.is_none_or(|b| t.x > b.x) {
            below = Some(*t);
        }
        if t.x >= point.x && above.is_none_or(|a| t.x < a.x) {
            above = Some(*t);
        }
    }
    let crack = match (below, above) {
        (Some(b), Some(a)) if a.x > b.x => b.y + (point.x - b.x) / (a.x - b.x) * (a.y - b.y),
        (Some(b), Some(_)) => b.y,
        (Some(b), None) if point.x - b.x <= margin => b.y,
        (None, Some(a)) if a.x - point.x <= margin => a.y,
        _ => return false,
    };
    crack < point.y - depth
}
