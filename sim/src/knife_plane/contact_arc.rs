//! The arc of the edge that will touch the object, and its segments
//! (seed 000 §IV, assumption A2, Fig. 4(a)).
//!
//! Under A2 every edge point moves only along the knife velocity. The edge
//! points whose straight paths meet the object's silhouette in the knife plane
//! form the contact arc k₁–k₂; it is split into m segments of equal arc length,
//! each with its chord's tangent, normal and slice-push ratio ξᵢ = tan βᵢ.
//!
//! Coordinates here are the knife plane's (z, y): world z and y at x = 0.

use nalgebra::{Vector2, Vector3};

use crate::geometry::{Polygon, SectionPlane, TriangleMesh};
use crate::knife::KnifeEdge;

/// One straight segment of the contact arc, in knife-frame coordinates (z, y).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct EdgeSegment {
    /// Arc length of the segment's heel end, m.
    pub s_start: f64,
    /// Arc length of the segment's tip end, m.
    pub s_end: f64,
    /// Midpoint of the chord in the knife frame (z, y), m.
    pub midpoint: Vector2<f64>,
    /// Unit tangent of the chord (towards the tip).
    pub tangent: Vector2<f64>,
    /// Unit normal of the chord pointing away from the blade (into the material).
    pub normal: Vector2<f64>,
    /// Chord length, m.
    pub length: f64,
}

impl EdgeSegment {
    /// Slice-push ratio ξ = tan β of this segment for a knife moving along
    /// `direction` (knife plane), β the angle between the normal and the
    /// velocity: ξ = |t·d| / (n·d). Infinite when the segment does not move
    /// into the material (n·d ≤ 0).
    pub fn slice_push_ratio(&self, direction: &Vector2<f64>) -> f64 {
        let dn = self.normal.dot(direction);
        if dn <= 0.0 {
            return f64::INFINITY;
        }
        self.tangent.dot(direction).abs() / dn
    }

    /// The segment's tangent and normal as world vectors (x = 0).
    pub fn world_frame(&self) -> (Vector3<f64>, Vector3<f64>) {
        (
            Vector3::new(0.0, self.tangent.y, self.tangent.x),
            Vector3::new(0.0, self.normal.y, self.normal.x),
        )
    }
}

/// The object's silhouette in the knife plane x = 0, as a polygon in (z, y).
pub fn knife_plane_silhouette(mesh: &TriangleMesh) -> Option<Polygon> {
    let plane = SectionPlane {
        origin: Vector3::zeros(),
        u_axis: Vector3::z(),
        v_axis: Vector3::y(),
    };
    plane.section(mesh)
}

/// Smallest λ ≥ 0 at which `origin + λ·direction` meets the polygon's
/// boundary, or None.
pub fn ray_hit(polygon: &Polygon, origin: Vector2<f64>, direction: Vector2<f64>) -> Option<f64> {
    let n = polygon.points.len();
    let mut best: Option<f64> = None;
    for i in 0..n {
        let (a, b) = (polygon.points[i], polygon.points[(i + 1) % n]);
        let e = b - a;
        let denom = direction.x * e.y - direction.y * e.x;
        if denom.abs() < 1e-300 {
            continue;
        }
        let w = a - origin;
        let lambda = (w.x * e.y - w.y * e.x) / denom;
        let mu = (w.x * direction.y - w.y * direction.x) / denom;
        if lambda >= 0.0 && (0.0..=1.0).contains(&mu) && best.is_none_or(|b| lambda < b) {
            best = Some(lambda);
        }
    }
    best
}

/// Number of samples along the edge when searching for k₁ and k₂.
pub const ARC_SEARCH_SAMPLES: usize = 4000;

/// The contact arc (k₁, k₂) in arc length: the edge points (knife frame, the
/// knife's origin at `knife_origin` in the knife plane) whose paths along
/// `direction` hit `silhouette`. None if no edge point's path hits it.
pub fn contact_arc(
    edge: &KnifeEdge,
    knife_origin: Vector2<f64>,
    direction: Vector2<f64>,
    silhouette: &Polygon,
) -> Option<(f64, f64)> {
    arc_where(edge, |p| {
        ray_hit(silhouette, knife_origin + p, direction).is_some()
    })
}

