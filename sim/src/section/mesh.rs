//! Structured, graded quadrilateral mesh of the half section x ≥ 0.

use super::error::SectionError;
use super::geometry::SectionGeometry;
use super::settings::SectionSettings;

/// Largest number of nodes a section mesh may have.
pub(crate) const MAX_NODES: usize = 400_000;

/// A mapped mesh of bilinear quadrilaterals (Q4) on the half section.
///
/// Columns of nodes at x_0 = 0 < x_1 < … < x_C = X: `strip` uniform elements
/// across the half edge flat b/2 (so the flat is a set of whole element edges),
/// then widths growing geometrically up to a largest width. Rows: node (c, r)
/// sits at y = top(x_c)·r/R, so on the cut line the rows are uniform with the
/// spacing closest to the setting. Node (c, r) has index r·(C+1) + c; row 0
/// lies on the board.
#[derive(Debug, Clone)]
pub(crate) struct SectionMesh {
    /// x of each node column, m.
    pub xs: Vec<f64>,
    /// Number of element rows R.
    pub rows: usize,
    /// Number of node columns within the half edge flat, minus one (the strip
    /// nodes are columns 0..=strip).
    pub strip: usize,
    /// Node coordinates, m.
    pub nodes: Vec<[f64; 2]>,
    /// Elements as four node indices, counter-clockwise.
    pub elements: Vec<[usize; 4]>,
    /// Row spacing on the cut line, m.
    pub h: f64,
}

impl SectionMesh {
    /// Meshes `geometry` for an edge flat of width `edge_width` (m).
    pub fn new(
        geometry: &SectionGeometry,
        edge_width: f64,
        settings: &SectionSettings,
    ) -> Result<Self, SectionError> {
        let half_width = geometry.half_width();
        let half_flat = 0.5 * edge_width;
        if half_flat >= 0.5 * half_width {
            return Err(SectionError::UnsupportedShape(
                "the section must be more than twice as wide as the knife's edge flat",
            ));
        }
        let m = settings.strip_elements;
        let mut xs: Vec<f64> = (0..=m).map(|i| half_flat * i as f64 / m as f64).collect();
        let mut w = half_flat / m as f64;
        loop {
            w = (w * settings.grading_ratio).min(settings.max_element_width);
            let last = xs[xs.len() - 1];
            if last + w >= half_width - 0.3 * w {
                break;
            }
            xs.push(last + w);
            if xs.len() > MAX_NODES {
                break;
            }
        }
        xs.push(half_width);
        let height = geometry.height_at_cut();
        let rows = (height / settings.row_spacing).round().max(4.0) as usize;
        let cols = xs.len();
        if cols * (rows + 1) > MAX_NODES {
            return Err(SectionError::MeshTooLarge {
                rows,
                columns: cols - 1,
                limit: MAX_NODES,
            });
        }
        let mut nodes = Vec::with_capacity(cols * (rows + 1));
        for r in 0..=rows {
            for &x in &xs {
                nodes.push([x, geometry.top_at(x) * r as f64 / rows as f64]);
            }
        }
        let mut elements = Vec::with_capacity((cols - 1) * rows);
        for r in 0..rows {
            for c in 0..cols - 1 {
                let a = r * cols + c;
                elements.push([a, a + 1, a + 1 + cols, a + cols]);
            }
        }
        Ok(Self {
            xs,
            rows,
            strip: m,
            nodes,
            elements,
            h: height / rows as f64,
        })
    }

    /// Number of node columns C+1.
    pub fn columns(&self) -> usize {
        self.xs.len()
    }

    /// Index of node (column c, row r).
    pub fn node(&self, c: usize, r: usize) -> usize {
        r * self.columns() + c
    }

    /// Number of nodes.
    pub fn node_count(&self) -> usize {
        self.nodes.len()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// `resource_budget::section_nodes` bounds the mesh built here, and not
    /// by much (within 20 % and a few columns): on the default settings, a
    /// uniform width (ratio 1) and a steep grading on fine rows.
    #[test]
    fn the_resource_estimate_bounds_the_built_mesh() {
        let g = SectionGeometry::rectangle(0.03, 0.025).unwrap();
        for (ratio, rows) in [(1.3, 2e-4), (1.0, 2e-4), (2.0, 5e-5)] {
            let s = SectionSettings {
                grading_ratio: ratio,
                row_spacing: rows,
                ..Default::default()
            };
            let built = SectionMesh::new(&g, 1e-4, &s).unwrap().node_count() as f64;
            let estimate = crate::resource_budget::section_nodes(0.015, 0.025, 1e-4, &s);
            assert!(
                estimate >= built && estimate <= 1.2 * built + 4.0 * (0.025 / rows + 1.0),
                "ratio {ratio}: estimate {estimate}, built {built}"
            );
        }
    }

    #[test]
    fn graded_columns_resolve_the_flat_and_cover_the_section() {
        let g = SectionGeometry::rectangle(0.03, 0.02).unwrap();
        let s = SectionSettings::default();
        let m = SectionMesh::new(&g, 1e-4, &s).unwrap();
        assert_eq!(m.xs[s.strip_elements], 5e-5);
        assert_eq!(*m.xs.last().unwrap(), 0.015);
        assert!(m.xs.windows(2).all(|w| w[1] > w[0]));
        assert!(
            m.xs.windows(2)
                .all(|w| w[1] - w[0] <= s.max_element_width * 1.31)
        );
        assert_eq!(m.rows, 100);
        assert!((m.h - 2e-4).abs() < 1e-15);
        // Element areas add up to the half section.
        let area: f64 = m
            .elements
            .iter()
            .map(|e| {
                let p: Vec<_> = e.iter().map(|&i| m.nodes[i]).collect();
                0.5 * ((p[2][0] - p[0][0]) * (p[3][1] - p[1][1])
                    - (p[3][0] - p[1][0]) * (p[2][1] - p[0][1]))
            })
            .sum();
        assert!((area - 0.5 * g.area()).abs() < 1e-12);
    }
}
