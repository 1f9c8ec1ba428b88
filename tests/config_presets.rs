//! The preset files shipped in `config/` say exactly what the code's presets say.

use shearcut_sim::{KnifePreset, KnifeSettings, Material, MaterialPreset};

fn config(rel: &str) -> String {
    std::fs::read_to_string(format!("{}/config/{rel}", env!("CARGO_MANIFEST_DIR"))).unwrap()
}

#[test]
fn material_files_match_presets() {
    for p in MaterialPreset::ALL {
        let file: Material =
            toml::from_str(&config(&format!("materials/{}.toml", p.name()))).unwrap();
        let code = p.material();
        // Agar's E and ν are derived from μ and K; the file holds them to 17 digits.
        for (a, b) in [
            (file.youngs_modulus, code.youngs_modulus),
            (file.poisson_ratio, code.poisson_ratio),
            (file.friction_coefficient, code.friction_coefficient),
            (file.fracture_toughness, code.fracture_toughness),
            (
                file.initial_fracture_toughness,
                code.initial_fracture_toughness,
            ),
        ] {
            assert!((a - b).abs() <= 1e-15 * b.abs(), "{}: {a} vs {b}", p.name());
        }
        assert_eq!(file.skin_thickness, code.skin_thickness, "{}", p.name());
    }
}

#[test]
fn knife_files_match_presets() {
    for p in KnifePreset::ALL {
        let file: KnifeSettings =
            toml::from_str(&config(&format!("knives/{}.toml", p.name()))).unwrap();
        assert_eq!(file, p.settings(), "{}", p.name());
    }
}
