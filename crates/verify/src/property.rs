//! Properties: `never P`, `always P`, `reachable P`, and the liveness properties `eventually
//! P`, `always_eventually P`, `leads_to P ~> Q` with their `fair` assumptions (checked by
//! [`crate::liveness`]), where P is an expression of the label language (`proclaim_fsm`'s parser) over the world **now**, between two ringlets: a plain name
//! is a variable, a whiteboard type's current value or a reasoner's answer on the current
//! inputs; `Machine.STATE` is true while the machine runs in that state (`Machine.x` is its
//! variable `x`); `saw(Machine, e)` is what `e` was in that machine's last snapshot (never
//! posted before its first); `NameIsRunning` is whether a machine runs. Time tests make no
//! sense outside a machine and are refused. Every error names the property and the column.

use crate::error::PropertyError;
use crate::kind::ValueKind;
use crate::model::DOT;
use crate::model::{Model, Name, SlotId, SlotKind};
use crate::reasoner::{input, Input};
use crate::search::Search;
use crate::values::ValueId;
use crate::world::{Status, SystemState};
use proclaim_behaviour::PropertyKind;
use proclaim_board::Value;
use proclaim_fsm::code::parse_expression;
use proclaim_fsm::{BinOp, Expr, UnOp, TIME_TESTS};

/// A property as written: in the manifest or on the command line.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct PropertySource {
    pub name: String,
    pub kind: PropertyKind,
    /// For `leads_to`, both expressions as `P ~> Q`.
    pub expression: String,
    /// What a liveness property assumes the environment makes true infinitely often (each
    /// separately).
    pub fair: Vec<String>,
}

/// A property's expressions read but not yet resolved: its own (two for `leads_to`) and its
/// fairness assumptions.
#[derive(Clone, Debug)]
pub struct Parsed {
    pub main: Expr,
    /// `leads_to`'s Q.
    pub then: Option<Expr>,
    pub fair: Vec<Expr>,
}

impl Parsed {
    /// Every expression, for what the model must keep.
    pub fn exprs(&self) -> impl Iterator<Item = &Expr> {
        std::iter::once(&self.main)
            .chain(&self.then)
            .chain(&self.fair)
    }
}

/// A property read and resolved against a model.
#[derive(Clone, Debug)]
pub struct Property {
    pub source: PropertySource,
    term: Term,
    /// `leads_to`'s Q.
    then: Option<Term>,
    fair: Vec<Term>,
}

/// A property's expression resolved against the model (what [`crate::promela`] translates).
#[derive(Clone, Debug)]
pub(crate) enum Term {
    Const(Value),
    Slot(SlotId),
    Answer { theory: usize, output: usize },
    Running(usize),
    InState { machine: usize, state: u16 },
    Saw(usize),
    Not(Box<Term>),
    Neg(Box<Term>),
    And(Box<Term>, Box<Term>),
    Or(Box<Term>, Box<Term>),
    Binary(BinOp, Box<Term>, Box<Term>),
    Function(String, Vec<Term>),
}

/// Reads a property's expressions (names not yet resolved): `leads_to` needs its `~>`, and
/// only liveness properties may assume fairness.
pub fn parse(source: &PropertySource) -> Result<Parsed, PropertyError> {
    let error = |column: usize, message: String| PropertyError {
        property: source.name.clone(),
        column,
        message,
    };
    if !source.fair.is_empty() && !source.kind.is_liveness() {
        return Err(error(
            1,
            format!(
                "`fair` is an assumption of a liveness property, not of `{}`",
                source.kind.word()
            ),
        ));
    }
    let (main, then) = if source.kind == PropertyKind::LeadsTo {
        let Some(((p_at, p), (q_at, q))) = proclaim_behaviour::split_leads_to(&source.expression)
        else {
            return Err(error(
                1,
                "`leads_to` needs two expressions: `P ~> Q` (after every P, eventually Q)".into(),
            ));
        };
        let column = |at: usize| source.expression[..at].chars().count();
        (
            parse_text(&source.name, p, column(p_at))?,
            Some(parse_text(&source.name, q, column(q_at))?),
        )
    } else {
        (parse_text(&source.name, &source.expression, 0)?, None)
    };
    let fair = source
        .fair
        .iter()
        .map(|f| {
            parse_text(&source.name, f, 0).map_err(|mut e| {
                e.message = format!("in `fair {f}`: {}", e.message);
                e
            })
        })
        .collect::<Result<_, _>>()?;
    Ok(Parsed { main, then, fair })
}

