//! The velocity interface: reach a target (velocity, acceleration), position free.
//!
//! The time-optimal profile is one velocity change ([`super::vel_change::vel_change`]: ramp to a
//! peak acceleration, hold it if it is a limit, ramp to the target acceleration); both shapes
//! ("up" and "down") are kept as candidates, since the slower one bounds a blocked interval. For
//! synchronisation the change is stretched to a prescribed duration with a held intermediate
//! acceleration ([`super::vel_change::vel_change_timed`], closed form).

use super::brake::Limits;
use super::dof::{END_TOL_A, END_TOL_PV, LIMIT_TOL};
use super::profile::Profile;
use super::vel_change::{VelChange, vel_change_both, vel_change_timed};

fn build(prefix: &Profile, c: &VelChange) -> Profile {
    let mut p = *prefix;
    p.push(c.t1, c.j1);
    p.push(c.t2, 0.0);
    p.push(c.t3, c.j3);
    p
}

/// Checks the final velocity and acceleration and the acceleration limits after the prefix.
fn verify(p: &Profile, vf: f64, af: f64, l: &Limits) -> bool {
    let e = p.end();
    let x = p.extrema_from(p.brake_segments());
    (e.velocity - vf).abs() <= END_TOL_PV
        && (e.acceleration - af).abs() <= END_TOL_A
        && x.acceleration.max <= l.a_max + LIMIT_TOL * l.a_max.abs().max(1.0)
        && x.acceleration.min >= l.a_min - LIMIT_TOL * l.a_min.abs().max(1.0)
}

/// Velocity-interface profiles after `prefix`: the valid shapes ("up", "down"), up to two. The
/// shorter is time-optimal; if both are valid the longer one ends a blocked interval.
pub(crate) fn candidates(prefix: &Profile, vf: f64, af: f64, l: &Limits) -> [Option<Profile>; 2] {
    let s = prefix.end();
    if s.velocity == vf && s.acceleration == af {
        return [Some(*prefix), None];
    }
    vel_change_both(s.velocity, s.acceleration, vf, af, l.a_max, l.a_min, l.j).map(|c| {
        let p = build(prefix, &c?);
        verify(&p, vf, af, l).then_some(p)
    })
}

/// Velocity-interface profile lasting exactly `t` seconds after `prefix`.
pub(crate) fn fixed_duration(
    prefix: &Profile,
    vf: f64,
    af: f64,
    l: &Limits,
    t: f64,
) -> Option<Profile> {
    let s = prefix.end();
    if t == 0.0 {
        return (s.velocity == vf && s.acceleration == af).then_some(*prefix);
    }
    let c = vel_change_timed(s.velocity, s.acceleration, vf, af, l.a_max, l.a_min, l.j, t)?;
    let p = build(prefix, &c);
    verify(&p, vf, af, l).then_some(p)
}
