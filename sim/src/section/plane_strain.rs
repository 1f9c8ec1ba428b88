//! Plane-strain linear elasticity on Q4 elements (the in-plane part of
//! generalised plane strain, seed 000 §III.C and its ref. [1]).
//!
//! Element stiffness by selective reduced integration: the deviatoric (μ) part
//! with 2×2 Gauss points, the volumetric (λ) part with one point, which keeps
//! bilinear quads free of volumetric locking at the Poisson ratios of food
//! (0.35–0.45) and is stable (no hourglass modes) for Q4.

#![allow(non_snake_case)]

use super::mesh::SectionMesh;

/// Gauss points of the 2×2 rule on [−1, 1]².
const GAUSS: f64 = 0.577_350_269_189_625_8;

/// Shape-function gradients in x, y at (ξ, η) and the Jacobian determinant.
pub(crate) fn q4_gradients(p: &[[f64; 2]; 4], xi: f64, eta: f64) -> ([[f64; 2]; 4], f64) {
    let dn = [
        [-(1.0 - eta) / 4.0, -(1.0 - xi) / 4.0],
        [(1.0 - eta) / 4.0, -(1.0 + xi) / 4.0],
        [(1.0 + eta) / 4.0, (1.0 + xi) / 4.0],
        [-(1.0 + eta) / 4.0, (1.0 - xi) / 4.0],
    ];
    let mut j = [[0.0; 2]; 2];
    for a in 0..4 {
        for (k, jk) in j.iter_mut().enumerate() {
            jk[0] += dn[a][k] * p[a][0];
            jk[1] += dn[a][k] * p[a][1];
        }
    }
    // j[k][l] = d x_l / d ξ_k
    let det = j[0][0] * j[1][1] - j[0][1] * j[1][0];
    let inv = [
        [j[1][1] / det, -j[0][1] / det],
        [-j[1][0] / det, j[0][0] / det],
    ];
    let mut g = [[0.0; 2]; 4];
    for a in 0..4 {
        // d N / d x_l = Σ_k (J^{-1})_{l k} dN/dξ_k
        g[a][0] = inv[0][0] * dn[a][0] + inv[0][1] * dn[a][1];
        g[a][1] = inv[1][0] * dn[a][0] + inv[1][1] * dn[a][1];
    }
    (g, det)
}

/// Lamé constants (λ, μ) from E (Pa) and ν.
pub(crate) fn lame(e: f64, nu: f64) -> (f64, f64) {
    (
        e * nu / ((1.0 + nu) * (1.0 - 2.0 * nu)),
        e / (2.0 * (1.0 + nu)),
    )
}

/// 8×8 plane-strain stiffness of one Q4 element (DOFs x0, y0, x1, y1, …), per unit thickness.
pub(crate) fn element_stiffness(p: &[[f64; 2]; 4], lambda: f64, mu: f64) -> [[f64; 8]; 8] {
    let mut K = [[0.0; 8]; 8];
    for (xi, eta) in [
        (-GAUSS, -GAUSS),
        (GAUSS, -GAUSS),
        (GAUSS, GAUSS),
        (-GAUSS, GAUSS),
    ] {
        let (g, det) = q4_gradients(p, xi, eta);
        for a in 0..4 {
            for b in 0..4 {
                let (ax, ay, bx, by) = (g[a][0], g[a][1], g[b][0], g[b][1]);
                // μ (2 ε:ε) part: D_μ = μ diag(2, 2, 1) on (εxx, εyy, γxy).
                K[2 * a][2 * b] += mu * (2.0 * ax * bx + ay * by) * det;
                K[2 * a][2 * b + 1] += mu * (ay * bx) * det;
                K[2 * a + 1][2 * b] += mu * (ax * by) * det;
                K[2 * a + 1][2 * b + 1] += mu * (2.0 * ay * by + ax * bx) * det;
            }
        }
    }
    let (g, det) = q4_gradients(p, 0.0, 0.0);
    let w = 4.0 * det;
    for a in 0..4 {
        for b in 0..4 {
            let ga = [g[a][0], g[a][1]];
            let gb = [g[b][0], g[b][1]];
            for k in 0..2 {
                for l in 0..2 {
                    K[2 * a + k][2 * b + l] += lambda * ga[k] * gb[l] * w;
                }
            }
        }
    }
    K
}

