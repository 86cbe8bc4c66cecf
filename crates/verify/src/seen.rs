//! What a world of the model shows of the behaviour, as data no search numbers: the same in the
//! model with the clocks of different machines unordered and in the one with them ordered, so
//! that a run of the one can be followed through the other (`confirm.rs`).

use proclaim_board::Value;

/// A world as it shows: everything but the bits that order the clocks of different machines.
#[derive(Clone, Debug, PartialEq)]
pub(crate) struct Seen {
    pub turn: u8,
    /// Per machine: its state, mode (`world::Status` as a number), OnEntry pending, started
    /// this round, tests due.
    pub machines: Vec<(u16, u8, bool, bool, u16)>,
    pub values: Vec<Shown>,
    pub saw: Vec<Shown>,
}

/// A slot's value as a world shows it, by value (each search numbers its values its own way).
#[derive(Clone, Debug, PartialEq)]
pub(crate) enum Shown {
    /// The model does not store it: no later step reads it.
    Unstored,
    Never,
    Posted,
    Is(Value),
}

/// The worlds a trace passes through, from the one before its first step to the one after its
/// last, as another model of the same behaviour can follow them. Two traces are compared by
/// what they show, so every run is equal to every other.
#[derive(Clone, Debug, Default)]
pub struct Run(pub(crate) Vec<Seen>);

impl PartialEq for Run {
    fn eq(&self, _: &Run) -> bool {
        true
    }
}

impl Run {
    pub(crate) fn push(&mut self, seen: Seen) {
        self.0.push(seen);
    }

    /// The worlds up to step `at`'s start, and those from it on (that world in both).
    pub(crate) fn split(self, at: usize) -> (Run, Run) {
        if self.0.len() <= at {
            return (self, Run::default());
        }
        let rest = self.0[at..].to_vec();
        let mut first = self.0;
        first.truncate(at + 1);
        (Run(first), Run(rest))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn world(turn: u8) -> Seen {
        Seen {
            turn,
            machines: Vec::new(),
            values: Vec::new(),
            saw: Vec::new(),
        }
    }

    #[test]
    fn a_run_split_at_a_step_keeps_that_steps_world_on_both_sides() {
        let run = Run((0..4).map(world).collect());
        let (first, rest) = run.clone().split(2);
        assert_eq!(first.0, vec![world(0), world(1), world(2)]);
        assert_eq!(rest.0, vec![world(2), world(3)]);
        let (all, none) = run.split(7);
        assert_eq!((all.0.len(), none.0.len()), (4, 0));
    }
}
