//! Braking pre-phase for start states that make a limit violation unavoidable.
//!
//! A start state `(v, a)` is *safe* when every limit can still be respected from it:
//!
//! ```text
//!   a_min ≤ a ≤ a_max,   v_min ≤ v ≤ v_max,
//!   a > 0  ⇒  v + a²/(2J) ≤ v_max     (the lowest velocity peak reachable with jerk −J)
//!   a < 0  ⇒  v − a²/(2J) ≥ v_min
//! ```
//!
//! Outside this set no trajectory respects the limits, and a generator that silently starts a
//! normal profile overshoots (ruckig's issues #86 and #188). We instead brake first ("down":
//! decreasing the acceleration; or the mirror image "up") and stop at the first instant the state
//! is safe. Along −J the quantity `v + a²/(2J)` is constant, so the overshoot above `v_max` is the
//! smallest possible (`v0 + a0²/(2J)`). The state re-enters the safe set at `v = v_max` with an
//! acceleration in `[a_b, 0]`, `a_b = max(a_min, −√(2J (v_max − v_min)))` (deeper, and `v_min`
//! would be overshot afterwards). If `v` comes back to `v_max` while the −J ramp is still above
//! `a_b`, that is the earliest entry; otherwise the earliest entry is the time-optimal velocity
//! change to `(v_max, a_b)` (bang-bang: −J below `a_b`, +J back; holding `a_b` instead arrives
//! later). The main profile
//! then starts from the safe state; the trajectory reports
//! [`super::TrajectoryStatus::BrakingThenTarget`] while the pre-phase runs. Returning earliest is
//! not always fastest overall, so the calculator also tries holding `a_b` ([`brake_with`]) and
//! [`brake_to_limit`], keeps per DoF the variant with the shortest total duration, and keeps the
//! others available to the synchronisation.

use super::profile::Profile;
use super::vel_change::vel_change;

/// Per-DoF limits in the form the solvers use (`v_min ≤ 0 ≤ v_max`, `a_min ≤ 0 ≤ a_max`, `j ≥ 0`).
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct Limits {
    pub v_max: f64,
    pub v_min: f64,
    pub a_max: f64,
    pub a_min: f64,
    pub j: f64,
}

impl Limits {
    fn mirrored(&self) -> Self {
        Self {
            v_max: -self.v_min,
            v_min: -self.v_max,
            a_max: -self.a_min,
            a_min: -self.a_max,
            j: self.j,
        }
    }
}

fn tol(x: f64) -> f64 {
    1e-12 * x.abs().max(1.0)
}

/// Violations that braking "down" (decreasing acceleration) resolves.
fn needs_down(v: f64, a: f64, l: &Limits, check_velocity: bool) -> bool {
    a > l.a_max + tol(l.a_max)
        || (check_velocity
            && (v > l.v_max + tol(l.v_max)
                || (a > 0.0 && l.j > 0.0 && v + a * a / (2.0 * l.j) > l.v_max + tol(l.v_max))))
}

/// True if the state `(v, a)` is safe (see the module documentation).
pub(crate) fn is_safe(v: f64, a: f64, l: &Limits, check_velocity: bool) -> bool {
    !needs_down(v, a, l, check_velocity) && !needs_down(-v, -a, &l.mirrored(), check_velocity)
}

