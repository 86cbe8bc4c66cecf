//! The manifest's sections for experts that are other programs: `[[prolog]]`, a knowledge base
//! SWI-Prolog proves, and `[[expert]]`, any command speaking the JSON-lines protocol.
//!
//! ```toml
//! [[prolog]]
//! file = "offside.pl"                  # a label `L` holds when the goal `L` succeeds
//! answers = ["offside"]
//! inputs = ["behindBall", "inOwnHalf"] # each visible as the fact value(Type, Value)
//! time_limit = "200ms"                 # optional: a proof past it is an error (false)
//! name = "referee"                     # optional: the file's stem
//!
//! [[expert]]
//! command = ["python3", "ball.py"]     # run in the behaviour's folder
//! answers = ["ballNear"]
//! inputs = ["ballDistance"]
//! name = "ball"                        # optional: the last argument's stem
//! folder = "tools"                     # optional: where it runs, from the manifest's folder
//! ```

use serde::{Deserialize, Serialize};

#[derive(Clone, Debug, Deserialize, Serialize, PartialEq)]
#[serde(deny_unknown_fields)]
pub struct PrologEntry {
    pub file: String,
    /// The labels it answers, each a goal of the knowledge base.
    pub answers: Vec<String>,
    /// The whiteboard types it sees, each as the fact `value(Type, Value)`.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub inputs: Vec<String>,
    /// How long one proof may take (default 200ms).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub time_limit: Option<String>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub name: Option<String>,
}

#[derive(Clone, Debug, Deserialize, Serialize, PartialEq)]
#[serde(deny_unknown_fields)]
pub struct ProgramEntry {
    /// The program and its arguments, run in the behaviour's folder.
    pub command: Vec<String>,
    pub answers: Vec<String>,
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub inputs: Vec<String>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub name: Option<String>,
    /// Where it runs, relative to the manifest's folder (default: that folder).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub folder: Option<String>,
}
