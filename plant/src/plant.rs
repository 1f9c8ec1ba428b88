//! The whole-knife, whole-object plant, stepped like a robot arm's servo loop.

use std::sync::Arc;

use nalgebra::{Vector2, Vector3};

use shearcut_sim::geometry::{Polygon, SectionPlane, TriangleMesh};
use shearcut_sim::invalid_setting::InvalidSetting;
use shearcut_sim::knife::Knife;
use shearcut_sim::material::Material;
use shearcut_sim::section::{CrossSection, SectionError, SectionGeometry, SectionSettings};

use super::crack_front::CrackFront;
use super::ft_sensor::FtSensor;
use super::successor::{Preparation, SectionFactory, SuccessorJob, SuccessorWorker};
use super::wrench::{SegmentLoad, wrench_at};
use shearcut_sim::arm::{ArmLimitMonitor, ArmLimits, ArmReading, ArmStatus, KnifeCommand};
use shearcut_sim::knife_plane::contact_arc::{
    EdgeSegment, contact_arc, knife_plane_silhouette, ray_hit, segment_grid, span_arc,
};

use crate::plant_step::{PlantStep, PlantTruth};

pub use crate::plant_error::PlantError;
pub use crate::plant_settings::{MAX_SEGMENTS, PlantSettings};

/// One segment's section and its bookkeeping.
#[derive(Debug, Clone)]
struct SegmentSection {
    /// Index of the segment on the contact arc (heel 0); the worker's slot.
    slot: usize,
    segment: EdgeSegment,
    section: Box<CrossSection>,
    /// The section's plane in the world.
    plane: SectionPlane,
    /// The section's shape, to tell whether a re-chosen plane cuts the same
    /// one (shared with the worker's jobs).
    geometry: Arc<SectionGeometry>,
    /// Whether the plane cuts the object (a segment that slid off the piece
    /// has no material: no force, not advanced).
    active: bool,
    /// Knife work per unit length done on the section's predecessors, J/m.
    work_offset: f64,
    /// Signed distance of the segment's midpoint from the plane when the
    /// plane was chosen, m: q lies on the midpoint's path, not at the
    /// midpoint (the edge indents below the crack tip), so a slicing segment
    /// starts off its new plane by λ·(d·t); the slide is counted from there.
    /// 0 for a fresh section: the midpoint reaches its first contact when
    /// the section starts.
    slide_reference: f64,
    /// Normal distance the edge still has to travel to reach the section's top, m.
    gap: f64,
    /// Normal distance the edge has been pulled back out, m.
    lift: f64,
    /// Sign of the last tangential motion (+1 towards the tip).
    tangential_sign: f64,
    /// Side (±1) of the plane towards which the pending successor was
    /// foreseen; 0 when none is pending.
    predicted_sign: f64,
    /// Whether the section took over a cut (a re-chosen successor, or a
    /// near-face segment's first section): its plane follows the segment
    /// even before its edge advances (a successor restarted at the top of
    /// its section has not advanced yet).
    successor: bool,
}

