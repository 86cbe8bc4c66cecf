//! The code a compiled behaviour's machines are, as a tree both target languages spell:
//! functions of the world, their statements and expressions. `machine_code.rs` builds it once
//! from the plan (what a ringlet does is decided there); a `Spelling` (`spell_c.rs`,
//! `spell_rust.rs`) only says how its language writes each node, and `print` lays it out.

/// A function of the behaviour: its first parameter is the world.
pub(crate) struct Function {
    pub name: String,
    /// Whether it changes the world, or only reads it.
    pub writes: bool,
    /// Its parameters after the world.
    pub params: Vec<(&'static str, Type)>,
    pub returns: Type,
    pub body: Vec<Stmt>,
}

/// The few types a machine's functions take and return.
#[derive(Clone, Copy)]
pub(crate) enum Type {
    /// A truth value (`int` in C).
    Truth,
    /// An index into the behaviour's tables.
    Index,
    /// Milliseconds on the run's clock.
    Ms,
    /// Text the caller keeps.
    Text,
}

pub(crate) enum Stmt {
    /// A call, for what it does.
    Do(Expr),
    /// `place = value`.
    Set(Expr, Expr),
    If(Expr, Vec<Stmt>),
    While(Expr, Vec<Stmt>),
    Block(Vec<Stmt>),
    /// Each arm's body runs when `on` is one of its numbers; `otherwise` when none is.
    Switch {
        on: Expr,
        arms: Vec<(Vec<i64>, Vec<Stmt>)>,
        otherwise: Vec<Stmt>,
    },
    Return(Expr),
    Break,
    /// A local variable and its first value.
    Let(&'static str, Type, Expr),
    /// A loop's round counter, from 0.
    Counter(String),
    Increment(String),
}

#[derive(Clone)]
pub(crate) enum Expr {
    /// A field of the world.
    World(&'static str),
    Index(Box<Expr>, Box<Expr>),
    /// A constant table of the behaviour (`machine_name`).
    Table(&'static str),
    /// A name both languages write alike: a parameter, a constant, a counter.
    Name(String),
    /// A whole value of the activity language (64 bits, signed).
    Whole(i64),
    /// A count, an index or milliseconds (unsigned).
    Count(u64),
    /// A state's number.
    Number(i64),
    Truth(bool),
    Text(String),
    /// A function of the runtime or the behaviour, given the world first.
    Call(String, Vec<Expr>),
    /// A function of values alone (`v_add`, `truthy`).
    Pure(&'static str, Vec<Expr>),
    /// An event reported to the host (`entered`, `fired`, `warned`).
    Report(&'static str, Vec<Expr>),
    /// An operation on the world's text buffer (`text_clear`, `text_value`).
    Buffer(&'static str, Vec<Expr>),
    Not(Box<Expr>),
    Binary(Op, Box<Expr>, Box<Expr>),
    /// A label, handed to `proved` to be proved there.
    Label(Box<Expr>),
    /// Output `output` of a theory's decision function (`theory` its code's name), its
    /// variables the world's inputs from `offset`.
    Decide {
        theory: String,
        output: usize,
        offset: usize,
    },
}

#[derive(Clone, Copy)]
pub(crate) enum Op {
    And,
    Or,
    Equal,
}

impl Op {
    pub fn symbol(self) -> &'static str {
        match self {
            Op::And => "&&",
            Op::Or => "||",
            Op::Equal => "==",
        }
    }
}

impl Expr {
    pub fn call(name: &str, args: Vec<Expr>) -> Expr {
        Expr::Call(name.to_string(), args)
    }

    pub fn count(n: usize) -> Expr {
        Expr::Count(n as u64)
    }

    pub fn index(table: Expr, at: Expr) -> Expr {
        Expr::Index(Box::new(table), Box::new(at))
    }

    pub fn binary(op: Op, left: Expr, right: Expr) -> Expr {
        Expr::Binary(op, Box::new(left), Box::new(right))
    }

    /// A call's arguments (not a pure function's).
    pub fn arguments(&self) -> Option<&[Expr]> {
        match self {
            Expr::Call(_, args) | Expr::Report(_, args) | Expr::Buffer(_, args) => Some(args),
            _ => None,
        }
    }

    /// The same call given other arguments.
    pub fn with_arguments(&self, args: Vec<Expr>) -> Expr {
        match self {
            Expr::Call(name, _) => Expr::Call(name.clone(), args),
            Expr::Report(name, _) => Expr::Report(name, args),
            Expr::Buffer(name, _) => Expr::Buffer(name, args),
            other => other.clone(),
        }
    }

    /// Whether evaluating it reads the world (then Rust cannot pass it beside the world).
    pub fn reads_world(&self) -> bool {
        match self {
            Expr::World(_) | Expr::Call(..) | Expr::Report(..) | Expr::Buffer(..) => true,
            Expr::Label(_) | Expr::Decide { .. } => true,
            Expr::Index(a, b) | Expr::Binary(_, a, b) => a.reads_world() || b.reads_world(),
            Expr::Not(e) => e.reads_world(),
            Expr::Pure(_, args) => args.iter().any(Expr::reads_world),
            Expr::Table(_)
            | Expr::Name(_)
            | Expr::Whole(_)
            | Expr::Count(_)
            | Expr::Number(_)
            | Expr::Truth(_)
            | Expr::Text(_) => false,
        }
    }
}

/// How one language writes the tree's nodes; `print` lays out the rest.
pub(crate) trait Spelling {
    /// An expression.
    fn expr(&self, e: &Expr) -> String;
    /// Arguments, separated by commas.
    fn list(&self, args: &[Expr]) -> String {
        let shown: Vec<String> = args.iter().map(|a| self.expr(a)).collect();
        shown.join(", ")
    }
    /// A condition, without the parentheses a binary operation carries elsewhere.
    fn bare(&self, e: &Expr) -> String {
        match e {
            Expr::Binary(op, l, r) => {
                format!("{} {} {}", self.expr(l), op.symbol(), self.expr(r))
            }
            e => self.expr(e),
        }
    }
    /// A function's first line(s) up to and including its opening brace, and what its body
    /// starts with (C marks each parameter used).
    fn head(&self, f: &Function) -> (String, Vec<String>);
    /// `if` or `while` and its condition, up to the opening brace.
    fn test(&self, keyword: &str, condition: &Expr) -> String;
    /// A local variable's declaration with its first value.
    fn local(&self, name: &str, t: Type, value: &Expr) -> String;
    fn counter(&self, name: &str) -> String;
    fn increment(&self, name: &str) -> String;
    /// A call standing as a statement: its lines.
    fn call_statement(&self, call: &Expr) -> Vec<String>;
    /// A switch: its first line, an arm's first lines, the default arm's first line, and
    /// whether an arm that runs to its end must say so (`break` in C).
    fn switch(&self, on: &Expr) -> String;
    fn arm(&self, numbers: &[i64]) -> Vec<String>;
    fn otherwise(&self) -> String;
    fn arm_breaks(&self) -> bool;
}

/// A function as `spelling` writes it, four spaces an indent.
pub(crate) fn print(f: &Function, spelling: &dyn Spelling) -> String {
    let (head, opening) = spelling.head(f);
    let mut out = head;
    out.push('\n');
    for line in opening {
        line_at(&mut out, 1, &line);
    }
    statements(&mut out, 1, &f.body, spelling);
    out.push_str("}\n\n");
    out
}

fn line_at(out: &mut String, depth: usize, line: &str) {
    for _ in 0..depth {
        out.push_str("    ");
    }
    out.push_str(line);
    out.push('\n');
}

fn statements(out: &mut String, depth: usize, body: &[Stmt], spelling: &dyn Spelling) {
    for s in body {
        statement(out, depth, s, spelling);
    }
}

fn statement(out: &mut String, depth: usize, s: &Stmt, spelling: &dyn Spelling) {
    match s {
        Stmt::Do(call) => {
            for line in spelling.call_statement(call) {
                line_at(out, depth, &line);
            }
        }
        Stmt::Set(place, value) => {
            let line = format!("{} = {};", spelling.expr(place), spelling.expr(value));
            line_at(out, depth, &line);
        }
        Stmt::If(condition, body) | Stmt::While(condition, body) => {
            let keyword = if matches!(s, Stmt::If(..)) {
                "if"
            } else {
                "while"
            };
            line_at(out, depth, &spelling.test(keyword, condition));
            statements(out, depth + 1, body, spelling);
            line_at(out, depth, "}");
        }
        Stmt::Block(body) => {
            line_at(out, depth, "{");
            statements(out, depth + 1, body, spelling);
            line_at(out, depth, "}");
        }
        Stmt::Switch {
            on,
            arms,
            otherwise,
        } => switch(out, depth, (on, arms, otherwise), spelling),
        Stmt::Return(value) => line_at(out, depth, &format!("return {};", spelling.expr(value))),
        Stmt::Break => line_at(out, depth, "break;"),
        Stmt::Let(name, t, value) => line_at(out, depth, &spelling.local(name, *t, value)),
        Stmt::Counter(name) => line_at(out, depth, &spelling.counter(name)),
        Stmt::Increment(name) => line_at(out, depth, &spelling.increment(name)),
    }
}

type Arms<'a> = (&'a Expr, &'a [(Vec<i64>, Vec<Stmt>)], &'a [Stmt]);

/// A switch; without arms, only what its default does.
fn switch(out: &mut String, depth: usize, (on, arms, otherwise): Arms, spelling: &dyn Spelling) {
    if arms.is_empty() {
        statements(out, depth, otherwise, spelling);
        return;
    }
    line_at(out, depth, &spelling.switch(on));
    let heads = arms
        .iter()
        .map(|(numbers, body)| (spelling.arm(numbers), body.as_slice()));
    for (head, body) in heads.chain([(vec![spelling.otherwise()], otherwise)]) {
        for line in head {
            line_at(out, depth, &line);
        }
        statements(out, depth + 1, body, spelling);
        let ends = matches!(body.last(), Some(Stmt::Return(_) | Stmt::Break));
        if spelling.arm_breaks() && !ends {
            line_at(out, depth + 1, "break;");
        }
        line_at(out, depth, "}");
    }
    line_at(out, depth, "}");
}
