//! The whole-knife, whole-object plant, stepped like a robot arm's servo loop.

use nalgebra::{Vector2, Vector3};
use serde::{Deserialize, Serialize};

use crate::geometry::{SectionPlane, TriangleMesh};
use crate::invalid_setting::InvalidSetting;
use crate::knife::Knife;
use crate::material::Material;
use crate::section::{CrossSection, SectionError, SectionSettings};

use super::arm_limits::{ArmLimitMonitor, ArmLimits, LimitViolation};
use super::contact_arc::{EdgeSegment, contact_arc, knife_plane_silhouette, ray_hit, segments};
use super::ft_sensor::{FtSensor, FtSensorSettings};
use super::section_shape::section_geometry;
use super::wrench::{SegmentLoad, Wrench, wrench_at};

/// Settings of the plant.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct PlantSettings {
    /// Number m of edge segments (and cross sections) on the contact arc (default 10).
    pub segments: usize,
    /// Gap between the edge and the object when the plant starts, m (default 0.001).
    pub start_gap: f64,
    /// Rim height below which a dome-shaped section is clipped, as a fraction
    /// of the section's height (default 0.05).
    pub rim_fraction: f64,
    /// The F/T sensor.
    pub sensor: FtSensorSettings,
}

impl Default for PlantSettings {
    fn default() -> Self {
        Self {
            segments: 10,
            start_gap: 1e-3,
            rim_fraction: 0.05,
            sensor: FtSensorSettings::default(),
        }
    }
}

impl PlantSettings {
    /// Checks every field.
    pub fn validate(&self) -> Result<(), InvalidSetting> {
        if !(1..=64).contains(&self.segments) {
            return Err(InvalidSetting::new(
                "segments",
                self.segments,
                "must be in [1, 64]",
            ));
        }
        if !(self.start_gap.is_finite() && self.start_gap >= 0.0) {
            return Err(InvalidSetting::new(
                "start_gap",
                self.start_gap,
                "must be a finite number >= 0 m",
            ));
        }
        if !(self.rim_fraction > 0.0 && self.rim_fraction < 0.5) {
            return Err(InvalidSetting::new(
                "rim_fraction",
                self.rim_fraction,
                "must be in (0, 0.5)",
            ));
        }
        self.sensor.validate().map_err(|e| e.prefixed("sensor"))
    }
}

/// Why a plant cannot be built.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum PlantError {
    /// A setting is out of range.
    #[error(transparent)]
    Setting(#[from] InvalidSetting),
    /// The knife's planned path never meets the object.
    #[error(
        "the knife moving along the planned direction never touches the object (check z0 and the knife's length)"
    )]
    NoContact,
    /// A cross section could not be built.
    #[error("cross section {index}: {source}")]
    Section {
        /// Index of the segment.
        index: usize,
        /// Why.
        source: SectionError,
    },
}

/// A knife motion command: a Cartesian twist (translation only).
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct KnifeCommand {
    /// Knife velocity in the world frame, m/s (the x component must be 0:
    /// the knife moves in its own plane).
    pub velocity: Vector3<f64>,
}

/// What the plant reports after a tick.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum PlantStatus {
    /// The command was executed.
    Moving,
    /// The command broke an arm limit and was refused: the knife holds still.
    LimitViolation(LimitViolation),
}

/// The measurement after a tick: what an arm and an F/T sensor report, plus
/// the model's cut state.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Measurement {
    /// Simulated time, s.
    pub time: f64,
    /// Knife frame origin (heel end of the edge) in the world frame, m.
    pub position: Vector3<f64>,
    /// Knife velocity actually executed, m/s.
    pub velocity: Vector3<f64>,
    /// F/T sensor reading [fx, fy, fz, tx, ty, tz] at the sensor, N and N·m
    /// (object on knife; with noise and bias).
    pub wrench: [f64; 6],
    /// The noise-free wrench at the sensor.
    pub true_wrench: Wrench,
    /// Mean crack depth over the sections in the object, m.
    pub crack_depth: f64,
    /// Length of edge in contact with material, m.
    pub contact_length: f64,
    /// Number of sections that have fractured.
    pub fractured_sections: usize,
    /// Cumulative knife work on the object, J.
    pub work: f64,
    /// Largest surface deformation next to the blade over the sections, m.
    pub deformation: f64,
    /// Outcome of the tick.
    pub status: PlantStatus,
}

