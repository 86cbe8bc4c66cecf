//! The activity language planned as steps: expressions over a machine's own variables and the
//! behaviour's globals, statements, the built-ins decoded by `proclaim_lower::builtin`, and the
//! texts a posting carries. Values are the runner's `Int` and `Bool`, with
//! `proclaim_lower::arith`'s meaning written once in each target's runtime; fractions, text held
//! in variables, whiteboard reads, host functions and sleeps are refused.

use crate::plan::{Conversion, Function, Piece, Step, Value};
use crate::refusal::{Language, Refusal};
use proclaim_fsm::control::Command;
use proclaim_fsm::{Action, BinOp, Expr, ForLoop, Statement, UnOp, VarType, TIME_TESTS};
use proclaim_lower::arith;
use proclaim_lower::builtin::{builtin, Builtin, Content, Target};
use proclaim_lower::{read_statement, StatementReader};
use std::collections::HashMap;

/// What a variable of the behaviour is: its slot and how assignment converts.
#[derive(Clone, Debug)]
pub(crate) struct Variable {
    pub slot: usize,
    pub conversion: Conversion,
}

/// The kinds a variable so converted may hold.
fn kinds_of(conversion: Conversion) -> Kinds {
    match conversion {
        Conversion::Whole => Kinds::INT,
        Conversion::Truth => Kinds::BOOL,
        Conversion::Kept => Kinds::ANY,
    }
}

/// The runner's value kinds an expression may have (whole number, truth value).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) struct Kinds(u8);

impl Kinds {
    const INT: Kinds = Kinds(1);
    const BOOL: Kinds = Kinds(2);
    const ANY: Kinds = Kinds(3);

    fn union(self, other: Kinds) -> Kinds {
        Kinds(self.0 | other.0)
    }
}

/// The variables one machine sees, looked up as gufsm did: its own (declared anywhere in it),
/// then the behaviour's whiteboard variables (`extern`), then the globals; any other name it
/// reads is a whiteboard value read by name alone.
pub(crate) struct Variables {
    pub own: HashMap<String, Variable>,
    /// Each whiteboard value's number, and whether it is bound with `extern` (a variable).
    pub board: HashMap<String, (usize, bool)>,
    pub globals: HashMap<String, Variable>,
}

impl Variables {
    /// A variable with a slot (the machine's own, or a global) and whether it is a global;
    /// `None` for a whiteboard value or no variable.
    pub fn lookup(&self, name: &str) -> Option<(&Variable, bool)> {
        if let Some(v) = self.own.get(name) {
            return Some((v, false));
        }
        if self.board.contains_key(name) {
            return None;
        }
        self.globals.get(name).map(|v| (v, true))
    }

    /// The whiteboard value `name` reads here (the machine's own variable hides one).
    pub fn extern_number(&self, name: &str) -> Option<usize> {
        if self.own.contains_key(name) {
            return None;
        }
        self.board.get(name).map(|(number, _)| *number)
    }

    /// The whiteboard value a posting to type `ty` sets.
    pub fn posted_value(&self, ty: &str) -> Option<usize> {
        self.board.get(ty).map(|(number, _)| *number)
    }

    /// Whether `name` is a variable here of either kind (not an atom to ask).
    pub fn is_variable(&self, name: &str) -> bool {
        self.lookup(name).is_some()
            || (!self.own.contains_key(name) && self.board.get(name).is_some_and(|(_, b)| *b))
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

/// Whether a posting's text sets a theory input as the reasoner expert reads it, in the words a
/// compiled program reads too: `true`, `false`, `unknown` (in any case) or a whole number
/// (true unless 0). Other text (`yes`, `True`) the reasoner reads by its truthiness, which a
/// compiled program does not keep.
fn is_input_word(text: &str) -> bool {
    text == "true"
        || text == "false"
        || text.eq_ignore_ascii_case("unknown")
        || text.parse::<i64>().is_ok()
}

/// The longest text of a value: `-9223372036854775808`.
const VALUE_TEXT: usize = 20;

/// Where an activity runs and what it sees; plans its actions as steps.
pub(crate) struct Activity<'a> {
    pub file: &'a str,
    pub line: usize,
    pub state: &'a str,
    pub variables: &'a Variables,
    pub machines: &'a [String],
    /// Types that are theory inputs.
    pub inputs: &'a [String],
    pub target: Language,
    /// The longest text a posting needs, grown as postings are planned.
    pub longest_text: &'a mut usize,
    /// Numbers the `for` loops.
    pub loops: &'a mut usize,
    /// Counts the places that post a control command: no ringlet queues more than that.
    pub commands: &'a mut usize,
}

/// A statement planned as the step it runs as, `depth` blocks deep: each kind met where
/// [`proclaim_lower::read`] meets it.
struct Planned<'p, 'a> {
    activity: &'p mut Activity<'a>,
    depth: usize,
}

impl StatementReader for Planned<'_, '_> {
    type Read = Result<Step, Refusal>;

