//! The sweeps of one `shearcut fit` and what is fitted from each: the
//! nominal material (the nominal surrogate and its held-out accuracy), the
//! material at other stiffness-to-toughness ratios (the ratio corrections,
//! module `ratio`) and the held-out runs at scaled materials (the accuracy
//! with and without the corrections).

use super::accuracy::{AccuracyReport, RatioAccuracy, RunComparison, compare_run};
use super::file::SurrogateFileError;
use super::fit::{FitError, ScaledSweep, fit_ratio_correction, fit_surrogate};
use super::model::Surrogate;
use super::sweep::{
    FIT_SECTION_SIZES, FIT_SLICE_PUSH_RATIOS, HELD_OUT_SECTION_SIZES, HELD_OUT_SLICE_PUSH_RATIOS,
    SweepRun, SweepSettings, grid, run_sweep,
};
use crate::blade::BladeSection;
use crate::material::Material;
use crate::section::SectionError;

/// Stiffness factors S of the sweeps the ratio corrections are fitted to
/// (toughness factor 1, so ρ = S/T = 0.5 and 2): wider than the ±30 %
/// corners ρ = 0.54–1.86 the estimator is tested on, which are then
/// interpolated, not fitted.
pub const RATIO_STIFFNESS_FACTORS: [f64; 2] = [0.5, 2.0];

/// Scale factors (T, S) of the held-out runs at other ratios (ρ = 1.86 and
/// 0.54): the accuracy with and without the ratio corrections.
pub const HELD_OUT_SCALES: [(f64, f64); 2] = [(0.7, 1.3), (1.3, 0.7)];

/// `material` with its toughnesses R_c, R'_c scaled by `toughness` and its
/// Young's modulus E by `stiffness` (ν, μ and the skin kept).
pub fn scaled_material(material: &Material, toughness: f64, stiffness: f64) -> Material {
    Material {
        youngs_modulus: stiffness * material.youngs_modulus,
        fracture_toughness: toughness * material.fracture_toughness,
        initial_fracture_toughness: toughness * material.initial_fracture_toughness,
        ..*material
    }
}

