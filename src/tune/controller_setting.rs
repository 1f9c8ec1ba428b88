//! One controller setting of a sweep: which controller, and the keys of
//! `[controller]` it sets (e.g. `mpc.deformation_weight = 100`), applied to
//! a scenario as if they had been written in its file.

use serde::Serialize;
use shearcut_sim::InvalidSetting;

use crate::controller_choice::ControllerChoice;
use crate::scenario::{Scenario, ScenarioFile};
use crate::tune::constant_grid::ConstantGridPoint;
use crate::tune::perturbation::float_cell;

/// A controller with settings: what a row of the results is "a setting" of.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct ControllerSetting {
    /// The controller (with `grid_point`, ignored: the ratio is resolved
    /// on each scenario).
    #[serde(serialize_with = "as_string")]
    pub choice: ControllerChoice,
    /// Keys below `[controller]` (dotted, e.g. `mpc.deformation_weight`)
    /// and their values, in the sweep's key order.
    pub overrides: Vec<(String, toml::Value)>,
    /// A point of the sweep's best-constant grid: the controller is the
    /// constant ratio this point is on the scenario it is applied to
    /// ([`ConstantGridPoint::choice_on`]), not `choice`.
    pub grid_point: Option<ConstantGridPoint>,
}

fn as_string<S: serde::Serializer>(c: &ControllerChoice, s: S) -> Result<S::Ok, S::Error> {
    s.serialize_str(&c.to_string())
}

impl ControllerSetting {
    /// A controller with no settings changed.
    pub fn fixed(choice: ControllerChoice) -> Self {
        Self {
            choice,
            overrides: Vec::new(),
            grid_point: None,
        }
    }

    /// The setting's controller in tables: the choice, or the grid point's
    /// name (`best-constant:i/n`).
    pub fn label(&self) -> String {
        self.grid_point
            .map_or_else(|| self.choice.to_string(), |g| g.label())
    }

    /// The scenario `s` run under this setting: `[controller] kind` is the
    /// choice (a grid point's ratio on `s`) and every override is set, then
    /// the scenario is read and validated as a file would be, its object's
    /// extent and resource budgets included ([`Scenario::check_budget`]).
    /// Errors name the key below `controller.` (a single override's when
    /// one alone is wrong), or the budget's (`resources.*`, `motion.depth`,
    /// `object.path`).
    pub fn apply(&self, s: &Scenario) -> Result<Scenario, InvalidSetting> {
        let choice = match &self.grid_point {
            Some(g) => g.choice_on(s)?,
            None => self.choice,
        };
        let mut root = toml::Value::try_from(s).map_err(|e| {
            InvalidSetting::new("scenario", &s.name, format!("does not serialise: {e}"))
        })?;
        let controller = root
            .as_table_mut()
            .and_then(|t| t.get_mut("controller"))
            .and_then(toml::Value::as_table_mut)
            .ok_or_else(|| InvalidSetting::new("controller", "missing", "a table"))?;
        controller.insert("kind".to_string(), toml::Value::String(choice.to_string()));
        for (key, value) in &self.overrides {
            set_dotted(controller, key, value.clone())?;
        }
        let keys = || {
            self.overrides
                .iter()
                .map(|(k, _)| k.as_str())
                .collect::<Vec<_>>()
                .join(", ")
        };
        let file: ScenarioFile = root.try_into().map_err(|e: toml::de::Error| {
            let message = e.message().split_whitespace().collect::<Vec<_>>().join(" ");
            match self.overrides.as_slice() {
                [(key, value)] => InvalidSetting::new(format!("controller.{key}"), value, message),
                _ => InvalidSetting::new(format!("controller.{{{}}}", keys()), "", message),
            }
        })?;
        let resolved = file.resolve(&s.name)?;
        resolved.check_budget()?;
        Ok(resolved)
    }

    /// Whether the setting sets the blade budget, which moves the object
    /// along the edge as a variant's does (`perturbation::check_on_edge`: a job's
    /// scenario, its variant applied, must keep the object on the edge).
    pub fn sets_blade_budget(&self) -> bool {
        self.overrides.iter().any(|(k, _)| k == "blade_budget")
    }
}

