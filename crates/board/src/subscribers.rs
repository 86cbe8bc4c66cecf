//! The subscriptions of a board, indexed by the types they name, so a posting visits only the
//! subscribers that want it (a behaviour of 1,000 machines holds 1,000 subscriptions, and a
//! posting of one type is wanted by a few).

use crate::message::Message;
use crate::pattern::Pattern;
use rustc_hash::FxHashMap;
use tokio::sync::mpsc;

struct Subscriber {
    pattern: Pattern,
    tx: mpsc::Sender<Message>,
}

#[derive(Default)]
pub(crate) struct Subscribers {
    next_id: u64,
    all: FxHashMap<u64, Subscriber>,
    /// Subscribers whose pattern names types exactly, by type.
    by_type: FxHashMap<String, Vec<u64>>,
    /// Subscribers to globs and to everything: asked about every posting.
    wide: Vec<u64>,
    /// Subscriber count at which closed subscriptions are next pruned.
    prune_at: usize,
}

impl Subscribers {
    pub fn add(&mut self, pattern: Pattern, tx: mpsc::Sender<Message>) {
        // Dropped subscriptions are otherwise removed only when a message for them is posted;
        // pruning whenever the count doubles keeps them bounded at amortised constant cost.
        if self.all.len() >= self.prune_at {
            let closed: Vec<u64> = self
                .all
                .iter()
                .filter(|(_, s)| s.tx.is_closed())
                .map(|(id, _)| *id)
                .collect();
            closed.into_iter().for_each(|id| self.remove(id));
            self.prune_at = (self.all.len() * 2).max(64);
        }
        let id = self.next_id;
        self.next_id += 1;
        match &pattern {
            Pattern::Type(t) => self.by_type.entry(t.clone()).or_default().push(id),
            Pattern::Any(types) => {
                for t in types {
                    let ids = self.by_type.entry(t.clone()).or_default();
                    if !ids.contains(&id) {
                        ids.push(id);
                    }
                }
            }
            Pattern::Glob(_) | Pattern::All => self.wide.push(id),
        }
        self.all.insert(id, Subscriber { pattern, tx });
    }

    /// Hands the message to every subscriber that wants it; returns how many had no room.
    pub fn deliver(&mut self, message: &Message) -> u64 {
        let ty: &str = &message.ty;
        let mut dropped = 0;
        let mut closed = Vec::new();
        let exact = self.by_type.get(ty).map(Vec::as_slice).unwrap_or_default();
        for id in exact.iter().chain(&self.wide) {
            let Some(s) = self.all.get(id) else { continue };
            if !s.pattern.matches(ty) {
                continue;
            }
            match s.tx.try_send(message.clone()) {
                Ok(()) => {}
                Err(mpsc::error::TrySendError::Full(_)) => dropped += 1,
                Err(mpsc::error::TrySendError::Closed(_)) => closed.push(*id),
            }
        }
        closed.into_iter().for_each(|id| self.remove(id));
        dropped
    }

    fn remove(&mut self, id: u64) {
        let Some(s) = self.all.remove(&id) else {
            return;
        };
        let types: Vec<&String> = match &s.pattern {
            Pattern::Type(t) => vec![t],
            Pattern::Any(types) => types.iter().collect(),
            Pattern::Glob(_) | Pattern::All => {
                self.wide.retain(|w| *w != id);
                Vec::new()
            }
        };
        for t in types {
            if let Some(ids) = self.by_type.get_mut(t.as_str()) {
                ids.retain(|i| *i != id);
                if ids.is_empty() {
                    self.by_type.remove(t.as_str());
                }
            }
        }
    }

    pub fn len(&self) -> usize {
        self.all.len()
    }
}
