//! Statements of an activity: declarations, assignments, calls, blocks and `for` loops.

use super::expr::Expr;
use std::fmt;

/// The type a declaration names. gufsm kept every variable as an integer; proclaim keeps the
/// declared kind so `float` variables hold fractions and `bool` ones truth values.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum VarType {
    Int,
    Bool,
    Char,
    Float,
    Double,
    /// Any other type name (`string`, `Point`): holds whatever is assigned to it.
    Named(String),
}

impl VarType {
    /// The built-in type a keyword names.
    pub fn keyword(word: &str) -> Option<VarType> {
        Some(match word {
            "int" | "long" | "short" | "unsigned" => VarType::Int,
            "bool" => VarType::Bool,
            "char" => VarType::Char,
            "float" => VarType::Float,
            "double" => VarType::Double,
            _ => return None,
        })
    }

    /// The type as written.
    pub fn name(&self) -> &str {
        match self {
            VarType::Int => "int",
            VarType::Bool => "bool",
            VarType::Char => "char",
            VarType::Float => "float",
            VarType::Double => "double",
            VarType::Named(n) => n,
        }
    }
}

#[derive(Clone, Debug, PartialEq)]
pub enum Statement {
    /// `int count;`, `float speed = 0.5;`: a variable of this machine alone.
    Declare {
        ty: VarType,
        name: String,
        value: Option<Expr>,
    },
    /// `extern ballDistance;`: the whiteboard message of that type, for every machine of the
    /// behaviour: reading gives its latest value, assigning posts it.
    Extern {
        ty: Option<VarType>,
        name: String,
    },
    /// `x = e;`
    Assign {
        name: String,
        value: Expr,
    },
    /// A call for its effect: `post("Say", "hi");`, `msleep(100);`.
    Expr(Expr),
    Block(Vec<Statement>),
    /// `for (i = 0; i < 3; i = i + 1) { … }`
    For {
        init: Option<Box<Statement>>,
        condition: Option<Expr>,
        step: Option<Box<Statement>>,
        body: Box<Statement>,
    },
}

/// What a statement does, read once for everyone who runs or prints one (the runner, the
/// checker's ringlet and the Promela writer): a declaration with a value is an assignment, a
/// declaration without one and an `extern` do nothing, and a call standing alone is a call.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum StatementKind<'s> {
    Assign {
        name: &'s str,
        value: &'s Expr,
    },
    Call {
        function: &'s str,
        arguments: &'s [Expr],
    },
    /// An expression evaluated for nothing but what evaluating it reads.
    Evaluate(&'s Expr),
    Sequence(&'s [Statement]),
    Loop(ForLoop<'s>),
    Nothing,
}

/// A `for` loop's parts.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ForLoop<'s> {
    pub init: Option<&'s Statement>,
    pub condition: Option<&'s Expr>,
    pub step: Option<&'s Statement>,
    pub body: &'s Statement,
}

impl Statement {
    /// What the statement does ([`StatementKind`]).
    pub fn kind(&self) -> StatementKind<'_> {
        match self {
            Statement::Declare {
                name,
                value: Some(value),
                ..
            }
            | Statement::Assign { name, value } => StatementKind::Assign { name, value },
            Statement::Declare { value: None, .. } | Statement::Extern { .. } => {
                StatementKind::Nothing
            }
            Statement::Expr(Expr::Call {
                function,
                arguments,
                ..
            }) => StatementKind::Call {
                function,
                arguments,
            },
            Statement::Expr(other) => StatementKind::Evaluate(other),
            Statement::Block(body) => StatementKind::Sequence(body),
            Statement::For {
                init,
                condition,
                step,
                body,
            } => StatementKind::Loop(ForLoop {
                init: init.as_deref(),
                condition: condition.as_ref(),
                step: step.as_deref(),
                body,
            }),
        }
    }

    /// Calls `f` on this statement and every statement inside it, outermost first.
    pub fn visit<'a>(&'a self, f: &mut impl FnMut(&'a Statement)) {
        f(self);
        match self.kind() {
            StatementKind::Sequence(body) => body.iter().for_each(|s| s.visit(f)),
            StatementKind::Loop(l) => {
                l.init.into_iter().chain(l.step).for_each(|s| s.visit(f));
                l.body.visit(f);
            }
            _ => {}
        }
    }

    /// The expressions the statement itself evaluates (not those of statements inside it).
    pub fn expressions(&self) -> Vec<&Expr> {
        match self {
            Statement::Declare { value, .. } => value.iter().collect(),
            Statement::Assign { value, .. } | Statement::Expr(value) => vec![value],
            Statement::For { condition, .. } => condition.iter().collect(),
            Statement::Extern { .. } | Statement::Block(_) => Vec::new(),
        }
    }

    fn write(&self, f: &mut impl fmt::Write, terminated: bool) -> fmt::Result {
        let end = if terminated { ";" } else { "" };
        match self {
            Statement::Declare { ty, name, value } => {
                write!(f, "{} {name}", ty.name())?;
                if let Some(v) = value {
                    f.write_str(" = ")?;
                    v.write(f, "!")?;
                }
                f.write_str(end)
            }
            Statement::Extern { ty, name } => match ty {
                Some(ty) => write!(f, "extern {} {name}{end}", ty.name()),
                None => write!(f, "extern {name}{end}"),
            },
            Statement::Assign { name, value } => {
                write!(f, "{name} = ")?;
                value.write(f, "!")?;
                f.write_str(end)
            }
            Statement::Expr(e) => {
                let mut text = String::new();
                e.write(&mut text, "!")?;
                // A statement that starts with a string is a posting (`"Type": content`): an
                // expression that starts with one keeps the parentheses it was written in.
                if text.starts_with('"') {
                    write!(f, "({text}){end}")
                } else {
                    write!(f, "{text}{end}")
                }
            }
            Statement::Block(body) => {
                f.write_str("{")?;
                for s in body {
                    f.write_str(" ")?;
                    s.write(f, true)?;
                }
                f.write_str(" }")
            }
            Statement::For {
                init,
                condition,
                step,
                body,
            } => {
                f.write_str("for (")?;
                if let Some(init) = init {
                    init.write(f, false)?;
                }
                f.write_str("; ")?;
                if let Some(c) = condition {
                    c.write(f, "!")?;
                }
                f.write_str("; ")?;
                if let Some(step) = step {
                    step.write(f, false)?;
                }
                f.write_str(") ")?;
                body.write(f, true)
            }
        }
    }
}

/// One line of C: `x = y + 1;`, `for (…) { … }`. Parsing it gives the same statement back.
impl fmt::Display for Statement {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        self.write(f, true)
    }
}
