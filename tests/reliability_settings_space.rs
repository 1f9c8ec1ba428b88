//! A property test over the whole settings space of a scenario: every
//! numeric key at values inside its documented range, on its edges, just
//! outside, and at NaN, ±inf and ±1e300. The promise (issue 27): a scenario
//! is refused with one line naming the key when a value is outside its
//! range, and otherwise either refused with one line (a tied bound or the
//! resource budget) or accepted with a resource estimate within budget; an
//! accepted scenario, cut on the single-section model, finishes with
//! finite results.

use proptest::prelude::*;
use shearcut::commands::simulate::simulate;
use shearcut::scenario::Scenario;
use shearcut_sim::physical_range::*;
use shearcut_sim::resource_budget::{PLANT_NODES_BUDGET, SECTION_NODES_BUDGET, SERIES_ROWS_BUDGET};

/// The base: fig7-potato cut once, on a coarse mesh with coarse steps, so
/// that an accepted scenario is cheap to run.
const BASE: &str = r#"
name = "space"
[material]
preset = "potato-cuboid"
[knife]
preset = "straight"
[object]
kind = "cuboid"
width = 0.03
height = 0.025
length = 0.03
[motion]
slice_push_ratios = [0.75]
z0 = 0.02
depth = 0.005
step = 1e-4
[section]
row_spacing = 5e-4
[plant]
[loop]
[loop.arm_limits]
[controller]
"#;

/// A numeric key: its table, name and range (integers as their f64 bounds).
struct Key {
    table: &'static str,
    name: &'static str,
    range: PhysicalRange,
    integer: bool,
}

const fn key(table: &'static str, name: &'static str, range: PhysicalRange) -> Key {
    Key {
        table,
        name,
        range,
        integer: false,
    }
}

const fn count(table: &'static str, name: &'static str, (lo, hi): (u64, u64)) -> Key {
    Key {
        table,
        name,
        range: PhysicalRange::new(lo as f64, hi as f64, ""),
        integer: true,
    }
}

/// Every numeric key with a range of its own (bounds tied to other keys,
/// such as the step's lower end or the edge flat's upper end, are the
/// "refused with one line" branch).
const KEYS: &[Key] = &[
    key("material", "youngs_modulus", YOUNGS_MODULUS),
    key("material", "poisson_ratio", POISSON_RATIO),
    key("material", "friction_coefficient", FRICTION_COEFFICIENT),
    key("material", "fracture_toughness", FRACTURE_TOUGHNESS),
    key("material", "initial_fracture_toughness", FRACTURE_TOUGHNESS),
    key("material", "skin_thickness", SKIN_THICKNESS),
    key("object", "width", OBJECT_SIZE),
    key("object", "height", OBJECT_SIZE),
    key("object", "length", OBJECT_SIZE),
    key("motion", "speed", KNIFE_SPEED),
    key("motion", "step", MOTION_STEP),
    key("motion", "slice_push_ratios", SLICE_PUSH_RATIO),
    key("motion", "z0", EDGE_OFFSET),
    key("section", "row_spacing", ROW_SPACING),
    key("section", "grading_ratio", GRADING_RATIO),
    key("section", "max_element_width", ELEMENT_WIDTH),
    key(
        "section",
        "initial_crack_extension",
        INITIAL_CRACK_EXTENSION,
    ),
    key("section", "bisection_tolerance", ROOT_TOLERANCE),
    count("section", "max_bracket_doublings", BRACKET_DOUBLINGS),
    count("section", "max_bisection_iterations", ROOT_ITERATIONS),
    key("plant", "start_gap", PLANT_DISTANCE),
    key("plant", "update_distance", UPDATE_DISTANCE),
    key("plant", "sensor.rate_hz", RATE),
    key("plant", "sensor.force_noise", FORCE_NOISE),
    key("loop", "rate_hz", RATE),
    count("loop", "missed_command_limit", MISSED_COMMANDS),
    key("loop.arm_limits", "velocity", ARM_VELOCITY),
    key("loop.arm_limits", "acceleration", ARM_ACCELERATION),
    key("loop.arm_limits", "jerk", ARM_JERK),
    key("controller", "speed", KNIFE_SPEED),
    key("controller", "max_duration", RUN_DURATION),
    key("controller", "force_setpoint", FORCE),
];

/// Where in (or around) the range a value is drawn.
#[derive(Debug, Clone, Copy)]
enum Where {
    /// Log-uniform (or uniform when the range touches 0) at fraction u.
    Inside(f64),
    Min,
    Max,
    BelowMin,
    AboveMax,
    NotFinite(f64),
}

fn value(range: &PhysicalRange, w: Where) -> f64 {
    let (lo, hi) = (range.min, range.max);
    match w {
        Where::Inside(u) if lo > 0.0 => (lo.ln() + u * (hi / lo).ln()).exp().clamp(lo, hi),
        Where::Inside(u) => (lo + u * (hi - lo)).clamp(lo, hi),
        Where::Min => lo,
        Where::Max => hi,
        Where::BelowMin if lo > 0.0 => lo * 0.99,
        Where::BelowMin => lo - 1e-3 * (hi - lo).max(1.0),
        Where::AboveMax => hi * 1.01 + 1e-9,
        Where::NotFinite(v) => v,
    }
}

