//! The reference prover: cdl.md §4 read literally (top-down, with a history, loops fail), over
//! the written theory. Exponential in the worst case and kept simple on purpose: it is the oracle
//! the fast engine is tested against, not a tool for large theories.

use crate::closure::{close, ClosureOutcome, Resolvents};
use crate::literal::{Lit, RuleId};
use crate::theory::{RuleKind, Theory};
use proclaim_syntax::Algorithm;
use std::cell::RefCell;
use std::collections::{HashMap, HashSet};

#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
enum Tag {
    Beta,
    Pi,
    Sup,
}

struct Rule {
    label: Option<RuleId>,
    kind: RuleKind,
    body: Vec<Lit>,
    head: Lit,
}

/// The theory with given input values, ready to be asked.
pub struct ReferenceProver {
    rules: Vec<Rule>,
    /// `(winner, loser)` by written rule id.
    priorities: HashSet<(RuleId, RuleId)>,
    mu: HashSet<Lit>,
    memo: RefCell<Memo>,
}

/// Answers by goal and history (as a sorted set).
type Memo = HashMap<(Tag, Lit, Vec<(Tag, Lit)>), bool>;

impl ReferenceProver {
    /// Builds the prover for `theory` with the input facts `facts` (true inputs as `a`, false as
    /// `~a`). `None` when the facts and the axioms are inconsistent.
    pub fn new(theory: &Theory, facts: &[Lit]) -> Option<ReferenceProver> {
        // Written rules keep their ids (priorities name them); clause rules are regenerated
        // from the closure of the axioms together with the input facts, as cdl.md §2 says.
        let mut rules: Vec<Rule> = theory
            .rules()
            .take(theory.written_rule_count())
            .map(|r| Rule {
                label: Some(r.id),
                kind: r.kind,
                body: r.body.to_vec(),
                head: r.head,
            })
            .collect();
        let clauses: Vec<Vec<Lit>> = theory
            .axioms()
            .iter()
            .map(|c| c.lits.clone())
            .chain(facts.iter().map(|&f| vec![f]))
            .collect();
        let clauses = match close(&clauses, Resolvents::All) {
            ClosureOutcome::Closed { clauses, .. } => clauses,
            ClosureOutcome::Input => clauses,
            ClosureOutcome::Inconsistent { .. } | ClosureOutcome::TooLarge => return None,
        };
        for clause in clauses {
            for &head in &clause {
                rules.push(Rule {
                    label: None,
                    kind: RuleKind::Strict,
                    body: clause
                        .iter()
                        .filter(|&&l| l != head)
                        .map(|l| l.complement())
                        .collect(),
                    head,
                });
            }
        }
        let mut mu = HashSet::new();
        loop {
            let before = mu.len();
            for r in &rules {
                if r.kind == RuleKind::Strict && r.body.iter().all(|a| mu.contains(a)) {
                    mu.insert(r.head);
                }
            }
            if mu.len() == before {
                break;
            }
        }
        Some(ReferenceProver {
            rules,
            priorities: theory.priorities().iter().copied().collect(),
            mu,
            memo: RefCell::default(),
        })
    }

    pub fn prove(&self, alg: Algorithm, q: Lit) -> bool {
        let mut h = Vec::new();
        match alg {
            Algorithm::Mu => self.mu.contains(&q),
            Algorithm::Beta => self.run(Tag::Beta, q, &mut h),
            Algorithm::Pi => self.run(Tag::Pi, q, &mut h),
            Algorithm::Alpha => self.run(Tag::Pi, q, &mut h) && self.run(Tag::Beta, q, &mut h),
            Algorithm::Delta => self.run(Tag::Pi, q, &mut h) || self.run(Tag::Beta, q, &mut h),
        }
    }

    fn beats(&self, t: &Rule, s: &Rule) -> bool {
        matches!((t.label, s.label), (Some(a), Some(b)) if self.priorities.contains(&(a, b)))
    }

    fn supports(&self, q: Lit) -> impl Iterator<Item = &Rule> + '_ {
        self.rules
            .iter()
            .filter(move |r| r.head == q && r.kind != RuleKind::Warning)
    }

    fn attacks(&self, q: Lit) -> impl Iterator<Item = &Rule> + '_ {
        self.rules.iter().filter(move |r| r.head == q.complement())
    }

    fn app(&self, tag: Tag, r: &Rule, h: &mut Vec<(Tag, Lit)>) -> bool {
        r.body.iter().all(|&a| self.run(tag, a, h))
    }

    /// One goal with history `h` (the goals on the current path). The answer is a function of
    /// the goal and the history as a set, so it is remembered under both: the same literal
    /// reading, without walking every order of the same goals again.
    fn run(&self, tag: Tag, q: Lit, h: &mut Vec<(Tag, Lit)>) -> bool {
        if h.contains(&(tag, q)) {
            return false;
        }
        let mut key = h.clone();
        key.sort_unstable_by_key(|&(t, l)| (t as u8, l));
        let key = (tag, q, key);
        if let Some(&known) = self.memo.borrow().get(&key) {
            return known;
        }
        h.push((tag, q));
        let result = match tag {
            Tag::Beta | Tag::Pi => self.defeasible(tag, q, h),
            Tag::Sup => self.support(q, h),
        };
        h.pop();
        self.memo.borrow_mut().insert(key, result);
        result
    }

    fn defeasible(&self, tag: Tag, q: Lit, h: &mut Vec<(Tag, Lit)>) -> bool {
        if self.mu.contains(&q) {
            return true;
        }
        if self.mu.contains(&q.complement()) {
            return false;
        }
        if !self.supports(q).any(|r| self.app(tag, r, h)) {
            return false;
        }
        let attacker_tag = if tag == Tag::Beta {
            Tag::Beta
        } else {
            Tag::Sup
        };
        self.attacks(q).all(|s| {
            !self.app(attacker_tag, s, h)
                || self
                    .supports(q)
                    .any(|t| self.beats(t, s) && self.app(tag, t, h))
        })
    }

    fn support(&self, q: Lit, h: &mut Vec<(Tag, Lit)>) -> bool {
        if self.mu.contains(&q) {
            return true;
        }
        self.supports(q).any(|r| {
            self.app(Tag::Sup, r, h)
                && self
                    .attacks(q)
                    .all(|s| !self.beats(s, r) || !self.app(Tag::Pi, s, h))
        })
    }
}
