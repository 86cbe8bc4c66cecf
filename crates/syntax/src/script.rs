//! The impersonator's script: what to answer for which atom, from the start, at a time, or at a
//! query step. One statement a line, `#` comments:
//!
//! ```text
//! readyReceived = false          # from the start
//! at 2s readyReceived = true     # two seconds after the start
//! at 500ms setReceived = yes     # true/false, yes/no, on/off or 1/0
//! step 3: playingReceived = true # when the third query arrives, before it is answered
//! ```

use crate::{code_lines, LineError, LineErrors};
use std::time::Duration;

#[derive(Clone, Debug, PartialEq, Eq)]
pub enum When {
    Start,
    At(Duration),
    /// The n-th query (1-based) the impersonator receives.
    Step(u64),
}

#[derive(Clone, Debug, PartialEq, Eq)]
pub struct ScriptStep {
    pub when: When,
    pub atom: String,
    pub value: bool,
    pub line: usize,
}

#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct Script {
    pub steps: Vec<ScriptStep>,
}

impl Script {
    /// Every atom the script speaks of, in first-mention order.
    pub fn atoms(&self) -> Vec<String> {
        let mut atoms: Vec<String> = Vec::new();
        for s in &self.steps {
            if !atoms.contains(&s.atom) {
                atoms.push(s.atom.clone());
            }
        }
        atoms
    }
}

/// A truth value as a script may write it.
fn truth_word(text: &str) -> Option<bool> {
    match text.trim().to_ascii_lowercase().as_str() {
        "true" | "yes" | "on" | "1" => Some(true),
        "false" | "no" | "off" | "0" => Some(false),
        _ => None,
    }
}

/// Parses a script; every bad line is reported.
pub fn parse_script(text: &str) -> Result<Script, LineErrors> {
    let mut steps = Vec::new();
    let mut errors = Vec::new();
    for (line, code) in code_lines(text) {
        match script_step(code) {
            Ok((when, atom, value)) => steps.push(ScriptStep {
                when,
                atom: atom.to_string(),
                value,
                line,
            }),
            Err(message) => errors.push(LineError { line, message }),
        }
    }
    if errors.is_empty() {
        Ok(Script { steps })
    } else {
        Err(LineErrors(errors))
    }
}

/// One line of a script: when, and which atom becomes what; or why the line is not one.
fn script_step(code: &str) -> Result<(When, &str, bool), String> {
    let (when, assignment) = when_of(code)?;
    let (atom, value) = assignment_of(assignment)?;
    Ok((when, atom, value))
}

/// The line's time (`at 2s`, `step 3:`, or at the start) and the assignment after it.
fn when_of(code: &str) -> Result<(When, &str), String> {
    if let Some(rest) = code.strip_prefix("at ") {
        let rest = rest.trim_start();
        let (time, assignment) = rest.split_once(char::is_whitespace).unwrap_or((rest, ""));
        match crate::parse_duration(time) {
            Some(d) => Ok((When::At(d), assignment)),
            None => Err(format!(
                "`{time}` is not a time; write `at 2s` or `at 500ms`"
            )),
        }
    } else if let Some(rest) = code.strip_prefix("step ") {
        let Some((n, assignment)) = rest.split_once(':') else {
            return Err("expected `step N: atom = value`".into());
        };
        match n.trim().parse::<u64>() {
            Ok(n) if n > 0 => Ok((When::Step(n), assignment)),
            _ => Err(format!("`{}` is not a step number (1, 2, …)", n.trim())),
        }
    } else {
        Ok((When::Start, code))
    }
}

/// `atom = value`, the value a truth word.
fn assignment_of(assignment: &str) -> Result<(&str, bool), String> {
    let Some((atom, value)) = assignment.split_once('=') else {
        return Err(format!(
            "expected `atom = value`, found `{}`",
            assignment.trim()
        ));
    };
    let atom = atom.trim();
    if atom.is_empty()
        || !atom
            .chars()
            .all(|c| c.is_alphanumeric() || c == '_' || c == '~')
    {
        return Err(format!("`{atom}` is not an atom"));
    }
    if value.trim().is_empty() {
        return Err(format!("`{atom}` has no value"));
    }
    let Some(truth) = truth_word(value) else {
        let value = value.trim();
        return Err(if value.starts_with('=') {
            format!(
                "write `{atom} = {}`, with one `=`",
                value.trim_start_matches('=').trim()
            )
        } else {
            format!("`{value}` is not a truth value: write true or false (or yes/no, on/off, 1/0)")
        });
    };
    Ok((atom, truth))
}
