//! Procedural natural shapes: a half potato on its flat base and an eggplant.
//!
//! Both are centred on the knife plane x = 0, sit on the board (y = 0) and
//! start at z = 0, extending along +z; the scenario shifts them along z.

use std::f64::consts::PI;

use nalgebra::Vector3;

use super::triangle_mesh::TriangleMesh;

/// Tessellation: rings along the shape's axis and points per ring.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Tessellation {
    /// Number of rings (≥ 4).
    pub rings: usize,
    /// Points per ring (≥ 8).
    pub segments: usize,
}

impl Default for Tessellation {
    fn default() -> Self {
        Self {
            rings: 48,
            segments: 64,
        }
    }
}

/// Half of an ellipsoid with semi-axes (width/2, height, length/2), cut at its
/// equator and resting on the cut: a potato halved lengthwise and laid flat
/// (seed 000 §V.C, Fig. 5).
pub fn half_potato(length: f64, width: f64, height: f64, tess: Tessellation) -> TriangleMesh {
    let (a, c) = (0.5 * width, 0.5 * length);
    // Dome parametrised by polar angle θ ∈ [0, π/2] from the top and azimuth φ.
    let rings = tess.rings.max(4);
    let segs = tess.segments.max(8);
    let mut v = vec![Vector3::new(0.0, height, c)]; // apex
    for i in 1..=rings {
        let th = 0.5 * PI * i as f64 / rings as f64;
        for j in 0..segs {
            let ph = 2.0 * PI * j as f64 / segs as f64;
            v.push(Vector3::new(
                a * th.sin() * ph.cos(),
                height * th.cos(),
                c + c * th.sin() * ph.sin(),
            ));
        }
    }
    let base_centre = v.len();
    v.push(Vector3::new(0.0, 0.0, c));
    let ring = |i: usize, j: usize| 1 + (i - 1) * segs + (j % segs);
    let mut t = Vec::new();
    for j in 0..segs {
        t.push([0, ring(1, j + 1), ring(1, j)]);
    }
    for i in 1..rings {
        for j in 0..segs {
            t.push([ring(i, j), ring(i, j + 1), ring(i + 1, j)]);
            t.push([ring(i, j + 1), ring(i + 1, j + 1), ring(i + 1, j)]);
        }
    }
    for j in 0..segs {
        t.push([base_centre, ring(rings, j), ring(rings, j + 1)]);
    }
    TriangleMesh::new(v, t).expect("the procedural half potato is closed")
}

/// Radius profile of the eggplant along its axis, u ∈ [0, 1] from stem to
/// blossom end: a slim neck swelling into a bulb, zero at both ends.
pub fn eggplant_profile(u: f64) -> f64 {
    let u = u.clamp(0.0, 1.0);
    // sin-shaped closure at both ends, weighted towards the blossom end.
    let closure = (PI * u).sin().max(0.0).sqrt();
    let swell = 0.55 + 0.45 * u;
    closure * swell
}

