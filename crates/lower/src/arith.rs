//! The activity language's operators over plain values, with C's semantics as gufsm had them:
//! whole numbers stay whole (`7 / 2` is 3), a fraction anywhere makes a fraction, `x / 0` and
//! `x % 0` give the largest whole number (gufsm's `INT_MAX`), text joins with `+`, a comparison
//! with a value never posted is false, and a typed variable converts what is assigned (`int n =
//! 2.7` holds 2). One place for the runner's evaluator and for the verifier's model, so a proof
//! is about the arithmetic the robot runs.

use proclaim_board::Value;
use proclaim_fsm::{BinOp, VarType};
use std::cmp::Ordering;

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

fn as_float(n: Number) -> f64 {
    match n {
        Number::Int(i) => i as f64,
        Number::Float(x) => x,
    }
}

/// `<`, `==`, … between two values: numbers by value, strings by text.
pub fn compare(a: &Value, b: &Value) -> Option<Ordering> {
    if let (Value::Str(x), Value::Str(y)) = (a, b) {
        return Some(x.cmp(y));
    }
    match (number(a)?, number(b)?) {
        (Number::Int(x), Number::Int(y)) => Some(x.cmp(&y)),
        (x, y) => as_float(x).partial_cmp(&as_float(y)),
    }
}

/// A binary operator other than the short-circuiting `&&` and `||` (which the evaluator does
/// itself): `None` where arithmetic has no value.
pub fn binary(op: BinOp, left: Option<Value>, right: Option<Value>) -> Option<Value> {
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
            if op == BinOp::Add
                && (matches!(left, Value::Str(_)) || matches!(right, Value::Str(_)))
                && (number(&left).is_none() || number(&right).is_none())
            {
                return Some(Value::Str(text(&left) + &text(&right)));
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

/// Unary minus.
pub fn negate(v: &Value) -> Option<Value> {
    Some(match v {
        Value::Int(i) => Value::Int(i.wrapping_neg()),
        Value::Bool(b) => Value::Int(-i64::from(*b)),
        other => Value::Float(-other.as_f64()?),
    })
}

/// The built-in functions of expressions (`abs`, `sqrt`, `min`, …) on evaluated arguments;
/// `None` for any other function or a wrong number of arguments.
pub fn function(name: &str, arguments: &[Option<Value>]) -> Option<Value> {
    let number = |i: usize| arguments.get(i)?.as_ref()?.as_f64();
    let x = number(0);
    Some(match (name, arguments.len()) {
        ("abs", 1) => match arguments[0].clone()? {
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
            let (a, b) = (arguments[0].clone()?, arguments[1].clone()?);
            let a_first = compare(&a, &b).is_some_and(|o| {
                (name == "min" && o != Ordering::Greater) || (name == "max" && o != Ordering::Less)
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

/// Whether `name` is one of [`function`]'s built-ins.
pub fn is_function(name: &str) -> bool {
    matches!(
        name,
        "abs"
            | "sqrt"
            | "sin"
            | "cos"
            | "tan"
            | "atan"
            | "atan2"
            | "round"
            | "floor"
            | "ceil"
            | "min"
            | "max"
    )
}

/// A value as a person reads it: text without quotes, lists space-separated.
pub fn text(value: &Value) -> String {
    match value {
        Value::Str(s) => s.clone(),
        Value::List(items) => items.iter().map(text).collect::<Vec<_>>().join(" "),
        other => other.to_string(),
    }
}

/// A declared variable's value before anything is assigned.
pub fn zero(ty: &VarType) -> Value {
    match ty {
        VarType::Bool => Value::Bool(false),
        VarType::Float | VarType::Double => Value::Float(0.0),
        VarType::Int | VarType::Char | VarType::Named(_) => Value::Int(0),
    }
}

/// What a variable of type `ty` holds when `value` is assigned to it, as C converts.
pub fn convert(ty: &VarType, value: Value) -> Value {
    match ty {
        VarType::Int | VarType::Char => match value {
            Value::Float(x) => Value::Int(x as i64),
            Value::Bool(b) => Value::Int(i64::from(b)),
            Value::Str(ref s) => s
                .trim()
                .parse::<f64>()
                .map_or(Value::Int(0), |x| Value::Int(x as i64)),
            other => other,
        },
        VarType::Float | VarType::Double => match value.as_f64() {
            Some(x) => Value::Float(x),
            None => Value::Float(0.0),
        },
        VarType::Bool => Value::Bool(value.truthy()),
        VarType::Named(_) => value,
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use proclaim_fsm::{parse_label, Expr, UnOp};

    /// A tiny evaluator over three names, enough to run a table of cases through these
    /// operators alone (`eval.rs` runs the same expressions through the runner's evaluator).
    fn eval(e: &Expr) -> Option<Value> {
        match e {
            Expr::Int(i) => Some(Value::Int(*i)),
            Expr::Float(x) => Some(Value::Float(*x)),
            Expr::Str(s) => Some(Value::Str(s.clone())),
            Expr::Name(n) if n == "g" => Some(Value::Int(7)),
            Expr::Name(n) if n == "posted" => Some(Value::Int(12)),
            Expr::Name(n) if n == "word" => Some(Value::Str("ball".into())),
            Expr::Name(_) => None,
            Expr::Unary {
                op: UnOp::Neg,
                operand,
            } => negate(&eval(operand)?),
            Expr::Unary {
                op: UnOp::Not,
                operand,
            } => Some(Value::Bool(!eval(operand).is_some_and(|v| v.truthy()))),
            Expr::Binary { op, left, right } => binary(*op, eval(left), eval(right)),
            Expr::Call {
                function: f,
                arguments,
                ..
            } => function(f, &arguments.iter().map(eval).collect::<Vec<_>>()),
            _ => None,
        }
    }

    fn check(text: &str, expect: Option<Value>) {
        let e = parse_label(text).expect("parses");
        assert_eq!(eval(&e), expect, "{text}");
    }

    #[test]
    fn c_arithmetic_as_the_runner_has_it() {
        check("7 / 2", Some(Value::Int(3)));
        check("7 / 2.0", Some(Value::Float(3.5)));
        check("-7 % 3", Some(Value::Int(-1)));
        check("1 / 0", Some(Value::Int(i64::MAX)));
        check("5 % 0", Some(Value::Int(i64::MAX)));
        check("g * 2 + posted", Some(Value::Int(26)));
        check("g == 2 * (g / 2)", Some(Value::Bool(false)));
        check("posted - never", None);
        check("never < 3", Some(Value::Bool(false)));
        check("never != 3", Some(Value::Bool(false)));
        check("!(never < 3)", Some(Value::Bool(true)));
        check("word + \" at \" + g", Some(Value::Str("ball at 7".into())));
        check("\"12\" + 1", Some(Value::Int(13)));
        check("abs(-3)", Some(Value::Int(3)));
        check("max(g, 2.5)", Some(Value::Int(7)));
        check("min(g, 2.5)", Some(Value::Float(2.5)));
    }

    #[test]
    fn assignment_converts_to_the_declared_type() {
        for (ty, value, expect) in [
            (VarType::Int, Value::Float(2.7), Value::Int(2)),
            (VarType::Int, Value::Str(" 3.9".into()), Value::Int(3)),
            (VarType::Float, Value::Int(2), Value::Float(2.0)),
            (VarType::Bool, Value::Str("off".into()), Value::Bool(false)),
            (
                VarType::Named("string".into()),
                Value::Str("x".into()),
                Value::Str("x".into()),
            ),
        ] {
            assert_eq!(convert(&ty, value.clone()), expect, "{ty:?} = {value:?}");
        }
    }
}
