//! Where the environment's values flow (spec §6, "Free values"): which storage places may hold
//! a value a free whiteboard type took, through which arithmetic, and what the behaviour
//! compares it with. [`crate::domain`] turns these comparisons into a finite domain that keeps
//! the truth of every one of them; what no finite domain can keep is an [`Inexact`], and a
//! verdict that claims an absence is then undecided, never "holds".
//!
//! The analysis is flow-insensitive: every statement of every activity may run at any time,
//! so a place holds the join of everything ever assigned or posted to it. A value is tracked
//! as a [`Term`]: a free type's value passed through a chain of operations with constants
//! (`ballRR`, `Battery_Charge / 10`, `-(x + 3)`), each monotone, so that a comparison of the
//! chain with a constant splits the free type's values into intervals. Anything else a free
//! value meets (another free value in arithmetic, a value computed at run time in a
//! comparison, `%`, `abs`, text joined to it) makes the term opaque, with the reason.

use crate::model::{Model, Name, SlotId, SlotKind};
use crate::outcome::Inexact;
use proclaim_board::Value;
use proclaim_fsm::{Action, BinOp, Expr, ForLoop, Statement, UnOp, VarType, TIME_TESTS};
use proclaim_lower::arith;
use proclaim_lower::builtin::{builtin, Builtin, Content, Target};
use proclaim_lower::{read_statement, RingletPlan, StatementReader};
use rustc_hash::FxHashSet;

/// Constants a place may hold before it counts as "computed at run time".
const MAX_CONSTANTS: usize = 16;
/// Distinct terms of one free type a place may hold before they become one opaque term.
const MAX_TERMS: usize = 16;
/// Operations a term may pass through before it counts as fed back into itself.
const MAX_CHAIN: usize = 8;
/// Walks over the whole behaviour before what has not settled is made opaque.
const MAX_PASSES: usize = 1024;

/// One monotone operation of a term's chain.
#[derive(Clone, Debug, PartialEq)]
pub enum Op {
    /// `t op constant`, or `constant op t` when `constant_left`.
    Arith {
        op: BinOp,
        constant: Value,
        constant_left: bool,
    },
    Neg,
    /// Assigned to a typed variable (`int n = x * 0.5`).
    Convert(VarType),
    /// `round`, `floor` or `ceil`.
    Function(&'static str),
}

/// A free type's value as some place may hold it.
#[derive(Clone, Debug, PartialEq)]
pub enum Term {
    /// `ops` applied in order to the value of free slot `input`.
    Chain { input: SlotId, ops: Vec<Op> },
    /// Derived from `input` in a way no finite domain of it keeps (`why`).
    Opaque { input: SlotId, why: String },
}

impl Term {
    fn input(&self) -> SlotId {
        match self {
            Term::Chain { input, .. } | Term::Opaque { input, .. } => *input,
        }
    }

    fn is_copy(&self) -> bool {
        matches!(self, Term::Chain { ops, .. } if ops.is_empty())
    }

    /// The term passed through `op` (opaque once the chain is too long to be anything but a
    /// value fed back into itself).
    fn then(&self, op: Op) -> Term {
        match self {
            Term::Opaque { .. } => self.clone(),
            Term::Chain { input, ops } if ops.len() >= MAX_CHAIN => Term::Opaque {
                input: *input,
                why: "arithmetic on it is repeated without bound (a loop, or a value that feeds itself)".into(),
            },
            Term::Chain { input, ops } => {
                let mut ops = ops.clone();
                ops.push(op);
                Term::Chain { input: *input, ops }
            }
        }
    }

