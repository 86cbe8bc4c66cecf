//! The activity language as C: expressions over a machine's own variables and the behaviour's
//! globals, statements, the built-ins decoded by `proclaim_runner::builtin`, and the texts a
//! posting carries. Values are the runner's `Int` and `Bool` (a tagged `struct value`), with
//! `proclaim_runner::arith`'s meaning written once in the C helpers of [`RUNTIME`]; fractions,
//! text held in variables, whiteboard reads, host functions and sleeps are refused.

use crate::behaviour::Refusal;
use proclaim_fsm::control::Command;
use proclaim_fsm::{
    Action, BinOp, Expr, ForLoop, Statement, StatementKind, UnOp, VarType, TIME_TESTS,
};
use proclaim_runner::builtin::{builtin, Builtin, Content, Target};
use proclaim_runner::{arith, LOOP_LIMIT};
use std::collections::HashMap;
use std::fmt::Write;

/// What a variable of the behaviour is in C: its slot in `w->var` and how assignment converts.
#[derive(Clone, Debug)]
pub(crate) struct Variable {
    pub slot: usize,
    pub conversion: Conversion,
}

/// How a value assigned to a variable is converted, as `arith::convert` does.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum Conversion {
    /// `int`, `char`: a truth value becomes 0 or 1.
    Whole,
    /// `bool`: the value's truth.
    Truth,
    /// A global, or a declared type the runner keeps as assigned.
    Kept,
}

impl Conversion {
    fn c(self) -> &'static str {
        match self {
            Conversion::Whole => "CONVERT_WHOLE",
            Conversion::Truth => "CONVERT_TRUTH",
            Conversion::Kept => "CONVERT_KEPT",
        }
    }

    /// The kinds a variable so converted may hold.
    fn kinds(self) -> Kinds {
        match self {
            Conversion::Whole => Kinds::INT,
            Conversion::Truth => Kinds::BOOL,
            Conversion::Kept => Kinds::ANY,
        }
    }
}

/// The runner's value kinds an expression may have (whole number, truth value).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
struct Kinds(u8);

impl Kinds {
    const INT: Kinds = Kinds(1);
    const BOOL: Kinds = Kinds(2);
    const ANY: Kinds = Kinds(3);

    fn union(self, other: Kinds) -> Kinds {
        Kinds(self.0 | other.0)
    }
}

/// The variables one machine sees: its own (declared anywhere in it), then the globals.
pub(crate) struct Variables {
    pub own: HashMap<String, Variable>,
    pub globals: HashMap<String, Variable>,
}

impl Variables {
    pub fn lookup(&self, name: &str) -> Option<(&Variable, bool)> {
        if let Some(v) = self.own.get(name) {
            return Some((v, false));
        }
        self.globals.get(name).map(|v| (v, true))
    }
}

/// How a declared type converts, or why it cannot be compiled.
pub(crate) fn conversion(ty: &VarType) -> Result<Conversion, String> {
    match ty {
        VarType::Int | VarType::Char => Ok(Conversion::Whole),
        VarType::Bool => Ok(Conversion::Truth),
        VarType::Float | VarType::Double => Err(format!(
            "a `{}` variable (fractions are not compiled yet)",
            if *ty == VarType::Float {
                "float"
            } else {
                "double"
            }
        )),
        VarType::Named(_) => Ok(Conversion::Kept),
    }
}

/// A sub-machine control command as C's `enum command` names it.
pub(crate) fn command_c(command: Option<Command>) -> &'static str {
    match command {
        Some(Command::On) => "COMMAND_ON",
        Some(Command::Off) => "COMMAND_OFF",
        Some(Command::Suspend) => "COMMAND_SUSPEND",
        Some(Command::Resume) => "COMMAND_RESUME",
        Some(Command::Restart) => "COMMAND_RESTART",
        Some(Command::Reload) | Some(Command::Reread) | None => "COMMAND_UNKNOWN",
    }
}

/// A piece of a posting's text: written as is, or a value's text at run time.
#[derive(Clone, Debug)]
enum Piece {
    Literal(String),
    Value(String),
    /// A value as a whole number (`post_int`).
    Whole(String),
}