    fn assign(&mut self, name: &str, value: &Expr) -> Self::Read {
        self.activity.assignment(name, value)
    }

    fn call(&mut self, function: &str, arguments: &[Expr]) -> Self::Read {
        self.activity.call(function, arguments, self.depth)
    }

    // An expression standing alone has no effect (nothing in one has a side effect).
    fn evaluate(&mut self, _expr: &Expr) -> Self::Read {
        Ok(Step::Nothing)
    }

    fn sequence(&mut self, body: &[Statement]) -> Self::Read {
        let steps = body
            .iter()
            .map(|s| self.activity.statement(s, self.depth + 1))
            .collect::<Result<_, _>>()?;
        Ok(Step::Block(steps))
    }

    fn for_loop(&mut self, parts: ForLoop<'_>) -> Self::Read {
        self.activity.for_loop(parts, self.depth)
    }

    fn nothing(&mut self) -> Self::Read {
        Ok(Step::Nothing)
    }
}

impl Activity<'_> {
    /// A label's reading of the team (`what`: an aggregate, a teammate's value, the quorum),
    /// which no compiled program has.
    pub fn team_refusal(&self, e: &Expr, what: &str) -> Refusal {
        self.refuse(match self.target {
            Language::C => format!("`{e}`: {what} (a freestanding C behaviour has no network to its team's boards)"),
            Language::Rust => format!("`{e}`: {what} (a compiled Rust behaviour joins no team: its `--listen` or `--connect` whiteboard is not a team's, whose teammates' postings it would aggregate; run it with `proclaim run --member`)"),
        })
    }

    fn refuse(&self, what: String) -> Refusal {
        Refusal {
            file: self.file.to_string(),
            line: self.line,
            what,
        }
    }

    /// The steps of a list of actions.
    pub fn actions(&mut self, actions: &[Action]) -> Result<Vec<Step>, Refusal> {
        actions.iter().map(|a| self.action(a)).collect()
    }

    fn action(&mut self, action: &Action) -> Result<Step, Refusal> {
        match action {
            Action::Post { ty, content } => {
                let Some(text) = posted_text(content) else {
                    return Err(self.refuse(format!(
                        "the number `{}` (floating-point postings are not compiled yet)",
                        content.trim()
                    )));
                };
                if self.variables.posted_value(ty).is_some() && content.trim().starts_with('"') {
                    return Err(self.refuse(format!(
                        "the text {} posted to `{ty}`, a whiteboard value the machines read (a compiled one holds a whole number or a truth value)",
                        content.trim()
                    )));
                }
                if self.inputs.contains(ty) && !is_input_word(&text) {
                    return Err(self.refuse(format!(
                        "a theory input posted as `{content}` (only true, false, unknown or a whole number)"
                    )));
                }
                self.post(ty, vec![Piece::Literal(text)], 0)
            }
            Action::Call { function, .. } => Err(self.refuse(format!(
                "the host function `{function}` (host functions are not compiled yet)"
            ))),
            Action::Statement(s) => self.statement(s, 0),
            Action::Code(text) => Err(self.refuse(format!("the unread code `{text}`"))),
        }
    }

    /// A posting of `pieces` to `ty`: to a machine's name it is a control command (its word
    /// must be known here), to a theory input it must be a constant truth word.
    fn post(&mut self, ty: &str, pieces: Vec<Piece>, depth: usize) -> Result<Step, Refusal> {
        if let Some(target) = self.machines.iter().position(|n| n == ty) {
            return self.command(ty, target, &pieces, depth);
        }
        if let Some(number) = self.variables.posted_value(ty) {
            return self.post_extern(ty, number, pieces);
        }
        if self.inputs.iter().any(|i| i == ty) && !matches!(pieces.as_slice(), [Piece::Literal(_)])
        {
            return Err(self.refuse(format!(
                "a computed posting to the theory input `{ty}` (only true, false or unknown)"
            )));
        }
        if let [Piece::Literal(text)] = pieces.as_slice() {
            return Ok(Step::Post {
                ty: ty.to_string(),
                content: text.clone(),
            });
        }
        self.note_text(&pieces);
        Ok(Step::PostBuilt {
            ty: ty.to_string(),
            pieces,
        })
    }

