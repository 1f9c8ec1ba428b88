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
//! are computed from one sparse factorisation of the stiffness with X and the
//! bottom fixed: C from unit loads on Y, E and A from unit displacements of X.
//!
//! # Antiplane (seed 000 §III.C, ∇²u_t = 0)
//! Kept: Z = u_t of the strip columns; only the bottom is fixed, so the
//! flexibility C_z = S_ZZ⁻¹ is the antiplane stiffness's inverse on Z.
//!
//! # Memory allocation
//! Construction allocates the matrices (|Y|² + |Y|·R + R² + |Z|² doubles, a few
//! MB for the default mesh). [`CondensedLine::solve`] allocates nothing, nor
//! does [`CondensedLine::solve_released`] (crack faces released from the
//! blade: a dense Cholesky of the released rows' block of A in a
//! [`ReleasedWorkspace`]).

#![allow(non_snake_case, clippy::needless_range_loop)]

use faer::linalg::solvers::Solve;
use faer::sparse::linalg::solvers::{Llt, SymbolicLlt};
use faer::sparse::{SparseColMat, Triplet};
use faer::{Mat, Side};

use super::error::SectionError;
use super::mesh::SectionMesh;
use super::{antiplane, plane_strain};

/// Columns solved at once when condensing.
const BLOCK: usize = 64;

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
    /// C = S_YY⁻¹ (|Y|×|Y|).
    C: Mat<f64>,
    /// Eᵀ (R×|Y|): column q is row q of E.
    Et: Mat<f64>,
    /// A (R×R), symmetric.
    A: Mat<f64>,
    /// Antiplane flexibility C_z (|Z|×|Z|).
    Cz: Mat<f64>,
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

pub(crate) fn sparse_llt(
    n: usize,
    triplets: &[Triplet<usize, usize, f64>],
) -> Result<Llt<usize, f64>, SectionError> {
    let K = SparseColMat::<usize, f64>::try_new_from_triplets(n, n, triplets)
        .map_err(|_| SectionError::Factorisation("sparse assembly failed"))?;
    let symbolic = SymbolicLlt::try_new(K.symbolic(), Side::Lower)
        .map_err(|_| SectionError::Factorisation("symbolic Cholesky failed"))?;
    Llt::try_new_with_symbolic(symbolic, K.as_ref(), Side::Lower)
        .map_err(|_| SectionError::Factorisation("stiffness is not positive definite"))
}

impl CondensedLine {
    /// Factorises the stiffness of `mesh` (E in Pa, ν) and condenses it.
    pub fn new(mesh: &SectionMesh, e_mod: f64, nu: f64) -> Result<Self, SectionError> {
        let n = mesh.rows;
        let k = mesh.strip + 1;
        let nn = mesh.node_count();
        // ---- in-plane: classify DOFs.
        const FIXED: usize = usize::MAX;
        let mut x_of = vec![FIXED; 2 * nn]; // DOF -> X index
        let mut free_of = vec![FIXED; 2 * nn]; // DOF -> free index
        for r in 1..=n {
            x_of[2 * mesh.node(0, r)] = r - 1;
        }
        let mut nf = 0;
        for dof in 0..2 * nn {
            let node = dof / 2;
            if node >= mesh.columns() && x_of[dof] == FIXED {
                free_of[dof] = nf;
                nf += 1;
            }
        }
        let mut kff = Vec::new();
        let mut kfx: Vec<Vec<(usize, f64)>> = vec![Vec::new(); n]; // per X column
        let mut kxx = Mat::<f64>::zeros(n, n);
        plane_strain::assemble(mesh, e_mod, nu, |i, j, v| {
            match (free_of[i], free_of[j], x_of[i], x_of[j]) {
                (fi, fj, _, _) if fi != FIXED && fj != FIXED => kff.push(Triplet::new(fi, fj, v)),
                (fi, _, _, xj) if fi != FIXED && xj != FIXED => kfx[xj].push((fi, v)),
                (_, _, xi, xj) if xi != FIXED && xj != FIXED => kxx[(xi, xj)] += v,
                _ => {}
            }
        });
        let llt = sparse_llt(nf, &kff)?;
        let ny = k * n;
        let y_free: Vec<usize> = (0..k)
            .flat_map(|c| (1..=n).map(move |r| (c, r)))
            .map(|(c, r)| free_of[2 * mesh.node(c, r) + 1])
            .collect();
        let mut C = Mat::<f64>::zeros(ny, ny);
        let mut Et = Mat::<f64>::zeros(n, ny);
        let mut A = kxx;
        let total = ny + n;
        let mut start = 0;
        while start < total {
            let cols = BLOCK.min(total - start);
            let mut rhs = Mat::<f64>::zeros(nf, cols);
            for j in 0..cols {
                let q = start + j;
                if q < ny {
                    rhs[(y_free[q], j)] = 1.0;
                } else {
                    for &(fi, v) in &kfx[q - ny] {
                        rhs[(fi, j)] -= v;
                    }
                }
            }
            llt.solve_in_place(rhs.as_mut());
            for j in 0..cols {
                let q = start + j;
                if q < ny {
                    for (a, &fa) in y_free.iter().enumerate() {
                        C[(a, q)] = rhs[(fa, j)];
                    }
                } else {
                    let i = q - ny;
                    for (a, &fa) in y_free.iter().enumerate() {
                        Et[(i, a)] = -rhs[(fa, j)];
                    }
                    // A[:, i] += K_Xf v: K_Xf = K_fXᵀ.
                    for (xi, col) in kfx.iter().enumerate() {
                        let s: f64 = col.iter().map(|&(fi, v)| v * rhs[(fi, j)]).sum();
                        A[(xi, i)] += s;
                    }
                }
            }
            start += cols;
        }
        // ---- antiplane.
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
        let lltz = sparse_llt(nz, &kzz)?;
        let z_free: Vec<usize> = (0..k)
            .flat_map(|c| (1..=n).map(move |r| (c, r)))
            .map(|(c, r)| zfree[mesh.node(c, r)])
            .collect();
        let mut Cz = Mat::<f64>::zeros(ny, ny);
        let mut start = 0;
        while start < ny {
            let cols = BLOCK.min(ny - start);
            let mut rhs = Mat::<f64>::zeros(nz, cols);
            for j in 0..cols {
                rhs[(z_free[start + j], j)] = 1.0;
            }
            lltz.solve_in_place(rhs.as_mut());
            for j in 0..cols {
                for (a, &fa) in z_free.iter().enumerate() {
                    Cz[(a, start + j)] = rhs[(fa, j)];
                }
            }
            start += cols;
        }
        Ok(Self { n, k, C, Et, A, Cz })
    }

