//! Failures of building or running a cross section.

use crate::invalid_setting::InvalidSetting;

/// Why a [`CrossSection`](super::CrossSection) could not be built or stepped.
///
/// Raised by construction (bad settings, unsupported shapes, a singular
/// stiffness) or by a step given an impossible knife motion. Outcomes of a
/// step that are physics, not failures (the crack ran through, the knife is
/// above the section), are reported in [`SectionStep`](super::SectionStep).
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum SectionError {
    /// A setting, material or blade value is out of range.
    #[error("invalid setting: {0}")]
    InvalidSetting(#[from] InvalidSetting),
    /// The section polygon cannot be meshed by this model; the text says why.
    #[error("unsupported section shape: {0}")]
    UnsupportedShape(&'static str),
    /// The mesh would be larger than the model allows (rows × columns).
    #[error("mesh too large: {rows} rows x {columns} columns (limit {limit} nodes)")]
    MeshTooLarge {
        /// Rows of elements along the cut line.
        rows: usize,
        /// Columns of elements across the half section.
        columns: usize,
        /// The node limit.
        limit: usize,
    },
    /// The stiffness matrix could not be factorised (singular or not positive definite).
    #[error("stiffness factorisation failed: {0}")]
    Factorisation(&'static str),
    /// A knife step with a negative or non-finite increment.
    #[error("invalid knife step: {0}")]
    InvalidStep(&'static str),
}
