//! The surrogate against full-model runs: the accuracy report of `shearcut fit`.
//!
//! The full model's forces have a sawtooth after fracture (the crack advances
//! in energy-balanced jumps and the edge or wedge re-loads between them; the
//! README's "Known limitations"), which no smooth function of the state can
//! follow. The surrogate predicts the mean: forces are compared with the full
//! model's post-fracture forces averaged over a centred window of knife travel
//! ([`SMOOTHING_WINDOW`], 2 mm, ten rows of the default mesh); pre-fracture forces, which
//! rise smoothly, are compared sample by sample. Work is cumulative, so it is
//! compared directly. The surrogate runs on its own prediction of the onset
//! (fractured once the depth passes its own d*), as the MPC would.

use serde::{Deserialize, Serialize};

use super::model::Surrogate;
use super::ratio::RatioCorrection;
use super::state::{CutState, ScaleFactors};
use super::sweep::{SweepCase, SweepRun};

/// Width of the averaging window of the full model's forces, m.
pub const SMOOTHING_WINDOW: f64 = 2e-3;

/// One depth of a comparison.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ComparisonPoint {
    /// Knife depth, m.
    pub depth: f64,
    /// Full model F_n as computed (with its sawtooth), N/m.
    pub force_normal_raw: f64,
    /// Full model F_n, window mean after fracture, N/m.
    pub force_normal_full: f64,
    /// Surrogate F_n, N/m.
    pub force_normal_surrogate: f64,
    /// Full model F_t, window mean after fracture, N/m.
    pub force_tangential_full: f64,
    /// Surrogate F_t, N/m.
    pub force_tangential_surrogate: f64,
    /// Full model cumulative knife work, J/m.
    pub work_full: f64,
    /// Surrogate cumulative work (trapezoid of work per depth), J/m.
    pub work_surrogate: f64,
}

/// Accuracy of the surrogate on one run.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RunAccuracy {
    /// Slice-push ratio of the run.
    pub xi: f64,
    /// Section height, m.
    pub height: f64,
    /// Section half width, m.
    pub half_width: f64,
    /// RMS error of F_n, % of the full model's F_n range over the run.
    pub force_normal_rms_pct: f64,
    /// RMS error of F_t, % of its range (0 at ξ = 0, where F_t = 0).
    pub force_tangential_rms_pct: f64,
    /// RMS error of the cumulative work, % of its range (the final work).
    pub work_rms_pct: f64,
    /// Peak F_n (surrogate − full)/full, % (full: window means after fracture).
    pub peak_force_error_pct: f64,
    /// Fracture-onset depth (surrogate − full)/full, %.
    pub onset_depth_error_pct: f64,
    /// Full model's onset depth, m (middle of the step that fractured).
    pub onset_depth_full: f64,
    /// Surrogate's onset depth, m.
    pub onset_depth_surrogate: f64,
    /// Full model's peak F_n (window means after fracture), N/m.
    pub peak_force_full: f64,
    /// Full model's peak F_n including the sawtooth, N/m (for information).
    pub peak_force_raw: f64,
}

/// A run compared: the series and the numbers.
#[derive(Debug, Clone, PartialEq)]
pub struct RunComparison {
    /// The run's case.
    pub case: SweepCase,
    /// Depth by depth.
    pub points: Vec<ComparisonPoint>,
    /// Errors.
    pub accuracy: RunAccuracy,
}

/// Centred moving average of `v` over samples whose depth lies within
/// ±window/2, restricted to the index range `from..` (the post-fracture part).
fn window_mean(depth: &[f64], v: &[f64], from: usize, window: f64) -> Vec<f64> {
    let mut out = v.to_vec();
    let (mut lo, mut hi) = (from, from);
    let mut sum = 0.0;
    for i in from..v.len() {
        while hi < v.len() && depth[hi] <= depth[i] + 0.5 * window {
            sum += v[hi];
            hi += 1;
        }
        while depth[lo] < depth[i] - 0.5 * window {
            sum -= v[lo];
            lo += 1;
        }
        out[i] = sum / (hi - lo) as f64;
    }
    out
}

fn rms_pct(a: &[f64], b: &[f64]) -> f64 {
    let (lo, hi) = b
        .iter()
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(l, h), &x| {
            (l.min(x), h.max(x))
        });
    let range = (hi - lo).max(0.0);
    if range <= 0.0 || a.is_empty() {
        return 0.0;
    }
    let ms = a.iter().zip(b).map(|(x, y)| (x - y) * (x - y)).sum::<f64>() / a.len() as f64;
    100.0 * ms.sqrt() / range
}

