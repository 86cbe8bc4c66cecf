//! The values the free environment may give a whiteboard type: a finite abstraction of "any
//! value of its kind".
//!
//! A type only ever used as a truth value (a label's atom, a reasoner's input, a script's
//! atom) takes `true` and `false`. Any other type takes every constant the behaviour compares
//! it with or posts to it, the neighbours `c - 1` and `c + 1` of each number it is ordered
//! against (`x < 20` then sees 19, 20 and 21: below, at and above), and one "other" value equal
//! to none of them. This is sound for what the activity language can do with a value it did
//! not compute itself: test its truth, compare it with constants (`==`, `!=`, `<`, …) and
//! post or copy it. It is **not** exact for arithmetic on the value or for comparing two free
//! values with each other (`a < b`): there the abstraction picks representatives, and a run
//! that needs a value between them is not explored. Every free type may also still be "never
//! posted" in the initial state (a sensor that has not spoken yet).

use proclaim_board::Value;
use proclaim_fsm::{Action, BinOp, Expr, Machine, Statement};
use rustc_hash::{FxHashMap, FxHashSet};

/// What the environment may set a free type to.
#[derive(Clone, Debug, PartialEq)]
pub struct FreeDomain {
    /// At every snapshot.
    pub values: Vec<Value>,
    /// In the initial state: `None` (never posted) and then `values`.
    pub initial: Vec<Option<Value>>,
}

/// Constants gathered per type while reading the behaviour.
#[derive(Debug, Default)]
pub struct Domains {
    seen: FxHashMap<String, Vec<Value>>,
    conditions: FxHashSet<String>,
}

impl Domains {
    pub fn add(&mut self, name: &str, value: Value) {
        let values = self.seen.entry(name.to_string()).or_default();
        if !values.contains(&value) {
            values.push(value);
        }
    }

    /// Constants a machine compares or posts.
    pub fn gather_machine(&mut self, machine: &Machine) {
        for t in &machine.transitions {
            self.gather_expr(&t.label);
        }
        for a in machine.actions() {
            if let Action::Post { ty, content } = a {
                self.add(ty, Value::parse(content));
            }
        }
        for s in machine.statements() {
            for e in s.expressions() {
                self.gather_expr(e);
            }
            if let Statement::Assign { name, value } = s {
                if let Some(v) = constant(value) {
                    self.add(name, v);
                }
            }
            if let Statement::Expr(Expr::Call {
                function,
                arguments,
            }) = s
            {
                if let ("post" | "post_int", [Expr::Str(ty), value]) =
                    (function.as_str(), arguments.as_slice())
                {
                    if let Some(v) = constant(value) {
                        self.add(ty, v);
                    }
                }
            }
        }
    }

    /// Constants an expression compares names with, and the names it uses as truth values.
    pub fn gather_expr(&mut self, expr: &Expr) {
        expr.visit_names(&mut |name, condition| {
            if condition {
                self.conditions.insert(name.to_string());
            }
        });
        self.comparisons(expr);
    }

    fn comparisons(&mut self, expr: &Expr) {
        match expr {
            Expr::Binary { op, left, right } => {
                let ordered = matches!(op, BinOp::Lt | BinOp::Le | BinOp::Gt | BinOp::Ge);
                let compares = ordered || matches!(op, BinOp::Eq | BinOp::Ne);
                if compares {
                    for (a, b) in [(left, right), (right, left)] {
                        if let (Expr::Name(n), Some(c)) = (&**a, constant(b)) {
                            if ordered {
                                for v in neighbours(&c) {
                                    self.add(n, v);
                                }
                            }
                            self.add(n, c);
                        }
                    }
                }
                self.comparisons(left);
                self.comparisons(right);
            }
            Expr::Unary { operand, .. } => self.comparisons(operand),
            Expr::Call { arguments, .. } => arguments.iter().for_each(|a| self.comparisons(a)),
            _ => {}
        }
    }

    /// The domain of free type `name`.
    pub fn domain(&self, name: &str) -> FreeDomain {
        let seen = self.seen.get(name).cloned().unwrap_or_default();
        let mut values: Vec<Value> = if seen.iter().all(|v| matches!(v, Value::Bool(_))) {
            vec![Value::Bool(false), Value::Bool(true)]
        } else {
            let mut values = seen.clone();
            values.push(other(&seen));
            values
        };
        if self.conditions.contains(name) {
            // Used as a truth value too: both truths must be possible.
            for truth in [false, true] {
                if !values.iter().any(|v| v.truthy() == truth) {
                    values.push(Value::Bool(truth));
                }
            }
        }
        let initial = std::iter::once(None)
            .chain(values.iter().cloned().map(Some))
            .collect();
        FreeDomain { values, initial }
    }
}

/// A literal's value (`-3` is a literal too).
fn constant(e: &Expr) -> Option<Value> {
    Some(match e {
        Expr::Bool(b) => Value::Bool(*b),
        Expr::Int(i) => Value::Int(*i),
        Expr::Float(x) => Value::Float(*x),
        Expr::Str(s) => Value::Str(s.clone()),
        Expr::Unary {
            op: proclaim_fsm::UnOp::Neg,
            operand,
        } => match constant(operand)? {
            Value::Int(i) => Value::Int(i.wrapping_neg()),
            Value::Float(x) => Value::Float(-x),
            _ => return None,
        },
        _ => return None,
    })
}

/// Values just below and above a number an ordering compares with.
fn neighbours(c: &Value) -> Vec<Value> {
    match c {
        Value::Int(i) => vec![Value::Int(i.wrapping_sub(1)), Value::Int(i.wrapping_add(1))],
        Value::Float(x) => vec![Value::Float(x - 0.5), Value::Float(x + 0.5)],
        _ => Vec::new(),
    }
}

/// A value equal to none of `seen` and of the same kind as most of them.
fn other(seen: &[Value]) -> Value {
    if seen.iter().any(|v| matches!(v, Value::Str(_))) {
        let mut candidate = "other".to_string();
        while seen.contains(&Value::Str(candidate.clone())) {
            candidate.push('_');
        }
        Value::Str(candidate)
    } else {
        let largest = seen
            .iter()
            .filter_map(Value::as_f64)
            .fold(0.0_f64, f64::max);
        Value::Int(largest as i64 + 1000)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use proclaim_fsm::parse_label;

    fn check(labels: &[&str], name: &str, expect: &[Value]) {
        let mut domains = Domains::default();
        for l in labels {
            domains.gather_expr(&parse_label(l).expect("parses"));
        }
        let domain = domains.domain(name);
        assert_eq!(domain.values, expect, "{labels:?}");
        assert_eq!(domain.initial.len(), expect.len() + 1, "never posted first");
        assert_eq!(domain.initial[0], None);
    }

    #[test]
    fn domains_are_the_constants_compared_with_and_one_other() {
        check(
            &["doorOpen && cook"],
            "doorOpen",
            &[false.into(), true.into()],
        );
        check(
            &["mode == \"kick\"", "mode != \"walk\""],
            "mode",
            &[
                Value::Str("kick".into()),
                Value::Str("walk".into()),
                Value::Str("other".into()),
            ],
        );
        check(
            &["d < 20"],
            "d",
            &[
                Value::Int(19),
                Value::Int(21),
                Value::Int(20),
                Value::Int(1021),
            ],
        );
        // Used as a truth value and compared with text: both truths are there.
        check(
            &["mode == \"on\" || mode"],
            "mode",
            &[
                Value::Str("on".into()),
                Value::Str("other".into()),
                Value::Bool(false),
            ],
        );
    }
}
