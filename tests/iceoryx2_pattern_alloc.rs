//! Which iceoryx2 0.10 operations allocate after construction, counted by
//! the workspace's counting allocator over every thread (its own test
//! binary, one test so nothing else runs while counting). The loop's
//! transport is built on the ones asserted here to allocate nothing:
//! blackboard entries (write and read), event notification and listening,
//! the node's signal check. The others
//! are printed for the record (`-- --nocapture`); measured with iceoryx2
//! 0.10.0:
//! - publish-subscribe: one allocation per `loan_uninit` (and so per
//!   `send_copy`): `Publisher::loan_uninit` → `SampleMutUninit::new`
//!   (iceoryx2 `src/sample_mut_uninit.rs:327`) → `ChunkMutSharedState::new`
//!   (`src/port/details/chunk_mut_shared_state.rs:102`) → the `ipc::Service`
//!   thread-safety policy's `Rc::new` (iceoryx2-cal
//!   `src/arc_sync_policy/single_threaded.rs:69`); `Subscriber::receive`
//!   allocates nothing. A round trip over two pub-sub services would cost
//!   two allocations (one per side), whatever the buffer, history or port
//!   counts.
//! - request-response: the same per-request state (one allocation on the
//!   client per request, two on the server).
//! - `WaitSet::wait_and_process_once_with_timeout`: two per wait.
//! - `Node::list` (dead-node detection): about 1200 per call.

use std::sync::atomic::Ordering;
use std::time::Duration;

use iceoryx2::prelude::*;
use shearcut::transport::wire::{WireCommand, WireMeasurement};

#[path = "../controllers/tests/support/counting_allocator.rs"]
mod counting_allocator;

use counting_allocator::{ALLOCATIONS, Counting, TRACK_ALL};

#[global_allocator]
static GLOBAL: Counting = Counting;

const CALLS: usize = 1000;

/// Allocations per call of `f` (after 100 warm-up calls).
fn per_call(what: &str, mut f: impl FnMut()) -> f64 {
    for _ in 0..100 {
        f();
    }
    ALLOCATIONS.store(0, Ordering::SeqCst);
    TRACK_ALL.store(true, Ordering::SeqCst);
    for _ in 0..CALLS {
        f();
    }
    TRACK_ALL.store(false, Ordering::SeqCst);
    let n = ALLOCATIONS.load(Ordering::SeqCst) as f64 / CALLS as f64;
    println!("{what:<55} {n:>8.1} allocations per call");
    n
}

#[test]
fn the_transport_uses_only_allocation_free_iceoryx2_operations() {
    let prefix = format!("scp{}_", std::process::id());
    let mut cfg = Config::default();
    cfg.global.prefix = FileName::new(prefix.as_bytes()).unwrap();
    let node = NodeBuilder::new()
        .config(&cfg)
        .create::<ipc::Service>()
        .unwrap();
    let name = |s: &str| ServiceName::new(s).unwrap();

    // What the loop uses.
    let board = node
        .service_builder(&name("probe/board"))
        .blackboard_creator::<u64>()
        .add::<WireMeasurement>(0, WireMeasurement::empty())
        .create()
        .unwrap();
    let writer = board.writer_builder().create().unwrap();
    let reader = board.reader_builder().create().unwrap();
    let written = writer.entry::<WireMeasurement>(&0).unwrap();
    let read = reader.entry::<WireMeasurement>(&0).unwrap();
    let mut m = WireMeasurement::empty();
    let board_cost = per_call("blackboard update_with_copy + get", || {
        m.sequence = m.sequence.wrapping_add(1);
        written.update_with_copy(m);
        assert_eq!(read.get().sequence, m.sequence);
    });
    let event = node
        .service_builder(&name("probe/event"))
        .event()
        .open_or_create()
        .unwrap();
    let notifier = event.notifier_builder().create().unwrap();
    let listener = event.listener_builder().create().unwrap();
    let try_cost = per_call("notify + listener try_wait", || {
        notifier.notify().unwrap();
        listener.try_wait(|_| {}).unwrap();
    });
    let timed_cost = per_call("notify + listener timed_wait", || {
        notifier.notify().unwrap();
        listener
            .timed_wait(|_| {}, Duration::from_millis(1))
            .unwrap();
    });
    let signal_cost = per_call("node.wait(0) (SIGINT/SIGTERM check)", || {
        let _ = node.wait(Duration::ZERO);
    });

    // What it avoids.
    let topic = node
        .service_builder(&name("probe/topic"))
        .publish_subscribe::<WireCommand>()
        .max_publishers(1)
        .max_subscribers(1)
        .history_size(0)
        .subscriber_max_buffer_size(1)
        .open_or_create()
        .unwrap();
    let publisher = topic
        .publisher_builder()
        .max_loaned_samples(1)
        .create()
        .unwrap();
    let subscriber = topic.subscriber_builder().buffer_size(1).create().unwrap();
    let c = WireCommand::empty();
    per_call("publish-subscribe loan_uninit + send + receive", || {
        publisher
            .loan_uninit()
            .unwrap()
            .write_payload(c)
            .send()
            .unwrap();
        assert!(subscriber.receive().unwrap().is_some());
    });
    per_call("publish-subscribe receive (nothing waiting)", || {
        assert!(subscriber.receive().unwrap().is_none());
    });
    let waitset = WaitSetBuilder::new().create::<ipc::Service>().unwrap();
    let _guard = waitset.attach_notification(&listener).unwrap();
    per_call(
        "notify + WaitSet wait_and_process_once_with_timeout",
        || {
            notifier.notify().unwrap();
            waitset
                .wait_and_process_once_with_timeout(
                    |_| {
                        let _ = listener.try_wait(|_| {});
                        CallbackProgression::Continue
                    },
                    Duration::from_millis(1),
                )
                .unwrap();
        },
    );
    per_call("Node::list (dead-node detection)", || {
        let _ = Node::<ipc::Service>::list(&cfg, |_| CallbackProgression::Continue);
    });
    drop(_guard);
    drop((waitset, subscriber, publisher, topic));
    drop((
        listener, notifier, event, read, written, reader, writer, board, node,
    ));
    if let Ok(entries) = std::fs::read_dir("/dev/shm") {
        for e in entries.flatten() {
            if e.file_name().to_string_lossy().starts_with(&prefix) {
                std::fs::remove_file(e.path()).ok();
            }
        }
    }
    assert_eq!(
        (board_cost, try_cost, timed_cost, signal_cost),
        (0.0, 0.0, 0.0, 0.0)
    );
}
