//! The model [`crate::verify`] explores, written as Promela so that SPIN checks the very same
//! thing: the same machines, schedule, environment, reasoners and time bits, over the same
//! value numbers.
//!
//! - **State.** Per machine its state, mode (0 running, 1 suspended, 2 dormant), just-entered
//!   and started-this-round bits and due time bits (arrays `st`, `mode`, `je`, `fresh`, `due`),
//!   and where machines' clocks are ordered what orders them (`promela_clocks.rs`);
//!   `turn`; every slot (`s<i>`) and every `saw()` value (`saw<i>`) as a **value number** of the
//!   model's [`crate::values::Values`] (0 never posted); that is [`crate::world::SystemState`] field by
//!   field.
//! - **Values.** The numbers are those the machines' ringlets can write, found to a fixpoint
//!   with no search (as the symbolic engine finds its fields' values; a bounded exploration
//!   numbers them only where a slot's values keep growing), plus every constant the activities
//!   and properties name. Operators, conversions and built-in functions are tables
//!   over those numbers computed with [`crate::arith`], the checker's semantics; a result no
//!   number stands for is `BEYOND`, and every step asserts that no variable holds it, so a
//!   value the checker never met is SPIN's assertion error rather than a silent disagreement.
//! - **Reasoners.** One table per answer, indexed by the inputs' valuation (unknown, false,
//!   true per input, base 3), each entry proved by the engine ([`crate::reasoner`]).
//! - **One step is one ringlet**, as in [`crate::ringlet`]: a `d_step` picks the machine whose
//!   turn it is and runs its OnEntry (noting the free types it read or posted: `tch<i>`); the
//!   snapshot's choices (which time tests came due, what the noted free types now hold) are
//!   `if` choices; a `d_step` records `saw()`, tries the transitions in priority order and
//!   runs OnExit or Internal and the machine's commands to itself; then the environment sets
//!   every free type (`if` choices); a last `d_step` evaluates the properties (`hit<i>`).
//! - **Liveness properties** are `ltl` claims over bits set at the end of a step (`lp<i>`,
//!   `lq<i>`, `fair<i>_<j>`, and `acc[k]`: a clock of a machine lets time pass, see
//!   [`crate::acceptance`]),
//!   which keep their value through the next step's parts, so SPIN's extra states only repeat
//!   a checker state (LTL without next cannot tell). The fairness is the antecedent:
//!   `([]<> acc[0] && …) -> <> lp<i>`; once no machine can ring every acceptance bit is set
//!   and SPIN's stutter extension repeats that state for ever. Checked by `pan -a`.
//! - **Safety properties** are one `ltl` claim each, `[] !hit<i>`, where `hit<i>` is set only at the
//!   end of a step (the states between a step's parts are SPIN's, not the checker's, and never
//!   hit): for `never P` hit is P, for `always P` it is !P, for `reachable P` it is P, so a
//!   violation is the witness. Run `pan -N p<i>` per property; [`Claim::verdict`] reads the
//!   answer. Everything the search needs is safety: compile `pan.c` with `-DSAFETY`.
//!
//! The tables and temporaries are `hidden` (outside SPIN's state vector), so SPIN's breadth
//! first mode (`-DBFS`), which refuses hidden variables, is not available; depth first it is.

use crate::arith::{self, text};
use crate::model::{Name, SlotKind};
use crate::property::{Property, Term};
use crate::reasoner::{input, Input};
use crate::search::Search;
use crate::values::{ValueId, NEVER};
use crate::{explore, prepare, Options, PropertySource, Reductions, Verdict, VerifyError};
use proclaim_behaviour::{Behaviour, PropertyKind};
use proclaim_board::Value;
use proclaim_fsm::control::Command;
use proclaim_fsm::{Action, BinOp, Expr, ForLoop, Statement, UnOp, VarType, TIME_TESTS};
use proclaim_lower::builtin::{builtin, Builtin, Content, Target};
use proclaim_lower::{read_statement, RingletPlan, StatementReader, LOOP_LIMIT};
use std::fmt::{self, Write};

/// Why a behaviour cannot be written as Promela.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum EmitError {
    /// The behaviour or a property cannot be checked at all.
    Verify(VerifyError),
    /// Something the checker models that this translation does not write, and where.
    Unsupported { machine: String, what: String },
}

impl fmt::Display for EmitError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            EmitError::Verify(e) => e.fmt(f),
            EmitError::Unsupported { machine, what } => {
                write!(f, "cannot write machine {machine} as Promela: {what}")
            }
        }
    }
}

impl std::error::Error for EmitError {}

impl From<VerifyError> for EmitError {
    fn from(e: VerifyError) -> EmitError {
        EmitError::Verify(e)
    }
}

/// A property as an `ltl` claim of the Promela text.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Claim {
    /// The claim's name: `pan -N <name>` checks it.
    pub name: String,
    pub property: String,
    pub kind: PropertyKind,
}

impl Claim {
    /// The property's verdict from SPIN's search of this claim: `violated` when `pan` found
    /// an error, `complete` when its search was not cut short. A violation of a `reachable`
    /// claim is its witness.
    pub fn verdict(&self, violated: bool, complete: bool) -> Verdict {
        match (self.kind, violated, complete) {
            (PropertyKind::Reachable, true, _) => Verdict::Holds,
            (_, true, _) => Verdict::Fails,
            (_, false, false) => Verdict::Incomplete,
            (PropertyKind::Reachable, false, true) => Verdict::Fails,
            (_, false, true) => Verdict::Holds,
        }
    }
}

/// A behaviour and its properties as Promela.
#[derive(Clone, Debug)]
pub struct Promela {
    pub text: String,
    /// One per property, in the order given.
    pub claims: Vec<Claim>,
    /// Every value a run can meet is numbered (if not, SPIN may meet a value beyond them and
    /// report an assertion error).
    pub values_complete: bool,
}

/// Where the table filling goes, before the initial step, once every value is numbered.
const TABLES: &str = "TABLES";

/// At most this many assignments in one `d_step` (SPIN refuses a sequence of a few thousand).
const FILL_PER_STEP: usize = 1000;

/// The table filling as `d_step`s of at most [`FILL_PER_STEP`] assignments each.
fn table_steps(fill: &str) -> String {
    let assignments: Vec<&str> = fill.split_inclusive("; ").collect();
    assignments
        .chunks(FILL_PER_STEP)
        .map(|chunk| format!("d_step {{ {} }};", chunk.concat().trim_end()))
        .collect::<Vec<_>>()
        .join("\n  ")
}

/// Reasoner tables above this many entries (3 to the number of inputs) are refused.
const MAX_VALUATIONS: usize = 3usize.pow(12);

/// The Promela of `behaviour` with `properties` (see the module's documentation); `options`
/// bound the exploration that numbers the values.
pub fn to_promela(
    behaviour: &Behaviour,
    properties: &[PropertySource],
    options: Options,
) -> Result<Promela, EmitError> {
    // The ordered model: what verify's verdicts are of, once those a run decided are checked
    // again ordered (`refine.rs`); SPIN searches it whole.
    let (model, compiled) = prepare(behaviour, properties, true)?;
    crate::check_stored_free(&model)?;
    let model = Search::new(&model);
    // The values are numbered from the machines' ringlets to a fixpoint, with no search; only
    // where a slot's values keep growing (a counter) does a bounded search number them.
    let values_complete = crate::symbolic::number_values(&model).is_ok()
        || explore::explore(
            &model,
            &compiled,
            Options {
                reductions: Reductions::NONE,
                ..options
            }
            .limits(),
            &mut |_| {},
        )
        .complete;
    // Writing numbers the constants it meets and learns how many commands a machine may send
    // itself in a ringlet; the text is final once a pass adds neither.
    let mut queue = 0;
    loop {
        let known = model.values.borrow().len();
        let mut writer = Writer::new(&model, queue);
        let text = writer.write(&behaviour.name, &compiled, values_complete)?;
        if model.values.borrow().len() == known && writer.most_self_posts == queue {
            let claims = compiled
                .iter()
                .enumerate()
                .map(|(i, p)| Claim {
                    name: format!("p{i}"),
                    property: p.source.name.clone(),
                    kind: p.source.kind,
                })
                .collect();
            return Ok(Promela {
                text,
                claims,
                values_complete,
            });
        }
        queue = writer.most_self_posts;
    }
}

