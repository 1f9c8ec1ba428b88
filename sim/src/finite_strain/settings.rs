//! Settings of the finite-strain wire–slab model (seed 001).

use serde::{Deserialize, Serialize};

use crate::invalid_setting::InvalidSetting;
use crate::physical_range::{PhysicalRange, WIRE_RADIUS};

/// How the slab's sides (X = ±L/2) are held.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum SideSupport {
    /// The sides move only vertically (seed 001's slabs): u_x = u_z = 0.
    Roller,
    /// The sides are free (the section FEM's rectangle, for comparisons).
    Free,
}

/// What presses on the top surface.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Indenter {
    /// The rigid wire of radius `wire_radius` (penalty contact).
    Wire,
    /// A rigid, frictionless flat punch of half width `wire_radius`: the top
    /// nodes with |X| ≤ R move down by d, sliding freely sideways (the edge
    /// strip of the section FEM, for the small-d comparison).
    FlatPunch,
}

/// Settings of [`WireSlab`](super::WireSlab): the slab, the wire, the mesh,
/// contact, loading and the solver. SI units.
///
/// Mesh settings fix the model's size and are read at construction.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct WireSlabSettings {
    /// Shear modulus μ of the gel, Pa (default 35e3, seed 001's agar).
    pub shear_modulus: f64,
    /// Bulk modulus as a multiple of μ, K/μ (default 30, seed 001).
    pub bulk_modulus_ratio: f64,
    /// Wire radius R, m (default 150e-6).
    pub wire_radius: f64,
    /// Length of wire in contact, the slab's thickness h along the wire, m
    /// (default 5e-3): forces per unit length are multiplied by it.
    pub wire_length: f64,
    /// Width L of the slab across the wire (the periodic slab's cross
    /// section is L × B), m (default 40e-3).
    pub slab_width: f64,
    /// Depth B of the slab below the surface the wire presses on, m
    /// (default 40e-3).
    pub slab_depth: f64,
    /// How the sides are held (default `roller`: vertical motion only).
    pub sides: SideSupport,
    /// What presses on the surface (default `wire`).
    pub indenter: Indenter,
    /// Element rows per wire radius in the fine zone (default 6).
    pub elements_per_radius: usize,
    /// Element columns of the fine zone per element row: its elements are
    /// this many times taller than wide, so that the surface under the wire,
    /// stretched about threefold along itself at nucleation, is resolved
    /// along the wire's circumference (default 3; 1 = square elements).
    pub column_refinement: usize,
    /// Extent of the uniformly fine zone from the wire's line, in wire radii
    /// (default 2), both across and down.
    pub fine_zone_radii: f64,
    /// Growth ratio of element sizes beyond the fine zone (default 1.5).
    pub grading_ratio: f64,
    /// Largest element size, m (default 4e-3).
    pub max_element_size: f64,
    /// Contact penalty κ: contact pressure κμ per penetration R
    /// (dimensionless, default 1e3).
    pub contact_penalty: f64,
    /// Friction coefficient along the wire μ_f = f_t/f_n at sliding
    /// (default 1.0; `inf` = no slip).
    pub friction_coefficient: f64,
    /// Load step: increment of the wire's depth d per step, m (default
    /// 20e-6); steps are halved (at most 6 times) where Newton's method fails.
    pub depth_step: f64,
    /// Deepest indentation before giving up on nucleation, m (default 8e-3).
    pub max_depth: f64,
    /// Nucleation stress σ* as a multiple of μ (default 2, seed 001).
    pub nucleation_stress_ratio: f64,
    /// Side ℓ of the square surface cell over which σ₁ is averaged for the
    /// nucleation criterion, in wire radii (default 0.25: the node spacing
    /// 100R/400 of seed 001's 3D slab, whose cells' σ₁ it compares with σ*).
    pub nucleation_cell_radii: f64,
    /// Newton tolerance on the out-of-balance force, relative to μR
    /// (dimensionless, default 1e-9).
    pub newton_tolerance: f64,
    /// Most Newton iterations per load step (default 40).
    pub max_newton_iterations: usize,
    /// Most solves per load step while the contact sets (contact, stick or
    /// slip, friction caps μ_f f_n) settle (default 8).
    pub contact_passes: usize,
}

impl Default for WireSlabSettings {
    fn default() -> Self {
        Self {
            shear_modulus: 35e3,
            bulk_modulus_ratio: 30.0,
            wire_radius: 150e-6,
            wire_length: 5e-3,
            slab_width: 40e-3,
            slab_depth: 40e-3,
            sides: SideSupport::Roller,
            indenter: Indenter::Wire,
            elements_per_radius: 6,
            column_refinement: 3,
            fine_zone_radii: 2.0,
            grading_ratio: 1.5,
            max_element_size: 4e-3,
            contact_penalty: 1e3,
            friction_coefficient: 1.0,
            depth_step: 20e-6,
            max_depth: 8e-3,
            nucleation_stress_ratio: 2.0,
            nucleation_cell_radii: 0.25,
            newton_tolerance: 1e-9,
            max_newton_iterations: 40,
            contact_passes: 8,
        }
    }
}

