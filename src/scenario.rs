//! Scenario files: what is cut, with which knife, how, and in which loop.
//!
//! A scenario is a TOML file (see `config/scenarios/` and the README's
//! "Config format"). Every table is `deny_unknown_fields`; after parsing, the
//! scenario is resolved (presets expanded) and validated, and every error names
//! the key, the value and what is allowed.
//!
//! Validation has three layers, all run on load and by `shearcut check`:
//! every number against its physical range (`shearcut_sim::physical_range`;
//! the model's settings check their own, this module those of the loop, the
//! plant's sensor and the controller), every array exactly as long as its
//! key takes (`shearcut_sim::array_lengths`), and the run's resource
//! estimate (section meshes, series length) against its budget
//! (`shearcut_sim::resource_budget`). A scenario file is read with a size
//! cap and only as UTF-8 TOML; a mesh it names is read and checked too.

use std::path::{Path, PathBuf};

use serde::{Deserialize, Serialize};
use shearcut_plant::PlantSettings;
use shearcut_sim::arm::ArmLimits;
use shearcut_sim::array_lengths::check_array_lengths;
use shearcut_sim::capped_read::read_capped_text;
use shearcut_sim::physical_range::{
    ARM_ACCELERATION, ARM_JERK, ARM_VELOCITY, EDGE_OFFSET, FORCE, FORCE_NOISE, KNIFE_SPEED,
    MAX_CUTS, MIN_STEP_PER_ROW, MISSED_COMMANDS, MOTION_STEP, OBJECT_SIZE, PLANT_DISTANCE, RATE,
    RUN_DURATION, SENSOR_BIAS, SLICE_PUSH_RATIO, TORQUE_NOISE, UPDATE_DISTANCE, check_count,
};
use shearcut_sim::resource_budget::{CONFIG_FILE_BYTES, ResourceEstimate, section_nodes};
use shearcut_sim::{
    BladeSection, EdgeShape, InvalidSetting, Knife, KnifePreset, KnifeSettings, Material,
    MaterialPreset, ObjectShape, SectionSettings, SensorMount,
};

use crate::controller_choice::ControllerChoice;
use crate::controller_settings::ControllerSettings;
use crate::error::ConfigError;
use shearcut_controllers::planner::LatencyMode;

/// A scenario as written in a file, before presets are resolved.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ScenarioFile {
    /// Name of the scenario, used in result directory names (default: the file stem).
    pub name: Option<String>,
    /// Free text describing the scenario.
    pub description: Option<String>,
    /// Seed of every random process (sensor noise), default 0.
    #[serde(default)]
    pub seed: u64,
    /// The material: a preset, optionally with fields overridden, or all fields inline.
    pub material: MaterialSpec,
    /// The knife: a preset, optionally with tables overridden, or inline.
    pub knife: KnifeSpec,
    /// The object on the board.
    pub object: ObjectShape,
    /// The prescribed open-loop motion.
    #[serde(default)]
    pub motion: MotionSettings,
    /// Mesh and fracture-solver settings of the cross-section model.
    #[serde(default)]
    pub section: SectionSettings,
    /// The multi-section plant: segments, start gap, F/T sensor.
    #[serde(default)]
    pub plant: PlantSettings,
    /// Settings of the control loop.
    #[serde(default, rename = "loop")]
    pub control_loop: LoopSettings,
    /// The closed loop's controller (`shearcut run`).
    #[serde(default)]
    pub controller: ControllerSettings,
}

/// `[material]`: `preset = "…"` and/or the fields of [`Material`].
#[derive(Debug, Clone, Default, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct MaterialSpec {
    /// A preset name: potato-cuboid, eggplant-cuboid, potato-whole, eggplant-whole, agar.
    pub preset: Option<String>,
    /// Young's modulus E, Pa (overrides the preset).
    pub youngs_modulus: Option<f64>,
    /// Poisson's ratio ν in (0, 0.5) (overrides the preset).
    pub poisson_ratio: Option<f64>,
    /// Blade–material friction coefficient μ (overrides the preset).
    pub friction_coefficient: Option<f64>,
    /// Interior fracture toughness R_c, N/m (overrides the preset).
    pub fracture_toughness: Option<f64>,
    /// Initial fracture toughness R'_c, N/m (overrides the preset).
    pub initial_fracture_toughness: Option<f64>,
    /// Skin thickness, m (overrides the preset; default none: R'_c until
    /// each section's first fracture). Given, a surface layer this thick has
    /// toughness R'_c and the interior R_c (see `Material::skin_thickness`).
    pub skin_thickness: Option<f64>,
}

/// `[knife]`: `preset = "…"` and/or `edge`, `blade`, `sensor` tables.
#[derive(Debug, Clone, Default, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct KnifeSpec {
    /// A preset name: straight, chef, wire.
    pub preset: Option<String>,
    /// Edge shape (overrides the preset's).
    pub edge: Option<EdgeShape>,
    /// Blade section (overrides the preset's).
    pub blade: Option<BladeSection>,
    /// Sensor mount (overrides the preset's).
    pub sensor: Option<SensorMount>,
}

/// `[motion]`: the prescribed straight knife motion of `shearcut simulate`.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct MotionSettings {
    /// Knife speed along its velocity, m/s (default 0.00625, seed 000 §V).
    pub speed: f64,
    /// Slice-push ratios ξ = tan α to run, one cut each (default [0.0]).
    pub slice_push_ratios: Vec<f64>,
    /// Distance along the edge from the heel to the object's near face, m
    /// (default 0.02; seed 000 Fig. 6(b)'s z₀). A number, or a list paired
    /// with `slice_push_ratios` by index; a list of one (or a ratio list of
    /// one) is repeated to the other's length.
    #[serde(deserialize_with = "one_or_many")]
    pub z0: Vec<f64>,
    /// Depth of the cut below the object's top, m (default: 0.8 × object height).
    pub depth: Option<f64>,
    /// Vertical knife displacement per model step, m (default 1e-5).
    pub step: f64,
}

impl MotionSettings {
    /// The object's place along the edge in a closed-loop run, m: the first
    /// of `z0` (a loop cuts once).
    ///
    /// # Panics
    /// If `z0` is empty, which validation refuses: every [`Scenario`] is
    /// resolved from a file or text, and code that sets `z0` sets one value.
    pub fn loop_z0(&self) -> f64 {
        self.z0[0]
    }
}

