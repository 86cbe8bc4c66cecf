//! A proving session over a compiled engine: input values, the μ closure, and every goal's
//! answer, computed on demand component by component and re-proved only where an input change
//! reaches.

use crate::engine::Engine;
use crate::goal::{
    condition, goal, successors, Goal, Read, ATTACK, ATTACK_READ, BETA, KINDS, PI, SUP,
};
use crate::literal::{Atom, Lit};
use crate::query::Formula;
use crate::theory::RuleKind;
use proclaim_syntax::Algorithm;
use rustc_hash::FxHashMap;
use std::fmt;
use std::sync::Arc;

const UNKNOWN: u8 = 0;
const FALSE: u8 = 1;
const TRUE: u8 = 2;
/// A member of the component being evaluated.
const PENDING: u8 = 3;

/// Components larger than this are evaluated top-down without memoising on the history (the
/// memo key is a 64-bit set of the component's goals).
const MEMO_LIMIT: usize = 64;

#[derive(Clone, Copy, Debug)]
struct Frame {
    goal: Goal,
    lo: u32,
    hi: u32,
    cursor: u32,
}

/// Setting an input would make the axioms inconsistent.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct InputConflict {
    /// The input literal that was refused.
    pub input: String,
    /// The axiom clause (of the resolution closure) every literal of which the inputs would make
    /// false.
    pub clause: String,
}

impl fmt::Display for InputConflict {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(
            f,
            "setting `{}` contradicts the axiom `{}` given the other inputs; the input was left unchanged",
            self.input, self.clause
        )
    }
}

impl std::error::Error for InputConflict {}

/// Proving state for one engine: holds input values (true, false or unknown) and caches every
/// answer until an input it depends on changes.
pub struct Session {
    engine: Arc<Engine>,
    inputs: Vec<Option<bool>>,
    mu: Vec<bool>,
    values: Vec<u8>,
    index: Vec<u32>,
    low: Vec<u32>,
    next_index: u32,
    stack: Vec<Goal>,
    frames: Vec<Frame>,
    succ: Vec<u32>,
    component: Vec<Goal>,
    // Scratch for incremental updates, stamped with `epoch` so nothing is cleared between uses.
    stamp: Vec<u32>,
    epoch: u32,
    counters: Vec<u32>,
    queue: Vec<Lit>,
    /// How many goals were evaluated since the session began (for tests and benchmarks).
    evaluated: u64,
}

impl Session {
    /// A session with every input unknown.
    pub fn new(engine: impl Into<Arc<Engine>>) -> Session {
        let engine = engine.into();
        let lits = engine.lit_count;
        let mut session = Session {
            inputs: vec![None; lits / 2],
            mu: vec![false; lits],
            values: vec![UNKNOWN; lits * KINDS],
            index: vec![0; lits * KINDS],
            low: vec![0; lits * KINDS],
            next_index: 1,
            stack: Vec::new(),
            frames: Vec::new(),
            succ: Vec::new(),
            component: Vec::new(),
            stamp: vec![0; lits],
            epoch: 0,
            counters: vec![0; engine.theory.rule_count()],
            queue: Vec::new(),
            evaluated: 0,
            engine,
        };
        session.compute_mu();
        session
    }

    pub fn engine(&self) -> &Arc<Engine> {
        &self.engine
    }

    pub fn input(&self, atom: Atom) -> Option<bool> {
        self.inputs[atom.0 as usize]
    }

    /// Number of goal evaluations so far; shows how much an input change re-proved.
    pub fn evaluations(&self) -> u64 {
        self.evaluated
    }

