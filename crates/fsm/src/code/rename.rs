//! Names replaced where they are read or written: how a machine's parameters and the outcomes
//! of the machines it starts are lowered to the globals they become (`interface.rs`).

use super::{Expr, Statement};

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
