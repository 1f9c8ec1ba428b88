//! The whole-knife, whole-object plant, stepped like a robot arm's servo loop.

mod placement;
mod rechoice;
mod segment_section;

use std::sync::Arc;

use nalgebra::{Vector2, Vector3};

use shearcut_sim::geometry::{Polygon, SectionPlane, TriangleMesh};
use shearcut_sim::invalid_setting::InvalidSetting;
use shearcut_sim::knife::Knife;
use shearcut_sim::section::{SectionError, SectionStep};

use super::crack_front::CrackFront;
use super::ft_sensor::FtSensor;
use super::successor::{SectionFactory, SuccessorWorker};
use super::tick_list::TickList;
use super::wrench::{SegmentLoad, wrench_at};
use shearcut_sim::arm::{ArmLimitMonitor, ArmReading, ArmStatus, KnifeCommand};
use shearcut_sim::knife_plane::contact_arc::{
    EdgeSegment, contact_arc, knife_plane_silhouette, ray_hit, segment_grid, span_arc,
};

use crate::plant_step::{PlantStep, PlantTruth};
use crate::successor_policy::SuccessorPolicy;
use placement::{DormantSegment, Lookahead};
use segment_section::{SegmentSection, tip_of};

use crate::section_stepper::{Advance, SectionStepper, advance_counted};

pub use crate::plant_error::PlantError;
pub use crate::plant_settings::{MAX_SEGMENTS, PlantSettings};
pub use crate::plant_spec::PlantSpec;

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
/// takes several 1 kHz servo ticks (docs/benchmarks.md, "Section
/// construction"). So the plant foresees each
/// successor: as soon as a section has started cutting or been re-chosen
/// (the tick after), q is taken where the midpoint will be when its slide
/// reaches the threshold on the side it is moving to (moving on along the
/// direction of motion), with the front fitted then, and a worker thread
/// cuts and builds the successor for that plane: the worker has a whole
/// update distance of travel to finish it. At the
/// re-choice the plant takes it (waiting only if the worker is late, or,
/// under [`SuccessorPolicy::KeepCurrent`], on the first tick after the
/// worker finished it: [`Plant::successor_deferrals`]); the
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
/// in (and frees superseded ones). A clone's ticks allocate nothing either
/// (its lists keep their capacity: `tick_list`).
///
/// [`CrossSection`]: shearcut_sim::section::CrossSection
/// [`CrossSection::take_over`]: shearcut_sim::section::CrossSection::take_over
#[derive(Debug, Clone)]
pub struct Plant {
    sections: TickList<SegmentSection>,
    /// Threads that advance the sections within a tick.
    stepper: SectionStepper,
    /// Whether the re-choices and placements after the last step are done
    /// ([`Plant::settle`]).
    settled: bool,
    /// Per section (the index into `sections`): its normal and tangential
    /// travel this tick, m, if it advances. Preallocated.
    travel: Vec<Option<(f64, f64)>>,
    /// Per section: the outcome of its advance this tick. Preallocated.
    advanced: Vec<Option<Result<SectionStep, SectionError>>>,
    /// The sections dealt to the stepping threads this tick, in dealing
    /// order. Preallocated.
    dealing: TickList<usize>,
    /// The object, material, blade and section settings, shared with the
    /// worker that builds successor sections.
    factory: Arc<SectionFactory>,
    /// Prepares successor sections ahead of their re-choices.
    worker: SuccessorWorker,
    /// Whether a tick waits for a successor the worker has not finished.
    policy: SuccessorPolicy,
    /// Successors due but not finished, skipped by a tick (see
    /// [`Plant::successor_deferrals`]).
    deferrals: usize,
    /// Whether the knife has moved since construction (the worker holds
    /// the first orders until it has: [`Plant::new`]).
    moved: bool,
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
    tips: TickList<Vector2<f64>>,
    /// The last crack front fitted for a re-choice.
    front: Option<CrackFront>,
    rechoices: usize,
    rebuilds: usize,
    unforeseen: usize,
    first_contacts: usize,
    wakes: usize,
    loads: TickList<SegmentLoad>,
    monitor: ArmLimitMonitor,
    sensor: FtSensor,
    sensor_offset: Vector3<f64>,
    position: Vector3<f64>,
    time: f64,
    work: f64,
}

