//! Objects on the cutting board.
//!
//! World frame (DESIGN §2): origin on the board, y up, the blade in the
//! yz-plane at x = 0, x normal to the blade. Objects sit on the board (y ≥ 0)
//! and are centred on the knife plane x = 0, so every cross section is
//! symmetric about the cut line.

use serde::{Deserialize, Serialize};

use std::path::PathBuf;

use nalgebra::Vector3;

use crate::geometry::natural_shapes::{Tessellation, eggplant, half_potato};
use crate::geometry::{MeshError, TriangleMesh, read_mesh};
use crate::invalid_setting::InvalidSetting;
use crate::physical_range::OBJECT_SIZE;

mod table;

/// An object's shape and size, as written in config (`object = { kind = … }`).
///
/// Read through a TOML table (`object/table.rs`) so that an error names its
/// key.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(tag = "kind", rename_all = "kebab-case")]
#[serde(try_from = "toml::Table")]
pub enum ObjectShape {
    /// A cuboid piece (seed 000 §V.A–B), centred on x = 0, base on the board.
    Cuboid(Cuboid),
    /// A potato halved lengthwise and laid on its flat cut (seed 000 §V.C): half
    /// an ellipsoid.
    HalfPotato {
        /// Extent along the edge (world z), m, in [0.001, 1].
        length: f64,
        /// Extent across the cut (world x), m, in [0.001, 1].
        width: f64,
        /// Height above the board, m, in [0.001, 1].
        height: f64,
    },
    /// An eggplant lying across the knife (its axis along world x, the knife
    /// plane through its middle), slightly flattened where it rests on the board.
    Eggplant {
        /// Length along its axis (world x), m, in [0.001, 1].
        length: f64,
        /// Largest diameter, m, in [0.001, 1].
        diameter: f64,
        /// Depth of the flat on which it rests, m (default 0.004).
        #[serde(default = "default_eggplant_flat")]
        flat: f64,
    },
    /// A closed triangle mesh from an OBJ or STL file, in metres. It is placed
    /// centred on x = 0 (bounding box), resting on the board (min y = 0),
    /// starting at z = 0 (min z = 0).
    Mesh {
        /// Path of the .obj or .stl file.
        path: PathBuf,
    },
}

fn default_eggplant_flat() -> f64 {
    0.004
}

/// A cuboid piece.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Cuboid {
    /// Extent across the cut (world x), m, in [0.001, 1].
    pub width: f64,
    /// Height above the board (world y), m, in [0.001, 1].
    pub height: f64,
    /// Extent along the edge (world z), m, in [0.001, 1].
    pub length: f64,
}

impl Cuboid {
    /// Checks every field.
    pub fn validate(&self) -> Result<(), InvalidSetting> {
        OBJECT_SIZE.check("width", self.width)?;
        OBJECT_SIZE.check("height", self.height)?;
        OBJECT_SIZE.check("length", self.length)
    }
}

impl ObjectShape {
    /// Checks the shape's fields; keys are relative to the object table.
    pub fn validate(&self) -> Result<(), InvalidSetting> {
        match self {
            ObjectShape::Cuboid(c) => c.validate(),
            ObjectShape::HalfPotato {
                length,
                width,
                height,
            } => {
                OBJECT_SIZE.check("length", *length)?;
                OBJECT_SIZE.check("width", *width)?;
                OBJECT_SIZE.check("height", *height)
            }
            ObjectShape::Eggplant {
                length,
                diameter,
                flat,
            } => {
                OBJECT_SIZE.check("length", *length)?;
                OBJECT_SIZE.check("diameter", *diameter)?;
                if !(flat.is_finite() && *flat >= 0.0 && *flat < 0.25 * diameter) {
                    return Err(InvalidSetting::new(
                        "flat",
                        flat,
                        "must be in [0, diameter/4) m",
                    ));
                }
                Ok(())
            }
            ObjectShape::Mesh { path } => {
                if path.as_os_str().is_empty() {
                    return Err(InvalidSetting::new(
                        "path",
                        "\"\"",
                        "must name an .obj or .stl file",
                    ));
                }
                Ok(())
            }
        }
    }

    /// Extent [x, y, z] of the built-in shapes' bounding box, m (None for
    /// a mesh file, known only once it is read).
    pub fn nominal_extent(&self) -> Option<[f64; 3]> {
        match self {
            ObjectShape::Cuboid(c) => Some([c.width, c.height, c.length]),
            ObjectShape::HalfPotato {
                length,
                width,
                height,
            } => Some([*width, *height, *length]),
            ObjectShape::Eggplant {
                length,
                diameter,
                flat,
            } => Some([*length, diameter - flat, *diameter]),
            ObjectShape::Mesh { .. } => None,
        }
    }

    /// Height of the highest point above the board, m, for the built-in shapes
    /// (None for a mesh file, known only once it is read).
    pub fn nominal_height(&self) -> Option<f64> {
        match self {
            ObjectShape::Cuboid(c) => Some(c.height),
            ObjectShape::HalfPotato { height, .. } => Some(*height),
            ObjectShape::Eggplant { diameter, flat, .. } => Some(diameter - flat),
            ObjectShape::Mesh { .. } => None,
        }
    }

    /// The object's closed surface, placed centred on x = 0, on the board, from z = 0.
    pub fn mesh(&self) -> Result<TriangleMesh, MeshError> {
        let tess = Tessellation::default();
        let raw = match self {
            ObjectShape::Cuboid(c) => TriangleMesh::cuboid(
                Vector3::new(-0.5 * c.width, 0.0, 0.0),
                Vector3::new(0.5 * c.width, c.height, c.length),
            ),
            ObjectShape::HalfPotato {
                length,
                width,
                height,
            } => half_potato(*length, *width, *height, tess),
            ObjectShape::Eggplant {
                length,
                diameter,
                flat,
            } => eggplant(*length, *diameter, *flat, tess),
            ObjectShape::Mesh { path } => read_mesh(path)?,
        };
        let (lo, hi) = raw.bounds();
        let shift = Vector3::new(-0.5 * (lo.x + hi.x), -lo.y, -lo.z);
        TriangleMesh::new(
            raw.vertices().iter().map(|v| v + shift).collect(),
            raw.triangles().to_vec(),
        )
    }
}