/// The plant: a knife (any edge) cutting an object (any closed mesh) through
/// moving cross sections, with an arm's limit reflexes and an F/T sensor.
///
/// # Segments (seed 000 §IV, assumption A2, Fig. 4(a))
/// The edge over the object's span along z (the arc a pressing knife
/// touches) is split into [`PlantSettings::segments`] segments of equal arc
/// length; segments of the same length continue the grid over the edge
/// within [`PlantSettings::reach`] of that span and over the arc the planned
/// direction touches. Each segment stands for its chord; its cross section,
/// normal to it, carries the force per unit length.
///
/// # Sections placed where the edge arrives
/// A segment gets its first section when its midpoint, moving along the
/// *executed* direction of motion, reaches the material: not where a
/// planned direction said it would (seed 000 places the sections for the
/// planned motion; a controller that slices at another ratio than planned,
/// or saws, brings other parts of the edge to other places, and sections
/// fixed for the plan cut material the knife never reaches; docs/model.md,
/// "The plant", gives the size of that error). Each tick, a segment
/// without a section whose midpoint's path (along the direction of motion)
/// meets the object within two update distances orders its section from
/// the worker thread, normal to it through q:
/// - where the path meets the **intact surface** (the top, not yet cut): q
///   is the entry point, and the section is fresh (no crack); it is taken
///   when the midpoint is a quarter of an update distance from the surface,
///   with that gap still to travel. The order is renewed when the predicted
///   entry moves by more than a tenth of the update distance (the controller
///   turned the knife).
/// - where the path enters **behind the crack front** (through a side face
///   below the top, e.g. a cuboid's near face when slicing steeply, or a
///   surface the knife has already cut, e.g. the far end of the kerf when
///   sawing back): q is the crack front's crossing of the path at the entry
///   point (or the entry point itself if that crossing is not in the
///   material); the section is taken when the midpoint is in the material
///   and takes over the cut like a re-chosen section
///   ([`CrossSection::take_over`]): the crack depth where the front crosses
///   its plane, the knife where it is (an edge below the front keeps its
///   indentation), and the first-fracture flag and drag of the nearest
///   started section, whose part of the edge cut this material before
///   moving on; it then follows its segment at once. A surface counts as
///   cut where the crack interpolated between the started sections' tips
///   lies more than a quarter of an update distance below it. Without a
///   started section there is no front, and nothing enters behind it.
///
/// A segment whose path never meets the object never gets a section.
/// [`Plant::new`] orders the sections for the planned direction and waits
/// for them, so that a knife moving along it finds them built; along
/// another direction they are re-ordered (and the plant may wait for the
/// worker on the first ticks). The results depend on the planned direction
/// only through the tenth-of-an-update-distance tolerance on renewing an
/// order ([`Plant::first_contacts`], [`Plant::woken_segments`],
/// [`Plant::dormant_segments`]).
///
/// # Moving cross sections (seed 000 §IV, Fig. 4(b))
/// After each tick the plant measures, for every section that has started
/// cutting or taken over a cut (a successor), how far its segment's midpoint has slid off the section's plane
/// (along the plane's normal) since the plane was chosen. Past
/// [`PlantSettings::update_distance`] the section is re-chosen: a
/// [`CrackFront`] is fitted over the crack tips of the started sections, and
/// the new plane is normal to the segment through q, the front's crossing of
/// the midpoint's path. The path is the line through the midpoint along the
/// *direction of motion*: that of the last nonzero executed velocity (the
/// planned direction before the knife first moves), so a controller that
/// turns the knife mid-cut moves the sections along where the edge really
/// goes. Then
/// - if the plane misses the object (the segment slid off the piece), the
///   section becomes inactive (no force, not advanced) until a later
///   re-choice finds material again;
/// - if it cuts the same shape (a cuboid's interior), only the plane moves
///   and the section keeps its state;
/// - otherwise a new [`CrossSection`] for the new shape takes over,
///   takes over the cut ([`CrossSection::take_over`]): the crack depth
///   where the front crosses the new plane, the predecessor's fracture flag,
///   and the edge's indentation below the crack tip and drag (the knife does
///   not move when a plane is re-chosen), with the elastic state evaluated
///   on the new shape; the predecessor's knife work is kept, so the plant's
///   cumulative work never drops. (Restarting the edge at the crack tip
///   would throw away the indentation at every re-choice: a flank section
///   under the eggplant's tough skin, re-chosen every few millimetres of
///   travel, would never build up the indentation its first fracture needs
///   and never fracture while the knife went on through.)
///
/// Without a started section there is nothing to fit and no re-choice.
///
/// # Successors prepared ahead (no section built inside a tick)
/// Building a section (cutting the mesh, meshing, factorising, condensing)
/// takes 0.1–0.2 s, two hundred 1 kHz ticks. So the plant foresees each
/// successor: as soon as a section has started cutting or been re-chosen
/// (the tick after), q is taken where the midpoint will be when its slide
/// reaches the threshold on the side it is moving to (moving on along the
/// direction of motion), with the front fitted then, and a worker thread
/// cuts and builds the successor for that plane: the worker has a whole
/// update distance of travel to finish it. At the
/// re-choice the plant takes it (waiting only if the worker is late); the
/// adopted plane is the foreseen one, the carried crack depth is read off
/// the front fitted at the re-choice. What the worker returns is a function
/// of the job alone, and the job is fixed at a deterministic tick, so the
/// results are bit-identical for a seed whatever the thread timing. A
/// motion that reverses across a plane re-orders the successor for the
/// other side once the midpoint is back over the plane. A re-choice that was
/// still not foreseen on its side (see [`Plant::unforeseen_rechoices`])
/// orders its successor from the current front and waits for it.
///
/// # Memory allocation
/// [`Plant::new`] allocates everything a tick needs and starts the worker;
/// [`Plant::step`] allocates nothing on the caller's thread, re-choices
/// included: the worker allocates the successors, the tick only moves them
/// in (and frees superseded ones).
#[derive(Debug, Clone)]
pub struct Plant {
    sections: Vec<SegmentSection>,
    /// The object, material, blade and section settings, shared with the
    /// worker that builds successor sections.
    factory: Arc<SectionFactory>,
    /// Prepares successor sections ahead of their re-choices.
    worker: SuccessorWorker,
    update_distance: f64,
    /// Direction of motion in the knife plane (z, y), unit: the planned one
    /// until the knife moves, then that of the last nonzero executed velocity.
    motion: Vector2<f64>,
    /// The object's silhouette in the knife plane (z, y).
    silhouette: Polygon,
    /// Height of the silhouette's top, m: the depth is measured below it.
    top: f64,
    /// Every segment of the edge's grid, heel to tip (the worker's slots).
    edge_segments: Vec<EdgeSegment>,
    /// The segments without a section yet. Preallocated; shrinks as they
    /// get theirs.
    dormant: Vec<DormantSegment>,
    /// Crack tips of the started sections (knife plane (z, y)), preallocated.
    tips: Vec<Vector2<f64>>,
    /// The last crack front fitted for a re-choice.
    front: Option<CrackFront>,
    rechoices: usize,
    rebuilds: usize,
    unforeseen: usize,
    first_contacts: usize,
    wakes: usize,
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
    /// along z, seed 000 Fig. 6(b)), with the lowest point of its edge over
    /// the object `start_gap` above it. `direction` is the planned direction
    /// of motion (knife plane (z, y), pointing down into the object): the
    /// first sections are built for it here (see the type's docs), and the
    /// sections follow it until the knife first moves. `section` configures
    /// every cross section; `arm_limits` are the reflexes checked on every
    /// command.
    ///
    /// # Errors
    /// A setting is out of range, no edge point's path along `direction`
    /// meets the object, or a first section cannot be built.
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
        let start = Self::start_position(knife, object, z0, settings.start_gap);
        let origin = Vector2::new(start.z, start.y);
        let edge = knife.edge();
        // m segments over the object's span (the arc a pressing knife
        // touches), the grid continued over the edge within `reach` of the
        // span and over the arc the planned direction touches.
        let down = Vector2::new(0.0, -1.0);
        let anchor = contact_arc(edge, origin, down, &silhouette).ok_or(PlantError::NoContact)?;
        let (lo, hi) = silhouette.bounds();
        let reach =
            span_arc(edge, origin, lo.x - settings.reach, hi.x + settings.reach).unwrap_or(anchor);
        let planned = contact_arc(edge, origin, d, &silhouette).unwrap_or(anchor);
        let cover = (reach.0.min(planned.0), reach.1.max(planned.1));
        let grid = segment_grid(edge, anchor, settings.segments, cover);
        if grid.len() > MAX_SEGMENTS {
            return Err(InvalidSetting::new(
                "reach",
                settings.reach,
                format!(
                    "gives {} segments of the edge (segments = {}), at most {MAX_SEGMENTS} are allowed",
                    grid.len(),
                    settings.segments
                ),
            )
            .into());
        }
        let factory = Arc::new(SectionFactory {
            object: object.clone(),
            material: *material,
            blade: *knife.blade(),
            settings: *section,
            rim_fraction: settings.rim_fraction,
        });
        let worker = SuccessorWorker::new(Arc::clone(&factory), grid.len(), settings.workers);
        let mut plant = Self {
            loads: Vec::with_capacity(grid.len()),
            tips: Vec::with_capacity(grid.len()),
            sections: Vec::with_capacity(grid.len()),
            dormant: grid
                .iter()
                .enumerate()
                .map(|(slot, _)| DormantSegment { slot, order: None })
                .collect(),
            edge_segments: grid,
            worker,
            factory,
            update_distance: settings.update_distance,
            motion: d,
            top: hi.y,
            silhouette,
            front: None,
            rechoices: 0,
            rebuilds: 0,
            unforeseen: 0,
            first_contacts: 0,
            wakes: 0,
            monitor: ArmLimitMonitor::new(*arm_limits),
            sensor: FtSensor::new(settings.sensor, seed).map_err(|e| e.prefixed("sensor"))?,
            sensor_offset: knife.sensor_position(),
            position: Vector3::new(0.0, origin.y, origin.x),
            time: 0.0,
            work: 0.0,
        };
        // Prepare the first sections for the planned direction, so that a
        // knife moving along it finds them built (a real-time loop must not
        // wait for them), and place those whose midpoints are already at
        // the surface.
        let hits = plant
            .edge_segments
            .iter()
            .filter(|s| ray_hit(&plant.silhouette, origin + s.midpoint, d).is_some())
            .count();
        if hits == 0 {
            return Err(PlantError::NoContact);
        }
        let section_error = |(index, source)| PlantError::Section { index, source };
        plant.place(Lookahead::Everywhere).map_err(section_error)?;
        plant.worker.wait_idle();
        plant.place(Lookahead::Lead).map_err(section_error)?;
        Ok(plant)
    }

    /// Where [`Plant::new`] puts the knife frame's origin (world frame, m):
    /// z so that the piece is `z0` from the heel along the edge, y so that
    /// the lowest point of the edge over the object is `start_gap` above its
    /// top. Cheap (no section is built): a controller process that needs
    /// the start without a plant of its own computes it here.
    pub fn start_position(
        knife: &Knife,
        object: &TriangleMesh,
        z0: f64,
        start_gap: f64,
    ) -> Vector3<f64> {
        let (lo, hi) = object.bounds();
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
        Vector3::new(0.0, hi.y + start_gap - lowest_over, origin_z)
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

    /// Number of segments whose first section was placed behind the crack
    /// front (their paths entered through a side face below the top or a
    /// surface the knife had already cut).
    pub fn woken_segments(&self) -> usize {
        self.wakes
    }

    /// Number of segments whose first section was placed fresh on the
    /// intact surface where their midpoints arrived.
    pub fn first_contacts(&self) -> usize {
        self.first_contacts
    }

    /// Number of segments still without a section (their midpoints have not
    /// reached the material, or never will).
    pub fn dormant_segments(&self) -> usize {
        self.dormant.len()
    }

    /// Every segment of the edge's grid, heel to tip, with a section or not.
    pub fn edge_segments(&self) -> &[EdgeSegment] {
        &self.edge_segments
    }

    /// Number of re-choices whose successor had not been foreseen on the side
    /// the segment slid to, so that the tick waited for the worker to build
    /// it: the midpoint crossed the whole update distance in one tick, or a
    /// section's edge first touched after its segment had slid farther than
    /// that off the plane it was placed on.
    pub fn unforeseen_rechoices(&self) -> usize {
        self.unforeseen
    }

    /// Number of successors that were not ready when their re-choice took
    /// them, so that the tick waited for the worker. A diagnostic of the
    /// machine's load: it depends on thread timing (the plant's results do
    /// not).
    pub fn successor_waits(&self) -> usize {
        self.worker.waits()
    }

    /// Number of sections the worker built for orders that were renewed or
    /// dropped before they were taken (a predicted plane that moved, a
    /// motion that reversed, the orders [`Plant::new`] placed for the
    /// planned direction when the knife goes elsewhere): CPU spent on
    /// nothing. A diagnostic like [`Plant::successor_waits`]: it depends on
    /// thread timing (an order renewed before a worker started it costs
    /// nothing), the plant's results do not.
    pub fn wasted_builds(&self) -> usize {
        self.worker.wasted_builds()
    }

    /// Direction of motion the re-choices follow, in the knife plane (world
    /// z, y), unit: that of the last nonzero executed velocity, or the
    /// planned direction before the knife first moves.
    pub fn direction_of_motion(&self) -> Vector2<f64> {
        self.motion
    }

    /// Linear solves of the condensed line done by the current sections so
    /// far (their cost counter, see [`CrossSection::solves`]).
    pub fn section_solves(&self) -> u64 {
        self.sections.iter().map(|s| s.section.solves()).sum()
    }

    /// The sections' current states, heel to tip.
    pub fn section_states(&self) -> impl Iterator<Item = &shearcut_sim::section::SectionStep> {
        self.sections.iter().map(|s| s.section.state())
    }

    /// Executes `command` for `dt` seconds and returns the measurement.
    /// A command that breaks an arm limit is refused: the knife holds still
    /// and the status says why. After the sections advance, those that slid
    /// `update_distance` off their planes are re-chosen, and the next
    /// successors are ordered from the worker (see the type's docs).
    /// Allocates nothing.
    ///
    /// # Errors
    /// A section's step fails, or a re-chosen section cannot be built.
    pub fn step(&mut self, command: &KnifeCommand, dt: f64) -> Result<PlantStep, SectionError> {
        let mut v = command.velocity;
        let status = match self.monitor.check(v, dt) {
            Ok(()) => ArmStatus::Moving,
            Err(violation) => {
                v = Vector3::zeros();
                self.monitor.reset();
                ArmStatus::LimitViolation(violation)
            }
        };
        let dt = if dt.is_finite() && dt > 0.0 { dt } else { 0.0 };
        let dp = v * dt;
        self.position += Vector3::new(0.0, dp.y, dp.z);
        self.time += dt;
        let dp2 = Vector2::new(dp.z, dp.y);
        if let Some(u) = dp2.try_normalize(0.0) {
            self.motion = u;
        }
        self.loads.clear();
        let mut contact_length = 0.0;
        let mut fractured = 0;
        let mut tip_height_sum = 0.0;
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
            tip_height_sum += tip_of(s).y;
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
        self.place(Lookahead::Lead).map_err(|(_, e)| e)?;
        let sensor_origin = self.position + self.sensor_offset;
        let true_wrench = wrench_at(&sensor_origin, &self.loads);
        let wrench = self.sensor.read(self.time, &true_wrench.to_array());
        Ok(PlantStep {
            reading: ArmReading {
                time: self.time,
                position: self.position,
                velocity: v,
                wrench,
                status,
            },
            truth: PlantTruth {
                wrench: true_wrench,
                crack_depth: if active > 0 {
                    self.top - tip_height_sum / active as f64
                } else {
                    0.0
                },
                contact_length,
                fractured_sections: fractured,
                work: self.work,
                deformation,
            },
        })
    }

    /// Re-chooses the sections whose segments slid more than
    /// `update_distance` off their planes, and orders the successors of the
    /// tracked sections without one from the worker (seed 000 §IV, Fig. 4(b);
    /// see the type's docs). Allocates nothing.
    fn rechoose(&mut self) -> Result<(), SectionError> {
        let position = self.position;
        let threshold = self.update_distance;
        let worker = &self.worker;
        let motion = self.motion;
        let due = self.sections.iter().any(|s| {
            let slide = slide_of(s, &position);
            tracked(s)
                && (slide.abs() > threshold
                    || foresee(
                        s,
                        slide,
                        approach_rate(s, &motion),
                        worker.is_pending(s.slot),
                    ))
        });
        if !due {
            return Ok(());
        }
        let Some(front) = fit_front(&self.sections, &mut self.tips) else {
            return Ok(());
        };
        self.front = Some(front);
        let u = self.motion;
        let size = self.factory.object.size();
        for i in 0..self.sections.len() {
            let (before, rest) = self.sections.split_at_mut(i);
            let (s, after) = rest.split_first_mut().expect("i < len");
            if !tracked(s) {
                continue;
            }
            let m = midpoint_world(&position, &s.segment);
            let m2 = Vector2::new(m.z, m.y);
            let slide = signed_offset(&s.plane, &m) - s.slide_reference;
            if slide.abs() > threshold {
                self.rechoices += 1;
                let sign = slide.signum();
                if !(self.worker.is_pending(s.slot) && s.predicted_sign == sign) {
                    // Not foreseen (the motion reversed, or one tick crossed
                    // the whole half distance): prepare it now and wait.
                    self.worker.cancel(s.slot);
                    let plane = plane_on_path(&front, m2, u, tip_of(s), &s.segment, size);
                    self.worker.submit(s.slot, job(s, plane));
                    self.unforeseen += 1;
                }
                s.predicted_sign = 0.0;
                let Some((plane, prepared)) = self.worker.take(s.slot) else {
                    continue;
                };
                let tip = tip_of(s);
                let was_active = s.active;
                let old_origin = s.plane.origin;
                s.plane = plane;
                s.slide_reference = signed_offset(&plane, &m);
                match prepared {
                    Preparation::NoMaterial => s.active = false,
                    Preparation::SameShape => {}
                    Preparation::Failed(e) => return Err(e),
                    // `take` resumes a worker's panic; kept for completeness.
                    Preparation::Panicked(p) => std::panic::resume_unwind(p),
                    Preparation::New { geometry, section } => {
                        // The crack carried over: the front where it crosses
                        // the new plane (its trace in the knife plane is the
                        // line from the board point along the segment's up).
                        // From an active predecessor, the front shifted to
                        // pass through the predecessor's own tip, so that
                        // the least-squares fit's residual at that tip
                        // (millimetres where intact flank tips and deep
                        // middle ones share one quadratic) neither heals nor
                        // deepens the crack; or, if it misses within the
                        // object's size, the height of the predecessor's
                        // tip. A predecessor that had slid off the piece
                        // (sawing back over a side face) was not advanced
                        // while the rest of the edge cut on: its tip is
                        // stale, so the segment re-enters behind the
                        // current front and takes over the nearest started
                        // section's cut, as a first section entering
                        // through a side face does (`Plant::place`).
                        let o = Vector2::new(plane.origin.z, plane.origin.y);
                        let up = Vector2::new(plane.v_axis.z, plane.v_axis.y);
                        let neighbour =
                            nearest_started_of(before.iter().chain(after.iter()), s.slot)
                                .filter(|_| !was_active);
                        let (through, fallback) = match neighbour {
                            Some(n) => (front, n.state().crack_tip_height),
                            None => {
                                let mut through_tip = front;
                                through_tip.coefficients[0] += tip.y - front.height_at(tip.x);
                                (through_tip, tip.y / up.y)
                            }
                        };
                        let along = through
                            .intersect_nearest(o, up)
                            .filter(|l| *l >= 0.0 && *l <= size)
                            .unwrap_or(fallback);
                        let depth = (geometry.height_at_cut() - along).max(0.0);
                        // The edge stays where it is: the predecessor's edge
                        // height moved to the new plane's board point (both
                        // planes are normal to the same segment, so heights
                        // differ by the origins' offset along its up); for
                        // a predecessor that had slid off the object (not
                        // advanced), the midpoint's own height, less any
                        // lift.
                        let edge = if was_active {
                            s.section.state().edge_height
                                + (old_origin - plane.origin).dot(&plane.v_axis)
                        } else {
                            (m - plane.origin).dot(&plane.v_axis) - s.lift
                        };
                        // The successor takes over the cut: that crack, the
                        // predecessor's first-fracture flag, and the knife
                        // where it is (see `CrossSection::take_over`).
                        let mut section = section;
                        section.take_over(neighbour.unwrap_or(&s.section), depth, edge);
                        // An edge above the new section's top (a lower shape
                        // towards the flank) has that gap to travel first.
                        s.gap = (edge - geometry.height_at_cut()).max(0.0);
                        let old = *s.section.state();
                        s.section = section;
                        s.work_offset += old.work.knife;
                        s.geometry = geometry;
                        s.active = true;
                        s.successor = true;
                        self.rebuilds += 1;
                    }
                }
            } else if foresee(
                s,
                slide,
                approach_rate(s, &u),
                self.worker.is_pending(s.slot),
            ) {
                // Foresee the successor: where the midpoint will be when the
                // slide reaches the threshold on the side it is moving to,
                // moving on along the direction of motion u, and the front's
                // crossing of u's line through that point. (A new order
                // supersedes a pending one.)
                let rate = approach_rate(s, &u);
                let sign = rate.signum();
                let travel = (sign * threshold - slide) / rate;
                let ahead = m2 + u * travel;
                let plane = plane_on_path(&front, ahead, u, tip_of(s), &s.segment, size);
                self.worker.submit(s.slot, job(s, plane));
                s.predicted_sign = sign;
            }
        }
        Ok(())
    }
}

