//! The reasoner expert: a CDL theory on the whiteboard. Its declared inputs are read from
//! messages (of the same name unless mapped), its declared outputs are the atoms it answers,
//! each with the algorithm its `output{}` names.

use parking_lot::Mutex;
use proclaim_board::{undecided_type, ModuleDecl, Pattern, Value, Whiteboard, QUERY_TYPE};
use proclaim_cdl::{Algorithm, Atom, Engine, Explanation, Lit, SearchLimits, Session, Theory};
use rustc_hash::FxHashMap;
use serde::{Deserialize, Serialize};
use std::sync::atomic::{AtomicU64, Ordering};
use std::sync::Arc;
use tracing::Instrument;

struct OutputSlot {
    name: String,
    lit: Lit,
    algorithm: Algorithm,
    last: Option<bool>,
    /// Whether its last answer was undecided (answered false).
    undecided: bool,
}

/// What a reasoner expert holds between two messages: each input as it was applied and each
/// output's last answer (whose change it posts unasked). A run's checkpoint keeps it, so the
/// expert taken up from it posts what the uninterrupted one would have.
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct ReasonerMemory {
    /// The sequence number of the last message it handled (of those it follows: its inputs and
    /// queries); one of those above it is still to be handled.
    pub handled: u64,
    pub inputs: Vec<HeldInput>,
    pub outputs: Vec<LastAnswer>,
}

#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct HeldInput {
    #[serde(rename = "type")]
    pub ty: String,
    /// `None`: unknown.
    pub value: Option<bool>,
}

#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct LastAnswer {
    pub name: String,
    /// `None`: never answered yet.
    pub last: Option<bool>,
    pub undecided: bool,
}

pub struct ReasonerExpert {
    name: String,
    session: Session,
    /// Message type → input atom.
    inputs: FxHashMap<String, Atom>,
    outputs: Vec<OutputSlot>,
    /// Answers the search could not decide within its limits (answered false).
    undecided: Arc<AtomicU64>,
    /// Outputs that became undecided or decided again since last posted (`NameUndecided`).
    undecided_changes: Vec<(String, bool)>,
    /// Kept up to date after every message, when someone asked ([`ReasonerExpert::remembered`]).
    memory: Option<Arc<Mutex<ReasonerMemory>>>,
    /// Taken up from a checkpoint: the board's inputs were applied already.
    resumed: bool,
}

impl ReasonerExpert {
    /// An expert for `theory`; `mapping` renames input atoms to message types (atom → type).
    /// A theory that declares no outputs answers every atom of its rules with β.
    pub fn new(
        name: impl Into<String>,
        theory: Theory,
        mapping: &FxHashMap<String, String>,
    ) -> ReasonerExpert {
        let inputs = theory
            .input_atoms()
            .map(|a| {
                let atom = theory.atom_name(a);
                (
                    mapping
                        .get(atom)
                        .cloned()
                        .unwrap_or_else(|| atom.to_string()),
                    a,
                )
            })
            .collect();
        let mut outputs: Vec<OutputSlot> = theory
            .outputs()
            .iter()
            .map(|o| OutputSlot {
                name: theory.show(o.lit).to_string(),
                lit: o.lit,
                algorithm: o.algorithm,
                last: None,
                undecided: false,
            })
            .collect();
        if outputs.is_empty() {
            let input_atoms: Vec<Atom> = theory.input_atoms().collect();
            outputs = (0..theory.atom_count() as u32)
                .map(Atom)
                .filter(|a| !input_atoms.contains(a))
                .map(|a| OutputSlot {
                    name: theory.atom_name(a).to_string(),
                    lit: Lit::positive(a),
                    algorithm: Algorithm::Beta,
                    last: None,
                    undecided: false,
                })
                .collect();
        }
        ReasonerExpert {
            name: name.into(),
            session: Session::new(Arc::new(Engine::new(theory))),
            inputs,
            outputs,
            undecided: Arc::default(),
            undecided_changes: Vec::new(),
            memory: None,
            resumed: false,
        }
    }

