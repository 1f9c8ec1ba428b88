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

/// Calls `add(i, j, k_ij)` for every entry of the global antiplane stiffness
/// (DOF = node): element by element, row a and column b of each element
/// matrix (the reference of the section's checks; the build maps the DOFs
/// with [`assemble_mapped`]).
#[cfg(test)]
pub(crate) fn assemble(mesh: &SectionMesh, g_mod: f64, add: impl FnMut(usize, usize, f64)) {
    assemble_mapped(mesh, g_mod, Some, add);
}

/// [`assemble`] onto the positions `map(node)` of the DOFs it keeps: calls
/// `add(map(i), map(j), k_ij)` for the entries whose DOFs both map to a
/// position, in the same order as [`assemble`] (so sums over the calls are
/// the same to the bit); each element's DOFs are mapped once.
pub(crate) fn assemble_mapped(
    mesh: &SectionMesh,
    g_mod: f64,
    map: impl Fn(usize) -> Option<usize>,
    mut add: impl FnMut(usize, usize, f64),
) {
    for e in &mesh.elements {
        let K = element_stiffness(&corners(mesh, e), g_mod);
        let at: [Option<usize>; 4] = std::array::from_fn(|a| map(e[a]));
        for (a, row) in K.iter().enumerate() {
            let Some(pa) = at[a] else { continue };
            for (b, &k) in row.iter().enumerate() {
                if let Some(pb) = at[b] {
                    add(pa, pb, k);
                }
            }
        }
    }
}
