//! The whiteboard's table as a persistent value: every type with what it holds, shared
//! structurally with the live board, so taking a [`Snapshot`] costs one reference count and
//! reading it never holds the board's lock.

use crate::message::{Kind, Message};
use imbl::shared_ptr::DefaultSharedPtr;
use imbl::{GenericHashMap, Vector};
use rustc_hash::FxBuildHasher;
use std::sync::Arc;
use std::time::Duration;

/// What one type holds.
#[derive(Clone, Debug)]
pub(crate) struct Slot {
    pub kind: Kind,
    /// A state's current value.
    pub latest: Option<Message>,
    /// A data type's bounded history, oldest first.
    pub history: Vector<Message>,
    /// A signal type's unread signals, oldest first.
    pub signals: Vector<Message>,
    /// The last signal posted, read or not (what a person looking at the board wants to see).
    pub last_signal: Option<Message>,
    pub posts: u64,
}

impl Slot {
    pub fn new(kind: Kind) -> Slot {
        Slot {
            kind,
            latest: None,
            history: Vector::new(),
            signals: Vector::new(),
            last_signal: None,
            posts: 0,
        }
    }

    /// The newest message of any kind.
    fn newest(&self) -> Option<&Message> {
        match self.kind {
            Kind::State => self.latest.as_ref(),
            Kind::Data => self.history.back(),
            Kind::Signal => self.last_signal.as_ref(),
        }
    }
}

pub(crate) type Table = GenericHashMap<Arc<str>, Slot, FxBuildHasher, DefaultSharedPtr>;

/// The board as it was at one moment: consistent (taken under the board's lock), cheap (O(1),
/// shared with the live table until either changes), and readable for as long as it is kept.
#[derive(Clone)]
pub struct Snapshot {
    pub(crate) table: Table,
    /// The highest sequence number when it was taken.
    pub seq: u64,
    /// The board's clock when it was taken.
    pub time: Duration,
}

/// One type as a person reads the board: its kind, its newest message, how many were posted.
#[derive(Clone, Debug, PartialEq)]
pub struct BoardRow<'s> {
    pub ty: &'s str,
    pub kind: Kind,
    pub newest: &'s Message,
    pub posts: u64,
}

impl Snapshot {
    pub fn empty() -> Snapshot {
        Snapshot {
            table: Table::default(),
            seq: 0,
            time: Duration::ZERO,
        }
    }

    /// How many types the board knows.
    pub fn len(&self) -> usize {
        self.table.len()
    }

    pub fn is_empty(&self) -> bool {
        self.table.is_empty()
    }

    pub fn kind(&self, ty: &str) -> Option<Kind> {
        self.table.get(ty).map(|s| s.kind)
    }

    /// The newest message of a type, of any kind (a signal's whether read or not).
    pub fn newest(&self, ty: &str) -> Option<&Message> {
        self.table.get(ty).and_then(Slot::newest)
    }

    /// Every type that has been posted, by name.
    pub fn rows(&self) -> Vec<BoardRow<'_>> {
        let mut rows: Vec<BoardRow<'_>> = self
            .table
            .iter()
            .filter_map(|(ty, slot)| {
                Some(BoardRow {
                    ty,
                    kind: slot.kind,
                    newest: slot.newest()?,
                    posts: slot.posts,
                })
            })
            .collect();
        rows.sort_unstable_by(|a, b| a.ty.cmp(b.ty));
        rows
    }

    /// Every type with its kind and what it holds (a state's value, a data history, unread
    /// signals) in sequence order: what a process joining a networked board starts from.
    pub fn contents(&self) -> (Vec<(String, Kind)>, Vec<Message>) {
        let mut kinds = Vec::with_capacity(self.table.len());
        let mut messages = Vec::new();
        for (ty, slot) in &self.table {
            kinds.push((ty.to_string(), slot.kind));
            messages.extend(slot.latest.iter().cloned());
            messages.extend(slot.history.iter().cloned());
            messages.extend(slot.signals.iter().cloned());
        }
        kinds.sort_by(|a, b| a.0.cmp(&b.0));
        messages.sort_by_key(|m| m.seq);
        (kinds, messages)
    }
}

impl std::fmt::Debug for Snapshot {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(f, "Snapshot({} types, seq {})", self.table.len(), self.seq)
    }
}
