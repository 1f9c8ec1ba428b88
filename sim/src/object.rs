//! Objects on the cutting board.
//!
//! World frame (DESIGN §2): origin on the board, y up, the blade in the
//! yz-plane at x = 0, x normal to the blade. Objects sit on the board (y ≥ 0)
//! and are centred on the knife plane x = 0, so every cross section is
//! symmetric about the cut line.

use serde::{Deserialize, Serialize};

use crate::invalid_setting::{InvalidSetting, positive};

/// An object's shape and size, as written in config (`object = { kind = … }`).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(tag = "kind", rename_all = "kebab-case", deny_unknown_fields)]
pub enum ObjectShape {
    /// A cuboid piece (seed 000 §V.A–B), centred on x = 0, base on the board.
    Cuboid(Cuboid),
}

/// A cuboid piece.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Cuboid {
    /// Extent across the cut (world x), m.
    pub width: f64,
    /// Height above the board (world y), m.
    pub height: f64,
    /// Extent along the edge (world z), m.
    pub length: f64,
}

impl Cuboid {
    /// Checks every field.
    pub fn validate(&self) -> Result<(), InvalidSetting> {
        positive("width", self.width)?;
        positive("height", self.height)?;
        positive("length", self.length)
    }
}

impl ObjectShape {
    /// Checks the shape's fields; keys are relative to the object table.
    pub fn validate(&self) -> Result<(), InvalidSetting> {
        match self {
            ObjectShape::Cuboid(c) => c.validate(),
        }
    }

    /// Height of the object's highest point above the board, m.
    pub fn height(&self) -> f64 {
        match self {
            ObjectShape::Cuboid(c) => c.height,
        }
    }

    /// Extent of the object along z, m.
    pub fn length(&self) -> f64 {
        match self {
            ObjectShape::Cuboid(c) => c.length,
        }
    }
}
