//! Proving a label: atoms by the query protocol, `timeout()` against the time in the state,
//! comparisons against whiteboard values.

use crate::event::Answerer;
use proclaim_board::{QueryOutcome, Whiteboard};
use proclaim_fsm::{CmpOp, Label, Operand};
use std::time::Duration;

/// Where a label is proved: the board, who asks, how long the state has been active.
pub(crate) struct Context<'a> {
    pub board: &'a Whiteboard,
    pub module: &'a str,
    pub in_state: Duration,
    pub answer_timeout: Duration,
    pub answered: &'a mut Vec<(String, bool, Answerer)>,
}

pub(crate) fn value(board: &Whiteboard, operand: &Operand) -> Option<f64> {
    match operand {
        Operand::Number(n) => Some(*n),
        Operand::Value(name) => board.latest(name)?.value.as_f64(),
        Operand::Call { function, argument } => {
            let x = value(board, argument)?;
            Some(match function.as_str() {
                "abs" => x.abs(),
                "sqrt" => x.sqrt(),
                "atan" => x.atan(),
                "sin" => x.sin(),
                "cos" => x.cos(),
                "tan" => x.tan(),
                _ => return None,
            })
        }
        Operand::Arith { left, op, right } => {
            let (l, r) = (value(board, left)?, value(board, right)?);
            Some(match op {
                '+' => l + r,
                '-' => l - r,
                '*' => l * r,
                '/' => l / r,
                _ => return None,
            })
        }
    }
}

/// Proves a label; `And` and `Or` stop at the first answer that decides them, as the original
/// interpreter asked its experts one label at a time.
pub(crate) fn prove<'a>(
    label: &'a Label,
    cx: &'a mut Context<'_>,
) -> std::pin::Pin<Box<dyn std::future::Future<Output = bool> + Send + 'a>> {
    Box::pin(async move {
        match label {
            Label::True => true,
            Label::False => false,
            Label::Atom(atom) => {
                let outcome = cx.board.query(cx.module, atom, cx.answer_timeout).await;
                let (value, by) = match &outcome {
                    QueryOutcome::Answered { value, by, .. } => {
                        (*value, Answerer::Expert(by.to_string()))
                    }
                    QueryOutcome::TimedOut => (false, Answerer::TimedOut),
                    // No expert, but a module posts it as a state (`PlacerIsRunning`, a
                    // sensor value): its current value is the answer.
                    QueryOutcome::NoExpert => match cx.board.latest(atom) {
                        Some(m) => (m.value.truthy(), Answerer::Posted(m.module.to_string())),
                        None => (false, Answerer::NoExpert),
                    },
                };
                cx.answered.push((atom.clone(), value, by));
                value
            }
            Label::Not(inner) => !prove(inner, cx).await,
            Label::And(parts) => {
                for p in parts {
                    if !prove(p, cx).await {
                        return false;
                    }
                }
                true
            }
            Label::Or(parts) => {
                for p in parts {
                    if prove(p, cx).await {
                        return true;
                    }
                }
                false
            }
            Label::Timeout(limit) => {
                value(cx.board, limit).is_some_and(|us| cx.in_state.as_secs_f64() * 1e6 >= us)
            }
            Label::Compare { left, op, right } => {
                match (value(cx.board, left), value(cx.board, right)) {
                    (Some(l), Some(r)) => match op {
                        CmpOp::Eq => l == r,
                        CmpOp::Ne => l != r,
                        CmpOp::Lt => l < r,
                        CmpOp::Le => l <= r,
                        CmpOp::Gt => l > r,
                        CmpOp::Ge => l >= r,
                    },
                    // A value never posted makes the comparison false.
                    _ => false,
                }
            }
        }
    })
}

/// The message types a label reads: a post of any of them may change its answer.
pub(crate) fn dependencies(label: &Label, out: &mut Vec<String>) {
    fn operand(o: &Operand, out: &mut Vec<String>) {
        match o {
            Operand::Value(v) => out.push(v.clone()),
            Operand::Call { argument, .. } => operand(argument, out),
            Operand::Arith { left, right, .. } => {
                operand(left, out);
                operand(right, out);
            }
            Operand::Number(_) => {}
        }
    }
    match label {
        Label::Atom(a) => out.push(a.clone()),
        Label::Not(l) => dependencies(l, out),
        Label::And(ls) | Label::Or(ls) => ls.iter().for_each(|l| dependencies(l, out)),
        Label::Compare { left, right, .. } => {
            operand(left, out);
            operand(right, out);
        }
        Label::Timeout(t) => operand(t, out),
        Label::True | Label::False => {}
    }
}
