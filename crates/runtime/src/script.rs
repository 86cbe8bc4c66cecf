//! The impersonator's script: what to answer for which atom, from the start, at a time, or at a
//! query step. One statement a line, `#` comments:
//!
//! ```text
//! readyReceived = false          # from the start
//! at 2s readyReceived = true     # two seconds after the start
//! at 500ms setReceived = yes     # true/false, yes/no, on/off or 1/0
//! step 3: playingReceived = true # when the third query arrives, before it is answered
//! at 1s ballRR = -120            # a number (`1` and `0` are truths; `+1` is the number)
//! at 2s mode = "kick"            # text, in double quotes
//! ```
//!
//! A sensor posts numbers and text, so a script can too: a counterexample that needs
//! `ballRR < 0` must be a script that replays. A query is answered with the value's truth.

use crate::{code_lines, LineError, LineErrors};
use std::time::Duration;

#[derive(Clone, Debug, PartialEq, Eq)]
pub enum When {
    Start,
    At(Duration),
    /// The n-th query (1-based) the impersonator receives.
    Step(u64),
}

/// What a script line sets an atom to.
#[derive(Clone, Debug, PartialEq)]
pub enum ScriptValue {
    Truth(bool),
    Whole(i64),
    Fraction(f64),
    Text(String),
}

impl ScriptValue {
    /// The truth value, when the line set one.
    pub fn as_truth(&self) -> Option<bool> {
        match self {
            ScriptValue::Truth(b) => Some(*b),
            _ => None,
        }
    }
}

impl From<bool> for ScriptValue {
    fn from(b: bool) -> ScriptValue {
        ScriptValue::Truth(b)
    }
}

impl std::fmt::Display for ScriptValue {
    /// As a script writes it, so that it reads back the same.
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            ScriptValue::Truth(b) => write!(f, "{b}"),
            // `1` and `0` are truth words; `+1` is the number.
            ScriptValue::Whole(i @ (0 | 1)) => write!(f, "+{i}"),
            ScriptValue::Whole(i) => write!(f, "{i}"),
            // `{:?}` keeps the point (`2.0`), so a fraction reads back as one.
            ScriptValue::Fraction(x) => write!(f, "{x:?}"),
            ScriptValue::Text(s) => write!(f, "{}", quote(s)),
        }
    }
}

/// Text in double quotes, `\"` and `\\` escaped.
fn quote(s: &str) -> String {
    format!("\"{}\"", s.replace('\\', "\\\\").replace('"', "\\\""))
}

#[derive(Clone, Debug, PartialEq)]
pub struct ScriptStep {
    pub when: When,
    pub atom: String,
    pub value: ScriptValue,
    pub line: usize,
}

#[derive(Clone, Debug, Default, PartialEq)]
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
fn script_step(code: &str) -> Result<(When, &str, ScriptValue), String> {
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
                "`{time}` is not a time up to {}s; write `at 2s` or `at 500ms`",
                crate::LONGEST_DURATION.as_secs()
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

/// `atom = value`, the value a truth word, a number or quoted text.
fn assignment_of(assignment: &str) -> Result<(&str, ScriptValue), String> {
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
    let Some(value) = script_value(value) else {
        let value = value.trim();
        return Err(if value.starts_with('=') {
            format!(
                "write `{atom} = {}`, with one `=`",
                value.trim_start_matches('=').trim()
            )
        } else if value.starts_with('"') {
            format!("`{value}` is not closed: text ends with `\"`")
        } else {
            format!("`{value}` is not a value: write true or false (or yes/no, on/off, 1/0), a number, or text in double quotes (`\"{value}\"`)")
        });
    };
    Ok((atom, value))
}

/// A truth word, a number, or text in double quotes.
fn script_value(text: &str) -> Option<ScriptValue> {
    let text = text.trim();
    if let Some(truth) = truth_word(text) {
        return Some(ScriptValue::Truth(truth));
    }
    if let Some(quoted) = text.strip_prefix('"') {
        return unquote(quoted).map(ScriptValue::Text);
    }
    if let Ok(i) = text.parse::<i64>() {
        return Some(ScriptValue::Whole(i));
    }
    // Rust also reads `inf` and `NaN` as numbers; a sensor's reading is a finite one.
    match text.parse::<f64>() {
        Ok(x)
            if x.is_finite()
                && text.starts_with(|c: char| {
                    c.is_ascii_digit() || c == '-' || c == '+' || c == '.'
                }) =>
        {
            Some(ScriptValue::Fraction(x))
        }
        _ => None,
    }
}

/// The text of `rest` up to its closing quote (which must end the value), `\"` and `\\`
/// read as one character.
fn unquote(rest: &str) -> Option<String> {
    let mut out = String::new();
    let mut chars = rest.chars();
    while let Some(c) = chars.next() {
        match c {
            '"' => return chars.as_str().trim().is_empty().then_some(out),
            '\\' => out.push(chars.next()?),
            c => out.push(c),
        }
    }
    None
}

#[cfg(test)]
mod tests {
    use super::*;

    fn check(line: &str, expect: Result<ScriptValue, &str>) {
        let got = parse_script(line).map(|s| s.steps[0].value.clone());
        match (got, expect) {
            (Ok(v), Ok(e)) => assert_eq!(v, e, "{line}"),
            (Err(errors), Err(e)) => {
                let message = &errors.0[0].message;
                assert!(message.contains(e), "{line}: {message}");
            }
            (got, expect) => panic!("{line}: {got:?}, expected {expect:?}"),
        }
    }

    #[test]
    fn a_script_sets_truths_numbers_and_text() {
        check("a = yes", Ok(ScriptValue::Truth(true)));
        check("a = 0", Ok(ScriptValue::Truth(false)));
        check("at 1s ballRR = -120", Ok(ScriptValue::Whole(-120)));
        check("charge = 15", Ok(ScriptValue::Whole(15)));
        check("x = 2.5", Ok(ScriptValue::Fraction(2.5)));
        check("x = -0.5", Ok(ScriptValue::Fraction(-0.5)));
        check("mode = \"kick\"", Ok(ScriptValue::Text("kick".into())));
        check(
            "say = \"a \\\"b\\\" c\"",
            Ok(ScriptValue::Text("a \"b\" c".into())),
        );
        check("mode = kick", Err("`kick` is not a value"));
        check("mode = \"kick", Err("is not closed"));
        check("x = inf", Err("is not a value"));
        check("x = NaN", Err("is not a value"));
        check("x == 3", Err("with one `=`"));
    }

    #[test]
    fn a_time_too_long_for_any_clock_is_an_error_not_a_panic() {
        check("at 1000000000s a = yes", Ok(ScriptValue::Truth(true)));
        for time in [
            "18446744073709551616s",
            "1e300s",
            "1000000001s",
            "-1s",
            "NaNs",
        ] {
            check(
                &format!("at {time} a = yes"),
                Err("is not a time up to 1000000000s"),
            );
        }
    }

    #[test]
    fn values_print_as_a_script_reads_them() {
        for v in [
            ScriptValue::Truth(false),
            ScriptValue::Whole(-7),
            ScriptValue::Whole(1),
            ScriptValue::Whole(0),
            ScriptValue::Fraction(2.0),
            ScriptValue::Fraction(-0.25),
            ScriptValue::Text("say \"hi\" \\ there".into()),
        ] {
            let line = format!("at 1s a = {v}");
            check(&line, Ok(v));
        }
    }
}