/// Compares `surrogate` (nominal scale) with the full-model `run`.
pub fn compare_run(surrogate: &Surrogate, run: &SweepRun) -> RunComparison {
    compare_run_scaled(surrogate, run, &ScaleFactors::default())
}

/// Compares `surrogate` at the scale factors `scale` with the full-model
/// `run` of the correspondingly scaled material (R_c and R'_c × toughness,
/// E × stiffness, μ × friction).
pub fn compare_run_scaled(
    surrogate: &Surrogate,
    run: &SweepRun,
    scale: &ScaleFactors,
) -> RunComparison {
    let c = run.case;
    let n = run.samples.len();
    let depth: Vec<f64> = run.samples.iter().map(|s| s.depth).collect();
    let f_n: Vec<f64> = run.samples.iter().map(|s| s.force_normal).collect();
    let f_t: Vec<f64> = run.samples.iter().map(|s| s.force_tangential).collect();
    let first = run.samples.iter().position(|s| s.fractured).unwrap_or(n);
    let f_n_s = window_mean(&depth, &f_n, first, SMOOTHING_WINDOW);
    let f_t_s = window_mean(&depth, &f_t, first, SMOOTHING_WINDOW);
    let mut state = CutState {
        depth: 0.0,
        height: c.height,
        half_width: c.half_width,
        fractured: false,
        travel_since_fracture: 0.0,
    };
    let onset_sur = surrogate.evaluate(c.xi, &state, scale).fracture_onset_depth;
    let onset_full = run
        .onset_depth
        .map_or(f64::NAN, |d| d - 0.5 * run.onset_resolution);
    let mut points = Vec::with_capacity(n);
    let (mut w_sur, mut last_d, mut last_rate) = (0.0, 0.0, 0.0);
    for (i, s) in run.samples.iter().enumerate() {
        state.depth = s.depth;
        state.fractured = s.depth >= onset_sur;
        state.travel_since_fracture = (s.depth - onset_sur).max(0.0);
        let o = surrogate.evaluate(c.xi, &state, scale);
        w_sur += 0.5 * (last_rate + o.work_per_depth) * (s.depth - last_d);
        last_d = s.depth;
        last_rate = o.work_per_depth;
        points.push(ComparisonPoint {
            depth: s.depth,
            force_normal_raw: s.force_normal,
            force_normal_full: f_n_s[i],
            force_normal_surrogate: o.force_normal,
            force_tangential_full: f_t_s[i],
            force_tangential_surrogate: o.force_tangential,
            work_full: s.work,
            work_surrogate: w_sur,
        });
    }
    let col = |f: fn(&ComparisonPoint) -> f64| points.iter().map(f).collect::<Vec<_>>();
    let peak = |v: &[f64]| v.iter().copied().fold(f64::NEG_INFINITY, f64::max);
    let peak_full = peak(&f_n_s);
    let peak_sur = peak(&col(|p| p.force_normal_surrogate));
    let accuracy = RunAccuracy {
        xi: c.xi,
        height: c.height,
        half_width: c.half_width,
        force_normal_rms_pct: rms_pct(&col(|p| p.force_normal_surrogate), &f_n_s),
        force_tangential_rms_pct: if c.xi > 0.0 {
            rms_pct(&col(|p| p.force_tangential_surrogate), &f_t_s)
        } else {
            0.0
        },
        work_rms_pct: rms_pct(&col(|p| p.work_surrogate), &col(|p| p.work_full)),
        peak_force_error_pct: 100.0 * (peak_sur - peak_full) / peak_full,
        onset_depth_error_pct: 100.0 * (onset_sur - onset_full) / onset_full,
        onset_depth_full: onset_full,
        onset_depth_surrogate: onset_sur,
        peak_force_full: peak_full,
        peak_force_raw: peak(&f_n),
    };
    RunComparison {
        case: c,
        points,
        accuracy,
    }
}

/// The accuracy report of a fit: every held-out run, and the worst of each
/// figure over them.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct AccuracyReport {
    /// Material preset name.
    pub material_name: String,
    /// Knife preset name.
    pub knife_name: String,
    /// Largest RMS error of F_n, % of range.
    pub worst_force_normal_rms_pct: f64,
    /// Largest RMS error of F_t, % of range.
    pub worst_force_tangential_rms_pct: f64,
    /// Largest RMS error of cumulative work, % of range.
    pub worst_work_rms_pct: f64,
    /// Largest |peak F_n error|, %.
    pub worst_peak_force_error_pct: f64,
    /// Largest |onset depth error|, %.
    pub worst_onset_depth_error_pct: f64,
    /// The held-out runs.
    pub runs: Vec<RunAccuracy>,
    /// The held-out runs at other stiffness-to-toughness ratios, with and
    /// without the ratio corrections (absent in reports before format 4).
    #[serde(default)]
    pub scaled: Vec<RatioAccuracy>,
}

