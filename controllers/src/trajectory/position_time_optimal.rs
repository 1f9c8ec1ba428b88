//! Time-optimal position profiles of one DoF (the "step 1" problem).
//!
//! By Pontryagin's principle the time-optimal jerk is bang-bang (±J) except on arcs where a
//! constraint is active: a hold at an acceleration limit (jerk 0) or a cruise at a velocity limit
//! (jerk 0, acceleration 0). That gives the classical 7-phase profile
//!
//! ```text
//!   phase      1    2      3    4        5    6      7
//!   UDDU      +J   0@a+   −J   0@v,a=0  −J   0@a−   +J
//!   UDUD      +J   0@a+   −J   0@v,a=0  +J   0@a+   −J
//! ```
//!
//! and their mirror images (DUUD, DUDU). Phases may have zero length. We cover the families
//! with two parametrisations, each reduced to one scalar equation:
//!
//! * **Peak family** ([`peak_family`]): every profile whose acceleration passes through zero at
//!   the phase-4 junction (all UDDU/UDUD/DUUD/DUDU profiles with or without cruise, with or
//!   without either acceleration limit) is two time-optimal velocity changes
//!   `(v0, a0) → (v_p, 0) → (vf, af)` ([`super::vel_change`]) joined at a peak velocity `v_p`.
//!   The position equation `D(v_p) = Δp` is piecewise smooth in `v_p` with known break points
//!   (where a part changes direction or starts to hold its acceleration limit); all its roots on
//!   `[v_min, v_max]` are candidates. If `D(v_max) < Δp` a cruise at `v_max` of length
//!   `(Δp − D(v_max))/v_max` closes the gap (likewise at `v_min`).
//! * **Three-arc family** ([`three_arc_family`]): UDDU profiles with `t4 = 0` whose
//!   acceleration does not change sign between phases 3 and 5 (`+J, [0@a+], −J, [0@a−], +J`),
//!   parametrised by the ramp `s = a1 − a2` (no limit: the velocity equation gives
//!   `a1² − a2² = K`, so `a1 = (s + K/s)/2`, `a2 = (K/s − s)/2`), by `a2` (phase 2 at `a+`, its
//!   length linear in `a2²` from the velocity equation) or by `a1` (phase 6 at `a−`). The
//!   residual is again the position equation, solved in the problem's frame and its mirror.
//!
//! Roots are found as polynomial roots on every smooth window ([`super::peak_window`]) or,
//! where the family is not polynomial in one variable, by [`super::roots::scan`]; each candidate is integrated and verified
//! ([`Dof::check`]). The shortest valid one is time-optimal; the other valid durations are
//! kept, since they bound the blocked intervals used by synchronisation.

use super::dof::{Dof, Segments};
use super::peak_polynomials as pp;
use super::peak_window::{PeakResidual, scan_peak_window};
use super::polynomial::{RootSet, closed_form_roots, polynomial_roots};
use super::profile::{Profile, integrate};
use super::roots::{Roots, scan};
use super::vel_change::{VelChange, vel_change};

/// Maximum number of distinct valid candidates kept.
pub(crate) const MAX_CANDIDATES: usize = 12;

/// Samples for the three-arc families.
const ARC_SAMPLES: usize = 10;

/// The valid candidates of one DoF, sorted by duration.
#[derive(Debug, Clone, Copy)]
pub(crate) struct TimeOptimal {
    pub n: usize,
    pub duration: [f64; MAX_CANDIDATES],
    pub segs: [Segments; MAX_CANDIDATES],
    pub dir: [f64; MAX_CANDIDATES],
}

impl TimeOptimal {
    pub fn new() -> Self {
        Self {
            n: 0,
            duration: [0.0; MAX_CANDIDATES],
            segs: [Segments::default(); MAX_CANDIDATES],
            dir: [1.0; MAX_CANDIDATES],
        }
    }

    /// Verifies a candidate and inserts it sorted by duration (duplicates within 1e-12 dropped).
    fn offer(&mut self, dof: &Dof, prefix: &Profile, segs: &Segments, dir: f64) {
        let d = segs.duration();
        for k in 0..self.n {
            if (self.duration[k] - d).abs() <= 1e-12 * (1.0 + d) {
                return;
            }
        }
        if self.n == MAX_CANDIDATES && d >= self.duration[self.n - 1] {
            return;
        }
        if !dof.check(prefix, segs, dir) {
            return;
        }
        self.insert(d, segs, dir);
    }