/// Why a fit's sweeps or least squares failed.
#[derive(Debug, thiserror::Error)]
pub enum FitCampaignError {
    /// A full-model run failed.
    #[error("full-model sweep: {0}")]
    Sweep(#[from] SectionError),
    /// A least-squares problem failed.
    #[error("surrogate fit: {0}")]
    Fit(#[from] FitError),
    /// The fitted surrogate fails the checks a file of it would be read
    /// with (a prediction within the range is not finite).
    #[error("the fitted surrogate would be refused on reading: {0}")]
    Refused(#[from] SurrogateFileError),
}

/// What a fit produced.
#[derive(Debug, Clone)]
pub struct FitCampaign {
    /// The surrogate, with its ratio corrections.
    pub surrogate: Surrogate,
    /// Its accuracy on the held-out runs, nominal and at the scaled
    /// materials of [`HELD_OUT_SCALES`].
    pub report: AccuracyReport,
    /// The nominal held-out comparisons (for plots).
    pub comparisons: Vec<RunComparison>,
}

/// The section sizes (height, half width; m) a fit sweeps and holds out:
/// by default [`FIT_SECTION_SIZES`] and [`HELD_OUT_SECTION_SIZES`], to
/// which `shearcut fit --extra-sizes` and `--extra-held-out-sizes` add
/// (objects larger than the default range, whose MPC would otherwise
/// evaluate the surrogate beyond its `[range]`).
#[derive(Debug, Clone, PartialEq)]
pub struct FitSizes {
    /// Sizes of the fit's sweeps, nominal and at the ratio factors.
    pub fit: Vec<(f64, f64)>,
    /// Sizes of the held-out runs of the accuracy report.
    pub held_out: Vec<(f64, f64)>,
}

impl Default for FitSizes {
    fn default() -> Self {
        Self {
            fit: FIT_SECTION_SIZES.to_vec(),
            held_out: HELD_OUT_SECTION_SIZES.to_vec(),
        }
    }
}

/// Number of full-model runs of [`fit_campaign`] over `sizes`.
pub fn fit_run_count(sizes: &FitSizes) -> usize {
    let fit = FIT_SLICE_PUSH_RATIOS.len() * sizes.fit.len();
    let held_out = HELD_OUT_SLICE_PUSH_RATIOS.len() * sizes.held_out.len();
    fit * (1 + RATIO_STIFFNESS_FACTORS.len()) + held_out * (1 + HELD_OUT_SCALES.len())
}

/// The fit of `shearcut fit`: sweeps the fit's grid
/// ([`FIT_SLICE_PUSH_RATIOS`] × `sizes.fit`) and the held-out runs
/// ([`HELD_OUT_SLICE_PUSH_RATIOS`] × `sizes.held_out`)
/// at the nominal material, fits the nominal surrogate from those alone
/// ([`fit_surrogate`], so it is the same as without the ratio sweeps), sweeps
/// the fit's grid again at E × [`RATIO_STIFFNESS_FACTORS`] and fits the
/// ratio corrections to them ([`fit_ratio_correction`]), then runs the
/// held-out cases at the materials of [`HELD_OUT_SCALES`] for the report.
/// `window_weight`: [`Surrogate::fit_window_weight`](super::Surrogate).
/// `threads` sweep threads; the result does not depend on their number.
/// `progress` is called after each full-model run ([`fit_run_count`] in
/// all).
#[allow(clippy::too_many_arguments)]
pub fn fit_campaign(
    material: &Material,
    blade: &BladeSection,
    material_name: &str,
    knife_name: &str,
    settings: &SweepSettings,
    sizes: &FitSizes,
    window_weight: f64,
    threads: usize,
    progress: &(dyn Fn() + Sync),
) -> Result<FitCampaign, FitCampaignError> {
    let fit_cases = grid(&FIT_SLICE_PUSH_RATIOS, &sizes.fit);
    let held_out_cases = grid(&HELD_OUT_SLICE_PUSH_RATIOS, &sizes.held_out);
    let mut cases = fit_cases.clone();
    cases.extend(&held_out_cases);
    let runs = run_sweep(material, blade, &cases, settings, threads, progress)?;
    let (fit_runs, held_out) = runs.split_at(fit_cases.len());
    let mut surrogate = fit_surrogate(
        material,
        blade,
        material_name,
        knife_name,
        fit_runs,
        window_weight,
    )?;
    let ratio_runs: Vec<(f64, Vec<SweepRun>)> = RATIO_STIFFNESS_FACTORS
        .iter()
        .map(|&s| {
            let m = scaled_material(material, 1.0, s);
            run_sweep(&m, blade, &fit_cases, settings, threads, progress).map(|r| (s, r))
        })
        .collect::<Result<_, _>>()?;
    let sweeps: Vec<ScaledSweep<'_>> = ratio_runs
        .iter()
        .map(|(s, runs)| ScaledSweep {
            toughness: 1.0,
            stiffness: *s,
            runs,
        })
        .collect();
    surrogate.ratio = fit_ratio_correction(&surrogate, &sweeps)?;
    surrogate.validate()?;
    let comparisons: Vec<RunComparison> = held_out
        .iter()
        .map(|r| compare_run(&surrogate, r))
        .collect();
    let mut report = AccuracyReport::new(
        material_name,
        knife_name,
        comparisons.iter().map(|c| c.accuracy).collect(),
    );
    for &(t, s) in &HELD_OUT_SCALES {
        let m = scaled_material(material, t, s);
        let runs = run_sweep(&m, blade, &held_out_cases, settings, threads, progress)?;
        report
            .scaled
            .push(RatioAccuracy::new(&surrogate, t, s, &runs));
    }
    Ok(FitCampaign {
        surrogate,
        report,
        comparisons,
    })
}
