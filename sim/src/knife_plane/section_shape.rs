//! From a plane section of the object to the section model's geometry.

use nalgebra::Vector3;

use crate::geometry::{Polygon, SectionPlane, TriangleMesh};
use crate::knife_plane::knife_plane_silhouette;
use crate::section::{SectionError, SectionGeometry};

/// The section model's geometry of `mesh`'s section normal to a straight
/// edge (world z) through its crest: the z of the top of its silhouette in
/// the knife plane, where a descending edge first touches (the middle of a
/// flat top), clipped at `rim_fraction` of its height as the plant clips
/// its sections ([`section_geometry`]; `PlantSettings::rim_fraction`).
///
/// # Errors
/// The mesh does not cross the knife plane, the plane misses the mesh, or
/// the section is not one the section model takes.
pub fn crest_section(
    mesh: &TriangleMesh,
    rim_fraction: f64,
) -> Result<SectionGeometry, SectionError> {
    let silhouette = knife_plane_silhouette(mesh).ok_or(SectionError::UnsupportedShape(
        "the object does not cross the knife plane",
    ))?;
    let (lo, hi) = silhouette.bounds();
    // The silhouette's highest vertices (one on a dome, a flat top's ends).
    let near_top = 1e-9 * (hi.y - lo.y).max(hi.x - lo.x);
    let (sum, n) = silhouette
        .points
        .iter()
        .filter(|p| p.y >= hi.y - near_top)
        .fold((0.0, 0usize), |(sum, n), p| (sum + p.x, n + 1));
    let plane = SectionPlane {
        origin: Vector3::new(0.0, 0.0, sum / n as f64),
        u_axis: Vector3::x(),
        v_axis: Vector3::y(),
    };
    let polygon = plane.section(mesh).ok_or(SectionError::UnsupportedShape(
        "the crest's plane misses the object",
    ))?;
    section_geometry(&polygon, rim_fraction * polygon.bounds().1.y)
}

/// The section model's geometry for a plane section `polygon` (u across the
/// cut, v up from the board): the upper boundary symmetrised about u = 0 and
/// clipped where it is lower than `rim` (m), so that a dome meeting the board
/// (a half potato's rim) ends in a vertical side of height `rim` instead of a
/// sliver of zero height that no mesh resolves.
pub fn section_geometry(polygon: &Polygon, rim: f64) -> Result<SectionGeometry, SectionError> {
    let (lo, hi) = polygon.bounds();
    let half = 0.5 * (hi.x - lo.x);
    // Samples of the upper boundary at the vertices' |u|, symmetrised.
    let mut us: Vec<f64> = polygon
        .points
        .iter()
        .map(|p| p.x.abs())
        .filter(|u| *u < half)
        .collect();
    us.push(0.0);
    us.push(half);
    us.sort_by(f64::total_cmp);
    us.dedup_by(|a, b| (*a - *b).abs() <= 1e-12 * half.max(1e-12));
    let top = |u: f64| -> Option<f64> {
        let (a, b) = (polygon.top_at(u)?, polygon.top_at(-u)?);
        Some(0.5 * (a + b))
    };
    let mut right: Vec<[f64; 2]> = Vec::with_capacity(us.len() + 1);
    for &u in &us {
        match top(u) {
            Some(t) if t >= rim => right.push([u, t]),
            _ => break,
        }
    }
    let Some(&[u_last, t_last]) = right.last() else {
        return Err(SectionError::UnsupportedShape(
            "the section is lower than the rim height everywhere",
        ));
    };
    // Extend to where the boundary drops to the rim height (linear between samples).
    let x_side = match us.iter().find(|&&u| u > u_last) {
        Some(&u_next) => match top(u_next) {
            Some(t_next) if t_next < t_last => {
                u_last + (u_next - u_last) * (t_last - rim) / (t_last - t_next)
            }
            _ => u_last,
        },
        None => half,
    };
    if x_side > u_last {
        right.push([x_side, rim]);
    }
    let x_max = right.last().map_or(half, |p| p[0]);
    let mut vertices: Vec<[f64; 2]> = vec![[-x_max, 0.0], [x_max, 0.0]];
    vertices.extend(right.iter().rev().copied());
    vertices.extend(right.iter().filter(|p| p[0] > 0.0).map(|p| [-p[0], p[1]]));
    SectionGeometry::from_polygon(&vertices)
}

#[cfg(test)]
mod tests {
    use super::*;
    use nalgebra::Vector2;

    #[test]
    fn rectangle_passes_through() {
        let g = section_geometry(&Polygon::rectangle(0.03, 0.025), 1e-4).unwrap();
        assert!((g.height_at_cut() - 0.025).abs() < 1e-15);
        assert!((g.half_width() - 0.015).abs() < 1e-15);
        // Flat top all the way to the vertical side.
        assert!((g.top_at(0.0149) - 0.025).abs() < 1e-15);
    }

    #[test]
    fn dome_is_clipped_at_the_rim() {
        // Half ellipse of half-width 0.03 and height 0.02, as a polygon.
        let pts: Vec<_> = (0..=64)
            .map(|k| {
                let th = std::f64::consts::PI * k as f64 / 64.0;
                Vector2::new(0.03 * th.cos(), 0.02 * th.sin())
            })
            .collect();
        let g = section_geometry(&Polygon::new(pts), 0.002).unwrap();
        assert!((g.height_at_cut() - 0.02).abs() < 1e-12);
        // The ellipse is 2 mm high at |u| = 0.03·√(1 − 0.01) ≈ 0.02985.
        let expect = 0.03 * (1.0f64 - 0.01).sqrt();
        assert!(
            (g.half_width() - expect).abs() < 2e-4,
            "{} vs {expect}",
            g.half_width()
        );
    }
}