    fn opaque(&self, why: String) -> Term {
        Term::Opaque {
            input: self.input(),
            why,
        }
    }
}

/// Applies a chain to a value, with the runner's own operators.
pub fn apply(ops: &[Op], x: Value) -> Option<Value> {
    let mut v = x;
    for op in ops {
        v = match op {
            Op::Arith {
                op,
                constant,
                constant_left: false,
            } => arith::binary(*op, Some(v), Some(constant.clone()))?,
            Op::Arith {
                op,
                constant,
                constant_left: true,
            } => arith::binary(*op, Some(constant.clone()), Some(v))?,
            Op::Neg => arith::negate(&v)?,
            Op::Convert(ty) => arith::convert(ty, v),
            Op::Function(f) => arith::function(f, &[Some(v)])?,
        };
    }
    Some(v)
}

/// What an expression may be: constants, and terms of free types.
#[derive(Clone, Debug, PartialEq)]
struct Flow {
    /// `None` once it may be a value computed at run time that no constant bounds.
    constants: Option<Vec<Value>>,
    terms: Vec<Term>,
}

impl Flow {
    fn nothing() -> Flow {
        Flow {
            constants: Some(Vec::new()),
            terms: Vec::new(),
        }
    }

    fn constant(v: Value) -> Flow {
        Flow {
            constants: Some(vec![v]),
            terms: Vec::new(),
        }
    }

    fn truth() -> Flow {
        Flow {
            constants: Some(vec![Value::Bool(false), Value::Bool(true)]),
            terms: Vec::new(),
        }
    }

    fn computed() -> Flow {
        Flow {
            constants: None,
            terms: Vec::new(),
        }
    }

    /// Joins `other` in; whether anything changed.
    fn join(&mut self, other: &Flow) -> bool {
        let before = self.clone();
        match (&mut self.constants, &other.constants) {
            (Some(mine), Some(theirs)) => {
                for v in theirs {
                    if !mine.contains(v) {
                        mine.push(v.clone());
                    }
                }
                if mine.len() > MAX_CONSTANTS {
                    self.constants = None;
                }
            }
            (mine, None) => *mine = None,
            (None, _) => {}
        }
        for t in &other.terms {
            // One opaque term of a type is enough to say why.
            let covered = self.terms.iter().any(|mine| {
                mine == t
                    || (mine.input() == t.input()
                        && matches!(mine, Term::Opaque { .. })
                        && matches!(t, Term::Opaque { .. }))
            });
            if !covered {
                self.terms.push(t.clone());
            }
        }
        self.bound_terms();
        *self != before
    }

    /// At most [`MAX_TERMS`] chains of one free type (beyond, one opaque term stands for
    /// them) and one opaque term of it: the join stays finite.
    fn bound_terms(&mut self) {
        let inputs: Vec<SlotId> = self.terms.iter().map(Term::input).collect();
        for input in inputs {
            let chains = self
                .terms
                .iter()
                .filter(|t| t.input() == input && !matches!(t, Term::Opaque { .. }))
                .count();
            if chains > MAX_TERMS {
                self.terms
                    .retain(|t| t.input() != input || matches!(t, Term::Opaque { .. }));
                self.terms.push(Term::Opaque {
                    input,
                    why: "it is computed into too many different forms".into(),
                });
            }
            let mut opaque_seen = false;
            self.terms.retain(|t| {
                if t.input() != input || !matches!(t, Term::Opaque { .. }) {
                    return true;
                }
                let keep = !opaque_seen;
                opaque_seen = true;
                keep
            });
        }
    }

