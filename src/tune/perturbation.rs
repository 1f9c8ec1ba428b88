//! A perturbed variant of a scenario: the food and the sensor a setting will
//! meet rather than the preset — the material's E, R_c and μ scaled, the
//! object scaled, another knife, the object at another place along the
//! edge, another blade budget, the F/T sensor's noise and bias, another
//! noise seed.
//!
//! A variant changes the plant only. The controller keeps the model it
//! would have in a lab: the MPC's surrogate stays the one of the scenario's
//! nominal material (pinned by [`Perturbation::apply`] when the scenario
//! names none), for the variant's knife (a lab knows its knife).

use serde::{Deserialize, Serialize};
use shearcut_sim::{InvalidSetting, Knife, KnifePreset, MaterialPreset, ObjectShape};

use crate::closed_loop::cut_task;
use crate::scenario::Scenario;
use crate::surrogates::built_in_surrogate;
use crate::tune::controller_setting::ControllerSetting;

/// Smallest and largest material scale factor accepted.
pub const MATERIAL_SCALE_RANGE: [f64; 2] = [0.1, 10.0];
/// Smallest and largest object size factor accepted.
pub const SIZE_SCALE_RANGE: [f64; 2] = [0.5, 2.0];
/// Smallest and largest blade budget accepted, m: from a cramped stroke to
/// more than a constant ratio near the material's optimum (ξ ≈ 0.6) needs
/// over the loop scenarios' 20–40 mm of depth.
pub const BLADE_BUDGET_RANGE: [f64; 2] = [0.005, 0.030];

/// One variant: every field left at its default leaves the scenario as it is.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct Perturbation {
    /// Factor on the material's Young's modulus E (default 1; in [0.1, 10]).
    pub youngs_modulus_scale: f64,
    /// Factor on the material's fracture toughness, interior R_c and
    /// initial R'_c alike (default 1; in [0.1, 10]).
    pub fracture_toughness_scale: f64,
    /// Factor on the blade–material friction coefficient μ (default 1; in
    /// [0.1, 10]).
    pub friction_scale: f64,
    /// Factor on every dimension of the object, and on `[motion] depth`
    /// when the scenario gives one, so the cut keeps its share of the
    /// object (default 1; in [0.5, 2]; only 1 for a mesh object).
    pub size_scale: f64,
    /// Knife preset replacing the scenario's knife: straight, chef or wire
    /// (default: the scenario's knife).
    pub knife: Option<String>,
    /// Standard deviation of the F/T sensor's white noise on each force
    /// axis, N (default: the scenario's `[plant.sensor] force_noise`; >= 0).
    pub force_noise: Option<f64>,
    /// Constant bias of the F/T sensor's forces [fx, fy, fz] in the sensor
    /// frame, N (default: the scenario's; finite).
    pub force_bias: Option<[f64; 3]>,
    /// Seed of the scenario's random processes, the sensor noise (default:
    /// the scenario's `seed`).
    pub seed: Option<u64>,
    /// Distance along the edge from the heel to the object's near face at
    /// the start of the cut, m (`[motion] z0`; default: the scenario's).
    /// Within the usable edge: the knife slides towards its tip, so the
    /// object moves towards the heel by up to the blade budget B, and
    /// z0 ∈ [B, edge length − the object's length along the edge] keeps
    /// it on the edge over the whole stroke (checked by
    /// [`Perturbation::apply`] against the knife, the object and B).
    pub z0: Option<f64>,
    /// The blade budget: the net travel along the edge the controllers may
    /// use, m (`[controller] blade_budget`; default: the scenario's; in
    /// [0.005, 0.030]).
    pub blade_budget: Option<f64>,
}

impl Default for Perturbation {
    fn default() -> Self {
        Self {
            youngs_modulus_scale: 1.0,
            fracture_toughness_scale: 1.0,
            friction_scale: 1.0,
            size_scale: 1.0,
            knife: None,
            force_noise: None,
            force_bias: None,
            seed: None,
            z0: None,
            blade_budget: None,
        }
    }
}

/// Names of the result columns a variant fills ([`Perturbation::cells`]).
pub const VARIANT_COLUMNS: [&str; 12] = [
    "variant.youngs_modulus_scale",
    "variant.fracture_toughness_scale",
    "variant.friction_scale",
    "variant.size_scale",
    "variant.knife",
    "variant.force_noise_n",
    "variant.force_bias_x_n",
    "variant.force_bias_y_n",
    "variant.force_bias_z_n",
    "variant.seed",
    "variant.z0_m",
    "variant.blade_budget_m",
];

