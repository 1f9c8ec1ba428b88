//! Sweep files (`shearcut tune SWEEP.toml`): scenarios, perturbed variants
//! of them, controllers with grids or lists of their settings, replicas,
//! and the weightings a recommendation is made for. See
//! `config/sweeps/` and docs/tuning.md.
//!
//! ```toml
//! name = "potato-weights"              # default: the file stem
//! scenarios = ["loop-potato-whole"]    # built-in names or paths (relative to this file)
//! replicas = 2                         # replica k starts the knife k·5 µm higher
//!
//! [specimens]                          # optional: replica k ≥ 1 cuts another specimen
//! size = 0.05                          # its size ×(1 ± 0.05)
//! material = 0.1                       # its E and R_c ×(1 ± 0.1) each
//!
//! [variants]                           # the cross product of these lists
//! youngs_modulus_scale = [0.8, 1.0, 1.25]
//!
//! [[controllers]]
//! kind = "mpc"
//! [controllers.grid]                   # keys below [controller]; the cross product
//! "mpc.deformation_weight" = [0.0, 1.0, 100.0, 10000.0]
//!
//! [[controllers]]
//! kind = ["press", "slice:0.5"]
//! ```
//!
//! Every table denies unknown keys; every value is checked on load, and an
//! error names the file, the key, the value and what is allowed (exit 2).

use std::collections::BTreeMap;
use std::path::Path;

use serde::Deserialize;
use shearcut_sim::InvalidSetting;

use crate::commands::compare::SEARCH_POINTS;
use crate::controller_choice::ControllerChoice;
use crate::error::ConfigError;
use crate::scenario::Scenario;
use crate::tune::constant_grid::{BEST_CONSTANT_KIND, ConstantGridPoint, MAX_POINTS};
use crate::tune::controller_setting::ControllerSetting;
use crate::tune::perturbation::Perturbation;
use crate::tune::specimen_spread::SpecimenSpread;
use crate::tune::weighting::{Weighting, default_weightings};

/// Most replicas a sweep may ask for (as `compare`).
pub const MAX_REPLICAS: u32 = crate::commands::compare::MAX_REPLICAS as u32;
/// Most jobs a sweep may expand to (a guard against a typo in a grid).
pub const MAX_JOBS: usize = 100_000;

/// A sweep file as written.
#[derive(Debug, Clone, Default, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct SweepFile {
    /// Name of the sweep (default: the file stem): the default result
    /// directory is `runs/tune-<name>`.
    pub name: Option<String>,
    /// Scenarios to run on: built-in names or TOML paths, relative to the
    /// sweep file (at least one).
    pub scenarios: Vec<String>,
    /// Replicas of every run, 1–21 (default 1): replica k starts the knife
    /// k·5 µm higher ([`crate::run_replica::RunReplica`]).
    pub replicas: Option<u32>,
    /// How much the specimens of a variant differ: replica k ≥ 1 cuts
    /// another object of the variant's kind
    /// ([`crate::tune::specimen_spread`]; default: none, every replica
    /// cuts the variant as given).
    pub specimens: Option<SpecimenSpread>,
    /// Perturbed variants as a grid: each key a value or a list, the
    /// variants the cross product (default: the scenario as given).
    pub variants: Option<VariantGrid>,
    /// Perturbed variants listed one by one (`[[variant]]`; instead of
    /// `[variants]`).
    pub variant: Vec<Perturbation>,
    /// Controllers and their settings (`[[controllers]]`, at least one).
    pub controllers: Vec<ControllerSweep>,
    /// Named weightings of the recommendation (default: least-work,
    /// least-deformation, least-force, fastest, balanced).
    pub weightings: Option<BTreeMap<String, Weighting>>,
}

/// `[variants]`: lists whose cross product are the variants (fields as in
/// [`Perturbation`]; last key fastest in the job order).
#[derive(Debug, Clone, Default, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct VariantGrid {
    /// Factors on E (default [1]).
    pub youngs_modulus_scale: OneOrMany<f64>,
    /// Factors on R_c and R'_c (default [1]).
    pub fracture_toughness_scale: OneOrMany<f64>,
    /// Factors on μ (default [1]).
    pub friction_scale: OneOrMany<f64>,
    /// Factors on the object's size (default [1]).
    pub size_scale: OneOrMany<f64>,
    /// Knife presets (default: the scenario's knife).
    pub knife: OneOrMany<String>,
    /// Sensor force noise, N (default: the scenario's).
    pub force_noise: OneOrMany<f64>,
    /// Sensor force biases [fx, fy, fz], N (default: the scenario's).
    pub force_bias: Vec<[f64; 3]>,
    /// Noise seeds (default: the scenario's).
    pub seed: OneOrMany<u64>,
    /// Places of the object along the edge (`[motion] z0`), m (default:
    /// the scenario's).
    pub z0: OneOrMany<f64>,
    /// Blade budgets (`[controller] blade_budget`), m (default: the
    /// scenario's).
    pub blade_budget: OneOrMany<f64>,
}

