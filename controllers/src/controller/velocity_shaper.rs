//! Jerk-limited knife velocity commands from planned velocities.

use nalgebra::Vector3;
use shearcut_sim::arm::KnifeCommand;

use super::cut_task::MotionLimits;
use crate::trajectory::{
    ControlInterface, Synchronization, TrajectoryError, TrajectoryGenerator, TrajectoryInput,
    TrajectoryOutput, TrajectorySettings, TrajectoryStatus,
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
///
/// [`VelocityShaper::command_in_line`] changes the speed along a fixed
/// direction instead (a one-DoF profile of the speed mapped onto both axes:
/// phase synchronisation of the velocity interface), so the slice-push ratio
/// stays exactly constant while the knife stops or starts — what a sawing
/// reversal needs.
#[derive(Debug, Clone)]
pub struct VelocityShaper {
    generator: TrajectoryGenerator<2>,
    input: TrajectoryInput<2>,
    output: TrajectoryOutput<2>,
    line_generator: TrajectoryGenerator<1>,
    line_input: TrajectoryInput<1>,
    line_output: TrajectoryOutput<1>,
    /// Unit direction (y, z) of the line mode, if in it.
    line: Option<[f64; 2]>,
    /// Whether the line mode's speed has reached its target.
    line_finished: bool,
    limits: MotionLimits,
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
        let line_generator =
            TrajectoryGenerator::new(TrajectorySettings::default().with_cycle_time(period))?;
        let line_input = TrajectoryInput::<1> {
            interface: ControlInterface::Velocity,
            max_acceleration: [limits.acceleration],
            max_jerk: [limits.jerk],
            ..TrajectoryInput::default()
        };
        Ok(Self {
            generator,
            input,
            output: TrajectoryOutput::default(),
            line_generator,
            line_input,
            line_output: TrajectoryOutput::default(),
            line: None,
            line_finished: false,
            limits: *limits,
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
        self.line = None;
        self.line_finished = false;
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

    /// The command for the next tick on the way to the speed `speed` (m/s,
    /// ≥ 0) along the knife-plane direction of slice-push ratio `xi` (≥ 0)
    /// and tangential `direction` (+1 towards the tip, −1 back): the
    /// velocity stays on the line (−1, direction·ξ)·v_n through rest, so ξ
    /// is constant throughout (a straight line in velocity space). Entering
    /// the line mode projects the current velocity and acceleration onto the
    /// line, so call it from rest or from a velocity along that line (a
    /// cruise at ξ); the speed limit along the line is the tighter of the
    /// two axes' speed limits, and acceleration and jerk are limited as per
    /// axis (so also on each axis).
    pub fn command_in_line(&mut self, xi: f64, direction: f64, speed: f64) -> KnifeCommand {
        let norm = (1.0 + xi * xi).sqrt();
        let u = [-1.0 / norm, direction.signum() * xi / norm];
        if self.line != Some(u) {
            let v = self.input.current_velocity;
            let a = self.input.current_acceleration;
            self.line_input.current_velocity = [(v[0] * u[0] + v[1] * u[1]).max(0.0)];
            self.line_input.current_acceleration = [a[0] * u[0] + a[1] * u[1]];
            let mut v_max = self.limits.normal_speed / u[0].abs();
            if u[1] != 0.0 {
                v_max = v_max.min(self.limits.tangential_speed / u[1].abs());
            }
            self.line_input.max_velocity = [v_max];
            self.line = Some(u);
        }
        self.line_input.target_velocity = [speed.clamp(0.0, self.line_input.max_velocity[0])];
        self.line_input.target_acceleration = [0.0];
        self.line_finished = match self
            .line_generator
            .update(&self.line_input, &mut self.line_output)
        {
            Ok(status) => {
                self.line_output.pass_to_input(&mut self.line_input);
                status == TrajectoryStatus::Finished
            }
            Err(_) => {
                self.errors += 1;
                self.line_input.current_acceleration = [0.0];
                false
            }
        };
        let (s, a) = (
            self.line_input.current_velocity[0],
            self.line_input.current_acceleration[0],
        );
        self.input.current_velocity = [s * u[0], s * u[1]];
        self.input.current_acceleration = [a * u[0], a * u[1]];
        self.current()
    }

    /// Whether the line mode's speed has reached its target (at rest
    /// acceleration); false outside the line mode.
    pub fn line_finished(&self) -> bool {
        self.line.is_some() && self.line_finished
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
        self.line = None;
    }

    /// Ticks whose plan the generator could not use (non-finite).
    pub fn errors(&self) -> u64 {
        self.errors
    }
}
