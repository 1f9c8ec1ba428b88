//! Linear elastic, brittle-in-the-seed's-sense food materials.
//!
//! The presets are the four rows of seed 000 Table I (potato and eggplant, cuboid
//! pieces without skin and whole objects with skin) plus the agar gel of seed 001.

use serde::{Deserialize, Serialize};

use crate::invalid_setting::{InvalidSetting, non_negative, positive};
use crate::physical_range::{
    FRACTURE_TOUGHNESS, FRICTION_COEFFICIENT, POISSON_RATIO, SKIN_THICKNESS, YOUNGS_MODULUS,
};

/// Mechanical properties of a food material (seed 000 Table I).
///
/// All fields are SI. Forces in a 2D cross section are per unit length of edge,
/// so toughness is in N/m (J/m²).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Material {
    /// Young's modulus E, Pa.
    pub youngs_modulus: f64,
    /// Poisson's ratio ν, dimensionless, in [0, 0.49] (see
    /// [`crate::physical_range::POISSON_RATIO`]).
    pub poisson_ratio: f64,
    /// Coefficient of Coulomb friction μ between blade and material, dimensionless.
    pub friction_coefficient: f64,
    /// Interior fracture toughness R_c for pressing, N/m.
    pub fracture_toughness: f64,
    /// Initial fracture toughness R'_c, N/m: the toughness until the first
    /// fracture (a skin, or the stress concentration that a soft material lacks
    /// before a crack exists). Seed 000 §V.
    pub initial_fracture_toughness: f64,
    /// Thickness of the skin, m (optional, ≥ 0; default: none).
    ///
    /// Given, the skin is a surface layer of toughness R'_c: a crack tip
    /// within `skin_thickness` of the section's top (the object's outer
    /// surface in that plane) grows against R'_c, deeper against R_c, and a
    /// step's extension pays the depth-weighted toughness of the layers it
    /// crosses. It depends on the depth only, so a section that starts below
    /// the skin (a moving section's successor deep in the cut) gets R_c at
    /// once, and 0 means R_c throughout.
    ///
    /// Not given (the presets; Table I gives R'_c but no thickness), R'_c
    /// holds until the section's first fracture, however deep that is: seed
    /// 000 §V's initial toughness.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub skin_thickness: Option<f64>,
}

/// The named material presets.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum MaterialPreset {
    /// Potato, cuboid pieces without skin (Table I row 1).
    PotatoCuboid,
    /// Eggplant, cuboid pieces without skin (Table I row 2).
    EggplantCuboid,
    /// Whole potato with skin (Table I row 3).
    PotatoWhole,
    /// Whole eggplant with skin (Table I row 4).
    EggplantWhole,
    /// Agar gel of seed 001: shear modulus 35 kPa, bulk modulus 30 × shear modulus.
    Agar,
}

impl MaterialPreset {
    /// Every preset, in documentation order.
    pub const ALL: [MaterialPreset; 5] = [
        MaterialPreset::PotatoCuboid,
        MaterialPreset::EggplantCuboid,
        MaterialPreset::PotatoWhole,
        MaterialPreset::EggplantWhole,
        MaterialPreset::Agar,
    ];

    /// The preset's name as used in config files.
    pub fn name(self) -> &'static str {
        match self {
            MaterialPreset::PotatoCuboid => "potato-cuboid",
            MaterialPreset::EggplantCuboid => "eggplant-cuboid",
            MaterialPreset::PotatoWhole => "potato-whole",
            MaterialPreset::EggplantWhole => "eggplant-whole",
            MaterialPreset::Agar => "agar",
        }
    }

    /// Looks a preset up by its config name.
    pub fn from_name(name: &str) -> Option<Self> {
        Self::ALL.into_iter().find(|p| p.name() == name)
    }

    /// The material of this preset.
    pub fn material(self) -> Material {
        match self {
            MaterialPreset::PotatoCuboid => Material {
                youngs_modulus: 2.0e6,
                poisson_ratio: 0.4,
                friction_coefficient: 0.1,
                fracture_toughness: 150.0,
                initial_fracture_toughness: 150.0,
                skin_thickness: None,
            },
            MaterialPreset::EggplantCuboid => Material {
                youngs_modulus: 0.4e6,
                poisson_ratio: 0.35,
                friction_coefficient: 1.0,
                fracture_toughness: 140.0,
                initial_fracture_toughness: 275.0,
                skin_thickness: None,
            },
            MaterialPreset::PotatoWhole => Material {
                youngs_modulus: 2.0e6,
                poisson_ratio: 0.4,
                friction_coefficient: 0.1,
                fracture_toughness: 230.0,
                initial_fracture_toughness: 230.0,
                skin_thickness: None,
            },
            MaterialPreset::EggplantWhole => Material {
                youngs_modulus: 0.55e6,
                poisson_ratio: 0.35,
                friction_coefficient: 1.0,
                fracture_toughness: 260.0,
                initial_fracture_toughness: 650.0,
                skin_thickness: None,
            },
            MaterialPreset::Agar => Material::from_shear_and_bulk(
                AGAR_SHEAR_MODULUS,
                30.0 * AGAR_SHEAR_MODULUS,
                // Seed 001 gives neither friction nor toughness. Friction: a
                // smooth wire on wet gel slides easily; 0.1 is an assumption.
                0.1,
                // Toughness: agar gels of ~1.5 % concentration have fracture
                // energies of a few J/m²; 5 N/m is an order-of-magnitude value,
                // not a seed figure.
                AGAR_FRACTURE_TOUGHNESS,
                AGAR_FRACTURE_TOUGHNESS,
            ),
        }
    }
}

