//! The story of a closed-loop cut at `RUST_LOG=info`: one log line per
//! milestone (the edge touches, the first section fractures, the knife
//! reverses along the edge, the run ends), never one per tick. Logging
//! reads the loop's values and changes none of them.

use shearcut_sim::arm::ArmReading;

use super::plant_link::LinkAnswer;
use super::runner::LoopEnd;

/// Tangential moves shorter than this per tick are standstill, m (as the
/// summary's reversal count).
const STANDSTILL: f64 = 1e-9;

/// What the story has told so far.
#[derive(Debug, Clone, Default)]
pub struct CutStory {
    touched: bool,
    fractured: bool,
    /// Sign of the last tangential move (0 before any).
    tangential_sign: f64,
    /// Knife position along the edge at the last tick, m.
    last_z: Option<f64>,
    reversals: u32,
}

impl CutStory {
    /// A story with nothing told yet.
    pub fn new() -> Self {
        Self::default()
    }

    /// Notes one tick's answer; logs the milestones it reaches. Touch and
    /// fracture come from a simulated plant's truth (an arm bridge has
    /// none); reversals from the arm's reading.
    pub fn observe(&mut self, answer: &LinkAnswer) {
        let r = &answer.reading;
        if let Some(truth) = &answer.truth {
            if !self.touched && truth.contact_length > 0.0 {
                self.touched = true;
                tracing::info!(
                    "t = {:.3} s: the edge touches ({:.1} mm of edge in contact)",
                    r.time,
                    truth.contact_length * 1e3
                );
            }
            if !self.fractured && truth.fractured_sections > 0 {
                self.fractured = true;
                tracing::info!(
                    "t = {:.3} s: first fracture (crack front {:.2} mm below the top, work {:.4} J so far)",
                    r.time,
                    truth.crack_depth * 1e3,
                    truth.work
                );
            }
        }
        self.note_tangential_move(r);
    }

    fn note_tangential_move(&mut self, r: &ArmReading) {
        let z = r.position.z;
        if let Some(last) = self.last_z.replace(z) {
            let d = z - last;
            if d.abs() < STANDSTILL {
                return;
            }
            if self.tangential_sign != 0.0 && d.signum() != self.tangential_sign {
                self.reversals += 1;
                tracing::info!(
                    "t = {:.3} s: reversal {} along the edge, now towards the {}",
                    r.time,
                    self.reversals,
                    if d > 0.0 { "tip" } else { "heel" }
                );
            }
            self.tangential_sign = d.signum();
        }
    }

    /// Logs how the run ended after `ticks` controller ticks and `time` s
    /// of simulated time; `last` is the final answer, `rechoices` the
    /// plant's section re-choices over the run if it says (summarised
    /// here, not one line each).
    pub fn end(
        &self,
        end: &LoopEnd,
        ticks: usize,
        time: f64,
        last: &LinkAnswer,
        rechoices: Option<usize>,
    ) {
        let truth = last.truth;
        let what = match end {
            LoopEnd::Completed => "target depth reached".to_string(),
            LoopEnd::ControllerDone => "the controller ended its cut, knife at rest".to_string(),
            LoopEnd::TimedOut => "timed out".to_string(),
            LoopEnd::Failed(why) => format!("failed: {why}"),
            LoopEnd::Stopped(signal) => format!("stopped by {signal}"),
        };
        match truth {
            Some(t) => tracing::info!(
                "t = {time:.3} s: {what} after {ticks} ticks ({} reversals; crack front {:.2} mm, work {:.4} J)",
                self.reversals,
                t.crack_depth * 1e3,
                t.work
            ),
            None => tracing::info!(
                "t = {time:.3} s: {what} after {ticks} ticks ({} reversals)",
                self.reversals
            ),
        }
        if let Some(n) = rechoices {
            tracing::info!("the plant re-chose its moving sections {n} times over the cut");
        }
    }
}