/// A value number or Promela code computing one.
#[derive(Clone, Debug)]
enum Operand {
    Const(ValueId),
    Code(String),
    /// A Promela truth standing for the value `true` or `false` (numbers `yes` and `no`),
    /// kept as a truth so that testing it again costs no table.
    Truth {
        truth: String,
        yes: ValueId,
        no: ValueId,
    },
}

impl Operand {
    fn code(&self) -> String {
        match self {
            Operand::Const(id) => id.to_string(),
            Operand::Code(c) => c.clone(),
            Operand::Truth { truth, yes, no } => format!("({truth} -> {yes} : {no})"),
        }
    }
}

/// A table over value numbers, and what it holds.
#[derive(Clone, Debug, PartialEq)]
enum Table {
    /// Truth of a value (a bit).
    Truthy,
    /// A reasoner input's digit: 0 unknown, 1 false, 2 true.
    Input,
    Neg,
    /// What a variable of the type holds when the value is assigned.
    Convert(VarType),
    /// `say(x)`: the value as text.
    Text,
    /// `post_int(T, x)`: the value as a whole number.
    PostInt,
    /// `c op x` for constant `c`.
    Left(BinOp, ValueId),
    /// `x op c` for constant `c`.
    Right(BinOp, ValueId),
    /// `x op y`, indexed `x * VALUES + y`.
    Both(BinOp),
    Function1(String),
    /// `f(x, y)`, indexed as [`Table::Both`].
    Function2(String),
    /// `post(T, a, b)`'s text: both parts' texts, the empty ones left out, joined by a space.
    Join,
}

impl Table {
    fn two_dimensional(&self) -> bool {
        matches!(self, Table::Both(_) | Table::Function2(_) | Table::Join)
    }

    fn describe(&self) -> String {
        match self {
            Table::Truthy => "truth of a value".into(),
            Table::Input => "reasoner input: 0 unknown, 1 false, 2 true".into(),
            Table::Neg => "-x".into(),
            Table::Convert(ty) => format!("assigned to a variable of type {ty:?}"),
            Table::Text => "the value as text".into(),
            Table::PostInt => "the value as a whole number".into(),
            Table::Left(op, c) => format!("#{c} {} x", op.symbol()),
            Table::Right(op, c) => format!("x {} #{c}", op.symbol()),
            Table::Both(op) => format!("x {} y", op.symbol()),
            Table::Function1(f) => format!("{f}(x)"),
            Table::Function2(f) => format!("{f}(x, y)"),
            Table::Join => "post(T, x, y)'s text".into(),
        }
    }
}

/// A table entry before it is numbered.
enum Entry {
    /// A truth or an input digit, stored as it is.
    Number(ValueId),
    Value(Option<Value>),
}

/// Writes one pass of the Promela text.
struct Writer<'m> {
    model: &'m Search<'m>,
    out: String,
    depth: usize,
    tables: Vec<Table>,
    /// Hidden `int` temporaries used.
    temps: usize,
    /// The machine whose code is written, and its state.
    machine: usize,
    state: usize,
    /// Writing an OnEntry: reads and posts of free types are noted.
    noting: bool,
    /// Inside a `for` loop.
    in_loop: usize,
    /// Commands to the machine itself written so far for the current machine.
    self_posts: usize,
    most_self_posts: usize,
    /// Length of the queue of commands a machine sends itself (from the previous pass).
    queue: usize,
}

