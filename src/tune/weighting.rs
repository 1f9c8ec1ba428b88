//! A weighting of the objectives: what "best" means for a recommendation.
//!
//! A setting's score under a weighting is Σ wᵢ·mᵢ/bᵢ over the objectives
//! (work, maximum deformation, peak vertical force, time), mᵢ the setting's
//! mean over the variants and replicas and bᵢ the least such mean in its
//! scenario group: each objective counts relative to the best the sweep
//! reached, so the weights are free of units.

use std::collections::BTreeMap;

use serde::{Deserialize, Serialize};
use shearcut_sim::InvalidSetting;

use crate::tune::objective::Objective;

/// `[weightings.NAME]`: weights of the objectives (each >= 0, default 0,
/// at least one > 0; unitless, see the module doc).
#[derive(Debug, Clone, Copy, PartialEq, Default, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct Weighting {
    /// Weight of the work done on the object (default 0).
    pub work: f64,
    /// Weight of the largest surface deformation (default 0).
    pub deformation: f64,
    /// Weight of the peak vertical force (default 0).
    pub peak_force: f64,
    /// Weight of the time to the target depth (default 0).
    pub time: f64,
}

impl Weighting {
    /// The weight of `objective`.
    pub fn weight(&self, objective: Objective) -> f64 {
        match objective {
            Objective::Work => self.work,
            Objective::Deformation => self.deformation,
            Objective::PeakForce => self.peak_force,
            Objective::Time => self.time,
        }
    }

    /// Checks every weight (finite, >= 0) and that one is > 0.
    pub fn validate(&self) -> Result<(), InvalidSetting> {
        for o in Objective::ALL {
            let w = self.weight(o);
            if !(w.is_finite() && w >= 0.0) {
                return Err(InvalidSetting::new(
                    o.key(),
                    w,
                    "must be a finite number >= 0",
                ));
            }
        }
        if Objective::ALL.iter().all(|&o| self.weight(o) == 0.0) {
            return Err(InvalidSetting::new(
                "(all)",
                0,
                "give at least one of work, deformation, peak_force, time a weight > 0",
            ));
        }
        Ok(())
    }

    /// The score of objective means `means` (in [`Objective::ALL`]'s
    /// order) against the group's best means `best`.
    pub fn score(&self, means: &[f64; 4], best: &[f64; 4]) -> f64 {
        Objective::ALL
            .iter()
            .enumerate()
            .map(|(i, &o)| {
                let w = self.weight(o);
                if w == 0.0 {
                    0.0
                } else {
                    w * means[i] / best[i].max(f64::MIN_POSITIVE)
                }
            })
            .sum()
    }
}

/// The weightings used when a sweep names none.
pub fn default_weightings() -> BTreeMap<String, Weighting> {
    let one = |f: fn(&mut Weighting)| {
        let mut w = Weighting::default();
        f(&mut w);
        w
    };
    BTreeMap::from([
        ("least-work".to_string(), one(|w| w.work = 1.0)),
        (
            "least-deformation".to_string(),
            one(|w| w.deformation = 1.0),
        ),
        ("least-force".to_string(), one(|w| w.peak_force = 1.0)),
        ("fastest".to_string(), one(|w| w.time = 1.0)),
        (
            "balanced".to_string(),
            Weighting {
                work: 1.0,
                deformation: 1.0,
                peak_force: 1.0,
                time: 1.0,
            },
        ),
    ])
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_score_counts_each_objective_relative_to_the_best() {
        let w = Weighting {
            work: 1.0,
            deformation: 2.0,
            ..Weighting::default()
        };
        // Work 10 % above the best, deformation at the best: 1.1 + 2·1.
        let s = w.score(&[1.1, 0.5, 9.0, 9.0], &[1.0, 0.5, 1.0, 1.0]);
        assert!((s - 3.1).abs() < 1e-12, "{s}");
        assert!(Weighting::default().validate().is_err());
        for w in default_weightings().values() {
            w.validate().unwrap();
        }
    }
}
