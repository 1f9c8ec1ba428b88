//! The one-DoF problem, candidate segment lists and their verification.
//!
//! Every solver works on a [`Dof`] whose start state is already inside the limits (see
//! [`super::brake`]). It produces [`Segments`]: durations and jerks in the problem's own frame
//! or in its mirror image (`dir = −1`: positions, velocities, accelerations and jerks negated,
//! upper and lower limits swapped). No candidate is trusted: [`Dof::check`] integrates it on
//! top of the braking prefix and checks the final state and every analytic extremum against the
//! limits before it may be used.

use super::profile::{MAX_SEGMENTS, Profile, integrate};

/// Final-state tolerance on position and velocity (the issue requires 1e-8).
pub(crate) const END_TOL_PV: f64 = 1e-9;
/// Final-state tolerance on acceleration (the issue requires 1e-10).
pub(crate) const END_TOL_A: f64 = 1e-11;
/// Relative tolerance on the limits (the issue requires 1e-12).
pub(crate) const LIMIT_TOL: f64 = 1e-12;

/// One DoF: start state (after any braking), target state and limits.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct Dof {
    pub p0: f64,
    pub v0: f64,
    pub a0: f64,
    pub pf: f64,
    pub vf: f64,
    pub af: f64,
    pub v_max: f64,
    pub v_min: f64,
    pub a_max: f64,
    pub a_min: f64,
    pub j: f64,
}

impl Dof {
    /// The mirror image: every state negated, upper and lower limits swapped.
    pub fn mirrored(&self) -> Self {
        Self {
            p0: -self.p0,
            v0: -self.v0,
            a0: -self.a0,
            pf: -self.pf,
            vf: -self.vf,
            af: -self.af,
            v_max: -self.v_min,
            v_min: -self.v_max,
            a_max: -self.a_min,
            a_min: -self.a_max,
            j: self.j,
        }
    }

    /// Start equals target exactly.
    pub fn at_target(&self) -> bool {
        self.p0 == self.pf && self.v0 == self.vf && self.a0 == self.af
    }

    /// Tolerance-scaled test of the segments `segs` (jerks multiplied by `dir`) appended to the
    /// braking `prefix`: final state and velocity/acceleration extrema after the prefix. The
    /// profile is not built: the segments are integrated from the prefix's end state with
    /// exactly the arithmetic of [`Profile::push`], and the test is that of [`Self::verify`], so
    /// `check` agrees with `verify` on the profile [`Segments::append_to`] builds.
    pub fn check(&self, prefix: &Profile, segs: &Segments, dir: f64) -> bool {
        if prefix.brake_segments() != prefix.len() {
            // Not a pure braking prefix: its later segments count too (never the case here).
            return self.verify_built(prefix, segs, dir);
        }
        let e = prefix.end();
        let (mut p, mut v, mut a) = (e.position, e.velocity, e.acceleration);
        let (mut v_lo, mut v_hi, mut a_lo, mut a_hi) = (v, v, a, a);
        let mut len = prefix.len();
        for k in 0..segs.n {
            let (t, j) = (segs.t[k], dir * segs.j[k]);
            // Profile::push's rules.
            if t.is_nan() || t < 0.0 || !t.is_finite() || !j.is_finite() {
                return false;
            }
            if t == 0.0 {
                continue;
            }
            if len == MAX_SEGMENTS {
                return false;
            }
            len += 1;
            // Velocity extremum inside the segment where a + j τ = 0 (as in extrema_from).
            if j != 0.0 {
                let tau = -a / j;
                if tau > 0.0 && tau < t {
                    let vv = integrate(p, v, a, j, tau).1;
                    v_lo = v_lo.min(vv);
                    v_hi = v_hi.max(vv);
                }
            }
            (p, v, a) = integrate(p, v, a, j, t);
            v_lo = v_lo.min(v);
            v_hi = v_hi.max(v);
            a_lo = a_lo.min(a);
            a_hi = a_hi.max(a);
        }
        let scale_p = 1.0 + self.pf.abs().max(self.p0.abs()) * 1e-7;
        if !((p - self.pf).abs() <= END_TOL_PV * scale_p
            && (v - self.vf).abs() <= END_TOL_PV
            && (a - self.af).abs() <= END_TOL_A)
        {
            return false;
        }
        let up = |lim: f64| lim + LIMIT_TOL * lim.abs().max(1.0);
        let lo = |lim: f64| lim - LIMIT_TOL * lim.abs().max(1.0);
        v_hi <= up(self.v_max)
            && v_lo >= lo(self.v_min)
            && a_hi <= up(self.a_max)
            && a_lo >= lo(self.a_min)
    }

    /// [`Self::check`] by building the whole profile.
    fn verify_built(&self, prefix: &Profile, segs: &Segments, dir: f64) -> bool {
        let mut p = *prefix;
        for k in 0..segs.n {
            if !p.push(segs.t[k], dir * segs.j[k]) {
                return false;
            }
        }
        self.verify(&p)
    }

    /// Checks final state and limits of a complete profile.
    pub fn verify(&self, p: &Profile) -> bool {
        let e = p.end();
        let scale_p = 1.0 + self.pf.abs().max(self.p0.abs()) * 1e-7;
        if !((e.position - self.pf).abs() <= END_TOL_PV * scale_p
            && (e.velocity - self.vf).abs() <= END_TOL_PV
            && (e.acceleration - self.af).abs() <= END_TOL_A)
        {
            return false;
        }
        let x = p.extrema_from(p.brake_segments());
        let up = |lim: f64| lim + LIMIT_TOL * lim.abs().max(1.0);
        let lo = |lim: f64| lim - LIMIT_TOL * lim.abs().max(1.0);
        x.velocity.max <= up(self.v_max)
            && x.velocity.min >= lo(self.v_min)
            && x.acceleration.max <= up(self.a_max)
            && x.acceleration.min >= lo(self.a_min)
    }
}

/// Up to eight constant-jerk segments of a candidate in the solver's frame.
#[derive(Debug, Clone, Copy, Default)]
pub(crate) struct Segments {
    pub n: usize,
    pub t: [f64; 8],
    pub j: [f64; 8],
}

impl Segments {
    /// Appends a segment; tiny negative durations from rounding (≥ −1e-12·(1 + scale)) are
    /// clamped to zero, larger ones reject the candidate (returns `false`).
    pub fn push(&mut self, t: f64, j: f64, scale: f64) -> bool {
        if !t.is_finite() || self.n == 8 {
            return false;
        }
        let t = if t < 0.0 {
            if t < -1e-12 * (1.0 + scale) {
                return false;
            }
            0.0
        } else {
            t
        };
        self.t[self.n] = t;
        self.j[self.n] = j;
        self.n += 1;
        true
    }

    /// Writes `prefix` followed by these segments (jerks multiplied by `dir`) to `out`; `false`
    /// if a segment does not fit (never the case for checked segments, see [`Dof::check`]).
    pub fn append_to(&self, prefix: &Profile, dir: f64, out: &mut Profile) -> bool {
        if prefix.is_empty() {
            let s = prefix.start();
            out.restart(s.position, s.velocity, s.acceleration);
        } else {
            *out = *prefix;
        }
        for k in 0..self.n {
            if !out.push(self.t[k], dir * self.j[k]) {
                return false;
            }
        }
        true
    }

    /// Sum of the durations (s).
    pub fn duration(&self) -> f64 {
        self.t[..self.n].iter().sum()
    }
}
