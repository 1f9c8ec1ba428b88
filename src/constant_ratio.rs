//! The constant slice-push ratios a cut's blade budget allows, and the
//! choice of the best of them on replicated runs: what `shearcut compare`
//! searches and what a sweep's `best-constant` grid runs
//! (`crate::tune::sweep_file`).
//!
//! A constant ratio ξ spends ξ·d of blade over d of depth, so over the
//! whole cut (target depth D, blade budget B) the largest constant ratio
//! that stays within one stroke is B/D ([`ratio_cap`]). The coarse grid
//! runs from 0 (pressing) to that cap in equal steps ([`coarse_grid`]);
//! ratios are rounded to 3 decimals, so that tables name them readably
//! (the search's resolution is far coarser).

use shearcut_controllers::controller::CutTask;

use crate::controller_choice::ControllerChoice;

/// `x` rounded to 3 decimals.
pub fn round3(x: f64) -> f64 {
    (x * 1e3).round() / 1e3
}

/// The largest constant ratio the blade allows over the whole cut: the
/// task's blade budget over its target depth, at most `max_ratio` (the
/// MPC's `max_slice_push_ratio`, the same bound for both).
pub fn ratio_cap(task: &CutTask, max_ratio: f64) -> f64 {
    (task.blade_budget / task.target_depth).min(max_ratio)
}

/// `points` (≥ 2) ratios from 0 to `cap` in equal steps, each rounded to 3
/// decimals: ratio i is round3(cap·i/(points − 1)).
pub fn coarse_grid(cap: f64, points: usize) -> Vec<f64> {
    let last = points.max(2) - 1;
    (0..=last)
        .map(|i| round3(cap * i as f64 / last as f64))
        .collect()
}

/// The constant-ratio controller for ratio `xi` (0: pressing).
pub fn constant_choice(xi: f64) -> ControllerChoice {
    if xi == 0.0 {
        ControllerChoice::Press
    } else {
        ControllerChoice::Slice(xi)
    }
}

/// The mean work of one candidate's runs (J, each run's work and whether
/// it reached the target depth), or `None` unless every run completed: a
/// cut that stopped short did less work and cannot be the best.
pub fn completed_mean_work(runs: impl IntoIterator<Item = (f64, bool)>) -> Option<f64> {
    let (mut sum, mut n) = (0.0, 0usize);
    for (work, completed) in runs {
        if !completed {
            return None;
        }
        sum += work;
        n += 1;
    }
    (n > 0).then(|| sum / n as f64)
}

/// Of `candidates` (an index with its [`completed_mean_work`]), the index
/// of the least mean work; the first of equals; `None` if none completed.
pub fn least_mean_work(
    candidates: impl IntoIterator<Item = (usize, Option<f64>)>,
) -> Option<usize> {
    candidates
        .into_iter()
        .filter_map(|(i, w)| w.map(|w| (i, w)))
        .fold(None, |best: Option<(usize, f64)>, (i, w)| match best {
            Some((_, b)) if b <= w => best,
            _ => Some((i, w)),
        })
        .map(|(i, _)| i)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_grid_runs_from_pressing_to_the_cap() {
        assert_eq!(coarse_grid(0.6, 6), [0.0, 0.12, 0.24, 0.36, 0.48, 0.6]);
        assert_eq!(coarse_grid(0.5, 5), [0.0, 0.125, 0.25, 0.375, 0.5]);
        // 1/3 of 0.5 is named by its 3 decimals.
        assert_eq!(coarse_grid(0.5, 4)[1], 0.167);
        assert_eq!(constant_choice(0.0), ControllerChoice::Press);
        assert_eq!(constant_choice(0.25), ControllerChoice::Slice(0.25));
    }

    #[test]
    fn the_best_is_the_least_mean_over_completed_runs() {
        let a = completed_mean_work([(1.0, true), (1.2, true)]);
        let b = completed_mean_work([(1.05, true), (1.05, true)]);
        let short = completed_mean_work([(0.5, true), (0.9, false)]);
        assert_eq!(a, Some(1.1));
        assert_eq!(short, None);
        assert_eq!(completed_mean_work([]), None);
        assert_eq!(least_mean_work([(0, a), (1, b), (2, short)]), Some(1));
        assert_eq!(least_mean_work([(3, a), (4, a)]), Some(3));
        assert_eq!(least_mean_work([(0, None)]), None);
    }
}