impl Default for MotionSettings {
    fn default() -> Self {
        Self {
            speed: 0.00625,
            slice_push_ratios: vec![0.0],
            z0: vec![0.02],
            depth: None,
            step: 1e-5,
        }
    }
}

/// How the loop's time advances.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum ClockMode {
    /// The plant advances simulated time once per command: deterministic, as fast as the model allows.
    Lockstep,
    /// Paced by wall-clock time at the loop rate; deadline misses are counted.
    Realtime,
}

/// `[loop]`: the arm-style control loop between controller and plant.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct LoopSettings {
    /// Loop rate, Hz (default 1000, an arm's servo rate).
    pub rate_hz: f64,
    /// Clock mode (default lockstep).
    pub clock: ClockMode,
    /// Consecutive missed commands after which the plant brakes (default 20, as libfranka).
    pub missed_command_limit: u32,
    /// Arm limits on the knife's translation, checked by finite differences.
    pub arm_limits: ArmLimits,
    /// How long a controller process waits for its plant (or an arm
    /// bridge) to serve the run before it gives up, s (default 10).
    pub connect_timeout: f64,
    /// Real-time priority of the servo threads: 0 (default) leaves them to
    /// the normal scheduler; 1–99 runs the controller process's servo
    /// thread and the plant process's stepping thread under `SCHED_FIFO`
    /// at that priority, as a real arm's servo loop runs, once the MPC's
    /// planner thread and the plant's successor workers have started at
    /// normal priority. Needs `CAP_SYS_NICE` (or root); `shearcut
    /// controller` and `shearcut plant` fail with one line when it cannot
    /// be set. Only the separate processes (`--transport iceoryx2`) apply
    /// it.
    pub servo_priority: u8,
}

impl Default for LoopSettings {
    fn default() -> Self {
        Self {
            rate_hz: 1000.0,
            clock: ClockMode::Lockstep,
            missed_command_limit: 20,
            arm_limits: ArmLimits::default(),
            connect_timeout: 10.0,
            servo_priority: 0,
        }
    }
}

/// A scenario with presets resolved and every value validated.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Scenario {
    /// Name used in result directories.
    pub name: String,
    /// Free text.
    pub description: String,
    /// Seed of every random process.
    pub seed: u64,
    /// The material.
    pub material: Material,
    /// The knife.
    pub knife: KnifeSettings,
    /// The object.
    pub object: ObjectShape,
    /// The prescribed motion.
    pub motion: MotionSettings,
    /// The cross-section model's settings.
    pub section: SectionSettings,
    /// The plant's settings.
    pub plant: PlantSettings,
    /// The loop.
    #[serde(rename = "loop")]
    pub control_loop: LoopSettings,
    /// The closed loop's controller.
    pub controller: ControllerSettings,
}

/// Scenarios shipped with shearcut (`config/scenarios/*.toml`), available by
/// name as well as by path; `shearcut scenarios` lists them.
pub const BUILT_IN_SCENARIOS: [(&str, &str); 14] = [
    (
        "fig7-potato",
        include_str!("../config/scenarios/fig7-potato.toml"),
    ),
    (
        "fig7-eggplant",
        include_str!("../config/scenarios/fig7-eggplant.toml"),
    ),
    (
        "fig8-potato",
        include_str!("../config/scenarios/fig8-potato.toml"),
    ),
    (
        "fig9-eggplant",
        include_str!("../config/scenarios/fig9-eggplant.toml"),
    ),
    (
        "fig10-potato-whole",
        include_str!("../config/scenarios/fig10-potato-whole.toml"),
    ),
    (
        "fig11-eggplant-whole",
        include_str!("../config/scenarios/fig11-eggplant-whole.toml"),
    ),
    (
        "loop-potato-cuboid",
        include_str!("../config/scenarios/loop-potato-cuboid.toml"),
    ),
    (
        "loop-potato-cuboid-short-stroke",
        include_str!("../config/scenarios/loop-potato-cuboid-short-stroke.toml"),
    ),
    (
        "loop-potato-whole",
        include_str!("../config/scenarios/loop-potato-whole.toml"),
    ),
    (
        "loop-potato-whole-realtime",
        include_str!("../config/scenarios/loop-potato-whole-realtime.toml"),
    ),
    (
        "loop-eggplant-whole",
        include_str!("../config/scenarios/loop-eggplant-whole.toml"),
    ),
    (
        "loop-eggplant-whole-coarse",
        include_str!("../config/scenarios/loop-eggplant-whole-coarse.toml"),
    ),
    (
        "seed001-agar-section",
        include_str!("../config/scenarios/seed001-agar-section.toml"),
    ),
    (
        "seed001-agar-section-surface-stress",
        include_str!("../config/scenarios/seed001-agar-section-surface-stress.toml"),
    ),
];

impl Scenario {
    /// Loads a scenario from a path, or by the name of a built-in scenario.
    /// A file is read with a cap of [`CONFIG_FILE_BYTES`] and must be UTF-8.
    /// A file wins over a built-in scenario of the same name, with a warning
    /// that says so.
    pub fn load(path_or_name: &str) -> Result<Self, ConfigError> {
        let path = Path::new(path_or_name);
        let built_in = BUILT_IN_SCENARIOS.iter().find(|(n, _)| *n == path_or_name);
        match built_in {
            Some((name, text)) if !path.exists() => return Self::parse(text, name, name),
            Some((name, _)) => tracing::warn!(
                "`{name}` is read from the file of that name in the working directory, \
                 not the built-in scenario of that name"
            ),
            None => {}
        }
        let wire_slab = || {
            ConfigError::Argument(InvalidSetting::new(
                "SCENARIO",
                path_or_name,
                format!(
                    "a scenario of the cutting model (this one is of seed 001's \
                     `model = \"{WIRE_SLAB_MODEL}\"`: `shearcut simulate` and `shearcut check` \
                     run it)"
                ),
            ))
        };
        if !path.exists()
            && BUILT_IN_WIRE_SLAB_SCENARIOS
                .iter()
                .any(|(n, _)| *n == path_or_name)
        {
            return Err(wire_slab());
        }
        let text =
            read_capped_text(path, CONFIG_FILE_BYTES).map_err(|source| ConfigError::Read {
                path: path.to_path_buf(),
                source,
            })?;
        if is_wire_slab(&text) {
            return Err(wire_slab());
        }
        let stem = path
            .file_stem()
            .and_then(|s| s.to_str())
            .unwrap_or("scenario");
        let origin = path.display().to_string();
        let mut scenario = Self::parse_resolved(&text, &origin, stem)?;
        // A mesh path is relative to the scenario file, not to the working
        // directory; it is kept absolute, so that the scenario as a run
        // writes it (`scenario.toml` in its result directory) reads back
        // from anywhere.
        if let ObjectShape::Mesh { path: mesh } = &mut scenario.object
            && mesh.is_relative()
            && let Some(dir) = path.parent()
        {
            let joined = dir.join(&*mesh);
            *mesh = std::path::absolute(&joined).unwrap_or(joined);
        }
        scenario.check_extent_and_resources(&origin)?;
        Ok(scenario)
    }

