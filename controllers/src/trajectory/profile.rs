//! One degree of freedom as a sequence of constant-jerk segments.
//!
//! A [`Profile`] stores up to [`MAX_SEGMENTS`] segments `(duration, jerk)` and the state
//! `(p, v, a)` at the start of each, obtained by exact integration of the triple integrator
//!
//! ```text
//! a(τ) = a_k + j_k τ
//! v(τ) = v_k + a_k τ + j_k τ² / 2
//! p(τ) = p_k + v_k τ + a_k τ² / 2 + j_k τ³ / 6 ,   0 ≤ τ ≤ t_k .
//! ```
//!
//! Extrema are analytic: the acceleration is piecewise linear (extrema at segment ends), the
//! velocity has interior extrema where `a(τ) = 0`, the position where `v(τ) = 0` (a quadratic per
//! segment).

/// Maximum number of constant-jerk segments of one DoF: up to 3 braking segments, the 7 phases of
/// the main profile and a final hold segment, with room to spare.
pub const MAX_SEGMENTS: usize = 14;

/// Kinematic state of one DoF.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct DofState {
    /// Position (m or rad).
    pub position: f64,
    /// Velocity (m/s or rad/s).
    pub velocity: f64,
    /// Acceleration (m/s² or rad/s²).
    pub acceleration: f64,
}

/// Minimum and maximum of one quantity along a profile, with the times at which they occur.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct Bound {
    /// Smallest value.
    pub min: f64,
    /// Largest value.
    pub max: f64,
    /// Time of the smallest value (s from the trajectory start).
    pub t_min: f64,
    /// Time of the largest value (s from the trajectory start).
    pub t_max: f64,
}

impl Bound {
    fn new(x: f64, t: f64) -> Self {
        Self {
            min: x,
            max: x,
            t_min: t,
            t_max: t,
        }
    }

    fn include(&mut self, x: f64, t: f64) {
        if x < self.min {
            self.min = x;
            self.t_min = t;
        }
        if x > self.max {
            self.max = x;
            self.t_max = t;
        }
    }
}

/// Extrema of position, velocity and acceleration of one DoF over its whole profile.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct DofExtrema {
    /// Position extrema.
    pub position: Bound,
    /// Velocity extrema.
    pub velocity: Bound,
    /// Acceleration extrema.
    pub acceleration: Bound,
}

/// Integrates one constant-jerk segment of duration `t` from `(p, v, a)`.
#[inline(always)]
pub(crate) fn integrate(p: f64, v: f64, a: f64, j: f64, t: f64) -> (f64, f64, f64) {
    (
        p + t * (v + t * (a / 2.0 + t * j / 6.0)),
        v + t * (a + t * j / 2.0),
        a + t * j,
    )
}

/// A jerk-limited motion of one DoF: constant-jerk segments and their start states.
#[derive(Debug, Clone, Copy)]
pub struct Profile {
    len: usize,
    /// Number of leading segments that belong to a braking pre-phase.
    brake_len: usize,
    t: [f64; MAX_SEGMENTS],
    j: [f64; MAX_SEGMENTS],
    /// Start time of each segment, `t0[len]` is the duration.
    t0: [f64; MAX_SEGMENTS + 1],
    p: [f64; MAX_SEGMENTS + 1],
    v: [f64; MAX_SEGMENTS + 1],
    a: [f64; MAX_SEGMENTS + 1],
}

impl Default for Profile {
    fn default() -> Self {
        Self::new(0.0, 0.0, 0.0)
    }
}

impl Profile {
    /// An empty (zero-duration) profile resting at `(p, v, a)`.
    #[must_use]
    pub fn new(p: f64, v: f64, a: f64) -> Self {
        let mut s = Self {
            len: 0,
            brake_len: 0,
            t: [0.0; MAX_SEGMENTS],
            j: [0.0; MAX_SEGMENTS],
            t0: [0.0; MAX_SEGMENTS + 1],
            p: [0.0; MAX_SEGMENTS + 1],
            v: [0.0; MAX_SEGMENTS + 1],
            a: [0.0; MAX_SEGMENTS + 1],
        };
        s.p[0] = p;
        s.v[0] = v;
        s.a[0] = a;
        s
    }

    /// Makes this an empty profile resting at `(p, v, a)` like [`Self::new`], without clearing
    /// the segment arrays beyond the start state (nothing reads past [`Self::len`]); cheaper
    /// than overwriting the whole profile when a calculation writes its result in place.
    pub(crate) fn restart(&mut self, p: f64, v: f64, a: f64) {
        self.len = 0;
        self.brake_len = 0;
        self.t0[0] = 0.0;
        self.p[0] = p;
        self.v[0] = v;
        self.a[0] = a;
    }

    /// Appends a segment of `duration` seconds with constant `jerk`; zero-length segments are
    /// skipped. Returns `false` if the profile is full or the duration is negative or not finite.
    pub fn push(&mut self, duration: f64, jerk: f64) -> bool {
        if duration.is_nan() || duration < 0.0 || !duration.is_finite() || !jerk.is_finite() {
            return false;
        }
        if duration == 0.0 {
            return true;
        }
        if self.len == MAX_SEGMENTS {
            return false;
        }
        let k = self.len;
        self.t[k] = duration;
        self.j[k] = jerk;
        let (p, v, a) = integrate(self.p[k], self.v[k], self.a[k], jerk, duration);
        self.p[k + 1] = p;
        self.v[k + 1] = v;
        self.a[k + 1] = a;
        self.t0[k + 1] = self.t0[k] + duration;
        self.len += 1;
        true
    }

