//! Kinematics of one bilinear quadrilateral (Q4) of the slab's cross section,
//! with three displacement components per node (in-plane x, y and z along the
//! wire).
//!
//! Generalised plane strain: the fields do not vary along the wire (z), so the
//! deformation gradient is the full 3×3
//!
//! ```text
//!     ⎡1 + ∂u_x/∂X   ∂u_x/∂Y     0⎤
//! F = ⎢  ∂u_y/∂X   1 + ∂u_y/∂Y   0⎥ ,  J = det F (in-plane only),
//!     ⎣  ∂u_z/∂X     ∂u_z/∂Y     1⎦
//! ```
//!
//! and shear along the wire (the last row) enters the isochoric energy
//! through I₁ J^(−2/3), coupling it to the indentation. Total Lagrangian: all
//! gradients are taken in the reference configuration.
//!
//! Integration is selectively reduced: the isochoric energy with the 2×2
//! Gauss rule, the volumetric energy K/2 (J − 1)² with one point at the
//! centre. This is the nonlinear form of the selective rule of the section
//! FEM; it keeps the nearly incompressible gel (K = 30μ, ν = 0.48) free of
//! volumetric locking. Both are exact energies of the discrete field, so the
//! element gradient and stiffness are exact derivatives of one scalar, which
//! Newton's method with an energy line search needs.

#![allow(clippy::needless_range_loop)]

use nalgebra::Matrix3;

use super::neo_hookean::{NeoHookean, Tangent};

/// Gauss abscissa of the 2×2 rule, 1/√3.
const GAUSS: f64 = 0.577_350_269_189_625_8;

/// Parent coordinates of the four Gauss points and the centre (index 4).
const POINTS: [(f64, f64); 5] = [
    (-GAUSS, -GAUSS),
    (GAUSS, -GAUSS),
    (GAUSS, GAUSS),
    (-GAUSS, GAUSS),
    (0.0, 0.0),
];

/// Index of the centre point in [`QuadGeometry`].
pub(crate) const CENTRE: usize = 4;

/// Nodal displacements of one element, m: `[node][component]`, components (x, y, z).
pub(crate) type NodalDisplacements = [[f64; 3]; 4];

/// Reference geometry of one Q4: shape-function gradients and weights at the
/// four Gauss points and the centre.
#[derive(Debug, Clone, Copy)]
pub(crate) struct QuadGeometry {
    /// ∂N_a/∂X_J at each point, m⁻¹.
    pub grads: [[[f64; 2]; 4]; 5],
    /// Integration weight (Jacobian × rule weight) at each point, m²; the
    /// centre's is the element area (one-point rule).
    pub weights: [f64; 5],
}

impl QuadGeometry {
    /// Geometry of the quad with corners `p` (counter-clockwise, m); `None`
    /// if the element is inverted or degenerate at any point.
    pub fn new(p: &[[f64; 2]; 4]) -> Option<Self> {
        let mut grads = [[[0.0; 2]; 4]; 5];
        let mut weights = [0.0; 5];
        for (q, &(xi, eta)) in POINTS.iter().enumerate() {
            let dn = [
                [-(1.0 - eta) / 4.0, -(1.0 - xi) / 4.0],
                [(1.0 - eta) / 4.0, -(1.0 + xi) / 4.0],
                [(1.0 + eta) / 4.0, (1.0 + xi) / 4.0],
                [-(1.0 + eta) / 4.0, (1.0 - xi) / 4.0],
            ];
            // jac[k][l] = ∂X_l/∂ξ_k
            let mut jac = [[0.0; 2]; 2];
            for a in 0..4 {
                for k in 0..2 {
                    jac[k][0] += dn[a][k] * p[a][0];
                    jac[k][1] += dn[a][k] * p[a][1];
                }
            }
            let det = jac[0][0] * jac[1][1] - jac[0][1] * jac[1][0];
            if det.is_nan() || det <= 0.0 {
                return None;
            }
            let inv = [
                [jac[1][1] / det, -jac[0][1] / det],
                [-jac[1][0] / det, jac[0][0] / det],
            ];
            for a in 0..4 {
                grads[q][a][0] = inv[0][0] * dn[a][0] + inv[0][1] * dn[a][1];
                grads[q][a][1] = inv[1][0] * dn[a][0] + inv[1][1] * dn[a][1];
            }
            weights[q] = if q == CENTRE { 4.0 * det } else { det };
        }
        Some(Self { grads, weights })
    }

