//! Going back and branching from the page (`docs/spec/behaviour.md` §3.5): a replayed recording
//! whose behaviour the program knows offers to branch at the round the slider shows; the
//! program ([`Monitor::set_brancher`](crate::Monitor::set_brancher)) starts the branch, live and
//! paused at that round, and the page goes to the branch's own page. A live page can be told
//! to stop its run ([`Monitor::set_stopper`](crate::Monitor::set_stopper)), which keeps a
//! branch's recording whole.

use serde::{Deserialize, Serialize};
use std::sync::Arc;

/// Starts a branch of the replayed recording at the start of a round: where its page is and
/// which file records it, or why it could not start.
pub type Brancher = Arc<dyn Fn(u64) -> Result<Branched, String> + Send + Sync>;

/// A branch started.
#[derive(Clone, Debug, PartialEq, Eq, Serialize)]
pub struct Branched {
    /// The branch's live page.
    pub url: String,
    /// The recording it writes, a test once it is stopped.
    pub file: String,
    /// What the branch said as it started (the behaviour no longer replays the recording).
    pub notes: Vec<String>,
}

/// What the page asks: a branch where the slider is, after the first `at` events.
#[derive(Deserialize)]
pub(crate) struct BranchAsked {
    pub at: usize,
}

/// The round a branch from the moment after `at` events starts: the one after the round of the
/// last event shown, so the branch begins with that round whole.
pub(crate) fn round_after(rounds: &[u64], at: usize) -> u64 {
    at.min(rounds.len())
        .checked_sub(1)
        .and_then(|last| rounds.get(last))
        .map_or(1, |round| round + 1)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_branch_starts_after_the_round_of_the_last_event_shown() {
        let rounds = [1, 1, 2, 2, 2, 5];
        assert_eq!(round_after(&rounds, 0), 1, "before any event: the start");
        assert_eq!(round_after(&rounds, 2), 2);
        assert_eq!(round_after(&rounds, 3), 3);
        assert_eq!(round_after(&rounds, 6), 6);
        assert_eq!(
            round_after(&rounds, 60),
            6,
            "past the end: after the last round"
        );
    }
}
