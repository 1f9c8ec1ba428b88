//! What every controller is told about the cut it must make.

use std::sync::Arc;

use nalgebra::Vector3;
use shearcut_sim::InvalidSetting;

use crate::observer::EdgeOutline;

/// Speed, acceleration and jerk limits a controller plans within, per axis
/// of the knife plane (normal and tangential).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct MotionLimits {
    /// Largest normal speed (down into the object), m/s.
    pub normal_speed: f64,
    /// Largest tangential speed along the edge, m/s.
    pub tangential_speed: f64,
    /// Largest acceleration per axis, m/s².
    pub acceleration: f64,
    /// Largest jerk per axis, m/s³.
    pub jerk: f64,
}

impl MotionLimits {
    /// Per-axis limits that keep the twist's norm within an arm's Cartesian
    /// `acceleration` and `jerk` limits (their finite-difference checks act
    /// on the vector norm: two axes each at `x/√2` stay below `x`), with a
    /// safety `margin` in (0, 1] against the finite-difference rounding, and
    /// the given speed caps.
    pub fn within_arm(
        normal_speed: f64,
        tangential_speed: f64,
        acceleration: f64,
        jerk: f64,
        margin: f64,
    ) -> Self {
        let per_axis = margin / std::f64::consts::SQRT_2;
        Self {
            normal_speed,
            tangential_speed,
            acceleration: acceleration * per_axis,
            jerk: jerk * per_axis,
        }
    }

    /// The normal speed of a knife moving at `speed` (m/s, along its
    /// velocity) with slice-push ratio `xi`: s/√(1+ξ²), lowered so that
    /// neither the normal nor the tangential (ξ·v_n) speed limit is exceeded.
    pub fn normal_speed_for(&self, speed: f64, xi: f64) -> f64 {
        let v_n = (speed / (1.0 + xi * xi).sqrt()).min(self.normal_speed);
        if xi * v_n > self.tangential_speed {
            self.tangential_speed / xi
        } else {
            v_n
        }
    }

    /// Checks every limit is finite and positive.
    pub fn validate(&self) -> Result<(), InvalidSetting> {
        for (key, value) in [
            ("normal_speed", self.normal_speed),
            ("tangential_speed", self.tangential_speed),
            ("acceleration", self.acceleration),
            ("jerk", self.jerk),
        ] {
            if !(value.is_finite() && value > 0.0) {
                return Err(InvalidSetting::new(key, value, "a finite number > 0"));
            }
        }
        Ok(())
    }
}

/// The cut a controller must make, and what a lab knows before it starts.
///
/// A controller is told nothing else about the world than this and what
/// the arm reports each tick ([`ArmReading`](shearcut_sim::arm::ArmReading)).
///
/// The cut's depth is geometric: the knife's edge against the object's
/// outline in the knife plane ([`EdgeOutline`]), at the pose the arm
/// reports. The edge's depth ([`edge_depth`](Self::edge_depth)) is its
/// deepest penetration below the outline's top; pressing, it is the knife's
/// travel since the edge touched, and when the knife slides along a curved
/// edge it follows the part of the edge that comes over the object. On a
/// real cell the edge comes from the knife's drawing or a scan, and the
/// outline from vision (a silhouette in the knife's plane) or a measured
/// template, placed in the arm's frame and its height set by a touch-off
/// (jog the knife down until the F/T sensor reads a few newtons:
/// [`EdgeOutline::touch_height`] there is the knife's height). The MPC's
/// [`DepthProfile`](crate::mpc::DepthProfile) is read at this depth.
#[derive(Debug, Clone, PartialEq)]
pub struct CutTask {
    /// Depth of the cut below the object's top at which it is complete, m,
    /// measured as the edge's depth ([`edge_depth`](Self::edge_depth): its
    /// deepest penetration below the outline's top).
    pub target_depth: f64,
    /// Edge travel past the target depth before the cut is done, m. The
    /// crack front can lag the edge (the material compressed under it), and
    /// a controller, which cannot see the crack, lets the edge go this much
    /// deeper so that the crack reaches the target.
    pub overtravel: f64,
    /// The knife's edge against the object's outline in the knife plane
    /// (world z, y; the board is y = 0), shared by the controllers made for
    /// the task.
    pub outline: Arc<EdgeOutline>,
    /// Servo period, s (1 ms for a 1 kHz arm).
    pub period: f64,
    /// Tangential blade travel available, m: how far the knife may move
    /// along its edge before the contact arc would leave the blade.
    pub blade_budget: f64,
    /// Motion limits.
    pub limits: MotionLimits,
}

