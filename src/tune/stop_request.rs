//! SIGINT/SIGTERM during a batch of runs (`tune`, `compare`): the runs in
//! flight end at their next tick, no other run starts, and the command
//! writes what is done and exits 130/143.
//!
//! The [`TerminationWatch`] is polled by a watcher thread beside the runs
//! ([`StopRequest::poll`], which takes the signal handler's lock); the
//! runs' loops read the request at the end of each tick through
//! [`StopAtTick`], one atomic load.

use std::sync::atomic::{AtomicU8, Ordering};

use crate::closed_loop::{ControlSample, LoopRecorder};
use crate::cut_record::CutSample;
use crate::transport::{StopSignal, TerminationWatch};

/// A stop asked of the runs of one command: the first signal seen, kept
/// for the rest of the command (the signal handler reports a signal once).
#[derive(Debug)]
pub struct StopRequest {
    /// 0 while none, else the signal's exit code (130 or 143).
    code: AtomicU8,
    /// The signals' source; `None`: nothing asks for a stop.
    watch: Option<TerminationWatch>,
}

impl StopRequest {
    /// A request that SIGINT or SIGTERM makes, through `watch` (whose
    /// creation made the signals stop ending the process).
    pub fn watching(watch: TerminationWatch) -> Self {
        Self {
            code: AtomicU8::new(0),
            watch: Some(watch),
        }
    }

    /// A request that is never made (runs not stopped by signals).
    pub fn never() -> Self {
        Self {
            code: AtomicU8::new(0),
            watch: None,
        }
    }

    /// Whether there are signals to watch for.
    pub fn is_watching(&self) -> bool {
        self.watch.is_some()
    }

    /// The signal that asked for the stop, if one did (one atomic load).
    pub fn signal(&self) -> Option<StopSignal> {
        match self.code.load(Ordering::Acquire) {
            130 => Some(StopSignal::Sigint),
            143 => Some(StopSignal::Sigterm),
            _ => None,
        }
    }

    /// Records `signal` unless a signal was recorded before.
    pub fn request(&self, signal: StopSignal) {
        let _ =
            self.code
                .compare_exchange(0, signal.exit_code(), Ordering::AcqRel, Ordering::Acquire);
    }

    /// Looks at the watch for a new signal and records it; the signal
    /// asking for the stop, if any (takes the signal handler's lock: the
    /// watcher thread's call, not a loop's).
    pub fn poll(&self) -> Option<StopSignal> {
        if let Some(signal) = self.watch.as_ref().and_then(TerminationWatch::requested) {
            self.request(signal);
        }
        self.signal()
    }
}

/// A run's recorder that records nothing and ends the loop at the end of
/// the tick after a stop was requested ([`LoopEnd::Stopped`]).
///
/// [`LoopEnd::Stopped`]: crate::closed_loop::LoopEnd::Stopped
#[derive(Debug, Clone, Copy)]
pub struct StopAtTick<'a>(pub &'a StopRequest);

impl LoopRecorder for StopAtTick<'_> {
    fn sample(&mut self, _: &CutSample) {}
    fn control(&mut self, _: &ControlSample) {}
    fn tick_done(&mut self, _: f64) {}
    fn stop_requested(&self) -> Option<StopSignal> {
        self.0.signal()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_first_signal_is_kept() {
        let stop = StopRequest::never();
        assert_eq!(stop.signal(), None);
        assert_eq!(stop.poll(), None);
        stop.request(StopSignal::Sigterm);
        stop.request(StopSignal::Sigint);
        assert_eq!(stop.signal(), Some(StopSignal::Sigterm));
        assert_eq!(
            StopAtTick(&stop).stop_requested(),
            Some(StopSignal::Sigterm)
        );
    }
}
