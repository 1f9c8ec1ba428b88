//! The job list of a sweep: every (scenario, controller setting, variant,
//! replica), in a fixed order, each named by a hash of what it runs.
//!
//! Order: scenarios as listed; within one, the controller settings as the
//! sweep expands them; within one setting, the variants; within one
//! variant, the replicas (each its own specimen of the variant when the
//! sweep has `[specimens]`). The order and every job's scenario depend only on
//! the sweep file and the scenarios it names, so every machine and every
//! shard builds the same list.
//!
//! A job's id is the first 16 hex digits of the SHA-1 of shearcut's version,
//! the job's fully resolved scenario (variant and setting applied: TOML,
//! every number in its exact shortest form, including the noise seed; a
//! mesh object and a surrogate file by the digest of the file's bytes, not
//! its path) and its replica. Equal ids are equal runs: a re-run finds a
//! job's result under its id whatever else the sweep file gained or lost,
//! and wherever the checkout and its files lie.

use std::collections::HashMap;
use std::path::{Path, PathBuf};

use serde::{Deserialize, Serialize};
use shearcut_sim::capped_read::read_capped;
use shearcut_sim::resource_budget::{CONFIG_FILE_BYTES, MESH_FILE_BYTES};
use shearcut_sim::{InvalidSetting, ObjectShape};

use crate::commands::check::resolved_toml;
use crate::controller_choice::ControllerChoice;
use crate::error::ConfigError;
use crate::run_replica::RunReplica;
use crate::scenario::Scenario;
use crate::surrogates::{built_in_surrogate, surrogate_named};
use crate::tune::controller_setting::{ControllerSetting, controller_cells, value_cell};
use crate::tune::perturbation::{Perturbation, VARIANT_COLUMNS, check_on_edge};
use crate::tune::sweep_file::Sweep;

/// Columns naming a job, first in every results table.
pub const JOB_COLUMNS: [&str; 7] = [
    "job",
    "id",
    "scenario",
    "setting",
    "variant",
    "replica",
    "controller",
];

/// What a job is, as recorded in `jobs.json` (enough to tabulate and
/// analyse results without the scenarios).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct JobRecord {
    /// Position in the job list.
    pub index: usize,
    /// Hash of the run (see the module doc).
    pub id: String,
    /// Index of the scenario in the sweep.
    pub scenario: usize,
    /// Index of the controller setting in the sweep.
    pub setting: usize,
    /// Index of the variant in the sweep.
    pub variant: usize,
    /// The replica.
    pub replica: u32,
    /// The controller (`mpc`, `slice:0.5`, …; a best-constant grid point
    /// by its name, `best-constant:i/n`: its ratio on the job's variant is
    /// the `controller.kind` cell).
    pub controller: String,
    /// The settings' cells, aligned with [`JobCatalog::setting_columns`].
    pub cells: Vec<String>,
}

/// One controller setting on one scenario, as `jobs.json` keeps it.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct SettingRecord {
    /// The controller (a best-constant grid point by its name).
    pub controller: String,
    /// Whether the setting is a point of the best-constant grid
    /// ([`crate::tune::constant_grid`]).
    #[serde(default)]
    pub best_constant: bool,
    /// The keys the sweep set, `key = value` each (dotted below
    /// `[controller]`).
    pub overrides: Vec<String>,
    /// The scenario's whole `[controller]` table under this setting (no
    /// variant), TOML: what a recommendation writes out.
    pub controller_toml: String,
}

/// Everything about a sweep's jobs the results need, written to
/// `jobs.json` in every result directory (shards of one sweep write
/// identical files; `tune merge` checks that they do).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct JobCatalog {
    /// The sweep's name.
    pub sweep: String,
    /// The scenarios' names.
    pub scenarios: Vec<String>,
    /// The variants' names ([`Perturbation::label`]), in the sweep's order.
    #[serde(default)]
    pub variants: Vec<String>,
    /// Per scenario, per setting.
    pub settings: Vec<Vec<SettingRecord>>,
    /// The settings' columns: the variant's, then every `controller.*` key.
    pub setting_columns: Vec<String>,
    /// The jobs, in order.
    pub jobs: Vec<JobRecord>,
    /// The sweep's weightings, by name.
    pub weightings: std::collections::BTreeMap<String, crate::tune::weighting::Weighting>,
}