impl Plant {
    /// Gives the dormant segments their first sections where their
    /// midpoints' paths along the direction of motion u reach the material
    /// (see the type's docs, "Sections placed where the edge arrives").
    /// Within `ORDER_LEAD × update_distance` of the material a segment
    /// orders its section from the worker, re-ordering it when the predicted
    /// plane moves by more than the tolerance of its kind, and takes it
    /// (waiting if the worker is late): an intact surface's section when the
    /// midpoint is within `TAKE_LEAD × update_distance` of it, one behind
    /// the crack front when the midpoint is in the material. `lookahead`
    /// [`Lookahead::Everywhere`] orders every intact entry whatever its
    /// distance (at construction). Allocates nothing; an error names the
    /// segment's slot.
    fn place(&mut self, lookahead: Lookahead) -> Result<(), (usize, SectionError)> {
        if self.dormant.is_empty() {
            return Ok(());
        }
        let position = self.position;
        let u = self.motion;
        let ud = self.update_distance;
        let lead = match lookahead {
            Lookahead::Lead => ORDER_LEAD * ud,
            Lookahead::Everywhere => f64::INFINITY,
        };
        let size = self.factory.object.size();
        let side_tolerance = 1e-9 * size;
        // The front over the started sections' tips (the tips stay in
        // self.tips for `surface_is_cut`), fitted when first needed.
        let mut fitted: Option<Option<CrackFront>> = None;
        let mut k = 0;
        while k < self.dormant.len() {
            let DormantSegment { slot, order } = self.dormant[k];
            let segment = self.edge_segments[slot];
            let m = midpoint_world(&position, &segment);
            let m2 = Vector2::new(m.z, m.y);
            let inside = self
                .silhouette
                .top_at(m2.x)
                .is_some_and(|top| m2.y >= 0.0 && m2.y < top);
            let entry = if inside {
                Some(0.0)
            } else {
                ray_hit(&self.silhouette, m2, u)
            };
            let Some(entry) = entry else {
                // The path misses the object: nothing to prepare.
                self.worker.cancel(slot);
                self.dormant[k].order = None;
                k += 1;
                continue;
            };
            if entry > lead {
                // Far yet: keep what was ordered for the planned direction.
                k += 1;
                continue;
            }
            let ahead = m2 + u * entry;
            let front = *fitted.get_or_insert_with(|| fit_front(&self.sections, &mut self.tips));
            let pending = self.worker.is_pending(slot);
            let on_top = !inside
                && self
                    .silhouette
                    .top_at(ahead.x)
                    .is_some_and(|top| ahead.y >= top - side_tolerance);
            let intact = on_top
                && !(front.is_some()
                    && surface_is_cut(&self.tips, ahead, 0.5 * segment.length, SURFACE_CUT * ud));
            let target = match (order, front) {
                // A midpoint that passed an intact surface before its
                // section was taken (more than the take lead in one tick)
                // still takes the section ordered for it.
                (Some(o), _) if inside && pending && o.kind == EntryKind::Intact => {
                    Some((o.q, EntryKind::Intact))
                }
                _ if intact => Some((ahead, EntryKind::Intact)),
                (_, Some(front)) => {
                    // q: the front's crossing of the path if it lies in the
                    // material (the front is extrapolated beyond the tips
                    // here), else the entry point itself.
                    let q = front
                        .intersect_nearest(ahead, u)
                        .map(|l| ahead + u * l)
                        .filter(|q| {
                            self.silhouette
                                .top_at(q.x)
                                .is_some_and(|top| q.y >= 0.0 && q.y <= top)
                        })
                        .unwrap_or(ahead);
                    Some((q, EntryKind::BehindFront))
                }
                // Entering behind a crack front that does not exist yet
                // (a side face before any section started): wait.
                (_, None) => None,
            };
            let Some((q, kind)) = target else {
                self.worker.cancel(slot);
                self.dormant[k].order = None;
                k += 1;
                continue;
            };
            let keep = order.is_some_and(|o| {
                o.kind == kind && (o.q - q).norm() <= kind.reorder_tolerance() * ud
            });
            if !keep {
                let up = -Vector3::new(0.0, segment.normal.y, segment.normal.x);
                let plane = SectionPlane::normal_to_segment(Vector3::new(0.0, q.y, q.x), up);
                self.worker.submit(
                    slot,
                    SuccessorJob {
                        plane,
                        current: None,
                    },
                );
                self.dormant[k].order = Some(EntryOrder { q, kind });
            }
            let due = match kind {
                EntryKind::Intact => entry <= TAKE_LEAD * ud,
                EntryKind::BehindFront => inside,
            };
            if !(due && self.worker.is_pending(slot)) {
                k += 1;
                continue;
            }
            let Some((plane, prepared)) = self.worker.take(slot) else {
                k += 1;
                continue;
            };
            let (geometry, mut section) = match prepared {
                Preparation::New { geometry, section } => (geometry, section),
                Preparation::Failed(e) => return Err((slot, e)),
                Preparation::Panicked(p) => std::panic::resume_unwind(p),
                // No material worth a section on that plane: the order
                // stays on record (not pending), so it is re-ordered only
                // once the predicted plane moves on.
                Preparation::NoMaterial | Preparation::SameShape => {
                    k += 1;
                    continue;
                }
            };
            let edge = (m - plane.origin).dot(&plane.v_axis);
            let (gap, slide_reference, successor) = match kind {
                EntryKind::Intact => {
                    // A fresh section: the edge has the rest of the way to
                    // its top to travel. The slide is counted once it starts
                    // cutting, when the midpoint is at q.
                    self.first_contacts += 1;
                    ((edge - geometry.height_at_cut()).max(0.0), 0.0, false)
                }
                EntryKind::BehindFront => {
                    let o = Vector2::new(plane.origin.z, plane.origin.y);
                    let up = Vector2::new(plane.v_axis.z, plane.v_axis.y);
                    let along = front
                        .and_then(|f| f.intersect_nearest(o, up))
                        .filter(|l| *l >= 0.0 && *l <= size)
                        .unwrap_or(m2.y / up.y);
                    let depth = (geometry.height_at_cut() - along).max(0.0);
                    // The material here was cut by the neighbouring part of
                    // the edge, which moved on: the section takes over the
                    // state of the nearest started section (its first
                    // fracture and drag) with the knife where it is, so an
                    // edge already below the front keeps its indentation
                    // (like a re-chosen section, `CrossSection::take_over`).
                    // Without a started neighbour (cannot happen with a
                    // front), a crack below the top still means the first
                    // fracture is done.
                    match nearest_started(&self.sections, slot) {
                        Some(neighbour) => section.take_over(neighbour, depth, edge),
                        None => section.restart_with_crack(depth, depth > 0.0),
                    }
                    self.wakes += 1;
                    (
                        (edge - geometry.height_at_cut()).max(0.0),
                        signed_offset(&plane, &m),
                        true,
                    )
                }
            };
            let at = self
                .sections
                .iter()
                .position(|s| s.slot > slot)
                .unwrap_or(self.sections.len());
            self.sections.insert(
                at,
                SegmentSection {
                    slot,
                    segment,
                    section,
                    plane,
                    geometry,
                    active: true,
                    work_offset: 0.0,
                    slide_reference,
                    gap,
                    lift: 0.0,
                    tangential_sign: 0.0,
                    predicted_sign: 0.0,
                    successor,
                },
            );
            self.dormant.remove(k);
            // A new section changes the tips: refit when next needed.
            fitted = None;
        }
        Ok(())
    }
}

