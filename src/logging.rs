//! Logging through `tracing`, filtered like `RUST_LOG`.

use tracing_subscriber::EnvFilter;

/// Default filter: our own info messages; iceoryx2's per-process chatter
/// ("No config file was loaded") only at error level.
pub const DEFAULT_FILTER: &str = "info,iceoryx2_bb_loggers::tracing=error";

/// Installs a stderr subscriber honouring `RUST_LOG` (falls back to
/// [`DEFAULT_FILTER`]; an unparsable `RUST_LOG` also falls back). Safe to call
/// more than once: later calls do nothing.
pub fn init() {
    let filter =
        EnvFilter::try_from_default_env().unwrap_or_else(|_| EnvFilter::new(DEFAULT_FILTER));
    let _ = tracing_subscriber::fmt()
        .with_env_filter(filter)
        .with_writer(std::io::stderr)
        .with_target(false)
        .try_init();
}