    /// Sets an input to true, false or unknown (`None`). Only what depends on it is re-proved, and
    /// only when next asked. Refused, leaving everything as it was, when the new value together
    /// with the other inputs contradicts the axioms.
    ///
    /// An atom of an input group (`input{throwIn, goalKick, openPlay}`: exactly one is true) set
    /// true makes the others of its group false, as a sensor moving from one to another means.
    pub fn set_input(&mut self, atom: Atom, value: Option<bool>) -> Result<(), InputConflict> {
        let mut changes = vec![(atom, value)];
        if value == Some(true) {
            let engine = self.engine.clone();
            if let Some(group) = engine
                .theory()
                .inputs()
                .iter()
                .find(|g| g.atoms.len() > 1 && g.atoms.contains(&atom))
            {
                changes.extend(
                    group
                        .atoms
                        .iter()
                        .filter(|&&other| other != atom)
                        .map(|&other| (other, Some(false))),
                );
            }
        }
        let mut done: Vec<(Atom, Option<bool>)> = Vec::new();
        for (atom, value) in changes {
            let before = self.inputs[atom.0 as usize];
            if let Err(conflict) = self.set_one_input(atom, value) {
                // A refused change leaves the session as it was.
                for (atom, before) in done.into_iter().rev() {
                    let _ = self.set_one_input(atom, before);
                }
                return Err(conflict);
            }
            done.push((atom, before));
        }
        Ok(())
    }

    fn set_one_input(&mut self, atom: Atom, value: Option<bool>) -> Result<(), InputConflict> {
        let a = atom.0 as usize;
        if self.inputs[a] == value {
            return Ok(());
        }
        if let Some(v) = value {
            let fact = Lit::new(atom, !v);
            self.check_against_axioms(fact)?;
        }
        self.inputs[a] = value;
        self.update_mu(atom);
        Ok(())
    }

    /// Sets several inputs; stops at the first conflict (the inputs set before it stay set).
    pub fn set_inputs(
        &mut self,
        values: impl IntoIterator<Item = (Atom, Option<bool>)>,
    ) -> Result<(), InputConflict> {
        values
            .into_iter()
            .try_for_each(|(atom, value)| self.set_input(atom, value))
    }

    /// Whether `alg` proves the literal.
    pub fn prove(&mut self, alg: Algorithm, lit: Lit) -> bool {
        match alg {
            Algorithm::Mu => self.mu[lit.index()],
            Algorithm::Beta => self.goal_value(goal(lit, BETA)),
            Algorithm::Pi => self.goal_value(goal(lit, PI)),
            Algorithm::Alpha => self.goal_value(goal(lit, PI)) && self.goal_value(goal(lit, BETA)),
            Algorithm::Delta => self.goal_value(goal(lit, PI)) || self.goal_value(goal(lit, BETA)),
        }
    }

    /// Whether `alg` proves a formula (cdl.md §4, clauses as queries).
    pub fn prove_formula(&mut self, alg: Algorithm, formula: &Formula) -> bool {
        match formula {
            Formula::Lit(l) => self.prove(alg, *l),
            Formula::Clause(c) => self.prove_clause(alg, c),
            Formula::Conjunction(cs) => cs.iter().all(|c| self.prove_clause(alg, c)),
        }
    }

    fn prove_clause(&mut self, alg: Algorithm, clause: &[Lit]) -> bool {
        match alg {
            Algorithm::Mu => self.mu_clause(clause),
            Algorithm::Beta | Algorithm::Pi => {
                self.mu_clause(clause) || clause.iter().any(|&l| self.prove(alg, l))
            }
            Algorithm::Alpha => {
                self.prove_clause(Algorithm::Pi, clause)
                    && self.prove_clause(Algorithm::Beta, clause)
            }
            Algorithm::Delta => {
                self.prove_clause(Algorithm::Pi, clause)
                    || self.prove_clause(Algorithm::Beta, clause)
            }
        }
    }

    /// `+μ c`: a tautology, a member proved by μ, or a clause of the closure (with the input facts
    /// resolved away) inside `c`.
    fn mu_clause(&self, clause: &[Lit]) -> bool {
        if clause.iter().any(|&l| clause.contains(&l.complement())) {
            return true;
        }
        if clause.iter().any(|&l| self.mu[l.index()]) {
            return true;
        }
        let closure = self.engine.theory.closure();
        clause.iter().any(|&l| {
            self.engine.closure_by_lit.row(l.index()).iter().any(|&c| {
                closure[c as usize]
                    .lits
                    .iter()
                    .all(|&x| clause.contains(&x) || self.input_falsifies(x))
            })
        })
    }

    fn input_falsifies(&self, lit: Lit) -> bool {
        self.inputs[lit.atom().0 as usize] == Some(lit.is_negated())
    }

