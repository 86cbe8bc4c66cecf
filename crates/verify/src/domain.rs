//! The values the free environment may give a whiteboard type: a finite abstraction of "any
//! value of its kind" that keeps the truth of every test the behaviour makes of it (spec §6,
//! "Free values").
//!
//! [`crate::flow`] finds every test of a free type's value: the value, or a chain of monotone
//! operations on it (`rr = ballRR`, `Battery_Charge / 10`), compared with a constant or taken
//! as a truth. Each such test splits the type's values into at most three intervals, whose
//! ends are found by bisection with the runner's own operators (`Space::boundaries`). The
//! domain is [`Domains::of_constants`] (every constant the behaviour gives the type, kept
//! whole so that a run posting one is a path of the model value for value) and one value of
//! every interval not already stood for by a value on which every test agrees: on it each
//! label, activity and property takes every truth a real value could give it. Where copies
//! of free values are compared with each other, each interval holds as many values as there
//! are places so compared, so that every order among them is there too. Whole numbers
//! range over C's 32-bit `int` (gufsm's values), widened to take in every constant; a type
//! the behaviour compares with a fraction ranges over fractions. Every free type may also
//! still be "never posted" in the initial state (a sensor that has not spoken yet).
//!
//! [`Domains`] gathers the constants a behaviour gives each type (what it posts, assigns and
//! compares): they also say what kind of value a type holds, for the properties' kind checks.

use crate::flow::{apply, Facts, Op, Predicate, Test};
use crate::kind::ValueKind;
use crate::model::{FreeDomain, Slot, SlotId};
use crate::outcome::Inexact;
use proclaim_board::Value;
use proclaim_fsm::{Action, BinOp, Expr, Machine, Statement};
use proclaim_lower::arith;
use rustc_hash::{FxHashMap, FxHashSet};

/// Constants gathered per type while reading the behaviour.
#[derive(Debug, Default)]
pub struct Domains {
    seen: FxHashMap<String, Vec<Value>>,
    conditions: FxHashSet<String>,
}

impl Domains {
    pub fn add(&mut self, name: &str, value: Value) {
        let values = self.seen.entry(name.to_string()).or_default();
        if !values.contains(&value) {
            values.push(value);
        }
    }

    /// Constants a machine compares or posts.
    pub fn gather_machine(&mut self, machine: &Machine) {
        for t in &machine.transitions {
            self.gather_expr(&t.label);
        }
        for a in machine.actions() {
            if let Action::Post { ty, content } = a {
                self.add(ty, Value::parse(content));
            }
        }
        for s in machine.statements() {
            for e in s.expressions() {
                // A value copied or posted (`rr = ballRR`) is no truth test of it; a loop's
                // condition, a `!` or an `&&` inside one is.
                if !matches!(e, Expr::Name(_)) || matches!(s, Statement::For { .. }) {
                    self.gather_expr(e);
                }
            }
            if let Statement::Assign { name, value } = s {
                if let Some(v) = constant(value) {
                    self.add(name, v);
                }
            }
            if let Statement::Expr(Expr::Call {
                function,
                arguments,
                ..
            }) = s
            {
                if let ("post" | "post_int", [Expr::Str(ty), value]) =
                    (function.as_str(), arguments.as_slice())
                {
                    if let Some(v) = constant(value) {
                        self.add(ty, v);
                    }
                }
            }
        }
    }

    /// Constants an expression compares names with, and the names it uses as truth values.
    pub fn gather_expr(&mut self, expr: &Expr) {
        expr.visit_names(&mut |name, condition| {
            if condition {
                self.conditions.insert(name.to_string());
            }
        });
        self.comparisons(expr);
    }

    fn comparisons(&mut self, expr: &Expr) {
        match expr {
            Expr::Binary { op, left, right } => {
                let compares = matches!(
                    op,
                    BinOp::Lt | BinOp::Le | BinOp::Gt | BinOp::Ge | BinOp::Eq | BinOp::Ne
                );
                if compares {
                    for (a, b) in [(left, right), (right, left)] {
                        if let (Expr::Name(n), Some(c)) = (&**a, constant(b)) {
                            if matches!(op, BinOp::Lt | BinOp::Le | BinOp::Gt | BinOp::Ge) {
                                for v in neighbours(&c) {
                                    self.add(n, v);
                                }
                            }
                            self.add(n, c);
                        }
                    }
                }
                self.comparisons(left);
                self.comparisons(right);
            }
            Expr::Unary { operand, .. } => self.comparisons(operand),
            Expr::Call { arguments, .. } => arguments.iter().for_each(|a| self.comparisons(a)),
            _ => {}
        }
    }