/// The longest text of a value: `-9223372036854775808`.
const VALUE_TEXT: usize = 20;

/// Where an activity runs and what it sees; compiles its actions into C.
pub(crate) struct Activity<'a> {
    pub file: &'a str,
    pub line: usize,
    pub machine: usize,
    pub state: &'a str,
    pub variables: &'a Variables,
    pub machines: &'a [String],
    /// Types that are theory inputs.
    pub inputs: &'a [String],
    /// The longest text a posting needs, grown as postings are compiled.
    pub longest_text: &'a mut usize,
    /// Numbers the `for` loops' counters.
    pub loops: &'a mut usize,
    /// Counts the places that post a control command: no ringlet queues more than that.
    pub commands: &'a mut usize,
}

impl Activity<'_> {
    fn refuse(&self, what: String) -> Refusal {
        Refusal {
            file: self.file.to_string(),
            line: self.line,
            what,
        }
    }

    /// The C of a list of actions, indented for a `case` of `ring_M`.
    pub fn actions(&mut self, actions: &[Action]) -> Result<String, Refusal> {
        let mut out = String::new();
        for action in actions {
            out.push_str(&self.action(action, 0)?);
        }
        Ok(out)
    }

    fn action(&mut self, action: &Action, depth: usize) -> Result<String, Refusal> {
        match action {
            Action::Post { ty, content } => {
                let Some(text) = posted_text(content) else {
                    return Err(self.refuse(format!(
                        "the number `{}` (floating-point postings are not compiled yet)",
                        content.trim()
                    )));
                };
                if self.inputs.contains(ty)
                    && !["true", "false", "unknown"].contains(&text.as_str())
                {
                    return Err(self.refuse(format!(
                        "a theory input posted as `{content}` (only true, false or unknown)"
                    )));
                }
                self.post(ty, vec![Piece::Literal(text)], depth)
            }
            Action::Call { function, .. } => Err(self.refuse(format!(
                "the host function `{function}` (host functions are not compiled yet)"
            ))),
            Action::Statement(s) => self.statement(s, depth),
            Action::Code(text) => Err(self.refuse(format!("the unread code `{text}`"))),
        }
    }

    fn indent(depth: usize) -> String {
        " ".repeat(12 + 4 * depth)
    }

    /// A posting of `pieces` to `ty`: to a machine's name it is a control command (its word
    /// must be known here), to a theory input it must be a constant truth word.
    fn post(&mut self, ty: &str, pieces: Vec<Piece>, depth: usize) -> Result<String, Refusal> {
        let pad = Self::indent(depth);
        let m = self.machine;
        if let Some(target) = self.machines.iter().position(|n| n == ty) {
            let word = match pieces.as_slice() {
                [] => String::new(),
                [Piece::Literal(word)] => word.clone(),
                _ => {
                    return Err(self.refuse(format!(
                        "a computed control command to `{ty}` (only a constant word is compiled)"
                    )))
                }
            };
            let command = Command::parse(&word);
            if matches!(command, Some(Command::Reload | Command::Reread)) {
                return Err(self.refuse(format!(
                    "`{ty}: {word}` (a compiled machine has no file to read again)"
                )));
            }
            if depth > 0 {
                return Err(self.refuse(format!(
                    "a control command to `{ty}` inside a block or a loop (a compiled behaviour queues a fixed number)"
                )));
            }
            *self.commands += 1;
            return Ok(format!(
                "{pad}post(w, {m}u, \"{}\", \"{}\");\n{pad}command(w, {target}u, {}, \"{}\");\n",
                esc(ty),
                esc(&word),
                command_c(command),
                esc(&word)
            ));
        }
        if self.inputs.iter().any(|i| i == ty) && !matches!(pieces.as_slice(), [Piece::Literal(_)])
        {
            return Err(self.refuse(format!(
                "a computed posting to the theory input `{ty}` (only true, false or unknown)"
            )));
        }
        if let [Piece::Literal(text)] = pieces.as_slice() {
            return Ok(format!(
                "{pad}post(w, {m}u, \"{}\", \"{}\");\n",
                esc(ty),
                esc(text)
            ));
        }
        let mut out = self.build_text(&pieces, depth);
        let _ = writeln!(out, "{pad}post(w, {m}u, \"{}\", w->text);", esc(ty));
        Ok(out)
    }

    /// The C that builds `pieces` into `w->text`.
    fn build_text(&mut self, pieces: &[Piece], depth: usize) -> String {
        let pad = Self::indent(depth);
        let mut out = String::new();
        let mut longest = 1;
        let _ = writeln!(out, "{pad}text_clear(w);");
        for piece in pieces {
            match piece {
                Piece::Literal(s) => {
                    longest += s.len();
                    if !s.is_empty() {
                        let _ = writeln!(out, "{pad}text_literal(w, \"{}\");", esc(s));
                    }
                }
                Piece::Value(v) => {
                    longest += VALUE_TEXT;
                    let _ = writeln!(out, "{pad}text_value(w, {v});");
                }
                Piece::Whole(v) => {
                    longest += VALUE_TEXT;
                    let _ = writeln!(out, "{pad}text_whole(w, {v});");
                }
            }
        }
        *self.longest_text = (*self.longest_text).max(longest);
        out
    }

    fn statement(&mut self, statement: &Statement, depth: usize) -> Result<String, Refusal> {
        let pad = Self::indent(depth);
        let m = self.machine;
        if let Statement::Extern { name, .. } = statement {
            return Err(self.refuse(format!(
                "`extern {name}` (whiteboard variables are not compiled yet)"
            )));
        }
        Ok(match statement.kind() {
            StatementKind::Assign { name, value } => {
                let Some((variable, global)) = self.variables.lookup(name) else {
                    return Err(self.refuse(format!(
                        "the assignment to `{name}`, which is no variable here (an extern?)"
                    )));
                };
                let (value, _) = self.value(value)?;
                format!(
                    "{pad}assign(w, {m}u, {}u, {}, {}, \"{}\", {value});\n",
                    variable.slot,
                    variable.conversion.c(),
                    u8::from(global),
                    esc(name)
                )
            }
            StatementKind::Nothing => String::new(),
            StatementKind::Call {
                function,
                arguments,
            } => self.call(function, arguments, depth)?,
            // An expression standing alone has no effect (nothing in one has a side effect).
            StatementKind::Evaluate(_) => String::new(),
            StatementKind::Sequence(body) => {
                let mut out = format!("{pad}{{\n");
                for s in body {
                    out.push_str(&self.statement(s, depth + 1)?);
                }
                out.push_str(&format!("{pad}}}\n"));
                out
            }
            StatementKind::Loop(parts) => self.for_loop(parts, depth)?,
        })
    }

    /// A `for` loop as a C `while`, stopped at the runner's [`LOOP_LIMIT`] with its warning.
    fn for_loop(&mut self, parts: ForLoop<'_>, depth: usize) -> Result<String, Refusal> {
        let pad = Self::indent(depth);
        let m = self.machine;
        let n = *self.loops;
        *self.loops += 1;
        let inner = Self::indent(depth + 1);
        let mut out = format!("{pad}{{\n{inner}uint32_t rounds_{n} = 0;\n");
        if let Some(init) = parts.init {
            out.push_str(&self.statement(init, depth + 1)?);
        }
        let condition = match parts.condition {
            Some(c) => self.truth(c)?,
            None => "1".into(),
        };
        let _ = writeln!(out, "{inner}while ({condition}) {{");
        let deeper = Self::indent(depth + 2);
        let _ = writeln!(
            out,
            "{deeper}if (rounds_{n} == LOOP_LIMIT) {{\n{deeper}    w->cb.warned(w, machine_name[{m}], \"a `for` loop in state {} stopped after {LOOP_LIMIT} rounds\");\n{deeper}    break;\n{deeper}}}\n{deeper}rounds_{n}++;",
            esc(self.state)
        );
        out.push_str(&self.statement(parts.body, depth + 2)?);
        if let Some(step) = parts.step {
            out.push_str(&self.statement(step, depth + 2)?);
        }
        let _ = writeln!(out, "{inner}}}\n{pad}}}");
        Ok(out)
    }

    /// A call standing as a statement, by the runner's one decoding of the built-ins.
    fn call(
        &mut self,
        function: &str,
        arguments: &[Expr],
        depth: usize,
    ) -> Result<String, Refusal> {
        let pad = Self::indent(depth);
        let m = self.machine;
        match builtin(function, arguments) {
            Builtin::Post { to, content } => {
                let ty = match to {
                    Target::Fixed(name) => name.to_string(),
                    Target::Named(Expr::Str(name)) => name.clone(),
                    Target::Named(other) => {
                        return Err(self.refuse(format!(
                            "`{function}` to `{other}` (only a quoted type is compiled)"
                        )))
                    }
                };
                let pieces = self.content(&content)?;
                self.post(&ty, pieces, depth)
            }
            Builtin::Print(content) => {
                let pieces = self.content(&content)?;
                let mut out = self.build_text(&pieces, depth);
                let _ = writeln!(out, "{pad}w->cb.printed(w, machine_name[{m}], w->text);");
                Ok(out)
            }
            Builtin::Sleep { .. } => {
                Err(self.refuse(format!("`{function}` (a compiled ringlet does not sleep)")))
            }
            Builtin::Other => Err(self.refuse(format!(
                "the call `{function}` (host functions are not compiled yet)"
            ))),
        }
    }

    /// What a built-in posts or prints, as pieces of text (`Content::value`, then `text`).
    fn content(&mut self, content: &Content<'_>) -> Result<Vec<Piece>, Refusal> {
        Ok(match content {
            Content::Value(e) | Content::Text(e) => self.text(e)?,
            Content::Int(e) => {
                if is_text(e) {
                    return Err(self.refuse(format!(
                        "`post_int` of the text `{e}` (text as a number is not compiled yet)"
                    )));
                }
                vec![Piece::Whole(self.value(e)?.0)]
            }
            Content::Joined(parts) => {
                let mut out = Vec::new();
                for part in parts.iter() {
                    let pieces = self.text(part)?;
                    let empty = pieces
                        .iter()
                        .all(|p| matches!(p, Piece::Literal(s) if s.is_empty()));
                    if empty {
                        continue;
                    }
                    if !out.is_empty() {
                        out.push(Piece::Literal(" ".into()));
                    }
                    out.extend(pieces);
                }
                out
            }
            Content::List(values) => {
                let mut out = Vec::new();
                for (i, v) in values.iter().enumerate() {
                    if i > 0 {
                        out.push(Piece::Literal(" ".into()));
                    }
                    out.extend(self.text(v)?);
                }
                out
            }
            Content::Command(command) => vec![Piece::Literal(command.word().into())],
            Content::StateName => vec![Piece::Literal(self.state.to_string())],
        })
    }

    /// An expression's text: a text expression (literals joined by `+`) piece by piece, or a
    /// value's.
    fn text(&mut self, e: &Expr) -> Result<Vec<Piece>, Refusal> {
        match e {
            Expr::Str(s) => Ok(vec![Piece::Literal(s.clone())]),
            Expr::Binary {
                op: BinOp::Add,
                left,
                right,
            } if is_text(left) || is_text(right) => {
                // `+` joins texts only when one side is no number; a side that can never read
                // as one keeps that so whatever the other side holds.
                if !never_a_number(left) && !never_a_number(right) {
                    return Err(self.refuse(format!(
                        "`{e}`: text that may read as a number (`\"12\" + 1` is 13) is not compiled yet"
                    )));
                }
                let mut pieces = self.text(left)?;
                pieces.extend(self.text(right)?);
                Ok(pieces)
            }
            other => Ok(vec![Piece::Value(self.value(other)?.0)]),
        }
    }

    /// The C of an expression's truth.
    pub fn truth(&mut self, e: &Expr) -> Result<String, Refusal> {
        let (value, _) = self.value(e)?;
        Ok(format!("truthy({value})"))
    }

    /// The C of an expression's value (a `struct value`) and the kinds it may have.
    fn value(&mut self, e: &Expr) -> Result<(String, Kinds), Refusal> {
        Ok(match e {
            Expr::Bool(b) => (format!("v_bool({})", u8::from(*b)), Kinds::BOOL),
            Expr::Int(i) => (format!("v_int({})", int_c(*i)), Kinds::INT),
            Expr::Duration(us) => (format!("v_int({})", int_c(*us as i64)), Kinds::INT),
            Expr::Float(x) => {
                return Err(
                    self.refuse(format!("the number `{x}` (fractions are not compiled yet)"))
                )
            }
            Expr::Str(s) => {
                return Err(self.refuse(format!(
                    "the text \"{s}\" where a value is computed (text is compiled only in postings)"
                )))
            }
            Expr::Name(n) => match self.variables.lookup(n) {
                Some((v, _)) => (format!("w->var[{}]", v.slot), v.conversion.kinds()),
                None => {
                    return Err(self.refuse(format!(
                        "`{n}`, which is no variable: reading the whiteboard is not compiled yet"
                    )))
                }
            },
            Expr::Unary {
                op: UnOp::Not,
                operand,
            } => (format!("v_bool(!{})", self.truth(operand)?), Kinds::BOOL),
            Expr::Unary {
                op: UnOp::Neg,
                operand,
            } => (format!("v_neg({})", self.value(operand)?.0), Kinds::INT),
            Expr::Binary { op, left, right } => self.binary(e, *op, left, right)?,
            Expr::Call {
                function,
                arguments,
            } => self.call_value(e, function, arguments)?,
        })
    }

    /// The C of a binary operation: `&&` and `||` on truths, the rest on values.
    fn binary(
        &mut self,
        e: &Expr,
        op: BinOp,
        left: &Expr,
        right: &Expr,
    ) -> Result<(String, Kinds), Refusal> {
        if is_text(left) || is_text(right) {
            return Err(self.refuse(format!("`{e}` (text is compiled only in postings)")));
        }
        let (f, kinds) = match op {
            BinOp::And | BinOp::Or => {
                let (l, r) = (self.truth(left)?, self.truth(right)?);
                return Ok((format!("v_bool({l} {} {r})", op.symbol()), Kinds::BOOL));
            }
            BinOp::Eq => ("v_eq", Kinds::BOOL),
            BinOp::Ne => ("v_ne", Kinds::BOOL),
            BinOp::Lt => ("v_lt", Kinds::BOOL),
            BinOp::Le => ("v_le", Kinds::BOOL),
            BinOp::Gt => ("v_gt", Kinds::BOOL),
            BinOp::Ge => ("v_ge", Kinds::BOOL),
            BinOp::Add => ("v_add", Kinds::INT),
            BinOp::Sub => ("v_sub", Kinds::INT),
            BinOp::Mul => ("v_mul", Kinds::INT),
            BinOp::Div => ("v_div", Kinds::INT),
            BinOp::Rem => ("v_rem", Kinds::INT),
        };
        let (l, _) = self.value(left)?;
        let (r, _) = self.value(right)?;
        Ok((format!("{f}({l}, {r})"), kinds))
    }

    /// The C of a call inside an expression: `abs`, `min` and `max`; the rest is refused.
    fn call_value(
        &mut self,
        e: &Expr,
        function: &str,
        arguments: &[Expr],
    ) -> Result<(String, Kinds), Refusal> {
        if TIME_TESTS.iter().any(|(t, _)| *t == function) {
            return Err(self.refuse(format!(
                "`{e}` in an activity (time tests are compiled in labels)"
            )));
        }
        if arguments.iter().any(is_text) {
            return Err(self.refuse(format!("`{e}` (text is compiled only in postings)")));
        }
        match (function, arguments) {
            ("abs", [x]) => {
                let (x, kinds) = self.value(x)?;
                if kinds != Kinds::INT {
                    return Err(self.refuse(format!(
                        "`{e}`: abs of what may be a truth value is a fraction in the runner (not compiled yet)"
                    )));
                }
                Ok((format!("v_abs({x})"), Kinds::INT))
            }
            ("min" | "max", [a, b]) => {
                let (a, ka) = self.value(a)?;
                let (b, kb) = self.value(b)?;
                Ok((format!("v_{function}({a}, {b})"), ka.union(kb)))
            }
            _ if function.starts_with("team.") => Err(self.refuse(format!(
                "`{e}`: a team aggregate (a compiled behaviour has no team board)"
            ))),
            _ if arith::is_function(function) => {
                Err(self.refuse(format!("`{e}` (its value is a fraction: not compiled yet)")))
            }
            _ => Err(self.refuse(format!(
                "the call `{e}` in an expression (host functions are not compiled yet)"
            ))),
        }
    }
}