/// One held-out run at scale factors (T, S) ≠ (1, 1): the surrogate with its
/// ratio corrections and with them zeroed (linear scaling).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RatioRunAccuracy {
    /// Slice-push ratio of the run.
    pub xi: f64,
    /// Section height, m.
    pub height: f64,
    /// Section half width, m.
    pub half_width: f64,
    /// RMS error of F_n with the corrections, % of the full model's range.
    pub force_normal_rms_pct: f64,
    /// RMS error of F_t with the corrections, % of range.
    pub force_tangential_rms_pct: f64,
    /// RMS error of the cumulative work with the corrections, % of range.
    pub work_rms_pct: f64,
    /// RMS error of F_n scaled linearly (no correction), % of range.
    pub force_normal_rms_pct_linear: f64,
    /// RMS error of F_t scaled linearly, % of range.
    pub force_tangential_rms_pct_linear: f64,
    /// RMS error of the cumulative work scaled linearly, % of range.
    pub work_rms_pct_linear: f64,
}

/// The held-out runs of a material scaled by (T, S): the worst and mean
/// force errors with and without the ratio corrections.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RatioAccuracy {
    /// Toughness factor T (R_c and R'_c).
    pub toughness: f64,
    /// Stiffness factor S (E).
    pub stiffness: f64,
    /// Largest F_n RMS error with the corrections, % of range.
    pub worst_force_normal_rms_pct: f64,
    /// Largest F_t RMS error with the corrections, % of range.
    pub worst_force_tangential_rms_pct: f64,
    /// Largest F_n RMS error scaled linearly, % of range.
    pub worst_force_normal_rms_pct_linear: f64,
    /// Largest F_t RMS error scaled linearly, % of range.
    pub worst_force_tangential_rms_pct_linear: f64,
    /// Mean F_n RMS error with the corrections, % of range.
    pub mean_force_normal_rms_pct: f64,
    /// Mean F_t RMS error with the corrections, % of range.
    pub mean_force_tangential_rms_pct: f64,
    /// Mean F_n RMS error scaled linearly, % of range.
    pub mean_force_normal_rms_pct_linear: f64,
    /// Mean F_t RMS error scaled linearly, % of range.
    pub mean_force_tangential_rms_pct_linear: f64,
    /// Run by run.
    pub runs: Vec<RatioRunAccuracy>,
}

impl RatioAccuracy {
    /// Compares `surrogate` at (T, S) = (`toughness`, `stiffness`), F = 1,
    /// with and without its ratio corrections, against `runs` of the
    /// correspondingly scaled material.
    pub fn new(surrogate: &Surrogate, toughness: f64, stiffness: f64, runs: &[SweepRun]) -> Self {
        let scale = ScaleFactors {
            toughness,
            stiffness,
            friction: 1.0,
        };
        let linear = Surrogate {
            ratio: RatioCorrection::default(),
            ..surrogate.clone()
        };
        let runs: Vec<RatioRunAccuracy> = runs
            .iter()
            .map(|run| {
                let a = compare_run_scaled(surrogate, run, &scale).accuracy;
                let b = compare_run_scaled(&linear, run, &scale).accuracy;
                RatioRunAccuracy {
                    xi: a.xi,
                    height: a.height,
                    half_width: a.half_width,
                    force_normal_rms_pct: a.force_normal_rms_pct,
                    force_tangential_rms_pct: a.force_tangential_rms_pct,
                    work_rms_pct: a.work_rms_pct,
                    force_normal_rms_pct_linear: b.force_normal_rms_pct,
                    force_tangential_rms_pct_linear: b.force_tangential_rms_pct,
                    work_rms_pct_linear: b.work_rms_pct,
                }
            })
            .collect();
        let worst = |f: fn(&RatioRunAccuracy) -> f64| runs.iter().map(f).fold(0.0, f64::max);
        let mean = |f: fn(&RatioRunAccuracy) -> f64| {
            runs.iter().map(f).sum::<f64>() / runs.len().max(1) as f64
        };
        Self {
            toughness,
            stiffness,
            worst_force_normal_rms_pct: worst(|r| r.force_normal_rms_pct),
            worst_force_tangential_rms_pct: worst(|r| r.force_tangential_rms_pct),
            worst_force_normal_rms_pct_linear: worst(|r| r.force_normal_rms_pct_linear),
            worst_force_tangential_rms_pct_linear: worst(|r| r.force_tangential_rms_pct_linear),
            mean_force_normal_rms_pct: mean(|r| r.force_normal_rms_pct),
            mean_force_tangential_rms_pct: mean(|r| r.force_tangential_rms_pct),
            mean_force_normal_rms_pct_linear: mean(|r| r.force_normal_rms_pct_linear),
            mean_force_tangential_rms_pct_linear: mean(|r| r.force_tangential_rms_pct_linear),
            runs,
        }
    }
}