/// `[[controllers]]`: one or more controllers, with a grid or a list of
/// settings.
#[derive(Debug, Clone, Default, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct ControllerSweep {
    /// The controllers: `mpc`, `press`, `slice:XI`, `force:N`, one or a
    /// list; or `best-constant` alone: the constant ratios of `compare`'s
    /// coarse search on each variant (`points` of them, from pressing to
    /// the largest ratio the variant's blade budget allows over its depth;
    /// [`crate::tune::constant_grid`]), the best of which per variant is
    /// paired with the MPC (`best-constant.csv`).
    pub kind: OneOrMany<String>,
    /// Points of the `best-constant` grid, 2–21 (default 6, as `compare`);
    /// for `best-constant` only.
    pub points: Option<usize>,
    /// Keys below `[controller]` (dotted or as sub-tables, e.g.
    /// `"mpc.deformation_weight" = [0.0, 100.0]`), each a value or a list:
    /// the settings are the cross product (keys in sorted order, the last
    /// fastest).
    pub grid: toml::Table,
    /// Settings listed one by one, each a table of keys below
    /// `[controller]` (instead of `grid`).
    pub sets: Vec<toml::Table>,
}

/// A value or a list of values.
#[derive(Debug, Clone, Deserialize)]
#[serde(untagged, expecting = "a value or a list of values of the key's type")]
pub enum OneOrMany<T> {
    /// One value.
    One(T),
    /// A list.
    Many(Vec<T>),
}

impl<T> Default for OneOrMany<T> {
    fn default() -> Self {
        Self::Many(Vec::new())
    }
}

impl<T: Clone> OneOrMany<T> {
    /// The values as a list.
    pub fn to_vec(&self) -> Vec<T> {
        match self {
            Self::One(v) => vec![v.clone()],
            Self::Many(v) => v.clone(),
        }
    }
}

/// A sweep with its scenarios loaded and its lists expanded, every value
/// checked.
#[derive(Debug, Clone)]
pub struct Sweep {
    /// The sweep's name.
    pub name: String,
    /// The sweep file's text, as read (copied into the result directory).
    pub text: String,
    /// The scenarios, in the file's order.
    pub scenarios: Vec<Scenario>,
    /// The variants, in grid or list order.
    pub variants: Vec<Perturbation>,
    /// How the file gives its variants: how errors name a variant
    /// ([`Sweep::variant_key`]).
    pub variants_from: VariantSource,
    /// The controller settings, in the file's order.
    pub settings: Vec<ControllerSetting>,
    /// Replicas per run.
    pub replicas: u32,
    /// How the replicas' specimens differ (none by default).
    pub specimens: SpecimenSpread,
    /// Named weightings of the recommendation, by name.
    pub weightings: BTreeMap<String, Weighting>,
}

impl Sweep {
    /// Reads, expands and checks a sweep file.
    pub fn load(path: &Path) -> Result<Self, ConfigError> {
        let text = shearcut_sim::capped_read::read_capped_text(
            path,
            shearcut_sim::resource_budget::CONFIG_FILE_BYTES,
        )
        .map_err(|source| ConfigError::Read {
            path: path.to_path_buf(),
            source,
        })?;
        let origin = path.display().to_string();
        let stem = path.file_stem().and_then(|s| s.to_str()).unwrap_or("sweep");
        Self::parse(&text, &origin, stem, path.parent())
    }

