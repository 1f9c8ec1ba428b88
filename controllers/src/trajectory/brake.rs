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
//! normal profile overshoots (ruckig's issues #86 and #188). We instead brake first, with the
//! largest jerk that reduces the violation ("down": jerk −J until `a_b`, then hold `a_b`; or the
//! mirror image "up"), and stop at the first instant the state is safe. The braking acceleration
//! is `a_b = max(a_min, −√(2J (v_max − v_min)))`: the deepest one from which the state is safe on
//! re-entering `v ≤ v_max` (braking harder would overshoot `v_min` afterwards). Along −J the quantity
//! `v + a²/(2J)` is constant while `a > 0`, so the overshoot above `v_max` is the smallest
//! possible (`v0 + a0²/(2J)`), and since every segment uses the extreme admissible jerk or
//! acceleration, no other motion reaches the safe set sooner. The main profile then starts from
//! the safe state; the trajectory reports [`super::TrajectoryStatus::BrakingThenTarget`] while
//! the pre-phase runs.

use super::profile::Profile;

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

/// Down-braking duration from `(v0, a0)`: ramp with −J to `a_min`, then hold `a_min`.
/// Returns `(ramp duration, hold duration)`.
fn down_times(v0: f64, a0: f64, l: &Limits, check_velocity: bool) -> Option<(f64, f64)> {
    let j = l.j;
    if j <= 0.0 {
        return None;
    }
    // Deepest braking acceleration: the limit, and, when velocities are checked, shallow enough
    // that the state is safe when v returns to v_max (v_max − a²/(2J) ≥ v_min).
    let a_floor = if check_velocity {
        l.a_min.max(-(2.0 * j * (l.v_max - l.v_min)).sqrt())
    } else {
        l.a_min
    };
    let t_ramp_full = ((a0 - a_floor) / j).max(0.0);
    // Acceleration back under a_max.
    let t_a = ((a0 - l.a_max) / j).max(0.0);
    // Velocity back under v_max with a ≤ 0.
    let mut t_v = 0.0;
    let v_bad = v0 > l.v_max || (a0 > 0.0 && v0 + a0 * a0 / (2.0 * j) > l.v_max);
    if check_velocity && v_bad {
        let disc = a0 * a0 + 2.0 * j * (v0 - l.v_max);
        let t = (a0 + disc.max(0.0).sqrt()) / j;
        if t <= t_ramp_full {
            t_v = t;
        } else {
            if a_floor >= 0.0 {
                return None;
            }
            let tr = t_ramp_full;
            let vr = v0 + a0 * tr - 0.5 * j * tr * tr;
            t_v = tr + (vr - l.v_max) / (-a_floor);
        }
    }
    let tb = t_a.max(t_v);
    Some((tb.min(t_ramp_full), (tb - t_ramp_full).max(0.0)))
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
/// interface, which constrains only the acceleration. Returns `None` if the limits make braking
/// impossible (zero jerk or zero acceleration limit on the needed side).
pub(crate) fn brake(p0: f64, v0: f64, a0: f64, l: &Limits, check_velocity: bool) -> Option<Brake> {
    let mut prefix = Profile::new(p0, v0, a0);
    if is_safe(v0, a0, l, check_velocity) {
        return Some(Brake {
            prefix,
            active: false,
        });
    }
    let (dir, lim) = if needs_down(v0, a0, l, check_velocity) {
        (1.0, *l)
    } else {
        (-1.0, l.mirrored())
    };
    let (t_ramp, t_hold) = down_times(dir * v0, dir * a0, &lim, check_velocity)?;
    prefix.push(t_ramp, -dir * l.j);
    prefix.push(t_hold, 0.0);
    prefix.mark_brake();
    Some(Brake {
        prefix,
        active: true,
    })
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
    fn velocity_below_minimum() {
        let b = brake(0.0, -3.0, 0.0, &L, true).unwrap();
        let e = b.prefix.end();
        assert!(
            b.active && is_safe(e.velocity, e.acceleration, &L, true),
            "{e:?}"
        );
    }
}
