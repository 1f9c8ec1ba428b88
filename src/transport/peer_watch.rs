//! Whether the other side of a run is there while this process starts up:
//! a thread that looks at the peer's iceoryx2 node every [`PEER_LOOK`] from
//! the moment this process's own node exists until the loop starts, so that
//! a peer that dies (or exits) before the loop is noticed within a look,
//! even while this process is busy building its plant or controller.

use std::sync::atomic::{AtomicBool, AtomicU8, Ordering};
use std::sync::{Arc, Mutex};
use std::thread::JoinHandle;
use std::time::Duration;

use iceoryx2::identifiers::UniqueNodeId;
use iceoryx2::prelude::*;

use super::loop_services::{PeerState, Role, node_name};
use super::run_node::look;

/// How often the watch looks at the peer's node (iceoryx2's node list:
/// allocating on every look, on the watch's own thread).
pub const PEER_LOOK: Duration = Duration::from_millis(20);

/// What this process knows of its peer before the loop starts.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum PeerFate {
    /// Not seen yet (it may not have started).
    NotSeen = 0,
    /// Seen alive at the last look.
    Alive = 1,
    /// Its node is dead: the process died without cleaning up (a kill, a
    /// crash), iceoryx2 dead-node detection.
    Died = 2,
    /// Seen alive, and its node is gone: the process exited (or died and
    /// another process of the prefix cleaned its node before a look).
    Ended = 3,
    /// Never seen alive, and a recent dead node of its name found at this
    /// process's start ([`RECENT_PEER`](super::run_node::RECENT_PEER)): the
    /// peer died before this process looked, unless a live node of the
    /// name appears within [`UNSEEN_GRACE`] (then the dead one was an
    /// earlier run's, killed just before this run started). The watch
    /// turns it into [`PeerFate::Died`] after the grace.
    DiedUnseen = 4,
}

/// How long a process whose peer ended (exited) before the loop waits for
/// a SIGINT/SIGTERM of its own before it reports the peer's end: a
/// supervisor stopping a run on a signal stops the controller first and
/// the plant just after, and the plant's end is then that clean stop, not
/// a lost controller.
pub const ENDED_PEER_SIGNAL_WAIT: Duration = Duration::from_millis(250);

/// How long a [`PeerFate::DiedUnseen`] peer has to appear alive before it
/// is taken for dead: longer than a process's start up to its node's
/// creation, when two processes of a run are started together.
pub const UNSEEN_GRACE: Duration = Duration::from_secs(1);

impl PeerFate {
    fn from_code(code: u8) -> Self {
        match code {
            1 => PeerFate::Alive,
            2 => PeerFate::Died,
            3 => PeerFate::Ended,
            4 => PeerFate::DiedUnseen,
            _ => PeerFate::NotSeen,
        }
    }

    /// Whether the peer is gone for good (died or ended).
    pub fn is_gone(self) -> bool {
        matches!(self, PeerFate::Died | PeerFate::Ended)
    }

    /// The fate after a look that found the node `state`.
    fn after(self, state: PeerState) -> Self {
        match (state, self) {
            (_, PeerFate::Died | PeerFate::Ended) => self,
            (PeerState::Alive, _) => PeerFate::Alive,
            (PeerState::Dead, _) => PeerFate::Died,
            (PeerState::Absent, PeerFate::Alive) => PeerFate::Ended,
            (PeerState::Absent, PeerFate::NotSeen | PeerFate::DiedUnseen) => self,
        }
    }
}

/// The watching thread and what it found. Reading the fate is one atomic
/// load; [`PeerWatch::stop`] ends the thread (it must end before the loop:
/// its looks allocate). After that, [`PeerWatch::look_now`] looks once
/// on the caller's thread.
#[derive(Debug)]
pub struct PeerWatch {
    fate: Arc<AtomicU8>,
    stop: Arc<AtomicBool>,
    thread: Mutex<Option<JoinHandle<()>>>,
    target: Arc<Mutex<PeerTarget>>,
}

/// What a look at the peer needs: the configuration, the peer's node name
/// and the id of its node once seen alive.
#[derive(Debug)]
struct PeerTarget {
    config: Config,
    peer: String,
    seen: Option<UniqueNodeId>,
    /// When this process's own node was created: a dead peer node created
    /// later is this run's peer, killed before a look saw it alive.
    own_created: Option<Duration>,
}

impl PeerTarget {
    /// Looks at the peer's node; the fate that follows `fate`.
    fn look(&mut self, fate: &AtomicU8) -> PeerFate {
        let (state, id) = look(&self.config, &self.peer, self.seen, self.own_created);
        self.seen = id;
        let now = PeerFate::from_code(fate.load(Ordering::Acquire)).after(state);
        fate.store(now as u8, Ordering::Release);
        now
    }
}