    /// Every literal `alg` proves, in literal order.
    pub fn conclusions(&mut self, alg: Algorithm) -> Vec<Lit> {
        (0..self.engine.lit_count as u32)
            .map(Lit)
            .filter(|&l| self.prove(alg, l))
            .collect()
    }

    /// How many literals `alg` proves (without collecting them).
    pub fn count_conclusions(&mut self, alg: Algorithm) -> usize {
        (0..self.engine.lit_count as u32)
            .filter(|&l| self.prove(alg, Lit(l)))
            .count()
    }

    // ---- μ: least fixpoint of the strict rules plus input facts -------------------------------

    fn compute_mu(&mut self) {
        let engine = Arc::clone(&self.engine);
        for r in 0..engine.theory.rule_count() {
            self.counters[r] = engine.strict_body_len[r];
        }
        self.queue.clear();
        for &r in &engine.strict_facts {
            let h = engine.head(r);
            if !self.mu[h.index()] {
                self.mu[h.index()] = true;
                self.queue.push(h);
            }
        }
        self.propagate_mu(&engine, None);
    }

    /// Forward chaining from the literals in `queue`; with `region`, only rules whose consequent
    /// is stamped with the current epoch are counted down.
    fn propagate_mu(&mut self, engine: &Engine, region: Option<u32>) {
        while let Some(x) = self.queue.pop() {
            for &r in engine.strict_uses.row(x.index()) {
                let h = engine.head(r);
                if region.is_some_and(|e| self.stamp[h.index()] != e) || self.mu[h.index()] {
                    continue;
                }
                let c = &mut self.counters[r as usize];
                *c = c.saturating_sub(1);
                if *c == 0 {
                    self.mu[h.index()] = true;
                    self.queue.push(h);
                }
            }
        }
    }

    fn next_epoch(&mut self) -> u32 {
        self.epoch = self.epoch.wrapping_add(1);
        if self.epoch == 0 {
            self.stamp.iter_mut().for_each(|s| *s = 0);
            self.epoch = 1;
        }
        self.epoch
    }

    /// Recomputes μ where the input `atom` can reach through strict rules, then forgets every
    /// answer that read a literal whose μ changed.
    fn update_mu(&mut self, atom: Atom) {
        let engine = Arc::clone(&self.engine);
        let epoch = self.next_epoch();
        // The region: literals strict rules can derive from `atom` or `~atom`.
        let mut region = vec![Lit::positive(atom), Lit::new(atom, true)];
        for &l in &region {
            self.stamp[l.index()] = epoch;
        }
        let mut i = 0;
        while i < region.len() {
            let x = region[i];
            i += 1;
            for &r in engine.strict_uses.row(x.index()) {
                let h = engine.head(r);
                if self.stamp[h.index()] != epoch {
                    self.stamp[h.index()] = epoch;
                    region.push(h);
                }
            }
        }
        let before: Vec<bool> = region.iter().map(|l| self.mu[l.index()]).collect();
        for &l in &region {
            self.mu[l.index()] = false;
        }
        // Count first, with the whole region false, then seed: a literal that becomes true is
        // counted down exactly once, by propagation.
        for &h in &region {
            for &r in engine.rules_for(h) {
                if engine.kind(r) == RuleKind::Strict {
                    self.counters[r as usize] = engine
                        .body(r)
                        .iter()
                        .filter(|a| !self.mu[a.index()])
                        .count() as u32;
                }
            }
        }
        self.queue.clear();
        for &h in &region {
            let input_fact = self.inputs[h.atom().0 as usize] == Some(!h.is_negated());
            let derived = input_fact
                || engine
                    .rules_for(h)
                    .iter()
                    .any(|&r| engine.kind(r) == RuleKind::Strict && self.counters[r as usize] == 0);
            if derived && !self.mu[h.index()] {
                self.mu[h.index()] = true;
                self.queue.push(h);
            }
        }
        self.propagate_mu(&engine, Some(epoch));
        let changed: Vec<Lit> = region
            .iter()
            .zip(before)
            .filter(|(l, b)| self.mu[l.index()] != *b)
            .map(|(l, _)| *l)
            .collect();
        self.invalidate(&changed);
    }

