//! A calculated multi-DoF trajectory: one [`Profile`] per DoF, sampled at any time.

use super::calculator::independent_min_duration;
use super::dof::Dof;
use super::profile::{DofExtrema, DofState, Profile};

/// A whole trajectory of `N` DoFs, as returned by [`super::TrajectoryGenerator::calculate`].
///
/// ## Memory allocation
/// Fixed size (`N` profiles of at most [`super::profile::MAX_SEGMENTS`] segments); nothing is
/// allocated, so it can live on the stack or inside the generator.
#[derive(Debug, Clone, Copy)]
pub struct Trajectory<const N: usize> {
    pub(crate) profiles: [Profile; N],
    pub(crate) duration: f64,
    pub(crate) independent_min_durations: [f64; N],
    /// DoFs whose minimal duration the synchronisation did not need: computed on demand by
    /// [`Self::independent_min_durations`] from these problems.
    pub(crate) pending: [Option<Dof>; N],
    pub(crate) braking: bool,
}

impl<const N: usize> Default for Trajectory<N> {
    fn default() -> Self {
        Self {
            profiles: [Profile::default(); N],
            duration: 0.0,
            independent_min_durations: [0.0; N],
            pending: [None; N],
            braking: false,
        }
    }
}

impl<const N: usize> Trajectory<N> {
    /// Duration (s) until every DoF has reached its target.
    #[must_use]
    pub fn duration(&self) -> f64 {
        self.duration
    }

    /// The time-optimal duration of each DoF on its own (s), braking pre-phase included.
    ///
    /// The time synchronisation solves the time-optimal problem only for the DoFs that may be
    /// limiting (see `calculator::synchronize_limiting_first`); the others' durations are
    /// computed here, on each call (no allocation; about as long as one DoF of
    /// [`super::TrajectoryGenerator::calculate`] each). NaN for a DoF without a time-optimal
    /// profile.
    #[must_use]
    pub fn independent_min_durations(&self) -> [f64; N] {
        core::array::from_fn(|i| match &self.pending[i] {
            Some(d) => independent_min_duration(d),
            None => self.independent_min_durations[i],
        })
    }

    /// True if at least one DoF starts with a braking pre-phase (a limit violation was
    /// unavoidable from the start state).
    #[must_use]
    pub fn is_braking(&self) -> bool {
        self.braking
    }

    /// Longest braking pre-phase (s) over the DoFs (zero without braking).
    #[must_use]
    pub fn brake_duration(&self) -> f64 {
        self.profiles
            .iter()
            .map(Profile::brake_duration)
            .fold(0.0, f64::max)
    }

    /// The profile of DoF `dof`.
    #[must_use]
    pub fn profile(&self, dof: usize) -> &Profile {
        &self.profiles[dof]
    }

    /// State of every DoF at time `t` (s). After the duration, each DoF holds its target (a
    /// target with non-zero acceleration keeps accelerating, as the profile's last state does).
    pub fn at_time(
        &self,
        t: f64,
        position: &mut [f64; N],
        velocity: &mut [f64; N],
        acceleration: &mut [f64; N],
    ) {
        for (i, prof) in self.profiles.iter().enumerate() {
            let s: DofState = prof.state_at(t);
            position[i] = s.position;
            velocity[i] = s.velocity;
            acceleration[i] = s.acceleration;
        }
    }

    /// State of DoF `dof` at time `t` (s).
    #[must_use]
    pub fn state_at(&self, dof: usize, t: f64) -> DofState {
        self.profiles[dof].state_at(t)
    }

    /// Analytic extrema of position, velocity and acceleration of every DoF over
    /// `[0, duration]` (braking pre-phase included).
    #[must_use]
    pub fn extrema(&self) -> [DofExtrema; N] {
        core::array::from_fn(|i| self.profiles[i].extrema())
    }
}
