//! What a schedule's ringlets share with it: the number of the round under way, and the feed
//! that paces a replay (told of each ringlet and each query it asks).

use proclaim_board::Whiteboard;
use proclaim_runtime::Ringlet;
use std::sync::atomic::{AtomicU64, Ordering};
use std::sync::Arc;
use std::time::Duration;

/// The number of the round under way (0 before the first), shared by the machines of a
/// schedule so that every event says which round it happened in; and how many of their events
/// were changes ([`proclaim_runtime::Event::is_change`]), so the schedule can tell a still round.
#[derive(Clone, Debug, Default)]
pub struct RoundCounter(Arc<Counts>);

#[derive(Debug, Default)]
struct Counts {
    round: AtomicU64,
    changes: AtomicU64,
}

impl RoundCounter {
    pub fn get(&self) -> u64 {
        self.0.round.load(Ordering::Relaxed)
    }

    /// Starts the next round; its number.
    pub(crate) fn advance(&self) -> u64 {
        self.0.round.fetch_add(1, Ordering::Relaxed) + 1
    }

    /// Goes on from round `round` (a schedule taken up from a checkpoint).
    pub(crate) fn set(&self, round: u64) {
        self.0.round.store(round, Ordering::Relaxed);
    }

    /// A machine reported a change.
    pub(crate) fn changed(&self) {
        self.0.changes.fetch_add(1, Ordering::Relaxed);
    }

    /// The changes reported so far.
    pub(crate) fn changes(&self) -> u64 {
        self.0.changes.load(Ordering::Relaxed)
    }
}

/// What paces a schedule from outside instead of its own waiting: a replay of a recorded run,
/// which posts the recorded outside messages where they came the first time (before a ringlet,
/// or in it before one of its queries) and moves the (virtual) clock to each ringlet's time.
pub trait Feed: Send {
    /// Before each ringlet of a running machine: posts what came before it; the time since the
    /// epoch to wait for before it starts.
    fn before(&mut self, ringlet: Ringlet, board: &Whiteboard) -> Option<Duration>;
    /// Before the `nth` query (from 0) that a ringlet asks an expert: posts what came before it.
    fn before_query(&mut self, ringlet: Ringlet, nth: usize, board: &Whiteboard) {
        let _ = (ringlet, nth, board);
    }
    /// When a round is over (before the next starts); false ends the run.
    fn after_round(&mut self, round: u64) -> bool;
}

/// A feed shared by the schedule and the ringlet it runs (whose queries it hears of).
pub(crate) type SharedFeed = Arc<parking_lot::Mutex<dyn Feed>>;

/// What a ringlet under a feed tells it of its queries.
#[derive(Clone)]
pub(crate) struct QueryHook {
    pub feed: SharedFeed,
    pub ringlet: Ringlet,
}
