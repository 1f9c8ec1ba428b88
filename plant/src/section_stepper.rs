//! Threads that advance a tick's cross sections beside the plant's own.
//!
//! Within a tick the sections are independent: each advances by its own
//! normal and tangential travel (seed 000 §IV, assumption A2), and the plant
//! sums their loads afterwards in the segments' order. So they can advance
//! on several threads and the plant's results stay bit-identical to one
//! thread's, however the threads are scheduled: each section's arithmetic is
//! the same, only where it runs changes. This is for a plant that must keep
//! a wall-clock period (a realtime loop), where the sum of the sections'
//! steps late in a cut exceeds it on one core.
//!
//! A section crosses to a helper thread by moving its box into the helper's
//! preallocated queue and comes back the same way: no section is shared,
//! and nothing is allocated after construction (a mutex and two condition
//! variables per helper, held only to move boxes). The plant's own thread
//! takes back from the queues the sections no helper has started
//! ([`SectionStepper::take_back`]), so the threads share a tick's sections
//! as they become free rather than by a fixed deal.

use std::sync::{Arc, Condvar, Mutex, MutexGuard};
use std::thread::JoinHandle;

use shearcut_sim::section::{CrossSection, SectionError, SectionStep};

/// How often a plant waiting for a helper's sections looks whether the
/// helper is still alive.
const HELPER_LOOK: std::time::Duration = std::time::Duration::from_millis(100);

/// A section to advance: its segment's index in the plant's list, the
/// section, and its normal and tangential travel, m.
pub(crate) struct Advance {
    pub index: usize,
    pub section: Box<CrossSection>,
    pub normal: f64,
    pub tangential: f64,
}

/// A section advanced: the same index and section, the outcome of
/// [`CrossSection::advance`] and the condensed-line solves it took.
pub(crate) struct Advanced {
    pub index: usize,
    pub section: Box<CrossSection>,
    pub step: Result<SectionStep, SectionError>,
    pub solves: u64,
}

/// What the plant and one helper hand each other.
struct Queue {
    /// Sections to advance (capacity: the plant's sections).
    jobs: Vec<Advance>,
    /// Sections advanced (capacity: the plant's sections).
    done: Vec<Advanced>,
    /// The plant is dropping the stepper: the helper ends.
    closed: bool,
}

/// One helper's queue and its signals.
struct Lane {
    queue: Mutex<Queue>,
    /// Signalled when a job is queued or the lane is closed.
    job_ready: Condvar,
    /// Signalled when a section is advanced.
    done_ready: Condvar,
}

impl Lane {
    fn lock(&self) -> MutexGuard<'_, Queue> {
        // A helper that panicked left whole boxes in the queues.
        self.queue.lock().unwrap_or_else(|e| e.into_inner())
    }
}

/// One helper thread and its lane.
struct Helper {
    lane: Arc<Lane>,
    handle: Option<JoinHandle<()>>,
}

/// The plant's helper threads for advancing sections (none: the plant
/// advances every section itself).
pub(crate) struct SectionStepper {
    helpers: Vec<Helper>,
    /// Sections sent to each helper and neither received back nor taken
    /// back.
    in_flight: Vec<usize>,
    /// Room of each queue: the most sections one tick can send.
    capacity: usize,
}

impl std::fmt::Debug for SectionStepper {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("SectionStepper")
            .field("threads", &self.threads())
            .finish_non_exhaustive()
    }
}

impl SectionStepper {
    /// Starts `threads − 1` helper threads (none for `threads` ≤ 1) for a
    /// plant of at most `sections` sections. The helpers are spawned by the
    /// calling thread and so run under its scheduling policy and priority
    /// (a thread inherits its creator's); a helper the operating system
    /// refuses to start is left out.
    pub fn new(threads: usize, sections: usize) -> Self {
        let capacity = sections.max(1);
        let helpers: Vec<Helper> = (1..threads.max(1))
            .filter_map(|i| {
                let lane = Arc::new(Lane {
                    queue: Mutex::new(Queue {
                        jobs: Vec::with_capacity(capacity),
                        done: Vec::with_capacity(capacity),
                        closed: false,
                    }),
                    job_ready: Condvar::new(),
                    done_ready: Condvar::new(),
                });
                let theirs = Arc::clone(&lane);
                let handle = std::thread::Builder::new()
                    .name(format!("section-stepper-{i}"))
                    .spawn(move || advance_until_closed(&theirs))
                    .ok()?;
                Some(Helper {
                    lane,
                    handle: Some(handle),
                })
            })
            .collect();
        Self {
            in_flight: vec![0; helpers.len()],
            helpers,
            capacity,
        }
    }

