//! The ranges a real cutting cell could have, in one place.
//!
//! Every numeric setting of the model is checked against one of these
//! ranges when it is loaded (and by `shearcut check`); an error names the
//! key, the value and the range. The ranges are wide enough for any food a
//! kitchen knife or a wire cuts and narrow enough that the model's
//! arithmetic stays finite and its memory and run time stay bounded: a
//! value outside them is a typing mistake or a unit slip, never a cell.

use crate::invalid_setting::InvalidSetting;

/// A closed interval `[min, max]` of allowed values with their unit.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PhysicalRange {
    /// Smallest allowed value.
    pub min: f64,
    /// Largest allowed value.
    pub max: f64,
    /// Unit shown in messages (`m`, `Pa`, `N/m`, or empty).
    pub unit: &'static str,
}

impl PhysicalRange {
    /// The range `[min, max]` in `unit`.
    pub const fn new(min: f64, max: f64, unit: &'static str) -> Self {
        Self { min, max, unit }
    }

    /// The same range with its upper end lowered to `max` (when `max` is
    /// below it): a bound tied to another setting, e.g. a depth below the
    /// object's height.
    #[must_use]
    pub fn at_most(self, max: f64) -> Self {
        Self {
            max: self.max.min(max),
            ..self
        }
    }

    /// The same range with its lower end raised to `min` (when `min` is above it).
    #[must_use]
    pub fn at_least(self, min: f64) -> Self {
        Self {
            min: self.min.max(min),
            ..self
        }
    }

    /// Whether `value` is finite and within the range (NaN is not).
    pub fn contains(&self, value: f64) -> bool {
        value.is_finite() && value >= self.min && value <= self.max
    }

    /// `Ok` when `value` is in the range, else an error naming `key`, the
    /// value and the range.
    pub fn check(&self, key: &str, value: f64) -> Result<(), InvalidSetting> {
        if self.contains(value) {
            Ok(())
        } else {
            Err(InvalidSetting::new(key, number_text(value), self.allowed()))
        }
    }

    /// Checks every element of `values`, naming `key[i]` for the first one out of range.
    pub fn check_each(&self, key: &str, values: &[f64]) -> Result<(), InvalidSetting> {
        for (i, v) in values.iter().enumerate() {
            self.check(&format!("{key}[{i}]"), *v)?;
        }
        Ok(())
    }

    /// The sentence of an error: `must be in [min, max] unit`.
    pub fn allowed(&self) -> String {
        let unit = if self.unit.is_empty() {
            String::new()
        } else {
            format!(" {}", self.unit)
        };
        format!(
            "must be in [{}, {}]{unit}",
            number_text(self.min),
            number_text(self.max)
        )
    }
}

/// Checks an integer setting against `[min, max]`.
pub fn check_count(key: &str, value: u64, min: u64, max: u64) -> Result<(), InvalidSetting> {
    if (min..=max).contains(&value) {
        Ok(())
    } else {
        Err(InvalidSetting::new(
            key,
            value,
            format!("must be an integer in [{min}, {max}]"),
        ))
    }
}

/// A number as a short token for a one-line message: plain for ordinary
/// magnitudes, scientific (`1e300`, `5e-324`) for very large or small ones.
/// Beyond 16 characters (a bound computed as 2.0000000000000002e-7) the
/// number is rounded to 12 significant digits.
pub fn number_text(value: f64) -> String {
    let a = value.abs();
    let scientific = value.is_finite() && a != 0.0 && !(1e-4..1e6).contains(&a);
    let text = if scientific {
        format!("{value:e}")
    } else {
        format!("{value}")
    };
    if text.len() <= 16 || !value.is_finite() {
        return text;
    }
    let rounded: f64 = format!("{value:.11e}").parse().unwrap_or(value);
    if scientific {
        format!("{rounded:e}")
    } else {
        format!("{rounded}")
    }
}

/// Size of an object (cuboid sides, a natural shape's length, width,
/// height, diameter; a mesh's bounding box), m: a pea to a pumpkin.
pub const OBJECT_SIZE: PhysicalRange = PhysicalRange::new(1e-3, 1.0, "m");

/// Young's modulus E, Pa: soft gels (a few kPa) to raw roots (tens of MPa).
pub const YOUNGS_MODULUS: PhysicalRange = PhysicalRange::new(1e3, 1e8, "Pa");

