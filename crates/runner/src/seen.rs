//! What a ringlet reads of the whiteboard (`docs/spec/behaviour.md` §3.1): the live board
//! until its snapshot, taken after OnEntry; from then to the end of the ringlet, the board as
//! it was at that moment, with the machine's own postings since on top (a machine sees what it
//! wrote itself, and nothing anyone else posted meanwhile). The snapshot is taken when the
//! ringlet first reads the board after OnEntry: nothing of the ringlet runs in between, so that
//! is the same snapshot, and a ringlet that reads nothing (labels over variables and time)
//! takes none.
//!
//! An atom a label asks of its expert (§2) is answered after the snapshot, so the snapshot
//! cannot hold it; the first read of a type after the snapshot is held instead, to the end of
//! the ringlet. A later query of that atom is still asked (the protocol and the count of
//! queries a replay follows are unchanged), but the ringlet reads what it read first, even when
//! the expert has changed its mind since (a reasoner whose input moved mid-ringlet), as the
//! verifier's model reads one world per ringlet.

use parking_lot::Mutex;
use proclaim_board::{Message, Snapshot, Value, Whiteboard};
use proclaim_runtime::Answerer;
use rustc_hash::{FxHashMap, FxHashSet};
use std::sync::{Arc, OnceLock};

#[derive(Default)]
pub(crate) struct Seen {
    /// Between the snapshot point and the end of the ringlet.
    held: bool,
    snapshot: OnceLock<Snapshot>,
    own: FxHashMap<String, Message>,
    /// What the ringlet's conditions read of each atom they asked: its first answer, held.
    answers: Mutex<FxHashMap<String, (bool, Answerer)>>,
    /// The types the ringlet read from its snapshot before any condition asked them.
    from_snapshot: Mutex<FxHashSet<Arc<str>>>,
}

impl Seen {
    /// From now to the end of the ringlet, reads see the board as it is now.
    pub fn take(&mut self) {
        self.held = true;
        self.snapshot = OnceLock::new();
        self.own.clear();
        self.answers.get_mut().clear();
        self.from_snapshot.get_mut().clear();
    }

    /// The ringlet is over: reads see the live board again (the next OnEntry). What it saw is
    /// kept, to tell news from what the machine already knew.
    pub fn release(&mut self) {
        self.held = false;
    }

    /// Between two ringlets, as a checkpoint left it: the last snapshot (if the ringlet took
    /// one) and what the machine posted itself in it.
    pub fn between_ringlets(snapshot: Option<Snapshot>, own: FxHashMap<String, Message>) -> Seen {
        let seen = Seen {
            own,
            ..Seen::default()
        };
        if let Some(snapshot) = snapshot {
            let _ = seen.snapshot.set(snapshot);
        }
        seen
    }

    /// The last ringlet's snapshot, if it took one.
    pub fn last_snapshot(&self) -> Option<&Snapshot> {
        self.snapshot.get()
    }

    /// What the last ringlet posted itself, by type.
    pub fn own(&self) -> impl Iterator<Item = (&str, &Message)> + '_ {
        self.own.iter().map(|(ty, m)| (ty.as_str(), m))
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
        if let Some(own) = self.own.get(ty) {
            return Some(own.clone());
        }
        let message = self
            .snapshot
            .get_or_init(|| board.snapshot())
            .newest(ty)
            .cloned()?;
        if !self.answers.lock().contains_key(ty) {
            self.from_snapshot.lock().insert(message.ty.clone());
        }
        Some(message)
    }

    /// The value of `ty` as this ringlet reads it: what it posted itself, else an expert's
    /// answer a condition of it held, else the snapshot's (or the live board's before the
    /// snapshot). A condition that read a posted value, or no answer at all, leaves the value
    /// as posted: a number stays a number, and what was never posted stays absent.
    pub fn value(&self, board: &Whiteboard, ty: &str) -> Option<Value> {
        if self.held && !self.own.contains_key(ty) {
            if let Some((answer, Answerer::Expert(_))) = self.answers.lock().get(ty) {
                return Some(Value::Bool(*answer));
            }
        }
        self.latest(board, ty).map(|m| m.value)
    }

    /// A condition of this ringlet asked `atom` and got `value` from `by`: what the ringlet
    /// reads of it. The first read of the atom since the snapshot (this answer, an earlier
    /// one, or the snapshot's value read before any condition asked) is held to the end of
    /// the ringlet; before the snapshot every answer stands as given.
    pub fn answer(
        &self,
        board: &Whiteboard,
        atom: &str,
        value: bool,
        by: Answerer,
    ) -> (bool, Answerer) {
        if !self.held {
            return (value, by);
        }
        if let Some(held) = self.answers.lock().get(atom) {
            return held.clone();
        }
        let first = if self.from_snapshot.lock().contains(atom) {
            match self.latest(board, atom) {
                Some(m) => (m.value.truthy(), Answerer::Posted(m.module.to_string())),
                None => (value, by),
            }
        } else {
            (value, by)
        };
        self.answers.lock().insert(atom.to_string(), first.clone());
        first
    }

    /// The machine posted `message` itself: it reads it back for the rest of the ringlet.
    pub fn posted(&mut self, message: &Message) {
        if self.held {
            self.own.insert(message.ty.to_string(), message.clone());
        }
    }
}
