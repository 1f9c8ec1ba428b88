//! Line load on an elastic half-space: the crack nucleation argument of seed 001.
//!
//! Cylindrical coordinates (r, φ, z) with the z axis on the surface along the
//! loaded line (the wire or edge), φ = 0 pointing into the body normal to the
//! surface and φ = ±π/2 on the surface. The line carries a force per unit
//! length with a normal part `f_n` and a part `f_t` along z. Tensors are indexed
//! (r, φ, z) = (0, 1, 2).

use std::f64::consts::PI;

use nalgebra::Matrix3;

/// Stress tensor of seed 001 eq. 1 with the components of eqs. 2–3:
/// σ_rr = 2σ_zz = −2f_n cos φ/(πr), σ_rz = σ_zr = f_t/(πr), all others zero.
/// Compression is negative (the seed's sign in this paper).
pub fn line_load_stress(r: f64, phi: f64, f_n: f64, f_t: f64) -> Matrix3<f64> {
    let srr = -2.0 * f_n * phi.cos() / (PI * r);
    let szz = 0.5 * srr;
    let srz = f_t / (PI * r);
    Matrix3::new(srr, 0.0, srz, 0.0, 0.0, 0.0, srz, 0.0, szz)
}

/// Largest principal stress of the (r, z) block of eq. 1 (seed 001 eq. 4):
/// σ₁ = −3f_n cos φ/(2πr) + √((f_n cos φ/(2πr))² + (f_t/(πr))²).
///
/// For pure normal loading (f_t = 0) it is ≤ 0 everywhere in the body: the
/// material under a pressing edge is in compression.
pub fn largest_principal_stress(r: f64, phi: f64, f_n: f64, f_t: f64) -> f64 {
    let n = f_n * phi.cos() / (2.0 * PI * r);
    let t = f_t / (PI * r);
    -3.0 * n + (n * n + t * t).sqrt()
}

/// The largest tensile stress at distance `r` from the line, reached on the
/// surface (φ = ±π/2): σ₁ = |f_t|/(πr) (seed 001, after eq. 4).
pub fn surface_tensile_maximum(r: f64, f_t: f64) -> f64 {
    f_t.abs() / (PI * r)
}

#[cfg(test)]
mod tests {
    use super::*;
    use nalgebra::Matrix2;
    use proptest::prelude::*;

    proptest! {
        // Eq. 4 equals the larger eigenvalue of the (r, z) block of eq. 1.
        #[test]
        fn eq4_is_the_larger_eigenvalue_of_the_block(
            r in 1e-4f64..1.0, phi in -1.57f64..1.57, f_n in 0.0f64..1e3, f_t in -1e3f64..1e3
        ) {
            let s = line_load_stress(r, phi, f_n, f_t);
            let block = Matrix2::new(s[(0, 0)], s[(0, 2)], s[(2, 0)], s[(2, 2)]);
            let eig = block.symmetric_eigenvalues();
            let larger = eig[0].max(eig[1]);
            let eq4 = largest_principal_stress(r, phi, f_n, f_t);
            prop_assert!((larger - eq4).abs() <= 1e-10 * block.abs().max().max(1e-300));
        }

        #[test]
        fn pure_pressing_is_compressive_everywhere(
            r in 1e-4f64..1.0, phi in -1.5f64..1.5, f_n in 0.0f64..1e3
        ) {
            prop_assert!(largest_principal_stress(r, phi, f_n, 0.0) <= 0.0);
        }
    }

    #[test]
    fn surface_maximum_is_eq4_on_the_surface() {
        let (r, f_n, f_t) = (0.002, 40.0, 7.0);
        let on_surface = largest_principal_stress(r, std::f64::consts::FRAC_PI_2, f_n, f_t);
        assert!((on_surface - surface_tensile_maximum(r, f_t)).abs() < 1e-9 * on_surface);
        // And nowhere inside is it larger.
        for k in 0..=100 {
            let phi = -std::f64::consts::FRAC_PI_2 + std::f64::consts::PI * k as f64 / 100.0;
            assert!(largest_principal_stress(r, phi, f_n, f_t) <= on_surface * (1.0 + 1e-12));
        }
    }
}