/// Reads one expression of property `name`; an error's column counts from `shift` characters
/// before the text.
fn parse_text(name: &str, text: &str, shift: usize) -> Result<Expr, PropertyError> {
    let chars: Vec<char> = text.chars().collect();
    let mangled: String = chars
        .iter()
        .enumerate()
        .map(|(i, &c)| {
            let word = |j: Option<&char>| j.is_some_and(|c| c.is_alphanumeric() || *c == '_');
            let between_words = c == '.'
                && i > 0
                && word(chars.get(i - 1))
                && chars
                    .get(i + 1)
                    .is_some_and(|c| c.is_alphabetic() || *c == '_')
                && !chars[..i]
                    .iter()
                    .rev()
                    .take_while(|c| c.is_alphanumeric() || **c == '_')
                    .all(|c| c.is_ascii_digit());
            if between_words {
                DOT
            } else {
                c
            }
        })
        .collect();
    parse_expression(&mangled).map_err(|e| PropertyError {
        property: name.to_string(),
        column: shift + mangled[..e.offset.min(mangled.len())].chars().count() + 1,
        message: e.message,
    })
}

impl Property {
    /// Resolves `parsed` (from [`parse`]) against `model`, registering the `saw()` values the
    /// exploration must keep.
    pub fn compile(
        model: &mut Model,
        source: &PropertySource,
        parsed: &Parsed,
    ) -> Result<Property, PropertyError> {
        let mut compiler = Compiler {
            model,
            property: &source.name,
            text: &source.expression,
        };
        let term = compiler.truth(&parsed.main)?;
        let then = match &parsed.then {
            Some(e) => Some(compiler.truth(e)?),
            None => None,
        };
        let mut fair = Vec::new();
        for (text, e) in source.fair.iter().zip(&parsed.fair) {
            compiler.text = text;
            fair.push(compiler.truth(e).map_err(|mut error| {
                error.message = format!("in `fair {text}`: {}", error.message);
                error
            })?);
        }
        Ok(Property {
            source: source.clone(),
            term,
            then,
            fair,
        })
    }

    /// The resolved expression (`leads_to`'s P).
    pub(crate) fn term(&self) -> &Term {
        &self.term
    }

    /// `leads_to`'s Q, resolved.
    pub(crate) fn then_term(&self) -> Option<&Term> {
        self.then.as_ref()
    }

    /// The fairness assumptions, resolved.
    pub(crate) fn fair_terms(&self) -> &[Term] {
        &self.fair
    }

    /// Whether the property's expression (`leads_to`'s P) is true in `world`.
    pub fn holds_in(&self, model: &Search, world: &SystemState) -> bool {
        truth(&self.term, model, world)
    }

    /// Whether `leads_to`'s Q is true in `world` (false for the other kinds).
    pub fn then_holds_in(&self, model: &Search, world: &SystemState) -> bool {
        self.then.as_ref().is_some_and(|t| truth(t, model, world))
    }

    /// Whether fairness assumption `i` is true in `world`.
    pub fn fair_holds_in(&self, i: usize, model: &Search, world: &SystemState) -> bool {
        truth(&self.fair[i], model, world)
    }

    /// Whether `world` is what the property looks for: a violation of `never`/`always`, a
    /// witness of `reachable`; never for a liveness property, which no single state settles.
    pub fn is_target(&self, model: &Search, world: &SystemState) -> bool {
        match self.source.kind {
            PropertyKind::Never | PropertyKind::Reachable => self.holds_in(model, world),
            PropertyKind::Always => !self.holds_in(model, world),
            PropertyKind::Eventually | PropertyKind::LeadsTo | PropertyKind::AlwaysEventually => {
                false
            }
        }
    }
}

fn show_expr(e: &Expr) -> String {
    e.to_string().replace(DOT, ".")
}

struct Compiler<'a> {
    model: &'a mut Model,
    property: &'a str,
    /// The text the expression being compiled was read from, for columns.
    text: &'a str,
}