impl<'m> Writer<'m> {
    fn new(model: &'m Search<'m>, queue: usize) -> Writer<'m> {
        Writer {
            model,
            out: String::new(),
            depth: 0,
            tables: Vec::new(),
            temps: 0,
            machine: 0,
            state: 0,
            noting: false,
            in_loop: 0,
            self_posts: 0,
            most_self_posts: 0,
            queue,
        }
    }

    fn line(&mut self, text: &str) {
        for _ in 0..self.depth {
            self.out.push_str("  ");
        }
        self.out.push_str(text);
        self.out.push('\n');
    }

    fn unsupported(&self, what: String) -> EmitError {
        EmitError::Unsupported {
            machine: self.model.machines[self.machine].name.clone(),
            what,
        }
    }

    fn id(&self, value: &Value) -> ValueId {
        self.model.values.borrow_mut().intern(value)
    }

    fn id_of(&self, value: Option<&Value>) -> ValueId {
        self.model.values.borrow_mut().intern_option(value)
    }

    fn value_of(&self, id: ValueId) -> Option<Value> {
        self.model.values.borrow().get(id).cloned()
    }

    fn temp(&mut self) -> String {
        self.temps += 1;
        format!("t{}", self.temps - 1)
    }

    fn table(&mut self, table: Table) -> String {
        let i = match self.tables.iter().position(|t| *t == table) {
            Some(i) => i,
            None => {
                self.tables.push(table);
                self.tables.len() - 1
            }
        };
        format!("tab{i}")
    }

    /// A truth as a value number.
    fn of_truth(&self, truth: String) -> Operand {
        let (t, f) = (self.id(&Value::Bool(true)), self.id(&Value::Bool(false)));
        match truth.as_str() {
            "1" => Operand::Const(t),
            "0" => Operand::Const(f),
            _ => Operand::Truth {
                truth,
                yes: t,
                no: f,
            },
        }
    }

    /// A table of one argument applied to `x` (computed now when `x` is a constant).
    fn unary(&mut self, table: Table, x: Operand) -> Operand {
        match x {
            Operand::Const(id) => Operand::Const(self.fold1(&table, id)),
            code => Operand::Code(format!("{}[{}]", self.table(table), code.code())),
        }
    }

    fn binary(&mut self, op: BinOp, l: Operand, r: Operand) -> Operand {
        match (l, r) {
            (Operand::Const(a), Operand::Const(b)) => {
                let v = arith::binary(op, self.value_of(a), self.value_of(b));
                Operand::Const(self.id_of(v.as_ref()))
            }
            (Operand::Const(a), r) => self.unary(Table::Left(op, a), r),
            (l, Operand::Const(b)) => self.unary(Table::Right(op, b), l),
            (l, r) => self.two(Table::Both(op), l, r),
        }
    }

    fn two(&mut self, table: Table, l: Operand, r: Operand) -> Operand {
        if let (Operand::Const(a), Operand::Const(b)) = (&l, &r) {
            let v = self.entry2(&table, self.value_of(*a), self.value_of(*b));
            return self.fold_constant(v);
        }
        let name = self.table(table);
        Operand::Code(format!("{name}[({})*VALUES+({})]", l.code(), r.code()))
    }

    /// A one-argument table's entry on a value, with the checker's semantics: a truth or an
    /// input digit, or a value.
    fn entry1(&self, table: &Table, v: Option<Value>) -> Entry {
        let zero_if_never = || v.clone().unwrap_or(Value::Int(0));
        Entry::Value(match table {
            Table::Truthy => return Entry::Number(ValueId::from(v.is_some_and(|v| v.truthy()))),
            Table::Input => {
                return Entry::Number(match input(v.as_ref()) {
                    Input::Unknown => 0,
                    Input::Value(false) => 1,
                    Input::Value(true) => 2,
                })
            }
            Table::Neg => v.as_ref().and_then(arith::negate),
            Table::Convert(ty) => Some(arith::convert(ty, zero_if_never())),
            Table::Text => Some(Value::Str(text(&zero_if_never()))),
            Table::PostInt => Some(match zero_if_never() {
                Value::Int(i) => Value::Int(i),
                other => Value::Int(other.as_f64().unwrap_or(0.0) as i64),
            }),
            Table::Left(op, c) => arith::binary(*op, self.value_of(*c), v),
            Table::Right(op, c) => arith::binary(*op, v, self.value_of(*c)),
            Table::Function1(f) => arith::function(f, &[v]),
            Table::Both(_) | Table::Function2(_) | Table::Join => None,
        })
    }

    /// A two-argument table's entry on two values.
    fn entry2(&self, table: &Table, x: Option<Value>, y: Option<Value>) -> Option<Value> {
        match table {
            Table::Both(op) => arith::binary(*op, x, y),
            Table::Function2(f) => arith::function(f, &[x, y]),
            Table::Join => {
                let parts: Vec<String> = [x, y]
                    .iter()
                    .map(|v| text(&v.clone().unwrap_or(Value::Int(0))))
                    .filter(|t| !t.is_empty())
                    .collect();
                Some(Value::Str(parts.join(" ")))
            }
            _ => None,
        }
    }

    /// The number of a table's result when it has one (an unnumbered value is `BEYOND`).
    fn lookup(&self, value: Option<Value>) -> Option<ValueId> {
        match value {
            None => Some(NEVER),
            Some(v) => self.model.values.borrow().find(&v),
        }
    }

    /// A one-argument table's entry for value number `id`, as stored in the table.
    fn apply1(&self, table: &Table, id: ValueId) -> Option<ValueId> {
        match self.entry1(table, self.value_of(id)) {
            Entry::Number(n) => Some(n),
            Entry::Value(v) => self.lookup(v),
        }
    }

    /// A computed constant's number (numbered when new).
    fn fold_constant(&self, value: Option<Value>) -> Operand {
        Operand::Const(self.id_of(value.as_ref()))
    }

    /// A one-argument table on a constant, computed now (a new result is numbered).
    fn fold1(&self, table: &Table, id: ValueId) -> ValueId {
        match self.entry1(table, self.value_of(id)) {
            Entry::Number(n) => n,
            Entry::Value(v) => self.id_of(v.as_ref()),
        }
    }

    // ----- expressions of a machine, as its ringlet reads them -----

    /// Promela truth of `e` (0 or 1 when known now).
    fn truth(&mut self, e: &Expr) -> Result<String, EmitError> {
        match e {
            Expr::Unary {
                op: UnOp::Not,
                operand,
            } => {
                let t = self.truth(operand)?;
                Ok(match t.as_str() {
                    "1" => "0".into(),
                    "0" => "1".into(),
                    _ => format!("!({t})"),
                })
            }
            Expr::Binary {
                op: op @ (BinOp::And | BinOp::Or),
                left,
                right,
            } => {
                let l = self.truth(left)?;
                let outer = std::mem::take(&mut self.out);
                let r = self.truth(right)?;
                let right_code = std::mem::replace(&mut self.out, outer);
                let and = *op == BinOp::And;
                if right_code.is_empty() {
                    let joiner = if and { "&&" } else { "||" };
                    return Ok(format!("({l} {joiner} {r})"));
                }
                // The right side notes what it reads only when it is evaluated.
                let t = self.temp();
                self.line(&format!("{t} = {l};"));
                self.line("if");
                let guard = if and { t.clone() } else { format!("!{t}") };
                self.line(&format!(":: {guard} ->"));
                self.out.push_str(&right_code);
                self.depth += 1;
                self.line(&format!("{t} = {r};"));
                self.depth -= 1;
                self.line(":: else -> skip;");
                self.line("fi;");
                Ok(format!("({t} != 0)"))
            }
            _ => {
                let v = self.value(e)?;
                Ok(self.truthy(v))
            }
        }
    }

    fn truthy(&mut self, v: Operand) -> String {
        match v {
            Operand::Const(id) => {
                let b = self.value_of(id).is_some_and(|v| v.truthy());
                if b { "1" } else { "0" }.into()
            }
            Operand::Truth { truth, .. } => truth,
            Operand::Code(c) => format!("{}[{c}]", self.table(Table::Truthy)),
        }
    }

    fn value(&mut self, e: &Expr) -> Result<Operand, EmitError> {
        Ok(match e {
            Expr::Bool(b) => Operand::Const(self.id(&Value::Bool(*b))),
            Expr::Int(i) => Operand::Const(self.id(&Value::Int(*i))),
            Expr::Float(x) => Operand::Const(self.id(&Value::Float(*x))),
            Expr::Str(s) => Operand::Const(self.id(&Value::Str(s.clone()))),
            Expr::Duration(us) => Operand::Const(self.id(&Value::Int(*us as i64))),
            Expr::Name(n) => match self.model.resolve(Some(self.machine), n) {
                None => Operand::Const(NEVER),
                Some(name) => self.name_value(name),
            },
            Expr::Unary { op: UnOp::Not, .. }
            | Expr::Binary {
                op: BinOp::And | BinOp::Or,
                ..
            } => {
                let t = self.truth(e)?;
                self.of_truth(t)
            }
            Expr::Unary {
                op: UnOp::Neg,
                operand,
            } => {
                let v = self.value(operand)?;
                self.unary(Table::Neg, v)
            }
            Expr::Binary { op, left, right } => {
                let l = self.value(left)?;
                let r = self.value(right)?;
                self.binary(*op, l, r)
            }
            Expr::Call {
                function,
                arguments,
                ..
            } => {
                if TIME_TESTS.iter().any(|(f, _)| f == function) {
                    let t = self.time_due(e);
                    return Ok(self.of_truth(t));
                }
                let mut args = Vec::new();
                for a in arguments {
                    args.push(self.value(a)?);
                }
                self.function(function, args)
            }
        })
    }

    fn function(&mut self, function: &str, args: Vec<Operand>) -> Operand {
        if !arith::is_function(function) {
            // A host function's result is nothing the model knows.
            return Operand::Const(NEVER);
        }
        match <[Operand; 2]>::try_from(args) {
            Ok([x, y]) => {
                if let (Operand::Const(a), Operand::Const(b)) = (&x, &y) {
                    let v = arith::function(function, &[self.value_of(*a), self.value_of(*b)]);
                    return self.fold_constant(v);
                }
                self.two(Table::Function2(function.into()), x, y)
            }
            Err(args) => match <[Operand; 1]>::try_from(args) {
                Ok([Operand::Const(a)]) => {
                    let v = arith::function(function, &[self.value_of(a)]);
                    self.fold_constant(v)
                }
                Ok([x]) => self.unary(Table::Function1(function.into()), x),
                Err(_) => Operand::Const(NEVER),
            },
        }
    }

    /// Whether a time test of the current state is due (one no label has never is).
    fn time_due(&self, call: &Expr) -> String {
        let k = self.machine;
        let tests = &self.model.machines[k].states[self.state].time_tests;
        match tests.iter().position(|t| t.call == *call) {
            Some(i) => format!("((due[{k}] >> {i}) & 1)"),
            None => "0".into(),
        }
    }

    fn slot_code(&mut self, slot: usize) -> Operand {
        let s = &self.model.slots[slot];
        if self.noting && s.free.is_some() {
            self.line(&format!("tch{slot} = 1;"));
        }
        if s.kind == (SlotKind::Message { external: true }) {
            // An extern reads 0 before anything is posted.
            let zero = self.id(&Value::Int(0));
            Operand::Code(format!("(s{slot} == {NEVER} -> {zero} : s{slot})"))
        } else {
            Operand::Code(format!("s{slot}"))
        }
    }

    fn name_value(&mut self, name: Name) -> Operand {
        match name {
            Name::Slot(slot) => self.slot_code(slot),
            Name::Answer { theory, output } => {
                let t = self.answer(theory, output, 0);
                self.of_truth(t)
            }
            Name::Running(m) => self.of_truth(format!("(mode[{m}] == 0)")),
        }
    }

    /// A reasoner's answer on the inputs as read now: its table at their valuation.
    fn answer(&mut self, theory: usize, output: usize, depth: usize) -> String {
        let inputs = self.model.theories[theory].inputs.clone();
        let mut index = Vec::new();
        for (i, (_, name)) in inputs.iter().enumerate() {
            let digit = match name {
                Some(Name::Answer { theory, output }) if depth < 8 => {
                    format!("({} -> 2 : 1)", self.answer(*theory, *output, depth + 1))
                }
                Some(n @ (Name::Slot(_) | Name::Running(_))) => match self.name_value(*n) {
                    Operand::Const(id) => self.fold1(&Table::Input, id).to_string(),
                    Operand::Truth { truth, .. } => format!("({truth} -> 2 : 1)"),
                    code => format!("{}[{}]", self.table(Table::Input), code.code()),
                },
                _ => "0".into(),
            };
            index.push(format!("{digit}*{}", 3usize.pow(i as u32)));
        }
        if index.is_empty() {
            index.push("0".into());
        }
        format!("ans{theory}_{output}[{}]", index.join(" + "))
    }

    // ----- activities -----

    fn run(&mut self, actions: &[Action]) -> Result<(), EmitError> {
        for action in actions {
            match action {
                Action::Post { ty, content } => {
                    let v = Operand::Const(self.id(&Value::parse(content)));
                    self.post(ty, &v)?;
                }
                Action::Statement(s) => self.exec(s)?,
                // Host functions change nothing a machine reads; unread code does nothing.
                Action::Call { .. } | Action::Code(_) => {}
            }
        }
        Ok(())
    }

    fn exec(&mut self, statement: &Statement) -> Result<(), EmitError> {
        read_statement(&mut Exec(self), statement)
    }

    /// A `for` loop as a Promela `do`, stopped at the runner's [`LOOP_LIMIT`].
    fn for_loop(&mut self, parts: ForLoop<'_>) -> Result<(), EmitError> {
        if let Some(init) = parts.init {
            self.exec(init)?;
        }
        let rounds = self.temp();
        self.line(&format!("{rounds} = 0;"));
        self.line("do");
        self.line(":: true ->");
        self.depth += 1;
        let go = match parts.condition {
            Some(c) => self.truth(c)?,
            None => "1".into(),
        };
        self.line("if");
        self.line(&format!(":: ({go}) && {rounds} < {LOOP_LIMIT} ->"));
        self.depth += 1;
        self.line(&format!("{rounds}++;"));
        self.in_loop += 1;
        self.exec(parts.body)?;
        if let Some(step) = parts.step {
            self.exec(step)?;
        }
        self.in_loop -= 1;
        self.depth -= 1;
        self.line(":: else -> break;");
        self.line("fi;");
        self.depth -= 1;
        self.line("od;");
        Ok(())
    }

    /// `v`, or the number 0 where it is no value (an assignment of nothing assigns 0).
    fn or_zero(&mut self, v: Operand) -> Operand {
        let zero = self.id(&Value::Int(0));
        match v {
            Operand::Const(NEVER) => Operand::Const(zero),
            Operand::Const(id) => Operand::Const(id),
            code => {
                let t = self.temp();
                self.line(&format!("{t} = {};", code.code()));
                self.line(&format!(
                    "if :: {t} == {NEVER} -> {t} = {zero}; :: else -> skip; fi;"
                ));
                Operand::Code(t)
            }
        }
    }

    /// Keeps a computed value in a temporary when it will be used more than once.
    fn settle(&mut self, v: Operand) -> Operand {
        match &v {
            Operand::Code(c) if is_temp(c) => v,
            Operand::Code(_) | Operand::Truth { .. } => {
                let t = self.temp();
                self.line(&format!("{t} = {};", v.code()));
                Operand::Code(t)
            }
            Operand::Const(_) => v,
        }
    }

    fn assign(&mut self, name: &str, v: Operand) -> Result<(), EmitError> {
        match self.model.resolve(Some(self.machine), name) {
            Some(Name::Slot(slot)) => match &self.model.slots[slot].kind {
                SlotKind::Local { ty, .. } => {
                    let c = self.unary(Table::Convert(ty.clone()), v);
                    self.line(&format!("s{slot} = {};", c.code()));
                }
                SlotKind::Global => self.line(&format!("s{slot} = {};", v.code())),
                SlotKind::Message { .. } => self.post(name, &v)?,
            },
            _ => self.post(name, &v)?,
        }
        Ok(())
    }

    /// A posting to type `ty` (a constant name): a command to a machine, or a whiteboard
    /// value; nothing when nothing models the type.
    fn post(&mut self, ty: &str, v: &Operand) -> Result<(), EmitError> {
        if let Some(j) = self.model.machine_index(ty) {
            let word = |value: Option<Value>| match value {
                Some(Value::Str(s)) => Command::parse(&s),
                Some(other) => Command::parse(&other.to_string()),
                None => None,
            };
            match v {
                Operand::Const(id) => {
                    if let Some(command) = word(self.value_of(*id)) {
                        self.command(j, command)?;
                    }
                }
                code => {
                    let c = code.code();
                    let count = self.model.values.borrow().len() as ValueId;
                    let words: Vec<(ValueId, Command)> = (1..=count)
                        .filter_map(|id| Some((id, word(self.value_of(id))?)))
                        .collect();
                    self.line("if");
                    for (id, command) in words {
                        self.line(&format!(":: {c} == {id} ->"));
                        self.depth += 1;
                        self.command(j, command)?;
                        self.depth -= 1;
                    }
                    self.line(":: else -> skip;");
                    self.line("fi;");
                }
            }
            return Ok(());
        }
        if let Some(Name::Slot(slot)) = self.model.names.get(ty) {
            let s = &self.model.slots[*slot];
            if matches!(s.kind, SlotKind::Message { .. }) {
                if self.noting && s.free.is_some() {
                    self.line(&format!("tch{slot} = 1;"));
                }
                self.line(&format!("s{slot} = {};", v.code()));
            }
        }
        Ok(())
    }

    /// A posting whose type is computed: the type is the value's text.
    fn post_to(&mut self, ty: Operand, v: Operand) -> Result<(), EmitError> {
        let type_name = |value: Option<Value>| text(&value.unwrap_or(Value::Int(0)));
        match ty {
            Operand::Const(id) => {
                let name = type_name(self.value_of(id));
                self.post(&name, &v)
            }
            code => {
                let c = code.code();
                let v = self.settle(v);
                let count = self.model.values.borrow().len() as ValueId;
                let model = self.model;
                let targets: Vec<(ValueId, String)> = (0..=count)
                    .map(|id| (id, type_name(self.value_of(id))))
                    .filter(|(_, name)| {
                        model.machine_index(name).is_some()
                            || matches!(model.names.get(name), Some(Name::Slot(s))
                                if matches!(model.slots[*s].kind, SlotKind::Message { .. }))
                    })
                    .collect();
                self.line("if");
                for (id, name) in targets {
                    self.line(&format!(":: {c} == {id} ->"));
                    self.depth += 1;
                    self.post(&name, &v)?;
                    self.depth -= 1;
                }
                self.line(":: else -> skip;");
                self.line("fi;");
                Ok(())
            }
        }
    }

    fn call(&mut self, function: &str, arguments: &[Expr]) -> Result<(), EmitError> {
        let Builtin::Post { to, content } = builtin(function, arguments) else {
            // Arguments are still evaluated: they may read (and so note) free types.
            for a in arguments {
                self.value(a)?;
            }
            return Ok(());
        };
        // The type first, then the value, as the runner evaluates them.
        let named = match to {
            Target::Named(e) => Some(self.value(e)?),
            Target::Fixed(_) => None,
        };
        let v = match content {
            Content::Value(e) => {
                let v = self.value(e)?;
                self.or_zero(v)
            }
            Content::Int(e) => {
                let v = self.value(e)?;
                self.unary(Table::PostInt, v)
            }
            Content::Joined([a, b]) => {
                let a = self.value(a)?;
                let b = self.value(b)?;
                self.two(Table::Join, a, b)
            }
            Content::Joined(_) | Content::List(_) => {
                return Err(self.unsupported(format!("`{function}` posts a list")))
            }
            Content::Command(command) => {
                Operand::Const(self.id(&Value::Str(command.word().into())))
            }
            Content::Text(e) => {
                let v = self.value(e)?;
                self.unary(Table::Text, v)
            }
            Content::StateName => {
                let name = self.model.machines[self.machine].states[self.state]
                    .name
                    .clone();
                Operand::Const(self.id(&Value::Str(name)))
            }
        };
        match (named, to) {
            (Some(ty), _) => self.post_to(ty, v),
            (None, to) => self.post(&to.name(|_| String::new()), &v),
        }
    }

    /// A command to machine `j`: at once to another machine, at the ringlet's end to itself.
    fn command(&mut self, j: usize, command: Command) -> Result<(), EmitError> {
        if j != self.machine {
            self.control(j, command);
            return Ok(());
        }
        if self.in_loop > 0 {
            return Err(self.unsupported(
                "a command to the machine itself inside a `for` loop (the queue of them has a fixed length)"
                    .into(),
            ));
        }
        self.self_posts += 1;
        self.most_self_posts = self.most_self_posts.max(self.self_posts);
        let code = command_code(command);
        self.line(&format!("defer[ndefer] = {code};"));
        self.line("ndefer++;");
        Ok(())
    }

    /// gufsm's `SuspensibleMachine` (and [`crate::ringlet`]'s `control`): a machine that
    /// starts rings from the next round.
    fn control(&mut self, j: usize, command: Command) {
        let initial = self.model.machines[j].initial;
        let restart = format!(
            "st[{j}] = {initial}; mode[{j}] = 0; je[{j}] = 1; fresh[{j}] = 1; due[{j}] = 0;"
        );
        match command {
            Command::On | Command::Resume => {
                self.line("if");
                self.line(&format!(":: mode[{j}] == 0 -> skip;"));
                self.line(&format!(":: mode[{j}] == 2 -> {restart}"));
                self.line(&format!(
                    ":: mode[{j}] == 1 -> mode[{j}] = 0; je[{j}] = 1; fresh[{j}] = 1; due[{j}] = 0;"
                ));
                self.line("fi;");
            }
            Command::Restart => self.line(&restart),
            Command::Suspend => self.line(&format!(
                "if :: mode[{j}] == 0 -> mode[{j}] = 1; :: else -> skip; fi;"
            )),
            Command::Off => self.line(&format!("mode[{j}] = 2;")),
            Command::Reload => {
                self.line(&format!("st[{j}] = {initial}; je[{j}] = 1; due[{j}] = 0;"))
            }
            Command::Reread => {}
        }
    }

    // ----- properties -----

    fn term_truth(&mut self, term: &Term) -> String {
        match term {
            Term::Not(t) => format!("!({})", self.term_truth(t)),
            Term::And(l, r) => format!("({} && {})", self.term_truth(l), self.term_truth(r)),
            Term::Or(l, r) => format!("({} || {})", self.term_truth(l), self.term_truth(r)),
            other => {
                let v = self.term(other);
                self.truthy(v)
            }
        }
    }

    fn term(&mut self, term: &Term) -> Operand {
        match term {
            Term::Const(v) => Operand::Const(self.id(v)),
            Term::Slot(slot) => self.slot_code(*slot),
            Term::Answer { theory, output } => {
                let t = self.answer(*theory, *output, 0);
                self.of_truth(t)
            }
            Term::Running(m) => self.of_truth(format!("(mode[{m}] == 0)")),
            Term::InState { machine, state } => self.of_truth(format!(
                "(mode[{machine}] == 0 && st[{machine}] == {state})"
            )),
            Term::Saw(i) => Operand::Code(format!("saw{i}")),
            Term::Not(_) | Term::And(..) | Term::Or(..) => {
                let t = self.term_truth(term);
                self.of_truth(t)
            }
            Term::Neg(t) => {
                let v = self.term(t);
                self.unary(Table::Neg, v)
            }
            Term::Binary(op, l, r) => {
                let (l, r) = (self.term(l), self.term(r));
                self.binary(*op, l, r)
            }
            Term::Function(f, args) => {
                let args = args.iter().map(|a| self.term(a)).collect();
                self.function(f, args)
            }
        }
    }

    // ----- the whole text -----

    /// The whole model: what it is (a comment), its variables, the tables every operator and
    /// reasoner answer is looked up in, the process that runs one ringlet a step, and one
    /// claim a property.
    fn write(
        &mut self,
        behaviour: &str,
        properties: &[Property],
        values_complete: bool,
    ) -> Result<String, EmitError> {
        let mut body = self.initial_step(properties);
        body.push_str(&self.ringlet_steps(properties)?);
        let mut text = self.header(behaviour, values_complete);
        self.declarations(&mut text, properties);
        let fill = self.tables(&mut text)?;
        let _ = writeln!(text, "\nactive proctype rounds() {{");
        text.push_str(&body.replacen(TABLES, &table_steps(&fill), 1));
        let _ = writeln!(text, "}}\n");
        for (i, p) in properties.iter().enumerate() {
            let _ = writeln!(
                text,
                "ltl p{i} {{ {} }} /* {} {} */",
                ltl(i, p, crate::acceptance::clock_sets(self.model)),
                p.source.kind.word(),
                comment(&p.source.name)
            );
        }
        Ok(text)
    }

    /// The initial state: the tables (filled in once the pass has numbered every value), the
    /// machines and variables, then every free type at each value of its initial domain.
    fn initial_step(&mut self, properties: &[Property]) -> String {
        let model = self.model;
        self.depth = 1;
        self.line(TABLES);
        self.line("d_step {");
        self.depth += 1;
        for (k, m) in model.machines.iter().enumerate() {
            let mode = if m.start { 0 } else { 2 };
            self.line(&format!(
                "st[{k}] = {}; mode[{k}] = {mode}; je[{k}] = 1;",
                m.initial
            ));
        }
        for (i, s) in model.slots.iter().enumerate() {
            let id = self.id_of(s.initial.as_ref());
            if id != NEVER {
                self.line(&format!("s{i} = {id};"));
            }
        }
        self.depth -= 1;
        self.line("};");
        self.line("atomic {");
        self.depth += 1;
        for (slot, domain) in model.free_slots() {
            let ids: Vec<ValueId> = domain
                .initial
                .iter()
                .map(|v| self.id_of(v.as_ref()))
                .collect();
            self.choose(slot, &ids);
        }
        self.line("skip;");
        self.depth -= 1;
        self.line("};");
        self.properties(properties);
        std::mem::take(&mut self.out)
    }

    /// The loop of steps: choose the machine that rings, run its OnEntry, its snapshot and the
    /// rest of its ringlet, then let every free type take any value.
    fn ringlet_steps(&mut self, properties: &[Property]) -> Result<String, EmitError> {
        let model = self.model;
        self.line("do");
        self.line(":: d_step {");
        self.depth += 1;
        for (i, p) in properties.iter().enumerate() {
            // Liveness bits keep the last step's end through this step's parts.
            if !p.source.kind.is_liveness() {
                self.line(&format!("hit{i} = 0;"));
            }
        }
        self.select();
        self.on_entry()?;
        self.depth -= 1;
        self.line("};");
        self.depth += 1;
        self.line("if :: ringing == 0 -> break; :: else -> skip; fi;");
        self.snapshot_choices();
        self.rest_of_ringlet()?;
        self.line("atomic {");
        self.depth += 1;
        let free: Vec<(usize, Vec<ValueId>)> = model
            .free_slots()
            .map(|(slot, d)| (slot, d.values.iter().map(|v| self.id(v)).collect()))
            .collect();
        for (slot, ids) in &free {
            self.choose(*slot, ids);
        }
        self.line("skip;");
        self.depth -= 1;
        self.line("};");
        self.depth -= 1;
        self.properties(properties);
        self.line("od;");
        self.stays_for_ever(properties);
        Ok(std::mem::take(&mut self.out))
    }

    /// OnEntry of the ringing machine's state, where it has just entered it.
    fn on_entry(&mut self) -> Result<(), EmitError> {
        let model = self.model;
        self.line("if");
        for k in 0..model.machines.len() {
            self.machine = k;
            self.self_posts = 0;
            self.line(&format!(":: ringing == {} && je[{k}] ->", k + 1));
            self.depth += 1;
            self.line("if");
            let machine = &model.machines[k].machine;
            for (s, state) in machine.states.iter().enumerate() {
                self.state = s;
                self.line(&format!(":: st[{k}] == {s} ->"));
                self.depth += 1;
                self.noting = true;
                self.run(RingletPlan::of_state(machine, state).arriving())?;
                self.noting = false;
                if let Some(clocks) = crate::promela_clocks::arrival(model, k, s) {
                    self.line(&clocks);
                }
                self.line("skip;");
                self.depth -= 1;
            }
            self.line("fi;");
            self.line(&format!("je[{k}] = 0; arrived = 1;"));
            self.depth -= 1;
        }
        self.line(":: else -> arrived = 0;");
        self.line("fi;");
        Ok(())
    }

    /// The comment that says what the file is and how to check it, the value numbering and the
    /// machines' state numbering.
    fn header(&self, behaviour: &str, values_complete: bool) -> String {
        let model = self.model;
        let universe = model.values.borrow().len();
        let mut text = String::new();
        let w = &mut text;
        let _ = writeln!(
            w,
            "/* {}: the model of `proclaim verify`, one ringlet a step (generated by\n   `proclaim verify --emit promela`). Check property i with\n     spin -a FILE && gcc -O2 -DSAFETY -o pan pan.c && ./pan -N p<i> -m1000000\n   A claim violation of a never/always property is a counterexample, of a\n   reachable one its witness; an assertion error means SPIN met a value the\n   checker never numbered. A liveness claim (eventually, leads_to,\n   always_eventually) needs the acceptance-cycle search: compile without\n   -DSAFETY and run ./pan -a -N p<i>. */",
            comment(behaviour)
        );
        if !values_complete {
            let _ = writeln!(
                w,
                "/* The checker's exploration ran out of states: the values numbered below may\n   not be all a run computes. */"
            );
        }
        let _ = writeln!(w, "#define VALUES {}", universe + 2);
        let _ = writeln!(w, "#define BEYOND {}", universe + 1);
        let _ = writeln!(w, "\n/* Values (0: never posted; BEYOND: none of these):");
        for id in 1..=universe as ValueId {
            let shown = model.show(self.value_of(id).as_ref());
            let _ = writeln!(w, "   {id} = {}", comment(&shown));
        }
        let _ = writeln!(w, "*/\n");
        let _ = writeln!(w, "/* Machines, in manifest order:");
        for (k, m) in model.machines.iter().enumerate() {
            let states: Vec<String> = m
                .states
                .iter()
                .enumerate()
                .map(|(i, s)| format!("{i} {}", s.name))
                .collect();
            let _ = writeln!(
                w,
                "   {k} {}: {}",
                comment(&m.name),
                comment(&states.join(", "))
            );
        }
        let _ = writeln!(w, "*/");
        text
    }

    /// The schedule's variables, one a slot, one a `saw`, the properties' flags and the temporaries.
    fn declarations(&self, w: &mut String, properties: &[Property]) {
        let model = self.model;
        let n = model.machines.len();
        let value_type = self.value_type();
        let _ = writeln!(
            w,
            "byte turn;\nbyte ringing; /* the ringing machine + 1, 0 between steps */"
        );
        let _ = writeln!(
            w,
            "byte st[{n}];\nbyte mode[{n}]; /* 0 running, 1 suspended, 2 dormant */"
        );
        let _ = writeln!(w, "bit je[{n}]; /* just entered: OnEntry still to run */");
        let _ = writeln!(w, "bit fresh[{n}]; /* started this round */");
        let _ = writeln!(
            w,
            "short due[{n}]; /* bit i: the state's time test i is due */"
        );
        if crate::promela_clocks::any(model) {
            let _ = writeln!(w, "{}", crate::promela_clocks::declarations(model));
        }
        for (i, s) in model.slots.iter().enumerate() {
            let what = match &s.kind {
                SlotKind::Local { .. } => "variable",
                SlotKind::Global => "global",
                SlotKind::Message { .. } if s.free.is_some() => "free whiteboard type",
                SlotKind::Message { .. } => "whiteboard type",
            };
            let _ = writeln!(w, "{value_type} s{i}; /* {what} {} */", comment(&s.name));
        }
        for (i, (m, e)) in model.saw.iter().enumerate() {
            let _ = writeln!(
                w,
                "{value_type} saw{i}; /* saw({}, {}) */",
                comment(&model.machines[*m].name),
                comment(&e.to_string())
            );
        }
        for (slot, _) in model.free_slots() {
            let _ = writeln!(w, "bit tch{slot}; /* OnEntry read or posted s{slot} */");
        }
        if self.queue > 0 {
            let _ = writeln!(
                w,
                "byte defer[{}]; /* commands to the ringing machine itself */\nbyte ndefer;",
                self.queue
            );
        }
        property_declarations(w, properties, crate::acceptance::clock_sets(model));
        let _ = writeln!(
            w,
            "\nhidden byte sel;\nhidden byte wrapped;\nbit arrived; /* the ringing machine ran its OnEntry in this step (read past a state\n              SPIN stores, so not hidden; 0 between steps) */"
        );
        for i in 0..self.temps {
            let _ = writeln!(w, "hidden int t{i};");
        }
    }

    /// The smallest Promela integer type that holds every value number and BEYOND.
    fn value_type(&self) -> &'static str {
        let beyond = self.model.values.borrow().len() + 1;
        if beyond < 256 {
            "byte"
        } else if beyond < 32768 {
            "short"
        } else {
            "int"
        }
    }

    /// Declares the operator tables and the reasoners' answer tables into `w`; returns the
    /// statements that fill them, for the initial step.
    fn tables(&self, w: &mut String) -> Result<String, EmitError> {
        let universe = self.model.values.borrow().len();
        let beyond = (universe + 1) as ValueId;
        let width = universe + 2;
        let value_type = self.value_type();
        let mut fill = String::new();
        for (i, t) in self.tables.iter().enumerate() {
            // Hidden variables cannot be bits.
            let element = match t {
                Table::Truthy | Table::Input => "byte",
                _ => value_type,
            };
            let size = if t.two_dimensional() {
                width * width
            } else {
                width
            };
            let _ = writeln!(w, "hidden {element} tab{i}[{size}]; /* {} */", t.describe());
            for a in 0..width as ValueId {
                let row: Vec<(usize, ValueId)> = if t.two_dimensional() {
                    (0..width as ValueId)
                        .map(|b| {
                            let r = if a == beyond || b == beyond {
                                Some(beyond)
                            } else {
                                self.lookup(self.entry2(t, self.value_of(a), self.value_of(b)))
                            };
                            (a as usize * width + b as usize, r.unwrap_or(beyond))
                        })
                        .collect()
                } else {
                    let r = if a == beyond {
                        match t {
                            Table::Truthy | Table::Input => Some(0),
                            _ => Some(beyond),
                        }
                    } else {
                        self.apply1(t, a)
                    };
                    vec![(a as usize, r.unwrap_or(beyond))]
                };
                for (index, r) in row {
                    if r != 0 {
                        let _ = write!(fill, "tab{i}[{index}] = {r}; ");
                    }
                }
            }
        }
        self.answer_tables(w, &mut fill)?;
        if fill.is_empty() {
            fill.push_str("skip;");
        }
        Ok(fill)
    }

    /// Each reasoner's answers under every valuation of its inputs, one table an output.
    fn answer_tables(&self, w: &mut String, fill: &mut String) -> Result<(), EmitError> {
        for (t, theory) in self.model.theories.iter().enumerate() {
            let inputs = theory.inputs.len();
            let valuations = 3usize.pow(inputs as u32);
            if valuations > MAX_VALUATIONS {
                return Err(EmitError::Unsupported {
                    machine: theory.name.clone(),
                    what: format!("the reasoner has {inputs} inputs (3^{inputs} valuations)"),
                });
            }
            for o in 0..theory.outputs.len() {
                let _ = writeln!(
                    w,
                    "hidden byte ans{t}_{o}[{valuations}]; /* {} of {} */",
                    comment(&theory.outputs[o]),
                    comment(&theory.name)
                );
            }
            for index in 0..valuations {
                let mut rest = index;
                let valuation: Vec<Input> = (0..inputs)
                    .map(|_| {
                        let digit = rest % 3;
                        rest /= 3;
                        match digit {
                            0 => Input::Unknown,
                            1 => Input::Value(false),
                            _ => Input::Value(true),
                        }
                    })
                    .collect();
                let answers = self.model.reasoner(t).answers(&valuation).to_vec();
                for (o, a) in answers.iter().enumerate() {
                    if *a {
                        let _ = write!(fill, "ans{t}_{o}[{index}] = 1; ");
                    }
                }
            }
        }
        Ok(())
    }

    /// `slot` takes any of `ids`.
    /// The environment sets free type `slot` to one of `ids`, or leaves it never posted while
    /// it is (a sensor may stay silent).
    fn choose(&mut self, slot: usize, ids: &[ValueId]) {
        let options: Vec<String> = ids.iter().map(|id| format!(":: s{slot} = {id};")).collect();
        self.line(&format!(
            "if {} :: s{slot} == {NEVER} -> skip; fi;",
            options.join(" ")
        ));
    }

    /// The next machine that may ring from `turn` in manifest order (passing the end starts a
    /// round: no machine is fresh any more); `ringing` is 0 when none can.
    fn select(&mut self) {
        let model = self.model;
        let n = model.machines.len();
        self.line("ringing = 0; sel = turn; wrapped = 0;");
        self.line("do");
        let mut clear: String = (0..n).map(|k| format!(" fresh[{k}] = 0;")).collect();
        clear.push_str(&crate::promela_clocks::new_round(model));
        self.line(&format!(
            ":: sel >= {n} -> if :: wrapped -> break; :: else -> sel = 0; wrapped = 1;{clear} fi;"
        ));
        for (k, m) in model.machines.iter().enumerate() {
            let not_final: Vec<String> = m
                .states
                .iter()
                .enumerate()
                .filter(|(_, s)| s.is_final())
                .map(|(s, _)| format!("st[{k}] != {s}"))
                .collect();
            let not_final = if not_final.is_empty() {
                "1".to_string()
            } else {
                not_final.join(" && ")
            };
            self.line(&format!(
                ":: sel == {k} && mode[{k}] == 0 && !fresh[{k}] && (je[{k}] || ({not_final})) -> ringing = {}; break;",
                k + 1
            ));
        }
        self.line(":: else -> sel++;");
        self.line("od;");
    }

    /// Between OnEntry and the snapshot: due time tests of the state (constant ones in order),
    /// and the free types OnEntry touched.
    fn snapshot_choices(&mut self) {
        let model = self.model;
        self.line("atomic {");
        self.depth += 1;
        self.line("if");
        for (k, m) in model.machines.iter().enumerate() {
            let timed: Vec<(usize, &crate::model::StateModel)> = m
                .states
                .iter()
                .enumerate()
                .filter(|(_, s)| !s.time_tests.is_empty())
                .collect();
            if timed.is_empty() {
                continue;
            }
            self.line(&format!(":: ringing == {} ->", k + 1));
            self.depth += 1;
            self.line("if");
            for (s, state) in timed {
                for line in due_choices(model, k, s, state) {
                    self.line(&line);
                }
            }
            self.line(":: else -> skip;");
            self.line("fi;");
            self.depth -= 1;
        }
        self.line(":: else -> skip;");
        self.line("fi;");
        let free: Vec<(usize, Vec<ValueId>)> = model
            .free_slots()
            .map(|(slot, d)| (slot, d.values.iter().map(|v| self.id(v)).collect()))
            .collect();
        for (slot, ids) in free {
            let options: Vec<String> = ids.iter().map(|id| format!(":: s{slot} = {id};")).collect();
            self.line(&format!(
                "if :: tch{slot} -> tch{slot} = 0; if {} :: s{slot} == {NEVER} -> skip; fi; :: else -> skip; fi;",
                options.join(" ")
            ));
        }
        self.depth -= 1;
        self.line("};");
    }

    /// From the snapshot to the ringlet's end: `saw()`, the first transition that holds (its
    /// OnExit, the target entered) or Internal, the commands to itself, the next turn. One
    /// indivisible step a machine's state, each its own `d_step` (its first statement the
    /// guard): SPIN refuses one `d_step` too long, and a state of regions has many arms.
    fn rest_of_ringlet(&mut self) -> Result<(), EmitError> {
        let model = self.model;
        self.line("if");
        for (k, m) in model.machines.iter().enumerate() {
            self.machine = k;
            self.self_posts = 0;
            for s in 0..m.states.len() {
                self.state = s;
                self.line(&format!(
                    ":: d_step {{ ringing == {} && st[{k}] == {s} ->",
                    k + 1
                ));
                self.depth += 1;
                self.state_ringlet(k, s)?;
                self.obey_deferred(k);
                self.line(&format!("turn = {};", k + 1));
                self.depth -= 1;
                self.line("};");
            }
        }
        self.line(":: else -> skip;");
        self.line("fi;");
        Ok(())
    }

    /// Machine `k`'s ringlet in state `s` from its snapshot: `saw()`, then each arm of its
    /// [`RingletPlan`] in order (what it runs leaving, the target entered), else staying.
    fn state_ringlet(&mut self, k: usize, s: usize) -> Result<(), EmitError> {
        let model = self.model;
        let (m, state) = (&model.machines[k], &model.machines[k].states[s]);
        for (j, (seer, e)) in model.saw.iter().enumerate() {
            if *seer == k {
                let v = self.value(e)?;
                self.line(&format!("saw{j} = {};", v.code()));
            }
        }
        let plan = RingletPlan::of_state(&m.machine, &m.machine.states[s]);
        let mut opened = 0;
        for arm in plan.arms() {
            let Some(t) = state.modelled(arm).map(|t| &state.transitions[t]) else {
                continue;
            };
            let holds = self.truth(&t.label)?;
            self.line("if");
            self.line(&format!(":: {holds} ->"));
            self.depth += 1;
            self.run(arm.leaving())?;
            if arm.stays() {
                // Not entered again: state, arrival and due tests are as they were.
                self.line("skip;");
                self.depth -= 1;
                self.line(":: else ->");
                self.depth += 1;
                opened += 1;
                continue;
            }
            // The due tests of a composite the move stays in stay due, at their new places,
            // with those each implies there (`ringlet::implied_time`: one due test's
            // implications are the same whatever else is due, so they are joined bit by bit).
            let target = &m.states[t.target];
            let kept = crate::ringlet::kept_time_bits(
                &state.time_tests,
                &target.time_tests,
                &arm.transition.enters,
            );
            let due = match kept.as_slice() {
                [] => "0".to_string(),
                kept => kept
                    .iter()
                    .map(|&(i, j)| {
                        let implied = crate::ringlet::implied_time(target, 1 << j);
                        format!("(((due[{k}] >> {i}) & 1) * {implied})")
                    })
                    .collect::<Vec<_>>()
                    .join(" | "),
            };
            if let Some(left) = crate::promela_clocks::leaving(model, k, state) {
                self.line(&left);
            }
            self.line(&format!(
                "st[{k}] = {}; je[{k}] = 1; due[{k}] = {due};",
                t.target
            ));
            self.depth -= 1;
            self.line(":: else ->");
            self.depth += 1;
            opened += 1;
        }
        self.run(plan.staying())?;
        self.line("skip;");
        for _ in 0..opened {
            self.depth -= 1;
            self.line("fi;");
        }
        Ok(())
    }

    /// The commands machine `k`'s ringlet posted, obeyed as it ends.
    fn obey_deferred(&mut self, k: usize) {
        for i in 0..self.queue {
            let options: Vec<String> = Command::ALL
                .iter()
                .map(|c| (command_code(*c), *c))
                .map(|(code, c)| {
                    let saved = std::mem::take(&mut self.out);
                    let depth = std::mem::replace(&mut self.depth, 0);
                    self.control(k, c);
                    self.depth = depth;
                    let body = std::mem::replace(&mut self.out, saved);
                    format!(":: defer[{i}] == {code} -> {}", body.replace('\n', " "))
                })
                .collect();
            self.line(&format!(
                "if {} :: else -> skip; fi; defer[{i}] = 0;",
                options.join(" ")
            ));
        }
        if self.queue > 0 {
            self.line("ndefer = 0;");
        }
    }

    /// The end of a step: `ringing` cleared, each property's hit bit, and no variable beyond
    /// the numbered values.
    fn properties(&mut self, properties: &[Property]) {
        let model = self.model;
        self.line("d_step {");
        self.depth += 1;
        self.line("ringing = 0; arrived = 0;");
        self.noting = false;
        for (i, p) in properties.iter().enumerate() {
            let holds = self.term_truth(p.term());
            let hit = match p.source.kind {
                PropertyKind::Never | PropertyKind::Reachable => holds,
                PropertyKind::Always => format!("!({holds})"),
                PropertyKind::Eventually
                | PropertyKind::LeadsTo
                | PropertyKind::AlwaysEventually => {
                    self.line(&format!("lp{i} = ({holds} -> 1 : 0);"));
                    if let Some(then) = p.then_term() {
                        let then = self.term_truth(then);
                        self.line(&format!("lq{i} = ({then} -> 1 : 0);"));
                    }
                    for (j, fair) in p.fair_terms().iter().enumerate() {
                        let fair = self.term_truth(fair);
                        self.line(&format!("fair{i}_{j} = ({fair} -> 1 : 0);"));
                    }
                    continue;
                }
            };
            self.line(&format!("hit{i} = ({hit} -> 1 : 0);"));
        }
        if properties.iter().any(|p| p.source.kind.is_liveness()) {
            let mut set = 0;
            for (k, m) in model.machines.iter().enumerate() {
                for &clock in &m.clocks {
                    let due = self.time_passes(k, clock);
                    self.line(&format!("acc[{set}] = ({due} -> 1 : 0);"));
                    set += 1;
                }
            }
        }
        let mut vars: Vec<String> = (0..model.slots.len()).map(|i| format!("s{i}")).collect();
        vars.extend((0..model.saw.len()).map(|i| format!("saw{i}")));
        if !vars.is_empty() {
            let checks: Vec<String> = vars.iter().map(|v| format!("{v} != BEYOND")).collect();
            self.line(&format!("assert({});", checks.join(" && ")));
        }
        self.depth -= 1;
        self.line("};");
    }

    /// Machine `k` lets the time of `clock` pass in the state now (liveness's acceptance set
    /// of that clock, [`crate::acceptance::time_passes`]): not running, the clock just started,
    /// or every test of it in its state due (a state with none among them).
    fn time_passes(&self, k: usize, clock: Option<usize>) -> String {
        let mut options = vec![format!("mode[{k}] != 0")];
        for (s, state) in self.model.machines[k].states.iter().enumerate() {
            let mask = state.clock_mask(clock);
            if state.arrival_starts(clock) {
                options.push(format!("(st[{k}] == {s} && je[{k}])"));
            }
            options.push(if mask == 0 {
                format!("st[{k}] == {s}")
            } else {
                format!("(st[{k}] == {s} && (due[{k}] & {mask}) == {mask})")
            });
        }
        format!("({})", options.join(" || "))
    }

    /// After the last step, where no machine can ring any more: the run stays so for ever,
    /// which counts as a run (a liveness property whose P never comes fails on it whatever the
    /// fairness assumptions), so every acceptance bit is set.
    fn stays_for_ever(&mut self, properties: &[Property]) {
        if !properties.iter().any(|p| p.source.kind.is_liveness()) {
            return;
        }
        let mut bits: Vec<String> = (0..crate::acceptance::clock_sets(self.model))
            .map(|k| format!("acc[{k}] = 1;"))
            .collect();
        for (i, p) in properties.iter().enumerate() {
            bits.extend((0..p.fair_terms().len()).map(|j| format!("fair{i}_{j} = 1;")));
        }
        // `break` may not jump into a d_step: an atomic sequence instead.
        self.line(&format!("atomic {{ {} }}", bits.join(" ")));
    }
}