    fn map_constants(&self, f: impl Fn(&Value) -> Option<Value>) -> Option<Vec<Value>> {
        let mut out = Vec::new();
        for v in self.constants.as_ref()? {
            if let Some(r) = f(v) {
                if !out.contains(&r) {
                    out.push(r);
                }
            }
        }
        Some(out)
    }
}

/// A test of a term: a comparison with a constant, or its truth.
#[derive(Clone, Debug, PartialEq)]
pub enum Test {
    Compare(BinOp, Value),
    Truth,
}

/// A condition on free type `input`'s value that some label, activity or property tests.
#[derive(Clone, Debug, PartialEq)]
pub struct Predicate {
    pub ops: Vec<Op>,
    pub test: Test,
}

/// What the analysis found.
#[derive(Debug, Default)]
pub struct Facts {
    /// Per slot (free ones only): the conditions tested of its value.
    pub predicates: Vec<Vec<Predicate>>,
    /// Free slots whose plain copies are compared with each other (a slot with itself, when
    /// an old copy is compared with its new value).
    pub pairs: Vec<(SlotId, SlotId)>,
    /// The places (slots) whose plain copies of free values are compared with each other.
    pub compared_places: Vec<SlotId>,
    /// The places read by name into another place (`b = a`, `post("T", a)`).
    pub copy_sources: Vec<SlotId>,
    /// Per place: the free slots it may hold a plain copy of.
    pub copies_in: Vec<Vec<SlotId>>,
    /// Where a free value goes where no finite domain follows it.
    pub inexact: Vec<Inexact>,
}

/// Where an expression stands, for the reasons given.
#[derive(Clone)]
struct At {
    machine: Option<usize>,
    place: String,
}

struct Analysis<'m> {
    model: &'m Model,
    places: Vec<Flow>,
    /// Record uses (the last pass) rather than only join flows.
    record: bool,
    facts: Facts,
    seen_inexact: FxHashSet<(SlotId, String)>,
    changed: bool,
}

/// Follows every free slot's value through the behaviour. `files` names each machine's file
/// (for the places reasons point at); `properties` are the properties' expressions.
pub fn analyse(model: &Model, files: &[String], properties: &[&Expr]) -> Facts {
    let places = model
        .slots
        .iter()
        .enumerate()
        .map(|(i, slot)| {
            let mut flow = match (&slot.initial, &slot.kind) {
                (Some(v), _) => Flow::constant(v.clone()),
                (None, SlotKind::Message { external: true }) => Flow::constant(Value::Int(0)),
                (None, _) => Flow::nothing(),
            };
            if slot.free.is_some() {
                flow.terms.push(Term::Chain {
                    input: i,
                    ops: Vec::new(),
                });
            }
            flow
        })
        .collect();
    let mut a = Analysis {
        model,
        places,
        record: false,
        facts: Facts {
            predicates: vec![Vec::new(); model.slots.len()],
            ..Facts::default()
        },
        seen_inexact: FxHashSet::default(),
        changed: true,
    };
    let mut passes = 0;
    while a.changed && passes < MAX_PASSES {
        a.changed = false;
        a.walk(files, properties);
        passes += 1;
    }
    if a.changed {
        // Not settled (it always is well before this): nothing derived is trusted.
        for flow in &mut a.places {
            for t in &mut flow.terms {
                *t = t.opaque("its flow through the behaviour did not settle".into());
            }
        }
    }
    a.record = true;
    a.walk(files, properties);
    a.facts.copies_in = a
        .places
        .iter()
        .map(|f| {
            f.terms
                .iter()
                .filter(|t| t.is_copy())
                .map(Term::input)
                .collect()
        })
        .collect();
    a.facts
}

/// A statement's flow of values at one place: each kind met where [`proclaim_lower::read`]
/// meets it.
struct FlowOf<'f, 'm, 'a> {
    analysis: &'f mut Analysis<'m>,
    at: &'a At,
}

impl StatementReader for FlowOf<'_, '_, '_> {
    type Read = ();

    fn assign(&mut self, name: &str, value: &Expr) {
        let flow = self.analysis.expr(self.at, value);
        self.analysis.copied_from(self.at, value);
        self.analysis.assign(self.at, name, flow);
    }

    fn call(&mut self, function: &str, arguments: &[Expr]) {
        self.analysis.call_statement(self.at, function, arguments);
    }

    fn evaluate(&mut self, expr: &Expr) {
        self.analysis.expr(self.at, expr);
    }

    fn sequence(&mut self, body: &[Statement]) {
        body.iter()
            .for_each(|s| self.analysis.statement(self.at, s));
    }

    fn for_loop(&mut self, parts: ForLoop<'_>) {
        // Flow-insensitive: the parts in any order, any number of times.
        for part in [parts.init, parts.step, Some(parts.body)]
            .into_iter()
            .flatten()
        {
            self.analysis.statement(self.at, part);
        }
        if let Some(c) = parts.condition {
            let flow = self.analysis.expr(self.at, c);
            self.analysis.truth_use(self.at, &flow);
        }
    }

    fn nothing(&mut self) {}
}

