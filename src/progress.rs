//! Progress bars for commands that run many cuts: on stderr, drawn only
//! when it is a terminal (indicatif hides them otherwise), so logs and
//! pipes see nothing of them.

use indicatif::{ProgressBar, ProgressStyle};

/// A bar over `runs` runs, labelled `what` ("compare loop-potato-whole"),
/// with the elapsed time and an estimate of the time left.
pub fn run_bar(runs: usize, what: &str) -> ProgressBar {
    let bar = ProgressBar::new(runs as u64);
    bar.set_style(
        ProgressStyle::with_template(
            "{elapsed_precise} [{bar:30}] {pos}/{len} runs, ETA {eta} {msg}",
        )
        .unwrap_or_else(|_| ProgressStyle::default_bar())
        .progress_chars("=> "),
    );
    bar.set_message(what.to_string());
    bar
}