/// One runnable job.
#[derive(Debug, Clone)]
pub struct Job {
    /// Its record.
    pub record: JobRecord,
    /// The scenario to run: variant and setting applied.
    pub scenario: Scenario,
    /// The controller.
    pub choice: ControllerChoice,
    /// The replica.
    pub replica: RunReplica,
}

/// The jobs of a sweep and their catalogue.
#[derive(Debug, Clone)]
pub struct JobList {
    /// The jobs, in order.
    pub jobs: Vec<Job>,
    /// Their catalogue.
    pub catalog: JobCatalog,
}

impl JobCatalog {
    /// Checks what the tables and `tune merge` rely on in a catalogue read
    /// back from `jobs.json` (a file anyone may edit): the sweep's name is
    /// one a sweep file allows, every job's index is its place, its
    /// scenario, setting and variant index into the catalogue's lists, its
    /// cells match the columns, and its id is a job id (16 hexadecimal
    /// digits: it names the job's row file). The error says which job and
    /// what is wrong.
    pub fn check(&self) -> Result<(), String> {
        if !crate::tune::sweep_file::is_plain_name(&self.sweep) {
            return Err(format!(
                "sweep {:?}: a name of at most {} letters, digits, '-', '_', '.'",
                self.sweep,
                crate::tune::sweep_file::MAX_NAME_CHARS
            ));
        }
        // Scenario and weighting names name the analysis' files.
        for name in &self.scenarios {
            crate::scenario::check_name(name).map_err(|e| format!("scenario {e}"))?;
        }
        for name in self.weightings.keys() {
            if !crate::tune::sweep_file::is_plain_name(name) {
                return Err(format!("weighting {name:?}: a plain name"));
            }
        }
        if self.settings.len() != self.scenarios.len() {
            return Err(format!(
                "{} settings lists for {} scenarios",
                self.settings.len(),
                self.scenarios.len()
            ));
        }
        for (i, j) in self.jobs.iter().enumerate() {
            let wrong = |what: String| Err(format!("job {i}: {what}"));
            if j.index != i {
                return wrong(format!("index {} at place {i}", j.index));
            }
            if j.id.len() != 16 || !j.id.chars().all(|c| c.is_ascii_hexdigit()) {
                return wrong(format!("id {:?} is not 16 hexadecimal digits", j.id));
            }
            let Some(settings) = self.settings.get(j.scenario) else {
                return wrong(format!(
                    "scenario {} of {}",
                    j.scenario,
                    self.scenarios.len()
                ));
            };
            if j.setting >= settings.len() {
                return wrong(format!("setting {} of {}", j.setting, settings.len()));
            }
            // A catalogue without its variants' names has none to index.
            if !self.variants.is_empty() && j.variant >= self.variants.len() {
                return wrong(format!("variant {} of {}", j.variant, self.variants.len()));
            }
            if j.cells.len() != self.setting_columns.len() {
                return wrong(format!(
                    "{} cells for {} columns",
                    j.cells.len(),
                    self.setting_columns.len()
                ));
            }
        }
        Ok(())
    }
}

