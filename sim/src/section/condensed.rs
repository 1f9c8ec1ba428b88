//! Static condensation of the section's stiffness onto the cut line
//! (DESIGN §3.2a): every boundary condition that changes during a cut lives on
//! the line x = 0 and on the strip of nodes under the edge flat, so the
//! stiffness is factorised once (sparse Cholesky, faer) and reduced to a few
//! dense matrices; each crack/contact configuration is then a small dense solve.
//!
//! # In-plane (plane strain)
//! Degrees of freedom kept: X = u_x of the cut-line nodes (rows 1..=R), Y = u_y
//! of the nodes of the strip columns 0..=m (rows 1..=R). All others are
//! eliminated. With the bottom row fixed and the X DOFs prescribed (g), the
//! response to forces f_Y on the Y DOFs is
//!
//! ```text
//! u_Y = C f_Y − E g,      p = A g + Eᵀ f_Y,
//! ```
//!
//! with C = S_YY⁻¹, E = C S_YX, A = S_XX − S_XY C S_YX (S the Schur complement
//! of the stiffness onto X ∪ Y) and p the reactions on the X DOFs. The matrices
//! come from one partial sparse Cholesky factorisation of the stiffness (bottom
//! fixed) with the kept DOFs ordered last, Y before X: the factor's trailing
//! dense block L_bb = [[L_YY, 0], [L_XY, L_XX]] is the Cholesky factor of S,
//! so C = L_YY⁻ᵀ L_YY⁻¹, Eᵀ = L_XY L_YY⁻¹ and A = L_XX L_XXᵀ (dense kernels,
//! no sparse triangular solves). The interior is ordered by nested dissection
//! of the mesh's node grid ([`nested_dissection`]).
//!
//! Of C the solves read only the entries between DOFs of rows at most one
//! apart (the strip constraint taps rows j and j + 1 of every strip column)
//! and the row of the cut line's top DOF (the surface deflection), so only
//! those are formed: dot products of columns of L_YY⁻¹ instead of the whole
//! product L_YY⁻ᵀ L_YY⁻¹ (a third of the dense work of a build).
//!
//! # Antiplane (seed 000 §III.C, ∇²u_t = 0)
//! Kept: Z = u_t of the strip columns; only the bottom is fixed, so the
//! flexibility C_z = S_ZZ⁻¹ is the antiplane stiffness's inverse on Z, from
//! the same partial factorisation with Z last; only its band (rows at most
//! one apart) is formed, as for C.
//!
//! # Memory allocation
//! Construction allocates the matrices (|Y|·R + R² doubles and the bands,
//! under 1 MB for the default mesh; the dense scratch of the factorisation
//! is kept between builds by the [`factor_cache`]). [`CondensedLine::solve`] allocates nothing, nor
//! does [`CondensedLine::solve_released`] (crack faces released from the
//! blade: a dense Cholesky of the released rows' block of A in a
//! [`ReleasedWorkspace`]).

#![allow(non_snake_case, clippy::needless_range_loop)]

use std::sync::Arc;

use faer::dyn_stack::MemStack;
use faer::linalg::matmul::triangular::{self, BlockStructure};
use faer::linalg::triangular_inverse;
use faer::sparse::linalg::cholesky::SymbolicCholeskyRaw;
use faer::sparse::linalg::cholesky::supernodal::{
    SupernodalLltRef, factorize_supernodal_numeric_llt,
};
#[cfg(test)]
use faer::sparse::linalg::solvers::{Llt, SymbolicLlt};
#[cfg(test)]
use faer::sparse::{SparseColMat, SymbolicSparseColMat, Triplet};
use faer::{Accum, Mat, MatMut, MatRef, Par};

use super::error::SectionError;
use super::factor_cache::{self, FactorMemory, Problem, StiffnessPattern, Topology};
use super::mesh::SectionMesh;
use super::nested_dissection::nested_dissection;
use super::{antiplane, plane_strain};

/// Largest number of strip columns (strip_elements + 1).
pub(crate) const MAX_STRIP: usize = 9;

/// The condensed line of a section. Row r of the line (1..=R) is index r − 1;
/// Y/Z index of strip column c, row r is c·R + r − 1.
#[derive(Debug, Clone)]
pub(crate) struct CondensedLine {
    /// Rows R of the line (excluding the fixed bottom node).
    pub n: usize,
    /// Strip columns m + 1.
    pub k: usize,
    /// The band of C = S_YY⁻¹ that the solves read: the entries between
    /// DOFs of rows at most one apart (any strip columns), see
    /// [`inverse_band`].
    c_band: Vec<f64>,
    /// Row of C of the cut line's top DOF (strip column 0, row R), |Y|.
    c_top: Vec<f64>,
    /// Eᵀ (R×|Y|): column q is row q of E.
    Et: Mat<f64>,
    /// A (R×R), symmetric.
    A: Mat<f64>,
    /// The band of the antiplane flexibility C_z = S_ZZ⁻¹ (as `c_band`).
    cz_band: Vec<f64>,
}

/// The edge-flat constraint: the material at the crack tip's reference height,
/// interpolated between rows j and j+1 with weight φ, moves with the edge.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct StripConstraint {
    /// Lower row j (1..=R).
    pub row: usize,
    /// Interpolation weight of row j+1, in [0, 1).
    pub phi: f64,
    /// Prescribed value (u_y of the strip, m; or u_t for antiplane).
    pub value: f64,
    /// Which strip columns touch the edge (unilateral contact per column;
    /// the others carry no force).
    pub active: [bool; MAX_STRIP],
}

/// Result of an in-plane solve.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub(crate) struct InPlane {
    /// Strain energy of the half model, J/m.
    pub energy: f64,
    /// Sum of the strip forces on the material along +y, N/m (half model).
    pub strip_force: f64,
}

/// Sparse Cholesky factorisation of the SPD matrix given by `triplets` (both
/// triangles): the reference solver of the section's checks.
#[cfg(test)]
pub(crate) fn sparse_llt(
    n: usize,
    triplets: &[Triplet<usize, usize, f64>],
) -> Result<Llt<usize, f64>, SectionError> {
    let K = SparseColMat::<usize, f64>::try_new_from_triplets(n, n, triplets)
        .map_err(|_| SectionError::Factorisation("sparse assembly failed"))?;
    let symbolic = SymbolicLlt::try_new(K.symbolic(), faer::Side::Lower)
        .map_err(|_| SectionError::Factorisation("symbolic Cholesky failed"))?;
    Llt::try_new_with_symbolic(symbolic, K.as_ref(), faer::Side::Lower)
        .map_err(|_| SectionError::Factorisation("stiffness is not positive definite"))
}