/// A statement as the Promela it runs as, each kind met where [`proclaim_lower::read`] meets it.
struct Exec<'w, 'm>(&'w mut Writer<'m>);

impl StatementReader for Exec<'_, '_> {
    type Read = Result<(), EmitError>;

    fn assign(&mut self, name: &str, value: &Expr) -> Self::Read {
        let v = self.0.value(value)?;
        let v = self.0.or_zero(v);
        self.0.assign(name, v)
    }

    fn call(&mut self, function: &str, arguments: &[Expr]) -> Self::Read {
        self.0.call(function, arguments)
    }

    fn evaluate(&mut self, expr: &Expr) -> Self::Read {
        self.0.value(expr).map(|_| ())
    }

    fn sequence(&mut self, body: &[Statement]) -> Self::Read {
        body.iter().try_for_each(|s| self.0.exec(s))
    }

    fn for_loop(&mut self, parts: ForLoop<'_>) -> Self::Read {
        self.0.for_loop(parts)
    }

    fn nothing(&mut self) -> Self::Read {
        Ok(())
    }
}

/// The `if` options of machine `k` in state `s` at its snapshot: the sets of its time tests that
/// may be due ([`crate::ringlet::due_masks`]) as the other machines' clocks allow
/// ([`crate::promela_clocks::agrees`]); in a ringlet that arrived, none whose clock that
/// arrival started ([`crate::ringlet::fresh_time`]).
fn due_choices(
    model: &Search,
    k: usize,
    s: usize,
    state: &crate::model::StateModel,
) -> Vec<String> {
    let masks = crate::ringlet::due_masks(state, 0);
    let options = |keep: &dyn Fn(u16) -> bool| {
        let options: Vec<String> = masks
            .iter()
            .filter(|&&m| keep(m))
            .map(|&m| {
                let clocks = crate::promela_clocks::agrees(model, k, state, m)
                    .map_or(String::new(), |c| format!(" && {c}"));
                format!(":: (due[{k}] | {m}) == {m}{clocks} -> due[{k}] = {m};")
            })
            .collect();
        options.join(" ")
    };
    let fresh = crate::ringlet::fresh_time(state);
    if fresh == 0 {
        return vec![format!(
            ":: st[{k}] == {s} -> if {} fi;",
            options(&|_| true)
        )];
    }
    vec![
        format!(
            ":: st[{k}] == {s} && arrived -> if {} fi;",
            options(&|m| m & fresh == 0)
        ),
        format!(
            ":: st[{k}] == {s} && !arrived -> if {} fi;",
            options(&|_| true)
        ),
    ]
}

