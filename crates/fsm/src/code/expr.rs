//! Expressions: what a label is, and what an activity computes.

use std::fmt;

/// The functions a label may call to test the time spent in the state, with the number of
/// microseconds one unit of their argument stands for.
pub const TIME_TESTS: [(&str, f64); 3] = [("timeout", 1.0), ("after_ms", 1e3), ("after", 1e6)];

#[derive(Clone, Debug, PartialEq)]
pub enum Expr {
    Bool(bool),
    Int(i64),
    Float(f64),
    Str(String),
    /// A duration (`500ms`, `2s`), in microseconds: `timeout(500ms)`, `after(2s)`.
    Duration(u64),
    /// A variable, a whiteboard value, or (where a truth value is wanted and no variable has the
    /// name) a proposition an expert proclaims. Which one is decided where it runs.
    Name(String),
    Unary {
        op: UnOp,
        operand: Box<Expr>,
    },
    Binary {
        op: BinOp,
        left: Box<Expr>,
        right: Box<Expr>,
    },
    /// `f(a, b)`: a built-in (`timeout`, `abs`, `post`, …) or a host function.
    Call {
        function: String,
        arguments: Vec<Expr>,
        /// For a time test (`timeout`, `after`, `after_ms`) of a lowered label, the clock it
        /// reads: the composite whose entry it counts from (an index into
        /// `Machine::composites`), or `None` for the arrival in its flat state. Parsing gives
        /// `None`; lowering sets the rest (`docs/spec/behaviour.md` §3.2), and every back end
        /// reads it. Never written back as text.
        clock: Option<usize>,
    },
}

#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum UnOp {
    /// `!` (also written `~`, as gufsm's lexer allows).
    Not,
    Neg,
}

#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum BinOp {
    Or,
    And,
    Eq,
    Ne,
    Lt,
    Le,
    Gt,
    Ge,
    Add,
    Sub,
    Mul,
    Div,
    Rem,
}

impl BinOp {
    pub fn symbol(self) -> &'static str {
        match self {
            BinOp::Or => "||",
            BinOp::And => "&&",
            BinOp::Eq => "==",
            BinOp::Ne => "!=",
            BinOp::Lt => "<",
            BinOp::Le => "<=",
            BinOp::Gt => ">",
            BinOp::Ge => ">=",
            BinOp::Add => "+",
            BinOp::Sub => "-",
            BinOp::Mul => "*",
            BinOp::Div => "/",
            BinOp::Rem => "%",
        }
    }

    /// C's binding strength: larger binds tighter.
    pub fn precedence(self) -> u8 {
        match self {
            BinOp::Or => 1,
            BinOp::And => 2,
            BinOp::Eq | BinOp::Ne => 3,
            BinOp::Lt | BinOp::Le | BinOp::Gt | BinOp::Ge => 4,
            BinOp::Add | BinOp::Sub => 5,
            BinOp::Mul | BinOp::Div | BinOp::Rem => 6,
        }
    }

    pub fn from_symbol(symbol: &str) -> Option<BinOp> {
        ALL_BINOPS.into_iter().find(|op| op.symbol() == symbol)
    }

    /// Whether the result is a truth value whose operands are truth values (`&&`, `||`).
    pub fn is_logical(self) -> bool {
        matches!(self, BinOp::And | BinOp::Or)
    }
}

const ALL_BINOPS: [BinOp; 13] = [
    BinOp::Or,
    BinOp::And,
    BinOp::Eq,
    BinOp::Ne,
    BinOp::Lt,
    BinOp::Le,
    BinOp::Gt,
    BinOp::Ge,
    BinOp::Add,
    BinOp::Sub,
    BinOp::Mul,
    BinOp::Div,
    BinOp::Rem,
];

/// Unary operators bind tighter than any binary one.
const UNARY_PRECEDENCE: u8 = 7;

impl Expr {
    pub const TRUE: Expr = Expr::Bool(true);