impl JobList {
    /// Expands `sweep` into its jobs; `origin` names the sweep in errors.
    pub fn new(sweep: &Sweep, origin: &str) -> Result<Self, ConfigError> {
        let invalid = |setting: InvalidSetting| ConfigError::Invalid {
            path: origin.to_string(),
            setting,
        };
        let mut jobs = Vec::new();
        let mut file_digests = HashMap::new();
        let mut settings = Vec::new();
        let mut columns: Vec<String> = VARIANT_COLUMNS.iter().map(|c| c.to_string()).collect();
        let mut job_cells: Vec<Vec<(String, String)>> = Vec::new();
        for (si, base) in sweep.scenarios.iter().enumerate() {
            // Replica r's specimen of each variant (the variant itself
            // unless the sweep spreads its specimens), applied once: the
            // variants alone were checked when the sweep was read, so an
            // error here is a specimen's.
            let mut specimens = Vec::new();
            for (vi, variant) in sweep.variants.iter().enumerate() {
                for r in 0..sweep.replicas {
                    let specimen = sweep.specimens.specimen_of(variant, r);
                    let perturbed = specimen.apply_for(base, &sweep.settings).map_err(|e| {
                        invalid(e.prefixed(&format!(
                            "{} on {}, replica {r}'s specimen",
                            sweep.variant_key(vi),
                            base.name
                        )))
                    })?;
                    specimens.push((vi, r, specimen, perturbed));
                }
            }
            let mut of_scenario = Vec::new();
            for (ki, setting) in sweep.settings.iter().enumerate() {
                let at = |e: InvalidSetting| {
                    invalid(e.prefixed(&format!("setting {ki} on {}", base.name)))
                };
                let nominal = setting.apply(base).map_err(at)?;
                // A surrogate the setting names must open here (a path is
                // relative to the working directory), not fail every job.
                if let Some(name) = &nominal.controller.surrogate {
                    surrogate_named(name).map_err(at)?;
                }
                of_scenario.push(setting_record(setting, &nominal));
                for &(vi, r, ref specimen, ref perturbed) in &specimens {
                    let scenario = setting.apply(perturbed).map_err(at)?;
                    if setting.sets_blade_budget() {
                        check_on_edge(&scenario).map_err(|e| {
                            // Replica r's specimen, where it is not its variant.
                            let replica = if *specimen == sweep.variants[vi] {
                                String::new()
                            } else {
                                format!(", replica {r}'s specimen")
                            };
                            invalid(
                                InvalidSetting {
                                    key: "z0, with its blade_budget".to_string(),
                                    ..e
                                }
                                .prefixed(&format!(
                                    "setting {ki} on {}, {}{replica}",
                                    base.name,
                                    sweep.variant_key(vi)
                                )),
                            )
                        })?;
                    }
                    let mut cells: Vec<(String, String)> = VARIANT_COLUMNS
                        .iter()
                        .map(|c| c.to_string())
                        .zip(specimen.cells(&scenario))
                        .collect();
                    cells.extend(controller_cells(&scenario));
                    for (key, _) in &cells {
                        if !columns.contains(key) {
                            columns.push(key.clone());
                        }
                    }
                    let index = jobs.len();
                    let id = job_id(&identity_toml(&scenario, &mut file_digests), r);
                    jobs.push(Job {
                        record: JobRecord {
                            index,
                            id,
                            scenario: si,
                            setting: ki,
                            variant: vi,
                            replica: r,
                            controller: setting.label(),
                            cells: Vec::new(),
                        },
                        choice: scenario.controller.kind,
                        scenario,
                        replica: RunReplica { index: r },
                    });
                    job_cells.push(cells);
                }
            }
            settings.push(of_scenario);
        }
        for (job, cells) in jobs.iter_mut().zip(&job_cells) {
            job.record.cells = columns
                .iter()
                .map(|c| {
                    cells
                        .iter()
                        .find(|(k, _)| k == c)
                        .map_or(String::new(), |(_, v)| v.clone())
                })
                .collect();
        }
        for (i, job) in jobs.iter().enumerate() {
            if let Some(j) = jobs[..i].iter().position(|o| o.record.id == job.record.id) {
                return Err(invalid(InvalidSetting::new(
                    "(the sweep)",
                    format!("jobs {j} and {i}"),
                    "run the same scenario, controller, settings and replica: list each once",
                )));
            }
        }
        let catalog = JobCatalog {
            sweep: sweep.name.clone(),
            scenarios: sweep.scenarios.iter().map(|s| s.name.clone()).collect(),
            variants: sweep.variants.iter().map(Perturbation::label).collect(),
            settings,
            setting_columns: columns,
            jobs: jobs.iter().map(|j| j.record.clone()).collect(),
            weightings: sweep.weightings.clone(),
        };
        Ok(Self { jobs, catalog })
    }
}

