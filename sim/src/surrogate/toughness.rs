//! The toughness ratio r(ξ,ν) of seed 000 eq. (6) with its first and second
//! derivatives in ξ, exact (no fit): the part of the surrogate that is law.

use crate::mechanics::slice_push::compressibility_factor;

/// r(ξ,ν) and its derivatives ∂r/∂ξ, ∂²r/∂ξ² (seed 000 eq. 6).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ToughnessRatio {
    /// r(ξ,ν) = R_c^s/R_c, dimensionless.
    pub value: f64,
    /// ∂r/∂ξ.
    pub slope: f64,
    /// ∂²r/∂ξ².
    pub curvature: f64,
}

impl ToughnessRatio {
    /// Evaluates eq. (6) and its derivatives at (ξ, ν), analytic.
    ///
    /// With q = ξ/(1−ν−2ν²), s = √(1+q²), f = 2/(1+s) and
    /// g = 1 + ξ²/(2(1+ν)), r = f·g and
    /// r'' = f''g + 2f'g' + fg'' with f' = −2s'/(1+s)², s' = q/(s·c),
    /// s'' = 1/(c²s³), f'' = 4s'²/(1+s)³ − 2s''/(1+s)², g' = ξ/(1+ν),
    /// g'' = 1/(1+ν).
    #[inline]
    pub fn at(xi: f64, nu: f64) -> Self {
        let c = compressibility_factor(nu);
        let q = xi / c;
        let s = (1.0 + q * q).sqrt();
        let f = 2.0 / (1.0 + s);
        let ds = q / (s * c);
        let dds = 1.0 / (c * c * s * s * s);
        let one_s = 1.0 + s;
        let df = -2.0 * ds / (one_s * one_s);
        let ddf = 4.0 * ds * ds / (one_s * one_s * one_s) - 2.0 * dds / (one_s * one_s);
        let g = 1.0 + xi * xi / (2.0 * (1.0 + nu));
        let dg = xi / (1.0 + nu);
        let ddg = 1.0 / (1.0 + nu);
        Self {
            value: f * g,
            slope: df * g + f * dg,
            curvature: ddf * g + 2.0 * df * dg + f * ddg,
        }
    }
}

/// The ξ in [0, ξ_hi] below which r(·,ν) is concave (r'' < 0), found by
/// bisection on r'' (r'' < 0 at ξ = 0 for food-like ν, then > 0): eq. (6)
/// falls from r = 1 with a concave shoulder before its convex trough, so any
/// work model with r·R_c as a term is not convex in ξ near pressing. Returns
/// 0 when r''(0) ≥ 0 and `xi_hi` if r'' < 0 on the whole interval.
pub fn concave_up_to(nu: f64, xi_hi: f64) -> f64 {
    if ToughnessRatio::at(0.0, nu).curvature >= 0.0 {
        return 0.0;
    }
    if ToughnessRatio::at(xi_hi, nu).curvature < 0.0 {
        return xi_hi;
    }
    let (mut a, mut b) = (0.0, xi_hi);
    for _ in 0..100 {
        let m = 0.5 * (a + b);
        if ToughnessRatio::at(m, nu).curvature < 0.0 {
            a = m;
        } else {
            b = m;
        }
    }
    0.5 * (a + b)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::mechanics::slice_push::{toughness_ratio, toughness_ratio_derivative};

    #[test]
    fn value_and_slope_match_the_mechanics_module() {
        for &nu in &[0.3, 0.35, 0.4, 0.45] {
            for &xi in &[0.0, 0.2, 0.75, 1.4, 2.4, 3.0] {
                let t = ToughnessRatio::at(xi, nu);
                assert!((t.value - toughness_ratio(xi, nu)).abs() < 1e-14);
                assert!((t.slope - toughness_ratio_derivative(xi, nu)).abs() < 1e-12);
            }
        }
    }

    #[test]
    fn curvature_matches_central_difference_of_the_slope() {
        for &nu in &[0.3, 0.35, 0.4, 0.45] {
            for &xi in &[0.0, 0.2, 0.75, 1.4, 2.4, 3.0] {
                let h = 1e-5;
                let fd = (toughness_ratio_derivative(xi + h, nu)
                    - toughness_ratio_derivative(xi - h, nu))
                    / (2.0 * h);
                let an = ToughnessRatio::at(xi, nu).curvature;
                assert!(
                    (fd - an).abs() < 1e-6 * (1.0 + an.abs()),
                    "nu {nu} xi {xi}: {fd} vs {an}"
                );
            }
        }
    }

    #[test]
    fn concave_shoulder_ends_before_the_minimum() {
        // ν = 0.4: r''(0) = 2(1/(2·1.4) − 1/(4·0.28²)) < 0; the minimum of r
        // is at ξ ≈ 1.365, where r is convex.
        let xi_c = concave_up_to(0.4, 3.0);
        assert!(xi_c > 0.0 && xi_c < 1.365, "{xi_c}");
        assert!(ToughnessRatio::at(0.5 * xi_c, 0.4).curvature < 0.0);
        assert!(ToughnessRatio::at(xi_c + 0.05, 0.4).curvature > 0.0);
        assert!(ToughnessRatio::at(1.365, 0.4).curvature > 0.0);
    }
}