    /// A posting to a whiteboard variable's type: one value, which its readers read as posted
    /// (`Value::parse` of a constant); text, which no compiled value holds, is refused.
    fn post_extern(&self, ty: &str, number: usize, pieces: Vec<Piece>) -> Result<Step, Refusal> {
        let value = match pieces.as_slice() {
            [Piece::Literal(text)] if text == "true" || text == "false" => {
                Some(Value::Bool(text == "true"))
            }
            [Piece::Literal(text)] => text.parse::<i64>().ok().map(Value::Int),
            [Piece::Value(_)] => pieces.into_iter().next().and_then(|p| match p {
                Piece::Value(v) => Some(v),
                _ => None,
            }),
            // `post_int`'s whole number: adding 0 makes a truth value whole, as `v_int` does.
            [Piece::Whole(_)] => pieces.into_iter().next().and_then(|p| match p {
                Piece::Whole(v) => Some(Value::Apply(Function::Add, vec![v, Value::Int(0)])),
                _ => None,
            }),
            _ => None,
        };
        match value {
            Some(value) => Ok(Step::PostExtern { number, value }),
            None => Err(self.refuse(format!(
                "a posting of text to `{ty}`, a whiteboard value the machines read (a compiled one holds a whole number or a truth value)"
            ))),
        }
    }

