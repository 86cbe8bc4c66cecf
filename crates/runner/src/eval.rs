//! Evaluating expressions of the activity language over variables and whiteboard values, with
//! C's arithmetic: whole numbers stay whole (`7 / 2` is 3), a fraction anywhere makes the
//! result a fraction, and (as gufsm had it) dividing by zero gives the largest whole number
//! instead of stopping the robot.

use crate::activity::text;
use crate::seen::Seen;
use crate::variables::{Locals, Scope, Shared};
use proclaim_board::{Value, Whiteboard};
use proclaim_fsm::{BinOp, Expr, UnOp, TIME_TESTS};
use std::cmp::Ordering;
use std::time::Duration;

/// What names mean where an expression runs.
pub(crate) struct Env<'a> {
    pub board: &'a Whiteboard,
    /// How the board reads in this part of the ringlet (live, or its snapshot).
    pub seen: &'a Seen,
    pub locals: &'a Locals,
    pub shared: &'a Shared,
    /// Time since the machine entered its current state (for `timeout`, `after`, `after_ms`).
    pub in_state: Duration,
}

impl Env<'_> {
    pub fn scope(&self) -> Scope<'_> {
        Scope {
            locals: self.locals,
            shared: self.shared,
        }
    }

    /// A name's value: a variable's, else the latest whiteboard message of that type (`None`
    /// when none was ever posted). An extern never posted reads 0, as gufsm's cache did.
    pub fn read(&self, name: &str) -> Option<Value> {
        if let Some(v) = self.locals.get(name) {
            return Some(v.clone());
        }
        if self.shared.is_extern(name) {
            return Some(self.latest(name).map_or(Value::Int(0), |m| m.value));
        }
        if let Some(v) = self.shared.global(name) {
            return Some(v);
        }
        self.latest(name).map(|m| m.value)
    }

    /// The newest message of a type, as the ringlet sees the board.
    pub fn latest(&self, ty: &str) -> Option<proclaim_board::Message> {
        self.seen.latest(self.board, ty)
    }

    /// The value of an expression; `None` where it reads a whiteboard value never posted.
    pub fn value(&self, expr: &Expr) -> Option<Value> {
        match expr {
            Expr::Bool(b) => Some(Value::Bool(*b)),
            Expr::Int(i) => Some(Value::Int(*i)),
            Expr::Float(x) => Some(Value::Float(*x)),
            Expr::Str(s) => Some(Value::Str(s.clone())),
            // A duration read as a number is its microseconds (gufsm's unit of time).
            Expr::Duration(us) => Some(Value::Int(*us as i64)),
            Expr::Name(n) => self.read(n),
            Expr::Unary {
                op: UnOp::Not,
                operand,
            } => Some(Value::Bool(!self.truth(operand))),
            Expr::Unary {
                op: UnOp::Neg,
                operand,
            } => negate(&self.value(operand)?),
            Expr::Binary { op, left, right } => match op {
                BinOp::And => Some(Value::Bool(self.truth(left) && self.truth(right))),
                BinOp::Or => Some(Value::Bool(self.truth(left) || self.truth(right))),
                _ => binary(*op, self.value(left), self.value(right)),
            },
            Expr::Call {
                function,
                arguments,
            } => self.call(function, arguments),
        }
    }

    /// The truth of an expression, by gufsm's rule ([`Value::truthy`]); a value never posted
    /// is false.
    pub fn truth(&self, expr: &Expr) -> bool {
        self.value(expr).is_some_and(|v| v.truthy())
    }

    /// The functions an expression may use; `None` for one that gives no value (a host
    /// function or an activity built-in such as `post`, which only statements run).
    pub fn call(&self, function: &str, arguments: &[Expr]) -> Option<Value> {
        if let Some(limit) = self.time_limit(function, arguments) {
            return Some(Value::Bool(limit.is_some_and(|l| self.in_state >= l)));
        }
        let number = |i: usize| arguments.get(i).and_then(|a| self.value(a)?.as_f64());
        let x = number(0);
        Some(match (function, arguments.len()) {
            ("abs", 1) => match self.value(&arguments[0])? {
                Value::Int(i) => Value::Int(i.wrapping_abs()),
                other => Value::Float(other.as_f64()?.abs()),
            },
            ("sqrt", 1) => Value::Float(x?.sqrt()),
            ("sin", 1) => Value::Float(x?.sin()),
            ("cos", 1) => Value::Float(x?.cos()),
            ("tan", 1) => Value::Float(x?.tan()),
            ("atan", 1) => Value::Float(x?.atan()),
            ("atan2", 2) => Value::Float(x?.atan2(number(1)?)),
            ("round", 1) => Value::Int(x?.round() as i64),
            ("floor", 1) => Value::Int(x?.floor() as i64),
            ("ceil", 1) => Value::Int(x?.ceil() as i64),
            ("min" | "max", 2) => {
                let (a, b) = (self.value(&arguments[0])?, self.value(&arguments[1])?);
                let a_first = compare(&a, &b).is_some_and(|o| {
                    (function == "min" && o != Ordering::Greater)
                        || (function == "max" && o != Ordering::Less)
                });
                if a_first {
                    a
                } else {
                    b
                }
            }
            _ => return None,
        })
    }

    /// For `timeout(µs)`, `after(s)` and `after_ms(ms)`: how long the state must have been
    /// active (`Some(None)` when the argument has no value); `None` for other functions.
    pub fn time_limit(&self, function: &str, arguments: &[Expr]) -> Option<Option<Duration>> {
        let (_, micros_per_unit) = TIME_TESTS.iter().find(|(f, _)| *f == function)?;
        let [argument] = arguments else {
            return Some(None);
        };
        // A duration says its own unit: `after(2s)` and `timeout(2s)` are the same test.
        if let Expr::Duration(us) = argument {
            return Some(Some(Duration::from_micros(*us)));
        }
        Some(
            self.value(argument)
                .and_then(|v| v.as_f64())
                .map(|n| Duration::from_secs_f64((n * micros_per_unit).max(0.0) / 1e6)),
        )
    }
}