/// Whether an expression is text: a quoted string, or `+` with text on a side.
fn is_text(e: &Expr) -> bool {
    match e {
        Expr::Str(_) => true,
        Expr::Binary {
            op: BinOp::Add,
            left,
            right,
        } => is_text(left) || is_text(right),
        _ => false,
    }
}

/// Whether a text expression can never read as a number, whatever joins it: it holds a
/// character that no number (`12`, `-3.5e2`, `inf`, `NaN`) has.
fn never_a_number(e: &Expr) -> bool {
    match e {
        Expr::Str(s) => s
            .chars()
            .any(|c| !c.is_whitespace() && !c.is_ascii_digit() && !"+-.eEiInNfFtTyYaA".contains(c)),
        Expr::Binary {
            op: BinOp::Add,
            left,
            right,
        } => never_a_number(left) || never_a_number(right),
        _ => false,
    }
}

/// A whole number as a C expression of type `int64_t`.
fn int_c(i: i64) -> String {
    if i == i64::MIN {
        "(-INT64_C(9223372036854775807) - 1)".into()
    } else {
        format!("INT64_C({i})")
    }
}

/// A posting's content as the runner reads it (`Value::parse`) and shows it in a trace: a truth
/// word, a whole number, or text without its quotes; `None` for a floating-point number, whose
/// printed form is not compiled yet.
pub(crate) fn posted_text(content: &str) -> Option<String> {
    let t = content.trim();
    if t == "true" || t == "false" {
        Some(t.to_string())
    } else if let Ok(i) = t.parse::<i64>() {
        Some(i.to_string())
    } else if t.parse::<f64>().is_ok() {
        None
    } else {
        Some(t.trim_matches('"').to_string())
    }
}