    /// Expands and checks sweep TOML; `origin` names it in errors, `stem`
    /// is the default name, scenario paths are relative to `dir`.
    pub fn parse(
        text: &str,
        origin: &str,
        stem: &str,
        dir: Option<&Path>,
    ) -> Result<Self, ConfigError> {
        let file: SweepFile =
            toml::from_str(text).map_err(|e| crate::scenario::parse_error(origin, text, &e))?;
        let invalid = |setting: InvalidSetting| ConfigError::Invalid {
            path: origin.to_string(),
            setting,
        };
        if let Ok(table) = toml::from_str::<toml::Table>(text) {
            refuse_empty_lists(&table).map_err(invalid)?;
            refuse_bias_lengths(&table).map_err(invalid)?;
        }
        let name = file.name.clone().unwrap_or_else(|| stem.to_string());
        if !is_plain_name(&name) {
            return Err(invalid(InvalidSetting::new(
                "name",
                format!("{name:?}"),
                format!(
                    "must be non-empty, at most {MAX_NAME_CHARS} of letters, digits, '-', '_', '.'"
                ),
            )));
        }
        let replicas = file.replicas.unwrap_or(1);
        if !(1..=MAX_REPLICAS).contains(&replicas) {
            return Err(invalid(InvalidSetting::new(
                "replicas",
                replicas,
                format!("must be in 1..={MAX_REPLICAS}"),
            )));
        }
        let specimens = file.specimens.unwrap_or_default();
        specimens
            .validate()
            .map_err(|e| invalid(e.prefixed("specimens")))?;
        if file.scenarios.is_empty() {
            return Err(invalid(InvalidSetting::new(
                "scenarios",
                "[]",
                "name at least one scenario (built-in name or path)",
            )));
        }
        let mut scenarios = Vec::new();
        for (i, name) in file.scenarios.iter().enumerate() {
            let relative = dir.map(|d| d.join(name));
            let path = match &relative {
                Some(p) if p.exists() => p.display().to_string(),
                _ => name.clone(),
            };
            let s = Scenario::load(&path).map_err(|e| {
                invalid(InvalidSetting::new(
                    format!("scenarios[{i}]"),
                    format!("{name:?}"),
                    e.to_string(),
                ))
            })?;
            if scenarios.iter().any(|t: &Scenario| t.name == s.name) {
                return Err(invalid(InvalidSetting::new(
                    format!("scenarios[{i}]"),
                    format!("{name:?}"),
                    format!("a second scenario named {:?}: names must differ", s.name),
                )));
            }
            scenarios.push(s);
        }
        // The cap on the sweep's size, counted from its lists' lengths
        // before any list is expanded: a few long grids multiply out to
        // more points than memory holds.
        let planned = [
            scenarios.len(),
            variant_count(&file),
            setting_count(&file.controllers),
            replicas as usize,
        ]
        .into_iter()
        .fold(1usize, usize::saturating_mul);
        if planned > MAX_JOBS {
            return Err(invalid(too_many_jobs(planned)));
        }
        let settings = expand_settings(&file.controllers).map_err(invalid)?;
        let variants = expand_variants(&file).map_err(invalid)?;
        // Every variant and every setting alone, on every scenario: the
        // error names the sweep's own key.
        for s in &scenarios {
            for (i, v) in variants.iter().enumerate() {
                let key = if !file.variant.is_empty() {
                    format!("variant[{i}]")
                } else if file.variants.is_some() {
                    "variants".to_string()
                } else {
                    "the scenario as given".to_string()
                };
                let applied = v
                    .apply_for(s, &settings)
                    .map_err(|e| invalid(e.prefixed(&key)))?;
                ControllerSetting::fixed(s.controller.kind)
                    .apply(&applied)
                    .map_err(|e| invalid(e.prefixed(&format!("{key} on {}", s.name))))?;
            }
            for (i, entry) in file.controllers.iter().enumerate() {
                for (key, value) in grid_axes(&entry.grid)
                    .into_iter()
                    .flat_map(|(k, vs)| vs.into_iter().map(move |v| (k.clone(), v)))
                    .chain(entry.sets.iter().flat_map(flat_keys))
                {
                    let single = ControllerSetting {
                        overrides: vec![(key, value)],
                        ..ControllerSetting::fixed(ControllerChoice::Mpc)
                    };
                    single
                        .apply(s)
                        .map_err(|e| invalid(e.prefixed(&format!("controllers[{i}]"))))?;
                }
            }
        }
        let weightings = file.weightings.clone().unwrap_or_else(default_weightings);
        if weightings.is_empty() {
            return Err(invalid(InvalidSetting::new(
                "weightings",
                "{}",
                "name at least one weighting, or leave the table out for the defaults",
            )));
        }
        for (name, w) in &weightings {
            // A weighting names its recommendation's file.
            if !is_plain_name(name) {
                return Err(invalid(InvalidSetting::new(
                    "weightings",
                    format!("{name:?}"),
                    format!(
                        "names must be non-empty, at most {MAX_NAME_CHARS} of letters, digits, '-', '_', '.'"
                    ),
                )));
            }
            w.validate()
                .map_err(|e| invalid(e.prefixed(&format!("weightings.{name}"))))?;
        }
        let jobs = scenarios.len() * variants.len() * settings.len() * replicas as usize;
        if jobs > MAX_JOBS {
            return Err(invalid(too_many_jobs(jobs)));
        }
        Ok(Self {
            name,
            text: text.to_string(),
            scenarios,
            variants,
            variants_from: if !file.variant.is_empty() {
                VariantSource::List
            } else if file.variants.is_some() {
                VariantSource::Grid
            } else {
                VariantSource::Scenario
            },
            settings,
            replicas,
            specimens,
            weightings,
        })
    }

    /// How an error names variant `i` of the expanded list: `variant[i]`,
    /// the file's own key, for a `[[variant]]` list; `variants (<its
    /// label>)` for a point of a `[variants]` grid, which has no key of
    /// its own (the grid's values are named `variants.<key>` when the
    /// file is read); `the scenario as given` when the file has neither.
    pub fn variant_key(&self, i: usize) -> String {
        match self.variants_from {
            VariantSource::List => format!("variant[{i}]"),
            VariantSource::Grid => {
                let label = self
                    .variants
                    .get(i)
                    .map_or_else(String::new, Perturbation::label);
                format!("variants ({label})")
            }
            VariantSource::Scenario => "the scenario as given".to_string(),
        }
    }
}

/// Where a sweep's variants come from.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum VariantSource {
    /// Neither table: the one variant is the scenario as given.
    Scenario,
    /// A `[variants]` grid.
    Grid,
    /// A `[[variant]]` list.
    List,
}

/// Whether `name` may name a sweep or a weighting, which name files and
/// directories: non-empty, of ASCII letters, digits, '-', '_' and '.', and
/// at most [`MAX_NAME_CHARS`] long.
pub(crate) fn is_plain_name(name: &str) -> bool {
    !name.is_empty()
        && name.len() <= MAX_NAME_CHARS
        && name
            .chars()
            .all(|c| c.is_ascii_alphanumeric() || "-_.".contains(c))
}

/// Longest sweep or weighting name, characters (file names are at most
/// 255 bytes; the result files add a prefix and a suffix).
pub const MAX_NAME_CHARS: usize = 100;

/// A sweep of `jobs` runs, over [`MAX_JOBS`].
fn too_many_jobs(jobs: usize) -> InvalidSetting {
    let count = if jobs == usize::MAX {
        format!("over {} jobs", usize::MAX)
    } else {
        format!("{jobs} jobs")
    };
    InvalidSetting::new(
        "(the sweep)",
        count,
        format!("at most {MAX_JOBS}: shrink the grids"),
    )
}