/// How far ahead [`Plant::place`] orders sections.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Lookahead {
    /// Within `ORDER_LEAD × update_distance` of the material (every tick).
    Lead,
    /// Every path that meets the object (at construction, for the planned
    /// direction).
    Everywhere,
}

/// Where a dormant segment's midpoint path enters the material.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum EntryKind {
    /// Through the intact surface: a fresh section (no crack) through the
    /// entry point, taken just before the midpoint gets there.
    Intact,
    /// Through a side face below the top, a surface the knife has already
    /// cut, or with the midpoint already in the material: a section through
    /// the crack front's crossing of the path, taken when the midpoint is
    /// in the material and takes over the cut there.
    BehindFront,
}

impl EntryKind {
    /// How far (in update distances) the predicted plane may move before
    /// the order is renewed. An intact entry's section is fixed until its
    /// edge starts cutting, so it is placed to a tenth of the update
    /// distance; a section behind the front follows its segment at once
    /// (re-chosen after one update distance of slide), so its first plane
    /// need be no closer than that.
    fn reorder_tolerance(self) -> f64 {
        match self {
            Self::Intact => 0.1,
            Self::BehindFront => 1.0,
        }
    }
}

/// The order a dormant segment placed with the worker.
#[derive(Debug, Clone, Copy, PartialEq)]
struct EntryOrder {
    /// The point the section's plane passes through (knife plane (z, y)).
    q: Vector2<f64>,
    /// How the path enters the material there.
    kind: EntryKind,
}