/// Property `i`'s `ltl` formula: `[] !hit<i>` for a safety property; for a liveness property
/// its formula over the step-end bits (`lp`, `lq`) under the fairness of time (`acc<k>`, one a
/// clock of a machine) and of its `fair` assumptions, as an antecedent: only fair runs count.
fn ltl(i: usize, property: &Property, clocks: usize) -> String {
    let mut fair: Vec<String> = (0..clocks).map(|k| format!("[]<> acc[{k}]")).collect();
    fair.extend((0..property.fair_terms().len()).map(|j| format!("[]<> fair{i}_{j}")));
    let assuming = |goal: String| {
        if fair.is_empty() {
            goal
        } else {
            format!("({}) -> ({goal})", fair.join(" && "))
        }
    };
    match property.source.kind {
        PropertyKind::Never | PropertyKind::Always | PropertyKind::Reachable => {
            format!("[] !hit{i}")
        }
        PropertyKind::Eventually => assuming(format!("<> lp{i}")),
        PropertyKind::LeadsTo => assuming(format!("[] (lp{i} -> <> lq{i})")),
        PropertyKind::AlwaysEventually => assuming(format!("[]<> lp{i}")),
    }
}

/// A command's number in the queue of commands a machine sends itself (0: none).
fn command_code(command: Command) -> usize {
    1 + Command::ALL.iter().position(|c| *c == command).unwrap_or(0)
}

