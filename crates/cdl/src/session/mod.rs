//! A proving session over a compiled engine: input values, the μ closure, and every goal's
//! answer, computed on demand component by component and re-proved only where an input change
//! reaches.

use crate::component::{Component, Method, Outcome, SearchLimits};
use crate::engine::Engine;
use crate::goal::{
    condition, goal, kind_of, lit_of, successors, Goal, ATTACK, ATTACK_READ, BETA, KINDS, PI, SUP,
};
use crate::literal::{Atom, Lit};
use crate::query::Formula;
use crate::theory::RuleKind;
pub use answers::ProofOutcome;
use proclaim_syntax::Algorithm;
use rustc_hash::FxHashMap;
use std::fmt;
use std::sync::Arc;
use truth::Truth;

mod answers;
mod mu;
mod solve;
mod truth;

const UNKNOWN: u8 = 0;
pub(crate) const FALSE: u8 = 1;
pub(crate) const TRUE: u8 = 2;
/// A member of the component being evaluated.
pub(crate) const PENDING: u8 = 3;
/// The search ran out of budget before deciding the goal, or the goal reads one that did.
pub(crate) const UNDECIDED: u8 = 4;

#[derive(Clone, Copy, Debug)]
struct Frame {
    goal: Goal,
    lo: u32,
    hi: u32,
    cursor: u32,
    /// Tarjan's low-link of `goal`: needed only while the goal is on the walk's path, so it
    /// lives here rather than in an array over every goal.
    low: u32,
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

/// A goal the search could not decide within its [`SearchLimits`]: neither proved nor refuted.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Undecided {
    /// The goal asked, as `beta a0`.
    pub goal: String,
    /// The undecided goal of an attack cycle this one depends on (itself when it lies on it),
    /// as `beta a7`.
    pub stalled_at: String,
    /// Goals in that component.
    pub component: usize,
    /// The step budget that was spent.
    pub steps: u64,
}

impl fmt::Display for Undecided {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "`{}` is undecided: ", self.goal)?;
        if self.stalled_at != self.goal {
            write!(f, "it depends on `{}`, whose ", self.stalled_at)?;
        } else {
            write!(f, "its ")?;
        }
        write!(
            f,
            "component of {} goals, where rules attack each other in a cycle, was not decided within the search budget of {} steps",
            self.component, self.steps
        )
    }
}

impl std::error::Error for Undecided {}

/// A component the search decided (or gave up on), for `check`'s warnings.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Searched {
    /// Its goals.
    pub goals: Vec<(Algorithm, Lit)>,
    /// Goals the search expanded.
    pub steps: u64,
    /// Whether the budget ran out.
    pub undecided: bool,
}

/// Proving state for one engine: holds input values (true, false or unknown) and caches every
/// answer until an input it depends on changes.
pub struct Session {
    engine: Arc<Engine>,
    inputs: Vec<Option<bool>>,
    mu: Vec<bool>,
    values: Vec<u8>,
    /// Tarjan's visit number of each goal still unsettled (0: not visited); once a component
    /// closes, its members' positions in it, which `cycle.rs` reads while they are pending.
    index: Vec<u32>,
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
    limits: SearchLimits,
    /// For each undecided goal, the undecided member of an attack cycle it depends on (itself
    /// when it is one) and the size of that cycle's component.
    stalls: FxHashMap<Goal, (Goal, usize)>,
    /// Components that needed the top-down search, kept for `check`.
    searched: Vec<Searched>,
}

impl Session {
    /// A session with every input unknown.
    pub fn new(engine: impl Into<Arc<Engine>>) -> Session {
        let engine = engine.into();
        let lits = engine.lit_count;
        let mut session = Session {
            inputs: vec![None; lits / 2],
            mu: vec![false; lits],
            values: vec![UNKNOWN; engine.goal_count()],
            index: vec![0; engine.goal_count()],
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
            limits: SearchLimits::default(),
            stalls: FxHashMap::default(),
            searched: Vec::new(),
            engine,
        };
        session.compute_mu();
        session
    }