impl Perturbation {
    /// Checks every field against its range; keys are the field names.
    pub fn validate(&self) -> Result<(), InvalidSetting> {
        let [lo, hi] = MATERIAL_SCALE_RANGE;
        for (key, v) in [
            ("youngs_modulus_scale", self.youngs_modulus_scale),
            ("fracture_toughness_scale", self.fracture_toughness_scale),
            ("friction_scale", self.friction_scale),
        ] {
            if !(v.is_finite() && (lo..=hi).contains(&v)) {
                return Err(InvalidSetting::new(
                    key,
                    v,
                    format!("must be in [{lo}, {hi}]"),
                ));
            }
        }
        let [lo, hi] = SIZE_SCALE_RANGE;
        if !(self.size_scale.is_finite() && (lo..=hi).contains(&self.size_scale)) {
            return Err(InvalidSetting::new(
                "size_scale",
                self.size_scale,
                format!("must be in [{lo}, {hi}]"),
            ));
        }
        if let Some(name) = &self.knife
            && KnifePreset::from_name(name).is_none()
        {
            return Err(InvalidSetting::new(
                "knife",
                format!("{name:?}"),
                format!(
                    "must be one of {}",
                    KnifePreset::ALL.map(|p| p.name()).join(", ")
                ),
            ));
        }
        if let Some(n) = self.force_noise
            && !(n.is_finite() && n >= 0.0)
        {
            return Err(InvalidSetting::new(
                "force_noise",
                n,
                "must be a finite number >= 0 N",
            ));
        }
        if let Some(b) = self.force_bias
            && let Some(x) = b.iter().find(|x| !x.is_finite())
        {
            return Err(InvalidSetting::new("force_bias", x, "must be finite (N)"));
        }
        if let Some(z0) = self.z0
            && !(z0.is_finite() && (0.0..=1.0).contains(&z0))
        {
            return Err(InvalidSetting::new(
                "z0",
                z0,
                "must be in [0, 1] m (and on the knife's edge: see apply)",
            ));
        }
        let [lo, hi] = BLADE_BUDGET_RANGE;
        if let Some(b) = self.blade_budget
            && !(b.is_finite() && (lo..=hi).contains(&b))
        {
            return Err(InvalidSetting::new(
                "blade_budget",
                b,
                format!("must be in [{lo}, {hi}] m"),
            ));
        }
        Ok(())
    }

    /// The scenario `base` under this variant. The MPC's surrogate is
    /// pinned to the nominal material's (see the module doc); the result is
    /// validated again, budgets included, when a controller setting is
    /// applied to it ([`ControllerSetting::apply`](super::controller_setting::ControllerSetting::apply)),
    /// as every sweep and `compare` job is.
    ///
    /// # Errors
    /// A factor the object cannot take; for a variant that sets `z0`,
    /// `blade_budget`, `size_scale` or `knife`, an object off the knife's
    /// usable edge ([`crate::closed_loop::check_on_edge`]): key `z0` (value z0, m) when the
    /// variant sets z0, else `z0, with <the first of those keys it sets>`;
    /// a knife or mesh that cannot be built, under its own key.
    pub fn apply(&self, base: &Scenario) -> Result<Scenario, InvalidSetting> {
        let s = self.apply_off_edge(base)?;
        self.check_edge(&s)?;
        Ok(s)
    }

    /// The scenario `base` under this variant for jobs run with `settings`:
    /// [`apply`](Self::apply), but when every setting sets its own blade
    /// budget the object's place on the edge is not checked against the
    /// scenario's budget, which no job runs with (each job is checked with
    /// its own: [`JobList::new`](super::job_list::JobList::new)).
    ///
    /// # Errors
    /// As [`apply`](Self::apply).
    pub fn apply_for(
        &self,
        base: &Scenario,
        settings: &[ControllerSetting],
    ) -> Result<Scenario, InvalidSetting> {
        if !settings.is_empty() && settings.iter().all(ControllerSetting::sets_blade_budget) {
            self.apply_off_edge(base)
        } else {
            self.apply(base)
        }
    }

