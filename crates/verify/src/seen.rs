//! What a world of the model shows of the behaviour, as data no search numbers: the same in the
//! model with the clocks of different machines unordered and in the one with them ordered, so
//! that a run of the one can be followed through the other (`confirm.rs`). The two models may
//! be built for different properties, so a run names its slots and `saw()`s; a value is kept
//! by its exact key (a float by its bits), since each search numbers its values its own way.

use crate::values::Key;
use std::sync::Arc;

/// A world as it shows: everything but the bits that order the clocks of different machines.
#[derive(Clone, Debug, PartialEq)]
pub(crate) struct Seen {
    pub turn: u8,
    /// Per machine: its state, mode (`world::Status` as a number), OnEntry pending, started
    /// this round, tests due.
    pub machines: Vec<(u16, u8, bool, bool, u16)>,
    /// Per slot of the model, in its order.
    pub values: Vec<Shown>,
    /// Per `saw()` of the model's properties, in its order.
    pub saw: Vec<Shown>,
}

/// A slot's value as a world shows it.
#[derive(Clone, Debug, PartialEq)]
pub(crate) enum Shown {
    /// The model does not store it: nothing after reads it, so it may be anything.
    Unstored,
    Never,
    Posted,
    Is(Key),
}

impl Shown {
    /// Whether two models' worlds agree on the value: the same, or one of them not keeping it.
    pub fn agrees(&self, other: &Shown) -> bool {
        *self == Shown::Unstored || *other == Shown::Unstored || self == other
    }
}

/// The names of a model's slots and `saw()`s, in its order.
#[derive(Clone, Debug, Default, PartialEq)]
pub(crate) struct Names {
    pub slots: Vec<String>,
    pub saw: Vec<String>,
}

/// The worlds a trace passes through, from the one before its first step to the one after its
/// last, as another model of the same behaviour can follow them.
#[derive(Clone, Debug, Default)]
pub struct Run {
    pub(crate) worlds: Vec<Seen>,
    /// The machine each step rang.
    pub(crate) rang: Vec<usize>,
    pub(crate) names: Arc<Names>,
}

impl Run {
    pub(crate) fn new(names: Names) -> Run {
        Run {
            worlds: Vec::new(),
            rang: Vec::new(),
            names: Arc::new(names),
        }
    }

    /// Whether the run ends in the world it starts in, as a lasso's loop must (no step: yes).
    pub fn closes(&self) -> bool {
        self.worlds.first() == self.worlds.last()
    }

    /// The world the run starts in.
    pub(crate) fn start(&mut self, seen: Seen) {
        self.worlds.push(seen);
    }

    /// A step of `machine` to the world `seen`.
    pub(crate) fn push(&mut self, machine: usize, seen: Seen) {
        self.rang.push(machine);
        self.worlds.push(seen);
    }

    /// The worlds up to step `at`'s start, and those from it on (that world in both).
    pub(crate) fn split(self, at: usize) -> (Run, Run) {
        let mut worlds = self.worlds;
        let mut rang = self.rang;
        let rest = Run {
            worlds: worlds.get(at..).map(<[Seen]>::to_vec).unwrap_or_default(),
            rang: rang.get(at..).map(<[usize]>::to_vec).unwrap_or_default(),
            names: self.names.clone(),
        };
        worlds.truncate(at + 1);
        rang.truncate(at);
        let first = Run {
            worlds,
            rang,
            names: self.names,
        };
        (first, rest)
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
        let mut run = Run::default();
        run.start(world(0));
        (1..4).for_each(|t| run.push(usize::from(t), world(t)));
        let (first, rest) = run.clone().split(2);
        assert_eq!(first.worlds, vec![world(0), world(1), world(2)]);
        assert_eq!(rest.worlds, vec![world(2), world(3)]);
        assert_eq!((first.rang, rest.rang), (vec![1, 2], vec![3]));
        let (all, none) = run.split(7);
        assert_eq!((all.worlds.len(), none.worlds.len()), (4, 0));
    }

    #[test]
    fn a_value_one_model_does_not_keep_agrees_with_any() {
        let one = Shown::Is(Key::Int(1));
        assert!(one.agrees(&Shown::Unstored) && Shown::Unstored.agrees(&one));
        assert!(!one.agrees(&Shown::Is(Key::Int(2))) && !one.agrees(&Shown::Never));
        let (zero, minus) = (
            Shown::Is(Key::Float(0f64.to_bits())),
            Shown::Is(Key::Float((-0f64).to_bits())),
        );
        assert!(!zero.agrees(&minus), "0.0 and -0.0 are different values");
    }
}