/// Poisson's ratio ν. Above 0.49 the plane-strain elements lock and seed
/// 000 eq. 6's factor 1 − ν − 2ν² = (1 − 2ν)(1 + ν) goes to zero, so the
/// slicing toughness collapses: a cut then "completes" in a few ticks at
/// no work. Agar (ν = 0.4835, seed 001's K = 30μ) is inside.
pub const POISSON_RATIO: PhysicalRange = PhysicalRange::new(0.0, 0.49, "");

/// Coulomb friction coefficient μ between blade and food (Table I: 0.1 to 1).
pub const FRICTION_COEFFICIENT: PhysicalRange = PhysicalRange::new(0.0, 2.0, "");

/// Fracture toughness R_c or R'_c, N/m (agar ≈ 5, eggplant skin 650).
pub const FRACTURE_TOUGHNESS: PhysicalRange = PhysicalRange::new(0.1, 1e4, "N/m");

/// Skin thickness, m: none up to the whole object.
pub const SKIN_THICKNESS: PhysicalRange = PhysicalRange::new(0.0, 1.0, "m");

/// Length of a knife's edge or a wire, m.
pub const EDGE_LENGTH: PhysicalRange = PhysicalRange::new(5e-3, 1.0, "m");

/// A coordinate of a point in the knife frame (polyline edge points, the
/// sensor mount), m.
pub const KNIFE_COORDINATE: PhysicalRange = PhysicalRange::new(-1.0, 1.0, "m");

/// Most points of a polyline edge.
pub const MAX_EDGE_POINTS: u64 = 10_000;

/// Shortest step in z between two polyline edge points, m.
pub const MIN_EDGE_CHORD: f64 = 1e-6;

/// Radius of a cutting wire, m (seed 001: about 150 µm); at least 50 µm,
/// so that the wedge standing in for it (2R thick) is a valid blade.
pub const WIRE_RADIUS: PhysicalRange = PhysicalRange::new(5e-5, 5e-3, "m");

/// Full thickness of a blade, m.
pub const BLADE_THICKNESS: PhysicalRange = PhysicalRange::new(1e-4, 0.02, "m");

/// Bevel angle of a blade face to its mid-plane, rad (about 0.6° to 80°).
pub const BEVEL_ANGLE: PhysicalRange = PhysicalRange::new(0.01, 1.4, "rad");

/// Width of the edge flat, m (its upper end is the blade's thickness).
pub const EDGE_WIDTH: PhysicalRange = PhysicalRange::new(1e-6, 0.02, "m");

/// Knife speed of a prescribed motion or a controller, m/s.
pub const KNIFE_SPEED: PhysicalRange = PhysicalRange::new(1e-4, 1.0, "m/s");

/// Slice-push ratio ξ = tan α (20 is α ≈ 87°).
pub const SLICE_PUSH_RATIO: PhysicalRange = PhysicalRange::new(0.0, 20.0, "");

/// Most cuts (slice-push ratios) of one `simulate`.
pub const MAX_CUTS: u64 = 64;

/// Distance along the edge from the heel to the object, m.
pub const EDGE_OFFSET: PhysicalRange = PhysicalRange::new(0.0, 1.0, "m");

/// Knife displacement per step of the single-section model, m. Its lower
/// end is also tied to the mesh: at least 1/1000 of the row spacing.
pub const MOTION_STEP: PhysicalRange = PhysicalRange::new(1e-7, 1e-3, "m");

/// Smallest motion step as a fraction of the section's row spacing.
pub const MIN_STEP_PER_ROW: f64 = 1e-3;

/// Row spacing of a section mesh along the cut line, m. The mesh's size
/// is bounded separately (see [`crate::resource_budget`]).
pub const ROW_SPACING: PhysicalRange = PhysicalRange::new(1e-5, 5e-3, "m");

/// Largest element width of a section mesh, m.
pub const ELEMENT_WIDTH: PhysicalRange = PhysicalRange::new(1e-5, 0.05, "m");

/// Grading ratio of element widths away from the cut line.
pub const GRADING_RATIO: PhysicalRange = PhysicalRange::new(1.0, 3.0, "");

/// Initial trial crack extension δ₀ (a flaw size), m; at most the row spacing.
pub const INITIAL_CRACK_EXTENSION: PhysicalRange = PhysicalRange::new(1e-9, 1e-4, "m");

/// Relative tolerance of the fracture root search.
pub const ROOT_TOLERANCE: PhysicalRange = PhysicalRange::new(1e-12, 1e-2, "");

