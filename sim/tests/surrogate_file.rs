//! Surrogate files: the shipped ones parse and match their presets; files
//! with a wrong version, a missing key, an unknown key or a non-finite
//! coefficient are refused with an error naming it.

use std::path::PathBuf;

use shearcut_sim::surrogate::{
    RatioCorrection, SURROGATE_FORMAT_VERSION, Surrogate, SurrogateFileError,
};
use shearcut_sim::{KnifePreset, MaterialPreset};

fn shipped(material: &str, knife: &str) -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
        .join("../config/surrogates")
        .join(format!("{material}-{knife}.toml"))
}

const TABLE_ONE: [MaterialPreset; 4] = [
    MaterialPreset::PotatoCuboid,
    MaterialPreset::EggplantCuboid,
    MaterialPreset::PotatoWhole,
    MaterialPreset::EggplantWhole,
];

#[test]
fn shipped_surrogates_parse_and_match_their_presets() {
    for m in TABLE_ONE {
        let mut coefficients = Vec::new();
        for k in [KnifePreset::Straight, KnifePreset::Chef] {
            let path = shipped(m.name(), k.name());
            let s =
                Surrogate::from_path(&path).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
            assert_eq!(s.version, SURROGATE_FORMAT_VERSION);
            assert_eq!(s.material_name, m.name());
            assert_eq!(s.knife_name, k.name());
            assert_eq!(s.material, m.material(), "{}", path.display());
            assert_eq!(s.blade.section(), k.settings().blade, "{}", path.display());
            coefficients.push((s.pre_fracture, s.post_fracture, s.range));
        }
        // Straight and chef's knives share the blade section, the only part
        // of the knife a section sees: the fits are identical.
        assert_eq!(coefficients[0], coefficients[1], "{}", m.name());
    }
}

fn potato_text() -> String {
    std::fs::read_to_string(shipped("potato-cuboid", "straight")).unwrap()
}

#[test]
fn round_trip_through_toml_is_exact() {
    let s = Surrogate::from_toml_str(&potato_text()).unwrap();
    let again = Surrogate::from_toml_str(&s.to_toml_string()).unwrap();
    assert_eq!(s, again);
}

#[test]
fn wrong_version_is_refused_with_both_versions() {
    let text = potato_text().replace(
        &format!("version = {SURROGATE_FORMAT_VERSION}"),
        "version = 99",
    );
    let e = Surrogate::from_toml_str(&text).unwrap_err();
    assert!(
        matches!(e, SurrogateFileError::WrongVersion { found: 99, .. }),
        "{e}"
    );
    let msg = e.to_string();
    assert!(
        msg.contains("99") && msg.contains(&SURROGATE_FORMAT_VERSION.to_string()),
        "{msg}"
    );
}

#[test]
fn missing_version_is_refused() {
    let text: String = potato_text()
        .lines()
        .filter(|l| !l.starts_with("version"))
        .map(|l| format!("{l}\n"))
        .collect();
    let e = Surrogate::from_toml_str(&text).unwrap_err();
    assert!(
        matches!(e, SurrogateFileError::MissingVersion { .. }),
        "{e}"
    );
    assert!(e.to_string().contains("version"));
}

#[test]
fn missing_field_is_refused_and_named() {
    let text: String = potato_text()
        .lines()
        .filter(|l| !l.starts_with("face_reaction"))
        .map(|l| format!("{l}\n"))
        .collect();
    let e = Surrogate::from_toml_str(&text).unwrap_err();
    assert!(matches!(e, SurrogateFileError::Format(_)), "{e}");
    assert!(e.to_string().contains("face_reaction"), "{e}");
    assert!(!e.to_string().contains('\n'), "one line: {e}");
}

#[test]
fn unknown_field_is_refused_and_named() {
    let text = potato_text().replace("[post_fracture]\n", "[post_fracture]\nsplit_typo = [1.0]\n");
    let e = Surrogate::from_toml_str(&text).unwrap_err();
    assert!(e.to_string().contains("split_typo"), "{e}");
}

/// The shipped potato surrogate with the first coefficient of the array
/// `key` (the first line `key = [`) written as `value`; and that
/// coefficient as shipped.
fn potato_with_first(key: &str, value: &str) -> (String, f64) {
    let text = potato_text();
    let start = format!("{key} = [");
    let line = text.lines().find(|l| l.starts_with(&start)).unwrap();
    let first = line.trim_start_matches(&start).split(',').next().unwrap();
    let shipped = first.trim().parse().unwrap();
    (text.replace(line, &line.replacen(first, value, 1)), shipped)
}