    /// The constants gathered for `name`, in first-met order.
    pub fn seen(&self, name: &str) -> &[Value] {
        self.seen.get(name).map_or(&[], Vec::as_slice)
    }

    /// What kind of value `name` holds, as its constants say; a type given no constant and
    /// never used as a truth may hold anything (`rr = ballRR` says nothing of `ballRR`).
    pub fn kind(&self, name: &str) -> ValueKind {
        if self.seen(name).is_empty() && !self.conditions.contains(name) {
            return ValueKind::Any;
        }
        ValueKind::of_values(&self.of_constants(name).values)
    }

    /// The domain of the constants alone: every constant the behaviour compares `name` with
    /// or gives it, the neighbours of each it orders it against, one other value, and both
    /// truths where it is used as one. [`sound_domains`] adds the intervals' values to it.
    pub fn of_constants(&self, name: &str) -> FreeDomain {
        let seen = self.seen(name);
        let mut values: Vec<Value> = if seen.iter().all(|v| matches!(v, Value::Bool(_))) {
            vec![Value::Bool(false), Value::Bool(true)]
        } else {
            let mut values = seen.to_vec();
            values.push(other(seen));
            values
        };
        if self.conditions.contains(name) {
            for truth in [false, true] {
                if !values.iter().any(|v| v.truthy() == truth) {
                    values.push(Value::Bool(truth));
                }
            }
        }
        FreeDomain::of(values)
    }
}

impl FreeDomain {
    pub(crate) fn of(values: Vec<Value>) -> FreeDomain {
        let initial = std::iter::once(None)
            .chain(values.iter().cloned().map(Some))
            .collect();
        FreeDomain { values, initial }
    }
}

/// The domain of every free slot of `slots` from what [`crate::flow`] found, and the tests no
/// finite domain keeps (arithmetic that may wrap around, text compared by its order).
pub fn sound_domains(
    slots: &[Slot],
    facts: &Facts,
    hints: &Domains,
) -> (Vec<Option<FreeDomain>>, Vec<Inexact>) {
    let free: Vec<SlotId> = (0..slots.len())
        .filter(|&i| slots[i].free.is_some())
        .collect();
    // Free types whose copies are compared with each other share their intervals.
    let mut group: Vec<SlotId> = (0..slots.len()).collect();
    fn root(group: &mut [SlotId], mut i: SlotId) -> SlotId {
        while group[i] != i {
            group[i] = group[group[i]];
            i = group[i];
        }
        i
    }
    for &(a, b) in &facts.pairs {
        let (ra, rb) = (root(&mut group, a), root(&mut group, b));
        group[ra.max(rb)] = ra.min(rb);
    }
    let mut domains = vec![None; slots.len()];
    let mut inexact = Vec::new();
    for &leader in &free {
        if root(&mut group, leader) != leader {
            continue;
        }
        let members: Vec<SlotId> = free
            .iter()
            .copied()
            .filter(|&m| root(&mut group, m) == leader)
            .collect();
        let k = values_an_interval(facts, &members);
        let mut tests: Vec<(SlotId, &Predicate)> = Vec::new();
        let mut hint_values: Vec<Value> = Vec::new();
        for &m in &members {
            tests.extend(facts.predicates[m].iter().map(|p| (m, p)));
            for v in hints.of_constants(&slots[m].name).values {
                if !hint_values.contains(&v) {
                    hint_values.push(v);
                }
            }
        }
        let group = Group {
            tests: &tests,
            hints: &hint_values,
            k,
        };
        let values = group.values(slots, &mut inexact);
        for &m in &members {
            domains[m] = Some(FreeDomain::of(values.clone()));
        }
    }
    (domains, inexact)
}