    /// Forgets the answers of every goal that can read a changed literal, transitively.
    fn invalidate(&mut self, changed: &[Lit]) {
        if changed.is_empty() {
            return;
        }
        let engine = Arc::clone(&self.engine);
        let epoch = self.next_epoch();
        let mut work: Vec<Lit> = Vec::new();
        let mark = |l: Lit, stamp: &mut Vec<u32>, work: &mut Vec<Lit>| {
            if stamp[l.index()] != epoch {
                stamp[l.index()] = epoch;
                work.push(l);
            }
        };
        for &l in changed {
            mark(l, &mut self.stamp, &mut work);
            mark(l.complement(), &mut self.stamp, &mut work);
        }
        while let Some(y) = work.pop() {
            for kind in 0..KINDS as u32 {
                let g = goal(y, kind) as usize;
                self.values[g] = UNKNOWN;
                self.index[g] = 0;
            }
            for &z in engine.dependents.row(y.index()) {
                mark(Lit(z), &mut self.stamp, &mut work);
                mark(Lit(z).complement(), &mut self.stamp, &mut work);
            }
        }
    }

    fn check_against_axioms(&self, fact: Lit) -> Result<(), InputConflict> {
        let theory = &self.engine.theory;
        let closure = theory.closure();
        for &c in self.engine.closure_by_lit.row(fact.complement().index()) {
            let clause = &closure[c as usize].lits;
            let falsified = clause
                .iter()
                .all(|&x| x == fact.complement() || self.input_falsifies(x));
            if falsified {
                let parts: Vec<String> =
                    clause.iter().map(|&l| theory.show(l).to_string()).collect();
                return Err(InputConflict {
                    input: theory.show(fact).to_string(),
                    clause: match parts.len() {
                        1 => parts[0].clone(),
                        _ => format!("\\/{{{}}}", parts.join(", ")),
                    },
                });
            }
        }
        Ok(())
    }

    // ---- β, π and support: components of the goal graph, on demand -----------------------------

    fn goal_value(&mut self, g: Goal) -> bool {
        if self.values[g as usize] == UNKNOWN {
            self.solve(g);
        }
        self.values[g as usize] == TRUE
    }

    pub(crate) fn mu(&self) -> &[bool] {
        &self.mu
    }

    /// The support goal of a literal, which `prove(Pi, …)` may have left unsettled.
    pub(crate) fn support_value(&mut self, lit: Lit) -> bool {
        self.goal_value(goal(lit, SUP))
    }

    /// Tarjan's algorithm from `root` over the unsettled goals it reaches; each component is
    /// evaluated as soon as it closes, so its successors are all settled by then.
    fn solve(&mut self, root: Goal) {
        let goals = self.values.len() as u32;
        if self.next_index >= u32::MAX - goals - 1 {
            self.index.iter_mut().for_each(|i| *i = 0);
            self.next_index = 1;
        }
        self.visit(root);
        while let Some(frame) = self.frames.last_mut() {
            if frame.cursor < frame.hi {
                let s = self.succ[frame.cursor as usize] & !ATTACK;
                frame.cursor += 1;
                let g = frame.goal as usize;
                if self.values[s as usize] != UNKNOWN {
                    continue;
                }
                if self.index[s as usize] == 0 {
                    self.visit(s);
                } else {
                    self.low[g] = self.low[g].min(self.index[s as usize]);
                }
            } else {
                let f = *frame;
                self.frames.pop();
                let g = f.goal as usize;
                if self.low[g] == self.index[g] {
                    self.close_component(f);
                }
                self.succ.truncate(f.lo as usize);
                if let Some(parent) = self.frames.last() {
                    let p = parent.goal as usize;
                    // A finished component reuses `low` as scratch; it never lowers its caller.
                    if self.values[g] == UNKNOWN {
                        self.low[p] = self.low[p].min(self.low[g]);
                    }
                }
            }
        }
    }

