//! The section polygon in section coordinates.

use serde::{Deserialize, Serialize};

use super::error::SectionError;

/// The shape of a cross section normal to the knife edge.
///
/// Section coordinates: x across the cut (normal to the blade), y up, the
/// board at y = 0, the cut line at x = 0. The model is a half model (x ≥ 0,
/// the cut line a plane of symmetry, DESIGN §3.2a), so the polygon must be
/// symmetric about x = 0: objects are placed symmetric about the knife plane.
///
/// Supported shapes are the region under a graph: a flat base on the board
/// from −X to X and an upper boundary y = top(x) > 0 for |x| ≤ X that is a
/// function of x (vertical sides of positive height at ±X, a dome or a
/// rectangle in between). A half potato with a flat base qualifies once its
/// rim is clipped at a small height.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct SectionGeometry {
    /// Upper boundary of the half section as (x, y) points, m, from x = 0 to
    /// x = X with strictly increasing x; y > 0. Linear between points.
    top: Vec<[f64; 2]>,
}

impl SectionGeometry {
    /// A rectangle `width` wide (across the cut, m) and `height` tall (m),
    /// centred on the cut line and standing on the board.
    pub fn rectangle(width: f64, height: f64) -> Result<Self, SectionError> {
        let (w, h) = (0.5 * width, height);
        Self::from_polygon(&[[-w, 0.0], [w, 0.0], [w, h], [-w, h]])
    }

    /// A section from a closed polygon (vertices in order, either
    /// orientation, last vertex not repeated), m.
    ///
    /// Refuses polygons that are not symmetric about x = 0 (to 1e-9 of their
    /// size), that do not stand on the board with a flat base, or whose upper
    /// boundary is not a function of x (see the type's documentation).
    pub fn from_polygon(vertices: &[[f64; 2]]) -> Result<Self, SectionError> {
        if vertices.len() < 3 {
            return Err(SectionError::UnsupportedShape(
                "a polygon needs at least 3 vertices",
            ));
        }
        if vertices.iter().flatten().any(|v| !v.is_finite()) {
            return Err(SectionError::UnsupportedShape(
                "polygon vertices must be finite",
            ));
        }
        let size = vertices
            .iter()
            .flatten()
            .fold(0.0f64, |m, v| m.max(v.abs()));
        let tol = 1e-9 * size.max(1e-12);
        if vertices.iter().any(|v| v[1] < -tol) {
            return Err(SectionError::UnsupportedShape(
                "the polygon must lie on or above the board (y >= 0)",
            ));
        }
        let x_max = vertices.iter().fold(f64::MIN, |m, v| m.max(v[0]));
        let x_min = vertices.iter().fold(f64::MAX, |m, v| m.min(v[0]));
        if (x_max + x_min).abs() > tol || x_max <= 0.0 {
            return Err(SectionError::UnsupportedShape(
                "the polygon must be symmetric about the cut line x = 0 (half model)",
            ));
        }
        // Upper chain: walk the polygon, drop the vertices on the base y = 0 and
        // keep those of the right half; the boundary must be a graph.
        let n = vertices.len();
        let on_base = |v: &[f64; 2]| v[1].abs() <= tol;
        // The base must be one edge from -X to X on y = 0.
        let base = (0..n).any(|i| {
            let (a, b) = (vertices[i], vertices[(i + 1) % n]);
            on_base(&a) && on_base(&b) && (a[0] - b[0]).abs() >= 2.0 * x_max - tol
        });
        if !base {
            return Err(SectionError::UnsupportedShape(
                "the polygon must have a flat base on the board from -X to X",
            ));
        }
        let mut top: Vec<[f64; 2]> = vertices
            .iter()
            .filter(|v| !on_base(v) && v[0] >= -tol)
            .map(|v| [v[0].max(0.0), v[1]])
            .collect();
        top.sort_by(|a, b| a[0].total_cmp(&b[0]));
        // Vertical sides at x = X: keep the top of each.
        top.dedup_by(|b, a| {
            if (a[0] - b[0]).abs() <= tol {
                a[1] = a[1].max(b[1]);
                true
            } else {
                false
            }
        });
        if top.is_empty() || top[0][0] > tol {
            // Add the point on the cut line by symmetry (mirror of the left chain).
            let left = vertices.iter().filter(|v| !on_base(v) && v[0] < 0.0).fold(
                None::<[f64; 2]>,
                |m, v| match m {
                    Some(m) if m[0] > v[0] => Some(m),
                    _ => Some(*v),
                },
            );
            match (left, top.first()) {
                (Some(l), Some(r)) => {
                    let t = (0.0 - l[0]) / (r[0] - l[0]);
                    top.insert(0, [0.0, l[1] + t * (r[1] - l[1])]);
                }
                _ => {
                    return Err(SectionError::UnsupportedShape(
                        "the polygon has no upper boundary over the cut line",
                    ));
                }
            }
        }
        // Check symmetry of the heights: every left vertex mirrors onto the chain.
        let geometry = Self { top };
        for v in vertices.iter().filter(|v| !on_base(v)) {
            let h = geometry.top_at(v[0].abs());
            if v[0].abs() < x_max - tol && (h - v[1]).abs() > 1e-6 * size.max(1e-12) {
                return Err(SectionError::UnsupportedShape(
                    "the polygon must be symmetric about x = 0 with an upper boundary that is a function of x",
                ));
            }
        }
        // The two vertical sides must reach the same height.
        let side = |sign: f64| {
            vertices
                .iter()
                .filter(|v| (v[0] - sign * x_max).abs() <= tol)
                .fold(0.0f64, |m, v| m.max(v[1]))
        };
        if (side(1.0) - side(-1.0)).abs() > 1e-6 * size.max(1e-12) {
            return Err(SectionError::UnsupportedShape(
                "the polygon must be symmetric about x = 0 (its sides differ in height)",
            ));
        }
        if geometry.top.iter().any(|p| p[1] <= tol) {
            return Err(SectionError::UnsupportedShape(
                "the upper boundary must stay above the board (clip the rim at a small height)",
            ));
        }
        Ok(geometry)
    }