/// One segment's section and its bookkeeping.
#[derive(Debug, Clone)]
struct SegmentSection {
    segment: EdgeSegment,
    section: CrossSection,
    /// Normal distance the edge still has to travel to reach the section's top, m.
    gap: f64,
    /// Normal distance the edge has been pulled back out, m.
    lift: f64,
    /// Sign of the last tangential motion (+1 towards the tip).
    tangential_sign: f64,
}

/// The plant: a knife (any edge) cutting an object (any closed mesh) through m
/// moving cross sections, with an arm's limit reflexes and an F/T sensor.
///
/// Segments and sections are chosen at construction from the knife's planned
/// direction of motion (assumption A2): each segment's section is normal to
/// it through the first contact of its midpoint's path with the object
/// (seed 000 §IV). Sections are not re-chosen as the knife moves yet: for a
/// knife that translates, each segment keeps its orientation, so this is exact
/// for uniform objects (cuboids) and an approximation where the object's
/// section changes along the path of a slicing segment.
///
/// # Memory allocation
/// [`Plant::new`] allocates everything; [`Plant::step`] allocates nothing.
#[derive(Debug, Clone)]
pub struct Plant {
    sections: Vec<SegmentSection>,
    loads: Vec<SegmentLoad>,
    monitor: ArmLimitMonitor,
    sensor: FtSensor,
    sensor_offset: Vector3<f64>,
    position: Vector3<f64>,
    time: f64,
    work: f64,
}

impl Plant {
    /// Builds the plant.
    ///
    /// `object` is placed with its near face (min z) at `object_z`; the knife's
    /// origin starts at z = `object_z − z0` (so the piece is z₀ from the heel
    /// along z, seed 000 Fig. 6(b)), with its edge `start_gap` above the
    /// object along the planned `direction` of motion (knife plane (z, y),
    /// pointing down into the object). `section` configures every cross
    /// section; `arm_limits` are the reflexes checked on every command.
    #[allow(clippy::too_many_arguments)]
    pub fn new(
        material: &Material,
        knife: &Knife,
        object: &TriangleMesh,
        z0: f64,
        direction: Vector2<f64>,
        settings: &PlantSettings,
        section: &SectionSettings,
        arm_limits: &ArmLimits,
        seed: u64,
    ) -> Result<Self, PlantError> {
        settings.validate()?;
        section.validate().map_err(|e| e.prefixed("section"))?;
        arm_limits
            .validate()
            .map_err(|e| e.prefixed("arm_limits"))?;
        material.validate().map_err(|e| e.prefixed("material"))?;
        let d = direction
            .try_normalize(0.0)
            .filter(|d| d.y < 0.0)
            .ok_or_else(|| {
                InvalidSetting::new(
                    "direction",
                    format!("{direction:?}"),
                    "must point downwards (y < 0)",
                )
            })?;
        let silhouette = knife_plane_silhouette(object).ok_or(PlantError::NoContact)?;
        let (lo, hi) = object.bounds();
        // Knife origin: z from z₀, y so that the lowest point of the edge over
        // the object is start_gap above its top.
        let origin_z = lo.z - z0;
        let edge = knife.edge();
        let mut lowest_over = f64::INFINITY;
        for k in 0..=2000 {
            let p = edge.point_at(edge.length() * k as f64 / 2000.0);
            if p.x + origin_z >= lo.z && p.x + origin_z <= hi.z {
                lowest_over = lowest_over.min(p.y);
            }
        }
        if !lowest_over.is_finite() {
            lowest_over = edge.lowest_point().1.y;
        }
        let origin = Vector2::new(origin_z, hi.y + settings.start_gap - lowest_over);
        let arc = contact_arc(edge, origin, d, &silhouette).ok_or(PlantError::NoContact)?;
        let mut sections = Vec::with_capacity(settings.segments);
        for (index, segment) in segments(edge, arc, settings.segments)
            .into_iter()
            .enumerate()
        {
            let start = origin + segment.midpoint;
            let Some(lambda) = ray_hit(&silhouette, start, d) else {
                // The midpoint's path misses (a gap in the silhouette): no section.
                continue;
            };
            let q = start + d * lambda;
            let up = -Vector3::new(0.0, segment.normal.y, segment.normal.x);
            let plane = SectionPlane::normal_to_segment(Vector3::new(0.0, q.y, q.x), up);
            let Some(polygon) = plane.section(object) else {
                continue;
            };
            let height = polygon.bounds().1.y;
            let geometry = section_geometry(&polygon, settings.rim_fraction * height)
                .map_err(|source| PlantError::Section { index, source })?;
            let section = CrossSection::new(&geometry, material, knife.blade(), section)
                .map_err(|source| PlantError::Section { index, source })?;
            sections.push(SegmentSection {
                segment,
                section,
                gap: lambda * d.dot(&segment.normal),
                lift: 0.0,
                tangential_sign: 0.0,
            });
        }
        if sections.is_empty() {
            return Err(PlantError::NoContact);
        }
        let loads = Vec::with_capacity(sections.len());
        Ok(Self {
            loads,
            sections,
            monitor: ArmLimitMonitor::new(*arm_limits),
            sensor: FtSensor::new(settings.sensor, seed).map_err(|e| e.prefixed("sensor"))?,
            sensor_offset: knife.sensor_position(),
            position: Vector3::new(0.0, origin.y, origin.x),
            time: 0.0,
            work: 0.0,
        })
    }

