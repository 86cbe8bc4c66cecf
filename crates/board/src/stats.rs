//! The counters a whiteboard keeps on every path, which `proclaim run` prints at the end and a
//! checkpoint carries on.

/// Counters kept on every path.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct Stats {
    pub posts: u64,
    /// Messages a subscriber's full queue could not take.
    pub drops: u64,
    pub queries: u64,
    /// Queries no answer arrived for in time.
    pub timeouts: u64,
    /// Queries for atoms no registered module answers.
    pub unanswerable: u64,
    /// Subscriptions the board holds now (dropped ones linger until pruned, boundedly).
    pub subscribers: usize,
}
