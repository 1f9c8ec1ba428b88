//! Position profiles of one DoF with a prescribed duration (the "step 2" problem used to
//! synchronise DoFs that are not limiting).
//!
//! Three families, tried in order, each reduced to one scalar equation in one parameter:
//!
//! * **Peak + cruise**: `(v0, a0) → (v_p, 0)`, cruise at `v_p` for `t_c`, `(v_p, 0) → (vf, af)`,
//!   with both velocity changes time-optimal. The duration fixes `t_c = T − T₁(v_p) − T₂(v_p)`.
//!   On each smooth window of the peak family we solve the position equation
//!   `D₁(v_p) + D₂(v_p) + v_p t_c(v_p) = Δp` (a polynomial, see [`super::peak_window`]) and
//!   keep the roots with `t_c ≥ 0`.
//! * **Held first peak**: `+J (a0→a1)`, hold `a1` for `t_h`, `−J (a1→a2)`, `+J (a2→af)`. The
//!   duration fixes `t_h`; the velocity equation then reads `a2² − 2 a1 a2 − C(a1) = 0`, so
//!   `a2 = a1 − √(a1² + C)`, and the position equation is solved for `a1`.
//! * **Held second trough**: `+J (a0→a1)`, `−J (a1→a2)`, hold `a2` for `t_h`, `+J (a2→af)`;
//!   symmetric, `a1 = a2 + √(a2² − D(a2))`, solved for `a2`.
//!
//! * **Four free arcs** (UDUD without cruise, acceleration not zero between the halves):
//!   `+J (a0→a1)`, `−J (a1→a_m)`, `+J (a_m→a2)`, `−J (a2→af)`. The duration gives
//!   `a1 + a2 = S(a_m)`, the velocity equation `a1² + a2² = Q(a_m)`, hence
//!   `a1,2 = (S ± √(2Q − S²))/2`; solved for `a_m` on both branches.
//!
//! The last three are evaluated in the problem's frame and its mirror image. As everywhere, each
//! candidate is integrated and verified before use.

use super::dof::{Dof, Segments};
use super::peak_window::{PeakResidual, scan_peak_window};
use super::polynomial::{RootSet, polynomial_roots};
use super::position_time_optimal::{peak_breaks, peak_distance, peak_parts, peak_segments};
use super::profile::{Profile, integrate};
use super::roots::{Roots, scan};

const ARC_SAMPLES: usize = 12;

/// A profile of one DoF lasting exactly `t` seconds after the braking `prefix`, if one is found:
/// its (verified) segments and direction (`−1` for the mirror frame), to be appended to `prefix`
/// (see [`Segments::append_to`]).
pub(crate) fn fixed_duration(d: &Dof, prefix: &Profile, t: f64) -> Option<(Segments, f64)> {
    fixed_duration_then(d, prefix, t, || true)
}

/// [`fixed_duration`] that asks `before_held()` once the peak + cruise family (where most
/// profiles are found) has failed, before the held families are searched, and gives up if it
/// returns `false`. The limiting-DoF-first synchronisation solves the DoF's time-optimal
/// problem there: if its minimal duration exceeds `t`, no profile of duration `t` exists and
/// the held families (the most expensive part of a search that fails) need not be tried.
pub(crate) fn fixed_duration_then(
    d: &Dof,
    prefix: &Profile,
    t: f64,
    mut before_held: impl FnMut() -> bool,
) -> Option<(Segments, f64)> {
    if t.is_nan() || t < 0.0 {
        return None;
    }
    if t == 0.0 {
        return d.at_target().then_some((Segments::default(), 1.0));
    }
    if d.at_target() && d.v0 == 0.0 && d.a0 == 0.0 {
        // Resting at the target: wait.
        let mut s = Segments::default();
        return s.push(t, 0.0, t).then_some((s, 1.0));
    }
    if d.j <= 0.0 {
        // Without jerk the state can only be held, which reaches the target only if the DoF
        // rests at it.
        return None;
    }
    if let Some(p) = peak_cruise(d, prefix, t) {
        return Some(p);
    }
    if !before_held() {
        return None;
    }
    if let Some(p) = held(d, d, prefix, t, 1.0) {
        return Some(p);
    }
    held(d, &d.mirrored(), prefix, t, -1.0)
}

