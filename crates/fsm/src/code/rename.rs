//! Names replaced where they are read or written: how a machine's parameters and the outcomes
//! of the machines it starts are lowered to the globals they become (`interface.rs`); and calls
//! replaced, as a chart's `in(STATE)` is by what its flat state says (`native/flatten.rs`).

use super::{BinOp, Expr, Statement};

impl Expr {
    /// Replaces every name read for which `to` gives a new one.
    pub fn rename(&mut self, to: &mut impl FnMut(&str) -> Option<String>) {
        match self {
            Expr::Name(n) => {
                if let Some(new) = to(n) {
                    *n = new;
                }
            }
            Expr::Unary { operand, .. } => operand.rename(to),
            Expr::Binary { left, right, .. } => {
                left.rename(to);
                right.rename(to);
            }
            Expr::Call { arguments, .. } => arguments.iter_mut().for_each(|a| a.rename(to)),
            Expr::Bool(_) | Expr::Int(_) | Expr::Float(_) | Expr::Str(_) | Expr::Duration(_) => {}
        }
    }
}

impl Expr {
    /// Replaces every call for which `to` gives an expression (the calls inside one it
    /// replaces are not visited; those inside one it keeps are).
    pub fn replace_calls(&mut self, to: &mut impl FnMut(&str, &[Expr]) -> Option<Expr>) {
        match self {
            Expr::Call {
                function,
                arguments,
                ..
            } => match to(function, arguments) {
                Some(new) => *self = new,
                None => arguments.iter_mut().for_each(|a| a.replace_calls(to)),
            },
            Expr::Unary { operand, .. } => operand.replace_calls(to),
            Expr::Binary { left, right, .. } => {
                left.replace_calls(to);
                right.replace_calls(to);
            }
            Expr::Name(_)
            | Expr::Bool(_)
            | Expr::Int(_)
            | Expr::Float(_)
            | Expr::Str(_)
            | Expr::Duration(_) => {}
        }
    }

    /// The expression with its constant truths folded away (`TRUE && x` is `x`, `!FALSE` is
    /// `TRUE`), as after [`Expr::replace_calls`] put them in.
    pub fn folded_truths(self) -> Expr {
        match self {
            Expr::Unary {
                op: super::UnOp::Not,
                operand,
            } => match operand.folded_truths() {
                Expr::Bool(b) => Expr::Bool(!b),
                other => Expr::negation(other),
            },
            Expr::Binary { op, left, right } if matches!(op, BinOp::And | BinOp::Or) => {
                let (left, right) = (left.folded_truths(), right.folded_truths());
                let and = op == BinOp::And;
                match (&left, &right) {
                    // The side that decides: `FALSE && x`, `TRUE || x`.
                    (Expr::Bool(b), _) | (_, Expr::Bool(b)) if *b != and => Expr::Bool(*b),
                    (Expr::Bool(_), _) => right,
                    (_, Expr::Bool(_)) => left,
                    _ => Expr::binary(op, left, right),
                }
            }
            other => other,
        }
    }
}

impl Statement {
    /// Replaces every name read or assigned, in this statement and those inside it, for which
    /// `to` gives a new one (a declaration's or an `extern`'s name is left: it names no value
    /// read).
    pub fn rename(&mut self, to: &mut impl FnMut(&str) -> Option<String>) {
        match self {
            Statement::Declare { value, .. } => {
                if let Some(v) = value {
                    v.rename(to);
                }
            }
            Statement::Extern { .. } => {}
            Statement::Assign { name, value } => {
                if let Some(new) = to(name) {
                    *name = new;
                }
                value.rename(to);
            }
            Statement::Expr(e) => e.rename(to),
            Statement::Block(body) => body.iter_mut().for_each(|s| s.rename(to)),
            Statement::For {
                init,
                condition,
                step,
                body,
            } => {
                for s in init.iter_mut().chain(step.iter_mut()) {
                    s.rename(to);
                }
                if let Some(c) = condition {
                    c.rename(to);
                }
                body.rename(to);
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use crate::code::parse_statements;

    #[test]
    fn reads_and_assignments_are_renamed_declarations_are_not() {
        let mut parsed = parse_statements("int side; x = side + f(side); side = 2;").unwrap();
        for s in &mut parsed {
            s.rename(&mut |n| (n == "side").then(|| "Dive_side".to_string()));
        }
        let text: Vec<String> = parsed.iter().map(ToString::to_string).collect();
        assert_eq!(
            text,
            [
                "int side;",
                "x = Dive_side + f(Dive_side);",
                "Dive_side = 2;"
            ]
        );
    }
}
