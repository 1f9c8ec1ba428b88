//! `shearcut fit`: full-model sweeps, the least-squares fit of a surrogate,
//! its accuracy against held-out runs, and plots (DESIGN §3.4,
//! `docs/surrogates.md`).
//!
//! The sweeps cut rectangular sections of the material with the knife's
//! blade section at constant ξ (`shearcut_sim::surrogate::FIT_SLICE_PUSH_RATIOS`
//! × `FIT_SECTION_SIZES`, plus `--extra-sizes`), on both cores; the held-out
//! runs use ξ values and section sizes that are not in the fit. Everything is
//! deterministic, so the same command reproduces the shipped files under
//! `config/surrogates/`.

use std::path::{Path, PathBuf};

use crate::progress::run_bar;
use shearcut_sim::surrogate::{
    AccuracyReport, FitSizes, RunComparison, Surrogate, SweepSettings, fit_campaign, fit_run_count,
};
use shearcut_sim::{EdgeShape, InvalidSetting, KnifePreset, MaterialPreset};

use crate::cli::print;
use crate::error::{ConfigError, RunError};
use crate::plot::ensure_parent;
use crate::plot::surrogate_fit::draw_surrogate_fit;
use crate::render_plot;
use crate::result_file::write_text;
use crate::run_dir::claim_output_file;

/// Threads of the sweeps (the machine's cores, at most 2 by default: DESIGN
/// targets a 2-core development machine).
const SWEEP_THREADS: usize = 2;

/// The section sizes `--extra-sizes` and `--extra-held-out-sizes` accept
/// (height and half width each, mm): from a few rows of the section's mesh
/// (0.2 mm apart) to a melon.
const EXTRA_SIZE_RANGE_MM: [f64; 2] = [5.0, 250.0];

/// What `fit` produced.
#[derive(Debug, Clone)]
pub struct FitOutput {
    /// The surrogate.
    pub surrogate: Surrogate,
    /// Its accuracy on the held-out runs.
    pub report: AccuracyReport,
    /// The held-out comparisons (for plots).
    pub comparisons: Vec<RunComparison>,
}

/// The default surrogate file of a material and knife:
/// `config/surrogates/<material>-<knife>.toml`.
pub fn default_path(material: &str, knife: &str) -> PathBuf {
    PathBuf::from("config/surrogates").join(format!("{material}-{knife}.toml"))
}

fn names<T: Copy>(all: &[T], name: fn(T) -> &'static str) -> String {
    all.iter().map(|&p| name(p)).collect::<Vec<_>>().join(", ")
}

/// Resolves the preset names; a bad name is a config error (exit 2).
pub fn resolve(material: &str, knife: &str) -> Result<(MaterialPreset, KnifePreset), ConfigError> {
    let m = MaterialPreset::from_name(material).ok_or_else(|| {
        ConfigError::Argument(InvalidSetting::new(
            "--material",
            material,
            format!(
                "must be a material preset: {}",
                names(&MaterialPreset::ALL, MaterialPreset::name)
            ),
        ))
    })?;
    let k = KnifePreset::from_name(knife).ok_or_else(|| {
        ConfigError::Argument(InvalidSetting::new(
            "--knife",
            knife,
            format!(
                "must be a knife preset: {}",
                names(&KnifePreset::ALL, KnifePreset::name)
            ),
        ))
    })?;
    if let EdgeShape::Wire { .. } = k.settings().edge {
        return Err(ConfigError::Argument(InvalidSetting::new(
            "--knife",
            knife,
            "must be a bladed knife (the surrogate is fitted to the wedge-blade section model; a wire has no blade)",
        )));
    }
    Ok((m, k))
}