fn peak_cruise(d: &Dof, prefix: &Profile, t: f64) -> Option<(Segments, f64)> {
    let dp = d.pf - d.p0;
    let mut br = [0.0; 8];
    let nb = peak_breaks(d, &mut br);
    // The cruise residual `D₁ + D₂ + v_p (T − T₁ − T₂) − Δp` is one polynomial per smooth window
    // whatever the sign of the cruise time `T − T₁ − T₂`; roots with a negative cruise time are
    // rejected when the segments are built (`Segments::push`). So every smooth window is solved
    // once, without first locating the admissible set `T₁ + T₂ ≤ T`.
    let mut g = |vp: f64| {
        let (dist, tt) = peak_distance(d, vp);
        dist + vp * (t - tt) - dp
    };
    let try_vp = |vp: f64| -> Option<(Segments, f64)> {
        let (c1, c2) = peak_parts(d, vp)?;
        let tc = t - c1.duration() - c2.duration();
        let s = peak_segments(&c1, tc, &c2, t)?;
        d.check(prefix, &s, 1.0).then_some((s, 1.0))
    };
    // Any valid profile will do, so the windows are visited starting with the one that holds
    // the mean velocity Δp/T (where a long cruise, the common case, has its peak), then
    // alternately outwards; every window is still visited before giving up.
    let nw = nb - 1;
    let guess = dp / t;
    let first = br[1..nb - 1].iter().take_while(|&&b| b < guess).count();
    for k in 0..2 * nw {
        // first, first + 1, first − 1, first + 2, …, skipping indices outside 0..nw (each
        // window exactly once).
        let step = k.div_ceil(2);
        let idx = if k % 2 == 1 {
            first + step
        } else {
            first.wrapping_sub(step)
        };
        let Some(w) = (idx < nw).then(|| [br[idx], br[idx + 1]]) else {
            continue;
        };
        // First any one root of the window (bracketed by a sign change, no isolation of the
        // others); if it gives no valid profile, every root.
        let mut tried = f64::NAN;
        for set in [RootSet::AnyOne, RootSet::All] {
            let mut roots = Roots::new();
            scan_peak_window(
                d,
                &mut g,
                w[0],
                w[1],
                1,
                PeakResidual::CruiseDistance { dp, t },
                set,
                &mut roots,
            );
            for &vp in roots.as_slice() {
                if vp == tried {
                    continue;
                }
                if let Some(p) = try_vp(vp) {
                    return Some(p);
                }
            }
            match roots.as_slice() {
                // A single root that failed: ask for all of them.
                [vp] if set == RootSet::AnyOne => tried = *vp,
                // Every root was tried (the closed forms returned all of them).
                _ => break,
            }
        }
    }
    None
}

/// A radicand that is negative only by rounding (relative to `scale`) is taken as zero, so
/// that interval end points where two branches meet are evaluated.
#[inline]
fn radicand(r: f64, scale: f64) -> f64 {
    if r < 0.0 && r > -1e-12 * scale {
        0.0
    } else {
        r
    }
}

#[inline]
fn reach(v0: f64, a0: f64, segs: &[(f64, f64)]) -> f64 {
    let (mut p, mut v, mut a) = (0.0, v0, a0);
    for &(t, j) in segs {
        (p, v, a) = integrate(p, v, a, j, t);
    }
    let _ = (v, a);
    p
}