/// The record of `setting` on a scenario, `applied` being the scenario
/// under it.
fn setting_record(setting: &ControllerSetting, applied: &Scenario) -> SettingRecord {
    #[derive(Serialize)]
    struct ControllerTable<'a> {
        controller: &'a crate::controller_settings::ControllerSettings,
    }
    SettingRecord {
        controller: setting.label(),
        best_constant: setting.grid_point.is_some(),
        overrides: setting
            .overrides
            .iter()
            .map(|(k, v)| format!("{k} = {}", value_cell(v)))
            .collect(),
        controller_toml: toml::to_string_pretty(&ControllerTable {
            controller: &applied.controller,
        })
        .unwrap_or_default(),
    }
}

/// The text a job's id hashes: the resolved scenario, with a mesh object's
/// path and a surrogate file's path (`[controller] surrogate` that is no
/// built-in name) replaced by digests of the files' bytes (`sha1:…`), so
/// that the id follows what the files hold, not where the checkout or the
/// shared file system puts them: a file rewritten in place is a new run. A
/// file that cannot be read keeps its path (its runs end with the error).
/// `digests` holds the digest of each path read.
fn identity_toml(s: &Scenario, digests: &mut HashMap<PathBuf, String>) -> String {
    let mesh = match &s.object {
        ObjectShape::Mesh { path } => file_digest(path, MESH_FILE_BYTES, digests),
        _ => None,
    };
    let surrogate = s
        .controller
        .surrogate
        .as_deref()
        .filter(|name| built_in_surrogate(name).is_none())
        .and_then(|name| file_digest(Path::new(name), CONFIG_FILE_BYTES, digests));
    if mesh.is_none() && surrogate.is_none() {
        return resolved_toml(s);
    }
    let mut by_content = s.clone();
    if let Some(d) = mesh {
        by_content.object = ObjectShape::Mesh {
            path: PathBuf::from(d),
        };
    }
    if surrogate.is_some() {
        by_content.controller.surrogate = surrogate;
    }
    resolved_toml(&by_content)
}

/// `sha1:<hex>` of the bytes of the file at `path` (memoised in
/// `digests`); None if it cannot be read or holds more than `cap` bytes
/// (its reader refuses it too).
fn file_digest(path: &Path, cap: u64, digests: &mut HashMap<PathBuf, String>) -> Option<String> {
    if let Some(d) = digests.get(path) {
        return Some(d.clone());
    }
    let bytes = read_capped(path, cap).ok()?;
    let d = format!("sha1:{}", sha1_smol::Sha1::from(bytes).digest());
    digests.insert(path.to_path_buf(), d.clone());
    Some(d)
}

/// The id of the run of resolved scenario `resolved` as replica `replica`.
pub fn job_id(resolved: &str, replica: u32) -> String {
    let mut h = sha1_smol::Sha1::new();
    h.update(concat!("shearcut ", env!("CARGO_PKG_VERSION"), "\n").as_bytes());
    h.update(resolved.as_bytes());
    h.update(format!("\nreplica = {replica}\n").as_bytes());
    h.digest().to_string()[..16].to_string()
}

/// The job list of the sweep file text `text` (named `s.toml`), for tests.
#[cfg(test)]
pub(crate) fn list_of(text: &str) -> JobList {
    let sweep = Sweep::parse(text, "s.toml", "s", None).unwrap();
    JobList::new(&sweep, "s.toml").unwrap()
}

#[cfg(test)]
mod tests {
    use super::*;

    const SWEEP: &str = r#"
        scenarios = ["loop-potato-cuboid", "loop-potato-whole"]
        replicas = 2
        [variants]
        youngs_modulus_scale = [0.8, 1.25]
        [[controllers]]
        kind = "mpc"
        grid = { "mpc.deformation_weight" = [0.0, 100.0] }
        [[controllers]]
        kind = "press"
    "#;

