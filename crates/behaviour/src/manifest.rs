//! `behaviour.toml`: which machines, theories, sensor wrappers and impersonator make up a
//! behaviour, and how it runs.
//!
//! ```toml
//! description = "The seed paper's guGameController"
//! ring_period = "100ms"       # optional, the longest wait between rings
//! answer_timeout = "1s"       # optional, how long a label waits for its expert
//! schedule = "rounds"         # optional: rounds of ringlets (§3.1), or "concurrent"
//!
//! [[machine]]
//! file = "GameController.machine"      # native, Qfsm .fsm, or either file of a T/A pair
//!
//! [[machine]]
//! file = "Placer.machine"
//! start = false                        # a sub-machine: dormant until `Placer: On`
//! priority = 2                         # optional: its subsumption layer (default 0, the bottom)
//!
//! [suppress]                           # optional: types a higher layer's posting holds
//! walk = { hold = "500ms" }            # lower layers' postings to `walk` are suppressed for
//!                                      # 500ms after each higher one (Brooks' suppression)
//!
//! [[theory]]
//! file = "microwave.dl"                # a reasoner expert; its outputs are the labels it answers
//! mapping = "inputs.map"               # optional: input atom → message type
//! budget = 1000000                     # optional: search steps per attack cycle (the guide)
//!
//! [[prolog]]                           # a Prolog knowledge base; [[expert]]: any program
//! file = "offside.pl"                  # (both in program_entries.rs)
//! answers = ["offside"]
//!
//! [[sensor]]
//! kind = "gamecontroller"              # also: chest_button, foot_bumpers, fall
//! simulator = true                     # or a game script file, or false for a real one
//!
//! [impersonator]
//! script = "kitchen.script"            # answers from a script (testcdl)
//!
//! dictionary = "../nao.toml"           # modules outside the behaviour, as [[module]] entries
//! [[module]]                           # one such module here
//! name = "leds"
//! reads = ["LEDS"]                     # also posts = […], answers = […]
//!
//! [team]                               # optional: a robot of a team (team.rs)
//! name = "blue"
//! member = "robot1"                    # `proclaim run --member robot2` overrides it
//! shared = ["ballDistance", "role"]    # read on teammates as robot2.ballDistance,
//!                                      # team.min(ballDistance), team.argmin(…) == me
//! size = 3                             # optional: how many robots; `team.quorum` is true
//!                                      # while this one hears a majority of them
//!
//! [ranges]                             # optional: what the world posts to a type is a whole
//! doseEntered = "0..100"               # number of this range; verify tries each one
//!
//! [[property]]                         # checked by `proclaim verify` (spec §6)
//! name = "door interlock"
//! never = 'Magnetron == "on" && saw(Microwave, doorOpen)'   # or always = …, reachable = …
//! # liveness: eventually = …, always_eventually = …, leads_to = ["P", "Q"]; fair = "EXPR" assumes
//! # the environment makes EXPR true infinitely often
//! ```

use proclaim_syntax::{line_column, FileDiagnostic};
use serde::{Deserialize, Serialize};
use std::collections::BTreeMap;
use toml::Spanned;

/// The manifest's file name inside a behaviour's folder.
pub const MANIFEST: &str = "behaviour.toml";

#[derive(Clone, Debug, Default, Deserialize, Serialize, PartialEq)]
#[serde(deny_unknown_fields)]
pub struct Manifest {
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub description: Option<String>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub ring_period: Option<String>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub answer_timeout: Option<String>,
    /// How the machines share time: rounds of ringlets (the default), or each on its own task.
    #[serde(default, skip_serializing_if = "Schedule::is_rounds")]
    pub schedule: Schedule,
    /// How long `proclaim run` runs when not told (a behaviour that never ends by itself).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub run_for: Option<String>,
    /// A file of `[[module]]` entries: modules outside the behaviour (actuators, other
    /// programs), so the dependency diagram and `check` know who listens and who answers.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub dictionary: Option<String>,
    #[serde(default, rename = "machine", skip_serializing_if = "Vec::is_empty")]
    pub machines: Vec<MachineEntry>,
    #[serde(default, rename = "theory", skip_serializing_if = "Vec::is_empty")]
    pub theories: Vec<TheoryEntry>,
    #[serde(default, rename = "sensor", skip_serializing_if = "Vec::is_empty")]
    pub sensors: Vec<SensorEntry>,
    /// Prolog knowledge bases answering labels (`program_entries.rs`).
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub prolog: Vec<crate::program_entries::PrologEntry>,
    /// Programs answering labels over JSON lines (`program_entries.rs`).
    #[serde(default, rename = "expert", skip_serializing_if = "Vec::is_empty")]
    pub programs: Vec<crate::program_entries::ProgramEntry>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub impersonator: Option<ImpersonatorEntry>,
    #[serde(default, rename = "module", skip_serializing_if = "Vec::is_empty")]
    pub modules: Vec<ModuleEntry>,
    /// The robot's team: who it is in it and which types it shares (`team.rs` checks it).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub team: Option<TeamEntry>,
    /// What `proclaim verify` checks of the behaviour.
    #[serde(default, rename = "property", skip_serializing_if = "Vec::is_empty")]
    pub properties: Vec<PropertyEntry>,
    /// Types under subsumption: a higher-priority machine's posting holds the type for `hold`
    /// against lower ones (`subsumption.rs` checks the entries against the machines).
    #[serde(default, skip_serializing_if = "BTreeMap::is_empty")]
    pub suppress: BTreeMap<Spanned<String>, SuppressEntry>,
    /// Types posted from outside the machines that take only whole numbers of a range
    /// (`ranges.rs` reads and checks them).
    #[serde(default, skip_serializing_if = "BTreeMap::is_empty")]
    pub ranges: BTreeMap<Spanned<String>, Spanned<String>>,
}

