//! Section forces summed into the wrench on the knife (seed 000 §IV, DESIGN §3.3).

use nalgebra::Vector3;

/// Force and torque the object exerts on the knife, N and N·m, expressed at a
/// reference point with axes parallel to the world frame.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct Wrench {
    /// Force, N.
    pub force: Vector3<f64>,
    /// Torque about the reference point, N·m.
    pub torque: Vector3<f64>,
}

impl Wrench {
    /// As `[fx, fy, fz, tx, ty, tz]`.
    pub fn to_array(&self) -> [f64; 6] {
        [
            self.force.x,
            self.force.y,
            self.force.z,
            self.torque.x,
            self.torque.y,
            self.torque.z,
        ]
    }
}

/// The load of one edge segment: its section's forces per unit length,
/// applied over the segment's length at its midpoint.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SegmentLoad {
    /// Midpoint of the segment in the world frame, m.
    pub midpoint: Vector3<f64>,
    /// Unit normal of the segment pointing into the material (the direction
    /// the edge presses in), world frame.
    pub normal: Vector3<f64>,
    /// Unit tangent of the segment, world frame.
    pub tangent: Vector3<f64>,
    /// Segment length, m.
    pub length: f64,
    /// Normal force per unit length, N/m, resisting the edge's motion along
    /// `normal` (positive pushes the knife back along −normal).
    pub force_normal: f64,
    /// Tangential force per unit length along `tangent`, N/m, acting on the
    /// knife (signed: negative resists a motion along +tangent).
    pub force_tangent: f64,
}

impl SegmentLoad {
    /// The force this segment's section exerts on the knife, N.
    pub fn force(&self) -> Vector3<f64> {
        (-self.normal * self.force_normal + self.tangent * self.force_tangent) * self.length
    }
}

/// Sums segment loads into the wrench at `reference` (e.g. the F/T sensor
/// origin, world frame): F = Σ fᵢ, τ = Σ (mᵢ − reference) × fᵢ.
pub fn wrench_at(reference: &Vector3<f64>, loads: &[SegmentLoad]) -> Wrench {
    let mut w = Wrench::default();
    for l in loads {
        let f = l.force();
        w.force += f;
        w.torque += (l.midpoint - reference).cross(&f);
    }
    w
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn straight_edge_pressing_gives_force_times_length() {
        // Ten segments of 3 mm along z at y = 0.01, pressing down (normal −y),
        // each with 100 N/m: total 3 N up on the knife.
        let loads: Vec<_> = (0..10)
            .map(|i| SegmentLoad {
                midpoint: Vector3::new(0.0, 0.01, 0.0215 + 0.003 * i as f64),
                normal: -Vector3::y(),
                tangent: Vector3::z(),
                length: 0.003,
                force_normal: 100.0,
                force_tangent: 0.0,
            })
            .collect();
        let sensor = Vector3::new(0.0, 0.04, -0.03);
        let w = wrench_at(&sensor, &loads);
        assert!((w.force - Vector3::new(0.0, 3.0, 0.0)).norm() < 1e-12);
        // τ_x = Σ (m − s)_y f_z − (m − s)_z f_y = −Σ (z_i + 0.03)·0.3.
        let expected: f64 = (0..10)
            .map(|i| -(0.0215 + 0.003 * i as f64 + 0.03) * 0.3)
            .sum();
        assert!((w.torque.x - expected).abs() < 1e-12);
        // Forces in the yz-plane at x = 0: no τ_y, τ_z.
        assert_eq!((w.torque.y, w.torque.z), (0.0, 0.0));
    }

    #[test]
    fn torque_is_independent_of_splitting_a_segment() {
        let one = SegmentLoad {
            midpoint: Vector3::new(0.0, 0.0, 0.1),
            normal: Vector3::new(0.0, -0.8, 0.6),
            tangent: Vector3::new(0.0, 0.6, 0.8),
            length: 0.02,
            force_normal: 50.0,
            force_tangent: -7.0,
        };
        let halves = [
            SegmentLoad {
                midpoint: one.midpoint - one.tangent * 0.005,
                length: 0.01,
                ..one
            },
            SegmentLoad {
                midpoint: one.midpoint + one.tangent * 0.005,
                length: 0.01,
                ..one
            },
        ];
        let s = Vector3::new(0.0, 0.05, 0.0);
        let a = wrench_at(&s, &[one]);
        let b = wrench_at(&s, &halves);
        assert!((a.force - b.force).norm() < 1e-14 && (a.torque - b.torque).norm() < 1e-15);
    }
}
