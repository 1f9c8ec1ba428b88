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

use core::cell::Cell;

use super::dof::{Dof, Segments};
use super::peak_polynomials as pp;
use super::peak_window::{PeakResidual, scan_peak_window};
use super::polynomial::{RootSet, closed_form_roots, polynomial_roots};
use super::profile::{Profile, integrate};
use super::roots::{Roots, scan};
use super::vel_change::{VelChange, vel_change_at_rest_end};

/// Maximum number of distinct valid candidates kept.
pub(crate) const MAX_CANDIDATES: usize = 12;

/// Samples for the three-arc families.
const ARC_SAMPLES: usize = 10;

/// What a time-optimal search must find.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum Search {
    /// Every valid extremal profile (their durations bound the blocked intervals that time
    /// synchronisation needs).
    All,
    /// The shortest valid profile only (one DoF on its own, or a DoF whose minimal duration is
    /// all the synchronisation asks for): the closed-form cruise profile is tried first and
    /// ends the search when it is provably time-optimal ([`cruise_is_time_optimal`]), so does
    /// a provably time-optimal peak-family profile ([`peak_is_time_optimal`]), and every
    /// family or window whose duration lower bound is not below the shortest profile found so
    /// far is skipped.
    Shortest,
}

/// The valid candidates of one DoF, sorted by duration.
#[derive(Debug, Clone, Copy)]
pub(crate) struct TimeOptimal {
    pub n: usize,
    pub duration: [f64; MAX_CANDIDATES],
    pub segs: [Segments; MAX_CANDIDATES],
    pub dir: [f64; MAX_CANDIDATES],
    /// Only the shortest candidate is wanted ([`Search::Shortest`]).
    shortest: bool,
}

impl TimeOptimal {
    pub fn new() -> Self {
        Self {
            n: 0,
            duration: [0.0; MAX_CANDIDATES],
            segs: [Segments::default(); MAX_CANDIDATES],
            dir: [1.0; MAX_CANDIDATES],
            shortest: false,
        }
    }

    /// Whether a family or window whose profiles all last at least `lower_bound` can be
    /// skipped: only the shortest profile is wanted and one no longer than that bound is
    /// already known. (A profile of that family would be at least as long: at most equal
    /// within the 1e-12 of the duplicate test, and then it would be dropped by [`Self::offer`].)
    #[inline]
    fn beaten(&self, lower_bound: f64) -> bool {
        self.shortest && self.n > 0 && lower_bound >= self.duration[0]
    }