impl CondensedLine {
    /// Factorises the stiffness of `mesh` (E in Pa, ν) and condenses it.
    ///
    /// One partial sparse Cholesky factorisation per problem with the kept
    /// DOFs ordered last (see [`schur_factor`]); everything after it is
    /// dense: with L_bb = [[L_YY, 0], [L_XY, L_XX]] the factor of the Schur
    /// complement S onto Y ∪ X (Y first),
    ///
    /// ```text
    /// S_YY = L_YY L_YYᵀ  ⇒  C = L_YY⁻ᵀ L_YY⁻¹ (its band, see
    ///                       [`inverse_band`]),
    /// S_XY = L_XY L_YYᵀ  ⇒  Eᵀ = S_XY C = L_XY L_YY⁻¹,
    /// A = S_XX − S_XY C S_YX = L_XX L_XXᵀ.
    /// ```
    pub fn new(mesh: &SectionMesh, e_mod: f64, nu: f64) -> Result<Self, SectionError> {
        let n = mesh.rows;
        let k = mesh.strip + 1;
        let nn = mesh.node_count();
        let ny = k * n;
        let bottom = mesh.columns();
        // ---- in-plane: number the DOFs interior first, then Y, then X.
        let mut index = vec![FIXED; 2 * nn];
        for c in 0..k {
            for r in 1..=n {
                index[2 * mesh.node(c, r) + 1] = KEPT + c * n + r - 1;
            }
        }
        for r in 1..=n {
            index[2 * mesh.node(0, r)] = KEPT + ny + r - 1;
        }
        let ni = number_interior(&mut index, 2 * bottom);
        let mut memory = factor_cache::take_memory();
        schur_factor(
            Topology::of(mesh, Problem::InPlane),
            ni,
            ny + n,
            || nested_dissection(mesh, &index, 2, KEPT, ni),
            &mut memory,
            |add| {
                // (The upper triangle's calls are skipped here already.)
                plane_strain::assemble_mapped(
                    mesh,
                    e_mod,
                    nu,
                    |i| position(index[i], ni),
                    |a, b, v| {
                        if a >= b {
                            add(a, b, v);
                        }
                    },
                );
            },
        )?;
        let FactorMemory { dense, inverse, .. } = &mut memory;
        let l = MatRef::from_column_major_slice(&dense[..(ny + n) * (ny + n)], ny + n, ny + n);
        let l_yy = l.submatrix(0, 0, ny, ny);
        let l_xy = l.submatrix(ny, 0, n, ny);
        let l_xx = l.submatrix(ny, ny, n, n);
        let linv = lower_inverse(l_yy, inverse);
        let (c_band, c_top) = (inverse_band(linv, n, k), inverse_row(linv, n - 1));
        // Eᵀ = L_XY L_YY⁻¹.
        let mut Et = Mat::<f64>::zeros(n, ny);
        triangular::matmul(
            Et.as_mut(),
            BlockStructure::Rectangular,
            Accum::Replace,
            l_xy,
            BlockStructure::Rectangular,
            linv,
            BlockStructure::TriangularLower,
            1.0,
            Par::Seq,
        );
        // A = L_XX L_XXᵀ, lower half, then mirrored.
        let mut A = Mat::<f64>::zeros(n, n);
        triangular::matmul(
            A.as_mut(),
            BlockStructure::TriangularLower,
            Accum::Replace,
            l_xx,
            BlockStructure::TriangularLower,
            l_xx.transpose(),
            BlockStructure::TriangularUpper,
            1.0,
            Par::Seq,
        );
        symmetrise_from_lower(&mut A);
        // ---- antiplane: interior nodes first, then Z.
        let mut zindex = vec![FIXED; nn];
        for c in 0..k {
            for r in 1..=n {
                zindex[mesh.node(c, r)] = KEPT + c * n + r - 1;
            }
        }
        let nzi = number_interior(&mut zindex, bottom);
        schur_factor(
            Topology::of(mesh, Problem::Antiplane),
            nzi,
            ny,
            || nested_dissection(mesh, &zindex, 1, KEPT, nzi),
            &mut memory,
            |add| {
                antiplane::assemble_mapped(
                    mesh,
                    e_mod / (2.0 * (1.0 + nu)),
                    |i| position(zindex[i], nzi),
                    |a, b, v| {
                        if a >= b {
                            add(a, b, v);
                        }
                    },
                );
            },
        )?;
        let FactorMemory { dense, inverse, .. } = &mut memory;
        let lz = MatRef::from_column_major_slice(&dense[..ny * ny], ny, ny);
        let cz_band = inverse_band(lower_inverse(lz, inverse), n, k);
        factor_cache::give_back(memory);
        Ok(Self {
            n,
            k,
            c_band,
            c_top,
            Et,
            A,
            cz_band,
        })
    }

    /// Entry (strip column c1, row index a; strip column c2, row index b)
    /// of the flexibility whose band is `band` (C or C_z; row indices
    /// 0..R at most one apart, see [`inverse_band`]).
    #[inline(always)]
    fn band_entry(&self, band: &[f64], c1: usize, a: usize, c2: usize, b: usize) -> f64 {
        debug_assert!(
            a.abs_diff(b) <= 1,
            "only the band of the flexibility is kept"
        );
        band[((a * self.k + c1) * self.k + c2) * 3 + b + 1 - a]
    }

    /// Y/Z index of strip column c, row r (1..=R).
    #[inline]
    fn yi(&self, c: usize, r: usize) -> usize {
        c * self.n + r - 1
    }

    /// The (index, weight) pairs of the strip constraint of column c.
    #[inline]
    fn taps(&self, c: usize, s: &StripConstraint) -> [(usize, f64); 2] {
        self.tap_rows(s).map(|(r, w)| (c * self.n + r, w))
    }

    /// The (row index 0..R, weight) pairs of the strip constraint, the same
    /// in every strip column ([`Self::taps`] without the column).
    #[inline]
    fn tap_rows(&self, s: &StripConstraint) -> [(usize, f64); 2] {
        let lo = (s.row - 1, 1.0 - s.phi);
        if s.phi > 0.0 {
            [lo, (s.row, s.phi)]
        } else {
            [lo, (lo.0, 0.0)]
        }
    }

    /// M = P F Pᵀ for flexibility F (the band of C or C_z).
    fn strip_matrix(&self, F: &[f64], s: &StripConstraint) -> [[f64; MAX_STRIP]; MAX_STRIP] {
        let mut M = [[0.0; MAX_STRIP]; MAX_STRIP];
        let t = self.tap_rows(s);
        for (a, row) in M.iter_mut().enumerate().take(self.k) {
            for (b, m) in row.iter_mut().enumerate().take(self.k) {
                for &(ra, wa) in &t {
                    for &(rb, wb) in &t {
                        *m += wa * wb * self.band_entry(F, a, ra, b, rb);
                    }
                }
            }
        }
        M
    }

    /// In-plane solve with every X DOF prescribed to `g` (gaps, m) and, if
    /// `strip` is given, the strip constraint. Writes the X reactions of the
    /// rows from `first_nonzero` on into `p` (N/m, +x on the material; the
    /// rows below, which carry no gap, are not computed: the few below it
    /// down to a multiple of 4 are set to 0, the others are left as they
    /// were) and the
    /// strip forces into `lambda` (N/m, +y on the material). `g` must be 0
    /// below `first_nonzero`. Allocation-free.
    #[inline(always)]
    pub fn solve(
        &self,
        g: &[f64],
        first_nonzero: usize,
        strip: Option<&StripConstraint>,
        p: &mut [f64],
        lambda: &mut [f64; MAX_STRIP],
    ) -> InPlane {
        let n = self.n;
        *lambda = [0.0; MAX_STRIP];
        let mut energy_strip = 0.0;
        if let Some(s) = strip {
            let mut M = self.strip_matrix(&self.c_band, s);
            let mut rhs = [0.0; MAX_STRIP];
            for (a, r) in rhs.iter_mut().enumerate().take(self.k) {
                *r = s.value;
                for (q, w) in self.taps(a, s) {
                    if w != 0.0 {
                        *r += w * dot(
                            &self.Et.col_as_slice(q)[first_nonzero..],
                            &g[first_nonzero..],
                        );
                    }
                }
            }
            mask_inactive(&mut M, &mut rhs, s, self.k);
            small_solve(&mut M, &mut rhs, self.k);
            lambda[..self.k].copy_from_slice(&rhs[..self.k]);
            energy_strip = s.value * rhs[..self.k].iter().sum::<f64>();
        }
        // Only the rows at and above `first_nonzero` are needed (the rows
        // below carry no gap): A_FC g_C restricted to them, the symmetric
        // block of A that the gaps touch. Element by element the sums are
        // the same as over the whole columns.
        let f0 = first_nonzero.min(n);
        // g is 0 below `first_nonzero`: the energy's dot from the 4-aligned
        // row at or below it has the same partial sums as the full one.
        let f4 = f0 & !3;
        p[f4..f0].fill(0.0);
        column_product(&self.A, g, f0, n, &mut p[f0..n]);
        if let Some(s) = strip {
            for a in 0..self.k {
                for (q, w) in self.taps(a, s) {
                    if w != 0.0 {
                        axpy(w * lambda[a], &self.Et.col_as_slice(q)[f0..], &mut p[f0..n]);
                    }
                }
            }
        }
        InPlane {
            energy: 0.5 * (dot(&g[f4..n], &p[f4..n]) + energy_strip),
            strip_force: lambda[..self.k].iter().sum(),
        }
    }

