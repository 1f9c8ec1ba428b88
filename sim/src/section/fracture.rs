//! Fracture of a section by the energy balance of seed 000 eq. (1),
//! dW = R_c^s ds + dU, with the slicing toughness R_c^s = r(ξ,ν)·R_c of eq. (6)
//! and the crack extension found by bracketing (§III.C) and a safeguarded
//! regula falsi (Illinois) on the bracket.

pub(crate) use crate::mechanics::toughness_ratio;

/// Outcome of solving R(s) = T for the crack extension s of one step.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) enum Extension {
    /// R(δ₀) < T: the crack does not grow in this step.
    None,
    /// R(s) = T within tolerance at extension `s` (m), `r` = R(s).
    Balanced {
        /// Crack extension, m.
        s: f64,
        /// Energy release rate at s, N/m.
        r: f64,
    },
    /// R(s_max) ≥ T: the crack runs to the end of the line (`s` = s_max).
    RunsThrough {
        /// Crack extension, m.
        s: f64,
        /// Energy release rate at s, N/m.
        r: f64,
    },
    /// No bracket within the allowed doublings (the step keeps the largest
    /// extension tried, whose R still exceeds T).
    Unbracketed {
        /// Crack extension, m.
        s: f64,
        /// Energy release rate at s, N/m.
        r: f64,
    },
}

/// Where growth starts (seed 000 §III.C): the smallest trial extension
/// 2ᵏ·`delta0` (k ≥ 0, capped at min(`s_scan`, `s_max`)) whose
/// `release(s)` reaches `trigger`, with that release; `None` if none does or
/// `s_max` ≤ 0.
pub(crate) fn growth_start(
    mut release: impl FnMut(f64) -> f64,
    delta0: f64,
    s_scan: f64,
    s_max: f64,
    trigger: f64,
) -> Option<(f64, f64)> {
    if s_max <= 0.0 {
        return None;
    }
    let mut d0 = delta0.min(s_max);
    let mut r0 = release(d0);
    while r0 < trigger {
        if d0 >= s_scan.min(s_max) {
            return None;
        }
        d0 = (2.0 * d0).min(s_scan.min(s_max));
        r0 = release(d0);
    }
    Some((d0, r0))
}

/// Bracketing of seed 000 §III.C, then Illinois regula falsi on the bracket.
///
/// `release(s)` is the energy release rate R(s) = (dW − dU)/s for a trial
/// extension s. Growth starts ([`growth_start`]) when R(δ₀) ≥ `trigger`, or
/// when R(2ᵏδ₀) ≥ `trigger` for a larger trial up to `s_scan`: R(s) need not be monotone,
/// because the stiffness under the edge changes with the crack depth (near the
/// top surface the strip stiffens as the crack faces beside it form, so the
/// balance can be met only by an extension that releases the indentation's
/// stored energy). The extension then
/// solves R(s) = `target` (≤ trigger): δ is grown in integer multiples
/// (doubling) until R(kδ₀) < target brackets the root, or s reaches `s_max`,
/// then narrowed (Illinois regula falsi, midpoint fallback; at most
/// `max_bisections` trials) until |R − target| ≤ tol·target.
#[allow(clippy::too_many_arguments)]
pub(crate) fn solve_extension(
    mut release: impl FnMut(f64) -> f64,
    delta0: f64,
    s_scan: f64,
    s_max: f64,
    trigger: f64,
    target: f64,
    tol: f64,
    max_doublings: u32,
    max_bisections: u32,
) -> Extension {
    let Some((d0, r0)) = growth_start(&mut release, delta0, s_scan, s_max, trigger) else {
        return Extension::None;
    };
    let (mut lo, mut r_lo) = (d0, r0);
    let mut hi = d0;
    let mut r_hi = r0;
    let mut bracketed = false;
    for _ in 0..max_doublings {
        if hi >= s_max {
            break;
        }
        hi = (2.0 * hi).min(s_max);
        r_hi = release(hi);
        if r_hi < target {
            bracketed = true;
            break;
        }
        lo = hi;
        r_lo = r_hi;
    }
    if !bracketed {
        return if hi >= s_max {
            Extension::RunsThrough { s: hi, r: r_hi }
        } else {
            Extension::Unbracketed { s: lo, r: r_lo }
        };
    }
    if (r_lo - target).abs() <= tol * target {
        return Extension::Balanced { s: lo, r: r_lo };
    }
    // Illinois regula falsi on the bracket [lo, hi] (R(lo) ≥ T > R(hi)): the
    // secant of the bracket's ends, with the retained end's value halved
    // when the same end is kept twice, converges superlinearly where R is
    // smooth (a few evaluations instead of bisection's ~25 for 1e-7); a
    // trial outside the bracket's interior falls back to its midpoint.
    let (mut f_lo, mut f_hi) = (r_lo - target, r_hi - target);
    let mut kept: i8 = 0;
    let (mut s, mut r) = (lo, r_lo);
    for _ in 0..max_bisections {
        s = (lo * f_hi - hi * f_lo) / (f_hi - f_lo);
        if !(s > lo && s < hi) {
            s = 0.5 * (lo + hi);
        }
        r = release(s);
        if (r - target).abs() <= tol * target || hi - lo <= 4.0 * f64::EPSILON * hi {
            break;
        }
        let f = r - target;
        if f >= 0.0 {
            lo = s;
            f_lo = f;
            if kept == 1 {
                f_hi *= 0.5;
            }
            kept = 1;
        } else {
            hi = s;
            f_hi = f;
            if kept == -1 {
                f_lo *= 0.5;
            }
            kept = -1;
        }
    }
    Extension::Balanced { s, r }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn bisection_finds_the_root_of_a_decreasing_rate() {
        // R(s) = 200 − 1e6 s: R = 150 at s = 5e-5.
        let e = solve_extension(
            |s| 200.0 - 1e6 * s,
            1e-6,
            1e-6,
            1.0,
            150.0,
            150.0,
            1e-9,
            60,
            200,
        );
        match e {
            Extension::Balanced { s, r } => {
                assert!((s - 5e-5).abs() < 1e-12);
                assert!((r - 150.0).abs() < 1e-6);
            }
            other => panic!("{other:?}"),
        }
        assert_eq!(
            solve_extension(|_| 100.0, 1e-6, 1e-3, 1.0, 150.0, 150.0, 1e-9, 60, 200),
            Extension::None
        );
        assert!(matches!(
            solve_extension(|_| 200.0, 1e-6, 1e-6, 1e-3, 150.0, 150.0, 1e-9, 60, 200),
            Extension::RunsThrough { .. }
        ));
    }
}
