//! Assembly of the slab's total energy, its gradient and its sparse Hessian
//! over the free degrees of freedom, and the sparse Cholesky factorisation of
//! that Hessian (faer).
//!
//! Degrees of freedom: 3 per node (u_x, u_y, u_z), DOF 3·node + component.
//! Prescribed DOFs keep the values they hold in the displacement vector.
//! The Hessian's sparsity pattern (elements plus the 3×3 blocks of the surface
//! nodes that may touch the wire) is fixed, so the symbolic factorisation is
//! done once at construction.
//!
//! # Memory allocation
//! [`System::new`] allocates the pattern (~78 entries per element), the value
//! array and the symbolic factor; each factorisation allocates its numeric
//! factor (faer's `Llt`).

#![allow(clippy::needless_range_loop)]

use faer::sparse::linalg::solvers::{Llt, SymbolicLlt};
use faer::sparse::{Argsort, Pair, SparseColMat, SymbolicSparseColMat};

use super::element::{CENTRE, NodalDisplacements, QuadGeometry};
use super::error::FiniteStrainError;
use super::mesh::SlabMesh;
use super::neo_hookean::NeoHookean;

/// Energy, gradient and Hessian of a potential acting on one node.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub(crate) struct NodeTerm {
    /// Energy, J/m.
    pub energy: f64,
    /// Gradient with respect to (u_x, u_y, u_z), N/m.
    pub gradient: [f64; 3],
    /// Hessian, N/m².
    pub hessian: [[f64; 3]; 3],
}

/// A potential acting node by node on a fixed set of surface nodes (the wire's
/// contact).
pub(crate) trait SurfacePotential {
    /// The potential of the node in slot `slot` of [`System::surface_nodes`],
    /// at reference position `reference` (m) and displacement `u` (m).
    fn term(&self, slot: usize, reference: [f64; 2], u: [f64; 3]) -> NodeTerm;
}

/// No surface potential (tests of the bulk alone).
pub(crate) struct NoSurface;

impl SurfacePotential for NoSurface {
    fn term(&self, _slot: usize, _reference: [f64; 2], _u: [f64; 3]) -> NodeTerm {
        NodeTerm::default()
    }
}

/// The assembled energy of a mesh with prescribed DOFs.
pub(crate) struct System {
    pub mesh: SlabMesh,
    pub material: NeoHookean,
    geometry: Vec<QuadGeometry>,
    /// Position among the free DOFs of each DOF, `None` if prescribed.
    free: Vec<Option<usize>>,
    n_free: usize,
    /// Nodes with a surface potential.
    surface_nodes: Vec<usize>,
    /// Slot in the value array of each element's lower-triangle entry
    /// `[3a+i][3b+k]` (row ≥ column among free DOFs), `usize::MAX` if not kept.
    element_slots: Vec<[usize; 144]>,
    surface_slots: Vec<[usize; 9]>,
    diagonal_slots: Vec<usize>,
    symbolic: SymbolicSparseColMat<usize>,
    argsort: Argsort<usize>,
    llt_symbolic: SymbolicLlt<usize>,
    /// Hessian values in pattern order, N/m².
    pub values: Vec<f64>,
}

/// What one evaluation returns besides the Hessian values.
#[derive(Debug, Clone, Copy)]
pub(crate) struct Evaluation {
    /// Total energy, J/m.
    pub energy: f64,
}