/// `[team] name = "blue"`, `member = "robot1"`, `shared = ["ballDistance", "role"]`: the
/// robot's team, its own name in it (`run --member` overrides it) and the types whose postings
/// its teammates hear. Spanned, so a bad entry is reported at its place.
#[derive(Clone, Debug, Deserialize, Serialize, PartialEq)]
#[serde(deny_unknown_fields)]
pub struct TeamEntry {
    pub name: Spanned<String>,
    pub member: Spanned<String>,
    #[serde(default)]
    pub shared: Vec<Spanned<String>>,
    /// How many robots the team has: with it, `team.quorum` says whether the robot hears a
    /// majority of them.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub size: Option<Spanned<i64>>,
}

/// `[suppress] walk = { hold = "500ms" }`: how long a posting holds the type against lower
/// priorities. Spanned, so a bad entry is reported at its place.
#[derive(Clone, Debug, Deserialize, Serialize, PartialEq)]
#[serde(deny_unknown_fields)]
pub struct SuppressEntry {
    pub hold: Spanned<String>,
}

impl Manifest {
    /// The manifest as `behaviour.toml` text, after `comment` (each of its lines as a `#`
    /// comment): what `deps --launch` and `liveness` write, read back by `parse_manifest`.
    pub fn to_toml(&self, comment: &str) -> String {
        let mut out: String = comment.lines().map(|l| format!("# {l}\n")).collect();
        // Every field is a string, a number, a bool or a table of them: nothing fails here.
        out.push_str(&toml::to_string(self).unwrap_or_default());
        out
    }
}

/// How the machines of a behaviour share time (`docs/spec/behaviour.md` §3.1).
#[derive(Clone, Copy, Debug, Default, Deserialize, Serialize, PartialEq, Eq)]
#[serde(rename_all = "lowercase")]
pub enum Schedule {
    /// One ringlet per running machine per round, in manifest order, on one task: the same
    /// inputs give the same run.
    #[default]
    Rounds,
    /// Each machine on a task of its own, racing the others (for machines that share nothing).
    Concurrent,
}

impl Schedule {
    fn is_rounds(&self) -> bool {
        *self == Schedule::Rounds
    }
}

/// A module outside the behaviour: what it posts, reads and answers.
#[derive(Clone, Debug, Default, Deserialize, Serialize, PartialEq)]
#[serde(deny_unknown_fields)]
pub struct ModuleEntry {
    pub name: String,
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub posts: Vec<String>,
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub reads: Vec<String>,
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub answers: Vec<String>,
}

/// A dictionary file: only `[[module]]` entries.
#[derive(Clone, Debug, Default, Deserialize, PartialEq)]
#[serde(deny_unknown_fields)]
pub struct Dictionary {
    #[serde(default, rename = "module")]
    pub modules: Vec<ModuleEntry>,
}

#[derive(Clone, Debug, Deserialize, Serialize, PartialEq)]
#[serde(deny_unknown_fields)]
pub struct MachineEntry {
    pub file: String,
    /// Running from the start; `false` for a sub-machine another machine turns on.
    #[serde(default = "yes", skip_serializing_if = "is_true")]
    pub start: bool,
    /// Which machine, when the file holds several (Qfsm).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub name: Option<String>,
    /// Its subsumption layer: every posting it makes carries this priority, which decides
    /// only for the types of `[suppress]` (0, the bottom layer, by default).
    #[serde(default, skip_serializing_if = "is_zero")]
    pub priority: u32,
    /// The parameters of a machine that starts with the behaviour (`params = { side = 1 }`);
    /// a machine another one starts is given them by that start (`Dive: On(side = 1)`).
    #[serde(default, skip_serializing_if = "BTreeMap::is_empty")]
    pub params: BTreeMap<String, toml::Value>,
}