    /// [`apply`](Self::apply) without the check of the object's place on
    /// the edge.
    fn apply_off_edge(&self, base: &Scenario) -> Result<Scenario, InvalidSetting> {
        let mut s = base.clone();
        if let Some(name) = &self.knife {
            let preset = KnifePreset::from_name(name)
                .ok_or_else(|| InvalidSetting::new("knife", name, "a knife preset"))?;
            s.knife = preset.settings();
        }
        if s.controller.surrogate.is_none() {
            s.controller.surrogate = nominal_surrogate(base, &s);
        }
        let m = &mut s.material;
        m.youngs_modulus *= self.youngs_modulus_scale;
        m.fracture_toughness *= self.fracture_toughness_scale;
        m.initial_fracture_toughness *= self.fracture_toughness_scale;
        m.friction_coefficient *= self.friction_scale;
        if self.size_scale != 1.0 {
            scale_object(&mut s.object, self.size_scale)?;
            s.motion.depth = s.motion.depth.map(|d| d * self.size_scale);
        }
        if let Some(n) = self.force_noise {
            s.plant.sensor.force_noise = n;
        }
        if let Some(b) = self.force_bias {
            s.plant.sensor.bias[..3].copy_from_slice(&b);
        }
        if let Some(seed) = self.seed {
            s.seed = seed;
        }
        if let Some(z0) = self.z0 {
            s.motion.z0 = vec![z0];
        }
        if let Some(b) = self.blade_budget {
            s.controller.blade_budget = Some(b);
        }
        Ok(s)
    }

    /// Checks the place on the edge of `s`, this variant applied: a variant
    /// that moves the object along the edge, changes its length along it,
    /// the blade it may use or the knife is checked before any run. The
    /// error's value is z0; its key says which of the variant's keys made
    /// the scenario's z0 wrong.
    fn check_edge(&self, s: &Scenario) -> Result<(), InvalidSetting> {
        let moves = [
            ("blade_budget", self.blade_budget.is_some()),
            ("size_scale", self.size_scale != 1.0),
            ("knife", self.knife.is_some()),
        ];
        let changed = moves.iter().find(|(_, set)| *set).map(|(key, _)| *key);
        if self.z0.is_some() || changed.is_some() {
            check_on_edge(s).map_err(|e| match (e.key.as_str(), self.z0, changed) {
                ("z0", None, Some(key)) => InvalidSetting {
                    key: format!("z0, with {key}"),
                    ..e
                },
                _ => e,
            })?;
        }
        Ok(())
    }

    /// The variant's name in tables: its changes from the scenario, e.g.
    /// `size ×1.25, z0 95 mm` (`as given` for none).
    pub fn label(&self) -> String {
        let mm = |x: f64| format!("{} mm", (x * 1e4).round() / 10.0);
        let mut parts = Vec::new();
        for (name, k) in [
            ("E", self.youngs_modulus_scale),
            ("R_c", self.fracture_toughness_scale),
            ("μ", self.friction_scale),
            ("size", self.size_scale),
        ] {
            if k != 1.0 {
                parts.push(format!("{name} ×{k}"));
            }
        }
        if let Some(k) = &self.knife {
            parts.push(format!("knife {k}"));
        }
        if let Some(n) = self.force_noise {
            parts.push(format!("noise {n} N"));
        }
        if let Some([x, y, z]) = self.force_bias {
            parts.push(format!("bias [{x}, {y}, {z}] N"));
        }
        if let Some(seed) = self.seed {
            parts.push(format!("seed {seed}"));
        }
        if let Some(z0) = self.z0 {
            parts.push(format!("z0 {}", mm(z0)));
        }
        if let Some(b) = self.blade_budget {
            parts.push(format!("blade {}", mm(b)));
        }
        if parts.is_empty() {
            "as given".to_string()
        } else {
            parts.join(", ")
        }
    }

    /// The variant's result cells for scenario `s` after [`apply`](Self::apply),
    /// in the order of [`VARIANT_COLUMNS`]: the factors, and the knife,
    /// sensor and seed the run had.
    pub fn cells(&self, s: &Scenario) -> Vec<String> {
        let knife = KnifePreset::ALL
            .into_iter()
            .find(|p| p.settings() == s.knife)
            .map_or("custom", |p| p.name());
        let bias = &s.plant.sensor.bias;
        vec![
            float_cell(self.youngs_modulus_scale),
            float_cell(self.fracture_toughness_scale),
            float_cell(self.friction_scale),
            float_cell(self.size_scale),
            knife.to_string(),
            float_cell(s.plant.sensor.force_noise),
            float_cell(bias[0]),
            float_cell(bias[1]),
            float_cell(bias[2]),
            s.seed.to_string(),
            s.motion
                .z0
                .first()
                .copied()
                .map_or(String::new(), float_cell),
            s.controller.blade_budget.map_or(String::new(), float_cell),
        ]
    }
}

