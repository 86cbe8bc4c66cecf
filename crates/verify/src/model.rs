//! The model of a loaded behaviour (spec §6): its machines in manifest order with their states,
//! prioritised transitions and time tests; every storage place a run has (a machine's own
//! variables, the behaviour's globals, the whiteboard types machines and reasoners read) as a
//! numbered slot; which slots the environment sets freely and from which finite domain; and
//! the reasoners whose answers labels ask for.
//!
//! Names resolve as the runner resolves them (`proclaim-runner`'s `variables.rs`): a name a
//! machine declares is its own, then externs, then globals (every other name some activity
//! assigns); any other name is a reasoner's answer when a theory outputs it, `NameIsRunning`
//! when it speaks of a machine, and otherwise a whiteboard type.

use crate::arith::text;
use crate::kind::ValueKind;
use crate::outcome::Inexact;
use crate::reasoner::ReasonerSeed;

use proclaim_board::Value;

use proclaim_fsm::{Expr, Label, Machine};
use rustc_hash::{FxHashMap, FxHashSet};
use std::time::Duration;

/// `Machine.STATE` is not in the label language; the dot becomes a letter no name can hold
/// (`ª`, one character, so columns stay the same) before parsing.
pub(crate) const DOT: char = 'ª';

pub type SlotId = usize;

/// What a name stands for where it is read.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Name {
    Slot(SlotId),
    /// Output `output` of reasoner `theory`: computed from its inputs, never stored.
    Answer {
        theory: usize,
        output: usize,
    },
    /// `NameIsRunning` of machine `m`: derived from its mode.
    Running(usize),
}

#[derive(Clone, Debug, PartialEq)]
pub enum SlotKind {
    /// A variable machine `machine` declares.
    Local {
        machine: usize,
        ty: proclaim_fsm::VarType,
    },
    /// A name some activity assigns that no machine declares: shared, starting at 0.
    Global,
    /// A whiteboard type; `external` when some machine declares it `extern` (it then reads 0
    /// before anything is posted, as gufsm's cache did).
    Message { external: bool },
}

#[derive(Clone, Debug)]
pub struct Slot {
    pub name: String,
    pub kind: SlotKind,
    /// The value before anything happens (`None`: never posted).
    pub initial: Option<Value>,
    /// Set by the environment at every snapshot, from this domain.
    pub free: Option<FreeDomain>,
    /// What kind of value it holds, from the constants the behaviour gives it (a property
    /// comparing it with another kind is refused).
    pub value_kind: ValueKind,
}

/// A time test of a state's labels: `timeout(3s)`, `after(2)`, `after_ms(n)`.
#[derive(Clone, Debug)]
pub struct TimeTest {
    /// The call as lowered: its clock included, so one test is one call.
    pub call: Expr,
    /// Its duration when the argument is a constant; tests of one clock with one come true in
    /// order of duration (a state cannot be 2 s old and not 1 s old).
    pub micros: Option<u64>,
    /// What it counts from (the call's clock): the entry of the state, or of the composite (an
    /// index into `Machine::composites`) whose transition it is on, which moves inside it
    /// keep (§3.2).
    pub clock: Option<usize>,
}

#[derive(Clone, Debug)]
pub struct TransitionModel {
    /// Its index in the machine's `transitions` (what findings report).
    pub index: usize,
    pub target: usize,
    pub label: Expr,
}

#[derive(Clone, Debug)]
pub struct StateModel {
    pub name: String,
    /// Outgoing transitions in priority order.
    pub transitions: Vec<TransitionModel>,
    pub time_tests: Vec<TimeTest>,
    /// The composites an arrival into it entered ([`Machine::arrival_enters`]): their time
    /// starts with its own.
    pub arrival_enters: Vec<usize>,
    /// Pairs `(later, earlier)` of its constant time tests on two clocks, where the clock of
    /// `earlier` started no later than that of `later` and `earlier`'s duration is no longer:
    /// at any moment `later` is due only if `earlier` is ([`crate::ringlet::due_masks`]).
    pub time_order: Vec<(u8, u8)>,
}

