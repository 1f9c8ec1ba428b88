//! Surrogates: the cross-section model reduced to functions of ξ and the
//! cut's state that cost well under a microsecond (DESIGN §3.4), fitted by
//! linear least squares to full-model sweeps (`shearcut fit`).
//!
//! Files: `state` ([`CutState`], [`ScaleFactors`]), `output`
//! ([`SurrogateOutput`] and its parts), `toughness` (eq. 6 with two
//! derivatives, exact), `basis` (the fitted functions' bases), `catch_up`
//! (the crack's jump at the first fracture and the knee), `jet` (ξ-jets), `ratio` (the
//! corrections for the stiffness-to-toughness ratio), `model`
//! ([`Surrogate`] and its evaluation), `file` (TOML, versioned), `sweep`
//! (full-model runs), `fit` (least squares), `accuracy` (the report against
//! held-out runs), `equivalent_rectangle` (the rectangle a section of
//! another shape maps to), `campaign` (the sweeps of one fit and what each is for). The structure and its equations are in
//! `docs/surrogates.md`.

mod accuracy;
mod basis;
mod campaign;
mod catch_up;
mod equivalent_rectangle;
mod file;
mod fit;
mod jet;
mod model;
mod output;
mod ratio;
mod state;
mod sweep;
mod toughness;

pub use accuracy::{
    AccuracyReport, ComparisonPoint, RatioAccuracy, RatioRunAccuracy, RunAccuracy, RunComparison,
    SMOOTHING_WINDOW, compare_run, compare_run_scaled,
};
pub use basis::RAMP_LENGTHS;
pub use campaign::{
    FitCampaign, FitCampaignError, FitSizes, HELD_OUT_SCALES, RATIO_STIFFNESS_FACTORS,
    fit_campaign, fit_run_count, scaled_material,
};
pub use catch_up::CATCH_UP_TERMS;
pub use equivalent_rectangle::equivalent_half_width;
pub use file::SurrogateFileError;
pub use fit::{FitError, ScaledSweep, fit_ratio_correction, fit_surrogate};
pub use model::{
    FitRange, FittedBlade, OLDEST_READ_FORMAT_VERSION, PostFracture, PreFracture,
    SURROGATE_FORMAT_VERSION, Surrogate,
};
pub use output::{QuadraticModel, ScaledParts, SurrogateOutput};
pub use ratio::{RatioCorrection, log_ratio};
pub use state::{CutState, ScaleFactors};
pub use sweep::{
    FIT_SECTION_SIZES, FIT_SLICE_PUSH_RATIOS, HELD_OUT_SECTION_SIZES, HELD_OUT_SLICE_PUSH_RATIOS,
    SweepCase, SweepRun, SweepSample, SweepSettings, grid, run_case, run_sweep,
};
pub use toughness::{ToughnessRatio, concave_up_to};
