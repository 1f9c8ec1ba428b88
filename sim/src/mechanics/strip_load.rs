//! Stresses in a half-space under a strip load: the knife edge (seed 000 §III.A).
//!
//! Frame x'y'z' of seed 000 Fig. 2: the strip runs along x' (the knife edge), z'
//! points into the body through the point p, and θ₁, θ₂ are the angles between
//! z' and the lines from p to the strip's two borders in the y'z'-plane.
//! Tensors are indexed (x', y', z') = (0, 1, 2). Loads are per unit area and
//! positive when they press into the body, as in the seed.

use std::f64::consts::PI;

use nalgebra::Matrix3;

/// Stress at p due to a normal strip load `f_n` (seed 000 eq. 2, Boussinesq
/// integrated over the strip (its ref. 28)); σ_x'x' = ν(σ_y'y' + σ_z'z') (plane strain).
pub fn normal_strip_stress(theta1: f64, theta2: f64, f_n: f64, nu: f64) -> Matrix3<f64> {
    let dt = theta2 - theta1;
    let ds = 0.5 * ((2.0 * theta2).sin() - (2.0 * theta1).sin());
    let szz = (dt + ds) * f_n / PI;
    let syy = (dt - ds) * f_n / PI;
    let syz = (theta2.sin().powi(2) - theta1.sin().powi(2)) * f_n / PI;
    let sxx = nu * (syy + szz);
    Matrix3::new(sxx, 0.0, 0.0, 0.0, syy, syz, 0.0, syz, szz)
}

/// Stress at p due to a tangential strip load `f_t` along the edge (seed 000
/// eq. 3, Cerruti integrated over the strip).
///
/// `ln|cos θ₁| − ln|cos θ₂|` is evaluated as `ln(|cos θ₁|/|cos θ₂|)`, which is
/// exactly 0 for the symmetric limit θ₁ = −θ₂ = −π/2 just below the edge.
pub fn tangential_strip_stress(theta1: f64, theta2: f64, f_t: f64) -> Matrix3<f64> {
    let sxz = (theta2 - theta1) * f_t / PI;
    let sxy = (theta1.cos().abs() / theta2.cos().abs()).ln() * f_t / PI;
    Matrix3::new(0.0, sxy, sxz, sxy, 0.0, 0.0, sxz, 0.0, 0.0)
}

/// Stress just below the edge, θ₁ = −π/2, θ₂ = π/2: the sum of eqs. 2 and 3,
/// which the seed prints as σ_x'x' = 2νf_n, σ_y'y' = σ_z'z' = f_n, σ_z'x' = f_t.
pub fn stress_below_edge(f_n: f64, f_t: f64, nu: f64) -> Matrix3<f64> {
    normal_strip_stress(-PI / 2.0, PI / 2.0, f_n, nu)
        + tangential_strip_stress(-PI / 2.0, PI / 2.0, f_t)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn below_the_edge_reduces_to_the_seed_values() {
        let (f_n, f_t, nu) = (1234.0, 321.0, 0.37);
        let s = stress_below_edge(f_n, f_t, nu);
        let expected = Matrix3::new(2.0 * nu * f_n, 0.0, f_t, 0.0, f_n, 0.0, f_t, 0.0, f_n);
        // sin(π) is 1.2e-16 in f64, so entries agree to rounding.
        assert!((s - expected).abs().max() < 1e-12 * f_n, "{s}");
    }

    #[test]
    fn stress_is_symmetric_and_vanishes_far_away() {
        let s =
            normal_strip_stress(0.1, 0.1001, 1.0, 0.3) + tangential_strip_stress(0.1, 0.1001, 1.0);
        assert!((s - s.transpose()).abs().max() == 0.0);
        assert!(s.abs().max() < 1e-3);
    }

    #[test]
    fn narrow_strip_tends_to_flamant_line_load() {
        // A strip of width b at depth r directly below (θ₂ = −θ₁ = atan(b/2r))
        // carries a line force P = f_n·b; Flamant gives σ_z'z' = 2P/(πr) there.
        let (r, b, f_n) = (0.01_f64, 1e-6_f64, 1.0e6_f64);
        let th = (0.5 * b / r).atan();
        let s = normal_strip_stress(-th, th, f_n, 0.3);
        let flamant = 2.0 * f_n * b / (PI * r);
        assert!((s[(2, 2)] - flamant).abs() < 1e-6 * flamant);
        assert!(s[(1, 1)].abs() < 1e-6 * flamant);
    }
}