    /// Marks the segments pushed so far as the braking pre-phase.
    pub(crate) fn mark_brake(&mut self) {
        self.brake_len = self.len;
    }

    /// Number of segments.
    #[must_use]
    pub fn len(&self) -> usize {
        self.len
    }

    /// True if the profile has no segment (the DoF rests at its start state).
    #[must_use]
    pub fn is_empty(&self) -> bool {
        self.len == 0
    }

    /// Segment `k` as `(duration, jerk)`, for `k <` [`Self::len`].
    #[must_use]
    pub fn segment(&self, k: usize) -> (f64, f64) {
        (self.t[k], self.j[k])
    }

    /// Duration of the profile (s).
    #[must_use]
    pub fn duration(&self) -> f64 {
        self.t0[self.len]
    }

    /// Duration of the braking pre-phase (s), zero if there is none.
    #[must_use]
    pub fn brake_duration(&self) -> f64 {
        self.t0[self.brake_len]
    }

    /// State at the start.
    #[must_use]
    pub fn start(&self) -> DofState {
        self.state_at_index(0)
    }

    /// State at the end (integrated, not copied from the target).
    #[must_use]
    pub fn end(&self) -> DofState {
        self.state_at_index(self.len)
    }

    fn state_at_index(&self, k: usize) -> DofState {
        DofState {
            position: self.p[k],
            velocity: self.v[k],
            acceleration: self.a[k],
        }
    }

    /// State at time `t` (s). Before 0 the start state is returned; after the duration the motion
    /// continues with the final acceleration held constant (zero jerk), as in a real controller
    /// that keeps its last command's acceleration.
    #[must_use]
    pub fn state_at(&self, t: f64) -> DofState {
        if t.is_nan() || t <= 0.0 {
            return self.start();
        }
        // Find the segment: linear scan is fastest for ≤ 14 entries.
        let mut k = 0;
        while k < self.len && t >= self.t0[k + 1] {
            k += 1;
        }
        let (tau, j) = if k == self.len {
            (t - self.t0[self.len], 0.0)
        } else {
            (t - self.t0[k], self.j[k])
        };
        let (p, v, a) = integrate(self.p[k], self.v[k], self.a[k], j, tau);
        DofState {
            position: p,
            velocity: v,
            acceleration: a,
        }
    }

    /// Jerk at time `t` (s).
    #[must_use]
    pub fn jerk_at(&self, t: f64) -> f64 {
        let mut k = 0;
        while k < self.len && t >= self.t0[k + 1] {
            k += 1;
        }
        if k == self.len { 0.0 } else { self.j[k] }
    }

    /// Analytic extrema of position, velocity and acceleration, starting at segment `from`
    /// (use 0 for the whole profile, or the braking length to skip the braking pre-phase).
    #[must_use]
    pub fn extrema_from(&self, from: usize) -> DofExtrema {
        let k0 = from.min(self.len);
        let t_start = self.t0[k0];
        let mut e = DofExtrema {
            position: Bound::new(self.p[k0], t_start),
            velocity: Bound::new(self.v[k0], t_start),
            acceleration: Bound::new(self.a[k0], t_start),
        };
        for k in k0..self.len {
            let (t, j) = (self.t[k], self.j[k]);
            let (p, v, a) = (self.p[k], self.v[k], self.a[k]);
            let te = self.t0[k + 1];
            e.position.include(self.p[k + 1], te);
            e.velocity.include(self.v[k + 1], te);
            e.acceleration.include(self.a[k + 1], te);
            // Velocity extremum inside the segment where a + j τ = 0.
            if j != 0.0 {
                let tau = -a / j;
                if tau > 0.0 && tau < t {
                    let (pp, vv, _) = integrate(p, v, a, j, tau);
                    e.velocity.include(vv, self.t0[k] + tau);
                    e.position.include(pp, self.t0[k] + tau);
                }
            }
            // Position extrema where v + a τ + j τ²/2 = 0.
            let mut roots = [f64::NAN; 2];
            if j != 0.0 {
                let disc = a * a - 2.0 * j * v;
                if disc >= 0.0 {
                    let sq = disc.sqrt();
                    // Numerically stable quadratic roots of (j/2) τ² + a τ + v.
                    let q = -(a + a.signum() * sq);
                    if q != 0.0 {
                        roots[0] = q / j;
                        roots[1] = 2.0 * v / q;
                    } else {
                        roots[0] = 0.0;
                    }
                }
            } else if a != 0.0 {
                roots[0] = -v / a;
            }
            for tau in roots {
                if tau > 0.0 && tau < t {
                    let (pp, _, _) = integrate(p, v, a, j, tau);
                    e.position.include(pp, self.t0[k] + tau);
                }
            }
        }
        e
    }

    /// Analytic extrema over the whole profile, braking pre-phase included.
    #[must_use]
    pub fn extrema(&self) -> DofExtrema {
        self.extrema_from(0)
    }

    /// Index of the first segment after the braking pre-phase.
    #[must_use]
    pub fn brake_segments(&self) -> usize {
        self.brake_len
    }
}