impl PeerWatch {
    /// Starts watching the node named `peer` under `config`, from what was
    /// known at the start (`initial`; `seen`, the id of the peer's node seen
    /// alive; `own_created`, when this process's node was created, on the
    /// clock of [`creation_time`](super::run_node::creation_time)). Only the
    /// node seen alive can die or end, or one created after this process's
    /// own node (a peer killed between two looks): a dead node of the same
    /// name created earlier and never seen alive is an earlier run's.
    pub fn start(
        config: Config,
        peer: String,
        initial: PeerFate,
        seen: Option<UniqueNodeId>,
        own_created: Option<Duration>,
    ) -> Self {
        let fate = Arc::new(AtomicU8::new(initial as u8));
        let stop = Arc::new(AtomicBool::new(false));
        let target = Arc::new(Mutex::new(PeerTarget {
            config,
            peer,
            seen,
            own_created,
        }));
        let thread = if initial.is_gone() {
            None
        } else {
            let (fate, stop, target) = (Arc::clone(&fate), Arc::clone(&stop), Arc::clone(&target));
            std::thread::Builder::new()
                .name("peer-watch".to_string())
                .spawn(move || {
                    #[allow(clippy::disallowed_methods)] // The grace's wall time.
                    let started = std::time::Instant::now();
                    while !stop.load(Ordering::Acquire) {
                        let mut now = match target.lock() {
                            Ok(mut t) => t.look(&fate),
                            Err(_) => break,
                        };
                        if now == PeerFate::DiedUnseen && started.elapsed() >= UNSEEN_GRACE {
                            now = PeerFate::Died;
                            fate.store(now as u8, Ordering::Release);
                        }
                        if now.is_gone() {
                            break;
                        }
                        std::thread::park_timeout(PEER_LOOK);
                    }
                })
                .ok()
        };
        Self {
            fate,
            stop,
            thread: Mutex::new(thread),
            target,
        }
    }

    /// One look at the peer now, on the caller's thread (it lists the
    /// prefix's nodes and allocates: off any tick path), from what the
    /// watch knew; the fate that follows. A peer already gone stays so.
    pub fn look_now(&self) -> PeerFate {
        let fate = self.fate();
        if fate.is_gone() {
            return fate;
        }
        match self.target.lock() {
            Ok(mut t) => t.look(&self.fate),
            Err(_) => fate,
        }
    }

    /// What the watch found at its last look (one atomic load).
    pub fn fate(&self) -> PeerFate {
        PeerFate::from_code(self.fate.load(Ordering::Acquire))
    }

    /// The peer's fate if it is gone, waiting up to `patience` for the
    /// watch's next looks (a step that failed may have failed because the
    /// peer died in it).
    #[allow(clippy::disallowed_methods)] // A wait for the watch, not model time.
    pub fn gone_within(&self, patience: Duration) -> Option<PeerFate> {
        let until = std::time::Instant::now() + patience;
        loop {
            let fate = self.fate();
            if fate.is_gone() {
                return Some(fate);
            }
            if std::time::Instant::now() >= until || self.stop.load(Ordering::Acquire) {
                return None;
            }
            std::thread::sleep(Duration::from_millis(1));
        }
    }

    /// Ends the watch (waits for a look in progress); its last fate stays
    /// readable.
    pub fn stop(&self) {
        self.stop.store(true, Ordering::Release);
        let handle = self.thread.lock().ok().and_then(|mut t| t.take());
        if let Some(handle) = handle {
            handle.thread().unpark();
            let _ = handle.join();
        }
    }
}

impl Drop for PeerWatch {
    fn drop(&mut self) {
        self.stop();
    }
}

/// The one line saying how `peer`, the other side of run `run_id`, went
/// after `commands` commands of the loop (`fate` is [`PeerFate::Died`] or
/// [`PeerFate::Ended`]): `the controller 'controller/x' died after 12
/// commands of run 'x' (iceoryx2 dead-node detection)`.
pub fn gone_in_loop(peer: Role, run_id: &str, fate: PeerFate, commands: u64) -> String {
    let (verb, why) = gone_verb(fate);
    format!(
        "the {} '{}' {verb} after {commands} commands of run '{run_id}' ({why})",
        peer.as_str(),
        node_name(peer, run_id)
    )
}

/// The verb and the cause of a peer's `fate` (died or ended).
fn gone_verb(fate: PeerFate) -> (&'static str, &'static str) {
    match fate {
        PeerFate::Died => ("died", "iceoryx2 dead-node detection"),
        _ => ("ended", "its process exited; its stderr says why"),
    }
}

/// The one line saying how `peer`, the other side of run `run_id`, went
/// before the loop started (`fate` is [`PeerFate::Died`] or
/// [`PeerFate::Ended`]): `the plant 'plant/x' died before serving run 'x'
/// (iceoryx2 dead-node detection)`, `the controller 'controller/x' ended
/// before its first command of run 'x' (its process exited; …)`.
pub fn gone_before_loop(peer: Role, run_id: &str, fate: PeerFate) -> String {
    let before = match peer {
        Role::Plant => "serving",
        Role::Controller => "its first command of",
    };
    let (verb, why) = gone_verb(fate);
    format!(
        "the {} '{}' {verb} before {before} run '{run_id}' ({why})",
        peer.as_str(),
        node_name(peer, run_id)
    )
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_peer_seen_and_then_absent_ended_and_a_dead_one_died() {
        use PeerFate::*;
        assert_eq!(NotSeen.after(PeerState::Absent), NotSeen);
        assert_eq!(NotSeen.after(PeerState::Alive), Alive);
        assert_eq!(Alive.after(PeerState::Absent), Ended);
        assert_eq!(NotSeen.after(PeerState::Dead), Died);
        assert_eq!(Alive.after(PeerState::Dead), Died);
        // Gone stays gone.
        assert_eq!(Ended.after(PeerState::Alive), Ended);
        assert_eq!(Died.after(PeerState::Absent), Died);
        // A recent dead node never seen alive stays so until a live one
        // of the name appears (the dead one was an earlier run's).
        assert_eq!(DiedUnseen.after(PeerState::Absent), DiedUnseen);
        assert_eq!(DiedUnseen.after(PeerState::Alive), Alive);
        assert!(!DiedUnseen.is_gone());
    }
}