    /// A mesh object's job is named by the mesh's bytes: the same file in
    /// another directory (a moved checkout, another node's mount) keeps the
    /// id; other bytes at the same path change it.
    #[test]
    fn a_mesh_or_surrogate_files_job_id_follows_its_bytes_not_its_path() {
        let root = std::env::temp_dir().join(format!("shearcut-mesh-id-{}", std::process::id()));
        let tetrahedron = |a: &str| {
            format!(
                "v 0 0 0\nv {a} 0 0\nv 0 {a} 0\nv 0 0 {a}\nf 1 3 2\nf 1 2 4\nf 2 3 4\nf 1 4 3\n"
            )
        };
        let scenario_at = |dir: &str, a: &str| {
            let d = root.join(dir);
            std::fs::create_dir_all(&d).unwrap();
            let mesh = d.join("tetrahedron.obj");
            std::fs::write(&mesh, tetrahedron(a)).unwrap();
            let text = format!(
                "[material]\npreset = \"potato-cuboid\"\n[knife]\npreset = \"straight\"\n\
                 [object]\nkind = \"mesh\"\npath = \"{}\"\n",
                mesh.display()
            );
            Scenario::parse(&text, "t", "t").unwrap()
        };
        let id = |s: &Scenario| job_id(&identity_toml(s, &mut HashMap::new()), 0);
        let (a, b) = (scenario_at("a", "0.03"), scenario_at("b", "0.03"));
        assert_ne!(resolved_toml(&a), resolved_toml(&b));
        assert_eq!(id(&a), id(&b));
        let c = scenario_at("b", "0.04");
        assert_ne!(id(&c), id(&a));
        // A surrogate file likewise; a built-in surrogate and a scenario
        // with neither file hash their resolved text as it is.
        let mut with_file = Scenario::load("loop-potato-whole").unwrap();
        let mut built_in = with_file.clone();
        built_in.controller.surrogate = Some("potato-whole-chef".into());
        assert_eq!(
            identity_toml(&built_in, &mut HashMap::new()),
            resolved_toml(&built_in)
        );
        let surrogate = root.join("a").join("fit.toml");
        std::fs::write(&surrogate, "[fit]\n").unwrap();
        with_file.controller.surrogate = Some(surrogate.display().to_string());
        let before = id(&with_file);
        std::fs::write(&surrogate, "[fit]\nrefitted = true\n").unwrap();
        assert_ne!(id(&with_file), before);
        // Unreadable: the path names it (its runs end with the error).
        std::fs::remove_dir_all(&root).unwrap();
        assert_eq!(identity_toml(&c, &mut HashMap::new()), resolved_toml(&c));
        assert_eq!(
            identity_toml(&with_file, &mut HashMap::new()),
            resolved_toml(&with_file)
        );
    }

    /// A specimen that leaves the edge refuses the sweep, naming its
    /// variant and replica.
    #[test]
    fn a_specimen_off_the_edge_is_named_by_its_variant_and_replica() {
        // The 90 mm half potato at z0 105 mm on the chef's 200 mm edge: a
        // specimen over 1.056 times its size runs past the tip.
        let sweep = Sweep::parse(
            "scenarios = [\"loop-potato-whole\"]\nreplicas = 6\n[variants]\nz0 = 0.105\n\
             [specimens]\nsize = 0.2\n[[controllers]]\nkind = \"press\"\n",
            "s.toml",
            "s",
            None,
        )
        .unwrap();
        let e = JobList::new(&sweep, "s.toml").unwrap_err().to_string();
        assert!(
            e.contains("`variants (z0 105 mm) on loop-potato-whole, replica ")
                && e.contains("'s specimen.z0` = 0.105: must be"),
            "{e}"
        );
        // With a blade budget in every setting, each job is checked with
        // it: replica 0 (the variant as given) fits the edge, a larger
        // specimen is named by its replica.
        let budgeted = sweep.text.replace(
            "kind = \"press\"",
            "kind = \"slice:1.5\"\ngrid = { blade_budget = 0.03 }",
        );
        let budgeted = Sweep::parse(&budgeted, "s.toml", "s", None).unwrap();
        let e = JobList::new(&budgeted, "s.toml").unwrap_err().to_string();
        assert!(
            e.contains("`setting 0 on loop-potato-whole, variants (z0 105 mm), replica ")
                && e.contains("'s specimen.z0, with its blade_budget` = 0.105: must be in [0.0300"),
            "{e}"
        );
        // A listed variant is named by its own key.
        let listed = sweep.text.replace("[variants]", "[[variant]]");
        let listed = Sweep::parse(&listed, "s.toml", "s", None).unwrap();
        let e = JobList::new(&listed, "s.toml").unwrap_err().to_string();
        assert!(
            e.contains("`variant[0] on loop-potato-whole, replica "),
            "{e}"
        );
        // Within the edge, every specimen runs.
        let text = sweep.text.replace("z0 = 0.105", "z0 = 0.05");
        let sweep = Sweep::parse(&text, "s.toml", "s", None).unwrap();
        assert_eq!(JobList::new(&sweep, "s.toml").unwrap().jobs.len(), 6);
    }