    /// Adds the (already verified) candidates of `other` that are not yet present.
    pub fn merge(&mut self, other: &Self) {
        for k in 0..other.n {
            let d = other.duration[k];
            if self.duration[..self.n]
                .iter()
                .any(|&x| (x - d).abs() <= 1e-12 * (1.0 + d))
            {
                continue;
            }
            if self.n == MAX_CANDIDATES && d >= self.duration[self.n - 1] {
                continue;
            }
            self.insert(d, &other.segs[k], other.dir[k]);
        }
    }

    /// Inserts a verified candidate of duration `d`, keeping the list sorted.
    fn insert(&mut self, d: f64, segs: &Segments, dir: f64) {
        let mut k = self.n.min(MAX_CANDIDATES - 1);
        if self.n < MAX_CANDIDATES {
            self.n += 1;
        }
        while k > 0 && self.duration[k - 1] > d {
            self.duration[k] = self.duration[k - 1];
            self.segs[k] = self.segs[k - 1];
            self.dir[k] = self.dir[k - 1];
            k -= 1;
        }
        self.duration[k] = d;
        self.segs[k] = *segs;
        self.dir[k] = dir;
    }

    /// The candidate `k` as a full profile on top of `prefix`, written to `out`.
    pub fn profile_into(&self, prefix: &Profile, k: usize, out: &mut Profile) {
        self.segs[k].append_to(prefix, self.dir[k], out);
    }
}

/// Pushes a velocity change's three segments.
fn push_change(s: &mut Segments, c: &VelChange, scale: f64) -> bool {
    s.push(c.t1, c.j1, scale) && s.push(c.t2, 0.0, scale) && s.push(c.t3, c.j3, scale)
}

/// The two velocity changes of the peak family at peak velocity `vp`.
#[inline(always)]
pub(crate) fn peak_parts(d: &Dof, vp: f64) -> Option<(VelChange, VelChange)> {
    let c1 = vel_change(d.v0, d.a0, vp, 0.0, d.a_max, d.a_min, d.j)?;
    let c2 = vel_change(vp, 0.0, d.vf, d.af, d.a_max, d.a_min, d.j)?;
    Some((c1, c2))
}

/// Distance covered by the two parts at peak velocity `vp` (NaN if a part is impossible).
#[inline(always)]
pub(crate) fn peak_distance(d: &Dof, vp: f64) -> (f64, f64) {
    match peak_parts(d, vp) {
        Some((c1, c2)) => (
            c1.distance(d.v0, d.a0) + c2.distance(vp, 0.0),
            c1.duration() + c2.duration(),
        ),
        None => (f64::NAN, f64::NAN),
    }
}

/// Sorted break points of the peak family's residual inside `[v_min, v_max]` (both included).
pub(crate) fn peak_breaks(d: &Dof, out: &mut [f64; 8]) -> usize {
    let j = d.j;
    let cands = [
        d.v0 + d.a0 * d.a0.abs() / (2.0 * j),
        d.v0 + (d.a_max * d.a_max - 0.5 * d.a0 * d.a0) / j,
        d.v0 - (d.a_min * d.a_min - 0.5 * d.a0 * d.a0) / j,
        d.vf - d.af * d.af.abs() / (2.0 * j),
        d.vf - (d.a_max * d.a_max - 0.5 * d.af * d.af) / j,
        d.vf + (d.a_min * d.a_min - 0.5 * d.af * d.af) / j,
    ];
    out[0] = d.v_min;
    let mut n = 1;
    for c in cands {
        if c > d.v_min && c < d.v_max && c.is_finite() {
            out[n] = c;
            n += 1;
        }
    }
    out[n] = d.v_max;
    n += 1;
    // insertion sort
    for i in 1..n {
        let mut k = i;
        while k > 0 && out[k - 1] > out[k] {
            out.swap(k - 1, k);
            k -= 1;
        }
    }
    n
}

