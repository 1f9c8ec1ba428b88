//! What a section build can reuse from earlier builds (DESIGN §3.2a): the
//! stiffness's sparsity pattern and the symbolic analysis of its partial
//! Cholesky factorisation, which depend only on the mesh's topology, and the
//! large scratch memory of the numeric factorisation.
//!
//! The section mesh is structured ([`SectionMesh`]): its topology is fixed by
//! the rows, the node columns and the strip width, and successive sections of
//! a plant segment (planes 1 mm apart, `plant/successor.rs`) often share it
//! and differ only in the nodes' coordinates. A [`StiffnessPattern`] holds,
//! for one problem (in-plane or antiplane) on one topology, the lower
//! triangle's compressed-column pattern, the order in which the element
//! contributions are summed into each entry, and the symbolic factorisation;
//! a process-wide cache keeps the most recently used ones.
//!
//! # Bit-identical by construction
//! Reusing a pattern changes no floating-point operation: the entries are
//! summed in exactly the order of the assembly the pattern was computed for
//! (the triplets of the lower triangle, counted into columns in assembly
//! order, then each column sorted by row with the same unstable sort on the
//! same element type: the sort's permutation depends on the keys only;
//! checked against the triplet assembly in `condensed.rs`), and
//! the symbolic factorisation is the one computed from that pattern. A build
//! gives the same bits whether the pattern was cached or not, so results never
//! depend on which thread built what before (tests in `condensed.rs`).
//!
//! # Memory
//! A cached pattern of the default potato mesh (175 rows × 27 node columns)
//! takes about 2.5 MB for the in-plane problem and 0.8 MB for the antiplane
//! one; at most [`CAPACITY`] are kept (least recently used dropped), so at
//! most about 210 MB (how often a closed loop misses: `docs/benchmarks.md`,
//! "Section construction"). The number of builds varies by a few with the
//! worker's timing, their results do not. The scratch
//! memory ([`FactorMemory`]: the factor's values, 8 MB for that mesh, faer's
//! stack and the dense trailing factor and its inverse, 3 MB) is kept for
//! the next build, at most [`SPARE_MEMORY`] sets.

use std::sync::{Arc, Mutex, MutexGuard};

use faer::Par;
use faer::dyn_stack::{MemBuffer, StackReq};
use faer::perm::PermRef;
use faer::sparse::linalg::SupernodalThreshold;
use faer::sparse::linalg::cholesky::{
    CholeskySymbolicParams, SymbolicCholesky, SymmetricOrdering, factorize_symbolic_cholesky,
};
use faer::sparse::{SparseColMatRef, SymbolicSparseColMat};

use super::error::SectionError;
use super::mesh::SectionMesh;

/// Most patterns kept (in-plane and antiplane counted separately: 64 mesh
/// topologies; see the module's Memory section).
pub(crate) const CAPACITY: usize = 128;

/// Which stiffness of the section.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum Problem {
    /// Plane strain, two DOFs per node.
    InPlane,
    /// Antiplane shear, one DOF per node.
    Antiplane,
}

/// The mesh topology a pattern belongs to: with the structured mesh, the
/// element connectivity and the DOF numbering follow from these.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) struct Topology {
    problem: Problem,
    rows: usize,
    columns: usize,
    strip: usize,
}

impl Topology {
    /// The topology of `mesh` for `problem`.
    pub fn of(mesh: &SectionMesh, problem: Problem) -> Self {
        Self {
            problem,
            rows: mesh.rows,
            columns: mesh.columns(),
            strip: mesh.strip,
        }
    }
}

/// The assembled stiffness's structure and symbolic factorisation for one
/// topology (see the module documentation).
#[derive(Debug)]
pub(crate) struct StiffnessPattern {
    /// Interior DOFs (eliminated), numbered first.
    pub ni: usize,
    /// Kept DOFs, numbered last.
    pub nb: usize,
    /// The lower triangle's pattern in the factorisation's order, P K Pᵀ
    /// (compressed columns, rows unsorted: laid out as faer's
    /// `permute_self_adjoint_to_unsorted` lays them out).
    permuted: SymbolicSparseColMat<usize>,
    /// Indices of the assembled lower-triangle contributions (in assembly
    /// order) in the order they are summed, entry after entry (entries in
    /// the column order of K's lower triangle, rows sorted).
    order: Vec<u32>,
    /// Where each entry's contributions start in `order` (one more than the
    /// entries, the last being `order.len()`).
    entry_start: Vec<u32>,
    /// Where each entry goes in `permuted`.
    target: Vec<u32>,
    /// The symbolic partial Cholesky factorisation (supernodal, fill-reducing
    /// order of the interior, kept DOFs last).
    pub symbolic: SymbolicCholesky<usize>,
    /// The stack the numeric factorisation needs (sequential, default
    /// parameters).
    pub stack: StackReq,
}

