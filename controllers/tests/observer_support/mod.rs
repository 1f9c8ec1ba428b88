//! Drives the full plant open loop for the observer tests: a jerk-limited
//! ramp to a constant knife velocity (pressing or slicing), as the
//! baselines move, on coarse sections so that a test takes seconds.
#![allow(dead_code)] // Each test binary uses a part.

use nalgebra::Vector3;
use shearcut_controllers::controller::{MotionLimits, VelocityShaper};
use shearcut_controllers::observer::{CutObserver, CutObserverSettings, CutTarget};
use shearcut_plant::{FtSensorSettings, Plant, PlantSettings, PlantSpec, PlantStep as Measurement};
use shearcut_sim::arm::ArmLimits;
use shearcut_sim::geometry::{Polygon, TriangleMesh};
use shearcut_sim::knife_plane::knife_plane_silhouette;
use shearcut_sim::section::SectionSettings;
use shearcut_sim::{Cuboid, Knife, KnifePreset, MaterialPreset, ObjectShape};

/// Servo period, s.
pub const PERIOD: f64 = 1e-3;

/// A cut to drive: material, knife, object, where the piece sits on the
/// edge (z₀, m) and the sensor.
pub struct Cut {
    pub material: MaterialPreset,
    pub knife: Knife,
    pub mesh: TriangleMesh,
    pub z0: f64,
    pub segments: usize,
    pub sensor: FtSensorSettings,
}

impl Cut {
    /// The potato cuboid of `loop-potato-cuboid` (30 × 25 × 30 mm) under
    /// the straight edge.
    pub fn potato_cuboid(sensor: FtSensorSettings) -> Self {
        Self {
            material: MaterialPreset::PotatoCuboid,
            knife: Knife::new(&KnifePreset::Straight.settings()).unwrap(),
            mesh: ObjectShape::Cuboid(Cuboid {
                width: 0.03,
                height: 0.025,
                length: 0.03,
            })
            .mesh()
            .unwrap(),
            z0: 0.02,
            segments: 3,
            sensor,
        }
    }

    /// The half potato of `loop-potato-whole` (90 × 60 × 35 mm) under the
    /// chef's knife, 20 segments.
    pub fn half_potato(sensor: FtSensorSettings) -> Self {
        Self {
            material: MaterialPreset::PotatoWhole,
            knife: Knife::new(&KnifePreset::Chef.settings()).unwrap(),
            mesh: ObjectShape::HalfPotato {
                length: 0.09,
                width: 0.06,
                height: 0.035,
            }
            .mesh()
            .unwrap(),
            z0: 0.02,
            segments: 20,
            sensor,
        }
    }

    /// The object's outline in the knife plane, as the task gives it.
    pub fn outline(&self) -> Polygon {
        knife_plane_silhouette(&self.mesh).unwrap()
    }

    /// Observers with default settings for `target`.
    pub fn observer(&self, target: CutTarget) -> CutObserver {
        CutObserver::new(
            &self.knife,
            &self.outline(),
            target,
            &CutObserverSettings::default(),
        )
        .unwrap()
    }

    /// `ticks` measurements of the knife moving at slice-push ratio `xi`
    /// and `speed` (m/s, along the velocity) from rest, starting 1 mm above
    /// the object, on sections coarser than the default (rows every 0.5 mm).
    pub fn drive(&self, xi: f64, speed: f64, ticks: usize) -> Vec<Measurement> {
        let arm = ArmLimits::default();
        let limits = MotionLimits::within_arm(0.05, 0.1, arm.acceleration, arm.jerk, 0.9);
        let settings = PlantSettings {
            segments: self.segments,
            reach: 0.02,
            sensor: self.sensor,
            ..PlantSettings::default()
        };
        let section = SectionSettings {
            row_spacing: 5e-4,
            ..SectionSettings::default()
        };
        let mut plant = Plant::new(
            PlantSpec {
                material: &self.material.material(),
                knife: &self.knife,
                object: &self.mesh,
                z0: self.z0,
                direction: Plant::direction_at(xi),
                settings: &settings,
                section: &section,
                arm_limits: &arm,
            },
            0,
        )
        .unwrap();
        let mut shaper = VelocityShaper::new(PERIOD, &limits).unwrap();
        let v_n = limits.normal_speed_for(speed, xi);
        let mut m = plant.step(&Default::default(), PERIOD).unwrap();
        let mut out = Vec::with_capacity(ticks);
        for _ in 0..ticks {
            out.push(m);
            m = plant.step(&shaper.command(v_n, xi * v_n), PERIOD).unwrap();
        }
        out
    }
}

/// Index of the first measurement where `f` holds.
pub fn first(ms: &[Measurement], f: impl Fn(&Measurement) -> bool) -> Option<usize> {
    ms.iter().position(f)
}

/// The knife's downward travel per tick at the cruise of `ms` (the last
/// measurement's normal speed), m.
pub fn travel_per_tick(ms: &[Measurement]) -> f64 {
    -ms.last().unwrap().reading.velocity.y * PERIOD
}

/// The noise-free sensor.
pub fn quiet() -> FtSensorSettings {
    FtSensorSettings {
        force_noise: 0.0,
        torque_noise: 0.0,
        ..FtSensorSettings::default()
    }
}

/// The default noise (0.01 N, 0.5 mN·m) and the bias `fy` (N) on fy, the
/// opposite on fx and fz.
pub fn noisy(fy: f64) -> FtSensorSettings {
    FtSensorSettings {
        bias: [-fy, fy, -fy, 0.0, 0.0, 0.0],
        ..FtSensorSettings::default()
    }
}

/// The knife frame origin of a measurement.
pub fn position(m: &Measurement) -> Vector3<f64> {
    m.reading.position
}