    /// Parses, resolves and validates scenario TOML, including the object's
    /// extent and the resource estimate (a mesh path is taken as it is).
    /// `origin` names the text in errors; `default_name` is used when the
    /// file has no `name`.
    pub fn parse(text: &str, origin: &str, default_name: &str) -> Result<Self, ConfigError> {
        let scenario = Self::parse_resolved(text, origin, default_name)?;
        scenario.check_extent_and_resources(origin)?;
        Ok(scenario)
    }

    /// Parses and resolves, checking ranges and array lengths.
    fn parse_resolved(text: &str, origin: &str, default_name: &str) -> Result<Self, ConfigError> {
        let invalid = |setting| ConfigError::Invalid {
            path: origin.to_string(),
            setting,
        };
        let file: ScenarioFile = toml::from_str(text).map_err(|e| parse_error(origin, text, &e))?;
        let written: toml::Value =
            toml::from_str(text).map_err(|e| parse_error(origin, text, &e))?;
        let read = toml::Value::try_from(&file).map_err(|e| {
            invalid(InvalidSetting::new(
                "(scenario)",
                "(as read)",
                format!("does not serialise back: {e}"),
            ))
        })?;
        check_array_lengths(&written, &read).map_err(invalid)?;
        file.resolve(default_name).map_err(invalid)
    }

    /// The object's bounding-box extent [x, y, z], m: from the shape, or
    /// read from its mesh file (once per file and process, for the last
    /// [`MESH_EXTENTS_KEPT`] files: a sweep checks
    /// every job's scenario, [`check_budget`](Self::check_budget), and a
    /// variant cannot rescale a mesh). A file is known by its path, length
    /// and modification time, so a mesh rewritten in a long-lived process
    /// (Python, the C ABI) is read again.
    pub fn object_extent(&self) -> Result<[f64; 3], InvalidSetting> {
        static MESH_EXTENTS: std::sync::Mutex<Vec<(MeshFile, [f64; 3])>> =
            std::sync::Mutex::new(Vec::new());
        if let Some(e) = self.object.nominal_extent() {
            return Ok(e);
        }
        let file = match &self.object {
            ObjectShape::Mesh { path } => MeshFile::of(path),
            _ => None,
        };
        let known = |f: &MeshFile| {
            let extents = MESH_EXTENTS.lock().unwrap_or_else(|e| e.into_inner());
            extents.iter().find(|(g, _)| g == f).map(|(_, e)| *e)
        };
        if let Some(e) = file.as_ref().and_then(known) {
            return Ok(e);
        }
        let mesh = self
            .object
            .mesh()
            .map_err(|e| InvalidSetting::new("object.path", "(mesh)", e.to_string()))?;
        let (lo, hi) = mesh.bounds();
        let extent = [hi.x - lo.x, hi.y - lo.y, hi.z - lo.z];
        if let Some(f) = file {
            let mut extents = MESH_EXTENTS.lock().unwrap_or_else(|e| e.into_inner());
            extents.retain(|(g, _)| g.path != f.path);
            if extents.len() >= MESH_EXTENTS_KEPT {
                extents.remove(0);
            }
            extents.push((f, extent));
        }
        Ok(extent)
    }

    /// Checks the object's extent and the resource estimate, naming
    /// `origin` in the error ([`check_budget`](Self::check_budget)).
    fn check_extent_and_resources(&self, origin: &str) -> Result<(), ConfigError> {
        self.check_budget().map_err(|setting| ConfigError::Invalid {
            path: origin.to_string(),
            setting,
        })
    }

    /// Checks the object's extent (a mesh's bounding box against the
    /// object size range, the depth against its height) and the resource
    /// estimate against its budget: what loading a scenario file checks
    /// after resolving it, and what a scenario built from another (a
    /// sweep's variant and controller setting) must pass too.
    pub fn check_budget(&self) -> Result<(), InvalidSetting> {
        let extent = self.object_extent()?;
        if self.object.nominal_extent().is_none() {
            for (axis, v) in ["x", "y", "z"].into_iter().zip(extent) {
                OBJECT_SIZE.check(&format!("object.path (bounding box along {axis})"), v)?;
            }
            if let Some(d) = self.motion.depth
                && d >= extent[1]
            {
                return Err(InvalidSetting::new(
                    "motion.depth",
                    d,
                    format!("must be below the mesh's height {} m", extent[1]),
                ));
            }
        }
        self.resources(extent).check()
    }

    /// Whether `shearcut simulate` cuts this scenario as one section × the
    /// piece's length (a cuboid under a straight edge or a wire) rather
    /// than with the multi-section plant.
    pub fn simulates_one_section(&self) -> bool {
        matches!(
            (&self.object, &self.knife.edge),
            (
                ObjectShape::Cuboid(_),
                EdgeShape::Straight { .. } | EdgeShape::Wire { .. }
            )
        )
    }