    fn visit(&mut self, g: Goal) {
        let i = g as usize;
        self.index[i] = self.next_index;
        self.low[i] = self.next_index;
        self.next_index += 1;
        self.stack.push(g);
        let lo = self.succ.len() as u32;
        let values = &self.values;
        successors(&self.engine, &self.mu, g, &mut self.succ, |s| {
            values[s as usize] == UNKNOWN
        });
        self.frames.push(Frame {
            goal: g,
            lo,
            hi: self.succ.len() as u32,
            cursor: lo,
        });
    }

    fn close_component(&mut self, root: Frame) {
        self.component.clear();
        while let Some(g) = self.stack.pop() {
            self.component.push(g);
            if g == root.goal {
                break;
            }
        }
        self.evaluated += self.component.len() as u64;
        let engine = Arc::clone(&self.engine);
        if self.component.len() == 1 {
            let g = root.goal;
            let self_loop = self.succ[root.lo as usize..root.hi as usize]
                .iter()
                .any(|&s| s & !ATTACK == g);
            if !self_loop {
                let values = &self.values;
                let v = condition(&engine, &self.mu, g, &mut |s, _| values[s as usize] == TRUE);
                self.values[g as usize] = if v { TRUE } else { FALSE };
                return;
            }
        }
        self.evaluate_cycle(&engine);
    }

    /// A component with a cycle. With only support edges inside it the condition is monotone in
    /// the component's goals, and the answer is the least fixpoint (loops fail, cdl.md §5.5).
    ///
    /// With an attack inside, answers depend on the history. Least fixpoints bound them exactly:
    /// `up` reads every internal attack as failing, so a goal outside it fails under any history.
    /// `low` reads an internal attack on `x` by goal `g` as `x`'s upper bound computed with `g`
    /// removed (`g` is on the history whenever it reads `x`), so a goal inside `low` holds from
    /// the empty history: its minimal derivation never meets a goal twice on a path. Only goals
    /// between the bounds are proved top-down, as cdl.md §4 reads, with the history restricted to
    /// the component.
    fn evaluate_cycle(&mut self, engine: &Engine) {
        let members = std::mem::take(&mut self.component);
        for (position, &g) in members.iter().enumerate() {
            self.values[g as usize] = PENDING;
            self.low[g as usize] = position as u32;
        }
        // (read member, reading member) pairs, and the internal attack reads by reader.
        let mut readers: Vec<(u32, u32)> = Vec::new();
        let mut attacks: Vec<(u32, u32)> = Vec::new();
        let mut buffer = Vec::new();
        for (from, &g) in members.iter().enumerate() {
            buffer.clear();
            let values = &self.values;
            successors(engine, &self.mu, g, &mut buffer, |s| {
                values[s as usize] == PENDING
            });
            for &s in &buffer {
                let to = self.low[(s & !ATTACK) as usize];
                readers.push((to, from as u32));
                if s & ATTACK != 0 {
                    attacks.push((from as u32, to));
                }
            }
        }
        readers.sort_unstable();
        readers.dedup();
        attacks.sort_unstable();
        attacks.dedup();
        let fixpoint = Fixpoint {
            engine,
            mu: &self.mu,
            values: &self.values,
            position: &self.low,
            members: &members,
            readers: &readers,
        };
        let results: Vec<bool> = if attacks.is_empty() {
            fixpoint.least(|_, _| false, None)
        } else {
            let up = fixpoint.least(|_, _| false, None);
            // Which internal attack reads can hold while their reader is on the history. One
            // fixpoint per attacking goal: bounded, falling back to the plain upper bound.
            let attackers = attacks.iter().map(|&(g, _)| g).filter(|&g| up[g as usize]);
            let mut distinct: Vec<u32> = attackers.collect();
            distinct.dedup();
            let refine = distinct.len().saturating_mul(members.len()) <= REFINE_LIMIT;
            let mut holds: FxHashMap<(u32, u32), bool> = FxHashMap::default();
            if refine {
                for &g in &distinct {
                    let without = fixpoint.least(|_, _| false, Some(g));
                    let start = attacks.partition_point(|&(r, _)| r < g);
                    for &(_, x) in attacks[start..].iter().take_while(|&&(r, _)| r == g) {
                        holds.insert((g, x), without[x as usize]);
                    }
                }
            }
            let low = fixpoint.least(
                |reader, x| {
                    if refine {
                        holds.get(&(reader, x)).copied().unwrap_or(false)
                    } else {
                        up[x as usize]
                    }
                },
                None,
            );
            let mut top_down = TopDown {
                engine,
                mu: &self.mu,
                values: &self.values,
                position: &self.low,
                up: &up,
                in_history: vec![false; members.len()],
                history: 0,
                memo: FxHashMap::default(),
                memoise: members.len() <= MEMO_LIMIT,
            };
            members
                .iter()
                .enumerate()
                .map(|(i, &g)| low[i] || (up[i] && top_down.prove(g)))
                .collect()
        };
        for (&g, v) in members.iter().zip(results) {
            self.values[g as usize] = if v { TRUE } else { FALSE };
        }
        self.component = members;
    }
}

