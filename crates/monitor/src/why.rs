//! Why a machine read the answer it did, asked from the page (a click on an answer in the
//! events list). The monitor knows nothing of theories: the program that serves the page gives
//! it an [`Explainer`], which is handed the run's events so far and what was asked.

use proclaim_runner::{Answerer, Event};
use serde::Deserialize;
use std::collections::{BTreeMap, VecDeque};
use std::sync::Arc;

/// An answer the page asks about: the label a machine read in a round.
#[derive(Clone, Debug, Deserialize, PartialEq, Eq)]
pub struct AnswerAsked {
    pub round: u64,
    pub machine: String,
    pub label: String,
}

/// Explains an answer from the run's events: the text to show, or why it cannot be.
pub type Explainer = Arc<dyn Fn(&[Event], &AnswerAsked) -> Result<String, String> + Send + Sync>;

/// How many of a live run's latest events the page keeps whole for an explainer.
pub const HISTORY: usize = 100_000;

/// A live run's events as an explainer needs them, in bounded memory: the latest [`HISTORY`]
/// whole, and of those before them only each type's last posting (an expert's answer counts as
/// its posting), which is all a theory's inputs can have come from.
#[derive(Default)]
pub(crate) struct History {
    before: BTreeMap<String, Event>,
    recent: VecDeque<Event>,
}

impl History {
    pub fn push(&mut self, event: Event) {
        self.recent.push_back(event);
        if self.recent.len() > HISTORY {
            if let Some(old) = self.recent.pop_front() {
                self.fold(old);
            }
        }
    }

    /// An event that leaves the window: a posting (or an expert's answer, as a posting) kept
    /// as its type's last.
    fn fold(&mut self, event: Event) {
        match event {
            Event::Posted { ref ty, .. } => {
                self.before.insert(ty.clone(), event);
            }
            Event::Answered {
                atom,
                value,
                by: Answerer::Expert(expert),
                round,
                at,
                ..
            } => {
                let posted = Event::Posted {
                    machine: expert,
                    ty: atom.clone(),
                    content: value.to_string(),
                    priority: 0,
                    round,
                    at,
                };
                self.before.insert(atom, posted);
            }
            _ => {}
        }
    }

    /// The events to explain from: the folded postings first, then the window.
    pub fn events(&self) -> Vec<Event> {
        let before = self.before.values().cloned();
        before.chain(self.recent.iter().cloned()).collect()
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::time::Duration;

    fn posted(ty: &str, content: &str, round: u64) -> Event {
        Event::Posted {
            machine: "M".into(),
            ty: ty.into(),
            content: content.into(),
            priority: 0,
            round,
            at: Duration::ZERO,
        }
    }

    #[test]
    fn a_long_runs_history_keeps_each_types_last_posting_before_its_window() {
        let mut history = History::default();
        for round in 0..(HISTORY as u64 + 3) {
            history.push(posted(
                if round % 2 == 0 { "a" } else { "b" },
                &round.to_string(),
                round,
            ));
        }
        let events = history.events();
        assert_eq!(events.len(), HISTORY + 2);
        // Rounds 0, 1 and 2 left the window: `a`'s last was round 2's, `b`'s round 1's.
        assert_eq!(events[0], posted("a", "2", 2));
        assert_eq!(events[1], posted("b", "1", 1));
        assert_eq!(events[2], posted("b", "3", 3));
    }
}
