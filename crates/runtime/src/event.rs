//! What a running machine reports: the trace of a behaviour, as data. Events serialise one per
//! line as JSON (`at_us` is microseconds since the machine started), so a trace file replays.
//! The interpreter (`proclaim-runner`) and every compiled behaviour report these same events, so
//! their traces agree byte for byte by construction.

use serde::{Deserialize, Serialize};
use std::time::Duration;

/// A ringlet: the round, the machine's place in the schedule, the board's highest sequence
/// number as it began and its round's moment (time since the epoch). A message with a sequence
/// number up to `seq` was on the board before the ringlet began, and one up to `snapshot` was
/// in what it read; a recording of these is what lets a replay post every outside message
/// before the same ringlet again.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
pub struct Ringlet {
    pub round: u64,
    pub machine: usize,
    pub seq: u64,
    #[serde(rename = "at_us", with = "crate::event::micros")]
    pub at: Duration,
    /// The board's highest sequence number in the ringlet's snapshot, once it has run and if it
    /// read the board (a message that came after the ringlet began but before its snapshot was
    /// seen by it).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub snapshot: Option<u64>,
}

/// Every event that carries a time also carries its `round`: the round of the schedule it
/// happened in (`docs/spec/behaviour.md` §3.1), or, for a machine run on its own task
/// (`schedule = "concurrent"`), that machine's own count of ringlets. Traces written before
/// rounds existed read back with round 0.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(tag = "event", rename_all = "snake_case")]
pub enum Event {
    Entered {
        machine: String,
        state: String,
        id: i64,
        #[serde(default)]
        round: u64,
        #[serde(rename = "at_us", with = "micros")]
        at: Duration,
    },
    /// A label's atom was answered, or counted false for want of an answer.
    Answered {
        machine: String,
        atom: String,
        value: bool,
        by: Answerer,
        #[serde(default)]
        round: u64,
        #[serde(rename = "at_us", with = "micros")]
        at: Duration,
    },
    Fired {
        machine: String,
        from: i64,
        to: i64,
        label: String,
        #[serde(default)]
        round: u64,
        #[serde(rename = "at_us", with = "micros")]
        at: Duration,
    },
    /// A posting of an activity (sub-machine control included).
    Posted {
        machine: String,
        #[serde(rename = "type")]
        ty: String,
        content: String,
        /// The machine's subsumption priority (the manifest's `priority`); absent when 0.
        #[serde(default, skip_serializing_if = "is_zero")]
        priority: u32,
        #[serde(default)]
        round: u64,
        #[serde(rename = "at_us", with = "micros")]
        at: Duration,
    },
    /// A posting to a type declared `suppress` that readers never saw: `by`'s posting, of the
    /// higher priority `by_priority`, holds the type until `until_us`.
    Suppressed {
        machine: String,
        #[serde(rename = "type")]
        ty: String,
        content: String,
        priority: u32,
        by: String,
        by_priority: u32,
        #[serde(rename = "until_us", with = "micros")]
        until: Duration,
        #[serde(default)]
        round: u64,
        #[serde(rename = "at_us", with = "micros")]
        at: Duration,
    },
    /// The hold on a suppressed type ran out and this lower-priority posting of `machine`
    /// (made at `posted_us`, suppressed or subsumed then) took over: it is on the board now.
    TookOver {
        machine: String,
        #[serde(rename = "type")]
        ty: String,
        content: String,
        priority: u32,
        #[serde(rename = "posted_us", with = "micros")]
        posted: Duration,
        #[serde(default)]
        round: u64,
        #[serde(rename = "at_us", with = "micros")]
        at: Duration,
    },
    /// An activity changed a variable's value: the machine's own, or a global of the
    /// behaviour (an extern's change is its posting).
    Assigned {
        machine: String,
        variable: String,
        value: String,
        #[serde(default)]
        round: u64,
        #[serde(rename = "at_us", with = "micros")]
        at: Duration,
    },
    /// A host function the embedding program did not register; it is skipped (reported once).
    UnknownFunction { machine: String, function: String },
    Control {
        machine: String,
        command: String,
        #[serde(default)]
        round: u64,
        #[serde(rename = "at_us", with = "micros")]
        at: Duration,
    },
    /// The machine's file was read again and replaced the running machine; `state` is where it
    /// goes on (the current state kept by `reread`, else the initial state).
    Reloaded {
        machine: String,
        state: String,
        #[serde(default)]
        round: u64,
        #[serde(rename = "at_us", with = "micros")]
        at: Duration,
    },
    /// The machine's file could not be read again; the machine runs on unchanged.
    ReloadFailed {
        machine: String,
        error: String,
        #[serde(default)]
        round: u64,
        #[serde(rename = "at_us", with = "micros")]
        at: Duration,
    },
    /// The machine reached a state with no way out, and that state's OnEntry has run.
    Finished {
        machine: String,
        state: String,
        #[serde(default)]
        round: u64,
        #[serde(rename = "at_us", with = "micros")]
        at: Duration,
    },
    /// `print(…)`, `print_state_name()` and their kin.
    Printed {
        machine: String,
        text: String,
        #[serde(default)]
        round: u64,
        #[serde(rename = "at_us", with = "micros")]
        at: Duration,
    },
    /// Something in an activity went wrong but the machine runs on (a `for` loop stopped at
    /// its limit, a value that is not a number where one was needed).
    Warned {
        machine: String,
        message: String,
        #[serde(default)]
        round: u64,
        #[serde(rename = "at_us", with = "micros")]
        at: Duration,
    },
    /// The machine stopped for good (`RunOptions::halt_on_timeout`), saying why.
    Halted {
        machine: String,
        reason: String,
        #[serde(default)]
        round: u64,
        #[serde(rename = "at_us", with = "micros")]
        at: Duration,
    },
}