    /// u_y (m) of the material at the strip position of column `a` after
    /// [`Self::solve`] (interpolated between the rows around the tip).
    pub fn strip_uy(
        &self,
        a: usize,
        g: &[f64],
        first_nonzero: usize,
        s: &StripConstraint,
        lambda: &[f64; MAX_STRIP],
    ) -> f64 {
        let mut u = 0.0;
        let t = self.tap_rows(s);
        for &(r, w) in &t {
            if w == 0.0 {
                continue;
            }
            u -= w * dot(
                &self.Et.col_as_slice(a * self.n + r)[first_nonzero..],
                &g[first_nonzero..],
            );
            for (b, &lb) in lambda.iter().enumerate().take(self.k) {
                if lb != 0.0 {
                    for &(rb, wb) in &t {
                        u += w * wb * lb * self.band_entry(&self.c_band, a, r, b, rb);
                    }
                }
            }
        }
        u
    }

    /// u_y at strip column 0 (the cut line), row r, after [`Self::solve`].
    pub fn line_uy(
        &self,
        r: usize,
        g: &[f64],
        strip: Option<&StripConstraint>,
        lambda: &[f64; MAX_STRIP],
    ) -> f64 {
        let q = self.yi(0, r);
        let mut u = -dot(self.Et.col_as_slice(q), g);
        if let Some(s) = strip {
            for (a, &la) in lambda.iter().enumerate().take(self.k) {
                for (qa, w) in self.taps(a, s) {
                    u += w * la * self.c_top[qa];
                }
            }
        }
        u
    }

    /// Antiplane solve with the strip constraint (u_t = `strip.value` on the
    /// strip at the tip). Returns (energy J/m, sum of strip forces N/m) of the
    /// half model. Allocation-free.
    pub fn solve_antiplane(&self, strip: &StripConstraint) -> (f64, f64) {
        let mut M = self.strip_matrix(&self.cz_band, strip);
        let mut rhs = [0.0; MAX_STRIP];
        rhs[..self.k].fill(strip.value);
        mask_inactive(&mut M, &mut rhs, strip, self.k);
        small_solve(&mut M, &mut rhs, self.k);
        let f: f64 = rhs[..self.k].iter().sum();
        (0.5 * strip.value * f, f)
    }
}

/// Released sets whose factors [`ReleasedWorkspace`] keeps. The trial
/// extensions of a step and the passes of the contact active set move
/// between a few released sets (a face row near the tip or near the end of
/// the bevel in or out), so their factors are kept rather than recomputed.
const FACTOR_SLOTS: usize = 4;

/// The dense Cholesky factor of A_FF for one released set F: the rows of the
/// lower factor packed one after the other (row a, of length a + 1, from
/// a·(a+1)/2), so a factor of F is also the factor of any leading part of F.
#[derive(Debug, Clone)]
struct ReleasedFactor {
    /// The released rows F (ascending) whose factor is in `l`.
    rows: Vec<usize>,
    /// Packed lower factor, capacity R·(R+1)/2.
    l: Vec<f64>,
    /// When the factor was last used (the workspace's call counter).
    used: u64,
}

/// Offset of row a of a packed lower triangle.
#[inline(always)]
fn packed_row(a: usize) -> usize {
    a * (a + 1) / 2
}

/// Preallocated memory of [`CondensedLine::solve_released`]: the released
/// rows, dense Cholesky factors of A_FF for the last few released sets and
/// the right-hand sides.
#[derive(Debug, Clone)]
pub(crate) struct ReleasedWorkspace {
    idx: Vec<usize>,
    /// Factors of the last `FACTOR_SLOTS` released sets (least recently
    /// used replaced first).
    factors: [ReleasedFactor; FACTOR_SLOTS],
    /// Calls so far (the factors' use clock).
    calls: u64,
    z: Vec<f64>,
}

impl ReleasedWorkspace {
    /// Memory for a line of `n` rows (`FACTOR_SLOTS`·n·(n+1)/2 +
    /// n·(MAX_STRIP + 2) doubles; a factor's pages are touched only as far
    /// as its released sets reach).
    pub fn new(n: usize) -> Self {
        Self {
            idx: Vec::with_capacity(n),
            factors: std::array::from_fn(|_| ReleasedFactor {
                rows: Vec::with_capacity(n),
                l: vec![0.0; packed_row(n)],
                used: 0,
            }),
            calls: 0,
            z: vec![0.0; n * (MAX_STRIP + 1)],
        }
    }

    /// The slot holding the factor of the released set `idx`, computing it
    /// (Cholesky–Crout, row by row) if no slot holds it: into the least
    /// recently used slot, starting from the longest leading part of `idx`
    /// that some slot has factorised already (those rows of the factor are
    /// the same). Every row is computed with the same operations as a
    /// factorisation from scratch. Allocation-free.
    #[inline(always)]
    fn factor(&mut self, A: &Mat<f64>) -> usize {
        self.calls += 1;
        let idx = &self.idx;
        let m = idx.len();
        if let Some(hit) = self.factors.iter().position(|f| f.rows == *idx) {
            self.factors[hit].used = self.calls;
            return hit;
        }
        let prefix =
            |f: &ReleasedFactor| f.rows.iter().zip(idx).take_while(|(a, b)| a == b).count();
        let victim = (0..FACTOR_SLOTS)
            .min_by_key(|&s| self.factors[s].used)
            .unwrap_or(0);
        let (best, keep) = (0..FACTOR_SLOTS)
            .map(|s| (s, prefix(&self.factors[s])))
            .max_by_key(|&(s, p)| (p, s == victim))
            .unwrap_or((victim, 0));
        if best != victim && keep > 0 {
            let len = packed_row(keep);
            let (src, dst) = if best < victim {
                let (lo, hi) = self.factors.split_at_mut(victim);
                (&lo[best], &mut hi[0])
            } else {
                let (lo, hi) = self.factors.split_at_mut(best);
                (&hi[0], &mut lo[victim])
            };
            dst.l[..len].copy_from_slice(&src.l[..len]);
        }
        let f = &mut self.factors[victim];
        let l = &mut f.l[..packed_row(m)];
        // Row-oriented (Cholesky–Crout): contiguous dot products.
        for a in keep..m {
            let (before, rest) = l.split_at_mut(packed_row(a));
            let ra = &mut rest[..a + 1];
            let col = A.col_as_slice(idx[a]);
            for (b, &j) in idx.iter().enumerate().take(a + 1) {
                ra[b] = col[j];
            }
            for b in 0..a {
                let rb = &before[packed_row(b)..packed_row(b) + b + 1];
                ra[b] = (ra[b] - dot(&ra[..b], &rb[..b])) / rb[b];
            }
            let d = ra[a] - dot(&ra[..a], &ra[..a]);
            ra[a] = d.max(f64::MIN_POSITIVE).sqrt();
        }
        f.rows.clear();
        f.rows.extend_from_slice(idx);
        f.used = self.calls;
        victim
    }
}

