//! The peak family's equations on one smooth window of the peak velocity `v_p`, solved as
//! polynomials.
//!
//! Between the break points of [`super::position_time_optimal::peak_breaks`] each of the two
//! velocity changes `(v0, a0) → (v_p, 0)` and `(v_p, 0) → (vf, af)` keeps its shape: it either
//! holds an acceleration limit (ramps of fixed length, hold linear in `v_p`) or it is a pure
//! ramp pair with peak magnitude
//!
//! ```text
//!   x² = s1 J (v_p − v0) + a0²/2     (first change, jerk sign s1 first)
//!   y² = s2 J (vf − v_p) + af²/2     (second change, jerk sign s2 first)
//! ```
//!
//! Durations are linear in `x`, `y` (or `v_p` for a held change) and distances cubic, so in the
//! right variable every residual is a polynomial:
//!
//! | shapes | variable | distance `D − Δp` | with cruise, `D + v_p (T − T₁ − T₂) − Δp` | duration `T₁ + T₂ − T` |
//! |---|---|---|---|---|
//! | hold / hold | `v_p` | 2 | 2 | 1 |
//! | ramps / hold | `x` | 4 | 4 | 2 |
//! | hold / ramps | `y` | 4 | 4 | 2 |
//! | ramps / ramps, `s2 = −s1` | `u = x + y` (then `x − y = −K/u`) | 4 after `·u` | 5 after `·u²` | 1 |
//!
//! (`K = y² − x²` is constant in the last row.) Windows where both changes are ramp pairs with
//! the same sign (`x² + y²` constant) are sampled by [`super::roots::scan`], as is any window
//! whose shapes are not constant or whose polynomial check fails.

use super::dof::Dof;
use super::polynomial::{RootSet, closed_form_roots_checked, polynomial_roots};
use super::position_time_optimal::peak_parts;
use super::roots::{Roots, scan};

/// Which peak-family residual is solved.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) enum PeakResidual {
    /// Position equation `D(v_p) = Δp` without cruise (time-optimal step).
    Distance {
        /// Displacement Δp.
        dp: f64,
    },
    /// Position equation with a cruise filling the prescribed duration `t`.
    CruiseDistance {
        /// Displacement Δp.
        dp: f64,
        /// Prescribed duration (s).
        t: f64,
    },
    /// Duration equation `T₁ + T₂ = t` (the fixed-duration search solves the cruise equation on
    /// whole windows instead; its closed forms are covered by the unit test below).
    #[cfg_attr(not(test), allow(dead_code))]
    Duration {
        /// Prescribed duration (s).
        t: f64,
    },
}

impl PeakResidual {
    /// Degrees for (hold/hold, one ramp pair, two opposite ramp pairs) and the power of `u`
    /// multiplying the last.
    fn degrees(self) -> ([usize; 3], i32) {
        match self {
            Self::Distance { .. } => ([2, 4, 4], 1),
            Self::CruiseDistance { .. } => ([2, 4, 5], 2),
            Self::Duration { .. } => ([1, 2, 1], 0),
        }
    }

    /// Closed-form coefficients for the window shape (`h1`, `h2`: the changes hold a limit).
    fn coefficients(self, h1: bool, h2: bool, q: &mut PeakInputs) -> (usize, [f64; 7]) {
        use super::peak_polynomials as pp;
        let same = !h1 && !h2 && q.s1 == q.s2;
        match self {
            Self::Distance { dp } => {
                q.dp = dp;
                if same {
                    return pp::distance_ramps_ramps_same(q);
                }
                match (h1, h2) {
                    (true, true) => pp::distance_hold_hold(q),
                    (false, true) => pp::distance_ramps_hold(q),
                    (true, false) => pp::distance_hold_ramps(q),
                    (false, false) => pp::distance_ramps_ramps(q),
                }
            }
            Self::CruiseDistance { dp, t } => {
                q.dp = dp;
                q.t = t;
                if same {
                    return pp::cruise_ramps_ramps_same(q);
                }
                match (h1, h2) {
                    (true, true) => pp::cruise_hold_hold(q),
                    (false, true) => pp::cruise_ramps_hold(q),
                    (true, false) => pp::cruise_hold_ramps(q),
                    (false, false) => pp::cruise_ramps_ramps(q),
                }
            }
            Self::Duration { t } => {
                q.t = t;
                if same {
                    return pp::duration_ramps_ramps_same(q);
                }
                match (h1, h2) {
                    (true, true) => pp::duration_hold_hold(q),
                    (false, true) => pp::duration_ramps_hold(q),
                    (true, false) => pp::duration_hold_ramps(q),
                    (false, false) => pp::duration_ramps_ramps(q),
                }
            }
        }
    }
}