impl Compiler<'_> {
    fn error(&self, at: &Expr, message: String) -> PropertyError {
        PropertyError {
            property: self.property.to_string(),
            column: column_of(self.text, at),
            message,
        }
    }

    /// A whole expression of the property: a constant that is not a truth value is refused
    /// (legal as truthiness, but almost always a slip).
    fn truth(&mut self, expr: &Expr) -> Result<Term, PropertyError> {
        let (term, kind) = self.term(expr)?;
        if matches!(kind, ValueKind::Text | ValueKind::Number) && matches!(term, Term::Const(_)) {
            return Err(self.error(
                expr,
                format!("the property is the constant {}", show_expr(expr)),
            ));
        }
        Ok(term)
    }

    fn term(&mut self, e: &Expr) -> Result<(Term, ValueKind), PropertyError> {
        Ok(match e {
            Expr::Bool(b) => (Term::Const(Value::Bool(*b)), ValueKind::Truth),
            Expr::Int(i) => (Term::Const(Value::Int(*i)), ValueKind::Number),
            Expr::Float(x) => (Term::Const(Value::Float(*x)), ValueKind::Number),
            Expr::Str(s) => (Term::Const(Value::Str(s.clone())), ValueKind::Text),
            Expr::Duration(us) => (Term::Const(Value::Int(*us as i64)), ValueKind::Number),
            Expr::Name(n) => self.name(e, n)?,
            Expr::Unary {
                op: UnOp::Not,
                operand,
            } => (Term::Not(Box::new(self.term(operand)?.0)), ValueKind::Truth),
            Expr::Unary {
                op: UnOp::Neg,
                operand,
            } => {
                let (t, k) = self.term(operand)?;
                if matches!(k, ValueKind::Text | ValueKind::Truth) {
                    return Err(self.error(e, format!("`-` of {}", k.describe())));
                }
                (Term::Neg(Box::new(t)), ValueKind::Number)
            }
            Expr::Binary { op, left, right } => {
                let (l, lk) = self.term(left)?;
                let (r, rk) = self.term(right)?;
                let (l, r) = (Box::new(l), Box::new(r));
                match op {
                    BinOp::And => (Term::And(l, r), ValueKind::Truth),
                    BinOp::Or => (Term::Or(l, r), ValueKind::Truth),
                    BinOp::Eq | BinOp::Ne | BinOp::Lt | BinOp::Le | BinOp::Gt | BinOp::Ge => {
                        let ordered = !matches!(op, BinOp::Eq | BinOp::Ne);
                        let clash = match (lk, rk) {
                            (ValueKind::Any, _) | (_, ValueKind::Any) => false,
                            (a, b) if a == b => ordered && a == ValueKind::Truth,
                            _ => true,
                        };
                        if clash {
                            return Err(self.error(
                                e,
                                format!(
                                    "`{}` compares {} with {}",
                                    op.symbol(),
                                    lk.describe(),
                                    rk.describe()
                                ),
                            ));
                        }
                        (Term::Binary(*op, l, r), ValueKind::Truth)
                    }
                    _ => {
                        let joins_text =
                            *op == BinOp::Add && (lk == ValueKind::Text || rk == ValueKind::Text);
                        if !joins_text && (lk == ValueKind::Text || rk == ValueKind::Text) {
                            return Err(self.error(e, format!("`{}` on text", op.symbol())));
                        }
                        let kind = if joins_text {
                            ValueKind::Text
                        } else {
                            ValueKind::Number
                        };
                        (Term::Binary(*op, l, r), kind)
                    }
                }
            }
            Expr::Call {
                function,
                arguments,
                ..
            } => self.call(e, function, arguments)?,
        })
    }

    fn call(
        &mut self,
        e: &Expr,
        function: &str,
        arguments: &[Expr],
    ) -> Result<(Term, ValueKind), PropertyError> {
        if function == "saw" {
            let [Expr::Name(machine), seen] = arguments else {
                return Err(self.error(
                    e,
                    "`saw` takes a machine and what it read: saw(Machine, name)".into(),
                ));
            };
            let Some(m) = self.model.machine_index(machine) else {
                return Err(self.error(
                    &arguments[0],
                    format!("`{machine}` is no machine of the behaviour"),
                ));
            };
            // What it read resolves in the machine's own scope (its variables too).
            let mut unknown = None;
            seen.visit_names(&mut |n, _| {
                if unknown.is_none() && self.model.resolve(Some(m), n).is_none() {
                    unknown = Some(n.to_string());
                }
            });
            if let Some(n) = unknown {
                return Err(
                    self.error(seen, format!("`{n}` is nothing machine {machine} can read"))
                );
            }
            if seen.calls().iter().any(|(f, _)| is_time_test(f)) {
                return Err(self.error(seen, "a time test cannot be seen".into()));
            }
            let index = match self
                .model
                .saw
                .iter()
                .position(|(k, x)| *k == m && x == seen)
            {
                Some(i) => i,
                None => {
                    self.model.saw.push((m, seen.clone()));
                    self.model.saw.len() - 1
                }
            };
            return Ok((Term::Saw(index), ValueKind::Any));
        }
        if is_time_test(function) {
            return Err(self.error(
                e,
                format!("`{function}` speaks of a machine's time in its state: properties cannot use it"),
            ));
        }
        if !crate::arith::is_function(function) {
            return Err(self.error(e, format!("unknown function `{function}`")));
        }
        let mut terms = Vec::new();
        for a in arguments {
            terms.push(self.term(a)?.0);
        }
        Ok((
            Term::Function(function.to_string(), terms),
            ValueKind::Number,
        ))
    }

    fn name(&mut self, e: &Expr, name: &str) -> Result<(Term, ValueKind), PropertyError> {
        if let Some((machine, part)) = name.split_once(DOT) {
            let Some(m) = self.model.machine_index(machine) else {
                return Err(self.error(e, format!("`{machine}` is no machine of the behaviour")));
            };
            let mm = &self.model.machines[m];
            // A nested state is every flat state it lowers to, and a composite every state
            // inside it (`docs/spec/behaviour.md` §3.2).
            let part = &part.replace(DOT, ".");
            let flat = &mm.machine.states;
            let states = mm
                .states
                .iter()
                .enumerate()
                .filter(|(i, s)| {
                    s.name == *part
                        || flat
                            .get(*i)
                            .is_some_and(|f| mm.machine.state_is_in(f, part))
                })
                .map(|(s, _)| Term::InState {
                    machine: m,
                    state: s as u16,
                });
            if let Some(any) = states.reduce(|a, b| Term::Or(Box::new(a), Box::new(b))) {
                return Ok((any, ValueKind::Truth));
            }
            if let Some(&slot) = mm.locals.get(part) {
                return Ok((Term::Slot(slot), self.slot_kind(slot)));
            }
            let states: Vec<&str> = mm.states.iter().map(|s| s.name.as_str()).collect();
            return Err(self.error(
                e,
                format!(
                    "machine {machine} has no state or variable `{part}` (its states: {})",
                    states.join(", ")
                ),
            ));
        }
        match self.model.resolve(None, name) {
            Some(Name::Slot(slot)) => Ok((Term::Slot(slot), self.slot_kind(slot))),
            Some(Name::Answer { theory, output }) => {
                Ok((Term::Answer { theory, output }, ValueKind::Truth))
            }
            Some(Name::Running(m)) => Ok((Term::Running(m), ValueKind::Truth)),
            None if self.model.machine_index(name).is_some() => Err(self.error(
                e,
                format!("`{name}` is a machine: write {name}.STATE for \"in that state\""),
            )),
            None => Err(self.error(
                e,
                format!(
                    "unknown name `{name}`: no variable, whiteboard type or reasoner answer of the behaviour"
                ),
            )),
        }
    }

    fn slot_kind(&self, slot: SlotId) -> ValueKind {
        let s = &self.model.slots[slot];
        match &s.kind {
            SlotKind::Local { ty, .. } => match ty {
                proclaim_fsm::VarType::Bool => ValueKind::Truth,
                proclaim_fsm::VarType::Named(_) => ValueKind::Any,
                _ => ValueKind::Number,
            },
            SlotKind::Global => ValueKind::Any,
            SlotKind::Message { .. } => s.value_kind,
        }
    }
}