    pub fn negation(operand: Expr) -> Expr {
        Expr::Unary {
            op: UnOp::Not,
            operand: Box::new(operand),
        }
    }

    pub fn binary(op: BinOp, left: Expr, right: Expr) -> Expr {
        Expr::Binary {
            op,
            left: Box::new(left),
            right: Box::new(right),
        }
    }

    /// `parts` joined by `op`, left to right; `None` when there are none.
    pub fn fold(op: BinOp, parts: impl IntoIterator<Item = Expr>) -> Option<Expr> {
        parts
            .into_iter()
            .reduce(|left, right| Expr::binary(op, left, right))
    }

    /// Names standing where a truth value is wanted (the whole label, or an operand of `!`,
    /// `&&`, `||`): the propositions an expert may be asked for, in order, once each.
    pub fn condition_names(&self) -> Vec<&str> {
        let mut out = Vec::new();
        self.visit_names(&mut |name, condition| {
            if condition && !out.contains(&name) {
                out.push(name);
            }
        });
        out
    }

    /// Calls `f(name, stands_as_condition)` for every name read, left to right.
    pub fn visit_names<'a>(&'a self, f: &mut impl FnMut(&'a str, bool)) {
        self.visit_names_at(true, f);
    }

    fn visit_names_at<'a>(&'a self, condition: bool, f: &mut impl FnMut(&'a str, bool)) {
        match self {
            Expr::Name(n) => f(n, condition),
            Expr::Unary { op, operand } => operand.visit_names_at(*op == UnOp::Not, f),
            Expr::Binary { op, left, right } => {
                left.visit_names_at(op.is_logical(), f);
                right.visit_names_at(op.is_logical(), f);
            }
            Expr::Call { arguments, .. } => {
                arguments.iter().for_each(|a| a.visit_names_at(false, f));
            }
            Expr::Bool(_) | Expr::Int(_) | Expr::Float(_) | Expr::Str(_) | Expr::Duration(_) => {}
        }
    }

    /// Every time test in the expression (`timeout`, `after`, `after_ms`), outermost first:
    /// its function, its arguments and the clock it reads.
    pub fn time_tests(&self) -> Vec<(&str, &[Expr], Option<usize>)> {
        let mut out = Vec::new();
        self.visit_exprs(&mut |e| {
            if let Expr::Call {
                function,
                arguments,
                clock,
            } = e
            {
                if TIME_TESTS.iter().any(|(t, _)| t == function) {
                    out.push((function.as_str(), arguments.as_slice(), *clock));
                }
            }
        });
        out
    }

    /// Sets the clock of every time test in the expression (see [`Expr::Call`]'s `clock`).
    pub fn set_time_clocks(&mut self, to: Option<usize>) {
        match self {
            Expr::Call {
                function,
                arguments,
                clock,
            } => {
                if TIME_TESTS.iter().any(|(t, _)| t == function) {
                    *clock = to;
                }
                arguments.iter_mut().for_each(|a| a.set_time_clocks(to));
            }
            Expr::Unary { operand, .. } => operand.set_time_clocks(to),
            Expr::Binary { left, right, .. } => {
                left.set_time_clocks(to);
                right.set_time_clocks(to);
            }
            _ => {}
        }
    }

    /// Calls `f` on the expression and every expression inside it, outermost first.
    fn visit_exprs<'a>(&'a self, f: &mut impl FnMut(&'a Expr)) {
        f(self);
        match self {
            Expr::Call { arguments, .. } => arguments.iter().for_each(|a| a.visit_exprs(f)),
            Expr::Unary { operand, .. } => operand.visit_exprs(f),
            Expr::Binary { left, right, .. } => {
                left.visit_exprs(f);
                right.visit_exprs(f);
            }
            _ => {}
        }
    }

    /// Every call in the expression, outermost first.
    pub fn calls(&self) -> Vec<(&str, &[Expr])> {
        let mut out = Vec::new();
        self.visit_calls(&mut |f, a| out.push((f, a)));
        out
    }

