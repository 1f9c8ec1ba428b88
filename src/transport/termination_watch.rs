//! SIGINT and SIGTERM, caught by iceoryx2's signal handler and polled.

use std::time::{Duration, Instant};

use iceoryx2_bb_posix::signal::{NonFatalFetchableSignal, SignalHandler};
use serde::Serialize;

/// The signal that asked a run to stop.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[serde(rename_all = "lowercase")]
pub enum StopSignal {
    /// SIGINT (Ctrl-C): exit code 130.
    Sigint,
    /// SIGTERM: exit code 143.
    Sigterm,
}

impl StopSignal {
    /// The exit code of a process that stopped cleanly on this signal
    /// (128 + its number).
    pub fn exit_code(self) -> u8 {
        match self {
            StopSignal::Sigint => 130,
            StopSignal::Sigterm => 143,
        }
    }

    /// The signal's conventional name: `SIGINT` or `SIGTERM`.
    pub fn name(self) -> &'static str {
        match self {
            StopSignal::Sigint => "SIGINT",
            StopSignal::Sigterm => "SIGTERM",
        }
    }
}

impl std::fmt::Display for StopSignal {
    /// Writes [`StopSignal::name`].
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(self.name())
    }
}

/// Watches for SIGINT and SIGTERM. Its creation installs iceoryx2's
/// handlers (the process's iceoryx2 nodes install the same ones), so from
/// then on the signals no longer end the process: its owner must poll
/// [`TerminationWatch::requested`] and stop.
///
/// A signal is reported once: the handler keeps the last one until it is
/// read (by this watch or by an iceoryx2 node's `wait`).
#[derive(Debug)]
pub struct TerminationWatch(());

impl TerminationWatch {
    /// Installs the handlers (a signal that came before is forgotten).
    pub fn new() -> Self {
        let _ = SignalHandler::last_signal();
        Self(())
    }

    /// The signal received since the last call, if any (does not wait;
    /// takes the handler's lock: poll it off any hard real-time path).
    pub fn requested(&self) -> Option<StopSignal> {
        match SignalHandler::last_signal() {
            Some(NonFatalFetchableSignal::Interrupt) => Some(StopSignal::Sigint),
            Some(NonFatalFetchableSignal::Terminate) => Some(StopSignal::Sigterm),
            _ => None,
        }
    }

    /// The signal received within `grace` (returns as soon as one is;
    /// looks every millisecond).
    #[allow(clippy::disallowed_methods)] // A supervisor's wait, not a model's time.
    pub fn requested_within(&self, grace: Duration) -> Option<StopSignal> {
        let deadline = Instant::now() + grace;
        loop {
            if let Some(signal) = self.requested() {
                return Some(signal);
            }
            let now = Instant::now();
            if now >= deadline {
                return None;
            }
            std::thread::sleep((deadline - now).min(Duration::from_millis(1)));
        }
    }
}

impl Default for TerminationWatch {
    fn default() -> Self {
        Self::new()
    }
}
