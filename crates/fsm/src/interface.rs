//! What a machine offers the machines that start it (`docs/spec/behaviour.md` §3.3): the
//! parameters a start gives it and the outcomes its final states announce, each lowered to a
//! global of the behaviour named after the machine, so every back end runs them as the
//! globals it already runs.

use crate::code::{Expr, VarType};

/// A machine's parameters and outcomes, as declared (`param side: int`, `outcome saved`).
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Interface {
    pub params: Vec<Param>,
    pub outcomes: Vec<DeclaredOutcome>,
}

#[derive(Clone, Debug, PartialEq)]
pub struct Param {
    pub name: String,
    pub ty: VarType,
    pub line: usize,
}

#[derive(Clone, Debug, PartialEq)]
pub struct DeclaredOutcome {
    pub name: String,
    pub line: usize,
}

impl Interface {
    pub fn is_empty(&self) -> bool {
        self.params.is_empty() && self.outcomes.is_empty()
    }

    pub fn param(&self, name: &str) -> Option<&Param> {
        self.params.iter().find(|p| p.name == name)
    }

    pub fn outcome(&self, name: &str) -> Option<&DeclaredOutcome> {
        self.outcomes.iter().find(|o| o.name == name)
    }

    pub fn outcome_names(&self) -> Vec<&str> {
        self.outcomes.iter().map(|o| o.name.as_str()).collect()
    }

    /// The parameters `given` leaves out, in declared order.
    pub fn missing_from(&self, given: &[(String, Expr)]) -> Vec<&str> {
        (self.params.iter().map(|p| p.name.as_str()))
            .filter(|p| !given.iter().any(|(n, _)| n == p))
            .collect()
    }

    /// The same parameters (names and types) and outcomes, wherever they were written.
    pub fn same_as(&self, other: &Interface) -> bool {
        let params = |i: &Interface| -> Vec<(String, VarType)> {
            i.params
                .iter()
                .map(|p| (p.name.clone(), p.ty.clone()))
                .collect()
        };
        let outcomes =
            |i: &Interface| -> Vec<String> { i.outcomes.iter().map(|o| o.name.clone()).collect() };
        params(self) == params(other) && outcomes(self) == outcomes(other)
    }
}

/// The global a parameter or an outcome of `machine` is kept in: `Dive_side`, `Dive_saved`.
/// Not `Dive.side`: a dotted name reads a teammate's value (`robot2.ballDistance`).
pub fn global_of(machine: &str, name: &str) -> String {
    format!("{machine}_{name}")
}

/// Letters, digits and `_`, not first a digit: a parameter's, an outcome's or an argument's name.
pub(crate) fn is_name(text: &str) -> bool {
    text.starts_with(|c: char| c.is_alphabetic() || c == '_')
        && text.chars().all(|c| c.is_alphanumeric() || c == '_')
}

/// Whether `value`, when it is a constant, is one a parameter of type `ty` can hold; an
/// expression is the caller's to get right, as any assignment's is.
pub fn fits(ty: &VarType, value: &Expr) -> bool {
    match (ty, value) {
        (VarType::Named(_), _) => true,
        (VarType::Int | VarType::Char, Expr::Int(_)) => true,
        (VarType::Bool, Expr::Bool(_)) => true,
        (VarType::Float | VarType::Double, Expr::Int(_) | Expr::Float(_)) => true,
        (VarType::Char, Expr::Str(s)) => s.chars().count() == 1,
        (_, Expr::Int(_) | Expr::Float(_) | Expr::Bool(_) | Expr::Str(_) | Expr::Duration(_)) => {
            false
        }
        // A negative constant is written `-1`.
        (_, Expr::Unary { operand, .. }) if matches!(**operand, Expr::Int(_) | Expr::Float(_)) => {
            matches!(
                ty,
                VarType::Int | VarType::Char | VarType::Float | VarType::Double
            )
        }
        _ => true,
    }
}