/// A segment without a section yet.
#[derive(Debug, Clone, Copy, PartialEq)]
struct DormantSegment {
    /// Its index in the edge's grid (the worker's slot).
    slot: usize,
    /// The last order placed for it (pending with the worker, or taken and
    /// found without material).
    order: Option<EntryOrder>,
}

/// How far ahead of the material (in update distances, along the direction
/// of motion) a dormant segment orders its first section from the worker.
const ORDER_LEAD: f64 = 2.0;

/// How close to an intact surface (in update distances, along the direction
/// of motion) a dormant segment's midpoint takes its first section.
const TAKE_LEAD: f64 = 0.25;

/// Depth below the surface (in update distances) from which the crack
/// interpolated between the started sections' tips counts as having cut
/// the surface. It exceeds the sag of the chord between neighbouring tips
/// on a curved top (0.06 mm for 4.5 mm segments on a 45 mm radius), so an
/// intact curved surface is not taken for a cut one.
const SURFACE_CUT: f64 = 0.25;

/// Whether the surface point `point` (on the silhouette's top) has been cut:
/// the crack interpolated linearly between the started sections' tips
/// (`tips`, any order) bracketing its z, or the nearest tip's within
/// `margin` beyond the outermost, lies more than `depth` below it.
fn surface_is_cut(tips: &[Vector2<f64>], point: Vector2<f64>, margin: f64, depth: f64) -> bool {
    let (mut below, mut above): (Option<Vector2<f64>>, Option<Vector2<f64>>) = (None, None);
    for t in tips {
        if t.x <= point.x && below.is_none_or(|b| t.x > b.x) {
            below = Some(*t);
        }
        if t.x >= point.x && above.is_none_or(|a| t.x < a.x) {
            above = Some(*t);
        }
    }
    let crack = match (below, above) {
        (Some(b), Some(a)) if a.x > b.x => b.y + (point.x - b.x) / (a.x - b.x) * (a.y - b.y),
        (Some(b), Some(_)) => b.y,
        (Some(b), None) if point.x - b.x <= margin => b.y,
        (None, Some(a)) if a.x - point.x <= margin => a.y,
        _ => return false,
    };
    crack < point.y - depth
}