    /// Upper bounds of what the scenario costs to simulate or run, for an
    /// object of bounding-box `extent` [x, y, z], m.
    ///
    /// - Section mesh: one section × the piece: half the width and the
    ///   height; the plant's sections, oblique to the object, at most half
    ///   the horizontal diagonal wide.
    /// - Plant: a section per segment and one successor building for each.
    /// - Series: `simulate` on one section runs at most height/step steps
    ///   per cut; on the plant, at most (2·height + gap)/(v·cos α) of
    ///   loop ticks per cut (its stop rule); `run` at most
    ///   `max_duration × rate_hz` ticks. The longest counts.
    pub fn resources(&self, extent: [f64; 3]) -> ResourceEstimate {
        let [x, height, z] = extent;
        let edge_width =
            Knife::new(&self.knife).map_or(self.knife.blade.edge_width, |k| k.blade().edge_width);
        let plant_section = section_nodes(0.5 * x.hypot(z), height, edge_width, &self.section);
        let one_section = section_nodes(0.5 * x, height, edge_width, &self.section);
        let dt = 1.0 / self.control_loop.rate_hz;
        let cuts = self.motion.cuts();
        let simulate_rows: f64 = if self.simulates_one_section() {
            cuts.len() as f64 * (height / self.motion.step).ceil()
        } else {
            cuts.iter()
                .map(|&(xi, _)| {
                    let v_down = self.motion.speed * xi.atan().cos();
                    ((2.0 * height + self.plant.start_gap) / (v_down * dt)).ceil()
                })
                .sum()
        };
        let run_rows = (self.controller.max_duration * self.control_loop.rate_hz).ceil();
        ResourceEstimate {
            section_nodes: if self.simulates_one_section() {
                one_section.max(plant_section)
            } else {
                plant_section
            },
            plant_nodes: 2.0 * self.plant.segments as f64 * plant_section,
            series_rows: simulate_rows.max(run_rows),
        }
    }
}

/// A one-line parse error with line and column, never quoting the text.
pub(crate) fn parse_error(origin: &str, text: &str, e: &toml::de::Error) -> ConfigError {
    let (line, column) = shearcut_sim::toml_error::position(text, e);
    ConfigError::Parse {
        path: origin.to_string(),
        line,
        column,
        message: shearcut_sim::toml_error::message(text, e),
    }
}

impl ScenarioFile {
    /// Expands presets and validates every value.
    pub fn resolve(self, default_name: &str) -> Result<Scenario, InvalidSetting> {
        let material = self
            .material
            .resolve()
            .map_err(|e| e.prefixed("material"))?;
        let knife = self.knife.resolve().map_err(|e| e.prefixed("knife"))?;
        self.object.validate().map_err(|e| e.prefixed("object"))?;
        self.section
            .validate_for(&material)
            .map_err(|e| e.prefixed("section"))?;
        self.motion
            .validate(self.object.nominal_height(), self.section.row_spacing)
            .map_err(|e| e.prefixed("motion"))?;
        self.plant.validate().map_err(|e| e.prefixed("plant"))?;
        check_plant_ranges(&self.plant).map_err(|e| e.prefixed("plant"))?;
        self.control_loop
            .validate()
            .map_err(|e| e.prefixed("loop"))?;
        self.controller
            .validate()
            .map_err(|e| e.prefixed("controller"))?;
        check_controller_ranges(&self.controller).map_err(|e| e.prefixed("controller"))?;
        if self.controller.kind == ControllerChoice::Mpc {
            check_planner_keeps_the_clock(&self.control_loop, &self.controller)?;
        }
        let name = self.name.unwrap_or_else(|| default_name.to_string());
        check_name(&name)?;
        Ok(Scenario {
            name,
            description: self.description.unwrap_or_default(),
            seed: self.seed,
            material,
            knife,
            object: self.object,
            motion: self.motion,
            section: self.section,
            plant: self.plant,
            control_loop: self.control_loop,
            controller: self.controller,
        })
    }
}

impl MaterialSpec {
    /// The material: the preset with overrides, or the inline fields.
    pub fn resolve(&self) -> Result<Material, InvalidSetting> {
        let base = self
            .preset
            .as_deref()
            .map(|name| {
                find_preset(
                    name,
                    MaterialPreset::from_name,
                    MaterialPreset::ALL.map(|p| p.name()),
                )
            })
            .transpose()?
            .map(MaterialPreset::material);
        let field = |key: &'static str, given: Option<f64>, from_preset: Option<f64>| {
            given.or(from_preset).ok_or_else(|| {
                InvalidSetting::new(
                    key,
                    "missing",
                    "give it, or name a `preset` that supplies it",
                )
            })
        };
        let m = Material {
            youngs_modulus: field(
                "youngs_modulus",
                self.youngs_modulus,
                base.map(|b| b.youngs_modulus),
            )?,
            poisson_ratio: field(
                "poisson_ratio",
                self.poisson_ratio,
                base.map(|b| b.poisson_ratio),
            )?,
            friction_coefficient: field(
                "friction_coefficient",
                self.friction_coefficient,
                base.map(|b| b.friction_coefficient),
            )?,
            fracture_toughness: field(
                "fracture_toughness",
                self.fracture_toughness,
                base.map(|b| b.fracture_toughness),
            )?,
            initial_fracture_toughness: field(
                "initial_fracture_toughness",
                self.initial_fracture_toughness,
                base.map(|b| b.initial_fracture_toughness),
            )?,
            skin_thickness: self.skin_thickness.or(base.and_then(|b| b.skin_thickness)),
        };
        m.validate()?;
        Ok(m)
    }
}

impl KnifeSpec {
    /// The knife: the preset with overrides, or the inline tables.
    pub fn resolve(&self) -> Result<KnifeSettings, InvalidSetting> {
        let base = self
            .preset
            .as_deref()
            .map(|name| {
                find_preset(
                    name,
                    KnifePreset::from_name,
                    KnifePreset::ALL.map(|p| p.name()),
                )
            })
            .transpose()?
            .map(KnifePreset::settings);
        let edge = match (&self.edge, &base) {
            (Some(e), _) => e.clone(),
            (None, Some(b)) => b.edge.clone(),
            (None, None) => {
                return Err(InvalidSetting::new(
                    "edge",
                    "missing",
                    "give an `edge` table, or name a `preset`",
                ));
            }
        };
        let k = KnifeSettings {
            edge,
            blade: self
                .blade
                .or(base.as_ref().map(|b| b.blade))
                .unwrap_or_default(),
            sensor: self
                .sensor
                .or(base.as_ref().map(|b| b.sensor))
                .unwrap_or_default(),
        };
        k.validate()?;
        Ok(k)
    }
}