impl System {
    /// Builds the system; `prescribed[d]` marks DOF d fixed.
    pub fn new(
        mesh: SlabMesh,
        material: NeoHookean,
        prescribed: &[bool],
        surface_nodes: Vec<usize>,
    ) -> Result<Self, FiniteStrainError> {
        let mut geometry = Vec::with_capacity(mesh.elements.len());
        for e in 0..mesh.elements.len() {
            geometry.push(
                QuadGeometry::new(&mesh.corners(e)).ok_or(FiniteStrainError::Mesh(
                    "an element is inverted or degenerate",
                ))?,
            );
        }
        let mut free = vec![None; prescribed.len()];
        let mut n_free = 0;
        for (d, &p) in prescribed.iter().enumerate() {
            if !p {
                free[d] = Some(n_free);
                n_free += 1;
            }
        }
        let mut pairs: Vec<Pair<usize, usize>> = Vec::new();
        let mut push = |r: Option<usize>, c: Option<usize>| match (r, c) {
            (Some(r), Some(c)) if r >= c => {
                pairs.push(Pair { row: r, col: c });
                pairs.len() - 1
            }
            _ => usize::MAX,
        };
        let mut element_slots = Vec::with_capacity(mesh.elements.len());
        for el in &mesh.elements {
            let dofs: [Option<usize>; 12] = std::array::from_fn(|d| free[3 * el[d / 3] + d % 3]);
            let mut slots = [usize::MAX; 144];
            for r in 0..12 {
                for c in 0..12 {
                    slots[12 * r + c] = push(dofs[r], dofs[c]);
                }
            }
            element_slots.push(slots);
        }
        let mut surface_slots = Vec::with_capacity(surface_nodes.len());
        for &n in &surface_nodes {
            let dofs: [Option<usize>; 3] = std::array::from_fn(|i| free[3 * n + i]);
            surface_slots.push(std::array::from_fn(|k| push(dofs[k / 3], dofs[k % 3])));
        }
        let diagonal_slots: Vec<usize> = (0..n_free).map(|d| push(Some(d), Some(d))).collect();
        let (symbolic, argsort) =
            SymbolicSparseColMat::try_new_from_indices(n_free, n_free, &pairs)
                .map_err(|_| FiniteStrainError::Factorisation("sparse pattern"))?;
        let llt_symbolic = SymbolicLlt::try_new(symbolic.as_ref(), faer::Side::Lower)
            .map_err(|_| FiniteStrainError::Factorisation("symbolic Cholesky"))?;
        let values = vec![0.0; pairs.len()];
        Ok(Self {
            mesh,
            material,
            geometry,
            free,
            n_free,
            surface_nodes,
            element_slots,
            surface_slots,
            diagonal_slots,
            symbolic,
            argsort,
            llt_symbolic,
            values,
        })
    }

    /// Number of free DOFs.
    pub fn free_count(&self) -> usize {
        self.n_free
    }

    /// The nodes carrying the surface potential.
    pub fn surface_nodes(&self) -> &[usize] {
        &self.surface_nodes
    }

    /// Element geometry (reference gradients and weights) of element `e`.
    pub fn element(&self, e: usize) -> &QuadGeometry {
        &self.geometry[e]
    }

    /// Displacements of the nodes of element `e`, m.
    pub fn element_displacements(&self, e: usize, u: &[f64]) -> NodalDisplacements {
        self.mesh.elements[e].map(|n| [u[3 * n], u[3 * n + 1], u[3 * n + 2]])
    }

    fn node_displacement(u: &[f64], n: usize) -> [f64; 3] {
        [u[3 * n], u[3 * n + 1], u[3 * n + 2]]
    }

    /// Total energy (J/m) at displacement `u`; +∞ if an element inverts.
    pub fn energy(&self, u: &[f64], surface: &dyn SurfacePotential) -> f64 {
        let mut e = 0.0;
        for (k, g) in self.geometry.iter().enumerate() {
            e += g.energy(&self.material, &self.element_displacements(k, u));
        }
        for (slot, &n) in self.surface_nodes.iter().enumerate() {
            e += surface
                .term(slot, self.mesh.nodes[n], Self::node_displacement(u, n))
                .energy;
        }
        e
    }

