//! The slice-push ratio ξ and the toughness ratio r(ξ, ν) (seed 000 §III.B).

use serde::{Deserialize, Serialize};

/// Slice-push ratio ξ = dt/dn: tangential over normal knife displacement
/// (Atkins et al., seed 000 §III.B). For a straight horizontal edge moving at
/// angle α from −y, ξ = tan α. Dimensionless; the sign of the tangential
/// motion does not change the mechanics, so functions use |ξ|.
#[derive(Debug, Clone, Copy, PartialEq, PartialOrd, Serialize, Deserialize)]
#[serde(transparent)]
pub struct SlicePushRatio(pub f64);

impl SlicePushRatio {
    /// ξ = tan α for a velocity at angle `alpha` (rad) from the −y axis.
    pub fn from_angle(alpha: f64) -> Self {
        Self(alpha.tan())
    }

    /// The angle α = atan ξ, rad.
    pub fn angle(self) -> f64 {
        self.0.atan()
    }
}

/// `1 − ν − 2ν²` = (1+ν)(1−2ν), the factor of f_n in the strain below the edge.
#[inline]
pub fn compressibility_factor(nu: f64) -> f64 {
    1.0 - nu - 2.0 * nu * nu
}

/// Ratio of tangential to normal edge force, F_t/F_n = (G/E)·ξ = ξ/(2(1+ν))
/// (seed 000 §III.B, the unnumbered equation after Atkins' assumption).
#[inline]
pub fn force_ratio(xi: f64, nu: f64) -> f64 {
    xi / (2.0 * (1.0 + nu))
}

/// Ratio of the normal edge force during slicing to that during pressing at the
/// same maximum principal strain, f_n^s/f_n^p = 2/(1+√(1+(ξ/(1−ν−2ν²))²))
/// (seed 000 §III.B, derived from eq. 5).
#[inline]
pub fn normal_force_ratio(xi: f64, nu: f64) -> f64 {
    let q = xi / compressibility_factor(nu);
    2.0 / (1.0 + (1.0 + q * q).sqrt())
}

/// Toughness ratio r = R_c^s / R_c (seed 000 eq. 6):
/// r(ξ,ν) = 2/(1+√(1+(ξ/(1−ν−2ν²))²)) · (1 + ξ²/(2(1+ν))).
///
/// r(0, ν) = 1; it falls to a minimum and rises again for large ξ (Fig. 3).
#[inline]
pub fn toughness_ratio(xi: f64, nu: f64) -> f64 {
    normal_force_ratio(xi, nu) * (1.0 + xi * xi / (2.0 * (1.0 + nu)))
}

/// Derivative ∂r/∂ξ of [`toughness_ratio`], analytic.
pub fn toughness_ratio_derivative(xi: f64, nu: f64) -> f64 {
    let c = compressibility_factor(nu);
    let q = xi / c;
    let s = (1.0 + q * q).sqrt();
    let f = 2.0 / (1.0 + s);
    // df/dξ = −2/(1+s)² · ds/dξ, ds/dξ = q/(s c).
    let df = -2.0 / ((1.0 + s) * (1.0 + s)) * q / (s * c);
    let g = 1.0 + xi * xi / (2.0 * (1.0 + nu));
    let dg = xi / (1.0 + nu);
    df * g + f * dg
}

#[cfg(test)]
mod tests {
    use super::*;

    // Hand values from the issue, computed independently to 4 decimals.
    #[test]
    fn toughness_ratio_hand_values() {
        assert_eq!(format!("{:.4}", toughness_ratio(0.75, 0.4)), "0.6224");
        assert_eq!(format!("{:.4}", toughness_ratio(1.8, 0.4)), "0.5748");
        assert_eq!(format!("{:.4}", toughness_ratio(0.33, 0.35)), "0.9086");
        assert_eq!(toughness_ratio(0.0, 0.3), 1.0);
    }

    #[test]
    fn minimum_for_nu_04() {
        // Golden-section search on [0.5, 3]; r is unimodal there (Fig. 3).
        let (mut a, mut b) = (0.5_f64, 3.0_f64);
        let g = (5f64.sqrt() - 1.0) / 2.0;
        for _ in 0..200 {
            let c = b - g * (b - a);
            let d = a + g * (b - a);
            if toughness_ratio(c, 0.4) < toughness_ratio(d, 0.4) {
                b = d;
            } else {
                a = c;
            }
        }
        let xi = 0.5 * (a + b);
        assert_eq!(format!("{:.4}", toughness_ratio(xi, 0.4)), "0.5573");
        assert!((xi - 1.365).abs() < 0.005, "argmin {xi}");
        // The derivative vanishes there.
        assert!(toughness_ratio_derivative(xi, 0.4).abs() < 1e-6);
    }

    #[test]
    fn derivative_matches_central_difference() {
        for &nu in &[0.2, 0.35, 0.4, 0.48] {
            for &xi in &[0.0, 0.1, 0.5, 1.0, 2.0, 5.0] {
                let h = 1e-6;
                let fd = (toughness_ratio(xi + h, nu) - toughness_ratio(xi - h, nu)) / (2.0 * h);
                let an = toughness_ratio_derivative(xi, nu);
                assert!((fd - an).abs() < 1e-7, "nu {nu} xi {xi}: {fd} vs {an}");
            }
        }
    }

    #[test]
    fn slicing_toughness_is_product_of_force_ratio_and_work_factor() {
        // r = f_n^s/f_n^p · (1 + ξ · F_t/F_n): the work per unit depth with
        // dt = ξ dn (eq. 6's first line).
        let (xi, nu) = (0.9, 0.35);
        let lhs = toughness_ratio(xi, nu);
        let rhs = normal_force_ratio(xi, nu) * (1.0 + xi * force_ratio(xi, nu));
        assert!((lhs - rhs).abs() < 1e-15);
    }

    #[test]
    fn angle_round_trip() {
        let xi = SlicePushRatio::from_angle(0.6435011087932844);
        assert!((xi.0 - 0.75).abs() < 1e-12);
        assert!((xi.angle() - 0.6435011087932844).abs() < 1e-15);
    }
}
