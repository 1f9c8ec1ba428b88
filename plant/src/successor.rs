//! Cross sections prepared ahead of time on worker threads, so that a
//! re-choice (seed 000 §IV, Fig. 4(b)) or a segment's first contact never
//! meshes, factorises or condenses a section inside
//! [`Plant::step`](super::Plant::step).
//!
//! The plant submits a [`SuccessorJob`] (a segment's predicted plane) as soon
//! as the segment's section has started cutting or been re-chosen (or its
//! midpoint nears the material), and takes the result when it is due,
//! blocking only if no worker has finished it yet. A result is a pure function of its job (the plane, the
//! current shape and the plant's fixed object, material, blade and settings),
//! so what the plant does is independent of thread timing: two runs with the
//! same seed are bit-identical however the worker is scheduled.
//!
//! The hand-off uses a mutex and two condition variables over per-segment
//! slots, preallocated at construction: submitting and taking allocate
//! nothing on the plant's thread (the worker allocates the new section, and
//! dropping a superseded one only frees).

use std::sync::{Arc, Condvar, Mutex, MutexGuard};
use std::thread::JoinHandle;

use shearcut_sim::blade::BladeSection;
use shearcut_sim::geometry::{SectionPlane, TriangleMesh};
use shearcut_sim::material::Material;
use shearcut_sim::section::{CrossSection, SectionError, SectionGeometry, SectionSettings};

use shearcut_sim::knife_plane::section_shape::section_geometry;

/// What the plant needs to cut sections: fixed at construction.
#[derive(Debug, Clone)]
pub(crate) struct SectionFactory {
    /// The object, cut by the planes.
    pub object: TriangleMesh,
    /// The material of every section.
    pub material: Material,
    /// The blade's cross section.
    pub blade: BladeSection,
    /// Mesh and solver settings of every section.
    pub settings: SectionSettings,
    /// Rim height below which a dome-shaped section is clipped, as a fraction
    /// of the section's height.
    pub rim_fraction: f64,
}

impl SectionFactory {
    /// The successor for `plane`: no material, the current shape again, or a
    /// new section: the work a re-choice would otherwise do inside the tick.
    pub fn prepare(&self, plane: &SectionPlane, current: Option<&SectionGeometry>) -> Preparation {
        let Some(polygon) = plane.section(&self.object) else {
            return Preparation::NoMaterial;
        };
        let height = polygon.bounds().1.y;
        let Ok(geometry) = section_geometry(&polygon, self.rim_fraction * height) else {
            // Lower than the rim everywhere: no material worth a section.
            return Preparation::NoMaterial;
        };
        if geometry.half_width() <= self.blade.edge_width {
            // A sliver grazed at the object's flank, no wider across the cut
            // than twice the edge flat: the flat covers it, no mesh resolves
            // it, and its material is negligible. Like a section lower than
            // the rim, no material worth a section.
            return Preparation::NoMaterial;
        }
        if current.is_some_and(|c| same_geometry(&geometry, c)) {
            return Preparation::SameShape;
        }
        match CrossSection::new(&geometry, &self.material, &self.blade, &self.settings) {
            Ok(section) => Preparation::New {
                geometry: Arc::new(geometry),
                section: Box::new(section),
            },
            Err(e) => Preparation::Failed(e),
        }
    }
}

/// A successor the worker prepared.
#[derive(Debug)]
pub(crate) enum Preparation {
    /// The plane misses the object, or its section is lower than the rim or
    /// no wider than twice the knife's edge flat (a sliver at the flank).
    NoMaterial,
    /// The plane cuts the same shape as the current section (a prism's
    /// interior): only the plane moves.
    SameShape,
    /// A new section for a new shape, built, factorised and condensed.
    New {
        /// Its shape.
        geometry: Arc<SectionGeometry>,
        /// The section, in its initial state.
        section: Box<CrossSection>,
    },
    /// The section could not be built.
    Failed(SectionError),
    /// Building it panicked on the worker (a bug): [`SuccessorWorker::take`]
    /// resumes the panic on the plant's thread instead of waiting forever.
    Panicked(Box<dyn std::any::Any + Send>),
}

/// A request for a segment's successor.
#[derive(Debug, Clone)]
pub(crate) struct SuccessorJob {
    /// Plane of the successor.
    pub plane: SectionPlane,
    /// The current section's shape, if it is active (to tell a same shape).
    pub current: Option<Arc<SectionGeometry>>,
}

#[derive(Debug, Default)]
struct Slot {
    /// Generation of the job last submitted for this segment (0: none).
    wanted: u64,
    /// The job not yet taken by the worker.
    job: Option<(u64, SuccessorJob)>,
    /// The finished result for generation `.0`.
    result: Option<(u64, Preparation)>,
}