/// How many variants [`expand_variants`] makes, saturating, without making
/// them: the listed ones, or the product of the grid's list lengths.
fn variant_count(file: &SweepFile) -> usize {
    if !file.variant.is_empty() {
        return file.variant.len();
    }
    let Some(g) = &file.variants else { return 1 };
    fn n<T>(v: &OneOrMany<T>) -> usize {
        match v {
            OneOrMany::One(_) => 1,
            OneOrMany::Many(v) => v.len().max(1),
        }
    }
    [
        n(&g.youngs_modulus_scale),
        n(&g.fracture_toughness_scale),
        n(&g.friction_scale),
        n(&g.size_scale),
        n(&g.knife),
        n(&g.force_noise),
        g.force_bias.len().max(1),
        n(&g.seed),
        n(&g.z0),
        n(&g.blade_budget),
    ]
    .into_iter()
    .fold(1, usize::saturating_mul)
}

/// How many settings [`expand_settings`] makes, saturating, without making
/// them: per entry, its kinds (or a `best-constant` grid's points) times
/// its sets or the product of its grid's list lengths.
fn setting_count(entries: &[ControllerSweep]) -> usize {
    entries
        .iter()
        .map(|entry| {
            let points = if entry.sets.is_empty() {
                grid_axes(&entry.grid)
                    .iter()
                    .map(|(_, values)| values.len().max(1))
                    .fold(1, usize::saturating_mul)
            } else {
                entry.sets.len()
            };
            let kinds = entry.kind.to_vec();
            // An entry that expands to nothing (no kind, a points count
            // out of range) is refused when expanded; counted as one it
            // cannot hide another list's length.
            let per_point = if kinds.iter().any(|k| k == BEST_CONSTANT_KIND) {
                entry.points.unwrap_or(SEARCH_POINTS).clamp(1, MAX_POINTS)
            } else {
                kinds.len().max(1)
            };
            per_point.saturating_mul(points)
        })
        .fold(0, usize::saturating_add)
        .max(1)
}

/// The variants: the listed ones, the grid's cross product, or the
/// scenario as given.
fn expand_variants(file: &SweepFile) -> Result<Vec<Perturbation>, InvalidSetting> {
    let listed = !file.variant.is_empty();
    let variants = match (&file.variants, listed) {
        (Some(_), true) => {
            return Err(InvalidSetting::new(
                "variant",
                format!("{} listed", file.variant.len()),
                "give either a [variants] grid or [[variant]] tables, not both",
            ));
        }
        (None, true) => file.variant.clone(),
        (None, false) => vec![Perturbation::default()],
        (Some(g), false) => {
            // The cross product, the first key slowest: each axis in turn
            // splits every variant built so far.
            let mut out = vec![Perturbation::default()];
            fn axis<T: Clone>(
                out: Vec<Perturbation>,
                values: Vec<T>,
                set: impl Fn(&mut Perturbation, T),
            ) -> Vec<Perturbation> {
                if values.is_empty() {
                    return out;
                }
                out.into_iter()
                    .flat_map(|p| values.iter().map(move |v| (p.clone(), v.clone())))
                    .map(|(mut p, v)| {
                        set(&mut p, v);
                        p
                    })
                    .collect()
            }
            out = axis(out, g.youngs_modulus_scale.to_vec(), |p, v| {
                p.youngs_modulus_scale = v;
            });
            out = axis(out, g.fracture_toughness_scale.to_vec(), |p, v| {
                p.fracture_toughness_scale = v;
            });
            out = axis(out, g.friction_scale.to_vec(), |p, v| p.friction_scale = v);
            out = axis(out, g.size_scale.to_vec(), |p, v| p.size_scale = v);
            out = axis(out, g.knife.to_vec(), |p, v| p.knife = Some(v));
            out = axis(out, g.force_noise.to_vec(), |p, v| p.force_noise = Some(v));
            out = axis(out, g.force_bias.clone(), |p, v| p.force_bias = Some(v));
            out = axis(out, g.seed.to_vec(), |p, v| p.seed = Some(v));
            out = axis(out, g.z0.to_vec(), |p, v| p.z0 = Some(v));
            out = axis(out, g.blade_budget.to_vec(), |p, v| {
                p.blade_budget = Some(v)
            });
            out
        }
    };
    let key = if listed { "variant" } else { "variants" };
    for (i, v) in variants.iter().enumerate() {
        v.validate().map_err(|e| {
            if listed {
                e.prefixed(&format!("{key}[{i}]"))
            } else {
                e.prefixed(key)
            }
        })?;
    }
    for (i, v) in variants.iter().enumerate() {
        if let Some(j) = variants[..i].iter().position(|w| w == v) {
            return Err(InvalidSetting::new(
                key,
                format!("variants {j} and {i}"),
                "are the same: list each variant once",
            ));
        }
    }
    Ok(variants)
}

/// The controller settings of every `[[controllers]]` entry, in order:
/// per entry, per kind, the grid's cross product (or the listed sets).
fn expand_settings(entries: &[ControllerSweep]) -> Result<Vec<ControllerSetting>, InvalidSetting> {
    if entries.is_empty() {
        return Err(InvalidSetting::new(
            "controllers",
            "[]",
            "add at least one [[controllers]] table with a `kind`",
        ));
    }
    let mut out: Vec<ControllerSetting> = Vec::new();
    for (i, entry) in entries.iter().enumerate() {
        let at = |key: &str| format!("controllers[{i}].{key}");
        let kinds = entry.kind.to_vec();
        if kinds.is_empty() {
            return Err(InvalidSetting::new(
                at("kind"),
                "missing",
                "one of mpc, press, slice:XI, force:N, or a list of them; or best-constant",
            ));
        }
        if kinds.iter().any(|k| k == BEST_CONSTANT_KIND) {
            for setting in best_constant_grid(entry, i)? {
                if out.contains(&setting) {
                    return Err(InvalidSetting::new(
                        at("kind"),
                        BEST_CONSTANT_KIND,
                        "the same setting twice: list best-constant once",
                    ));
                }
                out.push(setting);
            }
            continue;
        }
        if let Some(n) = entry.points {
            return Err(InvalidSetting::new(
                at("points"),
                n,
                "only for kind = \"best-constant\"",
            ));
        }
        let points = override_points(entry, i)?;
        for text in &kinds {
            let choice: ControllerChoice = text.parse().map_err(|e: InvalidSetting| {
                InvalidSetting::new(at("kind"), &e.value, e.allowed)
            })?;
            for overrides in &points {
                let setting = ControllerSetting {
                    overrides: overrides.clone(),
                    ..ControllerSetting::fixed(choice)
                };
                if out.contains(&setting) {
                    return Err(InvalidSetting::new(
                        at("kind"),
                        text,
                        "the same setting twice: list each setting once",
                    ));
                }
                out.push(setting);
            }
        }
    }
    Ok(out)
}

