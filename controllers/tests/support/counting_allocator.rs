//! The workspace's counting global allocator for the allocation tests: every
//! call is forwarded unchanged to the system allocator and counted. Each test
//! binary installs it with `#[global_allocator] static GLOBAL: Counting =
//! Counting;` (crates outside `controllers` include this file by
//! `#[path]`), so it sees only that binary's tests.
//!
//! Allocations and reallocations are counted three ways; deallocations never
//! count:
//! - per thread, always: [`thread_allocations`] is the calling thread's count
//!   since it started. A test reads it before and after the measured calls;
//!   concurrent tests and the harness's threads do not disturb it.
//! - tracked threads: while a thread's [`TRACK`] flag is set, its allocations
//!   add to [`ALLOCATIONS`].
//! - every thread: while [`TRACK_ALL`] is set, every thread's allocations add
//!   to [`ALLOCATIONS`] (for a measurement spanning threads, e.g. both sides
//!   of an iceoryx2 link; the binary then runs one test, or serialises them).
//!
//! An allocation counted by both flags adds one to [`ALLOCATIONS`].
#![allow(unsafe_code)] // GlobalAlloc is an unsafe trait; the impl only forwards to System.
#![allow(dead_code)] // Each test binary uses the counts it needs.

use std::alloc::{GlobalAlloc, Layout, System};
use std::cell::Cell;
use std::sync::atomic::{AtomicBool, AtomicUsize, Ordering};

/// The counting allocator.
pub struct Counting;

/// Allocations and reallocations counted while [`TRACK`] (per thread) or
/// [`TRACK_ALL`] (every thread) was set.
pub static ALLOCATIONS: AtomicUsize = AtomicUsize::new(0);

/// Whether every thread's allocations add to [`ALLOCATIONS`].
pub static TRACK_ALL: AtomicBool = AtomicBool::new(false);

thread_local! {
    /// Whether this thread's allocations add to [`ALLOCATIONS`].
    pub static TRACK: Cell<bool> = const { Cell::new(false) };
    /// Allocations made by this thread since it started.
    static THREAD_ALLOCATIONS: Cell<usize> = const { Cell::new(0) };
}

/// Allocations and reallocations made by the calling thread since it started.
pub fn thread_allocations() -> usize {
    THREAD_ALLOCATIONS.with(Cell::get)
}

fn count() {
    // Const-initialised thread locals without destructors: safe to touch in
    // the allocator (`try_with` covers thread teardown).
    let _ = THREAD_ALLOCATIONS.try_with(|c| c.set(c.get() + 1));
    if TRACK_ALL.load(Ordering::SeqCst) || TRACK.try_with(Cell::get).unwrap_or(false) {
        ALLOCATIONS.fetch_add(1, Ordering::SeqCst);
    }
}

// SAFETY: every call is forwarded unchanged to the system allocator.
unsafe impl GlobalAlloc for Counting {
    unsafe fn alloc(&self, layout: Layout) -> *mut u8 {
        count();
        // SAFETY: same contract as the caller's.
        unsafe { System.alloc(layout) }
    }

    unsafe fn dealloc(&self, ptr: *mut u8, layout: Layout) {
        // SAFETY: same contract as the caller's.
        unsafe { System.dealloc(ptr, layout) }
    }

    unsafe fn realloc(&self, ptr: *mut u8, layout: Layout, new_size: usize) -> *mut u8 {
        count();
        // SAFETY: same contract as the caller's.
        unsafe { System.realloc(ptr, layout, new_size) }
    }
}