/// Stress (σxx, σyy, σxy) at the element centre from nodal displacements, Pa.
#[cfg(test)]
pub(crate) fn centre_stress(p: &[[f64; 2]; 4], u: &[f64; 8], lambda: f64, mu: f64) -> [f64; 3] {
    let (g, _) = q4_gradients(p, 0.0, 0.0);
    let (mut exx, mut eyy, mut gxy) = (0.0, 0.0, 0.0);
    for a in 0..4 {
        exx += g[a][0] * u[2 * a];
        eyy += g[a][1] * u[2 * a + 1];
        gxy += g[a][1] * u[2 * a] + g[a][0] * u[2 * a + 1];
    }
    let tr = exx + eyy;
    [
        lambda * tr + 2.0 * mu * exx,
        lambda * tr + 2.0 * mu * eyy,
        mu * gxy,
    ]
}

/// Element corner coordinates.
pub(crate) fn corners(mesh: &SectionMesh, e: &[usize; 4]) -> [[f64; 2]; 4] {
    [
        mesh.nodes[e[0]],
        mesh.nodes[e[1]],
        mesh.nodes[e[2]],
        mesh.nodes[e[3]],
    ]
}

/// Calls `add(i, j, k_ij)` for every entry of the global in-plane stiffness
/// (DOF 2·node + component), per unit thickness: element by element, row a
/// and column b of each element matrix (the reference of the section's
/// checks; the build maps the DOFs with [`assemble_mapped`]).
#[cfg(test)]
pub(crate) fn assemble(
    mesh: &SectionMesh,
    e_mod: f64,
    nu: f64,
    add: impl FnMut(usize, usize, f64),
) {
    assemble_mapped(mesh, e_mod, nu, Some, add);
}

/// [`assemble`] onto the positions `map(dof)` of the DOFs it keeps: calls
/// `add(map(i), map(j), k_ij)` for the entries whose DOFs both map to a
/// position, in the same order as [`assemble`] (so sums over the calls are
/// the same to the bit); each element's DOFs are mapped once.
pub(crate) fn assemble_mapped(
    mesh: &SectionMesh,
    e_mod: f64,
    nu: f64,
    map: impl Fn(usize) -> Option<usize>,
    mut add: impl FnMut(usize, usize, f64),
) {
    let (lambda, mu) = lame(e_mod, nu);
    for e in &mesh.elements {
        let K = element_stiffness(&corners(mesh, e), lambda, mu);
        let at: [Option<usize>; 8] = std::array::from_fn(|a| map(2 * e[a / 2] + a % 2));
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

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn element_has_three_rigid_modes_and_reproduces_uniform_strain() {
        let p = [[0.0, 0.0], [2.0, 0.1], [2.2, 1.0], [-0.1, 1.2]];
        let (l, m) = lame(1.0e6, 0.4);
        let K = element_stiffness(&p, l, m);
        let modes: [[f64; 8]; 3] = [
            [1.0, 0.0, 1.0, 0.0, 1.0, 0.0, 1.0, 0.0],
            [0.0, 1.0, 0.0, 1.0, 0.0, 1.0, 0.0, 1.0],
            [
                -p[0][1], p[0][0], -p[1][1], p[1][0], -p[2][1], p[2][0], -p[3][1], p[3][0],
            ],
        ];
        for u in modes {
            for row in K {
                let f: f64 = row.iter().zip(u).map(|(k, u)| k * u).sum();
                assert!(f.abs() < 1e-6, "rigid mode produces force {f}");
            }
        }
        // Uniform εyy = 1e-3: σyy = (λ+2μ)·1e-3 at the centre.
        let u: [f64; 8] =
            std::array::from_fn(|i| if i % 2 == 1 { 1e-3 * p[i / 2][1] } else { 0.0 });
        let s = centre_stress(&p, &u, l, m);
        assert!((s[1] - (l + 2.0 * m) * 1e-3).abs() < 1e-9 * s[1].abs());
        assert!((s[0] - l * 1e-3).abs() < 1e-9 * s[1].abs());
    }
}
