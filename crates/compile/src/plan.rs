//! A behaviour's compiled form that no target language decides: the whiteboard's slots, the
//! machines, their states and transitions, labels as conditions and activities as steps. A
//! printer (`print_c.rs`, `print_rust.rs`) writes it in its language, so every target keeps one
//! meaning.

use crate::tabulate::Compiled;
use proclaim_fsm::control::Command;

/// Everything a printer needs to write a behaviour.
pub(crate) struct Plan {
    pub name: String,
    pub theories: Vec<PlannedTheory>,
    /// The theories' outputs, numbered across the behaviour.
    pub outputs: Vec<Output>,
    /// Posting types that set a theory input, in theory order, then the impersonator's atoms.
    pub inputs: Vec<Input>,
    /// How many atoms come from outside (no theory answers them; the behaviour's script or a
    /// sensor does): the host supplies them, from its script.
    pub outside: usize,
    /// Each module whose atoms come from the run's script (a sensor wrapper, a Prolog or program
    /// expert) and the atoms it answers: a run's script must set one of them, so that the
    /// interpreter leaves the module out as the compiled program does.
    pub sensors: Vec<(String, Vec<String>)>,
    /// The behaviour's own script (`[impersonator]`), its file as shown and its text: what a
    /// run without `--script` plays.
    pub script: Option<(String, String)>,
    /// The value slots (each machine's own variables, then the globals): whether each starts as
    /// a truth value rather than a whole number.
    pub slots: Vec<bool>,
    /// The whiteboard values the machines read, numbered: the board's newest value of each
    /// type, which every machine reads through its ringlet's snapshot and a posting sets (the
    /// whiteboard variables, `extern x`, and the types read by name alone).
    pub externs: Vec<BoardValue>,
    pub machines: Vec<MachinePlan>,
    pub period_ms: u64,
    /// How long a query to an expert in another process waits (the manifest's `answer_timeout`).
    pub answer_timeout_ms: u64,
    /// The longest text a posting or a print builds.
    pub longest_text: usize,
    /// Places that post a control command: no ringlet queues more than that.
    pub commands: usize,
    /// The types under subsumption (the manifest's `[suppress]`), in name order.
    pub suppressed: Vec<Suppressed>,
    /// The composite states of every machine's chart, numbered across the behaviour: the
    /// machine each is in (its time tests count from its entry, `docs/spec/behaviour.md` §3.2).
    pub composites: Vec<usize>,
    /// The manifest's `[ranges]`: each type's lowest and highest whole number from outside,
    /// which what `verify` proved assumed (a posting that leaves one is a warning).
    pub ranges: Vec<(String, i64, i64)>,
}

/// A whiteboard type the machines read as a value: its newest posting, of a whole number or a
/// truth value.
pub(crate) struct BoardValue {
    pub name: String,
    /// Bound with `extern` by some machine: read as a whole 0 while nothing was posted, as
    /// gufsm's cache did; else read as no value at all (`x == 1` and `x != 1` both false).
    pub bound: bool,
    /// `NameIsRunning` of machine `status_of`: the runner posts that machine's running state.
    pub status_of: Option<usize>,
}

/// A type under subsumption: a posting of a higher layer holds it against lower layers'.
pub(crate) struct Suppressed {
    pub ty: String,
    pub hold_ms: u64,
}

impl Plan {
    /// The decision variables of every theory, then a known/true pair for each atom the
    /// impersonator answers.
    pub fn variables(&self) -> usize {
        self.theories
            .iter()
            .map(|t| t.compiled.variables())
            .sum::<usize>()
            + 2 * self.outside
    }

    /// Each posting type that sets inputs, in first-seen order, with the variable pairs it sets.
    pub fn input_types(&self) -> Vec<(&str, Vec<&Input>)> {
        let mut types: Vec<(&str, Vec<&Input>)> = Vec::new();
        for input in &self.inputs {
            match types.iter_mut().find(|(ty, _)| *ty == input.ty) {
                Some((_, inputs)) => inputs.push(input),
                None => types.push((&input.ty, vec![input])),
            }
        }
        types
    }

    /// The outputs a theory answers (the first ones; the impersonator's follow).
    pub fn theory_outputs(&self) -> usize {
        self.outputs
            .iter()
            .filter(|o| matches!(o.answer, Answer::Theory { .. }))
            .count()
    }

    /// The machines' subsumption layers, each priority once, lowest first.
    pub fn layers(&self) -> Vec<u32> {
        let mut layers: Vec<u32> = self.machines.iter().map(|m| m.priority).collect();
        layers.sort_unstable();
        layers.dedup();
        layers
    }

