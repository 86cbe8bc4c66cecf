//! The exact reductions of the search: what a state needs to store, decided once from what the
//! machines, reasoners and properties read. Each is switchable ([`Reductions`]), and the tests
//! hold every verdict and every counterexample's length to those of the search without it.
//!
//! - **Chosen when read.** A free type (the environment's) is not stored: a ringlet that reads
//!   it chooses its value there and then, once per snapshot, as the environment could have set
//!   it just before (`ringlet.rs` walks every choice). Its value between ringlets cannot matter
//!   to anything but a property that names it, so such a type stays stored, set after every
//!   ringlet as before.
//! - **Cone of influence.** A variable or whiteboard type that no label, statement, asked
//!   reasoner, `saw()` or property reads is never stored, and writing it does nothing: nothing
//!   can tell its values apart.
//! - **Stop when decided** (in `explore.rs`): once every property has found what it looks for
//!   (a witness, a violation), the rest of the graph cannot change a verdict.

use crate::model::{Model, Name, SlotId, Storage};
use crate::property::{Property, Term};
use proclaim_fsm::Expr;

/// Which exact reductions the search applies; all by default.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Reductions {
    pub chosen_when_read: bool,
    pub cone_of_influence: bool,
    pub stop_when_decided: bool,
}

impl Default for Reductions {
    fn default() -> Reductions {
        Reductions {
            chosen_when_read: true,
            cone_of_influence: true,
            stop_when_decided: true,
        }
    }
}

impl Reductions {
    /// The plain search: every slot stored, every state explored.
    pub const NONE: Reductions = Reductions {
        chosen_when_read: false,
        cone_of_influence: false,
        stop_when_decided: false,
    };
}

/// How each slot of `model` is kept under `reductions`, given the properties checked.
pub fn storage(model: &Model, properties: &[Property], reductions: Reductions) -> Vec<Storage> {
    let mut reads = Reads::new(model);
    for (m, machine) in model.machines.iter().enumerate() {
        for t in &machine.machine.transitions {
            reads.expression(Some(m), &t.label);
        }
        for s in machine.machine.statements() {
            for e in s.expressions() {
                reads.expression(Some(m), e);
            }
        }
    }
    for (m, e) in &model.saw {
        reads.expression(Some(*m), e);
    }
    for p in properties {
        reads.term(p.term());
        if let Some(then) = p.then_term() {
            reads.term(then);
        }
        for fair in p.fair_terms() {
            reads.term(fair);
        }
    }
    model
        .slots
        .iter()
        .enumerate()
        .map(|(slot, s)| {
            if reductions.chosen_when_read && s.free.is_some() && !reads.named[slot] {
                Storage::ChosenWhenRead
            } else if reductions.cone_of_influence && !reads.read[slot] && !reads.named[slot] {
                Storage::Unread
            } else {
                Storage::Stored
            }
        })
        .collect()
}

/// What is read, gathered: by machines and reasoners (`read`), and by properties between
/// ringlets (`named`, which must be stored to be seen there).
struct Reads<'m> {
    model: &'m Model,
    read: Vec<bool>,
    named: Vec<bool>,
    /// Reasoners asked by a machine or a property, and those asked by a property.
    asked: Vec<bool>,
    asked_by_property: Vec<bool>,
}

impl<'m> Reads<'m> {
    fn new(model: &'m Model) -> Reads<'m> {
        Reads {
            model,
            read: vec![false; model.slots.len()],
            named: vec![false; model.slots.len()],
            asked: vec![false; model.theories.len()],
            asked_by_property: vec![false; model.theories.len()],
        }
    }

    fn expression(&mut self, machine: Option<usize>, e: &Expr) {
        let mut names = Vec::new();
        e.visit_names(&mut |n, _| names.push(n.to_string()));
        for n in names {
            if let Some(name) = self.model.resolve(machine, &n) {
                self.name(name, false);
            }
        }
    }

    fn name(&mut self, name: Name, by_property: bool) {
        match name {
            Name::Slot(slot) => self.slot(slot, by_property),
            Name::Answer { theory, .. } => self.theory(theory, by_property),
            Name::Running(_) => {}
        }
    }

    fn slot(&mut self, slot: SlotId, by_property: bool) {
        self.read[slot] = true;
        self.named[slot] |= by_property;
    }

    /// A reasoner asked: its inputs are read where it is asked (between ringlets too, when a
    /// property asks it).
    fn theory(&mut self, theory: usize, by_property: bool) {
        let seen = if by_property {
            &mut self.asked_by_property
        } else {
            &mut self.asked
        };
        if seen[theory] {
            return;
        }
        seen[theory] = true;
        let inputs: Vec<Name> = self.model.theories[theory]
            .inputs
            .iter()
            .filter_map(|(_, name)| *name)
            .collect();
        for name in inputs {
            self.name(name, by_property);
        }
    }

    fn term(&mut self, term: &Term) {
        match term {
            Term::Slot(slot) => self.slot(*slot, true),
            Term::Answer { theory, .. } => self.theory(*theory, true),
            Term::Const(_) | Term::Running(_) | Term::InState { .. } | Term::Saw(_) => {}
            Term::Not(t) | Term::Neg(t) => self.term(t),
            Term::And(l, r) | Term::Or(l, r) | Term::Binary(_, l, r) => {
                self.term(l);
                self.term(r);
            }
            Term::Function(_, args) => args.iter().for_each(|a| self.term(a)),
        }
    }
}