/// The crack front over the tips of the active started sections (`tips` is
/// the preallocated buffer). Allocates nothing.
fn fit_front(sections: &[SegmentSection], tips: &mut Vec<Vector2<f64>>) -> Option<CrackFront> {
    tips.clear();
    for s in sections {
        if s.active && started(s) {
            tips.push(tip_of(s));
        }
    }
    CrackFront::fit(tips)
}

/// The started active section nearest along the edge to slot `slot`.
fn nearest_started(sections: &[SegmentSection], slot: usize) -> Option<&CrossSection> {
    nearest_started_of(sections.iter(), slot)
}

/// The started active section of `sections` nearest along the edge to slot
/// `slot`.
fn nearest_started_of<'a>(
    sections: impl Iterator<Item = &'a SegmentSection>,
    slot: usize,
) -> Option<&'a CrossSection> {
    sections
        .filter(|s| s.active && started(s))
        .min_by_key(|s| s.slot.abs_diff(slot))
        .map(|s| &*s.section)
}

/// Whether a section has started cutting (its edge reached the material).
fn started(s: &SegmentSection) -> bool {
    s.section.state().knife_displacement > 0.0
}

/// Whether a section's plane follows its segment: it has started cutting or
/// took over a cut.
fn tracked(s: &SegmentSection) -> bool {
    s.successor || started(s)
}

