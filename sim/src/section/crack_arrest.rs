//! Where a running crack stops: Griffith's balance held along the crack's
//! path (seed 000 eq. 1 per increment of crack, dW − dU = R_c^s ds) instead
//! of over a whole step's extension.
//!
//! Seed 000 §III.C solves one step's extension s from the balance over the
//! extension as a whole, Q(s) = r·Γ(s), with Q(s) = W(s) − ΔU(s) the energy
//! the step makes available and r·Γ(s) what the extension pays (r·R_c·s
//! without a skin layer). In steady cutting the extension of a step is
//! small and the release rate G(a) = dQ/da hardly changes over it, so this
//! is the local balance G = r·R_c. After seed 001's surface-stress
//! nucleation it is not: the section stores far more energy than R_c pays
//! for over the distance to the wire (about F_n·d/2 against R_c·d), and the
//! whole-extension balance spends all of it on crack, sending the crack many
//! times the indentation down. Seed 001 instead sees the force drop at
//! nucleation and a steady cutting force after it (its Fig. 1c: "once the
//! surface has ruptured, the natural stress focusing at the advancing crack
//! suffices to propagate the cut"), the stored energy "irreversibly lost
//! when the stress reaches the critical fracture threshold". The local
//! balance gives exactly this: the crack runs while G(a) ≥ r·R_c, i.e. while
//! the indentation still presses it open, and arrests where G(a) falls
//! below r·R_c, a short distance ahead of the wire whose faces' opening
//! alone drives it there (G of a crack opened by a wedge falls as its tip
//! leaves the wedge). The energy released beyond r·Γ on the way is the
//! unstable release of the step.
//!
//! G is resolved over windows of one row spacing: the crack tip moves along
//! the cut line by interpolation between rows, so the mesh resolves G only
//! as an average over a row.

use super::fracture::{Extension, growth_start, solve_extension};

/// The extension s ≤ `s_max` at which a crack growing from s = 0 arrests.
///
/// `released(s)` is Q(s), the energy (J/m) a step with crack extension s
/// makes available for fracture, `paid(s)` the energy r·Γ(s) the extension
/// pays (both 0 at s = 0, `paid` increasing). Growth starts as in
/// [`solve_extension`] on the ratio Q(s)/(r·Γ(s)) against 1: when it reaches
/// 1 at `delta0` or, doubling, at an extension up to `s_scan`. The crack
/// then advances window by window (`window` m, the first window at least
/// as long as the start) while each window releases at least what it pays,
/// (Q(b) − Q(a))/(r·Γ(b) − r·Γ(a)) ≥ 1, and stops in the first window that
/// does not, where the balance over the part of the window crossed is met
/// (within `tol`), or at the window's start if the release rate just past
/// it is already below the toughness. Returns [`Extension::None`] if growth
/// does not start, [`Extension::RunsThrough`] at `s_max`,
/// [`Extension::Balanced`] otherwise (its `r`: the ratio of the last
/// window's balance). Allocation-free.
#[allow(clippy::too_many_arguments)]
pub(super) fn solve_arrest(
    mut released: impl FnMut(f64) -> f64,
    paid: impl Fn(f64) -> f64,
    delta0: f64,
    s_scan: f64,
    s_max: f64,
    window: f64,
    tol: f64,
    max_doublings: u32,
    max_bisections: u32,
) -> Extension {
    let Some((start, _)) = growth_start(|s| released(s) / paid(s), delta0, s_scan, s_max, 1.0)
    else {
        return Extension::None;
    };
    let (mut a, mut q_a) = (0.0, 0.0);
    let mut length = window.max(start);
    loop {
        let b = (a + length).min(s_max);
        let q_b = released(b);
        let ratio = (q_b - q_a) / (paid(b) - paid(a));
        if ratio >= 1.0 {
            if b >= s_max {
                return Extension::RunsThrough { s: b, r: ratio };
            }
            (a, q_a, length) = (b, q_b, window);
            continue;
        }
        // The arrest is in (a, b]: where the window's part crossed balances.
        let scan = if a == 0.0 { start } else { delta0 };
        let crossed = solve_extension(
            |x| (released(a + x) - q_a) / (paid(a + x) - paid(a)),
            delta0.min(b - a),
            scan,
            b - a,
            1.0,
            1.0,
            tol,
            max_doublings,
            max_bisections,
        );
        return match crossed {
            Extension::None => Extension::Balanced { s: a, r: 1.0 },
            Extension::Balanced { s, r }
            | Extension::RunsThrough { s, r }
            | Extension::Unbracketed { s, r } => Extension::Balanced { s: a + s, r },
        };
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A release rate G(s) that is high up to 1 mm and low beyond: the
    /// whole-extension balance runs on until the early surplus is spent,
    /// the arrest stops where G falls below the toughness.
    #[test]
    fn the_crack_stops_where_the_release_rate_falls_below_the_toughness() {
        let t = 5.0;
        // G = 60 N/m up to 1 mm, then 1 N/m: Q(s) = ∫G.
        let q = |s: f64| 60.0 * s.min(1e-3) + 1.0 * (s - 1e-3).max(0.0);
        let paid = |s: f64| t * s;
        let whole = solve_extension(|s| q(s) / s, 1e-6, 1e-6, 1.0, t, t, 1e-9, 60, 200);
        let Extension::Balanced { s: s_whole, .. } = whole else {
            panic!("{whole:?}")
        };
        // 60e-3 − 1e-3 + s = 5 s → s = 14.75 mm.
        assert!((s_whole - 14.75e-3).abs() < 1e-9, "{s_whole}");
        let arrest = solve_arrest(q, paid, 1e-6, 1e-6, 1.0, 5e-5, 1e-9, 60, 200);
        let Extension::Balanced { s, .. } = arrest else {
            panic!("{arrest:?}")
        };
        // Resolved to one window (50 µm) of the drop at 1 mm.
        assert!((s - 1e-3).abs() <= 5e-5, "{s}");
    }

    /// No growth without the start; a release rate above the toughness all
    /// the way runs through; a step releasing just enough balances as
    /// `solve_extension` does.
    #[test]
    fn start_run_through_and_balance() {
        let paid = |s: f64| 5.0 * s;
        assert_eq!(
            solve_arrest(|s| 4.0 * s, paid, 1e-6, 1e-6, 1.0, 5e-5, 1e-9, 60, 200),
            Extension::None
        );
        assert!(matches!(
            solve_arrest(|s| 6.0 * s, paid, 1e-6, 1e-6, 2e-3, 5e-5, 1e-9, 60, 200),
            Extension::RunsThrough { s, .. } if s == 2e-3
        ));
        // Q(s) = 10 s − 1e3 s²: mean rate 10 − 1e3 s = 5 at s = 5 mm, local
        // rate 10 − 2e3 s = 5 at 2.5 mm.
        let q = |s: f64| 10.0 * s - 1e3 * s * s;
        let Extension::Balanced { s, .. } =
            solve_arrest(q, paid, 1e-6, 1e-6, 1.0, 5e-5, 1e-9, 60, 200)
        else {
            panic!()
        };
        // Resolved to one window (50 µm) of the local balance at 2.5 mm,
        // half the whole-extension balance's 5 mm.
        assert!((s - 2.5e-3).abs() <= 5e-5, "{s}");
    }
}