impl CondensedLine {
    /// In-plane solve with the X DOFs of the rows flagged in `released` free
    /// (loaded by `f_ext`, N/m, +x on the material; zero if `None`) and all
    /// others prescribed to `g`. On return `g` holds the solved displacements
    /// of the released rows, `p` the reactions from `first_nonzero` on (p =
    /// f_ext on released rows; not computed below `first_nonzero`, as
    /// [`Self::solve`])
    /// and `lambda` the strip forces, as in [`Self::solve`]. Released rows
    /// must lie at or above `first_nonzero`. Allocation-free.
    ///
    /// With F the released rows, C the prescribed ones, B = EᵀPᵀ the strip's
    /// coupling (P the strip taps) and M = P C Pᵀ:
    /// A_FF g_F + B_F λ = f_F − A_FC g_C and M λ − B_Fᵀ g_F = value + B_Cᵀ g_C;
    /// A_FF is SPD (a principal block of the condensed stiffness), so g_F is
    /// eliminated by a dense Cholesky factorisation and λ solves the k×k
    /// Schur system (M + B_Fᵀ A_FF⁻¹ B_F) λ = value + B_Cᵀ g_C + B_Fᵀ A_FF⁻¹ r_F.
    #[allow(clippy::too_many_arguments)]
    pub fn solve_released(
        &self,
        g: &mut [f64],
        first_nonzero: usize,
        released: &[bool],
        f_ext: Option<&[f64]>,
        strip: Option<&StripConstraint>,
        p: &mut [f64],
        lambda: &mut [f64; MAX_STRIP],
        ws: &mut ReleasedWorkspace,
    ) -> InPlane {
        // The same code compiled for the widest vector instructions the CPU
        // has (pulp's runtime dispatch, through faer). The arithmetic is the
        // same operation by operation (Rust never fuses a multiply and an
        // add, and the sums keep their order), so the results are the same
        // to the bit on any CPU; only the loops run wider.
        faer::traits::pulp::Arch::new().dispatch(ReleasedSolve {
            line: self,
            g,
            first_nonzero,
            released,
            f_ext,
            strip,
            p,
            lambda,
            ws,
        })
    }

    /// [`Self::solve_released`]'s body, inlined into each instruction set's
    /// version.
    #[allow(clippy::too_many_arguments)]
    #[inline(always)]
    fn solve_released_body(
        &self,
        g: &mut [f64],
        first_nonzero: usize,
        released: &[bool],
        f_ext: Option<&[f64]>,
        strip: Option<&StripConstraint>,
        p: &mut [f64],
        lambda: &mut [f64; MAX_STRIP],
        ws: &mut ReleasedWorkspace,
    ) -> InPlane {
        let n = self.n;
        ws.idx.clear();
        // (Released rows lie at or above `first_nonzero`.)
        ws.idx
            .extend((first_nonzero.min(n)..n).filter(|&i| released[i]));
        let m = ws.idx.len();
        if m == 0 {
            return self.solve(g, first_nonzero, strip, p, lambda);
        }
        let first = first_nonzero.min(ws.idx[0]);
        for &i in &ws.idx {
            g[i] = 0.0;
        }
        // r_F = f_F − A_FC g_C (A symmetric: row i is column i).
        for (a, &i) in ws.idx.iter().enumerate() {
            let f = f_ext.map_or(0.0, |f| f[i]);
            ws.z[a] = f - dot(&self.A.col_as_slice(i)[first..], &g[first..]);
        }
        // Dense Cholesky of A_FF (lower, packed rows), unless the factor of
        // this released set is kept already.
        let slot = ws.factor(&self.A);
        let l = &ws.factors[slot].l[..packed_row(m)];
        if let Some(s) = strip {
            // Z_B = B_F, column a in z[(a + 1)·n..], then r_F and Z_B are
            // solved together: Z_B = A_FF⁻¹ B_F.
            let zb = &mut ws.z[n..];
            for a in 0..self.k {
                let zc = &mut zb[a * n..a * n + m];
                zc.fill(0.0);
                for (q, w) in self.taps(a, s) {
                    if w != 0.0 {
                        let et = self.Et.col_as_slice(q);
                        for (z, &i) in zc.iter_mut().zip(&ws.idx) {
                            *z += w * et[i];
                        }
                    }
                }
            }
            chol_solve_columns(l, &mut ws.z, n, m, 1 + self.k);
            let (rf, zb) = ws.z.split_at(n);
            let mut S = self.strip_matrix(&self.c_band, s);
            let mut rhs = [0.0; MAX_STRIP];
            for a in 0..self.k {
                rhs[a] = s.value;
                for (q, w) in self.taps(a, s) {
                    if w != 0.0 {
                        let et = self.Et.col_as_slice(q);
                        // B_Cᵀ g_C (g_F is zero here) and B_Fᵀ A_FF⁻¹ r_F,
                        // and B_Fᵀ Z_B into S: each sum in the order of the
                        // released rows, the sums side by side.
                        rhs[a] += w * dot(&et[first..], &g[first..]);
                        let Sa = &mut S[a];
                        for (c, &i) in ws.idx.iter().enumerate() {
                            let t = w * et[i];
                            rhs[a] += t * rf[c];
                            for b in 0..self.k {
                                Sa[b] += t * zb[b * n + c];
                            }
                        }
                    }
                }
            }
            mask_inactive(&mut S, &mut rhs, s, self.k);
            small_solve(&mut S, &mut rhs, self.k);
            for (c, &i) in ws.idx.iter().enumerate() {
                let mut v = rf[c];
                for (b, &lb) in rhs.iter().enumerate().take(self.k) {
                    v -= zb[b * n + c] * lb;
                }
                g[i] = v;
            }
        } else {
            chol_solve_columns(l, &mut ws.z, n, m, 1);
            for (c, &i) in ws.idx.iter().enumerate() {
                g[i] = ws.z[c];
            }
        }
        // The full displacement vector satisfies the strip equations, so the
        // plain solve recovers the same λ, the reactions and the energy; the
        // external forces' work is part of ½ g·p (p_F = f_F).
        self.solve(g, first, strip, p, lambda)
    }
}

/// The arguments of [`CondensedLine::solve_released`], run by pulp's
/// dispatch with the CPU's vector instructions enabled.
struct ReleasedSolve<'a> {
    line: &'a CondensedLine,
    g: &'a mut [f64],
    first_nonzero: usize,
    released: &'a [bool],
    f_ext: Option<&'a [f64]>,
    strip: Option<&'a StripConstraint>,
    p: &'a mut [f64],
    lambda: &'a mut [f64; MAX_STRIP],
    ws: &'a mut ReleasedWorkspace,
}

impl faer::traits::pulp::WithSimd for ReleasedSolve<'_> {
    type Output = InPlane;

    #[inline(always)]
    fn with_simd<S: faer::traits::pulp::Simd>(self, _simd: S) -> InPlane {
        self.line.solve_released_body(
            self.g,
            self.first_nonzero,
            self.released,
            self.f_ext,
            self.strip,
            self.p,
            self.lambda,
            self.ws,
        )
    }
}

/// Solves L Lᵀ x = b in place (x ← b on entry) for the packed lower factor
/// `l` of order `m`, for the `cols` right-hand sides z[c·stride..c·stride +
/// m]: L y = b (rows of L contiguous), then Lᵀ x = y (column sweep along the
/// rows of L). The columns are swept side by side, row by row, so their
/// independent divisions and dot products overlap; each column's operations
/// are those of a solve on its own.
#[inline(always)]
fn chol_solve_columns(l: &[f64], z: &mut [f64], stride: usize, m: usize, cols: usize) {
    for a in 0..m {
        let r = packed_row(a);
        let (row, d) = (&l[r..r + a], l[r + a]);
        for c in 0..cols {
            let x = &mut z[c * stride..c * stride + m];
            x[a] = (x[a] - dot(row, &x[..a])) / d;
        }
    }
    for a in (0..m).rev() {
        let r = packed_row(a);
        let (row, d) = (&l[r..r + a], l[r + a]);
        for c in 0..cols {
            let x = &mut z[c * stride..c * stride + m];
            x[a] /= d;
            let xa = x[a];
            axpy(-xa, row, &mut x[..a]);
        }
    }
}

