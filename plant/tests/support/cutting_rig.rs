//! The plant tests' shared set-up: arm limits loose enough for commanded
//! velocity steps, a noise-free F/T sensor, a coarse section mesh, and the
//! objects the tests cut (included with `#[path]`).
#![allow(dead_code)] // Each test binary uses the parts it needs.

use nalgebra::Vector3;
use shearcut_plant::{ArmLimits, FtSensorSettings, PlantSettings};
use shearcut_sim::geometry::TriangleMesh;
use shearcut_sim::{ObjectShape, SectionSettings};

/// Arm limits that let a test command velocity steps (1 m/s, 10⁹ m/s²,
/// 10¹⁵ m/s³); the limit tests use the real limits.
pub const LOOSE: ArmLimits = ArmLimits {
    velocity: 1.0,
    acceleration: 1e9,
    jerk: 1e15,
};

/// The default plant with `segments` segments and a noise-free sensor, for
/// exact comparisons.
pub fn noise_free(segments: usize) -> PlantSettings {
    PlantSettings {
        segments,
        sensor: FtSensorSettings {
            force_noise: 0.0,
            torque_noise: 0.0,
            ..Default::default()
        },
        ..PlantSettings::default()
    }
}

/// The default section with rows every 0.5 mm instead of 0.2 mm: keeps the
/// tests fast; each compares models built with the same settings.
pub fn coarse_section() -> SectionSettings {
    SectionSettings {
        row_spacing: 5e-4,
        ..SectionSettings::default()
    }
}

/// A cuboid `width` (x, centred on the cut) × `height` (y, on the board) ×
/// `length` (z, from 0), m.
pub fn cuboid(width: f64, height: f64, length: f64) -> TriangleMesh {
    TriangleMesh::cuboid(
        Vector3::new(-0.5 * width, 0.0, 0.0),
        Vector3::new(0.5 * width, height, length),
    )
}

/// The half potato (80 × 50 × 30 mm) the chef's-knife tests cut.
pub fn half_potato() -> TriangleMesh {
    ObjectShape::HalfPotato {
        length: 0.08,
        width: 0.05,
        height: 0.03,
    }
    .mesh()
    .unwrap()
}