/// Segments of a peak-family profile with an optional cruise.
pub(crate) fn peak_segments(
    c1: &VelChange,
    cruise: f64,
    c2: &VelChange,
    scale: f64,
) -> Option<Segments> {
    let mut s = Segments::default();
    (push_change(&mut s, c1, scale) && s.push(cruise, 0.0, scale) && push_change(&mut s, c2, scale))
        .then_some(s)
}

/// Whether no peak-family profile with its peak in the window `[l, r]` covers the distance
/// `dp` (then the window holds no root of the position equation and is skipped): `(T₁, T₂)` at
/// `l` and `r` are the durations of the two velocity changes there.
///
/// On a window each change keeps its shape, so `T₁` and `T₂` are monotone there (affine in
/// `v_p` when a change holds its acceleration limit, affine in `x` or `y` for a ramp pair; see
/// [`super::peak_window`]) and `T = T₁ + T₂` lies between the sums of their smaller and of
/// their larger end values. The velocity of the first change stays between
/// `v₀ ± a₀²/(2J)` and `v_p` (its acceleration passes through zero at most once before the
/// end, after a ramp of `|a₀|/J`), that of the second between `v_p` and `v_f ± a_f²/(2J)`;
/// so `v_lo ≤ v ≤ v_hi` throughout, and the distance `D = ∫ v dt` lies between `v_lo T` and
/// `v_hi T`. Outside that range (with a relative margin of 1e-9 for rounding) there is no
/// root. On the benchmark's cases this skips most windows of long moves, whose shortest
/// profile cruises at the velocity limit.
fn distance_excluded(d: &Dof, dp: f64, l: f64, r: f64, at_l: (f64, f64), at_r: (f64, f64)) -> bool {
    let (d_lo, d_hi, scale) = distance_range(d, l, r, at_l, at_r);
    let margin = 1e-9 * (dp.abs() + scale) + 1e-12;
    // NaN durations (a change impossible at an end) compare false: not excluded.
    dp > d_hi + margin || dp < d_lo - margin
}

/// The range `[D_lo, D_hi]` of the distance of the peak-family profiles with their peak in
/// `[l, r]` (see [`distance_excluded`]), and the scale of the bound (`max |v| · T_max`).
fn distance_range(
    d: &Dof,
    l: f64,
    r: f64,
    (t1l, t2l): (f64, f64),
    (t1r, t2r): (f64, f64),
) -> (f64, f64, f64) {
    let t_lo = t1l.min(t1r) + t2l.min(t2r);
    let t_hi = t1l.max(t1r) + t2l.max(t2r);
    let ov0 = d.a0 * d.a0 / (2.0 * d.j);
    let ovf = d.af * d.af / (2.0 * d.j);
    let v_lo = (d.v0 - ov0).min(l).min(d.vf - ovf);
    let v_hi = (d.v0 + ov0).max(r).max(d.vf + ovf);
    let d_lo = (v_lo * t_lo).min(v_lo * t_hi);
    let d_hi = (v_hi * t_lo).max(v_hi * t_hi);
    (d_lo, d_hi, v_lo.abs().max(v_hi.abs()) * t_hi.abs())
}

/// Peak family (see the module documentation).
fn peak_family(d: &Dof, prefix: &Profile, density: usize, out: &mut TimeOptimal) {
    let dp = d.pf - d.p0;
    let scale = 1.0;
    let mut f = |vp: f64| peak_distance(d, vp).0 - dp;
    let mut br = [0.0; 8];
    let nb = peak_breaks(d, &mut br);
    // The durations of both velocity changes at the break points, for the distance bound.
    let mut parts = [(f64::NAN, f64::NAN); 8];
    if density == 1 {
        for (p, &vp) in parts.iter_mut().zip(&br[..nb]) {
            if let Some((c1, c2)) = peak_parts(d, vp) {
                *p = (c1.duration(), c2.duration());
            }
        }
    }
    let mut roots = Roots::new();
    for (k, w) in br[..nb].windows(2).enumerate() {
        if density == 1 && distance_excluded(d, dp, w[0], w[1], parts[k], parts[k + 1]) {
            continue;
        }
        scan_peak_window(
            d,
            &mut f,
            w[0],
            w[1],
            density,
            PeakResidual::Distance { dp },
            RootSet::All,
            &mut roots,
        );
    }
    for &vp in roots.as_slice() {
        if let Some((c1, c2)) = peak_parts(d, vp)
            && let Some(s) = peak_segments(&c1, 0.0, &c2, scale)
        {
            out.offer(d, prefix, &s, 1.0);
        }
    }
    // Cruise at a velocity limit.
    for vc in [d.v_max, d.v_min] {
        if vc == 0.0 {
            continue;
        }
        if let Some((c1, c2)) = peak_parts(d, vc) {
            let dist = c1.distance(d.v0, d.a0) + c2.distance(vc, 0.0);
            let tc = (dp - dist) / vc;
            if tc > 0.0
                && let Some(s) = peak_segments(&c1, tc, &c2, scale)
            {
                out.offer(d, prefix, &s, 1.0);
            }
        }
    }
}