/// How many values of a group each interval needs: one where no two places' copies of its
/// values are compared; else one for every place whose copy may be compared, now or after it
/// is copied on (`b = a; … b < in0`: `a`, `b` and `in0` may hold three values at once, each
/// to be ordered against the others).
fn values_an_interval(facts: &Facts, members: &[SlotId]) -> usize {
    let holds_ours = |p: &SlotId| facts.copies_in[*p].iter().any(|i| members.contains(i));
    let compared = facts
        .compared_places
        .iter()
        .filter(|p| holds_ours(p))
        .count();
    if compared < 2 {
        return 1;
    }
    let mut places: Vec<SlotId> = facts
        .compared_places
        .iter()
        .chain(&facts.copy_sources)
        .copied()
        .filter(holds_ours)
        .collect();
    places.sort_unstable();
    places.dedup();
    places.len()
}

/// Free types whose values are chosen together, and every test made of them.
struct Group<'a> {
    tests: &'a [(SlotId, &'a Predicate)],
    hints: &'a [Value],
    /// Values each interval holds.
    k: usize,
}

impl Group<'_> {
    fn values(&self, slots: &[Slot], inexact: &mut Vec<Inexact>) -> Vec<Value> {
        let constants = || {
            self.tests.iter().filter_map(|(_, p)| match &p.test {
                Test::Compare(_, c) => Some(c),
                Test::Truth => None,
            })
        };
        let chained = self.tests.iter().any(|(_, p)| !p.ops.is_empty());
        let text = constants().any(|c| matches!(c, Value::Str(_)));
        let number = chained
            || constants().any(|c| matches!(c, Value::Int(_) | Value::Float(_)))
            || self
                .hints
                .iter()
                .any(|v| matches!(v, Value::Int(_) | Value::Float(_)));
        if !text && !number {
            let mut values = vec![Value::Bool(false), Value::Bool(true)];
            values.extend(
                self.hints
                    .iter()
                    .filter(|v| !values.contains(v))
                    .cloned()
                    .collect::<Vec<_>>(),
            );
            return values;
        }
        let mut points = Vec::new();
        if number {
            points.extend(self.number_points(slots, inexact));
        }
        if text {
            points.extend(self.text_points(slots, inexact));
        }
        if self.tests.iter().any(|(_, p)| p.test == Test::Truth) {
            // A type used as a truth may be posted one (a script's `false`, an assignment).
            points.extend([Value::Bool(false), Value::Bool(true)]);
        }
        // The constants the behaviour gives the type stay (a run that posts them is then a
        // path of the model value for value, as the conformance test follows it); of the
        // values added here, one read at a time, those every test takes alike as a value
        // already there are left out.
        let mut kept: Vec<(Vec<bool>, Value)> = Vec::new();
        let signature =
            |v: &Value| -> Vec<bool> { self.tests.iter().map(|(_, p)| holds(p, v)).collect() };
        for v in self.hints {
            if !kept.iter().any(|(_, k)| k == v) {
                kept.push((signature(v), v.clone()));
            }
        }
        for v in points {
            let s = signature(&v);
            let same = kept
                .iter()
                .any(|(k, kv)| *kv == v || (self.k == 1 && *k == s));
            if !same {
                kept.push((s, v));
            }
        }
        kept.into_iter().map(|(_, v)| v).collect()
    }

    /// One value of every interval the numeric tests cut (`k` where copies are compared).
    fn number_points(&self, slots: &[Slot], inexact: &mut Vec<Inexact>) -> Vec<Value> {
        let space = Space::of(self.tests, self.hints);
        let mut cuts = Vec::new();
        for (m, p) in self.tests {
            if matches!(&p.test, Test::Compare(_, Value::Str(_))) {
                continue;
            }
            if let Some(why) = space.wraps(&p.ops) {
                inexact.push(Inexact {
                    value: slots[*m].name.clone(),
                    why,
                    place: "its tests".into(),
                });
            }
            cuts.extend(space.boundaries(p));
        }
        cuts.sort_unstable();
        cuts.dedup();
        space.representatives(&cuts, self.k)
    }

    /// The text constants and `k` texts equal to none of them.
    fn text_points(&self, slots: &[Slot], inexact: &mut Vec<Inexact>) -> Vec<Value> {
        let constants = || {
            self.tests.iter().filter_map(|(_, p)| match &p.test {
                Test::Compare(_, c) => Some(c),
                Test::Truth => None,
            })
        };
        for (m, p) in self.tests {
            if let Test::Compare(op, Value::Str(_)) = &p.test {
                if !matches!(op, BinOp::Eq | BinOp::Ne) {
                    inexact.push(Inexact {
                        value: slots[*m].name.clone(),
                        why: format!(
                            "it is compared with text by `{}`, by text order",
                            op.symbol()
                        ),
                        place: "its tests".into(),
                    });
                }
            }
        }
        let mut texts: Vec<Value> = Vec::new();
        for c in constants() {
            if matches!(c, Value::Str(_)) && !texts.contains(c) {
                texts.push(c.clone());
            }
        }
        let mut other = "other".to_string();
        for _ in 0..self.k {
            while texts.contains(&Value::Str(other.clone())) {
                other.push('_');
            }
            texts.push(Value::Str(other.clone()));
        }
        texts
    }
}