/// The settings of a `best-constant` entry (index `i` in the sweep): one
/// per grid point and set of other keys (its `grid` or `sets`, e.g. the
/// `overtravel` every controller of the sweep gets; the point slowest). It
/// stands alone: no other kind, and the ratio is the grid's (no `kind` key,
/// as for every entry).
fn best_constant_grid(
    entry: &ControllerSweep,
    i: usize,
) -> Result<Vec<ControllerSetting>, InvalidSetting> {
    let at = |key: &str| format!("controllers[{i}].{key}");
    if entry.kind.to_vec().len() > 1 {
        return Err(InvalidSetting::new(
            at("kind"),
            BEST_CONSTANT_KIND,
            "stands alone in its [[controllers]] table: no other kind",
        ));
    }
    // No `kind` key: refused by `override_points` for every entry.
    let others = override_points(entry, i)?;
    let points = entry.points.unwrap_or(SEARCH_POINTS);
    if !(2..=MAX_POINTS).contains(&points) {
        return Err(InvalidSetting::new(
            at("points"),
            points,
            format!("must be in 2..={MAX_POINTS}"),
        ));
    }
    Ok((0..points)
        .flat_map(|index| {
            others.iter().map(move |overrides| ControllerSetting {
                overrides: overrides.clone(),
                grid_point: Some(ConstantGridPoint { index, points }),
                ..ControllerSetting::fixed(ControllerChoice::Press)
            })
        })
        .collect())
}

/// An empty list where a sweep lists values (`[variants]`' keys, a
/// controller entry's `kind`, `sets` and `grid` keys) is refused, naming the key: left
/// out, a key keeps the scenario's own value; written empty, it would
/// silently do the same.
fn refuse_empty_lists(table: &toml::Table) -> Result<(), InvalidSetting> {
    let empty = |v: &toml::Value| v.as_array().is_some_and(Vec::is_empty);
    let refuse = |key: String| {
        Err(InvalidSetting::new(
            key,
            "[]",
            "needs at least one value (leave the key out for the scenario's own)",
        ))
    };
    if let Some(variants) = table.get("variants").and_then(toml::Value::as_table) {
        for (k, v) in variants {
            if empty(v) {
                return refuse(format!("variants.{k}"));
            }
        }
    }
    let entries = table.get("controllers").and_then(toml::Value::as_array);
    for (i, entry) in entries.into_iter().flatten().enumerate() {
        for k in ["kind", "sets"] {
            if entry.get(k).is_some_and(empty) {
                return refuse(format!("controllers[{i}].{k}"));
            }
        }
        let grid = entry.get("grid").and_then(toml::Value::as_table);
        if let Some((k, _)) = grid
            .map(grid_axes)
            .unwrap_or_default()
            .into_iter()
            .find(|(_, vs)| vs.is_empty())
        {
            return refuse(format!("controllers[{i}].grid.{k}"));
        }
    }
    Ok(())
}

/// A force bias is three components, [fx, fy, fz]: a longer list would
/// be read as its first three (as a scenario's `force_bias` is refused,
/// a sweep's is).
fn refuse_bias_lengths(table: &toml::Table) -> Result<(), InvalidSetting> {
    let refuse = |key: String, v: &toml::Value| {
        Err(InvalidSetting::new(
            key,
            v,
            "must be three components [fx, fy, fz], N",
        ))
    };
    let grid = table
        .get("variants")
        .and_then(|v| v.get("force_bias"))
        .and_then(toml::Value::as_array);
    for (i, bias) in grid.into_iter().flatten().enumerate() {
        if bias.as_array().is_some_and(|b| b.len() != 3) {
            return refuse(format!("variants.force_bias[{i}]"), bias);
        }
    }
    let listed = table.get("variant").and_then(toml::Value::as_array);
    for (i, v) in listed.into_iter().flatten().enumerate() {
        if let Some(bias) = v.get("force_bias")
            && bias.as_array().is_some_and(|b| b.len() != 3)
        {
            return refuse(format!("variant[{i}].force_bias"), bias);
        }
    }
    Ok(())
}

