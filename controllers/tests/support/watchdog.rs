//! Runs a test body on its own thread and fails the test if it has not
//! finished within a generous bound, so that a hang (a deadlock of the tick
//! side or the planner thread) fails instead of blocking the suite. Not a
//! timing assertion: a correct body takes milliseconds.
#![allow(dead_code)] // Each test binary uses a part.

use std::sync::mpsc;
use std::time::Duration;

/// Runs `body`; panics if it hangs for 120 s, re-raises its panic.
pub fn within_watchdog<F: FnOnce() + Send + 'static>(body: F) {
    let (done, finished) = mpsc::channel();
    let handle = std::thread::spawn(move || {
        body();
        let _ = done.send(());
    });
    match finished.recv_timeout(Duration::from_secs(120)) {
        Ok(()) => handle.join().unwrap(),
        Err(mpsc::RecvTimeoutError::Disconnected) => {
            // The body panicked: surface its message.
            if let Err(p) = handle.join() {
                std::panic::resume_unwind(p);
            }
        }
        Err(mpsc::RecvTimeoutError::Timeout) => panic!("hang: the body did not finish in 120 s"),
    }
}