    /// Threads that advance sections, the caller's included.
    pub fn threads(&self) -> usize {
        self.helpers.len() + 1
    }

    /// Sends `job` to helper `k` (of `threads() − 1`). Allocates nothing.
    ///
    /// # Panics
    /// `k` is out of range, or more sections are sent in one tick than the
    /// plant has (a bug).
    pub fn send(&mut self, k: usize, job: Advance) {
        assert!(
            self.in_flight[k] < self.capacity,
            "more sections sent in one tick than the plant has"
        );
        let lane = &self.helpers[k].lane;
        lane.lock().jobs.push(job);
        lane.job_ready.notify_one();
        self.in_flight[k] += 1;
    }

    /// Takes back a section sent to a helper that no helper has started
    /// (the last queued of the first helper that has one), for the calling
    /// thread to advance. Allocates nothing.
    pub fn take_back(&mut self) -> Option<Advance> {
        for (helper, n) in self.helpers.iter().zip(&mut self.in_flight) {
            if *n == 0 {
                continue;
            }
            if let Some(job) = helper.lane.lock().jobs.pop() {
                *n -= 1;
                return Some(job);
            }
        }
        None
    }

    /// Receives every section sent and not yet received, calling `back` on
    /// each. Allocates nothing.
    ///
    /// # Panics
    /// A helper has died (a panic in [`CrossSection::advance`], a bug).
    pub fn receive_all(&mut self, mut back: impl FnMut(Advanced)) {
        for (helper, n) in self.helpers.iter().zip(&mut self.in_flight) {
            if *n == 0 {
                continue;
            }
            let lane = &helper.lane;
            let mut queue = lane.lock();
            while queue.done.len() < *n {
                assert!(
                    helper.handle.as_ref().is_some_and(|h| !h.is_finished()),
                    "a section stepper thread died"
                );
                // A helper that panics mid-section never signals: look
                // again at whether it is alive every `HELPER_LOOK`.
                queue = lane
                    .done_ready
                    .wait_timeout(queue, HELPER_LOOK)
                    .map_or_else(|e| e.into_inner().0, |(q, _)| q);
            }
            for advanced in queue.done.drain(..) {
                back(advanced);
            }
            *n = 0;
        }
    }
}

impl Clone for SectionStepper {
    /// New helper threads, as many, spawned by the cloning thread.
    fn clone(&self) -> Self {
        Self::new(self.threads(), self.capacity)
    }
}

impl Drop for SectionStepper {
    fn drop(&mut self) {
        for helper in &mut self.helpers {
            helper.lane.lock().closed = true;
            helper.lane.job_ready.notify_one();
            if let Some(handle) = helper.handle.take() {
                let _ = handle.join();
            }
        }
    }
}

/// A helper's loop: advance each section queued and hand it back, until
/// the plant closes the lane.
fn advance_until_closed(lane: &Lane) {
    let mut queue = lane.lock();
    loop {
        if let Some(mut job) = queue.jobs.pop() {
            drop(queue);
            let (step, solves) = advance_counted(&mut job.section, job.normal, job.tangential);
            queue = lane.lock();
            queue.done.push(Advanced {
                index: job.index,
                section: job.section,
                step,
                solves,
            });
            lane.done_ready.notify_one();
        } else if queue.closed {
            return;
        } else {
            queue = lane
                .job_ready
                .wait(queue)
                .unwrap_or_else(|e| e.into_inner());
        }
    }
}

/// [`CrossSection::advance`] by `normal` and `tangential` travel (m), with
/// the condensed-line solves it took (the section's cost for dealing).
pub(crate) fn advance_counted(
    section: &mut CrossSection,
    normal: f64,
    tangential: f64,
) -> (Result<SectionStep, SectionError>, u64) {
    let before = section.solves();
    let step = section.advance(normal, tangential);
    (step, section.solves().saturating_sub(before))
}
