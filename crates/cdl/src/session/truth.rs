//! Three-valued answers inside a session: proved, not proved, or undecided within the search
//! limits, combined as Kleene's logic does.

use crate::goal::Goal;

/// A three-valued answer: proved, not proved, or undecided (naming the goal that is).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(super) enum Truth {
    True,
    False,
    Undecided(Goal),
}

impl From<bool> for Truth {
    fn from(b: bool) -> Truth {
        if b {
            Truth::True
        } else {
            Truth::False
        }
    }
}

impl Truth {
    /// Kleene's conjunction, asking the right side only when the left does not decide it.
    pub(super) fn and(self, right: impl FnOnce() -> Truth) -> Truth {
        match self {
            Truth::False => Truth::False,
            Truth::True => right(),
            Truth::Undecided(g) => match right() {
                Truth::False => Truth::False,
                _ => Truth::Undecided(g),
            },
        }
    }

    /// Kleene's disjunction.
    pub(super) fn or(self, right: impl FnOnce() -> Truth) -> Truth {
        match self {
            Truth::True => Truth::True,
            Truth::False => right(),
            Truth::Undecided(g) => match right() {
                Truth::True => Truth::True,
                _ => Truth::Undecided(g),
            },
        }
    }
}
