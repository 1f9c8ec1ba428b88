//! The re-choice of the plant's moving cross sections (seed 000 §IV,
//! Fig. 4(b); [`Plant`]'s docs, "Moving cross sections" and "Successors
//! prepared ahead"): after each tick a section whose segment's midpoint slid
//! more than the update distance off its plane is re-chosen through the
//! crack front's crossing of the midpoint's path, its successor taken from
//! the worker; and each tracked section without a pending successor orders
//! one where the midpoint will be at the threshold. Under
//! [`SuccessorPolicy::KeepCurrent`] a successor not built yet is left to a
//! later tick. Allocates nothing on the tick's thread.

use std::sync::Arc;

use nalgebra::{Vector2, Vector3};

use shearcut_sim::geometry::SectionPlane;
use shearcut_sim::knife_plane::contact_arc::EdgeSegment;
use shearcut_sim::section::SectionError;

use super::Plant;
use super::segment_section::{
    SegmentSection, fit_front, midpoint_world, nearest_started_of, signed_offset, slide_of, tip_of,
    tracked,
};
use crate::crack_front::CrackFront;
use crate::successor::{Preparation, SuccessorJob};
use crate::successor_policy::SuccessorPolicy;

impl Plant {
    /// Re-chooses the sections whose segments slid more than
    /// `update_distance` off their planes, and orders the successors of the
    /// tracked sections without one from the worker (seed 000 §IV, Fig. 4(b);
    /// see the type's docs). Allocates nothing.
    pub(super) fn rechoose(&mut self) -> Result<(), SectionError> {
        let position = self.position;
        let threshold = self.update_distance;
        let worker = &self.worker;
        let motion = self.motion;
        let due = self.sections.iter().any(|s| {
            let slide = slide_of(s, &position);
            tracked(s)
                && (slide.abs() > threshold
                    || foresee(
                        s,
                        slide,
                        approach_rate(s, &motion),
                        worker.is_pending(s.slot),
                    ))
        });
        if !due {
            return Ok(());
        }
        let Some(front) = fit_front(&self.sections, &mut self.tips) else {
            return Ok(());
        };
        self.front = Some(front);
        let u = self.motion;
        let size = self.factory.object.size();
        for i in 0..self.sections.len() {
            let (before, rest) = self.sections.split_at_mut(i);
            let (s, after) = rest.split_first_mut().expect("i < len");
            if !tracked(s) {
                continue;
            }
            let m = midpoint_world(&position, &s.segment);
            let m2 = Vector2::new(m.z, m.y);
            let slide = signed_offset(&s.plane, &m) - s.slide_reference;
            if slide.abs() > threshold {
                let sign = slide.signum();
                if !(self.worker.is_pending(s.slot) && s.predicted_sign == sign) {
                    // Not foreseen (the motion reversed, or one tick crossed
                    // the whole half distance): prepare it now and wait.
                    self.worker.cancel(s.slot);
                    let plane = plane_on_path(&front, m2, u, tip_of(s), &s.segment, size);
                    self.worker.submit(s.slot, job(s, plane));
                    self.unforeseen += 1;
                    s.predicted_sign = sign;
                }
                if self.policy == SuccessorPolicy::KeepCurrent && !self.worker.is_ready(s.slot) {
                    // Not built yet: the section keeps cutting on its plane
                    // and the re-choice takes the successor on a later tick.
                    self.deferrals += 1;
                    continue;
                }
                self.rechoices += 1;
                s.predicted_sign = 0.0;
                let Some((plane, prepared)) = self.worker.take(s.slot) else {
                    continue;
                };
                let tip = tip_of(s);
                let was_active = s.active;
                let old_origin = s.plane.origin;
                s.plane = plane;
                s.slide_reference = signed_offset(&plane, &m);
                match prepared {
                    Preparation::NoMaterial => s.active = false,
                    Preparation::SameShape => {}
                    Preparation::Failed(e) => return Err(e),
                    // `take` resumes a worker's panic; kept for completeness.
                    Preparation::Panicked(p) => std::panic::resume_unwind(p),
                    Preparation::New { geometry, section } => {
                        // The crack carried over: the front where it crosses
                        // the new plane (its trace in the knife plane is the
                        // line from the board point along the segment's up).
                        // From an active predecessor, the front shifted to
                        // pass through the predecessor's own tip, so that
                        // the least-squares fit's residual at that tip
                        // (millimetres where intact flank tips and deep
                        // middle ones share one quadratic) neither heals nor
                        // deepens the crack; or, if it misses within the
                        // object's size, the height of the predecessor's
                        // tip. A predecessor that had slid off the piece
                        // (sawing back over a side face) was not advanced
                        // while the rest of the edge cut on: its tip is
                        // stale, so the segment re-enters behind the
                        // current front and takes over the nearest started
                        // section's cut, as a first section entering
                        // through a side face does (`Plant::place`).
                        let o = Vector2::new(plane.origin.z, plane.origin.y);
                        let up = Vector2::new(plane.v_axis.z, plane.v_axis.y);
                        let neighbour =
                            nearest_started_of(before.iter().chain(after.iter()), s.slot)
                                .filter(|_| !was_active);
                        let (through, fallback) = match neighbour {
                            Some(n) => (front, n.state().crack_tip_height),
                            None => {
                                let mut through_tip = front;
                                through_tip.coefficients[0] += tip.y - front.height_at(tip.x);
                                (through_tip, tip.y / up.y)
                            }
                        };
                        let along = through
                            .intersect_nearest(o, up)
                            .filter(|l| *l >= 0.0 && *l <= size)
                            .unwrap_or(fallback);
                        let depth = (geometry.height_at_cut() - along).max(0.0);
                        // The edge stays where it is: the predecessor's edge
                        // height moved to the new plane's board point (both
                        // planes are normal to the same segment, so heights
                        // differ by the origins' offset along its up); for
                        // a predecessor that had slid off the object (not
                        // advanced), the midpoint's own height, less any
                        // lift.
                        let edge = if was_active {
                            s.section().state().edge_height
                                + (old_origin - plane.origin).dot(&plane.v_axis)
                        } else {
                            (m - plane.origin).dot(&plane.v_axis) - s.lift
                        };
                        // The successor takes over the cut: that crack, the
                        // predecessor's first-fracture flag, and the knife
                        // where it is (see `CrossSection::take_over`).
                        let mut section = section;
                        section.take_over(neighbour.unwrap_or(s.section()), depth, edge);
                        // An edge above the new section's top (a lower shape
                        // towards the flank) has that gap to travel first.
                        s.gap = (edge - geometry.height_at_cut()).max(0.0);
                        let old = *s.section().state();
                        *s.section_mut() = section;
                        s.work_offset += old.work.knife;
                        s.geometry = geometry;
                        s.active = true;
                        s.successor = true;
                        self.rebuilds += 1;
                    }
                }
            } else if foresee(
                s,
                slide,
                approach_rate(s, &u),
                self.worker.is_pending(s.slot),
            ) {
                // Foresee the successor: where the midpoint will be when the
                // slide reaches the threshold on the side it is moving to,
                // moving on along the direction of motion u, and the front's
                // crossing of u's line through that point. (A new order
                // supersedes a pending one.)
                let rate = approach_rate(s, &u);
                let sign = rate.signum();
                let travel = (sign * threshold - slide) / rate;
                let ahead = m2 + u * travel;
                let plane = plane_on_path(&front, ahead, u, tip_of(s), &s.segment, size);
                self.worker.submit(s.slot, job(s, plane));
                s.predicted_sign = sign;
            }
        }
        Ok(())
    }
}

