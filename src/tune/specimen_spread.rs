//! Specimens: the replicas of a variant as different objects of its kind.
//!
//! A variant of a sweep ("a half potato 25 % larger") stands for every
//! object of that description, and no two potatoes are the same: their
//! size, stiffness and toughness differ from one to the next. Replicas by
//! start height alone ([`crate::run_replica`]) cut one object again and
//! again, so a constant ratio whose crack events happen to fall well on
//! that object (the eggplant's crack arrests, docs/heldout.md) wins on all
//! of them. With `[specimens]` in the sweep file, replica k ≥ 1 cuts
//! another specimen as well: its size scaled by 1 + s·u₁, its Young's
//! modulus E by 1 + m·u₂ and its fracture toughness (R_c and R'_c) by
//! 1 + m·u₃, on top of the variant's own factors, with u₁, u₂, u₃ drawn
//! uniform in [−1, 1] from a generator seeded by k alone. Replica 0 is the
//! variant as given. Every controller meets the same specimens (the
//! replicas stay paired), and the draws depend only on k, so every
//! machine and shard builds the same ones.
//!
//! As with a variant's material factors, the MPC keeps the nominal
//! material's surrogate, and every controller is told the specimen's
//! outline and depth (a lab measures the object before it cuts).

use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;
use serde::Deserialize;
use shearcut_sim::InvalidSetting;

use crate::tune::perturbation::Perturbation;

/// Largest size half-range accepted (relative).
pub const MAX_SIZE_SPREAD: f64 = 0.2;
/// Largest material half-range accepted (relative).
pub const MAX_MATERIAL_SPREAD: f64 = 0.5;

/// Seed of the specimens' generator, before the replica index is added:
/// fixed, so a specimen is the same in every sweep.
const SPECIMEN_SEED: u64 = 0x5EC1_3E45;

/// `[specimens]`: how much the specimens of a variant differ (default: not
/// at all, every replica cuts the variant as given).
#[derive(Debug, Clone, Copy, PartialEq, Default, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct SpecimenSpread {
    /// Half-range of the specimens' size factor, relative: each specimen
    /// is 1 ± `size` times the variant's size (default 0; in [0, 0.2]).
    pub size: f64,
    /// Half-range of the specimens' E and R_c factors, relative, drawn
    /// independently (default 0; in [0, 0.5]).
    pub material: f64,
}

/// One specimen's factors on the variant.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SpecimenFactors {
    /// On every dimension of the object and on the target depth.
    pub size: f64,
    /// On Young's modulus E.
    pub youngs_modulus: f64,
    /// On R_c and R'_c.
    pub fracture_toughness: f64,
}

impl SpecimenFactors {
    /// The variant as given.
    pub const NOMINAL: Self = Self {
        size: 1.0,
        youngs_modulus: 1.0,
        fracture_toughness: 1.0,
    };
}

impl SpecimenSpread {
    /// Checks both half-ranges; keys are the field names.
    pub fn validate(&self) -> Result<(), InvalidSetting> {
        for (key, v, hi) in [
            ("size", self.size, MAX_SIZE_SPREAD),
            ("material", self.material, MAX_MATERIAL_SPREAD),
        ] {
            if !(v.is_finite() && (0.0..=hi).contains(&v)) {
                return Err(InvalidSetting::new(key, v, format!("must be in [0, {hi}]")));
            }
        }
        Ok(())
    }

    /// Whether every replica cuts the variant as given.
    pub fn is_none(&self) -> bool {
        self.size == 0.0 && self.material == 0.0
    }

    /// The factors of replica `replica`'s specimen (replica 0: nominal).
    pub fn factors(&self, replica: u32) -> SpecimenFactors {
        if replica == 0 || self.is_none() {
            return SpecimenFactors::NOMINAL;
        }
        let mut rng = ChaCha8Rng::seed_from_u64(SPECIMEN_SEED + u64::from(replica));
        let mut draw = |half: f64| 1.0 + half * rng.random_range(-1.0..=1.0);
        SpecimenFactors {
            size: draw(self.size),
            youngs_modulus: draw(self.material),
            fracture_toughness: draw(self.material),
        }
    }