/// Text as a C string literal's inside.
pub(crate) fn esc(text: &str) -> String {
    let mut out = String::new();
    for c in text.chars() {
        match c {
            '"' => out.push_str("\\\""),
            '\\' => out.push_str("\\\\"),
            '\n' => out.push_str("\\n"),
            '?' => out.push_str("\\?"),
            c if (c as u32) < 0x20 || (c as u32) > 0x7e => {
                let mut buf = [0u8; 4];
                for b in c.encode_utf8(&mut buf).bytes() {
                    let _ = write!(out, "\\{b:03o}");
                }
            }
            c => out.push(c),
        }
    }
    out
}

/// The C helpers compiled activities call: the runner's values and `arith`'s operators on them.
pub(crate) const RUNTIME: &str = r#"
/* A value as the runner holds it: a whole number, or a truth value (0 or 1). */
#define CONVERT_WHOLE 0
#define CONVERT_TRUTH 1
#define CONVERT_KEPT 2

static struct value v_int(int64_t i)
{
    struct value v;
    v.i = i;
    v.is_bool = 0;
    return v;
}

static struct value v_bool(int b)
{
    struct value v;
    v.i = b ? 1 : 0;
    v.is_bool = 1;
    return v;
}

static int truthy(struct value v)
{
    return v.i != 0;
}