/// The sets of keys an entry (index `i`) lists: its grid's cross product,
/// or its sets (not both); one empty set for neither.
fn override_points(
    entry: &ControllerSweep,
    i: usize,
) -> Result<Vec<Vec<(String, toml::Value)>>, InvalidSetting> {
    let at = |key: &str| format!("controllers[{i}].{key}");
    if !entry.grid.is_empty() && !entry.sets.is_empty() {
        return Err(InvalidSetting::new(
            at("sets"),
            format!("{} listed", entry.sets.len()),
            "give either a grid or sets, not both",
        ));
    }
    // Each set's keys, and the grid's, in sorted order.
    let key_lists: Vec<Vec<String>> = if entry.sets.is_empty() {
        vec![grid_axes(&entry.grid).into_iter().map(|(k, _)| k).collect()]
    } else {
        entry
            .sets
            .iter()
            .map(|set| flat_keys(set).into_iter().map(|(k, _)| k).collect())
            .collect()
    };
    let table = if entry.sets.is_empty() {
        "grid"
    } else {
        "sets"
    };
    for keys in &key_lists {
        // The controller is the entry's `kind`: a key that replaced it would
        // run another controller under this entry's label.
        if keys.iter().any(|k| k == "kind") {
            return Err(InvalidSetting::new(
                at(table),
                "kind",
                "the controller is the entry's `kind`: give another [[controllers]] entry instead",
            ));
        }
        if let Some(twice) = keys.windows(2).find(|w| w[0] == w[1]) {
            return Err(InvalidSetting::new(
                at(table),
                &twice[0],
                "is given twice (as a dotted key and as a sub-table's): give it once",
            ));
        }
    }
    if !entry.sets.is_empty() {
        return Ok(entry.sets.iter().map(flat_keys).collect());
    }
    // Empty lists were refused with the file ([`refuse_empty_lists`]).
    Ok(cross_product(&grid_axes(&entry.grid)))
}

/// The grid's axes: every leaf key (dotted below the grid table) with its
/// values (a lone value is a list of one), in sorted key order.
fn grid_axes(grid: &toml::Table) -> Vec<(String, Vec<toml::Value>)> {
    let mut axes = Vec::new();
    collect_axes("", grid, &mut axes);
    axes.sort_by(|a, b| a.0.cmp(&b.0));
    axes
}

fn collect_axes(prefix: &str, t: &toml::Table, out: &mut Vec<(String, Vec<toml::Value>)>) {
    for (k, v) in t {
        let key = if prefix.is_empty() {
            k.clone()
        } else {
            format!("{prefix}.{k}")
        };
        match v {
            toml::Value::Table(sub) => collect_axes(&key, sub, out),
            toml::Value::Array(a) => out.push((key, a.clone())),
            other => out.push((key, vec![other.clone()])),
        }
    }
}

/// A listed set's keys, dotted below the set's table, in sorted order.
fn flat_keys(t: &toml::Table) -> Vec<(String, toml::Value)> {
    let mut axes = Vec::new();
    collect_leaves("", t, &mut axes);
    axes.sort_by(|a, b| a.0.cmp(&b.0));
    axes
}

fn collect_leaves(prefix: &str, t: &toml::Table, out: &mut Vec<(String, toml::Value)>) {
    for (k, v) in t {
        let key = if prefix.is_empty() {
            k.clone()
        } else {
            format!("{prefix}.{k}")
        };
        match v {
            toml::Value::Table(sub) => collect_leaves(&key, sub, out),
            other => out.push((key, other.clone())),
        }
    }
}

/// Every combination of the axes' values, the last axis fastest.
fn cross_product(axes: &[(String, Vec<toml::Value>)]) -> Vec<Vec<(String, toml::Value)>> {
    let mut points = vec![Vec::new()];
    for (key, values) in axes {
        points = points
            .into_iter()
            .flat_map(|p: Vec<(String, toml::Value)>| {
                values.iter().map(move |v| {
                    let mut q = p.clone();
                    q.push((key.clone(), v.clone()));
                    q
                })
            })
            .collect();
    }
    points
}

#[cfg(test)]
mod tests {
    use super::*;

    const SWEEP: &str = r#"
        scenarios = ["loop-potato-cuboid"]
        replicas = 2
        [variants]
        youngs_modulus_scale = [0.8, 1.25]
        friction_scale = 1.5
        [[controllers]]
        kind = "mpc"
        [controllers.grid.mpc]
        deformation_weight = [0.0, 100.0]
        stages = [5, 10]
        [[controllers]]
        kind = ["press", "slice:0.5"]
    "#;

    fn parse(text: &str) -> Result<Sweep, ConfigError> {
        Sweep::parse(text, "s.toml", "s", None)
    }

    #[test]
    fn grids_expand_in_order_last_key_fastest() {
        let s = parse(SWEEP).unwrap();
        assert_eq!(s.name, "s");
        assert_eq!(s.replicas, 2);
        assert_eq!(s.variants.len(), 2);
        assert_eq!(s.variants[1].youngs_modulus_scale, 1.25);
        assert_eq!(s.variants[1].friction_scale, 1.5);
        let names: Vec<String> = s
            .settings
            .iter()
            .map(|c| {
                let keys: Vec<String> = c
                    .overrides
                    .iter()
                    .map(|(k, v)| format!("{k}={v}"))
                    .collect();
                format!("{} {}", c.choice, keys.join(" "))
            })
            .collect();
        assert_eq!(
            names,
            [
                "mpc mpc.deformation_weight=0.0 mpc.stages=5",
                "mpc mpc.deformation_weight=0.0 mpc.stages=10",
                "mpc mpc.deformation_weight=100.0 mpc.stages=5",
                "mpc mpc.deformation_weight=100.0 mpc.stages=10",
                "press ",
                "slice:0.5 ",
            ]
        );
        assert_eq!(s.weightings.len(), 5);
    }