/// Marks a DOF fixed (the bottom row) in the numbering of [`CondensedLine::new`].
const FIXED: usize = usize::MAX;
/// Offset marking a kept DOF: `KEPT + q` is kept DOF q (interior DOFs are
/// numbered below it).
const KEPT: usize = usize::MAX / 2;

/// Numbers the DOFs from `first` on that are neither fixed nor kept (the
/// interior) 0, 1, … in DOF order; the DOFs before `first` (the bottom row of
/// nodes: `first` is the number of DOFs per node row) are fixed. Returns the
/// number of interior DOFs.
fn number_interior(index: &mut [usize], first: usize) -> usize {
    let mut ni = 0;
    for (dof, slot) in index.iter_mut().enumerate() {
        if dof < first {
            *slot = FIXED;
        } else if *slot == FIXED {
            *slot = ni;
            ni += 1;
        }
    }
    ni
}

/// Position of a numbered DOF in the matrix of [`schur_factor`]: interior
/// DOFs first, the kept ones after the `ni` interior ones; `None` if fixed.
#[inline]
fn position(index: usize, ni: usize) -> Option<usize> {
    match index {
        FIXED => None,
        i if i >= KEPT => Some(ni + i - KEPT),
        i => Some(i),
    }
}

/// The lower Cholesky factor L_bb (dense, `nb`×`nb`, column-major into
/// `memory.dense`) of the Schur complement
/// S = K_bb − K_bi K_ii⁻¹ K_ib of the SPD matrix K onto its last `nb` rows
/// and columns, after the `ni` interior ones: S = L_bb L_bbᵀ. K is given by
/// `assemble`, which calls its argument `add(i, j, k_ij)` for every
/// contribution (both triangles, duplicates summed; the upper ones are
/// skipped).
///
/// K is factorised once by faer's supernodal sparse Cholesky with the kept
/// DOFs ordered last, so the trailing block of the factor is L_bb: a partial
/// factorisation, no triangular solves. The kept DOFs form a dense trailing
/// front that the supernodal kernels treat with dense (BLAS-3) updates. The
/// interior is ordered by `interior_order` (new → old interior number; a
/// nested dissection of the mesh's node grid, [`nested_dissection`]),
/// called only when the pattern is not cached.
///
/// K's pattern, the order in which its contributions are summed and the
/// symbolic factorisation depend only on the mesh's `topology`: they are
/// taken from the [`factor_cache`] when a section of the same topology was
/// built before (bit-identical either way), and the scratch memory comes
/// from `memory`.
fn schur_factor(
    topology: Topology,
    ni: usize,
    nb: usize,
    interior_order: impl FnOnce() -> Vec<usize>,
    memory: &mut FactorMemory,
    assemble: impl FnOnce(&mut dyn FnMut(usize, usize, f64)),
) -> Result<(), SectionError> {
    let cached = factor_cache::lookup(&topology).filter(|p| p.ni == ni && p.nb == nb);
    let FactorMemory {
        contributions,
        pairs,
        ..
    } = memory;
    contributions.clear();
    pairs.clear();
    let record = cached.is_none();
    assemble(&mut |a, b, v| {
        if a >= b {
            contributions.push(v);
            if record {
                pairs.push((a, b));
            }
        }
    });
    let pattern = match cached {
        Some(p) if p.contributions() == contributions.len() => p,
        Some(_) => {
            return Err(SectionError::Factorisation(
                "the cached stiffness pattern does not match the mesh",
            ));
        }
        None => {
            // Fill-reducing order of the interior, the kept DOFs last, in place.

            let nt = ni + nb;
            let mut fwd = interior_order();
            fwd.extend(ni..nt);
            let p = Arc::new(StiffnessPattern::new(ni, nb, pairs, &fwd)?);
            factor_cache::insert(topology, Arc::clone(&p));
            p
        }
    };
    let symbolic = &pattern.symbolic;
    let SymbolicCholeskyRaw::Supernodal(supernodal) = symbolic.raw() else {
        return Err(SectionError::Factorisation(
            "the Cholesky factor is not supernodal",
        ));
    };
    let FactorMemory {
        contributions,
        lower,
        factor,
        stack,
        dense,
        ..
    } = memory;
    let stack = factor_cache::grow_stack(stack, pattern.stack)?;
    let K = pattern.sum(contributions, lower);
    let len = symbolic.len_val();
    if factor.len() < len {
        factor.resize(len, 0.0);
    }
    let values = &mut factor[..len];
    // K is already in the factorisation's order (as faer's
    // `SymbolicCholesky::factorize_numeric_llt` would permute it).
    factorize_supernodal_numeric_llt(
        values,
        K,
        Default::default(),
        supernodal,
        Par::Seq,
        MemStack::new(stack),
        Default::default(),
    )
    .map_err(|_| SectionError::Factorisation("stiffness is not positive definite"))?;
    // Read L_bb off the supernodes holding columns ni.. (their rows are all
    // kept DOFs too: the kept ones come last).
    let factor = SupernodalLltRef::new(supernodal, &factor[..len]);
    // Only the lower triangle is read (as L's blocks, or lower-triangular
    // ones): zero it (the entries outside the supernodes' patterns are
    // the factor's structural zeros) and leave the upper one as it was.
    if dense.len() < nb * nb {
        dense.resize(nb * nb, 0.0);
    }
    for j in 0..nb {
        dense[j * nb + j..(j + 1) * nb].fill(0.0);
    }
    let mut L = MatMut::from_column_major_slice_mut(&mut dense[..nb * nb], nb, nb);
    for s in 0..supernodal.n_supernodes() {
        let node = factor.supernode(s);
        let start = node.start();
        let Ls = node.val();
        let width = Ls.ncols();
        if start + width <= ni {
            continue;
        }
        let pattern = node.pattern();
        for jj in 0..width {
            let j = start + jj;
            if j < ni {
                continue;
            }
            for ii in jj..width {
                L[(start + ii - ni, j - ni)] = Ls[(ii, jj)];
            }
            for (p, &row) in pattern.iter().enumerate() {
                L[(row - ni, j - ni)] = Ls[(width + p, jj)];
            }
        }
    }
    Ok(())
}

/// The lower triangle of the symmetric matrix given by `triplets` (both
/// triangles, duplicates summed; the upper ones are skipped) in compressed
/// sparse columns: a counting sort on the columns, then a sort of each
/// column's few entries by row. The assembly of the section builds before
/// the [`factor_cache`]; kept as the reference of its summation order.
#[cfg(test)]
fn lower_csc(nt: usize, triplets: &[Triplet<usize, usize, f64>]) -> SparseColMat<usize, f64> {
    let mut start = vec![0usize; nt + 1];
    for t in triplets.iter().filter(|t| t.row >= t.col) {
        start[t.col + 1] += 1;
    }
    for j in 0..nt {
        start[j + 1] += start[j];
    }
    let total = start[nt];
    let mut next = start.clone();
    let mut entries = vec![(0usize, 0.0f64); total];
    for t in triplets.iter().filter(|t| t.row >= t.col) {
        entries[next[t.col]] = (t.row, t.val);
        next[t.col] += 1;
    }
    let mut col_ptr = Vec::with_capacity(nt + 1);
    let mut row_idx = Vec::with_capacity(total);
    let mut values = Vec::with_capacity(total);
    col_ptr.push(0);
    for j in 0..nt {
        let column = &mut entries[start[j]..start[j + 1]];
        column.sort_unstable_by_key(|e| e.0);
        let first = row_idx.len();
        for &(i, v) in column.iter() {
            if row_idx.len() > first && row_idx[row_idx.len() - 1] == i {
                let last = values.len() - 1;
                values[last] += v;
            } else {
                row_idx.push(i);
                values.push(v);
            }
        }
        col_ptr.push(row_idx.len());
    }
    let symbolic = SymbolicSparseColMat::new_checked(nt, nt, col_ptr, None, row_idx);
    SparseColMat::new(symbolic, values)
}

