//! Compressible neo-Hookean material of seed 001:
//! W(F) = μ/2 (tr(FFᵀ) J^(−2/3) − 3) + K/2 (J − 1)², J = det F.
//!
//! The energy is split into an isochoric part (the μ term) and a volumetric
//! part (the K term) because the element integrates them with different rules
//! (see `element`). Tensors are 3×3 with row-major indices; a fourth-order
//! tangent `A[3i+j][3k+l] = ∂²W/∂F_ij ∂F_kl` is a 9×9 array.

#![allow(clippy::needless_range_loop)]

use nalgebra::Matrix3;

/// Material constants of the compressible neo-Hookean solid.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct NeoHookean {
    /// Shear modulus μ, Pa.
    pub shear_modulus: f64,
    /// Bulk modulus K, Pa (seed 001: K = 30μ).
    pub bulk_modulus: f64,
}

/// Fourth-order tangent ∂²W/∂F∂F, flattened as `[3i+j][3k+l]`, Pa.
pub type Tangent = [[f64; 9]; 9];

impl NeoHookean {
    /// The seed's gel: bulk modulus 30 × shear modulus `mu` (Pa).
    pub fn seed_gel(mu: f64) -> Self {
        Self {
            shear_modulus: mu,
            bulk_modulus: 30.0 * mu,
        }
    }

    /// Young's modulus of the linearised material, E = 9Kμ/(3K + μ), Pa.
    pub fn youngs_modulus(&self) -> f64 {
        let (mu, k) = (self.shear_modulus, self.bulk_modulus);
        9.0 * k * mu / (3.0 * k + mu)
    }

    /// Poisson ratio of the linearised material, ν = (3K − 2μ)/(2(3K + μ))
    /// (0.4835 for K = 30μ).
    pub fn poisson_ratio(&self) -> f64 {
        let (mu, k) = (self.shear_modulus, self.bulk_modulus);
        (3.0 * k - 2.0 * mu) / (2.0 * (3.0 * k + mu))
    }

    /// Isochoric energy density μ/2 (I₁ J^(−2/3) − 3), J/m³; +∞ for J ≤ 0.
    pub fn isochoric_energy(&self, f: &Matrix3<f64>) -> f64 {
        let j = f.determinant();
        if j <= 0.0 {
            return f64::INFINITY;
        }
        0.5 * self.shear_modulus * (f.norm_squared() * j.powf(-2.0 / 3.0) - 3.0)
    }

    /// Volumetric energy density K/2 (J − 1)², J/m³; +∞ for J ≤ 0.
    pub fn volumetric_energy(&self, f: &Matrix3<f64>) -> f64 {
        let j = f.determinant();
        if j <= 0.0 {
            return f64::INFINITY;
        }
        0.5 * self.bulk_modulus * (j - 1.0) * (j - 1.0)
    }

    /// Isochoric first Piola–Kirchhoff stress and tangent:
    /// P = μ J^(−2/3) (F − I₁/3 F⁻ᵀ).
    pub fn isochoric_stress_tangent(&self, f: &Matrix3<f64>) -> (Matrix3<f64>, Tangent) {
        let j = f.determinant();
        let h = f.try_inverse().unwrap_or_else(Matrix3::zeros).transpose();
        let i1 = f.norm_squared();
        let c = self.shear_modulus * j.powf(-2.0 / 3.0);
        let p = c * (f - h * (i1 / 3.0));
        let mut a = [[0.0; 9]; 9];
        for i in 0..3 {
            for jj in 0..3 {
                for k in 0..3 {
                    for l in 0..3 {
                        // d/dF_kl of J^(-2/3) (F_ij − I₁/3 H_ij), with
                        // dJ^(-2/3)/dF_kl = −2/3 J^(-2/3) H_kl and
                        // dH_ij/dF_kl = −H_il H_kj.
                        let delta = if i == k && jj == l { 1.0 } else { 0.0 };
                        a[3 * i + jj][3 * k + l] = c
                            * (-2.0 / 3.0 * h[(k, l)] * (f[(i, jj)] - i1 / 3.0 * h[(i, jj)])
                                + delta
                                - 2.0 / 3.0 * f[(k, l)] * h[(i, jj)]
                                + i1 / 3.0 * h[(i, l)] * h[(k, jj)]);
                    }
                }
            }
        }
        (p, a)
    }

    /// Volumetric first Piola–Kirchhoff stress and tangent:
    /// P = K (J − 1) J F⁻ᵀ.
    pub fn volumetric_stress_tangent(&self, f: &Matrix3<f64>) -> (Matrix3<f64>, Tangent) {
        let j = f.determinant();
        let h = f.try_inverse().unwrap_or_else(Matrix3::zeros).transpose();
        let kk = self.bulk_modulus;
        let p = h * (kk * (j - 1.0) * j);
        let mut a = [[0.0; 9]; 9];
        for i in 0..3 {
            for jj in 0..3 {
                for k in 0..3 {
                    for l in 0..3 {
                        a[3 * i + jj][3 * k + l] = kk * (2.0 * j * j - j) * h[(i, jj)] * h[(k, l)]
                            - kk * (j * j - j) * h[(i, l)] * h[(k, jj)];
                    }
                }
            }
        }
        (p, a)
    }