impl AccuracyReport {
    /// Collects the per-run figures.
    pub fn new(material_name: &str, knife_name: &str, runs: Vec<RunAccuracy>) -> Self {
        let worst =
            |f: fn(&RunAccuracy) -> f64| runs.iter().map(|r| f(r).abs()).fold(0.0, f64::max);
        Self {
            material_name: material_name.to_string(),
            knife_name: knife_name.to_string(),
            worst_force_normal_rms_pct: worst(|r| r.force_normal_rms_pct),
            worst_force_tangential_rms_pct: worst(|r| r.force_tangential_rms_pct),
            worst_work_rms_pct: worst(|r| r.work_rms_pct),
            worst_peak_force_error_pct: worst(|r| r.peak_force_error_pct),
            worst_onset_depth_error_pct: worst(|r| r.onset_depth_error_pct),
            runs,
            scaled: Vec::new(),
        }
    }

    /// A plain-text table of the report.
    pub fn table(&self) -> String {
        let mut s = format!(
            "surrogate {} / {} against held-out full-model runs\n   xi  H (mm)  w/2 (mm)  Fn rms %  Ft rms %  work rms %  peak Fn %  onset %  (onset full/sur mm)\n",
            self.material_name, self.knife_name
        );
        for r in &self.runs {
            s += &format!(
                "{:5.2}  {:6.1}  {:8.1}  {:8.2}  {:8.2}  {:10.2}  {:+9.2}  {:+7.2}  ({:.3}/{:.3})\n",
                r.xi,
                1e3 * r.height,
                1e3 * r.half_width,
                r.force_normal_rms_pct,
                r.force_tangential_rms_pct,
                r.work_rms_pct,
                r.peak_force_error_pct,
                r.onset_depth_error_pct,
                1e3 * r.onset_depth_full,
                1e3 * r.onset_depth_surrogate,
            );
        }
        s += &format!(
            "worst: Fn {:.2} %, Ft {:.2} %, work {:.2} % of range; peak Fn {:.2} %, onset {:.2} %\n",
            self.worst_force_normal_rms_pct,
            self.worst_force_tangential_rms_pct,
            self.worst_work_rms_pct,
            self.worst_peak_force_error_pct,
            self.worst_onset_depth_error_pct
        );
        for a in &self.scaled {
            s += &format!(
                "at T = {:.2}, S = {:.2} (rho = {:.3}): Fn rms % corrected/linear, Ft rms % corrected/linear\n",
                a.toughness,
                a.stiffness,
                a.stiffness / a.toughness
            );
            for r in &a.runs {
                s += &format!(
                    "{:5.2}  {:6.1}  {:8.1}  {:6.2} / {:6.2}  {:6.2} / {:6.2}\n",
                    r.xi,
                    1e3 * r.height,
                    1e3 * r.half_width,
                    r.force_normal_rms_pct,
                    r.force_normal_rms_pct_linear,
                    r.force_tangential_rms_pct,
                    r.force_tangential_rms_pct_linear,
                );
            }
            s += &format!(
                "worst: Fn {:.2} % (linear {:.2} %), Ft {:.2} % (linear {:.2} %); mean: Fn {:.2} % (linear {:.2} %), Ft {:.2} % (linear {:.2} %)\n",
                a.worst_force_normal_rms_pct,
                a.worst_force_normal_rms_pct_linear,
                a.worst_force_tangential_rms_pct,
                a.worst_force_tangential_rms_pct_linear,
                a.mean_force_normal_rms_pct,
                a.mean_force_normal_rms_pct_linear,
                a.mean_force_tangential_rms_pct,
                a.mean_force_tangential_rms_pct_linear,
            );
        }
        s
    }
}
