//! Strain below the knife edge and its maximum principal value (seed 000 eqs. 4–5).

use nalgebra::Matrix3;

use super::slice_push::compressibility_factor;

/// Small strain from stress by Hooke's law, ε = ((1+ν)σ − ν tr(σ) I)/E.
pub fn hooke_strain(stress: &Matrix3<f64>, youngs_modulus: f64, nu: f64) -> Matrix3<f64> {
    let tr = stress.trace();
    (stress * (1.0 + nu) - Matrix3::identity() * (nu * tr)) / youngs_modulus
}

/// The strain tensor just below the edge as printed in seed 000 §III.A:
/// ε = (1/E)·[[0, 0, f_t(1+ν)], [0, f_n(1−ν−2ν²), 0], [f_t(1+ν), 0, f_n(1−ν−2ν²)]].
pub fn strain_below_edge(f_n: f64, f_t: f64, youngs_modulus: f64, nu: f64) -> Matrix3<f64> {
    let c = f_n * compressibility_factor(nu) / youngs_modulus;
    let a = f_t * (1.0 + nu) / youngs_modulus;
    Matrix3::new(0.0, 0.0, a, 0.0, c, 0.0, a, 0.0, c)
}

/// Maximum principal strain below the edge (seed 000 eq. 4):
/// ε_max = (f_n/2E)((1−ν−2ν²) + √((1−ν−2ν²)² + 4((f_t/f_n)(1+ν))²)).
///
/// Written without dividing by f_n so that f_n = 0 is defined.
pub fn max_principal_strain(f_n: f64, f_t: f64, youngs_modulus: f64, nu: f64) -> f64 {
    let c = f_n * compressibility_factor(nu);
    let a = 2.0 * f_t * (1.0 + nu);
    (c + (c * c + a * a).sqrt()) / (2.0 * youngs_modulus)
}

/// Maximum principal strain with the seed's force split f_t/f_n = ξ/(2(1+ν))
/// substituted (seed 000 eq. 5): ε_max = (f_n/2E)((1−ν−2ν²) + √((1−ν−2ν²)² + ξ²)).
pub fn max_principal_strain_slicing(f_n: f64, xi: f64, youngs_modulus: f64, nu: f64) -> f64 {
    let c = compressibility_factor(nu);
    f_n / (2.0 * youngs_modulus) * (c + (c * c + xi * xi).sqrt())
}

#[cfg(test)]
mod tests {
    use super::super::slice_push::force_ratio;
    use super::super::strip_load::stress_below_edge;
    use super::*;
    use nalgebra::SymmetricEigen;
    use proptest::prelude::*;

    #[test]
    fn hooke_of_the_seed_stresses_is_the_seed_strain() {
        let (f_n, f_t, e, nu) = (900.0, 250.0, 2.0e6, 0.4);
        let from_stress = hooke_strain(&stress_below_edge(f_n, f_t, nu), e, nu);
        let printed = strain_below_edge(f_n, f_t, e, nu);
        assert!((from_stress - printed).abs().max() < 1e-12 * printed.abs().max());
    }

    proptest! {
        // Eq. 4 is the largest eigenvalue of the strain tensor, for any loads
        // and material (relative tolerance: eigen-solver rounding).
        #[test]
        fn eq4_is_the_largest_eigenvalue(
            f_n in 0.0f64..1e4, f_t in -1e4f64..1e4, e in 1e3f64..1e8, nu in 0.01f64..0.49
        ) {
            let strain = strain_below_edge(f_n, f_t, e, nu);
            let eig = SymmetricEigen::new(strain).eigenvalues;
            let largest = eig.iter().cloned().fold(f64::NEG_INFINITY, f64::max);
            let eq4 = max_principal_strain(f_n, f_t, e, nu);
            let scale = strain.abs().max().max(1e-300);
            prop_assert!((largest - eq4).abs() <= 1e-12 * scale, "{} vs {}", largest, eq4);
        }

        // Eq. 5 is eq. 4 with f_t = f_n·ξ/(2(1+ν)).
        #[test]
        fn eq5_is_eq4_with_the_seed_force_split(
            f_n in 1.0f64..1e4, xi in 0.0f64..5.0, nu in 0.01f64..0.49
        ) {
            let e = 1e6;
            let a = max_principal_strain(f_n, f_n * force_ratio(xi, nu), e, nu);
            let b = max_principal_strain_slicing(f_n, xi, e, nu);
            prop_assert!((a - b).abs() <= 1e-13 * a.abs());
        }
    }
}
