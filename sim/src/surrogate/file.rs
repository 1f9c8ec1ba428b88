//! Reading and writing surrogate files (TOML, versioned).

use std::path::{Path, PathBuf};

use crate::array_lengths::check_array_lengths;
use crate::capped_read::{CappedReadError, read_capped_text};
use crate::invalid_setting::InvalidSetting;
use crate::resource_budget::CONFIG_FILE_BYTES;

use crate::toml_error::one_line;

use super::campaign::RATIO_STIFFNESS_FACTORS;
use super::model::{OLDEST_READ_FORMAT_VERSION, SURROGATE_FORMAT_VERSION, Surrogate};
use super::state::{CutState, ScaleFactors};
use crate::physical_range::number_text;

/// Why a surrogate file was refused. Each message names the key or value.
#[derive(Debug, thiserror::Error)]
pub enum SurrogateFileError {
    /// The file could not be read.
    #[error("cannot read surrogate file `{path}`: {source}")]
    Read {
        /// The file.
        path: PathBuf,
        /// Why.
        source: CappedReadError,
    },
    /// Not TOML, or a key is missing, unknown or of the wrong type.
    #[error("surrogate file: {0}")]
    Format(String),
    /// The key `version` is missing or not an integer.
    #[error(
        "surrogate file: missing integer key `version` (this build reads versions {oldest} to {expected})"
    )]
    MissingVersion {
        /// The oldest version this build reads.
        oldest: u32,
        /// The version this build writes (the newest it reads).
        expected: u32,
    },
    /// The file is of another format version.
    #[error(
        "surrogate file: `version` = {found}, but this build reads versions {oldest} to {expected}; refit with `shearcut fit`"
    )]
    WrongVersion {
        /// The version in the file.
        found: i64,
        /// The oldest version this build reads.
        oldest: u32,
        /// The version this build writes (the newest it reads).
        expected: u32,
    },
    /// A material or blade constant is out of its range.
    #[error("surrogate file: {0}")]
    Invalid(InvalidSetting),
    /// Every number is finite, but a prediction within the fitted range is
    /// not (a coefficient, range or blade out of any fit's scale).
    #[error(
        "surrogate file: its prediction `{output}` is not finite at ξ = {}, section height {} m, half width {} m, depth {} m, {}, E × {}: a coefficient, the range or the blade is out of scale; refit with `shearcut fit`",
        number_text(*.xi),
        number_text(*.height),
        number_text(*.half_width),
        number_text(*.depth),
        if *.fractured { "after the first fracture" } else { "before the first fracture" },
        number_text(*.stiffness)
    )]
    NonFinitePrediction {
        /// The output, e.g. `force_normal` or `work_per_depth_parts.by_stiffness`.
        output: String,
        /// Slice-push ratio.
        xi: f64,
        /// Section height, m.
        height: f64,
        /// Section half width, m.
        half_width: f64,
        /// Depth of the edge below the top, m.
        depth: f64,
        /// Whether after the first fracture.
        fractured: bool,
        /// The stiffness factor (1: the nominal material).
        stiffness: f64,
    },
    /// A number is not finite (or a physical constant not positive).
    #[error("surrogate file: `{key}` = {} {allowed}", number_text(*.value))]
    BadValue {
        /// The key, e.g. `post_fracture.split[1]`.
        key: String,
        /// The value.
        value: f64,
        /// What is allowed.
        allowed: &'static str,
    },
}

impl Surrogate {
    /// Reads a surrogate file (see [`Self::from_toml_str`]): at most
    /// [`CONFIG_FILE_BYTES`] of UTF-8 text.
    pub fn from_path(path: &Path) -> Result<Self, SurrogateFileError> {
        let text = read_capped_text(path, CONFIG_FILE_BYTES).map_err(|source| {
            SurrogateFileError::Read {
                path: path.to_path_buf(),
                source,
            }
        })?;
        Self::from_toml_str(&text)
    }

