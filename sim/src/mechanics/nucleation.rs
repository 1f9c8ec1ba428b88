//! Seed 001's scalings of the forces at which slicing a soft slab nucleates a cut.
//!
//! Symbols: shear modulus μ (Pa), indentation d (m), slab thickness along the
//! wire h (m), slab breadth B (m), wire radius R (m).

/// Normal force of a wire indenting a slab by `d` (seed 001, from its Fig. 3
/// simulations): F_n ≈ 5μdh / ln(B/R), N. The logarithm is the signature of the
/// 1/r decay of the two-dimensional line-load field.
pub fn indentation_normal_force(
    shear_modulus: f64,
    depth: f64,
    thickness: f64,
    breadth: f64,
    radius: f64,
) -> f64 {
    5.0 * shear_modulus * depth * thickness / (breadth / radius).ln()
}

/// Maximum tangential force before the cut nucleates (seed 001): F_t,max ≈ 2μRh, N.
pub fn max_tangential_force(shear_modulus: f64, radius: f64, thickness: f64) -> f64 {
    2.0 * shear_modulus * radius * thickness
}

/// Surface tensile stress that seed 001 takes for nucleation: σ* = 2μ, Pa.
pub fn nucleation_stress(shear_modulus: f64) -> f64 {
    2.0 * shear_modulus
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn agar_experiment_orders_of_magnitude() {
        // Seed 001: μ = 35 kPa, R = 150 µm, h = 5 mm, B ≈ 40 mm.
        let (mu, r, h, b) = (35e3, 150e-6, 5e-3, 40e-3);
        // F_t,max = 2·35e3·150e-6·5e-3 = 0.0525 N.
        assert!((max_tangential_force(mu, r, h) - 0.0525).abs() < 1e-12);
        // At d = 1 mm: 5·35e3·1e-3·5e-3/ln(266.67) = 0.1566 N.
        let f = indentation_normal_force(mu, 1e-3, h, b, r);
        assert!((f - 0.875 / (b / r).ln()).abs() < 1e-12);
        assert!((f - 0.15659).abs() < 1e-4);
        // The tangential force stays an order of magnitude below the normal
        // force at the indentations of seed 001 Fig. 1 (d of several mm).
        assert!(max_tangential_force(mu, r, h) < 0.1 * indentation_normal_force(mu, 4e-3, h, b, r));
        assert_eq!(nucleation_stress(mu), 70e3);
    }
}
