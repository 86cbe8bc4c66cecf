//! Transition labels: expressions of the activity language ([`crate::code`]). `TRUE`, atoms,
//! `~a` or `!a`, `&&`, `||`, parentheses, numbers (non-zero is true), arithmetic and
//! comparisons over variables and whiteboard values, and the time tests `timeout(µs)`,
//! `after(s)` and `after_ms(ms)` (time since the state was entered); a robot of a team also reads
//! its teammates (`robot2.ballDistance`, `team.argmin(ballDistance) == me`: `team.rs`).

pub use crate::code::TIME_TESTS;
use crate::code::{parse_expression, CodeError, Expr};

/// A label is an expression whose value is read as true or false.
pub type Label = Expr;

/// Where and why a label did not parse (`offset` in bytes into the label).
pub type LabelError = CodeError;

/// Parses a label. An empty label is `TRUE` (Qfsm writes no inputs for an unconditional
/// transition).
pub fn parse_label(text: &str) -> Result<Label, LabelError> {
    if text.trim().is_empty() {
        return Ok(Expr::TRUE);
    }
    parse_expression(text)
}