#[derive(Clone, Debug, Deserialize, Serialize, PartialEq)]
#[serde(deny_unknown_fields)]
pub struct TheoryEntry {
    pub file: String,
    /// The expert's name on the whiteboard (default: the theory's `name{}`, else the file stem).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub name: Option<String>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub mapping: Option<String>,
    /// Steps the search may take inside one attack cycle before an answer is undecided
    /// (answered false, with a warning); default 10,000,000.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub budget: Option<u64>,
}

#[derive(Clone, Debug, Deserialize, Serialize, PartialEq)]
#[serde(deny_unknown_fields)]
pub struct SensorEntry {
    pub kind: SensorKind,
    /// GameController: the UDP port (default 3838; an ephemeral loopback port with the
    /// simulator).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub port: Option<u16>,
    /// GameController: our team number (default: the first team of each packet).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub team: Option<u8>,
    /// GameController: our player number.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub player: Option<u8>,
    /// GameController: `true` plays the built-in short game to the receiver, a file name plays
    /// that game script, `false` listens for a real GameController.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub simulator: Option<Simulator>,
}

#[derive(Clone, Copy, Debug, Deserialize, Serialize, PartialEq, Eq)]
#[serde(rename_all = "snake_case")]
pub enum SensorKind {
    Gamecontroller,
    ChestButton,
    FootBumpers,
    Fall,
}

#[derive(Clone, Debug, Deserialize, Serialize, PartialEq, Eq)]
#[serde(untagged)]
pub enum Simulator {
    On(bool),
    Script(String),
}

#[derive(Clone, Debug, Deserialize, Serialize, PartialEq)]
#[serde(deny_unknown_fields)]
pub struct ImpersonatorEntry {
    pub script: String,
}

/// A property `proclaim verify` checks: a name and exactly one of `never`, `always`,
/// `reachable`, `eventually`, `always_eventually` (each an expression of the label language, read
/// by `proclaim-verify`) or `leads_to = [P, Q]`; a liveness property may assume `fair = "EXPR"`
/// (the environment makes EXPR true infinitely often).
#[derive(Clone, Debug, Deserialize, Serialize, PartialEq)]
#[serde(try_from = "RawProperty", into = "RawProperty")]
pub struct PropertyEntry {
    pub name: String,
    pub kind: PropertyKind,
    /// For `leads_to`, both expressions as `P ~> Q` (how the command line writes it).
    pub expression: String,
    pub fair: Option<String>,
}

/// What a property says of its expression over every reachable state (safety) or over every
/// infinite run (liveness).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum PropertyKind {
    Never,
    Always,
    Reachable,
    /// Every run reaches a state where it holds.
    Eventually,
    /// Every state where the first holds is followed by one where the second does.
    LeadsTo,
    /// Every run holds it again and again.
    AlwaysEventually,
}

impl PropertyKind {
    pub const ALL: [PropertyKind; 6] = [
        PropertyKind::Never,
        PropertyKind::Always,
        PropertyKind::Reachable,
        PropertyKind::Eventually,
        PropertyKind::LeadsTo,
        PropertyKind::AlwaysEventually,
    ];

    /// The key that declares it in the manifest.
    pub fn word(self) -> &'static str {
        match self {
            PropertyKind::Never => "never",
            PropertyKind::Always => "always",
            PropertyKind::Reachable => "reachable",
            PropertyKind::Eventually => "eventually",
            PropertyKind::LeadsTo => "leads_to",
            PropertyKind::AlwaysEventually => "always_eventually",
        }
    }

    /// The `verify` option that gives it on the command line.
    pub fn option(self) -> String {
        format!("--{}", self.word().replace('_', "-"))
    }

    /// Whether it speaks of infinite runs rather than of single states.
    pub fn is_liveness(self) -> bool {
        matches!(
            self,
            PropertyKind::Eventually | PropertyKind::LeadsTo | PropertyKind::AlwaysEventually
        )
    }
}

/// What separates a `leads_to` property's two expressions in its one-line form `P ~> Q`.
pub const LEADS_TO: &str = "~>";

/// A part of a text and the byte offset where it starts.
pub type Part<'a> = (usize, &'a str);

