//! Jerk-limited knife velocity commands from planned velocities.

use nalgebra::Vector3;
use shearcut_sim::plant::KnifeCommand;

use super::cut_task::MotionLimits;
use crate::trajectory::{
    ControlInterface, Synchronization, TrajectoryError, TrajectoryGenerator, TrajectoryInput,
    TrajectoryOutput, TrajectorySettings,
};

/// Turns a planned knife velocity (normal speed down, tangential speed
/// towards the tip) into one command per servo tick, time-optimally under
/// the acceleration and jerk limits, with our trajectory generator's velocity
/// interface on the knife plane's two axes (y, z).
///
/// The arm is assumed to execute every accepted command, so the generator's
/// own output is its next current state; [`VelocityShaper::resync`] restarts
/// from a measured velocity when the arm did something else (a refused
/// command). Allocation-free.
#[derive(Debug, Clone)]
pub struct VelocityShaper {
    generator: TrajectoryGenerator<2>,
    input: TrajectoryInput<2>,
    output: TrajectoryOutput<2>,
    errors: u64,
}

impl VelocityShaper {
    /// A shaper at rest for a servo `period` (s) within `limits`.
    ///
    /// # Errors
    /// The period is not finite and positive.
    pub fn new(period: f64, limits: &MotionLimits) -> Result<Self, TrajectoryError> {
        let generator =
            TrajectoryGenerator::new(TrajectorySettings::default().with_cycle_time(period))?;
        let input = TrajectoryInput::<2> {
            interface: ControlInterface::Velocity,
            synchronization: Synchronization::Time,
            max_velocity: [limits.normal_speed, limits.tangential_speed],
            max_acceleration: [limits.acceleration; 2],
            max_jerk: [limits.jerk; 2],
            ..TrajectoryInput::default()
        };
        Ok(Self {
            generator,
            input,
            output: TrajectoryOutput::default(),
            errors: 0,
        })
    }

    /// A shaper at rest for a cut task's servo period and limits; a bad
    /// period is reported as the task's invalid setting.
    pub fn for_task(task: &super::CutTask) -> Result<Self, shearcut_sim::InvalidSetting> {
        Self::new(task.period, &task.limits)
            .map_err(|e| shearcut_sim::InvalidSetting::new("period", task.period, e.to_string()))
    }

    /// The command for the next tick on the way to the planned normal speed
    /// `normal_speed` (m/s, down) and `tangential_speed` (m/s, towards the tip).
    pub fn command(&mut self, normal_speed: f64, tangential_speed: f64) -> KnifeCommand {
        self.input.target_velocity = [-normal_speed, tangential_speed];
        self.input.target_acceleration = [0.0; 2];
        match self.generator.update(&self.input, &mut self.output) {
            Ok(_) => self.output.pass_to_input(&mut self.input),
            Err(_) => {
                // Only a non-finite plan gets here: hold the velocity, and
                // let the acceleration decay to zero through the jerk limit
                // next tick by restarting from the held state.
                self.errors += 1;
                self.input.current_acceleration = [0.0; 2];
            }
        }
        self.current()
    }

    /// The last command.
    pub fn current(&self) -> KnifeCommand {
        let v = self.input.current_velocity;
        KnifeCommand {
            velocity: Vector3::new(0.0, v[0], v[1]),
        }
    }

    /// Restarts from a measured knife `velocity` at zero acceleration (after
    /// the arm refused a command and stopped, say).
    pub fn resync(&mut self, velocity: &Vector3<f64>) {
        self.input.current_velocity = [velocity.y, velocity.z];
        self.input.current_acceleration = [0.0; 2];
    }

    /// Ticks whose plan the generator could not use (non-finite).
    pub fn errors(&self) -> u64 {
        self.errors
    }
}