#[derive(Debug)]
struct Slots {
    slots: Vec<Slot>,
    shutdown: bool,
    /// Whether the workers leave the submitted jobs alone (see
    /// [`SuccessorWorker::hold`]).
    held: bool,
    /// Sections built for a job that was superseded or cancelled before its
    /// result was taken (see [`SuccessorWorker::wasted_builds`]).
    wasted: usize,
}

/// Whether `result` holds a section the worker built (not a shape it only
/// cut and found empty or the same).
fn built(result: &Option<(u64, Preparation)>) -> bool {
    matches!(result, Some((_, Preparation::New { .. })))
}

#[derive(Debug)]
struct Shared {
    slots: Mutex<Slots>,
    /// Signalled when a job is submitted or at shutdown.
    job_ready: Condvar,
    /// Signalled when a result is stored.
    result_ready: Condvar,
}

impl Shared {
    fn lock(&self) -> MutexGuard<'_, Slots> {
        // A panic on the worker while holding the lock leaves consistent
        // slots (results are stored whole): keep going.
        self.slots.lock().unwrap_or_else(|e| e.into_inner())
    }
}

/// The worker thread preparing successor sections, one slot per segment.
pub(crate) struct SuccessorWorker {
    shared: Arc<Shared>,
    factory: Arc<SectionFactory>,
    /// The worker threads (none only if the OS refused to start any).
    handles: Vec<JoinHandle<()>>,
    next_generation: u64,
    /// The jobs submitted and not yet taken, per segment (kept to clone the
    /// worker with the same pending work).
    pending: Vec<Option<(u64, SuccessorJob)>>,
    /// Results that were not ready when taken (diagnostic, timing-dependent).
    waits: usize,
    /// The workers' hold, as last set from this side (read without the
    /// lock).
    held: bool,
}

impl std::fmt::Debug for SuccessorWorker {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("SuccessorWorker")
            .field("segments", &self.pending.len())
            .field("next_generation", &self.next_generation)
            .finish_non_exhaustive()
    }
}

impl SuccessorWorker {
    /// Starts `threads` worker threads (at least one) for `segments`
    /// segments. Each takes the oldest job not yet taken, so several build
    /// at once; what is built is still a function of the jobs alone.
    pub fn new(factory: Arc<SectionFactory>, segments: usize, threads: usize) -> Self {
        let shared = Arc::new(Shared {
            slots: Mutex::new(Slots {
                slots: (0..segments).map(|_| Slot::default()).collect(),
                shutdown: false,
                held: false,
                wasted: 0,
            }),
            job_ready: Condvar::new(),
            result_ready: Condvar::new(),
        });
        let handles = (0..threads.max(1))
            .filter_map(|i| {
                let shared = Arc::clone(&shared);
                let factory = Arc::clone(&factory);
                std::thread::Builder::new()
                    .name(format!("successor-sections-{i}"))
                    .spawn(move || run(&shared, &factory))
                    .ok()
            })
            .collect();
        Self {
            shared,
            factory,
            handles,
            next_generation: 1,
            pending: (0..segments).map(|_| None).collect(),
            waits: 0,
            held: false,
        }
    }

    /// Keeps the workers from starting the jobs submitted from now on until
    /// [`Self::release`] (or a [`Self::take`] or [`Self::wait_idle`], which
    /// release first): orders placed before their plane is certain are
    /// renewed for free instead of built and dropped. Results do not
    /// change: a result is a function of its job alone.
    pub fn hold(&mut self) {
        self.held = true;
        self.shared.lock().held = true;
    }

    /// Lets the workers start the held jobs (oldest first). Without a hold
    /// it only reads a flag: allocates nothing and takes no lock.
    pub fn release(&mut self) {
        if !self.held {
            return;
        }
        self.held = false;
        self.shared.lock().held = false;
        self.shared.job_ready.notify_all();
    }

    /// Whether a job for segment `index` is pending.
    pub fn is_pending(&self, index: usize) -> bool {
        self.pending[index].is_some()
    }

    /// Whether [`Self::take`] of segment `index` would return without
    /// waiting: its pending job is finished, or there is none (`take`
    /// returns `None`), or there is no worker thread (`take` prepares it
    /// itself). Never blocks: a worker holding the slots' lock at that
    /// moment counts as not finished, and so does a held job. Allocates
    /// nothing.
    pub fn is_ready(&self, index: usize) -> bool {
        let Some((generation, _)) = &self.pending[index] else {
            return true;
        };
        if self.handles.is_empty() {
            return true;
        }
        if self.held {
            return false;
        }
        let slots = match self.shared.slots.try_lock() {
            Ok(slots) => slots,
            Err(std::sync::TryLockError::Poisoned(e)) => e.into_inner(),
            Err(std::sync::TryLockError::WouldBlock) => return false,
        };
        slots.slots[index]
            .result
            .as_ref()
            .is_some_and(|(g, _)| g == generation)
    }

