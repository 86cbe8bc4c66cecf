//! The automatic engine choice as a race on one frozen model: the explicit search runs alone
//! while the graph is small; once it has stored [`crate::AUTO_EXPLICIT_STATES`] states undecided,
//! or ran out of memory, the symbolic engine starts on a second thread beside it (none starts
//! after a search that stopped at `--max-states`, a bound the user set). The first
//! engine to decide answers and the other stops at its next step. The two share `--max-memory`:
//! each says what it holds, and each counts what the other holds against the budget.
//!
//! No fixed rule can know which engine suits a behaviour (a deep, narrow graph takes the
//! symbolic engine one image a layer; a wide one takes the explicit search one ringlet a state),
//! so the choice is made by how far each gets, measured by running both.

use std::sync::atomic::{AtomicBool, AtomicUsize, Ordering};
use std::sync::{Condvar, Mutex};

/// Which engine a [`crate::search::Search`] runs for.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Side {
    Explicit = 0,
    Symbolic = 1,
}

impl Side {
    fn other(self) -> Side {
        match self {
            Side::Explicit => Side::Symbolic,
            Side::Symbolic => Side::Explicit,
        }
    }
}

/// Whether the symbolic engine is to start: not yet said, go, or not at all (the explicit
/// search decided alone).
#[derive(Clone, Copy, PartialEq, Eq)]
enum Start {
    Waiting,
    Go,
    Never,
}

pub struct Race {
    max_memory: usize,
    held: [AtomicUsize; 2],
    /// An engine decided: the other's work can change nothing.
    over: AtomicBool,
    start: Mutex<Start>,
    started: Condvar,
}

impl Race {
    pub fn new(max_memory: usize) -> Race {
        Race {
            max_memory,
            held: [AtomicUsize::new(0), AtomicUsize::new(0)],
            over: AtomicBool::new(false),
            start: Mutex::new(Start::Waiting),
            started: Condvar::new(),
        }
    }

    /// What `side` may hold at most now: the budget less what the other side holds.
    pub fn budget(&self, side: Side) -> usize {
        let other = self.held[side.other() as usize].load(Ordering::Relaxed);
        self.max_memory.saturating_sub(other)
    }

    /// `side` holds `bytes` now.
    pub fn hold(&self, side: Side, bytes: usize) {
        self.held[side as usize].store(bytes, Ordering::Relaxed);
    }

    /// Whether an engine has decided (the other stops).
    pub fn is_over(&self) -> bool {
        self.over.load(Ordering::Relaxed)
    }

    /// Lets the symbolic engine start (the explicit search has not decided in its first states).
    pub fn start_symbolic(&self) {
        self.say(Start::Go);
    }

    /// The symbolic engine is not to start if it has not (the explicit search stopped where
    /// the user bounded it, `--max-states`).
    pub fn no_rival(&self) {
        self.say(Start::Never);
    }

    /// `side` is done and holds nothing more; `decided` ends the race. An explicit search that
    /// ends undecided before the symbolic engine started lets it start now.
    pub fn finish(&self, side: Side, decided: bool) {
        if decided {
            self.over.store(true, Ordering::Relaxed);
        }
        self.hold(side, 0);
        if side == Side::Explicit {
            self.say(if decided { Start::Never } else { Start::Go });
        }
    }

    /// Waits until the symbolic engine may start: `false` if it never is to.
    pub fn wait_for_start(&self) -> bool {
        let mut start = self.start.lock().unwrap_or_else(|e| e.into_inner());
        while *start == Start::Waiting {
            start = self.started.wait(start).unwrap_or_else(|e| e.into_inner());
        }
        *start == Start::Go
    }

    /// Says whether the symbolic engine starts, once: the first word stands.
    fn say(&self, word: Start) {
        let mut start = self.start.lock().unwrap_or_else(|e| e.into_inner());
        if *start == Start::Waiting {
            *start = word;
            self.started.notify_all();
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn each_side_counts_what_the_other_holds_against_the_budget() {
        let race = Race::new(100);
        race.hold(Side::Explicit, 70);
        assert_eq!(race.budget(Side::Symbolic), 30);
        assert_eq!(race.budget(Side::Explicit), 100);
        race.finish(Side::Explicit, false);
        assert_eq!(race.budget(Side::Symbolic), 100);
    }

    #[test]
    fn the_symbolic_engine_starts_once_the_explicit_search_gives_up_and_never_after_it_decided() {
        let race = Race::new(1);
        race.finish(Side::Explicit, true);
        assert!(!race.wait_for_start());
        assert!(race.is_over());
        let race = Race::new(1);
        race.finish(Side::Explicit, false);
        assert!(race.wait_for_start());
        assert!(!race.is_over());
        let race = Race::new(1);
        race.start_symbolic();
        race.finish(Side::Explicit, true);
        assert!(race.wait_for_start(), "the first word stands");
    }
}