/// The arc of the edge (knife origin at `knife_origin`) over the span
/// [`z_low`, `z_high`] of the knife plane's z: the edge points a knife
/// pressing anywhere over that span could bring down onto the object. None
/// if no edge point lies over it.
pub fn span_arc(
    edge: &KnifeEdge,
    knife_origin: Vector2<f64>,
    z_low: f64,
    z_high: f64,
) -> Option<(f64, f64)> {
    arc_where(edge, |p| (z_low..=z_high).contains(&(knife_origin.x + p.x)))
}

/// The first and last arc lengths at which `holds` (of the edge point in
/// the knife frame) is true, searched over [`ARC_SEARCH_SAMPLES`] samples
/// and refined by bisection (the set is assumed to be one interval).
fn arc_where(edge: &KnifeEdge, holds: impl Fn(Vector2<f64>) -> bool) -> Option<(f64, f64)> {
    let len = edge.length();
    let hits = |s: f64| holds(edge.point_at(s));
    let mut first: Option<usize> = None;
    let mut last: Option<usize> = None;
    for k in 0..=ARC_SEARCH_SAMPLES {
        if hits(len * k as f64 / ARC_SEARCH_SAMPLES as f64) {
            first.get_or_insert(k);
            last = Some(k);
        }
    }
    let (k1, k2) = (first?, last?);
    // Refine each end by bisection between the last miss and the first hit.
    let refine = |hit: usize, miss: Option<usize>| -> f64 {
        let Some(miss) = miss else {
            return len * hit as f64 / ARC_SEARCH_SAMPLES as f64;
        };
        let (mut a, mut b) = (
            len * miss as f64 / ARC_SEARCH_SAMPLES as f64,
            len * hit as f64 / ARC_SEARCH_SAMPLES as f64,
        );
        for _ in 0..60 {
            let m = 0.5 * (a + b);
            if hits(m) { b = m } else { a = m }
        }
        b
    };
    let s1 = refine(k1, k1.checked_sub(1));
    let s2 = refine(k2, (k2 < ARC_SEARCH_SAMPLES).then_some(k2 + 1));
    Some((s1, s2))
}

/// Splits the arc [s1, s2] into `m` segments of equal arc length.
pub fn segments(edge: &KnifeEdge, (s1, s2): (f64, f64), m: usize) -> Vec<EdgeSegment> {
    let m = m.max(1);
    (0..m)
        .map(|i| {
            let a = s1 + (s2 - s1) * i as f64 / m as f64;
            let b = s1 + (s2 - s1) * (i + 1) as f64 / m as f64;
            segment(edge, a, b)
        })
        .collect()
}

/// The segments of the arc `anchor` = [s1, s2] split into `m` equal ones,
/// continued with segments of the same length beyond both ends until they
/// cover `cover` (clipped to the edge: the first and last may be shorter).
/// The anchor's segments are exactly those of [`segments`]; the whole grid
/// runs heel to tip.
pub fn segment_grid(
    edge: &KnifeEdge,
    anchor: (f64, f64),
    m: usize,
    cover: (f64, f64),
) -> Vec<EdgeSegment> {
    let m = m.max(1);
    let (s1, s2) = anchor;
    let step = (s2 - s1) / m as f64;
    if step <= 0.0 {
        return segments(edge, anchor, m);
    }
    let len = edge.length();
    let (low, high) = (cover.0.min(s1).max(0.0), cover.1.max(s2).min(len));
    let before = ((s1 - low) / step).ceil() as usize;
    let after = ((high - s2) / step).ceil() as usize;
    let mut out = Vec::with_capacity(before + m + after);
    for i in (1..=before).rev() {
        let (a, b) = (s1 - step * i as f64, s1 - step * (i - 1) as f64);
        if b > 0.0 {
            out.push(segment(edge, a.max(0.0), b));
        }
    }
    out.extend(segments(edge, anchor, m));
    for i in 0..after {
        let (a, b) = (s2 + step * i as f64, s2 + step * (i + 1) as f64);
        if a < len {
            out.push(segment(edge, a, b.min(len)));
        }
    }
    out
}

