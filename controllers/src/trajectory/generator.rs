//! The online interface: one [`TrajectoryGenerator::update`] per control cycle.

use super::calculator;
use super::input::{TrajectoryError, TrajectoryInput, TrajectorySettings, TrajectoryStatus};
use super::trajectory::Trajectory;

/// Result of one control cycle.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct TrajectoryOutput<const N: usize> {
    /// Commanded position of each DoF for the next cycle.
    pub new_position: [f64; N],
    /// Commanded velocity.
    pub new_velocity: [f64; N],
    /// Commanded acceleration.
    pub new_acceleration: [f64; N],
    /// Time (s) since the current trajectory was calculated.
    pub time: f64,
    /// Duration (s) of the current trajectory.
    pub duration: f64,
    /// True if this cycle calculated a new trajectory (the input changed).
    pub new_calculation: bool,
}

impl<const N: usize> Default for TrajectoryOutput<N> {
    fn default() -> Self {
        Self {
            new_position: [0.0; N],
            new_velocity: [0.0; N],
            new_acceleration: [0.0; N],
            time: 0.0,
            duration: 0.0,
            new_calculation: false,
        }
    }
}

impl<const N: usize> TrajectoryOutput<N> {
    /// Copies the commanded state into the input's current state (the usual way to close the loop
    /// when the robot follows the command exactly).
    pub fn pass_to_input(&self, input: &mut TrajectoryInput<N>) {
        input.current_position = self.new_position;
        input.current_velocity = self.new_velocity;
        input.current_acceleration = self.new_acceleration;
    }
}

/// Time-optimal jerk-limited online trajectory generator for `N` DoFs.
///
/// ## Memory allocation
/// Everything is fixed-size and owned by value: the settings, one [`Trajectory`] (`N` profiles)
/// and a copy of the last input. [`Self::update`] and [`Self::calculate`] use only the stack
/// (a few kB per DoF) and never allocate.
#[derive(Debug, Clone)]
pub struct TrajectoryGenerator<const N: usize> {
    settings: TrajectorySettings,
    trajectory: Trajectory<N>,
    /// The input of the running trajectory with its current state advanced to the last output;
    /// an identical next input continues the trajectory instead of recalculating.
    expected: Option<TrajectoryInput<N>>,
    time: f64,
}

impl<const N: usize> TrajectoryGenerator<N> {
    /// A generator with validated `settings`.
    pub fn new(settings: TrajectorySettings) -> Result<Self, TrajectoryError> {
        settings.validate()?;
        Ok(Self {
            settings,
            trajectory: Trajectory::default(),
            expected: None,
            time: 0.0,
        })
    }

    /// The settings.
    #[must_use]
    pub fn settings(&self) -> &TrajectorySettings {
        &self.settings
    }

    /// The trajectory followed by [`Self::update`].
    #[must_use]
    pub fn trajectory(&self) -> &Trajectory<N> {
        &self.trajectory
    }

    /// Calculates the whole trajectory for `input` into `trajectory` (offline use; does not
    /// change the state of the online interface). On error `trajectory` may be partly
    /// overwritten (some DoFs' profiles already written): do not sample it.
    pub fn calculate(
        &self,
        input: &TrajectoryInput<N>,
        trajectory: &mut Trajectory<N>,
    ) -> Result<TrajectoryStatus, TrajectoryError> {
        calculator::calculate(input, &self.settings, trajectory)
    }

    /// One control cycle: recalculates if `input` differs from the state the generator expects
    /// (new target, limits, or a current state not equal to the last command), then advances one
    /// cycle and writes the next command. Returns `Finished` once the target is reached,
    /// `BrakingThenTarget` while an unavoidable-violation braking pre-phase runs, `Working`
    /// otherwise. On error the output is left unchanged, and the next call recalculates
    /// whatever its input (the failed calculation may have overwritten part of the running
    /// trajectory, which must not be followed on).
    pub fn update(
        &mut self,
        input: &TrajectoryInput<N>,
        output: &mut TrajectoryOutput<N>,
    ) -> Result<TrajectoryStatus, TrajectoryError> {
        output.new_calculation = false;
        if self.expected.as_ref() != Some(input) {
            if let Err(e) = calculator::calculate(input, &self.settings, &mut self.trajectory) {
                self.expected = None;
                return Err(e);
            }
            self.time = 0.0;
            output.new_calculation = true;
        }
        self.time += self.settings.cycle_time;
        let traj = &self.trajectory;
        traj.at_time(
            self.time,
            &mut output.new_position,
            &mut output.new_velocity,
            &mut output.new_acceleration,
        );
        output.time = self.time;
        output.duration = traj.duration();
        let mut next = *input;
        output.pass_to_input(&mut next);
        self.expected = Some(next);
        Ok(if self.time >= traj.duration() {
            TrajectoryStatus::Finished
        } else if self.time < traj.brake_duration() {
            TrajectoryStatus::BrakingThenTarget
        } else {
            TrajectoryStatus::Working
        })
    }
}