impl CutTask {
    /// The edge's clearance above the object's outline with the knife frame
    /// origin at `position` (world, m): negative once inside, +∞ when no
    /// edge point is over the outline ([`EdgeOutline::clearance`]).
    pub fn clearance(&self, position: &Vector3<f64>) -> f64 {
        self.outline.clearance(position.z, position.y)
    }

    /// The edge's depth in the object with the knife frame origin at
    /// `position` (world, m): its deepest penetration below the outline's
    /// top, 0 above it ([`EdgeOutline::depth`]).
    pub fn edge_depth(&self, position: &Vector3<f64>) -> f64 {
        self.outline.depth(position.z, position.y)
    }

    /// Length of edge inside the object with the knife frame origin at
    /// `position` (world, m; [`EdgeOutline::contact_length`]).
    pub fn contact_length(&self, position: &Vector3<f64>) -> f64 {
        self.outline.contact_length(position.z, position.y)
    }

    /// Whether the edge, `edge_depth` deep (m, [`edge_depth`](Self::edge_depth)),
    /// has reached the target depth plus the overtravel: the cut is done.
    pub fn reached(&self, edge_depth: f64) -> bool {
        edge_depth >= self.target_depth + self.overtravel
    }

    /// Checks the task, naming the offending key.
    pub fn validate(&self) -> Result<(), InvalidSetting> {
        if !(self.target_depth.is_finite() && self.target_depth > 0.0) {
            return Err(InvalidSetting::new(
                "target_depth",
                self.target_depth,
                "a finite depth > 0 m",
            ));
        }
        if !(self.overtravel.is_finite() && self.overtravel >= 0.0) {
            return Err(InvalidSetting::new(
                "overtravel",
                self.overtravel,
                "a finite length >= 0 m",
            ));
        }
        if !(self.period.is_finite() && self.period > 0.0) {
            return Err(InvalidSetting::new(
                "period",
                self.period,
                "a finite period > 0 s",
            ));
        }
        if !(self.blade_budget.is_finite() && self.blade_budget >= 0.0) {
            return Err(InvalidSetting::new(
                "blade_budget",
                self.blade_budget,
                "a finite length >= 0 m",
            ));
        }
        self.limits.validate().map_err(|e| e.prefixed("limits"))
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use nalgebra::Vector2;
    use shearcut_sim::geometry::Polygon;
    use shearcut_sim::{Knife, KnifePreset};

    /// The straight edge over a block 50 mm high, z from −1 to 1 m.
    fn task(overtravel: f64) -> CutTask {
        let knife = Knife::new(&KnifePreset::Straight.settings()).unwrap();
        let block = Polygon::new(vec![
            Vector2::new(-1.0, 0.0),
            Vector2::new(1.0, 0.0),
            Vector2::new(1.0, 0.05),
            Vector2::new(-1.0, 0.05),
        ]);
        CutTask {
            target_depth: 0.02,
            overtravel,
            outline: Arc::new(EdgeOutline::new(knife.edge(), &block)),
            period: 1e-3,
            blade_budget: 0.01,
            limits: MotionLimits::within_arm(0.05, 0.1, 5.0, 500.0, 0.9),
        }
    }

    /// The cut is done only once the edge is the overtravel past the target.
    #[test]
    fn done_after_the_overtravel() {
        let t = task(0.002);
        let at = |y: f64| t.edge_depth(&Vector3::new(0.0, y, 0.0));
        assert_eq!(at(0.06), 0.0);
        assert!((at(0.03) - 0.02).abs() < 1e-15);
        assert!(!t.reached(at(0.0301)));
        assert!(!t.reached(at(0.0285)));
        assert!(t.reached(at(0.0279)));
        assert!(task(0.0).reached(at(0.0299)));
    }

    #[test]
    fn negative_overtravel_is_named() {
        let e = task(-1e-3).validate().unwrap_err().to_string();
        assert!(e.contains("overtravel"), "{e}");
    }
}