/// Shallowest target depth, m: a tenth of a millimetre (a shallower
/// target is no cut).
pub const MIN_DEPTH: f64 = 1e-4;

impl MotionSettings {
    /// Checks speed, ratios, z₀, step and depth against their physical
    /// ranges, an object of height `object_height` (when known before
    /// loading a mesh) and a section mesh of `row_spacing` (the step is at
    /// least [`MIN_STEP_PER_ROW`] of it).
    pub fn validate(
        &self,
        object_height: Option<f64>,
        row_spacing: f64,
    ) -> Result<(), InvalidSetting> {
        KNIFE_SPEED.check("speed", self.speed)?;
        check_count(
            "slice_push_ratios",
            self.slice_push_ratios.len() as u64,
            1,
            MAX_CUTS,
        )
        .map_err(|e| InvalidSetting {
            value: format!("{} ratio(s)", self.slice_push_ratios.len()),
            ..e
        })?;
        SLICE_PUSH_RATIO.check_each("slice_push_ratios", &self.slice_push_ratios)?;
        EDGE_OFFSET.check_each("z0", &self.z0)?;
        let (nx, nz) = (self.slice_push_ratios.len(), self.z0.len());
        if nz == 0 || nz > MAX_CUTS as usize || (nx != nz && nx != 1 && nz != 1) {
            return Err(InvalidSetting::new(
                "z0",
                format!("{nz} value(s)"),
                format!(
                    "must be one value, as many as slice_push_ratios ({nx}), or up to {MAX_CUTS} with one ratio"
                ),
            ));
        }
        MOTION_STEP
            .at_least(MIN_STEP_PER_ROW * row_spacing)
            .check("step", self.step)?;
        if let Some(d) = self.depth {
            let h = object_height.unwrap_or(OBJECT_SIZE.max);
            if !(d.is_finite() && d >= MIN_DEPTH && d < h) {
                return Err(InvalidSetting::new(
                    "depth",
                    d,
                    format!("must be in [{MIN_DEPTH}, {h}) m, up to the object's height"),
                ));
            }
        }
        Ok(())
    }
}

impl MotionSettings {
    /// The cuts to run: (ξ, z₀) pairs, broadcasting a single value.
    pub fn cuts(&self) -> Vec<(f64, f64)> {
        let n = self.slice_push_ratios.len().max(self.z0.len());
        (0..n)
            .map(|i| {
                let xi = self.slice_push_ratios[i.min(self.slice_push_ratios.len() - 1)];
                let z0 = self.z0[i.min(self.z0.len() - 1)];
                (xi, z0)
            })
            .collect()
    }
}

/// Accepts `key = 0.02` as well as `key = [0.02, 0.05]`.
fn one_or_many<'de, D: serde::Deserializer<'de>>(d: D) -> Result<Vec<f64>, D::Error> {
    #[derive(Deserialize)]
    #[serde(untagged, expecting = "a number or a list of numbers")]
    enum OneOrMany {
        One(f64),
        Many(Vec<f64>),
    }
    Ok(match OneOrMany::deserialize(d)? {
        OneOrMany::One(v) => vec![v],
        OneOrMany::Many(v) => v,
    })
}

impl LoopSettings {
    /// Checks rate, arm limits and the missed-command limit against their
    /// physical ranges.
    pub fn validate(&self) -> Result<(), InvalidSetting> {
        RATE.at_most(LOOP_RATE_MAX).check("rate_hz", self.rate_hz)?;
        let (lo, hi) = MISSED_COMMANDS;
        check_count(
            "missed_command_limit",
            u64::from(self.missed_command_limit),
            lo,
            hi,
        )?;
        if !(self.connect_timeout.is_finite()
            && self.connect_timeout >= 0.1
            && self.connect_timeout <= 3600.0)
        {
            return Err(InvalidSetting::new(
                "connect_timeout",
                self.connect_timeout,
                "must be in [0.1, 3600] s",
            ));
        }
        check_count("servo_priority", u64::from(self.servo_priority), 0, 99)?;
        self.arm_limits
            .validate()
            .map_err(|e| e.prefixed("arm_limits"))?;
        // The model accepts any finite positive limits (its tests step the
        // command freely); a configured arm must be one that could exist.
        let limits = &self.arm_limits;
        ARM_VELOCITY.check("arm_limits.velocity", limits.velocity)?;
        ARM_ACCELERATION.check("arm_limits.acceleration", limits.acceleration)?;
        ARM_JERK.check("arm_limits.jerk", limits.jerk)
    }
}

/// Highest loop rate, Hz: an arm's servo loop runs at 0.5–1 kHz.
pub const LOOP_RATE_MAX: f64 = 20_000.0;

/// The physical ranges of the plant's settings that its own validation
/// leaves open (sensor rate, noise and bias; start gap, reach and update
/// distance); keys are relative to `[plant]`.
pub fn check_plant_ranges(p: &PlantSettings) -> Result<(), InvalidSetting> {
    PLANT_DISTANCE.check("start_gap", p.start_gap)?;
    PLANT_DISTANCE.check("reach", p.reach)?;
    UPDATE_DISTANCE.check("update_distance", p.update_distance)?;
    RATE.check("sensor.rate_hz", p.sensor.rate_hz)?;
    FORCE_NOISE.check("sensor.force_noise", p.sensor.force_noise)?;
    TORQUE_NOISE.check("sensor.torque_noise", p.sensor.torque_noise)?;
    SENSOR_BIAS.check_each("sensor.bias", &p.sensor.bias)
}