impl StiffnessPattern {
    /// The pattern of the matrix with `ni` interior and `nb` kept DOFs whose
    /// lower-triangle contributions are `pairs` (row ≥ column, in assembly
    /// order, duplicates allowed), factorised in the order `fwd` (new → old
    /// index, the kept DOFs last in place).
    pub fn new(
        ni: usize,
        nb: usize,
        pairs: &[(usize, usize)],
        fwd: &[usize],
    ) -> Result<Self, SectionError> {
        let nt = ni + nb;
        if pairs.len() >= u32::MAX as usize {
            return Err(SectionError::Factorisation("the stiffness is too large"));
        }
        // Counting sort on the columns (stable: assembly order within each
        // column), then each column sorted by row with the element type and
        // sort of the former triplet path, (row, value) pairs sorted
        // unstably by row: the value slot carries the contribution's index.
        let mut start = vec![0usize; nt + 1];
        for &(_, c) in pairs {
            start[c + 1] += 1;
        }
        for j in 0..nt {
            start[j + 1] += start[j];
        }
        let total = start[nt];
        let mut next = start.clone();
        let mut entries = vec![(0usize, 0.0f64); total];
        for (t, &(r, c)) in pairs.iter().enumerate() {
            entries[next[c]] = (r, f64::from_bits(t as u64));
            next[c] += 1;
        }
        let mut col_ptr = Vec::with_capacity(nt + 1);
        let mut row_idx = Vec::with_capacity(total);
        let mut order = Vec::with_capacity(total);
        let mut entry_start = Vec::with_capacity(total + 1);
        col_ptr.push(0);
        for j in 0..nt {
            let column = &mut entries[start[j]..start[j + 1]];
            column.sort_unstable_by_key(|e| e.0);
            let first = row_idx.len();
            for &(i, t) in column.iter() {
                if !(row_idx.len() > first && row_idx[row_idx.len() - 1] == i) {
                    row_idx.push(i);
                    entry_start.push(order.len() as u32);
                }
                order.push(t.to_bits() as u32);
            }
            col_ptr.push(row_idx.len());
        }
        entry_start.push(order.len() as u32);
        let lower = SymbolicSparseColMat::new_checked(nt, nt, col_ptr, None, row_idx);
        let mut inv = vec![0; nt];
        for (new, &old) in fwd.iter().enumerate() {
            inv[old] = new;
        }
        let perm = PermRef::new_checked(fwd, &inv, nt);
        let symbolic = factorize_symbolic_cholesky(
            lower.as_ref(),
            faer::Side::Lower,
            SymmetricOrdering::Custom(perm),
            CholeskySymbolicParams {
                supernodal_flop_ratio_threshold: SupernodalThreshold::FORCE_SUPERNODAL,
                ..Default::default()
            },
        )
        .map_err(|_| SectionError::Factorisation("symbolic Cholesky failed"))?;
        let stack = symbolic.factorize_numeric_llt_scratch::<f64>(Par::Seq, Default::default());
        // P K Pᵀ's lower triangle, laid out as faer's numeric factorisation
        // lays it out from K (counts per new column, then entries in K's
        // column order): the factorisation then starts from it directly.
        let mut count = vec![0usize; nt + 1];
        let mut dest = Vec::with_capacity(lower.row_idx().len());
        for old_j in 0..nt {
            let new_j = inv[old_j];
            for old_i in lower.row_idx_of_col(old_j) {
                let new_i = inv[old_i];
                let (col, row) = if new_i >= new_j {
                    (new_j, new_i)
                } else {
                    (new_i, new_j)
                };
                count[col + 1] += 1;
                dest.push((col, row));
            }
        }
        for j in 0..nt {
            count[j + 1] += count[j];
        }
        let col_ptr = count.clone();
        let mut row_idx = vec![0usize; dest.len()];
        let mut target = Vec::with_capacity(dest.len());
        for &(col, row) in &dest {
            row_idx[count[col]] = row;
            target.push(count[col] as u32);
            count[col] += 1;
        }
        let permuted = SymbolicSparseColMat::new_unsorted_checked(nt, nt, col_ptr, None, row_idx);
        Ok(Self {
            ni,
            nb,
            permuted,
            order,
            entry_start,
            target,
            symbolic,
            stack,
        })
    }

    /// Number of lower-triangle contributions the assembly must deliver.
    pub fn contributions(&self) -> usize {
        self.order.len()
    }

