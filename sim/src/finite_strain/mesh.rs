//! Graded structured mesh of the half slab X ≥ 0 (the wire's plane x = 0 is a
//! plane of symmetry; see `slab`).
//!
//! Node columns run from the symmetry plane X = 0 to the side X = L/2, node
//! rows from the clamped base Y = 0 to the free top Y = B. Near the wire
//! (X and B − Y within the fine zone) the spacing is uniform, R divided by the
//! elements per radius for the rows and by `column_refinement` times as many
//! for the columns; beyond, it grows geometrically up to a largest size.
//!
//! **Tall, narrow elements near the wire.** Under deep pressing the surface
//! under the wire stretches about threefold along itself and thins about
//! threefold, so reference elements three times taller than wide come out
//! about square where the surface stress is read. The stress under the wire,
//! and with it the nucleation depth under pressing, depends on the column
//! spacing and hardly on the row spacing (docs/seed001.md, "Mesh").

/// A mesh of bilinear quadrilaterals (Q4).
#[derive(Debug, Clone)]
pub(crate) struct SlabMesh {
    /// Node coordinates (X, Y) in the reference configuration, m.
    pub nodes: Vec<[f64; 2]>,
    /// Elements as four node indices, counter-clockwise.
    pub elements: Vec<[usize; 4]>,
    /// Nodes of the top surface (Y = B), by increasing X.
    pub top: Vec<usize>,
    /// Y of each node row, m (row 0 is the base).
    pub ys: Vec<f64>,
}

/// Coordinates 0 = s₀ < s₁ < … < s_n = `length`: spacing `fine` up to
/// `fine_extent`, then each spacing `ratio` times the last, at most `largest`.
pub(crate) fn graded_coordinates(
    length: f64,
    fine: f64,
    fine_extent: f64,
    ratio: f64,
    largest: f64,
) -> Vec<f64> {
    let mut s = vec![0.0];
    let mut w = fine;
    loop {
        let last = s[s.len() - 1];
        if last >= fine_extent - 1e-9 * fine {
            w = (w * ratio).min(largest).max(fine);
        }
        if last + w >= length - 0.3 * w {
            break;
        }
        s.push(last + w);
    }
    s.push(length);
    s
}

impl SlabMesh {
    /// Structured mesh on the node columns `xs` and rows `ys` (both increasing).
    pub fn structured(xs: Vec<f64>, ys: Vec<f64>) -> Self {
        let cols = xs.len();
        let mut nodes = Vec::with_capacity(cols * ys.len());
        for &y in &ys {
            for &x in &xs {
                nodes.push([x, y]);
            }
        }
        let mut elements = Vec::with_capacity((cols - 1) * (ys.len() - 1));
        for r in 0..ys.len() - 1 {
            for c in 0..cols - 1 {
                let a = r * cols + c;
                elements.push([a, a + 1, a + 1 + cols, a + cols]);
            }
        }
        let top = ((ys.len() - 1) * cols..ys.len() * cols).collect();
        Self {
            nodes,
            elements,
            top,
            ys,
        }
    }

    /// The half slab of width `half_width` and depth `depth` (m), graded
    /// from row spacing `fine` (m) and column spacing `fine /
    /// column_refinement` within `fine_extent` (m) of the wire's line
    /// (X = 0, Y = depth) by `ratio` up to `largest` (m).
    pub fn half_slab(
        half_width: f64,
        depth: f64,
        fine: f64,
        fine_extent: f64,
        ratio: f64,
        largest: f64,
        column_refinement: usize,
    ) -> Self {
        let column = fine / column_refinement as f64;
        let xs = graded_coordinates(half_width, column, fine_extent, ratio, largest);
        let down = graded_coordinates(depth, fine, fine_extent, ratio, largest);
        let ys: Vec<f64> = down.iter().rev().map(|s| depth - s).collect();
        Self::structured(xs, ys)
    }

    /// Corners of element `e`, m.
    pub fn corners(&self, e: usize) -> [[f64; 2]; 4] {
        self.elements[e].map(|n| self.nodes[n])
    }

    /// Undeformed length of top surface that node `top[k]` stands for (half
    /// the neighbouring spacings; the first node on the symmetry plane gets
    /// half a spacing, which is its share of the half model), m.
    pub fn top_tributary(&self, k: usize) -> f64 {
        let x = |i: usize| self.nodes[self.top[i]][0];
        let left = if k > 0 { x(k) - x(k - 1) } else { 0.0 };
        let right = if k + 1 < self.top.len() {
            x(k + 1) - x(k)
        } else {
            0.0
        };
        0.5 * (left + right)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn graded_mesh_is_fine_near_the_wire_and_covers_the_half_slab() {
        let r = 150e-6;
        let m = SlabMesh::half_slab(20e-3, 40e-3, r / 6.0, 4.0 * r, 1.25, 2e-3, 3);
        let xs: Vec<f64> = m.top.iter().map(|&n| m.nodes[n][0]).collect();
        assert_eq!(xs[0], 0.0);
        assert_eq!(*xs.last().unwrap(), 20e-3);
        assert_eq!(*m.ys.last().unwrap(), 40e-3);
        assert_eq!(m.ys[0], 0.0);
        // Uniform columns R/18 and rows R/6 within the fine zone.
        for w in xs.windows(2).take(72) {
            assert!((w[1] - w[0] - r / 18.0).abs() < 1e-15);
        }
        let rows: Vec<f64> = m.ys.iter().rev().map(|y| 40e-3 - y).collect();
        for w in rows.windows(2).take(24) {
            assert!((w[1] - w[0] - r / 6.0).abs() < 1e-15);
        }
        assert!(xs.windows(2).all(|w| w[1] - w[0] <= 2e-3 * 1.3 + 1e-12));
        let area: f64 = (0..m.elements.len())
            .map(|e| {
                let p = m.corners(e);
                0.5 * ((p[2][0] - p[0][0]) * (p[3][1] - p[1][1])
                    - (p[3][0] - p[1][0]) * (p[2][1] - p[0][1]))
            })
            .sum();
        assert!((area - 20e-3 * 40e-3).abs() < 1e-12 * area);
        let trib: f64 = (0..m.top.len()).map(|k| m.top_tributary(k)).sum();
        assert!((trib - 20e-3).abs() < 1e-15);
    }
}