    /// Number of results that were not ready when taken.
    pub fn waits(&self) -> usize {
        self.waits
    }

    /// Number of sections built for jobs that were superseded or cancelled
    /// before their results were taken: CPU spent on nothing. Like
    /// [`Self::waits`] it depends on thread timing (a job superseded before
    /// a worker started it costs nothing); results pending when the plant
    /// is dropped are not counted. Locks the slots.
    pub fn wasted_builds(&self) -> usize {
        self.shared.lock().wasted
    }

    /// Submits `job` for segment `index`, superseding any pending one.
    /// Allocates nothing.
    pub fn submit(&mut self, index: usize, job: SuccessorJob) {
        let generation = self.next_generation;
        self.next_generation += 1;
        self.pending[index] = Some((generation, job.clone()));
        if self.handles.is_empty() {
            return;
        }
        let mut slots = self.shared.lock();
        let slot = &mut slots.slots[index];
        slot.wanted = generation;
        slot.job = Some((generation, job));
        // A superseded result is dropped here (frees only).
        let wasted = built(&slot.result);
        slot.result = None;
        slots.wasted += usize::from(wasted);
        drop(slots);
        self.shared.job_ready.notify_one();
    }

    /// Drops the pending job of segment `index`, if any.
    pub fn cancel(&mut self, index: usize) {
        if self.pending[index].take().is_none() || self.handles.is_empty() {
            return;
        }
        let mut slots = self.shared.lock();
        let slot = &mut slots.slots[index];
        slot.wanted = 0;
        slot.job = None;
        let wasted = built(&slot.result);
        slot.result = None;
        slots.wasted += usize::from(wasted);
    }

    /// Waits until the worker has finished every pending job (their results
    /// wait in their slots for [`SuccessorWorker::take`]), releasing a
    /// [`Self::hold`] first.
    pub fn wait_idle(&mut self) {
        if self.handles.is_empty() {
            return;
        }
        self.release();
        let mut slots = self.shared.lock();
        loop {
            let busy = self.pending.iter().zip(&slots.slots).any(|(p, s)| {
                p.as_ref()
                    .is_some_and(|(g, _)| s.result.as_ref().is_none_or(|(r, _)| r != g))
            });
            if !busy {
                return;
            }
            slots = self
                .shared
                .result_ready
                .wait(slots)
                .unwrap_or_else(|e| e.into_inner());
        }
    }

    /// Takes the result of segment `index`'s pending job, waiting for the
    /// worker if it is not ready (releasing a [`Self::hold`] first); `None`
    /// without a pending job. Allocates nothing. (Without a worker thread,
    /// which only happens when the OS refused to start one, the job is
    /// prepared here.)
    pub fn take(&mut self, index: usize) -> Option<(SectionPlane, Preparation)> {
        let (generation, job) = self.pending[index].take()?;
        if self.handles.is_empty() {
            let p = self.factory.prepare(&job.plane, job.current.as_deref());
            return Some((job.plane, p));
        }
        self.release();
        let mut slots = self.shared.lock();
        let mut waited = false;
        loop {
            let slot = &mut slots.slots[index];
            if slot.result.as_ref().is_some_and(|(g, _)| *g == generation) {
                let (_, p) = slot.result.take()?;
                slot.wanted = 0;
                if waited {
                    self.waits += 1;
                }
                if let Preparation::Panicked(payload) = p {
                    drop(slots);
                    std::panic::resume_unwind(payload);
                }
                return Some((job.plane, p));
            }
            waited = true;
            slots = self
                .shared
                .result_ready
                .wait(slots)
                .unwrap_or_else(|e| e.into_inner());
        }
    }
}

impl Clone for SuccessorWorker {
    /// A new worker with the same pending jobs and hold: their results are
    /// functions of the jobs, so the clone adopts the same successors.
    fn clone(&self) -> Self {
        let mut w = Self::new(
            Arc::clone(&self.factory),
            self.pending.len(),
            self.handles.len(),
        );
        if self.held {
            w.hold();
        }
        let mut jobs: Vec<_> = self
            .pending
            .iter()
            .enumerate()
            .filter_map(|(i, p)| p.as_ref().map(|(g, j)| (*g, i, j.clone())))
            .collect();
        jobs.sort_by_key(|(g, _, _)| *g);
        for (_, i, j) in jobs {
            w.submit(i, j);
        }
        w.waits = self.waits;
        w.shared.lock().wasted = self.wasted_builds();
        w
    }
}

impl Drop for SuccessorWorker {
    fn drop(&mut self) {
        self.shared.lock().shutdown = true;
        self.shared.job_ready.notify_all();
        for h in self.handles.drain(..) {
            let _ = h.join();
        }
    }
}

