//! A planning job shaped like the MPC's for the planner tests and bench:
//! requests are a cut state, plans are 64 stages of (ξ, τ) plus a status,
//! origin, step and counters. The plan is a deterministic, non-linear
//! function of the request and of the job's memory of its previous plans,
//! so any lost, repeated or reordered request changes every later plan.
#![allow(dead_code)] // Each test binary uses a part.

use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::{Arc, Barrier};
use std::time::Duration;

use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;
use shearcut_controllers::planner::PlanJob;

/// Stages of a plan: the MPC's largest horizon.
pub const STAGES: usize = 64;

/// What the tick side asks for.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct CutRequest {
    /// Depth reached, m.
    pub depth: f64,
    /// Normal speed, m/s.
    pub speed: f64,
}

/// A fixed-size plan.
#[derive(Debug, Clone, PartialEq)]
pub struct StagePlan {
    /// Slice-push ratio per stage.
    pub xi: [f64; STAGES],
    /// Time per unit depth per stage, s/m.
    pub tau: [f64; STAGES],
    /// Depth of the first stage, m.
    pub origin: f64,
    /// Depth per stage, m.
    pub step: f64,
    /// Plans made by the job so far, this one included.
    pub count: u64,
}

impl Default for StagePlan {
    fn default() -> Self {
        Self {
            xi: [0.0; STAGES],
            tau: [20.0; STAGES],
            origin: 0.0,
            step: 1e-3,
            count: 0,
        }
    }
}

impl StagePlan {
    /// Every number of the plan as bits, for exact comparisons.
    pub fn bits(&self) -> Vec<u64> {
        let mut v: Vec<u64> = self
            .xi
            .iter()
            .chain(&self.tau)
            .map(|x| x.to_bits())
            .collect();
        v.extend([self.origin.to_bits(), self.step.to_bits(), self.count]);
        v
    }
}

/// The job. Options: sleep a random time before each plan (to shake the
/// thread schedule), block on a barrier before the first plan, panic at a
/// given plan, flag its drop.
#[derive(Default)]
pub struct StageJob {
    /// Memory of the previous plans (0 at start).
    pub memory: f64,
    /// Plans made so far.
    pub count: u64,
    /// Sleeps up to this many µs before a plan, drawn from `sleeps`.
    pub max_sleep_us: u64,
    /// Random source of the sleeps (not of the plans).
    pub sleeps: Option<ChaCha8Rng>,
    /// Passed before the first plan.
    pub gate: Option<Gate>,
    /// Panics while making this plan (1-based).
    pub panic_at: Option<u64>,
    /// Set when the job is dropped.
    pub dropped: Option<DropFlag>,
}

impl StageJob {
    /// A job that sleeps 0..`max_sleep_us` µs before each plan (seeded).
    pub fn with_sleeps(seed: u64, max_sleep_us: u64) -> Self {
        Self {
            max_sleep_us,
            sleeps: Some(ChaCha8Rng::seed_from_u64(seed)),
            ..Self::default()
        }
    }
}

impl PlanJob for StageJob {
    type Request = CutRequest;
    type Plan = StagePlan;

    fn plan(&mut self, request: &CutRequest, out: &mut StagePlan) {
        if let Some(gate) = self.gate.take() {
            gate.entered.wait();
            gate.release.wait();
        }
        if let Some(rng) = &mut self.sleeps {
            let us = rng.random_range(0..=self.max_sleep_us);
            if us > 0 {
                std::thread::sleep(Duration::from_micros(us));
            }
        }
        self.count += 1;
        assert!(self.panic_at != Some(self.count), "planned to panic");
        out.origin = request.depth;
        out.step = 1e-3 + 1e-5 * (self.count % 7) as f64;
        for i in 0..STAGES {
            let x = (i as f64 + 1.0) * (request.depth * 37.0 + self.memory);
            out.xi[i] = 1.2 + 0.8 * x.sin();
            out.tau[i] = 1.0 / (request.speed + 1e-3 * (x * 0.5).cos().abs());
        }
        out.count = self.count;
        self.memory = 0.7 * self.memory + 0.3 * out.xi[STAGES / 2];
    }
}

/// Two barriers of two: the job waits on `entered` (telling the test it
/// is planning) and then on `release` (until the test lets it go).
pub struct Gate {
    /// Passed when the job starts its first plan.
    pub entered: Arc<Barrier>,
    /// Passed when the test releases the job.
    pub release: Arc<Barrier>,
}

/// A flag set when its holder is dropped.
pub struct DropFlag(pub Arc<AtomicBool>);

impl Drop for DropFlag {
    fn drop(&mut self) {
        self.0.store(true, Ordering::SeqCst);
    }
}