impl StateModel {
    /// The bits of its time tests that count from `clock`.
    pub fn clock_mask(&self, clock: Option<usize>) -> u16 {
        self.time_mask(|t| t.clock == clock)
    }

    /// The bits of its time tests that `keep` holds of.
    pub fn time_mask(&self, keep: impl Fn(&TimeTest) -> bool) -> u16 {
        self.time_tests
            .iter()
            .enumerate()
            .filter(|(_, t)| keep(t))
            .fold(0, |mask, (i, _)| mask | (1 << i))
    }

    /// Whether arriving in it starts `clock`: its own, or a composite the arrival entered.
    pub fn arrival_starts(&self, clock: Option<usize>) -> bool {
        clock.is_none_or(|c| self.arrival_enters.contains(&c))
    }

    /// A state with no way out: its machine's run ends once its OnEntry has run.
    pub fn is_final(&self) -> bool {
        self.transitions.is_empty()
    }

    /// Where the ringlet's `arm` is among [`StateModel::transitions`]; `None` for one the model
    /// leaves out (its target is no state).
    pub fn modelled(&self, arm: proclaim_lower::Arm<'_>) -> Option<usize> {
        self.transitions.iter().position(|t| t.index == arm.number)
    }
}

#[derive(Debug)]
pub struct MachineModel {
    pub name: String,
    pub machine: Machine,
    /// Index = position in `machine.states`.
    pub states: Vec<StateModel>,
    pub initial: usize,
    /// Running from the start (else a sub-machine, dormant until `Name: On`).
    pub start: bool,
    /// The machine's own variables.
    pub locals: FxHashMap<String, SlotId>,
    /// What its time tests count from: its states' entries (first, always), then each
    /// composite whose transitions test the time ([`TimeTest::clock`]).
    pub clocks: Vec<Option<usize>>,
}

impl MachineModel {
    /// The label of `t` as its file wrote it, for traces and messages.
    pub fn shown(&self, t: &TransitionModel) -> &Label {
        self.machine.transitions[t.index].shown()
    }

    /// A time test as traces show it: its call, and the composite it counts from when it is
    /// not its state's own (`after(3s) since LOOK`).
    pub fn time_test_shown(&self, test: &TimeTest) -> String {
        match test.clock.and_then(|c| self.machine.composites.get(c)) {
            Some(composite) => format!("{} since {}", test.call, composite.name),
            None => test.call.to_string(),
        }
    }

    /// The most time tests any one state has: the bits of the machine's time field in either
    /// engine's state (a bit a test, set once it came due).
    pub fn most_time_tests(&self) -> usize {
        self.states
            .iter()
            .map(|s| s.time_tests.len())
            .max()
            .unwrap_or(0)
    }
}

/// A reasoner: which slots feed its inputs, which atoms it answers.
pub struct TheoryModel {
    pub name: String,
    /// (message type, what it is in the model), in the expert's order; `None` for a type
    /// nothing models (it stays unknown to the theory).
    pub inputs: Vec<(String, Option<Name>)>,
    pub outputs: Vec<String>,
    pub(crate) reasoner: ReasonerSeed,
}

/// What the environment may set a free type to.
#[derive(Clone, Debug, PartialEq)]
pub struct FreeDomain {
    /// At every snapshot.
    pub values: Vec<Value>,
    /// In the initial state: `None` (never posted) and then `values`.
    pub initial: Vec<Option<Value>>,
}

/// How the search keeps a slot.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Storage {
    /// In every state (free ones set by the environment after every ringlet).
    Stored,
    /// A free type no property names: chosen by each snapshot that reads it, never stored.
    ChosenWhenRead,
    /// Nothing reads it: never stored, and writes to it are dropped.
    Unread,
}