/// Fewest and most doublings of the trial crack extension. The fewest
/// take the smallest flaw (1e-9 m) past the largest object (1 m), 2³⁰ >
/// 10⁹, so no step is left unbracketed for want of doublings (with fewer,
/// the crack lags the knife and the knife's work grows by tens of times
/// while the run still "completes").
pub const BRACKET_DOUBLINGS: (u64, u64) = (30, 200);

/// Fewest and most root-search iterations per step. The fewest let the
/// midpoint fallback reach machine precision on any bracket (52 halvings).
pub const ROOT_ITERATIONS: (u64, u64) = (60, 10_000);

/// Loop and sensor rates, Hz (an F/T interface samples at up to 7 kHz;
/// 100 kHz is far beyond any arm).
pub const RATE: PhysicalRange = PhysicalRange::new(1.0, 1e5, "Hz");

/// Arm speed limit, m/s.
pub const ARM_VELOCITY: PhysicalRange = PhysicalRange::new(1e-3, 10.0, "m/s");

/// Arm acceleration limit, m/s².
pub const ARM_ACCELERATION: PhysicalRange = PhysicalRange::new(1e-2, 100.0, "m/s^2");

/// Arm jerk limit, m/s³ (FR3: 4500). Far larger limits overflow the
/// trajectory generator's cubic terms: the knife then never moves.
pub const ARM_JERK: PhysicalRange = PhysicalRange::new(1.0, 1e5, "m/s^3");

/// Standard deviation of F/T force noise, N.
pub const FORCE_NOISE: PhysicalRange = PhysicalRange::new(0.0, 100.0, "N");

/// Standard deviation of F/T torque noise, N·m.
pub const TORQUE_NOISE: PhysicalRange = PhysicalRange::new(0.0, 10.0, "N m");

/// A bias of the F/T sensor, N or N·m.
pub const SENSOR_BIAS: PhysicalRange = PhysicalRange::new(-1e3, 1e3, "N or N m");

/// A distance of the plant's geometry (start gap, reach), m.
pub const PLANT_DISTANCE: PhysicalRange = PhysicalRange::new(0.0, 1.0, "m");

/// How far a segment may slide before its section is re-chosen, m.
pub const UPDATE_DISTANCE: PhysicalRange = PhysicalRange::new(1e-5, 0.05, "m");

/// Longest simulated closed-loop run, s.
pub const RUN_DURATION: PhysicalRange = PhysicalRange::new(1e-2, 3600.0, "s");

/// A force setpoint or limit, N.
pub const FORCE: PhysicalRange = PhysicalRange::new(1e-3, 1e4, "N");

/// Consecutive missed commands before the plant brakes.
pub const MISSED_COMMANDS: (u64, u64) = (1, 1000);

/// Cycle time of a trajectory case, s (1 Hz to 100 kHz).
pub const CYCLE_TIME: PhysicalRange = PhysicalRange::new(1e-5, 1.0, "s");

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn messages_name_key_value_and_range_on_one_line() {
        let e = OBJECT_SIZE.check("object.width", 1e300).unwrap_err();
        assert_eq!(
            e.to_string(),
            "`object.width` = 1e300: must be in [0.001, 1] m"
        );
        let e = POISSON_RATIO.check("poisson_ratio", f64::NAN).unwrap_err();
        assert_eq!(e.to_string(), "`poisson_ratio` = NaN: must be in [0, 0.49]");
        let e = CYCLE_TIME.check("cycle_time", 5e-324).unwrap_err();
        assert!(e.to_string().contains("5e-324"), "{e}");
        assert_eq!(number_text(2.0000000000000002e-7), "2e-7");
        assert_eq!(number_text(0.1 + 0.2), "0.3");
    }

    #[test]
    fn bounds_are_inclusive_and_tied_bounds_narrow_only() {
        assert!(OBJECT_SIZE.contains(1e-3) && OBJECT_SIZE.contains(1.0));
        assert!(!OBJECT_SIZE.contains(f64::INFINITY));
        assert_eq!(OBJECT_SIZE.at_most(2.0).max, 1.0);
        assert_eq!(OBJECT_SIZE.at_most(0.5).max, 0.5);
        assert_eq!(OBJECT_SIZE.at_least(0.0).min, 1e-3);
    }

    #[test]
    fn doublings_reach_the_largest_object_from_the_smallest_flaw() {
        let reach = INITIAL_CRACK_EXTENSION.min * 2f64.powi(BRACKET_DOUBLINGS.0 as i32);
        assert!(reach >= OBJECT_SIZE.max, "{reach}");
    }
}
