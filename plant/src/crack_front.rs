//! The crack front in the knife plane: a second-degree polynomial fitted over
//! the sections' crack tips (seed 000 §IV, Fig. 4(b)).

use nalgebra::{Matrix3, Vector2, Vector3};

/// y(z) = c₀ + c₁ (z − z̄) + c₂ (z − z̄)² in the knife plane (world z, y), m.
///
/// Centring on z̄ keeps the normal equations well conditioned for fronts a few
/// centimetres long at z ≈ 0.1 m.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct CrackFront {
    /// Centre of the fit, m.
    pub z_mean: f64,
    /// Coefficients c₀ (m), c₁ (—), c₂ (1/m).
    pub coefficients: [f64; 3],
}

impl CrackFront {
    /// Least-squares fit through the crack tips (z, y). With fewer than three
    /// distinct z the degree drops (two: a line; one: a constant). Allocates
    /// nothing. `None` for no points or non-finite input.
    pub fn fit(tips: &[Vector2<f64>]) -> Option<Self> {
        if tips.is_empty() || tips.iter().any(|p| !(p.x.is_finite() && p.y.is_finite())) {
            return None;
        }
        let n = tips.len() as f64;
        let z_mean = tips.iter().map(|p| p.x).sum::<f64>() / n;
        let spread = tips
            .iter()
            .map(|p| (p.x - z_mean).abs())
            .fold(0.0, f64::max);
        let scale = if spread > 0.0 { spread } else { 1.0 };
        // Normal equations in the scaled variable s = (z − z̄)/scale.
        let mut a = Matrix3::zeros();
        let mut b = Vector3::zeros();
        for p in tips {
            let s = (p.x - z_mean) / scale;
            let phi = Vector3::new(1.0, s, s * s);
            a += phi * phi.transpose();
            b += phi * p.y;
        }
        let distinct = count_distinct(tips, 1e-12 * scale.max(1e-3));
        let c = match distinct {
            0 => return None,
            1 => Vector3::new(b[0] / a[(0, 0)], 0.0, 0.0),
            2 => {
                let m = nalgebra::Matrix2::new(a[(0, 0)], a[(0, 1)], a[(1, 0)], a[(1, 1)]);
                let x = m.lu().solve(&Vector2::new(b[0], b[1]))?;
                Vector3::new(x[0], x[1], 0.0)
            }
            _ => a.lu().solve(&b)?,
        };
        Some(Self {
            z_mean,
            coefficients: [c[0], c[1] / scale, c[2] / (scale * scale)],
        })
    }

    /// Height of the front at `z`, m.
    pub fn height_at(&self, z: f64) -> f64 {
        let s = z - self.z_mean;
        let [c0, c1, c2] = self.coefficients;
        c0 + s * (c1 + s * c2)
    }

    /// Slope dy/dz of the front at `z`.
    pub fn slope_at(&self, z: f64) -> f64 {
        let [_, c1, c2] = self.coefficients;
        c1 + 2.0 * c2 * (z - self.z_mean)
    }

    /// Where the line `origin + λ·direction` (knife plane, (z, y)) meets the
    /// front: the smallest λ ≥ 0, or None if it never does.
    pub fn intersect(&self, origin: Vector2<f64>, direction: Vector2<f64>) -> Option<f64> {
        self.roots(origin, direction, |l| l >= 0.0, |l| l)
    }

    /// Where the whole line `origin + λ·direction` (λ of either sign) meets
    /// the front nearest to `origin`: the root with the smallest |λ|, or None.
    /// The plant uses it for a midpoint that may be below the front (the
    /// edge indents below the crack tip) or above it.
    pub fn intersect_nearest(&self, origin: Vector2<f64>, direction: Vector2<f64>) -> Option<f64> {
        self.roots(origin, direction, |_| true, f64::abs)
    }