fn within(key: &str, value: f64, lo: f64, hi: f64) -> Result<(), InvalidSetting> {
    PhysicalRange::new(lo, hi, "").check(key, value)
}

/// The slab's shear modulus μ, Pa: a soft gel to a stiff vegetable.
const SHEAR_MODULUS: PhysicalRange = PhysicalRange::new(100.0, 1e8, "Pa");
/// The wire's length along its axis (the forces' out-of-plane length), m.
const WIRE_LENGTH: PhysicalRange = PhysicalRange::new(1e-4, 1.0, "m");

fn count_within(key: &str, value: usize, lo: usize, hi: usize) -> Result<(), InvalidSetting> {
    if (lo..=hi).contains(&value) {
        Ok(())
    } else {
        Err(InvalidSetting::new(
            key,
            value,
            format!("must be an integer in [{lo}, {hi}]"),
        ))
    }
}

impl WireSlabSettings {
    /// Checks every field; the error names the key, the value and the range.
    pub fn validate(&self) -> Result<(), InvalidSetting> {
        SHEAR_MODULUS.check("shear_modulus", self.shear_modulus)?;
        within("bulk_modulus_ratio", self.bulk_modulus_ratio, 1.0, 1e4)?;
        WIRE_RADIUS.check("wire_radius", self.wire_radius)?;
        WIRE_LENGTH.check("wire_length", self.wire_length)?;
        let r = self.wire_radius;
        within("slab_width", self.slab_width, 20.0 * r, 1e4 * r)?;
        within("slab_depth", self.slab_depth, 20.0 * r, 1e4 * r)?;
        count_within("elements_per_radius", self.elements_per_radius, 2, 64)?;
        count_within("column_refinement", self.column_refinement, 1, 8)?;
        within("fine_zone_radii", self.fine_zone_radii, 1.0, 9.0)?;
        within("grading_ratio", self.grading_ratio, 1.0, 2.0)?;
        within(
            "max_element_size",
            self.max_element_size,
            r / (self.elements_per_radius * self.column_refinement) as f64,
            self.slab_depth.max(self.slab_width),
        )?;
        within("contact_penalty", self.contact_penalty, 10.0, 1e7)?;
        if self.friction_coefficient.is_nan() || self.friction_coefficient <= 0.0 {
            return Err(InvalidSetting::new(
                "friction_coefficient",
                self.friction_coefficient,
                "must be > 0 (inf for no slip)",
            ));
        }
        within("depth_step", self.depth_step, 1e-3 * r, 10.0 * r)?;
        within(
            "max_depth",
            self.max_depth,
            self.depth_step,
            0.5 * self.slab_depth,
        )?;
        within(
            "nucleation_stress_ratio",
            self.nucleation_stress_ratio,
            1e-3,
            1e3,
        )?;
        within(
            "nucleation_cell_radii",
            self.nucleation_cell_radii,
            0.05,
            2.0,
        )?;
        within("newton_tolerance", self.newton_tolerance, 1e-14, 1e-3)?;
        count_within("max_newton_iterations", self.max_newton_iterations, 1, 1000)?;
        count_within("contact_passes", self.contact_passes, 1, 100)?;
        Ok(())
    }

    /// Side ℓ of the nucleation criterion's surface cell, m.
    pub fn nucleation_cell(&self) -> f64 {
        self.nucleation_cell_radii * self.wire_radius
    }

    /// Nucleation stress σ* = ratio · μ, Pa.
    pub fn nucleation_stress(&self) -> f64 {
        self.nucleation_stress_ratio * self.shear_modulus
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn defaults_are_valid_and_errors_name_key_value_and_range() {
        WireSlabSettings::default().validate().unwrap();
        let s = WireSlabSettings {
            grading_ratio: 3.0,
            ..Default::default()
        };
        let e = s.validate().unwrap_err();
        assert_eq!(e.key, "grading_ratio");
        assert_eq!(e.to_string(), "`grading_ratio` = 3: must be in [1, 2]");
        let inf = WireSlabSettings {
            friction_coefficient: f64::INFINITY,
            ..Default::default()
        };
        inf.validate().unwrap();
        let s: WireSlabSettings =
            toml::from_str("friction_coefficient = inf\nsides = \"free\"").unwrap();
        assert!(s.friction_coefficient.is_infinite());
        assert_eq!(s.sides, SideSupport::Free);
        assert!(toml::from_str::<WireSlabSettings>("radius = 1.0").is_err());
    }
}