#[test]
fn non_finite_coefficient_is_refused_and_named() {
    for bad in ["nan", "inf", "-inf"] {
        let (t, _) = potato_with_first("split", bad);
        let e = Surrogate::from_toml_str(&t).unwrap_err();
        match &e {
            SurrogateFileError::BadValue { key, value, .. } => {
                assert_eq!(key, "post_fracture.split[0]");
                assert!(!value.is_finite());
            }
            other => panic!("{bad}: {other}"),
        }
        assert!(e.to_string().contains("post_fracture.split[0]"), "{e}");
    }
}

/// A value out of its range is written short in the message (1e300, not
/// its 301 digits).
#[test]
fn a_huge_catch_up_exponent_is_refused_in_a_short_line() {
    let text = potato_text();
    assert!(text.contains("catch_up_exponent = 1.0\n"));
    let t = text.replace("catch_up_exponent = 1.0\n", "catch_up_exponent = 1e300\n");
    let e = Surrogate::from_toml_str(&t).unwrap_err().to_string();
    assert_eq!(
        e,
        "surrogate file: `ratio.catch_up_exponent` = 1e300 must be in [0, 4] (fit writes 1)"
    );
}

#[test]
fn a_finite_coefficient_whose_prediction_overflows_is_refused() {
    let (t, shipped) = potato_with_first("drag", "1e308");
    let e = Surrogate::from_toml_str(&t).unwrap_err();
    assert!(
        matches!(
            &e,
            SurrogateFileError::NonFinitePrediction {
                output,
                xi: 0.0,
                fractured: true,
                stiffness: 1.0,
                ..
            } if output == "force_normal_slope"
        ),
        "{e}"
    );
    let line = e.to_string();
    assert!(
        line.contains("`force_normal_slope` is not finite at ξ = 0, section height 0.02 m")
            && line.ends_with("refit with `shearcut fit`")
            && line.lines().count() == 1,
        "{e}"
    );
    // A correction for the stiffness-to-toughness ratio out of scale: it
    // vanishes at the nominal material, but its slope in ln(S/T) does not.
    let (t, _) = potato_with_first("face_reaction_linear", "1e308");
    let e = Surrogate::from_toml_str(&t).unwrap_err();
    assert!(
        matches!(
            &e,
            SurrogateFileError::NonFinitePrediction { output, .. }
                if output.ends_with("_log_ratio_slope")
        ),
        "{e}"
    );
    // The same coefficient within a fit's scale (×10) is accepted.
    let (t, _) = potato_with_first("drag", &(10.0 * shipped).to_string());
    assert!(Surrogate::from_toml_str(&t).is_ok());
}

#[test]
fn invalid_material_constant_is_refused_and_named() {
    let text = potato_text().replace("poisson_ratio = 0.4", "poisson_ratio = 0.7");
    let e = Surrogate::from_toml_str(&text).unwrap_err();
    assert!(e.to_string().contains("material.poisson_ratio"), "{e}");
}

#[test]
fn a_range_or_exponent_out_of_bounds_is_refused_and_named() {
    for (from, to, key) in [
        ("xi_max = 2.4", "xi_max = -1.0", "range.xi_max"),
        (
            "height = [0.02, 0.045]",
            "height = [-1.0, 0.045]",
            "range.height[0]",
        ),
        (
            "height = [0.02, 0.045]",
            "height = [0.05, 0.045]",
            "range.height[1]",
        ),
        (
            "half_width = [0.01, 0.03]",
            "half_width = [0.0, 0.03]",
            "range.half_width[0]",
        ),
        (
            "catch_up_exponent = 1.0",
            "catch_up_exponent = -1.0",
            "ratio.catch_up_exponent",
        ),
    ] {
        let text = potato_text();
        assert!(text.contains(from), "{from}");
        let e = Surrogate::from_toml_str(&text.replace(from, to)).unwrap_err();
        assert!(e.to_string().contains(key), "{to}: {e}");
    }
}

#[test]
fn unreadable_file_names_the_path() {
    let e = Surrogate::from_path(std::path::Path::new("/nonexistent/s.toml")).unwrap_err();
    assert!(e.to_string().contains("/nonexistent/s.toml"), "{e}");
}

