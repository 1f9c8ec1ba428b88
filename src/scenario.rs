//! Scenario files: what is cut, with which knife, how, and in which loop.
//!
//! A scenario is a TOML file (see `config/scenarios/` and the README's
//! "Config format"). Every table is `deny_unknown_fields`; after parsing, the
//! scenario is resolved (presets expanded) and validated, and every error names
//! the key, the value and what is allowed.

use std::path::Path;

use serde::{Deserialize, Serialize};
use shearcut_sim::plant::{ArmLimits, PlantSettings};
use shearcut_sim::{
    BladeSection, EdgeShape, InvalidSetting, KnifePreset, KnifeSettings, Material, MaterialPreset,
    ObjectShape, SectionSettings, SensorMount,
};

use crate::controller_settings::ControllerSettings;
use crate::error::ConfigError;

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
}

impl Default for LoopSettings {
    fn default() -> Self {
        Self {
            rate_hz: 1000.0,
            clock: ClockMode::Lockstep,
            missed_command_limit: 20,
            arm_limits: ArmLimits::default(),
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

/// Scenarios shipped with shearcut, available by name as well as by path.
pub const BUILT_IN_SCENARIOS: [(&str, &str); 7] = [
    (
        "fig7-potato",
        include_str!("../config/scenarios/fig7-potato.toml"),
    ),
    (
        "fig7-eggplant",
        include_str!("../config/scenarios/fig7-eggplant.toml"),
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
];

impl Scenario {
    /// Loads a scenario from a path, or by the name of a built-in scenario.
    pub fn load(path_or_name: &str) -> Result<Self, ConfigError> {
        let path = Path::new(path_or_name);
        if !path.exists()
            && let Some((name, text)) = BUILT_IN_SCENARIOS.iter().find(|(n, _)| *n == path_or_name)
        {
            return Self::parse(text, name, name);
        }
        let text = std::fs::read_to_string(path).map_err(|source| ConfigError::Read {
            path: path.to_path_buf(),
            source,
        })?;
        let stem = path
            .file_stem()
            .and_then(|s| s.to_str())
            .unwrap_or("scenario");
        let mut scenario = Self::parse(&text, &path.display().to_string(), stem)?;
        // A mesh path is relative to the scenario file, not to the working directory.
        if let ObjectShape::Mesh { path: mesh } = &mut scenario.object
            && mesh.is_relative()
            && let Some(dir) = path.parent()
        {
            *mesh = dir.join(&*mesh);
        }
        Ok(scenario)
    }

    /// Parses, resolves and validates scenario TOML. `origin` names the text in
    /// errors; `default_name` is used when the file has no `name`.
    pub fn parse(text: &str, origin: &str, default_name: &str) -> Result<Self, ConfigError> {
        let file: ScenarioFile = toml::from_str(text).map_err(|e| parse_error(origin, text, &e))?;
        file.resolve(default_name)
            .map_err(|setting| ConfigError::Invalid {
                path: origin.to_string(),
                setting,
            })
    }
}

/// A one-line parse error with line and column.
fn parse_error(origin: &str, text: &str, e: &toml::de::Error) -> ConfigError {
    let (line, column) = match e.span() {
        Some(span) => {
            let before = &text[..span.start.min(text.len())];
            let line = before.matches('\n').count() + 1;
            let column = before.len() - before.rfind('\n').map_or(0, |i| i + 1) + 1;
            (line, column)
        }
        None => (1, 1),
    };
    ConfigError::Parse {
        path: origin.to_string(),
        line,
        column,
        message: e.message().split_whitespace().collect::<Vec<_>>().join(" "),
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
        self.motion
            .validate(self.object.nominal_height())
            .map_err(|e| e.prefixed("motion"))?;
        self.section.validate().map_err(|e| e.prefixed("section"))?;
        self.plant.validate().map_err(|e| e.prefixed("plant"))?;
        self.control_loop
            .validate()
            .map_err(|e| e.prefixed("loop"))?;
        self.controller
            .validate()
            .map_err(|e| e.prefixed("controller"))?;
        let name = self.name.unwrap_or_else(|| default_name.to_string());
        if name.is_empty() || name.contains(['/', '\\']) {
            return Err(InvalidSetting::new(
                "name",
                format!("{name:?}"),
                "must be non-empty and contain no path separators",
            ));
        }
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

impl MotionSettings {
    /// Checks speed, ratios, z₀ and depth against an object of height
    /// `object_height` (when known before loading a mesh).
    pub fn validate(&self, object_height: Option<f64>) -> Result<(), InvalidSetting> {
        if !(self.speed.is_finite() && self.speed > 0.0) {
            return Err(InvalidSetting::new(
                "speed",
                self.speed,
                "must be a finite number > 0 m/s",
            ));
        }
        if self.slice_push_ratios.is_empty() {
            return Err(InvalidSetting::new(
                "slice_push_ratios",
                "[]",
                "needs at least one ratio",
            ));
        }
        for (i, xi) in self.slice_push_ratios.iter().enumerate() {
            if !(xi.is_finite() && *xi >= 0.0 && *xi <= 20.0) {
                return Err(InvalidSetting::new(
                    format!("slice_push_ratios[{i}]"),
                    xi,
                    "must be in [0, 20] (ξ = tan α; 20 is α ≈ 87°)",
                ));
            }
        }
        for (i, z0) in self.z0.iter().enumerate() {
            if !(z0.is_finite() && *z0 >= 0.0) {
                return Err(InvalidSetting::new(
                    format!("z0[{i}]"),
                    z0,
                    "must be a finite number >= 0 m",
                ));
            }
        }
        let (nx, nz) = (self.slice_push_ratios.len(), self.z0.len());
        if nz == 0 || (nx != nz && nx != 1 && nz != 1) {
            return Err(InvalidSetting::new(
                "z0",
                format!("{nz} value(s)"),
                format!("must be one value or as many as slice_push_ratios ({nx})"),
            ));
        }
        if !(self.step.is_finite() && self.step > 0.0 && self.step <= 1e-3) {
            return Err(InvalidSetting::new(
                "step",
                self.step,
                "must be in (0, 0.001] m",
            ));
        }
        if let Some(d) = self.depth {
            let h = object_height.unwrap_or(f64::INFINITY);
            if !(d.is_finite() && d > 0.0 && d < h) {
                return Err(InvalidSetting::new(
                    "depth",
                    d,
                    format!("must be in (0, {h}) m, the object's height"),
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
    #[serde(untagged)]
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
    /// Checks rate, limits and the missed-command limit.
    pub fn validate(&self) -> Result<(), InvalidSetting> {
        if !(self.rate_hz.is_finite() && self.rate_hz >= 1.0 && self.rate_hz <= 20_000.0) {
            return Err(InvalidSetting::new(
                "rate_hz",
                self.rate_hz,
                "must be in [1, 20000] Hz",
            ));
        }
        if self.missed_command_limit == 0 {
            return Err(InvalidSetting::new(
                "missed_command_limit",
                0,
                "must be at least 1",
            ));
        }
        self.arm_limits
            .validate()
            .map_err(|e| e.prefixed("arm_limits"))
    }
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
            "bad.toml: `material.poisson_ratio` = 0.7: must be in the open interval (0, 0.5)"
        );
    }

    #[test]
    fn unknown_key_reports_line_and_column() {
        let text = MINIMAL.replace("width = 0.03", "widht = 0.03");
        let e = Scenario::parse(&text, "bad.toml", "t")
            .unwrap_err()
            .to_string();
        // toml spans the table that holds the unknown key: `[object]` on line 6.
        assert!(e.starts_with("bad.toml:6:"), "{e}");
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
            let text = std::fs::read_to_string(path).map_err(|source| ConfigError::Read {
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
        let is_slab = toml::from_str::<toml::Table>(&text)
            .ok()
            .and_then(|t| t.get("model").and_then(|m| m.as_str().map(str::to_string)))
            .is_some_and(|m| m == WIRE_SLAB_MODEL);
        if !is_slab {
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
        s.slab.validate().map_err(|e| invalid(e.prefixed("slab")))?;
        s.sweep.validate().map_err(invalid)?;
        Ok(Some(s))
    }
}
