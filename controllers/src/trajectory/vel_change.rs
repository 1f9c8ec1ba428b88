//! Time-optimal change of (velocity, acceleration) under acceleration and jerk limits.
//!
//! This is the second-order sub-problem that appears twice in every position profile (from the
//! start state to the peak/cruise velocity, and from there to the target) and is the whole of the
//! velocity interface. With jerk ±J, going *up* from `(v_s, a_s)` to `(v_e, a_e)` uses
//!
//! ```text
//!   +J for (a_p − a_s)/J,   hold a_p for t_h,   −J for (a_p − a_e)/J
//!   Δv = (2 a_p² − a_s² − a_e²) / (2J) + a_p t_h
//! ```
//!
//! With `t_h = 0` the peak is `a_p = √(J Δv + (a_s² + a_e²)/2)`; if that exceeds `a_max` the peak
//! is clamped to `a_max` and `t_h` follows linearly from Δv. The shape is valid when
//! `a_p ≥ max(a_s, a_e)`. *Down* is the mirror image; the faster valid one is time-optimal.

/// A velocity change as three segments: ramp, hold at the peak acceleration, ramp.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct VelChange {
    /// Duration of the first ramp (s).
    pub t1: f64,
    /// Jerk of the first ramp.
    pub j1: f64,
    /// Duration of the hold at the peak acceleration (s).
    pub t2: f64,
    /// Peak acceleration (held during `t2`).
    pub peak: f64,
    /// Duration of the second ramp (s).
    pub t3: f64,
    /// Jerk of the second ramp.
    pub j3: f64,
}

impl VelChange {
    /// Total duration (s).
    #[inline]
    pub fn duration(&self) -> f64 {
        self.t1 + self.t2 + self.t3
    }

    /// Distance travelled starting from `(v, a)`.
    #[inline]
    pub fn distance(&self, v: f64, a: f64) -> f64 {
        let (p1, v1, a1) = super::profile::integrate(0.0, v, a, self.j1, self.t1);
        let (p2, v2, a2) = super::profile::integrate(p1, v1, a1, 0.0, self.t2);
        super::profile::integrate(p2, v2, a2, self.j3, self.t3).0
    }
}

/// Relative slack accepted when a shape sits exactly on its validity boundary.
const SHAPE_EPS: f64 = 1e-12;

/// The "up" shape (+J, hold, −J). `None` if it cannot realise the change.
#[inline(always)]
fn up(vs: f64, a_s: f64, ve: f64, ae: f64, a_max: f64, j: f64) -> Option<VelChange> {
    let dv = ve - vs;
    let m = a_s.max(ae);
    if m > a_max * (1.0 + SHAPE_EPS) + SHAPE_EPS {
        return None;
    }
    let r = j * dv + 0.5 * (a_s * a_s + ae * ae);
    let scale = 1.0 + m * m;
    let mut ap;
    if r < 0.0 {
        if r < -SHAPE_EPS * scale || m > 1e-6 {
            return None;
        }
        ap = 0.0;
    } else {
        ap = r.sqrt();
    }
    if ap < m {
        if m * m - r > SHAPE_EPS * scale {
            return None;
        }
        ap = m;
    }
    let mut th = 0.0;
    if ap > a_max {
        if a_max <= 0.0 {
            return None;
        }
        ap = a_max;
        th = (dv - (2.0 * a_max * a_max - a_s * a_s - ae * ae) / (2.0 * j)) / a_max;
        if th < 0.0 {
            th = 0.0;
        }
    }
    Some(VelChange {
        t1: ((ap - a_s) / j).max(0.0),
        j1: j,
        t2: th,
        peak: ap,
        t3: ((ap - ae) / j).max(0.0),
        j3: -j,
    })
}

/// The "down" shape (−J, hold, +J), the mirror image of [`up`]. `None` if it cannot realise
/// the change.
#[inline(always)]
fn down(vs: f64, a_s: f64, ve: f64, ae: f64, a_min: f64, j: f64) -> Option<VelChange> {
    up(-vs, -a_s, -ve, -ae, -a_min, j).map(|c| VelChange {
        t1: c.t1,
        j1: -c.j1,
        t2: c.t2,
        peak: -c.peak,
        t3: c.t3,
        j3: -c.j3,
    })
}