/// The worker's loop: the oldest submitted job first; none while held.
fn run(shared: &Shared, factory: &SectionFactory) {
    let mut slots = shared.lock();
    loop {
        if slots.shutdown {
            return;
        }
        let next = if slots.held {
            None
        } else {
            slots
                .slots
                .iter()
                .enumerate()
                .filter_map(|(i, s)| s.job.as_ref().map(|(g, _)| (*g, i)))
                .min()
        };
        let Some((_, index)) = next else {
            slots = shared
                .job_ready
                .wait(slots)
                .unwrap_or_else(|e| e.into_inner());
            continue;
        };
        let Some((generation, job)) = slots.slots[index].job.take() else {
            continue;
        };
        drop(slots);
        let prepared = std::panic::catch_unwind(std::panic::AssertUnwindSafe(|| {
            factory.prepare(&job.plane, job.current.as_deref())
        }))
        .unwrap_or_else(Preparation::Panicked);
        slots = shared.lock();
        let slot = &mut slots.slots[index];
        if slot.wanted == generation {
            slot.result = Some((generation, prepared));
            shared.result_ready.notify_all();
        } else if matches!(prepared, Preparation::New { .. }) {
            // Superseded or cancelled while it was being built.
            slots.wasted += 1;
        }
    }
}

/// Whether two section shapes agree to a relative 1e-9 of their size (the
/// plane cuts of a prism's interior differ by rounding only).
pub(crate) fn same_geometry(a: &SectionGeometry, b: &SectionGeometry) -> bool {
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

#[cfg(test)]
mod tests {
    use nalgebra::Vector3;

    use super::*;
    use shearcut_sim::material::MaterialPreset;

    /// A worker over a 30 × 20 × 30 mm potato cuboid (coarse sections).
    fn worker(segments: usize) -> SuccessorWorker {
        let factory = SectionFactory {
            object: TriangleMesh::cuboid(
                Vector3::new(-0.015, 0.0, 0.0),
                Vector3::new(0.015, 0.02, 0.03),
            ),
            material: MaterialPreset::PotatoCuboid.material(),
            blade: BladeSection::default(),
            settings: SectionSettings {
                row_spacing: 1e-3,
                ..SectionSettings::default()
            },
            rim_fraction: 0.05,
        };
        SuccessorWorker::new(Arc::new(factory), segments, 1)
    }

    /// A vertical plane across the cuboid at z (m).
    fn job(z: f64) -> SuccessorJob {
        SuccessorJob {
            plane: SectionPlane::normal_to_segment(Vector3::new(0.0, 0.01, z), Vector3::y()),
            current: None,
        }
    }

    #[test]
    fn built_sections_dropped_before_they_are_taken_count_as_wasted() {
        let mut w = worker(2);
        // Built and taken: not wasted.
        w.submit(0, job(0.01));
        w.wait_idle();
        assert!(matches!(w.take(0), Some((_, Preparation::New { .. }))));
        assert_eq!(w.wasted_builds(), 0);
        // Built, then renewed: wasted; the renewed one is taken.
        w.submit(0, job(0.01));
        w.wait_idle();
        w.submit(0, job(0.012));
        assert_eq!(w.wasted_builds(), 1);
        assert!(matches!(w.take(0), Some((_, Preparation::New { .. }))));
        assert_eq!(w.wasted_builds(), 1);
        // Built, then cancelled: wasted.
        w.submit(1, job(0.02));
        w.wait_idle();
        w.cancel(1);
        assert_eq!(w.wasted_builds(), 2);
        // A plane that misses the object builds nothing: not wasted.
        w.submit(1, job(0.05));
        w.wait_idle();
        w.cancel(1);
        assert_eq!(w.wasted_builds(), 2);
        // A clone keeps the count.
        assert_eq!(w.clone().wasted_builds(), 2);
    }

    #[test]
    fn held_orders_are_not_built_and_renewing_them_costs_nothing() {
        let mut w = worker(2);
        w.hold();
        w.submit(0, job(0.01));
        // Held: not started, so not ready however long the worker idles.
        std::thread::sleep(std::time::Duration::from_millis(50));
        assert!(!w.is_ready(0));
        w.submit(0, job(0.012));
        w.release();
        let (plane, p) = w.take(0).unwrap();
        assert!(matches!(p, Preparation::New { .. }));
        assert_eq!(plane.origin.z, 0.012);
        assert_eq!(w.wasted_builds(), 0);
        // A take releases a hold itself (it would wait forever otherwise),
        // and so does a clone's.
        w.hold();
        w.submit(1, job(0.02));
        let mut c = w.clone();
        assert!(matches!(w.take(1), Some((_, Preparation::New { .. }))));
        assert!(matches!(c.take(1), Some((_, Preparation::New { .. }))));
    }
}