    /// Half width X of the section, m.
    pub fn half_width(&self) -> f64 {
        self.top[self.top.len() - 1][0]
    }

    /// Height of the section on the cut line, m: where the knife first touches.
    pub fn height_at_cut(&self) -> f64 {
        self.top[0][1]
    }

    /// Height of the upper boundary at |x|, m (x clamped to [0, X]).
    pub fn top_at(&self, x: f64) -> f64 {
        let x = x.abs();
        let t = &self.top;
        if x <= t[0][0] {
            return t[0][1];
        }
        for w in t.windows(2) {
            if x <= w[1][0] {
                let s = (x - w[0][0]) / (w[1][0] - w[0][0]);
                return w[0][1] + s * (w[1][1] - w[0][1]);
            }
        }
        t[t.len() - 1][1]
    }

    /// Cross-sectional area of the full section, m².
    pub fn area(&self) -> f64 {
        2.0 * self
            .top
            .windows(2)
            .map(|w| 0.5 * (w[0][1] + w[1][1]) * (w[1][0] - w[0][0]))
            .sum::<f64>()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn rectangle_and_dome() {
        let r = SectionGeometry::rectangle(0.04, 0.03).unwrap();
        assert_eq!(r.half_width(), 0.02);
        assert_eq!(r.height_at_cut(), 0.03);
        assert!((r.area() - 0.0012).abs() < 1e-15);
        let dome = SectionGeometry::from_polygon(&[
            [-0.02, 0.0],
            [0.02, 0.0],
            [0.02, 0.005],
            [0.01, 0.02],
            [0.0, 0.025],
            [-0.01, 0.02],
            [-0.02, 0.005],
        ])
        .unwrap();
        assert!((dome.top_at(0.005) - 0.0225).abs() < 1e-12);
        assert!((dome.top_at(-0.015) - 0.0125).abs() < 1e-12);
    }

    #[test]
    fn asymmetric_or_floating_polygons_are_refused() {
        let e = SectionGeometry::from_polygon(&[
            [-0.01, 0.0],
            [0.02, 0.0],
            [0.02, 0.01],
            [-0.01, 0.01],
        ]);
        assert!(matches!(e, Err(SectionError::UnsupportedShape(_))));
        let e = SectionGeometry::from_polygon(&[
            [-0.01, 0.001],
            [0.01, 0.001],
            [0.01, 0.01],
            [-0.01, 0.01],
        ]);
        assert!(matches!(e, Err(SectionError::UnsupportedShape(_))));
        let e = SectionGeometry::from_polygon(&[
            [-0.01, 0.0],
            [0.01, 0.0],
            [0.01, 0.01],
            [0.0, 0.02],
            [-0.01, 0.012],
        ]);
        assert!(matches!(e, Err(SectionError::UnsupportedShape(_))));
    }
}