/// [`vel_change`] with one end at rest in acceleration (`ae = 0` if `rest_at_end`, else
/// `a_s = 0`), computing only the shape that can be valid when the change lies clearly on one
/// side of its direction break `v_stop`: if `ae = 0`, the end velocity reached from `(vs,
/// a_s)` by bringing the acceleration to zero at once, `vs + a_s|a_s|/(2J)`; if `a_s = 0`,
/// the start velocity from which `(ve, ae)` is reached that way, `ve − ae|ae|/(2J)`. With `ae
/// = 0`, [`up`] needs `J (ve − vs) ≥ a_s²/2` if `a_s ≥ 0` (`J (ve − vs) + a_s²/2 ≥ 0` if `a_s <
/// 0`), i.e. `ve ≥ v_stop` up to its `1e-12` slack, and [`down`] the mirror condition `ve ≤
/// v_stop`; with `a_s = 0`, `up` needs `vs ≤ v_stop` and `down` `vs ≥ v_stop`. So outside a
/// band around the break (relative `1e-9`, far wider than the slack and the rounding) at most
/// one shape is valid, and it is what [`vel_change`] returns: the result is exactly
/// [`vel_change`]'s, for half the work. Inside the band, or if that shape is not valid,
/// [`vel_change`] itself.
#[inline(always)]
#[allow(clippy::too_many_arguments)]
pub(crate) fn vel_change_at_rest_end(
    vs: f64,
    a_s: f64,
    ve: f64,
    ae: f64,
    a_max: f64,
    a_min: f64,
    j: f64,
    rest_at_end: bool,
    v_stop: f64,
) -> Option<VelChange> {
    debug_assert!(if rest_at_end { ae == 0.0 } else { a_s == 0.0 });
    if j > 0.0 {
        // The free velocity (the end if ae = 0, else the start) above or below the break;
        // "up" is valid above it for ae = 0, below it for a_s = 0.
        let (free, a) = if rest_at_end { (ve, a_s) } else { (vs, ae) };
        let band = 1e-9 * (1.0 + free.abs() + v_stop.abs() + (1.0 + a * a) / j);
        let above = free > v_stop + band;
        let below = free < v_stop - band;
        if above || below {
            let c = if above == rest_at_end {
                up(vs, a_s, ve, ae, a_max, j)
            } else {
                down(vs, a_s, ve, ae, a_min, j)
            };
            if c.is_some() {
                return c;
            }
        }
    }
    vel_change(vs, a_s, ve, ae, a_max, a_min, j)
}

/// Time-optimal velocity change from `(vs, a_s)` to `(ve, ae)` with accelerations in
/// `[a_min, a_max]` (`a_min ≤ 0 ≤ a_max`) and jerk magnitude `j > 0`.
#[inline(always)]
pub(crate) fn vel_change(
    vs: f64,
    a_s: f64,
    ve: f64,
    ae: f64,
    a_max: f64,
    a_min: f64,
    j: f64,
) -> Option<VelChange> {
    if j <= 0.0 {
        return if vs == ve && a_s == ae && a_s == 0.0 {
            Some(VelChange {
                t1: 0.0,
                j1: 0.0,
                t2: 0.0,
                peak: 0.0,
                t3: 0.0,
                j3: 0.0,
            })
        } else {
            None
        };
    }
    let u = up(vs, a_s, ve, ae, a_max, j);
    let d = down(vs, a_s, ve, ae, a_min, j);
    match (u, d) {
        (Some(u), Some(d)) => Some(if d.duration() < u.duration() { d } else { u }),
        (u, None) => u,
        (None, d) => d,
    }
}

/// Both shapes ("up" then "down"), each if valid. When both are valid the slower one is the end
/// of a blocked interval for synchronisation (durations between the two are impossible).
pub(crate) fn vel_change_both(
    vs: f64,
    a_s: f64,
    ve: f64,
    ae: f64,
    a_max: f64,
    a_min: f64,
    j: f64,
) -> [Option<VelChange>; 2] {
    if j <= 0.0 {
        return [vel_change(vs, a_s, ve, ae, a_max, a_min, j), None];
    }
    let u = up(vs, a_s, ve, ae, a_max, j);
    let d = down(vs, a_s, ve, ae, a_min, j);
    [u, d]
}

/// Velocity changes of exactly duration `t_total` (for synchronisation of the velocity interface):
/// ramp with jerk `s1·J` to an acceleration `a_p`, hold it for `t_h`, ramp with `s2·J` to `ae`.
/// With `t_h = T − (s1 (a_p − a_s) + s2 (ae − a_p)) / J` the velocity equation becomes a
/// quadratic in `a_p`, solved in closed form for the four sign choices.
#[allow(clippy::too_many_arguments)]
pub(crate) fn vel_change_timed(
    vs: f64,
    a_s: f64,
    ve: f64,
    ae: f64,
    a_max: f64,
    a_min: f64,
    j: f64,
    t_total: f64,
) -> Option<VelChange> {
    if j <= 0.0 {
        return None;
    }
    let dv = ve - vs;
    let mut best: Option<VelChange> = None;
    let mut best_err = f64::INFINITY;
    for (s1, s2) in [(1.0, -1.0), (-1.0, 1.0), (1.0, 1.0), (-1.0, -1.0)] {
        // Δv = s1 (a_p² − a_s²)/(2J) + a_p t_h + s2 (ae² − a_p²)/(2J)
        // t_h = T − (s1 (a_p − a_s) + s2 (ae − a_p))/J
        // ⇒ c2 a_p² + c1 a_p + c0 = 0
        let c2 = (s1 - s2) / (2.0 * j) - (s1 - s2) / j;
        let c1 = t_total + (s1 * a_s - s2 * ae) / j;
        let c0 = (-s1 * a_s * a_s + s2 * ae * ae) / (2.0 * j) - dv;
        let mut roots = [f64::NAN; 2];
        if c2.abs() < 1e-300 {
            if c1 != 0.0 {
                roots[0] = -c0 / c1;
            }
        } else {
            let disc = c1 * c1 - 4.0 * c2 * c0;
            if disc >= 0.0 {
                let sq = disc.sqrt();
                let q = -0.5 * (c1 + c1.signum() * sq);
                roots[0] = q / c2;
                if q != 0.0 {
                    roots[1] = c0 / q;
                }
            }
        }
        for ap in roots {
            if !ap.is_finite() || ap > a_max || ap < a_min {
                continue;
            }
            let t1 = s1 * (ap - a_s) / j;
            let t3 = s2 * (ae - ap) / j;
            let th = t_total - t1 - t3;
            let tol = 1e-12 * (1.0 + t_total);
            if t1 < -tol || t3 < -tol || th < -tol {
                continue;
            }
            let c = VelChange {
                t1: t1.max(0.0),
                j1: s1 * j,
                t2: th.max(0.0),
                peak: ap,
                t3: t3.max(0.0),
                j3: s2 * j,
            };
            let v_end = vs
                + c.t1 * (a_s + 0.5 * c.j1 * c.t1)
                + c.peak * c.t2
                + c.t3 * (c.peak + 0.5 * c.j3 * c.t3);
            let err = (v_end - ve).abs() + (c.duration() - t_total).abs();
            if err < best_err {
                best_err = err;
                best = Some(c);
            }
        }
    }
    best
}