/// How far the segment's midpoint slid off the section's plane since it was
/// chosen (signed, along the plane's normal), m.
fn slide_of(s: &SegmentSection, position: &Vector3<f64>) -> f64 {
    signed_offset(&s.plane, &midpoint_world(position, &s.segment)) - s.slide_reference
}

/// Whether to order a successor for `s` (slid `slide` off its plane, moving
/// off it at `rate` per unit travel): none is pending, or the pending one
/// was foreseen on the other side of the plane, which the midpoint has
/// crossed back over and is moving away from (the motion reversed). Never
/// while moving within the plane (`rate` = 0).
fn foresee(s: &SegmentSection, slide: f64, rate: f64, pending: bool) -> bool {
    rate != 0.0
        && (!pending || (s.predicted_sign * slide < 0.0 && rate.signum() != s.predicted_sign))
}

/// Rate at which the segment's midpoint leaves its section's plane per unit
/// travel along the direction of motion `u` (signed along the plane's
/// normal); 0 below 1e-9 (moving within the plane).
fn approach_rate(s: &SegmentSection, u: &Vector2<f64>) -> f64 {
    let n = s.plane.normal();
    let rate = u.dot(&Vector2::new(n.z, n.y));
    if rate.abs() < 1e-9 { 0.0 } else { rate }
}

/// The worker's job for a successor of `s` on `plane`.
fn job(s: &SegmentSection, plane: SectionPlane) -> SuccessorJob {
    SuccessorJob {
        plane,
        current: s.active.then(|| Arc::clone(&s.geometry)),
    }
}

/// The plane normal to `segment` through q, where the line through `m`
/// (knife plane) along the direction of motion `u` meets the crack front
/// nearest to `m`; if it misses (or meets the front's extrapolation farther
/// than `size` away), q is at the height of the section's own `tip` on that
/// line (at `m` for a motion without vertical component).
fn plane_on_path(
    front: &CrackFront,
    m: Vector2<f64>,
    u: Vector2<f64>,
    tip: Vector2<f64>,
    segment: &EdgeSegment,
    size: f64,
) -> SectionPlane {
    let lambda = front
        .intersect_nearest(m, u)
        .filter(|l| l.abs() <= size)
        .unwrap_or_else(|| {
            if u.y.abs() > 1e-12 {
                (tip.y - m.y) / u.y
            } else {
                0.0
            }
        });
    let q = m + u * lambda;
    let up = -Vector3::new(0.0, segment.normal.y, segment.normal.x);
    SectionPlane::normal_to_segment(Vector3::new(0.0, q.y, q.x), up)
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