    /// Deformation gradient at point `q` for nodal displacements `u`.
    pub fn deformation_gradient(&self, q: usize, u: &NodalDisplacements) -> Matrix3<f64> {
        let mut f = Matrix3::identity();
        for (a, ua) in u.iter().enumerate() {
            for (i, &ui) in ua.iter().enumerate() {
                f[(i, 0)] += ui * self.grads[q][a][0];
                f[(i, 1)] += ui * self.grads[q][a][1];
            }
        }
        f
    }

    /// Strain energy of the element per unit length along the wire, J/m
    /// (+∞ if any point is inverted).
    pub fn energy(&self, material: &NeoHookean, u: &NodalDisplacements) -> f64 {
        let mut e = 0.0;
        for q in 0..4 {
            e += self.weights[q] * material.isochoric_energy(&self.deformation_gradient(q, u));
        }
        let fc = self.deformation_gradient(CENTRE, u);
        e + self.weights[CENTRE] * material.volumetric_energy(&fc)
    }

    /// Energy (J/m), gradient (N/m, DOF 3a + i) and stiffness (N/m², the
    /// exact Hessian) of the element; `None` if any point is inverted.
    pub fn gradient_hessian(
        &self,
        material: &NeoHookean,
        u: &NodalDisplacements,
        g: &mut [f64; 12],
        k: &mut [[f64; 12]; 12],
    ) -> Option<f64> {
        *g = [0.0; 12];
        *k = [[0.0; 12]; 12];
        let mut energy = 0.0;
        for q in 0..5 {
            let f = self.deformation_gradient(q, u);
            let det = f.determinant();
            if det.is_nan() || det <= 0.0 {
                return None;
            }
            let (p, a) = if q == CENTRE {
                energy += self.weights[q] * material.volumetric_energy(&f);
                material.volumetric_stress_tangent(&f)
            } else {
                energy += self.weights[q] * material.isochoric_energy(&f);
                material.isochoric_stress_tangent(&f)
            };
            self.add_point(q, &p, &a, g, k);
        }
        Some(energy)
    }

    fn add_point(
        &self,
        q: usize,
        p: &Matrix3<f64>,
        a: &Tangent,
        g: &mut [f64; 12],
        k: &mut [[f64; 12]; 12],
    ) {
        let w = self.weights[q];
        let gr = &self.grads[q];
        for na in 0..4 {
            for i in 0..3 {
                g[3 * na + i] += w * (p[(i, 0)] * gr[na][0] + p[(i, 1)] * gr[na][1]);
                for nb in 0..4 {
                    for kk in 0..3 {
                        let mut s = 0.0;
                        for jj in 0..2 {
                            for l in 0..2 {
                                s += a[3 * i + jj][3 * kk + l] * gr[na][jj] * gr[nb][l];
                            }
                        }
                        k[3 * na + i][3 * nb + kk] += w * s;
                    }
                }
            }
        }
    }

