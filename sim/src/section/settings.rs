//! Settings of a cross-section simulation: mesh resolution and the fracture solver.

use serde::{Deserialize, Serialize};

use crate::invalid_setting::InvalidSetting;
use crate::material::Material;
use crate::physical_range::{
    BRACKET_DOUBLINGS, ELEMENT_WIDTH, GRADING_RATIO, INITIAL_CRACK_EXTENSION, ROOT_ITERATIONS,
    ROOT_TOLERANCE, ROW_SPACING, check_count,
};

/// What sets off a section's first fracture.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum FirstFracture {
    /// Seed 000's energy balance with the initial toughness: the crack first
    /// grows when R(δ₀) ≥ r(ξ,ν)·R'_c (eqs. 1 and 6). The default.
    #[default]
    Toughness,
    /// Seed 001's surface stress: the crack first grows when the edge's load
    /// per unit length (F_n, F_t) reaches the loads at which the
    /// finite-strain slab's surface σ₁ reaches σ* = 2μ
    /// ([`NucleationEnvelope::SEED_GEL`](crate::finite_strain::NucleationEnvelope::SEED_GEL),
    /// scaled by μR with R the edge flat's width: a wire knife's flat is R
    /// wide); from then on it grows while its release rate, resolved over a
    /// row, is at least r·R_c and arrests where it falls below (R'_c plays
    /// no part, except as a skin layer's toughness). For nearly
    /// incompressible soft solids (Poisson ratio at least 0.45), like the
    /// seed's gel (K = 30μ) whose envelope it is.
    SurfaceStress,
}

/// Smallest Poisson ratio for [`FirstFracture::SurfaceStress`]: the
/// envelope is that of a gel with K = 30μ (ν = 0.4835); ν = 0.45 is K ≈ 9.7μ.
pub const SURFACE_STRESS_MIN_POISSON_RATIO: f64 = 0.45;

/// Settings of one cross section (DESIGN §3.2; seed 000 §III.C).
///
/// Mesh settings fix allocation sizes and cannot change after
/// [`CrossSection::new`](super::CrossSection::new); the fracture-solver settings
/// could, but are read once too.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct SectionSettings {
    /// Height of the elements along the cut line, m (default 2e-4; in
    /// [1e-5, 5e-3]). The crack
    /// tip travels down this line, so its spacing is uniform; the tip position
    /// between two rows is interpolated (see `CrossSection`).
    pub row_spacing: f64,
    /// Number of elements across the half width of the edge flat, b/2
    /// (default 1). The flat is loaded as a rigid strip (seed 000 eq. 2 is a
    /// strip load); more elements resolve its pressure better.
    pub strip_elements: usize,
    /// Growth ratio of element widths away from the cut line (default 1.3):
    /// the mesh is graded from b/(2·strip_elements) at the cut line.
    pub grading_ratio: f64,
    /// Largest element width, m (default 2e-3), reached by the grading.
    pub max_element_width: f64,
    /// Initial trial crack extension δ₀, m (default 1e-6): the flaw size of
    /// seed 000 §III.C. The crack starts to grow in a step when the energy
    /// release rate for an extension δ₀ reaches the toughness.
    pub initial_crack_extension: f64,
    /// Relative tolerance on the energy release rate in the root search on
    /// the bracket (Illinois regula falsi; the key keeps its historic name),
    /// |R − R_c^s| ≤ tol·R_c^s (default 1e-7).
    pub bisection_tolerance: f64,
    /// Most doublings of the trial extension while bracketing R = R_c^s
    /// (default 60; in [30, 200], enough to take the smallest flaw past the
    /// largest object). Beyond it the step reports an unbracketed status.
    pub max_bracket_doublings: u32,
    /// Most root-search iterations on the bracket per step (default 200; in
    /// [60, 10000]).
    pub max_bisection_iterations: u32,
    /// What sets off the first fracture: `"toughness"` (R'_c, seed 000; the
    /// default) or `"surface_stress"` (σ* = 2μ, seed 001; soft gels only,
    /// Poisson ratio ≥ 0.45).
    pub first_fracture: FirstFracture,
}

impl Default for SectionSettings {
    fn default() -> Self {
        Self {
            row_spacing: 2.0e-4,
            strip_elements: 1,
            grading_ratio: 1.3,
            max_element_width: 2.0e-3,
            initial_crack_extension: 1.0e-6,
            bisection_tolerance: 1.0e-7,
            max_bracket_doublings: 60,
            max_bisection_iterations: 200,
            first_fracture: FirstFracture::Toughness,
        }
    }
}

impl SectionSettings {
    /// Checks every field against its physical range
    /// ([`crate::physical_range`]); δ₀ is at most the row spacing. The
    /// error names the key. The mesh's size is bounded separately
    /// ([`crate::resource_budget::section_nodes`]).
    pub fn validate(&self) -> Result<(), InvalidSetting> {
        ROW_SPACING.check("row_spacing", self.row_spacing)?;
        check_count("strip_elements", self.strip_elements as u64, 1, 8)?;
        GRADING_RATIO.check("grading_ratio", self.grading_ratio)?;
        ELEMENT_WIDTH.check("max_element_width", self.max_element_width)?;
        INITIAL_CRACK_EXTENSION
            .at_most(self.row_spacing)
            .check("initial_crack_extension", self.initial_crack_extension)?;
        ROOT_TOLERANCE.check("bisection_tolerance", self.bisection_tolerance)?;
        let (lo, hi) = BRACKET_DOUBLINGS;
        check_count(
            "max_bracket_doublings",
            u64::from(self.max_bracket_doublings),
            lo,
            hi,
        )?;
        let (lo, hi) = ROOT_ITERATIONS;
        check_count(
            "max_bisection_iterations",
            u64::from(self.max_bisection_iterations),
            lo,
            hi,
        )
    }

    /// [`Self::validate`], and that the first-fracture criterion suits
    /// `material`: the surface-stress criterion needs a Poisson ratio of at
    /// least [`SURFACE_STRESS_MIN_POISSON_RATIO`].
    pub fn validate_for(&self, material: &Material) -> Result<(), InvalidSetting> {
        self.validate()?;
        if self.first_fracture == FirstFracture::SurfaceStress
            && (material.poisson_ratio.is_nan()
                || material.poisson_ratio < SURFACE_STRESS_MIN_POISSON_RATIO)
        {
            return Err(InvalidSetting::new(
                "first_fracture",
                "surface_stress",
                format!(
                    "needs a nearly incompressible soft solid (Poisson ratio >= {SURFACE_STRESS_MIN_POISSON_RATIO}); the material's is {}",
                    material.poisson_ratio
                ),
            ));
        }
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn defaults_validate_and_bad_keys_are_named() {
        SectionSettings::default().validate().unwrap();
        let s = SectionSettings {
            strip_elements: 0,
            ..Default::default()
        };
        assert_eq!(s.validate().unwrap_err().key, "strip_elements");
        let parsed: Result<SectionSettings, _> = serde_json::from_str(r#"{"row_spacng": 1}"#);
        assert!(parsed.is_err(), "unknown keys are refused");
    }
}