    #[test]
    fn a_blade_budget_from_a_grid_keeps_each_jobs_object_on_the_edge() {
        // The half potato with 30 mm of blade: z0 must be at least 30 mm.
        let text = |z0: &str| {
            format!(
                "scenarios = [\"loop-potato-whole\"]\n[variants]\nz0 = {z0}\n[[controllers]]\nkind = \"slice:1.5\"\ngrid = {{ blade_budget = 0.03 }}\n"
            )
        };
        let sweep = Sweep::parse(&text("[0.04, 0.06]"), "s.toml", "s", None).unwrap();
        assert_eq!(JobList::new(&sweep, "s.toml").unwrap().jobs.len(), 2);
        let sweep = Sweep::parse(&text("[0.04, 0.02]"), "s.toml", "s", None).unwrap();
        let e = JobList::new(&sweep, "s.toml").unwrap_err().to_string();
        assert!(
            e.contains("`setting 0 on loop-potato-whole, variants (z0 20 mm).z0, with its blade_budget` = 0.02: must be in [0.0300")
                && e.contains("stays on the"),
            "{e}"
        );
        // z0 10 mm is off the edge with the scenario's 15 mm of blade, on
        // it with 5 mm: a sweep whose every setting sets 5 mm runs it; one
        // with a setting that keeps the scenario's budget is refused.
        let five = "scenarios = [\"loop-potato-whole\"]\n[variants]\nz0 = 0.01\n[[controllers]]\nkind = \"slice:0.2\"\ngrid = { blade_budget = 0.005 }\n";
        let sweep = Sweep::parse(five, "s.toml", "s", None).unwrap();
        let list = JobList::new(&sweep, "s.toml").unwrap();
        assert_eq!(list.jobs.len(), 1);
        assert_eq!(list.jobs[0].scenario.controller.blade_budget, Some(0.005));
        let mixed = format!("{five}[[controllers]]\nkind = \"press\"\n");
        let e = Sweep::parse(&mixed, "s.toml", "s", None)
            .unwrap_err()
            .to_string();
        assert!(
            e.contains("`variants.z0` = 0.01: must be in [0.0150"),
            "{e}"
        );
        // Without variants, the scenario as given: z0 20 mm with 30 mm of blade.
        let none = "scenarios = [\"loop-potato-whole\"]\n[[controllers]]\nkind = \"slice:1.5\"\ngrid = { blade_budget = 0.03 }\n";
        let sweep = Sweep::parse(none, "s.toml", "s", None).unwrap();
        let e = JobList::new(&sweep, "s.toml").unwrap_err().to_string();
        assert!(
            e.contains("`setting 0 on loop-potato-whole, the scenario as given.z0, with its blade_budget` = 0.02"),
            "{e}"
        );
    }