    /// Knife frame origin in the world frame, m.
    pub fn position(&self) -> Vector3<f64> {
        self.position
    }

    /// The segments that own a section, heel to tip.
    pub fn segments(&self) -> impl Iterator<Item = &EdgeSegment> {
        self.sections.iter().map(|s| &s.segment)
    }

    /// The sections' current states, heel to tip.
    pub fn section_states(&self) -> impl Iterator<Item = &crate::section::SectionStep> {
        self.sections.iter().map(|s| s.section.state())
    }

    /// Executes `command` for `dt` seconds and returns the measurement.
    /// A command that breaks an arm limit is refused: the knife holds still
    /// and the status says why. Allocates nothing.
    pub fn step(&mut self, command: &KnifeCommand, dt: f64) -> Result<Measurement, SectionError> {
        let mut v = command.velocity;
        let status = match self.monitor.check(v, dt) {
            Ok(()) => PlantStatus::Moving,
            Err(violation) => {
                v = Vector3::zeros();
                self.monitor.reset();
                PlantStatus::LimitViolation(violation)
            }
        };
        let dt = if dt.is_finite() && dt > 0.0 { dt } else { 0.0 };
        let dp = v * dt;
        self.position += Vector3::new(0.0, dp.y, dp.z);
        self.time += dt;
        let dp2 = Vector2::new(dp.z, dp.y);
        self.loads.clear();
        let mut contact_length = 0.0;
        let mut fractured = 0;
        let mut depth_sum = 0.0;
        let mut deformation: f64 = 0.0;
        let mut work = 0.0;
        for s in &mut self.sections {
            let dn = dp2.dot(&s.segment.normal);
            let dt_seg = dp2.dot(&s.segment.tangent);
            if dt_seg != 0.0 {
                s.tangential_sign = dt_seg.signum();
            }
            // Normal travel eats first the gap to the surface, then any lift.
            let mut advance = 0.0;
            if dn > 0.0 {
                let mut rest = dn;
                let g = rest.min(s.gap);
                s.gap -= g;
                rest -= g;
                let l = rest.min(s.lift);
                s.lift -= l;
                rest -= l;
                advance = rest;
            } else if dn < 0.0 {
                if s.gap > 0.0 {
                    s.gap -= dn;
                } else {
                    s.lift -= dn;
                }
            }
            let state = if advance > 0.0 {
                s.section.advance(advance, dt_seg * advance / dn)?
            } else {
                *s.section.state()
            };
            let touching = s.gap <= 0.0 && s.lift <= 0.0 && state.knife_displacement > 0.0;
            work += state.work.knife * s.segment.length;
            depth_sum += state.crack_depth;
            deformation = deformation.max(state.surface_deflection);
            if state.fractured {
                fractured += 1;
            }
            if touching {
                contact_length += s.segment.length;
                let (tangent, normal) = s.segment.world_frame();
                let midpoint =
                    self.position + Vector3::new(0.0, s.segment.midpoint.y, s.segment.midpoint.x);
                self.loads.push(SegmentLoad {
                    midpoint,
                    normal,
                    tangent,
                    length: s.segment.length,
                    force_normal: state.force_vertical,
                    force_tangent: -s.tangential_sign * state.force_tangential,
                });
            }
        }
        self.work = work;
        let sensor_origin = self.position + self.sensor_offset;
        let true_wrench = wrench_at(&sensor_origin, &self.loads);
        let wrench = self.sensor.read(self.time, &true_wrench.to_array());
        Ok(Measurement {
            time: self.time,
            position: self.position,
            velocity: v,
            wrench,
            true_wrench,
            crack_depth: depth_sum / self.sections.len() as f64,
            contact_length,
            fractured_sections: fractured,
            work: self.work,
            deformation,
            status,
        })
    }
}