/// Checks that the object of `s` stays on its knife's edge over the cut
/// ([`check_on_edge`](crate::closed_loop::check_on_edge)). The error's key
/// is `z0` (the caller renames it), its value z0, m.
pub(crate) fn check_on_edge(s: &Scenario) -> Result<(), InvalidSetting> {
    let z0 = s.motion.loop_z0();
    let knife = Knife::new(&s.knife).map_err(|e| e.prefixed("knife"))?;
    let mesh = s
        .object
        .mesh()
        .map_err(|e| InvalidSetting::new("object", "mesh", e.to_string()))?;
    let task = cut_task(s, &knife, &mesh)?;
    crate::closed_loop::check_on_edge(&knife, &mesh, &task, z0)
}

/// A number as a result cell: the shortest text that reads back to the same
/// bits (Rust's `Debug` form of `f64`).
pub fn float_cell(x: f64) -> String {
    format!("{x:?}")
}

/// The built-in surrogate the scenario `base` plans with by default (its
/// material preset's, for `variant`'s knife), if it has one.
fn nominal_surrogate(base: &Scenario, variant: &Scenario) -> Option<String> {
    let material = MaterialPreset::ALL
        .into_iter()
        .find(|p| p.material() == base.material)?;
    let knife = KnifePreset::ALL
        .into_iter()
        .find(|p| p.settings() == variant.knife)?;
    let name = format!("{}-{}", material.name(), knife.name());
    built_in_surrogate(&name).is_some().then_some(name)
}

