//! The model's numbers next to seed 001's observations.

use serde::Serialize;

use super::settings::WireSlabSettings;
use super::slab::IndentationRun;
use crate::mechanics::nucleation;

/// Seed 001's observations and the model's counterparts (SI units).
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct SeedComparison {
    /// Slope dF_n/dd of the first angle's run (normally θ = 0), least squares
    /// over R ≤ d ≤ the nucleation depth (the seed fits after the stiffening
    /// at d ≲ R), N/m.
    pub normal_slope: f64,
    /// Seed: 5μh/ln(B/R) with B the slab depth, N/m.
    pub seed_normal_slope: f64,
    /// Largest tangential force at nucleation over the angles, N.
    pub max_tangential_force: f64,
    /// Seed: F_t ≈ 2μRh, N.
    pub seed_max_tangential_force: f64,
    /// Normal force at nucleation of the first angle over that of the last.
    pub normal_force_ratio: f64,
    /// Seed: about 5 between 0° and 75° (experiment and 3D simulation).
    pub seed_normal_force_ratio: f64,
    /// First angle's run: f_n/(μR) (f_n per unit length) from which on the
    /// surface σ₁ maximum lies under the wire up to the run's end
    /// ([`SlabState::maximum_under_wire`](super::SlabState::maximum_under_wire));
    /// `None` if it never does.
    pub under_wire_from: Option<f64>,
    /// Seed (Fig. 2a, pure normal loading): about 12.
    pub seed_under_wire_from: f64,
}

impl SeedComparison {
    /// Compares `runs` (in angle order) of a slab with `settings`.
    pub fn new(settings: &WireSlabSettings, runs: &[IndentationRun]) -> Self {
        let s = settings;
        let (mu, r, h) = (s.shear_modulus, s.wire_radius, s.wire_length);
        let first = runs.first();
        let normal_slope = first.map_or(0.0, |run| {
            let end = run
                .nucleation
                .map_or(f64::INFINITY, |n| n.depth)
                .min(run.states.last().map_or(0.0, |st| st.depth));
            let pts: Vec<(f64, f64)> = run
                .states
                .iter()
                .filter(|st| st.depth >= r && st.depth <= end)
                .map(|st| (st.depth, st.force_normal))
                .collect();
            least_squares_slope(&pts)
        });
        let max_tangential_force = runs
            .iter()
            .filter_map(|run| run.nucleation.map(|n| n.force_tangential))
            .fold(0.0, f64::max);
        let nucleation_fn = |run: Option<&IndentationRun>| {
            run.and_then(|r| r.nucleation)
                .map_or(f64::NAN, |n| n.force_normal)
        };
        let under_wire_from = first.and_then(|run| {
            // The start of the last stretch of states with the maximum under
            // the wire (at small loads σ₁ is near zero everywhere and its
            // maximum wanders).
            let tail = run
                .states
                .iter()
                .rev()
                .take_while(|st| st.maximum_under_wire())
                .last()?;
            Some(tail.force_normal / h / (mu * r))
        });
        Self {
            normal_slope,
            seed_normal_slope: nucleation::indentation_normal_force(mu, 1.0, h, s.slab_depth, r),
            max_tangential_force,
            seed_max_tangential_force: nucleation::max_tangential_force(mu, r, h),
            normal_force_ratio: nucleation_fn(first) / nucleation_fn(runs.last()),
            seed_normal_force_ratio: 5.0,
            under_wire_from,
            seed_under_wire_from: 12.0,
        }
    }
}

/// Slope of the least-squares line through `pts` (0 for fewer than 2 points).
fn least_squares_slope(pts: &[(f64, f64)]) -> f64 {
    if pts.len() < 2 {
        return 0.0;
    }
    let n = pts.len() as f64;
    let mx = pts.iter().map(|p| p.0).sum::<f64>() / n;
    let my = pts.iter().map(|p| p.1).sum::<f64>() / n;
    let sxy: f64 = pts.iter().map(|p| (p.0 - mx) * (p.1 - my)).sum();
    let sxx: f64 = pts.iter().map(|p| (p.0 - mx).powi(2)).sum();
    sxy / sxx
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn slope_of_a_line() {
        let pts: Vec<(f64, f64)> = (0..5).map(|i| (i as f64, 3.0 * i as f64 + 1.0)).collect();
        assert!((least_squares_slope(&pts) - 3.0).abs() < 1e-12);
    }
}
