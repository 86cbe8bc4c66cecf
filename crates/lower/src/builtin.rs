//! What a call standing as a statement means, decoded in one place for everything that gives the
//! activity language a meaning: the runner runs it, the verifier explores it and writes it as
//! Promela. Each of them only says what its environment does with a posting, a print or a sleep.

use crate::arith::text;
use proclaim_board::Value;
use proclaim_fsm::control::Command;
use proclaim_fsm::Expr;

/// Where a built-in posts.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Target<'a> {
    /// The type this expression's text names (`post("ballSeen", 1)`, `start("Walk")`).
    Named(&'a Expr),
    /// A type of its own: `Say` for `say`, `Speech` for `speech`.
    Fixed(&'static str),
}

/// What a built-in posts or prints.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Content<'a> {
    /// The expression's value.
    Value(&'a Expr),
    /// The expression's value as an integer (a number is truncated toward zero; anything else
    /// is 0).
    Int(&'a Expr),
    /// The expressions' texts, the empty ones left out, joined by a space
    /// (`post("Say", "", "Hello")`).
    Joined(&'a [Expr]),
    /// The expressions' values as a list.
    List(&'a [Expr]),
    /// A control command's word (`On`, `Off`, `suspend`, ...).
    Command(Command),
    /// The expression's text.
    Text(&'a Expr),
    /// The name of the state the machine is in.
    StateName,
}

/// A call standing as a statement.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Builtin<'a> {
    /// A posting to the whiteboard.
    Post {
        to: Target<'a>,
        content: Content<'a>,
    },
    /// `print`, `print_int`, `print_fixed`, `print_state_name`: a line on the log and in the
    /// trace; nothing a machine reads.
    Print(Content<'a>),
    /// `msleep(ms)`, `sleep(s)`: the activity waits this long (milliseconds per unit).
    Sleep { amount: &'a Expr, ms_per_unit: f64 },
    /// Anything else: a function of the environment (a time test, arithmetic) or of the host.
    Other,
}

/// The meaning of the call `function(arguments)` standing as a statement.
pub fn builtin<'a>(function: &str, arguments: &'a [Expr]) -> Builtin<'a> {
    let post = |to, content| Builtin::Post { to, content };
    match (function, arguments) {
        ("post", [ty, value]) => post(Target::Named(ty), Content::Value(value)),
        ("post", [ty, parts @ ..]) if parts.len() == 2 => {
            post(Target::Named(ty), Content::Joined(parts))
        }
        ("post_int", [ty, value]) => post(Target::Named(ty), Content::Int(value)),
        ("postv" | "post_v", [ty, values @ ..]) if !values.is_empty() => {
            post(Target::Named(ty), Content::List(values))
        }
        (f, [ty]) if Command::from_function(f).is_some() => post(
            Target::Named(ty),
            Content::Command(Command::from_function(f).unwrap_or(Command::On)),
        ),
        ("say", [t]) => post(Target::Fixed("Say"), Content::Text(t)),
        ("speech", [t]) => post(Target::Fixed("Speech"), Content::Text(t)),
        ("say_state_name", []) => post(Target::Fixed("Say"), Content::StateName),
        ("speak_state_name", []) => post(Target::Fixed("Speech"), Content::StateName),
        ("print" | "print_int" | "print_fixed", [t]) => Builtin::Print(Content::Text(t)),
        ("print_state_name", []) => Builtin::Print(Content::StateName),
        ("msleep", [amount]) => Builtin::Sleep {
            amount,
            ms_per_unit: 1.0,
        },
        ("sleep", [amount]) => Builtin::Sleep {
            amount,
            ms_per_unit: 1000.0,
        },
        _ => Builtin::Other,
    }
}

impl Target<'_> {
    /// The type's name, `text` giving an expression's text.
    pub fn name(&self, text: impl FnOnce(&Expr) -> String) -> String {
        match self {
            Target::Named(e) => text(e),
            Target::Fixed(name) => (*name).to_string(),
        }
    }
}

impl Content<'_> {
    /// The value posted or printed, `value` giving an expression's value and `state` the name
    /// of the state the machine is in.
    pub fn value(&self, mut value: impl FnMut(&Expr) -> Value, state: &str) -> Value {
        match self {
            Content::Value(e) => value(e),
            Content::Int(e) => match value(e) {
                Value::Int(i) => Value::Int(i),
                other => Value::Int(other.as_f64().unwrap_or(0.0) as i64),
            },
            Content::Joined(parts) => Value::Str(
                parts
                    .iter()
                    .map(|p| text(&value(p)))
                    .filter(|t| !t.is_empty())
                    .collect::<Vec<_>>()
                    .join(" "),
            ),
            Content::List(values) => Value::List(values.iter().map(value).collect()),
            Content::Command(command) => Value::Str(command.word().into()),
            Content::Text(e) => Value::Str(text(&value(e))),
            Content::StateName => Value::Str(state.to_string()),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn call(source: &str) -> (String, Vec<Expr>) {
        match proclaim_fsm::code::parse_expression(source) {
            Ok(Expr::Call {
                function,
                arguments,
                ..
            }) => (function, arguments),
            other => panic!("{source} is not a call: {other:?}"),
        }
    }

    /// Each call's meaning, with its arguments' texts standing for their values.
    fn check(source: &str, expect: &str) {
        let (function, arguments) = call(source);
        let value = |e: &Expr| Value::parse(&e.to_string());
        let shown = match builtin(&function, &arguments) {
            Builtin::Post { to, content } => format!(
                "post {} {}",
                to.name(|e| e.to_string()),
                text(&content.value(value, "S"))
            ),
            Builtin::Print(content) => format!("print {}", text(&content.value(value, "S"))),
            Builtin::Sleep {
                amount,
                ms_per_unit,
            } => format!("sleep {amount} x {ms_per_unit} ms"),
            Builtin::Other => "other".into(),
        };
        assert_eq!(shown, expect, "{source}");
    }

    #[test]
    fn every_builtin_means_what_the_runner_does() {
        check("post(t, v)", "post t v");
        check("post(t, a, b)", "post t a b");
        check("post_int(t, 2.5)", "post t 2");
        check("postv(t, 1, b)", "post t 1 b");
        check("start(Walk)", "post Walk On");
        check("suspend(Walk)", "post Walk suspend");
        check("say(hello)", "post Say hello");
        check("speech(hello)", "post Speech hello");
        check("say_state_name()", "post Say S");
        check("speak_state_name()", "post Speech S");
        check("print_int(x)", "print x");
        check("print_state_name()", "print S");
        check("msleep(5)", "sleep 5 x 1 ms");
        check("sleep(2)", "sleep 2 x 1000 ms");
        check("post(t)", "other");
        check("postv(t)", "other");
        check("timeout(1)", "other");
        check("kick()", "other");
    }
}