/// Whether test `p` holds of value `x`, as the runner computes it.
fn holds(p: &Predicate, x: &Value) -> bool {
    let Some(v) = apply(&p.ops, x.clone()) else {
        return false;
    };
    match &p.test {
        Test::Truth => v.truthy(),
        Test::Compare(op, c) => {
            arith::binary(*op, Some(v), Some(c.clone())).is_some_and(|r| r.truthy())
        }
    }
}

/// Numbers as points of a line the bisection walks: whole numbers, or fractions (ordered by
/// their bits, so that every fraction between two is there).
#[derive(Clone, Copy, Debug)]
enum Space {
    Whole { low: i64, high: i64 },
    Fraction { low: f64, high: f64 },
}

/// C's `int`, the range of gufsm's values.
const WHOLE: (i64, i64) = (i32::MIN as i64, i32::MAX as i64);
const FRACTION: (f64, f64) = (-1e15, 1e15);

impl Space {
    fn of(tests: &[(SlotId, &Predicate)], hints: &[Value]) -> Space {
        let mut numbers: Vec<&Value> = hints.iter().collect();
        for (_, p) in tests {
            if let Test::Compare(_, c) = &p.test {
                numbers.push(c);
            }
            for op in &p.ops {
                if let Op::Arith { constant, .. } = op {
                    numbers.push(constant);
                }
            }
        }
        let fraction = numbers.iter().any(|v| matches!(v, Value::Float(_)));
        let extreme = |pick: fn(f64, f64) -> f64, start: f64| {
            numbers.iter().filter_map(|v| v.as_f64()).fold(start, pick)
        };
        if fraction {
            Space::Fraction {
                low: extreme(f64::min, FRACTION.0) - 1.0,
                high: extreme(f64::max, FRACTION.1) + 1.0,
            }
        } else {
            let pad = 64.0;
            let low = (extreme(f64::min, WHOLE.0 as f64) - pad).max(i64::MIN as f64 / 2.0);
            let high = (extreme(f64::max, WHOLE.1 as f64) + pad).min(i64::MAX as f64 / 2.0);
            Space::Whole {
                low: low as i64,
                high: high as i64,
            }
        }
    }

    fn ordinal_range(self) -> (u64, u64) {
        match self {
            Space::Whole { low, high } => (whole_ordinal(low), whole_ordinal(high)),
            Space::Fraction { low, high } => (fraction_ordinal(low), fraction_ordinal(high)),
        }
    }

    fn value(self, o: u64) -> Value {
        match self {
            Space::Whole { .. } => Value::Int((o ^ (1 << 63)) as i64),
            Space::Fraction { .. } => Value::Float(if o >> 63 == 1 {
                f64::from_bits(o & !(1 << 63))
            } else {
                f64::from_bits(!o)
            }),
        }
    }

    /// The first values of each interval on which `p`'s outcome is constant (the test's
    /// ordering against its constant, so `==` cuts twice): the chain is monotone, so its
    /// comparison with a constant changes at most twice along the line.
    fn boundaries(self, p: &Predicate) -> Vec<u64> {
        let c = match &p.test {
            Test::Compare(_, c) => c.clone(),
            Test::Truth => Value::Int(0),
        };
        let rank = |o: u64| -> u8 {
            match apply(&p.ops, self.value(o)).and_then(|v| arith::compare(&v, &c)) {
                Some(std::cmp::Ordering::Less) => 0,
                Some(std::cmp::Ordering::Equal) => 1,
                Some(std::cmp::Ordering::Greater) => 2,
                None => 3,
            }
        };
        let (low, high) = self.ordinal_range();
        let mut out = Vec::new();
        bisect(low, high, rank(low), rank(high), &rank, &mut out);
        out
    }