    /// A grid or set that names a key twice (dotted and as a sub-table's),
    /// or replaces the entry's controller, is refused: either would run
    /// other settings than the tables say.
    #[test]
    fn a_key_given_twice_or_the_controller_in_a_grid_is_refused() {
        let base = "scenarios = [\"loop-potato-cuboid\"]\n[[controllers]]\nkind = \"mpc\"\n";
        for (table, key, expected) in [
            (
                "[controllers.grid]\n\"mpc.stages\" = [5]\nmpc = { stages = [10] }\n",
                "`controllers[0].grid` = mpc.stages",
                "is given twice",
            ),
            (
                "[[controllers.sets]]\n\"mpc.stages\" = 5\nmpc = { stages = 10 }\n",
                "`controllers[0].sets` = mpc.stages",
                "is given twice",
            ),
            (
                "[controllers.grid]\nkind = [\"press\"]\n",
                "`controllers[0].grid` = kind",
                "give another [[controllers]] entry",
            ),
        ] {
            let e = parse(&format!("{base}{table}")).unwrap_err().to_string();
            assert!(e.contains(key) && e.contains(expected), "{e}");
        }
    }

    #[test]
    fn the_counts_before_expanding_are_the_expanded_lengths() {
        for text in [
            SWEEP,
            r#"
            scenarios = ["loop-potato-cuboid"]
            [[variant]]
            size_scale = 0.9
            [[variant]]
            z0 = 0.03
            [[controllers]]
            kind = "best-constant"
            points = 4
            sets = [{ max_duration = 6.0 }, { max_duration = 5.0 }]
            [[controllers]]
            kind = ["mpc", "press"]
            grid = { max_duration = [4.0, 5.0, 6.0] }
        "#,
        ] {
            let file: SweepFile = toml::from_str(text).unwrap();
            let s = parse(text).unwrap();
            assert_eq!(variant_count(&file), s.variants.len());
            assert_eq!(setting_count(&file.controllers), s.settings.len());
        }
    }

    /// A sweep of 12⁵ variants of the cuboid with `controllers` (its
    /// `[[controllers]]` tables, `{twelve}` standing for a list of twelve
    /// values).
    fn twelve_fold(controllers: &str) -> String {
        let twelve = "[0.5, 0.6, 0.7, 0.8, 0.9, 1.0, 1.1, 1.2, 1.3, 1.4, 1.5, 1.6]";
        format!(
            "scenarios = [\"loop-potato-cuboid\"]\n[variants]\nyoungs_modulus_scale = {twelve}\nfracture_toughness_scale = {twelve}\nfriction_scale = {twelve}\nsize_scale = {twelve}\nforce_noise = {twelve}\n{}",
            controllers.replace("{twelve}", twelve)
        )
    }

    #[test]
    fn a_grid_too_large_to_expand_is_refused_before_it_is_expanded() {
        // 12⁸ ≈ 4.3e8 settings times 12⁵ variants: far more than memory
        // holds if expanded first; and an entry that expands to nothing
        // (no kind) does not hide the variants' 12⁵ from the cap.
        for controllers in [
            "[[controllers]]\nkind = \"mpc\"\n[controllers.grid.mpc]\ntime_weight = {twelve}\nsmoothness_weight = {twelve}\ndeformation_weight = {twelve}\ntrust_region = {twelve}\nmin_saving = {twelve}\nforgetting = {twelve}\nforce_penalty = {twelve}\nmax_slice_push_ratio = {twelve}\n",
            "[[controllers]]\ngrid = { max_duration = 6.0 }\n",
        ] {
            let e = parse(&twelve_fold(controllers)).unwrap_err().to_string();
            assert!(
                e.contains("(the sweep)") && e.contains("shrink the grids"),
                "{e}"
            );
            assert!(!e.contains('\n'), "{e}");
        }
    }

    #[test]
    fn a_setting_over_the_scenario_budgets_is_refused_as_the_file_would_be() {
        // An hour of closed loop at 1 kHz: 3.6e6 rows of series, over the
        // budget a scenario file with this duration is refused for.
        let e = parse(
            r#"
            scenarios = ["loop-potato-cuboid"]
            [[controllers]]
            kind = "press"
            grid = { max_duration = 3600.0 }
        "#,
        )
        .unwrap_err()
        .to_string();
        assert!(
            e.contains("controllers[0]") && e.contains("resources.series"),
            "{e}"
        );
    }

    #[test]
    fn variant_grids_cross_the_place_and_the_blade_first_key_slowest() {
        let s = parse(
            r#"
            scenarios = ["loop-potato-whole"]
            [variants]
            size_scale = [0.8, 1.0]
            z0 = [0.03, 0.06]
            blade_budget = 0.01
            [[controllers]]
            kind = "mpc"
        "#,
        )
        .unwrap();
        let v: Vec<(f64, Option<f64>, Option<f64>)> = s
            .variants
            .iter()
            .map(|p| (p.size_scale, p.z0, p.blade_budget))
            .collect();
        assert_eq!(
            v,
            [
                (0.8, Some(0.03), Some(0.01)),
                (0.8, Some(0.06), Some(0.01)),
                (1.0, Some(0.03), Some(0.01)),
                (1.0, Some(0.06), Some(0.01)),
            ]
        );
        let e = error(
            r#"
            scenarios = ["loop-potato-whole"]
            [variants]
            z0 = 0.15
            [[controllers]]
            kind = "mpc"
        "#,
        );
        assert!(
            e.starts_with("s.toml: `variants.z0` = 0.15: must be in [0.0150, 0.1100] m"),
            "{e}"
        );
    }