    /// The most answers one label asks (its atoms, each place counted).
    pub fn most_asks(&self) -> usize {
        fn asks(c: &Condition) -> usize {
            match c {
                Condition::Ask(_) | Condition::AskPosted { .. } => 1,
                Condition::Not(c) => asks(c),
                Condition::Both { left, right, .. } => asks(left) + asks(right),
                Condition::Constant(_) | Condition::Elapsed { .. } | Condition::Truth(_) => 0,
            }
        }
        self.machines
            .iter()
            .flat_map(|m| &m.states)
            .flat_map(|s| &s.transitions)
            .map(|t| asks(&t.condition))
            .max()
            .unwrap_or(0)
    }

    /// Room for the longest text a posting makes (its end included), constant or built: what
    /// a posting held back by subsumption keeps until it takes over.
    pub fn longest_posting(&self) -> usize {
        fn walk(step: &Step, longest: &mut usize) {
            match step {
                Step::Post { content, .. } => *longest = (*longest).max(content.len() + 1),
                Step::Block(steps) => steps.iter().for_each(|s| walk(s, longest)),
                Step::Loop {
                    init, body, step, ..
                } => {
                    for s in init.iter().chain(step.iter()) {
                        walk(s, longest);
                    }
                    walk(body, longest);
                }
                _ => {}
            }
        }
        let mut longest = self.longest_text;
        for state in self.machines.iter().flat_map(|m| &m.states) {
            let leavings = state.leavings.iter().flatten();
            for s in state.entry.iter().chain(leavings).chain(&state.staying) {
                walk(s, &mut longest);
            }
        }
        longest
    }
}

pub(crate) struct PlannedTheory {
    pub compiled: Compiled,
    /// The name its code goes by (`theory_NAME`), an identifier in every target.
    pub prefix: String,
}

pub(crate) struct Output {
    pub name: String,
    pub answer: Answer,
    /// The expert a trace names as its answerer.
    pub expert: String,
}

/// Where an output's answer comes from.
pub(crate) enum Answer {
    /// Output `index` of theory `theory`, whose decision variables start at `offset`.
    Theory {
        theory: usize,
        index: usize,
        offset: usize,
    },
    /// From outside: the last truth the host posted for it (false before any), the pair of
    /// decision variables (known, true) at `variable`; answered by the impersonator when the
    /// run's script sets it, else by no expert.
    Outside { variable: usize },
}

pub(crate) struct Input {
    /// The posting type that sets it.
    pub ty: String,
    /// Its pair of decision variables (known, true).
    pub variable: usize,
    /// The variables of the other atoms of its input group: set true, it makes them known and
    /// false, as the reasoner's session does (`docs/spec/cdl.md` §1).
    pub group: Vec<usize>,
}

pub(crate) struct MachinePlan {
    pub name: String,
    pub initial: i64,
    /// Whether it runs from the start (else dormant until started).
    pub start: bool,
    /// Its subsumption layer (the manifest's `priority`), which its postings carry.
    pub priority: u32,
    pub states: Vec<StatePlan>,
    /// How `proclaim draw` draws it, for a compiled program's monitor page: every transition
    /// (source, target, label) in the machine's order, and the DOT text.
    pub drawing: Drawing,
}

pub(crate) struct Drawing {
    /// Each transition's source, target, label and whether it stays (`when p { … }`).
    pub transitions: Vec<(i64, i64, String, bool)>,
    pub dot: String,
}

pub(crate) struct StatePlan {
    pub id: i64,
    pub name: String,
    pub entry: Vec<Step>,
    /// What its transitions run as they fire, each once ([`TransitionPlan::leaving`]).
    pub leavings: Vec<Vec<Step>>,
    pub staying: Vec<Step>,
    /// Tried top to bottom; the first whose condition holds fires.
    pub transitions: Vec<TransitionPlan>,
    /// No way out: the machine's run is over here.
    pub is_final: bool,
    /// The outputs its labels ask, sorted, each once.
    pub reads: Vec<usize>,
    /// The milliseconds after entry at which its time tests come due, in label order, each
    /// with the composite it counts from (none: from the state's entry).
    pub due_ms: Vec<(u64, Option<usize>)>,
    /// Whether its labels read a global.
    pub reads_globals: bool,
    /// The whiteboard variables its labels read, each once.
    pub reads_externs: Vec<usize>,
}