/// Velocity braking "down" from `(v0, a0)` with `a_min ≤ a0 ≤ a_max`, until the state is back
/// in the safe set. If `v` returns to `v_max` on the ramp with −J before the acceleration falls
/// below the braking acceleration `a_b`, the braking ends there; otherwise the braking is the
/// time-optimal velocity change ([`vel_change`], bang-bang: −J beyond `a_b`, then +J back) to
/// `(v_max, a_b)`, the earliest entry into the safe set at `v_max` (holding `a_b` instead would
/// arrive later). Returns the segments `(duration, jerk)`.
fn down_velocity(v0: f64, a0: f64, l: &Limits, hold: bool) -> Option<[(f64, f64); 3]> {
    let j = l.j;
    // Deepest braking acceleration: the limit, and shallow enough that the state is safe when v
    // returns to v_max (v_max − a²/(2J) ≥ v_min).
    let a_b = l.a_min.max(-(2.0 * j * (l.v_max - l.v_min)).sqrt());
    if a_b >= 0.0 {
        return None;
    }
    let js = if a0 > a_b { -j } else { j };
    let t_ramp = (a_b - a0) / js;
    // v(t) = v0 + a0 t − J t²/2 = v_max on the ramp, after the velocity peak (a ≤ 0).
    if js < 0.0 {
        let (qa, qb, qc) = (0.5 * js, a0, v0 - l.v_max);
        let disc = qb * qb - 4.0 * qa * qc;
        if disc >= 0.0 {
            let sq = disc.sqrt();
            let mut best = f64::INFINITY;
            for t in [(-qb - sq) / (2.0 * qa), (-qb + sq) / (2.0 * qa)] {
                if t >= 0.0 && t <= t_ramp && a0 + js * t <= 0.0 && t < best {
                    best = t;
                }
            }
            if best.is_finite() {
                return Some([(best, js), (0.0, 0.0), (0.0, 0.0)]);
            }
        }
    }
    if !hold && let Some(c) = vel_change(v0, a0, l.v_max, a_b, l.a_max, l.a_min, j) {
        return Some([(c.t1, c.j1), (c.t2, 0.0), (c.t3, c.j3)]);
    }
    let vr = v0 + a0 * t_ramp + 0.5 * js * t_ramp * t_ramp;
    let t_hold = ((vr - l.v_max) / (-a_b)).max(0.0);
    Some([(t_ramp, js), (t_hold, 0.0), (0.0, 0.0)])
}

/// Outcome of the braking analysis of one DoF.
#[derive(Debug, Clone, Copy)]
pub(crate) struct Brake {
    /// The braking segments (possibly none) starting at the current state.
    pub prefix: Profile,
    /// True if the start state was unsafe and a braking pre-phase was added.
    pub active: bool,
}

/// Computes the braking pre-phase of one DoF. `check_velocity` is false for the velocity
/// interface, which constrains only the acceleration. First an acceleration outside its limits
/// is ramped back with the full jerk; then, if the velocity is still unsafe, velocity braking
/// (down or up) follows; this repeats at most four times. Returns `None` if no safe state is
/// reached (zero jerk, or a zero acceleration limit on the side needed).
pub(crate) fn brake(p0: f64, v0: f64, a0: f64, l: &Limits, check_velocity: bool) -> Option<Brake> {
    brake_with(p0, v0, a0, l, check_velocity, false)
}

/// [`brake`] whose velocity braking ramps to `a_b` and holds it (`hold`), instead of the
/// earliest return: it re-enters the safe set later, but its continuation is sometimes faster
/// overall, so the calculator tries both.
pub(crate) fn brake_with(
    p0: f64,
    v0: f64,
    a0: f64,
    l: &Limits,
    check_velocity: bool,
    hold: bool,
) -> Option<Brake> {
    let mut prefix = Profile::new(p0, v0, a0);
    if is_safe(v0, a0, l, check_velocity) {
        return Some(Brake {
            prefix,
            active: false,
        });
    }
    if l.j <= 0.0 {
        return None;
    }
    for _ in 0..4 {
        let s = prefix.end();
        let (v, a) = (s.velocity, s.acceleration);
        if is_safe(v, a, l, check_velocity) {
            prefix.mark_brake();
            return Some(Brake {
                prefix,
                active: true,
            });
        }
        if a > l.a_max {
            prefix.push((a - l.a_max) / l.j, -l.j);
        } else if a < l.a_min {
            prefix.push((l.a_min - a) / l.j, l.j);
        } else {
            let (dir, lim) = if needs_down(v, a, l, check_velocity) {
                (1.0, *l)
            } else {
                (-1.0, l.mirrored())
            };
            let segs = down_velocity(dir * v, dir * a, &lim, hold)?;
            for (t, js) in segs {
                prefix.push(t, dir * js);
            }
        }
    }
    let s = prefix.end();
    if is_safe(s.velocity, s.acceleration, l, check_velocity) {
        prefix.mark_brake();
        Some(Brake {
            prefix,
            active: true,
        })
    } else {
        None
    }
}