#[cfg(test)]
mod tests {
    use super::*;
    use rand::{Rng, SeedableRng};
    use rand_chacha::ChaCha8Rng;

    /// The one-shape shortcut equals the full time-optimal change bit for bit (or both are
    /// `None`), with either end at rest, on random changes including ones right at and near
    /// the direction break (asymmetric limits, accelerations inside them).
    #[test]
    fn at_rest_end_equals_vel_change() {
        let mut rng = ChaCha8Rng::seed_from_u64(31);
        let (mut compared, mut some) = (0, 0);
        for k in 0..200_000 {
            let mut u = |a: f64, b: f64| rng.random_range(a..b);
            let (a_max, a_min, j) = (u(0.1, 12.0), -u(0.1, 12.0), u(0.1, 12.0));
            let a = u(a_min, a_max);
            let v = u(-10.0, 10.0);
            let rest_at_end = k % 2 == 0;
            let v_stop = if rest_at_end {
                v + a * a.abs() / (2.0 * j)
            } else {
                v - a * a.abs() / (2.0 * j)
            };
            // The free velocity: anywhere, or at the break up to a few ulps or a tiny offset.
            let free = match k % 5 {
                0 => v_stop,
                1 => v_stop * (1.0 + u(-1e-15, 1e-15)),
                2 => v_stop + u(-1e-8, 1e-8),
                _ => u(-10.0, 10.0),
            };
            let (vs, a_s, ve, ae) = if rest_at_end {
                (v, a, free, 0.0)
            } else {
                (free, 0.0, v, a)
            };
            let full = vel_change(vs, a_s, ve, ae, a_max, a_min, j);
            let fast =
                vel_change_at_rest_end(vs, a_s, ve, ae, a_max, a_min, j, rest_at_end, v_stop);
            let bits = |c: Option<VelChange>| {
                c.map(|c| [c.t1, c.j1, c.t2, c.peak, c.t3, c.j3].map(f64::to_bits))
            };
            assert_eq!(
                bits(full),
                bits(fast),
                "{vs} {a_s} {ve} {ae} {a_max} {a_min} {j}"
            );
            compared += 1;
            some += usize::from(full.is_some());
        }
        assert!(some > compared / 2, "{some} of {compared}");
    }

    #[test]
    fn rest_to_rest_without_limit() {
        let c = vel_change(0.0, 0.0, 1.0, 0.0, 10.0, -10.0, 1.0).unwrap();
        assert!((c.t1 - 1.0).abs() < 1e-15 && (c.t3 - 1.0).abs() < 1e-15 && c.t2 == 0.0);
        assert!((c.distance(0.0, 0.0) - 1.0).abs() < 1e-14);
    }

    #[test]
    fn clamped_peak_holds() {
        let c = vel_change(0.0, 0.0, 4.0, 0.0, 1.0, -1.0, 1.0).unwrap();
        assert_eq!(c.peak, 1.0);
        assert!((c.t2 - 3.0).abs() < 1e-14);
    }

    #[test]
    fn down_when_overshooting() {
        // a_s = 1 carries the velocity up by 0.5 even with immediate −J: must go negative.
        let c = vel_change(0.0, 1.0, 0.1, 0.0, 10.0, -10.0, 1.0).unwrap();
        assert!(c.peak < 0.0);
    }

    #[test]
    fn timed_matches_duration() {
        let c = vel_change_timed(0.0, 0.0, 1.0, 0.0, 10.0, -10.0, 1.0, 5.0).unwrap();
        assert!((c.duration() - 5.0).abs() < 1e-12);
    }
}