/// Section sizes given as `HEIGHTxHALF_WIDTH` in mm (`65x95`), in m,
/// rounded to the µm (so that the command a file's header records
/// reproduces it, and equal sizes compare equal). Empty values after the
/// last size (a trailing comma) are skipped; one before a size is refused.
/// The option is named `key` in the error (exit 2).
pub fn parse_section_sizes(key: &str, values: &[String]) -> Result<Vec<(f64, f64)>, ConfigError> {
    let [low, high] = EXTRA_SIZE_RANGE_MM;
    // An empty value is no size (`""`, a trailing comma); an empty item
    // before a size (`65x95,,50x60`) is a typo.
    let last_size = values.iter().rposition(|v| !v.trim().is_empty());
    if last_size.is_some_and(|n| values[..n].iter().any(|v| v.trim().is_empty())) {
        return Err(ConfigError::Argument(InvalidSetting::new(
            key,
            values.join(","),
            "sizes HEIGHTxHALF_WIDTH in mm separated by single commas (an item is empty)",
        )));
    }
    values
        .iter()
        .filter(|v| !v.trim().is_empty())
        .map(|v| {
            let size = v.split_once(['x', 'X']).and_then(|(h, w)| {
                let h: f64 = h.trim().parse().ok()?;
                let w: f64 = w.trim().parse().ok()?;
                let within = |x: f64| (low..=high).contains(&x);
                let metres = |mm: f64| (mm * 1e3).round() / 1e6;
                (within(h) && within(w)).then_some((metres(h), metres(w)))
            });
            size.ok_or_else(|| {
                ConfigError::Argument(InvalidSetting::new(
                    key,
                    v,
                    format!(
                        "must be HEIGHTxHALF_WIDTH in mm, each in [{low}, {high}] (e.g. 65x95)"
                    ),
                ))
            })
        })
        .collect()
}

/// The default sizes with `extra` added to the fit's sweeps and
/// `extra_held_out` to its held-out runs. Every size appears once: an extra
/// size already fitted, or a held-out one fitted or already held out, is
/// refused (exit 2, naming the option it came from).
pub fn fit_sizes(
    extra: &[(f64, f64)],
    extra_held_out: &[(f64, f64)],
) -> Result<FitSizes, ConfigError> {
    let mut sizes = FitSizes::default();
    for (key, given, held_out) in [
        ("--extra-sizes", extra, false),
        ("--extra-held-out-sizes", extra_held_out, true),
    ] {
        for &(h, w) in given {
            if sizes.fit.contains(&(h, w)) || sizes.held_out.contains(&(h, w)) {
                return Err(ConfigError::Argument(InvalidSetting::new(
                    key,
                    format!("{}x{}", mm(h), mm(w)),
                    "is already a fitted or held-out size (each size once; a held-out run is not fitted)",
                )));
            }
            let list = if held_out {
                &mut sizes.held_out
            } else {
                &mut sizes.fit
            };
            list.push((h, w));
        }
    }
    Ok(sizes)
}

/// Runs the sweeps, fits and compares (no files written). `window_weight`
/// is the weight of each run's settled-window row in the strain-energy
/// fits (`shearcut fit --window-weight`; 0: none). `progress` is called
/// after each full-model run; the total is [`fit_run_count`].
pub fn fit(
    material: MaterialPreset,
    knife: KnifePreset,
    sizes: &FitSizes,
    window_weight: f64,
    progress: &(dyn Fn() + Sync),
) -> Result<FitOutput, RunError> {
    let threads = std::thread::available_parallelism()
        .map_or(1, |n| n.get())
        .min(SWEEP_THREADS);
    let f = fit_campaign(
        &material.material(),
        &knife.settings().blade,
        material.name(),
        knife.name(),
        &SweepSettings::default(),
        sizes,
        window_weight,
        threads,
        progress,
    )
    .map_err(|e| RunError::write("surrogate fit", e))?;
    Ok(FitOutput {
        surrogate: f.surrogate,
        report: f.report,
        comparisons: f.comparisons,
    })
}

/// A length in m as mm, to the µm (as `--extra-sizes` writes it).
fn mm(length: f64) -> f64 {
    (length * 1e6).round() / 1e3
}

/// `sizes` as `--extra-sizes` takes them (mm), comma-separated.
fn sizes_argument(sizes: &[(f64, f64)]) -> String {
    sizes
        .iter()
        .map(|&(h, w)| format!("{}x{}", mm(h), mm(w)))
        .collect::<Vec<_>>()
        .join(",")
}

/// The surrogate file's text: a header comment with the command that wrote
/// it (`extra` and `extra_held_out` the sizes given beyond the defaults),
/// then the data.
pub fn surrogate_file_text(
    s: &Surrogate,
    extra: &[(f64, f64)],
    extra_held_out: &[(f64, f64)],
) -> String {
    let mut options = String::new();
    if s.fit_window_weight > 0.0 {
        options += &format!(" --window-weight {}", s.fit_window_weight);
    }
    if !extra.is_empty() {
        options += &format!(" --extra-sizes {}", sizes_argument(extra));
    }
    if !extra_held_out.is_empty() {
        options += &format!(" --extra-held-out-sizes {}", sizes_argument(extra_held_out));
    }
    format!(
        "# Surrogate of the cross-section model (docs/surrogates.md), written by\n# `shearcut fit --material {} --knife {}{options}`. Do not edit: refit.\n{}",
        s.material_name,
        s.knife_name,
        s.to_toml_string()
    )
}