/// Bounds the work of refining the lower bound: attacking goals times component size.
const REFINE_LIMIT: usize = 50_000_000;

/// Least fixpoints over the members of one component.
struct Fixpoint<'a> {
    engine: &'a Engine,
    mu: &'a [bool],
    values: &'a [u8],
    /// A member's position in `members`, by goal.
    position: &'a [u32],
    members: &'a [Goal],
    /// (read member, reading member), sorted: a member that turns true wakes only its readers.
    readers: &'a [(u32, u32)],
}

impl Fixpoint<'_> {
    /// Support reads of members take the current approximation; an attack read of member `x` by
    /// member `r` takes `attack(r, x)`; `excluded` is held false; settled goals are read as they
    /// are.
    fn least(&self, attack: impl Fn(u32, u32) -> bool, excluded: Option<u32>) -> Vec<bool> {
        let mut current = vec![false; self.members.len()];
        let mut work: Vec<u32> = (0..self.members.len() as u32)
            .filter(|&i| Some(i) != excluded)
            .collect();
        while let Some(i) = work.pop() {
            if current[i as usize] || Some(i) == excluded {
                continue;
            }
            let mut read = |s: Goal, how: Read| match self.values[s as usize] {
                PENDING => {
                    let p = self.position[s as usize];
                    if how == ATTACK_READ {
                        attack(i, p)
                    } else {
                        current[p as usize]
                    }
                }
                v => v == TRUE,
            };
            if condition(self.engine, self.mu, self.members[i as usize], &mut read) {
                current[i as usize] = true;
                let start = self.readers.partition_point(|&(to, _)| to < i);
                work.extend(
                    self.readers[start..]
                        .iter()
                        .take_while(|&&(to, _)| to == i)
                        .map(|&(_, from)| from),
                );
            }
        }
        current
    }
}

/// Top-down proof inside one component, with the history of cdl.md §4 (a goal met again on the
/// current path fails). Goals outside the component are settled and read from `values`.
struct TopDown<'a> {
    engine: &'a Engine,
    mu: &'a [bool],
    values: &'a [u8],
    position: &'a [u32],
    /// Members outside the upper bound fail under every history.
    up: &'a [bool],
    in_history: Vec<bool>,
    /// The history as a set of positions, for the memo key (small components only).
    history: u64,
    memo: FxHashMap<(u32, u64), bool>,
    memoise: bool,
}

impl TopDown<'_> {
    fn prove(&mut self, g: Goal) -> bool {
        match self.values[g as usize] {
            TRUE => return true,
            FALSE | UNKNOWN => return false,
            _ => {}
        }
        let p = self.position[g as usize];
        if self.in_history[p as usize] || !self.up[p as usize] {
            return false;
        }
        if self.memoise {
            if let Some(&v) = self.memo.get(&(p, self.history)) {
                return v;
            }
        }
        let key = (p, self.history);
        self.in_history[p as usize] = true;
        if self.memoise {
            self.history |= 1 << p;
        }
        let (engine, mu) = (self.engine, self.mu);
        // The path can be as long as the component: grow the stack on the heap rather than
        // overflow it.
        let v = stacker::maybe_grow(64 * 1024, 4 * 1024 * 1024, || {
            condition(engine, mu, g, &mut |s, _| self.prove(s))
        });
        self.in_history[p as usize] = false;
        if self.memoise {
            self.history &= !(1 << p);
            self.memo.insert(key, v);
        }
        v
    }
}
