//! Surrogates: the cross-section model reduced to functions of ξ and the
//! cut's state that cost well under a microsecond (DESIGN §3.4), fitted by
//! linear least squares to full-model sweeps (`shearcut fit`).
//!
//! Files: `state` ([`CutState`], [`ScaleFactors`]), `output`
//! ([`SurrogateOutput`] and its parts), `toughness` (eq. 6 with two
//! derivatives, exact), `basis` (the fitted functions' bases), `catch_up`
//! (the crack's jump at the first fracture and the knee), `jet` (ξ-jets), `model`
//! ([`Surrogate`] and its evaluation), `file` (TOML, versioned), `sweep`
//! (full-model runs), `fit` (least squares), `accuracy` (the report against
//! held-out runs). The structure and its equations are in
//! `docs/surrogates.md`.

mod accuracy;
mod basis;
mod catch_up;
mod file;
mod fit;
mod jet;
mod model;
mod output;
mod state;
mod sweep;
mod toughness;

pub use accuracy::{
    AccuracyReport, ComparisonPoint, RunAccuracy, RunComparison, SMOOTHING_WINDOW, compare_run,
};
pub use basis::RAMP_LENGTHS;
pub use catch_up::CATCH_UP_TERMS;
pub use file::SurrogateFileError;
pub use fit::{FitError, fit_surrogate};
pub use model::{
    FitRange, FittedBlade, PostFracture, PreFracture, SURROGATE_FORMAT_VERSION, Surrogate,
};
pub use output::{QuadraticModel, ScaledParts, SurrogateOutput};
pub use state::{CutState, ScaleFactors};
pub use sweep::{
    FIT_SECTION_SIZES, FIT_SLICE_PUSH_RATIOS, HELD_OUT_SECTION_SIZES, HELD_OUT_SLICE_PUSH_RATIOS,
    SweepCase, SweepRun, SweepSample, SweepSettings, grid, run_case, run_sweep,
};
pub use toughness::{ToughnessRatio, concave_up_to};