    /// Cauchy stress at point `q` (Pa): the isochoric part from F at `q`,
    /// the pressure K(J − 1) from the centre's J (the element's one
    /// volumetric point).
    pub fn cauchy(&self, material: &NeoHookean, q: usize, u: &NodalDisplacements) -> Matrix3<f64> {
        let f = self.deformation_gradient(q, u);
        let jc = self.deformation_gradient(CENTRE, u).determinant();
        material.isochoric_cauchy(&f) + material.volumetric_cauchy(jc)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn distorted() -> [[f64; 2]; 4] {
        [
            [0.0, 0.0],
            [2.0e-3, 0.1e-3],
            [2.2e-3, 1.0e-3],
            [-0.1e-3, 1.2e-3],
        ]
    }

    /// Nodal displacements of the homogeneous deformation F0: u = (F0 − I) X.
    fn homogeneous(p: &[[f64; 2]; 4], f0: &Matrix3<f64>) -> NodalDisplacements {
        std::array::from_fn(|a| {
            std::array::from_fn(|i| {
                (f0[(i, 0)] - if i == 0 { 1.0 } else { 0.0 }) * p[a][0]
                    + (f0[(i, 1)] - if i == 1 { 1.0 } else { 0.0 }) * p[a][1]
            })
        })
    }

    /// The element's stiffness is the derivative of its gradient, and its
    /// gradient the derivative of its energy (central differences with step
    /// 1e-9 m on a 2 mm element: relative error ~1e-7 from truncation and
    /// round-off; 1e-5 of the largest entry is a safe bar).
    #[test]
    fn gradient_and_stiffness_are_exact_derivatives() {
        let m = NeoHookean::seed_gel(35e3);
        let p = distorted();
        let geom = QuadGeometry::new(&p).unwrap();
        let f0 = Matrix3::new(1.1, 0.2, 0.0, -0.05, 0.85, 0.0, 0.3, -0.2, 1.0);
        let mut u = homogeneous(&p, &f0);
        u[2][1] += 0.1e-3; // not homogeneous
        u[3][2] -= 0.2e-3;
        let (mut g, mut k) = ([0.0; 12], [[0.0; 12]; 12]);
        geom.gradient_hessian(&m, &u, &mut g, &mut k).unwrap();
        let gmax = g.iter().fold(0.0f64, |a, b| a.max(b.abs()));
        let kmax = k.iter().flatten().fold(0.0f64, |a, b| a.max(b.abs()));
        let eps = 1e-9;
        for d in 0..12 {
            let (mut up, mut um) = (u, u);
            up[d / 3][d % 3] += eps;
            um[d / 3][d % 3] -= eps;
            let fd = (geom.energy(&m, &up) - geom.energy(&m, &um)) / (2.0 * eps);
            assert!(
                (fd - g[d]).abs() < 1e-5 * gmax,
                "gradient {d}: {fd} vs {}",
                g[d]
            );
            let (mut gp, mut gm, mut kk) = ([0.0; 12], [0.0; 12], [[0.0; 12]; 12]);
            geom.gradient_hessian(&m, &up, &mut gp, &mut kk).unwrap();
            geom.gradient_hessian(&m, &um, &mut gm, &mut kk).unwrap();
            for r in 0..12 {
                let fd = (gp[r] - gm[r]) / (2.0 * eps);
                assert!((fd - k[r][d]).abs() < 1e-5 * kmax, "K[{r}][{d}]");
            }
        }
        // Symmetric, as a Hessian must be (to round-off).
        for r in 0..12 {
            for c in 0..12 {
                assert!((k[r][c] - k[c][r]).abs() < 1e-12 * kmax);
            }
        }
    }

    /// Every Gauss point of a distorted element under the homogeneous F0
    /// reports the closed-form Cauchy stress (round-off only: 1e-9 of μ).
    fn assert_stress(f0: &Matrix3<f64>, expected: &Matrix3<f64>) {
        let m = NeoHookean::seed_gel(35e3);
        let p = distorted();
        let geom = QuadGeometry::new(&p).unwrap();
        let u = homogeneous(&p, f0);
        for q in 0..5 {
            let s = geom.cauchy(&m, q, &u);
            assert!(
                (s - expected).abs().max() < 1e-9 * m.shear_modulus,
                "point {q}: {s} vs {expected}"
            );
        }
    }

    /// Uniaxial strain F = diag(λ, 1, 1): J = λ, I₁ = λ² + 2,
    /// σ_xx = (2/3) μ λ^(−5/3) (λ² − 1) + K (λ − 1),
    /// σ_yy = σ_zz = −(1/3) μ λ^(−5/3) (λ² − 1) + K (λ − 1).
    #[test]
    fn uniaxial_stretch_gives_the_closed_form_stress() {
        let m = NeoHookean::seed_gel(35e3);
        let (mu, k) = (m.shear_modulus, m.bulk_modulus);
        for lambda in [0.6, 0.9, 1.3, 2.0] {
            let f0 = Matrix3::new(lambda, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 1.0);
            let a = mu * f64::powf(lambda, -5.0 / 3.0) * (lambda * lambda - 1.0);
            let p = k * (lambda - 1.0);
            let e = Matrix3::from_diagonal(&nalgebra::Vector3::new(
                2.0 / 3.0 * a + p,
                -a / 3.0 + p,
                -a / 3.0 + p,
            ));
            assert_stress(&f0, &e);
        }
    }

    /// Simple shear in the plane (F = I + γ e_x⊗e_y) and along the wire
    /// (F = I + γ e_z⊗e_x, the slicing mode): J = 1, σ_shear = μγ, normal
    /// stresses μγ²(2/3, −1/3, −1/3) with 2/3 on the sheared fibre's axis.
    #[test]
    fn simple_shear_gives_the_closed_form_stress() {
        let mu = NeoHookean::seed_gel(35e3).shear_modulus;
        for g in [0.1, 0.5, 1.5] {
            let mut f0 = Matrix3::identity();
            f0[(0, 1)] = g;
            let e = Matrix3::new(
                2.0 / 3.0 * mu * g * g,
                mu * g,
                0.0,
                mu * g,
                -mu * g * g / 3.0,
                0.0,
                0.0,
                0.0,
                -mu * g * g / 3.0,
            );
            assert_stress(&f0, &e);
            let mut f0 = Matrix3::identity();
            f0[(2, 0)] = g;
            let e = Matrix3::new(
                -mu * g * g / 3.0,
                0.0,
                mu * g,
                0.0,
                -mu * g * g / 3.0,
                0.0,
                mu * g,
                0.0,
                2.0 / 3.0 * mu * g * g,
            );
            assert_stress(&f0, &e);
        }
    }

    /// Objectivity: a rigid rotation in the plane (any angle, including
    /// beyond 90°) gives zero stress, zero energy and zero nodal forces; a
    /// rotation superposed on a stretch rotates the stress (σ' = QσQᵀ).
    #[test]
    fn rigid_rotation_gives_zero_stress_and_rotates_stress() {
        let m = NeoHookean::seed_gel(35e3);
        let p = distorted();
        let geom = QuadGeometry::new(&p).unwrap();
        for angle in [0.3f64, 1.2, 2.5] {
            let (c, s) = (angle.cos(), angle.sin());
            let q = Matrix3::new(c, -s, 0.0, s, c, 0.0, 0.0, 0.0, 1.0);
            let u = homogeneous(&p, &q);
            let (mut g, mut k) = ([0.0; 12], [[0.0; 12]; 12]);
            let e = geom.gradient_hessian(&m, &u, &mut g, &mut k).unwrap();
            // Round-off: |W| ≲ 10 ε μ per unit volume, over ~2.4e-6 m².
            assert!(e.abs() < 1e-15 * m.shear_modulus * 2.4e-6, "energy {e}");
            assert!(g.iter().all(|x| x.abs() < 1e-9), "forces {g:?}");
            for point in 0..5 {
                assert!(geom.cauchy(&m, point, &u).abs().max() < 1e-9 * m.shear_modulus);
            }
            let f0 = Matrix3::new(1.2, 0.1, 0.0, 0.0, 0.9, 0.0, 0.2, 0.0, 1.0);
            let s0 = geom.cauchy(&m, 0, &homogeneous(&p, &f0));
            let s1 = geom.cauchy(&m, 0, &homogeneous(&p, &(q * f0)));
            let rotated = q * s0 * q.transpose();
            assert!((s1 - rotated).abs().max() < 1e-9 * m.shear_modulus);
        }
    }
}