/// The alternative braking pre-phase: after bringing the acceleration within its limits, the
/// time-optimal velocity change ([`vel_change`]) to rest *at* the violated velocity limit,
/// `(v_max, 0)` (or `(v_min, 0)`). It ends later than [`brake`] but at zero acceleration, which
/// is faster overall when the target lies beyond the limit velocity; the calculator keeps the
/// variant with the shorter total duration. `None` if not applicable or not needed.
pub(crate) fn brake_to_limit(p0: f64, v0: f64, a0: f64, l: &Limits) -> Option<Profile> {
    if l.j <= 0.0 || is_safe(v0, a0, l, true) {
        return None;
    }
    let mut prefix = Profile::new(p0, v0, a0);
    let s = prefix.start();
    if s.acceleration > l.a_max {
        prefix.push((s.acceleration - l.a_max) / l.j, -l.j);
    } else if s.acceleration < l.a_min {
        prefix.push((l.a_min - s.acceleration) / l.j, l.j);
    }
    let s = prefix.end();
    let (v, a) = (s.velocity, s.acceleration);
    if is_safe(v, a, l, true) {
        return None;
    }
    let target = if needs_down(v, a, l, true) {
        l.v_max
    } else {
        l.v_min
    };
    let c = vel_change(v, a, target, 0.0, l.a_max, l.a_min, l.j)?;
    prefix.push(c.t1, c.j1);
    prefix.push(c.t2, 0.0);
    prefix.push(c.t3, c.j3);
    let e = prefix.end();
    if (e.velocity - target).abs() > 1e-9 || e.acceleration.abs() > 1e-11 {
        return None;
    }
    prefix.mark_brake();
    Some(prefix)
}

#[cfg(test)]
mod tests {
    use super::*;

    const L: Limits = Limits {
        v_max: 1.0,
        v_min: -1.0,
        a_max: 1.0,
        a_min: -1.0,
        j: 1.0,
    };

    #[test]
    fn safe_state_needs_no_brake() {
        let b = brake(0.0, 0.5, 0.5, &L, true).unwrap();
        assert!(!b.active && b.prefix.is_empty());
    }

    #[test]
    fn unavoidable_overshoot_is_braked_minimally() {
        // v0 + a0²/(2J) = 0.9 + 0.5 > 1: overshoot unavoidable.
        let b = brake(0.0, 0.9, 1.0, &L, true).unwrap();
        assert!(b.active);
        let e = b.prefix.end();
        assert!(is_safe(e.velocity, e.acceleration, &L, true));
        let x = b.prefix.extrema();
        assert!(
            (x.velocity.max - 1.4).abs() < 1e-12,
            "minimal overshoot {}",
            x.velocity.max
        );
    }

    #[test]
    fn acceleration_above_limit() {
        let b = brake(0.0, -0.9, 3.0, &L, true).unwrap();
        let e = b.prefix.end();
        assert!(
            b.active && is_safe(e.velocity, e.acceleration, &L, true),
            "{e:?}"
        );
    }

    #[test]
    fn velocity_too_high_and_acceleration_too_low() {
        let l = Limits {
            v_max: 0.522,
            v_min: -0.522,
            a_max: 1.595,
            a_min: -1.595,
            j: 10.14,
        };
        let b = brake(0.0, 0.64, -2.1186, &l, true).unwrap();
        let e = b.prefix.end();
        assert!(
            b.active && is_safe(e.velocity, e.acceleration, &l, true),
            "{e:?}"
        );
    }

    #[test]
    fn acceleration_deeper_than_safe_braking() {
        let l = Limits {
            v_max: 0.1796,
            v_min: -0.1796,
            a_max: 10.37,
            a_min: -10.37,
            j: 2.757,
        };
        let b = brake(0.0, -0.587, 1.453, &l, true).unwrap();
        let e = b.prefix.end();
        assert!(
            b.active && is_safe(e.velocity, e.acceleration, &l, true),
            "{e:?}"
        );
    }

    #[test]
    fn velocity_below_minimum() {
        let b = brake(0.0, -3.0, 0.0, &L, true).unwrap();
        let e = b.prefix.end();
        assert!(
            b.active && is_safe(e.velocity, e.acceleration, &L, true),
            "{e:?}"
        );
    }
}