pub struct Model {
    pub machines: Vec<MachineModel>,
    pub slots: Vec<Slot>,
    pub theories: Vec<TheoryModel>,
    /// How names that are no machine's own variable resolve.
    pub names: FxHashMap<String, Name>,
    /// Every whiteboard type a machine or an outside module posts, reads or answers: the
    /// names a property may use besides slots.
    pub known_types: FxHashSet<String>,
    /// What a property's `saw(Machine, name)` keeps: per machine, the name read at its last
    /// snapshot. Added by the properties before exploring.
    pub saw: Vec<(usize, Expr)>,
    /// How the search keeps each slot ([`crate::reduce`]); every slot stored until the
    /// reductions are decided.
    pub storage: Vec<Storage>,
    pub ring_period: Duration,
    /// Per machine, its rank among those whose clocks are ordered against each other's
    /// ([`crate::clocks::ranks`]).
    pub clock_ranks: Vec<Option<u8>>,
    /// Their constant durations ([`crate::clocks::durations`]).
    pub clock_durations: Vec<u64>,
    /// Where free values go that their finite domains do not follow ([`crate::flow`]): empty
    /// when the model's environment is exact for every test the behaviour makes.
    pub inexact: Vec<Inexact>,
}

impl Model {
    /// Leaves the clocks of different machines unordered ([`crate::Options::clock_order`]
    /// off): no machine has a rank, and the state keeps nothing for them.
    pub fn unorder_clocks(&mut self) {
        self.clock_ranks = vec![None; self.machines.len()];
        self.clock_durations.clear();
    }

    /// The `saw()` expressions machine `machine`'s labels hold, with their indices in `saw`.
    pub fn saw_of(&self, machine: usize) -> impl Iterator<Item = (usize, &Expr)> {
        self.saw
            .iter()
            .enumerate()
            .filter(move |(_, (m, _))| *m == machine)
            .map(|(j, (_, e))| (j, e))
    }

    /// How `name` resolves in machine `m` (`None` for a whiteboard type nobody models: it
    /// reads as never posted).
    pub fn resolve(&self, m: Option<usize>, name: &str) -> Option<Name> {
        if let Some(m) = m {
            if let Some(&slot) = self.machines[m].locals.get(name) {
                return Some(Name::Slot(slot));
            }
        }
        self.names.get(name).copied()
    }

    /// Per machine, per state: false, for a search to mark the states it enters.
    pub fn per_state(&self) -> Vec<Vec<bool>> {
        self.machines
            .iter()
            .map(|m| vec![false; m.states.len()])
            .collect()
    }

    /// Per machine, per transition (in the machine's list): false, for a search to mark the
    /// transitions that fire.
    pub fn per_transition(&self) -> Vec<Vec<bool>> {
        self.machines
            .iter()
            .map(|m| vec![false; m.machine.transitions.len()])
            .collect()
    }

    pub fn machine_index(&self, name: &str) -> Option<usize> {
        self.machines.iter().position(|m| m.name == name)
    }

    /// The free slots, in slot order.
    pub fn free_slots(&self) -> impl Iterator<Item = (SlotId, &FreeDomain)> + '_ {
        self.slots
            .iter()
            .enumerate()
            .filter_map(|(i, s)| Some((i, s.free.as_ref()?)))
    }

    /// The free slots every state stores (the environment sets them after every ringlet);
    /// the others are chosen where they are read.
    pub fn stored_free_slots(&self) -> impl Iterator<Item = (SlotId, &FreeDomain)> + '_ {
        self.free_slots()
            .filter(|(slot, _)| self.storage[*slot] == Storage::Stored)
    }

    /// A slot's value as people read it.
    pub fn show(&self, value: Option<&Value>) -> String {
        match value {
            None => "(never posted)".to_string(),
            Some(Value::Str(s)) => format!("{s:?}"),
            Some(v) => text(v),
        }
    }
}
