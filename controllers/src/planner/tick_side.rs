//! The tick side of planning: [`Planner`].

use std::panic::{AssertUnwindSafe, catch_unwind};
use std::sync::Arc;
use std::sync::atomic::Ordering;
use std::thread::JoinHandle;

use triple_buffer::{Input, Output, triple_buffer};

use super::exchange::{Signals, Stamped};
use super::planner_settings::validate;
use super::{
    LatencyPolicy, PlanInForce, PlanJob, PlannerError, PlannerStats, PlannerStatus, SubmitStatus,
    planner_thread,
};

/// Runs a [`PlanJob`] off the servo tick and hands its plans to the tick.
///
/// The tick side calls [`Self::poll`] once at the start of every servo
/// tick (it advances the tick count and returns the plan in force) and
/// [`Self::submit`] whenever it wants a new plan. Under
/// [`LatencyPolicy::Lockstep`] and [`LatencyPolicy::Realtime`] the job runs
/// on a thread spawned by [`Self::new`] and joined on drop; requests and
/// plans cross through one single-slot triple buffer each way.
///
/// ## Guarantees of the tick side
/// - Allocation-free after construction: `poll` and `submit` are a few
///   atomic operations, a copy of the request and an unpark.
/// - Wait-free under `Realtime`: `poll` takes whatever plan is newest and
///   no lock is ever taken. The one wait is `Lockstep`'s, in the `poll` at
///   which a plan is due and not yet ready (see
///   [`LatencyPolicy::Lockstep`]): a mutex and condition variable that the
///   planner thread holds only to ring it after a plan.
/// - A valid plan is always in force (the initial plan until the first
///   arrives); its age in ticks is known ([`PlanInForce::age`]).
/// - A panic in the job becomes [`PlannerStatus::JobPanicked`]: the last
///   plan stays in force, never a hang.
///
/// ## Memory allocation
/// `new` clones the initial plan into three buffers (two for `Inline`),
/// makes three request slots and spawns the thread; nothing after that.
pub struct Planner<J: PlanJob> {
    policy: LatencyPolicy,
    /// Current tick (0 at the first poll).
    tick: u64,
    polled: bool,
    /// Number of the next request.
    next_seq: u64,
    /// Number of the plan in force (0: the initial plan).
    seq_in_force: u64,
    /// Request tick of the plan in force.
    request_tick: Option<u64>,
    /// Lockstep: number and due tick of the request in flight.
    in_flight: Option<(u64, u64)>,
    fresh: bool,
    status: PlannerStatus,
    stats: PlannerStats,
    engine: Engine<J>,
}

enum Engine<J: PlanJob> {
    Inline {
        job: J,
        in_force: J::Plan,
        scratch: J::Plan,
    },
    Threaded {
        requests: Input<Stamped<Option<J::Request>>>,
        plans: Output<Stamped<J::Plan>>,
        signals: Arc<Signals>,
        thread: Option<JoinHandle<()>>,
    },
}

impl<J: PlanJob + Send + 'static> Planner<J> {
    /// A planner running `job` under `policy`, with `initial` in force
    /// until the first plan arrives.
    ///
    /// # Errors
    /// [`PlannerError::Setting`] if a lockstep latency is outside
    /// 1..=[`super::MAX_LOCKSTEP_TICKS`]; [`PlannerError::Spawn`] if the
    /// thread cannot be started.
    pub fn new(job: J, initial: J::Plan, policy: LatencyPolicy) -> Result<Self, PlannerError> {
        validate(policy)?;
        let engine = match policy {
            LatencyPolicy::Inline => Engine::Inline {
                job,
                scratch: initial.clone(),
                in_force: initial,
            },
            LatencyPolicy::Lockstep { .. } | LatencyPolicy::Realtime => {
                let (requests, requests_out) = triple_buffer(&Stamped {
                    seq: 0,
                    tick: 0,
                    value: None,
                });
                let (plans_in, plans) = triple_buffer(&Stamped {
                    seq: 0,
                    tick: 0,
                    value: initial,
                });
                let signals = Arc::new(Signals::default());
                let thread_signals = Arc::clone(&signals);
                let ring = matches!(policy, LatencyPolicy::Lockstep { .. });
                let thread = std::thread::Builder::new()
                    .name("shearcut-planner".into())
                    .spawn(move || {
                        planner_thread::run(job, requests_out, plans_in, thread_signals, ring);
                    })?;
                Engine::Threaded {
                    requests,
                    plans,
                    signals,
                    thread: Some(thread),
                }
            }
        };
        Ok(Self {
            policy,
            tick: 0,
            polled: false,
            next_seq: 1,
            seq_in_force: 0,
            request_tick: None,
            in_flight: None,
            fresh: false,
            status: PlannerStatus::Running,
            stats: PlannerStats::default(),
            engine,
        })
    }
}