/// Who settled an atom's value.
#[derive(Clone, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Answerer {
    Expert(String),
    /// An expert is registered but did not answer in time; counted false.
    TimedOut,
    /// No expert answers the atom, but a module posted it (a machine's `NameIsRunning`, a
    /// sensor value): its latest value.
    Posted(String),
    /// No module answers or posts the atom; counted false at once.
    NoExpert,
}

impl Event {
    /// Whether a machine did something a later round could tell from doing nothing: every event
    /// but an answer read. A round of answers alone, with the outside silent and no time test to
    /// come, is the same round for ever after (`docs/spec/behaviour.md` §3.1, a still round).
    pub fn is_change(&self) -> bool {
        !matches!(self, Event::Answered { .. })
    }

    pub fn machine(&self) -> &str {
        match self {
            Event::Entered { machine, .. }
            | Event::Answered { machine, .. }
            | Event::Fired { machine, .. }
            | Event::Posted { machine, .. }
            | Event::Suppressed { machine, .. }
            | Event::TookOver { machine, .. }
            | Event::Assigned { machine, .. }
            | Event::UnknownFunction { machine, .. }
            | Event::Control { machine, .. }
            | Event::Reloaded { machine, .. }
            | Event::ReloadFailed { machine, .. }
            | Event::Finished { machine, .. }
            | Event::Printed { machine, .. }
            | Event::Warned { machine, .. }
            | Event::Halted { machine, .. } => machine,
        }
    }

    /// The round it happened in (0 for the events that carry none).
    pub fn round(&self) -> u64 {
        match self {
            Event::Entered { round, .. }
            | Event::Answered { round, .. }
            | Event::Fired { round, .. }
            | Event::Posted { round, .. }
            | Event::Suppressed { round, .. }
            | Event::TookOver { round, .. }
            | Event::Assigned { round, .. }
            | Event::Control { round, .. }
            | Event::Reloaded { round, .. }
            | Event::ReloadFailed { round, .. }
            | Event::Finished { round, .. }
            | Event::Printed { round, .. }
            | Event::Warned { round, .. }
            | Event::Halted { round, .. } => *round,
            Event::UnknownFunction { .. } => 0,
        }
    }

    /// When it happened, for the events that carry a time.
    pub fn at(&self) -> Option<Duration> {
        match self {
            Event::Entered { at, .. }
            | Event::Answered { at, .. }
            | Event::Fired { at, .. }
            | Event::Posted { at, .. }
            | Event::Suppressed { at, .. }
            | Event::TookOver { at, .. }
            | Event::Assigned { at, .. }
            | Event::Control { at, .. }
            | Event::Reloaded { at, .. }
            | Event::ReloadFailed { at, .. }
            | Event::Finished { at, .. }
            | Event::Printed { at, .. }
            | Event::Warned { at, .. }
            | Event::Halted { at, .. } => Some(*at),
            Event::UnknownFunction { .. } => None,
        }
    }
}

fn is_zero(priority: &u32) -> bool {
    *priority == 0
}

pub mod micros {
    use serde::{Deserialize, Deserializer, Serializer};
    use std::time::Duration;

    pub fn serialize<S: Serializer>(d: &Duration, s: S) -> Result<S::Ok, S::Error> {
        s.serialize_u64(d.as_micros().min(u128::from(u64::MAX)) as u64)
    }

    pub fn deserialize<'de, D: Deserializer<'de>>(d: D) -> Result<Duration, D::Error> {
        Ok(Duration::from_micros(u64::deserialize(d)?))
    }
}
