//! Why a plant cannot be built.

use shearcut_sim::invalid_setting::InvalidSetting;
use shearcut_sim::section::SectionError;

/// Why a plant cannot be built.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum PlantError {
    /// A setting is out of range.
    #[error(transparent)]
    Setting(#[from] InvalidSetting),
    /// The knife's planned path never meets the object.
    #[error(
        "the knife moving along the planned direction never touches the object (check z0 and the knife's length)"
    )]
    NoContact,
    /// A cross section could not be built.
    #[error("cross section {index}: {source}")]
    Section {
        /// Index of the segment.
        index: usize,
        /// Why.
        source: SectionError,
    },
}
