//! The whole-knife, whole-object plant, stepped like a robot arm's servo loop.

use nalgebra::{Vector2, Vector3};
use serde::{Deserialize, Serialize};

use crate::blade::BladeSection;
use crate::geometry::{SectionPlane, TriangleMesh};
use crate::invalid_setting::InvalidSetting;
use crate::knife::Knife;
use crate::material::Material;
use crate::section::{CrossSection, SectionError, SectionGeometry, SectionSettings};

use super::arm_limits::{ArmLimitMonitor, ArmLimits, LimitViolation};
use super::contact_arc::{EdgeSegment, contact_arc, knife_plane_silhouette, ray_hit, segments};
use super::crack_front::CrackFront;
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
    /// How far a segment's midpoint may slide off its cross section's plane
    /// before the section is re-chosen through the crack front, m (default
    /// 0.001: seed 000 §IV updates the sections in 1 mm steps).
    pub update_distance: f64,
    /// The F/T sensor.
    pub sensor: FtSensorSettings,
}

impl Default for PlantSettings {
    fn default() -> Self {
        Self {
            segments: 10,
            start_gap: 1e-3,
            rim_fraction: 0.05,
            update_distance: 1e-3,
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
        if !(self.update_distance.is_finite() && self.update_distance > 0.0) {
            return Err(InvalidSetting::new(
                "update_distance",
                self.update_distance,
                "must be a finite number > 0 m",
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
    /// Mean crack depth over the active sections (those whose plane cuts the
    /// object; 0 when none is), m.
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
    /// The section's plane in the world.
    plane: SectionPlane,
    /// The section's shape, to tell whether a re-chosen plane cuts the same one.
    geometry: SectionGeometry,
    /// Whether the plane cuts the object (a segment that slid off the piece
    /// has no material: no force, not advanced).
    active: bool,
    /// Knife work per unit length done on the section's predecessors, J/m.
    work_offset: f64,
    /// Signed distance of the segment's midpoint from the plane when the
    /// plane was chosen, m: q lies on the midpoint's path, not at the
    /// midpoint (the edge indents below the crack tip), so a slicing segment
    /// starts off its new plane by λ·(d·t); the slide is counted from there.
    /// 0 at construction: the midpoint reaches its first contact when the
    /// section starts.
    slide_reference: f64,
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
/// (seed 000 §IV).
///
/// # Moving cross sections (seed 000 §IV, Fig. 4(b))
/// After each tick the plant measures, for every section that has started
/// cutting, how far its segment's midpoint has slid off the section's plane
/// (along the plane's normal) since the plane was chosen. Past [`PlantSettings::update_distance`] the
/// section is re-chosen: a [`CrackFront`] is fitted over the crack tips of the
/// started sections, intersected with the midpoint's path (the line through
/// the midpoint along the planned direction) at q, and the new plane is
/// normal to the segment through q. Then
/// - if the plane misses the object (the segment slid off the piece), the
///   section becomes inactive (no force, not advanced) until a later
///   re-choice finds material again;
/// - if it cuts the same shape (a cuboid's interior), only the plane moves
///   and the section keeps its state;
/// - otherwise a new [`CrossSection`] is built for the new shape and
///   restarted with the crack depth at q and the predecessor's fracture flag
///   ([`CrossSection::restart_with_crack`]); the predecessor's knife work is
///   kept, so the plant's cumulative work never drops. Only the crack is
///   carried over, not the predecessor's elastic state.
///
/// Without a started section there is nothing to fit and no re-choice.
///
/// # Memory allocation
/// [`Plant::new`] allocates everything a tick without a re-choice needs;
/// such a [`Plant::step`] allocates nothing (a pressing straight edge: its
/// segments move within their planes). A re-choice cuts the object mesh with
/// the new plane, which allocates the section polygon, and a rebuild
/// allocates a new [`CrossSection`] (mesh, factorisation, workspace).
#[derive(Debug, Clone)]
pub struct Plant {
    sections: Vec<SegmentSection>,
    /// The object, cut again by re-chosen planes.
    object: TriangleMesh,
    material: Material,
    blade: BladeSection,
    section_settings: SectionSettings,
    rim_fraction: f64,
    update_distance: f64,
    /// Planned direction of motion in the knife plane (z, y), unit.
    direction: Vector2<f64>,
    /// Crack tips of the started sections (knife plane (z, y)), preallocated.
    tips: Vec<Vector2<f64>>,
    /// The last crack front fitted for a re-choice.
    front: Option<CrackFront>,
    rechoices: usize,
    rebuilds: usize,
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
                plane,
                geometry,
                active: true,
                work_offset: 0.0,
                slide_reference: 0.0,
                gap: lambda * d.dot(&segment.normal),
                lift: 0.0,
                tangential_sign: 0.0,
            });
        }
        if sections.is_empty() {
            return Err(PlantError::NoContact);
        }
        let loads = Vec::with_capacity(sections.len());
        let tips = Vec::with_capacity(sections.len());
        Ok(Self {
            loads,
            sections,
            object: object.clone(),
            material: *material,
            blade: *knife.blade(),
            section_settings: *section,
            rim_fraction: settings.rim_fraction,
            update_distance: settings.update_distance,
            direction: d,
            tips,
            front: None,
            rechoices: 0,
            rebuilds: 0,
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

    /// For each section, heel to tip: its segment, its plane, and whether the
    /// plane cuts the object (inactive sections carry no force).
    pub fn section_planes(&self) -> impl Iterator<Item = (&EdgeSegment, &SectionPlane, bool)> {
        self.sections
            .iter()
            .map(|s| (&s.segment, &s.plane, s.active))
    }

    /// Crack tips of the active sections that have started cutting, in the
    /// knife plane (world z, y), heel to tip: the points the crack front is
    /// fitted over.
    pub fn crack_tips(&self) -> impl Iterator<Item = Vector2<f64>> + '_ {
        self.sections
            .iter()
            .filter(|s| s.active && s.section.state().knife_displacement > 0.0)
            .map(tip_of)
    }

    /// The crack front fitted at the last re-choice (None before the first).
    pub fn crack_front(&self) -> Option<&CrackFront> {
        self.front.as_ref()
    }

    /// Number of section re-choices so far (a plane moved, a section became
    /// inactive, or a section was rebuilt).
    pub fn rechoices(&self) -> usize {
        self.rechoices
    }

    /// Number of re-choices that built a new [`CrossSection`] for a new shape.
    pub fn rebuilds(&self) -> usize {
        self.rebuilds
    }

    /// The sections' current states, heel to tip.
    pub fn section_states(&self) -> impl Iterator<Item = &crate::section::SectionStep> {
        self.sections.iter().map(|s| s.section.state())
    }

    /// Executes `command` for `dt` seconds and returns the measurement.
    /// A command that breaks an arm limit is refused: the knife holds still
    /// and the status says why. After the sections advance, those that slid
    /// `update_distance` off their planes are re-chosen (see the type's docs).
    /// Allocates nothing unless a section is re-chosen.
    ///
    /// # Errors
    /// A section's step fails, or a re-chosen section cannot be built.
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
        let mut active = 0usize;
        for s in &mut self.sections {
            if !s.active {
                // No material under the segment: no force, not advanced.
                let state = s.section.state();
                work += (s.work_offset + state.work.knife) * s.segment.length;
                if state.fractured {
                    fractured += 1;
                }
                continue;
            }
            active += 1;
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
            work += (s.work_offset + state.work.knife) * s.segment.length;
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
        self.rechoose()?;
        let sensor_origin = self.position + self.sensor_offset;
        let true_wrench = wrench_at(&sensor_origin, &self.loads);
        let wrench = self.sensor.read(self.time, &true_wrench.to_array());
        Ok(Measurement {
            time: self.time,
            position: self.position,
            velocity: v,
            wrench,
            true_wrench,
            crack_depth: if active > 0 {
                depth_sum / active as f64
            } else {
                0.0
            },
            contact_length,
            fractured_sections: fractured,
            work: self.work,
            deformation,
            status,
        })
    }

    /// Re-chooses the sections whose segments slid more than
    /// `update_distance` off their planes (seed 000 §IV, Fig. 4(b); see the
    /// type's docs).
    fn rechoose(&mut self) -> Result<(), SectionError> {
        let position = self.position;
        let threshold = self.update_distance;
        let slid = |s: &SegmentSection| {
            s.section.state().knife_displacement > 0.0
                && (signed_offset(&s.plane, &midpoint_world(&position, &s.segment))
                    - s.slide_reference)
                    .abs()
                    > threshold
        };
        if !self.sections.iter().any(slid) {
            return Ok(());
        }
        self.tips.clear();
        for s in &self.sections {
            if s.active && s.section.state().knife_displacement > 0.0 {
                self.tips.push(tip_of(s));
            }
        }
        let Some(front) = CrackFront::fit(&self.tips) else {
            return Ok(());
        };
        self.front = Some(front);
        let d = self.direction;
        for s in &mut self.sections {
            let m = midpoint_world(&position, &s.segment);
            if !(s.section.state().knife_displacement > 0.0
                && (signed_offset(&s.plane, &m) - s.slide_reference).abs() > threshold)
            {
                continue;
            }
            self.rechoices += 1;
            let m2 = Vector2::new(m.z, m.y);
            // q: the front on the midpoint's path; if the path misses the
            // fitted front (or meets its extrapolation farther than the
            // object's size away), the height of the section's own tip on
            // that path.
            let lambda = front
                .intersect_nearest(m2, d)
                .filter(|l| l.abs() <= self.object.size())
                .unwrap_or_else(|| (tip_of(s).y - m2.y) / d.y);
            let q2 = m2 + d * lambda;
            let q = Vector3::new(0.0, q2.y, q2.x);
            let up = -Vector3::new(0.0, s.segment.normal.y, s.segment.normal.x);
            let plane = SectionPlane::normal_to_segment(q, up);
            s.plane = plane;
            s.slide_reference = signed_offset(&plane, &m);
            let Some(polygon) = plane.section(&self.object) else {
                s.active = false;
                continue;
            };
            let height = polygon.bounds().1.y;
            let Ok(geometry) = section_geometry(&polygon, self.rim_fraction * height) else {
                // Lower than the rim everywhere: no material worth a section.
                s.active = false;
                continue;
            };
            if s.active && same_geometry(&geometry, &s.geometry) {
                continue;
            }
            let mut section = CrossSection::new(
                &geometry,
                &self.material,
                &self.blade,
                &self.section_settings,
            )?;
            let depth = (geometry.height_at_cut() - plane.to_plane(&q).y).max(0.0);
            let old = s.section.state();
            section.restart_with_crack(depth, old.fractured);
            s.work_offset += old.work.knife;
            s.section = section;
            s.geometry = geometry;
            s.active = true;
            self.rebuilds += 1;
        }
        Ok(())
    }
}

/// A segment's midpoint in the world (x = 0) for the knife at `position`.
fn midpoint_world(position: &Vector3<f64>, segment: &EdgeSegment) -> Vector3<f64> {
    position + Vector3::new(0.0, segment.midpoint.y, segment.midpoint.x)
}

/// Signed distance of `p` from `plane` along its normal, m.
fn signed_offset(plane: &SectionPlane, p: &Vector3<f64>) -> f64 {
    (p - plane.origin).dot(&plane.normal())
}

/// A section's crack tip in the knife plane (world z, y).
fn tip_of(s: &SegmentSection) -> Vector2<f64> {
    let w = s
        .plane
        .to_world(&Vector2::new(0.0, s.section.state().crack_tip_height));
    Vector2::new(w.z, w.y)
}

/// Whether two section shapes agree to a relative 1e-9 of their size (the
/// plane cuts of a prism's interior differ by rounding only).
fn same_geometry(a: &SectionGeometry, b: &SectionGeometry) -> bool {
    let scale = a.height_at_cut().max(a.half_width());
    let tol = 1e-9 * scale;
    let close = |x: f64, y: f64| (x - y).abs() <= tol;
    if !(close(a.height_at_cut(), b.height_at_cut()) && close(a.half_width(), b.half_width())) {
        return false;
    }
    const SAMPLES: usize = 64;
    (0..=SAMPLES).all(|k| {
        let x = a.half_width() * k as f64 / SAMPLES as f64;
        close(a.top_at(x), b.top_at(x))
    })
}
