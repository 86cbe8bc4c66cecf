//! Evaluating an expression of the activity language, written once: the walk over it, with C's
//! arithmetic ([`crate::arith`]), whatever its names and calls mean where it runs (a machine's
//! ringlet on the board, the checker's model, a Python clock's limits).

use crate::arith::{binary, negate};
use proclaim_board::Value;
use proclaim_fsm::{BinOp, Expr, UnOp};

/// The walk over an expression, the same wherever it runs (a machine's ringlet, the verifier's
/// model); what its names and calls mean is the implementor's.
pub trait Evaluate {
    /// A name's value; `None` where it reads a whiteboard value never posted.
    fn read(&mut self, name: &str) -> Option<Value>;

    /// A function's value; `None` for one that gives no value (a host function, or a
    /// built-in statement such as `post`). A time test reads `clock` (see [`Expr::Call`]).
    fn call(&mut self, function: &str, arguments: &[Expr], clock: Option<usize>) -> Option<Value>;

    /// The value of an expression, with C's arithmetic (`crate::arith`).
    fn value(&mut self, expr: &Expr) -> Option<Value> {
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
                _ => {
                    let (l, r) = (self.value(left), self.value(right));
                    binary(*op, l, r)
                }
            },
            Expr::Call {
                function,
                arguments,
                clock,
            } => self.call(function, arguments, *clock),
        }
    }

    /// The truth of an expression, by gufsm's rule ([`Value::truthy`]); a value never posted
    /// is false.
    fn truth(&mut self, expr: &Expr) -> bool {
        self.value(expr).is_some_and(|v| v.truthy())
    }
}