    /// Verifies a candidate and inserts it sorted by duration (duplicates within 1e-12 dropped).
    /// With [`Search::Shortest`] a candidate not shorter than the best one is not verified.
    ///
    /// Returns `false` only if the candidate was checked and failed the verification (a
    /// candidate that is beaten, a duplicate or too long to keep is not checked: `true`).
    fn offer(&mut self, dof: &Dof, prefix: &Profile, segs: &Segments, dir: f64) -> bool {
        let d = segs.duration();
        if self.beaten(d) {
            return true;
        }
        for k in 0..self.n {
            if (self.duration[k] - d).abs() <= 1e-12 * (1.0 + d) {
                return true;
            }
        }
        if self.n == MAX_CANDIDATES && d >= self.duration[self.n - 1] {
            return true;
        }
        if !dof.check(prefix, segs, dir) {
            return false;
        }
        self.insert(d, segs, dir);
        true
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
    // Exactly `vel_change` of both parts, computing one shape each where only one can be
    // valid (the direction breaks of `peak_direction_breaks`).
    let (v_stop1, v_stop2) = peak_direction_breaks(d);
    let c1 = vel_change_at_rest_end(d.v0, d.a0, vp, 0.0, d.a_max, d.a_min, d.j, true, v_stop1)?;
    let c2 = vel_change_at_rest_end(vp, 0.0, d.vf, d.af, d.a_max, d.a_min, d.j, false, v_stop2)?;
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
    let (v_stop1, v_stop2) = peak_direction_breaks(d);
    let cands = [
        v_stop1,
        d.v0 + (d.a_max * d.a_max - 0.5 * d.a0 * d.a0) / j,
        d.v0 - (d.a_min * d.a_min - 0.5 * d.a0 * d.a0) / j,
        v_stop2,
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
///
/// `t_cap`: only profiles not longer than this matter (the shortest profile found so far by a
/// shortest-only search, else +∞); the durations above it are left out of the range.
fn distance_excluded(
    d: &Dof,
    dp: f64,
    (l, r): (f64, f64),
    at_l: (f64, f64),
    at_r: (f64, f64),
    t_cap: f64,
) -> bool {
    let (d_lo, d_hi, scale) = distance_range(d, l, r, at_l, at_r, t_cap);
    let margin = 1e-9 * (dp.abs() + scale) + 1e-12;
    // NaN durations (a change impossible at an end) compare false: not excluded.
    dp > d_hi + margin || dp < d_lo - margin
}

/// The range `[D_lo, D_hi]` of the distance of the peak-family profiles with their peak in
/// `[l, r]` and a duration of at most `t_cap` (see [`distance_excluded`]), and the scale of the
/// bound (`max |v| · T_max`).
fn distance_range(
    d: &Dof,
    l: f64,
    r: f64,
    (t1l, t2l): (f64, f64),
    (t1r, t2r): (f64, f64),
    t_cap: f64,
) -> (f64, f64, f64) {
    let t_lo = nan_min(t1l, t1r) + nan_min(t2l, t2r);
    let t_hi = nan_min(nan_max(t1l, t1r) + nan_max(t2l, t2r), t_cap);
    let ov0 = ramp_out_velocity(d.a0, d.j);
    let ovf = ramp_out_velocity(d.af, d.j);
    let v_lo = (d.v0 - ov0).min(l).min(d.vf - ovf);
    let v_hi = (d.v0 + ov0).max(r).max(d.vf + ovf);
    let d_lo = nan_min(v_lo * t_lo, v_lo * t_hi);
    let d_hi = nan_max(v_hi * t_lo, v_hi * t_hi);
    (d_lo, d_hi, v_lo.abs().max(v_hi.abs()) * t_hi.abs())
}

/// A lower bound of the duration `T₁ + T₂` of the peak-family profiles (without cruise) with
/// their peak in a window, from the durations `(T₁, T₂)` of both velocity changes at the
/// window's ends: each is monotone on the window (see [`distance_excluded`]), so it is at
/// least its smaller end value. NaN (a change impossible at an end) gives NaN, which bounds
/// nothing (`beaten` is false).
fn window_min_duration((t1l, t2l): (f64, f64), (t1r, t2r): (f64, f64)) -> f64 {
    nan_min(t1l, t1r) + nan_min(t2l, t2r)
}

/// The smaller of `a` and `b`, NaN if either is (`f64::min` returns the other operand).
fn nan_min(a: f64, b: f64) -> f64 {
    if a.is_nan() || b.is_nan() {
        f64::NAN
    } else {
        a.min(b)
    }
}

/// The larger of `a` and `b`, NaN if either is (`f64::max` returns the other operand).
fn nan_max(a: f64, b: f64) -> f64 {
    if a.is_nan() || b.is_nan() {
        f64::NAN
    } else {
        a.max(b)
    }
}

/// The peak family's two velocity changes with the peak at each velocity limit, computed once
/// per search: they are the parts of the cruise profiles ([`cruises`]) and the outermost break
/// points of the peak family ([`peak_breaks`] starts at `v_min` and ends at `v_max`).
#[derive(Debug, Clone, Copy)]
pub(crate) struct LimitParts {
    /// `peak_parts(d, v_max)`.
    at_max: Option<(VelChange, VelChange)>,
    /// `peak_parts(d, v_min)`.
    at_min: Option<(VelChange, VelChange)>,
    /// Their distance (exactly `peak_distance(d, v_max).0`; NaN if they do not exist).
    dist_at_max: f64,
    /// Likewise at `v_min`.
    dist_at_min: f64,
}

impl LimitParts {
    pub fn new(d: &Dof) -> Self {
        let at_max = peak_parts(d, d.v_max);
        let at_min = peak_parts(d, d.v_min);
        let dist = |parts: Option<(VelChange, VelChange)>, vp: f64| {
            parts.map_or(f64::NAN, |(c1, c2)| {
                c1.distance(d.v0, d.a0) + c2.distance(vp, 0.0)
            })
        };
        Self {
            at_max,
            at_min,
            dist_at_max: dist(at_max, d.v_max),
            dist_at_min: dist(at_min, d.v_min),
        }
    }
}

/// Peak family (see the module documentation).
/// Returns whether a shortest-only search found a provably time-optimal profile
/// ([`peak_is_time_optimal`]) and may end.
fn peak_family(
    d: &Dof,
    prefix: &Profile,
    density: usize,
    limit_parts: &LimitParts,
    out: &mut TimeOptimal,
) -> bool {
    let dp = d.pf - d.p0;
    let scale = 1.0;
    // The residual (exactly `peak_distance(d, vp).0 - dp`), remembering the velocity changes
    // of its last evaluation: a root is usually last evaluated by its polishing, and its
    // profile is built from the same changes.
    let last = Cell::new(None::<(f64, VelChange, VelChange)>);
    let mut f = |vp: f64| match peak_parts(d, vp) {
        Some((c1, c2)) => {
            last.set(Some((vp, c1, c2)));
            c1.distance(d.v0, d.a0) + c2.distance(vp, 0.0) - dp
        }
        None => f64::NAN,
    };
    let mut br = [0.0; 8];
    let nb = peak_breaks(d, &mut br);
    // The durations of both velocity changes at the break points and the residual `D − Δp`
    // there, for the bounds below, computed when a window first needs them (a search that
    // ends early leaves the far break points alone; at the outermost ones, the velocity
    // limits, the changes are known already).
    let mut parts = [(f64::NAN, f64::NAN); 8];
    let mut residual = [f64::NAN; 8];
    let mut known = [false; 8];
    let mut at_break = |k: usize, parts: &mut [(f64, f64); 8], residual: &mut [f64; 8]| {
        if known[k] {
            return;
        }
        known[k] = true;
        let vp = br[k];
        let (changes, dist) = if k == 0 {
            (limit_parts.at_min, limit_parts.dist_at_min)
        } else if k == nb - 1 {
            (limit_parts.at_max, limit_parts.dist_at_max)
        } else {
            let changes = peak_parts(d, vp);
            // Exactly the arithmetic of `peak_distance`.
            let dist = changes.map_or(f64::NAN, |(c1, c2)| {
                c1.distance(d.v0, d.a0) + c2.distance(vp, 0.0)
            });
            (changes, dist)
        };
        if let Some((c1, c2)) = changes {
            parts[k] = (c1.duration(), c2.duration());
            residual[k] = dist - dp;
        }
    };
    let (v_stop1, v_stop2) = peak_direction_breaks(d);
    let mut roots = Roots::new();
    // The roots of each window are offered before the next window is solved, so that a
    // shortest-only search can skip the windows that cannot hold a shorter profile and end at
    // a provably time-optimal one. The windows are visited from the side of the move's
    // direction (downwards from `v_max` if `Δp > 0`, upwards from `v_min` otherwise): there
    // the distance usually increases and the windows beyond the root are skipped by the
    // residuals at their ends, and the first root found is usually the one that
    // `peak_is_time_optimal` proves. (Offering the cruise profiles first, and solving the
    // windows in the order of their duration bounds, cost more than they saved.)
    let mut offered = 0;
    let downwards = dp > 0.0;
    for step in 0..nb - 1 {
        let k = if downwards { nb - 2 - step } else { step };
        let w = [br[k], br[k + 1]];
        let t_cap = if out.shortest && out.n > 0 {
            out.duration[0]
        } else {
            f64::INFINITY
        };
        let mut set = RootSet::All;
        if density == 1 {
            at_break(k, &mut parts, &mut residual);
            at_break(k + 1, &mut parts, &mut residual);
            if out.beaten(window_min_duration(parts[k], parts[k + 1]))
                || distance_excluded(d, dp, (w[0], w[1]), parts[k], parts[k + 1], t_cap)
            {
                continue;
            }
            if distance_increasing(d, w[0], w[1], v_stop1, v_stop2) {
                let (res_l, res_r) = (residual[k], residual[k + 1]);
                let margin = residual_margin(d, dp, (w[0], w[1]), parts[k], parts[k + 1]);
                // NaN compares false throughout: neither skipped nor `Single`.
                if (res_l > margin && res_r > margin) || (res_l < -margin && res_r < -margin) {
                    continue;
                }
                if (res_l > margin && res_r < -margin) || (res_l < -margin && res_r > margin) {
                    set = RootSet::Single;
                }
            }
        }
        scan_peak_window(
            d,
            &mut f,
            w[0],
            w[1],
            density,
            PeakResidual::Distance { dp },
            set,
            &mut roots,
        );
        // Offers the roots, returning (whether one was offered and passed or was not needed,
        // whether a shortest-only search may end at it).
        let offer_roots = |found: &[f64], out: &mut TimeOptimal| {
            let mut usable = false;
            for &vp in found {
                let parts = match last.get() {
                    Some((v, c1, c2)) if v.to_bits() == vp.to_bits() => Some((c1, c2)),
                    _ => peak_parts(d, vp),
                };
                if let Some((c1, c2)) = parts
                    && let Some(s) = peak_segments(&c1, 0.0, &c2, scale)
                {
                    usable |= out.offer(d, prefix, &s, 1.0);
                    // A verified profile that is the best so far and provably time-optimal
                    // ends a shortest-only search.
                    if out.shortest
                        && density == 1
                        && out.n > 0
                        && out.duration[0].to_bits() == s.duration().to_bits()
                        && peak_is_time_optimal(d, vp, &c1, &c2, (v_stop1, v_stop2))
                    {
                        return (true, true);
                    }
                }
            }
            (usable, false)
        };
        let (usable, proven) = offer_roots(&roots.as_slice()[offered..], out);
        if proven {
            return true;
        }
        if set == RootSet::Single && !usable {
            // The single root, refined over the whole window, can sit a few ulps from the
            // one the isolating search finds and fail the verification where |Δp| is so large
            // that its tolerance is below an ulp of Δp: solve the window again in full
            // (into its own root list, where the near-equal root is not a duplicate).
            let mut again = Roots::new();
            scan_peak_window(
                d,
                &mut f,
                w[0],
                w[1],
                density,
                PeakResidual::Distance { dp },
                RootSet::All,
                &mut again,
            );
            if offer_roots(again.as_slice(), out).1 {
                return true;
            }
        }
        offered = roots.as_slice().len();
    }
    offer_cruise(d, prefix, limit_parts, out);
    false
}

/// Whether the peak-family profile `c1`, `c2` (the two time-optimal velocity changes
/// `(v0, a0) → (v_p, 0) → (vf, af)`, no cruise), once verified, is the shortest of all
/// profiles.
///
/// In the frame where `v_p > 0` (mirror otherwise) let the first change be `+J`, a hold at
/// `a_max`, `−J` and the second `−J`, a hold at `a_min`, `+J` (phases may be empty), with
/// `a₀ ≥ 0` or `v₀ + a₀²/(2J) ≤ v_p`, `a_f ≤ 0` or `v_f + a_f²/(2J) ≤ v_p`, `Δp > 0`, and
/// let the profile's velocity be negative at most on an initial and a final stretch: the
/// first change's velocity falls (while `a < 0`) and then rises to `v_p`, so it is negative
/// only on an initial stretch if `v₀ ≤ 0` or its minimum (`v₀ − a₀²/(2J)` if `a₀ < 0`, else
/// `v₀`) is `≥ 0`; likewise the second change with `v_f` and `v_f − a_f²/(2J)` (if `a_f >
/// 0`). Take any feasible trajectory `x` of duration `T < T_P = T₁ + T₂` and let `w` be its
/// largest velocity.
///
/// * `w > v_p`: the conditions give `v₀, v_f ≤ v_p`, so `x` reaches `w` inside, with `a = 0`,
///   and needs at least the time-optimal changes `(v₀, a₀) → (w, 0)` and `(w, 0) → (v_f,
///   a_f)`, `T₁(w) + T₂(w)`. Above `v_p` the first change stays `+J`-first (above its
///   direction break) and the second `−J`-first, and both last longer the higher `w` is (a
///   longer hold, or a higher ramp peak): `T ≥ T₁(w) + T₂(w) > T_P`, a contradiction.
/// * `w ≤ v_p`: the pointwise bounds of [`cruise_is_time_optimal`] hold with `v_c = v_p`
///   (their only way out, `x` exceeding `v_c`, is the case above): `v_x ≤ v₁` on the first
///   `u ≤ T₁` seconds and `v_x ≤ v₂` (the second change's velocity, aligned with the end) on
///   the last `T − u ≤ T₂`. So `∫ v_x ≤ Δp − ∫ v_P` over the stretch of `P` of length
///   `L = T_P − T > 0` between them, `[u, u + L]`, which contains the peak `T₁`, and `u`
///   may be chosen: if `L` fits into the middle part where `v_P ≥ 0`, a stretch there
///   around the peak (`v = v_p > 0`) has a positive integral; otherwise a stretch that covers
///   the whole middle part and only parts of the negative ends has an integral of at least
///   `∫ v_P = Δp > 0`. Either way `x` falls short of the target.
///
/// So no trajectory is shorter. In floating point, though, the adjacent windows of a
/// direction break `v_stop1`, `v_stop2` ([`peak_direction_breaks`]) can hold two valid roots
/// a few 1e-12 s apart, more than the duplicate test drops: within a relative 1e-9 of a
/// direction break the proof is not claimed, and the search goes on.
fn peak_is_time_optimal(
    d: &Dof,
    vp: f64,
    c1: &VelChange,
    c2: &VelChange,
    (v_stop1, v_stop2): (f64, f64),
) -> bool {
    if vp == 0.0 || vp.is_nan() {
        return false;
    }
    let near = |b: f64| (vp - b).abs() <= 1e-9 * vp.abs().max(b.abs());
    if near(v_stop1) || near(v_stop2) {
        return false;
    }
    EnvelopeFrame::of(d, vp, c1, c2).is_some_and(|e| {
        e.sign * (d.pf - d.p0) > 0.0
            && (e.min1 >= 0.0 || e.v0 <= 0.0)
            && (e.min2 >= 0.0 || e.vf <= 0.0)
    })
}

/// What both optimality proofs ([`cruise_is_time_optimal`], [`peak_is_time_optimal`]) ask of
/// the two velocity changes `c1`: `(v₀, a₀) → (v_top, 0)` and `c2`: `(v_top, 0) → (v_f, a_f)`,
/// in the frame where the top velocity `v_top` (the cruise or the peak) is positive.
struct EnvelopeFrame {
    /// The frame's sign (`v_top`'s).
    sign: f64,
    /// Start and target velocities in the frame.
    v0: f64,
    vf: f64,
    /// The lowest velocities of the first and the second change in the frame
    /// (`v₀ − a₀²/(2J)` if `a₀ < 0`, else `v₀`; `v_f − a_f²/(2J)` if `a_f > 0`, else `v_f`).
    min1: f64,
    min2: f64,
}

impl EnvelopeFrame {
    /// The frame of `v_top`, if the changes have the shapes the proofs need (the first
    /// `+J`-first with a hold at the upper acceleration limit, the second `−J`-first with a
    /// hold at the lower one, in the frame) and the start and target lie below `v_top`
    /// (`a₀ ≥ 0` or `v₀ + a₀²/(2J) ≤ v_top`, `a_f ≤ 0` or `v_f + a_f²/(2J) ≤ v_top`).
    #[inline(always)]
    fn of(d: &Dof, v_top: f64, c1: &VelChange, c2: &VelChange) -> Option<Self> {
        let s = v_top.signum();
        let (v0, a0, vf, af, j) = (s * d.v0, s * d.a0, s * d.vf, s * d.af, d.j);
        let v_top = s * v_top;
        let (hold_up, hold_down) = if s > 0.0 {
            (d.a_max, d.a_min)
        } else {
            (d.a_min, d.a_max)
        };
        let shapes = (c1.t1 == 0.0 || s * c1.j1 > 0.0)
            && (c1.t2 == 0.0 || c1.peak == hold_up)
            && (c1.t3 == 0.0 || s * c1.j3 < 0.0)
            && (c2.t1 == 0.0 || s * c2.j1 < 0.0)
            && (c2.t2 == 0.0 || c2.peak == hold_down)
            && (c2.t3 == 0.0 || s * c2.j3 > 0.0);
        let start = a0 >= 0.0 || v0 + ramp_out_velocity(a0, j) <= v_top;
        let target = af <= 0.0 || vf + ramp_out_velocity(af, j) <= v_top;
        if !(shapes && start && target) {
            return None;
        }
        let min1 = if a0 < 0.0 {
            v0 - ramp_out_velocity(a0, j)
        } else {
            v0
        };
        let min2 = if af > 0.0 {
            vf - ramp_out_velocity(af, j)
        } else {
            vf
        };
        Some(Self {
            sign: s,
            v0,
            vf,
            min1,
            min2,
        })
    }
}

/// The velocity change `a²/(2J)` while an acceleration `a` is brought to zero with the full
/// jerk `J` (in the direction of `a`): the distance from a state `(v, a)` to the velocity at
/// which it comes to rest in acceleration at once.
#[inline(always)]
fn ramp_out_velocity(a: f64, j: f64) -> f64 {
    a * a / (2.0 * j)
}

/// The peak velocities where the first and the second velocity change of the peak family
/// switch direction, `v₀ + a₀|a₀|/(2J)` and `v_f − a_f|a_f|/(2J)` (the first change starts
/// with `+J` above the first, the second change starts with `+J` below the second; both are
/// break points of [`peak_breaks`], computed with the same arithmetic).
fn peak_direction_breaks(d: &Dof) -> (f64, f64) {
    (
        d.v0 + d.a0 * d.a0.abs() / (2.0 * d.j),
        d.vf - d.af * d.af.abs() / (2.0 * d.j),
    )
}

/// Whether the peak family's distance `D(v_p)` is strictly increasing on the window `[l, r]`.
///
/// Let `X`, `Y > 0` be the peak acceleration magnitudes of the two changes (the held limit, or
/// the ramp peaks `x`, `y` of [`super::peak_window`]) and `s₁`, `s₂` the signs of their first
/// jerks. For the first change `(v₀, a₀) → (v_p, 0)`, `dD₁/dv_p = s₁ (v_p + s₁ X²/(2J))/X`:
/// with `s₁ = +1` and a hold, raising `v_p` by `δ` lengthens the hold by `δ/X` at the
/// velocity `v_p − X²/(2J)` and raises the final ramp (`X/J` long) by `δ`, so the derivative
/// is `(v_p − X²/(2J))/X + X/J`; a ramp pair gives the same with `x` (`t₁ = (x − a₀)/J`,
/// `t₃ = x/J`, `dD₁/dx = 2(v_p + x²/(2J))/J`, `dx/dv_p = J/(2x)`); `s₁ = −1` is the mirror
/// image. The second change read backwards in time is a first change from `(v_f, −a_f)` to
/// `(v_p, 0)` with the opposite sign and the same distance, so `dD₂/dv_p = −s₂ (v_p − s₂
/// Y²/(2J))/Y`. Together
///
/// ```text
///   dD/dv_p = s₁ v_p/X − s₂ v_p/Y + (X + Y)/(2J),
/// ```
///
/// positive where `s₁ = +1, s₂ = −1, v_p ≥ 0` or `s₁ = −1, s₂ = +1, v_p ≤ 0`. Where `v_p` has
/// the other sign, it is positive as long as `|v_p| < XY/(2J)` (`(X + Y)/(2J) > |v_p|
/// (1/X + 1/Y)`). On a window both signs are constant (`v_stop1`, `v_stop2` from
/// [`peak_direction_breaks`] are break points): `s₁ = +1` above `v_stop1`, `s₂ = +1` below
/// `v_stop2`. With `s₁ = +1, s₂ = −1`, `X = min(√(J (v_p − v₀) + a₀²/2), a_max)` and `Y =
/// min(√(J (v_p − v_f) + a_f²/2), −a_min)` both grow with `v_p`, so on the part `v_p < 0`
/// of a window `[l, r]`, `XY ≥ X(l) Y(l)`, and `2J |l| < X(l) Y(l)` (with a relative margin
/// of 1e-9 for rounding) makes the derivative positive there; the mirror image for `s₁ =
/// −1, s₂ = +1` uses the end `r`.
fn distance_increasing(d: &Dof, l: f64, r: f64, v_stop1: f64, v_stop2: f64) -> bool {
    let mid = 0.5 * (l + r);
    let (up1, up2) = (mid > v_stop1, mid < v_stop2);
    if up1 == up2 {
        return false;
    }
    // The end where |v_p| is largest on the side of the "wrong" sign.
    let (v, hold) = if up1 {
        if l >= 0.0 {
            return true;
        }
        (l, (d.a_max, -d.a_min))
    } else {
        if r <= 0.0 {
            return true;
        }
        (r, (-d.a_min, d.a_max))
    };
    let s1 = if up1 { 1.0 } else { -1.0 };
    let x = (s1 * d.j * (v - d.v0) + 0.5 * d.a0 * d.a0)
        .max(0.0)
        .sqrt()
        .min(hold.0);
    let y = (s1 * d.j * (v - d.vf) + 0.5 * d.af * d.af)
        .max(0.0)
        .sqrt()
        .min(hold.1);
    2.0 * d.j * v.abs() * (1.0 + 1e-9) < x * y
}

/// The margin `1e-8 (1 + |Δp| + |v|_max T_max)` of the residuals `D − Δp` at the ends of a
/// window whose distance is increasing ([`distance_increasing`]), far above their rounding:
/// if both exceed it with the same sign, every peak-family profile of the window misses the
/// target position by more than that, none would pass the verification (tolerance 1e-9 on
/// the final position), and skipping the window changes no result; if they exceed it with
/// opposite signs, the window holds exactly one root ([`RootSet::Single`]). NaN (a change
/// impossible at an end) if the window's duration bound is NaN.
fn residual_margin(
    d: &Dof,
    dp: f64,
    (l, r): (f64, f64),
    at_l: (f64, f64),
    at_r: (f64, f64),
) -> f64 {
    let (_, _, scale) = distance_range(d, l, r, at_l, at_r, f64::INFINITY);
    1e-8 * (1.0 + dp.abs() + scale)
}

/// The profiles that cruise at a velocity limit: for each nonzero limit `vc` whose two
/// time-optimal velocity changes `(v0, a0) → (vc, 0) → (vf, af)` exist (`limit_parts`),
/// `(vc, c1, t_c, c2)` with `t_c` the cruise time that covers the displacement (negative if
/// none does).
fn cruises<'a>(
    d: &'a Dof,
    limit_parts: &'a LimitParts,
) -> impl Iterator<Item = (f64, VelChange, f64, VelChange)> + 'a {
    let dp = d.pf - d.p0;
    [
        (d.v_max, limit_parts.at_max, limit_parts.dist_at_max),
        (d.v_min, limit_parts.at_min, limit_parts.dist_at_min),
    ]
    .into_iter()
    .filter(|&(vc, _, _)| vc != 0.0)
    .filter_map(move |(vc, parts, dist)| {
        let (c1, c2) = parts?;
        Some((vc, c1, (dp - dist) / vc, c2))
    })
}

/// Offers the profiles that cruise at a velocity limit for a positive time.
fn offer_cruise(d: &Dof, prefix: &Profile, limit_parts: &LimitParts, out: &mut TimeOptimal) {
    for (_, c1, tc, c2) in cruises(d, limit_parts) {
        if tc > 0.0
            && let Some(s) = peak_segments(&c1, tc, &c2, 1.0)
        {
            out.offer(d, prefix, &s, 1.0);
        }
    }
}

/// Offers the profile that cruises at a velocity limit if it is provably time-optimal
/// ([`cruise_is_time_optimal`]); whether it was (then it is the only candidate in `out`).
fn optimal_cruise(
    d: &Dof,
    prefix: &Profile,
    limit_parts: &LimitParts,
    out: &mut TimeOptimal,
) -> bool {
    for (vc, c1, tc, c2) in cruises(d, limit_parts) {
        if cruise_is_time_optimal(d, vc, &c1, tc, &c2)
            && let Some(s) = peak_segments(&c1, tc, &c2, 1.0)
        {
            out.offer(d, prefix, &s, 1.0);
            return out.n > 0;
        }
    }
    false
}

/// Whether the profile `c1`, cruise at `vc` for `tc`, `c2` (the two time-optimal velocity
/// changes `(v0, a0) → (vc, 0) → (vf, af)`), once verified, is the shortest of all profiles.
///
/// In the frame where `vc > 0` (mirror otherwise), let `T₁`, `T₂` be the durations of `c1`,
/// `c2` and `T_c = T₁ + t_c + T₂`. Any feasible trajectory `x` of duration `T` satisfies
/// `v_x(t) ≤ v₁(t)` for `t ≤ T₁` and `v_x(t) ≤ v₂(t + T_c − T)` for `t ≥ T − T₂` (the
/// velocities of `c1` and `c2`), and `v_x ≤ v_c` everywhere:
///
/// * `c1` is `+J`, a hold at `a_max`, `−J` (a `+J`-first shape): until its `−J` ramp its
///   acceleration is `min(a₀ + J t, a_max)`, an upper bound of every trajectory's; on the
///   ramp `v₁ + a₁²/(2J) = v_c` with `a₁ ≥ 0`, and `x` could only exceed `v₁` there at an
///   instant with `a_x > a₁ ≥ 0`, `v_x > v₁`, i.e. `v_x + a_x²/(2J) > v_c`; from there
///   `v + a²/(2J)` does not decrease while `a > 0` (jerk ≥ −J), so `x` exceeds `v_c` when its
///   acceleration returns to zero, or ends with `a_f > 0`, `v_f + a_f²/(2J) > v_c`, which the
///   condition on the target below excludes;
/// * `c2` is `−J`, a hold at `a_min`, `+J`: after its first ramp every trajectory's
///   acceleration is at least `c2`'s (the jerk and `a_min` bounds backwards from `a_f`); on
///   the first ramp `v₂ = v_c − a₂²/(2J)`, and `x` could only exceed `v₂` at an instant with
///   `a_x < a₂ ≤ 0`, `v_x + a_x²/(2J) > v_c`; backwards in time the acceleration rises by at
///   most `J` per second, so `x` exceeded `v_c` `|a_x|/J` earlier, or that instant lies before
///   the start and then `v₀ + a₀²/(2J) > v_c` with `a₀ < 0`, which the condition on the start
///   below excludes.
///
/// Then if `T₁ + T₂ ≤ T < T_c`, `Δp = ∫ v_x ≤ D₁ + D₂ + v_c (T − T₁ − T₂) < Δp`: impossible.
/// If `T < T₁ + T₂`, split at `u ≤ T₁` with `T − u ≤ T₂`: `∫ v_x ≤ ∫₀^u v₁ + ∫ v₂` over the
/// last `T − u` of `c2`, and `Δp` minus that is `∫_u^{T₁} v₁ + ∫ v₂ (the rest of c2) + v_c t_c
/// ≥ v_c t_c − T₁ n₁ − T₂ n₂`, where `n₁`, `n₂` bound the negative velocities of `c1`, `c2`
/// (`n₁ = max(0, −min v₁)`, `min v₁ = v₀ − a₀²/(2J)` if `a₀ < 0`, else `v₀`; `min v₂ =
/// v_f − a_f²/(2J)` if `a_f > 0`, else `v_f`). So `v_c t_c > T₁ n₁ + T₂ n₂` makes every
/// shorter duration infeasible. Conditions (in the frame `vc > 0`): the shapes above,
/// `a₀ ≥ 0` or `v₀ + a₀²/(2J) ≤ v_c`, `a_f ≤ 0` or `v_f + a_f²/(2J) ≤ v_c`, and
/// `v_c t_c > T₁ n₁ + T₂ n₂`, with `t_c > 1e-9 (1 + T_c)` so that no profile without cruise
/// (whose duration would differ by `t_c`) can be a rounding-level duplicate of this one.
fn cruise_is_time_optimal(d: &Dof, vc: f64, c1: &VelChange, tc: f64, c2: &VelChange) -> bool {
    let (t1, t2) = (c1.duration(), c2.duration());
    if tc.is_nan() || tc <= 1e-9 * (1.0 + t1 + t2 + tc) {
        return false;
    }
    EnvelopeFrame::of(d, vc, c1, c2)
        .is_some_and(|e| e.sign * vc * tc > t1 * (-e.min1).max(0.0) + t2 * (-e.min2).max(0.0))
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

/// For a shortest-only search that has a profile of duration `T*` already: whether a
/// three-arc variant of `d` whose durations are at least `t_lb` holds no shorter profile
/// that the peak family does not hold too. Either `t_lb ≥ T*`, or no duration in
/// `[t_lb, T*]` fits the distance of a three-arc profile whose acceleration keeps its sign
/// between the first and the last ramp (the others pass through `a = 0` at a velocity peak
/// and are peak-family profiles, which the peak family finds up to the precision of its root
/// finding: such a duplicate may differ from the three-arc solution by ~1e-11 s, see
/// `tests/trajectory_synchronization.rs`). In every variant the jerk is `+J` only on the
/// first ramp (from `a0`) and the last one (to `af`), so the velocity has local minima only
/// where these pass upwards through `a = 0`, at `v0 − a0²/(2J)` (if `a0 < 0`) and
/// `vf − af²/(2J)` (if `af > 0`); its only local maximum is where the `−J` ramp passes
/// downwards through `a = 0`, which a profile that keeps the sign of its acceleration does
/// not do. So its velocity stays in `[min(v0, v0 − a0²/(2J) if a0 < 0, vf, vf − af²/(2J) if
/// af > 0), max(v0, vf)]`, and the distance `D = ∫ v dt` of a profile of duration `T` lies
/// between `T` times these bounds (relative margin 1e-9 for rounding, as in
/// [`distance_excluded`]).
fn three_arc_skip(d: &Dof, out: &TimeOptimal) -> impl Fn(f64) -> bool + use<> {
    let cap = (out.shortest && out.n > 0).then(|| out.duration[0]);
    let dp = d.pf - d.p0;
    let r0 = if d.a0 < 0.0 {
        ramp_out_velocity(d.a0, d.j)
    } else {
        0.0
    };
    let rf = if d.af > 0.0 {
        ramp_out_velocity(d.af, d.j)
    } else {
        0.0
    };
    let v_lo = (d.v0 - r0).min(d.vf - rf);
    let v_hi = d.v0.max(d.vf);
    move |t_lb: f64| {
        let Some(t_cap) = cap else {
            return false;
        };
        if t_lb >= t_cap {
            return true;
        }
        let t_lo = t_lb.max(0.0);
        let d_lo = (v_lo * t_lo).min(v_lo * t_cap);
        let d_hi = (v_hi * t_lo).max(v_hi * t_cap);
        let margin = 1e-9 * (dp.abs() + v_lo.abs().max(v_hi.abs()) * t_cap) + 1e-12;
        // A NaN bound compares false: not skipped.
        dp > d_hi + margin || dp < d_lo - margin
    }
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
    let (a0, af, amax, amin) = (d.a0, d.af, d.a_max, d.a_min);
    // Every variant below needs `af > 0` or `a0 < 0` (the unlimited one either, the held
    // ones `af > 0` and `a0 < 0` respectively).
    if !(af > 0.0 || a0 < 0.0) {
        return;
    }
    let arc_samples = ARC_SAMPLES * density;
    let j = d.j;
    let dp = d.pf - d.p0;
    let dv = d.vf - d.v0;
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
    let skip = three_arc_skip(d, out);
    // Its duration (a1 − a0 + s + af − a2)/J = (2s + af − a0)/J grows with s: at least its
    // value at the range's lower end.
    let lo = (amax - disc1.sqrt())
        .max(-amin - disc2.sqrt())
        .max(1e-9 * (amax - amin));
    let hi1 = (amax + disc1.sqrt()).min(-amin + disc2.sqrt());
    if disc1 >= 0.0 && disc2 >= 0.0 && (af > 0.0 || a0 < 0.0) && !skip((2.0 * lo + af - a0) / j) {
        // Keeping the sign (a2 > 0 for K > 0, a1 < 0 for K < 0) is s² < |K|; beyond it the
        // profile passes through a = 0 and the peak family finds it (with a margin for
        // rounding: a duplicate costs only its verification).
        let hi = hi1.min(k.abs().sqrt() * (1.0 + 1e-9));
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
    let times2 = |a2: f64| {
        let t2 = (dv - (2.0 * amax * amax - a0 * a0 - 2.0 * a2 * a2 + af * af) / (2.0 * j)) / amax;
        ((amax - a0) / j, t2, (amax - a2) / j, (af - a2) / j)
    };
    // Its duration (2 a+ − a0 + af − 2 a2)/J + t2(a2) has the derivative (2/J)(a2/a+ − 1) ≤ 0
    // on the range (a2 ≤ a+): at least its value at the range's upper end.
    let duration2 = |a2: f64| {
        let (t1, t2, t3, t4) = times2(a2);
        t1 + t2 + t3 + t4
    };
    if amax > 0.0
        && af > 0.0
        && feasible_hold(
            dv - (2.0 * amax * amax - a0 * a0 - 2.0 * x2 + af * af) / (2.0 * j),
            dv.abs() + (2.0 * amax * amax + a0 * a0 + 2.0 * x2 + af * af) / (2.0 * j),
            amax,
        )
        && !skip(duration2(hi2))
    {
        let times = times2;
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
    let times3 = |a1: f64| {
        let t6 = (dv - (2.0 * a1 * a1 - a0 * a0 - 2.0 * amin * amin + af * af) / (2.0 * j)) / amin;
        ((a1 - a0) / j, (a1 - amin) / j, t6, (af - amin) / j)
    };
    // Its duration (2 a1 − a0 − 2 a− + af)/J + t6(a1) has the derivative (2/J)(1 − a1/a−) ≥ 0
    // on the range (a1 ≥ a−): at least its value at the range's lower end.
    let duration3 = |a1: f64| {
        let (t1, t2, t3, t4) = times3(a1);
        t1 + t2 + t3 + t4
    };
    if amin < 0.0
        && a0 < 0.0
        && feasible_hold(
            dv - (2.0 * x3 - a0 * a0 - 2.0 * amin * amin + af * af) / (2.0 * j),
            dv.abs() + (2.0 * x3 + a0 * a0 + 2.0 * amin * amin + af * af) / (2.0 * j),
            amin,
        )
        && !skip(duration3(lo3))
    {
        let times = times3;
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
pub(crate) fn time_optimal(
    d: &Dof,
    prefix: &Profile,
    density: usize,
    search: Search,
) -> TimeOptimal {
    let mut out = TimeOptimal::new();
    time_optimal_into(d, prefix, density, search, &mut out);
    out
}

/// [`time_optimal`] written to `out` (which is cleared first), without moving the result.
pub(crate) fn time_optimal_into(
    d: &Dof,
    prefix: &Profile,
    density: usize,
    search: Search,
    out: &mut TimeOptimal,
) {
    out.n = 0;
    out.shortest = search == Search::Shortest;
    if d.at_target() {
        out.offer(d, prefix, &Segments::default(), 1.0);
        return;
    }
    if d.j <= 0.0 {
        return;
    }
    let limit_parts = LimitParts::new(d);
    if out.shortest && density == 1 && optimal_cruise(d, prefix, &limit_parts, out) {
        return;
    }
    if peak_family(d, prefix, density, &limit_parts, out) {
        return;
    }
    three_arc_family(d, d, prefix, 1.0, density, out);
    three_arc_family(d, &d.mirrored(), prefix, -1.0, density, out);
}

#[cfg(test)]
mod tests {
    use super::*;
    use rand::{Rng, SeedableRng};
    use rand_chacha::ChaCha8Rng;

    /// A random problem with asymmetric limits: limits and jerk U(0.1, 12), start and target
    /// velocity and acceleration anywhere inside the limits, target position U(±`spread`).
    fn random_dof(rng: &mut ChaCha8Rng, spread: f64) -> Dof {
        let mut u = |a: f64, b: f64| rng.random_range(a..b);
        let (v_max, v_min) = (u(0.1, 12.0), -u(0.1, 12.0));
        let (a_max, a_min) = (u(0.1, 12.0), -u(0.1, 12.0));
        let j = u(0.1, 12.0);
        Dof {
            p0: 0.0,
            v0: u(v_min, v_max),
            a0: u(a_min, a_max),
            pf: u(-spread, spread),
            vf: u(v_min, v_max),
            af: u(a_min, a_max),
            v_max,
            v_min,
            a_max,
            a_min,
            j,
        }
    }

    /// A random problem ([`random_dof`]) with a safe start (`None` if the start makes a
    /// violation unavoidable or the target is not reachable within the limits).
    fn random_problem(rng: &mut ChaCha8Rng, spread: f64) -> Option<Dof> {
        Some(random_dof(rng, spread)).filter(random_problem_is_valid)
    }

    /// [`random_problem`] with short moves (spread 3) for even `k`, long ones (40) for odd.
    fn short_or_long_problem(rng: &mut ChaCha8Rng, k: usize) -> Option<Dof> {
        random_problem(rng, if k.is_multiple_of(2) { 3.0 } else { 40.0 })
    }

    /// Asserts that the duration a proof ended `probe`'s search with is the complete
    /// search's minimum, bit for bit.
    fn assert_complete_search_agrees(d: &Dof, prefix: &Profile, probe: &TimeOptimal, what: &str) {
        let all = time_optimal(d, prefix, 1, Search::All);
        assert_eq!(
            all.duration[0].to_bits(),
            probe.duration[0].to_bits(),
            "{d:?}: complete {} {what} {}",
            all.duration[0],
            probe.duration[0]
        );
    }

    /// The shortest-only search ([`Search::Shortest`]: the provably time-optimal cruise
    /// profile first, then the families and windows whose duration bound can still beat the
    /// best profile) finds exactly (bit for bit) the minimal duration of the complete search,
    /// on 6000 random problems with asymmetric limits (short and long moves); the cruise
    /// proof ends the search in a good part of them.
    #[test]
    fn shortest_search_equals_the_complete_search() {
        let mut rng = ChaCha8Rng::seed_from_u64(11);
        let (mut compared, mut cruise_proved) = (0, 0);
        for k in 0..6000 {
            let Some(d) = short_or_long_problem(&mut rng, k) else {
                continue;
            };
            let prefix = Profile::new(d.p0, d.v0, d.a0);
            let all = time_optimal(&d, &prefix, 1, Search::All);
            let shortest = time_optimal(&d, &prefix, 1, Search::Shortest);
            assert_eq!(all.n > 0, shortest.n > 0, "{d:?}");
            if all.n == 0 {
                continue;
            }
            assert_eq!(
                all.duration[0].to_bits(),
                shortest.duration[0].to_bits(),
                "{d:?}: complete {} shortest {}",
                all.duration[0],
                shortest.duration[0]
            );
            let mut probe = TimeOptimal::new();
            probe.shortest = true;
            cruise_proved += usize::from(optimal_cruise(
                &d,
                &prefix,
                &LimitParts::new(&d),
                &mut probe,
            ));
            compared += 1;
        }
        assert!(compared > 3000, "{compared}");
        assert!(
            cruise_proved > compared / 10,
            "{cruise_proved} of {compared}"
        );
        eprintln!("{compared} compared, cruise proved optimal in {cruise_proved}");
    }

    /// The three-arc skip ([`three_arc_skip`] with the duration bounds of each variant) never
    /// drops a profile shorter than the best one so far: for every three-arc profile that the
    /// complete search finds on random problems (asymmetric limits, short and long moves), a
    /// shortest-only search whose best duration so far lies just above that profile's still
    /// finds it or a shorter one (the search drops whatever is not shorter than its best);
    /// and the bound skips variants in a good part of the problems.
    #[test]
    fn three_arc_skip_never_drops_a_shorter_profile() {
        let mut rng = ChaCha8Rng::seed_from_u64(13);
        let (mut checked, mut skipped) = (0, 0);
        for k in 0..20_000 {
            let Some(d) = short_or_long_problem(&mut rng, k) else {
                continue;
            };
            let prefix = Profile::new(d.p0, d.v0, d.a0);
            let arcs = |out: &mut TimeOptimal| {
                three_arc_family(&d, &d, &prefix, 1.0, 1, out);
                three_arc_family(&d, &d.mirrored(), &prefix, -1.0, 1, out);
            };
            let mut all = TimeOptimal::new();
            arcs(&mut all);
            for c in 0..all.n {
                let t = all.duration[c];
                // A shortest-only search that has a (fictitious) profile just above `t`.
                let mut short = TimeOptimal::new();
                short.shortest = true;
                short.insert(t + 1e-9 * (1.0 + t), &Segments::default(), 1.0);
                arcs(&mut short);
                assert!(
                    short.duration[0] <= t + 1e-12 * (1.0 + t),
                    "{d:?}: three-arc profile of {t} s dropped, best {}",
                    short.duration[0]
                );
                checked += 1;
            }
            // How often the skip fires against the complete search's best profile.
            let best = time_optimal(&d, &prefix, 1, Search::All);
            if best.n > 0 {
                let mut short = TimeOptimal::new();
                short.shortest = true;
                short.insert(best.duration[0], &Segments::default(), 1.0);
                let skip = three_arc_skip(&d, &short);
                skipped += usize::from(skip(0.0));
            }
        }
        assert!(checked > 300 && skipped > 2000, "{checked} {skipped}");
        eprintln!("{checked} three-arc profiles kept, skip fired in {skipped} problems");
    }

    /// The cruise proof never claims a profile that a complete search beats, including on
    /// problems built to tempt it: start and target velocities far below zero (negative
    /// velocities of both changes, the case that the `n₁`, `n₂` terms exist for) and
    /// accelerations that point away from the cruise.
    #[test]
    fn cruise_proof_is_never_beaten() {
        let mut rng = ChaCha8Rng::seed_from_u64(12);
        let (mut proved, mut tried) = (0, 0);
        for _ in 0..6000 {
            let Some(mut d) = random_problem(&mut rng, 30.0) else {
                continue;
            };
            // Push the velocities towards the limit opposite to the move.
            let toward = if d.pf > 0.0 { d.v_min } else { d.v_max };
            let w: f64 = rng.random_range(0.0..0.95);
            d.v0 = (1.0 - w) * d.v0 + w * toward;
            d.vf = (1.0 - w) * d.vf + w * toward;
            if random_problem_is_valid(&d) {
                tried += 1;
                let prefix = Profile::new(d.p0, d.v0, d.a0);
                let mut probe = TimeOptimal::new();
                probe.shortest = true;
                if optimal_cruise(&d, &prefix, &LimitParts::new(&d), &mut probe) {
                    proved += 1;
                    assert_complete_search_agrees(&d, &prefix, &probe, "cruise");
                }
            }
        }
        assert!(tried > 2000 && proved > 200, "{proved} of {tried}");
        eprintln!("cruise proved optimal in {proved} of {tried}");
    }

    /// The peak proof ([`peak_is_time_optimal`]) never ends a search with a profile that the
    /// complete search beats: random problems with asymmetric limits, short and long moves,
    /// half of them with the start and target velocities pulled towards zero (where the
    /// velocity of the profile comes close to changing sign) and the accelerations left
    /// anywhere; every search the proof ends returns the complete search's minimum, bit for
    /// bit, and it ends a good part of them.
    #[test]
    fn peak_proof_is_never_beaten() {
        let mut rng = ChaCha8Rng::seed_from_u64(17);
        let (mut proved, mut tried) = (0, 0);
        for k in 0..12_000 {
            let Some(mut d) = short_or_long_problem(&mut rng, k) else {
                continue;
            };
            if k % 4 < 2 {
                let w: f64 = rng.random_range(0.0..1.0);
                d.v0 *= 0.1 * w;
                d.vf *= 0.1 * w;
            }
            if !random_problem_is_valid(&d) {
                continue;
            }
            tried += 1;
            let prefix = Profile::new(d.p0, d.v0, d.a0);
            let mut probe = TimeOptimal::new();
            probe.shortest = true;
            let limit_parts = LimitParts::new(&d);
            if optimal_cruise(&d, &prefix, &limit_parts, &mut probe) {
                continue;
            }
            if peak_family(&d, &prefix, 1, &limit_parts, &mut probe) {
                proved += 1;
                assert_complete_search_agrees(&d, &prefix, &probe, "peak");
            }
        }
        assert!(tried > 5000 && proved > 1000, "{proved} of {tried}");
        eprintln!("peak proof in {proved} of {tried}");
    }

    /// Whether the start is safe (no violation unavoidable) and the target reachable within
    /// the limits.
    fn random_problem_is_valid(d: &Dof) -> bool {
        let r0 = ramp_out_velocity(d.a0, d.j);
        let rf = ramp_out_velocity(d.af, d.j);
        (d.a0 <= 0.0 || d.v0 + r0 <= d.v_max)
            && (d.a0 >= 0.0 || d.v0 - r0 >= d.v_min)
            && (d.af <= 0.0 || d.vf - rf >= d.v_min)
            && (d.af >= 0.0 || d.vf + rf <= d.v_max)
    }

    /// The peak family's distance is increasing on every window that [`distance_increasing`]
    /// says it is (400 random problems with asymmetric limits, states anywhere inside them,
    /// 400 peaks per window, rounding allowed), and the windows it applies to are a good part
    /// of all; and the duration bound of [`window_min_duration`] never exceeds the duration
    /// of a profile in its window.
    #[test]
    fn window_bounds_hold_on_every_window() {
        let mut rng = ChaCha8Rng::seed_from_u64(21);
        let (mut windows, mut increasing, mut checked) = (0, 0, 0);
        for _ in 0..400 {
            let d = random_dof(&mut rng, 6.0);
            let mut br = [0.0; 8];
            let nb = peak_breaks(&d, &mut br);
            let (v_stop1, v_stop2) = peak_direction_breaks(&d);
            let durations = |vp: f64| {
                peak_parts(&d, vp).map_or((f64::NAN, f64::NAN), |(c1, c2)| {
                    (c1.duration(), c2.duration())
                })
            };
            for w in br[..nb].windows(2) {
                let (l, r) = (w[0], w[1]);
                windows += 1;
                let t_lb = window_min_duration(durations(l), durations(r));
                let inc = distance_increasing(&d, l, r, v_stop1, v_stop2);
                increasing += usize::from(inc);
                let mut last = f64::NEG_INFINITY;
                for k in 0..=400 {
                    let vp = l + (r - l) * k as f64 / 400.0;
                    let (dist, t) = peak_distance(&d, vp);
                    if dist.is_nan() {
                        continue;
                    }
                    checked += 1;
                    assert!(
                        t_lb.is_nan() || t >= t_lb - 1e-12 * (1.0 + t),
                        "duration {t} below the bound {t_lb} at v_p = {vp} in [{l}, {r}] of {d:?}"
                    );
                    if inc {
                        let tol = 1e-12 * (1.0 + dist.abs() + t * (l.abs() + r.abs()));
                        assert!(
                            dist >= last - tol,
                            "distance {dist} after {last} at v_p = {vp} in [{l}, {r}] of {d:?}"
                        );
                        last = dist;
                    }
                }
            }
        }
        assert!(checked > 100_000, "{checked}");
        assert!(increasing * 4 > windows, "{increasing} of {windows}");
        eprintln!("{increasing} of {windows} windows increasing");
    }

    /// The distance bound of [`distance_excluded`] holds on every window: 400 random problems
    /// (asymmetric limits, states anywhere inside them), 200 peaks per window, every distance
    /// of the peak family inside `[D_lo, D_hi]` up to rounding.
    #[test]
    fn distance_range_bounds_every_window() {
        let mut rng = ChaCha8Rng::seed_from_u64(5);
        let mut checked = 0;
        for _ in 0..400 {
            let d = random_dof(&mut rng, 6.0);
            let mut br = [0.0; 8];
            let nb = peak_breaks(&d, &mut br);
            let durations = |vp: f64| {
                peak_parts(&d, vp).map_or((f64::NAN, f64::NAN), |(c1, c2)| {
                    (c1.duration(), c2.duration())
                })
            };
            for w in br[..nb].windows(2) {
                let (l, r) = (w[0], w[1]);
                let (d_lo, d_hi, scale) =
                    distance_range(&d, l, r, durations(l), durations(r), f64::INFINITY);
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
