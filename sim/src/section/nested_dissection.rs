//! Fill-reducing elimination order of a section's interior DOFs: nested
//! dissection of the structured mesh's node grid (DESIGN §3.2a).
//!
//! The mesh ([`SectionMesh`]) is a grid of node rows 0..=R and node columns
//! 0..C; a Q4 element couples nodes at most one row and one column apart, so
//! a whole node row (or column) of a rectangle of the grid separates the
//! rectangle's nodes above it from those below (left from right). The order
//! splits a rectangle across its longer side (in nodes, columns weighted by
//! `COLUMN_WEIGHT`), orders both halves recursively, then the separator;
//! rectangles of at most `LEAF_NODES` nodes are ordered row by row.
//!
//! The section is a tall strip (175 rows × 27 columns for the default half
//! potato) whose kept DOFs (the cut line, column 0 and the strip columns)
//! are ordered after the interior. Splitting by rows only leaves ≈ 60
//! leaves of three rows, each eliminated between two separators 27 nodes
//! long; splitting the strip into near-square blocks and those by columns
//! and rows in turn needs fewer floating-point operations
//! (`docs/benchmarks.md`, "Section construction", counts them).

use super::mesh::SectionMesh;

/// Rectangles of at most this many nodes are leaves (ordered row by row).
const LEAF_NODES: usize = 24;

/// Weight of a column against a row when choosing the side to split.
const COLUMN_WEIGHT: usize = 1;

/// The elimination order (new → old interior number) of the `ni` interior
/// DOFs whose numbers `index` gives (DOF `dofs_per_node`·node + component;
/// entries ≥ `kept_from` or equal to `usize::MAX` are not interior) on the
/// node rows 1..=R of `mesh`.
pub(crate) fn nested_dissection(
    mesh: &SectionMesh,
    index: &[usize],
    dofs_per_node: usize,
    kept_from: usize,
    ni: usize,
) -> Vec<usize> {
    let mut order = Vec::with_capacity(ni);
    let grid = Grid {
        mesh,
        index,
        dofs_per_node,
        kept_from,
    };
    grid.dissect(1, mesh.rows + 1, 0, mesh.columns(), &mut order);
    order
}

struct Grid<'a> {
    mesh: &'a SectionMesh,
    index: &'a [usize],
    dofs_per_node: usize,
    kept_from: usize,
}

impl Grid<'_> {
    /// Appends the interior DOFs of the nodes of rows r0..r1 and columns
    /// c0..c1, row by row.
    fn emit(&self, r0: usize, r1: usize, c0: usize, c1: usize, order: &mut Vec<usize>) {
        for r in r0..r1 {
            for c in c0..c1 {
                let node = self.mesh.node(c, r);
                for d in 0..self.dofs_per_node {
                    let i = self.index[self.dofs_per_node * node + d];
                    if i < self.kept_from {
                        order.push(i);
                    }
                }
            }
        }
    }

    /// Appends the interior DOFs of rows r0..r1 and columns c0..c1 in
    /// nested-dissection order.
    fn dissect(&self, r0: usize, r1: usize, c0: usize, c1: usize, order: &mut Vec<usize>) {
        let (h, w) = (r1 - r0, c1 - c0);
        if h * w <= LEAF_NODES || (h < 3 && w < 3) {
            self.emit(r0, r1, c0, c1, order);
            return;
        }
        if h >= 3 && (h >= COLUMN_WEIGHT * w || w < 3) {
            let mid = (r0 + r1) / 2;
            self.dissect(r0, mid, c0, c1, order);
            self.dissect(mid + 1, r1, c0, c1, order);
            self.emit(mid, mid + 1, c0, c1, order);
        } else {
            let mid = (c0 + c1) / 2;
            self.dissect(r0, r1, c0, mid, order);
            self.dissect(r0, r1, mid + 1, c1, order);
            self.emit(r0, r1, mid, mid + 1, order);
        }
    }
}