    /// What the expert holds, kept up to date while it runs (read it between two steps of
    /// the machines, when it has nothing left to do).
    pub fn remembered(&mut self) -> Arc<Mutex<ReasonerMemory>> {
        let memory = Arc::new(Mutex::new(self.memory(0)));
        self.memory = Some(memory.clone());
        memory
    }

    fn memory(&self, handled: u64) -> ReasonerMemory {
        ReasonerMemory {
            handled,
            inputs: self
                .inputs_held()
                .into_iter()
                .map(|(ty, value)| HeldInput { ty, value })
                .collect(),
            outputs: self
                .outputs
                .iter()
                .map(|o| LastAnswer {
                    name: o.name.clone(),
                    last: o.last,
                    undecided: o.undecided,
                })
                .collect(),
        }
    }

    /// Takes up where `memory` left off: its inputs applied, its outputs' last answers known
    /// (an output it does not name is posted at the start, as a new expert's are).
    pub fn resumed(mut self, memory: &ReasonerMemory) -> ReasonerExpert {
        for input in &memory.inputs {
            if let Some(&atom) = self.inputs.get(&input.ty) {
                if let Err(conflict) = self.session.set_input(atom, input.value) {
                    tracing::warn!(expert = %self.name, %conflict, "input refused");
                }
            }
        }
        for kept in &memory.outputs {
            if let Some(o) = self.outputs.iter_mut().find(|o| o.name == kept.name) {
                o.last = kept.last;
                o.undecided = kept.undecided;
            }
        }
        self.resumed = true;
        self
    }

    fn remember(&self, handled: u64) {
        if let Some(memory) = &self.memory {
            *memory.lock() = self.memory(handled);
        }
    }

    /// Bounds the search inside attack cycles (the manifest's `budget`); an answer not decided
    /// within them is false, with a warning, and counted.
    pub fn with_limits(mut self, limits: SearchLimits) -> ReasonerExpert {
        self.session.set_limits(limits);
        self
    }

    /// The expert answering only those of its outputs in `labels`: another module (the
    /// embedding program, a script) answers the rest. Its reasoning is unchanged: a conclusion
    /// that rests on an output it gave up still rests on its own.
    pub fn answering_only(mut self, labels: &[String]) -> ReasonerExpert {
        self.outputs.retain(|o| labels.contains(&o.name));
        self
    }

    /// How many answers were undecided within the search limits so far (shared: it keeps
    /// counting while the expert runs).
    pub fn undecided(&self) -> Arc<AtomicU64> {
        self.undecided.clone()
    }

    /// The answer to output `o`: an undecided one is false, with a warning, as a timed-out
    /// query is, and its `NameUndecided` is due to change when it was decided before.
    fn decide(&mut self, o: usize) -> bool {
        let (algorithm, lit) = (self.outputs[o].algorithm, self.outputs[o].lit);
        let (value, undecided) = match self.session.decide(algorithm, lit) {
            Ok(v) => (v, false),
            Err(undecided) => {
                self.undecided.fetch_add(1, Ordering::Relaxed);
                tracing::warn!(expert = %self.name, %undecided, "answered false");
                (false, true)
            }
        };
        let slot = &mut self.outputs[o];
        if slot.undecided != undecided {
            slot.undecided = undecided;
            self.undecided_changes.push((slot.name.clone(), undecided));
        }
        value
    }

    /// Outputs whose being undecided changed since last asked: (name, undecided now).
    pub fn undecided_changes(&mut self) -> Vec<(String, bool)> {
        std::mem::take(&mut self.undecided_changes)
    }

    /// What it posts, reads and answers, for the registry.
    pub fn declaration(&self) -> ModuleDecl {
        let mut reads: Vec<&String> = self.inputs.keys().collect();
        reads.sort();
        ModuleDecl::new(&self.name)
            .reads(reads.into_iter().cloned().chain([QUERY_TYPE.to_string()]))
            .posts(self.outputs.iter().map(|o| o.name.clone()))
            .answers(self.outputs.iter().map(|o| o.name.clone()))
    }