    /// `k` values of every interval that `cuts` (sorted) leaves, the one below the first cut
    /// included; for whole numbers, fewer where an interval holds fewer.
    fn representatives(self, cuts: &[u64], k: usize) -> Vec<Value> {
        let k = k as u64;
        let mut out = Vec::new();
        let (low, high) = self.ordinal_range();
        let mut starts = vec![];
        match cuts.first() {
            Some(&first) if first > low => starts.push((first.saturating_sub(k).max(low), first)),
            Some(_) => {}
            None => starts.push((whole_or_zero(self), high)),
        }
        for (i, &c) in cuts.iter().enumerate() {
            let end = cuts.get(i + 1).copied().unwrap_or(high);
            starts.push((c, end.max(c + 1)));
        }
        for (start, end) in starts {
            match self {
                Space::Whole { .. } => {
                    for o in start..end.min(start + k) {
                        out.push(self.value(o));
                    }
                }
                Space::Fraction { .. } => {
                    let (a, b) = (self.value(start), self.value(end));
                    let (a, b) = (a.as_f64().unwrap_or(0.0), b.as_f64().unwrap_or(0.0));
                    for j in 0..k {
                        let x = if j == 0 {
                            a
                        } else {
                            a + (b - a) * j as f64 / k as f64
                        };
                        let v = Value::Float(x);
                        if !out.contains(&v) {
                            out.push(v);
                        }
                    }
                }
            }
        }
        out
    }

    /// Why the runner's whole-number arithmetic on a chain may wrap around within the range,
    /// if it may (the chain is then not monotone there).
    fn wraps(self, ops: &[Op]) -> Option<String> {
        let Space::Whole { low, high } = self else {
            return None;
        };
        for x in [low, high] {
            let mut exact = i128::from(x);
            let mut v = Value::Int(x);
            for op in ops {
                let (next_exact, next) = match op {
                    Op::Arith {
                        op,
                        constant: Value::Int(c),
                        constant_left,
                    } => {
                        let c = i128::from(*c);
                        let (a, b) = if *constant_left {
                            (c, exact)
                        } else {
                            (exact, c)
                        };
                        let e = match op {
                            BinOp::Add => a + b,
                            BinOp::Sub => a - b,
                            // Beyond i128 is beyond i64 too: reported below as wrapping.
                            BinOp::Mul => a.checked_mul(b).unwrap_or(i128::MAX),
                            BinOp::Div if b == 0 => i128::from(i64::MAX),
                            BinOp::Div => a / b,
                            _ => return None,
                        };
                        (
                            e,
                            apply(
                                std::slice::from_ref(&Op::Arith {
                                    op: *op,
                                    constant: Value::Int(c as i64),
                                    constant_left: *constant_left,
                                }),
                                v,
                            )?,
                        )
                    }
                    Op::Neg => (-exact, apply(&[Op::Neg], v)?),
                    // Fractions and conversions do not wrap.
                    _ => return None,
                };
                if i64::try_from(next_exact).map_or(true, |e| next != Value::Int(e)) {
                    return Some(format!(
                        "its arithmetic wraps around for {x}, within the whole numbers it may take"
                    ));
                }
                exact = next_exact;
                v = next;
            }
        }
        None
    }
}

fn whole_or_zero(space: Space) -> u64 {
    match space {
        Space::Whole { .. } => whole_ordinal(0),
        Space::Fraction { .. } => fraction_ordinal(0.0),
    }
}

fn whole_ordinal(x: i64) -> u64 {
    (x as u64) ^ (1 << 63)
}

fn fraction_ordinal(x: f64) -> u64 {
    let bits = x.to_bits();
    if bits >> 63 == 1 {
        !bits
    } else {
        bits | (1 << 63)
    }
}

/// The ordinals in `(low, high]` where `rank` differs from its value just below, for a
/// monotone `rank`.
fn bisect(
    low: u64,
    high: u64,
    at_low: u8,
    at_high: u8,
    rank: &dyn Fn(u64) -> u8,
    out: &mut Vec<u64>,
) {
    if at_low == at_high || high <= low {
        return;
    }
    if high - low == 1 {
        out.push(high);
        return;
    }
    let mid = low + (high - low) / 2;
    let at_mid = rank(mid);
    bisect(low, mid, at_low, at_mid, rank, out);
    bisect(mid, high, at_mid, at_high, rank, out);
}

