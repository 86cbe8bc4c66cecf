//! A control command posted with arguments, `Dive: restart(side = -1, power = kick + 1)`: how
//! a start gives a machine its parameters (`docs/spec/behaviour.md` §3.3).

use crate::code::{parse_expression, Expr};
use crate::control::Command;
use crate::interface::is_name;

/// A control command as posted with its arguments: `On(side = 1, power = kick + 1)`.
#[derive(Clone, Debug, PartialEq)]
pub struct Start {
    pub command: Command,
    pub arguments: Vec<(String, Expr)>,
}

/// Reads a posting's content as a command with arguments: `None` when it is not one (no
/// `(` after a command word: plain content, or a command alone), else the command or why its
/// arguments cannot be read.
pub fn start_of(content: &str) -> Option<Result<Start, String>> {
    let (word, rest) = content.split_once('(')?;
    let command = Command::parse(word)?;
    let Some(inner) = rest.trim_end().strip_suffix(')') else {
        return Some(Err(format!(
            "`{content}`: the arguments of `{word}` end with `)`",
            word = word.trim()
        )));
    };
    let mut arguments: Vec<(String, Expr)> = Vec::new();
    for part in split_arguments(inner)
        .into_iter()
        .filter(|p| !p.trim().is_empty())
    {
        let Some((name, value)) = split_assignment(part) else {
            return Some(Err(format!(
                "`{}`: an argument is `name = value`",
                part.trim()
            )));
        };
        if value.trim().is_empty() {
            return Some(Err(format!("`{name} =` gives `{name}` no value")));
        }
        let value = match parse_expression(value) {
            Ok(v) => v,
            Err(e) => return Some(Err(format!("`{}`: {}", value.trim(), e.message))),
        };
        if arguments.iter().any(|(n, _)| *n == name) {
            return Some(Err(format!("`{name}` is given twice")));
        }
        arguments.push((name, value));
    }
    Some(Ok(Start { command, arguments }))
}

/// The arguments between commas outside parentheses and quotes.
fn split_arguments(text: &str) -> Vec<&str> {
    let (mut parts, mut depth, mut quoted, mut from) = (Vec::new(), 0i32, false, 0);
    let mut escaped = false;
    for (i, c) in text.char_indices() {
        match c {
            _ if escaped => escaped = false,
            '\\' if quoted => escaped = true,
            '"' => quoted = !quoted,
            '(' if !quoted => depth += 1,
            ')' if !quoted => depth -= 1,
            ',' if !quoted && depth == 0 => {
                parts.push(&text[from..i]);
                from = i + 1;
            }
            _ => {}
        }
    }
    parts.push(&text[from..]);
    parts
}

/// `name = value`: the name (a plain identifier) and the value's text.
fn split_assignment(part: &str) -> Option<(String, &str)> {
    let at = part.find('=')?;
    if part[at + 1..].starts_with('=') {
        return None;
    }
    let name = part[..at].trim();
    is_name(name).then(|| (name.to_string(), &part[at + 1..]))
}

#[cfg(test)]
mod tests {
    use super::*;

    fn check(content: &str, expect: &str) {
        let got = match start_of(content) {
            None => "not a start".to_string(),
            Some(Err(e)) => format!("error: {e}"),
            Some(Ok(s)) => {
                let args: Vec<String> = s
                    .arguments
                    .iter()
                    .map(|(n, v)| format!("{n} := {v}"))
                    .collect();
                format!("{} {}", s.command, args.join("; "))
            }
        };
        assert_eq!(got, expect, "{content}");
    }

    #[test]
    fn a_start_reads_its_arguments_and_says_what_is_wrong_with_them() {
        check("On", "not a start");
        check("ChestBoard Red (blink)", "not a start");
        check("On(side = 1)", "On side := 1");
        check(
            "restart(side = f(a, b), name = \"x, (y\")",
            "restart side := f(a, b); name := \"x, (y\"",
        );
        check("On()", "On ");
        check(
            "On(side == 1)",
            "error: `side == 1`: an argument is `name = value`",
        );
        check("On(side = )", "error: `side =` gives `side` no value");
        check(
            "On(side = 1 +)",
            "error: `1 +`: expected a name, a number, a string, `(`, `!` or `-`, found the end",
        );
        check(
            "On(side = 1",
            "error: `On(side = 1`: the arguments of `On` end with `)`",
        );
        check("On(a = 1, a = 2)", "error: `a` is given twice");
    }
}