/// Whether to order a successor for `s` (slid `slide` off its plane, moving
/// off it at `rate` per unit travel): none is pending, or the pending one
/// was foreseen on the other side of the plane, which the midpoint has
/// crossed back over and is moving away from (the motion reversed). Never
/// while moving within the plane (`rate` = 0).
fn foresee(s: &SegmentSection, slide: f64, rate: f64, pending: bool) -> bool {
    rate != 0.0
        && (!pending || (s.predicted_sign * slide < 0.0 && rate.signum() != s.predicted_sign))
}

/// Rate at which the segment's midpoint leaves its section's plane per unit
/// travel along the direction of motion `u` (signed along the plane's
/// normal); 0 below 1e-9 (moving within the plane).
fn approach_rate(s: &SegmentSection, u: &Vector2<f64>) -> f64 {
    let n = s.plane.normal();
    let rate = u.dot(&Vector2::new(n.z, n.y));
    if rate.abs() < 1e-9 { 0.0 } else { rate }
}

/// The worker's job for a successor of `s` on `plane`.
fn job(s: &SegmentSection, plane: SectionPlane) -> SuccessorJob {
    SuccessorJob {
        plane,
        current: s.active.then(|| Arc::clone(&s.geometry)),
    }
}

/// The plane normal to `segment` through q, where the line through `m`
/// (knife plane) along the direction of motion `u` meets the crack front
/// nearest to `m`; if it misses (or meets the front's extrapolation farther
/// than `size` away), q is at the height of the section's own `tip` on that
/// line (at `m` for a motion without vertical component).
fn plane_on_path(
    front: &CrackFront,
    m: Vector2<f64>,
    u: Vector2<f64>,
    tip: Vector2<f64>,
    segment: &EdgeSegment,
    size: f64,
) -> SectionPlane {
    let lambda = front
        .intersect_nearest(m, u)
        .filter(|l| l.abs() <= size)
        .unwrap_or_else(|| {
            if u.y.abs() > 1e-12 {
                (tip.y - m.y) / u.y
            } else {
                0.0
            }
        });
    let q = m + u * lambda;
    let up = -Vector3::new(0.0, segment.normal.y, segment.normal.x);
    SectionPlane::normal_to_segment(Vector3::new(0.0, q.y, q.x), up)
}