fn negate(v: &Value) -> Option<Value> {
    Some(match v {
        Value::Int(i) => Value::Int(i.wrapping_neg()),
        Value::Bool(b) => Value::Int(-i64::from(*b)),
        other => Value::Float(-other.as_f64()?),
    })
}

enum Number {
    Int(i64),
    Float(f64),
}

fn number(v: &Value) -> Option<Number> {
    match v {
        Value::Bool(b) => Some(Number::Int(i64::from(*b))),
        Value::Int(i) => Some(Number::Int(*i)),
        Value::Float(x) => Some(Number::Float(*x)),
        Value::Str(s) => {
            let t = s.trim();
            t.parse()
                .map(Number::Int)
                .ok()
                .or_else(|| t.parse().ok().map(Number::Float))
        }
        _ => None,
    }
}

/// `<`, `==`, … between two values: numbers by value, strings by text.
fn compare(a: &Value, b: &Value) -> Option<Ordering> {
    if let (Value::Str(x), Value::Str(y)) = (a, b) {
        return Some(x.cmp(y));
    }
    match (number(a)?, number(b)?) {
        (Number::Int(x), Number::Int(y)) => Some(x.cmp(&y)),
        (x, y) => as_float(x).partial_cmp(&as_float(y)),
    }
}

fn as_float(n: Number) -> f64 {
    match n {
        Number::Int(i) => i as f64,
        Number::Float(x) => x,
    }
}