/// L⁻¹ of a dense lower-triangular factor L (its lower triangle only), in
/// `memory`: the strictly upper part is whatever `memory` held (faer writes
/// and reads only the lower triangle, and so do the users of the result:
/// [`inverse_entry`] and the lower-triangular product of Eᵀ).
fn lower_inverse<'a>(L: MatRef<'_, f64>, memory: &'a mut Vec<f64>) -> MatRef<'a, f64> {
    let m = L.nrows();
    if memory.len() < m * m {
        memory.resize(m * m, 0.0);
    }
    let Linv = MatMut::from_column_major_slice_mut(&mut memory[..m * m], m, m);
    triangular_inverse::invert_lower_triangular(Linv, L, Par::Seq);
    MatRef::from_column_major_slice(&memory[..m * m], m, m)
}

/// The entries of F = (L Lᵀ)⁻¹ = L⁻ᵀ L⁻¹ that the solves read, from
/// `linv` = L⁻¹ (m×m, m = k·n; index c·n + a for strip column c, row a):
/// F[(c₁·n + a, c₂·n + b)] for |a − b| ≤ 1 at
/// `((a·k + c₁)·k + c₂)·3 + b + 1 − a` (0 where b is out of range). Each
/// entry is the dot product of columns q₁ and q₂ of L⁻¹ over the rows from
/// max(q₁, q₂) on (below them L⁻¹ is zero), so F is exactly symmetric.
fn inverse_band(linv: MatRef<'_, f64>, n: usize, k: usize) -> Vec<f64> {
    let mut band = vec![0.0; n * k * k * 3];
    for a in 0..n {
        for c1 in 0..k {
            for c2 in 0..k {
                for b in a.saturating_sub(1)..(a + 2).min(n) {
                    let (q1, q2) = (c1 * n + a, c2 * n + b);
                    band[((a * k + c1) * k + c2) * 3 + b + 1 - a] = inverse_entry(linv, q1, q2);
                }
            }
        }
    }
    band
}

/// Row q of (L Lᵀ)⁻¹ from `linv` = L⁻¹, as [`inverse_band`].
fn inverse_row(linv: MatRef<'_, f64>, q: usize) -> Vec<f64> {
    (0..linv.ncols())
        .map(|p| inverse_entry(linv, q, p))
        .collect()
}

/// Entry (q1, q2) of L⁻ᵀ L⁻¹ from `linv` = L⁻¹ (column-major, contiguous
/// columns): symmetric in its arguments.
#[inline]
fn inverse_entry(linv: MatRef<'_, f64>, q1: usize, q2: usize) -> f64 {
    let from = q1.max(q2);
    let col = |q: usize| {
        &linv
            .col(q)
            .try_as_col_major()
            .expect("contiguous")
            .as_slice()[from..]
    };
    let (x, y) = if q1 <= q2 {
        (col(q1), col(q2))
    } else {
        (col(q2), col(q1))
    };
    dot(x, y)
}

/// Copies the strictly lower triangle of a square matrix onto its upper one.
fn symmetrise_from_lower(M: &mut Mat<f64>) {
    for j in 0..M.ncols() {
        for i in j + 1..M.nrows() {
            M[(j, i)] = M[(i, j)];
        }
    }
}

/// Dot product with four partial sums (lets the compiler vectorise).
#[inline(always)]
fn dot(a: &[f64], b: &[f64]) -> f64 {
    let n = a.len().min(b.len());
    let (a, b) = (&a[..n], &b[..n]);
    let mut acc = [0.0; 4];
    let (ca, cb) = (a.chunks_exact(4), b.chunks_exact(4));
    let (ra, rb) = (ca.remainder(), cb.remainder());
    for (x, y) in ca.zip(cb) {
        for k in 0..4 {
            acc[k] += x[k] * y[k];
        }
    }
    let tail: f64 = ra.iter().zip(rb).map(|(x, y)| x * y).sum();
    (acc[0] + acc[1]) + (acc[2] + acc[3]) + tail
}

/// `out` = Σ_{i ∈ from..to, g_i ≠ 0} g_i · M[from..to, i] (`out` has
/// to − from entries), each entry summed from 0 in ascending i: the same
/// operations, in the same order, as zeroing `out` and adding the columns
/// one by one with [`axpy`], so the same bits. Computed in blocks of
/// [`PRODUCT_BLOCK`] rows whose sums stay in registers while the columns
/// stream past (one load of M per term instead of a load and a store of
/// `out` too). Allocation-free.
#[inline(always)]
fn column_product(M: &Mat<f64>, g: &[f64], from: usize, to: usize, out: &mut [f64]) {
    let (g, out) = (&g[from..to], &mut out[..to - from]);
    let mut blocks = out.chunks_exact_mut(PRODUCT_BLOCK);
    let mut row = from;
    for block in &mut blocks {
        let mut acc = [0.0; PRODUCT_BLOCK];
        for (i, &gi) in g.iter().enumerate() {
            if gi != 0.0 {
                let col = &M.col_as_slice(from + i)[row..row + PRODUCT_BLOCK];
                for (a, &m) in acc.iter_mut().zip(col) {
                    *a += gi * m;
                }
            }
        }
        block.copy_from_slice(&acc);
        row += PRODUCT_BLOCK;
    }
    let rest = blocks.into_remainder();
    if !rest.is_empty() {
        rest.fill(0.0);
        for (i, &gi) in g.iter().enumerate() {
            if gi != 0.0 {
                axpy(gi, &M.col_as_slice(from + i)[row..to], rest);
            }
        }
    }
}

/// Rows per block of [`column_product`]: four 256-bit registers.
const PRODUCT_BLOCK: usize = 16;

#[inline(always)]
fn axpy(alpha: f64, x: &[f64], y: &mut [f64]) {
    for (yi, xi) in y.iter_mut().zip(x) {
        *yi += alpha * xi;
    }
}

/// Decouples the inactive strip columns: their rows and columns of M become
/// the identity and their right-hand side 0, so their force is 0.
fn mask_inactive(
    M: &mut [[f64; MAX_STRIP]; MAX_STRIP],
    b: &mut [f64; MAX_STRIP],
    s: &StripConstraint,
    k: usize,
) {
    for a in 0..k {
        if !s.active[a] {
            for c in 0..k {
                M[a][c] = 0.0;
                M[c][a] = 0.0;
            }
            M[a][a] = 1.0;
            b[a] = 0.0;
        }
    }
}

/// Solves the k×k system M x = b in place (b ← x) by Gaussian elimination
/// with partial pivoting; k ≤ MAX_STRIP (the strip constraints).
fn small_solve(M: &mut [[f64; MAX_STRIP]; MAX_STRIP], b: &mut [f64; MAX_STRIP], k: usize) {
    for col in 0..k {
        let piv = (col..k)
            .max_by(|&i, &j| M[i][col].abs().total_cmp(&M[j][col].abs()))
            .unwrap_or(col);
        M.swap(col, piv);
        b.swap(col, piv);
        let d = M[col][col];
        for row in col + 1..k {
            let f = M[row][col] / d;
            for c in col..k {
                M[row][c] -= f * M[col][c];
            }
            b[row] -= f * b[col];
        }
    }
    for col in (0..k).rev() {
        let mut s = b[col];
        for c in col + 1..k {
            s -= M[col][c] * b[c];
        }
        b[col] = s / M[col][col];
    }
}