impl<J: PlanJob> Planner<J> {
    /// Starts the next servo tick (tick 0 at the first call) and returns
    /// the plan in force in it: under `Realtime` the newest plan, under
    /// `Lockstep` the plan due now (waiting for it if it is not ready, the
    /// only wait) or else the one in force.
    pub fn poll(&mut self) -> PlanInForce<'_, J::Plan> {
        if self.polled {
            self.tick += 1;
        }
        self.polled = true;
        self.fresh = false;
        if let Engine::Threaded { plans, signals, .. } = &mut self.engine {
            match self.policy {
                LatencyPolicy::Realtime => {
                    if plans.update() {
                        let s = plans.output_buffer();
                        self.stats.superseded += s.seq - self.seq_in_force - 1;
                        self.seq_in_force = s.seq;
                        self.request_tick = Some(s.tick);
                        self.stats.delivered += 1;
                        self.fresh = true;
                    }
                    if self.status == PlannerStatus::Running
                        && signals.panicked.load(Ordering::Acquire)
                    {
                        self.status = panicked(signals);
                    }
                }
                LatencyPolicy::Lockstep { .. } => {
                    if let Some((seq, due)) = self.in_flight
                        && due == self.tick
                    {
                        self.in_flight = None;
                        signals.wait_settled(seq);
                        if signals.published.load(Ordering::Acquire) >= seq {
                            plans.update();
                            let s = plans.output_buffer();
                            debug_assert_eq!(s.seq, seq);
                            self.seq_in_force = s.seq;
                            self.request_tick = Some(s.tick);
                            self.stats.delivered += 1;
                            self.fresh = true;
                        } else {
                            self.status = panicked(signals);
                        }
                    }
                }
                LatencyPolicy::Inline => {}
            }
        }
        self.plan()
    }

    /// Asks for a plan starting from `request`, stamped with the current
    /// tick. `Inline` plans it here, visible at once; `Lockstep` makes it
    /// visible at the poll `ticks` ticks on; `Realtime` when it is ready.
    pub fn submit(&mut self, request: &J::Request) -> SubmitStatus {
        if self.status != PlannerStatus::Running {
            self.stats.refused += 1;
            return SubmitStatus::JobPanicked;
        }
        if self.in_flight.is_some() {
            self.stats.refused += 1;
            return SubmitStatus::InFlight;
        }
        let seq = self.next_seq;
        self.next_seq += 1;
        self.stats.submitted += 1;
        match &mut self.engine {
            Engine::Inline {
                job,
                in_force,
                scratch,
            } => {
                if catch_unwind(AssertUnwindSafe(|| job.plan(request, scratch))).is_ok() {
                    std::mem::swap(in_force, scratch);
                    self.seq_in_force = seq;
                    self.request_tick = Some(self.tick);
                    self.stats.delivered += 1;
                    self.fresh = true;
                } else {
                    self.status = PlannerStatus::JobPanicked {
                        request_tick: self.tick,
                    };
                }
            }
            Engine::Threaded {
                requests, thread, ..
            } => {
                requests.write(Stamped {
                    seq,
                    tick: self.tick,
                    value: Some(*request),
                });
                if let Some(thread) = thread {
                    thread.thread().unpark();
                }
                if let LatencyPolicy::Lockstep { ticks } = self.policy {
                    self.in_flight = Some((seq, self.tick + u64::from(ticks)));
                }
            }
        }
        SubmitStatus::Accepted
    }

    /// The plan in force in the current tick, without advancing it.
    pub fn plan(&self) -> PlanInForce<'_, J::Plan> {
        let plan = match &self.engine {
            Engine::Inline { in_force, .. } => in_force,
            Engine::Threaded { plans, .. } => &plans.output_buffer().value,
        };
        PlanInForce {
            plan,
            request_tick: self.request_tick,
            age: self.tick - self.request_tick.unwrap_or(0),
            fresh: self.fresh,
            status: self.status,
        }
    }

    /// The current tick (0 until after the first poll).
    pub fn tick(&self) -> u64 {
        self.tick
    }

    /// The latency policy.
    pub fn policy(&self) -> LatencyPolicy {
        self.policy
    }

    /// Counters so far.
    pub fn stats(&self) -> PlannerStats {
        self.stats
    }

    /// How long each plan took on the planner thread so far, µs of wall
    /// clock, in the order made (`Lockstep` and `Realtime`; empty under
    /// `Inline`, whose plans are made on the tick). Locks and copies: for
    /// after a run, never on a tick.
    pub fn solve_times_us(&self) -> Vec<f64> {
        match &self.engine {
            Engine::Threaded { signals, .. } => signals
                .solve_times_us
                .lock()
                .unwrap_or_else(std::sync::PoisonError::into_inner)
                .clone(),
            Engine::Inline { .. } => Vec::new(),
        }
    }
}

fn panicked(signals: &Signals) -> PlannerStatus {
    PlannerStatus::JobPanicked {
        request_tick: signals.panicked_tick.load(Ordering::Relaxed),
    }
}

impl<J: PlanJob> Drop for Planner<J> {
    /// Stops the planner thread and joins it: waits for the plan under way,
    /// if any, and drops the job on its thread.
    fn drop(&mut self) {
        if let Engine::Threaded {
            signals, thread, ..
        } = &mut self.engine
            && let Some(thread) = thread.take()
        {
            signals.stop.store(true, Ordering::Release);
            thread.thread().unpark();
            // The loop catches the job's panics, so the thread itself
            // does not panic; nothing to report if it somehow did.
            let _ = thread.join();
        }
    }
}