    fn visit_calls<'a>(&'a self, f: &mut impl FnMut(&'a str, &'a [Expr])) {
        match self {
            Expr::Call {
                function,
                arguments,
                ..
            } => {
                f(function, arguments);
                arguments.iter().for_each(|a| a.visit_calls(f));
            }
            Expr::Unary { operand, .. } => operand.visit_calls(f),
            Expr::Binary { left, right, .. } => {
                left.visit_calls(f);
                right.visit_calls(f);
            }
            _ => {}
        }
    }

    fn precedence(&self) -> u8 {
        match self {
            Expr::Binary { op, .. } => op.precedence(),
            Expr::Unary { .. } => UNARY_PRECEDENCE,
            // A negative literal prints with its sign, which binds like a unary minus.
            Expr::Int(i) if *i < 0 => UNARY_PRECEDENCE,
            Expr::Float(x) if x.is_sign_negative() => UNARY_PRECEDENCE,
            _ => UNARY_PRECEDENCE + 1,
        }
    }

    /// Writes the expression with `not` as the negation sign and parentheses only where
    /// needed; parsing the text gives the same expression back.
    pub(crate) fn write(&self, f: &mut impl fmt::Write, not: &str) -> fmt::Result {
        match self {
            Expr::Bool(true) => f.write_str("TRUE"),
            Expr::Bool(false) => f.write_str("FALSE"),
            Expr::Int(i) => write!(f, "{i}"),
            Expr::Float(x) => write!(f, "{x:?}"),
            Expr::Str(s) => write_quoted(f, s),
            Expr::Duration(us) if us % 1_000_000 == 0 => write!(f, "{}s", us / 1_000_000),
            Expr::Duration(us) if us % 1_000 == 0 => write!(f, "{}ms", us / 1_000),
            Expr::Duration(us) => write!(f, "{us}us"),
            Expr::Name(n) => f.write_str(n),
            Expr::Unary { op, operand } => {
                f.write_str(match op {
                    UnOp::Not => not,
                    UnOp::Neg => "-",
                })?;
                // `--x` lexes as two minus signs, so only binary operands need parentheses.
                let tight = matches!(**operand, Expr::Binary { .. });
                if tight {
                    f.write_str("(")?;
                }
                operand.write(f, not)?;
                if tight {
                    f.write_str(")")?;
                }
                Ok(())
            }
            Expr::Binary { op, left, right } => {
                let p = op.precedence();
                write_side(f, left, left.precedence() < p, not)?;
                write!(f, " {} ", op.symbol())?;
                write_side(f, right, right.precedence() <= p, not)
            }
            Expr::Call {
                function,
                arguments,
                ..
            } => {
                write!(f, "{function}(")?;
                for (i, a) in arguments.iter().enumerate() {
                    if i > 0 {
                        f.write_str(", ")?;
                    }
                    a.write(f, not)?;
                }
                f.write_str(")")
            }
        }
    }
}

fn write_side(f: &mut impl fmt::Write, side: &Expr, parenthesise: bool, not: &str) -> fmt::Result {
    if parenthesise {
        f.write_str("(")?;
        side.write(f, not)?;
        f.write_str(")")
    } else {
        side.write(f, not)
    }
}

pub(crate) fn write_quoted(f: &mut impl fmt::Write, s: &str) -> fmt::Result {
    f.write_char('"')?;
    for c in s.chars() {
        match c {
            '"' => f.write_str("\\\"")?,
            '\\' => f.write_str("\\\\")?,
            '\n' => f.write_str("\\n")?,
            '\t' => f.write_str("\\t")?,
            '\r' => f.write_str("\\r")?,
            c => f.write_char(c)?,
        }
    }
    f.write_char('"')
}

/// The label form: `~` for not (as the original tables wrote it), `&&`, `||`, parentheses
/// only where needed.
impl fmt::Display for Expr {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        self.write(f, "~")
    }
}
