//! Where a running machine's events go: the trace's [`Event`]s are `proclaim-runtime`'s, shared
//! with compiled behaviours; this is the channel and the clock they are reported with.

use crate::feed::RoundCounter;
pub use proclaim_runtime::event::{Answerer, Event};
use std::time::Duration;
use tokio::sync::mpsc;
use tokio::time::Instant;

/// Where a machine's events go, and the moment their times count from (one moment for every
/// machine of a behaviour, so a merged trace is in time order).
#[derive(Clone)]
pub(crate) struct Reporter {
    pub sender: Option<mpsc::UnboundedSender<Event>>,
    pub epoch: Instant,
    /// The schedule's round (shared by the machines of one round schedule).
    pub round: RoundCounter,
}

impl Reporter {
    /// Time since the epoch.
    pub fn now(&self) -> Duration {
        self.epoch.elapsed()
    }

    /// Sends the event made for the time and round now: a change the machine made.
    pub fn emit(&self, event: impl FnOnce(Duration, u64) -> Event) {
        self.round.changed();
        self.emit_read(event);
    }

    /// [`Reporter::emit`] for an answer the machine read, which changes nothing.
    pub fn emit_read(&self, event: impl FnOnce(Duration, u64) -> Event) {
        if let Some(tx) = &self.sender {
            let _ = tx.send(event(self.now(), self.round.get()));
        }
    }
}
