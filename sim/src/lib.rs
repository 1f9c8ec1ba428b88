//! shearcut-sim: the cutting model of shearcut.
//!
//! Materials, knives and objects; the analytic mechanics of seed 000 (strip
//! loads, principal strain, the slice-push toughness ratio) and seed 001 (line
//! loads, nucleation scalings); and, built on them, the cross-section FEM,
//! the multi-section plant and its surrogates. SI units throughout.

pub mod arm;
pub mod array_lengths;
pub mod blade;
pub mod capped_read;
pub mod finite_strain;
pub mod geometry;
pub mod invalid_setting;
pub mod knife;
pub mod knife_plane;
pub mod material;
pub mod mechanics;
pub mod object;
pub mod physical_range;
pub mod resource_budget;
pub mod section;
pub mod surrogate;
pub mod toml_error;

pub use blade::BladeSection;
pub use invalid_setting::InvalidSetting;
pub use knife::{EdgeShape, Knife, KnifeEdge, KnifePreset, KnifeSettings, SensorMount};
pub use material::{Material, MaterialPreset};
pub use mechanics::{SlicePushRatio, toughness_ratio};
pub use object::{Cuboid, ObjectShape};
pub use section::{
    CrossSection, FirstFracture, SectionError, SectionGeometry, SectionSettings, SectionStep,
    StepStatus, WorkSplit,
};