    /// Parses a surrogate from TOML: the `version` must be within
    /// [`OLDEST_READ_FORMAT_VERSION`]..=[`SURROGATE_FORMAT_VERSION`], every key present and known (the `[ratio]` table whole or not
    /// at all: a file without one reads as zero correction, the surrogate
    /// then linear in the scale factors), every coefficient finite and the
    /// material and blade constants within their physical ranges; every
    /// array exactly as long as its key takes; every prediction within the
    /// fitted range finite ([`Self::validate`]). Errors never quote the text.
    pub fn from_toml_str(text: &str) -> Result<Self, SurrogateFileError> {
        let table: toml::Table =
            toml::from_str(text).map_err(|e| SurrogateFileError::Format(one_line(text, &e)))?;
        match table.get("version").and_then(toml::Value::as_integer) {
            None => {
                return Err(SurrogateFileError::MissingVersion {
                    oldest: OLDEST_READ_FORMAT_VERSION,
                    expected: SURROGATE_FORMAT_VERSION,
                });
            }
            Some(v)
                if !(i64::from(OLDEST_READ_FORMAT_VERSION)
                    ..=i64::from(SURROGATE_FORMAT_VERSION))
                    .contains(&v) =>
            {
                return Err(SurrogateFileError::WrongVersion {
                    found: v,
                    oldest: OLDEST_READ_FORMAT_VERSION,
                    expected: SURROGATE_FORMAT_VERSION,
                });
            }
            Some(_) => {}
        }
        let s: Surrogate =
            toml::from_str(text).map_err(|e| SurrogateFileError::Format(one_line(text, &e)))?;
        let read =
            toml::Value::try_from(&s).map_err(|e| SurrogateFileError::Format(e.to_string()))?;
        check_array_lengths(&toml::Value::Table(table), &read)
            .map_err(SurrogateFileError::Invalid)?;
        s.validate()?;
        Ok(s)
    }

    /// Checks that every output, slope and part is finite at the ends and
    /// middles of the fitted range: ξ at 0, ¼, ½, ¾ and 1 of `xi_max`; the
    /// smallest, middle and largest height and half width; depths of 10,
    /// 50 and 90 % of the height; before the first fracture and after it
    /// (the travel since it half the depth); at the nominal material and
    /// at the stiffness factors of the ratio correction's fit
    /// ([`RATIO_STIFFNESS_FACTORS`]): 810 evaluations.
    fn check_predictions(&self) -> Result<(), SurrogateFileError> {
        let r = &self.range;
        let ends_and_middle = |[lo, hi]: [f64; 2]| [lo, 0.5 * (lo + hi), hi];
        let stiffnesses = std::iter::once(1.0).chain(RATIO_STIFFNESS_FACTORS);
        for stiffness in stiffnesses {
            let scale = ScaleFactors {
                stiffness,
                ..ScaleFactors::default()
            };
            for xi in [0.0, 0.25, 0.5, 0.75, 1.0].map(|f| f * r.xi_max) {
                for (height, half_width) in ends_and_middle(r.height)
                    .into_iter()
                    .flat_map(|h| ends_and_middle(r.half_width).map(|w| (h, w)))
                {
                    for (depth, fractured) in [0.1, 0.5, 0.9]
                        .into_iter()
                        .flat_map(|f| [(f * height, false), (f * height, true)])
                    {
                        let state = CutState {
                            depth,
                            height,
                            half_width,
                            fractured,
                            travel_since_fracture: 0.5 * depth,
                        };
                        if let Some(output) = self.evaluate(xi, &state, &scale).first_non_finite() {
                            return Err(SurrogateFileError::NonFinitePrediction {
                                output,
                                xi,
                                height,
                                half_width,
                                depth,
                                fractured,
                                stiffness,
                            });
                        }
                    }
                }
            }
        }
        Ok(())
    }

    /// The surrogate as TOML.
    pub fn to_toml_string(&self) -> String {
        // Serialising plain structs of numbers, strings and arrays cannot fail.
        toml::to_string(self).unwrap_or_default()
    }