impl Analysis<'_> {
    fn walk(&mut self, files: &[String], properties: &[&Expr]) {
        let model = self.model;
        for (k, m) in model.machines.iter().enumerate() {
            let file = files.get(k).map_or(m.name.as_str(), String::as_str);
            for s in &m.machine.states {
                let at = At {
                    machine: Some(k),
                    place: format!("{file}:{} (state {})", s.line, s.name),
                };
                let activities = RingletPlan::of_state(&m.machine, s).activities();
                for action in activities.into_iter().flatten() {
                    match action {
                        Action::Post { ty, content } => {
                            self.post(&at, ty, &Flow::constant(Value::parse(content)))
                        }
                        Action::Statement(st) => self.statement(&at, st),
                        Action::Call { .. } | Action::Code(_) => {}
                    }
                }
            }
            for t in &m.machine.transitions {
                let at = At {
                    machine: Some(k),
                    place: format!("{file}:{} (a label)", t.line),
                };
                let flow = self.expr(&at, &t.label);
                self.truth_use(&at, &flow);
            }
        }
        for theory in &model.theories {
            let at = At {
                machine: None,
                place: format!("the inputs of theory {}", theory.name),
            };
            for (_, name) in &theory.inputs {
                if let Some(Name::Slot(slot)) = name {
                    let flow = self.places[*slot].clone();
                    self.truth_use(&at, &flow);
                }
            }
        }
        for e in properties {
            let at = At {
                machine: None,
                // A property's `Machine.STATE` is parsed with its dot replaced.
                place: format!("the property `{e}`").replace(crate::model::DOT, "."),
            };
            let flow = self.expr(&at, e);
            self.truth_use(&at, &flow);
        }
    }

    /// What a statement does, as [`proclaim_lower::read`] meets its kinds.
    fn statement(&mut self, at: &At, s: &Statement) {
        read_statement(&mut FlowOf { analysis: self, at }, s);
    }

    fn call_statement(&mut self, at: &At, function: &str, arguments: &[Expr]) {
        match builtin(function, arguments) {
            Builtin::Post { to, content } => {
                let flow = match content {
                    Content::Value(e) => {
                        self.copied_from(at, e);
                        self.expr(at, e)
                    }
                    Content::Int(e) => {
                        let f = self.expr(at, e);
                        self.converted(&f, &VarType::Int)
                    }
                    Content::Command(c) => Flow::constant(Value::Str(c.word().into())),
                    Content::Joined(parts) | Content::List(parts) => {
                        self.joined(at, parts, "posted as part of text or a list")
                    }
                    Content::Text(e) => self.joined(at, std::slice::from_ref(e), "posted as text"),
                    Content::StateName => Flow::computed(),
                };
                match to {
                    Target::Fixed(ty) => self.post(at, ty, &flow),
                    Target::Named(e) => {
                        let name = self.expr(at, e);
                        match (&name.constants, name.terms.is_empty()) {
                            (Some(names), true) => {
                                for n in names.clone() {
                                    self.post(at, &arith::text(&n), &flow);
                                }
                            }
                            _ => {
                                for t in flow.terms.iter().chain(&name.terms) {
                                    let why = format!("it is posted to a type whose name `{e}` is computed at run time");
                                    self.inexact(at, &t.opaque(why));
                                }
                            }
                        }
                    }
                }
            }
            _ => {
                for a in arguments {
                    self.expr(at, a);
                }
            }
        }
    }

    /// Text made of `parts`: nothing a free domain follows once a free value is in it.
    fn joined(&mut self, at: &At, parts: &[Expr], why: &str) -> Flow {
        let mut out = Flow::computed();
        for p in parts {
            let f = self.expr(at, p);
            out.terms
                .extend(f.terms.iter().map(|t| t.opaque(format!("`{p}` is {why}"))));
        }
        out.bound_terms();
        out
    }

    /// `name = value`, as the ringlet stores it: the machine's own variable (converted to its
    /// type), a global, or a posting.
    fn assign(&mut self, at: &At, name: &str, flow: Flow) {
        match self.model.resolve(at.machine, name) {
            Some(Name::Slot(slot)) => {
                let flow = match &self.model.slots[slot].kind {
                    SlotKind::Local {
                        ty: VarType::Bool, ..
                    } => {
                        self.truth_use(at, &flow);
                        Flow::truth()
                    }
                    SlotKind::Local { ty, .. } => self.converted(&flow, ty),
                    SlotKind::Global | SlotKind::Message { .. } => flow,
                };
                self.store(slot, &flow);
            }
            _ => self.post(at, name, &flow),
        }
    }

    fn converted(&self, flow: &Flow, ty: &VarType) -> Flow {
        if matches!(ty, VarType::Named(_)) {
            return flow.clone();
        }
        Flow {
            constants: flow.map_constants(|v| Some(arith::convert(ty, v.clone()))),
            terms: flow
                .terms
                .iter()
                .map(|t| t.then(Op::Convert(ty.clone())))
                .collect(),
        }
    }

    fn post(&mut self, at: &At, ty: &str, flow: &Flow) {
        if self.model.machine_index(ty).is_some() {
            for t in &flow.terms {
                let why = format!("it is posted to machine {ty} as a control command");
                self.inexact(at, &t.opaque(why));
            }
            return;
        }
        if let Some(&Name::Slot(slot)) = self.model.names.get(ty) {
            if matches!(self.model.slots[slot].kind, SlotKind::Message { .. }) {
                self.store(slot, flow);
            }
        }
    }

    fn store(&mut self, slot: SlotId, flow: &Flow) {
        if self.places[slot].join(flow) {
            self.changed = true;
        }
    }

    fn expr(&mut self, at: &At, e: &Expr) -> Flow {
        match e {
            Expr::Bool(b) => Flow::constant(Value::Bool(*b)),
            Expr::Int(i) => Flow::constant(Value::Int(*i)),
            Expr::Float(x) => Flow::constant(Value::Float(*x)),
            Expr::Str(s) => Flow::constant(Value::Str(s.clone())),
            Expr::Duration(us) => Flow::constant(Value::Int(*us as i64)),
            Expr::Name(n) => match self.model.resolve(at.machine, n) {
                Some(Name::Slot(slot)) => self.places[slot].clone(),
                Some(Name::Answer { .. } | Name::Running(_)) => Flow::truth(),
                None => Flow::nothing(),
            },
            Expr::Unary {
                op: UnOp::Not,
                operand,
            } => {
                let f = self.expr(at, operand);
                self.truth_use(at, &f);
                Flow::truth()
            }
            Expr::Unary {
                op: UnOp::Neg,
                operand,
            } => {
                let f = self.expr(at, operand);
                Flow {
                    constants: f.map_constants(arith::negate),
                    terms: f.terms.iter().map(|t| t.then(Op::Neg)).collect(),
                }
            }
            Expr::Binary { op, left, right } => {
                let (l, r) = (self.expr(at, left), self.expr(at, right));
                match op {
                    BinOp::And | BinOp::Or => {
                        self.truth_use(at, &l);
                        self.truth_use(at, &r);
                        Flow::truth()
                    }
                    BinOp::Eq | BinOp::Ne | BinOp::Lt | BinOp::Le | BinOp::Gt | BinOp::Ge => {
                        self.compare_use(at, *op, (&l, left), (&r, right), e);
                        Flow::truth()
                    }
                    _ => arithmetic(*op, &l, &r, e),
                }
            }
            Expr::Call {
                function,
                arguments,
                ..
            } => self.call(at, function, arguments, e),
        }
    }

    fn call(&mut self, at: &At, function: &str, arguments: &[Expr], e: &Expr) -> Flow {
        if function == "saw" {
            // A property's `saw(Machine, e)`: `e` as that machine reads it.
            if let [Expr::Name(m), inner] = arguments {
                let inner_at = At {
                    machine: self.model.machine_index(m),
                    place: at.place.clone(),
                };
                let f = self.expr(&inner_at, inner);
                self.truth_use(&inner_at, &f);
                return Flow::truth();
            }
        }
        let flows: Vec<Flow> = arguments.iter().map(|a| self.expr(at, a)).collect();
        if TIME_TESTS.iter().any(|(f, _)| *f == function) {
            return Flow::truth();
        }
        if !arith::is_function(function) {
            // A host function: the model gives it no value.
            return Flow::nothing();
        }
        let monotone = ["round", "floor", "ceil"]
            .into_iter()
            .find(|f| *f == function);
        let mut out = Flow::nothing();
        out.constants = constants_of(function, &flows);
        for f in &flows {
            for t in &f.terms {
                out.terms.push(match (monotone, flows.len()) {
                    (Some(name), 1) => t.then(Op::Function(name)),
                    _ => t.opaque(format!("`{e}` passes it to {function}()")),
                });
            }
        }
        out.bound_terms();
        out
    }

    /// A place read by name into another (`b = a`): an old value it holds may yet be compared.
    fn copied_from(&mut self, at: &At, value: &Expr) {
        if !self.record {
            return;
        }
        if let Expr::Name(n) = value {
            if let Some(Name::Slot(slot)) = self.model.resolve(at.machine, n) {
                if !self.facts.copy_sources.contains(&slot) {
                    self.facts.copy_sources.push(slot);
                }
            }
        }
    }

    /// `flow` tested as a truth value.
    fn truth_use(&mut self, at: &At, flow: &Flow) {
        if !self.record {
            return;
        }
        for t in &flow.terms {
            match t {
                Term::Chain { input, ops } => self.predicate(
                    *input,
                    Predicate {
                        ops: ops.clone(),
                        test: Test::Truth,
                    },
                ),
                Term::Opaque { .. } => self.inexact(at, &t.clone()),
            }
        }
    }

    /// `l op r`: each side's terms against the other side's constants; plain copies against
    /// each other.
    fn compare_use(
        &mut self,
        at: &At,
        op: BinOp,
        (l, left): (&Flow, &Expr),
        (r, right): (&Flow, &Expr),
        e: &Expr,
    ) {
        if !self.record {
            return;
        }
        for (mine, other, op) in [(l, r, op), (r, l, flipped(op))] {
            for t in &mine.terms {
                let Term::Chain { input, ops } = t else {
                    self.inexact(at, t);
                    continue;
                };
                match &other.constants {
                    Some(constants) => {
                        for c in constants {
                            self.predicate(
                                *input,
                                Predicate {
                                    ops: ops.clone(),
                                    test: Test::Compare(op, c.clone()),
                                },
                            );
                        }
                    }
                    None => self.inexact(
                        at,
                        &t.opaque(format!(
                            "`{e}` compares it with a value computed at run time"
                        )),
                    ),
                }
            }
        }
        for tl in &l.terms {
            for tr in &r.terms {
                if tl.is_copy() && tr.is_copy() {
                    let pair = (tl.input().min(tr.input()), tl.input().max(tr.input()));
                    if !self.facts.pairs.contains(&pair) {
                        self.facts.pairs.push(pair);
                    }
                    // A plain copy is read from a place by name: the places whose values are
                    // compared with each other.
                    for side in [left, right] {
                        let place = match side {
                            Expr::Name(n) => match self.model.resolve(at.machine, n) {
                                Some(Name::Slot(slot)) => slot,
                                _ => continue,
                            },
                            _ => continue,
                        };
                        if !self.facts.compared_places.contains(&place) {
                            self.facts.compared_places.push(place);
                        }
                    }
                } else {
                    let why = format!("`{e}` compares a computed free value with another");
                    self.inexact(at, &tl.opaque(why.clone()));
                    self.inexact(at, &tr.opaque(why));
                }
            }
        }
    }

    fn predicate(&mut self, input: SlotId, p: Predicate) {
        let list = &mut self.facts.predicates[input];
        if !list.contains(&p) {
            list.push(p);
        }
    }

    fn inexact(&mut self, at: &At, t: &Term) {
        if !self.record {
            return;
        }
        let Term::Opaque { input, why } = t else {
            return;
        };
        if self.seen_inexact.insert((*input, why.clone())) {
            self.facts.inexact.push(Inexact {
                value: self.model.slots[*input].name.clone(),
                why: why.clone(),
                place: at.place.clone(),
            });
        }
    }
}