/// Under `[loop] clock = "realtime"` the MPC's plans must reach the servo
/// tick as the planner finishes them (`[controller.mpc.planner] latency =
/// "realtime"`): a `"lockstep"` planner makes the tick at which a plan is
/// due wait for its solve, and an `"inline"` one solves on the tick, so
/// either would stall a servo loop paced by the wall clock.
///
/// Checked on load when `[controller] kind = "mpc"`, and again by a run
/// whose controller is chosen on the command line.
pub fn check_planner_keeps_the_clock(
    control_loop: &LoopSettings,
    controller: &ControllerSettings,
) -> Result<(), InvalidSetting> {
    let latency = controller.mpc.planner.latency;
    if control_loop.clock == ClockMode::Realtime && latency != LatencyMode::Realtime {
        let name = match latency {
            LatencyMode::Lockstep => "\"lockstep\"",
            LatencyMode::Inline => "\"inline\"",
            LatencyMode::Realtime => "\"realtime\"",
        };
        return Err(InvalidSetting::new(
            "controller.mpc.planner.latency",
            name,
            "must be \"realtime\" under [loop] clock = \"realtime\" (a lockstep or inline planner makes the servo tick wait for its solve)",
        ));
    }
    Ok(())
}

/// The physical ranges of the controller's settings (speeds, duration,
/// force setpoint, blade budget, the constant ratio or force of `kind`);
/// keys are relative to `[controller]`.
pub fn check_controller_ranges(c: &ControllerSettings) -> Result<(), InvalidSetting> {
    KNIFE_SPEED.check("speed", c.speed)?;
    KNIFE_SPEED.check("max_normal_speed", c.max_normal_speed)?;
    KNIFE_SPEED.check("max_tangential_speed", c.max_tangential_speed)?;
    RUN_DURATION.check("max_duration", c.max_duration)?;
    FORCE.check("force_setpoint", c.force_setpoint)?;
    if let Some(b) = c.blade_budget {
        EDGE_OFFSET.check("blade_budget", b)?;
    }
    check_controller_kind("kind", c.kind)
}

/// The physical range of a controller choice's constant (its slice-push
/// ratio or force setpoint), named `<key> (slice ratio)` or `<key> (force
/// setpoint)` in an error.
pub fn check_controller_kind(key: &str, kind: ControllerChoice) -> Result<(), InvalidSetting> {
    match kind {
        ControllerChoice::Slice(xi) => SLICE_PUSH_RATIO.check(&format!("{key} (slice ratio)"), xi),
        ControllerChoice::Force(f) => FORCE.check(&format!("{key} (force setpoint)"), f),
        ControllerChoice::Mpc | ControllerChoice::Press => Ok(()),
    }
}

/// Longest scenario name, bytes of UTF-8: it names result directories,
/// with a time stamp or a sweep's prefix added, and file names are at most
/// 255 bytes.
pub const MAX_NAME_BYTES: usize = 100;

/// A scenario's `name`, which names its default result directory under
/// `runs/`: not blank, at most [`MAX_NAME_BYTES`] long, with no path
/// separators and no control characters (a NUL cannot be in a file name;
/// a newline would split every line that prints the directory).
pub(crate) fn check_name(name: &str) -> Result<(), InvalidSetting> {
    if name.trim().is_empty()
        || name.len() > MAX_NAME_BYTES
        || name.contains(['/', '\\'])
        || name.chars().any(char::is_control)
    {
        return Err(InvalidSetting::new(
            "name",
            format!("{name:?}"),
            format!(
                "must be non-blank, at most {MAX_NAME_BYTES} bytes, with no path separators or control characters"
            ),
        ));
    }
    Ok(())
}

/// Looks up a preset by `name`; the error lists the allowed `names`.
fn find_preset<P, const N: usize>(
    name: &str,
    lookup: impl Fn(&str) -> Option<P>,
    names: [&str; N],
) -> Result<P, InvalidSetting> {
    lookup(name).ok_or_else(|| {
        InvalidSetting::new(
            "preset",
            format!("{name:?}"),
            format!("must be one of {}", names.join(", ")),
        )
    })
}

/// Most mesh files [`Scenario::object_extent`] remembers (the oldest is
/// forgotten first).
const MESH_EXTENTS_KEPT: usize = 64;

/// A mesh file as [`Scenario::object_extent`] remembers it: its path, length
/// (bytes) and modification time.
#[derive(Debug, Clone, PartialEq)]
struct MeshFile {
    path: PathBuf,
    length: u64,
    modified: std::time::SystemTime,
}