#[cfg(test)]
mod tests {
    //! The partial factorisation against the previous algorithm (one sparse
    //! factorisation of the stiffness with X and the bottom fixed, then unit
    //! loads on Y and unit displacements of X solved column by column), kept
    //! here as the reference.

    use faer::linalg::solvers::Solve;

    use super::super::geometry::SectionGeometry;
    use super::super::settings::SectionSettings;
    use super::*;

    /// (C, Eᵀ, A, C_z) by unit solves: the reference.
    fn by_unit_solves(mesh: &SectionMesh, e_mod: f64, nu: f64) -> [Mat<f64>; 4] {
        let n = mesh.rows;
        let k = mesh.strip + 1;
        let nn = mesh.node_count();
        let mut x_of = vec![FIXED; 2 * nn];
        let mut free_of = vec![FIXED; 2 * nn];
        for r in 1..=n {
            x_of[2 * mesh.node(0, r)] = r - 1;
        }
        let mut nf = 0;
        for dof in 0..2 * nn {
            if dof / 2 >= mesh.columns() && x_of[dof] == FIXED {
                free_of[dof] = nf;
                nf += 1;
            }
        }
        let mut kff = Vec::new();
        let mut kfx: Vec<Vec<(usize, f64)>> = vec![Vec::new(); n];
        let mut A = Mat::<f64>::zeros(n, n);
        plane_strain::assemble(mesh, e_mod, nu, |i, j, v| {
            match (free_of[i], free_of[j], x_of[i], x_of[j]) {
                (fi, fj, _, _) if fi != FIXED && fj != FIXED => kff.push(Triplet::new(fi, fj, v)),
                (fi, _, _, xj) if fi != FIXED && xj != FIXED => kfx[xj].push((fi, v)),
                (_, _, xi, xj) if xi != FIXED && xj != FIXED => A[(xi, xj)] += v,
                _ => {}
            }
        });
        let llt = sparse_llt(nf, &kff).unwrap();
        let ny = k * n;
        let y_free: Vec<usize> = (0..k)
            .flat_map(|c| (1..=n).map(move |r| (c, r)))
            .map(|(c, r)| free_of[2 * mesh.node(c, r) + 1])
            .collect();
        let mut rhs = Mat::<f64>::zeros(nf, ny + n);
        for (q, &fq) in y_free.iter().enumerate() {
            rhs[(fq, q)] = 1.0;
        }
        for (i, col) in kfx.iter().enumerate() {
            for &(fi, v) in col {
                rhs[(fi, ny + i)] -= v;
            }
        }
        llt.solve_in_place(rhs.as_mut());
        let C = Mat::from_fn(ny, ny, |a, q| rhs[(y_free[a], q)]);
        let Et = Mat::from_fn(n, ny, |i, a| -rhs[(y_free[a], ny + i)]);
        for (xi, col) in kfx.iter().enumerate() {
            for i in 0..n {
                A[(xi, i)] += col
                    .iter()
                    .map(|&(fi, v)| v * rhs[(fi, ny + i)])
                    .sum::<f64>();
            }
        }
        let mut zfree = vec![FIXED; nn];
        let mut nz = 0;
        for (node, z) in zfree.iter_mut().enumerate() {
            if node >= mesh.columns() {
                *z = nz;
                nz += 1;
            }
        }
        let mut kzz = Vec::new();
        antiplane::assemble(mesh, e_mod / (2.0 * (1.0 + nu)), |i, j, v| {
            if zfree[i] != FIXED && zfree[j] != FIXED {
                kzz.push(Triplet::new(zfree[i], zfree[j], v));
            }
        });
        let lltz = sparse_llt(nz, &kzz).unwrap();
        let z_free: Vec<usize> = (0..k)
            .flat_map(|c| (1..=n).map(move |r| (c, r)))
            .map(|(c, r)| zfree[mesh.node(c, r)])
            .collect();
        let mut rz = Mat::<f64>::zeros(nz, ny);
        for (q, &fq) in z_free.iter().enumerate() {
            rz[(fq, q)] = 1.0;
        }
        lltz.solve_in_place(rz.as_mut());
        let Cz = Mat::from_fn(ny, ny, |a, q| rz[(z_free[a], q)]);
        [C, Et, A, Cz]
    }

    /// The entries of C (or C_z) that a line keeps: its band (see
    /// [`inverse_band`]) and, for C, the row of the top DOF of column 0.
    fn kept_entries(F: &Mat<f64>, n: usize, k: usize, top_row: bool) -> Vec<f64> {
        let mut v = Vec::new();
        for a in 0..n {
            for c1 in 0..k {
                for c2 in 0..k {
                    for b in a.saturating_sub(1)..(a + 2).min(n) {
                        v.push(F[(c1 * n + a, c2 * n + b)]);
                    }
                }
            }
        }
        if top_row {
            v.extend((0..k * n).map(|q| F[(n - 1, q)]));
        }
        v
    }

    /// The same entries as [`kept_entries`] from a line.
    fn line_entries(line: &CondensedLine, band: &[f64], top_row: bool) -> Vec<f64> {
        let (n, k) = (line.n, line.k);
        let mut v = Vec::new();
        for a in 0..n {
            for c1 in 0..k {
                for c2 in 0..k {
                    for b in a.saturating_sub(1)..(a + 2).min(n) {
                        v.push(line.band_entry(band, c1, a, c2, b));
                    }
                }
            }
        }
        if top_row {
            v.extend_from_slice(&line.c_top);
        }
        v
    }

    /// ‖new − reference‖ / ‖reference‖ (Euclidean) for C (its kept
    /// entries), Eᵀ, A and C_z (its band), in that order.
    fn relative_differences(geometry: &SectionGeometry, settings: &SectionSettings) -> [f64; 4] {
        let mesh = SectionMesh::new(geometry, 1e-4, settings).unwrap();
        let (e_mod, nu) = (2.0e6, 0.4);
        let line = CondensedLine::new(&mesh, e_mod, nu).unwrap();
        let [C, Et, A, Cz] = by_unit_solves(&mesh, e_mod, nu);
        let (n, k) = (line.n, line.k);
        let rel = |new: &[f64], reference: &[f64]| {
            let d: f64 = new
                .iter()
                .zip(reference)
                .map(|(a, b)| (a - b).powi(2))
                .sum();
            let r: f64 = reference.iter().map(|b| b * b).sum();
            (d / r).sqrt()
        };
        let flat = |m: &Mat<f64>| {
            (0..m.ncols())
                .flat_map(|j| m.col(j).iter().copied().collect::<Vec<_>>())
                .collect::<Vec<_>>()
        };
        [
            rel(
                &line_entries(&line, &line.c_band, true),
                &kept_entries(&C, n, k, true),
            ),
            rel(&flat(&line.Et), &flat(&Et)),
            rel(&flat(&line.A), &flat(&A)),
            rel(
                &line_entries(&line, &line.cz_band, false),
                &kept_entries(&Cz, n, k, false),
            ),
        ]
    }

    fn assert_same(geometry: &SectionGeometry, settings: &SectionSettings) {
        let d = relative_differences(geometry, settings);
        for (name, d) in ["C", "Et", "A", "Cz"].iter().zip(d) {
            assert!(d < 1e-10, "{name}: relative difference {d:e}");
        }
    }

    use super::tests_support::dome;

