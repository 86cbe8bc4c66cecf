//! What a ringlet reads of the whiteboard (`../shared/spec/behaviour.md` §3.1): the live board
//! until its snapshot, taken after OnEntry; from then to the end of the ringlet, the board as
//! it was at that moment, with the machine's own postings since on top (a machine sees what it
//! wrote itself, and nothing anyone else posted meanwhile).

use proclaim_board::{Message, Snapshot, Whiteboard};
use rustc_hash::FxHashMap;

#[derive(Default)]
pub(crate) struct Seen {
    snapshot: Option<Snapshot>,
    own: FxHashMap<String, Message>,
    /// Whether the ringlet is over (reads go to the live board; the snapshot is kept to tell
    /// news from what the machine already saw).
    released: bool,
}

impl Seen {
    /// From now to the end of the ringlet, reads see the board as it is now.
    pub fn take(&mut self, board: &Whiteboard) {
        self.snapshot = Some(board.snapshot());
        self.own.clear();
        self.released = false;
    }

    /// The ringlet is over: reads see the live board again (the next OnEntry).
    pub fn release(&mut self) {
        self.released = true;
    }

    /// The board's sequence number when the last ringlet took its snapshot.
    pub fn seq(&self) -> Option<u64> {
        self.snapshot.as_ref().map(|s| s.seq)
    }

    /// Whether the last ringlet saw `ty` holding `value` (itself posting it, or in its
    /// snapshot): a posting of that value is no news to this machine.
    pub fn saw(&self, ty: &str, value: &proclaim_board::Value) -> bool {
        let Some(snapshot) = &self.snapshot else {
            return false;
        };
        self.own
            .get(ty)
            .or_else(|| snapshot.newest(ty))
            .is_some_and(|m| m.value == *value)
    }

    /// The newest message of `ty` as this ringlet sees it. Before the snapshot this is the
    /// board's `latest`, which takes a signal; after it, nothing is taken.
    pub fn latest(&self, board: &Whiteboard, ty: &str) -> Option<Message> {
        match &self.snapshot {
            Some(_) if self.released => board.latest(ty),
            None => board.latest(ty),
            Some(snapshot) => self.own.get(ty).or_else(|| snapshot.newest(ty)).cloned(),
        }
    }

    /// The machine posted `message` itself: it reads it back for the rest of the ringlet.
    pub fn posted(&mut self, message: &Message) {
        if self.snapshot.is_some() && !self.released {
            self.own.insert(message.ty.to_string(), message.clone());
        }
    }
}