/// Parameters of the closed-form coefficients ([`super::peak_polynomials`]).
#[derive(Debug, Clone, Copy)]
pub(crate) struct PeakInputs {
    pub v0: f64,
    pub a0: f64,
    pub vf: f64,
    pub af: f64,
    pub j: f64,
    /// Acceleration held by the first change (`a_max` if it starts with +J, else `a_min`).
    pub hold1: f64,
    /// Acceleration held by the second change.
    pub hold2: f64,
    pub dp: f64,
    pub t: f64,
    /// Sign of the first change's first jerk.
    pub s1: f64,
    /// Sign of the second change's first jerk.
    pub s2: f64,
    /// `R = √(x² + y²)` when both changes are ramp pairs of the same sign.
    pub radius: f64,
}

/// Shape of both velocity changes at `vp` (first holds, first jerk sign, second holds, second
/// jerk sign) and the residual `kind` there (the guard value of the window's polynomial).
#[inline(always)]
fn shape(d: &Dof, vp: f64, kind: PeakResidual) -> Option<(bool, f64, bool, f64, f64)> {
    let (c1, c2) = peak_parts(d, vp)?;
    // Exactly the arithmetic of `peak_distance`.
    let dist = c1.distance(d.v0, d.a0) + c2.distance(vp, 0.0);
    let tt = c1.duration() + c2.duration();
    let y = match kind {
        PeakResidual::Distance { dp } => dist - dp,
        PeakResidual::CruiseDistance { dp, t } => dist + vp * (t - tt) - dp,
        PeakResidual::Duration { t } => tt - t,
    };
    Some((c1.t2 > 0.0, c1.j1.signum(), c2.t2 > 0.0, c2.j1.signum(), y))
}

/// Fallback sampling density of a window.
const PEAK_SAMPLES: usize = 6;

/// Roots of a peak-family residual `f(v_p)` on one window `[l, r]` between break points (see the
/// module documentation). `density` multiplies the samples of the fallback scan; `set` says
/// whether every root is needed or any one will do (see [`RootSet`]; only the closed forms
/// make use of it).
#[allow(clippy::too_many_arguments)]
pub(crate) fn scan_peak_window<F: FnMut(f64) -> f64>(
    d: &Dof,
    f: &mut F,
    l: f64,
    r: f64,
    density: usize,
    kind: PeakResidual,
    set: RootSet,
    out: &mut Roots,
) {
    let w = r - l;
    if w.is_nan() || w <= 0.0 {
        scan(f, l, r, 1, out);
        return;
    }
    if density == 1 && polynomial_window(d, f, l, r, kind, set, out) {
        return;
    }
    let scale = d.a_max.max(-d.a_min).powi(2) / d.j;
    let samples = if scale > 0.0 {
        ((w / scale) * 2.0 * density as f64)
            .ceil()
            .clamp((PEAK_SAMPLES * density) as f64, (48 * density) as f64) as usize
    } else {
        PEAK_SAMPLES * density
    };
    scan(f, l, r, samples, out);
}