fn toml_number(v: f64, integer: bool) -> String {
    if v.is_nan() {
        "nan".into()
    } else if v.is_infinite() {
        if v > 0.0 { "inf".into() } else { "-inf".into() }
    } else if integer {
        format!("{}", v.round() as i64)
    } else {
        format!("{v:e}")
    }
}

/// The base scenario with `key = text` set in its table (the base's own
/// line for the key, if any, commented out).
fn scenario_text(k: &Key, text: &str) -> String {
    let assignment = if k.name == "slice_push_ratios" {
        format!("{} = [{text}]", k.name)
    } else {
        format!("{} = {text}", k.name)
    };
    BASE.replace(&format!("\n{} = ", k.name), &format!("\n# {} = ", k.name))
        .replace(
            &format!("[{}]\n", k.table),
            &format!("[{}]\n{assignment}\n", k.table),
        )
}

fn where_strategy() -> impl Strategy<Value = Where> {
    prop_oneof![
        4 => (0.0..=1.0f64).prop_map(Where::Inside),
        1 => Just(Where::Min),
        1 => Just(Where::Max),
        2 => Just(Where::BelowMin),
        2 => Just(Where::AboveMax),
        1 => prop::sample::select(vec![f64::NAN, f64::INFINITY, f64::NEG_INFINITY, 1e300, -1e300])
            .prop_map(Where::NotFinite),
    ]
}

/// Parses the scenario with one key set; checks the promise on the outcome.
/// Returns the scenario when accepted.
fn parse_and_check(k: &Key, w: Where) -> Option<Scenario> {
    let v = match (k.integer, w) {
        (true, Where::BelowMin) => k.range.min - 1.0,
        (true, Where::AboveMax) => k.range.max + 1.0,
        _ => value(&k.range, w),
    };
    let text = toml_number(v, k.integer);
    let in_range = k.range.contains(if k.integer { v.round() } else { v });
    // Negative or non-finite integers are refused by the TOML reader itself.
    let full_key = format!("{}.{}", k.table, k.name);
    match Scenario::parse(&scenario_text(k, &text), "space", "space") {
        Err(e) => {
            let e = e.to_string();
            assert!(!e.contains('\n'), "one line: {e}");
            if !in_range && !(k.integer && (v < 0.0 || !v.is_finite() || v > 4e9)) {
                assert!(
                    e.contains(&format!("`{full_key}")),
                    "{full_key} = {text} refused without naming the key: {e}"
                );
            }
            None
        }
        Ok(s) => {
            assert!(
                in_range,
                "{full_key} = {text} is outside its range and was accepted"
            );
            let extent = s.object_extent().unwrap();
            let r = s.resources(extent);
            assert!(r.section_nodes <= SECTION_NODES_BUDGET, "{r:?}");
            assert!(r.plant_nodes <= PLANT_NODES_BUDGET, "{r:?}");
            assert!(r.series_rows <= SERIES_ROWS_BUDGET, "{r:?}");
            Some(s)
        }
    }
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 512, ..ProptestConfig::default() })]

    /// Parsing only: 512 (key, value) draws over every key.
    #[test]
    fn every_key_is_in_range_or_refused_with_one_line(
        i in 0..KEYS.len(),
        w in where_strategy(),
    ) {
        parse_and_check(&KEYS[i], w);
    }
}

/// Keys whose whole range keeps the base's single-section cut cheap.
const RUN_KEYS: &[usize] = &[0, 1, 2, 3, 4, 9, 11];

proptest! {
    #![proptest_config(ProptestConfig { cases: 12, ..ProptestConfig::default() })]

    /// Accepted scenarios run: the single-section cut finishes with finite
    /// work, forces and depth (or is refused as bad input before it runs).
    #[test]
    fn an_accepted_material_or_motion_runs_to_finite_results(
        i in prop::sample::select(RUN_KEYS),
        u in 0.0..=1.0f64,
    ) {
        let k = &KEYS[i];
        if let Some(s) = parse_and_check(k, Where::Inside(u)) {
            match simulate(&s) {
                Ok(out) => {
                    for c in &out.summaries {
                        prop_assert!(c.work_j.is_finite() && c.work_j >= 0.0, "{c:?}");
                        prop_assert!(c.peak_force_vertical_n.is_finite(), "{c:?}");
                        prop_assert!(c.cut_depth_m.is_finite(), "{c:?}");
                    }
                    prop_assert!(out.samples.iter().all(|x| x.force_vertical_n.is_finite() && x.work_j.is_finite()));
                }
                Err(e) => prop_assert_eq!(e.exit_code(), 2, "{}", e),
            }
        }
    }
}
