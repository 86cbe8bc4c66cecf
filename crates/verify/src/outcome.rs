//! What verification finds, as data: each property's verdict with its shortest counterexample
//! (or witness), the built-in findings, and the size of the exploration.

pub use crate::seen::Run;
use serde::Serialize;

#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize)]
#[serde(rename_all = "lowercase")]
pub enum Verdict {
    Holds,
    Fails,
    /// The search stopped (a budget ran out) before the question was settled.
    Incomplete,
}

/// Why the search stopped.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum Stop {
    /// Every reachable state was explored.
    Explored,
    /// Every property had found what it looks for; the rest could change no verdict.
    Decided,
    /// `--max-states` states were stored.
    StateBudget,
    /// The states stored reached `--max-memory` bytes.
    MemoryBudget,
    /// One state had more successors than the search takes of one state (its ringlet reads
    /// free values whose combinations multiply past it).
    ChoiceBudget,
}

impl Stop {
    /// The reason in words, for the report.
    pub fn describe(self) -> &'static str {
        match self {
            Stop::Explored => "every reachable state explored",
            Stop::Decided => "stopped once every property was decided",
            Stop::StateBudget => "the state budget ran out (--max-states)",
            Stop::MemoryBudget => "the memory budget ran out (--max-memory)",
            Stop::ChoiceBudget => {
                "a ringlet reads more combinations of free values than one state's successors may hold"
            }
        }
    }
}

/// A free value that reaches something the model's finite domain of it cannot follow (spec
/// §6, "Free values"): what the search then claims to be absent may not be.
#[derive(Clone, Debug, PartialEq, Eq, Hash, Serialize)]
pub struct Inexact {
    /// The free whiteboard type.
    pub value: String,
    /// What happens to it, with the expression.
    pub why: String,
    /// Where: file and line, or the property.
    pub place: String,
}

impl std::fmt::Display for Inexact {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(f, "{}: {}, at {}", self.value, self.why, self.place)
    }
}

/// A whiteboard type or variable and the value it took.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct Assignment {
    pub name: String,
    /// As people read it (text quoted).
    pub value: String,
    /// The value's truth when it is a truth value (what an impersonator script can set).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub truth: Option<bool>,
    /// The value as an impersonator script writes it (`-3`, `"kick"`); `None` where a script
    /// cannot set it (a list, text with a `#` or a line break).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub script: Option<String>,
}

/// One ringlet of a counterexample.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct TraceStep {
    /// Rounds count from 1; every running machine rings once per round.
    pub round: u32,
    pub machine: String,
    pub from: String,
    /// The state it moved to, when a transition fired and moved (one that stays has a label
    /// and no `to`).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub to: Option<String>,
    /// The label of the transition that fired.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub label: Option<String>,
    /// Time tests of its state that came due at the snapshot.
    #[serde(skip_serializing_if = "Vec::is_empty")]
    pub timers: Vec<String>,
    /// Free types as the ringlet read them, where they differ from what was last read (the
    /// search chooses a free type no property names where it is read).
    #[serde(skip_serializing_if = "Vec::is_empty")]
    pub read: Vec<Assignment>,
    /// Free types the world changed between the machine's OnEntry and its snapshot.
    #[serde(skip_serializing_if = "Vec::is_empty")]
    pub at_snapshot: Vec<Assignment>,
    /// Free types this ringlet read otherwise than an earlier ringlet of its round did: the
    /// world changed them between two machines' ringlets of one round.
    #[serde(skip_serializing_if = "Vec::is_empty")]
    pub between: Vec<Assignment>,
    /// Free types the world changed after the ringlet (seen by the next snapshot).
    #[serde(skip_serializing_if = "Vec::is_empty")]
    pub environment: Vec<Assignment>,
}

/// A path from an initial state: what the environment set first, then ringlet by ringlet.
#[derive(Clone, Debug, Serialize)]
pub struct Trace {
    pub initially: Vec<Assignment>,
    pub steps: Vec<TraceStep>,
    /// Truth values a ringlet read while nothing had posted them: false to the model, as to the
    /// runner (no expert answers them). A script posts them false from the start, so its replay
    /// asks no absent expert.
    #[serde(skip_serializing_if = "Vec::is_empty")]
    pub unposted: Vec<String>,
    /// The worlds the steps pass through, as a second model can follow them (`confirm.rs`).
    #[serde(skip)]
    pub run: Run,
}

/// Two traces are the same when they show the same: the worlds they pass through are each
/// model's own.
impl PartialEq for Trace {
    fn eq(&self, other: &Trace) -> bool {
        (self.initially == other.initially)
            && (self.steps == other.steps)
            && (self.unposted == other.unposted)
    }
}

