//! `[controller]`: how `shearcut run` controls the knife.

use serde::{Deserialize, Serialize};
use shearcut_controllers::controller::ForceFeedbackGains;
use shearcut_controllers::mpc::MpcSettings;
use shearcut_sim::InvalidSetting;
use shearcut_sim::physical_range::PhysicalRange;

use crate::controller_choice::ControllerChoice;

/// Allowed [`ControllerSettings::overtravel`]: up to 10 mm past the target.
const OVERTRAVEL: PhysicalRange = PhysicalRange::new(0.0, 0.01, "m");
/// The force loop's proportional gain: > 0, at most 1 m/s per newton of
/// error (the knife's speed range per newton).
const PROPORTIONAL_GAIN: PhysicalRange = PhysicalRange::new(1e-9, 1.0, "(m/s)/N");
/// The force loop's integral gain.
const INTEGRAL_GAIN: PhysicalRange = PhysicalRange::new(0.0, 100.0, "(m/s)/(N s)");

/// `[controller]`: the closed loop's controller and its limits.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct ControllerSettings {
    /// The controller `shearcut run` uses unless `--controller` says
    /// otherwise: `mpc`, `press`, `slice:XI` or `force:N` (default
    /// `slice:0.75`).
    #[serde(with = "choice_as_string")]
    pub kind: ControllerChoice,
    /// Knife speed along its velocity for the baselines, and the force
    /// loop's top speed, m/s (default 0.02).
    pub speed: f64,
    /// Largest normal (downward) knife speed any controller may plan, m/s
    /// (default 0.05).
    pub max_normal_speed: f64,
    /// Largest tangential knife speed any controller may plan, m/s
    /// (default 0.1).
    pub max_tangential_speed: f64,
    /// Setpoint of the force loop in `shearcut compare`, N (default 20).
    pub force_setpoint: f64,
    /// Tangential blade travel available towards the tip, m (default: z₀:
    /// the object moves towards the heel as the knife slides, and z₀ is the
    /// room there). A run needs z₀ in [blade_budget, the edge's length
    /// minus the object's length along it], which keeps the whole object on
    /// the blade (`closed_loop::check_on_edge`).
    pub blade_budget: Option<f64>,
    /// Edge travel past the target depth before a controller ends its cut,
    /// m (default 0.004, at most 0.01): the crack front can lag the edge,
    /// and a controller cannot see it (`CutTask::overtravel`; the default
    /// covers the largest lag measured on the held-out variants, with a
    /// millimetre to spare: docs/limitations.md, "The crack can lag the
    /// edge").
    pub overtravel: f64,
    /// Longest simulated run, s (default 30): a cut that has not reached its
    /// target depth by then stops as timed out.
    pub max_duration: f64,
    /// Gains of `force:N` (default: full speed at zero force, integral
    /// time 2 s; see `ForceFeedbackGains::for_setpoint`).
    pub force_gains: Option<ForceFeedbackGains>,
    /// The surrogate the MPC plans with: a built-in name
    /// (`<material>-<knife>`, e.g. `potato-whole-chef`) or a file written by
    /// `shearcut fit` (default: the built-in one for the scenario's material
    /// and knife presets).
    pub surrogate: Option<String>,
    /// `[controller.mpc]`: the MPC's horizon, weights and limits.
    pub mpc: MpcSettings,
}

impl Default for ControllerSettings {
    fn default() -> Self {
        Self {
            kind: ControllerChoice::Slice(0.75),
            speed: 0.02,
            max_normal_speed: 0.05,
            max_tangential_speed: 0.1,
            force_setpoint: 20.0,
            blade_budget: None,
            overtravel: 0.004,
            max_duration: 30.0,
            force_gains: None,
            surrogate: None,
            mpc: MpcSettings::default(),
        }
    }
}

impl ControllerSettings {
    /// Checks every value, naming the key.
    pub fn validate(&self) -> Result<(), InvalidSetting> {
        for (key, value) in [
            ("speed", self.speed),
            ("max_normal_speed", self.max_normal_speed),
            ("max_tangential_speed", self.max_tangential_speed),
            ("max_duration", self.max_duration),
            ("force_setpoint", self.force_setpoint),
        ] {
            if !(value.is_finite() && value > 0.0) {
                return Err(InvalidSetting::new(key, value, "a finite number > 0"));
            }
        }
        if let Some(b) = self.blade_budget
            && !(b.is_finite() && b >= 0.0)
        {
            return Err(InvalidSetting::new(
                "blade_budget",
                b,
                "a finite length >= 0 m",
            ));
        }
        OVERTRAVEL.check("overtravel", self.overtravel)?;
        if let Some(g) = self.force_gains {
            PROPORTIONAL_GAIN.check("force_gains.proportional", g.proportional)?;
            INTEGRAL_GAIN.check("force_gains.integral", g.integral)?;
        }
        self.mpc.validate().map_err(|e| e.prefixed("mpc"))
    }
}

/// `kind` is written as its string form.
mod choice_as_string {
    use serde::{Deserialize, Deserializer, Serializer};

    use crate::controller_choice::ControllerChoice;

    pub fn serialize<S: Serializer>(c: &ControllerChoice, s: S) -> Result<S::Ok, S::Error> {
        s.serialize_str(&c.to_string())
    }

    pub fn deserialize<'de, D: Deserializer<'de>>(d: D) -> Result<ControllerChoice, D::Error> {
        let text = String::deserialize(d)?;
        text.parse().map_err(|e: shearcut_sim::InvalidSetting| {
            serde::de::Error::custom(format!("`{}`: {}", e.value, e.allowed))
        })
    }
}