fn is_time_test(function: &str) -> bool {
    TIME_TESTS.iter().any(|(f, _)| *f == function)
}

/// The column (1-based, in characters) of the first name `at` reads, or of its first call, in
/// the property's text; 1 when it cannot be found.
fn column_of(text: &str, at: &Expr) -> usize {
    let mut needle = None;
    at.visit_names(&mut |n, _| {
        needle.get_or_insert_with(|| n.replace(DOT, "."));
    });
    if needle.is_none() {
        needle = at.calls().first().map(|(f, _)| f.to_string());
    }
    let Some(needle) = needle else { return 1 };
    let bytes = text.as_bytes();
    let word = |b: u8| b.is_ascii_alphanumeric() || b == b'_';
    let mut from = 0;
    while let Some(i) = text[from..].find(&needle) {
        let start = from + i;
        let end = start + needle.len();
        let before_ok = start == 0 || !word(bytes[start - 1]);
        let after_ok = end >= bytes.len() || !word(bytes[end]);
        if before_ok && after_ok {
            return text[..start].chars().count() + 1;
        }
        from = start + needle.chars().next().map_or(1, char::len_utf8);
    }
    1
}

/// A term's value in `world`.
fn value(term: &Term, model: &Search, world: &SystemState) -> Option<Value> {
    match term {
        Term::Const(v) => Some(v.clone()),
        Term::Slot(slot) => slot_value(model, &world.values, *slot),
        Term::Answer { theory, output } => {
            Some(Value::Bool(answer(model, world, *theory, *output, 0)))
        }
        Term::Running(m) => Some(Value::Bool(world.machines[*m].status == Status::Running)),
        Term::InState { machine, state } => {
            let c = &world.machines[*machine];
            Some(Value::Bool(
                c.status == Status::Running && c.state == *state,
            ))
        }
        Term::Saw(i) => model.values.borrow().get(world.saw[*i]).cloned(),
        Term::Not(t) => Some(Value::Bool(!truth(t, model, world))),
        Term::Neg(t) => crate::arith::negate(&value(t, model, world)?),
        Term::And(l, r) => Some(Value::Bool(
            truth(l, model, world) && truth(r, model, world),
        )),
        Term::Or(l, r) => Some(Value::Bool(
            truth(l, model, world) || truth(r, model, world),
        )),
        Term::Binary(op, l, r) => {
            crate::arith::binary(*op, value(l, model, world), value(r, model, world))
        }
        Term::Function(f, args) => {
            let args: Vec<Option<Value>> = args.iter().map(|a| value(a, model, world)).collect();
            crate::arith::function(f, &args)
        }
    }
}