impl Plant {
    /// Builds the plant from `spec` (where the knife starts, the first
    /// sections for its planned direction: [`PlantSpec`]); `seed` seeds the
    /// F/T sensor's noise.
    ///
    /// # Errors
    /// A setting is out of range, no edge point's path along the planned
    /// direction meets the object, or a first section cannot be built.
    pub fn new(spec: PlantSpec<'_>, seed: u64) -> Result<Self, PlantError> {
        let PlantSpec {
            material,
            knife,
            object,
            settings,
            section,
            arm_limits,
            ..
        } = spec;
        let EdgeLayout {
            direction: d,
            silhouette,
            origin,
            grid,
            top,
        } = EdgeLayout::new(&spec)?;
        let factory = Arc::new(SectionFactory {
            object: object.clone(),
            material: *material,
            blade: *knife.blade(),
            settings: *section,
            rim_fraction: settings.rim_fraction,
        });
        let worker = SuccessorWorker::new(Arc::clone(&factory), grid.len(), settings.workers);
        let mut plant = Self {
            stepper: SectionStepper::new(settings.stepping_threads, grid.len()),
            settled: true,
            travel: vec![None; grid.len()],
            advanced: vec![None; grid.len()],
            dealing: TickList::with_capacity(grid.len()),
            loads: TickList::with_capacity(grid.len()),
            tips: TickList::with_capacity(grid.len()),
            sections: TickList::with_capacity(grid.len()),
            dormant: grid
                .iter()
                .enumerate()
                .map(|(slot, _)| DormantSegment::new(slot))
                .collect(),
            edge_segments: grid,
            worker,
            policy: SuccessorPolicy::Wait,
            deferrals: 0,
            moved: false,
            factory,
            update_distance: settings.update_distance,
            motion: d,
            top,
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
        // Order the first sections for the planned direction and place
        // those whose midpoints are already at the surface. The orders are
        // held until the knife first moves (a start along another direction
        // renews them before anything is built) or a real-time loop asks
        // for them to be built now (`build_ordered_sections`).
        let section_error = |(index, source)| PlantError::Section { index, source };
        plant.worker.hold();
        plant.place(Lookahead::Everywhere).map_err(section_error)?;
        plant.place(Lookahead::Lead).map_err(section_error)?;
        Ok(plant)
    }

    /// Checks what [`Plant::new`] checks before it builds a section: every
    /// setting in range, the planned direction pointing down, the edge
    /// meeting the object, and the segment grid within [`MAX_SEGMENTS`].
    /// Cheap (no section is built): `shearcut check` asks it of a scenario
    /// so that a run refusing it is refused before the run.
    ///
    /// # Errors
    /// Those of [`Plant::new`] but a first section's.
    pub fn check(spec: PlantSpec<'_>) -> Result<(), PlantError> {
        EdgeLayout::new(&spec).map(|_| ())
    }

    /// The direction of motion at slice-push ratio `xi` in the knife plane
    /// (z, y), the `direction` [`Plant::new`] takes: unit, pointing down,
    /// at α = atan ξ from the vertical towards the tip.
    pub fn direction_at(xi: f64) -> Vector2<f64> {
        let alpha = xi.atan();
        Vector2::new(alpha.sin(), -alpha.cos())
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
            .filter(|s| s.active && s.section().state().knife_displacement > 0.0)
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
    ///
    /// [`CrossSection`]: shearcut_sim::section::CrossSection
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

    /// Threads that advance the sections within a tick, this plant's
    /// stepping thread included ([`PlantSettings::stepping_threads`]).
    pub fn stepping_threads(&self) -> usize {
        self.stepper.threads()
    }

    /// Starts the plant's section-stepping helper threads anew from the
    /// calling thread, as many, so that they run under its scheduling (a
    /// thread inherits its creator's): call it from the thread that steps,
    /// after raising that thread's priority. Results do not change.
    pub fn restart_stepping_threads(&mut self) {
        self.stepper = SectionStepper::new(self.stepper.threads(), self.edge_segments.len());
    }

    /// Sets what a tick does with a successor the worker has not finished
    /// when it is due ([`SuccessorPolicy::Wait`] unless set).
    pub fn set_successor_policy(&mut self, policy: SuccessorPolicy) {
        self.policy = policy;
    }

    /// Builds the sections ordered so far now, waiting for the worker: the
    /// first sections [`Plant::new`] ordered for the planned direction,
    /// which are otherwise built once the knife first moves (a start along
    /// another direction renews those orders before anything is built). A
    /// real-time loop calls it before its first tick, so that a knife
    /// moving along the planned direction finds them ready. Results do not
    /// change.
    pub fn build_ordered_sections(&mut self) {
        self.worker.wait_idle();
    }

    /// What a tick does with a successor the worker has not finished.
    pub fn successor_policy(&self) -> SuccessorPolicy {
        self.policy
    }

    /// Number of times a tick found a due successor not finished and, under
    /// [`SuccessorPolicy::KeepCurrent`], went on without it: one per
    /// segment per tick (a re-choice left to a later tick, its section
    /// stepped on its plane; a first section not taken, that strip of the
    /// edge cutting nothing). Always 0 under [`SuccessorPolicy::Wait`]. A
    /// diagnostic of the machine's load like [`Plant::successor_waits`],
    /// but here the plant's results depend on it.
    pub fn successor_deferrals(&self) -> usize {
        self.deferrals
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
    ///
    /// [`CrossSection::solves`]: shearcut_sim::section::CrossSection::solves
    pub fn section_solves(&self) -> u64 {
        self.sections.iter().map(|s| s.section().solves()).sum()
    }

    /// The sections' current states, heel to tip.
    pub fn section_states(&self) -> impl Iterator<Item = &shearcut_sim::section::SectionStep> {
        self.sections.iter().map(|s| s.section().state())
    }

    /// Advances every section with a travel this tick (`travel`), on the
    /// stepper's helper threads and this one; the outcomes land in
    /// `advanced`. With helpers, every section is queued for them, costliest
    /// first by its last advance's condensed-line solves, and this thread
    /// takes back and advances queued sections until none is left: a helper
    /// that wakes late, or a section that costs more than its neighbours,
    /// leaves the other thread the rest (dynamic sharing). Each section's
    /// arithmetic is the same on any thread: the results do not depend on
    /// the threads or on the order. Allocates nothing.
    fn advance_sections(&mut self) {
        let helpers = self.stepper.threads() - 1;
        if helpers > 0 {
            self.dealing.clear();
            self.dealing
                .extend((0..self.sections.len()).filter(|&i| self.travel[i].is_some()));
            // Each helper takes from the end of its queue: the costliest
            // last in the list. (An unstable sort allocates nothing.)
            let sections = &self.sections;
            self.dealing
                .sort_unstable_by_key(|&i| (sections[i].solves_last_advance, i));
            for (n, &i) in self.dealing.iter().enumerate() {
                if let (Some((normal, tangential)), Some(section)) =
                    (self.travel[i], self.sections[i].lend())
                {
                    self.stepper.send(
                        n % helpers,
                        Advance {
                            index: i,
                            section,
                            normal,
                            tangential,
                        },
                    );
                    self.travel[i] = None;
                }
            }
        }
        for i in 0..self.sections.len() {
            self.advanced[i] = None;
            if let Some((normal, tangential)) = self.travel[i] {
                let s = &mut self.sections[i];
                let (step, solves) = advance_counted(s.section_mut(), normal, tangential);
                self.advanced[i] = Some(step);
                s.solves_last_advance = solves;
            }
        }
        let (sections, advanced) = (&mut self.sections, &mut self.advanced);
        while let Some(mut job) = self.stepper.take_back() {
            let (step, solves) = advance_counted(&mut job.section, job.normal, job.tangential);
            advanced[job.index] = Some(step);
            let s = &mut sections[job.index];
            s.solves_last_advance = solves;
            s.put_back(job.section);
        }
        self.stepper.receive_all(|a| {
            sections[a.index].solves_last_advance = a.solves;
            sections[a.index].put_back(a.section);
            advanced[a.index] = Some(a.step);
        });
    }

    /// Re-chooses the sections that slid `update_distance` off their planes
    /// and orders the next successors (see the type's docs), after a
    /// [`Self::step_measured`]; does nothing if that is done. Allocates
    /// nothing.
    ///
    /// # Errors
    /// A re-chosen section cannot be built.
    pub fn settle(&mut self) -> Result<(), SectionError> {
        if !self.settled {
            self.rechoose()?;
            self.place(Lookahead::Lead).map_err(|(_, e)| e)?;
            self.settled = true;
            if self.moved {
                // The orders now follow the knife's own direction.
                self.worker.release();
            }
        }
        Ok(())
    }

    /// Executes `command` for `dt` seconds and returns the measurement.
    /// A command that breaks an arm limit is refused: the knife holds still
    /// and the status says why. After the sections advance, those that slid
    /// `update_distance` off their planes are re-chosen, and the next
    /// successors are ordered from the worker (see the type's docs): that
    /// is [`Self::step_measured`] followed by [`Self::settle`].
    /// Allocates nothing.
    ///
    /// # Errors
    /// A section's step fails, or a re-chosen section cannot be built.
    pub fn step(&mut self, command: &KnifeCommand, dt: f64) -> Result<PlantStep, SectionError> {
        let measured = self.step_measured(command, dt)?;
        self.settle()?;
        Ok(measured)
    }

    /// [`Self::step`] up to its measurement: the re-choices and placements
    /// that follow it wait for [`Self::settle`], which the next step calls
    /// first if nobody did. The measurement does not depend on them, so a
    /// realtime plant answers with it at once and settles in the time left
    /// before its next tick; results are bit-identical to [`Self::step`]'s.
    /// Allocates nothing.
    ///
    /// # Errors
    /// As [`Self::step`].
    pub fn step_measured(
        &mut self,
        command: &KnifeCommand,
        dt: f64,
    ) -> Result<PlantStep, SectionError> {
        self.settle()?;
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
            self.moved = true;
        }
        self.loads.clear();
        let mut contact_length = 0.0;
        let mut fractured = 0;
        let mut tip_height_sum = 0.0;
        let mut deformation: f64 = 0.0;
        let mut work = 0.0;
        let mut active = 0usize;
        // Each active segment's travel into its section: the gap to the
        // surface first, then any lift, then the section.
        for (i, s) in self.sections.iter_mut().enumerate() {
            self.travel[i] = None;
            if !s.active {
                continue;
            }
            let dn = dp2.dot(&s.segment.normal);
            let dt_seg = dp2.dot(&s.segment.tangent);
            if dt_seg != 0.0 {
                s.tangential_sign = dt_seg.signum();
            }
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
            if advance > 0.0 {
                self.travel[i] = Some((advance, dt_seg * advance / dn));
            }
        }
        self.advance_sections();
        for (i, s) in self.sections.iter_mut().enumerate() {
            if !s.active {
                // No material under the segment: no force, not advanced.
                let state = s.section().state();
                work += (s.work_offset + state.work.knife) * s.segment.length;
                if state.fractured {
                    fractured += 1;
                }
                continue;
            }
            active += 1;
            let state = match self.advanced[i].take() {
                Some(step) => step?,
                None => *s.section().state(),
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
        self.settled = false;
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
}

/// Where the plant's edge meets its object, before any section is built:
/// the checked settings' geometry ([`Plant::new`], [`Plant::check`]).
struct EdgeLayout {
    /// The planned direction of motion, unit, pointing down.
    direction: Vector2<f64>,
    /// The object's silhouette in the knife plane (z, y), m.
    silhouette: Polygon,
    /// The knife frame's origin at the start, knife plane (z, y), m.
    origin: Vector2<f64>,
    /// The edge's segments, heel to tip.
    grid: Vec<EdgeSegment>,
    /// The object's top in the knife plane, m.
    top: f64,
}

impl EdgeLayout {
    /// Checks the settings and the planned direction, and lays the edge's
    /// segments over the object.
    fn new(spec: &PlantSpec<'_>) -> Result<Self, PlantError> {
        let &PlantSpec {
            material,
            knife,
            object,
            z0,
            direction,
            settings,
            section,
            arm_limits,
        } = spec;
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
        let start = Plant::start_position(knife, object, z0, settings.start_gap);
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
        // At least one segment's path along the planned direction meets
        // the object.
        if !grid
            .iter()
            .any(|s| ray_hit(&silhouette, origin + s.midpoint, d).is_some())
        {
            return Err(PlantError::NoContact);
        }
        FtSensor::new(settings.sensor, 0).map_err(|e| e.prefixed("sensor"))?;
        Ok(Self {
            direction: d,
            silhouette,
            origin,
            grid,
            top: hi.y,
        })
    }
}