/// A binary operator on two values (`&&` and `||` read them as truth values; `Env::value`
/// short-circuits those itself). A comparison with a value never posted is false; arithmetic
/// with one has no value.
pub(crate) fn binary(op: BinOp, left: Option<Value>, right: Option<Value>) -> Option<Value> {
    let ordering = |want: fn(Ordering) -> bool| {
        Some(Value::Bool(match (&left, &right) {
            (Some(a), Some(b)) => compare(a, b).is_some_and(want),
            _ => false,
        }))
    };
    match op {
        BinOp::Eq => ordering(|o| o == Ordering::Equal),
        BinOp::Ne => Some(Value::Bool(match (&left, &right) {
            (Some(a), Some(b)) => compare(a, b) != Some(Ordering::Equal),
            _ => false,
        })),
        BinOp::Lt => ordering(|o| o == Ordering::Less),
        BinOp::Le => ordering(|o| o != Ordering::Greater),
        BinOp::Gt => ordering(|o| o == Ordering::Greater),
        BinOp::Ge => ordering(|o| o != Ordering::Less),
        BinOp::And | BinOp::Or => {
            let (a, b) = (left?.truthy(), right?.truthy());
            Some(Value::Bool(if op == BinOp::And { a && b } else { a || b }))
        }
        BinOp::Add | BinOp::Sub | BinOp::Mul | BinOp::Div | BinOp::Rem => {
            let (left, right) = (left?, right?);
            if op == BinOp::Add && (matches!(left, Value::Str(_)) || matches!(right, Value::Str(_)))
            {
                // Text joined to text or a number (`post("Say", "ball at " + d)`), unless both
                // read as numbers (a sensor posting "12").
                if number(&left).is_none() || number(&right).is_none() {
                    return Some(Value::Str(text(&left) + &text(&right)));
                }
            }
            arithmetic(op, number(&left)?, number(&right)?)
        }
    }
}

fn arithmetic(op: BinOp, left: Number, right: Number) -> Option<Value> {
    Some(match (left, right) {
        (Number::Int(a), Number::Int(b)) => Value::Int(match op {
            BinOp::Add => a.wrapping_add(b),
            BinOp::Sub => a.wrapping_sub(b),
            BinOp::Mul => a.wrapping_mul(b),
            BinOp::Div if b == 0 => i64::MAX,
            BinOp::Div => a.wrapping_div(b),
            BinOp::Rem if b == 0 => i64::MAX,
            BinOp::Rem => a.wrapping_rem(b),
            _ => return None,
        }),
        (a, b) => {
            let (a, b) = (as_float(a), as_float(b));
            Value::Float(match op {
                BinOp::Add => a + b,
                BinOp::Sub => a - b,
                BinOp::Mul => a * b,
                BinOp::Div => a / b,
                BinOp::Rem => a % b,
                _ => return None,
            })
        }
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use proclaim_fsm::parse_label;

    fn eval(text: &str) -> Option<Value> {
        let board = Whiteboard::local();
        board.post("test", "posted", Value::Int(12));
        board.post("test", "word", Value::Str("ball".into()));
        let shared = Shared::for_machines([]);
        shared.set_global("g", Value::Int(7));
        let env = Env {
            board: &board,
            seen: &Seen::default(),
            locals: &Locals::default(),
            shared: &shared,
            in_state: Duration::from_millis(1500),
        };
        env.value(&parse_label(text).expect("parses"))
    }

    #[tokio::test]
    async fn c_arithmetic_over_variables_and_whiteboard_values() {
        for (text, expect) in [
            ("7 / 2", Some(Value::Int(3))),
            ("7 / 2.0", Some(Value::Float(3.5))),
            ("-7 % 3", Some(Value::Int(-1))),
            ("1 / 0", Some(Value::Int(i64::MAX))),
            ("g * 2 + posted", Some(Value::Int(26))),
            ("g == 2 * (g / 2)", Some(Value::Bool(false))),
            ("posted - never", None),
            ("never < 3", Some(Value::Bool(false))),
            ("!(never < 3)", Some(Value::Bool(true))),
            ("word + \" at \" + g", Some(Value::Str("ball at 7".into()))),
            ("abs(-3)", Some(Value::Int(3))),
            ("max(g, 2.5)", Some(Value::Int(7))),
            (
                "timeout(1500000) && after(1) && !after_ms(1501)",
                Some(Value::Bool(true)),
            ),
            ("timeout(g * 1000000)", Some(Value::Bool(false))),
            (
                "timeout(1500ms) && after(1s) && !after_ms(2s)",
                Some(Value::Bool(true)),
            ),
            ("timeout(2s) + 500ms", Some(Value::Int(500_000))),
        ] {
            assert_eq!(eval(text), expect, "{text}");
        }
    }
}