/* Wrapping arithmetic, as the runner's `wrapping_add` and kin. */
static int64_t wrap(uint64_t u)
{
    return u <= (uint64_t)INT64_MAX ? (int64_t)u : -(int64_t)(~u) - 1;
}

static struct value v_add(struct value a, struct value b)
{
    return v_int(wrap((uint64_t)a.i + (uint64_t)b.i));
}

static struct value v_sub(struct value a, struct value b)
{
    return v_int(wrap((uint64_t)a.i - (uint64_t)b.i));
}

static struct value v_mul(struct value a, struct value b)
{
    return v_int(wrap((uint64_t)a.i * (uint64_t)b.i));
}

/* Dividing by zero gives the largest whole number, as gufsm's INT_MAX. */
static struct value v_div(struct value a, struct value b)
{
    if (b.i == 0) {
        return v_int(INT64_MAX);
    }
    if (b.i == -1) {
        return v_int(wrap(0u - (uint64_t)a.i));
    }
    return v_int(a.i / b.i);
}

static struct value v_rem(struct value a, struct value b)
{
    if (b.i == 0) {
        return v_int(INT64_MAX);
    }
    if (b.i == -1) {
        return v_int(0);
    }
    return v_int(a.i % b.i);
}

static struct value v_neg(struct value a)
{
    return v_int(wrap(0u - (uint64_t)a.i));
}