    #[test]
    fn a_catalogue_read_back_is_checked_before_anything_indexes_with_it() {
        let catalog = list_of(SWEEP).catalog;
        assert_eq!(catalog.check(), Ok(()));
        let broken = |edit: &dyn Fn(&mut JobCatalog)| {
            let mut c = catalog.clone();
            edit(&mut c);
            c.check().unwrap_err()
        };
        let e = broken(&|c| c.jobs[3].setting = 7);
        assert!(e.starts_with("job 3: setting 7 of 3"), "{e}");
        let e = broken(&|c| c.jobs[0].scenario = 2);
        assert!(e.starts_with("job 0: scenario 2 of 2"), "{e}");
        let e = broken(&|c| c.jobs[1].variant = 5);
        assert!(e.starts_with("job 1: variant 5 of 2"), "{e}");
        let e = broken(&|c| c.jobs[2].id = "../../outside".to_string());
        assert!(e.contains("not 16 hexadecimal digits"), "{e}");
        let e = broken(&|c| c.jobs[2].index = 9);
        assert!(e.starts_with("job 2: index 9"), "{e}");
        let e = broken(&|c| c.jobs[4].cells.pop().map_or((), drop));
        assert!(e.contains("cells for"), "{e}");
        let e = broken(&|c| c.sweep = "../x/y".to_string());
        assert!(e.starts_with("sweep"), "{e}");
        let e = broken(&|c| c.scenarios[1] = "../../x".to_string());
        assert!(
            e.starts_with("scenario") && e.contains("path separators"),
            "{e}"
        );
        let e = broken(&|c| {
            let w = *c.weightings.values().next().unwrap();
            c.weightings.insert("../y".to_string(), w);
        });
        assert!(e.starts_with("weighting \"../y\""), "{e}");
        // Without its variants' names (an older catalogue) a job's
        // variant index is not checked against them.
        let mut c = catalog.clone();
        c.variants.clear();
        assert_eq!(c.check(), Ok(()));
    }

    #[test]
    fn a_grid_point_runs_its_share_of_each_variants_cap() {
        // The half potato (25 mm deep): 15 and 5 mm of blade, caps 0.6 and
        // 0.2; point 1 of 0..=2 is half of each.
        let list = list_of(
            r#"
            scenarios = ["loop-potato-whole-realtime"]
            [variants]
            blade_budget = [0.015, 0.005]
            [[controllers]]
            kind = "best-constant"
            points = 3
            "#,
        );
        let ratios: Vec<(String, String)> = list
            .jobs
            .iter()
            .map(|j| (j.record.controller.clone(), j.choice.to_string()))
            .collect();
        let pair = |a: &str, b: &str| (a.to_string(), b.to_string());
        assert_eq!(
            ratios,
            [
                pair("best-constant:0/2", "press"),
                pair("best-constant:0/2", "press"),
                pair("best-constant:1/2", "slice:0.3"),
                pair("best-constant:1/2", "slice:0.1"),
                pair("best-constant:2/2", "slice:0.6"),
                pair("best-constant:2/2", "slice:0.2"),
            ]
        );
        assert_eq!(list.catalog.variants, ["blade 15 mm", "blade 5 mm"]);
        assert!(list.catalog.settings[0].iter().all(|s| s.best_constant));
        let kind = list
            .catalog
            .setting_columns
            .iter()
            .position(|c| c == "controller.kind")
            .unwrap();
        assert_eq!(list.jobs[3].record.cells[kind], "slice:0.1");
    }