    /// Isochoric Cauchy stress μ J^(−5/3) (FFᵀ − I₁/3 I), Pa.
    pub fn isochoric_cauchy(&self, f: &Matrix3<f64>) -> Matrix3<f64> {
        let j = f.determinant();
        let b = f * f.transpose();
        (b - Matrix3::identity() * (b.trace() / 3.0)) * (self.shear_modulus * j.powf(-5.0 / 3.0))
    }

    /// Volumetric Cauchy stress K (J − 1) I (a pressure), Pa, for dilatation `j`.
    pub fn volumetric_cauchy(&self, j: f64) -> Matrix3<f64> {
        Matrix3::identity() * (self.bulk_modulus * (j - 1.0))
    }

    /// Cauchy stress σ = J⁻¹ (∂W/∂F) Fᵀ of the whole energy at one F, Pa.
    pub fn cauchy(&self, f: &Matrix3<f64>) -> Matrix3<f64> {
        self.isochoric_cauchy(f) + self.volumetric_cauchy(f.determinant())
    }
}

/// Largest eigenvalue of a symmetric 3×3 tensor (the largest principal stress σ₁).
pub fn largest_principal(s: &Matrix3<f64>) -> f64 {
    let sym = (s + s.transpose()) * 0.5;
    sym.symmetric_eigenvalues().max()
}

#[cfg(test)]
mod tests {
    use super::*;

    fn gel() -> NeoHookean {
        NeoHookean::seed_gel(35e3)
    }

    fn sample_f() -> Matrix3<f64> {
        Matrix3::new(1.2, 0.3, 0.0, -0.1, 0.9, 0.0, 0.25, -0.4, 1.0)
    }

    fn total_energy(m: &NeoHookean, f: &Matrix3<f64>) -> f64 {
        m.isochoric_energy(f) + m.volumetric_energy(f)
    }

    /// P and A are the derivatives of W: central differences with step 1e-6
    /// have truncation error ~1e-12·|W'''| and round-off ~1e-16·W/1e-6, so
    /// agreement to 1e-6 relative is the right bar.
    #[test]
    fn stress_and_tangent_are_derivatives_of_the_energy() {
        let m = gel();
        let f = sample_f();
        let (pi, ai) = m.isochoric_stress_tangent(&f);
        let (pv, av) = m.volumetric_stress_tangent(&f);
        let eps = 1e-6;
        let scale = m.bulk_modulus;
        for k in 0..3 {
            for l in 0..3 {
                let mut fp = f;
                fp[(k, l)] += eps;
                let mut fm = f;
                fm[(k, l)] -= eps;
                let dw = (total_energy(&m, &fp) - total_energy(&m, &fm)) / (2.0 * eps);
                assert!((dw - pi[(k, l)] - pv[(k, l)]).abs() < 1e-6 * scale);
                let (pip, _) = m.isochoric_stress_tangent(&fp);
                let (pim, _) = m.isochoric_stress_tangent(&fm);
                let (pvp, _) = m.volumetric_stress_tangent(&fp);
                let (pvm, _) = m.volumetric_stress_tangent(&fm);
                for i in 0..3 {
                    for j in 0..3 {
                        let fd_i = (pip[(i, j)] - pim[(i, j)]) / (2.0 * eps);
                        let fd_v = (pvp[(i, j)] - pvm[(i, j)]) / (2.0 * eps);
                        assert!((fd_i - ai[3 * i + j][3 * k + l]).abs() < 1e-6 * scale);
                        assert!((fd_v - av[3 * i + j][3 * k + l]).abs() < 1e-6 * scale);
                    }
                }
            }
        }
    }

    /// σ = J⁻¹ P Fᵀ with P from the two parts.
    #[test]
    fn cauchy_is_the_pushed_forward_piola_stress() {
        let m = gel();
        let f = sample_f();
        let p = m.isochoric_stress_tangent(&f).0 + m.volumetric_stress_tangent(&f).0;
        let s = p * f.transpose() / f.determinant();
        assert!((s - m.cauchy(&f)).abs().max() < 1e-9 * m.bulk_modulus);
    }

    /// Linearised constants of K = 30μ: ν = 88/182, E = 2μ(1 + ν).
    #[test]
    fn linearised_constants() {
        let m = gel();
        assert!((m.poisson_ratio() - 88.0 / 182.0).abs() < 1e-15);
        let e = 2.0 * m.shear_modulus * (1.0 + m.poisson_ratio());
        assert!((m.youngs_modulus() - e).abs() < 1e-9 * e);
    }
}