    /// The root of the line–front intersection accepted by `accept` with the
    /// smallest `key`.
    fn roots(
        &self,
        origin: Vector2<f64>,
        direction: Vector2<f64>,
        accept: impl Fn(f64) -> bool,
        key: impl Fn(f64) -> f64,
    ) -> Option<f64> {
        // g(λ) = y(λ) − front(z(λ)) = α λ² + β λ + γ.
        let [_, c1, c2] = self.coefficients;
        let s0 = origin.x - self.z_mean;
        let (dz, dy) = (direction.x, direction.y);
        let alpha = -c2 * dz * dz;
        let beta = dy - (c1 * dz + 2.0 * c2 * s0 * dz);
        let gamma = origin.y - self.height_at(origin.x);
        let mut best: Option<f64> = None;
        let mut consider = |l: f64| {
            if l.is_finite() && accept(l) && best.is_none_or(|b| key(l) < key(b)) {
                best = Some(l);
            }
        };
        if alpha.abs() <= 1e-14 * (beta.abs() + gamma.abs()).max(1e-300) {
            if beta != 0.0 {
                consider(-gamma / beta);
            }
        } else {
            let disc = beta * beta - 4.0 * alpha * gamma;
            if disc >= 0.0 {
                // Numerically stable pair of roots.
                let q = -0.5 * (beta + beta.signum() * disc.sqrt());
                consider(q / alpha);
                if q != 0.0 {
                    consider(gamma / q);
                }
            }
        }
        best
    }
}

fn count_distinct(tips: &[Vector2<f64>], tol: f64) -> usize {
    let mut first: Option<f64> = None;
    let mut second: Option<f64> = None;
    for p in tips {
        match (first, second) {
            (None, _) => first = Some(p.x),
            (Some(a), None) if (p.x - a).abs() > tol => second = Some(p.x),
            (Some(a), Some(b)) if (p.x - a).abs() > tol && (p.x - b).abs() > tol => return 3,
            _ => {}
        }
    }
    usize::from(first.is_some()) + usize::from(second.is_some())
}

#[cfg(test)]
mod tests {
    use super::*;
    use proptest::prelude::*;

    proptest! {
        // Tips on an exact parabola are fitted exactly (to rounding), so the
        // front passes through every tip.
        #[test]
        fn fit_passes_through_tips_on_a_parabola(
            c0 in 0.0f64..0.05, c1 in -0.5f64..0.5, c2 in -5.0f64..5.0,
            z0 in 0.0f64..0.15, len in 0.01f64..0.1, m in 3usize..12
        ) {
            let tips: Vec<_> = (0..m)
                .map(|i| {
                    let z = z0 + len * i as f64 / (m - 1) as f64;
                    Vector2::new(z, c0 + c1 * z + c2 * z * z)
                })
                .collect();
            let f = CrackFront::fit(&tips).unwrap();
            for p in &tips {
                prop_assert!((f.height_at(p.x) - p.y).abs() < 1e-10);
            }
        }
    }

    #[test]
    fn degenerate_fits() {
        assert!(CrackFront::fit(&[]).is_none());
        let one = CrackFront::fit(&[Vector2::new(0.1, 0.02)]).unwrap();
        assert_eq!(one.height_at(0.3), 0.02);
        let two = CrackFront::fit(&[Vector2::new(0.1, 0.02), Vector2::new(0.2, 0.03)]).unwrap();
        assert!((two.height_at(0.15) - 0.025).abs() < 1e-15);
        assert!((two.slope_at(0.0) - 0.1).abs() < 1e-12);
    }

    #[test]
    fn intersection_with_a_descending_trajectory() {
        // Front y = 0.02 − 2(z − 0.1)²; a midpoint at (0.11, 0.05) moving
        // straight down meets it at y = 0.02 − 2·0.0001 = 0.0198.
        let f = CrackFront {
            z_mean: 0.1,
            coefficients: [0.02, 0.0, -2.0],
        };
        let l = f
            .intersect(Vector2::new(0.11, 0.05), Vector2::new(0.0, -1.0))
            .unwrap();
        assert!((0.05 - l - 0.0198).abs() < 1e-15);
        // Slicing at 45°: check the point found lies on the front.
        let d = Vector2::new(1.0, -1.0).normalize();
        let o = Vector2::new(0.09, 0.05);
        let l = f.intersect(o, d).unwrap();
        let p = o + d * l;
        assert!((p.y - f.height_at(p.x)).abs() < 1e-14);
        // The whole line: the root nearest the origin, behind it (λ < 0)
        // for a point below the front, where `intersect` finds none.
        let below = Vector2::new(0.1, 0.015);
        let l = f.intersect_nearest(below, Vector2::new(0.0, -1.0)).unwrap();
        assert!((l + 0.005).abs() < 1e-15, "{l}");
        assert!(f.intersect(below, Vector2::new(0.0, -1.0)).is_none());
        // Moving up, away from the front below: no intersection.
        assert!(
            f.intersect(Vector2::new(0.1, 0.05), Vector2::new(0.0, 1.0))
                .is_none()
        );
    }
}