/// The two "held" families in the frame of `d` (`orig` is the problem to verify against).
fn held(orig: &Dof, d: &Dof, prefix: &Profile, t: f64, dir: f64) -> Option<(Segments, f64)> {
    let j = d.j;
    let dp = d.pf - d.p0;
    let dv = d.vf - d.v0;
    let (a0, af) = (d.a0, d.af);

    // Held first peak, parameter a1.
    let seg_a = |a1: f64| {
        let c = 0.5 * (2.0 * a1 * a1 - a0 * a0 + af * af) + j * t * a1
            - a1 * (2.0 * a1 - a0 + af)
            - j * dv;
        let r = radicand(a1 * a1 + c, a1 * a1 + c.abs());
        if r < 0.0 {
            return None;
        }
        let a2 = a1 - r.sqrt();
        let th = t - (2.0 * a1 - a0 - 2.0 * a2 + af) / j;
        Some([
            ((a1 - a0) / j, j),
            (th, 0.0),
            ((a1 - a2) / j, -j),
            ((af - a2) / j, j),
        ])
    };
    // Held second trough, parameter a2.
    let seg_b = |a2: f64| {
        let c = 0.5 * (-a0 * a0 - 2.0 * a2 * a2 + af * af) + j * t * a2 + a2 * (a0 + 2.0 * a2 - af)
            - j * dv;
        let r = radicand(a2 * a2 - c, a2 * a2 + c.abs());
        if r < 0.0 {
            return None;
        }
        let a1 = a2 + r.sqrt();
        let th = t - (2.0 * a1 - a0 - 2.0 * a2 + af) / j;
        Some([
            ((a1 - a0) / j, j),
            ((a1 - a2) / j, -j),
            (th, 0.0),
            ((af - a2) / j, j),
        ])
    };
    // Four free arcs +J (a0→a1), −J (a1→am), +J (am→a2), −J (a2→af), parameter am:
    // the duration gives a1 + a2 = S, the velocity equation a1² + a2² = Q.
    let seg_c = |am: f64, branch: f64| {
        let s = 0.5 * (j * t + a0 + af + 2.0 * am);
        let q = 0.5 * (2.0 * j * dv + a0 * a0 + af * af + 2.0 * am * am);
        let r = radicand(2.0 * q - s * s, 2.0 * q.abs() + s * s);
        if r < 0.0 {
            return None;
        }
        let a1 = 0.5 * (s + branch * r.sqrt());
        let a2 = s - a1;
        Some([
            ((a1 - a0) / j, j),
            ((a1 - am) / j, -j),
            ((a2 - am) / j, j),
            ((a2 - af) / j, -j),
        ])
    };
    for fam in 0..4 {
        let segs = |x: f64| match fam {
            0 => seg_a(x),
            1 => seg_b(x),
            2 => seg_c(x, 1.0),
            _ => seg_c(x, -1.0),
        };
        let mut f = |x: f64| match segs(x) {
            Some(s) => reach(d.v0, a0, &s) - dp,
            None => f64::NAN,
        };
        // Split the parameter range where the radicand changes sign (analytic, see above).
        let k = j * t + a0 - af;
        let m = 0.5 * (af * af - a0 * a0) - j * dv;
        let mut br = [f64::NAN; 2];
        match fam {
            // seg_a: radicand k a1 + m; seg_b: radicand −k a2 − m.
            0 | 1 => br[0] = -m / k,
            // seg_c: radicand am² − 2B am + 2A − B².
            _ => {
                let b = 0.5 * (j * t + a0 + af);
                let a = 0.5 * (2.0 * j * dv + a0 * a0 + af * af);
                let disc = 2.0 * b * b - 2.0 * a;
                if disc >= 0.0 {
                    br = [b - disc.sqrt(), b + disc.sqrt()];
                }
            }
        }
        let mut pts = [d.a_min, d.a_max, d.a_max, d.a_max];
        let mut n = 1;
        for x in br {
            if x > d.a_min && x < d.a_max {
                pts[n] = x;
                n += 1;
            }
        }
        pts[n] = d.a_max;
        pts[..=n].sort_unstable_by(f64::total_cmp);
        let mut roots = Roots::new();
        for w in pts[..=n].windows(2) {
            // The held families are quartics in z = √(radicand) (radicand k·a1 + m, resp.
            // −k·a2 − m, linear in the parameter).
            if fam < 2 && k != 0.0 {
                let sg = if fam == 0 { 1.0 } else { -1.0 };
                let rad = |x: f64| sg * (k * x + m);
                let x_of_z = |z: f64| (sg * z * z - m) / k;
                if rad(0.5 * (w[0] + w[1])) < 0.0 {
                    continue;
                }
                let (zl, zr) = (rad(w[0]).max(0.0).sqrt(), rad(w[1]).max(0.0).sqrt());
                let mut g = |z: f64| f(x_of_z(z).clamp(w[0], w[1]));
                let mut rz = Roots::new();
                if polynomial_roots(&mut g, zl.min(zr), zl.max(zr), 4, &mut rz) {
                    for &z in rz.as_slice() {
                        roots.push(x_of_z(z).clamp(w[0], w[1]));
                    }
                    continue;
                }
            }
            scan(&mut f, w[0], w[1], ARC_SAMPLES, &mut roots);
        }
        for &x in roots.as_slice() {
            let Some(s) = segs(x) else { continue };
            let mut sg = Segments::default();
            if s.iter().all(|&(ti, ji)| sg.push(ti, ji, t)) && orig.check(prefix, &sg, dir) {
                return Some((sg, dir));
            }
        }
    }
    None
}
