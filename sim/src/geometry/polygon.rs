//! Simple polygons in a section plane.

use nalgebra::Vector2;

/// A simple closed polygon, counter-clockwise, in section coordinates (u, v):
/// u across the cut (world x), v up from the board, m. The last point is not
/// repeated.
#[derive(Debug, Clone, PartialEq)]
pub struct Polygon {
    /// Vertices, counter-clockwise.
    pub points: Vec<Vector2<f64>>,
}

impl Polygon {
    /// A polygon through `points`, re-ordered counter-clockwise if needed.
    pub fn new(mut points: Vec<Vector2<f64>>) -> Self {
        if signed_area(&points) < 0.0 {
            points.reverse();
        }
        Self { points }
    }

    /// The axis-aligned rectangle [−w/2, w/2] × [0, h].
    pub fn rectangle(width: f64, height: f64) -> Self {
        let hw = 0.5 * width;
        Self::new(vec![
            Vector2::new(-hw, 0.0),
            Vector2::new(hw, 0.0),
            Vector2::new(hw, height),
            Vector2::new(-hw, height),
        ])
    }

    /// Total length of the line v = `v` inside the polygon, m: the sum of
    /// its inside intervals between even–odd crossings of the edges (each
    /// edge half-open in v, so a vertex on the line counts once).
    pub fn chord_length(&self, v: f64) -> f64 {
        let n = self.points.len();
        let mut crossings: Vec<f64> = (0..n)
            .filter_map(|i| {
                let (a, b) = (self.points[i], self.points[(i + 1) % n]);
                ((a.y <= v) != (b.y <= v)).then(|| a.x + (v - a.y) / (b.y - a.y) * (b.x - a.x))
            })
            .collect();
        crossings.sort_by(f64::total_cmp);
        crossings.chunks_exact(2).map(|p| p[1] - p[0]).sum()
    }

    /// Enclosed area, m².
    pub fn area(&self) -> f64 {
        signed_area(&self.points).abs()
    }

    /// (min, max) corners of the bounding box.
    pub fn bounds(&self) -> (Vector2<f64>, Vector2<f64>) {
        let mut lo = Vector2::repeat(f64::INFINITY);
        let mut hi = Vector2::repeat(f64::NEG_INFINITY);
        for p in &self.points {
            lo = lo.inf(p);
            hi = hi.sup(p);
        }
        (lo, hi)
    }

    /// Height of the top boundary above the board at u (the largest v where
    /// the vertical line at u crosses the boundary), or None if it misses.
    pub fn top_at(&self, u: f64) -> Option<f64> {
        let n = self.points.len();
        let mut top: Option<f64> = None;
        for i in 0..n {
            let (a, b) = (self.points[i], self.points[(i + 1) % n]);
            let (lo, hi) = if a.x <= b.x { (a, b) } else { (b, a) };
            if u < lo.x || u > hi.x {
                continue;
            }
            let v = if hi.x - lo.x > 0.0 {
                lo.y + (u - lo.x) / (hi.x - lo.x) * (hi.y - lo.y)
            } else {
                lo.y.max(hi.y)
            };
            top = Some(top.map_or(v, |t: f64| t.max(v)));
        }
        top
    }

    /// Largest distance between the polygon and its mirror image in u = 0,
    /// measured as the largest |top_at(u) − top_at(−u)| over the vertices, m.
    pub fn asymmetry(&self) -> f64 {
        self.points
            .iter()
            .map(|p| match (self.top_at(p.x), self.top_at(-p.x)) {
                (Some(a), Some(b)) => (a - b).abs(),
                _ => f64::INFINITY,
            })
            .fold(0.0, f64::max)
    }
}

/// Shoelace signed area (positive for counter-clockwise).
pub fn signed_area(points: &[Vector2<f64>]) -> f64 {
    let n = points.len();
    (0..n)
        .map(|i| {
            let (a, b) = (points[i], points[(i + 1) % n]);
            a.x * b.y - b.x * a.y
        })
        .sum::<f64>()
        * 0.5
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn rectangle_area_bounds_top() {
        let r = Polygon::rectangle(0.03, 0.02);
        assert!((r.area() - 6e-4).abs() < 1e-18);
        assert_eq!(r.top_at(0.0), Some(0.02));
        assert_eq!(r.top_at(0.02), None);
        assert_eq!(r.asymmetry(), 0.0);
        let (lo, hi) = r.bounds();
        assert_eq!((lo.x, hi.y), (-0.015, 0.02));
    }

    #[test]
    fn clockwise_input_is_reoriented() {
        let p = Polygon::new(vec![
            Vector2::new(0.0, 0.0),
            Vector2::new(0.0, 1.0),
            Vector2::new(1.0, 0.0),
        ]);
        assert!(signed_area(&p.points) > 0.0);
    }

    #[test]
    fn chord_lengths_of_a_rectangle_and_a_notched_shape() {
        let r = Polygon::rectangle(0.03, 0.02);
        assert!((r.chord_length(0.01) - 0.03).abs() < 1e-15);
        assert_eq!(r.chord_length(0.03), 0.0);
        // A U shape: two prongs 1 wide with a gap of 1 above v = 1.
        let u = Polygon::new(
            [
                (0.0, 0.0),
                (3.0, 0.0),
                (3.0, 2.0),
                (2.0, 2.0),
                (2.0, 1.0),
                (1.0, 1.0),
                (1.0, 2.0),
                (0.0, 2.0),
            ]
            .iter()
            .map(|&(x, y)| Vector2::new(x, y))
            .collect(),
        );
        assert!((u.chord_length(0.5) - 3.0).abs() < 1e-15);
        assert!((u.chord_length(1.5) - 2.0).abs() < 1e-15);
    }
}
