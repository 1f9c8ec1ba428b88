//! The fitted surrogates built into shearcut (`config/surrogates/<material>-<knife>.toml`,
//! written by `shearcut fit`; other files there, and any file `fit` writes,
//! are named by path), and the choice of one for a scenario.

use std::path::Path;

use shearcut_sim::surrogate::Surrogate;
use shearcut_sim::{InvalidSetting, KnifePreset, MaterialPreset};

use crate::scenario::Scenario;

/// Shipped surrogates by name (`<material>-<knife>`).
pub const BUILT_IN_SURROGATES: [(&str, &str); 8] = [
    (
        "potato-cuboid-straight",
        include_str!("../config/surrogates/potato-cuboid-straight.toml"),
    ),
    (
        "potato-cuboid-chef",
        include_str!("../config/surrogates/potato-cuboid-chef.toml"),
    ),
    (
        "potato-whole-straight",
        include_str!("../config/surrogates/potato-whole-straight.toml"),
    ),
    (
        "potato-whole-chef",
        include_str!("../config/surrogates/potato-whole-chef.toml"),
    ),
    (
        "eggplant-cuboid-straight",
        include_str!("../config/surrogates/eggplant-cuboid-straight.toml"),
    ),
    (
        "eggplant-cuboid-chef",
        include_str!("../config/surrogates/eggplant-cuboid-chef.toml"),
    ),
    (
        "eggplant-whole-straight",
        include_str!("../config/surrogates/eggplant-whole-straight.toml"),
    ),
    (
        "eggplant-whole-chef",
        include_str!("../config/surrogates/eggplant-whole-chef.toml"),
    ),
];

/// The surrogate a scenario's MPC plans with: `[controller] surrogate` (a
/// built-in name or a file path) if given, else the built-in one for the
/// scenario's material and knife presets (the controller's nominal model of
/// the food; the estimator adapts it to the actual food).
pub fn surrogate_for(s: &Scenario) -> Result<Surrogate, InvalidSetting> {
    let name = match &s.controller.surrogate {
        Some(name) => name.clone(),
        None => {
            let material = MaterialPreset::ALL
                .into_iter()
                .find(|p| p.material() == s.material);
            let knife = KnifePreset::ALL
                .into_iter()
                .find(|p| p.settings() == s.knife);
            match (material, knife) {
                (Some(m), Some(k)) => format!("{}-{}", m.name(), k.name()),
                _ => {
                    return Err(InvalidSetting::new(
                        "controller.surrogate",
                        "(none)",
                        "the material or knife is not a preset: name a surrogate (built-in <material>-<knife>, e.g. potato-whole-chef, or a file written by `shearcut fit`)",
                    ));
                }
            }
        }
    };
    surrogate_named(&name)
}

/// The text of the built-in surrogate `name`, if `name` is one: a name in
/// `controller.surrogate` is a built-in one first, else a file's path.
pub fn built_in_surrogate(name: &str) -> Option<&'static str> {
    BUILT_IN_SURROGATES
        .iter()
        .find(|(n, _)| *n == name)
        .map(|(_, text)| *text)
}

/// A surrogate by `[controller] surrogate`'s rule: a built-in name
/// ([`BUILT_IN_SURROGATES`]) first, else a file written by `shearcut fit`.
/// Errors name the key `controller.surrogate`.
pub fn surrogate_named(name: &str) -> Result<Surrogate, InvalidSetting> {
    let bad = |why: String| InvalidSetting::new("controller.surrogate", name, why);
    if let Some(text) = built_in_surrogate(name) {
        return Surrogate::from_toml_str(text).map_err(|e| bad(e.to_string()));
    }
    let path = Path::new(name);
    if path.exists() {
        return Surrogate::from_path(path).map_err(|e| bad(e.to_string()));
    }
    Err(bad(format!(
        "neither a built-in surrogate ({}) nor a file (a path is relative to the working directory)",
        BUILT_IN_SURROGATES
            .iter()
            .map(|(n, _)| *n)
            .collect::<Vec<_>>()
            .join(", ")
    )))
}