/// An eggplant lying on the board across the knife (its axis along world x,
/// stem at −x): a body of revolution of length `length` and largest diameter
/// `diameter`, flattened at the bottom by `flat` (m, where its weight rests on
/// the board). The knife plane x = 0 cuts it into slices, as a cook does.
pub fn eggplant(length: f64, diameter: f64, flat: f64, tess: Tessellation) -> TriangleMesh {
    let rings = tess.rings.max(4);
    let segs = tess.segments.max(8);
    let r_max = 0.5 * diameter;
    // Normalise the profile's peak to 1.
    let peak = (0..=1000)
        .map(|k| eggplant_profile(k as f64 / 1000.0))
        .fold(0.0, f64::max);
    let axis_y = r_max - flat;
    let mut v = vec![Vector3::new(-0.5 * length, axis_y, 0.0)];
    for i in 1..rings {
        let u = i as f64 / rings as f64;
        let r = r_max * eggplant_profile(u) / peak;
        for j in 0..segs {
            let ph = 2.0 * PI * j as f64 / segs as f64;
            // Clip to the board: points below y = 0 are pressed flat onto it.
            let y = (axis_y + r * ph.sin()).max(0.0);
            v.push(Vector3::new(u * length - 0.5 * length, y, r * ph.cos()));
        }
    }
    let tip = v.len();
    v.push(Vector3::new(0.5 * length, axis_y, 0.0));
    let ring = |i: usize, j: usize| 1 + (i - 1) * segs + (j % segs);
    let mut t = Vec::new();
    for j in 0..segs {
        t.push([0, ring(1, j), ring(1, j + 1)]);
    }
    for i in 1..rings - 1 {
        for j in 0..segs {
            t.push([ring(i, j), ring(i + 1, j), ring(i, j + 1)]);
            t.push([ring(i, j + 1), ring(i + 1, j), ring(i + 1, j + 1)]);
        }
    }
    for j in 0..segs {
        t.push([tip, ring(rings - 1, j + 1), ring(rings - 1, j)]);
    }
    TriangleMesh::new(v, t).expect("the procedural eggplant is closed")
}

#[cfg(test)]
mod tests {
    use super::super::plane_section::SectionPlane;
    use super::*;

    #[test]
    fn half_potato_volume_and_middle_section() {
        let (l, w, h) = (0.09, 0.06, 0.035);
        let m = half_potato(
            l,
            w,
            h,
            Tessellation {
                rings: 64,
                segments: 128,
            },
        );
        // Half ellipsoid: (2/3)π·(w/2)·h·(l/2); the tessellation is inscribed,
        // so slightly smaller (< 0.5 % at this resolution).
        let exact = 2.0 / 3.0 * PI * 0.5 * w * h * 0.5 * l;
        assert!(
            m.volume() < exact && m.volume() > 0.995 * exact,
            "{} vs {exact}",
            m.volume()
        );
        let (lo, hi) = m.bounds();
        assert!(lo.y.abs() < 1e-15 && (hi.y - h).abs() < 1e-15);
        // The section through the middle is a half ellipse of area π·(w/2)·h/2.
        let plane = SectionPlane::normal_to_segment(Vector3::new(0.0, 0.01, 0.5 * l), Vector3::y());
        let p = plane.section(&m).unwrap();
        let half_ellipse = 0.5 * PI * 0.5 * w * h;
        assert!((p.area() - half_ellipse).abs() < 0.01 * half_ellipse);
        assert!(p.asymmetry() < 1e-9);
    }

    #[test]
    fn eggplant_lies_across_the_knife() {
        let (l, d, flat) = (0.2, 0.07, 0.005);
        let m = eggplant(l, d, flat, Tessellation::default());
        let (lo, hi) = m.bounds();
        assert!(lo.y.abs() < 1e-15);
        assert!((hi.x - lo.x - l).abs() < 1e-12);
        // The knife plane x = 0 cuts a near-circular slice: as wide as tall
        // (plus the flat), at most the diameter.
        let slice = crate::knife_plane::knife_plane_silhouette(&m).unwrap();
        let (slo, shi) = slice.bounds();
        let (wide, tall) = (shi.x - slo.x, shi.y - slo.y);
        assert!(
            wide <= d + 1e-12 && (wide - (tall + flat)).abs() < 0.02 * d,
            "{wide} {tall}"
        );
        // Bulb towards +x: the slice at x = +0.05 is larger than at −0.05.
        let width_at = |x: f64| {
            let plane = SectionPlane {
                origin: Vector3::new(x, 0.0, 0.0),
                u_axis: Vector3::z(),
                v_axis: Vector3::y(),
            };
            let (lo, hi) = plane.section(&m).unwrap().bounds();
            hi.x - lo.x
        };
        assert!(width_at(0.05) > width_at(-0.05));
    }
}
