//! Replicas of a closed-loop run on objects whose heights differ by a
//! fraction of a nanometre: how far the plant's discrete crack events move
//! a result.
//!
//! The plant's cracks advance row by row of the sections' meshes (every
//! 0.2 mm) in jumps, so where a cut stops within a jump, and whether a
//! section fractures on one tick or the next, can flip under any change at
//! rounding level. A constant-ratio run on the potato cuboid does 0.1536 J
//! or 0.1610 J (+4.8 %) with the object 1 nm taller or shorter. Comparing
//! controllers by one run each, and picking the best constant ratio as the
//! smallest of a dozen such runs, favours whichever run happened to fall on
//! the cheap side. A replica scales the object's heights by 1 + k·10⁻⁷
//! (2.5 nm on 25 mm: far below any real tolerance, far above rounding), so
//! the mean over replicas estimates the work a controller does on "this
//! object", and the spread shows the plant's scatter.

use nalgebra::Vector3;
use shearcut_sim::geometry::TriangleMesh;

/// Relative change of the object's heights per replica step.
pub const HEIGHT_STEP: f64 = 1e-7;

/// One replica: the object's heights scaled by 1 + `offset`·[`HEIGHT_STEP`]
/// (offset 0 is the object as given).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct ObjectReplica {
    /// Steps of [`HEIGHT_STEP`], positive taller.
    pub offset: i32,
}

impl ObjectReplica {
    /// The object as given.
    pub const NOMINAL: Self = Self { offset: 0 };

    /// The `index`-th of a set of replicas, alternating around the
    /// nominal object: 0, +1, −1, +2, −2, …
    pub fn nth(index: usize) -> Self {
        let step = index.div_ceil(2) as i32;
        Self {
            offset: if index % 2 == 1 { step } else { -step },
        }
    }

    /// The factor on the object's heights.
    pub fn height_scale(&self) -> f64 {
        1.0 + self.offset as f64 * HEIGHT_STEP
    }

    /// `mesh` with every vertex's height above the board (world y) scaled:
    /// the object still stands on the board. The nominal replica is `mesh`
    /// itself, bit for bit.
    pub fn mesh(&self, mesh: &TriangleMesh) -> TriangleMesh {
        if self.offset == 0 {
            return mesh.clone();
        }
        let f = self.height_scale();
        let vertices = mesh
            .vertices()
            .iter()
            .map(|v| Vector3::new(v.x, v.y * f, v.z))
            .collect();
        TriangleMesh::new(vertices, mesh.triangles().to_vec())
            .expect("scaling heights by a factor near 1 keeps a closed mesh closed")
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn replicas_alternate_around_the_nominal_object() {
        let offsets: Vec<i32> = (0..5).map(|i| ObjectReplica::nth(i).offset).collect();
        assert_eq!(offsets, [0, 1, -1, 2, -2]);
        assert_eq!(ObjectReplica::nth(0), ObjectReplica::NOMINAL);
    }

    #[test]
    fn a_replica_scales_heights_above_the_board_only() {
        let mesh = TriangleMesh::cuboid(
            Vector3::new(-0.015, 0.0, 0.02),
            Vector3::new(0.015, 0.025, 0.05),
        );
        let (lo, hi) = ObjectReplica { offset: -3 }.mesh(&mesh).bounds();
        assert_eq!(lo, Vector3::new(-0.015, 0.0, 0.02));
        assert_eq!((hi.x, hi.z), (0.015, 0.05));
        assert!((hi.y - 0.025 * (1.0 - 3e-7)).abs() < 1e-18, "{}", hi.y);
        let same = ObjectReplica::NOMINAL.mesh(&mesh);
        assert_eq!(same.vertices(), mesh.vertices());
    }
}