/// A literal's value (`-3` is a literal too).
fn constant(e: &Expr) -> Option<Value> {
    Some(match e {
        Expr::Bool(b) => Value::Bool(*b),
        Expr::Int(i) => Value::Int(*i),
        Expr::Float(x) => Value::Float(*x),
        Expr::Str(s) => Value::Str(s.clone()),
        Expr::Unary {
            op: proclaim_fsm::UnOp::Neg,
            operand,
        } => match constant(operand)? {
            Value::Int(i) => Value::Int(i.wrapping_neg()),
            Value::Float(x) => Value::Float(-x),
            _ => return None,
        },
        _ => return None,
    })
}

/// Values just below and above a number an ordering compares with.
fn neighbours(c: &Value) -> Vec<Value> {
    match c {
        Value::Int(i) => vec![Value::Int(i.wrapping_sub(1)), Value::Int(i.wrapping_add(1))],
        Value::Float(x) => vec![Value::Float(x - 0.5), Value::Float(x + 0.5)],
        _ => Vec::new(),
    }
}

/// A value equal to none of `seen` and of the same kind as most of them.
fn other(seen: &[Value]) -> Value {
    if seen.iter().any(|v| matches!(v, Value::Str(_))) {
        let mut candidate = "other".to_string();
        while seen.contains(&Value::Str(candidate.clone())) {
            candidate.push('_');
        }
        Value::Str(candidate)
    } else {
        let largest = seen
            .iter()
            .filter_map(Value::as_f64)
            .fold(0.0_f64, f64::max);
        Value::Int(largest as i64 + 1000)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn whole() -> Space {
        Space::Whole {
            low: WHOLE.0,
            high: WHOLE.1,
        }
    }

    fn test(ops: Vec<Op>, op: BinOp, c: i64) -> Predicate {
        Predicate {
            ops,
            test: Test::Compare(op, Value::Int(c)),
        }
    }

    fn divided_by(c: i64) -> Vec<Op> {
        vec![Op::Arith {
            op: BinOp::Div,
            constant: Value::Int(c),
            constant_left: false,
        }]
    }

    /// The first value of each interval the test cuts, as whole numbers.
    fn check(p: &Predicate, expect: &[i64]) {
        let space = whole();
        let cuts: Vec<Value> = space
            .boundaries(p)
            .into_iter()
            .map(|o| space.value(o))
            .collect();
        let expect: Vec<Value> = expect.iter().map(|&i| Value::Int(i)).collect();
        assert_eq!(cuts, expect, "{p:?}");
    }

    #[test]
    fn a_test_cuts_where_the_runners_arithmetic_changes_its_outcome() {
        check(&test(vec![], BinOp::Lt, 20), &[20, 21]);
        check(&test(vec![], BinOp::Eq, -3), &[-3, -2]);
        // Truncating division: every x from -9 to 9 is 0 when divided by 10.
        check(&test(divided_by(10), BinOp::Lt, 0), &[-9, 10]);
        check(&test(divided_by(10), BinOp::Lt, 20), &[200, 210]);
        // Dividing by a negative number turns the order round.
        check(&test(divided_by(-10), BinOp::Gt, 2), &[-29, -19]);
        check(
            &Predicate {
                ops: vec![Op::Neg],
                test: Test::Truth,
            },
            &[0, 1],
        );
    }

    #[test]
    fn each_interval_has_a_value_and_values_alike_are_one() {
        let tests = [test(vec![], BinOp::Gt, 0), test(vec![], BinOp::Lt, 0)];
        let tests: Vec<(SlotId, &Predicate)> = tests.iter().map(|p| (0, p)).collect();
        let group = Group {
            tests: &tests,
            hints: &[],
            k: 1,
        };
        let mut inexact = Vec::new();
        let values = group.number_points(&[], &mut inexact);
        // Below, at and above 0: the sign of a copied sighting.
        assert_eq!(values, [Value::Int(-1), Value::Int(0), Value::Int(1)]);
        assert!(inexact.is_empty());
    }

    #[test]
    fn arithmetic_that_wraps_within_the_range_is_said() {
        let times = |c| Op::Arith {
            op: BinOp::Mul,
            constant: Value::Int(c),
            constant_left: false,
        };
        assert_eq!(whole().wraps(&[times(1000)]), None);
        assert!(whole()
            .wraps(&[times(1 << 40)])
            .is_some_and(|why| why.contains("wraps around")));
    }
}