pub(crate) struct TransitionPlan {
    pub condition: Condition,
    pub target: i64,
    /// The label as written, for the trace.
    pub label: String,
    /// What it runs as it fires: its state's `leavings[leaving]`.
    pub leaving: usize,
    /// The composites it enters ([`Plan::composites`]), whose time tests count from then.
    pub enters: Vec<usize>,
    /// It fires without moving (`Arm::stays`): its state is not entered again.
    pub stays: bool,
}

/// A label as the runner proves it.
pub(crate) enum Condition {
    Constant(bool),
    /// A theory output asked (and reported as answered).
    Ask(usize),
    /// An atom no expert answers, read from whiteboard value `number` as the ringlet sees it
    /// (reported as answered by the module that posted it, or by none).
    AskPosted {
        number: usize,
        atom: String,
    },
    Not(Box<Condition>),
    Both {
        and: bool,
        left: Box<Condition>,
        right: Box<Condition>,
    },
    /// At least this many milliseconds in the state, or in a composite ([`Plan::composites`]).
    Elapsed {
        ms: u64,
        composite: Option<usize>,
    },
    /// A value's truth.
    Truth(Value),
}

/// An expression's value, as the runner's `Int` and `Bool`.
pub(crate) enum Value {
    Bool(bool),
    Int(i64),
    /// A variable's slot.
    Slot(usize),
    /// A whiteboard value, as the ringlet reads it (live before its snapshot, the snapshot and
    /// its own postings after); while nothing was posted, a whole 0 when bound with `extern`,
    /// else no value.
    Extern(usize),
    /// The truth value of `!operand`.
    Not(Box<Value>),
    /// The truth value of `left && right` or `left || right`.
    Logic {
        and: bool,
        left: Box<Value>,
        right: Box<Value>,
    },
    Apply(Function, Vec<Value>),
}

/// `proclaim-lower`'s `arith` operators and functions on values.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum Function {
    Eq,
    Ne,
    Lt,
    Le,
    Gt,
    Ge,
    Add,
    Sub,
    Mul,
    Div,
    Rem,
    Neg,
    Abs,
    Min,
    Max,
}

impl Function {
    /// The helper's name in every runtime (`v_add`, …).
    pub fn helper(self) -> &'static str {
        match self {
            Function::Eq => "v_eq",
            Function::Ne => "v_ne",
            Function::Lt => "v_lt",
            Function::Le => "v_le",
            Function::Gt => "v_gt",
            Function::Ge => "v_ge",
            Function::Add => "v_add",
            Function::Sub => "v_sub",
            Function::Mul => "v_mul",
            Function::Div => "v_div",
            Function::Rem => "v_rem",
            Function::Neg => "v_neg",
            Function::Abs => "v_abs",
            Function::Min => "v_min",
            Function::Max => "v_max",
        }
    }
}

/// How a value assigned to a variable is converted, as `arith::convert` does.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum Conversion {
    /// `int`, `char`: a truth value becomes 0 or 1.
    Whole,
    /// `bool`: the value's truth.
    Truth,
    /// A global, or a declared type the runner keeps as assigned.
    Kept,
}

/// A piece of a posting's or a print's text.
pub(crate) enum Piece {
    Literal(String),
    /// A value's text.
    Value(Value),
    /// A value as a whole number (`post_int`).
    Whole(Value),
}

/// One thing an activity does.
pub(crate) enum Step {
    /// A posting of constant text.
    Post {
        ty: String,
        content: String,
    },
    /// A posting of text built at run time.
    PostBuilt {
        ty: String,
        pieces: Vec<Piece>,
    },
    /// A control command to machine `target`, posted as `ty: word`.
    Command {
        ty: String,
        word: String,
        command: Option<Command>,
        target: usize,
    },
    Print(Vec<Piece>),
    /// A posting of a value to a whiteboard variable's type (an assignment to it, or a posting
    /// of one value): posted as its text, then read as the value.
    PostExtern {
        number: usize,
        value: Value,
    },
    Assign {
        slot: usize,
        conversion: Conversion,
        global: bool,
        name: String,
        value: Value,
    },
    Block(Vec<Step>),
    /// A `for` loop, stopped after `proclaim_lower::LOOP_LIMIT` rounds with a warning.
    Loop {
        /// Numbers the loop's counter, unique in the behaviour.
        number: usize,
        /// The state it is in, for the warning.
        state: String,
        init: Option<Box<Step>>,
        condition: Option<Value>,
        body: Box<Step>,
        step: Option<Box<Step>>,
    },
    /// A statement that does nothing (an empty one, an expression standing alone).
    Nothing,
}