/// What `shearcut fit` was asked for, as given on the command line.
#[derive(Debug, Clone, Copy)]
pub struct FitRequest<'a> {
    /// `--material`.
    pub material: &'a str,
    /// `--knife`.
    pub knife: &'a str,
    /// `--window-weight`.
    pub window_weight: f64,
    /// `--extra-sizes` (each `HEIGHTxHALF_WIDTH`, mm).
    pub extra_sizes: &'a [String],
    /// `--extra-held-out-sizes`.
    pub extra_held_out_sizes: &'a [String],
    /// `--out`.
    pub out: Option<&'a Path>,
}

/// Checks, before minutes of sweeps, that `path` (`--out`) names a `.toml`
/// file (the report and plot take its stem) this process can write
/// ([`claim_output_file`]). Bad input (exit 2).
fn claim_output(path: &Path) -> Result<(), RunError> {
    if path.extension().is_none_or(|e| e != "toml") || path.file_stem().is_none() {
        return Err(RunError::Config(ConfigError::Argument(
            InvalidSetting::new(
                "--out",
                path.display(),
                "a file name ending in .toml (the report and the plot go next to it)",
            ),
        )));
    }
    claim_output_file("--out", path)
}

/// Runs the subcommand: sweeps with a progress bar, fit, report, files.
/// `window_weight` as in [`fit`]; refused (exit 2) unless finite and ≥ 0;
/// the extra sizes as [`parse_section_sizes`] and [`fit_sizes`] check them.
///
/// Writes `out` (default [`default_path`]), the report next to it
/// (`<stem>.accuracy.toml`) and the plot (`<stem>.png`).
pub fn run(request: &FitRequest<'_>) -> Result<(), RunError> {
    let FitRequest {
        material,
        knife,
        window_weight,
        extra_sizes,
        extra_held_out_sizes,
        out,
    } = *request;
    let (m, k) = resolve(material, knife)?;
    if !(window_weight.is_finite() && window_weight >= 0.0) {
        return Err(ConfigError::Argument(InvalidSetting::new(
            "--window-weight",
            window_weight,
            "finite and >= 0",
        ))
        .into());
    }
    let extra = parse_section_sizes("--extra-sizes", extra_sizes)?;
    let extra_held_out = parse_section_sizes("--extra-held-out-sizes", extra_held_out_sizes)?;
    let sizes = fit_sizes(&extra, &extra_held_out)?;
    let path = out.map_or_else(|| default_path(m.name(), k.name()), Path::to_path_buf);
    claim_output(&path)?;
    let bar = run_bar(
        fit_run_count(&sizes),
        &format!("full-model sweeps of {}", m.name()),
    );
    let result = fit(m, k, &sizes, window_weight, &|| bar.inc(1));
    bar.finish_and_clear();
    let output = result?;
    ensure_parent(&path)?;
    // The surrogate last: a kill leaves no new surrogate beside an old
    // report and plot.
    let report_path = path.with_extension("accuracy.toml");
    let report_text = format!(
        "# Accuracy of {} against held-out full-model runs (forces: window means over {} mm after fracture).\n{}",
        path.display(),
        shearcut_sim::surrogate::SMOOTHING_WINDOW * 1e3,
        toml::to_string(&output.report).map_err(|e| RunError::write(&report_path, e))?
    );
    write_text(&report_path, &report_text)?;
    let plot_path = path.with_extension("png");
    render_plot!(&plot_path, (1000, 1250), |root| draw_surrogate_fit(
        root,
        &format!(
            "Surrogate vs full model, held-out runs: {} / {}",
            m.name(),
            k.name()
        ),
        &output.comparisons
    ))?;
    write_text(
        &path,
        &surrogate_file_text(&output.surrogate, &extra, &extra_held_out),
    )?;
    print(&format!(
        "{}wrote {}, {}, {}\n",
        output.report.table(),
        path.display(),
        report_path.display(),
        plot_path.display()
    ))
}