    /// P K Pᵀ's lower triangle (see `permuted`) with the entries summed
    /// from `contributions` (in assembly order, as for [`Self::new`]) into
    /// `values`.
    pub fn sum<'a>(
        &'a self,
        contributions: &[f64],
        values: &'a mut Vec<f64>,
    ) -> SparseColMatRef<'a, usize, f64> {
        debug_assert_eq!(contributions.len(), self.order.len());
        let entries = self.target.len();
        values.clear();
        values.resize(entries, 0.0);
        for (e, &to) in self.target.iter().enumerate() {
            let (a, b) = (
                self.entry_start[e] as usize,
                self.entry_start[e + 1] as usize,
            );
            let mut v = contributions[self.order[a] as usize];
            for &t in &self.order[a + 1..b] {
                v += contributions[t as usize];
            }
            values[to as usize] = v;
        }
        SparseColMatRef::new(self.permuted.as_ref(), values)
    }
}

/// Scratch memory of one build, kept between builds.
#[derive(Default)]
pub(crate) struct FactorMemory {
    /// Lower-triangle contributions in assembly order.
    pub contributions: Vec<f64>,
    /// Their (row, column), recorded when the pattern is not cached.
    pub pairs: Vec<(usize, usize)>,
    /// The assembled lower triangle's values.
    pub lower: Vec<f64>,
    /// The factor's values.
    pub factor: Vec<f64>,
    /// faer's stack and its size (see [`grow_stack`]).
    pub stack: Option<(StackReq, MemBuffer)>,
    /// The dense factor of the Schur complement (column-major).
    pub dense: Vec<f64>,
    /// The inverse of a block of it (column-major).
    pub inverse: Vec<f64>,
}

impl std::fmt::Debug for FactorMemory {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("FactorMemory")
            .field("factor", &self.factor.len())
            .finish_non_exhaustive()
    }
}

/// A stack of at least `req` in `slot`, grown if needed.
pub(crate) fn grow_stack(
    slot: &mut Option<(StackReq, MemBuffer)>,
    req: StackReq,
) -> Result<&mut MemBuffer, SectionError> {
    let need = match slot {
        Some((have, _)) => {
            let both = have.or(req);
            (both != *have).then_some(both)
        }
        None => Some(req),
    };
    if let Some(req) = need {
        *slot = None;
        let buffer = MemBuffer::try_new(req)
            .map_err(|_| SectionError::Factorisation("out of memory for the factor"))?;
        *slot = Some((req, buffer));
    }
    match slot {
        Some((_, buffer)) => Ok(buffer),
        None => Err(SectionError::Factorisation("out of memory for the factor")),
    }
}

#[derive(Default)]
struct Cache {
    /// Most recently used last.
    patterns: Vec<(Topology, Arc<StiffnessPattern>)>,
    /// Scratch memory not in use by a build.
    memory: Vec<FactorMemory>,
}

static CACHE: Mutex<Cache> = Mutex::new(Cache {
    patterns: Vec::new(),
    memory: Vec::new(),
});

fn cache() -> MutexGuard<'static, Cache> {
    // The cache's state is consistent between statements: keep going after
    // a panic elsewhere.
    CACHE.lock().unwrap_or_else(|e| e.into_inner())
}

/// The cached pattern of `topology`, if any (marked as recently used).
pub(crate) fn lookup(topology: &Topology) -> Option<Arc<StiffnessPattern>> {
    let mut c = cache();
    let i = c.patterns.iter().position(|(t, _)| t == topology)?;
    let entry = c.patterns.remove(i);
    let pattern = Arc::clone(&entry.1);
    c.patterns.push(entry);
    Some(pattern)
}

/// Caches `pattern` for `topology`, dropping the least recently used beyond
/// [`CAPACITY`].
pub(crate) fn insert(topology: Topology, pattern: Arc<StiffnessPattern>) {
    let mut c = cache();
    c.patterns.retain(|(t, _)| *t != topology);
    c.patterns.push((topology, pattern));
    if c.patterns.len() > CAPACITY {
        let excess = c.patterns.len() - CAPACITY;
        c.patterns.drain(..excess);
    }
}

/// Drops the cached pattern of `topology` (tests: a cold build).
#[cfg(test)]
pub(crate) fn forget(topology: &Topology) {
    cache().patterns.retain(|(t, _)| t != topology);
}

/// Scratch memory for a build (left by an earlier one, or new).
pub(crate) fn take_memory() -> FactorMemory {
    cache().memory.pop().unwrap_or_default()
}

/// Most sets of scratch memory kept (the plant builds on its worker thread,
/// and on its own thread at construction).
const SPARE_MEMORY: usize = 2;

/// Returns scratch memory after a build (dropped if enough are kept).
pub(crate) fn give_back(memory: FactorMemory) {
    let mut c = cache();
    if c.memory.len() < SPARE_MEMORY {
        c.memory.push(memory);
    }
}