fn is_temp(code: &str) -> bool {
    code.len() > 1 && code.starts_with('t') && code[1..].bytes().all(|b| b.is_ascii_digit())
}

/// Text safe inside a Promela comment.
fn comment(text: &str) -> String {
    text.replace("*/", "* /").replace('\n', " ")
}

/// Each property's bits: `hit<i>` for a safety property; `lp<i>`, `lq<i>` and `fair<i>_<j>`
/// for a liveness one, and `acc` once any is there.
fn property_declarations(w: &mut String, properties: &[Property], n: usize) {
    for (i, p) in properties.iter().enumerate() {
        if p.source.kind.is_liveness() {
            let _ = writeln!(
                w,
                "bit lp{i}; /* {} {}: {}, at the end of the last step */",
                p.source.kind.word(),
                comment(&p.source.name),
                comment(&p.source.expression)
            );
            if p.then_term().is_some() {
                let _ = writeln!(w, "bit lq{i}; /* its second expression */");
            }
            for (j, f) in p.source.fair.iter().enumerate() {
                let _ = writeln!(
                    w,
                    "bit fair{i}_{j}; /* assumed infinitely often: {} */",
                    comment(f)
                );
            }
            continue;
        }
        let _ = writeln!(
            w,
            "bit hit{i}; /* {} {}: {} */",
            p.source.kind.word(),
            comment(&p.source.name),
            comment(&p.source.expression)
        );
    }
    if properties.iter().any(|p| p.source.kind.is_liveness()) {
        let _ = writeln!(
            w,
            "bit acc[{n}]; /* liveness: a clock of a machine lets time pass now */"
        );
    }
}
