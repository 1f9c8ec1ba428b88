//! Sawing strokes: reversing the knife's tangential direction when the
//! blade budget runs out, at a constant slice-push ratio.
//!
//! A slicing cut spends blade: the contact arc moves along the edge by ξ
//! per unit depth (seed 000 §III, ξ = v_t / v_n), and the arc must stay on
//! the blade ([`BladeBudget`]). Once a stroke has used the blade, a cook
//! draws the knife back: the tangential direction reverses and the arc
//! travels back over the same part of the edge. Seed 000's toughness law
//! r(ξ, ν) (eq. 6) depends on |ξ| only, so the reversed stroke cuts as
//! easily as the forward one; what a reversal costs is the time to stop and
//! restart.
//!
//! A reversal here keeps ξ constant throughout: the knife decelerates along
//! its current direction of motion to rest, then accelerates along the
//! mirrored direction (−1, −σξ) — both straight lines through rest in the
//! knife plane's velocity space ([`VelocityShaper::command_in_line`]). So no
//! part of the reversal presses at a lower ratio than planned, and the depth
//! made while stopping and restarting is still cut at ξ. The stop starts
//! when the tangential stopping distance (plus one tick) reaches what is
//! left of the stroke. A knife that has already stopped tangentially at the
//! stroke's end (it pressed on there until a plan chose to saw) has nothing
//! to stop: it reverses at once, its tangential axis accelerating from rest
//! into the new direction while the normal motion goes on, rather than
//! stopping the normal motion too along the pressing line.

use shearcut_sim::arm::KnifeCommand;

use super::blade_budget::{BladeBudget, stopping_distance};
use super::cut_task::CutTask;
use super::velocity_shaper::VelocityShaper;

/// Where a stroke is.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum StrokePhase {
    /// Moving along the stroke (the shaper follows the plan).
    Stroking,
    /// Stopping along the line of slice-push ratio `xi` before reversing.
    Stopping {
        /// The ratio held while stopping.
        xi: f64,
    },
    /// Accelerating along the reversed line to `speed` (m/s, along the
    /// line) at ratio `xi`.
    Restarting {
        /// The ratio held while restarting.
        xi: f64,
        /// The speed along the line to reach, m/s.
        speed: f64,
    },
}

/// The sawing state of a cut: the tangential direction, the reversals made
/// and the one under way, if any. Allocation-free.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SawingStroke {
    direction: f64,
    phase: StrokePhase,
    reversals: u32,
    max_reversals: u32,
}

/// Fraction of the stroke left below which a knife that has already stopped
/// tangentially (a plan that chose to saw late) reverses anyway.
const STOPPED_AT_END: f64 = 0.05;

impl SawingStroke {
    /// Towards the tip, no reversal yet, at most `max_reversals` (0: never
    /// saw).
    pub fn new(max_reversals: u32) -> Self {
        Self {
            direction: 1.0,
            phase: StrokePhase::Stroking,
            reversals: 0,
            max_reversals,
        }
    }

    /// The tangential direction now: +1 towards the tip, −1 back.
    pub fn direction(&self) -> f64 {
        self.direction
    }

    /// Reversals made so far.
    pub fn reversals(&self) -> u32 {
        self.reversals
    }

    /// Reversals still allowed.
    pub fn reversals_left(&self) -> u32 {
        self.max_reversals - self.reversals
    }

    /// The phase.
    pub fn phase(&self) -> StrokePhase {
        self.phase
    }

    /// The command for the next tick towards the plan (`normal_speed`,
    /// `tangential_speed` ≥ 0, m/s, the latter in the stroke's direction),
    /// with `budget` observed this tick. `saw` says whether the plan wants
    /// more blade than this stroke has (so reversing pays); otherwise the
    /// knife stops tangentially at the stroke's end and presses on, as
    /// without sawing.
    pub fn command(
        &mut self,
        shaper: &mut VelocityShaper,
        budget: &BladeBudget,
        task: &CutTask,
        normal_speed: f64,
        tangential_speed: f64,
        saw: bool,
    ) -> KnifeCommand {
        let l = &task.limits;
        let allowed_towards = |direction| {
            budget.allowed_speed_towards(direction, tangential_speed, l.acceleration, l.jerk)
        };
        let mut allowed = allowed_towards(self.direction);
        if self.phase == StrokePhase::Stroking
            && saw
            && self.reversals < self.max_reversals
            && tangential_speed > 0.0
            && (allowed < tangential_speed || self.at_end(shaper, budget, task))
        {
            let v = shaper.current().velocity;
            if v.z * self.direction <= 0.0 {
                // Already stopped tangentially (a plan that chose to saw
                // late): nothing to stop; the shaper takes the tangential
                // axis from rest into the new direction while the normal
                // motion goes on.
                self.direction = -self.direction;
                self.reversals += 1;
                allowed = allowed_towards(self.direction);
            } else {
                let v_n = -v.y;
                let xi = if v_n > 0.0 { v.z.abs() / v_n } else { 0.0 };
                self.phase = StrokePhase::Stopping { xi };
            }
        }
        match self.phase {
            StrokePhase::Stroking => shaper.command(normal_speed, self.direction * allowed),
            StrokePhase::Stopping { xi } => {
                let command = shaper.command_in_line(xi, self.direction, 0.0);
                if shaper.line_finished() {
                    self.direction = -self.direction;
                    self.reversals += 1;
                    let xi = if normal_speed > 0.0 {
                        tangential_speed / normal_speed
                    } else {
                        0.0
                    };
                    self.phase = StrokePhase::Restarting {
                        xi,
                        speed: normal_speed.hypot(tangential_speed),
                    };
                }
                command
            }
            StrokePhase::Restarting { xi, speed } => {
                let command = shaper.command_in_line(xi, self.direction, speed);
                if shaper.line_finished() {
                    self.phase = StrokePhase::Stroking;
                }
                command
            }
        }
    }

    /// Whether the stroke must stop now to stay on the blade: the
    /// tangential distance of a stop along the current line, plus one tick
    /// of travel, reaches 99 % of what is left (the margin of
    /// [`BladeBudget::allowed_speed_towards`]); or the knife has already
    /// stopped tangentially near the end.
    fn at_end(&self, shaper: &VelocityShaper, budget: &BladeBudget, task: &CutTask) -> bool {
        let left = budget.remaining_towards(self.direction);
        let v = shaper.current().velocity;
        let v_t = v.z * self.direction;
        if v_t <= 0.0 {
            return left < STOPPED_AT_END * budget.stroke_length();
        }
        let speed = v.y.hypot(v.z);
        let l = &task.limits;
        let stop = v_t / speed * stopping_distance(speed, l.acceleration, l.jerk);
        stop + v_t * task.period >= 0.99 * left
    }
}
