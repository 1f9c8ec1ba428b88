//! Logging through `tracing`, filtered like `RUST_LOG`.

use std::io::IsTerminal;

use tracing_subscriber::EnvFilter;

/// Default filter: warnings and errors only (a run is quiet unless
/// something is wrong); iceoryx2's per-process chatter ("No config file was
/// loaded") only at error level. `RUST_LOG=info` tells the story of each
/// closed-loop cut ([`crate::closed_loop::CutStory`]).
pub const DEFAULT_FILTER: &str = "warn,iceoryx2_bb_loggers::tracing=error";

/// iceoryx2's logger target, held at error level unless `RUST_LOG` names it.
const ICEORYX2_QUIET: &str = "iceoryx2_bb_loggers::tracing=error";

/// Installs a stderr subscriber honouring `RUST_LOG` (falls back to
/// [`DEFAULT_FILTER`]; an unparsable `RUST_LOG` also falls back). Safe to call
/// more than once: later calls do nothing. Colours only when stderr is a
/// terminal: a log piped to a file or a supervisor stays plain text.
pub fn init() {
    let from_env = std::env::var("RUST_LOG").ok().and_then(|v| {
        let filter = EnvFilter::try_new(&v).ok()?;
        Some(if v.contains("iceoryx2") {
            filter
        } else {
            filter.add_directive(ICEORYX2_QUIET.parse().ok()?)
        })
    });
    let filter = from_env.unwrap_or_else(|| EnvFilter::new(DEFAULT_FILTER));
    let _ = tracing_subscriber::fmt()
        .with_env_filter(filter)
        .with_writer(std::io::stderr)
        .with_ansi(std::io::stderr().is_terminal())
        .with_target(false)
        .try_init();
}