    /// Applies one input message: true, false (truthiness), or unknown for the string `unknown`.
    /// Returns false when the type is not an input of this theory. An input that contradicts the
    /// axioms is refused, logged, and changes nothing.
    pub fn apply(&mut self, ty: &str, value: &Value) -> bool {
        let Some(&atom) = self.inputs.get(ty) else {
            return false;
        };
        let v = match value {
            Value::Str(s) if s.eq_ignore_ascii_case("unknown") => None,
            other => Some(other.truthy()),
        };
        if let Err(conflict) = self.session.set_input(atom, v) {
            tracing::warn!(expert = %self.name, %conflict, "input refused");
        }
        true
    }

    /// The outputs whose value changed since last asked (all of them the first time).
    pub fn changed_outputs(&mut self) -> Vec<(String, bool)> {
        let mut changed = Vec::new();
        for i in 0..self.outputs.len() {
            let v = self.decide(i);
            let o = &mut self.outputs[i];
            if o.last != Some(v) {
                o.last = Some(v);
                changed.push((o.name.clone(), v));
            }
        }
        changed
    }

    /// The answer for one output, if this expert owns it.
    pub fn answer(&mut self, atom: &str) -> Option<bool> {
        let o = self.outputs.iter().position(|o| o.name == atom)?;
        Some(self.decide(o))
    }

    /// Why output `atom` is answered as it is now: its algorithm's proof (or failure) of it,
    /// `depth` levels down; `None` when this expert does not own it.
    pub fn explain(&mut self, atom: &str, depth: usize) -> Option<Explanation> {
        let o = self.outputs.iter().position(|o| o.name == atom)?;
        let (algorithm, lit) = (self.outputs[o].algorithm, self.outputs[o].lit);
        Some(self.session.explain(algorithm, lit, depth))
    }

    /// Each input as the expert holds it now: its message type and value (`None`: unknown),
    /// in the order of the types' names.
    pub fn inputs_held(&self) -> Vec<(String, Option<bool>)> {
        let mut held: Vec<(String, Option<bool>)> = self
            .inputs
            .iter()
            .map(|(ty, atom)| (ty.clone(), self.session.input(*atom)))
            .collect();
        held.sort();
        held
    }

    /// Registers, posts the initial outputs, then follows its inputs and answers queries until
    /// the whiteboard is gone.
    pub async fn run(self, board: Whiteboard) {
        let span = tracing::info_span!("reasoner_expert", name = %self.name);
        self.serve(board).instrument(span).await
    }

    fn post_undecided(&mut self, board: &Whiteboard) {
        for (name, undecided) in self.undecided_changes() {
            board.post(&self.name, &undecided_type(&name), undecided);
        }
    }

    async fn serve(mut self, board: Whiteboard) {
        // Subscribed before registering, so no query sent once it is registered is missed.
        let mut types: Vec<String> = self.inputs.keys().cloned().collect();
        types.push(QUERY_TYPE.to_string());
        let mut messages = board.subscribe_pattern(Pattern::Any(types));
        let subscribed = board.snapshot().seq;
        board.register(self.declaration());
        // Inputs posted before the expert started count too (taken up from a checkpoint, they
        // were applied as they came).
        let current: Vec<(String, Value)> = self
            .inputs
            .keys()
            .filter(|_| !self.resumed)
            .filter_map(|ty| board.latest(ty).map(|m| (ty.clone(), m.value)))
            .collect();
        for (ty, value) in current {
            self.apply(&ty, &value);
        }
        let initial = self.changed_outputs();
        self.post_undecided(&board);
        for (name, v) in initial {
            board.post(&self.name, &name, v);
        }
        self.remember(subscribed);
        while let Some(m) = messages.next().await {
            if &*m.ty == QUERY_TYPE {
                if let Value::Str(atom) = &m.value {
                    if let Some(v) = self.answer(atom) {
                        // Before the answer: whoever reads the answer finds it marked.
                        self.post_undecided(&board);
                        board.post(&self.name, atom, v);
                    }
                }
            } else if self.apply(&m.ty, &m.value) {
                let changed = self.changed_outputs();
                self.post_undecided(&board);
                for (name, v) in changed {
                    board.post(&self.name, &name, v);
                }
            }
            self.remember(m.seq);
        }
    }
}