#[test]
fn negative_knee_width_is_refused_and_named() {
    let text = potato_text();
    let line = text
        .lines()
        .find(|l| l.starts_with("knee_width = ["))
        .unwrap();
    let t = text.replace(line, "knee_width = [-0.5, 1.0]");
    let e = Surrogate::from_toml_str(&t).unwrap_err();
    assert!(e.to_string().contains("post_fracture.knee_width[0]"), "{e}");
    let t = text.replace(line, "knee_width = [0.0, 0.0]");
    let e = Surrogate::from_toml_str(&t).unwrap_err();
    assert!(e.to_string().contains("knee_width"), "{e}");
}

#[test]
fn older_versions_are_refused_with_a_refit_hint() {
    // Version 1 had no catch-up, version 2 no knee lead, its face reaction's
    // ramps ran on the travel and its split had four terms, version 3 no
    // column term in the compliances: their coefficients mean something
    // else.
    for old in [1, 2, 3] {
        let text = potato_text().replace(
            &format!("version = {SURROGATE_FORMAT_VERSION}"),
            &format!("version = {old}"),
        );
        let e = Surrogate::from_toml_str(&text).unwrap_err();
        assert!(e.to_string().contains("shearcut fit"), "{e}");
    }
}

#[test]
fn negative_knee_lead_is_refused_and_named() {
    let text = potato_text();
    let line = text
        .lines()
        .find(|l| l.starts_with("knee_lead = "))
        .unwrap();
    let t = text.replace(line, "knee_lead = -0.1");
    let e = Surrogate::from_toml_str(&t).unwrap_err();
    assert!(e.to_string().contains("post_fracture.knee_lead"), "{e}");
}

#[test]
fn negative_window_weight_is_refused_and_named() {
    let text = potato_text();
    let line = text
        .lines()
        .find(|l| l.starts_with("fit_window_weight = "))
        .expect("the potato cuboid was fitted with a window weight");
    let t = text.replace(line, "fit_window_weight = -1.0");
    let e = Surrogate::from_toml_str(&t).unwrap_err();
    assert!(e.to_string().contains("fit_window_weight"), "{e}");
}

/// The potato file without its `[ratio]` table.
fn without_ratio_text() -> String {
    let text = potato_text();
    let start = text
        .find("[ratio]")
        .expect("a format-4 file has a [ratio] table");
    let end = text[start + 1..]
        .find("\n[")
        .map_or(text.len(), |i| start + 2 + i);
    format!("{}{}", &text[..start], &text[end..])
}

#[test]
fn a_file_without_ratio_table_reads_as_zero_ratio_correction() {
    let text = without_ratio_text();
    assert!(!text.contains("[ratio]") && !text.contains("face_reaction_linear"));
    let linear = Surrogate::from_toml_str(&text).unwrap();
    assert_eq!(linear.ratio, RatioCorrection::default());
    assert!(linear.ratio.is_zero());
    let full = Surrogate::from_toml_str(&potato_text()).unwrap();
    assert_eq!(linear.pre_fracture, full.pre_fracture);
    assert_eq!(linear.post_fracture, full.post_fracture);
}

#[test]
fn ratio_arrays_are_validated_and_named() {
    let text = potato_text();
    let line = text
        .lines()
        .find(|l| l.starts_with("face_reaction_linear = "))
        .unwrap();
    // Too short.
    let t = text.replace(line, "face_reaction_linear = [0.0, 1.0]");
    let e = Surrogate::from_toml_str(&t).unwrap_err();
    assert!(e.to_string().contains("face_reaction_linear"), "{e}");
    // Not finite.
    let bad = line.replacen('[', "[nan, ", 1);
    let bad = {
        // Keep the length: drop the last element.
        let cut = bad.rfind(',').unwrap();
        format!("{}]", &bad[..cut])
    };
    let t = text.replace(line, &bad);
    let e = Surrogate::from_toml_str(&t).unwrap_err();
    assert!(
        e.to_string().contains("ratio.face_reaction_linear[0]"),
        "{e}"
    );
    // A table missing one of its keys is refused and the key named.
    let line = text
        .lines()
        .find(|l| l.starts_with("strain_energy_rate_quadratic = "))
        .unwrap();
    let t = text.replace(line, "");
    let e = Surrogate::from_toml_str(&t).unwrap_err();
    assert!(
        e.to_string().contains("strain_energy_rate_quadratic"),
        "{e}"
    );
}