    /// Every number of the surrogate with its key, in file order.
    pub fn named_values(&self) -> Vec<(String, f64)> {
        let mut v = Vec::new();
        let m = &self.material;
        for (k, x) in [
            ("material.youngs_modulus", m.youngs_modulus),
            ("material.poisson_ratio", m.poisson_ratio),
            ("material.friction_coefficient", m.friction_coefficient),
            ("material.fracture_toughness", m.fracture_toughness),
            (
                "material.initial_fracture_toughness",
                m.initial_fracture_toughness,
            ),
            ("blade.thickness", self.blade.thickness),
            ("blade.bevel_angle", self.blade.bevel_angle),
            ("blade.edge_width", self.blade.edge_width),
            ("range.xi_max", self.range.xi_max),
        ] {
            v.push((k.to_string(), x));
        }
        let mut arr = |key: &str, a: &[f64]| {
            for (i, x) in a.iter().enumerate() {
                v.push((format!("{key}[{i}]"), *x));
            }
        };
        arr("range.height", &self.range.height);
        arr("range.half_width", &self.range.half_width);
        let pre = &self.pre_fracture;
        arr("pre_fracture.normal_compliance", &pre.normal_compliance);
        arr(
            "pre_fracture.tangential_compliance",
            &pre.tangential_compliance,
        );
        arr("pre_fracture.deflection", &pre.deflection);
        arr("pre_fracture.onset", &pre.onset);
        let post = &self.post_fracture;
        arr("post_fracture.catch_up", &post.catch_up);
        arr("post_fracture.knee_width", &post.knee_width);
        arr("post_fracture.split", &post.split);
        arr("post_fracture.drag", &post.drag);
        arr("post_fracture.face_reaction", &post.face_reaction);
        arr("post_fracture.strain_energy_rate", &post.strain_energy_rate);
        arr("post_fracture.strain_depth_rate", &post.strain_depth_rate);
        arr(
            "post_fracture.face_reaction_slice",
            &post.face_reaction_slice,
        );
        arr("post_fracture.deflection", &post.deflection);
        let ratio = &self.ratio;
        arr(
            "ratio.strain_energy_rate_linear",
            &ratio.strain_energy_rate_linear,
        );
        arr(
            "ratio.strain_energy_rate_quadratic",
            &ratio.strain_energy_rate_quadratic,
        );
        arr("ratio.face_reaction_linear", &ratio.face_reaction_linear);
        arr(
            "ratio.face_reaction_quadratic",
            &ratio.face_reaction_quadratic,
        );
        arr(
            "ratio.face_reaction_slice_linear",
            &ratio.face_reaction_slice_linear,
        );
        arr(
            "ratio.face_reaction_slice_quadratic",
            &ratio.face_reaction_slice_quadratic,
        );
        arr(
            "ratio.face_reaction_slice_size_linear",
            &ratio.face_reaction_slice_size_linear,
        );
        arr(
            "ratio.face_reaction_slice_size_quadratic",
            &ratio.face_reaction_slice_size_quadratic,
        );
        arr("ratio.drag_linear", &ratio.drag_linear);
        arr("ratio.drag_quadratic", &ratio.drag_quadratic);
        v.push(("post_fracture.knee_lead".to_string(), post.knee_lead));
        v.push((
            "ratio.catch_up_exponent".to_string(),
            ratio.catch_up_exponent,
        ));
        v.push(("post_fracture.slip_ratio".to_string(), post.slip_ratio));
        v
    }

    /// Checks that every number is finite, the physical constants valid,
    /// and every prediction within the fitted range finite (see
    /// `check_predictions`).
    pub fn validate(&self) -> Result<(), SurrogateFileError> {
        for (key, value) in self.named_values() {
            if !value.is_finite() {
                return Err(SurrogateFileError::BadValue {
                    key,
                    value,
                    allowed: "must be a finite number",
                });
            }
        }
        let r = &self.range;
        let bad = |key: &str, value: f64, allowed: &'static str| {
            Err(SurrogateFileError::BadValue {
                key: key.to_string(),
                value,
                allowed,
            })
        };
        if r.xi_max <= 0.0 {
            return bad("range.xi_max", r.xi_max, "must be positive");
        }
        for (key, [lo, hi]) in [
            ("range.height", r.height),
            ("range.half_width", r.half_width),
        ] {
            if lo <= 0.0 {
                return bad(&format!("{key}[0]"), lo, "must be a positive size, m");
            }
            if hi < lo {
                return bad(&format!("{key}[1]"), hi, "must be at least [0]");
            }
        }
        let k = self.ratio.catch_up_exponent;
        if !(0.0..=4.0).contains(&k) {
            return bad(
                "ratio.catch_up_exponent",
                k,
                "must be in [0, 4] (fit writes 1)",
            );
        }
        let [kappa, beta] = self.post_fracture.knee_width;
        for (i, w) in [kappa, beta].into_iter().enumerate() {
            if w < 0.0 {
                return Err(SurrogateFileError::BadValue {
                    key: format!("post_fracture.knee_width[{i}]"),
                    value: w,
                    allowed: "must be non-negative",
                });
            }
        }
        let slip = self.post_fracture.slip_ratio;
        if slip <= 0.0 {
            return Err(SurrogateFileError::BadValue {
                key: "post_fracture.slip_ratio".to_string(),
                value: slip,
                allowed: "must be positive",
            });
        }
        let weight = self.fit_window_weight;
        if !(weight.is_finite() && weight >= 0.0) {
            return Err(SurrogateFileError::BadValue {
                key: "fit_window_weight".to_string(),
                value: weight,
                allowed: "must be a finite number >= 0",
            });
        }
        let lead = self.post_fracture.knee_lead;
        if lead < 0.0 {
            return Err(SurrogateFileError::BadValue {
                key: "post_fracture.knee_lead".to_string(),
                value: lead,
                allowed: "must be non-negative",
            });
        }
        if kappa + beta <= 0.0 {
            return Err(SurrogateFileError::BadValue {
                key: "post_fracture.knee_width[0]".to_string(),
                value: kappa,
                allowed: "must be positive when knee_width[1] is 0 (the knee needs a width)",
            });
        }
        self.material
            .validate()
            .map_err(|e| SurrogateFileError::Invalid(e.prefixed("material")))?;
        self.blade
            .section()
            .validate()
            .map_err(|e| SurrogateFileError::Invalid(e.prefixed("blade")))?;
        self.check_predictions()
    }
}
