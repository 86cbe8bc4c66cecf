//! What a ringlet reads of the whiteboard (`docs/spec/behaviour.md` §3.1): the live board
//! until its snapshot, taken after OnEntry; from then to the end of the ringlet, the board as
//! it was at that moment, with the machine's own postings since on top (a machine sees what it
//! wrote itself, and nothing anyone else posted meanwhile). The snapshot is taken when the
//! ringlet first reads the board after OnEntry: nothing of the ringlet runs in between, so that
//! is the same snapshot, and a ringlet that reads nothing (labels over variables and time)
//! takes none.

use proclaim_board::{Message, Snapshot, Value, Whiteboard};
use rustc_hash::FxHashMap;
use std::sync::OnceLock;

#[derive(Default)]
pub(crate) struct Seen {
    /// Between the snapshot point and the end of the ringlet.
    held: bool,
    snapshot: OnceLock<Snapshot>,
    own: FxHashMap<String, Message>,
}

impl Seen {
    /// From now to the end of the ringlet, reads see the board as it is now.
    pub fn take(&mut self) {
        self.held = true;
        self.snapshot = OnceLock::new();
        self.own.clear();
    }

    /// The ringlet is over: reads see the live board again (the next OnEntry). What it saw is
    /// kept, to tell news from what the machine already knew.
    pub fn release(&mut self) {
        self.held = false;
    }

    /// The board's sequence number when the last ringlet took its snapshot, if it took one.
    pub fn seq(&self) -> Option<u64> {
        self.snapshot.get().map(|s| s.seq)
    }

    /// Whether a posting of `value` to `ty` is no news to the machine: the last ringlet saw
    /// that value (posting it itself, or in its snapshot), or read nothing of the board at all.
    pub fn saw(&self, ty: &str, value: &Value) -> bool {
        if let Some(own) = self.own.get(ty) {
            return own.value == *value;
        }
        match self.snapshot.get() {
            Some(snapshot) => snapshot.newest(ty).is_some_and(|m| m.value == *value),
            None => true,
        }
    }

    /// The newest message of `ty` as this ringlet sees it. Before the snapshot this is the
    /// board's `latest`, which takes a signal; after it, nothing is taken.
    pub fn latest(&self, board: &Whiteboard, ty: &str) -> Option<Message> {
        if !self.held {
            return board.latest(ty);
        }
        self.own
            .get(ty)
            .or_else(|| self.snapshot.get_or_init(|| board.snapshot()).newest(ty))
            .cloned()
    }

    /// The machine posted `message` itself: it reads it back for the rest of the ringlet.
    pub fn posted(&mut self, message: &Message) {
        if self.held {
            self.own.insert(message.ty.to_string(), message.clone());
        }
    }
}