    /// A session with its own bounds on the search inside attack cycles.
    pub fn with_limits(engine: impl Into<Arc<Engine>>, limits: SearchLimits) -> Session {
        let mut session = Session::new(engine);
        session.limits = limits;
        session
    }

    pub fn limits(&self) -> SearchLimits {
        self.limits
    }

    /// Changes the search bounds; goals left undecided under the old ones are asked again.
    pub fn set_limits(&mut self, limits: SearchLimits) {
        self.limits = limits;
        for (value, index) in self.values.iter_mut().zip(&mut self.index) {
            if *value == UNDECIDED {
                *value = UNKNOWN;
                *index = 0;
            }
        }
        self.stalls.clear();
    }

    /// The components decided by searching so far (those the bounds and the structure did not
    /// settle), largest first.
    pub fn searched(&self) -> Vec<Searched> {
        let mut all = self.searched.clone();
        all.sort_by_key(|s| std::cmp::Reverse(s.goals.len()));
        all
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

    /// Whether `alg` proves the literal. A goal the search could not decide within its limits
    /// counts as not proved; [`Session::decide`] tells the two apart.
    pub fn prove(&mut self, alg: Algorithm, lit: Lit) -> bool {
        self.truth(alg, lit) == Truth::True
    }

    /// Whether `alg` proves the literal, or why it is undecided.
    pub fn decide(&mut self, alg: Algorithm, lit: Lit) -> Result<bool, Undecided> {
        let truth = self.truth(alg, lit);
        self.answer(alg, || self.engine.theory.show(lit).to_string(), truth)
    }

    /// Whether `alg` proves a formula (cdl.md §4, clauses as queries); undecided goals count as
    /// not proved.
    pub fn prove_formula(&mut self, alg: Algorithm, formula: &Formula) -> bool {
        self.formula_truth(alg, formula) == Truth::True
    }

    /// Whether `alg` proves a formula, or why it is undecided.
    pub fn decide_formula(&mut self, alg: Algorithm, formula: &Formula) -> Result<bool, Undecided> {
        let truth = self.formula_truth(alg, formula);
        self.answer(alg, || formula.show(&self.engine.theory), truth)
    }

    /// The answer as `decide` gives it; `shown` is asked only for an undecided one.
    fn answer(
        &self,
        alg: Algorithm,
        shown: impl FnOnce() -> String,
        truth: Truth,
    ) -> Result<bool, Undecided> {
        match truth {
            Truth::True => Ok(true),
            Truth::False => Ok(false),
            Truth::Undecided(g) => {
                let (stalled, component) = self.stalls.get(&g).copied().unwrap_or((g, 0));
                Err(Undecided {
                    goal: format!("{alg} {}", shown()),
                    stalled_at: self.show_goal(stalled),
                    component,
                    steps: self.limits.steps,
                })
            }
        }
    }

    fn show_goal(&self, g: Goal) -> String {
        if self.engine.is_aggregate(g) {
            let (rep, kind) = self.engine.aggregate_parts(g);
            return format!(
                "{} of what implies {}",
                ["beta", "pi", "support"][kind as usize],
                self.engine.theory.show(Lit(rep))
            );
        }
        let kind = match kind_of(g) {
            BETA => "beta",
            PI => "pi",
            _ => "support",
        };
        format!("{kind} {}", self.engine.theory.show(lit_of(g)))
    }

    fn truth(&mut self, alg: Algorithm, lit: Lit) -> Truth {
        match alg {
            Algorithm::Mu => Truth::from(self.mu[lit.index()]),
            Algorithm::Beta => self.goal_truth(goal(lit, BETA)),
            Algorithm::Pi => self.goal_truth(goal(lit, PI)),
            Algorithm::Alpha => self
                .goal_truth(goal(lit, PI))
                .and(|| self.goal_truth(goal(lit, BETA))),
            Algorithm::Delta => self
                .goal_truth(goal(lit, PI))
                .or(|| self.goal_truth(goal(lit, BETA))),
        }
    }

    fn formula_truth(&mut self, alg: Algorithm, formula: &Formula) -> Truth {
        match formula {
            Formula::Lit(l) => self.truth(alg, *l),
            Formula::Clause(c) => self.clause_truth(alg, c),
            Formula::Conjunction(cs) => cs
                .iter()
                .fold(Truth::True, |t, c| t.and(|| self.clause_truth(alg, c))),
        }
    }

    fn clause_truth(&mut self, alg: Algorithm, clause: &[Lit]) -> Truth {
        match alg {
            Algorithm::Mu => Truth::from(self.mu_clause(clause)),
            Algorithm::Beta | Algorithm::Pi => clause
                .iter()
                .fold(Truth::from(self.mu_clause(clause)), |t, &l| {
                    t.or(|| self.truth(alg, l))
                }),
            Algorithm::Alpha => self
                .clause_truth(Algorithm::Pi, clause)
                .and(|| self.clause_truth(Algorithm::Beta, clause)),
            Algorithm::Delta => self
                .clause_truth(Algorithm::Pi, clause)
                .or(|| self.clause_truth(Algorithm::Beta, clause)),
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
        let written = clause.iter().any(|&l| {
            self.engine.closure_by_lit.row(l.index()).iter().any(|&c| {
                closure[c as usize]
                    .lits
                    .iter()
                    .all(|&x| clause.contains(&x) || self.input_falsifies(x))
            })
        });
        // An implicit resolvent `\/{a, b}` inside the clause: a path from `~a` to `b`. (One with
        // a literal the inputs make false holds by μ already: the path carries the input.)
        written
            || clause
                .iter()
                .any(|&a| self.implied(a.complement(), |b| b != a && clause.contains(&b)))
    }

    /// Whether a literal `found` accepts lies on an implication path from `from` (length ≥ 1).
    fn implied(&self, from: Lit, found: impl Fn(Lit) -> bool) -> bool {
        let forward = &self.engine.implications.forward;
        if self.engine.implications.representative.is_empty() {
            return false;
        }
        let mut seen = rustc_hash::FxHashSet::default();
        let mut work: Vec<Lit> = forward.row(from.index()).iter().map(|&x| Lit(x)).collect();
        while let Some(x) = work.pop() {
            if found(x) {
                return true;
            }
            if seen.insert(x) {
                work.extend(forward.row(x.index()).iter().map(|&y| Lit(y)));
            }
        }
        false
    }

    fn input_falsifies(&self, lit: Lit) -> bool {
        self.inputs[lit.atom().0 as usize] == Some(lit.is_negated())
    }

    // ---- β, π and support: components of the goal graph, on demand -----------------------------

    fn goal_value(&mut self, g: Goal) -> bool {
        self.goal_truth(g) == Truth::True
    }

    fn goal_truth(&mut self, g: Goal) -> Truth {
        if self.values[g as usize] == UNKNOWN {
            if self.concluded_by_nothing(g) {
                // Its condition reads no goal (cdl.md §4: no rule and no μ proof, no proof).
                self.values[g as usize] = FALSE;
                self.evaluated += 1;
            } else {
                self.solve(g);
            }
        }
        match self.values[g as usize] {
            TRUE => Truth::True,
            UNDECIDED => Truth::Undecided(g),
            _ => Truth::False,
        }
    }

    /// A β or π goal whose literal no rule concludes and μ does not prove: most negated
    /// literals of a large theory, which every-conclusion output asks about one by one, and
    /// which need no walk. (A literal an implication leads to is the head of the clause's rule.)
    fn concluded_by_nothing(&self, g: Goal) -> bool {
        let kind = kind_of(g);
        !self.engine.is_aggregate(g)
            && (kind == BETA || kind == PI)
            && !self.mu[lit_of(g).index()]
            && self.engine.rules_for(lit_of(g)).is_empty()
    }

    pub(crate) fn mu(&self) -> &[bool] {
        &self.mu
    }

    /// The support goal of a literal, which `prove(Pi, …)` may have left unsettled.
    pub(crate) fn support_value(&mut self, lit: Lit) -> bool {
        self.goal_value(goal(lit, SUP))
    }
}