fn truth(term: &Term, model: &Search, world: &SystemState) -> bool {
    value(term, model, world).is_some_and(|v| v.truthy())
}

fn slot_value(model: &Search, values: &[ValueId], slot: SlotId) -> Option<Value> {
    match model.values.borrow().get(values[slot]).cloned() {
        None if model.slots[slot].kind == (SlotKind::Message { external: true }) => {
            Some(Value::Int(0))
        }
        v => v,
    }
}

fn answer(model: &Search, world: &SystemState, theory: usize, output: usize, depth: usize) -> bool {
    let t = &model.theories[theory];
    let inputs: Vec<Input> = t
        .inputs
        .iter()
        .map(|(_, name)| match name {
            Some(Name::Slot(s)) => input(slot_value(model, &world.values, *s).as_ref()),
            Some(Name::Answer { theory, output }) if depth < 8 => {
                Input::Value(answer(model, world, *theory, *output, depth + 1))
            }
            Some(Name::Running(m)) => Input::Value(world.machines[*m].status == Status::Running),
            _ => Input::Unknown,
        })
        .collect();
    model.reasoner(theory).answers(&inputs)[output]
}

#[cfg(test)]
mod tests {
    use super::*;

    fn check(text: &str, expect: Result<&str, usize>) {
        let source = PropertySource {
            name: "p".into(),
            kind: PropertyKind::Never,
            expression: text.into(),
            fair: Vec::new(),
        };
        match (parse(&source), expect) {
            (Ok(e), Ok(shown)) => assert_eq!(show_expr(&e.main), shown, "{text}"),
            (Err(e), Err(column)) => assert_eq!(e.column, column, "{text}: {e}"),
            (got, want) => panic!("{text}: got {got:?}, want {want:?}"),
        }
    }

    #[test]
    fn dotted_names_parse_and_errors_keep_their_column() {
        check(
            "Microwave.COOKING && doorOpen",
            Ok("Microwave.COOKING && doorOpen"),
        );
        check(
            "saw(Microwave, doorOpen) && Magnetron == \"on\"",
            Ok("saw(Microwave, doorOpen) && Magnetron == \"on\""),
        );
        check("x < 2.5", Ok("x < 2.5"));
        check("Pump.RUNNING && && methaneHigh", Err(17));
        check("Pump.RUNNING )", Err(14));
    }

    #[test]
    fn columns_point_at_the_name() {
        let e = parse_expression("b").expect("parses");
        assert_eq!(column_of("ab && b", &e), 7);
        let e = Expr::Name(format!("Pump{DOT}X"));
        assert_eq!(column_of("x && Pump.X", &e), 6);
        // Names may be any letters; columns count characters, not bytes.
        let e = Expr::Name("été".into());
        assert_eq!(column_of("étés || été", &e), 9);
    }
}