    #[test]
    fn a_best_constant_grid_is_one_setting_per_point_and_stands_alone() {
        let base = r#"
            scenarios = ["loop-potato-whole"]
            [[controllers]]
            kind = "mpc"
            [[controllers]]
            kind = "best-constant"
            points = 4
        "#;
        let s = parse(base).unwrap();
        let labels: Vec<String> = s.settings.iter().map(ControllerSetting::label).collect();
        assert_eq!(
            labels,
            [
                "mpc",
                "best-constant:0/3",
                "best-constant:1/3",
                "best-constant:2/3",
                "best-constant:3/3"
            ]
        );
        let e = error(&base.replace("points = 4", "points = 1"));
        assert_eq!(e, "s.toml: `controllers[1].points` = 1: must be in 2..=21");
        let e = error(&base.replace("kind = \"mpc\"", "kind = \"mpc\"\npoints = 3"));
        assert!(
            e.starts_with("s.toml: `controllers[0].points` = 3: only for kind"),
            "{e}"
        );
        let e = error(&base.replace(
            "kind = \"best-constant\"",
            "kind = [\"best-constant\", \"press\"]",
        ));
        assert!(e.contains("stands alone"), "{e}");
        let e = error(&base.replace("points = 4", "grid = { kind = \"press\" }"));
        assert!(e.contains("give another [[controllers]] entry"), "{e}");
        // Other keys cross the points, the point slowest.
        let s = parse(&base.replace(
            "points = 4",
            "points = 2\ngrid = { overtravel = [0.004, 0.01] }",
        ))
        .unwrap();
        let grid: Vec<(String, String)> = s.settings[1..]
            .iter()
            .map(|c| (c.label(), c.overrides[0].1.to_string()))
            .collect();
        let pair = |a: &str, b: &str| (a.to_string(), b.to_string());
        assert_eq!(
            grid,
            [
                pair("best-constant:0/1", "0.004"),
                pair("best-constant:0/1", "0.01"),
                pair("best-constant:1/1", "0.004"),
                pair("best-constant:1/1", "0.01"),
            ]
        );
        let e =
            error(&(base.to_string() + "[[controllers]]\nkind = \"best-constant\"\npoints = 4\n"));
        assert!(e.contains("list best-constant once"), "{e}");
        // Without `points`: compare's six.
        let s = parse(&base.replace("points = 4", "")).unwrap();
        assert_eq!(s.settings.len(), 1 + 6);
    }

    fn error(text: &str) -> String {
        let e = parse(text).unwrap_err().to_string();
        assert!(!e.contains('\n'), "{e}");
        e
    }

    #[test]
    fn bad_sweeps_are_one_line_naming_the_key() {
        let e = error(&SWEEP.replace("replicas = 2", "replicas = 0"));
        assert_eq!(e, "s.toml: `replicas` = 0: must be in 1..=21");
        let e = error(&SWEEP.replace("replicas = 2", "replica = 2"));
        assert!(e.starts_with("s.toml:3:") && e.contains("replica"), "{e}");
        let e = error(&SWEEP.replace("stages = [5, 10]", "stages = [5, 0]"));
        assert_eq!(
            e,
            "s.toml: `controllers[0].controller.mpc.stages` = 0: in 1..=200"
        );
        let e = error(&SWEEP.replace("deformation_weight", "deformation_weigth"));
        assert!(
            e.starts_with("s.toml: `controllers[0].controller.mpc.deformation_weigth` = ")
                && e.contains("unknown field"),
            "{e}"
        );
        let e = error(&SWEEP.replace("friction_scale = 1.5", "friction_scale = 50.0"));
        assert_eq!(
            e,
            "s.toml: `variants.friction_scale` = 50: must be in [0.1, 10]"
        );
        let e = error(&SWEEP.replace("\"slice:0.5\"", "\"slice:-1\""));
        assert!(
            e.starts_with("s.toml: `controllers[1].kind` = slice:-1: "),
            "{e}"
        );
        let e = error(&SWEEP.replace("loop-potato-cuboid", "no-such-scenario"));
        assert!(
            e.starts_with("s.toml: `scenarios[0]` = \"no-such-scenario\": "),
            "{e}"
        );
        let e = error("scenarios = [\"loop-potato-cuboid\"]\n");
        assert!(e.contains("`controllers` = []"), "{e}");
        let e = error(&(SWEEP.to_string() + "[weightings.odd]\nwork = -1.0\n"));
        assert!(e.contains("`weightings.odd.work` = -1"), "{e}");
        for bias in [
            "[variants]\nforce_bias = [[1.0, 2.0, 3.0, 4.0]]",
            "[[variant]]\nforce_bias = [1.0, 2.0, 3.0, 4.0]",
        ] {
            let text = format!(
                "scenarios = [\"loop-potato-cuboid\"]\n[[controllers]]\nkind = \"press\"\n{bias}\n"
            );
            let e = error(&text);
            assert!(
                e.contains("force_bias") && e.contains("three components"),
                "{e}"
            );
        }
        // A weighting names its recommendation's file.
        let e = error(&(SWEEP.to_string() + "[weightings.\"a/b\"]\nwork = 1.0\n"));
        assert!(e.contains("`weightings` = \"a/b\": names must be"), "{e}");
        let e = error(&format!("name = \"{}\"\n{SWEEP}", "a".repeat(101)));
        assert!(e.contains("`name` = ") && e.contains("at most 100"), "{e}");
        let e = error(&SWEEP.replace(
            "kind = [\"press\", \"slice:0.5\"]",
            "kind = [\"press\", \"press\"]",
        ));
        assert!(e.contains("the same setting twice"), "{e}");
    }
}