/// `l op r` for an arithmetic operator.
fn arithmetic(op: BinOp, l: &Flow, r: &Flow, e: &Expr) -> Flow {
    let constants = match (&l.constants, &r.constants) {
        (Some(a), Some(b)) if a.len() * b.len() <= MAX_CONSTANTS => {
            let mut out = Vec::new();
            for x in a {
                for y in b {
                    if let Some(v) = arith::binary(op, Some(x.clone()), Some(y.clone())) {
                        if !out.contains(&v) {
                            out.push(v);
                        }
                    }
                }
            }
            Some(out)
        }
        _ => None,
    };
    let mut terms = Vec::new();
    for (mine, other, constant_left) in [(l, r, false), (r, l, true)] {
        for t in &mine.terms {
            if !other.terms.is_empty() {
                terms.push(t.opaque(format!("`{e}` combines it with another free value")));
                continue;
            }
            let Some(constants) = &other.constants else {
                terms.push(t.opaque(format!(
                    "`{e}` combines it with a value computed at run time"
                )));
                continue;
            };
            for c in constants {
                let why = if op == BinOp::Rem {
                    Some("takes a remainder of it")
                } else if constant_left && op == BinOp::Div {
                    Some("divides by it")
                } else if matches!(c, Value::Str(_)) {
                    Some("joins it with text")
                } else {
                    None
                };
                terms.push(match why {
                    Some(why) => t.opaque(format!("`{e}` {why}")),
                    None => t.then(Op::Arith {
                        op,
                        constant: c.clone(),
                        constant_left,
                    }),
                });
            }
        }
    }
    let mut flow = Flow { constants, terms };
    flow.bound_terms();
    flow
}

/// The constants a built-in function gives on its arguments' constants.
fn constants_of(function: &str, flows: &[Flow]) -> Option<Vec<Value>> {
    let mut rows: Vec<Vec<Option<Value>>> = vec![Vec::new()];
    for f in flows {
        let constants = f.constants.as_ref()?;
        let mut next = Vec::new();
        for row in &rows {
            for c in constants {
                let mut r = row.clone();
                r.push(Some(c.clone()));
                next.push(r);
            }
        }
        if next.len() > MAX_CONSTANTS {
            return None;
        }
        rows = next;
    }
    let mut out = Vec::new();
    for row in rows {
        if let Some(v) = arith::function(function, &row) {
            if !out.contains(&v) {
                out.push(v);
            }
        }
    }
    Some(out)
}

/// `a op b` as `b op' a`.
fn flipped(op: BinOp) -> BinOp {
    match op {
        BinOp::Lt => BinOp::Gt,
        BinOp::Gt => BinOp::Lt,
        BinOp::Le => BinOp::Ge,
        BinOp::Ge => BinOp::Le,
        other => other,
    }
}
