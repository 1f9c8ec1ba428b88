//! The blade's cross section normal to its edge: a wedge with a blunt edge.

use serde::{Deserialize, Serialize};

use crate::invalid_setting::InvalidSetting;
use crate::physical_range::{BEVEL_ANGLE, BLADE_THICKNESS, EDGE_WIDTH};

/// Cross section of the blade in a plane normal to the edge (DESIGN §3.2).
///
/// The edge is a flat of width `edge_width` (the contact strip that loads the
/// material, seed 000 eq. 2); above it each face rises at `bevel_angle` from the
/// blade's mid-plane until the blade reaches its full `thickness`. So the blade's
/// half-thickness at height `h` above the edge is
/// `min(edge_width/2 + h·tan(bevel_angle), thickness/2)`.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct BladeSection {
    /// Full thickness of the blade above the bevel, m (default 0.002).
    pub thickness: f64,
    /// Angle of each bevel face to the blade's mid-plane, rad (default 0.2618 = 15°).
    pub bevel_angle: f64,
    /// Width of the edge flat that contacts the material, m (default 1e-4). A
    /// mathematical point edge has no finite stiffness in 2D (DESIGN §3.2).
    pub edge_width: f64,
}

impl Default for BladeSection {
    fn default() -> Self {
        Self {
            thickness: 0.002,
            bevel_angle: 15f64.to_radians(),
            edge_width: 1.0e-4,
        }
    }
}

impl BladeSection {
    /// Half-thickness of the blade at `height` above the edge, m (0 below the edge).
    pub fn half_thickness_at(&self, height: f64) -> f64 {
        if height < 0.0 {
            return 0.0;
        }
        (0.5 * self.edge_width + height * self.bevel_angle.tan()).min(0.5 * self.thickness)
    }

    /// Height above the edge at which the bevel ends and the blade is full thickness, m.
    pub fn bevel_height(&self) -> f64 {
        (0.5 * (self.thickness - self.edge_width)).max(0.0) / self.bevel_angle.tan()
    }

    /// Checks every field against its physical range; the edge flat is at
    /// most the blade's thickness. The error names the key.
    pub fn validate(&self) -> Result<(), InvalidSetting> {
        BLADE_THICKNESS.check("thickness", self.thickness)?;
        EDGE_WIDTH
            .at_most(self.thickness)
            .check("edge_width", self.edge_width)?;
        BEVEL_ANGLE.check("bevel_angle", self.bevel_angle)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn wedge_opens_at_the_bevel_and_saturates() {
        let b = BladeSection::default();
        assert_eq!(b.half_thickness_at(-1.0), 0.0);
        assert!((b.half_thickness_at(0.0) - 0.5e-4).abs() < 1e-15);
        let h = b.bevel_height();
        assert!((b.half_thickness_at(h) - 1e-3).abs() < 1e-12);
        assert_eq!(b.half_thickness_at(10.0 * h), 1e-3);
    }
}