/// Parameters of the three-arc family's closed-form coefficients
/// ([`super::peak_polynomials`]), in the frame being solved.
#[derive(Debug, Clone, Copy)]
pub(crate) struct ArcInputs {
    pub v0: f64,
    pub a0: f64,
    pub af: f64,
    pub j: f64,
    pub a_max: f64,
    pub a_min: f64,
    /// `vf − v0`.
    pub dv: f64,
    /// `K = J Δv + (a0² − af²)/2` of the unlimited variant.
    pub k: f64,
    /// `pf − p0`.
    pub dp: f64,
}

/// Integrates signed-duration segments from `(0, v0, a0)`; returns the position reached.
#[inline]
fn reach(v0: f64, a0: f64, segs: &[(f64, f64)]) -> f64 {
    let (mut p, mut v, mut a) = (0.0, v0, a0);
    for &(t, j) in segs {
        (p, v, a) = integrate(p, v, a, j, t);
    }
    let _ = (v, a);
    p
}

/// Three-arc family in the frame of `d` (call with the mirror image for DUUD shapes).
///
/// Only the profiles whose acceleration keeps its sign between phases 1 and 7 are new here (the
/// others pass through a = 0 and belong to the peak family), so: the unlimited variant needs
/// `a2 > 0` (hence `af > 0`) or `a1 < 0` (hence `a0 < 0`); the `a+`-hold variant needs
/// `0 ≤ a2 ≤ af`; the `a−`-hold variant needs `a0 ≤ a1 ≤ 0`. The scans are restricted
/// accordingly.
fn three_arc_family(
    orig: &Dof,
    d: &Dof,
    prefix: &Profile,
    dir: f64,
    density: usize,
    out: &mut TimeOptimal,
) {
    let arc_samples = ARC_SAMPLES * density;
    let j = d.j;
    let dp = d.pf - d.p0;
    let dv = d.vf - d.v0;
    let (a0, af, amax, amin) = (d.a0, d.af, d.a_max, d.a_min);
    let scale = 1.0;

    // (1) no acceleration limit: +J (a0→a1), −J (a1→a2), +J (a2→af), a1² − a2² = K.
    let k = j * dv + 0.5 * (a0 * a0 - af * af);
    let q = ArcInputs {
        v0: d.v0,
        a0,
        af,
        j,
        a_max: amax,
        a_min: amin,
        dv,
        k,
        dp,
    };
    let disc1 = amax * amax - k;
    let disc2 = amin * amin + k;
    if disc1 >= 0.0 && disc2 >= 0.0 && (af > 0.0 || a0 < 0.0) {
        let lo = (amax - disc1.sqrt())
            .max(-amin - disc2.sqrt())
            .max(1e-9 * (amax - amin));
        let hi = (amax + disc1.sqrt()).min(-amin + disc2.sqrt());
        let times = |s: f64| {
            let a1 = 0.5 * (s + k / s);
            let a2 = 0.5 * (k / s - s);
            ((a1 - a0) / j, s / j, (af - a2) / j)
        };
        let mut f = |s: f64| {
            let (t1, t2, t3) = times(s);
            reach(d.v0, a0, &[(t1, j), (t2, -j), (t3, j)]) - dp
        };
        let mut roots = Roots::new();
        // r·s is a quartic in s (the times are linear in s and K/s).
        let mut g = |s: f64| f(s) * s;
        let (n, c) = pp::arc_free(&q);
        if density > 1
            || !(closed_form_roots(n, &c, &mut g, lo, hi, &mut roots)
                || polynomial_roots(&mut g, lo, hi, 4, &mut roots))
        {
            scan(&mut f, lo, hi, arc_samples, &mut roots);
        }
        for &s in roots.as_slice() {
            let (t1, t2, t3) = times(s);
            let mut sg = Segments::default();
            if sg.push(t1, j, scale) && sg.push(t2, -j, scale) && sg.push(t3, j, scale) {
                out.offer(orig, prefix, &sg, dir);
            }
        }
    }

    // (2) phase 2 at a_max: +J (a0→amax), hold t2, −J (amax→a2), +J (a2→af).
    // The hold t2(a2) = (Δv − (2 a+² − a0² − 2 a2² + af²)/(2J))/a+ grows with a2², so its
    // largest value on the range is at the largest a2²; if even that is negative (beyond the
    // rounding of the formula), every root would be rejected by `Segments::push`: skip.
    let hold_max_range = |lo: f64, hi: f64| lo.abs().max(hi.abs()).powi(2);
    let feasible_hold = |num: f64, terms: f64, hold: f64| {
        let t = num / hold;
        t >= -1e-9 * (1.0 + terms / hold.abs())
    };
    let (lo2, hi2) = (-1e-12 * amax, af.min(amax));
    let x2 = hold_max_range(lo2, hi2);
    if amax > 0.0
        && af > 0.0
        && feasible_hold(
            dv - (2.0 * amax * amax - a0 * a0 - 2.0 * x2 + af * af) / (2.0 * j),
            dv.abs() + (2.0 * amax * amax + a0 * a0 + 2.0 * x2 + af * af) / (2.0 * j),
            amax,
        )
    {
        let times = |a2: f64| {
            let t2 =
                (dv - (2.0 * amax * amax - a0 * a0 - 2.0 * a2 * a2 + af * af) / (2.0 * j)) / amax;
            ((amax - a0) / j, t2, (amax - a2) / j, (af - a2) / j)
        };
        let mut f = |a2: f64| {
            let (t1, t2, t3, t4) = times(a2);
            reach(d.v0, a0, &[(t1, j), (t2, 0.0), (t3, -j), (t4, j)]) - dp
        };
        let mut roots = Roots::new();
        // A quartic in a2 (the hold is quadratic in a2, the ramps linear).
        let (lo, hi) = (lo2, hi2);
        let (n, c) = pp::arc_hold_max(&q);
        if density > 1
            || !(closed_form_roots(n, &c, &mut f, lo, hi, &mut roots)
                || polynomial_roots(&mut f, lo, hi, 4, &mut roots))
        {
            scan(&mut f, lo, hi, arc_samples, &mut roots);
        }
        for &a2 in roots.as_slice() {
            let (t1, t2, t3, t4) = times(a2);
            let mut sg = Segments::default();
            if sg.push(t1, j, scale)
                && sg.push(t2, 0.0, scale)
                && sg.push(t3, -j, scale)
                && sg.push(t4, j, scale)
            {
                out.offer(orig, prefix, &sg, dir);
            }
        }
    }

    // (3) phase 6 at a_min: +J (a0→a1), −J (a1→amin), hold t6, +J (amin→af).
    // Likewise t6(a1) = (Δv − (2 a1² − a0² − 2 a−² + af²)/(2J))/a− (a− < 0) grows with a1².
    let (lo3, hi3) = (a0.max(amin), -1e-12 * amin);
    let x3 = hold_max_range(lo3, hi3);
    if amin < 0.0
        && a0 < 0.0
        && feasible_hold(
            dv - (2.0 * x3 - a0 * a0 - 2.0 * amin * amin + af * af) / (2.0 * j),
            dv.abs() + (2.0 * x3 + a0 * a0 + 2.0 * amin * amin + af * af) / (2.0 * j),
            amin,
        )
    {
        let times = |a1: f64| {
            let t6 =
                (dv - (2.0 * a1 * a1 - a0 * a0 - 2.0 * amin * amin + af * af) / (2.0 * j)) / amin;
            ((a1 - a0) / j, (a1 - amin) / j, t6, (af - amin) / j)
        };
        let mut f = |a1: f64| {
            let (t1, t2, t3, t4) = times(a1);
            reach(d.v0, a0, &[(t1, j), (t2, -j), (t3, 0.0), (t4, j)]) - dp
        };
        let mut roots = Roots::new();
        let (lo, hi) = (lo3, hi3);
        let (n, c) = pp::arc_hold_min(&q);
        if density > 1
            || !(closed_form_roots(n, &c, &mut f, lo, hi, &mut roots)
                || polynomial_roots(&mut f, lo, hi, 4, &mut roots))
        {
            scan(&mut f, lo, hi, arc_samples, &mut roots);
        }
        for &a1 in roots.as_slice() {
            let (t1, t2, t3, t4) = times(a1);
            let mut sg = Segments::default();
            if sg.push(t1, j, scale)
                && sg.push(t2, -j, scale)
                && sg.push(t3, 0.0, scale)
                && sg.push(t4, j, scale)
            {
                out.offer(orig, prefix, &sg, dir);
            }
        }
    }
}