/// Sets `key` (dotted, below `table`) to `value`, creating tables on the
/// way. An integer given for a key that holds a float becomes a float.
fn set_dotted(
    table: &mut toml::Table,
    key: &str,
    value: toml::Value,
) -> Result<(), InvalidSetting> {
    let mut parts: Vec<&str> = key.split('.').collect();
    let leaf = parts.pop().unwrap_or_default();
    if leaf.is_empty() || parts.iter().any(|p| p.is_empty()) {
        return Err(InvalidSetting::new(
            format!("controller.{key}"),
            &value,
            "is not a key (dotted names below [controller], e.g. mpc.deformation_weight)",
        ));
    }
    let mut at = table;
    for part in parts {
        let next = at
            .entry(part.to_string())
            .or_insert_with(|| toml::Value::Table(toml::Table::new()));
        at = next.as_table_mut().ok_or_else(|| {
            InvalidSetting::new(
                format!("controller.{key}"),
                &value,
                format!("`{part}` holds a value, not a table"),
            )
        })?;
    }
    let value = match (at.get(leaf), value) {
        (Some(toml::Value::Float(_)), toml::Value::Integer(i)) => toml::Value::Float(i as f64),
        (_, v) => v,
    };
    at.insert(leaf.to_string(), value);
    Ok(())
}

/// The scenario's `[controller]` table as result cells: every key (dotted,
/// prefixed `controller.`) with its value, in the table's order. Keys left
/// out (unset options) have no cell.
pub fn controller_cells(s: &Scenario) -> Vec<(String, String)> {
    let mut cells = Vec::new();
    if let Ok(toml::Value::Table(t)) = toml::Value::try_from(&s.controller) {
        flatten("controller", &t, &mut cells);
    }
    cells
}

fn flatten(prefix: &str, table: &toml::Table, out: &mut Vec<(String, String)>) {
    for (k, v) in table {
        let key = format!("{prefix}.{k}");
        match v {
            toml::Value::Table(t) => flatten(&key, t, out),
            other => out.push((key, value_cell(other))),
        }
    }
}

/// A TOML value as a result cell: strings bare, floats in their shortest
/// exact form, arrays as `[a; b]` (no commas, so CSV readers keep one cell
/// unquoted).
pub fn value_cell(v: &toml::Value) -> String {
    match v {
        toml::Value::String(s) => s.clone(),
        toml::Value::Float(x) => float_cell(*x),
        toml::Value::Integer(i) => i.to_string(),
        toml::Value::Boolean(b) => b.to_string(),
        toml::Value::Array(a) => format!(
            "[{}]",
            a.iter().map(value_cell).collect::<Vec<_>>().join("; ")
        ),
        other => other.to_string(),
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scenario::BUILT_IN_SCENARIOS;

    fn setting(choice: &str, overrides: &[(&str, toml::Value)]) -> ControllerSetting {
        ControllerSetting {
            choice: choice.parse().unwrap(),
            overrides: overrides
                .iter()
                .map(|(k, v)| (k.to_string(), v.clone()))
                .collect(),
            grid_point: None,
        }
    }

    #[test]
    fn no_override_gives_back_every_built_in_scenario_bit_for_bit() {
        for (name, _) in BUILT_IN_SCENARIOS {
            let s = Scenario::load(name).unwrap();
            let same = setting(&s.controller.kind.to_string(), &[])
                .apply(&s)
                .unwrap();
            assert_eq!(same, s, "{name}");
        }
    }

    #[test]
    fn overrides_set_nested_keys_and_integers_become_floats() {
        let s = Scenario::load("loop-potato-cuboid").unwrap();
        let t = setting(
            "slice:0.5",
            &[
                ("mpc.deformation_weight", toml::Value::Integer(100)),
                ("mpc.stages", toml::Value::Integer(20)),
                ("mpc.max_force", toml::Value::Float(25.0)),
                ("speed", toml::Value::Float(0.03)),
            ],
        )
        .apply(&s)
        .unwrap();
        assert_eq!(t.controller.kind, ControllerChoice::Slice(0.5));
        assert_eq!(t.controller.mpc.deformation_weight, 100.0);
        assert_eq!(t.controller.mpc.stages, 20);
        assert_eq!(t.controller.mpc.max_force, Some(25.0));
        assert_eq!(t.controller.speed, 0.03);
        let cells = controller_cells(&t);
        assert!(cells.contains(&("controller.mpc.max_force".into(), "25.0".into())));
        assert!(cells.contains(&("controller.kind".into(), "slice:0.5".into())));
    }

    #[test]
    fn a_wrong_key_or_value_is_named() {
        let s = Scenario::load("loop-potato-cuboid").unwrap();
        let e = setting(
            "mpc",
            &[("mpc.deformation_weigth", toml::Value::Float(1.0))],
        )
        .apply(&s)
        .unwrap_err();
        assert_eq!(e.key, "controller.mpc.deformation_weigth");
        assert!(e.allowed.contains("unknown field"), "{e}");
        let e = setting(
            "mpc",
            &[("mpc.deformation_weight", toml::Value::Float(-1.0))],
        )
        .apply(&s)
        .unwrap_err();
        assert_eq!(
            e.to_string(),
            "`controller.mpc.deformation_weight` = -1: must be in [0, 1e9] J/m²"
        );
    }
}
