//! One direction of the loop: an iceoryx2 blackboard holding a single entry,
//! the latest command (controller → plant) or measurement (plant →
//! controller). Its one writer overwrites the entry in place and its reader
//! copies it out: both are lock-free copies in shared memory that allocate
//! nothing after the ports are built (publish-subscribe in iceoryx2 0.10
//! allocates one reference-counted sample state per loan, see
//! `tests/iceoryx2_pattern_alloc.rs`). Lockstep needs no queue: each side
//! waits for the other's answer, and sequence numbers tell a new value from
//! the previous one.

use std::fmt;

use iceoryx2::port::reader::{EntryHandle, Reader};
use iceoryx2::port::writer::{EntryHandleMut, Writer};
use iceoryx2::prelude::*;
use iceoryx2::service::port_factory::blackboard;

use super::loop_services::ServiceError;

/// A run's blackboard service (key type `u64`, one entry).
pub type Board = blackboard::PortFactory<ipc::Service, u64>;

/// The key of the single entry of each board.
pub const ENTRY_KEY: u64 = 0;

fn iceoryx(context: &str, e: impl fmt::Debug) -> ServiceError {
    ServiceError::Iceoryx(format!("{context}: {e:?}"))
}

/// The write end of a board: the only writer of its entry.
pub struct BoardWriter<T: Copy + ZeroCopySend + 'static> {
    // Fields drop in order: the entry before its port.
    entry: EntryHandleMut<ipc::Service, u64, T>,
    _writer: Writer<ipc::Service, u64>,
}

impl<T: Copy + ZeroCopySend + fmt::Debug + 'static> BoardWriter<T> {
    /// The writer of `board`'s entry.
    ///
    /// # Errors
    /// iceoryx2 refused (another writer exists, or the entry's type differs).
    pub fn new(board: &Board) -> Result<Self, ServiceError> {
        let writer = board
            .writer_builder()
            .create()
            .map_err(|e| iceoryx("board writer", e))?;
        let entry = writer
            .entry::<T>(&ENTRY_KEY)
            .map_err(|e| iceoryx("board entry", e))?;
        Ok(Self {
            entry,
            _writer: writer,
        })
    }

    /// Overwrites the entry with `value` (a copy into shared memory; no
    /// allocation).
    pub fn publish(&self, value: T) {
        self.entry.update_with_copy(value);
    }
}

impl<T: Copy + ZeroCopySend + 'static> fmt::Debug for BoardWriter<T> {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.debug_struct("BoardWriter")
            .field("value", &std::any::type_name::<T>())
            .finish()
    }
}

/// The read end of a board (keeps the peer's board open).
pub struct BoardReader<T: Copy + ZeroCopySend + 'static> {
    // Fields drop in order: the entry before its port, the port before the
    // service.
    entry: EntryHandle<ipc::Service, u64, T>,
    _reader: Reader<ipc::Service, u64>,
    _board: Board,
}

impl<T: Copy + ZeroCopySend + fmt::Debug + 'static> BoardReader<T> {
    /// A reader of `board`'s entry (the reader keeps the board open).
    ///
    /// # Errors
    /// iceoryx2 refused (too many readers, or the entry's type differs).
    pub fn new(board: Board) -> Result<Self, ServiceError> {
        let reader = board
            .reader_builder()
            .create()
            .map_err(|e| iceoryx("board reader", e))?;
        let entry = reader
            .entry::<T>(&ENTRY_KEY)
            .map_err(|e| iceoryx("board entry", e))?;
        Ok(Self {
            entry,
            _reader: reader,
            _board: board,
        })
    }

    /// A copy of the entry's latest value (no allocation).
    pub fn latest(&self) -> T {
        *self.entry.get()
    }
}

impl<T: Copy + ZeroCopySend + 'static> fmt::Debug for BoardReader<T> {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.debug_struct("BoardReader")
            .field("value", &std::any::type_name::<T>())
            .finish()
    }
}