/// Shear modulus of the agar of seed 001, Pa.
pub const AGAR_SHEAR_MODULUS: f64 = 35.0e3;
/// Fracture toughness assumed for agar, N/m (not given by seed 001).
pub const AGAR_FRACTURE_TOUGHNESS: f64 = 5.0;

impl Material {
    /// A material from shear modulus μ and bulk modulus K (isotropic identities
    /// E = 9Kμ/(3K+μ), ν = (3K−2μ)/(2(3K+μ))).
    pub fn from_shear_and_bulk(
        shear_modulus: f64,
        bulk_modulus: f64,
        friction_coefficient: f64,
        fracture_toughness: f64,
        initial_fracture_toughness: f64,
    ) -> Self {
        let (g, k) = (shear_modulus, bulk_modulus);
        Self {
            youngs_modulus: 9.0 * k * g / (3.0 * k + g),
            poisson_ratio: (3.0 * k - 2.0 * g) / (2.0 * (3.0 * k + g)),
            friction_coefficient,
            fracture_toughness,
            initial_fracture_toughness,
            skin_thickness: None,
        }
    }

    /// Shear modulus G = E / (2(1+ν)), Pa.
    pub fn shear_modulus(&self) -> f64 {
        self.youngs_modulus / (2.0 * (1.0 + self.poisson_ratio))
    }

    /// Plane-strain modulus E' = E / (1 − ν²), Pa.
    pub fn plane_strain_modulus(&self) -> f64 {
        self.youngs_modulus / (1.0 - self.poisson_ratio * self.poisson_ratio)
    }

    /// Checks every field against its physical range
    /// ([`crate::physical_range`]), as a material read from a file must
    /// be; the error names the key, the value and the range.
    pub fn validate(&self) -> Result<(), InvalidSetting> {
        YOUNGS_MODULUS.check("youngs_modulus", self.youngs_modulus)?;
        POISSON_RATIO.check("poisson_ratio", self.poisson_ratio)?;
        FRICTION_COEFFICIENT.check("friction_coefficient", self.friction_coefficient)?;
        FRACTURE_TOUGHNESS.check("fracture_toughness", self.fracture_toughness)?;
        FRACTURE_TOUGHNESS.check(
            "initial_fracture_toughness",
            self.initial_fracture_toughness,
        )?;
        if let Some(t) = self.skin_thickness {
            SKIN_THICKNESS.check("skin_thickness", t)?;
        }
        Ok(())
    }

    /// Checks only what the cross-section equations need (E and the
    /// toughnesses finite and positive, ν in the open interval (0, 0.5),
    /// μ and the skin finite and non-negative): a model built in code may
    /// step outside the physical ranges, e.g. a toughness of 1e9 N/m to
    /// keep a section from fracturing.
    pub fn validate_domain(&self) -> Result<(), InvalidSetting> {
        positive("youngs_modulus", self.youngs_modulus)?;
        let nu = self.poisson_ratio;
        if !(nu.is_finite() && nu > 0.0 && nu < 0.5) {
            return Err(InvalidSetting::new(
                "poisson_ratio",
                nu,
                "must be in the open interval (0, 0.5)",
            ));
        }
        non_negative("friction_coefficient", self.friction_coefficient)?;
        positive("fracture_toughness", self.fracture_toughness)?;
        positive(
            "initial_fracture_toughness",
            self.initial_fracture_toughness,
        )?;
        non_negative("skin_thickness", self.skin_thickness.unwrap_or(0.0))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn presets_are_valid_and_named_uniquely() {
        for p in MaterialPreset::ALL {
            p.material().validate().unwrap();
            assert_eq!(MaterialPreset::from_name(p.name()), Some(p));
        }
    }

    #[test]
    fn table_one_eggplant_whole_row() {
        let m = MaterialPreset::EggplantWhole.material();
        assert_eq!(m.youngs_modulus, 0.55e6);
        assert_eq!(m.fracture_toughness, 260.0);
        assert_eq!(m.initial_fracture_toughness, 650.0);
    }

    #[test]
    fn skin_thickness_is_optional_and_validated() {
        let m = MaterialPreset::EggplantWhole.material();
        assert_eq!(m.skin_thickness, None);
        for ok in [0.0, 5e-4] {
            Material {
                skin_thickness: Some(ok),
                ..m
            }
            .validate()
            .unwrap();
        }
        for bad in [-1e-3, f64::NAN, f64::INFINITY] {
            let e = Material {
                skin_thickness: Some(bad),
                ..m
            }
            .validate()
            .unwrap_err();
            assert_eq!(e.key, "skin_thickness");
        }
        let parsed: Material = serde_json::from_str(
            r#"{"youngs_modulus": 1e6, "poisson_ratio": 0.3, "friction_coefficient": 0.1,
                "fracture_toughness": 100.0, "initial_fracture_toughness": 200.0,
                "skin_thickness": 1e-3}"#,
        )
        .unwrap();
        assert_eq!(parsed.skin_thickness, Some(1e-3));
    }

    #[test]
    fn agar_moduli_round_trip() {
        let m = MaterialPreset::Agar.material();
        // G recovered from E and ν equals the seed's 35 kPa.
        assert!((m.shear_modulus() - AGAR_SHEAR_MODULUS).abs() < 1e-9 * AGAR_SHEAR_MODULUS);
        // K = 30 μ gives ν = 88/182.
        assert!((m.poisson_ratio - 88.0 / 182.0).abs() < 1e-15);
    }

    #[test]
    fn poisson_ratio_out_of_range_names_the_key() {
        let mut m = MaterialPreset::PotatoCuboid.material();
        m.poisson_ratio = 0.7;
        let e = m.validate().unwrap_err();
        assert_eq!(e.key, "poisson_ratio");
        assert!(e.to_string().contains("[0, 0.49]"), "{e}");
    }
}