/// All valid extremal candidates of the position problem `d` (start state inside the limits),
/// appended on top of the braking `prefix`.
/// `density` multiplies the number of samples of every scan (1 normally; larger to recover an
/// extremal profile missed between samples, see the calculator).
pub(crate) fn time_optimal(d: &Dof, prefix: &Profile, density: usize) -> TimeOptimal {
    let mut out = TimeOptimal::new();
    time_optimal_into(d, prefix, density, &mut out);
    out
}

/// [`time_optimal`] written to `out` (which is cleared first), without moving the result.
pub(crate) fn time_optimal_into(d: &Dof, prefix: &Profile, density: usize, out: &mut TimeOptimal) {
    out.n = 0;
    if d.at_target() {
        out.offer(d, prefix, &Segments::default(), 1.0);
        return;
    }
    if d.j <= 0.0 {
        return;
    }
    peak_family(d, prefix, density, out);
    three_arc_family(d, d, prefix, 1.0, density, out);
    three_arc_family(d, &d.mirrored(), prefix, -1.0, density, out);
}

#[cfg(test)]
mod tests {
    use super::*;
    use rand::{Rng, SeedableRng};
    use rand_chacha::ChaCha8Rng;

    /// The distance bound of [`distance_excluded`] holds on every window: 400 random problems
    /// (asymmetric limits, states anywhere inside them), 200 peaks per window, every distance
    /// of the peak family inside `[D_lo, D_hi]` up to rounding.
    #[test]
    fn distance_range_bounds_every_window() {
        let mut rng = ChaCha8Rng::seed_from_u64(5);
        let mut checked = 0;
        for _ in 0..400 {
            let mut u = |a: f64, b: f64| rng.random_range(a..b);
            let (v_max, v_min) = (u(0.1, 12.0), -u(0.1, 12.0));
            let (a_max, a_min) = (u(0.1, 12.0), -u(0.1, 12.0));
            let d = Dof {
                p0: 0.0,
                v0: u(v_min, v_max),
                a0: u(a_min, a_max),
                pf: u(-6.0, 6.0),
                vf: u(v_min, v_max),
                af: u(a_min, a_max),
                v_max,
                v_min,
                a_max,
                a_min,
                j: u(0.1, 12.0),
            };
            let mut br = [0.0; 8];
            let nb = peak_breaks(&d, &mut br);
            let durations = |vp: f64| {
                peak_parts(&d, vp).map_or((f64::NAN, f64::NAN), |(c1, c2)| {
                    (c1.duration(), c2.duration())
                })
            };
            for w in br[..nb].windows(2) {
                let (l, r) = (w[0], w[1]);
                let (d_lo, d_hi, scale) = distance_range(&d, l, r, durations(l), durations(r));
                if !(d_lo.is_finite() && d_hi.is_finite()) {
                    continue;
                }
                for k in 0..=200 {
                    let vp = l + (r - l) * k as f64 / 200.0;
                    let (dist, _) = peak_distance(&d, vp);
                    if dist.is_nan() {
                        continue;
                    }
                    let tol = 1e-12 * (1.0 + scale);
                    assert!(
                        dist >= d_lo - tol && dist <= d_hi + tol,
                        "{dist} outside [{d_lo}, {d_hi}] at v_p = {vp} in [{l}, {r}] of {d:?}"
                    );
                    checked += 1;
                }
            }
        }
        assert!(checked > 100_000, "{checked}");
    }
}
