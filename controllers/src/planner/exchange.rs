//! The single-slot exchange between the tick side and the planner thread.
//!
//! One triple buffer per direction (crate `triple_buffer`): the writer
//! publishes into a slot and the reader takes the newest published value,
//! both wait-free and allocation-free after construction (the three
//! buffers are cloned once from an initial value). Nothing queues: a value
//! not yet taken is replaced by the next one. [`Signals`] adds what the
//! buffers cannot say: the planner's health, the newest plan published,
//! shutdown, and the one place the tick side may wait (lockstep).

use std::sync::atomic::{AtomicBool, AtomicU64, Ordering};
use std::sync::{Condvar, Mutex, PoisonError};

/// A value with the request it belongs to.
#[derive(Debug, Clone, Copy)]
pub(super) struct Stamped<T> {
    /// Request number, from 1 (0: the initial value, answering none).
    pub seq: u64,
    /// Tick at which the request was submitted.
    pub tick: u64,
    /// The request or the plan.
    pub value: T,
}

/// Flags and counters shared by both sides.
#[derive(Debug, Default)]
pub(super) struct Signals {
    /// Set by the tick side: the planner thread returns.
    pub stop: AtomicBool,
    /// Set by the planner thread when the job panicked.
    pub panicked: AtomicBool,
    /// Tick of the request whose plan panicked (valid once `panicked`).
    pub panicked_tick: AtomicU64,
    /// Number of the newest plan published (0: none).
    pub published: AtomicU64,
    /// How long each plan took on the planner thread, µs (wall clock), in
    /// the order made. Written by the planner thread after each plan, read
    /// by the tick side's owner after the run ([`super::Planner::solve_times_us`]),
    /// never by a tick.
    pub solve_times_us: Mutex<Vec<f64>>,
    /// Guards the lockstep wait's condition against lost wake-ups.
    lock: Mutex<()>,
    /// Rung after each plan or panic when a lockstep tick side may wait.
    ready: Condvar,
}

impl Signals {
    /// Whether the plan numbered `seq` was published or will never be.
    pub fn settled(&self, seq: u64) -> bool {
        self.published.load(Ordering::Acquire) >= seq || self.panicked.load(Ordering::Acquire)
    }

    /// Blocks until [`Self::settled`]`(seq)`: the lockstep tick side's only
    /// wait. Allocation-free (a futex on Linux).
    pub fn wait_settled(&self, seq: u64) {
        if self.settled(seq) {
            return;
        }
        let guard = self.lock.lock().unwrap_or_else(PoisonError::into_inner);
        let _guard = self
            .ready
            .wait_while(guard, |()| !self.settled(seq))
            .unwrap_or_else(PoisonError::into_inner);
    }

    /// Wakes a tick side blocked in [`Self::wait_settled`]; called by the
    /// planner thread after it changed `published` or `panicked`.
    pub fn ring(&self) {
        let _guard = self.lock.lock().unwrap_or_else(PoisonError::into_inner);
        self.ready.notify_all();
    }
}