    /// Y/Z index of strip column c, row r (1..=R).
    #[inline]
    fn yi(&self, c: usize, r: usize) -> usize {
        c * self.n + r - 1
    }

    /// The (index, weight) pairs of the strip constraint of column c.
    #[inline]
    fn taps(&self, c: usize, s: &StripConstraint) -> [(usize, f64); 2] {
        let lo = (self.yi(c, s.row), 1.0 - s.phi);
        if s.phi > 0.0 {
            [lo, (self.yi(c, s.row + 1), s.phi)]
        } else {
            [lo, (lo.0, 0.0)]
        }
    }

    /// M = P F Pᵀ for flexibility F (C or C_z).
    fn strip_matrix(&self, F: &Mat<f64>, s: &StripConstraint) -> [[f64; MAX_STRIP]; MAX_STRIP] {
        let mut M = [[0.0; MAX_STRIP]; MAX_STRIP];
        for (a, row) in M.iter_mut().enumerate().take(self.k) {
            let ta = self.taps(a, s);
            for (b, m) in row.iter_mut().enumerate().take(self.k) {
                let tb = self.taps(b, s);
                for &(ia, wa) in &ta {
                    for &(ib, wb) in &tb {
                        *m += wa * wb * F[(ia, ib)];
                    }
                }
            }
        }
        M
    }

