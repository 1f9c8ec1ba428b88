//! Antiplane shear on Q4 elements: the tangential part of generalised plane
//! strain (seed 000 §III.C, assumption A1): ∇²u_t = 0 with shear modulus G,
//! the bottom fixed, the strip under the edge moved with the knife.

#![allow(non_snake_case)]

use super::mesh::SectionMesh;
use super::plane_strain::{corners, q4_gradients};

/// Gauss points of the 2×2 rule on [−1, 1]².
const GAUSS: f64 = 0.577_350_269_189_625_8;

/// 4×4 Laplace stiffness G ∫ ∇N·∇N of one Q4 element, per unit thickness.
pub(crate) fn element_stiffness(p: &[[f64; 2]; 4], g_mod: f64) -> [[f64; 4]; 4] {
    let mut K = [[0.0; 4]; 4];
    for (xi, eta) in [
        (-GAUSS, -GAUSS),
        (GAUSS, -GAUSS),
        (GAUSS, GAUSS),
        (-GAUSS, GAUSS),
    ] {
        let (g, det) = q4_gradients(p, xi, eta);
        for a in 0..4 {
            for b in 0..4 {
                K[a][b] += g_mod * (g[a][0] * g[b][0] + g[a][1] * g[b][1]) * det;
            }
        }
    }
    K
}

/// Calls `add(i, j, k_ij)` for every entry of the global antiplane stiffness (DOF = node).
pub(crate) fn assemble(mesh: &SectionMesh, g_mod: f64, mut add: impl FnMut(usize, usize, f64)) {
    for e in &mesh.elements {
        let K = element_stiffness(&corners(mesh, e), g_mod);
        for a in 0..4 {
            for b in 0..4 {
                add(e[a], e[b], K[a][b]);
            }
        }
    }
}
