//! What can go wrong in this crate's calls, each variant saying what and where; the
//! binary turns them into its messages and exit codes.

use proclaim_syntax::{FileDiagnostic, LineErrors};
use std::fmt;

#[derive(Debug)]
pub enum BehaviourError {
    /// The behaviour's files have problems, each at its place.
    Files(Vec<FileDiagnostic>),
    /// The impersonator script has problems, each at its line.
    Script(LineErrors),
    /// A socket a sensor wrapper needs could not be opened or has no address.
    Socket { what: String, error: std::io::Error },
    /// No async runtime could be made for a run on a clock of its own.
    Runtime(std::io::Error),
    /// A line of a JSON-lines trace is no event.
    TraceLine { line: usize, error: String },
    /// A checkpoint was asked of a run whose state is not all its own.
    Checkpoint(String),
    /// A checkpoint does not fit the behaviour taking it up: each reason.
    Resume(Vec<String>),
    /// A recording cannot be branched where asked, or not on this run.
    Branch(String),
    /// The behaviour has no module (or machine) of that name.
    NoSuch {
        kind: &'static str,
        name: String,
        known: Vec<String>,
    },
}

impl fmt::Display for BehaviourError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            BehaviourError::Files(problems) => {
                let lines: Vec<String> = problems.iter().map(ToString::to_string).collect();
                f.write_str(&lines.join("\n"))
            }
            BehaviourError::Script(errors) => {
                let lines: Vec<String> = errors.iter().map(|e| format!("script: {e}")).collect();
                f.write_str(&lines.join("\n"))
            }
            BehaviourError::Socket { what, error } => write!(f, "{what}: {error}"),
            BehaviourError::Runtime(error) => write!(f, "no async runtime: {error}"),
            BehaviourError::TraceLine { line, error } => {
                write!(f, "line {line}: not a trace event: {error}")
            }
            BehaviourError::Checkpoint(why) => write!(f, "no checkpoint can be taken: {why}"),
            BehaviourError::Resume(why) => {
                write!(f, "the checkpoint cannot be taken up: {}", why.join("; "))
            }
            BehaviourError::Branch(why) => write!(f, "no branch: {why}"),
            BehaviourError::NoSuch { kind, name, known } => {
                let plural = if *kind == "module" {
                    "the behaviour has"
                } else {
                    "the behaviour's machines are"
                };
                write!(f, "no {kind} `{name}`; {plural} {}", known.join(", "))
            }
        }
    }
}

impl std::error::Error for BehaviourError {
    fn source(&self) -> Option<&(dyn std::error::Error + 'static)> {
        match self {
            BehaviourError::Socket { error, .. } | BehaviourError::Runtime(error) => Some(error),
            _ => None,
        }
    }
}