    #[test]
    fn the_list_is_ordered_and_its_ids_are_stable_and_distinct() {
        let sweep = Sweep::parse(SWEEP, "s.toml", "s", None).unwrap();
        let a = JobList::new(&sweep, "s.toml").unwrap();
        let b = JobList::new(&sweep, "s.toml").unwrap();
        assert_eq!(a.catalog, b.catalog);
        // 2 scenarios × 3 settings × 2 variants × 2 replicas.
        assert_eq!(a.jobs.len(), 24);
        let order: Vec<(usize, usize, usize, u32)> = a
            .jobs
            .iter()
            .map(|j| {
                (
                    j.record.scenario,
                    j.record.setting,
                    j.record.variant,
                    j.record.replica,
                )
            })
            .collect();
        let mut sorted = order.clone();
        sorted.sort();
        assert_eq!(order, sorted, "scenario, setting, variant, replica");
        let j = &a.jobs[5];
        assert_eq!(
            (j.record.setting, j.record.variant, j.record.replica),
            (1, 0, 1)
        );
        assert_eq!(j.scenario.controller.mpc.deformation_weight, 100.0);
        assert_eq!(j.scenario.material.youngs_modulus, 0.8 * 2.0e6);
        let col = |name: &str| {
            a.catalog
                .setting_columns
                .iter()
                .position(|c| c == name)
                .unwrap()
        };
        assert_eq!(
            j.record.cells[col("controller.mpc.deformation_weight")],
            "100.0"
        );
        assert_eq!(j.record.cells[col("variant.youngs_modulus_scale")], "0.8");
        // A job's id does not depend on what else the sweep holds.
        let alone = list_of(
            &SWEEP
                .replace("\"loop-potato-cuboid\", ", "")
                .replace("[0.8, 1.25]", "0.8"),
        );
        let whole_first = &a.jobs[12];
        assert_eq!(alone.jobs[0].record.id, whole_first.record.id);
        let mut ids: Vec<&str> = a.jobs.iter().map(|j| j.record.id.as_str()).collect();
        ids.sort_unstable();
        ids.dedup();
        assert_eq!(ids.len(), 24);
    }

    #[test]
    fn specimens_make_each_replica_another_object_and_leave_replica_zero_as_it_was() {
        let plain = list_of(SWEEP);
        let spread = list_of(&SWEEP.replace(
            "replicas = 2\n",
            "replicas = 2\n[specimens]\nsize = 0.05\nmaterial = 0.1\n",
        ));
        assert_eq!(spread.jobs.len(), plain.jobs.len());
        let f = crate::tune::specimen_spread::SpecimenSpread {
            size: 0.05,
            material: 0.1,
        }
        .factors(1);
        for (p, s) in plain.jobs.iter().zip(&spread.jobs) {
            if p.record.replica == 0 {
                // The variant as given: the same run under the same id.
                assert_eq!(p.record.id, s.record.id);
                continue;
            }
            assert_ne!(p.record.id, s.record.id);
            let (pm, sm) = (&p.scenario.material, &s.scenario.material);
            // Products in another order: equal to rounding.
            let near = |a: f64, b: f64| (a / b - 1.0).abs() < 1e-14;
            assert!(near(
                sm.youngs_modulus,
                pm.youngs_modulus * f.youngs_modulus
            ));
            assert!(near(
                sm.fracture_toughness,
                pm.fracture_toughness * f.fracture_toughness
            ));
            // Every controller meets the same specimen; the MPC keeps the
            // nominal material's surrogate.
            assert_eq!(
                s.scenario.controller.surrogate,
                p.scenario.controller.surrogate
            );
        }
        // The half potato's target scales with the specimen.
        fn replica_one(list: &JobList) -> &Job {
            let of_whole = |j: &&Job| j.record.scenario == 1 && j.record.replica == 1;
            list.jobs.iter().find(of_whole).unwrap()
        }
        let (whole, nominal) = (replica_one(&spread), replica_one(&plain));
        let depth = |j: &Job| j.scenario.motion.depth.unwrap();
        assert!((depth(whole) / depth(nominal) - f.size).abs() < 1e-12);
        // The variant's cells show the specimen cut.
        let col = spread
            .catalog
            .setting_columns
            .iter()
            .position(|c| c == "variant.size_scale")
            .unwrap();
        assert_eq!(
            whole.record.cells[col],
            crate::tune::perturbation::float_cell(f.size)
        );
        let e = Sweep::parse(
            &SWEEP.replace("replicas = 2\n", "replicas = 2\n[specimens]\nsize = 0.5\n"),
            "s.toml",
            "s",
            None,
        )
        .unwrap_err();
        assert_eq!(
            e.to_string(),
            "s.toml: `specimens.size` = 0.5: must be in [0, 0.2]"
        );
    }
}