/// The polynomial solution of one window; `false` if the window needs sampling.
fn polynomial_window<F: FnMut(f64) -> f64>(
    d: &Dof,
    f: &mut F,
    l: f64,
    r: f64,
    kind: PeakResidual,
    set: RootSet,
    out: &mut Roots,
) -> bool {
    // The shape at the window's midpoint, and the residual there, which guards the closed
    // form (see `closed_form_roots_checked`).
    let vp_mid = 0.5 * (l + r);
    let Some((h1, s1, h2, s2, y_mid)) = shape(d, vp_mid, kind) else {
        return false;
    };
    let mut q = PeakInputs {
        v0: d.v0,
        a0: d.a0,
        vf: d.vf,
        af: d.af,
        j: d.j,
        hold1: if s1 > 0.0 { d.a_max } else { d.a_min },
        hold2: if s2 > 0.0 { d.a_max } else { d.a_min },
        dp: 0.0,
        t: 0.0,
        s1,
        s2,
        radius: 0.0,
    };
    if !h1 && !h2 && s1 == s2 {
        let k = s1 * d.j * (d.vf - d.v0) + 0.5 * (d.a0 * d.a0 + d.af * d.af);
        if k.is_nan() || k <= 0.0 {
            return false;
        }
        q.radius = k.sqrt();
    }
    let (deg, coef) = kind.coefficients(h1, h2, &mut q);
    let j = d.j;
    let (v0, a0, vf, af) = (d.v0, d.a0, d.vf, d.af);
    let ([deg_hh, deg_one, deg_two], mult) = kind.degrees();
    let x_of = |vp: f64| (s1 * j * (vp - v0) + 0.5 * a0 * a0).max(0.0).sqrt();
    let y_of = |vp: f64| (s2 * j * (vf - vp) + 0.5 * af * af).max(0.0).sqrt();
    let vp_of_x = |x: f64| v0 + s1 * (x * x - 0.5 * a0 * a0) / j;
    let vp_of_y = |y: f64| vf - s2 * (y * y - 0.5 * af * af) / j;
    let mut roots = Roots::new();
    match (h1, h2) {
        (true, true) => {
            let check = Some((vp_mid, y_mid));
            if !closed_form_roots_checked(deg, &coef, f, l, r, check, set, &mut roots)
                && !polynomial_roots(f, l, r, deg_hh, &mut roots)
            {
                return false;
            }
            for &vp in roots.as_slice() {
                out.push(vp);
            }
        }
        (false, true) => {
            let (xl, xr) = (x_of(l), x_of(r));
            let mut g = |x: f64| f(vp_of_x(x));
            let (lo, hi) = (xl.min(xr), xl.max(xr));
            let check = Some((x_of(vp_mid), y_mid));
            if !closed_form_roots_checked(deg, &coef, &mut g, lo, hi, check, set, &mut roots)
                && !polynomial_roots(&mut g, lo, hi, deg_one, &mut roots)
            {
                return false;
            }
            for &x in roots.as_slice() {
                out.push(vp_of_x(x).clamp(l, r));
            }
        }
        (true, false) => {
            let (yl, yr) = (y_of(l), y_of(r));
            let mut g = |y: f64| f(vp_of_y(y));
            let (lo, hi) = (yl.min(yr), yl.max(yr));
            let check = Some((y_of(vp_mid), y_mid));
            if !closed_form_roots_checked(deg, &coef, &mut g, lo, hi, check, set, &mut roots)
                && !polynomial_roots(&mut g, lo, hi, deg_one, &mut roots)
            {
                return false;
            }
            for &y in roots.as_slice() {
                out.push(vp_of_y(y).clamp(l, r));
            }
        }
        (false, false) if s1 == s2 => {
            // x² + y² = R²: x = R (1 − w²)/(1 + w²), y = 2 R w/(1 + w²), w = y/(R + x) ∈ [0, 1].
            let rad = q.radius;
            let w_of = |vp: f64| y_of(vp) / (rad + x_of(vp));
            let vp_of_w = |w: f64| vp_of_x(rad * (1.0 - w * w) / (1.0 + w * w));
            let (wl, wr) = (w_of(l), w_of(r));
            let (lo, hi) = (wl.min(wr), wl.max(wr));
            let (deg_same, mult_same) = if matches!(kind, PeakResidual::Duration { .. }) {
                (2, 1)
            } else {
                (6, 3)
            };
            let mut g = |w: f64| f(vp_of_w(w)) * (1.0 + w * w).powi(mult_same);
            let wm = w_of(vp_mid);
            let check = Some((wm, y_mid * (1.0 + wm * wm).powi(mult_same)));
            if !closed_form_roots_checked(deg, &coef, &mut g, lo, hi, check, set, &mut roots)
                && !polynomial_roots(&mut g, lo, hi, deg_same, &mut roots)
            {
                return false;
            }
            for &w in roots.as_slice() {
                out.push(vp_of_w(w).clamp(l, r));
            }
        }
        (false, false) => {
            // y² − x² = K, constant on the window.
            let k = s1 * j * (v0 - vf) + 0.5 * (af * af - a0 * a0);
            let u_of = |vp: f64| x_of(vp) + y_of(vp);
            let vp_of_u = |u: f64| vp_of_x(0.5 * (u - k / u));
            let (ul, ur) = (u_of(l), u_of(r));
            let (lo, hi) = (ul.min(ur), ul.max(ur));
            if lo.is_nan() || lo <= 0.0 {
                return false;
            }
            let mut g = |u: f64| f(vp_of_u(u)) * u.powi(mult);
            let um = u_of(vp_mid);
            let check = Some((um, y_mid * um.powi(mult)));
            if !closed_form_roots_checked(deg, &coef, &mut g, lo, hi, check, set, &mut roots)
                && !polynomial_roots(&mut g, lo, hi, deg_two, &mut roots)
            {
                return false;
            }
            for &u in roots.as_slice() {
                out.push(vp_of_u(u).clamp(l, r));
            }
        }
    }
    true
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::trajectory::position_time_optimal::{peak_breaks, peak_distance};
    use rand::{Rng, SeedableRng};
    use rand_chacha::ChaCha8Rng;

    /// Every root that a dense sampling finds on a window is also found by the closed forms
    /// (position equation with and without cruise, and the duration equation).
    #[test]
    fn closed_forms_find_the_roots_of_dense_sampling() {
        let mut rng = ChaCha8Rng::seed_from_u64(7);
        let mut compared = 0;
        for _ in 0..400 {
            let mut u = |a: f64, b: f64| rng.random_range(a..b);
            let (v_max, a_max, j) = (u(0.5, 4.0), u(0.5, 4.0), u(0.5, 4.0));
            let d = Dof {
                p0: 0.0,
                v0: u(-0.5, 0.5) * v_max,
                a0: u(-0.5, 0.5) * a_max,
                pf: u(-6.0, 6.0),
                vf: u(-0.5, 0.5) * v_max,
                af: u(-0.5, 0.5) * a_max,
                v_max,
                v_min: -v_max,
                a_max,
                a_min: -a_max,
                j,
            };
            let dp = d.pf - d.p0;
            let t = u(1.0, 8.0);
            let mut br = [0.0; 8];
            let nb = peak_breaks(&d, &mut br);
            for w in br[..nb].windows(2) {
                let (l, r) = (w[0], w[1]);
                let kinds = [
                    PeakResidual::Distance { dp },
                    PeakResidual::CruiseDistance { dp, t },
                    PeakResidual::Duration { t },
                ];
                for kind in kinds {
                    let mut f = |vp: f64| {
                        let (dist, tt) = peak_distance(&d, vp);
                        match kind {
                            PeakResidual::Distance { dp } => dist - dp,
                            PeakResidual::CruiseDistance { dp, t } => dist + vp * (t - tt) - dp,
                            PeakResidual::Duration { t } => tt - t,
                        }
                    };
                    let mut fast = Roots::new();
                    if !polynomial_window(&d, &mut f, l, r, kind, RootSet::All, &mut fast) {
                        continue;
                    }
                    let mut dense = Roots::new();
                    scan(&mut f, l, r, 4000, &mut dense);
                    for &x in dense.as_slice() {
                        compared += 1;
                        assert!(
                            fast.as_slice()
                                .iter()
                                .any(|&y| (x - y).abs() <= 1e-7 * (1.0 + x.abs())),
                            "{kind:?} on [{l}, {r}] of {d:?}: dense root {x}, closed forms {:?}",
                            fast.as_slice()
                        );
                    }
                }
            }
        }
        assert!(compared > 200, "{compared}");
    }
}
