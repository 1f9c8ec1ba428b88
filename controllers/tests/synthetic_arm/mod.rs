//! A stand-in for the plant in controller tests: an arm that executes every
//! command its limit monitor accepts, and a material that pushes back like
//! a linear spring (F_y = k·depth), with the crack as deep as the knife.

// Each test binary uses a different part of this shared module.
#![allow(dead_code)]

use std::sync::Arc;

use nalgebra::{Vector2, Vector3};
use shearcut_controllers::controller::{CutTask, MotionLimits};
use shearcut_controllers::observer::EdgeOutline;
use shearcut_sim::arm::{ArmLimitMonitor, ArmLimits, ArmReading, ArmStatus, KnifeCommand};
use shearcut_sim::geometry::Polygon;
use shearcut_sim::{EdgeShape, Knife, KnifePreset, KnifeSettings};

/// Servo period, s.
pub const PERIOD: f64 = 1e-3;

/// A straight edge 30 mm long over a flat-topped block whose top is at
/// y = 0, from z = −2 m to 3 m: the whole edge is in contact at every depth
/// and wherever the knife slides (the profiles of these tests have 30 mm).
pub fn flat_outline() -> Arc<EdgeOutline> {
    let knife = Knife::new(&KnifeSettings {
        edge: EdgeShape::Straight { length: 0.03 },
        ..KnifePreset::Straight.settings()
    })
    .unwrap();
    let block = Polygon::new(vec![
        Vector2::new(-2.0, -2.0),
        Vector2::new(3.0, -2.0),
        Vector2::new(3.0, 0.0),
        Vector2::new(-2.0, 0.0),
    ]);
    Arc::new(EdgeOutline::new(knife.edge(), &block))
}

/// A task at 1 kHz within FR3 limits (90 % margin), over [`flat_outline`].
pub fn task(target_depth: f64, blade_budget: f64) -> CutTask {
    let arm = ArmLimits::default();
    CutTask {
        target_depth,
        outline: flat_outline(),
        overtravel: 0.0,
        period: PERIOD,
        blade_budget,
        limits: MotionLimits::within_arm(0.05, 0.1, arm.acceleration, arm.jerk, 0.9),
    }
}

/// The arm, its limit reflexes and a spring material.
pub struct SyntheticArm {
    /// Limit reflexes (FR3).
    pub monitor: ArmLimitMonitor,
    /// Knife position, m.
    pub position: Vector3<f64>,
    /// Executed velocity, m/s.
    pub velocity: Vector3<f64>,
    /// Spring stiffness, N/m of depth.
    pub stiffness: f64,
    /// Simulated time, s.
    pub time: f64,
    /// Commands refused.
    pub refused: usize,
    /// Depth at which the material first fractures, m (`None`: never):
    /// past it the force drops to half its peak and stays there, as a
    /// crack's steady cutting force below the indentation's peak.
    pub fracture_depth: Option<f64>,
}

impl SyntheticArm {
    /// At rest at the origin (the object's top at y = 0).
    pub fn new(stiffness: f64) -> Self {
        Self {
            monitor: ArmLimitMonitor::new(ArmLimits::default()),
            position: Vector3::zeros(),
            velocity: Vector3::zeros(),
            stiffness,
            time: 0.0,
            refused: 0,
            fracture_depth: None,
        }
    }

    /// The knife's depth below the object's top (y = 0), m: the crack is
    /// as deep as the knife.
    pub fn depth(&self) -> f64 {
        (-self.position.y).max(0.0)
    }

    /// The arm's reading now.
    pub fn measure(&self, status: ArmStatus) -> ArmReading {
        let depth = self.depth();
        let force = match self.fracture_depth {
            Some(d) if depth >= d => 0.5 * self.stiffness * d,
            _ => self.stiffness * depth,
        };
        ArmReading {
            time: self.time,
            position: self.position,
            velocity: self.velocity,
            wrench: [0.0, force, 0.0, 0.0, 0.0, 0.0],
            status,
        }
    }

    /// Executes one command (or refuses it) and measures.
    pub fn step(&mut self, command: &KnifeCommand) -> ArmReading {
        let status = match self.monitor.check(command.velocity, PERIOD) {
            Ok(()) => {
                self.velocity = command.velocity;
                ArmStatus::Moving
            }
            Err(why) => {
                self.refused += 1;
                self.monitor.reset();
                self.velocity = Vector3::zeros();
                ArmStatus::LimitViolation(why)
            }
        };
        self.position += self.velocity * PERIOD;
        self.time += PERIOD;
        self.measure(status)
    }
}

/// A convex stand-in for the surrogate: work per unit depth and length
/// w(ξ) = 150 − 120ξ + 45ξ² N/m (minimum at ξ = 4/3), force 140/(1+ξ) N/m.
#[derive(Debug, Clone, Copy)]
pub struct QuadraticModel;

impl shearcut_controllers::mpc::SliceModel for QuadraticModel {
    fn stage(
        &self,
        xi: f64,
        _state: &shearcut_controllers::mpc::StageState,
    ) -> shearcut_controllers::mpc::StageCost {
        shearcut_controllers::mpc::StageCost {
            work_per_depth: 150.0 - 120.0 * xi + 45.0 * xi * xi,
            work_per_depth_slope: -120.0 + 90.0 * xi,
            work_per_depth_curvature: 90.0,
            force_normal: 140.0 / (1.0 + xi),
            force_normal_slope: -140.0 / ((1.0 + xi) * (1.0 + xi)),
            deformation: 0.0,
            deformation_slope: 0.0,
            ..shearcut_controllers::mpc::StageCost::default()
        }
    }
}