impl MeshFile {
    /// The file at `path` now; None if its length or modification time
    /// cannot be read (the extent is then read every time, and the mesh
    /// reader reports why a file cannot be read).
    fn of(path: &Path) -> Option<Self> {
        let meta = std::fs::metadata(path).ok()?;
        Some(Self {
            path: path.to_path_buf(),
            length: meta.len(),
            modified: meta.modified().ok()?,
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    const MINIMAL: &str = r#"
        [material]
        preset = "potato-cuboid"
        [knife]
        preset = "straight"
        [object]
        kind = "cuboid"
        width = 0.03
        height = 0.03
        length = 0.04
    "#;

    /// A mesh file rewritten at the same path is measured again: the
    /// extent's memo knows a file by its length and modification time too.
    #[test]
    fn a_mesh_rewritten_at_its_path_is_measured_again() {
        let dir = std::env::temp_dir().join(format!("shearcut-extent-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let mesh = dir.join("tetrahedron.obj");
        // A closed tetrahedron with legs `a` along x, y and z.
        let tetrahedron = |a: &str| {
            format!(
                "v 0 0 0\nv {a} 0 0\nv 0 {a} 0\nv 0 0 {a}\nf 1 3 2\nf 1 2 4\nf 2 3 4\nf 1 4 3\n"
            )
        };
        std::fs::write(&mesh, tetrahedron("0.03")).unwrap();
        let text = MINIMAL.replace(
            "kind = \"cuboid\"\n        width = 0.03\n        height = 0.03\n        length = 0.04",
            &format!("kind = \"mesh\"\npath = \"{}\"", mesh.display()),
        );
        assert!(text.contains("tetrahedron.obj"));
        let s = Scenario::parse(&text, "t", "t").unwrap();
        let extent = |s: &Scenario| s.object_extent().unwrap();
        // The reader keeps single-precision coordinates: 0.03 to 1e-9.
        for e in extent(&s) {
            assert!((e - 0.03).abs() < 1e-8, "{e}");
        }
        std::fs::write(&mesh, tetrahedron("0.045")).unwrap();
        for e in extent(&s) {
            assert!((e - 0.045).abs() < 1e-8, "{e}");
        }
        std::fs::remove_dir_all(dir).ok();
    }

    /// A name that could not name a directory, or would split the line
    /// that prints it, is refused naming `name`; ordinary text is not.
    #[test]
    fn a_name_with_control_characters_or_blank_is_refused() {
        for bad in ["a\u{0}b", "a\nb", "tab\there", " ", "", "a/b"] {
            let e = check_name(bad).unwrap_err();
            assert_eq!(e.key, "name", "{bad:?}");
            assert!(e.allowed.contains("control characters"), "{e}");
        }
        for good in ["loop-potato-cuboid", "pomme de terre", "ナス"] {
            assert!(check_name(good).is_ok(), "{good:?}");
        }
    }

    #[test]
    fn built_in_scenarios_resolve() {
        for (name, text) in BUILT_IN_SCENARIOS {
            let s = Scenario::parse(text, name, name).unwrap();
            assert_eq!(s.name, name);
        }
    }

    /// The main job's scenario is the reference whole-potato cut on a
    /// coarser discretisation, nothing else: the same object, knife,
    /// material, motion, loop and controller.
    #[test]
    fn the_real_time_whole_potato_differs_from_the_reference_only_in_discretisation() {
        let reference = Scenario::load("loop-potato-whole").unwrap();
        let mut fast = Scenario::load("loop-potato-whole-realtime").unwrap();
        assert!(fast.section.row_spacing > reference.section.row_spacing);
        assert!(fast.plant.update_distance > reference.plant.update_distance);
        fast.name.clone_from(&reference.name);
        fast.description.clone_from(&reference.description);
        fast.section = reference.section;
        fast.plant.update_distance = reference.plant.update_distance;
        assert_eq!(fast, reference);
    }

    /// The held-out evaluation's whole eggplant is the reference eggplant
    /// on the real-time potato's discretisation, nothing else.
    #[test]
    fn the_coarse_whole_eggplant_differs_from_the_reference_only_in_discretisation() {
        let reference = Scenario::load("loop-eggplant-whole").unwrap();
        let potato = Scenario::load("loop-potato-whole-realtime").unwrap();
        let mut coarse = Scenario::load("loop-eggplant-whole-coarse").unwrap();
        assert_eq!(coarse.section, potato.section);
        assert_eq!(coarse.plant.update_distance, potato.plant.update_distance);
        coarse.name.clone_from(&reference.name);
        coarse.description.clone_from(&reference.description);
        coarse.section = reference.section;
        coarse.plant.update_distance = reference.plant.update_distance;
        assert_eq!(coarse, reference);
    }

    #[test]
    fn minimal_scenario_takes_documented_defaults() {
        let s = Scenario::parse(MINIMAL, "t", "minimal").unwrap();
        assert_eq!(s.name, "minimal");
        assert_eq!(s.motion.speed, 0.00625);
        assert_eq!(s.control_loop.rate_hz, 1000.0);
        assert_eq!(s.control_loop.missed_command_limit, 20);
        assert_eq!(s.material, MaterialPreset::PotatoCuboid.material());
    }

    #[test]
    fn override_of_a_preset_field() {
        let text = MINIMAL.replace(
            "preset = \"potato-cuboid\"",
            "preset = \"potato-cuboid\"\nfracture_toughness = 99.0",
        );
        let s = Scenario::parse(&text, "t", "t").unwrap();
        assert_eq!(s.material.fracture_toughness, 99.0);
        assert_eq!(s.material.youngs_modulus, 2.0e6);
    }

    #[test]
    fn poisson_ratio_out_of_range_is_one_line_naming_the_key() {
        let text = MINIMAL.replace(
            "preset = \"potato-cuboid\"",
            "preset = \"potato-cuboid\"\npoisson_ratio = 0.7",
        );
        let e = Scenario::parse(&text, "bad.toml", "t")
            .unwrap_err()
            .to_string();
        assert_eq!(
            e,
            "bad.toml: `material.poisson_ratio` = 0.7: must be in [0, 0.49]"
        );
    }

    #[test]
    fn unknown_key_reports_line_and_column() {
        let text = MINIMAL.replace("width = 0.03", "widht = 0.03");
        let e = Scenario::parse(&text, "bad.toml", "t")
            .unwrap_err()
            .to_string();
        // toml spans the table that holds the unknown key, `[object]` on
        // line 6; the error is placed on the key's own line.
        assert_eq!(text.lines().nth(7).map(str::trim), Some("widht = 0.03"));
        assert!(e.starts_with("bad.toml:8:"), "{e}");
        assert!(e.contains("widht") && !e.contains('\n'), "{e}");
    }

    #[test]
    fn unknown_preset_lists_the_allowed_ones() {
        let text = MINIMAL.replace("\"straight\"", "\"sword\"");
        let e = Scenario::parse(&text, "x", "t").unwrap_err().to_string();
        assert!(
            e.contains("`knife.preset` = \"sword\": must be one of straight, chef, wire"),
            "{e}"
        );
    }

    #[test]
    fn missing_material_field_without_preset() {
        let text = MINIMAL.replace("preset = \"potato-cuboid\"", "youngs_modulus = 1e6");
        let e = Scenario::parse(&text, "x", "t").unwrap_err().to_string();
        assert!(e.contains("`material.poisson_ratio` = missing"), "{e}");
    }

    #[test]
    fn skin_thickness_is_read_and_validated() {
        let base = Scenario::parse(MINIMAL, "t", "t").unwrap();
        assert_eq!(base.material.skin_thickness, None, "default: no layer");
        let text = MINIMAL.replace(
            "preset = \"potato-cuboid\"",
            "preset = \"potato-cuboid\"\nskin_thickness = 5e-4",
        );
        let s = Scenario::parse(&text, "t", "t").unwrap();
        assert_eq!(s.material.skin_thickness, Some(5e-4));
        let text = MINIMAL.replace(
            "preset = \"potato-cuboid\"",
            "preset = \"potato-cuboid\"\nskin_thickness = -1.0",
        );
        let e = Scenario::parse(&text, "bad.toml", "t")
            .unwrap_err()
            .to_string();
        assert!(e.contains("`material.skin_thickness` = -1"), "{e}");
    }

    /// Settings of the cut's end and the servo thread: defaults as documented,
    /// out-of-range values named with their key and range.
    #[test]
    fn overtravel_and_servo_priority_defaults_and_ranges() {
        let s = Scenario::parse(MINIMAL, "t", "minimal").unwrap();
        assert_eq!(s.controller.overtravel, 0.004);
        assert_eq!(s.control_loop.servo_priority, 0);
        let text = format!("{MINIMAL}\n[controller]\novertravel = 0.02\n");
        let e = Scenario::parse(&text, "x", "t").unwrap_err().to_string();
        assert!(e.contains("`controller.overtravel` = 0.02"), "{e}");
        assert!(e.contains("[0, 0.01] m"), "{e}");
        let text = format!("{MINIMAL}\n[loop]\nservo_priority = 100\n");
        let e = Scenario::parse(&text, "x", "t").unwrap_err().to_string();
        assert!(e.contains("`loop.servo_priority` = 100"), "{e}");
        assert!(e.contains("[0, 99]"), "{e}");
    }

    #[test]
    fn depth_must_be_inside_the_object() {
        let text = format!("{MINIMAL}\n[motion]\ndepth = 0.05\n");
        let e = Scenario::parse(&text, "x", "t").unwrap_err().to_string();
        assert!(e.contains("`motion.depth` = 0.05"), "{e}");
    }
}

/// Value of the top-level `model` key that marks a scenario of seed 001's
/// finite-strain wire–slab model (run by `shearcut simulate`).
pub const WIRE_SLAB_MODEL: &str = "finite-strain-wire";

/// Whether scenario TOML `text` is of the finite-strain wire–slab model
/// (its top-level `model` is [`WIRE_SLAB_MODEL`]).
fn is_wire_slab(text: &str) -> bool {
    toml::from_str::<toml::Table>(text)
        .ok()
        .and_then(|t| t.get("model").and_then(|m| m.as_str().map(str::to_owned)))
        .is_some_and(|m| m == WIRE_SLAB_MODEL)
}

/// Built-in scenarios of the finite-strain wire–slab model.
pub const BUILT_IN_WIRE_SLAB_SCENARIOS: [(&str, &str); 1] = [(
    "seed001-agar-wire",
    include_str!("../config/scenarios/seed001-agar-wire.toml"),
)];

/// A scenario of seed 001's finite-strain model: a periodic slab indented
/// and sheared by a wire at several kinematic angles, up to crack nucleation.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct WireSlabScenario {
    /// Must be `"finite-strain-wire"`.
    pub model: String,
    /// Name used in result directories (default: the file stem).
    #[serde(default)]
    pub name: String,
    /// Free text.
    #[serde(default)]
    pub description: String,
    /// The slab, wire, mesh, contact, loading and solver.
    #[serde(default)]
    pub slab: shearcut_sim::finite_strain::WireSlabSettings,
    /// The kinematic angles.
    #[serde(default)]
    pub sweep: AngleSweepSettings,
}

/// `[sweep]` of a [`WireSlabScenario`].
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct AngleSweepSettings {
    /// Kinematic angles θ = atan(V_t/V_n), degrees, each in [0, 85]
    /// (default [0, 15, 30, 45, 60, 75], seed 001 Fig. 1e–f).
    pub angles_deg: Vec<f64>,
    /// Threads the angles are shared over, 1–64 (default 2).
    pub threads: usize,
}

impl Default for AngleSweepSettings {
    fn default() -> Self {
        Self {
            angles_deg: vec![0.0, 15.0, 30.0, 45.0, 60.0, 75.0],
            threads: 2,
        }
    }
}

impl AngleSweepSettings {
    /// Checks the angles and the thread count; errors name the key.
    pub fn validate(&self) -> Result<(), InvalidSetting> {
        if self.angles_deg.is_empty() || self.angles_deg.len() > 32 {
            return Err(InvalidSetting::new(
                "sweep.angles_deg",
                self.angles_deg.len(),
                "must list 1 to 32 angles",
            ));
        }
        for a in &self.angles_deg {
            if !(0.0..=85.0).contains(a) {
                return Err(InvalidSetting::new(
                    "sweep.angles_deg",
                    a,
                    "each angle must be in [0, 85] degrees",
                ));
            }
        }
        if !(1..=64).contains(&self.threads) {
            return Err(InvalidSetting::new(
                "sweep.threads",
                self.threads,
                "must be an integer in [1, 64]",
            ));
        }
        Ok(())
    }
}

impl WireSlabScenario {
    /// Loads `path_or_name` (a path or a built-in name) if it is a
    /// finite-strain wire–slab scenario (`model = "finite-strain-wire"`);
    /// `Ok(None)` if it is another kind of scenario or not a file.
    pub fn load(path_or_name: &str) -> Result<Option<Self>, ConfigError> {
        let path = Path::new(path_or_name);
        let (text, origin, stem) = if path.exists() {
            let text =
                read_capped_text(path, CONFIG_FILE_BYTES).map_err(|source| ConfigError::Read {
                    path: path.to_path_buf(),
                    source,
                })?;
            let stem = path
                .file_stem()
                .and_then(|s| s.to_str())
                .unwrap_or("scenario")
                .to_string();
            (text, path.display().to_string(), stem)
        } else if let Some((name, text)) = BUILT_IN_WIRE_SLAB_SCENARIOS
            .iter()
            .find(|(n, _)| *n == path_or_name)
        {
            (text.to_string(), name.to_string(), name.to_string())
        } else {
            return Ok(None);
        };
        if !is_wire_slab(&text) {
            return Ok(None);
        }
        let mut s: Self = toml::from_str(&text).map_err(|e| parse_error(&origin, &text, &e))?;
        if s.name.is_empty() {
            s.name = stem;
        }
        let invalid = |setting: InvalidSetting| ConfigError::Invalid {
            path: origin.clone(),
            setting,
        };
        check_name(&s.name).map_err(invalid)?;
        s.slab.validate().map_err(|e| invalid(e.prefixed("slab")))?;
        s.sweep.validate().map_err(invalid)?;
        Ok(Some(s))
    }
}