/// `P ~> Q` split at its `~>` (the first outside a quoted text), both sides trimmed, each with
/// the byte offset where it starts; `None` without one.
pub fn split_leads_to(text: &str) -> Option<(Part<'_>, Part<'_>)> {
    let mut quoted = false;
    let mut previous = None;
    for (i, c) in text.char_indices() {
        match c {
            '"' if previous != Some('\\') => quoted = !quoted,
            '>' if !quoted && previous == Some('~') => {
                let (left, right) = (&text[..i - 1], &text[i + 1..]);
                return Some((trimmed(left, 0), trimmed(right, i + 1)));
            }
            _ => {}
        }
        previous = Some(c);
    }
    None
}

/// `part` without its surrounding spaces, and where that starts when `part` starts at `at`.
fn trimmed(part: &str, at: usize) -> Part<'_> {
    (at + part.len() - part.trim_start().len(), part.trim())
}

/// `[[property]]` as written: the kinds' keys optional, so that none or two given is an
/// error at the table's place rather than serde's generic message.
#[derive(Clone, Debug, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
struct RawProperty {
    name: String,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    never: Option<String>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    always: Option<String>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    reachable: Option<String>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    eventually: Option<String>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    leads_to: Option<[String; 2]>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    always_eventually: Option<String>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    fair: Option<String>,
}

impl TryFrom<RawProperty> for PropertyEntry {
    type Error = String;

    fn try_from(raw: RawProperty) -> Result<PropertyEntry, String> {
        let given: Vec<(PropertyKind, String)> = [
            (PropertyKind::Never, raw.never),
            (PropertyKind::Always, raw.always),
            (PropertyKind::Reachable, raw.reachable),
            (PropertyKind::Eventually, raw.eventually),
            (
                PropertyKind::LeadsTo,
                raw.leads_to.map(|[p, q]| format!("{p} {LEADS_TO} {q}")),
            ),
            (PropertyKind::AlwaysEventually, raw.always_eventually),
        ]
        .into_iter()
        .filter_map(|(kind, e)| Some((kind, e?)))
        .collect();
        match <[_; 1]>::try_from(given) {
            Ok([(kind, _)]) if raw.fair.is_some() && !kind.is_liveness() => Err(format!(
                "property `{}`: `fair` is an assumption of a liveness property (eventually, leads_to, always_eventually), not of `{}`",
                raw.name,
                kind.word()
            )),
            Ok([(kind, expression)]) => Ok(PropertyEntry {
                name: raw.name,
                kind,
                expression,
                fair: raw.fair,
            }),
            Err(_) => Err(format!(
                "property `{}` needs exactly one of `never`, `always`, `reachable`, `eventually`, `leads_to`, `always_eventually`",
                raw.name
            )),
        }
    }
}

impl From<PropertyEntry> for RawProperty {
    fn from(p: PropertyEntry) -> RawProperty {
        let mut raw = RawProperty {
            name: p.name,
            never: None,
            always: None,
            reachable: None,
            eventually: None,
            leads_to: None,
            always_eventually: None,
            fair: p.fair,
        };
        let slot = match p.kind {
            PropertyKind::Never => &mut raw.never,
            PropertyKind::Always => &mut raw.always,
            PropertyKind::Reachable => &mut raw.reachable,
            PropertyKind::Eventually => &mut raw.eventually,
            PropertyKind::AlwaysEventually => &mut raw.always_eventually,
            PropertyKind::LeadsTo => {
                raw.leads_to = Some(match split_leads_to(&p.expression) {
                    Some(((_, left), (_, right))) => [left.to_string(), right.to_string()],
                    None => [p.expression, String::new()],
                });
                return raw;
            }
        };
        *slot = Some(p.expression);
        raw
    }
}

fn yes() -> bool {
    true
}

fn is_true(value: &bool) -> bool {
    *value
}

fn is_zero(value: &u32) -> bool {
    *value == 0
}

/// Reads a manifest, the text of `file`; an error says where and why.
pub fn parse_manifest(file: &str, text: &str) -> Result<Manifest, FileDiagnostic> {
    parse_toml(file, text)
}

/// Reads a dictionary of outside modules, the text of `file`; an error says where and why.
pub fn parse_dictionary(file: &str, text: &str) -> Result<Dictionary, FileDiagnostic> {
    parse_toml(file, text)
}

fn parse_toml<T: serde::de::DeserializeOwned>(file: &str, text: &str) -> Result<T, FileDiagnostic> {
    toml::from_str(text).map_err(|e| {
        let start = e.span().map_or(0, |s| s.start.min(text.len()));
        let (line, column) = line_column(text, start);
        FileDiagnostic::error(file, line, e.message()).at_column(column, text)
    })
}