    /// In-plane solve with every X DOF prescribed to `g` (gaps, m) and, if
    /// `strip` is given, the strip constraint. Writes the X reactions into `p`
    /// (N/m, +x on the material) and the strip forces into `lambda` (N/m, +y on
    /// the material). Allocation-free.
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
            let mut M = self.strip_matrix(&self.C, s);
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
        p[..n].fill(0.0);
        for (i, &gi) in g.iter().enumerate().skip(first_nonzero) {
            if gi != 0.0 {
                axpy(gi, self.A.col_as_slice(i), p);
            }
        }
        if let Some(s) = strip {
            for a in 0..self.k {
                for (q, w) in self.taps(a, s) {
                    if w != 0.0 {
                        axpy(w * lambda[a], self.Et.col_as_slice(q), p);
                    }
                }
            }
        }
        InPlane {
            energy: 0.5 * (dot(g, p) + energy_strip),
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
        for (q, w) in self.taps(a, s) {
            if w == 0.0 {
                continue;
            }
            u -= w * dot(
                &self.Et.col_as_slice(q)[first_nonzero..],
                &g[first_nonzero..],
            );
            for (b, &lb) in lambda.iter().enumerate().take(self.k) {
                if lb != 0.0 {
                    for (qb, wb) in self.taps(b, s) {
                        u += w * wb * lb * self.C[(q, qb)];
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
                    u += w * la * self.C[(q, qa)];
                }
            }
        }
        u
    }

    /// Antiplane solve with the strip constraint (u_t = `strip.value` on the
    /// strip at the tip). Returns (energy J/m, sum of strip forces N/m) of the
    /// half model. Allocation-free.
    pub fn solve_antiplane(&self, strip: &StripConstraint) -> (f64, f64) {
        let mut M = self.strip_matrix(&self.Cz, strip);
        let mut rhs = [0.0; MAX_STRIP];
        rhs[..self.k].fill(strip.value);
        mask_inactive(&mut M, &mut rhs, strip, self.k);
        small_solve(&mut M, &mut rhs, self.k);
        let f: f64 = rhs[..self.k].iter().sum();
        (0.5 * strip.value * f, f)
    }
}

/// Preallocated memory of [`CondensedLine::solve_released`]: the released
/// rows, a dense Cholesky factor of A_FF and its right-hand sides.
#[derive(Debug, Clone)]
pub(crate) struct ReleasedWorkspace {
    idx: Vec<usize>,
    /// The released rows whose A_FF is factorised in `l` (the factor is
    /// reused while the active set does not change, which is most calls).
    factored: Vec<usize>,
    l: Vec<f64>,
    z: Vec<f64>,
}

impl ReleasedWorkspace {
    /// Memory for a line of `n` rows (n² + n·(MAX_STRIP + 2) doubles).
    pub fn new(n: usize) -> Self {
        Self {
            idx: Vec::with_capacity(n),
            factored: Vec::with_capacity(n),
            l: vec![0.0; n * n],
            z: vec![0.0; n * (MAX_STRIP + 1)],
        }
    }
}

impl CondensedLine {
    /// In-plane solve with the X DOFs of the rows flagged in `released` free
    /// (loaded by `f_ext`, N/m, +x on the material; zero if `None`) and all
    /// others prescribed to `g`. On return `g` holds the solved displacements
    /// of the released rows, `p` the reactions (p = f_ext on released rows)
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
        let n = self.n;
        ws.idx.clear();
        ws.idx.extend((0..n).filter(|&i| released[i]));
        let m = ws.idx.len();
        if m == 0 {
            return self.solve(g, first_nonzero, strip, p, lambda);
        }
        let first = first_nonzero.min(ws.idx[0]);
        for &i in &ws.idx {
            g[i] = 0.0;
        }
        // r_F = f_F − A_FC g_C (A symmetric: row i is column i).
        let (rf, zb) = ws.z.split_at_mut(n);
        for (a, &i) in ws.idx.iter().enumerate() {
            let f = f_ext.map_or(0.0, |f| f[i]);
            rf[a] = f - dot(&self.A.col_as_slice(i)[first..], &g[first..]);
        }
        // Dense Cholesky of A_FF (lower, row-major m×m in ws.l), unless the
        // factor of this released set is already there.
        let l = &mut ws.l[..m * m];
        if ws.factored != ws.idx {
            for (a, &i) in ws.idx.iter().enumerate() {
                let col = self.A.col_as_slice(i);
                for (b, &j) in ws.idx.iter().enumerate().take(a + 1) {
                    l[a * m + b] = col[j];
                }
            }
            // Row-oriented (Cholesky–Crout): contiguous dot products.
            for a in 0..m {
                let (before, rest) = l.split_at_mut(a * m);
                let ra = &mut rest[..m];
                for b in 0..a {
                    let rb = &before[b * m..b * m + b + 1];
                    ra[b] = (ra[b] - dot(&ra[..b], &rb[..b])) / rb[b];
                }
                let d = ra[a] - dot(&ra[..a], &ra[..a]);
                ra[a] = d.max(f64::MIN_POSITIVE).sqrt();
            }
            ws.factored.clear();
            ws.factored.extend_from_slice(&ws.idx);
        }
        let chol_solve = |l: &[f64], x: &mut [f64]| {
            // L y = x (rows of L contiguous), then Lᵀ z = y (column sweep
            // along the rows of L).
            for a in 0..m {
                x[a] = (x[a] - dot(&l[a * m..a * m + a], &x[..a])) / l[a * m + a];
            }
            for a in (0..m).rev() {
                x[a] /= l[a * m + a];
                let xa = x[a];
                axpy(-xa, &l[a * m..a * m + a], &mut x[..a]);
            }
        };
        chol_solve(l, &mut rf[..m]);
        if let Some(s) = strip {
            // Z_B = A_FF⁻¹ B_F, column a in zb[a·n..].
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
                chol_solve(l, zc);
            }
            let mut S = self.strip_matrix(&self.C, s);
            let mut rhs = [0.0; MAX_STRIP];
            for a in 0..self.k {
                rhs[a] = s.value;
                for (q, w) in self.taps(a, s) {
                    if w != 0.0 {
                        let et = self.Et.col_as_slice(q);
                        // B_Cᵀ g_C (g_F is zero here) and B_Fᵀ A_FF⁻¹ r_F.
                        rhs[a] += w * dot(&et[first..], &g[first..]);
                        for (c, &i) in ws.idx.iter().enumerate() {
                            rhs[a] += w * et[i] * rf[c];
                        }
                        for b in 0..self.k {
                            let zc = &zb[b * n..b * n + m];
                            for (c, &i) in ws.idx.iter().enumerate() {
                                S[a][b] += w * et[i] * zc[c];
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
            for (c, &i) in ws.idx.iter().enumerate() {
                g[i] = rf[c];
            }
        }
        // The full displacement vector satisfies the strip equations, so the
        // plain solve recovers the same λ, the reactions and the energy; the
        // external forces' work is part of ½ g·p (p_F = f_F).
        self.solve(g, first, strip, p, lambda)
    }
}

/// Dot product with four partial sums (lets the compiler vectorise).
#[inline]
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

#[inline]
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