    /// A posting to machine `target`: a control command of a constant word, not in a block.
    fn command(
        &mut self,
        ty: &str,
        target: usize,
        pieces: &[Piece],
        depth: usize,
    ) -> Result<Step, Refusal> {
        let word = match pieces {
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
        Ok(Step::Command {
            ty: ty.to_string(),
            word,
            command,
            target,
        })
    }

    /// Grows the longest text to hold `pieces` built.
    fn note_text(&mut self, pieces: &[Piece]) {
        let longest = 1 + pieces
            .iter()
            .map(|piece| match piece {
                Piece::Literal(s) => s.len(),
                Piece::Value(_) | Piece::Whole(_) => VALUE_TEXT,
            })
            .sum::<usize>();
        *self.longest_text = (*self.longest_text).max(longest);
    }

    fn statement(&mut self, statement: &Statement, depth: usize) -> Result<Step, Refusal> {
        // The binding is the behaviour's (`plan_externs`): the statement itself does nothing.
        if let Statement::Extern { .. } = statement {
            return Ok(Step::Nothing);
        }
        read_statement(
            &mut Planned {
                activity: self,
                depth,
            },
            statement,
        )
    }

    /// An assignment: to a whiteboard variable it posts the value, unconverted.
    fn assignment(&mut self, name: &str, value: &Expr) -> Result<Step, Refusal> {
        if let Some(number) = self.variables.extern_number(name) {
            let (value, _) = self.value(value)?;
            return Ok(Step::PostExtern { number, value });
        }
        let Some((variable, global)) = self.variables.lookup(name) else {
            return Err(self.refuse(format!(
                "the assignment to `{name}`, which is no variable here"
            )));
        };
        let (slot, conversion) = (variable.slot, variable.conversion);
        let (value, _) = self.value(value)?;
        Ok(Step::Assign {
            slot,
            conversion,
            global,
            name: name.to_string(),
            value,
        })
    }

    /// A `for` loop, stopped at the runner's loop limit with its warning.
    fn for_loop(&mut self, parts: ForLoop<'_>, depth: usize) -> Result<Step, Refusal> {
        let number = *self.loops;
        *self.loops += 1;
        let init = match parts.init {
            Some(init) => Some(Box::new(self.statement(init, depth + 1)?)),
            None => None,
        };
        let condition = match parts.condition {
            Some(c) => Some(self.value(c)?.0),
            None => None,
        };
        let body = Box::new(self.statement(parts.body, depth + 2)?);
        let step = match parts.step {
            Some(step) => Some(Box::new(self.statement(step, depth + 2)?)),
            None => None,
        };
        Ok(Step::Loop {
            number,
            state: self.state.to_string(),
            init,
            condition,
            body,
            step,
        })
    }

    /// A call standing as a statement, by the runner's one decoding of the built-ins.
    fn call(&mut self, function: &str, arguments: &[Expr], depth: usize) -> Result<Step, Refusal> {
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
                self.note_text(&pieces);
                Ok(Step::Print(pieces))
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

    /// An expression's value and the kinds it may have.
    pub fn value(&mut self, e: &Expr) -> Result<(Value, Kinds), Refusal> {
        Ok(match e {
            Expr::Bool(b) => (Value::Bool(*b), Kinds::BOOL),
            Expr::Int(i) => (Value::Int(*i), Kinds::INT),
            Expr::Duration(us) => (Value::Int(*us as i64), Kinds::INT),
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
            Expr::Name(n) => match (self.variables.lookup(n), self.variables.extern_number(n)) {
                (Some((v, _)), _) => (Value::Slot(v.slot), kinds_of(v.conversion)),
                (None, Some(number)) => (Value::Extern(number), Kinds::ANY),
                (None, None) => {
                    return Err(self.refuse(format!(
                        "`{n}`, which is no variable: reading it from the whiteboard is not compiled (a machine's name, a theory's answer or a type under subsumption)"
                    )))
                }
            },
            Expr::Unary {
                op: UnOp::Not,
                operand,
            } => (Value::Not(Box::new(self.value(operand)?.0)), Kinds::BOOL),
            Expr::Unary {
                op: UnOp::Neg,
                operand,
            } => (
                Value::Apply(Function::Neg, vec![self.value(operand)?.0]),
                Kinds::INT,
            ),
            Expr::Binary { op, left, right } => self.binary(e, *op, left, right)?,
            Expr::Call {
                function,
                arguments,
                ..
            } => self.call_value(e, function, arguments)?,
        })
    }

    /// A binary operation: `&&` and `||` on truths, the rest on values.
    fn binary(
        &mut self,
        e: &Expr,
        op: BinOp,
        left: &Expr,
        right: &Expr,
    ) -> Result<(Value, Kinds), Refusal> {
        if is_text(left) || is_text(right) {
            return Err(self.refuse(format!("`{e}` (text is compiled only in postings)")));
        }
        let (function, kinds) = match op {
            BinOp::And | BinOp::Or => {
                let (l, r) = (self.value(left)?.0, self.value(right)?.0);
                let value = Value::Logic {
                    and: op == BinOp::And,
                    left: Box::new(l),
                    right: Box::new(r),
                };
                return Ok((value, Kinds::BOOL));
            }
            BinOp::Eq => (Function::Eq, Kinds::BOOL),
            BinOp::Ne => (Function::Ne, Kinds::BOOL),
            BinOp::Lt => (Function::Lt, Kinds::BOOL),
            BinOp::Le => (Function::Le, Kinds::BOOL),
            BinOp::Gt => (Function::Gt, Kinds::BOOL),
            BinOp::Ge => (Function::Ge, Kinds::BOOL),
            BinOp::Add => (Function::Add, Kinds::INT),
            BinOp::Sub => (Function::Sub, Kinds::INT),
            BinOp::Mul => (Function::Mul, Kinds::INT),
            BinOp::Div => (Function::Div, Kinds::INT),
            BinOp::Rem => (Function::Rem, Kinds::INT),
        };
        let (l, _) = self.value(left)?;
        let (r, _) = self.value(right)?;
        Ok((Value::Apply(function, vec![l, r]), kinds))
    }

    /// A call inside an expression: `abs`, `min` and `max`; the rest is refused.
    fn call_value(
        &mut self,
        e: &Expr,
        function: &str,
        arguments: &[Expr],
    ) -> Result<(Value, Kinds), Refusal> {
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
                Ok((Value::Apply(Function::Abs, vec![x]), Kinds::INT))
            }
            ("min" | "max", [a, b]) => {
                let (a, ka) = self.value(a)?;
                let (b, kb) = self.value(b)?;
                let f = if function == "min" {
                    Function::Min
                } else {
                    Function::Max
                };
                Ok((Value::Apply(f, vec![a, b]), ka.union(kb)))
            }
            _ if function.starts_with("team.") => Err(self.team_refusal(e, "a team aggregate")),
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
