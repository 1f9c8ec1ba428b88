//! The kinematic-angle sweep of seed 001 (its Figs. 1e–f and 3d–e): one
//! indentation to nucleation per angle θ, angles shared out over threads.
//! Each angle runs on its own slab, so the results do not depend on the
//! number of threads.

use super::settings::WireSlabSettings;
use super::slab::{IndentationRun, WireSlab, WireSlabError};

/// Indentations at several kinematic angles.
#[derive(Debug, Clone, PartialEq)]
pub struct AngleSweep {
    /// One run per angle, in the order of the angles given; of a stopped
    /// sweep, one per angle started, the last of each thread
    /// [`IndentationRun::stopped`] if it had not ended.
    pub runs: Vec<IndentationRun>,
}

/// Runs [`WireSlab::indent`] at each angle of `angles_deg` (degrees) on
/// `threads` threads (at least 1).
pub fn sweep_angles(
    settings: &WireSlabSettings,
    angles_deg: &[f64],
    threads: usize,
) -> Result<AngleSweep, WireSlabError> {
    sweep_angles_until(settings, angles_deg, threads, &|| false, &|_, _| {})
}

/// [`sweep_angles`], each thread asking `stop` after each load step
/// ([`WireSlab::indent_until`]): once it answers `true`, the runs in
/// progress end there and no further angle is started (each thread's
/// first angle is, so a stopped sweep holds a run per thread). `stop` must keep answering
/// `true` once it has. Each run that ends (stopped or not) is handed to
/// `ended` on its thread with the index of its angle in `angles_deg`, as it
/// ends.
pub fn sweep_angles_until(
    settings: &WireSlabSettings,
    angles_deg: &[f64],
    threads: usize,
    stop: &(dyn Fn() -> bool + Sync),
    ended: &(dyn Fn(usize, &IndentationRun) + Sync),
) -> Result<AngleSweep, WireSlabError> {
    settings.validate()?;
    let threads = threads.clamp(1, angles_deg.len().max(1));
    let mut results: Vec<Option<Result<IndentationRun, WireSlabError>>> =
        (0..angles_deg.len()).map(|_| None).collect();
    std::thread::scope(|scope| {
        let handles: Vec<_> = (0..threads)
            .map(|t| {
                scope.spawn(move || {
                    let mut out = Vec::new();
                    let mut slab = match WireSlab::new(settings) {
                        Ok(s) => s,
                        Err(e) => return vec![(t, Err(e))],
                    };
                    for (i, &a) in angles_deg.iter().enumerate().skip(t).step_by(threads) {
                        // A thread's first angle always starts (a stopped
                        // sweep has a run, of one state at least, per thread).
                        if !out.is_empty() && stop() {
                            break;
                        }
                        let run = slab.indent_until(a.to_radians(), stop);
                        if let Ok(run) = &run {
                            ended(i, run);
                        }
                        out.push((i, run.map_err(WireSlabError::from)));
                    }
                    out
                })
            })
            .collect();
        for h in handles {
            for (i, r) in h.join().expect("a sweep thread panicked") {
                results[i] = Some(r);
            }
        }
    });
    let mut runs = Vec::with_capacity(angles_deg.len());
    for r in results {
        match r {
            Some(Ok(run)) => runs.push(run),
            Some(Err(e)) => return Err(e),
            None => {}
        }
    }
    Ok(AngleSweep { runs })
}