impl Trace {
    /// The first `at` steps, and the rest with rounds numbered on (a lasso's way in and its
    /// loop, cut from one replayed run).
    pub(crate) fn split(self, at: usize) -> (Trace, Trace) {
        let at = at.min(self.steps.len());
        let (way_in, rest) = self.steps.split_at(at);
        let (run_in, run_rest) = self.run.split(at);
        let first = Trace {
            initially: self.initially,
            steps: way_in.to_vec(),
            unposted: self.unposted,
            run: run_in,
        };
        let then = Trace {
            initially: Vec::new(),
            steps: rest.to_vec(),
            unposted: Vec::new(),
            run: run_rest,
        };
        (first, then)
    }
}

#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct PropertyOutcome {
    pub name: String,
    /// `never`, `always`, `reachable`, `eventually`, `leads_to` or `always_eventually`.
    pub kind: String,
    pub expression: String,
    /// What a liveness property assumes the environment makes true infinitely often.
    #[serde(skip_serializing_if = "Vec::is_empty")]
    pub fair: Vec<String>,
    pub verdict: Verdict,
    /// For a `never`/`always` that fails: the shortest counterexample; for a `reachable` that
    /// holds: the shortest witness.
    /// For a liveness property that fails, the way into the loop of its lasso.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub trace: Option<Trace>,
    /// For a liveness property that fails: the loop its run repeats for ever after `trace`
    /// (rounds numbered on from it); no steps when the run ends where no machine can ring any
    /// more, which stays so for ever.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub cycle: Option<Trace>,
    /// Undecided because the run that decided it, with the clocks of different machines
    /// unordered, was not confirmed with them ordered (`refine.rs`): it may need one
    /// machine's longer timeout up before another's shorter one, which no real run shows.
    #[serde(skip_serializing_if = "std::ops::Not::not")]
    pub unconfirmed: bool,
    /// Decided by following the run the unordered search found through the ordered model,
    /// where the ordered search ran out (`confirm.rs`): the run is real, but not the shortest
    /// one with the clocks ordered.
    #[serde(skip_serializing_if = "std::ops::Not::not")]
    pub followed: bool,
}

/// What the exploration noticed whatever the properties say (spec §6's built-in checks).
#[derive(Clone, Debug, PartialEq, Serialize)]
#[serde(tag = "finding", rename_all = "snake_case")]
pub enum Finding {
    /// No run ever makes the state current.
    NeverEntered { machine: String, state: String },
    /// The transition never fires in any run (its label never holds there, or an earlier one
    /// always does, or its source is never entered).
    NeverFires {
        machine: String,
        from: String,
        to: String,
        label: String,
        line: usize,
    },
    /// A reachable state from which no machine can ever fire a transition again, whatever
    /// the environment does, while a machine that runs is not in a final state.
    Deadlock { waiting: Vec<String>, trace: Trace },
}

#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct SearchStats {
    pub states: usize,
    pub transitions: usize,
    /// Every reachable state was explored (else the search stopped early, for `stopped`).
    pub complete: bool,
    pub stopped: Stop,
    /// Bytes the search's tables held when it stopped.
    pub bytes: usize,
    /// Memory per stored state: its packed record, parent and hash-table entry, and its
    /// share of the edges kept for the deadlock check.
    pub bytes_per_state: f64,
    pub packed_bytes_per_state: f64,
    /// Breadth-first layers explored: the farthest state found is this many steps from an
    /// initial one.
    pub depth: usize,
    /// Distinct values met (grows with counters).
    pub values: usize,
    /// Input valuations the reasoners were asked to prove.
    pub valuations: usize,
    /// `explicit` or `symbolic`: which engine gave the report. The symbolic engine counts its
    /// layers as `transitions` and stores no state on its own (`packed_bytes_per_state` 0).
    pub engine: &'static str,
}

#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct Report {
    pub properties: Vec<PropertyOutcome>,
    pub findings: Vec<Finding>,
    pub stats: SearchStats,
    /// Why the model's free values are not exact, where they are not: a property that found
    /// nothing is then incomplete, and no "never" finding is reported.
    #[serde(skip_serializing_if = "Vec::is_empty")]
    pub inexact: Vec<Inexact>,
    /// The machines whose clocks were taken unordered against each other's (two or more with
    /// constant time tests, [`crate::Options::clock_order`] off), where that leaves a property
    /// undecided ([`PropertyOutcome::unconfirmed`]) or a deadlock found unconfirmed.
    #[serde(skip_serializing_if = "Vec::is_empty")]
    pub unordered_clocks: Vec<String>,
    /// The search that checked again, with the clocks of different machines ordered, the
    /// verdicts a run decided (`refine.rs`), where there was one.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub clocks_ordered: Option<OrderedCheck>,
}

/// The second search of `refine.rs`: how far it went and how long it took.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct OrderedCheck {
    pub stats: SearchStats,
    pub seconds: f64,
}

impl Report {
    /// The command line's exit status: 0 every property holds, 1 some fails, 3 none fails but
    /// some is undecided.
    pub fn exit_code(&self) -> u8 {
        if self.properties.iter().any(|p| p.verdict == Verdict::Fails) {
            1
        } else if self
            .properties
            .iter()
            .any(|p| p.verdict == Verdict::Incomplete)
        {
            3
        } else {
            0
        }
    }
}