    /// Energy, gradient over the free DOFs (`gradient`, N/m) and the Hessian
    /// values (into `self.values`); `None` if an element inverts.
    pub fn evaluate(
        &mut self,
        u: &[f64],
        surface: &dyn SurfacePotential,
        gradient: &mut [f64],
    ) -> Option<Evaluation> {
        gradient.fill(0.0);
        self.values.fill(0.0);
        let mut energy = 0.0;
        let (mut g, mut k) = ([0.0; 12], [[0.0; 12]; 12]);
        for e in 0..self.geometry.len() {
            let ue = self.element_displacements(e, u);
            energy += self.geometry[e].gradient_hessian(&self.material, &ue, &mut g, &mut k)?;
            let el = self.mesh.elements[e];
            for r in 0..12 {
                if let Some(fr) = self.free[3 * el[r / 3] + r % 3] {
                    gradient[fr] += g[r];
                }
                for c in 0..12 {
                    let s = self.element_slots[e][12 * r + c];
                    if s != usize::MAX {
                        self.values[s] += k[r][c];
                    }
                }
            }
        }
        for (slot, &n) in self.surface_nodes.iter().enumerate() {
            let t = surface.term(slot, self.mesh.nodes[n], Self::node_displacement(u, n));
            energy += t.energy;
            for i in 0..3 {
                if let Some(fr) = self.free[3 * n + i] {
                    gradient[fr] += t.gradient[i];
                }
                for j in 0..3 {
                    let s = self.surface_slots[slot][3 * i + j];
                    if s != usize::MAX {
                        self.values[s] += t.hessian[i][j];
                    }
                }
            }
        }
        Some(Evaluation { energy })
    }

    /// Size of the summands of the total energy, J/m: 3μ/2 (the isochoric
    /// energy density's terms μ/2·I₁J^(−2/3) at small strain) times the
    /// half slab's reference area. The energy's round-off is a small multiple
    /// of 10⁻¹⁶ of it, whatever the energy itself.
    pub fn energy_scale(&self) -> f64 {
        let area: f64 = self.geometry.iter().map(|g| g.weights[CENTRE]).sum();
        1.5 * self.material.shear_modulus * area
    }

    /// Largest diagonal entry of the assembled Hessian, N/m².
    pub fn largest_diagonal(&self) -> f64 {
        let mat = self.matrix(0.0);
        let mut m = 0.0f64;
        for j in 0..self.n_free {
            for (r, v) in mat.row_idx_of_col_raw(j).iter().zip(mat.val_of_col(j)) {
                if *r == j {
                    m = m.max(*v);
                }
            }
        }
        m
    }

    /// Sum of the elastic forces ∂Π/∂u over the DOFs `dofs` (N/m): what the
    /// slab exerts back on whatever holds those DOFs, with its sign flipped.
    pub fn internal_force(&self, u: &[f64], dofs: &[usize]) -> f64 {
        let (mut g, mut k) = ([0.0; 12], [[0.0; 12]; 12]);
        let mut sum = 0.0;
        for (e, el) in self.mesh.elements.iter().enumerate() {
            if !el
                .iter()
                .any(|n| (0..3).any(|i| dofs.contains(&(3 * n + i))))
            {
                continue;
            }
            let ue = self.element_displacements(e, u);
            if self.geometry[e]
                .gradient_hessian(&self.material, &ue, &mut g, &mut k)
                .is_none()
            {
                return f64::NAN;
            }
            for (r, gr) in g.iter().enumerate() {
                if dofs.contains(&(3 * el[r / 3] + r % 3)) {
                    sum += gr;
                }
            }
        }
        sum
    }

    /// The DOF of each free position.
    pub fn free_dofs(&self) -> Vec<usize> {
        let mut dofs = vec![0; self.n_free];
        for (d, f) in self.free.iter().enumerate() {
            if let Some(f) = f {
                dofs[*f] = d;
            }
        }
        dofs
    }

    fn matrix(&self, shift: f64) -> SparseColMat<usize, f64> {
        let mut vals = self.values.clone();
        if shift != 0.0 {
            for &s in &self.diagonal_slots {
                vals[s] += shift;
            }
        }
        SparseColMat::new_from_argsort(self.symbolic.clone(), &self.argsort, &vals)
            .expect("values match the pattern")
    }

    /// Sparse Cholesky factor of the Hessian plus `shift`·I (N/m²);
    /// `None` if that matrix is not positive definite.
    pub fn factor(&self, shift: f64) -> Option<Llt<usize, f64>> {
        let mat = self.matrix(shift);
        Llt::try_new_with_symbolic(self.llt_symbolic.clone(), mat.as_ref(), faer::Side::Lower).ok()
    }
}
