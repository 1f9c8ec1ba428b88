//! Settings of a cross-section simulation: mesh resolution and the fracture solver.

use serde::{Deserialize, Serialize};

use crate::invalid_setting::{InvalidSetting, positive};

/// Settings of one cross section (DESIGN §3.2; seed 000 §III.C).
///
/// Mesh settings fix allocation sizes and cannot change after
/// [`CrossSection::new`](super::CrossSection::new); the fracture-solver settings
/// could, but are read once too.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct SectionSettings {
    /// Height of the elements along the cut line, m (default 2e-4). The crack
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
    /// (default 60). Beyond it the step reports an unbracketed status.
    pub max_bracket_doublings: u32,
    /// Most root-search iterations on the bracket per step (default 200).
    pub max_bisection_iterations: u32,
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
        }
    }
}

impl SectionSettings {
    /// Checks every field; the error names the key.
    pub fn validate(&self) -> Result<(), InvalidSetting> {
        positive("row_spacing", self.row_spacing)?;
        if !(1..=8).contains(&self.strip_elements) {
            return Err(InvalidSetting::new(
                "strip_elements",
                self.strip_elements,
                "must be an integer in 1..=8",
            ));
        }
        let g = self.grading_ratio;
        if !(g.is_finite() && (1.0..=3.0).contains(&g)) {
            return Err(InvalidSetting::new(
                "grading_ratio",
                g,
                "must be in the interval [1, 3]",
            ));
        }
        positive("max_element_width", self.max_element_width)?;
        positive("initial_crack_extension", self.initial_crack_extension)?;
        let t = self.bisection_tolerance;
        if !(t.is_finite() && t > 0.0 && t < 0.1) {
            return Err(InvalidSetting::new(
                "bisection_tolerance",
                t,
                "must be in the open interval (0, 0.1)",
            ));
        }
        if self.max_bracket_doublings == 0 || self.max_bracket_doublings > 200 {
            return Err(InvalidSetting::new(
                "max_bracket_doublings",
                self.max_bracket_doublings,
                "must be an integer in 1..=200",
            ));
        }
        if self.max_bisection_iterations == 0 {
            return Err(InvalidSetting::new(
                "max_bisection_iterations",
                self.max_bisection_iterations,
                "must be an integer >= 1",
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