static struct value v_abs(struct value a)
{
    return a.i < 0 ? v_neg(a) : a;
}

static struct value v_eq(struct value a, struct value b)
{
    return v_bool(a.i == b.i);
}

static struct value v_ne(struct value a, struct value b)
{
    return v_bool(a.i != b.i);
}

static struct value v_lt(struct value a, struct value b)
{
    return v_bool(a.i < b.i);
}

static struct value v_le(struct value a, struct value b)
{
    return v_bool(a.i <= b.i);
}

static struct value v_gt(struct value a, struct value b)
{
    return v_bool(a.i > b.i);
}

static struct value v_ge(struct value a, struct value b)
{
    return v_bool(a.i >= b.i);
}

/* The first when it is not greater (min) or not less (max), as the runner picks. */
static struct value v_min(struct value a, struct value b)
{
    return a.i <= b.i ? a : b;
}

static struct value v_max(struct value a, struct value b)
{
    return a.i >= b.i ? a : b;
}

static struct value convert(int conversion, struct value v)
{
    if (conversion == CONVERT_WHOLE) {
        return v_int(v.i);
    }
    if (conversion == CONVERT_TRUTH) {
        return v_bool(truthy(v));
    }
    return v;
}

/* A value's text, as the trace shows it, into `out` (at least 21 bytes); its length. */
static unsigned value_text(char *out, struct value v)
{
    char digits[20];
    unsigned n = 0, len = 0;
    uint64_t u;
    const char *word;
    if (v.is_bool) {
        word = v.i ? "true" : "false";
        while (word[len] != '\0') {
            out[len] = word[len];
            len++;
        }
        out[len] = '\0';
        return len;
    }
    u = v.i < 0 ? 0u - (uint64_t)v.i : (uint64_t)v.i;
    do {
        digits[n++] = (char)('0' + (int)(u % 10u));
        u /= 10u;
    } while (u != 0u);
    if (v.i < 0) {
        out[len++] = '-';
    }
    while (n > 0) {
        out[len++] = digits[--n];
    }
    out[len] = '\0';
    return len;
}

static void text_clear(struct world *w)
{
    w->text_length = 0;
    w->text[0] = '\0';
}

static void text_literal(struct world *w, const char *s)
{
    while (*s != '\0') {
        w->text[w->text_length++] = *s++;
    }
    w->text[w->text_length] = '\0';
}

static void text_value(struct world *w, struct value v)
{
    w->text_length += value_text(w->text + w->text_length, v);
}

static void text_whole(struct world *w, struct value v)
{
    text_value(w, v_int(v.i));
}

/* An assignment as the runner makes it: converted to the variable's type, reported when the
 * value changed; a global's change is news to the labels that read globals. */
static void assign(struct world *w, unsigned m, unsigned slot, int conversion, int global,
                   const char *name, struct value v)
{
    char shown[24];
    v = convert(conversion, v);
    if (w->var[slot].i == v.i && w->var[slot].is_bool == v.is_bool) {
        return;
    }
    w->var[slot] = v;
    if (global) {
        w->globals_changes++;
    }
    (void)value_text(shown, v);
    w->cb.assigned(w, machine_name[m], name, shown);
}
"#;
