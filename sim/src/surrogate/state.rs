//! The state of a cut that the surrogate is evaluated at, and the online
//! scale factors of the material.

/// Where a cut is, for one cross section of the object under a piece of edge.
/// Lengths in m.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct CutState {
    /// Depth of the knife edge below the section's (undeformed) top surface
    /// at the cut, m: the knife's normal travel since the edge first touched.
    pub depth: f64,
    /// Height of the section at the cut (top surface above the board), m.
    pub height: f64,
    /// Half width of the section across the cut (normal to the blade), m.
    pub half_width: f64,
    /// Whether the first fracture has happened (the toughness is R_c, not R'_c).
    pub fractured: bool,
    /// Normal knife travel since the first fracture, m (ignored before it).
    pub travel_since_fracture: f64,
}

/// Multipliers of the material's nominal properties, for an online estimator
/// to adapt the surrogate without refitting (DESIGN §4). Default 1, 1, 1.
///
/// - `toughness` multiplies R_c and R'_c,
/// - `stiffness` multiplies E (ν is kept),
/// - `friction` multiplies μ.
///
/// How each enters each output is documented on
/// [`SurrogateOutput`](super::SurrogateOutput) and exposed as
/// [`ScaledParts`](super::ScaledParts).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ScaleFactors {
    /// Multiplier of R_c and R'_c, dimensionless (default 1).
    pub toughness: f64,
    /// Multiplier of E, dimensionless (default 1).
    pub stiffness: f64,
    /// Multiplier of μ, dimensionless (default 1).
    pub friction: f64,
}

impl Default for ScaleFactors {
    fn default() -> Self {
        Self {
            toughness: 1.0,
            stiffness: 1.0,
            friction: 1.0,
        }
    }
}
