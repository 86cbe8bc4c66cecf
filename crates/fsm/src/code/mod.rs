//! gufsm's activity language ("SimpleC"): the expressions of labels and the statements of
//! activities, one language for both, as the Griffith team wrote them in Qfsm descriptions
//! (`currentTime = currentTime - 1; postv("walk", 100, yaw, yaw, 100);`) and transition labels
//! (`buttonPushed && !doorOpen && currentTime < 4`). Its grammar follows gufsm's
//! `LANGUAGE/SimpleCParser.g` and `SimpleCLexer.g`, widened where the team's files go beyond
//! them: floats, `* / %`, `<= >= !=`, unary minus, declarations with initial values.
//!
//! Parsing is pure and total over its input: text in, a tree or an error naming the column,
//! what was expected and what was found. Printing gives text that parses back to the same tree.

mod expr;
mod parse;
mod rename;
mod stmt;
mod token;

pub(crate) use token::LexError;

pub use expr::{BinOp, Expr, UnOp, TIME_TESTS};
pub use parse::{parse_expression, parse_statements, CodeError};
pub use stmt::{ForLoop, Statement, StatementKind, VarType};