/// Scales every dimension of `object` by `k`.
fn scale_object(object: &mut ObjectShape, k: f64) -> Result<(), InvalidSetting> {
    match object {
        ObjectShape::Cuboid(c) => {
            c.width *= k;
            c.height *= k;
            c.length *= k;
        }
        ObjectShape::HalfPotato {
            length,
            width,
            height,
        } => {
            *length *= k;
            *width *= k;
            *height *= k;
        }
        ObjectShape::Eggplant {
            length,
            diameter,
            flat,
        } => {
            *length *= k;
            *diameter *= k;
            *flat *= k;
        }
        ObjectShape::Mesh { .. } => {
            return Err(InvalidSetting::new(
                "size_scale",
                k,
                "must be 1 for a mesh object (scale the mesh file instead)",
            ));
        }
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_default_variant_is_the_scenario_with_its_surrogate_named() {
        let s = Scenario::load("loop-potato-whole").unwrap();
        let v = Perturbation::default().apply(&s).unwrap();
        assert_eq!(v.controller.surrogate.as_deref(), Some("potato-whole-chef"));
        let mut unpinned = v.clone();
        unpinned.controller.surrogate = None;
        assert_eq!(unpinned, s);
    }

    #[test]
    fn factors_scale_the_material_object_and_depth() {
        let s = Scenario::load("loop-potato-whole").unwrap();
        let p = Perturbation {
            youngs_modulus_scale: 1.5,
            fracture_toughness_scale: 0.5,
            friction_scale: 2.0,
            size_scale: 0.8,
            knife: Some("straight".into()),
            force_noise: Some(0.1),
            force_bias: Some([0.0, 0.5, 0.0]),
            seed: Some(7),
            z0: None,
            blade_budget: None,
        };
        let v = p.apply(&s).unwrap();
        assert_eq!(v.material.youngs_modulus, 1.5 * s.material.youngs_modulus);
        assert_eq!(
            v.material.initial_fracture_toughness,
            0.5 * s.material.initial_fracture_toughness
        );
        assert_eq!(v.material.friction_coefficient, 0.2);
        assert_eq!(v.motion.depth, Some(0.025 * 0.8));
        assert_eq!(
            v.object.nominal_height(),
            s.object.nominal_height().map(|h| h * 0.8)
        );
        // The controller keeps the nominal potato's model, for its knife.
        assert_eq!(
            v.controller.surrogate.as_deref(),
            Some("potato-whole-straight")
        );
        let cells = p.cells(&v);
        assert_eq!(cells.len(), VARIANT_COLUMNS.len());
        assert_eq!(cells[4], "straight");
        assert_eq!(cells[7], "0.5");
        assert_eq!(cells[9], "7");
    }

    #[test]
    fn out_of_range_factors_name_their_key() {
        let p = Perturbation {
            size_scale: 3.0,
            ..Perturbation::default()
        };
        let e = p.validate().unwrap_err();
        assert_eq!(e.to_string(), "`size_scale` = 3: must be in [0.5, 2]");
        let p = Perturbation {
            knife: Some("sword".into()),
            ..Perturbation::default()
        };
        assert_eq!(p.validate().unwrap_err().key, "knife");
    }

    #[test]
    fn z0_and_blade_budget_reach_the_scenario_within_the_usable_edge() {
        // The half potato is 90 mm long along the chef's 200 mm edge and
        // the scenario gives 15 mm of blade: z0 ∈ [0.015, 0.11] m.
        let s = Scenario::load("loop-potato-whole").unwrap();
        let at = |z0: Option<f64>, blade_budget: Option<f64>| {
            let p = Perturbation {
                z0,
                blade_budget,
                ..Perturbation::default()
            };
            p.validate()?;
            p.apply(&s)
        };
        let v = at(Some(0.095), None).unwrap();
        assert_eq!(v.motion.z0, vec![0.095]);
        assert_eq!(v.controller.blade_budget, Some(0.015));
        let v = at(Some(0.04), Some(0.03)).unwrap();
        assert_eq!(
            (v.motion.loop_z0(), v.controller.blade_budget),
            (0.04, Some(0.03))
        );
        let p = Perturbation {
            z0: Some(0.04),
            blade_budget: Some(0.03),
            ..Perturbation::default()
        };
        assert_eq!(&p.cells(&v)[10..], ["0.04", "0.03"]);
        assert_eq!(p.label(), "z0 40 mm, blade 30 mm");
        assert_eq!(Perturbation::default().label(), "as given");
        // Past the tip, past the heel over the stroke, a stroke longer
        // than the room behind the object, a budget out of range.
        let e = at(Some(0.12), None).unwrap_err();
        assert_eq!(e.key, "z0");
        assert!(
            e.to_string()
                .starts_with("`z0` = 0.12: must be in [0.0150, 0.1100] m"),
            "{e}"
        );
        assert_eq!(at(Some(0.01), None).unwrap_err().key, "z0");
        let e = at(None, Some(0.03)).unwrap_err();
        assert_eq!(e.key, "z0, with blade_budget");
        assert!(e.to_string().contains("30.0 mm stroke"), "{e}");
        let e = at(None, Some(0.04)).unwrap_err();
        assert_eq!(
            e.to_string(),
            "`blade_budget` = 0.04: must be in [0.005, 0.03] m"
        );
        assert_eq!(at(Some(f64::NAN), None).unwrap_err().key, "z0");
        // A scaled object is checked at its new length: 112.5 mm from
        // z0 = 0.095 runs past the tip.
        let p = Perturbation {
            size_scale: 1.25,
            z0: Some(0.095),
            ..Perturbation::default()
        };
        assert_eq!(p.apply(&s).unwrap_err().key, "z0");
        // A larger potato at the scenario's z0: 1.7 × 90 mm from 50 mm
        // runs past the tip.
        let mut at_50 = s.clone();
        at_50.motion.z0 = vec![0.05];
        let p = Perturbation {
            size_scale: 1.7,
            ..Perturbation::default()
        };
        let e = p.apply(&at_50).unwrap_err();
        assert!(
            e.to_string().starts_with("`z0, with size_scale` = 0.05: "),
            "{e}"
        );
        // Another knife: at the scenario's z0 (20 mm) the 90 mm potato
        // runs past the end of the 100 mm wire.
        let p = Perturbation {
            knife: Some("wire".into()),
            ..Perturbation::default()
        };
        let e = p.apply(&s).unwrap_err();
        assert!(
            e.to_string().starts_with("`z0, with knife` = 0.02: "),
            "{e}"
        );
    }

    #[test]
    fn float_cells_read_back_to_the_same_bits() {
        for x in [0.1, 1.0 / 3.0, 1e-20, 2.5e7, 0.0] {
            let back: f64 = float_cell(x).parse().unwrap();
            assert_eq!(back.to_bits(), x.to_bits());
        }
    }
}
