//! The toughness a knife step's crack extension pays (seed 000 eqs. 1 and
//! 6): the slicing toughness r(ξ,ν)·R'_c before the first fracture and
//! r(ξ,ν)·R_c after it, or, with a skin layer
//! ([`Material::skin_thickness`]), the toughness integrated over the depths
//! the extension crosses.

use crate::material::Material;

use super::fracture::toughness_ratio;

/// The toughness of one step's crack extension and the balance the
/// extension solves.
///
/// Without a skin layer the extension s solves R(s) = T for a constant T:
/// growth starts when R ≥ `trigger` = r·R'_c (r·R_c after the first
/// fracture) and balances at `target` = r·min(R'_c, R_c) (r·R_c after it).
///
/// With a skin layer of thickness t the toughness depends on the depth: an
/// extension s from the tip's depth a₀ pays
/// Γ(s) = R'_c·|[a₀, a₀+s] ∩ [0, t]| + R_c·(the rest) and balances
/// R(s) = r·Γ(s)/s, whatever the first-fracture flag says. The root search
/// then runs on the ratio R(s)/(r·Γ(s)/s) against 1 (same relative
/// tolerance): `trigger` = `target` = 1.
#[derive(Debug, Clone, Copy)]
pub(super) struct StepToughness {
    /// Toughness ratio r(ξ,ν) of seed 000 eq. (6) (∞ for ξ = ∞).
    r: f64,
    /// Initial fracture toughness R'_c, N/m.
    initial: f64,
    /// Fracture toughness R_c, N/m.
    toughness: f64,
    /// The constant balance target without a skin layer, N/m.
    uniform_target: f64,
    /// Skin thickness t and the tip's depth a₀ at the start of the step, m.
    skin: Option<(f64, f64)>,
    /// What the balance must reach for the crack to grow (N/m, or 1 with a
    /// skin layer).
    pub(super) trigger: f64,
    /// What the balance settles at (N/m, or 1 with a skin layer).
    pub(super) target: f64,
}

impl StepToughness {
    /// The toughness for a step of slice-push ratio `xi` in `material`, from
    /// a tip `depth` (m) below the top; `after_first` when the toughness is
    /// R_c's already (the first fracture happened, or seed 001's surface
    /// stress replaces R'_c).
    pub(super) fn new(material: &Material, xi: f64, after_first: bool, depth: f64) -> Self {
        let mat = material;
        let r = if xi.is_finite() {
            toughness_ratio(xi, mat.poisson_ratio)
        } else {
            f64::INFINITY
        };
        let (trigger, target) = if after_first {
            (r * mat.fracture_toughness, r * mat.fracture_toughness)
        } else {
            (
                r * mat.initial_fracture_toughness,
                r * mat.initial_fracture_toughness.min(mat.fracture_toughness),
            )
        };
        let skin = mat.skin_thickness.map(|t| (t, depth));
        let uniform_target = target;
        let (trigger, target) = if skin.is_some() {
            (1.0, 1.0)
        } else {
            (trigger, target)
        };
        Self {
            r,
            initial: mat.initial_fracture_toughness,
            toughness: mat.fracture_toughness,
            uniform_target,
            skin,
            trigger,
            target,
        }
    }

    /// The toughness per unit extension an extension `s` (m) pays, N/m:
    /// r·Γ(s)/s with a skin layer, the constant target without.
    fn layered(&self, s: f64) -> f64 {
        match self.skin {
            Some((t, a0)) => {
                let in_skin = (t - a0).clamp(0.0, s);
                self.r * (self.initial * in_skin + self.toughness * (s - in_skin)) / s
            }
            None => self.uniform_target,
        }
    }

    /// The balance the root search runs on for an energy release rate
    /// `release` (N/m) at extension `s` (m): R(s) itself, or R(s)/(r·Γ(s)/s)
    /// with a skin layer.
    pub(super) fn balance(&self, release: f64, s: f64) -> f64 {
        if self.skin.is_some() {
            release / self.layered(s)
        } else {
            release
        }
    }

    /// The energy release rate R(s), N/m, back from a `balance` at
    /// extension `s` (m).
    pub(super) fn rate(&self, s: f64, balance: f64) -> f64 {
        if self.skin.is_some() {
            balance * self.layered(s)
        } else {
            balance
        }
    }

    /// The toughness the extension `s` (m) pays per unit extension, N/m.
    pub(super) fn target_at(&self, s: f64) -> f64 {
        if self.skin.is_some() {
            self.layered(s)
        } else {
            self.target
        }
    }
}
