//! The recorder's per-tick calls on the loop's thread (a
//! [`SeriesStream`]'s `control`, `tick_done`, `sample` and
//! `stop_requested`) allocate nothing: the workspace's counting allocator
//! (its own test binary) counts the calling thread's allocations inside
//! each call of a real closed-loop run; the writer thread formats and
//! writes the rows meanwhile.

#[path = "../controllers/tests/support/counting_allocator.rs"]
mod counting_allocator;

use counting_allocator::{Counting, thread_allocations};
use shearcut::closed_loop::{
    ControlSample, DroppedRows, LoopRecorder, SeriesStream, run_closed_loop_recorded,
};
use shearcut::cut_record::CutSample;
use shearcut::run_replica::RunReplica;
use shearcut::scenario::Scenario;
use shearcut::transport::StopSignal;

#[global_allocator]
static GLOBAL: Counting = Counting;

/// A recorder that counts the allocations its inner recorder makes on the
/// calling thread, and the calls.
struct CountingRecorder {
    inner: SeriesStream,
    allocations: usize,
    calls: usize,
}

impl CountingRecorder {
    fn measure(&mut self, f: impl FnOnce(&mut SeriesStream)) {
        let before = thread_allocations();
        f(&mut self.inner);
        self.allocations += thread_allocations() - before;
        self.calls += 1;
    }
}

impl LoopRecorder for CountingRecorder {
    fn sample(&mut self, sample: &CutSample) {
        self.measure(|s| s.sample(sample));
    }

    fn control(&mut self, record: &ControlSample) {
        self.measure(|s| s.control(record));
    }

    fn tick_done(&mut self, time: f64) {
        self.measure(|s| s.tick_done(time));
    }

    fn stop_requested(&self) -> Option<StopSignal> {
        let before = thread_allocations();
        let stop = self.inner.stop_requested();
        assert_eq!(thread_allocations(), before, "stop_requested allocated");
        stop
    }
}

#[test]
fn a_series_streams_per_tick_calls_allocate_nothing() {
    let dir = std::env::temp_dir().join(format!("shearcut-series-alloc-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    // The small loop of tests/closed_loop.rs: a force controller 3 mm into
    // the fig7 potato on a two-segment plant, several flush periods long.
    let text = include_str!("../config/scenarios/fig7-potato.toml")
        .replace("depth = 0.02", "depth = 0.003")
        + "\n[plant]\nsegments = 2\n\n[section]\nrow_spacing = 0.0005\n";
    let s = Scenario::parse(&text, "alloc.toml", "alloc").unwrap();
    let choice = "force:5".parse().unwrap();
    let mut recorder = CountingRecorder {
        inner: SeriesStream::create(&dir).unwrap(),
        allocations: 0,
        calls: 0,
    };
    let run = run_closed_loop_recorded(&s, choice, RunReplica::NOMINAL, &mut recorder).unwrap();
    let o = &run.output;
    assert!(o.simulated_s > 0.3, "{} s: several flushes", o.simulated_s);
    assert_eq!(
        recorder.calls,
        o.control.len() + o.samples.len() + o.ticks,
        "one call per record and per tick end"
    );
    assert_eq!(recorder.allocations, 0, "in {} calls", recorder.calls);
    // Nothing was dropped, and the files hold every record.
    assert_eq!(recorder.inner.finish().unwrap(), DroppedRows::default());
    let rows = |name: &str| {
        csv::Reader::from_path(dir.join(name))
            .unwrap()
            .records()
            .count()
    };
    assert_eq!(rows("controller.csv"), o.control.len());
    assert_eq!(rows("timeseries.csv"), o.samples.len());
    std::fs::remove_dir_all(&dir).ok();
}