/// The chord of the edge between arc lengths `a` and `b`.
fn segment(edge: &KnifeEdge, a: f64, b: f64) -> EdgeSegment {
    let (pa, pb) = (edge.point_at(a), edge.point_at(b));
    let chord = pb - pa;
    let length = chord.norm();
    let tangent = if length > 0.0 {
        chord / length
    } else {
        edge.tangent_at(a)
    };
    EdgeSegment {
        s_start: a,
        s_end: b,
        midpoint: 0.5 * (pa + pb),
        tangent,
        normal: Vector2::new(tangent.y, -tangent.x),
        length,
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::knife::{Knife, KnifePreset};

    fn cuboid_silhouette(z0: f64, length: f64, height: f64) -> Polygon {
        let m = TriangleMesh::cuboid(
            Vector3::new(-0.015, 0.0, z0),
            Vector3::new(0.015, height, z0 + length),
        );
        knife_plane_silhouette(&m).unwrap()
    }

    #[test]
    fn straight_edge_pressing_covers_the_piece() {
        let k = Knife::new(&KnifePreset::Straight.settings()).unwrap();
        let sil = cuboid_silhouette(0.05, 0.03, 0.025);
        // Knife origin 0.03 above the board at z = 0.03: the piece spans edge
        // arc lengths 0.02 to 0.05.
        let arc = contact_arc(
            k.edge(),
            Vector2::new(0.03, 0.03),
            Vector2::new(0.0, -1.0),
            &sil,
        )
        .unwrap();
        assert!(
            (arc.0 - 0.02).abs() < 1e-12 && (arc.1 - 0.05).abs() < 1e-12,
            "{arc:?}"
        );
        let segs = segments(k.edge(), arc, 10);
        assert!((segs.iter().map(|s| s.length).sum::<f64>() - 0.03).abs() < 1e-12);
        assert!(
            segs.iter()
                .all(|s| s.slice_push_ratio(&Vector2::new(0.0, -1.0)) == 0.0)
        );
    }

    #[test]
    fn slicing_lengthens_the_arc_by_the_travel() {
        // Moving at ξ = 1 (45°) towards the heel (−z): edge points up to the
        // height of the piece ahead along z also reach it.
        let k = Knife::new(&KnifePreset::Straight.settings()).unwrap();
        let sil = cuboid_silhouette(0.05, 0.03, 0.025);
        let d = Vector2::new(-1.0, -1.0).normalize();
        let arc = contact_arc(k.edge(), Vector2::new(0.03, 0.026), d, &sil).unwrap();
        // The edge at y = 0.026 is 1 mm above the top: a point must start at
        // z ≥ 0.051 to land on the top face, and points up to z = 0.08 + 0.026
        // reach the far face before the board. Knife origin at z = 0.03.
        assert!(
            (arc.0 - 0.021).abs() < 1e-9 && (arc.1 - 0.076).abs() < 1e-9,
            "{arc:?}"
        );
        let segs = segments(k.edge(), arc, 4);
        assert!((segs[0].slice_push_ratio(&d) - 1.0).abs() < 1e-12);
    }

    #[test]
    fn chef_edge_segments_tilt_towards_the_tip() {
        let k = Knife::new(&KnifePreset::Chef.settings()).unwrap();
        // A piece far along the edge (z0 = 0.14 from the heel) under the curved part.
        let sil = cuboid_silhouette(0.14, 0.03, 0.025);
        let arc = contact_arc(
            k.edge(),
            Vector2::new(0.0, 0.026),
            Vector2::new(0.0, -1.0),
            &sil,
        )
        .unwrap();
        let segs = segments(k.edge(), arc, 10);
        // Normals tilt more towards the tip, so ξᵢ grows along the arc.
        let xi: Vec<f64> = segs
            .iter()
            .map(|s| s.slice_push_ratio(&Vector2::new(0.0, -1.0)))
            .collect();
        assert!(xi.windows(2).all(|w| w[1] > w[0]), "{xi:?}");
        for s in &segs {
            assert!(
                (s.tangent.norm() - 1.0).abs() < 1e-12 && s.tangent.dot(&s.normal).abs() < 1e-12
            );
        }
    }

    #[test]
    fn ray_hits_first_boundary() {
        let sq = Polygon::rectangle(2.0, 1.0);
        let l = ray_hit(&sq, Vector2::new(0.0, 3.0), Vector2::new(0.0, -1.0)).unwrap();
        assert!((l - 2.0).abs() < 1e-15);
        assert!(ray_hit(&sq, Vector2::new(5.0, 3.0), Vector2::new(0.0, -1.0)).is_none());
    }
}