    #[test]
    fn partial_factorisation_matches_unit_solves_on_a_rectangle() {
        let settings = SectionSettings {
            row_spacing: 5e-4,
            ..SectionSettings::default()
        };
        assert_same(&SectionGeometry::rectangle(0.01, 0.008).unwrap(), &settings);
    }

    #[test]
    fn partial_factorisation_matches_unit_solves_with_a_wide_strip_on_a_dome() {
        let settings = SectionSettings {
            row_spacing: 5e-4,
            strip_elements: 3,
            ..SectionSettings::default()
        };
        assert_same(&dome(0.006, 0.009), &settings);
    }

    /// The factor cache's assembly (contributions summed in a recorded
    /// order, placed in the factorisation's order) gives the same bits as
    /// the triplet assembly it replaced.
    #[test]
    fn cached_assembly_sums_in_the_order_of_the_triplets() {
        let settings = SectionSettings {
            row_spacing: 5e-4,
            ..SectionSettings::default()
        };
        let mesh = SectionMesh::new(&dome(0.006, 0.009), 1e-4, &settings).unwrap();
        let (n, k, nn) = (mesh.rows, mesh.strip + 1, mesh.node_count());
        let mut index = vec![FIXED; 2 * nn];
        for c in 0..k {
            for r in 1..=n {
                index[2 * mesh.node(c, r) + 1] = KEPT + c * n + r - 1;
            }
        }
        for r in 1..=n {
            index[2 * mesh.node(0, r)] = KEPT + k * n + r - 1;
        }
        let ni = number_interior(&mut index, 2 * mesh.columns());
        let nb = (k + 1) * n;
        let (mut triplets, mut pairs, mut contributions) = (Vec::new(), Vec::new(), Vec::new());
        plane_strain::assemble(&mesh, 2.0e6, 0.4, |i, j, v| {
            if let (Some(a), Some(b)) = (position(index[i], ni), position(index[j], ni)) {
                triplets.push(Triplet::new(a, b, v));
                if a >= b {
                    pairs.push((a, b));
                    contributions.push(v);
                }
            }
        });
        let mut fwd = nested_dissection(&mesh, &index, 2, KEPT, ni);
        fwd.extend(ni..ni + nb);
        let pattern = StiffnessPattern::new(ni, nb, &pairs, &fwd).unwrap();
        let mut values = Vec::new();
        // P K Pᵀ: entry (r, c) is K's (fwd[r], fwd[c]).
        let cached = pattern.sum(&contributions, &mut values);
        let reference = lower_csc(ni + nb, &triplets);
        assert_eq!(cached.compute_nnz(), reference.compute_nnz());
        for c in 0..ni + nb {
            for (r, v) in cached.row_idx_of_col(c).zip(cached.val_of_col(c)) {
                let (i, j) = (fwd[r].max(fwd[c]), fwd[r].min(fwd[c]));
                let k = reference.row_idx_of_col(j).position(|x| x == i);
                let k = k.expect("the entry is in K's pattern");
                assert_eq!(v.to_bits(), reference.val_of_col(j)[k].to_bits());
            }
        }
    }

    /// A build whose pattern comes from the cache gives the same bits as the
    /// build that computed it, also for another shape of the same topology
    /// (same rows and columns, other coordinates).
    #[test]
    fn builds_from_the_factor_cache_are_bit_identical() {
        let settings = SectionSettings {
            row_spacing: 5e-4,
            ..SectionSettings::default()
        };
        let (e_mod, nu) = (2.0e6, 0.4);
        let bits = |line: &CondensedLine| {
            let dense = [&line.Et, &line.A].map(|m| {
                (0..m.ncols())
                    .flat_map(|j| m.col_as_slice(j).iter().map(|x| x.to_bits()))
                    .collect::<Vec<_>>()
            });
            let kept = [&line.c_band, &line.c_top, &line.cz_band]
                .map(|v| v.iter().map(|x| x.to_bits()).collect::<Vec<_>>());
            [&dense[0], &dense[1], &kept[0], &kept[1], &kept[2]].map(|v| v.clone())
        };
        let a = SectionMesh::new(&dome(0.006, 0.009), 1e-4, &settings).unwrap();
        let b = SectionMesh::new(&dome(0.0061, 0.0091), 1e-4, &settings).unwrap();
        assert_eq!((a.rows, a.columns()), (b.rows, b.columns()));
        assert_ne!(a.nodes, b.nodes);
        let cold = |mesh: &SectionMesh| {
            for problem in [Problem::InPlane, Problem::Antiplane] {
                factor_cache::forget(&Topology::of(mesh, problem));
            }
            CondensedLine::new(mesh, e_mod, nu).unwrap()
        };
        let a_cold = bits(&cold(&a));
        let a_cached = bits(&CondensedLine::new(&a, e_mod, nu).unwrap());
        assert!(a_cold == a_cached, "a cached build differs");
        let b_cached = bits(&CondensedLine::new(&b, e_mod, nu).unwrap());
        let b_cold = bits(&cold(&b));
        assert!(b_cold == b_cached, "a build on a cached topology differs");
        assert!(a_cold != b_cold, "the two shapes differ");
    }

    /// The blocked column product gives the bits of the column-by-column
    /// axpy it replaced, for every start row (block remainders of every
    /// length) and with zero gaps skipped.
    #[test]
    fn column_product_is_the_axpy_sum_to_the_bit() {
        let n = 53;
        let mut seed = 0x2545_f491_4f6c_dd1d_u64;
        let mut next = || {
            seed ^= seed << 13;
            seed ^= seed >> 7;
            seed ^= seed << 17;
            (seed >> 11) as f64 / (1u64 << 53) as f64 - 0.5
        };
        let M = Mat::<f64>::from_fn(n, n, |_, _| next());
        let mut g: Vec<f64> = (0..n).map(|_| next()).collect();
        for i in (0..n).step_by(5) {
            g[i] = 0.0;
        }
        for from in 0..=n {
            let mut reference = vec![0.0; n - from];
            for (i, &gi) in g.iter().enumerate().skip(from) {
                if gi != 0.0 {
                    axpy(gi, &M.col_as_slice(i)[from..], &mut reference);
                }
            }
            let mut out = vec![f64::NAN; n - from];
            column_product(&M, &g, from, n, &mut out);
            let bits = |v: &[f64]| v.iter().map(|x| x.to_bits()).collect::<Vec<_>>();
            assert_eq!(bits(&out), bits(&reference), "from row {from}");
        }
    }

    /// The default mesh of the loop's half potato (a large reference
    /// computation: run in a release build).
    #[test]
    #[ignore = "the reference takes minutes in a debug build; run with --release -- --ignored"]
    fn partial_factorisation_matches_unit_solves_on_the_default_potato_mesh() {
        assert_same(&dome(0.03, 0.035), &SectionSettings::default());
    }
}

#[cfg(test)]
mod tests_support {
    use super::super::geometry::SectionGeometry;
    /// A dome (half ellipse on a low rim), like a half potato's section.
    pub(super) fn dome(half_width: f64, height: f64) -> SectionGeometry {
        let rim = 0.05 * height;
        let mut v = vec![[-half_width, 0.0], [half_width, 0.0]];
        for i in 0..=32 {
            let t = std::f64::consts::FRAC_PI_2 * i as f64 / 32.0;
            let (x, y) = (half_width * t.cos(), rim + (height - rim) * t.sin());
            v.push([x, y]);
        }
        for i in (0..32).rev() {
            let t = std::f64::consts::FRAC_PI_2 * i as f64 / 32.0;
            v.push([-half_width * t.cos(), rim + (height - rim) * t.sin()]);
        }
        SectionGeometry::from_polygon(&v).unwrap()
    }
}