    /// `variant` as replica `replica`'s specimen: its factors multiplied by
    /// the specimen's (the variant itself for replica 0).
    pub fn specimen_of(&self, variant: &Perturbation, replica: u32) -> Perturbation {
        let f = self.factors(replica);
        if f == SpecimenFactors::NOMINAL {
            return variant.clone();
        }
        Perturbation {
            size_scale: variant.size_scale * f.size,
            youngs_modulus_scale: variant.youngs_modulus_scale * f.youngs_modulus,
            fracture_toughness_scale: variant.fracture_toughness_scale * f.fracture_toughness,
            ..variant.clone()
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    const SPREAD: SpecimenSpread = SpecimenSpread {
        size: 0.05,
        material: 0.1,
    };

    #[test]
    fn replica_zero_and_no_spread_cut_the_variant_as_given() {
        let v = Perturbation {
            size_scale: 1.25,
            ..Perturbation::default()
        };
        assert_eq!(SPREAD.specimen_of(&v, 0), v);
        assert_eq!(SpecimenSpread::default().specimen_of(&v, 3), v);
        assert!(SpecimenSpread::default().is_none());
    }

    #[test]
    fn specimens_differ_within_their_half_ranges_and_are_the_same_every_time() {
        let factors: Vec<SpecimenFactors> = (1..=20).map(|k| SPREAD.factors(k)).collect();
        for f in &factors {
            assert!((f.size - 1.0).abs() <= 0.05, "{f:?}");
            assert!((f.youngs_modulus - 1.0).abs() <= 0.1, "{f:?}");
            assert!((f.fracture_toughness - 1.0).abs() <= 0.1, "{f:?}");
        }
        // Twenty draws of each spread out over their ranges, independently.
        let span = |g: fn(&SpecimenFactors) -> f64| {
            let xs: Vec<f64> = factors.iter().map(g).collect();
            xs.iter().cloned().fold(f64::MIN, f64::max)
                - xs.iter().cloned().fold(f64::MAX, f64::min)
        };
        assert!(span(|f| f.size) > 0.05, "sizes cover over half their range");
        assert!(span(|f| f.youngs_modulus) > 0.1);
        assert!(span(|f| f.fracture_toughness) > 0.1);
        assert!(
            factors
                .iter()
                .any(|f| (f.youngs_modulus - f.fracture_toughness).abs() > 0.02)
        );
        assert_eq!(
            factors,
            (1..=20).map(|k| SPREAD.factors(k)).collect::<Vec<_>>()
        );
    }

    #[test]
    fn a_specimen_multiplies_the_variants_factors() {
        let v = Perturbation {
            size_scale: 0.75,
            youngs_modulus_scale: 1.3,
            fracture_toughness_scale: 0.7,
            z0: Some(0.05),
            ..Perturbation::default()
        };
        let f = SPREAD.factors(2);
        let s = SPREAD.specimen_of(&v, 2);
        assert_eq!(s.size_scale, 0.75 * f.size);
        assert_eq!(s.youngs_modulus_scale, 1.3 * f.youngs_modulus);
        assert_eq!(s.fracture_toughness_scale, 0.7 * f.fracture_toughness);
        assert_eq!((s.z0, s.friction_scale), (Some(0.05), 1.0));
    }

    #[test]
    fn out_of_range_spreads_name_their_key() {
        let bad = |size, material| SpecimenSpread { size, material }.validate().unwrap_err();
        assert_eq!(
            bad(0.3, 0.0).to_string(),
            "`size` = 0.3: must be in [0, 0.2]"
        );
        assert_eq!(
            bad(0.0, -0.1).to_string(),
            "`material` = -0.1: must be in [0, 0.5]"
        );
        assert!(bad(f64::NAN, 0.0).to_string().starts_with("`size` = NaN"));
        assert!(SPREAD.validate().is_ok());
    }
}
