//! One search of a frozen [`Model`]: what a search grows as it goes (the values it meets, each
//! theory's proved answers) kept beside the model, so the model is a value that several
//! searches, on several threads, read at once. A search in a [`Race`] also hears from it what
//! memory it may take and whether the other engine has already answered.

use crate::model::Model;
use crate::race::{Race, Side};
use crate::reasoner::Reasoner;
use crate::values::Values;
use std::cell::{RefCell, RefMut};
use std::ops::Deref;

pub struct Search<'m> {
    model: &'m Model,
    /// Values met so far (the packed states store their numbers): each search numbers its own.
    pub values: RefCell<Values>,
    reasoners: Vec<RefCell<Reasoner>>,
    race: Option<(&'m Race, Side)>,
}

impl<'m> Search<'m> {
    pub fn new(model: &'m Model) -> Search<'m> {
        Search {
            model,
            values: RefCell::new(Values::default()),
            reasoners: model
                .theories
                .iter()
                .map(|t| RefCell::new(t.reasoner.start()))
                .collect(),
            race: None,
        }
    }

    /// A search that races another engine's on the same model.
    pub fn racing(model: &'m Model, race: &'m Race, side: Side) -> Search<'m> {
        Search {
            race: Some((race, side)),
            ..Search::new(model)
        }
    }

    /// The bytes this search may hold: `max`, less what a rival holds.
    pub fn memory_budget(&self, max: usize) -> usize {
        self.race
            .map_or(max, |(race, side)| race.budget(side).min(max))
    }

    /// This search holds `bytes` now (its rival counts them against the budget).
    pub fn hold(&self, bytes: usize) {
        if let Some((race, side)) = self.race {
            race.hold(side, bytes);
        }
    }

    /// Whether a rival has answered: this search's work can change nothing.
    pub fn overtaken(&self) -> bool {
        self.race.is_some_and(|(race, _)| race.is_over())
    }

    /// The explicit search has not decided in its first states: a rival may start.
    pub fn call_rival(&self) {
        if let Some((race, _)) = self.race {
            race.start_symbolic();
        }
    }

    /// Theory `theory`'s reasoner, as this search has proved it so far.
    pub fn reasoner(&self, theory: usize) -> RefMut<'_, Reasoner> {
        self.reasoners[theory].borrow_mut()
    }

    /// How many values this search has met.
    pub fn values_met(&self) -> usize {
        self.values.borrow().len()
    }

    /// How many input valuations this search's reasoners proved.
    pub fn valuations(&self) -> usize {
        self.reasoners.iter().map(|r| r.borrow().valuations()).sum()
    }
}

impl Deref for Search<'_> {
    type Target = Model;

    fn deref(&self) -> &Model {
        self.model
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The model is a frozen value: searches on other threads may read it at once.
    #[test]
    fn the_model_is_shared_between_threads() {
        fn shared<T: Send + Sync>() {}
        shared::<Model>();
    }
}
